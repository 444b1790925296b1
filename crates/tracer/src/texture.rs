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

use glam::DVec3;
use irsig_radiometry::BandModel;
use irsig_texture::Footprint;

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
    /// Interval `i`'s Hermite cubic in powers of `u = (T − T_i)/STEP_K` in `[0, 1]`,
    /// `[a, b, c, d]` for `((a·u + b)·u + c)·u + d`: one read and three Horner steps a
    /// hit, where the Hermite basis took four weights each of `u`, `u²` and `u³`.
    cubics: Vec<[f64; 4]>,
}

impl BlackbodyTable {
    /// The table of `band` over `[lo_k, hi_k]` (clamped to at least 1 K, and to
    /// [`MAX_NODES`] nodes from `lo_k`).
    pub(crate) fn new<B: BandModel>(band: &B, [lo_k, hi_k]: [f64; 2]) -> Self {
        let lo_k = lo_k.max(1.0);
        let span = (hi_k - lo_k).max(0.0);
        let n = ((span / STEP_K).ceil() as usize + 2).min(MAX_NODES);
        let nodes: Vec<(f64, f64)> = (0..n)
            .map(|i| band.radiance_and_derivative(lo_k + i as f64 * STEP_K))
            .collect();
        // The Hermite basis `h₀₀ = 2u³ − 3u² + 1`, `h₁₀ = u³ − 2u² + u`, `h₀₁ = −2u³ + 3u²`,
        // `h₁₁ = u³ − u²` gathered by powers of `u`, the slopes `m = STEP_K·dL/dT`.
        let cubics = nodes
            .windows(2)
            .map(|w| {
                let [(l0, d0), (l1, d1)] = [w[0], w[1]];
                let (m0, m1) = (d0 * STEP_K, d1 * STEP_K);
                [
                    2.0 * l0 + m0 - 2.0 * l1 + m1,
                    -3.0 * l0 - 2.0 * m0 + 3.0 * l1 - m1,
                    m0,
                    l0,
                ]
            })
            .collect();
        Self { lo_k, cubics }
    }

    /// `(L(T), dL/dT)` at `t_k`, held to the table's span.
    #[inline]
    pub(crate) fn at(&self, t_k: f64) -> (f64, f64) {
        let last = self.cubics.len().saturating_sub(1);
        let x = ((t_k - self.lo_k) / STEP_K).max(0.0);
        let i = (x as usize).min(last);
        let u = (x - i as f64).clamp(0.0, 1.0);
        let Some(&[a, b, c, d]) = self.cubics.get(i) else {
            return (0.0, 0.0);
        };
        let value = ((a * u + b) * u + c) * u + d;
        let slope = ((3.0 * a * u + 2.0 * b) * u + c) / STEP_K;
        (value, slope)
    }
}

/// A facet's texture coordinates as a function of the world point: `uv(p) = uv₀ + (∇u·(p −
/// a), ∇v·(p − a))`, the barycentric interpolation of its corners' coordinates for every
/// point of its plane. The gradients are the corners' coordinate differences along the
/// dual basis of the edges `e₁ = b − a`, `e₂ = c − a`: the barycentrics `(β, γ)` of
/// `p − a = β e₁ + γ e₂` solve the 2 × 2 Gram system `G (β, γ) = (e₁·d, e₂·d)`
/// (Ericson, *Real-Time Collision Detection*, §3.4), linear in `d = p − a`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct UvMap {
    origin_m: DVec3,
    uv0: [f64; 2],
    grad_u: DVec3,
    grad_v: DVec3,
    /// Texture-coordinate units per metre: `√(A_uv / A_world)`, the square root of the
    /// triangle's area in texture coordinates over its area in the world, constant over
    /// the triangle (the map is affine). A footprint's width in metres times it is its
    /// width in texture coordinates, as an isotropic scale (a stretched mapping's two
    /// axes are averaged geometrically).
    uv_per_m: f64,
}

