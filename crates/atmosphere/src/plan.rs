//! Planning an atmosphere build (issue 14, Build 3): from the observers of a scene to the
//! list of radiative-transfer paths a [`SpectralAtmosphere`] needs, a LOWTRAN7 card deck
//! for each, and back from the paths' spectra to the spectral atmosphere.
//!
//! The plan is data ([`AtmospherePlan`], written by `irsig-atmos plan`); this module
//! derives from it the unique paths in a fixed order ([`paths`]), the deck of each
//! ([`deck`]) and, given each path's spectra, the atmosphere ([`assemble`]). Running the
//! code is the tool's business (libraries spawn no processes).
//!
//! The nodes are those of the built-ins (scripts/atmosphere/regen.py): slant paths end
//! 1 m above the ground (a path to 0 m makes LOWTRAN add a ground's emission), slant
//! observers at 2 m–3 km plus every observer of the scene, nadir angles 0–88° up to the
//! horizon of the highest observer, sky observers 0–10 km plus the scene's, the `.cor`
//! fit at 1 km, the ground sky every 5°, and the hemispheric sky by 32-point
//! Gauss–Legendre quadrature in cos θ.

use std::collections::BTreeMap;

use irsig_formats::radtran::tape5::{
    Card1, Card2, Card3, Card4, CardDeck, Cards, Geometry, ProfileLevel as DeckLevel, Step,
    UserProfile,
};
use irsig_model::{
    AtmospherePlan, CorrectionPaths, PlanModel, ProfileLevel, SpectralAtmosphere, SpectralAxis,
    SpectralGrid, SpectralSlantTables,
};

use crate::error::{AtmosphereError, AtmosphereErrorKind};

/// The built-ins' slant observer altitudes, metres (the grid extends past 3 km as needed).
pub const SLANT_ALTITUDE_M: [f64; 19] = [
    2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 300.0, 500.0, 700.0, 1000.0, 1500.0, 2000.0, 3000.0,
    5000.0, 7000.0, 10_000.0, 15_000.0, 20_000.0,
];
/// The built-ins' slant nadir angles, degrees.
pub const SLANT_NADIR_DEG: [f64; 18] = [
    0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 65.0, 70.0, 75.0, 78.0, 80.0, 82.0, 84.0, 85.0, 86.0,
    87.0, 88.0,
];
/// The built-ins' sky observer altitudes, metres.
pub const SKY_ALTITUDE_M: [f64; 7] = [0.0, 300.0, 1000.0, 2000.0, 3000.0, 5000.0, 10_000.0];
/// The built-ins' profile levels, metres.
pub const LEVELS_M: [f64; 14] = [
    50.0, 100.0, 200.0, 300.0, 500.0, 700.0, 1000.0, 1500.0, 2000.0, 3000.0, 4000.0, 5000.0,
    7000.0, 10_000.0,
];
/// Earth radius LOWTRAN7 uses, metres.
const EARTH_RADIUS_M: f64 = 6_371_230.0;
/// Levels of the US Standard 1976 model put above a radiosonde's last level, km.
const ABOVE_RADIOSONDE_KM: [f64; 22] = [
    1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 12.0, 14.0, 16.0, 18.0, 20.0, 25.0, 30.0,
    35.0, 40.0, 50.0, 70.0, 100.0,
];

fn sky_zenith_deg() -> Vec<f64> {
    (0..16)
        .map(|i| 5.0 * f64::from(i))
        .chain([80.0, 83.0, 85.0, 86.0, 87.0, 88.0, 89.0, 90.0])
        .collect()
}

/// Gauss–Legendre nodes and weights on [0, 1], `n` points (Newton on P_n).
fn gauss_legendre_01(n: usize) -> Vec<(f64, f64)> {
    let nf = n as f64;
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let kf = k as f64;
                    let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
                    p0 = p1;
                    p1 = p2;
                }
                dp = nf * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            (0.5 * (x + 1.0), 0.5 * w)
        })
        .collect()
}

