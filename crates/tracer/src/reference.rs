//! A rendering converged by construction: the truth the tolerance is promised against
//! (docs/accuracy.md, "The converged reference"), per pixel with its own error. Every pixel
//! is traced in two independent halves, in rounds of more rays, until the halves agree;
//! the tolerance's checks (`tests/guarantee.rs`, `tests/guarantee_sun.rs`) and the
//! shipped pipelines' rows (`irsig-tests`'s `tolerance_rows`) measure against it.

use rayon::prelude::*;

use irsig_radiometry::BandModel;

use crate::env::Atmosphere;
use crate::{Camera, Tile, TraceError, TraceOptions, Tracer};

/// The |x| below which `p` % of `values` lie (the nearest rank above).
///
/// # Panics
/// `values` is empty.
#[must_use]
pub fn percentile(values: &[f64], p: f64) -> f64 {
    let mut v: Vec<f64> = values.iter().map(|x| x.abs()).collect();
    v.sort_by(f64::total_cmp);
    let i = ((p / 100.0) * (v.len() - 1) as f64).ceil() as usize;
    v[i.min(v.len() - 1)]
}

/// One round of [`converged_reference`]: `side × side` jittered-stratified rays per pixel
/// from `seeds` seeds a half, each hit with `sky_view_rays` sky-view rays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReferenceRound {
    /// Rays per pixel along each side of one seed's stratification (at most 64).
    pub side: u32,
    /// Independent seeds averaged in each half.
    pub seeds: u32,
    /// Sky-view rays per diffuse hit.
    pub sky_view_rays: u32,
}

impl ReferenceRound {
    /// Rays per pixel in each half.
    #[must_use]
    pub fn rays(&self) -> u32 {
        self.side * self.side * self.seeds
    }
}

/// The rounds of [`converged_reference`]: each traces four times the rays per pixel of the
/// one before (256, 1,024, 4,096, 16,384, 65,536, 262,144 a half), from fresh seeds.
/// Sky-view rays per pixel (rays × sky-view rays a hit) quadruple too, except from the
/// second round to the third, where only the primary rays do (an edge's noise is the
/// primary rays', and 16 sky-view rays a hit keep the deeper rounds affordable).
pub const REFERENCE_ROUNDS: [ReferenceRound; 6] = [
    ReferenceRound {
        side: 16,
        seeds: 1,
        sky_view_rays: 64,
    },
    ReferenceRound {
        side: 32,
        seeds: 1,
        sky_view_rays: 64,
    },
    ReferenceRound {
        side: 64,
        seeds: 1,
        sky_view_rays: 16,
    },
    ReferenceRound {
        side: 64,
        seeds: 4,
        sky_view_rays: 16,
    },
    ReferenceRound {
        side: 64,
        seeds: 16,
        sky_view_rays: 16,
    },
    ReferenceRound {
        side: 64,
        seeds: 64,
        sky_view_rays: 16,
    },
];

/// The rounds [`converged_reference`] traces unless told otherwise: all six, up to 262,144
/// rays a half. At 0.1 K five left 3 % of a low view over the stop and its error's 99th
/// percentile at 0.040 K; the sixth brought it to 0.013 K.
pub const REFERENCE_ROUNDS_DEFAULT: usize = 6;

/// The round a pixel that is not one surface reaches at least (64 × 64 rays a half): two
/// halves of 16 × 16 rays can agree by chance on an edge, where a few rays flipping across
/// it are all that moves them.
pub const REFERENCE_EDGE_ROUND: usize = 2;

/// The chance, at most, that both halves of a round miss a sliver of another surface worth
/// the stop, once a pixel beside an edge whose halves are equal to the last bit is taken as
/// converged ([`sliver_rays`]).
pub const REFERENCE_SLIVER_MISS: f64 = 0.01;

