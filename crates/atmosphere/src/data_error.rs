//! The atmosphere data's own error along a path, K: how far the `table` model's answer can
//! be from the atmospheric model its tables were made from, by the region of the table
//! the path reads. Between rows it is the residual the rows were placed to
//! ([`InterpolationResidual`], measured at the midpoints between neighbouring rows and the
//! cells' centres when the rows were placed); past the widest nadir row, where no table
//! has rows and the model's correction fades to none at 90°, it is what that region was
//! measured to cost against LOWTRAN7 ([`BEYOND_WIDEST_ROW`]). These are bounds of
//! measured errors (the largest found), not standard deviations.

use irsig_model::InterpolationResidual;

/// The nadir angle up to which a path to the ground reads the table's near rows (its
/// residual is [`InterpolationResidual::slant_k`]); beyond it, up to the widest row, the
/// grazing rows ([`InterpolationResidual::grazing_k`]).
pub const NEAR_ROWS_NADIR_DEG: f64 = 80.0;

/// How far past a row an angle may lie and still be that row's: the angle of a path is
/// recomputed from its direction by an arc cosine, which lands a row's own angle a few
/// 1e-7° off.
const ROW_TOLERANCE_DEG: f64 = 1e-6;

/// Observer altitudes of [`BEYOND_WIDEST_ROW`], m above the ground.
pub const BEYOND_ALTITUDES_M: [f64; 6] = [5.0, 20.0, 50.0, 100.0, 300.0, 1000.0];

/// Nadir angles of [`BEYOND_WIDEST_ROW`] at each of [`BEYOND_ALTITUDES_M`], degrees: past
/// the built-ins' widest row (88°) and short of each observer's horizon (89.44° from
/// 300 m, 88.98° from 1 km).
pub const BEYOND_NADIRS_DEG: [&[f64]; 6] = [
    &[88.5, 89.0, 89.5, 89.8, 89.9],
    &[88.5, 89.0, 89.5, 89.8],
    &[88.5, 89.0, 89.5, 89.7],
    &[88.25, 88.5, 88.75, 89.0, 89.25, 89.5, 89.6],
    &[88.25, 88.5, 88.75, 89.0, 89.25, 89.4],
    &[88.25, 88.5, 88.75, 88.9],
];

