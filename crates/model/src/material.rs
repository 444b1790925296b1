use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_increasing, check_range};
use crate::image_map::ImageMaps;
use crate::texture::StatisticalTexture;
use crate::thermal::ThermalProperties;

/// A material's number, as facets and the interaction map carry it. 0 is never a material:
/// the legacy interaction map uses 0 for "nothing hit".
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(transparent)]
pub struct MaterialId(pub u16);

impl MaterialId {
    /// Checks that a facet's material id is 1 or more: 0 is "nothing hit" in the
    /// interaction map, never a facet's material. `path` names the field for the error.
    pub(crate) fn check_facet(self, path: impl Fn() -> String) -> Result<(), ModelError> {
        check_range(path, f64::from(self.0), 1.0, f64::from(u16::MAX))
    }
}

/// One material: how it emits and reflects in the band.
#[derive(Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// The material's number (1 or more), unique in its library.
    pub id: MaterialId,
    /// The name input files use for it (`asphalt`, `steel`), unique in its library.
    pub name: String,
    /// Angular emissivity, `(angle_deg, emissivity)`: the angle between the view ray and the
    /// surface normal in degrees, 0 to 90, strictly increasing, with emissivity 0 to 1.
    /// Linearly interpolated; rotationally symmetric (thesis §3.2.2, `.ems`).
    pub emissivity: Vec<(f64, f64)>,
    /// How the reflected part `r = 1 − ε` divides: 0 is Lambertian (diffuse), 1 is a
    /// mirror (specular); in between, that fraction of `r` is specular and the rest diffuse.
    pub specular_fraction: f64,
    /// Where the numbers come from (a measurement, a paper, a legacy `.ems` file).
    pub source: String,
    /// The band, µm (shortest and longest wavelength), whose values the angular
    /// `emissivity` table gives, when they are one band's (a library fitted to 8–14 µm
    /// measurements). A tracer refuses to use the table in a band that is not within it:
    /// a material needs a `spectral` curve over any other band (its 3–5 µm values are not
    /// its 8–14 µm ones). `None`: the table holds in every band (a grey body).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub band_um: Option<(f64, f64)>,
    /// The emissivity against wavelength, if known (DIRSIG `.ems` curves, the Fresnel
    /// equations over an n, k table). Then ε(λ, θ) = ε(λ) · `emissivity`(θ) /
    /// `emissivity`(0°): the angular table gives the shape, this curve the spectrum, and a
    /// tracer averages it over each band or sub-band it uses. `None`: the angular table is
    /// the band's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spectral: Option<SpectralEmissivity>,
    /// The RMS slope of the surface's facets, dimensionless (`σ² = ⟨z_x² + z_y²⟩`, isotropic
    /// Gaussian slopes, the rough-surface emissivity's parameter), 0 to
    /// [`crate::limits::MAX_RMS_SLOPE`]: the roughness of the specular share's lobe, which
    /// spreads the sun's glint. `None` or 0: a smooth mirror.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rms_slope: Option<f64>,
    /// What the thermal model (`irsig-therm`) needs: the wall's layers, its back and its
    /// surface's solar absorptance and broadband emissivity. `None`: the material's facets
    /// take the temperatures the scene gives them, and the thermal model refuses it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thermal: Option<ThermalProperties>,
    /// Random fields over world space that vary the temperature of the material's facets
    /// and its emissivity from point to point ([`crate::texture`]). `None`: every facet
    /// is one temperature and one emissivity, as the scene and the table give them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub texture: Option<StatisticalTexture>,
    /// Grey images laid on the material's facets by their texture coordinates, that vary
    /// the temperature and the emissivity within a facet ([`crate::image_map`]); with a
    /// statistical texture too, the offsets add and the scales multiply. `None`: no image.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub maps: Option<ImageMaps>,
}

