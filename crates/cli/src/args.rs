//! The command-line vocabulary the tools share, defined once so that every tool spells a
//! setting the same way: the band (`--band MIN-MAX` or `--band RESPONSE-FILE`), the
//! digital-count calibration (`--dc-per-kelvin`, `--reference-k`, `--dc-at-reference`,
//! `--gain-dc-per-radiance`, `--offset-dc`, `--dc-bits`), library enums offered by name,
//! a table's `--format` and lists or ranges of numbers (`--angles 0:90:5`).

use std::str::FromStr;

use clap::builder::{PossibleValuesParser, TypedValueParser};
use irsig_radiometry::{Band, SensorResponse};
use irsig_sensor_model::quantise::Calibration;
use miette::miette;

/// A spectral band as given on a command line: `MIN-MAX` in micrometres (a flat response),
/// or the path of a sensor response file (`formats/srf.md`), whose first and last
/// wavelengths bound the band. Resolve it with [`BandArg::load`].
#[derive(Debug, Clone, PartialEq)]
pub enum BandArg {
    /// A flat band between two wavelengths, µm.
    Flat {
        /// Short end, µm.
        min_um: f64,
        /// Long end, µm.
        max_um: f64,
    },
    /// A sensor response file.
    Response(String),
}

impl Default for BandArg {
    /// The thesis's band, 8–14 µm, flat.
    fn default() -> Self {
        Self::Flat {
            min_um: 8.0,
            max_um: 14.0,
        }
    }
}

impl FromStr for BandArg {
    type Err = String;

    /// `MIN-MAX` (two positive numbers of µm joined by `-`), else a file name. `8:14`, the
    /// old spelling of some tools, is refused with the new one.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let number = |t: &str| t.trim().parse::<f64>().ok().filter(|v| v.is_finite());
        // The `-` that splits two numbers (an exponent such as `8e-1` holds one too).
        for (i, _) in s.match_indices('-') {
            if let (Some(min_um), Some(max_um)) = (number(&s[..i]), number(&s[i + 1..])) {
                return Ok(Self::Flat { min_um, max_um });
            }
        }
        if let Some((a, b)) = s.split_once(':')
            && number(a).is_some()
            && number(b).is_some()
        {
            return Err(format!(
                "expected MIN-MAX in micrometres, such as {a}-{b}, or a sensor response \
                 file; found `{s}`"
            ));
        }
        if s.is_empty() {
            return Err(
                "expected MIN-MAX in micrometres, such as 8-14, or a sensor response file"
                    .to_owned(),
            );
        }
        Ok(Self::Response(s.to_owned()))
    }
}

impl std::fmt::Display for BandArg {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Flat { min_um, max_um } => write!(f, "{min_um}-{max_um}"),
            Self::Response(path) => f.write_str(path),
        }
    }
}

impl BandArg {
    /// The band: flat, or weighted by the response file read from disk.
    ///
    /// # Errors
    /// Limits that are not `0 < MIN < MAX` (bad usage), or a response file that cannot be
    /// read or parsed (at its line and column).
    pub fn load(&self) -> miette::Result<Band> {
        match self {
            Self::Flat { min_um, max_um } => Band::new(*min_um, *max_um)
                .map_err(|e| crate::usage_error(format!("--band {self}: {e}"))),
            Self::Response(path) => {
                let input = crate::read_input(path)?;
                let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
                let table = irsig_formats::srf::parse(&input.name, text)?;
                let (Some(&lo), Some(&hi)) =
                    (table.wavelength_um.first(), table.wavelength_um.last())
                else {
                    return Err(miette!("{}: the response table is empty", input.name));
                };
                let srf = SensorResponse::new(table.wavelength_um, table.response)
                    .map_err(|e| miette!("{}: {e}", input.name))?;
                Band::new(lo, hi)
                    .and_then(|b| b.with_response(&srf))
                    .map_err(|e| miette!("{}: {e}", input.name))
            }
        }
    }
}

/// `--band` of the tools that render or re-render a frame (irsig-trace, irsig-merge): the
/// shared band of every tool, or `total`, the whole spectrum (σT⁴/π), exact and for checking
/// by hand.
#[derive(Debug, Clone, PartialEq)]
pub enum TraceBand {
    /// `total`: σT⁴/π.
    Total,
    /// A band as every tool takes it.
    Band(BandArg),
}

