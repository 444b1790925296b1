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
mod tests {
    use super::*;

    #[test]
    fn days_of_the_year_by_hand() {
        let day = |utc: &str| {
            SunSpec::At {
                utc: utc.to_owned(),
                latitude_deg: 0.0,
                longitude_deg: 0.0,
                altitude_m: 0.0,
                refraction: None,
                delta_t_s: None,
                delta_ut1_s: None,
            }
            .day_of_year()
        };
        assert_eq!(day("2024-01-01T00:00:00Z"), Some(1));
        assert_eq!(day("2023-03-01T12:00:00Z"), Some(60));
        // 2024 is a leap year: 31 + 29 + 1.
        assert_eq!(day("2024-03-01T12:00:00Z"), Some(61));
        assert_eq!(day("2024-06-21T12:00:00Z"), Some(173));
        assert_eq!(day("2024-12-31T12:00:00Z"), Some(366));
        // 1900 is not a leap year (divisible by 100), 2000 is (by 400).
        assert_eq!(day("1900-12-31T12:00:00Z"), Some(365));
        assert_eq!(day("2000-12-31T12:00:00Z"), Some(366));
        // Astronomical year 0 (1 BC) is a leap year; a time that does not parse has none.
        assert_eq!(day("-0000-12-31T00:00:00Z"), Some(366));
        assert_eq!(day("2024-06-21 12:00"), None);
        let direction = SunSpec::Direction {
            zenith_deg: 30.0,
            azimuth_deg: 180.0,
        };
        assert_eq!(direction.day_of_year(), None);
    }

    /// A [`SunSpec::At`] in short.
    #[derive(Clone, Copy)]
    struct Site {
        utc: &'static str,
        latitude_deg: f64,
        longitude_deg: f64,
        altitude_m: f64,
        refraction: Option<Refraction>,
        delta_t_s: Option<f64>,
        delta_ut1_s: Option<f64>,
    }

    impl Site {
        fn spec(self) -> SunSpec {
            SunSpec::At {
                utc: self.utc.into(),
                latitude_deg: self.latitude_deg,
                longitude_deg: self.longitude_deg,
                altitude_m: self.altitude_m,
                refraction: self.refraction,
                delta_t_s: self.delta_t_s,
                delta_ut1_s: self.delta_ut1_s,
            }
        }

        fn position(self) -> SunPosition {
            self.spec().position().unwrap()
        }
    }

    /// RIT, Rochester NY, at noon UTC on the 2026 June solstice, every option left out.
    const RIT: Site = Site {
        utc: "2026-06-21T12:00:00Z",
        latitude_deg: 43.08,
        longitude_deg: -77.67,
        altitude_m: 0.0,
        refraction: None,
        delta_t_s: None,
        delta_ut1_s: None,
    };

    /// The SPA paper's worked example: Reda & Andreas (2008 revision), Appendix A.5,
    /// Table A5.1, and NREL's spa_tester.c. 17 October 2003, 12:30:30 local time at UTC−7
    /// (19:30:30 UTC), 39.742476° N, 105.1786° W, 1830.14 m, 820 mbar, 11 °C, ΔT = 67 s,
    /// ΔUT1 = 0. The example's surface slope and azimuth rotation affect only its
    /// incidence angle.
    const SPA_EXAMPLE: Site = Site {
        utc: "2003-10-17T19:30:30Z",
        latitude_deg: 39.742476,
        longitude_deg: -105.1786,
        altitude_m: 1830.14,
        refraction: Some(Refraction {
            pressure_hpa: 820.0,
            temperature_c: 11.0,
        }),
        delta_t_s: Some(67.0),
        delta_ut1_s: Some(0.0),
    };

    /// The difference of two azimuths, degrees, in [0, 180].
    fn azimuth_difference(a: f64, b: f64) -> f64 {
        let d = (a - b).rem_euclid(360.0);
        d.min(360.0 - d)
    }

