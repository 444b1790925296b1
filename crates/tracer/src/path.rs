//! The geometry of one ray from the sensor, recorded once and then evaluated in every
//! sub-band: which facets it met, at what angles and altitudes, where its reflections and
//! hemisphere rays went. Tracing (the BVH) is the expensive part; evaluating the radiance
//! equation on a recorded path is a few table lookups per sub-band, so a spectral
//! rendering of K sub-bands traces each ray once, not K times.

use rand::Rng;

use irsig_atmosphere::range_to_ground_from_cos_m;
use irsig_radiometry::BandModel;
use irsig_texture::Footprint;

use crate::differential::Differentials;
use crate::env::Atmosphere;
use crate::geometry::Hit;
use crate::sun::SunGeometry;
use crate::tracer::{Ctx, FacetRadiometry, FrameConsts, Tracer};
use glam::DVec3;

/// Where a ray that left the scene ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Escape {
    /// Above the horizon: the sky seen from `alt_m` at `zenith_deg`, along `dir` (unit: by
    /// day the scattered sunlight depends on its azimuth from the sun too).
    Sky {
        alt_m: f64,
        zenith_deg: f64,
        dir: DVec3,
    },
    /// Below it: the terrain background.
    Terrain,
}

/// A facet a ray met: what its radiance needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Surface {
    pub(crate) facet: u32,
    pub(crate) data: FacetRadiometry,
    /// Cosine of the angle between the reversed ray and the facet normal.
    pub(crate) cos_incidence: f64,
    pub(crate) back_face: bool,
    /// Altitude of the hit above the ground, metres.
    pub(crate) alt_m: f64,
    /// ε at this incidence in the tracer's own emissivity tables, found once: every
    /// sub-band whose table for the material is the same reads it
    /// ([`crate::tracer::BandData::emissivity_of`]). Before the texture's scale.
    pub(crate) emissivity: f64,
    /// The material's texture at the hit point ([`irsig_texture`]); `None` for a material
    /// without one, whose hits take exactly the facet's temperature and the table's ε.
    pub(crate) texel: Option<irsig_texture::Texel>,
    /// The materials mixed at the hit, where its material's material map gives more than
    /// one ([`crate::mixture`]); `None` elsewhere, and `data.material` is the hit's.
    pub(crate) mix: Option<crate::mixture::Mix>,
}

/// What arrives along the mirror direction of a facet with a specular part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Mirror {
    /// The next node of the path: the reflection ray hit a facet (event 4).
    Next,
    /// The reflection ray left the scene (event 3).
    Escaped(Escape),
    /// No bounce left: the environment along the mirror direction, not traced (the sky at
    /// the mirror angle from the facet's altitude, or the terrain below the horizon), as if
    /// nothing stood in the way. The named model of a chain cut short: a mirror whose
    /// reflection points at the ground sees the ground, not the hemispheric sky.
    Untraced(Escape),
}

/// What arrives diffusely at a facet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Diffuse {
    /// The hemispheric sky (F = 1, the thesis's model).
    Hemispheric,
    /// Sky-view rays `rays[start..start + count]` of the path, `sky` of which reached the
    /// sky.
    Rays { start: u32, count: u32, sky: u32 },
}

