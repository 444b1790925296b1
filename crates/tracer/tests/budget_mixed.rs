//! The error budget in mixed pixels against central finite differences: a generated scene
//! of a thin pole (two, of one material, as two objects) against the ground and the sky,
//! and a glass pane whose edges cut pixels and whose reflection meets the ground, traced
//! with refinement at night and by day, and with sky-view rays. Each material's temperature and emissivity, one
//! object's temperature and every facet's temperature are moved by ± a small step; the
//! pixel's charges ([`irsig_tracer::Frame::charges`]) summed over the groups the input
//! governs must be the central difference of the pixel's radiance. The settings are
//! those of a saved decision, the same for every run; a pixel whose refinement differs
//! between the runs (another estimator) is left out and counted.

use crate::air::{BUDGET_AIR, FnAir};
use irsig_model::decision::{Decision, SwitchableModel};
use irsig_model::{MaterialLibrary, RawScene, View};
use irsig_radiometry::Band;
use irsig_tracer::DVec3;
use irsig_tracer::pilot::refinement_of;
use irsig_tracer::testing::{box_mesh, grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Camera, Frame, Sun, SunBeam, Tile, TraceOptions, Tracer};

/// The parts, object by object: (material, kinetic temperature K).
const PARTS: [(u16, f64); 4] = [(1, 290.0), (2, 315.0), (2, 311.0), (3, 296.0)];

/// The materials: (id, ε, specular share): stone, the poles' paint, glass.
const MATERIALS: [(u16, f64, f64); 3] = [(1, 0.9, 0.0), (2, 0.95, 0.0), (3, 0.84, 0.9)];

/// What is moved: each part's temperature step and each material's ε step.
#[derive(Debug, Clone, Copy, Default)]
struct Step {
    by_part_k: [f64; 4],
    by_material_eps: [f64; 3],
}

fn scene(step: &Step) -> RawScene {
    // Ground 60 m deep; two poles 8 cm and 10 cm wide, 4 m tall, 25 and 30 m out (under
    // half a pixel of the 64-pixel, 24° image); a glass pane 4 m × 3 m, 18 m out.
    let meshes = [
        ground_quad([-40.0, -10.0], [40.0, 60.0], 0.0),
        box_mesh([-0.04, 25.0, 0.0], [0.04, 25.08, 4.0]),
        box_mesh([3.0, 30.0, 0.0], [3.1, 30.1, 4.0]),
        box_mesh([-6.0, 18.0, 0.0], [-2.0, 18.05, 3.0]),
    ];
    let parts: Vec<(&_, u16, f64)> = meshes
        .iter()
        .zip(PARTS)
        .zip(step.by_part_k)
        .map(|((mesh, (material, t)), dt)| (mesh, material, t + dt))
        .collect();
    raw_scene(&parts)
}

fn materials(step: &Step) -> MaterialLibrary {
    let m: Vec<(u16, f64, f64)> = MATERIALS
        .iter()
        .zip(step.by_material_eps)
        .map(|(&(id, eps, s), de)| (id, eps + de, s))
        .collect();
    grey_materials(&m)
}

/// The saved decisions: without sky-view rays, and with 16 (whose facets the budget
/// charges too).
const DECISIONS: [(&str, &str); 2] = [
    (
        "budget-mixed.decision.ron",
        include_str!("data/budget-mixed.decision.ron"),
    ),
    (
        "budget-mixed-sky-view.decision.ron",
        include_str!("data/budget-mixed-sky-view.decision.ron"),
    ),
];

fn decision(sky_view: bool) -> Decision {
    let (name, text) = DECISIONS[usize::from(sky_view)];
    irsig_formats::canonical::from_ron(name, text).unwrap()
}

fn camera() -> Camera {
    Camera::from_view(&View::LookAt {
        position_m: [0.0, -5.0, 2.0],
        target_m: [-1.0, 20.0, 1.5],
        up: [0.0, 0.0, 1.0],
        pixels: [64, 64],
        fov_deg: [24.0, 24.0],
        gain_dc_per_k: None,
    })
    .unwrap()
}

