//! A material map: an image laid on a material's facets by their texture coordinates
//! ([`crate::FacetUv`]) whose texels say which materials of the same library lie there,
//! as a mixture of area fractions.
//!
//! Two forms. An *index* map is an 8- or 16-bit grey PNG whose grey values (the integers
//! the file stores, 0 to 255 or 0 to 65,535) each name one material through a table. A
//! *weights* map is a PNG whose channels (grey, grey and alpha, RGB or RGBA, 8 or 16 bits)
//! are each the area fraction of one named material, the channel's value over its
//! greatest; a texel's fractions sum to 1 within a stated tolerance.
//!
//! The filter reads fractions: each material's fraction is its indicator image (1 where a
//! texel is that material, else 0) or its channel, read with the map's filter. Nearest
//! gives the one texel's materials; Bilinear and Footprint give the fractions of the
//! texels around the point, a mixture. The mixture's optics are the materials' mixed
//! linearly by area fraction: emissivity `Σ wᵢ εᵢ` in each sub-band and angle, and the
//! specular and diffuse reflectances `Σ wᵢ (1 − εᵢ) sᵢ` and `Σ wᵢ (1 − εᵢ)(1 − sᵢ)`. The
//! image itself is not here: `irsig-raster` reads it, `irsig-texture` samples it.

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_range};
use crate::image_map::MapFilter;

/// The most materials one map may mix: a texel of an RGBA image holds four weights, and a
/// hit's mixture is carried with the hit as four (material, fraction) pairs.
pub const MAX_MAP_MATERIALS: usize = 4;

/// The greatest tolerance on a weights map's sum: the 8-bit quantum of a channel times
/// four channels is 4/255 ≈ 0.016; 0.05 is well beyond rounding, and more is a mistake.
pub const MAX_SUM_TOLERANCE: f64 = 0.05;

/// A material map.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialMap {
    /// The image: a PNG, its path relative to the materials file's folder (never absolute,
    /// never above that folder).
    pub image: String,
    /// What the texels mean.
    pub form: MapForm,
    /// How a point between texel centres takes its fractions.
    #[serde(default)]
    pub filter: MapFilter,
}

/// What a material map's texels mean.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum MapForm {
    /// An 8- or 16-bit grey image whose stored values each name one material. A value of
    /// the image that the table does not list is refused when the image is read.
    Index {
        /// Each listed value and the material it names.
        table: Vec<IndexEntry>,
    },
    /// An image whose channels, in the file's order (grey; grey, alpha; R, G, B; R, G, B,
    /// A), are the fractions of these materials, one name per channel.
    Weights {
        /// One material name per channel.
        channels: Vec<String>,
        /// How far a texel's fractions may sum from 1 (0 to [`MAX_SUM_TOLERANCE`]).
        tolerance: f64,
    },
}

/// One row of an index map's table.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IndexEntry {
    /// The value the image stores (0 to 255 in an 8-bit image, 0 to 65,535 in a 16-bit).
    pub grey: u16,
    /// The name of a material of the same library.
    pub material: String,
}

impl MaterialMap {
    /// The names of the materials the map mixes, in the order the form gives them, each
    /// once.
    #[must_use]
    pub fn materials(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        let listed: Vec<&str> = match &self.form {
            MapForm::Index { table } => table.iter().map(|e| e.material.as_str()).collect(),
            MapForm::Weights { channels, .. } => channels.iter().map(String::as_str).collect(),
        };
        for n in listed {
            if !names.contains(&n) {
                names.push(n);
            }
        }
        names
    }

