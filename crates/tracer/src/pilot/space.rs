//! What the pilot may choose from ([`PilotSpace`]: the band sets and every model's
//! settings, reference first), and the one model whose settings are not plain numbers,
//! [`Supersample`].

use irsig_atmosphere::{ModelKind, SubBandCount};
use irsig_model::decision::SwitchableModel;

use crate::error::{TraceError, TraceErrorKind};
use crate::path_table::PathTermsMode;
use crate::tracer::BandSet;

/// How many rays a pixel gets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Supersample {
    /// `n × n` rays in every pixel (`1`: the centre ray only).
    Every(u32),
    /// `n × n` rays only where the centre differs from a neighbour's by more than the
    /// tolerance (adaptive supersampling, thesis §3.3.4).
    Adaptive(u32),
    /// Edge and thin pixels refined to a standard error, in levels up to side `n`
    /// ([`crate::refine`]): what a tolerance renders with.
    Refine(u32),
}

impl Supersample {
    /// The setting as the decision names it: `1`, `4`, `adaptive-4`, `refine-32`.
    #[must_use]
    pub fn name(self) -> String {
        match self {
            Self::Every(n) => n.to_string(),
            Self::Adaptive(n) => format!("adaptive-{n}"),
            Self::Refine(n) => format!("refine-{n}"),
        }
    }
}

impl std::fmt::Display for Supersample {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.name())
    }
}

impl std::str::FromStr for Supersample {
    type Err = String;

    /// `N` or `adaptive-N`, N from 1 to 64, or `refine-N`, N from 1 to
    /// [`crate::refine::MAX_SIDE`].
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (make, n): (fn(u32) -> Self, &str) = if let Some(n) = s.strip_prefix("adaptive-") {
            (Self::Adaptive, n)
        } else if let Some(n) = s.strip_prefix("refine-") {
            (Self::Refine, n)
        } else {
            (Self::Every, s)
        };
        let largest = if s.starts_with("refine-") {
            crate::refine::MAX_SIDE
        } else {
            64
        };
        n.parse()
            .ok()
            .filter(|n| (1..=largest).contains(n))
            .map(make)
            .ok_or_else(|| {
                format!(
                    "expected N (N x N rays per pixel, 1 to 64), adaptive-N or refine-N (N \
                     from 1 to {}), found `{s}`",
                    crate::refine::MAX_SIDE
                )
            })
    }
}

/// A band set the pilot may choose: an atmosphere model over some sub-bands.
#[derive(Debug)]
pub struct BandChoice<S> {
    /// The atmosphere model.
    pub atmosphere: ModelKind,
    /// The sub-bands (1 for the band model).
    pub sub_bands: SubBandCount,
    /// The set, built for the tracer's scene
    /// ([`Tracer::band_set`](crate::Tracer::band_set)).
    pub set: BandSet<S>,
    /// What one exact path-terms call costs in one of its sub-bands, ns (BENCHMARKS.md:
    /// `table` 880, `layered` 830, `thesis` 92, `none` 5).
    pub path_call_ns: f64,
    /// What precomputing the sky for one of its sub-bands costs a rendering, ns.
    pub sky_ns: f64,
}

/// What the pilot may choose from. Each list is ordered from the most accurate setting
/// (the reference, first) to the cheapest; a model with one entry is fixed (pinned, or one
/// that cannot matter), and `reasons` says why.
#[derive(Debug)]
pub struct PilotSpace<S> {
    /// Every (atmosphere, sub-bands) pair the pilot needs: the reference pair, each
    /// sub-band count at the reference atmosphere, and each atmosphere in the band model
    /// (`1`), the reference atmosphere's band model included: every model but the
    /// sub-bands is measured in it (see [`Tracer::pilot`](crate::Tracer::pilot)). Where an
    /// atmosphere has no band model here, it is measured at the reference sub-bands.
    pub bands: Vec<BandChoice<S>>,
    /// Atmosphere models, reference first.
    pub atmospheres: Vec<ModelKind>,
    /// Sub-band counts, reference first.
    pub sub_bands: Vec<SubBandCount>,
    /// Specular bounces, reference (most) first.
    pub bounces: Vec<u32>,
    /// Sky-view rays per diffuse hit, reference first; 0 is the thesis's F = 1.
    pub sky_view_rays: Vec<u32>,
    /// Rays per pixel, reference first (with a tolerance: refinement alone, unless
    /// pinned).
    pub supersampling: Vec<Supersample>,
    /// Path terms, reference (`Exact`) first.
    pub path_terms: Vec<PathTermsMode>,
    /// Models whose setting is fixed, and why (pinned by the user, or cannot matter here).
    pub reasons: Vec<(SwitchableModel, String)>,
    /// Models the user pinned.
    pub pinned: Vec<SwitchableModel>,
    /// With a sun (the tracer's, [`Tracer::with_sun`](crate::Tracer::with_sun); each band
    /// set then carries its beams, [`Tracer::lit_band_set`](crate::Tracer::lit_band_set)):
    /// whether it may be switched off, and the shadow rays on offer. `None`: a night, and
    /// the decision names no sun.
    pub sun: Option<SunOffer<S>>,
}

