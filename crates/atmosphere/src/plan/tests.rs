use super::*;

#[test]
fn gauss_legendre_integrates_polynomials_on_the_unit_interval() {
    let gl = gauss_legendre_01(32);
    let w: f64 = gl.iter().map(|g| g.1).sum();
    assert!((w - 1.0).abs() < 1e-14);
    let x5: f64 = gl.iter().map(|g| g.1 * g.0.powi(5)).sum();
    assert!((x5 - 1.0 / 6.0).abs() < 1e-14);
}

#[test]
fn a_plan_covers_its_observers_and_the_builtin_nodes() {
    let p = make_plan("t", PlanModel::Standard(1), &[5.0, 5.2, 450.0]).unwrap();
    p.validate().unwrap();
    assert_eq!(p.observers_m, [5.0, 450.0]);
    assert!(p.slant_altitude_m.contains(&450.0) && p.slant_altitude_m.contains(&3000.0));
    assert!(!p.slant_altitude_m.contains(&5000.0));
    assert_eq!(p.slant_nadir_deg.last(), Some(&88.0));
    // The hemispheric weights integrate 2 cos θ over cos θ: a uniform sky of 1 gives 1.
    let w: f64 = p.hemispheric.iter().map(|h| h.1).sum();
    assert!((w - 1.0).abs() < 1e-4, "{w}");
    let all = paths(&p);
    // Shared nodes run once: the 1 km nadir path is a level, a .cor path and a slant node.
    let n1000 = all
            .iter()
            .filter(|q| matches!(q, Path::Down { altitude_m, nadir_deg } if *altitude_m == 1000.0 && *nadir_deg == 0.0))
            .count();
    assert_eq!(n1000, 1);
    let high = make_plan("t", PlanModel::Standard(6), &[9000.0]).unwrap();
    assert!(high.slant_nadir_deg.last().unwrap() < &88.0);
    assert!(make_plan("t", PlanModel::Standard(6), &[1.0]).is_err());
}

#[test]
fn several_suns_run_the_beam_at_every_zenith_and_altitude_and_no_scattering() {
    let night = make_plan("t", PlanModel::Standard(6), &[5.0]).unwrap();
    let mut one = night.clone();
    add_sun(&mut one, 30.0, 172, false).unwrap();
    let mut day = night.clone();
    // Unsorted, a repeat once rounded: three suns.
    add_suns(&mut day, &[60.0, 30.0, 45.0, 30.0002], 172, false).unwrap();
    day.validate().unwrap();
    let sun = day.sun.as_ref().unwrap();
    assert_eq!(sun.zeniths_deg(), [30.0, 45.0, 60.0]);
    let (before, after) = (paths(&night), paths(&day));
    assert_eq!(after[..before.len()], before[..]);
    assert_eq!(after.len(), before.len() + 3 * sun.altitude_m.len());
    for z in [30.0, 45.0, 60.0] {
        let runs = after
            .iter()
            .filter(|p| matches!(p, Path::Sun { zenith_deg, .. } if *zenith_deg == z))
            .count();
        assert_eq!(runs, sun.altitude_m.len(), "{z}");
    }
    // The beams' run numbers, [sun][altitude].
    let runs = sun_runs(&day);
    assert_eq!(runs.len(), 3 * sun.altitude_m.len());
    for (k, &i) in runs.iter().enumerate() {
        let (z, a) = (
            [30.0, 45.0, 60.0][k / sun.altitude_m.len()],
            sun.altitude_m[k % sun.altitude_m.len()],
        );
        assert!(
            matches!(after[i], Path::Sun { zenith_deg, altitude_m, .. } if zenith_deg == z && altitude_m == a),
            "{k}: {:?}",
            after[i]
        );
    }
    assert!(sun_runs(&night).is_empty());
    // One sun plans as it did: the same runs as `add_sun`'s.
    let mut single = night.clone();
    add_suns(&mut single, &[30.0], 172, false).unwrap();
    assert_eq!(single, one);
    assert!(single.sun.as_ref().unwrap().further_zenith_deg.is_empty());
    // No sun, or one at the horizon, is none.
    let mut p = night.clone();
    assert!(add_suns(&mut p, &[], 172, false).is_err());
    assert!(add_suns(&mut p, &[30.0, 89.9999], 172, false).is_err());
    assert!(add_suns(&mut p, &[f64::NAN], 172, false).is_err());
    assert!(p.sun.is_none());
}

