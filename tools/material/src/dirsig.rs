//! `irsig-material dirsig`: a DIRSIG classic `.mat` and the spectral `.ems` curves it
//! names to a canonical material library of spectral materials.
//!
//! Each `MATERIAL_ENTRY` becomes a material with id = `ID`, name = `NAME`, specular
//! fraction = `SPECULAR_FRACTION` (0 when absent) and, from its `.ems`, `spectral` = the
//! mean of the file's curves (DIRSIG picks one per pixel from a texture map; irsig has
//! none) and the angular table = the file's 91 angular factors times that curve's 8–14 µm
//! average at 300 K (the factors alone when the curve does not cover 8–14 µm): the
//! tracer keeps the shape and averages the curve over its own band. A `FILENAME` that
//! cannot be read is an error at its place in the `.mat`; an entry without one is an
//! error unless `--default-emissivity E` gives it a constant, band-only emissivity.
//!
//! An entry whose temperature solver is THERM (`TEMP_SOLVER_NAME = Therm`) gets a thermal
//! record from its block (`irsig_formats::dirsig::therm`: one layer, units converted to
//! SI), with the back boundary `--thermal-back` gives: DIRSIG does not say what lies
//! behind the slab (its `EXPOSED_AREA` has no counterpart in irsig), so the user does.
//! Without `--thermal-back` such an entry is an error, unless `--no-thermal` converts no
//! temperature solver at all. A value irsig cannot represent (`THICKNESS = 0`, a negative
//! `EXPOSED_AREA`) is an error at its place. Other solvers give no thermal record.

use std::path::PathBuf;

use irsig_formats::ParseError;
use irsig_formats::dirsig::{ems, mat, therm};
use irsig_model::thermal::{BackAir, BackBoundary, ThermalProperties};
use irsig_model::{Material, MaterialId, MaterialLibrary, SpectralEmissivity};
use irsig_radiometry::{Band, band_average_emissivity};
use miette::{IntoDiagnostic, Report, WrapErr};

/// Arguments of `irsig-material dirsig`.
#[derive(Debug, Clone, clap::Args)]
#[command(after_help = "\
Examples:
  irsig-material dirsig materials/anadirsig.mat --default-emissivity 0.95 --no-thermal -o lib.ron
  irsig-material dirsig scene.mat --thermal-back adiabatic -o lib.ron
  irsig-material dirsig scene.mat --thermal-back convective:10 -o lib.ron   # outdoor air behind",
    mut_arg("output", |a| a.help("Output canonical material library (stdout when absent or `-`)")),
)]
pub struct Args {
    /// The DIRSIG `.mat` file; the `.ems` files it names are relative to its folder.
    #[arg(value_name = "MAT")]
    pub mat: String,
    /// The constant emissivity (0–1) of entries that name no `.ems` file. Without it such
    /// an entry is an error.
    #[arg(long, value_name = "E")]
    pub default_emissivity: Option<f64>,
    /// What lies behind the slab of every THERM temperature solver converted:
    /// `adiabatic` (nothing crosses it), `temperature:K` (held at K kelvin, deep soil),
    /// `convective:H` (air behind it at the outdoor temperature, H in W m⁻² K⁻¹) or
    /// `convective:H:K` (air held at K). Needed when an entry has a THERM block.
    #[arg(long, value_name = "BACK", conflicts_with = "no_thermal")]
    pub thermal_back: Option<String>,
    /// Convert no temperature solver: the library's materials get no thermal record.
    #[arg(long)]
    pub no_thermal: bool,
    /// `-o PATH`: the material library.
    #[command(flatten)]
    pub output: irsig_cli::args::outputs::Output,
}

