//! A material's statistical texture: seeded random fields over world space that vary a
//! facet's temperature and emissivity from point to point.
//!
//! A field of grass or a road in the thermal infrared is not one temperature: it varies by
//! one to a few kelvin over centimetres to metres. The thesis's sources (Grumman and TACOM,
//! §2) gave their images that variation from the statistics of measured images; this is
//! that description: a standard deviation, a correlation length and the shape of the power
//! spectrum. The field is a function of the world position alone, so it does not move from
//! frame to frame or with the image's tiling. The maths (how a field with this spectrum is
//! drawn and evaluated) is `irsig-texture`'s; this module is the declaration and its rules.

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_range};

/// The largest standard deviation of a temperature texture, K: 100 K, far beyond any
/// natural surface's variation (a sunlit field's is a few kelvin). A larger one is a
/// mistake, and would push the temperatures it draws toward 0 K.
pub const MAX_TEMPERATURE_SIGMA_K: f64 = 100.0;

/// The largest standard deviation of an emissivity scale: 1 (the scale `1 + σ·g` is then
/// clipped to keep ε within 0 to 1 a third of the time).
pub const MAX_EMISSIVITY_SIGMA: f64 = 1.0;

/// The lengths a texture may name, m: from 1 µm (below the thermal wavelengths themselves)
/// to 10⁷ m (the Earth's radius); the ratio of a 1/f range's longest to shortest at most
/// [`MAX_ONE_OVER_F_RATIO`].
pub const TEXTURE_LENGTH_M: [f64; 2] = [1e-6, 1e7];

/// The widest 1/f range, longest over shortest wavelength: six decades, more than a
/// field's texture spans from a blade of grass to a landscape.
pub const MAX_ONE_OVER_F_RATIO: f64 = 1e6;

/// A material's statistical texture: a seed and, for each quantity it varies, a random
/// field. Facets of the material take the field's value at each point a ray meets them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StatisticalTexture {
    /// The seed the fields are drawn from: the same seed gives the same texture, bit for
    /// bit, on every run and at any thread count. The temperature and emissivity fields are
    /// drawn from streams of their own, so they are independent.
    pub seed: u64,
    /// An offset added to the facet's temperature, K: a field of mean 0 and standard
    /// deviation `sigma` kelvin. `None`: the facet's temperature everywhere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature_offset_k: Option<RandomField>,
    /// A scale on the material's emissivity: `1 + g` for a field `g` of mean 0 and standard
    /// deviation `sigma` (dimensionless); the scaled ε is held to 0 to 1 and the reflectance
    /// is `1 − ε`. `None`: the material's emissivity everywhere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emissivity_scale: Option<RandomField>,
    /// How a ray takes the fields' value: at its hit point, or averaged over its pixel's
    /// footprint there.
    #[serde(default, skip_serializing_if = "FieldFilter::is_point")]
    pub filter: FieldFilter,
}

/// The named ways a ray reads a statistical texture.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum FieldFilter {
    /// The fields' value at the point the ray hits. A field finer than a pixel's footprint
    /// then aliases unless the pixel is supersampled: one ray gives one point of it, not
    /// the pixel's mean.
    #[default]
    Point,
    /// The fields' mean over the ray's pixel cell where it lies on the facet (its sub-pixel
    /// cell for a supersampled ray): the cell's parallelogram from the ray's differentials
    /// (Igehy 1999), through mirror bounces, over which each plane wave of a field averages
    /// to itself at the hit times `sinc(π f·a)·sinc(π f·b)` (`a`, `b` the parallelogram's
    /// edges), exactly. A field much finer than a pixel gives the pixel its mean, not
    /// moiré. What it leaves: the cell is the plane's linear image of the pixel (the
    /// perspective within one pixel is not followed), and the mean is taken of the
    /// temperature offset and the ε scale, not of the radiance they give (a difference of
    /// `½·L''/L'·σ²` in temperature for the variance filtered away, 0.005 K for 1 K at
    /// 300 K in 8–14 µm). Costs a hit about four times a point's where the footprint
    /// matters; where the footprint is under 10⁻³ of the field's shortest wavelength it is
    /// the point's value, at the point's cost. Hits of sky-view rays read the point.
    Footprint,
}

