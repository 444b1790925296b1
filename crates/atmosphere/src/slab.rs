//! **Slab tables** (a named model): the view path from an observer to a point
//! above the ground taken from LOWTRAN7 run for that slab itself, rather than built from
//! paths that end at the ground or in space.
//!
//! Why: a LOWTRAN7 spectral point is a band-model average (20 cm⁻¹), and such averages do
//! not multiply along a path, so neither the difference of two paths (`L(o → t) = P(h_o) −
//! τ·P(h_t)`, the scattered sunlight's model in [`crate::scattered`]) nor the night model's
//! correction over `layered` is LOWTRAN7's slab: on a 87 m slab in hazy 3.4–4.1 µm air the
//! difference of LOWTRAN7's own terms is +21.5 % of the scattered light and −54 % of the
//! thermal path radiance (`scripts/accuracy/slab-additivity.py`, docs/accuracy.md). A
//! plan with `slabs` (`irsig_model::PlanSlabs`) runs, from each observer, slabs down to
//! target altitudes below it and up to those above it, at a few nadir or zenith angles
//! and, by day, at the sun's relative azimuths; the spectral atmosphere keeps them
//! (`SpectralAtmosphere::slabs`).
//!
//! What it does: for a band or sub-band (the response weight `w(λ)`, [`BandQuadrature`]),
//! each slab's band-mean τ, thermal path radiance and scattered sunlight, interpolated in
//! the target's altitude as a power of its distance from the observer (linear in log–log
//! between two rows; next to the observer's own row, the path of no length, τ = 1, no
//! radiance, the nearest two rows' power carried in to 0; τ through its absorptance 1 −
//! τ), by a monotone cubic in angle and, for
//! the scattered light, in azimuth from the sun (as [`crate::sunlit`] interpolates its
//! tables, but of the scattered light's logarithm). A path is taken from the slab tables when
//! its observer is one of the tables' (within half a metre: plans hold whole metres) and its
//! target and angle lie within the rows; anything else is the other models' as before
//! ([`SlabPaths::covers`]). Its error against LOWTRAN7 between rows is measured in
//! `tests/tests/slab_trace.rs` and tabled in docs/accuracy.md ("Slab tables").

use irsig_model::{SpectralAtmosphere, SpectralSlabTable};

use crate::PathTerms;
use crate::error::AtmosphereError;
use crate::spectral::BandQuadrature;
use crate::sunlit::Table;

/// How far, metres, a path's observer may be from a slab table's and still use it (the
/// plan's observers are whole metres).
pub const OBSERVER_TOLERANCE_M: f64 = 0.5;

/// Paths down to targets at most this high above the ground, metres, are the slant tables'
/// (which end at the ground, and are exact there), not the slab tables': a plan's lowest
/// slab row (`crate::plan::slab_targets_m`).
pub const GROUND_ROW_M: f64 = 2.0;

/// How far, degrees, a path's angle may lie outside a slab table's angle rows and still
/// be covered (then taken as the nearest row's): a path at a row's own angle, recomputed
/// by `acos` from its direction, lands within about 1e-8° of it, on either side.
pub const ANGLE_TOLERANCE_DEG: f64 = 1e-6;

/// The radiance, W m⁻² sr⁻¹, below which the scattered table's logarithm holds 0 (its
/// observer's own row): `exp(ln TINY)` is taken as 0.
const TINY: f64 = 1e-30;

/// One direction's band tables: `[target][angle]` (scattered: `[target][angle][azimuth]`).
#[derive(Debug, Clone, PartialEq)]
struct Side {
    transmission: Table,
    thermal: Table,
    scattered: Option<Table>,
}

