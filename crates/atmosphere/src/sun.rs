//! The sun's position in the sky of a scene: computed from a UTC time and a place with
//! NREL's Solar Position Algorithm, or given as a direction.
//!
//! The algorithm is SPA: I. Reda and A. Andreas, "Solar position algorithm for solar
//! radiation applications", Solar Energy 76(5), 577–589 (2004); NREL/TP-560-34302, revised
//! January 2008. It gives the topocentric zenith and azimuth of the centre of the sun's
//! disc to ±0.0003° for the years −2000 to 6000. The implementation is the
//! `solar-positioning` crate's, which reproduces NREL's reference program; this module
//! parses and checks what a user gives, picks ΔT, and turns the angles into the scene
//! frame (x east, y north, z up, as [`irsig_model::View`] positions are).
//!
//! Angles are in degrees at this boundary: zenith from the local vertical (0 = overhead,
//! 90 = horizon), azimuth clockwise from true north (90 = east, 180 = south), latitude
//! positive north, longitude positive east. Altitude is in metres above mean sea level.
//!
//! **Refraction.** Sunlight reaches the ground along a ray the air has bent, so the
//! direction it arrives from is the apparent (refracted) one. SPA's refraction term
//! (its eq. 42, for the site's pressure and temperature) was made for visible light, but
//! air's refractivity in the 8–14 µm window is within a few per cent of its visible value
//! (Mathar 2007, J. Opt. A 9, 470), so it serves the thermal infrared as well. It is applied only when the spec gives the
//! site's pressure and temperature ([`Refraction`]): a time and a place do not give them,
//! and a guessed standard atmosphere would hide an assumption. Without them the
//! direction is the geometric (topocentric, unrefracted) one. The two differ by less than
//! 0.06° above 15° elevation, a fifth of the sun's 0.27° radius, and by about 0.5° at
//! the horizon, where the air's transmission along the sun's path is small anyway.
//!
//! ```
//! use irsig_atmosphere::sun::SunSpec;
//! // Rochester, NY (RIT), at noon UTC on the 2026 June solstice.
//! let sun = SunSpec::At {
//!     utc: "2026-06-21T12:00:00Z".into(),
//!     latitude_deg: 43.08,
//!     longitude_deg: -77.67,
//!     altitude_m: 170.0,
//!     refraction: None,
//!     delta_t_s: None,
//!     delta_ut1_s: None,
//! };
//! let position = sun.position()?;
//! // Eight in the morning local time: low in the east.
//! assert!(position.is_above_horizon());
//! assert!(position.azimuth_deg > 60.0 && position.azimuth_deg < 90.0);
//! let [east, north, up] = position.to_scene_direction();
//! assert!(east > 0.5 && up > 0.3 && north.abs() < 0.3);
//! # Ok::<(), irsig_atmosphere::AtmosphereError>(())
//! ```

use irsig_formats::ParseError;
use irsig_formats::views::ViewSun;
use irsig_model::{LengthUnit, View};
use serde::{Deserialize, Serialize};
use solar_positioning::time::JulianDate;
use solar_positioning::{Location, RefractionCorrection, SolarPositions, delta_t};

use crate::{AtmosphereError, AtmosphereErrorKind};

/// The first year SPA covers (astronomical numbering: year 0 is 1 BC).
pub const SPA_FIRST_YEAR: i32 = -2000;
/// The last year SPA covers.
pub const SPA_LAST_YEAR: i32 = 6000;
/// The altitudes accepted for a site, metres above mean sea level: from below the Dead
/// Sea's shore (−430 m) to the edge of space.
pub const ALTITUDE_RANGE_M: [f64; 2] = [-1000.0, 100_000.0];
/// The pressures accepted for refraction, hPa (the highest sea-level pressure recorded
/// is 1084 hPa).
pub const PRESSURE_RANGE_HPA: [f64; 2] = [0.0, 1100.0];
/// The air temperatures accepted for refraction, °C (the extremes recorded are −89 °C and
/// 57 °C).
pub const TEMPERATURE_RANGE_C: [f64; 2] = [-100.0, 60.0];
/// |UT1 − UTC| is kept below 0.9 s by leap seconds.
pub const DELTA_UT1_MAX_S: f64 = 0.9;

const SECONDS_PER_DAY: f64 = 86_400.0;

