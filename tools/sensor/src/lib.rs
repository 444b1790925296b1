//! `irsig-sensor`: what a thermal imager makes of the radiance field the tracer computed
//! (thesis §3.4, §4.2, §5.2).
//!
//! Reads the tracer's multi-layer EXR (path or `-`), blurs its `radiance` layer
//! (W m⁻² sr⁻¹) by the cascaded MTF given with `--mtf` (by FFT, edges by `--edge`),
//! reduces it from the render grid to the sensor grid when the input was rendered at
//! `--samples-per-pixel` k > 1, adds NEΔT noise when asked, and writes the same EXR with
//! the sensor's radiance (truth layers pass through, or are reduced consistently when the
//! resolution changes). On request it also writes the apparent-temperature EXR, the
//! digital-count PNG and its LUT, a grey preview and a colour preview with a kelvin colour
//! bar. All outputs appear together or not at all. File forms: `formats/sensor.md`.
//!
//! ```no_run
//! use clap::Parser;
//! let cli = irsig_sensor::Cli::parse_from([
//!     "irsig-sensor", "radiance.exr", "-o", "sensor.exr", "--mtf", "box:5x5",
//!     "--dc-per-kelvin", "4", "--dc-png", "dc.png", "--lut", "dc.lut",
//! ]);
//! irsig_sensor::run(cli)?;
//! # Ok::<(), miette::Report>(())
//! ```

// A closed stderr must not panic the tool: notes go through `irsig_cli::note!`.
#![warn(clippy::print_stderr)]

pub mod animation;
pub mod contact_sheet;
mod preview;
pub mod spec;

use std::path::PathBuf;

use clap::{Parser, ValueEnum};
use irsig_cli::args::outputs::{ColourPreview, DcPng, Lut, Output};
use irsig_cli::args::{DcArgs, ImageBandArgs, ResolvedBand, Seed, ThreadsArgs};
use irsig_model::limits::MEMORY_BUDGET_BYTES;
use irsig_model::provenance::{InputRecord, Provenance};
use irsig_model::truth::Layer;
use irsig_radiometry::{AnyBand, BandModel};
use irsig_raster::{Raster, counts_png, into_exr_bytes};
use irsig_sensor_model::blur::{EdgeMode, blur};
use irsig_sensor_model::mtf::{Mtf, MtfChain};
use irsig_sensor_model::noise::{add_gaussian_noise, nedt_radiance_sigma};
use irsig_sensor_model::quantise::{Calibration, Quantiser};
use irsig_sensor_model::sample::{reduce_majority, reduce_mean, reduce_mean_ignoring_nan};
use irsig_sensor_model::{Plane, SensorError};
use miette::{IntoDiagnostic, WrapErr, miette};

/// The name of the layer the sensor acts on.
const RADIANCE_LAYER: &str = Layer::Radiance.name();

/// Command line of `irsig-sensor`.
#[derive(Debug, Parser)]
#[command(group = clap::ArgGroup::new("sequence").args(["contact_sheet", "animation"]))]
#[command(
    name = "irsig-sensor",
    version,
    about = "Blur, sample, add noise to and quantise a radiance EXR as a thermal imager would",
    after_help = "Example:\n  irsig-sensor --contact-sheet sheet.png --sheet-columns 8 f01.dc.png f02.dc.png ...\n\n  irsig-sensor --animation day.gif --frame-delay-ms 250 h00.dc.png h01.dc.png ...\n\n  irsig-sensor radiance.exr -o sensor.exr --mtf box:5x5 \\\n    --mtf diffraction:lambda-um=10,f=2,pitch-um=25 --nedt-k 0.05 --seed 1 \\\n    --dc-per-kelvin 4 --dc-png dc.png --lut dc.lut --colour-preview preview.png\n\n  irsig-trace … | irsig-sensor - --mtf gauss:hp=0.25 -o - > sensor.exr\n\nMTF forms (cycles and lengths per sensor pixel): box:5x5 | gauss:sigma=0.8 | \
gauss:hp=0.25 | ss:across=0.3,along=0.2 | diffraction:lambda-um=10,f=2,pitch-um=25 | \
footprint:1x1 | motion:len=3,angle=30 | jitter:0.3 | jitter:x=0.3,y=0.5",
    mut_arg("output", |a| a.help("The output EXR (`-` or absent: stdout)")),
    mut_arg("seed", |a| a.help("Seed of the noise: the same seed gives the same noise, bit for bit")),
)]
pub struct Cli {
    /// The tracer's radiance EXR (with a `radiance` layer in W m^-2 sr^-1), or `-`.
    #[arg(default_value = "-")]
    pub input: String,

