//! The error budget's charges: each ray's partial derivatives of the radiance at the sensor,
//! charged to the input group of every facet the ray's events met, and summed per pixel.
//!
//! A declared uncertainty is one input: every facet it governs is off by the same error
//! (a correlated input, GUM §5.2), so the pixel's sensitivity to it is the sum over the
//! events that met those facets, averaged over the pixel's rays as its radiance is:
//! `∂L̄/∂x = Σ_rays Σ_events ∂L/∂x / n`. The caller says which facets share an input
//! ([`crate::Tracer::with_budget_groups`]); the tracer knows nothing of uncertainties. A
//! pixel whose rays meet a material on 30 % of its area so gets 30 % of that material's
//! sensitivity, whatever its centre ray met.
//!
//! Along a path of specular bounces the radiance is
//! `L = τ·(ε₀L_T,0 + r₀s₀·L₁ + …) + L_u` with `L_j` the surface-leaving radiance of the
//! j-th facet (thesis eq. 2 and 6), so the j-th event's partials are those of its own
//! surface carried by the throughput before it, `τ·Π_{i<j} r_i s_i`:
//! `∂L/∂T_j = τ·Π r_i s_i·ε_j·dL_T,j/dT` and `∂L/∂ε_j = τ·Π r_i s_i·(L_T,j − L_refl,j)`
//! (a change of ε moves r = 1 − ε the other way). A facet a sky-view ray meets brings
//! `ε₂·L_T2 + r₂·L_d` as one of the `n` rays of the diffuse incident radiance, so it is
//! charged `τ·Π r_i s_i·r_j(1 − s_j)/n` times its own `ε₂·dL_T2/dT` and `L_T2 − L_d`.
//! Facets beyond the last bounce are not traced, and do not move the radiance: nothing is
//! charged to them (their absence is a model's error, the tolerance's).

use irsig_radiometry::BandModel;

use crate::day::sky_hemispheric;
use crate::env::Atmosphere;
use crate::path::{Diffuse, HemiRay, Mirror, Path, Surface};
use crate::shade::SurfaceTerms;
use crate::tracer::{BandData, Tracer};

/// The group of a facet that is charged to no input.
pub const NO_GROUP: u32 = u32::MAX;

/// The most facets one path meets: the primary hit and 64 specular bounces
/// ([`crate::TraceOptions::specular_bounces`]'s largest).
pub(crate) const MAX_EVENTS: usize = 65;

/// One input group's share of a pixel's partial derivatives: means over the pixel's rays.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Charge {
    /// The group ([`crate::Tracer::with_budget_groups`]).
    pub group: u32,
    /// ∂L/∂T of the group's facets moved together, W m⁻² sr⁻¹ K⁻¹.
    pub temperature_sensitivity: f32,
    /// ∂L/∂ε of the group's facets moved together, W m⁻² sr⁻¹.
    pub emissivity_sensitivity: f32,
}

/// The charges of every pixel of a frame, row-major: each pixel's few [`Charge`]s, in the
/// order its rays first met their groups, stored end to end.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Charges {
    /// Where each pixel's charges end in `entries`.
    ends: Vec<u32>,
    entries: Vec<Charge>,
    /// The rays each pixel's charges are the mean of.
    rays: Vec<u32>,
}

impl Charges {
    /// The pixels held (0: the frame kept no charges).
    #[must_use]
    pub fn len(&self) -> usize {
        self.ends.len()
    }

    /// Whether the frame kept no charges.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }

    /// The charges of pixel `i` (empty past the end, or where the pixel met no group).
    #[must_use]
    pub fn pixel(&self, i: usize) -> &[Charge] {
        let Some(&end) = self.ends.get(i) else {
            return &[];
        };
        let start = if i == 0 { 0 } else { self.ends[i - 1] };
        self.entries
            .get(start as usize..end as usize)
            .unwrap_or_default()
    }

    /// The rays pixel `i`'s charges are the mean of (0 past the end).
    #[must_use]
    pub fn rays(&self, i: usize) -> u32 {
        self.rays.get(i).copied().unwrap_or(0)
    }

    /// Appends a pixel whose charges are `charges`, the mean of `rays` rays (how the tracer
    /// fills a frame's; for a budget's tests, how a frame is made by hand).
    pub fn push(&mut self, charges: &[Charge], rays: u32) {
        self.entries.extend_from_slice(charges);
        self.ends.push(self.entries.len() as u32);
        self.rays.push(rays);
    }

    /// Appends pixel `i` of `other`.
    pub(crate) fn push_from(&mut self, other: &Self, i: usize) {
        self.push(other.pixel(i), other.rays(i));
    }