#[test]
fn scattered_sunlight_is_refused_for_a_sun_past_its_lowest_and_the_beam_is_not() {
    let night = make_plan("t", PlanModel::Standard(6), &[5.0]).unwrap();
    let mut p = night.clone();
    let e = add_suns(&mut p, &[30.0, 88.5], 172, true).unwrap_err();
    assert!(e.to_string().contains("a sun at 88.5 deg"), "{e}");
    assert!(p.sun.is_none(), "nothing planned");
    // 88° itself is the last row the measurement ran; the beam alone goes lower.
    add_suns(&mut p, &[30.0, 88.0], 172, true).unwrap();
    let mut beam = night.clone();
    add_suns(&mut beam, &[30.0, 88.5, 89.999], 172, false).unwrap();
    // One sun alike (LOWTRAN7 left a sky path of a lone sun at 88.5° unrun too), naming
    // the remedy for one sun; its beam alone goes lower.
    let mut one = night.clone();
    let e = add_sun(&mut one, 88.5, 172, true).unwrap_err().to_string();
    assert!(
        e.contains("a sun at 88.5 deg") && e.contains("a higher sun"),
        "{e}"
    );
    assert!(one.sun.is_none(), "nothing planned");
    add_sun(&mut one, 88.0, 172, true).unwrap();
    let mut beam = night;
    add_sun(&mut beam, 89.5, 172, false).unwrap();
}

#[test]
fn several_suns_with_scattering_run_every_sunlit_path_once_per_sun() {
    let night = make_plan("t", PlanModel::Standard(6), &[5.0]).unwrap();
    let mut one = night.clone();
    add_sun(&mut one, 30.0, 172, true).unwrap();
    let mut day = night.clone();
    add_suns(&mut day, &[60.0, 30.0, 45.0], 172, true).unwrap();
    day.validate().unwrap();
    let sun = day.sun.as_ref().unwrap();
    let (single, all) = (paths(&one), paths(&day));
    // Per sun: its beam at each altitude, and each slant and sky path at each azimuth.
    let na = RELATIVE_AZIMUTH_DEG.len();
    let sunlit = (day.slant_altitude_m.len() * day.slant_nadir_deg.len()
        + sun.altitude_m.len() * day.sky_zenith_deg.len())
        * na;
    assert_eq!(
        sunlit,
        single.len() - paths(&night).len() - sun.altitude_m.len()
    );
    // And once, the phase function at each of the sun's altitudes: a lone sun has none.
    let phase = sun.altitude_m.len() * SCATTERING_DEG.len();
    assert_eq!(
        all.len(),
        paths(&night).len() + 3 * (sun.altitude_m.len() + sunlit) + phase
    );
    assert!(!single.iter().any(|p| matches!(p, Path::Phase { .. })));
    for z in [30.0, 45.0, 60.0] {
        let lit = all
            .iter()
            .filter(|p| {
                matches!(p, Path::DownSunlit { sun_zenith_deg, .. }
                        | Path::UpSunlit { sun_zenith_deg, .. } if *sun_zenith_deg == z)
            })
            .count();
        assert_eq!(lit, sunlit, "{z}");
    }
    // The first sun's sunlit paths are the one-sun plan's, in its order.
    let first_lit = |ps: &[Path]| -> Vec<Path> {
        ps.iter()
            .copied()
            .filter(|p| {
                matches!(p, Path::DownSunlit { sun_zenith_deg, .. }
                        | Path::UpSunlit { sun_zenith_deg, .. } if *sun_zenith_deg == 30.0)
            })
            .collect()
    };
    assert_eq!(first_lit(&all), first_lit(&single));
    // Each sun's deck scatters its own sun (card 3A2's PARM2).
    let lit45 = all
        .iter()
        .find(|p| matches!(p, Path::UpSunlit { sun_zenith_deg, .. } if *sun_zenith_deg == 45.0))
        .unwrap();
    let d = deck(&day, lit45).unwrap();
    let Step::Full(c) = &d.steps[0] else {
        panic!("a full deck")
    };
    assert_eq!(c.geometry.scattering.as_ref().unwrap().card3a2[1], 45.0);
    // The phase function's runs come last, each a slab of 100 m above its altitude lit
    // by a sun of their own at 45 deg: on the sun (a line of sight up at 45 deg toward
    // its azimuth) and straight back (down at nadir 45 deg away from it).
    let phases: Vec<&Path> = all
        .iter()
        .filter(|p| matches!(p, Path::Phase { .. }))
        .collect();
    assert_eq!(phases.len(), phase);
    assert!(matches!(all[all.len() - phase], Path::Phase { .. }));
    let low = sun.altitude_m[0].max(day.path_end_m);
    for (theta, h1, h2, angle, azimuth) in [
        (0.0, low, low + 100.0, 45.0, 0.0),
        (90.0, low, low + 100.0, 45.0, 180.0),
        (180.0, low + 100.0, low, 135.0, 180.0),
    ] {
        let p = Path::Phase {
            altitude_m: sun.altitude_m[0],
            scattering_deg: theta,
        };
        assert!(phases.contains(&&p), "{p:?}");
        let d = deck(&day, &p).unwrap();
        let Step::Full(c) = &d.steps[0] else {
            panic!("a full deck")
        };
        assert_eq!(c.card1.iemsct, 2, "{theta}");
        let Card3::Path {
            h1_km,
            h2_km,
            angle_deg,
            ..
        } = c.geometry.card3
        else {
            panic!("{theta}: {:?}", c.geometry.card3)
        };
        assert_eq!(
            (h1_km, h2_km, angle_deg),
            (h1 / 1000.0, h2 / 1000.0, angle),
            "{theta}"
        );
        let sc = c.geometry.scattering.as_ref().unwrap();
        assert_eq!((sc.card3a2[0], sc.card3a2[1]), (azimuth, 45.0), "{theta}");
    }
    // A slab table holds one sun's scattered sunlight: slabs beside several are refused,
    // either way round.
    let mut slabbed = day.clone();
    assert!(add_slabs(&mut slabbed, 20.0).is_err());
    assert_eq!(slabbed, day);
    let mut first_slabs = night.clone();
    add_slabs(&mut first_slabs, 20.0).unwrap();
    let e = add_suns(&mut first_slabs, &[30.0, 45.0], 172, true).unwrap_err();
    assert!(e.to_string().contains("slab"), "{e}");
    add_suns(&mut first_slabs, &[30.0, 45.0], 172, false).unwrap();
}

