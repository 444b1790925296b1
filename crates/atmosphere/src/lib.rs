//! Atmosphere models for irsig: how much of a surface's radiance reaches the sensor, how
//! much the air adds on the way, and what the sky looks like (thesis §3.2, eq. 8–11,
//! Appendix E).
//!
//! An [`AtmosphereModel`] is built from a canonical [`irsig_model::Atmosphere`] and a
//! [`ModelKind`]:
//!
//! | kind | τ and L_u of a path | cost |
//! | --- | --- | --- |
//! | `none` | vacuum: τ = 1, L_u = 0, sky radiance 0 | nothing |
//! | `thesis` | `.cor` polynomial (eq. 10), `L_u·secθ` (eq. 11) | a few interpolations |
//! | `layered` | eq. 8–9 layer by layer, curve-of-growth slant scaling | one pass over the layers |
//! | `table` | LOWTRAN7 slant-path tables, bilinear, as corrections to `layered` | `layered` + two lookups |
//!
//! `docs/accuracy.md` measures each against LOWTRAN7's own slant paths; `table` is the
//! accurate default where the atmosphere has slant tables (the built-ins do).
//!
//! The sun is part of the sky: [`sun`] gives its position from a UTC time and a place
//! (NREL's SPA, ±0.0003°) or from a given direction, as angles and as a unit vector in the
//! scene frame (its altitudes are above sea level, not above the tables' ground).
//!
//! [`loads`] plans and assembles a day's broadband thermal loads at the ground from
//! LOWTRAN7 (direct and diffuse sunlight per sun zenith angle, the sky's longwave), what a
//! surface energy balance takes from the atmosphere.
//!
//! Conventions: altitudes in metres above the ground of the tables (scene z = 0), ranges in
//! metres, angles in degrees (nadir angle 0 = straight down, zenith angle 0 = straight up),
//! radiance in W m⁻² sr⁻¹. The Earth is flat for paths (plane-parallel layers, as the
//! scene is) and spherical only for the horizon ([`critical_nadir_angle_deg`]).
//!
//! ```
//! use irsig_atmosphere::{builtin, AtmosphereModel, ModelKind};
//! let atm = builtin("us-std-1976")?;
//! let model = AtmosphereModel::new(&atm, ModelKind::Table)?;
//! // A sensor 1 km up looking straight down at the ground.
//! let p = model.path(1000.0, 0.0, 1000.0);
//! assert!((p.transmission - 0.8195).abs() < 1e-3); // LOWTRAN7: 0.819461
//! assert!((p.path_radiance_w_m2_sr - 7.388).abs() < 0.01);
//! // The validation experiment's camera: 4.77 m above, 8.61 m from its target.
//! let p = model.path(4.77, 0.0, 8.61);
//! assert!(p.transmission > 0.98 && p.path_radiance_w_m2_sr < 1.0);
//! // What a sensor at the ground sees at 60° from the zenith.
//! assert!((model.sky_radiance(0.0, 60.0) - 16.224).abs() < 0.01);
//! # Ok::<(), irsig_atmosphere::AtmosphereError>(())
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]

mod builtin;
pub mod data_error;
mod earth;
mod error;
mod interp;
mod layered;
pub mod legacy;
pub mod loads;
pub mod plan;
mod precomputed;
pub mod refraction;
pub mod scattered;
mod sky;
pub mod slab;
pub mod solar;
mod spectral;
pub mod sun;
pub mod sunlit;
mod table;
mod thesis;

use std::fmt;
use std::str::FromStr;

use irsig_model::Atmosphere;
use serde::{Deserialize, Serialize};

