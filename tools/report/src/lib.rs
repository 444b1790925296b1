//! `irsig-report`: one self-contained HTML page per run (`formats/report.md`). It reads a
//! run's outputs — the tracer's truth EXR and/or a radiance EXR, and optionally the regions
//! file, the tolerance pilot's decision, the sensor stage's LUT and colour preview and the
//! pipeline file — and writes a page that shows the apparent temperature in false colour with
//! its scale in kelvin, its histogram, a line profile, per-region statistics (the
//! `irsig-stats` table, computed by its library), the decision table, the error budget
//! (`sigma_total`) with its scale, the LUT curve, and provenance: every input's SHA-256, the
//! run's command lines and irsig's version. Images are `data:` URIs and plots inline SVG
//! (drawn by plotters): the page needs no other file and no network.
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

pub mod plots;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use base64::Engine as _;
use clap::Parser;
use irsig_cli::Input;
use irsig_cli::args::{BandArg, ImageBandArgs};
use irsig_model::RegionSet;
use irsig_model::decision::Decision;
use irsig_model::truth::Layer;
use irsig_raster::Raster;
use miette::miette;
use sha2::{Digest, Sha256};

const APPARENT_LAYER: &str = Layer::ApparentTemperature.name();
const MATERIAL_LAYER: &str = Layer::MaterialPrimary.name();
const RADIANCE_LAYER: &str = Layer::Radiance.name();
const SIGMA_LAYER: &str = Layer::SigmaTotal.name();

/// Bins of the histogram of apparent temperature.
const HISTOGRAM_BINS: usize = 64;

/// The PNG signature: the colour preview must start with it.
const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

const EXAMPLE: &str = "\
Examples:
  irsig-report out/truth.exr -o out/report.html
      the colour image, histogram and provenance of the tracer's apparent temperature
  irsig-report out/truth.exr --radiance out/sensor.exr --regions regions.ron \\
      --decision out/frame.decision.ron --lut out/lut.txt --colour-preview out/colour.png \\
      --profile 0,200:511,200 --pipeline pipelines/quickstart.ron -o out/report.html
      everything: the sensor's apparent temperature, statistics per region, the pilot's
      decision, the error budget (when the truth EXR has sigma_total), the LUT curve and
      the run's command lines

What the page holds: formats/report.md.";

/// One self-contained HTML report of a run.
#[derive(Debug, Parser)]
#[command(name = "irsig-report", version, about, after_help = EXAMPLE)]
#[command(group = clap::ArgGroup::new("image").required(true).multiple(true).args(["truth", "radiance"]))]
pub struct Cli {
    /// The tracer's truth EXR: its `apparent_temperature` (K) is shown unless --radiance
    /// is given; its `material_primary` selects the regions; its `sigma_total`, when
    /// present, is the error-budget image.
    pub truth: Option<String>,
    /// Show the apparent temperature of this image's `radiance` layer (W m^-2 sr^-1) in
    /// --band instead (the sensor stage's EXR, say); the same size as the truth EXR.
    #[arg(long, value_name = "FILE")]
    pub radiance: Option<String>,
    /// The band of --radiance, which that image records (irsig-trace and irsig-sensor
    /// write it); --band must be that band unless --override-band.
    #[command(flatten)]
    pub band: ImageBandArgs,
    /// Per-region statistics from this regions file (canonical RON); needs the truth EXR.
    #[arg(long, value_name = "FILE", requires = "truth")]
    pub regions: Option<String>,
    /// The tolerance pilot's decision (`irsig-trace --tolerance`, `*.decision.ron`).
    #[arg(long, value_name = "FILE")]
    pub decision: Option<String>,
    /// The sensor stage's LUT (`irsig-sensor --lut`): its curve, count against kelvin.
    #[arg(long, value_name = "FILE")]
    pub lut: Option<PathBuf>,
    /// The sensor stage's colour preview PNG (`irsig-sensor --colour-preview`), shown as
    /// it is.
    #[arg(long, value_name = "FILE")]
    pub colour_preview: Option<PathBuf>,
    /// A line profile of apparent temperature from pixel (X0, Y0) to (X1, Y1), columns and
    /// rows from the top-left pixel (0, 0).
    #[arg(long, value_name = "X0,Y0:X1,Y1")]
    pub profile: Option<ProfileLine>,
    /// The pipeline file of the run: its stages' command lines are listed (and the file
    /// hashed like every input).
    #[arg(long, value_name = "FILE")]
    pub pipeline: Option<String>,
    /// A command line of the run, listed as given (repeatable, in order).
    #[arg(long, value_name = "TEXT")]
    pub command: Vec<String>,
    /// The page's title (default: the image's file name).
    #[arg(long, value_name = "TEXT")]
    pub title: Option<String>,
    /// Output HTML file (`-` or absent: stdout); written atomically.
    #[arg(short = 'o', long, value_name = "FILE")]
    pub output: Option<PathBuf>,
}

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