/// Runs `irsig-material dirsig`.
///
/// # Errors
/// A malformed `.mat` or `.ems` (file, line, column), an `.ems` that cannot be read (at
/// its `FILENAME` in the `.mat`), an entry without one and no `--default-emissivity`, an
/// `ID` outside 1–65535, curves of one file on different wavelengths, a THERM block
/// without `--thermal-back` or with a value irsig cannot represent; nothing is written.
pub fn run(args: &Args) -> miette::Result<()> {
    let back = checked_options(args)?;
    let input = irsig_cli::read_input(&args.mat)?;
    let text = irsig_formats::canonical::utf8(&input.name, &input.bytes).map_err(Report::new)?;
    let entries = mat::parse(&input.name, text).map_err(Report::new)?;
    let dir = input.base_dir();
    // The .mat and every .ems it names are inputs: none may be the output.
    let ems_files = entries
        .iter()
        .filter_map(|e| e.emissivity_file.as_ref())
        .map(|f| dir.join(&f.value));
    irsig_cli::refuse_output_is_input(
        std::iter::once(PathBuf::from(&args.mat)).chain(ems_files),
        args.output.path.iter(),
    )?;
    let at_span = |span: (usize, usize), message: String| {
        Report::new(ParseError::at_span(
            &input.name,
            text,
            span.0,
            span.1,
            message,
        ))
    };
    let thesis_band = Band::new(8.0, 14.0).map_err(|e| miette::miette!("{e}"))?;
    let mut materials = Vec::with_capacity(entries.len());
    for entry in &entries {
        let id = u16::try_from(entry.id.value)
            .ok()
            .filter(|&i| i > 0)
            .ok_or_else(|| {
                at_span(
                    entry.id.span,
                    format!(
                        "expected a material ID 1 to 65535, found {}",
                        entry.id.value
                    ),
                )
            })?;
        let thermal = entry_thermal(args, back, &input.name, text, entry, id)?;
        let Some(file) = &entry.emissivity_file else {
            let Some(e) = args.default_emissivity else {
                return Err(at_span(
                    entry.id.span,
                    format!(
                        "material `{}` (ID {id}) names no emissivity file, so its emissivity \
                         is unknown: give --default-emissivity E",
                        entry.name
                    ),
                ));
            };
            materials.push(Material {
                id: MaterialId(id),
                name: entry.name.clone(),
                emissivity: vec![(0.0, e)],
                specular_fraction: entry.specular_fraction.unwrap_or(0.0),
                source: format!(
                    "DIRSIG {} ID {id}: no emissivity file, constant {e} from --default-emissivity",
                    input.name
                ),
                band_um: None,
                spectral: None,
                rms_slope: None,
                thermal,
                texture: None,
                maps: None,
            });
            continue;
        };
        let path = dir.join(&file.value);
        // Through the bounded reader, as every file: `FILENAME = /dev/zero` used to be
        // read until memory ran out.
        let bytes = irsig_formats::file::read_file(&path).map_err(|e| {
            at_span(
                file.span,
                format!(
                    "material `{}` names the emissivity file `{}`, which cannot be read ({e})",
                    entry.name,
                    path.display()
                ),
            )
        })?;
        let ems_name = path.display().to_string();
        let ems_text = irsig_formats::canonical::utf8(&ems_name, &bytes).map_err(Report::new)?;
        let curves = ems::parse(&ems_name, ems_text).map_err(Report::new)?;
        let first = &curves.curves[0];
        let n = curves.curves.len() as f64;
        let mut mean = vec![0.0; first.emissivity.len()];
        for c in &curves.curves {
            if c.wavelength_um != first.wavelength_um {
                return Err(Report::new(ParseError::at_line_column(
                    &ems_name,
                    ems_text,
                    c.position.line,
                    c.position.column,
                    "this curve's wavelengths differ from the first curve's: the curves of \
                     one file are averaged, so they must share their wavelengths",
                )));
            }
            for (m, e) in mean.iter_mut().zip(&c.emissivity) {
                *m += e / n;
            }
        }
        let mean: Vec<f64> = mean.into_iter().map(|e| e.clamp(0.0, 1.0)).collect();
        let scale = band_average_emissivity(&first.wavelength_um, &mean, &thesis_band, 300.0)
            .unwrap_or(1.0);
        let emissivity = curves
            .angular_factor
            .iter()
            .enumerate()
            .map(|(k, f)| (k as f64, (f * scale).clamp(0.0, 1.0)))
            .collect();
        materials.push(Material {
            id: MaterialId(id),
            name: entry.name.clone(),
            emissivity,
            specular_fraction: entry.specular_fraction.unwrap_or(0.0),
            source: format!(
                "DIRSIG {} ID {id}, {} (mean of {} curve(s))",
                input.name,
                file.value,
                curves.curves.len()
            ),
            band_um: None,
            spectral: Some(SpectralEmissivity {
                wavelength_um: first.wavelength_um.clone(),
                emissivity: mean,
                // DIRSIG's angular factors are one curve for every wavelength.
                angular: None,
            }),
            rms_slope: None,
            thermal,
            texture: None,
            maps: None,
        });
    }
    let library = MaterialLibrary { materials };
    if let Err(e) = library.validate() {
        return Err(miette::miette!(
            "{}: the converted material library is invalid: `{}`: {}",
            input.name,
            e.path,
            e.kind
        ));
    }
    let ron = irsig_formats::canonical::to_ron(&library)
        .into_diagnostic()
        .wrap_err("cannot write RON")?;
    irsig_cli::write_output(args.output.path.as_deref(), |w| w.write_all(ron.as_bytes()))
}

