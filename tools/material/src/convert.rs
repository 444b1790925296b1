//! `irsig-material convert`: the 1990 material index file and the `.ems` tables it names
//! (thesis §3.2.2, §4.1, Appendix H `emis_type`) to a canonical material library, and
//! `--to-legacy` back.
//!
//! Each index entry `index name [file.ems [0|1]]` becomes a material with id = index,
//! the `.ems` rows as its angular emissivity (validated by the `.ems` parser: 0 ≤ ε ≤ 1,
//! angles 0–90° strictly increasing) and specular fraction 0 or 1 from the flag. An `.ems`
//! table is one band's emissivity and does not say which band: `--band` does, 8–14 µm
//! (the thesis's) when it is not given, which stderr then says; the material records it
//! (`band_um`), so that a trace in another band is refused rather than given 8–14 µm
//! values (formats/canonical/material-library.md). An entry
//! without an `.ems` file is an error naming its line, unless `--default-emissivity E`
//! says which constant emissivity such materials get; the material's `source` records
//! which happened. Back to legacy, a library is written as `STEM.mat` plus `NAME.ems` per
//! material; a specular fraction strictly between 0 and 1 has no legacy form and is an
//! error rather than a silent rounding.

use std::path::{Path, PathBuf};

use irsig_cli::args::BandArgs;
use irsig_cli::args::band::Flat;
use irsig_cli::args::outputs::{Output, ToLegacyArgs};
use irsig_formats::ParseError;
use irsig_formats::legacy::{Position, ems, material_index};
use irsig_model::{Material, MaterialId, MaterialLibrary};
use miette::{IntoDiagnostic, Report, WrapErr};

/// Arguments of `irsig-material convert`.
#[derive(Debug, Clone, clap::Args)]
#[command(after_help = "\
Examples:
  # the 1990 material index file and the .ems tables it names to a material library;
  # entries without an .ems file get the constant emissivity 0.9
  irsig-material convert materials.mat --default-emissivity 0.9 -o lib.ron

  # .ems tables made for 3-5 um (irsig-material fresnel --band 3-5 --legacy)
  irsig-material convert mwir.mat --band 3-5 -o mwir.ron

  # a material library back to legacy/materials.mat plus legacy/NAME.ems per material
  irsig-material convert --to-legacy lib.ron --out-dir legacy/",
    mut_arg("band", |a| a.conflicts_with("to_legacy").help(
        "The band the `.ems` tables are band emissivities for, MIN-MAX in micrometres: an \
         `.ems` file does not record it. Each converted material records it, and a trace in \
         another band refuses the material [default: 8-14, the thesis's band, said on stderr]"
    )),
    mut_arg("output", |a| a
        .conflicts_with("to_legacy")
        .help("Output canonical material library (stdout when absent or `-`)")),
    mut_arg("to_legacy", |a| a.help(
        "Convert the other way: this canonical material library (a file or `-`) to a \
         material index file (`STEM.mat`) and one `NAME.ems` per material in `--out-dir`"
    )),
    mut_arg("out_dir", |a| a.help("Directory for the legacy files written by `--to-legacy`")),
    mut_arg("stem", |a| a.help(
        "File stem of the material index written by `--to-legacy` [default: materials]"
    )),
)]
pub struct ConvertArgs {
    /// The 1990 material index file (`index name [file.ems [0|1]]` per line), or `-`,
    /// converted with the `.ems` tables it names to a canonical material library.
    #[arg(
        value_name = "INDEX",
        required_unless_present = "to_legacy",
        conflicts_with = "to_legacy"
    )]
    pub index: Option<String>,
    /// The directory the index's `.ems` file names are relative to (default: the index
    /// file's directory).
    #[arg(long, value_name = "DIR", conflicts_with = "to_legacy")]
    pub ems_dir: Option<PathBuf>,
    /// The constant emissivity (0–1, at every angle) of materials the index gives no
    /// `.ems` file. Without it such a material is an error.
    #[arg(long, value_name = "E", conflicts_with = "to_legacy")]
    pub default_emissivity: Option<f64>,
    /// `--band`: a flat band.
    #[command(flatten)]
    pub band: BandArgs<Flat>,
    /// `-o PATH`: the material library.
    #[command(flatten)]
    pub output: Output,
    /// `--to-legacy LIBRARY`, `--out-dir`, `--stem`.
    #[command(flatten)]
    pub legacy: ToLegacyArgs,
}

