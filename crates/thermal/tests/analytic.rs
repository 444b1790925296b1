//! The solver against closed-form solutions: a semi-infinite solid under a sinusoidal
//! surface temperature (Carslaw & Jaeger), a slab after a step in air temperature
//! (Incropera §5.5), a thin insulated plate in steady sun, and a periodic day whose energy
//! closes. Expected values come from the physics, computed here.

use crate::common::{
    DAY_S, SIGMA, bisect, concrete, doe2_h, latent_flux_w_m2, props, quiet, render, steel, surface,
};
use irsig_model::thermal::{BackAir, BackBoundary, Roughness};
use irsig_thermal::{
    Convection, Discretisation, Facet, Loads, Orientation, Scheme, Scratch, StepFluxes, TimeStep,
    Wall, step, step_held,
};
use std::f64::consts::{PI, TAU};

/// Carslaw & Jaeger (1959, §2.6): under `T(0, t) = T_m + A sin ωt`, a semi-infinite solid's
/// steady periodic temperature is `T_m + A e^{−x/d} sin(ωt − x/d)`, `d = √(2α/ω)`: the
/// amplitude decays as `e^{−x/d}` and the phase lags `x/d`. A 1.5 m wall (11 d) with an
/// insulated back is semi-infinite to `e^{−22}`.
#[test]
fn semi_infinite_solid_under_a_sinusoidal_surface_temperature() {
    let (t_mean, amplitude) = (300.0, 10.0);
    let omega = TAU / DAY_S;
    let alpha = 1.4 / (2300.0 * 880.0);
    let d = (2.0 * alpha / omega).sqrt();
    let wall = Wall::new(
        &props(vec![concrete(1.5)], BackBoundary::Adiabatic),
        &Discretisation::max_spacing(0.0025, 1),
    )
    .unwrap();
    let exact = |x: f64, t: f64| t_mean + amplitude * (-x / d).exp() * (omega * t - x / d).sin();
    let mut temps: Vec<f64> = wall.depths_m().iter().map(|&x| exact(x, 0.0)).collect();
    let dt_s = 120.0;
    let time_step = TimeStep {
        dt_s,
        scheme: Scheme::CrankNicolson,
    };
    let steps_per_day = (DAY_S / dt_s) as usize;
    let mut scratch = Scratch::new();
    let loads = quiet(300.0);
    // Nodes near d/2, d and 2d.
    let probes: Vec<usize> = [0.5 * d, d, 2.0 * d]
        .iter()
        .map(|&x| {
            wall.depths_m()
                .iter()
                .position(|&depth| depth >= x)
                .unwrap()
        })
        .collect();
    let mut sums = vec![(0.0, 0.0); probes.len()];
    let mut worst: f64 = 0.0;
    for n in 1..=2 * steps_per_day {
        let t = n as f64 * dt_s;
        step_held(
            &wall,
            &mut temps,
            exact(0.0, t),
            &loads,
            &loads,
            time_step,
            &mut scratch,
        )
        .unwrap();
        for (k, &i) in probes.iter().enumerate() {
            let x = wall.depths_m()[i];
            worst = worst.max((temps[i] - exact(x, t)).abs());
            if n > steps_per_day {
                let y = temps[i] - t_mean;
                sums[k].0 += y * (omega * t).sin();
                sums[k].1 += y * (omega * t).cos();
            }
        }
    }
    // The floor is 0.05 K; at these settings the departure is below 1 mK.
    assert!(worst < 0.005, "worst departure {worst} K");
    for (k, &i) in probes.iter().enumerate() {
        let x = wall.depths_m()[i];
        let (a, b) = (
            2.0 * sums[k].0 / steps_per_day as f64,
            2.0 * sums[k].1 / steps_per_day as f64,
        );
        let got_amplitude = a.hypot(b);
        let got_lag = -b.atan2(a);
        let want_amplitude = amplitude * (-x / d).exp();
        assert!(
            (got_amplitude - want_amplitude).abs() < 1e-3,
            "x = {x}: amplitude {got_amplitude} vs {want_amplitude}"
        );
        assert!(
            (got_lag - x / d).abs() < 2e-4,
            "x = {x}: phase lag {got_lag} vs {}",
            x / d
        );
    }
}

