//! A material library's image maps, read: each map's grey PNG found beside the materials
//! file (its path relative to that file's folder, by the rules every reference follows),
//! refused from its header when too large, decoded by `irsig-raster` and handed to the
//! tracer as `irsig_texture::MaterialMaps`.

use std::path::Path;

use irsig_model::{MaterialId, MaterialLibrary};
use irsig_texture::{GreyImage, MaterialMaps, MixMap, TextureError, TextureErrorKind};

/// Each material's maps with their images read, by material id: what the tracer takes.
pub(crate) type Maps = Vec<(MaterialId, MaterialMaps)>;

/// The maps of every material of `lib` that has some, with their images read, and the
/// bytes of each image read (for the run's inputs); `materials_file` is the library's path
/// as given.
///
/// # Errors
/// A map that breaks a rule of its declaration (a NaN in its mapping), or an image that is
/// missing, unreadable, not a grey PNG or too large, naming the materials file, the map's
/// path in it and the image file.
pub(crate) fn read_maps(
    lib: &MaterialLibrary,
    materials_file: &str,
) -> Result<(Maps, Vec<Vec<u8>>), crate::RenderError> {
    let dir = Path::new(materials_file)
        .parent()
        .map_or_else(|| Path::new(".").to_path_buf(), Path::to_path_buf);
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".").to_path_buf()
    } else {
        dir
    };
    let mut out = Vec::new();
    let mut read = Vec::new();
    for (i, m) in lib.materials.iter().enumerate() {
        let Some(maps) = &m.maps else { continue };
        let loaded = MaterialMaps::new(maps, |name, map| {
            let at = format!("materials[{i}].maps.{name}.image");
            let image_error = |why: String| TextureError {
                kind: TextureErrorKind::Image(format!("{at}: image `{}`: {why}", map.image)),
            };
            let path =
                irsig_formats::mesh::resolve_reference(&dir, &map.image).map_err(image_error)?;
            let bytes = irsig_formats::file::read_file(&path)
                .map_err(|e| image_error(format!("cannot read {}: {e}", path.display())))?;
            let (width, height, grey) = irsig_raster::read_png_grey(&bytes)
                .map_err(|e| image_error(format!("{}: {e}", path.display())))?;
            read.push(bytes);
            GreyImage::new(width, height, grey)
        })
        .and_then(|loaded| match &maps.material {
            None => Ok(loaded),
            Some(map) => {
                let at = format!("materials[{i}].maps.material.image");
                let (mix, bytes) = read_material_map(&dir, map, &at)?;
                read.push(bytes);
                Ok(loaded.with_material(mix))
            }
        })
        .map_err(|e| {
            crate::RenderError::maps(
                format!("{materials_file}: material {} ({})", m.id.0, m.name),
                e,
            )
        })?;
        out.push((m.id, loaded));
    }
    Ok((out, read))
}

