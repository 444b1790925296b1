//! Everything a run needs, built once from the inputs, and the run itself: what the
//! moments' scenes and the history hold.

use std::collections::HashMap;

use irsig_model::loads::BroadbandLoads;
use irsig_model::weather::Weather;
use irsig_model::{MaterialLibrary, RawScene};
use irsig_tracer::exposure::{Exposure, ExposureOptions, ViewFactors};
use miette::miette;

use crate::Cli;
use crate::environment::{Environment, Site, SkyLongwave};
use crate::mixture::{self, Mixed};
use crate::models::{MixtureArg, Models, Switch};
use crate::setup::{self, MaterialModel};
use crate::solve::{self, Ground, LitCache, Scenario, Settings};

/// The hottest a held facet may be, K.
const MAX_HELD_K: f64 = 3000.0;
/// The most heat deposited behind a facet, W/m².
const MAX_HEAT_W_M2: f64 = 1e5;

/// The scene resolved for the solver: what does not change with the models' settings.
#[derive(Debug)]
pub struct Prepared<'a> {
    pub(crate) scene: &'a RawScene,
    materials: &'a MaterialLibrary,
    ground_material: Option<String>,
    pub(crate) exposure: Exposure,
    solved: Vec<bool>,
    held_k: Vec<Option<f64>>,
    heat_w_m2: Vec<f64>,
    ground_albedo: f64,
    pub(crate) environment: Environment<'a>,
    seed: u64,
    /// Per facet, its area fractions under its material's material map, when it is solved
    /// and has one (empty when none has).
    fractions: Vec<Option<[f64; irsig_model::material_map::MAX_MAP_MATERIALS]>>,
    /// The SHA-256 of each material map image the fractions were read from.
    map_images: Vec<String>,
}

/// What the models' settings make of the materials: each solved material's wall and
/// surface, each facet's slot among them, the facets' optics and the ground's model.
#[derive(Debug)]
pub(crate) struct Walls {
    models: Vec<MaterialModel>,
    slot: Vec<Option<usize>>,
    /// Per facet, its parts when it is solved by its map's materials (empty when none is).
    mix: Vec<Option<Box<Mixed>>>,
    optics: Vec<(f64, f64)>,
    ground: Option<MaterialModel>,
}

impl Walls {
    /// Facet `i`'s material model's slot (a mixed facet's: its largest part's), or `None`
    /// when it is held.
    pub(crate) fn slot_of(&self, i: usize) -> Option<usize> {
        self.slot[i]
    }

    /// Whether facet `i` is solved part by part.
    pub(crate) fn is_mixed(&self, i: usize) -> bool {
        self.mix.get(i).is_some_and(Option::is_some)
    }

    /// The mean number of nodes of the walls of `facets` (a held facet's is 0).
    pub(crate) fn mean_nodes(&self, facets: &[u32]) -> f64 {
        let total: usize = facets
            .iter()
            .map(
                |&f| match self.mix.get(f as usize).and_then(Option::as_ref) {
                    Some(m) => m
                        .parts
                        .iter()
                        .map(|p| self.models[p.slot].wall.nodes())
                        .sum(),
                    None => self.slot[f as usize].map_or(0, |s| self.models[s].wall.nodes()),
                },
            )
            .sum();
        total as f64 / facets.len().max(1) as f64
    }
}

/// What a run gives: each moment's surface temperatures and the ground's, and the history
/// when asked for.
#[derive(Debug)]
pub struct Outcome {
    /// Per moment, every stepped facet's surface temperature, K.
    pub surface_k: Vec<Vec<f64>>,
    /// Per moment, the ground's temperature, when it is solved.
    pub ground_k: Vec<Option<f64>>,
    /// Per moment, the per-material temperatures of every stepped facet solved part by
    /// part (the raw scene's `mix_temperatures`).
    pub mix_k: Vec<Vec<irsig_model::MixTemperatures>>,
    /// The times of the history's rows and its table (times × facets), when asked for.
    pub history: Option<(Vec<f64>, Vec<f32>)>,
    /// When the solve started, s.
    pub start_s: f64,
}

