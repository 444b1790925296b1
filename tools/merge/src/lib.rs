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
//! the merged layers, by the code irsig-trace uses (`irsig_render::products`). Truth tiles
//! that carry the error budget's layers (`irsig-trace --tile --uncertainties`) merge like
//! any other.
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
use irsig_cli::args::{DcArgs, FrameOutputArgs, ImageBandArgs, ThreadsArgs, ViewArgs};
use irsig_formats::legacy::decode;
use irsig_formats::views::parse_views;
use irsig_model::frame::{FrameFile, FrameFiles};
use irsig_model::truth::Layer;
use irsig_raster::merge::Layout;
use irsig_raster::{Raster, RasterInfo};
use irsig_render::products::{self, FrameRadiometry, MapRefused};
use miette::miette;

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
#[command(
    name = "irsig-merge",
    version,
    about,
    after_help = EXAMPLE,
    mut_arg("view", |a| a.help(
        "The view the tiles were traced with: its DC/K is the counts' gain when no \
         --dc-per-kelvin is given (as in irsig-trace). A canonical RON view or a 1990 viewing \
         file, holding one view"
    )),
    mut_arg("legacy_unit", |a| a.alias("view-unit")),
)]
pub struct Cli {
    /// The tiles: radiance and truth EXRs written by `irsig-trace --tile`, in any order
    /// (told apart by their layers). Files, not `-`.
    #[arg(required = true, value_name = "TILE")]
    pub tiles: Vec<String>,
    /// Where the frame's files go: -o PREFIX for every file the tiles given can make
    /// (radiance EXR, counts and LUT from radiance tiles; truth EXR and map from truth
    /// tiles), or one flag per file, each of which needs its tiles.
    #[command(flatten)]
    pub output: FrameOutputArgs,
    /// `--view FILE` (one) and the unit of a 1990 viewing file.
    #[command(flatten)]
    pub views: ViewArgs,
    /// The band the tiles were traced in, which they record (the counts' calibration and the
    /// LUT's temperatures use it).
    #[command(flatten)]
    pub band: ImageBandArgs,
    /// How radiance becomes digital counts, as for irsig-trace: without a gain, the view's
    /// DC/K, else 2 counts per kelvin (the thesis's auto-bias).
    #[command(flatten)]
    pub dc: DcArgs,
    /// `--threads N`: worker threads.
    #[command(flatten)]
    pub threads: ThreadsArgs,
}

/// The flags' own rules are clap's and the run's: nothing more is checked before a file
/// is read.
impl irsig_cli::CheckArgs for Cli {}

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

/// Reads every tile's header and sorts the tiles into radiance and truth: a radiance tile
/// holds the layer `radiance`, a truth tile the truth layers, with or without the error
/// budget's.
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
        let names: Vec<&str> = info.layers.iter().map(|(n, _)| n.as_str()).collect();
        let is = |layers: Vec<Layer>| names.iter().copied().eq(layers.iter().map(|l| l.name()));
        let tile = Tile {
            name: input.name,
            info: info.clone(),
        };
        if is(vec![Layer::Radiance]) {
            tiles.radiance.push(tile);
        } else if (0..32)
            .map(|k| [k & 1 != 0, k & 2 != 0, k & 4 != 0, k & 8 != 0, k & 16 != 0])
            .any(|[sun, texture, data, budget, tolerance]| {
                is(products::truth_layers(
                    sun, texture, data, budget, tolerance,
                ))
            })
        {
            tiles.truth.push(tile);
        } else {
            return Err(miette!(
                "`{}` is neither a radiance tile (the layer `radiance`) nor a truth tile \
                 (the layers {}, then the sun's {}, then the texture's {}, then the \
                 atmosphere data's {}, then the error budget's {}, then the tolerance's {}, \
                 each group when rendered so): its layers are {}",
                tile.name,
                Layer::TRUTH.map(Layer::name).join(", "),
                Layer::SUN.map(Layer::name).join(", "),
                Layer::TEXTURE.map(Layer::name).join(", "),
                Layer::DATA.map(Layer::name).join(", "),
                Layer::BUDGET.map(Layer::name).join(", "),
                Layer::TOLERANCE.map(Layer::name).join(", "),
                names.join(", ")
            ));
        }
    }
    Ok(tiles)
}

/// The files to write: with -o, every one the tiles given can make; else those named, each
/// of which must have its tiles.
fn outputs(cli: &Cli, tiles: &Tiles) -> miette::Result<FrameFiles<PathBuf>> {
    let (radiance, truth) = (!tiles.radiance.is_empty(), !tiles.truth.is_empty());
    let of_radiance = |k: &FrameFile| {
        matches!(
            k,
            FrameFile::RadianceExr | FrameFile::DcPng | FrameFile::Lut
        )
    };
    let kinds: Vec<FrameFile> = FrameFile::ALL
        .into_iter()
        .filter(|k| if of_radiance(k) { radiance } else { truth })
        .collect();
    if let Some(files) = cli.output.prefixed(0, 1, &kinds) {
        return Ok(files);
    }
    let files = cli.output.named();
    for (kind, _) in files.iter() {
        let (have, tile) = if of_radiance(&kind) {
            (radiance, "radiance")
        } else {
            (truth, "truth")
        };
        if !have {
            return Err(irsig_cli::usage_error(format!(
                "{} is made from {tile} tiles, and none was given",
                FrameOutputArgs::flag(kind)
            )));
        }
    }
    Ok(files)
}

