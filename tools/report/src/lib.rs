//! `irsig-report`: one self-contained HTML page per run (`formats/report.md`). It reads a
//! run's outputs — the tracer's truth EXR and/or a radiance EXR, and optionally the regions
//! file, the tolerance pilot's decision, the declared uncertainties, the sensor stage's LUT
//! and colour preview and the pipeline file — and writes a page that shows the apparent
//! temperature in false colour with its scale in kelvin and the profile's line drawn on it,
//! the pixels the counts clip (with a warning at the top of the page), its histogram, a line
//! profile, per-region statistics (the `irsig-stats` table, computed by its library), the
//! decision table, the error budget (`sigma_total`, its sources and what was declared), the
//! LUT curve, and provenance along the whole chain: every input the images record (the
//! trace's and the sensor's, by SHA-256), the report's own, the pipeline's files as they
//! are, the run's command lines and irsig's version. Files are named relative to the page.
//! Images are `data:` URIs and plots inline SVG (drawn by plotters): the page needs no
//! other file and no network. A section that does not apply is left out, and one line says
//! which flag would fill it.
//!
//! ```no_run
//! use clap::Parser;
//! let cli = irsig_report::Cli::parse_from([
//!     "irsig-report", "out/truth.exr", "--regions", "regions.ron",
//!     "--decision", "out/frame.decision.ron", "--lut", "out/lut.txt",
//!     "--profile", "0,200:511,200", "-o", "out/report.html",
//! ]);
//! irsig_report::run(cli)?;
//! # Ok::<(), miette::Report>(())
//! ```

// A closed stderr must not panic the tool: notes go through `irsig_cli::note!`.
#![warn(clippy::print_stderr)]

pub mod chain;
pub mod names;
pub mod plots;
pub mod saturation;

mod html;
mod sections;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use base64::Engine as _;
use clap::Parser;
use irsig_cli::Input;
use irsig_cli::args::ImageBandArgs;
use irsig_cli::args::inputs::{
    Decision as DecisionArg, RadianceImage, Regions, Uncertainties as UncertaintiesArg,
};
use irsig_cli::args::outputs::{ColourPreview, Lut, Output};
use irsig_model::RegionSet;
use irsig_model::decision::Decision;
use irsig_model::truth::Layer;
use irsig_model::uncertainty::{Facets, Uncertainties};
use irsig_raster::Raster;
use miette::miette;

use crate::chain::Known;
use crate::names::Names;
use html::*;
use sections::*;

const APPARENT_LAYER: &str = Layer::ApparentTemperature.name();
const MATERIAL_LAYER: &str = Layer::MaterialPrimary.name();
const RADIANCE_LAYER: &str = Layer::Radiance.name();
const SIGMA_LAYER: &str = Layer::SigmaTotal.name();

/// The error budget's sources, each a σ layer of the truth EXR, with what it is in words.
const BUDGET_SOURCES: [(Layer, &str); 6] = [
    (Layer::SigmaKineticTemperature, "kinetic temperature"),
    (Layer::SigmaEmissivity, "emissivity"),
    (Layer::SigmaTransmission, "atmospheric transmission"),
    (Layer::SigmaPathRadiance, "path and sky radiance"),
    (Layer::SigmaModel, "the pilot's chosen models"),
    (Layer::SigmaTotal, "root-sum-square of the above"),
];

/// Bins of the histogram of apparent temperature.
const HISTOGRAM_BINS: usize = 64;

/// The PNG signature: the colour preview must start with it.
const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

const EXAMPLE: &str = "\
Examples:
  irsig-report out/truth.exr -o out/report.html
      the colour image, histogram and provenance of the tracer's apparent temperature
  irsig-report out/truth.exr --radiance out/sensor.exr --regions regions.ron \\
      --decision out/frame.decision.ron --uncertainties u.ron --lut out/lut.txt \\
      --colour-preview out/colour.png --profile 0,200:511,200 \\
      --pipeline pipelines/quickstart.ron -o out/report.html
      everything: the sensor's apparent temperature, the pixels its counts clip,
      statistics per region, the pilot's decision, the error budget (when the truth EXR
      has sigma_total) with what was declared, the LUT curve, the pipeline's files and
      the run's command lines

What the page holds: formats/report.md.";

