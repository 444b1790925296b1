//! The pinhole camera: the ω φ κ matrix of thesis Appendix H, the look-at form, and rays
//! through pixel centres.
//!
//! # Pixel origin and axes
//!
//! Pixel `(0, 0)` is the **top-left** pixel of the image. Columns increase to the right
//! (along the camera's `right` axis), rows increase **downwards** (against the camera's
//! `up` axis): row 0 is the top row, as `irsig-raster` stores images. The ray of pixel
//! `(column, row)` passes through the centre of that pixel:
//!
//! ```text
//! u = (2 (column + ½) / width  − 1) · tan(fov_x / 2)
//! v = (1 − 2 (row + ½) / height)    · tan(fov_y / 2)
//! direction = forward + u · right + v · up
//! ```
//!
//! so the fields of view reach the outer edges of the outer pixels, and any size and aspect
//! works (the 1990 code was limited to 512 × 512).
//!
//! # The legacy ω φ κ matrix
//!
//! Appendix H builds `m` from ω (about x), φ (about y) and κ (about z), forms the
//! camera-frame direction `(x_c, y_c, −f)` and maps it to the world as the row vector
//! `d_c · m`. So the rows of `m` are the camera's axes in world coordinates: row 1 is
//! `right`, row 2 is `up`, and row 3 points backwards (`forward = −row 3`). With
//! ω = φ = κ = 0 the sensor looks straight down with north (+y) at the top of the image and
//! east (+x) to the right. The 1990 loop cast its rays through integer offsets
//! `i ∈ [−W/2, W/2)` from the optical axis, i.e. half a pixel off the pixel centres, and
//! mirrored its column index; irsig uses pixel centres as above, which keeps the same
//! orientation (east to the right, north up for a nadir view).

use irsig_model::View;

use crate::error::{TraceError, TraceErrorKind};
use glam::DVec3;

/// A pinhole camera in world coordinates (metres).
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// The sensor position, world metres.
    pub position_m: DVec3,
    /// Unit vector along increasing columns.
    pub right: DVec3,
    /// Unit vector towards the top of the image (decreasing rows).
    pub up: DVec3,
    /// Unit vector along the optical axis.
    pub forward: DVec3,
    /// Image size, `[columns, rows]`.
    pub pixels: [u32; 2],
    /// `tan` of half the full fields of view, `[x, y]`.
    pub tan_half_fov: [f64; 2],
}

/// The rows of the Appendix H photogrammetric matrix for ω, φ, κ in degrees:
/// `[right, up, backward]` in world coordinates.
#[must_use]
pub fn omega_phi_kappa_matrix(omega_deg: f64, phi_deg: f64, kappa_deg: f64) -> [DVec3; 3] {
    let (so, co) = omega_deg.to_radians().sin_cos();
    let (sp, cp) = phi_deg.to_radians().sin_cos();
    let (sk, ck) = kappa_deg.to_radians().sin_cos();
    [
        DVec3::new(cp * ck, cp * sk, -sp),
        DVec3::new(so * sp * ck - co * sk, so * sp * sk + co * ck, so * cp),
        DVec3::new(co * sp * ck + so * sk, co * sp * sk - so * ck, co * cp),
    ]
}

/// ω and κ in degrees exactly as thesis eq. 13–14 give them for a sensor at `position`
/// aimed at the origin: `ω = arccos(z / |p|)`, `κ = arctan(x / |y|)` (κ = 0 when x = y = 0).
///
/// Eq. 14 loses the quadrant: for a sensor with y > 0 (Table 2 frames 15 and 16) it gives
/// κ = 0, and the legacy matrix with that κ looks *away* from the origin; the thesis's
/// frames 15–16 "appear upside-down", which is what the matrix gives with ω negated (the
/// image plane then faces the origin with its top towards −z). Use
/// [`look_at_omega_phi_kappa_deg`] for a view that faces the target upright.
#[must_use]
pub fn thesis_look_at_angles_deg(position: DVec3) -> (f64, f64) {
    let [x, y, z] = position.to_array();
    let r = (x * x + y * y + z * z).sqrt();
    let omega = (z / r).acos().to_degrees();
    let kappa = if x == 0.0 {
        0.0
    } else {
        (x / y.abs()).atan().to_degrees()
    };
    (omega, kappa)
}