impl UvMap {
    /// The map of the triangle `[a, b, c]` (world, m) whose corners have coordinates `uv`;
    /// `None` for a degenerate triangle (the raw scene has none).
    pub(crate) fn new([a, b, c]: [DVec3; 3], uv: [[f64; 2]; 3]) -> Option<Self> {
        let (e1, e2) = (b - a, c - a);
        let (g11, g12, g22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let det = g11 * g22 - g12 * g12;
        if !(det.is_normal() && det > 0.0) {
            return None;
        }
        // β = dual_b·d, γ = dual_c·d.
        let dual_b = (e1 * g22 - e2 * g12) / det;
        let dual_c = (e2 * g11 - e1 * g12) / det;
        let grad = |axis: usize| -> DVec3 {
            let (db, dc) = (uv[1][axis] - uv[0][axis], uv[2][axis] - uv[0][axis]);
            dual_b * db + dual_c * dc
        };
        // Twice each area: |e₁ × e₂| = √det in the world, |Δu₁Δv₂ − Δu₂Δv₁| in texture
        // coordinates.
        let uv_area = ((uv[1][0] - uv[0][0]) * (uv[2][1] - uv[0][1])
            - (uv[2][0] - uv[0][0]) * (uv[1][1] - uv[0][1]))
            .abs();
        Some(Self {
            origin_m: a,
            uv0: uv[0],
            grad_u: grad(0),
            grad_v: grad(1),
            uv_per_m: (uv_area / det.sqrt()).sqrt(),
        })
    }

    /// A ray's footprint on this facet in texture-coordinate units, the width an
    /// isotropic filter reads: its cell's longer edge ([`Footprint::width_m`]) times
    /// [`Self::uv_per_m`]; 0 without one (a sky-view ray's hit). Grazing incidence gives an
    /// infinite footprint: the pyramid's last level, the image's mean.
    #[inline]
    pub(crate) fn footprint_uv(&self, footprint: Option<&Footprint>) -> f64 {
        footprint.map_or(0.0, |f| f.width_m() * self.uv_per_m)
    }

    /// The texture coordinates at the world point `p_m` of the facet's plane.
    #[inline]
    pub(crate) fn at(&self, p_m: DVec3) -> [f64; 2] {
        let d = p_m - self.origin_m;
        [
            self.uv0[0] + self.grad_u.dot(d),
            self.uv0[1] + self.grad_v.dot(d),
        ]
    }
}

/// Each facet's [`UvMap`], for the facets whose material has image maps (`has_maps[slot]`);
/// empty when no material has any.
///
/// # Errors
/// Such a facet without texture coordinates, named with its object.
pub(crate) fn facet_uv_maps(
    scene: &irsig_model::RawScene,
    slot_of: impl Fn(u16) -> usize,
    has_maps: &[bool],
) -> Result<Vec<Option<UvMap>>, crate::error::TraceError> {
    use crate::error::{TraceError, TraceErrorKind};
    if !has_maps.iter().any(|&m| m) {
        return Ok(Vec::new());
    }
    scene
        .facets
        .iter()
        .enumerate()
        .map(|(i, f)| {
            if !has_maps
                .get(slot_of(f.material.0))
                .copied()
                .unwrap_or(false)
            {
                return Ok(None);
            }
            let Some(uv) = f.uv else {
                return Err(TraceError::new(TraceErrorKind::NoTextureCoordinates {
                    facet: i,
                    object: scene
                        .objects
                        .get(f.object as usize)
                        .cloned()
                        .unwrap_or_default(),
                    material: f.material.0,
                }));
            };
            // Indices were checked by the scene's validation.
            Ok(UvMap::new(
                f.vertices
                    .map(|v| DVec3::from(scene.positions_m[v as usize])),
                uv,
            ))
        })
        .collect()
}

/// Refuses an emissivity-scale map that takes a material's ε outside 0 to 1 anywhere in
/// sub-band `sub_band` (from 0): the greatest scale times the greatest ε it scales above 1,
/// or a scale below 0. Never clamped, so refused. The ε it scales is the material's own
/// table's, or, under a material map, its map's materials' (a mapped hit is always one of
/// them or their mixture, each ε scaled by the host's texel: [`crate::mixture`]), never
/// the host's own.
///
/// # Errors
/// The first material whose map does.
pub(crate) fn check_emissivity_scales(
    materials: &[crate::tracer::MaterialData],
    tables: &[irsig_radiometry::EmissivityTable],
    sub_band: usize,
) -> Result<(), crate::error::TraceError> {
    let greatest =
        |t: &irsig_radiometry::EmissivityTable| t.emissivity().iter().copied().fold(0.0, f64::max);
    for (m, table) in materials.iter().zip(tables) {
        let Some(maps) = &m.maps else { continue };
        let [lo, hi] = maps.emissivity_scale_range();
        let max_emissivity = if m.mix_slots.is_empty() {
            greatest(table)
        } else {
            m.mix_slots
                .iter()
                .map(|&s| greatest(&tables[usize::from(s)]))
                .fold(0.0, f64::max)
        };
        if lo < 0.0 || hi * max_emissivity > 1.0 {
            return Err(crate::error::TraceError::new(
                crate::error::TraceErrorKind::EmissivityScaleOutOfRange {
                    material: m.id,
                    scale_lo: lo,
                    scale_hi: hi,
                    max_emissivity,
                    sub_band: sub_band + 1,
                },
            ));
        }
    }
    Ok(())
}

impl<B, A> crate::tracer::Tracer<B, A> {
    /// Whether any material of the scene has a texture (statistical, or image maps): a
    /// frame then keeps the texture's truth layers ([`crate::Frame::texture`]).
    #[must_use]
    pub fn is_textured(&self) -> bool {
        self.materials.iter().any(|m| {
            m.texture.is_some()
                || m.maps
                    .as_ref()
                    .is_some_and(irsig_texture::MaterialMaps::varies_texel)
        })
    }

