//! `irsig-stats`: the thesis's local-area analysis (Shor 1990, §4.8–4.9, Tables 5–7) as a
//! stage. It reads a traced image and a regions file (`formats/canonical/regions.md`: each
//! region a material id, a pixel box or both, with optional reference temperatures such as
//! a paper's values and their source), and writes per region the pixel count and the mean,
//! standard deviation, minimum and maximum apparent temperature, beside each reference
//! value and the difference mean − reference. Aligned text by default, `--format csv|ron`.
//!
//! The regions select pixels by the `material_primary` layer of the tracer's truth EXR. The
//! values are, by default, that EXR's `apparent_temperature` layer (K); `--layer` picks
//! another layer in kelvin, and `--radiance FILE` takes the `radiance` layer of another
//! image of the same size (the sensor stage's blurred EXR, say) and converts it to apparent
//! temperature in `--band`.
//!
//! ```no_run
//! use clap::Parser;
//! let cli = irsig_stats::Cli::parse_from([
//!     "irsig-stats", "out/frame.truth.exr", "--regions", "regions.ron",
//!     "--radiance", "out/frame.sensor.exr", "--celsius", "-o", "out/table.txt",
//! ]);
//! irsig_stats::run(cli)?;
//! # Ok::<(), miette::Report>(())
//! ```

// A closed stderr must not panic the tool: notes go through `irsig_cli::note!`.
#![warn(clippy::print_stderr)]

use std::fmt::Write as _;

use clap::Parser;
use irsig_cli::args::inputs::{RadianceImage, Regions};
use irsig_cli::args::outputs::Output;
use irsig_cli::args::{Format, ImageBandArgs, TableFormat};
use irsig_model::RegionSet;
use irsig_model::truth::Layer;
use irsig_raster::Raster;
use miette::miette;

use irsig_regions::{Inputs, Row, Table, tabulate};

mod texture;

/// The truth layer regions select by.
const MATERIAL_LAYER: &str = Layer::MaterialPrimary.name();
/// The default value layer: the tracer's apparent temperature, K.
const APPARENT_LAYER: &str = Layer::ApparentTemperature.name();
/// The layer `--radiance` reads, W m⁻² sr⁻¹.
const RADIANCE_LAYER: &str = Layer::Radiance.name();

const EXAMPLE: &str = "\
Examples:
  irsig-stats out/frame.truth.exr --regions regions.ron
      mean/std/min/max apparent temperature (K) per region, beside the regions file's
      reference values, as an aligned table on stdout
  irsig-stats out/frame.truth.exr --regions regions.ron --radiance out/frame.sensor.exr \\
      --band 8-14 --celsius --format csv -o table.csv
      the same for the sensor stage's blurred radiance, in degC, as CSV
  irsig-stats out/frame.truth.exr --regions regions.ron --layer kinetic_temperature
      the kinetic temperature the tracer assigned, per region
  irsig-stats out/frame.truth.exr --regions regions.ron --texture grass --pixel-m 0.05 \\
      --texture-out grass-texture.ron
      also the texture of region `grass` (sigma, correlation lengths, a fitted spectrum)
      as a material's `texture` description

