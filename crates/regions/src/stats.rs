//! Statistics of one value plane over the pixels a region selects.

use irsig_model::{MaterialId, Region};

/// Mean, spread and extremes of a region's values, in the unit of the value plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegionStats {
    /// Pixels selected.
    pub pixels: usize,
    /// Arithmetic mean.
    pub mean: f64,
    /// Population standard deviation (the thesis's Tables 5 and 6 "Std. Dev." of a local
    /// area).
    pub std_dev: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

/// Why a region has no statistics.
#[derive(Debug, Clone, PartialEq)]
pub enum RegionProblem {
    /// The region's box reaches beyond the image.
    BoxOutside {
        /// Image width, pixels.
        width: usize,
        /// Image height, pixels.
        height: usize,
    },
    /// The region selects no pixel.
    Empty,
    /// A selected pixel's value is NaN or infinite.
    NotFinite {
        /// Its column.
        column: usize,
        /// Its row.
        row: usize,
    },
}

/// The statistics of `values` over the pixels of a `width`-wide image that `region`
/// selects: inside its box (if any) and with `ids` equal to its material (if any). Sums run
/// in f64 in row-major order, so the result does not depend on anything but the inputs.
///
/// # Errors
/// A box beyond the image, an empty selection or a non-finite selected value.
pub fn region_stats(
    region: &Region,
    ids: &[f32],
    values: &[f32],
    width: usize,
) -> Result<RegionStats, RegionProblem> {
    let (plane, _) = region_plane(region, ids, values, width)?;
    let selected: Vec<f64> = plane.into_iter().filter(|v| !v.is_nan()).collect();
    let n = selected.len();
    let (sum, min, max) = selected.iter().fold(
        (0.0_f64, f64::INFINITY, f64::NEG_INFINITY),
        |(sum, min, max), &v| (sum + v, min.min(v), max.max(v)),
    );
    let mean = sum / n as f64;
    // Two passes: the variance of values that differ by millikelvin around 300 K loses
    // every digit to cancellation in the one-pass form.
    let variance = selected.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n as f64;
    Ok(RegionStats {
        pixels: n,
        mean,
        std_dev: variance.sqrt(),
        min,
        max,
    })
}

/// The values `region` selects of a `width`-wide image, as a plane over its box (the whole
/// image without one) with NaN at the pixels it does not select (another material), and
/// that plane's width: what [`estimate`] reads.
///
/// # Errors
/// A box beyond the image, an empty selection or a non-finite selected value.
pub fn region_plane(
    region: &Region,
    ids: &[f32],
    values: &[f32],
    width: usize,
) -> Result<(Vec<f64>, usize), RegionProblem> {
    let height = values.len().checked_div(width).unwrap_or(0);
    let (columns, rows) = match region.pixels {
        Some(b) => {
            let (c0, c1) = (b.columns.0 as usize, b.columns.1 as usize);
            let (r0, r1) = (b.rows.0 as usize, b.rows.1 as usize);
            if c1 >= width || r1 >= height {
                return Err(RegionProblem::BoxOutside { width, height });
            }
            (c0..=c1, r0..=r1)
        }
        None if width == 0 || height == 0 => return Err(RegionProblem::Empty),
        None => (0..=width - 1, 0..=height - 1),
    };
    let wanted = region.material.map(|MaterialId(id)| f32::from(id));
    let mut plane = Vec::with_capacity(columns.clone().count() * rows.clone().count());
    let mut any = false;
    for row in rows {
        for column in columns.clone() {
            let i = row * width + column;
            let selected = wanted.is_none_or(|id| ids.get(i).copied() == Some(id));
            match values.get(i) {
                Some(&v) if selected => {
                    if !v.is_finite() {
                        return Err(RegionProblem::NotFinite { column, row });
                    }
                    any = true;
                    plane.push(f64::from(v));
                }
                _ => plane.push(f64::NAN),
            }
        }
    }
    if !any {
        return Err(RegionProblem::Empty);
    }
    Ok((plane, columns.count()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::PixelBox;

    fn region(material: Option<u16>, pixels: Option<PixelBox>) -> Region {
        Region {
            name: "r".into(),
            material: material.map(MaterialId),
            pixels,
            references: vec![],
        }
    }

    /// A 4 × 3 image: ids 1 on the left half, 2 on the right; value = 10·row + column.
    fn image() -> (Vec<f32>, Vec<f32>) {
        let mut ids = Vec::new();
        let mut values = Vec::new();
        for row in 0..3 {
            for column in 0..4 {
                ids.push(if column < 2 { 1.0 } else { 2.0 });
                values.push((10 * row + column) as f32);
            }
        }
        (ids, values)
    }

    #[test]
    fn material_box_and_both_select_what_they_say() {
        let (ids, values) = image();
        // Material 2: columns 2, 3 of rows 0-2: 2 3 12 13 22 23, mean 12.5.
        let s = region_stats(&region(Some(2), None), &ids, &values, 4).unwrap();
        assert_eq!((s.pixels, s.mean, s.min, s.max), (6, 12.5, 2.0, 23.0));
        // Population std of {2,3,12,13,22,23}: deviations ±10.5, ±9.5, ±0.5, so the
        // variance is 2·(110.25 + 90.25 + 0.25) / 6 = 401.5 / 6.
        assert!((s.std_dev - (401.5_f64 / 6.0).sqrt()).abs() < 1e-12);
        // Box columns 1-2, row 1: 11 and 12.
        let b = PixelBox {
            columns: (1, 2),
            rows: (1, 1),
        };
        let s = region_stats(&region(None, Some(b)), &ids, &values, 4).unwrap();
        assert_eq!((s.pixels, s.mean, s.std_dev), (2, 11.5, 0.5));
        // Both: only column 1 is material 1.
        let s = region_stats(&region(Some(1), Some(b)), &ids, &values, 4).unwrap();
        assert_eq!((s.pixels, s.mean, s.std_dev), (1, 11.0, 0.0));
    }

    #[test]
    fn problems_are_reported_not_averaged_over() {
        let (ids, mut values) = image();
        let outside = PixelBox {
            columns: (0, 4),
            rows: (0, 0),
        };
        assert_eq!(
            region_stats(&region(None, Some(outside)), &ids, &values, 4),
            Err(RegionProblem::BoxOutside {
                width: 4,
                height: 3
            })
        );
        assert_eq!(
            region_stats(&region(Some(9), None), &ids, &values, 4),
            Err(RegionProblem::Empty)
        );
        values[6] = f32::NAN;
        assert_eq!(
            region_stats(&region(Some(2), None), &ids, &values, 4),
            Err(RegionProblem::NotFinite { column: 2, row: 1 })
        );
        // The NaN is outside material 1: no problem there.
        assert!(region_stats(&region(Some(1), None), &ids, &values, 4).is_ok());
    }

    #[test]
    fn the_spread_of_a_hot_uniform_region_is_not_lost_to_cancellation() {
        // 1000 values 350 ± 0.001 K: std 0.001 K exactly in the two-pass form.
        let values: Vec<f32> = (0..1000)
            .map(|i| if i % 2 == 0 { 350.001 } else { 349.999 })
            .collect();
        let ids = vec![1.0; 1000];
        let s = region_stats(&region(Some(1), None), &ids, &values, 100).unwrap();
        let expected = (f64::from(350.001_f32) - f64::from(349.999_f32)) / 2.0;
        assert!((s.std_dev - expected).abs() < 1e-9, "{}", s.std_dev);
        assert!((s.mean - 350.0).abs() < 1e-4);
    }
}
