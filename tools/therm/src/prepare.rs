//! Everything a run needs, built once from the inputs, and the run itself: what the
//! moments' scenes and the history hold.

use std::collections::HashMap;

use irsig_model::weather::Weather;
use irsig_model::{MaterialLibrary, RawScene};
use irsig_tracer::exposure::{Exposure, ExposureOptions, ViewFactors};
use miette::miette;

use crate::Cli;
use crate::environment::{Environment, Site};
use crate::models::{Models, Switch};
use crate::setup::{self, MaterialModel};
use crate::solve::{self, Ground, Scenario, Settings};

/// The hottest a held facet may be, K.
const MAX_HELD_K: f64 = 3000.0;
/// The most heat deposited behind a facet, W/m².
const MAX_HEAT_W_M2: f64 = 1e5;

/// The scene resolved for the solver.
#[derive(Debug)]
pub struct Prepared<'a> {
    scene: &'a RawScene,
    exposure: Exposure,
    views: ViewFactors,
    models: Vec<MaterialModel>,
    slot: Vec<Option<usize>>,
    held_k: Vec<Option<f64>>,
    heat_w_m2: Vec<f64>,
    optics: Vec<(f64, f64)>,
    ground: Option<MaterialModel>,
    ground_albedo: f64,
    environment: Environment<'a>,
}

/// What a run gives: each moment's surface temperatures and the ground's, and the history
/// when asked for.
#[derive(Debug)]
pub struct Outcome {
    /// Per moment, every facet's surface temperature, K.
    pub surface_k: Vec<Vec<f64>>,
    /// Per moment, the ground's temperature, when it is solved.
    pub ground_k: Vec<Option<f64>>,
    /// The times of the history's rows and its table (times × facets), when asked for.
    pub history: Option<(Vec<f64>, Vec<f32>)>,
    /// When the solve started, s.
    pub start_s: f64,
}

impl<'a> Prepared<'a> {
    /// Resolves the scene: held and heated facets, every solved facet's material model, the
    /// ground, what each facet sees (view factors, once), and the weather's sources.
    ///
    /// # Errors
    /// Bad flags, a material without thermal properties, a weather record without the
    /// sunlight's columns.
    pub fn new(
        cli: &Cli,
        scene: &'a RawScene,
        materials: &MaterialLibrary,
        weather: &'a Weather,
        weather_name: &str,
        site: Site,
    ) -> miette::Result<Self> {
        cli.models.validate()?;
        let held_k = setup::per_facet(scene, &cli.hold, "--hold", "K", (1.0, MAX_HELD_K))?;
        let heat = setup::per_facet(
            scene,
            &cli.heat,
            "--heat",
            "W/m2",
            (-MAX_HEAT_W_M2, MAX_HEAT_W_M2),
        )?;
        let heat_w_m2: Vec<f64> = heat.iter().map(|h| h.unwrap_or(0.0)).collect();
        let solved: Vec<bool> = held_k.iter().map(Option::is_none).collect();
        let by_id = setup::material_models(
            scene,
            materials,
            &solved,
            &cli.models.discretisation(),
            cli.models.convection(),
        )?;
        let (models, slot) = slots(scene, &solved, by_id);
        let optics = optics(scene, materials, &models, &slot);
        let ground = match &cli.ground_material {
            Some(name) => Some(setup::ground_model(
                materials,
                name,
                &cli.models.discretisation(),
                cli.models.convection(),
            )?),
            None => None,
        };
        let ground_albedo = match (cli.ground_albedo, &ground) {
            (Some(a), _) if a.is_finite() && (0.0..=1.0).contains(&a) => a,
            (Some(a), _) => {
                return Err(irsig_cli::usage_error(format!(
                    "--ground-albedo: expected 0 to 1, found {a}"
                )));
            }
            (None, Some(g)) => 1.0 - g.surface.solar_absorptance,
            (None, None) => 0.2,
        };
        let (sunlight, sky) = Environment::sources(weather, weather_name)?;
        let exposure = Exposure::new(scene).map_err(|e| miette!("{e}"))?;
        let views = exposure
            .views(
                cli.models.hemisphere_rays,
                cli.seed,
                ExposureOptions {
                    samples_per_side: cli.models.shadow_samples,
                },
            )
            .map_err(|e| miette!("{e}"))?;
        Ok(Self {
            scene,
            exposure,
            views,
            models,
            slot,
            held_k,
            heat_w_m2,
            optics,
            ground,
            ground_albedo,
            environment: Environment {
                weather,
                site,
                sunlight,
                sky,
            },
        })
    }

    /// Where the sky's longwave came from, in words.
    #[must_use]
    pub fn radiation(&self) -> String {
        format!(
            "sunlight: the weather file's dni and dhi columns; sky longwave: {}",
            match self.environment.sky {
                crate::environment::SkyLongwave::Weather => "the weather file's column",
                crate::environment::SkyLongwave::Prata =>
                    "Prata (1996) clear sky with Crawford & Duchon (1999) clouds",
            }
        )
    }

