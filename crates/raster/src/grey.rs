//! Grey PNG images read as maps: 8- or 16-bit grey, each pixel's grey value 0 (black) to 1
//! (white), the image's size checked from its header against the memory budget before a
//! pixel is decoded.

use image::{ImageDecoder, ImageReader};
use irsig_model::limits::{MAX_IMAGE_PIXELS, MEMORY_BUDGET_BYTES};

use crate::RasterError;

/// Bytes a decoded grey map holds per pixel: the decoder's 16-bit sample and the map's
/// `f32` grey.
const BYTES_PER_PIXEL: u64 = 2 + 4;

/// A grey PNG's pixels as grey values 0 to 1, `(width, height, grey)`, row 0 at the top:
/// an 8-bit value over 255, a 16-bit one over 65,535.
///
/// # Errors
/// A file that is not a PNG, whose header claims more than
/// [`irsig_model::limits::MAX_IMAGE_PIXELS`] pixels or more bytes decoded than
/// [`irsig_model::limits::MEMORY_BUDGET_BYTES`] (refused from the header, before the
/// pixels are decoded), or whose pixels are not one grey sample (RGB, or grey with alpha).
pub fn read_png_grey(bytes: &[u8]) -> Result<(usize, usize, Vec<f32>), RasterError> {
    let reader = || ImageReader::with_format(std::io::Cursor::new(bytes), image::ImageFormat::Png);
    let (width, height) = reader().into_dimensions()?;
    let pixels = u64::from(width) * u64::from(height);
    if pixels > MAX_IMAGE_PIXELS || pixels * BYTES_PER_PIXEL > MEMORY_BUDGET_BYTES {
        return Err(RasterError::TooLarge(format!(
            "the PNG's header claims {width} × {height} = {pixels} pixels, more than the \
             {MAX_IMAGE_PIXELS} an image may have"
        )));
    }
    let decoder = reader().into_decoder()?;
    let colour = decoder.color_type();
    if !matches!(colour, image::ColorType::L8 | image::ColorType::L16) {
        return Err(RasterError::PngPixels(format!(
            "{colour:?}: expected 8- or 16-bit grey (one sample per pixel, no alpha)"
        )));
    }
    let grey: Vec<f32> = match image::DynamicImage::from_decoder(decoder)? {
        image::DynamicImage::ImageLuma8(img) => img
            .into_raw()
            .into_iter()
            .map(|g| f32::from(g) / 255.0)
            .collect(),
        image::DynamicImage::ImageLuma16(img) => img
            .into_raw()
            .into_iter()
            .map(|g| f32::from(g) / 65535.0)
            .collect(),
        other => {
            return Err(RasterError::PngPixels(format!(
                "{:?}: expected 8- or 16-bit grey",
                other.color()
            )));
        }
    };
    Ok((width as usize, height as usize, grey))
}