/// An input as the provenance lists it.
struct Provenance {
    role: &'static str,
    name: String,
    bytes: usize,
    sha256: String,
}

fn provenance(role: &'static str, input: &Input) -> Provenance {
    Provenance {
        role,
        name: input.name.clone(),
        bytes: input.bytes.len(),
        sha256: format!("{:x}", Sha256::digest(&input.bytes)),
    }
}

fn layer<'a>(image: &'a Raster, name: &str, layer: &str) -> miette::Result<&'a [f32]> {
    image
        .layer(layer)
        .map(|l| l.data.as_slice())
        .ok_or_else(|| {
            let names: Vec<&str> = image.layers.iter().map(|l| l.name.as_str()).collect();
            miette!(
                "{name}: no layer `{layer}` (it has: {}); expected the tracer's truth EXR \
                 (`{APPARENT_LAYER}`, `{MATERIAL_LAYER}`) or, for --radiance, an image with \
                 `{RADIANCE_LAYER}`",
                names.join(", ")
            )
        })
}

fn escape(s: &str) -> String {
    html_escape::encode_text(s).into_owned()
}

fn attribute(s: &str) -> String {
    html_escape::encode_double_quoted_attribute(s).into_owned()
}

/// Displayed images are enlarged by a whole factor (pixels stay square and sharp) to be
/// at least this many CSS pixels tall, like the colour bar beside them.
const DISPLAY_HEIGHT: usize = 360;

/// A PNG as an `<img>` with a `data:` URI, shown enlarged by a whole factor.
fn img(id: &str, png: &[u8], width: usize, height: usize, alt: &str) -> String {
    let scale = DISPLAY_HEIGHT.div_ceil(height.max(1)).max(1);
    format!(
        "<img id=\"{id}\" width=\"{}\" height=\"{}\" alt=\"{}\" \
         src=\"data:image/png;base64,{}\">",
        width * scale,
        height * scale,
        attribute(alt),
        base64::engine::general_purpose::STANDARD.encode(png)
    )
}

/// The values in the inferno map over `range` as an RGB PNG (no finite value: black).
fn false_colour(values: &[f32], width: usize, height: usize, range: (f64, f64)) -> Vec<u8> {
    let rgb: Vec<u8> = values
        .iter()
        .flat_map(|&v| {
            if v.is_finite() {
                plots::inferno((f64::from(v) - range.0) / (range.1 - range.0))
            } else {
                [0, 0, 0]
            }
        })
        .collect();
    let mut png = Vec::new();
    // Writing into memory fails only on a size mismatch, which the caller rules out.
    let _ = irsig_raster::write_png_rgb8(&mut png, width, height, &rgb);
    png
}

/// The smallest and largest finite values (infinite when there is none).
fn extremes(values: &[f32]) -> (f64, f64) {
    values
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(f64::from(v)), hi.max(f64::from(v)))
        })
}

/// Mean of the finite values.
fn finite_mean(values: &[f32]) -> f64 {
    let (sum, n) = values
        .iter()
        .filter(|v| v.is_finite())
        .fold((0.0, 0usize), |(s, n), &v| (s + f64::from(v), n + 1));
    if n == 0 { f64::NAN } else { sum / n as f64 }
}