    /// The angle between the directions of two positions, degrees.
    fn angle_between(a: &SunPosition, b: &SunPosition) -> f64 {
        let (a, b) = (a.to_scene_direction(), b.to_scene_direction());
        let dot: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
        dot.clamp(-1.0, 1.0).acos().to_degrees()
    }

    #[test]
    fn the_spa_papers_worked_example() {
        let sun = SPA_EXAMPLE.position();
        assert!(sun.refracted);
        // Published: topocentric zenith (refracted) 50.111622°, azimuth 194.340241°
        // (spa_tester.c; the paper prints 50.11162° and 194.34024°). Rounded to 1e-6°;
        // SPA itself claims ±0.0003°.
        assert!((sun.zenith_deg - 50.111_622).abs() < 2e-6, "{sun:?}");
        assert!((sun.azimuth_deg - 194.340_241).abs() < 2e-6, "{sun:?}");
        // Refraction lifts the sun by SPA's eq. 42 at e0 ≈ 39.87° elevation, 820 mbar and
        // 11 °C: (820/1010)(283/284)·1.02/(60·tan(39.87° + 10.3°/44.98)) = 0.0163°.
        let lift = sun.geometric_zenith_deg - sun.zenith_deg;
        assert!((lift - 0.0163).abs() < 0.0003, "{lift}");
        let geometric = Site {
            refraction: None,
            ..SPA_EXAMPLE
        }
        .position();
        assert!(!geometric.refracted);
        assert!((geometric.zenith_deg - sun.geometric_zenith_deg).abs() < 1e-12);
        // Half a second of UT1 − UTC turns the Earth by 0.0021°: the sun moves by about
        // 0.0021°·cos δ (δ = −9.3°), several times SPA's 0.0003°.
        let later = Site {
            delta_ut1_s: Some(0.5),
            ..SPA_EXAMPLE
        }
        .position();
        let moved = angle_between(&later, &sun);
        assert!(
            (moved - 0.0021 * 9.31f64.to_radians().cos()).abs() < 2e-4,
            "{moved}"
        );
    }

    /// The zenith angle and azimuth where the sun crosses the meridian (`upper`: least
    /// zenith) or at its lower culmination (greatest zenith), found over the longitudes
    /// of a latitude at a fixed instant.
    fn culmination(utc: &'static str, latitude_deg: f64, upper: bool) -> (f64, f64) {
        let site = |longitude_deg| Site {
            utc,
            latitude_deg,
            longitude_deg,
            ..RIT
        };
        let zenith = |longitude: f64| {
            let z = site(longitude).position().zenith_deg;
            if upper { z } else { -z }
        };
        let best = (-180..180)
            .map(f64::from)
            .min_by(|&a, &b| zenith(a).total_cmp(&zenith(b)))
            .unwrap();
        // Golden-section search around the best whole degree.
        let (mut a, mut b) = ((best - 1.0).max(-180.0), (best + 1.0).min(180.0));
        let g = (5f64.sqrt() - 1.0) / 2.0;
        while b - a > 1e-9 {
            let (c, d) = (b - g * (b - a), a + g * (b - a));
            if zenith(c) < zenith(d) {
                b = d;
            } else {
                a = c;
            }
        }
        let sun = site(0.5 * (a + b)).position();
        (sun.zenith_deg, sun.azimuth_deg)
    }

