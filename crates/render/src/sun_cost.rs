//! What one sub-band costs a sunlit frame, in kelvin of apparent temperature.
//!
//! The band model multiplies the path's τ, the sun's beam and ε each averaged over the
//! band and misses that they are opaque in the same absorption bands, so the sunlight a
//! surface reflects comes out low. docs/accuracy.md ("The sun's share by day") measures
//! how low against the spectral integral over LOWTRAN7's spectra: 7.1–8.4 % of the
//! sunlight in 8–14 µm and 20.2–25.5 % in 3–5 µm, the more the lower the sun. A frame's
//! cost is that shortfall on the sunlight each pixel's radiance holds: with `L_sun` the
//! sunlight at the sensor (the truth's `sun_share × L`) and `f` the shortfall, the
//! spectral radiance is `L + L_sun·f/(1 − f)`, and the pixel's apparent temperature moves
//! by that over `dL/dT` at its own (first order in a change of a few per cent of `L`).

use irsig_radiometry::BandModel;
use irsig_tracer::Frame;

/// The shortfall of one sub-band's sunlight measured in a band `range_um`: the larger of
/// the measured figures, for a band inside 3–5 µm or inside 8–14 µm; `None` elsewhere
/// (not measured).
#[must_use]
pub fn measured_shortfall(range_um: [f64; 2]) -> Option<f64> {
    let inside = |lo: f64, hi: f64| range_um[0] >= lo - 1e-9 && range_um[1] <= hi + 1e-9;
    if inside(3.0, 5.0) {
        Some(0.255)
    } else if inside(8.0, 14.0) {
        Some(0.084)
    } else {
        None
    }
}

/// The apparent-temperature cost of a sunlight shortfall `shortfall` (0 to 1) over the
/// pixels of `frame` that hold sunlight: `(median, largest)` in kelvin, `None` when the
/// frame kept no sun truth or no pixel holds sunlight.
#[must_use]
pub fn cost_k(band: &impl BandModel, frame: &Frame, shortfall: f64) -> Option<(f64, f64)> {
    if frame.sun.len() != frame.radiance_w_m2_sr.len() || !(0.0..1.0).contains(&shortfall) {
        return None;
    }
    let mut kelvin: Vec<f64> = frame
        .sun
        .iter()
        .zip(&frame.radiance_w_m2_sr)
        .map(|(sun, &radiance)| (f64::from(sun.sun_share) * radiance, radiance))
        // NaN (a sky pixel's share without scattered sunlight) and 0 hold no sunlight.
        .filter(|&(sunlight, _)| sunlight > 0.0)
        .filter_map(|(sunlight, radiance)| {
            let slope = band.radiance_derivative(band.temperature(radiance));
            let missing = sunlight * shortfall / (1.0 - shortfall);
            (slope > 0.0).then(|| missing / slope)
        })
        .collect();
    if kelvin.is_empty() {
        return None;
    }
    kelvin.sort_by(f64::total_cmp);
    Some((kelvin[kelvin.len() / 2], kelvin[kelvin.len() - 1]))
}

/// The warning that says what one sub-band cost view `view` (from 1), or `None` when it
/// cannot be said (no sun truth kept, no sunlight, a band not measured).
#[must_use]
pub fn note(
    band: &impl BandModel,
    range_um: Option<[f64; 2]>,
    frame: &Frame,
    view: usize,
) -> Option<String> {
    let shortfall = measured_shortfall(range_um?)?;
    let (median, largest) = cost_k(band, frame, shortfall)?;
    Some(format!(
        "view {view}: one sub-band's sunlight, {:.1} % low as measured in this band, costs \
         the sunlit pixels of this frame {median:.3} K of apparent temperature at the median \
         and {largest:.3} K at most (colder than the spectral integral)",
        100.0 * shortfall
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_radiometry::Band;
    use irsig_tracer::SunPixel;

    fn frame(radiance: &[f64], share: &[f32]) -> Frame {
        Frame {
            width: radiance.len() as u32,
            height: 1,
            radiance_w_m2_sr: radiance.to_vec(),
            sun: share
                .iter()
                .map(|&s| SunPixel {
                    solar_irradiance_w_m2: 0.0,
                    sun_visible_fraction: 1.0,
                    reflected_solar_w_m2_sr: 0.0,
                    sun_share: s,
                })
                .collect(),
            truth: Vec::new(),
            sampling: Vec::new(),
            charges: irsig_tracer::Charges::default(),
        }
    }

    #[test]
    fn the_cost_is_the_missing_sunlight_over_the_slope() {
        // 3-5 um, a 300 K pixel of which 10 % is sunlight, 25 % short: the spectral
        // radiance is L + 0.1·L·0.25/0.75 = L + L/30. By hand (Planck's law by Simpson's
        // rule, an independent script): L = 1.865956 W m⁻² sr⁻¹ and dL/dT = 0.0676983
        // W m⁻² sr⁻¹ K⁻¹ at 300 K, so ΔT = (1.865956/30)/0.0676983 = 0.91876 K.
        let band = Band::new(3.0, 5.0).unwrap();
        let l = band.radiance(300.0);
        assert!((l - 1.865_956).abs() < 1e-5, "{l}");
        let f = frame(&[l, l, 0.5 * l], &[0.1, 0.0, f32::NAN]);
        let (median, largest) = cost_k(&band, &f, 0.25).unwrap();
        assert!(
            (largest - 0.918_76).abs() < 1e-4,
            "{largest} K against 0.91876 by hand"
        );
        assert_eq!(median.to_bits(), largest.to_bits(), "one sunlit pixel");
        // No sunlight, no sun truth, no shortfall: nothing to say.
        assert_eq!(cost_k(&band, &frame(&[l], &[0.0]), 0.25), None);
        assert_eq!(cost_k(&band, &frame(&[l], &[]), 0.25), None);
        assert_eq!(cost_k(&band, &f, 1.0), None);
    }

    #[test]
    fn the_measured_shortfalls_are_the_bands_measured() {
        assert_eq!(measured_shortfall([3.0, 5.0]), Some(0.255));
        assert_eq!(measured_shortfall([3.5, 4.1]), Some(0.255));
        assert_eq!(measured_shortfall([8.0, 14.0]), Some(0.084));
        assert_eq!(measured_shortfall([7.5, 14.0]), None);
        assert_eq!(measured_shortfall([1.0, 2.5]), None);
    }
}
