//! The EnergyPlus weather format (EPW), as the EnergyPlus "Auxiliary Programs" manual
//! defines it (chapter "Weather Converter Program", section "EnergyPlus Weather File (EPW)
//! Data Dictionary"): eight header lines, the first `LOCATION,city,state,country,source,
//! WMO,latitude,longitude,time zone,elevation`, then one row per record of 35
//! comma-separated fields.
//!
//! What irsig reads of a row, by field (counting from 1), and how:
//!
//! | field | quantity | file unit | missing when ≥ | missing is |
//! | --- | --- | --- | --- | --- |
//! | 1–5 | year, month, day, hour (1–24), minute | local standard time | – | refused |
//! | 7 | dry-bulb temperature | °C | 99.9 | refused |
//! | 8 | dew-point temperature | °C | 99.9 | `None` (relative humidity then needed) |
//! | 9 | relative humidity | % | 999 | `None` |
//! | 10 | station pressure | Pa | 999999 | refused |
//! | 13 | horizontal infrared radiation from the sky | Wh/m² in the interval | 9999 | `None` |
//! | 14, 15, 16 | global, direct normal, diffuse horizontal radiation | Wh/m² in the interval | 9999 | `None` |
//! | 21 | wind direction | degrees from north | 999 | `None` |
//! | 22 | wind speed | m/s | 999 | refused |
//! | 23 | total sky cover | tenths | 99 | `None` |
//!
//! The other fields (flags, extraterrestrial radiation, illuminances, opaque sky cover,
//! visibility, weather codes, precipitation, ...) are read as text and not used. Times
//! are converted to UTC with the LOCATION line's time zone; radiation, the energy received
//! in the interval before the time stamp (one hour, or 60 / N minutes with N records an
//! hour from the DATA PERIODS line), becomes that interval's mean irradiance in W/m²,
//! marked [`Sampling::PrecedingMean`].

// ParseError is the crate's shared error; its size is decided there, not here.
#![allow(clippy::result_large_err)]

use irsig_model::weather::{
    RadiationSampling, Sampling, Site, Weather, WeatherRecord, utc_seconds,
};

use super::{Options, fields, range, record_field};
use crate::ParseError;
use crate::legacy::lex::{Line, Lines, Span};

/// The number of fields of a data row.
const ROW_FIELDS: usize = 35;

/// The header lines, in order, by the keyword each starts with.
const HEADERS: [&str; 8] = [
    "LOCATION",
    "DESIGN CONDITIONS",
    "TYPICAL/EXTREME PERIODS",
    "GROUND TEMPERATURES",
    "HOLIDAYS/DAYLIGHT SAVING",
    "COMMENTS 1",
    "COMMENTS 2",
    "DATA PERIODS",
];

/// A field irsig reads: its index in the row (from 0), its name for messages, and the value
/// from which on it means "missing".
struct Column {
    index: usize,
    name: &'static str,
    missing_from: f64,
}

const DRY_BULB: Column = Column {
    index: 6,
    name: "dry-bulb temperature, °C",
    missing_from: 99.9,
};
const DEW_POINT: Column = Column {
    index: 7,
    name: "dew-point temperature, °C",
    missing_from: 99.9,
};
const RELATIVE_HUMIDITY: Column = Column {
    index: 8,
    name: "relative humidity, %",
    missing_from: 999.0,
};
const PRESSURE: Column = Column {
    index: 9,
    name: "station pressure, Pa",
    missing_from: 999_999.0,
};
const INFRARED: Column = Column {
    index: 12,
    name: "horizontal infrared radiation from the sky, Wh/m²",
    missing_from: 9999.0,
};
const GHI: Column = Column {
    index: 13,
    name: "global horizontal radiation, Wh/m²",
    missing_from: 9999.0,
};
const DNI: Column = Column {
    index: 14,
    name: "direct normal radiation, Wh/m²",
    missing_from: 9999.0,
};
const DHI: Column = Column {
    index: 15,
    name: "diffuse horizontal radiation, Wh/m²",
    missing_from: 9999.0,
};
const WIND_DIRECTION: Column = Column {
    index: 20,
    name: "wind direction, degrees",
    missing_from: 999.0,
};
const WIND_SPEED: Column = Column {
    index: 21,
    name: "wind speed, m/s",
    missing_from: 999.0,
};
const SKY_COVER: Column = Column {
    index: 22,
    name: "total sky cover, tenths",
    missing_from: 99.0,
};

