//! `irsig-material fresnel`: an angular emissivity table of an opaque surface, smooth or
//! rough (`--roughness`), from its complex refractive index, as a canonical material
//! library entry or a legacy `.ems`.

use std::io::Write;
use std::path::{Path, PathBuf};

use irsig_cli::args::band::Wavelengths;
use irsig_cli::args::outputs::{Legacy, Name, Output};
use irsig_cli::args::{BandArg, BandArgs, values};
use irsig_model::{Material, MaterialId, MaterialLibrary, SpectralAngular, SpectralEmissivity};
use irsig_radiometry::EmissivityTable;
use irsig_radiometry::fresnel::{
    ComplexIndex, FacetTable, IndexTable, RoughSurface, RoughView, rough_band_emissivity_table,
    rough_emissivity_table,
};
use miette::miette;
use rayon::prelude::*;

/// Arguments of `fresnel`.
#[derive(Debug, clap::Args)]
#[command(
    mut_arg("band", |a| a.help(
        "The band of the spectral average: MIN-MAX in micrometres (flat response) or a \
         sensor response file (formats/srf.md) [default: 8-14]"
    )),
    mut_arg("legacy", |a| a.help(
        "Write a legacy `.ems` (also chosen by an `-o` name ending in `.ems`): the \
         band-averaged angular table only, since the 1990 format has no wavelength axis to \
         carry the spectrum of an `--nk-table`"
    )),
    mut_arg("name", |a| a.help(
        "Material name in the library entry [default: the nk table's file stem, else \
         `fresnel`]"
    )),
    mut_arg("output", |a| a.help("Output file (stdout when absent or `-`)")),
)]
pub struct Args {
    /// Real part of a constant refractive index (> 0).
    #[arg(
        long,
        allow_hyphen_values = true,
        required_unless_present = "nk_table",
        conflicts_with = "nk_table"
    )]
    pub n: Option<f64>,
    /// Extinction coefficient (imaginary part, ≥ 0) of a constant index.
    #[arg(
        long,
        allow_hyphen_values = true,
        default_value_t = 0.0,
        conflicts_with = "nk_table"
    )]
    pub k: f64,
    /// A table of `wavelength_um n k` rows (formats/nk.md); `-` for stdin. The angular
    /// table is then averaged over the band with Planck weighting at `--planck-temperature`, and
    /// the library entry keeps the spectrum too: ε(λ) at normal incidence at the table's
    /// wavelengths (`spectral`), which a tracer averages over its own band or sub-bands.
    #[arg(long, value_name = "FILE")]
    pub nk_table: Option<PathBuf>,
    /// With `--nk-table`: write the band-averaged angular table only, without the spectrum
    /// (a band-only material, as a legacy `.ems` always is; needed for `irsig-trace --band
    /// total`, which cannot average a spectrum).
    #[arg(long, requires = "nk_table")]
    pub band_only: bool,
    /// `--band`: a band with wavelengths.
    #[command(flatten)]
    pub band: BandArgs<Wavelengths>,
    /// Temperature of the Planck weighting, K: the surface temperature the table is made
    /// for [default: 300].
    #[arg(long, value_name = "K", allow_hyphen_values = true)]
    pub planck_temperature: Option<f64>,
    /// Angles from the surface normal, deg: a list `a,b,c` or a range `from:to:step`,
    /// 0–90, increasing. Include 90 (ε = 0) so interpolation reaches grazing.
    #[arg(long, default_value = "0:90:1", allow_hyphen_values = true)]
    pub angles: String,
    /// `--legacy`: a `.ems`.
    #[command(flatten)]
    pub legacy: Legacy,
    /// `--name`: the material's.
    #[command(flatten)]
    pub name: Name,
    /// Material id in the library entry (1–65535).
    #[arg(long, default_value_t = 1)]
    pub id: u16,
    /// RMS slope of the surface's facets: dimensionless, the tangent of their tilt
    /// (σ² = <z_x² + z_y²>, Cox & Munk's parameter; 0 is smooth, 0.1 a lightly rippled
    /// pool, 0.6-1.5 soils and canopies). Fresnel facets with Gaussian slopes, Smith's
    /// shadowing and one reflection (Masuda et al. 1988; Wu & Smith 1997).
    #[arg(
        long,
        default_value_t = 0.0,
        allow_hyphen_values = true,
        value_name = "SLOPE"
    )]
    pub roughness: f64,
    /// Share (0 to below 1) of what enters the surface that its body (grains, leaves,
    /// pigment) returns diffusely; the emissivity is 1 − this times the facets'.
    #[arg(
        long,
        default_value_t = 0.0,
        allow_hyphen_values = true,
        value_name = "SHARE"
    )]
    pub diffuse_reflectance: f64,
    /// Fraction of the reflection that is specular (0 diffuse – 1 mirror) [default: 1
    /// for a smooth surface (Fresnel's equations describe a mirror), 0 with --roughness
    /// above 0 or a diffuse body].
    #[arg(long, allow_hyphen_values = true)]
    pub specular_fraction: Option<f64>,
    /// `-o PATH`.
    #[command(flatten)]
    pub output: Output,
}

