//! The time loop: every facet's wall advanced step by step under the loads of its moment.
//!
//! At each step's end, every facet's loads are assembled from the moment
//! ([`crate::environment::Moment`]), its sunlit share (shadow rays through the scene) and
//! what its hemisphere holds ([`irsig_tracer::exposure::ViewFactors`]):
//!
//! ```text
//! shortwave = DNI cos θ V + DHI F_sky + ρ_g GHI F_terrain + Σ_j F_ij (1 − α_j) E_j
//! longwave  = E_sky F_sky + σ T_g⁴ F_terrain + Σ_j F_ij (ε_j σ T_j⁴ + (1 − ε_j) L_j)
//! ```
//!
//! `E_j` and `L_j` are the shortwave and longwave irradiance facet `j` received, and `T_j`
//! its surface temperature, at the step's start: facets exchange with a lag of one step,
//! so that every facet's step reads only the previous step's values and the result is the
//! same at any thread count. The sky is isotropic (its diffuse sunlight and its longwave
//! reach a facet in proportion to the share of the hemisphere it sees), other facets are
//! Lambertian, and the ground beyond the scene is flat, unshadowed and at `T_g` (the ground
//! model's surface, or the air's). With exchange off (a named approximation), the facets a
//! facet sees count as that ground.
//!
//! Held facets keep their temperature and still radiate and reflect to the others. A facet
//! under a material map, solved by per-material walls ([`crate::mixture`]), steps one wall
//! per material with a share under the same loads; its `T_j` is their radiative mean and
//! its `α_j`, `ε_j` the fraction-weighted means of theirs.

use irsig_model::RawScene;
use irsig_thermal::{
    Facet, Loads, Orientation, STEFAN_BOLTZMANN_W_M2_K4, Scratch, ThermalError, TimeStep, step,
};
use irsig_tracer::exposure::{Exposure, ExposureOptions, ViewFactors};
use miette::miette;
use rayon::prelude::*;
use std::sync::Arc;

use crate::environment::{Environment, Moment};
use crate::mixture::Mixed;
use crate::setup::MaterialModel;
use irsig_model::material_map::MAX_MAP_MATERIALS;

/// Per facet, each part's surface temperature (unused past its parts), K.
pub type PartsK = [f64; MAX_MAP_MATERIALS];

/// The settings of the models the loop itself runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The time step and scheme.
    pub time_step: TimeStep,
    /// Sample points for the shadow rays.
    pub shadow: ExposureOptions,
    /// Whether facets exchange sunlight and longwave with each other.
    pub exchange: bool,
    /// The walls' start above the air's temperature, K: 0 in a run; the pilot's measure
    /// of what the start still weighs after the spin-up.
    pub initial_offset_k: f64,
}

/// The ground beyond the scene.
#[derive(Debug, Clone, Copy)]
pub struct Ground<'a> {
    /// Solved as an open horizontal facet of this material, or `None`: at the air's
    /// temperature.
    pub model: Option<&'a MaterialModel>,
    /// The share of sunlight it reflects.
    pub albedo: f64,
}

