//! Applying an MTF chain to an image: by FFT for any chain, directly for a small kernel.
//!
//! The FFT path pads the image by the reach of the point-spread function on every side
//! (filled according to the [`EdgeMode`]), grows it to a size whose factors are 2, 3 and 5,
//! multiplies its spectrum by the chain's OTF and transforms back. With that padding the
//! result is the linear convolution with the chosen edge extension, the same (to rounding)
//! as [`convolve_direct`] for a kernel of taps.
//!
//! Every row and every column is transformed independently of the others with the same
//! plan, so the result is bit-identical at any number of rayon threads.

use irsig_fft::{Complex, Complex64, Float, Plans2d};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

use crate::Plane;
use crate::error::{Result, SensorError};
use crate::mtf::{Axis, Kernel, Mtf, MtfChain};

/// How the image is continued beyond its edges.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum EdgeMode {
    /// Mirror the image about its edge, repeating the edge pixel (… c b a | a b c …). A
    /// uniform image stays uniform and no dark or bright border appears. The default.
    #[default]
    Reflect,
    /// Zero radiance beyond the edge: edge pixels darken as the blur mixes in nothing.
    Zero,
    /// The image repeats periodically (the right edge continues at the left).
    Wrap,
}

impl EdgeMode {
    /// The index inside `0..n` that outside index `i` takes its value from, or `None`
    /// for a zero.
    fn source(self, i: isize, n: usize) -> Option<usize> {
        let n_i = n as isize;
        match self {
            Self::Wrap => Some(i.rem_euclid(n_i) as usize),
            Self::Zero => (0..n_i).contains(&i).then_some(i as usize),
            Self::Reflect => {
                let period = 2 * n_i;
                let m = i.rem_euclid(period);
                Some(if m < n_i { m } else { period - 1 - m } as usize)
            }
        }
    }
}

/// The smallest length ≥ `n` whose only prime factors are 2, 3 and 5 (fast FFT sizes).
fn fast_len(n: usize) -> usize {
    let mut m = n.max(1);
    loop {
        let mut r = m;
        for p in [2, 3, 5] {
            while r % p == 0 {
                r /= p;
            }
        }
        if r == 1 {
            return m;
        }
        m += 1;
    }
}

/// Blurs `image` by the chain's OTF, using the FFT.
///
/// `samples_per_pixel` says how finely the image is sampled: the chain's frequencies are
/// in cycles per *sensor* pixel, and an image rendered at k samples per sensor pixel (to
/// be reduced later by [`crate::sample::reduce_mean`]) has its Nyquist at k/2 of them.
///
/// # Errors
/// An empty image, an invalid chain, or `samples_per_pixel` of 0.
pub fn blur(
    image: &Plane,
    chain: &MtfChain,
    edge: EdgeMode,
    samples_per_pixel: u32,
) -> Result<Plane> {
    blur_with_precision(image, chain, edge, samples_per_pixel, Precision::Double)
}

/// The arithmetic of the FFTs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Precision {
    /// f64 throughout: agrees with direct convolution to ~1e-15 relative.
    #[default]
    Double,
    /// f32 FFTs (about twice as fast). The image mean is removed in f64 before and restored
    /// after, so a uniform image and the mean stay exact with reflect or wrap edges; the
    /// detail (and, with zero edges, the border step) carries f32 rounding of about ten
    /// ulps, ~1e-6 relative, against the f32 ulp (6e-8) the images are stored with.
    Single,
}

/// [`blur`] with a choice of FFT arithmetic.
///
/// # Errors
/// As [`blur`].
pub fn blur_with_precision(
    image: &Plane,
    chain: &MtfChain,
    edge: EdgeMode,
    samples_per_pixel: u32,
    precision: Precision,
) -> Result<Plane> {
    match precision {
        Precision::Double => blur_generic::<f64>(image, chain, edge, samples_per_pixel),
        Precision::Single => blur_generic::<f32>(image, chain, edge, samples_per_pixel),
    }
}

