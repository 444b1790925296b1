//! The weather readers on the shipped sample (`formats/samples/golden-tmy3-aug.epw`, four
//! August days of NREL's TMY3 for Golden, Colorado, as EnergyPlus ships it) read back with
//! values checked by hand against its rows, and every refusal of both forms at its line and
//! column. The malformed inputs are the sample or a small CSV with one edit each, made here
//! (no tool reads weather yet, so they are not in the end-to-end malformed corpus).

// Times are whole seconds and the file's numbers are read as printed: exact in f64.
#![allow(clippy::float_cmp)]

use std::path::PathBuf;

use irsig_formats::weather::{self, Options};
use irsig_model::weather::{Sampling, Weather, WeatherErrorKind};

fn sample_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../formats/samples/golden-tmy3-aug.epw")
}

fn sample_text() -> String {
    let bytes = irsig_formats::file::read_file(&sample_path()).unwrap();
    String::from_utf8(bytes).unwrap()
}

fn read_epw(text: &str) -> Result<Weather, irsig_formats::ParseError> {
    weather::read("golden.epw", text.as_bytes(), &Options::default())
}

/// `text` with the first `old` after the line starting `line_start` replaced by `new`.
fn edit_row(text: &str, line_start: &str, old: &str, new: &str) -> String {
    let at = text
        .find(line_start)
        .unwrap_or_else(|| panic!("no {line_start}"));
    let within = text[at..].find(old).unwrap() + at;
    format!("{}{new}{}", &text[..within], &text[within + old.len()..])
}

/// Seconds since 1970-01-01T00:00:00Z, from Python's `datetime` (an independent calendar).
const AUG_4_0800Z: f64 = 996_912_000.0;
const AUG_7_2100Z: f64 = 997_218_000.0;
const AUG_8_0030Z: f64 = 997_230_600.0;
const AUG_8_0100Z: f64 = 997_232_400.0;
const AUG_8_0700Z: f64 = 997_254_000.0;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[test]
fn the_sample_reads_back_as_its_rows_say() {
    let w = read_epw(&sample_text()).unwrap();
    let site = w.site.as_ref().unwrap();
    // LOCATION,Denver Centennial  Golden   Nr,CO,USA,TMY3,724666,39.74,-105.18,-7.0,1829.0
    assert_eq!(site.name, "Denver Centennial  Golden   Nr");
    assert_eq!(
        (
            site.latitude_deg,
            site.longitude_deg,
            site.utc_offset_h,
            site.elevation_m
        ),
        (39.74, -105.18, -7.0, 1829.0)
    );
    assert!(w.source.contains("WMO 724666"), "{}", w.source);
    // 96 hourly rows, 2001-08-04 01:00 to 2001-08-07 24:00 local standard time (UTC−7).
    assert_eq!(w.records.len(), 96);
    assert_eq!(w.span_s(), Some((AUG_4_0800Z, AUG_8_0700Z)));
    assert_eq!(
        w.radiation.ghi,
        Sampling::PrecedingMean { interval_s: 3600.0 }
    );
    // Line 94, 2001-08-07 hour 14: 32.0 °C, dew point 8.0 °C, 23 %, 83500 Pa, infrared
    // 425, GHI 863, DNI 759, DHI 204 Wh/m², wind from 160° at 5.7 m/s, sky cover 6 tenths.
    let r = &w.records[85];
    assert_eq!(r.time_s, AUG_7_2100Z);
    assert!(close(r.air_temperature_k, 305.15));
    assert!(close(r.dew_point_k.unwrap(), 281.15));
    assert!(close(r.relative_humidity.unwrap(), 0.23));
    assert_eq!(r.pressure_pa, 83_500.0);
    assert_eq!(r.longwave_down_w_m2, Some(425.0));
    assert_eq!(
        (r.ghi_w_m2, r.dni_w_m2, r.dhi_w_m2),
        (Some(863.0), Some(759.0), Some(204.0))
    );
    assert_eq!((r.wind_direction_deg, r.wind_speed_m_s), (Some(160.0), 5.7));
    assert!(close(r.cloud_cover.unwrap(), 0.6));
    // 17:30 local: halfway from hour 17 (31.0 °C) to hour 18 (29.0 °C), so 30.0 °C; the
    // GHI of the hour ending at 18:00 (253 Wh/m²) belongs to 17:30.
    let c = w.at(AUG_8_0030Z).unwrap();
    assert!(
        close(c.air_temperature_k, 303.15),
        "{}",
        c.air_temperature_k
    );
    assert_eq!(c.ghi_w_m2, Some(253.0));
    // 18:00 local: halfway from 17:30 (253) to 18:30 (the hour ending 19:00, 58).
    let c = w.at(AUG_8_0100Z).unwrap();
    assert!(close(c.ghi_w_m2.unwrap(), 155.5));
    assert!(close(c.air_temperature_k, 302.15), "29.0 °C at 18:00");
    // Outside the four days: refused, naming the time and the span.
    let e = w.at(AUG_8_0700Z + 1.0).unwrap_err();
    assert!(matches!(e.kind, WeatherErrorKind::OutsideRecord { .. }));
    let text = e.to_string();
    assert!(
        text.contains("2001-08-08T07:00:01Z")
            && text.contains("2001-08-04T08:00:00Z")
            && text.contains("2001-08-08T07:00:00Z"),
        "{text}"
    );
}

