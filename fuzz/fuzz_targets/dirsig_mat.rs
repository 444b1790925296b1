#![no_main]
//! Fuzzes `irsig_formats::dirsig::mat` (DIRSIG `.mat` material sets): no panic, errors
//! inside the input, and every accepted entry's specular fraction, where given, is 0 to 1.

#[path = "radtran_common.rs"]
mod common;

use irsig_formats::dirsig::mat;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some(entries) = common::check(data, mat::parse) {
        for e in &entries {
            assert!(e.specular_fraction.is_none_or(|f| (0.0..=1.0).contains(&f)));
        }
    }
});
