//! What the sky and the air give the scene at one moment: the weather interpolated, the
//! sun's direction, and the sunlight and sky longwave from the chosen source.

use irsig_atmosphere::loads::weathered::{clouded, earth_sun_factor, longwave_w_m2};
use irsig_atmosphere::loads::{SunLoads, sun_loads_at};
use irsig_atmosphere::sun::SunSpec;
use irsig_model::loads::BroadbandLoads;
use irsig_model::weather::Weather;
use irsig_thermal::sky;
use miette::miette;

/// Where the sunlight (direct normal and diffuse horizontal) comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Sunlight {
    /// The weather file's `dni` and `dhi` columns (measured or a typical year's).
    Weather,
    /// A loads table LOWTRAN7 made (`--loads-table`): clear sky at the sun's zenith angle,
    /// taken to the moment's Earth–Sun distance and, where the weather gives cloud cover, under
    /// Kasten & Czeplak's (1980) clouds (`irsig_atmosphere::loads::weathered`).
    Loads,
}

/// Where the sky's longwave irradiance comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SkyLongwave {
    /// The weather file's downwelling longwave column (EPW's horizontal infrared).
    Weather,
    /// A loads table's (`--loads-table`): its sky's effective emissivity at the weather's air
    /// temperature, with Crawford & Duchon's (1999) cloud term.
    Loads,
    /// Prata's (1996) clear-sky formula from the air's temperature and dew point, with
    /// Crawford & Duchon's (1999) cloud term when the weather gives cloud cover
    /// ([`irsig_thermal::sky`]).
    Prata,
}

impl Sunlight {
    /// Where it comes from, in words, for the provenance.
    #[must_use]
    pub fn describe(self) -> &'static str {
        match self {
            Self::Weather => "the weather file's dni and dhi columns",
            Self::Loads => {
                "the LOWTRAN7 loads table (clear sky, at the moment's Earth-Sun distance; the \
                 weather's cloud cover by Kasten & Czeplak 1980)"
            }
        }
    }
}

