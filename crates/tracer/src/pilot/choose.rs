//! The choice: the cheapest combination of settings whose error holds in every class and
//! over the frame, and what a rendering with it costs.
//!
//! The error of a combination at a point is bounded by the sum of its models' errors there.
//! A combination is allowed when, with `T_det` the share of the tolerance left to the
//! deterministic models (half; refinement has the other half):
//! - in every class the decision guarantees, the 90th percentile of that bound (an upper
//!   bound with 95 % confidence from the class's points) is within `T_det`, and no model
//!   alone changes any of its points by more than the tolerance;
//! - over the frame, the bound's percentile (each point weighted by the pixels it stands
//!   for, at a percentile halfway to 100 for the sample's own uncertainty) is within
//!   `T_det`.
//!
//! A class whose most accurate settings are themselves further than `T_det` from converged
//! cannot be guaranteed: it is listed, and its pixels marked.
//!
//! Costs are counts (rays, path evaluations and path-term calls per sub-band, sky and
//! table precomputations) times unit costs measured once on the reference machine
//! ([`UNIT_COSTS`], BENCHMARKS.md), so the choice is the same on every run of the same
//! inputs; the BVH's cost per ray grows with the logarithm of its triangles.

use irsig_atmosphere::SubBandCount;

use crate::path_table::PathTermsMode;
use crate::pilot::classes::Census;
use crate::pilot::measure::Measured;
use crate::pilot::stats::{confident_rank, order_statistic, weighted_percentile};
use crate::pilot::{PilotSpace, Supersample};

/// Unit costs of the cost model, ns of one core's time (BENCHMARKS.md "The tolerance
/// pilot's cost model"): a ray through a BVH of `t` triangles costs
/// `ray_base + ray_per_log2 · log2(t)`; a node and a hemisphere ray evaluated in one
/// sub-band; a path-table lookup in one sub-band.
pub(crate) struct UnitCosts {
    pub(crate) ray_base_ns: f64,
    pub(crate) ray_per_log2_ns: f64,
    pub(crate) node_eval_ns: f64,
    pub(crate) hemi_eval_ns: f64,
    pub(crate) table_lookup_ns: f64,
}

/// The measured unit costs (BENCHMARKS.md "The tolerance pilot's cost model"): fitted to
/// single-thread renderings of the quickstart at 128 × 96 with 1, 4, 16 and all 108
/// sub-bands, 1 to 16 × 16 rays a pixel, 0 and 64 sky-view rays, exact and tabulated path
/// terms, the table build's cost taken out of the tabulated ones.
pub(crate) const UNIT_COSTS: UnitCosts = UnitCosts {
    ray_base_ns: 60.0,
    ray_per_log2_ns: 14.0,
    node_eval_ns: 22.0,
    hemi_eval_ns: 18.0,
    table_lookup_ns: 10.0,
};

/// A path-term call for a further sub-band of a path already located, as a share of the
/// first call's cost (the sub-bands share the path's grid search, but the layered walk's
/// curve of growth is each sub-band's own): 150 of 165 ns by a sensor 5 m up, 243 of 327
/// at 1 km.
const PATH_ALONG_SHARE: f64 = 0.8;

/// Paths a refined pixel is assumed to cost while combinations are compared (before the
/// trial measures it): two levels from the edge side, 8 × (16 + 64).
const PRIOR_PATHS_PER_CANDIDATE: f64 = 640.0;

/// The paths at each side assumed before the trial (`(side, paths)`): those two levels.
const PRIOR_PATHS_BY_SIDE: [(u32, f64); 2] = [(4, 128.0), (8, 512.0)];

/// The models a combination sets ([`irsig_model::decision::SwitchableModel::ALL`]).
pub(crate) const MODELS: usize = 8;
/// The sun's index in a combination (`lit`, [`crate::pilot::SunOffer`]).
pub(crate) const SUN_MODEL: usize = 6;
/// The shadow rays' index in a combination.
pub(crate) const SHADOW_RAYS_MODEL: usize = 7;

/// A combination: one index per model ([`irsig_model::decision::SwitchableModel::ALL`]
/// order), into its list (without a sun, the sun's two models have one setting each, and
/// no error).
pub(crate) type Combo = [usize; MODELS];

