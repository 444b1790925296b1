//! A blackbody (or grey, or spectral) plate seen through one slant path of an
//! atmosphere's tables, and LOWTRAN7's own spectral integral for that path: what
//! `tests/tests/spectral_trace.rs` and `tests/tests/spectral_materials.rs` compare
//! `irsig-trace --probe` with. The expected values use nothing of the code under test: a
//! Planck function, Simpson's rule, a bisection and the trapezoid rule over the table's
//! own LOWTRAN7 spectra.
// Test helpers: they panic, naming what failed, rather than return errors.
#![allow(clippy::missing_panics_doc, clippy::must_use_candidate)]

use std::path::Path;

use irsig_model::{SpectralAtmosphere, SpectralAxis};

use crate::bin;

/// 2hc², W m² sr⁻¹ (CODATA 2018, exact in the 2019 SI).
pub const C1_W_M2_SR: f64 = 2.0 * 6.626_070_15e-34 * 299_792_458.0 * 299_792_458.0;
/// hc/k, m K.
pub const C2_M_K: f64 = 6.626_070_15e-34 * 299_792_458.0 / 1.380_649e-23;

/// Planck's spectral radiance, W m⁻² sr⁻¹ µm⁻¹.
pub fn planck_per_um(wavelength_um: f64, t_k: f64) -> f64 {
    let l = wavelength_um * 1e-6;
    C1_W_M2_SR / (l.powi(5) * ((C2_M_K / (l * t_k)).exp() - 1.0)) * 1e-6
}

/// ∫ f over [lo, hi] by composite Simpson with `n` (even) intervals.
pub fn simpson(lo: f64, hi: f64, n: u32, f: impl Fn(f64) -> f64) -> f64 {
    let h = (hi - lo) / f64::from(n);
    let mut s = f(lo) + f(hi);
    for i in 1..n {
        let w = if i % 2 == 1 { 4.0 } else { 2.0 };
        s += w * f(lo + h * f64::from(i));
    }
    s * h / 3.0
}

