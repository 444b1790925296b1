//! The scenes nobody tuned the tolerance to, drawn from a seed: the tolerance's checks
//! (`tests/guarantee.rs`) and its cost bench (`examples/generated_scene.rs`) trace them
//! against converged references. Four kinds ([`SceneKind`]), each with two views of 48 × 36
//! pixels (0 low, 1 from above), every one of the same five grey materials
//! ([`GENERATED_MATERIALS`]) so that a check reads every kind's materials alike.

use irsig_model::{MaterialLibrary, RawScene, View};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::{Mesh, box_mesh, grey_materials, ground_quad, raw_scene};
use crate::Vacuum;

/// The sky of every generated scene: a uniform 25 W m⁻² sr⁻¹ (a 193 K blackbody over
/// the whole spectrum), no air.
pub const GENERATED_SKY: Vacuum = Vacuum {
    sky_radiance_w_m2_sr: 25.0,
};

/// The material ids of every generated scene: ground, diffuse paint, glass, polished metal,
/// pole and wire.
pub const GENERATED_MATERIALS: [u16; 5] = [1, 2, 3, 4, 5];

/// A scene nobody tuned the tolerance to, drawn from `seed` (the tolerance's checks,
/// `tests/guarantee.rs`, and its cost bench, `examples/generated_scene.rs`): a ground
/// 400 × 600 m, six boxes near and far (diffuse, glass or metal in turn), three poles
/// 3–6 cm wide and a wire of 1 cm, a fraction of a pixel at their distance, temperatures
/// drawn at random; and its view `view` of 48 × 36 pixels: 0 a low camera looking along
/// the ground (its far end grazing), 1 a camera on a mast looking down across the scene.
#[must_use]
pub fn generated_scene(seed: u64, view: usize) -> (RawScene, MaterialLibrary, View) {
    let [ground_id, paint, glass, metal, pole] = GENERATED_MATERIALS;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut t = |lo: f64, hi: f64| rng.random_range(lo..hi);
    let ground = ground_quad([-200.0, -200.0], [200.0, 400.0], 0.0);
    let mut meshes = vec![(ground, ground_id, t(285.0, 315.0))];
    // Boxes near and far, each diffuse, glass-fronted or metal.
    for k in 0..6 {
        let y = t(5.0, 80.0);
        let x = t(-0.5, 0.5) * y;
        let (w, d, h) = (t(1.0, 6.0), t(1.0, 6.0), t(1.0, 8.0));
        let material = [paint, glass, metal][k % 3];
        let kinetic = t(270.0, 340.0);
        meshes.push((box_mesh([x, y, 0.0], [x + w, y + d, h]), material, kinetic));
    }
    // Poles 3-6 cm wide and a wire of 1 cm: a fraction of a pixel at their distance.
    for _ in 0..3 {
        let (x, y) = (t(-10.0, 10.0), t(10.0, 40.0));
        let width = t(0.03, 0.06);
        let kinetic = t(290.0, 340.0);
        meshes.push((
            box_mesh([x, y, 0.0], [x + width, y + width, t(4.0, 10.0)]),
            pole,
            kinetic,
        ));
    }
    let (y, z) = (t(12.0, 30.0), t(3.0, 7.0));
    meshes.push((
        box_mesh([-30.0, y, z], [30.0, y + 0.01, z + 0.01]),
        pole,
        t(280.0, 320.0),
    ));
    let parts: Vec<_> = meshes.iter().map(|(m, id, k)| (m, *id, *k)).collect();
    let scene = raw_scene(&parts);
    let materials = generated_materials();
    let low = View::LookAt {
        position_m: [t(-3.0, 3.0), -8.0, t(1.5, 4.0)],
        target_m: [0.0, 30.0, t(0.0, 2.0)],
        up: [0.0, 0.0, 1.0],
        pixels: [48, 36],
        fov_deg: [60.0, 45.0],
        gain_dc_per_k: None,
    };
    let mast = View::LookAt {
        position_m: [t(-30.0, 30.0), -30.0, t(12.0, 25.0)],
        target_m: [0.0, t(15.0, 40.0), 0.0],
        up: [0.0, 0.0, 1.0],
        pixels: [48, 36],
        fov_deg: [50.0, 37.5],
        gain_dc_per_k: None,
    };
    (scene, materials, if view == 0 { low } else { mast })
}

