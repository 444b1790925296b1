//! The atmosphere models against hand computations, the thesis equations they implement,
//! and the edges: zero-length, horizontal and grazing paths, ground and space, bad tables.

use approx::assert_relative_eq;
use irsig_atmosphere::{
    AtmosphereErrorKind, AtmosphereModel, ModelKind, PathTerms, builtin, critical_nadir_angle_deg,
};
use proptest::prelude::*;

fn model(kind: ModelKind) -> AtmosphereModel {
    AtmosphereModel::new(&builtin("us-std-1976").unwrap(), kind).unwrap()
}

#[test]
fn critical_angle_matches_the_tangent_construction_by_hand() {
    // Figure 7: the tangent from a sensor h above a sphere of radius R meets the vertical
    // at asin(R/(R+h)). By hand with R = 6371.23 km: h = 1 km gives a tangent length
    // sqrt(2Rh + h²) = sqrt(12743.46) = 112.8869 km, angle at the centre
    // atan(112.8869/6371.23) = atan(0.0177182) = 0.0177164 rad = 1.01507°, so 88.98493°;
    // h = 10 km: sqrt(127524.6) = 357.1059 km, atan(0.0560498) = 0.0559912 rad = 3.20806°,
    // so 86.79194°.
    assert_relative_eq!(critical_nadir_angle_deg(1000.0), 88.98493, epsilon = 2e-5);
    assert_relative_eq!(critical_nadir_angle_deg(10_000.0), 86.79194, epsilon = 2e-5);
    assert_relative_eq!(critical_nadir_angle_deg(0.0), 90.0);
    assert_relative_eq!(critical_nadir_angle_deg(-5.0), 90.0);
    assert!(critical_nadir_angle_deg(4.77) < 90.0 && critical_nadir_angle_deg(4.77) > 89.9);
}

#[test]
fn thesis_model_is_eq_10_and_11_at_the_fit_altitude() {
    // US Std 1976 at 1 km: τ(0) = 0.819461, L_u(0) = 7.387818 W m⁻² sr⁻¹;
    // .cor 1.10293990 −0.11240644 0.00703145. At 60° (sec = 2):
    // c = 1.10293990 − 0.22481288 + 0.02812580 = 0.90625282, τ = 0.742639, L_u = 14.775636.
    let p = model(ModelKind::Thesis).path(1000.0, 0.0, 2000.0);
    assert_relative_eq!(p.transmission, 0.819461 * 0.90625282, max_relative = 1e-9);
    assert_relative_eq!(p.path_radiance_w_m2_sr, 7.387818 * 2.0, max_relative = 1e-9);
}

#[test]
fn layered_model_reproduces_the_atm_table_at_nadir() {
    let atm = builtin("us-std-1976").unwrap();
    let m = model(ModelKind::Layered);
    for l in &atm.levels {
        let p = m.path(l.altitude_m, 0.0, l.altitude_m);
        assert_relative_eq!(p.transmission, l.transmission, max_relative = 1e-12);
        assert_relative_eq!(
            p.path_radiance_w_m2_sr,
            l.path_radiance_w_m2_sr,
            max_relative = 1e-9
        );
    }
}

#[test]
fn curve_of_growth_exponent_is_fitted_between_strong_line_and_beer() {
    let p = model(ModelKind::Layered)
        .curve_of_growth_exponent()
        .unwrap();
    // From the README numbers: at 80° from 1 km −ln τ is 0.5748 against 0.1991 at nadir,
    // ln(2.887)/ln(sec 80° = 5.759) = 0.606; the 5–80° fit gives a little less.
    assert!((0.55..0.62).contains(&p), "{p}");
}