    /// Further input images, for --contact-sheet or --animation only.
    #[arg(value_name = "MORE", requires = "sequence")]
    pub more_inputs: Vec<String>,

    /// Contact-sheet mode: put every input image (PNG, or EXR whose `radiance` layer is
    /// stretched over all EXR inputs) side by side, labelled 1, 2, ..., in one 8-bit grey
    /// PNG written to this file; nothing else is done or written.
    #[arg(long, value_name = "PNG", conflicts_with_all = [
        "output", "mtf", "dc_png", "lut", "temperature_exr", "preview", "colour_preview",
        "nedt_k",
    ])]
    pub contact_sheet: Option<PathBuf>,

    /// Tiles per row of the contact sheet (default: a near-square sheet).
    #[arg(long, value_name = "N", requires = "contact_sheet",
          value_parser = clap::value_parser!(u32).range(1..))]
    pub sheet_columns: Option<u32>,

    /// Animation mode: every input PNG (one size, in the order given) as a frame of one
    /// animated GIF written to this file, looping forever; nothing else is done or written.
    /// Frames of at most 256 colours (any 8-bit grey PNG) are kept exactly, others are
    /// reduced to 256 colours.
    #[arg(long, value_name = "GIF", conflicts_with_all = [
        "output", "mtf", "dc_png", "lut", "temperature_exr", "preview", "colour_preview",
        "nedt_k", "contact_sheet",
    ])]
    pub animation: Option<PathBuf>,

    /// How long each frame of the animation is shown, milliseconds (GIF holds hundredths
    /// of a second: 10 to 655350 in steps of 10).
    #[arg(long, value_name = "MS", default_value_t = 500, requires = "animation",
          value_parser = animation::parse_delay_ms)]
    pub frame_delay_ms: u32,

    /// `-o PATH`: the output EXR.
    #[command(flatten)]
    pub output: Output,

    /// One MTF component; repeat to cascade them (their product, eq. 12).
    #[arg(long = "mtf", value_name = "KIND:PARAMS", value_parser = spec::parse_mtf)]
    pub mtf: Vec<Mtf>,

    /// How the image continues beyond its edges for the blur.
    #[arg(long, value_enum, default_value_t = Edge::Reflect)]
    pub edge: Edge,

    /// The input was rendered at this many samples per sensor pixel in each direction;
    /// after the blur each k x k block is averaged into one detector.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub samples_per_pixel: u32,

    /// Layers to reduce by majority rather than by mean when k > 1 (in addition to
    /// `material*`, `event`, `interaction*` and `*_id`).
    #[arg(long = "categorical", value_name = "LAYER")]
    pub categorical: Vec<String>,

    /// The band of the radiance, which the input records (irsig-trace writes it); --band
    /// must be that band unless --override-band.
    #[command(flatten)]
    pub band: ImageBandArgs,

    /// Noise-equivalent temperature difference, kelvin: adds Gaussian noise of
    /// σ = NEdT·dL/dT(reference) to the radiance.
    #[arg(long)]
    pub nedt_k: Option<f64>,

    /// The temperature the NEdT is quoted at, kelvin.
    #[arg(long, default_value_t = 300.0)]
    pub nedt_reference_k: f64,

    /// `--seed`: of the noise.
    #[command(flatten)]
    pub seed: Seed,

    /// How radiance becomes digital counts (--dc-png and --lut need a gain).
    #[command(flatten)]
    pub dc: DcArgs,

    /// `--dc-png FILE`.
    #[command(flatten)]
    pub dc_png: DcPng,

    /// `--lut FILE`.
    #[command(flatten)]
    pub lut: Lut,

    /// Write the apparent (blackbody) temperature of the sensor's radiance, K, as an EXR.
    #[arg(long)]
    pub temperature_exr: Option<PathBuf>,

    /// Write a grey preview PNG: apparent temperature stretched over --preview-range (by
    /// default from its minimum, black, to its maximum, white).
    #[arg(long)]
    pub preview: Option<PathBuf>,

    /// Bits of the grey preview.
    #[arg(long, value_enum, default_value_t = PreviewBits::Eight)]
    pub preview_bits: PreviewBits,

    /// The temperatures the previews (--preview, --colour-preview) span: MIN-MAX in kelvin
    /// (280-320), percentiles of the image's pLO-pHI (p1-p99: a glint or a hot spot no
    /// longer darkens the rest), or `full`, the coldest to the hottest pixel. Pixels
    /// outside are clipped to its ends
    #[arg(long, value_name = "RANGE", default_value = "full")]
    pub preview_range: preview::PreviewRange,

    /// `--colour-preview FILE`.
    #[command(flatten)]
    pub colour_preview: ColourPreview,

    /// `--threads N`: worker threads (the blur, the EXR's compression).
    #[command(flatten)]
    pub threads: ThreadsArgs,
}