/// One self-contained HTML report of a run.
#[derive(Debug, Parser)]
#[command(
    name = "irsig-report",
    version,
    about,
    after_help = EXAMPLE,
    mut_arg("radiance", |a| a.help(
        "Show the apparent temperature of this image's `radiance` layer (W m^-2 sr^-1) in \
         --band instead (the sensor stage's EXR, say); the same size as the truth EXR"
    )),
    mut_arg("regions", |a| a.requires("truth").help(
        "Per-region statistics from this regions file (canonical RON); needs the truth EXR"
    )),
    mut_arg("uncertainties", |a| a.requires("truth").help(
        "The declared uncertainties the truth EXR was traced with (`irsig-trace \
         --uncertainties`), listed in the error budget; must be the file the truth EXR records"
    )),
    mut_arg("lut", |a| a.help(
        "The sensor stage's LUT (`irsig-sensor --lut`): its curve, count against kelvin, and \
         the pixels at count 0 and at full scale"
    )),
    mut_arg("colour_preview", |a| a.help(
        "The sensor stage's colour preview PNG (`irsig-sensor --colour-preview`): checked and \
         listed with its SHA-256 (the page shows the image once, in its own colours)"
    )),
    mut_arg("output", |a| a.help(
        "Output HTML file (`-` or absent: stdout); written atomically. Files are named on the \
         page relative to its directory"
    )),
)]
#[command(group = clap::ArgGroup::new("image").required(true).multiple(true).args(["truth", "radiance"]))]
pub struct Cli {
    /// The tracer's truth EXR: its `apparent_temperature` (K) is shown unless --radiance
    /// is given; its `material_primary` selects the regions; its `sigma_total`, when
    /// present, is the error-budget image.
    pub truth: Option<String>,
    /// `--radiance FILE`.
    #[command(flatten)]
    pub radiance: RadianceImage,
    /// The band of --radiance, which that image records (irsig-trace and irsig-sensor
    /// write it); --band must be that band unless --override-band.
    #[command(flatten)]
    pub band: ImageBandArgs,
    /// `--regions FILE`.
    #[command(flatten)]
    pub regions: Regions,
    /// `--decision FILE`.
    #[command(flatten)]
    pub decision: DecisionArg,
    /// `--uncertainties FILE`.
    #[command(flatten)]
    pub uncertainties: UncertaintiesArg,
    /// `--lut FILE`: the sensor stage's LUT, read.
    #[command(flatten)]
    pub lut: Lut,
    /// `--colour-preview FILE`: the sensor stage's colour preview, read.
    #[command(flatten)]
    pub colour_preview: ColourPreview,
    /// A line profile of apparent temperature from pixel (X0, Y0) to (X1, Y1), columns and
    /// rows from the top-left pixel (0, 0); the line is drawn on the image.
    #[arg(long, value_name = "X0,Y0:X1,Y1")]
    pub profile: Option<ProfileLine>,
    /// The pipeline file of the run: its stages' command lines are listed, and its files
    /// as they are now (hashed like every input).
    #[arg(long, value_name = "FILE")]
    pub pipeline: Option<String>,
    /// A command line of the run, listed as given (repeatable, in order).
    #[arg(long, value_name = "TEXT")]
    pub command: Vec<String>,
    /// The page's title (default: the image's file name).
    #[arg(long, value_name = "TEXT")]
    pub title: Option<String>,
    /// `-o PATH`: the page.
    #[command(flatten)]
    pub output: Output,
}

/// The flags' own rules are clap's and the run's: nothing more is checked before a file
/// is read.
impl irsig_cli::CheckArgs for Cli {}

/// A line between two pixels, `X0,Y0:X1,Y1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ProfileLine {
    /// The start: column, row.
    pub from: (usize, usize),
    /// The end: column, row.
    pub to: (usize, usize),
}

impl FromStr for ProfileLine {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let expected = || format!("`{s}`: expected X0,Y0:X1,Y1 in pixels, such as 0,200:511,200");
        let point = |p: &str| -> Result<(usize, usize), String> {
            let (x, y) = p.split_once(',').ok_or_else(expected)?;
            Ok((
                x.trim().parse().map_err(|_| expected())?,
                y.trim().parse().map_err(|_| expected())?,
            ))
        };
        let (a, b) = s.split_once(':').ok_or_else(expected)?;
        Ok(Self {
            from: point(a)?,
            to: point(b)?,
        })
    }
}

impl std::fmt::Display for ProfileLine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{},{}:{},{}",
            self.from.0, self.from.1, self.to.0, self.to.1
        )
    }
}

