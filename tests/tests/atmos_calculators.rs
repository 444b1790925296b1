//! End-to-end tests of the `irsig-atmos` calculators (radiance, temperature, rtt, bounces,
//! shape-factor): thesis table rows through the command line, CSV and RON that parse
//! back, the legacy `.rtt` against the reference one, and bad values refused with exit 1
//! or 2 and a message.

use irsig_tests::bin;

fn stdout_of(args: &[&str]) -> String {
    let out = bin("irsig-atmos").args(args).assert().success();
    String::from_utf8(out.get_output().stdout.clone()).unwrap()
}

fn last_number(line: &str) -> f64 {
    line.split_whitespace().last().unwrap().parse().unwrap()
}

#[test]
fn radiance_at_300_k_is_the_last_number_on_its_line() {
    let out = stdout_of(&["radiance", "--temperature", "300"]);
    let l = last_number(out.lines().nth(1).unwrap());
    // .rtt reference: 5.49334613768e-03 W cm^-2 sr^-1.
    assert!((l - 54.933_461).abs() < 1e-6, "{out}");
}

#[test]
fn temperature_inverts_radiance() {
    let out = stdout_of(&["temperature", "--radiance-w-m2-sr", "54.9334613768"]);
    assert!(
        (last_number(out.lines().nth(1).unwrap()) - 300.0).abs() < 1e-4,
        "{out}"
    );
}

#[test]
fn legacy_rtt_matches_the_reference_file() {
    // The shared LOWTRAN7 reference set's `.rtt`, byte for byte, as the repository keeps it.
    let reference =
        irsig_tests::repo_root().join("crates/atmosphere/data/lowtran/us-std-1976/us-std-1976.rtt");
    let out = stdout_of(&[
        "rtt", "--from", "200", "--to", "350", "--step-k", "1", "--legacy",
    ]);
    let expected = std::fs::read_to_string(reference).unwrap();
    // Same layout; digits may differ only in the last place from rounding.
    let (ours, theirs): (Vec<_>, Vec<_>) = (out.lines().collect(), expected.lines().collect());
    assert_eq!(ours.len(), theirs.len());
    for (a, b) in ours.iter().zip(&theirs) {
        let (ta, la) = a.split_once(' ').unwrap();
        let (tb, lb) = b.split_once(' ').unwrap();
        assert_eq!(ta, tb);
        let (la, lb): (f64, f64) = (la.parse().unwrap(), lb.parse().unwrap());
        assert!((la / lb - 1.0).abs() < 1e-11, "{a} vs {b}");
    }
}

#[test]
fn bounces_reproduce_table_a1_rows() {
    let out = stdout_of(&[
        "bounces",
        "--target-emissivity",
        "0.98",
        "--target-temperature",
        "260,300",
        "--background-emissivity",
        "0.95",
        "--background-temperature",
        "300",
        "--max",
        "4",
    ]);
    let rows: Vec<Vec<f64>> = out
        .lines()
        .skip(1)
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    // Thesis Table A-1 (see crates/radiometry/tests/thesis_tables.rs for the residual).
    let thesis = [
        [258.9804, 260.9005, 260.9953, 261.0000, 261.0002],
        [298.6722, 299.9259, 299.9884, 299.9913, 299.9915],
    ];
    for (row, expected) in rows.iter().zip(thesis) {
        for (got, want) in row[4..].iter().zip(expected) {
            assert!((got - want).abs() < 0.01, "{row:?}");
        }
    }
}

