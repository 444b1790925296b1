#![no_main]
//! Fuzzes `irsig_formats::legacy::atm`.

#[path = "common.rs"]
mod common;

use irsig_formats::legacy::atm;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::check(data, atm::parse, atm::write));
