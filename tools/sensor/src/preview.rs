//! PNG previews of the sensor's apparent temperature: grey, and colour with a colour bar
//! labelled in kelvin.

use irsig_raster::{write_png_gray8, write_png_gray16, write_png_rgb8};
use miette::IntoDiagnostic;

use crate::PreviewBits;

/// `--preview-range`: which temperatures span a preview's black to white (grey) or its
/// colour map and bar. Pixels outside are clipped to its ends.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum PreviewRange {
    /// The image's coldest to its hottest finite pixel.
    #[default]
    Full,
    /// Given limits, K.
    Kelvin(f64, f64),
    /// Percentiles of the image's finite temperatures, 0-100 (nearest rank).
    Percentiles(f64, f64),
}

impl std::str::FromStr for PreviewRange {
    type Err = String;

    /// `MIN-MAX` in kelvin (`280-320`), `pLO-pHI` percentiles (`p1-p99`), or `full`.
    fn from_str(s: &str) -> Result<Self, String> {
        let expected = "expected MIN-MAX in kelvin (280-320), percentiles pLO-pHI (p1-p99) \
                        or `full`";
        if s.trim() == "full" {
            return Ok(Self::Full);
        }
        let (a, b) = s
            .split_once('-')
            .ok_or_else(|| format!("{expected}, found `{s}`"))?;
        let (a, b, percent) = match (a.trim().strip_prefix('p'), b.trim().strip_prefix('p')) {
            (Some(a), Some(b)) => (a, b, true),
            (None, None) => (a.trim(), b.trim(), false),
            _ => {
                return Err(format!(
                    "{expected}: both ends percentiles or neither, found `{s}`"
                ));
            }
        };
        let number = |v: &str| {
            v.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("{expected}, found `{v}` in `{s}`"))
        };
        let (lo, hi) = (number(a)?, number(b)?);
        if percent {
            if !(0.0 <= lo && lo < hi && hi <= 100.0) {
                return Err(format!(
                    "expected percentiles 0 <= LO < HI <= 100, found p{lo}-p{hi}"
                ));
            }
            Ok(Self::Percentiles(lo, hi))
        } else {
            if !(0.0 <= lo && lo < hi) {
                return Err(format!(
                    "expected temperatures 0 <= MIN < MAX in kelvin, found {lo}-{hi}"
                ));
            }
            Ok(Self::Kelvin(lo, hi))
        }
    }
}

impl PreviewRange {
    /// The temperatures, K, this range gives the image `t` (NaN pixels left out).
    #[must_use]
    pub fn of(self, t: &[f32]) -> (f64, f64) {
        match self {
            Self::Full => range(t),
            Self::Kelvin(lo, hi) => (lo, hi),
            Self::Percentiles(lo, hi) => {
                let mut v: Vec<f32> = t.iter().copied().filter(|v| v.is_finite()).collect();
                if v.is_empty() {
                    return range(t);
                }
                v.sort_unstable_by(f32::total_cmp);
                // Nearest rank: the smallest value with at least p % of the values at or
                // below it.
                let rank = |p: f64| {
                    let n = v.len();
                    let k = (p * n as f64 / 100.0).ceil() as usize;
                    f64::from(v[k.clamp(1, n) - 1])
                };
                let (a, b) = (rank(lo), rank(hi));
                if b - a < 1e-9 {
                    (a - 0.5, b + 0.5)
                } else {
                    (a, b)
                }
            }
        }
    }
}

/// The finite range of the temperatures (a flat image gets a 1 K span so it maps to
/// mid-grey rather than dividing by zero).
fn range(t: &[f32]) -> (f64, f64) {
    let (lo, hi) = t
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(f64::from(v)), hi.max(f64::from(v)))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-9 {
        return (lo - 0.5, hi + 0.5);
    }
    (lo, hi)
}

fn unit(v: f32, (lo, hi): (f64, f64)) -> f64 {
    ((f64::from(v) - lo) / (hi - lo)).clamp(0.0, 1.0)
}

/// Apparent temperature stretched linearly over the range `r`, K (black to white).
pub fn grey(
    t: &[f32],
    w: usize,
    h: usize,
    bits: PreviewBits,
    r: (f64, f64),
) -> miette::Result<Vec<u8>> {
    let mut out = Vec::new();
    match bits {
        PreviewBits::Eight => {
            let v: Vec<u8> = t
                .iter()
                .map(|&x| (unit(x, r) * 255.0).round() as u8)
                .collect();
            write_png_gray8(&mut out, w, h, &v).into_diagnostic()?;
        }
        PreviewBits::Sixteen => {
            let v: Vec<u16> = t
                .iter()
                .map(|&x| (unit(x, r) * 65535.0).round() as u16)
                .collect();
            write_png_gray16(&mut out, w, h, &v).into_diagnostic()?;
        }
    }
    Ok(out)
}

