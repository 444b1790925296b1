//! `--tolerance K`: the cheapest settings of the named models that keep the facets'
//! temperatures within K of a converged solve, chosen on a sample of the scene's facets.
//!
//! 1. **The sample.** The facets are put in classes by material (or held), by which way
//!    they face (up, down, sideways) and by their shading at the first moment and one and
//!    three hours before it (sunlit, a shadow's edge, shaded); up to [`PER_CLASS`] of each
//!    class are taken, evenly spread through it, at most [`MAX_SAMPLE`] in all. A facet the sample sees but does not
//!    hold is stood in for by a sampled facet of its class, whose temperature and loads it
//!    then takes: the pilot's only approximation of the scene.
//! 2. **The reference.** The most accurate setting of every model on offer: 60 s steps of
//!    TR-BDF2, a first cell of 0.25 mm, 8 × 8 shadow samples, 1,024 hemisphere rays,
//!    exchange on, and the longest spin-up the weather allows (up to a week).
//! 3. **Each model alone.** Every cheaper setting of one model, the others at the
//!    reference: its error is the 99th percentile over the sample and the moments of the
//!    difference from the reference.
//! 4. **The choice.** Every combination is priced by unit costs (nanoseconds per facet-step
//!    of a wall's node, an exchange entry and a shadow ray, per hemisphere ray; BENCHMARKS.md,
//!    "irsig-therm"); the cheapest whose errors sum to at most K is taken.
//! 5. **The check.** The chosen combination is run on the sample against the reference; if
//!    its 99th percentile exceeds K, the budget is cut in proportion and the choice made
//!    again (at most four times, then the reference itself).
//!
//! What the tolerance does not choose is measured and reported (the spreads): the other
//! convection correlation, Prata's sky where the weather has a longwave column, and the
//! start (walls 10 K above the air at the spin-up's start).

use irsig_model::thermal_decision::{ThermalChoice, ThermalDecision, ThermalSpread};
use miette::miette;

use crate::environment::SkyLongwave;
use crate::models::{ConvectionArg, Models, SchemeArg, Switch};
use crate::prepare::{Grid, Prepared, Run, Stepped, Walls};
use crate::solve::LitCache;

/// The most facets a class gives the sample.
pub const PER_CLASS: usize = 24;
/// The most facets in the sample.
pub const MAX_SAMPLE: usize = 512;
/// The longest spin-up the reference takes, hours.
const MAX_SPIN_UP_H: f64 = 168.0;

/// Unit costs, ns (BENCHMARKS.md, "irsig-therm"): one node of one facet's wall per
/// Backward Euler step, one exchange entry per step, one shadow ray, one hemisphere ray.
const NODE_NS: f64 = 17.0;
const EXCHANGE_NS: f64 = 4.0;
const SHADOW_RAY_NS: f64 = 250.0;
const HEMISPHERE_RAY_NS: f64 = 400.0;
/// TR-BDF2's cost over Backward Euler's (BENCHMARKS.md, "the thermal solver").
const TR_BDF2_COST: f64 = 2.35;

/// One model's settings on offer, cheapest first, the reference last.
struct Menu {
    name: &'static str,
    settings: Vec<Models>,
}

/// The sample and who stands in for every facet.
struct Sample {
    facets: Vec<u32>,
    proxy: Vec<u32>,
}

impl Sample {
    fn new(prepared: &Prepared<'_>, walls: &Walls, first_s: f64) -> miette::Result<Self> {
        let scene = prepared.scene;
        let shade = shade_signatures(prepared, first_s)?;
        let mut classes: std::collections::BTreeMap<(u32, u8, u8), Vec<u32>> = Default::default();
        for (i, f) in scene.facets.iter().enumerate() {
            let nz = prepared.exposure.frame(i).normal.z;
            let way = if nz > 0.7 {
                0
            } else if nz < -0.7 {
                2
            } else {
                1
            };
            // A facet solved part by part is a kind of its own, by its largest part.
            let mixed = if walls.is_mixed(i) { 1 << 30 } else { 0 };
            let kind = walls
                .slot_of(i)
                .map_or(u32::MAX - u32::from(f.material.0), |s| s as u32 + mixed);
            classes
                .entry((kind, way, shade[i]))
                .or_default()
                .push(i as u32);
        }
        let per_class = (MAX_SAMPLE / classes.len().max(1)).clamp(1, PER_CLASS);
        let mut facets = Vec::new();
        let mut proxy = vec![0_u32; scene.facets.len()];
        for members in classes.values() {
            let take = per_class.min(members.len());
            let first = facets.len() as u32;
            for k in 0..take {
                facets.push(members[k * members.len() / take]);
            }
            for (n, &m) in members.iter().enumerate() {
                proxy[m as usize] = first + (n % take) as u32;
            }
        }
        for (local, &g) in facets.iter().enumerate() {
            proxy[g as usize] = local as u32;
        }
        Ok(Self { facets, proxy })
    }
}