/// A field of a [`SunSpec`]: what an error about the sun names, and what each caller
/// spells its own way (a view file by [`SunField::path`], a command line by a flag).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SunField {
    /// The time, UTC ([`SunSpec::At`]'s `utc`).
    Utc,
    /// The site's latitude, degrees.
    LatitudeDeg,
    /// The site's longitude, degrees.
    LongitudeDeg,
    /// The site's altitude above mean sea level, metres.
    AltitudeM,
    /// The site's air pressure for refraction, hPa.
    PressureHpa,
    /// The site's air temperature for refraction, °C.
    TemperatureC,
    /// ΔT = TT − UT1, seconds.
    DeltaTS,
    /// UT1 − UTC, seconds.
    DeltaUt1S,
    /// A given direction's zenith angle, degrees ([`SunSpec::Direction`]).
    ZenithDeg,
    /// A given direction's azimuth, degrees clockwise from north.
    AzimuthDeg,
}

impl SunField {
    /// Every field, in the order of [`SunSpec`]'s.
    pub const ALL: [Self; 10] = [
        Self::Utc,
        Self::LatitudeDeg,
        Self::LongitudeDeg,
        Self::AltitudeM,
        Self::PressureHpa,
        Self::TemperatureC,
        Self::DeltaTS,
        Self::DeltaUt1S,
        Self::ZenithDeg,
        Self::AzimuthDeg,
    ];

    /// Where the field is in a [`SunSpec`] as files write it: `latitude_deg`,
    /// `refraction.pressure_hpa`.
    #[must_use]
    pub fn path(self) -> &'static str {
        match self {
            Self::Utc => "utc",
            Self::LatitudeDeg => "latitude_deg",
            Self::LongitudeDeg => "longitude_deg",
            Self::AltitudeM => "altitude_m",
            Self::PressureHpa => "refraction.pressure_hpa",
            Self::TemperatureC => "refraction.temperature_c",
            Self::DeltaTS => "delta_t_s",
            Self::DeltaUt1S => "delta_ut1_s",
            Self::ZenithDeg => "zenith_deg",
            Self::AzimuthDeg => "azimuth_deg",
        }
    }

    /// Checks a number given for this field against the field's range, the rule
    /// [`SunSpec::validate`] applies to it (a caller that reads one value alone, a command
    /// line's flag, checks it here before it has the whole spec).
    ///
    /// # Errors
    /// The range and the value found, in words; for [`SunField::Utc`], which is a time and
    /// not a number, always ([`check_utc`] checks a time).
    pub fn check(self, value: f64) -> Result<(), String> {
        match self {
            Self::Utc => Err(format!(
                "expected a UTC time YYYY-MM-DDTHH:MM:SSZ, found the number {value}"
            )),
            Self::LatitudeDeg => in_range(value, -90.0, 90.0, "° (positive north)"),
            Self::LongitudeDeg => in_range(value, -180.0, 180.0, "° (positive east)"),
            Self::AltitudeM => {
                let [low, high] = ALTITUDE_RANGE_M;
                in_range(value, low, high, " m above sea level")
            }
            Self::PressureHpa => {
                let [low, high] = PRESSURE_RANGE_HPA;
                if value > low && value <= high {
                    Ok(())
                } else {
                    Err(format!(
                        "must be in ({low}, {high}] hPa (the local pressure), found {value}"
                    ))
                }
            }
            Self::TemperatureC => {
                let [low, high] = TEMPERATURE_RANGE_C;
                in_range(value, low, high, " °C")
            }
            Self::DeltaTS => {
                if value.is_finite() {
                    Ok(())
                } else {
                    Err(format!("must be a finite number of seconds, found {value}"))
                }
            }
            Self::DeltaUt1S => in_range(value, -DELTA_UT1_MAX_S, DELTA_UT1_MAX_S, " s (UT1 − UTC)"),
            Self::ZenithDeg => in_range(value, 0.0, 180.0, "° from the vertical"),
            Self::AzimuthDeg => {
                if (0.0..360.0).contains(&value) {
                    Ok(())
                } else {
                    Err(format!(
                        "must be in [0, 360)° clockwise from north, found {value}"
                    ))
                }
            }
        }
    }
}

