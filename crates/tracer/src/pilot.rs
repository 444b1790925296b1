//! The tolerance pilot: which models does this scene, seen from this view, need to meet a
//! tolerance in kelvin?
//!
//! A stratified sample of pixels is traced once with the most accurate geometry (the most
//! bounces and sky-view rays on offer), and each recorded path is evaluated again under
//! every cheaper setting of every model, the others at their most accurate: the atmosphere
//! models and sub-band counts as other [`BandSet`]s, the bounces by cutting the path, the
//! sky-view factor by dropping its rays, the tabulated path terms through a table. Only
//! supersampling needs more rays: each sample pixel's sub-pixel rays are traced at each
//! candidate density (with one bounce and no sky-view rays, which do not change where the
//! edges are). The per-pixel error of a combination is bounded by the sum of its models'
//! errors; the cheapest combination whose bound meets the tolerance at the percentile is
//! chosen. Costs come from counts the pilot makes (rays, path evaluations, path-term calls
//! per sub-band) times fixed unit costs measured once (BENCHMARKS.md), so the choice is the
//! same on every run of the same inputs.

use irsig_atmosphere::{ModelKind, SubBandCount};
use irsig_model::decision::{Decision, ErrorEstimate, ModelChoice, SwitchableModel};
use irsig_radiometry::{BandModel, InverseTable};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::camera::Camera;
use crate::env::Atmosphere;
use crate::error::{TraceError, TraceErrorKind};
use crate::path::{Diffuse, Escape, HemiRay, Mirror, Path, Primary};
use crate::path_table::{PathTable, PathTermsMode};
use crate::tracer::{BandSet, Ctx, Event, FrameConsts, Sample, TraceOptions, Tracer};

/// Unit costs of the cost model, nanoseconds (BENCHMARKS.md, 2-core Zen 3): a ray through
/// the BVH (100k-1M triangles), a node or hemisphere ray evaluated in one sub-band, a path
/// table lookup in one sub-band.
const RAY_NS: f64 = 300.0;
const NODE_EVAL_NS: f64 = 25.0;
const HEMI_EVAL_NS: f64 = 12.0;
const TABLE_LOOKUP_NS: f64 = 15.0;
/// Nodes of a path table (altitudes × ranges): what building one costs in path calls.
const TABLE_NODES: f64 = (crate::PATH_TABLE_ALTITUDES * crate::PATH_TABLE_RANGES) as f64;

/// How many rays a pixel gets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Supersample {
    /// `n × n` rays in every pixel (`1`: the centre ray only).
    Every(u32),
    /// `n × n` rays only where the centre differs from a neighbour's by more than the
    /// tolerance (adaptive supersampling, thesis §3.3.4).
    Adaptive(u32),
}

impl Supersample {
    /// The setting as the decision names it: `1`, `4`, `adaptive-4`.
    #[must_use]
    pub fn name(self) -> String {
        match self {
            Self::Every(n) => n.to_string(),
            Self::Adaptive(n) => format!("adaptive-{n}"),
        }
    }

    fn n(self) -> u32 {
        match self {
            Self::Every(n) | Self::Adaptive(n) => n,
        }
    }
}

impl std::fmt::Display for Supersample {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.name())
    }
}

impl std::str::FromStr for Supersample {
    type Err = String;

    /// `N` or `adaptive-N`, N from 1 to 64.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (adaptive, n) = match s.strip_prefix("adaptive-") {
            Some(n) => (true, n),
            None => (false, s),
        };
        let n: u32 = n
            .parse()
            .ok()
            .filter(|n| (1..=64).contains(n))
            .ok_or_else(|| {
                format!("expected N (N x N rays per pixel, 1 to 64) or adaptive-N, found `{s}`")
            })?;
        Ok(if adaptive {
            Self::Adaptive(n)
        } else {
            Self::Every(n)
        })
    }
}

/// A band set the pilot may choose: an atmosphere model over some sub-bands.
#[derive(Debug)]
pub struct BandChoice<S> {
    /// The atmosphere model.
    pub atmosphere: ModelKind,
    /// The sub-bands (1 for the band model).
    pub sub_bands: SubBandCount,
    /// The set, built for the tracer's scene ([`Tracer::band_set`]).
    pub set: BandSet<S>,
    /// What one exact path-terms call costs in one of its sub-bands, ns (BENCHMARKS.md:
    /// `table` 880, `layered` 830, `thesis` 92, `none` 5).
    pub path_call_ns: f64,
    /// What precomputing the sky for one of its sub-bands costs a rendering, ns.
    pub sky_ns: f64,
}