/// Each facet's shading at the first moment and one and three hours before it, in one
/// number: per moment 0 (sunlit, or the sun down), 1 (partly shaded) or 2 (shaded, or
/// facing away), from 4 × 4 shadow rays. A shadow's edge and the ground a shadow has
/// just left are classes of their own, so the sample holds them.
fn shade_signatures(prepared: &Prepared<'_>, first_s: f64) -> miette::Result<Vec<u8>> {
    let n = prepared.scene.facets.len();
    let all: Vec<u32> = (0..n as u32).collect();
    let mut signature = vec![0_u8; n];
    for hours in [0.0, 1.0, 3.0] {
        let moment = prepared.environment.at(first_s - hours * 3600.0)?;
        let Some(s) = moment.to_sun else {
            continue;
        };
        let lit = prepared.exposure.sunlit_fractions(
            &all,
            irsig_tracer::DVec3::from(s),
            irsig_tracer::exposure::ExposureOptions {
                samples_per_side: 4,
            },
        );
        for (sig, l) in signature.iter_mut().zip(lit) {
            let class = if l >= 1.0 {
                0
            } else if l > 0.0 {
                1
            } else {
                2
            };
            *sig = *sig * 3 + class;
        }
    }
    Ok(signature)
}

/// The reference settings: the most accurate on offer.
fn reference(base: &Models, spin_up_h: f64) -> Models {
    Models {
        step_s: 60.0,
        scheme: SchemeArg::TrBdf2,
        first_cell_mm: 0.25,
        shadow_samples: 8,
        hemisphere_rays: 1024,
        exchange: Switch::On,
        convection: base.convection,
        mixture: base.mixture,
        spin_up_h,
    }
}

/// Every model's menu, each setting the reference with that one model changed.
fn menus(reference: &Models, times: &[f64]) -> Vec<Menu> {
    let with = |f: &dyn Fn(&mut Models)| {
        let mut m = reference.clone();
        f(&mut m);
        m
    };
    // A step must put every moment on the grid from the first.
    let fits = |step: f64| {
        times
            .iter()
            .all(|t| ((t - times[0]) / step - ((t - times[0]) / step).round()).abs() < 1e-6)
    };
    let mut steps: Vec<Models> = [1800.0, 900.0, 600.0, 300.0, 120.0]
        .into_iter()
        .filter(|&s| fits(s))
        .map(|s| {
            with(&|m| {
                m.step_s = s;
                m.scheme = SchemeArg::BackwardEuler;
            })
        })
        .collect();
    steps.extend(
        [600.0, 300.0, 120.0]
            .into_iter()
            .filter(|&s| fits(s))
            .map(|s| with(&|m| m.step_s = s)),
    );
    let spin: Vec<Models> = [24.0, 48.0, 72.0, 120.0]
        .into_iter()
        .filter(|&h| h < reference.spin_up_h)
        .map(|h| with(&|m| m.spin_up_h = h))
        .collect();
    vec![
        Menu {
            name: "time step",
            settings: steps,
        },
        Menu {
            name: "cells",
            settings: [10.0, 5.0, 2.0, 1.0, 0.5]
                .into_iter()
                .map(|c| with(&|m| m.first_cell_mm = c))
                .collect(),
        },
        Menu {
            name: "shadow samples",
            settings: [1, 2, 4]
                .into_iter()
                .map(|k| with(&|m| m.shadow_samples = k))
                .collect(),
        },
        Menu {
            name: "hemisphere rays",
            settings: [16, 64, 256]
                .into_iter()
                .map(|r| with(&|m| m.hemisphere_rays = r))
                .collect(),
        },
        Menu {
            name: "exchange",
            settings: vec![with(&|m| m.exchange = Switch::Off)],
        },
        Menu {
            name: "spin-up",
            settings: spin,
        },
    ]
}

