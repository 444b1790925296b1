//! The tolerance pilot's side of a frame: what the pilot may choose from for a scene
//! ([`offer`]), the pins that fix a model ([`Pin`]), and the decision as a table.

use std::fmt::Write as _;
use std::str::FromStr;

use irsig_atmosphere::{ModelKind, SubBandCount};
use irsig_model::MaterialLibrary;
use irsig_model::decision::{Decision, SwitchableModel};
use irsig_tracer::PathTermsMode;
use irsig_tracer::pilot::{REFINE_MAX_SIDE, Supersample};

use crate::error::{RenderError, RequestError, Setting, Spelling};
/// The bounces on offer, a convergence sequence from the most: Appendix A finds one enough
/// at earth-ambient temperatures; the step from 4 to 8 measures what 8 leave (a hall of
/// mirrors that still changes there is not guaranteed).
pub const BOUNCES: [u32; 5] = [8, 4, 2, 1, 0];
/// The sky-view rays on offer, from the most: each step of four halves a Monte Carlo
/// estimate's error, and the step from 64 to 256 measures what 256 leave.
pub const SKY_VIEW_RAYS: [u32; 4] = [256, 64, 16, 0];
/// The shadow rays per facet hit on offer by day, from the most: 64 stratified over the
/// sun's disk down to 4, each step of four a convergence step, and 1 to the disk's
/// centre (hard shadows); the step from 16 to 64 measures what 64 leave.
pub const SHADOW_RAYS: [u32; 4] = [64, 16, 4, 1];

/// A model fixed by hand (`MODEL=SETTING`): the pilot measures it but does not choose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pin {
    /// `atmosphere=table|layered|thesis|none`.
    Atmosphere(ModelKind),
    /// `bounces=N`, 0 to 64.
    Bounces(u32),
    /// `sky-view=N` rays (0: off).
    SkyView(u32),
    /// `supersampling=N` or `adaptive-N`.
    Supersampling(Supersample),
    /// `path-terms=exact|tabulated`.
    PathTerms(PathTermsMode),
    /// `sub-bands=1|K|full`.
    SubBands(SubBandCount),
    /// `sun=on|off`, by day.
    Sun(bool),
    /// `shadow-rays=N`, 1 to 65536, by day.
    ShadowRays(u32),
}

impl Pin {
    /// The model pinned.
    #[must_use]
    pub fn model(self) -> SwitchableModel {
        match self {
            Self::Atmosphere(_) => SwitchableModel::Atmosphere,
            Self::Bounces(_) => SwitchableModel::Bounces,
            Self::SkyView(_) => SwitchableModel::SkyView,
            Self::Supersampling(_) => SwitchableModel::Supersampling,
            Self::PathTerms(_) => SwitchableModel::PathTerms,
            Self::SubBands(_) => SwitchableModel::SubBands,
            Self::Sun(_) => SwitchableModel::Sun,
            Self::ShadowRays(_) => SwitchableModel::ShadowRays,
        }
    }
}

impl std::fmt::Display for Pin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let model = self.model();
        match self {
            Self::Atmosphere(k) => write!(f, "{model}={k}"),
            Self::Bounces(n) | Self::SkyView(n) | Self::ShadowRays(n) => write!(f, "{model}={n}"),
            Self::Sun(lit) => write!(f, "{model}={}", if *lit { "on" } else { "off" }),
            Self::Supersampling(s) => write!(f, "{model}={s}"),
            Self::PathTerms(p) => write!(f, "{model}={}", p.name()),
            Self::SubBands(k) => write!(f, "{model}={k}"),
        }
    }
}

