#![no_main]
//! Fuzzes `irsig_formats::weather` (EPW and the weather CSV): no panic, errors inside the
//! input, and every accepted record passes its own rules and can be asked for its first
//! and last moment.

#[path = "radtran_common.rs"]
mod common;

use irsig_formats::weather::{self, Options};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    for options in [Options::default(), Options { year: Some(2019) }] {
        let read = |file: &str, text: &str| weather::read(file, text.as_bytes(), &options);
        if let Some(w) = common::check(data, read) {
            assert!(w.validate().is_ok());
            let (first, last) = w.span_s().expect("two records at least");
            assert!(w.at(first).is_ok() && w.at(last).is_ok());
            assert!(w.at(last + 1.0).is_err());
        }
    }
});
