//! Refinement of each pixel to a standard-error target: the sampling model of a tolerance.
//!
//! Every pixel gets its centre ray. A pixel becomes a candidate when its centre's apparent
//! temperature differs from one of its 8 neighbours' by more than [`Refinement::edge_k`] (an
//! edge passes near it), or when a facet that projects thinner than a pixel lies within a
//! pixel of it (a wire, a pole, a far spire: [`Tracer::thin_pixels`], found from the
//! geometry, so that no thin feature is missed because no centre ray happened to hit it),
//! or when the horizon crosses it (an edge along the image's border has no neighbour on
//! its far side to show it).
//! A candidate is traced in levels: at side `n`, [`ROUNDS`] independent stratified rounds
//! of `n × n` jittered rays each; the round means give the level's mean and its standard
//! error, `σ = std(round means)/√ROUNDS`, an estimate from the pixel's own samples as a Monte
//! Carlo renderer reports it. A level whose σ (in kelvin of apparent temperature, through
//! the band's slope at the mean) is above the target is replaced by the next, at twice the
//! side, up to [`Refinement::max_side`]. The test reads the rounds' means with the
//! hemispheric sky in place of the sky-view rays: edges are found and refined by geometry,
//! while the sky-view rays' noise is the sky-view model's error, which the pilot bounds. A
//! level whose rounds all agree, or whose rays are too few for a sliver worth the target to
//! be hardly missed, may have missed a sliver of the edge that made the pixel a candidate:
//! its border is then walked, densely enough that a corner between two border rays costs
//! less than the target, and a border ray outside the range the level's rays saw sends the
//! pixel on to the next level; a pixel that ends there above the target is
//! *capped*, and the frame says so ([`PixelSampling::capped`]). Thin candidates start at
//! [`Refinement::thin_side`], so that a feature a quarter of a pixel wide cannot slip
//! between the rays of a first level.
//!
//! Each pixel draws from its own stream (the seed and its index), so a tile's pixels are
//! the whole frame's, bit for bit, at any thread count.

use irsig_radiometry::{BandModel, InverseTable};

use crate::camera::Camera;
use crate::charge::{ChargeSink, Charges, Tally};
use crate::env::Atmosphere;
use crate::path::Path;
use rayon::prelude::*;

use crate::tile::Tile;
use crate::tracer::{
    Ctx, Event, FrameConsts, INVERSE_TABLE_K, REFINEMENT_STREAM, Sample, SunPixel, TexturePixel,
    TraceOptions, Tracer, TruthPixel,
};
use glam::DVec3;

/// The independent stratified rounds of a level: their means give its standard error with
/// 7 degrees of freedom (3σ holds a mean with 98 % confidence; 4 rounds' 3 left 6 % out).
pub const ROUNDS: usize = 8;

/// The largest side a level may have: 8 rounds of 128 × 128 rays. An edge's stratified
/// estimate converges as the −3/4 power of its rays, so a 200 K edge (a 300 K object
/// against a clear sky) needs this side for a standard error of 0.05 K.
pub const MAX_SIDE: u32 = 128;

/// How pixels are refined to a standard error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Refinement {
    /// The standard error of a refined pixel's apparent temperature to reach, K.
    pub target_k: f64,
    /// A pixel whose centre differs from a neighbour's by more than this is a candidate, K.
    pub edge_k: f64,
    /// The largest side of a level (`max_side²` rays a round, [`ROUNDS`] rounds).
    pub max_side: u32,
    /// The side a thin candidate starts at.
    pub thin_side: u32,
}