/// The rays a half past which two halves equal to the last bit are taken as converged, for
/// a pixel beside an edge in a frame whose temperatures span `range_k`, stopped at
/// `stop_k`. A sliver of another surface covering a fraction f of the pixel moves it by at
/// most f × `range_k` (for a surface the frame shows somewhere, at a temperature within
/// its range), so only one of f ≥ `stop_k` / `range_k` matters. Each of a half's N
/// jittered-stratified rays misses it with chance 1 − f_s·N, f_s being the sliver's share
/// in that ray's stratum, so all N miss it with chance at most Π exp(−f_s·N) = exp(−f·N),
/// and both halves exp(−2·f·N): under [`REFERENCE_SLIVER_MISS`] once N ≥
/// ln(1 / [`REFERENCE_SLIVER_MISS`]) × `range_k` / (2 × `stop_k`).
#[must_use]
pub fn sliver_rays(range_k: f64, stop_k: f64) -> f64 {
    REFERENCE_SLIVER_MISS.recip().ln() * range_k / (2.0 * stop_k)
}

/// A converged rendering ([`converged_reference`]): the truth per pixel and its own error.
#[derive(Debug, Clone)]
pub struct ConvergedReference {
    /// Apparent temperature per pixel, K: the mean of the two halves of its last round.
    pub truth: Vec<f64>,
    /// The truth's own error per pixel, K: half its two halves' difference (signed).
    pub error: Vec<f64>,
    /// Pixels traced at each round of [`REFERENCE_ROUNDS`] (every pixel at the first).
    pub pixels_per_round: Vec<usize>,
    /// The pixels still over the stopping test after the last round, by index.
    pub capped: Vec<usize>,
    /// The stopping test: the halves' difference, K.
    pub stop_k: f64,
}

impl ConvergedReference {
    /// The 99th percentile of the truth's own error, K.
    #[must_use]
    pub fn error_p99_k(&self) -> f64 {
        percentile(&self.error, 99.0)
    }

    /// One line: the pixels at each round and those capped.
    #[must_use]
    pub fn rounds_line(&self) -> String {
        let rounds: Vec<String> = self
            .pixels_per_round
            .iter()
            .zip(REFERENCE_ROUNDS)
            .map(|(n, r)| format!("{n} at {}", r.rays()))
            .collect();
        format!(
            "pixels by rays a half: {}; {} capped",
            rounds.join(", "),
            self.capped.len()
        )
    }
}

