//! Material maps at a hit: which materials of the library lie at the point, and the optics
//! of their mixture.
//!
//! A material map ([`irsig_model::material_map`]) gives, at a hit's texture coordinates
//! (read with the map's filter over the ray's footprint, at every event the image maps are
//! read at), each of its materials' area fraction `wᵢ`. Where one material has it all (the
//! Nearest filter always; the others inside a texel's patch of one material) the hit *is*
//! that material: its record carries that material's slot and everything after (emissivity
//! table, specular share, lobe, truth layers) is the material's, exactly as on a facet of
//! its own. Elsewhere the hit is a mixture ([`Mix`]), carried with the hit, whose optics
//! are linear in the fractions: in each sub-band and at the hit's angle
//! `ε = Σ wᵢ εᵢ`, specular reflectance `Σ wᵢ (1 − εᵢ) sᵢ` and diffuse `Σ wᵢ (1 − εᵢ)(1 − sᵢ)`,
//! so its surface-leaving radiance `ε L_T + ρ_s L_spec + ρ_d L_diff` is exactly the
//! fraction-weighted mean of each material's on its own, under the same incident light
//! and at the facet's one temperature. Where the raw scene gives the facet per-material
//! temperatures (`RawScene::mix_temperatures`, what `irsig-therm`'s per-material walls
//! solve), each material emits at its own: a hit of one material at `Tₖ` (its record's
//! temperature), a mixed hit `Σ wᵢ εᵢ L(Tᵢ)`, carried as the mixture's `L_T` times its `ε`
//! (`L_T = Σ wᵢ εᵢ L(Tᵢ) / Σ wᵢ εᵢ`, and `dL_T/dT` alike for the error budget). The host
//! material's statistical texture and grey
//! image maps still apply (to each εᵢ); the mixed materials' own textures are not read.
//! The record's slot is the material of the greatest fraction, which the truth layers
//! name. Materials without a material map never reach this module.

use irsig_model::material_map::MAX_MAP_MATERIALS;

use crate::geometry::Hit;
use crate::tracer::{BandData, FacetRadiometry, Tracer};

/// A mixture of materials at a hit: each material's slot and its area fraction (0 past the
/// map's materials).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Mix {
    pub(crate) slots: [u16; MAX_MAP_MATERIALS],
    pub(crate) weights: [f32; MAX_MAP_MATERIALS],
    /// Each material's temperature index, where the facet has per-material temperatures;
    /// [`NO_TEMPERATURES`] in the first place where it has none (every material then at
    /// the facet's temperature).
    pub(crate) temperatures: [u32; MAX_MAP_MATERIALS],
}

/// [`Mix::temperatures`]'s first place on a facet without per-material temperatures.
pub(crate) const NO_TEMPERATURES: u32 = u32::MAX;

impl Mix {
    /// The mixed materials with a fraction above 0: `(slot, fraction)`.
    #[inline]
    pub(crate) fn parts(&self) -> impl Iterator<Item = (usize, f64)> + '_ {
        self.slots
            .iter()
            .zip(self.weights)
            .filter(|(_, w)| *w > 0.0)
            .map(|(&s, w)| (usize::from(s), f64::from(w)))
    }

    /// The mixed materials with a fraction above 0 and their temperature indices, when the
    /// facet has per-material temperatures: `(slot, fraction, temperature index)`.
    #[inline]
    pub(crate) fn parts_at_temperatures(
        &self,
    ) -> Option<impl Iterator<Item = (usize, f64, usize)> + '_> {
        (self.temperatures[0] != NO_TEMPERATURES).then(|| {
            self.slots
                .iter()
                .zip(self.weights)
                .zip(self.temperatures)
                .filter(|((_, w), _)| *w > 0.0)
                .map(|((&s, w), t)| (usize::from(s), f64::from(w), t as usize))
        })
    }
}

impl<B, A> Tracer<B, A> {
    /// The radiometry record of a hit under its material's material map, and the mixture
    /// there when more than one material has a fraction: the record names the material of
    /// the greatest fraction. A hit whose material has no material map is returned as it
    /// is, with no mixture.
    #[inline]
    pub(crate) fn resolve_material(
        &self,
        hit: &Hit<FacetRadiometry>,
        footprint: Option<&irsig_texture::Footprint>,
    ) -> (FacetRadiometry, Option<Mix>) {
        let m = &self.materials[usize::from(hit.data.material)];
        let (Some(map), Some(uv)) = (
            m.maps.as_ref().and_then(|x| x.material()),
            self.uv_maps.get(hit.facet as usize).copied().flatten(),
        ) else {
            return (hit.data, None);
        };
        let p_m = self.geometry.to_world(hit.point_local);
        let w = map.sample(uv.at(p_m), uv.footprint_uv(footprint));
        let mut data = hit.data;
        let mut best = 0;
        for k in 1..map.materials() {
            if w[k] > w[best] {
                best = k;
            }
        }
        data.material = m.mix_slots[best];
        let temperatures = self
            .mix_temperatures
            .get(hit.facet as usize)
            .copied()
            .flatten();
        if w.iter().filter(|&&x| x > 0.0).count() <= 1 {
            if let Some(t) = temperatures {
                let index = t[best] as usize;
                data.temperature_index = t[best];
                data.temperature_k = self.temperatures[index];
                data.blackbody = self.bands.bands[0].blackbody[index];
            }
            return (data, None);
        }
        let mut slots = [data.material; MAX_MAP_MATERIALS];
        slots[..m.mix_slots.len()].copy_from_slice(&m.mix_slots);
        let weights = w.map(|x| x as f32);
        let temperatures = temperatures.unwrap_or([NO_TEMPERATURES; MAX_MAP_MATERIALS]);
        (
            data,
            Some(Mix {
                slots,
                weights,
                temperatures,
            }),
        )
    }