/// Checks a UTC time as [`SunSpec::validate`] does: its form
/// (`YYYY-MM-DDTHH:MM:SS[.fraction]Z`), SPA's years and the calendar (no 30 February).
///
/// # Errors
/// What is wrong with the time, in words.
pub fn check_utc(utc: &str) -> Result<(), String> {
    utc_day(utc).map(|_| ())
}

/// The time `utc` as calendar fields and as SPA's Julian day, checked.
fn utc_day(utc: &str) -> Result<(UtcTime, JulianDate), String> {
    let when = parse_utc(utc)?;
    if !(SPA_FIRST_YEAR..=SPA_LAST_YEAR).contains(&when.year) {
        return Err(format!(
            "year {} of `{utc}` is outside SPA's years, {SPA_FIRST_YEAR} to {SPA_LAST_YEAR}",
            when.year
        ));
    }
    // The calendar first (month 13, 30 February): ΔT's estimate needs a month.
    let day = JulianDate::from_utc(
        when.year,
        when.month,
        when.day,
        when.hour,
        when.minute,
        when.second,
        0.0,
    )
    .map_err(|e| format!("`{utc}`: {e}"))?;
    Ok((when, day))
}

/// Where the sun is: computed from a time and a place, or given as a direction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum SunSpec {
    /// The sun seen from a place at a time, by SPA.
    At {
        /// The time, UTC, as `YYYY-MM-DDTHH:MM:SS[.fraction]Z` (ISO 8601; a leading `-`
        /// for years before year 0, astronomical numbering). Years −2000 to 6000. A leap
        /// second (`:60`) is refused: SPA's time is UT1, which has none.
        utc: String,
        /// Latitude, degrees, positive north, in [−90, 90].
        latitude_deg: f64,
        /// Longitude, degrees, positive east, in [−180, 180].
        longitude_deg: f64,
        /// The site's altitude, metres above mean sea level (its parallax); default 0.
        #[serde(default)]
        altitude_m: f64,
        /// The air at the site, to give the apparent (refracted) direction; without it
        /// the direction is geometric.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        refraction: Option<Refraction>,
        /// ΔT = TT − UT1, seconds. Default: the Espenak & Meeus estimate for the time's
        /// month (years −500 to 3000; about 69 s in 2026). Ten seconds of ΔT move the sun
        /// by about 0.0001°.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        delta_t_s: Option<f64>,
        /// UT1 − UTC, seconds, in [−0.9, 0.9] (IERS Bulletin A); default 0. Needed for
        /// SPA's 0.0003°: 0.9 s of Earth rotation moves the sun by up to 0.004°.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        delta_ut1_s: Option<f64>,
    },
    /// The sun's direction given as it is.
    Direction {
        /// Zenith angle, degrees from the local vertical, in [0, 180].
        zenith_deg: f64,
        /// Azimuth, degrees clockwise from north (90 = east), in [0, 360).
        azimuth_deg: f64,
    },
}

/// The air at a site, for SPA's refraction term (its eq. 42).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Refraction {
    /// Local (not sea-level) air pressure, hPa (= mbar), in (0, 1100].
    pub pressure_hpa: f64,
    /// Local air temperature, °C, in [−100, 60].
    pub temperature_c: f64,
}

/// The sun's position resolved: where the centre of its disc is in the local sky.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunPosition {
    /// Zenith angle of the direction light arrives from, degrees (0 = overhead, 90 =
    /// horizon, up to 180): apparent when [`refracted`](Self::refracted), otherwise
    /// geometric.
    pub zenith_deg: f64,
    /// The topocentric zenith angle without refraction, degrees.
    pub geometric_zenith_deg: f64,
    /// Azimuth, degrees clockwise from true north (90 = east, 180 = south), in [0, 360).
    pub azimuth_deg: f64,
    /// Whether `zenith_deg` includes atmospheric refraction.
    pub refracted: bool,
}

impl SunPosition {
    /// Elevation above the horizon, degrees: 90 − [`zenith_deg`](Self::zenith_deg).
    #[must_use]
    pub fn elevation_deg(&self) -> f64 {
        90.0 - self.zenith_deg
    }

    /// Whether the centre of the sun's disc is above the (flat, sea-level) horizon.
    #[must_use]
    pub fn is_above_horizon(&self) -> bool {
        self.zenith_deg < 90.0
    }

