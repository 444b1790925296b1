use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_finite, check_range};
use crate::material::MaterialId;

/// What a ray sees when it leaves the scene below the horizon: flat terrain of one
/// temperature, and either one emissivity or a material of the library (the 1990 code
/// hard-wired a 286 K blackbody).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Terrain {
    /// Kinetic temperature of the terrain in kelvin.
    pub temperature_k: f64,
    /// Band emissivity of the terrain, 0 to 1, the same at every angle. The rest reflects
    /// the hemispheric sky. Not read when `material` is given.
    #[serde(default = "one")]
    pub emissivity: f64,
    /// A material of the material library the terrain is made of: its angular emissivity
    /// (per sub-band, where the library is spectral) and its specular fraction, as a
    /// horizontal facet of that material at the terrain's temperature would have them.
    /// A ground plane of grass inside the scene and a grass terrain beyond its edge then
    /// meet without a seam; a constant `emissivity` differs from an angular table by up to
    /// the table's whole fall toward grazing incidence. `None`: the constant.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<MaterialId>,
}

fn one() -> f64 {
    1.0
}

impl Default for Terrain {
    /// The 1990 code's background: a 286 K blackbody.
    fn default() -> Self {
        Self {
            temperature_k: 286.0,
            emissivity: 1.0,
            material: None,
        }
    }
}

impl Terrain {
    /// Checks the temperature, the emissivity and the material's id (1 or more; whether
    /// the library defines it is the tracer's check, which holds the library).
    ///
    /// # Errors
    /// The first rule broken, below `prefix`.
    pub fn validate(&self, prefix: &str) -> Result<(), ModelError> {
        check_range(
            || format!("{prefix}.temperature_k"),
            self.temperature_k,
            0.0,
            f64::MAX,
        )?;
        check_range(|| format!("{prefix}.emissivity"), self.emissivity, 0.0, 1.0)?;
        match self.material {
            Some(m) => m.check_facet(|| format!("{prefix}.material")),
            None => Ok(()),
        }
    }
}

/// Which facets of an object an override applies to.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum FacetSelection {
    /// Facets `first..=last`, counted from 0 in the object's facet order.
    Range {
        /// First facet index, inclusive.
        first: usize,
        /// Last facet index, inclusive.
        last: usize,
    },
    /// Every facet of this material.
    Material(MaterialId),
    /// Every facet of the object.
    All,
}

/// A per-facet edit applied while flattening: give the selected facets a new material, a
/// new temperature, or both (the thesis's recommendation on facet editing, §5.2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FacetOverride {
    /// Which facets.
    pub select: FacetSelection,
    /// Their new material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<MaterialId>,
    /// Their new kinetic temperature in kelvin.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature_k: Option<f64>,
}

/// One object placed in the world.
///
/// A vertex `p` of the object goes to world space as `T + R·(S·p)`: scale first, then
/// rotation, then translation, with `R = Rz(rz)·Ry(ry)·Rx(rx)` (rotate about x first, then
/// y, then z, all about the world axes, right-handed, positive counter-clockwise looking
/// down the axis towards the origin).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Placement {
    /// The canonical object file, relative to the scene file.
    pub object: PathBuf,
    /// Rotations about x, y and z in degrees.
    #[serde(default)]
    pub rotation_deg: [f64; 3],
    /// Translation in metres.
    #[serde(default)]
    pub translation_m: [f64; 3],
    /// Scale factors along x, y and z (unitless; the object is already in metres).
    #[serde(default = "unit_scale")]
    pub scale: [f64; 3],
    /// Kinetic temperature in kelvin for facets that carry none of their own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature_k: Option<f64>,
    /// Per-facet edits, applied in order after the object temperature.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub overrides: Vec<FacetOverride>,
}

fn unit_scale() -> [f64; 3] {
    [1.0; 3]
}

/// A scene: objects placed in the world, and the terrain seen beyond them.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// The objects, in order.
    pub objects: Vec<Placement>,
    /// The terrain background below the horizon.
    #[serde(default)]
    pub terrain: Terrain,
}

impl Scene {
    /// Checks every number in the scene.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        if self.objects.is_empty() {
            return Err(ModelError::new("objects", ModelErrorKind::Empty));
        }
        self.terrain.validate("terrain")?;
        for (i, p) in self.objects.iter().enumerate() {
            check_finite(|| format!("objects[{i}].rotation_deg"), &p.rotation_deg)?;
            check_finite(|| format!("objects[{i}].translation_m"), &p.translation_m)?;
            check_finite(|| format!("objects[{i}].scale"), &p.scale)?;
            if p.scale.contains(&0.0) {
                return Err(ModelError::new(
                    format!("objects[{i}].scale"),
                    ModelErrorKind::Other("a zero scale flattens the object to nothing".into()),
                ));
            }
            if let Some(t) = p.temperature_k {
                check_range(|| format!("objects[{i}].temperature_k"), t, 0.0, f64::MAX)?;
            }
            for (k, o) in p.overrides.iter().enumerate() {
                if let Some(t) = o.temperature_k {
                    check_range(
                        || format!("objects[{i}].overrides[{k}].temperature_k"),
                        t,
                        0.0,
                        f64::MAX,
                    )?;
                }
                if let FacetSelection::Range { first, last } = o.select {
                    if first > last {
                        return Err(ModelError::new(
                            format!("objects[{i}].overrides[{k}].select"),
                            ModelErrorKind::Other(format!(
                                "range {first}..={last} is empty: first must not exceed last"
                            )),
                        ));
                    }
                }
            }
        }
        Ok(())
    }
}