/// ω φ κ (degrees, φ = 0) of the legacy matrix for a sensor at `position` looking at
/// `target` with the image upright (its `up` axis has a non-negative z component):
/// ω = arccos(−d_z/|d|) (eq. 13 with the target not at the origin) and the quadrant-aware
/// form of eq. 14, κ = atan2(−d_x, d_y), where `d = target − position`.
///
/// For a sensor at y < 0 aimed at the origin this equals eq. 14; for y > 0 it gives
/// κ = ±180°, where eq. 14 gives 0. Straight down (d_x = d_y = 0) gives κ = 0: north up.
#[must_use]
pub fn look_at_omega_phi_kappa_deg(position: DVec3, target: DVec3) -> [f64; 3] {
    let d = target - position;
    let r = d.dot(d).sqrt();
    let omega = (-d.z / r).clamp(-1.0, 1.0).acos().to_degrees();
    let kappa = if d.x == 0.0 && d.y == 0.0 {
        0.0
    } else {
        (-d.x).atan2(d.y).to_degrees()
    };
    [omega, 0.0, kappa]
}

impl Camera {
    /// The camera of a view (either form).
    ///
    /// # Errors
    /// The view fails [`View::validate`].
    pub fn from_view(view: &View) -> Result<Self, TraceError> {
        view.validate()
            .map_err(|e| TraceError::new(TraceErrorKind::InvalidView(e)))?;
        let fov = view.fov_deg();
        let tan_half_fov = [
            (fov[0].to_radians() / 2.0).tan(),
            (fov[1].to_radians() / 2.0).tan(),
        ];
        let (right, up, forward) = match view {
            View::Legacy {
                omega_phi_kappa_deg: [o, p, k],
                ..
            } => {
                let [m1, m2, m3] = omega_phi_kappa_matrix(*o, *p, *k);
                (m1, m2, -m3)
            }
            View::LookAt {
                position_m,
                target_m,
                up,
                ..
            } => {
                let f = (DVec3::from(*target_m) - DVec3::from(*position_m)).normalize();
                let r = f.cross(DVec3::from(*up)).normalize();
                (r, r.cross(f), f)
            }
        };
        Ok(Self {
            position_m: view.position_m().into(),
            right,
            up,
            forward,
            pixels: view.pixels(),
            tan_half_fov,
        })
    }

    /// The unit world direction through image position `(x, y)` in pixel units, where
    /// `(0, 0)` is the top-left corner of the image and `(column + 0.5, row + 0.5)` the
    /// centre of a pixel.
    #[must_use]
    pub fn direction_at(&self, x: f64, y: f64) -> DVec3 {
        self.direction_uv(self.u_at(x), self.v_at(y))
    }

    /// Image-plane coordinate (at unit distance along `forward`) of image x.
    #[inline]
    pub(crate) fn u_at(&self, x: f64) -> f64 {
        (2.0 * x / f64::from(self.pixels[0]) - 1.0) * self.tan_half_fov[0]
    }

    /// Image-plane coordinate (at unit distance along `forward`) of image y.
    #[inline]
    pub(crate) fn v_at(&self, y: f64) -> f64 {
        (1.0 - 2.0 * y / f64::from(self.pixels[1])) * self.tan_half_fov[1]
    }

    /// The unit direction through image-plane point `(u, v)`.
    #[inline]
    pub(crate) fn direction_uv(&self, u: f64, v: f64) -> DVec3 {
        (self.forward + (self.right * u + self.up * v)).normalize()
    }