/// One facet of a path: the surface, and where its reflected and diffuse light come from
/// (`None` where the material has no such part).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Node {
    pub(crate) surface: Surface,
    pub(crate) mirror: Option<Mirror>,
    pub(crate) diffuse: Option<Diffuse>,
    /// z of the unit reflection direction (its zenith angle is shown in the probe).
    pub(crate) reflected_z: f64,
    /// Where the mirror direction leaves the scene if nothing stood in the way: what a chain
    /// cut at this node reflects ([`Mirror::Untraced`]).
    pub(crate) environment: Escape,
    /// The sun's diffuse light at this facet per unit of the beam's normal irradiance,
    /// `cos θ_i·V/π`, sr⁻¹ ([`crate::sun`]): 0 without a sun, without a diffuse part, in
    /// shadow or with the sun behind the facet.
    pub(crate) sun_diffuse_per_sr: f64,
    /// The sun's glint per unit of the beam's normal irradiance, sr⁻¹, which the specular
    /// share `s·r` multiplies: for a smooth material `1/Ω_sun` when the reflection leaves
    /// toward the sky inside the disk, else 0; for a rough one the lobe over the disk
    /// times the visible fraction of the sun ([`crate::lobe`]).
    pub(crate) sun_glint_per_sr: f64,
    /// The sun's irradiance at this facet per unit of the beam's normal irradiance,
    /// `cos θ_i·V` (what `sun_diffuse_per_sr` is `1/π` of), for the truth layers: 0 without a
    /// sun. Found where the facet has a diffuse part, and at a primary facet without one
    /// when the centre ray's truth is kept ([`crate::tracer::Ctx::sun_truth`]).
    pub(crate) sun_cos_visible: f64,
    /// The fraction of the facet's shadow rays that reached the sun, 0 to 1 (NaN where not
    /// found: no sun, or a facet with no diffuse part whose truth is not kept).
    pub(crate) sun_visible: f64,
}

/// What a facet's shadow rays found: `cos θ_i·V` (each ray weighted by its own cosine)
/// and the unweighted fraction of rays that reached the sun.
#[derive(Debug, Clone, Copy, PartialEq)]
struct SunLight {
    cos_visible: f64,
    visible: f64,
}

/// The glint of a mirror whose reflection ray `refl` (unit) went as `mirror`, per unit of
/// the beam's normal irradiance, sr⁻¹: the disk's `1/Ω_sun` when the ray leaves toward the
/// sky (or would, its bounces spent) inside the disk, else 0.
pub(crate) fn glint_per_sr(sun: &SunGeometry, refl: DVec3, mirror: Mirror) -> f64 {
    let to_sky = matches!(
        mirror,
        Mirror::Escaped(Escape::Sky { .. }) | Mirror::Untraced(Escape::Sky { .. })
    );
    if to_sky && refl[2] > 0.0 && refl.dot(sun.to_sun) >= sun.cos_radius {
        sun.inverse_solid_angle_per_sr
    } else {
        0.0
    }
}

/// Sample `k`'s point in the unit square: an `m × m` grid of strata, each jittered by
/// `(xi1, xi2)`, then any remainder unstratified.
fn stratified(k: u32, m: u32, xi1: f64, xi2: f64) -> (f64, f64) {
    if k < m * m {
        (
            (f64::from(k % m) + xi1) / f64::from(m),
            (f64::from(k / m) + xi2) / f64::from(m),
        )
    } else {
        (xi1, xi2)
    }
}

/// A sky-view ray from a facet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum HemiRay {
    /// It hit another facet, whose surface-leaving radiance it brings back
    /// (`ε₂·L_T2 + r₂·L_d`, no further rays).
    Facet(Surface),
    /// It left the scene.
    Escaped(Escape),
}

/// What the ray from the sensor met first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Primary {
    /// Event 1 above the horizon: the sky path from the sensor to space.
    Sky { zenith_deg: f64 },
    /// Event 1 below the horizon: the terrain, `range_m` away along the curved Earth. Its
    /// path terms use `path_range_m`, the range to a flat ground at the same nadir angle
    /// (`altitude / cos nadir`): the atmosphere models are plane-parallel and read the
    /// slant angle from the range, and LOWTRAN's own slant paths to the ground at that
    /// angle (which do follow the curved Earth) are what they reproduce.
    Terrain { range_m: f64, path_range_m: f64 },
    /// A facet, `range_m` away at `alt_m`: the path's first node.
    Facet { range_m: f64, alt_m: f64 },
}

/// A recorded path: the primary event, the chain of facets of its specular bounces (node
/// `i + 1` is what node `i`'s reflection ray hit) and the sky-view rays of its first facet.
/// Scratch space reused from ray to ray.
#[derive(Debug, Clone)]
pub(crate) struct Path {
    pub(crate) primary: Primary,
    /// The ray's direction from the sensor, unit: by day the sunlight scattered into the
    /// view path depends on its azimuth from the sun.
    pub(crate) dir: DVec3,
    pub(crate) nodes: Vec<Node>,
    pub(crate) rays: Vec<HemiRay>,
    /// The ray's cell, carried through its mirror bounces, which the texture filters read
    /// as its footprint at each facet: the pixel's, or its sub-pixel cell's for a
    /// supersampled ray ([`Ctx::subpixel_side`]). `None` when no texture of the scene
    /// filters over a footprint.
    cell: Option<Differentials>,
}

