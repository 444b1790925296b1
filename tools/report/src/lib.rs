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
mod page;
mod read;
mod sections;

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
    // Everything is read and checked; then the page.
    let run = read::read(&cli)?;
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
    let page = page::page(&title, &run)?;
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