    /// Checks the image path, the table (not empty, each grey once, names not empty) or
    /// the channels (one to four, names not empty and distinct, a tolerance within 0 to
    /// [`MAX_SUM_TOLERANCE`]), and that at most [`MAX_MAP_MATERIALS`] materials are mixed.
    /// Whether the names are the library's is [`crate::MaterialLibrary::validate`]'s.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str) -> Result<(), ModelError> {
        let err = |path: String, kind| Err(ModelError::new(path, kind));
        if self.image.trim().is_empty() {
            return err(format!("{prefix}.image"), ModelErrorKind::Empty);
        }
        match &self.form {
            MapForm::Index { table } => {
                if table.is_empty() {
                    return err(format!("{prefix}.form.table"), ModelErrorKind::Empty);
                }
                for (i, e) in table.iter().enumerate() {
                    if e.material.trim().is_empty() {
                        return err(
                            format!("{prefix}.form.table[{i}].material"),
                            ModelErrorKind::Empty,
                        );
                    }
                    if table[..i].iter().any(|p| p.grey == e.grey) {
                        return err(
                            format!("{prefix}.form.table[{i}].grey"),
                            ModelErrorKind::Duplicate(e.grey.to_string()),
                        );
                    }
                }
            }
            MapForm::Weights {
                channels,
                tolerance,
            } => {
                if channels.is_empty() || channels.len() > 4 {
                    return err(
                        format!("{prefix}.form.channels"),
                        ModelErrorKind::Other(format!(
                            "{} channels: expected 1 to 4 (grey, grey and alpha, RGB, RGBA)",
                            channels.len()
                        )),
                    );
                }
                for (i, c) in channels.iter().enumerate() {
                    if c.trim().is_empty() {
                        return err(
                            format!("{prefix}.form.channels[{i}]"),
                            ModelErrorKind::Empty,
                        );
                    }
                    if channels[..i].contains(c) {
                        return err(
                            format!("{prefix}.form.channels[{i}]"),
                            ModelErrorKind::Duplicate(c.clone()),
                        );
                    }
                }
                check_range(
                    || format!("{prefix}.form.tolerance"),
                    *tolerance,
                    0.0,
                    MAX_SUM_TOLERANCE,
                )?;
            }
        }
        let n = self.materials().len();
        if n > MAX_MAP_MATERIALS {
            return err(
                format!("{prefix}.form"),
                ModelErrorKind::Other(format!(
                    "{n} materials: a map mixes at most {MAX_MAP_MATERIALS}"
                )),
            );
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn index(table: &[(u16, &str)]) -> MaterialMap {
        MaterialMap {
            image: "m.png".into(),
            form: MapForm::Index {
                table: table
                    .iter()
                    .map(|&(grey, m)| IndexEntry {
                        grey,
                        material: m.into(),
                    })
                    .collect(),
            },
            filter: MapFilter::Nearest,
        }
    }

    #[test]
    fn an_index_table_lists_each_grey_once_and_at_most_four_materials() {
        assert!(
            index(&[(0, "asphalt"), (255, "grass")])
                .validate("m")
                .is_ok()
        );
        // Two greys may name one material: it is mixed once.
        let two = index(&[(0, "asphalt"), (1, "asphalt"), (2, "grass")]);
        assert!(two.validate("m").is_ok());
        assert_eq!(two.materials(), ["asphalt", "grass"]);
        let e = index(&[(3, "a"), (3, "b")]).validate("m").unwrap_err();
        assert_eq!(e.path, "m.form.table[1].grey");
        let e = index(&[]).validate("m").unwrap_err();
        assert_eq!(e.path, "m.form.table");
        let e = index(&[(0, "a"), (1, "b"), (2, "c"), (3, "d"), (4, "e")])
            .validate("m")
            .unwrap_err();
        assert_eq!(e.path, "m.form");
        let e = index(&[(0, " ")]).validate("m").unwrap_err();
        assert_eq!(e.path, "m.form.table[0].material");
    }

    #[test]
    fn weights_name_one_to_four_distinct_channels_with_a_finite_tolerance() {
        let weights = |channels: &[&str], tolerance| MaterialMap {
            image: "w.png".into(),
            form: MapForm::Weights {
                channels: channels.iter().map(|c| (*c).to_string()).collect(),
                tolerance,
            },
            filter: MapFilter::Bilinear,
        };
        assert!(weights(&["a", "b", "c"], 0.01).validate("m").is_ok());
        let e = weights(&["a", "b"], f64::NAN).validate("m").unwrap_err();
        assert_eq!(e.path, "m.form.tolerance");
        assert_eq!(e.kind, ModelErrorKind::NotFinite);
        let e = weights(&["a", "b"], 0.2).validate("m").unwrap_err();
        assert_eq!(e.path, "m.form.tolerance");
        let e = weights(&["a", "a"], 0.01).validate("m").unwrap_err();
        assert_eq!(e.path, "m.form.channels[1]");
        let e = weights(&[], 0.01).validate("m").unwrap_err();
        assert_eq!(e.path, "m.form.channels");
        let e = weights(&["a", "b", "c", "d", "e"], 0.01)
            .validate("m")
            .unwrap_err();
        assert_eq!(e.path, "m.form.channels");
    }
}