impl FromStr for TraceBand {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s == "total" {
            Ok(Self::Total)
        } else {
            s.parse().map(Self::Band)
        }
    }
}

/// A flat band `MIN-MAX` in micrometres as `[min, max]`, for settings that cannot take a
/// response file (the band a DIRTRAN table was integrated over): a clap value parser.
///
/// # Errors
/// Anything but two numbers with `0 < MIN < MAX`.
pub fn flat_band(s: &str) -> Result<[f64; 2], String> {
    match s.parse::<BandArg>()? {
        BandArg::Flat { min_um, max_um } if min_um > 0.0 && max_um > min_um => Ok([min_um, max_um]),
        BandArg::Flat { min_um, max_um } => Err(format!(
            "expected 0 < MIN < MAX in micrometres, found {min_um}-{max_um}"
        )),
        BandArg::Response(_) => Err(format!(
            "expected MIN-MAX in micrometres, such as 8-14, found `{s}`"
        )),
    }
}

/// How a tool turns radiance into digital counts: one set of flags for every tool that
/// writes a DC image and its LUT.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct DcArgs {
    /// Gain in digital counts per kelvin. Alone: the thesis's auto-bias (Figure 14), the
    /// scene's mid radiance at mid-scale, so counts differ from scene to scene; with
    /// --reference-k: a fixed calibration, the same counts in every scene.
    #[arg(long, value_name = "DC_PER_K")]
    pub dc_per_kelvin: Option<f64>,
    /// Fixed calibration: the temperature (K) at which the gain is --dc-per-kelvin and
    /// whose blackbody radiance maps to --dc-at-reference.
    #[arg(long, value_name = "K", conflicts_with = "gain_dc_per_radiance")]
    pub reference_k: Option<f64>,
    /// Fixed calibration: the count of a blackbody at --reference-k (default mid-scale).
    #[arg(long, value_name = "DC", requires = "reference_k")]
    pub dc_at_reference: Option<f64>,
    /// A straight line instead: counts per W m^-2 sr^-1 (with --offset-dc).
    #[arg(long, value_name = "DC_PER_W_M2_SR", conflicts_with = "dc_per_kelvin")]
    pub gain_dc_per_radiance: Option<f64>,
    /// The count of zero radiance, with --gain-dc-per-radiance (default 0).
    #[arg(long, value_name = "DC", requires = "gain_dc_per_radiance")]
    pub offset_dc: Option<f64>,
    /// Bits per digital count (1-16): an 8-bit PNG up to 8, else a 16-bit one.
    #[arg(long, default_value_t = 8, value_name = "BITS",
          value_parser = clap::value_parser!(u8).range(1..=16))]
    pub dc_bits: u8,
}

impl DcArgs {
    /// The calibration the flags ask for; `default_dc_per_kelvin` stands in for a missing
    /// --dc-per-kelvin (the tracer's view gain). `None` when no gain is known.
    #[must_use]
    pub fn calibration(&self, default_dc_per_kelvin: Option<f64>) -> Option<Calibration> {
        if let Some(gain) = self.gain_dc_per_radiance {
            return Some(Calibration::GainOffset {
                gain_dc_per_w_m2_sr: gain,
                offset_dc: self.offset_dc.unwrap_or(0.0),
            });
        }
        let dc_per_kelvin = self.dc_per_kelvin.or(default_dc_per_kelvin)?;
        Some(match self.reference_k {
            Some(reference_k) => Calibration::Fixed {
                dc_per_kelvin,
                reference_k,
                dc_at_reference: self.dc_at_reference,
            },
            None => Calibration::AutoBias { dc_per_kelvin },
        })
    }
}

/// The gain of the tracer's digital counts when neither the command line nor the view
/// gives one, counts per kelvin (the thesis experiment's viewing files say 2).
pub const TRACER_DC_PER_KELVIN: f64 = 2.0;

