//! A material's image maps: grey images laid on its facets by their texture coordinates
//! ([`crate::FacetUv`]) that vary the temperature and the emissivity within a facet, as a
//! textured asset's images vary its colour.
//!
//! A map drives the same two quantities a statistical texture does ([`crate::texture`]):
//! an offset added to the facet's temperature and a scale on the material's emissivity.
//! Where a material has both, the offsets add and the scales multiply. Each map is a
//! linear function of the texel's grey value `g`, 0 (black) to 1 (white, 255 in an 8-bit
//! image, 65,535 in a 16-bit one): `a + b·g`. The image itself (its texels, its size, its
//! file syntax) is not here: `irsig-raster` reads it, `irsig-texture` samples it.

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_range};

/// The largest temperature offset a map may give, K, at either end of its grey range: as a
/// statistical texture's σ ([`crate::texture::MAX_TEMPERATURE_SIGMA_K`]), far beyond any
/// surface's variation; a larger one is a mistake.
pub const MAX_OFFSET_K: f64 = 100.0;

/// A material's image maps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageMaps {
    /// An offset added to the facet's temperature, K. `None`: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature_offset_k: Option<ImageMap>,
    /// A scale on the material's emissivity (dimensionless); the reflectance is `1 − ε`.
    /// Never clamped: a scale that can make ε exceed 1 anywhere in the band, or fall below
    /// 0, is refused when the image is read. `None`: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emissivity_scale: Option<ImageMap>,
    /// Which materials of the library lie where on the facets, as area fractions
    /// ([`crate::material_map`]): the facets' optics are the mixture's, and the material's
    /// own emissivity and reflectance are not used at them. `None`: the material's own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<crate::material_map::MaterialMap>,
}

/// One image map: the image, the linear function of its grey value and the filter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageMap {
    /// The image: an 8- or 16-bit grey PNG, its path relative to the materials file's
    /// folder (never absolute, never above that folder).
    pub image: String,
    /// `a`: the value at grey 0, in the unit of what the map drives (K for a temperature
    /// offset, dimensionless for an emissivity scale).
    pub at_black: f64,
    /// `b`: the change from grey 0 to grey 1 (white), in the same unit.
    pub per_grey: f64,
    /// How a point between texel centres takes its value.
    #[serde(default)]
    pub filter: MapFilter,
}

/// The named filters a map is read with. All repeat the image outside 0 to 1.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum MapFilter {
    /// The texel the point falls in.
    #[default]
    Nearest,
    /// The four texels whose centres surround the point, weighted by how near each is
    /// along each axis: a texel's own value at its centre, the mean of two halfway between
    /// their centres.
    Bilinear,
    /// Against aliasing where a texel is smaller than a pixel's footprint: a box-filtered
    /// mip pyramid of the image (each level's texel the mean of the 2 × 2 below it), read
    /// bilinearly at the level whose texel is the footprint's size and blended between the
    /// two levels around it (Williams 1983, "trilinear"). The footprint is the longer edge
    /// of the ray's pixel cell on the facet (its ray differentials, through its mirror
    /// bounces), in texels through the facet's ratio of texture area to world area. A texture far away gives the mean of its texels, within the spread of
    /// the texel means at that level; under one texel a pixel it is `Bilinear`. Hits of
    /// sky-view rays read the image itself (a hemisphere's ray has no footprint to speak
    /// of).
    Footprint,
}

impl ImageMap {
    /// The map's value at grey `g`.
    #[must_use]
    pub fn at(&self, grey: f64) -> f64 {
        self.per_grey.mul_add(grey, self.at_black)
    }

    /// Checks the image's path (not empty) and that `a` and `b` are finite and, with
    /// `limit`, that the value stays within `limit` over greys 0 to 1.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str, limit: [f64; 2]) -> Result<(), ModelError> {
        if self.image.trim().is_empty() {
            return Err(ModelError::new(
                format!("{prefix}.image"),
                ModelErrorKind::Empty,
            ));
        }
        let [lo, hi] = limit;
        check_range(|| format!("{prefix}.at_black"), self.at_black, lo, hi)?;
        check_range(
            || format!("{prefix}.per_grey"),
            self.per_grey,
            -2.0 * hi.max(-lo),
            2.0 * hi.max(-lo),
        )?;
        let white = self.at(1.0);
        if !(lo..=hi).contains(&white) {
            return Err(ModelError::new(
                format!("{prefix}.per_grey"),
                ModelErrorKind::Other(format!(
                    "white (grey 1) maps to {white}, outside {lo} to {hi}"
                )),
            ));
        }
        Ok(())
    }
}

