//! The radiance equation on a recorded path, summed over the sub-bands (thesis eq. 2 and 6,
//! the events of Figure 6):
//!
//! ```text
//! L = Σ_k τ_k·[ε_k·L_T,k + r_k·(s·L_spec,k + (1 − s)·(F·L_d,k + (1 − F)·L_b,k))] + L_u,k
//! ```
//!
//! With a sun ([`crate::sun`]), `L_spec,k` takes the disk's radiance `E_n,k/Ω_sun` where the
//! mirror direction leaves inside it, and `L_d,k` the sunlit share `E_n,k·cos θ_i·V/π` as
//! a radiance, both at the facet's altitude. By day, with the atmosphere's scattered
//! sunlight ([`Atmosphere::scattered`]), the sky along a ray, the hemispheric sky and each
//! view path's `L_u` gain it for their direction (`crate::day`);
//! it counts as the sun's in the sun's truth terms.
//!
//! By day the sunlight in `L_leaving,k` reaches the sensor through the view path's τ for
//! sunlight (`SunBeam::sunlit_transmission`), the rest through `τ_k`: the two sources have
//! two spectra, and a sub-band's τ averaged for one is wrong for the other
//! ([`crate::sun`]).
//!
//! With one sub-band this is the band model. With several, the truth terms are the
//! band-integrated ones: radiances add over sub-bands; the emissivity is the emitted-
//! radiance-weighted mean `Σ ε_k L_T,k / Σ L_T,k`, and the transmission the one that keeps
//! `L = τ·L_leaving + L_u` true, `Σ τ_k L_leaving,k / Σ L_leaving,k`.

use irsig_atmosphere::PathTerms;
use irsig_radiometry::BandModel;

use crate::charge::ChargeSink;
use crate::day::{
    escaped_sunlight, lit_path, scattered_hemispheric, scattered_sky, sky, sky_hemispheric,
};
use crate::env::Atmosphere;
use crate::path::{Diffuse, Escape, HemiRay, Mirror, Node, Path, Primary};
use crate::path_table::PathTable;
use crate::tracer::{BandData, BandSet, Event, FrameConsts, Sample, Tracer};

/// The terms of one facet's surface-leaving radiance in one sub-band.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct SurfaceTerms {
    pub(crate) emissivity: f64,
    pub(crate) blackbody: f64,
    /// `s·L_spec + (1 − s)·L_diffuse`: what the reflectance multiplies.
    pub(crate) reflected: f64,
    specular_incident: f64,
    sky_hemispheric: f64,
    diffuse_incident: f64,
    pub(crate) leaving: f64,
    /// The sunlight in `leaving` (0 without a sun, or when not asked for).
    solar: f64,
    /// The beam's irradiance on the facet, W m⁻² (0 without a sun, or when not asked for).
    irradiance: f64,
}

/// Band-integrated terms of the first facet, summed over sub-bands.
#[derive(Debug, Clone, Copy, Default)]
struct Sums {
    emitted: f64,
    blackbody: f64,
    specular_incident: f64,
    sky_hemispheric: f64,
    diffuse_incident: f64,
    leaving: f64,
    transmitted: f64,
    path_radiance: f64,
    radiance: f64,
    /// `Σ τ·ε·dL_T/dT`.
    temperature_sensitivity: f64,
    /// `Σ τ·(L_T − L_reflected)`.
    emissivity_sensitivity: f64,
    solar: f64,
    transmitted_solar: f64,
    irradiance: f64,
}

impl Sums {
    /// Adds one sub-band's terms; `derivative` is its dL_T/dT at the facet's temperature,
    /// `transmitted` its `τ·L_leaving` with the sunlight through its own τ
    /// ([`transmitted`]), `solar_transmission` that τ.
    fn add(
        &mut self,
        t: &SurfaceTerms,
        transmission: [f64; 2],
        transmitted: f64,
        path_radiance: f64,
        derivative: f64,
    ) {
        let [transmission, solar_transmission] = transmission;
        self.emitted += t.emissivity * t.blackbody;
        self.blackbody += t.blackbody;
        self.specular_incident += t.specular_incident;
        self.sky_hemispheric += t.sky_hemispheric;
        self.diffuse_incident += t.diffuse_incident;
        self.leaving += t.leaving;
        self.transmitted += transmitted;
        self.path_radiance += path_radiance;
        self.radiance += transmitted + path_radiance;
        self.temperature_sensitivity += transmission * t.emissivity * derivative;
        self.emissivity_sensitivity += transmission * (t.blackbody - t.reflected);
        self.solar += t.solar;
        self.transmitted_solar += solar_transmission * t.solar;
        self.irradiance += t.irradiance;
    }
}

