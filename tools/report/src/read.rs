//! A report's inputs, every one read and checked before the page is begun: the images and
//! the values every section shows, then each optional file, and the provenance along the
//! chain.

use irsig_cli::args::ResolvedBand;
use irsig_formats::lut::LutRow;
use irsig_model::provenance::Provenance;

use super::*;
use crate::saturation::Saturation;

/// An image read: its name as messages give it, its layers and what it records.
pub(crate) type Image = (String, Raster, Option<Provenance>);

/// Everything the page shows, read and checked.
pub(crate) struct Run {
    pub(crate) names: Names,
    pub(crate) truth: Option<Image>,
    /// The apparent temperature every section shows, K, row-major.
    pub(crate) values: Vec<f32>,
    pub(crate) width: usize,
    pub(crate) height: usize,
    /// Where `values` come from, as the page names it.
    pub(crate) shown_source: String,
    /// The finite range of `values`, K.
    pub(crate) range: (f64, f64),
    pub(crate) profile: Option<Profile>,
    pub(crate) regions: Option<(irsig_regions::Table, RegionSet)>,
    pub(crate) decision: Option<Decision>,
    /// The SHA-256 of the uncertainties the truth EXR records: `None` without a truth EXR
    /// or provenance, `Some(None)` when it was traced without.
    pub(crate) recorded_uncertainties: Option<Option<String>>,
    pub(crate) uncertainties: Option<Uncertainties>,
    /// The LUT's name as the page shows it, and its rows.
    pub(crate) lut: Option<(String, Vec<LutRow>)>,
    pub(crate) commands: Vec<String>,
    pub(crate) pipeline: Option<PipelineFiles>,
    pub(crate) recorded: chain::Recorded,
    pub(crate) chain_rows: Vec<chain::Row>,
    pub(crate) saturated: Option<Saturation>,
}

/// A line profile and its points: distance from the start, pixels, and value, K.
pub(crate) type Profile = (ProfileLine, Vec<(f64, f64)>);

/// The pipeline's base folder as the page shows it, and its files as they are now.
pub(crate) type PipelineFiles = (String, Vec<PipelineFile>);

/// A radiance image read, with the band its radiances are in.
type RadianceImage = (String, Raster, ResolvedBand, Option<Provenance>);

/// Reads and checks every input `cli` names.
///
/// # Errors
/// As [`crate::run`].
pub(crate) fn read(cli: &Cli) -> miette::Result<Run> {
    let names = Names::for_output(cli.output.path.as_deref());
    let mut inputs: Vec<(String, Known)> = Vec::new();
    let (truth, mut radiance) = images(cli, &names, &mut inputs)?;
    let (values, width, height, source, shown_source) = values_of(&names, &truth, &radiance)?;
    // Past the values, of the radiance image only its radiances are kept, and only to
    // compare with a LUT's (saturation): the page is made in the memory per pixel the
    // README states.
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
    let profile = profile_of(cli, &values, width, height)?;
    let regions = regions_of(cli, &names, &mut inputs, &truth, &values, width, &source)?.map(
        |(mut table, set)| {
            table.values.clone_from(&shown_source);
            (table, set)
        },
    );
    let decision = match &cli.decision.file {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(own(&names, "decision", &input));
            let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
            Some(irsig_formats::canonical::from_ron(&input.name, text)?)
        }
        None => None,
    };
    let (recorded_uncertainties, uncertainties) =
        uncertainties_of(cli, &names, &mut inputs, &truth)?;
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
    let (commands, pipeline) = pipeline_of(cli, &names, &mut inputs)?;

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
    Ok(Run {
        names,
        truth,
        values,
        width,
        height,
        shown_source,
        range,
        profile,
        regions,
        decision,
        recorded_uncertainties,
        uncertainties,
        lut,
        commands,
        pipeline,
        recorded,
        chain_rows,
        saturated,
    })
}

/// The truth EXR and the radiance image, each with what it records; the band a --band
/// names checked against the one an image records.
fn images(
    cli: &Cli,
    names: &Names,
    inputs: &mut Vec<(String, Known)>,
) -> miette::Result<(Option<Image>, Option<RadianceImage>)> {
    let truth = match &cli.truth {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(own(names, "truth EXR", &input));
            let image = irsig_cli::read_exr(&input.name, &input.bytes)?;
            let recorded = irsig_cli::provenance(&input.name, &image)?;
            // Without a radiance image a --band is the truth EXR's, whose apparent
            // temperatures are in the band it records: given, it must be that band.
            if cli.radiance.file.is_none() {
                cli.band.check_truth(
                    "irsig-report",
                    &input.name,
                    recorded.as_ref().map(|p| &p.band),
                )?;
            }
            Some((input.name, image, recorded))
        }
        None => None,
    };
    let radiance = match &cli.radiance.file {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            inputs.push(own(names, "radiance EXR", &input));
            let image = irsig_cli::read_exr(&input.name, &input.bytes)?;
            let recorded = irsig_cli::provenance(&input.name, &image)?;
            let band = cli.band.resolve_saying(
                "irsig-report",
                &input.name,
                recorded.as_ref().map(|p| &p.band),
            )?;
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
    Ok((truth, radiance))
}