impl Refinement {
    /// Checks the numbers: positive finite kelvins, sides from 1 to [`MAX_SIDE`] with the thin
    /// side at most the largest.
    ///
    /// # Errors
    /// The first out of range, in words.
    pub fn validate(&self) -> Result<(), String> {
        for (what, v) in [("target_k", self.target_k), ("edge_k", self.edge_k)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!(
                    "refinement {what} {v} is out of range: expected a finite number of \
                     kelvin above 0"
                ));
            }
        }
        if !(1..=MAX_SIDE).contains(&self.max_side)
            || !(1..=self.max_side).contains(&self.thin_side)
        {
            return Err(format!(
                "refinement sides {} (thin) and {} (largest) are out of range: expected 1 to \
                 {MAX_SIDE}, the thin one at most the largest",
                self.thin_side, self.max_side
            ));
        }
        Ok(())
    }

    /// The rays a capped pixel costs: [`ROUNDS`] rounds at every level from `start` up.
    #[must_use]
    pub fn rays_to_cap(&self, start: u32) -> u64 {
        let mut side = start.max(1);
        let mut rays = 0;
        loop {
            rays += ROUNDS as u64 * u64::from(side) * u64::from(side);
            if side >= self.max_side {
                return rays;
            }
            side = (side * 2).min(self.max_side);
        }
    }
}

/// What refinement did to one pixel, and what the error budget reads of its rays.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PixelSampling {
    /// The standard error of the pixel's apparent temperature, K: the last level's, from
    /// its rounds (the sky-view rays' noise included); 0 for a pixel that kept its centre
    /// ray.
    pub sigma_k: f32,
    /// The geometric part of [`PixelSampling::sigma_k`], K: the last level's rounds read
    /// with the hemispheric sky in place of the sky-view rays, what refinement's stopping
    /// test holds to its target (the rest is the sky-view rays' noise, which a target does
    /// not scale); 0 for a pixel that kept its centre ray.
    pub geometric_sigma_k: f32,
    /// Rays traced for the pixel, its centre ray included.
    pub rays: u32,
    /// Refinement ended at the largest side with σ above the target.
    pub capped: bool,
    /// The levels traced: bit k for the level of side `min(2^k, max_side)` (a level's side
    /// is a power of two or the refinement's largest, [`PixelSampling::level_sides`]); 0
    /// for a pixel that kept its centre ray.
    pub levels: u32,
    /// The mean over the pixel's value's rays of ∂L/∂T (`Sample::temperature_sensitivity`).
    pub temperature_sensitivity: f32,
    /// The mean of ∂L/∂ε.
    pub emissivity_sensitivity: f32,
    /// The mean path radiance, W m⁻² sr⁻¹ (0 where it does not apply).
    pub path_radiance_w_m2_sr: f32,
}

impl PixelSampling {
    /// The bit of [`PixelSampling::levels`] for a level of side `side`.
    fn level_bit(side: u32) -> u32 {
        1 << side
            .checked_next_power_of_two()
            .map_or(31, u32::trailing_zeros)
    }

    /// The sides of the levels traced, smallest first, under a refinement whose largest
    /// side is `max_side`.
    pub fn level_sides(&self, max_side: u32) -> impl Iterator<Item = u32> + '_ {
        (0..32)
            .filter(|k| self.levels & (1 << k) != 0)
            .map(move |k| (1_u32 << k).min(max_side))
    }

    /// A pixel that kept its centre ray, whose terms are `t`.
    pub(crate) fn from_truth(t: &TruthPixel) -> Self {
        let path = t.path_radiance_w_m2_sr;
        Self {
            sigma_k: 0.0,
            geometric_sigma_k: 0.0,
            rays: 1,
            capped: false,
            levels: 0,
            temperature_sensitivity: t.temperature_sensitivity,
            emissivity_sensitivity: t.emissivity_sensitivity,
            path_radiance_w_m2_sr: if path.is_finite() { path } else { 0.0 },
        }
    }
}

/// The centre pass of a refined tile: each centre's radiance and terms, and its radiance
/// with the hemispheric sky in place of its sky-view rays (the candidates are found on it:
/// the sky-view rays' noise is the sky-view model's error, which the pilot bounds, not an
/// edge).
pub(crate) struct Centres {
    pub(crate) radiance_w_m2_sr: Vec<f64>,
    pub(crate) truth: Vec<TruthPixel>,
    /// The sun's truth of each centre; empty without a sun.
    pub(crate) sun: Vec<SunPixel>,
    /// The texture's truth of each centre; empty for an untextured scene.
    pub(crate) texture: Vec<TexturePixel>,
    pub(crate) calm_w_m2_sr: Vec<f64>,
    /// Each centre ray's charges ([`crate::charge`]); empty unless the tracer keeps them.
    pub(crate) charges: Charges,
}