impl Side {
    fn new(t: &SpectralSlabTable, q: &BandQuadrature, n: usize, azimuths: usize) -> Self {
        let table = |values: Vec<f64>, azimuths: usize| Table {
            altitude_m: t.target_m.clone(),
            angle_deg: t.angle_deg.clone(),
            values,
            azimuths,
        };
        let band = |v: &[f32], f: &dyn Fn(&[f32]) -> f64| -> Vec<f64> {
            v.chunks_exact(n).map(f).collect()
        };
        Self {
            transmission: table(band(&t.transmission, &|s| q.transmission(s)), 1),
            thermal: table(
                band(&t.path_radiance_w_m2_sr_per_unit, &|s| q.radiance(s)),
                1,
            ),
            // Held as logarithms: the aerosol's forward peak makes the scattered light fall
            // about exponentially with the angle from the sun, so the cubics in azimuth
            // and angle bend less in its logarithm (LOWTRAN7's light 150 m up to 800 m at
            // zenith 40°, 70° from the sun, between the 60° and 90° rows: +2.4 % of
            // itself interpolated as values, +0.5 % as logarithms). The observer's own row,
            // 0, is held as the logarithm of `TINY`.
            scattered: (azimuths > 0 && !t.scattered_w_m2_sr_per_unit.is_empty()).then(|| {
                let values = band(&t.scattered_w_m2_sr_per_unit, &|s| q.radiance(s));
                table(
                    values.into_iter().map(|v| v.max(TINY).ln()).collect(),
                    azimuths,
                )
            }),
        }
    }

    /// `table` at the target `target_m` (within the rows), `angle_deg` and `az`: between
    /// two rows a power of the distance `d` from the observer `observer_m` through both,
    /// `y = y₁ (d/d₁)^p`, `p = ln(y₂/y₁)/ln(d₂/d₁)` (linear in log–log), which is exact for
    /// a quantity growing as any power of the path's length: linear on thin paths, as its
    /// square root in the curve of growth of strong lines. Between the observer's own row
    /// (`d = 0`, no length) and the nearest, the power of the nearest two rows carried in
    /// to 0 (the band model's growth is steepest on the shortest paths, where a line
    /// to 0 is most wrong: LOWTRAN7's 35 m slab from 650 m was 27 % above it); linear
    /// where that power is not positive or a value is not (an empty table).
    #[allow(clippy::too_many_arguments)]
    fn along(
        table: &Table,
        azimuth_deg: &[f64],
        observer_m: f64,
        target_m: f64,
        angle_deg: f64,
        az: f64,
        map: fn(f64) -> f64,
    ) -> f64 {
        let rows = &table.altitude_m;
        let (k, f) = crate::interp::locate(rows, target_m);
        let row = |i: usize| map(table.at_altitude_row(i, azimuth_deg, angle_deg, az));
        let a = row(k);
        if rows.len() < 2 || f == 0.0 {
            return a;
        }
        let b = row(k + 1);
        let d = |h: f64| (h - observer_m).abs();
        let dx = d(target_m);
        // The pair the power is taken through: this interval's, or next to the observer
        // the nearest two rows beyond it.
        let (near, far) = if d(rows[k]) == 0.0 {
            (k + 1, k + 2)
        } else if d(rows[k + 1]) == 0.0 {
            (k, k.wrapping_sub(1))
        } else {
            (k, k + 1)
        };
        let linear = irsig_model::interp::lerp(a, b, f);
        if far >= rows.len() || dx <= 0.0 {
            return linear;
        }
        let (y1, y2) = (
            if near == k { a } else { b },
            if far == k + 1 { b } else { row(far) },
        );
        let (d1, d2) = (d(rows[near]), d(rows[far]));
        if !(y1 > 0.0 && y2 > 0.0 && d1 > 0.0 && d2 > 0.0) {
            return linear;
        }
        let p = (y2 / y1).ln() / (d2 / d1).ln();
        if !(p.is_finite() && p > 0.0) {
            return linear;
        }
        y1 * (dx / d1).powf(p)
    }

    /// The angle the tables are read at when the target at `target_m` and the angle lie
    /// within the rows (the angle within [`ANGLE_TOLERANCE_DEG`] of them, taken into them);
    /// `None` otherwise.
    fn covers(&self, target_m: f64, angle_deg: f64) -> Option<f64> {
        let (h, a) = (&self.thermal.altitude_m, &self.thermal.angle_deg);
        let (lo, hi) = (a[0], a[a.len() - 1]);
        let within = (lo - ANGLE_TOLERANCE_DEG..=hi + ANGLE_TOLERANCE_DEG).contains(&angle_deg);
        ((h[0]..=h[h.len() - 1]).contains(&target_m) && within).then(|| angle_deg.clamp(lo, hi))
    }
}