/// The flags' own rules are clap's and the run's: nothing more is checked before a file
/// is read.
impl irsig_cli::CheckArgs for Cli {}

/// `--preview-bits`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PreviewBits {
    /// 8-bit grey.
    #[value(name = "8")]
    Eight,
    /// 16-bit grey.
    #[value(name = "16")]
    Sixteen,
}

/// `--edge`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Edge {
    /// Mirror about the edge (… c b a | a b c …).
    Reflect,
    /// Zero radiance beyond the edge.
    Zero,
    /// Periodic.
    Wrap,
}

impl From<Edge> for EdgeMode {
    fn from(e: Edge) -> Self {
        match e {
            Edge::Reflect => Self::Reflect,
            Edge::Zero => Self::Zero,
            Edge::Wrap => Self::Wrap,
        }
    }
}

/// Whether a layer holds labels (reduced by majority) rather than quantities: the tracer's
/// label layers (`irsig_model::truth::Layer::is_label`) and any named in `extra`.
#[must_use]
pub fn is_categorical(name: &str, extra: &[String]) -> bool {
    Layer::from_name(name).is_some_and(Layer::is_label) || extra.iter().any(|e| e == name)
}

/// What the sensor made of one input.
#[derive(Debug, Clone)]
pub struct SensorOutput {
    /// The input's layers with `radiance` replaced by the sensor's, at the sensor grid.
    pub raster: Raster,
}

impl SensorOutput {
    /// The sensor's radiance, W m^-2 sr^-1 (the raster's `radiance` layer).
    #[must_use]
    pub fn radiance(&self) -> &[f32] {
        self.raster
            .layer(RADIANCE_LAYER)
            .map_or(&[][..], |l| l.data.as_slice())
    }
}

/// Everything `process` needs besides the image.
#[derive(Debug, Clone)]
pub struct Settings {
    /// The MTF cascade.
    pub chain: MtfChain,
    /// Edge handling.
    pub edge: EdgeMode,
    /// Render samples per sensor pixel.
    pub samples_per_pixel: u32,
    /// Extra categorical layer names.
    pub categorical: Vec<String>,
    /// NEdT in K and its reference temperature, if noise is wanted.
    pub nedt: Option<(f64, f64)>,
    /// Noise seed.
    pub seed: u64,
}