    // Almanac values. The instants of the 2026 equinox and solstices are the U.S. Naval
    // Observatory's ("Earth's Seasons and Apsides"): March equinox 20 March 14:46 UT, June
    // solstice 21 June 08:24 UT, December solstice 21 December 20:50 UT. At a solstice
    // the sun's declination is ± the true obliquity of the ecliptic: 23.4359° (IAU 1976,
    // ε0 = 23°26′21.448″ − 46.815″·T, T = 0.265 century) plus the nutation in obliquity,
    // 9.20″·cos Ω = +0.0023° with the Moon's node Ω ≈ 333° in 2026: 23.4382°. At an
    // equinox it is 0 (it changes 0.016° an hour; the minute's rounding is 0.0002°). On
    // the meridian the zenith angle is |φ − δ| and at lower culmination 180° − |φ + δ|;
    // the topocentric parallax adds at most 8.8″·sin z = 0.0024°. RIT is at 43.08° N.
    const OBLIQUITY_2026_DEG: f64 = 23.4382;
    const ALMANAC_TOLERANCE_DEG: f64 = 0.003;

    #[test]
    fn the_june_solstice_sun_crosses_the_meridian_at_the_latitude_less_the_obliquity() {
        let utc = "2026-06-21T08:24:00Z";
        let (z, azimuth) = culmination(utc, 43.08, true);
        let want = 43.08 - OBLIQUITY_2026_DEG;
        assert!((z - want).abs() < ALMANAC_TOLERANCE_DEG, "{z} vs {want}");
        // Northern mid-latitudes: due south at noon.
        assert!(azimuth_difference(azimuth, 180.0) < 0.01, "{azimuth}");
        // The subsolar latitude: the sun overhead.
        let (z, _) = culmination(utc, OBLIQUITY_2026_DEG, true);
        assert!(z < ALMANAC_TOLERANCE_DEG, "{z}");
        // Sydney (33.87° S), midwinter noon: low in the north.
        let (z, azimuth) = culmination(utc, -33.87, true);
        let want = 33.87 + OBLIQUITY_2026_DEG;
        assert!((z - want).abs() < ALMANAC_TOLERANCE_DEG, "{z} vs {want}");
        assert!(azimuth_difference(azimuth, 0.0) < 0.01, "{azimuth}");
        // RIT at solar midnight: 23.48° below the northern horizon.
        let (z, azimuth) = culmination(utc, 43.08, false);
        let want = 180.0 - 43.08 - OBLIQUITY_2026_DEG;
        assert!((z - want).abs() < ALMANAC_TOLERANCE_DEG, "{z} vs {want}");
        assert!(azimuth_difference(azimuth, 0.0) < 0.01, "{azimuth}");
    }

    #[test]
    fn the_december_solstice_and_march_equinox_suns_cross_the_meridian_where_the_almanac_says() {
        let (z, azimuth) = culmination("2026-12-21T20:50:00Z", 43.08, true);
        let want = 43.08 + OBLIQUITY_2026_DEG;
        assert!((z - want).abs() < ALMANAC_TOLERANCE_DEG, "{z} vs {want}");
        assert!(azimuth_difference(azimuth, 180.0) < 0.01, "{azimuth}");
        let (z, azimuth) = culmination("2026-03-20T14:46:00Z", 43.08, true);
        assert!((z - 43.08).abs() < ALMANAC_TOLERANCE_DEG, "{z}");
        assert!(azimuth_difference(azimuth, 180.0) < 0.01, "{azimuth}");
        // On the equator at an equinox the noon sun is overhead.
        let (z, _) = culmination("2026-03-20T14:46:00Z", 0.0, true);
        assert!(z < ALMANAC_TOLERANCE_DEG, "{z}");
    }