impl ProfileLine {
    /// The pixels along the line, one per step of the longer axis, ends included, each
    /// with its distance from the start in pixels.
    #[must_use]
    pub fn pixels(&self) -> Vec<(usize, usize, f64)> {
        let (x0, y0) = (self.from.0 as f64, self.from.1 as f64);
        let (dx, dy) = (self.to.0 as f64 - x0, self.to.1 as f64 - y0);
        let steps = dx.abs().max(dy.abs()) as usize;
        let length = dx.hypot(dy);
        (0..=steps)
            .map(|k| {
                let u = if steps == 0 {
                    0.0
                } else {
                    k as f64 / steps as f64
                };
                (
                    (x0 + u * dx).round() as usize,
                    (y0 + u * dy).round() as usize,
                    u * length,
                )
            })
            .collect()
    }
}

/// An input the report itself read, as provenance lists it.
fn own(names: &Names, role: &str, input: &Input) -> (String, Known) {
    (
        role.to_owned(),
        Known {
            shown: names.show_name(&input.name),
            sha256: input.sha256(),
        },
    )
}

/// One file the pipeline names, as it is now.
struct PipelineFile {
    shown: String,
    /// `sha256:` and hex, or `None` when the file is missing.
    sha256: Option<String>,
    written_by: Vec<String>,
    read_by: Vec<String>,
}

/// Every file the pipeline's steps read or write, once each, hashed as it is now; the
/// report's own output is left out (it is being written).
fn pipeline_files(
    plan: &irsig_pipeline::Plan,
    names: &Names,
    output: Option<&Path>,
) -> miette::Result<Vec<PipelineFile>> {
    let this_page = output
        .filter(|o| o.as_os_str() != "-")
        .map(|o| names.show(o));
    let mut files: Vec<PipelineFile> = Vec::new();
    for step in &plan.steps {
        let refs = step
            .inputs
            .iter()
            .map(|f| (f, false))
            .chain(step.outputs.iter().map(|f| (f, true)));
        for (file, written) in refs {
            let path = plan.base_dir().join(&file.path);
            let shown = names.show(&path);
            if this_page.as_deref() == Some(shown.as_str()) {
                continue;
            }
            let i = match files.iter().position(|f| f.shown == shown) {
                Some(i) => i,
                None => {
                    let sha256 = irsig_cli::read_input_if_any(&path)?.map(|i| i.sha256());
                    files.push(PipelineFile {
                        shown,
                        sha256,
                        written_by: Vec::new(),
                        read_by: Vec::new(),
                    });
                    files.len() - 1
                }
            };
            let list = if written {
                &mut files[i].written_by
            } else {
                &mut files[i].read_by
            };
            if !list.contains(&step.name) {
                list.push(step.name.clone());
            }
        }
    }
    Ok(files)
}

