#![no_main]
//! Fuzzes `irsig_formats::nk` (complex refractive index tables): no panic, errors inside
//! the input, and an accepted table keeps the format's rules (at least two rows,
//! wavelengths positive and strictly increasing, n finite and above 0, k finite and not
//! negative).

#[path = "radtran_common.rs"]
mod common;

use irsig_formats::nk;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some(t) = common::check(data, nk::parse) {
        assert!(t.wavelength_um.len() >= 2);
        assert_eq!(t.wavelength_um.len(), t.n.len());
        assert_eq!(t.wavelength_um.len(), t.k.len());
        assert!(t.wavelength_um[0] > 0.0);
        assert!(t.wavelength_um.windows(2).all(|w| w[0] < w[1]));
        assert!(t.n.iter().all(|n| n.is_finite() && *n > 0.0));
        assert!(t.k.iter().all(|k| k.is_finite() && *k >= 0.0));
    }
});
