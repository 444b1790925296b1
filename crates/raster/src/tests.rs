#[test]
fn parallel_compression_writes_the_same_bytes_as_one_thread() {
    // Many scan-line blocks (ZIP: 16 lines each), several layers, data that compresses
    // unevenly, so blocks finish out of order on the threads.
    let (w, h) = (257, 300);
    let mut r = super::Raster::new(w, h);
    for l in 0..3u32 {
        let data = (0..w * h)
            .map(|i| {
                let i = i as u32;
                if (i / 700) % 3 == l {
                    (i.wrapping_mul(2_654_435_761) >> 7) as f32
                } else {
                    280.0
                }
            })
            .collect();
        r.push_layer(format!("l{l}"), "K", data).unwrap();
    }
    let write = |parallel| {
        let mut bytes = Vec::new();
        super::write_exr_threads(&mut std::io::Cursor::new(&mut bytes), r.clone(), parallel)
            .unwrap();
        bytes
    };
    let one = write(false);
    for _ in 0..4 {
        assert_eq!(write(true), one);
    }
}

use super::*;

fn sample() -> Raster {
    let mut r = Raster::new(3, 2);
    r.push_layer(
        "radiance",
        "W m^-2 sr^-1",
        vec![1.0, 2.0, 3.0, 4.0, 5.0, f32::MAX],
    )
    .unwrap();
    r.push_layer("range", "m", vec![0.5, 1e-30, 1e30, 0.0, -0.0, 7.25])
        .unwrap();
    r
}

#[test]
fn exr_round_trip_is_bit_exact_and_keeps_units() {
    let r = sample();
    let back = read_exr(&exr_bytes(&r).unwrap()).unwrap();
    assert_eq!((back.width, back.height), (3, 2));
    for l in &r.layers {
        let b = back.layer(&l.name).unwrap();
        assert_eq!(b.unit, l.unit);
        let bits: Vec<u32> = b.data.iter().map(|v| v.to_bits()).collect();
        let want: Vec<u32> = l.data.iter().map(|v| v.to_bits()).collect();
        assert_eq!(bits, want, "layer {}", l.name);
    }
}

#[test]
fn a_raster_read_back_keeps_its_layer_order_and_writes_the_same_bytes() {
    // "range" sorts before "radiance" nowhere: the file's channels are alphabetical,
    // the raster's order is the units attribute's.
    let mut r = Raster::new(2, 1);
    r.push_layer("zeta", "K", vec![1.0, 2.0]).unwrap();
    r.push_layer("alpha", "", vec![3.0, 4.0]).unwrap();
    r.push_layer("alpha_2", "m", vec![5.0, 6.0]).unwrap();
    let bytes = exr_bytes(&r).unwrap();
    let back = read_exr(&bytes).unwrap();
    assert_eq!(back, r);
    assert_eq!(exr_bytes(&back).unwrap(), bytes);
    let info = read_exr_info(&bytes).unwrap();
    assert_eq!(info, r.info());
}

#[test]
fn a_part_of_a_frame_keeps_its_place_frame_and_run() {
    let part = FramePart {
        frame_width: 10,
        frame_height: 8,
        x: 7,
        y: 6,
        run: "0123abcd".into(),
    };
    let mut r = Raster::new(3, 2).with_part(part.clone());
    r.push_layer("radiance", "W m^-2 sr^-1", vec![1.0; 6])
        .unwrap();
    r.push_layer("range", "m", vec![2.0; 6]).unwrap();
    let bytes = exr_bytes(&r).unwrap();
    let back = read_exr(&bytes).unwrap();
    assert_eq!(back.part, Some(part.clone()));
    assert_eq!(back, r);
    assert_eq!(exr_bytes(&back).unwrap(), bytes, "bytes stable");
    assert_eq!(read_exr_info(&bytes).unwrap().part, Some(part.clone()));
    // A part outside its frame, or a run of two lines, is not written.
    let mut outside = r.clone();
    outside.part.as_mut().unwrap().x = 8;
    assert!(matches!(exr_bytes(&outside), Err(RasterError::Part(_))));
    let mut two_lines = r.clone();
    two_lines.part.as_mut().unwrap().run = "a\nb".into();
    assert!(matches!(exr_bytes(&two_lines), Err(RasterError::Part(_))));
    // Without a part, nothing of a frame is written or read.
    let mut plain = r.clone();
    plain.part = None;
    assert_eq!(read_exr(&exr_bytes(&plain).unwrap()).unwrap().part, None);
}