pub use builtin::{
    BUILTIN_NAMES, BUILTIN_SPECTRAL_RANGES_UM, BUILTIN_TOP_M, STANDARD_MODELS, builtin,
    builtin_ron, builtin_spectral, builtin_spectral_bytes, builtin_spectral_bytes_over,
    builtin_spectral_mwir, builtin_spectral_mwir_bytes, builtin_spectral_over,
};
pub use earth::{
    EARTH_RADIUS_M, critical_nadir_angle_deg, range_to_ground_from_cos_m, range_to_ground_m,
};
pub use error::{AtmosphereError, AtmosphereErrorKind};
pub use layered::DEFAULT_CURVE_OF_GROWTH_EXPONENT;
pub use precomputed::{PrecomputedAtmosphere, SKY_LEVELS};
pub use sky::{
    APPENDIX_E_EXTRAPOLATE_FROM_DEG, APPENDIX_E_FIT_FROM_DEG, HEMISPHERIC_TOLERANCE,
    HemisphericSky, SkyView,
};
pub use spectral::{
    BandQuadrature, Collapser, SubBandCount, Transmissions, collapse, sub_band_edges,
};

use layered::{Profile, Slant};
use sky::GroundSky;

/// Which atmosphere model to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ModelKind {
    /// The 1990 model: `.cor` polynomial and `L_u·secθ` (eq. 10–11), with both path ends.
    Thesis,
    /// Eq. 8–9 layer by layer, between any two altitudes.
    Layered,
    /// Slant-path tables from the atmospheric model itself; the accurate default.
    Table,
    /// Vacuum: τ = 1, L_u = 0 and a black (0 K) sky.
    None,
}

impl ModelKind {
    /// All kinds, in the order they are listed to users.
    pub const ALL: [Self; 4] = [Self::Thesis, Self::Layered, Self::Table, Self::None];
    /// Their names, in the same order.
    pub const NAMES: [&'static str; 4] = ["thesis", "layered", "table", "none"];

    /// The name used in files and on command lines.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Thesis => Self::NAMES[0],
            Self::Layered => Self::NAMES[1],
            Self::Table => Self::NAMES[2],
            Self::None => Self::NAMES[3],
        }
    }
}

impl fmt::Display for ModelKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ModelKind {
    type Err = AtmosphereError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| AtmosphereErrorKind::UnknownModel(s.to_owned()).into())
    }
}

/// What the air does to radiance on one path: `L_sensor = transmission · L_surface +
/// path_radiance_w_m2_sr`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathTerms {
    /// Band transmittance of the path, 0 to 1.
    pub transmission: f64,
    /// Band path radiance the air along the path sends toward the sensor, W m⁻² sr⁻¹.
    pub path_radiance_w_m2_sr: f64,
}

impl PathTerms {
    /// A path through vacuum.
    pub const VACUUM: Self = Self {
        transmission: 1.0,
        path_radiance_w_m2_sr: 0.0,
    };

    /// The radiance at the sensor for `surface_radiance_w_m2_sr` leaving the far end.
    #[must_use]
    pub fn apply(&self, surface_radiance_w_m2_sr: f64) -> f64 {
        self.transmission * surface_radiance_w_m2_sr + self.path_radiance_w_m2_sr
    }
}

/// A path located in a model's grids ([`AtmosphereModel::locate_path`]), to be evaluated
/// in every model on the same grids ([`AtmosphereModel::path_along`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathGeometry(Located);

#[derive(Debug, Clone, Copy, PartialEq)]
enum Located {
    /// An end or the range is not finite: the terms are NaN.
    NonFinite,
    /// A path of no length, or no atmosphere: vacuum.
    Vacuum,
    /// The `thesis` model's path (it searches per band).
    Slant(Slant),
    /// The `layered` model's path and its levels.
    Layered(Slant, layered::Walk),
    /// The `table` model's path, its levels and its slant-grid cell.
    Table(Slant, table::TableWalk),
}

#[derive(Debug, Clone, PartialEq)]
enum Inner {
    None,
    Thesis(thesis::Thesis),
    Layered(Profile),
    /// Boxed: its slant tables make it several times the size of the others.
    Table(Box<table::Table>),
}

/// An atmosphere model the tracer asks for path terms and sky radiance. Cheap to query;
/// build it once per render. `Send + Sync`, no interior mutability: results depend only on
/// the arguments.
///
/// Non-finite arguments give NaN results; finite ones always give finite results, with
/// the transmission in [0, 1] and radiances ≥ 0.
#[derive(Debug, Clone, PartialEq)]
pub struct AtmosphereModel {
    inner: Inner,
    ground_sky: GroundSky,
    /// The data's own error per path, where a `table` model's slant tables record their
    /// interpolation residual.
    data_error: Option<data_error::DataError>,
}

