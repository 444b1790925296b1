//! The solver against an independent one written here: cell-centred finite volumes (cell
//! centres, not nodes, on the grid; layers joined by series resistances of half cells;
//! the surface temperature an algebraic balance solved by bisection at every stage),
//! integrated explicitly by classical fourth-order Runge–Kutta with 0.5 s steps. Both
//! solve a three-layer wall (render, concrete, insulation) with a convective back, under
//! radiation, McAdams convection and latent heat, for six hours from a uniform start.

use crate::common::{DAY_S, SIGMA, bisect, concrete, insulation, latent_flux_w_m2, props, render};
use irsig_model::thermal::{BackAir, BackBoundary, Roughness, ThermalLayer};
use irsig_thermal::{
    Convection, Discretisation, Facet, Loads, Orientation, Scheme, Scratch, Surface, TimeStep,
    Wall, step,
};
use std::f64::consts::TAU;

const ABSORPTANCE: f64 = 0.7;
const EMISSIVITY: f64 = 0.92;
const WET: f64 = 0.5;
const BACK_H: f64 = 2.5;
const BACK_AIR_K: f64 = 293.15;

fn loads(t: f64) -> Loads {
    let phase = TAU * t / DAY_S;
    Loads {
        shortwave_w_m2: 450.0 * (1.0 + phase.sin()),
        longwave_w_m2: 320.0 + 25.0 * (phase - 1.0).sin(),
        air_temperature_k: 291.0 + 6.0 * (phase - 0.7).sin(),
        dew_point_k: 282.0,
        pressure_pa: 98_000.0,
        wind_speed_m_s: 2.0 + 0.5 * phase.cos(),
        source_w_m2: 0.0,
    }
}

fn layers() -> Vec<ThermalLayer> {
    vec![render(0.005), concrete(0.1), insulation(0.03)]
}

/// The cell-centred method of lines: cells of `dx_m`, temperatures at their centres.
struct CellCentred {
    capacity: Vec<f64>,
    /// Conductance between cell j and j + 1: `1 / (Δx/2k_j + Δx/2k_{j+1})`.
    between: Vec<f64>,
    /// From the surface to the first centre, `2k/Δx`.
    surface_g: f64,
    /// From the last centre to the back air, `1 / (Δx/2k + 1/h)`.
    back_g: f64,
}

impl CellCentred {
    fn new(dx_m: f64) -> Self {
        let mut capacity = Vec::new();
        let mut conductivity = Vec::new();
        for l in layers() {
            let n = (l.thickness_m / dx_m).round() as usize;
            for _ in 0..n {
                capacity.push(l.density_kg_m3 * l.specific_heat_j_kg_k * dx_m);
                conductivity.push(l.conductivity_w_m_k);
            }
        }
        let between = conductivity
            .windows(2)
            .map(|k| 1.0 / (dx_m / (2.0 * k[0]) + dx_m / (2.0 * k[1])))
            .collect();
        let last = conductivity[conductivity.len() - 1];
        Self {
            capacity,
            surface_g: 2.0 * conductivity[0] / dx_m,
            back_g: 1.0 / (dx_m / (2.0 * last) + 1.0 / BACK_H),
            between,
        }
    }

    /// The surface temperature that balances the first cell's conduction.
    fn surface_k(&self, first_cell_k: f64, l: &Loads) -> f64 {
        let h = 5.7 + 3.8 * l.wind_speed_m_s;
        let net_in = |t: f64| {
            ABSORPTANCE * l.shortwave_w_m2 + EMISSIVITY * l.longwave_w_m2
                - EMISSIVITY * SIGMA * t.powi(4)
                - h * (t - l.air_temperature_k)
                - latent_flux_w_m2(WET, h, t, l.dew_point_k, l.pressure_pa)
        };
        bisect(
            |t| self.surface_g * (t - first_cell_k) - net_in(t),
            first_cell_k - 100.0,
            first_cell_k + 100.0,
        )
    }

    /// dT/dt of every cell.
    fn derivative(&self, temps: &[f64], l: &Loads, out: &mut [f64]) {
        let n = temps.len();
        let ts = self.surface_k(temps[0], l);
        for j in 0..n {
            let mut q = 0.0;
            if j == 0 {
                q += self.surface_g * (ts - temps[0]);
            } else {
                q += self.between[j - 1] * (temps[j - 1] - temps[j]);
            }
            if j + 1 < n {
                q += self.between[j] * (temps[j + 1] - temps[j]);
            } else {
                q += self.back_g * (BACK_AIR_K - temps[j]);
            }
            out[j] = q / self.capacity[j];
        }
    }

