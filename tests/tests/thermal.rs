//! The thermal pipeline (`pipelines/thermal.ron`) end to end, with real LOWTRAN7 runs: the
//! quickstart scene's temperatures on a summer afternoon from `irsig-therm`, traced in both
//! bands.
//!
//! - Its ground is what its generator writes.
//! - The panel's and the car's thermal shadows lie where hand geometry puts the shadows of
//!   the last hour: the grass and the track they have covered since 13:00 are cooler than
//!   the open grass and track by several kelvin, the ground they never covered is not.
//! - The README's pictures (`docs/thermal-lwir.png`, `docs/thermal-mwir.png`) are what the
//!   pipeline makes now.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH: these tests fail when it is
//! missing, saying so; they never skip.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use irsig_atmosphere::sun::SunSpec;
use irsig_tests::{bin_path, lowtran, repo_root};

/// The site and the afternoon: Golden, Colorado; 7 August 2001 (the weather's year), in
/// UTC (MDT + 6 h).
const LATITUDE_DEG: f64 = 39.74;
const LONGITUDE_DEG: f64 = -105.18;
/// The panel's box (x, y, z ranges, m) and the car's: thermal/scene.ron.
const PANEL: [[f64; 2]; 3] = [[-3.0, 3.0], [0.0, 0.1], [0.0, 2.5]];
const CAR: [[f64; 2]; 3] = [[6.0, 8.0], [4.0, 8.5], [0.0, 1.4]];
/// The ids the ground uses (thermal/materials.ron).
const GRASS: u16 = 6;
const TRACK: u16 = 100;

/// The pipeline, copied with what it reads into a temporary directory and run once.
fn thermal() -> &'static tempfile::TempDir {
    static RUN: OnceLock<tempfile::TempDir> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let root = repo_root();
        let copy = |from: &Path, to: &Path| {
            std::fs::create_dir_all(to.parent().unwrap()).unwrap();
            std::fs::copy(from, to).unwrap();
        };
        for sub in ["thermal", "quickstart"] {
            for entry in std::fs::read_dir(root.join("pipelines").join(sub)).unwrap() {
                let path = entry.unwrap().path();
                copy(
                    &path,
                    &dir.path()
                        .join("pipelines")
                        .join(sub)
                        .join(path.file_name().unwrap()),
                );
            }
        }
        for file in [
            "pipelines/thermal.ron",
            "pipelines/materials/scene-library.ron",
            "formats/samples/golden-tmy3-aug.epw",
        ] {
            copy(&root.join(file), &dir.path().join(file));
        }
        let out = std::process::Command::new(bin_path("irsig-run"))
            .current_dir(dir.path())
            .env("IRSIG_LOWTRAN", lowtran())
            .arg("pipelines/thermal.ron")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "irsig-run pipelines/thermal.ron failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        dir
    })
}

fn out(name: &str) -> PathBuf {
    thermal().path().join("out/thermal").join(name)
}

/// The unit vector toward the sun at `hh:mm` MDT on the day.
fn to_sun(hour: u32, minute: u32) -> [f64; 3] {
    SunSpec::At {
        utc: format!("2001-08-07T{:02}:{minute:02}:00Z", hour + 6),
        latitude_deg: LATITUDE_DEG,
        longitude_deg: LONGITUDE_DEG,
        altitude_m: 0.0,
        refraction: None,
        delta_t_s: None,
        delta_ut1_s: None,
    }
    .position()
    .unwrap()
    .to_scene_direction()
}

/// Whether the ray from the ground point `(x, y, 0)` toward `s` passes through `b` (the
/// slab test, by hand).
fn shaded_by(x: f64, y: f64, s: [f64; 3], b: [[f64; 2]; 3]) -> bool {
    let p = [x, y, 0.0];
    let (mut t0, mut t1) = (0.0_f64, f64::INFINITY);
    for k in 0..3 {
        if s[k].abs() < 1e-12 {
            if p[k] < b[k][0] || p[k] > b[k][1] {
                return false;
            }
            continue;
        }
        let (a, c) = ((b[k][0] - p[k]) / s[k], (b[k][1] - p[k]) / s[k]);
        t0 = t0.max(a.min(c));
        t1 = t1.min(a.max(c));
    }
    t0 <= t1
}

