//! A weather record: the air's temperature, humidity, pressure and wind, the sky's cover and
//! the measured radiation, at a sequence of times, and the place it was measured. What the
//! thermal model (`irsig-therm`) drives a surface's heat balance with.
//!
//! Plain data, its rules ([`Weather::validate`]) and its interpolation ([`Weather::at`]);
//! the file forms (EPW, CSV with a unit header) are read by `irsig_formats::weather`. Two
//! small pure functions live here because every reader and the thermal model need the same
//! ones: the calendar ([`utc_seconds`], [`format_utc`]) and the dew point from relative
//! humidity ([`dew_point_from_relative_humidity`]), kept in one place so that the reader
//! stores what a file gives and the thermal model derives the rest the same way.
//!
//! ```
//! use irsig_model::weather::{RadiationSampling, Weather, WeatherRecord, utc_seconds};
//! let t0 = utc_seconds(2001, 8, 7, 18, 0, 0.0).unwrap();
//! let record = |t: f64, air_k: f64| WeatherRecord {
//!     air_temperature_k: air_k,
//!     ..WeatherRecord::calm(t, 280.0, 83_500.0)
//! };
//! let w = Weather {
//!     site: None,
//!     records: vec![record(t0, 300.0), record(t0 + 3600.0, 302.0)],
//!     radiation: RadiationSampling::default(),
//!     source: "example".into(),
//! };
//! w.validate().unwrap();
//! let c = w.at(t0 + 900.0).unwrap();
//! assert!((c.air_temperature_k - 300.5).abs() < 1e-12);
//! assert!(w.at(t0 + 7200.0).is_err(), "never extrapolated");
//! ```

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_range};

/// The longest step between records accepted, as a multiple of the record's median step.
pub const MAX_GAP_MEDIAN_STEPS: f64 = 3.0;
/// The longest step between records accepted whatever the median step, seconds (6 h): an
/// afternoon's heating is lost in a longer one.
pub const MAX_GAP_S: f64 = 6.0 * 3600.0;
/// Air (and dew-point) temperatures accepted, K: −123 °C to 77 °C, wider than any
/// measured at the surface (−89.2 °C, Vostok; 56.7 °C, Death Valley).
pub const AIR_TEMPERATURE_K: [f64; 2] = [150.0, 350.0];
/// Station pressures accepted, Pa: 30–110 kPa (Everest's summit is about 33 kPa).
pub const PRESSURE_PA: [f64; 2] = [30_000.0, 110_000.0];
/// Wind speeds accepted, m/s (the highest measured gust is 113 m/s).
pub const MAX_WIND_SPEED_M_S: f64 = 100.0;
/// Irradiances accepted, W/m² (the solar constant is 1361 W/m²).
pub const MAX_IRRADIANCE_W_M2: f64 = 2000.0;
/// Relative humidities accepted, as a fraction: up to 1.1, the EnergyPlus weather
/// format's own limit (a hygrometer near saturation reads a little over 100 %).
pub const MAX_RELATIVE_HUMIDITY: f64 = 1.1;

/// A weather record: where, when and what.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Weather {
    /// Where it was measured, when the file says (EPW does; the CSV form does not).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub site: Option<Site>,
    /// The records, strictly increasing in time: at least two.
    pub records: Vec<WeatherRecord>,
    /// How each radiation column was sampled: at its time stamp, or as a mean over the
    /// interval that ends there.
    #[serde(default)]
    pub radiation: RadiationSampling,
    /// Where the numbers come from (the file, its station, its data set).
    pub source: String,
}

/// The place a weather record was measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Site {
    /// The station's name.
    pub name: String,
    /// Latitude, degrees, north positive: −90 to 90.
    pub latitude_deg: f64,
    /// Longitude, degrees, east positive: −180 to 180.
    pub longitude_deg: f64,
    /// Elevation above sea level, m: −1000 to 9000.
    pub elevation_m: f64,
    /// The offset of the file's local standard time from UTC, hours (−7 for Colorado):
    /// −12 to 14. The record's times are UTC whatever it is; this says what "local" meant.
    pub utc_offset_h: f64,
}