/// A rendering of `camera` converged by construction, in the first `rounds` of
/// [`REFERENCE_ROUNDS`], 8 bounces throughout. Every pixel is traced in two independent
/// halves (their own seeds) at the first round. A pixel goes on to the next round, from
/// fresh seeds, while its two halves differ by more than `stop_k`, and until
/// [`REFERENCE_EDGE_ROUND`] when it may not be one surface: its first round's mean with the
/// hemispheric sky (no sky-view rays) more than `stop_k` from its centre ray's or from a
/// neighbour's (an edge, a reflected horizon, a wire; [`not_one_surface`]); such a pixel
/// whose halves are equal to the last bit goes on past that round too, until its rays a
/// half reach [`sliver_rays`]. The last round's halves are kept; their mean is the truth,
/// half their difference its own error. A guarantee at tolerance T takes `stop_k` = T/6,
/// so a stopped pixel's measured error is at most T/12, a quarter of the T/3 its 99th
/// percentile must stay under: the margin is for halves that agree by chance (one
/// difference is a one-sample estimate of the spread).
///
/// # Errors
/// The tracer's, where it cannot render the camera.
pub fn converged_reference<B: BandModel + Sync, A: Atmosphere>(
    tracer: &Tracer<B, A>,
    camera: &Camera,
    stop_k: f64,
    rounds: usize,
) -> Result<ConvergedReference, TraceError> {
    let rounds = &REFERENCE_ROUNDS[..rounds.clamp(1, REFERENCE_ROUNDS.len())];
    let temperature = |l: f64| tracer.apparent_temperature_k(l);
    let options = |round: ReferenceRound, sky_view_rays: u32, seed: u64| TraceOptions {
        specular_bounces: 8,
        sky_view_rays,
        supersampling: round.side,
        adaptive_threshold_k: None,
        seed,
        truth: false,
    };
    let whole = |o: TraceOptions| -> Result<Vec<f64>, TraceError> {
        let frame = tracer.render(camera, &o, &|_| {})?;
        Ok(frame
            .radiance_w_m2_sr
            .iter()
            .map(|&l| temperature(l))
            .collect())
    };
    let first = REFERENCE_ROUNDS[0];
    let centre = whole(TraceOptions {
        supersampling: 1,
        ..options(first, 0, 0)
    })?;
    let calm = whole(options(first, 0, 101))?;
    let mut a = whole(options(first, first.sky_view_rays, 101))?;
    let mut b = whole(options(first, first.sky_view_rays, 202))?;
    let width = camera.pixels[0];
    let edge = not_one_surface(&centre, &calm, camera.pixels, stop_k);
    // The round each pixel's halves come from.
    let mut level = vec![0; a.len()];
    // A pixel that may not be one surface whose halves are equal to the last bit saw one
    // value with every ray of both: a sliver of another surface (a hot corner reflected in
    // a mirror) that neither met would leave them so, so they are no evidence it has
    // converged, and it goes on until a sliver worth the stop would hardly have been
    // missed ([`sliver_rays`], over the frame's range of temperatures).
    let range_k = frame_range_k(&centre, &calm);
    let sliver = sliver_rays(range_k, stop_k);
    let needs = |a: &[f64], b: &[f64], level: &[usize], i: usize| {
        let blind = a[i].to_bits() == b[i].to_bits()
            && f64::from(REFERENCE_ROUNDS[level[i]].rays()) < sliver;
        (a[i] - b[i]).abs() > stop_k || (edge[i] && (level[i] < REFERENCE_EDGE_ROUND || blind))
    };
    let mut pixels_per_round = vec![a.len()];
    for (r, &round) in rounds.iter().enumerate().skip(1) {
        // A pixel that is not one surface goes straight to its round.
        let next: Vec<usize> = (0..a.len())
            .filter(|&i| needs(&a, &b, &level, i) && (!edge[i] || r >= REFERENCE_EDGE_ROUND))
            .collect();
        pixels_per_round.push(next.len());
        // Seeds of round r, half h: 1000·r + 500·h + k, none shared with the first
        // round's (101, 202) or another round's.
        let half = |i: usize, h: u64| {
            let tile = Tile {
                x: i as u32 % width,
                y: i as u32 / width,
                width: 1,
                height: 1,
            };
            let from = 1000 * r as u64 + 500 * h;
            let mut sum = 0.0;
            for seed in from..from + u64::from(round.seeds) {
                let o = options(round, round.sky_view_rays, seed);
                sum += tracer
                    .render_tile(camera, &o, tile, &|_| {})?
                    .radiance_w_m2_sr[0];
            }
            Ok::<_, TraceError>(temperature(sum / f64::from(round.seeds)))
        };
        let traced: Vec<(usize, f64, f64)> = next
            .par_iter()
            .map(|&i| Ok((i, half(i, 0)?, half(i, 1)?)))
            .collect::<Result<_, TraceError>>()?;
        for (i, x, y) in traced {
            (a[i], b[i], level[i]) = (x, y, r);
        }
    }
    let capped = (0..a.len()).filter(|&i| needs(&a, &b, &level, i)).collect();
    Ok(ConvergedReference {
        truth: a.iter().zip(&b).map(|(a, b)| 0.5 * (a + b)).collect(),
        error: a.iter().zip(&b).map(|(a, b)| 0.5 * (a - b)).collect(),
        pixels_per_round,
        capped,
        stop_k,
    })
}

/// The span of the frame's temperatures, K: the largest less the smallest of its centre
/// rays' and its first round's means (finite values only; 0 for a uniform frame).
fn frame_range_k(centre: &[f64], calm: &[f64]) -> f64 {
    let (lo, hi) = centre
        .iter()
        .chain(calm)
        .filter(|t| t.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
            (lo.min(t), hi.max(t))
        });
    if hi >= lo { hi - lo } else { 0.0 }
}

