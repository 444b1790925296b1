//! irsig's weather CSV: a header row naming each column and its unit, then one row per
//! record, comma-separated.
//!
//! ```text
//! time,air_temperature[degC],dew_point[degC],pressure[hPa],wind_speed[m/s],ghi[W/m2 mean 3600s]
//! 2001-08-07T14:00:00-07:00,32.0,8.0,835,5.7,863
//! ```
//!
//! - `time`, without a unit: RFC 3339, with `Z` or an offset from UTC (`2001-08-07T21:00:00Z`,
//!   `2001-08-07T14:00:00-07:00`), seconds required, a fraction allowed; strictly
//!   increasing.
//! - every other column `name[unit]`, the units accepted listed in [`Quantity::units`]
//!   (`formats/weather.md` has the table). Required: `air_temperature`, `pressure`,
//!   `wind_speed`, and `dew_point` or `relative_humidity`. Optional: `wind_direction`,
//!   `cloud_cover`, `ghi`, `dni`, `dhi`, `longwave_down`. A radiation column is the value
//!   at its time stamp, or, with ` mean N s` (or `min`, `h`) after its unit, the mean over
//!   the N seconds that end at the stamp.
//! - a column whose name starts with `x_` is carried by the file and not read (a measured
//!   surface temperature beside the weather that drove it); it still needs a unit.
//! - an empty field is a missing value, allowed in optional columns only. Blank lines and
//!   `#` comments are skipped, as in every irsig text format.

// ParseError is the crate's shared error; its size is decided there, not here.
#![allow(clippy::result_large_err)]

use irsig_model::weather::{RadiationSampling, Sampling, Weather, WeatherRecord};

use super::{fields, range, record_field};
use crate::ParseError;
use crate::legacy::lex::{Line, Lines, Span};

/// A weather quantity a column may hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// `air_temperature`: the air's (dry-bulb) temperature.
    AirTemperature,
    /// `dew_point`: the dew-point temperature.
    DewPoint,
    /// `relative_humidity`: over water.
    RelativeHumidity,
    /// `pressure`: at the station.
    Pressure,
    /// `wind_speed`.
    WindSpeed,
    /// `wind_direction`: where the wind blows from, clockwise from north.
    WindDirection,
    /// `cloud_cover`: the share of the sky covered.
    CloudCover,
    /// `ghi`: global horizontal irradiance.
    Ghi,
    /// `dni`: direct normal irradiance.
    Dni,
    /// `dhi`: diffuse horizontal irradiance.
    Dhi,
    /// `longwave_down`: downwelling longwave irradiance on a horizontal surface.
    LongwaveDown,
}

/// Every quantity, in the order the page lists them.
const QUANTITIES: [Quantity; 11] = [
    Quantity::AirTemperature,
    Quantity::DewPoint,
    Quantity::RelativeHumidity,
    Quantity::Pressure,
    Quantity::WindSpeed,
    Quantity::WindDirection,
    Quantity::CloudCover,
    Quantity::Ghi,
    Quantity::Dni,
    Quantity::Dhi,
    Quantity::LongwaveDown,
];

/// A unit a column may be given in, and its conversion to the record's SI unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// `K`.
    Kelvin,
    /// `degC` (or `°C`): K − 273.15.
    Celsius,
    /// `degF` (or `°F`): (K − 273.15) · 9/5 + 32.
    Fahrenheit,
    /// `Pa`.
    Pascal,
    /// `hPa`: 100 Pa.
    Hectopascal,
    /// `kPa`: 1000 Pa.
    Kilopascal,
    /// `mbar`: 100 Pa.
    Millibar,
    /// `m/s`.
    MetrePerSecond,
    /// `km/h`: 1/3.6 m/s.
    KilometrePerHour,
    /// `knots` (or `kn`): 1852 m per hour.
    Knot,
    /// `deg`: degrees.
    Degree,
    /// `W/m2` (or `W/m^2`).
    WattPerSquareMetre,
    /// `fraction`: 0 to 1.
    Fraction,
    /// `%`: 0 to 100.
    Percent,
    /// `okta`: eighths of the sky, 0 to 8.
    Okta,
    /// `tenths`: tenths of the sky, 0 to 10.
    Tenths,
}