const GAP: usize = 6;
const BAR: usize = 16;
const TICK: usize = 4;
/// Blank columns between a tick and its label: three times the two blank columns between
/// the font's characters, so that a tick never reads as a minus sign before the number.
const LABEL_GAP: usize = 6;
pub(crate) const GLYPH: usize = 8;
/// The font's digits and letters are lit on rows 0–6 of their 8 × 8 cell: a label whose
/// cell starts this many rows above its tick is centred on it.
const LABEL_HALF: usize = 3;
/// Blank rows kept between the outermost labels and the canvas's top and bottom edges.
const EDGE: usize = 2;
const MIN_HEIGHT: usize = 64;

/// The five tick labels of the colour bar over `r` (K), bottom to top, with as many
/// decimals as make ticks a quarter of the range apart read differently (at least one, at
/// most three: 1 mK), so a scene spanning 0.08 K is not labelled 300.0K five times.
fn tick_labels(r: (f64, f64)) -> [String; 5] {
    let step = (r.1 - r.0) / 4.0;
    let decimals = (1..=3).find(|&d| step >= 10f64.powi(-d)).unwrap_or(3) as usize;
    std::array::from_fn(|i| {
        let u = i as f64 / 4.0;
        format!("{:.decimals$}K", r.0 + u * (r.1 - r.0))
    })
}

/// The image in the inferno colour map (coldest dark, hottest bright) with, to its right, a
/// vertical colour bar over the range `r`, K, from its low end (bottom) to its high end (top),
/// and five labelled ticks in kelvin. The canvas is at least 64 pixels tall so that labels
/// fit.
pub fn colour_with_bar(t: &[f32], w: usize, h: usize, r: (f64, f64)) -> miette::Result<Vec<u8>> {
    let labels = tick_labels(r);
    let label_chars = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0);
    let cw = w + GAP + BAR + TICK + LABEL_GAP + label_chars * GLYPH + 2;
    let ch = h.max(MIN_HEIGHT);
    let mut rgb = vec![0u8; cw * ch * 3];
    let mut put = |x: usize, y: usize, c: [u8; 3]| {
        if x < cw && y < ch {
            let i = (y * cw + x) * 3;
            rgb[i..i + 3].copy_from_slice(&c);
        }
    };
    let colour = |u: f64| {
        let c = colorous::INFERNO.eval_continuous(u);
        [c.r, c.g, c.b]
    };
    for y in 0..h {
        for x in 0..w {
            let v = t[y * w + x];
            // NaN (no data) shows as mid-grey, outside the colour map.
            let c = if v.is_finite() {
                colour(unit(v, r))
            } else {
                [128, 128, 128]
            };
            put(x, y, c);
        }
    }
    // The bar spans rows top..=bottom, leaving room above and below for the outermost
    // labels, which are centred on the bar's ends, and a margin beyond them.
    let top = EDGE + LABEL_HALF;
    let bottom = ch - 1 - EDGE - LABEL_HALF;
    let x0 = w + GAP;
    for y in top..=bottom {
        let u = (bottom - y) as f64 / (bottom - top) as f64;
        for x in x0..x0 + BAR {
            put(x, y, colour(u));
        }
    }
    let white = [255, 255, 255];
    for (i, label) in labels.iter().enumerate() {
        let u = i as f64 / 4.0;
        let y = bottom - ((bottom - top) as f64 * u).round() as usize;
        for x in x0 + BAR..x0 + BAR + TICK {
            put(x, y, white);
        }
        let lx = x0 + BAR + TICK + LABEL_GAP;
        let ly = y - LABEL_HALF;
        for_each_text_pixel(label, |x, y| put(lx + x, ly + y, white));
    }
    let mut out = Vec::new();
    write_png_rgb8(&mut out, cw, ch, &rgb).into_diagnostic()?;
    Ok(out)
}

