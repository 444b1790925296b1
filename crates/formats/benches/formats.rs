//! Parse and write throughput at a million triangles: parse-and-flatten for every form an
//! object reaches `irsig-flatten` in (OBJ, GLB, legacy facet file, canonical object as RON
//! and as binary; the 2 s floor is OBJ's), the object's own write and read in
//! both forms, and the raw scene as RON and as binary.
//!
//! Inputs are generated here (a UV sphere of exactly 1,000,000 triangles), never committed.

use std::sync::LazyLock;

use divan::Bencher;
use divan::counter::{BytesCount, ItemsCount};
use irsig_formats::canonical;
use irsig_formats::mesh::{read_gltf, read_obj};
use irsig_model::{Facet, MaterialId, Object, Placement, RawScene, Scene};

fn main() {
    divan::main();
}

const TRIANGLES: usize = 1_000_000;

static SPHERE: LazyLock<Object> = LazyLock::new(|| {
    let s = irsig_scene::uv_sphere(10.0, 1000, 501, MaterialId(1));
    assert_eq!(s.facets.len(), TRIANGLES);
    s
});

static OBJ: LazyLock<Vec<u8>> = LazyLock::new(|| {
    use std::fmt::Write as _;
    let mut text = String::from("o sphere\nusemtl concrete\n");
    for p in &SPHERE.positions_m {
        let _ = writeln!(text, "v {:.6} {:.6} {:.6}", p[0], p[1], p[2]);
    }
    for f in &SPHERE.facets {
        let [a, b, c] = f.vertices.map(|v| v + 1);
        let _ = writeln!(text, "f {a} {b} {c}");
    }
    text.into_bytes()
});

static GLB: LazyLock<Vec<u8>> = LazyLock::new(|| {
    let mut bin: Vec<u8> = Vec::new();
    for p in &SPHERE.positions_m {
        for c in p {
            #[allow(clippy::cast_possible_truncation)]
            bin.extend_from_slice(&(*c as f32).to_le_bytes());
        }
    }
    let positions_len = bin.len();
    for f in &SPHERE.facets {
        for v in f.vertices {
            bin.extend_from_slice(&v.to_le_bytes());
        }
    }
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":{}}}],"bufferViews":[{{"buffer":0,"byteLength":{positions_len}}},{{"buffer":0,"byteOffset":{positions_len},"byteLength":{}}}],"accessors":[{{"bufferView":0,"componentType":5126,"count":{},"type":"VEC3","min":[-10,-10,-10],"max":[10,10,10]}},{{"bufferView":1,"componentType":5125,"count":{},"type":"SCALAR"}}],"materials":[{{"name":"concrete"}}],"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1,"material":0}}]}}],"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0}}"#,
        bin.len(),
        bin.len() - positions_len,
        SPHERE.positions_m.len(),
        3 * SPHERE.facets.len()
    );
    let mut json = json.into_bytes();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut glb = Vec::with_capacity(total);
    glb.extend_from_slice(b"glTF");
    glb.extend_from_slice(&2u32.to_le_bytes());
    glb.extend_from_slice(&u32::try_from(total).unwrap().to_le_bytes());
    glb.extend_from_slice(&u32::try_from(json.len()).unwrap().to_le_bytes());
    glb.extend_from_slice(b"JSON");
    glb.extend_from_slice(&json);
    glb.extend_from_slice(&u32::try_from(bin.len()).unwrap().to_le_bytes());
    glb.extend_from_slice(b"BIN\0");
    glb.extend_from_slice(&bin);
    glb
});

/// The sphere as a legacy facet file (metres, material index 1, 6 decimals as the 1990
/// files have).
static FAC: LazyLock<Vec<u8>> = LazyLock::new(|| {
    use irsig_formats::legacy::object::{LegacyFacet, ObjectFile, write};
    let round = |c: f64| (c * 1e6).round() / 1e6;
    let file = ObjectFile {
        facets: SPHERE
            .facets
            .iter()
            .map(|f| LegacyFacet {
                material_index: 1,
                temperature_k: None,
                vertices: f
                    .vertices
                    .map(|v| SPHERE.positions_m[v as usize].map(round)),
                fourth_vertex: None,
                position: Default::default(),
            })
            .collect(),
        count_position: Default::default(),
    };
    write(&file).unwrap().into_bytes()
});

static OBJECT_RON: LazyLock<String> = LazyLock::new(|| canonical::to_ron(&*SPHERE).unwrap());
static OBJECT_BIN: LazyLock<Vec<u8>> =
    LazyLock::new(|| canonical::binary_object::encode(&SPHERE).unwrap());