#[test]
fn a_days_rows_are_its_moments_and_the_grid_between_them() {
    // Moments at 31.2, 58.9, 64.6 and 88.4 deg: the grid's 35-60, 70-80, 82-88 between
    // them; 65 is within 0.5 deg of 64.6 and left out, 88.5 is past the last moment.
    let rows = day_sun_rows(&[58.9, 31.2, 88.4, 64.6, 31.2004]);
    let want = [
        31.2, 35.0, 40.0, 45.0, 50.0, 55.0, 58.9, 60.0, 64.6, 70.0, 75.0, 80.0, 82.0, 84.0, 86.0,
        87.0, 87.5, 88.0, 88.4,
    ];
    assert_eq!(rows, want);
    // Every step within the grid's at its upper end.
    for w in rows.windows(2) {
        let limit = if w[1] <= 80.0 {
            6.0
        } else if w[1] <= 86.0 {
            2.4
        } else if w[1] <= 87.0 {
            1.2
        } else {
            0.6
        };
        assert!(w[1] - w[0] <= limit, "{w:?}");
    }
    // A morning's and an evening's sun 0.035 deg apart near 82 deg (a step of 2): one
    // row; near the zenith, 0.17 deg apart (a step of 5), both.
    assert_eq!(day_sun_rows(&[82.298, 82.333, 84.0]), [82.298, 84.0]);
    assert_eq!(day_sun_rows(&[82.298, 82.333]), [82.333]);
    assert_eq!(day_sun_rows(&[19.644, 19.814]), [19.644, 19.814]);
    assert_eq!(day_sun_rows(&[42.0]), [42.0]);
    assert!(day_sun_rows(&[]).is_empty());
    assert_eq!(day_sun_rows(&[0.0, 10.0]), [0.0, 5.0, 10.0]);
}

