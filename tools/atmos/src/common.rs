//! What the subcommands share: checked value lists, the band flag, and the table printer
//! (aligned text, CSV, RON).

use std::io::Write;

use irsig_cli::args::{TableFormat, values};
use miette::miette;

/// `--band` of the calculators: a band with wavelengths (a flat band or a response file),
/// spelt as in every tool.
pub type BandArgs = irsig_cli::args::BandArgs<irsig_cli::args::band::Wavelengths>;

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
pub fn print_table(
    format: TableFormat,
    columns: &[Column],
    rows: &[Vec<f64>],
) -> miette::Result<()> {
    irsig_cli::write_output(None, |w: &mut dyn Write| match format {
        TableFormat::Table => {
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
        TableFormat::Csv => {
            let header: Vec<&str> = columns.iter().map(|c| c.name.as_str()).collect();
            writeln!(w, "{}", header.join(","))?;
            for r in rows {
                let line: Vec<String> = r.iter().map(|v| format!("{v:e}")).collect();
                writeln!(w, "{}", line.join(","))?;
            }
            Ok(())
        }
        TableFormat::Ron => {
            let table = RonTable {
                columns: columns.iter().map(|c| c.name.as_str()).collect(),
                rows,
            };
            let text =
                irsig_formats::canonical::to_ron_pretty(&table).map_err(std::io::Error::other)?;
            writeln!(w, "{text}")
        }
    })
}

/// Makes a library error a diagnostic.
pub fn diagnostic(e: impl std::fmt::Display) -> miette::Report {
    miette!("{e}")
}
