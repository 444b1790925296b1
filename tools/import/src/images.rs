//! The images a glTF carries inside its file: taken from the mesh's materials, then written
//! into `--images DIR` or reported.
//!
//! A material map names its image by a path, so an image stored in a GLB's buffer or a
//! `data:` URI is of no use to one until it is a file. Each is written as stored (its
//! encoded bytes), once however many materials use it, named from its index and the name
//! the file gives it (`image-2-xrstandard_BaseColor.jpg`): the index keeps two images of
//! one name apart, and the name, reduced to letters, digits, `.`, `-` and `_`, can reach
//! no other folder. A file already there with the same bytes is left as it is; one with
//! other bytes is refused, so a second model's images never overwrite a first's.

use std::path::{Path, PathBuf};

use irsig_formats::mesh::{EmbeddedImage, Location, Mesh};
use miette::{IntoDiagnostic, WrapErr, miette};

use crate::Cli;

/// An embedded image and the first material that uses it.
pub(crate) struct Taken {
    material: String,
    first_use: Location,
    image: EmbeddedImage,
}

/// Takes the embedded images out of the mesh's materials, each image once.
pub(crate) fn take(mesh: &mut Mesh) -> Vec<Taken> {
    let mut taken: Vec<Taken> = Vec::new();
    for m in &mut mesh.materials {
        let Some(image) = m.embedded_image.take() else {
            continue;
        };
        if !taken.iter().any(|t| t.image.index == image.index) {
            taken.push(Taken {
                material: m.name.clone(),
                first_use: m.first_use.clone(),
                image,
            });
        }
    }
    taken
}

/// Writes each image into `--images DIR`, or without it says on stderr that it is there
/// and how to have it. An image's file must not be one of `inputs`.
pub(crate) fn write_or_report<const N: usize>(
    taken: &[Taken],
    cli: &Cli,
    inputs: [&str; N],
) -> miette::Result<()> {
    let Some(dir) = &cli.images else {
        for t in taken {
            irsig_cli::note!(
                "{}: material `{}` carries its base colour image inside the file ({}, {} bytes); \
                 --images DIR writes it out for a material map to name",
                t.first_use,
                t.material,
                describe(&t.image),
                t.image.bytes.len()
            );
        }
        return Ok(());
    };
    if taken.is_empty() {
        return Ok(());
    }
    let files: Vec<PathBuf> = taken
        .iter()
        .map(|t| dir.join(file_name(&t.image)))
        .collect();
    irsig_cli::refuse_output_is_input(inputs, &files)?;
    // Every file is checked before any is written, so a refusal leaves nothing new.
    let mut absent = Vec::new();
    for (t, file) in taken.iter().zip(&files) {
        if !already_there(file, &t.image.bytes)? {
            absent.push((file, &t.image.bytes));
        }
    }
    std::fs::create_dir_all(dir)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot make the folder --images {}", dir.display()))?;
    for (file, bytes) in absent {
        irsig_cli::write_output(Some(file), |w| w.write_all(bytes))?;
    }
    for (t, file) in taken.iter().zip(&files) {
        irsig_cli::note!(
            "{}: material `{}` names the image `{}`, written from the file's {}",
            t.first_use,
            t.material,
            file.display(),
            describe(&t.image)
        );
    }
    Ok(())
}

/// `images[I] `NAME`, image/jpeg`: how the file knows the image.
fn describe(image: &EmbeddedImage) -> String {
    let mut s = format!("images[{}]", image.index);
    if let Some(name) = &image.name {
        s.push_str(&format!(" `{name}`"));
    }
    if let Some(mime) = &image.mime_type {
        s.push_str(&format!(", {mime}"));
    }
    s
}

/// The image's file name: `image-I`, then `-NAME` with every character but letters,
/// digits, `.`, `-` and `_` turned to `_` and no leading dot, at most 100 of them; then
/// the MIME type's extension unless the name already ends in one of its own.
fn file_name(image: &EmbeddedImage) -> String {
    let mut name = format!("image-{}", image.index);
    if let Some(given) = &image.name {
        let safe: String = given
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_') {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let safe = safe.trim_start_matches('.');
        if !safe.is_empty() {
            name.push('-');
            name.extend(safe.chars().take(100));
        }
    }
    let extensions: &[&str] = match image.mime_type.as_deref() {
        Some("image/png") => &["png"],
        Some("image/jpeg") => &["jpg", "jpeg"],
        _ => &[],
    };
    let has = Path::new(&name)
        .extension()
        .is_some_and(|e| extensions.iter().any(|x| e.eq_ignore_ascii_case(x)));
    if let (false, Some(ext)) = (has, extensions.first()) {
        name.push('.');
        name.push_str(ext);
    }
    name
}

/// Whether `file` already holds `bytes` (`false`: there is no such file); a file there
/// with other bytes is refused.
fn already_there(file: &Path, bytes: &[u8]) -> miette::Result<bool> {
    match std::fs::read(file) {
        Ok(there) if there == bytes => Ok(true),
        Ok(_) => Err(miette!(
            help = "give --images another folder, or remove the file",
            "{} exists and holds another image: --images never overwrites one",
            file.display()
        )),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(false),
        Err(e) => Err(e)
            .into_diagnostic()
            .wrap_err_with(|| format!("cannot read {}", file.display())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(name: Option<&str>, mime: Option<&str>) -> EmbeddedImage {
        EmbeddedImage {
            index: 2,
            name: name.map(str::to_owned),
            mime_type: mime.map(str::to_owned),
            bytes: Vec::new().into(),
        }
    }

    #[test]
    fn a_name_reaches_no_other_folder_and_keeps_its_type() {
        assert_eq!(
            file_name(&image(Some("mat_BaseColor.jpg"), Some("image/jpeg"))),
            "image-2-mat_BaseColor.jpg"
        );
        assert_eq!(
            file_name(&image(Some("../../etc/passwd"), Some("image/png"))),
            "image-2-_.._etc_passwd.png"
        );
        assert_eq!(
            file_name(&image(Some("/abs\\x y"), None)),
            "image-2-_abs_x_y"
        );
        assert_eq!(
            file_name(&image(Some(".hidden"), Some("image/png"))),
            "image-2-hidden.png"
        );
        assert_eq!(file_name(&image(None, Some("image/jpeg"))), "image-2.jpg");
        assert_eq!(
            file_name(&image(Some("a.JPEG"), Some("image/jpeg"))),
            "image-2-a.JPEG"
        );
        let long = "x".repeat(500);
        assert_eq!(
            file_name(&image(Some(&long), None)).len(),
            "image-2-".len() + 100
        );
    }
}
