#![no_main]
//! Fuzzes `irsig_formats::legacy::ems`.

#[path = "common.rs"]
mod common;

use irsig_formats::legacy::ems;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::check(data, ems::parse, ems::write));
