//! The quickstart pipeline (`pipelines/quickstart.ron`, the README's first command) end to
//! end, run in full as shipped (512 × 384) on a copy of `pipelines/`:
//!
//! - `irsig-run` writes every output, and the sensor image holds the physics: the warm
//!   panel's apparent temperature matches a hand computation from the LOWTRAN7 tables to
//!   0.02 K, the sky above the horizon matches the sky table to 0.02 K and is colder than
//!   the ground,
//!   and the pool reflecting the panel is warmer than the pool reflecting the sky;
//! - the runner, the Makefile it emits (`make -j2`) and a hand-written Unix pipe of the
//!   same tools give byte-identical files;
//! - a broken quickstart file fails at its line and column and writes nothing;
//! - the README's picture (`docs/quickstart.png`, made by
//!   `scripts/docs/quickstart-picture.sh`) is the colour preview the quickstart makes now,
//!   and its caption's range of apparent temperature is the image's;
//! - `pipelines/quickstart.sh` says it is building before cargo starts, and shows cargo's
//!   progress only when standard error is a terminal (a stand-in `cargo` records how it
//!   was called, so nothing is built).

// Material ids, table nodes and kinetic temperatures are exact values stored as floats.
#![allow(clippy::float_cmp)]

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use irsig_model::{MaterialLibrary, SlantTables};
use irsig_radiometry::Band;
use irsig_raster::Raster;
use irsig_tests::{bin, bin_path, repo_root};

/// Every file the quickstart writes, under `out/quickstart/`.
const OUTPUTS: [&str; 11] = [
    "scene.raw",
    "radiance.exr",
    "truth.exr",
    "map.png",
    "sensor.exr",
    "temperature.exr",
    "dc.png",
    "lut.txt",
    "preview.png",
    "colour.png",
    "report.html",
];

/// A copy of `pipelines/quickstart.ron` and `pipelines/quickstart/` in `<tmp>/pipelines/`,
/// so that its outputs go to `<tmp>/out/quickstart/` and tests do not share files.
struct Copy {
    dir: tempfile::TempDir,
}

impl Copy {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        let from = repo_root().join("pipelines");
        let to = dir.path().join("pipelines");
        std::fs::create_dir_all(to.join("quickstart")).unwrap();
        std::fs::copy(from.join("quickstart.ron"), to.join("quickstart.ron")).unwrap();
        for entry in std::fs::read_dir(from.join("quickstart")).unwrap() {
            let path = entry.unwrap().path();
            std::fs::copy(&path, to.join("quickstart").join(path.file_name().unwrap())).unwrap();
        }
        Self { dir }
    }

    fn pipelines(&self) -> PathBuf {
        self.dir.path().join("pipelines")
    }

    fn out(&self, name: &str) -> PathBuf {
        self.dir.path().join("out/quickstart").join(name)
    }

    fn read(&self, name: &str) -> Vec<u8> {
        std::fs::read(self.out(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
    }

    fn exr(&self, name: &str) -> Raster {
        irsig_raster::read_exr(&self.read(name)).unwrap()
    }

    fn run(&self, args: &[&str]) -> assert_cmd::assert::Assert {
        let mut cmd = bin("irsig-run");
        cmd.current_dir(self.dir.path())
            .args(args)
            .arg("pipelines/quickstart.ron");
        cmd.assert()
    }

    /// A shell command run in `pipelines/` with the tools on `PATH`.
    fn sh(&self, script: &str) {
        let status = Command::new("sh")
            .arg("-c")
            .arg(script)
            .current_dir(self.pipelines())
            .env("PATH", path_with_tools())
            .status()
            .unwrap();
        assert!(status.success(), "`{script}` failed");
    }
}

fn path_with_tools() -> std::ffi::OsString {
    let dir = bin_path("irsig-run").parent().unwrap().to_path_buf();
    let mut paths = vec![dir];
    paths.extend(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    ));
    std::env::join_paths(paths).unwrap()
}

