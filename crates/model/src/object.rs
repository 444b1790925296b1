use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_finite, check_range};
use crate::material::MaterialId;

/// One triangle of an [`Object`]: three vertex indices, a material and, where the input
/// gives one, a kinetic temperature.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Facet {
    /// Indices into [`Object::positions_m`], counter-clockwise seen from the front (the side
    /// the normal `(b − a) × (c − a)` points to).
    pub vertices: [u32; 3],
    /// The facet's material.
    pub material: MaterialId,
    /// The facet's kinetic temperature in kelvin, if the input gives one. Otherwise the
    /// scene's per-object temperature applies when flattening.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature_k: Option<f64>,
    /// The texture coordinates `(u, v)` of the facet's three corners, in the order of
    /// [`Self::vertices`], if the input gives them ([`FacetUv`]). `None`: the facet has
    /// none, and no image map can be laid on it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uv: Option<FacetUv>,
}

/// A facet's texture coordinates: `(u, v)` at each of its three corners, in the facet's
/// vertex order. The image's texel `(0, 0)` starts at `(u, v) = (0, 0)` and `(1, 1)` is
/// its far corner; `u` runs along the image's rows (left to right) and `v` from its
/// bottom row to its top (OpenGL's and OBJ's convention; glTF's `v`, which runs from the
/// top, is turned by the importer). A coordinate outside 0 to 1 repeats the image.
pub type FacetUv = [[f64; 2]; 3];

/// The largest texture coordinate a facet may have, in images: 10⁶ repetitions of a map.
/// Beyond it an `f64` coordinate's fraction, the position within one repetition, keeps
/// fewer than 30 bits, too few to tell the texels of a large image apart.
pub const MAX_UV: f64 = 1e6;

/// Checks a facet's texture coordinates: finite and within ±[`MAX_UV`].
///
/// # Errors
/// The first coordinate out of range, at `{path}[corner][axis]`.
pub(crate) fn check_uv(path: impl Fn() -> String, uv: &FacetUv) -> Result<(), ModelError> {
    for (corner, c) in uv.iter().enumerate() {
        for (axis, &x) in c.iter().enumerate() {
            check_range(
                || format!("{}[{corner}][{axis}]", path()),
                x,
                -MAX_UV,
                MAX_UV,
            )?;
        }
    }
    Ok(())
}

/// A triangle mesh in its own (object) coordinates, in metres, as `irsig-import` writes it.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Object {
    /// A name for messages and for the raw scene's object list.
    pub name: String,
    /// Where the geometry came from (file name and importer), for provenance.
    #[serde(default)]
    pub source: String,
    /// Vertex positions in metres, object coordinates.
    pub positions_m: Vec<[f64; 3]>,
    /// The triangles.
    pub facets: Vec<Facet>,
}

impl Object {
    /// Checks that the object has facets, that every index and number is in range and that
    /// no triangle is degenerate.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        let vertices = self.facets.iter().map(|f| f.vertices);
        check_mesh(&self.positions_m, vertices, |i| {
            let f = &self.facets[i];
            f.material.check_facet(|| format!("facets[{i}].material"))?;
            if let Some(t) = f.temperature_k {
                check_range(|| format!("facets[{i}].temperature_k"), t, 0.0, f64::MAX)?;
            }
            if let Some(uv) = &f.uv {
                check_uv(|| format!("facets[{i}].uv"), uv)?;
            }
            Ok(())
        })
    }
}

/// The rules every mesh of the model keeps (an object's, a raw scene's): at least one
/// facet, finite positions within [`crate::limits::MAX_COORDINATE_M`], vertex indices in
/// range, and, after `facet(i)`'s own rules for facet `i`, no degenerate triangle.
///
/// # Errors
/// The first rule broken, at its path (`positions_m[3][2]`, `facets[7]`).
pub(crate) fn check_mesh(
    positions_m: &[[f64; 3]],
    facets: impl ExactSizeIterator<Item = [u32; 3]>,
    mut facet: impl FnMut(usize) -> Result<(), ModelError>,
) -> Result<(), ModelError> {
    if facets.len() == 0 {
        return Err(ModelError::new("facets", ModelErrorKind::Empty));
    }
    for (i, p) in positions_m.iter().enumerate() {
        check_finite(|| format!("positions_m[{i}]"), p)?;
        for (k, &x) in p.iter().enumerate() {
            let m = crate::limits::MAX_COORDINATE_M;
            check_range(|| format!("positions_m[{i}][{k}]"), x, -m, m)?;
        }
    }
    let len = positions_m.len();
    for (i, vertices) in facets.enumerate() {
        for (k, &v) in vertices.iter().enumerate() {
            if v as usize >= len {
                return Err(ModelError::new(
                    format!("facets[{i}].vertices[{k}]"),
                    ModelErrorKind::IndexOutOfRange {
                        index: u64::from(v),
                        len: len as u64,
                    },
                ));
            }
        }
        facet(i)?;
        let [a, b, c] = vertices.map(|v| positions_m[v as usize]);
        if triangle_is_degenerate(a, b, c) {
            return Err(ModelError::new(
                format!("facets[{i}]"),
                ModelErrorKind::DegenerateTriangle,
            ));
        }
    }
    Ok(())
}