/// Conversions the generic FFT path needs.
trait Sample: Float + Into<f64> {
    fn of(v: f64) -> Self;
}
impl Sample for f64 {
    fn of(v: f64) -> Self {
        v
    }
}
impl Sample for f32 {
    fn of(v: f64) -> Self {
        v as f32
    }
}

/// Blurs `image` by the chain's OTF with FFTs in `T`: pads it, filters its spectrum, and
/// crops the padding.
fn blur_generic<T: Sample>(
    image: &Plane,
    chain: &MtfChain,
    edge: EdgeMode,
    samples_per_pixel: u32,
) -> Result<Plane> {
    image.check()?;
    chain.validate()?;
    if samples_per_pixel == 0 {
        return Err(SensorError::parameter(
            "samples_per_pixel",
            0.0,
            "at least 1",
        ));
    }
    if chain.components.is_empty() {
        return Ok(image.clone());
    }
    let grid = Grid::new(image, chain, edge, samples_per_pixel);

    // The mean goes around the FFTs in f64: blurring a constant gives the constant (the
    // OTF is 1 at zero frequency), so this is exact, and the FFTs carry only the detail.
    let mean = image.data.iter().sum::<f64>() / image.data.len() as f64;
    let plans = T::plans_2d(grid.pw, grid.ph);

    // 1. Pad each row and transform it (rows are independent).
    let rows = forward_rows(image, &grid, edge, mean, &plans);

    // 2. Transpose so each frequency column is contiguous, filter it, transpose back.
    let mut cols = transpose(&rows, grid.ph, grid.spectrum_w);
    drop(rows);
    filter_columns(&mut cols, &grid, chain, samples_per_pixel, &plans);
    let mut rows = transpose(&cols, grid.spectrum_w, grid.ph);
    drop(cols);

    // 3. Transform rows back and crop the padding.
    let out = inverse_rows(&mut rows, &grid, mean, &plans);
    Ok(Plane {
        width: grid.w,
        height: grid.h,
        data: out,
    })
}

/// The padded image the FFTs work on: the image's size, its margins on each side, the
/// padded size and the length of a row's half spectrum.
struct Grid {
    w: usize,
    h: usize,
    mx: usize,
    my: usize,
    pw: usize,
    ph: usize,
    spectrum_w: usize,
    /// Samples per sensor pixel, as a float.
    s: f64,
}

impl Grid {
    /// The grid of `image` padded by the reach of `chain`'s point-spread function on every
    /// side (none for wrapped edges), grown to fast FFT sizes.
    fn new(image: &Plane, chain: &MtfChain, edge: EdgeMode, samples_per_pixel: u32) -> Self {
        let (w, h) = (image.width, image.height);
        let s = f64::from(samples_per_pixel);
        let (rx, ry) = chain.support_radius_px(samples_per_pixel);
        // Beyond one image width a reflected or wrapped margin only repeats itself, and a
        // zero margin that wide already keeps the wrapped tails off the image.
        let margin = |r: f64, n: usize| -> usize {
            let m = (r * s).ceil();
            if m.is_finite() && m < (2 * n) as f64 {
                m as usize
            } else {
                2 * n
            }
        };
        let (mx, my, pw, ph) = match edge {
            EdgeMode::Wrap => (0, 0, w, h),
            EdgeMode::Reflect | EdgeMode::Zero => {
                let mx = margin(rx, w);
                let my = margin(ry, h);
                (mx, my, fast_len(w + 2 * mx), fast_len(h + 2 * my))
            }
        };
        Self {
            w,
            h,
            mx,
            my,
            pw,
            ph,
            spectrum_w: pw / 2 + 1,
            s,
        }
    }

    /// The horizontal frequency of spectrum column `u`, cycles per sensor pixel.
    fn fx(&self, u: usize) -> f64 {
        u as f64 / self.pw as f64 * self.s
    }