/// Blur, reduce and add noise: the sensor's radiance and the consistent truth layers.
///
/// The input is consumed, so that every image is freed as soon as the next is made: the
/// radiance layer once it is in f64, that once it is blurred, and each other layer moved
/// into the output, not copied (at most 28 bytes per pixel besides the other layers;
/// README, "budget").
///
/// # Errors
/// A missing `radiance` layer, a non-finite radiance, a size that does not divide by k,
/// or invalid settings.
pub fn process(
    mut input: Raster,
    settings: &Settings,
    band: &impl BandModel,
) -> miette::Result<SensorOutput> {
    let Some(at) = input.layers.iter().position(|l| l.name == RADIANCE_LAYER) else {
        let names: Vec<&str> = input.layers.iter().map(|l| l.name.as_str()).collect();
        return Err(miette!(
            "no `{RADIANCE_LAYER}` layer (W m^-2 sr^-1) in the input; it has: {}",
            names.join(", ")
        ));
    };
    let k = settings.samples_per_pixel as usize;
    let (width, height) = (input.width, input.height);
    let plane = {
        let radiance = std::mem::take(&mut input.layers[at].data);
        Plane::from_f32(width, height, &radiance).map_err(sensor)?
    };
    plane
        .check_finite()
        .map_err(|e| miette!("layer `{RADIANCE_LAYER}`: {e}"))?;
    let blurred = blur(
        &plane,
        &settings.chain,
        settings.edge,
        settings.samples_per_pixel,
    )
    .map_err(sensor)?;
    drop(plane);
    let mut sensor_plane = if k == 1 {
        blurred
    } else {
        reduce_mean(&blurred, k).map_err(sensor)?
    };
    if let Some((nedt_k, reference_k)) = settings.nedt {
        let sigma = nedt_radiance_sigma(nedt_k, reference_k, band).map_err(sensor)?;
        add_gaussian_noise(&mut sensor_plane, sigma, settings.seed).map_err(sensor)?;
    }
    let mut raster = Raster::new(sensor_plane.width, sensor_plane.height);
    let mut radiance = Some(sensor_plane.to_f32());
    drop(sensor_plane);
    for l in std::mem::take(&mut input.layers) {
        let data = if l.name == RADIANCE_LAYER {
            radiance.take().unwrap_or_default()
        } else if k == 1 {
            l.data
        } else if is_categorical(&l.name, &settings.categorical) {
            reduce_majority(&l.data, width, height, k).map_err(sensor)?
        } else {
            reduce_mean_ignoring_nan(&l.data, width, height, k).map_err(sensor)?
        };
        raster.push_layer(l.name, l.unit, data).into_diagnostic()?;
    }
    Ok(SensorOutput { raster })
}

/// The most bytes `process` holds for an image of `width` × `height` pixels and `layers`
/// layers: 4 per pixel for each layer but the radiance, 8 for the radiance in f64 and 16 per
/// pixel of the image the blur transforms (a complex half spectrum, and its transpose while
/// it is made), which is the image widened on each side by the MTF chain's reach (at most
/// twice the image, as `irsig_sensor_model::blur` pads it) and rounded up to a length with
/// no prime factor above 5 (at most 1.11 times longer from 64 up). Decoding the input
/// costs 8 bytes per pixel per layer for a moment, before this.
#[must_use]
pub fn peak_bytes(
    width: usize,
    height: usize,
    layers: usize,
    chain: &MtfChain,
    edge: EdgeMode,
    samples_per_pixel: u32,
) -> u64 {
    let (w, h) = (width as f64, height as f64);
    let padded = if chain.components.is_empty() {
        0.0
    } else {
        let (rx, ry) = chain.support_radius_px(samples_per_pixel);
        let s = f64::from(samples_per_pixel.max(1));
        let side = |n: f64, r: f64| -> f64 {
            let margin = match edge {
                EdgeMode::Wrap => 0.0,
                _ => (r * s).ceil().min(2.0 * n),
            };
            ((n + 2.0 * margin) * 1.11).ceil() + 64.0
        };
        side(w, rx) * side(h, ry)
    };
    let pixels = w * h;
    let bytes = 4.0 * pixels * layers.saturating_sub(1) as f64 + 8.0 * pixels + 16.0 * padded;
    if bytes.is_finite() && bytes < u64::MAX as f64 {
        bytes as u64
    } else {
        u64::MAX
    }
}

fn sensor(e: SensorError) -> miette::Report {
    miette!("{e}")
}

/// Runs the tool.
///
/// # Errors
/// Bad input (named), bad usage (exit 2), or an output that cannot be written.
pub fn run(cli: Cli) -> miette::Result<()> {
    cli.threads.install(|| sense(&cli))
}