/// True when the triangle has no area relative to its size: its vertices coincide or are
/// collinear to within rounding. Scale-free, so millimetre facets and kilometre facets are
/// judged alike.
#[must_use]
pub fn triangle_is_degenerate(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> bool {
    let sub = |p: [f64; 3], q: [f64; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let e1 = sub(b, a);
    let e2 = sub(c, a);
    let cross = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let norm2 = |v: [f64; 3]| v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    let area2 = norm2(cross);
    let scale = norm2(e1).max(norm2(e2)).max(norm2(sub(c, b)));
    // |e1 × e2|² against (longest edge²)²: a sliver whose height is below about 1e-7 of its
    // length counts as degenerate.
    area2.is_nan() || area2 <= scale * scale * 1e-14
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_coordinates_are_out_of_range_not_degenerate() {
        // 1e300 used to be reported as a "degenerate triangle": its area overflows.
        let o = tri(
            vec![[0.0, 0.0, 0.0], [1e300, 0.0, 0.0], [0.0, 1e300, 0.0]],
            [0, 1, 2],
        );
        let e = o.validate().unwrap_err();
        assert_eq!(e.path, "positions_m[1][0]");
        assert!(e.to_string().contains("1e300"), "{e}");
    }

    fn tri(positions: Vec<[f64; 3]>, vertices: [u32; 3]) -> Object {
        Object {
            name: "t".into(),
            source: String::new(),
            positions_m: positions,
            facets: vec![Facet {
                vertices,
                material: MaterialId(1),
                temperature_k: None,
                uv: None,
            }],
        }
    }

    #[test]
    fn texture_coordinates_are_finite_and_bounded() {
        let mut o = tri(vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [0, 1, 2]);
        o.facets[0].uv = Some([[0.0, 0.0], [-MAX_UV, 1.0], [0.5, MAX_UV]]);
        assert!(o.validate().is_ok());
        o.facets[0].uv = Some([[0.0, 0.0], [1.0, 0.0], [0.0, f64::NAN]]);
        let e = o.validate().unwrap_err();
        assert_eq!(e.path, "facets[0].uv[2][1]");
        o.facets[0].uv = Some([[0.0, 0.0], [2e6, 0.0], [0.0, 1.0]]);
        assert_eq!(o.validate().unwrap_err().path, "facets[0].uv[1][0]");
    }

    #[test]
    fn a_good_triangle_passes() {
        assert!(
            tri(vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [0, 1, 2])
                .validate()
                .is_ok()
        );
    }

    #[test]
    fn tiny_and_huge_triangles_are_not_degenerate() {
        let s = 1e-6;
        assert!(!triangle_is_degenerate(
            [0.0; 3],
            [s, 0.0, 0.0],
            [0.0, s, 0.0]
        ));
        let s = 1e7;
        assert!(!triangle_is_degenerate(
            [s, s, 0.0],
            [s + 1.0, s, 0.0],
            [s, s + 1.0, 0.0]
        ));
    }

    #[test]
    fn collinear_and_coincident_triangles_are_degenerate() {
        assert!(triangle_is_degenerate(
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0]
        ));
        assert!(triangle_is_degenerate([1.0; 3], [1.0; 3], [1.0; 3]));
        assert!(triangle_is_degenerate(
            [0.0; 3],
            [f64::NAN, 0.0, 0.0],
            [0.0, 1.0, 0.0]
        ));
    }

    #[test]
    fn bad_index_empty_mesh_and_nan_are_reported() {
        let o = tri(vec![[0.0; 3], [1.0, 0.0, 0.0]], [0, 1, 2]);
        assert!(matches!(
            o.validate().unwrap_err().kind,
            ModelErrorKind::IndexOutOfRange { .. }
        ));
        let mut o = tri(vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [0, 1, 2]);
        o.facets.clear();
        assert_eq!(o.validate().unwrap_err().kind, ModelErrorKind::Empty);
        let o = tri(
            vec![[0.0; 3], [f64::INFINITY, 0.0, 0.0], [0.0, 1.0, 0.0]],
            [0, 1, 2],
        );
        assert_eq!(o.validate().unwrap_err().kind, ModelErrorKind::NotFinite);
    }
}