    /// One classical Runge–Kutta step from `t`.
    fn rk4(&self, temps: &mut [f64], t: f64, dt: f64) {
        let n = temps.len();
        let (mut k1, mut k2, mut k3, mut k4) =
            (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut y = vec![0.0; n];
        self.derivative(temps, &loads(t), &mut k1);
        for j in 0..n {
            y[j] = temps[j] + 0.5 * dt * k1[j];
        }
        self.derivative(&y, &loads(t + 0.5 * dt), &mut k2);
        for j in 0..n {
            y[j] = temps[j] + 0.5 * dt * k2[j];
        }
        self.derivative(&y, &loads(t + 0.5 * dt), &mut k3);
        for j in 0..n {
            y[j] = temps[j] + dt * k3[j];
        }
        self.derivative(&y, &loads(t + dt), &mut k4);
        for j in 0..n {
            temps[j] += dt / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
        }
    }
}

#[test]
fn agrees_with_an_explicit_cell_centred_runge_kutta_solver() {
    let dx = 0.001;
    // The reference: 135 cells, 0.5 s steps (RK4's stability limit here is about 0.7 s).
    let reference = CellCentred::new(dx);
    let mut cells = vec![293.0; reference.capacity.len()];
    // The solver under test: nodes 1 mm apart, Crank–Nicolson at 10 s.
    let wall = Wall::new(
        &props(
            layers(),
            BackBoundary::Convective {
                h_w_m2_k: BACK_H,
                air: BackAir::Fixed {
                    temperature_k: BACK_AIR_K,
                },
            },
        ),
        &Discretisation::max_spacing(dx, 1),
    )
    .unwrap();
    let surf = Surface {
        solar_absorptance: ABSORPTANCE,
        thermal_emissivity: EMISSIVITY,
        wet_fraction: WET,
        roughness: Roughness::Smooth,
        convection: Convection::McAdams,
    };
    let facet = Facet {
        wall: &wall,
        surface: &surf,
        orientation: Orientation {
            cos_tilt: 0.0,
            windward: true,
        },
    };
    let mut temps = wall.uniform_state(293.0);
    let mut scratch = Scratch::new();
    let time_step = TimeStep {
        dt_s: 10.0,
        scheme: Scheme::CrankNicolson,
    };
    // Depth 55 mm: a node of the solver, midway between two cell centres of the reference.
    let node_55mm = wall
        .depths_m()
        .iter()
        .position(|&d| (d - 0.055).abs() < 1e-9)
        .unwrap();
    let (mut worst_surface, mut worst_inside): (f64, f64) = (0.0, 0.0);
    let mut swing = (f64::INFINITY, f64::NEG_INFINITY);
    let ten_minutes = 600.0;
    for block in 0..36 {
        let t0 = f64::from(block) * ten_minutes;
        for k in 0..1200 {
            reference.rk4(&mut cells, t0 + f64::from(k) * 0.5, 0.5);
        }
        for k in 0..60 {
            let t = t0 + f64::from(k) * 10.0;
            step(
                &facet,
                &mut temps,
                &loads(t),
                &loads(t + 10.0),
                time_step,
                &mut scratch,
            )
            .unwrap();
        }
        let t = t0 + ten_minutes;
        let surface_ref = reference.surface_k(cells[0], &loads(t));
        let inside_ref = 0.5 * (cells[54] + cells[55]);
        worst_surface = worst_surface.max((temps[0] - surface_ref).abs());
        worst_inside = worst_inside.max((temps[node_55mm] - inside_ref).abs());
        swing = (swing.0.min(temps[0]), swing.1.max(temps[0]));
    }
    // Both are second-order in space with 1 mm cells and accurate in time: they agree to
    // a few hundredths of a millikelvin.
    assert!(
        worst_surface < 2e-3,
        "surface departs from the reference by {worst_surface} K"
    );
    assert!(
        worst_inside < 2e-3,
        "55 mm deep departs from the reference by {worst_inside} K"
    );
    // The comparison means something: the surface moved by several kelvin.
    assert!(swing.1 - swing.0 > 5.0, "{swing:?}");
}
