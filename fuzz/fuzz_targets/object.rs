#![no_main]
//! Fuzzes `irsig_formats::legacy::object`.

#[path = "common.rs"]
mod common;

use irsig_formats::legacy::object;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::check(data, object::parse, object::write));
