//! Building a tracer: the scene's BVH and per-facet radiometry, its sub-bands with their
//! precomputed blackbody tables, image maps and the sun; and band sets of other sub-bands
//! on the same scene, for the pilot.

use glam::DVec3;
use irsig_model::{MaterialLibrary, RawScene};
use irsig_radiometry::{BandModel, EmissivityTable};

use super::{BandData, BandSet, FacetRadiometry, MaterialData, SubBand, Tracer};
use crate::env::Atmosphere;
use crate::error::{TraceError, TraceErrorKind};
use crate::geometry::Geometry;
use crate::path_table::PathTermsMode;
use crate::sun::{Sun, SunBeam};
use crate::terrain;

impl<B: BandModel + Clone, A: Atmosphere> Tracer<B, A> {
    /// Validates the scene and materials, builds the BVH and precomputes each facet's L_T,
    /// for one band and its atmosphere.
    ///
    /// # Errors
    /// The raw scene or material library is invalid, or a facet names an unknown material.
    pub fn new(
        scene: &RawScene,
        materials: &MaterialLibrary,
        band: B,
        atmosphere: A,
    ) -> Result<Self, TraceError> {
        let one = SubBand {
            band: band.clone(),
            atmosphere,
            emissivity: None,
        };
        Self::with_sub_bands(scene, materials, band, vec![one])
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// [`Tracer::new`] for a radiance summed over `sub_bands` (the spectral model): each
    /// sub-band brings its own blackbody radiance, atmosphere and, optionally, material
    /// emissivities. `band` is the whole band, whose inverse gives the apparent
    /// temperature; the sub-bands should partition it.
    ///
    /// # Errors
    /// As [`Tracer::new`]; also no sub-band, or a sub-band whose emissivity list does not
    /// have one table per material.
    pub fn with_sub_bands(
        scene: &RawScene,
        materials: &MaterialLibrary,
        band: B,
        sub_bands: Vec<SubBand<B, A>>,
    ) -> Result<Self, TraceError> {
        Self::with_sub_bands_and_maps(scene, materials, band, sub_bands, Vec::new())
    }

    /// [`Tracer::with_sub_bands`] with image maps: `maps` gives, for each material of the
    /// library that has `maps`, its maps with their images read (`irsig-raster` reads
    /// them; the tracer knows no file).
    ///
    /// # Errors
    /// As [`Tracer::with_sub_bands`]; also a facet of a material with maps that has no
    /// texture coordinates, or an emissivity-scale map that takes ε outside 0 to 1.
    pub fn with_sub_bands_and_maps(
        scene: &RawScene,
        materials: &MaterialLibrary,
        band: B,
        sub_bands: Vec<SubBand<B, A>>,
        maps: Vec<(irsig_model::MaterialId, irsig_texture::MaterialMaps)>,
    ) -> Result<Self, TraceError> {
        scene
            .validate()
            .map_err(|e| TraceError::new(TraceErrorKind::InvalidScene(e)))?;
        materials
            .validate()
            .map_err(|e| TraceError::new(TraceErrorKind::InvalidMaterials(e)))?;
        if sub_bands.is_empty() {
            return Err(TraceError::new(TraceErrorKind::InvalidOptions(
                "no sub-band: expected at least one".into(),
            )));
        }
        let (slot_of, mut mats, tables) = material_data(materials)?;
        for (id, m) in maps {
            if let Some(slot) = mats.iter().position(|d| d.id == id.0) {
                mats[slot].maps = Some(m);
            }
        }
        mix_slots(materials, &slot_of, &mut mats)?;
        let (mut temperatures, mut index_of, temperature_index) =
            temperature_indices(scene, &slot_of)?;
        let mix_temperatures = crate::mixture::mix_temperature_indices(scene, materials, |t| {
            *index_of.entry(t.to_bits()).or_insert_with(|| {
                temperatures.push(t);
                (temperatures.len() - 1) as u32
            })
        })?;
        drop(index_of);
        let terrain_slot = match scene.terrain.material {
            None => None,
            Some(m) if slot_of[usize::from(m.0)] == u16::MAX => {
                return Err(TraceError::new(TraceErrorKind::UnknownTerrainMaterial {
                    material: m.0,
                }));
            }
            Some(m) => Some(slot_of[usize::from(m.0)]),
        };
        let first = &sub_bands[0].band;
        let blackbody: Vec<f64> = temperatures.iter().map(|&t| first.radiance(t)).collect();
        let radiometry = |i: usize| {
            let t = temperature_index[i] as usize;
            FacetRadiometry {
                material: slot_of[usize::from(scene.facets[i].material.0)],
                temperature_index: t as u32,
                temperature_k: temperatures[t],
                blackbody: blackbody[t],
            }
        };
        // Indices were checked by validate().
        let triangle = |i: usize| {
            scene.facets[i]
                .vertices
                .map(|v| DVec3::from(scene.positions_m[v as usize]))
        };
        let geometry = Geometry::with_data(scene.facets.len(), triangle, radiometry);
        drop(temperature_index);
        let mut tracer = Self {
            geometry,
            materials: mats,
            terrain: scene.terrain,
            terrain_slot,
            band,
            bands: BandSet {
                bands: Vec::new(),
                shared_grids: false,
            },
            temperatures,
            emissivity: tables,
            path_terms: PathTermsMode::Exact,
            refinement: None,
            sun: None,
            budget_groups: None,
            textured_span_k: None,
            uv_maps: Vec::new(),
            filters_footprint: false,
            mix_temperatures,
        };
        let has_maps: Vec<bool> = tracer.materials.iter().map(|m| m.maps.is_some()).collect();
        let slot = |id: u16| usize::from(slot_of[usize::from(id)]);
        tracer.uv_maps = crate::texture::facet_uv_maps(scene, slot, &has_maps)?;
        tracer.filters_footprint = tracer.materials.iter().any(|m| {
            m.texture
                .as_ref()
                .is_some_and(irsig_texture::TextureFields::filters_footprint)
                || m.maps
                    .as_ref()
                    .is_some_and(irsig_texture::MaterialMaps::filters_footprint)
        });
        tracer.textured_span_k = tracer.textured_span(scene);
        let mut own = tracer.band_set(sub_bands)?;
        // The first sub-band's L_T is in the facet records; its table is kept only where a
        // hit may take a material's own temperature ([`crate::mixture`]).
        own.bands[0].inline = true;
        if tracer.mix_temperatures.is_empty() {
            own.bands[0].blackbody = Vec::new();
        }
        tracer.bands = own;
        Ok(tracer)
    }

    /// This tracer with its sub-bands replaced by `sub_bands` (another atmosphere or
    /// another partition of the band), the BVH kept. The sun, whose beam is given per
    /// sub-band, goes with the old sub-bands: give it again ([`Self::with_sun`]).
    ///
    /// # Errors
    /// As [`Tracer::band_set`].
    pub fn with_bands(mut self, sub_bands: Vec<SubBand<B, A>>) -> Result<Self, TraceError> {
        self.bands = self.band_set(sub_bands)?;
        self.sun = None;
        Ok(self)
    }

    /// This tracer lit by `sun` (`None`: no sun, the default), whose beam list holds one
    /// beam per sub-band of the tracer's own ([`crate::sun`] says what the sun adds). Band
    /// sets made for other sub-bands ([`Self::band_set`]) have no sun. Setting a sun again
    /// replaces the previous one.
    ///
    /// # Errors
    /// A sun direction that is not a finite non-zero vector, an angular radius outside
    /// (0°, 10°], a shadow-ray count outside 1 to [`crate::sun::MAX_SHADOW_RAYS`], or not
    /// one beam per sub-band.
    pub fn with_sun(mut self, sun: Option<Sun>) -> Result<Self, TraceError> {
        let Some(sun) = sun else {
            self.remove_sun();
            return Ok(self);
        };
        let geometry = sun.geometry()?;
        if sun.beams.len() != self.bands.len() {
            return Err(TraceError::new(TraceErrorKind::InvalidOptions(format!(
                "sun: {} beams for {} sub-bands: expected one per sub-band",
                sun.beams.len(),
                self.bands.len()
            ))));
        }
        self.remove_sun();
        let mut bands = std::mem::take(&mut self.bands.bands);
        for (b, beam) in bands.iter_mut().zip(sun.beams) {
            let eps = self.terrain_emissivity(b);
            b.terrain_leaving = terrain::leaving(eps, b, Some((&beam, &geometry)));
            b.terrain_solar = terrain::solar(eps, b, Some((&beam, &geometry)));
            b.sun = Some(beam);
        }
        self.bands.bands = bands;
        self.sun = Some(geometry);
        Ok(self)
    }

    /// Takes the sun away, its terrain term with it.
    fn remove_sun(&mut self) {
        if self.sun.take().is_none() {
            return;
        }
        let mut bands = std::mem::take(&mut self.bands.bands);
        for b in &mut bands {
            let eps = self.terrain_emissivity(b);
            b.sun = None;
            b.terrain_leaving = terrain::leaving(eps, b, None);
            b.terrain_solar = terrain::solar(eps, b, None);
        }
        self.bands.bands = bands;
    }

    /// `set` (made by [`Self::band_set`]) lit by this tracer's sun with one beam per
    /// sub-band: what the pilot evaluates a sunlit frame's recorded paths with, so that
    /// its sub-band sets carry the sunlight of their own sub-bands. `None`: no sun, the
    /// set as it was.
    ///
    /// # Errors
    /// Beams given to a tracer without a sun, or not one beam per sub-band.
    pub fn lit_band_set<S: Atmosphere>(
        &self,
        mut set: BandSet<S>,
        beams: Option<Vec<SunBeam>>,
    ) -> Result<BandSet<S>, TraceError> {
        let Some(beams) = beams else {
            return Ok(set);
        };
        let bad = |m: String| TraceError::new(TraceErrorKind::InvalidOptions(m));
        let geometry = self
            .sun
            .as_ref()
            .ok_or_else(|| bad("sun beams for a band set of a tracer without a sun".into()))?;
        if beams.len() != set.len() {
            return Err(bad(format!(
                "sun: {} beams for {} sub-bands: expected one per sub-band",
                beams.len(),
                set.len()
            )));
        }
        for (b, beam) in set.bands.iter_mut().zip(beams) {
            let eps = self.terrain_emissivity(b);
            b.terrain_leaving = terrain::leaving(eps, b, Some((&beam, geometry)));
            b.terrain_solar = terrain::solar(eps, b, Some((&beam, geometry)));
            b.sun = Some(beam);
        }
        Ok(set)
    }

    /// Whether the sun shines on this tracer's scene ([`Self::with_sun`]).
    #[must_use]
    pub fn has_sun(&self) -> bool {
        self.sun.is_some()
    }

    /// The sub-bands `sub_bands` prepared for this tracer's scene: every facet temperature's
    /// and the terrain's blackbody radiance in each, and each material's emissivity. For
    /// evaluating recorded paths under another band model or atmosphere (the pilot).
    ///
    /// # Errors
    /// No sub-band, or a sub-band whose emissivity list does not have one table per
    /// material.
    pub fn band_set<S: Atmosphere>(
        &self,
        sub_bands: Vec<SubBand<B, S>>,
    ) -> Result<BandSet<S>, TraceError> {
        if sub_bands.is_empty() {
            return Err(TraceError::new(TraceErrorKind::InvalidOptions(
                "no sub-band: expected at least one".into(),
            )));
        }
        let terrain = self.terrain;
        let mut bands = Vec::with_capacity(sub_bands.len());
        for (k, sb) in sub_bands.into_iter().enumerate() {
            let emissivity = match sb.emissivity {
                None => self.emissivity.clone(),
                Some(e) if e.len() == self.emissivity.len() => e,
                Some(e) => {
                    return Err(TraceError::new(TraceErrorKind::InvalidOptions(format!(
                        "sub-band {}: {} emissivity tables for {} materials",
                        k + 1,
                        e.len(),
                        self.emissivity.len()
                    ))));
                }
            };
            crate::texture::check_emissivity_scales(&self.materials, &emissivity, k)?;
            let (blackbody, derivative) = self
                .temperatures
                .iter()
                .map(|&t| sb.band.radiance_and_derivative(t))
                .unzip();
            let terrain_blackbody = sb.band.radiance(terrain.temperature_k);
            let own_emissivity = emissivity
                .iter()
                .zip(&self.emissivity)
                .map(|(a, b)| a == b)
                .collect();
            let textured = self
                .textured_span_k
                .map(|span| crate::texture::BlackbodyTable::new(&sb.band, span));
            bands.push(BandData {
                textured,
                temperatures_k: if self.mix_temperatures.is_empty() {
                    Vec::new()
                } else {
                    self.temperatures.clone()
                },
                atmosphere: sb.atmosphere,
                emissivity,
                own_emissivity,
                blackbody,
                derivative,
                inline: false,
                terrain_blackbody,
                terrain_leaving: 0.0,
                terrain_solar: 0.0,
                sun: None,
            });
            let b = bands.last_mut().expect("just pushed");
            let eps = self.terrain_emissivity(b);
            b.terrain_leaving = terrain::leaving(eps, b, None);
            b.terrain_solar = terrain::solar(eps, b, None);
        }
        Ok(BandSet::new(bands))
    }

    /// The span of temperatures, K, that the hits of materials whose texture varies the
    /// temperature reach: their facets' coldest minus and hottest plus the largest offset
    /// any of them gives. `None`: no such material has a facet.
    fn textured_span(&self, scene: &RawScene) -> Option<[f64; 2]> {
        let offset: Vec<f64> = self
            .materials
            .iter()
            .map(|m| {
                m.texture
                    .as_ref()
                    .map_or(0.0, irsig_texture::TextureFields::max_temperature_offset_k)
                    + m.maps
                        .as_ref()
                        .map_or(0.0, irsig_texture::MaterialMaps::max_temperature_offset_k)
            })
            .collect();
        if offset.iter().all(|&o| o <= 0.0) {
            return None;
        }
        let slot_of: std::collections::HashMap<u16, usize> = self
            .materials
            .iter()
            .enumerate()
            .map(|(slot, m)| (m.id, slot))
            .collect();
        let mut span: Option<[f64; 2]> = None;
        let mut reach = |t: f64, o: f64| {
            let [lo, hi] = span.get_or_insert([f64::INFINITY, f64::NEG_INFINITY]);
            *lo = lo.min(t - o);
            *hi = hi.max(t + o);
        };
        let offset_of =
            |f: &irsig_model::RawFacet| slot_of.get(&f.material.0).map_or(0.0, |&s| offset[s]);
        for f in &scene.facets {
            let o = offset_of(f);
            if o > 0.0 {
                reach(f.temperature_k, o);
            }
        }
        // A mapped facet's materials at their own temperatures, offset by its texture.
        for m in &scene.mix_temperatures {
            let o = offset_of(&scene.facets[m.facet as usize]);
            if o > 0.0 {
                for &t in &m.temperatures_k {
                    reach(t, o);
                }
            }
        }
        span
    }
}

/// Each material map's materials as slots ([`MaterialData::mix_slots`]), once its image is
/// given with the material's maps.
///
/// # Errors
/// A material map whose image was not given, or whose specular materials differ in lobe.
fn mix_slots(
    library: &MaterialLibrary,
    slot_of: &[u16],
    mats: &mut [MaterialData],
) -> Result<(), TraceError> {
    for (m, data) in library.materials.iter().zip(mats.iter_mut()) {
        let Some(map) = m.maps.as_ref().and_then(|x| x.material.as_ref()) else {
            continue;
        };
        let loaded = data.maps.as_ref().and_then(|x| x.material());
        if loaded.is_none_or(|l| l.materials() != map.materials().len()) {
            return Err(TraceError::new(TraceErrorKind::InvalidOptions(format!(
                "material {} ({}): its material map `{}` was not given with its image",
                m.id.0, m.name, map.image
            ))));
        }
        crate::mixture::check_shared_lobe(m, library)?;
        // The library's validation found every name.
        data.mix_slots = map
            .materials()
            .into_iter()
            .filter_map(|n| library.by_name(n))
            .map(|c| slot_of[usize::from(c.id.0)])
            .collect();
    }
    Ok(())
}

/// A material library as the tracer holds it: each id's slot (indexed by id; `u16::MAX`:
/// none), and in slot order each material's data and angular emissivity table.
type Slots = (Vec<u16>, Vec<MaterialData>, Vec<EmissivityTable>);

/// The library's [`Slots`].
fn material_data(materials: &MaterialLibrary) -> Result<Slots, TraceError> {
    let mut slot_of = vec![u16::MAX; usize::from(u16::MAX) + 1];
    let mut mats = Vec::with_capacity(materials.materials.len());
    let mut tables = Vec::with_capacity(materials.materials.len());
    for (slot, m) in materials.materials.iter().enumerate() {
        slot_of[usize::from(m.id.0)] = slot as u16;
        let (angle_deg, emissivity) = m.emissivity.iter().copied().unzip();
        let table = EmissivityTable::new(angle_deg, emissivity).map_err(|e| {
            TraceError::new(TraceErrorKind::InvalidEmissivity {
                material: m.id.0,
                reason: e.to_string(),
            })
        })?;
        tables.push(table);
        let texture = match &m.texture {
            Some(t) if t.varies() => Some(irsig_texture::TextureFields::new(t).map_err(|e| {
                TraceError::new(TraceErrorKind::InvalidOptions(format!(
                    "material {}: {e}",
                    m.id.0
                )))
            })?),
            _ => None,
        };
        mats.push(MaterialData {
            id: m.id.0,
            name: m.name.clone(),
            specular_fraction: m.specular_fraction,
            lobe: m
                .rms_slope
                .filter(|&sigma| sigma > 0.0 && m.specular_fraction > 0.0)
                .map(crate::lobe::Lobe::new),
            texture,
            maps: None,
            mix_slots: Vec::new(),
        });
    }
    Ok((slot_of, mats, tables))
}

/// The scene's distinct facet temperatures (K), their index by bit pattern, and each
/// facet's index into them.
type TemperatureIndex = (Vec<f64>, std::collections::HashMap<u64, u32>, Vec<u32>);

/// The scene's [`TemperatureIndex`], once every facet's material is known (`slot_of`).
fn temperature_indices(scene: &RawScene, slot_of: &[u16]) -> Result<TemperatureIndex, TraceError> {
    // One table entry per distinct temperature (scenes hold few, and neighbouring facets
    // usually share one), so K sub-bands cost K small tables, not K × facets; the
    // records' L_T is read from the first sub-band's.
    let mut temperatures: Vec<f64> = Vec::new();
    let mut index_of: std::collections::HashMap<u64, u32> = std::collections::HashMap::new();
    let mut last: Option<(u64, u32)> = None;
    let mut temperature_index = Vec::with_capacity(scene.facets.len());
    for (i, f) in scene.facets.iter().enumerate() {
        if slot_of[usize::from(f.material.0)] == u16::MAX {
            return Err(TraceError::new(TraceErrorKind::UnknownMaterial {
                facet: i,
                material: f.material.0,
            }));
        }
        let bits = f.temperature_k.to_bits();
        temperature_index.push(match last {
            Some((b, index)) if b == bits => index,
            _ => {
                let index = *index_of.entry(bits).or_insert_with(|| {
                    temperatures.push(f.temperature_k);
                    (temperatures.len() - 1) as u32
                });
                last = Some((bits, index));
                index
            }
        });
    }
    Ok((temperatures, index_of, temperature_index))
}
