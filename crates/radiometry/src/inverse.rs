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
        let target = radiance_w_m2_sr;
        let x = (target.ln() - self.ln_l0) * self.per;
        // Outside the table (or not a finite positive radiance): the cold solve.
        if !(x >= 0.0 && x <= (self.t.len().max(1) - 1) as f64) || self.t.len() < 2 {
            return self.band.temperature(target);
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
                break;
            }
            let step = (l - target) / dl;
            t -= step;
            // Newton converges quadratically: the error left after a step is about
            // (y/2)·(step/T)² relative, y = hc/λkT (below 100 from 3 K up in 8-14 µm), so a
            // step under 1e-8 T leaves less than 1e-14 T.
            if step.abs() <= 1e-8 * t {
                return t;
            }
        }
        self.band.temperature(target)
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
}
