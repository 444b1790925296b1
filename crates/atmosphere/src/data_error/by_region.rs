//! The built-ins' error between their rows by region of their tables, measured against
//! LOWTRAN7: the sky by observer altitude and zenith angle ([`SKY`]), and the paths to the
//! ground at 80–88° by observer altitude and nadir angle ([`GRAZING`]). The residual the
//! rows were placed to ([`InterpolationResidual`]) is the largest error found over every
//! midpoint of a region, 0–10 km; most of a region errs far less, and these cells say
//! where the error lies (docs/accuracy.md, "The sky and the grazing rows by region").
//!
//! [`InterpolationResidual`]: irsig_model::InterpolationResidual

/// Upper ends of the observer-altitude bands of [`SKY`]'s cells, m above the ground, each
/// band `[previous top, top)`; the first starts at the ground, the last holds the sky
/// table's top (10 km) and anything above. The built-ins' rows lie every 50 m to 3 km, and
/// the 50 m just below each kilometre (a level of LOWTRAN7's profiles) is a band of its
/// own: an observer there sees LOWTRAN7's answer drop steeply over the last metres below
/// the level (docs/accuracy.md, "The sky and the grazing rows by region"), which the rows
/// around it do not follow.
pub const SKY_ALTITUDE_TOPS_M: [f64; 7] = [950.0, 1000.0, 1950.0, 2000.0, 2950.0, 3000.0, 10_000.0];

/// Upper ends of the zenith-angle bands of [`SKY`]'s cells, degrees, each band
/// `(previous top, top]`; the first starts at the zenith.
pub const SKY_ZENITH_TOPS_DEG: [f64; 5] = [60.0, 80.0, 85.0, 88.0, 90.0];

/// Upper ends of the observer-altitude bands of [`GRAZING`]'s cells, m above the ground,
/// each band `[previous top, top)`; the first starts at [`NEAR_GROUND_TOP_M`](super::NEAR_GROUND_TOP_M), the last
/// holds the slant table's top (3 km) and anything above. (The slant rows were placed by
/// error, and show no step below the kilometres as the sky's rows do.)
pub const GRAZING_ALTITUDE_TOPS_M: [f64; 5] = [50.0, 200.0, 1000.0, 2000.0, 3000.0];

/// Upper ends of the nadir-angle bands of [`GRAZING`]'s cells, degrees, each band
/// `(previous top, top]`; the first starts at [`NEAR_ROWS_NADIR_DEG`](super::NEAR_ROWS_NADIR_DEG), the last ends at
/// the widest row (88°).
pub const GRAZING_NADIR_TOPS_DEG: [f64; 2] = [84.0, 88.0];

/// The band of `tops` (upper ends, as [`SKY_ALTITUDE_TOPS_M`]) an altitude `altitude_m`
/// lies in: `[previous top, top)`, the last band holding its top and anything above.
#[must_use]
pub fn altitude_band(tops: &[f64], altitude_m: f64) -> usize {
    tops.iter()
        .position(|&t| altitude_m < t)
        .unwrap_or(tops.len() - 1)
}

/// The band of `tops` (upper ends, as [`SKY_ZENITH_TOPS_DEG`]) an angle `angle_deg` lies
/// in: `(previous top, top]`, the last band holding anything past it.
#[must_use]
pub fn angle_band(tops: &[f64], angle_deg: f64) -> usize {
    tops.iter()
        .position(|&t| angle_deg <= t + super::ROW_TOLERANCE_DEG)
        .unwrap_or(tops.len() - 1)
}

/// One built-in's measured sky error: `|model − LOWTRAN7|`, K, the largest over the
/// paths halfway between rows of each cell of [`SKY_ALTITUDE_TOPS_M`] ×
/// [`SKY_ZENITH_TOPS_DEG`].
pub type SkyRows = [[f64; 5]; 7];

/// One built-in's measured error of its paths to the ground at 80–88°: `|model −
/// LOWTRAN7|`, K, the largest over the paths halfway between rows of each cell of
/// [`GRAZING_ALTITUDE_TOPS_M`] × [`GRAZING_NADIR_TOPS_DEG`], over blackbodies of 260, 290
/// and 320 K at the path's end.
pub type GrazingRows = [[f64; 2]; 5];