/// What the pilot may choose from. Each list is ordered from the most accurate setting
/// (the reference, first) to the cheapest; a model with one entry is fixed (pinned, or one
/// that cannot matter), and `reasons` says why.
#[derive(Debug)]
pub struct PilotSpace<S> {
    /// Every (atmosphere, sub-bands) pair the pilot needs: the reference pair, each
    /// sub-band count at the reference atmosphere, and each atmosphere in the band model
    /// (`1`), the reference atmosphere's band model included: every model but the
    /// sub-bands is measured in it (see [`Tracer::pilot`]). Where an atmosphere has no band
    /// model here, it is measured at the reference sub-bands.
    pub bands: Vec<BandChoice<S>>,
    /// Atmosphere models, reference first.
    pub atmospheres: Vec<ModelKind>,
    /// Sub-band counts, reference first.
    pub sub_bands: Vec<SubBandCount>,
    /// Specular bounces, reference (most) first.
    pub bounces: Vec<u32>,
    /// Sky-view rays per diffuse hit, reference first; 0 is the thesis's F = 1.
    pub sky_view_rays: Vec<u32>,
    /// Rays per pixel, reference first.
    pub supersampling: Vec<Supersample>,
    /// Path terms, reference (`Exact`) first.
    pub path_terms: Vec<PathTermsMode>,
    /// Models whose setting is fixed, and why (pinned by the user, or cannot matter here).
    pub reasons: Vec<(SwitchableModel, String)>,
    /// Models the user pinned.
    pub pinned: Vec<SwitchableModel>,
}

/// One sample pixel's errors (kelvin, against the reference setting, per model and
/// alternative in list order, the reference's own 0 included) and the counts the cost
/// model needs.
#[derive(Debug, Clone, Default)]
struct PixelSample {
    errors: [Vec<f64>; 6],
    /// The primary ray hit a facet.
    hit: bool,
    /// Reflection rays the path traced at each bounce limit, by `bounces` index.
    reflection_rays: Vec<u32>,
    /// Hemisphere rays at the first facet (0 when it has no diffuse part).
    diffuse: bool,
    /// Nodes in the reference path (facets evaluated per sub-band).
    nodes: u32,
    /// The pixel is at an edge (adaptive supersampling refines it).
    edge: bool,
}

