use super::*;

pub(crate) fn small() -> SpectralAtmosphere {
    SpectralAtmosphere {
        name: "t".into(),
        source: "test".into(),
        grid: SpectralGrid {
            axis: SpectralAxis::WavenumberPerCm,
            points: vec![710.0, 715.0, 720.0],
        },
        levels: vec![ProfileLevel {
            altitude_asl_m: 1000.0,
            temperature_k: 281.0,
            altitude_m: 1000.0,
        }],
        level_transmission: vec![0.1, 0.2, 0.3],
        level_path_radiance_w_m2_sr_per_unit: vec![0.1, 0.09, 0.08],
        transmission_correction: None,
        sky_zenith_deg: vec![0.0, 90.0],
        sky_radiance_w_m2_sr_per_unit: vec![0.1; 6],
        sky_hemispheric_w_m2_sr_per_unit: None,
        radiosonde: vec![],
        slant: None,
        solar: None,
        slabs: vec![],
    }
}

/// A slab table on 3 grid points at 2 angles: τ 0.9 and path radiance 0.01, but on the
/// observer's own row (`observer`), the path of no length, τ = 1 and no radiance.
fn slab_table(target_m: Vec<f64>, observer: usize) -> SpectralSlabTable {
    let values = |away: f32, own: f32| -> Vec<f32> {
        (0..target_m.len())
            .flat_map(|t| std::iter::repeat_n(if t == observer { own } else { away }, 6))
            .collect()
    };
    SpectralSlabTable {
        angle_deg: vec![10.0, 50.0],
        transmission: values(0.9, 1.0),
        path_radiance_w_m2_sr_per_unit: values(0.01, 0.0),
        scattered_w_m2_sr_per_unit: vec![],
        target_m,
    }
}

#[test]
fn a_slab_table_out_of_order_nan_or_of_a_wrong_length_is_refused_by_name() {
    let mut a = small();
    a.slabs = vec![SpectralSlab {
        observer_m: 600.0,
        down: Some(slab_table(vec![300.0, 550.0, 600.0], 2)),
        up: Some(slab_table(vec![600.0, 800.0], 0)),
    }];
    a.validate().unwrap();
    type Break = dyn Fn(&mut SpectralSlab);
    let cases: [(&Break, &str); 10] = [
        (
            &|s| s.down.as_mut().unwrap().target_m.swap(0, 1),
            "slabs[0].down.target_m[1]",
        ),
        (
            &|s| s.up.as_mut().unwrap().transmission[5] = f32::NAN,
            "slabs[0].up.transmission[1][2]",
        ),
        (
            &|s| {
                s.down
                    .as_mut()
                    .unwrap()
                    .path_radiance_w_m2_sr_per_unit
                    .pop();
            },
            "slabs[0].down.path_radiance_w_m2_sr_per_unit",
        ),
        (
            &|s| s.up.as_mut().unwrap().angle_deg = vec![50.0, 10.0],
            "slabs[0].up.angle_deg[1]",
        ),
        (
            &|s| s.up.as_mut().unwrap().target_m = vec![500.0, 800.0],
            "slabs[0].up.target_m[0]",
        ),
        (
            &|s| s.down.as_mut().unwrap().target_m = vec![300.0, 550.0, 590.0],
            "slabs[0].down.target_m",
        ),
        (
            // Scattered spectra in an atmosphere without the sun's azimuths.
            &|s| s.down.as_mut().unwrap().scattered_w_m2_sr_per_unit = vec![0.0; 18],
            "slabs[0].down.scattered_w_m2_sr_per_unit",
        ),
        // The observer's own row is the path of no length: τ = 1, no radiance. An
        // observer row with τ = 0.5 was accepted.
        (
            &|s| s.down.as_mut().unwrap().transmission[13] = 0.5,
            "slabs[0].down.transmission[4][1]",
        ),
        (
            &|s| s.up.as_mut().unwrap().transmission[0] = 0.999,
            "slabs[0].up.transmission[0][0]",
        ),
        (
            &|s| s.up.as_mut().unwrap().path_radiance_w_m2_sr_per_unit[5] = 1e-9,
            "slabs[0].up.path_radiance_w_m2_sr_per_unit[1][2]",
        ),
    ];
    for (break_it, path) in cases {
        let mut b = a.clone();
        break_it(&mut b.slabs[0]);
        let e = b.validate().unwrap_err();
        assert_eq!(e.path, path, "{e}");
    }
    let mut b = a.clone();
    b.slabs.push(SpectralSlab {
        observer_m: 100.0,
        ..a.slabs[0].clone()
    });
    assert_eq!(b.validate().unwrap_err().path, "slabs[1].observer_m");
}