impl FromStr for Pin {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (model, setting) = s
            .split_once('=')
            .ok_or_else(|| format!("expected MODEL=SETTING such as bounces=2, found `{s}`"))?;
        let model: SwitchableModel = model.trim().parse().map_err(|e| format!("{e}"))?;
        let setting = setting.trim();
        let pin = match model {
            SwitchableModel::Atmosphere => setting.parse().ok().map(Self::Atmosphere),
            SwitchableModel::Bounces => setting
                .parse::<u32>()
                .ok()
                .filter(|&b| b <= 64)
                .map(Self::Bounces),
            SwitchableModel::SkyView => setting
                .parse::<u32>()
                .ok()
                .filter(|&n| n <= 1 << 20)
                .map(Self::SkyView),
            SwitchableModel::Supersampling => setting.parse().ok().map(Self::Supersampling),
            SwitchableModel::PathTerms => setting.parse().ok().map(Self::PathTerms),
            SwitchableModel::SubBands => setting.parse().ok().map(Self::SubBands),
            SwitchableModel::Sun => match setting {
                "on" => Some(Self::Sun(true)),
                "off" => Some(Self::Sun(false)),
                _ => None,
            },
            SwitchableModel::ShadowRays => setting
                .parse::<u32>()
                .ok()
                .filter(|n| (1..=irsig_tracer::sun::MAX_SHADOW_RAYS).contains(n))
                .map(Self::ShadowRays),
        };
        pin.ok_or_else(|| {
            let expected = match model {
                SwitchableModel::Atmosphere => "table, layered, thesis or none",
                SwitchableModel::Bounces => "a number of bounces, 0 to 64",
                SwitchableModel::SkyView => "a number of rays (0: off)",
                SwitchableModel::Supersampling => {
                    "N (N x N rays per pixel), adaptive-N or refine-N (N from 1 to 64)"
                }
                SwitchableModel::PathTerms => "exact or tabulated",
                SwitchableModel::SubBands => "a number of sub-bands (1: the band model) or full",
                SwitchableModel::Sun => "on or off",
                SwitchableModel::ShadowRays => "a number of shadow rays per hit, 1 to 65536",
            };
            format!("{model}={setting}: expected {expected}")
        })
    }
}

/// The settings on offer for each model, most accurate first, and why a model has one.
#[derive(Debug)]
pub struct Offer {
    pub atmospheres: Vec<ModelKind>,
    pub bounces: Vec<u32>,
    pub sky_view_rays: Vec<u32>,
    pub supersampling: Vec<Supersample>,
    pub path_terms: Vec<PathTermsMode>,
    pub sub_bands: Vec<SubBandCount>,
    /// By day, the sun on and off (empty at night).
    pub sun: Vec<bool>,
    /// By day, the shadow rays per hit (empty at night).
    pub shadow_rays: Vec<u32>,
    pub reasons: Vec<(SwitchableModel, String)>,
    pub pinned: Vec<SwitchableModel>,
}

/// The sub-band counts offered with a spectral atmosphere, most accurate first: the
/// atmosphere's full grid, then 16 and 4 sub-bands of equal shares, then the band model.
pub const SPECTRAL_SUB_BANDS: [SubBandCount; 4] = [
    SubBandCount::Full,
    SubBandCount::Count(16),
    SubBandCount::Count(4),
    SubBandCount::BAND,
];

/// What the pilot may choose for a scene with `materials` under `atmosphere` (the kinds
/// its tables allow, or `None` for a vacuum; `spectral` when it has spectra, so that
/// sub-band counts are on offer; `sun` by day, so that the sun and its shadow rays are),
/// with `pins` fixing models.
///
/// # Errors
/// A pin the scene cannot honour (an atmosphere model whose table is missing, sub-bands of
/// an atmosphere without spectra, the sun's models at night): a request error naming the
/// pin.
pub fn offer(
    materials: &MaterialLibrary,
    kinds: Option<&[ModelKind]>,
    spectral: bool,
    sun: bool,
    pins: &[Pin],
    spelling: Spelling,
) -> Result<Offer, RenderError> {
    let mut offer = Offer::unpinned(materials, kinds, spectral, sun, pins, spelling);
    for &pin in pins {
        offer.pin(pin, spectral, sun, spelling)?;
    }
    Ok(offer)
}