/// What a path meets on average, each point weighted by what it stands for.
#[derive(Debug, Clone, Default)]
pub(crate) struct PathMix {
    /// Share of paths whose primary ray hits a facet.
    pub(crate) hit: f64,
    /// Share whose first facet casts sky-view rays.
    pub(crate) diffuse: f64,
    /// Facets evaluated per path.
    pub(crate) nodes: f64,
    /// Nodes with a diffuse part: each casts the shadow rays of a sunlit path.
    pub(crate) lit_nodes: f64,
    /// Reflection rays per path at each bounce limit.
    pub(crate) reflections: Vec<f64>,
}

impl PathMix {
    /// The mix of the points `keep` accepts.
    fn of(
        census: &Census,
        measured: &[Measured],
        bounces: usize,
        keep: impl Fn(&super::classes::SamplePoint) -> bool,
    ) -> Option<Self> {
        let mut total = 0.0;
        let mut mix = Self {
            reflections: vec![0.0; bounces],
            ..Self::default()
        };
        for (p, m) in census.points.iter().zip(measured) {
            if !keep(p) {
                continue;
            }
            let w = census.classes[p.class].weight();
            total += w;
            mix.hit += w * f64::from(u8::from(m.hit));
            mix.diffuse += w * f64::from(u8::from(m.diffuse));
            mix.nodes += w * f64::from(m.nodes);
            mix.lit_nodes += w * f64::from(m.lit_nodes);
            for (r, &n) in mix.reflections.iter_mut().zip(&m.reflection_rays) {
                *r += w * f64::from(n);
            }
        }
        if total <= 0.0 {
            return None;
        }
        mix.hit /= total;
        mix.diffuse /= total;
        mix.nodes /= total;
        mix.lit_nodes /= total;
        for r in &mut mix.reflections {
            *r /= total;
        }
        Some(mix)
    }
}

/// The frame's counts the cost model reads, each point weighted by what it stands for.
#[derive(Debug, Clone)]
pub(crate) struct Counts {
    pub(crate) pixels: f64,
    /// What a centre ray's path meets, over the frame.
    pub(crate) frame: PathMix,
    /// What a refined pixel's paths meet: the mix of the sample's points on refinement
    /// candidates (edges are mostly sky against an object, so their paths are cheaper
    /// than the frame's), the frame's when no point lies on one.
    pub(crate) refined: PathMix,
    /// Refinement candidates (pixels).
    pub(crate) candidates: f64,
    /// Paths per refined pixel.
    pub(crate) paths_per_candidate: f64,
    /// A refined pixel's paths at each side (`(side, paths)`): what shares its sky-view
    /// rays out.
    pub(crate) paths_by_side: Vec<(u32, f64)>,
    /// Triangles in the BVH.
    pub(crate) triangles: f64,
}

impl Counts {
    /// What a refinement trial measured, where it refined any pixel: its paths per
    /// candidate, and per refinement side.
    pub(crate) fn take_trial(&mut self, trial: &super::trial::Trial) {
        if trial.pixels > 0 {
            self.paths_per_candidate = trial.paths_per_candidate;
            self.paths_by_side.clone_from(&trial.paths_by_side);
        }
    }

    pub(crate) fn of(
        census: &Census,
        measured: &[Measured],
        triangles: usize,
        bounces: usize,
    ) -> Self {
        let frame = PathMix::of(census, measured, bounces, |_| true).unwrap_or(PathMix {
            reflections: vec![0.0; bounces],
            ..PathMix::default()
        });
        let on_candidate = |p: &super::classes::SamplePoint| {
            usize::try_from(p.pixel)
                .ok()
                .and_then(|i| census.candidate.get(i))
                .copied()
                .unwrap_or(false)
        };
        let refined =
            PathMix::of(census, measured, bounces, on_candidate).unwrap_or_else(|| frame.clone());
        let pixels = census.candidate.len() as f64;
        Self {
            pixels,
            frame,
            refined,
            candidates: census.candidate_share() * pixels,
            paths_per_candidate: PRIOR_PATHS_PER_CANDIDATE,
            paths_by_side: PRIOR_PATHS_BY_SIDE.to_vec(),
            triangles: triangles.max(1) as f64,
        }
    }
}

