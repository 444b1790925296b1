//! The `--tolerance` verification of docs/accuracy.md on the shipped pipelines: for the
//! quickstart, three fly-by frames (near, far, oblique), the thesis experiment and the
//! daylight pipeline's two bands by day (its atmosphere built with LOWTRAN7), at
//! tolerances of 1, 0.3 and 0.1 K, the models the pilot chose and the chosen rendering's
//! error against a reference converged by construction: the 99th percentile of |ΔT| of
//! the apparent temperature, the worst material's 90th percentile (materials of 10 pixels
//! or more), the share the decision does not guarantee; the pilot's and the run's time,
//! and the cheapest rendering's.
//!
//! ```text
//! cargo build --release --bins
//! cargo run --release -p irsig-tests --example tolerance_rows [BIN_DIR] > rows.md
//! ```
//!
//! Each view is traced at fewer pixels than it ships with (its field of view unchanged,
//! the quickstart 64 × 48, the others 64 pixels wide): the reference traces hundreds of
//! thousands of rays on its hardest pixels. The reference
//! (`irsig_tracer::reference::converged_reference`, through `Plan::converge`) has the most
//! accurate setting of every model the pilot compares against that is not sampled (table
//! atmosphere, exact path terms, the atmosphere's full spectral grid; by day the sun with
//! 16 shadow rays a hit) and converges the sampled ones (rays a pixel, sky-view rays, 8
//! bounces) in rounds, until each pixel's two independent halves differ by a sixth of the
//! smallest tolerance, 0.1 K: its first `IRSIG_ROWS_REFERENCE_ROUNDS` rounds (default 5).
//! `IRSIG_ROWS_CASE=TEXT` runs the cases whose name holds TEXT alone. The reference's own
//! error (half its halves' difference) is printed per case: under a third of a tolerance,
//! that tolerance's rows are verified. The cheapest rendering: the thesis model, no
//! bounce, F = 1, one ray per pixel, tabulated path terms, the band model.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use clap::Parser;
use irsig_model::decision::Decision;
use irsig_model::truth::Layer;
use irsig_radiometry::{Band, InverseTable};
use irsig_tracer::reference::{ConvergedReference, material_p90s, percentile};

struct Case {
    name: &'static str,
    scene: &'static str,
    materials: &'static str,
    view: &'static str,
    /// The pixels traced, across and down.
    pixels: [u32; 2],
    /// The band, µm (the apparent temperatures' too).
    band: [f64; 2],
    /// More flags: [`DAY_ATMOSPHERE`] stands for the daylight atmosphere's file.
    extra: &'static [&'static str],
}

/// The daylight pipeline's atmosphere, built here with LOWTRAN7 (`$IRSIG_LOWTRAN`, else
/// `lowtran7` on PATH) when a case names it: mid-latitude winter, the sun 70° from the
/// zenith on day 172, 710–3340 cm⁻¹ every 20 (both bands), planned from the quickstart's
/// view (`irsig-atmos plan`, then `build`).
const DAY_ATMOSPHERE: &str = "<the daylight atmosphere>";

/// The daylight pipeline's sun: 70° from the zenith, due north.
const DAY_SUN: [&str; 4] = ["--sun-zenith-deg", "70", "--sun-azimuth-deg", "0"];