fn legacy_by_name(path: Option<&Path>) -> bool {
    path.and_then(Path::extension)
        .is_some_and(|e| e.eq_ignore_ascii_case("ems"))
}

/// The flags' own rules, before a file is read (what `irsig-run` asks of a stage too): the
/// angles, the surface, a Planck weighting within
/// [`irsig_model::limits::PLANCK_WEIGHTING_K`] and only for an n, k table.
///
/// # Errors
/// A usage error naming the flag, or a bad value.
pub(crate) fn flags(args: &Args) -> miette::Result<(Vec<f64>, RoughSurface)> {
    // clap's `requires` is waived when a conflicting argument (here --n) is present, so
    // this rule is checked by hand.
    if args.nk_table.is_none() && (args.band.given().is_some() || args.planck_temperature.is_some())
    {
        return Err(irsig_cli::usage_error(
            "--band and --planck-temperature weight the spectral average of --nk-table; \
             a constant --n/--k has none",
        ));
    }
    let [t_min, t_max] = irsig_model::limits::PLANCK_WEIGHTING_K;
    if let Some(t) = args.planck_temperature
        && !(t_min..=t_max).contains(&t)
    {
        // A value out of its range, as --roughness's: bad input, not bad usage.
        return Err(miette!(
            // Debug form: 1e308 as written, not its 309 digits.
            "--planck-temperature {t:?}: the Planck weighting temperature must be from {t_min} \
             to {t_max} K"
        ));
    }
    let angles = values("--angles", &args.angles)?;
    let surface = RoughSurface::new(args.roughness)
        .and_then(|s| s.with_diffuse_reflectance(args.diffuse_reflectance))
        .map_err(|e| miette!("--roughness/--diffuse-reflectance: {e}"))?;
    Ok((angles, surface))
}

