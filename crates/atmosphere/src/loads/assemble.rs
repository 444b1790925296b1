//! From the runs of a loads plan to the table of a day's loads ([`assemble`]), and the
//! table at any sun zenith angle between its rows ([`sun_loads_at`]).

use std::collections::BTreeMap;

use irsig_model::loads::{BroadbandLoads, LoadsPlan};

use super::{LoadsPath, bad, key, paths};
use crate::error::AtmosphereError;
use crate::interp;
use crate::plan::PathSpectra;

/// The longwave below the thermal range, where the lower atmosphere is opaque and the sky
/// a blackbody at the ground's air temperature: computed by the caller, which knows the
/// Planck integral (this crate works in the radiances LOWTRAN7 gives).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LongwaveOutside {
    /// The air temperature at the ground (the model's lowest level), K.
    pub air_temperature_k: f64,
    /// `π ∫₀^{v1} B_ν(T_air) dν`, W m⁻², `v1` the thermal range's lower end.
    pub below_range_w_m2: f64,
}

/// `∫ y dν` by the trapezoid over the points `nu` (cm⁻¹), `y(i)` per cm⁻¹.
fn trapezoid(nu: &[f64], y: impl Fn(usize) -> f64) -> f64 {
    (1..nu.len())
        .map(|i| 0.5 * (y(i - 1) + y(i)) * (nu[i] - nu[i - 1]))
        .sum()
}

/// What a run of `path` must hold, and the length found, for the check of its spectra.
fn needs(path: &LoadsPath, s: &PathSpectra) -> (&'static str, usize) {
    match path {
        LoadsPath::Longwave { .. } => (
            "a thermal path radiance (a thermal radiance run, IEMSCT = 1)",
            s.radiance_w_m2_sr_per_cm.len(),
        ),
        LoadsPath::Direct { .. } => (
            "an extraterrestrial solar irradiance and a transmittance (a direct solar \
             irradiance run, IEMSCT = 3)",
            s.extraterrestrial_w_m2_per_cm
                .len()
                .min(s.transmission.len()),
        ),
        LoadsPath::Diffuse { .. } => (
            "a scattered solar radiance (a solar scattering run, IEMSCT = 2)",
            s.scattered_w_m2_sr_per_cm.len(),
        ),
    }
}

