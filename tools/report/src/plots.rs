//! The report's plots, drawn by plotters as SVG text: the histogram, the line profile, the
//! LUT curve and the colour bars of the false-colour images. What is computed here is only
//! the data the plots show (bin counts, the colour bar's steps).

use plotters::prelude::*;

/// Width and height of a chart, SVG pixels.
const CHART: (u32, u32) = (640, 360);
/// Width and height of a colour bar, SVG pixels.
const BAR: (u32, u32) = (130, 384);
/// Colour steps drawn in a colour bar.
const BAR_STEPS: usize = 128;
/// Length of an axis's tick marks, SVG pixels. A label sits twice this far from its axis
/// (plotters' rule), so it stands clear of the tick and the axis line instead of touching
/// them, which plotters' default (a tick of a pixel or two) lets it do.
const TICK: i32 = 5;

fn failed(what: &str) -> impl Fn(String) -> miette::Report + '_ {
    move |e| miette::miette!("cannot draw the {what}: {e}")
}

/// The inferno colour of `u` in [0, 1] (coldest dark, hottest bright), as the sensor stage's
/// colour preview draws it.
#[must_use]
pub fn inferno(u: f64) -> [u8; 3] {
    let c = colorous::INFERNO.eval_continuous(u.clamp(0.0, 1.0));
    [c.r, c.g, c.b]
}

/// The range of the finite values, widened to 1 K around a flat image; `None` when no value
/// is finite.
#[must_use]
pub fn finite_range(values: &[f32]) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(f64::from(v)), hi.max(f64::from(v)))
        });
    if !lo.is_finite() {
        return None;
    }
    if hi - lo < 1e-9 {
        return Some((lo - 0.5, hi + 0.5));
    }
    Some((lo, hi))
}

/// How many finite values fall in each of `bins` equal bins over `range` (the last bin
/// closed at the top).
#[must_use]
pub fn bin_counts(values: &[f32], range: (f64, f64), bins: usize) -> Vec<u64> {
    let mut counts = vec![0u64; bins];
    let width = (range.1 - range.0) / bins as f64;
    for &v in values.iter().filter(|v| v.is_finite()) {
        let i = ((f64::from(v) - range.0) / width).floor();
        if i >= 0.0 {
            let i = (i as usize).min(bins - 1);
            counts[i] += 1;
        }
    }
    counts
}

/// A histogram of `values` (K) in `bins` bins over `range`.
///
/// # Errors
/// Only if plotters fails to draw, which it does not for finite ranges.
pub fn histogram(values: &[f32], range: (f64, f64), bins: usize) -> miette::Result<String> {
    let counts = bin_counts(values, range, bins);
    let top = counts.iter().copied().max().unwrap_or(1).max(1) as f64 * 1.05;
    let width = (range.1 - range.0) / bins as f64;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, CHART).into_drawing_area();
        root.fill(&WHITE)
            .map_err(|e| failed("histogram")(e.to_string()))?;
        let mut chart = ChartBuilder::on(&root)
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(64)
            .build_cartesian_2d(range.0..range.1, 0.0..top)
            .map_err(|e| failed("histogram")(e.to_string()))?;
        chart
            .configure_mesh()
            .set_all_tick_mark_size(TICK)
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .disable_x_mesh()
            .x_desc("apparent temperature (K)")
            .y_desc("pixels")
            .y_label_formatter(&|v| format!("{v:.0}"))
            .draw()
            .map_err(|e| failed("histogram")(e.to_string()))?;
        chart
            .draw_series(counts.iter().enumerate().map(|(i, &c)| {
                let x0 = range.0 + i as f64 * width;
                Rectangle::new([(x0, 0.0), (x0 + width, c as f64)], BLUE.mix(0.7).filled())
            }))
            .map_err(|e| failed("histogram")(e.to_string()))?;
        root.present()
            .map_err(|e| failed("histogram")(e.to_string()))?;
    }
    Ok(svg)
}