/// One model's setting as its flag spells it.
fn setting(name: &str, m: &Models) -> String {
    match name {
        "time step" => format!(
            "{} s {}",
            m.step_s,
            match m.scheme {
                SchemeArg::BackwardEuler => "backward-euler",
                SchemeArg::CrankNicolson => "crank-nicolson",
                SchemeArg::TrBdf2 => "tr-bdf2",
            }
        ),
        "cells" => format!("first {} mm", m.first_cell_mm),
        "shadow samples" => format!("{0} x {0}", m.shadow_samples),
        "hemisphere rays" => m.hemisphere_rays.to_string(),
        "exchange" => if m.exchange == Switch::On {
            "on"
        } else {
            "off"
        }
        .into(),
        _ => format!("{} h", m.spin_up_h),
    }
}

/// The pilot's runs on its sample.
struct Pilot<'p, 'a> {
    prepared: &'p Prepared<'a>,
    sample: Sample,
    times: &'p [f64],
    /// The sample's sunlit shares, cast once per moment and sample count for every run.
    lit: LitCache,
}

impl Pilot<'_, '_> {
    /// The sample's temperatures at the moments, flat (moment after moment).
    fn run(&self, models: &Models, offset_k: f64, sky: SkyLongwave) -> miette::Result<Vec<f64>> {
        let walls = self.prepared.walls(models)?;
        let views = self.prepared.views(&self.sample.facets, models)?;
        let grid = Grid::new(models, self.times)?;
        let outcome = self.prepared.run_on(&Run {
            stepped: Stepped {
                facets: &self.sample.facets,
                proxy: &self.sample.proxy,
            },
            views: &views,
            walls: &walls,
            models,
            grid: &grid,
            offset_k,
            sky,
            history: false,
            progress: false,
            lit_cache: Some(&self.lit),
        })?;
        Ok(outcome.surface_k.concat())
    }

    /// Predicted cost of a run of `models`, ns per facet (comparable between settings,
    /// not a time), with `nodes` the mean wall's nodes and `entries` the mean exchange
    /// entries its settings give.
    fn cost(&self, models: &Models, nodes: f64, entries: f64) -> f64 {
        let span = self.times.last().unwrap_or(&0.0) - self.times[0];
        let steps = (models.spin_up_h * 3600.0 + span) / models.step_s;
        let scheme = if models.scheme == SchemeArg::BackwardEuler {
            1.0
        } else {
            TR_BDF2_COST
        };
        let exchange = if models.exchange == Switch::On {
            EXCHANGE_NS * entries
        } else {
            0.0
        };
        // Shadow rays: half the facets face the sun, half the day.
        let shadow = 0.25 * f64::from(models.shadow_samples).powi(2) * SHADOW_RAY_NS;
        steps * (NODE_NS * scheme * nodes + exchange + shadow)
            + f64::from(models.hemisphere_rays) * HEMISPHERE_RAY_NS
    }
}

/// The 99th percentile and the largest of `|a − b|`, K.
fn difference(a: &[f64], b: &[f64]) -> (f64, f64) {
    let mut d: Vec<f64> = a.iter().zip(b).map(|(x, y)| (x - y).abs()).collect();
    d.sort_by(f64::total_cmp);
    let p99 = d[((d.len() as f64 * 0.99).ceil() as usize).clamp(1, d.len()) - 1];
    (p99, *d.last().unwrap_or(&0.0))
}

/// The longest spin-up the weather allows before the first moment, hours.
fn available_spin_up_h(prepared: &Prepared<'_>, first: f64) -> f64 {
    let start = prepared
        .environment
        .weather
        .span_s()
        .map_or(first, |(s, _)| s);
    ((first - start) / 3600.0).floor().min(MAX_SPIN_UP_H)
}