/// Each fine ground cell's centre, material and mean facet temperature (two facets a cell).
fn cells() -> Vec<(f64, f64, u16, f64)> {
    let bytes = std::fs::read(out("scene.raw")).unwrap();
    let scene = irsig_formats::canonical::read_raw_scene("scene.raw", &bytes).unwrap();
    let mut by_cell: std::collections::BTreeMap<(i64, i64), (u16, f64, u32)> =
        std::collections::BTreeMap::new();
    for f in scene.facets.iter().filter(|f| f.object == 0) {
        let v = f.vertices.map(|i| scene.positions_m[i as usize]);
        let xs = v.map(|p| p[0]);
        let ys = v.map(|p| p[1]);
        let width =
            xs.iter().fold(f64::MIN, |a, &b| a.max(b)) - xs.iter().fold(f64::MAX, |a, &b| a.min(b));
        if width > 0.3 {
            continue; // a coarse rectangle
        }
        // The cell's lower-left corner, in quarter metres.
        let key = (
            (xs.iter().fold(f64::MAX, |a, &b| a.min(b)) * 4.0).round() as i64,
            (ys.iter().fold(f64::MAX, |a, &b| a.min(b)) * 4.0).round() as i64,
        );
        let e = by_cell.entry(key).or_insert((f.material.0, 0.0, 0));
        e.1 += f.temperature_k;
        e.2 += 1;
    }
    by_cell
        .into_iter()
        .map(|((i, j), (m, t, n))| {
            (
                f64::from(i as i32) / 4.0 + 0.125,
                f64::from(j as i32) / 4.0 + 0.125,
                m,
                t / f64::from(n),
            )
        })
        .collect()
}

#[test]
fn the_ground_is_what_its_generator_writes() {
    let out = std::process::Command::new("python3")
        .arg(repo_root().join("pipelines/thermal/generate.py"))
        .output()
        .expect("python3 runs pipelines/thermal/generate.py");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let committed = std::fs::read(repo_root().join("pipelines/thermal/ground.ron")).unwrap();
    assert!(
        out.stdout == committed,
        "pipelines/thermal/ground.ron is not what generate.py writes: run \
         `python3 pipelines/thermal/generate.py > pipelines/thermal/ground.ron`"
    );
}

#[test]
fn the_shadows_of_the_last_hour_are_cool_where_hand_geometry_puts_them() {
    // Covered since 13:00: shaded at 13:00, 13:20, 13:40 and 14:00. Open: shaded by
    // neither box at any quarter hour from 06:00 to 14:00, and 3 m clear of both boxes.
    let last_hour: Vec<[f64; 3]> = [(13, 0), (13, 20), (13, 40), (14, 0)]
        .map(|(h, m)| to_sun(h, m))
        .to_vec();
    let day: Vec<[f64; 3]> = (0..33)
        .map(|q| to_sun(6 + q / 4, 15 * (q % 4)))
        .filter(|s| s[2] > 0.0)
        .collect();
    let clear = |x: f64, y: f64, b: [[f64; 2]; 3]| {
        x < b[0][0] - 3.0 || x > b[0][1] + 3.0 || y < b[1][0] - 3.0 || y > b[1][1] + 3.0
    };
    let mut covered: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    let mut open: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    for (x, y, m, t) in cells() {
        let kind = match m {
            GRASS => 0,
            TRACK => 1,
            _ => continue,
        };
        let by = |s: [f64; 3]| shaded_by(x, y, s, PANEL) || shaded_by(x, y, s, CAR);
        let under = |b: [[f64; 2]; 3]| x >= b[0][0] && x <= b[0][1] && y >= b[1][0] && y <= b[1][1];
        if under(PANEL) || under(CAR) {
            continue;
        }
        if last_hour.iter().all(|&s| by(s)) {
            covered[kind].push(t);
        } else if day.iter().all(|&s| !by(s)) && clear(x, y, PANEL) && clear(x, y, CAR) {
            open[kind].push(t);
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    for (kind, name) in [(0, "grass"), (1, "track")] {
        assert!(
            covered[kind].len() >= 4 && open[kind].len() >= 20,
            "{name}: {} covered, {} open cells",
            covered[kind].len(),
            open[kind].len()
        );
        let (c, o) = (mean(&covered[kind]), mean(&open[kind]));
        let spread = open[kind]
            .iter()
            .fold(0.0_f64, |a, &t| a.max((t - o).abs()));
        eprintln!(
            "{name}: covered {c:.2} K ({} cells), open {o:.2} K ({} cells, within {spread:.2} K)",
            covered[kind].len(),
            open[kind].len()
        );
        // The open ground is one temperature; what the shadows covered is well below it.
        assert!(spread < 0.5, "{name}: the open cells spread {spread} K");
        assert!(o - c > 3.0, "{name}: covered {c} K, open {o} K");
        assert!(
            covered[kind].iter().all(|&t| t < o - 1.0),
            "{name}: a covered cell is within 1 K of the open ground"
        );
    }
}

#[test]
fn the_readme_pictures_are_what_the_pipeline_makes() {
    for band in ["lwir", "mwir"] {
        let made = std::fs::read(out(&format!("{band}.colour.png"))).unwrap();
        let committed =
            std::fs::read(repo_root().join(format!("docs/thermal-{band}.png"))).unwrap();
        assert!(
            made == committed,
            "docs/thermal-{band}.png is stale: run `sh scripts/docs/thermal-picture.sh` and \
             check the README's caption"
        );
    }
    let readme = std::fs::read_to_string(repo_root().join("README.md")).unwrap();
    for want in [
        "docs/thermal-lwir.png",
        "docs/thermal-mwir.png",
        "pipelines/thermal.ron",
    ] {
        assert!(readme.contains(want), "the README does not name {want}");
    }
}
