#![no_main]
//! Fuzzes `irsig_formats::canonical::read_object` on the binary object (`IRSIGOBJ`): the
//! file name ends in `.bin`, so every input goes to the binary decoder. An object that
//! reads encodes back to bytes that read to the same object.

#[path = "mesh_common.rs"]
#[allow(dead_code)] // each target uses only some of the checks
mod mesh_common;

use irsig_formats::canonical::{binary_object, read_object};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    match read_object("fuzz.bin", data) {
        Ok(object) => {
            let bytes = binary_object::encode(&object).expect("a read object encodes");
            let again = read_object("rewritten.bin", &bytes).expect("its encoding reads");
            assert_eq!(binary_object::encode(&again).expect("encodes again"), bytes);
        }
        Err(e) => mesh_common::check_error(&e, "fuzz.bin", data),
    }
});
