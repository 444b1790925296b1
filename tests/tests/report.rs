//! The run report (`irsig-report`) end to end: a small quickstart frame flattened, traced
//! with the tolerance pilot and declared uncertainties and sensed with counts that clip, all
//! by `irsig-run` from a pipeline file, then reported with every input. The page is opened
//! in headless Chromium (Debian's `chromium`, installed by `.ci/run`), which must render it
//! with every image loaded and every plot present, and what it shows must be what the files
//! say:
//!
//! - the numbers are those of the decision sidecar, of `irsig-stats` run on the same
//!   files, of the LUT file and of the declared uncertainties;
//! - the pixels at count 0 and at full scale, over the frame and per region, are those of
//!   the sensor's count image, and a warning saying so sits visibly above the image;
//! - the profile's line lies on the image over the centres of its end pixels;
//! - the colour bars' tick labels stand clear of their axis;
//! - provenance covers the whole chain: every input the trace and the sensor read, as
//!   `sha256sum` hashes the files they were given, named relative to the page.
//!
//! Bad input — a missing file, images of two sizes, a decision file that does not parse, a
//! profile outside the image, uncertainties the truth EXR was not traced with, an
//! unwritable output — is refused with a message naming it, and nothing is written.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use irsig_model::decision::Decision;
use irsig_tests::{bin, repo_root};
use predicates::prelude::*;

/// The quickstart camera at 60 × 45 pixels: the panel, the pool, the car and the sky.
const VIEW: &str = "LookAt(position_m: (0.0, -22.6851, 5.0), target_m: (1.5, 0.0, 1.0), \
                    pixels: (60, 45), fov_deg: (47.0, 36.0), gain_dc_per_k: Some(3.0))";

const MATERIALS: &str = "quickstart/materials.ron";

/// Declared uncertainties: every facet's temperature ± 0.5 K, the grass's ε ± 0.01, τ and
/// path radiance ± 2 % and 5 %.
const UNCERTAINTIES: &str = "(temperature: [(facets: All, sigma_k: 0.5)], \
     emissivity: [(material: 1, sigma: 0.01)], transmission_relative: 0.02, \
     path_radiance_relative: 0.05)";

/// Regions: two materials, a pixel box, and a reference column.
const REGIONS: &str = r#"(references: [(name: "guess", source: "a round number")],
 regions: [
  (name: "grass", material: Some(1), pixels: None, references: [(name: "guess", temperature_k: 295.0)]),
  (name: "pool <water> & co", material: Some(2), pixels: None, references: []),
  (name: "left half", material: None, pixels: Some((columns: (0, 29), rows: (0, 44))), references: []),
 ])"#;

/// The run, as a pipeline file beside its data: flatten the quickstart scene, trace it with
/// the pilot and the uncertainties, sense it with a 3 × 3 box at 8 counts per kelvin. The
/// scene spans some 60 K (sky to panel) and 8-bit counts at 8 per kelvin only 32 K, so the
/// counts clip at both ends.
const PIPELINE: &str = r#"Pipeline(stages: [
    Stage(name: "flatten", tool: "flatten", args: ["quickstart/scene.ron"],
          reads: ["quickstart/ground.ron", "quickstart/box.ron"],
          inputs: {"materials": "quickstart/materials.ron"}, outputs: {"o": "scene.raw"}),
    Stage(name: "trace", tool: "trace",
          inputs: {"scene": "scene.raw", "materials": "quickstart/materials.ron",
                   "view": "view.ron", "uncertainties": "u.ron"},
          params: {"atmosphere": "us-std-1976", "tolerance": 0.3},
          outputs: {"radiance-exr": "frame.radiance.exr", "truth-exr": "frame.truth.exr",
                    "decision-out": "frame.decision.ron"}),
    Stage(name: "sensor", tool: "sensor", args: ["frame.radiance.exr"],
          params: {"mtf": "box:3x3", "dc-per-kelvin": 8},
          outputs: {"o": "sensor.exr", "lut": "lut.txt", "colour-preview": "colour.png",
                    "dc-png": "dc.png"}),
])"#;

/// A traced, sensed frame and the report's inputs, in a temporary directory.
struct Run {
    dir: tempfile::TempDir,
}

