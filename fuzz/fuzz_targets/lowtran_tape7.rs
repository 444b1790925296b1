#![no_main]
//! Fuzzes `irsig_formats::radtran::lowtran_tape7`: no panic, errors inside the input.

#[path = "radtran_common.rs"]
mod common;

use irsig_formats::radtran::lowtran_tape7;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = common::check(data, lowtran_tape7::parse);
});