#[test]
fn the_table_model_returns_lowtran_at_every_node_down_to_2_m() {
    // LOWTRAN's slant paths end 1 m above the ground (`slant.ground_m`). On every node, a
    // path from the node's altitude to 1 m at the node's angle must come back as LOWTRAN's
    // own numbers. (With the layered reference taken to 0 m instead, the 2 m row erred by
    // half its optical depth, the 5 m row by a fifth.)
    for name in ["us-std-1976", "midlat-winter"] {
        let atm = builtin(name).unwrap();
        let slant = atm.slant.clone().unwrap();
        assert_eq!(slant.ground_m, Some(1.0), "{name}");
        let table = AtmosphereModel::new(&atm, ModelKind::Table).unwrap();
        for (i, &h) in slant.altitude_m.iter().enumerate() {
            for (j, &a) in slant.nadir_deg.iter().enumerate() {
                let range = (h - 1.0) / a.to_radians().cos();
                let p = table.path(h, 1.0, range);
                let (tau, lu) = (slant.transmission[i][j], slant.path_radiance_w_m2_sr[i][j]);
                assert_relative_eq!(p.transmission, tau, max_relative = 1e-9);
                assert_relative_eq!(p.path_radiance_w_m2_sr, lu, max_relative = 1e-9);
            }
        }
        // To the ground itself the path has one more metre of air: less τ, more L_u.
        let to_1m = table.path(5.0, 1.0, 4.0);
        let to_ground = table.path(5.0, 0.0, 5.0);
        assert!(to_ground.transmission < to_1m.transmission, "{name}");
        assert!(to_ground.path_radiance_w_m2_sr > to_1m.path_radiance_w_m2_sr);
    }
}

#[test]
fn slant_tables_ending_at_or_above_their_lowest_altitude_are_refused() {
    let mut atm = builtin("us-std-1976").unwrap();
    let slant = atm.slant.as_mut().unwrap();
    slant.ground_m = Some(slant.altitude_m[0]);
    let e = atm.validate().unwrap_err().to_string();
    assert!(e.contains("slant.ground_m"), "{e}");
    atm.slant.as_mut().unwrap().ground_m = Some(f64::NAN);
    assert!(atm.validate().is_err());
}

#[test]
fn a_short_oblique_path_near_the_ground_is_almost_clear() {
    // The validation experiment's camera: 4.77 m above and 8.61 m from its target.
    // LOWTRAN7 gives τ = 0.9857, L = 0.60 W m⁻² sr⁻¹ for 10 m horizontal at 5 m.
    for kind in [ModelKind::Thesis, ModelKind::Layered, ModelKind::Table] {
        let p = model(kind).path(4.77, 0.0, 8.61);
        assert!(
            p.transmission > 0.98 && p.transmission < 1.0,
            "{kind}: {p:?}"
        );
        assert!(
            p.path_radiance_w_m2_sr > 0.1 && p.path_radiance_w_m2_sr < 1.0,
            "{kind}: {p:?}"
        );
    }
}

#[test]
fn horizontal_paths_are_finite_and_continuous_with_slightly_tilted_ones() {
    for kind in ModelKind::ALL {
        let m = model(kind);
        let flat = m.path(5.0, 5.0, 1000.0);
        let tilted = m.path(5.0, 4.99, 1000.0);
        assert!(flat.transmission.is_finite() && flat.path_radiance_w_m2_sr.is_finite());
        assert!(
            (flat.transmission - tilted.transmission).abs() < 2e-3,
            "{kind}: {flat:?} {tilted:?}"
        );
        assert!(
            (flat.path_radiance_w_m2_sr - tilted.path_radiance_w_m2_sr).abs() < 0.05,
            "{kind}"
        );
    }
}

#[test]
fn longer_paths_transmit_less_and_emit_more() {
    for kind in [ModelKind::Layered, ModelKind::Table] {
        let m = model(kind);
        let mut last = PathTerms::VACUUM;
        for range in [1.0, 10.0, 100.0, 1000.0, 10_000.0, 100_000.0] {
            let p = m.path(10.0, 10.0, range);
            assert!(p.transmission < last.transmission, "{kind} {range}");
            assert!(
                p.path_radiance_w_m2_sr > last.path_radiance_w_m2_sr,
                "{kind} {range}"
            );
            last = p;
        }
    }
}