    /// The unit world direction through the centre of pixel `(column, row)`.
    #[must_use]
    pub fn pixel_direction(&self, column: u32, row: u32) -> DVec3 {
        self.direction_at(f64::from(column) + 0.5, f64::from(row) + 0.5)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Thesis Table 2: frame, sensor position (km), ω (x-axis) and κ (z-axis) in degrees.
    const TABLE_2: [(u32, [f64; 3], f64, f64); 24] = [
        (1, [1.60, -3.00, 0.70], 78.3664, 28.0725),
        (2, [0.80, -3.00, 0.70], 77.2948, 14.9314),
        (3, [0.40, -3.00, 0.70], 76.9772, 7.5946),
        (4, [0.00, -3.00, 0.70], 76.8660, 0.0),
        (5, [-0.40, -3.00, 0.70], 76.9772, -7.5946),
        (6, [-0.80, -3.00, 0.70], 77.2948, -14.9314),
        (7, [-1.60, -3.00, 0.70], 78.3664, -28.0725),
        (8, [-3.20, -3.00, 0.70], 80.9328, -46.8476),
        (9, [0.00, -12.00, 0.70], 86.6615, 0.0),
        (10, [0.00, -9.00, 0.70], 85.5526, 0.0),
        (11, [0.00, -6.00, 0.70], 83.3456, 0.0),
        (12, [0.00, -3.00, 0.70], 76.8660, 0.0),
        (13, [0.00, -1.50, 0.70], 64.9831, 0.0),
        (14, [0.00, 0.00, 0.70], 0.0, 0.0),
        (15, [0.00, 1.50, 0.70], 64.9831, 0.0),
        (16, [0.00, 3.00, 0.70], 76.8660, 0.0),
        (17, [-0.80, -3.00, 0.70], 77.2948, -14.9314),
        (18, [-0.80, -3.00, 0.70], 77.2948, -14.9314),
        (19, [-0.80, -3.00, 0.70], 77.2948, -14.9314),
        (20, [-0.80, -3.00, 0.70], 77.2948, -14.9314),
        (21, [0.00, -3.00, 0.70], 76.8660, 0.0),
        (22, [0.00, -3.00, 0.70], 76.8660, 0.0),
        (23, [0.00, -3.00, 0.70], 76.8660, 0.0),
        (24, [0.00, -3.00, 0.70], 76.8660, 0.0),
    ];

    fn km(p: [f64; 3]) -> DVec3 {
        DVec3::from(p) * 1000.0
    }

    #[test]
    fn table_2_angles_follow_from_eq_13_and_14() {
        for (frame, pos, omega, kappa) in TABLE_2 {
            let (o, k) = thesis_look_at_angles_deg(km(pos));
            // Table 2 prints four decimals.
            assert!((o - omega).abs() < 6e-5, "frame {frame}: ω {o} vs {omega}");
            assert!((k - kappa).abs() < 6e-5, "frame {frame}: κ {k} vs {kappa}");
        }
    }

    fn legacy(pos: DVec3, opk: [f64; 3]) -> View {
        View::Legacy {
            position_m: pos.to_array(),
            pixels: [256, 256],
            omega_phi_kappa_deg: opk,
            fov_deg: [1.0, 1.0],
            gain_dc_per_k: Some(2.0),
        }
    }

    #[test]
    fn table_2_legacy_views_aim_at_the_origin_except_frames_15_and_16() {
        for (frame, pos, omega, kappa) in TABLE_2 {
            let p = km(pos);
            let cam = Camera::from_view(&legacy(p, [omega, 0.0, kappa])).unwrap();
            let to_origin = (-p).normalize();
            let c = cam.forward.dot(to_origin);
            if pos[1] > 0.0 {
                // Eq. 14's κ = 0 for y > 0 points the legacy camera away from the origin.
                assert!(c < 0.0, "frame {frame}");
                // With ω negated it faces the origin, upside down: the thesis's observation.
                let cam = Camera::from_view(&legacy(p, [-omega, 0.0, kappa])).unwrap();
                assert!(cam.forward.dot(to_origin) > 1.0 - 1e-9, "frame {frame}");
                assert!(cam.up[2] < 0.0, "frame {frame} should be upside down");
                // The quadrant-aware κ faces the origin upright.
                let opk = look_at_omega_phi_kappa_deg(p, DVec3::ZERO);
                assert!((opk[2].abs() - 180.0).abs() < 1e-12);
                let cam = Camera::from_view(&legacy(p, opk)).unwrap();
                assert!(cam.forward.dot(to_origin) > 1.0 - 1e-12);
                assert!(cam.up[2] > 0.0);
            } else {
                // Four decimals of angle: the axis is within about 1e-6 rad of the origin.
                assert!(c > 1.0 - 1e-11, "frame {frame}: cos = {c}");
                if frame != 14 {
                    assert!(cam.up[2] > 0.0, "frame {frame} upright");
                }
            }
        }
    }

    #[test]
    fn nadir_view_has_north_up_and_east_right() {
        let cam = Camera::from_view(&legacy(DVec3::new(0.0, 0.0, 700.0), [0.0; 3])).unwrap();
        // Top-left pixel looks north-west, bottom-right south-east.
        let tl = cam.pixel_direction(0, 0);
        assert!(tl[0] < 0.0 && tl[1] > 0.0 && tl[2] < 0.0);
        let br = cam.pixel_direction(255, 255);
        assert!(br[0] > 0.0 && br[1] < 0.0);
        // The outer edge of the image is at half the field of view.
        let edge = cam.direction_at(256.0, 128.0);
        let angle = edge.dot(DVec3::NEG_Z).acos().to_degrees();
        assert!((angle - 0.5).abs() < 1e-12);
        // Pixel centres are symmetric about the axis.
        let a = cam.pixel_direction(127, 128);
        let b = cam.pixel_direction(128, 128);
        assert!((a[0] + b[0]).abs() < 1e-15);
    }

    #[test]
    fn legacy_and_look_at_views_give_the_same_rays() {
        let cases = [
            ([1600.0, -3000.0, 700.0], [0.0; 3]),
            ([-3200.0, -3000.0, 700.0], [0.0; 3]),
            ([0.0, 1500.0, 700.0], [0.0; 3]),
            ([12.0, 40.0, 4.77], [-3.0, 20.0, 0.5]),
        ];
        for (pos, target) in cases {
            for (pixels, fov) in [([256, 256], [1.0, 1.0]), ([640, 120], [40.0, 9.0])] {
                let opk = look_at_omega_phi_kappa_deg(pos.into(), target.into());
                let a = Camera::from_view(&View::Legacy {
                    position_m: pos,
                    pixels,
                    omega_phi_kappa_deg: opk,
                    fov_deg: fov,
                    gain_dc_per_k: None,
                })
                .unwrap();
                let b = Camera::from_view(&View::LookAt {
                    position_m: pos,
                    target_m: target,
                    up: [0.0, 0.0, 1.0],
                    pixels,
                    fov_deg: fov,
                    gain_dc_per_k: None,
                })
                .unwrap();
                for (c, r) in [(0, 0), (pixels[0] - 1, 0), (7, pixels[1] - 1), (100, 60)] {
                    let (da, db) = (a.pixel_direction(c, r), b.pixel_direction(c, r));
                    for k in 0..3 {
                        assert!((da[k] - db[k]).abs() < 1e-12, "{pos:?} ({c},{r})");
                    }
                }
            }
        }
    }

    #[test]
    fn straight_down_look_at_with_north_up_matches_the_zero_matrix() {
        let a = Camera::from_view(&legacy(DVec3::new(5.0, 6.0, 700.0), [0.0; 3])).unwrap();
        let b = Camera::from_view(&View::LookAt {
            position_m: [5.0, 6.0, 700.0],
            target_m: [5.0, 6.0, 0.0],
            up: [0.0, 1.0, 0.0],
            pixels: [256, 256],
            fov_deg: [1.0, 1.0],
            gain_dc_per_k: None,
        })
        .unwrap();
        for k in 0..3 {
            assert!((a.right[k] - b.right[k]).abs() < 1e-15);
            assert!((a.up[k] - b.up[k]).abs() < 1e-15);
            assert!((a.forward[k] - b.forward[k]).abs() < 1e-15);
        }
    }

    #[test]
    fn any_aspect_and_size_work() {
        let cam = Camera::from_view(&View::Legacy {
            position_m: [0.0, 0.0, 10.0],
            pixels: [2000, 3],
            omega_phi_kappa_deg: [0.0; 3],
            fov_deg: [90.0, 1.0],
            gain_dc_per_k: None,
        })
        .unwrap();
        let left_edge = cam.direction_at(0.0, 1.5);
        assert!((left_edge.dot(DVec3::NEG_Z).acos().to_degrees() - 45.0).abs() < 1e-9);
        assert!(Camera::from_view(&legacy(DVec3::splat(0.0), [f64::NAN, 0.0, 0.0])).is_err());
    }
}