impl AtmosphereModel {
    /// Builds the `kind` model over `atmosphere`.
    ///
    /// # Errors
    /// The atmosphere fails validation, lacks a table the model needs (`thesis`: the
    /// `.cor`; `table`: the slant tables), or its transmission grows with altitude.
    pub fn new(atmosphere: &Atmosphere, kind: ModelKind) -> Result<Self, AtmosphereError> {
        atmosphere.validate()?;
        let inner = match kind {
            ModelKind::None => Inner::None,
            ModelKind::Thesis => Inner::Thesis(thesis::Thesis::new(atmosphere)?),
            ModelKind::Layered => Inner::Layered(Profile::new(atmosphere)?),
            ModelKind::Table => Inner::Table(Box::new(table::Table::new(atmosphere)?)),
        };
        let ground_sky = GroundSky {
            zenith_deg: atmosphere.sky.iter().map(|r| r.0).collect(),
            radiance: atmosphere.sky.iter().map(|r| r.1).collect(),
            given_hemispheric: atmosphere.sky_hemispheric_w_m2_sr,
        };
        let data_error = match &inner {
            Inner::Table(t) => t
                .slant
                .interpolation_residual
                .zip(t.slant.nadir_deg.last().copied())
                .map(|(r, widest)| {
                    data_error::DataError::new(r, widest, &atmosphere.name, atmosphere.band_um)
                }),
            _ => None,
        };
        Ok(Self {
            inner,
            ground_sky,
            data_error,
        })
    }

    /// The model's kind.
    #[must_use]
    pub fn kind(&self) -> ModelKind {
        match self.inner {
            Inner::None => ModelKind::None,
            Inner::Thesis(_) => ModelKind::Thesis,
            Inner::Layered(_) => ModelKind::Layered,
            Inner::Table(_) => ModelKind::Table,
        }
    }

    /// The curve-of-growth exponent `p` of the layered slant scaling (`τ = exp(−u^p)`),
    /// fitted to the `.cor` or [`DEFAULT_CURVE_OF_GROWTH_EXPONENT`]; `None` for `none`.
    #[must_use]
    pub fn curve_of_growth_exponent(&self) -> Option<f64> {
        self.profile().map(|p| p.p)
    }

    /// The same model with the layered slant scaling's curve-of-growth exponent set to `p`
    /// (`1` is Beer's law per layer) instead of fitted; `p` is held to [0.1, 1]. For
    /// measuring the choice (docs/accuracy.md); `none` is returned unchanged.
    ///
    /// # Errors
    /// As [`AtmosphereModel::new`].
    pub fn with_curve_of_growth_exponent(
        self,
        atmosphere: &Atmosphere,
        p: f64,
    ) -> Result<Self, AtmosphereError> {
        let p = if p.is_finite() {
            p.clamp(0.1, 1.0)
        } else {
            DEFAULT_CURVE_OF_GROWTH_EXPONENT
        };
        let profile = Profile::with_exponent(atmosphere, Some(p))?;
        let inner = match self.inner {
            Inner::None => Inner::None,
            Inner::Layered(_) => Inner::Layered(profile),
            Inner::Thesis(mut t) => {
                t.profile = profile;
                Inner::Thesis(t)
            }
            Inner::Table(_) => {
                Inner::Table(Box::new(table::Table::with_profile(atmosphere, profile)?))
            }
        };
        Ok(Self { inner, ..self })
    }

    /// The widest nadir angle of the `table` model's slant rows, degrees (`None` for the
    /// other kinds). Past it, toward the horizon, the table's correction fades to none at
    /// 90° and a path to the ground is the plane-parallel layered one's, whose error
    /// against LOWTRAN7's spherical path grows to kelvins (docs/accuracy.md, "The last
    /// degrees to the horizon").
    #[must_use]
    pub fn widest_nadir_row_deg(&self) -> Option<f64> {
        match &self.inner {
            Inner::Table(t) => t.slant.nadir_deg.last().copied(),
            _ => None,
        }
    }