    /// What the material's textures give at a hit: its statistical texture at the world
    /// point and its image maps at the point's texture coordinates, combined (offsets add,
    /// scales multiply); `None` for a material with neither. `footprint` is the ray's cell
    /// on the facet ([`crate::differential`]), which the footprint filters read (`None`:
    /// the point).
    #[inline]
    pub(crate) fn texel_at(
        &self,
        hit: &crate::geometry::Hit<crate::tracer::FacetRadiometry>,
        footprint: Option<&Footprint>,
    ) -> Option<irsig_texture::Texel> {
        let m = &self.materials[usize::from(hit.data.material)];
        let maps = m.maps.as_ref().filter(|x| x.varies_texel());
        if m.texture.is_none() && maps.is_none() {
            return None;
        }
        let p_m = self.geometry.to_world(hit.point_local);
        let field = m
            .texture
            .as_ref()
            .map(|t| t.sample_over(p_m.to_array(), footprint));
        let map = maps
            .zip(self.uv_maps.get(hit.facet as usize).copied().flatten())
            .map(|(maps, uv)| maps.sample_over(uv.at(p_m), uv.footprint_uv(footprint)));
        match (field, map) {
            (Some(a), Some(b)) => Some(a * b),
            (a, b) => a.or(b),
        }
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

    #[test]
    fn a_facets_uv_map_interpolates_its_corners_by_barycentrics() {
        // A tilted triangle a = (1, 2, 3), b = a + (2, 0, 1), c = a + (0, 3, -1) with
        // coordinates (0.1, 0.2), (0.9, 0.2), (0.1, 0.8): a point β e₁ + γ e₂ from a has
        // u = 0.1 + 0.8 β and v = 0.2 + 0.6 γ.
        let a = [1.0, 2.0, 3.0];
        let b = [3.0, 2.0, 4.0];
        let c = [1.0, 5.0, 2.0];
        let map = UvMap::new(
            [DVec3::from(a), DVec3::from(b), DVec3::from(c)],
            [[0.1, 0.2], [0.9, 0.2], [0.1, 0.8]],
        )
        .unwrap();
        for (beta, gamma) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.25, 0.5), (0.3, 0.3)] {
            let p: [f64; 3] =
                std::array::from_fn(|k| a[k] + beta * (b[k] - a[k]) + gamma * (c[k] - a[k]));
            let [u, v] = map.at(DVec3::from(p));
            assert!(
                (u - (0.1 + 0.8 * beta)).abs() < 1e-14,
                "{beta} {gamma}: {u}"
            );
            assert!(
                (v - (0.2 + 0.6 * gamma)).abs() < 1e-14,
                "{beta} {gamma}: {v}"
            );
        }
        assert!(
            UvMap::new(
                [DVec3::from(a), DVec3::from(a), DVec3::from(c)],
                [[0.0; 2]; 3]
            )
            .is_none()
        );
    }

    #[test]
    fn a_footprint_in_texture_coordinates_is_its_longer_edge_times_the_scale() {
        // A right triangle of legs 4 m and 2 m (area 4 m²) mapped onto legs 0.5 and 0.25
        // (area 1/16): √(1/64) = 1/8 unit per metre.
        let map = UvMap::new(
            [
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(4.0, 0.0, 0.0),
                DVec3::new(0.0, 2.0, 0.0),
            ],
            [[0.0, 0.0], [0.5, 0.0], [0.0, 0.25]],
        )
        .unwrap();
        assert!((map.uv_per_m - 0.125).abs() < 1e-15);
        // A cell of edges 2 m and 4 m (a 2 m cell seen at 60°): 0.5 units; at grazing
        // incidence infinite; no footprint, the point.
        let cell = |a: [f64; 3], b: [f64; 3]| Footprint { edges_m: [a, b] };
        let slanted = cell([0.0, 2.0, 0.0], [3.2, 0.0, 2.4]);
        assert!((map.footprint_uv(Some(&slanted)) - 0.5).abs() < 1e-15);
        let grazing = cell([f64::INFINITY; 3], [0.0, 2.0, 0.0]);
        assert!(map.footprint_uv(Some(&grazing)).is_infinite());
        assert!(map.footprint_uv(None).abs() < f64::MIN_POSITIVE);
        // A mirrored mapping has the same scale.
        let mirrored = UvMap::new(
            [
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(4.0, 0.0, 0.0),
                DVec3::new(0.0, 2.0, 0.0),
            ],
            [[0.5, 0.0], [0.0, 0.0], [0.5, 0.25]],
        )
        .unwrap();
        assert!((mirrored.uv_per_m - 0.125).abs() < 1e-15);
    }
}