/// The values every section shows: apparent temperature, K, with the image's size; the
/// source as messages name it, and as the page does.
fn values_of(
    names: &Names,
    truth: &Option<Image>,
    radiance: &Option<RadianceImage>,
) -> miette::Result<(Vec<f32>, usize, usize, String, String)> {
    match (radiance, truth) {
        (Some((name, image, band, _)), _) => {
            let l = layer(image, name, RADIANCE_LAYER)?;
            let t = irsig_radiometry::apparent_temperatures(&band.band, l);
            let say = |n: &str| {
                format!(
                    "apparent temperature of the `{RADIANCE_LAYER}` layer of {n} in {}",
                    band.record
                )
            };
            Ok((
                t,
                image.width,
                image.height,
                say(name),
                say(&names.show_name(name)),
            ))
        }
        (None, Some((name, image, _))) => Ok((
            layer(image, name, APPARENT_LAYER)?.to_vec(),
            image.width,
            image.height,
            format!("`{APPARENT_LAYER}` layer of {name}"),
            format!("`{APPARENT_LAYER}` layer of {}", names.show_name(name)),
        )),
        (None, None) => Err(irsig_cli::usage_error(
            "expected a truth EXR or --radiance FILE: the report shows an image",
        )),
    }
}

/// The line profile's pixels and values, its ends checked against the image.
fn profile_of(
    cli: &Cli,
    values: &[f32],
    width: usize,
    height: usize,
) -> miette::Result<Option<Profile>> {
    let Some(line) = cli.profile else {
        return Ok(None);
    };
    for (end, (x, y)) in [("start", line.from), ("end", line.to)] {
        if x >= width || y >= height {
            return Err(irsig_cli::usage_error(format!(
                "--profile {line}: the {end} ({x}, {y}) is outside the image ({width} x \
                 {height} pixels: columns 0-{}, rows 0-{})",
                width - 1,
                height - 1
            )));
        }
    }
    let points = line
        .pixels()
        .into_iter()
        .map(|(x, y, d)| (d, f64::from(values[y * width + x])))
        .collect();
    Ok(Some((line, points)))
}

/// The per-region statistics of the regions file, over the truth EXR's materials.
fn regions_of(
    cli: &Cli,
    names: &Names,
    inputs: &mut Vec<(String, Known)>,
    truth: &Option<Image>,
    values: &[f32],
    width: usize,
    source: &str,
) -> miette::Result<Option<(irsig_regions::Table, RegionSet)>> {
    let (Some(path), Some((truth_name, image, _))) = (&cli.regions.file, truth) else {
        return Ok(None);
    };
    let input = irsig_cli::read_input(path)?;
    inputs.push(own(names, "regions", &input));
    let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
    let set: RegionSet = irsig_formats::canonical::from_ron(&input.name, text)?;
    let ids = layer(image, truth_name, MATERIAL_LAYER)?;
    let table = irsig_regions::tabulate(&irsig_regions::Inputs {
        regions_name: &input.name,
        regions_text: text,
        set: &set,
        image_name: truth_name,
        material_ids: ids,
        width,
        values,
        source: source.to_owned(),
        unit: "K",
        celsius: false,
    })?;
    Ok(Some((table, set)))
}

/// What the truth EXR records of the uncertainties it was traced with, and the declared
/// uncertainties given, which must be those.
fn uncertainties_of(
    cli: &Cli,
    names: &Names,
    inputs: &mut Vec<(String, Known)>,
    truth: &Option<Image>,
) -> miette::Result<(Option<Option<String>>, Option<Uncertainties>)> {
    let recorded = truth.as_ref().and_then(|(_, _, p)| p.as_ref()).map(|p| {
        p.inputs
            .iter()
            .find(|i| i.stage == "trace" && i.role == "uncertainties")
            .map(|i| i.sha256.clone())
    });
    let Some(path) = &cli.uncertainties.file else {
        return Ok((recorded, None));
    };
    let input = irsig_cli::read_input(path)?;
    let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
    let u: Uncertainties = irsig_formats::canonical::from_ron(&input.name, text)?;
    let truth_name = truth.as_ref().map_or("", |(n, _, _)| n.as_str());
    match &recorded {
        Some(Some(sha)) if *sha != input.sha256() => {
            return Err(irsig_cli::usage_error(format!(
                "--uncertainties {}: its SHA-256 is {}, but {truth_name} was traced with \
                 uncertainties of SHA-256 {}: give the file the truth EXR was traced with",
                input.name,
                chain::hex(&input.sha256()),
                chain::hex(sha)
            )));
        }
        Some(None) => {
            return Err(irsig_cli::usage_error(format!(
                "--uncertainties {}: {truth_name} was traced without declared uncertainties \
                 (it records none): trace with --uncertainties FILE for an error budget",
                input.name
            )));
        }
        _ => {}
    }
    inputs.push(own(names, "uncertainties", &input));
    Ok((recorded, Some(u)))
}

/// The run's command lines (the pipeline's steps', then `--command`'s) and the pipeline's
/// files as they are now.
fn pipeline_of(
    cli: &Cli,
    names: &Names,
    inputs: &mut Vec<(String, Known)>,
) -> miette::Result<(Vec<String>, Option<PipelineFiles>)> {
    let Some(path) = &cli.pipeline else {
        return Ok((cli.command.clone(), None));
    };
    let input = irsig_cli::read_input(path)?;
    inputs.push(own(names, "pipeline", &input));
    let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
    let base = input.base_dir();
    let pipeline =
        irsig_pipeline::Pipeline::parse(&input.name, text, &base).map_err(miette::Report::new)?;
    let mut tools = irsig_pipeline::Tools::new(|t| Some(PathBuf::from(format!("irsig-{t}"))));
    tools.with_sun_flags(irsig_pipeline::SunFlags {
        field: irsig_cli::args::sun::flag,
        day_of_year: irsig_cli::args::DayOfYear::FLAG,
    });
    let plan = pipeline.plan(&tools).map_err(miette::Report::new)?;
    let files = pipeline_files(&plan, names, cli.output.path.as_deref())?;
    let commands = plan
        .steps
        .iter()
        .map(irsig_pipeline::Step::command_line)
        .chain(cli.command.iter().cloned())
        .collect();
    Ok((commands, Some((names.show(plan.base_dir()), files))))
}