    /// The rows `rows`, one after the other.
    pub(crate) fn concat(rows: Vec<Self>) -> Self {
        let mut out = Self::default();
        for row in rows {
            let base = out.entries.len() as u32;
            out.ends.extend(row.ends.iter().map(|e| e + base));
            out.entries.extend(row.entries);
            out.rays.extend(row.rays);
        }
        out
    }
}

/// Where a ray's charges go: nowhere (`()`, the radiance alone), or a pixel's [`Tally`].
pub(crate) trait ChargeSink {
    /// Whether charges are computed at all (a constant: `()` costs nothing).
    const ON: bool;
    /// Adds one event's partials, in one sub-band, to `group`.
    fn charge(&mut self, group: u32, temperature: f64, emissivity: f64);
    /// Forgets what was charged (a new pixel, or a refinement level that replaces the
    /// last).
    fn restart(&mut self);
    /// Says how many rays the pixel's value is the mean of.
    fn set_rays(&mut self, rays: u32);
}

impl ChargeSink for () {
    const ON: bool = false;
    #[inline]
    fn charge(&mut self, _: u32, _: f64, _: f64) {}
    #[inline]
    fn restart(&mut self) {}
    #[inline]
    fn set_rays(&mut self, _: u32) {}
}

/// The groups a [`Tally`] holds without the heap.
const INLINE: usize = 4;

/// The sums of one pixel's charges: a few groups inline, more spilled to the heap (a
/// pixel's rays meet few materials), in the order first met, so that the sums, and the
/// frame, are the same at any thread count.
#[derive(Debug, Default)]
pub(crate) struct Tally {
    inline: [(u32, f64, f64); INLINE],
    len: usize,
    spill: Vec<(u32, f64, f64)>,
    rays: u32,
}

impl Tally {
    /// Appends the pixel's charges, divided by its rays, to `out`.
    pub(crate) fn finish_into(&self, out: &mut Charges) {
        let n = f64::from(self.rays.max(1));
        let mut charges = [Charge {
            group: NO_GROUP,
            temperature_sensitivity: 0.0,
            emissivity_sensitivity: 0.0,
        }; INLINE];
        let as_charge = |&(group, t, e): &(u32, f64, f64)| Charge {
            group,
            temperature_sensitivity: (t / n) as f32,
            emissivity_sensitivity: (e / n) as f32,
        };
        if self.spill.is_empty() {
            for (c, sum) in charges.iter_mut().zip(&self.inline[..self.len]) {
                *c = as_charge(sum);
            }
            out.push(&charges[..self.len], self.rays);
        } else {
            let all: Vec<Charge> = self
                .inline
                .iter()
                .chain(&self.spill)
                .map(as_charge)
                .collect();
            out.push(&all, self.rays);
        }
    }
}

impl ChargeSink for Tally {
    const ON: bool = true;

    #[inline]
    fn charge(&mut self, group: u32, temperature: f64, emissivity: f64) {
        if group == NO_GROUP {
            return;
        }
        let found = self.inline[..self.len]
            .iter_mut()
            .chain(self.spill.iter_mut())
            .find(|(g, _, _)| *g == group);
        match found {
            Some((_, t, e)) => {
                *t += temperature;
                *e += emissivity;
            }
            None if self.len < INLINE => {
                self.inline[self.len] = (group, temperature, emissivity);
                self.len += 1;
            }
            None => self.spill.push((group, temperature, emissivity)),
        }
    }

    fn restart(&mut self) {
        self.len = 0;
        self.spill.clear();
        self.rays = 0;
    }

