//! Facets under a material map, solved by the "per-material walls" model: each material of
//! the map with a share of the facet has a wall and surface of its own, under the facet's
//! one set of loads (the same sun and shadow, sky, wind, air and exchange), and no heat
//! flows between them.
//!
//! No lateral conduction is the model's one physical assumption. It holds where each
//! material's patch is wider than a few diurnal diffusion lengths `√(κ · 86400 s / π)`,
//! the depth (and so the sideways reach) over which the daily wave's amplitude falls by
//! `e`: with `κ = k / (ρ c)`, 10 cm for asphalt (0.75 W m⁻¹ K⁻¹, 2110 kg m⁻³,
//! 920 J kg⁻¹ K⁻¹), 5.4 cm for the grass's thatch (0.06, 300, 1920), 6.2 cm for the soil
//! below it (0.52, 2050, 1840), 7.0 cm for the clay track (0.25, 1600, 887.5) and 14 cm for
//! concrete (1.4, 2300, 880). Lanes, verges and lawns are metres wide: only a band about
//! one such length wide along each boundary is evened out by conduction, a share of order
//! 0.1 m over the patch's width of the facet's area. Texels much smaller than
//! that (a map of gravel in sand at a centimetre) would need the conduction; they are not
//! what material maps are for.
//!
//! A facet's area fractions are the map's fractions averaged over its texture-coordinate
//! triangle: the triangle cut into `N × N` equal sub-triangles ([`GRID`] = 16, so 256
//! points), each sampled at its centroid with the map's filter and no footprint. The
//! facet's surface temperature, what other facets exchange with and what a reader that
//! knows nothing of maps emits, is the emission-weighted radiative mean
//! `T = (Σ fᵢ εᵢ Tᵢ⁴ / Σ fᵢ εᵢ)^¼`, and its optics are the fraction-weighted means of the
//! parts' (`α = Σ fᵢ αᵢ`, `ε = Σ fᵢ εᵢ`), so that it sends `ε σ T⁴ = Σ fᵢ εᵢ σ Tᵢ⁴`.

use irsig_model::material_map::MAX_MAP_MATERIALS;
use irsig_model::{MaterialLibrary, RawScene};
use miette::miette;
use rayon::prelude::*;

/// The side of the stratified barycentric grid a facet's fractions are sampled on: `GRID²`
/// sub-triangles of equal area. At 256 points a two-material boundary crossing the facet
/// moves a fraction by at most about 1/16 per texel edge crossed; the fractions' error is
/// of the order of the share of sub-triangles the edges cut, `≈ 1/GRID` for an edge along a
/// facet, and much less for a facet many texels wide.
pub const GRID: u32 = 16;

/// One material of a facet's map with a share of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Part {
    /// Its material model's slot.
    pub slot: usize,
    /// Its area fraction on the facet, 0 to 1.
    pub fraction: f64,
    /// Its place in the map's materials.
    pub index: usize,
}

/// A facet solved part by part.
#[derive(Debug, Clone, PartialEq)]
pub struct Mixed {
    /// The materials with a share, each once; their fractions sum to 1.
    pub parts: Vec<Part>,
    /// How many materials the map mixes (the raw scene's entry holds one temperature each).
    pub materials: usize,
}

impl Mixed {
    /// The emission-weighted radiative mean of the parts' surface temperatures `t_k`
    /// (one per part, in order), with `eps` each part's broadband emissivity. Where no part
    /// emits (every `εᵢ` 0), the area-weighted mean.
    #[must_use]
    pub fn radiative_mean(&self, t_k: &[f64], eps: impl Fn(usize) -> f64) -> f64 {
        let (mut num, mut den, mut plain) = (0.0, 0.0, 0.0);
        for (p, &t) in self.parts.iter().zip(t_k) {
            let w = p.fraction * eps(p.slot);
            num += w * t.powi(4);
            den += w;
            plain += p.fraction * t;
        }
        if den > 0.0 {
            (num / den).powf(0.25)
        } else {
            plain
        }
    }