/// Runs the tool.
///
/// # Errors
/// Unreadable or malformed input (the regions, decision and LUT files with line and
/// column), a missing layer, images of different sizes, a profile outside the image, a
/// region that selects nothing, or an unwritable output; nothing is written then.
pub fn run(cli: Cli) -> miette::Result<()> {
    let band_file = BandArg::response_file(cli.band.band.as_ref()).map(PathBuf::from);
    let named = [
        &cli.truth,
        &cli.radiance,
        &cli.regions,
        &cli.decision,
        &cli.pipeline,
    ]
    .into_iter()
    .flatten()
    .map(PathBuf::from)
    .chain(cli.lut.iter().cloned())
    .chain(cli.colour_preview.iter().cloned())
    .chain(band_file);
    irsig_cli::refuse_output_is_input(named, cli.output.iter())?;
    let mut inputs: Vec<Provenance> = Vec::new();

    let truth = match &cli.truth {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(provenance("truth EXR", &input));
            let image = irsig_cli::read_exr(&input.name, &input.bytes)?;
            Some((input.name, image))
        }
        None => None,
    };
    let radiance = match &cli.radiance {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(provenance("radiance EXR", &input));
            let image = irsig_cli::read_exr(&input.name, &input.bytes)?;
            let recorded = irsig_cli::provenance(&input.name, &image)?;
            let band = cli
                .band
                .resolve(&input.name, recorded.as_ref().map(|p| &p.band))?;
            if let Some(w) = &band.warning {
                irsig_cli::note!("irsig-report: warning: {w}");
            }
            if let Some((name, t)) = &truth
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
            Some((input.name, image, band))
        }
        None => None,
    };

    // The values every section shows: apparent temperature, K. The radiance image is not
    // needed past them: it goes, so that the page is made in the memory of one image.
    let (values, width, height, source): (Vec<f32>, usize, usize, String) = match (radiance, &truth)
    {
        (Some((name, image, band)), _) => {
            let l = layer(&image, &name, RADIANCE_LAYER)?;
            let t = irsig_radiometry::apparent_temperatures(&band.band, l);
            (
                t,
                image.width,
                image.height,
                format!(
                    "apparent temperature of the `{RADIANCE_LAYER}` layer of {name} in {}",
                    band.record
                ),
            )
        }
        (None, Some((name, image))) => (
            layer(image, name, APPARENT_LAYER)?.to_vec(),
            image.width,
            image.height,
            format!("`{APPARENT_LAYER}` layer of {name}"),
        ),
        (None, None) => {
            return Err(irsig_cli::usage_error(
                "expected a truth EXR or --radiance FILE: the report shows an image",
            ));
        }
    };
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

    let stats = match (&cli.regions, &truth) {
        (Some(path), Some((truth_name, image))) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(provenance("regions", &input));
            let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
            let set: RegionSet = irsig_formats::canonical::from_ron(&input.name, text)?;
            let ids = layer(image, truth_name, MATERIAL_LAYER)?;
            Some(irsig_regions::tabulate(&irsig_regions::Inputs {
                regions_name: &input.name,
                regions_text: text,
                set: &set,
                image_name: truth_name,
                material_ids: ids,
                width,
                values: &values,
                source: source.clone(),
                celsius: false,
            })?)
        }
        _ => None,
    };

    let decision = match &cli.decision {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(provenance("decision", &input));
            let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
            let d: Decision = irsig_formats::canonical::from_ron(&input.name, text)?;
            Some(d)
        }
        None => None,
    };

    let lut = match &cli.lut {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(provenance("LUT", &input));
            let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
            Some((
                input.name.clone(),
                irsig_formats::lut::parse(&input.name, text)?,
            ))
        }
        None => None,
    };

    let preview = match &cli.colour_preview {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(provenance("colour preview", &input));
            if !input.bytes.starts_with(PNG_SIGNATURE) {
                return Err(miette::Report::new(irsig_formats::ParseError::in_binary(
                    input.name.clone(),
                    0,
                    "expected a PNG (the sensor stage's --colour-preview), found no PNG \
                     signature",
                )));
            }
            Some(input)
        }
        None => None,
    };

    let commands: Vec<String> = match &cli.pipeline {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(provenance("pipeline", &input));
            let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
            let base = input.base_dir();
            let pipeline = irsig_pipeline::Pipeline::parse(&input.name, text, &base)
                .map_err(miette::Report::new)?;
            let tools = irsig_pipeline::Tools::new(|t| Some(PathBuf::from(format!("irsig-{t}"))));
            let plan = pipeline.plan(&tools).map_err(miette::Report::new)?;
            plan.steps
                .iter()
                .map(irsig_pipeline::Step::command_line)
                .chain(cli.command.iter().cloned())
                .collect()
        }
        None => cli.command.clone(),
    };

    // The truth EXR's other layers are not needed past the statistics: only σ is kept,
    // moved out of the image, not copied.
    let sigma = match truth {
        Some((name, mut image)) => {
            let i = image.layers.iter().position(|l| l.name == SIGMA_LAYER);
            i.map(|i| (name, image.layers.swap_remove(i).data))
        }
        None => None,
    };

    // Everything is read and checked; now the page.
    let title = cli.title.clone().unwrap_or_else(|| {
        let name = cli
            .radiance
            .as_deref()
            .or(cli.truth.as_deref())
            .unwrap_or("run");
        Path::new(name)
            .file_name()
            .map_or_else(|| name.to_owned(), |n| n.to_string_lossy().into_owned())
    });
    let mut page = String::new();
    let w = &mut page;
    let _ = write!(
        w,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>irsig report: {t}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
         <h1>irsig report: {t}</h1>\n",
        t = escape(&title)
    );

    // The colour image and its scale.
    let _ = write!(
        w,
        "<section id=\"image\">\n<h2>Apparent temperature</h2>\n<p>{} ({width} x {height} \
         pixels): minimum <span class=\"num\" id=\"t-min\">{:.3}</span> K, mean <span \
         class=\"num\" id=\"t-mean\">{:.3}</span> K, maximum <span class=\"num\" \
         id=\"t-max\">{:.3}</span> K.</p>\n<div class=\"figure\">{}{}</div>\n",
        escape(&source),
        extremes(&values).0,
        finite_mean(&values),
        extremes(&values).1,
        img(
            "colour",
            &false_colour(&values, width, height, range),
            width,
            height,
            "apparent temperature in the inferno colour map"
        ),
        plots::colour_bar(range, "apparent temperature (K)")?
    );
    if let Some(input) = &preview {
        let _ = write!(
            w,
            "<h3>The sensor stage's colour preview</h3>\n<p>{}</p>\n<div class=\"figure\">\
             <img id=\"colour-preview\" alt=\"the sensor stage's colour preview\" \
             src=\"data:image/png;base64,{}\"></div>\n",
            escape(&input.name),
            base64::engine::general_purpose::STANDARD.encode(&input.bytes)
        );
    }
    w.push_str("</section>\n");

    // Histogram.
    let _ = write!(
        w,
        "<section id=\"histogram\">\n<h2>Histogram of apparent temperature</h2>\n<p>{} \
         bins of {:.4} K.</p>\n<div class=\"figure\">{}</div>\n</section>\n",
        HISTOGRAM_BINS,
        (range.1 - range.0) / HISTOGRAM_BINS as f64,
        plots::histogram(&values, range, HISTOGRAM_BINS)?
    );

    // Line profile.
    w.push_str("<section id=\"profile\">\n<h2>Line profile</h2>\n");
    match &profile {
        Some((line, points)) => {
            let _ = write!(
                w,
                "<p>From pixel ({}, {}) to ({}, {}), {} pixels.</p>\n<div class=\"figure\">{}\
                 </div>\n",
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
        None => w.push_str("<p class=\"absent\">No profile: give --profile X0,Y0:X1,Y1.</p>\n"),
    }
    w.push_str("</section>\n");

    // Per-region statistics.
    w.push_str("<section id=\"regions\">\n<h2>Per-region statistics</h2>\n");
    match &stats {
        Some(table) => stats_table(w, table),
        None => w.push_str(
            "<p class=\"absent\">No regions: give the truth EXR and --regions FILE.</p>\n",
        ),
    }
    w.push_str("</section>\n");

    // The decision.
    w.push_str("<section id=\"decision\">\n<h2>The tolerance pilot's decision</h2>\n");
    match &decision {
        Some(d) => decision_table(w, d),
        None => w.push_str(
            "<p class=\"absent\">No decision: trace with --tolerance K and give --decision \
             FILE.</p>\n",
        ),
    }
    w.push_str("</section>\n");

    // The error budget.
    w.push_str("<section id=\"budget\">\n<h2>Error budget</h2>\n");
    match &sigma {
        Some((name, s)) => match plots::finite_range(s) {
            Some(r) => {
                let _ = write!(
                    w,
                    "<p>The `{SIGMA_LAYER}` layer of {}: σ of apparent temperature from the \
                     declared uncertainties, root-sum-square of its sources, from <span \
                     class=\"num\" id=\"sigma-min\">{:.4}</span> K to <span class=\"num\" \
                     id=\"sigma-max\">{:.4}</span> K.</p>\n<div class=\"figure\">{}{}</div>\n",
                    escape(name),
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
                    "<p class=\"absent\">The `{SIGMA_LAYER}` layer of {} has no finite \
                     value.</p>",
                    escape(name)
                );
            }
        },
        None => w.push_str(
            "<p class=\"absent\">No error budget: trace with --uncertainties FILE and give \
             its truth EXR.</p>\n",
        ),
    }
    w.push_str("</section>\n");

    // The LUT.
    w.push_str("<section id=\"lut\">\n<h2>LUT: digital count against temperature</h2>\n");
    match &lut {
        Some((name, rows)) => {
            let points: Vec<(f64, f64)> = rows
                .iter()
                .map(|r| (r.temperature_k, f64::from(r.dc)))
                .collect();
            let _ = write!(
                w,
                "<p>{}: {} counts, <span class=\"num\" id=\"lut-first\">{:.4}</span> K at \
                 count 0 to <span class=\"num\" id=\"lut-last\">{:.4}</span> K at count {}.\
                 </p>\n<div class=\"figure\">{}</div>\n",
                escape(name),
                rows.len(),
                rows[0].temperature_k,
                rows[rows.len() - 1].temperature_k,
                rows[rows.len() - 1].dc,
                plots::line_chart("LUT curve", &points, "temperature (K)", "digital count")?
            );
        }
        None => w.push_str("<p class=\"absent\">No LUT: give --lut FILE.</p>\n"),
    }
    w.push_str("</section>\n");

    // Provenance.
    let _ = write!(
        w,
        "<section id=\"provenance\">\n<h2>Provenance</h2>\n<p>irsig <span \
         id=\"version\">{}</span>.</p>\n<table id=\"inputs\">\n<thead><tr><th>input</th>\
         <th>file</th><th>bytes</th><th>SHA-256</th></tr></thead>\n<tbody>\n",
        env!("CARGO_PKG_VERSION")
    );
    for p in &inputs {
        let _ = writeln!(
            w,
            "<tr><td>{}</td><td>{}</td><td class=\"num\">{}</td><td><code>{}</code></td></tr>",
            p.role,
            escape(&p.name),
            p.bytes,
            p.sha256
        );
    }
    w.push_str("</tbody>\n</table>\n");
    if commands.is_empty() {
        w.push_str(
            "<p class=\"absent\">No command lines: give --pipeline FILE or --command TEXT.</p>\n",
        );
    } else {
        w.push_str("<h3>Command lines</h3>\n<pre id=\"commands\">");
        for c in &commands {
            let _ = writeln!(w, "{}", escape(c));
        }
        w.push_str("</pre>\n");
    }
    w.push_str("</section>\n</body>\n</html>\n");

    irsig_cli::write_output(cli.output.as_deref(), |out| out.write_all(page.as_bytes()))
}

const STYLE: &str = "body{font-family:sans-serif;margin:2em;max-width:80em}\
table{border-collapse:collapse;margin:0.5em 0}\
td,th{border:1px solid #bbb;padding:0.2em 0.5em}\
td.num,.num{font-variant-numeric:tabular-nums}td.num{text-align:right}\
.figure{display:flex;align-items:flex-start;gap:1em;flex-wrap:wrap}\
img{image-rendering:pixelated}.absent{color:#777}pre{white-space:pre-wrap}";

/// The `irsig-stats` table as HTML, three decimals.
fn stats_table(w: &mut String, table: &irsig_regions::Table) {
    let _ = write!(
        w,
        "<p>Values: {} ({}).</p>\n<table id=\"stats\">\n<thead><tr><th>region</th>\
         <th>pixels</th><th>mean_k</th><th>std_dev_k</th><th>min_k</th><th>max_k</th>",
        escape(&table.values),
        escape(&table.unit)
    );
    for (name, _) in &table.references {
        let n = escape(name);
        let _ = write!(w, "<th>{n}_k</th><th>mean_minus_{n}_k</th>");
    }
    w.push_str("</tr></thead>\n<tbody>\n");
    for row in &table.regions {
        let _ = write!(
            w,
            "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{:.3}</td>\
             <td class=\"num\">{:.3}</td><td class=\"num\">{:.3}</td><td class=\"num\">{:.3}\
             </td>",
            escape(&row.region),
            row.pixels,
            row.mean,
            row.std_dev,
            row.min,
            row.max
        );
        for r in &row.references {
            match r {
                Some(c) => {
                    let _ = write!(
                        w,
                        "<td class=\"num\">{:.3}</td><td class=\"num\">{:+.3}</td>",
                        c.reference, c.difference
                    );
                }
                None => w.push_str("<td>-</td><td>-</td>"),
            }
        }
        w.push_str("</tr>\n");
    }
    w.push_str("</tbody>\n</table>\n");
    for (name, source) in &table.references {
        let _ = writeln!(
            w,
            "<p class=\"source\">{}: {}</p>",
            escape(name),
            escape(source)
        );
    }
}

/// The decision as the tracer prints it: one row per model, then the combination.
fn decision_table(w: &mut String, d: &Decision) {
    let _ = write!(
        w,
        "<p>Tolerance <span class=\"num\" id=\"tolerance\">{}</span> K at the <span \
         class=\"num\" id=\"percentile\">{}</span>th percentile of the pilot's <span \
         class=\"num\" id=\"pilot-pixels\">{}</span> pixels.</p>\n<table id=\"decision-table\">\
         \n<thead><tr><th>model</th><th>choice</th><th>reference</th><th>pinned</th>\
         <th>error_percentile_k</th><th>error_max_k</th><th>relative_cost</th><th>why</th>\
         </tr></thead>\n<tbody>\n",
        d.tolerance_k, d.percentile, d.pilot_pixels
    );
    for c in &d.choices {
        let _ = writeln!(
            w,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{:.3}</td>\
             <td class=\"num\">{:.3}</td><td class=\"num\">{:.3}</td><td>{}</td></tr>",
            c.model,
            escape(&c.setting),
            escape(&c.reference),
            if c.pinned { "yes" } else { "no" },
            c.error.percentile_k,
            c.error.max_k,
            c.relative_cost,
            escape(&c.reason)
        );
    }
    let _ = writeln!(
        w,
        "<tr class=\"total\"><td>predicted</td><td></td><td></td><td></td><td class=\"num\">\
         {:.3}</td><td class=\"num\">{:.3}</td><td class=\"num\">{:.3}</td><td>the chosen \
         combination's error bound and cost</td></tr>\n</tbody>\n</table>",
        d.predicted.percentile_k, d.predicted.max_k, d.relative_cost
    );
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
