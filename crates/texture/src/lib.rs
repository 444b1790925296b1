//! irsig-texture: texture, the one home of what varies a surface within a facet.
//!
//! A material's statistical texture (`irsig_model::texture::StatisticalTexture`) is drawn
//! here into random fields over world space ([`Field`]: a sum of plane waves with
//! frequencies from a named spectrum, Shinozuka & Deodatis 1991), and sampled at a point
//! into a [`Texel`]: a temperature offset and an emissivity scale. The tracer samples it
//! at every facet a ray meets; the estimator in `irsig-regions` fits the same spectra
//! ([`correlation`]) to a measured image. A value depends on the position and the seed
//! alone, so a texture does not move between frames, tiles or thread counts.
//!
//! ```
//! use irsig_model::texture::{
//!     CorrelationLength, FieldFilter, FieldSpectrum, RandomField, StatisticalTexture,
//! };
//! use irsig_texture::TextureFields;
//!
//! let texture = StatisticalTexture {
//!     seed: 7,
//!     temperature_offset_k: Some(RandomField {
//!         sigma: 1.5,
//!         spectrum: FieldSpectrum::Gaussian {
//!             correlation_length_m: CorrelationLength::Isotropic(0.5),
//!         },
//!     }),
//!     emissivity_scale: None,
//!     filter: FieldFilter::Point,
//! };
//! let fields = TextureFields::new(&texture)?;
//! let texel = fields.sample([3.0, 4.0, 0.0]);
//! assert!(texel.temperature_offset_k.abs() <= 8.0 * 1.5);
//! assert_eq!(texel.emissivity_scale, 1.0);
//! // Kept physical: ε stays within 0 to 1 whatever the scale.
//! assert_eq!(irsig_texture::Texel { temperature_offset_k: 0.0, emissivity_scale: 1.2 }
//!     .emissivity(0.9), 1.0);
//! # Ok::<(), irsig_texture::TextureError>(())
//! ```
//!
//! A material's image maps ([`MaterialMaps`]) are sampled here too: a [`GreyImage`] read
//! at texture coordinates with a named filter (nearest, bilinear, or the footprint's
//! box-filtered mip pyramid [`MipPyramid`] against aliasing; all repeating), its grey
//! mapped linearly to a temperature offset or an emissivity scale. The image arrives
//! decoded: reading the file is `irsig-raster`'s.
//!
//! Must not know rays, files, the band or the command line: it gives numbers at points.

#![deny(clippy::print_stdout, clippy::print_stderr)]

mod field;
mod image;
mod mix;
mod spectrum;
#[cfg(any(test, feature = "testing"))]
pub mod testing;

pub use field::{CLIP_SIGMAS, Field, Footprint, WAVES};
pub use image::{GreyImage, MaterialMaps, MipPyramid};
pub use mix::MixMap;
pub use spectrum::{correlation, correlation_length_m};

use irsig_model::ModelError;
use irsig_model::texture::{FieldFilter, StatisticalTexture};

/// Mixed into a texture's seed for its temperature field's stream.
const TEMPERATURE_STREAM: u64 = 0x7465_6d70_6572_6174;
/// Mixed into a texture's seed for its emissivity field's stream.
const EMISSIVITY_STREAM: u64 = 0x656d_6973_7369_7669;

/// Why a texture cannot be used.
#[derive(Debug, thiserror::Error)]
#[error("{kind}")]
pub struct TextureError {
    /// What went wrong.
    pub kind: TextureErrorKind,
}

/// The kinds of [`TextureError`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TextureErrorKind {
    /// The texture breaks a rule of its declaration (a σ that is NaN or negative, a length
    /// out of range): the path of the value and what was expected.
    #[error("invalid texture: {0}")]
    Invalid(ModelError),
    /// A map's image is not one a map can read: no texel, a texel count that disagrees
    /// with its size, or a grey outside 0 to 1.
    #[error("unusable map image: {0}")]
    BadImage(String),
    /// A map's image could not be had (missing, unreadable, too large): the file and why,
    /// as the caller that reads images says it.
    #[error("{0}")]
    Image(String),
}

/// What a texture gives at one point of a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Texel {
    /// Added to the facet's temperature, K.
    pub temperature_offset_k: f64,
    /// Multiplies the material's emissivity (the result held to 0 to 1).
    pub emissivity_scale: f64,
}

impl std::ops::Mul for Texel {
    type Output = Self;

    /// Two textures at one point (a statistical texture and an image map): the offsets
    /// add, the scales multiply.
    fn mul(self, other: Self) -> Self {
        Self {
            temperature_offset_k: self.temperature_offset_k + other.temperature_offset_k,
            emissivity_scale: self.emissivity_scale * other.emissivity_scale,
        }
    }
}

impl Texel {
    /// No texture: no offset, a scale of 1.
    pub const NONE: Self = Self {
        temperature_offset_k: 0.0,
        emissivity_scale: 1.0,
    };