/// Incropera & DeWitt (6th ed., §5.5.1, eq. 5.42): a plane wall of half-thickness `L`
/// initially at `T_i`, its surfaces suddenly exposed to air at `T_∞` through `h`:
/// `(T − T_∞)/(T_i − T_∞) = Σ C_n exp(−ζ_n² Fo) cos(ζ_n x*)`, `ζ_n tan ζ_n = Bi`,
/// `C_n = 4 sin ζ_n / (2ζ_n + sin 2ζ_n)`, `x*` from the mid-plane, which the insulated
/// back stands for.
#[test]
fn slab_after_a_step_in_air_temperature() {
    let (l, k, h) = (0.1, 1.4, 20.0);
    let (t_initial, t_air) = (300.0, 350.0);
    let alpha = k / (2300.0 * 880.0);
    let bi = h * l / k;
    // ζ_n in (nπ, nπ + π/2): `(−1)^n (ζ sin ζ − Bi cos ζ)` rises from −Bi to
    // nπ + π/2.
    let zetas: Vec<f64> = (0..200)
        .map(|n| {
            let sign = if n % 2 == 0 { 1.0 } else { -1.0 };
            let lo = f64::from(n) * PI;
            bisect(|z| sign * (z * z.sin() - bi * z.cos()), lo, lo + 0.5 * PI)
        })
        .collect();
    let exact = |depth: f64, t: f64| {
        let fo = alpha * t / (l * l);
        let x_star = 1.0 - depth / l;
        let theta: f64 = zetas
            .iter()
            .map(|&z| {
                4.0 * z.sin() / (2.0 * z + (2.0 * z).sin())
                    * (-z * z * fo).exp()
                    * (z * x_star).cos()
            })
            .sum();
        t_air + (t_initial - t_air) * theta
    };
    let wall = Wall::new(
        &props(vec![concrete(l)], BackBoundary::Adiabatic),
        &Discretisation::max_spacing(0.001, 1),
    )
    .unwrap();
    let surf = surface(0.0, 0.0, 0.0, Convection::Fixed { h_w_m2_k: h });
    let facet = Facet {
        wall: &wall,
        surface: &surf,
        orientation: Orientation {
            cos_tilt: 0.0,
            windward: true,
        },
    };
    let air = quiet(t_air);
    let mut temps = wall.uniform_state(t_initial);
    let dt_s = 10.0;
    let time_step = TimeStep {
        dt_s,
        scheme: Scheme::CrankNicolson,
    };
    let mut scratch = Scratch::new();
    let checks =
        [0.05, 0.2, 0.5, 1.0, 2.0].map(|fo: f64| (fo * l * l / alpha / dt_s).round() as usize);
    let mut worst: f64 = 0.0;
    for n in 1..=checks[checks.len() - 1] {
        step(&facet, &mut temps, &air, &air, time_step, &mut scratch).unwrap();
        if checks.contains(&n) {
            let t = n as f64 * dt_s;
            for (&x, &got) in wall.depths_m().iter().zip(&temps) {
                worst = worst.max((got - exact(x, t)).abs());
            }
        }
    }
    // Heated by 50 K, every node within 0.05 K of the series at every check (the floor);
    // at these settings, within about 1 mK.
    assert!(worst < 0.005, "worst departure {worst} K");
    // The series itself is right: at Fo = 0.2 the surface has risen well but not all the way.
    let surface_rise = exact(0.0, 0.2 * l * l / alpha) - t_initial;
    assert!(surface_rise > 15.0 && surface_rise < 40.0, "{surface_rise}");
}

/// A 1 mm steel plate, insulated behind, in steady sun: it settles where what it absorbs
/// equals what it emits and convects, `α E + ε E_LW = ε σ T⁴ + h (T − T_air)` (plus the
/// latent heat of a wet plate), the root found here by bisection.
#[test]
fn thin_insulated_plate_in_steady_sun() {
    let wall = Wall::new(
        &props(vec![steel(0.001)], BackBoundary::Adiabatic),
        &Discretisation::cells_per_layer(2),
    )
    .unwrap();
    let sun = Loads {
        shortwave_w_m2: 800.0,
        longwave_w_m2: 350.0,
        air_temperature_k: 300.0,
        dew_point_k: 285.0,
        pressure_pa: 95_000.0,
        wind_speed_m_s: 2.0,
        source_w_m2: 0.0,
    };
    let (a, e) = (0.9, 0.9);
    let roof = Orientation {
        cos_tilt: 1.0,
        windward: true,
    };
    let rough = Roughness::MediumRough.multiplier();
    type HFn = Box<dyn Fn(f64) -> f64>;
    let cases: Vec<(Convection, f64, HFn)> = vec![
        // McAdams: h = 5.7 + 3.8 V = 13.3 at 2 m/s.
        (Convection::McAdams, 0.0, Box::new(|_| 13.3)),
        (
            Convection::Doe2,
            0.0,
            Box::new(move |t| doe2_h(t, 300.0, 1.0, true, rough, 2.0)),
        ),
        (
            Convection::Doe2,
            0.6,
            Box::new(move |t| doe2_h(t, 300.0, 1.0, true, rough, 2.0)),
        ),
    ];
    for (convection, wet, h) in cases {
        let surf = surface(a, e, wet, convection);
        let facet = Facet {
            wall: &wall,
            surface: &surf,
            orientation: roof,
        };
        let balance = |t: f64| {
            e * SIGMA * t.powi(4)
                + h(t) * (t - 300.0)
                + latent_flux_w_m2(wet, h(t), t, 285.0, 95_000.0)
                - a * 800.0
                - e * 350.0
        };
        let want = bisect(balance, 250.0, 450.0);
        for scheme in [Scheme::BackwardEuler, Scheme::CrankNicolson, Scheme::TrBdf2] {
            let mut temps = wall.uniform_state(290.0);
            let mut scratch = Scratch::new();
            let time_step = TimeStep { dt_s: 60.0, scheme };
            for _ in 0..300 {
                step(&facet, &mut temps, &sun, &sun, time_step, &mut scratch).unwrap();
            }
            // Backward Euler and TR-BDF2 settle on the root exactly. Crank–Nicolson is not
            // L-stable: the
            // plate's fast through-thickness mode, excited by the start, flips sign each
            // step and decays only as (1 − 2/(λ dt))ⁿ, leaving a few mK of ripple here.
            let tolerance = match scheme {
                Scheme::CrankNicolson => 0.05,
                _ => 1e-6,
            };
            for &t in &temps {
                assert!(
                    (t - want).abs() < tolerance,
                    "{convection:?} wet {wet} {scheme:?}: {t} K vs {want} K"
                );
            }
        }
        assert!(
            want > 310.0,
            "{convection:?}: the sun warms the plate: {want}"
        );
    }
}

