#![no_main]
//! Fuzzes `irsig_formats::srf` (sensor response files): no panic, errors inside the input,
//! and an accepted table keeps the format's rules (at least two samples, wavelengths
//! positive and strictly increasing, responses finite and not negative, not all 0).

#[path = "radtran_common.rs"]
mod common;

use irsig_formats::srf;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some(t) = common::check(data, srf::parse) {
        assert!(t.wavelength_um.len() >= 2);
        assert_eq!(t.wavelength_um.len(), t.response.len());
        assert!(t.wavelength_um[0] > 0.0);
        assert!(t.wavelength_um.windows(2).all(|w| w[0] < w[1]));
        assert!(t.response.iter().all(|r| r.is_finite() && *r >= 0.0));
        assert!(t.response.iter().any(|r| *r > 0.0));
    }
});
