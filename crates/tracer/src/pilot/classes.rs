//! The populations of pixels a frame is made of, and the pilot's sample of them.
//!
//! A cheap pass traces every pixel's centre ray (one bounce, the hemispheric sky, the band
//! model) and puts each pixel in a [`PixelClass`]: what the ray met first (the sky, the
//! terrain, a diffuse facet, a specular facet whose reflection escapes or meets another
//! facet), the material, whether it meets its facet at a grazing angle, whether it looks
//! within a few degrees of the horizon, and whether its reflection meets another mirror
//! (where the bounces' cut errs). The refinement candidates, where a centre ray may miss
//! what part of the pixel holds (facets thinner than a pixel, [`Tracer::thin_pixels`], the
//! horizon, edges), are probed densely; a population only such a probe finds is a class
//! of its own, *sub-pixel*. The sample is stratified over the
//! classes: a floor of [`CLASS_FLOOR`] points in each (every point of a smaller one), the
//! rest in proportion to the pixels, and each point weighs back to the frame by the
//! pixels it stands for. A population of 0.1 % of the frame (a glass pane, a wire) is
//! therefore always measured, however small.

use rand::{SeedableRng, seq::SliceRandom};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use irsig_model::decision::ClassReport;
use irsig_radiometry::BandModel;

use crate::env::Atmosphere;
use crate::path::{Mirror, Path, Primary};
use crate::tracer::{
    BandSet, Ctx, Event, FrameConsts, MaterialData, Sample, TraceOptions, Tracer, TruthPixel,
};
use glam::DVec3;

/// Points each class is sampled with at least (all of a smaller one). With 24 points the
/// class's largest error bounds its 90th percentile with 92 % confidence (1 − 0.9²⁴).
pub const CLASS_FLOOR: usize = 24;
/// A facet seen more than this far from its normal is met at a grazing angle, degrees
/// (where emissivity falls fastest and the rough-surface model departs most from Fresnel).
pub const GRAZING_DEG: f64 = 75.0;
/// A ray within this of the horizon looks through the longest, most interpolated paths of
/// the atmosphere, degrees.
pub const HORIZON_DEG: f64 = 5.0;
/// Candidate pixels (thin, on the horizon, or on an edge) probed for sub-pixel
/// populations, at most.
const PROBED: usize = 512;
/// Probe rays per probed pixel (a 4 × 4 stratified grid).
const PROBE_SIDE: u32 = 4;

/// A population of pixels: what the centre ray met, how, and where it looked.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PixelClass {
    /// The first event (thesis Figure 6).
    pub event: Event,
    /// The material id of the facet met (0: none).
    pub material: u16,
    /// The facet is met more than [`GRAZING_DEG`] from its normal.
    pub grazing: bool,
    /// The ray (sky or terrain) looks within [`HORIZON_DEG`] of the horizon.
    pub horizon: bool,
    /// The facet's reflection meets a facet that reflects specularly too: a chain the
    /// bounces cut, where their error lives (a mirror seen in a mirror).
    pub mirror_in_mirror: bool,
}

impl PixelClass {
    /// The class of a recorded path along `dir` (world, unit).
    pub(crate) fn of_path(path: &Path, materials: &[MaterialData], dir: DVec3) -> Self {
        let cos_grazing = GRAZING_DEG.to_radians().cos();
        let near_horizon = dir[2].abs() < HORIZON_DEG.to_radians().sin();
        match (path.primary, path.nodes.first()) {
            (Primary::Facet { .. }, Some(node)) => Self {
                mirror_in_mirror: matches!(node.mirror, Some(Mirror::Next))
                    && path.nodes.get(1).is_some_and(|next| next.mirror.is_some()),
                event: match node.mirror {
                    None => Event::Diffuse,
                    Some(Mirror::Next) => Event::SpecularHitsFacet,
                    Some(Mirror::Escaped(_) | Mirror::Untraced(_)) => Event::SpecularEscapes,
                },
                material: materials
                    .get(usize::from(node.surface.data.material))
                    .map_or(0, |m| m.id),
                grazing: node.surface.cos_incidence < cos_grazing,
                horizon: false,
            },
            (Primary::Terrain { .. }, _) => Self {
                event: Event::Terrain,
                material: 0,
                grazing: false,
                horizon: near_horizon,
                mirror_in_mirror: false,
            },
            _ => Self {
                event: Event::Sky,
                material: 0,
                grazing: false,
                horizon: near_horizon,
                mirror_in_mirror: false,
            },
        }
    }