impl Offer {
    /// Every setting the scene allows for each model, before any pin, with the reasons for
    /// the models left one.
    fn unpinned(
        materials: &MaterialLibrary,
        kinds: Option<&[ModelKind]>,
        spectral: bool,
        sun: bool,
        pins: &[Pin],
        spelling: Spelling,
    ) -> Self {
        let mut reasons = Vec::new();
        let specular = materials
            .materials
            .iter()
            .any(|m| m.specular_fraction > 0.0);
        let diffuse = materials
            .materials
            .iter()
            .any(|m| m.specular_fraction < 1.0);
        // Sub-bands pinned to the band model: every atmosphere model costs one sky, as
        // without spectra.
        let band_pinned = pins
            .iter()
            .any(|p| matches!(p, Pin::SubBands(c) if c.is_band()));
        let atmospheres = offered_atmospheres(kinds, spectral, band_pinned, spelling, &mut reasons);
        let bounces = if specular {
            BOUNCES.to_vec()
        } else {
            reasons.push((
                SwitchableModel::Bounces,
                "no specular material: bounces cannot matter".to_owned(),
            ));
            vec![0]
        };
        let sky_view_rays = if diffuse {
            SKY_VIEW_RAYS.to_vec()
        } else {
            reasons.push((
                SwitchableModel::SkyView,
                "no diffuse material: the sky-view factor cannot matter".to_owned(),
            ));
            vec![0]
        };
        // Refinement to a standard error: each pixel gets the rays it needs, and no fixed
        // grid can do better at the same cost (a pin may still ask for one).
        let supersampling = vec![Supersample::Refine(REFINE_MAX_SIDE)];
        let path_terms = if kinds.is_some() {
            vec![PathTermsMode::Exact, PathTermsMode::Tabulated]
        } else {
            reasons.push((
                SwitchableModel::PathTerms,
                "no atmosphere: path terms are exact and free".to_owned(),
            ));
            vec![PathTermsMode::Exact]
        };
        let sub_bands = if spectral {
            SPECTRAL_SUB_BANDS.to_vec()
        } else {
            reasons.push((
                SwitchableModel::SubBands,
                "the atmosphere has no spectra: the band model".to_owned(),
            ));
            vec![SubBandCount::BAND]
        };
        // By day the sun may be left out where its effect is within the tolerance; shadow
        // rays matter only where a facet reflects diffusely.
        let (sun_lit, shadow_rays) = if sun {
            let rays = if diffuse {
                SHADOW_RAYS.to_vec()
            } else {
                reasons.push((
                    SwitchableModel::ShadowRays,
                    "no diffuse material: shadow rays cannot matter".to_owned(),
                ));
                vec![1]
            };
            (vec![true, false], rays)
        } else {
            (Vec::new(), Vec::new())
        };
        Self {
            atmospheres,
            bounces,
            sky_view_rays,
            supersampling,
            path_terms,
            sub_bands,
            sun: sun_lit,
            shadow_rays,
            reasons,
            pinned: Vec::new(),
        }
    }

