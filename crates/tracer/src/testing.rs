//! Closed test meshes for the tracer's tests and benchmarks (vertex list plus
//! counter-clockwise-outward triangles, metres). The project's scene generators live in
//! `irsig-scene`; these exist so the tracer can be tested on its own.

use irsig_model::{Material, MaterialId, MaterialLibrary, RawFacet, RawScene, View};

use crate::geometry::Geometry;
use glam::DVec3;
use irsig_radiometry::{BandModel, TotalRadiance};

pub use crate::lobe::LobeProbe;
pub use crate::reference::percentile;
use crate::{Camera, TraceOptions, Tracer, Vacuum};

mod generated;
pub use generated::{
    GENERATED_MATERIALS, GENERATED_SKY, SceneKind, generated_materials, generated_scene,
    generated_scene_of,
};

/// A closed mesh: vertex positions and triangles as vertex indices.
pub type Mesh = (Vec<[f64; 3]>, Vec<[u32; 3]>);

/// A closed UV sphere with `2 · segments · (rings − 1)` triangles, poles as single
/// vertices, wound counter-clockwise seen from outside. `rings ≥ 2`, `segments ≥ 3`.
#[must_use]
pub fn uv_sphere(centre: [f64; 3], radius: f64, rings: u32, segments: u32) -> Mesh {
    let rings = rings.max(2);
    let segments = segments.max(3);
    let mut v = vec![[centre[0], centre[1], centre[2] + radius]];
    for i in 1..rings {
        let theta = std::f64::consts::PI * f64::from(i) / f64::from(rings);
        for j in 0..segments {
            let phi = std::f64::consts::TAU * f64::from(j) / f64::from(segments);
            v.push([
                centre[0] + radius * theta.sin() * phi.cos(),
                centre[1] + radius * theta.sin() * phi.sin(),
                centre[2] + radius * theta.cos(),
            ]);
        }
    }
    v.push([centre[0], centre[1], centre[2] - radius]);
    let south = (v.len() - 1) as u32;
    let ring = |i: u32, j: u32| 1 + (i - 1) * segments + (j % segments);
    let mut f = Vec::new();
    for j in 0..segments {
        f.push([0, ring(1, j), ring(1, j + 1)]);
    }
    for i in 1..rings - 1 {
        for j in 0..segments {
            let (a, b, c, d) = (
                ring(i, j),
                ring(i, j + 1),
                ring(i + 1, j),
                ring(i + 1, j + 1),
            );
            f.push([a, c, d]);
            f.push([a, d, b]);
        }
    }
    for j in 0..segments {
        f.push([south, ring(rings - 1, j + 1), ring(rings - 1, j)]);
    }
    (v, f)
}

/// An axis-aligned box from `lo` to `hi` as 12 triangles, normals outward.
#[must_use]
pub fn box_mesh(lo: [f64; 3], hi: [f64; 3]) -> Mesh {
    let p = |i: u32| {
        [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ]
    };
    let v = (0..8).map(p).collect();
    // Each face as a quad counter-clockwise from outside.
    let quads = [
        [0, 2, 3, 1], // z = lo
        [4, 5, 7, 6], // z = hi
        [0, 1, 5, 4], // y = lo
        [2, 6, 7, 3], // y = hi
        [0, 4, 6, 2], // x = lo
        [1, 3, 7, 5], // x = hi
    ];
    let f = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    (v, f)
}