#[test]
fn a_typical_year_is_read_as_the_year_asked_for() {
    // The sample's rows are all 2001; read as 2019 they move by 18 years (4 leap days).
    let options = Options { year: Some(2019) };
    let w = weather::read("golden.epw", sample_text().as_bytes(), &options).unwrap();
    let days = 18.0 * 365.0 + 4.0;
    assert_eq!(w.records[0].time_s, AUG_4_0800Z + days * 86_400.0);
    // Without it, a year that changes between months is refused at its row.
    let mixed = edit_row(&sample_text(), "2001,8,6,1,", "2001", "1999");
    let e = read_epw(&mixed).unwrap_err();
    assert_eq!((e.line, e.column), (57, 1), "{e}");
    assert!(e.message.contains("typical-year"), "{e}");
}

/// `(line, column)` of the refusal of `text`, and its message.
fn refusal(text: &str) -> (usize, usize, String) {
    let e = read_epw(text).unwrap_err();
    (e.line, e.column, e.message)
}

#[test]
fn an_epw_is_refused_at_the_value() {
    let base = sample_text();
    // Line 94 (2001-08-07 hour 14): dry bulb at column 66, dew point 71, pressure 78,
    // GHI 98, wind speed 137 (counted with Python's str.split).
    let row = "2001,8,7,14,";
    let cases: [(&str, &str, usize, &str); 6] = [
        (",32.0,8.0,", ",99.9,8.0,", 66, "missing"),
        (",32.0,8.0,", ",NaN,8.0,", 66, "finite"),
        (",83500,", ",999999,", 78, "missing"),
        (",83500,", ",20000,", 78, "out of range"),
        (",863,", ",-5,", 98, "out of range"),
        (",5.7,6,", ",999,6,", 137, "missing"),
    ];
    for (old, new, column, fragment) in cases {
        let (l, c, m) = refusal(&edit_row(&base, row, old, new));
        assert_eq!((l, c), (94, column), "{new}: {m}");
        assert!(m.contains(fragment), "{new}: {m}");
    }
    // A missing dew point is no refusal while the relative humidity is there...
    let w = read_epw(&edit_row(&base, row, ",32.0,8.0,", ",32.0,99.9,")).unwrap();
    assert_eq!(w.records[85].dew_point_k, None);
    assert!(w.at(AUG_7_2100Z).unwrap().dew_point_k < 285.0);
    // ... but without both, the row has no humidity: refused at the dew point.
    let (l, c, m) = refusal(&edit_row(&base, row, ",32.0,8.0,23,", ",32.0,99.9,999,"));
    assert_eq!((l, c), (94, 71), "{m}");
    assert!(m.contains("neither"), "{m}");
    // Missing optional columns are `None`: sky cover 99, GHI 9999, wind direction 999.
    let w = read_epw(&edit_row(&base, row, ",160,5.7,6,", ",999,5.7,99,")).unwrap();
    assert_eq!(
        (w.records[85].wind_direction_deg, w.records[85].cloud_cover),
        (None, None)
    );
    let w = read_epw(&edit_row(&base, row, ",863,", ",9999,")).unwrap();
    assert_eq!(w.records[85].ghi_w_m2, None);
}