/// Runs the tool.
///
/// # Errors
/// Unreadable or malformed input (the regions, decision, uncertainties and LUT files with
/// line and column), a missing layer, images of different sizes, a profile outside the
/// image, a region that selects nothing, uncertainties other than those the truth EXR
/// records, or an unwritable output; nothing is written then.
#[allow(clippy::too_many_lines)] // one page, section by section
pub fn run(cli: Cli) -> miette::Result<()> {
    let band_file = cli.band.band.response_file().map(PathBuf::from);
    let named = [
        &cli.truth,
        &cli.radiance.file,
        &cli.regions.file,
        &cli.decision.file,
        &cli.pipeline,
    ]
    .into_iter()
    .flatten()
    .map(PathBuf::from)
    .chain(cli.lut.path.iter().cloned())
    .chain(cli.colour_preview.path.iter().cloned())
    .chain(band_file);
    irsig_cli::refuse_output_is_input(named, cli.output.path.iter())?;
    let names = Names::for_output(cli.output.path.as_deref());
    let mut inputs: Vec<(String, Known)> = Vec::new();

    let truth = match &cli.truth {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(own(&names, "truth EXR", &input));
            let image = irsig_cli::read_exr(&input.name, &input.bytes)?;
            let recorded = irsig_cli::provenance(&input.name, &image)?;
            // Without a radiance image a --band is the truth EXR's, whose apparent
            // temperatures are in the band it records: given, it must be that band.
            if cli.radiance.file.is_none() && cli.band.band.given().is_some() {
                let band = cli
                    .band
                    .resolve(&input.name, recorded.as_ref().map(|p| &p.band))?;
                if let Some(w) = &band.warning {
                    irsig_cli::note!("irsig-report: warning: {w}");
                }
            }
            Some((input.name, image, recorded))
        }
        None => None,
    };
    let radiance = match &cli.radiance.file {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(own(&names, "radiance EXR", &input));
            let image = irsig_cli::read_exr(&input.name, &input.bytes)?;
            let recorded = irsig_cli::provenance(&input.name, &image)?;
            let band = cli
                .band
                .resolve(&input.name, recorded.as_ref().map(|p| &p.band))?;
            if let Some(w) = &band.warning {
                irsig_cli::note!("irsig-report: warning: {w}");
            }
            if let Some((name, t, _)) = &truth
                && (image.width, image.height) != (t.width, t.height)
            {
                return Err(miette!(
                    "{}: the image is {} x {} pixels but the truth EXR {name} is {} x {}: \
                     expected the same size (trace and sense at one resolution)",
                    input.name,
                    image.width,
                    image.height,
                    t.width,
                    t.height
                ));
            }
            Some((input.name, image, band, recorded))
        }
        None => None,
    };

    // The values every section shows: apparent temperature, K; `source` names them as
    // messages do, `shown` as the page does.
    let (values, width, height, source, shown_source): (Vec<f32>, usize, usize, String, String) =
        match (&radiance, &truth) {
            (Some((name, image, band, _)), _) => {
                let l = layer(image, name, RADIANCE_LAYER)?;
                let t = irsig_radiometry::apparent_temperatures(&band.band, l);
                let say = |n: &str| {
                    format!(
                        "apparent temperature of the `{RADIANCE_LAYER}` layer of {n} in {}",
                        band.record
                    )
                };
                (
                    t,
                    image.width,
                    image.height,
                    say(name),
                    say(&names.show_name(name)),
                )
            }
            (None, Some((name, image, _))) => (
                layer(image, name, APPARENT_LAYER)?.to_vec(),
                image.width,
                image.height,
                format!("`{APPARENT_LAYER}` layer of {name}"),
                format!("`{APPARENT_LAYER}` layer of {}", names.show_name(name)),
            ),
            (None, None) => {
                return Err(irsig_cli::usage_error(
                    "expected a truth EXR or --radiance FILE: the report shows an image",
                ));
            }
        };
    // Past the values, of the radiance image only its radiances are kept, and only to
    // compare with a LUT's (saturation): the page is made in the memory per pixel the
    // README states.
    let mut radiance = radiance;
    let radiance_values: Option<Vec<f32>> = radiance.as_mut().and_then(|(_, image, _, _)| {
        let i = image.layers.iter().position(|l| l.name == RADIANCE_LAYER);
        let kept = i
            .filter(|_| cli.lut.path.is_some())
            .map(|i| image.layers.swap_remove(i).data);
        image.layers = Vec::new();
        kept
    });
    let Some(range) = plots::finite_range(&values) else {
        return Err(miette!(
            "{source}: no pixel has a finite apparent temperature: expected an image with \
             at least one"
        ));
    };

    let profile = match cli.profile {
        Some(line) => {
            for (end, (x, y)) in [("start", line.from), ("end", line.to)] {
                if x >= width || y >= height {
                    return Err(irsig_cli::usage_error(format!(
                        "--profile {line}: the {end} ({x}, {y}) is outside the image \
                         ({width} x {height} pixels: columns 0-{}, rows 0-{})",
                        width - 1,
                        height - 1
                    )));
                }
            }
            Some((
                line,
                line.pixels()
                    .into_iter()
                    .map(|(x, y, d)| (d, f64::from(values[y * width + x])))
                    .collect::<Vec<_>>(),
            ))
        }
        None => None,
    };

    let regions = match (&cli.regions.file, &truth) {
        (Some(path), Some((truth_name, image, _))) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(own(&names, "regions", &input));
            let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
            let set: RegionSet = irsig_formats::canonical::from_ron(&input.name, text)?;
            let ids = layer(image, truth_name, MATERIAL_LAYER)?;
            let mut table = irsig_regions::tabulate(&irsig_regions::Inputs {
                regions_name: &input.name,
                regions_text: text,
                set: &set,
                image_name: truth_name,
                material_ids: ids,
                width,
                values: &values,
                source: source.clone(),
                unit: "K",
                celsius: false,
            })?;
            table.values.clone_from(&shown_source);
            Some((table, set, ids))
        }
        _ => None,
    };

    let decision = match &cli.decision.file {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(own(&names, "decision", &input));
            let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
            let d: Decision = irsig_formats::canonical::from_ron(&input.name, text)?;
            Some(d)
        }
        None => None,
    };

    // What the truth EXR records of the uncertainties it was traced with.
    let recorded_uncertainties = truth.as_ref().and_then(|(_, _, p)| p.as_ref()).map(|p| {
        p.inputs
            .iter()
            .find(|i| i.stage == "trace" && i.role == "uncertainties")
            .map(|i| i.sha256.clone())
    });
    let uncertainties = match &cli.uncertainties.file {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
            let u: Uncertainties = irsig_formats::canonical::from_ron(&input.name, text)?;
            let truth_name = truth.as_ref().map_or("", |(n, _, _)| n.as_str());
            match &recorded_uncertainties {
                Some(Some(sha)) if *sha != input.sha256() => {
                    return Err(irsig_cli::usage_error(format!(
                        "--uncertainties {}: its SHA-256 is {}, but {truth_name} was traced \
                         with uncertainties of SHA-256 {}: give the file the truth EXR was \
                         traced with",
                        input.name,
                        chain::hex(&input.sha256()),
                        chain::hex(sha)
                    )));
                }
                Some(None) => {
                    return Err(irsig_cli::usage_error(format!(
                        "--uncertainties {}: {truth_name} was traced without declared \
                         uncertainties (it records none): trace with --uncertainties FILE \
                         for an error budget",
                        input.name
                    )));
                }
                _ => {}
            }
            inputs.push(own(&names, "uncertainties", &input));
            Some(u)
        }
        None => None,
    };

    let lut = match &cli.lut.path {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(own(&names, "LUT", &input));
            let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
            Some((
                names.show_name(&input.name),
                irsig_formats::lut::parse(&input.name, text)?,
            ))
        }
        None => None,
    };

    if let Some(path) = &cli.colour_preview.path {
        let input = irsig_cli::read_input(path)?;
        if !input.bytes.starts_with(PNG_SIGNATURE) {
            return Err(miette::Report::new(irsig_formats::ParseError::in_binary(
                input.name.clone(),
                0,
                "expected a PNG (the sensor stage's --colour-preview), found no PNG signature",
            )));
        }
        inputs.push(own(&names, "colour preview", &input));
    }

    let (commands, pipeline): (Vec<String>, Option<(String, Vec<PipelineFile>)>) =
        match &cli.pipeline {
            Some(path) => {
                let input = irsig_cli::read_input(path)?;
                inputs.push(own(&names, "pipeline", &input));
                let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
                let base = input.base_dir();
                let pipeline = irsig_pipeline::Pipeline::parse(&input.name, text, &base)
                    .map_err(miette::Report::new)?;
                let mut tools =
                    irsig_pipeline::Tools::new(|t| Some(PathBuf::from(format!("irsig-{t}"))));
                tools.with_sun_flags(irsig_pipeline::SunFlags {
                    field: irsig_cli::args::sun::flag,
                    day_of_year: irsig_cli::args::DayOfYear::FLAG,
                });
                let plan = pipeline.plan(&tools).map_err(miette::Report::new)?;
                let files = pipeline_files(&plan, &names, cli.output.path.as_deref())?;
                (
                    plan.steps
                        .iter()
                        .map(irsig_pipeline::Step::command_line)
                        .chain(cli.command.iter().cloned())
                        .collect(),
                    Some((names.show(plan.base_dir()), files)),
                )
            }
            None => (cli.command.clone(), None),
        };

    let sigma = match &truth {
        Some((name, image, _)) => image.layer(SIGMA_LAYER).map(|_| (name.clone(), image)),
        None => None,
    };

    // Provenance along the chain: what the images record, matched to the files known here.
    let recorded = chain::merge(
        truth.as_ref().and_then(|(_, _, p)| p.as_ref()),
        radiance.as_ref().and_then(|(_, _, _, p)| p.as_ref()),
    );
    let known: Vec<Known> = pipeline
        .iter()
        .flat_map(|(_, files)| files)
        .filter_map(|f| {
            f.sha256.as_ref().map(|s| Known {
                shown: f.shown.clone(),
                sha256: s.clone(),
            })
        })
        .collect();
    let chain_rows = chain::rows(&recorded, &known, &inputs);

    let saturated = lut
        .as_ref()
        .and_then(|(_, rows)| saturation::saturation(rows, radiance_values.as_deref(), &values));

    // Everything is read and checked; now the page.
    let title = cli.title.clone().unwrap_or_else(|| {
        let name = cli
            .radiance
            .file
            .as_deref()
            .or(cli.truth.as_deref())
            .unwrap_or("run");
        Path::new(name)
            .file_name()
            .map_or_else(|| name.to_owned(), |n| n.to_string_lossy().into_owned())
    });
    let (lo, hi) = extremes(&values);
    let mut page = String::new();
    let w = &mut page;
    let _ = write!(
        w,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>irsig report: {t}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
         <h1>irsig report: {t}</h1>\n",
        t = escape(&title)
    );

    // Warnings first, where nobody can miss them.
    let mut warnings: Vec<(&str, String)> = Vec::new();
    if let (Some(s), Some((_, rows))) = (&saturated, &lut)
        && s.at_zero + s.at_full > 0
    {
        warnings.push((
            "saturation-warning",
            format!(
                "Saturated counts: {} pixels ({} %) are at full scale, count {}, and {} ({} %) \
                 at count 0; their counts do not tell their temperatures. The LUT spans \
                 {:.2}-{:.2} K, the image {lo:.2}-{hi:.2} K: give the sensor fewer counts per \
                 kelvin (--dc-per-kelvin), more bits (--dc-bits) or a fixed calibration \
                 (--reference-k) whose counts cover the scene.",
                s.at_full,
                percent(s.at_full, s.pixels),
                s.full_count,
                s.at_zero,
                percent(s.at_zero, s.pixels),
                rows[0].temperature_k,
                rows[rows.len() - 1].temperature_k,
            ),
        ));
    }
    if let Some(roles) = &recorded.disagree {
        warnings.push((
            "chain-warning",
            format!(
                "The truth EXR and the radiance image record different inputs of the trace \
                 ({roles}): they are not from one run, and statistics that pair the one's \
                 materials with the other's values mean nothing."
            ),
        ));
    }
    if pipeline.is_some() {
        let stale = chain::unmatched(&chain_rows);
        if !stale.is_empty() {
            warnings.push((
                "stale-warning",
                format!(
                    "The images were made from inputs that no file of the pipeline holds now \
                     ({}): the pipeline's files changed since; run it again.",
                    stale.join(", ")
                ),
            ));
        }
    }
    if !warnings.is_empty() {
        w.push_str("<div id=\"warnings\">\n");
        for (id, text) in &warnings {
            let _ = writeln!(
                w,
                "<p class=\"warning\" id=\"{id}\" role=\"alert\">{}</p>",
                escape(text)
            );
        }
        w.push_str("</div>\n");
    }

    // The colour image, the profile's line on it, and its scale.
    let scale = display_scale(height);
    let _ = write!(
        w,
        "<section id=\"image\">\n<h2>Apparent temperature</h2>\n<p>{} ({width} x {height} \
         pixels): minimum <span class=\"num\" id=\"t-min\">{lo:.3}</span> K, mean <span \
         class=\"num\" id=\"t-mean\">{:.3}</span> K, maximum <span class=\"num\" \
         id=\"t-max\">{hi:.3}</span> K.</p>\n<div class=\"figure\"><div class=\"holder\">{}{}\
         </div>{}</div>\n",
        escape(&shown_source),
        finite_mean(&values),
        img(
            "colour",
            &false_colour(&values, width, height, range),
            width,
            height,
            "apparent temperature in the inferno colour map"
        ),
        profile
            .as_ref()
            .map(|(line, _)| profile_overlay(line, width, height, scale))
            .unwrap_or_default(),
        plots::colour_bar(range, "apparent temperature (K)")?
    );
    if let Some((line, _)) = &profile {
        let _ = writeln!(
            w,
            "<p>The line profile's pixels are drawn on the image in cyan, from the ring at \
             ({}, {}) to ({}, {}).</p>",
            line.from.0, line.from.1, line.to.0, line.to.1
        );
    }
    w.push_str("</section>\n");

    // The pixels the counts clip.
    if let (Some(s), Some((name, rows))) = (&saturated, &lut) {
        let (first, last) = (&rows[0], &rows[rows.len() - 1]);
        let _ = write!(
            w,
            "<section id=\"saturation\">\n<h2>Saturation</h2>\n<p>Of the <span class=\"num\" \
             id=\"sat-pixels\">{}</span> pixels, <span class=\"num\" id=\"sat-zero\">{}</span> \
             ({} %) are at count 0 and <span class=\"num\" id=\"sat-full\">{}</span> ({} %) at \
             full scale, count {}: the counts of {} ({:.4}-{:.4} K) against the image's \
             {lo:.3}-{hi:.3} K ({}).</p>\n",
            s.pixels,
            s.at_zero,
            percent(s.at_zero, s.pixels),
            s.at_full,
            percent(s.at_full, s.pixels),
            s.full_count,
            escape(name),
            first.temperature_k,
            last.temperature_k,
            s.compared
        );
        if let Some((table, set, ids)) = &regions
            && s.at_zero + s.at_full > 0
        {
            w.push_str(
                "<table id=\"saturation-regions\">\n<thead><tr><th>region</th><th>pixels</th>\
                 <th>at count 0</th><th>at full scale</th><th>saturated (%)</th></tr></thead>\
                 \n<tbody>\n",
            );
            for (region, row) in set.regions.iter().zip(&table.regions) {
                let count = |mask: &[f32]| {
                    irsig_regions::stats::region_stats(region, ids, mask, width)
                        .map_or(0, |r| (r.mean * r.pixels as f64).round() as usize)
                };
                let (zero, full) = (count(&s.zero_mask), count(&s.full_mask));
                let _ = writeln!(
                    w,
                    "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{zero}</td>\
                     <td class=\"num\">{full}</td><td class=\"num\">{}</td></tr>",
                    escape(&row.region),
                    row.pixels,
                    percent(zero + full, row.pixels)
                );
            }
            w.push_str("</tbody>\n</table>\n");
        }
        w.push_str("</section>\n");
    }

    // Histogram.
    let _ = write!(
        w,
        "<section id=\"histogram\">\n<h2>Histogram of apparent temperature</h2>\n<p>{} \
         bins of {:.4} K.</p>\n<div class=\"figure\">{}</div>\n</section>\n",
        HISTOGRAM_BINS,
        (range.1 - range.0) / HISTOGRAM_BINS as f64,
        plots::histogram(&values, range, HISTOGRAM_BINS)?
    );

    // What is left out, and the flag that would put it in: one line.
    let mut not_shown: Vec<&str> = Vec::new();

    // Line profile.
    match &profile {
        Some((line, points)) => {
            let _ = write!(
                w,
                "<section id=\"profile\">\n<h2>Line profile</h2>\n<p>From pixel ({}, {}) to \
                 ({}, {}), {} pixels (the line on the image above).</p>\n<div class=\"figure\">\
                 {}</div>\n</section>\n",
                line.from.0,
                line.from.1,
                line.to.0,
                line.to.1,
                points.len(),
                plots::line_chart(
                    "line profile",
                    points,
                    "distance from the start (pixels)",
                    "apparent temperature (K)"
                )?
            );
        }
        None => not_shown.push("a line profile (--profile X0,Y0:X1,Y1)"),
    }

    // Per-region statistics.
    match &regions {
        Some((table, _, _)) => {
            w.push_str("<section id=\"regions\">\n<h2>Per-region statistics</h2>\n");
            stats_table(w, table);
            w.push_str("</section>\n");
        }
        None => not_shown.push("per-region statistics (the truth EXR and --regions FILE)"),
    }

    // The decision.
    match &decision {
        Some(d) => {
            w.push_str("<section id=\"decision\">\n<h2>The tolerance pilot's decision</h2>\n");
            decision_table(w, d);
            w.push_str("</section>\n");
        }
        None => not_shown.push(
            "the tolerance pilot's decision (trace with --tolerance K, then --decision FILE)",
        ),
    }

    // The error budget.
    match &sigma {
        Some((name, image)) => {
            let s = image
                .layer(SIGMA_LAYER)
                .map_or(&[][..], |l| l.data.as_slice());
            w.push_str("<section id=\"budget\">\n<h2>Error budget</h2>\n");
            match plots::finite_range(s) {
                Some(r) => {
                    let _ = write!(
                        w,
                        "<p>The `{SIGMA_LAYER}` layer of {}: σ of apparent temperature from \
                         the declared uncertainties, root-sum-square of its sources, from \
                         <span class=\"num\" id=\"sigma-min\">{:.4}</span> K to <span \
                         class=\"num\" id=\"sigma-max\">{:.4}</span> K.</p>\n<div \
                         class=\"figure\">{}{}</div>\n",
                        escape(&names.show_name(name)),
                        extremes(s).0,
                        extremes(s).1,
                        img(
                            "sigma",
                            &false_colour(s, width, height, r),
                            width,
                            height,
                            "sigma_total in the inferno colour map"
                        ),
                        plots::colour_bar(r, "σ total (K)")?
                    );
                }
                None => {
                    let _ = writeln!(
                        w,
                        "<p>The `{SIGMA_LAYER}` layer of {} has no finite value.</p>",
                        escape(&names.show_name(name))
                    );
                }
            }
            w.push_str(
                "<table id=\"budget-sources\">\n<thead><tr><th>source</th><th>layer</th>\
                 <th>mean σ (K)</th><th>largest σ (K)</th></tr></thead>\n<tbody>\n",
            );
            for (layer, what) in BUDGET_SOURCES {
                if let Some(l) = image.layer(layer.name()) {
                    let _ = writeln!(
                        w,
                        "<tr><td>{what}</td><td><code>{}</code></td><td class=\"num\">{:.4}</td>\
                         <td class=\"num\">{:.4}</td></tr>",
                        layer.name(),
                        finite_mean(&l.data),
                        extremes(&l.data).1
                    );
                }
            }
            w.push_str("</tbody>\n</table>\n<h3>What was declared</h3>\n");
            match (&uncertainties, &recorded_uncertainties) {
                (Some(u), _) => declared_table(w, u),
                (None, Some(Some(sha))) => {
                    let _ = writeln!(
                        w,
                        "<p id=\"declared-absent\">The truth EXR was traced with declared \
                         uncertainties of SHA-256 <code>{}</code>; give that file as \
                         --uncertainties FILE to list them here.</p>",
                        chain::hex(sha)
                    );
                }
                (None, _) => w.push_str(
                    "<p id=\"declared-absent\">The truth EXR does not record its declared \
                     uncertainties' file; give it as --uncertainties FILE to list them \
                     here.</p>\n",
                ),
            }
            w.push_str("</section>\n");
        }
        None => not_shown
            .push("the error budget (trace with --uncertainties FILE, then give its truth EXR)"),
    }

    // The LUT.
    match &lut {
        Some((name, rows)) => {
            let points: Vec<(f64, f64)> = rows
                .iter()
                .map(|r| (r.temperature_k, f64::from(r.dc)))
                .collect();
            let _ = write!(
                w,
                "<section id=\"lut\">\n<h2>LUT: digital count against temperature</h2>\n<p>{}: \
                 {} counts, <span class=\"num\" id=\"lut-first\">{:.4}</span> K at count 0 to \
                 <span class=\"num\" id=\"lut-last\">{:.4}</span> K at count {}.</p>\n<div \
                 class=\"figure\">{}</div>\n</section>\n",
                escape(name),
                rows.len(),
                rows[0].temperature_k,
                rows[rows.len() - 1].temperature_k,
                rows[rows.len() - 1].dc,
                plots::line_chart("LUT curve", &points, "temperature (K)", "digital count")?
            );
        }
        None => not_shown.push("the LUT and the counts it clips (--lut FILE)"),
    }

    if !not_shown.is_empty() {
        let _ = writeln!(
            w,
            "<p class=\"absent\" id=\"not-shown\">Not shown: {}.</p>",
            escape(&not_shown.join("; "))
        );
    }

    // Provenance along the chain.
    provenance_section(w, &recorded, &chain_rows, pipeline.as_ref(), &commands);
    w.push_str("</body>\n</html>\n");

    irsig_cli::write_output(cli.output.path.as_deref(), |out| {
        out.write_all(page.as_bytes())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profile_lines_parse_and_step_along_the_longer_axis() {
        let l: ProfileLine = "0,0:4,2".parse().unwrap();
        assert_eq!(
            l,
            ProfileLine {
                from: (0, 0),
                to: (4, 2)
            }
        );
        let p = l.pixels();
        // Five steps along x; y = 0, 0.5, 1, 1.5, 2 rounded half away from zero.
        let xy: Vec<(usize, usize)> = p.iter().map(|&(x, y, _)| (x, y)).collect();
        assert_eq!(xy, vec![(0, 0), (1, 1), (2, 1), (3, 2), (4, 2)]);
        assert!((p[4].2 - 20f64.sqrt()).abs() < 1e-12);
        assert_eq!("3,3:3,3".parse::<ProfileLine>().unwrap().pixels().len(), 1);
        for bad in ["", "1,2", "1,2:3", "a,1:2,3", "-1,0:2,2"] {
            assert!(bad.parse::<ProfileLine>().is_err(), "{bad}");
        }
    }
}