/// One record: the conditions at one time. Temperatures in K, pressure in Pa, speeds in
/// m/s, directions in degrees, fractions 0 to 1, irradiances in W/m².
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WeatherRecord {
    /// Seconds since 1970-01-01T00:00:00Z (UTC, no leap seconds): the time stamp.
    pub time_s: f64,
    /// Air (dry-bulb) temperature, K.
    pub air_temperature_k: f64,
    /// Dew-point temperature, K, when the file gives it. A record needs it or
    /// [`relative_humidity`](Self::relative_humidity).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dew_point_k: Option<f64>,
    /// Station (not sea-level) pressure, Pa.
    pub pressure_pa: f64,
    /// Wind speed, m/s.
    pub wind_speed_m_s: f64,
    /// The direction the wind blows from, degrees clockwise from north, 0 to 360.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wind_direction_deg: Option<f64>,
    /// The share of the sky covered by cloud, 0 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cloud_cover: Option<f64>,
    /// Relative humidity over water, as a fraction (0.5 is 50 %), up to
    /// [`MAX_RELATIVE_HUMIDITY`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub relative_humidity: Option<f64>,
    /// Global horizontal irradiance, W/m².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ghi_w_m2: Option<f64>,
    /// Direct normal irradiance (the sun's beam on a surface facing it), W/m².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dni_w_m2: Option<f64>,
    /// Diffuse horizontal irradiance (the sky without the sun's disk), W/m².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dhi_w_m2: Option<f64>,
    /// Downwelling longwave (thermal-infrared) irradiance on a horizontal surface, W/m².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub longwave_down_w_m2: Option<f64>,
}

/// How a column's values relate to their time stamps.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Sampling {
    /// The value at the time stamp.
    #[default]
    Instantaneous,
    /// The mean over the interval of `interval_s` seconds that ends at the time stamp (an
    /// hourly file's radiation: EPW and TMY3 give the energy received in the hour before
    /// the stamp). The value belongs to the middle of its interval.
    PrecedingMean {
        /// The interval, s: above 0, at most a day.
        interval_s: f64,
    },
}

/// How each radiation column was sampled. The other columns (temperatures, humidity,
/// pressure, wind, cloud) are always instantaneous.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RadiationSampling {
    /// [`WeatherRecord::ghi_w_m2`].
    #[serde(default)]
    pub ghi: Sampling,
    /// [`WeatherRecord::dni_w_m2`].
    #[serde(default)]
    pub dni: Sampling,
    /// [`WeatherRecord::dhi_w_m2`].
    #[serde(default)]
    pub dhi: Sampling,
    /// [`WeatherRecord::longwave_down_w_m2`].
    #[serde(default)]
    pub longwave_down: Sampling,
}

impl RadiationSampling {
    /// Every radiation column sampled alike.
    #[must_use]
    pub fn all(sampling: Sampling) -> Self {
        Self {
            ghi: sampling,
            dni: sampling,
            dhi: sampling,
            longwave_down: sampling,
        }
    }
}

/// The conditions at one moment, interpolated from a [`Weather`] record by [`Weather::at`].
/// Units as [`WeatherRecord`]'s.
#[derive(Debug, Clone, PartialEq)]
pub struct Conditions {
    /// The moment, s since 1970-01-01T00:00:00Z.
    pub time_s: f64,
    /// Air temperature, K.
    pub air_temperature_k: f64,
    /// Dew point, K: the record's, or derived from its relative humidity by
    /// [`dew_point_from_relative_humidity`] where it gives none.
    pub dew_point_k: f64,
    /// Station pressure, Pa.
    pub pressure_pa: f64,
    /// Wind speed, m/s.
    pub wind_speed_m_s: f64,
    /// Wind direction, degrees from north, 0 to 360.
    pub wind_direction_deg: Option<f64>,
    /// Cloud cover, 0 to 1.
    pub cloud_cover: Option<f64>,
    /// Relative humidity, a fraction.
    pub relative_humidity: Option<f64>,
    /// Global horizontal irradiance, W/m².
    pub ghi_w_m2: Option<f64>,
    /// Direct normal irradiance, W/m².
    pub dni_w_m2: Option<f64>,
    /// Diffuse horizontal irradiance, W/m².
    pub dhi_w_m2: Option<f64>,
    /// Downwelling longwave irradiance, W/m².
    pub longwave_down_w_m2: Option<f64>,
}

/// Why a weather record cannot give the conditions asked for.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{kind}")]
pub struct WeatherError {
    /// What went wrong.
    pub kind: WeatherErrorKind,
}

/// What went wrong asking a weather record for a moment.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum WeatherErrorKind {
    /// The moment lies outside the record: it is never extrapolated or clamped.
    OutsideRecord {
        /// The moment asked for, s since 1970-01-01T00:00:00Z.
        time_s: f64,
        /// The record's first time stamp.
        first_s: f64,
        /// The record's last time stamp.
        last_s: f64,
    },
    /// The moment is NaN or infinite.
    NotFinite,
    /// The record has fewer than two records, or a record gives neither a dew point nor a
    /// relative humidity above 0: [`Weather::validate`] refuses both.
    Invalid(String),
}

impl std::fmt::Display for WeatherErrorKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::OutsideRecord {
                time_s,
                first_s,
                last_s,
            } => write!(
                f,
                "{} is outside the weather record, which runs from {} to {}: a record is \
                 never extrapolated; give weather that covers the run (its spin-up too)",
                format_utc(*time_s),
                format_utc(*first_s),
                format_utc(*last_s)
            ),
            Self::NotFinite => write!(f, "the time asked for is not a finite number"),
            Self::Invalid(why) => write!(f, "the weather record is not valid: {why}"),
        }
    }
}