/// The five grey materials of every generated scene: ground ε 0.95, paint 0.9, glass 0.12
/// (all specular), polished metal 0.05 (0.9 specular), pole and wire 0.9; diffuse where not
/// said (ids [`GENERATED_MATERIALS`]).
#[must_use]
pub fn generated_materials() -> MaterialLibrary {
    let [ground, paint, glass, metal, pole] = GENERATED_MATERIALS;
    grey_materials(&[
        (ground, 0.95, 0.0),
        (paint, 0.9, 0.0),
        (glass, 0.12, 1.0),
        (metal, 0.05, 0.9),
        (pole, 0.9, 0.0),
    ])
}

/// What a generated scene is made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SceneKind {
    /// A flat ground with boxes near and far, poles and a wire ([`generated_scene`]).
    Open,
    /// Hills: a height field whose slopes reach 30–50°, its facets warmer on the slopes
    /// facing +x and cooler on those facing −x, with boxes, poles and a wire standing on it.
    Terrain,
    /// Many mirrors: a dozen metal and glass panels at random yaws and tilts, near enough
    /// to see each other, between hot and cold boxes.
    Mirrors,
    /// An interior: a closed room (no sky), floor, ceiling and walls each at its own
    /// temperature, a cold window pane, a metal cabinet, a hot radiator, a table on thin
    /// legs and a hot pipe under the ceiling.
    Interior,
}

impl SceneKind {
    /// Every kind, in order.
    pub const ALL: [SceneKind; 4] = [
        SceneKind::Open,
        SceneKind::Terrain,
        SceneKind::Mirrors,
        SceneKind::Interior,
    ];

    /// The kind's name: `open`, `terrain`, `mirrors` or `interior`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            SceneKind::Open => "open",
            SceneKind::Terrain => "terrain",
            SceneKind::Mirrors => "mirrors",
            SceneKind::Interior => "interior",
        }
    }

    /// The kind named `name` ([`Self::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<SceneKind> {
        SceneKind::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// The scene of kind `kind` drawn from `seed`, and its view `view` (0 low, 1 from above).
/// [`SceneKind::Open`] is [`generated_scene`]; the other kinds draw from their own
/// streams, so seed 0 of each is its own scene.
#[must_use]
pub fn generated_scene_of(
    kind: SceneKind,
    seed: u64,
    view: usize,
) -> (RawScene, MaterialLibrary, View) {
    let salt = |k: u64| seed ^ (k << 56);
    match kind {
        SceneKind::Open => generated_scene(seed, view),
        SceneKind::Terrain => terrain(&mut Draw::new(salt(1)), view),
        SceneKind::Mirrors => mirrors(&mut Draw::new(salt(2)), view),
        SceneKind::Interior => interior(&mut Draw::new(salt(3)), view),
    }
}

/// A seeded stream of uniform draws.
struct Draw(ChaCha8Rng);

impl Draw {
    fn new(seed: u64) -> Draw {
        Draw(ChaCha8Rng::seed_from_u64(seed))
    }

    /// A value drawn uniformly from `[lo, hi)`.
    fn t(&mut self, lo: f64, hi: f64) -> f64 {
        self.0.random_range(lo..hi)
    }
}

/// A 48 × 36 view from `position_m` towards `target_m`, `fov_deg` wide, z up.
fn look(position_m: [f64; 3], target_m: [f64; 3], fov_deg: [f64; 2]) -> View {
    View::LookAt {
        position_m,
        target_m,
        up: [0.0, 0.0, 1.0],
        pixels: [48, 36],
        fov_deg,
        gain_dc_per_k: None,
    }
}