    #[test]
    #[ignore = "prints the almanac table of docs/accuracy.md; run with --ignored --nocapture"]
    #[allow(clippy::print_stderr)]
    fn almanac_table() {
        let rows = [
            (
                "2026-06-21T08:24:00Z",
                43.08,
                true,
                43.08 - OBLIQUITY_2026_DEG,
            ),
            ("2026-06-21T08:24:00Z", OBLIQUITY_2026_DEG, true, 0.0),
            (
                "2026-06-21T08:24:00Z",
                -33.87,
                true,
                33.87 + OBLIQUITY_2026_DEG,
            ),
            (
                "2026-06-21T08:24:00Z",
                43.08,
                false,
                180.0 - 43.08 - OBLIQUITY_2026_DEG,
            ),
            (
                "2026-12-21T20:50:00Z",
                43.08,
                true,
                43.08 + OBLIQUITY_2026_DEG,
            ),
            ("2026-03-20T14:46:00Z", 43.08, true, 43.08),
            ("2026-03-20T14:46:00Z", 0.0, true, 0.0),
        ];
        for (utc, latitude, upper, almanac) in rows {
            let (z, _) = culmination(utc, latitude, upper);
            let parallax = 8.8 / 3600.0 * z.to_radians().sin();
            eprintln!(
                "| {utc} | {latitude}° | {almanac:.4} | {z:.4} | {:+.4} | {parallax:.4} |",
                z - almanac
            );
        }
    }

    #[test]
    fn the_default_delta_t_is_the_estimate() {
        // ΔT was 69.1 s in 2026 (IERS Bulletin A: TT − UTC = 69.184 s, UT1 − UTC ≈ 0);
        // the sun's ecliptic longitude moves 0.041° an hour, so a few seconds of ΔT are
        // far below SPA's 0.0003°, and a wrong default of minutes would show.
        let default = RIT.position();
        let given = Site {
            delta_t_s: Some(69.1),
            ..RIT
        }
        .position();
        assert!(angle_between(&default, &given) < 0.0001);
        let hour_off = Site {
            delta_t_s: Some(69.1 + 3600.0),
            ..RIT
        }
        .position();
        assert!(angle_between(&default, &hour_off) > 0.02);
        assert!(!default.refracted);
        assert!((default.zenith_deg - default.geometric_zenith_deg).abs() < 1e-12);
        // Eight in the morning at RIT: above the horizon, in the east.
        assert!(default.is_above_horizon());
        assert!(default.azimuth_deg > 45.0 && default.azimuth_deg < 90.0);
    }

    #[test]
    fn the_scene_direction_is_east_north_up() {
        let position = |zenith_deg, azimuth_deg| {
            SunSpec::Direction {
                zenith_deg,
                azimuth_deg,
            }
            .position()
            .unwrap()
        };
        let close = |got: [f64; 3], want: [f64; 3]| {
            assert!(
                got.iter().zip(want).all(|(g, w)| (g - w).abs() < 1e-12),
                "{got:?} vs {want:?}"
            );
        };
        let direction = |z, a| position(z, a).to_scene_direction();
        close(direction(0.0, 0.0), [0.0, 0.0, 1.0]);
        close(direction(0.0, 123.0), [0.0, 0.0, 1.0]);
        close(direction(90.0, 90.0), [1.0, 0.0, 0.0]);
        close(direction(90.0, 0.0), [0.0, 1.0, 0.0]);
        close(direction(90.0, 180.0), [0.0, -1.0, 0.0]);
        close(direction(90.0, 270.0), [-1.0, 0.0, 0.0]);
        let h = 0.5f64.sqrt();
        close(direction(45.0, 180.0), [0.0, -h, h]);
        close(direction(180.0, 0.0), [0.0, 0.0, -1.0]);
        for z in [0.0, 17.0, 89.9, 90.0, 135.0] {
            for a in [0.0, 45.0, 200.0, 359.9] {
                let [x, y, up] = direction(z, a);
                assert!(((x * x + y * y + up * up).sqrt() - 1.0).abs() < 1e-12);
            }
        }
        assert!(position(89.99, 0.0).is_above_horizon());
        assert!(!position(90.0, 0.0).is_above_horizon());
        assert!(!position(120.0, 0.0).is_above_horizon());
        assert!((position(30.0, 10.0).elevation_deg() - 60.0).abs() < 1e-12);
    }