/// Everything the loop reads. The loop steps a list of the scene's facets (all of them, or
/// the tolerance pilot's sample); the views are in that list's order, the other per-facet
/// lists in the scene's, and a facet seen that is not stepped is stood in for by one that
/// is (`proxy`).
#[derive(Debug)]
pub struct Scenario<'a> {
    /// The scene.
    pub scene: &'a RawScene,
    /// Its BVH, for the shadow rays.
    pub exposure: &'a Exposure,
    /// The facets stepped: their indices in the scene.
    pub facets: &'a [u32],
    /// Per facet of the scene: the stepped facet (its place in `facets`) whose state it
    /// takes when another facet sees it; itself when it is stepped.
    pub proxy: &'a [u32],
    /// What each stepped facet's hemisphere holds.
    pub views: &'a ViewFactors,
    /// The material model of each solved facet's material, by slot.
    pub models: &'a [MaterialModel],
    /// Per facet of the scene: its material model's slot, or `None` when it is held.
    pub slot: &'a [Option<usize>],
    /// Per facet of the scene: its parts, when it is solved by its material map's
    /// materials (empty when none is).
    pub mix: &'a [Option<Box<Mixed>>],
    /// Per facet of the scene: the temperature it is held at, if it is.
    pub held_k: &'a [Option<f64>],
    /// Per facet of the scene: heat deposited at its wall's back, W/m².
    pub heat_w_m2: &'a [f64],
    /// Per facet of the scene: solar absorptance and broadband emissivity (a held facet's
    /// from its material where it has a thermal record, else 1 and 1: a blackbody).
    pub optics: &'a [(f64, f64)],
    /// The weather, the sun and the sky.
    pub environment: &'a Environment<'a>,
    /// The ground beyond the scene.
    pub ground: Ground<'a>,
    /// Sunlit shares to reuse, when several runs step the same facets.
    pub lit_cache: Option<&'a LitCache>,
}

/// Sunlit shares already cast, by moment and sample points per side: the tolerance
/// pilot's runs over one sample share them (the shares depend on nothing else).
#[derive(Debug, Default)]
pub struct LitCache(pub std::sync::Mutex<std::collections::HashMap<LitKey, Arc<Vec<f32>>>>);

/// A moment (its time's bits) and the sample points per side of its shadow rays.
pub type LitKey = (u64, u32);

/// The state between steps.
#[derive(Debug, Clone)]
struct State {
    /// Node temperatures, `stride` per facet (a facet uses its wall's first nodes).
    nodes: Vec<f64>,
    /// Surface temperature per facet, K (a mixed facet's radiative mean).
    surface_k: Vec<f64>,
    /// Each part's surface temperature per facet, when any facet is mixed (else empty).
    parts_k: Vec<PartsK>,
    /// The loads each facet had at the step's start.
    loads: Vec<Loads>,
    /// The ground's nodes, when it is solved.
    ground_nodes: Vec<f64>,
    /// The ground's loads at the step's start.
    ground_loads: Loads,
}

/// What a step gives each facet.
#[derive(Debug, Clone, Copy)]
struct FacetOut {
    surface_k: f64,
    parts_k: PartsK,
    loads: Loads,
}

