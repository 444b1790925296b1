//! Texture at the hit: the band radiance of a textured temperature.
//!
//! A material's statistical texture (`irsig_texture`) moves a hit's temperature off its
//! facet's by an offset that differs at every point, so its `L_T` cannot come from the
//! per-temperature tables the facets share. Each sub-band holds instead a table of
//! `L(T)` and `dL/dT` over the span of temperatures the textured facets can reach, at
//! [`STEP_K`], interpolated by the cubic Hermite polynomial through the two nodes' values
//! and slopes. Its error is `h⁴/384·max|L⁗|` (Burden & Faires, *Numerical Analysis*,
//! §3.4): with `L ∝ exp(−c₂/λT)` the relative fourth derivative is about `(c₂/λT²)⁴`,
//! which gives 10⁻⁶ of `L` at 50 K in 8–14 µm and 10⁻¹² at 300 K (tested against the
//! band's own radiance below). Untextured hits never read it.

use irsig_radiometry::BandModel;

/// The table's step, K.
pub(crate) const STEP_K: f64 = 0.25;

/// The most nodes a table may hold: a span of 16,384 K at [`STEP_K`], more than any scene's
/// temperatures (1 to 5,000 K) and their textures reach.
const MAX_NODES: usize = 1 << 16;

/// `L(T)` and `dL/dT` of one sub-band over a span of temperatures.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BlackbodyTable {
    /// The first node's temperature, K.
    lo_k: f64,
    /// `(L, dL/dT)` at `lo_k + i·STEP_K`.
    nodes: Vec<(f64, f64)>,
}

impl BlackbodyTable {
    /// The table of `band` over `[lo_k, hi_k]` (clamped to at least 1 K, and to
    /// [`MAX_NODES`] nodes from `lo_k`).
    pub(crate) fn new<B: BandModel>(band: &B, [lo_k, hi_k]: [f64; 2]) -> Self {
        let lo_k = lo_k.max(1.0);
        let span = (hi_k - lo_k).max(0.0);
        let n = ((span / STEP_K).ceil() as usize + 2).min(MAX_NODES);
        let nodes = (0..n)
            .map(|i| band.radiance_and_derivative(lo_k + i as f64 * STEP_K))
            .collect();
        Self { lo_k, nodes }
    }

    /// `(L(T), dL/dT)` at `t_k`, held to the table's span.
    #[inline]
    pub(crate) fn at(&self, t_k: f64) -> (f64, f64) {
        let last = self.nodes.len().saturating_sub(2);
        let x = ((t_k - self.lo_k) / STEP_K).max(0.0);
        let i = (x as usize).min(last);
        let u = (x - i as f64).clamp(0.0, 1.0);
        let (Some(&(l0, d0)), Some(&(l1, d1))) = (self.nodes.get(i), self.nodes.get(i + 1)) else {
            return self.nodes.first().copied().unwrap_or((0.0, 0.0));
        };
        let (m0, m1) = (d0 * STEP_K, d1 * STEP_K);
        let (u2, u3) = (u * u, u * u * u);
        let value = (2.0 * u3 - 3.0 * u2 + 1.0) * l0
            + (u3 - 2.0 * u2 + u) * m0
            + (-2.0 * u3 + 3.0 * u2) * l1
            + (u3 - u2) * m1;
        let slope = ((6.0 * u2 - 6.0 * u) * l0
            + (3.0 * u2 - 4.0 * u + 1.0) * m0
            + (-6.0 * u2 + 6.0 * u) * l1
            + (3.0 * u2 - 2.0 * u) * m1)
            / STEP_K;
        (value, slope)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_radiometry::{Band, TotalRadiance};

    #[test]
    fn the_table_is_the_band_radiance() {
        let band = Band::new(8.0, 14.0).unwrap();
        let table = BlackbodyTable::new(&band, [40.0, 400.0]);
        let mut worst: f64 = 0.0;
        for i in 0..3600 {
            let t = 50.0 + f64::from(i) * 0.0971;
            let (l, d) = table.at(t);
            worst = worst.max((l / band.radiance(t) - 1.0).abs());
            assert!((d / band.radiance_derivative(t) - 1.0).abs() < 1e-3, "{t}");
        }
        assert!(worst < 2e-6, "{worst}");
        // σT⁴/π exactly at the nodes, and its slope 4σT³/π.
        let total = BlackbodyTable::new(&TotalRadiance, [299.0, 301.0]);
        let (l, d) = total.at(300.0);
        assert!((l / TotalRadiance.radiance(300.0) - 1.0).abs() < 1e-14);
        assert!((d / TotalRadiance.radiance_derivative(300.0) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn outside_its_span_the_table_holds_its_ends() {
        let table = BlackbodyTable::new(&TotalRadiance, [290.0, 310.0]);
        let (below, _) = table.at(-5.0);
        assert!((below / TotalRadiance.radiance(290.0) - 1.0).abs() < 1e-12);
        let (above, _) = table.at(1e9);
        assert!(above.is_finite());
        assert!(table.at(f64::NAN).0.is_finite());
        // A span of one temperature still interpolates.
        let one = BlackbodyTable::new(&TotalRadiance, [300.0, 300.0]);
        assert!((one.at(300.0).0 / TotalRadiance.radiance(300.0) - 1.0).abs() < 1e-14);
    }
}