    /// Fixes `pin`'s model to its setting, the pin its reason.
    ///
    /// # Errors
    /// As [`offer`].
    fn pin(
        &mut self,
        pin: Pin,
        spectral: bool,
        sun: bool,
        spelling: Spelling,
    ) -> Result<(), RenderError> {
        let model = pin.model();
        let why = format!("pinned by {} {pin}", spelling.of(Setting::Pin));
        self.reasons.retain(|(m, _)| *m != model);
        self.reasons.push((model, why));
        self.pinned.push(model);
        match pin {
            Pin::Atmosphere(kind) => {
                if !self.atmospheres.contains(&kind) {
                    return Err(RequestError::with_value(
                        Setting::Pin,
                        pin,
                        format!(
                            "this atmosphere offers {}",
                            self.atmospheres
                                .iter()
                                .map(ToString::to_string)
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    )
                    .into());
                }
                self.atmospheres = vec![kind];
            }
            Pin::Bounces(n) => self.bounces = vec![n],
            Pin::SkyView(n) => self.sky_view_rays = vec![n],
            Pin::Supersampling(s) => self.supersampling = vec![s],
            Pin::PathTerms(p) => self.path_terms = vec![p],
            Pin::SubBands(count) => {
                if !spectral && !count.is_band() {
                    return Err(RequestError::with_value(
                        Setting::Pin,
                        pin,
                        "this atmosphere has no spectra; only 1 (the band model) is on offer",
                    )
                    .into());
                }
                self.sub_bands = vec![count];
            }
            Pin::Sun(_) | Pin::ShadowRays(_) if !sun => {
                return Err(RequestError::with_value(
                    Setting::Pin,
                    pin,
                    "this frame has no sun (give one with the sun's settings)",
                )
                .into());
            }
            Pin::Sun(lit) => self.sun = vec![lit],
            Pin::ShadowRays(n) => self.shadow_rays = vec![n],
        }
        Ok(())
    }
}

/// The atmosphere models on offer under `kinds` (`None`: a vacuum), with the reason when
/// the scene leaves one.
fn offered_atmospheres(
    kinds: Option<&[ModelKind]>,
    spectral: bool,
    band_pinned: bool,
    spelling: Spelling,
    reasons: &mut Vec<(SwitchableModel, String)>,
) -> Vec<ModelKind> {
    match kinds {
        // Spectra with slant tables: the table model, LOWTRAN's own paths in every
        // sub-band; the layered and thesis models, approximations for atmospheres without
        // slant tables, would each cost a sky precomputation per sub-band of the pilot's
        // full grid (BENCHMARKS.md: 88 and 121 ms).
        Some(k) if spectral && !band_pinned && k.contains(&ModelKind::Table) => {
            reasons.push((
                SwitchableModel::Atmosphere,
                "a spectral atmosphere with slant tables: the table model".to_owned(),
            ));
            vec![ModelKind::Table]
        }
        Some(k) => k.to_vec(),
        None => {
            reasons.push((
                SwitchableModel::Atmosphere,
                format!("no atmosphere ({} none)", spelling.of(Setting::Atmosphere)),
            ));
            vec![ModelKind::None]
        }
    }
}

/// The decision as a table for people: model, choice, error at the percentile and at worst
/// (K), relative cost, why. The first line says the tolerance; the rest are indented.
#[must_use]
pub fn table(d: &Decision) -> String {
    let mut out = String::new();
    let p = d.percentile;
    let _ = writeln!(
        out,
        "tolerance {} K at the {p}th percentile of the frame and the 90th of every class, \
         from {} pilot points:",
        d.tolerance_k, d.pilot_pixels
    );
    if !d.relative_to.is_empty() {
        let _ = writeln!(out, "  relative to {}", d.relative_to);
    }
    let _ = writeln!(
        out,
        "  {:<14} {:<12} {:<12} {:>9} {:>9} {:>7}  why",
        "model", "choice", "reference", "p(K)", "worst(K)", "cost"
    );
    for c in &d.choices {
        let _ = writeln!(
            out,
            "  {:<14} {:<12} {:<12} {:>9.4} {:>9.4} {:>7.3}  {}",
            c.model.name(),
            c.setting,
            c.reference,
            c.error.percentile_k,
            c.error.max_k,
            c.relative_cost,
            c.reason
        );
    }
    let _ = writeln!(
        out,
        "  predicted error of the combination: {:.4} K at the {p}th percentile, {:.4} K at \
         worst; cost {:.3} of the most accurate rendering",
        d.predicted.percentile_k, d.predicted.max_k, d.relative_cost
    );
    if let Some(s) = &d.sampling {
        let _ = writeln!(
            out,
            "  refinement: {:.2} % of the pixels (edges over {:.4} K, thin facets) to a \
             standard error of {:.4} K, about {:.0} rays each, {:.1} % of them predicted to \
             reach the cap of {} x {} rays ({} tried)",
            100.0 * s.candidates_share,
            s.edge_k,
            s.target_k,
            s.paths_per_candidate,
            100.0 * s.capped_share,
            s.max_side,
            s.max_side,
            s.trial_pixels
        );
    }
    let _ = writeln!(
        out,
        "  {:<44} {:>7} {:>7} {:>9} {:>9}  held",
        "class", "share%", "points", "p90(K)", "worst(K)"
    );
    for c in &d.classes {
        let mut name = format!("{} ({}", c.name, c.event);
        for (flag, word) in [
            (c.grazing, ", grazing"),
            (c.horizon, ", horizon"),
            (c.mirror_in_mirror, ", reflecting a mirror"),
            (c.sub_pixel, ", sub-pixel"),
        ] {
            if flag {
                name.push_str(word);
            }
        }
        name.push(')');
        let _ = writeln!(
            out,
            "  {:<44} {:>7.3} {:>7} {:>9.4} {:>9.4}  {}",
            name,
            100.0 * c.share,
            c.samples,
            c.error.percentile_k,
            c.error.max_k,
            if c.guaranteed { "yes" } else { "NO" }
        );
    }
    if d.not_guaranteed_share > 0.0 {
        let _ = writeln!(
            out,
            "  not guaranteed: {:.3} % of the pixels, marked in the truth EXR's `not_guaranteed` \
             layer",
            100.0 * d.not_guaranteed_share
        );
    }
    if let Some(e) = &d.data_error {
        let _ = writeln!(
            out,
            "  the inputs' own error, outside the tolerance (the error budget's): the \
             atmosphere data's along the view paths, {:.4} K at the 99th percentile of the \
             pixels, up to {:.4} K{} (per pixel, with the sky surfaces reflect: the truth \
             EXR's `atmosphere_data_error`)",
            e.p99_k,
            e.max_k,
            if e.unmeasured_share > 0.0 {
                format!(
                    "; {:.1} % of the pixels lie past the widest row in a band never \
                     measured there",
                    100.0 * e.unmeasured_share
                )
            } else {
                String::new()
            }
        );
    } else if let Some(sigma) = d.data_error_k {
        let _ = writeln!(
            out,
            "  the inputs' own error, outside the tolerance (the error budget's): the \
             atmosphere data's interpolation between its rows, up to {sigma:.4} K (one \
             number for the frame: a decision written before the per-pixel record)"
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Settings spelt as a command line spells them, in kebab case.
    const SPELLING: Spelling = Spelling(|setting| format!("--{setting:?}").to_lowercase());

    #[test]
    fn pins_name_a_model_and_one_of_its_settings() {
        assert_eq!("bounces=2".parse::<Pin>(), Ok(Pin::Bounces(2)));
        assert_eq!(
            "supersampling=adaptive-4"
                .parse::<Pin>()
                .map(|p| p.to_string()),
            Ok("supersampling=adaptive-4".to_owned())
        );
        assert!("supersampling=adaptive-4".parse::<Pin>().is_ok());
        let e = "bounce=2".parse::<Pin>().unwrap_err();
        assert!(e.contains("unknown model `bounce`"), "{e}");
        assert!("bounces".parse::<Pin>().is_err());
        assert!("atmosphere=lowtran".parse::<Pin>().is_err());
        assert!("supersampling=0".parse::<Pin>().is_err());
        assert!("sub-bands=0".parse::<Pin>().is_err());
        assert_eq!("sun=off".parse::<Pin>(), Ok(Pin::Sun(false)));
        assert_eq!("shadow-rays=16".parse::<Pin>(), Ok(Pin::ShadowRays(16)));
        assert!("sun=maybe".parse::<Pin>().is_err());
        assert!("shadow-rays=0".parse::<Pin>().is_err());
    }

    #[test]
    fn the_sun_is_on_offer_by_day_only() {
        let materials = MaterialLibrary::default();
        let kinds = [ModelKind::Table];
        let night = offer(&materials, Some(&kinds), true, false, &[], SPELLING).unwrap();
        assert!(night.sun.is_empty() && night.shadow_rays.is_empty());
        let pin: Pin = "sun=off".parse().unwrap();
        assert!(offer(&materials, Some(&kinds), true, false, &[pin], SPELLING).is_err());
        let day = offer(&materials, Some(&kinds), true, true, &[pin], SPELLING).unwrap();
        assert_eq!(day.sun, vec![false]);
        assert!(day.pinned.contains(&SwitchableModel::Sun));
    }

    #[test]
    fn a_spectral_atmosphere_offers_sub_bands_over_the_table_model() {
        let materials = MaterialLibrary::default();
        let kinds = [ModelKind::Table, ModelKind::Layered, ModelKind::Thesis];
        let o = offer(&materials, Some(&kinds), true, false, &[], SPELLING).unwrap();
        assert_eq!(o.sub_bands, SPECTRAL_SUB_BANDS.to_vec());
        assert_eq!(o.atmospheres, vec![ModelKind::Table]);
        // The band model pinned: every atmosphere model again, as without spectra.
        let pin: Pin = "sub-bands=1".parse().unwrap();
        let o = offer(&materials, Some(&kinds), true, false, &[pin], SPELLING).unwrap();
        assert_eq!(o.sub_bands, vec![SubBandCount::BAND]);
        assert_eq!(o.atmospheres, kinds.to_vec());
        // Without spectra only the band model; a count above 1 cannot be pinned.
        let o = offer(&materials, Some(&kinds), false, false, &[], SPELLING).unwrap();
        assert_eq!(o.sub_bands, vec![SubBandCount::BAND]);
        let pin: Pin = "sub-bands=16".parse().unwrap();
        assert!(offer(&materials, Some(&kinds), false, false, &[pin], SPELLING).is_err());
    }
}
