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

/// One almanac row: the instant (UT), the latitude (°, north positive), the upper (noon)
/// or lower (midnight) culmination, the almanac's zenith angle there (°), and the azimuth
/// the sun crosses at (°, clockwise from north; `None` overhead, where it has none).
type AlmanacRow = (&'static str, f64, bool, f64, Option<f64>);

/// The table of docs/accuracy.md ("Almanac values"), each row's zenith from the almanac
/// relations above, not from SPA.
const ALMANAC: [AlmanacRow; 7] = [
    // June solstice: RIT at noon, due south; the subsolar latitude, the sun overhead;
    // Sydney (33.87° S), midwinter noon, low in the north; RIT at solar midnight,
    // 23.48° below the northern horizon.
    (
        "2026-06-21T08:24:00Z",
        43.08,
        true,
        43.08 - OBLIQUITY_2026_DEG,
        Some(180.0),
    ),
    ("2026-06-21T08:24:00Z", OBLIQUITY_2026_DEG, true, 0.0, None),
    (
        "2026-06-21T08:24:00Z",
        -33.87,
        true,
        33.87 + OBLIQUITY_2026_DEG,
        Some(0.0),
    ),
    (
        "2026-06-21T08:24:00Z",
        43.08,
        false,
        180.0 - 43.08 - OBLIQUITY_2026_DEG,
        Some(0.0),
    ),
    // December solstice and March equinox at RIT, noon; on the equator at the equinox
    // the noon sun is overhead.
    (
        "2026-12-21T20:50:00Z",
        43.08,
        true,
        43.08 + OBLIQUITY_2026_DEG,
        Some(180.0),
    ),
    ("2026-03-20T14:46:00Z", 43.08, true, 43.08, Some(180.0)),
    ("2026-03-20T14:46:00Z", 0.0, true, 0.0, None),
];

/// Every row within [`ALMANAC_TOLERANCE_DEG`] of the almanac's zenith and 0.01° of its
/// azimuth. With `--nocapture` it prints the rows of docs/accuracy.md's table (`cargo test
/// -p irsig-atmosphere --lib the_sun_crosses_the_meridian -- --nocapture`), whose last
/// column, the topocentric parallax the almanac leaves out, accounts for the differences.
#[test]
#[allow(clippy::print_stderr)]
fn the_sun_crosses_the_meridian_where_the_almanac_says() {
    for (utc, latitude, upper, almanac, azimuth_want) in ALMANAC {
        let (z, azimuth) = culmination(utc, latitude, upper);
        let parallax = 8.8 / 3600.0 * z.to_radians().sin();
        eprintln!(
            "| {utc} | {latitude}° | {almanac:.4} | {z:.4} | {:+.4} | {parallax:.4} |",
            z - almanac
        );
        assert!(
            (z - almanac).abs() < ALMANAC_TOLERANCE_DEG,
            "{utc} at {latitude}°: zenith {z} against the almanac's {almanac}"
        );
        if let Some(want) = azimuth_want {
            assert!(
                azimuth_difference(azimuth, want) < 0.01,
                "{utc} at {latitude}°: azimuth {azimuth} against {want}"
            );
        }
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
        ron::from_str::<SunSpec>(r#"At(utc: "2026-06-21T12:00:00Z", latitude_deg: 1)"#).is_err()
    );
}