/// The slab tables of one observer.
#[derive(Debug, Clone, PartialEq)]
struct Observer {
    observer_m: f64,
    down: Option<Side>,
    up: Option<Side>,
}

/// A band's (or sub-band's) slab tables: every observer's, over one response.
#[derive(Debug, Clone, PartialEq)]
pub struct SlabPaths {
    observers: Vec<Observer>,
    /// The sun's relative azimuths of the scattered tables, degrees (empty at night).
    azimuth_deg: Vec<f64>,
}

/// Where a path lies in the slab tables: which observer, which side, the target and the
/// angle (nadir down, zenith up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlabCell {
    observer: usize,
    down: bool,
    target_m: f64,
    angle_deg: f64,
}

/// Why a path is not the slab tables' (it is then the other models', as without them).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum SlabMiss {
    /// Its observer is none of the tables' (within [`OBSERVER_TOLERANCE_M`]).
    Observer,
    /// The tables hold no slab in its direction (down or up) from its observer.
    Side,
    /// Its target lies beyond the tables' target rows.
    Target,
    /// Its angle lies beyond the tables' angle rows (within [`ANGLE_TOLERANCE_DEG`]).
    Angle,
}

impl SlabMiss {
    /// A few words for a warning.
    #[must_use]
    pub const fn describe(self) -> &'static str {
        match self {
            Self::Observer => "the observer is none of the tables'",
            Self::Side => "the tables hold no slab in that direction",
            Self::Target => "the target lies beyond the target rows",
            Self::Angle => "the angle lies beyond the angle rows",
        }
    }
}

impl SlabPaths {
    /// The slab tables of `spectral` over the band `[lo_um, hi_um]` with response
    /// `weight(λ in µm)`; `None` when it has none.
    ///
    /// # Errors
    /// An atmosphere that fails validation, or a band [`BandQuadrature::new`] refuses.
    pub fn new(
        spectral: &SpectralAtmosphere,
        lo_um: f64,
        hi_um: f64,
        weight: impl Fn(f64) -> f64,
    ) -> Result<Option<Self>, AtmosphereError> {
        if spectral.slabs.is_empty() {
            return Ok(None);
        }
        spectral.validate()?;
        let n = spectral.grid.points.len();
        let q = BandQuadrature::new(&spectral.grid, lo_um, hi_um, weight)?;
        let azimuth_deg = spectral
            .solar
            .as_ref()
            .map_or_else(Vec::new, |s| s.relative_azimuth_deg.clone());
        let observers = spectral
            .slabs
            .iter()
            .map(|s| Observer {
                observer_m: s.observer_m,
                down: s
                    .down
                    .as_ref()
                    .map(|t| Side::new(t, &q, n, azimuth_deg.len())),
                up: s
                    .up
                    .as_ref()
                    .map(|t| Side::new(t, &q, n, azimuth_deg.len())),
            })
            .collect();
        Ok(Some(Self {
            observers,
            azimuth_deg,
        }))
    }

    /// The cell of the path from `observer_m` to `target_m`, `range_m` long (straight: the
    /// angle at the observer is `acos(|Δh|/range)`), when the slab tables cover it: its
    /// observer within [`OBSERVER_TOLERANCE_M`] of a table's, its target and angle within
    /// that table's rows. `None`: the path is the other models'.
    #[must_use]
    pub fn covers(&self, observer_m: f64, target_m: f64, range_m: f64) -> Option<SlabCell> {
        let dh = (target_m - observer_m).abs();
        if !(range_m > 0.0 && range_m.is_finite()) {
            return None;
        }
        self.covers_along(observer_m, target_m, dh / range_m)
    }

    /// [`SlabPaths::covers`] for a line of sight whose cosine with the vertical is
    /// `cos_angle` (`|dir_z|` of a unit direction).
    #[must_use]
    pub fn covers_along(&self, observer_m: f64, target_m: f64, cos_angle: f64) -> Option<SlabCell> {
        self.locate(observer_m, target_m, cos_angle).ok()
    }