/// Sums over a round's rays.
#[derive(Default)]
struct Sums {
    radiance: f64,
    temperature_sensitivity: f64,
    emissivity_sensitivity: f64,
    path_radiance: f64,
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// The pixels of `camera`'s image that lie within a pixel of a facet that projects
    /// thinner than a pixel (its smallest height on the image under one pixel), or that
    /// the horizon crosses (the terrain background below it, the sky above), row-major:
    /// where a feature can hide between centre rays. A horizon along the image's top or
    /// bottom row, or one that every neighbour's centre sees on the same side, is an edge
    /// no centre's contrast shows. Found by projecting every facet and the corners of every
    /// pixel, not by tracing: whether the facet or the horizon is hidden behind another
    /// facet does not matter (a candidate too many costs rays, one too few an error).
    #[must_use]
    pub fn thin_pixels(&self, camera: &Camera) -> Vec<bool> {
        let [w, h] = camera.pixels;
        self.thin_pixels_in(camera, Tile::whole(w, h))
    }

    /// [`Self::thin_pixels`] over the pixels of `tile` only (row-major, row 0 the tile's
    /// top row): each pixel's flag is the whole image's, and the mask is the tile's size.
    pub(crate) fn thin_pixels_in(&self, camera: &Camera, tile: Tile) -> Vec<bool> {
        let [w, h] = camera.pixels;
        let (wf, hf) = (f64::from(w), f64::from(h));
        let tw = tile.width as usize;
        let mut mask = vec![false; tile.pixels()];
        // The tile's first and last column and row, in the image.
        let (tx0, ty0) = (f64::from(tile.x), f64::from(tile.y));
        let tx1 = f64::from(tile.x + tile.width) - 1.0;
        let ty1 = f64::from(tile.y + tile.height) - 1.0;
        let project = |p: DVec3| -> Option<[f64; 2]> {
            let d = p - camera.position_m;
            let z = d.dot(camera.forward);
            if z <= 0.0 {
                return None;
            }
            let u = d.dot(camera.right) / z;
            let v = d.dot(camera.up) / z;
            Some([
                (u / camera.tan_half_fov[0] + 1.0) * wf / 2.0,
                (1.0 - v / camera.tan_half_fov[1]) * hf / 2.0,
            ])
        };
        // The horizon: a pixel whose corners look on both sides of the Earth's limb.
        let cos_critical = self.cos_critical_nadir(camera);
        let below =
            |x: u32, y: u32| -camera.direction_at(f64::from(x), f64::from(y))[2] > cos_critical;
        for y in tile.y..tile.y + tile.height {
            for x in tile.x..tile.x + tile.width {
                let corners = [
                    below(x, y),
                    below(x + 1, y),
                    below(x, y + 1),
                    below(x + 1, y + 1),
                ];
                if corners.contains(&true) && corners.contains(&false) {
                    mask[(y - tile.y) as usize * tw + (x - tile.x) as usize] = true;
                }
            }
        }
        self.geometry.for_each_triangle(|tri| {
            let (Some(a), Some(b), Some(c)) = (project(tri[0]), project(tri[1]), project(tri[2]))
            else {
                return;
            };
            let edge =
                |p: [f64; 2], q: [f64; 2]| ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt();
            let longest = edge(a, b).max(edge(b, c)).max(edge(c, a));
            let twice_area = ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs();
            // The smallest height of the projected triangle, pixels.
            if longest.is_nan() || longest <= 0.0 || twice_area / longest >= 1.0 {
                return;
            }
            let lo = |k: usize| (a[k].min(b[k]).min(c[k]) - 1.0).floor().max(0.0);
            let hi = |k: usize, size: f64| (a[k].max(b[k]).max(c[k]) + 1.0).ceil().min(size - 1.0);
            let (x0, x1) = (lo(0).max(tx0), hi(0, wf).min(tx1));
            let (y0, y1) = (lo(1).max(ty0), hi(1, hf).min(ty1));
            if x0 > x1 || y0 > y1 {
                return;
            }
            for y in y0 as u32..=y1 as u32 {
                for x in x0 as u32..=x1 as u32 {
                    let centre = [f64::from(x) + 0.5, f64::from(y) + 0.5];
                    if distance_to_triangle(centre, [a, b, c]) <= 1.0 {
                        mask[(y - tile.y) as usize * tw + (x - tile.x) as usize] = true;
                    }
                }
            }
        });
        mask
    }

