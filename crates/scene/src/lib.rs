//! Scenes into world space: the 1990 "raw" step (thesis §4.1), plus mesh generators.
//!
//! [`flatten`] takes a [`Scene`] and the [`Object`] each placement names and produces the
//! [`RawScene`] the tracer reads:
//!
//! 1. **Geometry.** Each vertex `p` goes to `T + R·(S·p)` with `S = diag(scale)`,
//!    `R = Rz(rz)·Ry(ry)·Rx(rx)` (rotate about world x first, then y, then z; right-handed,
//!    degrees) and `T` the translation, exactly as [`irsig_model::Placement`] documents.
//!    The thesis's scene file gives the same nine numbers; its code (Appendix H) is not
//!    published for this step, so the order is ours, documented and tested by hand.
//!    A mirroring scale (an odd number of negative factors, `det S < 0`) reverses each
//!    triangle's winding so that its front stays the side that faced out.
//! 2. **Temperature.** A facet keeps the temperature the input gave it; a facet without
//!    one takes the placement's `temperature_k`.
//! 3. **Overrides**, in order: each selects facets (an index range, a material, or all)
//!    and sets their material, temperature or both. A material selection matches the
//!    material the facet has at that point, after earlier overrides.
//! 4. A facet with no temperature after all this is an error naming the object and facet.
//!
//! The generators ([`uv_sphere`], [`terrain`]) build closed meshes with outward winding
//! at any resolution, for tests and benchmarks across the workspace.
//!
//! ```
//! use irsig_model::{MaterialId, Placement, Scene};
//! let ball = irsig_scene::uv_sphere(1.0, 8, 4, MaterialId(1));
//! let scene = Scene {
//!     objects: vec![Placement {
//!         object: "ball.ron".into(),
//!         rotation_deg: [0.0, 0.0, 90.0],
//!         translation_m: [10.0, 0.0, 0.0],
//!         scale: [2.0, 2.0, 2.0],
//!         temperature_k: Some(300.0),
//!         overrides: vec![],
//!     }],
//!     ..Scene::default()
//! };
//! let raw = irsig_scene::flatten(&scene, &[&ball]).unwrap();
//! assert_eq!(raw.facets.len(), ball.facets.len());
//! assert!(raw.facets.iter().all(|f| f.temperature_k == 300.0));
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]

mod generate;

pub use generate::{terrain, uv_sphere};

use irsig_model::{FacetSelection, ModelError, Object, Placement, RawFacet, RawScene, Scene};

/// Why a scene cannot be flattened.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}", self.describe())]
pub struct FlattenError {
    /// Which placement (index into `Scene::objects`), if the error belongs to one.
    pub placement: Option<usize>,
    /// The placed object's name, if the error belongs to one.
    pub object: Option<String>,
    /// What is wrong.
    pub kind: FlattenErrorKind,
}

/// What is wrong with a scene or its objects.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum FlattenErrorKind {
    /// The number of objects given differs from the number of placements.
    ObjectCount {
        /// Placements in the scene.
        placements: usize,
        /// Objects given.
        objects: usize,
    },
    /// The scene, an object or the result breaks a model rule.
    Model(ModelError),
    /// A facet has no temperature from its input, its placement or an override.
    NoTemperature {
        /// The facet's index within its object.
        facet: usize,
    },
    /// An override's index range reaches past the object's facets.
    RangeOutOfBounds {
        /// Which override of the placement.
        overrides_index: usize,
        /// The range's last facet.
        last: usize,
        /// How many facets the object has.
        facets: usize,
    },
    /// A transformed vertex is not finite (a scale or translation too large for `f64`).
    NotFinite {
        /// The vertex's index within its object.
        vertex: usize,
    },
    /// The raw scene would hold more than `u32::MAX` vertices or objects.
    TooLarge,
}