    /// Why the tables do not cover the line of sight [`SlabPaths::covers_along`] is asked
    /// about; `None` when they do, when the path ends near the ground below their rows
    /// ([`GROUND_ROW_M`]), or when it has no length or a NaN (which no model covers). What
    /// a frame counts to say how many of its paths fell back.
    #[must_use]
    pub fn why_not(&self, observer_m: f64, target_m: f64, cos_angle: f64) -> Option<SlabMiss> {
        self.locate(observer_m, target_m, cos_angle).err().flatten()
    }

    /// The cell of a line of sight, or why there is none (`None`: no fallback to count).
    fn locate(
        &self,
        observer_m: f64,
        target_m: f64,
        cos_angle: f64,
    ) -> Result<SlabCell, Option<SlabMiss>> {
        let dh = target_m - observer_m;
        if !(dh.is_finite() && dh != 0.0 && cos_angle.is_finite()) {
            return Err(None);
        }
        let k = self
            .observers
            .iter()
            .position(|o| (o.observer_m - observer_m).abs() <= OBSERVER_TOLERANCE_M)
            .ok_or(Some(SlabMiss::Observer))?;
        let o = &self.observers[k];
        let down = dh < 0.0;
        let side = if down { &o.down } else { &o.up };
        let side = side.as_ref().ok_or(Some(SlabMiss::Side))?;
        // The table's observer row stands for this observer: the target is placed at the
        // same height above (or below) it.
        let target_m = o.observer_m + dh;
        let h = &side.thermal.altitude_m;
        if !(h[0]..=h[h.len() - 1]).contains(&target_m) {
            // Near the ground the path is the slant tables', by design.
            let ground = down && target_m < h[0] && target_m <= GROUND_ROW_M;
            return Err((!ground).then_some(SlabMiss::Target));
        }
        let angle_deg = cos_angle.abs().clamp(0.0, 1.0).acos().to_degrees();
        let angle_deg = side
            .covers(target_m, angle_deg)
            .ok_or(Some(SlabMiss::Angle))?;
        Ok(SlabCell {
            observer: k,
            down,
            target_m,
            angle_deg,
        })
    }

    /// The observers' altitudes, metres, in the tables' order.
    #[must_use]
    pub fn observers_m(&self) -> Vec<f64> {
        self.observers.iter().map(|o| o.observer_m).collect()
    }

    fn side(&self, c: &SlabCell) -> (&Side, f64) {
        let o = &self.observers[c.observer];
        let side = if c.down { &o.down } else { &o.up };
        // A cell is only made by `covers`, for a side that exists.
        let side = side
            .as_ref()
            .unwrap_or_else(|| unreachable!("a slab cell of a missing side"));
        (side, o.observer_m)
    }

    /// The air's own path terms of the slab at `cell`: band-mean τ and thermal path
    /// radiance, W m⁻² sr⁻¹.
    #[must_use]
    pub fn terms(&self, cell: &SlabCell) -> PathTerms {
        let (s, o) = self.side(cell);
        let (h, a) = (cell.target_m, cell.angle_deg);
        // τ through its absorptance 1 − τ, which grows with the path as a radiance does.
        let absorptance = Side::along(&s.transmission, &[0.0], o, h, a, 0.0, |t| 1.0 - t);
        PathTerms {
            transmission: (1.0 - absorptance).clamp(0.0, 1.0),
            path_radiance_w_m2_sr: Side::along(&s.thermal, &[0.0], o, h, a, 0.0, |l| l).max(0.0),
        }
    }

