#![no_main]
//! Fuzzes `irsig_formats::legacy::rtt`.

#[path = "common.rs"]
mod common;

use irsig_formats::legacy::rtt;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| common::check(data, rtt::parse, rtt::write));
