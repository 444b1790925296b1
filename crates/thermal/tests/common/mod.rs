//! Walls, surfaces and loads the solver tests share, and the physics they check against,
//! written here from the cited formulas (not taken from the crate).

// Each test file uses a different part of this module.
#![allow(dead_code)]

use irsig_model::thermal::{BackBoundary, Roughness, ThermalLayer, ThermalProperties};
use irsig_thermal::{Convection, Loads, Surface};

pub const SIGMA: f64 = 5.670_374_419e-8;
pub const DAY_S: f64 = 86_400.0;

/// A layer of `thickness_m` with conductivity, density and specific heat.
pub fn layer(thickness_m: f64, k: f64, rho: f64, c: f64) -> ThermalLayer {
    ThermalLayer {
        thickness_m,
        conductivity_w_m_k: k,
        density_kg_m3: rho,
        specific_heat_j_kg_k: c,
        source: "test".into(),
    }
}

/// Concrete, Incropera Table A.3: k 1.4, ρ 2300, c 880 (α = 6.917e-7 m²/s).
pub fn concrete(thickness_m: f64) -> ThermalLayer {
    layer(thickness_m, 1.4, 2300.0, 880.0)
}

/// Cement render or plaster: k 0.7, ρ 1600, c 840.
pub fn render(thickness_m: f64) -> ThermalLayer {
    layer(thickness_m, 0.7, 1600.0, 840.0)
}

/// Expanded polystyrene-like insulation: k 0.04, ρ 30, c 1400.
pub fn insulation(thickness_m: f64) -> ThermalLayer {
    layer(thickness_m, 0.04, 30.0, 1400.0)
}

/// Plain carbon steel, Incropera Table A.1: k 60.5, ρ 7854, c 434.
pub fn steel(thickness_m: f64) -> ThermalLayer {
    layer(thickness_m, 60.5, 7854.0, 434.0)
}

/// A paint film: k 0.2, ρ 1200, c 1500.
pub fn paint(thickness_m: f64) -> ThermalLayer {
    layer(thickness_m, 0.2, 1200.0, 1500.0)
}

pub fn props(layers: Vec<ThermalLayer>, back: BackBoundary) -> ThermalProperties {
    ThermalProperties {
        layers,
        back,
        solar_absorptance: None,
        thermal_emissivity: None,
        wet_fraction: 0.0,
        roughness: Roughness::MediumRough,
        source: "test".into(),
    }
}

pub fn surface(
    solar_absorptance: f64,
    thermal_emissivity: f64,
    wet_fraction: f64,
    convection: Convection,
) -> Surface {
    Surface {
        solar_absorptance,
        thermal_emissivity,
        wet_fraction,
        roughness: Roughness::MediumRough,
        convection,
    }
}

/// Still, dry-ish air at `air_k` with no radiation and no source.
pub fn quiet(air_k: f64) -> Loads {
    Loads {
        shortwave_w_m2: 0.0,
        longwave_w_m2: 0.0,
        air_temperature_k: air_k,
        dew_point_k: air_k - 10.0,
        pressure_pa: 101_325.0,
        wind_speed_m_s: 0.0,
        source_w_m2: 0.0,
    }
}

/// The root of an increasing function on `[lo, hi]` by bisection, to 1e-12 K.
pub fn bisect(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    assert!(f(lo) < 0.0 && f(hi) > 0.0, "no sign change on [{lo}, {hi}]");
    while hi - lo > 1e-12 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Saturation vapour pressure over water, Pa (Alduchov & Eskridge 1996, AERK).
pub fn vapour_pressure_pa(t_k: f64) -> f64 {
    let t = t_k - 273.15;
    610.94 * (17.625 * t / (t + 243.04)).exp()
}

/// Latent heat of vaporisation, J/kg (Henderson-Sellers 1984).
pub fn latent_heat_j_kg(t_k: f64) -> f64 {
    1.918_46e6 * (t_k / (t_k - 33.91)).powi(2)
}

/// The latent heat flux of a surface at `t_k` (W/m², positive evaporating) by the
/// Chilton–Colburn analogy: `f_w h / (c_p Le^⅔) · 0.622 (e_s(T) − e_a) / p · L_v(T)`, with
/// c_p = 1005 J/kg/K and Le = 0.865.
pub fn latent_flux_w_m2(wet: f64, h: f64, t_k: f64, dew_k: f64, pressure_pa: f64) -> f64 {
    wet * h / (1005.0 * 0.865_f64.powf(2.0 / 3.0))
        * 0.622
        * (vapour_pressure_pa(t_k) - vapour_pressure_pa(dew_k))
        / pressure_pa
        * latent_heat_j_kg(t_k)
}

/// The DOE-2 exterior convective coefficient, from the EnergyPlus Engineering Reference.
pub fn doe2_h(t_s: f64, t_air: f64, cos_tilt: f64, windward: bool, rf: f64, wind: f64) -> f64 {
    let dt = t_s - t_air;
    let hn = if dt == 0.0 || cos_tilt == 0.0 {
        1.31 * dt.abs().cbrt()
    } else if dt * cos_tilt > 0.0 {
        9.482 * dt.abs().cbrt() / (7.238 - cos_tilt.abs())
    } else {
        1.810 * dt.abs().cbrt() / (1.382 + cos_tilt.abs())
    };
    let (a, b) = if windward {
        (3.26, 0.89)
    } else {
        (3.55, 0.617)
    };
    let hf = a * wind.powf(b);
    hn + rf * ((hn * hn + hf * hf).sqrt() - hn)
}
