//! What the subcommands share: value lists and ranges, the band options, and the table
//! printer (aligned text, CSV, RON).

use std::io::Write;

use irsig_cli::args::BandArg;
use irsig_radiometry::Band;
use miette::miette;

/// Output format of a table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Format {
    /// Aligned columns for reading.
    #[default]
    Table,
    /// Comma-separated values with a header row.
    Csv,
    /// RON: `(columns: [..], rows: [[..], ..])`.
    Ron,
}

/// `--band`, as every tool takes it.
#[derive(Debug, clap::Args)]
pub struct BandArgs {
    /// The band: `MIN-MAX` in micrometres (flat response) or a sensor response file
    /// (formats/srf.md), whose first and last wavelengths bound it.
    #[arg(long, default_value = "8-14", value_name = "MIN-MAX|FILE")]
    pub band: BandArg,
}

impl BandArgs {
    pub fn band(&self) -> miette::Result<Band> {
        self.band.load()
    }
}

/// Parses a single value `a`, a list `a,b,c` or an inclusive range `a:b:step`.
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

/// Values that must be temperatures in K (finite, ≥ 0).
pub fn temperatures(option: &str, text: &str) -> miette::Result<Vec<f64>> {
    let v = values(option, text)?;
    if let Some(bad) = v.iter().find(|&&t| t < 0.0) {
        return Err(miette!(
            "{option}: temperatures are in K and must be ≥ 0, found {bad}"
        ));
    }
    Ok(v)
}

/// Values that must be fractions in [0, 1] (emissivity, shape factor).
pub fn fractions(option: &str, text: &str) -> miette::Result<Vec<f64>> {
    let v = values(option, text)?;
    if let Some(bad) = v.iter().find(|&&f| !(0.0..=1.0).contains(&f)) {
        return Err(miette!("{option}: must be in [0, 1], found {bad}"));
    }
    Ok(v)
}

/// A column: its name (with unit) and the decimals shown in the text table.
#[derive(Debug)]
pub struct Column {
    pub name: String,
    pub decimals: usize,
}

impl Column {
    pub fn new(name: impl Into<String>, decimals: usize) -> Self {
        Self {
            name: name.into(),
            decimals,
        }
    }
}

#[derive(serde::Serialize)]
struct RonTable<'a> {
    columns: Vec<&'a str>,
    rows: &'a [Vec<f64>],
}

fn text_value(v: f64, decimals: usize) -> String {
    if v == 0.0 || (1e-3..1e9).contains(&v.abs()) {
        format!("{v:.decimals$}")
    } else {
        format!("{v:.decimals$e}")
    }
}

/// Prints `rows` under `columns` to stdout in `format`. CSV and RON carry full precision.
pub fn print_table(format: Format, columns: &[Column], rows: &[Vec<f64>]) -> miette::Result<()> {
    irsig_cli::write_output(None, |w: &mut dyn Write| match format {
        Format::Table => {
            let cells: Vec<Vec<String>> = rows
                .iter()
                .map(|r| {
                    r.iter()
                        .zip(columns)
                        .map(|(&v, c)| text_value(v, c.decimals))
                        .collect()
                })
                .collect();
            let widths: Vec<usize> = columns
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    cells
                        .iter()
                        .filter_map(|r| r.get(i).map(String::len))
                        .chain([c.name.len()])
                        .max()
                        .unwrap_or(0)
                })
                .collect();
            let header: Vec<String> = columns
                .iter()
                .zip(&widths)
                .map(|(c, &wd)| format!("{:>wd$}", c.name))
                .collect();
            writeln!(w, "{}", header.join("  "))?;
            for r in &cells {
                let line: Vec<String> = r
                    .iter()
                    .zip(&widths)
                    .map(|(v, &wd)| format!("{v:>wd$}"))
                    .collect();
                writeln!(w, "{}", line.join("  "))?;
            }
            Ok(())
        }
        Format::Csv => {
            let header: Vec<&str> = columns.iter().map(|c| c.name.as_str()).collect();
            writeln!(w, "{}", header.join(","))?;
            for r in rows {
                let line: Vec<String> = r.iter().map(|v| format!("{v:e}")).collect();
                writeln!(w, "{}", line.join(","))?;
            }
            Ok(())
        }
        Format::Ron => {
            let table = RonTable {
                columns: columns.iter().map(|c| c.name.as_str()).collect(),
                rows,
            };
            let text = ron::ser::to_string_pretty(&table, ron::ser::PrettyConfig::default())
                .map_err(std::io::Error::other)?;
            writeln!(w, "{text}")
        }
    })
}

/// Makes a library error a diagnostic.
pub fn diagnostic(e: impl std::fmt::Display) -> miette::Report {
    miette!("{e}")
}