/// Checks the options' values before anything is read: the default emissivity within 0–1,
/// and the back boundary, which it returns.
///
/// # Errors
/// Bad usage (exit 2), naming the option.
fn checked_options(args: &Args) -> miette::Result<Option<BackBoundary>> {
    if let Some(e) = args.default_emissivity {
        if !(0.0..=1.0).contains(&e) {
            return Err(irsig_cli::usage_error(format!(
                "--default-emissivity must lie in 0–1, found {e}"
            )));
        }
    }
    args.thermal_back
        .as_deref()
        .map(parse_back)
        .transpose()
        .map_err(|why| irsig_cli::usage_error(format!("--thermal-back: {why}")))
}

/// The thermal record of `entry` (ID `id` of the `.mat` named `file`, text `text`): none
/// with `--no-thermal` or without a THERM block; else its block converted, with `back`
/// behind the slab.
///
/// # Errors
/// A THERM block without `--thermal-back`, at its `TEMP_SOLVER_NAME`; what
/// `therm::thermal` refuses.
fn entry_thermal(
    args: &Args,
    back: Option<BackBoundary>,
    file: &str,
    text: &str,
    entry: &mat::Entry,
    id: u16,
) -> miette::Result<Option<ThermalProperties>> {
    if args.no_thermal || !therm::is_therm(entry) {
        return Ok(None);
    }
    let Some(back) = back else {
        let solver = entry.temp_solver.as_ref().and_then(|s| s.name.as_ref());
        let (start, len) = solver.map_or(entry.id.span, |n| n.span);
        return Err(Report::new(ParseError::at_span(
            file,
            text,
            start,
            len,
            format!(
                "material `{}` (ID {id}) has a THERM temperature solver, whose slab DIRSIG \
                 does not say what lies behind (its EXPOSED_AREA has no counterpart in \
                 irsig): give --thermal-back adiabatic, temperature:K, convective:H or \
                 convective:H:K, or --no-thermal to convert without thermal records",
                entry.name
            ),
        )));
    };
    therm::thermal(file, text, entry, back).map_err(Report::new)
}

/// A `--thermal-back` value as a back boundary.
fn parse_back(text: &str) -> Result<BackBoundary, String> {
    let number = |s: &str, what: &str| -> Result<f64, String> {
        match s.trim().parse::<f64>() {
            Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
            _ => Err(format!("expected {what} (a positive number), found `{s}`")),
        }
    };
    let parts: Vec<&str> = text.split(':').collect();
    let back = match parts.as_slice() {
        ["adiabatic"] => BackBoundary::Adiabatic,
        ["temperature", k] => BackBoundary::Temperature {
            temperature_k: number(k, "a temperature in K")?,
        },
        ["convective", h] => BackBoundary::Convective {
            h_w_m2_k: number(h, "a convective coefficient in W m⁻² K⁻¹")?,
            air: BackAir::Outdoor,
        },
        ["convective", h, k] => BackBoundary::Convective {
            h_w_m2_k: number(h, "a convective coefficient in W m⁻² K⁻¹")?,
            air: BackAir::Fixed {
                temperature_k: number(k, "the air's temperature in K")?,
            },
        },
        _ => {
            return Err(format!(
                "expected adiabatic, temperature:K, convective:H or convective:H:K, found \
                 `{text}`"
            ));
        }
    };
    back.validate("--thermal-back")
        .map_err(|e| format!("`{text}`: {}", e.kind))?;
    Ok(back)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_back_boundary_form_parses() {
        assert_eq!(parse_back("adiabatic"), Ok(BackBoundary::Adiabatic));
        assert_eq!(
            parse_back("temperature:288.15"),
            Ok(BackBoundary::Temperature {
                temperature_k: 288.15
            })
        );
        assert_eq!(
            parse_back("convective:10"),
            Ok(BackBoundary::Convective {
                h_w_m2_k: 10.0,
                air: BackAir::Outdoor
            })
        );
        assert_eq!(
            parse_back("convective:2.5:293"),
            Ok(BackBoundary::Convective {
                h_w_m2_k: 2.5,
                air: BackAir::Fixed {
                    temperature_k: 293.0
                }
            })
        );
        for bad in [
            "",
            "insulated",
            "temperature",
            "temperature:-5",
            "temperature:NaN",
            "convective:0",
            "convective:10:20:30",
            "temperature:1e9",
        ] {
            assert!(parse_back(bad).is_err(), "{bad}");
        }
    }
}