/// The quickstart run once by `irsig-run`, shared by the tests that read its outputs.
fn by_runner() -> &'static Copy {
    static RUN: OnceLock<Copy> = OnceLock::new();
    RUN.get_or_init(|| {
        let copy = Copy::new();
        copy.run(&[]).success();
        copy
    })
}

/// The quickstart camera, as `pipelines/quickstart/view.ron` gives it, projected here
/// independently of the tracer: a pinhole whose pixel (c, r) looks along
/// `f + u·right + v·up` with `u = (2(c + ½)/W − 1)·tan(fov_x/2)`,
/// `v = (1 − 2(r + ½)/H)·tan(fov_y/2)` (docs of `formats/canonical/view.md`).
struct Camera {
    eye: [f64; 3],
    forward: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    tan_half: [f64; 2],
    pixels: [usize; 2],
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

impl Camera {
    fn quickstart() -> Self {
        let text =
            std::fs::read_to_string(repo_root().join("pipelines/quickstart/view.ron")).unwrap();
        let irsig_model::View::LookAt {
            position_m,
            target_m,
            pixels,
            fov_deg,
            ..
        } = ron::from_str(&text).unwrap()
        else {
            panic!("the quickstart view is a LookAt view");
        };
        let forward = unit(sub(target_m, position_m));
        let right = unit(cross(forward, [0.0, 0.0, 1.0]));
        let up = cross(right, forward);
        Self {
            eye: position_m,
            forward,
            right,
            up,
            tan_half: [
                (fov_deg[0].to_radians() / 2.0).tan(),
                (fov_deg[1].to_radians() / 2.0).tan(),
            ],
            pixels: [pixels[0] as usize, pixels[1] as usize],
        }
    }

    /// The pixel (column, row) whose footprint holds the world point `p`.
    fn pixel_of(&self, p: [f64; 3]) -> (usize, usize) {
        let d = sub(p, self.eye);
        let z = dot(d, self.forward);
        let u = dot(d, self.right) / z / self.tan_half[0];
        let v = dot(d, self.up) / z / self.tan_half[1];
        let col = (u + 1.0) / 2.0 * self.pixels[0] as f64;
        let row = (1.0 - v) / 2.0 * self.pixels[1] as f64;
        (col.floor() as usize, row.floor() as usize)
    }

