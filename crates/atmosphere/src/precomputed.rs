//! An [`AtmosphereModel`] with its sky precomputed on a grid of observer altitudes, for a
//! renderer's hot path: a sky ray costs two table lookups instead of an integration, and
//! the hemispheric sky (eq. 5, an integral) is read rather than recomputed.

use crate::scattered::ScatteredSunlight;
use crate::sky::SkyView;
use crate::slab::SlabPaths;
use crate::{AtmosphereModel, PathTerms};
use rayon::prelude::*;

/// Altitude levels of the precomputed sky, from the ground to the top.
pub const SKY_LEVELS: usize = 33;

/// An atmosphere model with its sky precomputed between the ground and a top altitude.
/// Path terms are the model's own, exact; the sky is interpolated linearly between
/// [`SKY_LEVELS`] altitudes (each a [`SkyView`], itself linear on a 0.25° grid).
#[derive(Debug, Clone)]
pub struct PrecomputedAtmosphere {
    model: AtmosphereModel,
    /// `(altitude_m, sky view, hemispheric radiance)`, altitudes increasing.
    levels: Vec<(f64, SkyView, f64)>,
    warnings: Vec<String>,
    /// By day, the sunlight scattered into its paths ([`Self::with_scattered`]).
    scattered: Option<ScatteredSunlight>,
    /// Slab tables for paths that end above the ground ([`Self::with_slabs`]).
    slabs: Option<SlabPaths>,
}

impl PrecomputedAtmosphere {
    /// Precomputes the sky of `model` at [`SKY_LEVELS`] altitudes from the ground to
    /// `max_altitude_m` (at least 1 m): the highest sensor or scene point.
    #[must_use]
    pub fn new(model: AtmosphereModel, max_altitude_m: f64) -> Self {
        Self::with_levels(model, max_altitude_m, SKY_LEVELS)
    }

    /// As [`PrecomputedAtmosphere::new`] with `levels` altitudes (at least 2). Fewer
    /// levels cost less and interpolate the sky more coarsely in altitude: the tolerance
    /// pilot's sub-band sets use few, because linear interpolation commutes with the
    /// sub-bands' sum and so changes every count's sky alike.
    #[must_use]
    pub fn with_levels(model: AtmosphereModel, max_altitude_m: f64, levels: usize) -> Self {
        let count = levels.max(2);
        let top = if max_altitude_m.is_finite() {
            max_altitude_m.max(1.0)
        } else {
            1.0
        };
        // Each level's view on its own (rayon); collected in order, so the same on any
        // thread count. The hemispheric sky is eq. 5 over these same views (level 0 is the
        // ground), each computed once.
        let views: Vec<(f64, SkyView)> = (0..count)
            .into_par_iter()
            .map(|i| {
                let h = top * i as f64 / (count - 1) as f64;
                (h, model.sky_view(h))
            })
            .collect();
        let hemispheric: Vec<_> = views
            .iter()
            .map(|(h, view)| {
                model.sky_hemispheric_from(Some(&views[0].1), (*h > 0.0).then_some(view))
            })
            .collect();
        let mut warnings = Vec::new();
        let mut levels = Vec::with_capacity(count);
        for ((h, view), hemi) in views.into_iter().zip(hemispheric) {
            if let Some(w) = hemi.warning
                && !warnings.contains(&w)
            {
                warnings.push(w);
            }
            levels.push((h, view, hemi.radiance_w_m2_sr));
        }
        Self {
            model,
            levels,
            warnings,
            scattered: None,
            slabs: None,
        }
    }

    /// This atmosphere by day: `scattered` is the sunlight its paths and sky gain, which a
    /// renderer adds to the thermal terms ([`Self::scattered`]). Nothing else changes.
    #[must_use]
    pub fn with_scattered(mut self, scattered: ScatteredSunlight) -> Self {
        self.scattered = Some(scattered);
        self
    }

    /// This atmosphere with slab tables: a path they cover ([`SlabPaths::covers`]) takes
    /// its τ and thermal path radiance from them ([`Self::path`]), and by day its
    /// scattered sunlight (the tracer asks [`Self::slabs`]).
    #[must_use]
    pub fn with_slabs(mut self, slabs: SlabPaths) -> Self {
        self.slabs = Some(slabs);
        self
    }

    /// The slab tables, if any.
    #[must_use]
    pub fn slabs(&self) -> Option<&SlabPaths> {
        self.slabs.as_ref()
    }

    /// The scattered sunlight, by day with scattered tables; `None` at night or without.
    #[must_use]
    pub fn scattered(&self) -> Option<&ScatteredSunlight> {
        self.scattered.as_ref()
    }

    /// The model underneath.
    #[must_use]
    pub fn model(&self) -> &AtmosphereModel {
        &self.model
    }

