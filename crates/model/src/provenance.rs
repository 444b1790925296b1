//! What an image was made from, recorded in the image itself so that the stages after the
//! tracer need not be told again: the band its radiances are in (its limits, and a sensor
//! response's table itself with the file's SHA-256), the sub-bands, the atmosphere and its
//! model, and every input the chain read (stage, role, SHA-256). Contents, not names: the
//! same inputs read from a pipe, another folder or another spelling of a path make the same
//! record, so a run gives the same bytes however its stages are chained. irsig-trace
//! writes it into its EXRs, irsig-merge keeps it, irsig-sensor adds its own input, and the
//! sensor, the statistics and the report take the band from it by default (a `--band` that
//! disagrees is refused). `irsig-formats` reads and writes it as canonical RON;
//! formats/images.md says where it lives in an EXR.
//!
//! ```
//! use irsig_model::provenance::BandRecord;
//! let flat = BandRecord::Flat { min_um: 8.0, max_um: 14.0 };
//! assert!(flat.same_band(&BandRecord::Flat { min_um: 8.0, max_um: 14.0 }));
//! assert_eq!(flat.to_string(), "8-14 um, flat");
//! ```

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_range};

/// The band an image's radiances are in.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum BandRecord {
    /// The whole spectrum: radiance σT⁴/π.
    Total,
    /// A flat response between two wavelengths.
    Flat {
        /// Short end, µm.
        min_um: f64,
        /// Long end, µm.
        max_um: f64,
    },
    /// A sensor response table, as read from its file.
    Response {
        /// The file's SHA-256 (`sha256:` and 64 hex digits).
        sha256: String,
        /// Wavelengths, µm, increasing.
        wavelength_um: Vec<f64>,
        /// The response at each wavelength (relative).
        response: Vec<f64>,
    },
}

impl BandRecord {
    /// Whether `other` is the same band: the same kind and the same numbers (a response
    /// file's hash may differ: the same table written out again is the same band).
    #[must_use]
    pub fn same_band(&self, other: &Self) -> bool {
        match (self, other) {
            (Self::Total, Self::Total) => true,
            (
                Self::Flat { min_um, max_um },
                Self::Flat {
                    min_um: a,
                    max_um: b,
                },
            ) => min_um.to_bits() == a.to_bits() && max_um.to_bits() == b.to_bits(),
            (
                Self::Response {
                    wavelength_um,
                    response,
                    ..
                },
                Self::Response {
                    wavelength_um: w,
                    response: r,
                    ..
                },
            ) => {
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                bits(wavelength_um) == bits(w) && bits(response) == bits(r)
            }
            _ => false,
        }
    }

    /// Checks the numbers: finite limits with 0 < min < max; a response table of two or
    /// more rows of equal length, its wavelengths increasing within
    /// [`crate::limits::RESPONSE_WAVELENGTH_UM`], its values within 0 and
    /// [`crate::limits::MAX_RESPONSE`], its file's hash a SHA-256.
    ///
    /// # Errors
    /// The first rule broken, at its path.
    pub fn validate(&self, path: &str) -> Result<(), ModelError> {
        match self {
            Self::Total => Ok(()),
            Self::Flat { min_um, max_um } => {
                check_range(|| format!("{path}.min_um"), *min_um, f64::MIN_POSITIVE, 1e6)?;
                check_range(|| format!("{path}.max_um"), *max_um, *min_um, 1e6)?;
                if max_um <= min_um {
                    return Err(ModelError::new(
                        format!("{path}.max_um"),
                        ModelErrorKind::Other(format!(
                            "{max_um} um: expected more than the short end, {min_um} um"
                        )),
                    ));
                }
                Ok(())
            }
            Self::Response {
                sha256,
                wavelength_um,
                response,
            } => {
                if wavelength_um.len() < 2 || wavelength_um.len() != response.len() {
                    return Err(ModelError::new(
                        format!("{path}.response"),
                        ModelErrorKind::Other(format!(
                            "{} wavelengths and {} responses: expected two or more of each, \
                             as many of one as of the other",
                            wavelength_um.len(),
                            response.len()
                        )),
                    ));
                }
                check_sha256(&format!("{path}.sha256"), sha256)?;
                // A response file's own rules (formats/srf.md): the table the band is.
                let [w_min, w_max] = crate::limits::RESPONSE_WAVELENGTH_UM;
                for (i, &w) in wavelength_um.iter().enumerate() {
                    check_range(|| format!("{path}.wavelength_um[{i}]"), w, w_min, w_max)?;
                    if i > 0 && w <= wavelength_um[i - 1] {
                        return Err(ModelError::new(
                            format!("{path}.wavelength_um[{i}]"),
                            ModelErrorKind::Other(format!(
                                "{w} um: expected more than the row before, {} um",
                                wavelength_um[i - 1]
                            )),
                        ));
                    }
                }
                for (i, &r) in response.iter().enumerate() {
                    check_range(
                        || format!("{path}.response[{i}]"),
                        r,
                        0.0,
                        crate::limits::MAX_RESPONSE,
                    )?;
                }
                Ok(())
            }
        }
    }
}

/// A content hash as irsig writes one: `sha256:` and 64 lowercase hex digits. A shorter or
/// other hash (`sha256:00`) names no content, and a record holding one cannot be matched
/// to the file it claims to be.
///
/// # Errors
/// Another form, at `path`.
pub fn check_sha256(path: &str, sha256: &str) -> Result<(), ModelError> {
    let hex = sha256.strip_prefix("sha256:").unwrap_or("");
    if hex.len() == 64
        && hex
            .bytes()
            .all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b))
    {
        return Ok(());
    }
    Err(ModelError::new(
        path,
        ModelErrorKind::Other(format!(
            "`{sha256}`: expected `sha256:` and the 64 lowercase hex digits of a SHA-256"
        )),
    ))
}

