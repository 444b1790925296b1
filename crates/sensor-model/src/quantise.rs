//! Radiance to digital counts, the look-up table back, and apparent temperature
//! (thesis §3.4.3, Figure 14, §4.2, §5.2; Appendix H `save_image`).
//!
//! A [`Quantiser`] is a straight line from band radiance L (W m⁻² sr⁻¹) to counts,
//! `DC = round(gain·L + offset)`, clamped to `0 ..= 2^bits − 1` at **both** ends (the 1990
//! code clamped only above 255, so scenes whose radiance fell below the bias wrapped
//! around into negative shorts). Three ways to choose the line:
//!
//! - [`Quantiser::from_gain_offset`]: gain and offset as given;
//! - [`Quantiser::auto_bias`]: the thesis's DC-per-kelvin auto-bias (Figure 14), which
//!   depends on the scene's radiance range, so the same object gets different counts in
//!   different scenes ("pseudo autocontrast");
//! - [`Quantiser::fixed`]: the §5.2 recommendation, a gain stated per kelvin at a fixed
//!   reference temperature and a fixed offset, so counts mean the same in every scene
//!   (with `dc_per_kelvin = 1/NEΔT` one count is one NEΔT at the reference).
//!
//! Radiance ↔ temperature comes from the band (any `irsig_radiometry::BandModel`, normally
//! `irsig_radiometry::Band`).

use std::fmt;

use irsig_radiometry::{BandModel, InverseTable};
use rayon::prelude::*;

use crate::error::{Result, SensorError, SensorErrorKind, finite, positive};

/// How the line from radiance to counts is chosen: the three calibrations of
/// [`Quantiser`], as data, so that every stage that writes counts offers the same ones.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Calibration {
    /// [`Quantiser::from_gain_offset`]: gain and offset as given.
    GainOffset {
        /// Counts per W m⁻² sr⁻¹.
        gain_dc_per_w_m2_sr: f64,
        /// The count of zero radiance.
        offset_dc: f64,
    },
    /// [`Quantiser::auto_bias`] over the image's own range (thesis Figure 14).
    AutoBias {
        /// Counts per kelvin at the scene's mid radiance.
        dc_per_kelvin: f64,
    },
    /// [`Quantiser::fixed`] (§5.2): the same counts in every scene.
    Fixed {
        /// Counts per kelvin at the reference.
        dc_per_kelvin: f64,
        /// The reference temperature, K.
        reference_k: f64,
        /// The count of a blackbody at the reference; `None`: mid-scale, 2^(bits−1).
        dc_at_reference: Option<f64>,
    },
}

/// A calibration as a user asks for it, before a missing gain is filled in: what the
/// digital-count flags of every tool say (`irsig_cli::args::DcArgs`), as data.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CountRequest {
    /// Counts per kelvin, if given.
    pub dc_per_kelvin: Option<f64>,
    /// A fixed calibration's reference temperature, K.
    pub reference_k: Option<f64>,
    /// The count of a blackbody at the reference (default mid-scale).
    pub dc_at_reference: Option<f64>,
    /// A straight line instead: counts per W m⁻² sr⁻¹.
    pub gain_dc_per_w_m2_sr: Option<f64>,
    /// The count of zero radiance, with the straight line (default 0).
    pub offset_dc: Option<f64>,
    /// Bits per count.
    pub bits: u8,
}

impl CountRequest {
    /// The calibration asked for; `default_dc_per_kelvin` stands in for a missing counts
    /// per kelvin (a view's gain). `None` when no gain is known.
    #[must_use]
    pub fn calibration(&self, default_dc_per_kelvin: Option<f64>) -> Option<Calibration> {
        if let Some(gain) = self.gain_dc_per_w_m2_sr {
            return Some(Calibration::GainOffset {
                gain_dc_per_w_m2_sr: gain,
                offset_dc: self.offset_dc.unwrap_or(0.0),
            });
        }
        let dc_per_kelvin = self.dc_per_kelvin.or(default_dc_per_kelvin)?;
        Some(match self.reference_k {
            Some(reference_k) => Calibration::Fixed {
                dc_per_kelvin,
                reference_k,
                dc_at_reference: self.dc_at_reference,
            },
            None => Calibration::AutoBias { dc_per_kelvin },
        })
    }
}

