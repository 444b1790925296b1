//! `--contact-sheet`: several images side by side in one 8-bit grey PNG, for a fly-by's
//! frames at a glance (the thesis's Figures 16-19 are such sheets).
//!
//! Tiles are laid out row by row in the order given, `columns` to a row, each in a cell as
//! large as the largest input, with a 4-pixel black gap around every cell; each tile is
//! labelled with its place in the list (1, 2, ...) in its top-left corner. PNG inputs
//! (grey or colour, 8 or 16 bits) are shown as their grey value scaled to 8 bits (a DC image
//! keeps its own gain and bias, as in Figure 18); EXR inputs show their `radiance` layer
//! stretched linearly from the smallest to the largest finite radiance over *all* EXR
//! inputs, so that EXR tiles compare with one another.

use irsig_raster::read_exr;
use miette::{IntoDiagnostic, miette};

use crate::RADIANCE_LAYER;
use crate::preview::{GLYPH, for_each_text_pixel};

/// Black gap around each cell, pixels.
pub const GAP: usize = 4;

/// One input's pixels before they are put on the sheet.
enum Tile {
    Grey { w: usize, h: usize, data: Vec<u8> },
    Radiance { w: usize, h: usize, data: Vec<f32> },
}

impl Tile {
    fn size(&self) -> (usize, usize) {
        match self {
            Self::Grey { w, h, .. } | Self::Radiance { w, h, .. } => (*w, *h),
        }
    }
}

/// Reads one input: a PNG (by its signature) or an EXR.
fn read_tile(name: &str, bytes: &[u8]) -> miette::Result<Tile> {
    if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        let img = image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
            .map_err(|e| miette!("`{name}` is not a readable PNG: {e}"))?
            .to_luma8();
        let (w, h) = (img.width() as usize, img.height() as usize);
        return Ok(Tile::Grey {
            w,
            h,
            data: img.into_raw(),
        });
    }
    let raster = read_exr(bytes)
        .map_err(|e| miette!("`{name}` is neither a PNG nor a readable EXR: {e}"))?;
    let layer = raster.layer(RADIANCE_LAYER).ok_or_else(|| {
        miette!("`{name}`: no `{RADIANCE_LAYER}` layer to show on the contact sheet")
    })?;
    Ok(Tile::Radiance {
        w: raster.width,
        h: raster.height,
        data: layer.data.clone(),
    })
}

/// The sheet's size in pixels for `n` tiles of at most `cell` pixels in `columns` columns.
#[must_use]
pub fn sheet_size(n: usize, columns: usize, cell: (usize, usize)) -> (usize, usize) {
    let columns = columns.clamp(1, n.max(1));
    let rows = n.div_ceil(columns);
    (
        columns * cell.0 + (columns + 1) * GAP,
        rows * cell.1 + (rows + 1) * GAP,
    )
}

/// Builds the sheet from `(name, bytes)` inputs; `columns` of `None` gives a near-square
/// sheet (⌈√n⌉ columns). Returns the PNG bytes.
///
/// # Errors
/// No inputs, an input that is neither PNG nor EXR, an EXR without a `radiance` layer, or
/// a sheet too large to encode.
pub fn build(inputs: &[(String, Vec<u8>)], columns: Option<usize>) -> miette::Result<Vec<u8>> {
    if inputs.is_empty() {
        return Err(miette!("a contact sheet needs at least one input image"));
    }
    let tiles = inputs
        .iter()
        .map(|(name, bytes)| read_tile(name, bytes))
        .collect::<miette::Result<Vec<_>>>()?;
    let n = tiles.len();
    let columns = columns.unwrap_or_else(|| (1..=n).find(|c| c * c >= n).unwrap_or(1));
    let columns = columns.clamp(1, n);
    let cell = tiles.iter().fold((0, 0), |(w, h), t| {
        let (tw, th) = t.size();
        (w.max(tw), h.max(th))
    });
    let (sw, sh) = sheet_size(n, columns, cell);
    // One stretch for every EXR tile: the finite radiance range over all of them.
    let (lo, hi) = tiles
        .iter()
        .filter_map(|t| match t {
            Tile::Radiance { data, .. } => Some(data),
            Tile::Grey { .. } => None,
        })
        .flatten()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(f64::from(v)), hi.max(f64::from(v)))
        });
    let stretch = |v: f32| -> u8 {
        if !v.is_finite() || hi <= lo {
            return 0;
        }
        ((f64::from(v) - lo) / (hi - lo) * 255.0)
            .round()
            .clamp(0.0, 255.0) as u8
    };
    let mut sheet = vec![0u8; sw * sh];
    for (k, tile) in tiles.iter().enumerate() {
        let x0 = GAP + (k % columns) * (cell.0 + GAP);
        let y0 = GAP + (k / columns) * (cell.1 + GAP);
        let (w, h) = tile.size();
        for y in 0..h {
            let row = &mut sheet[(y0 + y) * sw + x0..(y0 + y) * sw + x0 + w];
            match tile {
                Tile::Grey { data, .. } => row.copy_from_slice(&data[y * w..(y + 1) * w]),
                Tile::Radiance { data, .. } => {
                    for (o, &v) in row.iter_mut().zip(&data[y * w..(y + 1) * w]) {
                        *o = stretch(v);
                    }
                }
            }
        }
        label(&mut sheet, sw, (x0, y0), (w, h), &(k + 1).to_string());
    }
    let mut out = Vec::new();
    irsig_raster::write_png_gray8(&mut std::io::Cursor::new(&mut out), sw, sh, &sheet)
        .into_diagnostic()?;
    Ok(out)
}

