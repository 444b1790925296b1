//! Detector sampling: an image rendered at k samples per sensor pixel in each direction is
//! reduced to the sensor grid by integrating each detector's footprint (thesis §3.3.4: the
//! tracer renders finer than the sensor so that aliasing is small).
//!
//! - Continuous layers (radiance, range, temperature) are the mean of each k × k block:
//!   the detector integrates flux over its area.
//! - Categorical layers (material ids, object ids) cannot be averaged. We take the
//!   **majority** of the block — the label that covers most of the detector's footprint —
//!   and break ties by the smallest label, so the result is deterministic and does not
//!   depend on the order of samples. (The centre sample was the alternative; it ignores
//!   the footprint and is undefined for even k.)

use std::collections::BTreeMap;

use rayon::prelude::*;

use crate::Plane;
use crate::error::{Result, SensorErrorKind};

fn check_factor(width: usize, height: usize, factor: usize) -> Result<()> {
    if factor == 0 || width % factor != 0 || height % factor != 0 {
        return Err(SensorErrorKind::NotDivisible {
            width,
            height,
            factor,
        }
        .into());
    }
    Ok(())
}

/// The mean of every `factor` × `factor` block.
///
/// # Errors
/// An empty image, or sides that are not multiples of `factor`.
pub fn reduce_mean(image: &Plane, factor: usize) -> Result<Plane> {
    image.check()?;
    check_factor(image.width, image.height, factor)?;
    let (w, h) = (image.width / factor, image.height / factor);
    let scale = 1.0 / (factor * factor) as f64;
    let mut data = vec![0.0; w * h];
    data.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, out) in row.iter_mut().enumerate() {
            let mut acc = 0.0;
            for sy in y * factor..(y + 1) * factor {
                let line = &image.data[sy * image.width..(sy + 1) * image.width];
                acc += line[x * factor..(x + 1) * factor].iter().sum::<f64>();
            }
            *out = acc * scale;
        }
    });
    Ok(Plane {
        width: w,
        height: h,
        data,
    })
}

/// The mean of every `factor` × `factor` block of an f32 truth layer, over the samples
/// that are not NaN (truth layers hold NaN where a quantity does not apply, such as the
/// range where no facet was hit); NaN where the whole block is.
///
/// # Errors
/// Data of the wrong length, an empty image, or sides that are not multiples of `factor`.
pub fn reduce_mean_ignoring_nan(
    values: &[f32],
    width: usize,
    height: usize,
    factor: usize,
) -> Result<Vec<f32>> {
    check_layer(values.len(), width, height)?;
    check_factor(width, height, factor)?;
    let (w, h) = (width / factor, height / factor);
    let mut out = vec![0.0_f32; w * h];
    out.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, value) in row.iter_mut().enumerate() {
            let (mut sum, mut n) = (0.0_f64, 0_usize);
            for sy in y * factor..(y + 1) * factor {
                for &v in &values[sy * width + x * factor..sy * width + (x + 1) * factor] {
                    if !v.is_nan() {
                        sum += f64::from(v);
                        n += 1;
                    }
                }
            }
            *value = if n == 0 {
                f32::NAN
            } else {
                (sum / n as f64) as f32
            };
        }
    });
    Ok(out)
}

fn check_layer(len: usize, width: usize, height: usize) -> Result<()> {
    if width == 0 || height == 0 {
        return Err(SensorErrorKind::EmptyImage { width, height }.into());
    }
    if len != width * height {
        return Err(SensorErrorKind::SizeMismatch {
            width,
            height,
            actual: len,
        }
        .into());
    }
    Ok(())
}

/// The majority label of every `factor` × `factor` block of a categorical layer (ties to
/// the smallest label; labels compared by value with `f32::total_cmp`).
///
/// # Errors
/// Data of the wrong length, an empty image, or sides that are not multiples of `factor`.
pub fn reduce_majority(
    labels: &[f32],
    width: usize,
    height: usize,
    factor: usize,
) -> Result<Vec<f32>> {
    check_layer(labels.len(), width, height)?;
    check_factor(width, height, factor)?;
    let (w, h) = (width / factor, height / factor);
    let mut out = vec![0.0_f32; w * h];
    out.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        let mut counts: BTreeMap<Label, usize> = BTreeMap::new();
        for (x, value) in row.iter_mut().enumerate() {
            counts.clear();
            for sy in y * factor..(y + 1) * factor {
                for sx in x * factor..(x + 1) * factor {
                    *counts.entry(Label(labels[sy * width + sx])).or_default() += 1;
                }
            }
            // BTreeMap iterates smallest label first; keep the first of the largest count.
            let mut best = (Label(0.0), 0);
            for (label, &n) in &counts {
                if n > best.1 {
                    best = (*label, n);
                }
            }
            *value = best.0.0;
        }
    });
    Ok(out)
}

/// An f32 label with a total order.
#[derive(Debug, Clone, Copy)]
struct Label(f32);

impl PartialEq for Label {
    fn eq(&self, other: &Self) -> bool {
        self.0.total_cmp(&other.0).is_eq()
    }
}
impl Eq for Label {}
impl PartialOrd for Label {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Label {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_of_blocks_by_hand() {
        #[rustfmt::skip]
        let image = Plane::new(4, 2, vec![
            1.0, 2.0, 10.0, 20.0,
            3.0, 4.0, 30.0, 40.0,
        ]).unwrap();
        let r = reduce_mean(&image, 2).unwrap();
        assert_eq!((r.width, r.height), (2, 1));
        assert!((r.data[0] - 2.5).abs() < 1e-15);
        assert!((r.data[1] - 25.0).abs() < 1e-15);
        // The total flux is conserved.
        let big = Plane::new(6, 9, (0..54).map(f64::from).collect()).unwrap();
        let small = reduce_mean(&big, 3).unwrap();
        let total_big: f64 = big.data.iter().sum();
        let total_small: f64 = small.data.iter().sum::<f64>() * 9.0;
        assert!((total_big - total_small).abs() < 1e-9);
    }

    #[test]
    fn majority_with_ties_to_the_smallest_label() {
        #[rustfmt::skip]
        let labels = [
            5.0, 5.0, 2.0, 7.0,
            5.0, 1.0, 7.0, 2.0,
        ];
        let r = reduce_majority(&labels, 4, 2, 2).unwrap();
        assert_eq!(r, vec![5.0, 2.0]);
    }

    #[test]
    fn truth_means_skip_nan() {
        #[rustfmt::skip]
        let range = [
            10.0, f32::NAN, f32::NAN, f32::NAN,
            20.0, 30.0, f32::NAN, f32::NAN,
        ];
        let r = reduce_mean_ignoring_nan(&range, 4, 2, 2).unwrap();
        assert!((r[0] - 20.0).abs() < 1e-6);
        assert!(r[1].is_nan());
    }

    #[test]
    fn indivisible_sizes_are_refused() {
        let image = Plane::new(5, 4, vec![0.0; 20]).unwrap();
        assert!(reduce_mean(&image, 2).is_err());
        assert!(reduce_mean(&image, 0).is_err());
        assert!(reduce_majority(&[0.0; 20], 5, 4, 2).is_err());
        assert!(reduce_majority(&[0.0; 19], 5, 4, 1).is_err());
        assert_eq!(reduce_mean(&image, 1).unwrap(), image);
    }
}