impl Default for Path {
    fn default() -> Self {
        Self {
            primary: Primary::Sky { zenith_deg: 0.0 },
            dir: DVec3::Z,
            nodes: Vec::new(),
            rays: Vec::new(),
            cell: None,
        }
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// Traces the ray from the sensor along `dir` and records its path into `path`.
    pub(crate) fn follow(
        &self,
        fc: &FrameConsts<'_>,
        dir: DVec3,
        ctx: &mut Ctx<'_>,
        path: &mut Path,
    ) {
        path.nodes.clear();
        path.rays.clear();
        path.dir = dir;
        match self
            .geometry
            .closest_hit(fc.origin, dir, 0.0, f64::INFINITY, None)
        {
            None => path.primary = self.primary_miss(fc, dir),
            Some(hit) => {
                let alt = self.geometry.to_world(hit.point_local)[2].max(0.0);
                path.primary = Primary::Facet {
                    range_m: hit.distance_m,
                    alt_m: alt,
                };
                path.cell = self
                    .filters_footprint
                    .then(|| Differentials::from_camera(fc.camera(), dir, ctx.subpixel_side));
                self.follow_surface(&hit, dir, alt, 0, ctx, path);
            }
        }
    }

    /// Event 1: the ray leaves the scene from the sensor. The ground test compares
    /// cosines, so a miss costs no arc cosine unless it sees the sky.
    fn primary_miss(&self, fc: &FrameConsts<'_>, dir: DVec3) -> Primary {
        let alt = fc.sensor_alt;
        let cos_nadir = (-dir[2]).clamp(-1.0, 1.0);
        if cos_nadir > fc.cos_critical_nadir {
            Primary::Terrain {
                range_m: range_to_ground_from_cos_m(alt, cos_nadir).unwrap_or(0.0),
                path_range_m: alt / cos_nadir,
            }
        } else {
            Primary::Sky {
                zenith_deg: dir[2].clamp(-1.0, 1.0).acos().to_degrees(),
            }
        }
    }

    /// Where a ray from a surface point at altitude `alt` along `dir` that leaves the scene
    /// ends: the sky above the horizon, the terrain below it.
    pub(crate) fn escape(&self, dir: DVec3, alt: f64) -> Escape {
        let nadir = (-dir[2]).clamp(-1.0, 1.0).acos().to_degrees();
        if nadir < self.bands.bands[0].atmosphere.critical_nadir_angle_deg(alt) {
            Escape::Terrain
        } else {
            Escape::Sky {
                alt_m: alt,
                zenith_deg: 180.0 - nadir,
                dir,
            }
        }
    }

    /// Records the facet `hit` at altitude `alt` as the next node, `depth` specular bounces
    /// already spent, then follows its reflection ray (while bounces remain) and, at the
    /// first facet, its sky-view rays.
    fn follow_surface(
        &self,
        hit: &Hit<FacetRadiometry>,
        dir: DVec3,
        alt: f64,
        depth: u32,
        ctx: &mut Ctx<'_>,
        path: &mut Path,
    ) {
        let footprint = path
            .cell
            .as_mut()
            .map(|c| c.at_hit(dir, hit.distance_m, hit.normal));
        let surface = self.surface(hit, alt, footprint.as_ref());
        let (has_mirror, has_diffuse, lobe) =
            self.reflection_parts(&surface.data, surface.mix.as_ref());
        let index = path.nodes.len();
        path.nodes.push(Node {
            surface,
            mirror: None,
            diffuse: None,
            reflected_z: f64::NAN,
            environment: Escape::Terrain,
            sun_diffuse_per_sr: 0.0,
            sun_glint_per_sr: 0.0,
            sun_cos_visible: 0.0,
            sun_visible: f64::NAN,
        });
        if has_mirror {
            // Mirror direction about the normal facing the ray.
            let refl = dir - hit.normal * (2.0 * dir.dot(hit.normal));
            path.nodes[index].reflected_z = refl[2];
            let environment = self.escape(refl, alt);
            path.nodes[index].environment = environment;
            let mirror = if depth < ctx.options.specular_bounces {
                let eps_m = self.geometry.surface_epsilon_m();
                match self.geometry.closest_hit(
                    hit.point_local,
                    refl,
                    eps_m,
                    f64::INFINITY,
                    Some(hit.facet),
                ) {
                    Some(h2) => {
                        let alt2 = self.geometry.to_world(h2.point_local)[2].max(0.0);
                        if let Some(c) = path.cell.as_mut() {
                            c.reflect(hit.normal);
                        }
                        self.follow_surface(&h2, refl, alt2, depth + 1, ctx, path);
                        Mirror::Next
                    }
                    None => Mirror::Escaped(self.escape(refl, alt)),
                }
            } else {
                Mirror::Untraced(environment)
            };
            path.nodes[index].mirror = Some(mirror);
            if let Some(sun) = &self.sun
                && lobe.is_none()
            {
                path.nodes[index].sun_glint_per_sr = glint_per_sr(sun, refl, mirror);
            }
        }
        // A rough specular share: the lobe over the disk, before the visible fraction.
        let lobe_glint = match (&self.sun, lobe) {
            (Some(sun), Some(lobe)) => lobe.glint_per_sr(sun, hit.normal, -dir),
            _ => 0.0,
        };
        if has_diffuse {
            let diffuse = if depth == 0 && ctx.options.sky_view_rays > 0 {
                self.follow_hemisphere(hit, alt, ctx, path)
            } else {
                Diffuse::Hemispheric
            };
            path.nodes[index].diffuse = Some(diffuse);
            if let Some(sun) = &self.sun {
                let light = self.sun_light(sun, hit, ctx, false);
                let node = &mut path.nodes[index];
                node.sun_diffuse_per_sr = light.cos_visible * std::f64::consts::FRAC_1_PI;
                node.sun_cos_visible = light.cos_visible;
                node.sun_visible = light.visible;
                node.sun_glint_per_sr = lobe_glint * light.visible;
            }
        } else if lobe_glint > 0.0
            && let Some(sun) = &self.sun
        {
            // A rough mirror lit through its lobe: its shadow rays, from the pixel's sun
            // stream whether or not truth is kept, give the glint's visible fraction and
            // the truth layers both.
            let light = self.sun_light(sun, hit, ctx, false);
            let node = &mut path.nodes[index];
            node.sun_glint_per_sr = lobe_glint * light.visible;
            if depth == 0 && ctx.sun_truth {
                node.sun_cos_visible = light.cos_visible;
                node.sun_visible = light.visible;
            }
        } else if depth == 0
            && ctx.sun_truth
            && let Some(sun) = &self.sun
        {
            // A pure mirror reflects no direct sunlight diffusely, but its truth layers
            // still say how much reaches it: its shadow rays draw from a stream of their
            // own, so that the rendered radiance is the same with and without truth.
            let light = self.sun_light(sun, hit, ctx, true);
            let node = &mut path.nodes[index];
            node.sun_cos_visible = light.cos_visible;
            node.sun_visible = light.visible;
        }
    }

    /// What the shadow rays of the hit's seen side find: `cos θ_i·V` and the fraction that
    /// reach the sun. One shadow ray to the disk's centre, or the disk sampled uniformly by
    /// solid angle (stratified, from the pixel's sun stream, or with `truth_stream` its
    /// truth-only sun stream), each ray weighted by its own cosine. A ray below the
    /// horizontal meets the ground; a ray behind the facet is not visible.
    fn sun_light(
        &self,
        sun: &SunGeometry,
        hit: &Hit<FacetRadiometry>,
        ctx: &mut Ctx<'_>,
        truth_stream: bool,
    ) -> SunLight {
        let eps_m = self.geometry.surface_epsilon_m();
        let lit = |d: DVec3| {
            let c = hit.normal.dot(d);
            if c <= 0.0
                || d[2] <= 0.0
                || self
                    .geometry
                    .occluded(hit.point_local, d, eps_m, f64::INFINITY, Some(hit.facet))
            {
                0.0
            } else {
                c
            }
        };
        let n = ctx.shadow_rays.unwrap_or(sun.shadow_rays);
        if n == 1 {
            let c = lit(sun.to_sun);
            return SunLight {
                cos_visible: c,
                visible: if c > 0.0 { 1.0 } else { 0.0 },
            };
        }
        // Nothing of the disk in front of the facet: no ray to cast.
        if hit.normal.dot(sun.to_sun) <= -sun.sin_radius {
            return SunLight {
                cos_visible: 0.0,
                visible: 0.0,
            };
        }
        let m = (f64::from(n).sqrt()) as u32;
        let (mut sum, mut seen) = (0.0, 0u32);
        for k in 0..n {
            let (xi1, xi2): (f64, f64) = {
                let rng = if truth_stream {
                    ctx.sun_truth_rng()
                } else {
                    ctx.sun_rng()
                };
                (rng.random(), rng.random())
            };
            let (u1, u2) = stratified(k, m, xi1, xi2);
            let c = lit(sun.disk_direction(u1, u2));
            sum += c;
            seen += u32::from(c > 0.0);
        }
        SunLight {
            cos_visible: sum / f64::from(n),
            visible: f64::from(seen) / f64::from(n),
        }
    }

    /// The record of a hit at altitude `alt`: with its material's texture sampled at the
    /// hit's world position and its image maps at the hit's texture coordinates, every
    /// event alike (the first hit, a specular bounce's, a sky-view ray's), a footprint
    /// filter over the ray's cell there, `footprint` ([`Tracer::texel_at`]; `None` for a
    /// sky-view ray's hit, which reads the point).
    fn surface(
        &self,
        hit: &Hit<FacetRadiometry>,
        alt: f64,
        footprint: Option<&Footprint>,
    ) -> Surface {
        let (data, mix) = self.resolve_material(hit, footprint);
        let slot = usize::from(data.material);
        Surface {
            facet: hit.facet,
            data,
            cos_incidence: hit.cos_incidence,
            back_face: hit.back_face,
            alt_m: alt,
            emissivity: self.emissivity[slot].at_cos(hit.cos_incidence),
            texel: self.texel_at(hit, footprint),
            mix,
        }
    }

    /// N cosine-weighted, stratified rays over the hemisphere above a hit: each a facet it
    /// hits or the sky or terrain it escapes to. The sky-view factor F is the fraction that
    /// reach the sky.
    fn follow_hemisphere(
        &self,
        hit: &Hit<FacetRadiometry>,
        alt: f64,
        ctx: &mut Ctx<'_>,
        path: &mut Path,
    ) -> Diffuse {
        let n = ctx.options.sky_view_rays;
        let m = (f64::from(n).sqrt()) as u32;
        let (t, b) = hit.normal.any_orthonormal_pair();
        let eps_m = self.geometry.surface_epsilon_m();
        let start = path.rays.len() as u32;
        let mut sky = 0u32;
        for k in 0..n {
            let (xi1, xi2): (f64, f64) = {
                let rng = ctx.rng();
                (rng.random(), rng.random())
            };
            let (u1, u2) = stratified(k, m, xi1, xi2);
            // Malley's method: uniform on the disc, projected up.
            let rad = u1.sqrt();
            let phi = std::f64::consts::TAU * u2;
            let z = (1.0 - u1).max(0.0).sqrt();
            let d = t * (rad * phi.cos()) + b * (rad * phi.sin()) + hit.normal * z;
            let ray = match self.geometry.closest_hit(
                hit.point_local,
                d,
                eps_m,
                f64::INFINITY,
                Some(hit.facet),
            ) {
                Some(h2) => {
                    let alt2 = self.geometry.to_world(h2.point_local)[2].max(0.0);
                    HemiRay::Facet(self.surface(&h2, alt2, None))
                }
                None => {
                    if d[2] >= 0.0 {
                        sky += 1;
                    }
                    HemiRay::Escaped(self.escape(d, alt))
                }
            };
            path.rays.push(ray);
        }
        Diffuse::Rays {
            start,
            count: n,
            sky,
        }
    }
}