const CASES: [Case; 7] = [
    Case {
        name: "quickstart",
        scene: "pipelines/quickstart/scene.ron",
        materials: "pipelines/quickstart/materials.ron",
        view: "pipelines/quickstart/view.ron",
        pixels: [64, 48],
        band: [8.0, 14.0],
        extra: &["--atmosphere", "us-std-1976"],
    },
    Case {
        name: "fly-by frame 14 (near: 700 m overhead)",
        scene: "pipelines/thesis-flyby/scene.ron",
        materials: "pipelines/thesis-flyby/materials.ron",
        view: "pipelines/thesis-flyby/views/frame-14.view",
        pixels: [64, 64],
        band: [8.0, 14.0],
        extra: &["--atmosphere", "us-std-1976", "--legacy-unit", "km"],
    },
    Case {
        name: "fly-by frame 9 (far: 12 km)",
        scene: "pipelines/thesis-flyby/scene.ron",
        materials: "pipelines/thesis-flyby/materials.ron",
        view: "pipelines/thesis-flyby/views/frame-09.view",
        pixels: [64, 64],
        band: [8.0, 14.0],
        extra: &["--atmosphere", "us-std-1976", "--legacy-unit", "km"],
    },
    Case {
        name: "fly-by frame 8 (oblique: 81° from nadir)",
        scene: "pipelines/thesis-flyby/scene.ron",
        materials: "pipelines/thesis-flyby/materials.ron",
        view: "pipelines/thesis-flyby/views/frame-08.view",
        pixels: [64, 64],
        band: [8.0, 14.0],
        extra: &["--atmosphere", "us-std-1976", "--legacy-unit", "km"],
    },
    Case {
        name: "thesis experiment",
        scene: "pipelines/thesis-experiment/scene.ron",
        materials: "pipelines/thesis-experiment/materials.ron",
        view: "pipelines/thesis-experiment/view.ron",
        pixels: [64, 50],
        band: [8.0, 14.0],
        extra: &["--atmosphere", "midlat-winter"],
    },
    Case {
        name: "daylight 3-5 µm (the quickstart at a low noon sun)",
        scene: "pipelines/quickstart/scene.ron",
        materials: "pipelines/daylight/materials.ron",
        view: "pipelines/quickstart/view.ron",
        pixels: [64, 48],
        band: [3.0, 5.0],
        extra: &[
            "--atmosphere",
            DAY_ATMOSPHERE,
            "--band",
            "3-5",
            DAY_SUN[0],
            DAY_SUN[1],
            DAY_SUN[2],
            DAY_SUN[3],
        ],
    },
    Case {
        name: "daylight 8-14 µm (the quickstart at a low noon sun)",
        scene: "pipelines/quickstart/scene.ron",
        materials: "pipelines/daylight/materials.ron",
        view: "pipelines/quickstart/view.ron",
        pixels: [64, 48],
        band: [8.0, 14.0],
        extra: &[
            "--atmosphere",
            DAY_ATMOSPHERE,
            "--band",
            "8-14",
            DAY_SUN[0],
            DAY_SUN[1],
            DAY_SUN[2],
            DAY_SUN[3],
        ],
    },
];

const TOLERANCES: [f64; 3] = [1.0, 0.3, 0.1];

/// Runs `tool` and gives its wall time and stderr, or its stderr when it fails.
fn run(bin: &Path, tool: &str, args: &[String]) -> Result<(f64, String), String> {
    let started = Instant::now();
    let out = Command::new(bin.join(tool))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("{tool}: {e}"));
    let seconds = started.elapsed().as_secs_f64();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    if out.status.success() {
        Ok((seconds, stderr))
    } else {
        Err(stderr)
    }
}

/// The view file `path` with `pixels` instead of its own (a RON view's `pixels: (W, H)`, a
/// thesis view file's second line that is not a comment), written to `to`.
fn smaller_view(path: &str, pixels: [u32; 2], to: &Path) {
    let text = std::fs::read_to_string(path).unwrap();
    let [w, h] = pixels;
    let out = if let Some(at) = text.find("pixels:") {
        let end = at + text[at..].find(')').expect("pixels: (W, H)") + 1;
        format!("{}pixels: ({w}, {h}){}", &text[..at], &text[end..])
    } else {
        let mut seen = 0;
        let lines: Vec<String> = text
            .lines()
            .map(|l| {
                if l.trim_start().starts_with('#') || l.trim().is_empty() {
                    return l.to_owned();
                }
                seen += 1;
                if seen == 2 {
                    format!("{w} {h}")
                } else {
                    l.to_owned()
                }
            })
            .collect();
        lines.join("\n") + "\n"
    };
    std::fs::write(to, out).unwrap();
}

/// The radiance EXR's apparent temperatures in the flat band `band` (µm).
fn temperatures(radiance: &Path, band: [f64; 2]) -> Vec<f64> {
    let raster = irsig_raster::read_exr(&std::fs::read(radiance).unwrap()).unwrap();
    let radiance: Vec<f64> = raster
        .layer("radiance")
        .unwrap()
        .data
        .iter()
        .map(|&l| f64::from(l))
        .collect();
    let band = Band::new(band[0], band[1]).unwrap();
    let table = InverseTable::new(&band, &radiance);
    radiance.iter().map(|&l| table.temperature(l)).collect()
}

/// The truth EXR's primary material.
fn material(truth: &Path) -> Vec<f32> {
    let raster = irsig_raster::read_exr(&std::fs::read(truth).unwrap()).unwrap();
    raster
        .layer(Layer::MaterialPrimary.name())
        .unwrap()
        .data
        .clone()
}