impl FlattenError {
    fn describe(&self) -> String {
        let who = match (&self.placement, &self.object) {
            (Some(i), Some(name)) => format!("object {i} (`{name}`): "),
            (Some(i), None) => format!("object {i}: "),
            _ => String::new(),
        };
        let what = match &self.kind {
            FlattenErrorKind::ObjectCount {
                placements,
                objects,
            } => {
                format!("{placements} placements but {objects} objects were given")
            }
            FlattenErrorKind::Model(e) => e.to_string(),
            FlattenErrorKind::NoTemperature { facet } => format!(
                "facet {facet} has no temperature: the input gives none, the placement has no \
                 `temperature_k` and no override sets one"
            ),
            FlattenErrorKind::RangeOutOfBounds {
                overrides_index,
                last,
                facets,
            } => format!(
                "overrides[{overrides_index}] selects facets up to {last}, but the object has {facets} (0 to {})",
                facets.saturating_sub(1)
            ),
            FlattenErrorKind::NotFinite { vertex } => {
                format!("vertex {vertex} is not finite after scaling, rotation and translation")
            }
            FlattenErrorKind::TooLarge => "more than 2^32 vertices or objects".into(),
        };
        format!("{who}{what}")
    }
}

/// A placement's transform, `p ↦ T + R·(S·p)`, as one matrix `M = R·S` (row-major) and a
/// translation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transform {
    /// `R·S`, row-major.
    pub matrix: [[f64; 3]; 3],
    /// `T` in metres.
    pub translation_m: [f64; 3],
}

/// `R = Rz(z)·Ry(y)·Rx(x)` for rotations in degrees, row-major: a column vector is rotated
/// about world x first, then y, then z, each counter-clockwise looking down the axis.
#[must_use]
pub fn rotation_matrix(rotation_deg: [f64; 3]) -> [[f64; 3]; 3] {
    let [(sx, cx), (sy, cy), (sz, cz)] = rotation_deg.map(sin_cos_deg);
    let rx = [[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]];
    let ry = [[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]];
    let rz = [[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]];
    mul(&rz, &mul(&ry, &rx))
}

/// `(sin, cos)` of an angle in degrees, exact at multiples of 90° (where `to_radians`
/// would leave 6e-17 instead of 0 and make hand-checked scenes come out a hair off).
#[allow(clippy::float_cmp)] // an exact test for whole quarter turns is the point
fn sin_cos_deg(angle_deg: f64) -> (f64, f64) {
    let quarter = angle_deg / 90.0;
    if quarter.fract() == 0.0 && quarter.abs() < 1e15 {
        // rem_euclid of an integral f64 is integral: 0, 1, 2 or 3.
        match quarter.rem_euclid(4.0) as u8 {
            0 => (0.0, 1.0),
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        }
    } else {
        angle_deg.to_radians().sin_cos()
    }
}

fn mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut m = [[0.0; 3]; 3];
    for (r, row) in m.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = (0..3).map(|k| a[r][k] * b[k][c]).sum();
        }
    }
    m
}

impl Transform {
    /// The transform of a placement.
    #[must_use]
    pub fn of(placement: &Placement) -> Self {
        let r = rotation_matrix(placement.rotation_deg);
        let s = placement.scale;
        let matrix = r.map(|row| [row[0] * s[0], row[1] * s[1], row[2] * s[2]]);
        Self {
            matrix,
            translation_m: placement.translation_m,
        }
    }

    /// `T + R·(S·p)`.
    #[must_use]
    pub fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let m = &self.matrix;
        let t = &self.translation_m;
        [
            t[0] + m[0][0] * p[0] + m[0][1] * p[1] + m[0][2] * p[2],
            t[1] + m[1][0] * p[0] + m[1][1] * p[1] + m[1][2] * p[2],
            t[2] + m[2][0] * p[0] + m[2][1] * p[1] + m[2][2] * p[2],
        ]
    }

    /// True when the transform mirrors (its determinant is negative), so windings must be
    /// reversed.
    #[must_use]
    pub fn mirrors(&self) -> bool {
        let m = &self.matrix;
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        det < 0.0
    }
}

