//! The thermal model's named approximations and their settings on the command line. Each
//! trades time for accuracy; docs/accuracy.md ("The thermal model") measures each one's
//! error against a converged solve.

use irsig_thermal::{Convection, Discretisation, Scheme, TimeStep};
use irsig_tracer::exposure::ExposureOptions;

/// The time-stepping scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SchemeArg {
    /// Backward Euler: first order in the step, damps every mode (L-stable).
    BackwardEuler,
    /// Crank–Nicolson: second order in the step; refused where a thin layer would ring.
    CrankNicolson,
    /// TR-BDF2: second order in the step and L-stable, at about twice Backward Euler's cost.
    TrBdf2,
}

/// The convection correlation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ConvectionArg {
    /// DOE-2 (EnergyPlus): natural convection by tilt and the sign of T_s − T_air, forced by
    /// the wind, windward or leeward, and the surface's roughness.
    Doe2,
    /// McAdams (1954): h = 5.7 + 3.8 V, wind only.
    Mcadams,
}

/// How a facet whose material has a material map is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MixtureArg {
    /// "Per-material walls": each material of the map with a share of the facet gets its
    /// own wall and surface under the facet's loads, with no conduction between them.
    PerMaterial,
    /// The host material's one wall for the whole facet, every map material at its one
    /// temperature (a named approximation, docs/accuracy.md measures its error).
    OneWall,
}

/// On or off.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Switch {
    /// On.
    On,
    /// Off.
    Off,
}

/// The models' settings, as flags.
#[derive(Debug, Clone, PartialEq, clap::Args)]
pub struct Models {
    /// The time step, seconds.
    #[arg(long, default_value_t = 300.0, value_name = "S")]
    pub step_s: f64,
    /// The time-stepping scheme.
    #[arg(long, value_enum, default_value_t = SchemeArg::BackwardEuler)]
    pub scheme: SchemeArg,
    /// The walls' cells: the first at the exposed surface this long, mm, each deeper one
    /// 1.3 times the one before, up to 50 mm.
    #[arg(long, default_value_t = 2.0, value_name = "MM")]
    pub first_cell_mm: f64,
    /// Shadow rays: a facet is sampled at N × N points, each casting one ray to the sun's
    /// centre per step.
    #[arg(long, default_value_t = 2, value_name = "N")]
    pub shadow_samples: u32,
    /// Hemisphere rays per facet, cast once, for its view factors to the sky, the ground
    /// and the other facets.
    #[arg(long, default_value_t = 64, value_name = "N")]
    pub hemisphere_rays: u32,
    /// Sunlight and longwave exchanged between facets (off: the facets a facet sees count
    /// as the open ground).
    #[arg(long, value_enum, default_value_t = Switch::On)]
    pub exchange: Switch,
    /// The convection correlation.
    #[arg(long, value_enum, default_value_t = ConvectionArg::Doe2)]
    pub convection: ConvectionArg,
    /// How a facet under a material map is solved: each map material's own wall
    /// (per-material), or the host material's one wall (one-wall).
    #[arg(long, value_enum, default_value_t = MixtureArg::PerMaterial)]
    pub mixture: MixtureArg,
    /// Hours simulated before the first moment, from walls at the air's temperature, so
    /// that the start no longer matters.
    #[arg(long, default_value_t = 72.0, value_name = "H")]
    pub spin_up_h: f64,
}

/// The largest cell, m: deeper than a diurnal wave reaches in concrete (≈ 0.15 m) the
/// gradients are small.
const MAX_CELL_M: f64 = 0.05;
/// The growth of cells with depth.
const GROWTH: f64 = 1.3;