    fn set_rays(&mut self, rays: u32) {
        self.rays = rays;
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// Keeps the error budget's charges in every frame whose truth is kept
    /// ([`crate::Frame::charges`]): `groups[f]` is the input group of raw-scene facet `f`
    /// (facets that share a declared uncertainty share a group; [`NO_GROUP`], or a facet
    /// past the end, is charged to none). `None` (the default): no charges, and a frame
    /// costs what it did.
    #[must_use]
    pub fn with_budget_groups(mut self, groups: Option<Vec<u32>>) -> Self {
        self.budget_groups = groups;
        self
    }

    /// Whether frames keep charges.
    #[must_use]
    pub fn keeps_charges(&self) -> bool {
        self.budget_groups.is_some()
    }

    /// The input group of a facet met.
    #[inline]
    fn group_of(&self, surface: &Surface) -> u32 {
        self.budget_groups
            .as_ref()
            .and_then(|g| g.get(surface.facet as usize))
            .copied()
            .unwrap_or(NO_GROUP)
    }

    /// Charges, in sub-band `b`, each facet of `path` (whose first facet's terms are
    /// `first`, seen through transmission `tau`) with its partials (the module's doc).
    pub(crate) fn charge_path<S: Atmosphere, C: ChargeSink>(
        &self,
        b: &BandData<S>,
        path: &Path,
        first: &SurfaceTerms,
        tau: f64,
        sink: &mut C,
    ) {
        match path.nodes.as_slice() {
            [only] if !matches!(only.diffuse, Some(Diffuse::Rays { .. })) => sink.charge(
                self.group_of(&only.surface),
                tau * first.emissivity * b.derivative_at(&only.surface),
                tau * (first.blackbody - first.reflected),
            ),
            _ => self.charge_chain(b, path, tau, sink),
        }
    }

    /// [`Self::charge_path`] along a chain of specular bounces, or with sky-view rays: its
    /// terms evaluated from the far end back, as the radiance is, then charged from the
    /// sensor out with the throughput before each facet.
    fn charge_chain<S: Atmosphere, C: ChargeSink>(
        &self,
        b: &BandData<S>,
        path: &Path,
        tau: f64,
        sink: &mut C,
    ) {
        // Per facet: ε·dL_T/dT, L_T − L_reflected, r·s (what it passes on of the next
        // facet) and r·(1 − s) (of what its sky-view rays bring).
        let mut local = [[0.0; 4]; MAX_EVENTS];
        let mut next = 0.0;
        for (node, slot) in path.nodes.iter().zip(local.iter_mut()).rev() {
            let terms = self.surface_terms::<false, S>(b, node, next, 0.0, path);
            let sfrac = self.materials[usize::from(node.surface.data.material)].specular_fraction;
            let r = 1.0 - terms.emissivity;
            *slot = [
                terms.emissivity * b.derivative_at(&node.surface),
                terms.blackbody - terms.reflected,
                r * sfrac,
                r * (1.0 - sfrac),
            ];
            next = terms.leaving;
        }
        let mut throughput = tau;
        for (node, [by_t, by_e, specular, diffuse]) in path.nodes.iter().zip(local) {
            sink.charge(
                self.group_of(&node.surface),
                throughput * by_t,
                throughput * by_e,
            );
            if let Some(Diffuse::Rays { start, count, .. }) = node.diffuse {
                self.charge_sky_view(b, path, (start, count), throughput * diffuse, sink);
            }
            if node.mirror != Some(Mirror::Next) {
                break;
            }
            throughput *= specular;
        }
    }

    /// Charges the facets the sky-view rays `start..start + count` met, each bringing
    /// `ε₂·L_T2 + r₂·L_d` to the diffuse incident radiance as one of `count`, seen through
    /// `weight` (the throughput to the facet that cast them times its `r·(1 − s)`).
    fn charge_sky_view<S: Atmosphere, C: ChargeSink>(
        &self,
        b: &BandData<S>,
        path: &Path,
        (start, count): (u32, u32),
        weight: f64,
        sink: &mut C,
    ) {
        let Some(rays) = path
            .rays
            .get(start as usize..start as usize + count as usize)
        else {
            return;
        };
        let weight = weight / f64::from(count.max(1));
        for ray in rays {
            if let HemiRay::Facet(h) = ray {
                let eps = b.emissivity_of(h);
                sink.charge(
                    self.group_of(h),
                    weight * eps * b.derivative_at(h),
                    weight * (b.blackbody_at(h) - sky_hemispheric(b, h.alt_m)),
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pixels_charges_are_its_sums_over_its_rays_per_group() {
        let mut t = Tally::default();
        // Six groups: four inline, two spilled; group 3 met twice, NO_GROUP never kept.
        for (g, dt) in [(3, 1.0), (5, 2.0), (3, 3.0), (7, 4.0), (9, 5.0), (11, 6.0)] {
            t.charge(g, dt, -dt);
        }
        t.charge(NO_GROUP, 100.0, 100.0);
        t.charge(13, 8.0, 0.0);
        t.set_rays(2);
        let mut out = Charges::default();
        t.finish_into(&mut out);
        t.restart();
        t.set_rays(1);
        t.finish_into(&mut out);
        assert_eq!(out.len(), 2);
        let first = out.pixel(0);
        let groups: Vec<u32> = first.iter().map(|c| c.group).collect();
        assert_eq!(groups, [3, 5, 7, 9, 11, 13]);
        // (1 + 3)/2, −(1 + 3)/2 and 8/2, exact in binary.
        assert!((first[0].temperature_sensitivity - 2.0).abs() < 1e-6);
        assert!((first[0].emissivity_sensitivity + 2.0).abs() < 1e-6);
        assert!((first[5].temperature_sensitivity - 4.0).abs() < 1e-6);
        assert_eq!(out.rays(0), 2);
        assert!(out.pixel(1).is_empty());
        assert!(out.pixel(2).is_empty());
        let rows = Charges::concat(vec![out.clone(), out]);
        assert_eq!(rows.len(), 4);
        assert_eq!(rows.pixel(2), rows.pixel(0));
        assert!(rows.pixel(3).is_empty());
    }
}