impl SkyLongwave {
    /// Where it comes from, in words, for the provenance.
    #[must_use]
    pub fn describe(self) -> &'static str {
        match self {
            Self::Weather => "the weather file's longwave column",
            Self::Loads => {
                "the LOWTRAN7 loads table's effective sky emissivity at the weather's air \
                 temperature, Crawford & Duchon 1999 clouds"
            }
            Self::Prata => "Prata (1996) clear sky with Crawford & Duchon (1999) clouds",
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
#[derive(Debug, Clone, Copy)]
pub struct Environment<'a> {
    /// The weather record.
    pub weather: &'a Weather,
    /// Where the sun is computed for.
    pub site: Site,
    /// The sunlight's source.
    pub sunlight: Sunlight,
    /// The sky longwave's source.
    pub sky: SkyLongwave,
    /// The loads table, when one is given.
    pub loads: Option<&'a BroadbandLoads>,
}

impl Environment<'_> {
    /// The sources to use: those asked for, else the best the inputs hold — the weather
    /// file's own columns (measured, or a typical year's), then the loads table, then (for
    /// the sky) Prata's formula.
    ///
    /// # Errors
    /// A source asked for that the inputs lack, or no sunlight at all.
    pub fn sources(
        weather: &Weather,
        name: &str,
        loads: Option<&BroadbandLoads>,
        asked: (Option<Sunlight>, Option<SkyLongwave>),
    ) -> miette::Result<(Sunlight, SkyLongwave)> {
        let has = |f: fn(&irsig_model::weather::WeatherRecord) -> Option<f64>| {
            weather.records.iter().all(|r| f(r).is_some())
        };
        let weather_sun = has(|r| r.dni_w_m2) && has(|r| r.dhi_w_m2);
        let weather_sky = has(|r| r.longwave_down_w_m2);
        let no_loads = || {
            irsig_cli::usage_error(
                "no --loads-table to take it from: make one with irsig-atmos plan --loads \
                 and irsig-atmos build",
            )
        };
        let sunlight = match asked.0 {
            Some(Sunlight::Weather) if !weather_sun => {
                return Err(miette!(
                    "--sunlight weather: `{name}` does not give the direct normal (dni) and \
                     diffuse horizontal (dhi) irradiance on every record (formats/weather.md)"
                ));
            }
            Some(Sunlight::Loads) if loads.is_none() => return Err(no_loads()),
            Some(s) => s,
            None if weather_sun => Sunlight::Weather,
            None if loads.is_some() => Sunlight::Loads,
            None => {
                return Err(miette!(
                    "`{name}` does not give the direct normal (dni) and diffuse horizontal \
                     (dhi) irradiance on every record, and no --loads-table was given: the \
                     thermal model needs sunlight from one of them"
                ));
            }
        };
        let sky = match asked.1 {
            Some(SkyLongwave::Weather) if !weather_sky => {
                return Err(miette!(
                    "--sky-longwave weather: `{name}` has no downwelling longwave column on \
                     every record"
                ));
            }
            Some(SkyLongwave::Loads) if loads.is_none() => return Err(no_loads()),
            Some(s) => s,
            None if weather_sky => SkyLongwave::Weather,
            None if loads.is_some() => SkyLongwave::Loads,
            None => SkyLongwave::Prata,
        };
        Ok((sunlight, sky))
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
        let (dni, dhi) = match (self.sunlight, self.loads) {
            (Sunlight::Loads, Some(table)) => {
                let l = self.table_sunlight(table, time_s, cos_z, c.cloud_cover)?;
                (l.direct_normal_w_m2, l.diffuse_horizontal_w_m2)
            }
            _ => (c.dni_w_m2.unwrap_or(0.0), c.dhi_w_m2.unwrap_or(0.0)),
        };
        // A beam reported while the sun is below the horizon (an hourly mean that straddles
        // sunrise) lights nothing directly.
        let dni = if to_sun.is_some() { dni.max(0.0) } else { 0.0 };
        let dhi = dhi.max(0.0);
        let longwave = match (self.sky, self.loads) {
            (SkyLongwave::Loads, Some(table)) => {
                longwave_w_m2(table, c.air_temperature_k, c.cloud_cover.unwrap_or(0.0))
            }
            (SkyLongwave::Weather, _) => c.longwave_down_w_m2.unwrap_or(0.0),
            _ => sky::clear_sky_longwave_w_m2(
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

impl Environment<'_> {
    /// The table's sunlight at `time_s` with the sun's zenith cosine `cos_z`: 0 with the sun
    /// below the horizon; between the table's last row and the horizon falling linearly to
    /// 0 at 90° (a named approximation: at most a few W/m² of diffuse light for a minute or
    /// so); scaled to the moment's Earth–Sun distance; under the weather's clouds.
    fn table_sunlight(
        &self,
        table: &BroadbandLoads,
        time_s: f64,
        cos_z: f64,
        cloud: Option<f64>,
    ) -> miette::Result<SunLoads> {
        let none = SunLoads {
            direct_normal_w_m2: 0.0,
            diffuse_horizontal_w_m2: 0.0,
            global_horizontal_w_m2: 0.0,
        };
        if cos_z <= 0.0 {
            return Ok(none);
        }
        let zenith = cos_z.clamp(-1.0, 1.0).acos().to_degrees();
        let last = table.sun_zenith_deg.last().copied().unwrap_or(90.0);
        let clear = if zenith > last {
            let at_last = sun_loads_at(table, last).map_err(|e| miette!("{e}"))?;
            let k = ((90.0 - zenith) / (90.0 - last).max(1e-9)).clamp(0.0, 1.0);
            SunLoads {
                direct_normal_w_m2: at_last.direct_normal_w_m2 * k,
                diffuse_horizontal_w_m2: at_last.diffuse_horizontal_w_m2 * k,
                global_horizontal_w_m2: at_last.global_horizontal_w_m2 * k,
            }
        } else {
            sun_loads_at(table, zenith)
                .map_err(|e| miette!("at {}: {e}", irsig_model::time::format_utc(time_s)))?
        };
        let day = irsig_model::time::day_of_year_utc(time_s).unwrap_or(table.day_of_year);
        let scale = earth_sun_factor(day) / earth_sun_factor(table.day_of_year);
        let scaled = SunLoads {
            direct_normal_w_m2: clear.direct_normal_w_m2 * scale,
            diffuse_horizontal_w_m2: clear.diffuse_horizontal_w_m2 * scale,
            global_horizontal_w_m2: clear.global_horizontal_w_m2 * scale,
        };
        Ok(clouded(scaled, cos_z, cloud.unwrap_or(0.0)))
    }
}