    /// The raw scene's per-material temperatures: each part's, in the map's order, and the
    /// facet's radiative mean `mean_k` for a material with no share (it has no wall; a
    /// filter that reaches past the facet's triangle may still give it a little weight at
    /// a hit near the edge, and then it emits at the mixture's temperature).
    #[must_use]
    pub fn temperatures(&self, parts_k: &[f64], mean_k: f64) -> Vec<f64> {
        let mut out = vec![mean_k; self.materials];
        for (p, &t) in self.parts.iter().zip(parts_k) {
            out[p.index] = t;
        }
        out
    }
}

/// The map's area fractions averaged over a facet's texture-coordinate triangle `uv`: the
/// mean of `sample` at the centroids of the triangle's `GRID²` equal sub-triangles.
#[must_use]
pub fn fractions(
    uv: &[[f64; 2]; 3],
    sample: impl Fn([f64; 2]) -> [f64; MAX_MAP_MATERIALS],
) -> [f64; MAX_MAP_MATERIALS] {
    let n = f64::from(GRID);
    let at = |a: f64, b: f64| {
        let c = 1.0 - a - b;
        [
            c * uv[0][0] + a * uv[1][0] + b * uv[2][0],
            c * uv[0][1] + a * uv[1][1] + b * uv[2][1],
        ]
    };
    let mut sum = [0.0; MAX_MAP_MATERIALS];
    let mut add = |w: [f64; MAX_MAP_MATERIALS]| {
        for (s, x) in sum.iter_mut().zip(w) {
            *s += x;
        }
    };
    for i in 0..GRID {
        for j in 0..GRID - i {
            let (fi, fj) = (f64::from(i), f64::from(j));
            // The upright sub-triangle (i, j), (i+1, j), (i, j+1): centroid at +1/3 each.
            add(sample(at((fi + 1.0 / 3.0) / n, (fj + 1.0 / 3.0) / n)));
            // The inverted one (i+1, j), (i+1, j+1), (i, j+1), where it lies inside.
            if i + j + 1 < GRID {
                add(sample(at((fi + 2.0 / 3.0) / n, (fj + 2.0 / 3.0) / n)));
            }
        }
    }
    let count = n * n;
    sum.map(|s| s / count)
}

/// Per facet, its area fractions under its material's material map, or `None`.
pub type FacetFractions = Vec<Option<[f64; MAX_MAP_MATERIALS]>>;

/// Each solved facet's area fractions under its material's material map (`None` for a
/// facet whose material has none, or that is held), the maps' images read beside
/// `materials_file`. Empty when no solved facet's material has a map. Beside them, the
/// SHA-256 of each map image read, in the library's order, for the provenance.
///
/// # Errors
/// A map's image that cannot be read as declared, or a facet of a mapped material without
/// texture coordinates (named with its object, material and map).
pub fn facet_fractions(
    scene: &RawScene,
    materials: &MaterialLibrary,
    materials_file: &str,
    solved: &[bool],
) -> miette::Result<(FacetFractions, Vec<String>)> {
    let mut maps = std::collections::HashMap::new();
    let mut images = Vec::new();
    for (k, m) in materials.materials.iter().enumerate() {
        if m.maps.as_ref().and_then(|x| x.material.as_ref()).is_none() {
            continue;
        }
        let used = scene
            .facets
            .iter()
            .zip(solved)
            .any(|(f, &s)| s && f.material == m.id);
        if !used {
            continue;
        }
        if let Some((map, bytes)) =
            irsig_render::read_material_map_of(materials, k, materials_file)?
        {
            images.push(irsig_cli::sha256_hex(&bytes));
            maps.insert(m.id.0, (map, m));
        }
    }
    if maps.is_empty() {
        return Ok((Vec::new(), images));
    }
    for (i, f) in scene.facets.iter().enumerate() {
        if let (true, Some((_, m)), None) = (solved[i], maps.get(&f.material.0), f.uv) {
            let object = scene
                .objects
                .get(f.object as usize)
                .map_or("?", String::as_str);
            let image = m
                .maps
                .as_ref()
                .and_then(|x| x.material.as_ref())
                .map_or("?", |x| x.image.as_str());
            return Err(miette!(
                "facet {i} (object `{object}`) has no texture coordinates, and its material \
                 `{}` (id {}) has the material map `{image}`, which lies on facets by them: \
                 give the object texture coordinates, or a material without a map",
                m.name,
                m.id.0
            ));
        }
    }
    let fractions = scene
        .facets
        .par_iter()
        .zip(solved)
        .map(|(f, &s)| match (s, maps.get(&f.material.0), &f.uv) {
            (true, Some((map, _)), Some(uv)) => Some(fractions(uv, |p| map.sample(p, 0.0))),
            _ => None,
        })
        .collect();
    Ok((fractions, images))
}