impl Unit {
    /// The unit named `text`, if irsig knows it.
    fn parse(text: &str) -> Option<Self> {
        Some(match text {
            "K" => Self::Kelvin,
            "degC" | "°C" => Self::Celsius,
            "degF" | "°F" => Self::Fahrenheit,
            "Pa" => Self::Pascal,
            "hPa" => Self::Hectopascal,
            "kPa" => Self::Kilopascal,
            "mbar" => Self::Millibar,
            "m/s" => Self::MetrePerSecond,
            "km/h" => Self::KilometrePerHour,
            "knots" | "kn" => Self::Knot,
            "deg" => Self::Degree,
            "W/m2" | "W/m^2" => Self::WattPerSquareMetre,
            "fraction" => Self::Fraction,
            "%" => Self::Percent,
            "okta" => Self::Okta,
            "tenths" => Self::Tenths,
            _ => return None,
        })
    }

    /// How the header writes it.
    #[must_use]
    pub fn text(self) -> &'static str {
        match self {
            Self::Kelvin => "K",
            Self::Celsius => "degC",
            Self::Fahrenheit => "degF",
            Self::Pascal => "Pa",
            Self::Hectopascal => "hPa",
            Self::Kilopascal => "kPa",
            Self::Millibar => "mbar",
            Self::MetrePerSecond => "m/s",
            Self::KilometrePerHour => "km/h",
            Self::Knot => "knots",
            Self::Degree => "deg",
            Self::WattPerSquareMetre => "W/m2",
            Self::Fraction => "fraction",
            Self::Percent => "%",
            Self::Okta => "okta",
            Self::Tenths => "tenths",
        }
    }

    /// A value in this unit in the record's SI unit (K, Pa, m/s, degrees, W/m², a fraction).
    #[must_use]
    pub fn to_si(self, v: f64) -> f64 {
        match self {
            Self::Kelvin
            | Self::Pascal
            | Self::MetrePerSecond
            | Self::Degree
            | Self::WattPerSquareMetre
            | Self::Fraction => v,
            Self::Celsius => v + 273.15,
            Self::Fahrenheit => (v - 32.0) * 5.0 / 9.0 + 273.15,
            Self::Hectopascal | Self::Millibar => v * 100.0,
            Self::Percent => v / 100.0,
            Self::Kilopascal => v * 1000.0,
            Self::KilometrePerHour => v / 3.6,
            Self::Knot => v * 1852.0 / 3600.0,
            Self::Okta => v / 8.0,
            Self::Tenths => v / 10.0,
        }
    }
}

