#![no_main]
//! Fuzzes `irsig_formats::dirsig::ems` (DIRSIG `.ems` spectral curves): no panic, errors
//! inside the input, and an accepted file keeps the format's rules (91 angular factors and
//! every emissivity 0 to 1; each curve at least two rows, wavelengths positive and strictly
//! increasing).

#[path = "radtran_common.rs"]
mod common;

use irsig_formats::dirsig::ems;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some(e) = common::check(data, ems::parse) {
        assert_eq!(e.angular_factor.len(), ems::ANGLES);
        assert!(e.angular_factor.iter().all(|f| (0.0..=1.0).contains(f)));
        assert!(!e.curves.is_empty());
        for c in &e.curves {
            assert!(c.wavelength_um.len() >= 2);
            assert_eq!(c.wavelength_um.len(), c.emissivity.len());
            assert!(c.wavelength_um[0] > 0.0);
            assert!(c.wavelength_um.windows(2).all(|w| w[0] < w[1]));
            assert!(c.emissivity.iter().all(|x| (0.0..=1.0).contains(x)));
        }
    }
});