impl WeatherRecord {
    /// A record of still, dry-ish air at `time_s`: the given air temperature and pressure,
    /// a dew point 10 K below the air, no wind, no other column. A starting point for
    /// tests and examples (`..WeatherRecord::calm(t, 290.0, 101_325.0)`).
    #[must_use]
    pub fn calm(time_s: f64, air_temperature_k: f64, pressure_pa: f64) -> Self {
        Self {
            time_s,
            air_temperature_k,
            dew_point_k: Some(air_temperature_k - 10.0),
            pressure_pa,
            wind_speed_m_s: 0.0,
            wind_direction_deg: None,
            cloud_cover: None,
            relative_humidity: None,
            ghi_w_m2: None,
            dni_w_m2: None,
            dhi_w_m2: None,
            longwave_down_w_m2: None,
        }
    }

    /// The record's dew point: the file's, else derived from its relative humidity.
    #[must_use]
    pub fn dew_point_or_derived_k(&self) -> Option<f64> {
        self.dew_point_k.or_else(|| {
            self.relative_humidity
                .and_then(|rh| dew_point_from_relative_humidity(self.air_temperature_k, rh))
        })
    }

    /// Checks every number of the record against its physical range.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix` (`records[3]`).
    pub fn validate(&self, prefix: &str) -> Result<(), ModelError> {
        let [t_min, t_max] = AIR_TEMPERATURE_K;
        check_range(|| format!("{prefix}.time_s"), self.time_s, -1e12, 1e12)?;
        check_range(
            || format!("{prefix}.air_temperature_k"),
            self.air_temperature_k,
            t_min,
            t_max,
        )?;
        if let Some(d) = self.dew_point_k {
            check_range(|| format!("{prefix}.dew_point_k"), d, t_min, t_max)?;
        }
        let [p_min, p_max] = PRESSURE_PA;
        check_range(
            || format!("{prefix}.pressure_pa"),
            self.pressure_pa,
            p_min,
            p_max,
        )?;
        check_range(
            || format!("{prefix}.wind_speed_m_s"),
            self.wind_speed_m_s,
            0.0,
            MAX_WIND_SPEED_M_S,
        )?;
        let optional = [
            ("wind_direction_deg", self.wind_direction_deg, 360.0),
            ("cloud_cover", self.cloud_cover, 1.0),
            (
                "relative_humidity",
                self.relative_humidity,
                MAX_RELATIVE_HUMIDITY,
            ),
            ("ghi_w_m2", self.ghi_w_m2, MAX_IRRADIANCE_W_M2),
            ("dni_w_m2", self.dni_w_m2, MAX_IRRADIANCE_W_M2),
            ("dhi_w_m2", self.dhi_w_m2, MAX_IRRADIANCE_W_M2),
            (
                "longwave_down_w_m2",
                self.longwave_down_w_m2,
                MAX_IRRADIANCE_W_M2,
            ),
        ];
        for (name, value, max) in optional {
            if let Some(v) = value {
                check_range(|| format!("{prefix}.{name}"), v, 0.0, max)?;
            }
        }
        if self.dew_point_or_derived_k().is_none() {
            let (field, why) = if self.relative_humidity.is_some() {
                (
                    "relative_humidity",
                    "a relative humidity of 0 gives no dew point, and the record has none",
                )
            } else {
                (
                    "dew_point_k",
                    "the record gives neither a dew point nor a relative humidity: the air's \
                     humidity is needed (latent heat, the sky's longwave)",
                )
            };
            return Err(ModelError::new(
                format!("{prefix}.{field}"),
                ModelErrorKind::Other(why.into()),
            ));
        }
        Ok(())
    }
}

impl Sampling {
    fn validate(self, path: impl Fn() -> String) -> Result<(), ModelError> {
        match self {
            Self::Instantaneous => Ok(()),
            Self::PrecedingMean { interval_s } => check_range(path, interval_s, 1e-3, 86_400.0),
        }
    }

    /// How far before its time stamp a value belongs: half its interval for a mean.
    fn offset_s(self) -> f64 {
        match self {
            Self::Instantaneous => 0.0,
            Self::PrecedingMean { interval_s } => interval_s / 2.0,
        }
    }
}

impl Site {
    /// Checks the site's numbers.
    ///
    /// # Errors
    /// The first rule broken, with its path below `prefix`.
    pub fn validate(&self, prefix: &str) -> Result<(), ModelError> {
        check_range(
            || format!("{prefix}.latitude_deg"),
            self.latitude_deg,
            -90.0,
            90.0,
        )?;
        check_range(
            || format!("{prefix}.longitude_deg"),
            self.longitude_deg,
            -180.0,
            180.0,
        )?;
        check_range(
            || format!("{prefix}.elevation_m"),
            self.elevation_m,
            -1000.0,
            9000.0,
        )?;
        check_range(
            || format!("{prefix}.utc_offset_h"),
            self.utc_offset_h,
            -12.0,
            14.0,
        )
    }
}