impl Run {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::create_dir(d.join("quickstart")).unwrap();
        for entry in std::fs::read_dir(repo_root().join("pipelines/quickstart")).unwrap() {
            let path = entry.unwrap().path();
            std::fs::copy(&path, d.join("quickstart").join(path.file_name().unwrap())).unwrap();
        }
        std::fs::write(d.join("view.ron"), VIEW).unwrap();
        std::fs::write(d.join("u.ron"), UNCERTAINTIES).unwrap();
        std::fs::write(d.join("regions.ron"), REGIONS).unwrap();
        std::fs::write(d.join("run.ron"), PIPELINE).unwrap();
        bin("irsig-run").arg(d.join("run.ron")).assert().success();
        Self { dir }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn arg(&self, name: &str) -> String {
        self.path(name).to_str().unwrap().to_owned()
    }

    /// `irsig-report` with every input, the output to `out`; `with` replaces the value of
    /// some flags.
    fn report(&self, out: &Path, with: &[(&str, &str)]) -> assert_cmd::Command {
        let flags = [
            ("--radiance", self.arg("sensor.exr")),
            ("--regions", self.arg("regions.ron")),
            ("--decision", self.arg("frame.decision.ron")),
            ("--uncertainties", self.arg("u.ron")),
            ("--lut", self.arg("lut.txt")),
            ("--colour-preview", self.arg("colour.png")),
            ("--profile", "0,30:59,12".to_owned()),
            ("--pipeline", self.arg("run.ron")),
            (
                "--command",
                "irsig-trace --tolerance 0.3 <probe> & more".to_owned(),
            ),
        ];
        let mut cmd = bin("irsig-report");
        cmd.arg(self.path("frame.truth.exr"));
        for (flag, value) in flags {
            let value = with
                .iter()
                .find(|(f, _)| *f == flag)
                .map_or(value.as_str(), |(_, v)| v);
            cmd.args([flag, value]);
        }
        cmd.arg("-o").arg(out);
        cmd
    }
}

/// What the probe script reports from the rendered page.
const PROBE: &str = r#"<script>
window.addEventListener('load', () => {
  const cells = (sel) => Array.from(document.querySelectorAll(sel + ' tbody tr'))
    .map(tr => Array.from(tr.children).map(td => td.textContent.trim()));
  const text = (id) => { const e = document.getElementById(id); return e ? e.textContent.trim() : null; };
  const rect = (e) => { if (!e) return null; const b = e.getBoundingClientRect();
    return [b.left, b.top, b.right, b.bottom]; };
  // A colour bar's labels against its axis: the axis line and its ticks are the polylines,
  // the labels the unrotated texts; the gap is from the labels' right ends to the leftmost
  // point of any tick or the axis.
  const bars = Array.from(document.querySelectorAll('#image .figure > svg, #budget .figure > svg'))
    .map(svg => {
      const lines = Array.from(svg.querySelectorAll('polyline')).map(l => l.getBoundingClientRect());
      const labels = Array.from(svg.querySelectorAll('text'))
        .filter(t => !(t.getAttribute('transform') || '').includes('rotate'))
        .map(t => t.getBoundingClientRect());
      const axisLeft = Math.min(...lines.map(b => b.left));
      const labelRight = Math.max(...labels.map(b => b.right));
      const sorted = labels.slice().sort((a, b) => a.top - b.top);
      let overlap = false;
      for (let i = 1; i < sorted.length; i++) overlap ||= sorted[i].top < sorted[i - 1].bottom;
      return {section: svg.closest('section').id, labels: labels.length,
        gap: axisLeft - labelRight, overlap};
    });
  const warning = document.getElementById('saturation-warning');
  const style = warning ? getComputedStyle(warning) : null;
  const out = {
    title: document.title,
    images: Array.from(document.images).map(i => ({id: i.id, complete: i.complete,
      natural: [i.naturalWidth, i.naturalHeight], rect: rect(i)})),
    svgs: Array.from(document.querySelectorAll('svg')).map(s => {
      const b = s.getBoundingClientRect();
      return [s.closest('section').id, s.id, b.width, b.height,
        s.querySelectorAll('rect,polyline,path,line').length];
    }),
    overlay: rect(document.getElementById('profile-overlay')),
    profile_line: rect(document.getElementById('profile-line')),
    bars,
    warning: warning ? {rect: rect(warning), text: warning.textContent,
      display: style.display, visibility: style.visibility, colour: style.color} : null,
    decision: cells('#decision-table'),
    stats: cells('#stats'),
    inputs: cells('#inputs'),
    declared: cells('#declared'),
    saturation: cells('#saturation-regions'),
    numbers: Object.fromEntries(['t-min', 't-max', 'sigma-min', 'sigma-max', 'lut-first',
      'lut-last', 'tolerance', 'percentile', 'pilot-pixels', 'version', 'commands',
      'sat-pixels', 'sat-zero', 'sat-full', 'not-shown'].map(i => [i, text(i)])),
  };
  const pre = document.createElement('pre');
  pre.id = 'probe-result';
  pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
});
</script>"#;