#[test]
fn an_epw_with_a_gap_a_repeat_or_a_bad_header_is_refused_at_its_line() {
    let base = sample_text();
    // Three hours cut out after 2001-08-05 03:00 (line 35): the row after, hour 7 on line
    // 36 of the cut file, follows a 4 h step, more than 3 median (1 h) steps.
    let cut: String = base
        .lines()
        .enumerate()
        .filter(|(i, _)| !(35..38).contains(i))
        .map(|(_, l)| format!("{l}\n"))
        .collect();
    let (l, c, m) = refusal(&cut);
    assert_eq!((l, c), (36, 1), "{m}");
    assert!(m.contains("gap of 4 h"), "{m}");
    // Hour 3 of 2001-08-05 written as hour 2 repeats hour 2's time (line 35).
    let (l, c, m) = refusal(&edit_row(
        &base,
        "2001,8,5,3,",
        "2001,8,5,3,",
        "2001,8,5,2,",
    ));
    assert_eq!((l, c), (35, 1), "{m}");
    assert!(m.contains("repeats"), "{m}");
    // Hours run 1 to 24.
    let (l, c, _) = refusal(&edit_row(
        &base,
        "2001,8,5,3,",
        "2001,8,5,3,",
        "2001,8,5,0,",
    ));
    assert_eq!((l, c), (35, 10));
    // A day August does not have.
    let (l, c, m) = refusal(&edit_row(
        &base,
        "2001,8,5,3,",
        "2001,8,5,3,",
        "2001,8,32,3,",
    ));
    assert_eq!((l, c, m.contains("no such date")), (35, 8, true), "{m}");
    // The header lines in their order.
    let swapped = base.replacen("COMMENTS 1", "COMMENTS 9", 1);
    let (l, c, m) = refusal(&swapped);
    assert_eq!((l, c), (6, 1), "{m}");
    assert!(m.contains("COMMENTS 1"), "{m}");
    // A row of 34 fields.
    let short = edit_row(&base, "2001,8,4,3,", ",999.0,99.0\n", ",999.0\n");
    let (l, _, m) = refusal(&short);
    assert_eq!(l, 11, "{m}");
    assert!(m.contains("35"), "{m}");
    // A latitude beyond the pole.
    let (l, c, _) = refusal(&base.replacen(",39.74,", ",99.74,", 1));
    assert_eq!((l, c), (1, 60));
    // Records per hour that do not divide the hour.
    let (l, c, _) = refusal(&base.replacen("DATA PERIODS,1,1,", "DATA PERIODS,1,7,", 1));
    assert_eq!((l, c), (8, 16));
}

fn csv(text: &str) -> Result<Weather, irsig_formats::ParseError> {
    weather::read("day.csv", text.as_bytes(), &Options::default())
}

const GOOD_CSV: &str = "\
time,air_temperature[degC],dew_point[degC],pressure[hPa],wind_speed[m/s],ghi[W/m2 mean 3600s]
2001-08-07T14:00:00-07:00,32.0,8.0,835,5.7,863
2001-08-07T15:00:00-07:00,32.0,8.0,835,6.2,760
2001-08-07T16:00:00-07:00,32.0,8.0,834,5.7,622
2001-08-07T17:00:00-07:00,31.0,8.0,834,6.2,375
";

#[test]
fn the_csv_form_reads_units_and_offsets() {
    let w = csv(GOOD_CSV).unwrap();
    assert_eq!(w.records.len(), 4);
    assert_eq!(w.records[0].time_s, AUG_7_2100Z);
    assert!(close(w.records[0].air_temperature_k, 305.15));
    assert!(close(w.records[0].pressure_pa, 83_500.0));
    assert_eq!(w.records[3].ghi_w_m2, Some(375.0));
    assert_eq!(
        w.radiation.ghi,
        Sampling::PrecedingMean { interval_s: 3600.0 }
    );
    assert_eq!(w.radiation.dni, Sampling::Instantaneous);
    // The same record in other units, in UTC, with an extra column and a missing optional
    // value: 89.6 °F is 32 °C, 83.5 kPa, 20.52 km/h is 5.7 m/s, 40 % humidity.
    let other = "\
# the same hour, other units
time , air_temperature[degF], relative_humidity[%], pressure[kPa], wind_speed[km/h], cloud_cover[okta], x_surface_temperature[degC]
2001-08-07T21:00:00Z,89.6,40,83.5,20.52,4,41.2
2001-08-07T22:00:00.5Z,89.6,40,83.5,20.52,,40.1
";
    let w = csv(other).unwrap();
    let r = &w.records[0];
    assert!(
        close(r.air_temperature_k, 305.15),
        "{}",
        r.air_temperature_k
    );
    assert!(close(r.pressure_pa, 83_500.0));
    assert!(close(r.wind_speed_m_s, 5.7));
    assert_eq!((r.relative_humidity, r.dew_point_k), (Some(0.4), None));
    assert_eq!(r.cloud_cover, Some(0.5));
    assert_eq!(w.records[1].cloud_cover, None);
    assert_eq!(w.records[1].time_s, AUG_7_2100Z + 3600.5);
    // Knots and millibars: 10 kn is 18.52 km/h.
    let knots = GOOD_CSV
        .replace("wind_speed[m/s]", "wind_speed[knots]")
        .replace("pressure[hPa]", "pressure[mbar]");
    let w = csv(&knots).unwrap();
    assert!(close(w.records[0].wind_speed_m_s, 5.7 * 1852.0 / 3600.0));
    assert!(close(w.records[0].pressure_pa, 83_500.0));
}

