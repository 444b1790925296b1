//! The band a frame is rendered in and how it divides into sub-bands (the spectral model):
//! each sub-band its own band model and its own atmosphere, collapsed from a spectral
//! atmosphere over it.

use irsig_atmosphere::SubBandCount;
use irsig_model::provenance::BandRecord;
use irsig_radiometry::{AnyBand, Band, BandModel, TotalRadiance, spectral_radiance_per_um};
use rayon::prelude::*;

use crate::error::{RenderError, RequestError, Setting};

/// The band of a request: wavelengths (flat or with a sensor response) or the whole
/// spectrum (σT⁴/π: exact, for checking by hand), and its record, which every image of the
/// run carries (`irsig_model::provenance`).
#[derive(Debug, Clone, PartialEq)]
pub struct BandRequest {
    /// The band.
    pub band: AnyBand,
    /// What the images record of it.
    pub record: BandRecord,
    /// How the user named it (`8-14`, a response file's path), for messages.
    pub label: String,
}

impl BandRequest {
    /// The band `band`, recorded as `record`, which the user called `label`.
    #[must_use]
    pub fn new(band: AnyBand, record: BandRecord, label: impl Into<String>) -> Self {
        Self {
            band,
            record,
            label: label.into(),
        }
    }

    /// The whole spectrum.
    #[must_use]
    pub fn total() -> Self {
        Self {
            band: AnyBand::Total(TotalRadiance),
            record: BandRecord::Total,
            label: "total".into(),
        }
    }

    /// A flat band of `[min, max]` µm.
    ///
    /// # Errors
    /// Limits that are not `0 < min < max`.
    pub fn flat(min_um: f64, max_um: f64) -> Result<Self, irsig_radiometry::RadiometryError> {
        Ok(Self {
            band: AnyBand::Band(Band::new(min_um, max_um)?),
            record: BandRecord::Flat { min_um, max_um },
            label: format!("{min_um}-{max_um}"),
        })
    }
}

/// The reference temperature of the sub-bands' equal shares, K: about the scenes'
/// (earth-ambient) temperatures, where the band's radiance is what the sensor sees. The
/// spectral materials and τ are Planck-weighted at it too.
pub const SHARE_REFERENCE_K: f64 = 300.0;

/// A band model whose sub-bands the tracer can trace: the frame's band, which
/// [`crate::plan`] passes as an [`AnyBand`] (a band or the whole spectrum) so that the
/// tracer's code is compiled once for both, where a type per kind compiled it twice; a
/// sub-band is always a [`Band`] (the whole spectrum has none, and reaches no sub-band: it
/// takes no spectral atmosphere).
pub trait SubBandModel: BandModel + Clone + std::fmt::Debug + Send + Sync {
    /// The model of the sub-band `band`.
    fn of_band(band: &Band) -> Self;
}

impl SubBandModel for AnyBand {
    fn of_band(band: &Band) -> Self {
        Self::Band(band.clone())
    }
}

/// A sub-band count's sub-bands: their band models and collapsed atmospheres.
pub type Collapsed = Vec<(Band, irsig_model::Atmosphere)>;

/// How the band divides into sub-bands: its range and its response (the weight of
/// [`irsig_atmosphere::collapse`]).
#[derive(Debug, Clone, Copy)]
pub struct Split<'a> {
    /// The band's limits, µm.
    pub range_um: [f64; 2],
    /// Its response, if not flat.
    pub response: Option<&'a irsig_radiometry::SensorResponse>,
}

impl<'a> Split<'a> {
    /// The split of `band`.
    #[must_use]
    pub fn of(band: &'a Band) -> Self {
        Self {
            range_um: [band.lambda_min_um(), band.lambda_max_um()],
            response: band.response(),
        }
    }

    /// The band model of `[a, b]` µm with the band's response; `None` where the response
    /// is 0 throughout.
    fn sub_band(&self, a: f64, b: f64) -> Result<Option<Band>, RenderError> {
        let flat =
            Band::new(a, b).map_err(|e| RenderError::band(format!("sub-band {a}-{b} um"), e))?;
        match self.response {
            None => Ok(Some(flat)),
            Some(r) => Ok(flat.with_response(r).ok()),
        }
    }