/// Rounds to the `decimals` a card's `F10.3` field keeps.
fn round3(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

/// A plan for observers at `observers_m` above the scene's lowest point.
///
/// # Errors
/// No observer, or one that is not finite or lies below 2 m (the lowest slant altitude;
/// the paths end 1 m up).
pub fn make_plan(
    name: &str,
    model: PlanModel,
    observers_m: &[f64],
) -> Result<AtmospherePlan, AtmosphereError> {
    let bad = |m: String| -> AtmosphereError { AtmosphereErrorKind::Plan(m).into() };
    if observers_m.is_empty() {
        return Err(bad("a plan needs at least one observer".into()));
    }
    let mut observers: Vec<f64> = Vec::new();
    for &h in observers_m {
        if !(h.is_finite() && h >= 2.0) {
            return Err(bad(format!(
                "an observer {h} m above the scene's lowest point: observers must be 2 m or more above it"
            )));
        }
        observers.push(h.round());
    }
    observers.sort_by(f64::total_cmp);
    observers.dedup();
    let top = observers[observers.len() - 1];
    let mut slant: Vec<f64> = SLANT_ALTITUDE_M
        .iter()
        .copied()
        .filter(|&a| a <= 3000.0 || a < top)
        .collect();
    slant.extend(&observers);
    slant.sort_by(f64::total_cmp);
    slant.dedup();
    let highest = slant[slant.len() - 1];
    // LOWTRAN refracts over a spherical Earth: keep inside the geometric horizon of the
    // highest observer (refraction lowers it a little further), so that every path of the
    // rectangular table reaches the ground (from 3 km: 88 deg does, 88.5 does not).
    let horizon = (EARTH_RADIUS_M / (EARTH_RADIUS_M + highest))
        .asin()
        .to_degrees();
    let nadir: Vec<f64> = SLANT_NADIR_DEG
        .iter()
        .copied()
        .filter(|&a| a <= horizon)
        .collect();
    let mut sky: Vec<f64> = SKY_ALTITUDE_M.to_vec();
    sky.extend(&observers);
    sky.sort_by(f64::total_cmp);
    sky.dedup();
    let mut levels = LEVELS_M.to_vec();
    if top > 10_000.0 {
        levels.push(top);
    }
    let hemispheric = gauss_legendre_01(32)
        .into_iter()
        .map(|(mu, w)| {
            let z = round3(mu.acos().to_degrees());
            (z, 2.0 * w * z.to_radians().cos())
        })
        .rev()
        .collect();
    Ok(AtmospherePlan {
        name: name.to_owned(),
        model,
        wavenumber_per_cm: [710.0, 1250.0, 5.0],
        path_end_m: 1.0,
        observers_m: observers,
        levels_m: levels,
        correction_altitude_m: 1000.0,
        correction_nadir_deg: (0..=16).map(|i| 5.0 * f64::from(i)).collect(),
        ground_sky_zenith_deg: (0..=18).map(|i| 5.0 * f64::from(i)).collect(),
        hemispheric,
        slant_altitude_m: slant,
        slant_nadir_deg: nadir,
        sky_altitude_m: sky,
        sky_zenith_deg: sky_zenith_deg(),
    })
}

/// One radiative-transfer path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Path {
    /// From `altitude_m` down to the plan's path end, `nadir_deg` from straight down.
    Down {
        /// Observer altitude, metres.
        altitude_m: f64,
        /// Nadir angle, degrees.
        nadir_deg: f64,
    },
    /// From `altitude_m` up to space, `zenith_deg` from straight up.
    Up {
        /// Observer altitude, metres.
        altitude_m: f64,
        /// Zenith angle, degrees.
        zenith_deg: f64,
    },
}

type Key = (u8, i64, i64);

fn key(p: &Path) -> Key {
    #[allow(clippy::cast_possible_truncation)]
    let q = |x: f64| (x * 1000.0).round() as i64;
    match *p {
        Path::Down {
            altitude_m,
            nadir_deg,
        } => (0, q(altitude_m), q(nadir_deg)),
        Path::Up {
            altitude_m,
            zenith_deg,
        } => (1, q(altitude_m), q(zenith_deg)),
    }
}

fn wanted(plan: &AtmospherePlan) -> Vec<Path> {
    let mut out = Vec::new();
    let down = |a: f64, n: f64| Path::Down {
        altitude_m: a,
        nadir_deg: n,
    };
    let up = |a: f64, z: f64| Path::Up {
        altitude_m: a,
        zenith_deg: z,
    };
    out.extend(plan.levels_m.iter().map(|&a| down(a, 0.0)));
    out.extend(
        plan.correction_nadir_deg
            .iter()
            .map(|&n| down(plan.correction_altitude_m, n)),
    );
    out.extend(plan.ground_sky_zenith_deg.iter().map(|&z| up(0.0, z)));
    out.extend(plan.hemispheric.iter().map(|&(z, _)| up(0.0, z)));
    for &a in &plan.slant_altitude_m {
        out.extend(plan.slant_nadir_deg.iter().map(|&n| down(a, n)));
    }
    for &a in &plan.sky_altitude_m {
        out.extend(plan.sky_zenith_deg.iter().map(|&z| up(a, z)));
    }
    out
}