impl FieldFilter {
    /// Whether this is [`FieldFilter::Point`], the default.
    #[must_use]
    pub fn is_point(&self) -> bool {
        *self == Self::Point
    }
}

/// A stationary Gaussian random field: its standard deviation and its power spectrum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RandomField {
    /// The standard deviation, in the unit of what the field drives (K for a temperature
    /// offset, dimensionless for an emissivity scale); 0 turns the field off.
    pub sigma: f64,
    /// The shape of the power spectrum and its length scale.
    pub spectrum: FieldSpectrum,
}

/// The named power spectra a field may have. Each is given by its correlation function
/// `C(r)` along a line through the field (a field's autocorrelation at separation `r`,
/// divided by its variance).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum FieldSpectrum {
    /// `C(r) = exp(−r²/ℓ²)`: a smooth field (its power spectrum is Gaussian too).
    Gaussian {
        /// ℓ, m: where the correlation falls to 1/e.
        correlation_length_m: CorrelationLength,
    },
    /// `C(r) = exp(−r/ℓ)`: a rough field, continuous but nowhere smooth (a Markov
    /// process along any line; its 3-D power spectrum falls as `(1 + k²ℓ²)⁻²`).
    Exponential {
        /// ℓ, m: where the correlation falls to 1/e.
        correlation_length_m: CorrelationLength,
    },
    /// "1/f": equal variance in every octave of spatial frequency between two
    /// wavelengths, none outside them (the radial spectral density is proportional to
    /// `1/k` for `2π/longest ≤ k ≤ 2π/shortest`). Isotropic.
    OneOverF {
        /// The shortest wavelength of the range, m.
        shortest_m: f64,
        /// The longest wavelength of the range, m; above `shortest_m`.
        longest_m: f64,
    },
}

/// A correlation length: one for every direction, or one along each world axis (x east,
/// y north, z up): an anisotropic field is an isotropic one stretched along the axes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum CorrelationLength {
    /// The same length in every direction, m.
    Isotropic(f64),
    /// The length along x, y and z, m.
    PerAxis(f64, f64, f64),
}

impl CorrelationLength {
    /// The length along each axis, m.
    #[must_use]
    pub fn per_axis_m(self) -> [f64; 3] {
        match self {
            Self::Isotropic(l) => [l; 3],
            Self::PerAxis(x, y, z) => [x, y, z],
        }
    }
}

impl StatisticalTexture {
    /// Checks both fields.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str) -> Result<(), ModelError> {
        if let Some(f) = &self.temperature_offset_k {
            f.validate(
                &format!("{prefix}.temperature_offset_k"),
                MAX_TEMPERATURE_SIGMA_K,
            )?;
        }
        if let Some(f) = &self.emissivity_scale {
            f.validate(&format!("{prefix}.emissivity_scale"), MAX_EMISSIVITY_SIGMA)?;
        }
        Ok(())
    }

    /// Whether either field varies anything (a σ above 0).
    #[must_use]
    pub fn varies(&self) -> bool {
        [&self.temperature_offset_k, &self.emissivity_scale]
            .into_iter()
            .flatten()
            .any(|f| f.sigma > 0.0)
    }
}