#[test]
fn zero_length_paths_and_the_none_model_are_vacuum() {
    for kind in ModelKind::ALL {
        assert_eq!(model(kind).path(100.0, 100.0, 0.0), PathTerms::VACUUM);
    }
    let none = model(ModelKind::None);
    assert_eq!(none.path(1000.0, 0.0, 5000.0), PathTerms::VACUUM);
    assert!(none.sky_radiance(0.0, 30.0).abs() < f64::MIN_POSITIVE);
    assert!(none.sky_hemispheric(0.0).radiance_w_m2_sr.abs() < f64::MIN_POSITIVE);
}

#[test]
fn paths_are_reciprocal_in_transmission() {
    for kind in [ModelKind::Layered, ModelKind::Table, ModelKind::Thesis] {
        let m = model(kind);
        let down = m.path(1000.0, 200.0, 1500.0);
        let up = m.path(200.0, 1000.0, 1500.0);
        assert_relative_eq!(down.transmission, up.transmission, max_relative = 1e-12);
    }
}

#[test]
fn sky_from_the_ground_is_the_dwr_interpolated() {
    // .dwr rows 55, 60, 65 and 70°: 1.521849e-03, 1.622407e-03, 1.752845e-03 and
    // 1.928773e-03 W cm⁻² sr⁻¹. Between 60 and 65° the monotone cubic's midpoint is the
    // chord's less h/8 times the difference of the node slopes, each the harmonic mean of
    // its neighbouring secants (equal steps): 16.8310, 0.045 below the chord (16.8763).
    let l = [15.21849, 16.22407, 17.52845, 19.28773];
    let secant: Vec<f64> = l.windows(2).map(|w| (w[1] - w[0]) / 5.0).collect();
    let slope = |k: usize| 2.0 / (1.0 / secant[k - 1] + 1.0 / secant[k]);
    let mid = 0.5 * (l[1] + l[2]) + 5.0 / 8.0 * (slope(1) - slope(2));
    assert!((mid - 16.8310).abs() < 1e-4, "{mid}");
    for kind in [ModelKind::Thesis, ModelKind::Layered] {
        let m = model(kind);
        assert_relative_eq!(m.sky_radiance(0.0, 60.0), 16.22407, max_relative = 1e-9);
        assert_relative_eq!(m.sky_radiance(0.0, 62.5), mid, max_relative = 1e-9);
        assert_relative_eq!(m.sky_radiance(0.0, 95.0), 43.94162, max_relative = 1e-9);
    }
}

#[test]
fn sky_above_83_degrees_follows_the_appendix_e_quadratic_and_stays_sane() {
    for kind in [ModelKind::Layered, ModelKind::Table] {
        let m = model(kind);
        let view = m.sky_view(3000.0);
        let mut last = 0.0;
        for z in [0.0, 30.0, 60.0, 83.0, 85.0, 88.0, 90.0, 91.5] {
            let l = view.radiance(z);
            assert!(l >= last && l < 60.0, "{kind} {z}: {l}");
            last = l;
            assert_relative_eq!(
                l,
                m.sky_radiance(3000.0, z),
                max_relative = 2e-3,
                epsilon = 1e-3
            );
        }
    }
}