/// The estimated cost of rendering a frame with `combo`, ns of one core's time.
pub(crate) fn cost<S>(space: &PilotSpace<S>, counts: &Counts, c: &Combo) -> f64 {
    let u = &UNIT_COSTS;
    let ray_ns = u.ray_base_ns + u.ray_per_log2_ns * counts.triangles.log2();
    let atm = space.atmospheres[c[0]];
    let count = space.sub_bands[c[5]];
    let band_of = |k: SubBandCount| {
        space
            .bands
            .iter()
            .find(|b| b.atmosphere == atm && b.sub_bands == k)
            .or_else(|| {
                space
                    .bands
                    .iter()
                    .find(|b| b.atmosphere == space.atmospheres[0] && b.sub_bands == k)
            })
    };
    let choice = band_of(count);
    let k = choice.map_or(1.0, |b| b.set.len() as f64);
    let (path_call_ns, sky_ns) = choice.map_or((880.0, 2e6), |b| (b.path_call_ns, b.sky_ns));
    let n_sky = space.sky_view_rays[c[2]];
    let sky_rays = f64::from(n_sky);
    // One path of the mix `mix`: its rays, its nodes and hemisphere rays evaluated in
    // every sub-band, and its path terms; `calm`: evaluated a second time with the
    // hemispheric sky in place of its sky-view rays, as refinement's stopping test does.
    let path_ns = |mix: &PathMix, hemi_rays: f64, table: bool, calm: bool| {
        let reflections = mix.reflections.get(c[1]).copied().unwrap_or(0.0);
        // A sunlit path's shadow rays (any-hit queries, priced as rays): its nodes with a
        // diffuse part, each casting the count chosen.
        let shadow_rays = match &space.sun {
            Some(sun) if sun.lit[c[SUN_MODEL]] => {
                mix.lit_nodes * f64::from(sun.shadow_rays[c[SHADOW_RAYS_MODEL]])
            }
            _ => 0.0,
        };
        let rays = 1.0 + reflections + mix.diffuse * hemi_rays + shadow_rays;
        let node_ns = k * mix.nodes * u.node_eval_ns;
        let evals = node_ns + k * mix.diffuse * hemi_rays * u.hemi_eval_ns;
        let terms = mix.hit
            * if table {
                k * u.table_lookup_ns
            } else {
                path_call_ns * (1.0 + (k - 1.0) * PATH_ALONG_SHARE)
            };
        let again = if calm { node_ns + terms } else { 0.0 };
        rays * ray_ns + evals + terms + again
    };
    let table = space.path_terms[c[4]] == PathTermsMode::Tabulated;
    let centre = path_ns(&counts.frame, sky_rays, table, false);
    // A refined pixel's paths share the centre's sky-view rays out by level
    // (`level_sky_view_rays`), weighted by its paths at each side (the trial's, else two
    // levels from the edge side), and each is also evaluated once more with the
    // hemispheric sky when it has sky-view rays.
    let level = |side: u32| f64::from(crate::refine::level_sky_view_rays(n_sky, side));
    let paths: f64 = counts.paths_by_side.iter().map(|&(_, p)| p).sum();
    let refined_hemi = if paths > 0.0 {
        counts
            .paths_by_side
            .iter()
            .map(|&(side, p)| p * level(side))
            .sum::<f64>()
            / paths
    } else {
        0.0
    };
    let refined = path_ns(&counts.refined, refined_hemi, table, n_sky > 0);
    let sampling = match space.supersampling[c[3]] {
        Supersample::Every(1) | Supersample::Adaptive(1) => counts.pixels * centre,
        Supersample::Every(n) => counts.pixels * f64::from(1 + n * n) * centre,
        Supersample::Adaptive(n) => {
            counts.pixels * centre + counts.candidates * f64::from(1 + n * n) * centre
        }
        Supersample::Refine(_) => {
            counts.pixels * centre + counts.candidates * counts.paths_per_candidate * refined
        }
    };
    let fixed = k * sky_ns
        + if table {
            k * (crate::PATH_TABLE_ALTITUDES * crate::PATH_TABLE_RANGES) as f64 * path_call_ns
        } else {
            0.0
        };
    sampling + fixed
}