impl Weather {
    /// The first and last time stamps, s since 1970-01-01T00:00:00Z (`None` without
    /// records).
    #[must_use]
    pub fn span_s(&self) -> Option<(f64, f64)> {
        Some((self.records.first()?.time_s, self.records.last()?.time_s))
    }

    /// The longest step between records accepted for this record: the lesser of
    /// [`MAX_GAP_MEDIAN_STEPS`] median steps and [`MAX_GAP_S`]. `None` with fewer than two
    /// records.
    #[must_use]
    pub fn max_step_s(&self) -> Option<f64> {
        let mut steps: Vec<f64> = self
            .records
            .windows(2)
            .map(|w| w[1].time_s - w[0].time_s)
            .collect();
        if steps.is_empty() {
            return None;
        }
        steps.sort_by(f64::total_cmp);
        let n = steps.len();
        let median = if n % 2 == 1 {
            steps[n / 2]
        } else {
            0.5 * (steps[n / 2 - 1] + steps[n / 2])
        };
        Some((MAX_GAP_MEDIAN_STEPS * median).min(MAX_GAP_S))
    }

    /// Checks the site, every record, the order of the times and the gaps between them.
    ///
    /// # Errors
    /// The first rule broken: `records` (fewer than two), `records[i].time_s` (not after
    /// the one before, or after a gap longer than [`Self::max_step_s`]), `records[i].field`
    /// (a number outside its range), `site.field`, `radiation.column`.
    pub fn validate(&self) -> Result<(), ModelError> {
        if let Some(site) = &self.site {
            site.validate("site")?;
        }
        let columns = [
            ("ghi", self.radiation.ghi),
            ("dni", self.radiation.dni),
            ("dhi", self.radiation.dhi),
            ("longwave_down", self.radiation.longwave_down),
        ];
        for (name, sampling) in columns {
            sampling.validate(|| format!("radiation.{name}.interval_s"))?;
        }
        if self.records.len() < 2 {
            return Err(ModelError::new(
                "records",
                ModelErrorKind::Other(format!(
                    "{} record(s): a weather record needs at least two times to interpolate \
                     between",
                    self.records.len()
                )),
            ));
        }
        for (i, r) in self.records.iter().enumerate() {
            r.validate(&format!("records[{i}]"))?;
        }
        for (i, w) in self.records.windows(2).enumerate() {
            if w[1].time_s <= w[0].time_s {
                // Exactly equal: a repeated stamp, as opposed to an earlier one.
                #[allow(clippy::float_cmp)]
                let what = if w[1].time_s == w[0].time_s {
                    "repeats"
                } else {
                    "comes before"
                };
                return Err(ModelError::new(
                    format!("records[{}].time_s", i + 1),
                    ModelErrorKind::Other(format!(
                        "{} {what} the time before it ({}): times must increase",
                        format_utc(w[1].time_s),
                        format_utc(w[0].time_s)
                    )),
                ));
            }
        }
        let limit = self.max_step_s().unwrap_or(MAX_GAP_S);
        for (i, w) in self.records.windows(2).enumerate() {
            let step = w[1].time_s - w[0].time_s;
            if step > limit {
                return Err(ModelError::new(
                    format!("records[{}].time_s", i + 1),
                    ModelErrorKind::Other(format!(
                        "a gap of {} h before {} (after {}): the longest step accepted is \
                         {} h ({MAX_GAP_MEDIAN_STEPS} median steps, at most {} h)",
                        hours(step),
                        format_utc(w[1].time_s),
                        format_utc(w[0].time_s),
                        hours(limit),
                        hours(MAX_GAP_S)
                    )),
                ));
            }
        }
        Ok(())
    }