/// Runs `irsig-material fresnel`.
///
/// # Errors
/// A bad index or angle list, an unreadable or malformed n, k table or response file, a
/// band the table does not cover, an invalid library entry, or an I/O error; nothing is
/// written then.
pub fn run(args: &Args) -> miette::Result<()> {
    let band_file = args.band.response_file().map(PathBuf::from);
    irsig_cli::refuse_output_is_input(
        args.nk_table.iter().cloned().chain(band_file),
        args.output.path.iter(),
    )?;
    let (angles, surface) = flags(args)?;
    let rough = surface.rms_slope() > 0.0 || surface.diffuse_reflectance() > 0.0;
    let kind = if rough {
        format!(
            "rough opaque surface, RMS slope {} with diffuse reflectance {} (Fresnel facets, \
             Gaussian slopes, Smith shadowing, one reflection: Masuda et al. 1988, Wu & Smith \
             1997; diffuse body: Torrance & Sparrow 1967)",
            surface.rms_slope(),
            surface.diffuse_reflectance()
        )
    } else {
        "smooth opaque surface".to_owned()
    };
    let (table, spectral, band_um, source, default_name) = match (&args.nk_table, args.n) {
        (Some(path), _) => {
            let input = irsig_cli::read_input(path)?;
            let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
            let nk = irsig_formats::nk::parse(&input.name, text)?;
            let first_um = nk.wavelength_um.first().copied().unwrap_or(f64::NAN);
            let index = IndexTable::new(nk.wavelength_um, &nk.n, &nk.k)
                .map_err(|e| miette!("{}: {e}", input.name))?;
            let band_arg = args.band.or_default();
            let band = args.band.load()?;
            let t = args.planck_temperature.unwrap_or(300.0);
            let table =
                rough_band_emissivity_table(&index, &band, t, surface, &angles).map_err(|e| {
                    // A table that does not cover the band ends too early or starts too late:
                    // point at its first or its last row.
                    let rows: Vec<usize> = data_rows(text).collect();
                    let row = if first_um > band.lambda_min_um() {
                        rows.first()
                    } else {
                        rows.last()
                    };
                    miette::Report::new(irsig_formats::ParseError::at_offset(
                        input.name.clone(),
                        text,
                        row.copied().unwrap_or(0),
                        e.to_string(),
                    ))
                })?;
            let srf = match &band_arg {
                BandArg::Response(path) => format!(" weighted by the response {path}"),
                BandArg::Flat { .. } | BandArg::Total => String::new(),
            };
            let spectral = (!args.band_only).then(|| spectrum(&index, surface, &angles));
            let kept = match &spectral {
                None => String::new(),
                Some(s) if s.wavelength_um.len() < index.wavelength_um().len() => format!(
                    "; spectral: the emissivity at normal incidence and at every angle at {} \
                     of the table's {} wavelengths, evenly spread by row",
                    s.wavelength_um.len(),
                    index.wavelength_um().len()
                ),
                Some(_) => "; spectral: the emissivity at the table's wavelengths, at normal \
                            incidence and at every angle"
                    .to_owned(),
            };
            let source = format!(
                "Fresnel, {kind} (irsig-material fresnel): n, k from {} linearly \
                 interpolated, averaged over {}-{} um{srf} with Planck weighting at {t} K{kept}",
                input.name,
                band.lambda_min_um(),
                band.lambda_max_um()
            );
            let stem = input
                .path
                .as_deref()
                .and_then(Path::file_stem)
                .map(|s| s.to_string_lossy().into_owned());
            // The angular table is this band's: a tracer refuses it in another band when
            // there is no spectrum to average (`--band-only`).
            let band_um = Some((band.lambda_min_um(), band.lambda_max_um()));
            (table, spectral, band_um, source, stem)
        }
        (None, Some(n)) => {
            let index = ComplexIndex::new(n, args.k).map_err(|e| miette!("{e}"))?;
            let table = rough_emissivity_table(index, surface, &angles)
                .map_err(|e| miette!("--angles: {e}"))?;
            let source = format!(
                "Fresnel, {kind} (irsig-material fresnel): constant index n = {n}, k = {}",
                args.k
            );
            (table, None, None, source, None)
        }
        (None, None) => return Err(irsig_cli::usage_error("give --n (and --k) or --nk-table")),
    };
    let output = args.output.path.as_deref();
    if args.legacy.on || legacy_by_name(output) {
        write_ems(&table, output)
    } else {
        let name = args
            .name
            .value
            .clone()
            .or(default_name)
            .unwrap_or_else(|| "fresnel".to_owned());
        let specular = args
            .specular_fraction
            .unwrap_or(if rough { 0.0 } else { 1.0 });
        let entry = Entry {
            spectral,
            band_um,
            name,
            specular_fraction: specular,
            source,
            // The facets' slopes are the specular lobe's too (the tracer's glint): one
            // surface for emission and reflection. A smooth surface records none.
            rms_slope: (surface.rms_slope() > 0.0).then_some(surface.rms_slope()),
        };
        write_library(&table, entry, args, output)
    }
}

/// The most wavelengths a spectral entry keeps: a table with more rows (a million) keeps
/// that many of them, evenly spread by row (first and last among them), so that the entry
/// stays a file a tracer reads in a moment (91 angles at a million rows would be 1.8 GB of
/// RON) and its cost is bounded. At 16,384 rows over 2-20 um the kept rows are about 1 nm
/// apart, finer than a solid's optical constants vary in the thermal infrared.
const MAX_SPECTRUM_ROWS: usize = 16_384;
/// The same for a rough surface, each of whose emissivities averages over a thousand facet
/// classes' Fresnel emissivities: 512 rows, about 12 nm apart over 8-14 um (a solid's
/// reststrahlen features are tenths of a micrometre wide).
const MAX_ROUGH_SPECTRUM_ROWS: usize = 512;

/// The rows a spectrum keeps of a table of `n` rows: all, or `max` evenly spread by row.
fn spectrum_rows(n: usize, max: usize) -> Vec<usize> {
    if n <= max {
        (0..n).collect()
    } else {
        (0..max).map(|k| k * (n - 1) / (max - 1)).collect()
    }
}