    /// Solves from the spin-up's start to the last moment, keeping each moment's
    /// temperatures and, when `history` is asked for, every step's from the first moment.
    ///
    /// # Errors
    /// Moments off the step's grid, a history too large to hold, a time outside the
    /// weather, a facet whose balance fails.
    pub fn solve(&self, models: &Models, times: &[f64], history: bool) -> miette::Result<Outcome> {
        let grid = Grid::new(models, times)?;
        let facets = self.scene.facets.len();
        let rows = grid.last_index - grid.first_index + 1;
        if history && (rows as u64) * (facets as u64) > irsig_model::history::MAX_HISTORY_VALUES {
            return Err(irsig_cli::usage_error(format!(
                "--history: {rows} steps × {facets} facets is more than the {} values a \
                 history holds; use a longer --step-s or fewer moments",
                irsig_model::history::MAX_HISTORY_VALUES
            )));
        }
        let scenario = Scenario {
            scene: self.scene,
            exposure: &self.exposure,
            views: &self.views,
            models: &self.models,
            slot: &self.slot,
            held_k: &self.held_k,
            heat_w_m2: &self.heat_w_m2,
            optics: &self.optics,
            environment: &self.environment,
            ground: Ground {
                model: self.ground.as_ref(),
                albedo: self.ground_albedo,
            },
        };
        let settings = Settings {
            time_step: models.time_step(),
            shadow: models.shadow(),
            exchange: models.exchange == Switch::On,
        };
        let mut outcome = Outcome {
            surface_k: Vec::new(),
            ground_k: Vec::new(),
            history: history.then(|| (Vec::new(), Vec::with_capacity(rows * facets))),
            start_s: grid.start_s,
        };
        let bar = irsig_cli::progress_bar(grid.last_index as u64, "therm");
        solve::run(
            &scenario,
            &settings,
            grid.start_s,
            grid.last_index,
            |k, t, surface, ground_k| {
                bar.set_position(k as u64);
                if k >= grid.first_index {
                    if let Some((times, table)) = &mut outcome.history {
                        times.push(t);
                        table.extend(surface.iter().map(|&s| s as f32));
                    }
                }
                if grid.moments.contains(&k) {
                    outcome.surface_k.push(surface.to_vec());
                    outcome
                        .ground_k
                        .push(self.ground.is_some().then_some(ground_k));
                }
                Ok(())
            },
        )?;
        bar.finish_and_clear();
        Ok(outcome)
    }
}

/// Every solved facet's material model by slot, and each facet's slot.
fn slots(
    scene: &RawScene,
    solved: &[bool],
    by_id: HashMap<u16, MaterialModel>,
) -> (Vec<MaterialModel>, Vec<Option<usize>>) {
    let mut ids: Vec<u16> = by_id.keys().copied().collect();
    ids.sort_unstable();
    let index: HashMap<u16, usize> = ids.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    let mut by_id = by_id;
    let models = ids.iter().filter_map(|id| by_id.remove(id)).collect();
    let slot = scene
        .facets
        .iter()
        .zip(solved)
        .map(|(f, &s)| s.then(|| index[&f.material.0]))
        .collect();
    (models, slot)
}

/// Each facet's solar absorptance and broadband emissivity as other facets see it: a solved
/// facet's surface's; a held facet's material's thermal record where it has one, else a
/// blackbody's (1, 1).
fn optics(
    scene: &RawScene,
    materials: &MaterialLibrary,
    models: &[MaterialModel],
    slot: &[Option<usize>],
) -> Vec<(f64, f64)> {
    scene
        .facets
        .iter()
        .zip(slot)
        .map(|(f, s)| match s {
            Some(k) => (
                models[*k].surface.solar_absorptance,
                models[*k].surface.thermal_emissivity,
            ),
            None => materials
                .by_id(f.material)
                .and_then(|m| m.thermal.as_ref())
                .map_or((1.0, 1.0), |t| {
                    (
                        t.solar_absorptance.unwrap_or(1.0),
                        t.thermal_emissivity.unwrap_or(1.0),
                    )
                }),
        })
        .collect()
}

/// The steps: from the spin-up's start, every `step_s`, through every moment.
#[derive(Debug)]
struct Grid {
    start_s: f64,
    /// The step index of the first moment.
    first_index: usize,
    /// The step index of the last moment.
    last_index: usize,
    /// The step index of every moment.
    moments: Vec<usize>,
}

impl Grid {
    fn new(models: &Models, times: &[f64]) -> miette::Result<Self> {
        let step = models.step_s;
        let first = times[0];
        let spin = (models.spin_up_h * 3600.0 / step).ceil() as usize;
        let mut moments = Vec::with_capacity(times.len());
        for &t in times {
            let k = (t - first) / step;
            if (k - k.round()).abs() > 1e-6 {
                let lo = first + k.floor() * step;
                return Err(irsig_cli::usage_error(format!(
                    "--at {}: not on the {step} s grid from the first moment {}; the nearest \
                     are {} and {}",
                    fmt(t),
                    fmt(first),
                    fmt(lo),
                    fmt(lo + step)
                )));
            }
            moments.push(spin + k.round() as usize);
        }
        let last_index = *moments.last().unwrap_or(&spin);
        Ok(Self {
            start_s: first - spin as f64 * step,
            first_index: spin,
            last_index,
            moments,
        })
    }
}

fn fmt(t: f64) -> String {
    irsig_formats::time::format_utc(t).unwrap_or_else(|| format!("{t} s"))
}