/// Where each value of a record came from, for errors found once all are read.
struct RowPlaces {
    /// Year to minute.
    date: (usize, usize),
    /// Every field's byte range.
    fields: Vec<(usize, usize)>,
}

/// Reads the text of an EPW file named `file` (for messages).
///
/// # Errors
/// A [`ParseError`] at the line and column of: a header line missing or out of order, a
/// LOCATION field that is not a number, a records-per-hour that does not divide an hour, a
/// row without 35 fields, a date or time that does not exist, a year that changes between
/// months without [`Options::year`] (a typical-year file), a required value missing (dry
/// bulb, pressure, wind speed), a value that is not a finite number, and whatever the
/// record's rules refuse ([`Weather::validate`]: ranges, order, gaps, a record without a
/// humidity), at the value.
pub fn parse(file: &str, text: &str, options: &Options) -> Result<Weather, ParseError> {
    let mut lines = Lines::new(file, text);
    let mut header = Vec::with_capacity(HEADERS.len());
    for keyword in HEADERS {
        let line = lines.expect_line(&format!("the EPW header line `{keyword},...`"))?;
        if !line.span.fragment().starts_with(keyword) {
            return Err(lines.error(
                line.span,
                format!(
                    "expected the EPW header line `{keyword},...` (the 8 header lines come \
                     in order: {})",
                    HEADERS.join(", ")
                ),
            ));
        }
        header.push(line);
    }
    let (site, source) = location(&lines, header[0], file)?;
    let per_hour = records_per_hour(&lines, header[7])?;
    let interval_s = 3600.0 / f64::from(per_hour);
    let mut records = Vec::new();
    let mut places = Vec::new();
    let mut last_date: Option<(i64, u32)> = None;
    while let Some(line) = lines.next_line() {
        let row = fields(line);
        if row.len() != ROW_FIELDS {
            let at = row.get(ROW_FIELDS).copied().unwrap_or(line.span);
            return Err(lines.error(
                at,
                format!(
                    "expected {ROW_FIELDS} comma-separated fields (an EPW data row), found {}",
                    row.len()
                ),
            ));
        }
        let (local_s, year, month) = row_time(&lines, &row, per_hour, options)?;
        if options.year.is_none()
            && let Some((last_year, last_month)) = last_date
            && year != last_year
            && !(month == 1 && last_month == 12 && year == last_year + 1)
        {
            return Err(lines.error(
                row[0],
                format!(
                    "the year changes from {last_year} to {year} between months: a \
                     typical-year file (TMY, IWEC) takes each month from another year, so \
                     its years make no time line; give the year to read it as"
                ),
            ));
        }
        last_date = Some((year, month));
        let time_s = local_s - site.utc_offset_h * 3600.0;
        records.push(row_record(&lines, &row, time_s, interval_s)?);
        let date_end = row[4].location_offset() + row[4].fragment().len();
        places.push(RowPlaces {
            date: (
                row[0].location_offset(),
                date_end - row[0].location_offset(),
            ),
            fields: row.iter().map(|s| range(*s)).collect(),
        });
    }
    let weather = Weather {
        site: Some(site),
        records,
        radiation: RadiationSampling::all(Sampling::PrecedingMean { interval_s }),
        source,
    };
    weather
        .validate()
        .map_err(|e| place_error(file, text, &lines, &places, &e))?;
    Ok(weather)
}

