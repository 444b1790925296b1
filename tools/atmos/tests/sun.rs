//! `irsig-atmos sun` end to end: the SPA paper's worked example through the command line
//! (angles and the scene-frame vector), the plain table with its units, a sun below the
//! horizon said on stderr, the old spelling `--utc` of `--sun-utc` still taken, a sun
//! given as a direction echoed, and each bad flag refused at parse time by name with its
//! range, exit 2, and nothing on stdout.

use assert_cmd::Command;

fn atmos() -> Command {
    Command::cargo_bin("irsig-atmos").unwrap()
}

/// The SPA paper's worked example (Reda & Andreas, NREL/TP-560-34302 rev. 2008, Table
/// A5.1, and NREL's spa_tester.c): 2003-10-17 12:30:30 at UTC−7, 39.742476° N, 105.1786° W,
/// 1830.14 m, 820 mbar, 11 °C, ΔT = 67 s.
const SPA_EXAMPLE: [&str; 15] = [
    "sun",
    "--sun-utc",
    "2003-10-17T19:30:30Z",
    "--latitude-deg",
    "39.742476",
    "--longitude-deg",
    "-105.1786",
    "--altitude-m",
    "1830.14",
    "--pressure-hpa",
    "820",
    "--temperature-c",
    "11",
    "--delta-t-s",
    "67",
];

fn stdout_of(args: &[&str]) -> String {
    let out = atmos().args(args).assert().success();
    String::from_utf8(out.get_output().stdout.clone()).unwrap()
}

#[test]
fn the_spa_example_through_the_command_line() {
    let csv = stdout_of(&[&SPA_EXAMPLE[..], &["--format", "csv"]].concat());
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header,
        [
            "zenith_deg",
            "geometric_zenith_deg",
            "azimuth_deg",
            "elevation_deg",
            "x_east",
            "y_north",
            "z_up"
        ]
    );
    let row: Vec<f64> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(lines.next().is_none(), "{csv}");
    // Published: topocentric (refracted) zenith 50.111622°, azimuth 194.340241°.
    let (zenith, azimuth) = (50.111_622_f64, 194.340_241_f64);
    assert!((row[0] - zenith).abs() < 2e-6, "{row:?}");
    assert!((row[2] - azimuth).abs() < 2e-6, "{row:?}");
    assert!((row[3] - (90.0 - zenith)).abs() < 2e-6, "{row:?}");
    // Refraction lifts the sun by SPA's eq. 42: about 0.0163° here.
    assert!((row[1] - row[0] - 0.0163).abs() < 3e-4, "{row:?}");
    // The vector toward the sun: east = sin z sin A, north = sin z cos A, up = cos z.
    let (z, a) = (zenith.to_radians(), azimuth.to_radians());
    let want = [z.sin() * a.sin(), z.sin() * a.cos(), z.cos()];
    for (got, want) in row[4..].iter().zip(want) {
        assert!((got - want).abs() < 1e-6, "{row:?}");
    }
}

#[test]
fn the_table_states_its_units_and_a_sun_below_the_horizon_is_said_on_stderr() {
    // `--utc`, the old spelling of `--sun-utc`, is still taken.
    let rit = [
        "sun",
        "--utc",
        "2026-06-21T12:00:00Z",
        "--latitude-deg",
        "43.08",
        "--longitude-deg",
        "-77.67",
    ];
    let out = atmos().args(rit).assert().success();
    let output = out.get_output();
    assert!(output.stderr.is_empty(), "{output:?}");
    let text = String::from_utf8(output.stdout.clone()).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split_whitespace().collect();
    assert_eq!(
        header,
        [
            "zenith_deg",
            "azimuth_deg",
            "elevation_deg",
            "x_east",
            "y_north",
            "z_up"
        ]
    );
    let row: Vec<f64> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    // Eight in the morning (EDT) at RIT on midsummer's day: in the east-north-east, up.
    assert!(row[0] < 90.0 && row[1] > 45.0 && row[1] < 90.0, "{text}");
    assert!(row[3] > 0.5 && row[5] > 0.0, "{text}");
    // Midnight EDT: below the horizon, said on stderr, the numbers still on stdout.
    let mut night = rit;
    night[2] = "2026-06-21T04:00:00Z";
    let out = atmos().args(night).assert().success();
    let output = out.get_output();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("below the horizon"), "{stderr}");
    let text = String::from_utf8(output.stdout.clone()).unwrap();
    let up: f64 = text
        .lines()
        .nth(1)
        .unwrap()
        .split_whitespace()
        .last()
        .unwrap()
        .parse()
        .unwrap();
    assert!(up < 0.0, "{text}");
}