    /// The centre pass over `tile` ([`Centres`]), rows in parallel.
    pub(crate) fn refinement_centres(
        &self,
        fc: &FrameConsts<'_>,
        options: &TraceOptions,
        tile: Tile,
    ) -> Centres {
        let camera = fc.camera();
        let n = tile.pixels();
        let row_len = tile.width.max(1) as usize;
        let mut out = Centres {
            radiance_w_m2_sr: vec![0.0; n],
            truth: vec![TruthPixel::from(&Sample::miss(Event::Sky)); n],
            sun: Vec::new(),
            texture: Vec::new(),
            calm_w_m2_sr: vec![0.0; n],
            charges: Charges::default(),
        };
        let charging = options.truth && self.keeps_charges();
        let lit = self.sun.is_some();
        if lit {
            out.sun = vec![SunPixel::from(&Sample::miss(Event::Sky)); n];
        }
        let textured = self.is_textured();
        if textured {
            out.texture = vec![TexturePixel::from(&Sample::miss(Event::Sky)); n];
        }
        // Without a sun, each row's sun slice is empty and nothing is written to it.
        let rows = n.div_ceil(row_len);
        let mut charge_rows: Vec<Charges> = (0..rows).map(|_| Charges::default()).collect();
        let sun_rows: Vec<&mut [SunPixel]> = if lit {
            out.sun.chunks_mut(row_len).collect()
        } else {
            (0..rows).map(|_| <&mut [SunPixel]>::default()).collect()
        };
        let texture_rows: Vec<&mut [TexturePixel]> = if textured {
            out.texture.chunks_mut(row_len).collect()
        } else {
            (0..rows)
                .map(|_| <&mut [TexturePixel]>::default())
                .collect()
        };
        out.radiance_w_m2_sr
            .par_chunks_mut(row_len)
            .zip(out.truth.par_chunks_mut(row_len))
            .zip(out.calm_w_m2_sr.par_chunks_mut(row_len))
            .zip(sun_rows)
            .zip(texture_rows)
            .zip(charge_rows.par_iter_mut())
            .enumerate()
            .for_each(|(r, (((((rad, tru), calm), sun), tex), charges))| {
                let mut path = Path::default();
                let mut hemispheric = Path::default();
                let mut centre = Sample::miss(Event::Sky);
                let mut tally = Tally::default();
                let row = tile.y + r as u32;
                for (c, ((l_out, t_out), calm_out)) in
                    rad.iter_mut().zip(tru.iter_mut()).zip(calm).enumerate()
                {
                    let col = tile.x + c as u32;
                    let index = u64::from(row) * u64::from(camera.pixels[0]) + u64::from(col);
                    let mut ctx = Ctx::for_pixel(options, index);
                    ctx.sun_truth = true;
                    self.follow(fc, camera.pixel_direction(col, row), &mut ctx, &mut path);
                    *l_out = if charging {
                        tally.restart();
                        tally.set_rays(1);
                        let l = self.radiance_charged::<true, Tally>(
                            fc,
                            &path,
                            &mut centre,
                            &mut tally,
                        );
                        tally.finish_into(charges);
                        l
                    } else {
                        self.radiance::<true>(fc, &path, &mut centre)
                    };
                    *t_out = TruthPixel::from(&centre);
                    if let Some(s_out) = sun.get_mut(c) {
                        *s_out = SunPixel::from(&centre);
                    }
                    if let Some(x_out) = tex.get_mut(c) {
                        *x_out = TexturePixel::from(&centre);
                    }
                    *calm_out = if path.has_sky_view_rays() {
                        path.with_sky_rays(0, &mut hemispheric);
                        self.radiance::<false>(fc, &hemispheric, &mut centre)
                    } else {
                        *l_out
                    };
                }
            });
        if charging {
            out.charges = Charges::concat(charge_rows);
        }
        out
    }