    /// The field an error names, and its message; `validate` refuses alike.
    fn refusal(spec: &SunSpec) -> (&'static str, String) {
        let e = spec.position().unwrap_err();
        assert_eq!(spec.validate().unwrap_err(), e);
        match e.kind {
            AtmosphereErrorKind::Sun { field, message } => (field.path(), message),
            other => panic!("not a sun error: {other}"),
        }
    }

    #[test]
    fn each_bad_field_is_refused_by_name_with_its_range() {
        let air = |pressure_hpa, temperature_c| {
            Some(Refraction {
                pressure_hpa,
                temperature_c,
            })
        };
        let direction = |zenith_deg, azimuth_deg| SunSpec::Direction {
            zenith_deg,
            azimuth_deg,
        };
        let nan = f64::NAN;
        let cases = [
            (
                Site {
                    latitude_deg: 90.5,
                    ..RIT
                }
                .spec(),
                "latitude_deg",
                "[-90, 90]",
            ),
            (
                Site {
                    latitude_deg: nan,
                    ..RIT
                }
                .spec(),
                "latitude_deg",
                "NaN",
            ),
            (
                Site {
                    longitude_deg: -181.0,
                    ..RIT
                }
                .spec(),
                "longitude_deg",
                "[-180, 180]",
            ),
            (
                Site {
                    longitude_deg: f64::INFINITY,
                    ..RIT
                }
                .spec(),
                "longitude_deg",
                "inf",
            ),
            (
                Site {
                    altitude_m: 2e5,
                    ..RIT
                }
                .spec(),
                "altitude_m",
                "[-1000, 100000]",
            ),
            (
                Site {
                    altitude_m: nan,
                    ..RIT
                }
                .spec(),
                "altitude_m",
                "NaN",
            ),
            (
                Site {
                    refraction: air(0.0, 10.0),
                    ..RIT
                }
                .spec(),
                "refraction.pressure_hpa",
                "(0, 1100]",
            ),
            (
                Site {
                    refraction: air(nan, 10.0),
                    ..RIT
                }
                .spec(),
                "refraction.pressure_hpa",
                "NaN",
            ),
            (
                Site {
                    refraction: air(1000.0, -150.0),
                    ..RIT
                }
                .spec(),
                "refraction.temperature_c",
                "[-100, 60]",
            ),
            (
                Site {
                    delta_t_s: Some(nan),
                    ..RIT
                }
                .spec(),
                "delta_t_s",
                "finite",
            ),
            // 1e308 s was reported as an invalid `utc`, the flag not given wrongly.
            (
                Site {
                    delta_t_s: Some(1e308),
                    ..RIT
                }
                .spec(),
                "delta_t_s",
                "ΔT of 1",
            ),
            (
                Site {
                    delta_ut1_s: Some(1.2),
                    ..RIT
                }
                .spec(),
                "delta_ut1_s",
                "[-0.9, 0.9]",
            ),
            (direction(180.5, 0.0), "zenith_deg", "[0, 180]"),
            (direction(nan, 0.0), "zenith_deg", "NaN"),
            (direction(10.0, 360.0), "azimuth_deg", "[0, 360)"),
            (direction(10.0, -0.5), "azimuth_deg", "[0, 360)"),
            (direction(10.0, nan), "azimuth_deg", "NaN"),
        ];
        for (spec, want_field, want_text) in &cases {
            let (field, message) = refusal(spec);
            assert_eq!(field, *want_field, "{spec:?}: {message}");
            assert!(message.contains(want_text), "{spec:?}: {message}");
        }
        // The edges of each range are accepted.
        for (latitude_deg, longitude_deg) in [(90.0, 180.0), (-90.0, -180.0)] {
            Site {
                latitude_deg,
                longitude_deg,
                ..RIT
            }
            .position();
        }
        direction(180.0, 359.999).position().unwrap();
        direction(0.0, 0.0).position().unwrap();
    }