/// Runs `irsig-material convert`.
///
/// # Errors
/// As [`from_legacy`] and [`to_legacy`].
pub fn run(args: &ConvertArgs) -> miette::Result<()> {
    match (&args.legacy.file, &args.index) {
        (Some(library), _) => to_legacy(args, library),
        (None, Some(index)) => from_legacy(args, index),
        (None, None) => Err(irsig_cli::usage_error(
            "give a material index file, or --to-legacy LIBRARY",
        )),
    }
}

/// The material index (and its `.ems` tables) to a canonical material library.
///
/// # Errors
/// A malformed index or `.ems` file (file, line, column), a missing `.ems` file (the index
/// line naming it), an entry without `.ems` and no `--default-emissivity`, a library that
/// breaks a model rule; nothing is written then.
pub fn from_legacy(args: &ConvertArgs, index_path: &str) -> miette::Result<()> {
    let default = match args.default_emissivity {
        Some(e) if !(0.0..=1.0).contains(&e) => {
            return Err(irsig_cli::usage_error(format!(
                "--default-emissivity must lie in 0–1, found {e}"
            )));
        }
        other => other,
    };
    let [min_um, max_um] = args.band.limits_um()?;
    let band_um = (min_um, max_um);
    let input = irsig_cli::read_input(index_path)?;
    let text = irsig_formats::canonical::utf8(&input.name, &input.bytes).map_err(Report::new)?;
    let index = material_index::parse(&input.name, text).map_err(Report::new)?;
    let ems_dir = args.ems_dir.clone().unwrap_or_else(|| input.base_dir());
    let at = |p: Position, message: String| {
        Report::new(ParseError::at_line_column(
            &input.name,
            text,
            p.line,
            p.column,
            message,
        ))
    };
    let mut materials = Vec::with_capacity(index.materials.len());
    if args.band.given().is_none() && index.materials.iter().any(|m| m.ems_file.is_some()) {
        irsig_cli::note!(
            "irsig-material: {}: the .ems tables are taken as 8-14 um band emissivities, the \
             thesis's band (an .ems file does not record its band); give --band MIN-MAX if \
             they were made for another",
            input.name
        );
    }
    for entry in &index.materials {
        let (emissivity, source) = match (&entry.ems_file, default) {
            (Some(file), _) => {
                let path = ems_dir.join(file);
                let ems_input = irsig_cli::read_input(&path).map_err(|e| {
                    e.wrap_err(format!(
                        "{}:{}: material `{}` names the .ems file {}, which cannot be read",
                        input.name,
                        entry.position,
                        entry.name,
                        path.display()
                    ))
                })?;
                let ems_text = irsig_formats::canonical::utf8(&ems_input.name, &ems_input.bytes)
                    .map_err(Report::new)?;
                let table = ems::parse(&ems_input.name, ems_text).map_err(Report::new)?;
                (
                    table.to_pairs(),
                    format!(
                        "material index {} line {}, emissivity from {}",
                        input.name, entry.position.line, ems_input.name
                    ),
                )
            }
            (None, Some(e)) => (
                vec![(0.0, e)],
                format!(
                    "material index {} line {}, no .ems file: constant emissivity {e} from \
                     --default-emissivity",
                    input.name, entry.position.line
                ),
            ),
            (None, None) => {
                return Err(at(
                    entry.position,
                    format!(
                        "material `{}` (index {}) names no .ems file, so its emissivity is \
                         unknown",
                        entry.name, entry.index
                    ),
                )
                .wrap_err("add its .ems file to the index, or give --default-emissivity E"));
            }
        };
        materials.push(Material {
            id: MaterialId(entry.index),
            name: entry.name.clone(),
            emissivity,
            specular_fraction: if entry.specular { 1.0 } else { 0.0 },
            source,
            // A constant from --default-emissivity is the same in every band.
            band_um: entry.ems_file.is_some().then_some(band_um),
            spectral: None,
            rms_slope: None,
            thermal: None,
            texture: None,
            maps: None,
        });
    }
    let library = MaterialLibrary { materials };
    // The parsers already enforce the model's rules; this is the last line of defence and
    // names the entry if a rule ever diverges.
    if let Err(e) = library.validate() {
        let entry = e
            .path
            .strip_prefix("materials[")
            .and_then(|r| r.split(']').next())
            .and_then(|i| i.parse::<usize>().ok())
            .and_then(|i| index.materials.get(i));
        let p = entry.map_or(Position { line: 1, column: 1 }, |m| m.position);
        return Err(at(
            p,
            format!(
                "the converted material library is invalid: `{}`: {}",
                e.path, e.kind
            ),
        ));
    }
    let ron = irsig_formats::canonical::to_ron(&library)
        .into_diagnostic()
        .wrap_err("cannot write RON")?;
    let inputs = std::iter::once(PathBuf::from(index_path)).chain(
        index
            .materials
            .iter()
            .filter_map(|m| m.ems_file.as_ref())
            .map(|f| ems_dir.join(f)),
    );
    irsig_cli::refuse_output_is_input(inputs, args.output.path.iter())?;
    irsig_cli::write_output(args.output.path.as_deref(), |w| w.write_all(ron.as_bytes()))
}