    /// `emissivity` scaled, held to 0 to 1: a texture never makes a surface emit more than
    /// a blackbody or reflect more than it receives (the reflectance is `1 − ε`).
    #[must_use]
    pub fn emissivity(self, emissivity: f64) -> f64 {
        (emissivity * self.emissivity_scale).clamp(0.0, 1.0)
    }
}

/// A material's texture, drawn and ready to sample.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureFields {
    temperature: Option<Field>,
    emissivity: Option<Field>,
    filter: FieldFilter,
}

impl TextureFields {
    /// Draws the fields of `texture`, each from its own stream of the seed.
    ///
    /// # Errors
    /// The texture breaks a rule of its declaration
    /// (`StatisticalTexture::validate`).
    pub fn new(texture: &StatisticalTexture) -> Result<Self, TextureError> {
        texture.validate("texture").map_err(|e| TextureError {
            kind: TextureErrorKind::Invalid(e),
        })?;
        let draw = |spec: &Option<irsig_model::texture::RandomField>, stream: u64| {
            spec.as_ref()
                .filter(|f| f.sigma > 0.0)
                .map(|f| Field::new(f, splitmix64(texture.seed ^ stream)))
        };
        Ok(Self {
            temperature: draw(&texture.temperature_offset_k, TEMPERATURE_STREAM),
            emissivity: draw(&texture.emissivity_scale, EMISSIVITY_STREAM),
            filter: texture.filter,
        })
    }

    /// The largest temperature offset the texture can give, K (0 without a temperature
    /// field): what a table of blackbody radiances over the textured temperatures spans.
    #[must_use]
    pub fn max_temperature_offset_k(&self) -> f64 {
        self.temperature
            .as_ref()
            .map_or(0.0, |f| CLIP_SIGMAS * f.sigma())
    }

    /// Whether a ray reads the fields over its footprint ([`FieldFilter::Footprint`]).
    #[must_use]
    pub fn filters_footprint(&self) -> bool {
        self.filter == FieldFilter::Footprint
    }

    /// The texel at the world point `p_m`.
    #[must_use]
    pub fn sample(&self, p_m: [f64; 3]) -> Texel {
        self.sample_over(p_m, None)
    }

    /// The texel a ray reads at the world point `p_m` through the texture's filter: with
    /// [`FieldFilter::Footprint`] and a `footprint`, the fields' means over it
    /// ([`Field::mean_over`]); otherwise their values at the point.
    #[must_use]
    pub fn sample_over(&self, p_m: [f64; 3], footprint: Option<&Footprint>) -> Texel {
        let footprint = footprint.filter(|_| self.filters_footprint());
        let fields = [self.temperature.as_ref(), self.emissivity.as_ref()];
        let [t, e] = field::values(fields, p_m, footprint);
        Texel {
            temperature_offset_k: t,
            emissivity_scale: 1.0 + e,
        }
    }
}

/// Splitmix64 (Steele, Lea & Flood 2014): decorrelates the streams of one seed.
fn splitmix64(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::texture::{CorrelationLength, FieldFilter, FieldSpectrum, RandomField};

    fn texture(t_sigma: f64, e_sigma: f64) -> StatisticalTexture {
        let spectrum = FieldSpectrum::Exponential {
            correlation_length_m: CorrelationLength::Isotropic(1.0),
        };
        StatisticalTexture {
            seed: 11,
            temperature_offset_k: Some(RandomField {
                sigma: t_sigma,
                spectrum: spectrum.clone(),
            }),
            emissivity_scale: Some(RandomField {
                sigma: e_sigma,
                spectrum,
            }),
            filter: FieldFilter::Point,
        }
    }

    #[test]
    fn bad_sigma_is_refused_with_its_path() {
        for bad in [f64::NAN, -1.0] {
            let e = TextureFields::new(&texture(bad, 0.1)).unwrap_err();
            let TextureErrorKind::Invalid(m) = e.kind else {
                panic!("expected an invalid texture")
            };
            assert_eq!(m.path, "texture.temperature_offset_k.sigma");
        }
    }

    #[test]
    fn the_two_fields_are_independent_streams() {
        let f = TextureFields::new(&texture(1.0, 1.0)).unwrap();
        // Same σ, same spectrum, same seed: different streams give different values.
        let t = f.sample([0.3, 0.7, 0.0]);
        assert!((t.temperature_offset_k - (t.emissivity_scale - 1.0)).abs() > 1e-6);
        assert!((f.max_temperature_offset_k() - CLIP_SIGMAS).abs() < 1e-12);
        let none = TextureFields::new(&texture(0.0, 0.0)).unwrap();
        assert_eq!(none.sample([1.0, 2.0, 3.0]), Texel::NONE);
    }

    #[test]
    fn emissivity_is_held_within_0_and_1() {
        let at = |scale| Texel {
            temperature_offset_k: 0.0,
            emissivity_scale: scale,
        };
        assert!((at(1.0).emissivity(0.9) - 0.9).abs() < 1e-15);
        assert!((at(2.0).emissivity(0.9) - 1.0).abs() < 1e-15);
        assert!(at(-0.5).emissivity(0.9).abs() < 1e-15);
        assert!((at(0.5).emissivity(0.9) - 0.45).abs() < 1e-15);
    }
}