    /// The unit vector from the scene toward the sun in the scene frame, `[east, north,
    /// up]` (x east, y north, z up).
    #[must_use]
    pub fn to_scene_direction(&self) -> [f64; 3] {
        let (sin_z, cos_z) = self.zenith_deg.to_radians().sin_cos();
        let (sin_a, cos_a) = self.azimuth_deg.to_radians().sin_cos();
        [sin_z * sin_a, sin_z * cos_a, cos_z]
    }
}

impl SunSpec {
    /// Checks every field against its range, and the time against its form and SPA's
    /// years, without computing the position.
    ///
    /// # Errors
    /// [`AtmosphereErrorKind::Sun`], naming the field and its accepted range.
    pub fn validate(&self) -> Result<(), AtmosphereError> {
        self.resolve().map(|_| ())
    }

    /// The sun's position: by SPA for [`SunSpec::At`], as given for
    /// [`SunSpec::Direction`].
    ///
    /// # Errors
    /// [`AtmosphereErrorKind::Sun`], naming the field and its accepted range: a latitude,
    /// longitude, altitude, zenith or azimuth out of range or not a number, a time that
    /// does not parse or lies outside SPA's years, no ΔT given for a year the estimate
    /// does not cover.
    pub fn position(&self) -> Result<SunPosition, AtmosphereError> {
        match self.resolve()? {
            Resolved::At {
                time,
                location,
                altitude_m,
                refraction,
            } => {
                let prepared = SolarPositions::new()
                    .for_time_from_julian(time)
                    .map_err(|e| from_spa(&e))?;
                let geometric = prepared
                    .at(location, altitude_m, None)
                    .map_err(|e| from_spa(&e))?;
                let apparent = refraction
                    .map(|r| prepared.at(location, altitude_m, Some(r)))
                    .transpose()
                    .map_err(|e| from_spa(&e))?;
                Ok(SunPosition {
                    zenith_deg: apparent.unwrap_or(geometric).zenith_angle(),
                    geometric_zenith_deg: geometric.zenith_angle(),
                    azimuth_deg: geometric.azimuth(),
                    refracted: apparent.is_some(),
                })
            }
            Resolved::Direction {
                zenith_deg,
                azimuth_deg,
            } => Ok(SunPosition {
                zenith_deg,
                geometric_zenith_deg: zenith_deg,
                azimuth_deg,
                refracted: false,
            }),
        }
    }

    /// The day of the year of a [`SunSpec::At`]'s time, 1–366 (1 January is 1; the
    /// Gregorian leap rule), what LOWTRAN7's IDAY wants for the Sun–Earth distance. `None`
    /// for a [`SunSpec::Direction`], which has no date, or a time that does not parse.
    #[must_use]
    pub fn day_of_year(&self) -> Option<u16> {
        let Self::At { utc, .. } = self else {
            return None;
        };
        let when = parse_utc(utc).ok()?;
        let leap = (when.year % 4 == 0 && when.year % 100 != 0) || when.year % 400 == 0;
        const BEFORE: [u32; 12] = [0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334];
        let before = BEFORE.get(usize::try_from(when.month.checked_sub(1)?).ok()?)?;
        let day = before + when.day + u32::from(leap && when.month > 2);
        u16::try_from(day).ok()
    }