fn scene() -> Scene {
    Scene {
        objects: vec![Placement {
            object: "sphere.ron".into(),
            rotation_deg: [10.0, 20.0, 30.0],
            translation_m: [100.0, 0.0, 5.0],
            scale: [1.0, 1.0, 1.0],
            temperature_k: Some(300.0),
            overrides: vec![],
        }],
        ..Scene::default()
    }
}

/// What `irsig-import` does after parsing: names to ids (one material here), then checks.
fn to_object(mesh: &irsig_formats::mesh::Mesh) -> Object {
    let object = Object {
        name: "sphere".into(),
        source: String::new(),
        positions_m: mesh.positions.clone(),
        facets: mesh
            .triangles
            .iter()
            .map(|t| Facet {
                vertices: t.vertices,
                material: MaterialId(1),
                temperature_k: None,
                uv: None,
            })
            .collect(),
    };
    object.validate().unwrap();
    object
}

static RAW: LazyLock<RawScene> =
    LazyLock::new(|| irsig_scene::flatten(&scene(), &[&SPHERE]).unwrap());
static RAW_RON: LazyLock<String> = LazyLock::new(|| canonical::to_ron(&*RAW).unwrap());
static RAW_BIN: LazyLock<Vec<u8>> = LazyLock::new(|| canonical::binary::encode(&RAW).unwrap());

#[divan::bench(sample_count = 3, sample_size = 1)]
fn obj_parse(b: Bencher) {
    b.counter(BytesCount::new(OBJ.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| read_obj("s.obj", &OBJ, None).unwrap().triangles.len());
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn obj_import_and_flatten(b: Bencher) {
    b.counter(BytesCount::new(OBJ.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| {
            let object = to_object(&read_obj("s.obj", &OBJ, None).unwrap());
            irsig_scene::flatten(&scene(), &[&object])
                .unwrap()
                .facets
                .len()
        });
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn glb_import_and_flatten(b: Bencher) {
    b.counter(BytesCount::new(GLB.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| {
            let object = to_object(&read_gltf("s.glb", &GLB, None).unwrap());
            irsig_scene::flatten(&scene(), &[&object])
                .unwrap()
                .facets
                .len()
        });
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn raw_ron_write(b: Bencher) {
    b.counter(BytesCount::new(RAW_RON.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| canonical::to_ron(&*RAW).unwrap().len());
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn raw_ron_read(b: Bencher) {
    b.counter(BytesCount::new(RAW_RON.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| {
            canonical::read_raw_scene("s.ron", RAW_RON.as_bytes())
                .unwrap()
                .facets
                .len()
        });
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn raw_binary_write(b: Bencher) {
    b.counter(BytesCount::new(RAW_BIN.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| canonical::binary::encode(&RAW).unwrap().len());
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn raw_binary_read(b: Bencher) {
    b.counter(BytesCount::new(RAW_BIN.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| {
            canonical::read_raw_scene("s.bin", &RAW_BIN)
                .unwrap()
                .facets
                .len()
        });
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn fac_import_and_flatten(b: Bencher) {
    b.counter(BytesCount::new(FAC.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| {
            let mesh = irsig_formats::mesh::read_legacy_object("s.fac", &FAC).unwrap();
            let object = to_object(&mesh);
            irsig_scene::flatten(&scene(), &[&object])
                .unwrap()
                .facets
                .len()
        });
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn object_ron_write(b: Bencher) {
    b.counter(BytesCount::new(OBJECT_RON.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| canonical::to_ron(&*SPHERE).unwrap().len());
}

/// What `irsig-flatten` does with a RON object: read, validate, flatten.
#[divan::bench(sample_count = 3, sample_size = 1)]
fn object_ron_read_and_flatten(b: Bencher) {
    b.counter(BytesCount::new(OBJECT_RON.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| {
            let object = canonical::read_object("s.ron", OBJECT_RON.as_bytes()).unwrap();
            irsig_scene::flatten(&scene(), &[&object])
                .unwrap()
                .facets
                .len()
        });
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn object_binary_write(b: Bencher) {
    b.counter(BytesCount::new(OBJECT_BIN.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| canonical::binary_object::encode(&SPHERE).unwrap().len());
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn object_binary_read(b: Bencher) {
    b.counter(BytesCount::new(OBJECT_BIN.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| {
            canonical::read_object("s.bin", &OBJECT_BIN)
                .unwrap()
                .facets
                .len()
        });
}

/// What `irsig-flatten` does with a binary object: read, validate, flatten.
#[divan::bench(sample_count = 5, sample_size = 1)]
fn object_binary_read_and_flatten(b: Bencher) {
    b.counter(BytesCount::new(OBJECT_BIN.len()))
        .counter(ItemsCount::new(TRIANGLES))
        .bench(|| {
            let object = canonical::read_object("s.bin", &OBJECT_BIN).unwrap();
            irsig_scene::flatten(&scene(), &[&object])
                .unwrap()
                .facets
                .len()
        });
}