#[test]
fn shape_factor_csv_and_ron_parse_back_and_match_table_b1() {
    let args = [
        "shape-factor",
        "--emissivity",
        "0.95",
        "--object-temperature",
        "240",
        "--background-temperature",
        "240,280,320,360",
        "--ld",
        "0.0014",
        "--ld-unit",
        "W/m2/sr",
        "--factors",
        "1,0.75,0.5,0.25,0",
    ];
    let csv = stdout_of(&[&args[..], &["--format", "csv"]].concat());
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 4);
    // Table B-1, ε = 0.95, T_obj = 240 K, T_b = 360 K.
    let thesis = [237.7909, 241.4325, 244.8838, 248.1689, 251.3073];
    for (got, want) in rows[3][3..].iter().zip(thesis) {
        assert!((got - want).abs() < 0.01, "{:?}", rows[3]);
    }
    let ron_text = stdout_of(&[&args[..], &["--format", "ron"]].concat());
    let ron_rows = ron_text.find("rows").unwrap();
    // Same numbers as the CSV, via a plain scan of the RON `rows` list.
    let numbers: Vec<f64> = ron_text[ron_rows..]
        .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-' || c == '+'))
        .filter(|s| !s.is_empty() && s.chars().any(|c| c.is_ascii_digit()))
        .map(|s| s.parse().unwrap())
        .collect();
    let flat: Vec<f64> = rows.concat();
    assert_eq!(numbers, flat);
    // The W/cm2/sr unit is 1e4 times larger: the same sky given in it changes the result.
    let cm = stdout_of(&[
        "shape-factor",
        "--emissivity",
        "0.95",
        "--object-temperature",
        "240",
        "--background-temperature",
        "240",
        "--ld",
        "0.0014",
        "--ld-unit",
        "W/cm2/sr",
        "--factors",
        "1",
        "--format",
        "csv",
    ]);
    let warmer: f64 = cm
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .next_back()
        .unwrap()
        .parse()
        .unwrap();
    assert!(warmer > 238.0, "{cm}");
}

#[test]
fn an_srf_file_is_used_and_a_bad_one_is_refused_with_its_position() {
    let flat = stdout_of(&["radiance", "--temperature", "300"]);
    let with = stdout_of(&[
        "radiance",
        "--temperature",
        "300",
        "--band",
        "formats/samples/srf-8-12um.txt",
    ]);
    let (a, b) = (
        last_number(flat.lines().nth(1).unwrap()),
        last_number(with.lines().nth(1).unwrap()),
    );
    assert!(b < a && b > 0.5 * a, "{a} {b}");
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.srf");
    std::fs::write(&bad, "8 0.5\n9 x\n").unwrap();
    bin("irsig-atmos")
        .args([
            "radiance",
            "--temperature",
            "300",
            "--band",
            bad.to_str().unwrap(),
        ])
        .assert()
        .code(1)
        .stderr(predicates::str::contains("bad.srf:2:3"));
}

#[test]
fn bad_values_exit_non_zero_with_a_message() {
    let cases: &[&[&str]] = &[
        &["radiance", "--temperature", "-5"],
        &["radiance", "--temperature", "NaN"],
        &["bounces", "--target-temperature", "1:2:0"],
        &[
            "bounces",
            "--target-temperature",
            "300",
            "--target-emissivity",
            "1.5",
        ],
        &[
            "shape-factor",
            "--emissivity",
            "1.5",
            "--object-temperature",
            "240",
            "--background-temperature",
            "240",
            "--ld",
            "0.0014",
            "--ld-unit",
            "W/m2/sr",
        ],
        &[
            "shape-factor",
            "--emissivity",
            "0.9",
            "--object-temperature",
            "240",
            "--background-temperature",
            "240",
            "--ld",
            "0.0014",
        ],
        &["temperature", "--radiance", "-1"], // the old spelling of --radiance-w-m2-sr
        &["radiance", "--temperature", "300", "--band", "14:8"],
    ];
    for args in cases {
        let out = bin("irsig-atmos").args(*args).assert().failure();
        let output = out.get_output();
        let code = output.status.code().unwrap();
        assert!(code == 1 || code == 2, "{args:?}: exit {code}");
        assert!(!output.stderr.is_empty(), "{args:?}: no message");
        assert!(output.stdout.is_empty(), "{args:?}: partial output");
    }
}