    /// The class of a rendered pixel from its centre ray's truth and direction;
    /// `reflects_specularly` says whether a material id reflects specularly (a facet met
    /// by the pixel's reflection that does makes it a mirror in a mirror).
    #[must_use]
    pub fn of_truth(t: &TruthPixel, dir: DVec3, reflects_specularly: impl Fn(u16) -> bool) -> Self {
        let facet = matches!(
            t.event,
            Event::Diffuse | Event::SpecularEscapes | Event::SpecularHitsFacet
        );
        Self {
            event: t.event,
            material: if facet { t.primary_material } else { 0 },
            grazing: facet && t.cos_incidence < GRAZING_DEG.to_radians().cos(),
            horizon: !facet && dir[2].abs() < HORIZON_DEG.to_radians().sin(),
            mirror_in_mirror: t.event == Event::SpecularHitsFacet
                && reflects_specularly(t.secondary_material),
        }
    }

    /// Whether a pixel of class `other`, rendered with any number of bounces, belongs to
    /// this population: the same, with the two specular events one (a reflection that
    /// meets a facet at one bounce may be cut at none).
    #[must_use]
    pub fn same_population(&self, other: &Self) -> bool {
        let specular = |e: Event| matches!(e, Event::SpecularEscapes | Event::SpecularHitsFacet);
        (self.event == other.event || (specular(self.event) && specular(other.event)))
            && self.material == other.material
            && self.grazing == other.grazing
            && self.horizon == other.horizon
            // A chain cut at fewer bounces escapes: what it would have met is unknown.
            && (self.mirror_in_mirror == other.mirror_in_mirror
                || self.event != other.event
                || self.event != Event::SpecularHitsFacet)
    }

    /// The class a decision's report names, if its event is one of [`Event::name`]'s.
    #[must_use]
    pub fn of_report(r: &ClassReport) -> Option<Self> {
        Some(Self {
            event: Event::from_name(&r.event)?,
            material: r.material,
            grazing: r.grazing,
            horizon: r.horizon,
            mirror_in_mirror: r.mirror_in_mirror,
        })
    }
}

/// A point the pilot measures: a position on the image (pixels, continuous) and the
/// class it stands for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SamplePoint {
    pub(crate) x: f64,
    pub(crate) y: f64,
    /// Row-major index of its pixel: its random stream.
    pub(crate) pixel: u64,
    /// Index into [`Census::classes`].
    pub(crate) class: usize,
    /// Found by a sub-pixel probe, not a centre ray.
    pub(crate) probe: bool,
}

/// One class of the census: the pixels it holds and the points sampled from it.
#[derive(Debug, Clone)]
pub(crate) struct ClassCensus {
    pub(crate) class: PixelClass,
    /// Found only by the sub-pixel probe.
    pub(crate) sub_pixel: bool,
    /// Its share of the frame's pixels (estimated from the probe for a sub-pixel class).
    pub(crate) share: f64,
    /// Points sampled from it.
    pub(crate) samples: usize,
}

impl ClassCensus {
    /// What each of its points stands for, as a share of the frame.
    pub(crate) fn weight(&self) -> f64 {
        if self.samples == 0 {
            0.0
        } else {
            self.share / self.samples as f64
        }
    }
}

/// The frame's populations, the candidates for refinement, and the stratified sample.
#[derive(Debug)]
pub(crate) struct Census {
    pub(crate) classes: Vec<ClassCensus>,
    pub(crate) points: Vec<SamplePoint>,
    /// Row-major: the pixel's centre differs from a neighbour's by more than the edge
    /// threshold, or a thin facet lies within a pixel of it.
    pub(crate) candidate: Vec<bool>,
    /// Row-major: the largest difference of its centre's apparent temperature from a
    /// neighbour's, K.
    pub(crate) contrast: Vec<f64>,
    /// Row-major: a thin facet lies within a pixel of it.
    pub(crate) thin: Vec<bool>,
}

impl Census {
    /// The share of the frame's pixels that are refinement candidates.
    pub(crate) fn candidate_share(&self) -> f64 {
        let n = self.candidate.len().max(1) as f64;
        self.candidate.iter().filter(|&&c| c).count() as f64 / n
    }