/// Opens `page` in headless Chromium and returns what the probe found, or panics with the
/// reason Chromium could not show it.
fn open_in_chromium(page: &Path) -> serde_json::Value {
    let html = std::fs::read_to_string(page).unwrap();
    let probe_page = page.with_extension("probe.html");
    std::fs::write(
        &probe_page,
        html.replacen("</body>", &format!("{PROBE}\n</body>"), 1),
    )
    .unwrap();
    let profile = tempfile::tempdir().unwrap();
    let (dom_path, err_path) = (page.with_extension("dom"), page.with_extension("stderr"));
    let mut child = Command::new("chromium")
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--virtual-time-budget=10000",
            "--dump-dom",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("file://{}", probe_page.display()))
        // Files, not pipes: the DOM is larger than a pipe holds, and nothing reads it
        // until Chromium has finished.
        .stdout(Stdio::from(std::fs::File::create(&dom_path).unwrap()))
        .stderr(Stdio::from(std::fs::File::create(&err_path).unwrap()))
        .spawn()
        .unwrap_or_else(|e| {
            panic!(
                "cannot start chromium ({e}): this test needs Debian's chromium \
                 (.ci/run installs it)"
            )
        });
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("chromium did not finish within 120 s");
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    let status = child.wait().unwrap();
    let dom = std::fs::read_to_string(&dom_path).unwrap();
    let stderr = std::fs::read_to_string(&err_path).unwrap_or_default();
    let Some(start) = dom.find("<pre id=\"probe-result\">") else {
        panic!(
            "chromium ({}) rendered no probe result; stderr:\n{}\nstdout:\n{}",
            status,
            stderr,
            &dom[..dom.len().min(2000)]
        );
    };
    let body = &dom[start + "<pre id=\"probe-result\">".len()..];
    let body = &body[..body.find("</pre>").unwrap()];
    let json = body
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&nbsp;", "\u{a0}")
        .replace("&amp;", "&");
    serde_json::from_str(&json).unwrap_or_else(|e| panic!("probe result {json}: {e}"))
}

fn number(v: &serde_json::Value) -> f64 {
    v.as_str()
        .unwrap_or_else(|| panic!("{v} is not text"))
        .parse()
        .unwrap_or_else(|e| panic!("{v}: {e}"))
}

/// `shown` (a number the page rounds to `decimals`) is `value`.
fn assert_shown(what: &str, shown: f64, value: f64, decimals: i32) {
    let half_unit = 0.5 * 10f64.powi(-decimals) + 1e-9;
    assert!(
        (shown - value).abs() <= half_unit,
        "{what}: the page shows {shown}, the file says {value}"
    );
}

/// `sha256sum FILE`'s hex digits.
fn sha256sum(file: &Path) -> String {
    let out = Command::new("sha256sum").arg(file).output().unwrap();
    assert!(out.status.success(), "sha256sum {}", file.display());
    String::from_utf8(out.stdout)
        .unwrap()
        .split_whitespace()
        .next()
        .unwrap()
        .to_owned()
}

/// The sensor's count image: its counts, row by row.
fn counts(png: &Path) -> Vec<u8> {
    image::open(png).unwrap().into_luma8().into_raw()
}