impl std::fmt::Display for BandRecord {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Total => f.write_str("the whole spectrum (total)"),
            Self::Flat { min_um, max_um } => write!(f, "{min_um}-{max_um} um, flat"),
            Self::Response {
                sha256,
                wavelength_um,
                ..
            } => {
                let (lo, hi) = (
                    wavelength_um.first().copied().unwrap_or(f64::NAN),
                    wavelength_um.last().copied().unwrap_or(f64::NAN),
                );
                let short = sha256.get(..19).unwrap_or(sha256);
                write!(f, "{lo}-{hi} um with a response ({short}…)")
            }
        }
    }
}

/// One input a stage read.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputRecord {
    /// The stage that read it (`trace`, `sensor`).
    pub stage: String,
    /// What it was to that stage (`scene`, `materials`, `view`, `atmosphere`).
    pub role: String,
    /// `sha256:` and 64 hex digits of its bytes.
    pub sha256: String,
}

/// What an image was made from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    /// The band its radiances are in.
    pub band: BandRecord,
    /// The sub-bands the radiance equation was summed over: `1` (the band model), `K` or
    /// `full`.
    pub sub_bands: String,
    /// The atmosphere: `none` (a vacuum), a built-in's name, or `file` (its hash is among
    /// the inputs).
    pub atmosphere: String,
    /// Its model (`table`, `layered`, `thesis`, `none`).
    pub atmosphere_model: String,
    /// Every input the chain read, in the order read.
    pub inputs: Vec<InputRecord>,
    /// The sun that lit the scene, if one did (absent: no sun, a night).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sun: Option<SunRecord>,
}

/// The sun an image was lit by: where it was and how its shadows were sampled.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SunRecord {
    /// Zenith angle of the sun's centre, degrees.
    pub zenith_deg: f64,
    /// Azimuth, degrees clockwise from north (the scene's +y; 90 = east, +x).
    pub azimuth_deg: f64,
    /// Shadow rays per facet hit.
    pub shadow_rays: u32,
}

impl Provenance {
    /// Checks the band and every input's hash.
    ///
    /// # Errors
    /// As [`BandRecord::validate`], or a hash that is not [`check_sha256`]'s form.
    pub fn validate(&self) -> Result<(), ModelError> {
        self.band.validate("band")?;
        for (i, input) in self.inputs.iter().enumerate() {
            check_sha256(&format!("inputs[{i}].sha256"), &input.sha256)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn response(name: &str, r: f64) -> BandRecord {
        BandRecord::Response {
            sha256: format!("sha256:{name}"),
            wavelength_um: vec![8.0, 10.0, 12.0],
            response: vec![0.0, r, 0.0],
        }
    }

    #[test]
    fn a_band_is_its_numbers_not_its_file_name() {
        assert!(response("a.srf", 1.0).same_band(&response("copy/a.srf", 1.0)));
        assert!(!response("a.srf", 1.0).same_band(&response("a.srf", 0.9)));
        let flat = BandRecord::Flat {
            min_um: 8.0,
            max_um: 14.0,
        };
        assert!(!flat.same_band(&BandRecord::Total));
        assert!(!flat.same_band(&BandRecord::Flat {
            min_um: 7.5,
            max_um: 14.0
        }));
        assert!(response("a.srf", 1.0).to_string().contains("8-12 um"));
    }

    #[test]
    fn bad_limits_and_tables_are_named() {
        let e = BandRecord::Flat {
            min_um: 14.0,
            max_um: 8.0,
        }
        .validate("band")
        .unwrap_err();
        assert_eq!(e.path, "band.max_um");
        let short = BandRecord::Response {
            sha256: String::new(),
            wavelength_um: vec![8.0],
            response: vec![1.0],
        };
        assert_eq!(short.validate("band").unwrap_err().path, "band.response");
        // A response whose hash is `sha256:00` was accepted: it names no file.
        let hash = format!("sha256:{}", "ab".repeat(32));
        let good = BandRecord::Response {
            sha256: hash.clone(),
            wavelength_um: vec![8.0, 10.0, 12.0],
            response: vec![0.0, 1.0, 0.0],
        };
        good.validate("band").unwrap();
        type Edit<'a> = &'a dyn Fn(&mut Vec<f64>, &mut Vec<f64>, &mut String);
        let broken = |edit: Edit<'_>| {
            let BandRecord::Response {
                mut sha256,
                mut wavelength_um,
                mut response,
            } = good.clone()
            else {
                unreachable!()
            };
            edit(&mut wavelength_um, &mut response, &mut sha256);
            BandRecord::Response {
                sha256,
                wavelength_um,
                response,
            }
            .validate("band")
            .unwrap_err()
            .path
        };
        assert_eq!(broken(&|_, _, h| *h = "sha256:00".into()), "band.sha256");
        assert_eq!(broken(&|_, _, h| *h = hash.to_uppercase()), "band.sha256");
        assert_eq!(broken(&|w, _, _| w[1] = 8.0), "band.wavelength_um[1]");
        assert_eq!(broken(&|w, _, _| w[2] = f64::NAN), "band.wavelength_um[2]");
        assert_eq!(broken(&|_, r, _| r[1] = -1.0), "band.response[1]");
        assert_eq!(broken(&|_, r, _| r[1] = 1e300), "band.response[1]");
    }
}