/// Flattens a scene: `objects[i]` is the object `scene.objects[i]` names (the same object
/// may be given for several placements). Checks the scene and every object first, and the
/// result last.
///
/// # Errors
/// A [`FlattenError`] naming the placement, object and facet where it can.
pub fn flatten(scene: &Scene, objects: &[&Object]) -> Result<RawScene, FlattenError> {
    let scene_err = |kind| FlattenError {
        placement: None,
        object: None,
        kind,
    };
    if objects.len() != scene.objects.len() {
        return Err(scene_err(FlattenErrorKind::ObjectCount {
            placements: scene.objects.len(),
            objects: objects.len(),
        }));
    }
    scene
        .validate()
        .map_err(|e| scene_err(FlattenErrorKind::Model(e)))?;
    let total_positions: usize = objects.iter().map(|o| o.positions_m.len()).sum();
    let total_facets: usize = objects.iter().map(|o| o.facets.len()).sum();
    let mut raw = RawScene {
        terrain: scene.terrain,
        objects: Vec::with_capacity(objects.len()),
        positions_m: Vec::with_capacity(total_positions),
        facets: Vec::with_capacity(total_facets),
        mix_temperatures: Vec::new(),
    };
    for (i, (placement, object)) in scene.objects.iter().zip(objects).enumerate() {
        let err = |kind| FlattenError {
            placement: Some(i),
            object: Some(object.name.clone()),
            kind,
        };
        object
            .validate()
            .map_err(|e| err(FlattenErrorKind::Model(e)))?;
        let base =
            u32::try_from(raw.positions_m.len()).map_err(|_| err(FlattenErrorKind::TooLarge))?;
        let object_index = u32::try_from(i).map_err(|_| err(FlattenErrorKind::TooLarge))?;
        if u32::try_from(raw.positions_m.len() + object.positions_m.len()).is_err() {
            return Err(err(FlattenErrorKind::TooLarge));
        }
        let transform = Transform::of(placement);
        for (k, &p) in object.positions_m.iter().enumerate() {
            let w = transform.apply(p);
            if !w.iter().all(|v| v.is_finite()) {
                return Err(err(FlattenErrorKind::NotFinite { vertex: k }));
            }
            raw.positions_m.push(w);
        }
        // Materials and temperatures after the placement temperature and the overrides.
        let mut materials: Vec<_> = object.facets.iter().map(|f| f.material).collect();
        let mut temperatures: Vec<Option<f64>> = object
            .facets
            .iter()
            .map(|f| f.temperature_k.or(placement.temperature_k))
            .collect();
        for (k, o) in placement.overrides.iter().enumerate() {
            let range = match o.select {
                FacetSelection::Range { first, last } => {
                    if last >= object.facets.len() {
                        return Err(err(FlattenErrorKind::RangeOutOfBounds {
                            overrides_index: k,
                            last,
                            facets: object.facets.len(),
                        }));
                    }
                    first..=last
                }
                FacetSelection::Material(_) | FacetSelection::All => {
                    0..=object.facets.len().saturating_sub(1)
                }
            };
            for f in range {
                if let FacetSelection::Material(m) = o.select {
                    if materials[f] != m {
                        continue;
                    }
                }
                if let Some(m) = o.material {
                    materials[f] = m;
                }
                if let Some(t) = o.temperature_k {
                    temperatures[f] = Some(t);
                }
            }
        }
        let mirrors = transform.mirrors();
        raw.objects.push(object.name.clone());
        for (k, facet) in object.facets.iter().enumerate() {
            let temperature_k =
                temperatures[k].ok_or_else(|| err(FlattenErrorKind::NoTemperature { facet: k }))?;
            let [a, b, c] = facet.vertices.map(|v| v + base);
            // A mirror reverses the winding; the corners' texture coordinates go with
            // their corners.
            let uv = facet
                .uv
                .map(|[p, q, r]| if mirrors { [p, r, q] } else { [p, q, r] });
            raw.facets.push(RawFacet {
                vertices: if mirrors { [a, c, b] } else { [a, b, c] },
                material: materials[k],
                temperature_k,
                object: object_index,
                uv,
            });
        }
    }
    raw.validate().map_err(|e| {
        // A rule of the whole raw scene (a coordinate the transform made too large) still
        // belongs to the placement that made the offending position or facet.
        let placement = raw_index(&e.path, "facets")
            .and_then(|k| raw.facets.get(k))
            .map(|f| f.object as usize)
            .or_else(|| {
                raw_index(&e.path, "positions_m").map(|k| {
                    let mut end = 0;
                    objects
                        .iter()
                        .position(|o| {
                            end += o.positions_m.len();
                            k < end
                        })
                        .unwrap_or(objects.len().saturating_sub(1))
                })
            });
        FlattenError {
            placement,
            object: placement
                .and_then(|i| objects.get(i))
                .map(|o| o.name.clone()),
            kind: FlattenErrorKind::Model(e),
        }
    })?;
    Ok(raw)
}

/// `k` of a model path `field[k]...`.
fn raw_index(path: &str, field: &str) -> Option<usize> {
    let rest = path.strip_prefix(field)?.strip_prefix('[')?;
    rest[..rest.find(']')?].parse().ok()
}

#[cfg(test)]
mod tests;