/// The day's loads from the spectra of every path of [`paths`] (same order): DNI per sun
/// zenith angle, `∫ E_toa τ dν` of its direct run; DHI, `Σ w ∫ L_scat dν` over its
/// diffuse lines of sight; E_LW, `Σ w ∫ L dν` over the longwave lines of sight plus
/// `outside.below_range_w_m2`. `model` and `source` say what was run; `notes` are the
/// caller's (runs moved off their node), to which the table's own are added (what lies
/// outside the spectral ranges, the rules).
///
/// # Errors
/// A count of spectra that is not the count of paths; a run without the spectrum its path
/// needs, or with fewer than two points; direct runs of different extraterrestrial
/// irradiances (another day); a table that fails validation.
pub fn assemble(
    plan: &LoadsPlan,
    spectra: &[PathSpectra],
    outside: &LongwaveOutside,
    model: &str,
    source: &str,
    mut notes: Vec<String>,
) -> Result<BroadbandLoads, AtmosphereError> {
    let all = paths(plan);
    if spectra.len() != all.len() {
        return Err(bad(format!(
            "the loads plan has {} paths, the runs gave {}",
            all.len(),
            spectra.len()
        )));
    }
    let mut integral = Vec::with_capacity(all.len());
    for (i, (p, s)) in all.iter().zip(spectra).enumerate() {
        let (what, found) = needs(p, s);
        let n = s.wavenumber_per_cm.len();
        if n < 2 || found != n {
            return Err(bad(format!(
                "run {i} ({p:?}): expected {what} at each of its {n} wavenumbers (at least \
                 2), found {found} values"
            )));
        }
        let nu = &s.wavenumber_per_cm;
        integral.push(match p {
            LoadsPath::Longwave { .. } => trapezoid(nu, |k| s.radiance_w_m2_sr_per_cm[k]),
            // LOWTRAN prints τ a little above 1 on the shortest paths: clamped.
            LoadsPath::Direct { .. } => trapezoid(nu, |k| {
                s.extraterrestrial_w_m2_per_cm[k] * s.transmission[k].clamp(0.0, 1.0)
            }),
            LoadsPath::Diffuse { .. } => trapezoid(nu, |k| s.scattered_w_m2_sr_per_cm[k]),
        });
    }
    let index: BTreeMap<_, usize> = all.iter().enumerate().map(|(i, p)| (key(p), i)).collect();
    let of = |p: LoadsPath| integral[index[&key(&p)]];
    // Every direct run of one day has one extraterrestrial spectrum.
    let direct: Vec<usize> = all
        .iter()
        .enumerate()
        .filter(|(_, p)| matches!(p, LoadsPath::Direct { .. }))
        .map(|(i, _)| i)
        .collect();
    let etoa = |i: usize| {
        let s = &spectra[i];
        trapezoid(&s.wavenumber_per_cm, |k| s.extraterrestrial_w_m2_per_cm[k])
    };
    let extraterrestrial = direct.first().map_or(0.0, |&i| etoa(i));
    for &i in &direct {
        let e = etoa(i);
        if (e - extraterrestrial).abs() > 1e-6 * extraterrestrial {
            return Err(bad(format!(
                "run {i} ({:?}) has another extraterrestrial solar irradiance ({e} W m-2) \
                 than run {} ({extraterrestrial} W m-2): the sun's runs must be of one day",
                all[i], direct[0]
            )));
        }
    }
    let longwave_in_range: f64 = plan
        .longwave
        .iter()
        .map(|&(zenith_deg, w)| w * of(LoadsPath::Longwave { zenith_deg }))
        .sum();
    let mut dni = Vec::with_capacity(plan.sun.len());
    let mut dhi = Vec::with_capacity(plan.sun.len());
    for sun in &plan.sun {
        dni.push(of(LoadsPath::Direct {
            sun_zenith_deg: sun.zenith_deg,
        }));
        dhi.push(
            sun.diffuse
                .iter()
                .map(|&(zenith_deg, azimuth_deg, w)| {
                    w * of(LoadsPath::Diffuse {
                        sun_zenith_deg: sun.zenith_deg,
                        zenith_deg,
                        azimuth_deg,
                    })
                })
                .sum(),
        );
    }
    let [s1, s2, _] = plan.solar_wavenumber_per_cm;
    let [t1, t2, _] = plan.thermal_wavenumber_per_cm;
    let runs: Vec<usize> = plan.sun.iter().map(|s| s.diffuse.len()).collect();
    notes.extend([
        format!(
            "DNI and DHI are the sunlight over {s1}-{s2} cm-1 ({:.4}-{:.4} um); the sun's \
             light outside it is in neither",
            1e4 / s2,
            1e4 / s1
        ),
        format!(
            "E_LW is LOWTRAN7's sky emission over {t1}-{t2} cm-1 plus {:.4} W m-2 below \
             {t1} cm-1, a blackbody at the air temperature at the ground, {} K (the lower \
             atmosphere is opaque there); the sky's emission above {t2} cm-1 is left out",
            outside.below_range_w_m2, outside.air_temperature_k
        ),
        format!(
            "DHI: {} to {} lines of sight per sun on the sun-centred rule; E_LW: {} lines \
             of sight, Gauss-Legendre in cos(zenith) (docs/accuracy.md, \"Broadband loads\")",
            runs.iter().min().copied().unwrap_or(0),
            runs.iter().max().copied().unwrap_or(0),
            plan.longwave.len()
        ),
    ]);
    let table = BroadbandLoads {
        apparent_sun_zenith_deg: Vec::new(),
        name: plan.name.clone(),
        source: source.to_owned(),
        model: model.to_owned(),
        aerosol: plan.aerosol.clone(),
        ground_albedo: plan.ground_albedo,
        day_of_year: plan.day_of_year,
        solar_wavenumber_per_cm: [s1, s2],
        thermal_wavenumber_per_cm: [t1, t2],
        extraterrestrial_normal_w_m2: extraterrestrial,
        sun_zenith_deg: plan.sun.iter().map(|s| s.zenith_deg).collect(),
        direct_normal_w_m2: dni,
        diffuse_horizontal_w_m2: dhi,
        longwave_down_w_m2: longwave_in_range + outside.below_range_w_m2,
        longwave_outside_range_w_m2: outside.below_range_w_m2,
        air_temperature_k: outside.air_temperature_k,
        notes,
    };
    table.validate()?;
    Ok(table)
}

/// The relative optical air mass at a sun zenith angle, the Kasten & Young (1989) fit
/// (Applied Optics 28, 4735): `m = 1 / (cos z + 0.50572 (96.07995° − z)^−1.6364)`, which
/// stays finite at the horizon (37.9 at 90°) where `1/cos z` does not.
#[must_use]
pub fn kasten_young_air_mass(zenith_deg: f64) -> f64 {
    1.0 / (zenith_deg.to_radians().cos() + 0.50572 * (96.079_95 - zenith_deg).powf(-1.6364))
}

/// A day's loads at one sun position, W m⁻².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunLoads {
    /// Direct normal irradiance.
    pub direct_normal_w_m2: f64,
    /// Diffuse horizontal irradiance.
    pub diffuse_horizontal_w_m2: f64,
    /// Global horizontal irradiance, `DNI cos z + DHI`.
    pub global_horizontal_w_m2: f64,
}