    /// The data's own error per path ([`data_error`]): `Some` for the `table` model of
    /// slant tables that record their interpolation residual (the built-ins'), `None` for
    /// the other kinds and for tables that record none (built and slab tables: their
    /// rows' error was never measured).
    #[must_use]
    pub fn data_error(&self) -> Option<data_error::DataError> {
        self.data_error
    }

    fn profile(&self) -> Option<&Profile> {
        match &self.inner {
            Inner::None => None,
            Inner::Thesis(t) => Some(&t.profile),
            Inner::Layered(p) => Some(p),
            Inner::Table(t) => Some(&t.profile),
        }
    }

    /// Transmission and path radiance of the straight path between a sensor at
    /// `sensor_altitude_m` and a point at `target_altitude_m`, `range_m` apart (metres;
    /// altitudes above the ground, below-ground values taken as 0; a range shorter than
    /// the altitude difference taken as that difference). The path radiance is what the
    /// air sends toward the sensor. A zero-length path is vacuum.
    #[must_use]
    pub fn path(&self, sensor_altitude_m: f64, target_altitude_m: f64, range_m: f64) -> PathTerms {
        self.path_along(&self.locate_path(sensor_altitude_m, target_altitude_m, range_m))
    }

    /// The grid searches of [`AtmosphereModel::path`] for a path: where its ends lie among
    /// the levels and where it lies in the slant tables. A spectral rendering asks every
    /// sub-band for the same path; their models share these grids
    /// ([`AtmosphereModel::shares_path_grids`]), so the path is located once and evaluated
    /// in each ([`AtmosphereModel::path_along`]).
    #[must_use]
    pub fn locate_path(
        &self,
        sensor_altitude_m: f64,
        target_altitude_m: f64,
        range_m: f64,
    ) -> PathGeometry {
        if !(sensor_altitude_m.is_finite() && target_altitude_m.is_finite() && range_m.is_finite())
        {
            return PathGeometry(Located::NonFinite);
        }
        let Some(s) = Slant::new(sensor_altitude_m, target_altitude_m, range_m) else {
            return PathGeometry(Located::Vacuum);
        };
        PathGeometry(match &self.inner {
            Inner::None => Located::Vacuum,
            Inner::Thesis(_) => Located::Slant(s),
            Inner::Layered(p) => Located::Layered(s, p.walk(&s)),
            Inner::Table(t) => Located::Table(s, t.walk(&s)),
        })
    }

    /// [`AtmosphereModel::path`] of a path located by this model or by one that shares its
    /// grids ([`AtmosphereModel::shares_path_grids`]): the same terms, bit for bit. A path
    /// located by a model of another kind is located again here; one located in other
    /// grids of the same kind gives other (finite, but wrong) terms.
    #[must_use]
    pub fn path_along(&self, geometry: &PathGeometry) -> PathTerms {
        let s = match &geometry.0 {
            Located::NonFinite => {
                return PathTerms {
                    transmission: f64::NAN,
                    path_radiance_w_m2_sr: f64::NAN,
                };
            }
            Located::Vacuum => return PathTerms::VACUUM,
            Located::Slant(s) | Located::Layered(s, _) | Located::Table(s, _) => s,
        };
        match (&self.inner, &geometry.0) {
            (Inner::None, _) => PathTerms::VACUUM,
            (Inner::Thesis(t), _) => t.path(s),
            (Inner::Layered(p), Located::Layered(_, w)) => p.along(w),
            (Inner::Layered(p), _) => p.path(s),
            (Inner::Table(t), Located::Table(_, w)) => t.along(w),
            (Inner::Table(t), _) => t.path(s),
        }
    }

