//! One sample point of the pilot measured: its path traced once with the most accurate
//! geometry on offer, then evaluated under every cheaper setting of every model (the
//! others at their most accurate), and each convergence sequence's steps, from which the
//! most accurate settings' own residual is estimated ([`super::residual`]).
//!
//! Only the sub-bands are measured against the reference sub-bands (the full grid): every
//! other model's error is measured in the band model, against the band model at the
//! reference geometry. A model's error in kelvin is a difference of two radiances through
//! the same band quadrature; changing the quadrature changes that difference by the
//! quadrature's own relative error (a few per cent at most), while evaluating every
//! geometric alternative in every sub-band of the full grid would cost the pilot some 30
//! times as much.

use irsig_model::decision::SwitchableModel;
use irsig_radiometry::{BandModel, InverseTable};

use crate::env::Atmosphere;
use crate::path::Path;
use crate::path_table::{PathTable, PathTermsMode};
use crate::pilot::choose::MODELS;
use crate::pilot::classes::SamplePoint;
use crate::pilot::{PilotSpace, Supersample};
use crate::tracer::{
    Ctx, Event, FrameConsts, PROBE_STREAM, SKY_VIEW_STREAM, Sample, TraceOptions, Tracer,
};

/// The side of the sub-pixel grid a pinned supersampling's error is measured against.
const REFERENCE_SIDE: u32 = 8;

/// One sample point's errors, kelvin, against the reference setting, per model (in
/// [`SwitchableModel::ALL`] order) and alternative (in the space's order, the reference's
/// own 0 included), and the counts the cost model needs.
#[derive(Debug, Clone, Default)]
pub(crate) struct Measured {
    pub(crate) errors: [Vec<f64>; MODELS],
    /// The apparent temperature at each bounce limit on offer, K, in the space's order
    /// (the most first): the bounces' convergence sequence, whose rate says what the most
    /// bounces leave ([`super::residual`]).
    pub(crate) by_bounces_k: Vec<f64>,
    /// The apparent temperature at each non-zero sky-view ray count on offer, in the
    /// space's order (each from rays of its own): the class's Monte Carlo error of the
    /// most rays is estimated from their differences ([`super`]).
    pub(crate) by_sky_view_k: Vec<f64>,
    /// The apparent temperature at each shadow-ray count above 1 on offer, in the space's
    /// order (empty without a sun): the most rays' own sampling error, as the sky-view
    /// rays'.
    pub(crate) by_shadow_rays_k: Vec<f64>,
    /// The index of the sun's `off` setting, where it is on offer: a shadow-ray count then
    /// costs that combination no error ([`crate::pilot::choose::error_of`]).
    pub(crate) sun_off: Option<usize>,
    /// Nodes of the reference path with a diffuse part (each casts shadow rays by day).
    pub(crate) lit_nodes: u32,
    /// The primary ray hit a facet.
    pub(crate) hit: bool,
    /// The first facet has a diffuse part (it casts sky-view rays).
    pub(crate) diffuse: bool,
    /// Nodes in the reference path (facets evaluated per sub-band).
    pub(crate) nodes: u32,
    /// Reflection rays the path traced at each bounce limit, by `bounces` index.
    pub(crate) reflection_rays: Vec<u32>,
}

