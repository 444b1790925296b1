//! The `--tolerance` verification of docs/accuracy.md: for the quickstart, three fly-by
//! frames (near, far, oblique) and the thesis experiment, at tolerances of 1, 0.3, 0.1 and
//! 0.03 K, the configuration the pilot chose, its measured error against a reference
//! rendering (99th percentile and worst |ΔT| of the apparent temperature), the pilot's
//! cost, and the whole run's time against the reference and the cheapest rendering.
//!
//! ```text
//! cargo build --release --bins
//! cargo run --release -p irsig-tests --example tolerance_rows [BIN_DIR] > rows.md
//! ```
//!
//! The reference rendering: table atmosphere (where the atmosphere has slant tables),
//! 4 bounces, 64 sky-view rays, 4 × 4 rays per pixel, exact path terms and the
//! atmosphere's full spectral grid: the most accurate setting of every model the pilot
//! compares against. The cheapest: the thesis model (or layered), no bounce, F = 1, one
//! ray per pixel, tabulated path terms, the band model.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use irsig_model::decision::Decision;
use irsig_radiometry::{Band, InverseTable};

struct Case {
    name: &'static str,
    scene: &'static str,
    materials: &'static str,
    view: &'static str,
    extra: &'static [&'static str],
}

const CASES: [Case; 5] = [
    Case {
        name: "quickstart",
        scene: "pipelines/quickstart/scene.ron",
        materials: "pipelines/quickstart/materials.ron",
        view: "pipelines/quickstart/view.ron",
        extra: &["--atmosphere", "us-std-1976"],
    },
    Case {
        name: "fly-by frame 14 (near: 700 m overhead)",
        scene: "pipelines/thesis-flyby/scene.ron",
        materials: "pipelines/thesis-flyby/materials.ron",
        view: "pipelines/thesis-flyby/views/frame-14.view",
        extra: &["--atmosphere", "us-std-1976", "--view-unit", "km"],
    },
    Case {
        name: "fly-by frame 9 (far: 12 km)",
        scene: "pipelines/thesis-flyby/scene.ron",
        materials: "pipelines/thesis-flyby/materials.ron",
        view: "pipelines/thesis-flyby/views/frame-09.view",
        extra: &["--atmosphere", "us-std-1976", "--view-unit", "km"],
    },
    Case {
        name: "fly-by frame 8 (oblique: 81° from nadir)",
        scene: "pipelines/thesis-flyby/scene.ron",
        materials: "pipelines/thesis-flyby/materials.ron",
        view: "pipelines/thesis-flyby/views/frame-08.view",
        extra: &["--atmosphere", "us-std-1976", "--view-unit", "km"],
    },
    Case {
        name: "thesis experiment",
        scene: "pipelines/thesis-experiment/scene.ron",
        materials: "pipelines/thesis-experiment/materials.ron",
        view: "pipelines/thesis-experiment/view.ron",
        extra: &["--atmosphere", "midlat-winter"],
    },
];

const TOLERANCES: [f64; 4] = [1.0, 0.3, 0.1, 0.03];

fn run(bin: &Path, tool: &str, args: &[&str]) -> (f64, String) {
    let started = Instant::now();
    let out = Command::new(bin.join(tool))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("{tool}: {e}"));
    let seconds = started.elapsed().as_secs_f64();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{tool} {args:?}:\n{stderr}");
    (seconds, stderr)
}