/// Every input of a contact sheet or an animation, `(name, bytes)`, in the order given.
fn read_all(cli: &Cli) -> miette::Result<Vec<(String, Vec<u8>)>> {
    std::iter::once(&cli.input)
        .chain(&cli.more_inputs)
        .map(|name| irsig_cli::read_input(name).map(|input| (input.name, input.bytes)))
        .collect()
}

/// The tool's work: a contact sheet, an animation, or the sensed image and the files made
/// from it.
fn sense(cli: &Cli) -> miette::Result<()> {
    refuse_outputs_over_inputs(cli)?;
    if let Some(sheet) = &cli.contact_sheet {
        let inputs = read_all(cli)?;
        let png = contact_sheet::build(&inputs, cli.sheet_columns.map(|c| c as usize))?;
        return irsig_cli::write_files_atomic(&[(sheet.clone(), png)]);
    }
    if let Some(gif) = &cli.animation {
        let inputs = read_all(cli)?;
        let bytes = animation::build(&inputs, cli.frame_delay_ms)?;
        return irsig_cli::write_files_atomic(&[(gif.clone(), bytes)]);
    }
    let wants_counts = cli.dc_png.path.is_some() || cli.lut.path.is_some();
    let calibration = cli.dc.calibration(None);
    if wants_counts && calibration.is_none() {
        return Err(irsig_cli::usage_error(
            "--dc-png and --lut need a calibration: --dc-per-kelvin (auto-bias), \
             --dc-per-kelvin with --reference-k (fixed), or --gain-dc-per-radiance",
        ));
    }
    let input = irsig_cli::read_input(&cli.input)?;
    let raster = irsig_cli::read_exr(&input.name, &input.bytes)?;
    let name = input.name.clone();
    let (provenance, resolved) = provenance_and_band(cli, &input, &raster)?;
    let comments = Some(
        irsig_formats::canonical::provenance_comments(&provenance).map_err(|e| miette!("{e}"))?,
    );
    let band = resolved.band;
    require_radiance(&input, &raster)?;
    // The file's bytes are not needed past the decoding.
    drop(input);
    let settings = settings_within_budget(cli, &name, &raster)?;
    let out = process(raster, &settings, &band).wrap_err_with(|| format!("`{name}`"))?;
    let (w, h) = (out.raster.width, out.raster.height);

    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let temperature = if cli.temperature_exr.is_some()
        || cli.preview.is_some()
        || cli.colour_preview.path.is_some()
    {
        Some(irsig_radiometry::apparent_temperatures(
            &band,
            out.radiance(),
        ))
    } else {
        None
    };
    if let (Some(path), Some(t)) = (&cli.temperature_exr, &temperature) {
        let mut r = Raster::new(w, h).with_comments(comments.clone());
        let layer = Layer::ApparentTemperature;
        r.push_layer(layer.name(), layer.unit(), t.clone())
            .into_diagnostic()?;
        files.push((path.clone(), into_exr_bytes(r).into_diagnostic()?));
    }
    if let Some(cal) = calibration.filter(|_| wants_counts) {
        push_count_files(cli, &cal, &out, &band, &provenance, &mut files)?;
    }
    if let (Some(path), Some(t)) = (&cli.preview, &temperature) {
        let r = cli.preview_range.of(t);
        files.push((path.clone(), preview::grey(t, w, h, cli.preview_bits, r)?));
    }
    if let (Some(path), Some(t)) = (&cli.colour_preview.path, &temperature) {
        let r = cli.preview_range.of(t);
        files.push((path.clone(), preview::colour_with_bar(t, w, h, r)?));
    }
    // The sensed image's layers go into the encoder, not a copy of them.
    let exr = into_exr_bytes(out.raster.with_comments(comments)).into_diagnostic()?;
    match &cli.output.path {
        Some(p) if p.as_os_str() != "-" => {
            files.push((p.clone(), exr));
            irsig_cli::write_files_atomic(&files)
        }
        _ => {
            irsig_cli::write_files_atomic(&files)?;
            irsig_cli::write_output(None, |w| w.write_all(&exr))
        }
    }
}