fn model_index(m: SwitchableModel) -> usize {
    m as usize
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// Runs the pilot over about `pixels` stratified sample pixels of `camera`'s image and
    /// chooses, for each model of `space`, the cheapest setting whose combination meets
    /// `tolerance_k` at `percentile` of the sample.
    ///
    /// # Errors
    /// A space without its reference band set, or a tolerance or percentile out of range.
    pub fn pilot<S: Atmosphere>(
        &self,
        camera: &Camera,
        space: &PilotSpace<S>,
        tolerance_k: f64,
        percentile: f64,
        pixels: u32,
        seed: u64,
    ) -> Result<Piloted, TraceError> {
        let bad = |m: String| TraceError::new(TraceErrorKind::InvalidOptions(m));
        irsig_model::decision::check_tolerance(tolerance_k, "tolerance")
            .map_err(|e| bad(e.to_string()))?;
        irsig_model::decision::check_percentile(percentile, "percentile")
            .map_err(|e| bad(e.to_string()))?;
        let find = |atmosphere: ModelKind, sub_bands: SubBandCount| {
            space
                .bands
                .iter()
                .position(|b| b.atmosphere == atmosphere && b.sub_bands == sub_bands)
        };
        let (Some(&ref_atm), Some(&ref_sb)) = (space.atmospheres.first(), space.sub_bands.first())
        else {
            return Err(bad(
                "the pilot needs at least one atmosphere and one sub-band count".into(),
            ));
        };
        let reference = find(ref_atm, ref_sb).ok_or_else(|| {
            bad(format!(
                "no band set for atmosphere {ref_atm}, sub-bands {ref_sb}"
            ))
        })?;
        // Every model but the sub-bands is measured in the band model (see `pilot_pixel`).
        let band_model = find(ref_atm, SubBandCount::BAND).unwrap_or(reference);
        let atm_sets = space
            .atmospheres
            .iter()
            .map(|&a| {
                find(a, SubBandCount::BAND)
                    .or_else(|| find(a, ref_sb))
                    .ok_or_else(|| bad(format!("no band set for {a}")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let sb_sets = space
            .sub_bands
            .iter()
            .map(|&k| {
                find(ref_atm, k).ok_or_else(|| bad(format!("no band set for {ref_atm}, {k}")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        for list_empty in [
            space.bounces.is_empty(),
            space.sky_view_rays.is_empty(),
            space.supersampling.is_empty(),
            space.path_terms.is_empty(),
        ] {
            if list_empty {
                return Err(bad("every model needs at least one setting".into()));
            }
        }
        let fc = self.frame_consts_with(camera, false);
        let table = space
            .path_terms
            .contains(&PathTermsMode::Tabulated)
            .then(|| self.path_table(camera, &space.bands[band_model].set));
        let samples = sample_pixels(camera.pixels, pixels, seed);
        // Apparent temperatures through the tracer's one table (a Newton polish from it,
        // not a cold solve: some 25 per sample).
        let inverse = self.inverse_table();
        let geometry = TraceOptions {
            specular_bounces: space.bounces[0],
            sky_view_rays: space.sky_view_rays[0],
            supersampling: 1,
            adaptive_threshold_k: None,
            seed,
            truth: false,
        };
        let results: Vec<PixelSample> = samples
            .par_iter()
            .map(|&(col, row)| {
                self.pilot_pixel(
                    &fc,
                    space,
                    &geometry,
                    (reference, band_model),
                    (&atm_sets, &sb_sets),
                    table.as_ref(),
                    &inverse,
                    tolerance_k,
                    (col, row),
                )
            })
            .collect();
        Ok(choose(
            space,
            &results,
            tolerance_k,
            percentile,
            camera.pixels,
        ))
    }

    /// One sample pixel: its reference path evaluated under every alternative.
    ///
    /// Only the sub-bands are measured against the reference sub-bands (the full grid):
    /// every other model's error is measured in the band model, against the band model
    /// at the reference geometry. A model's error in kelvin is a difference of two
    /// radiances through the same band quadrature; changing the quadrature changes that
    /// difference by the quadrature's own relative error (a few per cent at most: the band
    /// model is up to 1.9 K off at 300 K, docs/accuracy.md "Band against spectral"), so a
    /// 0.3 K error is misjudged by about 0.01 K, while
    /// evaluating the geometric alternatives (a pixel's 4 × 4 sub-pixel rays, its eight
    /// neighbours, each bounce limit) in every sub-band of the full grid cost the pilot
    /// 30 times as much.
    #[allow(clippy::too_many_arguments)]
    fn pilot_pixel<S: Atmosphere>(
        &self,
        fc: &FrameConsts<'_>,
        space: &PilotSpace<S>,
        geometry: &TraceOptions,
        (reference, band_model): (usize, usize),
        (atm_sets, sb_sets): (&[usize], &[usize]),
        table: Option<&PathTable>,
        inverse: &InverseTable<'_, B>,
        tolerance_k: f64,
        (col, row): (u32, u32),
    ) -> PixelSample {
        let camera = fc.camera();
        let t = |l: f64| inverse.temperature(l);
        let mut ctx = Ctx::for_pixel(
            geometry,
            u64::from(row) * u64::from(camera.pixels[0]) + u64::from(col),
        );
        let mut path = Path::default();
        let mut scratch = Sample::miss(Event::Sky);
        self.follow(fc, camera.pixel_direction(col, row), &mut ctx, &mut path);
        let eval = |set: usize, table: Option<&PathTable>, p: &Path, s: &mut Sample| {
            self.radiance_with::<false, S>(&space.bands[set].set, table, fc, p, s)
        };
        // The sub-bands are compared on the path with its first facet's sky-view rays
        // folded into the hemispheric sky (F = 1): the sky is where the spectral structure
        // is (the facets a sky-view ray meets are at short range, through air of τ ≈ 1),
        // and 64 sky lookups per sub-band were most of the pilot's time.
        let mut hemispheric = Path::default();
        path.with_sky_rays(0, &mut hemispheric);
        let t_ref = t(eval(reference, None, &hemispheric, &mut scratch));
        let l_band = eval(band_model, None, &path, &mut scratch);
        let t_band = t(l_band);
        let mut out = PixelSample {
            hit: matches!(path.primary, Primary::Facet { .. }),
            nodes: path.nodes.len() as u32,
            diffuse: path.nodes.first().is_some_and(|n| n.diffuse.is_some()),
            ..PixelSample::default()
        };
        let mut err = |model: SwitchableModel, l: f64| {
            let against = if model == SwitchableModel::SubBands {
                t_ref
            } else {
                t_band
            };
            out.errors[model_index(model)].push((t(l) - against).abs());
        };
        for &set in sb_sets {
            err(
                SwitchableModel::SubBands,
                eval(set, None, &hemispheric, &mut scratch),
            );
        }
        for &set in atm_sets {
            err(
                SwitchableModel::Atmosphere,
                eval(set, None, &path, &mut scratch),
            );
        }
        let mut cut = Path::default();
        for &b in &space.bounces {
            path.truncated(b, &mut cut);
            err(
                SwitchableModel::Bounces,
                eval(band_model, None, &cut, &mut scratch),
            );
        }
        for &n in &space.sky_view_rays {
            path.with_sky_rays(n, &mut cut);
            err(
                SwitchableModel::SkyView,
                eval(band_model, None, &cut, &mut scratch),
            );
        }
        for &mode in &space.path_terms {
            let l = match mode {
                PathTermsMode::Exact => l_band,
                PathTermsMode::Tabulated => eval(band_model, table, &path, &mut scratch),
            };
            out.errors[model_index(SwitchableModel::PathTerms)].push((t(l) - t(l_band)).abs());
        }
        out.reflection_rays = space
            .bounces
            .iter()
            .map(|&b| path.reflection_rays(b))
            .collect();
        // Supersampling: the sub-pixel rays at each density, with one bounce and no
        // sky-view rays (edges are where they are whatever the radiometry).
        let cheap = TraceOptions {
            specular_bounces: geometry.specular_bounces.min(1),
            sky_view_rays: 0,
            ..*geometry
        };
        let mut ctx = Ctx::for_pixel(
            &cheap,
            u64::from(row) * u64::from(camera.pixels[0]) + u64::from(col),
        );
        // The mean over n × n sub-pixel rays, once per density (an adaptive setting refines
        // an edge pixel exactly as the full setting of its density does).
        let mut densities: Vec<(u32, f64)> = Vec::new();
        for s in &space.supersampling {
            let n = s.n();
            if densities.iter().any(|&(m, _)| m == n) {
                continue;
            }
            let mean = if n <= 1 {
                self.follow(fc, camera.pixel_direction(col, row), &mut ctx, &mut path);
                eval(band_model, None, &path, &mut scratch)
            } else {
                let mut sum = 0.0;
                ctx.for_each_subpixel((col, row), n, |ctx, x, y| {
                    self.follow(fc, camera.direction_at(x, y), ctx, &mut path);
                    sum += eval(band_model, None, &path, &mut scratch);
                });
                sum / f64::from(n * n)
            };
            densities.push((n, mean));
        }
        let centre_l = match densities.iter().find(|&&(n, _)| n <= 1) {
            Some(&(_, l)) => l,
            None => {
                self.follow(fc, camera.pixel_direction(col, row), &mut ctx, &mut path);
                eval(band_model, None, &path, &mut scratch)
            }
        };
        let mean_of = |n: u32| {
            densities
                .iter()
                .find(|&&(m, _)| m == n)
                .map_or(centre_l, |&(_, l)| l)
        };
        // An edge: a neighbour's centre ray differs by more than the tolerance.
        let [w, h] = camera.pixels;
        let t_centre = t(centre_l);
        out.edge = (-1i64..=1)
            .flat_map(|dr| (-1i64..=1).map(move |dc| (dr, dc)))
            .filter(|&(dr, dc)| (dr, dc) != (0, 0))
            .map(|(dr, dc)| (i64::from(col) + dc, i64::from(row) + dr))
            .filter(|&(c, r)| c >= 0 && r >= 0 && c < i64::from(w) && r < i64::from(h))
            .any(|(c, r)| {
                self.follow(
                    fc,
                    camera.pixel_direction(c as u32, r as u32),
                    &mut ctx,
                    &mut path,
                );
                (t(eval(band_model, None, &path, &mut scratch)) - t_centre).abs() > tolerance_k
            });
        let t_ss_ref = t(mean_of(space.supersampling[0].n()));
        for s in &space.supersampling {
            let l = match *s {
                Supersample::Adaptive(_) if !out.edge => centre_l,
                Supersample::Adaptive(n) | Supersample::Every(n) => mean_of(n),
            };
            out.errors[model_index(SwitchableModel::Supersampling)].push((t(l) - t_ss_ref).abs());
        }
        out
    }
}

/// About `count` pixels, one in each cell of a grid over the image, at a seeded random
/// place in its cell.
fn sample_pixels([w, h]: [u32; 2], count: u32, seed: u64) -> Vec<(u32, u32)> {
    let count = count.clamp(1, w.saturating_mul(h).max(1));
    let aspect = f64::from(w) / f64::from(h.max(1));
    let across = ((f64::from(count) * aspect).sqrt().round() as u32).clamp(1, w.max(1));
    let down = (count / across).clamp(1, h.max(1));
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x7069_6c6f_7400_0000);
    let mut out = Vec::with_capacity((across * down) as usize);
    for j in 0..down {
        for i in 0..across {
            let (c0, c1) = (
                i * w / across,
                ((i + 1) * w / across).max(i * w / across + 1),
            );
            let (r0, r1) = (j * h / down, ((j + 1) * h / down).max(j * h / down + 1));
            out.push((
                rng.random_range(c0..c1.min(w)),
                rng.random_range(r0..r1.min(h)),
            ));
        }
    }
    out
}

/// The confidence with which the pilot's estimate of a percentile bounds the image's own.
pub const CONFIDENCE: f64 = 0.95;

/// The value at `percentile` of `values` (nearest rank).
#[cfg(test)]
fn percentile_of(values: &mut [f64], percentile: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    let rank = ((percentile / 100.0) * values.len() as f64).ceil() as usize;
    values[rank.clamp(1, values.len()) - 1]
}

/// The 1-based rank of the order statistic of `n` samples that is at least the
/// population's `percentile` with probability [`CONFIDENCE`]: the smallest `k` with
/// P(X ≤ k − 1) ≥ CONFIDENCE, X ~ Binomial(n, percentile/100) being the count of samples
/// below the population's percentile (distribution-free; any continuous distribution).
/// `n` when even the largest sample is not enough, and for the 100th percentile.
fn confident_rank(n: usize, percentile: f64) -> usize {
    let q = percentile / 100.0;
    if n == 0 || q >= 1.0 {
        return n;
    }
    // P(X = j) in logs, from j = 0 up: ln C(n, j) + j ln q + (n − j) ln(1 − q).
    let (ln_q, ln_1q) = (q.ln(), (1.0 - q).ln());
    let mut ln_choose = 0.0;
    let mut cumulative = 0.0;
    for j in 0..n {
        if j > 0 {
            ln_choose += ((n - j + 1) as f64).ln() - (j as f64).ln();
        }
        cumulative += (ln_choose + j as f64 * ln_q + (n - j) as f64 * ln_1q).exp();
        if cumulative >= CONFIDENCE {
            return j + 1;
        }
    }
    n
}

/// An upper bound, with [`CONFIDENCE`], on the `percentile` of the population `values`
/// are a random sample of: their order statistic at [`confident_rank`].
fn percentile_bound(values: &mut [f64], percentile: f64) -> f64 {
    let rank = confident_rank(values.len(), percentile);
    order_statistic(values, rank)
}

/// The `rank`-th smallest of `values` (1-based, clamped to them; 0 for none), by
/// selection: the pilot reads one per combination of settings, hundreds per frame.
fn order_statistic(values: &mut [f64], rank: usize) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let k = rank.clamp(1, values.len()) - 1;
    *values.select_nth_unstable_by(k, f64::total_cmp).1
}

/// A combination: one index per model, into its list.
type Combo = [usize; 6];

/// The setting the pilot chose for each model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chosen {
    /// The atmosphere model.
    pub atmosphere: ModelKind,
    /// Specular bounces per path.
    pub bounces: u32,
    /// Sky-view rays per diffuse hit.
    pub sky_view_rays: u32,
    /// Rays per pixel.
    pub supersampling: Supersample,
    /// Path terms of facet hits.
    pub path_terms: PathTermsMode,
    /// Sub-bands.
    pub sub_bands: SubBandCount,
}

/// What the pilot decided: the settings, and the decision that records them with their
/// errors, costs and reasons (what is written beside the outputs).
#[derive(Debug, Clone)]
pub struct Piloted {
    /// The settings chosen.
    pub chosen: Chosen,
    /// Their record.
    pub decision: Decision,
}

fn choose<S>(
    space: &PilotSpace<S>,
    samples: &[PixelSample],
    tolerance_k: f64,
    percentile: f64,
    [w, h]: [u32; 2],
) -> Piloted {
    let lens = [
        space.atmospheres.len(),
        space.bounces.len(),
        space.sky_view_rays.len(),
        space.supersampling.len(),
        space.path_terms.len(),
        space.sub_bands.len(),
    ];
    let pixels = f64::from(w) * f64::from(h);
    let n = samples.len().max(1) as f64;
    let mean = |f: &dyn Fn(&PixelSample) -> f64| samples.iter().map(f).sum::<f64>() / n;
    let hit_fraction = mean(&|s| f64::from(u8::from(s.hit)));
    let diffuse_fraction = mean(&|s| f64::from(u8::from(s.diffuse)));
    let edge_fraction = mean(&|s| f64::from(u8::from(s.edge)));
    let nodes = mean(&|s| f64::from(s.nodes));
    let band_of = |atm: ModelKind, k: SubBandCount| {
        space
            .bands
            .iter()
            .find(|b| b.atmosphere == atm && b.sub_bands == k)
    };
    let k_of =
        |k: SubBandCount| band_of(space.atmospheres[0], k).map_or(1.0, |b| b.set.len() as f64);
    // The estimated cost of a rendering, ns.
    let cost = |c: &Combo| -> f64 {
        let atm = space.atmospheres[c[0]];
        let k = k_of(space.sub_bands[c[5]]);
        let sky_rays = f64::from(space.sky_view_rays[c[2]]);
        let reflections = mean(&|s| f64::from(s.reflection_rays[c[1]]));
        let rays_per_path = 1.0 + reflections + diffuse_fraction * sky_rays;
        let paths_per_pixel = match space.supersampling[c[3]] {
            Supersample::Every(1) | Supersample::Adaptive(1) => 1.0,
            Supersample::Every(n) => 1.0 + f64::from(n * n),
            // The centre rays, the 8 neighbours' comparison (free: they are the image), and
            // the refined pixels again from their centre.
            Supersample::Adaptive(n) => 1.0 + edge_fraction * (1.0 + f64::from(n * n)),
        };
        let choice = band_of(atm, space.sub_bands[c[5]]);
        let (path_call_ns, sky_ns) = choice.map_or((880.0, 2e6), |b| (b.path_call_ns, b.sky_ns));
        let evals = paths_per_pixel
            * k
            * (nodes * NODE_EVAL_NS + diffuse_fraction * sky_rays * HEMI_EVAL_NS);
        let path_terms = match space.path_terms[c[4]] {
            PathTermsMode::Exact => paths_per_pixel * hit_fraction * k * path_call_ns,
            PathTermsMode::Tabulated => paths_per_pixel * hit_fraction * k * TABLE_LOOKUP_NS,
        };
        let fixed = k * sky_ns
            + match space.path_terms[c[4]] {
                PathTermsMode::Exact => 0.0,
                PathTermsMode::Tabulated => k * TABLE_NODES * path_call_ns,
            };
        pixels * (paths_per_pixel * rays_per_path * RAY_NS + evals + path_terms) + fixed
    };
    // The per-pixel bound of a combination: the sum of its models' errors.
    let bound = |c: &Combo| -> Vec<f64> {
        samples
            .iter()
            .map(|s| {
                (0..6)
                    .map(|m| s.errors[m].get(c[m]).copied().unwrap_or(0.0))
                    .sum()
            })
            .collect()
    };
    let reference: Combo = [0; 6];
    let reference_cost = cost(&reference);
    let rank = confident_rank(samples.len(), percentile);
    let mut best: Option<(f64, Combo, f64, f64)> = None;
    let mut combo = [0usize; 6];
    loop {
        let mut b = bound(&combo);
        let worst = b.iter().copied().fold(0.0, f64::max);
        let p = order_statistic(&mut b, rank);
        if p <= tolerance_k {
            let c = cost(&combo);
            // At equal cost (a model that changes nothing here), the cheaper settings.
            let cheaper = |b: &Combo| combo.iter().sum::<usize>() > b.iter().sum::<usize>();
            if best.is_none_or(|(bc, b, ..)| c < bc * (1.0 - 1e-12) || (c <= bc && cheaper(&b))) {
                best = Some((c, combo, p, worst));
            }
        }
        // Next combination (odometer over the lists).
        let mut m = 0;
        loop {
            if m == 6 {
                break;
            }
            combo[m] += 1;
            if combo[m] < lens[m] {
                break;
            }
            combo[m] = 0;
            m += 1;
        }
        if m == 6 {
            break;
        }
    }
    // The all-reference combination has no error against itself, so one always meets it.
    let (chosen_cost, chosen, p, worst) = best.unwrap_or((reference_cost, reference, 0.0, 0.0));
    let settings = |m: usize, i: usize| -> String {
        match m {
            0 => space.atmospheres[i].name().to_owned(),
            1 => space.bounces[i].to_string(),
            2 => space.sky_view_rays[i].to_string(),
            3 => space.supersampling[i].name(),
            4 => space.path_terms[i].name().to_owned(),
            _ => space.sub_bands[i].to_string(),
        }
    };
    let choices = SwitchableModel::ALL
        .iter()
        .enumerate()
        .map(|(m, &model)| {
            let i = chosen[m];
            let mut errors: Vec<f64> = samples
                .iter()
                .map(|s| s.errors[m].get(i).copied().unwrap_or(0.0))
                .collect();
            let max_k = errors.iter().copied().fold(0.0, f64::max);
            let mut alone = reference;
            alone[m] = i;
            let reason = space
                .reasons
                .iter()
                .find(|(r, _)| *r == model)
                .map(|(_, why)| why.clone())
                .unwrap_or_else(|| {
                    // Every alternative gave every pilot pixel the reference's temperature:
                    // the model cannot matter in this view (as far as the pilot saw).
                    let inert = lens[m] > 1
                        && samples.iter().all(|s| s.errors[m].iter().all(|&e| e == 0.0));
                    if lens[m] == 1 {
                        "the only setting on offer".to_owned()
                    } else if inert {
                        match model {
                            SwitchableModel::SkyView => format!(
                                "the sky-view rays of the {} pilot pixels met no facet: F = 1 is exact here",
                                samples.len()
                            ),
                            SwitchableModel::Bounces => format!(
                                "every bounce count offered gave the {} pilot pixels the same temperatures",
                                samples.len()
                            ),
                            _ => format!(
                                "every setting gave the {} pilot pixels the same temperatures",
                                samples.len()
                            ),
                        }
                    } else if i == lens[m] - 1 {
                        "the cheapest setting meets the tolerance".to_owned()
                    } else {
                        "the cheapest combination that meets the tolerance".to_owned()
                    }
                });
            ModelChoice {
                model,
                setting: settings(m, i),
                reference: settings(m, 0),
                pinned: space.pinned.contains(&model),
                error: ErrorEstimate {
                    percentile_k: percentile_bound(&mut errors, percentile),
                    max_k,
                },
                relative_cost: cost(&alone) / reference_cost,
                reason,
            }
        })
        .collect();
    Piloted {
        chosen: Chosen {
            atmosphere: space.atmospheres[chosen[0]],
            bounces: space.bounces[chosen[1]],
            sky_view_rays: space.sky_view_rays[chosen[2]],
            supersampling: space.supersampling[chosen[3]],
            path_terms: space.path_terms[chosen[4]],
            sub_bands: space.sub_bands[chosen[5]],
        },
        decision: Decision {
            tolerance_k,
            percentile,
            choices,
            predicted: ErrorEstimate {
                percentile_k: p,
                max_k: worst,
            },
            relative_cost: chosen_cost / reference_cost,
            pilot_pixels: samples.len() as u32,
        },
    }
}

impl Path {
    /// This path with at most `bounces` specular bounces, into `out`: what a rendering with
    /// that limit records (the last facet reflects its untraced environment).
    pub(crate) fn truncated(&self, bounces: u32, out: &mut Path) {
        out.primary = self.primary;
        out.rays.clone_from(&self.rays);
        out.nodes.clear();
        let keep = (bounces as usize + 1).min(self.nodes.len());
        out.nodes.extend_from_slice(&self.nodes[..keep]);
        if let Some(last) = out.nodes.last_mut()
            && keep == bounces as usize + 1
            && last.mirror.is_some()
        {
            last.mirror = Some(Mirror::Untraced(last.environment));
        }
    }

    /// This path with only the first `n` of its first facet's sky-view rays (0: F = 1).
    pub(crate) fn with_sky_rays(&self, n: u32, out: &mut Path) {
        out.clone_from(self);
        if let Some(node) = out.nodes.first_mut()
            && let Some(Diffuse::Rays { start, count, .. }) = node.diffuse
        {
            let n = n.min(count);
            node.diffuse = Some(if n == 0 {
                Diffuse::Hemispheric
            } else {
                let rays = &self.rays[start as usize..(start + n) as usize];
                let sky = rays
                    .iter()
                    .filter(|r| matches!(r, HemiRay::Escaped(Escape::Sky { zenith_deg, .. }) if *zenith_deg <= 90.0))
                    .count() as u32;
                Diffuse::Rays {
                    start,
                    count: n,
                    sky,
                }
            });
        }
    }

    /// Reflection rays this path traced within `bounces` bounces.
    pub(crate) fn reflection_rays(&self, bounces: u32) -> u32 {
        let traced = self
            .nodes
            .iter()
            .take(bounces as usize)
            .filter(|n| matches!(n.mirror, Some(Mirror::Next | Mirror::Escaped(_))))
            .count();
        traced as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_pixels_cover_the_image_one_per_cell() {
        let s = sample_pixels([512, 384], 256, 1);
        assert!((200..=300).contains(&s.len()), "{}", s.len());
        assert!(s.iter().all(|&(c, r)| c < 512 && r < 384));
        // Every quarter of the image holds about a quarter of them.
        let left_top = s.iter().filter(|&&(c, r)| c < 256 && r < 192).count();
        assert!(
            (s.len() / 4).abs_diff(left_top) <= 8,
            "{left_top} of {}",
            s.len()
        );
        assert_eq!(sample_pixels([512, 384], 256, 1), s);
        assert_eq!(sample_pixels([3, 2], 1000, 1).len(), 6);
    }

    #[test]
    fn order_statistics_are_those_of_the_sorted_values() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let values: Vec<f64> = (0..1000).map(|_| rng.random::<f64>()).collect();
        let mut sorted = values.clone();
        sorted.sort_by(f64::total_cmp);
        for rank in [1, 5, 500, 995, 1000] {
            let v = order_statistic(&mut values.clone(), rank);
            assert_eq!(v.to_bits(), sorted[rank - 1].to_bits());
        }
        // Clamped to the values, and none gives 0.
        let bits = |rank| order_statistic(&mut values.clone(), rank).to_bits();
        assert_eq!(bits(0), sorted[0].to_bits());
        assert_eq!(bits(5000), sorted[999].to_bits());
        assert_eq!(order_statistic(&mut [], 3).to_bits(), 0.0_f64.to_bits());
    }

    #[test]
    fn confident_ranks_are_binomial_order_statistics() {
        // 299 samples: the largest bounds the 99th percentile with 95 % confidence
        // (1 − 0.99^299 = 0.95046), 298 do not (1 − 0.99^298 = 0.94996).
        assert_eq!(confident_rank(299, 99.0), 299);
        assert_eq!(confident_rank(250, 99.0), 250);
        // 1024 samples: exceedances E ~ Binomial(1024, 0.01), P(E ≥ 5) = 0.9755 ≥ 0.95
        // and P(E ≥ 6) = 0.9423 < 0.95 (summed by hand), so the 5th largest, rank 1020.
        assert_eq!(confident_rank(1024, 99.0), 1020);
        // The median of 100 samples: P(X ≤ 58) = 0.9557, P(X ≤ 57) = 0.9334
        // (Binomial(100, 0.5), summed by hand), so rank 59.
        assert_eq!(confident_rank(100, 50.0), 59);
        assert_eq!(confident_rank(10, 100.0), 10);
        assert_eq!(confident_rank(0, 99.0), 0);
    }

    #[test]
    fn percentiles_by_nearest_rank() {
        let mut v: Vec<f64> = (1..=100).map(f64::from).collect();
        assert!((percentile_of(&mut v, 99.0) - 99.0).abs() < 1e-12);
        assert!((percentile_of(&mut v, 100.0) - 100.0).abs() < 1e-12);
        assert!((percentile_of(&mut v, 0.5) - 1.0).abs() < 1e-12);
        assert!(percentile_of(&mut [], 99.0).abs() < 1e-12);
    }
}
