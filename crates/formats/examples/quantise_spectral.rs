//! A binary spectral atmosphere rewritten in version 2 (each table quantised to 16 bits per
//! value against its spectra's maxima, and deflated): how `scripts/atmosphere/regen.py
//! --mwir` makes the 3–5 µm built-ins from LOWTRAN7's `f32` spectra.
//!
//! ```text
//! cargo run --release -p irsig-formats --example quantise_spectral -- FULL.bin OUT.bin
//! ```

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (Some(input), Some(output)) = (args.get(1), args.get(2)) else {
        eprintln!("usage: quantise_spectral FULL.bin OUT.bin");
        std::process::exit(2);
    };
    let bytes = std::fs::read(input).unwrap_or_else(|e| {
        eprintln!("quantise_spectral: cannot read {input}: {e}");
        std::process::exit(1);
    });
    let atmosphere = irsig_formats::canonical::binary_spectral::decode(input, &bytes)
        .unwrap_or_else(|e| {
            eprintln!("quantise_spectral: {e}");
            std::process::exit(1);
        });
    let out = irsig_formats::canonical::binary_spectral::encode_quantised(&atmosphere)
        .unwrap_or_else(|e| {
            eprintln!("quantise_spectral: {e}");
            std::process::exit(1);
        });
    std::fs::write(output, &out).unwrap_or_else(|e| {
        eprintln!("quantise_spectral: cannot write {output}: {e}");
        std::process::exit(1);
    });
    eprintln!(
        "quantise_spectral: {output}: {} bytes ({} in {input})",
        out.len(),
        bytes.len()
    );
}
