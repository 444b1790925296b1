//! The sub-bands a radiance is summed over: as a caller gives them ([`SubBand`]), as the
//! tracer keeps them with every facet temperature's blackbody radiance precomputed
//! ([`BandData`]), and a set of them on one scene ([`BandSet`]).

use irsig_atmosphere::PathTerms;
use irsig_radiometry::EmissivityTable;

use crate::env::Atmosphere;
use crate::sun::SunBeam;

use super::FacetRadiometry;

/// One sub-band of a spectral rendering: its part of the band, the atmosphere over it and
/// the materials' emissivity over it. A rendering sums the radiance equation over its
/// sub-bands (issue of band averaging: one band-mean τ times one band radiance is only an
/// approximation, measured in docs/accuracy.md).
#[derive(Debug, Clone)]
pub struct SubBand<B, A> {
    /// The blackbody radiance over this sub-band (its wavelengths, weighted by the
    /// response).
    pub band: B,
    /// The atmosphere over this sub-band.
    pub atmosphere: A,
    /// Each material's angular emissivity over this sub-band, in the library's order;
    /// `None`: the materials' own band tables.
    pub emissivity: Option<Vec<EmissivityTable>>,
}

/// A sub-band as the tracer keeps it: the atmosphere, each material's emissivity and the
/// blackbody radiance of every facet temperature, precomputed.
#[derive(Debug)]
pub(crate) struct BandData<A> {
    pub(crate) atmosphere: A,
    /// Per material slot.
    pub(crate) emissivity: Vec<EmissivityTable>,
    /// Per material slot: the table is the tracer's own, so a recorded hit's ε holds here.
    pub(crate) own_emissivity: Vec<bool>,
    /// L_T per temperature index, W m⁻² sr⁻¹; empty when `inline`.
    pub(crate) blackbody: Vec<f64>,
    /// dL_T/dT per temperature index, W m⁻² sr⁻¹ K⁻¹ (for the error budget).
    pub(crate) derivative: Vec<f64>,
    /// The facet records hold this sub-band's L_T (the tracer's own first sub-band).
    pub(crate) inline: bool,
    /// The terrain's L_T and surface-leaving radiance, W m⁻² sr⁻¹.
    pub(crate) terrain_blackbody: f64,
    pub(crate) terrain_leaving: f64,
    /// The sunlight in `terrain_leaving`, W m⁻² sr⁻¹: the beam's and the scattered sky's
    /// (0 at night).
    pub(crate) terrain_solar: f64,
    /// The sun's direct beam in this sub-band ([`Tracer::with_sun`]); `None`: no sun.
    pub(crate) sun: Option<SunBeam>,
    /// L_T and dL_T/dT over the temperatures textured hits reach
    /// ([`crate::texture`]); `None` when no material's texture varies the temperature.
    pub(crate) textured: Option<crate::texture::BlackbodyTable>,
    /// Every temperature index's temperature, K, where some facet has per-material
    /// temperatures (a mixed hit's textured `L(Tᵢ + offset)` reads them); else empty.
    pub(crate) temperatures_k: Vec<f64>,
}

impl<A> BandData<A> {
    /// ε of a recorded hit in this sub-band: the one found when the hit was recorded where
    /// the material's table is the tracer's own, else looked up (bit for bit the same).
    /// A textured hit's ε is the table's scaled by the texel, held to 0 to 1.
    #[inline]
    pub(crate) fn emissivity_of(&self, surface: &crate::path::Surface) -> f64 {
        let slot = usize::from(surface.data.material);
        let eps = if self.own_emissivity[slot] {
            surface.emissivity
        } else {
            self.emissivity[slot].at_cos(surface.cos_incidence)
        };
        if let Some(mix) = &surface.mix {
            return mix
                .parts()
                .map(|(slot, w)| w * self.component_emissivity(slot, surface))
                .sum();
        }
        match surface.texel {
            None => eps,
            Some(texel) => texel.emissivity(eps),
        }
    }

    /// ε of material slot `slot` at a mixed hit in this sub-band, scaled by the hit's
    /// texel ([`crate::mixture`]).
    #[inline]
    pub(crate) fn component_emissivity(&self, slot: usize, surface: &crate::path::Surface) -> f64 {
        let eps = self.emissivity[slot].at_cos(surface.cos_incidence);
        match surface.texel {
            None => eps,
            Some(texel) => texel.emissivity(eps),
        }
    }

    /// L_T of a facet in this sub-band, W m⁻² sr⁻¹.
    #[inline]
    pub(crate) fn blackbody_of(&self, facet: &FacetRadiometry) -> f64 {
        if self.inline {
            facet.blackbody
        } else {
            self.blackbody[facet.temperature_index as usize]
        }
    }