/// The hills: a sum of Gaussian bumps `(x, y, height, width)`, m.
struct Hills(Vec<[f64; 4]>);

impl Hills {
    /// Six bumps 3–25 m high and 12–50 m wide (σ), their centres 25–300 m along the
    /// ground: the steepest slope of a bump alone is `height / width · e^(−1/2)`, up to
    /// about 50°.
    fn draw(d: &mut Draw) -> Hills {
        Hills(
            (0..6)
                .map(|_| {
                    let y = d.t(25.0, 300.0);
                    [d.t(-0.6, 0.6) * y, y, d.t(3.0, 25.0), d.t(12.0, 50.0)]
                })
                .collect(),
        )
    }

    fn height_m(&self, x: f64, y: f64) -> f64 {
        self.0
            .iter()
            .map(|&[cx, cy, h, s]| {
                h * (-((x - cx).powi(2) + (y - cy).powi(2)) / (2.0 * s * s)).exp()
            })
            .sum()
    }
}

/// A generated terrain ([`SceneKind::Terrain`]): the hills as a height field of 5 m
/// cells over 400 × 600 m, each triangle in one of three meshes by which way it faces
/// (its normal's x over 0.2, under −0.2, or between), each at its own temperature; four
/// boxes, three poles and a wire standing on it.
fn terrain(d: &mut Draw, view: usize) -> (RawScene, MaterialLibrary, View) {
    let [ground_id, paint, glass, metal, pole] = GENERATED_MATERIALS;
    let hills = Hills::draw(d);
    let flat = d.t(285.0, 315.0);
    let facing = [flat, flat + d.t(3.0, 15.0), flat - d.t(2.0, 8.0)];
    let (cells, cell_m) = ([80_u32, 120], 5.0);
    let vertex = |i: u32, j: u32| {
        let (x, y) = (
            -200.0 + cell_m * f64::from(i),
            -200.0 + cell_m * f64::from(j),
        );
        [x, y, hills.height_m(x, y)]
    };
    let mut parts: [Mesh; 3] = Default::default();
    for j in 0..cells[1] {
        for i in 0..cells[0] {
            let [a, b, c, e] = [
                vertex(i, j),
                vertex(i + 1, j),
                vertex(i + 1, j + 1),
                vertex(i, j + 1),
            ];
            for tri in [[a, b, c], [a, c, e]] {
                let n = normal(tri);
                let k = if n[0] > 0.2 {
                    1
                } else if n[0] < -0.2 {
                    2
                } else {
                    0
                };
                let base = parts[k].0.len() as u32;
                parts[k].0.extend(tri);
                parts[k].1.push([base, base + 1, base + 2]);
            }
        }
    }
    let mut meshes: Vec<(Mesh, u16, f64)> = parts
        .into_iter()
        .zip(facing)
        .map(|(m, t)| (m, ground_id, t))
        .collect();
    // Each standing thing's foot sinks 1 m into the ground, so no slope shows a gap under it.
    let foot = |x: f64, y: f64| hills.height_m(x, y) - 1.0;
    for k in 0..4 {
        let y = d.t(5.0, 80.0);
        let x = d.t(-0.5, 0.5) * y;
        let (w, dd, h) = (d.t(1.0, 6.0), d.t(1.0, 6.0), d.t(2.0, 9.0));
        let z = foot(x, y);
        let material = [paint, glass, metal, paint][k];
        let kinetic = d.t(270.0, 340.0);
        meshes.push((
            box_mesh([x, y, z], [x + w, y + dd, z + h]),
            material,
            kinetic,
        ));
    }
    for _ in 0..3 {
        let (x, y) = (d.t(-10.0, 10.0), d.t(10.0, 40.0));
        let (width, z) = (d.t(0.03, 0.06), foot(x, y));
        let top = z + 1.0 + d.t(4.0, 10.0);
        let kinetic = d.t(290.0, 340.0);
        meshes.push((
            box_mesh([x, y, z], [x + width, y + width, top]),
            pole,
            kinetic,
        ));
    }
    let (y, z) = (d.t(12.0, 30.0), d.t(3.0, 7.0));
    let wire_z = z + hills.height_m(0.0, y);
    let kinetic = d.t(280.0, 320.0);
    meshes.push((
        box_mesh([-30.0, y, wire_z], [30.0, y + 0.01, wire_z + 0.01]),
        pole,
        kinetic,
    ));
    let parts: Vec<_> = meshes.iter().map(|(m, id, k)| (m, *id, *k)).collect();
    let low_x = d.t(-3.0, 3.0);
    let low = look(
        [low_x, -8.0, hills.height_m(low_x, -8.0) + d.t(1.5, 4.0)],
        [0.0, 30.0, hills.height_m(0.0, 30.0) + d.t(0.0, 2.0)],
        [60.0, 45.0],
    );
    let mast_x = d.t(-30.0, 30.0);
    let target_y = d.t(15.0, 40.0);
    let mast = look(
        [
            mast_x,
            -30.0,
            hills.height_m(mast_x, -30.0) + d.t(12.0, 25.0),
        ],
        [0.0, target_y, hills.height_m(0.0, target_y)],
        [50.0, 37.5],
    );
    (
        raw_scene(&parts),
        generated_materials(),
        if view == 0 { low } else { mast },
    )
}

