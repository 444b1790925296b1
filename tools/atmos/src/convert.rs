//! `irsig-atmos convert`: legacy DIRTRAN tables (thesis Figure 9) to and from the canonical
//! atmosphere file, with the legacy units stated on the command line and every table
//! validated (altitudes increase; 0 ≤ τ ≤ 1; angles in 0–90° and increasing; radiances
//! ≥ 0). Material files (the index and its `.ems` tables) are `irsig-material`'s.

use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use irsig_atmosphere::legacy::{
    ConvertOptions, DirtranTables, LegacyUnits, from_atmosphere, to_atmosphere,
};
use irsig_cli::args::BandArgs;
use irsig_cli::args::band::Flat;
use irsig_cli::args::outputs::{Name, Output, ToLegacyArgs};
use irsig_formats::legacy::{atm, cor, dwr, rsd, rtt};
use irsig_model::{Atmosphere, SlantTables};
use miette::{IntoDiagnostic, Report, WrapErr};

/// Arguments of `irsig-atmos convert`.
#[derive(Debug, Clone, Args)]
#[command(after_help = "\
Examples:
  # DIRTRAN tables (km, W cm^-2 sr^-1) to a canonical atmosphere
  irsig-atmos convert --atm us.atm --cor us.cor --dwr us.dwr --rtt us.rtt \\
      --altitude-unit km --radiance-unit W/cm2/sr --cor-altitude-m 1000 \\
      --name us-std-1976 --source 'LOWTRAN7 model 6' -o us-std-1976.ron

  # a canonical atmosphere (or a built-in) back to DIRTRAN tables us.atm us.cor us.dwr ...
  irsig-atmos convert --to-legacy us-std-1976.ron --altitude-unit km \\
      --radiance-unit W/cm2/sr --out-dir legacy/ --stem us

Material files (the index and its .ems tables) convert with irsig-material convert.",
    mut_arg("band", |a| a.help(
        "The band the tables were integrated over: MIN-MAX in micrometres, a flat band \
         [default: 8-14]"
    )),
    mut_arg("name", |a| a
        .required_unless_present("to_legacy")
        .help("Name of the atmosphere")),
    mut_arg("output", |a| a
        .conflicts_with("to_legacy")
        .help("Output canonical atmosphere (stdout when absent or `-`)")),
    mut_arg("to_legacy", |a| a.help(
        "Convert the other way: this canonical atmosphere (a file, `-`, or `builtin:NAME`) \
         to DIRTRAN tables"
    )),
    mut_arg("out_dir", |a| a.help("Directory for the legacy files written by `--to-legacy`")),
    mut_arg("stem", |a| a.help(
        "File stem of the DIRTRAN tables written by `--to-legacy` (default: the name)"
    )),
)]
pub struct ConvertArgs {
    /// The `.atm` table (altitude ASL, T in K, altitude above ground, τ, L_u).
    #[arg(
        long,
        value_name = "FILE",
        required_unless_present = "to_legacy",
        conflicts_with = "to_legacy"
    )]
    pub atm: Option<String>,
    /// The `.cor` coefficients a1 a2 a3 (thesis eq. 10).
    #[arg(long, value_name = "FILE", conflicts_with = "to_legacy")]
    pub cor: Option<String>,
    /// The altitude in metres the `.cor` was fitted at (the format does not say; the
    /// LOWTRAN7 reference tables use 1000). Lets the models scale the correction to other
    /// altitudes; without it the thesis model applies it unchanged at every altitude.
    #[arg(long, value_name = "METRES", requires = "cor")]
    pub cor_altitude_m: Option<f64>,
    /// The `.dwr` sky table (zenith angle, L_d; `-1` row = hemispheric).
    #[arg(
        long,
        value_name = "FILE",
        required_unless_present = "to_legacy",
        conflicts_with = "to_legacy"
    )]
    pub dwr: Option<String>,
    /// The `.rtt` temperature → band radiance table.
    #[arg(long, value_name = "FILE", conflicts_with = "to_legacy")]
    pub rtt: Option<String>,
    /// The `.rsd` radiosonde.
    #[arg(long, value_name = "FILE", conflicts_with = "to_legacy")]
    pub rsd: Option<String>,
    /// Slant tables (canonical `SlantTables` RON, SI) from scripts/atmosphere/regen.py.
    #[arg(long, value_name = "FILE", conflicts_with = "to_legacy")]
    pub slant: Option<String>,
    /// Unit of every altitude in the legacy tables (DIRTRAN wrote km).
    #[arg(long, value_enum)]
    pub altitude_unit: AltitudeUnit,
    /// Unit of every radiance in the legacy tables (DIRTRAN wrote W/cm2/sr; the thesis
    /// text once says W/m2/sr for the `.rtt`, so it must be stated).
    #[arg(long, value_enum)]
    pub radiance_unit: RadianceUnit,
    /// `--name`: of the atmosphere.
    #[command(flatten)]
    pub name: Name,
    /// Where the numbers come from (model, version, settings).
    #[arg(
        long,
        default_value = "DIRTRAN tables converted by irsig-atmos convert"
    )]
    pub source: String,
    /// `--band`: a flat band.
    #[command(flatten)]
    pub band: BandArgs<Flat>,
    /// `-o PATH`: the canonical atmosphere.
    #[command(flatten)]
    pub output: Output,
    /// `--to-legacy FILE`, `--out-dir`, `--stem`.
    #[command(flatten)]
    pub legacy: ToLegacyArgs,
}