impl Quantity {
    /// The column name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::AirTemperature => "air_temperature",
            Self::DewPoint => "dew_point",
            Self::RelativeHumidity => "relative_humidity",
            Self::Pressure => "pressure",
            Self::WindSpeed => "wind_speed",
            Self::WindDirection => "wind_direction",
            Self::CloudCover => "cloud_cover",
            Self::Ghi => "ghi",
            Self::Dni => "dni",
            Self::Dhi => "dhi",
            Self::LongwaveDown => "longwave_down",
        }
    }

    /// The units a column of this quantity may be given in.
    #[must_use]
    pub fn units(self) -> &'static [Unit] {
        use Unit::{
            Celsius, Degree, Fahrenheit, Fraction, Hectopascal, Kelvin, KilometrePerHour,
            Kilopascal, Knot, MetrePerSecond, Millibar, Okta, Pascal, Percent, Tenths,
            WattPerSquareMetre,
        };
        match self {
            Self::AirTemperature | Self::DewPoint => &[Kelvin, Celsius, Fahrenheit],
            Self::RelativeHumidity => &[Fraction, Percent],
            Self::Pressure => &[Pascal, Hectopascal, Kilopascal, Millibar],
            Self::WindSpeed => &[MetrePerSecond, KilometrePerHour, Knot],
            Self::WindDirection => &[Degree],
            Self::CloudCover => &[Fraction, Percent, Okta, Tenths],
            Self::Ghi | Self::Dni | Self::Dhi | Self::LongwaveDown => &[WattPerSquareMetre],
        }
    }

    fn is_radiation(self) -> bool {
        matches!(self, Self::Ghi | Self::Dni | Self::Dhi | Self::LongwaveDown)
    }

    fn is_required(self) -> bool {
        matches!(
            self,
            Self::AirTemperature | Self::Pressure | Self::WindSpeed
        )
    }

    /// The record's field this quantity fills, as [`Weather::validate`] names it.
    fn field(self) -> &'static str {
        match self {
            Self::AirTemperature => "air_temperature_k",
            Self::DewPoint => "dew_point_k",
            Self::RelativeHumidity => "relative_humidity",
            Self::Pressure => "pressure_pa",
            Self::WindSpeed => "wind_speed_m_s",
            Self::WindDirection => "wind_direction_deg",
            Self::CloudCover => "cloud_cover",
            Self::Ghi => "ghi_w_m2",
            Self::Dni => "dni_w_m2",
            Self::Dhi => "dhi_w_m2",
            Self::LongwaveDown => "longwave_down_w_m2",
        }
    }

    fn units_text(self) -> String {
        self.units()
            .iter()
            .map(|u| u.text())
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// What a header cell says a column holds.
#[derive(Debug, Clone)]
enum Column {
    Time,
    /// A weather quantity in a unit, sampled so.
    Value {
        quantity: Quantity,
        unit: Unit,
        sampling: Sampling,
        header: String,
    },
    /// An `x_` column, not read.
    Extra,
}

/// Reads the text of a weather CSV named `file` (for messages).
///
/// # Errors
/// A [`ParseError`] at the line and column of: a header cell without a unit, with a unit
/// irsig does not accept for it, naming an unknown column or one twice; a required column
/// missing (at the header); a row with more or fewer fields than the header; a time that
/// is not RFC 3339 with an offset; a number that is not a finite number (`NaN`, `inf`, a
/// word); an empty required field; and whatever the record's rules refuse
/// ([`Weather::validate`]: ranges, a time that repeats or goes back, a gap), at the value.
pub fn parse(file: &str, text: &str) -> Result<Weather, ParseError> {
    let mut lines = Lines::new(file, text);
    let header = lines.expect_line("the header row `time,air_temperature[degC],...`")?;
    let columns = header_columns(&lines, header)?;
    let mut radiation = RadiationSampling::default();
    for c in &columns {
        if let Column::Value {
            quantity, sampling, ..
        } = c
        {
            match quantity {
                Quantity::Ghi => radiation.ghi = *sampling,
                Quantity::Dni => radiation.dni = *sampling,
                Quantity::Dhi => radiation.dhi = *sampling,
                Quantity::LongwaveDown => radiation.longwave_down = *sampling,
                _ => {}
            }
        }
    }
    let mut records = Vec::new();
    let mut places: Vec<Vec<(usize, usize)>> = Vec::new();
    while let Some(line) = lines.next_line() {
        let row = fields(line);
        if row.len() != columns.len() {
            let at = row.get(columns.len()).copied().unwrap_or(line.span);
            return Err(lines.error(
                at,
                format!(
                    "expected {} comma-separated fields, as the header has, found {}",
                    columns.len(),
                    row.len()
                ),
            ));
        }
        records.push(row_record(&lines, &columns, &row)?);
        places.push(row.iter().map(|s| range(*s)).collect());
    }
    let weather = Weather {
        site: None,
        records,
        radiation,
        source: format!("weather CSV {file}"),
    };
    weather.validate().map_err(|e| {
        let place = record_field(&e).and_then(|(i, field)| {
            let k = columns.iter().position(|c| match c {
                Column::Time => field == "time_s",
                Column::Value { quantity, .. } => quantity.field() == field,
                Column::Extra => false,
            })?;
            Some((places.get(i)?[k], &columns[k]))
        });
        match place {
            Some(((offset, len), column)) => {
                let found = &text[offset..offset + len];
                let message = match column {
                    Column::Value {
                        header, quantity, ..
                    } => format!(
                        "{header} `{found}`: as {} in SI, {}",
                        quantity.field(),
                        e.kind
                    ),
                    _ => format!("the time `{found}`: {}", e.kind),
                };
                ParseError::at_span(file, text, offset, len, message)
            }
            None => lines.eof_error(&format!("the weather record: {e}")),
        }
    })?;
    Ok(weather)
}

/// The header row's columns, each checked.
fn header_columns(lines: &Lines<'_>, header: Line<'_>) -> Result<Vec<Column>, ParseError> {
    let cells = fields(header);
    let mut columns: Vec<Column> = Vec::with_capacity(cells.len());
    let mut names: Vec<String> = Vec::new();
    for cell in &cells {
        let column = header_cell(lines, *cell)?;
        let name = cell
            .fragment()
            .split('[')
            .next()
            .unwrap_or_default()
            .trim()
            .to_owned();
        if names.contains(&name) {
            return Err(lines.error(
                *cell,
                format!("the column `{name}` is given twice: which one is meant?"),
            ));
        }
        names.push(name);
        columns.push(column);
    }
    let has = |q: Quantity| {
        columns
            .iter()
            .any(|c| matches!(c, Column::Value { quantity, .. } if *quantity == q))
    };
    let mut missing: Vec<&str> = Vec::new();
    if !columns.iter().any(|c| matches!(c, Column::Time)) {
        missing.push("time");
    }
    for q in QUANTITIES.into_iter().filter(|q| q.is_required()) {
        if !has(q) {
            missing.push(q.name());
        }
    }
    if !has(Quantity::DewPoint) && !has(Quantity::RelativeHumidity) {
        missing.push("dew_point or relative_humidity");
    }
    if !missing.is_empty() {
        return Err(lines.error(
            header.span,
            format!(
                "the header lacks the required column(s) {}: a weather record needs the \
                 time, the air temperature, its humidity, the pressure and the wind speed",
                missing.join(", ")
            ),
        ));
    }
    Ok(columns)
}

/// One header cell: `time`, `name[unit]`, `name[unit mean N s]` or `x_name[unit]`.
fn header_cell(lines: &Lines<'_>, cell: Span<'_>) -> Result<Column, ParseError> {
    let text = *cell.fragment();
    let known = || {
        QUANTITIES
            .iter()
            .map(|q| q.name())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let (name, unit) = match text.split_once('[') {
        None => (text, None),
        Some((name, rest)) => {
            let Some(unit) = rest.strip_suffix(']') else {
                return Err(lines.error(
                    cell,
                    format!("expected `name[unit]`, found `{text}`: the `]` is missing"),
                ));
            };
            (name.trim(), Some(unit.trim()))
        }
    };
    if name == "time" {
        return match unit {
            None => Ok(Column::Time),
            Some(u) => Err(lines.error(
                cell,
                format!(
                    "the time column takes no unit (`{u}`): its values are RFC 3339 times \
                     that carry their offset from UTC"
                ),
            )),
        };
    }
    let quantity = QUANTITIES.into_iter().find(|q| q.name() == name);
    let Some(unit) = unit else {
        let example = quantity.map_or_else(
            || format!("{name}[unit]"),
            |q| format!("{name}[{}]", q.units()[0].text()),
        );
        return Err(lines.error(
            cell,
            format!(
                "the column `{name}` has no unit: write it as `{example}`{}",
                quantity.map_or_else(String::new, |q| format!(" (accepted: {})", q.units_text()))
            ),
        ));
    };
    if name.starts_with("x_") {
        return Ok(Column::Extra);
    }
    let Some(quantity) = quantity else {
        return Err(lines.error(
            cell,
            format!(
                "unknown column `{name}`: expected time, {}, or a name starting `x_` for a \
                 column the record does not read",
                known()
            ),
        ));
    };
    let (unit_text, mean) = match unit.split_once(char::is_whitespace) {
        Some((u, rest)) => (u, Some(rest.trim())),
        None => (unit, None),
    };
    let parsed = Unit::parse(unit_text).filter(|u| quantity.units().contains(u));
    let Some(parsed) = parsed else {
        return Err(lines.error(
            cell,
            format!(
                "unknown unit `{unit_text}` for {name}: expected one of {}",
                quantity.units_text()
            ),
        ));
    };
    let sampling = match mean {
        None => Sampling::Instantaneous,
        Some(clause) => mean_clause(lines, cell, quantity, clause)?,
    };
    Ok(Column::Value {
        quantity,
        unit: parsed,
        sampling,
        header: text.to_owned(),
    })
}

/// `mean N s` (or `min`, `h`) after a radiation column's unit: the mean over the N that end
/// at each time stamp.
fn mean_clause(
    lines: &Lines<'_>,
    cell: Span<'_>,
    quantity: Quantity,
    clause: &str,
) -> Result<Sampling, ParseError> {
    let error = |why: &str| {
        lines.error(
            cell,
            format!(
                "expected `{}[W/m2]` or `{}[W/m2 mean N s]` (or `min`, `h`: the mean over the \
                 interval that ends at each time), found `{}`: {why}",
                quantity.name(),
                quantity.name(),
                cell.fragment()
            ),
        )
    };
    if !quantity.is_radiation() {
        return Err(lines.error(
            cell,
            format!(
                "only radiation columns may be means over an interval; {} is read at its \
                 time stamp: write `{}[unit]`",
                quantity.name(),
                quantity.name()
            ),
        ));
    }
    let Some(length) = clause.strip_prefix("mean") else {
        return Err(error("after the unit only `mean N s` may follow"));
    };
    let length = length.trim();
    let split = length
        .find(|c: char| c.is_ascii_alphabetic())
        .unwrap_or(length.len());
    let (number, unit) = (length[..split].trim(), length[split..].trim());
    let n: f64 = match number.parse() {
        Ok(n) if f64::is_finite(n) && n > 0.0 => n,
        _ => return Err(error("the interval is not a positive number")),
    };
    let seconds = match unit {
        "s" => n,
        "min" => n * 60.0,
        "h" => n * 3600.0,
        _ => return Err(error("the interval's unit is s, min or h")),
    };
    Ok(Sampling::PrecedingMean {
        interval_s: seconds,
    })
}

/// One row's record in SI.
fn row_record(
    lines: &Lines<'_>,
    columns: &[Column],
    row: &[Span<'_>],
) -> Result<WeatherRecord, ParseError> {
    let mut record = WeatherRecord::calm(0.0, 0.0, 0.0);
    record.dew_point_k = None;
    for (column, &tok) in columns.iter().zip(row) {
        let (quantity, unit, header) = match column {
            Column::Extra => continue,
            Column::Time => {
                record.time_s = rfc3339(tok.fragment()).map_err(|why| {
                    lines.error(tok, format!("the time `{}`: {why}", tok.fragment()))
                })?;
                continue;
            }
            Column::Value {
                quantity,
                unit,
                header,
                ..
            } => (*quantity, *unit, header),
        };
        if tok.fragment().is_empty() {
            if quantity.is_required() {
                return Err(lines.error(
                    tok,
                    format!(
                        "expected {header} (a finite number), found nothing: the column is \
                         required at every time"
                    ),
                ));
            }
            continue;
        }
        let si = unit.to_si(lines.real(tok, header)?);
        let v = Some(si);
        match quantity {
            Quantity::AirTemperature => record.air_temperature_k = si,
            Quantity::Pressure => record.pressure_pa = si,
            Quantity::WindSpeed => record.wind_speed_m_s = si,
            Quantity::DewPoint => record.dew_point_k = v,
            Quantity::RelativeHumidity => record.relative_humidity = v,
            Quantity::WindDirection => record.wind_direction_deg = v,
            Quantity::CloudCover => record.cloud_cover = v,
            Quantity::Ghi => record.ghi_w_m2 = v,
            Quantity::Dni => record.dni_w_m2 = v,
            Quantity::Dhi => record.dhi_w_m2 = v,
            Quantity::LongwaveDown => record.longwave_down_w_m2 = v,
        }
    }
    Ok(record)
}

/// A time with an offset or a zone (`2001-08-07T14:00:00-07:00`, `2001-08-07T21:00:00.5Z`,
/// `2001-08-07T14:00[America/Denver]`; `T` may be `t` or a space) as seconds since
/// 1970-01-01T00:00:00Z: [`crate::time::parse_time`].
///
/// # Errors
/// What is wrong with it, in words.
pub fn rfc3339(text: &str) -> Result<f64, String> {
    crate::time::parse_time(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rfc3339_times_with_every_offset_form() {
        // 2001-08-07T21:00:00Z, from Python's datetime.
        let t = 997_218_000.0;
        assert_eq!(rfc3339("2001-08-07T21:00:00Z"), Ok(t));
        assert_eq!(rfc3339("2001-08-07t21:00:00z"), Ok(t));
        assert_eq!(rfc3339("2001-08-07 21:00:00Z"), Ok(t));
        assert_eq!(rfc3339("2001-08-07T14:00:00-07:00"), Ok(t));
        assert_eq!(rfc3339("2001-08-08T02:30:00+05:30"), Ok(t));
        assert_eq!(rfc3339("2001-08-07T21:00:00.25Z"), Ok(t + 0.25));
        // Across midnight and a year's end.
        assert_eq!(
            rfc3339("2000-12-31T23:00:00-02:00"),
            rfc3339("2001-01-01T01:00:00Z")
        );
        // Seconds may be left out, as RFC 3339's profile in ISO 8601 allows.
        assert_eq!(rfc3339("2001-08-07T21:00Z"), Ok(t));
        // ISO 8601's basic offset too: unambiguous.
        assert_eq!(rfc3339("2001-08-07T14:00:00-0700"), Ok(t));
        for bad in [
            "2001-08-07T21:00:00",
            "2001-8-7T21:00:00Z",
            "2001-08-07T24:00:00Z",
            "2001-02-29T00:00:00Z",
            "2001-08-07T21:00:00.Z",
            "2001-08-07T21:00:00Z junk",
            "",
            "２001-08-07T21:00:00Z",
        ] {
            assert!(rfc3339(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn every_unit_converts_to_si_by_hand() {
        let cases = [
            (Unit::Kelvin, 300.0, 300.0),
            (Unit::Celsius, -40.0, 233.15),
            (Unit::Fahrenheit, -40.0, 233.15),
            (Unit::Fahrenheit, 32.0, 273.15),
            (Unit::Pascal, 101_325.0, 101_325.0),
            (Unit::Hectopascal, 1013.25, 101_325.0),
            (Unit::Millibar, 1013.25, 101_325.0),
            (Unit::Kilopascal, 101.325, 101_325.0),
            (Unit::MetrePerSecond, 3.0, 3.0),
            (Unit::KilometrePerHour, 36.0, 10.0),
            (Unit::Knot, 3600.0, 1852.0),
            (Unit::Degree, 270.0, 270.0),
            (Unit::WattPerSquareMetre, 0.0, 0.0),
            (Unit::Fraction, 0.25, 0.25),
            (Unit::Percent, 100.0, 1.0),
            (Unit::Okta, 8.0, 1.0),
            (Unit::Tenths, 3.0, 0.3),
        ];
        for (unit, v, si) in cases {
            assert!((unit.to_si(v) - si).abs() < 1e-9, "{unit:?} {v}");
            assert_eq!(Unit::parse(unit.text()), Some(unit));
        }
        assert_eq!(Unit::parse("°C"), Some(Unit::Celsius));
        assert_eq!(Unit::parse("kn"), Some(Unit::Knot));
        assert_eq!(Unit::parse("W/m^2"), Some(Unit::WattPerSquareMetre));
        assert_eq!(Unit::parse("degc"), None, "units are case-sensitive");
        // Every quantity's first unit is the one the "no unit" message suggests, and each
        // accepts only its own kind.
        assert_eq!(Quantity::AirTemperature.units()[0], Unit::Kelvin);
        assert!(!Quantity::Pressure.units().contains(&Unit::Kelvin));
    }

    #[test]
    fn a_mean_clause_gives_the_interval() {
        let text = "x";
        let lines = Lines::new("h.csv", text);
        let cell = Span::new(text);
        for (clause, s) in [
            ("mean 3600s", 3600.0),
            ("mean 60 min", 3600.0),
            ("mean 1h", 3600.0),
            ("mean 300 s", 300.0),
        ] {
            assert_eq!(
                mean_clause(&lines, cell, Quantity::Ghi, clause).unwrap(),
                Sampling::PrecedingMean { interval_s: s }
            );
        }
        for bad in ["avg 60s", "mean 0s", "mean -5 s", "mean 60 days", "mean s"] {
            assert!(
                mean_clause(&lines, cell, Quantity::Ghi, bad).is_err(),
                "{bad}"
            );
        }
        assert!(mean_clause(&lines, cell, Quantity::AirTemperature, "mean 60s").is_err());
    }
}