/// A material map's image, found in `dir` and read as the map's form says: an index map
/// from a one-channel PNG whose every stored value the table lists (each value looked up,
/// so a value the table lacks is refused at its texel before anything is traced); a
/// weights map from a PNG of one channel per named material, each sample over the depth's
/// greatest. `at` is the map's image path in the materials file, for messages.
///
/// # Errors
/// A missing or unreadable image, one of the wrong channel count, a value the table does
/// not list, or weights that do not sum to 1 within the tolerance: named with `at`, the
/// image's name and path.
fn read_material_map(
    dir: &Path,
    map: &irsig_model::material_map::MaterialMap,
    at: &str,
) -> Result<(MixMap, Vec<u8>), TextureError> {
    use irsig_model::material_map::MapForm;
    let image_error = |why: String| TextureError {
        kind: TextureErrorKind::Image(format!("{at}: image `{}`: {why}", map.image)),
    };
    let path = irsig_formats::mesh::resolve_reference(dir, &map.image).map_err(image_error)?;
    let bytes = irsig_formats::file::read_file(&path)
        .map_err(|e| image_error(format!("cannot read {}: {e}", path.display())))?;
    let (width, height, channels, samples, greatest) = irsig_raster::read_png_samples(&bytes)
        .map_err(|e| image_error(format!("{}: {e}", path.display())))?;
    let names = map.materials();
    let mix = match &map.form {
        MapForm::Index(table) => {
            if channels != 1 {
                return Err(image_error(format!(
                    "{}: {channels} channels: an index map is one grey channel",
                    path.display()
                )));
            }
            let table: Vec<(u16, usize)> = table
                .iter()
                .map(|e| {
                    (
                        e.grey,
                        names.iter().position(|n| *n == e.material).unwrap_or(0),
                    )
                })
                .collect();
            MixMap::from_index(width, height, &samples, &table, names.len(), map.filter)
        }
        MapForm::Weights {
            channels: named,
            tolerance,
        } => {
            if channels != named.len() {
                return Err(image_error(format!(
                    "{}: {channels} channels, but the map names {} materials, one per channel",
                    path.display(),
                    named.len()
                )));
            }
            let top = f32::from(greatest);
            let weights: Vec<f32> = samples.iter().map(|&s| f32::from(s) / top).collect();
            MixMap::from_weights(width, height, channels, &weights, *tolerance, map.filter)
        }
    }
    .map_err(|e| image_error(format!("{}: {e}", path.display())))?;
    Ok((mix, bytes))
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::image_map::{ImageMap, ImageMaps, MapFilter};

    /// A library of one grey material whose temperature map is the image `image`.
    fn library(image: &str) -> MaterialLibrary {
        let mut lib: MaterialLibrary = irsig_formats::canonical::from_ron(
            "m.ron",
            r#"(materials: [(id: 3, name: "paint", emissivity: [(0.0, 0.9)],
                specular_fraction: 0.0, source: "test")])"#,
        )
        .unwrap();
        lib.materials[0].maps = Some(ImageMaps {
            temperature_offset_k: Some(ImageMap {
                image: image.into(),
                at_black: -5.0,
                per_grey: 10.0,
                filter: MapFilter::Nearest,
            }),
            emissivity_scale: None,
            material: None,
        });
        lib
    }

    #[test]
    fn a_grey_png_beside_the_materials_file_is_read_and_mapped() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("maps")).unwrap();
        let mut png = Vec::new();
        // One row of two texels: black, then white.
        irsig_raster::write_png_gray8(&mut png, 2, 1, &[0, 255]).unwrap();
        std::fs::write(dir.path().join("maps/t.png"), &png).unwrap();
        let materials = dir.path().join("m.ron");
        let (maps, read) = read_maps(&library("maps/t.png"), materials.to_str().unwrap()).unwrap();
        assert_eq!(read, [png]);
        assert_eq!(maps[0].0, MaterialId(3));
        // Left half black (-5 K), right half white (-5 + 10 = 5 K).
        let at = |u| maps[0].1.sample([u, 0.5]).temperature_offset_k;
        assert!((at(0.25) + 5.0).abs() < 1e-12 && (at(0.75) - 5.0).abs() < 1e-12);
    }

    #[test]
    fn missing_oversized_and_escaping_images_are_refused_naming_the_files() {
        let dir = tempfile::tempdir().unwrap();
        let materials = dir.path().join("m.ron");
        let materials = materials.to_str().unwrap();
        let e = read_maps(&library("nowhere.png"), materials).unwrap_err();
        let e = crate::error::chain_text(&e);
        assert!(e.starts_with(materials), "{e}");
        assert!(
            e.contains(
                "materials[0].maps.temperature_offset_k.image: image `nowhere.png`: cannot read"
            ),
            "{e}"
        );
        // Not a PNG at all.
        std::fs::write(dir.path().join("text.png"), "grey").unwrap();
        let e = read_maps(&library("text.png"), materials).unwrap_err();
        let e = crate::error::chain_text(&e);
        assert!(e.contains("text.png"), "{e}");
        // Above the materials file's folder, or absolute: refused before any file is read.
        for bad in ["../up.png", "/etc/hostname"] {
            let e = crate::error::chain_text(&read_maps(&library(bad), materials).unwrap_err());
            assert!(e.contains(bad), "{e}");
        }
    }

    #[test]
    fn the_sample_library_reads_its_checkerboard_with_white_where_i_plus_j_is_odd() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../formats/canonical/samples");
        let file = dir.join("materials-mapped.ron");
        let text = std::fs::read_to_string(&file).unwrap();
        let lib: MaterialLibrary =
            irsig_formats::canonical::from_ron("materials-mapped.ron", &text).unwrap();
        let (maps, read) = read_maps(&lib, file.to_str().unwrap()).unwrap();
        assert_eq!(read.len(), 2, "one image, named by both maps");
        // Texel (i, j), column i from the left and row j from the bottom, centre
        // ((i + 0.5)/8, (j + 0.5)/8): white (+10 K) where i + j is odd, as the sample's
        // comment and the script that wrote the image say.
        for (i, j) in [(0, 0), (1, 0), (0, 1), (7, 7), (6, 7), (3, 4)] {
            let uv = [(f64::from(i) + 0.5) / 8.0, (f64::from(j) + 0.5) / 8.0];
            let t = maps[0].1.sample(uv);
            let white = (i + j) % 2 == 1;
            let offset_k = if white { 10.0 } else { 0.0 };
            assert!((t.temperature_offset_k - offset_k).abs() < 1e-12, "{i} {j}");
            // Bilinear at a texel's centre is the texel: 0.95 or 0.95 + 0.1.
            let scale = if white { 1.05 } else { 0.95 };
            assert!((t.emissivity_scale - scale).abs() < 1e-12, "{i} {j}");
        }
    }
}
