#![no_main]
//! Fuzzes `irsig_formats::legacy::dwr`.

#[path = "common.rs"]
mod common;

use irsig_formats::legacy::dwr;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::check(data, dwr::parse, dwr::write));