/// A line chart of `points` (x, y), with axis titles; points with a non-finite y break
/// the line.
///
/// # Errors
/// Only if plotters fails to draw.
pub fn line_chart(
    what: &str,
    points: &[(f64, f64)],
    x_desc: &str,
    y_desc: &str,
) -> miette::Result<String> {
    let finite: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    let span = |v: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
        if !lo.is_finite() {
            (0.0, 1.0)
        } else if hi - lo < 1e-9 {
            (lo - 0.5, hi + 0.5)
        } else {
            let pad = (hi - lo) * 0.03;
            (lo - pad, hi + pad)
        }
    };
    let x = span(&mut finite.iter().map(|p| p.0));
    let y = span(&mut finite.iter().map(|p| p.1));
    let err = failed(what);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, CHART).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let mut chart = ChartBuilder::on(&root)
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(72)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)
            .map_err(|e| err(e.to_string()))?;
        chart
            .configure_mesh()
            .set_all_tick_mark_size(TICK)
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .x_desc(x_desc)
            .y_desc(y_desc)
            .draw()
            .map_err(|e| err(e.to_string()))?;
        // One line per run of finite points, so a gap shows as a gap.
        for run in points.split(|p| !(p.0.is_finite() && p.1.is_finite())) {
            if !run.is_empty() {
                chart
                    .draw_series(LineSeries::new(run.iter().copied(), RED.stroke_width(2)))
                    .map_err(|e| err(e.to_string()))?;
            }
        }
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg)
}

/// A vertical colour bar of the inferno map over `range`, labelled in `unit` on its left.
///
/// # Errors
/// Only if plotters fails to draw.
pub fn colour_bar(range: (f64, f64), unit: &str) -> miette::Result<String> {
    let err = failed("colour bar");
    let step = (range.1 - range.0) / BAR_STEPS as f64;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, BAR).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let mut chart = ChartBuilder::on(&root)
            .margin(10)
            .y_label_area_size(84)
            .build_cartesian_2d(0.0..1.0, range.0..range.1)
            .map_err(|e| err(e.to_string()))?;
        chart
            .draw_series((0..BAR_STEPS).map(|i| {
                let y0 = range.0 + i as f64 * step;
                let [r, g, b] = inferno((i as f64 + 0.5) / BAR_STEPS as f64);
                Rectangle::new([(0.0, y0), (1.0, y0 + step)], RGBColor(r, g, b).filled())
            }))
            .map_err(|e| err(e.to_string()))?;
        let decimals = (0..=4)
            .find(|&d| (range.1 - range.0) / 5.0 >= 10f64.powi(-d))
            .unwrap_or(4) as usize;
        chart
            .configure_mesh()
            .set_tick_mark_size(LabelAreaPosition::Left, TICK)
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .disable_mesh()
            .disable_x_axis()
            .y_labels(6)
            .y_desc(unit)
            .y_label_formatter(&|v| format!("{v:.decimals$}"))
            .draw()
            .map_err(|e| err(e.to_string()))?;
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bins_count_every_finite_value_once() {
        // 0..=9 in 5 bins of width 1.8 over [0, 9]: 0 1 | 2 3 | 4 5 | 6 7 | 8 9.
        let v: Vec<f32> = (0..10).map(|i| i as f32).chain([f32::NAN]).collect();
        assert_eq!(bin_counts(&v, (0.0, 9.0), 5), vec![2, 2, 2, 2, 2]);
        assert_eq!(finite_range(&v), Some((0.0, 9.0)));
        assert_eq!(finite_range(&[f32::NAN]), None);
        assert_eq!(finite_range(&[3.0, 3.0]), Some((2.5, 3.5)));
    }

    #[test]
    fn charts_are_svg_with_their_axis_titles() {
        let h = histogram(&[290.0, 291.0, 291.5], (290.0, 292.0), 4).unwrap();
        assert!(h.starts_with("<svg") && h.contains("apparent temperature (K)"));
        let l = line_chart("test", &[(0.0, 1.0), (1.0, f64::NAN), (2.0, 3.0)], "a", "b").unwrap();
        assert!(l.contains("<polyline") || l.contains("<path"));
        let b = colour_bar((290.0, 300.0), "K").unwrap();
        assert!(b.contains("300"));
    }
}