/// The daylight atmosphere's file in `dir` ([`DAY_ATMOSPHERE`]), built on first use.
fn day_atmosphere(bin: &Path, dir: &Path) -> String {
    let spa = dir.join("day.spa");
    if !spa.exists() {
        let (raw, plan) = (dir.join("day-scene.raw"), dir.join("day-plan"));
        let path = |p: &Path| p.to_string_lossy().into_owned();
        run(
            bin,
            "irsig-flatten",
            &strings(&[
                "pipelines/quickstart/scene.ron",
                "--materials",
                "pipelines/quickstart/materials.ron",
                "-o",
                &path(&raw),
            ]),
        )
        .unwrap();
        run(
            bin,
            "irsig-atmos",
            &strings(&[
                "plan",
                "--scene",
                &path(&raw),
                "--view",
                "pipelines/quickstart/view.ron",
                "--atmosphere",
                "midlat-winter",
                DAY_SUN[0],
                DAY_SUN[1],
                "--day-of-year",
                "172",
                "--wavenumber-per-cm",
                "710,3340,20",
                "-o",
                &path(&plan),
            ]),
        )
        .unwrap();
        let out = Command::new(bin.join("irsig-atmos"))
            .env("IRSIG_LOWTRAN", irsig_tests::lowtran())
            .args(["build", &path(&plan), "-o", &path(&spa)])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "irsig-atmos build: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    spa.to_string_lossy().into_owned()
}

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| (*s).to_owned()).collect()
}

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    std::env::set_current_dir(&root).unwrap();
    let bin = std::env::args()
        .nth(1)
        .map_or_else(|| root.join("target/release"), PathBuf::from);
    let rounds: usize = std::env::var("IRSIG_ROWS_REFERENCE_ROUNDS")
        .map_or(5, |r| r.parse().expect("IRSIG_ROWS_REFERENCE_ROUNDS=N"));
    let stop_k = TOLERANCES[TOLERANCES.len() - 1] / 6.0;
    let tmp = tempfile::tempdir().unwrap();
    println!(
        "| case | tolerance (K) | chosen: atmosphere, bounces, sky-view, supersampling, path \
         terms, sub-bands | p99 \\|ΔT\\| (K) | worst material p90 (K) | not guaranteed | \
         pilot (s) | run (s) | cheapest (s) |"
    );
    println!("| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: |");
    let mut references = Vec::new();
    let only = std::env::var("IRSIG_ROWS_CASE").unwrap_or_default();
    for case in CASES.iter().filter(|c| c.name.contains(&only)) {
        let ready = CaseRun::prepare(case, &bin, tmp.path());
        // The reference, through the same flags as the tool's renderings.
        let started = Instant::now();
        let reference = ready.reference(stop_k, rounds);
        references.push((
            case.name,
            reference.clone(),
            started.elapsed().as_secs_f64(),
        ));
        let cheapest_s = ready.cheapest_seconds();
        for tolerance in TOLERANCES {
            ready.tolerance_row(tolerance, &reference, cheapest_s);
        }
    }
    print_references(references);
}

/// The path of file `name` in `dir`, as a string.
fn in_dir(dir: &Path, name: &str) -> String {
    dir.join(name).to_string_lossy().into_owned()
}

/// One case made ready to trace: its scene flattened and its view made smaller, in the
/// scratch directory `dir`, with the tools in `bin`.
struct CaseRun<'a> {
    case: &'a Case,
    bin: &'a Path,
    dir: &'a Path,
    raw: String,
    view: String,
}

impl<'a> CaseRun<'a> {
    /// Flattens `case`'s scene and writes its smaller view, into `dir`.
    fn prepare(case: &'a Case, bin: &'a Path, dir: &'a Path) -> Self {
        let raw = in_dir(dir, "scene.raw");
        let view = in_dir(
            dir,
            &format!(
                "view.{}",
                Path::new(case.view).extension().unwrap().to_string_lossy()
            ),
        );
        smaller_view(case.view, case.pixels, Path::new(&view));
        run(
            bin,
            "irsig-flatten",
            &strings(&[case.scene, "--materials", case.materials, "-o", &raw]),
        )
        .unwrap();
        Self {
            case,
            bin,
            dir,
            raw,
            view,
        }
    }

    /// The path of file `name` in the scratch directory.
    fn path(&self, name: &str) -> String {
        in_dir(self.dir, name)
    }

    /// The flags of every rendering of the case (the daylight atmosphere built on first
    /// use), then `more`.
    fn base(&self, more: &[&str]) -> Vec<String> {
        let mut v = strings(&[
            "--scene",
            &self.raw,
            "--materials",
            self.case.materials,
            "--view",
            &self.view,
        ]);
        v.extend(self.case.extra.iter().map(|&a| {
            if a == DAY_ATMOSPHERE {
                day_atmosphere(self.bin, self.dir)
            } else {
                a.to_owned()
            }
        }));
        v.extend(strings(more));
        v
    }

