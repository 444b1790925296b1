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
    std::fs::write(dir.join("panel.obj"), OBJ).unwrap();
    std::fs::write(dir.join("panel.mtl"), mtl).unwrap();
    import_and_flatten_as(dir, "panel.obj", &[], materials);
}

/// [`import_and_flatten`] for the panel as a GLB (`dir/panel.glb`) whose material's base
/// colour is `png`, stored in the GLB's binary chunk, imported with `--images dir/images`.
/// In glTF's axes (+Y up) the panel lies on `y = 0` at `(x, 0, −y)`, which the import
/// turns to irsig's `(x, y, 0)`; its coordinates `(x/8, 1 − y/8)`, glTF's `v` running down.
pub fn import_and_flatten_glb(dir: &Path, png: &[u8], materials: &str) {
    std::fs::write(dir.join("panel.glb"), panel_glb(png)).unwrap();
    let images = dir.join("images");
    import_and_flatten_as(
        dir,
        "panel.glb",
        &["--images".as_ref(), images.as_os_str()],
        materials,
    );
}

/// Writes the scene, the view and `materials` into `dir`, imports `dir/model` (with
/// `import_flags`) as `panel.ron` and flattens the scene into `dir/scene.raw`.
fn import_and_flatten_as(
    dir: &Path,
    model: &str,
    import_flags: &[&std::ffi::OsStr],
    materials: &str,
) {
    let p = |name: &str| dir.join(name);
    std::fs::write(p("materials.ron"), materials).unwrap();
    std::fs::write(p("scene.ron"), SCENE).unwrap();
    std::fs::write(p("view.ron"), ron::to_string(&view()).unwrap()).unwrap();
    bin("irsig-import")
        .arg(p(model))
        .arg("--materials")
        .arg(p("materials.ron"))
        .args(import_flags)
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

/// The panel as GLB bytes (glTF 2.0 §4.4): a JSON chunk and a binary chunk of positions,
/// texture coordinates, indices and the PNG, each 4-byte aligned.
fn panel_glb(png: &[u8]) -> Vec<u8> {
    let s = SIDE_M as f32;
    let mut bin: Vec<u8> = Vec::new();
    for v in [0.0, 0.0, 0.0, s, 0.0, 0.0, s, 0.0, -s, 0.0, 0.0, -s] {
        bin.extend_from_slice(&f32::to_le_bytes(v));
    }
    for v in [0.0f32, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0] {
        bin.extend_from_slice(&v.to_le_bytes());
    }
    for i in [0u16, 1, 2, 0, 2, 3] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let image_at = bin.len() + (4 - bin.len() % 4) % 4;
    bin.resize(image_at, 0);
    bin.extend_from_slice(png);
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":{total}}}],
        "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},
                       {{"buffer":0,"byteOffset":48,"byteLength":32}},
                       {{"buffer":0,"byteOffset":80,"byteLength":12}},
                       {{"buffer":0,"byteOffset":{image_at},"byteLength":{n}}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,{neg}],"max":[{s},0,0]}},
                     {{"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"}},
                     {{"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}}],
        "images":[{{"bufferView":3,"mimeType":"image/png","name":"quarters.png"}}],
        "textures":[{{"source":0}}],
        "materials":[{{"name":"panel","pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":1}},"indices":2,"material":0}}]}}],
        "nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0}}"#,
        total = image_at + png.len(),
        n = png.len(),
        neg = -s,
    );
    let mut json = json.into_bytes();
    json.resize(json.len().next_multiple_of(4), b' ');
    bin.resize(bin.len().next_multiple_of(4), 0);
    let chunk_len = |c: &[u8]| u32::try_from(c.len()).unwrap().to_le_bytes();
    let mut glb = Vec::new();
    glb.extend_from_slice(b"glTF");
    glb.extend_from_slice(&2u32.to_le_bytes());
    glb.extend_from_slice(
        &u32::try_from(12 + 8 + json.len() + 8 + bin.len())
            .unwrap()
            .to_le_bytes(),
    );
    glb.extend_from_slice(&chunk_len(&json));
    glb.extend_from_slice(b"JSON");
    glb.extend_from_slice(&json);
    glb.extend_from_slice(&chunk_len(&bin));
    glb.extend_from_slice(b"BIN\0");
    glb.extend_from_slice(&bin);
    glb
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