    #[test]
    fn a_time_that_does_not_parse_or_that_spa_does_not_cover_is_refused() {
        let cases = [
            ("2026-06-21 12:00:00Z", "YYYY-MM-DDTHH:MM:SS"),
            ("2026-06-21T12:00:00", "must end in `Z`"),
            ("2026-06-21T12:00:00+02:00", "must end in `Z`"),
            ("", "must end in `Z`"),
            ("2026-6-21T12:00:00Z", "not a UTC time"),
            ("2026-06-21T12:00Z", "not a UTC time"),
            ("2026-06-21T12:00:00.Z", "not a UTC time"),
            ("2026-06-21T12:00:0xZ", "not a UTC time"),
            ("2026-06-21T12:00:00:00Z", "not a UTC time"),
            ("+2026-06-21T12:00:00Z", "not a UTC time"),
            ("2026-13-01T00:00:00Z", "month"),
            ("2026-02-29T00:00:00Z", "day"),
            ("2026-06-21T24:00:00Z", "hour"),
            ("2026-06-21T12:60:00Z", "minute"),
            ("2016-12-31T23:59:60Z", "leap second"),
            ("6001-01-01T00:00:00Z", "-2000 to 6000"),
            ("-2001-12-31T00:00:00Z", "-2000 to 6000"),
        ];
        for (utc, want) in cases {
            let (field, message) = refusal(&Site { utc, ..RIT }.spec());
            assert_eq!(field, "utc", "{utc}: {message}");
            assert!(message.contains(want), "{utc}: {message}");
        }
        // Within SPA's years but not the ΔT estimate's: ΔT must be given.
        let far = Site {
            utc: "4000-01-01T00:00:00Z",
            ..RIT
        };
        let (field, message) = refusal(&far.spec());
        assert_eq!(field, "delta_t_s", "{message}");
        assert!(message.contains("give delta_t_s"), "{message}");
        // With it, SPA's ends are accepted.
        for utc in [
            "4000-01-01T00:00:00Z",
            "-2000-01-01T12:00:00Z",
            "6000-12-30T12:00:00Z",
        ] {
            Site {
                utc,
                delta_t_s: Some(0.0),
                ..RIT
            }
            .position();
        }
        // A leap day, and fractions of a second that count.
        Site {
            utc: "2024-02-29T23:59:59.999Z",
            ..RIT
        }
        .position();
        let half = Site {
            utc: "2026-06-21T12:00:00.5Z",
            ..RIT
        }
        .position();
        // Half a second: 0.0021°·cos δ (δ = 23.44°) of the Earth's turn.
        let moved = angle_between(&half, &RIT.position());
        assert!(
            (moved - 0.0021 * 23.44f64.to_radians().cos()).abs() < 2e-4,
            "{moved}"
        );
    }

    #[test]
    fn a_spec_reads_from_ron_and_refuses_unknown_fields() {
        let spec: SunSpec = ron::from_str(
            r#"At(utc: "2003-10-17T19:30:30Z", latitude_deg: 39.742476,
                  longitude_deg: -105.1786, altitude_m: 1830.14,
                  refraction: Some((pressure_hpa: 820, temperature_c: 11)), delta_t_s: Some(67))"#,
        )
        .unwrap();
        assert_eq!(
            spec,
            Site {
                delta_ut1_s: None,
                ..SPA_EXAMPLE
            }
            .spec()
        );
        let back: SunSpec = ron::from_str(&ron::to_string(&spec).unwrap()).unwrap();
        assert_eq!(back, spec);
        let spec: SunSpec = ron::from_str("Direction(zenith_deg: 30, azimuth_deg: 180)").unwrap();
        assert!((spec.position().unwrap().to_scene_direction()[1] + 0.5).abs() < 1e-12);
        assert!(ron::from_str::<SunSpec>("Direction(zenith_deg: 30, azimuth: 180)").is_err());
        assert!(
            ron::from_str::<SunSpec>(r#"At(utc: "2026-06-21T12:00:00Z", latitude_deg: 1)"#)
                .is_err()
        );
    }
}