    /// The response at `wavelength_um` (1 for a flat band): the weight of the sub-bands'
    /// radiances and of the sun's beam in them.
    pub(crate) fn weight(&self, wavelength_um: f64) -> f64 {
        self.response.map_or(1.0, |r| r.at(wavelength_um))
    }

    /// The sub-bands of `count`: their band models (those the response reaches), each with
    /// the atmosphere collapsed over it. With more than one sub-band, τ is weighted by the
    /// response times the blackbody at [`SHARE_REFERENCE_K`], so that τ·L_T is the
    /// sub-band's ∫τB dλ; radiances by the response alone.
    ///
    /// The atmosphere comes checked, as a [`Collapser`](irsig_atmosphere::Collapser): a
    /// plan collapses it for several counts, and checking every spectrum of it again for
    /// each cost the tolerance pilot more than collapsing the band model.
    ///
    /// # Errors
    /// A count the grid cannot make over the band (a request error), or a sub-band the
    /// atmosphere cannot be collapsed over.
    pub fn collapse(
        &self,
        collapser: irsig_atmosphere::Collapser<'_>,
        count: SubBandCount,
    ) -> Result<Collapsed, RenderError> {
        let spectral = collapser.spectral();
        let [lo, hi] = self.range_um;
        let share = |a: f64, b: f64| match self.sub_band(a, b) {
            Ok(Some(band)) => band.radiance(SHARE_REFERENCE_K),
            Ok(None) => 0.0,
            Err(_) => f64::NAN,
        };
        let edges = irsig_atmosphere::sub_band_edges(&spectral.grid, lo, hi, count, share)
            .map_err(|e| RequestError::with_value(Setting::SubBands, count, e.to_string()))?;
        edges
            .par_windows(2)
            .map(|w| {
                let Some(band) = self.sub_band(w[0], w[1])? else {
                    return Ok(None);
                };
                let at = |e: irsig_atmosphere::AtmosphereError| {
                    RenderError::atmosphere(format!("sub-band {}-{} um", w[0], w[1]), e)
                };
                let mut atmosphere = collapser
                    .collapse(w[0], w[1], |l| self.weight(l))
                    .map_err(at)?;
                if !count.is_band() {
                    // τ as the target sees it (without it the full grid reads up to 0.024 K
                    // warm in a tropical atmosphere; docs/accuracy.md).
                    // Its transmittances alone: collapsing the radiances again under this
                    // weight was a third of the full grid's collapse, and none was read.
                    collapser
                        .transmissions(w[0], w[1], |l| {
                            self.weight(l) * spectral_radiance_per_um(l, SHARE_REFERENCE_K)
                        })
                        .map_err(at)?
                        .apply_to(&mut atmosphere);
                }
                Ok(Some((band, atmosphere)))
            })
            .filter_map(Result::transpose)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sub_bands_of_a_builtin_share_the_band_radiance_and_keep_its_transmission_bounds() {
        let spectral = irsig_atmosphere::builtin_spectral("us-std-1976").unwrap();
        let band = Band::new(8.0, 14.0).unwrap();
        let split = Split::of(&band);
        let collapser = irsig_atmosphere::Collapser::new(&spectral).unwrap();
        let four = split.collapse(collapser, SubBandCount::Count(4)).unwrap();
        assert_eq!(four.len(), 4);
        // The sub-bands tile the band: their blackbody radiances add up to the band's.
        let sum: f64 = four.iter().map(|(b, _)| b.radiance(300.0)).sum();
        let whole = band.radiance(300.0);
        assert!((sum - whole).abs() < 1e-9 * whole, "{sum} vs {whole}");
        // Equal shares at the reference temperature, to the grid's resolution.
        for (b, _) in &four {
            let share = b.radiance(SHARE_REFERENCE_K) / whole;
            assert!((share - 0.25).abs() < 0.02, "{share}");
        }
        for (_, a) in &four {
            assert!(
                a.levels
                    .iter()
                    .all(|l| (0.0..=1.0).contains(&l.transmission))
            );
        }
    }

    #[test]
    fn a_sub_band_is_a_band_whatever_the_frames_band() {
        let b = Band::new(8.0, 9.5).unwrap();
        assert_eq!(AnyBand::of_band(&b), AnyBand::Band(b));
    }
}
