//! [`PathTermsMode::Tabulated`]: τ and L_u of a frame's primary hits from a table.
//!
//! In one frame the sensor is fixed, so a hit's path terms depend only on the hit's
//! altitude and its range. A real atmosphere's `path` costs about 0.85 µs per call
//! (layered or table model), as much as tracing a ray through a million triangles; the
//! table costs two bilinear lookups. It spans the scene's bounding box: altitudes from
//! its bottom to its top, ranges from the sensor's nearest to its farthest corner.
//! Nodes where the range is shorter than the altitude difference (no such hit exists)
//! are evaluated at the vertical path, so the table stays continuous. Its error against
//! the exact terms, in kelvin, is measured in `tests/path_table.rs` and docs/accuracy.md
//! (worst 6.3 mK, 99th percentile under 5 mK, median under 7 µK). Building it costs
//! 129 × 513 `path` calls (about 56 ms on one core at 0.85 µs a call, rows in parallel):
//! worth it when a frame has more than about 70 000 facet hits (e.g. 280 × 280 pixels and
//! up).
//!
//! By day the sunlight scattered into a path depends on its direction from the sun as well,
//! which an altitude × range table cannot hold: the table keeps the air's own terms, and
//! the scattered light ([`Atmosphere::scattered`]) is added at each hit for the ray's
//! direction, from the table's τ, as with exact terms (`day::lit_path`).

use rayon::prelude::*;

use irsig_atmosphere::PathTerms;

use crate::env::Atmosphere;

/// How the tracer gets the path terms (τ, L_u) of a primary hit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PathTermsMode {
    /// `Atmosphere::path` for every hit (the default).
    #[default]
    Exact,
    /// An approximation: per frame, a table over the scene's altitudes × ranges
    /// ([`PATH_TABLE_ALTITUDES`] × [`PATH_TABLE_RANGES`] nodes; altitudes dense near the
    /// sensor's, where near-horizontal paths vary fastest), interpolated bilinearly.
    /// Terrain misses and secondary paths stay exact.
    Tabulated,
}

impl PathTermsMode {
    /// Both modes, in the order they are listed to users.
    pub const ALL: [Self; 2] = [Self::Exact, Self::Tabulated];
    /// Their names, in the same order.
    pub const NAMES: [&'static str; 2] = ["exact", "tabulated"];

    /// The name used in files and on command lines.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Exact => Self::NAMES[0],
            Self::Tabulated => Self::NAMES[1],
        }
    }
}

impl std::fmt::Display for PathTermsMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not a [`PathTermsMode`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown path-terms mode `{0}`: expected one of exact, tabulated")]
pub struct UnknownPathTermsMode(pub String);

impl std::str::FromStr for PathTermsMode {
    type Err = UnknownPathTermsMode;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| UnknownPathTermsMode(s.to_owned()))
    }
}

/// Altitude nodes of the path table.
pub const PATH_TABLE_ALTITUDES: usize = 129;
/// Range nodes of the path table.
pub const PATH_TABLE_RANGES: usize = 513;

/// One frame's path-term table, for every sub-band.
#[derive(Debug, Clone)]
pub(crate) struct PathTable {
    sensor_alt_m: f64,
    /// Scale of the altitude axis: nodes are uniform in asinh((alt − sensor) / h₀).
    h0_m: f64,
    u0: f64,
    per_u: f64,
    range0_m: f64,
    per_range: f64,
    /// Sub-bands.
    bands: usize,
    /// `(τ, L_u)` per node and sub-band: altitude-major, then range, then sub-band.
    nodes: Vec<(f64, f64)>,
}

/// Where a hit falls in the table: its first node and the two interpolation weights. The
/// same for every sub-band, so it is found once per hit.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cell {
    node: usize,
    fa: f64,
    fr: f64,
}

/// The node coordinates and interpolation weight of `x` on a grid starting at `x0` with
/// `per` nodes per unit, `n` nodes.
#[inline]
fn cell(x: f64, x0: f64, per: f64, n: usize) -> (usize, f64) {
    let last = (n - 1) as f64;
    let u = ((x - x0) * per).clamp(0.0, last);
    // NaN clamps to NaN, and `as usize` turns NaN into 0: a NaN input gives NaN out.
    let i = (u as usize).min(n - 2);
    (i, u - i as f64)
}