/// Highest supported number of bits per count.
pub const MAX_BITS: u8 = 16;

/// A linear radiance → count mapping with clamping at both ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quantiser {
    bits: u8,
    gain_dc_per_w_m2_sr: f64,
    offset_dc: f64,
}

impl Quantiser {
    /// `DC = round(gain·L + offset)`, clamped to `bits`.
    ///
    /// # Errors
    /// `bits` outside 1..=16, a gain that is not finite and positive, or a non-finite
    /// offset.
    pub fn from_gain_offset(bits: u8, gain_dc_per_w_m2_sr: f64, offset_dc: f64) -> Result<Self> {
        check_bits(bits)?;
        positive("gain_dc_per_w_m2_sr", gain_dc_per_w_m2_sr)?;
        finite("offset_dc", offset_dc)?;
        Ok(Self {
            bits,
            gain_dc_per_w_m2_sr,
            offset_dc,
        })
    }

    /// The thesis's auto-bias (Figure 14, `save_image` in Appendix H): the middle of the
    /// scene's radiance range L_mid = (L_max − L_min)/2 + L_min is converted to T_mid; ΔL is
    /// the radiance step for T_mid + 1 K; the gain is `dc_per_kelvin / ΔL` counts per
    /// radiance unit, and the offset puts L_mid at mid-scale, 2^(bits−1) (128 for 8 bits,
    /// as in 1990). Unlike 1990 the offset is not truncated to an integer, so L_mid maps to
    /// mid-scale exactly.
    ///
    /// # Errors
    /// Bad `bits` or gain, non-finite radiances, `max < min`, or a mid radiance whose
    /// temperature the band cannot give (L_mid ≤ 0).
    pub fn auto_bias(
        bits: u8,
        dc_per_kelvin: f64,
        min_radiance_w_m2_sr: f64,
        max_radiance_w_m2_sr: f64,
        band: &impl BandModel,
    ) -> Result<Self> {
        check_bits(bits)?;
        positive("dc_per_kelvin", dc_per_kelvin)?;
        let lo = finite("min_radiance_w_m2_sr", min_radiance_w_m2_sr)?;
        let hi = finite("max_radiance_w_m2_sr", max_radiance_w_m2_sr)?;
        if hi < lo {
            return Err(SensorError::parameter(
                "max_radiance_w_m2_sr",
                hi,
                "at least min_radiance_w_m2_sr",
            ));
        }
        let mid_radiance = (hi - lo) / 2.0 + lo;
        positive("mid-range radiance (W m^-2 sr^-1)", mid_radiance)?;
        let mid_temperature = positive(
            "temperature of the mid-range radiance (K)",
            band.temperature(mid_radiance),
        )?;
        let delta_radiance = band.radiance(mid_temperature + 1.0) - mid_radiance;
        positive("radiance step for +1 K (W m^-2 sr^-1)", delta_radiance)?;
        let gain = dc_per_kelvin / delta_radiance;
        let mid_scale = f64::from(1u32 << (bits - 1));
        Self::from_gain_offset(bits, gain, mid_scale - gain * mid_radiance)
    }

    /// [`Quantiser::auto_bias`] with the range taken from the image itself.
    ///
    /// # Errors
    /// As `auto_bias`; also an empty image or a non-finite pixel (its index is named).
    pub fn auto_bias_from_image(
        bits: u8,
        dc_per_kelvin: f64,
        radiance_w_m2_sr: &[f32],
        band: &impl BandModel,
    ) -> Result<Self> {
        let (lo, hi) = finite_range(radiance_w_m2_sr)?;
        Self::auto_bias(bits, dc_per_kelvin, lo, hi, band)
    }