/// Refuses an output path that is also one of the inputs (the band's response file among
/// them).
fn refuse_outputs_over_inputs(cli: &Cli) -> miette::Result<()> {
    let band_file = cli.band.band.response_file();
    let inputs = std::iter::once(cli.input.as_str())
        .chain(cli.more_inputs.iter().map(String::as_str))
        .chain(band_file);
    let outputs = [
        &cli.output.path,
        &cli.contact_sheet,
        &cli.animation,
        &cli.dc_png.path,
        &cli.lut.path,
        &cli.temperature_exr,
        &cli.preview,
        &cli.colour_preview.path,
    ];
    irsig_cli::refuse_output_is_input(inputs, outputs.into_iter().flatten())
}

/// The provenance the outputs record (the input's, else one of the band alone, with this
/// stage added) and the band the radiance is in.
fn provenance_and_band(
    cli: &Cli,
    input: &irsig_cli::Input,
    raster: &Raster,
) -> miette::Result<(Provenance, ResolvedBand)> {
    // The band is the one the radiance records; what the outputs record adds this stage.
    let recorded = irsig_cli::provenance(&input.name, raster)?;
    let resolved = cli.band.resolve_saying(
        "irsig-sensor",
        &input.name,
        recorded.as_ref().map(|p| &p.band),
    )?;
    let mut provenance = recorded.unwrap_or_else(|| Provenance {
        band: resolved.record.clone(),
        sub_bands: "not recorded".into(),
        atmosphere: "not recorded".into(),
        atmosphere_model: "not recorded".into(),
        inputs: Vec::new(),
        sun: None,
    });
    provenance.band = resolved.record.clone();
    provenance.inputs.push(InputRecord {
        stage: "sensor".into(),
        role: "radiance EXR".into(),
        sha256: input.sha256(),
    });
    Ok((provenance, resolved))
}

/// Refuses an input without a `radiance` layer, naming the layers it has and where in the
/// file they are listed.
fn require_radiance(input: &irsig_cli::Input, raster: &Raster) -> miette::Result<()> {
    if raster.layer(RADIANCE_LAYER).is_none() {
        let names: Vec<&str> = raster.layers.iter().map(|l| l.name.as_str()).collect();
        return Err(miette::Report::new(irsig_formats::ParseError::in_binary(
            input.name.clone(),
            irsig_raster::exr_attribute_offset(&input.bytes, "channels").unwrap_or(8),
            format!(
                "no `{RADIANCE_LAYER}` layer (W m^-2 sr^-1) in the input; it has: {}",
                names.join(", ")
            ),
        )));
    }
    Ok(())
}

/// The settings the command line asks for, refused (a usage error) when blurring `name`'s
/// `raster` with them would hold more than the memory budget.
fn settings_within_budget(cli: &Cli, name: &str, raster: &Raster) -> miette::Result<Settings> {
    let chain = MtfChain::new(cli.mtf.clone());
    let edge: EdgeMode = cli.edge.into();
    let peak = peak_bytes(
        raster.width,
        raster.height,
        raster.layers.len(),
        &chain,
        edge,
        cli.samples_per_pixel,
    );
    if peak > MEMORY_BUDGET_BYTES {
        return Err(irsig_cli::usage_error(format!(
            "{name}: blurring its {} x {} pixels with this MTF would hold {:.1} GiB, more \
             than the {} GiB budget: the MTF reaches too far for an image this large",
            raster.width,
            raster.height,
            peak as f64 / f64::from(1u32 << 30),
            MEMORY_BUDGET_BYTES >> 30
        )));
    }
    Ok(Settings {
        chain,
        edge,
        samples_per_pixel: cli.samples_per_pixel,
        categorical: cli.categorical.clone(),
        nedt: cli.nedt_k.map(|n| (n, cli.nedt_reference_k)),
        seed: cli.seed.value,
    })
}

