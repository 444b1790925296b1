//! The `table` model: τ and L_u on observer altitude × nadir angle from slant-path runs
//! of the atmospheric model (what DIRSIG's atmospheric database does), and sky radiance on
//! observer altitude × zenith angle.
//!
//! The tables hold paths from the observer down to their lower end: the ground, or 1 m
//! above it for LOWTRAN's ([`SlantTables::ground_m`]). To serve any path, and to stay
//! continuous at the edges of the grid, the table is stored as corrections to the layered
//! model: at every grid node the ratio of the table's slant optical depth to the layered
//! model's over the same path, and the same for path radiance. A path's layered terms are
//! then scaled by the ratios interpolated bilinearly at (upper end's altitude, angle),
//! clamped to the grid. On the grid and for a target at the tables' lower end this returns
//! the table exactly (a target on the ground then gets the last metre of air as well);
//! between nodes it interpolates the (smooth) model error rather than the (steep)
//! quantity itself; outside the grid (beyond the last angle, above the top altitude, or a
//! path to a target above the ground) it is the layered model with the nearest correction.

use std::sync::OnceLock;

use irsig_model::{Atmosphere, SlantTables};

use crate::PathTerms;
use crate::error::{AtmosphereError, AtmosphereErrorKind};
use crate::interp::Cell;
use crate::layered::{Profile, Slant, Walk};

/// A slant path located in a table's grids ([`Table::walk`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TableWalk {
    layered: Walk,
    cell: Cell,
    /// How much of the correction holds past the table's last angle (`None`: all of it).
    keep: Option<f64>,
}

#[derive(Debug, Clone)]
pub(crate) struct Table {
    pub profile: Profile,
    pub slant: SlantTables,
    /// Each altitude row's corrections, made on its first use ([`Table::row`]): a path
    /// reads two rows, and the tolerance pilot's full grid builds a table per sub-band
    /// (108 at 8-14 µm) whose paths, from a few observer heights, read a handful of the
    /// rows. A row is made by the same arithmetic whenever it is made, so a path's terms
    /// do not depend on which rows were made before.
    rows: Vec<OnceLock<Corrections>>,
}

/// One altitude row of a table's corrections to the layered model, per nadir angle.
#[derive(Debug, Clone)]
struct Corrections {
    /// The table's slant optical depth over the layered model's.
    depth_ratio: Vec<f64>,
    /// The table's path radiance over the layered model's.
    radiance_ratio: Vec<f64>,
}

/// Two tables are equal when their profiles and tables are: the corrections follow from
/// them, whichever rows have been made.
impl PartialEq for Table {
    fn eq(&self, other: &Self) -> bool {
        self.profile == other.profile && self.slant == other.slant
    }
}

impl Table {
    pub(crate) fn new(atm: &Atmosphere) -> Result<Self, AtmosphereError> {
        Self::with_profile(atm, Profile::new(atm)?)
    }

    pub(crate) fn with_profile(
        atm: &Atmosphere,
        profile: Profile,
    ) -> Result<Self, AtmosphereError> {
        let slant = atm.slant.clone().ok_or(AtmosphereErrorKind::MissingTable {
            model: "table",
            table: "slant",
            instead: "slant tables come from slant-path runs of an atmospheric code (`irsig-atmos \
                      build`), not from DIRTRAN tables: use the `layered` model (eq. 8-9) or \
                      the `thesis` model (eq. 10-11) with this atmosphere",
        })?;
        let rows = (0..slant.altitude_m.len())
            .map(|_| OnceLock::new())
            .collect();
        Ok(Self {
            profile,
            slant,
            rows,
        })
    }

    /// Row `i`'s corrections (`None` past the last row), made on first use.
    fn row(&self, i: usize) -> Option<&Corrections> {
        self.rows
            .get(i)
            .map(|row| row.get_or_init(|| self.corrections(i)))
    }

    /// The corrections of altitude row `i`: at every node the ratio of the table's slant
    /// optical depth to the layered model's over the same path, and of the path radiances.
    fn corrections(&self, i: usize) -> Corrections {
        let slant = &self.slant;
        let h = slant.altitude_m[i];
        // The layered model over the table's own paths: to its lower end, not to 0 m. (Taken
        // to 0 m, the 2 m row's ratio was LOWTRAN's 1 m of air over the layered model's 2 m:
        // half the optical depth for every path starting near 2 m.)
        let end = slant.ground_m.unwrap_or(0.0);
        let mut dr = Vec::with_capacity(slant.nadir_deg.len());
        let mut lr = Vec::with_capacity(slant.nadir_deg.len());
        for (j, &a) in slant.nadir_deg.iter().enumerate() {
            let sec = 1.0 / a.to_radians().cos();
            // The layered optical depth as `along` scales it, so that a path through a
            // node gets the table's own value back.
            let (layered, layered_depth) = Slant::new(h, end, (h - end) * sec)
                .map_or((PathTerms::VACUUM, 0.0), |s| {
                    self.profile.along_with_depth(&self.profile.walk(&s))
                });
            let tau = slant
                .transmission
                .get(i)
                .and_then(|r| r.get(j))
                .copied()
                .unwrap_or(1.0);
            let lu = slant
                .path_radiance_w_m2_sr
                .get(i)
                .and_then(|r| r.get(j))
                .copied()
                .unwrap_or(0.0);
            dr.push(ratio(-tau.max(1e-300).ln(), layered_depth));
            lr.push(ratio(lu, layered.path_radiance_w_m2_sr));
        }
        Corrections {
            depth_ratio: dr,
            radiance_ratio: lr,
        }
    }

