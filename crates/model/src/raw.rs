use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_finite, check_range};
use crate::material::MaterialId;
use crate::object::triangle_is_degenerate;
use crate::scene::Terrain;

/// One world-space triangle of a [`RawScene`]: every property resolved.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFacet {
    /// Indices into [`RawScene::positions_m`], counter-clockwise seen from the front.
    pub vertices: [u32; 3],
    /// The facet's material.
    pub material: MaterialId,
    /// The facet's kinetic temperature in kelvin.
    pub temperature_k: f64,
    /// Index into [`RawScene::objects`]: which placed object the facet came from.
    pub object: u32,
}

/// A flattened scene in world coordinates (metres, z up), what the tracer reads: the 1990
/// "raw" data.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    /// The terrain background below the horizon.
    #[serde(default)]
    pub terrain: Terrain,
    /// Names of the placed objects, for messages and truth outputs.
    pub objects: Vec<String>,
    /// Vertex positions in metres, world coordinates (x east, y north, z up).
    pub positions_m: Vec<[f64; 3]>,
    /// The triangles.
    pub facets: Vec<RawFacet>,
}

impl RawScene {
    /// Checks every index and number, and that no triangle is degenerate.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        self.terrain.validate("terrain")?;
        if self.facets.is_empty() {
            return Err(ModelError::new("facets", ModelErrorKind::Empty));
        }
        for (i, p) in self.positions_m.iter().enumerate() {
            check_finite(|| format!("positions_m[{i}]"), p)?;
            for (k, &x) in p.iter().enumerate() {
                let m = crate::limits::MAX_COORDINATE_M;
                check_range(|| format!("positions_m[{i}][{k}]"), x, -m, m)?;
            }
        }
        let len = self.positions_m.len();
        for (i, f) in self.facets.iter().enumerate() {
            for (k, &v) in f.vertices.iter().enumerate() {
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
            if f.object as usize >= self.objects.len() {
                return Err(ModelError::new(
                    format!("facets[{i}].object"),
                    ModelErrorKind::IndexOutOfRange {
                        index: u64::from(f.object),
                        len: self.objects.len() as u64,
                    },
                ));
            }
            f.material.check_facet(|| format!("facets[{i}].material"))?;
            check_range(
                || format!("facets[{i}].temperature_k"),
                f.temperature_k,
                0.0,
                f64::MAX,
            )?;
            let [a, b, c] = f.vertices.map(|v| self.positions_m[v as usize]);
            if triangle_is_degenerate(a, b, c) {
                return Err(ModelError::new(
                    format!("facets[{i}]"),
                    ModelErrorKind::DegenerateTriangle,
                ));
            }
        }
        Ok(())
    }
}