The regions file (canonical RON, formats/canonical/regions.md):
  (references: [(name: \"paper\", source: \"Table 7\")],
   regions: [(name: \"pool\", material: Some(2), pixels: Some((columns: (10, 40), rows: (5, 9))),
              references: [(name: \"paper\", temperature_k: 286.5)])])";

/// Per-region statistics of a traced image beside reference values.
#[derive(Debug, Parser)]
#[command(
    name = "irsig-stats",
    version,
    about,
    after_help = EXAMPLE,
    group(clap::ArgGroup::new("regions_required").args(["regions"]).required(true)),
    mut_arg("radiance", |a| a.conflicts_with("layer").help(
        "Take the values from this image's `radiance` layer (W m^-2 sr^-1), converted to \
         apparent temperature in --band, instead of a layer of the truth EXR. Same size as \
         the truth EXR"
    )),
    mut_arg("format", |a| a.help(
        "Output form: `table` (aligned columns, the sources as `#` comment lines), `csv` (a \
         header row, full precision) or `ron` (`(values: .., unit: .., references: [..], \
         regions: [..])`, full precision)"
    )),
    mut_arg("output", |a| a.help("Output file (`-` or absent: stdout); written atomically")),
)]
pub struct Cli {
    /// The tracer's truth EXR (its `material_primary` layer selects pixels), or `-`.
    pub truth: String,
    /// `--regions FILE`.
    #[command(flatten)]
    pub regions: Regions,
    /// `--radiance FILE`.
    #[command(flatten)]
    pub radiance: RadianceImage,
    /// The truth EXR's layer to take the values from, in its own unit (K for the
    /// temperatures, W m^-2 for `solar_irradiance`, none for a fraction).
    #[arg(long, value_name = "NAME", default_value = APPARENT_LAYER)]
    pub layer: String,
    /// The band of --radiance, which that image records (irsig-trace and irsig-sensor
    /// write it); --band must be that band unless --override-band.
    #[command(flatten)]
    pub band: ImageBandArgs,
    /// Report temperatures in degC (K − 273.15) instead of K; differences are the same.
    #[arg(long)]
    pub celsius: bool,
    /// `--format`.
    #[command(flatten)]
    pub format: Format,
    /// `-o PATH`.
    #[command(flatten)]
    pub output: Output,
    /// `--texture REGION --pixel-m M --texture-out FILE`.
    #[command(flatten)]
    pub texture: texture::TextureArgs,
}

/// The flags' own rules are clap's and the run's: nothing more is checked before a file
/// is read.
impl irsig_cli::CheckArgs for Cli {}

/// Runs the tool.
///
/// # Errors
/// Unreadable or malformed input (the regions file with line and column), a missing
/// layer, images of different sizes, a region that selects nothing, or an unwritable
/// output; nothing is written then.
pub fn run(cli: Cli) -> miette::Result<()> {
    let band_file = cli.band.band.response_file();
    let regions = cli.regions.required()?;
    let inputs = [cli.truth.as_str(), regions]
        .into_iter()
        .chain(cli.radiance.file.as_deref())
        .chain(band_file);
    irsig_cli::refuse_output_is_input(
        inputs,
        cli.output.path.iter().chain(cli.texture.texture_out.iter()),
    )?;
    if let (Some(out), Some(texture_out)) = (&cli.output.path, &cli.texture.texture_out)
        && out == texture_out
    {
        return Err(irsig_cli::usage_error(format!(
            "--texture-out {}: the same file as -o: expected two outputs",
            texture_out.display()
        )));
    }
    let regions_input = irsig_cli::read_input(regions)?;
    let regions_text = irsig_formats::canonical::utf8(&regions_input.name, &regions_input.bytes)?;
    let set: RegionSet = irsig_formats::canonical::from_ron(&regions_input.name, regions_text)?;
    let truth_input = irsig_cli::read_input(&cli.truth)?;
    let truth = irsig_cli::read_exr(&truth_input.name, &truth_input.bytes)?;
    // The truth EXR's own record is read as every stage reads one: a malformed record, or
    // a --band that is not the band it records (whose apparent temperatures it holds), is
    // refused even when no radiance image is converted.
    let truth_recorded = irsig_cli::provenance(&truth_input.name, &truth)?;
    if cli.radiance.file.is_none() {
        cli.band.check_truth(
            "irsig-stats",
            &truth_input.name,
            truth_recorded.as_ref().map(|p| &p.band),
        )?;
    }
    let ids = layer(&truth, &truth_input.name, MATERIAL_LAYER)?;
    let (values, source): (Vec<f32>, String) = match &cli.radiance.file {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            let image = irsig_cli::read_exr(&input.name, &input.bytes)?;
            let recorded = irsig_cli::provenance(&input.name, &image)?;
            let band = cli.band.resolve_saying(
                "irsig-stats",
                &input.name,
                recorded.as_ref().map(|p| &p.band),
            )?;
            if (image.width, image.height) != (truth.width, truth.height) {
                return Err(miette!(
                    "{}: the image is {} x {} pixels but the truth EXR {} is {} x {}: \
                     expected the same size (trace and sense at one resolution, or reduce \
                     the truth layers with the sensor stage)",
                    input.name,
                    image.width,
                    image.height,
                    truth_input.name,
                    truth.width,
                    truth.height
                ));
            }
            let radiance = layer(&image, &input.name, RADIANCE_LAYER)?;
            let temperatures = irsig_radiometry::apparent_temperatures(&band.band, radiance);
            (
                temperatures,
                format!(
                    "apparent temperature of the `radiance` layer of {} in {}",
                    input.name, band.record
                ),
            )
        }
        None => (
            layer(&truth, &truth_input.name, &cli.layer)?.to_vec(),
            format!("`{}` layer of {}", cli.layer, truth_input.name),
        ),
    };
    // The values' unit is the layer's: a temperature, a radiance, a ratio.
    let unit = match (&cli.radiance.file, Layer::from_name(&cli.layer)) {
        (Some(_), _) => "K",
        (None, Some(l)) if l.is_label() => {
            return Err(irsig_cli::usage_error(format!(
                "--layer {}: the layer holds labels, not quantities: expected a layer of \
                 values (a temperature, a radiance, a fraction)",
                cli.layer
            )));
        }
        (None, Some(l)) => l.unit(),
        (None, None) => {
            return Err(irsig_cli::usage_error(format!(
                "--layer {}: not a layer irsig-trace writes, so its unit is unknown",
                cli.layer
            )));
        }
    };
    if cli.celsius && unit != "K" {
        return Err(irsig_cli::usage_error(format!(
            "--celsius with --layer {}: the layer is not a temperature ({}): leave out --celsius",
            cli.layer,
            if unit.is_empty() { "a ratio" } else { unit }
        )));
    }

    let texture_text = match (&cli.texture.texture, cli.texture.pixel_m) {
        (Some(region), Some(pixel_m)) => Some(texture::describe(&texture::Request {
            region,
            pixel_m,
            seed: cli.texture.texture_seed,
            set: &set,
            ids,
            values: &values,
            width: truth.width,
            unit,
            source: &source,
            regions_name: &regions_input.name,
        })?),
        _ => None,
    };
    let table = tabulate(&Inputs {
        regions_name: &regions_input.name,
        regions_text,
        set: &set,
        image_name: &truth_input.name,
        material_ids: ids,
        width: truth.width,
        values: &values,
        source,
        unit,
        celsius: cli.celsius,
    })?;
    let text = render(&table, cli.format.value)?;
    // Everything is computed before anything is written.
    if let (Some(out), Some(t)) = (&cli.texture.texture_out, &texture_text) {
        irsig_cli::write_output(Some(out), |w| w.write_all(t.as_bytes()))?;
    }
    irsig_cli::write_output(cli.output.path.as_deref(), |w| w.write_all(text.as_bytes()))
}

fn layer<'a>(image: &'a Raster, name: &str, layer: &str) -> miette::Result<&'a [f32]> {
    image
        .layer(layer)
        .map(|l| l.data.as_slice())
        .ok_or_else(|| {
            let names: Vec<&str> = image.layers.iter().map(|l| l.name.as_str()).collect();
            miette!(
                "{name}: no layer `{layer}` (it has: {}); expected the tracer's truth EXR for \
             `{MATERIAL_LAYER}` and `{APPARENT_LAYER}`, or an image with `{RADIANCE_LAYER}` \
             for --radiance",
                names.join(", ")
            )
        })
}

/// A column name's unit suffix: `_k` for K, `_c` for degC, `_w_m-2` for `W m^-2`, none for
/// a ratio.
fn column_suffix(unit: &str) -> String {
    match unit {
        "K" => "_k".into(),
        "degC" => "_c".into(),
        "" => String::new(),
        u => format!("_{}", u.replace('^', "").replace(' ', "_").to_lowercase()),
    }
}

/// The table as text, CSV or RON.
///
/// # Errors
/// Only if RON serialisation fails, which it does not for finite numbers.
pub fn render(table: &Table, format: TableFormat) -> miette::Result<String> {
    let unit = column_suffix(&table.unit);
    // The spread and the differences are differences: kelvin for degC too.
    let spread = if table.unit == "degC" {
        "_k".to_owned()
    } else {
        unit.clone()
    };
    let mut header: Vec<String> = ["region", "pixels"]
        .into_iter()
        .map(String::from)
        .chain(
            ["mean", "std_dev", "min", "max"]
                .iter()
                .enumerate()
                .map(|(i, h)| {
                    if i == 1 {
                        format!("{h}{spread}")
                    } else {
                        format!("{h}{unit}")
                    }
                }),
        )
        .collect();
    for (name, _) in &table.references {
        header.push(format!("{name}{unit}"));
        header.push(format!("mean_minus_{name}{spread}"));
    }
    let cells = |row: &Row, full: bool| -> Vec<String> {
        let num = |v: f64| {
            if full {
                format!("{v}")
            } else {
                format!("{v:.2}")
            }
        };
        let mut c = vec![
            row.region.clone(),
            row.pixels.to_string(),
            num(row.mean),
            num(row.std_dev),
            num(row.min),
            num(row.max),
        ];
        for r in &row.references {
            match r {
                Some(r) => {
                    c.push(num(r.reference));
                    c.push(if full {
                        format!("{}", r.difference)
                    } else {
                        format!("{:+.2}", r.difference)
                    });
                }
                None => {
                    let empty = if full { "" } else { "-" };
                    c.push(empty.into());
                    c.push(empty.into());
                }
            }
        }
        c
    };
    let mut out = String::new();
    match format {
        TableFormat::Table => {
            let _ = writeln!(out, "# values: {} ({})", table.values, table.unit);
            for (name, source) in &table.references {
                let _ = writeln!(out, "# {name}: {source}");
            }
            let body: Vec<Vec<String>> = table.regions.iter().map(|r| cells(r, false)).collect();
            let widths: Vec<usize> = (0..header.len())
                .map(|i| {
                    body.iter()
                        .filter_map(|r| r.get(i).map(|s| s.chars().count()))
                        .chain([header[i].len()])
                        .max()
                        .unwrap_or(0)
                })
                .collect();
            for line in std::iter::once(&header).chain(&body) {
                let padded: Vec<String> = line
                    .iter()
                    .zip(&widths)
                    .enumerate()
                    .map(|(i, (s, &w))| {
                        let pad = w.saturating_sub(s.chars().count());
                        // The region name reads best left-aligned, numbers right-aligned.
                        if i == 0 {
                            format!("{s}{}", " ".repeat(pad))
                        } else {
                            format!("{}{s}", " ".repeat(pad))
                        }
                    })
                    .collect();
                let _ = writeln!(out, "{}", padded.join("  ").trim_end());
            }
        }
        TableFormat::Csv => {
            let _ = writeln!(out, "{}", header.join(","));
            for row in &table.regions {
                let c: Vec<String> = cells(row, true).into_iter().map(csv_field).collect();
                let _ = writeln!(out, "{}", c.join(","));
            }
        }
        TableFormat::Ron => {
            out =
                irsig_formats::canonical::to_ron_at_depth(table, 3).map_err(|e| miette!("{e}"))?;
        }
    }
    Ok(out)
}

/// A CSV field, quoted when it holds a comma, a quote or a line break (RFC 4180).
fn csv_field(s: String) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_regions::Compared;

    fn table() -> Table {
        Table {
            values: "test".into(),
            unit: "degC".into(),
            references: vec![
                ("paper".into(), "Table 7".into()),
                ("other".into(), String::new()),
            ],
            regions: vec![Row {
                region: "Left, Pool".into(),
                pixels: 12,
                mean: 10.0,
                std_dev: 0.25,
                min: 9.5,
                max: 10.5,
                references: vec![
                    Some(Compared {
                        reference: 9.62,
                        difference: 0.38,
                    }),
                    None,
                ],
            }],
        }
    }

    #[test]
    fn text_csv_and_ron_carry_the_same_row() {
        let t = table();
        let text = render(&t, TableFormat::Table).unwrap();
        assert!(text.starts_with("# values: test (degC)\n# paper: Table 7\n"));
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[3].starts_with("region"));
        assert!(lines[3].contains("paper_c") && lines[3].contains("mean_minus_paper_k"));
        assert!(lines[4].starts_with("Left, Pool"));
        assert!(lines[4].contains("9.62") && lines[4].contains("+0.38"));
        assert!(lines[4].trim_end().ends_with('-'));

        let csv = render(&t, TableFormat::Csv).unwrap();
        let mut l = csv.lines();
        assert_eq!(
            l.next(),
            Some(
                "region,pixels,mean_c,std_dev_k,min_c,max_c,paper_c,mean_minus_paper_k,\
                 other_c,mean_minus_other_k"
            )
        );
        assert_eq!(
            l.next(),
            Some("\"Left, Pool\",12,10,0.25,9.5,10.5,9.62,0.38,,")
        );

        let ron_text = render(&t, TableFormat::Ron).unwrap();
        let v: ron::Value = ron::from_str(&ron_text).unwrap();
        let again = format!("{v:?}");
        assert!(again.contains("Left, Pool") && again.contains("9.62"));
    }
}