    pub(crate) fn path(&self, s: &Slant) -> PathTerms {
        self.along(&self.walk(s))
    }

    /// Where `s` lies in the levels and in the slant grid: the grid searches of
    /// [`Table::path`], valid for every table on the same grids (the sub-bands of one
    /// atmosphere).
    pub(crate) fn walk(&self, s: &Slant) -> TableWalk {
        let (h, a) = (s.hi(), s.angle_deg());
        let t = &self.slant;
        // Past the table's last angle the correction fades linearly to none at 90°: the
        // edge correction describes long grazing paths to the ground, not horizontal ones
        // (holding it costs 0.9 K on a 1 km horizontal path that `layered` gets to 0.4 K).
        let last = t.nadir_deg.last().copied().unwrap_or(90.0);
        let keep = (a > last && last < 90.0).then(|| ((90.0 - a) / (90.0 - last)).clamp(0.0, 1.0));
        TableWalk {
            layered: self.profile.walk(s),
            cell: Cell::locate(&t.altitude_m, &t.nadir_deg, h, a),
            keep,
        }
    }

    /// The path terms along a located path.
    pub(crate) fn along(&self, walk: &TableWalk) -> PathTerms {
        let (layered, layered_depth) = self.profile.along_with_depth(&walk.layered);
        // A monotone cubic in angle (linear, the corrections erred between rows 2.5-5°
        // apart by up to 0.6 K near the horizon), linear in altitude: LOWTRAN7's paths
        // change their slope in altitude just above each of its profile's levels (1, 2,
        // 3 km), where a cubic through the rows overshoots; the rows are dense instead
        // (docs/accuracy.md).
        let angles = &self.slant.nadir_deg;
        let mut dr = walk
            .cell
            .cubic_in_rows(angles, |k| self.row(k).map(|r| r.depth_ratio.as_slice()));
        let mut lr = walk
            .cell
            .cubic_in_rows(angles, |k| self.row(k).map(|r| r.radiance_ratio.as_slice()));
        if let Some(keep) = walk.keep {
            dr = 1.0 + keep * (dr - 1.0);
            lr = 1.0 + keep * (lr - 1.0);
        }
        let depth = layered_depth * dr;
        PathTerms {
            transmission: (-depth).exp().clamp(0.0, 1.0),
            path_radiance_w_m2_sr: (layered.path_radiance_w_m2_sr * lr).max(0.0),
        }
    }

    /// Whether `other` has the same levels and slant grid, so that a path located in one
    /// ([`Table::walk`]) is located in the other.
    pub(crate) fn shares_grids(&self, other: &Self) -> bool {
        self.profile.z_m == other.profile.z_m
            && self.slant.altitude_m == other.slant.altitude_m
            && self.slant.nadir_deg == other.slant.nadir_deg
    }

    /// Sky radiance from the sky table, clamped to it: a monotone cubic in zenith angle
    /// along each altitude row, linear between rows. (Linear in angle, the ground sky was
    /// up to 0.48 K too warm between the 5° rows: the radiance is convex in angle;
    /// docs/accuracy.md. A cubic in altitude too was 0.1 K off at 30° from 1.7 km: the sky
    /// changes its slope at 2 km, a level of LOWTRAN7's profile, and the rows are dense.)
    pub(crate) fn sky(&self, observer_m: f64, zenith_deg: f64) -> f64 {
        let t = &self.slant;
        Cell::locate(&t.sky_altitude_m, &t.sky_zenith_deg, observer_m, zenith_deg)
            .cubic_in_columns(&t.sky_zenith_deg, &t.sky_radiance_w_m2_sr)
            .max(0.0)
    }
}

/// `num / den`, or 1 where the layered value is too small for a ratio to mean anything
/// (a path of almost no air).
fn ratio(num: f64, den: f64) -> f64 {
    if den > 1e-9 && num.is_finite() {
        num / den
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rows made so far.
    fn made(t: &Table) -> usize {
        t.rows.iter().filter(|r| r.get().is_some()).count()
    }

    #[test]
    fn a_path_makes_the_two_rows_it_reads_and_the_order_of_paths_changes_no_bit() {
        let atm = crate::builtin("us-std-1976").unwrap();
        let (a, b) = (Table::new(&atm).unwrap(), Table::new(&atm).unwrap());
        assert_eq!(made(&a), 0);
        // From 5 m to the ground at 80 degrees from nadir (the quickstart's panel), and from
        // 1.5 km down to 100 m at 30 degrees.
        let low = Slant::new(5.0, 0.0, 5.0 / 80f64.to_radians().cos()).unwrap();
        let high = Slant::new(1500.0, 100.0, 1400.0 / 30f64.to_radians().cos()).unwrap();
        let first = a.path(&low);
        assert_eq!(made(&a), 2, "a path reads two rows");
        let low_first = (first, a.path(&high));
        assert_eq!(made(&a), 4);
        let high_first = (b.path(&high), b.path(&low));
        for (x, y) in [(low_first.0, high_first.1), (low_first.1, high_first.0)] {
            assert_eq!(x.transmission.to_bits(), y.transmission.to_bits());
            assert_eq!(
                x.path_radiance_w_m2_sr.to_bits(),
                y.path_radiance_w_m2_sr.to_bits()
            );
        }
        // Made or not, the rows follow from the table: the two compare equal.
        assert_eq!(a, b);
        assert_eq!(a, Table::new(&atm).unwrap());
    }
}
