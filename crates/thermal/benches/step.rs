//! The cost of one facet-step: [`irsig_thermal::step`] on typical walls (10 and 20 nodes),
//! DOE-2 convection, dry and wet, Backward Euler and Crank–Nicolson, loads changing every
//! step as a day's do. Each iteration steps 288 facets (a day at 5 minutes for one facet,
//! or one step of 288 facets sharing a wall and a scratch), so the figure per item is the
//! cost of one facet-step with the elimination cached, as in `irsig-therm`.

use divan::{Bencher, black_box};
use irsig_model::thermal::{BackAir, BackBoundary, Roughness, ThermalLayer, ThermalProperties};
use irsig_thermal::{
    Convection, Discretisation, Facet, Loads, Orientation, Scheme, Scratch, Surface, TimeStep,
    Wall, step,
};

fn main() {
    divan::main();
}

const STEPS: usize = 288;

/// 5 mm of render over concrete over insulation, convective back to a room: `nodes` in all.
fn wall(nodes: usize) -> Wall {
    let layer = |thickness_m, k, rho, c| ThermalLayer {
        thickness_m,
        conductivity_w_m_k: k,
        density_kg_m3: rho,
        specific_heat_j_kg_k: c,
        source: "bench".into(),
    };
    let props = ThermalProperties {
        layers: vec![
            layer(0.005, 0.7, 1600.0, 840.0),
            layer(0.15, 1.4, 2300.0, 880.0),
            layer(0.05, 0.04, 30.0, 1400.0),
        ],
        back: BackBoundary::Convective {
            h_w_m2_k: 2.5,
            air: BackAir::Fixed {
                temperature_k: 293.15,
            },
        },
        solar_absorptance: Some(0.6),
        thermal_emissivity: Some(0.9),
        wet_fraction: 0.0,
        roughness: Roughness::Rough,
        source: "bench".into(),
    };
    // 3 layers of `(nodes − 1) / 3` cells.
    let w = Wall::new(&props, &Discretisation::cells_per_layer((nodes - 1) / 3)).unwrap();
    assert_eq!(w.nodes(), nodes);
    w
}

/// A day's loads at 5-minute steps: sun by day, air and sky cycling.
fn day() -> Vec<Loads> {
    (0..=STEPS)
        .map(|i| {
            let phase = std::f64::consts::TAU * i as f64 / STEPS as f64;
            Loads {
                shortwave_w_m2: (900.0 * (phase - std::f64::consts::FRAC_PI_2).sin()).max(0.0),
                longwave_w_m2: 330.0 + 30.0 * phase.sin(),
                air_temperature_k: 293.0 + 6.0 * (phase - 2.0).sin(),
                dew_point_k: 283.0,
                pressure_pa: 101_325.0,
                wind_speed_m_s: 2.0 + phase.cos(),
                source_w_m2: 0.0,
            }
        })
        .collect()
}

fn run(b: Bencher, nodes: usize, scheme: Scheme, wet_fraction: f64) {
    let wall = wall(nodes);
    let surface = Surface {
        solar_absorptance: 0.6,
        thermal_emissivity: 0.9,
        wet_fraction,
        roughness: Roughness::Rough,
        convection: Convection::Doe2,
    };
    let facet = Facet {
        wall: &wall,
        surface: &surface,
        orientation: Orientation {
            cos_tilt: 0.3,
            windward: true,
        },
    };
    let loads = day();
    let time_step = TimeStep {
        dt_s: 300.0,
        scheme,
    };
    let mut scratch = Scratch::new();
    let mut temps = wall.uniform_state(293.0);
    b.counter(divan::counter::ItemsCount::new(STEPS))
        .bench_local(|| {
            for w in loads.windows(2) {
                step(
                    &facet,
                    black_box(&mut temps),
                    &w[0],
                    &w[1],
                    time_step,
                    &mut scratch,
                )
                .unwrap();
            }
        });
}

#[divan::bench(args = [10, 19])]
fn backward_euler_dry(b: Bencher, nodes: usize) {
    run(b, nodes, Scheme::BackwardEuler, 0.0);
}

#[divan::bench(args = [10, 19])]
fn crank_nicolson_dry(b: Bencher, nodes: usize) {
    run(b, nodes, Scheme::CrankNicolson, 0.0);
}

#[divan::bench(args = [10, 19])]
fn backward_euler_wet(b: Bencher, nodes: usize) {
    run(b, nodes, Scheme::BackwardEuler, 1.0);
}