#[test]
fn a_sun_adds_one_direct_solar_run_per_sky_altitude_after_the_others() {
    let night = make_plan("t", PlanModel::Standard(6), &[5.0]).unwrap();
    let mut day = night.clone();
    add_sun(&mut day, 30.00004, 172, true).unwrap();
    day.validate().unwrap();
    let sun = day.sun.as_ref().unwrap();
    assert_eq!(sun.zenith_deg, 30.0);
    let mut rows = day.sky_altitude_m.clone();
    rows.extend(DAY_SKY_ALTITUDE_M);
    rows.sort_by(f64::total_cmp);
    assert_eq!(sun.altitude_m, rows);
    let (before, after) = (paths(&night), paths(&day));
    // The night's runs keep their numbers; the sun's follow, lowest first.
    assert_eq!(after[..before.len()], before[..]);
    let slant = day.slant_altitude_m.len() * day.slant_nadir_deg.len();
    let sky = sun.altitude_m.len() * day.sky_zenith_deg.len();
    assert_eq!(
        after.len(),
        before.len() + sun.altitude_m.len() + (slant + sky) * RELATIVE_AZIMUTH_DEG.len()
    );
    // Each sunlit path is a thermal path's deck in IEMSCT 2 with its azimuth and the
    // sun on cards 3A1-3A2.
    let sunlit = after[before.len() + sun.altitude_m.len() + 1];
    let Path::DownSunlit {
        altitude_m,
        nadir_deg,
        azimuth_deg,
        ..
    } = sunlit
    else {
        panic!("{sunlit:?}")
    };
    assert_eq!(azimuth_deg, RELATIVE_AZIMUTH_DEG[1]);
    let lit = deck(&day, &sunlit).unwrap();
    let dark = deck(
        &day,
        &Path::Down {
            altitude_m,
            nadir_deg,
        },
    )
    .unwrap();
    let (Step::Full(l), Step::Full(d)) = (&lit.steps[0], &dark.steps[0]) else {
        panic!("full decks")
    };
    assert_eq!((l.card1.iemsct, d.card1.iemsct), (2, 1));
    assert_eq!(l.geometry.card3, d.geometry.card3);
    let sc = l.geometry.scattering.as_ref().unwrap();
    assert_eq!(sc.card3a1, [2, 2, 172, 0]);
    assert_eq!(sc.card3a2[..2], [RELATIVE_AZIMUTH_DEG[1], 30.0]);
    let text = irsig_formats::radtran::tape5::write(&lit).unwrap();
    let back = irsig_formats::radtran::tape5::parse("d", &text).unwrap();
    assert_eq!(irsig_formats::radtran::tape5::write(&back).unwrap(), text);
    assert_eq!(
        after[before.len()],
        Path::Sun {
            altitude_m: 0.0,
            zenith_deg: 30.0,
            day_of_year: 172
        }
    );
    let d = deck(&day, &after[before.len() + 1]).unwrap();
    let text = irsig_formats::radtran::tape5::write(&d).unwrap();
    let back = irsig_formats::radtran::tape5::parse("d", &text).unwrap();
    let c = &back.calculations()[0];
    assert_eq!((c.card1.itype, c.card1.iemsct), (3, 3), "{text}");
    assert_eq!(
        c.card3,
        Card3::DirectSolar {
            h1_km: day.sky_altitude_m[1] / 1000.0,
            h2_km: 0.0,
            angle_deg: 30.0,
            iday: 172,
            ro_km: 0.0,
            isourc: 0,
            anglem_deg: 0.0,
        }
    );
    for (z, d) in [
        (90.0, 172),
        (89.9996, 172),
        (f64::NAN, 172),
        (-0.5, 172),
        (30.0, 0),
        (30.0, 367),
    ] {
        let mut p = night.clone();
        assert!(add_sun(&mut p, z, d, true).is_err(), "{z} {d}");
        assert!(p.sun.is_none());
    }
}