/// One built-in's measured error past the widest row: `|model − LOWTRAN7|`, K, at
/// [`BEYOND_ALTITUDES_M`] × [`BEYOND_NADIRS_DEG`].
pub type BeyondRows = [&'static [f64]; 6];

/// The error of the built-ins' paths to the ground past their widest row, by built-in
/// ([`crate::BUILTIN_NAMES`]' order), K, absolute. Measured by the ignored test
/// `beyond_the_widest_row` of `tests/tests/builtin_rows.rs`: LOWTRAN7 (run by the test,
/// spherical Earth, refracted path, 710–1350 cm⁻¹) against the built-in's `table` model
/// summed over 16 sub-bands of flat 8–14 µm, the largest apparent-temperature error over
/// blackbodies of 260, 290 and 320 K at the path's end (docs/accuracy.md, "The last
/// degrees to the horizon").
pub const BEYOND_WIDEST_ROW: [(&str, BeyondRows); 6] = [
    (
        "us-std-1976",
        [
            &[0.044, 0.068, 0.239, 0.573, 0.537],
            &[0.143, 0.331, 0.574, 0.261],
            &[0.265, 0.581, 0.740, 0.552],
            &[0.054, 0.143, 0.197, 0.204, 0.289, 0.888, 1.495],
            &[0.176, 0.459, 0.782, 1.303, 2.160, 3.057],
            &[0.672, 1.349, 1.984, 2.310],
        ],
    ),
    (
        "midlat-winter",
        [
            &[0.053, 0.151, 0.175, 0.299, 0.247],
            &[0.082, 0.258, 0.376, 0.132],
            &[0.127, 0.316, 0.238, 0.810],
            &[0.057, 0.035, 0.053, 0.053, 0.273, 1.125, 2.214],
            &[0.236, 0.568, 1.060, 1.823, 3.354, 5.416],
            &[0.969, 2.196, 3.852, 5.276],
        ],
    ),
    (
        "tropical",
        [
            &[0.390, 0.163, 1.893, 0.723, 0.620],
            &[0.423, 0.581, 0.879, 0.618],
            &[0.511, 0.907, 0.992, 0.868],
            &[0.110, 0.192, 0.306, 0.449, 0.590, 0.657, 0.655],
            &[0.068, 0.118, 0.197, 0.243, 0.322, 0.391],
            &[0.253, 0.543, 0.909, 1.173],
        ],
    ),
    (
        "midlat-summer",
        [
            &[0.519, 0.770, 1.009, 1.040, 0.849],
            &[0.272, 0.607, 0.935, 0.436],
            &[0.554, 1.119, 1.221, 1.037],
            &[0.139, 0.258, 0.332, 0.445, 0.681, 1.004, 1.073],
            &[0.158, 0.304, 0.385, 0.374, 0.400, 0.401],
            &[0.115, 0.273, 0.482, 0.680],
        ],
    ),
    (
        "subarctic-summer",
        [
            &[0.090, 0.134, 0.426, 0.955, 0.803],
            &[0.399, 0.710, 1.367, 0.540],
            &[0.477, 0.953, 1.199, 0.824],
            &[0.128, 0.239, 0.325, 0.326, 0.545, 1.060, 1.443],
            &[0.210, 0.495, 0.784, 1.109, 1.399, 1.440],
            &[0.349, 0.552, 0.534, 0.640],
        ],
    ),
    (
        "subarctic-winter",
        [
            &[0.067, 0.062, 0.280, 0.078, 0.162],
            &[0.010, 0.009, 0.041, 0.371],
            &[0.013, 0.026, 0.026, 0.543],
            &[0.005, 0.020, 0.040, 0.094, 0.182, 0.662, 1.244],
            &[0.102, 0.251, 0.494, 0.916, 1.855, 3.381],
            &[0.614, 1.504, 2.935, 4.430],
        ],
    ),
];

/// The band [`BEYOND_WIDEST_ROW`] was measured over, µm: a band inside LOWTRAN7's
/// 710–1350 cm⁻¹ run. Outside it nothing was measured past the widest row.
pub const BEYOND_MEASURED_BAND_UM: [f64; 2] = [7.40, 14.09];

/// The region of a slant table a path to the ground reads, by its nadir angle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathRegion {
    /// Nadir up to [`NEAR_ROWS_NADIR_DEG`]: between the near rows.
    NearRows,
    /// Past [`NEAR_ROWS_NADIR_DEG`] up to the widest row: between the grazing rows.
    GrazingRows,
    /// Past the widest row, toward the horizon: no row.
    BeyondWidestRow,
}

/// The data error of an atmosphere whose slant tables record their interpolation
/// residual: what each path's answer may be off by, K.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DataError {
    residual: InterpolationResidual,
    widest_row_deg: f64,
    /// The measured cost past the widest row (`None`: not measured for this band).
    beyond: Option<BeyondRows>,
}

impl DataError {
    /// The data error of tables that record `residual`, whose widest nadir row is
    /// `widest_row_deg`, of the atmosphere `name` over `band_um`. Past the widest row a
    /// built-in's own measurement answers; another atmosphere's, the largest any built-in
    /// was measured at (the built-ins span LOWTRAN7's six standard models); a band outside
    /// [`BEYOND_MEASURED_BAND_UM`] has no measurement there.
    #[must_use]
    pub fn new(
        residual: InterpolationResidual,
        widest_row_deg: f64,
        name: &str,
        band_um: [f64; 2],
    ) -> Self {
        let measured =
            band_um[0] >= BEYOND_MEASURED_BAND_UM[0] && band_um[1] <= BEYOND_MEASURED_BAND_UM[1];
        let beyond = measured.then(|| {
            BEYOND_WIDEST_ROW
                .iter()
                .find(|(n, _)| *n == name)
                .map_or(WORST_BEYOND, |(_, rows)| *rows)
        });
        Self {
            residual,
            widest_row_deg,
            beyond,
        }
    }