/// Chooses the settings for `tolerance_k`, measures them, and returns them with the
/// decision.
///
/// # Errors
/// A tolerance below 0.001 K, a weather record with less than a day before the first
/// moment, or a run that fails.
pub fn decide(
    prepared: &Prepared<'_>,
    base: &Models,
    times: &[f64],
    tolerance_k: f64,
) -> miette::Result<(Models, ThermalDecision)> {
    if !(tolerance_k.is_finite() && tolerance_k >= 1e-3) {
        return Err(irsig_cli::usage_error(format!(
            "--tolerance: expected at least 0.001 K, found {tolerance_k}"
        )));
    }
    let spin = available_spin_up_h(prepared, times[0]);
    if spin < 24.0 {
        return Err(miette!(
            "--tolerance needs at least a day of weather before the first moment to spin up \
             its reference; the record gives {spin} h"
        ));
    }
    let reference = reference(base, spin);
    let walls = prepared.walls(&reference)?;
    let pilot = Pilot {
        prepared,
        sample: Sample::new(prepared, &walls, times[0])?,
        times,
        lit: LitCache::default(),
    };
    let sky = prepared.environment.sky;
    let truth = pilot.run(&reference, 0.0, sky)?;
    let mut costs = Costs::default();
    costs.measure(&pilot, &reference)?;
    // Each model alone: every setting's models and error, the reference last.
    let menus = menus(&reference, times);
    let mut table: Vec<Vec<(Models, f64)>> = Vec::new();
    for menu in &menus {
        let mut row = Vec::new();
        for m in &menu.settings {
            costs.measure(&pilot, m)?;
            row.push((m.clone(), difference(&pilot.run(m, 0.0, sky)?, &truth).0));
        }
        row.push((reference.clone(), 0.0));
        table.push(row);
    }
    let reference_cost = costs.of(&pilot, &reference);
    let (chosen, picks, measured) =
        choose_and_check(&pilot, &table, &costs, &reference, &truth, tolerance_k)?;
    let spreads = spreads(&pilot, &chosen)?;
    let models = menus
        .iter()
        .zip(&table)
        .zip(&picks)
        .map(|((menu, row), &k)| ThermalChoice {
            model: menu.name.to_owned(),
            setting: setting(menu.name, &row[k].0),
            reference: setting(menu.name, &reference),
            error_k: row[k].1,
            relative_cost: costs.of(&pilot, &row[k].0) / reference_cost,
        })
        .collect::<Vec<_>>();
    let decision = ThermalDecision {
        tolerance_k,
        facets: prepared.scene.facets.len() as u64,
        pilot_facets: pilot.sample.facets.len() as u64,
        predicted_k: models.iter().map(|m| m.error_k).sum(),
        models,
        measured_p99_k: measured.0,
        measured_max_k: measured.1,
        relative_cost: costs.of(&pilot, &chosen) / reference_cost,
        spreads,
    };
    Ok((chosen, decision))
}

/// What the cost of a setting depends on, measured once per setting: the mean wall's nodes
/// by first cell, the mean exchange entries by hemisphere rays.
#[derive(Debug, Default)]
struct Costs {
    nodes: Vec<(u64, f64)>,
    entries: Vec<(u32, f64)>,
}

impl Costs {
    fn measure(&mut self, pilot: &Pilot<'_, '_>, m: &Models) -> miette::Result<()> {
        let cell = m.first_cell_mm.to_bits();
        if !self.nodes.iter().any(|(c, _)| *c == cell) {
            let walls = pilot.prepared.walls(m)?;
            self.nodes
                .push((cell, walls.mean_nodes(&pilot.sample.facets)));
        }
        if !self.entries.iter().any(|(r, _)| *r == m.hemisphere_rays) {
            self.entries
                .push((m.hemisphere_rays, mean_entries(pilot, m)?));
        }
        Ok(())
    }

    fn of(&self, pilot: &Pilot<'_, '_>, m: &Models) -> f64 {
        let cell = m.first_cell_mm.to_bits();
        let nodes = self
            .nodes
            .iter()
            .find(|(c, _)| *c == cell)
            .map_or(0.0, |x| x.1);
        let entries = self
            .entries
            .iter()
            .find(|(r, _)| *r == m.hemisphere_rays)
            .map_or(0.0, |x| x.1);
        pilot.cost(m, nodes, entries)
    }
}

/// The mean number of facets a sampled facet's hemisphere rays meet, by these settings.
fn mean_entries(pilot: &Pilot<'_, '_>, models: &Models) -> miette::Result<f64> {
    let views = pilot.prepared.views(&pilot.sample.facets, models)?;
    Ok(views.seen.len() as f64 / pilot.sample.facets.len().max(1) as f64)
}

/// The combination of one setting per model whose errors sum within `budget` at the least
/// cost (ties to the smaller error, then the first found).
fn cheapest(
    pilot: &Pilot<'_, '_>,
    table: &[Vec<(Models, f64)>],
    costs: &Costs,
    reference: &Models,
    budget: f64,
) -> Vec<usize> {
    let mut best: Option<(f64, f64, Vec<usize>)> = None;
    let mut pick = vec![0_usize; table.len()];
    loop {
        let error: f64 = pick.iter().zip(table).map(|(&k, row)| row[k].1).sum();
        if error <= budget {
            let cost = costs.of(pilot, &assemble(table, &pick, reference));
            if best
                .as_ref()
                .is_none_or(|(c, e, _)| cost < *c || (cost <= *c && error < *e))
            {
                best = Some((cost, error, pick.clone()));
            }
        }
        // The next combination, odometer-wise.
        let mut m = 0;
        while m < table.len() {
            pick[m] += 1;
            if pick[m] < table[m].len() {
                break;
            }
            pick[m] = 0;
            m += 1;
        }
        if m == table.len() {
            break;
        }
    }
    best.map_or_else(|| table.iter().map(|r| r.len() - 1).collect(), |b| b.2)
}

