//! What the thermal model needs to know of a material: the wall behind its surface, layer by
//! layer, what lies behind the wall, and how its surface takes up sunlight and gives off
//! heat. A material without it has its facets' temperatures given by hand; `irsig-therm`
//! refuses a facet whose material has none, naming the material.

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_range};

/// The thinnest layer accepted, metres (1 µm: a coat of paint is tens of µm).
pub const MIN_LAYER_THICKNESS_M: f64 = 1e-6;
/// The thickest layer accepted, metres (deep soil is modelled to a few metres).
pub const MAX_LAYER_THICKNESS_M: f64 = 100.0;
/// The most layers a wall may have.
pub const MAX_LAYERS: usize = 64;

/// A material's thermal properties: a wall of layers, its back, and its surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalProperties {
    /// The wall's layers, the exposed one (the facet's surface) first: at least one.
    pub layers: Vec<ThermalLayer>,
    /// What lies behind the last layer.
    pub back: BackBoundary,
    /// The share of sunlight (0.3–4 µm) the surface absorbs, 0 to 1. `None`: taken from the
    /// material's spectral emissivity, whose curve must then cover 0.3–4 µm (opaque, so the
    /// absorptance is ε weighted by the sun's spectrum); a material without such a curve and
    /// without this value is refused by the thermal model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solar_absorptance: Option<f64>,
    /// The surface's broadband (thermal-infrared, hemispherical) emissivity, 0 to 1, what
    /// it absorbs of longwave radiation and emits as `ε σ T⁴`. `None`: the hemispherical
    /// average of the material's angular emissivity table.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thermal_emissivity: Option<f64>,
    /// The share of the surface that is wet, 0 (dry) to 1 (open water): evaporation's
    /// latent heat is taken from that share at the rate of a wet surface.
    #[serde(default)]
    pub wet_fraction: f64,
    /// How rough the surface is to the wind, for the convection correlations that use it.
    #[serde(default)]
    pub roughness: Roughness,
    /// Where the surface's numbers (absorptance, emissivity, wetness) come from.
    pub source: String,
}

/// One layer of a wall: uniform, isotropic, its properties constant with temperature.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalLayer {
    /// Thickness, metres: [`MIN_LAYER_THICKNESS_M`] to [`MAX_LAYER_THICKNESS_M`].
    pub thickness_m: f64,
    /// Thermal conductivity, W m⁻¹ K⁻¹, above 0.
    pub conductivity_w_m_k: f64,
    /// Density, kg m⁻³, above 0.
    pub density_kg_m3: f64,
    /// Specific heat capacity, J kg⁻¹ K⁻¹, above 0.
    pub specific_heat_j_kg_k: f64,
    /// Where the layer's numbers come from (a handbook table, a measurement).
    pub source: String,
}

/// What lies behind a wall's last layer.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum BackBoundary {
    /// No heat crosses it: an insulated back, or the middle of a symmetric wall.
    Adiabatic,
    /// Held at a temperature: deep soil, a tank of water held warm.
    Temperature {
        /// The temperature, K.
        temperature_k: f64,
    },
    /// Convection to air behind the wall: a car's cabin, a building's room.
    Convective {
        /// The convective coefficient, W m⁻² K⁻¹, above 0.
        h_w_m2_k: f64,
        /// The air's temperature.
        air: BackAir,
    },
}

/// The air behind a wall.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum BackAir {
    /// The outdoor air's temperature at each moment (a ventilated shell).
    Outdoor,
    /// A fixed temperature, K (a heated room).
    Fixed {
        /// The temperature, K.
        temperature_k: f64,
    },
}