/// Adds the digital-count PNG and the LUT asked for to `files`, the counts calibrated by
/// `cal` over the sensed radiance; notes the pixels whose counts saturate.
fn push_count_files(
    cli: &Cli,
    cal: &Calibration,
    out: &SensorOutput,
    band: &AnyBand,
    provenance: &Provenance,
    files: &mut Vec<(PathBuf, Vec<u8>)>,
) -> miette::Result<()> {
    let (w, h) = (out.raster.width, out.raster.height);
    let bits = cli.dc.dc_bits;
    let q = Quantiser::calibrate(bits, cal, out.radiance(), band)
        .map_err(|e| miette!("quantisation: {e}"))?;
    if let Some(path) = &cli.dc_png.path {
        let counts = q.quantise(out.radiance(), w).map_err(sensor)?;
        let full = (1u32 << bits) - 1;
        let low = counts.iter().filter(|&&c| u32::from(c) == 0).count();
        let high = counts.iter().filter(|&&c| u32::from(c) == full).count();
        if low + high > 0 {
            irsig_cli::note!(
                "irsig-sensor: {high} pixel(s) saturate at count {full} and {low} at count 0 \
                 of {} ({}): their temperatures are clipped",
                counts.len(),
                lut_span_text(&q.lut(band))
            );
        }
        files.push((
            path.clone(),
            counts_png(&counts, w, h, bits).into_diagnostic()?,
        ));
    }
    if let Some(path) = &cli.lut.path {
        let text = q.lut(band).text_in_band(&provenance.band.to_string());
        files.push((path.clone(), text.into_bytes()));
    }
    Ok(())
}

/// What a look-up table spans, for a note: its temperatures from the first count of
/// positive radiance, and the counts below that, which have none.
fn lut_span_text(lut: &irsig_sensor_model::quantise::Lut) -> String {
    match lut.temperature_span() {
        None => "no count of the LUT has a positive radiance".to_owned(),
        Some(span) if span.counts_without_temperature == 0 => {
            format!("the LUT spans {:.2}-{:.2} K", span.lowest_k, span.highest_k)
        }
        Some(span) => format!(
            "the LUT spans {:.2}-{:.2} K; counts 0-{} stand for zero or negative radiance, \
             no temperature",
            span.lowest_k,
            span.highest_k,
            span.counts_without_temperature - 1
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_radiometry::Band;

    #[test]
    fn the_suns_layers_are_sampled_by_mean_and_labels_by_majority() {
        // A 2 × 2 render pixel block into one sensor pixel, no blur: the sun's quantities
        // are the mean of the four (a sky pixel's NaN left out), the material the majority.
        let mut input = Raster::new(2, 2);
        let push = |r: &mut Raster, layer: Layer, data: Vec<f32>| {
            r.push_layer(layer.name(), layer.unit(), data).unwrap();
        };
        push(&mut input, Layer::Radiance, vec![5.0; 4]);
        push(&mut input, Layer::MaterialPrimary, vec![2.0, 2.0, 7.0, 2.0]);
        push(
            &mut input,
            Layer::SolarIrradiance,
            vec![100.0, 200.0, 300.0, f32::NAN],
        );
        push(
            &mut input,
            Layer::SunVisibleFraction,
            vec![1.0, 0.0, 0.5, f32::NAN],
        );
        push(&mut input, Layer::SunShare, vec![0.1, 0.2, 0.3, 0.0]);
        let settings = Settings {
            chain: MtfChain::new(Vec::new()),
            edge: EdgeMode::Reflect,
            samples_per_pixel: 2,
            categorical: Vec::new(),
            nedt: None,
            seed: 0,
        };
        let out = process(input, &settings, &Band::new(8.0, 14.0).unwrap()).unwrap();
        let at = |layer: Layer| out.raster.layer(layer.name()).unwrap().data[0];
        assert_eq!(at(Layer::MaterialPrimary).to_bits(), 2.0f32.to_bits());
        assert!((at(Layer::SolarIrradiance) - 200.0).abs() < 1e-4);
        assert!((at(Layer::SunVisibleFraction) - 0.5).abs() < 1e-6);
        assert!((at(Layer::SunShare) - 0.15).abs() < 1e-6);
        assert!(Layer::SUN.iter().all(|l| !is_categorical(l.name(), &[])));
    }
}