impl Scenario<'_> {
    /// Nodes per stepped facet: the deepest wall's, or a mixed facet's walls' together.
    fn stride(&self) -> usize {
        let one = self
            .models
            .iter()
            .map(|m| m.wall.nodes())
            .max()
            .unwrap_or(1);
        let mixed = self
            .facets
            .iter()
            .filter_map(|&g| self.mixed(g as usize))
            .map(|m| {
                m.parts
                    .iter()
                    .map(|p| self.models[p.slot].wall.nodes())
                    .sum::<usize>()
            })
            .max()
            .unwrap_or(0);
        one.max(mixed)
    }

    /// Scene facet `g`'s parts, when it is solved part by part.
    fn mixed(&self, g: usize) -> Option<&Mixed> {
        self.mix.get(g).and_then(|m| m.as_deref())
    }

    /// Steps each part of the mixed facet `m`, facing as `orientation` says, in its own
    /// slice of `temps`, under the same loads, and gives each part's surface temperature
    /// and their radiative mean.
    fn step_mixed(
        &self,
        m: &Mixed,
        temps: &mut [f64],
        (before, after_loads): (&Loads, &Loads),
        (orientation, time_step): (Orientation, TimeStep),
        scratch: &mut Scratch,
    ) -> Result<(f64, PartsK), ThermalError> {
        let mut parts_k = [0.0; MAX_MAP_MATERIALS];
        let mut at = 0;
        for (k, p) in m.parts.iter().enumerate() {
            let model = &self.models[p.slot];
            let n = model.wall.nodes();
            let slice = &mut temps[at..at + n];
            let facet = Facet {
                wall: &model.wall,
                surface: &model.surface,
                orientation,
            };
            step(&facet, slice, before, after_loads, time_step, scratch)?;
            parts_k[k] = slice[0];
            at += n;
        }
        let mean = m.radiative_mean(&parts_k[..m.parts.len()], |s| {
            self.models[s].surface.thermal_emissivity
        });
        Ok((mean, parts_k))
    }

    fn orientation(&self, i: usize, moment: &Moment) -> Orientation {
        let n = self.exposure.frame(self.facets[i] as usize).normal;
        let horizontal = (n.x * n.x + n.y * n.y).sqrt();
        // EnergyPlus's rule: windward when the wind comes from within 100° of the
        // surface's outward direction; a roof (nearly horizontal) is windward, as is any
        // surface when the weather gives no direction.
        let windward = match moment.wind_from {
            Some([wx, wy]) if horizontal > 0.1 => {
                (n.x * wx + n.y * wy) / horizontal >= 100_f64.to_radians().cos()
            }
            _ => true,
        };
        Orientation {
            cos_tilt: n.z,
            windward,
        }
    }

    /// Facet `i`'s loads at `moment`, with `lit` its sunlit share and `prev` the surface
    /// temperatures and loads of the step's start.
    fn loads(
        &self,
        i: usize,
        moment: &Moment,
        lit: f32,
        prev: Previous<'_>,
        settings: &Settings,
    ) -> Loads {
        let n = self.exposure.frame(self.facets[i] as usize).normal;
        let direct = moment.to_sun.map_or(0.0, |s| {
            let cos_i = n.x * s[0] + n.y * s[1] + n.z * s[2];
            moment.dni_w_m2 * cos_i.max(0.0) * f64::from(lit)
        });
        let f_sky = f64::from(self.views.sky[i]);
        let f_terrain = f64::from(self.views.terrain[i]);
        let (seen, share) = self.views.seen_by(i);
        let ground_sw = self.ground.albedo * moment.ghi_w_m2;
        let ground_lw = STEFAN_BOLTZMANN_W_M2_K4 * prev.ground_k.powi(4);
        let mut shortwave = direct + moment.dhi_w_m2 * f_sky + ground_sw * f_terrain;
        let mut longwave = moment.longwave_down_w_m2 * f_sky + ground_lw * f_terrain;
        if settings.exchange {
            for (&j, &f) in seen.iter().zip(share) {
                let (alpha, eps) = self.optics[j as usize];
                let k = self.proxy[j as usize] as usize;
                let their = &prev.loads[k];
                let t = prev.surface_k[k];
                shortwave += f64::from(f) * (1.0 - alpha) * their.shortwave_w_m2;
                longwave += f64::from(f)
                    * (eps * STEFAN_BOLTZMANN_W_M2_K4 * t.powi(4)
                        + (1.0 - eps) * their.longwave_w_m2);
            }
        } else {
            let f: f64 = share.iter().map(|&f| f64::from(f)).sum();
            shortwave += ground_sw * f;
            longwave += ground_lw * f;
        }
        Loads {
            shortwave_w_m2: shortwave,
            longwave_w_m2: longwave,
            air_temperature_k: moment.air_temperature_k,
            dew_point_k: moment.dew_point_k,
            pressure_pa: moment.pressure_pa,
            wind_speed_m_s: moment.wind_speed_m_s,
            source_w_m2: self.heat_w_m2[self.facets[i] as usize],
        }
    }

    /// The open ground's loads at `moment`.
    fn ground_loads(moment: &Moment) -> Loads {
        Loads {
            shortwave_w_m2: moment.ghi_w_m2,
            longwave_w_m2: moment.longwave_down_w_m2,
            air_temperature_k: moment.air_temperature_k,
            dew_point_k: moment.dew_point_k,
            pressure_pa: moment.pressure_pa,
            wind_speed_m_s: moment.wind_speed_m_s,
            source_w_m2: 0.0,
        }
    }

    fn ground_k(&self, state: &State, moment: &Moment) -> f64 {
        if self.ground.model.is_some() {
            state.ground_nodes[0]
        } else {
            moment.air_temperature_k
        }
    }

    /// The state at the run's start: every wall at the air's temperature through its
    /// depth (as DIRSIG's THERM starts), held facets at their temperature, and the loads of
    /// that moment with every facet at the air's temperature.
    fn start(&self, moment: &Moment, lit: &[f32], settings: &Settings) -> State {
        let n = self.facets.len();
        let stride = self.stride();
        let t0 = moment.air_temperature_k + settings.initial_offset_k;
        let surface_k: Vec<f64> = self
            .facets
            .iter()
            .map(|&g| self.held_k[g as usize].unwrap_or(t0))
            .collect();
        let ground_nodes = self
            .ground
            .model
            .map_or_else(Vec::new, |m| m.wall.uniform_state(t0));
        let any_mixed = self
            .facets
            .iter()
            .any(|&g| self.mixed(g as usize).is_some());
        let mut state = State {
            nodes: vec![t0; n * stride],
            surface_k,
            parts_k: if any_mixed {
                vec![[t0; MAX_MAP_MATERIALS]; n]
            } else {
                Vec::new()
            },
            loads: vec![Self::ground_loads(moment); n],
            ground_nodes,
            ground_loads: Self::ground_loads(moment),
        };
        // Twice: the second pass sees the first's reflected sunlight.
        for _ in 0..2 {
            let prev = Previous {
                surface_k: &state.surface_k,
                loads: &state.loads,
                ground_k: self.ground_k(&state, moment),
            };
            let loads: Vec<Loads> = (0..n)
                .into_par_iter()
                .map(|i| self.loads(i, moment, lit[i], prev, settings))
                .collect();
            state.loads = loads;
        }
        state
    }

    /// One step of every facet, and of the ground, from the state's moment to `after`
    /// (with `lit` the sunlit shares then). Every facet reads the step's start alone, so
    /// its walls advance in place; on an error the run stops, naming the first failing
    /// facet by index whatever the threads' order.
    fn advance(
        &self,
        state: &mut State,
        after: &Moment,
        lit: &[f32],
        settings: &Settings,
    ) -> miette::Result<()> {
        let stride = self.stride();
        let prev = Previous {
            surface_k: &state.surface_k,
            loads: &state.loads,
            ground_k: self.ground_k(state, after),
        };
        let outs: Vec<Result<FacetOut, ThermalError>> = state
            .nodes
            .par_chunks_mut(stride)
            .enumerate()
            .map_init(Scratch::new, |scratch, (i, temps)| {
                let loads = self.loads(i, after, lit[i], prev, settings);
                let global = self.facets[i] as usize;
                if let (None, Some(m)) = (self.held_k[global], self.mixed(global)) {
                    let (surface_k, parts_k) = self.step_mixed(
                        m,
                        temps,
                        (&prev.loads[i], &loads),
                        (self.orientation(i, after), settings.time_step),
                        scratch,
                    )?;
                    return Ok(FacetOut {
                        surface_k,
                        parts_k,
                        loads,
                    });
                }
                let surface_k = match (self.held_k[global], self.slot[global]) {
                    (Some(t), _) => t,
                    (None, Some(slot)) => {
                        let m = &self.models[slot];
                        let temps = &mut temps[..m.wall.nodes()];
                        let facet = Facet {
                            wall: &m.wall,
                            surface: &m.surface,
                            orientation: self.orientation(i, after),
                        };
                        step(
                            &facet,
                            temps,
                            &prev.loads[i],
                            &loads,
                            settings.time_step,
                            scratch,
                        )?;
                        temps[0]
                    }
                    // Setup gives every facet that is not held a material model.
                    (None, None) => prev.surface_k[i],
                };
                Ok(FacetOut {
                    surface_k,
                    parts_k: [surface_k; MAX_MAP_MATERIALS],
                    loads,
                })
            })
            .collect();
        let mut surface_k = Vec::with_capacity(outs.len());
        let mut loads = Vec::with_capacity(outs.len());
        let keep_parts = !state.parts_k.is_empty();
        let mut parts_k = Vec::with_capacity(if keep_parts { outs.len() } else { 0 });
        for (i, out) in outs.into_iter().enumerate() {
            let out = out.map_err(|e| self.facet_error(i, &e))?;
            surface_k.push(out.surface_k);
            loads.push(out.loads);
            if keep_parts {
                parts_k.push(out.parts_k);
            }
        }
        if let Some(m) = self.ground.model {
            let after_loads = Self::ground_loads(after);
            let facet = Facet {
                wall: &m.wall,
                surface: &m.surface,
                orientation: Orientation {
                    cos_tilt: 1.0,
                    windward: true,
                },
            };
            step(
                &facet,
                &mut state.ground_nodes,
                &state.ground_loads,
                &after_loads,
                settings.time_step,
                &mut Scratch::new(),
            )
            .map_err(|e| miette!("the ground beyond the scene ({}): {e}", m.name))?;
            state.ground_loads = after_loads;
        }
        state.surface_k = surface_k;
        state.parts_k = parts_k;
        state.loads = loads;
        Ok(())
    }

    fn facet_error(&self, i: usize, e: &ThermalError) -> miette::Report {
        let global = self.facets[i] as usize;
        let f = &self.scene.facets[global];
        let object = self
            .scene
            .objects
            .get(f.object as usize)
            .map_or("?", String::as_str);
        let material = self.slot[global].map_or("?", |s| self.models[s].name.as_str());
        miette!("facet {global} (object `{object}`, material `{material}`): {e}")
    }
}

