#![no_main]
//! Fuzzes `irsig_formats::legacy::rsd`.

#[path = "common.rs"]
mod common;

use irsig_formats::legacy::rsd;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::check(data, rsd::parse, rsd::write));
