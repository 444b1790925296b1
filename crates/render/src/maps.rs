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
    let dir = folder_of(materials_file);
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

/// The folder a materials file's references are relative to: its own (`.` for a bare name).
fn folder_of(materials_file: &str) -> std::path::PathBuf {
    let dir = Path::new(materials_file)
        .parent()
        .map_or_else(|| Path::new(".").to_path_buf(), Path::to_path_buf);
    if dir.as_os_str().is_empty() {
        Path::new(".").to_path_buf()
    } else {
        dir
    }
}

/// The material map of the library's material `i`, its image read beside `materials_file`
/// (the library's path as given) as [`read_maps`] reads it, with the image's bytes: what
/// `irsig-therm` takes each facet's area fractions from. `None`: the material has no
/// material map.
///
/// # Errors
/// As [`read_maps`], for this map alone.
pub fn read_material_map_of(
    lib: &MaterialLibrary,
    i: usize,
    materials_file: &str,
) -> Result<Option<(MixMap, Vec<u8>)>, crate::RenderError> {
    let Some(m) = lib.materials.get(i) else {
        return Ok(None);
    };
    let Some(map) = m.maps.as_ref().and_then(|x| x.material.as_ref()) else {
        return Ok(None);
    };
    let at = format!("materials[{i}].maps.material.image");
    read_material_map(&folder_of(materials_file), map, &at)
        .map(Some)
        .map_err(|e| {
            crate::RenderError::maps(
                format!("{materials_file}: material {} ({})", m.id.0, m.name),
                e,
            )
        })
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
        MapForm::Index { table } => {
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

    /// A library of asphalt, grass, sand and a ground mapped by `map` (RON of a `MaterialMap`).
    fn mapped(map: &str) -> MaterialLibrary {
        irsig_formats::canonical::from_ron(
            "m.ron",
            &format!(
                r#"(materials: [
                (id: 1, name: "asphalt", emissivity: [(0.0, 0.95)], specular_fraction: 0.0,
                 source: "test"),
                (id: 2, name: "grass", emissivity: [(0.0, 0.98)], specular_fraction: 0.0,
                 source: "test"),
                (id: 4, name: "sand", emissivity: [(0.0, 0.9)], specular_fraction: 0.0,
                 source: "test"),
                (id: 3, name: "ground", emissivity: [(0.0, 0.9)], specular_fraction: 0.0,
                 source: "test", maps: Some((material: Some({map}))))])"#
            ),
        )
        .unwrap()
    }

    #[test]
    fn the_material_map_sample_reads_asphalt_and_grass_where_its_comment_says() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../formats/canonical/samples");
        let file = dir.join("materials-material-map.ron");
        let text = std::fs::read_to_string(&file).unwrap();
        let lib: MaterialLibrary =
            irsig_formats::canonical::from_ron("materials-material-map.ron", &text).unwrap();
        let (maps, read) = read_maps(&lib, file.to_str().unwrap()).unwrap();
        assert_eq!((maps.len(), read.len()), (1, 1));
        assert_eq!(maps[0].0, MaterialId(3));
        let mix = maps[0].1.material().unwrap();
        // Texel (i, j) from the bottom-left: grass (the map's second material) where i + j
        // is odd; at a texel's centre the bilinear filter gives it alone.
        for (i, j) in [(0, 0), (1, 0), (0, 1), (7, 7), (6, 7), (3, 4)] {
            let uv = [(f64::from(i) + 0.5) / 8.0, (f64::from(j) + 0.5) / 8.0];
            let w = mix.sample(uv, 0.0);
            let grass = f64::from(u8::from((i + j) % 2 == 1));
            assert!((w[1] - grass).abs() < 1e-12 && (w[0] - (1.0 - grass)).abs() < 1e-12);
        }
        // On the corner of four texels, half each.
        let w = mix.sample([0.25, 0.25], 0.0);
        assert!(
            (w[0] - 0.5).abs() < 1e-12 && (w[1] - 0.5).abs() < 1e-12,
            "{w:?}"
        );
    }

    #[test]
    fn material_maps_that_cannot_be_read_as_declared_are_refused_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let materials = dir.path().join("m.ron");
        let materials = materials.to_str().unwrap();
        let index = |image: &str, top: u16| {
            format!(
                r#"(image: "{image}", form: Index(table: [(grey: 0, material: "asphalt"),
                   (grey: {top}, material: "grass")]))"#
            )
        };
        let text = |lib: &MaterialLibrary| {
            crate::error::chain_text(&read_maps(lib, materials).unwrap_err())
        };
        // Missing.
        let e = text(&mapped(&index("gone.png", 255)));
        assert!(e.starts_with(materials), "{e}");
        assert!(
            e.contains("materials[3].maps.material.image: image `gone.png`: cannot read"),
            "{e}"
        );
        // A value the table does not list: 0 and 255 stored, 0 and 254 listed.
        let mut png = Vec::new();
        irsig_raster::write_png_gray8(&mut png, 2, 1, &[0, 255]).unwrap();
        std::fs::write(dir.path().join("two.png"), &png).unwrap();
        let e = text(&mapped(&index("two.png", 254)));
        assert!(e.contains("two.png") && e.contains("value 255"), "{e}");
        assert!(
            e.contains("column 1, row 0") && e.contains("[0, 254]"),
            "{e}"
        );
        assert!(read_maps(&mapped(&index("two.png", 255)), materials).is_ok());
        // Weights of an RGB image: (255, 0, 0) sums to 1, (128, 0, 0) to 0.502.
        let weights = |names: &str| {
            format!(r#"(image: "w.png", form: Weights(channels: [{names}], tolerance: 0.01))"#)
        };
        let mut rgb = Vec::new();
        irsig_raster::write_png_rgb8(&mut rgb, 2, 1, &[255, 0, 0, 128, 0, 0]).unwrap();
        std::fs::write(dir.path().join("w.png"), &rgb).unwrap();
        let three = r#""asphalt", "grass", "sand""#;
        let e = text(&mapped(&weights(three)));
        assert!(e.contains("w.png") && e.contains("column 1, row 0"), "{e}");
        assert!(e.contains("expected 1 within 0.01"), "{e}");
        // Two names for three channels.
        let e = text(&mapped(&weights(r#""asphalt", "grass""#)));
        assert!(e.contains("3 channels, but the map names 2"), "{e}");
        // An RGB image as an index map.
        let e = text(&mapped(&index("w.png", 255)));
        assert!(e.contains("an index map is one grey channel"), "{e}");
    }
}
