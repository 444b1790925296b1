//! The command-line vocabulary the tools share, each flag defined once here so that every
//! tool spells, types and documents a setting alike (`tests/tests/architecture.rs` holds
//! that a flag two tools share is defined here, once, with one type, default, value name,
//! number of values and requiredness):
//!
//! - the band ([`band`]: `--band`, one flag whose accepted forms each command states),
//! - the sun ([`sun`]: `--sun-zenith-deg`/`--sun-azimuth-deg` or `--sun-utc` with the place,
//!   SPA's corrections, a plan's `--day-of-year`),
//! - the views and the unit of the 1990 files ([`view`]: repeatable `--view`,
//!   `--legacy-unit`, km by default),
//! - the atmosphere ([`atmosphere`]: `--atmosphere`, accepted forms per command),
//! - how many things run at once ([`threads`]: `--threads`),
//! - the digital-count calibration ([`counts`]) and a frame's files ([`frame`]),
//! - where a tool writes ([`outputs`]: `-o`, `--dc-png`, `--lut`, `--colour-preview`,
//!   `--name`, `--ron`, `--legacy`, `--to-legacy`) and the inputs several tools read
//!   ([`inputs`]: `--scene`, `--materials`, `--regions`, `--radiance`, `--decision`,
//!   `--uncertainties`),
//! - and small parsers: library enums offered by name ([`named`]), a table's `--format`,
//!   a seed, lists or ranges of numbers ([`values`]) and a pixel ([`pixel`]).
//!
//! A tool takes a flag by flattening its struct (`#[command(flatten)]`); where it needs the
//! flag in its own way (required, or tied to another of its flags) it says so on its own
//! command (`mut_arg`, a group), never by defining the flag again. Old spellings a tool
//! once had stay accepted there as hidden aliases.

use std::str::FromStr;

use clap::builder::{PossibleValuesParser, TypedValueParser};
use irsig_model::LengthUnit;
use miette::miette;

pub mod atmosphere;
pub mod band;
pub mod counts;
pub mod frame;
pub mod inputs;
pub mod outputs;
pub mod sun;
pub mod threads;
pub mod tolerance;
pub mod view;

pub use atmosphere::AtmosphereArgs;
pub use band::{BandArg, BandArgs, ImageBandArgs, ResolvedBand, band_of};
pub use counts::DcArgs;
pub use frame::{FrameOutputArgs, with_suffix};
pub use sun::{DayOfYear, PlaceArgs, SunArgs, SunPrecisionArgs};
pub use threads::ThreadsArgs;
pub use tolerance::{DecisionOut, Tolerance};
pub use view::{LegacyUnitArgs, TrailingViews, ViewArgs, ViewFile};

/// A length unit by name (m, km, cm, mm, ft, in), as a clap value parser.
///
/// # Errors
/// Any other word, naming the units.
pub fn length_unit(s: &str) -> Result<LengthUnit, String> {
    s.parse()
}

/// `--ground-albedo ALBEDO`: the share of sunlight the ground reflects, in the tools that
/// model a ground's reflection (the thermal model's ground beyond the scene, a loads plan's
/// LOWTRAN7 runs).
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct GroundAlbedo {
    /// The share of sunlight the ground reflects, 0 to 1.
    #[arg(
        id = "ground_albedo",
        long = "ground-albedo",
        value_name = "ALBEDO",
        value_parser = albedo
    )]
    pub value: Option<f64>,
}

/// `--ground-albedo`: a finite albedo from 0 to 1.
fn albedo(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(a) if a.is_finite() && (0.0..=1.0).contains(&a) => Ok(a),
        _ => Err(format!(
            "expected the ground's albedo, a number from 0 to 1, found `{s}`"
        )),
    }
}

/// `--seed N`: the seed of a tool's random streams; the same seed gives the same bytes.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct Seed {
    /// Seed of the random streams: the same seed gives the same output, bit for bit.
    #[arg(id = "seed", long = "seed", value_name = "SEED", default_value_t = 0)]
    pub value: u64,
}

/// `--format table|csv|ron`: how a table is printed.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct Format {
    /// Output format: `table` (aligned columns), `csv` (a header row, full precision) or
    /// `ron` (full precision).
    #[arg(
        id = "format",
        long = "format",
        value_name = "FORMAT",
        value_enum,
        default_value_t
    )]
    pub value: TableFormat,
}

/// `--probe COLUMN,ROW`: a pixel, as a clap value parser.
///
/// # Errors
/// Anything but two whole numbers of 0 or more split by a comma.
pub fn pixel(s: &str) -> Result<(u32, u32), String> {
    let (a, b) = s
        .split_once(',')
        .ok_or_else(|| format!("expected COLUMN,ROW such as 128,64, found `{s}`"))?;
    let p = |t: &str| {
        t.trim()
            .parse::<u32>()
            .map_err(|_| format!("expected a pixel index (0 or more), found `{t}`"))
    };
    Ok((p(a)?, p(b)?))
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
    fn a_pixel_is_column_comma_row() {
        assert_eq!(pixel("128,64"), Ok((128, 64)));
        assert!(pixel("128").is_err());
        assert!(pixel("-1,3").is_err());
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