/// A canonical material library to `STEM.mat` and one `NAME.ems` per material in
/// `--out-dir`, all or nothing.
///
/// # Errors
/// An unreadable or invalid library, a specular fraction other than 0 or 1, a name the
/// legacy files cannot hold (whitespace, `#`, a number), or an I/O error.
pub fn to_legacy(args: &ConvertArgs, input: &str) -> miette::Result<()> {
    let input = irsig_cli::read_input(input)?;
    let library: MaterialLibrary =
        irsig_formats::canonical::from_ron_bytes(&input.name, &input.bytes).map_err(Report::new)?;
    let stem = args.legacy.stem.as_deref().unwrap_or("materials");
    if stem.is_empty() || stem.contains(['/', '\\']) {
        return Err(irsig_cli::usage_error(format!(
            "--stem must be a plain file stem, found `{stem}`"
        )));
    }
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut entries = Vec::with_capacity(library.materials.len());
    for (i, m) in library.materials.iter().enumerate() {
        // Exactly 0 or 1 is what the legacy flag can say.
        let specular = match m.specular_fraction {
            0.0 => false,
            1.0 => true,
            f => {
                return Err(miette::miette!(
                    "{}: `materials[{i}]` (`{}`): specular_fraction {f} has no legacy form; the \
                     material index file holds only 0 (diffuse) or 1 (specular)",
                    input.name,
                    m.name
                ));
            }
        };
        // The name becomes a file name: nothing that could leave --out-dir.
        if m.name.contains(['/', '\\']) || m.name.starts_with('.') {
            return Err(miette::miette!(
                "{}: `materials[{i}]`: the name `{}` cannot be a legacy .ems file name (no `/`, \\ or \
                 leading `.`)",
                input.name,
                m.name
            ));
        }
        // The .ems format has no band: a table for another band than the thesis's is said,
        // so that converting it back can give it again.
        if let Some((lo, hi)) = m.band_um
            && (lo, hi) != (8.0, 14.0)
        {
            irsig_cli::note!(
                "irsig-material: `{}`: its table is for {lo}-{hi} um, which an .ems file \
                 does not record; convert it back with --band {lo}-{hi}",
                m.name
            );
        }
        let ems_file = format!("{}.ems", m.name);
        let table = ems::EmsTable::from_pairs(&m.emissivity);
        let text = ems::write(&table)
            .map_err(|e| miette::miette!("{}: cannot write {ems_file}: {e}", input.name))?;
        files.push((args.legacy.out_dir.join(&ems_file), text.into_bytes()));
        entries.push(material_index::MaterialEntry {
            index: m.id.0,
            name: m.name.clone(),
            ems_file: Some(ems_file),
            specular,
            position: Position::default(),
        });
    }
    let index = material_index::MaterialIndexFile { materials: entries };
    let text = material_index::write(&index)
        .map_err(|e| miette::miette!("{}: cannot write the material index: {e}", input.name))?;
    files.push((
        args.legacy.out_dir.join(format!("{stem}.mat")),
        text.into_bytes(),
    ));
    if !Path::new(&args.legacy.out_dir).is_dir() {
        return Err(miette::miette!(
            "output directory {} does not exist",
            args.legacy.out_dir.display()
        ));
    }
    irsig_cli::refuse_output_is_input([&input.name], files.iter().map(|(p, _)| p))?;
    irsig_cli::write_files_atomic(&files)
}
