//! The atmosphere data's own error along a path, K: how far the `table` model's answer can
//! be from the atmospheric model its tables were made from, by the region of the table
//! the path reads. Between rows it is the residual the rows were placed to
//! ([`InterpolationResidual`], measured at the midpoints between neighbouring rows and the
//! cells' centres when the rows were placed); past the widest nadir row, where no table
//! has rows and the model's correction fades to none at 90°, it is what that region was
//! measured to cost against LOWTRAN7 in 8–14 and 3–5 µm ([`BEYOND_WIDEST_ROW`]); from an
//! observer below [`NEAR_GROUND_TOP_M`], whose paths the rows' residual leaves out, what
//! such paths were measured to cost ([`NEAR_GROUND`]). A built-in's sky and its paths at
//! 80–88° answer by region of its tables ([`by_region`]), where the residual is one
//! number for the whole region. These are bounds of measured errors (the largest found),
//! not standard deviations.

use irsig_model::InterpolationResidual;

pub mod by_region;

pub use by_region::{
    GRAZING, GRAZING_ALTITUDE_TOPS_M, GRAZING_NADIR_TOPS_DEG, GrazingRows, RegionMeasurement, SKY,
    SKY_ALTITUDE_TOPS_M, SKY_ZENITH_TOPS_DEG, SkyRows, altitude_band, angle_band,
};

/// The nadir angle up to which a path to the ground reads the table's near rows (its
/// residual is [`InterpolationResidual::slant_k`]); beyond it, up to the widest row, the
/// grazing rows ([`InterpolationResidual::grazing_k`]).
pub const NEAR_ROWS_NADIR_DEG: f64 = 80.0;

/// How far past a row an angle may lie and still be that row's: the angle of a path is
/// recomputed from its direction by an arc cosine, which lands a row's own angle a few
/// 1e-7° off.
const ROW_TOLERANCE_DEG: f64 = 1e-6;

/// Observer altitudes of [`BEYOND_WIDEST_ROW`]'s rows, m above the ground.
pub const BEYOND_ALTITUDES_M: [f64; 6] = [5.0, 20.0, 50.0, 100.0, 300.0, 1000.0];

/// Nadir angles of [`BEYOND_WIDEST_ROW`]'s rows at each of [`BEYOND_ALTITUDES_M`],
/// degrees: past the built-ins' widest row (88°) and short of each observer's horizon
/// (89.44° from 300 m, 88.98° from 1 km).
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

