#![no_main]
//! Fuzzes `irsig_formats::canonical::read_raw_scene`, mostly on the binary form
//! (`IRSIGRAW`; the seed corpus is binary, and bytes without the magic go to the RON
//! reader). A scene that reads encodes back to bytes that read to the same scene.

#[path = "mesh_common.rs"]
#[allow(dead_code)] // each target uses only some of the checks
mod mesh_common;

use irsig_formats::canonical::{binary, read_raw_scene};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    match read_raw_scene("fuzz.raw", data) {
        Ok(scene) => {
            let bytes = binary::encode(&scene).expect("a read scene encodes");
            let again = read_raw_scene("rewritten.raw", &bytes).expect("its encoding reads");
            assert_eq!(binary::encode(&again).expect("encodes again"), bytes);
            if binary::is_binary(data) {
                assert_eq!(bytes, data, "binary decode and encode are inverse");
            }
        }
        Err(e) => mesh_common::check_error(&e, "fuzz.raw", data),
    }
});