/// A legacy altitude unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AltitudeUnit {
    /// Kilometres.
    Km,
    /// Metres.
    M,
}

/// A legacy radiance unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum RadianceUnit {
    /// W cm⁻² sr⁻¹.
    #[value(name = "W/cm2/sr")]
    WCm2Sr,
    /// W m⁻² sr⁻¹.
    #[value(name = "W/m2/sr")]
    WM2Sr,
}

impl ConvertArgs {
    fn units(&self) -> LegacyUnits {
        LegacyUnits {
            metres_per_altitude_unit: match self.altitude_unit {
                AltitudeUnit::Km => 1000.0,
                AltitudeUnit::M => 1.0,
            },
            si_per_radiance_unit: match self.radiance_unit {
                RadianceUnit::WCm2Sr => 1e4,
                RadianceUnit::WM2Sr => 1.0,
            },
        }
    }
}

/// Runs `irsig-atmos convert`.
///
/// # Errors
/// A missing or malformed table (file, line, column and what was expected), a converted
/// atmosphere that breaks a rule, or an I/O error; nothing is written then.
pub fn run(args: &ConvertArgs) -> miette::Result<()> {
    match &args.legacy.file {
        Some(input) => to_legacy(args, input),
        None => from_legacy(args),
    }
}

fn read_text(path: &str) -> miette::Result<(String, String)> {
    let input = irsig_cli::read_input(path)?;
    let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)
        .map_err(Report::new)?
        .to_owned();
    Ok((input.name, text))
}

fn from_legacy(args: &ConvertArgs) -> miette::Result<()> {
    let (Some(atm_path), Some(dwr_path), Some(name)) = (&args.atm, &args.dwr, &args.name.value)
    else {
        return Err(irsig_cli::usage_error(
            "--atm, --dwr and --name are required unless --to-legacy is given",
        ));
    };
    let inputs = [
        &args.atm,
        &args.cor,
        &args.dwr,
        &args.rtt,
        &args.rsd,
        &args.slant,
    ];
    irsig_cli::refuse_output_is_input(inputs.into_iter().flatten(), args.output.path.iter())?;
    let (file, text) = read_text(atm_path)?;
    let atm_table = atm::parse(&file, &text).map_err(Report::new)?;
    let (file, text) = read_text(dwr_path)?;
    let dwr_table = dwr::parse(&file, &text).map_err(Report::new)?;
    let mut tables = DirtranTables {
        atm: atm_table.to_rows(),
        dwr: dwr_table.to_pairs(),
        ..DirtranTables::default()
    };
    if let Some(h) = dwr_table.hemispheric_w_cm2_sr {
        tables.dwr.push((-1.0, h));
    }
    if let Some(p) = &args.cor {
        let (file, text) = read_text(p)?;
        tables.cor = Some(cor::parse(&file, &text).map_err(Report::new)?.coefficients);
    }
    if let Some(p) = &args.rtt {
        let (file, text) = read_text(p)?;
        tables.rtt = rtt::parse(&file, &text).map_err(Report::new)?.to_pairs();
    }
    if let Some(p) = &args.rsd {
        let (file, text) = read_text(p)?;
        tables.rsd = rsd::parse(&file, &text).map_err(Report::new)?.to_rows();
    }
    let slant = match &args.slant {
        Some(p) => {
            let (file, text) = read_text(p)?;
            let s: SlantTables =
                irsig_formats::canonical::from_ron_as(&file, &text, "slant tables")
                    .map_err(Report::new)?;
            Some(s)
        }
        None => None,
    };
    if let Some(h) = args.cor_altitude_m {
        if !(h.is_finite() && h >= 0.0) {
            return Err(irsig_cli::usage_error(format!(
                "--cor-altitude-m must be a finite altitude ≥ 0 m, found {h}"
            )));
        }
    }
    let options = ConvertOptions {
        name: name.clone(),
        source: args.source.clone(),
        band_um: args.band.limits_um()?,
        units: args.units(),
        cor_altitude_m: args.cor_altitude_m,
        slant,
    };
    let atmosphere = to_atmosphere(&tables, &options)
        .map_err(|e| miette::miette!("the converted atmosphere is invalid: {e}"))?;
    let text = irsig_formats::canonical::to_ron(&atmosphere)
        .into_diagnostic()
        .wrap_err("cannot write RON")?;
    irsig_cli::write_output(args.output.path.as_deref(), |w| {
        w.write_all(text.as_bytes())
    })
}

