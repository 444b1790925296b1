#![no_main]
//! Fuzzes `irsig_formats::legacy::scene`.

#[path = "common.rs"]
mod common;

use irsig_formats::legacy::scene;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::check(data, scene::parse, scene::write));