    /// Whether a path located by this model ([`AtmosphereModel::locate_path`]) is located
    /// for `other` too: the same kind on the same levels and slant grid, as the sub-bands
    /// collapsed from one spectral atmosphere are.
    #[must_use]
    pub fn shares_path_grids(&self, other: &Self) -> bool {
        match (&self.inner, &other.inner) {
            (Inner::None, Inner::None) | (Inner::Thesis(_), Inner::Thesis(_)) => true,
            (Inner::Layered(a), Inner::Layered(b)) => a.z_m == b.z_m,
            (Inner::Table(a), Inner::Table(b)) => a.shares_grids(b),
            _ => false,
        }
    }

    /// Sky radiance in W m⁻² sr⁻¹ seen from `observer_altitude_m` at `zenith_deg` (0 = up):
    /// the path radiance from the observer to space. From the ground it is the `.dwr`
    /// interpolated by a monotone cubic in angle (zenith angles past 90° see the ground's horizon: the 90°
    /// value). From above the ground, `thesis` and `layered` sum the layered profile
    /// above the observer and the air above the profile's top (sized so the ground sky is
    /// reproduced) up to 83°, and extrapolate beyond by the Appendix E quadratic fitted
    /// over 60–83°; `table`
    /// interpolates its sky table up to its last angle (90°) and extrapolates beyond (rays
    /// below the horizontal that still miss the Earth) by an Appendix E least-squares
    /// quadratic fitted over its last 10°, where the radiance climbs steeply. Angles
    /// are clamped to 180° − [`critical_nadir_angle_deg`]. `none` gives 0 (a black sky).
    ///
    /// This fits a quadratic per call past 83°; a tracer should build a [`SkyView`] once
    /// per observer altitude with [`AtmosphereModel::sky_view`].
    #[must_use]
    pub fn sky_radiance(&self, observer_altitude_m: f64, zenith_deg: f64) -> f64 {
        if !(observer_altitude_m.is_finite() && zenith_deg.is_finite()) {
            return f64::NAN;
        }
        let h = observer_altitude_m.max(0.0);
        let z = zenith_deg.clamp(0.0, 180.0 - critical_nadir_angle_deg(h));
        match &self.inner {
            Inner::None => 0.0,
            Inner::Table(t) => {
                let last = t.slant.sky_zenith_deg.last().copied().unwrap_or(90.0);
                if z <= last {
                    t.sky(h, z)
                } else {
                    let points: Vec<(f64, f64)> = t
                        .slant
                        .sky_zenith_deg
                        .iter()
                        .filter(|&&a| a >= last - 10.0)
                        .map(|&a| (a, t.sky(h, a)))
                        .collect();
                    interp::fit_quadratic(&points)
                        .map_or_else(|| t.sky(h, last), |q| q.at(z).max(0.0))
                }
            }
            _ if h <= 0.0 => self.ground_sky.at(z),
            _ => sky::with_appendix_e(z, |zz| self.sky_above_ground(h, zz)),
        }
    }

    /// Sky radiance from `h > 0` at `zenith_deg ≤ 90` for `thesis` and `layered`: the
    /// layered profile above the observer plus the air above the profile's top, sized to
    /// reproduce the ground sky (see `Profile::sky`).
    fn sky_above_ground(&self, h: f64, zenith_deg: f64) -> f64 {
        let ground = self.ground_sky.at(zenith_deg);
        let m = 1.0 / zenith_deg.to_radians().cos().max(1e-9);
        match self.profile() {
            Some(p) => p.sky(h, m, ground),
            None => 0.0,
        }
    }

    /// The angular sky radiance seen from `observer_altitude_m`, precomputed for cheap
    /// lookups (0.25° grid, linear).
    #[must_use]
    pub fn sky_view(&self, observer_altitude_m: f64) -> SkyView {
        let h = observer_altitude_m.max(0.0);
        let max_zenith = 180.0 - critical_nadir_angle_deg(h);
        let fit = |lo: f64| -> Option<interp::Quadratic> {
            let pts: Vec<(f64, f64)> = (60..=83)
                .map(f64::from)
                .filter(|&a| a >= lo)
                .map(|a| (a, self.sky_radiance(h, a)))
                .collect();
            interp::fit_quadratic(&pts)
        };
        // Past 83° the per-call path refits the same quadratic; fit it once here.
        match &self.inner {
            Inner::Thesis(_) | Inner::Layered(_) if h > 0.0 => {
                let q = fit(APPENDIX_E_FIT_FROM_DEG);
                SkyView::build(h, max_zenith, |z| {
                    if z <= APPENDIX_E_EXTRAPOLATE_FROM_DEG {
                        self.sky_above_ground(h, z)
                    } else {
                        q.map_or_else(
                            || self.sky_above_ground(h, APPENDIX_E_EXTRAPOLATE_FROM_DEG),
                            |q| q.at(z).max(0.0),
                        )
                    }
                })
            }
            _ => SkyView::build(h, max_zenith, |z| self.sky_radiance(h, z)),
        }
    }

