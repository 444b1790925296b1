//! A ray's pixel cell carried along its path, for the texture filters: ray differentials
//! (Igehy 1999, "Tracing ray differentials", SIGGRAPH), for a pinhole camera and flat
//! facets.
//!
//! A camera ray is `p(t) = o + t·D(x, y)`, with `D = forward + u·right + v·up` unnormalised
//! and `(x, y)` the image position. Across its cell the ray's hit moves by `∂p/∂x` and
//! `∂p/∂y`: on the plane of normal `n` a hit `s` metres along the unit direction `d` moves
//! by `P·(∂p + s·e)`, where `e = ∂D/|D|` and `P = I − d·nᵀ/(d·n)` projects along the ray
//! onto the plane. A flat mirror reflects `e` as it reflects the direction, and keeps
//! `∂p`. The two moves are the edges of the parallelogram the cell covers on the facet:
//! exact for a plane to first order in the cell's size (the perspective within one cell is
//! not followed).

use glam::DVec3;
use irsig_texture::Footprint;

use crate::camera::Camera;

/// How a ray's point and direction move across its cell, along the cell's two image axes:
/// `dp` the point's move (m per cell) and `de` the unnormalised direction's over its
/// length (per cell, metres of move per metre travelled).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Differentials {
    dp: [DVec3; 2],
    de: [DVec3; 2],
}

impl Differentials {
    /// The camera's ray along the unit `dir`, its cell `1/side` of a pixel across (a
    /// supersampled ray's own cell). `D·forward = 1`, so `|D| = 1/(d·forward)`.
    pub(crate) fn from_camera(camera: &Camera, dir: DVec3, side: u32) -> Self {
        let [w, h] = camera.pixels.map(f64::from);
        let [tx, ty] = camera.tan_half_fov;
        let per_length = dir.dot(camera.forward) / f64::from(side.max(1));
        Self {
            dp: [DVec3::ZERO; 2],
            de: [
                camera.right * (2.0 * tx / w * per_length),
                camera.up * (-2.0 * ty / h * per_length),
            ],
        }
    }

    /// Moves the cell to a hit `distance_m` along the unit `dir`, on a plane of normal
    /// `normal`, and gives its footprint there. A ray along the plane (`d·n` = 0) gives
    /// edges that are not finite: the whole facet.
    pub(crate) fn at_hit(&mut self, dir: DVec3, distance_m: f64, normal: DVec3) -> Footprint {
        let along = dir.dot(normal);
        // One division for both edges.
        let per_along = 1.0 / along;
        for (dp, de) in self.dp.iter_mut().zip(self.de) {
            let q = *dp + de * distance_m;
            *dp = if along == 0.0 {
                DVec3::INFINITY
            } else {
                q - dir * (q.dot(normal) * per_along)
            };
        }
        Footprint {
            edges_m: self.dp.map(|e| e.to_array()),
        }
    }

    /// The reflection in a flat mirror of unit normal `normal`.
    pub(crate) fn reflect(&mut self, normal: DVec3) {
        for de in &mut self.de {
            *de -= normal * (2.0 * de.dot(normal));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::View;

    fn camera(omega_deg: f64) -> Camera {
        Camera::from_view(&View::Legacy {
            position_m: [0.0, 0.0, 100.0],
            pixels: [64, 48],
            omega_phi_kappa_deg: [omega_deg, 0.0, 0.0],
            fov_deg: [20.0, 15.0],
            gain_dc_per_k: None,
        })
        .unwrap()
    }

    /// Where the ray through image position `(x, y)` meets the plane `z = 0`.
    fn on_ground(cam: &Camera, x: f64, y: f64) -> DVec3 {
        let d = cam.direction_at(x, y);
        cam.position_m + d * (-cam.position_m[2] / d[2])
    }

    #[test]
    fn the_cell_on_a_plane_is_the_difference_of_neighbouring_rays() {
        // Straight down and tilted 50°: the edges are the moves of the hit between rays a
        // small step apart (central differences, whose error is second order in the step).
        for omega in [0.0, 50.0] {
            let cam = camera(omega);
            for (x, y) in [(32.0, 24.0), (0.5, 0.5), (63.2, 40.7)] {
                let dir = cam.direction_at(x, y);
                let distance = -cam.position_m[2] / dir[2];
                for side in [1, 4] {
                    let mut diff = Differentials::from_camera(&cam, dir, side);
                    let cell = diff.at_hit(dir, distance, DVec3::Z);
                    let h = 1e-3;
                    let s = f64::from(side);
                    let along_x =
                        (on_ground(&cam, x + h, y) - on_ground(&cam, x - h, y)) / (2.0 * h * s);
                    let along_y =
                        (on_ground(&cam, x, y + h) - on_ground(&cam, x, y - h)) / (2.0 * h * s);
                    for (edge, expected) in cell.edges_m.iter().zip([along_x, along_y]) {
                        let e = DVec3::from_array(*edge);
                        assert!(
                            (e - expected).length() < 1e-6 * expected.length(),
                            "{omega}° ({x}, {y}) /{side}: {e} against {expected}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn a_mirror_folds_the_cell_onto_what_it_shows() {
        // Straight down onto a mirror at z = 0, then up to a ceiling at z = 10 m: the cell
        // there is the cell on a plane 100 + 10 m below the camera, mirrored, so each edge
        // is the ground's at that depth: the ground's edge times 110/100.
        let cam = camera(0.0);
        let (x, y) = (20.3, 30.9);
        let dir = cam.direction_at(x, y);
        let to_mirror = -100.0 / dir[2];
        let mut diff = Differentials::from_camera(&cam, dir, 1);
        let on_mirror = diff.at_hit(dir, to_mirror, DVec3::Z);
        diff.reflect(DVec3::Z);
        let up = dir - DVec3::Z * (2.0 * dir[2]);
        let on_ceiling = diff.at_hit(up, 10.0 / up[2], -DVec3::Z);
        for (m, c) in on_mirror.edges_m.iter().zip(on_ceiling.edges_m) {
            let (m, c) = (DVec3::from_array(*m), DVec3::from_array(c));
            assert!((c - m * 1.1).length() < 1e-9 * m.length(), "{c} {m}");
        }
        // Along the plane: no finite cell.
        let mut flat = Differentials::from_camera(&cam, DVec3::X, 1);
        assert!(flat.at_hit(DVec3::X, 5.0, DVec3::Z).width_m().is_infinite());
    }
}