#[test]
fn hemispheric_sky_agrees_with_eq_5_and_warns_when_it_does_not() {
    let m = model(ModelKind::Layered);
    let h = m.sky_hemispheric(0.0);
    // README: L_d,hemi = 1.513059e-03 W cm⁻² sr⁻¹ by 32-point Gauss–Legendre in LOWTRAN.
    assert_relative_eq!(h.radiance_w_m2_sr, 15.13059, max_relative = 1e-12);
    assert!((h.computed_w_m2_sr / 15.13059 - 1.0).abs() < 0.01, "{h:?}");
    assert!(h.warning.is_none());
    let mut atm = builtin("us-std-1976").unwrap();
    atm.sky_hemispheric_w_m2_sr = Some(20.0);
    let h = AtmosphereModel::new(&atm, ModelKind::Layered)
        .unwrap()
        .sky_hemispheric(0.0);
    assert!(
        h.warning
            .is_some_and(|w| w.contains("differ") && w.contains(" %"))
    );
    // A given 0: the difference is said in radiance, not in infinitely many per cent.
    atm.sky_hemispheric_w_m2_sr = Some(0.0);
    let w = AtmosphereModel::new(&atm, ModelKind::Layered)
        .unwrap()
        .sky_hemispheric(0.0)
        .warning
        .expect("a warning");
    assert!(
        w.contains("W m^-2 sr^-1 (the given value is 0)") && !w.contains('%'),
        "{w}"
    );
    atm.sky_hemispheric_w_m2_sr = None;
    let h = AtmosphereModel::new(&atm, ModelKind::Layered)
        .unwrap()
        .sky_hemispheric(0.0);
    assert_relative_eq!(h.radiance_w_m2_sr, h.computed_w_m2_sr);
    // Above the ground there is less air overhead: less sky.
    assert!(
        model(ModelKind::Table)
            .sky_hemispheric(3000.0)
            .radiance_w_m2_sr
            < 15.13059 * 0.6
    );
}

#[test]
fn models_refuse_atmospheres_missing_what_they_need() {
    let mut atm = builtin("us-std-1976").unwrap();
    atm.slant = None;
    atm.transmission_correction = None;
    for kind in [ModelKind::Table, ModelKind::Thesis] {
        let e = AtmosphereModel::new(&atm, kind).unwrap_err();
        assert!(
            matches!(e.kind, AtmosphereErrorKind::MissingTable { .. }),
            "{e}"
        );
    }
    AtmosphereModel::new(&atm, ModelKind::Layered).unwrap();
    atm.levels[3].transmission = 0.99;
    let e = AtmosphereModel::new(&atm, ModelKind::Layered).unwrap_err();
    assert!(
        matches!(
            e.kind,
            AtmosphereErrorKind::TransmissionIncreases { level: 3, .. }
        ),
        "{e}"
    );
    atm.levels[3].transmission = f64::NAN;
    assert!(matches!(
        AtmosphereModel::new(&atm, ModelKind::Layered)
            .unwrap_err()
            .kind,
        AtmosphereErrorKind::Invalid(_)
    ));
    assert!("lowtran".parse::<ModelKind>().is_err());
    assert_eq!("table".parse::<ModelKind>().unwrap(), ModelKind::Table);
}

proptest! {
    #[test]
    fn finite_inputs_give_bounded_outputs(s in -100.0..20_000.0f64, t in -100.0..20_000.0f64, r in 0.0..1e6f64, z in -10.0..200.0f64, k in 0usize..4) {
        let m = model(ModelKind::ALL[k]);
        let p = m.path(s, t, r);
        prop_assert!((0.0..=1.0).contains(&p.transmission), "{:?}", p);
        prop_assert!(p.path_radiance_w_m2_sr >= 0.0 && p.path_radiance_w_m2_sr < 100.0, "{:?}", p);
        let l = m.sky_radiance(s, z);
        prop_assert!(l.is_finite() && (0.0..100.0).contains(&l), "{}", l);
    }
}

#[test]
fn non_finite_inputs_give_nan_not_a_panic() {
    let m = model(ModelKind::Table);
    assert!(m.path(f64::NAN, 0.0, 1.0).transmission.is_nan());
    assert!(m.path(1.0, 0.0, f64::INFINITY).transmission.is_nan());
    assert!(m.sky_radiance(0.0, f64::NAN).is_nan());
}