    /// The largest contrast of apparent temperature the scene can show, K: from the coldest
    /// of its facets, its terrain and the clear sky (the floor of [`INVERSE_TABLE_K`]) to
    /// the hottest of its facets and terrain. What a thin facet may hide from every centre
    /// ray, the same for a tile as for its frame.
    pub(crate) fn contrast_bound_k(&self) -> f64 {
        let t = self.terrain.temperature_k;
        let hi = self.temperatures.iter().copied().fold(t, f64::max);
        let lo = self
            .temperatures
            .iter()
            .copied()
            .fold(t.min(INVERSE_TABLE_K[0]), f64::min);
        (hi - lo).max(0.0)
    }

    /// A candidate pixel refined to `refinement`'s target from side `start`: its radiance
    /// and what the refinement did. `contrast_k` is the largest difference of apparent
    /// temperature the pixel may hide (against its neighbours' centres, or the scene's
    /// bound for a thin candidate): what a sliver no ray met could cost.
    ///
    /// A level stops on its *geometric* standard error: that of its rounds' means with
    /// the hemispheric sky in place of the sky-view rays. The sky-view rays' own noise is
    /// the sky-view model's error, which the pilot bounds (a refined pixel, with at least
    /// as many sky-view rays in each round as its centre had, has less of it than a pixel
    /// that kept its centre ray); the σ the pixel reports is its whole standard error.
    ///
    /// The rays of the level the pixel's value comes from are charged to `sink`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn refine_pixel<const TRUTH: bool, C: ChargeSink>(
        &self,
        fc: &FrameConsts<'_>,
        options: &TraceOptions,
        refinement: &Refinement,
        inverse: &InverseTable<'_, B>,
        (col, row): (u32, u32),
        start: u32,
        contrast_k: f64,
        path: &mut Path,
        sink: &mut C,
    ) -> (f64, PixelSampling) {
        let camera = fc.camera();
        let index = u64::from(row) * u64::from(camera.pixels[0]) + u64::from(col);
        let mut scratch = Sample::miss(Event::Sky);
        let mut hemispheric = Path::default();
        let mut rays = 1;
        let mut levels = 0;
        let mut side = start.clamp(1, refinement.max_side);
        loop {
            levels |= PixelSampling::level_bit(side);
            // Each level draws from a stream of its own (the centre ray's draws are the
            // centre pass's), and shares the centre's sky-view rays out among its paths
            // ([`level_sky_view_rays`]).
            let level = TraceOptions {
                sky_view_rays: level_sky_view_rays(options.sky_view_rays, side),
                ..*options
            };
            let mut ctx = Ctx::for_pixel(&level, index).stream(REFINEMENT_STREAM ^ u64::from(side));
            let mut means = [0.0; ROUNDS];
            let mut calm_means = [0.0; ROUNDS];
            let mut sums = Sums::default();
            // The range of the level's rays' calm radiance, for the border walk.
            let mut seen = (f64::INFINITY, f64::NEG_INFINITY);
            // A level replaces the last: its rays are the pixel's.
            sink.restart();
            for (mean, calm_mean) in means.iter_mut().zip(&mut calm_means) {
                let mut round = 0.0;
                let mut calm = 0.0;
                ctx.for_each_subpixel((col, row), side, |ctx, x, y| {
                    self.follow(fc, camera.direction_at(x, y), ctx, path);
                    let l = self.radiance_charged::<TRUTH, C>(fc, path, &mut scratch, sink);
                    round += l;
                    if TRUTH {
                        sums.temperature_sensitivity += scratch.temperature_sensitivity;
                        sums.emissivity_sensitivity += scratch.emissivity_sensitivity;
                        let lu = scratch.path_radiance_w_m2_sr;
                        sums.path_radiance += if lu.is_finite() { lu } else { 0.0 };
                    }
                    let c = if path.has_sky_view_rays() {
                        path.with_sky_rays(0, &mut hemispheric);
                        self.radiance::<false>(fc, &hemispheric, &mut scratch)
                    } else {
                        l
                    };
                    seen = (seen.0.min(c), seen.1.max(c));
                    calm += c;
                });
                let n = f64::from(side * side);
                *mean = round / n;
                *calm_mean = calm / n;
                sums.radiance += round;
            }
            rays += ROUNDS as u32 * side * side;
            let n_rounds = ROUNDS as f64;
            let moments = |m: &[f64; ROUNDS]| {
                let mean = m.iter().sum::<f64>() / n_rounds;
                let variance = m.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n_rounds - 1.0);
                (mean, variance)
            };
            let (mean, variance) = moments(&means);
            let (calm_mean, calm_variance) = moments(&calm_means);
            let t_mean = inverse.temperature(mean);
            let slope = self.band.radiance_derivative(t_mean);
            let in_k = |variance: f64| {
                if slope > 0.0 {
                    (variance / n_rounds).sqrt() / slope
                } else {
                    0.0
                }
            };
            let sigma_k = in_k(variance);
            let calm_sigma_k = in_k(calm_variance);
            // The level's rays may all have missed a sliver of the edge that made the pixel
            // a candidate: they did so by chance once their rounds agree to rounding, and
            // may have while they are too few for a sliver worth the target to be hardly
            // missed ([`sliver_miss_rays`]). The pixel's border is then walked, densely
            // enough that a corner no ray of it met costs less than the target. An edge
            // that crosses the pixel crosses its border; a feature wholly inside it is a
            // thin candidate's, and was started dense.
            let agree = calm_variance.sqrt() <= 1e-12 * calm_mean.abs().max(1e-300);
            let level_rays = ROUNDS as f64 * f64::from(side) * f64::from(side);
            let mut border_differs = false;
            if agree || level_rays < sliver_miss_rays(contrast_k, refinement.target_k) {
                let per_side = border_rays_per_side(contrast_k, refinement.target_k);
                rays += 4 * per_side;
                // Rounds that agree to rounding agree by chance if their rays saw more than
                // one surface (an edge along a boundary of the strata): the border is held
                // to their mean, as if they had seen one.
                let range = if agree {
                    let t = inverse.temperature(calm_mean);
                    (t - refinement.target_k, t + refinement.target_k)
                } else {
                    let (lo, hi) = (inverse.temperature(seen.0), inverse.temperature(seen.1));
                    seen_range(lo, hi, side, refinement.target_k)
                };
                border_differs = self.border_differs(
                    fc,
                    &mut ctx,
                    (col, row),
                    per_side,
                    range,
                    inverse,
                    path,
                    &mut scratch,
                );
            }
            let reached = calm_sigma_k <= refinement.target_k && !border_differs;
            if reached || side >= refinement.max_side {
                sink.set_rays(ROUNDS as u32 * side * side);
                let n = n_rounds * f64::from(side * side);
                return (
                    mean,
                    PixelSampling {
                        sigma_k: sigma_k as f32,
                        geometric_sigma_k: calm_sigma_k as f32,
                        rays,
                        capped: !reached,
                        levels,
                        temperature_sensitivity: (sums.temperature_sensitivity / n) as f32,
                        emissivity_sensitivity: (sums.emissivity_sensitivity / n) as f32,
                        path_radiance_w_m2_sr: (sums.path_radiance / n) as f32,
                    },
                );
            }
            side = next_side(side, calm_sigma_k, refinement);
        }
    }

    /// Whether a ray through the border of pixel (`col`, `row`), `per_side` jittered rays a
    /// side, sees an apparent temperature (with the hemispheric sky) outside `range` (K,
    /// [`seen_range`]).
    #[allow(clippy::too_many_arguments)]
    fn border_differs(
        &self,
        fc: &FrameConsts<'_>,
        ctx: &mut Ctx<'_>,
        (col, row): (u32, u32),
        per_side: u32,
        range: (f64, f64),
        inverse: &InverseTable<'_, B>,
        path: &mut Path,
        scratch: &mut Sample,
    ) -> bool {
        let camera = fc.camera();
        let (x0, y0) = (f64::from(col), f64::from(row));
        let mut differs = false;
        for side in 0..4 {
            for k in 0..per_side {
                let along = (f64::from(k) + ctx.jitter()) / f64::from(per_side);
                let (x, y) = match side {
                    0 => (x0 + along, y0),
                    1 => (x0 + 1.0, y0 + along),
                    2 => (x0 + 1.0 - along, y0 + 1.0),
                    _ => (x0, y0 + 1.0 - along),
                };
                self.follow(fc, camera.direction_at(x, y), ctx, path);
                let l = if path.has_sky_view_rays() {
                    let mut hemispheric = Path::default();
                    path.with_sky_rays(0, &mut hemispheric);
                    self.radiance::<false>(fc, &hemispheric, scratch)
                } else {
                    self.radiance::<false>(fc, path, scratch)
                };
                let t = inverse.temperature(l);
                differs |= t < range.0 || t > range.1;
            }
        }
        differs
    }
}