/// How rough a surface is to the wind: the classes and forced-convection multipliers of
/// the DOE-2 correlation (EnergyPlus Engineering Reference, "Outside surface heat balance",
/// after Yazdanian & Klems 1994 and the TARP roughness classes of Walton 1981).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Roughness {
    /// Stucco, rough soil (multiplier 2.17).
    VeryRough,
    /// Brick, plaster, asphalt (1.67).
    Rough,
    /// Concrete, most natural ground (1.52).
    #[default]
    MediumRough,
    /// Clear pine, sheet wood (1.13).
    MediumSmooth,
    /// Smooth plaster, painted metal (1.11).
    Smooth,
    /// Glass, polished metal, water (1.00).
    VerySmooth,
}

impl Roughness {
    /// The forced-convection multiplier `R_f` of the DOE-2 correlation.
    #[must_use]
    pub fn multiplier(self) -> f64 {
        match self {
            Self::VeryRough => 2.17,
            Self::Rough => 1.67,
            Self::MediumRough => 1.52,
            Self::MediumSmooth => 1.13,
            Self::Smooth => 1.11,
            Self::VerySmooth => 1.00,
        }
    }
}

impl ThermalProperties {
    /// The wall's total thickness, metres.
    #[must_use]
    pub fn thickness_m(&self) -> f64 {
        self.layers.iter().map(|l| l.thickness_m).sum()
    }

    /// Checks every layer, the back and the surface's numbers.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str) -> Result<(), ModelError> {
        if self.layers.is_empty() {
            return Err(ModelError::new(
                format!("{prefix}.layers"),
                ModelErrorKind::Other(
                    "a wall needs at least one layer (thickness_m, conductivity_w_m_k, \
                     density_kg_m3, specific_heat_j_kg_k)"
                        .into(),
                ),
            ));
        }
        if self.layers.len() > MAX_LAYERS {
            return Err(ModelError::new(
                format!("{prefix}.layers"),
                ModelErrorKind::Other(format!(
                    "{} layers: at most {MAX_LAYERS} are accepted",
                    self.layers.len()
                )),
            ));
        }
        for (i, layer) in self.layers.iter().enumerate() {
            layer.validate(&format!("{prefix}.layers[{i}]"))?;
        }
        self.back.validate(&format!("{prefix}.back"))?;
        if let Some(a) = self.solar_absorptance {
            check_range(|| format!("{prefix}.solar_absorptance"), a, 0.0, 1.0)?;
        }
        if let Some(e) = self.thermal_emissivity {
            check_range(|| format!("{prefix}.thermal_emissivity"), e, 0.0, 1.0)?;
        }
        check_range(
            || format!("{prefix}.wet_fraction"),
            self.wet_fraction,
            0.0,
            1.0,
        )
    }
}

impl ThermalLayer {
    /// Checks the layer's four numbers.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str) -> Result<(), ModelError> {
        if self.thickness_m == 0.0 {
            return Err(ModelError::new(
                format!("{prefix}.thickness_m"),
                ModelErrorKind::Other(
                    "a layer of zero thickness holds no heat and conducts none: remove it, \
                     or give its thickness in metres"
                        .into(),
                ),
            ));
        }
        check_range(
            || format!("{prefix}.thickness_m"),
            self.thickness_m,
            MIN_LAYER_THICKNESS_M,
            MAX_LAYER_THICKNESS_M,
        )?;
        // Silver's 429 W/m/K and aerogel's 0.013 bound real solids with room to spare.
        check_range(
            || format!("{prefix}.conductivity_w_m_k"),
            self.conductivity_w_m_k,
            1e-4,
            1e4,
        )?;
        check_range(
            || format!("{prefix}.density_kg_m3"),
            self.density_kg_m3,
            1e-2,
            1e5,
        )?;
        check_range(
            || format!("{prefix}.specific_heat_j_kg_k"),
            self.specific_heat_j_kg_k,
            1.0,
            1e5,
        )
    }

    /// Thermal diffusivity `k / (ρ c)`, m² s⁻¹.
    #[must_use]
    pub fn diffusivity_m2_s(&self) -> f64 {
        self.conductivity_w_m_k / (self.density_kg_m3 * self.specific_heat_j_kg_k)
    }
}