    /// The hemispheric sky radiance at `observer_altitude_m` (see [`HemisphericSky`]):
    /// the atmosphere's given value when it has one (the `.dwr` row `-1`, at the ground;
    /// above the ground scaled by the ratio of eq. 5 there to eq. 5 at the ground), else
    /// eq. 5 applied to [`AtmosphereModel::sky_radiance`]. When both a given and a computed
    /// ground value exist and differ by more than [`HEMISPHERIC_TOLERANCE`], `warning` says
    /// so. `none` gives 0.
    #[must_use]
    pub fn sky_hemispheric(&self, observer_altitude_m: f64) -> HemisphericSky {
        let h = observer_altitude_m.max(0.0);
        let ground = matches!(self.inner, Inner::Table(_)).then(|| self.sky_view(0.0));
        let here = (h > 0.0 && !matches!(self.inner, Inner::None)).then(|| self.sky_view(h));
        self.sky_hemispheric_from(ground.as_ref(), here.as_ref())
    }

    /// [`AtmosphereModel::sky_hemispheric`] from sky views already computed: `ground`
    /// at 0 m (needed by the `table` model only) and `here` at the observer's altitude
    /// (`None` at the ground). [`PrecomputedAtmosphere`] computes each view once.
    pub(crate) fn sky_hemispheric_from(
        &self,
        ground: Option<&SkyView>,
        here: Option<&SkyView>,
    ) -> HemisphericSky {
        if matches!(self.inner, Inner::None) {
            return HemisphericSky {
                radiance_w_m2_sr: 0.0,
                given_w_m2_sr: None,
                computed_w_m2_sr: 0.0,
                warning: None,
            };
        }
        let computed_ground = match (&self.inner, ground) {
            (Inner::Table(_), Some(view)) => view.hemispheric(),
            (Inner::Table(_), None) => self.sky_view(0.0).hemispheric(),
            _ => self.ground_sky.computed_hemispheric(),
        };
        let computed = here.map_or(computed_ground, SkyView::hemispheric);
        let given = self.ground_sky.given_hemispheric;
        let warning = given.and_then(|g| {
            let difference = (computed_ground - g).abs();
            let rel = difference / g.abs().max(1e-300);
            (rel > HEMISPHERIC_TOLERANCE).then(|| {
                // A given 0 makes any difference infinitely many per cent: say it in
                // radiance instead.
                let by = if g == 0.0 {
                    format!("{difference:.4e} W m^-2 sr^-1 (the given value is 0)")
                } else {
                    format!("{:.1} %", rel * 100.0)
                };
                format!(
                    "the hemispheric sky radiance given ({g:.4} W m^-2 sr^-1) and eq. 5 applied to the angular sky table ({computed_ground:.4}) differ by {by}; using the given value"
                )
            })
        });
        let radiance = match given {
            Some(g) if computed_ground > 0.0 => g * computed / computed_ground,
            Some(g) => g,
            None => computed,
        };
        HemisphericSky {
            radiance_w_m2_sr: radiance,
            given_w_m2_sr: given,
            computed_w_m2_sr: computed,
            warning,
        }
    }

    /// [`critical_nadir_angle_deg`], for callers holding a model.
    #[must_use]
    pub fn critical_nadir_angle_deg(&self, sensor_altitude_m: f64) -> f64 {
        critical_nadir_angle_deg(sensor_altitude_m)
    }
}