    /// The vertical frequency of spectrum row `v` (the upper half negative), cycles per
    /// sensor pixel.
    fn fy(&self, v: usize) -> f64 {
        let vf = if v <= self.ph / 2 {
            v as f64
        } else {
            v as f64 - self.ph as f64
        };
        vf / self.ph as f64 * self.s
    }
}

/// The half spectrum of every padded row of `image` less `mean`, the rows one after the
/// other, each `grid.spectrum_w` long.
fn forward_rows<T: Sample>(
    image: &Plane,
    grid: &Grid,
    edge: EdgeMode,
    mean: f64,
    plans: &Plans2d<T>,
) -> Vec<Complex<T>> {
    let (w, pw, spectrum_w) = (grid.w, grid.pw, grid.spectrum_w);
    // Columns of the padded image that come from each source column (or zero).
    let col_src: Vec<Option<usize>> = (0..pw)
        .map(|c| edge.source(c as isize - grid.mx as isize, w))
        .collect();
    let row_src: Vec<Option<usize>> = (0..grid.ph)
        .map(|r| edge.source(r as isize - grid.my as isize, grid.h))
        .collect();
    let row_forward = &plans.row_forward;
    let mut rows = vec![Complex::new(T::zero(), T::zero()); grid.ph * spectrum_w];
    rows.par_chunks_mut(spectrum_w)
        .zip(row_src.par_iter())
        .for_each_init(
            || (vec![T::zero(); pw], row_forward.make_scratch_vec()),
            |(line, scratch), (out, src)| {
                match src {
                    Some(r) => {
                        let source = &image.data[r * w..(r + 1) * w];
                        for (dst, c) in line.iter_mut().zip(&col_src) {
                            *dst = T::of(c.map_or(0.0, |c| source[c]) - mean);
                        }
                    }
                    None => line.fill(T::of(-mean)),
                }
                // The lengths match the plan by construction.
                let _ = row_forward.process_with_scratch(line, out, scratch);
            },
        );
    rows
}

/// Filters each frequency column of `cols` (`grid.ph` long, one per spectrum column) by
/// the chain's OTF: transformed, multiplied, and transformed back.
fn filter_columns<T: Sample>(
    cols: &mut [Complex<T>],
    grid: &Grid,
    chain: &MtfChain,
    samples_per_pixel: u32,
    plans: &Plans2d<T>,
) {
    let (ph, spectrum_w) = (grid.ph, grid.spectrum_w);
    let fy_of = |v: usize| grid.fy(v);
    // Separable components are tabulated once per spectrum column (x) and row (y); the
    // rest are evaluated at every frequency. The 1/(pw·ph) of the inverse transforms is
    // folded into the x table.
    let norm = 1.0 / (grid.pw as f64 * ph as f64);
    let (separable, other): (Vec<&Mtf>, Vec<&Mtf>) = chain
        .components
        .iter()
        .partition(|m| m.separable_otf(0.0, Axis::X, samples_per_pixel).is_some());
    let other: Vec<PreparedOtf<'_>> = other
        .into_iter()
        .map(|m| PreparedOtf::new(m, samples_per_pixel, &fy_of, ph))
        .collect();
    let table = |n: usize, freq: &dyn Fn(usize) -> f64, axis: Axis, scale: f64| -> Vec<Complex64> {
        (0..n)
            .map(|i| {
                separable.iter().fold(Complex64::new(scale, 0.0), |acc, m| {
                    acc * m
                        .separable_otf(freq(i), axis, samples_per_pixel)
                        .unwrap_or(Complex64::new(1.0, 0.0))
                })
            })
            .collect()
    };
    let table_x = table(spectrum_w, &|u| grid.fx(u), Axis::X, norm);
    let table_y = table(ph, &fy_of, Axis::Y, 1.0);
    let (col_forward, col_inverse) = (&plans.col_forward, &plans.col_inverse);
    let scratch_len = col_forward
        .get_inplace_scratch_len()
        .max(col_inverse.get_inplace_scratch_len());
    let zero = Complex::new(T::zero(), T::zero());
    cols.par_chunks_mut(ph).enumerate().for_each_init(
        || vec![zero; scratch_len],
        |scratch, (u, column)| {
            col_forward.process_with_scratch(column, scratch);
            let hx = table_x[u];
            let fx = grid.fx(u);
            for (v, (value, hy)) in column.iter_mut().zip(&table_y).enumerate() {
                let mut h = hx * hy;
                for m in &other {
                    h *= m.at(fx, fy_of(v), v);
                }
                *value = *value * Complex::new(T::of(h.re), T::of(h.im));
            }
            col_inverse.process_with_scratch(column, scratch);
        },
    );
}