/// Checks the tiles' layout from their headers, then reads and pastes them one at a time.
fn merge(tiles: &[Tile]) -> miette::Result<Option<Raster>> {
    if tiles.is_empty() {
        return Ok(None);
    }
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
    Ok(Some(frame))
}

/// The view's DC/K, from `--view`: the one view of the frame the tiles are of. A `sun` in
/// its file does not change the counts and is not read.
fn view_gain(cli: &Cli) -> miette::Result<Option<f64>> {
    let path = match cli.views.files.as_slice() {
        [] => return Ok(None),
        [path] => path,
        more => {
            return Err(irsig_cli::usage_error(format!(
                "{} view files: give --view once, the view of the frame the tiles are of",
                more.len()
            )));
        }
    };
    let input = irsig_cli::read_input(path)?;
    let text = decode(&input.name, &input.bytes)?;
    let views = parse_views(&input.name, text, cli.views.unit.unit())?;
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
    cli.threads.install(|| merge_frame(&cli))
}

fn merge_frame(cli: &Cli) -> miette::Result<()> {
    if cli.output.prefix.path.is_none() && !cli.output.has_files() {
        return Err(irsig_cli::usage_error(
            "give -o PREFIX for every output the tiles make, or per-output flags such as \
             --radiance-exr FILE",
        ));
    }
    let tiles = read_tiles(&cli.tiles)?;
    let out = outputs(cli, &tiles)?;
    let band_file = cli.band.band.response_file();
    irsig_cli::refuse_output_is_input(
        cli.tiles
            .iter()
            .map(String::as_str)
            .chain(cli.views.files.iter().map(String::as_str))
            .chain(band_file),
        out.iter().map(|(_, p)| p),
    )?;
    // Checked before the tiles are pasted (tens of seconds at 4096²).
    for (_, path) in out.iter() {
        irsig_cli::check_output(path)?;
    }
    let gain = view_gain(cli)?;
    // Radiance and truth tiles of one frame: one run, one frame.
    let frame_of = |t: &Tile| {
        t.info
            .part
            .as_ref()
            .map(|p| (p.run.clone(), p.frame_width, p.frame_height))
    };
    if let (Some(r), Some(t)) = (tiles.radiance.first(), tiles.truth.first())
        && frame_of(r) != frame_of(t)
    {
        return Err(miette!(
            "the radiance tile `{}` and the truth tile `{}` are not of one frame of one run \
             (a different scene, materials, view, band, atmosphere, option or frame size)",
            r.name,
            t.name
        ));
    }
    let wanted = out.wanted();
    let radiance = if wanted.wants(FrameFile::RadianceExr)
        || wanted.wants(FrameFile::DcPng)
        || wanted.wants(FrameFile::Lut)
    {
        merge(&tiles.radiance)?
    } else {
        None
    };
    let truth = if wanted.wants(FrameFile::TruthExr) || wanted.wants(FrameFile::MapPng) {
        merge(&tiles.truth)?
    } else {
        None
    };
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut emit = |kind: FrameFile, bytes: Vec<u8>| {
        if let Some(path) = out.get(kind) {
            files.push((path.clone(), bytes));
        }
        Ok(())
    };
    let refused = if cli.output.prefix.path.is_some() {
        MapRefused::Skip
    } else {
        MapRefused::Fail
    };
    let mut note = |text: String| irsig_cli::note!("irsig-merge: {text}");
    // The band and the rest of what made the frame, as the tiles record it.
    let first = tiles.radiance.first().or(tiles.truth.first());
    let provenance = match first.and_then(|t| t.info.comments.as_deref().map(|c| (t, c))) {
        Some((t, c)) => irsig_formats::canonical::provenance_of(&t.name, c).transpose()?,
        None => None,
    };
    let name = first.map_or("the tiles", |t| t.name.as_str());
    let band = cli
        .band
        .resolve(name, provenance.as_ref().map(|p| &p.band))?;
    if let Some(w) = &band.warning {
        irsig_cli::note!("irsig-merge: warning: {w}");
    }
    let r = FrameRadiometry {
        band: band.band,
        sub_bands: 1,
        view_gain: gain,
        counts: cli.dc.request(),
        provenance,
    };
    products::merged(&r, radiance, truth, &wanted, refused, &mut note, &mut emit)?;
    irsig_cli::write_files_atomic(&files)
}
