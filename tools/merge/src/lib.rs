//! `irsig-merge`: the tiles of a frame traced in parts (`irsig-trace --tile`) back into the
//! frame's files: the radiance EXR, the truth EXR, the 1990 interaction map, and the
//! digital-count image with its LUT — byte for byte what `irsig-trace` writes when it
//! traces the frame whole.
//!
//! Every tile's EXR says which frame it is part of and which run made it
//! (`irsig_raster::FramePart`, formats/images.md). The tiles are checked from their headers
//! before a pixel is decoded (`irsig_raster::merge::Layout`): one run, one frame size, the
//! same layers, no pixel in two tiles and none in no tile; anything else is an error that
//! names the files, and nothing is written. The map and the counts depend on the whole
//! frame (the counts' auto-bias reads its radiance range), so they are made here, from
//! the merged layers, by the code irsig-trace uses (`irsig_formats::legacy::map`,
//! `irsig_cli::args::DcArgs::tracer_quantiser`).
//!
//! ```text
//! irsig-merge tiles/t*.exr -o out/frame
//! # -> out/frame.radiance.exr, out/frame.truth.exr, out/frame.map.png, out/frame.dc.png,
//! #    out/frame.lut.txt
//! irsig-merge tiles/t*.radiance.exr --radiance-exr frame.exr --dc-png frame.png \
//!     --view view.ron --band 8-14
//! ```

use std::path::PathBuf;

use clap::Parser;
use irsig_cli::args::{DcArgs, TraceBand};
use irsig_formats::legacy::decode;
use irsig_formats::views::parse_views;
use irsig_model::LengthUnit;
use irsig_model::truth::Layer;
use irsig_radiometry::{BandModel, TotalRadiance};
use irsig_raster::merge::Layout;
use irsig_raster::{Raster, RasterInfo, counts_png, into_exr_bytes};
use miette::{IntoDiagnostic, miette};

const EXAMPLE: &str = "\
Examples:
  irsig-merge tiles/t*.exr -o out/frame
      the tiles' radiance and truth EXRs (any order) -> out/frame.radiance.exr,
      out/frame.truth.exr, out/frame.map.png, out/frame.dc.png, out/frame.lut.txt
  irsig-merge tiles/t*.radiance.exr --radiance-exr frame.exr --dc-png frame.png \\
      --lut frame.lut --view view.ron --band 8-14
      only these outputs, as a pipeline stage does; the counts as irsig-trace makes
      them for that view and band

The tiles come from irsig-trace --tile (X,Y,W,H or I/CxR) of one frame and one run: the
same scene, materials, view, band, atmosphere and options. Give irsig-merge the --band,
--view and digital-count flags the traces had: the counts and the LUT are made here.";

/// Merge the tiles of a frame into its radiance EXR, truth EXR, map, counts and LUT.
#[derive(Debug, Parser)]
#[command(name = "irsig-merge", version, about, after_help = EXAMPLE)]
pub struct Cli {
    /// The tiles: radiance and truth EXRs written by `irsig-trace --tile`, in any order
    /// (told apart by their layers). Files, not `-`.
    #[arg(required = true, value_name = "TILE")]
    pub tiles: Vec<String>,
    /// Output path prefix: PREFIX.radiance.exr, PREFIX.dc.png and PREFIX.lut.txt from
    /// radiance tiles, PREFIX.truth.exr and PREFIX.map.png from truth tiles, as
    /// `irsig-trace -o PREFIX` names them.
    #[arg(short = 'o', long, value_name = "PREFIX")]
    pub output: Option<PathBuf>,
    /// Write the frame's radiance image (f32 EXR) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub radiance_exr: Option<PathBuf>,
    /// Write the frame's truth layers (multi-layer f32 EXR) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub truth_exr: Option<PathBuf>,
    /// Write the legacy interaction map (8-bit nibble PNG) to FILE, from the truth tiles'
    /// material layers; an error when an id does not fit in four bits.
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub map_png: Option<PathBuf>,
    /// Write the digital-count image (PNG, --dc-bits deep) to FILE, from the radiance.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["output", "no_dc"])]
    pub dc_png: Option<PathBuf>,
    /// Write the digital-count LUT (text: DC, radiance, K, degC) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["output", "no_dc"])]
    pub lut: Option<PathBuf>,
    /// With -o, write no DC image or LUT.
    #[arg(long)]
    pub no_dc: bool,
    /// The view the tiles were traced with: its DC/K is the counts' gain when no
    /// --dc-per-kelvin is given (as in irsig-trace). A canonical RON view or a 1990 viewing
    /// file, holding one view.
    #[arg(long, value_name = "FILE")]
    pub view: Option<String>,
    /// Length unit of the position in a 1990 viewing file.
    #[arg(long, default_value = "km", value_name = "UNIT", value_parser = parse_unit)]
    pub view_unit: LengthUnit,
    /// The band the tiles were traced in: `MIN-MAX` in micrometres, a sensor response
    /// file, or `total`. The counts' calibration and the LUT's temperatures use it.
    #[arg(long, default_value = "8-14", value_name = "MIN-MAX|FILE|total")]
    pub band: TraceBand,
    /// How radiance becomes digital counts, as for irsig-trace: without a gain, the view's
    /// DC/K, else 2 counts per kelvin (the thesis's auto-bias).
    #[command(flatten)]
    pub dc: DcArgs,
}