    /// The sunlight scattered into the slab at `cell` seen `azimuth_deg` (0–180) from the
    /// sun's vertical plane, W m⁻² sr⁻¹; `None` without scattered tables (at night).
    #[must_use]
    pub fn scattered(&self, cell: &SlabCell, azimuth_deg: f64) -> Option<f64> {
        let (s, o) = self.side(cell);
        let t = s.scattered.as_ref()?;
        let (h, a) = (cell.target_m, cell.angle_deg);
        let from_log = |l: f64| {
            let v = l.exp();
            if v <= 2.0 * TINY { 0.0 } else { v }
        };
        Some(Side::along(t, &self.azimuth_deg, o, h, a, azimuth_deg, from_log).max(0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::{SpectralAxis, SpectralGrid, SpectralSlab};

    /// A grey atmosphere of two grid points whose slab from 600 m holds τ = 1 − Δh/1000·sec
    /// and L = Δh/100·sec at every point (linear in range): the tables give them back
    /// between rows, exactly in altitude and to the cubic's accuracy in angle.
    fn atmosphere() -> SpectralAtmosphere {
        let mut a = crate::builtin_spectral("us-std-1976").unwrap();
        a.grid = SpectralGrid {
            axis: SpectralAxis::WavelengthUm,
            points: vec![8.0, 12.0],
        };
        let n = 2;
        a.levels.truncate(1);
        a.level_transmission = vec![0.5; n];
        a.level_path_radiance_w_m2_sr_per_unit = vec![0.1; n];
        a.transmission_correction = None;
        a.sky_radiance_w_m2_sr_per_unit = vec![0.1; a.sky_zenith_deg.len() * n];
        a.sky_hemispheric_w_m2_sr_per_unit = None;
        a.slant = None;
        a.solar = None;
        let angles = vec![0.0, 20.0, 40.0, 60.0];
        let rows = |targets: &[f64]| {
            let mut t = Vec::new();
            let mut l = Vec::new();
            for &h in targets {
                for &z in &angles {
                    let r = (h - 600.0_f64).abs() / f64::to_radians(z).cos();
                    t.extend([(1.0 - r / 1000.0) as f32; 2]);
                    l.extend([(r / 100.0) as f32; 2]);
                }
            }
            (t, l)
        };
        let (td, ld) = rows(&[300.0, 500.0, 600.0]);
        let (tu, lu) = rows(&[600.0, 800.0]);
        a.slabs = vec![SpectralSlab {
            observer_m: 600.0,
            down: Some(SpectralSlabTable {
                target_m: vec![300.0, 500.0, 600.0],
                angle_deg: angles.clone(),
                transmission: td,
                path_radiance_w_m2_sr_per_unit: ld,
                scattered_w_m2_sr_per_unit: vec![],
            }),
            up: Some(SpectralSlabTable {
                target_m: vec![600.0, 800.0],
                angle_deg: angles.clone(),
                transmission: tu,
                path_radiance_w_m2_sr_per_unit: lu,
                scattered_w_m2_sr_per_unit: vec![],
            }),
        }];
        a.validate().unwrap();
        a
    }

    #[test]
    fn a_slab_between_rows_is_interpolated_and_outside_them_left_to_the_other_models() {
        let a = atmosphere();
        let s = SlabPaths::new(&a, 8.0, 12.0, |_| 1.0).unwrap().unwrap();
        // 600 m down to 400 m at nadir 0: Δh 200 m, between the 300 and 500 m rows.
        let c = s.covers(600.0, 400.0, 200.0).unwrap();
        let p = s.terms(&c);
        assert!((p.transmission - 0.8).abs() < 1e-6, "{p:?}");
        assert!((p.path_radiance_w_m2_sr - 2.0 * 4.0).abs() < 1e-5, "{p:?}");
        // Up 100 m at 20 deg (between the observer's own row and 800 m), from 0.3 m above
        // the table's observer (within the tolerance): range 100/cos 20.
        let r = 100.0 / 20_f64.to_radians().cos();
        let c = s.covers(600.3, 700.3, r).unwrap();
        let p = s.terms(&c);
        assert!((p.transmission - (1.0 - r / 1000.0)).abs() < 1e-6, "{p:?}");
        // Between angle rows the cubic follows sec θ closely: 30 deg, 100 m down.
        let r = 100.0 / 30_f64.to_radians().cos();
        let p = s.terms(&s.covers(600.0, 500.0, r).unwrap());
        let want = 4.0 * r / 100.0;
        assert!(
            (p.path_radiance_w_m2_sr / want - 1.0).abs() < 2e-3,
            "{p:?} {want}"
        );
        // Outside: another observer, below the lowest row, beyond the widest angle, no
        // length, or no side.
        assert!(s.covers(650.0, 400.0, 250.0).is_none());
        assert!(s.covers(600.0, 200.0, 400.0).is_none());
        assert!(s.covers(600.0, 500.0, 300.0).is_none());
        assert!(s.covers(600.0, 600.0, 0.0).is_none());
        assert!(s.covers(600.0, 900.0, 300.0).is_none());
        // No scattered tables at night.
        assert!(s.scattered(&c, 90.0).is_none());
        // An atmosphere without slabs has no slab paths.
        let mut none = a;
        none.slabs.clear();
        assert!(SlabPaths::new(&none, 8.0, 12.0, |_| 1.0).unwrap().is_none());
    }

    #[test]
    fn a_path_at_the_widest_angle_row_is_covered_and_read_on_that_row() {
        let a = atmosphere();
        let s = SlabPaths::new(&a, 8.0, 12.0, |_| 1.0).unwrap().unwrap();
        // 100 m down at the 60° row, its direction's cosine as a tracer has it: acos gives
        // the angle back only to a rounding, on either side of the row.
        let mut covered = 0;
        for k in -3_i32..=3 {
            let cos = 60_f64.to_radians().cos() + f64::from(k) * f64::EPSILON;
            let angle = cos.acos().to_degrees();
            assert!((angle - 60.0).abs() < ANGLE_TOLERANCE_DEG / 10.0, "{angle}");
            let c = s
                .covers_along(600.0, 500.0, cos)
                .expect("the row's own angle");
            // On the row: the range is 200 m, L = 2 per µm over the 4 µm band, τ = 0.8.
            let p = s.terms(&c);
            assert!((p.path_radiance_w_m2_sr - 8.0).abs() < 1e-5, "{p:?}");
            assert!((p.transmission - 0.8).abs() < 1e-6, "{p:?}");
            assert_eq!(s.why_not(600.0, 500.0, cos), None);
            covered += 1;
        }
        assert_eq!(covered, 7);
        // A tenth of a degree beyond it is not.
        let beyond = 60.1_f64.to_radians().cos();
        assert!(s.covers_along(600.0, 500.0, beyond).is_none());
        assert_eq!(s.why_not(600.0, 500.0, beyond), Some(SlabMiss::Angle));
    }

    #[test]
    fn a_path_the_tables_do_not_cover_is_told_why() {
        let a = atmosphere();
        let s = SlabPaths::new(&a, 8.0, 12.0, |_| 1.0).unwrap().unwrap();
        let down = 0.9;
        // 10 m above the table's observer: the tolerance is half a metre.
        assert_eq!(s.why_not(610.0, 500.0, down), Some(SlabMiss::Observer));
        assert_eq!(s.why_not(600.4, 500.0, down), None);
        // 400 m down from 600 m lies below the lowest target row, 300 m.
        assert_eq!(s.why_not(600.0, 200.0, down), Some(SlabMiss::Target));
        // Down to the ground itself is the slant tables' path, not a fallback: at and
        // below the lowest row a plan writes, but not above it.
        assert_eq!(s.why_not(600.0, GROUND_ROW_M, down), None);
        assert_eq!(s.why_not(600.0, 0.0, down), None);
        assert_eq!(
            s.why_not(600.0, GROUND_ROW_M + 0.5, down),
            Some(SlabMiss::Target)
        );
        // No length and NaN are no model's.
        assert_eq!(s.why_not(600.0, 600.0, down), None);
        assert_eq!(s.why_not(600.0, 500.0, f64::NAN), None);
        // Without an up side, a path up is told so.
        let mut no_up = a;
        no_up.slabs[0].up = None;
        let s = SlabPaths::new(&no_up, 8.0, 12.0, |_| 1.0).unwrap().unwrap();
        assert_eq!(s.why_not(600.0, 700.0, down), Some(SlabMiss::Side));
        assert_eq!(s.observers_m(), vec![600.0]);
    }
}