/// White digits on a black box in the tile's top-left corner, clipped to the tile.
fn label(
    sheet: &mut [u8],
    sw: usize,
    (x0, y0): (usize, usize),
    (w, h): (usize, usize),
    text: &str,
) {
    let bw = (text.len() * GLYPH + 2).min(w);
    let bh = (GLYPH + 2).min(h);
    for y in 0..bh {
        for x in 0..bw {
            sheet[(y0 + y) * sw + x0 + x] = 0;
        }
    }
    for_each_text_pixel(text, |gx, gy| {
        let (x, y) = (1 + gx, 1 + gy);
        if x < bw && y < bh {
            sheet[(y0 + y) * sw + x0 + x] = 255;
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_raster::{Raster, exr_bytes, write_png_gray8};

    fn png(w: usize, h: usize, v: u8) -> Vec<u8> {
        let mut out = Vec::new();
        write_png_gray8(&mut std::io::Cursor::new(&mut out), w, h, &vec![v; w * h]).unwrap();
        out
    }

    fn decode(bytes: &[u8]) -> image::GrayImage {
        image::load_from_memory(bytes).unwrap().to_luma8()
    }

    #[test]
    fn tiles_sit_in_a_grid_with_gaps_and_labels() {
        let inputs: Vec<(String, Vec<u8>)> = (0..5)
            .map(|k| (format!("f{k}.png"), png(20, 12, 40 + 10 * k as u8)))
            .collect();
        let sheet = decode(&build(&inputs, Some(3)).unwrap());
        // 3 columns x 2 rows of 20 x 12 cells, 4-pixel gaps: 3*20 + 4*4, 2*12 + 3*4.
        assert_eq!((sheet.width(), sheet.height()), (76, 36));
        // Tile 5 (index 4) is row 1, column 1: its bottom-right pixel, clear of the label.
        let (x, y) = (GAP + 24 + 19, GAP + 16 + 11);
        assert_eq!(sheet.get_pixel(x as u32, y as u32).0[0], 80);
        // The gaps are black, and the 6th cell (no tile) too.
        assert_eq!(sheet.get_pixel(1, 1).0[0], 0);
        assert_eq!(sheet.get_pixel(60, 30).0[0], 0);
        // Tile 1's label "1": some white pixels in its corner box.
        let white = (0..10)
            .flat_map(|y| (0..10).map(move |x| (x, y)))
            .filter(|&(x, y)| sheet.get_pixel((GAP + x) as u32, (GAP + y) as u32).0[0] == 255)
            .count();
        assert!(white > 5, "label pixels: {white}");
    }

    #[test]
    fn exr_tiles_share_one_stretch() {
        // 12 x 12 tiles, uniform but for the bottom-right pixel (clear of the 10 x 10 label).
        let exr = |base: f32, corner: f32| {
            let mut vals = vec![base; 144];
            vals[143] = corner;
            let mut r = Raster::new(12, 12);
            r.push_layer(RADIANCE_LAYER, "W m^-2 sr^-1", vals).unwrap();
            exr_bytes(&r).unwrap()
        };
        let inputs = vec![
            ("a.exr".to_owned(), exr(1.0, 2.0)),
            ("b.exr".to_owned(), exr(3.0, 5.0)),
        ];
        let sheet = decode(&build(&inputs, None).unwrap());
        assert_eq!((sheet.width(), sheet.height()), (36, 20));
        let px = |x: usize, y: usize| sheet.get_pixel(x as u32, y as u32).0[0];
        // One range, 1 to 5, for both: (v - 1) / 4 * 255.
        let (a, b) = (GAP, 2 * GAP + 12);
        assert_eq!(px(a, GAP + 11), 0);
        assert_eq!(px(a + 11, GAP + 11), 64);
        assert_eq!(px(b, GAP + 11), 128);
        assert_eq!(px(b + 11, GAP + 11), 255);
    }

    #[test]
    fn bad_inputs_are_named() {
        let e = build(&[("junk.png".into(), b"not an image".to_vec())], None).unwrap_err();
        assert!(e.to_string().contains("junk.png"), "{e}");
        assert!(build(&[], None).is_err());
    }
}