#[test]
fn bad_flags_are_refused_by_name_with_their_range() {
    let with = |flag: &str, value: &str| -> Vec<String> {
        let mut args: Vec<String> = SPA_EXAMPLE.iter().map(ToString::to_string).collect();
        match args.iter().position(|a| a == flag) {
            Some(i) => args[i + 1] = value.to_owned(),
            None => args.extend([flag.to_owned(), value.to_owned()]),
        }
        args
    };
    let cases = [
        (
            with("--latitude-deg", "91"),
            2,
            ["--latitude-deg", "[-90, 90]"],
        ),
        (with("--latitude-deg", "NaN"), 2, ["--latitude-deg", "NaN"]),
        (
            with("--longitude-deg", "-180.5"),
            2,
            ["--longitude-deg", "[-180, 180]"],
        ),
        (with("--altitude-m", "1e6"), 2, ["--altitude-m", "100000"]),
        (
            with("--sun-utc", "2003-10-17T19:30:30"),
            2,
            ["--sun-utc", "`Z`"],
        ),
        (
            with("--sun-utc", "2003-10-17"),
            2,
            ["--sun-utc", "YYYY-MM-DDTHH:MM:SS"],
        ),
        (
            with("--sun-utc", "7000-01-01T00:00:00Z"),
            2,
            ["--sun-utc", "-2000 to 6000"],
        ),
        (
            with("--sun-utc", "2003-02-30T00:00:00Z"),
            2,
            ["--sun-utc", "day"],
        ),
        (
            with("--pressure-hpa", "-3"),
            2,
            ["--pressure-hpa", "(0, 1100]"],
        ),
        (
            with("--temperature-c", "200"),
            2,
            ["--temperature-c", "[-100, 60]"],
        ),
        (
            with("--delta-ut1-s", "1.5"),
            2,
            ["--delta-ut1-s", "[-0.9, 0.9]"],
        ),
        (with("--delta-t-s", "inf"), 2, ["--delta-t-s", "finite"]),
        // Was "--utc: invalid date/time", a flag given rightly.
        (
            with("--delta-t-s", "1e308"),
            1,
            ["--delta-t-s", "ΔT of 1e308 s"],
        ),
        (
            with("--latitude-deg", "north"),
            2,
            ["--latitude-deg", "north"],
        ),
    ];
    for (args, code, says) in &cases {
        let out = atmos().args(args).assert().code(*code);
        let output = out.get_output();
        let stderr = String::from_utf8_lossy(&output.stderr);
        for s in says {
            assert!(stderr.contains(s), "{args:?}: {stderr}");
        }
        assert!(output.stdout.is_empty(), "{args:?}: partial output");
    }
    // Pressure without temperature is a usage error: refraction needs both.
    let out = atmos()
        .args(&SPA_EXAMPLE[..11])
        .assert()
        .code(2)
        .get_output()
        .clone();
    assert!(String::from_utf8_lossy(&out.stderr).contains("--temperature-c"));
}

#[test]
fn a_sun_given_as_a_direction_is_echoed_with_its_scene_vector() {
    // 60 deg from the zenith in the east: (sin 60°, 0, cos 60°) in (x east, y north, z up).
    let out = atmos()
        .args([
            "sun",
            "--sun-zenith-deg",
            "60",
            "--sun-azimuth-deg",
            "90",
            "--format",
            "csv",
        ])
        .assert()
        .success();
    let text = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let row: Vec<f64> = text
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let want = [60.0, 90.0, 30.0, 3f64.sqrt() / 2.0, 0.0, 0.5];
    for (got, want) in row.iter().zip(want) {
        assert!((got - want).abs() < 1e-9, "{row:?}");
    }
    // No sun at all is bad usage.
    atmos().arg("sun").assert().code(2);
}