    /// The unit direction of pixel (column, row)'s centre ray.
    fn direction(&self, col: usize, row: usize) -> [f64; 3] {
        let u = (2.0 * (col as f64 + 0.5) / self.pixels[0] as f64 - 1.0) * self.tan_half[0];
        let v = (1.0 - 2.0 * (row as f64 + 0.5) / self.pixels[1] as f64) * self.tan_half[1];
        unit([
            self.forward[0] + u * self.right[0] + v * self.up[0],
            self.forward[1] + u * self.right[1] + v * self.up[1],
            self.forward[2] + u * self.right[2] + v * self.up[2],
        ])
    }
}

/// Sample (column, row) of a layer.
fn at(r: &Raster, layer: &str, (col, row): (usize, usize)) -> f64 {
    let l = r.layer(layer).unwrap_or_else(|| panic!("no layer {layer}"));
    f64::from(l.data[row * r.width + col])
}

/// Reads a built-in atmosphere table file shipped in the repository (the LOWTRAN7 runs the
/// tracer's `table` model is built from).
fn lowtran(name: &str) -> String {
    std::fs::read_to_string(
        repo_root()
            .join("crates/atmosphere/data/lowtran/us-std-1976")
            .join(name),
    )
    .unwrap()
}

/// Linear interpolation in a table of increasing `x`.
fn interpolate(x: &[f64], y: &[f64], at: f64) -> f64 {
    let i = x.partition_point(|&v| v <= at).clamp(1, x.len() - 1);
    let f = (at - x[i - 1]) / (x[i] - x[i - 1]);
    y[i - 1] + f * (y[i] - y[i - 1])
}

fn sky_interpolate(x: &[f64], y: &[f64], at: f64) -> f64 {
    // The sky table between its angles as docs/accuracy.md states it: a monotone cubic
    // Hermite curve (Fritsch–Carlson), each inner node's slope the weighted harmonic mean
    // of its two secants (0 where they differ in sign), the end nodes' their secant.
    let i = x.partition_point(|&v| v <= at).clamp(1, x.len() - 1);
    let secant = |k: usize| (y[k + 1] - y[k]) / (x[k + 1] - x[k]);
    let slope = |k: usize| {
        if k == 0 || k == x.len() - 1 {
            return secant(k.min(x.len() - 2));
        }
        let (d0, d1) = (secant(k - 1), secant(k));
        if d0 * d1 <= 0.0 {
            return 0.0;
        }
        let (h0, h1) = (x[k] - x[k - 1], x[k + 1] - x[k]);
        (3.0 * h0 + 3.0 * h1) / ((2.0 * h1 + h0) / d0 + (h1 + 2.0 * h0) / d1)
    };
    let h = x[i] - x[i - 1];
    let t = (at - x[i - 1]) / h;
    let (t2, t3) = (t * t, t * t * t);
    (2.0 * t3 - 3.0 * t2 + 1.0) * y[i - 1]
        + (t3 - 2.0 * t2 + t) * h * slope(i - 1)
        + (-2.0 * t3 + 3.0 * t2) * y[i]
        + (t3 - t2) * h * slope(i)
}

#[test]
fn the_quickstart_writes_every_output() {
    let run = by_runner();
    for name in OUTPUTS {
        assert!(
            run.out(name).metadata().unwrap().len() > 0,
            "{name} is empty"
        );
    }
    let sensor = run.exr("sensor.exr");
    assert_eq!((sensor.width, sensor.height), (512, 384));
    let radiance = &sensor.layer("radiance").unwrap().data;
    assert!(radiance.iter().all(|l| l.is_finite() && *l > 0.0));
    // The LUT has one line per 8-bit count (and perhaps a header).
    let lut = String::from_utf8(run.read("lut.txt")).unwrap();
    assert!(lut.lines().count() >= 256, "{lut}");
    // Every material of the library is in the picture (interaction map ids 1-5).
    let truth = run.exr("truth.exr");
    let ids = &truth.layer("material_primary").unwrap().data;
    for id in 1..=5 {
        assert!(ids.contains(&(id as f32)), "material {id} not seen");
    }
    // A second run has nothing to do.
    run.run(&[])
        .success()
        .stderr(predicates::str::contains("0 stage(s) ran, 4 up to date"));
}

/// The warm panel's apparent temperature, by hand, against the sensor image.
///
/// The camera (view.ron) is 5 m up, and the line of sight to the panel's middle at 1 m
/// height runs 80° from nadir: a path that LOWTRAN7 itself was run for, the node
/// (observer 5 m, nadir 80°) of the built-in slant tables (observer down to 1 m). So τ and
/// L_u of the path are read straight from those tables, with no model in between:
///
///   L_app = τ · [ε(θ)·L_bb(T) + (1 − ε(θ))·L_d,hemi] + L_u
///
/// with T = 325 K (scene.ron), ε(θ) the matte paint's table (materials.ron) at the
/// incidence angle θ = 10° (the panel faces −y; the camera is 10° above its normal),
/// L_d,hemi the hemispheric sky radiance of the `.dwr` table (row −1: the thesis's eq. 5,
/// what a diffuse facet reflects when the sky-view factor is off, as here) and L_bb the
/// 8–14 µm band radiance (irsig_radiometry, checked against the `.rtt` table elsewhere).
/// The MTF is a 5 × 5 box: inside the panel, farther than 2 pixels from every edge, the
/// blurred radiance is the unblurred one (the region is checked to be panel).
#[test]
fn the_warm_panel_reads_its_hand_computed_temperature() {
    let band = Band::default();
    // τ and L_u of the path: LOWTRAN7, observer 5 m, nadir 80°.
    let slant: SlantTables = ron::from_str(&lowtran("us-std-1976.slant.ron")).unwrap();
    let i = slant.altitude_m.iter().position(|&h| h == 5.0).unwrap();
    let j = slant.nadir_deg.iter().position(|&a| a == 80.0).unwrap();
    let tau = slant.transmission[i][j];
    let path_radiance = slant.path_radiance_w_m2_sr[i][j];
    // L_d,hemi: the `.dwr`'s last row, `-1 L`, W cm^-2 sr^-1 → W m^-2 sr^-1.
    let dwr = lowtran("us-std-1976.dwr");
    let hemi_row: Vec<f64> = dwr
        .lines()
        .map(|l| {
            l.split_whitespace()
                .map(|v| v.parse().unwrap())
                .collect::<Vec<f64>>()
        })
        .find(|r| r[0] == -1.0)
        .unwrap();
    let sky_hemispheric = hemi_row[1] * 1e4;
    // ε(10°) from the library's table, linear between its rows.
    let library: MaterialLibrary = ron::from_str(
        &std::fs::read_to_string(repo_root().join("pipelines/quickstart/materials.ron")).unwrap(),
    )
    .unwrap();
    let paint = library
        .materials
        .iter()
        .find(|m| m.name == "matte black paint")
        .unwrap();
    let (angles, values): (Vec<f64>, Vec<f64>) = paint.emissivity.iter().copied().unzip();
    let camera = Camera::quickstart();
    let point = [0.0, 0.0, 1.0];
    let to_camera = unit(sub(camera.eye, point));
    let incidence_deg = dot(to_camera, [0.0, -1.0, 0.0]).acos().to_degrees();
    assert!((incidence_deg - 10.0).abs() < 1e-3, "{incidence_deg}");
    let nadir_deg = (-to_camera[2]).acos().to_degrees();
    assert!((180.0 - nadir_deg - 80.0).abs() < 1e-3, "{nadir_deg}");
    let eps = interpolate(&angles, &values, incidence_deg);
    let leaving = eps * band.radiance(325.0) + (1.0 - eps) * sky_hemispheric;
    let expected_k = band.temperature(tau * leaving + path_radiance);

    let run = by_runner();
    let sensor = run.exr("sensor.exr");
    let truth = run.exr("truth.exr");
    let (col, row) = camera.pixel_of(point);
    // The MTF's support (2 pixels each way) plus a margin, all on the panel's front.
    for dr in -4..=4_isize {
        for dc in -4..=4_isize {
            let p = (col.wrapping_add_signed(dc), row.wrapping_add_signed(dr));
            assert_eq!(at(&truth, "material_primary", p), 4.0, "at {p:?}");
            assert_eq!(at(&truth, "kinetic_temperature", p), 325.0, "at {p:?}");
        }
    }
    let seen_k = band.temperature(at(&sensor, "radiance", (col, row)));
    eprintln!(
        "panel: tau {tau}, L_u {path_radiance} W m^-2 sr^-1, L_d,hemi {sky_hemispheric}, \
         eps {eps}: hand {expected_k:.3} K, image {seen_k:.3} K at pixel ({col}, {row})"
    );
    // What is left between the two is the pixel centre's ray against the panel's middle:
    // 0.001° of incidence and nadir angle, a few millimetres of path (and f32 storage,
    // 1e-5 K). A τ 0.5 % off, or the zenith sky reflected in place of the hemispheric one,
    // would move the panel by 0.3 K or more.
    assert!(
        (seen_k - expected_k).abs() < 0.02,
        "panel: image {seen_k} K, hand computation {expected_k} K"
    );
    // Sanity of the hand computation itself: cooler than the panel (ε < 1 and the sky it
    // reflects is cold), warmer than the air the path runs through.
    assert!(expected_k < 325.0 && expected_k > 300.0, "{expected_k}");
}

/// The sky above the horizon: what the sky table gives for the pixel's zenith angle
/// (LOWTRAN7 from the ground up to space), warmer than space, colder than the ground.
#[test]
fn the_sky_is_warmer_than_space_and_colder_than_the_ground() {
    let band = Band::default();
    let slant: SlantTables = ron::from_str(&lowtran("us-std-1976.slant.ron")).unwrap();
    let camera = Camera::quickstart();
    let run = by_runner();
    let sensor = run.exr("sensor.exr");
    let truth = run.exr("truth.exr");
    // Row 20 of the middle column: 6° above the horizon. The ground in the same column
    // at the bottom: grass 10 m from the camera.
    let sky = (256, 20);
    let ground = (256, 380);
    assert_eq!(at(&truth, "material_primary", sky), 0.0);
    assert_eq!(at(&truth, "material_primary", ground), 1.0);
    let zenith_deg = camera.direction(sky.0, sky.1)[2].acos().to_degrees();
    assert!(zenith_deg < 85.0, "{zenith_deg}");
    // The sky table at the camera's 5 m: linear in zenith angle along the rows of the
    // ground and of the next altitude (300 m), then linear in altitude between them. Near
    // the horizon the lowest 300 m of air make much of the sky, so even 5 m of the way
    // counts (0.07 K here).
    let rows = [0, 1].map(|i| {
        sky_interpolate(
            &slant.sky_zenith_deg,
            &slant.sky_radiance_w_m2_sr[i],
            zenith_deg,
        )
    });
    let camera_m = camera.eye[2];
    let w =
        (camera_m - slant.sky_altitude_m[0]) / (slant.sky_altitude_m[1] - slant.sky_altitude_m[0]);
    let table_k = band.temperature(rows[0] + w * (rows[1] - rows[0]));
    let traced_k = band.temperature(at(&run.exr("radiance.exr"), "radiance", sky));
    let sky_k = band.temperature(at(&sensor, "radiance", sky));
    let ground_k = band.temperature(at(&sensor, "radiance", ground));
    eprintln!(
        "sky at zenith {zenith_deg:.2}°: table {table_k:.3} K, traced {traced_k:.3} K, \
         sensed {sky_k:.3} K; ground {ground_k:.2} K"
    );
    // As traced, the pixel is the table at its zenith angle and altitude: the tracer's sky
    // is the same table, precomputed on a 0.25° grid.
    assert!(
        (traced_k - table_k).abs() < 0.02,
        "sky traced {traced_k} K, table {table_k} K"
    );
    // The 5 × 5 box blur averages ±2 rows (±0.26°) of a radiance that is nearly linear in
    // angle over so little: the blurred pixel is the traced one to second order.
    assert!(
        (sky_k - traced_k).abs() < 0.02,
        "sky sensed {sky_k} K, traced {traced_k} K"
    );
    // Space is 0 W m^-2 sr^-1 in the band (2.7 K); the clear sky 6° up is far warmer,
    // from the water vapour near the ground, and far colder than the 298 K grass.
    assert!(
        sky_k > 200.0 && sky_k < ground_k - 20.0,
        "{sky_k} {ground_k}"
    );
}

/// The pool: where it mirrors the panel it reads warmer than where it mirrors the sky.
/// Two pool points at the same distance and incidence angle (74° from the normal, where
/// water reflects 19 %): (0, −5) mirrors the panel, (−4.5, −5) mirrors the sky beside it.
/// Expected difference ≈ 0.19 × (panel 61 − sky 22 W m^-2 sr^-1) ≈ 7 W m^-2 sr^-1, about
/// 9 K; asserted: more than 3 K.
#[test]
fn the_pool_mirrors_the_warm_panel() {
    let band = Band::default();
    let camera = Camera::quickstart();
    let run = by_runner();
    let sensor = run.exr("sensor.exr");
    let truth = run.exr("truth.exr");
    let panel = camera.pixel_of([0.0, -5.0, 0.0]);
    let sky = camera.pixel_of([-4.5, -5.0, 0.0]);
    for p in [panel, sky] {
        assert_eq!(at(&truth, "material_primary", p), 2.0, "water at {p:?}");
    }
    assert_eq!(
        at(&truth, "material_secondary", panel),
        4.0,
        "mirrors the panel"
    );
    assert_eq!(
        at(&truth, "material_secondary", sky),
        0.0,
        "mirrors the sky"
    );
    let panel_k = band.temperature(at(&sensor, "radiance", panel));
    let sky_k = band.temperature(at(&sensor, "radiance", sky));
    eprintln!("pool mirroring the panel {panel_k:.2} K, the sky {sky_k:.2} K");
    assert!(panel_k > sky_k + 3.0, "{panel_k} vs {sky_k}");
}

/// The same three stages by the Makefile `irsig-run --emit-makefile` writes (`make -j2`)
/// and by a Unix pipe typed by hand (the README's), against the runner: the same bytes.
#[test]
fn runner_makefile_and_pipe_give_byte_identical_outputs() {
    if Command::new("make").arg("--version").output().is_err() {
        panic!("GNU make is not installed: this test needs it (.ci/run installs it)");
    }
    let runner = by_runner();

    let by_make = Copy::new();
    let status = Command::new(bin_path("irsig-run"))
        .args(["--emit-makefile", "Makefile", "quickstart.ron"])
        .current_dir(by_make.pipelines())
        .status()
        .unwrap();
    assert!(status.success());
    by_make.sh("make -j2 -s");

    let by_pipe = Copy::new();
    by_pipe.sh("set -e
         mkdir -p ../out/quickstart
         irsig-flatten quickstart/scene.ron --materials quickstart/materials.ron \
           | tee ../out/quickstart/scene.raw \
           | irsig-trace --scene - --materials quickstart/materials.ron \
               --view quickstart/view.ron --atmosphere us-std-1976 \
               --radiance-exr ../out/quickstart/radiance.exr \
               --truth-exr ../out/quickstart/truth.exr --map-png ../out/quickstart/map.png
         irsig-sensor - --mtf box:5x5 --dc-per-kelvin 4 \
             --temperature-exr ../out/quickstart/temperature.exr \
             --dc-png ../out/quickstart/dc.png --lut ../out/quickstart/lut.txt \
             --preview ../out/quickstart/preview.png \
             --colour-preview ../out/quickstart/colour.png \
           < ../out/quickstart/radiance.exr > ../out/quickstart/sensor.exr
         irsig-report ../out/quickstart/truth.exr --radiance ../out/quickstart/sensor.exr \
             --regions quickstart/regions.ron --lut ../out/quickstart/lut.txt \
             --colour-preview ../out/quickstart/colour.png --pipeline quickstart.ron \
             --profile 256,0:256,383 -o ../out/quickstart/report.html");

    for name in OUTPUTS {
        let expected = runner.read(name);
        assert!(by_make.read(name) == expected, "make: {name} differs");
        assert!(by_pipe.read(name) == expected, "pipe: {name} differs");
    }
}

/// 1-based `file:line:column` of the first `needle` in `text`, counted here.
fn place(file: &str, text: &str, needle: &str) -> String {
    let offset = text.find(needle).unwrap();
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    format!("{file}:{line}:{column}")
}

/// Every file under `dir`, relative, sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = walk(dir)
        .into_iter()
        .map(|p| p.strip_prefix(dir).unwrap().to_path_buf())
        .collect();
    out.sort();
    out
}

fn walk(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            out.extend(walk(&path));
        } else {
            out.push(path);
        }
    }
    out
}