/// A flat rectangle in the plane z = `z` from `lo` to `hi` (x, y), facing +z, as two
/// triangles.
#[must_use]
pub fn ground_quad(lo: [f64; 2], hi: [f64; 2], z: f64) -> Mesh {
    (
        vec![
            [lo[0], lo[1], z],
            [hi[0], lo[1], z],
            [hi[0], hi[1], z],
            [lo[0], hi[1], z],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

/// The benchmarks' scene ("the shade profile's"): a UV sphere of radius 10 m centred 12 m
/// up over a 200 m ground quad. `size` 0, 1, 2 gives about 1k, 100k and 1M triangles.
/// [`bench_sphere`] is the sphere alone, the ground the last two triangles of [`bench_scene`].
#[must_use]
pub fn bench_sphere(size: usize) -> Mesh {
    let (rings, segments) = [(17, 32), (224, 224), (708, 708)][size.min(2)];
    uv_sphere([0.0, 0.0, 12.0], 10.0, rings, segments)
}

/// The ground quad of [`bench_scene`].
#[must_use]
pub fn bench_ground() -> Mesh {
    ground_quad([-100.0, -100.0], [100.0, 100.0], 0.0)
}

/// [`bench_sphere`] and [`bench_ground`] as one mesh: the sphere, then the ground's
/// vertices after its own.
#[must_use]
pub fn bench_scene(size: usize) -> Mesh {
    let mut mesh = bench_sphere(size);
    let ground = bench_ground();
    let offset = mesh.0.len() as u32;
    mesh.0.extend(&ground.0);
    mesh.1
        .extend(ground.1.iter().map(|t| t.map(|i| i + offset)));
    mesh
}

/// The benchmarks' camera on [`bench_scene`]: from (30, −30, 25) m towards the sphere's
/// centre, a 50° square field of `pixels` × `pixels`.
#[must_use]
pub fn bench_camera(pixels: u32) -> Camera {
    Camera::from_view(&View::LookAt {
        position_m: [30.0, -30.0, 25.0],
        target_m: [0.0, 0.0, 10.0],
        up: [0.0, 0.0, 1.0],
        pixels: [pixels, pixels],
        fov_deg: [50.0, 50.0],
        gain_dc_per_k: None,
    })
    .expect("the bench view is valid")
}

/// The terrain and box of `scripts/bench/thrend-scene.py` (the side-by-side with ThRend):
/// 2 × 707² = 999,698 triangles of a bumpy 800 m square (heights 5 m ± 4.5 m), and a
/// 40 × 40 × 30 m box standing on the ground beneath it, its 12 triangles after the
/// terrain's.
#[must_use]
pub fn bench_terrain() -> Mesh {
    const N: u32 = 707;
    const SIDE_M: f64 = 800.0;
    let height = |x: f64, y: f64| {
        5.0 + 3.0 * (x / 23.0).sin() * (y / 17.0).cos() + 1.5 * ((x + y) / 7.0).sin()
    };
    let step = SIDE_M / f64::from(N);
    let mut v = Vec::with_capacity(((N + 1) * (N + 1)) as usize);
    for i in 0..=N {
        let y = -SIDE_M / 2.0 + f64::from(i) * step;
        for j in 0..=N {
            let x = -SIDE_M / 2.0 + f64::from(j) * step;
            v.push([x, y, height(x, y)]);
        }
    }
    let mut t = Vec::with_capacity((2 * N * N) as usize);
    for i in 0..N {
        for j in 0..N {
            let a = i * (N + 1) + j;
            let (b, c, d) = (a + 1, a + N + 2, a + N + 1);
            t.push([a, b, c]);
            t.push([a, c, d]);
        }
    }
    let mut mesh = (v, t);
    let cube = box_mesh([30.0, -20.0, 0.0], [70.0, 20.0, 30.0]);
    let offset = mesh.0.len() as u32;
    mesh.0.extend(&cube.0);
    mesh.1.extend(cube.1.iter().map(|f| f.map(|i| i + offset)));
    mesh
}

/// The camera of `scripts/bench/thrend-scene.py` on [`bench_terrain`]: from (−300, 0, 40) m
/// towards (150, 0, −40) m, a 40° square field of `pixels` × `pixels`.
#[must_use]
pub fn bench_terrain_camera(pixels: u32) -> Camera {
    Camera::from_view(&View::LookAt {
        position_m: [-300.0, 0.0, 40.0],
        target_m: [150.0, 0.0, -40.0],
        up: [0.0, 0.0, 1.0],
        pixels: [pixels, pixels],
        fov_deg: [40.0, 40.0],
        gain_dc_per_k: None,
    })
    .expect("the bench view is valid")
}

/// The triangles of a mesh as vertex triples.
#[must_use]
pub fn triangles(mesh: &Mesh) -> Vec<[DVec3; 3]> {
    mesh.1
        .iter()
        .map(|f| f.map(|i| DVec3::from(mesh.0[i as usize])))
        .collect()
}

/// A square pit: a `2·half_width_m` square floor at z = 0 facing up, and four walls
/// `depth_m` high standing on its edges (each a thin closed box outside the floor, so the
/// floor's whole hemisphere is bounded by the walls and the opening). Returns
/// `(floor, walls)`.
#[must_use]
pub fn square_pit(half_width_m: f64, depth_m: f64) -> (Mesh, Mesh) {
    let (w, c, t) = (half_width_m, depth_m, 0.1 * half_width_m);
    let mut walls: Mesh = (Vec::new(), Vec::new());
    for (lo, hi) in [
        ([-w - t, -w - t, 0.0], [-w, w + t, c]),
        ([w, -w - t, 0.0], [w + t, w + t, c]),
        ([-w, -w - t, 0.0], [w, -w, c]),
        ([-w, w, 0.0], [w, w + t, c]),
    ] {
        let b = box_mesh(lo, hi);
        let base = walls.0.len() as u32;
        walls.0.extend(b.0);
        walls.1.extend(b.1.iter().map(|f| f.map(|v| v + base)));
    }
    (ground_quad([-w, -w], [w, w], 0.0), walls)
}

/// The exact sky-view factor at the centre of a square pit's floor ([`square_pit`]): the
/// configuration factor from a differential horizontal element to the square opening
/// `depth_m` above it, four times J. R. Howell's catalogue case B-3 (*A Catalog of
/// Radiation Heat Transfer Configuration Factors*: plane element to a parallel `a × b`
/// rectangle at distance `c`, the element's normal through a corner),
/// `F = 1/(2π) [X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))]`, X = a/c, Y = b/c.
#[must_use]
pub fn pit_centre_sky_view_factor(half_width_m: f64, depth_m: f64) -> f64 {
    let x = half_width_m / depth_m;
    let s = (1.0 + x * x).sqrt();
    // Four corner rectangles of a × a: 4 · 2 · X/√(1+X²) · atan(X/√(1+X²)) / (2π).
    4.0 * (x / s * (x / s).atan()) / std::f64::consts::PI
}

/// Two coplanar rectangles at z = 0 filling `[-r, r]²`, split along the straight line
/// through `(x_bottom, -r)` and `(x_top, r)`: `(west part, east part)`, both facing up.
/// `-r < x_bottom, x_top < r`.
#[must_use]
pub fn split_square(r: f64, x_bottom: f64, x_top: f64) -> (Mesh, Mesh) {
    let quad = |p: [[f64; 2]; 4]| -> Mesh {
        (
            p.iter().map(|q| [q[0], q[1], 0.0]).collect(),
            vec![[0, 1, 2], [0, 2, 3]],
        )
    };
    (
        quad([[-r, -r], [x_bottom, -r], [x_top, r], [-r, r]]),
        quad([[x_bottom, -r], [r, -r], [r, r], [x_top, r]]),
    )
}

/// The exact fraction of the pixel `[column, column + 1] × [row, row + 1]` (image units)
/// lying left of the line `x = x0 + slope·y`, by integrating the clamped width
/// `clamp(x0 + slope·y − column, 0, 1)` over the row analytically (it is linear between
/// the rows where the line enters and leaves the pixel).
#[must_use]
pub fn pixel_fraction_left_of_line(x0: f64, slope: f64, column: f64, row: f64) -> f64 {
    let width = |y: f64| (x0 + slope * y - column).clamp(0.0, 1.0);
    // Breakpoints: the row's ends and where the line crosses the pixel's two sides.
    let mut ys = vec![row, row + 1.0];
    if slope != 0.0 {
        for x in [column, column + 1.0] {
            let y = (x - x0) / slope;
            if y > row && y < row + 1.0 {
                ys.push(y);
            }
        }
    }
    ys.sort_by(f64::total_cmp);
    // The width is linear on each piece: the trapezoid rule is exact there.
    ys.windows(2)
        .map(|p| 0.5 * (width(p[0]) + width(p[1])) * (p[1] - p[0]))
        .sum()
}

/// A raw scene from meshes, each with its material id and kinetic temperature (K); one
/// object per mesh, default terrain.
#[must_use]
pub fn raw_scene(parts: &[(&Mesh, u16, f64)]) -> RawScene {
    let mut s = RawScene::default();
    for (k, (mesh, material, temperature_k)) in parts.iter().enumerate() {
        let base = s.positions_m.len() as u32;
        s.objects.push(format!("part{k}"));
        s.positions_m.extend(&mesh.0);
        s.facets.extend(mesh.1.iter().map(|f| RawFacet {
            vertices: f.map(|v| v + base),
            material: MaterialId(*material),
            temperature_k: *temperature_k,
            object: k as u32,
            uv: None,
        }));
    }
    s
}

/// The benchmarks' angular emissivity table, `(angle_deg, emissivity)`: 0.95 at the normal,
/// falling to 0 at grazing (the divan bench's materials and `shade_profile ... angular`).
pub const BENCH_EMISSIVITY: [(f64, f64); 4] =
    [(0.0, 0.95), (45.0, 0.93), (70.0, 0.85), (90.0, 0.0)];

/// A library of grey materials `(id, emissivity at every angle, specular fraction)`.
#[must_use]
pub fn grey_materials(materials: &[(u16, f64, f64)]) -> MaterialLibrary {
    MaterialLibrary {
        materials: materials
            .iter()
            .map(|&(id, emissivity, specular_fraction)| Material {
                id: MaterialId(id),
                name: format!("grey{id}"),
                emissivity: vec![(0.0, emissivity)],
                specular_fraction,
                source: "irsig_tracer::testing".into(),
                band_um: None,
                spectral: None,
                rms_slope: None,
                thermal: None,
                texture: None,
                maps: None,
            })
            .collect(),
    }
}

/// The sky-view factor trade: a 2 m square pit 1 m deep ([`square_pit`]; floor
/// ε = 0.9 at 300 K, blackbody walls at 300 K, a uniform sky of a 250 K blackbody, whole
/// spectrum) seen straight down through a 16 × 16 image so narrow (0.001°) that every
/// pixel's ray lands within a millimetre of the floor's centre: 256 independent F
/// estimates (each pixel draws its own random stream) of one exact configuration factor.
#[derive(Debug)]
pub struct PitExperiment {
    /// The pit's tracer.
    pub tracer: Tracer<TotalRadiance, Vacuum>,
    /// The nadir camera over the floor's centre.
    pub camera: Camera,
    /// The exact F at the floor's centre ([`pit_centre_sky_view_factor`]).
    pub exact_sky_view_factor: f64,
    /// The exact radiance of a centre pixel given the exact F, W m⁻² sr⁻¹.
    pub exact_radiance_w_m2_sr: f64,
}

impl PitExperiment {
    /// Floor half-width and pit depth, metres.
    pub const HALF_WIDTH_M: f64 = 1.0;
    /// Pit depth, metres.
    pub const DEPTH_M: f64 = 1.0;

    /// Builds the pit and its camera.
    ///
    /// # Panics
    /// Never: the scene is fixed and valid.
    #[must_use]
    pub fn new() -> Self {
        let (floor, walls) = square_pit(Self::HALF_WIDTH_M, Self::DEPTH_M);
        let scene = raw_scene(&[(&floor, 1, 300.0), (&walls, 2, 300.0)]);
        let materials = grey_materials(&[(1, 0.9, 0.0), (2, 1.0, 0.0)]);
        let l_sky = TotalRadiance.radiance(250.0);
        let tracer = Tracer::new(
            &scene,
            &materials,
            TotalRadiance,
            Vacuum {
                sky_radiance_w_m2_sr: l_sky,
            },
        )
        .unwrap();
        let camera = Camera::from_view(&View::Legacy {
            // Slightly off the floor's diagonals, so no ray runs along a triangle edge.
            position_m: [0.0011, 0.0023, 50.0],
            pixels: [16, 16],
            omega_phi_kappa_deg: [0.0; 3],
            fov_deg: [0.001, 0.001],
            gain_dc_per_k: None,
        })
        .unwrap();
        let f = pit_centre_sky_view_factor(Self::HALF_WIDTH_M, Self::DEPTH_M);
        let l_t = TotalRadiance.radiance(300.0);
        Self {
            tracer,
            camera,
            exact_sky_view_factor: f,
            exact_radiance_w_m2_sr: 0.9 * l_t + 0.1 * (f * l_sky + (1.0 - f) * l_t),
        }
    }

    /// Renders with `rays` sky-view rays per hit; `(F, radiance)` per pixel.
    ///
    /// # Panics
    /// If `rays` is out of [`TraceOptions`]' range.
    #[must_use]
    pub fn estimates(&self, rays: u32, seed: u64) -> Vec<(f64, f64)> {
        let options = TraceOptions {
            sky_view_rays: rays,
            seed,
            ..TraceOptions::default()
        };
        let frame = self.tracer.render(&self.camera, &options, &|_| {}).unwrap();
        frame
            .truth
            .iter()
            .zip(&frame.radiance_w_m2_sr)
            .map(|(s, &l)| (f64::from(s.sky_view_factor), l))
            .collect()
    }
}

impl Default for PitExperiment {
    fn default() -> Self {
        Self::new()
    }
}

/// The supersampling trade: two coplanar blackbody facets, 330 K west and 300 K
/// east of a straight edge, seen straight down (black sky, whole spectrum) by a 24 × 64
/// image. In image units the edge is the line `x = X0 + SLOPE·y`, so each pixel's exact
/// radiance is `f·L(330) + (1 − f)·L(300)` with `f` its area left of the line
/// ([`pixel_fraction_left_of_line`]).
#[derive(Debug)]
pub struct EdgeExperiment {
    /// The two facets' tracer.
    pub tracer: Tracer<TotalRadiance, Vacuum>,
    /// The nadir camera.
    pub camera: Camera,
}

impl EdgeExperiment {
    /// Where the edge crosses the image's top (image x at y = 0).
    pub const X0: f64 = 5.3;
    /// Image-x change of the edge per image row (about 11.3° from vertical).
    pub const SLOPE: f64 = 0.2;
    /// Image size.
    pub const PIXELS: [u32; 2] = [24, 64];
    /// Field of view, degrees (x, y).
    pub const FOV_DEG: [f64; 2] = [10.0, 20.0];
    /// Sensor height above the facets, metres.
    pub const HEIGHT_M: f64 = 100.0;
    /// West (hot) and east facet temperatures, K.
    pub const TEMPERATURES_K: [f64; 2] = [330.0, 300.0];

    /// Builds the facets and the camera. The image-to-ground map is worked out by hand
    /// from the camera's documented convention (pixel (0, 0) top-left, x east, y south
    /// for a nadir view with ω = φ = κ = 0): ground x = x_c + (2x/W − 1)·tan(fov_x/2)·H,
    /// ground y = y_c + (1 − 2y/H_px)·tan(fov_y/2)·H.
    ///
    /// # Panics
    /// Never: the scene is fixed and valid.
    #[must_use]
    pub fn new() -> Self {
        let centre = [3.7, -1.9];
        let [w, h] = Self::PIXELS.map(f64::from);
        let (tx, ty) = (
            (Self::FOV_DEG[0] / 2.0).to_radians().tan(),
            (Self::FOV_DEG[1] / 2.0).to_radians().tan(),
        );
        let ground_x = |x: f64| centre[0] + (2.0 * x / w - 1.0) * tx * Self::HEIGHT_M;
        let image_y = |gy: f64| (1.0 - (gy - centre[1]) / (ty * Self::HEIGHT_M)) * h / 2.0;
        let r = 100.0;
        // The edge's ground x at ground y = centre ± r, from its image-space line, relative
        // to the centre (split_square is centred on the origin).
        let edge_x = |gy: f64| ground_x(Self::X0 + Self::SLOPE * image_y(gy)) - centre[0];
        let (west, east) = split_square(r, edge_x(centre[1] - r), edge_x(centre[1] + r));
        // split_square is centred on the origin: move it under the camera.
        let shift = |m: Mesh| -> Mesh {
            (
                m.0.iter()
                    .map(|p| [p[0] + centre[0], p[1] + centre[1], p[2]])
                    .collect(),
                m.1,
            )
        };
        let (west, east) = (shift(west), shift(east));
        let scene = raw_scene(&[
            (&west, 1, Self::TEMPERATURES_K[0]),
            (&east, 1, Self::TEMPERATURES_K[1]),
        ]);
        let tracer = Tracer::new(
            &scene,
            &grey_materials(&[(1, 1.0, 0.0)]),
            TotalRadiance,
            Vacuum::default(),
        )
        .unwrap();
        let camera = Camera::from_view(&View::Legacy {
            position_m: [centre[0], centre[1], Self::HEIGHT_M],
            pixels: Self::PIXELS,
            omega_phi_kappa_deg: [0.0; 3],
            fov_deg: Self::FOV_DEG,
            gain_dc_per_k: None,
        })
        .unwrap();
        Self { tracer, camera }
    }

    /// The exact radiance of pixel `(column, row)`, W m⁻² sr⁻¹.
    #[must_use]
    pub fn exact_radiance_w_m2_sr(column: u32, row: u32) -> f64 {
        let f = pixel_fraction_left_of_line(Self::X0, Self::SLOPE, column.into(), row.into());
        let [hot, cold] = Self::TEMPERATURES_K.map(|t| TotalRadiance.radiance(t));
        f * hot + (1.0 - f) * cold
    }

    /// Renders with n × n supersampling; `(exact, rendered)` radiance of every pixel the
    /// edge crosses (0 < f < 1), row-major.
    ///
    /// # Panics
    /// If `n` is out of [`TraceOptions`]' range.
    #[must_use]
    pub fn edge_pixels(&self, n: u32, seed: u64) -> Vec<(f64, f64)> {
        let options = TraceOptions {
            supersampling: n,
            seed,
            ..TraceOptions::default()
        };
        let frame = self.tracer.render(&self.camera, &options, &|_| {}).unwrap();
        let [w, _] = Self::PIXELS;
        frame
            .radiance_w_m2_sr
            .iter()
            .enumerate()
            .filter_map(|(i, &l)| {
                let (col, row) = (i as u32 % w, i as u32 / w);
                let f = pixel_fraction_left_of_line(Self::X0, Self::SLOPE, col.into(), row.into());
                (f > 0.0 && f < 1.0).then(|| (Self::exact_radiance_w_m2_sr(col, row), l))
            })
            .collect()
    }
}

impl Default for EdgeExperiment {
    fn default() -> Self {
        Self::new()
    }
}

/// The baseline of the tracer's speed: bare obvhs on the same triangles and rays, with its
/// own (not watertight) triangle test and nothing else. The triangles are re-centred
/// exactly as [`crate::geometry::Geometry`] does and stored as the tracer stores them: in
/// BVH order, one cache-line-aligned record each, so a candidate costs one memory line. A
/// `primitive_indices` lookup first would be a second random access the tracer does not
/// make, and obvhs's plain 48-byte `Triangle`s straddle two lines half the time (13 % slower
/// at 1M triangles): either would flatter the ratio.
#[derive(Debug)]
pub struct BareObvhs {
    bvh: obvhs::cwbvh::CwBvh,
    tris: Vec<AlignedTriangle>,
    centre_m: DVec3,
}

impl BareObvhs {
    /// Builds the CWBVH (obvhs's very fast preset, as the tracer) over `mesh`, re-centred on `centre_m`
    /// (the tracer's [`crate::geometry::Geometry::centre_m`]).
    #[must_use]
    pub fn new(mesh: &Mesh, centre_m: DVec3) -> Self {
        Self::with_params(mesh, centre_m, obvhs::BvhBuildParams::very_fast_build())
    }

    /// As [`BareObvhs::new`], with obvhs's build `params` (one of its presets, for
    /// measuring what build quality trades against traversal).
    #[must_use]
    pub fn with_params(mesh: &Mesh, centre_m: DVec3, params: obvhs::BvhBuildParams) -> Self {
        let tris: Vec<obvhs::triangle::Triangle> = triangles(mesh)
            .iter()
            .map(|t| obvhs::triangle::Triangle {
                v0: f32_local(t[0], centre_m),
                v1: f32_local(t[1], centre_m),
                v2: f32_local(t[2], centre_m),
            })
            .collect();
        let bvh = obvhs::cwbvh::builder::build_cwbvh_from_tris(
            &tris,
            params,
            &mut std::time::Duration::default(),
        );
        let tris = bvh
            .primitive_indices
            .iter()
            .map(|&i| AlignedTriangle(tris[i as usize]))
            .collect();
        Self {
            bvh,
            tris,
            centre_m,
        }
    }

    /// The f32 rays of every pixel of `camera` (from its position, through pixel centres),
    /// made once so that timing a pass measures traversal only.
    #[must_use]
    pub fn primary_rays(&self, camera: &Camera) -> Vec<obvhs::ray::Ray> {
        let origin = f32_local(camera.position_m, self.centre_m);
        primary_directions(camera)
            .iter()
            .map(|d| {
                obvhs::ray::Ray::new_inf(
                    origin,
                    glam::Vec3A::new(d[0] as f32, d[1] as f32, d[2] as f32),
                )
            })
            .collect()
    }

    /// Closest hit of every ray; the number of rays that hit.
    #[must_use]
    pub fn pass(&self, rays: &[obvhs::ray::Ray]) -> u64 {
        let mut hits = 0;
        for ray in rays {
            let mut hit = obvhs::ray::RayHit::none();
            if self
                .bvh
                .ray_traverse(*ray, &mut hit, |r, id| self.tris[id].0.intersect(r))
            {
                hits += 1;
            }
        }
        hits
    }
}

/// Rays per packet of [`BareObvhs::packet_pass`].
pub const PACKET: usize = 64;

/// The lanes whose bits are set in `mask`, lowest first.
fn lanes_of(mut mask: u64) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let k = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            k
        })
    })
}