#[test]
fn a_csv_is_refused_at_the_line_and_column() {
    let swap = |old: &str, new: &str| GOOD_CSV.replacen(old, new, 1);
    let cases: Vec<(String, usize, usize, &str)> = vec![
        // A column without a unit, and one with a unit irsig does not take.
        (
            swap("air_temperature[degC]", "air_temperature"),
            1,
            6,
            "no unit",
        ),
        (
            swap("pressure[hPa]", "pressure[inHg]"),
            1,
            44,
            "unknown unit `inHg`",
        ),
        (
            swap("pressure[hPa]", "presure[hPa]"),
            1,
            44,
            "unknown column",
        ),
        (swap(",wind_speed[m/s]", ""), 1, 1, "wind_speed"),
        (swap("time,", "time[s],"), 1, 1, "no unit"),
        (
            swap("dew_point[degC]", "dew_point[degC mean 60s]"),
            1,
            28,
            "radiation",
        ),
        // A NaN, a word, nothing in a required column, a short row.
        (swap("32.0,8.0,835,6.2", "NaN,8.0,835,6.2"), 3, 27, "finite"),
        (swap("835,5.7,863", "835,calm,863"), 2, 40, "number"),
        (swap("32.0,8.0,834,5.7", ",8.0,834,5.7"), 4, 27, "required"),
        (
            swap("835,5.7,863", "835,5.7"),
            2,
            1,
            "6 comma-separated fields",
        ),
        // Times: without an offset, not a date, repeated, going back, after a gap.
        (
            swap("2001-08-07T15:00:00-07:00", "2001-08-07T15:00:00"),
            3,
            1,
            "offset",
        ),
        (
            swap("2001-08-07T15:00:00-07:00", "2001-08-07 3pm"),
            3,
            1,
            "RFC 3339",
        ),
        (swap("T15:00:00-07:00", "T14:00:00-07:00"), 3, 1, "repeats"),
        (
            swap("T16:00:00-07:00", "T13:00:00-07:00"),
            4,
            1,
            "comes before",
        ),
        (
            swap("T17:00:00-07:00", "T21:00:00-07:00"),
            5,
            1,
            "gap of 5 h",
        ),
        // A value out of its range, reported in the file's unit and in SI.
        (swap("31.0,8.0,834", "91.0,8.0,834"), 5, 27, "364.15"),
    ];
    for (text, line, column, fragment) in cases {
        let e = csv(&text).unwrap_err();
        assert_eq!((e.line, e.column), (line, column), "{e}\n{text}");
        assert!(e.message.contains(fragment), "{fragment}: {e}");
    }
    // One record is no record.
    let one: String = GOOD_CSV.lines().take(2).map(|l| format!("{l}\n")).collect();
    let e = csv(&one).unwrap_err();
    assert!(e.message.contains("at least two"), "{e}");
    // Not UTF-8.
    let e = weather::read("bad.csv", b"time\xff", &Options::default()).unwrap_err();
    assert!(e.message.contains("UTF-8"), "{e}");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]

    /// Any byte anywhere in either form, or the file cut anywhere: an answer, never a panic.
    #[test]
    fn no_input_panics(at in 0usize..20_000, byte in proptest::prelude::any::<u8>(), cut in 0usize..20_000) {
        for base in [sample_text(), GOOD_CSV.to_owned()] {
            let mut bytes = base.into_bytes();
            let at = at % bytes.len();
            bytes[at] = byte;
            let _ = weather::read("f", &bytes, &Options::default());
            bytes.truncate(cut % (bytes.len() + 1));
            let _ = weather::read("f", &bytes, &Options { year: Some(2019) });
        }
    }
}
