//! `--animation`: a sequence's frames (a day's hours, a fly-by's views) as one animated GIF
//! that loops forever, each frame shown for the same delay, through the `image` crate's
//! GIF encoder.
//!
//! The inputs are PNGs of one size (grey or colour, 8 or 16 bits), in the order given. GIF
//! holds at most 256 colours a frame: a frame with no more than that (every grey PNG of 8
//! bits, a digital-count image at any gain) is stored exactly; one with more (a colour
//! preview's smooth ramps) is reduced to 256 by NeuQuant (Dekker 1994, "Kohonen neural
//! networks for optimal colour quantization", Network 5, 351), the only loss. A 16-bit PNG
//! keeps its top 8 bits. GIF counts delays in hundredths of a second, so the delay must
//! be a whole number of 10 ms.

use image::codecs::gif::{GifEncoder, Repeat};
use image::{Delay, Frame, RgbaImage};
use miette::miette;

/// The longest delay a GIF can hold: 65 535 hundredths of a second, ms.
pub const MAX_DELAY_MS: u32 = 655_350;

/// NeuQuant's sampling factor, 1 (best) to 30 (fastest): 10 is its authors' default,
/// and it only matters for frames of more than 256 colours.
const QUANTISER_SPEED: i32 = 10;

/// Checks `--frame-delay-ms`: a whole number of hundredths of a second from 10 ms to
/// [`MAX_DELAY_MS`].
///
/// # Errors
/// A delay outside that range or not a multiple of 10 ms.
pub fn parse_delay_ms(s: &str) -> Result<u32, String> {
    let ms: u32 = s
        .trim()
        .parse()
        .map_err(|_| format!("expected a whole number of milliseconds, found `{s}`"))?;
    if !(10..=MAX_DELAY_MS).contains(&ms) || ms % 10 != 0 {
        return Err(format!(
            "a GIF frame's delay is a whole number of hundredths of a second: 10 to \
             {MAX_DELAY_MS} ms in steps of 10, found {ms} ms"
        ));
    }
    Ok(ms)
}

/// Decodes one input PNG to 8-bit RGBA, named in any error.
fn read_frame(name: &str, bytes: &[u8]) -> miette::Result<RgbaImage> {
    if !bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        return Err(miette!(
            "`{name}` is not a PNG: an animation is made from the frames' PNG images"
        ));
    }
    Ok(
        image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
            .map_err(|e| miette!("`{name}` is not a readable PNG: {e}"))?
            .to_rgba8(),
    )
}

