#![no_main]
//! Fuzzes `canonical::binary_spectral::decode` (the binary spectral atmosphere): no panic,
//! no allocation from a count beyond the bytes left, and an input that decodes encodes
//! back to exactly its own bytes.

use irsig_formats::canonical::binary_spectral;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(a) = binary_spectral::decode("fuzz", data) {
        let again = binary_spectral::encode(&a).expect("a decoded atmosphere encodes");
        let b = binary_spectral::decode("again", &again).expect("its encoding decodes");
        assert_eq!(a, b);
    }
});