impl DcArgs {
    /// The quantiser of the tracer's digital-count image (irsig-trace, and irsig-merge for
    /// a frame traced in tiles), over the whole frame's radiance (f32, W m⁻² sr⁻¹): the
    /// flags' calibration, with the view's DC/K (`view_dc_per_kelvin`), else
    /// [`TRACER_DC_PER_KELVIN`], for a missing gain. One function, so that a merged frame's
    /// counts and LUT are those of the frame traced whole.
    ///
    /// # Errors
    /// A calibration the quantiser refuses (no finite radiance, a gain of 0), as a message.
    pub fn tracer_quantiser(
        &self,
        view_dc_per_kelvin: Option<f64>,
        radiance_w_m2_sr: &[f32],
        band: &impl irsig_radiometry::BandModel,
    ) -> miette::Result<irsig_sensor_model::quantise::Quantiser> {
        let calibration = self
            .calibration(view_dc_per_kelvin.or(Some(TRACER_DC_PER_KELVIN)))
            .ok_or_else(|| miette!("digital counts: no gain"))?;
        irsig_sensor_model::quantise::Quantiser::calibrate(
            self.dc_bits,
            &calibration,
            radiance_w_m2_sr,
            band,
        )
        .map_err(|e| miette!("digital counts: {e}"))
    }
}

/// A clap value parser for a library enum known by name: the names are listed in `--help`
/// and in the error for any other word, and the value is the enum's own `FromStr`. Only
/// `tools/*` use clap, so the libraries' enums carry names, not clap derives.
#[must_use]
pub fn named<T>(names: &'static [&'static str]) -> impl TypedValueParser<Value = T>
where
    T: FromStr + Clone + Send + Sync + 'static,
    T::Err: std::error::Error + Send + Sync + 'static,
{
    PossibleValuesParser::new(names).try_map(|s: String| s.parse::<T>())
}

/// The form in which a tool prints a table (`--format`): the atmosphere calculators' and
/// the region statistics' one spelling.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum TableFormat {
    /// Aligned columns for reading.
    #[default]
    Table,
    /// Comma-separated values with a header row, full precision.
    Csv,
    /// RON, full precision.
    Ron,
}

