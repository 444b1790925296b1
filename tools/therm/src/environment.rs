//! What the sky and the air give the scene at one moment: the weather interpolated, the
//! sun's direction, and the sunlight and sky longwave from the chosen source.

use irsig_atmosphere::sun::SunSpec;
use irsig_model::weather::Weather;
use irsig_thermal::sky;
use miette::miette;

/// Where the sunlight (direct normal and diffuse horizontal) comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sunlight {
    /// The weather file's `dni` and `dhi` columns (measured or a typical year's).
    Weather,
}

/// Where the sky's longwave irradiance comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SkyLongwave {
    /// The weather file's downwelling longwave column (EPW's horizontal infrared).
    Weather,
    /// Prata's (1996) clear-sky formula from the air's temperature and dew point, with
    /// Crawford & Duchon's (1999) cloud term when the weather gives cloud cover
    /// ([`irsig_thermal::sky`]).
    Prata,
}

impl SkyLongwave {
    /// The name the decision and the provenance use.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Weather => "weather",
            Self::Prata => "prata",
        }
    }
}

/// The place: where the sun is computed for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Site {
    /// Latitude, degrees north.
    pub latitude_deg: f64,
    /// Longitude, degrees east.
    pub longitude_deg: f64,
    /// The ground's altitude above sea level, m.
    pub altitude_m: f64,
}

/// The air, the sun and the sky's radiation at one moment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Moment {
    /// The time, s since 1970-01-01T00:00:00Z.
    pub time_s: f64,
    /// Air temperature, K.
    pub air_temperature_k: f64,
    /// Dew point, K.
    pub dew_point_k: f64,
    /// Pressure, Pa.
    pub pressure_pa: f64,
    /// Wind speed, m/s.
    pub wind_speed_m_s: f64,
    /// The horizontal unit vector toward where the wind blows from (x east, y north), when
    /// the weather gives a direction.
    pub wind_from: Option<[f64; 2]>,
    /// The unit vector toward the sun (x east, y north, z up), when it is above the
    /// horizon.
    pub to_sun: Option<[f64; 3]>,
    /// Direct normal irradiance, W/m² (0 with the sun below the horizon).
    pub dni_w_m2: f64,
    /// Diffuse horizontal irradiance, W/m².
    pub dhi_w_m2: f64,
    /// Global horizontal irradiance, `DNI cos z + DHI`, W/m².
    pub ghi_w_m2: f64,
    /// The sky's longwave irradiance on a horizontal surface, W/m².
    pub longwave_down_w_m2: f64,
}

/// The weather, the place and the radiation sources: [`Environment::at`] gives a moment.
#[derive(Debug)]
pub struct Environment<'a> {
    /// The weather record.
    pub weather: &'a Weather,
    /// Where the sun is computed for.
    pub site: Site,
    /// The sunlight's source.
    pub sunlight: Sunlight,
    /// The sky longwave's source.
    pub sky: SkyLongwave,
}

impl Environment<'_> {
    /// The sources a weather record supports, the best first: its own columns where it has
    /// them. Sunlight needs `dni` and `dhi`; without a longwave column, Prata's formula.
    ///
    /// # Errors
    /// A weather record without direct and diffuse sunlight columns.
    pub fn sources(weather: &Weather, name: &str) -> miette::Result<(Sunlight, SkyLongwave)> {
        let has = |f: fn(&irsig_model::weather::WeatherRecord) -> Option<f64>| {
            weather.records.iter().all(|r| f(r).is_some())
        };
        if !(has(|r| r.dni_w_m2) && has(|r| r.dhi_w_m2)) {
            return Err(miette!(
                "`{name}` does not give the direct normal (dni) and diffuse horizontal (dhi) \
                 irradiance on every record: the thermal model needs both for the sunlight \
                 (formats/weather.md)"
            ));
        }
        let sky = if has(|r| r.longwave_down_w_m2) {
            SkyLongwave::Weather
        } else {
            SkyLongwave::Prata
        };
        Ok((Sunlight::Weather, sky))
    }

    /// The moment `time_s`.
    ///
    /// # Errors
    /// A time outside the weather record, or a sun SPA cannot place.
    pub fn at(&self, time_s: f64) -> miette::Result<Moment> {
        let c = self.weather.at(time_s).map_err(|e| miette!("{e}"))?;
        let utc = irsig_model::time::format_utc(time_s);
        let position = SunSpec::At {
            utc,
            latitude_deg: self.site.latitude_deg,
            longitude_deg: self.site.longitude_deg,
            altitude_m: self.site.altitude_m,
            refraction: None,
            delta_t_s: None,
            delta_ut1_s: None,
        }
        .position()
        .map_err(|e| miette!("the sun at {time_s} s: {e}"))?;
        let to_sun = position
            .is_above_horizon()
            .then(|| position.to_scene_direction());
        let cos_z = to_sun.map_or(0.0, |s| s[2]);
        let (dni, dhi) = match self.sunlight {
            Sunlight::Weather => (c.dni_w_m2.unwrap_or(0.0), c.dhi_w_m2.unwrap_or(0.0)),
        };
        // A beam reported while the sun is below the horizon (an hourly mean that straddles
        // sunrise) lights nothing directly.
        let dni = if to_sun.is_some() { dni.max(0.0) } else { 0.0 };
        let dhi = dhi.max(0.0);
        let longwave = match self.sky {
            SkyLongwave::Weather => c.longwave_down_w_m2.unwrap_or(0.0),
            SkyLongwave::Prata => sky::clear_sky_longwave_w_m2(
                c.air_temperature_k,
                c.dew_point_k,
                c.cloud_cover.unwrap_or(0.0),
            ),
        };
        let wind_from = c.wind_direction_deg.map(|d| {
            let r = d.to_radians();
            [r.sin(), r.cos()]
        });
        Ok(Moment {
            time_s,
            air_temperature_k: c.air_temperature_k,
            dew_point_k: c.dew_point_k,
            pressure_pa: c.pressure_pa,
            wind_speed_m_s: c.wind_speed_m_s,
            wind_from,
            to_sun,
            dni_w_m2: dni,
            dhi_w_m2: dhi,
            ghi_w_m2: dni * cos_z + dhi,
            longwave_down_w_m2: longwave,
        })
    }
}