    /// The reference converged to `stop_k` in at most `rounds` rounds, with the most
    /// accurate setting of every model that is not sampled.
    fn reference(&self, stop_k: f64, rounds: usize) -> ConvergedReference {
        let mut args = vec!["irsig-trace".to_owned()];
        args.extend(self.base(&[
            "--path-terms",
            "exact",
            "--atmosphere-model",
            "table",
            "--sub-bands",
            "full",
        ]));
        if self.case.extra.contains(&DAY_SUN[0]) {
            args.extend(strings(&["--sun-shadow-rays", "16"]));
        }
        let plan = irsig_trace::plan_of(&irsig_trace::Cli::parse_from(&args)).unwrap();
        plan.converge(stop_k, rounds).unwrap().remove(0)
    }

    /// The seconds the cheapest rendering takes.
    fn cheapest_seconds(&self) -> f64 {
        let cheapest = self.path("cheapest.exr");
        let (cheapest_s, _) = run(
            self.bin,
            "irsig-trace",
            &self.base(&[
                "--radiance-exr",
                &cheapest,
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
            ]),
        )
        .unwrap();
        cheapest_s
    }

    /// Renders the case at `tolerance` and prints its row: the pilot's choice and its error
    /// against `reference`, or the refusal.
    fn tolerance_row(&self, tolerance: f64, reference: &ConvergedReference, cheapest_s: f64) {
        let case = self.case;
        let (chosen, truth) = (self.path("chosen.exr"), self.path("chosen.truth.exr"));
        let decision = self.path("chosen.decision.ron");
        let tol = tolerance.to_string();
        let outcome = run(
            self.bin,
            "irsig-trace",
            &self.base(&[
                "--radiance-exr",
                &chosen,
                "--truth-exr",
                &truth,
                "--tolerance",
                &tol,
                "--decision-out",
                &decision,
            ]),
        );
        let (run_s, stderr) = match outcome {
            Ok(o) => o,
            Err(stderr) => {
                let why = refusal(&stderr);
                println!(
                    "| {} | {tolerance} | refused: {why} | | | | | | |",
                    case.name
                );
                return;
            }
        };
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
        let error: Vec<f64> = temperatures(Path::new(&chosen), case.band)
            .iter()
            .zip(&reference.truth)
            .map(|(c, r)| c - r)
            .collect();
        let worst = worst_material(&error, &material(Path::new(&truth)));
        println!(
            "| {} | {tolerance} | {} | {:.3} | {worst} | {:.2} % | {pilot_s:.2} | {run_s:.2} | \
             {cheapest_s:.2} |",
            case.name,
            settings.join(", "),
            percentile(&error, 99.0),
            100.0 * d.not_guaranteed_share,
        );
    }
}

/// Why a rendering was refused, from its stderr: the refusal's floor, else its last line.
fn refusal(stderr: &str) -> String {
    let lines: Vec<&str> = stderr.lines().map(str::trim).collect();
    lines
        .iter()
        .find_map(|l| l.find("floor is about").map(|at| &l[at..]))
        .or_else(|| lines.iter().rev().find(|l| !l.is_empty()).copied())
        .unwrap_or("(no message)")
        .replace('|', "\\|")
}

/// The worst material's 90th percentile of `error`, with the material and its pixels
/// (`material` each pixel's), for the row.
fn worst_material(error: &[f64], material: &[f32]) -> String {
    let mut ids: Vec<u16> = material.iter().map(|&m| m as u16).collect();
    ids.sort_unstable();
    ids.dedup();
    material_p90s(error, material, &ids)
        .into_iter()
        .max_by(|a, b| a.2.total_cmp(&b.2))
        .map_or("—".to_owned(), |(id, n, p90)| {
            format!("{p90:.3} (material {id}, {n} pixels)")
        })
}

/// Prints the table of the references: each case's reference error, its pixels by round,
/// those capped, and its time.
fn print_references(references: Vec<(&str, ConvergedReference, f64)>) {
    println!();
    println!(
        "| case | reference error p99 (K) | worst (K) | pixels by round | capped | CPU-bound \
         wall time (s) |"
    );
    println!("| --- | ---: | ---: | --- | ---: | ---: |");
    for (name, r, seconds) in references {
        let rounds: Vec<String> = r.pixels_per_round.iter().map(usize::to_string).collect();
        println!(
            "| {name} | {:.4} | {:.4} | {} | {} | {seconds:.0} |",
            r.error_p99_k(),
            percentile(&r.error, 100.0),
            rounds.join(" / "),
            r.capped.len(),
        );
    }
}
