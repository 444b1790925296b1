//! Apparent temperatures of a whole image: a monotone table of the band's T(L), with its
//! slope at every node, gives each pixel a starting temperature within 0.1 µK over
//! 150-500 K (cubic Hermite interpolation in ln L), and a Newton step on L(T) polishes it to full
//! precision. A cold solve per pixel ([`BandModel::temperature`]) costs several Planck
//! evaluations; the table's start costs one (a linear start, a few hundredths of a kelvin
//! off, cost three).

use crate::band_model::BandModel;

/// Table nodes, uniform in ln L between the smallest and the largest radiance.
const NODES: usize = 256;
/// Newton steps allowed after the table's start before falling back to the cold solve.
const MAX_STEPS: usize = 4;

/// How far, relative, the table's answer may be from the exact solve's:
/// `|warm − exact| ≤ WARM_AGREEMENT · max(T, 1 K)`. The last Newton step leaves
/// (y/2)·(1e-8)² relative, y = hc/λkT, under 1e-12 for any y below 10⁴ (an 8 µm band at
/// 1.8 K); the tests hold the table to this bound from 3 K to 5000 K.
pub const WARM_AGREEMENT: f64 = 1e-9;

/// The smallest radiance the table answers, W m⁻² sr⁻¹; below it the cold solve does. Far
/// below every physical scene (8 K in 3–5 µm), it keeps the table away from radiances
/// whose Planck exponentials are subnormal and have lost their precision (3–5 µm at 3.9 K
/// is 5e-303), where a Newton step's stopping test says nothing of the answer's error.
pub const MIN_WARM_RADIANCE_W_M2_SR: f64 = 1e-250;

/// Whether every temperature within [`WARM_AGREEMENT`] of `t` rounds to the same `f32`
/// as `t`: `t` lies clear of the midpoints to the `f32`s either side of its own (midpoints
/// and ties are left to the exact solve).
fn rounds_as_its_neighbourhood(t: f64) -> bool {
    let r = t as f32;
    if !(t.is_finite() && r.is_finite() && r > 0.0) {
        return false;
    }
    // The f32s either side of a positive finite one are its bit pattern's neighbours.
    let (down, up) = (
        f32::from_bits(r.to_bits() - 1),
        f32::from_bits(r.to_bits() + 1),
    );
    if !up.is_finite() {
        return false;
    }
    let margin = WARM_AGREEMENT * t.abs().max(1.0);
    // Sums of two f32s and their halves are exact in f64.
    let below = 0.5 * (f64::from(down) + f64::from(r));
    let above = 0.5 * (f64::from(r) + f64::from(up));
    t - margin > below && t + margin < above
}

/// The inverse of a band's radiance over a radiance range, for many lookups.
///
/// ```
/// use irsig_radiometry::{Band, BandModel, InverseTable};
/// let band = Band::default();
/// let image = [band.radiance(250.0), band.radiance(300.0), band.radiance(330.0)];
/// let table = InverseTable::new(&band, &image);
/// for (l, t) in image.iter().zip([250.0, 300.0, 330.0]) {
///     assert!((table.temperature(*l) - t).abs() < 1e-9);
/// }
/// ```
#[derive(Debug)]
pub struct InverseTable<'a, B: ?Sized> {
    band: &'a B,
    /// ln L of node 0, and nodes per unit of ln L.
    ln_l0: f64,
    per: f64,
    /// T at each node, K.
    t: Vec<f64>,
    /// dT/d(ln L) at each node times the node spacing in ln L, K: the Hermite tangents.
    slope: Vec<f64>,
}