/// What the rule found for a combination.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Verdict {
    /// The largest bound over the guaranteed points, K.
    pub(crate) worst_k: f64,
}

/// The error of model `k` at setting `combo[k]` at a point, K: a shadow-ray count is
/// none of a frame whose sun is off.
pub(crate) fn error_of(m: &Measured, combo: &Combo, k: usize) -> f64 {
    if k == SHADOW_RAYS_MODEL && m.sun_off == Some(combo[SUN_MODEL]) {
        return 0.0;
    }
    m.errors[k].get(combo[k]).copied().unwrap_or(0.0)
}

/// The per-point bound of `combo`: the sum of its models' errors.
pub(crate) fn bound(m: &Measured, combo: &Combo) -> f64 {
    (0..MODELS).map(|k| error_of(m, combo, k)).sum()
}

/// What a class's points are held to besides their bound: each class's residual
/// ([`super::residual`]) and whether each point's pixel is refined ([`super::predict`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pixels<'a> {
    /// Each class's residual, K.
    pub(crate) residual_k: &'a [f64],
    /// Each class's residual's deterministic part, K.
    pub(crate) bounces_k: &'a [f64],
    /// The sky-view rays' noise each class's refined pixels keep, K.
    pub(crate) refined_noise_k: &'a [f64],
    /// Refinement's target σ as a share of the tolerance.
    pub(crate) target_share: f64,
    /// Each point's pixel is a refinement candidate.
    pub(crate) candidate: &'a [bool],
}

/// Whether `combo` holds: in every guaranteed class and over the frame ([`self`]), and
/// every guaranteed class's pixels, with its residual (a refined pixel's with
/// refinement's noise and the sky-view rays' it keeps in place of the residual's), within
/// the tolerance at the 90th percentile ([`super::predict`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn holds(
    census: &Census,
    measured: &[Measured],
    by_class: &[Vec<usize>],
    guaranteed: &[bool],
    pixels: Pixels<'_>,
    combo: &Combo,
    tolerance_k: f64,
    det_k: f64,
    percentile: f64,
) -> Option<Verdict> {
    let mut scratch = Vec::new();
    let mut needs = Vec::new();
    for (c, points) in by_class.iter().enumerate() {
        if !guaranteed[c] || points.is_empty() {
            continue;
        }
        scratch.clear();
        needs.clear();
        for &i in points {
            let m = &measured[i];
            let b = bound(m, combo);
            scratch.push(b);
            needs.push(super::predict::need_k(
                b + pixels.residual_k[c],
                b + pixels.bounces_k[c],
                pixels.candidate[i],
                pixels.target_share * tolerance_k,
                pixels.refined_noise_k[c],
            ));
            // No model alone may change a point by more than the tolerance.
            if (0..MODELS).any(|k| error_of(m, combo, k) > tolerance_k) {
                return None;
            }
        }
        let rank = confident_rank(scratch.len(), 90.0);
        if order_statistic(&mut scratch, rank) > det_k
            || !super::predict::class_holds(&mut needs, tolerance_k)
        {
            return None;
        }
    }
    let mut weighted: Vec<(f64, f64)> = census
        .points
        .iter()
        .zip(measured)
        .filter(|(p, _)| guaranteed[p.class])
        .map(|(p, m)| (bound(m, combo), census.classes[p.class].weight()))
        .collect();
    let worst_k = weighted.iter().map(|v| v.0).fold(0.0, f64::max);
    let frame_k = weighted_percentile(&mut weighted, stricter(percentile));
    (frame_k <= det_k).then_some(Verdict { worst_k })
}

/// The percentile the frame's sample is held to: halfway from `percentile` to 100, for
/// the sample's own uncertainty (99 → 99.5).
pub(crate) fn stricter(percentile: f64) -> f64 {
    100.0 - (100.0 - percentile) / 2.0
}