/// Calls `lit(x, y)` for every lit pixel of `text` in the 8 × 8 legacy font, `(0, 0)` being
/// the top-left of the first glyph; characters outside it are blank.
pub(crate) fn for_each_text_pixel(text: &str, mut lit: impl FnMut(usize, usize)) {
    for (n, ch) in text.chars().enumerate() {
        let glyph = font8x8::legacy::BASIC_LEGACY
            .get(ch as usize)
            .copied()
            .unwrap_or([0; 8]);
        for (gy, bits) in glyph.iter().enumerate() {
            for gx in 0..GLYPH {
                // Bit 0 is the leftmost pixel of the row.
                if bits >> gx & 1 == 1 {
                    lit(n * GLYPH + gx, gy);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Percentiles by nearest rank, by hand: of 1..=100 K, p1 is 1 and p99 is 99; p0 is the
    /// smallest; NaN pixels are left out; given kelvin are taken as given.
    #[test]
    fn a_preview_range_is_its_limits_or_its_percentiles() {
        let t: Vec<f32> = (1..=100).map(|v| v as f32).chain([f32::NAN]).collect();
        assert_eq!(PreviewRange::Full.of(&t), (1.0, 100.0));
        assert_eq!(
            "p1-p99".parse::<PreviewRange>().unwrap().of(&t),
            (1.0, 99.0)
        );
        assert_eq!(
            "p0-p50".parse::<PreviewRange>().unwrap().of(&t),
            (1.0, 50.0)
        );
        assert_eq!(
            "p10-p100".parse::<PreviewRange>().unwrap().of(&t),
            (10.0, 100.0)
        );
        assert_eq!(
            "280-320".parse::<PreviewRange>().unwrap().of(&t),
            (280.0, 320.0)
        );
        assert_eq!("full".parse::<PreviewRange>().unwrap(), PreviewRange::Full);
        for bad in [
            "320-280", "p99-p1", "p1-99", "p0-p101", "a-b", "300", "nan-300", "-5-10",
        ] {
            assert!(bad.parse::<PreviewRange>().is_err(), "{bad} was taken");
        }
        // A flat percentile range still maps: 1 K wide about it.
        let flat = vec![300.0_f32; 10];
        assert_eq!(
            "p5-p95".parse::<PreviewRange>().unwrap().of(&flat),
            (299.5, 300.5)
        );
    }

    /// A range narrower than the image clips: the pixels below it are black, above white.
    #[test]
    fn pixels_outside_the_preview_range_clip_to_its_ends() {
        let t = [250.0_f32, 290.0, 300.0, 310.0, 350.0];
        let png = grey(&t, 5, 1, PreviewBits::Eight, (290.0, 310.0)).unwrap();
        let img = image::load_from_memory(&png).unwrap().to_luma8();
        let v: Vec<u8> = img.pixels().map(|p| p.0[0]).collect();
        assert_eq!(v, [0, 0, 128, 255, 255]);
    }

    #[test]
    fn tick_labels_resolve_the_range() {
        // 290-310 K: ticks 5 K apart, one decimal.
        assert_eq!(
            tick_labels((290.0, 310.0)),
            ["290.0K", "295.0K", "300.0K", "305.0K", "310.0K"].map(String::from)
        );
        // 0.08 K: ticks 0.02 K apart need two decimals.
        assert_eq!(
            tick_labels((300.0, 300.08)),
            ["300.00K", "300.02K", "300.04K", "300.06K", "300.08K"].map(String::from)
        );
        // 4 mK: three decimals, no more (ticks 1 mK apart).
        assert_eq!(
            tick_labels((300.0, 300.004)),
            ["300.000K", "300.001K", "300.002K", "300.003K", "300.004K"].map(String::from)
        );
        // Hot and wide: every label whole, the canvas grows to fit them.
        assert_eq!(tick_labels((1000.0, 1600.0))[4], "1600.0K");
    }

    /// Whether each pixel of the decoded PNG is white (ticks and labels are the only white).
    fn white_pixels(png: &[u8]) -> (usize, usize, Vec<bool>) {
        let img = image::load_from_memory(png).unwrap().to_rgb8();
        let (w, h) = (img.width() as usize, img.height() as usize);
        let white = img.pixels().map(|p| p.0 == [255, 255, 255]).collect();
        (w, h, white)
    }

    #[test]
    fn ticks_stand_apart_from_their_labels_and_no_label_touches_an_edge() {
        // The quickstart's range, whose top label read as "-321.9K"; an image of 64 rows,
        // the least the bar allows, so the labels are as crowded as they get.
        let (w, h) = (40, 64);
        let t: Vec<f32> = (0..w * h)
            .map(|i| 250.7 + 71.2 * (i / w) as f32 / (h - 1) as f32)
            .collect();
        let (cw, ch, white) = white_pixels(&colour_with_bar(&t, w, h, range(&t)).unwrap());
        let at = |x: usize, y: usize| white[y * cw + x];
        let tick_x = w + GAP + BAR;
        let tick_rows: Vec<usize> = (0..ch).filter(|&y| at(tick_x, y)).collect();
        assert_eq!(tick_rows.len(), 5, "{tick_rows:?}");
        let label_x = tick_x + TICK;
        // Rows of the label drawn beside each tick: the white pixels right of the ticks.
        let label_rows: Vec<usize> = (0..ch)
            .filter(|&y| (label_x..cw).any(|x| at(x, y)))
            .collect();
        for &y in &tick_rows {
            // The tick is TICK pixels long and ends there.
            assert!((tick_x..label_x).all(|x| at(x, y)), "tick at row {y}");
            // Across the whole height of the label beside it, the columns after the tick
            // stay dark for more than the font's two blank columns between characters.
            let first_lit = (y.saturating_sub(GLYPH)..(y + GLYPH).min(ch))
                .filter_map(|row| (label_x..cw).find(|&x| at(x, row)))
                .min()
                .unwrap();
            let gap = first_lit - label_x;
            assert!(
                gap >= 5,
                "tick at row {y}: {gap} dark columns before its label"
            );
        }
        // Every lit pixel of every label's glyphs is on the canvas (none clipped) ...
        let drawn = white.iter().filter(|&&p| p).count() - 5 * TICK;
        let mut expected = 0;
        for label in tick_labels(range(&t)) {
            for_each_text_pixel(&label, |_, _| expected += 1);
        }
        assert_eq!(drawn, expected, "lit label pixels on the canvas");
        // ... and a blank margin separates the top and bottom labels from the edges.
        let (first, last) = (label_rows[0], *label_rows.last().unwrap());
        assert!(first >= 2, "top label starts at row {first}");
        assert!(last <= ch - 3, "bottom label ends at row {last} of {ch}");
    }
}