    /// A fixed calibration (§5.2): `dc_per_kelvin` counts per kelvin at
    /// `reference_temperature_k` (gain = dc_per_kelvin / (dL/dT)), and
    /// the blackbody radiance at the reference maps to `dc_at_reference`. Counts then mean
    /// the same thing in every scene. Use `dc_per_kelvin = 1 / NEΔT` for one count per
    /// NEΔT.
    ///
    /// # Errors
    /// Bad bits, gain or temperature, or a band whose dL/dT is not positive there.
    pub fn fixed(
        bits: u8,
        dc_per_kelvin: f64,
        reference_temperature_k: f64,
        dc_at_reference: f64,
        band: &impl BandModel,
    ) -> Result<Self> {
        check_bits(bits)?;
        positive("dc_per_kelvin", dc_per_kelvin)?;
        positive("reference_temperature_k", reference_temperature_k)?;
        finite("dc_at_reference", dc_at_reference)?;
        let slope = positive(
            "dL/dT at the reference temperature (W m^-2 sr^-1 K^-1)",
            band.radiance_derivative(reference_temperature_k),
        )?;
        let gain = dc_per_kelvin / slope;
        let reference_radiance = band.radiance(reference_temperature_k);
        Self::from_gain_offset(bits, gain, dc_at_reference - gain * reference_radiance)
    }

    /// The quantiser `calibration` gives for an image `radiance_w_m2_sr` (whose range only
    /// [`Calibration::AutoBias`] reads).
    ///
    /// # Errors
    /// As the constructor the calibration names.
    pub fn calibrate(
        bits: u8,
        calibration: &Calibration,
        radiance_w_m2_sr: &[f32],
        band: &impl BandModel,
    ) -> Result<Self> {
        match *calibration {
            Calibration::GainOffset {
                gain_dc_per_w_m2_sr,
                offset_dc,
            } => Self::from_gain_offset(bits, gain_dc_per_w_m2_sr, offset_dc),
            Calibration::AutoBias { dc_per_kelvin } => {
                Self::auto_bias_from_image(bits, dc_per_kelvin, radiance_w_m2_sr, band)
            }
            Calibration::Fixed {
                dc_per_kelvin,
                reference_k,
                dc_at_reference,
            } => {
                check_bits(bits)?;
                let mid_scale = f64::from(1u32 << (bits - 1));
                Self::fixed(
                    bits,
                    dc_per_kelvin,
                    reference_k,
                    dc_at_reference.unwrap_or(mid_scale),
                    band,
                )
            }
        }
    }

    /// Bits per count.
    #[must_use]
    pub fn bits(&self) -> u8 {
        self.bits
    }

    /// The highest count, 2^bits − 1.
    #[must_use]
    pub fn max_count(&self) -> u16 {
        // bits ≤ 16 by construction.
        ((1u32 << self.bits) - 1) as u16
    }

    /// Counts per W m⁻² sr⁻¹.
    #[must_use]
    pub fn gain_dc_per_w_m2_sr(&self) -> f64 {
        self.gain_dc_per_w_m2_sr
    }

    /// The count of zero radiance (before clamping; may be fractional or negative).
    #[must_use]
    pub fn offset_dc(&self) -> f64 {
        self.offset_dc
    }

    /// The count for one radiance: rounded to nearest, clamped to `0..=max_count`. NaN
    /// maps to 0; use [`Quantiser::quantise`] to have it refused instead.
    #[must_use]
    pub fn count(&self, radiance_w_m2_sr: f64) -> u16 {
        let dc = (self.gain_dc_per_w_m2_sr * radiance_w_m2_sr + self.offset_dc).round();
        if dc.is_nan() {
            return 0;
        }
        // In range after the clamp, so the cast is exact.
        dc.clamp(0.0, f64::from(self.max_count())) as u16
    }

    /// Counts for a whole row-major image of `width` columns.
    ///
    /// # Errors
    /// A pixel that is NaN or infinite, named by column and row.
    pub fn quantise(&self, radiance_w_m2_sr: &[f32], width: usize) -> Result<Vec<u16>> {
        check_finite(radiance_w_m2_sr, width)?;
        Ok(radiance_w_m2_sr
            .iter()
            .map(|&l| self.count(f64::from(l)))
            .collect())
    }

    /// The radiance at the centre of the interval that rounds to `dc`: (dc − offset)/gain.
    #[must_use]
    pub fn radiance_at(&self, dc: u16) -> f64 {
        (f64::from(dc) - self.offset_dc) / self.gain_dc_per_w_m2_sr
    }

