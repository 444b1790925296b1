//! What the EXR reader refuses before it trusts a file, found by the `exr_sensor` fuzz
//! target: a header claiming more samples than the file's bytes encode (checked before a
//! block is inflated into a buffer of the claimed size), and layer names the units
//! attribute cannot carry.

/// 1,192 bytes, found by the `exr_sensor` fuzz target: a ZIP16 scanline image whose data
/// window claims 11,337,726 × 4 pixels of 12 f32 channels (2.2 GB of samples, inside the
/// 16 GiB memory budget). Its one block was inflated into a 2.17 GB buffer before the
/// data was found malformed.
const ZIP_CLAIM: &[u8] = include_bytes!("data/zip-block-past-file.exr");

#[test]
fn a_kilobyte_claiming_gigabytes_is_refused_before_any_block_is_read() {
    let err = irsig_raster::read_exr(ZIP_CLAIM).expect_err("the claim cannot be held");
    let message = err.to_string();
    assert!(
        message.contains("11337726x4 pixels of 12 channels")
            && message.contains("more than the file's 1192 bytes can hold"),
        "{message}"
    );
    // The error points at the data window, which makes the claim.
    let at = irsig_raster::exr_error_offset(ZIP_CLAIM, &err);
    assert_eq!(&ZIP_CLAIM[at..at + 11], b"dataWindow\0");
}

#[test]
fn a_real_compressed_frame_is_not_refused() {
    // A 64 x 48 frame of constant radiance, the most compressible image there is, written
    // with ZIP: its claim is far above its size, and within what deflate can hold.
    let mut r = irsig_raster::Raster::new(64, 48);
    r.push_layer("radiance", "W m-2 sr-1", vec![10.0; 64 * 48])
        .unwrap();
    let bytes = irsig_raster::exr_bytes(&r).unwrap();
    assert!(bytes.len() < 64 * 48 * 4 / 4, "{} bytes", bytes.len());
    let back = irsig_raster::read_exr(&bytes).unwrap();
    assert_eq!(back.width, 64);
}

#[test]
fn a_layer_name_the_units_attribute_cannot_carry_is_refused() {
    // The exr_sensor fuzz target found a channel named "em\nssivity": written, its units
    // line split in two and the layer read back in another place without its unit.
    let mut r = irsig_raster::Raster::new(2, 2);
    for name in ["em\nssivity", "a=b", "tab\there"] {
        let err = r.push_layer(name, "1", vec![0.0; 4]).unwrap_err();
        assert!(err.to_string().contains("units attribute"), "{err}");
    }
    let err = r
        .push_layer("radiance", "W\nm-2", vec![0.0; 4])
        .unwrap_err();
    assert!(err.to_string().contains("units attribute"), "{err}");
    // The fuzz target's input itself is refused when read.
    let found = include_bytes!("data/newline-in-channel-name.exr");
    let err = irsig_raster::read_exr(found).unwrap_err();
    assert!(err.to_string().contains("units attribute"), "{err}");
    // Names with spaces, dots and non-ASCII letters are fine.
    r.push_layer("apparent temperature.K", "K", vec![0.0; 4])
        .unwrap();
    r.push_layer("émissivité", "1", vec![0.0; 4]).unwrap();
}