impl Models {
    /// Checks every setting's range.
    ///
    /// # Errors
    /// The first setting out of range, naming its flag (bad usage).
    pub fn validate(&self) -> miette::Result<()> {
        let bad = |flag: &str, expected: &str, found: String| {
            Err(irsig_cli::usage_error(format!(
                "--{flag}: expected {expected}, found {found}"
            )))
        };
        if !(self.step_s.is_finite() && (1.0..=3600.0).contains(&self.step_s)) {
            return bad("step-s", "1 to 3600 seconds", self.step_s.to_string());
        }
        if !(self.first_cell_mm.is_finite() && (0.01..=50.0).contains(&self.first_cell_mm)) {
            return bad(
                "first-cell-mm",
                "0.01 to 50 mm",
                self.first_cell_mm.to_string(),
            );
        }
        if !(1..=irsig_tracer::exposure::MAX_SAMPLES_PER_SIDE).contains(&self.shadow_samples) {
            return bad(
                "shadow-samples",
                "1 to 64 points per side",
                self.shadow_samples.to_string(),
            );
        }
        if !(1..=irsig_tracer::exposure::MAX_HEMISPHERE_RAYS).contains(&self.hemisphere_rays) {
            return bad(
                "hemisphere-rays",
                "1 to 65536",
                self.hemisphere_rays.to_string(),
            );
        }
        if !(self.spin_up_h.is_finite() && (0.0..=24.0 * 366.0).contains(&self.spin_up_h)) {
            return bad("spin-up-h", "0 to 8784 hours", self.spin_up_h.to_string());
        }
        Ok(())
    }

    /// The time step.
    #[must_use]
    pub fn time_step(&self) -> TimeStep {
        TimeStep {
            dt_s: self.step_s,
            scheme: match self.scheme {
                SchemeArg::BackwardEuler => Scheme::BackwardEuler,
                SchemeArg::CrankNicolson => Scheme::CrankNicolson,
                SchemeArg::TrBdf2 => Scheme::TrBdf2,
            },
        }
    }

    /// How the walls are cut.
    #[must_use]
    pub fn discretisation(&self) -> Discretisation {
        let first = self.first_cell_mm * 1e-3;
        Discretisation::graded(first, GROWTH, MAX_CELL_M.max(first))
    }

    /// The convection correlation.
    #[must_use]
    pub fn convection(&self) -> Convection {
        match self.convection {
            ConvectionArg::Doe2 => Convection::Doe2,
            ConvectionArg::Mcadams => Convection::McAdams,
        }
    }

    /// The shadow rays' sample points.
    #[must_use]
    pub fn shadow(&self) -> ExposureOptions {
        ExposureOptions {
            samples_per_side: self.shadow_samples,
        }
    }

    /// Each model and its setting, in words, for the provenance and the decision.
    #[must_use]
    pub fn describe(&self) -> Vec<(String, String)> {
        let on = |s: Switch| if s == Switch::On { "on" } else { "off" };
        vec![
            ("time step".into(), format!("{} s", self.step_s)),
            (
                "scheme".into(),
                match self.scheme {
                    SchemeArg::BackwardEuler => "backward-euler".into(),
                    SchemeArg::CrankNicolson => "crank-nicolson".into(),
                    SchemeArg::TrBdf2 => "tr-bdf2".into(),
                },
            ),
            (
                "cells".into(),
                format!(
                    "first {} mm, growth {GROWTH}, at most {} mm",
                    self.first_cell_mm,
                    MAX_CELL_M * 1e3
                ),
            ),
            (
                "shadow samples".into(),
                format!("{0} x {0} per facet", self.shadow_samples),
            ),
            (
                "hemisphere rays".into(),
                format!("{} per facet", self.hemisphere_rays),
            ),
            ("exchange".into(), on(self.exchange).into()),
            (
                "convection".into(),
                match self.convection {
                    ConvectionArg::Doe2 => "doe2".into(),
                    ConvectionArg::Mcadams => "mcadams".into(),
                },
            ),
            ("spin-up".into(), format!("{} h", self.spin_up_h)),
            (
                "mixture".into(),
                match self.mixture {
                    MixtureArg::PerMaterial => "per-material".into(),
                    MixtureArg::OneWall => "one-wall".into(),
                },
            ),
        ]
    }
}
