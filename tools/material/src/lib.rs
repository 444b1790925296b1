//! `irsig-material`: material libraries, where a user looks for them.
//!
//! - `convert` ([`convert`]): the 1990 material index file with the `.ems` tables it names
//!   to a canonical material library (formats/canonical/material-library.md), and back
//!   (`--to-legacy`).
//! - `fresnel` ([`fresnel`]): an angular emissivity table of an opaque surface, smooth or
//!   rough (`--roughness`, an RMS facet slope), from its complex refractive index
//!   (constant, or a `wavelength_um n k` table averaged over the band), as a canonical
//!   material library entry or a legacy `.ems`.
//!
//! ```text
//! irsig-material convert materials.mat --default-emissivity 0.9 -o lib.ron
//! irsig-material convert --to-legacy lib.ron --out-dir legacy/
//! irsig-material fresnel --n 1.2 --k 0.05 -o glassy.ron
//! irsig-material fresnel --n 1.36 --roughness 0.8 --diffuse-reflectance 0.0347 -o asphalt.ron
//! irsig-material fresnel --nk-table water.nk --band 8-14 --planck-temperature 300 -o water.ems
//! irsig-material list pipelines/materials/scene-library.ron --plot plots/
//! ```

// A closed stderr must not panic the tool: notes go through `irsig_cli::note!`.
#![warn(clippy::print_stderr)]

use clap::{Parser, Subcommand};

pub mod convert;
pub mod dirsig;
pub mod fresnel;
pub mod list;

/// Material libraries: the 1990 material files converted, and angular emissivity from
/// Fresnel's equations.
#[derive(Debug, Parser)]
#[command(
    name = "irsig-material",
    version,
    after_help = "Examples:
  irsig-material convert formats/legacy/samples/materials.mat --default-emissivity 0.9 \\
      -o lib.ron
  irsig-material convert --to-legacy lib.ron --out-dir legacy/
  irsig-material fresnel --n 1.2 --k 0.05 --angles 0:90:5
  irsig-material fresnel --nk-table formats/samples/water-hale-querry-nk.txt --band 8-14 \\
      --planck-temperature 300 --angles 0:90:5 --legacy -o water.ems
  irsig-material list pipelines/materials/scene-library.ron --plot plots/"
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Material index + .ems tables <-> canonical material library, validated.
    Convert(convert::ConvertArgs),
    /// Angular emissivity of an opaque surface, smooth or rough, from its complex refractive
    /// index (Fresnel), as a material library entry (RON) or a legacy `.ems`.
    #[command(after_help = "Examples:
  irsig-material fresnel --n 1.2 --k 0.05 --angles 0:90:5
  irsig-material fresnel --n 1.36 --roughness 0.8 --diffuse-reflectance 0.0347 --name asphalt
  irsig-material fresnel --n 25 --k 90 --name aluminium --id 7 -o aluminium.ron
  irsig-material fresnel --nk-table formats/samples/water-hale-querry-nk.txt --band 8-14 \\
      --planck-temperature 300 --angles 0:90:5 --legacy -o water.ems

A constant index gives the monochromatic table. A table of n, k against wavelength is
averaged over the band (a response file as --band weights it) with Planck weighting at
--planck-temperature:
eps(theta) = int eps(lambda, theta) S B(lambda, T) dlambda / int S B(lambda, T) dlambda.
Output is a canonical material library (RON) unless --legacy or -o NAME.ems.

With --nk-table the library entry also keeps the spectrum by default: eps(lambda) at
normal incidence at the table's wavelengths (`spectral`), so that irsig-trace averages it
over its own band or each of its --sub-bands, taking the angular table above as the
shape, eps(lambda, theta) = eps(lambda) table(theta) / table(0). A Fresnel surface's shape
changes with wavelength, so this is an approximation whose error docs/accuracy.md
measures (\"Fresnel emissivity\"). --band-only drops the spectrum; a legacy .ems cannot
carry it.

--roughness SLOPE makes the surface rough: smooth Fresnel facets whose slopes are Gaussian
with RMS slope SLOPE (dimensionless, the tangent of the facets' tilt; 0 is smooth), seen
through Smith's shadowing, with one reflection (Masuda et al. 1988; Wu & Smith 1997).
--diffuse-reflectance SHARE puts a body that returns SHARE of what enters it diffusely
under the facets (eps = (1 - SHARE) times the facets'). Field-measured soils, sand, grass
and paint fitted this way: pipelines/materials/rough-surfaces.ron, docs/accuracy.md.")]
    Fresnel(fresnel::Args),
    /// A DIRSIG classic .mat and the spectral .ems curves it names -> a canonical material
    /// library of spectral materials (ε(λ) with an angular shape).
    Dirsig(dirsig::Args),
    /// What a material library holds: per material its spectrum's coverage, emissivity
    /// over 3-5 and 8-14 um, solar absorptance, thermal record and source; `--plot DIR`
    /// draws each spectrum as an SVG.
    List(list::Args),
}

impl irsig_cli::CheckArgs for Cli {
    fn check_args(&self) -> miette::Result<()> {
        match &self.command {
            Command::Fresnel(args) => fresnel::flags(args).map(drop),
            Command::Convert(_) | Command::Dirsig(_) | Command::List(_) => Ok(()),
        }
    }
}

/// Runs one subcommand.
///
/// # Errors
/// Bad input (exit 1): a malformed index, `.ems`, n, k or response file, a bad value
/// (emissivity outside 0–1, a refractive index that is not physical, a malformed list or
/// range); or bad usage (exit 2).
pub fn run(cli: Cli) -> miette::Result<()> {
    match cli.command {
        Command::Convert(args) => convert::run(&args),
        Command::Fresnel(args) => fresnel::run(&args),
        Command::Dirsig(args) => dirsig::run(&args),
        Command::List(args) => list::run(&args),
    }
}
