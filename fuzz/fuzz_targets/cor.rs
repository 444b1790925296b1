#![no_main]
//! Fuzzes `irsig_formats::legacy::cor`.

#[path = "common.rs"]
mod common;

use irsig_formats::legacy::cor;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::check(data, cor::parse, cor::write));