/// The band sets a measurement reads: the reference set, the band model's, each
/// atmosphere's and each sub-band count's (indices into the space's `bands`).
pub(crate) struct Sets<'a> {
    pub(crate) reference: usize,
    pub(crate) band_model: usize,
    pub(crate) atmospheres: &'a [usize],
    pub(crate) sub_bands: &'a [usize],
    pub(crate) table: Option<&'a PathTable>,
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// Measures `point` ([`Measured`]); `candidate` says whether its pixel is an edge or
    /// thin candidate (what an adaptive supersampling refines).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn measure<S: Atmosphere>(
        &self,
        fc: &FrameConsts<'_>,
        space: &PilotSpace<S>,
        sets: &Sets<'_>,
        inverse: &InverseTable<'_, B>,
        seed: u64,
        point: &SamplePoint,
        candidate: bool,
    ) -> Measured {
        let camera = fc.camera();
        let t = |l: f64| inverse.temperature(l);
        let reference = TraceOptions {
            specular_bounces: space.bounces[0],
            sky_view_rays: space.sky_view_rays[0],
            supersampling: 1,
            adaptive_threshold_k: None,
            seed,
            truth: false,
        };
        fn stream(ctx: Ctx<'_>, probe: bool, s: u64) -> Ctx<'_> {
            if probe {
                ctx.stream(PROBE_STREAM ^ s ^ 1)
            } else if s == 0 {
                ctx
            } else {
                ctx.stream(s)
            }
        }
        let dir = camera.direction_at(point.x, point.y);
        let mut path = Path::default();
        let mut scratch = Sample::miss(Event::Sky);
        // By day, every path is traced with the most shadow rays on offer.
        let shadow_rays = space.sun.as_ref().map(|s| s.shadow_rays[0]);
        let mut ctx = stream(Ctx::for_pixel(&reference, point.pixel), point.probe, 0);
        ctx.shadow_rays = shadow_rays;
        self.follow(fc, dir, &mut ctx, &mut path);
        let eval = |set: usize, table: Option<&PathTable>, p: &Path, s: &mut Sample| {
            self.radiance_with::<false, S>(&space.bands[set].set, table, fc, p, s)
        };
        // The sub-bands are compared on the path with its first facet's sky-view rays
        // folded into the hemispheric sky (F = 1): the sky is where the spectral structure
        // is (the facets a sky-view ray meets are at short range, through air of τ ≈ 1),
        // and 64 sky lookups per sub-band were most of the pilot's time.
        let mut hemispheric = Path::default();
        path.with_sky_rays(0, &mut hemispheric);
        let t_ref = t(eval(sets.reference, None, &hemispheric, &mut scratch));
        let l_band = eval(sets.band_model, None, &path, &mut scratch);
        let t_band = t(l_band);
        let mut out = Measured {
            hit: !path.nodes.is_empty(),
            nodes: path.nodes.len() as u32,
            lit_nodes: path.nodes.iter().filter(|n| n.diffuse.is_some()).count() as u32,
            diffuse: path.has_sky_view_rays()
                || path.nodes.first().is_some_and(|n| n.diffuse.is_some()),
            reflection_rays: space
                .bounces
                .iter()
                .map(|&b| path.reflection_rays(b))
                .collect(),
            ..Measured::default()
        };
        let index = |m: SwitchableModel| m as usize;
        for &set in sets.sub_bands {
            let l = eval(set, None, &hemispheric, &mut scratch);
            out.errors[index(SwitchableModel::SubBands)].push((t(l) - t_ref).abs());
        }
        for &set in sets.atmospheres {
            let l = eval(set, None, &path, &mut scratch);
            out.errors[index(SwitchableModel::Atmosphere)].push((t(l) - t_band).abs());
        }
        let mut cut = Path::default();
        let mut by_bounces = Vec::with_capacity(space.bounces.len());
        for &b in &space.bounces {
            path.truncated(b, &mut cut);
            let tb = t(eval(sets.band_model, None, &cut, &mut scratch));
            by_bounces.push(tb);
            out.errors[index(SwitchableModel::Bounces)].push((tb - t_band).abs());
        }
        // Sky-view rays: each count traced afresh (the first n of N stratified rays are
        // not a stratified set of n), from its own stream.
        let mut by_sky = Vec::with_capacity(space.sky_view_rays.len());
        for &n in &space.sky_view_rays {
            let tn = if n == reference.sky_view_rays {
                t_band
            } else if n == 0 {
                t(eval(sets.band_model, None, &hemispheric, &mut scratch))
            } else {
                let options = TraceOptions {
                    sky_view_rays: n,
                    ..reference
                };
                let mut ctx = stream(
                    Ctx::for_pixel(&options, point.pixel),
                    point.probe,
                    SKY_VIEW_STREAM + u64::from(n),
                );
                ctx.shadow_rays = shadow_rays;
                self.follow(fc, dir, &mut ctx, &mut cut);
                t(eval(sets.band_model, None, &cut, &mut scratch))
            };
            by_sky.push((n, tn));
            out.errors[index(SwitchableModel::SkyView)].push((tn - t_band).abs());
        }
        for &mode in &space.path_terms {
            let l = match mode {
                PathTermsMode::Exact => l_band,
                PathTermsMode::Tabulated => eval(sets.band_model, sets.table, &path, &mut scratch),
            };
            out.errors[index(SwitchableModel::PathTerms)].push((t(l) - t_band).abs());
        }
        out.by_bounces_k = by_bounces;
        out.by_sky_view_k = by_sky
            .iter()
            .filter(|(n, _)| *n > 0)
            .map(|&(_, t)| t)
            .collect();
        self.measure_sun(fc, space, sets, inverse, &reference, point, &path, &mut out);
        self.measure_supersampling(fc, space, inverse, seed, point, candidate, &mut out);
        out
    }

    /// The sun's two models at `point` (none without a sun: one setting each, no error):
    /// its effect, the band model's path evaluated without the beams; and each shadow-ray
    /// count's error, the path's shadow rays cast again at that count from the same
    /// stream (the rest of the path, its sky-view rays among them, kept: shadow rays draw
    /// from a stream of their own, so a rendering with that count records the same path
    /// with only the sunlight changed).
    #[allow(clippy::too_many_arguments)]
    fn measure_sun<S: Atmosphere>(
        &self,
        fc: &FrameConsts<'_>,
        space: &PilotSpace<S>,
        sets: &Sets<'_>,
        inverse: &InverseTable<'_, B>,
        reference: &TraceOptions,
        point: &SamplePoint,
        path: &Path,
        out: &mut Measured,
    ) {
        let [.., sun_errors, shadow_errors] = &mut out.errors;
        let Some(sun) = &space.sun else {
            sun_errors.push(0.0);
            shadow_errors.push(0.0);
            return;
        };
        let t = |l: f64| inverse.temperature(l);
        let mut scratch = Sample::miss(Event::Sky);
        let band = &space.bands[sets.band_model].set;
        let t_band = t(self.radiance_with::<false, S>(band, None, fc, path, &mut scratch));
        out.sun_off = sun.lit.iter().position(|&l| !l);
        for &lit in &sun.lit {
            sun_errors.push(if lit {
                0.0
            } else {
                let l = self.radiance_with::<false, S>(&sun.dark, None, fc, path, &mut scratch);
                (t(l) - t_band).abs()
            });
        }
        // Only a facet with a diffuse part casts shadow rays into the radiance.
        let casts = path.nodes.iter().any(|n| n.diffuse.is_some());
        let bare = TraceOptions {
            sky_view_rays: 0,
            ..*reference
        };
        let mut again = Path::default();
        let mut varied = Path::default();
        for (k, &n) in sun.shadow_rays.iter().enumerate() {
            let tn = if k == 0 || !casts || self.sun.is_none() {
                t_band
            } else {
                let mut ctx = Ctx::for_pixel(&bare, point.pixel);
                if point.probe {
                    ctx = ctx.stream(crate::tracer::PROBE_STREAM ^ 1);
                }
                ctx.shadow_rays = Some(n);
                let dir = fc.camera().direction_at(point.x, point.y);
                self.follow(fc, dir, &mut ctx, &mut again);
                varied.clone_from(path);
                for (node, other) in varied.nodes.iter_mut().zip(&again.nodes) {
                    node.sun_diffuse_per_sr = other.sun_diffuse_per_sr;
                    node.sun_cos_visible = other.sun_cos_visible;
                    node.sun_visible = other.sun_visible;
                }
                t(self.radiance_with::<false, S>(band, None, fc, &varied, &mut scratch))
            };
            shadow_errors.push((tn - t_band).abs());
            if n > 1 {
                out.by_shadow_rays_k.push(tn);
            }
        }
    }

    /// The error of each supersampling on offer at `point`'s pixel: the mean of its
    /// sub-pixel rays against an 8 × 8 grid's (with one bounce and no sky-view rays, which
    /// do not move an edge). Refinement's error on its candidates is not measured here: it
    /// is held to its target pixel by pixel, and its cost is tried on candidates
    /// ([`super`]). A pixel it does not take keeps its centre ray, which costs nothing
    /// where its facet is one material at one temperature; a textured hit varies within
    /// the pixel (a texture read at the point), so there the centre's distance from the
    /// grid's mean is refinement's error, as it is the adaptive setting's.
    #[allow(clippy::too_many_arguments)]
    fn measure_supersampling<S: Atmosphere>(
        &self,
        fc: &FrameConsts<'_>,
        space: &PilotSpace<S>,
        inverse: &InverseTable<'_, B>,
        seed: u64,
        point: &SamplePoint,
        candidate: bool,
        out: &mut Measured,
    ) {
        let errors = &mut out.errors[SwitchableModel::Supersampling as usize];
        let camera = fc.camera();
        let (col, row) = (point.x.floor() as u32, point.y.floor() as u32);
        let cheap = TraceOptions {
            specular_bounces: space.bounces[0].min(1),
            sky_view_rays: 0,
            supersampling: 1,
            adaptive_threshold_k: None,
            seed,
            truth: false,
        };
        let mut path = Path::default();
        let mut scratch = Sample::miss(Event::Sky);
        let mut mean = |n: u32, path: &mut Path| {
            let mut ctx = Ctx::for_pixel(&cheap, point.pixel);
            if n <= 1 {
                self.follow(fc, camera.pixel_direction(col, row), &mut ctx, path);
                return self.radiance::<false>(fc, path, &mut scratch);
            }
            let mut sum = 0.0;
            ctx.for_each_subpixel((col, row), n, |ctx, x, y| {
                self.follow(fc, camera.direction_at(x, y), ctx, path);
                sum += self.radiance::<false>(fc, path, &mut scratch);
            });
            sum / f64::from(n * n)
        };
        let l_centre = mean(1, &mut path);
        let textured = path
            .nodes
            .first()
            .is_some_and(|n| n.surface.texel.is_some());
        let refine_charges = textured && !candidate;
        if !refine_charges
            && space
                .supersampling
                .iter()
                .all(|s| matches!(s, Supersample::Refine(_)))
        {
            errors.extend(space.supersampling.iter().map(|_| 0.0));
            return;
        }
        let t_ref = inverse.temperature(mean(REFERENCE_SIDE, &mut path));
        let t_centre = inverse.temperature(l_centre);
        for s in &space.supersampling {
            let e = match *s {
                Supersample::Refine(_) if refine_charges => (t_centre - t_ref).abs(),
                Supersample::Refine(_) => 0.0,
                Supersample::Adaptive(_) if !candidate => (t_centre - t_ref).abs(),
                Supersample::Adaptive(n) | Supersample::Every(n) => {
                    (inverse.temperature(mean(n, &mut path)) - t_ref).abs()
                }
            };
            errors.push(e);
        }
    }
}