    /// The residual the tables record.
    #[must_use]
    pub fn residual(&self) -> InterpolationResidual {
        self.residual
    }

    /// The region a path to the ground `nadir_deg` from nadir reads.
    #[must_use]
    pub fn region(&self, nadir_deg: f64) -> PathRegion {
        if nadir_deg <= NEAR_ROWS_NADIR_DEG + ROW_TOLERANCE_DEG {
            PathRegion::NearRows
        } else if nadir_deg <= self.widest_row_deg + ROW_TOLERANCE_DEG {
            PathRegion::GrazingRows
        } else {
            PathRegion::BeyondWidestRow
        }
    }

    /// The data error of a path to the ground (or to a facet) from an observer
    /// `altitude_m` above the ground at `nadir_deg` from nadir, K: the residual of the
    /// region it reads; past the widest row, the measured cost there (never less than the
    /// grazing rows'), `None` where the band was not measured past it.
    #[must_use]
    pub fn ground_path_k(&self, altitude_m: f64, nadir_deg: f64) -> Option<f64> {
        match self.region(nadir_deg) {
            PathRegion::NearRows => Some(self.residual.slant_k),
            PathRegion::GrazingRows => Some(self.residual.grazing_k),
            PathRegion::BeyondWidestRow => self
                .beyond
                .map(|rows| beyond_k(&rows, altitude_m, nadir_deg).max(self.residual.grazing_k)),
        }
    }

    /// The data error of the sky from any altitude at any zenith angle, K.
    #[must_use]
    pub fn sky_k(&self) -> f64 {
        self.residual.sky_k
    }
}

/// The largest of every built-in's measurement at each cell: the bound for an atmosphere
/// that is none of them.
/// Every built-in's rows have the same cells; this is their largest, cell by cell (a test
/// checks it against [`BEYOND_WIDEST_ROW`]).
const WORST_BEYOND: BeyondRows = [
    &[0.519, 0.770, 1.893, 1.040, 0.849],
    &[0.423, 0.710, 1.367, 0.618],
    &[0.554, 1.119, 1.221, 1.037],
    &[0.139, 0.258, 0.332, 0.449, 0.681, 1.125, 2.214],
    &[0.236, 0.568, 1.060, 1.823, 3.354, 5.416],
    &[0.969, 2.196, 3.852, 5.276],
];

/// The measured error at `altitude_m` and `nadir_deg` from `rows`, interpolated so that it
/// is never below a measurement it lies between: the largest of the cells around it (the
/// altitude rows below and above it, in each the angles below and above it). Below the
/// first measured angle the first cell answers, past the last the row's largest; below
/// 5 m the 5 m row, above 1 km the 1 km row (unmeasured there: from higher the horizon
/// comes nearer the widest row and the region narrows).
fn beyond_k(rows: &BeyondRows, altitude_m: f64, nadir_deg: f64) -> f64 {
    let above = BEYOND_ALTITUDES_M
        .iter()
        .position(|&a| a >= altitude_m)
        .unwrap_or(BEYOND_ALTITUDES_M.len() - 1);
    let below = if BEYOND_ALTITUDES_M[above] > altitude_m {
        above.saturating_sub(1)
    } else {
        above
    };
    [below, above]
        .into_iter()
        .map(|k| row_k(BEYOND_NADIRS_DEG[k], rows[k], nadir_deg))
        .fold(0.0, f64::max)
}