/// The side of the level after one of side `side` whose geometric standard error was
/// `sigma_k`: a stratified estimate of an edge converges as the −3/2 power of the side, so
/// the side that reaches the target is `side · (σ/target)^(2/3)`; the next power of two
/// from there, at least twice `side`, at most the largest.
fn next_side(side: u32, sigma_k: f64, refinement: &Refinement) -> u32 {
    let wanted = f64::from(side) * (sigma_k / refinement.target_k).powf(2.0 / 3.0);
    let mut next = side.saturating_mul(2);
    while f64::from(next) < wanted && next < refinement.max_side {
        next = next.saturating_mul(2);
    }
    next.min(refinement.max_side)
}

/// The sky-view rays of each path of a level of side `side`, from the centre's `n`: `n`
/// shared out among the `side²` paths of a round, so that a round samples the hemisphere
/// with at least as many rays as the centre did; at least 4 each (a 2 × 2 stratified set),
/// or `n` when fewer; none when `n` is 0.
#[must_use]
pub fn level_sky_view_rays(n: u32, side: u32) -> u32 {
    n.div_ceil(side.max(1).saturating_mul(side.max(1)))
        .max(n.min(4))
}

/// The rays of a level below which its rays may all have missed a sliver of another
/// surface worth `target_k` in a pixel that may hide `contrast_k`: a sliver covering a
/// fraction f of the pixel moves it by at most f × `contrast_k`, and N jittered-stratified
/// rays all miss it with chance at most exp(−f·N) (as the converged reference's halves,
/// [`crate::reference::sliver_rays`], here over the level's rays at once).
fn sliver_miss_rays(contrast_k: f64, target_k: f64) -> f64 {
    2.0 * crate::reference::sliver_rays(contrast_k, target_k)
}