/// The image from the filtered half spectra `rows`: each row transformed back, cropped to
/// the image, and `mean` restored.
fn inverse_rows<T: Sample>(
    rows: &mut [Complex<T>],
    grid: &Grid,
    mean: f64,
    plans: &Plans2d<T>,
) -> Vec<f64> {
    let (w, pw, mx, spectrum_w) = (grid.w, grid.pw, grid.mx, grid.spectrum_w);
    let row_inverse = &plans.row_inverse;
    let mut out = vec![0.0_f64; w * grid.h];
    out.par_chunks_mut(w)
        .enumerate()
        .zip(rows.par_chunks_mut(spectrum_w).skip(grid.my).take(grid.h))
        .for_each_init(
            || (vec![T::zero(); pw], row_inverse.make_scratch_vec()),
            |(line, scratch), ((_, dst), spectrum)| {
                // The output is real: the imaginary parts that must vanish are rounding.
                spectrum[0].im = T::zero();
                if pw % 2 == 0 {
                    spectrum[spectrum_w - 1].im = T::zero();
                }
                let _ = row_inverse.process_with_scratch(spectrum, line, scratch);
                for (d, &v) in dst.iter_mut().zip(&line[mx..mx + w]) {
                    *d = v.into() + mean;
                }
            },
        );
    out
}

/// A non-separable model with its constants worked out once, for evaluation at every
/// frequency of the spectrum.
enum PreparedOtf<'a> {
    /// The radial diffraction MTF, tabulated in ν = f/f_c (see [`DiffractionTable`]).
    Diffraction { scale: f64, table: DiffractionTable },
    /// sinc(fx·`ax` + fy·`ay`), with sin(π fy ay) and cos(π fy ay) tabulated per
    /// spectrum row so that only products remain per frequency.
    Motion {
        ax: f64,
        ay: f64,
        row_sin_cos: Vec<(f64, f64)>,
    },
    /// Anything else, evaluated through [`Mtf::otf`].
    General {
        model: &'a Mtf,
        samples_per_pixel: u32,
    },
}

impl<'a> PreparedOtf<'a> {
    fn new(model: &'a Mtf, samples_per_pixel: u32, fy: &dyn Fn(usize) -> f64, rows: usize) -> Self {
        match model {
            Mtf::Diffraction {
                wavelength_m,
                f_number,
                pixel_pitch_m,
            } => Self::Diffraction {
                scale: wavelength_m * f_number / pixel_pitch_m,
                table: DiffractionTable::new(),
            },
            Mtf::Motion {
                length_px,
                angle_deg,
            } => {
                let (sin, cos) = angle_deg.to_radians().sin_cos();
                let ay = length_px * sin;
                Self::Motion {
                    ax: length_px * cos,
                    ay,
                    row_sin_cos: (0..rows).map(|v| (PI * fy(v) * ay).sin_cos()).collect(),
                }
            }
            _ => Self::General {
                model,
                samples_per_pixel,
            },
        }
    }