/// The plan's unique paths, in a fixed order (slant paths by altitude and angle, then sky
/// paths): run `i` of a build is path `i`.
#[must_use]
pub fn paths(plan: &AtmospherePlan) -> Vec<Path> {
    let mut map: BTreeMap<Key, Path> = BTreeMap::new();
    for p in wanted(plan) {
        map.entry(key(&p)).or_insert(p);
    }
    map.into_values().collect()
}

fn standard_cards(model: i64, itype: i64, card3: Card3, v: [f64; 3]) -> Cards {
    Cards {
        card1: Card1 {
            model,
            itype,
            iemsct: 1,
            imult: 0,
            m: [0; 6],
            mdef: 0,
            im: i64::from(model == 7),
            noprt: 0,
            tbound_k: 0.0,
            salb: 0.0,
        },
        card2: Card2 {
            ihaze: 0,
            iseasn: 0,
            ivulcn: 0,
            icstl: 0,
            icld: 0,
            ivsa: 0,
            vis_km: 0.0,
            wss_m_s: 0.0,
            whh_m_s: 0.0,
            rainrt_mm_h: 0.0,
            gndalt_km: 0.0,
        },
        card2a: None,
        card2b: None,
        profile: None,
        geometry: Geometry {
            card3,
            scattering: None,
            position: irsig_formats::legacy::Position::default(),
        },
        card4: Card4 {
            v1_per_cm: v[0],
            v2_per_cm: v[1],
            dv_per_cm: v[2],
            position: irsig_formats::legacy::Position::default(),
        },
        position: irsig_formats::legacy::Position::default(),
    }
}

/// LOWTRAN7's user profile (cards 2C–2C1) of a radiosonde: its levels in km above its
/// first one, mb, °C and dew point in °C (`JCHAR` `ABG`, the other gases from the US
/// Standard 1976 model), then US Standard 1976 levels above its last.
///
/// # Errors
/// A radiosonde of more than 30 levels (LOWTRAN holds 34 and the plan puts standard
/// levels above it), or one whose levels are closer than 1 m.
pub fn radiosonde_profile(
    levels: &[irsig_model::RadiosondeLevel],
) -> Result<UserProfile, AtmosphereError> {
    let bad = |m: String| -> AtmosphereError { AtmosphereErrorKind::Plan(m).into() };
    if levels.len() < 2 || levels.len() > 30 {
        return Err(bad(format!(
            "LOWTRAN7's user model holds at most 34 levels and the plan adds at least 4 above the radiosonde: the radiosonde has {} levels, expected 2 to 30",
            levels.len()
        )));
    }
    let ground = levels[0].altitude_m;
    let mut out = Vec::new();
    let mut last = f64::NEG_INFINITY;
    for l in levels {
        let z = round3((l.altitude_m - ground) / 1000.0);
        if z <= last {
            return Err(bad(format!(
                "radiosonde levels at {} m and below are closer than the 1 m a card keeps",
                l.altitude_m
            )));
        }
        last = z;
        let t_c = l.temperature_k - 273.15;
        let round = |x: f64| (x * 1e3).round() / 1e3;
        out.push(DeckLevel {
            zmdl_km: z,
            p: round(l.pressure_hpa),
            t: round(t_c),
            wmol: [round(t_c - l.dew_point_depression_k), 0.0, 0.0],
            jchar: "ABG66666666666".into(),
            wmol_more: None,
            aerosol: None,
            position: irsig_formats::legacy::Position::default(),
        });
    }
    for &z in ABOVE_RADIOSONDE_KM.iter().filter(|&&z| z > last + 0.5) {
        if out.len() == irsig_formats::radtran::tape5::MAX_LEVELS {
            break;
        }
        out.push(DeckLevel {
            zmdl_km: z,
            p: 0.0,
            t: 0.0,
            wmol: [0.0; 3],
            jchar: "66666666666666".into(),
            wmol_more: None,
            aerosol: None,
            position: irsig_formats::legacy::Position::default(),
        });
    }
    Ok(UserProfile {
        ird1: 0,
        ird2: 0,
        title: "RADIOSONDE (irsig-atmos plan)".into(),
        levels: out,
    })
}