/// A typo in a stage's parameter (the trace's atmosphere model) is caught by that tool's
/// own parser before any stage runs: the error names the quickstart file's line and
/// column, and no output (not even the flatten stage's, which comes first) is written.
#[test]
fn a_broken_quickstart_fails_at_its_line_and_column_and_writes_nothing() {
    let copy = Copy::new();
    let path = copy.pipelines().join("quickstart.ron");
    let text = std::fs::read_to_string(&path).unwrap().replace(
        "\"atmosphere-model\": \"table\"",
        "\"atmosphere-model\": \"tabel\"",
    );
    assert!(text.contains("tabel"));
    std::fs::write(&path, &text).unwrap();
    let before = files(copy.dir.path());
    let out = copy.run(&[]).code(1).get_output().stderr.clone();
    let report = String::from_utf8_lossy(&out)
        .replace('│', " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let want = place("pipelines/quickstart.ron", &text, "\"tabel\"");
    assert!(
        report.contains(&want) && report.contains("invalid value 'tabel'"),
        "expected {want} and the invalid value in:\n{report}"
    );
    assert_eq!(
        files(copy.dir.path()),
        before,
        "a failed run left files behind"
    );
}

/// The README's picture is the quickstart's colour preview as it is made now: the same size
/// and, pixel by pixel, within 2 of 255 levels in every channel (a change a reader could
/// see, such as another scale label or a region 0.5 K off, is more). Its caption's range of
/// apparent temperature is the image's, in whole kelvin, and the asphalt road is warm to its
/// far end, as the caption says: every pixel of it reads warmer than the grass's 298 K
/// kinetic temperature less 10 K (a smooth-surface Fresnel table made its grazing end 60 K
/// colder than that).
#[test]
fn the_readme_picture_is_what_the_quickstart_makes() {
    let run = by_runner();
    let made = image::load_from_memory(&run.read("colour.png"))
        .unwrap()
        .into_rgb8();
    let committed = image::open(repo_root().join("docs/quickstart.png"))
        .unwrap()
        .into_rgb8();
    let stale = "docs/quickstart.png is stale: run `sh scripts/docs/quickstart-picture.sh` and \
                 check the README's caption";
    assert_eq!(made.dimensions(), committed.dimensions(), "{stale}");
    let worst = made
        .as_raw()
        .iter()
        .zip(committed.as_raw())
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap_or(0);
    assert!(worst <= 2, "{stale} (a channel differs by {worst} levels)");

    let readme = std::fs::read_to_string(repo_root().join("README.md")).unwrap();
    let caption = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    let start = caption
        .find("apparent temperatures from ")
        .expect("the caption gives the picture's range")
        + "apparent temperatures from ".len();
    // "261 K to 322 K:", the punctuation after the range dropped.
    let words: Vec<&str> = caption[start..]
        .split(' ')
        .map(|w| w.trim_end_matches([':', ',', '.', ';']))
        .collect();
    assert_eq!(
        (words[1], words[2], words[4]),
        ("K", "to", "K"),
        "{:?}",
        &words[..5]
    );
    let (low, high): (f64, f64) = (words[0].parse().unwrap(), words[3].parse().unwrap());
    let temperature = run.exr("temperature.exr");
    let t = &temperature.layer("apparent_temperature").unwrap().data;
    let (lo, hi) = t
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(f64::from(v)), hi.max(f64::from(v)))
        });
    assert_eq!((low, high), (lo.round(), hi.round()), "the caption's range");

    let truth = run.exr("truth.exr");
    let ids = &truth.layer("material_primary").unwrap().data;
    let coldest_road = ids
        .iter()
        .zip(t.iter())
        .filter(|(id, _)| **id == 3.0)
        .map(|(_, &k)| f64::from(k))
        .fold(f64::INFINITY, f64::min);
    assert!(
        coldest_road > 288.0,
        "the road's coldest pixel reads {coldest_road} K"
    );
}