    /// The conditions at `time_s` (s since 1970-01-01T00:00:00Z), interpolated:
    ///
    /// - instantaneous quantities (temperatures, dew point, relative humidity, pressure,
    ///   wind speed, cloud cover, and radiation sampled at its stamps) linearly in time
    ///   between the two records around `time_s`;
    /// - wind direction along the shorter arc between the two (350° and 10° give 0°
    ///   halfway, not 180°);
    /// - a radiation column that is a mean over the interval ending at its stamp
    ///   ([`Sampling::PrecedingMean`]) linearly between the middles of the intervals, its
    ///   values placed there; past the last middle (the last half interval) it keeps the
    ///   last interval's mean, which is what is known there. Linear interpolation between
    ///   the middles does not keep each interval's mean exactly (a peaked day loses a
    ///   little at noon); the file gives no more;
    /// - the dew point from the records' dew points, or, where one of the two gives only a
    ///   relative humidity, from the dew points derived from it
    ///   ([`dew_point_from_relative_humidity`]) and interpolated;
    /// - an optional column is given where both records give it (or the one `time_s` falls
    ///   on does), else `None`.
    ///
    /// # Errors
    /// `time_s` is outside the first to the last time stamp (never extrapolated or
    /// clamped: the error names the time and the record's span), not finite, or the record
    /// has fewer than two records or lacks a humidity.
    pub fn at(&self, time_s: f64) -> Result<Conditions, WeatherError> {
        if !time_s.is_finite() {
            return Err(WeatherError {
                kind: WeatherErrorKind::NotFinite,
            });
        }
        let (first_s, last_s) = match self.span_s() {
            Some(span) if self.records.len() >= 2 => span,
            _ => {
                return Err(WeatherError {
                    kind: WeatherErrorKind::Invalid("fewer than two records".into()),
                });
            }
        };
        if time_s < first_s || time_s > last_s {
            return Err(WeatherError {
                kind: WeatherErrorKind::OutsideRecord {
                    time_s,
                    first_s,
                    last_s,
                },
            });
        }
        let (a, b, w) = self.bracket(time_s);
        let (ra, rb) = (&self.records[a], &self.records[b]);
        let lerp = |x: f64, y: f64| crate::interp::lerp(x, y, w);
        let dew_point_k = match (ra.dew_point_k, rb.dew_point_k) {
            (Some(x), Some(y)) => Some(lerp(x, y)),
            _ => lerp_opt(ra.dew_point_or_derived_k(), rb.dew_point_or_derived_k(), w),
        }
        .ok_or_else(|| WeatherError {
            kind: WeatherErrorKind::Invalid(format!(
                "no humidity at {}: a record gives neither a dew point nor a relative \
                 humidity above 0",
                format_utc(time_s)
            )),
        })?;
        let wind_direction_deg = match (ra.wind_direction_deg, rb.wind_direction_deg) {
            (Some(x), Some(y)) => {
                let turn = (y - x + 540.0).rem_euclid(360.0) - 180.0;
                Some((x + w * turn).rem_euclid(360.0))
            }
            (x, y) => lerp_opt(x, y, w),
        };
        let rad = self.radiation;
        Ok(Conditions {
            time_s,
            air_temperature_k: lerp(ra.air_temperature_k, rb.air_temperature_k),
            dew_point_k,
            pressure_pa: lerp(ra.pressure_pa, rb.pressure_pa),
            wind_speed_m_s: lerp(ra.wind_speed_m_s, rb.wind_speed_m_s),
            wind_direction_deg,
            cloud_cover: lerp_opt(ra.cloud_cover, rb.cloud_cover, w),
            relative_humidity: lerp_opt(ra.relative_humidity, rb.relative_humidity, w),
            ghi_w_m2: self.column(time_s, rad.ghi, |r| r.ghi_w_m2),
            dni_w_m2: self.column(time_s, rad.dni, |r| r.dni_w_m2),
            dhi_w_m2: self.column(time_s, rad.dhi, |r| r.dhi_w_m2),
            longwave_down_w_m2: self.column(time_s, rad.longwave_down, |r| r.longwave_down_w_m2),
        })
    }

    /// The records around `time_s` (within the span) and the weight of the second.
    fn bracket(&self, time_s: f64) -> (usize, usize, f64) {
        let k = self.records.partition_point(|r| r.time_s < time_s);
        if k == 0 {
            return (0, 0, 0.0);
        }
        let k = k.min(self.records.len() - 1);
        let (ta, tb) = (self.records[k - 1].time_s, self.records[k].time_s);
        let w = ((time_s - ta) / (tb - ta)).clamp(0.0, 1.0);
        (k - 1, k, w)
    }

    /// A radiation column at `time_s`: its values placed at their stamps less the
    /// sampling's offset (the middle of a mean's interval), linearly between them, the
    /// last value held past the last of those places.
    fn column(
        &self,
        time_s: f64,
        sampling: Sampling,
        value: impl Fn(&WeatherRecord) -> Option<f64>,
    ) -> Option<f64> {
        let (a, b, w) = self.bracket((time_s + sampling.offset_s()).min(self.span_s()?.1));
        lerp_opt(value(&self.records[a]), value(&self.records[b]), w)
    }
}

/// `a + w (b − a)` where both are given; the one given where the weight rests wholly on it
/// (exactly: on its stamp).
#[allow(clippy::float_cmp)]
fn lerp_opt(a: Option<f64>, b: Option<f64>, w: f64) -> Option<f64> {
    match (a, b) {
        (Some(x), Some(y)) => Some(crate::interp::lerp(x, y, w)),
        (Some(x), None) if w == 0.0 => Some(x),
        (None, Some(y)) if w == 1.0 => Some(y),
        _ => None,
    }
}