/// A PNG's stored samples as a material map reads them, `(width, height, channels,
/// samples, greatest)`: one to four channels (grey; grey and alpha; RGB; RGBA), 8 or 16
/// bits, the samples interleaved texel after texel, row 0 at the top, each the integer the
/// file stores; `greatest` is 255 or 65,535.
///
/// # Errors
/// As [`read_png_grey`]: not a PNG, too large from its header, or a pixel type other than
/// 8- or 16-bit grey, grey and alpha, RGB or RGBA.
pub fn read_png_samples(bytes: &[u8]) -> Result<(usize, usize, usize, Vec<u16>, u16), RasterError> {
    let reader = || ImageReader::with_format(std::io::Cursor::new(bytes), image::ImageFormat::Png);
    let (width, height) = reader().into_dimensions()?;
    let pixels = u64::from(width) * u64::from(height);
    // Up to four 16-bit samples decoded and kept as u16, and the fractions' f32 images.
    if pixels > MAX_IMAGE_PIXELS || pixels * (8 + 8 + 16) > MEMORY_BUDGET_BYTES {
        return Err(RasterError::TooLarge(format!(
            "the PNG's header claims {width} × {height} = {pixels} pixels, more than the \
             {MAX_IMAGE_PIXELS} an image may have"
        )));
    }
    let decoder = reader().into_decoder()?;
    let (w, h) = (width as usize, height as usize);
    let wide = |v: Vec<u8>| v.into_iter().map(u16::from).collect::<Vec<u16>>();
    Ok(match image::DynamicImage::from_decoder(decoder)? {
        image::DynamicImage::ImageLuma8(i) => (w, h, 1, wide(i.into_raw()), 255),
        image::DynamicImage::ImageLumaA8(i) => (w, h, 2, wide(i.into_raw()), 255),
        image::DynamicImage::ImageRgb8(i) => (w, h, 3, wide(i.into_raw()), 255),
        image::DynamicImage::ImageRgba8(i) => (w, h, 4, wide(i.into_raw()), 255),
        image::DynamicImage::ImageLuma16(i) => (w, h, 1, i.into_raw(), u16::MAX),
        image::DynamicImage::ImageLumaA16(i) => (w, h, 2, i.into_raw(), u16::MAX),
        image::DynamicImage::ImageRgb16(i) => (w, h, 3, i.into_raw(), u16::MAX),
        image::DynamicImage::ImageRgba16(i) => (w, h, 4, i.into_raw(), u16::MAX),
        other => {
            return Err(RasterError::PngPixels(format!(
                "{:?}: expected 8- or 16-bit grey, grey and alpha, RGB or RGBA",
                other.color()
            )));
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CRC-32 of PNG chunks (ISO 3309, the polynomial 0xEDB88320 reflected), bit by bit.
    fn crc32(data: &[u8]) -> u32 {
        let mut c = 0xffff_ffffu32;
        for &b in data {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 == 1 {
                    (c >> 1) ^ 0xedb8_8320
                } else {
                    c >> 1
                };
            }
        }
        !c
    }

    /// A PNG signature, a grey 8-bit IHDR claiming `width × height`, an IDAT of an empty
    /// zlib stream and an IEND: a header with no pixels behind it.
    fn header_only(width: u32, height: u32) -> Vec<u8> {
        let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
        let chunk = |out: &mut Vec<u8>, kind: &[u8], data: &[u8]| {
            out.extend_from_slice(&u32::try_from(data.len()).unwrap().to_be_bytes());
            let mut typed = kind.to_vec();
            typed.extend_from_slice(data);
            out.extend_from_slice(&typed);
            out.extend_from_slice(&crc32(&typed).to_be_bytes());
        };
        let mut ihdr = Vec::new();
        ihdr.extend_from_slice(&width.to_be_bytes());
        ihdr.extend_from_slice(&height.to_be_bytes());
        ihdr.extend_from_slice(&[8, 0, 0, 0, 0]); // 8 bits, grey, deflate, no filter, no interlace
        chunk(&mut out, b"IHDR", &ihdr);
        chunk(
            &mut out,
            b"IDAT",
            &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01],
        );
        chunk(&mut out, b"IEND", &[]);
        out
    }

    #[allow(clippy::float_cmp)] // coordinates and greys written exactly, read back exactly
    #[test]
    fn grey_8_and_16_bit_read_as_0_to_1_from_the_top_row() {
        let mut png8 = Vec::new();
        crate::write_png_gray8(&mut png8, 2, 2, &[0, 255, 51, 102]).unwrap();
        let (w, h, g) = read_png_grey(&png8).unwrap();
        assert_eq!((w, h), (2, 2));
        assert_eq!(g, [0.0, 1.0, 0.2, 0.4]);
        let mut png16 = Vec::new();
        crate::write_png_gray16(&mut png16, 2, 1, &[65535, 13107]).unwrap();
        let (_, _, g) = read_png_grey(&png16).unwrap();
        assert_eq!(g, [1.0, 0.2]);
    }

    #[test]
    fn a_huge_header_is_refused_before_any_pixel_is_decoded() {
        // 100,000 × 100,000 claimed by a 65-byte file.
        let e = read_png_grey(&header_only(100_000, 100_000)).unwrap_err();
        assert!(matches!(e, RasterError::TooLarge(_)), "{e}");
        assert!(e.to_string().contains("100000 × 100000"), "{e}");
        // The same header at 2 × 2 passes the size check and fails for want of pixels.
        let e = read_png_grey(&header_only(2, 2)).unwrap_err();
        assert!(!matches!(e, RasterError::TooLarge(_)), "{e}");
    }

    #[test]
    fn colour_and_non_png_are_refused() {
        let mut rgb = Vec::new();
        crate::write_png_rgb8(&mut rgb, 1, 1, &[1, 2, 3]).unwrap();
        let e = read_png_grey(&rgb).unwrap_err();
        assert!(e.to_string().contains("expected 8- or 16-bit grey"), "{e}");
        assert!(read_png_grey(b"not a png").is_err());
    }
}