fn to_legacy(args: &ConvertArgs, input: &str) -> miette::Result<()> {
    let atmosphere: Atmosphere = match input.strip_prefix("builtin:") {
        Some(name) => irsig_atmosphere::builtin(name).map_err(|e| miette::miette!("{e}"))?,
        None => {
            let input = irsig_cli::read_input(input)?;
            irsig_formats::canonical::from_ron_bytes(&input.name, &input.bytes)
                .map_err(Report::new)?
        }
    };
    let t = from_atmosphere(&atmosphere, args.units());
    let stem = args
        .legacy
        .stem
        .clone()
        .unwrap_or_else(|| atmosphere.name.clone());
    if stem.is_empty() || stem.contains(['/', '\\']) {
        return Err(irsig_cli::usage_error(format!(
            "--stem must be a plain file stem, found `{stem}`"
        )));
    }
    let path = |ext: &str| args.legacy.out_dir.join(format!("{stem}.{ext}"));
    let werr = |what: &str, e: irsig_formats::legacy::WriteError| {
        miette::miette!("cannot write the {what}: {e}")
    };
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let atm_table = atm::AtmTable::from_rows(&t.atm);
    files.push((
        path("atm"),
        atm::write(&atm_table)
            .map_err(|e| werr(".atm", e))?
            .into_bytes(),
    ));
    if let Some(c) = t.cor {
        let f = cor::CorFile {
            coefficients: c,
            position: Default::default(),
        };
        files.push((
            path("cor"),
            cor::write(&f).map_err(|e| werr(".cor", e))?.into_bytes(),
        ));
    }
    let dwr_table = dwr::DwrTable {
        rows: t
            .dwr
            .iter()
            .filter(|r| r.0 >= 0.0)
            .map(|&(zenith_deg, radiance_w_cm2_sr)| dwr::DwrRow {
                zenith_deg,
                radiance_w_cm2_sr,
                position: Default::default(),
            })
            .collect(),
        hemispheric_w_cm2_sr: t.dwr.iter().find(|r| r.0 < 0.0).map(|r| r.1),
        hemispheric_position: None,
    };
    files.push((
        path("dwr"),
        dwr::write(&dwr_table)
            .map_err(|e| werr(".dwr", e))?
            .into_bytes(),
    ));
    if !t.rtt.is_empty() {
        let table = rtt::RttTable {
            rows: t
                .rtt
                .iter()
                .map(|&(temperature_k, radiance_w_cm2_sr)| rtt::RttRow {
                    temperature_k,
                    radiance_w_cm2_sr,
                    position: Default::default(),
                })
                .collect(),
        };
        files.push((
            path("rtt"),
            rtt::write(&table)
                .map_err(|e| werr(".rtt", e))?
                .into_bytes(),
        ));
    }
    if !t.rsd.is_empty() {
        let table = rsd::RsdTable::from_rows(&t.rsd);
        files.push((
            path("rsd"),
            rsd::write(&table)
                .map_err(|e| werr(".rsd", e))?
                .into_bytes(),
        ));
    }
    if let Some(s) = &atmosphere.slant {
        let text = irsig_formats::canonical::to_ron_pretty(s).into_diagnostic()?;
        files.push((path("slant.ron"), text.into_bytes()));
    }
    if !Path::new(&args.legacy.out_dir).is_dir() {
        return Err(miette::miette!(
            "output directory {} does not exist",
            args.legacy.out_dir.display()
        ));
    }
    irsig_cli::refuse_output_is_input([input], files.iter().map(|(p, _)| p))?;
    irsig_cli::write_files_atomic(&files)
}
