//! Indexed-colour PNG (colour type 3): each pixel is one byte, an index into a palette
//! of RGB colours. A viewer shows the palette's colours; a reader that keeps the indices
//! (Pillow's mode `P`, MATLAB's `[X, map] = imread(...)`, the `png` crate without
//! transformations, [`read_png_indices`]) gets the bytes back unchanged. The interaction
//! map uses it so that its material ids are both visible and kept.

use std::io::Write;

use crate::{RasterError, dims, mismatch};

/// Writes an 8-bit indexed-colour PNG; `indices` is row-major from the top, one byte per
/// pixel, and `palette` has 256 entries so that every byte names a colour.
///
/// # Errors
/// A size mismatch or an encoder error.
pub fn write_png_indexed8(
    out: &mut impl Write,
    width: usize,
    height: usize,
    indices: &[u8],
    palette: &[[u8; 3]; 256],
) -> Result<(), RasterError> {
    let (w, h) = dims(width, height, indices.len(), 1)?;
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, w, h);
        encoder.set_color(png::ColorType::Indexed);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_palette(palette.as_flattened().to_vec());
        let mut writer = encoder.write_header().map_err(png_error)?;
        writer.write_image_data(indices).map_err(png_error)?;
        writer.finish().map_err(png_error)?;
    }
    out.write_all(&bytes)?;
    Ok(())
}

/// The pixel bytes of an 8-bit PNG as stored, palette indices not turned into colours
/// (grey values for a grey PNG): `(width, height, bytes)`, row-major from the top.
///
/// # Errors
/// A file that is not a PNG, or one whose pixels are not one byte each (16-bit, RGB,
/// grey with alpha, fewer than 8 bits).
pub fn read_png_indices(bytes: &[u8]) -> Result<(usize, usize, Vec<u8>), RasterError> {
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::IDENTITY);
    let mut reader = decoder.read_info().map_err(png_decode_error)?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| RasterError::TooLarge("the PNG is too large to decode".into()))?;
    let mut buf = vec![0; size];
    let info = reader.next_frame(&mut buf).map_err(png_decode_error)?;
    let one_byte = matches!(
        info.color_type,
        png::ColorType::Indexed | png::ColorType::Grayscale
    ) && info.bit_depth == png::BitDepth::Eight;
    if !one_byte {
        return Err(RasterError::PngPixels(format!(
            "{:?} at {:?} bits: expected one byte per pixel (8-bit indexed or grey)",
            info.color_type, info.bit_depth
        )));
    }
    let (width, height) = (info.width as usize, info.height as usize);
    buf.truncate(info.buffer_size());
    if buf.len() != width * height {
        return Err(mismatch("png", buf.len(), width, height));
    }
    Ok((width, height, buf))
}

fn png_error(e: png::EncodingError) -> RasterError {
    RasterError::PngPixels(e.to_string())
}

fn png_decode_error(e: png::DecodingError) -> RasterError {
    RasterError::PngPixels(e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn palette() -> [[u8; 3]; 256] {
        std::array::from_fn(|i| [i as u8, 255 - i as u8, 7])
    }

    #[test]
    fn the_indices_come_back_and_a_viewer_sees_the_palette() {
        let indices = [0, 1, 0x10, 0xff, 0x3c, 0x42];
        let mut out = Vec::new();
        write_png_indexed8(&mut out, 3, 2, &indices, &palette()).unwrap();
        assert_eq!(read_png_indices(&out).unwrap(), (3, 2, indices.to_vec()));
        // image expands the palette, as a picture viewer does.
        let rgb = image::load_from_memory(&out).unwrap().to_rgb8();
        assert_eq!(rgb.get_pixel(2, 0).0, [0x10, 0xef, 7]);
        assert_eq!(rgb.get_pixel(0, 1).0, [0xff, 0, 7]);
    }

    #[test]
    fn a_grey_png_reads_as_its_bytes_and_others_are_refused() {
        let mut grey = Vec::new();
        crate::write_png_gray8(&mut grey, 2, 1, &[9, 250]).unwrap();
        assert_eq!(read_png_indices(&grey).unwrap(), (2, 1, vec![9, 250]));
        let mut wide = Vec::new();
        crate::write_png_gray16(&mut wide, 1, 1, &[300]).unwrap();
        assert!(matches!(
            read_png_indices(&wide),
            Err(RasterError::PngPixels(m)) if m.contains("one byte per pixel")
        ));
        assert!(read_png_indices(b"not a png").is_err());
        assert!(write_png_indexed8(&mut Vec::new(), 2, 2, &[0; 3], &palette()).is_err());
        assert!(write_png_indexed8(&mut Vec::new(), 0, 0, &[], &palette()).is_err());
    }
}