/// Seconds as hours for a message: `3`, `4.5`.
fn hours(s: f64) -> String {
    let h = (s / 3600.0 * 1000.0).round() / 1000.0;
    format!("{h}")
}

/// The dew point, K, of air at `air_temperature_k` with relative humidity
/// `relative_humidity` (a fraction, over water): the Magnus form
/// `T_d = b γ / (a − γ)`, `γ = ln(RH) + a T / (b + T)`, T in °C, with Alduchov & Eskridge's
/// coefficients a = 17.625, b = 243.04 °C (Alduchov, O. A. and Eskridge, R. E., 1996,
/// "Improved Magnus form approximation of saturation vapor pressure", J. Appl. Meteor. 35,
/// 601–609, eq. 21: within 0.4 % of the saturation pressure over water from −40 to 50 °C).
/// `None` for a relative humidity of 0 or less (no dew point) or a number that is not
/// finite. The one place irsig turns humidity into a dew point: the weather readers store
/// what a file gives, and the thermal model calls this.
#[must_use]
pub fn dew_point_from_relative_humidity(
    air_temperature_k: f64,
    relative_humidity: f64,
) -> Option<f64> {
    const A: f64 = 17.625;
    const B_C: f64 = 243.04;
    if !(relative_humidity > 0.0 && relative_humidity.is_finite() && air_temperature_k.is_finite())
    {
        return None;
    }
    let t_c = air_temperature_k - 273.15;
    let gamma = relative_humidity.ln() + A * t_c / (B_C + t_c);
    let td_c = B_C * gamma / (A - gamma);
    (td_c.is_finite() && gamma < A).then_some(td_c + 273.15)
}

pub use crate::time::{format_utc, utc_seconds};

#[cfg(test)]
mod tests {
    use super::*;

    /// 2001-08-07T00:00:00Z, from Python's `datetime` (an independent calendar).
    const AUG_7_2001_S: f64 = 997_142_400.0;

