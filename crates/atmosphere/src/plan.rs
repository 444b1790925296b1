//! Planning an atmosphere build: from the observers of a scene to the
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
//! Gauss–Legendre quadrature in cos θ. A plan with a sun ([`add_sun`]) adds one direct
//! solar irradiance run (IEMSCT = 3) per sky altitude, after every other path.

use std::collections::BTreeMap;

use irsig_formats::radtran::tape5::{
    Card1, Card2, Card3, Card4, CardDeck, Cards, Geometry, ProfileLevel as DeckLevel, Scattering,
    Step, UserProfile,
};
use irsig_model::{
    AtmospherePlan, CorrectionPaths, PlanAerosol, PlanModel, PlanSlabs, PlanSun, ProfileLevel,
    SolarBeam, SpectralAtmosphere, SpectralAxis, SpectralGrid, SpectralSlab, SpectralSlabTable,
    SpectralSlantTables, SpectralSolar,
};

use crate::error::{AtmosphereError, AtmosphereErrorKind};

mod assemble;
mod deck;
mod outputs;
mod phase;

pub use assemble::*;
pub use deck::*;
pub use outputs::*;
pub use phase::SCATTERING_DEG;

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
pub(crate) fn gauss_legendre_01(n: usize) -> Vec<(f64, f64)> {
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
pub(crate) fn round3(x: f64) -> f64 {
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
    let horizon = crate::earth::critical_nadir_angle_deg(highest);
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
        sun: None,
        aerosol: None,
        slabs: None,
    })
}

/// The angles, degrees, at which a plan's slabs are run, down (nadir) and up (zenith)
/// alike: 10° apart to 60°, then 5° to 80°. Between rows 10° and 20° apart the monotone
/// cubic in angle met the floor of the slab tables (docs/accuracy.md, "Slab tables").
pub const SLAB_ANGLE_DEG: [f64; 11] = [
    0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 65.0, 70.0, 75.0, 80.0,
];

/// Target altitudes of a plan's slabs for a scene whose top is `top_m` above its lowest
/// point, metres: 2, 5, 10 and 25 m, 25 m apart to 100 m, 50 m apart above, up to the
/// first row at or above the top. Between rows 50 m apart, a power of the distance from
/// the observer met the floor on the 87 m slab (docs/accuracy.md, "Slab tables").
#[must_use]
pub fn slab_targets_m(top_m: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut h = crate::slab::GROUND_ROW_M;
    loop {
        out.push(h);
        if h >= top_m {
            break;
        }
        h = match h {
            x if x < 2.5 => 5.0,
            x if x < 7.5 => 10.0,
            x if x < 17.5 => 25.0,
            x if x < 100.0 => x + 25.0,
            x => x + 50.0,
        };
    }
    out
}

/// Asks `plan` for slabs that end above the ground ([`PlanSlabs`]): from each of its
/// observers to [`slab_targets_m`]`(top_m)` at [`SLAB_ANGLE_DEG`] down and up.
///
/// # Errors
/// What [`AtmospherePlan::validate`] refuses of them (a plan without observers, a top
/// that is not finite or not above the paths' end).
pub fn add_slabs(plan: &mut AtmospherePlan, top_m: f64) -> Result<(), AtmosphereError> {
    if !(top_m.is_finite() && top_m > plan.path_end_m) {
        return Err(AtmosphereErrorKind::Plan(format!(
            "slabs end above the ground and below the scene's top: expected a top above the \
             paths' end ({} m), found {top_m} m",
            plan.path_end_m
        ))
        .into());
    }
    let mut p = plan.clone();
    p.slabs = Some(PlanSlabs {
        target_m: slab_targets_m(top_m),
        nadir_deg: SLAB_ANGLE_DEG.to_vec(),
        zenith_deg: SLAB_ANGLE_DEG.to_vec(),
    });
    p.validate()
        .map_err(|e| AtmosphereError::from(AtmosphereErrorKind::Plan(e.to_string())))?;
    *plan = p;
    Ok(())
}

