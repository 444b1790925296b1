//! `irsig-material list`: what a material library holds, so that a user can choose a
//! material without reading RON. Per material: its id and name, the wavelengths its
//! spectrum covers (or the band its angular table is for), its emissivity at normal
//! incidence averaged over 3–5 and 8–14 µm (Planck-weighted at 300 K, as the tracer weights
//! a curve; a band the curve does not cover is refused there, shown `-`), its solar
//! absorptance (given, or its curve over 0.3–4 µm weighted by a 5778 K black body, the
//! sun's photosphere), its thermal record in brief, and its source. `--plot DIR` writes one
//! SVG per material: ε(λ) at normal incidence with the two bands marked, or ε(θ) for a
//! material without a spectrum.

use std::fmt::Write as _;
use std::path::PathBuf;

use irsig_model::thermal::{BackAir, BackBoundary, ThermalProperties};
use irsig_model::{Material, MaterialLibrary};
use irsig_radiometry::{Band, band_average_emissivity};
use miette::miette;
use plotters::prelude::*;

/// The thermal bands the listing averages over, µm.
const BANDS_UM: [(f64, f64); 2] = [(3.0, 5.0), (8.0, 14.0)];
/// The Planck weighting temperature of the band averages, K (the tracer's, for curves).
const SURFACE_K: f64 = 300.0;
/// The solar spectrum's range, µm, and the black body that stands for it, K.
const SOLAR_UM: (f64, f64) = (0.3, 4.0);
const SUN_K: f64 = 5778.0;
/// Width and height of a plot, SVG pixels.
const CHART: (u32, u32) = (560, 300);

/// Arguments of `irsig-material list`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  irsig-material list pipelines/materials/scene-library.ron
  irsig-material list pipelines/materials/scene-library.ron --plot plots/

Columns: id, name; the wavelengths the spectrum covers (um) or the band of its angular
table; the emissivity at normal incidence averaged over 3-5 and 8-14 um with Planck
weighting at 300 K ('-' where the material is refused: its curve or table does not cover
the band); the solar absorptance (given in the thermal record, or its curve over 0.3-4 um
weighted by a 5778 K black body); the thermal record (layers, depth, back boundary) or
'-'. The source follows on its own line.")]
pub struct Args {
    /// The material library (canonical RON); `-` for stdin.
    #[arg(value_name = "LIBRARY")]
    pub library: PathBuf,
    /// Also write one SVG plot per material into DIR (an existing directory), named
    /// `ID-NAME.svg`: its emissivity against wavelength, or against angle when it has no
    /// spectrum.
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
}

/// One material's line in the listing: what the columns show, computed.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// The material's id.
    pub id: u16,
    /// Its name.
    pub name: String,
    /// What it covers: `0.3-15 um` for a spectrum, `band 8-14 um` for a band table,
    /// `grey` for a table that holds in every band.
    pub coverage: String,
    /// ε at normal incidence over 3–5 and 8–14 µm; `None` where it is refused.
    pub band_emissivity: [Option<f64>; 2],
    /// The solar absorptance and where it comes from; `None` when neither is known.
    pub solar: Option<(f64, &'static str)>,
    /// The thermal record in brief, or `-`.
    pub thermal: String,
    /// The material's source.
    pub source: String,
}

/// Runs `irsig-material list`.
///
/// # Errors
/// An unreadable or invalid library (file, line and column); a `--plot` that is not a
/// directory (usage, exit 2); a plot that cannot be drawn or written. Nothing is written
/// unless every plot is.
pub fn run(args: &Args) -> miette::Result<()> {
    if let Some(dir) = &args.plot {
        if !dir.is_dir() {
            return Err(irsig_cli::usage_error(format!(
                "--plot {}: not a directory; make it first",
                dir.display()
            )));
        }
    }
    let input = irsig_cli::read_input(&args.library)?;
    let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
    let library: MaterialLibrary = irsig_formats::canonical::from_ron(&input.name, text)?;
    let summaries: Vec<Summary> = library.materials.iter().map(summarise).collect();
    if let Some(dir) = &args.plot {
        let mut staged = irsig_cli::Staged::new();
        for m in &library.materials {
            let svg = plot(m)?;
            staged.stage(&dir.join(plot_file_name(m)), svg.as_bytes())?;
        }
        staged.commit()?;
    }
    let table = render(&summaries);
    irsig_cli::write_output(None, |w| w.write_all(table.as_bytes()))
}

/// The listing's line for one material.
#[must_use]
pub fn summarise(m: &Material) -> Summary {
    let coverage = match (&m.spectral, m.band_um) {
        (Some(s), _) => format!(
            "{}-{} um",
            s.wavelength_um.first().copied().unwrap_or(f64::NAN),
            s.wavelength_um.last().copied().unwrap_or(f64::NAN)
        ),
        (None, Some((lo, hi))) => format!("band {lo}-{hi} um"),
        (None, None) => "grey".to_owned(),
    };
    let band_emissivity = BANDS_UM.map(|(lo, hi)| normal_emissivity_over(m, lo, hi));
    let given = m
        .thermal
        .as_ref()
        .and_then(|t| t.solar_absorptance)
        .map(|a| (a, "given"));
    let solar = given.or_else(|| {
        let s = m.spectral.as_ref()?;
        let band = Band::new(SOLAR_UM.0, SOLAR_UM.1).ok()?;
        band_average_emissivity(&s.wavelength_um, &s.emissivity, &band, SUN_K)
            .ok()
            .map(|a| (a, "curve"))
    });
    Summary {
        id: m.id.0,
        name: m.name.clone(),
        coverage,
        band_emissivity,
        solar,
        thermal: m.thermal.as_ref().map_or_else(|| "-".to_owned(), brief),
        source: m.source.clone(),
    }
}

