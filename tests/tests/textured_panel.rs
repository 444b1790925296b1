//! The textured panel that the texture tests trace through the real tools: an OBJ square
//! 8 m on a side on the ground, one repetition of its image across it (texture
//! coordinates 0 to 1), its `.mtl` naming the material `panel`, at 300 K on 280 K black
//! terrain, seen from 100 m straight above. Where each pixel's centre ray meets the ground
//! is found by hand geometry, so a test can say what each pixel must show.

use std::path::Path;

use irsig_model::View;
use irsig_tests::bin;
use irsig_tracer::Camera;

/// The panel's side, m, and the sensor's height above its centre.
pub const SIDE_M: f64 = 8.0;
pub const HEIGHT_M: f64 = 100.0;
pub const PIXELS: u32 = 32;
pub const FOV_DEG: f64 = 6.0;

const OBJ: &str = "\
mtllib panel.mtl
v 0 0 0
v 8 0 0
v 8 8 0
v 0 8 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
usemtl panel
f 1/1 2/2 3/3
f 1/1 3/3 4/4
";

const SCENE: &str = "(objects: [(object: \"panel.ron\", temperature_k: Some(300.0))], \
                     terrain: (temperature_k: 280.0, emissivity: 1.0))";

pub fn view() -> View {
    View::Legacy {
        position_m: [SIDE_M / 2.0, SIDE_M / 2.0, HEIGHT_M],
        pixels: [PIXELS, PIXELS],
        omega_phi_kappa_deg: [0.0, 0.0, 0.0],
        fov_deg: [FOV_DEG, FOV_DEG],
        gain_dc_per_k: None,
    }
}

/// Writes the panel (with `mtl` as its material file), the scene, the view and
/// `materials` (the library's RON) into `dir`, then imports and flattens it into
/// `dir/scene.raw`.
pub fn import_and_flatten(dir: &Path, mtl: &str, materials: &str) {
    let p = |name: &str| dir.join(name);
    std::fs::write(p("panel.obj"), OBJ).unwrap();
    std::fs::write(p("panel.mtl"), mtl).unwrap();
    std::fs::write(p("materials.ron"), materials).unwrap();
    std::fs::write(p("scene.ron"), SCENE).unwrap();
    std::fs::write(p("view.ron"), ron::to_string(&view()).unwrap()).unwrap();
    bin("irsig-import")
        .arg(p("panel.obj"))
        .arg("--materials")
        .arg(p("materials.ron"))
        .arg("-o")
        .arg(p("panel.ron"))
        .assert()
        .success();
    bin("irsig-flatten")
        .arg(p("scene.ron"))
        .arg("--materials")
        .arg(p("materials.ron"))
        .arg("-o")
        .arg(p("scene.raw"))
        .assert()
        .success();
}

/// Traces `dir/scene.raw` in a vacuum with `extra` flags into `dir/out.*`: the truth EXR.
pub fn trace(dir: &Path, extra: &[&str]) -> irsig_raster::Raster {
    let p = |name: &str| dir.join(name);
    bin("irsig-trace")
        .arg("--scene")
        .arg(p("scene.raw"))
        .arg("--materials")
        .arg(p("materials.ron"))
        .arg("--view")
        .arg(p("view.ron"))
        .args(["--atmosphere", "none"])
        .args(extra)
        .arg("-o")
        .arg(p("out"))
        .assert()
        .success();
    irsig_raster::read_exr(&std::fs::read(p("out.truth.exr")).unwrap()).unwrap()
}

/// Every pixel's index in the frame and where its centre ray meets the ground (x, y), m.
pub fn ground_points() -> Vec<(usize, f64, f64)> {
    let camera = Camera::from_view(&view()).unwrap();
    let o = camera.position_m;
    let mut out = Vec::new();
    for row in 0..PIXELS {
        for column in 0..PIXELS {
            // The centre ray meets the ground z = 0 at o + s·d, s = −o_z/d_z.
            let d = camera.pixel_direction(column, row);
            let s = -o[2] / d[2];
            out.push((
                (row * PIXELS + column) as usize,
                o[0] + s * d[0],
                o[1] + s * d[1],
            ));
        }
    }
    out
}

/// A truth layer's values, by name.
pub fn layer<'a>(truth: &'a irsig_raster::Raster, name: &str) -> &'a [f32] {
    &truth
        .layer(name)
        .unwrap_or_else(|| panic!("no layer `{name}`"))
        .data
}