/// The LOWTRAN7 card deck of one path: thermal radiance (IEMSCT = 1), no aerosol, no
/// multiple scattering, the plan's spectral range; case 2A (ITYPE 2, H1, H2, ANGLE =
/// 180 − nadir) down, case 3A (ITYPE 3, H1, ANGLE = zenith) up.
///
/// # Errors
/// As [`radiosonde_profile`].
pub fn deck(plan: &AtmospherePlan, path: &Path) -> Result<CardDeck, AtmosphereError> {
    let (itype, card3) = match *path {
        Path::Down {
            altitude_m,
            nadir_deg,
        } => (
            2,
            Card3::Path {
                h1_km: round3(altitude_m / 1000.0),
                h2_km: round3(plan.path_end_m / 1000.0),
                angle_deg: round3(180.0 - nadir_deg),
                range_km: 0.0,
                beta_deg: 0.0,
                ro_km: 0.0,
                len: 0,
            },
        ),
        Path::Up {
            altitude_m,
            zenith_deg,
        } => (
            3,
            Card3::Path {
                h1_km: round3(altitude_m / 1000.0),
                h2_km: 0.0,
                angle_deg: round3(zenith_deg),
                range_km: 0.0,
                beta_deg: 0.0,
                ro_km: 0.0,
                len: 0,
            },
        ),
    };
    let mut cards = match &plan.model {
        PlanModel::Standard(m) => {
            standard_cards(i64::from(*m), itype, card3, plan.wavenumber_per_cm)
        }
        PlanModel::Radiosonde(levels) => {
            let mut c = standard_cards(7, itype, card3, plan.wavenumber_per_cm);
            c.profile = Some(radiosonde_profile(levels)?);
            c
        }
    };
    cards.card1.mdef = i64::from(matches!(plan.model, PlanModel::Radiosonde(_)));
    Ok(CardDeck {
        steps: vec![Step::Full(Box::new(cards))],
    })
}

/// What a run gave for one path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathSpectra {
    /// Wavenumbers, cm⁻¹, increasing.
    pub wavenumber_per_cm: Vec<f64>,
    /// Transmittance, 0–1 (values a little above 1, as LOWTRAN prints them on short paths,
    /// are clamped to 1 by [`assemble`]).
    pub transmission: Vec<f64>,
    /// Path (or sky) radiance, W m⁻² sr⁻¹ per cm⁻¹.
    pub radiance_w_m2_sr_per_cm: Vec<f64>,
}