/// The site and the source text from the LOCATION line.
fn location(lines: &Lines<'_>, line: Line<'_>, file: &str) -> Result<(Site, String), ParseError> {
    let f = fields(line);
    if f.len() < 10 {
        return Err(lines.error(
            line.span,
            format!(
                "expected 10 fields `LOCATION,city,state,country,source,WMO,latitude,\
                 longitude,time zone,elevation`, found {}",
                f.len()
            ),
        ));
    }
    let number = |i: usize, what: &str| lines.real(f[i], what);
    let site = Site {
        name: f[1].fragment().to_string(),
        latitude_deg: number(6, "latitude, degrees north")?,
        longitude_deg: number(7, "longitude, degrees east")?,
        utc_offset_h: number(8, "time zone, hours from UTC")?,
        elevation_m: number(9, "elevation, m")?,
    };
    let checks = [
        (6, site.latitude_deg, -90.0, 90.0),
        (7, site.longitude_deg, -180.0, 180.0),
        (8, site.utc_offset_h, -12.0, 14.0),
        (9, site.elevation_m, -1000.0, 9000.0),
    ];
    for (i, value, min, max) in checks {
        if !(min..=max).contains(&value) {
            return Err(lines.error(f[i], format!("expected {min} to {max}, found {value}")));
        }
    }
    let text = |i: usize| f[i].fragment().trim().to_string();
    let source = format!(
        "EPW {file}: {}, {}, {} ({}, WMO {})",
        text(1),
        text(2),
        text(3),
        text(4),
        text(5)
    );
    Ok((site, source))
}

/// The number of records an hour, from the DATA PERIODS line's second field.
fn records_per_hour(lines: &Lines<'_>, line: Line<'_>) -> Result<u32, ParseError> {
    let f = fields(line);
    let Some(&tok) = f.get(2) else {
        return Err(lines.error(
            line.span,
            "expected `DATA PERIODS,number of periods,records per hour,...`",
        ));
    };
    let n = lines.unsigned(tok, "records per hour")?;
    match u32::try_from(n) {
        Ok(n) if n > 0 && 60 % n == 0 => Ok(n),
        _ => Err(lines.error(
            tok,
            format!("expected a number of records per hour that divides 60 minutes, found {n}"),
        )),
    }
}

/// A row's local standard time (s since 1970-01-01T00:00 of the local clock), its year and
/// its month.
fn row_time(
    lines: &Lines<'_>,
    row: &[Span<'_>],
    per_hour: u32,
    options: &Options,
) -> Result<(f64, i64, u32), ParseError> {
    let whole = |i: usize, what: &str| lines.unsigned(row[i], what);
    let file_year = whole(0, "year")?;
    let year = options
        .year
        .unwrap_or_else(|| i64::try_from(file_year).unwrap_or(i64::MAX));
    let small = |i: usize, what: &str| -> Result<u32, ParseError> {
        let v = whole(i, what)?;
        u32::try_from(v).map_err(|_| lines.error(row[i], format!("{what} {v} is too large")))
    };
    let (month, day, hour, minute) = (
        small(1, "month")?,
        small(2, "day")?,
        small(3, "hour, 1 to 24")?,
        small(4, "minute")?,
    );
    if !(1..=24).contains(&hour) {
        return Err(lines.error(
            row[3],
            format!("expected an hour 1 to 24 (hour 1 ends at 01:00), found {hour}"),
        ));
    }
    // One record an hour: the stamp is the hour's end, whatever the minute says (0 in TMY3
    // conversions, 60 in IWEC). More: the minute within the hour ends each interval.
    let (clock_hour, clock_minute) = if per_hour == 1 {
        if minute != 0 && minute != 60 {
            return Err(lines.error(
                row[4],
                format!(
                    "expected minute 0 or 60 in a file of one record an hour (DATA \
                     PERIODS), found {minute}"
                ),
            ));
        }
        (hour, 0)
    } else {
        let step = 60 / per_hour;
        if minute == 0 || minute > 60 || minute % step != 0 {
            return Err(lines.error(
                row[4],
                format!(
                    "expected a minute 1 to 60 that ends one of the {per_hour} intervals of \
                     the hour ({step}, {}, ...), found {minute}",
                    2 * step
                ),
            ));
        }
        (hour - 1, minute)
    };
    let local = utc_seconds(year, month, day, clock_hour, 0, 0.0).map_err(|why| {
        let at = match why.split(' ').next() {
            Some("year") => 0,
            Some("month") => 1,
            _ => 2,
        };
        lines.error(row[at], format!("no such date: {why}"))
    })?;
    Ok((local + f64::from(clock_minute) * 60.0, year, month))
}

/// A number of `column`, or `None` when it holds the missing-value code (or is blank).
fn value(lines: &Lines<'_>, row: &[Span<'_>], column: &Column) -> Result<Option<f64>, ParseError> {
    let tok = row[column.index];
    if tok.fragment().is_empty() {
        return Ok(None);
    }
    let v = lines.real(tok, column.name)?;
    Ok((v < column.missing_from).then_some(v))
}