/// A triangle's unit normal (its corners counter-clockwise seen from the front).
fn normal([a, b, c]: [[f64; 3]; 3]) -> [f64; 3] {
    let (u, v) = (sub(b, a), sub(c, a));
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    n.map(|x| x / len)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// A thin panel `size_m` = (width, thickness, height) centred on `centre_m`: a box turned
/// by `tilt` about x (its face's normal leaving the horizontal), then by `yaw` about z,
/// radians.
fn panel(centre_m: [f64; 3], size_m: [f64; 3], yaw: f64, tilt: f64) -> Mesh {
    let h = size_m.map(|s| s / 2.0);
    let (mut v, f) = box_mesh([-h[0], -h[1], -h[2]], h);
    let (st, ct, sy, cy) = (tilt.sin(), tilt.cos(), yaw.sin(), yaw.cos());
    for p in &mut v {
        let [x, y, z] = *p;
        let (y1, z1) = (y * ct - z * st, y * st + z * ct);
        let (x2, y2) = (x * cy - y1 * sy, x * sy + y1 * cy);
        *p = [x2 + centre_m[0], y2 + centre_m[1], z1 + centre_m[2]];
    }
    (v, f)
}

/// Many mirrors ([`SceneKind::Mirrors`]): on the flat ground, twelve panels 2 cm thick,
/// 1–4 m wide and 1–3 m high, their faces turned to any yaw and tilted up to 30° from the
/// vertical, metal and glass in turn, 12–46 m from the low camera; four boxes from 260 to
/// 360 K for them to reflect; two poles.
fn mirrors(d: &mut Draw, view: usize) -> (RawScene, MaterialLibrary, View) {
    let [ground_id, paint, glass, metal, pole] = GENERATED_MATERIALS;
    let ground = ground_quad([-200.0, -200.0], [200.0, 400.0], 0.0);
    let mut meshes = vec![(ground, ground_id, d.t(285.0, 315.0))];
    for k in 0..12 {
        let (w, h) = (d.t(1.0, 4.0), d.t(1.0, 3.0));
        let (yaw, tilt) = (
            d.t(0.0, std::f64::consts::PI),
            d.t(-30.0, 30.0).to_radians(),
        );
        // Its lowest corner 0.2-1 m above the ground, whatever its tilt.
        let z = 0.5 * (h * tilt.cos() + 0.02 * tilt.sin().abs()) + d.t(0.2, 1.0);
        let centre = [d.t(-12.0, 12.0), d.t(6.0, 40.0), z];
        let material = [metal, glass][k % 2];
        let kinetic = d.t(270.0, 340.0);
        meshes.push((panel(centre, [w, 0.02, h], yaw, tilt), material, kinetic));
    }
    for _ in 0..4 {
        let (x, y) = (d.t(-15.0, 15.0), d.t(4.0, 45.0));
        let (w, dd, h) = (d.t(0.5, 3.0), d.t(0.5, 3.0), d.t(0.5, 4.0));
        let kinetic = d.t(260.0, 360.0);
        meshes.push((box_mesh([x, y, 0.0], [x + w, y + dd, h]), paint, kinetic));
    }
    for _ in 0..2 {
        let (x, y) = (d.t(-8.0, 8.0), d.t(8.0, 30.0));
        let width = d.t(0.03, 0.06);
        let kinetic = d.t(290.0, 340.0);
        meshes.push((
            box_mesh([x, y, 0.0], [x + width, y + width, d.t(3.0, 8.0)]),
            pole,
            kinetic,
        ));
    }
    let parts: Vec<_> = meshes.iter().map(|(m, id, k)| (m, *id, *k)).collect();
    let low = look(
        [d.t(-3.0, 3.0), -6.0, d.t(1.5, 3.0)],
        [0.0, 20.0, d.t(0.5, 2.0)],
        [60.0, 45.0],
    );
    let mast = look(
        [d.t(-20.0, 20.0), -20.0, d.t(10.0, 18.0)],
        [0.0, d.t(15.0, 25.0), 0.0],
        [50.0, 37.5],
    );
    (
        raw_scene(&parts),
        generated_materials(),
        if view == 0 { low } else { mast },
    )
}

/// A quad from corners counter-clockwise seen from its front, as two triangles.
fn quad(corners: [[f64; 3]; 4]) -> Mesh {
    (corners.to_vec(), vec![[0, 1, 2], [0, 2, 3]])
}

/// An interior ([`SceneKind::Interior`]): a room 4–8 m wide (x), 6–12 m long (y) and
/// 2.5–3.5 m high, closed, its six sides facing in, each reaching 5 cm past the others so
/// no ray leaves through a seam; a cold window pane on the far wall with a hot radiator
/// under it, a metal cabinet by a side wall, a table on four legs 4 cm wide, and a hot pipe
/// 3 cm wide along the ceiling. The low view looks along the room from one end at standing
/// height; the other from a top corner down across it.
fn interior(d: &mut Draw, view: usize) -> (RawScene, MaterialLibrary, View) {
    let [ground_id, paint, glass, metal, pole] = GENERATED_MATERIALS;
    let (w, l, h) = (d.t(4.0, 8.0), d.t(6.0, 12.0), d.t(2.5, 3.5));
    let e = 0.05;
    let (x0, x1, y0, y1, z0, z1) = (-e, w + e, -e, l + e, -e, h + e);
    let sides = [
        // The floor faces up, the ceiling down, each wall into the room.
        (
            quad([[x0, y0, 0.0], [x1, y0, 0.0], [x1, y1, 0.0], [x0, y1, 0.0]]),
            ground_id,
        ),
        (
            quad([[x0, y0, h], [x0, y1, h], [x1, y1, h], [x1, y0, h]]),
            paint,
        ),
        (
            quad([[0.0, y0, z0], [0.0, y1, z0], [0.0, y1, z1], [0.0, y0, z1]]),
            paint,
        ),
        (
            quad([[w, y0, z0], [w, y0, z1], [w, y1, z1], [w, y1, z0]]),
            paint,
        ),
        (
            quad([[x0, 0.0, z0], [x0, 0.0, z1], [x1, 0.0, z1], [x1, 0.0, z0]]),
            paint,
        ),
        (
            quad([[x0, l, z0], [x1, l, z0], [x1, l, z1], [x0, l, z1]]),
            paint,
        ),
    ];
    let mut meshes: Vec<(Mesh, u16, f64)> = sides
        .into_iter()
        .map(|(m, id)| (m, id, d.t(285.0, 305.0)))
        .collect();
    // The window pane 2 cm off the far wall, and the radiator under it.
    let (pane_w, pane_h) = (d.t(1.0, 0.6 * w), d.t(0.8, 0.5 * h));
    let pane_x = d.t(0.2, w - pane_w - 0.2);
    let sill = d.t(0.8, h - pane_h - 0.2);
    let pane = box_mesh(
        [pane_x, l - 0.04, sill],
        [pane_x + pane_w, l - 0.02, sill + pane_h],
    );
    meshes.push((pane, glass, d.t(265.0, 285.0)));
    let radiator = box_mesh(
        [pane_x, l - 0.15, 0.15],
        [pane_x + pane_w, l - 0.05, sill - 0.1],
    );
    meshes.push((radiator, paint, d.t(320.0, 345.0)));
    // The cabinet against the wall x = 0, part-way along the room.
    let (cy, cd, ch) = (d.t(1.0, l - 3.0), d.t(0.8, 2.0), d.t(1.0, 2.0));
    meshes.push((
        box_mesh([0.02, cy, 0.0], [0.6, cy + cd, ch]),
        metal,
        d.t(288.0, 300.0),
    ));
    // The table: a top 4 cm thick 0.75 m up on four legs 4 cm wide.
    let (tx, ty) = (d.t(1.0, w - 2.0), d.t(1.5, l - 2.5));
    let (tw, td) = (d.t(0.8, 1.2), d.t(0.8, 1.6));
    let table_k = d.t(290.0, 300.0);
    meshes.push((
        box_mesh([tx, ty, 0.71], [tx + tw, ty + td, 0.75]),
        paint,
        table_k,
    ));
    for (lx, ly) in [
        (tx, ty),
        (tx + tw - 0.04, ty),
        (tx, ty + td - 0.04),
        (tx + tw - 0.04, ty + td - 0.04),
    ] {
        meshes.push((
            box_mesh([lx, ly, 0.0], [lx + 0.04, ly + 0.04, 0.71]),
            pole,
            table_k,
        ));
    }
    let pipe_x = d.t(0.5 * w, w - 0.3);
    let pipe = box_mesh(
        [pipe_x, 0.02, h - 0.25],
        [pipe_x + 0.03, l - 0.02, h - 0.22],
    );
    meshes.push((pipe, pole, d.t(330.0, 360.0)));
    let parts: Vec<_> = meshes.iter().map(|(m, id, k)| (m, *id, *k)).collect();
    let low = look(
        [d.t(0.3 * w, 0.7 * w), 0.3, d.t(1.2, 1.8)],
        [0.5 * w, l, d.t(0.8, 1.6)],
        [60.0, 45.0],
    );
    let corner = look(
        [0.3, 0.3, h - 0.3],
        [d.t(0.5, 0.8) * w, d.t(0.5, 0.8) * l, 0.0],
        [70.0, 52.5],
    );
    (
        raw_scene(&parts),
        generated_materials(),
        if view == 0 { low } else { corner },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Camera, TraceOptions, Tracer};
    use irsig_model::truth::Layer;
    use irsig_radiometry::TotalRadiance;

    /// The truth layer `layer` of the centre rays of `kind`'s scene `seed` from `view`.
    fn layer(kind: SceneKind, seed: u64, view: usize, layer: Layer) -> Vec<f32> {
        let (scene, materials, view) = generated_scene_of(kind, seed, view);
        let tracer = Tracer::new(&scene, &materials, TotalRadiance, GENERATED_SKY).unwrap();
        let camera = Camera::from_view(&view).unwrap();
        // With sky-view rays: without, the sky-view factor is 1 everywhere (the thesis's).
        let options = TraceOptions {
            truth: true,
            sky_view_rays: 64,
            ..TraceOptions::default()
        };
        let frame = tracer.render(&camera, &options, &|_| {}).unwrap();
        frame.truth_layer(layer).unwrap()
    }

    #[test]
    fn a_room_is_closed_every_ray_meets_a_surface_and_none_sees_the_sky() {
        for seed in 0..4 {
            for view in [0, 1] {
                let material = layer(SceneKind::Interior, seed, view, Layer::MaterialPrimary);
                assert!(material.iter().all(|&m| m > 0.0), "seed {seed} view {view}");
                // The glass pane has no diffuse part, and so no sky-view factor (NaN).
                let f = layer(SceneKind::Interior, seed, view, Layer::SkyViewFactor);
                let open: Vec<_> = f
                    .iter()
                    .zip(&material)
                    .enumerate()
                    .filter(|(_, (f, _))| **f != 0.0 && !f.is_nan())
                    .collect();
                let pane = f32::from(GENERATED_MATERIALS[2]);
                assert!(
                    f.iter()
                        .zip(&material)
                        .all(|(f, m)| f.is_nan() == (m.to_bits() == pane.to_bits())),
                    "seed {seed} view {view}"
                );
                assert!(open.is_empty(), "seed {seed} view {view}: {open:?}");
            }
        }
    }

    #[test]
    fn the_hills_show_slopes_of_every_facing_and_the_sky() {
        for seed in 0..4 {
            let material = layer(SceneKind::Terrain, seed, 0, Layer::MaterialPrimary);
            let kinetic = layer(SceneKind::Terrain, seed, 0, Layer::KineticTemperature);
            let mut ground: Vec<f32> = material
                .iter()
                .zip(&kinetic)
                .filter(|&(m, _)| m.to_bits() == f32::from(GENERATED_MATERIALS[0]).to_bits())
                .map(|(_, &k)| k)
                .collect();
            ground.sort_by(f32::total_cmp);
            ground.dedup();
            assert!(ground.len() >= 2, "seed {seed}: the ground at {ground:?} K");
            assert!(
                material.contains(&0.0),
                "seed {seed}: no sky in the low view"
            );
            // The steepest ground facet, from its normal.
            let (scene, _, _) = generated_scene_of(SceneKind::Terrain, seed, 0);
            let steepest = scene
                .facets
                .iter()
                .filter(|f| f.material.0 == GENERATED_MATERIALS[0])
                .map(|f| normal(f.vertices.map(|v| scene.positions_m[v as usize]))[2])
                .fold(1.0, f64::min)
                .acos()
                .to_degrees();
            assert!(
                steepest > 15.0,
                "seed {seed}: the steepest slope {steepest} deg"
            );
        }
    }

    #[test]
    fn every_panel_stands_clear_of_the_ground() {
        let [_, _, glass, metal, _] = GENERATED_MATERIALS;
        for seed in 0..8 {
            let (scene, _, _) = generated_scene_of(SceneKind::Mirrors, seed, 0);
            let panels: Vec<_> = scene
                .facets
                .iter()
                .filter(|f| [glass, metal].contains(&f.material.0))
                .collect();
            assert_eq!(panels.len(), 12 * 12, "seed {seed}");
            let lowest = panels
                .iter()
                .flat_map(|f| f.vertices)
                .map(|v| scene.positions_m[v as usize][2])
                .fold(f64::INFINITY, f64::min);
            assert!(lowest > 0.199, "seed {seed}: a panel reaches {lowest} m");
        }
    }

    #[test]
    fn a_kind_and_seed_draw_one_scene_and_the_kinds_differ() {
        for kind in SceneKind::ALL {
            assert_eq!(SceneKind::from_name(kind.name()), Some(kind));
            let (a, _, va) = generated_scene_of(kind, 5, 1);
            let (b, _, vb) = generated_scene_of(kind, 5, 1);
            assert_eq!(a.positions_m, b.positions_m);
            assert_eq!(format!("{va:?}"), format!("{vb:?}"));
        }
        let open = generated_scene_of(SceneKind::Open, 0, 0).0;
        assert_eq!(open.positions_m, generated_scene(0, 0).0.positions_m);
        let terrain = generated_scene_of(SceneKind::Terrain, 0, 0).0;
        assert_ne!(open.positions_m.len(), terrain.positions_m.len());
    }
}
