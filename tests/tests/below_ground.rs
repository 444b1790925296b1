//! A camera below the ground (`z < 0`) is traced, with a warning naming the view and how
//! far below it is; the same camera 2 m above the ground is traced without one.

use std::path::Path;

use irsig_tests::bin;

/// `irsig-trace` of a grey plate at `z = -5 m` seen from a camera at height `z_m`, with a
/// built-in atmosphere: its stderr.
fn trace_from(dir: &Path, z_m: f64) -> String {
    std::fs::write(
        dir.join("pit.raw.ron"),
        "(objects: [\"floor\"], positions_m: [(-1e5, -1e5, -5.0), (1e5, -1e5, -5.0), \
         (1e5, 1e5, -5.0), (-1e5, 1e5, -5.0)], facets: [(vertices: (0, 1, 2), material: 1, \
         temperature_k: 300.0, object: 0), (vertices: (0, 2, 3), material: 1, \
         temperature_k: 300.0, object: 0)])",
    )
    .unwrap();
    std::fs::write(
        dir.join("grey.ron"),
        "(materials: [(id: 1, name: \"grey\", emissivity: [(0.0, 0.6), (90.0, 0.6)], \
         specular_fraction: 0.0, source: \"a test\")])",
    )
    .unwrap();
    let view = dir.join(format!("view{z_m}.ron"));
    std::fs::write(
        &view,
        format!(
            "LookAt(position_m: (0.0, 0.0, {z_m:?}), target_m: (0.0, 10.0, -5.0), \
             up: (0.0, 0.0, 1.0), pixels: (4, 4), fov_deg: (1.0, 1.0))"
        ),
    )
    .unwrap();
    let out = bin("irsig-trace")
        .arg("--scene")
        .arg(dir.join("pit.raw.ron"))
        .arg("--materials")
        .arg(dir.join("grey.ron"))
        .arg("--view")
        .arg(&view)
        .args(["--atmosphere", "us-std-1976", "--band", "8-14", "-o"])
        .arg(dir.join(format!("frame{z_m}")))
        .assert()
        .success();
    String::from_utf8_lossy(&out.get_output().stderr).into_owned()
}

#[test]
fn a_camera_below_the_ground_is_traced_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let below = trace_from(dir.path(), -2.0);
    assert_eq!(below.matches("below the ground").count(), 1, "{below}");
    assert!(
        below.contains("view 1 puts the camera 2.000 m below the ground"),
        "{below}"
    );
    assert!(dir.path().join("frame-2.radiance.exr").is_file());
    let above = trace_from(dir.path(), 2.0);
    assert!(!above.contains("below the ground"), "{above}");
}