    /// The look-up table for every count 0..=max: radiance at the centre of the count's
    /// interval, its blackbody temperature in K and °C. (1990 listed only the counts that
    /// occurred, with the radiance of the first pixel that produced each.) Counts whose
    /// radiance is ≤ 0 carry whatever temperature the band documents for that case.
    #[must_use]
    pub fn lut(&self, band: &impl BandModel) -> Lut {
        let entries = (0..=self.max_count())
            .map(|dc| {
                let radiance_w_m2_sr = self.radiance_at(dc);
                let temperature_k = band.temperature(radiance_w_m2_sr);
                LutEntry {
                    dc,
                    radiance_w_m2_sr,
                    temperature_k,
                    temperature_c: temperature_k - 273.15,
                }
            })
            .collect();
        Lut { entries }
    }
}

fn check_bits(bits: u8) -> Result<()> {
    if (1..=MAX_BITS).contains(&bits) {
        Ok(())
    } else {
        Err(SensorError::parameter(
            "bits",
            f64::from(bits),
            "1 to 16 bits per count",
        ))
    }
}

fn check_finite(values: &[f32], width: usize) -> Result<()> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(SensorErrorKind::NonFinitePixel {
            x: i % width.max(1),
            y: i / width.max(1),
            value: f64::from(values[i]),
        }
        .into()),
    }
}

/// The smallest and largest value of an image.
///
/// # Errors
/// An empty image, or the first non-finite pixel (its index as x with y = 0).
pub fn finite_range(values: &[f32]) -> Result<(f64, f64)> {
    if values.is_empty() {
        return Err(SensorErrorKind::EmptyImage {
            width: 0,
            height: 0,
        }
        .into());
    }
    check_finite(values, values.len())?;
    let (lo, hi) = values
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    Ok((f64::from(lo), f64::from(hi)))
}

/// One row of the look-up table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LutEntry {
    /// The digital count.
    pub dc: u16,
    /// Band radiance at the centre of the count's interval, W m⁻² sr⁻¹.
    pub radiance_w_m2_sr: f64,
    /// Blackbody (apparent) temperature of that radiance, K.
    pub temperature_k: f64,
    /// The same in degrees Celsius.
    pub temperature_c: f64,
}

/// The count → radiance → temperature table (§4.2).
#[derive(Debug, Clone, PartialEq)]
pub struct Lut {
    /// One entry per count, in order.
    pub entries: Vec<LutEntry>,
}

/// The temperatures a look-up table can show ([`Lut::temperature_span`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TemperatureSpan {
    /// The temperature of the lowest count whose radiance is positive, K.
    pub lowest_k: f64,
    /// The temperature of the highest count, K.
    pub highest_k: f64,
    /// How many counts, from 0 up, stand for zero or negative radiance: no temperature
    /// (a fixed calibration whose reference puts count 0 below zero radiance).
    pub counts_without_temperature: usize,
}

impl Lut {
    /// From the lowest count of positive radiance to the highest count, and how many counts
    /// below it have no temperature; `None` when no count has a positive radiance. A
    /// count of zero or negative radiance has no blackbody temperature, so it is never the
    /// span's low end (its 0 K would be no temperature of the scene's).
    #[must_use]
    pub fn temperature_span(&self) -> Option<TemperatureSpan> {
        let first = self.entries.iter().position(|e| e.radiance_w_m2_sr > 0.0)?;
        Some(TemperatureSpan {
            lowest_k: self.entries[first].temperature_k,
            highest_k: self.entries.last()?.temperature_k,
            counts_without_temperature: first,
        })
    }

    /// The table's text ([`fmt::Display`]) with a second comment line naming the band its
    /// radiances and temperatures are in (`# band: …`), so that the file says it too.
    #[must_use]
    pub fn text_in_band(&self, band: &str) -> String {
        let text = self.to_string();
        let band: String = band
            .chars()
            .map(|c| if c.is_control() { ' ' } else { c })
            .collect();
        match text.split_once('\n') {
            Some((header, rows)) => format!("{header}\n# band: {band}\n{rows}"),
            None => text,
        }
    }
}