/// The numbers of an option such as `--angles`: a single value `a`, a list `a,b,c` or an
/// inclusive range `from:to:step` (at most a million values). `option` names the flag in
/// messages.
///
/// # Errors
/// A value that is not a finite number, a step that is not above 0, a range that ends
/// before it starts or holds more than a million values.
pub fn values(option: &str, text: &str) -> miette::Result<Vec<f64>> {
    let number = |s: &str| -> miette::Result<f64> {
        match s.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(miette!(
                "{option}: expected a finite number, found `{s}` in `{text}`"
            )),
        }
    };
    let parts: Vec<&str> = text.split(':').collect();
    match parts[..] {
        [single] => single.split(',').map(number).collect(),
        [from, to, step] => {
            let (from, to, step) = (number(from)?, number(to)?, number(step)?);
            if step <= 0.0 {
                return Err(miette!("{option}: range `{text}` needs a step > 0"));
            }
            if to < from {
                return Err(miette!("{option}: range `{text}` ends before it starts"));
            }
            let count = ((to - from) / step + 1e-9).floor() + 1.0;
            if count > 1e6 {
                return Err(miette!("{option}: range `{text}` has more than 1e6 values"));
            }
            Ok((0..count as usize)
                .map(|i| from + step * i as f64)
                .collect())
        }
        _ => Err(miette!(
            "{option}: expected a value, a list `a,b,c` or a range `from:to:step`, found `{text}`"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_band_is_min_max_or_a_file() {
        assert_eq!(
            "8-14".parse::<BandArg>(),
            Ok(BandArg::Flat {
                min_um: 8.0,
                max_um: 14.0
            })
        );
        assert_eq!(
            "7.5e0-1.2e1".parse::<BandArg>(),
            Ok(BandArg::Flat {
                min_um: 7.5,
                max_um: 12.0
            })
        );
        assert_eq!(
            "cam-lwir.srf".parse::<BandArg>(),
            Ok(BandArg::Response("cam-lwir.srf".into()))
        );
        let e = "8:14".parse::<BandArg>().unwrap_err();
        assert!(e.contains("such as 8-14"), "{e}");
        assert!("".parse::<BandArg>().is_err());
        assert_eq!(BandArg::default().to_string(), "8-14");
    }

    #[test]
    fn a_flat_band_is_two_increasing_positive_numbers() {
        assert_eq!(flat_band("8-14"), Ok([8.0, 14.0]));
        for bad in ["14-8", "0-14", "cam.srf", "8:14"] {
            assert!(flat_band(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn band_limits_are_checked_when_loaded() {
        for bad in ["14-8", "0-14"] {
            let b: BandArg = bad.parse().unwrap();
            assert!(b.load().is_err(), "{bad}");
        }
        let band = BandArg::default().load().unwrap();
        assert!((band.lambda_min_um() - 8.0).abs() < f64::EPSILON);
    }

    #[test]
    fn a_response_file_bounds_and_weights_the_band() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("cam.srf");
        std::fs::write(&path, "8.0 0.0\n10.0 1.0\n12.0 0.0\n").unwrap();
        let band = BandArg::Response(path.to_string_lossy().into_owned())
            .load()
            .unwrap();
        assert!((band.lambda_min_um() - 8.0).abs() < 1e-12);
        assert!((band.lambda_max_um() - 12.0).abs() < 1e-12);
        assert!(band.has_response());
        // A triangle response: less radiance than the flat 8-12 band.
        let flat = Band::new(8.0, 12.0).unwrap();
        assert!(band.radiance(300.0) < 0.6 * flat.radiance(300.0));
        let missing = BandArg::Response("no-such.srf".into()).load().unwrap_err();
        assert!(missing.to_string().contains("no-such.srf"), "{missing}");
    }

    #[test]
    fn dc_flags_give_one_calibration() {
        let fixed = DcArgs {
            dc_per_kelvin: Some(4.0),
            reference_k: Some(300.0),
            ..DcArgs::default()
        };
        assert_eq!(
            fixed.calibration(None),
            Some(Calibration::Fixed {
                dc_per_kelvin: 4.0,
                reference_k: 300.0,
                dc_at_reference: None
            })
        );
        let view_gain = DcArgs::default();
        assert_eq!(
            view_gain.calibration(Some(2.0)),
            Some(Calibration::AutoBias { dc_per_kelvin: 2.0 })
        );
        assert_eq!(DcArgs::default().calibration(None), None);
        let line = DcArgs {
            gain_dc_per_radiance: Some(3.0),
            ..DcArgs::default()
        };
        assert_eq!(
            line.calibration(Some(2.0)),
            Some(Calibration::GainOffset {
                gain_dc_per_w_m2_sr: 3.0,
                offset_dc: 0.0
            })
        );
    }

    #[test]
    fn table_formats_are_spelt_table_csv_ron() {
        use clap::ValueEnum;
        let names: Vec<String> = TableFormat::value_variants()
            .iter()
            .filter_map(|f| f.to_possible_value().map(|v| v.get_name().to_owned()))
            .collect();
        assert_eq!(names, ["table", "csv", "ron"]);
        assert_eq!(TableFormat::default(), TableFormat::Table);
    }

    #[test]
    fn values_are_one_a_list_or_a_range() {
        assert_eq!(values("--t", "300").unwrap(), [300.0]);
        assert_eq!(values("--t", "1, 2.5,-3").unwrap(), [1.0, 2.5, -3.0]);
        // 0 to 90 in steps of 30 includes both ends; a step that overshoots stops short.
        assert_eq!(values("--a", "0:90:30").unwrap(), [0.0, 30.0, 60.0, 90.0]);
        assert_eq!(values("--a", "0:1:0.4").unwrap(), [0.0, 0.4, 0.8]);
        for (bad, says) in [
            ("x", "expected a finite number, found `x`"),
            ("1,inf", "expected a finite number"),
            ("0:90:0", "needs a step > 0"),
            ("90:0:5", "ends before it starts"),
            ("0:1e7:1", "more than 1e6 values"),
            ("1:2", "a range `from:to:step`"),
        ] {
            let e = values("--a", bad).unwrap_err().to_string();
            assert!(e.starts_with("--a: ") && e.contains(says), "{bad}: {e}");
        }
    }
}