/// Where a path first meets a facet (range and altitude, m), and the path table (built for
/// the sub-bands being summed) its path terms come from, or `None` for the exact terms.
#[derive(Clone, Copy)]
struct FacetPlace<'t> {
    range_m: f64,
    alt_m: f64,
    table: Option<&'t PathTable>,
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// The radiance at the sensor of a recorded path, W m⁻² sr⁻¹. With `TRUTH`, every term
    /// also goes to `s`; without, `s` is not touched. Both give the same radiance, bit for
    /// bit.
    pub(crate) fn radiance<const TRUTH: bool>(
        &self,
        fc: &FrameConsts<'_>,
        path: &Path,
        s: &mut Sample,
    ) -> f64 {
        self.radiance_charged::<TRUTH, ()>(fc, path, s, &mut ())
    }

    /// [`Self::radiance`], each facet the path met charged with its partials to `sink`
    /// ([`crate::charge`]).
    pub(crate) fn radiance_charged<const TRUTH: bool, C: ChargeSink>(
        &self,
        fc: &FrameConsts<'_>,
        path: &Path,
        s: &mut Sample,
        sink: &mut C,
    ) -> f64 {
        self.radiance_sink::<TRUTH, A, C>(&self.bands, fc.path_table.as_ref(), fc, path, s, sink)
    }

    /// [`Self::radiance`] in the sub-bands of `set`, with `table` (built for `set`) for the
    /// path terms of facet hits, or the exact terms when `None`.
    pub(crate) fn radiance_with<const TRUTH: bool, S: Atmosphere>(
        &self,
        set: &BandSet<S>,
        table: Option<&PathTable>,
        fc: &FrameConsts<'_>,
        path: &Path,
        s: &mut Sample,
    ) -> f64 {
        self.radiance_sink::<TRUTH, S, ()>(set, table, fc, path, s, &mut ())
    }

    /// [`Self::radiance_with`], charging `sink`.
    fn radiance_sink<const TRUTH: bool, S: Atmosphere, C: ChargeSink>(
        &self,
        set: &BandSet<S>,
        table: Option<&PathTable>,
        fc: &FrameConsts<'_>,
        path: &Path,
        s: &mut Sample,
        sink: &mut C,
    ) -> f64 {
        match path.primary {
            Primary::Sky { zenith_deg } => {
                self.sky_radiance::<TRUTH, S>(set, fc, path, zenith_deg, s)
            }
            Primary::Terrain {
                range_m,
                path_range_m,
            } => self.terrain_radiance::<TRUTH, S>(set, fc, path, [range_m, path_range_m], s),
            Primary::Facet { range_m, alt_m } => {
                let place = FacetPlace {
                    range_m,
                    alt_m,
                    table,
                };
                self.facet_radiance::<TRUTH, S, C>(set, fc, path, &place, s, sink)
            }
        }
    }

    /// The radiance of a path that escapes to the sky at `zenith_deg`, with its truth.
    fn sky_radiance<const TRUTH: bool, S: Atmosphere>(
        &self,
        set: &BandSet<S>,
        fc: &FrameConsts<'_>,
        path: &Path,
        zenith_deg: f64,
        s: &mut Sample,
    ) -> f64 {
        // The sun's truth terms, when this set of sub-bands carries its beam.
        let lit = TRUTH && set.bands[0].sun.is_some();
        let radiance: f64 = set
            .bands
            .iter()
            .map(|b| sky(b, fc.sensor_alt, zenith_deg, path.dir))
            .sum();
        if TRUTH {
            *s = Sample::miss(Event::Sky);
            s.transmission = 0.0;
            s.path_radiance_w_m2_sr = radiance;
            s.radiance_w_m2_sr = radiance;
            if lit {
                // The sky's sunlight is what it scatters (none without scattered
                // tables).
                let scattered: f64 = set
                    .bands
                    .iter()
                    .map(|b| scattered_sky(b, fc.sensor_alt, zenith_deg, path.dir))
                    .sum();
                s.sun_share = share(scattered, radiance);
            }
        }
        radiance
    }

    /// The radiance of a path that first meets the terrain, `[range, range of the path
    /// terms]` (m) away, with its truth.
    fn terrain_radiance<const TRUTH: bool, S: Atmosphere>(
        &self,
        set: &BandSet<S>,
        fc: &FrameConsts<'_>,
        path: &Path,
        [range_m, path_range_m]: [f64; 2],
        s: &mut Sample,
    ) -> f64 {
        let one = set.bands.len() == 1;
        // The sun's truth terms, when this set of sub-bands carries its beam.
        let lit = TRUTH && set.bands[0].sun.is_some();
        let (mut radiance, mut transmitted, mut path_radiance) = (0.0, 0.0, 0.0);
        let (mut blackbody, mut leaving, mut single_tau) = (0.0, 0.0, 0.0);
        let (mut solar, mut transmitted_solar, mut irradiance) = (0.0, 0.0, 0.0);
        let (mut emitted, mut single_eps) = (0.0, 0.0);
        let cos_sun_zenith = self.sun.as_ref().map_or(0.0, |g| g.to_sun[2].max(0.0));
        set.path_terms(fc.sensor_alt, 0.0, path_range_m, |_, b, p| {
            let (p, scattered) = lit_path(b, p, fc.sensor_alt, 0.0, path.dir);
            let ground = self.terrain_terms(b, path.dir);
            let (through, tau_sun) =
                transmitted_of(b, p.transmission, ground.leaving, ground.solar);
            radiance += through + p.path_radiance_w_m2_sr;
            if TRUTH {
                transmitted += through;
                path_radiance += p.path_radiance_w_m2_sr;
                blackbody += b.terrain_blackbody;
                emitted += ground.emissivity * b.terrain_blackbody;
                single_eps = ground.emissivity;
                leaving += ground.leaving;
                single_tau = p.transmission;
                if let Some(beam) = &b.sun {
                    solar += ground.solar;
                    transmitted_solar += tau_sun * ground.solar + scattered;
                    irradiance += beam.normal_w_m2(0.0) * cos_sun_zenith;
                }
            }
        });
        if TRUTH {
            *s = Sample::miss(Event::Terrain);
            s.range_m = range_m;
            s.temperature_k = self.terrain.temperature_k;
            // A material's: as a facet's, the emitted-radiance-weighted mean over
            // the sub-bands; the constant's is the same in every sub-band.
            s.emissivity = if one || self.terrain_slot.is_none() {
                single_eps
            } else {
                emitted / blackbody
            };
            s.reflectance = 1.0 - s.emissivity;
            s.blackbody_w_m2_sr = blackbody;
            s.surface_leaving_w_m2_sr = leaving;
            s.transmission = effective_transmission(one, single_tau, transmitted, leaving);
            s.path_radiance_w_m2_sr = path_radiance;
            s.radiance_w_m2_sr = radiance;
            if lit {
                // The terrain beyond the scene is flat and unshadowed.
                s.solar_irradiance_w_m2 = irradiance;
                s.sun_visible_fraction = if cos_sun_zenith > 0.0 { 1.0 } else { 0.0 };
                s.reflected_solar_w_m2_sr = solar;
                s.sun_share = share(transmitted_solar, radiance);
            }
        }
        radiance
    }

    /// The radiance of a path that first meets a facet at `place`, with its truth and its
    /// charges.
    fn facet_radiance<const TRUTH: bool, S: Atmosphere, C: ChargeSink>(
        &self,
        set: &BandSet<S>,
        fc: &FrameConsts<'_>,
        path: &Path,
        place: &FacetPlace<'_>,
        s: &mut Sample,
        sink: &mut C,
    ) -> f64 {
        let FacetPlace {
            range_m,
            alt_m,
            table,
        } = *place;
        let one = set.bands.len() == 1;
        // The sun's truth terms, when this set of sub-bands carries its beam.
        let lit = TRUTH && set.bands[0].sun.is_some();
        let cell = table.map(|t| t.cell(alt_m, range_m));
        let mut sums = Sums::default();
        let (mut single, mut single_tau) = (SurfaceTerms::default(), 0.0);
        let mut radiance = 0.0;
        let mut add = |b: &BandData<S>, p: PathTerms| {
            // The path table's terms are the air's own: by day the scattered
            // sunlight is added here for the path's direction, table or not.
            let (p, scattered) = lit_path(b, p, fc.sensor_alt, alt_m, path.dir);
            // By day the sunlight in the leaving radiance is needed apart (it has a
            // path τ of its own), with or without the truth.
            let first = if b.sun.is_some() {
                self.leaving_chain::<true, S>(b, path)
            } else {
                self.leaving_chain::<TRUTH, S>(b, path)
            };
            let (through, tau_sun) = transmitted_of(b, p.transmission, first.leaving, first.solar);
            radiance += through + p.path_radiance_w_m2_sr;
            if C::ON {
                self.charge_path(b, path, &first, p.transmission, sink);
            }
            if TRUTH {
                let derivative = b.derivative_at(&path.nodes[0].surface);
                sums.add(
                    &first,
                    [p.transmission, tau_sun],
                    through,
                    p.path_radiance_w_m2_sr,
                    derivative,
                );
                sums.transmitted_solar += scattered;
                single = first;
                single_tau = p.transmission;
            }
        };
        match (table, cell) {
            (Some(table), Some(cell)) => {
                for (k, b) in set.bands.iter().enumerate() {
                    add(b, table.terms(cell, k));
                }
            }
            _ => set.path_terms(fc.sensor_alt, alt_m, range_m, |_, b, p| add(b, p)),
        }
        if TRUTH {
            self.facet_truth(one, path, range_m, &sums, &single, single_tau, s);
            s.radiance_w_m2_sr = radiance;
            if lit {
                s.solar_irradiance_w_m2 = sums.irradiance;
                s.sun_visible_fraction = path.nodes[0].sun_visible;
                s.reflected_solar_w_m2_sr = sums.solar;
                s.sun_share = share(sums.transmitted_solar, radiance);
            }
        }
        radiance
    }

    /// The truth terms of a path whose first event is a facet.
    #[allow(clippy::too_many_arguments)]
    fn facet_truth(
        &self,
        one: bool,
        path: &Path,
        range_m: f64,
        sums: &Sums,
        single: &SurfaceTerms,
        single_tau: f64,
        s: &mut Sample,
    ) {
        let node = &path.nodes[0];
        let surface = &node.surface;
        let m = &self.materials[usize::from(surface.data.material)];
        *s = Sample::miss(Event::Diffuse);
        s.primary_material = m.id;
        s.facet = Some(surface.facet);
        s.back_face = surface.back_face;
        s.range_m = range_m;
        s.cos_incidence = surface.cos_incidence;
        let texel = surface.texel.unwrap_or(irsig_texture::Texel::NONE);
        s.temperature_k = surface.data.temperature_k + texel.temperature_offset_k;
        s.texture_offset_k = texel.temperature_offset_k;
        s.texture_emissivity_scale = texel.emissivity_scale;
        s.emissivity = if one {
            single.emissivity
        } else {
            sums.emitted / sums.blackbody
        };
        s.reflectance = 1.0 - s.emissivity;
        s.specular_fraction = m.specular_fraction;
        s.blackbody_w_m2_sr = sums.blackbody;
        s.sky_hemispheric_w_m2_sr = sums.sky_hemispheric;
        if let Some(mirror) = node.mirror {
            s.reflected_zenith_deg = node.reflected_z.clamp(-1.0, 1.0).acos().to_degrees();
            s.event = match mirror {
                Mirror::Next => {
                    let second = &path.nodes[1].surface;
                    s.secondary_material = self.materials[usize::from(second.data.material)].id;
                    Event::SpecularHitsFacet
                }
                Mirror::Escaped(_) | Mirror::Untraced(_) => Event::SpecularEscapes,
            };
            s.specular_incident_w_m2_sr = sums.specular_incident;
        }
        if let Some(diffuse) = node.diffuse {
            s.sky_view_factor = match diffuse {
                Diffuse::Hemispheric => 1.0,
                Diffuse::Rays { count, sky, .. } => f64::from(sky) / f64::from(count),
            };
            s.diffuse_incident_w_m2_sr = sums.diffuse_incident;
        }
        s.surface_leaving_w_m2_sr = sums.leaving;
        s.transmission = effective_transmission(one, single_tau, sums.transmitted, sums.leaving);
        s.path_radiance_w_m2_sr = sums.path_radiance;
        s.temperature_sensitivity = sums.temperature_sensitivity;
        s.emissivity_sensitivity = sums.emissivity_sensitivity;
    }

    /// The surface-leaving terms of the path's first facet in sub-band `b`: the chain of
    /// specular bounces evaluated from its far end back. With `SOLAR`, the sunlight in each
    /// leaving radiance too.
    fn leaving_chain<const SOLAR: bool, S: Atmosphere>(
        &self,
        b: &BandData<S>,
        path: &Path,
    ) -> SurfaceTerms {
        let (mut next, mut next_solar) = (0.0, 0.0);
        let mut terms = SurfaceTerms::default();
        for node in path.nodes.iter().rev() {
            terms = self.surface_terms::<SOLAR, S>(b, node, next, next_solar, path);
            next = terms.leaving;
            next_solar = terms.solar;
        }
        terms
    }

    /// `ε·L_T + r·(s·L_spec + (1 − s)·L_diffuse)` of one node in sub-band `b`, given the
    /// surface-leaving radiance `next` of the node its reflection ray hit; with `SOLAR`,
    /// also the sunlight in it, given the sunlight `next_solar` in `next`.
    #[inline]
    pub(crate) fn surface_terms<const SOLAR: bool, S: Atmosphere>(
        &self,
        b: &BandData<S>,
        node: &Node,
        next: f64,
        next_solar: f64,
        path: &Path,
    ) -> SurfaceTerms {
        let surface = &node.surface;
        let (eps, sfrac) = match &surface.mix {
            None => (
                b.emissivity_of(surface),
                self.materials[usize::from(surface.data.material)].specular_fraction,
            ),
            Some(mix) => self.mixed_optics(b, surface, mix),
        };
        let blackbody = b.blackbody_at(surface);
        let sky_hemi = sky_hemispheric(b, surface.alt_m);
        let specular_incident = match node.mirror {
            None => 0.0,
            Some(Mirror::Next) => next,
            Some(Mirror::Escaped(e)) => escaped(b, e),
            Some(Mirror::Untraced(e)) => escaped(b, e),
        };
        let diffuse_incident = match node.diffuse {
            None => 0.0,
            Some(Diffuse::Hemispheric) => sky_hemi,
            Some(Diffuse::Rays { start, count, .. }) => {
                let rays = &path.rays[start as usize..(start + count) as usize];
                let sum: f64 = rays
                    .iter()
                    .map(|ray| match *ray {
                        HemiRay::Facet(h) => {
                            let e2 = b.emissivity_of(&h);
                            e2 * b.blackbody_at(&h) + (1.0 - e2) * sky_hemispheric(b, h.alt_m)
                        }
                        HemiRay::Escaped(e) => escaped(b, e),
                    })
                    .sum();
                sum / f64::from(count)
            }
        };
        // The sun's beam at the facet's altitude: its glint joins what arrives along the
        // mirror direction, its diffuse light the diffuse incident radiance (as the radiance
        // of a uniform sky giving the same irradiance). Without a sun nothing is added.
        let (specular_incident, diffuse_incident) = match &b.sun {
            Some(beam) if node.sun_glint_per_sr > 0.0 || node.sun_diffuse_per_sr > 0.0 => {
                let e = beam.normal_w_m2(surface.alt_m);
                (
                    specular_incident + e * node.sun_glint_per_sr,
                    diffuse_incident + e * node.sun_diffuse_per_sr,
                )
            }
            _ => (specular_incident, diffuse_incident),
        };
        let reflected = sfrac * specular_incident + (1.0 - sfrac) * diffuse_incident;
        let leaving = eps * blackbody + (1.0 - eps) * reflected;
        let (solar, irradiance) = match &b.sun {
            Some(beam) if SOLAR => self.solar_terms(b, beam, node, eps, sfrac, next_solar, path),
            _ => (0.0, 0.0),
        };
        SurfaceTerms {
            emissivity: eps,
            blackbody,
            reflected,
            specular_incident,
            sky_hemispheric: sky_hemi,
            diffuse_incident,
            leaving,
            solar,
            irradiance,
        }
    }

    /// The sunlight in one node's surface-leaving radiance in sub-band `b`, and the beam's
    /// irradiance on it, W m⁻²: the same terms as [`Self::surface_terms`] with everything
    /// that holds no sunlight left out. Sunlight arrives along the mirror direction as the
    /// glint, as what the next node reflects of it (`next_solar`) or from the sunlit
    /// terrain; diffusely as the direct beam and from the sunlit terrain that sky-view rays
    /// reach (the facets they meet reflect the hemispheric sky only).
    #[allow(clippy::too_many_arguments)]
    fn solar_terms<S: Atmosphere>(
        &self,
        b: &BandData<S>,
        beam: &crate::sun::SunBeam,
        node: &Node,
        eps: f64,
        sfrac: f64,
        next_solar: f64,
        path: &Path,
    ) -> (f64, f64) {
        let e = beam.normal_w_m2(node.surface.alt_m);
        let specular = match node.mirror {
            None => 0.0,
            Some(Mirror::Next) => next_solar,
            Some(Mirror::Escaped(Escape::Terrain) | Mirror::Untraced(Escape::Terrain)) => {
                b.terrain_solar
            }
            Some(
                Mirror::Escaped(sky @ Escape::Sky { .. })
                | Mirror::Untraced(sky @ Escape::Sky { .. }),
            ) => escaped_sunlight(b, sky),
        } + e * node.sun_glint_per_sr;
        let diffuse = match node.diffuse {
            None => 0.0,
            Some(Diffuse::Hemispheric) => scattered_hemispheric(b, node.surface.alt_m),
            Some(Diffuse::Rays { start, count, .. }) => {
                let rays = &path.rays[start as usize..(start + count) as usize];
                let terrain = rays
                    .iter()
                    .filter(|r| matches!(r, HemiRay::Escaped(Escape::Terrain)))
                    .count();
                let mut sum = terrain as f64 * b.terrain_solar;
                if b.atmosphere.scattered().is_some() {
                    // The scattered sky's sunlight, escaped or reflected by a facet met.
                    sum += rays
                        .iter()
                        .map(|ray| match *ray {
                            HemiRay::Facet(h) => {
                                (1.0 - b.emissivity_of(&h)) * scattered_hemispheric(b, h.alt_m)
                            }
                            HemiRay::Escaped(Escape::Terrain) => 0.0,
                            HemiRay::Escaped(e) => escaped_sunlight(b, e),
                        })
                        .sum::<f64>();
                }
                sum / f64::from(count)
            }
        } + e * node.sun_diffuse_per_sr;
        let solar = (1.0 - eps) * (sfrac * specular + (1.0 - sfrac) * diffuse);
        (solar, e * node.sun_cos_visible)
    }
}

