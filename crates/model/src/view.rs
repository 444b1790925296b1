use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_finite, check_range};

/// A length unit a legacy or mesh file is read in. Inside irsig everything is metres.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LengthUnit {
    /// Metres (glTF, most OBJ exports).
    #[default]
    M,
    /// Kilometres (the 1990 data).
    Km,
    /// Centimetres.
    Cm,
    /// Millimetres.
    Mm,
    /// Feet.
    Ft,
    /// Inches.
    In,
}

impl LengthUnit {
    /// Metres per unit.
    #[must_use]
    pub fn metres(self) -> f64 {
        match self {
            Self::M => 1.0,
            Self::Km => 1000.0,
            Self::Cm => 0.01,
            Self::Mm => 0.001,
            Self::Ft => 0.3048,
            Self::In => 0.0254,
        }
    }
}

impl std::str::FromStr for LengthUnit {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "m" => Ok(Self::M),
            "km" => Ok(Self::Km),
            "cm" => Ok(Self::Cm),
            "mm" => Ok(Self::Mm),
            "ft" => Ok(Self::Ft),
            "in" => Ok(Self::In),
            other => Err(format!(
                "unknown length unit `{other}`: expected m, km, cm, mm, ft or in"
            )),
        }
    }
}

/// Where the sensor is and how it looks.
///
/// Both forms give a pinhole camera with `pixels = [columns, rows]` and full fields of view
/// `fov_deg = [x, y]`. Positions are world coordinates in metres (x east, y north, z up).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum View {
    /// The 1990 viewing file: image-plane rotations ω φ κ about x, y and z (the
    /// photogrammetric matrix of thesis Appendix H). ω = φ = κ = 0 looks straight down.
    Legacy {
        /// Sensor position in metres.
        position_m: [f64; 3],
        /// Image size, `[columns, rows]`.
        pixels: [u32; 2],
        /// ω, φ, κ in degrees.
        omega_phi_kappa_deg: [f64; 3],
        /// Full fields of view, `[x, y]`, in degrees.
        fov_deg: [f64; 2],
        /// The 1990 system gain in digital counts per kelvin, if given.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        gain_dc_per_k: Option<f64>,
    },
    /// A sensor at `position_m` aimed at `target_m`, with `up` giving the image's upward
    /// direction (default +z).
    LookAt {
        /// Sensor position in metres.
        position_m: [f64; 3],
        /// The world point at the image centre, in metres.
        target_m: [f64; 3],
        /// World direction that appears upward in the image.
        #[serde(default = "z_up")]
        up: [f64; 3],
        /// Image size, `[columns, rows]`.
        pixels: [u32; 2],
        /// Full fields of view, `[x, y]`, in degrees.
        fov_deg: [f64; 2],
        /// System gain in digital counts per kelvin, if given.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        gain_dc_per_k: Option<f64>,
    },
}

fn z_up() -> [f64; 3] {
    [0.0, 0.0, 1.0]
}

impl View {
    /// The sensor position in metres.
    #[must_use]
    pub fn position_m(&self) -> [f64; 3] {
        match self {
            Self::Legacy { position_m, .. } | Self::LookAt { position_m, .. } => *position_m,
        }
    }

    /// The image size, `[columns, rows]`.
    #[must_use]
    pub fn pixels(&self) -> [u32; 2] {
        match self {
            Self::Legacy { pixels, .. } | Self::LookAt { pixels, .. } => *pixels,
        }
    }

    /// The full fields of view, `[x, y]`, in degrees.
    #[must_use]
    pub fn fov_deg(&self) -> [f64; 2] {
        match self {
            Self::Legacy { fov_deg, .. } | Self::LookAt { fov_deg, .. } => *fov_deg,
        }
    }

    /// The system gain in DC/K, if given.
    #[must_use]
    pub fn gain_dc_per_k(&self) -> Option<f64> {
        match self {
            Self::Legacy { gain_dc_per_k, .. } | Self::LookAt { gain_dc_per_k, .. } => {
                *gain_dc_per_k
            }
        }
    }