#[test]
fn chromium_renders_the_report_and_its_numbers_are_the_sidecars() {
    let run = Run::new();
    let page = run.path("report.html");
    run.report(&page, &[]).assert().success();
    let html = std::fs::read_to_string(&page).unwrap();
    // Self-contained: the only URL is the SVG namespace; every image is a data: URI.
    let urls: Vec<&str> = html
        .match_indices("http")
        .map(|(i, _)| &html[i..html.len().min(i + 30)])
        .filter(|u| !u.starts_with("http://www.w3.org/2000/svg"))
        .collect();
    assert!(urls.is_empty(), "the page refers to {urls:?}");
    assert_eq!(
        html.matches("src=\"").count(),
        html.matches("src=\"data:image/png;base64,").count()
    );
    assert!(!html.contains("<script"));
    // Files are named from the page's directory, never by this machine's absolute paths.
    let dir = run.dir.path().to_str().unwrap();
    assert!(!html.contains(dir), "the page names {dir}");

    let probe = open_in_chromium(&page);

    // Every image loaded, at its file's size; the colour image once (the sensor's colour
    // preview is the same picture: it is listed, not shown again).
    let images = probe["images"].as_array().unwrap();
    let ids: Vec<&str> = images.iter().map(|i| i["id"].as_str().unwrap()).collect();
    assert_eq!(ids, ["colour", "sigma"]);
    for image in images {
        assert_eq!(image["complete"], true, "{image}");
        let natural = &image["natural"];
        assert_eq!(
            (natural[0].as_f64().unwrap(), natural[1].as_f64().unwrap()),
            (60.0, 45.0),
            "{image}"
        );
    }
    // The plots are there and drawn: the profile's overlay and two colour bars, the
    // histogram, the profile, the LUT.
    let svgs = probe["svgs"].as_array().unwrap();
    let sections: Vec<(&str, &str)> = svgs
        .iter()
        .map(|s| (s[0].as_str().unwrap(), s[1].as_str().unwrap()))
        .collect();
    assert_eq!(
        sections,
        [
            ("image", "profile-overlay"),
            ("image", ""),
            ("histogram", ""),
            ("profile", ""),
            ("budget", ""),
            ("lut", "")
        ],
        "{svgs:?}"
    );
    for s in svgs {
        assert!(
            s[2].as_f64().unwrap() > 50.0 && s[3].as_f64().unwrap() > 50.0,
            "{s}"
        );
        assert!(s[4].as_f64().unwrap() >= 2.0, "{s} draws nothing");
    }

    // The profile's line lies on the image: the overlay covers the image exactly, and the
    // line runs between the centres of the end pixels (0, 30) and (59, 12) of the 60 × 45
    // image shown 8 times enlarged (360 CSS pixels tall).
    let rect = |v: &serde_json::Value| -> [f64; 4] {
        std::array::from_fn(|i| v[i].as_f64().unwrap_or_else(|| panic!("{v}")))
    };
    let image = rect(&images[0]["rect"]);
    let overlay = rect(&probe["overlay"]);
    for i in 0..4 {
        assert!(
            (overlay[i] - image[i]).abs() < 0.5,
            "{overlay:?} vs {image:?}"
        );
    }
    let scale = (image[3] - image[1]) / 45.0;
    assert!((scale - 8.0).abs() < 1e-6, "{scale}");
    let line = rect(&probe["profile_line"]);
    let expected = [
        image[0] + 0.5 * scale,
        image[1] + 12.5 * scale,
        image[0] + 59.5 * scale,
        image[1] + 30.5 * scale,
    ];
    for i in 0..4 {
        assert!(
            (line[i] - expected[i]).abs() < 1.0,
            "the profile's line spans {line:?}, its pixels {expected:?}"
        );
    }

    // The colour bars' tick labels stand clear of their ticks and axis line, and of each
    // other.
    let bars = probe["bars"].as_array().unwrap();
    assert_eq!(bars.len(), 2, "{bars:?}");
    for bar in bars {
        assert!(bar["labels"].as_u64().unwrap() >= 3, "{bar}");
        assert!(
            bar["gap"].as_f64().unwrap() >= 3.0,
            "{bar}: a label comes within 3 CSS pixels of the axis"
        );
        assert_eq!(bar["overlap"], false, "{bar}");
    }

    // Saturation: the counts are the sensor's own count image's.
    let dc = counts(&run.path("dc.png"));
    assert_eq!(dc.len(), 60 * 45);
    let at_zero = dc.iter().filter(|&&c| c == 0).count();
    let at_full = dc.iter().filter(|&&c| c == 255).count();
    assert!(
        at_zero > 0 && at_full > 0,
        "{at_zero} {at_full}: the run should clip"
    );
    let numbers = &probe["numbers"];
    assert_eq!(numbers["sat-pixels"], "2700");
    assert_eq!(numbers["sat-zero"], at_zero.to_string().as_str());
    assert_eq!(numbers["sat-full"], at_full.to_string().as_str());
    // Per region: the truth's materials select the pixels, the count image says which clip.
    let truth =
        irsig_raster::read_exr(&std::fs::read(run.path("frame.truth.exr")).unwrap()).unwrap();
    let ids = &truth.layer("material_primary").unwrap().data;
    // Material ids are small whole numbers stored exactly as f32.
    let is = |i: usize, id: u16| ids[i].to_bits() == f32::from(id).to_bits();
    let selects: [&dyn Fn(usize) -> bool; 3] = [&|i| is(i, 1), &|i| is(i, 2), &|i| i % 60 < 30];
    let rows = probe["saturation"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    for (row, select) in rows.iter().zip(selects) {
        let pixels: Vec<usize> = (0..dc.len()).filter(|&i| select(i)).collect();
        let zero = pixels.iter().filter(|&&i| dc[i] == 0).count();
        let full = pixels.iter().filter(|&&i| dc[i] == 255).count();
        assert_eq!(row[1], pixels.len().to_string().as_str(), "{row}");
        assert_eq!(row[2], zero.to_string().as_str(), "{row}");
        assert_eq!(row[3], full.to_string().as_str(), "{row}");
        assert_shown(
            &format!("{row} saturated %"),
            number(&row[4]),
            100.0 * (zero + full) as f64 / pixels.len() as f64,
            2,
        );
    }
    // And the page warns about it, in red, above the image.
    let warning = &probe["warning"];
    assert!(warning.is_object(), "no saturation warning");
    let text = warning["text"].as_str().unwrap();
    for says in [
        format!("{at_full} pixels"),
        "count 255".to_owned(),
        format!("{at_zero} ("),
        "count 0".to_owned(),
        "--dc-per-kelvin".to_owned(),
    ] {
        assert!(text.contains(&says), "{says:?} not in the warning: {text}");
    }
    assert_eq!(warning["display"], "block");
    assert_eq!(warning["visibility"], "visible");
    let w = rect(&warning["rect"]);
    assert!(w[2] - w[0] > 100.0 && w[3] - w[1] > 10.0, "{w:?}");
    assert!(
        w[3] <= image[1],
        "the warning is below the image: {w:?} {image:?}"
    );

    // The decision table is the sidecar's, read here by ron itself.
    let decision: Decision =
        ron::from_str(&std::fs::read_to_string(run.path("frame.decision.ron")).unwrap()).unwrap();
    // The tolerance and percentile are shown in full (Rust's shortest round-trip form):
    // they read back as the very numbers of the file.
    assert_eq!(
        number(&numbers["tolerance"]).to_bits(),
        decision.tolerance_k.to_bits()
    );
    assert_eq!(
        number(&numbers["percentile"]).to_bits(),
        decision.percentile.to_bits()
    );
    assert_eq!(
        numbers["pilot-pixels"],
        decision.pilot_pixels.to_string().as_str()
    );
    let rows = probe["decision"].as_array().unwrap();
    assert_eq!(rows.len(), decision.choices.len() + 1);
    for (row, c) in rows.iter().zip(&decision.choices) {
        let what = c.model.name();
        assert_eq!(row[0], what);
        assert_eq!(row[1], c.setting.as_str(), "{what}");
        assert_eq!(row[2], c.reference.as_str(), "{what}");
        assert_eq!(row[3], if c.pinned { "yes" } else { "no" }, "{what}");
        assert_shown(what, number(&row[4]), c.error.percentile_k, 3);
        assert_shown(what, number(&row[5]), c.error.max_k, 3);
        assert_shown(what, number(&row[6]), c.relative_cost, 3);
        assert_eq!(row[7], c.reason.as_str(), "{what}");
    }
    let total = &rows[decision.choices.len()];
    assert_eq!(total[0], "predicted");
    assert_shown(
        "predicted",
        number(&total[4]),
        decision.predicted.percentile_k,
        3,
    );
    assert_shown("predicted", number(&total[5]), decision.predicted.max_k, 3);
    assert_shown("predicted", number(&total[6]), decision.relative_cost, 3);

    // The budget lists what u.ron declares.
    assert_eq!(
        probe["declared"],
        serde_json::json!([
            ["kinetic temperature", "every facet", "0.5 K"],
            ["emissivity", "material 1", "0.01"],
            ["atmospheric transmission", "relative", "2 %"],
            ["path and sky radiance", "relative", "5 %"],
        ])
    );

    // The statistics are irsig-stats' on the same files.
    let out = bin("irsig-stats")
        .arg(run.path("frame.truth.exr"))
        .args(["--regions", &run.arg("regions.ron")])
        .args(["--radiance", &run.arg("sensor.exr")])
        .args(["--format", "csv"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let csv = String::from_utf8(out.stdout).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header,
        [
            "region",
            "pixels",
            "mean_k",
            "std_dev_k",
            "min_k",
            "max_k",
            "guess_k",
            "mean_minus_guess_k"
        ]
    );
    let expected: Vec<Vec<String>> = lines
        .map(|l| {
            // Region names hold no comma here.
            l.split(',').map(str::to_owned).collect()
        })
        .collect();
    let shown = probe["stats"].as_array().unwrap();
    assert_eq!(shown.len(), 3);
    for (row, want) in shown.iter().zip(&expected) {
        assert_eq!(row[0], want[0].as_str());
        assert_eq!(row[1], want[1].as_str(), "{}: pixels", want[0]);
        for i in 2..6 {
            let v: f64 = want[i].parse().unwrap();
            assert_shown(&format!("{} {}", want[0], header[i]), number(&row[i]), v, 3);
        }
        for i in 6..8 {
            if want[i].is_empty() {
                assert_eq!(row[i], "-");
            } else {
                let v: f64 = want[i].parse().unwrap();
                assert_shown(&format!("{} {}", want[0], header[i]), number(&row[i]), v, 3);
            }
        }
    }

    // The LUT's ends, as the LUT file spells them.
    let lut = std::fs::read_to_string(run.path("lut.txt")).unwrap();
    let rows: Vec<Vec<f64>> = lut
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_shown("LUT first", number(&numbers["lut-first"]), rows[0][2], 4);
    assert_shown(
        "LUT last",
        number(&numbers["lut-last"]),
        rows[rows.len() - 1][2],
        4,
    );
    // The image's range is the statistics' over the whole frame.
    let t_min = number(&numbers["t-min"]);
    let t_max = number(&numbers["t-max"]);
    assert!(t_min < t_max);
    for want in &expected {
        assert!(want[4].parse::<f64>().unwrap() >= t_min - 5e-4);
        assert!(want[5].parse::<f64>().unwrap() <= t_max + 5e-4);
    }
    assert!(number(&numbers["sigma-min"]) > 0.0);
    // Every section applies: nothing is listed as not shown.
    assert!(numbers["not-shown"].is_null(), "{}", numbers["not-shown"]);

    // Provenance along the whole chain: what the trace and the sensor read, as the images
    // record it, then the report's own inputs; each row's file (relative to the page) has
    // the SHA-256 shown, as sha256sum computes it. The built-in atmosphere's spectra are
    // the file the atmosphere crate embeds.
    let inputs = probe["inputs"].as_array().unwrap();
    let row_of = |stage: &str, role: &str| {
        inputs
            .iter()
            .find(|r| r[0] == stage && r[1] == role)
            .unwrap_or_else(|| panic!("no {stage} {role} in {inputs:?}"))
    };
    let chain = [
        ("trace", "scene", "scene.raw", "truth EXR, radiance EXR"),
        (
            "trace",
            "materials",
            "quickstart/materials.ron",
            "truth EXR, radiance EXR",
        ),
        ("trace", "view", "view.ron", "truth EXR, radiance EXR"),
        ("trace", "uncertainties", "u.ron", "truth EXR, radiance EXR"),
        (
            "sensor",
            "radiance EXR",
            "frame.radiance.exr",
            "radiance EXR",
        ),
        ("report", "truth EXR", "frame.truth.exr", "this page"),
        ("report", "radiance EXR", "sensor.exr", "this page"),
        ("report", "regions", "regions.ron", "this page"),
        ("report", "decision", "frame.decision.ron", "this page"),
        ("report", "uncertainties", "u.ron", "this page"),
        ("report", "LUT", "lut.txt", "this page"),
        ("report", "colour preview", "colour.png", "this page"),
        ("report", "pipeline", "run.ron", "this page"),
    ];
    for (stage, role, file, recorded_in) in chain {
        let row = row_of(stage, role);
        assert_eq!(row[2], file, "{stage} {role}");
        assert_eq!(
            row[3],
            sha256sum(&run.path(file)).as_str(),
            "{stage} {role}"
        );
        assert_eq!(row[4], recorded_in, "{stage} {role}");
    }
    let atmosphere = row_of("trace", "atmosphere (a built-in's spectra)");
    assert_eq!(atmosphere[2], "built in: us-std-1976");
    assert_eq!(
        atmosphere[3],
        sha256sum(&repo_root().join("crates/atmosphere/data/us-std-1976.spectral.bin")).as_str()
    );
    assert_eq!(inputs.len(), chain.len() + 1, "{inputs:?}");
    assert_eq!(numbers["version"], env!("CARGO_PKG_VERSION"));
    let commands = numbers["commands"].as_str().unwrap();
    assert!(commands.starts_with("irsig-flatten"), "{commands}");
    assert!(
        commands.ends_with("irsig-trace --tolerance 0.3 <probe> & more"),
        "{commands}"
    );
}

#[test]
fn the_quickstart_pipeline_is_listed_by_its_command_lines() {
    let run = Run::new();
    let page = run.path("p.html");
    bin("irsig-report")
        .arg(run.path("frame.truth.exr"))
        .args(["--pipeline", "pipelines/quickstart.ron", "-o"])
        .arg(&page)
        .assert()
        .success();
    let html = std::fs::read_to_string(&page).unwrap();
    let listed = &html[html.find("<pre id=\"commands\">").unwrap()..];
    let listed = &listed[..listed.find("</pre>").unwrap()];
    // The dry run of the same file prints the same command lines.
    let dry = bin("irsig-run")
        .args(["--dry-run", "--force", "quickstart.ron"])
        .current_dir(irsig_tests::repo_root().join("pipelines"))
        .output()
        .unwrap();
    assert!(dry.status.success());
    let stdout = String::from_utf8(dry.stdout).unwrap();
    let dry_lines: Vec<String> = stdout
        .lines()
        .map(|l| {
            l.replace('&', "&amp;")
                .replace('<', "&lt;")
                .replace('>', "&gt;")
                .replace('"', "&quot;")
        })
        .collect();
    let shown: Vec<&str> = listed["<pre id=\"commands\">".len()..].lines().collect();
    assert_eq!(shown, dry_lines);
    // What does not apply is one line, not empty sections.
    let not_shown = &html[html
        .find("<p class=\"absent\" id=\"not-shown\">Not shown:")
        .unwrap()..];
    let not_shown = &not_shown[..not_shown.find("</p>").unwrap()];
    for a in ["line profile", "per-region statistics", "decision", "LUT"] {
        assert!(not_shown.contains(a), "{a} not in {not_shown}");
    }
    for section in ["profile", "regions", "decision", "lut", "saturation"] {
        assert!(
            !html.contains(&format!("<section id=\"{section}\">")),
            "an empty {section} section"
        );
    }
    // The frame was traced from a 60 × 45 view the quickstart pipeline does not hold: the
    // page says its images are not that pipeline's.
    let stale = &html[html.find("id=\"stale-warning\"").expect("no stale warning")..];
    let stale = &stale[..stale.find("</p>").unwrap()];
    assert!(stale.contains("trace: view"), "{stale}");
}

#[test]
fn bad_input_is_refused_and_nothing_is_written() {
    let run = Run::new();
    let out = run.path("bad.html");
    let refuse = |cmd: &mut assert_cmd::Command, says: &[&str]| {
        let o = cmd.output().unwrap();
        assert!(!o.status.success(), "{says:?} succeeded");
        let stderr = String::from_utf8_lossy(&o.stderr)
            .replace('│', " ")
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        for s in says {
            assert!(stderr.contains(s), "expected {s:?} in:\n{stderr}");
        }
        assert!(!out.exists(), "{says:?}: a report was written");
        assert!(
            std::fs::read_dir(run.dir.path()).unwrap().all(|e| !e
                .unwrap()
                .file_name()
                .to_string_lossy()
                .contains("bad.html")),
            "{says:?}: a partial file was left"
        );
    };

    // No image at all.
    refuse(
        bin("irsig-report").args(["--lut", &run.arg("lut.txt")]),
        &["<TRUTH|--radiance"],
    );
    // A missing file.
    refuse(
        &mut run.report(&out, &[("--lut", &run.arg("no-such.lut"))]),
        &["no-such.lut"],
    );
    // Images of two sizes: a 120 × 90 radiance image against the 60 × 45 truth.
    std::fs::write(run.path("view2.ron"), VIEW.replace("(60, 45)", "(120, 90)")).unwrap();
    bin("irsig-trace")
        .arg("--scene")
        .arg(run.path("scene.raw"))
        .arg("--materials")
        .arg(run.path(MATERIALS))
        .arg("--view")
        .arg(run.path("view2.ron"))
        .args(["--atmosphere", "us-std-1976", "--no-dc", "-o"])
        .arg(run.path("big"))
        .assert()
        .success();
    refuse(
        bin("irsig-report")
            .arg(run.path("frame.truth.exr"))
            .args(["--radiance", &run.arg("big.radiance.exr"), "-o"])
            .arg(&out),
        &["big.radiance.exr", "120 x 90", "60 x 45", "same size"],
    );
    // A decision file that does not parse: its line and column.
    let text = std::fs::read_to_string(run.path("frame.decision.ron")).unwrap();
    let broken = text.replacen("percentile:", "percentil:", 1);
    std::fs::write(run.path("broken.decision.ron"), &broken).unwrap();
    let offset = broken.find("percentil:").unwrap();
    let line = broken[..offset].matches('\n').count() + 1;
    let column = offset - broken[..offset].rfind('\n').map_or(0, |i| i + 1) + 1;
    refuse(
        &mut run.report(&out, &[("--decision", &run.arg("broken.decision.ron"))]),
        &[&format!("broken.decision.ron:{line}:{column}")],
    );
    // A LUT row that is not one: its line and column.
    std::fs::write(run.path("bad.lut"), "# dc r t c\n0 1 2 3\n1 1 x 3\n").unwrap();
    refuse(
        &mut run.report(&out, &[("--lut", &run.arg("bad.lut"))]),
        &["bad.lut:3:5", "temperature in K"],
    );
    // A profile that leaves the image.
    refuse(
        &mut run.report(&out, &[("--profile", "0,0:60,10")]),
        &["--profile 0,0:60,10", "outside the image", "60 x 45"],
    );
    // Uncertainties other than those the truth EXR was traced with: both files' hashes.
    std::fs::write(run.path("u2.ron"), UNCERTAINTIES.replace("0.5", "0.25")).unwrap();
    refuse(
        &mut run.report(&out, &[("--uncertainties", &run.arg("u2.ron"))]),
        &[
            "u2.ron",
            &sha256sum(&run.path("u2.ron")),
            &sha256sum(&run.path("u.ron")),
        ],
    );
    // Not a PNG as the colour preview.
    refuse(
        &mut run.report(&out, &[("--colour-preview", &run.arg("lut.txt"))]),
        &["lut.txt", "PNG"],
    );
    // An unwritable output.
    let nowhere = run.path("no-such-dir/report.html");
    let o = run.report(&nowhere, &[]).output().unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("no-such-dir/report.html"));
    assert!(!nowhere.exists());
    // And a report that was there stays as it was when a later run fails.
    std::fs::write(&out, "earlier").unwrap();
    let o = run
        .report(&out, &[("--profile", "0,0:99,0")])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "earlier");
}

#[test]
fn a_region_outside_the_image_is_named_at_its_line() {
    let run = Run::new();
    std::fs::write(
        run.path("far.ron"),
        "(references: [],\n regions: [\n  (name: \"far\", material: None, pixels: \
         Some((columns: (0, 99), rows: (0, 1))), references: []),\n ])",
    )
    .unwrap();
    let out = run.path("far.html");
    bin("irsig-report")
        .arg(run.path("frame.truth.exr"))
        .args(["--regions", &run.arg("far.ron"), "-o"])
        .arg(&out)
        .assert()
        .failure()
        .stderr(predicate::str::contains("far.ron:3:").and(predicate::str::contains("beyond")));
    assert!(!out.exists());
}