impl ImageMaps {
    /// Checks both maps: a temperature offset within ±[`MAX_OFFSET_K`], an emissivity scale
    /// within 0 to 1/ε at grey 0 and 1 (ε is the material's; whether the scale keeps ε
    /// within 1 over the band is checked where the band is known).
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str) -> Result<(), ModelError> {
        if let Some(m) = &self.temperature_offset_k {
            m.validate(
                &format!("{prefix}.temperature_offset_k"),
                [-MAX_OFFSET_K, MAX_OFFSET_K],
            )?;
        }
        if let Some(m) = &self.emissivity_scale {
            // An emissivity of 10⁻⁶ or more times a scale of at most 10⁶: the upper bound
            // only keeps the numbers finite; ε · s ≤ 1 is the real rule.
            m.validate(&format!("{prefix}.emissivity_scale"), [0.0, 1e6])?;
        }
        if let Some(m) = &self.material {
            m.validate(&format!("{prefix}.material"))?;
        }
        Ok(())
    }

    /// The images the maps name, with the path of each in the model (for messages).
    #[must_use]
    pub fn images(&self) -> Vec<(&'static str, &ImageMap)> {
        [
            ("temperature_offset_k", &self.temperature_offset_k),
            ("emissivity_scale", &self.emissivity_scale),
        ]
        .into_iter()
        .filter_map(|(name, m)| m.as_ref().map(|m| (name, m)))
        .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(at_black: f64, per_grey: f64) -> ImageMap {
        ImageMap {
            image: "t.png".into(),
            at_black,
            per_grey,
            filter: MapFilter::Nearest,
        }
    }

    #[test]
    fn the_mapping_is_linear_in_grey() {
        let m = map(-2.0, 10.0);
        assert_eq!(m.at(0.0).to_bits(), (-2.0f64).to_bits());
        assert_eq!(m.at(1.0).to_bits(), 8.0f64.to_bits());
        assert_eq!(m.at(0.25).to_bits(), 0.5f64.to_bits());
    }

    #[test]
    fn nan_and_out_of_range_mappings_are_refused_at_their_path() {
        let maps = |t: ImageMap| ImageMaps {
            temperature_offset_k: Some(t),
            emissivity_scale: None,
            material: None,
        };
        assert!(maps(map(0.0, 10.0)).validate("m").is_ok());
        let e = maps(map(f64::NAN, 1.0)).validate("m").unwrap_err();
        assert_eq!(e.path, "m.temperature_offset_k.at_black");
        assert_eq!(e.kind, ModelErrorKind::NotFinite);
        let e = maps(map(0.0, f64::NAN)).validate("m").unwrap_err();
        assert_eq!(e.path, "m.temperature_offset_k.per_grey");
        // White at 0 + 150 K: beyond the largest offset.
        let e = maps(map(0.0, 150.0)).validate("m").unwrap_err();
        assert_eq!(e.path, "m.temperature_offset_k.per_grey");
        let mut empty = map(0.0, 1.0);
        empty.image = " ".into();
        let e = maps(empty).validate("m").unwrap_err();
        assert_eq!(e.path, "m.temperature_offset_k.image");
        // A negative emissivity scale at white.
        let e = ImageMaps {
            temperature_offset_k: None,
            emissivity_scale: Some(map(0.5, -1.0)),
            material: None,
        }
        .validate("m")
        .unwrap_err();
        assert_eq!(e.path, "m.emissivity_scale.per_grey");
    }

    #[test]
    fn the_filter_defaults_to_nearest_and_images_are_listed_in_order() {
        let both = ImageMaps {
            temperature_offset_k: Some(map(0.0, 1.0)),
            emissivity_scale: Some(map(1.0, 0.0)),
            material: None,
        };
        let names: Vec<_> = both.images().into_iter().map(|(n, _)| n).collect();
        assert_eq!(names, ["temperature_offset_k", "emissivity_scale"]);
        assert_eq!(MapFilter::default(), MapFilter::Nearest);
    }
}