#[test]
fn assemble_puts_the_suns_runs_in_the_solar_table() {
    let mut p = make_plan("t", PlanModel::Standard(6), &[5.0]).unwrap();
    add_sun(&mut p, 30.0, 172, true).unwrap();
    let nu = vec![2000.0, 2020.0];
    let all = paths(&p);
    let spectra: Vec<PathSpectra> = all
        .iter()
        .map(|q| match *q {
            Path::Sun { altitude_m, .. } => PathSpectra {
                wavenumber_per_cm: nu.clone(),
                transmission: vec![0.5 + altitude_m / 1e5, 0.25],
                radiance_w_m2_sr_per_cm: vec![],
                extraterrestrial_w_m2_per_cm: vec![0.0092, 0.0094],
                scattered_w_m2_sr_per_cm: vec![],
            },
            Path::DownSunlit { azimuth_deg, .. } | Path::UpSunlit { azimuth_deg, .. } => {
                PathSpectra {
                    wavenumber_per_cm: nu.clone(),
                    transmission: vec![0.9, 0.8],
                    radiance_w_m2_sr_per_cm: vec![0.01, 0.02],
                    extraterrestrial_w_m2_per_cm: vec![],
                    scattered_w_m2_sr_per_cm: vec![1e-4 * (1.0 + azimuth_deg), 0.0],
                }
            }
            _ => PathSpectra {
                wavenumber_per_cm: nu.clone(),
                transmission: vec![0.9, 0.8],
                radiance_w_m2_sr_per_cm: vec![0.01, 0.02],
                extraterrestrial_w_m2_per_cm: vec![],
                scattered_w_m2_sr_per_cm: vec![],
            },
        })
        .collect();
    let a = assemble(&p, &spectra, &|_| 288.0, 0.0, "test").unwrap();
    let s = a.solar.as_ref().unwrap();
    assert_eq!((s.zenith_deg, s.day_of_year), (30.0, 172));
    assert_eq!(s.altitude_m, p.sun.as_ref().unwrap().altitude_m);
    assert_eq!(s.extraterrestrial_w_m2_per_unit, [0.0092_f32, 0.0094]);
    // Row k is the run at altitude k.
    for (k, h) in s.altitude_m.iter().enumerate() {
        assert_eq!(s.transmission[2 * k], (0.5 + h / 1e5) as f32);
    }
    // The scattered tables, [altitude][angle][azimuth]: azimuth k's spectrum is its own.
    let na = s.relative_azimuth_deg.len();
    let sl = a.slant.as_ref().unwrap();
    assert_eq!(
        s.sky_scattered_w_m2_sr_per_unit.len(),
        s.altitude_m.len() * sl.sky_zenith_deg.len() * na * 2
    );
    for (k, az) in s.relative_azimuth_deg.iter().enumerate() {
        let want = (1e-4 * (1.0 + az)) as f32;
        assert_eq!(s.path_scattered_w_m2_sr_per_unit[2 * (na + k)], want);
        assert_eq!(s.sky_scattered_w_m2_sr_per_unit[2 * k], want);
    }
    // A thermal run where a solar one belongs, and runs of two days, are refused.
    let sun_last = all
        .iter()
        .rposition(|q| matches!(q, Path::Sun { .. }))
        .unwrap();
    let last = spectra.len() - 1;
    let mut thermal = spectra.clone();
    thermal[last].scattered_w_m2_sr_per_cm.clear();
    let e = assemble(&p, &thermal, &|_| 288.0, 0.0, "test").unwrap_err();
    assert!(e.to_string().contains(&format!("run {last}")), "{e}");
    let last = sun_last;
    let mut wrong = spectra.clone();
    wrong[last].extraterrestrial_w_m2_per_cm.clear();
    wrong[last].radiance_w_m2_sr_per_cm = vec![0.01, 0.02];
    let e = assemble(&p, &wrong, &|_| 288.0, 0.0, "test").unwrap_err();
    assert!(e.to_string().contains(&format!("run {last}")), "{e}");
    let mut two_days = spectra;
    two_days[last].extraterrestrial_w_m2_per_cm = vec![0.0095, 0.0094];
    let e = assemble(&p, &two_days, &|_| 288.0, 0.0, "test").unwrap_err();
    assert!(e.to_string().contains("one day"), "{e}");
}