/// A packet's rays, lane by lane: reciprocal direction and how far each may still go
/// (shortened by its hits).
struct Lanes {
    inv: [[f32; PACKET]; 3],
    t_max: [f32; PACKET],
}

impl BareObvhs {
    /// [`BareObvhs::pass`] with the rays taken [`PACKET`] at a time (consecutive rays: an
    /// 8 × 8 tile of pixels in tile order) and traversed together through the same obvhs
    /// nodes: a measured route to faster traversal, not the tracer's. A node's eight child
    /// boxes are decoded once for the packet and tested against each live lane (in groups
    /// of eight lanes, each group skipped when none of its lanes is live), children visited
    /// nearest first by the packet's nearest entry; below `threshold` live rays each goes on
    /// alone from the node (obvhs's `traverse!` started there), where a packet would test
    /// mostly dead lanes. The number of rays that hit.
    #[must_use]
    pub fn packet_pass(&self, rays: &[obvhs::ray::Ray], threshold: u32) -> u64 {
        use glam::UVec2;
        let mut hits = 0;
        let mut stack: Vec<(u32, u64)> = Vec::with_capacity(64);
        for packet in rays.chunks(PACKET) {
            let mut lanes = Lanes {
                inv: [[0.0; PACKET]; 3],
                t_max: [f32::INFINITY; PACKET],
            };
            for (k, r) in packet.iter().enumerate() {
                for axis in 0..3 {
                    lanes.inv[axis][k] = r.inv_direction[axis];
                }
                lanes.t_max[k] = r.tmax;
            }
            let live = u64::MAX >> (PACKET - packet.len());
            let packet_origin = packet[0].origin;
            assert!(
                packet.iter().all(|r| r.origin == packet_origin),
                "the rays of a packet share their origin"
            );
            stack.push((0, live));
            while let Some((index, mask)) = stack.pop() {
                if mask.count_ones() <= threshold {
                    for k in lanes_of(mask) {
                        let mut ray = packet[k];
                        ray.tmax = lanes.t_max[k];
                        let mut state = self.bvh.new_traversal(ray.direction);
                        state.current_group = UVec2::new(index, 0x8000_0000);
                        let mut node;
                        obvhs::traverse!(
                            self.bvh,
                            node,
                            state,
                            node.intersect_ray(&ray, state.oct_inv4),
                            {
                                let t = self.tris[state.primitive_id as usize].0.intersect(&ray);
                                if t < ray.tmax {
                                    ray.tmax = t;
                                }
                            }
                        );
                        lanes.t_max[k] = ray.tmax;
                    }
                    continue;
                }
                let node = &self.bvh.nodes[index as usize];
                // Per child: the packet's nearest entry, which lanes enter, the child.
                let mut children = [(0.0_f32, 0_u64, 0_usize); 8];
                let mut n = 0;
                for child in (0..8).filter(|&c| !node.is_child_empty(c)) {
                    let aabb = node.child_aabb(child);
                    let (mut enter, mut nearest) = (0_u64, f32::INFINITY);
                    let near = aabb.min - packet_origin;
                    let far = aabb.max - packet_origin;
                    for group in 0..PACKET / 8 {
                        if (mask >> (group * 8)) & 0xff == 0 {
                            continue;
                        }
                        let mut entry = [0.0_f32; 8];
                        let mut hit = [false; 8];
                        for j in 0..8 {
                            let k = group * 8 + j;
                            let (ax, bx) = (near.x * lanes.inv[0][k], far.x * lanes.inv[0][k]);
                            let (ay, by) = (near.y * lanes.inv[1][k], far.y * lanes.inv[1][k]);
                            let (az, bz) = (near.z * lanes.inv[2][k], far.z * lanes.inv[2][k]);
                            let t0 = ax.min(bx).max(ay.min(by)).max(az.min(bz)).max(1e-4);
                            let t1 = ax
                                .max(bx)
                                .min(ay.max(by))
                                .min(az.max(bz))
                                .min(lanes.t_max[k]);
                            entry[j] = t0;
                            hit[j] = t0 <= t1;
                        }
                        for j in 0..8 {
                            if hit[j] && mask >> (group * 8 + j) & 1 == 1 {
                                enter |= 1 << (group * 8 + j);
                                nearest = nearest.min(entry[j]);
                            }
                        }
                    }
                    if enter != 0 {
                        children[n] = (nearest, enter, child);
                        n += 1;
                    }
                }
                // Farthest first onto the stack, so the nearest is popped first.
                let children = &mut children[..n];
                children.sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
                for &(_, enter, child) in children.iter() {
                    if node.is_leaf(child) {
                        let (first, count) = node.child_primitives(child);
                        for prim in first..first + count {
                            let tri = &self.tris[prim as usize].0;
                            for k in lanes_of(enter) {
                                let mut ray = packet[k];
                                ray.tmax = lanes.t_max[k];
                                let t = tri.intersect(&ray);
                                if t < lanes.t_max[k] {
                                    lanes.t_max[k] = t;
                                }
                            }
                        }
                    } else {
                        stack.push((node.child_node_index(child), enter));
                    }
                }
            }
            hits += packet
                .iter()
                .zip(&lanes.t_max)
                .filter(|(r, t)| **t < r.tmax)
                .count() as u64;
        }
        hits
    }
}