/// One run: which facets it steps through which grid, with what walls, views and settings.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Run<'r> {
    /// The facets stepped.
    pub stepped: Stepped<'r>,
    /// Their views.
    pub views: &'r ViewFactors,
    /// The walls.
    pub walls: &'r Walls,
    /// The settings.
    pub models: &'r Models,
    /// The steps.
    pub grid: &'r Grid,
    /// The walls' start above the air's temperature, K.
    pub offset_k: f64,
    /// The sky's longwave source.
    pub sky: SkyLongwave,
    /// Keep every step's temperatures from the first moment.
    pub history: bool,
    /// Show a progress bar.
    pub progress: bool,
    /// Sunlit shares to reuse across runs of the same facets.
    pub lit_cache: Option<&'r LitCache>,
}

/// Which facets a run steps, and who stands in for the others.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stepped<'s> {
    pub facets: &'s [u32],
    pub proxy: &'s [u32],
}

impl<'a> Prepared<'a> {
    /// Resolves the scene: held and heated facets, the ground, and the weather's sources;
    /// checks that every solved facet's material can be modelled.
    ///
    /// # Errors
    /// Bad flags, a material without thermal properties, a weather record without the
    /// sunlight's columns.
    pub fn new(
        cli: &Cli,
        scene: &'a RawScene,
        materials: &'a MaterialLibrary,
        weather: (&'a Weather, &str),
        loads: Option<&'a BroadbandLoads>,
        site: Site,
    ) -> miette::Result<Self> {
        let (weather, weather_name) = weather;
        cli.models.validate()?;
        let held_k = setup::per_facet(scene, &cli.hold, "--hold", "K", (1.0, MAX_HELD_K))?;
        let heat = setup::per_facet(
            scene,
            &cli.heat,
            "--heat",
            "W/m2",
            (-MAX_HEAT_W_M2, MAX_HEAT_W_M2),
        )?;
        let solved: Vec<bool> = held_k.iter().map(Option::is_none).collect();
        let (fractions, map_images) = if cli.models.mixture == MixtureArg::PerMaterial {
            mixture::facet_fractions(scene, materials, cli.materials.required()?, &solved)?
        } else {
            (Vec::new(), Vec::new())
        };
        let (sunlight, sky) = Environment::sources(
            weather,
            weather_name,
            loads,
            (cli.sunlight, cli.sky_longwave),
        )?;
        let mut prepared = Self {
            scene,
            materials,
            ground_material: cli.ground_material.clone(),
            exposure: Exposure::new(scene).map_err(|e| miette!("{e}"))?,
            solved,
            held_k,
            heat_w_m2: heat.iter().map(|h| h.unwrap_or(0.0)).collect(),
            ground_albedo: 0.2,
            environment: Environment {
                weather,
                site,
                sunlight,
                sky,
                loads,
            },
            seed: cli.seed.value,
            fractions,
            map_images,
        };
        let walls = prepared.walls(&cli.models)?;
        // The parser checked a given albedo's range.
        prepared.ground_albedo = match (cli.ground_albedo.value, &walls.ground) {
            (Some(a), _) => a,
            (None, Some(g)) => 1.0 - g.surface.solar_absorptance,
            (None, None) => 0.2,
        };
        Ok(prepared)
    }

    /// The walls and surfaces the settings make.
    ///
    /// # Errors
    /// A material that cannot be modelled (named).
    pub(crate) fn walls(&self, models: &Models) -> miette::Result<Walls> {
        let discretisation = models.discretisation();
        let per_material = models.mixture == MixtureArg::PerMaterial;
        let by_map: Vec<bool> = (0..self.scene.facets.len())
            .map(|i| per_material && self.fractions.get(i).is_some_and(Option::is_some))
            .collect();
        let by_id = setup::material_models(
            self.scene,
            self.materials,
            (&self.solved, &by_map),
            &discretisation,
            models.convection(),
        )?;
        let (materials, index) = slots(by_id);
        let mix = if per_material && !self.fractions.is_empty() {
            mixture::mixed_facets(self.scene, self.materials, &self.fractions, |id| {
                index.get(&id).copied()
            })
        } else {
            Vec::new()
        };
        let slot = self
            .scene
            .facets
            .iter()
            .enumerate()
            .map(|(i, f)| {
                if !self.solved[i] {
                    return None;
                }
                match mix.get(i).and_then(Option::as_ref) {
                    Some(m) => m
                        .parts
                        .iter()
                        .max_by(|a, b| a.fraction.total_cmp(&b.fraction))
                        .map(|p| p.slot),
                    None => index.get(&f.material.0).copied(),
                }
            })
            .collect::<Vec<_>>();
        let optics = optics(self.scene, self.materials, &materials, (&slot, &mix));
        let ground = match &self.ground_material {
            Some(name) => Some(setup::ground_model(
                self.materials,
                name,
                &discretisation,
                models.convection(),
            )?),
            None => None,
        };
        Ok(Walls {
            models: materials,
            slot,
            mix,
            optics,
            ground,
        })
    }

    /// What each of `facets`' hemispheres holds, by the settings' rays and sample points.
    ///
    /// # Errors
    /// More view factors than fit.
    pub(crate) fn views(&self, facets: &[u32], models: &Models) -> miette::Result<ViewFactors> {
        self.exposure
            .views(
                facets,
                models.hemisphere_rays,
                self.seed,
                ExposureOptions {
                    samples_per_side: models.shadow_samples,
                },
            )
            .map_err(|e| miette!("{e}"))
    }

    /// The SHA-256 of each material map image read (per-material walls only), in the
    /// library's order.
    #[must_use]
    pub fn map_images(&self) -> &[String] {
        &self.map_images
    }

    /// Where the sunlight and the sky's longwave came from, in words.
    #[must_use]
    pub fn radiation(&self) -> String {
        format!(
            "sunlight: {}; sky longwave: {}",
            self.environment.sunlight.describe(),
            self.environment.sky.describe()
        )
    }

    /// Solves every facet from the spin-up's start to the last moment, keeping each
    /// moment's temperatures and, when `history` is asked for, every step's from the first
    /// moment.
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
        let all: Vec<u32> = (0..facets as u32).collect();
        let walls = self.walls(models)?;
        let views = self.views(&all, models)?;
        let stepped = Stepped {
            facets: &all,
            proxy: &all,
        };
        self.run_on(&Run {
            stepped,
            views: &views,
            walls: &walls,
            models,
            grid: &grid,
            offset_k: 0.0,
            sky: self.environment.sky,
            history,
            progress: true,
            lit_cache: None,
        })
    }