fn parse_unit(s: &str) -> Result<LengthUnit, String> {
    s.parse()
}

/// One tile file: its name and header.
struct Tile {
    name: String,
    info: RasterInfo,
}

/// The tiles of each kind the tracer writes.
#[derive(Default)]
struct Tiles {
    radiance: Vec<Tile>,
    truth: Vec<Tile>,
}

/// What a tile's layers say it is.
fn kind_of(info: &RasterInfo) -> Option<bool> {
    let names: Vec<&str> = info.layers.iter().map(|(n, _)| n.as_str()).collect();
    if names == [Layer::Radiance.name()] {
        Some(false)
    } else if names == Layer::TRUTH.map(Layer::name) {
        Some(true)
    } else {
        None
    }
}

/// Reads every tile's header and sorts the tiles into radiance and truth.
fn read_tiles(names: &[String]) -> miette::Result<Tiles> {
    let mut tiles = Tiles::default();
    for name in names {
        if name == "-" {
            return Err(irsig_cli::usage_error(
                "tiles are read twice (headers, then pixels): give files, not `-`",
            ));
        }
        let input = irsig_cli::read_input(name)?;
        let info = irsig_cli::read_exr_info(&input.name, &input.bytes)?;
        let tile = Tile {
            name: input.name,
            info,
        };
        match kind_of(&tile.info) {
            Some(false) => tiles.radiance.push(tile),
            Some(true) => tiles.truth.push(tile),
            None => {
                return Err(miette!(
                    "`{}` is neither a radiance tile (the layer `radiance`) nor a truth tile \
                     (the layers {}): its layers are {}",
                    tile.name,
                    Layer::TRUTH.map(Layer::name).join(", "),
                    tile.info
                        .layers
                        .iter()
                        .map(|(n, _)| n.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
        }
    }
    Ok(tiles)
}

/// The files to write, `None` where not wanted.
#[derive(Debug, Default)]
struct Outputs {
    radiance_exr: Option<PathBuf>,
    truth_exr: Option<PathBuf>,
    map_png: Option<PathBuf>,
    dc_png: Option<PathBuf>,
    lut: Option<PathBuf>,
}

impl Cli {
    /// The outputs: with -o, every one the tiles given can make; else those named, each
    /// of which must have its tiles.
    fn outputs(&self, tiles: &Tiles) -> miette::Result<Outputs> {
        let (radiance, truth) = (!tiles.radiance.is_empty(), !tiles.truth.is_empty());
        if let Some(prefix) = &self.output {
            let named = |suffix: &str| {
                let mut s = prefix.as_os_str().to_owned();
                s.push(".");
                s.push(suffix);
                PathBuf::from(s)
            };
            let dc = radiance && !self.no_dc;
            return Ok(Outputs {
                radiance_exr: radiance.then(|| named("radiance.exr")),
                truth_exr: truth.then(|| named("truth.exr")),
                map_png: truth.then(|| named("map.png")),
                dc_png: dc.then(|| named("dc.png")),
                lut: dc.then(|| named("lut.txt")),
            });
        }
        let out = Outputs {
            radiance_exr: self.radiance_exr.clone(),
            truth_exr: self.truth_exr.clone(),
            map_png: self.map_png.clone(),
            dc_png: self.dc_png.clone(),
            lut: self.lut.clone(),
        };
        let needs = |flag: &str, given: bool, have: bool, kind: &str| {
            if given && !have {
                Err(irsig_cli::usage_error(format!(
                    "{flag} is made from {kind} tiles, and none was given"
                )))
            } else {
                Ok(())
            }
        };
        needs(
            "--radiance-exr",
            out.radiance_exr.is_some(),
            radiance,
            "radiance",
        )?;
        needs("--dc-png", out.dc_png.is_some(), radiance, "radiance")?;
        needs("--lut", out.lut.is_some(), radiance, "radiance")?;
        needs("--truth-exr", out.truth_exr.is_some(), truth, "truth")?;
        needs("--map-png", out.map_png.is_some(), truth, "truth")?;
        Ok(out)
    }

    fn has_output_flags(&self) -> bool {
        self.radiance_exr.is_some()
            || self.truth_exr.is_some()
            || self.map_png.is_some()
            || self.dc_png.is_some()
            || self.lut.is_some()
    }
}

/// Checks the tiles' layout from their headers, then reads and pastes them one at a time.
fn merge(tiles: &[Tile]) -> miette::Result<Raster> {
    let infos: Vec<(String, RasterInfo)> = tiles
        .iter()
        .map(|t| (t.name.clone(), t.info.clone()))
        .collect();
    let layout = Layout::check(&infos).map_err(|e| miette!("{e}"))?;
    let mut frame = layout.frame();
    for tile in tiles {
        let input = irsig_cli::read_input(&tile.name)?;
        let raster = irsig_cli::read_exr(&input.name, &input.bytes)?;
        layout
            .paste(&mut frame, &tile.name, &raster)
            .map_err(|e| miette!("{e}"))?;
    }
    Ok(frame)
}

/// The view's DC/K, from `--view`.
fn view_gain(cli: &Cli) -> miette::Result<Option<f64>> {
    let Some(path) = &cli.view else {
        return Ok(None);
    };
    let input = irsig_cli::read_input(path)?;
    let text = decode(&input.name, &input.bytes)?;
    let views = parse_views(&input.name, text, cli.view_unit)?;
    match views.as_slice() {
        [view] => Ok(view.gain_dc_per_k()),
        _ => Err(irsig_cli::usage_error(format!(
            "--view `{}` holds {} views: give the view of the frame the tiles are of",
            input.name,
            views.len()
        ))),
    }
}

/// Runs the tool.
///
/// # Errors
/// Unreadable or mismatched tiles (named), bad usage (exit 2), or an output that cannot be
/// written. Nothing is written then.
pub fn run(cli: Cli) -> miette::Result<()> {
    if cli.output.is_none() && !cli.has_output_flags() {
        return Err(irsig_cli::usage_error(
            "give -o PREFIX for every output the tiles make, or per-output flags such as \
             --radiance-exr FILE",
        ));
    }
    let tiles = read_tiles(&cli.tiles)?;
    let out = cli.outputs(&tiles)?;
    // Checked before the tiles are pasted (tens of seconds at 4096²).
    for path in [
        &out.radiance_exr,
        &out.truth_exr,
        &out.map_png,
        &out.dc_png,
        &out.lut,
    ]
    .into_iter()
    .flatten()
    {
        irsig_cli::check_output(path)?;
    }
    let gain = view_gain(&cli)?;
    // Radiance and truth tiles of one frame: one run, one frame.
    if let (Some(r), Some(t)) = (tiles.radiance.first(), tiles.truth.first())
        && r.info
            .part
            .as_ref()
            .map(|p| (&p.run, p.frame_width, p.frame_height))
            != t.info
                .part
                .as_ref()
                .map(|p| (&p.run, p.frame_width, p.frame_height))
    {
        return Err(miette!(
            "the radiance tile `{}` and the truth tile `{}` are not of one frame of one run \
             (a different scene, materials, view, band, atmosphere, option or frame size)",
            r.name,
            t.name
        ));
    }
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if out.radiance_exr.is_some() || out.dc_png.is_some() || out.lut.is_some() {
        let frame = merge(&tiles.radiance)?;
        if out.dc_png.is_some() || out.lut.is_some() {
            match &cli.band {
                TraceBand::Total => counts(&cli, &out, &frame, gain, &TotalRadiance, &mut files)?,
                TraceBand::Band(arg) => {
                    counts(&cli, &out, &frame, gain, &arg.load()?, &mut files)?;
                }
            }
        }
        // The merged frame's layers go into the encoder, not a copy of them.
        if let Some(path) = &out.radiance_exr {
            files.push((path.clone(), into_exr_bytes(frame).into_diagnostic()?));
        }
    }
    if out.truth_exr.is_some() || out.map_png.is_some() {
        let frame = merge(&tiles.truth)?;
        if let Some(path) = &out.map_png {
            match interaction_map(&frame)? {
                Ok(png) => files.push((path.clone(), png)),
                Err(id) if cli.output.is_some() => eprintln!(
                    "irsig-merge: interaction map not written: material id {id} does not fit \
                     the legacy 4-bit nibble (ids 1 to 15); the truth EXR's material_primary \
                     and material_secondary layers hold the same information losslessly"
                ),
                Err(id) => {
                    return Err(miette!(
                        "{}: interaction map not written: material id {id} does not fit the \
                         legacy 4-bit nibble (ids 1 to 15); the truth EXR's material_primary \
                         and material_secondary layers hold the same information losslessly",
                        path.display()
                    ));
                }
            }
        }
        if let Some(path) = &out.truth_exr {
            files.push((path.clone(), into_exr_bytes(frame).into_diagnostic()?));
        }
    }
    irsig_cli::write_files_atomic(&files)
}

/// The digital counts and LUT of the merged radiance, as irsig-trace makes them.
fn counts(
    cli: &Cli,
    out: &Outputs,
    frame: &Raster,
    view_gain: Option<f64>,
    band: &impl BandModel,
    files: &mut Vec<(PathBuf, Vec<u8>)>,
) -> miette::Result<()> {
    let radiance = &frame
        .layer(Layer::Radiance.name())
        .ok_or_else(|| miette!("the merged frame has no radiance layer"))?
        .data;
    let q = cli.dc.tracer_quantiser(view_gain, radiance, band)?;
    if let Some(path) = &out.dc_png {
        let counts = q
            .quantise(radiance, frame.width)
            .map_err(|e| miette!("digital counts: {e}"))?;
        files.push((
            path.clone(),
            counts_png(&counts, frame.width, frame.height, cli.dc.dc_bits).into_diagnostic()?,
        ));
    }
    if let Some(path) = &out.lut {
        files.push((path.clone(), q.lut(band).to_string().into_bytes()));
    }
    Ok(())
}

/// The 1990 interaction map of the merged truth layers (`irsig_formats::legacy::map`), or
/// the first material id that does not fit a nibble.
fn interaction_map(truth: &Raster) -> miette::Result<Result<Vec<u8>, u32>> {
    let layer = |l: Layer| {
        truth
            .layer(l.name())
            .map(|l| &l.data)
            .ok_or_else(|| miette!("the merged truth has no `{}` layer", l.name()))
    };
    let (primary, secondary) = (
        layer(Layer::MaterialPrimary)?,
        layer(Layer::MaterialSecondary)?,
    );
    let id = |v: f32| -> miette::Result<u16> {
        if v.is_finite() && v.fract() == 0.0 && (0.0..=f32::from(u16::MAX)).contains(&v) {
            Ok(v as u16)
        } else {
            Err(miette!(
                "a material layer holds {v}, which is not a material id (0 to 65535)"
            ))
        }
    };
    let mut data = Vec::with_capacity(primary.len());
    for (&p, &s) in primary.iter().zip(secondary) {
        let (p, s) = (id(p)?, id(s)?);
        match irsig_formats::legacy::map::pixel(p, s) {
            Some(byte) => data.push(byte),
            None => return Ok(Err(u32::from(p.max(s)))),
        }
    }
    let mut png = Vec::new();
    irsig_raster::write_png_gray8(&mut png, truth.width, truth.height, &data).into_diagnostic()?;
    Ok(Ok(png))
}