/// A number of a column the record cannot do without: missing is refused.
fn required(lines: &Lines<'_>, row: &[Span<'_>], column: &Column) -> Result<f64, ParseError> {
    value(lines, row, column)?.ok_or_else(|| {
        lines.error(
            row[column.index],
            format!(
                "the {} is missing (≥ {} or blank, the format's missing-value code), and a \
                 weather record needs it at every time",
                column.name, column.missing_from
            ),
        )
    })
}

/// A row's record in SI: °C to K, % to a fraction, tenths to a fraction, the energy of an
/// interval (Wh/m²) to its mean irradiance (W/m²).
fn row_record(
    lines: &Lines<'_>,
    row: &[Span<'_>],
    time_s: f64,
    interval_s: f64,
) -> Result<WeatherRecord, ParseError> {
    let kelvin = |c: f64| c + 273.15;
    let per_interval = |wh: f64| wh * 3600.0 / interval_s;
    let radiation =
        |column: &Column| Ok::<_, ParseError>(value(lines, row, column)?.map(per_interval));
    Ok(WeatherRecord {
        time_s,
        air_temperature_k: kelvin(required(lines, row, &DRY_BULB)?),
        dew_point_k: value(lines, row, &DEW_POINT)?.map(kelvin),
        pressure_pa: required(lines, row, &PRESSURE)?,
        wind_speed_m_s: required(lines, row, &WIND_SPEED)?,
        wind_direction_deg: value(lines, row, &WIND_DIRECTION)?,
        cloud_cover: value(lines, row, &SKY_COVER)?.map(|tenths| tenths / 10.0),
        relative_humidity: value(lines, row, &RELATIVE_HUMIDITY)?.map(|p| p / 100.0),
        ghi_w_m2: radiation(&GHI)?,
        dni_w_m2: radiation(&DNI)?,
        dhi_w_m2: radiation(&DHI)?,
        longwave_down_w_m2: radiation(&INFRARED)?,
    })
}

/// A rule of the record broken, reported at the value (or the date) it concerns.
fn place_error(
    file: &str,
    text: &str,
    lines: &Lines<'_>,
    places: &[RowPlaces],
    e: &irsig_model::ModelError,
) -> ParseError {
    let Some((i, field)) = record_field(e) else {
        return lines.eof_error(&format!("the weather record: {e}"));
    };
    let Some(place) = places.get(i) else {
        return lines.eof_error(&format!("the weather record: {e}"));
    };
    let column = match field {
        "air_temperature_k" => Some(&DRY_BULB),
        "dew_point_k" => Some(&DEW_POINT),
        "relative_humidity" => Some(&RELATIVE_HUMIDITY),
        "pressure_pa" => Some(&PRESSURE),
        "wind_speed_m_s" => Some(&WIND_SPEED),
        "wind_direction_deg" => Some(&WIND_DIRECTION),
        "cloud_cover" => Some(&SKY_COVER),
        "ghi_w_m2" => Some(&GHI),
        "dni_w_m2" => Some(&DNI),
        "dhi_w_m2" => Some(&DHI),
        "longwave_down_w_m2" => Some(&INFRARED),
        _ => None,
    };
    let (offset, len) = column.map_or(place.date, |c| place.fields[c.index]);
    let found = &text[offset..offset + len];
    let message = match column {
        Some(c) => format!("{} `{found}`: as {field} in SI, {}", c.name, e.kind),
        None => format!("the time `{found}`: {}", e.kind),
    };
    ParseError::at_span(file, text, offset, len, message)
}