fn args(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

fn temperatures(path: &Path) -> Vec<f64> {
    let raster = irsig_raster::read_exr(&std::fs::read(path).unwrap()).unwrap();
    let radiance: Vec<f64> = raster
        .layer("radiance")
        .unwrap()
        .data
        .iter()
        .map(|&l| f64::from(l))
        .collect();
    let band = Band::default();
    let table = InverseTable::new(&band, &radiance);
    radiance.iter().map(|&l| table.temperature(l)).collect()
}

/// 99th percentile (nearest rank) and worst |a − b|.
fn errors(a: &[f64], b: &[f64]) -> (f64, f64) {
    let mut d: Vec<f64> = a.iter().zip(b).map(|(x, y)| (x - y).abs()).collect();
    d.sort_by(f64::total_cmp);
    let rank = (0.99 * d.len() as f64).ceil() as usize;
    (d[rank.clamp(1, d.len()) - 1], d[d.len() - 1])
}

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    std::env::set_current_dir(&root).unwrap();
    let bin = std::env::args()
        .nth(1)
        .map_or_else(|| root.join("target/release"), PathBuf::from);
    let tmp = tempfile::tempdir().unwrap();
    let path = |name: &str| tmp.path().join(name).to_string_lossy().into_owned();
    println!(
        "| case | tolerance (K) | chosen: atmosphere, bounces, sky-view, supersampling, path terms, sub-bands | \
         p99 / worst |ΔT| (K) | pilot (s) | run (s) | reference (s) | cheapest (s) |"
    );
    println!("| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: |");
    for case in &CASES {
        let raw = path("scene.raw");
        run(
            &bin,
            "irsig-flatten",
            &[case.scene, "--materials", case.materials, "-o", &raw],
        );
        let base = |out: &str| -> Vec<String> {
            let mut v: Vec<String> = [
                "--scene",
                raw.as_str(),
                "--materials",
                case.materials,
                "--view",
                case.view,
                "--radiance-exr",
                out,
            ]
            .iter()
            .map(|s| (*s).to_owned())
            .collect();
            v.extend(case.extra.iter().map(|s| (*s).to_owned()));
            v
        };
        let reference = path("reference.exr");
        let mut r = base(&reference);
        r.extend(
            [
                "--bounces",
                "4",
                "--sky-view-rays",
                "64",
                "--supersample",
                "4",
                "--path-terms",
                "exact",
                "--atmosphere-model",
                "table",
                "--sub-bands",
                "full",
            ]
            .map(str::to_owned),
        );
        let (reference_s, _) = run(&bin, "irsig-trace", &args(&r));
        let reference_t = temperatures(Path::new(&reference));
        let cheapest = path("cheapest.exr");
        let mut c = base(&cheapest);
        c.extend(
            [
                "--bounces",
                "0",
                "--sky-view-rays",
                "0",
                "--supersample",
                "1",
                "--path-terms",
                "tabulated",
                "--atmosphere-model",
                "thesis",
                "--sub-bands",
                "1",
            ]
            .map(str::to_owned),
        );
        let (cheapest_s, _) = run(&bin, "irsig-trace", &args(&c));
        for tolerance in TOLERANCES {
            let chosen = path("chosen.exr");
            let decision = path("chosen.decision.ron");
            let mut t = base(&chosen);
            let tol = tolerance.to_string();
            t.extend(
                [
                    "--tolerance",
                    tol.as_str(),
                    "--decision-out",
                    decision.as_str(),
                ]
                .map(str::to_owned),
            );
            let (run_s, stderr) = run(&bin, "irsig-trace", &args(&t));
            let pilot_s: f64 = stderr
                .lines()
                .find_map(|l| l.trim().strip_prefix("pilot: "))
                .and_then(|l| l.split(" in ").nth(1))
                .and_then(|l| l.trim_end_matches(" s").parse().ok())
                .unwrap_or(f64::NAN);
            let d: Decision = irsig_formats::canonical::from_ron(
                "decision",
                &std::fs::read_to_string(&decision).unwrap(),
            )
            .unwrap();
            let settings: Vec<&str> = d.choices.iter().map(|c| c.setting.as_str()).collect();
            let (p99, worst) = errors(&temperatures(Path::new(&chosen)), &reference_t);
            println!(
                "| {} | {tolerance} | {} | {p99:.3} / {worst:.2} | {pilot_s:.2} | {run_s:.2} | {reference_s:.2} | {cheapest_s:.2} |",
                case.name,
                settings.join(", "),
            );
        }
    }
}