/// The built-ins' error between their rows over one band, by region, against LOWTRAN7 run
/// by the ignored tests `by_region` (8–14 µm) and `by_region_mwir` (3–5 µm) of
/// `tests/tests/builtin_rows.rs`: each built-in's `table` model summed over 16 sub-bands of
/// the flat band, at every path the rows' placing probed (`scripts/atmosphere/regen.py`:
/// every altitude midpoint at every angle row and angle midpoint, every altitude row at
/// every angle midpoint). An atmosphere that is not a built-in has other rows, and its own
/// residual answers for it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegionMeasurement<R> {
    /// The wavelengths LOWTRAN7 was run over, µm: a band inside them takes this
    /// measurement.
    pub band_um: [f64; 2],
    /// By built-in ([`crate::BUILTIN_NAMES`]' order), K, absolute.
    pub rows: [(&'static str, R); 6],
}

/// The built-in `name`'s cells of the measurement among `measured` whose band holds
/// `band_um`; `None` for another atmosphere or a band none holds.
pub(super) fn own_cells<R: Copy>(
    measured: &[&RegionMeasurement<R>],
    name: &str,
    band_um: [f64; 2],
) -> Option<R> {
    measured
        .iter()
        .find(|m| band_um[0] >= m.band_um[0] && band_um[1] <= m.band_um[1])
        .and_then(|m| m.rows.iter().find(|(n, _)| *n == name).map(|(_, r)| *r))
}

/// The sky in 8–14 µm (LOWTRAN7 over 710–1350 cm⁻¹).
pub const SKY_LWIR: RegionMeasurement<SkyRows> = RegionMeasurement {
    band_um: [7.40, 14.09],
    rows: SKY_LWIR_ROWS,
};

/// The sky in 3–5 µm (LOWTRAN7 over 2000–3340 cm⁻¹).
pub const SKY_MWIR: RegionMeasurement<SkyRows> = RegionMeasurement {
    band_um: [2.994, 5.0],
    rows: SKY_MWIR_ROWS,
};

/// Every band the sky was measured in by region.
pub const SKY: [&RegionMeasurement<SkyRows>; 2] = [&SKY_LWIR, &SKY_MWIR];

/// The paths at 80–88° in 8–14 µm.
pub const GRAZING_LWIR: RegionMeasurement<GrazingRows> = RegionMeasurement {
    band_um: [7.40, 14.09],
    rows: GRAZING_LWIR_ROWS,
};

/// The paths at 80–88° in 3–5 µm.
pub const GRAZING_MWIR: RegionMeasurement<GrazingRows> = RegionMeasurement {
    band_um: [2.994, 5.0],
    rows: GRAZING_MWIR_ROWS,
};

/// Every band the paths at 80–88° were measured in by region.
pub const GRAZING: [&RegionMeasurement<GrazingRows>; 2] = [&GRAZING_LWIR, &GRAZING_MWIR];

// The cells as `by_region` and `by_region_mwir` printed them, each rounded up to 1 mK.
const SKY_LWIR_ROWS: [(&str, SkyRows); 6] = [
    (
        "us-std-1976",
        [
            [0.033, 0.042, 0.036, 0.043, 0.060],
            [0.052, 0.065, 0.098, 0.119, 0.522],
            [0.023, 0.028, 0.034, 0.053, 0.052],
            [0.052, 0.058, 0.068, 0.115, 0.421],
            [0.017, 0.017, 0.022, 0.021, 0.134],
            [0.038, 0.044, 0.057, 0.078, 0.309],
            [0.312, 0.333, 0.354, 0.384, 0.501],
        ],
    ),
    (
        "midlat-winter",
        [
            [0.019, 0.020, 0.067, 0.020, 0.057],
            [0.026, 0.031, 0.053, 0.048, 0.211],
            [0.018, 0.014, 0.060, 0.015, 0.070],
            [0.023, 0.035, 0.044, 0.054, 0.169],
            [0.016, 0.021, 0.050, 0.018, 0.187],
            [0.038, 0.049, 0.057, 0.086, 0.290],
            [0.349, 0.405, 0.466, 0.590, 0.761],
        ],
    ),
    (
        "tropical",
        [
            [0.044, 0.050, 0.040, 0.065, 0.097],
            [0.054, 0.075, 0.097, 0.183, 0.926],
            [0.041, 0.036, 0.047, 0.049, 0.058],
            [0.039, 0.038, 0.058, 0.088, 0.536],
            [0.035, 0.035, 0.034, 0.055, 0.134],
            [0.052, 0.051, 0.067, 0.098, 0.551],
            [0.394, 0.392, 0.408, 0.469, 0.773],
        ],
    ),
    (
        "midlat-summer",
        [
            [0.038, 0.040, 0.040, 0.034, 0.053],
            [0.054, 0.039, 0.058, 0.092, 0.604],
            [0.034, 0.050, 0.037, 0.039, 0.073],
            [0.054, 0.049, 0.059, 0.088, 0.599],
            [0.026, 0.040, 0.035, 0.035, 0.099],
            [0.045, 0.058, 0.087, 0.113, 0.374],
            [0.333, 0.340, 0.356, 0.387, 0.560],
        ],
    ),
    (
        "subarctic-summer",
        [
            [0.036, 0.036, 0.042, 0.030, 0.061],
            [0.045, 0.047, 0.065, 0.094, 0.585],
            [0.029, 0.035, 0.033, 0.034, 0.073],
            [0.032, 0.049, 0.070, 0.083, 0.448],
            [0.025, 0.021, 0.032, 0.028, 0.063],
            [0.037, 0.040, 0.042, 0.062, 0.312],
            [0.447, 0.534, 0.624, 0.793, 1.075],
        ],
    ),
    (
        "subarctic-winter",
        [
            [0.015, 0.028, 0.050, 0.029, 0.070],
            [0.025, 0.031, 0.046, 0.061, 0.177],
            [0.014, 0.025, 0.046, 0.033, 0.122],
            [0.026, 0.030, 0.035, 0.049, 0.131],
            [0.015, 0.028, 0.041, 0.029, 0.160],
            [0.031, 0.043, 0.045, 0.064, 0.218],
            [0.310, 0.317, 0.353, 0.414, 0.631],
        ],
    ),
];

const SKY_MWIR_ROWS: [(&str, SkyRows); 6] = [
    (
        "us-std-1976",
        [
            [0.018, 0.018, 0.022, 0.022, 0.060],
            [0.350, 0.365, 0.392, 0.455, 0.810],
            [0.016, 0.024, 0.022, 0.023, 0.057],
            [0.352, 0.353, 0.362, 0.408, 0.750],
            [0.019, 0.016, 0.025, 0.028, 0.054],
            [0.364, 0.371, 0.384, 0.403, 0.645],
            [0.866, 0.885, 0.910, 0.967, 1.135],
        ],
    ),
    (
        "midlat-winter",
        [
            [0.010, 0.015, 0.017, 0.015, 0.038],
            [0.183, 0.187, 0.193, 0.218, 0.401],
            [0.012, 0.014, 0.020, 0.018, 0.031],
            [0.190, 0.195, 0.198, 0.217, 0.343],
            [0.019, 0.021, 0.024, 0.022, 0.026],
            [0.341, 0.347, 0.343, 0.362, 0.582],
            [1.186, 1.185, 1.205, 1.265, 1.376],
        ],
    ),
    (
        "tropical",
        [
            [0.025, 0.021, 0.030, 0.033, 0.059],
            [0.294, 0.327, 0.376, 0.478, 0.828],
            [0.021, 0.018, 0.018, 0.018, 0.051],
            [0.212, 0.217, 0.242, 0.295, 0.520],
            [0.026, 0.023, 0.025, 0.028, 0.030],
            [0.359, 0.349, 0.368, 0.426, 0.758],
            [0.897, 0.943, 0.985, 1.057, 1.215],
        ],
    ),
    (
        "midlat-summer",
        [
            [0.018, 0.020, 0.023, 0.028, 0.042],
            [0.229, 0.242, 0.271, 0.339, 0.592],
            [0.023, 0.018, 0.022, 0.024, 0.038],
            [0.326, 0.326, 0.362, 0.417, 0.727],
            [0.027, 0.026, 0.021, 0.024, 0.050],
            [0.325, 0.324, 0.334, 0.371, 0.642],
            [0.840, 0.878, 0.897, 0.942, 1.064],
        ],
    ),
    (
        "subarctic-summer",
        [
            [0.020, 0.017, 0.018, 0.019, 0.049],
            [0.273, 0.290, 0.320, 0.381, 0.714],
            [0.019, 0.036, 0.027, 0.031, 0.049],
            [0.278, 0.293, 0.300, 0.345, 0.656],
            [0.016, 0.018, 0.023, 0.023, 0.049],
            [0.294, 0.298, 0.310, 0.340, 0.589],
            [1.460, 1.471, 1.507, 1.613, 1.822],
        ],
    ),
    (
        "subarctic-winter",
        [
            [0.012, 0.011, 0.015, 0.012, 0.040],
            [0.181, 0.184, 0.188, 0.207, 0.356],
            [0.012, 0.012, 0.019, 0.010, 0.028],
            [0.180, 0.182, 0.181, 0.192, 0.301],
            [0.015, 0.015, 0.021, 0.016, 0.031],
            [0.292, 0.299, 0.298, 0.304, 0.448],
            [0.558, 0.558, 0.564, 0.590, 0.907],
        ],
    ),
];

const GRAZING_LWIR_ROWS: [(&str, GrazingRows); 6] = [
    (
        "us-std-1976",
        [
            [0.068, 0.094],
            [0.052, 0.090],
            [0.044, 0.065],
            [0.032, 0.125],
            [0.023, 0.201],
        ],
    ),
    (
        "midlat-winter",
        [
            [0.073, 0.120],
            [0.031, 0.050],
            [0.037, 0.063],
            [0.019, 0.113],
            [0.012, 0.260],
        ],
    ),
    (
        "tropical",
        [
            [0.183, 0.254],
            [0.124, 0.281],
            [0.070, 0.099],
            [0.053, 0.095],
            [0.027, 0.022],
        ],
    ),
    (
        "midlat-summer",
        [
            [0.277, 0.493],
            [0.107, 0.147],
            [0.054, 0.075],
            [0.033, 0.065],
            [0.037, 0.029],
        ],
    ),
    (
        "subarctic-summer",
        [
            [0.131, 0.270],
            [0.076, 0.099],
            [0.044, 0.086],
            [0.029, 0.083],
            [0.018, 0.066],
        ],
    ),
    (
        "subarctic-winter",
        [
            [0.077, 0.130],
            [0.030, 0.040],
            [0.035, 0.048],
            [0.016, 0.065],
            [0.013, 0.174],
        ],
    ),
];

const GRAZING_MWIR_ROWS: [(&str, GrazingRows); 6] = [
    (
        "us-std-1976",
        [
            [0.118, 0.113],
            [0.076, 0.069],
            [0.133, 0.161],
            [0.170, 0.214],
            [0.238, 0.267],
        ],
    ),
    (
        "midlat-winter",
        [
            [0.160, 0.299],
            [0.059, 0.081],
            [0.063, 0.081],
            [0.088, 0.117],
            [0.130, 0.146],
        ],
    ),
    (
        "tropical",
        [
            [0.239, 0.378],
            [0.095, 0.111],
            [0.132, 0.175],
            [0.183, 0.259],
            [0.173, 0.189],
        ],
    ),
    (
        "midlat-summer",
        [
            [0.277, 0.249],
            [0.097, 0.100],
            [0.092, 0.122],
            [0.130, 0.175],
            [0.258, 0.294],
        ],
    ),
    (
        "subarctic-summer",
        [
            [0.314, 0.409],
            [0.085, 0.115],
            [0.106, 0.144],
            [0.144, 0.185],
            [0.201, 0.224],
        ],
    ),
    (
        "subarctic-winter",
        [
            [0.098, 0.152],
            [0.058, 0.093],
            [0.031, 0.053],
            [0.072, 0.104],
            [0.109, 0.136],
        ],
    ),
];
