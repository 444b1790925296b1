#![no_main]
//! Fuzzes `irsig_formats::legacy::material_index`.

#[path = "common.rs"]
mod common;

use irsig_formats::legacy::material_index;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::check(data, material_index::parse, material_index::write));