impl<'a, B: BandModel + ?Sized> InverseTable<'a, B> {
    /// A table spanning the finite positive radiances of `radiance_w_m2_sr` (W m⁻² sr⁻¹);
    /// others are solved cold when looked up.
    #[must_use]
    pub fn new(band: &'a B, radiance_w_m2_sr: &[f64]) -> Self {
        let (lo, hi) = radiance_w_m2_sr
            .iter()
            .filter(|l| l.is_finite() && **l > 0.0)
            .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &l| {
                (lo.min(l), hi.max(l))
            });
        if !(lo.is_finite() && hi > 0.0) {
            return Self {
                band,
                ln_l0: 0.0,
                per: 0.0,
                t: Vec::new(),
                slope: Vec::new(),
            };
        }
        let (ln_lo, ln_hi) = (lo.ln(), hi.ln());
        let span = (ln_hi - ln_lo).max(1e-9);
        let per = (NODES - 1) as f64 / span;
        let t: Vec<f64> = (0..NODES)
            .map(|i| band.temperature((ln_lo + i as f64 / per).exp()))
            .collect();
        // dT/d(ln L) = L / (dL/dT), exact at the node's temperature.
        let slope = t
            .iter()
            .map(|&t| {
                let (l, dl) = band.radiance_and_derivative(t);
                let s = l / dl / per;
                if s.is_finite() { s } else { 0.0 }
            })
            .collect();
        Self {
            band,
            ln_l0: ln_lo,
            per,
            t,
            slope,
        }
    }

    /// The apparent temperature of `radiance_w_m2_sr`, K: as [`BandModel::temperature`]
    /// to within 1e-9 K, and the same for the same radiance whichever order or thread looks
    /// it up.
    #[must_use]
    pub fn temperature(&self, radiance_w_m2_sr: f64) -> f64 {
        self.warm(radiance_w_m2_sr)
            .unwrap_or_else(|| self.band.temperature(radiance_w_m2_sr))
    }

    /// The apparent temperature of `radiance_w_m2_sr` as an image layer holds it, K: bit
    /// for bit the `f32` the exact solve ([`BandModel::temperature`]) rounds to. The table's
    /// answer is within [`WARM_AGREEMENT`] of the exact one, so where it lies farther than
    /// that from the midpoint between two `f32`s both round to the same `f32`; nearer (a few
    /// lookups in a hundred), the exact solve decides.
    #[must_use]
    pub fn temperature_f32(&self, radiance_w_m2_sr: f64) -> f32 {
        match self.warm(radiance_w_m2_sr) {
            Some(t) if rounds_as_its_neighbourhood(t) => t as f32,
            _ => self.band.temperature(radiance_w_m2_sr) as f32,
        }
    }

    /// The table's start polished by Newton steps; `None` outside the table, for what is
    /// not a finite radiance of at least [`MIN_WARM_RADIANCE_W_M2_SR`], or where the steps
    /// did not settle (then the cold solve answers).
    fn warm(&self, target: f64) -> Option<f64> {
        if target.is_nan() || target < MIN_WARM_RADIANCE_W_M2_SR {
            return None;
        }
        let x = (target.ln() - self.ln_l0) * self.per;
        if !(x >= 0.0 && x <= (self.t.len().max(1) - 1) as f64) || self.t.len() < 2 {
            return None;
        }
        let i = (x as usize).min(self.t.len() - 2);
        let f = x - i as f64;
        let (f2, f3) = (f * f, f * f * f);
        let mut t = (2.0 * f3 - 3.0 * f2 + 1.0) * self.t[i]
            + (f3 - 2.0 * f2 + f) * self.slope[i]
            + (3.0 * f2 - 2.0 * f3) * self.t[i + 1]
            + (f3 - f2) * self.slope[i + 1];
        for _ in 0..MAX_STEPS {
            let (l, dl) = self.band.radiance_and_derivative(t);
            if !(dl > 0.0 && dl.is_finite()) {
                return None;
            }
            let step = (l - target) / dl;
            t -= step;
            // Newton converges quadratically: the error left after a step is about
            // (y/2)·(step/T)² relative, y = hc/λkT (below 100 from 3 K up in 8-14 µm), so a
            // step under 1e-8 T leaves less than 1e-14 T.
            if step.abs() <= 1e-8 * t {
                return Some(t);
            }
        }
        None
    }

    /// [`Self::temperature`] of each radiance in turn, W m⁻² sr⁻¹ → K, looking up a run of
    /// equal radiances once: neighbouring pixels of one facet often share their radiance
    /// (every pixel of a uniform, grey facet seen through no atmosphere does), and the
    /// lookup is a function of the radiance alone, so the result is the same as one
    /// lookup per pixel.
    pub fn temperatures(
        &self,
        radiance_w_m2_sr: impl IntoIterator<Item = f64>,
    ) -> impl Iterator<Item = f64> {
        let mut last: Option<(u64, f64)> = None;
        radiance_w_m2_sr.into_iter().map(move |l| match last {
            Some((bits, t)) if bits == l.to_bits() => t,
            _ => {
                let t = self.temperature(l);
                last = Some((l.to_bits(), t));
                t
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Band, TotalRadiance};

    #[test]
    fn the_table_agrees_with_the_cold_solve_from_3_k_to_5000_k() {
        let band = Band::default();
        let temperatures: Vec<f64> = (0..4000).map(|i| 3.0 * 1.0019_f64.powi(i)).collect();
        assert!(*temperatures.last().unwrap() > 5000.0);
        let radiance: Vec<f64> = temperatures.iter().map(|&t| band.radiance(t)).collect();
        let table = InverseTable::new(&band, &radiance);
        for (&l, &t) in radiance.iter().zip(&temperatures) {
            let cold = band.temperature(l);
            let warm = table.temperature(l);
            assert!(
                (warm - cold).abs() <= 1e-9 * cold.max(1.0),
                "{t} K: {warm} vs {cold}"
            );
            assert!((warm - t).abs() <= 1e-6, "{t} K: {warm}");
        }
    }

    #[test]
    fn the_hermite_start_is_within_a_tenth_of_a_microkelvin_over_the_tracers_span() {
        // The span every tracer's table covers (150-500 K), at points between the nodes,
        // where interpolation is worst: one Newton step from there is full precision.
        let band = Band::default();
        let table = InverseTable::new(&band, &[band.radiance(150.0), band.radiance(500.0)]);
        let mut worst: f64 = 0.0;
        for i in 0..=3500 {
            let t = 150.0 + 0.1 * f64::from(i);
            let l = band.radiance(t);
            let x = (l.ln() - table.ln_l0) * table.per;
            let (k, f) = ((x as usize).min(NODES - 2), x.fract());
            let (f2, f3) = (f * f, f * f * f);
            let start = (2.0 * f3 - 3.0 * f2 + 1.0) * table.t[k]
                + (f3 - 2.0 * f2 + f) * table.slope[k]
                + (3.0 * f2 - 2.0 * f3) * table.t[k + 1]
                + (f3 - f2) * table.slope[k + 1];
            worst = worst.max((start - t).abs());
        }
        // 6.8e-8 K measured; a step under 1e-8 T (1.5 µK at 150 K) stops Newton after one.
        assert!(worst < 2e-7, "worst start {worst} K");
    }

    #[test]
    fn a_run_of_lookups_gives_each_radiance_its_own_temperature() {
        // Runs of one radiance, alternations, values outside the table and NaN: the same
        // bits as one lookup each.
        let band = Band::default();
        let (a, b) = (band.radiance(280.0), band.radiance(320.0));
        let image = [
            a,
            a,
            a,
            b,
            a,
            b,
            b,
            0.0,
            -0.0,
            0.0,
            f64::NAN,
            f64::NAN,
            a,
            band.radiance(900.0),
        ];
        let table = InverseTable::new(&band, &[a, b]);
        let each: Vec<u64> = image
            .iter()
            .map(|&l| table.temperature(l).to_bits())
            .collect();
        let run: Vec<u64> = table.temperatures(image).map(f64::to_bits).collect();
        assert_eq!(run, each);
        assert!((f64::from_bits(run[3]) - 320.0).abs() < 1e-9);
    }

    #[test]
    fn radiances_outside_the_table_and_odd_values_fall_back_to_the_cold_solve() {
        let band = Band::default();
        let table = InverseTable::new(&band, &[band.radiance(290.0), band.radiance(310.0)]);
        for l in [band.radiance(200.0), band.radiance(400.0), 0.0, -1.0] {
            assert!(
                (table.temperature(l) - band.temperature(l)).abs() < 1e-9,
                "{l}"
            );
        }
        assert!(table.temperature(f64::NAN).is_nan());
        // An image with nothing positive gives an empty table that still answers.
        let empty = InverseTable::new(&TotalRadiance, &[0.0, f64::NAN]);
        let l = TotalRadiance.radiance(300.0);
        assert!((empty.temperature(l) - 300.0).abs() < 1e-9);
        // One radiance: a table of one value.
        let single = InverseTable::new(&band, &[band.radiance(300.0)]);
        assert!((single.temperature(band.radiance(300.0)) - 300.0).abs() < 1e-9);
    }

    /// Radiances whose exact temperatures lie on or next to the midpoint between two
    /// neighbouring `f32`s, where rounding the table's answer could differ from rounding
    /// the exact one, and ordinary ones between 3 and 5000 K.
    fn hard_radiances(band: &impl BandModel) -> Vec<f64> {
        let mut out = Vec::new();
        for i in 0..2000 {
            let t = 3.0_f64 * 1.0037_f64.powi(i);
            let r = t as f32;
            let mid = 0.5 * (f64::from(r) + f64::from(f32::from_bits(r.to_bits() + 1)));
            for k in [-2.0, -1.0, 0.0, 1.0, 2.0] {
                out.push(band.radiance(mid * (1.0 + k * 1e-12)));
            }
            out.push(band.radiance(t));
        }
        // And radiances drawn log-uniformly over 1e-300 to 1e6 W m-2 sr-1 (a fixed LCG).
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..20_000 {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let u = (x >> 11) as f64 / (1u64 << 53) as f64;
            out.push(10f64.powf(-300.0 + 306.0 * u));
        }
        out
    }

    #[test]
    fn the_f32_is_the_exact_solves_bit_for_bit_where_rounding_is_closest() {
        let mwir = Band::new(3.0, 5.0).unwrap();
        let response = crate::SensorResponse::new(
            vec![7.5, 8.0, 10.0, 12.0, 14.5],
            vec![0.0, 0.7, 1.0, 0.6, 0.0],
        )
        .unwrap();
        let shaped = Band::lwir().with_response(&response).unwrap();
        for band in [Band::default(), mwir, shaped] {
            let radiance = hard_radiances(&band);
            let table = InverseTable::new(&band, &radiance);
            let mut decided_exactly = 0;
            for &l in &radiance {
                let exact = band.temperature(l) as f32;
                assert_eq!(
                    table.temperature_f32(l).to_bits(),
                    exact.to_bits(),
                    "{l} W m-2 sr-1: {} against the exact {exact} K",
                    table.temperature_f32(l)
                );
                if table
                    .warm(l)
                    .is_some_and(|t| !rounds_as_its_neighbourhood(t))
                {
                    decided_exactly += 1;
                }
            }
            // The midpoints themselves went to the exact solve: the guard was exercised.
            assert!(decided_exactly >= 2000, "{decided_exactly}");
        }
    }

    #[test]
    fn the_guard_leaves_a_temperature_clear_of_midpoints_to_the_table() {
        assert!(rounds_as_its_neighbourhood(300.0));
        let r = 300.0_f32;
        let mid = 0.5 * (f64::from(r) + f64::from(f32::from_bits(r.to_bits() + 1)));
        assert!(!rounds_as_its_neighbourhood(mid));
        assert!(!rounds_as_its_neighbourhood(mid - 1e-7));
        assert!(!rounds_as_its_neighbourhood(f64::NAN));
        assert!(!rounds_as_its_neighbourhood(1e300));
    }
}
