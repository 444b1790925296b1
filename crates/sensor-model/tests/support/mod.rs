//! The slanted-edge MTF measurement of ISO 12233 (ISO 12233:2017, *Photography —
//! Electronic still picture imaging — Resolution and spatial frequency responses*, §6
//! "edge-based spatial frequency response", the e-SFR method that the sfrmat programs
//! implement): an independent way to check that the blur applies the MTF it was asked for.
//!
//! Steps, as in the standard:
//! 1. locate the edge in every row: the centroid of the row's derivative;
//! 2. fit a straight line to those centroids (the edge is slanted a few degrees so that the
//!    pixels' distances to it fall at all sub-pixel phases);
//! 3. project every pixel onto the edge normal and average the values in bins of a quarter
//!    pixel: the 4× oversampled edge-spread function (ESF);
//! 4. differentiate (central difference) to the line-spread function (LSF), apply a Hamming
//!    window centred on it;
//! 5. |DFT|, normalised to 1 at zero frequency, corrected for the central difference's
//!    own transfer sin(2πfΔ)/(2πfΔ) and for the quarter-pixel binning, sinc(fΔ).
//!
//! Frequencies are in cycles per pixel measured along the edge normal.

use std::f64::consts::PI;

/// An image of a straight edge, 0 on one side and 1 on the other, sampled at pixel centres
/// (point samples: the edge itself adds no blur). The edge passes through (cx, cy); its
/// normal points at `normal_deg` from +x towards +y.
pub fn edge_image(width: usize, height: usize, normal_deg: f64) -> Vec<f64> {
    let (s, c) = normal_deg.to_radians().sin_cos();
    // An irrational offset keeps every pixel centre off the edge.
    let (cx, cy) = (
        width as f64 / 2.0 + 0.123_456,
        height as f64 / 2.0 + 0.271_828,
    );
    (0..width * height)
        .map(|i| {
            let (x, y) = ((i % width) as f64, (i / width) as f64);
            if (x - cx) * c + (y - cy) * s > 0.0 {
                1.0
            } else {
                0.0
            }
        })
        .collect()
}

/// Transposes an image, so that a near-horizontal edge can be measured as a near-vertical
/// one.
pub fn transpose(data: &[f64], width: usize, height: usize) -> Vec<f64> {
    let mut out = vec![0.0; data.len()];
    for y in 0..height {
        for x in 0..width {
            out[x * height + y] = data[y * width + x];
        }
    }
    out
}

/// The measured MTF of a near-vertical edge (normal within ~±10° of +x) in the region
/// `x0..x1`, `y0..y1`, as (frequency in cycles per pixel, MTF) pairs up to `f_max`.
pub fn slanted_edge_mtf(
    data: &[f64],
    width: usize,
    (x0, x1): (usize, usize),
    (y0, y1): (usize, usize),
    f_max: f64,
) -> Vec<(f64, f64)> {
    // 1. Edge centroid per row from the derivative [-1, 1]... of the row.
    let mut rows = Vec::new();
    for y in y0..y1 {
        let row = &data[y * width..(y + 1) * width];
        let (mut num, mut den) = (0.0, 0.0);
        for x in x0..x1 - 1 {
            let d = row[x + 1] - row[x];
            num += d * (x as f64 + 0.5);
            den += d;
        }
        rows.push((y as f64, num / den));
    }
    // 2. Least-squares line x = a + b·y.
    let n = rows.len() as f64;
    let (sy, sx) = rows
        .iter()
        .fold((0.0, 0.0), |(a, b), (y, x)| (a + y, b + x));
    let (my, mx) = (sy / n, sx / n);
    let (mut syy, mut sxy) = (0.0, 0.0);
    for (y, x) in &rows {
        syy += (y - my) * (y - my);
        sxy += (y - my) * (x - mx);
    }
    let b = sxy / syy;
    let a = mx - b * my;
    let cos = 1.0 / (1.0 + b * b).sqrt();

    // 3. Project onto the normal and bin at Δ = 1/4 pixel.
    const BINS_PER_PIXEL: f64 = 4.0;
    let delta = 1.0 / BINS_PER_PIXEL;
    let half = ((x1 - x0) as f64 / 2.0 - 2.0) * cos;
    let nbins = (2.0 * half * BINS_PER_PIXEL) as usize;
    let mut sum = vec![0.0; nbins];
    let mut count = vec![0usize; nbins];
    for y in y0..y1 {
        let edge_x = a + b * y as f64;
        for x in x0..x1 {
            let d = (x as f64 - edge_x) * cos + half;
            if d >= 0.0 {
                let i = (d * BINS_PER_PIXEL) as usize;
                if i < nbins {
                    sum[i] += data[y * width + x];
                    count[i] += 1;
                }
            }
        }
    }
    assert!(
        count.iter().all(|&c| c > 0),
        "a quarter-pixel bin is empty: slant the edge more or use more rows"
    );
    let esf: Vec<f64> = sum.iter().zip(&count).map(|(s, &c)| s / c as f64).collect();

    // 4. LSF by central difference, Hamming window about its centroid.
    let mut lsf = vec![0.0; nbins];
    for i in 1..nbins - 1 {
        lsf[i] = (esf[i + 1] - esf[i - 1]) / 2.0;
    }
    let total: f64 = lsf.iter().sum();
    let centre = lsf
        .iter()
        .enumerate()
        .map(|(i, v)| i as f64 * v)
        .sum::<f64>()
        / total;
    let span = nbins as f64;
    for (i, v) in lsf.iter_mut().enumerate() {
        let t = (i as f64 - centre) / span;
        *v *= 0.54 + 0.46 * (2.0 * PI * t).cos();
    }

    // 5. |DFT| normalised at 0, with the two corrections.
    let dc: f64 = lsf.iter().sum();
    let mut out = Vec::new();
    let mut k = 0_usize;
    loop {
        let f = k as f64 / (nbins as f64 * delta);
        if f > f_max + 1e-12 {
            break;
        }
        let (mut re, mut im) = (0.0, 0.0);
        for (i, v) in lsf.iter().enumerate() {
            let phase = -2.0 * PI * k as f64 * i as f64 / nbins as f64;
            re += v * phase.cos();
            im += v * phase.sin();
        }
        let derivative = sinc(2.0 * f * delta);
        let binning = sinc(f * delta);
        out.push((f, (re.hypot(im) / dc) / (derivative * binning)));
        k += 1;
    }
    out
}

fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-12 {
        1.0
    } else {
        (PI * x).sin() / (PI * x)
    }
}
