//! `irsig-import` and `irsig-flatten` end to end: the samples through files and through a
//! Unix pipe (world coordinates checked against hand-computed vertices), the README's
//! import pipe run as written, the real GLBs, and
//! the malformed corpus in `tests/data/malformed/{mesh,scene}` (exit 1, a message naming
//! the file and line, no output file left behind).

use std::io::Write as _;
use std::path::Path;
use std::process::{Command, Stdio};

use irsig_model::RawScene;
use irsig_tests::{bin, bin_path, repo_root};
use predicates::prelude::*;

const SAMPLES: &str = "formats/canonical/samples";
const LIBRARY: &str = "formats/canonical/samples/materials.ron";

fn has_point(raw: &RawScene, object: u32, p: [f64; 3]) -> bool {
    raw.facets.iter().filter(|f| f.object == object).any(|f| {
        f.vertices.iter().any(|&v| {
            let q = raw.positions_m[v as usize];
            (0..3).all(|k| (q[k] - p[k]).abs() < 1e-12)
        })
    })
}

/// Six times the volume enclosed by one object's facets: positive when they face out.
fn volume(raw: &RawScene, object: u32) -> f64 {
    raw.facets
        .iter()
        .filter(|f| f.object == object)
        .map(|f| {
            let [a, b, c] = f.vertices.map(|v| raw.positions_m[v as usize]);
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum()
}

/// The sample scene: box.obj (2 m × 1 m × 1 m, a corner at the origin) placed twice.
fn check_sample_scene(raw: &RawScene) {
    assert_eq!(raw.objects, ["box", "box"]);
    assert_eq!(raw.facets.len(), 24);
    // Object 0: Rz(90°) then +(10, 0, 0). By hand, (x, y, z) -> (10 − y, x, z):
    // (2, 1, 1) -> (9, 2, 1); (2, 0, 0) -> (10, 2, 0).
    assert!(has_point(raw, 0, [9.0, 2.0, 1.0]));
    assert!(has_point(raw, 0, [10.0, 2.0, 0.0]));
    // Object 1: scale (−1, 1, 1) then +(−5, 0, 0): (2, 1, 1) -> (−7, 1, 1).
    assert!(has_point(raw, 1, [-7.0, 1.0, 1.0]));
    // Both enclose 2 m³ with outward faces: the mirror's winding was reversed.
    assert!((volume(raw, 0) - 12.0).abs() < 1e-9, "{}", volume(raw, 0));
    assert!((volume(raw, 1) - 12.0).abs() < 1e-9, "{}", volume(raw, 1));
    // Temperatures: the lid (facets 2, 3) overridden to 320 K, the rest 300 K; the mirror
    // 290 K. Materials: object 0's steel (2) overridden to concrete (1).
    let t: Vec<f64> = raw.facets.iter().map(|f| f.temperature_k).collect();
    assert_eq!(
        t[..12],
        [
            300.0, 300.0, 320.0, 320.0, 300.0, 300.0, 300.0, 300.0, 300.0, 300.0, 300.0, 300.0
        ]
    );
    assert!(t[12..].iter().all(|&x| (x - 290.0).abs() < 1e-12));
    assert!(raw.facets[..12].iter().all(|f| f.material.0 == 1));
    assert_eq!(
        raw.facets[12..]
            .iter()
            .filter(|f| f.material.0 == 2)
            .count(),
        8
    );
}

#[test]
fn import_then_flatten_through_files() {
    let dir = tempfile::tempdir().unwrap();
    let object = dir.path().join("box.ron");
    bin("irsig-import")
        .args([&format!("{SAMPLES}/box.obj"), "--materials", LIBRARY, "-o"])
        .arg(&object)
        .assert()
        .success();
    // The committed sample object is what the importer makes of box.obj.
    let made = std::fs::read_to_string(&object).unwrap();
    let sample = std::fs::read_to_string(repo_root().join(SAMPLES).join("box.ron")).unwrap();
    assert_eq!(
        made.replace(&format!("{SAMPLES}/"), ""),
        sample.replace(&format!("{SAMPLES}/"), "")
    );
    let out = dir.path().join("scene.raw");
    bin("irsig-flatten")
        .args([
            &format!("{SAMPLES}/scene.ron"),
            "--materials",
            LIBRARY,
            "-o",
        ])
        .arg(&out)
        .assert()
        .success();
    let bytes = std::fs::read(&out).unwrap();
    assert!(bytes.starts_with(b"IRSIGRAW"));
    let raw = irsig_formats::canonical::read_raw_scene("scene.raw", &bytes).unwrap();
    check_sample_scene(&raw);
    // The RON form holds the same scene.
    let ron = bin("irsig-flatten")
        .args([&format!("{SAMPLES}/scene.ron"), "--ron"])
        .output()
        .unwrap();
    assert!(ron.status.success());
    let raw_ron = irsig_formats::canonical::read_raw_scene("scene.raw.ron", &ron.stdout).unwrap();
    assert_eq!(raw_ron, raw);
}

/// The first `sh` block after `marker` in the README.
fn readme_block(marker: &str) -> String {
    let readme = std::fs::read_to_string(repo_root().join("README.md")).unwrap();
    let after = &readme[readme.find(marker).expect("the marker is in the README")..];
    let start = after.find("```sh\n").expect("a sh block follows") + "```sh\n".len();
    let len = after[start..].find("```").expect("the block ends");
    after[start..start + len].to_owned()
}

#[test]
fn the_readme_import_pipe_runs_as_written() {
    // As the README says: from pipelines/, the tools on PATH. The repository's layout is
    // rebuilt in a scratch directory, so the run writes nothing into the repository.
    let block = readme_block("Importing a mesh pipes the same way");
    assert!(
        block.contains("irsig-import") && block.contains("| irsig-flatten"),
        "{block}"
    );
    let dir = tempfile::tempdir().unwrap();
    let samples = dir.path().join(SAMPLES);
    std::fs::create_dir_all(&samples).unwrap();
    for file in ["box.obj", "box.mtl", "materials.ron", "scene.ron"] {
        std::fs::copy(repo_root().join(SAMPLES).join(file), samples.join(file)).unwrap();
    }
    std::fs::create_dir(dir.path().join("pipelines")).unwrap();
    let tools = bin_path("irsig-import").parent().unwrap().to_path_buf();
    let path = std::env::join_paths(std::iter::once(tools).chain(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    )))
    .unwrap();
    let out = Command::new("sh")
        .args(["-e", "-c", &block])
        .current_dir(dir.path().join("pipelines"))
        .env("PATH", path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{block}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let written = std::fs::read(dir.path().join("out/box-scene.raw")).unwrap();
    let raw = irsig_formats::canonical::read_raw_scene("box-scene.raw", &written).unwrap();
    check_sample_scene(&raw);
    // The same bytes as flattening the committed sample object from its file.
    let direct = bin("irsig-flatten")
        .args([&format!("{SAMPLES}/scene.ron")])
        .output()
        .unwrap();
    assert!(direct.status.success());
    assert_eq!(written, direct.stdout);
}

#[test]
fn import_then_flatten_through_a_pipe() {
    let root = repo_root();
    let mut import = Command::new(bin_path("irsig-import"))
        .current_dir(&root)
        .args([&format!("{SAMPLES}/box.obj"), "--materials", LIBRARY])
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let flatten = Command::new(bin_path("irsig-flatten"))
        .current_dir(&root)
        .args([&format!("{SAMPLES}/scene.ron"), "--object", "box.ron=-"])
        .stdin(import.stdout.take().unwrap())
        .stdout(Stdio::piped())
        .output()
        .unwrap();
    assert!(import.wait().unwrap().success());
    assert!(
        flatten.status.success(),
        "{}",
        String::from_utf8_lossy(&flatten.stderr)
    );
    let raw = irsig_formats::canonical::read_raw_scene("<pipe>", &flatten.stdout).unwrap();
    check_sample_scene(&raw);
}

#[test]
fn real_glbs_import_with_their_triangle_counts() {
    for (file, triangles) in [
        (
            "tests/data/third-party/webxr-input-profiles/generic-fixed-hand/left.glb",
            2314,
        ),
        (
            "tests/data/third-party/webxr-input-profiles/generic-trigger/none.glb",
            3598,
        ),
    ] {
        let out = bin("irsig-import")
            .args([
                file,
                "--materials",
                LIBRARY,
                "--default-material",
                "skin",
                "--legacy-unit",
                "cm",
            ])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        // Standard output is a pipe here, so the importer writes the binary object.
        assert!(out.stdout.starts_with(b"IRSIGOBJ"));
        let object = irsig_formats::canonical::read_object(file, &out.stdout).unwrap();
        assert_eq!(object.facets.len(), triangles);
        // --legacy-unit cm: the 0.2 m-sized models become 2 mm-sized.
        let extent = object
            .positions_m
            .iter()
            .map(|p| p[1].abs())
            .fold(0.0, f64::max);
        assert!(extent < 0.002 && extent > 0.0002, "{extent}");
    }
}

#[test]
fn unknown_material_without_a_default_is_an_error_naming_it_and_its_line() {
    let file = "tests/data/malformed/mesh/unknown-material.obj";
    bin("irsig-import")
        .args([file, "--materials", LIBRARY])
        .assert()
        .code(1)
        .stderr(
            predicate::str::contains(format!("{file}:7"))
                .and(predicate::str::contains("`unobtainium`")),
        );
    // With a default named explicitly it imports.
    bin("irsig-import")
        .args([
            file,
            "--materials",
            LIBRARY,
            "--default-material",
            "concrete",
        ])
        .assert()
        .success();
    // A default the library does not have is a usage error.
    bin("irsig-import")
        .args([file, "--materials", LIBRARY, "--default-material", "nope"])
        .assert()
        .code(2);
}

/// miette wraps long messages at 80 columns behind `│`: join the lines back into one.
fn unwrap_report(stderr: &str) -> String {
    stderr
        .lines()
        .map(|l| l.trim_start().trim_start_matches(['│', '×']).trim())
        .collect::<Vec<_>>()
        .join(" ")
}

fn assert_fails_cleanly(tool: &str, args: &[&str], expect: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let output = bin(tool).args(args).arg("-o").arg(&out).output().unwrap();
    let stderr = unwrap_report(&String::from_utf8_lossy(&output.stderr));
    assert_eq!(output.status.code(), Some(1), "{tool} {args:?}: {stderr}");
    for e in expect {
        assert!(
            stderr.contains(e),
            "{tool} {args:?}: expected `{e}` in\n{stderr}"
        );
    }
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "{tool} {args:?} left {left:?}");
}

#[test]
fn zero_area_triangles_are_dropped_with_a_warning_or_refused_with_strict() {
    // Real meshes (pybullet_data's) hold a few exactly degenerate triangles among
    // thousands; no ray can hit them. They are dropped by default, and --strict refuses them.
    let obj = "tests/data/malformed/mesh/degenerate.obj";
    let out = bin("irsig-import")
        .args([obj, "--materials", LIBRARY, "--ron"])
        .output()
        .unwrap();
    let stderr = unwrap_report(&String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("dropped 1 zero-area triangle of 2")
            && stderr.contains("degenerate.obj:7:1")
            && stderr.contains("--strict"),
        "{stderr}"
    );
    let object: irsig_model::Object = ron::from_str(&String::from_utf8_lossy(&out.stdout)).unwrap();
    assert_eq!(object.facets.len(), 1);
    assert_fails_cleanly(
        "irsig-import",
        &[obj, "--materials", LIBRARY, "--strict"],
        // Line 7's face, whose `f` is its first character.
        &["degenerate.obj:7:1", "degenerate"],
    );
}

#[test]
fn malformed_meshes_fail_with_file_line_and_column_and_no_output() {
    let m = "tests/data/malformed/mesh";
    let cases: &[(&str, &[&str])] = &[
        ("truncated.obj", &["truncated.obj:6:6", "z coordinate"]),
        ("number-garbled.obj", &["number-garbled.obj:2:5", "`O`"]),
        ("nan.obj", &["nan.obj:3:5", "finite"]),
        ("inf.obj", &["inf.obj:3:5", "finite"]),
        ("non-utf8.obj", &["non-utf8.obj:4:9", "UTF-8"]),
        ("empty.obj", &["empty.obj:", "empty mesh"]),
        (
            "face-out-of-range.obj",
            &["face-out-of-range.obj:5:7", "index 7"],
        ),
        (
            "texcoord-before-first.obj",
            &[
                "texcoord-before-first.obj:7:7",
                "texture coordinate index -5",
            ],
        ),
        (
            "short-normal.obj",
            &["short-normal.obj:5:7", "3 numbers after `vn`"],
        ),
        ("truncated.glb", &["truncated.glb", "GLB"]),
        ("short-header.glb", &["short-header.glb", "12-byte header"]),
        (
            "short-colour.obj",
            &["short-colour.mtl:3:1", "three numbers"],
        ),
        ("garbled.glb", &["garbled.glb"]),
        (
            "position-out-of-range.gltf",
            &[
                "position-out-of-range.gltf",
                "meshes[0].primitives[0].attributes[\"POSITION\"]",
                "Index out of bounds",
            ],
        ),
        (
            "http-uri.glb",
            &["http-uri.glb", "example.invalid/tri.bin", "never fetches"],
        ),
    ];
    for (file, expect) in cases {
        let path = format!("{m}/{file}");
        assert_fails_cleanly("irsig-import", &[&path, "--materials", LIBRARY], expect);
    }
}

#[test]
fn malformed_scenes_fail_naming_the_file_and_no_output() {
    let s = "tests/data/malformed/scene";
    assert_fails_cleanly(
        "irsig-flatten",
        &[&format!("{s}/missing-object.ron")],
        &["missing-object.ron", "no-such-object.ron"],
    );
    assert_fails_cleanly(
        "irsig-flatten",
        &[&format!("{s}/bad-syntax.ron")],
        &["bad-syntax.ron:3:"],
    );
    assert_fails_cleanly(
        "irsig-flatten",
        &[&format!("{s}/no-temperature.ron")],
        &["no-temperature.ron", "`box`", "facet 0 has no temperature"],
    );
    assert_fails_cleanly(
        "irsig-flatten",
        &[&format!("{s}/negative-temperature.ron")],
        &["negative-temperature.ron:5:", "objects[0].temperature_k"],
    );
}

#[test]
fn stdin_without_a_format_and_two_stdin_uses_are_usage_errors() {
    bin("irsig-import")
        .args(["-", "--materials", LIBRARY])
        .assert()
        .code(2);
    bin("irsig-flatten")
        .args(["-", "--object", "box.ron=-"])
        .assert()
        .code(2);
    bin("irsig-flatten")
        .args([
            &format!("{SAMPLES}/scene.ron"),
            "--object",
            "nothing.ron=x.ron",
            "--ron",
        ])
        .assert()
        .code(2);
}

#[test]
fn obj_from_stdin_with_format() {
    let mut child = Command::new(bin_path("irsig-import"))
        .current_dir(repo_root())
        .args([
            "-",
            "--mesh-format",
            "obj",
            "--materials",
            LIBRARY,
            "--legacy-unit",
            "km",
        ])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let obj = std::fs::read(Path::new(&repo_root()).join(SAMPLES).join("box.obj")).unwrap();
    child.stdin.take().unwrap().write_all(&obj).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let object: irsig_model::Object =
        irsig_formats::canonical::read_object("<stdin>", &out.stdout).unwrap();
    // --legacy-unit km: the 2-unit edge is 2000 m.
    let max_x = object.positions_m.iter().map(|p| p[0]).fold(0.0, f64::max);
    assert!((max_x - 2000.0).abs() < 1e-9);
    // The MTL is not looked for when the OBJ comes from stdin: a warning says so.
    assert!(String::from_utf8_lossy(&out.stderr).contains("standard input"));
}

/// A library with the material index the thesis's sample facet file uses (6).
const LIBRARY_6: &str = "(materials: [(id: 6, name: \"six\", emissivity: [(0.0, 0.9)], specular_fraction: 0.0, source: \"test\")])";

#[test]
fn legacy_facet_file_and_legacy_scene_in_km() {
    let dir = tempfile::tempdir().unwrap();
    let fac = repo_root().join("formats/legacy/samples/thesis-4facets.fac");
    std::fs::copy(&fac, dir.path().join("thesis-4facets.fac")).unwrap();
    std::fs::write(dir.path().join("lib.ron"), LIBRARY_6).unwrap();
    // Import: 4 facets, km to m, material index 6 is id 6.
    let out = bin("irsig-import")
        .arg(&fac)
        .args(["--legacy-unit", "km", "--materials"])
        .arg(dir.path().join("lib.ron"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let object: irsig_model::Object =
        irsig_formats::canonical::read_object("fac", &out.stdout).unwrap();
    assert_eq!(object.facets.len(), 4);
    assert!(object.facets.iter().all(|f| f.material.0 == 6));
    assert!(
        object
            .positions_m
            .iter()
            .any(|p| (p[0] + 4096.91).abs() < 1e-9 && (p[1] + 3133.2).abs() < 1e-9)
    );
    // Flatten a legacy scene: rotate 90° about z, translate (10, −3, 0.5) km, scale
    // (0.5, 0.5, 1), 300 K. By hand, the vertex (−4.09691, −3.1332, 0) km scales to
    // (−2.048455, −1.5666, 0), turns to (1.5666, −2.048455, 0) and moves to
    // (11.5666, −5.048455, 0.5) km.
    std::fs::write(
        dir.path().join("scene.scn"),
        "thesis-4facets.fac\n0 0 90\n10 -3 0.5\n0.5 0.5 1\n300\n",
    )
    .unwrap();
    let out = bin("irsig-flatten")
        .arg(dir.path().join("scene.scn"))
        .args(["--legacy-unit", "km", "--ron", "--materials"])
        .arg(dir.path().join("lib.ron"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let raw = irsig_formats::canonical::read_raw_scene("raw", &out.stdout).unwrap();
    let want = [11_566.6, -5_048.455, 500.0];
    assert!(
        raw.positions_m
            .iter()
            .any(|q| (0..3).all(|k| (q[k] - want[k]).abs() < 1e-9)),
        "{:?}",
        &raw.positions_m[..3]
    );
    assert!(
        raw.facets
            .iter()
            .all(|f| (f.temperature_k - 300.0).abs() < 1e-12)
    );
    // Without a temperature the same scene is an error pointing at the entry's line.
    std::fs::write(
        dir.path().join("cold.scn"),
        "thesis-4facets.fac\n0 0 90\n10 -3 0.5\n0.5 0.5 1\n",
    )
    .unwrap();
    let out = bin("irsig-flatten")
        .arg(dir.path().join("cold.scn"))
        .args(["--legacy-unit", "km", "--ron"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cold.scn:1:1"));
}

#[test]
fn legacy_facet_file_with_4_vertex_facets_imports_as_triangles() {
    // formats/legacy/samples/quads.fac, in km: a unit square, a trapezoid at 300.5 K,
    // a tilted 10 m square and a triangle; the three 4-vertex facets become two
    // triangles each, 7 in all, each half with its facet's material and temperature.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("lib.ron"), LIBRARY_6).unwrap();
    let out = bin("irsig-import")
        .args([
            "formats/legacy/samples/quads.fac",
            "--legacy-unit",
            "km",
            "--ron",
            "--materials",
        ])
        .arg(dir.path().join("lib.ron"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let object: irsig_model::Object =
        irsig_formats::canonical::read_object("quads", &out.stdout).unwrap();
    assert_eq!(object.facets.len(), 7);
    assert_eq!(object.positions_m.len(), 4 + 4 + 4 + 3);
    assert!(object.facets.iter().all(|f| f.material.0 == 6));
    let temperatures: Vec<Option<f64>> = object.facets.iter().map(|f| f.temperature_k).collect();
    assert_eq!(
        temperatures,
        [None, None, Some(300.5), Some(300.5), None, None, None]
    );
    // The trapezoid (6,0) (4,1) (2,1) (2,0) km, vertices 4 to 7: cut along its shorter
    // diagonal v2–v4 into (v1 v2 v4) and (v2 v3 v4).
    assert_eq!(object.facets[2].vertices, [4, 5, 7]);
    assert_eq!(object.facets[3].vertices, [5, 6, 7]);
    // Twice the area, along the normal, of each triangle, in km².
    let doubled = |i: usize| {
        let [a, b, c] = object.facets[i]
            .vertices
            .map(|v| object.positions_m[v as usize]);
        let (u, w) = (
            [0, 1, 2].map(|k| b[k] - a[k]),
            [0, 1, 2].map(|k| c[k] - a[k]),
        );
        [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ]
        .map(|x| x / 1e6)
    };
    // The square's halves 1/2 + 1/2 km², the trapezoid's 2 + 1 (its area (4 + 2) / 2 ×
    // 1), all facing +z as the facets do.
    let halves: Vec<[f64; 3]> = (0..4).map(doubled).collect();
    let want = [
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 4.0],
        [0.0, 0.0, 2.0],
    ];
    for (h, w) in halves.iter().zip(want) {
        assert!((0..3).all(|k| (h[k] - w[k]).abs() < 1e-9), "{halves:?}");
    }
    // The triangle (0,0,0) (0,0,1) (1,0,0) faces +y, 1/2 km².
    let t = doubled(6);
    assert!(
        (t[1] - 1.0).abs() < 1e-9 && t[0].abs() < 1e-12 && t[2].abs() < 1e-12,
        "{t:?}"
    );
}

#[test]
fn import_writes_binary_into_pipes_and_bin_files_and_ron_to_redirections() {
    let dir = tempfile::tempdir().unwrap();
    let root = repo_root();
    let sample: irsig_model::Object = irsig_formats::canonical::from_ron(
        "box.ron",
        &std::fs::read_to_string(root.join(SAMPLES).join("box.ron")).unwrap(),
    )
    .unwrap();
    // A `.bin` output file: binary, and the same geometry as the RON sample.
    let bin_file = dir.path().join("box.bin");
    bin("irsig-import")
        .args([&format!("{SAMPLES}/box.obj"), "--materials", LIBRARY, "-o"])
        .arg(&bin_file)
        .assert()
        .success();
    let bytes = std::fs::read(&bin_file).unwrap();
    assert!(bytes.starts_with(b"IRSIGOBJ"));
    let object = irsig_formats::canonical::read_object("box.bin", &bytes).unwrap();
    assert_eq!(object.positions_m, sample.positions_m);
    assert_eq!(object.facets, sample.facets);
    // Standard output redirected to a file (`> box.ron`): RON, as a person would open it.
    let redirected = dir.path().join("redirected.ron");
    let status = Command::new(bin_path("irsig-import"))
        .current_dir(&root)
        .args([&format!("{SAMPLES}/box.obj"), "--materials", LIBRARY])
        .stdout(std::fs::File::create(&redirected).unwrap())
        .status()
        .unwrap();
    assert!(status.success());
    let text = std::fs::read_to_string(&redirected).unwrap();
    assert!(text.starts_with("(\n  name: \"box\""), "{text}");
    // --ron into a pipe overrides the pipe's default.
    let out = bin("irsig-import")
        .args([
            &format!("{SAMPLES}/box.obj"),
            "--materials",
            LIBRARY,
            "--ron",
        ])
        .output()
        .unwrap();
    assert!(out.stdout.starts_with(b"(\n"));
    // flatten reads the binary object where the scene names box.ron, with the same result
    // as from the RON sample.
    let from_ron = bin("irsig-flatten")
        .args([&format!("{SAMPLES}/scene.ron"), "--ron"])
        .output()
        .unwrap();
    let from_bin = bin("irsig-flatten")
        .args([&format!("{SAMPLES}/scene.ron"), "--ron", "--object"])
        .arg(format!("box.ron={}", bin_file.display()))
        .output()
        .unwrap();
    assert!(
        from_bin.status.success(),
        "{}",
        String::from_utf8_lossy(&from_bin.stderr)
    );
    assert_eq!(from_bin.stdout, from_ron.stdout);
}

#[test]
fn malformed_binary_objects_fail_in_flatten_with_offset_and_no_output() {
    let o = "tests/data/malformed/object";
    let cases: &[(&str, &[&str])] = &[
        ("truncated.bin", &["truncated.bin:1:", "the file has 197"]),
        ("wrong-magic.bin", &["wrong-magic.bin:1:1:", "`IRSIGOBJ`"]),
        (
            "count-lies.bin",
            &["count-lies.bin:1:", "1000000000 facets"],
        ),
        ("nan.bin", &["nan.bin:1:83:", "positions_m[1]"]),
        (
            "index-out-of-range.bin",
            &["index-out-of-range.bin:1:179:", "facets[1].vertices[2]"],
        ),
    ];
    for (file, expect) in cases {
        let object = format!("box.ron={o}/{file}");
        assert_fails_cleanly(
            "irsig-flatten",
            &[&format!("{SAMPLES}/scene.ron"), "--object", &object],
            expect,
        );
    }
}

/// A square pyramid standing on the ground in glTF's axes (+Y up): base corners
/// (±1, 0, ±1), apex (0, 2, 0), every face wound counter-clockwise seen from outside. Its
/// volume is base × height / 3 = 4 × 2 / 3. The glTF text and its buffer (`pyramid.bin`).
fn pyramid_gltf() -> (String, Vec<u8>) {
    let positions: [[f32; 3]; 5] = [
        [-1.0, 0.0, -1.0],
        [1.0, 0.0, -1.0],
        [1.0, 0.0, 1.0],
        [-1.0, 0.0, 1.0],
        [0.0, 2.0, 0.0],
    ];
    // Base (normal -y), then the sides facing -z, +x, +z and -x.
    let indices: [u8; 18] = [0, 1, 2, 0, 2, 3, 0, 4, 1, 1, 4, 2, 2, 4, 3, 3, 4, 0];
    let mut buf: Vec<u8> = positions
        .iter()
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    buf.extend(indices);
    let text = format!(
        r#"{{"asset":{{"version":"2.0"}},
"buffers":[{{"byteLength":{},"uri":"pyramid.bin"}}],
"bufferViews":[{{"buffer":0,"byteLength":60}},{{"buffer":0,"byteOffset":60,"byteLength":18}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":5,"type":"VEC3","min":[-1,0,-1],"max":[1,2,1]}},
  {{"bufferView":1,"componentType":5121,"count":18,"type":"SCALAR"}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}]}}"#,
        buf.len()
    );
    (text, buf)
}

/// The volume enclosed by an object's facets, positive when they face outward.
fn object_volume(o: &irsig_model::Object) -> f64 {
    o.facets
        .iter()
        .map(|f| {
            let [a, b, c] = f.vertices.map(|i| o.positions_m[i as usize]);
            (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]))
                / 6.0
        })
        .sum()
}

#[test]
#[allow(clippy::float_cmp)] // small integers and their negatives: exact in f32 and f64
fn gltf_is_turned_to_z_up_unless_its_axes_are_kept() {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("pyramid.gltf");
    let (text, buf) = pyramid_gltf();
    std::fs::write(&model, text).unwrap();
    std::fs::write(dir.path().join("pyramid.bin"), buf).unwrap();
    let import = |extra: &[&str]| {
        let out = dir.path().join("p.bin");
        bin("irsig-import")
            .arg(&model)
            .args(["--materials", LIBRARY, "--default-material", "skin", "-o"])
            .arg(&out)
            .args(extra)
            .assert()
            .success();
        irsig_formats::canonical::read_object("p.bin", &std::fs::read(&out).unwrap()).unwrap()
    };
    // (x, y, z) -> (x, -z, y): the apex (0, 2, 0) is on top at z = 2, the base corner
    // (1, 0, -1) lies on the ground at (1, 1, 0).
    let o = import(&[]);
    assert_eq!(o.positions_m[4], [0.0, 0.0, 2.0]);
    assert_eq!(o.positions_m[1], [1.0, 1.0, 0.0]);
    assert!(o.positions_m[..4].iter().all(|p| p[2] == 0.0));
    assert!(o.source.contains("+Y up turned to +Z up"), "{}", o.source);
    // A rotation: the faces still face outward and enclose the same volume.
    assert!((object_volume(&o) - 8.0 / 3.0).abs() < 1e-12);

    let kept = import(&["--keep-axes"]);
    assert_eq!(kept.positions_m[4], [0.0, 2.0, 0.0]);
    assert_eq!(kept.positions_m[1], [1.0, 0.0, -1.0]);
    assert!((object_volume(&kept) - 8.0 / 3.0).abs() < 1e-12);

    // The flag means nothing for a format with no stated up axis.
    bin("irsig-import")
        .args([
            "formats/canonical/samples/box.obj",
            "--materials",
            LIBRARY,
            "--keep-axes",
        ])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--keep-axes is for glTF"));
    // Nor --images for a format whose images are never inside it.
    bin("irsig-import")
        .args([
            "formats/canonical/samples/box.obj",
            "--materials",
            LIBRARY,
            "--images",
            "unused",
        ])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--images is for glTF"));
}

/// A terrain that names a material: flatten carries it into the binary raw scene, and
/// flatten and trace both refuse one the library lacks, flatten at the scene's
/// `terrain.material` and trace at the raw scene's bytes of it (the header flags' high half,
/// byte 14).
#[test]
fn a_terrain_material_goes_through_flatten_and_an_unknown_one_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        repo_root().join(SAMPLES).join("box.ron"),
        dir.path().join("box.ron"),
    )
    .unwrap();
    let sample = std::fs::read_to_string(repo_root().join(SAMPLES).join("scene.ron")).unwrap();
    let scene = |id: u16| {
        let text = sample.replace(
            "terrain: (temperature_k: 286.0, emissivity: 1.0),",
            &format!("terrain: (temperature_k: 286.0, material: Some({id})),"),
        );
        assert_ne!(text, sample);
        let path = dir.path().join(format!("scene-{id}.ron"));
        std::fs::write(&path, text).unwrap();
        path
    };
    let library = repo_root().join(LIBRARY);
    let raw = dir.path().join("one.raw");
    bin("irsig-flatten")
        .arg(scene(1))
        .arg("--materials")
        .arg(&library)
        .arg("-o")
        .arg(&raw)
        .assert()
        .success();
    let read =
        irsig_formats::canonical::read_raw_scene("one.raw", &std::fs::read(&raw).unwrap()).unwrap();
    assert_eq!(read.terrain.material, Some(irsig_model::MaterialId(1)));

    let unknown = scene(9);
    let out = bin("irsig-flatten")
        .arg(&unknown)
        .arg("--materials")
        .arg(&library)
        .arg("-o")
        .arg(dir.path().join("nine.raw"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("scene-9.ron:") && stderr.contains("the terrain's material is 9"),
        "{stderr}"
    );
    assert!(!dir.path().join("nine.raw").exists());
    // Without a library flatten cannot check it; trace can.
    let raw = dir.path().join("nine.raw");
    bin("irsig-flatten")
        .arg(&unknown)
        .arg("-o")
        .arg(&raw)
        .assert()
        .success();
    let view = dir.path().join("view.ron");
    std::fs::write(
        &view,
        "LookAt(position_m: (0.0, -14.0, 3.0), target_m: (0.0, 1.0, 0.5), pixels: (8, 6), \
         fov_deg: (64.0, 48.0))",
    )
    .unwrap();
    let out = bin("irsig-trace")
        .arg("--scene")
        .arg(&raw)
        .arg("--materials")
        .arg(&library)
        .arg("--view")
        .arg(&view)
        .arg("--radiance-exr")
        .arg(dir.path().join("r.exr"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("nine.raw:1:15") && stderr.contains("the terrain's material is 9"),
        "{stderr}"
    );
}

#[test]
fn a_glbs_embedded_base_colour_is_written_out_with_images_and_reported_without() {
    use sha2::{Digest, Sha256};
    let file = "tests/data/third-party/webxr-input-profiles/generic-trigger/none.glb";
    let dir = tempfile::tempdir().unwrap();
    let images = dir.path().join("images");
    let run = |with_images: bool| {
        let mut cmd = bin("irsig-import");
        cmd.args([file, "--materials", LIBRARY, "--default-material", "skin"]);
        if with_images {
            cmd.arg("--images").arg(&images);
        }
        cmd.output().unwrap()
    };
    // Without --images: the image is reported, and nothing is written.
    let out = run(false);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains(
            "carries its base colour image inside the file (images[2] \
             `xrstandard_nonhanded_mat_BaseColor.jpg`, image/jpeg, 157558 bytes)"
        ) && stderr.contains("--images DIR"),
        "{stderr}"
    );
    assert!(!images.exists());
    // With it, twice: the second run finds the same bytes there and leaves them.
    let written = images.join("image-2-xrstandard_nonhanded_mat_BaseColor.jpg");
    for _ in 0..2 {
        let out = run(true);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{stderr}");
        assert!(stderr.contains("names the image"), "{stderr}");
        assert!(out.stdout.starts_with(b"IRSIGOBJ"));
    }
    // Byte for byte the GLB's bufferViews[2] (images[2]'s view), as a separate reading of
    // the file (Python's `struct` on its JSON and BIN chunks) gives it: 157,558 bytes.
    let bytes = std::fs::read(&written).unwrap();
    let hash: String = Sha256::digest(&bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    assert_eq!(
        (bytes.len(), hash.as_str()),
        (
            157_558,
            "675671d20511dd82411cbdd81a42df8d9e8e71fb344e56dd0813dcf1a58d5c71"
        )
    );
    assert_eq!(std::fs::read_dir(&images).unwrap().count(), 1);
    // Another image under that name is never overwritten: refused, and no object written.
    std::fs::write(&written, b"another image").unwrap();
    let out = run(true);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("holds another image"), "{stderr}");
    assert!(out.stdout.is_empty());
    assert_eq!(std::fs::read(&written).unwrap(), b"another image");
}