#[test]
fn comments_in_any_script_round_trip_beside_a_part_and_keep_the_bytes_steady() {
    let part = FramePart::whole(3, 2, "sha256:abc");
    let comments = "irsig provenance\n(name: \"Ω/北/µm.srf\", lines: [\"a\"])\n";
    let r = sample()
        .with_part(part.clone())
        .with_comments(Some(comments.into()));
    let bytes = exr_bytes(&r).unwrap();
    // Three attributes of irsig's (units, run, comments): the bytes are the same on
    // every run of the writer.
    for _ in 0..4 {
        assert_eq!(exr_bytes(&r).unwrap(), bytes);
    }
    let back = read_exr(&bytes).unwrap();
    assert_eq!(back.comments.as_deref(), Some(comments));
    assert_eq!(back.part, Some(part));
    assert_eq!(
        read_exr_info(&bytes).unwrap().comments.as_deref(),
        Some(comments)
    );
    assert_eq!(
        read_exr(&exr_bytes(&sample()).unwrap()).unwrap().comments,
        None
    );
}

#[test]
fn comments_that_are_not_utf8_are_refused_at_their_byte() {
    // A Latin-1 byte in an image's provenance was read lossily, as another record.
    let r = sample().with_comments(Some("irsig provenance\nscene\n".into()));
    let mut bytes = exr_bytes(&r).unwrap();
    let at = bytes
        .windows(5)
        .position(|w| w == b"scene")
        .expect("the comment's text");
    bytes[at + 2] = 0xe9;
    for e in [
        read_exr(&bytes).unwrap_err(),
        read_exr_info(&bytes).unwrap_err(),
    ] {
        assert!(matches!(e, RasterError::Comments(19)), "{e}");
        assert_eq!(exr_error_offset(&bytes, &e), at + 2);
    }
}

#[test]
fn exr_bytes_are_deterministic() {
    assert_eq!(exr_bytes(&sample()).unwrap(), exr_bytes(&sample()).unwrap());
}

#[test]
fn garbage_and_truncated_exr_are_errors_not_panics() {
    assert!(read_exr(b"not an exr").is_err());
    assert!(read_exr(&[]).is_err());
    let bytes = exr_bytes(&sample()).unwrap();
    for cut in [4, 20, bytes.len() / 2, bytes.len() - 1] {
        assert!(read_exr(&bytes[..cut]).is_err(), "cut at {cut}");
    }
}

/// `bytes` with the box2i attribute `name` set to (0, 0)–(`max`, `max`).
fn patch_box(bytes: &mut [u8], name: &str, max: i32) {
    let key = format!("{name}\0box2i\0");
    let at = bytes
        .windows(key.len())
        .position(|w| w == key.as_bytes())
        .unwrap()
        + key.len()
        + 4; // the attribute's size
    for (i, v) in [0i32, 0, max, max].into_iter().enumerate() {
        bytes[at + 4 * i..at + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
    }
}

#[test]
fn a_header_claiming_a_huge_image_is_refused_before_decoding() {
    // A few hundred bytes whose header claims 100,000 x 100,000 pixels used to abort
    // the reader allocating them.
    let mut bytes = exr_bytes(&sample()).unwrap();
    assert!(bytes.len() < 1000);
    patch_box(&mut bytes, "dataWindow", 99_999);
    patch_box(&mut bytes, "displayWindow", 99_999);
    let e = read_exr(&bytes).unwrap_err();
    assert!(matches!(e, RasterError::TooLarge(_)), "{e}");
    assert!(e.to_string().contains("100000x100000"), "{e}");
}

#[test]
fn layers_must_fit_the_raster() {
    let mut r = Raster::new(2, 2);
    assert!(matches!(
        r.push_layer("a", "", vec![0.0; 3]),
        Err(RasterError::SizeMismatch { .. })
    ));
    r.push_layer("a", "", vec![0.0; 4]).unwrap();
    assert!(matches!(
        r.push_layer("a", "", vec![0.0; 4]),
        Err(RasterError::DuplicateLayer(_))
    ));
    assert!(matches!(
        exr_bytes(&Raster::new(2, 2)),
        Err(RasterError::Empty(_))
    ));
}

#[test]
fn png_writers_produce_decodable_images_of_the_right_depth() {
    let mut out = Vec::new();
    write_png_gray16(&mut out, 2, 1, &[0, 65535]).unwrap();
    let img = image::load_from_memory(&out).unwrap();
    assert_eq!(img.color(), image::ColorType::L16);
    assert_eq!(img.to_luma16().into_raw(), vec![0, 65535]);

    let mut out = Vec::new();
    write_png_gray8(&mut out, 1, 2, &[7, 200]).unwrap();
    assert_eq!(
        image::load_from_memory(&out).unwrap().to_luma8().into_raw(),
        vec![7, 200]
    );

    let mut out = Vec::new();
    write_png_rgb8(&mut out, 1, 1, &[1, 2, 3]).unwrap();
    assert_eq!(
        image::load_from_memory(&out).unwrap().to_rgb8().into_raw(),
        vec![1, 2, 3]
    );

    assert!(write_png_gray8(&mut Vec::new(), 2, 2, &[0; 3]).is_err());
    assert!(write_png_gray8(&mut Vec::new(), 0, 0, &[]).is_err());
}