/// A day of sinusoidal air and a half-sine sun on a rendered concrete wall ventilated
/// behind, wet and under DOE-2: after spin-up, the energy that entered and left over a day
/// equals the change of `Σ C_i T_i` to 1e-6 of the day's absorbed energy, and day n+1
/// repeats day n.
#[test]
fn a_periodic_day_closes_and_repeats() {
    let wall = Wall::new(
        &props(
            vec![render(0.005), concrete(0.1)],
            BackBoundary::Convective {
                h_w_m2_k: 3.0,
                air: BackAir::Outdoor,
            },
        ),
        &Discretisation::graded(5e-4, 1.3, 0.01),
    )
    .unwrap();
    let surf = surface(0.7, 0.92, 0.3, Convection::Doe2);
    let facet = Facet {
        wall: &wall,
        surface: &surf,
        orientation: Orientation {
            cos_tilt: 0.5,
            windward: false,
        },
    };
    let loads = |t: f64| {
        let phase = TAU * t / DAY_S;
        Loads {
            shortwave_w_m2: (800.0 * (phase - 0.5 * PI).sin()).max(0.0),
            longwave_w_m2: 330.0 + 20.0 * (phase - 2.0).sin(),
            air_temperature_k: 293.0 + 5.0 * (phase - 2.2).sin(),
            dew_point_k: 283.0,
            pressure_pa: 101_325.0,
            wind_speed_m_s: 2.0 + phase.cos(),
            source_w_m2: 0.0,
        }
    };
    for scheme in [Scheme::BackwardEuler, Scheme::CrankNicolson, Scheme::TrBdf2] {
        let dt_s = 300.0;
        let per_day = (DAY_S / dt_s) as usize;
        let mut scratch = Scratch::new();
        let mut temps = wall.uniform_state(290.0);
        let mut days: Vec<Vec<Vec<f64>>> = Vec::new();
        for day in 0..12 {
            // Crank–Nicolson does not damp the fast modes the uniform start excites in the
            // render's thin cells; spin up by Backward Euler, which does, then switch.
            let time_step = TimeStep {
                dt_s,
                scheme: if day < 6 {
                    Scheme::BackwardEuler
                } else {
                    scheme
                },
            };
            let stored_before = wall.stored_energy_j_m2(&temps);
            let mut total = StepFluxes::default();
            let mut history = Vec::with_capacity(per_day);
            for n in 0..per_day {
                let t = (day * per_day + n) as f64 * dt_s;
                let f = step(
                    &facet,
                    &mut temps,
                    &loads(t),
                    &loads(t + dt_s),
                    time_step,
                    &mut scratch,
                )
                .unwrap();
                total += f;
                history.push(temps.clone());
            }
            let absorbed = total.absorbed_shortwave_j_m2 + total.absorbed_longwave_j_m2;
            let flows = total.absorbed_shortwave_j_m2 + total.absorbed_longwave_j_m2
                - total.emitted_j_m2
                - total.convected_j_m2
                - total.latent_j_m2
                + total.back_j_m2
                + total.source_j_m2;
            let stored_change = wall.stored_energy_j_m2(&temps) - stored_before;
            assert!(
                // The floor is 1e-6; what remains is round-off.
                (stored_change - flows).abs() < 1e-9 * absorbed,
                "{scheme:?} day {day}: stored {stored_change} J/m², flows {flows} J/m², \
                 absorbed {absorbed} J/m²"
            );
            assert!(total.latent_j_m2 > 0.0, "a wet wall in sun evaporates");
            days.push(history);
        }
        let (last, before) = (&days[days.len() - 1], &days[days.len() - 2]);
        let mut worst: f64 = 0.0;
        for (a, b) in last.iter().zip(before) {
            for (x, y) in a.iter().zip(b) {
                worst = worst.max((x - y).abs());
            }
        }
        assert!(
            worst < 1e-5,
            "{scheme:?}: day n+1 departs from day n by {worst} K"
        );
        // The surface swings through the day: sun by day, cooler by night.
        let surface: Vec<f64> = last.iter().map(|t| t[0]).collect();
        let (lo, hi) = surface
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
                (lo.min(t), hi.max(t))
            });
        assert!(
            hi - lo > 5.0,
            "{scheme:?}: a diurnal swing of {} K",
            hi - lo
        );
    }
}