/// Builds the GIF from `(name, bytes)` PNG inputs, each shown for `delay_ms`, looping
/// forever. Returns the GIF's bytes.
///
/// # Errors
/// No inputs, an input that is not a readable PNG, frames of different sizes (the first
/// that differs is named), a frame wider or taller than a GIF's 65 535 pixels, or a delay
/// [`parse_delay_ms`] refuses.
pub fn build(inputs: &[(String, Vec<u8>)], delay_ms: u32) -> miette::Result<Vec<u8>> {
    parse_delay_ms(&delay_ms.to_string()).map_err(|e| miette!("{e}"))?;
    let Some((first_name, _)) = inputs.first() else {
        return Err(miette!("an animation needs at least one input image"));
    };
    let mut frames = Vec::with_capacity(inputs.len());
    for (name, bytes) in inputs {
        let image = read_frame(name, bytes)?;
        if let Some(first) = frames.first().map(Frame::buffer) {
            let (w, h) = first.dimensions();
            if image.dimensions() != (w, h) {
                return Err(miette!(
                    "`{name}` is {} x {} pixels, but `{first_name}` is {w} x {h}: every frame \
                     of an animation has the same size",
                    image.width(),
                    image.height(),
                ));
            }
        }
        if image.width() > u32::from(u16::MAX) || image.height() > u32::from(u16::MAX) {
            return Err(miette!(
                "`{name}` is {} x {} pixels; a GIF frame is at most 65535 x 65535",
                image.width(),
                image.height()
            ));
        }
        let delay = Delay::from_numer_denom_ms(delay_ms, 1);
        frames.push(Frame::from_parts(image, 0, 0, delay));
    }
    let mut out = Vec::new();
    {
        let mut encoder = GifEncoder::new_with_speed(&mut out, QUANTISER_SPEED);
        encoder
            .set_repeat(Repeat::Infinite)
            .map_err(|e| miette!("writing the animation: {e}"))?;
        encoder
            .encode_frames(frames)
            .map_err(|e| miette!("writing the animation: {e}"))?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::AnimationDecoder;
    use image::codecs::gif::GifDecoder;
    use irsig_raster::write_png_gray8;

    fn grey_png(w: usize, h: usize, f: impl Fn(usize, usize) -> u8) -> Vec<u8> {
        let data: Vec<u8> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| f(x, y))
            .collect();
        let mut out = Vec::new();
        write_png_gray8(&mut std::io::Cursor::new(&mut out), w, h, &data).unwrap();
        out
    }

    fn decode(gif: &[u8]) -> Vec<Frame> {
        GifDecoder::new(std::io::Cursor::new(gif))
            .unwrap()
            .into_frames()
            .collect_frames()
            .unwrap()
    }

    #[test]
    fn grey_frames_come_back_exactly_in_order_with_their_delay() {
        // Three 7 x 5 frames, each a ramp of its own: all 256 grey levels across the set,
        // none shared between frames at the same pixel.
        let frame = |k: usize| move |x: usize, y: usize| (k * 85 + x * 7 + y * 3) as u8;
        let inputs: Vec<(String, Vec<u8>)> = (0..3)
            .map(|k| (format!("f{k}.png"), grey_png(7, 5, frame(k))))
            .collect();
        let frames = decode(&build(&inputs, 250).unwrap());
        assert_eq!(frames.len(), 3);
        for (k, f) in frames.iter().enumerate() {
            // 250 ms is 25 hundredths of a second, stored exactly.
            assert_eq!(f.delay().numer_denom_ms(), (250, 1));
            let img = f.buffer();
            assert_eq!(img.dimensions(), (7, 5));
            for (x, y, p) in img.enumerate_pixels() {
                let v = frame(k)(x as usize, y as usize);
                assert_eq!(p.0, [v, v, v, 255], "frame {k} pixel ({x}, {y})");
            }
        }
    }

    #[test]
    fn a_single_frame_and_the_longest_delay_are_kept() {
        let frames =
            decode(&build(&[("a.png".into(), grey_png(1, 1, |_, _| 0))], MAX_DELAY_MS).unwrap());
        assert_eq!(frames.len(), 1);
        assert_eq!(frames[0].delay().numer_denom_ms(), (MAX_DELAY_MS, 1));
        assert_eq!(frames[0].buffer().get_pixel(0, 0).0, [0, 0, 0, 255]);
    }

    #[test]
    fn bad_inputs_and_delays_are_refused_by_name() {
        let e = build(&[], 100).unwrap_err();
        assert!(e.to_string().contains("at least one"), "{e}");
        let e = build(&[("junk.gif".into(), b"GIF89a".to_vec())], 100).unwrap_err();
        assert!(e.to_string().contains("junk.gif"), "{e}");
        let inputs = vec![
            ("a.png".to_owned(), grey_png(4, 4, |_, _| 9)),
            ("b.png".to_owned(), grey_png(4, 3, |_, _| 9)),
        ];
        let e = build(&inputs, 100).unwrap_err().to_string();
        assert!(
            e.contains("`b.png` is 4 x 3") && e.contains("`a.png` is 4 x 4"),
            "{e}"
        );
        for bad in ["0", "5", "15", "655360", "-10", "0.5", "ten"] {
            assert!(parse_delay_ms(bad).is_err(), "{bad} accepted");
        }
        assert_eq!(parse_delay_ms("10"), Ok(10));
        assert!(build(&[("a.png".into(), grey_png(2, 2, |_, _| 1))], 15).is_err());
    }
}