/// The built-ins' measured error over one band, against LOWTRAN7 run by an ignored test of
/// `tests/tests/builtin_rows.rs`: the built-in's `table` model summed over 16 sub-bands
/// of the flat band, the largest apparent-temperature error over blackbodies of 260, 290
/// and 320 K at the path's end, in cells of `R` ([`BeyondRows`], [`NearGroundRows`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BuiltinMeasurement<R> {
    /// The wavelengths LOWTRAN7 was run over, µm: a band inside them takes this
    /// measurement.
    pub band_um: [f64; 2],
    /// By built-in ([`crate::BUILTIN_NAMES`]' order), K, absolute.
    pub rows: [(&'static str, R); 6],
    /// The largest of the built-ins' cells, cell by cell: the bound for an atmosphere that
    /// is none of them (the built-ins span LOWTRAN7's six standard models).
    pub worst: R,
}

/// The cells of the measurement among `measured` whose band holds `band_um`, for the
/// atmosphere `name` (a built-in's own, another's the worst); `None` for a band none holds.
fn cells_for<R: Copy>(
    measured: &[&BuiltinMeasurement<R>],
    name: &str,
    band_um: [f64; 2],
) -> Option<R> {
    measured
        .iter()
        .find(|m| band_um[0] >= m.band_um[0] && band_um[1] <= m.band_um[1])
        .map(|m| {
            m.rows
                .iter()
                .find(|(n, _)| *n == name)
                .map_or(m.worst, |(_, rows)| *rows)
        })
}

/// The error of the built-ins' paths to the ground past their widest row over one band:
/// measured by the ignored tests `beyond_the_widest_row` (8–14 µm) and
/// `beyond_the_widest_row_mwir` (3–5 µm), spherical Earth, refracted path
/// (docs/accuracy.md, "The last degrees to the horizon").
pub type BeyondMeasurement = BuiltinMeasurement<BeyondRows>;

/// Past the widest row in 8–14 µm (LOWTRAN7 over 710–1350 cm⁻¹).
pub const BEYOND_WIDEST_ROW_LWIR: BeyondMeasurement = BeyondMeasurement {
    band_um: [7.40, 14.09],
    rows: [
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
    ],
    worst: [
        &[0.519, 0.770, 1.893, 1.040, 0.849],
        &[0.423, 0.710, 1.367, 0.618],
        &[0.554, 1.119, 1.221, 1.037],
        &[0.139, 0.258, 0.332, 0.449, 0.681, 1.125, 2.214],
        &[0.236, 0.568, 1.060, 1.823, 3.354, 5.416],
        &[0.969, 2.196, 3.852, 5.276],
    ],
};

/// Past the widest row in 3–5 µm (LOWTRAN7 over 2000–3340 cm⁻¹), the 3–5 µm built-ins'
/// rows being those of 8–14 µm.
pub const BEYOND_WIDEST_ROW_MWIR: BeyondMeasurement = BeyondMeasurement {
    band_um: [2.994, 5.0],
    rows: [
        (
            "us-std-1976",
            [
                &[0.129, 0.177, 0.162, 0.102, 0.290],
                &[0.059, 0.121, 0.203, 0.565],
                &[0.084, 0.133, 0.238, 0.731],
                &[0.038, 0.066, 0.124, 0.204, 0.349, 0.629, 1.052],
                &[0.104, 0.242, 0.393, 0.621, 1.002, 1.441],
                &[0.226, 0.479, 0.813, 1.095],
            ],
        ),
        (
            "midlat-winter",
            [
                &[0.036, 0.154, 0.163, 0.080, 0.316],
                &[0.078, 0.011, 0.047, 0.860],
                &[0.048, 0.105, 0.261, 1.343],
                &[0.034, 0.030, 0.051, 0.196, 0.445, 1.173, 1.976],
                &[0.165, 0.400, 0.733, 1.215, 2.069, 3.146],
                &[0.469, 1.020, 1.718, 2.301],
            ],
        ),
        (
            "tropical",
            [
                &[0.099, 0.394, 0.465, 0.086, 0.680],
                &[0.082, 0.046, 0.143, 0.708],
                &[0.105, 0.137, 0.341, 0.754],
                &[0.053, 0.107, 0.208, 0.327, 0.472, 0.708, 0.901],
                &[0.123, 0.257, 0.400, 0.573, 0.788, 0.973],
                &[0.217, 0.458, 0.741, 0.976],
            ],
        ),
        (
            "midlat-summer",
            [
                &[0.028, 0.121, 0.055, 0.049, 0.343],
                &[0.034, 0.054, 0.199, 0.636],
                &[0.090, 0.148, 0.362, 0.729],
                &[0.039, 0.106, 0.198, 0.284, 0.425, 0.678, 0.858],
                &[0.102, 0.229, 0.353, 0.518, 0.723, 0.918],
                &[0.181, 0.381, 0.623, 0.816],
            ],
        ),
        (
            "subarctic-summer",
            [
                &[0.267, 0.080, 0.031, 0.183, 0.241],
                &[0.069, 0.043, 0.102, 0.561],
                &[0.154, 0.155, 0.265, 0.681],
                &[0.034, 0.084, 0.146, 0.248, 0.380, 0.654, 1.036],
                &[0.118, 0.259, 0.411, 0.635, 0.946, 1.305],
                &[0.196, 0.425, 0.702, 0.948],
            ],
        ),
        (
            "subarctic-winter",
            [
                &[0.152, 0.151, 0.421, 0.096, 0.235],
                &[0.030, 0.040, 0.092, 0.700],
                &[0.046, 0.059, 0.147, 1.082],
                &[0.006, 0.045, 0.085, 0.187, 0.364, 1.083, 1.979],
                &[0.166, 0.401, 0.760, 1.331, 2.472, 4.135],
                &[0.638, 1.473, 2.698, 3.859],
            ],
        ),
    ],
    worst: [
        &[0.267, 0.394, 0.465, 0.183, 0.680],
        &[0.082, 0.121, 0.203, 0.860],
        &[0.154, 0.155, 0.362, 1.343],
        &[0.053, 0.107, 0.208, 0.327, 0.472, 1.173, 1.979],
        &[0.166, 0.401, 0.760, 1.331, 2.472, 4.135],
        &[0.638, 1.473, 2.698, 3.859],
    ],
};

/// Every band measured past the widest row. A band inside none of them has no
/// measurement there.
pub const BEYOND_WIDEST_ROW: [&BeyondMeasurement; 2] =
    [&BEYOND_WIDEST_ROW_LWIR, &BEYOND_WIDEST_ROW_MWIR];

/// Below this observer altitude, m above the ground, the rows' residual does not answer:
/// their placing measured no midpoint from lower (`scripts/atmosphere/README.md`), where
/// LOWTRAN7's own single-precision geometry moves its answer by tenths of a kelvin
/// between neighbouring paths (docs/accuracy.md, "LOWTRAN7's own rounding near the
/// ground"). [`NEAR_GROUND`] answers there.
pub const NEAR_GROUND_TOP_M: f64 = 10.0;

/// The observers of [`NEAR_GROUND`]'s two intervals, m above the ground: between the
/// built-ins' 2 and 5 m rows (which also serves observers below 2 m, where the tables
/// hold the 2 m row), and between the 5 and 10 m rows.
pub const NEAR_GROUND_ROWS_M: [[f64; 3]; 2] = [[2.5, 3.5, 4.5], [6.0, 7.5, 9.0]];

/// The observer altitude between [`NEAR_GROUND_ROWS_M`]'s intervals, m: the built-ins'
/// 5 m row.
const NEAR_GROUND_SPLIT_M: f64 = 5.0;

/// One built-in's measured error from observers below [`NEAR_GROUND_TOP_M`]: `|model −
/// LOWTRAN7|`, K, the largest over [`NEAR_GROUND_ROWS_M`]'s observers of each interval
/// and every nadir angle halfway between two rows, `[near rows (nadir ≤ 80°), grazing
/// rows (80–88°)]`.
pub type NearGroundRows = [[f64; 2]; 2];

/// The error of the built-ins' paths to the ground from below [`NEAR_GROUND_TOP_M`] over
/// one band: measured by the ignored tests `near_the_ground` (8–14 µm) and
/// `near_the_ground_mwir` (3–5 µm) (docs/accuracy.md, "LOWTRAN7's own rounding near the
/// ground").
pub type NearGroundMeasurement = BuiltinMeasurement<NearGroundRows>;

/// From below 10 m in 8–14 µm (LOWTRAN7 over 710–1350 cm⁻¹).
pub const NEAR_GROUND_LWIR: NearGroundMeasurement = NearGroundMeasurement {
    band_um: [7.40, 14.09],
    rows: NEAR_GROUND_LWIR_ROWS,
    worst: NEAR_GROUND_LWIR_WORST,
};

/// From below 10 m in 3–5 µm (LOWTRAN7 over 2000–3340 cm⁻¹).
pub const NEAR_GROUND_MWIR: NearGroundMeasurement = NearGroundMeasurement {
    band_um: [2.994, 5.0],
    rows: NEAR_GROUND_MWIR_ROWS,
    worst: NEAR_GROUND_MWIR_WORST,
};

/// `NEAR_GROUND_LWIR`'s cells, as `near_the_ground` printed them.
const NEAR_GROUND_LWIR_ROWS: [(&str, NearGroundRows); 6] = [
    ("us-std-1976", [[0.082, 0.283], [0.043, 0.146]]),
    ("midlat-winter", [[0.113, 0.274], [0.047, 0.131]]),
    ("tropical", [[0.574, 1.696], [0.264, 0.503]]),
    ("midlat-summer", [[0.258, 0.475], [0.093, 0.399]]),
    ("subarctic-summer", [[0.176, 0.311], [0.139, 0.290]]),
    ("subarctic-winter", [[0.198, 0.597], [0.062, 0.182]]),
];
const NEAR_GROUND_LWIR_WORST: NearGroundRows = [[0.574, 1.696], [0.264, 0.503]];

/// `NEAR_GROUND_MWIR`'s cells, as `near_the_ground_mwir` printed them.
const NEAR_GROUND_MWIR_ROWS: [(&str, NearGroundRows); 6] = [
    ("us-std-1976", [[0.793, 1.208], [0.284, 0.465]]),
    ("midlat-winter", [[0.534, 0.648], [0.154, 0.163]]),
    ("tropical", [[1.273, 1.787], [0.961, 0.944]]),
    ("midlat-summer", [[1.354, 1.503], [0.353, 0.450]]),
    ("subarctic-summer", [[0.668, 0.877], [0.297, 0.397]]),
    ("subarctic-winter", [[0.767, 1.045], [0.213, 0.316]]),
];
const NEAR_GROUND_MWIR_WORST: NearGroundRows = [[1.354, 1.787], [0.961, 0.944]];

/// Every band measured from below 10 m. A band inside none of them has no measurement
/// there.
pub const NEAR_GROUND: [&NearGroundMeasurement; 2] = [&NEAR_GROUND_LWIR, &NEAR_GROUND_MWIR];

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
    /// The measured cost from below [`NEAR_GROUND_TOP_M`] (`None`: not measured for this
    /// band).
    near_ground: Option<NearGroundRows>,
    /// A built-in's sky by region (`None`: another atmosphere, or a band not measured).
    sky: Option<SkyRows>,
    /// A built-in's paths at 80–88° by region (`None`: as `sky`).
    grazing: Option<GrazingRows>,
}