/// The LUT's text form (`formats/sensor.md`): a `#` header line naming the columns and
/// units, then one line per count: `dc radiance_w_m2_sr temperature_k temperature_c`,
/// whitespace-separated, radiance with 9 significant digits, temperatures to 1e-4 K.
impl fmt::Display for Lut {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "# dc radiance_w_m2_sr temperature_k temperature_c")?;
        for e in &self.entries {
            writeln!(
                f,
                "{} {:.8e} {:.4} {:.4}",
                e.dc, e.radiance_w_m2_sr, e.temperature_k, e.temperature_c
            )?;
        }
        Ok(())
    }
}

/// The apparent (blackbody-equivalent) temperature in K of every pixel, in parallel, through
/// the band's inverse table (`irsig_radiometry::InverseTable`); the same at any thread count.
///
/// # Errors
/// A non-finite pixel, named by column and row.
pub fn apparent_temperature(
    radiance_w_m2_sr: &[f32],
    width: usize,
    band: &impl BandModel,
) -> Result<Vec<f32>> {
    check_finite(radiance_w_m2_sr, width)?;
    let radiance: Vec<f64> = radiance_w_m2_sr.iter().map(|&l| f64::from(l)).collect();
    let inverse = InverseTable::new(band, &radiance);
    Ok(radiance
        .par_chunks(4096)
        .flat_map_iter(|run| inverse.temperatures(run.iter().copied()).map(|t| t as f32))
        .collect())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// An independent 8–14 µm blackbody band for the tests: Planck's law integrated with
    /// Simpson's rule on 401 points (within 1e-11 of 2001 points from 100 to 3000 K, 5e-9 at
    /// 30 K), temperature by bisection to a nanokelvin. Slow but transparently right; not
    /// the code under test. A 14-bit LUT inverts 16,384 radiances through it.
    pub(crate) struct SimpsonBand;

    const C1: f64 = 1.191_042_972e-16; // 2hc², W m² sr⁻¹
    const C2: f64 = 1.438_776_877e-2; // hc/k, m K

    fn planck(lambda_m: f64, t_k: f64) -> f64 {
        C1 / lambda_m.powi(5) / ((C2 / (lambda_m * t_k)).exp_m1())
    }

    fn simpson(f: impl Fn(f64) -> f64) -> f64 {
        let (a, b, n) = (8e-6, 14e-6, 400);
        let h = (b - a) / f64::from(n);
        let mut s = f(a) + f(b);
        for i in 1..n {
            let w = if i % 2 == 1 { 4.0 } else { 2.0 };
            s += w * f(a + h * f64::from(i));
        }
        s * h / 3.0
    }

    impl BandModel for SimpsonBand {
        fn radiance(&self, t_k: f64) -> f64 {
            simpson(|l| planck(l, t_k))
        }
        fn radiance_derivative(&self, t_k: f64) -> f64 {
            (self.radiance(t_k + 1e-3) - self.radiance(t_k - 1e-3)) / 2e-3
        }
        fn temperature(&self, radiance: f64) -> f64 {
            if radiance <= 0.0 {
                return 0.0;
            }
            let (mut lo, mut hi) = (1.0, 5000.0);
            while hi - lo > 1e-9 {
                let mid = 0.5 * (lo + hi);
                if self.radiance(mid) < radiance {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            0.5 * (lo + hi)
        }
    }

    #[test]
    fn planck_band_is_about_right() {
        // From the tabulated blackbody fractions F(λT): F(2400 µm K) = 0.140 25 and
        // F(4200 µm K) = 0.515 99, so 8–14 µm at 300 K holds 0.375 74 of σT⁴/π = 146.19,
        // i.e. 54.93 W m^-2 sr^-1.
        let l = SimpsonBand.radiance(300.0);
        assert!((l / 54.93 - 1.0).abs() < 1e-3, "{l}");
        // dL/dT: between 4L/T (all of it at short λ) and L/T; ~0.8 W m^-2 sr^-1 K^-1.
        let d = SimpsonBand.radiance_derivative(300.0);
        assert!((0.7..0.9).contains(&d), "{d}");
    }

    #[test]
    fn gain_offset_rounds_and_clamps_both_ends() {
        let q = Quantiser::from_gain_offset(8, 10.0, -100.0).unwrap();
        assert_eq!(q.count(10.0), 0);
        assert_eq!(q.count(10.04), 0);
        assert_eq!(q.count(10.06), 1);
        assert_eq!(q.count(22.5), 125);
        assert_eq!(q.count(-50.0), 0, "below the bias clamps to 0, not wraps");
        assert_eq!(q.count(35.5), 255);
        assert_eq!(q.count(1e30), 255);
        assert_eq!(q.max_count(), 255);
        let q16 = Quantiser::from_gain_offset(16, 1000.0, 0.0).unwrap();
        assert_eq!(q16.count(65.535), 65535);
        assert_eq!(q16.count(70.0), 65535);
        assert_eq!(q16.max_count(), 65535);
        assert!((q.radiance_at(125) - 22.5).abs() < 1e-12);
    }

    #[test]
    fn auto_bias_follows_figure_14_by_hand() {
        let band = SimpsonBand;
        let (lo, hi) = (band.radiance(280.0), band.radiance(320.0));
        let q = Quantiser::auto_bias(8, 4.0, lo, hi, &band).unwrap();
        // Figure 14 step by step.
        let l_mid = (hi - lo) / 2.0 + lo;
        let t_mid = band.temperature(l_mid);
        let d_l = band.radiance(t_mid + 1.0) - l_mid;
        let slope = 4.0 / d_l;
        assert!((q.gain_dc_per_w_m2_sr() - slope).abs() < 1e-9 * slope);
        assert!((q.gain_dc_per_w_m2_sr() * l_mid + q.offset_dc() - 128.0).abs() < 1e-9);
        assert_eq!(q.count(l_mid), 128);
        // One kelvin above T_mid is 4 counts higher.
        assert_eq!(q.count(band.radiance(t_mid + 1.0)), 132);
        // Radiance is convex in T, so the mid radiance lies above L(300 K): T_mid > 300 K.
        assert!((300.0..305.0).contains(&t_mid), "{t_mid}");
    }

    #[test]
    fn fixed_calibration_is_one_count_per_nedt_at_the_reference() {
        let band = SimpsonBand;
        let nedt = 0.1;
        let q = Quantiser::fixed(14, 1.0 / nedt, 300.0, 8192.0, &band).unwrap();
        assert_eq!(q.count(band.radiance(300.0)), 8192);
        assert_eq!(q.count(band.radiance(300.0 + nedt)), 8193);
        assert_eq!(q.count(band.radiance(300.0 + 10.0 * nedt)), 8202);
    }

    #[test]
    fn lut_inverts_the_counts() {
        let band = SimpsonBand;
        let q = Quantiser::auto_bias(8, 2.0, 20.0, 40.0, &band).unwrap();
        let lut = q.lut(&band);
        assert_eq!(lut.entries.len(), 256);
        for e in &lut.entries {
            if e.radiance_w_m2_sr > 0.0 && e.dc > 0 && e.dc < 255 {
                assert_eq!(q.count(e.radiance_w_m2_sr), e.dc);
                let back = band.radiance(e.temperature_k);
                assert!((back - e.radiance_w_m2_sr).abs() < 1e-9 * back);
                assert!((e.temperature_c - (e.temperature_k - 273.15)).abs() < 1e-12);
            }
        }
        let text = lut.to_string();
        assert!(text.starts_with("# dc radiance_w_m2_sr temperature_k temperature_c\n"));
        assert_eq!(text.lines().count(), 257);
    }

    /// A 14-bit fixed calibration of 10 counts per kelvin with 300 K at count 8192 puts
    /// zero radiance at count 8192 − 10 × L(300)/L'(300) by hand, L/L' ≈ 54.93/0.80 ≈ 69 K
    /// for 8–14 µm at 300 K: near count 7500. The counts below it are radiance ≤ 0, and
    /// the span starts above them, never at the 0 K the band gives zero radiance. With 300 K
    /// at count 500 no count is below zero radiance, and the span starts at count 0.
    #[test]
    fn a_luts_span_starts_at_its_first_count_of_positive_radiance() {
        let band = SimpsonBand;
        let q = Quantiser::fixed(14, 10.0, 300.0, 8192.0, &band).unwrap();
        let lut = q.lut(&band);
        let span = lut.temperature_span().unwrap();
        let n = span.counts_without_temperature;
        let by_hand = 8192.0 - 10.0 * band.radiance(300.0) / band.radiance_derivative(300.0);
        assert!((7400.0..7600.0).contains(&by_hand), "{by_hand}");
        assert!((n as f64 - by_hand).abs() <= 1.0, "{n} counts vs {by_hand}");
        assert!(lut.entries[n].radiance_w_m2_sr > 0.0);
        assert!(lut.entries[n - 1].radiance_w_m2_sr <= 0.0);
        assert!(span.lowest_k > 1.0 && span.lowest_k < 200.0, "{span:?}");
        assert_eq!(
            span.highest_k.to_bits(),
            lut.entries[16383].temperature_k.to_bits()
        );

        let q = Quantiser::fixed(14, 10.0, 300.0, 500.0, &band).unwrap();
        let lut = q.lut(&band);
        let span = lut.temperature_span().unwrap();
        assert_eq!(span.counts_without_temperature, 0);
        assert_eq!(
            span.lowest_k.to_bits(),
            lut.entries[0].temperature_k.to_bits()
        );
        assert!((150.0..300.0).contains(&span.lowest_k), "{span:?}");
    }

    #[test]
    fn bad_settings_and_pixels_are_refused() {
        let band = SimpsonBand;
        assert!(Quantiser::from_gain_offset(0, 1.0, 0.0).is_err());
        assert!(Quantiser::from_gain_offset(17, 1.0, 0.0).is_err());
        assert!(Quantiser::from_gain_offset(8, 0.0, 0.0).is_err());
        assert!(Quantiser::from_gain_offset(8, 1.0, f64::NAN).is_err());
        assert!(Quantiser::auto_bias(8, 1.0, 30.0, 20.0, &band).is_err());
        assert!(Quantiser::auto_bias(8, 1.0, -5.0, -1.0, &band).is_err());
        assert!(Quantiser::auto_bias_from_image(8, 1.0, &[], &band).is_err());
        let q = Quantiser::from_gain_offset(8, 1.0, 0.0).unwrap();
        let err = q.quantise(&[1.0, 2.0, 3.0, f32::NAN], 3).unwrap_err();
        assert!(matches!(
            err.kind(),
            SensorErrorKind::NonFinitePixel { x: 0, y: 1, value } if value.is_nan()
        ));
    }

    #[test]
    fn apparent_temperature_of_blackbody_radiance_is_its_temperature() {
        let band = SimpsonBand;
        let image: Vec<f32> = [250.0, 300.0, 350.0]
            .iter()
            .map(|&t| band.radiance(t) as f32)
            .collect();
        let t = apparent_temperature(&image, 3, &band).unwrap();
        for (got, want) in t.iter().zip([250.0, 300.0, 350.0]) {
            // f32 radiance carries ~1e-7 relative, i.e. ~1e-5 K here.
            assert!((f64::from(*got) - want).abs() < 1e-3, "{got} vs {want}");
        }
    }

    #[test]
    fn each_calibration_is_its_constructor() {
        let band = SimpsonBand;
        let image = [40.0_f32, 60.0, 52.0];
        let auto = Calibration::AutoBias { dc_per_kelvin: 4.0 };
        assert_eq!(
            Quantiser::calibrate(8, &auto, &image, &band).unwrap(),
            Quantiser::auto_bias(8, 4.0, 40.0, 60.0, &band).unwrap()
        );
        // A fixed calibration without a reference count puts the reference at mid-scale.
        let fixed = Calibration::Fixed {
            dc_per_kelvin: 10.0,
            reference_k: 300.0,
            dc_at_reference: None,
        };
        assert_eq!(
            Quantiser::calibrate(12, &fixed, &image, &band).unwrap(),
            Quantiser::fixed(12, 10.0, 300.0, 2048.0, &band).unwrap()
        );
        let line = Calibration::GainOffset {
            gain_dc_per_w_m2_sr: 3.0,
            offset_dc: -20.0,
        };
        assert_eq!(
            Quantiser::calibrate(8, &line, &[], &band).unwrap(),
            Quantiser::from_gain_offset(8, 3.0, -20.0).unwrap()
        );
        assert!(Quantiser::calibrate(0, &fixed, &image, &band).is_err());
        assert!(Quantiser::calibrate(17, &fixed, &image, &band).is_err());
    }
}
