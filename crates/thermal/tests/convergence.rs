//! The solver's observed orders of accuracy: the error against a fine reference falls as
//! the step halves at the scheme's order (Backward Euler 1, Crank–Nicolson and TR-BDF2 2)
//! and as the
//! node spacing halves at 2 (the vertex-centred finite volumes). The problem is a rendered
//! concrete wall ventilated behind, with the full nonlinear boundary (radiation, McAdams
//! convection, latent heat) under smooth loads.

use crate::common::{DAY_S, concrete, props, render, surface};
use irsig_model::thermal::{BackAir, BackBoundary, ThermalProperties};
use irsig_thermal::{
    Convection, Discretisation, Facet, Loads, Orientation, Scheme, Scratch, Surface, TimeStep,
    Wall, step,
};
use std::f64::consts::TAU;

fn wall_props() -> ThermalProperties {
    props(
        vec![render(0.01), concrete(0.1)],
        BackBoundary::Convective {
            h_w_m2_k: 3.0,
            air: BackAir::Outdoor,
        },
    )
}

fn the_surface() -> Surface {
    surface(0.7, 0.92, 0.4, Convection::McAdams)
}

/// Smooth loads: no sunrise kink, so that the schemes can show their orders.
fn loads(t: f64) -> Loads {
    let phase = TAU * t / DAY_S;
    Loads {
        shortwave_w_m2: 400.0 * (1.0 + phase.sin()),
        longwave_w_m2: 330.0 + 20.0 * (phase - 1.0).sin(),
        air_temperature_k: 293.0 + 5.0 * (phase - 0.5).sin(),
        dew_point_k: 283.0 + 2.0 * phase.cos(),
        pressure_pa: 101_325.0,
        wind_speed_m_s: 3.0 + phase.sin(),
        source_w_m2: 0.0,
    }
}

/// Runs `steps` steps of `dt_s` from `t0` and `temps`.
fn run(wall: &Wall, temps: &mut [f64], t0: f64, dt_s: f64, steps: usize, scheme: Scheme) {
    let surf = the_surface();
    let facet = Facet {
        wall,
        surface: &surf,
        orientation: Orientation {
            cos_tilt: 0.0,
            windward: true,
        },
    };
    let mut scratch = Scratch::new();
    let time_step = TimeStep { dt_s, scheme };
    for n in 0..steps {
        let t = t0 + n as f64 * dt_s;
        step(
            &facet,
            temps,
            &loads(t),
            &loads(t + dt_s),
            time_step,
            &mut scratch,
        )
        .unwrap();
    }
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// log₂ of successive error ratios.
fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect()
}

/// Six hours from a spun-up state with steps of 1200, 600, 300 and 150 s against a
/// reference at 1200/128 s by Crank–Nicolson, on one grid: the observed order of Backward
/// Euler must lie in 0.85–1.15, of Crank–Nicolson and TR-BDF2 in 1.8–2.2.
#[test]
fn error_falls_at_the_schemes_order_as_the_step_halves() {
    let wall = Wall::new(&wall_props(), &Discretisation::cells_per_layer(8)).unwrap();
    // A day and a half of spin-up by Backward Euler at 60 s, so that the start is smooth.
    let mut start = wall.uniform_state(293.0);
    run(&wall, &mut start, 0.0, 60.0, 2160, Scheme::BackwardEuler);
    let t0 = 2160.0 * 60.0;
    let span = 6.0 * 3600.0;
    let mut reference = start.clone();
    run(
        &wall,
        &mut reference,
        t0,
        1200.0 / 128.0,
        18 * 128,
        Scheme::CrankNicolson,
    );
    for (scheme, band) in [
        (Scheme::BackwardEuler, 0.85..=1.15),
        (Scheme::CrankNicolson, 1.8..=2.2),
        (Scheme::TrBdf2, 1.8..=2.2),
    ] {
        let errors: Vec<f64> = [1200.0, 600.0, 300.0, 150.0]
            .iter()
            .map(|&dt| {
                let mut temps = start.clone();
                run(&wall, &mut temps, t0, dt, (span / dt) as usize, scheme);
                max_difference(&temps, &reference)
            })
            .collect();
        for order in orders(&errors) {
            assert!(
                band.contains(&order),
                "{scheme:?}: errors {errors:?} give orders {:?}",
                orders(&errors)
            );
        }
    }
}

/// Two days of the same loads on grids of 2, 4, 8 and 16 cells per layer against 128, by
/// Crank–Nicolson at 10 s (its time error far below the grids'), compared at the coarse
/// grid's nodes (every grid's nodes include them): the observed order must lie in
/// 1.8–2.2.
#[test]
fn error_falls_at_second_order_as_the_spacing_halves() {
    let final_state = |cells: usize| {
        let wall = Wall::new(&wall_props(), &Discretisation::cells_per_layer(cells)).unwrap();
        let mut temps = wall.uniform_state(293.0);
        run(
            &wall,
            &mut temps,
            0.0,
            10.0,
            2 * 8640,
            Scheme::CrankNicolson,
        );
        // Sample at the nodes of the 2-cells-per-layer grid: every `cells / 2`-th node.
        temps
            .iter()
            .step_by(cells / 2)
            .copied()
            .collect::<Vec<f64>>()
    };
    let reference = final_state(128);
    let errors: Vec<f64> = [2, 4, 8, 16]
        .iter()
        .map(|&cells| max_difference(&final_state(cells), &reference))
        .collect();
    for order in orders(&errors) {
        assert!(
            (1.8..=2.2).contains(&order),
            "errors {errors:?} give orders {:?}",
            orders(&errors)
        );
    }
}