/// What a step reads of the step's start.
#[derive(Debug, Clone, Copy)]
struct Previous<'a> {
    surface_k: &'a [f64],
    loads: &'a [Loads],
    ground_k: f64,
}

/// Runs the loop from `start_s` for `steps` steps of `settings.time_step`, calling
/// `observe(k, time_s, surface_k, ground_k, parts_k)` after the start (`k = 0`) and after
/// every step; `parts_k` holds each stepped facet's parts' temperatures when any facet is
/// solved part by part, else it is empty.
///
/// # Errors
/// A moment the weather cannot give, or a facet whose balance fails (named).
pub fn run(
    scenario: &Scenario<'_>,
    settings: &Settings,
    start_s: f64,
    steps: usize,
    mut observe: impl FnMut(usize, f64, &[f64], f64, &[PartsK]) -> miette::Result<()>,
) -> miette::Result<()> {
    let cast = |m: &Moment| match m.to_sun {
        Some(s) => scenario.exposure.sunlit_fractions(
            scenario.facets,
            irsig_tracer::DVec3::from(s),
            settings.shadow,
        ),
        None => vec![0.0; scenario.facets.len()],
    };
    let lit_at = |m: &Moment| -> Arc<Vec<f32>> {
        let Some(cache) = scenario.lit_cache else {
            return Arc::new(cast(m));
        };
        let key = (m.time_s.to_bits(), settings.shadow.samples_per_side);
        let mut map = cache
            .0
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        map.entry(key).or_insert_with(|| Arc::new(cast(m))).clone()
    };
    let first = scenario.environment.at(start_s)?;
    let mut state = scenario.start(&first, &lit_at(&first), settings);
    observe(
        0,
        start_s,
        &state.surface_k,
        scenario.ground_k(&state, &first),
        &state.parts_k,
    )?;
    for k in 1..=steps {
        let t = start_s + k as f64 * settings.time_step.dt_s;
        let moment = scenario.environment.at(t)?;
        scenario
            .advance(&mut state, &moment, &lit_at(&moment), settings)
            .map_err(|e| miette!("at {}: {e}", irsig_model::time::format_utc(t)))?;
        observe(
            k,
            t,
            &state.surface_k,
            scenario.ground_k(&state, &moment),
            &state.parts_k,
        )?;
    }
    Ok(())
}
