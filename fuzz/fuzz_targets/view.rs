#![no_main]
//! Fuzzes `irsig_formats::legacy::view`.

#[path = "common.rs"]
mod common;

use irsig_formats::legacy::view;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::check(data, view::parse, view::write));