/// `sh pipelines/quickstart.sh` with a stand-in `cargo` that takes two seconds and records
/// its arguments and whether its standard error is a terminal, and a stand-in `irsig-run`:
/// the line saying what is being built comes first, within a second; cargo is never told to
/// be quiet, with standard error a pipe (a line per crate) or a terminal (its progress bar;
/// `script` gives the script one).
#[test]
fn quickstart_sh_says_it_is_building_and_shows_progress_in_a_pipe_and_on_a_terminal() {
    use std::io::Read as _;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let stub_bin = d.join("bin");
    std::fs::create_dir_all(&stub_bin).unwrap();
    let calls = d.join("cargo-calls");
    let write_exe = |path: &Path, text: &str| {
        std::fs::write(path, text).unwrap();
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt as _;
            std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)).unwrap();
        }
    };
    write_exe(
        &stub_bin.join("cargo"),
        &format!(
            "#!/bin/sh\nif [ -t 2 ]; then t=terminal; else t=pipe; fi\n\
             echo \"$t $*\" >> '{}'\nsleep 2\n",
            calls.display()
        ),
    );
    let target = d.join("target");
    std::fs::create_dir_all(target.join("release")).unwrap();
    write_exe(
        &target.join("release/irsig-run"),
        "#!/bin/sh\necho \"irsig-run $*\"\n",
    );
    let path = {
        let mut paths = vec![stub_bin.clone()];
        paths.extend(std::env::split_paths(
            &std::env::var_os("PATH").unwrap_or_default(),
        ));
        std::env::join_paths(paths).unwrap()
    };
    let script = repo_root().join("pipelines/quickstart.sh");

    // Standard error a pipe.
    let started = Instant::now();
    let mut child = Command::new("sh")
        .arg(&script)
        .arg("--dry-run")
        .env("PATH", &path)
        .env("CARGO_TARGET_DIR", &target)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = child.stderr.take().unwrap();
    let mut first = Vec::new();
    let mut byte = [0u8; 1];
    while stderr.read(&mut byte).unwrap() == 1 && byte[0] != b'\n' {
        first.push(byte[0]);
    }
    let first_after = started.elapsed();
    let first = String::from_utf8(first).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    assert!(
        first.starts_with("quickstart: building the tools"),
        "the first line is {first:?}"
    );
    assert!(
        first_after < Duration::from_secs(1),
        "the first line came after {first_after:?}"
    );
    assert!(
        started.elapsed() >= Duration::from_secs(2),
        "cargo was not waited for"
    );
    // The README quotes that line.
    let readme = std::fs::read_to_string(repo_root().join("README.md"))
        .unwrap()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let said = first.trim_start_matches("quickstart: ");
    assert!(
        readme.contains(&format!("`{said}`")),
        "the README does not quote {said:?}"
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.contains("irsig-run --dry-run pipelines/quickstart.ron"),
        "{stdout}"
    );
    assert_eq!(
        std::fs::read_to_string(&calls).unwrap(),
        "pipe build --release --bins\n"
    );

    // Standard error a terminal: `script` runs the command on a pseudo-terminal.
    std::fs::remove_file(&calls).unwrap();
    let shown = Command::new("script")
        .args(["-q", "-e", "-c"])
        .arg(format!("sh '{}'", script.display()))
        .arg("/dev/null")
        .env("PATH", &path)
        .env("CARGO_TARGET_DIR", &target)
        .output()
        .unwrap_or_else(|e| panic!("cannot run `script` (util-linux): {e}"));
    assert!(shown.status.success(), "{shown:?}");
    assert!(String::from_utf8_lossy(&shown.stdout).contains("quickstart: building the tools"));
    assert_eq!(
        std::fs::read_to_string(&calls).unwrap(),
        "terminal build --release --bins\n"
    );
}