/// The temperature, K, whose radiance by `band_radiance` is `radiance`, by bisection over
/// 150–400 K.
pub fn invert(radiance: f64, band_radiance: impl Fn(f64) -> f64) -> f64 {
    let (mut lo, mut hi) = (150.0, 400.0);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if band_radiance(mid) < radiance {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// ∫ B dλ over 8–14 µm, W m⁻² sr⁻¹: composite Simpson, 6000 intervals (relative error far
/// below 1e-9 for these temperatures).
pub fn band_radiance(t_k: f64) -> f64 {
    simpson(8.0, 14.0, 6000, |l| planck_per_um(l, t_k))
}

/// The apparent temperature of an 8–14 µm radiance, K.
pub fn apparent_k(radiance: f64) -> f64 {
    invert(radiance, band_radiance)
}

/// LOWTRAN7's own integral for the slant path of table node (`altitude`, `angle`) to a
/// blackbody at `t_k`: `∫ τ B dλ + ∫ L_path dλ` over 8–14 µm, W m⁻² sr⁻¹.
pub fn lowtran_integral(a: &SpectralAtmosphere, altitude: usize, angle: usize, t_k: f64) -> f64 {
    lowtran_integral_of(a, altitude, angle, t_k, |_| 1.0, &[], |_| 1.0)
}

/// As [`lowtran_integral`] for a Lambertian surface of emissivity `eps(λ)` (µm), which
/// also reflects `1 − ε` of the ground's hemispheric sky:
/// `∫ τ (ε B + (1 − ε) L_hemi) dλ + ∫ L_path dλ`. `breaks`: wavenumbers (cm⁻¹) where
/// `eps` jumps, added as nodes on both sides. `response`: the sensor's relative response
/// (µm), which multiplies the whole integrand.
pub fn lowtran_integral_of(
    a: &SpectralAtmosphere,
    altitude: usize,
    angle: usize,
    t_k: f64,
    eps: impl Fn(f64) -> f64,
    breaks: &[f64],
    response: impl Fn(f64) -> f64,
) -> f64 {
    assert_eq!(a.grid.axis, SpectralAxis::WavenumberPerCm);
    let hemi = a.sky_hemispheric_w_m2_sr_per_unit.as_ref().unwrap();
    let s = a.slant.as_ref().unwrap();
    let n = a.grid.points.len();
    let at = (altitude * s.nadir_deg.len() + angle) * n;
    let tau = &s.transmission[at..at + n];
    let path = &s.path_radiance_w_m2_sr_per_unit[at..at + n];
    let nu = &a.grid.points;
    // (wavenumber, τ, L_path per cm⁻¹) at ν, linear in ν between grid points.
    let value = |x: f64| -> (f64, f64, f64) {
        let k = nu.partition_point(|&p| p < x).clamp(1, n - 1);
        let t = (x - nu[k - 1]) / (nu[k] - nu[k - 1]);
        let lerp = |v: &[f32]| f64::from(v[k - 1]) * (1.0 - t) + f64::from(v[k]) * t;
        (lerp(tau), lerp(path), lerp(hemi))
    };
    let mut nodes: Vec<f64> = vec![1e4 / 14.0];
    nodes.extend(
        nu.iter()
            .copied()
            .filter(|&x| x > 1e4 / 14.0 && x < 1e4 / 8.0),
    );
    nodes.push(1e4 / 8.0);
    // The integrand per µm at each node, in increasing wavelength; at a jump of ε, its
    // value on each side.
    let mut points: Vec<(f64, f64)> = nodes
        .iter()
        .flat_map(|&x| {
            let (t, l, h) = value(x);
            let wavelength = 1e4 / x;
            let weight = response(wavelength);
            let at = move |w: f64, e: f64| {
                (
                    w,
                    weight
                        * (t * (e * planck_per_um(wavelength, t_k) + (1.0 - e) * h * x * x / 1e4)
                            + l * x * x / 1e4),
                )
            };
            if breaks.iter().any(|&b| (b - x).abs() < 1e-9) {
                vec![
                    at(wavelength, eps(wavelength - 1e-9)),
                    at(wavelength + 1e-12, eps(wavelength + 1e-9)),
                ]
            } else {
                vec![at(wavelength, eps(wavelength))]
            }
        })
        .collect();
    points.sort_by(|p, q| p.0.total_cmp(&q.0));
    points
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum()
}

/// The index of table node `x`.
pub fn node(nodes: &[f64], x: f64) -> usize {
    nodes.iter().position(|&v| (v - x).abs() < 1e-9).unwrap()
}

/// A blackbody plate at `t_k`, 200 km across, 1 m above the ground: where LOWTRAN7's
/// slant paths end (the tables' `ground_m`), so that the path is the table's own.
pub fn scene(dir: &Path, t_k: f64) -> std::path::PathBuf {
    let path = dir.join(format!("scene-{t_k}.ron"));
    std::fs::write(
        &path,
        format!(
            "(objects: [\"plate\"], \
             positions_m: [(-1e5, -1e5, 1.0), (1e5, -1e5, 1.0), (1e5, 1e5, 1.0), (-1e5, 1e5, 1.0)], \
             facets: [(vertices: (0, 1, 2), material: 1, temperature_k: {t_k:?}, object: 0), \
                      (vertices: (0, 2, 3), material: 1, temperature_k: {t_k:?}, object: 0)])"
        ),
    )
    .unwrap();
    let materials = dir.join("black.ron");
    std::fs::write(
        &materials,
        "(materials: [(id: 1, name: \"black\", emissivity: [(0.0, 1.0), (90.0, 1.0)], \
         specular_fraction: 0.0, source: \"a blackbody\")])",
    )
    .unwrap();
    path
}

/// The radiance `irsig-trace --probe` reports at the sensor for a 1-pixel view from
/// `altitude_m` at `nadir_deg`, W m⁻² sr⁻¹, and the sub-band count it used.
pub fn probe(
    dir: &Path,
    atmosphere: &str,
    sub_bands: &str,
    t_k: f64,
    altitude_m: f64,
    nadir_deg: f64,
) -> (f64, u32) {
    probe_with(
        dir,
        None,
        atmosphere,
        Some(sub_bands),
        t_k,
        altitude_m,
        nadir_deg,
    )
}

/// As [`probe`] with the plate made of material 1 of `materials` (else a blackbody), and
/// `--sub-bands` given only when `sub_bands` is.
pub fn probe_with(
    dir: &Path,
    materials: Option<&Path>,
    atmosphere: &str,
    sub_bands: Option<&str>,
    t_k: f64,
    altitude_m: f64,
    nadir_deg: f64,
) -> (f64, u32) {
    let materials = materials.map_or_else(|| dir.join("black.ron"), Path::to_path_buf);
    let mut args = vec![
        "--materials".to_owned(),
        materials.to_string_lossy().into_owned(),
        "--atmosphere".to_owned(),
        atmosphere.to_owned(),
    ];
    if let Some(k) = sub_bands {
        args.extend(["--sub-bands".to_owned(), k.to_owned()]);
    }
    probe_args(dir, &args, t_k, altitude_m, nadir_deg)
}

/// The radiance and sub-band count `irsig-trace --probe` reports for the plate at `t_k`
/// seen from `altitude_m` at `nadir_deg` (a 1-pixel view), with `args` (which give
/// `--materials`).
pub fn probe_args(
    dir: &Path,
    args: &[String],
    t_k: f64,
    altitude_m: f64,
    nadir_deg: f64,
) -> (f64, u32) {
    let view = dir.join("view.ron");
    let reach = (altitude_m - 1.0) * nadir_deg.to_radians().tan();
    std::fs::write(
        &view,
        format!(
            "LookAt(position_m: (0.0, 0.0, {altitude_m:?}), target_m: ({reach:?}, 0.0, 1.0), \
             up: (0.0, 1.0, 0.0), pixels: (1, 1), fov_deg: (0.01, 0.01))"
        ),
    )
    .unwrap();
    let scene = scene(dir, t_k);
    let out = bin("irsig-trace")
        .arg("--scene")
        .arg(scene)
        .arg("--view")
        .arg(&view)
        .args(args)
        .args(["--probe", "0,0"])
        .output()
        .unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let field = |name: &str| -> &str {
        stdout
            .lines()
            .find_map(|l| l.strip_prefix(name))
            .unwrap_or_else(|| panic!("no `{name}` in\n{stdout}"))
            .trim()
    };
    assert!(field("event").ends_with("(Diffuse)"), "{stdout}");
    let count = stdout
        .lines()
        .next()
        .and_then(|l| l.rsplit(", ").next())
        .and_then(|c| c.split(' ').next())
        .and_then(|c| c.parse().ok())
        .unwrap_or_else(|| panic!("no sub-band count in\n{stdout}"));
    (field("L at sensor (W m-2 sr-1)").parse().unwrap(), count)
}
