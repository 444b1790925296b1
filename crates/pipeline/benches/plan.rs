//! What the runner costs before any tool runs: parsing and checking a pipeline with a long
//! frame sweep (a fly-by of N frames, two stages per frame plus a gather), and writing its
//! Makefile. Run with `cargo bench -p irsig-pipeline`.

use std::path::{Path, PathBuf};

use irsig_pipeline::{Pipeline, Tools};

fn main() {
    divan::main();
}

fn pipeline_text(frames: usize) -> String {
    format!(
        r#"Pipeline(
    sweeps: {{"fly": FlyBy(frames: {frames}, path: [(0, -3000, 300), (0, 3000, 300)], look_at: (0, 0, 0))}},
    stages: [
        Stage(name: "trace", tool: "t", sweep: "fly", params: {{"eye": "{{eye}}", "look-at": "{{look_at}}"}},
              outputs: {{"o": "build/r-{{frame:04}}.exr"}}),
        Stage(name: "sensor", tool: "s", sweep: "fly", args: ["build/r-{{frame:04}}.exr"],
              params: {{"mtf": "gaussian", "sigma": 0.7}}, outputs: {{"o": "build/s-{{frame:04}}.png"}}),
        Stage(name: "sheet", tool: "c", gather: "fly", args: ["build/s-{{frame:04}}.png"],
              outputs: {{"o": "build/sheet.png"}}),
    ],
)"#
    )
}

fn tools() -> Tools {
    Tools::new(|t| Some(PathBuf::from(format!("/opt/irsig-{t}"))))
}

#[divan::bench(args = [24, 1000])]
fn parse_and_plan(bencher: divan::Bencher<'_, '_>, frames: usize) {
    let text = pipeline_text(frames);
    let tools = tools();
    bencher.bench(|| {
        Pipeline::parse("fly.ron", divan::black_box(&text), Path::new("."))
            .and_then(|p| p.plan(&tools))
            .map(|plan| plan.steps.len())
    });
}

#[divan::bench(args = [24, 1000])]
fn makefile(bencher: divan::Bencher<'_, '_>, frames: usize) {
    let plan = Pipeline::parse("fly.ron", &pipeline_text(frames), Path::new("."))
        .and_then(|p| p.plan(&tools()))
        .expect("the bench pipeline is valid");
    bencher.bench(|| plan.makefile().map(|m| m.len()));
}
