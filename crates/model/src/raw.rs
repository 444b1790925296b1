use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_range};
use crate::material::MaterialId;
use crate::material_map::MAX_MAP_MATERIALS;
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
    /// Per facet whose material has a material map, the temperature of each material of
    /// the map ([`MixTemperatures`]), where a thermal model solved them apart; a facet
    /// without an entry emits every material of its map at its `temperature_k`. Empty in
    /// most scenes, and then not written.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub mix_temperatures: Vec<MixTemperatures>,
}

/// One facet's per-material temperatures: the kinetic temperature of each material its
/// material's material map mixes, in the map's order
/// ([`crate::material_map::MaterialMap::materials`]). The facet's own `temperature_k` is
/// then the mixture's radiative mean, what a reader that knows nothing of maps emits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MixTemperatures {
    /// Index into [`RawScene::facets`].
    pub facet: u32,
    /// One temperature per material of the facet's material map, K (1 to
    /// [`MAX_MAP_MATERIALS`] of them).
    pub temperatures_k: Vec<f64>,
}

impl RawScene {
    /// Checks every index and number, that no triangle is degenerate, and that each
    /// per-material temperature entry names a facet once with 1 to [`MAX_MAP_MATERIALS`]
    /// finite non-negative temperatures. Whether their count is the facet's map's is the
    /// reader's of the material library to check (the tracer, `irsig-therm`).
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        self.terrain.validate("terrain")?;
        self.validate_facets()?;
        self.validate_mix_temperatures()
    }

    /// The per-material temperatures of facet `facet`, when it has them.
    #[must_use]
    pub fn mix_temperatures_of(&self, facet: usize) -> Option<&[f64]> {
        self.mix_temperatures
            .iter()
            .find(|m| m.facet as usize == facet)
            .map(|m| m.temperatures_k.as_slice())
    }

    fn validate_mix_temperatures(&self) -> Result<(), ModelError> {
        let mut seen = std::collections::HashSet::with_capacity(self.mix_temperatures.len());
        for (k, m) in self.mix_temperatures.iter().enumerate() {
            if m.facet as usize >= self.facets.len() {
                return Err(ModelError::new(
                    format!("mix_temperatures[{k}].facet"),
                    ModelErrorKind::IndexOutOfRange {
                        index: u64::from(m.facet),
                        len: self.facets.len() as u64,
                    },
                ));
            }
            if !seen.insert(m.facet) {
                return Err(ModelError::new(
                    format!("mix_temperatures[{k}].facet"),
                    ModelErrorKind::Duplicate(m.facet.to_string()),
                ));
            }
            let n = m.temperatures_k.len();
            if n == 0 || n > MAX_MAP_MATERIALS {
                return Err(ModelError::new(
                    format!("mix_temperatures[{k}].temperatures_k"),
                    ModelErrorKind::Other(format!(
                        "{n} temperatures: expected 1 to {MAX_MAP_MATERIALS}, one per material \
                         of the facet's material map"
                    )),
                ));
            }
            for (i, &t) in m.temperatures_k.iter().enumerate() {
                check_range(
                    || format!("mix_temperatures[{k}].temperatures_k[{i}]"),
                    t,
                    0.0,
                    f64::MAX,
                )?;
            }
        }
        Ok(())
    }

    fn validate_facets(&self) -> Result<(), ModelError> {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> RawScene {
        RawScene {
            objects: vec!["lot".into()],
            positions_m: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            facets: vec![RawFacet {
                vertices: [0, 1, 2],
                material: MaterialId(1),
                temperature_k: 300.0,
                object: 0,
                uv: None,
            }],
            ..RawScene::default()
        }
    }

    fn with(facet: u32, temperatures_k: Vec<f64>) -> RawScene {
        let mut s = scene();
        s.mix_temperatures.push(MixTemperatures {
            facet,
            temperatures_k,
        });
        s
    }

    #[test]
    fn per_material_temperatures_are_checked_at_their_path() {
        assert!(scene().validate().is_ok());
        let ok = with(0, vec![330.0, 0.0, 1e4, 290.0]);
        assert!(ok.validate().is_ok());
        assert_eq!(
            ok.mix_temperatures_of(0),
            Some(&[330.0, 0.0, 1e4, 290.0][..])
        );
        assert_eq!(scene().mix_temperatures_of(0), None);
        let path = |s: RawScene| s.validate().unwrap_err().to_string();
        assert_eq!(
            path(with(1, vec![300.0])),
            "mix_temperatures[0].facet: index 1 is out of range for 1 entries"
        );
        let mut twice = with(0, vec![300.0]);
        twice
            .mix_temperatures
            .push(twice.mix_temperatures[0].clone());
        assert_eq!(path(twice), "mix_temperatures[1].facet: duplicate `0`");
        assert!(
            path(with(0, vec![]))
                .starts_with("mix_temperatures[0].temperatures_k: 0 temperatures: expected 1 to 4")
        );
        assert!(path(with(0, vec![1.0; 5])).contains("5 temperatures"));
        assert_eq!(
            path(with(0, vec![300.0, -1.0])),
            "mix_temperatures[0].temperatures_k[1]: -1 is out of range: expected at least 0"
        );
        assert!(
            path(with(0, vec![f64::NAN]))
                .starts_with("mix_temperatures[0].temperatures_k[0]: expected a finite")
        );
    }
}