/// The settings of a pick: each model's setting taken from its menu.
fn assemble(table: &[Vec<(Models, f64)>], pick: &[usize], reference: &Models) -> Models {
    let mut m = reference.clone();
    for (row, &k) in table.iter().zip(pick) {
        let s = &row[k].0;
        // Each menu varies its own model; copy whatever differs from the reference.
        if s.step_s.to_bits() != reference.step_s.to_bits() || s.scheme != reference.scheme {
            m.step_s = s.step_s;
            m.scheme = s.scheme;
        }
        if s.first_cell_mm.to_bits() != reference.first_cell_mm.to_bits() {
            m.first_cell_mm = s.first_cell_mm;
        }
        if s.shadow_samples != reference.shadow_samples {
            m.shadow_samples = s.shadow_samples;
        }
        if s.hemisphere_rays != reference.hemisphere_rays {
            m.hemisphere_rays = s.hemisphere_rays;
        }
        if s.exchange != reference.exchange {
            m.exchange = s.exchange;
        }
        if s.spin_up_h.to_bits() != reference.spin_up_h.to_bits() {
            m.spin_up_h = s.spin_up_h;
        }
    }
    m
}

/// The cheapest pick within the tolerance that also measures within it, all models at once.
fn choose_and_check(
    pilot: &Pilot<'_, '_>,
    table: &[Vec<(Models, f64)>],
    costs: &Costs,
    reference: &Models,
    truth: &[f64],
    tolerance_k: f64,
) -> miette::Result<(Models, Vec<usize>, (f64, f64))> {
    let mut budget = tolerance_k;
    for _ in 0..4 {
        let pick = cheapest(pilot, table, costs, reference, budget);
        let chosen = assemble(table, &pick, reference);
        let measured = difference(
            &pilot.run(&chosen, 0.0, pilot.prepared.environment.sky)?,
            truth,
        );
        if measured.0 <= tolerance_k {
            return Ok((chosen, pick, measured));
        }
        budget *= 0.8 * tolerance_k / measured.0;
    }
    let pick: Vec<usize> = table.iter().map(|r| r.len() - 1).collect();
    Ok((reference.clone(), pick, (0.0, 0.0)))
}

/// What the tolerance does not choose, at the chosen settings.
fn spreads(pilot: &Pilot<'_, '_>, chosen: &Models) -> miette::Result<Vec<ThermalSpread>> {
    let sky = pilot.prepared.environment.sky;
    let at_chosen = pilot.run(chosen, 0.0, sky)?;
    let mut out = Vec::new();
    let mut other = chosen.clone();
    other.convection = match chosen.convection {
        ConvectionArg::Doe2 => ConvectionArg::Mcadams,
        ConvectionArg::Mcadams => ConvectionArg::Doe2,
    };
    let (p99_k, max_k) = difference(&pilot.run(&other, 0.0, sky)?, &at_chosen);
    out.push(ThermalSpread {
        what: format!(
            "convection: {} against {}",
            convection_name(other.convection),
            convection_name(chosen.convection)
        ),
        p99_k,
        max_k,
    });
    if sky != SkyLongwave::Prata {
        let (p99_k, max_k) = difference(&pilot.run(chosen, 0.0, SkyLongwave::Prata)?, &at_chosen);
        out.push(ThermalSpread {
            what: format!("sky longwave: prata against {}", sky.describe()),
            p99_k,
            max_k,
        });
    }
    let (p99_k, max_k) = difference(&pilot.run(chosen, 10.0, sky)?, &at_chosen);
    out.push(ThermalSpread {
        what: format!(
            "start: walls 10 K above the air {} h before the first moment",
            chosen.spin_up_h
        ),
        p99_k,
        max_k,
    });
    Ok(out)
}

fn convection_name(c: ConvectionArg) -> &'static str {
    match c {
        ConvectionArg::Doe2 => "doe2",
        ConvectionArg::Mcadams => "mcadams",
    }
}
