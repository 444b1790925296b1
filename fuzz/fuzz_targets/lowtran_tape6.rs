#![no_main]
//! Fuzzes `irsig_formats::radtran::lowtran_tape6`: no panic, errors inside the input.

#[path = "radtran_common.rs"]
mod common;

use irsig_formats::radtran::lowtran_tape6;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = common::check(data, lowtran_tape6::parse);
});