#[test]
fn slabs_follow_every_other_run_and_assemble_per_observer() {
    let mut p = make_plan("t", PlanModel::Standard(6), &[150.0, 650.0]).unwrap();
    add_sun(&mut p, 30.0, 172, true).unwrap();
    let before = paths(&p);
    add_slabs(&mut p, 800.0).unwrap();
    let slabs = p.slabs.clone().unwrap();
    assert_eq!(slabs.target_m[..5], [2.0, 5.0, 10.0, 25.0, 50.0]);
    assert_eq!(slabs.target_m.last(), Some(&800.0));
    let after = paths(&p);
    // The runs without slabs keep their numbers; each observer's slabs, thermal and at
    // each azimuth, follow.
    assert_eq!(after[..before.len()], before[..]);
    let na = RELATIVE_AZIMUTH_DEG.len();
    let runs = slabs.runs_of(150.0) + slabs.runs_of(650.0);
    assert_eq!(after.len(), before.len() + runs * (1 + na));
    // In key order: observer, target, zenith angle (nadir 80 is zenith 100).
    let first = after[before.len()];
    assert_eq!(
        first,
        Path::Slab {
            observer_m: 150.0,
            target_m: 2.0,
            zenith_deg: 100.0,
        }
    );
    let d = deck(&p, &first).unwrap();
    let c = &d.calculations()[0];
    assert_eq!((c.card1.itype, c.card1.iemsct), (2, 1));
    let Card3::Path {
        h1_km,
        h2_km,
        angle_deg,
        ..
    } = c.card3
    else {
        panic!("{:?}", c.card3)
    };
    assert_eq!((h1_km, h2_km, angle_deg), (0.15, 0.002, 100.0));
    // Assembled: per observer, the observer's own row is τ = 1 and no radiance.
    let nu = vec![2000.0, 2020.0];
    let spectra: Vec<PathSpectra> = after
        .iter()
        .map(|q| PathSpectra {
            wavenumber_per_cm: nu.clone(),
            transmission: vec![0.9, 0.8],
            radiance_w_m2_sr_per_cm: match q {
                Path::Sun { .. } => vec![],
                _ => vec![0.01, 0.02],
            },
            extraterrestrial_w_m2_per_cm: match q {
                Path::Sun { .. } => vec![0.0092, 0.0094],
                _ => vec![],
            },
            scattered_w_m2_sr_per_cm: match q {
                Path::DownSunlit { .. } | Path::UpSunlit { .. } | Path::SlabSunlit { .. } => {
                    vec![1e-3, 2e-3]
                }
                _ => vec![],
            },
        })
        .collect();
    let a = assemble(&p, &spectra, &|_| 288.0, 0.0, "test").unwrap();
    assert_eq!(a.slabs.len(), 2);
    let s = &a.slabs[1];
    assert_eq!(s.observer_m, 650.0);
    let down = s.down.as_ref().unwrap();
    assert_eq!(down.target_m.last(), Some(&650.0));
    let rows = down.target_m.len() * down.angle_deg.len();
    let own = &down.transmission[2 * (rows - 1)..];
    assert_eq!(own, [1.0, 1.0]);
    assert_eq!(down.transmission[0], 0.9);
    assert_eq!(down.scattered_w_m2_sr_per_unit.len(), rows * na * 2);
    let up = s.up.as_ref().unwrap();
    assert_eq!(up.target_m, [650.0, 700.0, 750.0, 800.0]);
    assert_eq!(up.path_radiance_w_m2_sr_per_unit[..2], [0.0, 0.0]);
    // The binary form holds the slabs and reads back what it wrote.
    let bytes = irsig_formats::canonical::binary_spectral::encode(&a).unwrap();
    let back = irsig_formats::canonical::binary_spectral::decode("t", &bytes).unwrap();
    assert_eq!(back, a);
    // No observers, no slabs.
    let mut none = p.clone();
    none.observers_m.clear();
    assert!(add_slabs(&mut none, 800.0).is_err());
    assert!(add_slabs(&mut p, f64::NAN).is_err());
}

#[test]
fn decks_write_and_read_back() {
    let p = make_plan("t", PlanModel::Standard(1), &[5.0]).unwrap();
    for path in paths(&p).iter().take(40) {
        let d = deck(&p, path).unwrap();
        let text = irsig_formats::radtran::tape5::write(&d).unwrap();
        let back = irsig_formats::radtran::tape5::parse("d", &text).unwrap();
        assert_eq!(irsig_formats::radtran::tape5::write(&back).unwrap(), text);
        assert_eq!(back.calculations()[0].card3, d.calculations()[0].card3);
    }
}
