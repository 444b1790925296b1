#![no_main]
//! Fuzzes `irsig_formats::radtran::tape5`: a deck that reads writes back, and the writing
//! reads to the same deck.

#[path = "radtran_common.rs"]
mod common;

use irsig_formats::radtran::tape5;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some(deck) = common::check(data, tape5::parse) {
        let written = tape5::write(&deck).expect("a deck that reads must write back");
        let back = tape5::parse("rewritten", &written)
            .unwrap_or_else(|e| panic!("writer output does not parse: {e}\n{written}"));
        assert_eq!(tape5::write(&back).unwrap(), written);
        assert_eq!(back.calculations().len(), deck.calculations().len());
    }
});