    /// Runs `run`, keeping each moment's temperatures and, when it asks, every step's from
    /// the first moment.
    ///
    /// # Errors
    /// A time outside the weather, a facet whose balance fails.
    pub(crate) fn run_on(&self, run: &Run<'_>) -> miette::Result<Outcome> {
        let Run {
            stepped,
            views,
            walls,
            models,
            grid,
            offset_k,
            sky,
            history,
            progress,
            lit_cache,
        } = *run;
        let environment = Environment {
            sky,
            ..self.environment
        };
        let scenario = Scenario {
            scene: self.scene,
            exposure: &self.exposure,
            facets: stepped.facets,
            proxy: stepped.proxy,
            views,
            models: &walls.models,
            slot: &walls.slot,
            mix: &walls.mix,
            held_k: &self.held_k,
            heat_w_m2: &self.heat_w_m2,
            optics: &walls.optics,
            environment: &environment,
            ground: Ground {
                model: walls.ground.as_ref(),
                albedo: self.ground_albedo,
            },
            lit_cache,
        };
        let settings = Settings {
            time_step: models.time_step(),
            shadow: models.shadow(),
            exchange: models.exchange == Switch::On,
            initial_offset_k: offset_k,
        };
        let n = stepped.facets.len();
        let rows = grid.last_index - grid.first_index + 1;
        let mut outcome = Outcome {
            surface_k: Vec::new(),
            ground_k: Vec::new(),
            mix_k: Vec::new(),
            history: history.then(|| (Vec::new(), Vec::with_capacity(rows * n))),
            start_s: grid.start_s,
        };
        let bar = progress.then(|| irsig_cli::progress_bar(grid.last_index as u64, "therm"));
        solve::run(
            &scenario,
            &settings,
            grid.start_s,
            grid.last_index,
            |k, t, surface, ground_k, parts_k| {
                if let Some(bar) = &bar {
                    bar.set_position(k as u64);
                }
                if k >= grid.first_index
                    && let Some((times, table)) = &mut outcome.history
                {
                    times.push(t);
                    table.extend(surface.iter().map(|&s| s as f32));
                }
                if grid.moments.contains(&k) {
                    outcome.surface_k.push(surface.to_vec());
                    outcome
                        .ground_k
                        .push(walls.ground.is_some().then_some(ground_k));
                    outcome
                        .mix_k
                        .push(mix_temperatures(walls, stepped.facets, surface, parts_k));
                }
                Ok(())
            },
        )?;
        if let Some(bar) = bar {
            bar.finish_and_clear();
        }
        Ok(outcome)
    }
}