    fn hourly(values: &[(f64, Option<f64>)]) -> Weather {
        let records = values
            .iter()
            .enumerate()
            .map(|(i, &(air_k, ghi))| WeatherRecord {
                ghi_w_m2: ghi,
                ..WeatherRecord::calm(AUG_7_2001_S + 3600.0 * i as f64, air_k, 83_500.0)
            })
            .collect();
        Weather {
            site: None,
            records,
            radiation: RadiationSampling::default(),
            source: "test".into(),
        }
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn the_dew_point_agrees_with_the_saturation_table() {
        // Saturation vapour pressure over water (CRC Handbook; WMO): 23.39 hPa at 20 °C,
        // 11.48 at 9 °C, 12.28 at 10 °C. At 50 % the vapour pressure is 11.69 hPa, which
        // the table puts at 9 + (11.69 − 11.48) / (12.28 − 11.48) = 9.26 °C.
        let td = dew_point_from_relative_humidity(293.15, 0.5).unwrap();
        assert!(close(td, 273.15 + 9.26, 0.03), "{td}");
        // Saturated air is at its dew point, hot or cold.
        for t in [233.15, 273.15, 323.15] {
            let td = dew_point_from_relative_humidity(t, 1.0).unwrap();
            assert!(close(td, t, 1e-9), "{t}: {td}");
        }
        // Drier air has a lower dew point; bone-dry air none; nonsense none.
        let dry = dew_point_from_relative_humidity(293.15, 1e-6).unwrap();
        assert!(dry < 200.0 && dry.is_finite(), "{dry}");
        assert_eq!(dew_point_from_relative_humidity(293.15, 0.0), None);
        assert_eq!(dew_point_from_relative_humidity(293.15, -0.1), None);
        assert_eq!(dew_point_from_relative_humidity(f64::NAN, 0.5), None);
        assert_eq!(
            dew_point_from_relative_humidity(293.15, f64::INFINITY),
            None
        );
    }

    #[test]
    fn instantaneous_columns_interpolate_linearly_and_never_extrapolate() {
        let w = hourly(&[(290.0, Some(0.0)), (300.0, Some(400.0)), (296.0, None)]);
        w.validate().unwrap();
        let c = w.at(AUG_7_2001_S + 900.0).unwrap();
        // A quarter of the way from 290 to 300 K; the dew points are 10 K below.
        assert!(close(c.air_temperature_k, 292.5, 1e-12));
        assert!(close(c.dew_point_k, 282.5, 1e-12));
        assert_eq!(c.ghi_w_m2, Some(100.0));
        // On a stamp, its own values, even beside a record without the column.
        let c = w.at(AUG_7_2001_S + 3600.0).unwrap();
        assert_eq!((c.air_temperature_k, c.ghi_w_m2), (300.0, Some(400.0)));
        // Between a record with GHI and one without: unknown, not invented.
        assert_eq!(w.at(AUG_7_2001_S + 5400.0).unwrap().ghi_w_m2, None);
        // Both ends are inside; a second beyond either is not.
        assert!(w.at(AUG_7_2001_S).is_ok());
        assert!(w.at(AUG_7_2001_S + 7200.0).is_ok());
        for t in [AUG_7_2001_S - 1.0, AUG_7_2001_S + 7201.0] {
            let e = w.at(t).unwrap_err();
            let text = e.to_string();
            assert!(
                text.contains("2001-08-07T00:00:00Z") && text.contains("2001-08-07T02:00:00Z"),
                "{text}"
            );
            assert!(matches!(e.kind, WeatherErrorKind::OutsideRecord { .. }));
        }
        assert!(matches!(
            w.at(f64::NAN).unwrap_err().kind,
            WeatherErrorKind::NotFinite
        ));
    }

    #[test]
    fn wind_direction_turns_the_short_way() {
        let mut w = hourly(&[(290.0, None), (290.0, None)]);
        w.records[0].wind_direction_deg = Some(350.0);
        w.records[1].wind_direction_deg = Some(10.0);
        let half = w
            .at(AUG_7_2001_S + 1800.0)
            .unwrap()
            .wind_direction_deg
            .unwrap();
        assert!(close(half, 0.0, 1e-9) || close(half, 360.0, 1e-9), "{half}");
        let quarter = w
            .at(AUG_7_2001_S + 900.0)
            .unwrap()
            .wind_direction_deg
            .unwrap();
        assert!(close(quarter, 355.0, 1e-9), "{quarter}");
        w.records[0].wind_direction_deg = Some(10.0);
        w.records[1].wind_direction_deg = Some(350.0);
        let quarter = w
            .at(AUG_7_2001_S + 900.0)
            .unwrap()
            .wind_direction_deg
            .unwrap();
        assert!(close(quarter, 5.0, 1e-9), "{quarter}");
        // Opposite directions: the turn is 180° either way, and stays within 0–360.
        w.records[1].wind_direction_deg = Some(190.0);
        let half = w
            .at(AUG_7_2001_S + 1800.0)
            .unwrap()
            .wind_direction_deg
            .unwrap();
        assert!((0.0..360.0).contains(&half), "{half}");
    }

    #[test]
    fn hourly_means_belong_to_the_middle_of_their_hour() {
        // Means over the hour before each stamp: 100, 300, 500 W/m² at 01, 02, 03 h, so
        // placed at 00:30, 01:30 and 02:30.
        let mut w = hourly(&[
            (290.0, Some(100.0)),
            (290.0, Some(300.0)),
            (290.0, Some(500.0)),
        ]);
        w.radiation.ghi = Sampling::PrecedingMean { interval_s: 3600.0 };
        w.validate().unwrap();
        let ghi = |after_first_s: f64| w.at(AUG_7_2001_S + after_first_s).unwrap().ghi_w_m2;
        assert_eq!(ghi(0.0), Some(200.0), "halfway from 00:30 to 01:30");
        assert_eq!(ghi(1800.0), Some(300.0), "01:30, the second hour's middle");
        assert_eq!(ghi(3600.0), Some(400.0));
        assert_eq!(ghi(5400.0), Some(500.0), "02:30, the last middle");
        assert_eq!(
            ghi(7200.0),
            Some(500.0),
            "the last half hour keeps its mean"
        );
        // The other radiation columns are still instantaneous.
        assert_eq!(w.at(AUG_7_2001_S).unwrap().dni_w_m2, None);
    }

    #[test]
    fn a_humidity_given_as_relative_humidity_gives_the_dew_point() {
        let mut w = hourly(&[(293.15, None), (293.15, None)]);
        for r in &mut w.records {
            r.dew_point_k = None;
            r.relative_humidity = Some(0.5);
        }
        w.validate().unwrap();
        let c = w.at(AUG_7_2001_S + 600.0).unwrap();
        let expected = dew_point_from_relative_humidity(293.15, 0.5).unwrap();
        assert!(close(c.dew_point_k, expected, 1e-12));
        assert_eq!(c.relative_humidity, Some(0.5));
        // One record with a dew point, the next with a relative humidity of 100 %: the
        // dew points are 283.15 and 293.15 K, so 288.15 halfway.
        w.records[0].dew_point_k = Some(283.15);
        w.records[1].relative_humidity = Some(1.0);
        let c = w.at(AUG_7_2001_S + 1800.0).unwrap();
        assert!(close(c.dew_point_k, 288.15, 1e-9), "{}", c.dew_point_k);
    }

    #[test]
    fn gaps_and_disorder_are_refused_at_their_record() {
        let t = |w: &Weather| w.validate().unwrap_err();
        // Hourly, with a 4 h step before record 3: three median steps is 3 h.
        let mut w = hourly(&[(290.0, None); 5]);
        for r in &mut w.records[3..] {
            r.time_s += 3.0 * 3600.0;
        }
        let e = t(&w);
        assert_eq!(e.path, "records[3].time_s");
        assert!(e.to_string().contains("gap of 4 h"), "{e}");
        // A 3 h step is accepted.
        let mut w = hourly(&[(290.0, None); 5]);
        for r in &mut w.records[3..] {
            r.time_s += 2.0 * 3600.0;
        }
        w.validate().unwrap();
        assert_eq!(w.max_step_s(), Some(3.0 * 3600.0));
        // Three-hourly: 9 h would be three steps, but no gap over 6 h is accepted.
        let mut w = hourly(&[(290.0, None); 4]);
        for (i, r) in w.records.iter_mut().enumerate() {
            r.time_s = AUG_7_2001_S + 3.0 * 3600.0 * i as f64;
        }
        w.records[3].time_s += 4.0 * 3600.0;
        assert_eq!(t(&w).path, "records[3].time_s", "a 7 h step");
        w.records[3].time_s -= 1.0 * 3600.0;
        w.validate().unwrap();
        w.records[3].time_s -= 3.0 * 3600.0;
        w.validate().unwrap();
        // Repeated and decreasing times.
        let mut w = hourly(&[(290.0, None); 3]);
        w.records[2].time_s = w.records[1].time_s;
        let e = t(&w);
        assert_eq!(e.path, "records[2].time_s");
        assert!(e.to_string().contains("repeats"), "{e}");
        w.records[2].time_s -= 10.0;
        assert!(t(&w).to_string().contains("comes before"));
        // One record is no record.
        let mut w = hourly(&[(290.0, None)]);
        assert_eq!(t(&w).path, "records");
        assert!(w.at(AUG_7_2001_S).is_err());
        w.records.clear();
        assert_eq!(w.span_s(), None);
        assert_eq!(w.max_step_s(), None);
    }

    #[test]
    fn every_number_has_its_physical_range() {
        let check = |edit: &dyn Fn(&mut WeatherRecord), path: &str| {
            let mut w = hourly(&[(290.0, None); 2]);
            edit(&mut w.records[1]);
            let e = w.validate().unwrap_err();
            assert_eq!(e.path, format!("records[1].{path}"), "{e}");
        };
        check(&|r| r.air_temperature_k = 149.0, "air_temperature_k");
        check(&|r| r.air_temperature_k = f64::NAN, "air_temperature_k");
        check(&|r| r.dew_point_k = Some(351.0), "dew_point_k");
        check(&|r| r.pressure_pa = 29_000.0, "pressure_pa");
        check(&|r| r.pressure_pa = 111_000.0, "pressure_pa");
        check(&|r| r.wind_speed_m_s = -0.1, "wind_speed_m_s");
        check(&|r| r.wind_speed_m_s = 100.5, "wind_speed_m_s");
        check(
            &|r| r.wind_direction_deg = Some(361.0),
            "wind_direction_deg",
        );
        check(&|r| r.cloud_cover = Some(1.01), "cloud_cover");
        check(&|r| r.relative_humidity = Some(1.2), "relative_humidity");
        check(&|r| r.ghi_w_m2 = Some(-1.0), "ghi_w_m2");
        check(&|r| r.dni_w_m2 = Some(2001.0), "dni_w_m2");
        check(&|r| r.dhi_w_m2 = Some(f64::INFINITY), "dhi_w_m2");
        check(&|r| r.longwave_down_w_m2 = Some(-5.0), "longwave_down_w_m2");
        check(&|r| r.dew_point_k = None, "dew_point_k");
        check(
            &|r| {
                r.dew_point_k = None;
                r.relative_humidity = Some(0.0);
            },
            "relative_humidity",
        );
        // The extremes themselves are accepted.
        let mut w = hourly(&[(150.0, Some(2000.0)), (350.0, Some(0.0))]);
        w.records[0].pressure_pa = 30_000.0;
        w.records[0].dew_point_k = Some(150.0);
        w.records[1].wind_speed_m_s = 100.0;
        w.records[1].cloud_cover = Some(1.0);
        w.records[0].wind_direction_deg = Some(360.0);
        w.validate().unwrap();
        // The site and the sampling.
        w.site = Some(Site {
            name: "Golden".into(),
            latitude_deg: 91.0,
            longitude_deg: -105.18,
            elevation_m: 1829.0,
            utc_offset_h: -7.0,
        });
        assert_eq!(w.validate().unwrap_err().path, "site.latitude_deg");
        w.site = None;
        w.radiation.dni = Sampling::PrecedingMean { interval_s: 0.0 };
        assert_eq!(w.validate().unwrap_err().path, "radiation.dni.interval_s");
    }
}