    /// The spec checked and turned into the algorithm's inputs.
    fn resolve(&self) -> Result<Resolved, AtmosphereError> {
        match self {
            Self::At {
                utc,
                latitude_deg,
                longitude_deg,
                altitude_m,
                refraction,
                delta_t_s,
                delta_ut1_s,
            } => {
                let (when, utc_day) = utc_day(utc).map_err(|m| sun_error(SunField::Utc, m))?;
                check(SunField::LatitudeDeg, *latitude_deg)?;
                check(SunField::LongitudeDeg, *longitude_deg)?;
                check(SunField::AltitudeM, *altitude_m)?;
                let refraction = refraction.map(Refraction::correction).transpose()?;
                let delta_t = match delta_t_s {
                    Some(s) => {
                        check(SunField::DeltaTS, *s)?;
                        *s
                    }
                    None => delta_t::estimate_from_date(when.year, when.month).map_err(|_| {
                        sun_error(
                            SunField::DeltaTS,
                            format!(
                                "no estimate of ΔT (TT − UT1) for year {} (the Espenak & Meeus estimate covers -500 to 3000): give delta_t_s",
                                when.year
                            ),
                        )
                    })?,
                };
                let delta_ut1 = delta_ut1_s.unwrap_or(0.0);
                check(SunField::DeltaUt1S, delta_ut1)?;
                // The time itself was accepted above: what fails now is the offsets, ΔT
                // when it was given (UT1 − UTC is under a second), checked here so that
                // `validate` refuses what `position` would.
                let offsets = |e: &solar_positioning::Error| match delta_t_s {
                    Some(_) => sun_error(
                        SunField::DeltaTS,
                        format!(
                            "ΔT of {delta_t:?} s puts `{utc}` outside the years SPA covers, \
                             {SPA_FIRST_YEAR} to {SPA_LAST_YEAR} ({e})"
                        ),
                    ),
                    None => from_spa(e),
                };
                let time =
                    JulianDate::new(utc_day.julian_date() + delta_ut1 / SECONDS_PER_DAY, delta_t)
                        .map_err(|e| offsets(&e))?;
                SolarPositions::new()
                    .for_time_from_julian(time)
                    .map_err(|e| offsets(&e))?;
                Ok(Resolved::At {
                    time,
                    location: Location {
                        latitude: *latitude_deg,
                        longitude: *longitude_deg,
                    },
                    altitude_m: *altitude_m,
                    refraction,
                })
            }
            Self::Direction {
                zenith_deg,
                azimuth_deg,
            } => {
                check(SunField::ZenithDeg, *zenith_deg)?;
                check(SunField::AzimuthDeg, *azimuth_deg)?;
                Ok(Resolved::Direction {
                    zenith_deg: *zenith_deg,
                    azimuth_deg: *azimuth_deg,
                })
            }
        }
    }
}

impl Refraction {
    fn correction(self) -> Result<RefractionCorrection, AtmosphereError> {
        check(SunField::PressureHpa, self.pressure_hpa)?;
        check(SunField::TemperatureC, self.temperature_c)?;
        RefractionCorrection::new(self.pressure_hpa, self.temperature_c).map_err(|e| from_spa(&e))
    }
}

/// What SPA is given, checked.
enum Resolved {
    At {
        time: JulianDate,
        location: Location,
        altitude_m: f64,
        refraction: Option<RefractionCorrection>,
    },
    Direction {
        zenith_deg: f64,
        azimuth_deg: f64,
    },
}

fn sun_error(field: SunField, message: String) -> AtmosphereError {
    AtmosphereErrorKind::Sun { field, message }.into()
}

/// [`SunField::check`] as the spec's error.
fn check(field: SunField, value: f64) -> Result<(), AtmosphereError> {
    field.check(value).map_err(|m| sun_error(field, m))
}

/// `value` in `[low, high]` (NaN is not).
fn in_range(value: f64, low: f64, high: f64, unit: &str) -> Result<(), String> {
    if (low..=high).contains(&value) {
        Ok(())
    } else {
        Err(format!("must be in [{low}, {high}]{unit}, found {value}"))
    }
}

/// The algorithm's own refusal, named by the field it concerns. Every input is checked
/// before SPA sees it, so this is a second line, not the usual path.
fn from_spa(e: &solar_positioning::Error) -> AtmosphereError {
    use solar_positioning::Error as E;
    let field = match e {
        E::InvalidLatitude { .. } => SunField::LatitudeDeg,
        E::InvalidLongitude { .. } => SunField::LongitudeDeg,
        E::InvalidHeight { .. } => SunField::AltitudeM,
        E::InvalidPressure { .. } => SunField::PressureHpa,
        E::InvalidTemperature { .. } => SunField::TemperatureC,
        _ => SunField::Utc,
    };
    sun_error(field, e.to_string())
}

/// A view file's views and its `sun`, if it has one
/// ([`irsig_formats::views::parse_views_and_sun`]), the sun checked as a flag's is: every
/// field in its range and the sun above the horizon, the field at fault reported at its
/// line and column.
///
/// # Errors
/// The views' own errors; a sun that is not a [`SunSpec`], has a field out of range or is
/// at or below the horizon; a sun in a list of views.
pub fn parse_views_and_sun(
    file: &str,
    text: &str,
    unit: LengthUnit,
) -> Result<(Vec<View>, Option<ViewSun<SunSpec>>), ParseError> {
    irsig_formats::views::parse_views_and_sun(file, text, unit, check_view_sun)
}

