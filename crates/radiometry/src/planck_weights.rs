//! The quadrature of a band average weighted by the response and Planck's law,
//! `∫ f(λ) S(λ) B_λ(λ, T) dλ / ∫ S(λ) B_λ(λ, T) dλ`, for a quantity `f` known at samples
//! (an emissivity curve, a refractive-index table): its nodes and weights, shared by
//! [`crate::band_average_emissivity`] and the Fresnel generator's band tables.

use std::sync::OnceLock;

use crate::band::{Band, gauss_legendre};
use crate::constants::{C1L_W_M2_SR, C2_M_K};
use crate::error::{RadiometryError, RadiometryErrorKind};

/// Gauss–Legendre nodes on each piece between breakpoints: `f` is linear on a piece and
/// the Planck function smooth, so 8 nodes on pieces of at most 0.25 µm are exact to ~1e-12.
const NODES_PER_PIECE: usize = 8;
/// The longest piece, µm.
const MAX_PIECE_UM: f64 = 0.25;
/// The most pieces between breakpoints an average takes (8 nodes each): a table denser
/// than that over the band (a million rows of n, k) has its breakpoints thinned to every
/// k-th, so that a piece spans k rows. `f` then has k − 1 kinks inside a piece, and the
/// rule's error there is of second order in the piece's width: at 1,024 pieces over a
/// 6 µm band a piece is about 6 nm wide, far finer than any feature of a solid's optical
/// constants in the thermal infrared. Cost is then bounded by the band, not the table
/// (a rough surface's band table evaluates each node at 1,801 angles).
const MAX_PIECES: usize = 1024;

/// [`gauss_legendre`]`(NODES_PER_PIECE)`, made once: a spectral material's band tables
/// average each angle's column over each sub-band (the tolerance pilot's full grid is 108
/// sub-bands), and finding the rule's nodes by Newton's method took most of that.
fn rule() -> &'static [(f64, f64)] {
    static RULE: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    RULE.get_or_init(|| gauss_legendre(NODES_PER_PIECE))
}

/// One node: its wavelength, µm, and its weight `w · S(λ) · B_λ(λ, T)`, scaled so the
/// largest is 1 (only ratios of sums of weights mean anything).
pub(crate) struct Node {
    pub(crate) wavelength_um: f64,
    pub(crate) weight: f64,
}

/// `breaks` (sorted, the band's limits first and last) with at most [`MAX_PIECES`]
/// pieces between them: every k-th kept, and the last. A list that fits is returned as it
/// is, so that tables of a few thousand rows keep their rule bit for bit.
fn thinned(breaks: Vec<f64>) -> Vec<f64> {
    let pieces: usize = breaks
        .windows(2)
        .map(|w| ((w[1] - w[0]) / MAX_PIECE_UM).ceil().max(1.0) as usize)
        .sum();
    if pieces <= MAX_PIECES {
        return breaks;
    }
    // The 0.25 µm split adds at most one piece per 0.25 µm of the band's span.
    let span_pieces = breaks
        .last()
        .zip(breaks.first())
        .map_or(0, |(hi, lo)| ((hi - lo) / MAX_PIECE_UM).ceil() as usize);
    let budget = MAX_PIECES.saturating_sub(span_pieces).max(1);
    let step = (breaks.len() - 1).div_ceil(budget);
    let last = breaks.len() - 1;
    (0..breaks.len())
        .filter(|&i| i % step == 0 || i == last)
        .map(|i| breaks[i])
        .collect()
}

