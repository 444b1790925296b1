#![no_main]
//! Fuzzes `irsig_formats::dirsig::mat` (DIRSIG `.mat` material sets): no panic, errors
//! inside the input, and every accepted entry's specular fraction, where given, is 0 to 1;
//! and `dirsig::therm` on every entry: no panic, and a thermal record it gives is valid.

#[path = "radtran_common.rs"]
mod common;

use irsig_formats::dirsig::{mat, therm};
use irsig_model::thermal::BackBoundary;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some(entries) = common::check(data, mat::parse) {
        for e in &entries {
            assert!(e.specular_fraction.is_none_or(|f| (0.0..=1.0).contains(&f)));
        }
        let text = irsig_formats::legacy::decode("fuzz", data).expect("decoded once already");
        for e in &entries {
            let thermal = |file: &str, text: &str| {
                therm::thermal(file, text, e, BackBoundary::Adiabatic)
            };
            if let Some(Some(t)) = common::check(text.as_bytes(), thermal) {
                assert!(t.validate("thermal").is_ok());
            }
        }
    }
});