/// `τ·L_leaving` of sub-band `b` through a view path of transmittance `tau`, and the
/// path's τ for sunlight: by day the sunlight `solar` in `leaving` goes through
/// [`SunBeam::sunlit_transmission`](crate::sun::SunBeam::sunlit_transmission) and the rest
/// through `tau`; without a sun, or where that is `tau` itself, `tau·leaving` and `tau`,
/// as ever.
#[inline]
fn transmitted_of<S: Atmosphere>(
    b: &BandData<S>,
    tau: f64,
    leaving: f64,
    solar: f64,
) -> (f64, f64) {
    if let Some(beam) = &b.sun {
        let tau_sun = beam.sunlit_transmission(tau);
        // A beam without pairs (or whose τ_sun is τ) sums as before, bit for bit.
        if tau_sun.to_bits() != tau.to_bits() {
            return (tau * (leaving - solar) + tau_sun * solar, tau_sun);
        }
    }
    (tau * leaving, tau)
}

/// The sun's share of a radiance at the sensor: its transmitted sunlight over the whole
/// (0 where the radiance is not positive).
fn share(transmitted_solar: f64, radiance: f64) -> f64 {
    if radiance > 0.0 {
        transmitted_solar / radiance
    } else {
        0.0
    }
}

/// The transmission to report: the sub-band's own with one sub-band (`one`), else the
/// leaving-radiance-weighted mean.
fn effective_transmission(one: bool, single: f64, transmitted: f64, leaving: f64) -> f64 {
    if one { single } else { transmitted / leaving }
}

/// Radiance arriving along a ray that left the scene, in one sub-band.
#[inline]
pub(crate) fn escaped<A: Atmosphere>(b: &BandData<A>, e: Escape) -> f64 {
    match e {
        Escape::Sky {
            alt_m,
            zenith_deg,
            dir,
        } => sky(b, alt_m, zenith_deg, dir),
        Escape::Terrain => b.terrain_leaving,
    }
}
