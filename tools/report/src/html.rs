//! The page's small parts: images as data URIs, the false-colour map and its range, the
//! profile's overlay and the tables' number formats.

use maud::{Markup, html};

use super::*;

pub(crate) fn layer<'a>(image: &'a Raster, name: &str, layer: &str) -> miette::Result<&'a [f32]> {
    image
        .layer(layer)
        .map(|l| l.data.as_slice())
        .ok_or_else(|| {
            let names: Vec<&str> = image.layers.iter().map(|l| l.name.as_str()).collect();
            miette!(
                "{name}: no layer `{layer}` (it has: {}); expected the tracer's truth EXR \
                 (`{APPARENT_LAYER}`, `{MATERIAL_LAYER}`) or, for --radiance, an image with \
                 `{RADIANCE_LAYER}`",
                names.join(", ")
            )
        })
}

/// Displayed images are enlarged by a whole factor (pixels stay square and sharp) to be
/// at least this many CSS pixels tall, like the colour bar beside them.
pub(crate) const DISPLAY_HEIGHT: usize = 360;

/// A PNG as an `<img>` with a `data:` URI, shown enlarged by a whole factor.
pub(crate) fn img(id: &str, png: &[u8], width: usize, height: usize, alt: &str) -> Markup {
    let scale = display_scale(height);
    let data = base64::engine::general_purpose::STANDARD.encode(png);
    html! {
        img id=(id) width=(width * scale) height=(height * scale) alt=(alt)
            src={ "data:image/png;base64," (data) };
    }
}

/// The values in the inferno map over `range` as an RGB PNG (no finite value: black).
pub(crate) fn false_colour(
    values: &[f32],
    width: usize,
    height: usize,
    range: (f64, f64),
) -> Vec<u8> {
    let rgb: Vec<u8> = values
        .iter()
        .flat_map(|&v| {
            if v.is_finite() {
                plots::inferno((f64::from(v) - range.0) / (range.1 - range.0))
            } else {
                [0, 0, 0]
            }
        })
        .collect();
    let mut png = Vec::new();
    // Writing into memory fails only on a size mismatch, which the caller rules out.
    let _ = irsig_raster::write_png_rgb8(&mut png, width, height, &rgb);
    png
}

/// The smallest and largest finite values (infinite when there is none).
pub(crate) fn extremes(values: &[f32]) -> (f64, f64) {
    values
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(f64::from(v)), hi.max(f64::from(v)))
        })
}

/// Mean of the finite values.
pub(crate) fn finite_mean(values: &[f32]) -> f64 {
    let (sum, n) = values
        .iter()
        .filter(|v| v.is_finite())
        .fold((0.0, 0usize), |(s, n), &v| (s + f64::from(v), n + 1));
    if n == 0 { f64::NAN } else { sum / n as f64 }
}

/// The whole factor a displayed image is enlarged by.
pub(crate) fn display_scale(height: usize) -> usize {
    DISPLAY_HEIGHT.div_ceil(height.max(1)).max(1)
}

/// The profile's line drawn over an image of `width` × `height` pixels shown at `scale`:
/// an SVG of the image's displayed size laid on it, its user units the image's pixels, the
/// line from the centre of the start pixel to the centre of the end pixel, dark under light
/// so that it shows on every colour of the map, a ring at the start. Its elements are
/// closed by end tags, as SVG inside HTML needs.
pub(crate) fn profile_overlay(
    line: &ProfileLine,
    width: usize,
    height: usize,
    scale: usize,
) -> Markup {
    let (x0, y0) = (line.from.0 as f64 + 0.5, line.from.1 as f64 + 0.5);
    let (x1, y1) = (line.to.0 as f64 + 0.5, line.to.1 as f64 + 0.5);
    // Strokes in display pixels, whatever the enlargement.
    let px = 1.0 / scale as f64;
    let (outer, inner, ring) = (4.0 * px, 2.0 * px, 5.0 * px);
    html! {
        svg id="profile-overlay" class="overlay" width=(width * scale) height=(height * scale)
            viewBox={ "0 0 " (width) " " (height) } xmlns="http://www.w3.org/2000/svg" {
            title {
                "the line profile, from (" (line.from.0) ", " (line.from.1) ") to ("
                (line.to.0) ", " (line.to.1) ")"
            }
            line x1=(x0) y1=(y0) x2=(x1) y2=(y1) stroke="#000000" stroke-width=(outer)
                stroke-linecap="round" {}
            line id="profile-line" x1=(x0) y1=(y0) x2=(x1) y2=(y1) stroke="#00e5ff"
                stroke-width=(inner) stroke-linecap="round" {}
            circle cx=(x0) cy=(y0) r=(ring) fill="none" stroke="#00e5ff"
                stroke-width=(inner) {}
        }
    }
}

/// A share as a percentage with enough decimals to tell a few pixels from none.
pub(crate) fn percent(part: usize, whole: usize) -> String {
    if whole == 0 {
        return "0".into();
    }
    let p = 100.0 * part as f64 / whole as f64;
    if part == 0 || p >= 1.0 {
        format!("{p:.2}")
    } else {
        format!("{p:.4}")
    }
}

/// Who a declared temperature uncertainty is about, in words.
pub(crate) fn facets(f: &Facets) -> String {
    match f {
        Facets::All => "every facet".into(),
        Facets::Material(m) => format!("facets of material {}", m.0),
        Facets::Object(o) => format!("facets of object `{o}`"),
    }
}

/// The declared uncertainties as a table: what, of whom, one σ.
pub(crate) fn declared_table(u: &Uncertainties) -> Markup {
    html! {
        table id="declared" {
            thead { tr { th { "quantity" } th { "of" } th { "σ" } } }
            tbody {
                @for t in &u.temperature {
                    tr {
                        td { "kinetic temperature" }
                        td { (facets(&t.facets)) }
                        td class="num" { (short(t.sigma_k)) " K" }
                    }
                }
                @if u.temperature.is_empty() {
                    tr { td { "kinetic temperature" } td { "none declared" } td {} }
                }
                @for e in &u.emissivity {
                    tr {
                        td { "emissivity" }
                        td { "material " (e.material.0) }
                        td class="num" { (short(e.sigma)) }
                    }
                }
                @if u.emissivity.is_empty() {
                    tr { td { "emissivity" } td { "none declared" } td {} }
                }
                tr {
                    td { "atmospheric transmission" }
                    td { "relative" }
                    td class="num" { (short(100.0 * u.transmission_relative)) " %" }
                }
                tr {
                    td { "path and sky radiance" }
                    td { "relative" }
                    td class="num" { (short(100.0 * u.path_radiance_relative)) " %" }
                }
            }
        }
    }
}

/// A number with at most six decimals, trailing zeros dropped (`100 × 0.05` is 5, not
/// 5.000000000000001).
pub(crate) fn short(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s.is_empty() || s == "-" || s == "-0" {
        "0".into()
    } else {
        s.to_owned()
    }
}