/// Each facet solved by its map's materials as a [`Mixed`]: its parts with a fraction
/// above 0, their slots by `slot_of` (a material id's slot). `None` for every other facet.
#[must_use]
pub fn mixed_facets(
    scene: &RawScene,
    materials: &MaterialLibrary,
    fractions: &[Option<[f64; MAX_MAP_MATERIALS]>],
    slot_of: impl Fn(u16) -> Option<usize>,
) -> Vec<Option<Box<Mixed>>> {
    scene
        .facets
        .iter()
        .zip(fractions)
        .map(|(f, w)| {
            let w = (*w)?;
            let map = materials
                .by_id(f.material)?
                .maps
                .as_ref()?
                .material
                .as_ref()?;
            let names = map.materials();
            let mut parts = Vec::with_capacity(names.len());
            for (index, name) in names.iter().enumerate() {
                let slot = materials.by_name(name).and_then(|c| slot_of(c.id.0));
                if let (Some(slot), true) = (slot, w[index] > 0.0) {
                    parts.push(Part {
                        slot,
                        fraction: w[index],
                        index,
                    });
                }
            }
            // The filters' fractions sum to 1 but for rounding: make them.
            let sum: f64 = parts.iter().map(|p| p.fraction).sum();
            for p in &mut parts {
                p.fraction /= sum;
            }
            (!parts.is_empty()).then(|| {
                Box::new(Mixed {
                    parts,
                    materials: names.len(),
                })
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_has_equal_sub_triangles_and_gives_a_half_plane_its_area() {
        let uv = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        // A constant map: the fractions themselves, from 256 samples.
        let count = std::cell::Cell::new(0);
        let f = fractions(&uv, |_| {
            count.set(count.get() + 1);
            [0.25, 0.75, 0.0, 0.0]
        });
        assert_eq!(count.get(), 256);
        assert!((f[0] - 0.25).abs() < 1e-15 && (f[1] - 0.75).abs() < 1e-15);
        // Material 1 where u > 0.5: the triangle's area there is (0.5)² / 2 over 1/2, a
        // quarter. The grid's lines fall on u = 0.5 (8/16), so no sub-triangle is cut.
        let f = fractions(&uv, |p| {
            if p[0] > 0.5 {
                [0.0, 1.0, 0.0, 0.0]
            } else {
                [1.0, 0.0, 0.0, 0.0]
            }
        });
        assert!((f[1] - 0.25).abs() < 1e-15, "{f:?}");
        assert!((f[0] + f[1] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn the_radiative_mean_weights_each_part_by_its_share_of_the_emission() {
        let mixed = Mixed {
            parts: vec![
                Part {
                    slot: 0,
                    fraction: 0.25,
                    index: 1,
                },
                Part {
                    slot: 1,
                    fraction: 0.75,
                    index: 0,
                },
            ],
            materials: 3,
        };
        let eps = |s: usize| if s == 0 { 0.9 } else { 0.95 };
        let t = mixed.radiative_mean(&[330.0, 300.0], eps);
        let by_hand = ((0.25 * 0.9 * 330f64.powi(4) + 0.75 * 0.95 * 300f64.powi(4))
            / (0.25 * 0.9 + 0.75 * 0.95))
            .powf(0.25);
        assert!((t - by_hand).abs() < 1e-12, "{t} {by_hand}");
        // Above the area mean (307.5 K): T⁴ weights the hot part more.
        assert!(t > 307.5 && t < 330.0);
        assert_eq!(
            mixed.temperatures(&[330.0, 300.0], t),
            vec![300.0, 330.0, t]
        );
        // Equal temperatures: that temperature.
        assert!((mixed.radiative_mean(&[290.0, 290.0], eps) - 290.0).abs() < 1e-12);
    }
}