/// Puts `aerosol` in every path of `plan` (LOWTRAN7's card 2: IHAZE, VIS and, for the
/// desert model, WSS), its visibility rounded to the whole metres a deck holds.
///
/// # Errors
/// What [`PlanAerosol::validate`] refuses; the message names the field.
pub fn add_aerosol(plan: &mut AtmospherePlan, aerosol: PlanAerosol) -> Result<(), AtmosphereError> {
    let aerosol = PlanAerosol {
        visibility_m: aerosol.visibility_m.round(),
        wind_speed_m_s: aerosol.wind_speed_m_s.map(round3),
        ..aerosol
    };
    aerosol
        .validate()
        .map_err(|e| AtmosphereError::from(AtmosphereErrorKind::Plan(e.to_string())))?;
    plan.aerosol = Some(aerosol);
    Ok(())
}

/// The azimuths of a line of sight from the sun's vertical plane at which a plan with a
/// sun runs every slant and sky path for its scattered sunlight, degrees. Closer toward
/// the sun, where the aerosols' forward peak makes the scattered light change fastest
/// (with rows 15° apart there, a hazy 3.4-4.1 um sky 12° from the sun was 2.2 % off
/// LOWTRAN7 between them; 10° apart, 0.2 %); the interpolation error between them is in
/// `docs/accuracy.md`.
pub const RELATIVE_AZIMUTH_DEG: [f64; 10] =
    [0.0, 10.0, 20.0, 30.0, 45.0, 60.0, 90.0, 120.0, 150.0, 180.0];

/// Sky observer altitudes a plan with a sun adds to the night's, metres.
pub const DAY_SKY_ALTITUDE_M: [f64; 3] = [500.0, 700.0, 1500.0];

/// Puts a sun at `zenith_deg` (rounded to the 0.001° a deck holds) on day `day_of_year` in
/// `plan`: its direct irradiance is then computed at the plan's sky altitudes (the
/// ground, 300 m to 10 km and every observer). With `scattered`, also at
/// [`DAY_SKY_ALTITUDE_M`] below the highest, and the sunlight scattered into every slant
/// and sky path at each of [`RELATIVE_AZIMUTH_DEG`] (LOWTRAN7's IEMSCT = 2), slant paths on
/// the slant table's nodes, sky paths on the sky table's zenith angles and the sun's
/// altitudes: about ten times the plan's runs, for the sunlight the tracer adds to its sky and paths by day, so
/// asked for by name (`irsig-atmos plan --sun-scattering`). Linear in altitude between the 0 and 300 m rows, the 3–5 µm
/// direct irradiance at 150 m is 6e-6 from LOWTRAN7's there, relative (US Standard 1976,
/// sun at 30°; tests/tests/solar.rs).
///
/// # Errors
/// A zenith angle that is not finite or not within 0 to below 90° (a sun at or below the
/// horizon gives no direct light), or a day outside 1–366; with `scattered`, a sun past
/// [`SCATTERED_MAX_ZENITH_DEG`]; the message names the value.
pub fn add_sun(
    plan: &mut AtmospherePlan,
    zenith_deg: f64,
    day_of_year: u16,
    scattered: bool,
) -> Result<(), AtmosphereError> {
    add_suns(plan, &[zenith_deg], day_of_year, scattered)
}

/// The lowest sun, as a zenith angle in degrees, whose scattered sunlight a plan runs, of
/// one sun or of a day's: LOWTRAN7 leaves some sunlit paths of a lower sun unrun, without a
/// table and without a message in TAPE6 (a sky path from the ground at zenith 60° by a sun
/// at 88.5°, alone or among a day's suns; docs/accuracy.md, "A day's scattered sunlight"),
/// so such a plan would be accepted and fail to build, after the runs before it.
pub const SCATTERED_MAX_ZENITH_DEG: f64 = 88.0;

