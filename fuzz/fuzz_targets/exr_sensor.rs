#![no_main]
//! Fuzzes the EXR reader `irsig-sensor` (and stats, report, merge) reads images with,
//! `irsig_raster::read_exr`: no panic and no allocation from a claimed size beyond the
//! budget (libFuzzer's RSS limit catches one); a refused file's error offset lies inside
//! the file (or at its end); an accepted image is consistent and writes to an EXR that
//! reads back to the same layers.

use irsig_raster::{exr_bytes, exr_error_offset, read_exr};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    match read_exr(data) {
        Ok(r) => {
            assert!(r.layers.iter().all(|l| l.data.len() == r.width * r.height));
            let bytes = exr_bytes(&r).expect("an accepted image writes");
            let again = read_exr(&bytes).expect("a written image reads");
            assert_eq!((r.width, r.height), (again.width, again.height));
            assert_eq!(r.layers.len(), again.layers.len());
            for (a, b) in r.layers.iter().zip(&again.layers) {
                assert_eq!(a.name, b.name);
                let same = a
                    .data
                    .iter()
                    .zip(&b.data)
                    .all(|(x, y)| x.to_bits() == y.to_bits());
                assert!(same, "layer {} changed on the round trip", a.name);
            }
        }
        Err(e) => assert!(exr_error_offset(data, &e) <= data.len()),
    }
});
