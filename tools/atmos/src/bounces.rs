//! `irsig-atmos bounces`: thesis Appendix A, the apparent temperature of a specular target
//! after 0..N bounces, every background surface alike (Figure A-1).

use irsig_cli::args::Format;
use irsig_radiometry::{Surface, bounce_temperatures};

use crate::common::{BandArgs, Column, diagnostic, fractions, print_table, temperatures};

/// Arguments of `bounces`. Each of the four surface options takes a value, a list
/// `a,b,c` or a range `from:to:step`; every combination is printed.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Target emissivity (0–1).
    #[arg(long, default_value = "0.98", allow_hyphen_values = true)]
    pub target_emissivity: String,
    /// Target temperature, K.
    #[arg(long, allow_hyphen_values = true)]
    pub target_temperature: String,
    /// Background emissivity (0–1).
    #[arg(long, default_value = "0.95", allow_hyphen_values = true)]
    pub background_emissivity: String,
    /// Background temperature, K.
    #[arg(long, default_value = "300", allow_hyphen_values = true)]
    pub background_temperature: String,
    /// Largest number of bounces.
    #[arg(long, default_value_t = 4)]
    pub max: usize,
    #[command(flatten)]
    pub band: BandArgs,
    /// `--format`.
    #[command(flatten)]
    pub format: Format,
}

pub fn run(args: &Args) -> miette::Result<()> {
    if args.max > 1000 {
        return Err(diagnostic(format!(
            "--max: at most 1000 bounces, found {}",
            args.max
        )));
    }
    let band = args.band.load()?;
    let te = fractions("--target-emissivity", &args.target_emissivity)?;
    let tt = temperatures("--target-temperature", &args.target_temperature)?;
    let be = fractions("--background-emissivity", &args.background_emissivity)?;
    let bt = temperatures("--background-temperature", &args.background_temperature)?;
    let mut rows = Vec::new();
    for &e_t in &te {
        for &t_t in &tt {
            for &e_b in &be {
                for &t_b in &bt {
                    let target = Surface {
                        emissivity: e_t,
                        temperature_k: t_t,
                    };
                    let background = Surface {
                        emissivity: e_b,
                        temperature_k: t_b,
                    };
                    let mut row = vec![e_t, t_t, e_b, t_b];
                    row.extend(
                        bounce_temperatures(&band, target, background, args.max)
                            .map_err(diagnostic)?,
                    );
                    rows.push(row);
                }
            }
        }
    }
    let mut columns = vec![
        Column::new("target_emissivity", 4),
        Column::new("target_temperature_k", 4),
        Column::new("background_emissivity", 4),
        Column::new("background_temperature_k", 4),
    ];
    columns.extend((0..=args.max).map(|n| Column::new(format!("bounces_{n}_k"), 4)));
    print_table(args.format.value, &columns, &rows)
}