/// Puts the suns of a day at `zenith_deg` (each rounded to the 0.001° a deck holds, then
/// sorted, repeats dropped) on day `day_of_year` in `plan`, as [`add_sun`] puts one: the
/// direct beam of every sun at every altitude of the sun's rows, so that one build's
/// solar table holds them all (`SpectralSolar::further_suns`) and the tracer interpolates
/// between them (`crate::solar`). With `scattered`, every sun also runs every sunlit slant
/// and sky path (the runs of [`add_sun`]'s scattered sunlight, once per sun), and the
/// tracer interpolates those between the suns too (`crate::scattered`); slabs, whose
/// tables hold one sun's scattered sunlight, are then refused ([`add_slabs`]).
///
/// # Errors
/// No zenith angle; one that is not finite or not within 0 to below 90° once rounded; a
/// day outside 1–366; `scattered` with several suns in a plan that has slabs, or with a sun
/// past [`SCATTERED_MAX_ZENITH_DEG`].
pub fn add_suns(
    plan: &mut AtmospherePlan,
    zenith_deg: &[f64],
    day_of_year: u16,
    scattered: bool,
) -> Result<(), AtmosphereError> {
    let plan_error = |m: String| AtmosphereError::from(AtmosphereErrorKind::Plan(m));
    let mut zeniths: Vec<f64> = zenith_deg.iter().map(|&z| round3(z)).collect();
    if let Some(z) = zeniths.iter().find(|z| !z.is_finite()) {
        return Err(plan_error(format!(
            "expected the sun's zenith angle from 0 to below 90 deg, found {z}"
        )));
    }
    zeniths.sort_by(f64::total_cmp);
    zeniths.dedup();
    let Some((&first, further)) = zeniths.split_first() else {
        return Err(plan_error("expected at least one sun zenith angle".into()));
    };
    if scattered && let Some(low) = zeniths.iter().find(|&&z| z > SCATTERED_MAX_ZENITH_DEG) {
        let what = if further.is_empty() {
            "a higher sun"
        } else {
            "a range that ends before the sun is that low"
        };
        return Err(plan_error(format!(
            "the sunlight the air scatters is planned for suns up to \
             {SCATTERED_MAX_ZENITH_DEG} deg from the zenith, and a sun at {low} deg is given \
             (LOWTRAN7 leaves some sunlit paths of a lower sun unrun): plan {what}, or the \
             direct beam alone"
        )));
    }
    if scattered && !further.is_empty() && plan.slabs.is_some() {
        return Err(plan_error(format!(
            "a slab table holds the scattered sunlight of one sun, and {} suns are given: \
             plan the direct beam alone for several suns beside slabs, or one sun with its \
             scattered sunlight",
            zeniths.len()
        )));
    }
    // The scattered sky changes faster with the observer's altitude than the thermal one
    // (the aerosol is mixed through the lowest km or two): the sun's rows, on which the
    // scattered sky is run too, add the slant grid's 500, 700 and 1500 m below the
    // highest sky row, where the night's 300 m-1 km gap made the interpolated
    // 3.4-4.1 um hazy sky 6 % low at 650 m (docs/accuracy.md).
    let top = plan.sky_altitude_m.last().copied().unwrap_or(0.0);
    let mut sky = plan.sky_altitude_m.clone();
    if scattered {
        sky.extend(DAY_SKY_ALTITUDE_M.iter().filter(|&&h| h < top));
        sky.sort_by(f64::total_cmp);
        sky.dedup();
    }
    let sun = PlanSun {
        zenith_deg: first,
        further_zenith_deg: further.to_vec(),
        day_of_year,
        altitude_m: sky,
        relative_azimuth_deg: if scattered {
            RELATIVE_AZIMUTH_DEG.to_vec()
        } else {
            Vec::new()
        },
    };
    // The rounding may carry 89.9996 to 90: checked after it.
    sun.validate()
        .map_err(|e| AtmosphereError::from(AtmosphereErrorKind::Plan(e.kind.to_string())))?;
    plan.sun = Some(sun);
    Ok(())
}

/// The sun rows of a day's table between its lit moments: every 5° to 80°, every 2° to
/// 86°, every degree to 87°, then every half degree to 89.5° (toward the horizon the air
/// mass, and the beam's curvature in it, grow fastest: with whole degrees past 87° the
/// 8–14 µm beam halfway between 88° and 89° was 2 % low). The direct beam interpolated between rows this far
/// apart is within the error `docs/accuracy.md` tables ("One atmosphere for a day's
/// suns", measured against LOWTRAN7 in `tests/tests/solar_day.rs`).
#[must_use]
pub fn day_sun_grid_deg() -> Vec<f64> {
    let mut grid: Vec<f64> = (0..=16).map(|i| 5.0 * f64::from(i)).collect();
    grid.extend([82.0, 84.0, 86.0, 87.0, 87.5, 88.0, 88.5, 89.0, 89.5]);
    grid
}