/// The spectrum: the Fresnel equations at normal incidence, and at every angle of
/// `--angles`, on the table's rows (at most [`MAX_SPECTRUM_ROWS`] of them, or
/// [`MAX_ROUGH_SPECTRUM_ROWS`] for a rough surface). With it a tracer takes the emissivity
/// at each wavelength (a Fresnel surface's angular shape changes with wavelength, which a
/// separable form misses by up to 0.08 in ε at 80° in one sixteenth of 8–14 µm:
/// docs/accuracy.md, "Fresnel emissivity"). Rows in parallel, each the same at any thread
/// count; each view's facet classes found once, and for a rough surface each row's facet
/// emissivities read from one [`FacetTable`] (within 1e-7 of evaluating each).
fn spectrum(index: &IndexTable, surface: RoughSurface, angles: &[f64]) -> SpectralEmissivity {
    let rough = surface.rms_slope() > 0.0;
    let max = if rough {
        MAX_ROUGH_SPECTRUM_ROWS
    } else {
        MAX_SPECTRUM_ROWS
    };
    let rows = spectrum_rows(index.wavelength_um().len(), max);
    let normal = surface.view(0.0);
    let views: Vec<RoughView> = angles.iter().map(|&a| surface.view(a)).collect();
    let values: Vec<(f64, Vec<f64>)> = rows
        .par_iter()
        .map(|&i| {
            let at = index.index()[i];
            if rough {
                // Each facet class read from one table of the row's index: a thousand
                // classes a view otherwise cost a Fresnel evaluation each.
                let table = FacetTable::new(at);
                (
                    normal.emissivity_from(&table),
                    views.iter().map(|v| v.emissivity_from(&table)).collect(),
                )
            } else {
                (
                    normal.emissivity(at),
                    views.iter().map(|v| v.emissivity(at)).collect(),
                )
            }
        })
        .collect();
    let (emissivity, angular) = values.into_iter().unzip();
    SpectralEmissivity {
        wavelength_um: rows.iter().map(|&i| index.wavelength_um()[i]).collect(),
        emissivity,
        angular: Some(SpectralAngular {
            angle_deg: angles.to_vec(),
            emissivity: angular,
        }),
    }
}

fn pairs(table: &EmissivityTable) -> Vec<(f64, f64)> {
    table
        .angle_deg()
        .iter()
        .copied()
        .zip(table.emissivity().iter().copied())
        .collect()
}

fn write_ems(table: &EmissivityTable, output: Option<&Path>) -> miette::Result<()> {
    let ems = irsig_formats::legacy::ems::EmsTable::from_pairs(&pairs(table));
    let text = irsig_formats::legacy::ems::write(&ems).map_err(|e| miette!("{e}"))?;
    irsig_cli::write_output(output, |w: &mut dyn Write| w.write_all(text.as_bytes()))
}

/// What a library entry carries beside its angular table.
struct Entry {
    spectral: Option<SpectralEmissivity>,
    band_um: Option<(f64, f64)>,
    name: String,
    specular_fraction: f64,
    source: String,
    rms_slope: Option<f64>,
}

fn write_library(
    table: &EmissivityTable,
    entry: Entry,
    args: &Args,
    output: Option<&Path>,
) -> miette::Result<()> {
    let library = MaterialLibrary {
        materials: vec![Material {
            id: MaterialId(args.id),
            name: entry.name,
            emissivity: pairs(table),
            specular_fraction: entry.specular_fraction,
            source: entry.source,
            band_um: entry.band_um,
            spectral: entry.spectral,
            rms_slope: entry.rms_slope,
            thermal: None,
            texture: None,
            maps: None,
        }],
    };
    // The model's own rules (id 0 reserved, specular fraction in [0, 1], a name).
    library
        .validate()
        .map_err(|e| miette!("the material library entry is not valid: {e}"))?;
    let text = irsig_formats::canonical::to_ron(&library).map_err(|e| miette!("{e}"))?;
    irsig_cli::write_output(output, |w: &mut dyn Write| w.write_all(text.as_bytes()))
}

/// The byte offsets of the rows of a table's `text`: its lines that are neither blank nor
/// comments, at their first character.
fn data_rows(text: &str) -> impl Iterator<Item = usize> + '_ {
    let mut offset = 0;
    text.split_inclusive('\n').filter_map(move |line| {
        let at = offset;
        offset += line.len();
        let t = line.trim_start();
        (!t.is_empty() && !t.starts_with('#')).then(|| at + (line.len() - t.len()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_spectrum_keeps_every_row_of_a_table_up_to_its_cap_and_spreads_them_beyond() {
        assert_eq!(
            spectrum_rows(300, MAX_SPECTRUM_ROWS),
            (0..300).collect::<Vec<_>>()
        );
        for n in [MAX_SPECTRUM_ROWS + 1, 20_000, 1_000_000] {
            let rows = spectrum_rows(n, MAX_SPECTRUM_ROWS);
            assert_eq!(rows.len(), MAX_SPECTRUM_ROWS);
            assert_eq!((rows[0], rows[rows.len() - 1]), (0, n - 1));
            assert!(rows.windows(2).all(|w| w[0] < w[1]));
            // Evenly spread: no gap more than one row wider than another.
            let gaps: Vec<usize> = rows.windows(2).map(|w| w[1] - w[0]).collect();
            let (lo, hi) = (gaps.iter().min().unwrap(), gaps.iter().max().unwrap());
            assert!(hi - lo <= 1, "{n}: gaps {lo} to {hi}");
        }
    }
}