/// The range of apparent temperature, K, a border ray may see without showing a feature
/// the level's rays missed: the range `lo`..`hi` they saw, widened by `target_k` and by
/// the distance a ray of a level of side `side` may stand from the border (up to a
/// stratum's diagonal, √2/side of the pixel) times that range (a smooth gradient reaches a
/// little further at the border than inside).
fn seen_range(lo: f64, hi: f64, side: u32, target_k: f64) -> (f64, f64) {
    let margin = target_k + (hi - lo).max(0.0) * std::f64::consts::SQRT_2 / f64::from(side.max(1));
    (lo - margin, hi + margin)
}

/// Rays along each side of a pixel's border so that a corner cut off by an edge between
/// them, whose legs are under `1/n`, is at most `1/(2n²)` of the pixel and costs at most
/// `contrast_k/(2n²)`: at or under `target_k`. From 4 to 256.
fn border_rays_per_side(contrast_k: f64, target_k: f64) -> u32 {
    let n = (contrast_k.max(0.0) / (2.0 * target_k)).sqrt().ceil();
    if n.is_finite() {
        n.clamp(4.0, 256.0) as u32
    } else {
        256
    }
}

/// The distance from point `p` to the triangle `t` (0 inside), in the plane.
fn distance_to_triangle(p: [f64; 2], t: [[f64; 2]; 3]) -> f64 {
    let cross = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let (d0, d1, d2) = (
        cross(t[0], t[1], p),
        cross(t[1], t[2], p),
        cross(t[2], t[0], p),
    );
    let inside = (d0 >= 0.0 && d1 >= 0.0 && d2 >= 0.0) || (d0 <= 0.0 && d1 <= 0.0 && d2 <= 0.0);
    if inside {
        return 0.0;
    }
    let segment = |a: [f64; 2], b: [f64; 2]| {
        let ab = [b[0] - a[0], b[1] - a[1]];
        let len2 = ab[0] * ab[0] + ab[1] * ab[1];
        let s = if len2 > 0.0 {
            (((p[0] - a[0]) * ab[0] + (p[1] - a[1]) * ab[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        ((p[0] - a[0] - s * ab[0]).powi(2) + (p[1] - a[1] - s * ab[1]).powi(2)).sqrt()
    };
    segment(t[0], t[1])
        .min(segment(t[1], t[2]))
        .min(segment(t[2], t[0]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_levels_a_pixel_visited_give_back_their_sides() {
        // Sides from the thin start, doubling, up to a largest side that is a power of two
        // and one that is not.
        for (max_side, visited) in [(128, [8, 16, 128]), (96, [8, 32, 96])] {
            let s = PixelSampling {
                levels: visited
                    .iter()
                    .fold(0, |m, &v| m | PixelSampling::level_bit(v)),
                ..PixelSampling::default()
            };
            assert_eq!(s.level_sides(max_side).collect::<Vec<_>>(), visited);
        }
        assert_eq!(PixelSampling::default().level_sides(128).count(), 0);
    }

    #[test]
    fn distances_to_a_triangle_are_zero_inside_and_to_the_nearest_side_outside() {
        let t = [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]];
        assert!(distance_to_triangle([1.0, 1.0], t).abs() < 1e-12);
        assert!((distance_to_triangle([2.0, -3.0], t) - 3.0).abs() < 1e-12);
        assert!((distance_to_triangle([-3.0, -4.0], t) - 5.0).abs() < 1e-12);
        // Wound the other way, the same.
        let r = [t[0], t[2], t[1]];
        assert!((distance_to_triangle([2.0, -3.0], r) - 3.0).abs() < 1e-12);
    }

    #[test]
    fn a_level_jumps_to_the_side_its_error_asks_for() {
        let r = Refinement {
            target_k: 0.1,
            edge_k: 0.05,
            max_side: 128,
            thin_side: 8,
        };
        // Twice the target: 2^(2/3) = 1.59 times the side, so the next power of two.
        assert_eq!(next_side(4, 0.2, &r), 8);
        // 20 times: 7.4 times the side, 4 → 29.5 → 32.
        assert_eq!(next_side(4, 2.0, &r), 32);
        assert_eq!(next_side(64, 100.0, &r), 128);
        assert_eq!(next_side(128, 100.0, &r), 128);
    }

    #[test]
    fn a_capped_pixel_costs_every_level() {
        let r = Refinement {
            target_k: 0.1,
            edge_k: 0.05,
            max_side: 16,
            thin_side: 8,
        };
        assert_eq!(r.rays_to_cap(2), 8 * (4 + 16 + 64 + 256));
        assert_eq!(r.rays_to_cap(8), 8 * (64 + 256));
        assert!(r.validate().is_ok());
        assert!(Refinement { thin_side: 32, ..r }.validate().is_err());
    }
}