/// The per-material temperatures of the stepped facets solved part by part: `surface` and
/// `parts_k` in the order of `stepped` (scene indices).
fn mix_temperatures(
    walls: &Walls,
    stepped: &[u32],
    surface: &[f64],
    parts_k: &[[f64; irsig_model::material_map::MAX_MAP_MATERIALS]],
) -> Vec<irsig_model::MixTemperatures> {
    if walls.mix.is_empty() {
        return Vec::new();
    }
    stepped
        .iter()
        .enumerate()
        .filter_map(|(i, &g)| {
            let m = walls.mix.get(g as usize)?.as_ref()?;
            Some(irsig_model::MixTemperatures {
                facet: g,
                temperatures_k: m.temperatures(&parts_k[i], surface[i]),
            })
        })
        .collect()
}

/// Every material model by slot (in the order of their ids), and each id's slot.
fn slots(by_id: HashMap<u16, MaterialModel>) -> (Vec<MaterialModel>, HashMap<u16, usize>) {
    let mut ids: Vec<u16> = by_id.keys().copied().collect();
    ids.sort_unstable();
    let index: HashMap<u16, usize> = ids.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    let mut by_id = by_id;
    let models = ids.iter().filter_map(|id| by_id.remove(id)).collect();
    (models, index)
}

/// Each facet's solar absorptance and broadband emissivity as other facets see it: a solved
/// facet's surface's (a mixed facet's the fraction-weighted means of its parts'); a held
/// facet's material's thermal record where it has one, else a blackbody's (1, 1).
fn optics(
    scene: &RawScene,
    materials: &MaterialLibrary,
    models: &[MaterialModel],
    (slot, mix): (&[Option<usize>], &[Option<Box<Mixed>>]),
) -> Vec<(f64, f64)> {
    scene
        .facets
        .iter()
        .zip(slot)
        .enumerate()
        .map(
            |(i, (f, s))| match (mix.get(i).and_then(Option::as_ref), s) {
                (Some(m), _) => m.parts.iter().fold((0.0, 0.0), |(a, e), p| {
                    let surface = &models[p.slot].surface;
                    (
                        a + p.fraction * surface.solar_absorptance,
                        e + p.fraction * surface.thermal_emissivity,
                    )
                }),
                (None, Some(k)) => (
                    models[*k].surface.solar_absorptance,
                    models[*k].surface.thermal_emissivity,
                ),
                (None, None) => materials
                    .by_id(f.material)
                    .and_then(|m| m.thermal.as_ref())
                    .map_or((1.0, 1.0), |t| {
                        (
                            t.solar_absorptance.unwrap_or(1.0),
                            t.thermal_emissivity.unwrap_or(1.0),
                        )
                    }),
            },
        )
        .collect()
}

/// The steps: from the spin-up's start, every `step_s`, through every moment.
#[derive(Debug)]
pub(crate) struct Grid {
    pub start_s: f64,
    /// The step index of the first moment.
    pub first_index: usize,
    /// The step index of the last moment.
    pub last_index: usize,
    /// The step index of every moment.
    pub moments: Vec<usize>,
}

impl Grid {
    /// The grid of `models`' step and spin-up through `times`.
    ///
    /// # Errors
    /// A moment off the grid from the first.
    pub(crate) fn new(models: &Models, times: &[f64]) -> miette::Result<Self> {
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
    irsig_model::time::format_utc(t)
}
