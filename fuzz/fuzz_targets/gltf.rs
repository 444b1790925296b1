#![no_main]
//! Fuzzes `irsig_formats::mesh::read_gltf` on glTF JSON and GLB bytes (the content tells
//! which). No base directory: only `data:` URIs can resolve, and nothing is ever fetched.

#[path = "mesh_common.rs"]
#[allow(dead_code)] // each target uses only some of the checks
mod mesh_common;

use irsig_formats::mesh::read_gltf;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    match read_gltf("fuzz.glb", data, None) {
        Ok(mesh) => mesh_common::check_mesh(&mesh),
        Err(e) => mesh_common::check_error(&e, "fuzz.glb", data),
    }
});