impl BackBoundary {
    /// Checks the back's numbers.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str) -> Result<(), ModelError> {
        match *self {
            Self::Adiabatic => Ok(()),
            Self::Temperature { temperature_k } => check_range(
                || format!("{prefix}.temperature_k"),
                temperature_k,
                1.0,
                5000.0,
            ),
            Self::Convective { h_w_m2_k, air } => {
                check_range(|| format!("{prefix}.h_w_m2_k"), h_w_m2_k, 1e-3, 1e5)?;
                match air {
                    BackAir::Outdoor => Ok(()),
                    BackAir::Fixed { temperature_k } => check_range(
                        || format!("{prefix}.air.temperature_k"),
                        temperature_k,
                        1.0,
                        5000.0,
                    ),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn concrete(thickness_m: f64) -> ThermalLayer {
        ThermalLayer {
            thickness_m,
            conductivity_w_m_k: 1.4,
            density_kg_m3: 2300.0,
            specific_heat_j_kg_k: 880.0,
            source: "Incropera, Table A.3".into(),
        }
    }

    fn wall(layers: Vec<ThermalLayer>, back: BackBoundary) -> ThermalProperties {
        ThermalProperties {
            layers,
            back,
            solar_absorptance: Some(0.65),
            thermal_emissivity: None,
            wet_fraction: 0.0,
            roughness: Roughness::default(),
            source: "test".into(),
        }
    }

    #[test]
    fn a_zero_thickness_layer_is_refused_with_its_place() {
        let w = wall(vec![concrete(0.1), concrete(0.0)], BackBoundary::Adiabatic);
        let e = w.validate("materials[2].thermal").unwrap_err();
        assert_eq!(e.path, "materials[2].thermal.layers[1].thickness_m");
        assert!(e.to_string().contains("zero thickness"), "{e}");
    }

    #[test]
    fn a_wall_without_layers_is_refused() {
        let e = wall(vec![], BackBoundary::Adiabatic)
            .validate("t")
            .unwrap_err();
        assert_eq!(e.path, "t.layers");
    }

    #[test]
    fn every_number_is_checked() {
        let mut layer = concrete(0.1);
        layer.conductivity_w_m_k = f64::NAN;
        assert_eq!(
            wall(vec![layer], BackBoundary::Adiabatic)
                .validate("t")
                .unwrap_err()
                .path,
            "t.layers[0].conductivity_w_m_k"
        );
        let back = BackBoundary::Convective {
            h_w_m2_k: -3.0,
            air: BackAir::Outdoor,
        };
        assert_eq!(
            wall(vec![concrete(0.1)], back)
                .validate("t")
                .unwrap_err()
                .path,
            "t.back.h_w_m2_k"
        );
        let back = BackBoundary::Temperature { temperature_k: 0.0 };
        assert_eq!(
            wall(vec![concrete(0.1)], back)
                .validate("t")
                .unwrap_err()
                .path,
            "t.back.temperature_k"
        );
        let mut w = wall(vec![concrete(0.1)], BackBoundary::Adiabatic);
        w.solar_absorptance = Some(1.2);
        assert_eq!(w.validate("t").unwrap_err().path, "t.solar_absorptance");
        w.solar_absorptance = None;
        w.wet_fraction = -0.1;
        assert_eq!(w.validate("t").unwrap_err().path, "t.wet_fraction");
        w.wet_fraction = 1.0;
        assert!(w.validate("t").is_ok());
    }

    #[test]
    fn thickness_and_diffusivity_by_hand() {
        let w = wall(vec![concrete(0.1), concrete(0.25)], BackBoundary::Adiabatic);
        assert!((w.thickness_m() - 0.35).abs() < 1e-15);
        // 1.4 / (2300 · 880) = 6.917e-7 m²/s.
        assert!((concrete(0.1).diffusivity_m2_s() - 6.916_996e-7).abs() < 1e-12);
    }
}