/// One frame with every step of `step` applied, the settings of the saved decision, the
/// budget's groups the objects (`charged`).
fn frame(step: &Step, (day, sky_view): (bool, bool), charged: bool) -> Frame {
    let (tracer, options) = tracer_and_options(step, (day, sky_view), charged);
    tracer.render(&camera(), &options, &|_| {}).unwrap()
}

/// The tracer [`frame`] renders with, and its options.
fn tracer_and_options(
    step: &Step,
    (day, sky_view): (bool, bool),
    charged: bool,
) -> (Tracer<Band, FnAir>, TraceOptions) {
    let d = decision(sky_view);
    let setting = |m: SwitchableModel| d.choice(m).unwrap().setting.parse::<u32>().unwrap();
    let options = TraceOptions {
        specular_bounces: setting(SwitchableModel::Bounces),
        sky_view_rays: setting(SwitchableModel::SkyView),
        ..TraceOptions::default()
    };
    let raw = scene(step);
    let groups = raw.facets.iter().map(|f| f.object).collect();
    let sun = day.then(|| {
        Sun::new(
            DVec3::new(0.4, -0.5, 0.75),
            vec![SunBeam::uniform(20.0).unwrap()],
        )
    });
    let tracer = Tracer::new(&raw, &materials(step), Band::default(), BUDGET_AIR)
        .unwrap()
        .with_sun(sun)
        .unwrap()
        .with_refinement(Some(refinement_of(d.sampling.as_ref().unwrap())))
        .unwrap()
        .with_budget_groups(charged.then_some(groups));
    (tracer, options)
}

/// An input: which objects it moves together, and its step.
#[derive(Debug)]
struct Input {
    name: &'static str,
    objects: Vec<u32>,
    temperature: bool,
    step: f64,
}

impl Input {
    fn steps(&self, sign: f64) -> Step {
        let mut s = Step::default();
        for &o in &self.objects {
            if self.temperature {
                s.by_part_k[o as usize] = sign * self.step;
            } else {
                let material = PARTS[o as usize].0;
                let m = MATERIALS.iter().position(|x| x.0 == material).unwrap();
                s.by_material_eps[m] = sign * self.step;
            }
        }
        s
    }
}

fn inputs() -> Vec<Input> {
    let objects_of = |m: u16| -> Vec<u32> {
        (0..PARTS.len() as u32)
            .filter(|&o| PARTS[o as usize].0 == m)
            .collect()
    };
    let t = |name, objects| Input {
        name,
        objects,
        temperature: true,
        step: 0.01,
    };
    let e = |name, objects| Input {
        name,
        objects,
        temperature: false,
        step: 1e-4,
    };
    vec![
        t("stone T", objects_of(1)),
        t("paint T", objects_of(2)),
        t("glass T", objects_of(3)),
        t("one pole's T (per object)", vec![1]),
        t("every facet's T", (0..PARTS.len() as u32).collect()),
        e("stone eps", objects_of(1)),
        e("paint eps", objects_of(2)),
        e("glass eps", objects_of(3)),
    ]
}

/// The p-th percentile of `v` (nearest rank).
fn percentile(mut v: Vec<f64>, p: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    let k = ((p / 100.0 * v.len() as f64).ceil() as usize).clamp(1, v.len());
    v[k - 1]
}