impl DataError {
    /// The data error of tables that record `residual`, whose widest nadir row is
    /// `widest_row_deg`, of the atmosphere `name` over `band_um`. Past the widest row a
    /// built-in's own measurement answers; another atmosphere's, the largest any built-in
    /// was measured at (the built-ins span LOWTRAN7's six standard models); a band inside
    /// none of [`BEYOND_WIDEST_ROW`]'s has no measurement there. From below
    /// [`NEAR_GROUND_TOP_M`] the same, with [`NEAR_GROUND`]. A built-in's sky and its
    /// grazing rows answer by region ([`SKY`], [`GRAZING`]) in a band they were measured
    /// in; elsewhere the residual answers.
    #[must_use]
    pub fn new(
        residual: InterpolationResidual,
        widest_row_deg: f64,
        name: &str,
        band_um: [f64; 2],
    ) -> Self {
        let beyond = cells_for(&BEYOND_WIDEST_ROW, name, band_um);
        let near_ground = cells_for(&NEAR_GROUND, name, band_um);
        Self {
            residual,
            widest_row_deg,
            beyond,
            near_ground,
            sky: by_region::own_cells(&SKY, name, band_um),
            grazing: by_region::own_cells(&GRAZING, name, band_um),
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
    /// `altitude_m` above the ground at `nadir_deg` from nadir, K: the record of the
    /// region it reads (the grazing rows' by region, [`Self::grazing_rows_k`]); past the
    /// widest row, the measured cost there (never less than the grazing rows' at the
    /// widest row), `None` where the band was not measured past it. From below
    /// [`NEAR_GROUND_TOP_M`], never less than what such paths were measured to cost
    /// ([`NEAR_GROUND`]; past the widest row, as the grazing rows), `None` where the band
    /// was not measured there.
    #[must_use]
    pub fn ground_path_k(&self, altitude_m: f64, nadir_deg: f64) -> Option<f64> {
        let region = self.region(nadir_deg);
        let rows = match region {
            PathRegion::NearRows => Some(self.residual.slant_k),
            PathRegion::GrazingRows => Some(self.grazing_rows_k(altitude_m, nadir_deg)),
            PathRegion::BeyondWidestRow => self.beyond.map(|rows| {
                beyond_k(&rows, altitude_m, nadir_deg)
                    .max(self.grazing_rows_k(altitude_m, self.widest_row_deg))
            }),
        };
        if altitude_m >= NEAR_GROUND_TOP_M {
            return rows;
        }
        let interval = usize::from(altitude_m >= NEAR_GROUND_SPLIT_M);
        let column = usize::from(region != PathRegion::NearRows);
        let near = self.near_ground?[interval][column];
        rows.map(|k| k.max(near))
    }

    /// The data error of a path to the ground between the grazing rows (80° to the widest
    /// row) from an observer `altitude_m` above the ground at `nadir_deg`, K: a built-in's
    /// measured cell there ([`GRAZING`]; below [`NEAR_GROUND_TOP_M`] the lowest band's),
    /// else the residual's `grazing_k`.
    #[must_use]
    pub fn grazing_rows_k(&self, altitude_m: f64, nadir_deg: f64) -> f64 {
        self.grazing.map_or(self.residual.grazing_k, |cells| {
            cells[altitude_band(&GRAZING_ALTITUDE_TOPS_M, altitude_m)]
                [angle_band(&GRAZING_NADIR_TOPS_DEG, nadir_deg)]
        })
    }

    /// The data error of the sky seen from `altitude_m` above the ground at `zenith_deg`
    /// from the zenith, K: a built-in's measured cell there ([`SKY`]), else the residual's
    /// `sky_k` (the largest over every altitude and angle).
    #[must_use]
    pub fn sky_k(&self, altitude_m: f64, zenith_deg: f64) -> f64 {
        self.sky.map_or(self.residual.sky_k, |cells| {
            cells[altitude_band(&SKY_ALTITUDE_TOPS_M, altitude_m)]
                [angle_band(&SKY_ZENITH_TOPS_DEG, zenith_deg)]
        })
    }

    /// The data error of the sky over the whole hemisphere above `altitude_m`, K: the
    /// largest of [`Self::sky_k`] over every zenith angle there, what the sky a surface
    /// reflects from any direction may be off by.
    #[must_use]
    pub fn hemisphere_sky_k(&self, altitude_m: f64) -> f64 {
        self.sky.map_or(self.residual.sky_k, |cells| {
            cells[altitude_band(&SKY_ALTITUDE_TOPS_M, altitude_m)]
                .iter()
                .copied()
                .fold(0.0, f64::max)
        })
    }
}

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

    /// Each of `m.worst`'s cells is the largest of the built-ins' same cell, bit for bit;
    /// `cells` lists a measurement's cells in one order.
    fn worst_is_the_largest<R>(m: &BuiltinMeasurement<R>, cells: impl Fn(&R) -> Vec<f64>) {
        let worst = cells(&m.worst);
        for (i, &w) in worst.iter().enumerate() {
            let largest = m.rows.iter().map(|(_, r)| cells(r)[i]).fold(0.0, f64::max);
            assert_eq!(w.to_bits(), largest.to_bits(), "{:?} cell {i}", m.band_um);
        }
    }

    /// us-std-1976's cells by region in 8–14 µm: the sky's and the grazing rows'.
    fn us_std_cells() -> (SkyRows, GrazingRows) {
        let (sky, grazing) = (by_region::SKY_LWIR.rows[0], by_region::GRAZING_LWIR.rows[0]);
        assert_eq!((sky.0, grazing.0), ("us-std-1976", "us-std-1976"));
        (sky.1, grazing.1)
    }

    #[test]
    fn each_region_answers_with_its_own_residual() {
        // An atmosphere that is not a built-in has its own rows: its residual answers.
        let d = DataError::new(RESIDUAL, 88.0, "my-own", [8.0, 14.0]);
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
        for (h, z) in [(0.0, 0.0), (975.0, 45.0), (9000.0, 90.0)] {
            assert_eq!(d.sky_k(h, z).to_bits(), 0.5_f64.to_bits());
        }
        assert_eq!(d.hemisphere_sky_k(100.0).to_bits(), 0.5_f64.to_bits());
    }

    #[test]
    fn a_built_in_reads_its_sky_and_grazing_rows_by_region() {
        let d = us_std();
        let (sky, grazing) = us_std_cells();
        // Altitude bands are [previous top, top); angle bands (previous top, top], a row's
        // own angle recomputed by an arc cosine included.
        assert_eq!(d.sky_k(0.0, 0.0).to_bits(), sky[0][0].to_bits());
        assert_eq!(d.sky_k(949.9, 60.0 + 3e-7).to_bits(), sky[0][0].to_bits());
        assert_eq!(d.sky_k(950.0, 60.01).to_bits(), sky[1][1].to_bits());
        assert_eq!(d.sky_k(999.9, 89.0).to_bits(), sky[1][4].to_bits());
        assert_eq!(d.sky_k(1000.0, 89.0).to_bits(), sky[2][4].to_bits());
        assert_eq!(d.sky_k(2975.0, 84.0).to_bits(), sky[5][2].to_bits());
        // Above the table's top, and below the horizon: the last bands.
        assert_eq!(d.sky_k(12_000.0, 95.0).to_bits(), sky[6][4].to_bits());
        // The reflected sky may come from any direction: the band's largest.
        let largest = |row: &[f64; 5]| row.iter().copied().fold(0.0, f64::max);
        assert_eq!(
            d.hemisphere_sky_k(0.0).to_bits(),
            largest(&sky[0]).to_bits()
        );
        assert_eq!(
            d.hemisphere_sky_k(975.0).to_bits(),
            largest(&sky[1]).to_bits()
        );
        // The grazing rows by observer altitude and nadir angle.
        assert_eq!(d.ground_path_k(300.0, 84.0), Some(grazing[2][0]));
        assert_eq!(d.ground_path_k(300.0, 84.01), Some(grazing[2][1]));
        assert_eq!(d.ground_path_k(49.9, 81.0), Some(grazing[0][0]));
        assert_eq!(d.ground_path_k(50.0, 81.0), Some(grazing[1][0]));
        assert_eq!(d.ground_path_k(5000.0, 88.0), Some(grazing[4][1]));
        // The near rows keep the residual.
        assert_eq!(d.ground_path_k(300.0, 80.0), Some(0.05));
        // 3-5 um reads its own cells; a band measured in neither, the residual.
        let mwir = DataError::new(RESIDUAL, 88.0, "us-std-1976", [3.0, 5.0]);
        assert_eq!(
            mwir.sky_k(975.0, 30.0).to_bits(),
            by_region::SKY_MWIR.rows[0].1[1][0].to_bits()
        );
        let swir = DataError::new(RESIDUAL, 88.0, "us-std-1976", [1.0, 3.0]);
        assert_eq!(swir.sky_k(975.0, 30.0).to_bits(), 0.5_f64.to_bits());
        assert_eq!(swir.ground_path_k(300.0, 85.0), Some(0.2));
    }

    #[test]
    fn every_built_in_has_a_finite_cell_in_every_region() {
        for m in SKY {
            let names: Vec<&str> = m.rows.iter().map(|(n, _)| *n).collect();
            assert_eq!(names, crate::BUILTIN_NAMES, "{:?}", m.band_um);
            let cells = m.rows.iter().flat_map(|(_, r)| r.iter().flatten());
            assert!(cells.copied().all(|e| e.is_finite() && e >= 0.0));
        }
        for m in GRAZING {
            let names: Vec<&str> = m.rows.iter().map(|(n, _)| *n).collect();
            assert_eq!(names, crate::BUILTIN_NAMES, "{:?}", m.band_um);
            let cells = m.rows.iter().flat_map(|(_, r)| r.iter().flatten());
            assert!(cells.copied().all(|e| e.is_finite() && e >= 0.0));
        }
        for tops in [
            &SKY_ALTITUDE_TOPS_M[..],
            &SKY_ZENITH_TOPS_DEG,
            &GRAZING_ALTITUDE_TOPS_M,
            &GRAZING_NADIR_TOPS_DEG,
        ] {
            assert!(tops.windows(2).all(|w| w[0] < w[1]), "{tops:?}");
        }
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
        // grazing rows' cell at the widest row where that is larger (from 5 m, the
        // near-ground paths' 0.146 K between 5 and 10 m).
        let (_, grazing) = us_std_cells();
        assert_eq!(
            d.ground_path_k(5.0, 88.1),
            Some(0.146_f64.max(grazing[0][1]))
        );
        assert_eq!(
            d.ground_path_k(1000.0, 88.1),
            Some(0.672_f64.max(grazing[3][1]))
        );
        // Past the last measured angle: the row's largest.
        assert_eq!(d.ground_path_k(1000.0, 88.95), Some(2.310));
        // Above 1 km: the 1 km row; below 5 m, the 5 m row (0.239 K at 89.5°), here
        // under the grazing paths' 0.283 K from between the 2 and 5 m rows.
        assert_eq!(d.ground_path_k(3000.0, 88.5), Some(1.349));
        assert_eq!(d.ground_path_k(1.0, 89.5), Some(0.283));
        assert_eq!(d.ground_path_k(5.0, 89.5), Some(0.239));
    }

    #[test]
    fn another_atmosphere_takes_the_largest_any_built_in_was_measured_at() {
        for m in BEYOND_WIDEST_ROW {
            worst_is_the_largest(m, |rows| {
                rows.iter().flat_map(|r| r.iter().copied()).collect()
            });
        }
        let d = DataError::new(RESIDUAL, 88.0, "my-own", [8.0, 14.0]);
        assert_eq!(d.ground_path_k(1000.0, 88.9), Some(5.276));
        let d = DataError::new(RESIDUAL, 88.0, "my-own", [3.0, 5.0]);
        assert_eq!(d.ground_path_k(1000.0, 88.9), Some(3.859));
    }

    #[test]
    fn a_band_not_measured_past_the_widest_row_has_no_number_there() {
        // 3-5 um and a part of it have their own measurement (us-std-1976 from 300 m at
        // 89°: 0.621 K in 3-5 um, 1.303 K in 8-14); 1-3 um and a band across both have none.
        let mwir = DataError::new(RESIDUAL, 88.0, "us-std-1976", [3.0, 5.0]);
        assert_eq!(mwir.ground_path_k(300.0, 89.0), Some(0.621));
        let part = DataError::new(RESIDUAL, 88.0, "us-std-1976", [3.4, 4.2]);
        assert_eq!(part.ground_path_k(300.0, 89.0), Some(0.621));
        assert_eq!(us_std().ground_path_k(300.0, 89.0), Some(1.303));
        for band in [[1.0, 3.0], [3.0, 14.0], [5.0, 8.0]] {
            let d = DataError::new(RESIDUAL, 88.0, "us-std-1976", band);
            assert_eq!(d.ground_path_k(300.0, 89.0), None, "{band:?}");
            assert_eq!(d.ground_path_k(300.0, 70.0), Some(0.05));
        }
    }

    #[test]
    fn below_ten_metres_the_near_ground_measurement_answers() {
        let d = us_std();
        // Between the 2 and 5 m rows (and below 2 m): 0.082 K near, 0.283 K grazing;
        // between 5 and 10 m: 0.043 and 0.146 K; from 10 m the rows' residual alone.
        assert_eq!(d.ground_path_k(3.0, 40.0), Some(0.082));
        assert_eq!(d.ground_path_k(1.0, 40.0), Some(0.082));
        assert_eq!(d.ground_path_k(4.999, 85.0), Some(0.283));
        assert_eq!(d.ground_path_k(5.0, 40.0), Some(0.05));
        let (_, grazing) = us_std_cells();
        assert_eq!(
            d.ground_path_k(5.0, 85.0),
            Some(0.146_f64.max(grazing[0][1]))
        );
        assert_eq!(d.ground_path_k(9.99, 80.0), Some(0.05));
        assert_eq!(
            d.ground_path_k(9.99, 87.0),
            Some(0.146_f64.max(grazing[0][1]))
        );
        assert_eq!(d.ground_path_k(10.0, 40.0), Some(0.05));
        // Past the widest row: the larger of that measurement and the grazing rows'.
        assert_eq!(d.ground_path_k(3.0, 88.1), Some(0.283));
        assert_eq!(d.ground_path_k(3.0, 89.9), Some(0.573));
        // Another atmosphere takes the largest of the built-ins'; 3-5 um its own; a band
        // measured in neither has no number from below 10 m.
        let other = DataError::new(RESIDUAL, 88.0, "my-own", [8.0, 14.0]);
        assert_eq!(other.ground_path_k(3.0, 40.0), Some(0.574));
        let mwir = DataError::new(RESIDUAL, 88.0, "us-std-1976", [3.0, 5.0]);
        assert_eq!(mwir.ground_path_k(7.0, 40.0), Some(0.284));
        let none = DataError::new(RESIDUAL, 88.0, "us-std-1976", [1.0, 3.0]);
        assert_eq!(none.ground_path_k(7.0, 40.0), None);
        assert_eq!(none.ground_path_k(10.0, 40.0), Some(0.05));
        for m in NEAR_GROUND {
            worst_is_the_largest(m, |rows| rows.iter().flatten().copied().collect());
            let names: Vec<&str> = m.rows.iter().map(|(n, _)| *n).collect();
            assert_eq!(names, crate::BUILTIN_NAMES, "{:?}", m.band_um);
        }
    }

    #[test]
    fn every_row_has_a_number_per_angle() {
        for (name, rows) in BEYOND_WIDEST_ROW
            .iter()
            .flat_map(|m| m.rows.iter().copied().chain([("worst", m.worst)]))
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