    /// What the model warned about while the sky was precomputed (a given hemispheric sky
    /// that disagrees with eq. 5), each once; a tool should print them.
    #[must_use]
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The two levels around `altitude_m` and the weight of the upper one.
    fn bracket(&self, altitude_m: f64) -> (usize, usize, f64) {
        let n = self.levels.len();
        let top = self.levels[n - 1].0;
        let x = (altitude_m.max(0.0) / top * (n - 1) as f64).min((n - 1) as f64);
        // x ≥ 0 (a NaN altitude is taken as 0): truncation is its floor, without a call to
        // libm's `floor`.
        let i = (x as usize).min(n - 2);
        (i, i + 1, x - i as f64)
    }

    /// The path terms: the slab tables' where they cover the path, else the model's
    /// ([`AtmosphereModel::path`]).
    #[must_use]
    pub fn path(&self, sensor_altitude_m: f64, target_altitude_m: f64, range_m: f64) -> PathTerms {
        if let Some(s) = &self.slabs
            && let Some(cell) = s.covers(sensor_altitude_m, target_altitude_m, range_m)
        {
            return s.terms(&cell);
        }
        self.model
            .path(sensor_altitude_m, target_altitude_m, range_m)
    }

    /// Sky radiance seen from `observer_altitude_m` at `zenith_deg`, W m⁻² sr⁻¹,
    /// interpolated between the two nearest levels.
    #[must_use]
    pub fn sky_radiance(&self, observer_altitude_m: f64, zenith_deg: f64) -> f64 {
        let (a, b, w) = self.bracket(observer_altitude_m);
        (1.0 - w) * self.levels[a].1.radiance(zenith_deg)
            + w * self.levels[b].1.radiance(zenith_deg)
    }

    /// The hemispheric sky radiance at `observer_altitude_m`, W m⁻² sr⁻¹ (the value
    /// [`AtmosphereModel::sky_hemispheric`] gives, interpolated between levels).
    #[must_use]
    pub fn sky_hemispheric(&self, observer_altitude_m: f64) -> f64 {
        let (a, b, w) = self.bracket(observer_altitude_m);
        (1.0 - w) * self.levels[a].2 + w * self.levels[b].2
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ModelKind, builtin};

    #[test]
    fn levels_reproduce_the_model_where_they_lie() {
        let model =
            AtmosphereModel::new(&builtin("us-std-1976").unwrap(), ModelKind::Table).unwrap();
        let p = PrecomputedAtmosphere::new(model.clone(), 3200.0);
        // 3200 m / 32 steps: a level every 100 m.
        for (h, z) in [(0.0, 0.0), (100.0, 45.0), (1000.0, 80.0), (3200.0, 30.0)] {
            let exact = model.sky_radiance(h, z);
            assert!(
                (p.sky_radiance(h, z) - exact).abs() < 1e-6 * exact.max(1.0),
                "{h} {z}"
            );
            let hemi = model.sky_hemispheric(h).radiance_w_m2_sr;
            assert!(
                (p.sky_hemispheric(h) - hemi).abs() < 1e-12 * hemi.max(1.0),
                "{h}"
            );
        }
        // Between levels: linear in altitude.
        let mid = p.sky_hemispheric(150.0);
        let expected = 0.5 * (p.sky_hemispheric(100.0) + p.sky_hemispheric(200.0));
        assert!((mid - expected).abs() < 1e-12);
        // Above the top: the top level.
        assert!((p.sky_hemispheric(1e6) - p.sky_hemispheric(3200.0)).abs() < 1e-12);
    }

    #[test]
    fn fewer_levels_lie_evenly_and_reproduce_the_model_there() {
        let model =
            AtmosphereModel::new(&builtin("us-std-1976").unwrap(), ModelKind::Table).unwrap();
        // 3200 m in 4 steps: a level every 800 m.
        let p = PrecomputedAtmosphere::with_levels(model.clone(), 3200.0, 5);
        for h in [0.0, 800.0, 1600.0, 2400.0, 3200.0] {
            let exact = model.sky_radiance(h, 60.0);
            assert!(
                (p.sky_radiance(h, 60.0) - exact).abs() < 1e-6 * exact,
                "{h}"
            );
        }
        let mid = p.sky_hemispheric(400.0);
        let expected = 0.5 * (p.sky_hemispheric(0.0) + p.sky_hemispheric(800.0));
        assert!((mid - expected).abs() < 1e-12);
        // Fewer than two levels would have no top: two.
        let two = PrecomputedAtmosphere::with_levels(model.clone(), 3200.0, 0);
        let exact = model.sky_hemispheric(3200.0).radiance_w_m2_sr;
        assert!((two.sky_hemispheric(3200.0) - exact).abs() < 1e-12 * exact);
    }

    #[test]
    fn a_non_finite_top_is_taken_as_the_ground() {
        let model =
            AtmosphereModel::new(&builtin("us-std-1976").unwrap(), ModelKind::Table).unwrap();
        let p = PrecomputedAtmosphere::new(model, f64::NAN);
        assert!(p.sky_hemispheric(0.5).is_finite());
    }
}