/// The sun rows of a day's table for the suns `lit_zenith_deg` (the zenith angles of every
/// lit moment, any order): each of them (rounded to the 0.001° a deck holds, each once),
/// and the rows of [`day_sun_grid_deg`] between the first and the last that are not within
/// a tenth of their step of one of them (a row that close adds a run and nothing to the
/// interpolation; leaving it out widens a step by a tenth at most on each side). A frame at one of the moments is then lit by its own row, and a moment
/// between them by rows close enough to interpolate.
#[must_use]
pub fn day_sun_rows(lit_zenith_deg: &[f64]) -> Vec<f64> {
    let mut rows: Vec<f64> = lit_zenith_deg
        .iter()
        .map(|&z| round3(z))
        .filter(|z| z.is_finite())
        .collect();
    rows.sort_by(f64::total_cmp);
    rows.dedup();
    let (Some(&first), Some(&last)) = (rows.first(), rows.last()) else {
        return rows;
    };
    let grid = day_sun_grid_deg();
    let mut fill = Vec::new();
    for (k, &g) in grid.iter().enumerate() {
        let step = grid
            .get(k + 1)
            .map_or(grid[k] - grid[k.saturating_sub(1)], |next| next - g);
        let near = rows.iter().any(|&z| (z - g).abs() < 0.1 * step);
        if g > first && g < last && !near {
            fill.push(g);
        }
    }
    rows.extend(fill);
    rows.sort_by(f64::total_cmp);
    // Two moments a hair apart (a morning's and an evening's sun) make a secant of two
    // nearly equal beams, whose rounding would bend the cubic's slopes around them: a row
    // within a fiftieth of its grid step of the one kept before it is left out (the last
    // row is kept, its neighbour left out instead); a moment left out is then
    // interpolated over that fiftieth.
    let step_at = |z: f64| {
        grid.windows(2)
            .find(|w| z <= w[1])
            .map_or(0.5, |w| w[1] - w[0])
    };
    let mut kept: Vec<f64> = Vec::with_capacity(rows.len());
    for (k, &z) in rows.iter().enumerate() {
        match kept.last() {
            Some(&before) if z - before < 0.02 * step_at(z) => {
                if k + 1 == rows.len() {
                    kept.pop();
                    kept.push(z);
                }
            }
            _ => kept.push(z),
        }
    }
    kept
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
    /// A slant path of the sunlit tables: [`Path::Down`] with the sunlight it scatters
    /// from the sun `sun_zenith_deg` from the zenith, the line of sight `azimuth_deg` from
    /// the sun's vertical plane.
    DownSunlit {
        /// Observer altitude, metres.
        altitude_m: f64,
        /// Nadir angle, degrees.
        nadir_deg: f64,
        /// Azimuth from the sun's, degrees, 0–180.
        azimuth_deg: f64,
        /// The sun's zenith angle, degrees (one of the plan's suns).
        sun_zenith_deg: f64,
    },
    /// A sky path of the sunlit tables: [`Path::Up`] with the sunlight it scatters from
    /// the sun `sun_zenith_deg` from the zenith.
    UpSunlit {
        /// Observer altitude, metres.
        altitude_m: f64,
        /// Zenith angle, degrees.
        zenith_deg: f64,
        /// Azimuth from the sun's, degrees, 0–180.
        azimuth_deg: f64,
        /// The sun's zenith angle, degrees (one of the plan's suns).
        sun_zenith_deg: f64,
    },
    /// A slab that ends above the ground ([`PlanSlabs`]): from an observer at
    /// `observer_m` to `target_m`, `zenith_deg` from straight up at the observer (above 90
    /// down, below it up).
    Slab {
        /// Observer altitude, metres.
        observer_m: f64,
        /// Target altitude, metres.
        target_m: f64,
        /// Zenith angle at the observer, degrees.
        zenith_deg: f64,
    },
    /// A slab with the sunlight it scatters, the line of sight `azimuth_deg` from the sun's
    /// vertical plane.
    SlabSunlit {
        /// Observer altitude, metres.
        observer_m: f64,
        /// Target altitude, metres.
        target_m: f64,
        /// Zenith angle at the observer, degrees.
        zenith_deg: f64,
        /// Azimuth from the sun's, degrees, 0–180.
        azimuth_deg: f64,
    },
    /// The sun's direct beam from the top of the atmosphere down to `altitude_m`, the sun
    /// `zenith_deg` from straight up, on day `day_of_year` (a direct solar irradiance run).
    Sun {
        /// Altitude the beam reaches, metres.
        altitude_m: f64,
        /// The sun's zenith angle, degrees.
        zenith_deg: f64,
        /// Day of the year, 1–366.
        day_of_year: u16,
    },
    /// A phase-function run of a day's table: a short slab in the layer above
    /// `altitude_m` that scatters the sun by `scattering_deg` (`phase::slab`), for the
    /// interpolation between the table's suns.
    Phase {
        /// The layer's bottom, metres (one of the sun's altitudes).
        altitude_m: f64,
        /// The scattering angle, degrees.
        scattering_deg: f64,
    },
}