/// A frame's apparent temperatures, K, through the total (all-wavelength) radiance.
#[must_use]
pub fn temperatures(frame: &crate::Frame) -> Vec<f64> {
    frame
        .radiance_w_m2_sr
        .iter()
        .map(|&l| TotalRadiance.temperature(l))
        .collect()
}

/// The unit direction of every pixel's centre ray of `camera`, row by row.
#[must_use]
pub fn primary_directions(camera: &Camera) -> Vec<DVec3> {
    let [w, h] = camera.pixels;
    (0..h)
        .flat_map(|r| (0..w).map(move |c| camera.pixel_direction(c, r)))
        .collect()
}

/// The tracer's own geometry on primary rays, without shading: [`Geometry::closest_hit`]
/// (f64 clip, watertight test, f64 refinement) from the sensor at `position_m` along each
/// of `directions`; the number of rays that hit. Between [`BareObvhs::pass`] and a render
/// it splits the tracer's cost into what its geometry adds to obvhs and what the
/// radiometry adds to that.
#[must_use]
pub fn geometry_pass<P: Copy + Send + Sync>(
    geometry: &Geometry<P>,
    position_m: DVec3,
    directions: &[DVec3],
) -> u64 {
    let origin = geometry.to_local(position_m);
    directions
        .iter()
        .map(|&d| {
            u64::from(
                geometry
                    .closest_hit(origin, d, 0.0, f64::INFINITY, None)
                    .is_some(),
            )
        })
        .sum()
}