impl RandomField {
    /// Checks σ (finite, 0 to `max_sigma`) and the spectrum's lengths.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str, max_sigma: f64) -> Result<(), ModelError> {
        check_range(|| format!("{prefix}.sigma"), self.sigma, 0.0, max_sigma)?;
        let [lo, hi] = TEXTURE_LENGTH_M;
        match &self.spectrum {
            FieldSpectrum::Gaussian {
                correlation_length_m,
            }
            | FieldSpectrum::Exponential {
                correlation_length_m,
            } => {
                let path = format!("{prefix}.spectrum.correlation_length_m");
                match *correlation_length_m {
                    CorrelationLength::Isotropic(l) => check_range(|| path.clone(), l, lo, hi)?,
                    CorrelationLength::PerAxis(x, y, z) => {
                        for (i, l) in [x, y, z].into_iter().enumerate() {
                            check_range(|| format!("{path}[{i}]"), l, lo, hi)?;
                        }
                    }
                }
            }
            FieldSpectrum::OneOverF {
                shortest_m,
                longest_m,
            } => {
                let path = format!("{prefix}.spectrum");
                check_range(|| format!("{path}.shortest_m"), *shortest_m, lo, hi)?;
                check_range(|| format!("{path}.longest_m"), *longest_m, lo, hi)?;
                if longest_m <= shortest_m || longest_m / shortest_m > MAX_ONE_OVER_F_RATIO {
                    return Err(ModelError::new(
                        format!("{path}.longest_m"),
                        ModelErrorKind::Other(format!(
                            "a 1/f range's longest wavelength {longest_m} m must be above its \
                             shortest {shortest_m} m and at most {MAX_ONE_OVER_F_RATIO:e} \
                             times it"
                        )),
                    ));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field(sigma: f64, spectrum: FieldSpectrum) -> StatisticalTexture {
        StatisticalTexture {
            seed: 1,
            temperature_offset_k: Some(RandomField { sigma, spectrum }),
            emissivity_scale: None,
            filter: FieldFilter::Point,
        }
    }

    fn gaussian(l: CorrelationLength) -> FieldSpectrum {
        FieldSpectrum::Gaussian {
            correlation_length_m: l,
        }
    }

    #[test]
    fn sigma_must_be_finite_and_not_negative() {
        let ok = field(0.0, gaussian(CorrelationLength::Isotropic(1.0)));
        assert!(ok.validate("t").is_ok());
        assert!(!ok.varies());
        for bad in [
            -0.1,
            f64::NAN,
            f64::INFINITY,
            MAX_TEMPERATURE_SIGMA_K * 1.01,
        ] {
            let e = field(bad, gaussian(CorrelationLength::Isotropic(1.0)))
                .validate("t")
                .unwrap_err();
            assert_eq!(e.path, "t.temperature_offset_k.sigma", "{bad}");
        }
        // An emissivity scale's σ is held to its own limit.
        let t = StatisticalTexture {
            seed: 0,
            temperature_offset_k: None,
            emissivity_scale: Some(RandomField {
                sigma: 2.0,
                spectrum: gaussian(CorrelationLength::Isotropic(1.0)),
            }),
            filter: FieldFilter::Point,
        };
        assert_eq!(
            t.validate("t").unwrap_err().path,
            "t.emissivity_scale.sigma"
        );
    }

    #[test]
    fn lengths_are_named_by_axis() {
        let e = field(1.0, gaussian(CorrelationLength::PerAxis(1.0, 0.0, 1.0)))
            .validate("t")
            .unwrap_err();
        assert_eq!(
            e.path,
            "t.temperature_offset_k.spectrum.correlation_length_m[1]"
        );
        let e = field(
            1.0,
            FieldSpectrum::Exponential {
                correlation_length_m: CorrelationLength::Isotropic(f64::NAN),
            },
        )
        .validate("t")
        .unwrap_err();
        assert_eq!(e.kind, ModelErrorKind::NotFinite);
    }

    #[test]
    fn a_one_over_f_range_must_be_ordered_and_bounded() {
        let with = |shortest_m, longest_m| {
            field(
                1.0,
                FieldSpectrum::OneOverF {
                    shortest_m,
                    longest_m,
                },
            )
            .validate("t")
        };
        assert!(with(0.01, 10.0).is_ok());
        assert!(with(10.0, 0.01).is_err());
        assert!(with(1.0, 1.0).is_err());
        assert!(with(1e-6, 10.0).is_err());
        assert!(with(0.0, 10.0).is_err());
    }

    #[test]
    fn per_axis_lengths_of_an_isotropic_length_are_equal() {
        let bits = |l: CorrelationLength| l.per_axis_m().map(f64::to_bits);
        assert_eq!(
            bits(CorrelationLength::Isotropic(2.0)),
            [2.0f64; 3].map(f64::to_bits)
        );
        assert_eq!(
            bits(CorrelationLength::PerAxis(1.0, 2.0, 3.0)),
            [1.0f64, 2.0, 3.0].map(f64::to_bits)
        );
    }
}