type Key = (u8, i64, i64, i64, i64);

fn key(p: &Path) -> Key {
    #[allow(clippy::cast_possible_truncation)]
    let q = |x: f64| (x * 1000.0).round() as i64;
    match *p {
        Path::Down {
            altitude_m,
            nadir_deg,
        } => (0, q(altitude_m), q(nadir_deg), 0, 0),
        Path::Up {
            altitude_m,
            zenith_deg,
        } => (1, q(altitude_m), q(zenith_deg), 0, 0),
        // After every thermal path: a plan's runs without a sun keep their numbers.
        Path::Sun {
            altitude_m,
            zenith_deg,
            ..
        } => (2, q(altitude_m), q(zenith_deg), 0, 0),
        // After the direct beam's: a plan with a sun but no azimuths numbers as before. By
        // sun first: a plan of one sun numbers its sunlit paths as it did before suns had
        // a field of their own, and each further sun's follow the first's.
        Path::DownSunlit {
            altitude_m,
            nadir_deg,
            azimuth_deg,
            sun_zenith_deg,
        } => (
            3,
            q(sun_zenith_deg),
            q(altitude_m),
            q(nadir_deg),
            q(azimuth_deg),
        ),
        Path::UpSunlit {
            altitude_m,
            zenith_deg,
            azimuth_deg,
            sun_zenith_deg,
        } => (
            4,
            q(sun_zenith_deg),
            q(altitude_m),
            q(zenith_deg),
            q(azimuth_deg),
        ),
        // After every other path: a plan without slabs numbers as before.
        Path::Slab {
            observer_m,
            target_m,
            zenith_deg,
        } => (5, q(observer_m), q(target_m), q(zenith_deg), 0),
        Path::SlabSunlit {
            observer_m,
            target_m,
            zenith_deg,
            azimuth_deg,
        } => (6, q(observer_m), q(target_m), q(zenith_deg), q(azimuth_deg)),
        // Last: a plan without them numbers as before.
        Path::Phase {
            altitude_m,
            scattering_deg,
        } => (7, q(altitude_m), q(scattering_deg), 0, 0),
    }
}

/// The slabs of `observer_m`, down then up: `(targets, angles, zenith of an angle)` with
/// the observer's own row (the path of no length) in its place, last down, first up.
#[allow(clippy::type_complexity)]
fn slab_tables(slabs: &PlanSlabs, observer_m: f64) -> [Option<(Vec<f64>, &[f64], bool)>; 2] {
    let (mut below, above) = slabs.targets_of(observer_m);
    let down = (!below.is_empty()).then(|| {
        below.push(observer_m);
        (below, slabs.nadir_deg.as_slice(), true)
    });
    let up = (!above.is_empty()).then(|| {
        let mut rows = vec![observer_m];
        rows.extend(above);
        (rows, slabs.zenith_deg.as_slice(), false)
    });
    [down, up]
}

/// The slab paths of `plan`, thermal (`azimuths` empty) or sunlit at each azimuth:
/// `[observer][down, up][target][angle][azimuth]`, the observer's own row left out (it is
/// the observer's value copied: compared exactly).
#[allow(clippy::float_cmp)]
fn slab_paths(plan: &AtmospherePlan, azimuths: Option<&[f64]>) -> Vec<Path> {
    let mut out = Vec::new();
    let Some(slabs) = &plan.slabs else {
        return out;
    };
    for &o in &plan.observers_m {
        for (targets, angles, down) in slab_tables(slabs, o).into_iter().flatten() {
            for &t in targets.iter().filter(|&&t| t != o) {
                for &a in angles {
                    let zenith_deg = if down { 180.0 - a } else { a };
                    match azimuths {
                        None => out.push(Path::Slab {
                            observer_m: o,
                            target_m: t,
                            zenith_deg,
                        }),
                        Some(az) => out.extend(az.iter().map(|&azimuth_deg| Path::SlabSunlit {
                            observer_m: o,
                            target_m: t,
                            zenith_deg,
                            azimuth_deg,
                        })),
                    }
                }
            }
        }
    }
    out
}

