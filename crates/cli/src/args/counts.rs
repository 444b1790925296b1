//! The digital-count calibration, one set of flags for every tool that writes counts
//! ([`DcArgs`]).

use irsig_sensor_model::quantise::{Calibration, CountRequest};

/// How a tool turns radiance into digital counts: one set of flags for every tool that
/// writes a DC image and its LUT.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct DcArgs {
    /// Gain in digital counts per kelvin. Alone: the thesis's auto-bias (Figure 14), the
    /// scene's mid radiance at mid-scale, so counts differ from scene to scene; with
    /// --reference-k: a fixed calibration, the same counts in every scene.
    #[arg(long, value_name = "DC_PER_K")]
    pub dc_per_kelvin: Option<f64>,
    /// Fixed calibration: the temperature (K) at which the gain is --dc-per-kelvin and
    /// whose blackbody radiance maps to --dc-at-reference.
    #[arg(long, value_name = "K", conflicts_with = "gain_dc_per_radiance")]
    pub reference_k: Option<f64>,
    /// Fixed calibration: the count of a blackbody at --reference-k (default mid-scale).
    #[arg(long, value_name = "DC", requires = "reference_k")]
    pub dc_at_reference: Option<f64>,
    /// A straight line instead: counts per W m^-2 sr^-1 (with --offset-dc).
    #[arg(long, value_name = "DC_PER_W_M2_SR", conflicts_with = "dc_per_kelvin")]
    pub gain_dc_per_radiance: Option<f64>,
    /// The count of zero radiance, with --gain-dc-per-radiance (default 0).
    #[arg(long, value_name = "DC", requires = "gain_dc_per_radiance")]
    pub offset_dc: Option<f64>,
    /// Bits per digital count (1-16): an 8-bit PNG up to 8, else a 16-bit one.
    #[arg(long, default_value_t = 8, value_name = "BITS",
          value_parser = clap::value_parser!(u8).range(1..=16))]
    pub dc_bits: u8,
}

impl DcArgs {
    /// The calibration the flags ask for, before a missing gain is filled in.
    #[must_use]
    pub fn request(&self) -> CountRequest {
        CountRequest {
            dc_per_kelvin: self.dc_per_kelvin,
            reference_k: self.reference_k,
            dc_at_reference: self.dc_at_reference,
            gain_dc_per_w_m2_sr: self.gain_dc_per_radiance,
            offset_dc: self.offset_dc,
            bits: self.dc_bits,
        }
    }

    /// The calibration the flags ask for; `default_dc_per_kelvin` stands in for a missing
    /// --dc-per-kelvin. `None` when no gain is known.
    #[must_use]
    pub fn calibration(&self, default_dc_per_kelvin: Option<f64>) -> Option<Calibration> {
        self.request().calibration(default_dc_per_kelvin)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dc_flags_give_one_calibration() {
        let fixed = DcArgs {
            dc_per_kelvin: Some(4.0),
            reference_k: Some(300.0),
            ..DcArgs::default()
        };
        assert_eq!(
            fixed.calibration(None),
            Some(Calibration::Fixed {
                dc_per_kelvin: 4.0,
                reference_k: 300.0,
                dc_at_reference: None
            })
        );
        let view_gain = DcArgs::default();
        assert_eq!(
            view_gain.calibration(Some(2.0)),
            Some(Calibration::AutoBias { dc_per_kelvin: 2.0 })
        );
        assert_eq!(DcArgs::default().calibration(None), None);
        let line = DcArgs {
            gain_dc_per_radiance: Some(3.0),
            ..DcArgs::default()
        };
        assert_eq!(
            line.calibration(Some(2.0)),
            Some(Calibration::GainOffset {
                gain_dc_per_w_m2_sr: 3.0,
                offset_dc: 0.0
            })
        );
    }
}