/// The derived form, with `rms_slope`, `thermal`, `texture` and `maps` shown only when given: a material
/// without them prints (and so feeds a run's hash, `irsig.run`) exactly as before the
/// fields existed.
impl std::fmt::Debug for Material {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut d = f.debug_struct("Material");
        d.field("id", &self.id)
            .field("name", &self.name)
            .field("emissivity", &self.emissivity)
            .field("specular_fraction", &self.specular_fraction)
            .field("source", &self.source)
            .field("band_um", &self.band_um)
            .field("spectral", &self.spectral);
        if let Some(sigma) = &self.rms_slope {
            d.field("rms_slope", sigma);
        }
        if let Some(thermal) = &self.thermal {
            d.field("thermal", thermal);
        }
        if let Some(texture) = &self.texture {
            d.field("texture", texture);
        }
        if let Some(maps) = &self.maps {
            d.field("maps", maps);
        }
        d.finish()
    }
}

/// A material's emissivity at normal incidence against wavelength: linear between the
/// samples, undefined outside them (a band the curve does not cover is an error).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectralEmissivity {
    /// Wavelengths, µm, strictly increasing, above 0; at least two.
    pub wavelength_um: Vec<f64>,
    /// Emissivity at each wavelength, 0 to 1.
    pub emissivity: Vec<f64>,
    /// ε at every wavelength and angle, when the angular shape changes with wavelength (a
    /// Fresnel surface: `irsig-material fresnel --nk-table`). Then a band or sub-band's
    /// angular table is this table averaged over it angle by angle, and the material's
    /// `emissivity` table and the curve above are not used for it. `None`: the separable
    /// form ε(λ) · `emissivity`(θ) / `emissivity`(0°).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angular: Option<SpectralAngular>,
}

/// ε(λ, θ) on a grid: one row per wavelength of the curve it belongs to.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectralAngular {
    /// Angles from the surface normal, degrees, 0 to 90, strictly increasing.
    pub angle_deg: Vec<f64>,
    /// `emissivity[i][j]`: ε at the curve's `wavelength_um[i]` and `angle_deg[j]`, 0 to 1.
    pub emissivity: Vec<Vec<f64>>,
}

impl SpectralEmissivity {
    /// Checks the curve.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str) -> Result<(), ModelError> {
        if self.wavelength_um.len() < 2 {
            return Err(ModelError::new(
                format!("{prefix}.wavelength_um"),
                ModelErrorKind::Other(
                    "a spectral emissivity needs at least two wavelengths".into(),
                ),
            ));
        }
        if self.emissivity.len() != self.wavelength_um.len() {
            return Err(ModelError::new(
                format!("{prefix}.emissivity"),
                ModelErrorKind::Other(format!(
                    "{} emissivities for {} wavelengths",
                    self.emissivity.len(),
                    self.wavelength_um.len()
                )),
            ));
        }
        for (i, &w) in self.wavelength_um.iter().enumerate() {
            check_range(|| format!("{prefix}.wavelength_um[{i}]"), w, 1e-3, 1e4)?;
        }
        for (i, &e) in self.emissivity.iter().enumerate() {
            check_range(|| format!("{prefix}.emissivity[{i}]"), e, 0.0, 1.0)?;
        }
        check_increasing(
            |i| format!("{prefix}.wavelength_um[{i}]"),
            self.wavelength_um.iter().copied(),
        )?;
        if let Some(a) = &self.angular {
            a.validate(&format!("{prefix}.angular"), self.wavelength_um.len())?;
        }
        Ok(())
    }
}

impl SpectralAngular {
    /// Checks the grid: `rows` rows (one per wavelength) of one value per angle.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str, rows: usize) -> Result<(), ModelError> {
        if self.angle_deg.is_empty() {
            return Err(ModelError::new(
                format!("{prefix}.angle_deg"),
                ModelErrorKind::Empty,
            ));
        }
        for (j, &a) in self.angle_deg.iter().enumerate() {
            check_range(|| format!("{prefix}.angle_deg[{j}]"), a, 0.0, 90.0)?;
        }
        check_increasing(
            |j| format!("{prefix}.angle_deg[{j}]"),
            self.angle_deg.iter().copied(),
        )?;
        if self.emissivity.len() != rows {
            return Err(ModelError::new(
                format!("{prefix}.emissivity"),
                ModelErrorKind::Other(format!(
                    "{} rows for {rows} wavelengths",
                    self.emissivity.len()
                )),
            ));
        }
        for (i, row) in self.emissivity.iter().enumerate() {
            if row.len() != self.angle_deg.len() {
                return Err(ModelError::new(
                    format!("{prefix}.emissivity[{i}]"),
                    ModelErrorKind::Other(format!(
                        "{} values for {} angles",
                        row.len(),
                        self.angle_deg.len()
                    )),
                ));
            }
            for (j, &e) in row.iter().enumerate() {
                check_range(|| format!("{prefix}.emissivity[{i}][{j}]"), e, 0.0, 1.0)?;
            }
        }
        Ok(())
    }
}