/// The nodes of the average over `band` at `temperature_k`, on every piece between the
/// band's limits (cut to the response's support), the `samples_um` of `f` and the
/// response's own wavelengths; nodes where the response is 0 are left out. `covers` is
/// called with the support `[lo, hi]`, µm, before any work: the caller refuses samples
/// that do not reach it (nothing is extrapolated).
///
/// Planck's law is taken in logarithms, so no temperature underflows every weight to 0.
///
/// # Errors
/// [`RadiometryErrorKind::InvalidTemperature`] unless `temperature_k` is within
/// [`irsig_model::limits::PLANCK_WEIGHTING_K`];
/// [`RadiometryErrorKind::InvalidResponse`] when the response is zero throughout the band
/// or the weights are; what `covers` returns.
pub(crate) fn nodes(
    band: &Band,
    temperature_k: f64,
    samples_um: &[f64],
    covers: impl FnOnce(f64, f64) -> Result<(), RadiometryError>,
) -> Result<Vec<Node>, RadiometryError> {
    let [t_min, t_max] = irsig_model::limits::PLANCK_WEIGHTING_K;
    if !(t_min..=t_max).contains(&temperature_k) {
        return Err(RadiometryError::new(
            RadiometryErrorKind::InvalidTemperature,
            format!(
                "the Planck weighting temperature must be from {t_min} to {t_max} K, found \
                 {temperature_k}"
            ),
        ));
    }
    let response = band.response();
    // Where the integrand can be non-zero: the band, cut to the response's support.
    let (mut lo, mut hi) = (band.lambda_min_um(), band.lambda_max_um());
    if let Some(srf) = response {
        let w = srf.wavelength_um();
        if let (Some(&first), Some(&last)) = (w.first(), w.last()) {
            lo = lo.max(first);
            hi = hi.min(last);
        }
    }
    if hi <= lo {
        return Err(RadiometryError::new(
            RadiometryErrorKind::InvalidResponse,
            format!(
                "the sensor response is zero everywhere inside the band {}–{} µm",
                band.lambda_min_um(),
                band.lambda_max_um()
            ),
        ));
    }
    covers(lo, hi)?;
    let inside = |&w: &f64| w > lo && w < hi;
    let mut breaks: Vec<f64> = vec![lo, hi];
    breaks.extend(samples_um.iter().copied().filter(inside));
    if let Some(srf) = response {
        breaks.extend(srf.wavelength_um().iter().copied().filter(inside));
    }
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let breaks = thinned(breaks);
    let rule = rule();
    // ln B = ln c1L − 5 ln λ − ln(e^x − 1), x = c2/(λT).
    let ln_planck = |lambda_um: f64| {
        let lambda_m = lambda_um * 1e-6;
        let x = C2_M_K / (lambda_m * temperature_k);
        let ln_expm1 = if x > 30.0 {
            x + (-(-x).exp()).ln_1p()
        } else {
            x.exp_m1().ln()
        };
        C1L_W_M2_SR.ln() - 5.0 * lambda_m.ln() - ln_expm1
    };
    let mut raw: Vec<(f64, f64, f64)> = Vec::new(); // (ln B, λ, quadrature weight · S)
    for pair in breaks.windows(2) {
        let &[a, b] = pair else { continue };
        let pieces = ((b - a) / MAX_PIECE_UM).ceil().max(1.0);
        let h = (b - a) / pieces;
        for p in 0..pieces as usize {
            let start = a + h * p as f64;
            for &(t, w) in rule {
                let lambda = start + 0.5 * h * (t + 1.0);
                let s = response.map_or(1.0, |r| r.at(lambda));
                if s > 0.0 {
                    raw.push((ln_planck(lambda), lambda, 0.5 * h * w * s));
                }
            }
        }
    }
    let max_ln = raw.iter().map(|r| r.0).fold(f64::NEG_INFINITY, f64::max);
    let nodes: Vec<Node> = raw
        .into_iter()
        .map(|(ln_b, lambda, w)| Node {
            wavelength_um: lambda,
            weight: w * (ln_b - max_ln).exp(),
        })
        .collect();
    let total: f64 = nodes.iter().map(|n| n.weight).sum();
    if total.is_nan() || total <= 0.0 {
        return Err(RadiometryError::new(
            RadiometryErrorKind::InvalidResponse,
            "the Planck and response weights are zero across the band",
        ));
    }
    Ok(nodes)
}
