use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_range};
use crate::material::MaterialId;
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
    /// The texture coordinates of the facet's corners, as its object gave them
    /// ([`crate::FacetUv`]); `None`: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uv: Option<crate::FacetUv>,
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
        let vertices = self.facets.iter().map(|f| f.vertices);
        crate::object::check_mesh(&self.positions_m, vertices, |i| {
            let f = &self.facets[i];
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
            match &f.uv {
                Some(uv) => crate::object::check_uv(|| format!("facets[{i}].uv"), uv),
                None => Ok(()),
            }
        })
    }
}