/// One altitude row's error at `nadir_deg`: the larger of the measured angles around it.
fn row_k(nadirs: &[f64], errors: &[f64], nadir_deg: f64) -> f64 {
    match nadirs.iter().position(|&a| a >= nadir_deg) {
        Some(0) => errors.first().copied().unwrap_or(0.0),
        Some(k) => errors[k - 1].max(errors[k]),
        None => errors.iter().copied().fold(0.0, f64::max),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const RESIDUAL: InterpolationResidual = InterpolationResidual {
        slant_k: 0.05,
        grazing_k: 0.2,
        sky_k: 0.5,
    };

    fn us_std() -> DataError {
        DataError::new(RESIDUAL, 88.0, "us-std-1976", [8.0, 14.0])
    }

    #[test]
    fn each_region_answers_with_its_own_residual() {
        let d = us_std();
        assert_eq!(d.ground_path_k(300.0, 0.0), Some(0.05));
        // 80° is the near rows' last angle; an arc cosine's few 1e-7° past it too.
        assert_eq!(d.ground_path_k(300.0, 80.0), Some(0.05));
        assert_eq!(d.ground_path_k(300.0, 80.0 + 3e-7), Some(0.05));
        assert_eq!(d.region(80.001), PathRegion::GrazingRows);
        assert_eq!(d.ground_path_k(300.0, 87.99), Some(0.2));
        // The widest row is a row.
        assert_eq!(d.region(88.0), PathRegion::GrazingRows);
        assert_eq!(d.ground_path_k(300.0, 88.0), Some(0.2));
        assert_eq!(d.region(88.01), PathRegion::BeyondWidestRow);
        assert_eq!(d.sky_k().to_bits(), 0.5_f64.to_bits());
    }

    #[test]
    fn past_the_widest_row_is_never_below_a_measurement_around_it() {
        let d = us_std();
        // 5 m, 89.9°: measured 0.537 K; between 89.8° (0.573) and 89.9°; the cell itself.
        assert_eq!(d.ground_path_k(5.0, 89.9), Some(0.573));
        // 300 m at 88.6°: between 88.5° (0.459) and 88.75° (0.782).
        assert_eq!(d.ground_path_k(300.0, 88.6), Some(0.782));
        // 650 m at 88.6°: the 300 m row's 0.782 and the 1 km row's 1.984.
        assert_eq!(d.ground_path_k(650.0, 88.6), Some(1.984));
        // Just past the widest row, before the first measured angle: the first cell, or the
        // grazing rows' residual where that is larger.
        assert_eq!(d.ground_path_k(5.0, 88.1), Some(0.2));
        assert_eq!(d.ground_path_k(1000.0, 88.1), Some(0.672));
        // Past the last measured angle: the row's largest.
        assert_eq!(d.ground_path_k(1000.0, 88.95), Some(2.310));
        // Above 1 km: the 1 km row; below 5 m, the 5 m row.
        assert_eq!(d.ground_path_k(3000.0, 88.5), Some(1.349));
        assert_eq!(d.ground_path_k(1.0, 89.5), Some(0.239_f64.max(0.2)));
    }

    #[test]
    fn another_atmosphere_takes_the_largest_any_built_in_was_measured_at() {
        for (k, worst) in WORST_BEYOND.iter().enumerate() {
            for (i, &w) in worst.iter().enumerate() {
                let largest = BEYOND_WIDEST_ROW
                    .iter()
                    .map(|(_, rows)| rows[k][i])
                    .fold(0.0, f64::max);
                assert_eq!(w.to_bits(), largest.to_bits(), "row {k} cell {i}");
            }
        }
        let d = DataError::new(RESIDUAL, 88.0, "my-own", [8.0, 14.0]);
        assert_eq!(d.ground_path_k(1000.0, 88.9), Some(5.276));
    }

    #[test]
    fn a_band_not_measured_past_the_widest_row_has_no_number_there() {
        let d = DataError::new(RESIDUAL, 88.0, "us-std-1976", [3.0, 5.0]);
        assert_eq!(d.ground_path_k(300.0, 89.0), None);
        assert_eq!(d.ground_path_k(300.0, 70.0), Some(0.05));
    }

    #[test]
    fn every_row_has_a_number_per_angle() {
        for (name, rows) in BEYOND_WIDEST_ROW
            .iter()
            .chain([("worst", WORST_BEYOND)].iter())
        {
            for (k, row) in rows.iter().enumerate() {
                assert_eq!(row.len(), BEYOND_NADIRS_DEG[k].len(), "{name} row {k}");
                assert!(row.iter().all(|e| e.is_finite() && *e >= 0.0), "{name}");
            }
        }
        assert!(
            BEYOND_NADIRS_DEG
                .iter()
                .all(|r| r.windows(2).all(|w| w[0] < w[1]))
        );
    }
}