#[test]
fn shapes_and_ranges_are_checked() {
    small().validate().unwrap();
    let mut a = small();
    a.level_transmission.push(0.5);
    assert_eq!(a.validate().unwrap_err().path, "level_transmission");
    let mut a = small();
    a.level_transmission[2] = 1.5;
    assert_eq!(a.validate().unwrap_err().path, "level_transmission[0][2]");
    let mut a = small();
    a.sky_radiance_w_m2_sr_per_unit[4] = f32::NAN;
    assert_eq!(
        a.validate().unwrap_err().path,
        "sky_radiance_w_m2_sr_per_unit[1][1]"
    );
    let mut a = small();
    a.grid.points[1] = 710.0;
    assert_eq!(a.validate().unwrap_err().path, "grid.points[1]");
    let mut a = small();
    a.grid.points.truncate(1);
    assert!(a.validate().is_err());
}

#[test]
fn the_solar_table_is_checked_like_the_others() {
    let sun = SpectralSolar {
        zenith_deg: 30.0,
        day_of_year: 172,
        altitude_m: vec![0.0, 300.0],
        extraterrestrial_w_m2_per_unit: vec![0.01, 0.011, 0.012],
        transmission: vec![0.5, 0.6, 0.7, 0.55, 0.65, 0.75],
        relative_azimuth_deg: Vec::new(),
        path_scattered_w_m2_sr_per_unit: Vec::new(),
        sky_scattered_w_m2_sr_per_unit: Vec::new(),
        further_suns: Vec::new(),
        apparent_zenith_deg: Vec::new(),
        phase: None,
    };
    let mut a = small();
    a.solar = Some(sun.clone());
    a.validate().unwrap();
    type Break = dyn Fn(&mut SpectralSolar);
    let cases: [(&Break, &str); 6] = [
        (&|s| s.zenith_deg = 90.0, "solar.zenith_deg"),
        (&|s| s.day_of_year = 0, "solar.day_of_year"),
        (&|s| s.altitude_m = vec![300.0, 0.0], "solar.altitude_m[1]"),
        (
            &|s| s.extraterrestrial_w_m2_per_unit[1] = -1.0,
            "solar.extraterrestrial_w_m2_per_unit[0][1]",
        ),
        (&|s| s.transmission[4] = 1.5, "solar.transmission[1][1]"),
        (
            &|s| s.transmission.pop().map(drop).unwrap_or(()),
            "solar.transmission",
        ),
    ];
    for (break_it, path) in cases {
        let mut s = sun.clone();
        break_it(&mut s);
        a.solar = Some(s);
        let e = a.validate().unwrap_err();
        assert_eq!(e.path, path, "{e}");
    }
    // Further suns: zeniths increasing above the first sun's and below 90, one
    // spectrum per altitude each.
    let mut day = sun.clone();
    day.further_suns = vec![
        SolarBeam {
            zenith_deg: 60.0,
            transmission: vec![0.25; 6],
            path_scattered_w_m2_sr_per_unit: Vec::new(),
            sky_scattered_w_m2_sr_per_unit: Vec::new(),
        },
        SolarBeam {
            zenith_deg: 89.999,
            transmission: vec![0.0; 6],
            path_scattered_w_m2_sr_per_unit: Vec::new(),
            sky_scattered_w_m2_sr_per_unit: Vec::new(),
        },
    ];
    a.solar = Some(day.clone());
    a.validate().unwrap();
    assert_eq!(day.zeniths_deg(), [30.0, 60.0, 89.999]);
    // The angles the beams ran at: one per sun and altitude, refraction lifting each
    // sun (at most its geometric angle), or none.
    let n = day.altitude_m.len();
    let mut lifted = day.clone();
    lifted.apparent_zenith_deg = [30.0, 59.973, 89.5]
        .iter()
        .flat_map(|&z| std::iter::repeat_n(z, n))
        .collect();
    a.solar = Some(lifted.clone());
    a.validate().unwrap();
    for (k, bad, path) in [
        (None, 0.0, "solar.apparent_zenith_deg"),
        (Some(n), 60.001, "solar.apparent_zenith_deg[2]"),
        (Some(0), -0.5, "solar.apparent_zenith_deg[0]"),
        (Some(2 * n), f64::NAN, "solar.apparent_zenith_deg[4]"),
    ] {
        let mut s = lifted.clone();
        match k {
            None => {
                s.apparent_zenith_deg.pop();
            }
            Some(k) => s.apparent_zenith_deg[k] = bad,
        }
        a.solar = Some(s);
        assert_eq!(a.validate().unwrap_err().path, path);
    }
    a.solar = Some(day.clone());
    assert_eq!(day.transmission_of(0), Some(&day.transmission[..]));
    assert_eq!(day.transmission_of(2), Some(&[0.0_f32; 6][..]));
    assert_eq!(day.transmission_of(3), None);
    let cases: [(&Break, &str); 6] = [
        (
            &|s| s.further_suns[0].zenith_deg = 30.0,
            "solar.further_suns[0].zenith_deg",
        ),
        (
            &|s| s.further_suns[1].zenith_deg = 50.0,
            "solar.further_suns[1].zenith_deg",
        ),
        (
            &|s| s.further_suns[1].zenith_deg = 90.0,
            "solar.further_suns[1].zenith_deg",
        ),
        (
            &|s| s.further_suns[0].zenith_deg = f64::NAN,
            "solar.further_suns[0].zenith_deg",
        ),
        (
            &|s| s.further_suns[1].transmission.truncate(3),
            "solar.further_suns[1].transmission",
        ),
        (
            &|s| s.further_suns[0].transmission[5] = 1.01,
            "solar.further_suns[0].transmission[1][2]",
        ),
    ];
    for (break_it, path) in cases {
        let mut s = day.clone();
        break_it(&mut s);
        a.solar = Some(s);
        let e = a.validate().unwrap_err();
        assert_eq!(e.path, path, "{e}");
    }
    let mut lit = day;
    lit.relative_azimuth_deg = vec![0.0, 180.0];
    a.slant = Some(SpectralSlantTables {
        altitude_m: vec![100.0],
        nadir_deg: vec![0.0],
        ground_m: None,
        transmission: vec![0.9; 3],
        path_radiance_w_m2_sr_per_unit: vec![0.01; 3],
        sky_altitude_m: vec![0.0],
        sky_zenith_deg: vec![0.0],
        sky_radiance_w_m2_sr_per_unit: vec![0.01; 3],
        interpolation_residual: None,
    });
    lit.path_scattered_w_m2_sr_per_unit = vec![0.01; 6];
    lit.sky_scattered_w_m2_sr_per_unit = vec![0.01; 12];
    // With scattered tables, each further sun holds its own on the same nodes.
    a.solar = Some(lit.clone());
    let e = a.validate().unwrap_err();
    assert_eq!(
        e.path, "solar.further_suns[0].path_scattered_w_m2_sr_per_unit",
        "{e}"
    );
    for b in &mut lit.further_suns {
        b.path_scattered_w_m2_sr_per_unit = vec![0.02; 6];
        b.sky_scattered_w_m2_sr_per_unit = vec![0.02; 12];
    }
    a.solar = Some(lit.clone());
    a.validate().unwrap();
    // The measured phase function: one spectrum per altitude and angle, the angles
    // increasing within 0-180, and only beside scattered-sunlight tables.
    let mut phased = lit.clone();
    phased.phase = Some(SolarPhase {
        scattering_deg: vec![0.0, 10.0, 180.0],
        scattered_w_m2_sr_per_unit_per_m: vec![1e-6; 2 * 3 * 3],
    });
    a.solar = Some(phased.clone());
    a.validate().unwrap();
    type BreakPhase = dyn Fn(&mut SolarPhase);
    let phase_cases: [(&BreakPhase, &str); 5] = [
        (
            &|p| {
                p.scattered_w_m2_sr_per_unit_per_m.pop();
            },
            "solar.phase.scattered_w_m2_sr_per_unit_per_m",
        ),
        (
            &|p| p.scattered_w_m2_sr_per_unit_per_m[5] = f32::NAN,
            "solar.phase.scattered_w_m2_sr_per_unit_per_m[1][2]",
        ),
        (
            &|p| p.scattering_deg[2] = 180.5,
            "solar.phase.scattering_deg[2]",
        ),
        (
            &|p| p.scattering_deg[1] = 0.0,
            "solar.phase.scattering_deg[1]",
        ),
        (&|p| p.scattering_deg.clear(), "solar.phase.scattering_deg"),
    ];
    for (break_it, path) in phase_cases {
        let mut s = phased.clone();
        break_it(s.phase.as_mut().unwrap());
        a.solar = Some(s);
        let e = a.validate().unwrap_err();
        assert_eq!(e.path, path, "{e}");
    }
    let mut unlit = phased.clone();
    unlit.relative_azimuth_deg.clear();
    unlit.path_scattered_w_m2_sr_per_unit.clear();
    unlit.sky_scattered_w_m2_sr_per_unit.clear();
    for b in &mut unlit.further_suns {
        b.path_scattered_w_m2_sr_per_unit.clear();
        b.sky_scattered_w_m2_sr_per_unit.clear();
    }
    a.solar = Some(unlit);
    assert_eq!(a.validate().unwrap_err().path, "solar.phase");
    let mut short = lit.clone();
    short.further_suns[1].sky_scattered_w_m2_sr_per_unit.pop();
    a.solar = Some(short);
    let e = a.validate().unwrap_err();
    assert_eq!(
        e.path, "solar.further_suns[1].sky_scattered_w_m2_sr_per_unit",
        "{e}"
    );
    let mut negative = lit.clone();
    negative.further_suns[0].path_scattered_w_m2_sr_per_unit[4] = -1.0;
    a.solar = Some(negative);
    assert!(a.validate().is_err());
    // Without azimuths, no sun may hold scattered spectra.
    let mut dark = lit.clone();
    dark.relative_azimuth_deg.clear();
    dark.path_scattered_w_m2_sr_per_unit.clear();
    dark.sky_scattered_w_m2_sr_per_unit.clear();
    a.solar = Some(dark.clone());
    let e = a.validate().unwrap_err();
    assert_eq!(
        e.path, "solar.further_suns[0].path_scattered_w_m2_sr_per_unit",
        "{e}"
    );
    for b in &mut dark.further_suns {
        b.path_scattered_w_m2_sr_per_unit.clear();
        b.sky_scattered_w_m2_sr_per_unit.clear();
    }
    a.solar = Some(dark);
    a.validate().unwrap();
    lit.further_suns.clear();
    a.solar = Some(lit);
    a.validate().unwrap();
    a.slant = None;
    let mut s = sun;
    s.extraterrestrial_w_m2_per_unit[0] = f32::NAN;
    a.solar = Some(s);
    let e = a.validate().unwrap_err().to_string();
    assert!(e.contains("irradiance"), "{e}");
}
