#![no_main]
//! Fuzzes `irsig_formats::mesh::read_obj`, with an MTL file beside it: the input is the OBJ
//! text, optionally followed by a NUL byte and the bytes of `m.mtl`, which the OBJ may name
//! with `mtllib m.mtl` (the seed corpus does).

#[path = "mesh_common.rs"]
#[allow(dead_code)] // each target uses only some of the checks
mod mesh_common;

use std::path::PathBuf;
use std::sync::LazyLock;

use irsig_formats::mesh::read_obj;
use libfuzzer_sys::fuzz_target;

static DIR: LazyLock<PathBuf> = LazyLock::new(|| {
    let dir = std::env::temp_dir().join(format!("irsig-fuzz-obj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch directory for m.mtl");
    dir
});

fuzz_target!(|data: &[u8]| {
    let (obj, mtl) = match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], Some(&data[i + 1..])),
        None => (data, None),
    };
    let mtl_path = DIR.join("m.mtl");
    match mtl {
        Some(bytes) => std::fs::write(&mtl_path, bytes).expect("write m.mtl"),
        None => {
            let _ = std::fs::remove_file(&mtl_path);
        }
    }
    match read_obj("fuzz.obj", obj, Some(&DIR)) {
        Ok(mesh) => mesh_common::check_mesh(&mesh),
        Err(e) => mesh_common::check_error(&e, "fuzz.obj", obj),
    }
});