    /// Checks the numbers: positive image size, fields of view in (0°, 180°), finite values,
    /// and for look-at a target apart from the position and an `up` not along the view.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        check_finite(|| "position_m".into(), &self.position_m())?;
        let [w, h] = self.pixels();
        if w == 0 || h == 0 {
            return Err(ModelError::new(
                "pixels",
                ModelErrorKind::Other(format!("image size {w}x{h} has no pixels")),
            ));
        }
        if u64::from(w) * u64::from(h) > crate::limits::MAX_IMAGE_PIXELS {
            return Err(ModelError::new(
                "pixels",
                ModelErrorKind::Other(format!(
                    "image size {w}x{h} is more than the {} pixels (8192x8192) one image \
                     may have",
                    crate::limits::MAX_IMAGE_PIXELS
                )),
            ));
        }
        for (i, f) in self.fov_deg().into_iter().enumerate() {
            check_range(|| format!("fov_deg[{i}]"), f, 1e-9, 179.999)?;
        }
        if let Some(g) = self.gain_dc_per_k() {
            check_range(|| "gain_dc_per_k".into(), g, 1e-12, f64::MAX)?;
        }
        match self {
            Self::Legacy {
                omega_phi_kappa_deg,
                ..
            } => check_finite(|| "omega_phi_kappa_deg".into(), omega_phi_kappa_deg),
            Self::LookAt {
                position_m,
                target_m,
                up,
                ..
            } => {
                check_finite(|| "target_m".into(), target_m)?;
                check_finite(|| "up".into(), up)?;
                let d = [
                    target_m[0] - position_m[0],
                    target_m[1] - position_m[1],
                    target_m[2] - position_m[2],
                ];
                let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                if dd == 0.0 {
                    return Err(ModelError::new(
                        "target_m",
                        ModelErrorKind::Other("the target coincides with the position".into()),
                    ));
                }
                let c = [
                    d[1] * up[2] - d[2] * up[1],
                    d[2] * up[0] - d[0] * up[2],
                    d[0] * up[1] - d[1] * up[0],
                ];
                let uu = up[0] * up[0] + up[1] * up[1] + up[2] * up[2];
                let cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
                if cc.is_nan() || cc <= 1e-18 * dd * uu {
                    return Err(ModelError::new(
                        "up",
                        ModelErrorKind::Other(
                            "`up` is parallel to the view direction: the image's roll is undefined"
                                .into(),
                        ),
                    ));
                }
                Ok(())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_image_larger_than_the_budget_is_rejected_before_any_allocation() {
        let view = |pixels| View::LookAt {
            position_m: [0.0, -10.0, 5.0],
            target_m: [0.0; 3],
            up: [0.0, 0.0, 1.0],
            pixels,
            fov_deg: [10.0, 10.0],
            gain_dc_per_k: None,
        };
        // 100,000 x 100,000 would be 80 GB of radiance alone; u32::MAX squared overflows
        // a u32 product.
        for p in [[100_000, 100_000], [u32::MAX, u32::MAX], [8193, 8192]] {
            let e = view(p).validate().unwrap_err();
            assert_eq!(e.path, "pixels", "{p:?}");
        }
        view([8192, 8192]).validate().unwrap();
    }

    #[test]
    fn look_at_straight_down_with_z_up_is_rejected() {
        let v = View::LookAt {
            position_m: [0.0, 0.0, 100.0],
            target_m: [0.0; 3],
            up: [0.0, 0.0, 1.0],
            pixels: [4, 4],
            fov_deg: [10.0, 10.0],
            gain_dc_per_k: None,
        };
        assert!(v.validate().is_err());
    }

    #[test]
    fn legacy_view_round_trips_through_ron() {
        let v = View::Legacy {
            position_m: [1600.0, -3000.0, 700.0],
            pixels: [256, 256],
            omega_phi_kappa_deg: [78.3664, 0.0, 28.0725],
            fov_deg: [1.0, 1.0],
            gain_dc_per_k: Some(2.0),
        };
        v.validate().unwrap();
        let text = ron::to_string(&v).unwrap();
        assert_eq!(ron::from_str::<View>(&text).unwrap(), v);
    }

    #[test]
    fn zero_pixels_and_wide_fov_are_rejected() {
        let mut v = View::Legacy {
            position_m: [0.0; 3],
            pixels: [0, 4],
            omega_phi_kappa_deg: [0.0; 3],
            fov_deg: [1.0, 1.0],
            gain_dc_per_k: None,
        };
        assert!(v.validate().is_err());
        if let View::Legacy {
            pixels, fov_deg, ..
        } = &mut v
        {
            *pixels = [4, 4];
            *fov_deg = [180.0, 1.0];
        }
        assert!(v.validate().is_err());
    }

    #[test]
    fn units_convert_to_metres() {
        assert!((LengthUnit::Km.metres() - 1000.0).abs() < 1e-12);
        assert_eq!("km".parse::<LengthUnit>(), Ok(LengthUnit::Km));
        assert!("furlong".parse::<LengthUnit>().is_err());
    }
}