/// A set of materials: the canonical form of the legacy material index file plus its
/// `.ems` files.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialLibrary {
    /// The materials, in any order.
    pub materials: Vec<Material>,
}

impl Material {
    /// Checks the emissivity table and the specular fraction.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str) -> Result<(), ModelError> {
        if self.id.0 == 0 {
            return Err(ModelError::new(
                format!("{prefix}.id"),
                ModelErrorKind::Other("material id 0 is reserved for \"nothing hit\"".into()),
            ));
        }
        if self.emissivity.is_empty() {
            return Err(ModelError::new(
                format!("{prefix}.emissivity"),
                ModelErrorKind::Empty,
            ));
        }
        for (i, &(angle, eps)) in self.emissivity.iter().enumerate() {
            check_range(
                || format!("{prefix}.emissivity[{i}].angle_deg"),
                angle,
                0.0,
                90.0,
            )?;
            check_range(
                || format!("{prefix}.emissivity[{i}].emissivity"),
                eps,
                0.0,
                1.0,
            )?;
        }
        check_increasing(
            |i| format!("{prefix}.emissivity[{i}].angle_deg"),
            self.emissivity.iter().map(|e| e.0),
        )?;
        check_range(
            || format!("{prefix}.specular_fraction"),
            self.specular_fraction,
            0.0,
            1.0,
        )?;
        if let Some(sigma) = self.rms_slope {
            check_range(
                || format!("{prefix}.rms_slope"),
                sigma,
                0.0,
                crate::limits::MAX_RMS_SLOPE,
            )?;
        }
        if let Some((shortest, longest)) = self.band_um {
            check_range(|| format!("{prefix}.band_um.0"), shortest, 1e-3, 1e4)?;
            check_range(|| format!("{prefix}.band_um.1"), longest, 1e-3, 1e4)?;
            if longest <= shortest {
                return Err(ModelError::new(
                    format!("{prefix}.band_um.1"),
                    ModelErrorKind::Other(format!(
                        "the band's longest wavelength {longest} um is not above its \
                         shortest {shortest} um"
                    )),
                ));
            }
        }
        if let Some(t) = &self.thermal {
            t.validate(&format!("{prefix}.thermal"))?;
        }
        if let Some(t) = &self.texture {
            t.validate(&format!("{prefix}.texture"))?;
        }
        if let Some(m) = &self.maps {
            m.validate(&format!("{prefix}.maps"))?;
        }
        if let Some(s) = &self.spectral {
            s.validate(&format!("{prefix}.spectral"))?;
            if self.emissivity.first().is_some_and(|r| r.1 <= 0.0) {
                return Err(ModelError::new(
                    format!("{prefix}.emissivity[0].emissivity"),
                    ModelErrorKind::Other(
                        "a spectral material's angular table gives the shape ε(θ)/ε(0°): its \
                         first value must be above 0"
                            .into(),
                    ),
                ));
            }
        }
        Ok(())
    }
}

