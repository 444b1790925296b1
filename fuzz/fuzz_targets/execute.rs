#![no_main]
//! Fuzzes `irsig_formats::legacy::execute`.

#[path = "common.rs"]
mod common;

use irsig_formats::legacy::execute;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::check(data, execute::parse, execute::write));
