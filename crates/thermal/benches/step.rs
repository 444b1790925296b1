//! The cost of one facet-step: [`irsig_thermal::step`] on typical walls (10 and 19 nodes),
//! DOE-2 convection, dry and wet, Backward Euler, Crank–Nicolson and TR-BDF2, loads
//! changing every step as a day's do. Each iteration makes 288 facet-steps, so the figure
//! per item is the cost of one facet-step with the elimination cached: either one facet
//! through a day at 5 minutes (the wind changes every step), or, in `irsig-therm`'s order,
//! 288 facets sharing a wall, a scratch and the weather, each with its own sun, through one
//! step.

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

/// `irsig-therm`'s order: every facet through one step, then the next step; the facets
/// share the weather (and so the wind) but each has its own sun and tilt.
fn run_all_facets(b: Bencher, nodes: usize, scheme: Scheme) {
    let wall = wall(nodes);
    let surface = Surface {
        solar_absorptance: 0.6,
        thermal_emissivity: 0.9,
        wet_fraction: 0.0,
        roughness: Roughness::Rough,
        convection: Convection::Doe2,
    };
    let orientations: Vec<Orientation> = (0..STEPS)
        .map(|i| Orientation {
            cos_tilt: (i as f64 * 0.37).sin(),
            windward: i % 3 != 0,
        })
        .collect();
    let day = day();
    let time_step = TimeStep {
        dt_s: 300.0,
        scheme,
    };
    let mut scratch = Scratch::new();
    let mut temps: Vec<Vec<f64>> = (0..STEPS).map(|_| wall.uniform_state(293.0)).collect();
    let suns: Vec<f64> = (0..STEPS)
        .map(|i| 0.5 + 0.5 * (i as f64 * 0.11).cos())
        .collect();
    let mut n = 0;
    b.counter(divan::counter::ItemsCount::new(STEPS))
        .bench_local(|| {
            let (before, after) = (day[n % STEPS], day[n % STEPS + 1]);
            for ((t, &orientation), &sun) in temps.iter_mut().zip(&orientations).zip(&suns) {
                let facet = Facet {
                    wall: &wall,
                    surface: &surface,
                    orientation,
                };
                let lit = |l: Loads| Loads {
                    shortwave_w_m2: l.shortwave_w_m2 * sun,
                    ..l
                };
                step(
                    &facet,
                    black_box(t),
                    &lit(before),
                    &lit(after),
                    time_step,
                    &mut scratch,
                )
                .unwrap();
            }
            n += 1;
        });
}

#[divan::bench(args = [10, 19])]
fn all_facets_backward_euler(b: Bencher, nodes: usize) {
    run_all_facets(b, nodes, Scheme::BackwardEuler);
}

#[divan::bench(args = [10, 19])]
fn all_facets_crank_nicolson(b: Bencher, nodes: usize) {
    run_all_facets(b, nodes, Scheme::CrankNicolson);
}

#[divan::bench(args = [10, 19])]
fn all_facets_tr_bdf2(b: Bencher, nodes: usize) {
    run_all_facets(b, nodes, Scheme::TrBdf2);
}