impl MaterialLibrary {
    /// Checks every material, and that ids and names are unique.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        let mut ids = std::collections::HashSet::new();
        let mut names = std::collections::HashSet::new();
        for (i, m) in self.materials.iter().enumerate() {
            let prefix = format!("materials[{i}]");
            m.validate(&prefix)?;
            if !ids.insert(m.id) {
                return Err(ModelError::new(
                    format!("{prefix}.id"),
                    ModelErrorKind::Duplicate(m.id.0.to_string()),
                ));
            }
            if !names.insert(m.name.as_str()) {
                return Err(ModelError::new(
                    format!("{prefix}.name"),
                    ModelErrorKind::Duplicate(m.name.clone()),
                ));
            }
        }
        self.validate_material_maps()
    }

    /// Checks that every material map names materials of this library, none of which has
    /// a material map of its own (a mixture is of plain materials).
    fn validate_material_maps(&self) -> Result<(), ModelError> {
        for (i, m) in self.materials.iter().enumerate() {
            let Some(map) = m.maps.as_ref().and_then(|x| x.material.as_ref()) else {
                continue;
            };
            for name in map.materials() {
                let path = || match &map.form {
                    crate::material_map::MapForm::Index { table } => {
                        let j = table.iter().position(|e| e.material == name).unwrap_or(0);
                        format!("materials[{i}].maps.material.form.table[{j}].material")
                    }
                    crate::material_map::MapForm::Weights { channels, .. } => {
                        let j = channels.iter().position(|c| c == name).unwrap_or(0);
                        format!("materials[{i}].maps.material.form.channels[{j}]")
                    }
                };
                let Some(component) = self.by_name(name) else {
                    return Err(ModelError::new(
                        path(),
                        ModelErrorKind::Other(format!(
                            "unknown material `{name}`: expected the name of a material of \
                             this library"
                        )),
                    ));
                };
                if component
                    .maps
                    .as_ref()
                    .is_some_and(|x| x.material.is_some())
                {
                    return Err(ModelError::new(
                        path(),
                        ModelErrorKind::Other(format!(
                            "material `{name}` has a material map of its own: a map mixes \
                             plain materials"
                        )),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The material with this name, if any. Names match exactly.
    #[must_use]
    pub fn by_name(&self, name: &str) -> Option<&Material> {
        self.materials.iter().find(|m| m.name == name)
    }

    /// The material with this id, if any.
    #[must_use]
    pub fn by_id(&self, id: MaterialId) -> Option<&Material> {
        self.materials.iter().find(|m| m.id == id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mat(id: u16, name: &str, eps: Vec<(f64, f64)>) -> Material {
        Material {
            id: MaterialId(id),
            name: name.into(),
            emissivity: eps,
            specular_fraction: 1.0,
            source: "test".into(),
            band_um: None,
            spectral: None,
            rms_slope: None,
            thermal: None,
            texture: None,
            maps: None,
        }
    }

    #[test]
    fn emissivity_above_one_names_its_place() {
        let lib = MaterialLibrary {
            materials: vec![
                mat(1, "a", vec![(0.0, 0.9)]),
                mat(2, "b", vec![(0.0, 0.9), (45.0, 1.3)]),
            ],
        };
        let err = lib.validate().unwrap_err();
        assert_eq!(err.path, "materials[1].emissivity[1].emissivity");
        assert!(err.to_string().contains("1.3"));
    }

    #[test]
    fn angles_must_increase_and_stay_within_0_to_90() {
        let m = mat(1, "a", vec![(0.0, 0.9), (0.0, 0.8)]);
        assert!(matches!(
            m.validate("m").unwrap_err().kind,
            ModelErrorKind::NotIncreasing { .. }
        ));
        let m = mat(1, "a", vec![(0.0, 0.9), (95.0, 0.8)]);
        assert!(matches!(
            m.validate("m").unwrap_err().kind,
            ModelErrorKind::OutOfRange { .. }
        ));
        let m = mat(1, "a", vec![(f64::NAN, 0.9)]);
        assert_eq!(m.validate("m").unwrap_err().kind, ModelErrorKind::NotFinite);
    }

    #[test]
    fn a_material_map_names_plain_materials_of_its_library() {
        use crate::image_map::{ImageMaps, MapFilter};
        use crate::material_map::{IndexEntry, MapForm, MaterialMap};
        let mapped = |names: &[&str]| ImageMaps {
            temperature_offset_k: None,
            emissivity_scale: None,
            material: Some(MaterialMap {
                image: "m.png".into(),
                form: MapForm::Index {
                    table: names
                        .iter()
                        .enumerate()
                        .map(|(g, n)| IndexEntry {
                            grey: g as u16,
                            material: (*n).into(),
                        })
                        .collect(),
                },
                filter: MapFilter::Nearest,
            }),
        };
        let mut host = mat(3, "ground", vec![(0.0, 0.9)]);
        host.maps = Some(mapped(&["asphalt", "grass"]));
        let lib = |host: Material| MaterialLibrary {
            materials: vec![
                mat(1, "asphalt", vec![(0.0, 0.95)]),
                mat(2, "grass", vec![(0.0, 0.98)]),
                host,
            ],
        };
        assert!(lib(host.clone()).validate().is_ok());
        host.maps = Some(mapped(&["asphalt", "gras"]));
        let e = lib(host.clone()).validate().unwrap_err();
        assert_eq!(e.path, "materials[2].maps.material.form.table[1].material");
        assert!(e.to_string().contains("unknown material `gras`"), "{e}");
        // A map naming its own material, which has a map: no nesting.
        host.maps = Some(mapped(&["asphalt", "ground"]));
        let e = lib(host).validate().unwrap_err();
        assert_eq!(e.path, "materials[2].maps.material.form.table[1].material");
    }

    #[test]
    fn duplicate_names_and_ids_are_rejected() {
        let lib = MaterialLibrary {
            materials: vec![mat(1, "a", vec![(0.0, 0.9)]), mat(1, "b", vec![(0.0, 0.9)])],
        };
        assert!(matches!(
            lib.validate().unwrap_err().kind,
            ModelErrorKind::Duplicate(_)
        ));
        let lib = MaterialLibrary {
            materials: vec![mat(1, "a", vec![(0.0, 0.9)]), mat(2, "a", vec![(0.0, 0.9)])],
        };
        assert!(matches!(
            lib.validate().unwrap_err().kind,
            ModelErrorKind::Duplicate(_)
        ));
    }

    #[test]
    fn an_rms_slope_must_be_finite_and_within_the_limit() {
        let with = |sigma: f64| {
            let mut m = mat(1, "a", vec![(0.0, 0.9)]);
            m.rms_slope = Some(sigma);
            m.validate("m")
        };
        assert!(with(0.0).is_ok());
        assert!(with(0.2).is_ok());
        assert!(with(crate::limits::MAX_RMS_SLOPE).is_ok());
        for bad in [-0.1, 10.5, f64::NAN, f64::INFINITY] {
            let e = with(bad).unwrap_err();
            assert_eq!(e.path, "m.rms_slope", "{bad}");
        }
    }

    #[test]
    fn a_material_without_a_slope_prints_as_before_the_field_existed() {
        let mut m = mat(1, "a", vec![(0.0, 0.9)]);
        assert_eq!(
            format!("{m:?}"),
            "Material { id: MaterialId(1), name: \"a\", emissivity: [(0.0, 0.9)], \
             specular_fraction: 1.0, source: \"test\", band_um: None, spectral: None }"
        );
        m.rms_slope = Some(0.2);
        assert!(format!("{m:?}").ends_with("spectral: None, rms_slope: 0.2 }"));
    }

    #[test]
    fn id_zero_is_reserved() {
        assert!(mat(0, "a", vec![(0.0, 0.9)]).validate("m").is_err());
    }

    #[test]
    fn an_angular_grid_must_fit_its_curve_and_hold_emissivities() {
        let with = |rows: Vec<Vec<f64>>| {
            let mut m = mat(1, "a", vec![(0.0, 0.9), (90.0, 0.0)]);
            m.spectral = Some(SpectralEmissivity {
                wavelength_um: vec![8.0, 14.0],
                emissivity: vec![0.9, 0.8],
                angular: Some(SpectralAngular {
                    angle_deg: vec![0.0, 90.0],
                    emissivity: rows,
                }),
            });
            m.validate("m")
        };
        assert!(with(vec![vec![0.9, 0.0], vec![0.8, 0.0]]).is_ok());
        // A row short: the row named.
        let e = with(vec![vec![0.9, 0.0], vec![0.8]]).unwrap_err();
        assert_eq!(e.path, "m.spectral.angular.emissivity[1]");
        // A row missing: the grid named.
        let e = with(vec![vec![0.9, 0.0]]).unwrap_err();
        assert_eq!(e.path, "m.spectral.angular.emissivity");
        // A value above 1: its row and column.
        let e = with(vec![vec![0.9, 0.0], vec![1.2, 0.0]]).unwrap_err();
        assert_eq!(e.path, "m.spectral.angular.emissivity[1][0]");
        assert!(matches!(e.kind, ModelErrorKind::OutOfRange { .. }));
    }
}