fn check(day: bool, sky_view: bool) {
    let run = (day, sky_view);
    let base = frame(&Step::default(), run, true);
    let facet_objects: Vec<u32> = scene(&Step::default())
        .facets
        .iter()
        .map(|f| f.object)
        .collect();
    let n = base.radiance_w_m2_sr.len();
    assert_eq!(base.charges.len(), n);
    let mut refined_total = 0;
    for input in inputs() {
        let up = frame(&input.steps(1.0), run, false);
        let down = frame(&input.steps(-1.0), run, false);
        let (mut plain_worst, mut refined, mut switched, mut zero, mut centre_off) =
            (0.0_f64, Vec::new(), 0, 0, 0);
        for i in 0..n {
            let s = &base.sampling[i];
            let same = |f: &Frame| f.sampling[i].rays == s.rays && f.sampling[i].levels == s.levels;
            if !same(&up) || !same(&down) {
                switched += 1;
                continue;
            }
            let fd = (up.radiance_w_m2_sr[i] - down.radiance_w_m2_sr[i]) / (2.0 * input.step);
            let budget: f64 = base
                .charges
                .pixel(i)
                .iter()
                .filter(|c| input.objects.contains(&c.group))
                .map(|c| {
                    f64::from(if input.temperature {
                        c.temperature_sensitivity
                    } else {
                        c.emissivity_sensitivity
                    })
                })
                .sum();
            if fd == 0.0 {
                assert!(
                    budget == 0.0,
                    "{}: pixel {i} charged {budget} for nothing",
                    input.name
                );
                continue;
            }
            // No pixel that holds the input gets nothing from it.
            zero += usize::from(budget == 0.0);
            let off = (budget / fd - 1.0).abs();
            if s.rays > 1 {
                refined.push(off);
                // The centre ray's facet alone, as the budget once had it.
                let centre_object = facet_objects.get(base.truth[i].facet as usize);
                let centre = if centre_object.is_some_and(|o| input.objects.contains(o)) {
                    f64::from(if input.temperature {
                        s.temperature_sensitivity
                    } else {
                        s.emissivity_sensitivity
                    })
                } else {
                    0.0
                };
                centre_off += usize::from((centre / fd - 1.0).abs() > 0.05);
            } else {
                plain_worst = plain_worst.max(off);
            }
        }
        let when = match run {
            (false, false) => "night",
            (true, false) => "day",
            (_, true) => "sky-view rays",
        };
        assert_eq!(zero, 0, "{when}, {}: {zero} pixels got 0", input.name);
        assert!(
            plain_worst <= 1e-4,
            "{when}, {}: plain pixels off by {plain_worst}",
            input.name
        );
        assert!(
            switched * 20 <= n,
            "{when}, {}: {switched} pixels switched refinement",
            input.name
        );
        if !refined.is_empty() {
            let p95 = percentile(refined.clone(), 95.0);
            assert!(
                p95 <= 0.02,
                "{when}, {}: refined pixels off by {p95} at p95 ({} pixels, {switched} \
                 switched and left out)",
                input.name,
                refined.len()
            );
        }
        refined_total += refined.len();
        // The scene mixes: the mean over the rays of whatever they met, times the centre's
        // σ, misses the input in some refined pixels.
        if input.name == "stone T" {
            assert!(
                centre_off >= 10,
                "{when}: only {centre_off} refined pixels where the centre's rule is off"
            );
        }
    }
    assert!(
        refined_total >= 100,
        "only {refined_total} refined comparisons"
    );
}

#[test]
fn mixed_pixels_budget_matches_finite_differences_at_night() {
    check(false, false);
}

#[test]
fn mixed_pixels_budget_matches_finite_differences_with_sky_view_rays() {
    // The ground beside the poles and below the glass sees them through its sky-view
    // rays: those pixels hold their partials too.
    check(false, true);
}

#[test]
fn mixed_pixels_budget_matches_finite_differences_by_day() {
    check(true, false);
}

#[test]
fn a_tiles_charges_are_the_frames_at_any_thread_count() {
    let (tracer, options) = tracer_and_options(&Step::default(), (true, true), true);
    let whole = tracer.render(&camera(), &options, &|_| {}).unwrap();
    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| tracer.render(&camera(), &options, &|_| {}).unwrap());
    assert_eq!(one_thread.charges, whole.charges);
    let tile = Tile {
        x: 20,
        y: 24,
        width: 24,
        height: 16,
    };
    let part = tracer
        .render_tile(&camera(), &options, tile, &|_| {})
        .unwrap();
    let mut mixed = 0;
    for r in 0..tile.height {
        for c in 0..tile.width {
            let j = (r * tile.width + c) as usize;
            let i = ((tile.y + r) * 64 + tile.x + c) as usize;
            assert_eq!(part.charges.pixel(j), whole.charges.pixel(i), "({c}, {r})");
            assert_eq!(part.charges.rays(j), whole.charges.rays(i));
            mixed += usize::from(whole.charges.pixel(i).len() > 1);
        }
    }
    assert!(mixed > 0, "the tile holds no pixel of two groups");
}