    /// The indices of the sample points in each class.
    pub(crate) fn points_by_class(&self) -> Vec<Vec<usize>> {
        let mut by_class: Vec<Vec<usize>> = vec![Vec::new(); self.classes.len()];
        for (i, p) in self.points.iter().enumerate() {
            by_class[p.class].push(i);
        }
        by_class
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// The census of `camera`'s frame: every pixel's class from its centre ray in `set`
    /// (one bounce, the hemispheric sky), the refinement candidates at `edge_k`, the
    /// sub-pixel probe of thin pixels, and a stratified sample of about `points` points.
    pub(crate) fn census<S: Atmosphere>(
        &self,
        fc: &FrameConsts<'_>,
        set: &BandSet<S>,
        edge_k: f64,
        points: usize,
        seed: u64,
    ) -> Census {
        let camera = fc.camera();
        let [w, h] = camera.pixels;
        let (wu, hu) = (w as usize, h as usize);
        let options = TraceOptions {
            specular_bounces: 1,
            sky_view_rays: 0,
            supersampling: 1,
            adaptive_threshold_k: None,
            seed,
            truth: false,
        };
        let per_pixel = self.centre_classes(fc, set, &options);
        let temperatures: Vec<f64> = per_pixel.iter().map(|p| p.1).collect();
        let contrast = crate::tracer::contrast_of(&temperatures, wu, hu);
        let thin = self.thin_pixels(camera);
        let candidate: Vec<bool> = contrast
            .iter()
            .zip(&thin)
            .map(|(&c, &t)| c > edge_k || t)
            .collect();

        // The classes the centre rays found, in a fixed order, and their pixels.
        let mut found: Vec<PixelClass> = per_pixel.iter().map(|p| p.0).collect();
        found.sort_unstable();
        found.dedup();
        let total = (wu * hu).max(1) as f64;
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x7069_6c6f_7400_0001);
        let (mut classes, mut chosen) =
            stratified_sample(&found, &per_pixel, w, total, points, &mut rng);

        // The sub-pixel probe: the refinement candidates (thin pixels, the horizon's, and
        // edges, where a sliver of a pixel may hold what no centre ray met: a wire, a mirror
        // glimpsed in a window's edge), 4 × 4 rays each; a class no centre ray found becomes
        // a class of its own, sampled at the points that found it.
        let mut probe_pixels: Vec<u32> = (0..(wu * hu) as u32)
            .filter(|&i| candidate[i as usize])
            .collect();
        let probe_count = probe_pixels.len();
        let (probed, _) = probe_pixels.partial_shuffle(&mut rng, PROBED.min(probe_count));
        probed.sort_unstable();
        let mut probe_points = self.probe_sub_pixels(fc, &options, probed, &found);
        let probe_rays = (probed.len() as f64 * f64::from(PROBE_SIDE * PROBE_SIDE)).max(1.0);
        // A class's area: the probe rays that met it, over the probed share of the
        // candidates.
        let share = |met: usize| met as f64 / probe_rays * probe_count as f64 / total;
        sub_pixel_classes(
            &mut probe_points,
            share,
            &mut rng,
            &mut classes,
            &mut chosen,
        );
        Census {
            classes,
            points: chosen,
            candidate,
            contrast,
            thin,
        }
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// Each pixel's class and apparent temperature from its centre ray, rows in parallel.
    fn centre_classes<S: Atmosphere>(
        &self,
        fc: &FrameConsts<'_>,
        set: &BandSet<S>,
        options: &TraceOptions,
    ) -> Vec<(PixelClass, f64)> {
        let camera = fc.camera();
        let [w, h] = camera.pixels;
        let inverse = self.inverse_table();
        (0..h)
            .into_par_iter()
            .flat_map_iter(|row| {
                let mut path = Path::default();
                let mut scratch = Sample::miss(Event::Sky);
                let inverse = &inverse;
                (0..w)
                    .map(move |col| {
                        let mut ctx =
                            Ctx::for_pixel(options, u64::from(row) * u64::from(w) + u64::from(col));
                        let dir = camera.pixel_direction(col, row);
                        self.follow(fc, dir, &mut ctx, &mut path);
                        let l = self.radiance_with::<false, S>(set, None, fc, &path, &mut scratch);
                        (
                            PixelClass::of_path(&path, &self.materials, dir),
                            inverse.temperature(l),
                        )
                    })
                    .collect::<Vec<_>>()
            })
            .collect()
    }

    /// The probed pixels' sub-pixel rays (each pixel its own stream, probed side by side,
    /// taken in order) that met a class no centre ray found, sorted by class and position.
    fn probe_sub_pixels(
        &self,
        fc: &FrameConsts<'_>,
        options: &TraceOptions,
        probed: &[u32],
        found: &[PixelClass],
    ) -> Vec<(PixelClass, SamplePoint)> {
        let camera = fc.camera();
        let w = camera.pixels[0];
        let mut probe_points: Vec<(PixelClass, SamplePoint)> = probed
            .par_iter()
            .map_init(Path::default, |path, &i| {
                let (col, row) = (i % w, i / w);
                let mut ctx =
                    Ctx::for_pixel(options, u64::from(i)).stream(crate::tracer::PROBE_STREAM);
                let mut hits: Vec<(PixelClass, f64, f64)> = Vec::new();
                ctx.for_each_subpixel((col, row), PROBE_SIDE, |ctx, x, y| {
                    let dir = camera.direction_at(x, y);
                    self.follow(fc, dir, ctx, path);
                    hits.push((PixelClass::of_path(path, &self.materials, dir), x, y));
                });
                hits.into_iter()
                    .filter(|(class, _, _)| found.binary_search(class).is_err())
                    .map(|(class, x, y)| {
                        (
                            class,
                            SamplePoint {
                                x,
                                y,
                                pixel: u64::from(i),
                                class: 0,
                                probe: true,
                            },
                        )
                    })
                    .collect::<Vec<_>>()
            })
            .flatten_iter()
            .collect();
        probe_points.sort_by(|a, b| {
            a.0.cmp(&b.0)
                .then(a.1.pixel.cmp(&b.1.pixel))
                .then(a.1.x.total_cmp(&b.1.x))
                .then(a.1.y.total_cmp(&b.1.y))
        });
        probe_points
    }
}

/// The stratified sample of the classes the centre rays `found` (sorted): a floor of
/// [`CLASS_FLOOR`] points in each, the rest in proportion to its pixels.
fn stratified_sample(
    found: &[PixelClass],
    per_pixel: &[(PixelClass, f64)],
    w: u32,
    total: f64,
    points: usize,
    rng: &mut ChaCha8Rng,
) -> (Vec<ClassCensus>, Vec<SamplePoint>) {
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); found.len()];
    for (i, p) in per_pixel.iter().enumerate() {
        if let Ok(k) = found.binary_search(&p.0) {
            members[k].push(i as u32);
        }
    }
    let mut classes = Vec::new();
    let mut chosen = Vec::new();
    for (k, (class, pixels)) in found.iter().zip(&mut members).enumerate() {
        let share = pixels.len() as f64 / total;
        let wanted = ((points as f64 * share).round() as usize)
            .max(CLASS_FLOOR)
            .min(pixels.len());
        let (picked, _) = pixels.partial_shuffle(rng, wanted);
        picked.sort_unstable();
        for &i in picked.iter() {
            let (col, row) = (i % w, i / w);
            chosen.push(SamplePoint {
                x: f64::from(col) + 0.5,
                y: f64::from(row) + 0.5,
                pixel: u64::from(i),
                class: k,
                probe: false,
            });
        }
        classes.push(ClassCensus {
            class: *class,
            sub_pixel: false,
            share,
            samples: wanted,
        });
    }
    (classes, chosen)
}