    /// L_T at a hit in this sub-band, W m⁻² sr⁻¹: the facet's, or at a texture's
    /// temperature offset the textured table's; at a mixed hit whose materials have their
    /// own temperatures, `Σ wᵢ εᵢ L(Tᵢ) / Σ wᵢ εᵢ` ([`crate::mixture`]).
    #[inline]
    pub(crate) fn blackbody_at(&self, surface: &crate::path::Surface) -> f64 {
        if let Some(mixed) = self.mixed_blackbody(surface, |l| l.0) {
            return mixed;
        }
        match (surface.texel, &self.textured) {
            (Some(texel), Some(table)) if texel.temperature_offset_k != 0.0 => {
                table
                    .at(surface.data.temperature_k + texel.temperature_offset_k)
                    .0
            }
            _ => self.blackbody_of(&surface.data),
        }
    }

    /// dL_T/dT at a hit in this sub-band, W m⁻² sr⁻¹ K⁻¹ (the error budget's
    /// sensitivity), at its textured temperature where it has one.
    #[inline]
    pub(crate) fn derivative_at(&self, surface: &crate::path::Surface) -> f64 {
        if let Some(mixed) = self.mixed_blackbody(surface, |l| l.1) {
            return mixed;
        }
        match (surface.texel, &self.textured) {
            (Some(texel), Some(table)) if texel.temperature_offset_k != 0.0 => {
                table
                    .at(surface.data.temperature_k + texel.temperature_offset_k)
                    .1
            }
            _ => self.derivative[surface.data.temperature_index as usize],
        }
    }
}

impl<A> BandData<A> {
    /// At a mixed hit whose materials have their own temperatures, the emission-weighted
    /// mean over the materials of `pick` of `(L(Tᵢ), dL/dT(Tᵢ))`: `Σ wᵢ εᵢ xᵢ / Σ wᵢ εᵢ`,
    /// so that the mixture's `ε = Σ wᵢ εᵢ` times it is each material's own emission summed.
    /// `Tᵢ` is offset by the hit's texel as a facet's temperature is. Where no material
    /// emits, the facet's own. `None` at any other hit.
    #[inline]
    fn mixed_blackbody(
        &self,
        surface: &crate::path::Surface,
        pick: impl Fn((f64, f64)) -> f64,
    ) -> Option<f64> {
        let parts = surface.mix.as_ref()?.parts_at_temperatures()?;
        let offset = match (surface.texel, &self.textured) {
            (Some(texel), Some(table)) if texel.temperature_offset_k != 0.0 => {
                Some((texel.temperature_offset_k, table))
            }
            _ => None,
        };
        let (mut sum, mut weight) = (0.0, 0.0);
        for (slot, w, t) in parts {
            let we = w * self.component_emissivity(slot, surface);
            let l = match offset {
                Some((o, table)) => table.at(self.temperatures_k[t] + o),
                None => (self.blackbody[t], self.derivative[t]),
            };
            sum += we * pick(l);
            weight += we;
        }
        if weight > 0.0 {
            Some(sum / weight)
        } else {
            let own = (
                self.blackbody_of(&surface.data),
                self.derivative[surface.data.temperature_index as usize],
            );
            Some(pick(own))
        }
    }
}

/// The sub-bands a radiance is summed over, ready for a tracer's scene: its own
/// ([`Tracer::with_sub_bands`]) or another set on the same scene ([`Tracer::band_set`]),
/// which the pilot evaluates recorded paths with.
#[derive(Debug)]
pub struct BandSet<A> {
    pub(crate) bands: Vec<BandData<A>>,
    /// Every sub-band's atmosphere model shares the first's grids, so a path is located
    /// once and evaluated in each ([`BandSet::path_terms`]).
    pub(crate) shared_grids: bool,
}

impl<A: Atmosphere> BandSet<A> {
    pub(super) fn new(bands: Vec<BandData<A>>) -> Self {
        let shared_grids = match bands.first().and_then(|b| b.atmosphere.model()) {
            Some(first) => bands.iter().all(|b| {
                b.atmosphere
                    .model()
                    .is_some_and(|m| first.shares_path_grids(m))
            }),
            None => false,
        };
        Self {
            bands,
            shared_grids,
        }
    }

    /// The path terms of every sub-band for the path between a sensor at `sensor_m`
    /// and a point at `target_m`, `range_m` apart, passed to `each` in sub-band order: the
    /// same terms, bit for bit, as each sub-band's own `path`, with the grid searches done
    /// once when the sub-bands share their grids.
    #[inline]
    pub(crate) fn path_terms(
        &self,
        sensor_m: f64,
        target_m: f64,
        range_m: f64,
        mut each: impl FnMut(usize, &BandData<A>, PathTerms),
    ) {
        let located = if self.shared_grids {
            self.bands
                .first()
                .and_then(|b| b.atmosphere.model())
                .map(|m| m.locate_path(sensor_m, target_m, range_m))
        } else {
            None
        };
        for (k, b) in self.bands.iter().enumerate() {
            let p = match (&located, b.atmosphere.model()) {
                (Some(g), Some(m)) => m.path_along(g),
                _ => b.atmosphere.path(sensor_m, target_m, range_m),
            };
            each(k, b, p);
        }
    }
}

impl<A> BandSet<A> {
    /// The number of sub-bands.
    #[must_use]
    pub fn len(&self) -> usize {
        self.bands.len()
    }

    /// Whether the set has no sub-band (never, once built).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.bands.is_empty()
    }
}