/// The direct beam's runs of one sun `zenith_deg` of `sun`, by altitude.
fn sun_paths_at(sun: &PlanSun, zenith_deg: f64) -> impl Iterator<Item = Path> + '_ {
    sun.altitude_m.iter().map(move |&a| Path::Sun {
        altitude_m: a,
        zenith_deg,
        day_of_year: sun.day_of_year,
    })
}

/// The direct beam's runs of every sun of `sun`, `[zenith][altitude]`.
fn sun_paths(sun: &PlanSun) -> impl Iterator<Item = Path> + '_ {
    sun.zeniths_deg()
        .into_iter()
        .flat_map(|z| sun_paths_at(sun, z))
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
    if let Some(sun) = &plan.sun {
        out.extend(sun_paths(sun));
        for z in sun.zeniths_deg() {
            out.extend(sunlit_slant_paths(plan, sun, z));
            out.extend(sunlit_sky_paths(plan, sun, z));
        }
    }
    out.extend(slab_paths(plan, None));
    if let Some(sun) = plan
        .sun
        .as_ref()
        .filter(|s| !s.relative_azimuth_deg.is_empty())
    {
        out.extend(slab_paths(plan, Some(&sun.relative_azimuth_deg)));
    }
    out.extend(phase::phase_paths(plan));
    out
}

/// The sunlit slant paths of the sun `sun_zenith_deg`, `[altitude][nadir][azimuth]`;
/// none without relative azimuths.
fn sunlit_slant_paths(plan: &AtmospherePlan, sun: &PlanSun, sun_zenith_deg: f64) -> Vec<Path> {
    let mut out = Vec::new();
    for &a in &plan.slant_altitude_m {
        for &n in &plan.slant_nadir_deg {
            out.extend(sun.relative_azimuth_deg.iter().map(|&az| Path::DownSunlit {
                altitude_m: a,
                nadir_deg: n,
                azimuth_deg: az,
                sun_zenith_deg,
            }));
        }
    }
    out
}

/// The sunlit sky paths of the sun `sun_zenith_deg`, `[altitude][zenith][azimuth]`, on
/// the sun's altitudes; none without relative azimuths.
fn sunlit_sky_paths(plan: &AtmospherePlan, sun: &PlanSun, sun_zenith_deg: f64) -> Vec<Path> {
    let mut out = Vec::new();
    for &a in &sun.altitude_m {
        for &z in &plan.sky_zenith_deg {
            out.extend(sun.relative_azimuth_deg.iter().map(|&az| Path::UpSunlit {
                altitude_m: a,
                zenith_deg: z,
                azimuth_deg: az,
                sun_zenith_deg,
            }));
        }
    }
    out
}

/// The run number (the index in [`paths`]) of each of `plan`'s direct beams,
/// `[sun][altitude]` over [`PlanSun::zeniths_deg`] and the sun's altitudes: the order of
/// `SpectralSolar::apparent_zenith_deg`. Empty without a sun.
#[must_use]
pub fn sun_runs(plan: &AtmospherePlan) -> Vec<usize> {
    let Some(sun) = &plan.sun else {
        return Vec::new();
    };
    let index: BTreeMap<Key, usize> = paths(plan)
        .iter()
        .enumerate()
        .map(|(i, p)| (key(p), i))
        .collect();
    sun_paths(sun)
        .filter_map(|p| index.get(&key(&p)).copied())
        .collect()
}

/// The plan's unique paths, in a fixed order (slant paths by altitude and angle, then sky
/// paths, then the sun's by altitude): run `i` of a build is path `i`.
#[must_use]
pub fn paths(plan: &AtmospherePlan) -> Vec<Path> {
    let mut map: BTreeMap<Key, Path> = BTreeMap::new();
    for p in wanted(plan) {
        map.entry(key(&p)).or_insert(p);
    }
    map.into_values().collect()
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // nodes are copied, not computed
mod tests;