/// An obvhs triangle alone in its cache line.
#[derive(Debug, Clone, Copy)]
#[repr(align(64))]
struct AlignedTriangle(obvhs::triangle::Triangle);

fn f32_local(p: DVec3, centre_m: DVec3) -> glam::Vec3A {
    glam::Vec3A::new(
        (p[0] - centre_m[0]) as f32,
        (p[1] - centre_m[1]) as f32,
        (p[2] - centre_m[2]) as f32,
    )
}

/// The pilot's space for a whole-spectrum tracer under a uniform `sky`: no atmosphere, the
/// band model, the tool's offer of bounces (8, 4, 2, 1, 0), sky-view rays (256, 64, 16, 0)
/// and refinement, exact path terms.
///
/// # Panics
/// If the tracer refuses the band set (it cannot: one sub-band, no emissivity table).
#[must_use]
pub fn vacuum_pilot_space(
    tracer: &Tracer<TotalRadiance, Vacuum>,
    sky: Vacuum,
) -> crate::pilot::PilotSpace<Vacuum> {
    use crate::pilot::{BandChoice, PilotSpace, REFINE_MAX_SIDE, Supersample};
    use irsig_atmosphere::{ModelKind, SubBandCount};
    let set = tracer
        .band_set(vec![crate::SubBand {
            band: TotalRadiance,
            atmosphere: sky,
            emissivity: None,
        }])
        .expect("one sub-band without emissivity tables");
    PilotSpace {
        bands: vec![BandChoice {
            atmosphere: ModelKind::None,
            sub_bands: SubBandCount::BAND,
            set,
            path_call_ns: 5.0,
            sky_ns: 0.0,
        }],
        atmospheres: vec![ModelKind::None],
        sub_bands: vec![SubBandCount::BAND],
        bounces: vec![8, 4, 2, 1, 0],
        sky_view_rays: vec![256, 64, 16, 0],
        supersampling: vec![Supersample::Refine(REFINE_MAX_SIDE)],
        path_terms: vec![crate::PathTermsMode::Exact],
        reasons: Vec::new(),
        pinned: Vec::new(),
        sun: None,
    }
}

/// [`vacuum_pilot_space`] by day: the band set lit by the tracer's sun (one sub-band,
/// `beam`), and the sun on or off and 64, 16, 4 or 1 shadow rays on offer, as
/// `irsig-trace` offers them.
///
/// # Panics
/// If the tracer has no sun ([`Tracer::with_sun`]).
#[must_use]
pub fn sunlit_pilot_space(
    tracer: &Tracer<TotalRadiance, Vacuum>,
    sky: Vacuum,
    beam: crate::SunBeam,
) -> crate::pilot::PilotSpace<Vacuum> {
    let one = || {
        tracer
            .band_set(vec![crate::SubBand {
                band: TotalRadiance,
                atmosphere: sky,
                emissivity: None,
            }])
            .expect("one sub-band without emissivity tables")
    };
    let mut space = vacuum_pilot_space(tracer, sky);
    space.bands[0].set = tracer
        .lit_band_set(one(), Some(vec![beam]))
        .expect("a tracer with a sun");
    space.sun = Some(crate::pilot::SunOffer {
        lit: vec![true, false],
        shadow_rays: vec![64, 16, 4, 1],
        dark: one(),
    });
    space
}