/// Keeps the one sun of a run's view files: `this` file's sun becomes `sun`, unless an
/// earlier file gave one already.
///
/// # Errors
/// A second sun, as a message naming both places.
pub fn keep_one_sun(
    sun: &mut Option<ViewSun<SunSpec>>,
    this: Option<ViewSun<SunSpec>>,
) -> Result<(), String> {
    match (sun.as_ref(), this) {
        (Some(first), Some(this)) => Err(format!(
            "{}: a second sun: the view file at {} gives one already; one sun lights a run",
            this.location, first.location
        )),
        (None, this @ Some(_)) => {
            *sun = this;
            Ok(())
        }
        (_, None) => Ok(()),
    }
}

/// A view file's sun checked as the flags' are: each field in its range and the sun above
/// the horizon, the field at fault named.
fn check_view_sun(spec: &SunSpec) -> Result<(), (String, String)> {
    let position = spec.position().map_err(|e| match e.kind {
        AtmosphereErrorKind::Sun { field, message } => (field.path().to_owned(), message),
        _ => (String::new(), e.to_string()),
    })?;
    if position.is_above_horizon() {
        return Ok(());
    }
    let field = match spec {
        SunSpec::Direction { .. } => "zenith_deg",
        SunSpec::At { .. } => "utc",
    };
    Err((
        field.to_owned(),
        format!(
            "the sun is {:.4} deg from the zenith, at or below the horizon: a sun below 90 deg \
             lights the scene; leave the sun out for a night",
            position.zenith_deg
        ),
    ))
}

/// The calendar fields of a UTC time.
#[derive(Debug, Clone, Copy, PartialEq)]
struct UtcTime {
    year: i32,
    month: u32,
    day: u32,
    hour: u32,
    minute: u32,
    second: f64,
}

/// Parses `YYYY-MM-DDTHH:MM:SS[.fraction]Z`, with an optional leading `-` on the year.
/// Only the form is checked here; SPA's `from_utc` checks the fields' ranges and the
/// calendar (30 February, 24:00).
fn parse_utc(text: &str) -> Result<UtcTime, String> {
    const FORM: &str =
        "expected a UTC time YYYY-MM-DDTHH:MM:SS[.fraction]Z, e.g. 2026-06-21T12:00:00Z";
    let bad = || format!("`{text}` is not a UTC time: {FORM}");
    let body = text.strip_suffix('Z').ok_or_else(|| {
        format!("`{text}` must end in `Z`: the time is UTC, without an offset; {FORM}")
    })?;
    let (date, time) = body.split_once('T').ok_or_else(bad)?;
    let (sign, date) = match date.strip_prefix('-') {
        Some(rest) => (-1, rest),
        None => (1, date),
    };
    let number = |part: Option<&str>, width: usize| -> Option<u32> {
        let part = part?;
        if part.len() == width && part.bytes().all(|b| b.is_ascii_digit()) {
            part.parse().ok()
        } else {
            None
        }
    };
    let mut fields = date.split('-');
    let year = number(fields.next(), 4).ok_or_else(bad)?;
    let month = number(fields.next(), 2).ok_or_else(bad)?;
    let day = number(fields.next(), 2).ok_or_else(bad)?;
    let mut clock = time.split(':');
    let hour = number(clock.next(), 2).ok_or_else(bad)?;
    let minute = number(clock.next(), 2).ok_or_else(bad)?;
    let seconds = clock.next().ok_or_else(bad)?;
    if fields.next().is_some() || clock.next().is_some() {
        return Err(bad());
    }
    let (whole, fraction) = seconds.split_once('.').unwrap_or((seconds, "0"));
    number(Some(whole), 2).ok_or_else(bad)?;
    if fraction.is_empty() || !fraction.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad());
    }
    let second: f64 = format!("{whole}.{fraction}").parse().map_err(|_| bad())?;
    if second >= 60.0 {
        return Err(format!(
            "`{text}`: second {second} is not in [0, 60): a leap second has no UT1 of its own, give the second before or after"
        ));
    }
    Ok(UtcTime {
        // At most 9999: four digits.
        year: sign * i32::try_from(year).map_err(|_| bad())?,
        month,
        day,
        hour,
        minute,
        second,
    })
}

#[cfg(test)]
mod tests;