/// The spectral atmosphere from the spectra of every path of [`paths`] (same order),
/// `temperature_k(altitude above the ground in m)` for the profile, the ground's altitude
/// above sea level and the source text.
///
/// # Errors
/// A count of spectra that is not the count of paths, runs on different spectral grids,
/// or an atmosphere that fails validation.
pub fn assemble(
    plan: &AtmospherePlan,
    spectra: &[PathSpectra],
    temperature_k: &dyn Fn(f64) -> f64,
    ground_asl_m: f64,
    source: &str,
) -> Result<SpectralAtmosphere, AtmosphereError> {
    let bad = |m: String| -> AtmosphereError { AtmosphereErrorKind::Plan(m).into() };
    let all = paths(plan);
    if spectra.len() != all.len() {
        return Err(bad(format!(
            "the plan has {} paths, the runs gave {}",
            all.len(),
            spectra.len()
        )));
    }
    let grid = spectra[0].wavenumber_per_cm.clone();
    for (i, s) in spectra.iter().enumerate() {
        if s.wavenumber_per_cm != grid {
            return Err(bad(format!(
                "run {i} is on a different spectral grid from run 0 ({} points from {} cm-1, against {} from {} cm-1)",
                s.wavenumber_per_cm.len(),
                s.wavenumber_per_cm.first().copied().unwrap_or(f64::NAN),
                grid.len(),
                grid.first().copied().unwrap_or(f64::NAN)
            )));
        }
    }
    let index: BTreeMap<Key, usize> = all.iter().enumerate().map(|(i, p)| (key(p), i)).collect();
    let get = |p: Path| -> &PathSpectra { &spectra[index[&key(&p)]] };
    #[allow(clippy::cast_possible_truncation)]
    let f32s = |v: &[f64]| v.iter().map(|&x| x as f32).collect::<Vec<f32>>();
    // LOWTRAN prints τ a little above 1 on metre-long paths: clamp.
    let tau = |p: Path| {
        let t: Vec<f64> = get(p)
            .transmission
            .iter()
            .map(|t| t.clamp(0.0, 1.0))
            .collect();
        f32s(&t)
    };
    let rad = |p: Path| f32s(&get(p).radiance_w_m2_sr_per_cm);
    let down = |a: f64, n: f64| Path::Down {
        altitude_m: a,
        nadir_deg: n,
    };
    let up = |a: f64, z: f64| Path::Up {
        altitude_m: a,
        zenith_deg: z,
    };
    let levels: Vec<ProfileLevel> = plan
        .levels_m
        .iter()
        .map(|&h| ProfileLevel {
            altitude_asl_m: ground_asl_m + h,
            temperature_k: (temperature_k(h) * 1e3).round() / 1e3,
            altitude_m: h,
        })
        .collect();
    let mut hemi = vec![0.0_f64; grid.len()];
    for &(z, w) in &plan.hemispheric {
        for (h, l) in hemi
            .iter_mut()
            .zip(&get(up(0.0, z)).radiance_w_m2_sr_per_cm)
        {
            *h += w * l;
        }
    }
    let flat = |ps: Vec<Path>, f: &dyn Fn(Path) -> Vec<f32>| -> Vec<f32> {
        ps.into_iter().flat_map(f).collect()
    };
    let slant_paths: Vec<Path> = plan
        .slant_altitude_m
        .iter()
        .flat_map(|&a| plan.slant_nadir_deg.iter().map(move |&n| down(a, n)))
        .collect();
    let sky_paths: Vec<Path> = plan
        .sky_altitude_m
        .iter()
        .flat_map(|&a| plan.sky_zenith_deg.iter().map(move |&z| up(a, z)))
        .collect();
    let atmosphere = SpectralAtmosphere {
        name: plan.name.clone(),
        source: source.to_owned(),
        grid: SpectralGrid {
            axis: SpectralAxis::WavenumberPerCm,
            points: grid,
        },
        levels,
        level_transmission: flat(plan.levels_m.iter().map(|&a| down(a, 0.0)).collect(), &tau),
        level_path_radiance_w_m2_sr_per_unit: flat(
            plan.levels_m.iter().map(|&a| down(a, 0.0)).collect(),
            &rad,
        ),
        transmission_correction: Some(CorrectionPaths {
            altitude_m: plan.correction_altitude_m,
            nadir_deg: plan.correction_nadir_deg.clone(),
            transmission: flat(
                plan.correction_nadir_deg
                    .iter()
                    .map(|&n| down(plan.correction_altitude_m, n))
                    .collect(),
                &tau,
            ),
        }),
        sky_zenith_deg: plan.ground_sky_zenith_deg.clone(),
        sky_radiance_w_m2_sr_per_unit: flat(
            plan.ground_sky_zenith_deg
                .iter()
                .map(|&z| up(0.0, z))
                .collect(),
            &rad,
        ),
        sky_hemispheric_w_m2_sr_per_unit: Some(f32s(&hemi)),
        radiosonde: match &plan.model {
            PlanModel::Radiosonde(l) => l.clone(),
            PlanModel::Standard(_) => Vec::new(),
        },
        slant: Some(SpectralSlantTables {
            altitude_m: plan.slant_altitude_m.clone(),
            nadir_deg: plan.slant_nadir_deg.clone(),
            ground_m: Some(plan.path_end_m),
            transmission: flat(slant_paths.clone(), &tau),
            path_radiance_w_m2_sr_per_unit: flat(slant_paths, &rad),
            sky_altitude_m: plan.sky_altitude_m.clone(),
            sky_zenith_deg: plan.sky_zenith_deg.clone(),
            sky_radiance_w_m2_sr_per_unit: flat(sky_paths, &rad),
            // The plan's rows are the scene's own paths: nothing lies between them that
            // was measured.
            interpolation_residual: None,
        }),
    };
    atmosphere.validate()?;
    Ok(atmosphere)
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // nodes are copied, not computed
mod tests {
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
}