/// ε at normal incidence averaged over `[lo, hi]` µm: the curve's Planck-weighted mean, a
/// band table's first value when the table is for a band containing this one (or for every
/// band), else `None` (the tracer refuses the material there).
fn normal_emissivity_over(m: &Material, lo: f64, hi: f64) -> Option<f64> {
    let band = Band::new(lo, hi).ok()?;
    if let Some(s) = &m.spectral {
        return band_average_emissivity(&s.wavelength_um, &s.emissivity, &band, SURFACE_K).ok();
    }
    let within = m
        .band_um
        .is_none_or(|(a, b)| lo >= a * (1.0 - 1e-9) && hi <= b * (1.0 + 1e-9));
    within.then(|| m.emissivity.first().map(|r| r.1)).flatten()
}

/// `2 layers, 0.72 m, held at 273.15 K`, and the like.
fn brief(t: &ThermalProperties) -> String {
    let n = t.layers.len();
    let back = match t.back {
        BackBoundary::Adiabatic => "adiabatic".to_owned(),
        BackBoundary::Temperature { temperature_k } => format!("held at {temperature_k} K"),
        BackBoundary::Convective { h_w_m2_k, air } => match air {
            BackAir::Outdoor => format!("h {h_w_m2_k} W/m2/K to outdoor air"),
            BackAir::Fixed { temperature_k } => format!("h {h_w_m2_k} W/m2/K to {temperature_k} K"),
        },
    };
    let layers = if n == 1 { "layer" } else { "layers" };
    format!("{n} {layers}, {} m, {back}", format_depth(t.thickness_m()))
}

fn format_depth(m: f64) -> String {
    let s = format!("{m:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_owned()
}

/// The listing as aligned text: one line per material, its source on the next.
#[must_use]
pub fn render(summaries: &[Summary]) -> String {
    let name_w = summaries
        .iter()
        .map(|s| s.name.chars().count())
        .max()
        .unwrap_or(4)
        .max(4);
    let cover_w = summaries
        .iter()
        .map(|s| s.coverage.len())
        .max()
        .unwrap_or(8)
        .max(8);
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:>5}  {:<name_w$}  {:<cover_w$}  {:>7}  {:>8}  {:<17}  thermal",
        "id", "name", "spectrum", "eps 3-5", "eps 8-14", "solar absorptance"
    );
    for s in summaries {
        let eps = |e: Option<f64>| e.map_or_else(|| "-".to_owned(), |e| format!("{e:.3}"));
        let solar = s
            .solar
            .map_or_else(|| "-".to_owned(), |(a, how)| format!("{a:.3} ({how})"));
        let _ = writeln!(
            out,
            "{:>5}  {:<name_w$}  {:<cover_w$}  {:>7}  {:>8}  {:<17}  {}",
            s.id,
            s.name,
            s.coverage,
            eps(s.band_emissivity[0]),
            eps(s.band_emissivity[1]),
            solar,
            s.thermal
        );
        let _ = writeln!(out, "{:>5}  source: {}", "", s.source);
    }
    out
}

/// `ID-NAME.svg`, the name's letters and digits kept, any run of others one `-`.
#[must_use]
pub fn plot_file_name(m: &Material) -> String {
    let mut slug = String::new();
    for c in m.name.chars() {
        if c.is_ascii_alphanumeric() {
            slug.push(c.to_ascii_lowercase());
        } else if !slug.ends_with('-') {
            slug.push('-');
        }
    }
    format!("{}-{}.svg", m.id.0, slug.trim_matches('-'))
}

fn drawing(e: impl std::fmt::Display) -> miette::Report {
    miette!("cannot draw the plot: {e}")
}

/// The material's plot as SVG text: ε(λ) at normal incidence with 3–5 and 8–14 µm shaded,
/// or ε(θ) when it has no spectrum.
///
/// # Errors
/// Only if plotters fails to draw.
pub fn plot(m: &Material) -> miette::Result<String> {
    let (points, x_desc, bands): (Vec<(f64, f64)>, &str, bool) = match &m.spectral {
        Some(s) => (
            s.wavelength_um
                .iter()
                .copied()
                .zip(s.emissivity.iter().copied())
                .collect(),
            "wavelength (um)",
            true,
        ),
        None => (m.emissivity.clone(), "angle from the normal (deg)", false),
    };
    let x0 = points.first().map_or(0.0, |p| p.0);
    let x1 = points.last().map_or(1.0, |p| p.0).max(x0 + 1e-6);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, CHART).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!("{} {}", m.id.0, m.name),
                ("sans-serif", 15).into_font(),
            )
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(x0..x1, 0.0..1.0)
            .map_err(drawing)?;
        chart
            .configure_mesh()
            .label_style(("sans-serif", 12))
            .axis_desc_style(("sans-serif", 13))
            .x_desc(x_desc)
            .y_desc("emissivity")
            .draw()
            .map_err(drawing)?;
        if bands {
            let shaded = BANDS_UM
                .iter()
                .map(|&(lo, hi)| (lo.max(x0), hi.min(x1)))
                .filter(|(lo, hi)| lo < hi)
                .map(|(lo, hi)| Rectangle::new([(lo, 0.0), (hi, 1.0)], BLUE.mix(0.08).filled()));
            chart.draw_series(shaded).map_err(drawing)?;
        }
        chart
            .draw_series(LineSeries::new(points, BLACK.stroke_width(1)))
            .map_err(drawing)?;
        root.present().map_err(drawing)?;
    }
    Ok(svg)
}
