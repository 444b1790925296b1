//! Which pixels the sensor stage's counts clip. Its quantiser is `DC = round(gain·L +
//! offset)` clamped to `0..=full` (`irsig_sensor_model::quantise`), and its LUT lists the
//! radiance at the centre of each count's interval, so a pixel is at count 0 when its
//! radiance is below the midpoint of counts 0 and 1, and at full scale when it is at or
//! above the midpoint of the last two counts. Such a pixel's count no longer tells its
//! temperature: everything colder than the first, or hotter than the last, reads the same.

use irsig_formats::lut::LutRow;

/// Pixels at either end of the counts.
#[derive(Debug, Clone, PartialEq)]
pub struct Saturation {
    /// The full-scale count (the LUT's last).
    pub full_count: u32,
    /// Pixels at count 0.
    pub at_zero: usize,
    /// Pixels at full scale.
    pub at_full: usize,
    /// Pixels with a finite value.
    pub pixels: usize,
    /// Per pixel: 1 at count 0, else 0 (NaN where the value is not finite).
    pub zero_mask: Vec<f32>,
    /// Per pixel: 1 at full scale, else 0 (NaN where the value is not finite).
    pub full_mask: Vec<f32>,
    /// What was compared with what, in words.
    pub compared: &'static str,
}

/// The pixels of `radiance` (W m⁻² sr⁻¹, compared with the LUT's radiance column) or, when
/// there is none, of `kelvin` (compared with its temperature column) that sit at count 0
/// or at full scale. `None` for a LUT of one count, which has no midpoint.
#[must_use]
pub fn saturation(lut: &[LutRow], radiance: Option<&[f32]>, kelvin: &[f32]) -> Option<Saturation> {
    let n = lut.len();
    if n < 2 {
        return None;
    }
    let (values, column, compared): (&[f32], fn(&LutRow) -> f64, &'static str) = match radiance {
        Some(r) => (
            r,
            |row| row.radiance_w_m2_sr,
            "the radiance of each pixel against the LUT's radiance column",
        ),
        None => (
            kelvin,
            |row| row.temperature_k,
            "the apparent temperature of each pixel against the LUT's temperature column",
        ),
    };
    let low = 0.5 * (column(&lut[0]) + column(&lut[1]));
    let high = 0.5 * (column(&lut[n - 2]) + column(&lut[n - 1]));
    let (mut at_zero, mut at_full, mut pixels) = (0, 0, 0);
    let mut zero_mask = Vec::with_capacity(values.len());
    let mut full_mask = Vec::with_capacity(values.len());
    for &v in values {
        if !v.is_finite() {
            zero_mask.push(f32::NAN);
            full_mask.push(f32::NAN);
            continue;
        }
        pixels += 1;
        let v = f64::from(v);
        let (z, f) = (v < low, v >= high);
        at_zero += usize::from(z);
        at_full += usize::from(f);
        zero_mask.push(if z { 1.0 } else { 0.0 });
        full_mask.push(if f { 1.0 } else { 0.0 });
    }
    Some(Saturation {
        full_count: lut[n - 1].dc,
        at_zero,
        at_full,
        pixels,
        zero_mask,
        full_mask,
        compared,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(dc: u32, radiance: f64, kelvin: f64) -> LutRow {
        LutRow {
            dc,
            radiance_w_m2_sr: radiance,
            temperature_k: kelvin,
            temperature_c: kelvin - 273.15,
        }
    }

    #[test]
    fn pixels_beyond_the_first_and_last_midpoints_are_clipped() {
        // Counts 0..=3 at radiance 10, 20, 30, 40: count 0 below 15, full scale from 35.
        let lut = [
            row(0, 10.0, 280.0),
            row(1, 20.0, 290.0),
            row(2, 30.0, 300.0),
            row(3, 40.0, 310.0),
        ];
        let radiance = [5.0, 14.99, 15.0, 34.99, 35.0, 99.0, f32::NAN];
        let s = saturation(&lut, Some(&radiance), &[0.0; 7]).unwrap();
        assert_eq!((s.at_zero, s.at_full, s.pixels, s.full_count), (2, 2, 6, 3));
        assert_eq!(&s.zero_mask[..6], &[1.0, 1.0, 0.0, 0.0, 0.0, 0.0]);
        assert_eq!(&s.full_mask[..6], &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0]);
        assert!(s.zero_mask[6].is_nan());
        // Without radiance, the temperatures against the kelvin column: 285 and 305.
        let s = saturation(&lut, None, &[284.0, 286.0, 305.0]).unwrap();
        assert_eq!((s.at_zero, s.at_full), (1, 1));
        assert!(saturation(&lut[..1], None, &[1.0]).is_none());
    }
}