/// Each class only the probe found (`probe_points` sorted by class) becomes a sub-pixel
/// class of the census, its share of the frame `share(rays that met it)`, sampled at up
/// to [`CLASS_FLOOR`] of those rays.
fn sub_pixel_classes(
    probe_points: &mut [(PixelClass, SamplePoint)],
    share: impl Fn(usize) -> f64,
    rng: &mut ChaCha8Rng,
    classes: &mut Vec<ClassCensus>,
    chosen: &mut Vec<SamplePoint>,
) {
    let mut start = 0;
    while start < probe_points.len() {
        let class = probe_points[start].0;
        let end = start
            + probe_points[start..]
                .iter()
                .take_while(|p| p.0 == class)
                .count();
        let group = &mut probe_points[start..end];
        let share = share(end - start);
        let k = classes.len();
        let wanted = CLASS_FLOOR.min(group.len());
        let (picked, _) = group.partial_shuffle(rng, wanted);
        picked.sort_by(|a, b| a.1.pixel.cmp(&b.1.pixel).then(a.1.x.total_cmp(&b.1.x)));
        for (_, p) in picked.iter() {
            chosen.push(SamplePoint { class: k, ..*p });
        }
        classes.push(ClassCensus {
            class,
            sub_pixel: true,
            share,
            samples: wanted,
        });
        start = end;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_two_specular_events_are_one_population() {
        let c = |event| PixelClass {
            event,
            material: 3,
            grazing: false,
            horizon: false,
            mirror_in_mirror: false,
        };
        assert!(c(Event::SpecularEscapes).same_population(&c(Event::SpecularHitsFacet)));
        // A mirror seen in a mirror is a population of its own where both reflections
        // meet a facet; a chain cut short may be either.
        let in_mirror = PixelClass {
            mirror_in_mirror: true,
            ..c(Event::SpecularHitsFacet)
        };
        assert!(!in_mirror.same_population(&c(Event::SpecularHitsFacet)));
        assert!(in_mirror.same_population(&c(Event::SpecularEscapes)));
        assert!(!c(Event::Diffuse).same_population(&c(Event::SpecularHitsFacet)));
        let other = PixelClass {
            material: 4,
            ..c(Event::Diffuse)
        };
        assert!(!c(Event::Diffuse).same_population(&other));
    }
}