/// The pixels that may not be one surface, row-major: a pixel whose first round's mean with
/// the hemispheric sky (`calm`) is more than `stop_k` from its centre ray's (`centre`), or
/// from one of its 8 neighbours' means. Beside an edge, a sliver of the far side no ray of
/// the first round met leaves both halves equal, to the last bit where every ray saw one
/// uniform surface (a mirror reflecting the uniform sky), and equal to the centre: only the
/// neighbour shows that an edge passes near.
fn not_one_surface(centre: &[f64], calm: &[f64], [w, h]: [u32; 2], stop_k: f64) -> Vec<bool> {
    crate::tracer::contrast_of(calm, w as usize, h as usize)
        .iter()
        .zip(centre.iter().zip(calm))
        .map(|(&contrast, (c, m))| contrast > stop_k || (c - m).abs() > stop_k)
        .collect()
}

/// The 90th percentile of |`error`| over the pixels of each material of `ids` (`material`:
/// the truth's primary-material layer) that has at least 10 of them, `(id, pixels, p90)`:
/// a class of a handful of pixels has no 90th percentile worth the name.
#[must_use]
pub fn material_p90s(error: &[f64], material: &[f32], ids: &[u16]) -> Vec<(u16, usize, f64)> {
    ids.iter()
        .filter_map(|&id| {
            let of: Vec<f64> = error
                .iter()
                .zip(material)
                .filter(|&(_, &m)| m.to_bits() == f32::from(id).to_bits())
                .map(|(e, _)| *e)
                .collect();
            (of.len() >= 10).then(|| (id, of.len(), percentile(&of, 90.0)))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pixel_beside_an_edge_may_not_be_one_surface_though_its_rays_all_agree() {
        // 4 × 3 pixels, each centre its own mean (every ray of each saw one surface), a
        // vertical edge of 30 K between columns 1 and 2; one pixel of column 3 whose mean
        // is 0.2 K off its centre (a wire in it).
        let mut calm = vec![300.0, 300.0, 270.0, 270.0];
        calm = calm.repeat(3);
        let mut centre = calm.clone();
        centre[11] += 0.2;
        let flagged = not_one_surface(&centre, &calm, [4, 3], 0.05);
        let expected = [
            false, true, true, false, // beside the edge: columns 1 and 2
            false, true, true, false, //
            false, true, true, true, // and the wire's pixel
        ];
        assert_eq!(flagged, expected);
        // A difference of the stop itself is not over it.
        assert!(!not_one_surface(&[1.0, 1.5], &[1.0, 1.5], [2, 1], 0.5)[0]);
    }

    #[test]
    fn equal_halves_beside_an_edge_are_believed_once_a_sliver_worth_the_stop_is_hardly_missed() {
        // A frame spanning 100 K stopped at a sixth of 0.5 K: a sliver worth the stop
        // covers 1/1,200 of the pixel; two halves of N rays both miss it with chance at
        // most exp(-2N/1,200), 1 % at N = 1,200 ln(100) / 2 = 2,763.2.
        let n = sliver_rays(100.0, 0.5 / 6.0);
        assert!((n - 2763.1).abs() < 0.1, "{n}");
        assert!((-2.0 * n / 1200.0).exp() <= REFERENCE_SLIVER_MISS * (1.0 + 1e-12));
        // Twice the range or half the stop, twice the rays.
        assert!((sliver_rays(200.0, 0.5 / 6.0) / n - 2.0).abs() < 1e-12);
        assert!((sliver_rays(100.0, 0.25 / 6.0) / n - 2.0).abs() < 1e-12);
        // The range ignores what is not finite, and a uniform frame spans nothing.
        let range = frame_range_k(&[300.0, f64::NAN, 250.0], &[310.0, f64::INFINITY]);
        assert!((range - 60.0).abs() < 1e-12, "{range}");
        assert!(frame_range_k(&[280.0; 4], &[280.0; 4]).abs() < 1e-12);
    }
}
