//! End-to-end tests of the `irsig-atmos` calculators (radiance, temperature, rtt, bounces,
//! shape-factor): thesis table rows through the command line, CSV and RON that parse
//! back, the legacy `.rtt` against the shared reference, and bad values refused with exit 1
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
    let out = stdout_of(&["temperature", "--radiance", "54.9334613768"]);
    assert!(
        (last_number(out.lines().nth(1).unwrap()) - 300.0).abs() < 1e-4,
        "{out}"
    );
}

#[test]
fn legacy_rtt_matches_the_reference_file() {
    let reference = irsig_tests::repo_root()
        .ancestors()
        .map(|a| a.join("shared/reference/atmospheres/us-std-1976/us-std-1976.rtt"))
        .find(|p| p.is_file());
    let Some(reference) = reference else {
        eprintln!("shared reference not found; skipped");
        return;
    };
    let out = stdout_of(&[
        "rtt", "--from", "200", "--to", "350", "--step", "1", "--legacy",
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
        &["temperature", "--radiance", "-1"],
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

/// `(angle_deg, emissivity)` rows of a legacy `.ems` text.
fn ems_rows(text: &str) -> Vec<(f64, f64)> {
    irsig_formats::legacy::ems::parse("out.ems", text)
        .unwrap()
        .to_pairs()
}

#[test]
#[allow(clippy::float_cmp)] // the angles are small integers, printed and read exactly
fn fresnel_water_from_the_hale_querry_table_matches_the_reference_ems() {
    // formats/legacy/samples/water-hale-querry.ems is the shared reference (same sha256):
    // the same physics by a 0.0005 µm trapezoid rule, printed to 6 decimals.
    let out = stdout_of(&[
        "fresnel",
        "--nk-table",
        "formats/samples/water-hale-querry-nk.txt",
        "--band",
        "8-14",
        "--temperature",
        "300",
        "--angles",
        "0:90:5",
        "--legacy",
    ]);
    let reference = std::fs::read_to_string(
        irsig_tests::repo_root().join("formats/legacy/samples/water-hale-querry.ems"),
    )
    .unwrap();
    let (ours, theirs) = (ems_rows(&out), ems_rows(&reference));
    assert_eq!(ours.len(), theirs.len());
    for (a, b) in ours.iter().zip(&theirs) {
        assert_eq!(a.0, b.0);
        assert!((a.1 - b.1).abs() < 6e-7, "{a:?} vs {b:?}");
    }
}

#[test]
fn fresnel_constant_index_writes_a_material_library_entry() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("glassy.ron");
    bin("irsig-atmos")
        .args([
            "fresnel",
            "--n",
            "1.2",
            "--k",
            "0.05",
            "--angles",
            "0,30,60,90",
        ])
        .args([
            "--name",
            "glassy",
            "--id",
            "3",
            "-o",
            path.to_str().unwrap(),
        ])
        .assert()
        .success();
    let text = std::fs::read_to_string(&path).unwrap();
    let lib: irsig_model::MaterialLibrary =
        irsig_formats::canonical::from_ron("glassy.ron", &text).unwrap();
    let m = &lib.materials[0];
    assert_eq!(
        (m.id.0, m.name.as_str(), m.specular_fraction),
        (3, "glassy", 1.0)
    );
    assert!(m.source.contains("n = 1.2, k = 0.05"), "{}", m.source);
    // Normal incidence by hand: 1 − (0.2² + 0.05²)/(2.2² + 0.05²) = 0.991761...
    let normal = 1.0 - (0.04 + 0.0025) / (4.84 + 0.0025);
    assert_eq!(m.emissivity.len(), 4);
    assert!(
        (m.emissivity[0].1 - normal).abs() < 1e-12,
        "{:?}",
        m.emissivity
    );
    assert_eq!(m.emissivity[3], (90.0, 0.0));
    // Same on stdout with `-o -`, and a `.ems` name selects the legacy layout.
    let piped = stdout_of(&[
        "fresnel",
        "--n",
        "1.2",
        "--k",
        "0.05",
        "--angles",
        "0,30,60,90",
        "--name",
        "glassy",
        "--id",
        "3",
        "-o",
        "-",
    ]);
    assert_eq!(piped, text);
    let ems = dir.path().join("glassy.ems");
    bin("irsig-atmos")
        .args([
            "fresnel",
            "--n",
            "1.2",
            "--k",
            "0.05",
            "--angles",
            "0,30,60,90",
        ])
        .args(["-o", ems.to_str().unwrap()])
        .assert()
        .success();
    let rows = ems_rows(&std::fs::read_to_string(&ems).unwrap());
    assert_eq!(rows, m.emissivity);
}

#[test]
fn fresnel_bad_input_exits_1_or_2_with_a_message_and_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let bad_nk = dir.path().join("bad.nk");
    std::fs::write(&bad_nk, "8 1.2 0.1\n9 1.3 -0.2\n").unwrap();
    let bad_nk = bad_nk.to_str().unwrap();
    let water = "formats/samples/water-hale-querry-nk.txt";
    let cases: &[(&[&str], i32, &str)] = &[
        (&["--n", "0"], 1, "n must be finite and > 0, found 0"),
        (&["--n", "-1.5"], 1, "found -1.5"),
        (&["--n", "NaN"], 1, "found NaN"),
        (
            &["--n", "1.2", "--k", "-0.1"],
            1,
            "k must be finite and ≥ 0, found -0.1",
        ),
        (&["--n", "1.2", "--angles", "0:95:5"], 1, "0–90"),
        (&["--n", "1.2", "--angles", "30,10"], 1, "increase"),
        (&["--nk-table", bad_nk], 1, "bad.nk:2:7"),
        (&["--nk-table", "no-such-file.nk"], 1, "no-such-file.nk"),
        (
            &["--nk-table", water, "--band", "7-14"],
            1,
            "covers 8–14 µm",
        ),
        (
            &["--nk-table", water, "--temperature", "-5"],
            1,
            "temperature",
        ),
        (
            &["--n", "1.2", "--nk-table", water],
            2,
            "cannot be used with",
        ),
        (&["--k", "0.1"], 2, "required"),
        (&["--n", "1.2", "--temperature", "300"], 2, "--nk-table"),
    ];
    for (args, code, message) in cases {
        let out_file = dir.path().join("out.ron");
        let out = bin("irsig-atmos")
            .arg("fresnel")
            .args(*args)
            .args(["-o", out_file.to_str().unwrap()])
            .assert()
            .code(*code);
        // miette wraps long messages at 80 columns behind a `│` gutter: unwrap them.
        let stderr = String::from_utf8_lossy(&out.get_output().stderr)
            .split_whitespace()
            .filter(|w| *w != "│")
            .collect::<Vec<_>>()
            .join(" ");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!out_file.exists(), "{args:?}: output left behind");
    }
}