impl PathTable {
    /// Tabulates each of `atmospheres` (one per sub-band) for a sensor at `sensor_alt_m`
    /// over hits at altitudes `alt_m` and ranges `range_m` (both `[low, high]`).
    pub(crate) fn new<A: Atmosphere>(
        atmospheres: &[&A],
        sensor_alt_m: f64,
        alt_m: [f64; 2],
        range_m: [f64; 2],
    ) -> Self {
        // A flat scene or a single distance still gets two nodes 1 m apart.
        let span = |[lo, hi]: [f64; 2]| (hi - lo).max(1.0);
        let per_range = (PATH_TABLE_RANGES - 1) as f64 / span(range_m);
        // Near-horizontal paths (a hit nearly level with the sensor) change fast with
        // altitude: the slant angle swings through the models' 88-90° blend within metres.
        // So the altitude axis is uniform in u = asinh((alt − sensor) / h₀), dense near
        // the sensor's altitude and coarse far from it. With a uniform altitude grid a low
        // oblique view erred by 26 mK, one from inside the scene by 22 mK.
        let h0_m = (span(alt_m) / 1000.0).max(0.1);
        let to_u = |alt: f64| ((alt - sensor_alt_m) / h0_m).asinh();
        let (u_lo, u_hi) = (to_u(alt_m[0]), to_u(alt_m[1]));
        let per_u = (PATH_TABLE_ALTITUDES - 1) as f64 / (u_hi - u_lo).max(1e-9);
        // Rows in parallel: each node is a pure function of its coordinates, so the table
        // is the same at any thread count.
        let nodes = (0..PATH_TABLE_ALTITUDES)
            .into_par_iter()
            .flat_map_iter(|i| {
                let alt = sensor_alt_m + h0_m * (u_lo + i as f64 / per_u).sinh();
                let vertical = (sensor_alt_m - alt).abs();
                (0..PATH_TABLE_RANGES).flat_map(move |j| {
                    let range = (range_m[0] + j as f64 / per_range).max(vertical);
                    atmospheres.iter().map(move |a| {
                        let p = a.path(sensor_alt_m, alt, range);
                        (p.transmission, p.path_radiance_w_m2_sr)
                    })
                })
            })
            .collect();
        Self {
            sensor_alt_m,
            h0_m,
            u0: u_lo,
            per_u,
            range0_m: range_m[0],
            per_range,
            bands: atmospheres.len(),
            nodes,
        }
    }

    /// Where a hit at `alt_m`, `range_m` away falls.
    #[inline]
    pub(crate) fn cell(&self, alt_m: f64, range_m: f64) -> Cell {
        let u = ((alt_m - self.sensor_alt_m) / self.h0_m).asinh();
        let (i, fa) = cell(u, self.u0, self.per_u, PATH_TABLE_ALTITUDES);
        let (j, fr) = cell(range_m, self.range0_m, self.per_range, PATH_TABLE_RANGES);
        Cell {
            node: i * PATH_TABLE_RANGES + j,
            fa,
            fr,
        }
    }

    /// The bilinearly interpolated path terms of sub-band `band` in `cell`.
    #[inline]
    pub(crate) fn terms(&self, cell: Cell, band: usize) -> PathTerms {
        let at = |node: usize| {
            self.nodes
                .get(node * self.bands + band)
                .copied()
                .unwrap_or((f64::NAN, f64::NAN))
        };
        let k = cell.node;
        let (a, b, c, d) = (
            at(k),
            at(k + 1),
            at(k + PATH_TABLE_RANGES),
            at(k + PATH_TABLE_RANGES + 1),
        );
        let (fa, fr) = (cell.fa, cell.fr);
        let lerp = |x: f64, y: f64, t: f64| x + (y - x) * t;
        PathTerms {
            transmission: lerp(lerp(a.0, b.0, fr), lerp(c.0, d.0, fr), fa),
            path_radiance_w_m2_sr: lerp(lerp(a.1, b.1, fr), lerp(c.1, d.1, fr), fa),
        }
    }
}