/// What the pilot may choose for the sun.
#[derive(Debug)]
pub struct SunOffer<S> {
    /// The sun's settings, reference first: `true` on, `false` off.
    pub lit: Vec<bool>,
    /// Shadow rays per facet hit, reference (most) first; each count four times the next
    /// (but 1, the disk's centre), so that the sequence measures what the most leave.
    pub shadow_rays: Vec<u32>,
    /// The band model's set at the reference atmosphere without the sun
    /// ([`Tracer::band_set`](crate::Tracer::band_set)): what `off` is evaluated with.
    pub dark: BandSet<S>,
}

/// Where in [`PilotSpace::bands`] the pilot finds each set it measures with.
#[derive(Debug)]
pub(crate) struct SetIndices {
    /// The reference atmosphere at the reference sub-bands.
    pub reference: usize,
    /// The reference atmosphere's band model (else the reference set).
    pub band_model: usize,
    /// Each atmosphere on offer in the band model (else at the reference sub-bands).
    pub atmospheres: Vec<usize>,
    /// Each sub-band count on offer at the reference atmosphere.
    pub sub_bands: Vec<usize>,
}

impl<S> PilotSpace<S> {
    /// The band sets the pilot measures with, found among [`Self::bands`].
    ///
    /// # Errors
    /// An empty list of atmospheres or sub-band counts, or a set the pilot needs missing.
    pub(crate) fn set_indices(&self) -> Result<SetIndices, TraceError> {
        let bad = |m: String| TraceError::new(TraceErrorKind::InvalidOptions(m));
        let find = |atmosphere: ModelKind, sub_bands: SubBandCount| {
            self.bands
                .iter()
                .position(|b| b.atmosphere == atmosphere && b.sub_bands == sub_bands)
        };
        let (Some(&ref_atm), Some(&ref_sb)) = (self.atmospheres.first(), self.sub_bands.first())
        else {
            return Err(bad(
                "the pilot needs at least one atmosphere and one sub-band count".into(),
            ));
        };
        let reference = find(ref_atm, ref_sb).ok_or_else(|| {
            bad(format!(
                "no band set for atmosphere {ref_atm}, sub-bands {ref_sb}"
            ))
        })?;
        let band_model = find(ref_atm, SubBandCount::BAND).unwrap_or(reference);
        let atmospheres = self
            .atmospheres
            .iter()
            .map(|&a| {
                find(a, SubBandCount::BAND)
                    .or_else(|| find(a, ref_sb))
                    .ok_or_else(|| bad(format!("no band set for {a}")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let sub_bands = self
            .sub_bands
            .iter()
            .map(|&k| {
                find(ref_atm, k).ok_or_else(|| bad(format!("no band set for {ref_atm}, {k}")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(SetIndices {
            reference,
            band_model,
            atmospheres,
            sub_bands,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn supersampling_settings_round_trip() {
        for s in [
            Supersample::Every(1),
            Supersample::Every(4),
            Supersample::Adaptive(2),
            Supersample::Refine(32),
        ] {
            assert_eq!(s.name().parse::<Supersample>(), Ok(s));
        }
        assert!("refine-0".parse::<Supersample>().is_err());
        assert!("refine-128".parse::<Supersample>().is_ok());
        assert!("refine-129".parse::<Supersample>().is_err());
        assert!("65".parse::<Supersample>().is_err());
        assert!("refined-4".parse::<Supersample>().is_err());
    }
}