/// The smallest direct irradiance whose logarithm is interpolated, W m⁻²: below it the
/// beam is nothing.
const DNI_FLOOR_W_M2: f64 = 1e-9;

/// The table's loads at `zenith_deg`, between its rows by monotone cubics (never above or
/// below the two rows around it) in the variables each is smooth in: the logarithm of the
/// DNI against the air mass ([`kasten_young_air_mass`]: Beer's law makes it nearly linear,
/// and the cubic follows the band-saturation curvature), and the DHI against cos z. With
/// rows 5° apart, the DNI is within 0.06 W m⁻² of LOWTRAN7's halfway between rows up to
/// 80°, 0.6 W m⁻² (0.4 %) at 82.5°; the DHI within 0.12 W m⁻² (docs/accuracy.md).
///
/// # Errors
/// A zenith angle that is not finite or lies outside the table's rows (no extrapolation:
/// plan the zenith angles a day needs, up to the last one it meets, 89.999° at most).
pub fn sun_loads_at(table: &BroadbandLoads, zenith_deg: f64) -> Result<SunLoads, AtmosphereError> {
    let zs = &table.sun_zenith_deg;
    let (first, last) = match (zs.first(), zs.last()) {
        (Some(&a), Some(&b)) => (a, b),
        _ => return Err(bad("the loads table has no rows".into())),
    };
    if !(zenith_deg.is_finite() && zenith_deg >= first - 1e-9 && zenith_deg <= last + 1e-9) {
        return Err(bad(format!(
            "the sun at {zenith_deg} deg from the zenith is outside the loads table's rows, \
             {first} to {last} deg: plan the zenith angles the day needs \
             (irsig-atmos plan --loads --sun-zeniths-deg)"
        )));
    }
    let z = zenith_deg.clamp(first, last);
    let air_mass: Vec<f64> = zs.iter().map(|&z| kasten_young_air_mass(z)).collect();
    let log_dni: Vec<f64> = table
        .direct_normal_w_m2
        .iter()
        .map(|&e| e.max(DNI_FLOOR_W_M2).ln())
        .collect();
    let minus_cos: Vec<f64> = zs.iter().map(|&z| -z.to_radians().cos()).collect();
    let dni = interp::monotone_cubic(&air_mass, &log_dni, kasten_young_air_mass(z)).exp();
    let dni = if dni <= DNI_FLOOR_W_M2 { 0.0 } else { dni };
    let dhi = interp::monotone_cubic(
        &minus_cos,
        &table.diffuse_horizontal_w_m2,
        -z.to_radians().cos(),
    );
    Ok(SunLoads {
        direct_normal_w_m2: dni,
        diffuse_horizontal_w_m2: dhi,
        global_horizontal_w_m2: dni * z.to_radians().cos() + dhi,
    })
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // a row is returned as it is stored, and values copied from the plan
mod tests {
    use super::*;
    use crate::loads::{LONGWAVE_NODES, make_loads_plan};
    use irsig_model::PlanModel;

    /// Spectra of a made-up atmosphere: per cm⁻¹ on 3 points 10 cm⁻¹ apart, a constant
    /// sun E of 0.1 W m⁻² per cm⁻¹ (2 W m⁻² over the range), τ = e^(−0.1 m(z)), a
    /// scattered sky of radiance `0.01 (1 + cos θ)` per cm⁻¹ and a thermal sky of 1.
    fn spectra(plan: &LoadsPlan) -> Vec<PathSpectra> {
        let nu = vec![1000.0, 1010.0, 1020.0];
        paths(plan)
            .iter()
            .map(|p| {
                let mut s = PathSpectra {
                    wavenumber_per_cm: nu.clone(),
                    transmission: vec![1.0; 3],
                    radiance_w_m2_sr_per_cm: Vec::new(),
                    extraterrestrial_w_m2_per_cm: Vec::new(),
                    scattered_w_m2_sr_per_cm: Vec::new(),
                };
                match *p {
                    LoadsPath::Longwave { .. } => s.radiance_w_m2_sr_per_cm = vec![1.0; 3],
                    LoadsPath::Direct { sun_zenith_deg } => {
                        s.transmission =
                            vec![(-0.1 * kasten_young_air_mass(sun_zenith_deg)).exp(); 3];
                        s.extraterrestrial_w_m2_per_cm = vec![0.1; 3];
                    }
                    LoadsPath::Diffuse { zenith_deg, .. } => {
                        s.scattered_w_m2_sr_per_cm =
                            vec![0.01 * (1.0 + zenith_deg.to_radians().cos()); 3];
                    }
                }
                s
            })
            .collect()
    }

    const OUTSIDE: LongwaveOutside = LongwaveOutside {
        air_temperature_k: 288.15,
        below_range_w_m2: 0.02,
    };

    #[test]
    fn the_table_is_the_integrals_of_the_runs() {
        let plan = make_loads_plan("t", PlanModel::Standard(6), 80, &[0.0, 40.0, 80.0]).unwrap();
        let t = assemble(&plan, &spectra(&plan), &OUTSIDE, "m", "s", vec!["n".into()]).unwrap();
        assert_eq!(t.sun_zenith_deg, [0.0, 40.0, 80.0]);
        assert!((t.extraterrestrial_normal_w_m2 - 2.0).abs() < 1e-12);
        for (k, &z) in t.sun_zenith_deg.iter().enumerate() {
            let want = 2.0 * (-0.1 * kasten_young_air_mass(z)).exp();
            assert!((t.direct_normal_w_m2[k] - want).abs() < 1e-12);
            // ∫ 0.2 (1 + cos θ) cos θ dΩ = 0.2 (π + 2π/3), to the rules' 1e-4.
            let sky = 0.2 * (std::f64::consts::PI + 2.0 * std::f64::consts::PI / 3.0);
            assert!(
                (t.diffuse_horizontal_w_m2[k] / sky - 1.0).abs() < 2e-4,
                "{k}"
            );
        }
        // A thermal sky of 20 W m-2 sr-1 over the range: 20 π, plus the part below it.
        let lw = 20.0 * std::f64::consts::PI + 0.02;
        assert!((t.longwave_down_w_m2 / lw - 1.0).abs() < 1e-12);
        assert_eq!(t.longwave_outside_range_w_m2, 0.02);
        assert_eq!(t.notes[0], "n");
        assert!(
            t.notes.len() == 4 && t.notes[1].contains("0.28"),
            "{:?}",
            t.notes
        );
        // Runs missing, of the wrong kind, or of two days: refused, naming the run.
        let mut s = spectra(&plan);
        s.pop();
        assert!(assemble(&plan, &s, &OUTSIDE, "m", "s", vec![]).is_err());
        let mut s = spectra(&plan);
        s[LONGWAVE_NODES].extraterrestrial_w_m2_per_cm.clear();
        let e = assemble(&plan, &s, &OUTSIDE, "m", "s", vec![]).unwrap_err();
        assert!(
            e.to_string().contains(&format!("run {LONGWAVE_NODES}")),
            "{e}"
        );
        let mut s = spectra(&plan);
        let last_beam = s.len() - 1 - plan.sun[2].diffuse.len();
        s[last_beam].extraterrestrial_w_m2_per_cm = vec![0.2; 3];
        let e = assemble(&plan, &s, &OUTSIDE, "m", "s", vec![]).unwrap_err();
        assert!(e.to_string().contains("one day"), "{e}");
    }

    #[test]
    fn between_rows_the_beam_follows_beers_law_and_the_sky_cos_z() {
        let zeniths: Vec<f64> = (0..=17).map(|k| 5.0 * f64::from(k)).collect();
        let plan = make_loads_plan("t", PlanModel::Standard(6), 80, &zeniths).unwrap();
        let t = assemble(&plan, &spectra(&plan), &OUTSIDE, "m", "s", vec![]).unwrap();
        // Beer's law in the air mass is what the DNI is interpolated in: exact to the
        // cubic's error on a straight line (none).
        for z in [2.5, 37.5, 62.5, 82.5] {
            let got = sun_loads_at(&t, z).unwrap();
            let want = 2.0 * (-0.1 * kasten_young_air_mass(z)).exp();
            assert!((got.direct_normal_w_m2 / want - 1.0).abs() < 1e-12, "{z}");
            let c = z.to_radians().cos();
            assert!(
                (got.global_horizontal_w_m2
                    - (got.direct_normal_w_m2 * c + got.diffuse_horizontal_w_m2))
                    .abs()
                    < 1e-12
            );
        }
        // At a row, the row.
        let at = sun_loads_at(&t, 40.0).unwrap();
        assert_eq!(at.diffuse_horizontal_w_m2, t.diffuse_horizontal_w_m2[8]);
        // Outside the rows, or not a number: refused.
        for z in [85.5, 90.0, -0.5, f64::NAN] {
            let e = sun_loads_at(&t, z).unwrap_err();
            assert!(
                e.to_string().contains("outside the loads table"),
                "{z}: {e}"
            );
        }
        // The air mass: 1 overhead, about 2 at 60 deg, finite on the horizon.
        assert!((kasten_young_air_mass(0.0) - 1.0).abs() < 1e-3);
        assert!((kasten_young_air_mass(60.0) - 1.9942).abs() < 1e-3);
        assert!((kasten_young_air_mass(90.0) - 37.92).abs() < 0.05);
    }
}