    /// `Mtf::otf` at (fx, fy(v)), the frequency of spectrum row `v`.
    fn at(&self, fx: f64, fy: f64, v: usize) -> Complex64 {
        match self {
            Self::Diffraction { scale, table } => {
                Complex64::new(table.at((fx * fx + fy * fy).sqrt() * scale), 0.0)
            }
            Self::Motion {
                ax,
                ay,
                row_sin_cos,
            } => {
                let x = fx * ax + fy * ay;
                if x.abs() < 1e-8 {
                    return Complex64::new(crate::mtf::sinc(x), 0.0);
                }
                // sin(a + b) with a from the column and b from the row.
                let (sa, ca) = (PI * fx * ax).sin_cos();
                let (sb, cb) = row_sin_cos[v];
                Complex64::new((sa * cb + ca * sb) / (PI * x), 0.0)
            }
            Self::General {
                model,
                samples_per_pixel,
            } => model.otf(fx, fy, *samples_per_pixel),
        }
    }
}

/// The diffraction MTF tabulated on 2^16 + 1 equal steps of ν in [0, 1] and interpolated
/// linearly: acos at every frequency of a 4096² spectrum costs as much as the FFT. With
/// step h the error is at most h²/8·|M''|; |M''| = (4/π)ν/√(1−ν²) is about 2 over most
/// of the range and grows only near the cut-off, where M itself vanishes as (1−ν)^3/2,
/// so the error stays below 2e-8 everywhere (1.06e-8 at worst, next to the cut-off) — far under the f32 precision the images are
/// stored in (tested up to the cut-off).
struct DiffractionTable {
    values: Vec<f64>,
}

impl DiffractionTable {
    const STEPS: usize = 1 << 16;

    fn new() -> Self {
        Self {
            values: (0..=Self::STEPS)
                .map(|i| crate::mtf::diffraction_mtf(i as f64 / Self::STEPS as f64))
                .collect(),
        }
    }

    fn at(&self, nu: f64) -> f64 {
        if nu >= 1.0 {
            return 0.0;
        }
        let x = nu * Self::STEPS as f64;
        let i = x as usize;
        let t = x - i as f64;
        match (self.values.get(i), self.values.get(i + 1)) {
            (Some(a), Some(b)) => a + (b - a) * t,
            _ => 0.0,
        }
    }
}

/// Transposes a `rows` × `cols` row-major matrix, in cache-sized tiles, in parallel over
/// output rows.
fn transpose<T: Sample>(src: &[Complex<T>], rows: usize, cols: usize) -> Vec<Complex<T>> {
    const TILE: usize = 32;
    let mut dst = vec![Complex::new(T::zero(), T::zero()); rows * cols];
    dst.par_chunks_mut(rows * TILE)
        .enumerate()
        .for_each(|(tile_index, block)| {
            let c0 = tile_index * TILE;
            let tile_cols = block.len() / rows;
            for r0 in (0..rows).step_by(TILE) {
                let r1 = (r0 + TILE).min(rows);
                for dc in 0..tile_cols {
                    let c = c0 + dc;
                    let out = &mut block[dc * rows..(dc + 1) * rows];
                    for r in r0..r1 {
                        out[r] = src[r * cols + c];
                    }
                }
            }
        });
    dst
}