    /// Which reflected parts a hit with record `data` and mixture `mix` has: a specular
    /// share anywhere (a mirror ray), a diffuse share anywhere (sky-view rays), and the
    /// specular share's lobe (the materials of one map share it, checked when built).
    #[inline]
    pub(crate) fn reflection_parts(
        &self,
        data: &FacetRadiometry,
        mix: Option<&Mix>,
    ) -> (bool, bool, Option<&crate::lobe::Lobe>) {
        match mix {
            None => {
                let m = &self.materials[usize::from(data.material)];
                (
                    m.specular_fraction > 0.0,
                    m.specular_fraction < 1.0,
                    m.lobe.as_ref(),
                )
            }
            Some(mix) => {
                let (mut specular, mut diffuse, mut lobe) = (false, false, None);
                for (slot, _) in mix.parts() {
                    let m = &self.materials[slot];
                    specular |= m.specular_fraction > 0.0;
                    diffuse |= m.specular_fraction < 1.0;
                    lobe = lobe.or(m.lobe.as_ref());
                }
                (specular, diffuse, lobe)
            }
        }
    }

    /// ε and the specular share `s` of the reflectance at a mixed hit in sub-band `b`:
    /// `ε = Σ wᵢ εᵢ` and `s = Σ wᵢ (1 − εᵢ) sᵢ / (1 − ε)` (0 where nothing is reflected), so
    /// that `(1 − ε) s` and `(1 − ε)(1 − s)` are the mixture's specular and diffuse
    /// reflectances. Each `εᵢ` is scaled by the hit's texel as a material's own would be.
    #[inline]
    pub(crate) fn mixed_optics<S>(
        &self,
        b: &BandData<S>,
        surface: &crate::path::Surface,
        mix: &Mix,
    ) -> (f64, f64) {
        let (mut eps, mut specular) = (0.0, 0.0);
        for (slot, w) in mix.parts() {
            let e = b.component_emissivity(slot, surface);
            eps += w * e;
            specular += w * (1.0 - e) * self.materials[slot].specular_fraction;
        }
        let r = 1.0 - eps;
        (eps, if r > 0.0 { specular / r } else { 0.0 })
    }
}

/// Each facet's per-material temperatures as indices into `temperatures` (each added
/// there once), when the scene gives any: `None` for a facet without; an empty list when
/// the scene has none.
///
/// # Errors
/// An entry whose count is not its facet's material map's material count, or whose facet's
/// material has no material map: naming the entry, the facet, the material and the map.
pub(crate) fn mix_temperature_indices(
    scene: &irsig_model::RawScene,
    library: &irsig_model::MaterialLibrary,
    mut index_of: impl FnMut(f64) -> u32,
) -> Result<Vec<Option<[u32; MAX_MAP_MATERIALS]>>, crate::error::TraceError> {
    if scene.mix_temperatures.is_empty() {
        return Ok(Vec::new());
    }
    let mut out = vec![None; scene.facets.len()];
    for (k, entry) in scene.mix_temperatures.iter().enumerate() {
        // The scene's validation put every facet in range.
        let i = entry.facet as usize;
        let id = scene.facets[i].material;
        let host = library.by_id(id);
        let map = host.and_then(|m| m.maps.as_ref()?.material.as_ref());
        let expected = map.map_or(0, |m| m.materials().len());
        if expected != entry.temperatures_k.len() {
            let name = host.map_or("?", |m| m.name.as_str());
            let why = match map {
                Some(m) => format!(
                    "its material map `{}` mixes {expected} materials: expected one \
                     temperature per material, in the map's order",
                    m.image
                ),
                None => "the material has no material map to give them to".to_owned(),
            };
            return Err(crate::error::TraceError::new(
                crate::error::TraceErrorKind::InvalidOptions(format!(
                    "raw scene: mix_temperatures[{k}]: facet {i} (material {} ({name})) has \
                     {} per-material temperatures, and {why}",
                    id.0,
                    entry.temperatures_k.len()
                )),
            ));
        }
        let mut t = [0; MAX_MAP_MATERIALS];
        for (slot, &kelvin) in t.iter_mut().zip(&entry.temperatures_k) {
            *slot = index_of(kelvin);
        }
        out[i] = Some(t);
    }
    Ok(out)
}

/// Refuses a material map whose materials with a specular share have different lobes
/// (RMS slopes): a mixed hit's mirror ray and glint are traced once, for one lobe.
///
/// # Errors
/// The host material and the two slopes.
pub(crate) fn check_shared_lobe(
    host: &irsig_model::Material,
    library: &irsig_model::MaterialLibrary,
) -> Result<(), crate::error::TraceError> {
    let Some(map) = host.maps.as_ref().and_then(|m| m.material.as_ref()) else {
        return Ok(());
    };
    let slope = |m: &irsig_model::Material| m.rms_slope.filter(|&s| s > 0.0);
    let mut first: Option<(&str, Option<f64>)> = None;
    for name in map.materials() {
        let Some(m) = library.by_name(name) else {
            continue;
        };
        if m.specular_fraction <= 0.0 {
            continue;
        }
        match first {
            None => first = Some((name, slope(m))),
            Some((other, s)) if s != slope(m) => {
                return Err(crate::error::TraceError::new(
                    crate::error::TraceErrorKind::InvalidOptions(format!(
                        "material {} ({}): its material map mixes `{other}` (RMS slope \
                         {s:?}) and `{name}` (RMS slope {:?}), whose specular shares differ \
                         in roughness: expected one RMS slope for all of a map's specular \
                         materials",
                        host.id.0,
                        host.name,
                        slope(m)
                    )),
                ));
            }
            Some(_) => {}
        }
    }
    Ok(())
}