/// Convolves `image` with a kernel of taps directly, continuing the image beyond its
/// edges by `edge`. For small kernels; the reference the FFT path is tested against.
///
/// # Errors
/// An empty image or an invalid kernel.
pub fn convolve_direct(image: &Plane, kernel: &Kernel, edge: EdgeMode) -> Result<Plane> {
    image.check()?;
    crate::mtf::Mtf::Kernel(kernel.clone()).validate()?;
    let (w, h) = (image.width, image.height);
    let mut out = vec![0.0_f64; w * h];
    out.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, value) in row.iter_mut().enumerate() {
            let mut acc = 0.0;
            for j in 0..kernel.height {
                let dy = j as isize + kernel.origin_y();
                let Some(sy) = edge.source(y as isize - dy, h) else {
                    continue;
                };
                for i in 0..kernel.width {
                    let dx = i as isize + kernel.origin_x();
                    if let Some(sx) = edge.source(x as isize - dx, w) {
                        acc += kernel.taps[j * kernel.width + i] * image.data[sy * w + sx];
                    }
                }
            }
            *value = acc;
        }
    });
    Ok(Plane {
        width: w,
        height: h,
        data: out,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pseudo_random_plane(w: usize, h: usize, seed: u64) -> Plane {
        // A fixed linear congruential sequence: varied pixels, no dependency.
        let mut state = seed;
        let data = (0..w * h)
            .map(|_| {
                state = state
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                (state >> 11) as f64 / (1u64 << 53) as f64 * 10.0 + 1.0
            })
            .collect();
        Plane::new(w, h, data).unwrap()
    }

    #[test]
    fn prepared_models_agree_with_the_definitions() {
        let models = [
            Mtf::Diffraction {
                wavelength_m: 11e-6,
                f_number: 1.7,
                pixel_pitch_m: 15e-6,
            },
            Mtf::Motion {
                length_px: 2.5,
                angle_deg: 117.0,
            },
        ];
        let rows = 64;
        let fy = |v: usize| (v as f64 - 32.0) / 64.0;
        for m in &models {
            let p = PreparedOtf::new(m, 1, &fy, rows);
            for v in 0..rows {
                for u in 0..=40 {
                    let fx = f64::from(u) / 80.0 * 1.3;
                    let (a, b) = (p.at(fx, fy(v), v), m.otf(fx, fy(v), 1));
                    assert!(
                        (a - b).norm() < 1e-9,
                        "{m:?} at ({fx}, {}): {a} vs {b}",
                        fy(v)
                    );
                }
            }
        }
        // The table right at and around the cut-off.
        let t = DiffractionTable::new();
        for i in 0..=2000 {
            let nu = 0.9990 + f64::from(i) * 1e-6;
            let exact = crate::mtf::diffraction_mtf(nu);
            assert!((t.at(nu) - exact).abs() < 2e-8, "ν = {nu}");
        }
    }

    #[test]
    fn single_precision_keeps_the_mean_exactly_and_the_detail_to_f32_rounding() {
        let image = pseudo_random_plane(50, 30, 9);
        let chain = MtfChain::new(vec![
            Mtf::Box {
                width_px: 3,
                height_px: 3,
            },
            Mtf::Gaussian { sigma_px: 0.9 },
        ]);
        let double = blur(&image, &chain, EdgeMode::Reflect, 1).unwrap();
        let single =
            blur_with_precision(&image, &chain, EdgeMode::Reflect, 1, Precision::Single).unwrap();
        // Pixels span 1..11: contrast 10; f32 rounding through two FFTs of ~60 points.
        for (a, b) in single.data.iter().zip(&double.data) {
            assert!((a - b).abs() < 1e-5, "{a} vs {b}");
        }
        let level = 47.123_456_789;
        let flat = Plane::new(40, 40, vec![level; 1600]).unwrap();
        let out = blur_with_precision(&flat, &chain, EdgeMode::Zero, 1, Precision::Single).unwrap();
        // With zero edges the FFTs carry the border's step, so the interior of a flat
        // image is the level to f32 rounding only.
        let v = out.data[20 * 40 + 20];
        assert!(((v - level) / level).abs() < 1e-5, "{v} vs {level}");
        // With reflect edges a flat image stays flat to f64 precision: the mean went
        // around the f32 FFTs.
        let out =
            blur_with_precision(&flat, &chain, EdgeMode::Reflect, 1, Precision::Single).unwrap();
        assert!(out.data.iter().all(|v| ((v - level) / level).abs() < 1e-12));
    }

    #[test]
    fn fast_lengths_have_small_factors() {
        assert_eq!(fast_len(1), 1);
        assert_eq!(fast_len(7), 8);
        assert_eq!(fast_len(11), 12);
        assert_eq!(fast_len(4128), 4320);
        assert_eq!(fast_len(97), 100);
    }

    #[test]
    fn reflect_repeats_the_edge_pixel() {
        let e = EdgeMode::Reflect;
        let got: Vec<_> = (-4..8).map(|i| e.source(i, 4).unwrap()).collect();
        assert_eq!(got, vec![3, 2, 1, 0, 0, 1, 2, 3, 3, 2, 1, 0]);
        assert_eq!(EdgeMode::Wrap.source(-1, 4), Some(3));
        assert_eq!(EdgeMode::Zero.source(4, 4), None);
    }

    #[test]
    fn fft_equals_direct_convolution_for_every_edge_mode() {
        let image = pseudo_random_plane(37, 23, 7);
        let kernel = Kernel::new(
            5,
            4,
            vec![
                0.1, 0.4, 0.9, 0.3, 0.2, 0.5, 1.0, 2.0, 0.7, 0.1, 0.3, 0.8, 1.5, 0.6, 0.2, 0.0,
                0.2, 0.4, 0.1, 0.05,
            ],
        )
        .unwrap();
        let chain = MtfChain::new(vec![Mtf::Kernel(kernel.clone())]);
        for edge in [EdgeMode::Reflect, EdgeMode::Zero, EdgeMode::Wrap] {
            let by_fft = blur(&image, &chain, edge, 1).unwrap();
            let direct = convolve_direct(&image, &kernel, edge).unwrap();
            for (a, b) in by_fft.data.iter().zip(&direct.data) {
                assert!(
                    (a - b).abs() < 1e-12 * b.abs().max(1.0),
                    "{edge:?}: {a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn thesis_box_equals_its_direct_convolution() {
        let image = pseudo_random_plane(40, 31, 3);
        let chain = MtfChain::new(vec![Mtf::Box {
            width_px: 5,
            height_px: 5,
        }]);
        let by_fft = blur(&image, &chain, EdgeMode::Reflect, 1).unwrap();
        let direct =
            convolve_direct(&image, &Kernel::uniform(5, 5).unwrap(), EdgeMode::Reflect).unwrap();
        for (a, b) in by_fft.data.iter().zip(&direct.data) {
            assert!((a - b).abs() < 1e-12 * b.abs(), "{a} vs {b}");
        }
        // And by hand: pixel (10, 10) is the mean of the 5×5 block around it.
        let mut sum = 0.0;
        for y in 8..13 {
            for x in 8..13 {
                sum += image.data[y * 40 + x];
            }
        }
        assert!((by_fft.data[10 * 40 + 10] - sum / 25.0).abs() < 1e-12);
    }

    #[test]
    fn uniform_image_keeps_its_mean_under_every_model() {
        let models = vec![
            Mtf::Box {
                width_px: 5,
                height_px: 5,
            },
            Mtf::Box {
                width_px: 2,
                height_px: 3,
            },
            Mtf::Gaussian { sigma_px: 1.3 },
            Mtf::SchottSalvaggio {
                across_track_half_power_cyc_px: 0.2,
                along_track_half_power_cyc_px: 0.35,
            },
            Mtf::Diffraction {
                wavelength_m: 10e-6,
                f_number: 1.5,
                pixel_pitch_m: 30e-6,
            },
            Mtf::Footprint {
                width_px: 1.0,
                height_px: 1.0,
            },
            Mtf::Motion {
                length_px: 4.5,
                angle_deg: 20.0,
            },
            Mtf::Jitter {
                sigma_x_px: 0.4,
                sigma_y_px: 0.2,
            },
        ];
        let level = 8.123_456_789e-3; // W m^-2 sr^-1 scale (band radiance is ~tens; any works)
        for m in models {
            for edge in [EdgeMode::Reflect, EdgeMode::Wrap] {
                for s in [1, 3] {
                    let image = Plane::new(30, 20, vec![level; 600]).unwrap();
                    let out = blur(&image, &MtfChain::new(vec![m.clone()]), edge, s).unwrap();
                    let mean = out.data.iter().sum::<f64>() / out.data.len() as f64;
                    assert!(
                        ((mean - level) / level).abs() < 1e-12,
                        "{m:?} {edge:?} s={s}: mean {mean} vs {level}"
                    );
                    for v in &out.data {
                        assert!(((v - level) / level).abs() < 1e-12, "{m:?}: pixel {v}");
                    }
                }
            }
        }
    }

    #[test]
    fn zero_edges_darken_the_border_by_the_missing_weight() {
        // A 3×3 box on a uniform image: a corner pixel sees 4 of 9 taps inside.
        let image = Plane::new(10, 10, vec![9.0; 100]).unwrap();
        let chain = MtfChain::new(vec![Mtf::Box {
            width_px: 3,
            height_px: 3,
        }]);
        let out = blur(&image, &chain, EdgeMode::Zero, 1).unwrap();
        assert!((out.data[0] - 4.0).abs() < 1e-12);
        assert!((out.data[5] - 6.0).abs() < 1e-12);
        assert!((out.data[55] - 9.0).abs() < 1e-12);
    }

    #[test]
    fn one_pixel_images_and_kernels_larger_than_the_image_work() {
        let one = Plane::new(1, 1, vec![3.5]).unwrap();
        let chain = MtfChain::new(vec![
            Mtf::Box {
                width_px: 9,
                height_px: 9,
            },
            Mtf::Gaussian { sigma_px: 4.0 },
        ]);
        for edge in [EdgeMode::Reflect, EdgeMode::Wrap] {
            let out = blur(&one, &chain, edge, 1).unwrap();
            assert!(
                (out.data[0] - 3.5).abs() < 1e-12,
                "{edge:?}: {}",
                out.data[0]
            );
        }
        let image = pseudo_random_plane(3, 4, 11);
        let k = Kernel::uniform(9, 7).unwrap();
        let a = blur(
            &image,
            &MtfChain::new(vec![Mtf::Kernel(k.clone())]),
            EdgeMode::Reflect,
            1,
        )
        .unwrap();
        let b = convolve_direct(&image, &k, EdgeMode::Reflect).unwrap();
        for (x, y) in a.data.iter().zip(&b.data) {
            assert!((x - y).abs() < 1e-12);
        }
    }

    #[test]
    fn bit_identical_at_any_thread_count() {
        let image = pseudo_random_plane(61, 47, 5);
        let chain = MtfChain::new(vec![
            Mtf::Gaussian { sigma_px: 0.8 },
            Mtf::Diffraction {
                wavelength_m: 10e-6,
                f_number: 2.0,
                pixel_pitch_m: 20e-6,
            },
            Mtf::Motion {
                length_px: 2.0,
                angle_deg: 45.0,
            },
        ]);
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| blur(&image, &chain, EdgeMode::Reflect, 2).unwrap())
        };
        let one = run(1);
        for threads in [2, 3, 5] {
            let many = run(threads);
            assert!(
                one.data
                    .iter()
                    .zip(&many.data)
                    .all(|(a, b)| a.to_bits() == b.to_bits()),
                "{threads} threads differ"
            );
        }
    }

    #[test]
    fn empty_and_bad_input_is_refused() {
        let chain = MtfChain::new(vec![Mtf::Gaussian { sigma_px: 1.0 }]);
        assert!(Plane::new(0, 3, vec![]).is_err());
        let image = Plane::new(2, 2, vec![1.0; 4]).unwrap();
        assert!(blur(&image, &chain, EdgeMode::Reflect, 0).is_err());
        let bad = MtfChain::new(vec![Mtf::Gaussian { sigma_px: -2.0 }]);
        assert!(blur(&image, &bad, EdgeMode::Reflect, 1).is_err());
    }
}
