//! Broadband thermal loads at the ground from LOWTRAN7: the direct normal and diffuse
//! horizontal sunlight at each of a day's sun positions, and the sky's downwelling
//! longwave irradiance, what a surface energy balance takes from the atmosphere.
//!
//! Like [`crate::plan`], this module plans and assembles; running LOWTRAN7 is the tool's
//! business. A [`LoadsPlan`] ([`make_loads_plan`]) lists the sun's zenith angles and the
//! lines of sight of the two hemisphere quadratures ([`rule`]); [`paths`] and [`deck`]
//! make one LOWTRAN7 card deck per path, every path starting at the ground (LOWTRAN7's
//! 0 km, the model's first level):
//!
//! - per sun zenith angle z (geometric), the **direct normal irradiance** (DNI): a direct
//!   solar irradiance run (IEMSCT = 3, ITYPE 3, the day's IDAY, ISOURC 0), `DNI =
//!   ∫ E_toa(ν) τ_sun(ν) dν` over the solar range. The deck's ANGLE = z is the first
//!   guess: LOWTRAN7 takes ANGLE as the apparent zenith, so the build runs it again at the
//!   angle whose refracted ray leaves toward z ([`crate::refraction`]; a sun bent less
//!   than 0.03° stays at z);
//! - per sun zenith angle, the **diffuse horizontal irradiance** (DHI): one solar
//!   scattering run per line of sight of [`rule::diffuse_nodes`] (IEMSCT = 2 with
//!   multiple scattering, IMULT = 1: LOWTRAN7's two-stream flux adding of Isaacs et al.
//!   1986, whose source function the line of sight integrates; single scattering alone
//!   leaves out a quarter of the hazy sky, docs/accuracy.md), `DHI = Σ wᵢ ∫ L_scat,ᵢ dν`;
//! - once, the **longwave irradiance** (E_LW): one thermal radiance run (IEMSCT = 1, with
//!   IMULT = 1 so that an aerosol scatters the sky's emission rather than emitting in
//!   proportion to its extinction) per line of sight of [`rule::longwave_nodes`], over
//!   the thermal range, plus a blackbody at the ground's air temperature below it, where
//!   the lower atmosphere is opaque ([`assemble`]).
//!
//! Spectral integrals are the trapezoid in wavenumber over a run's own grid, the rule
//! LOWTRAN7's own `INTEGRATED` lines use.

mod assemble;
pub mod rule;
pub mod weathered;

use std::collections::BTreeMap;

use irsig_formats::radtran::tape5::{Card3, CardDeck, Step};
use irsig_model::loads::{LoadsPlan, LoadsSun};
use irsig_model::{PlanAerosol, PlanModel};

use crate::error::{AtmosphereError, AtmosphereErrorKind};
use crate::plan::{radiosonde_profile, round3, set_aerosol, standard_cards, sun_scattering};

pub use assemble::{LongwaveOutside, SunLoads, assemble, kasten_young_air_mass, sun_loads_at};
pub use rule::{DiffuseRule, diffuse_nodes, longwave_nodes};

/// The solar runs' spectral range and step, cm⁻¹: 2500–35 720 every 20, 4.000 µm to
/// 0.27996 µm (the solar absorptance of a material record is 0.3–4 µm; below 0.29 µm the
/// ozone column leaves nothing at the ground). A 5 cm⁻¹ step (LOWTRAN7's finest) changes
/// the DNI by 0.01 W m⁻² and the DHI by 0.002 W m⁻²; 40 cm⁻¹ by 0.5 W m⁻²
/// (docs/accuracy.md).
pub const SOLAR_WAVENUMBER_PER_CM: [f64; 3] = [2500.0, 35_720.0, 20.0];

/// The thermal runs' spectral range and step, cm⁻¹: 20–5000 every 20 (500 µm to 2 µm).
/// Below 20 cm⁻¹ the sky is a blackbody at the ground's air temperature
/// ([`LongwaveOutside`], 0.02 W m⁻², within 10⁻⁴ W m⁻² of LOWTRAN7's own sky over 5–20
/// cm⁻¹); above 5000 cm⁻¹ the sky's emission is below 10⁻⁴ W m⁻² and left out; a 5 cm⁻¹
/// step changes E_LW by 0.05 W m⁻².
pub const THERMAL_WAVENUMBER_PER_CM: [f64; 3] = [20.0, 5000.0, 20.0];

/// Gauss–Legendre nodes in cos θ of the longwave rule: 8 are within 0.02 W m⁻² of 16.
pub const LONGWAVE_NODES: usize = 8;

fn bad(message: String) -> AtmosphereError {
    AtmosphereErrorKind::Loads(message).into()
}

/// A plan of a day's loads: `model`, `day_of_year` (1–366), the sun at each of
/// `zeniths_deg` (rounded to the 0.001° a deck holds, sorted, repeats dropped), each with
/// [`DiffuseRule::DEFAULT`]'s lines of sight, [`LONGWAVE_NODES`] longwave lines of sight,
/// the default spectral ranges, no aerosol and a black ground.
///
/// # Errors
/// No zenith angle; one that is not finite or not within 0 to below 90° (a sun at or
/// below the horizon gives no direct light, and LOWTRAN7 cannot make its path); a day
/// outside 1–366; a model the plan refuses.
pub fn make_loads_plan(
    name: &str,
    model: PlanModel,
    day_of_year: u16,
    zeniths_deg: &[f64],
) -> Result<LoadsPlan, AtmosphereError> {
    make_loads_plan_with(name, model, day_of_year, zeniths_deg, &DiffuseRule::DEFAULT)
}

/// [`make_loads_plan`] with another diffuse rule (a finer one, to measure the default's).
///
/// # Errors
/// As [`make_loads_plan`].
pub fn make_loads_plan_with(
    name: &str,
    model: PlanModel,
    day_of_year: u16,
    zeniths_deg: &[f64],
    rule: &DiffuseRule,
) -> Result<LoadsPlan, AtmosphereError> {
    if zeniths_deg.is_empty() {
        return Err(bad(
            "a loads plan needs at least one sun zenith angle".into()
        ));
    }
    if !(1..=366).contains(&day_of_year) {
        return Err(bad(format!(
            "expected a day of the year from 1 to 366, found {day_of_year}"
        )));
    }
    let mut zeniths = Vec::with_capacity(zeniths_deg.len());
    for &z in zeniths_deg {
        let r = round3(z);
        if !(z.is_finite() && (0.0..90.0).contains(&r)) {
            return Err(bad(format!(
                "the sun at {z} deg from the zenith: expected 0 to below 90 deg (at or below \
                 the horizon it gives no direct light; 89.999 is the last a deck holds)"
            )));
        }
        zeniths.push(r);
    }
    zeniths.sort_by(f64::total_cmp);
    zeniths.dedup();
    let plan = LoadsPlan {
        name: name.to_owned(),
        model,
        aerosol: None,
        ground_albedo: 0.0,
        day_of_year,
        solar_wavenumber_per_cm: SOLAR_WAVENUMBER_PER_CM,
        thermal_wavenumber_per_cm: THERMAL_WAVENUMBER_PER_CM,
        longwave: longwave_nodes(LONGWAVE_NODES),
        sun: zeniths
            .into_iter()
            .map(|z| LoadsSun {
                zenith_deg: z,
                diffuse: diffuse_nodes(z, rule),
            })
            .collect(),
    };
    plan.validate().map_err(|e| bad(e.to_string()))?;
    Ok(plan)
}

/// Puts `aerosol` in every run of `plan` (card 2), its visibility rounded to the whole
/// metres a deck holds, as [`crate::plan::add_aerosol`] does.
///
/// # Errors
/// What [`PlanAerosol::validate`] refuses; the message names the field.
pub fn add_aerosol(plan: &mut LoadsPlan, aerosol: PlanAerosol) -> Result<(), AtmosphereError> {
    let aerosol = PlanAerosol {
        visibility_m: aerosol.visibility_m.round(),
        wind_speed_m_s: aerosol.wind_speed_m_s.map(round3),
        ..aerosol
    };
    aerosol.validate().map_err(|e| bad(e.to_string()))?;
    plan.aerosol = Some(aerosol);
    Ok(())
}

/// Sets the ground's albedo of every run (card 1's SALB), rounded to the 0.01 a deck
/// holds.
///
/// # Errors
/// An albedo that is not finite or outside 0–1.
pub fn set_ground_albedo(plan: &mut LoadsPlan, albedo: f64) -> Result<(), AtmosphereError> {
    let a = (albedo * 100.0).round() / 100.0;
    if !(albedo.is_finite() && (0.0..=1.0).contains(&a)) {
        return Err(bad(format!(
            "expected a ground albedo from 0 to 1, found {albedo}"
        )));
    }
    plan.ground_albedo = a;
    Ok(())
}

/// One radiative-transfer path of a loads plan: each starts at the ground and looks up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LoadsPath {
    /// The sky's thermal radiance at `zenith_deg` (IEMSCT = 1).
    Longwave {
        /// Zenith angle of the line of sight, degrees.
        zenith_deg: f64,
    },
    /// The sun's direct beam at the ground, the sun at `sun_zenith_deg` (IEMSCT = 3).
    Direct {
        /// The sun's zenith angle, degrees.
        sun_zenith_deg: f64,
    },
    /// The sunlight the sky scatters toward the ground along a line of sight `zenith_deg`
    /// from the zenith and `azimuth_deg` from the sun's azimuth (IEMSCT = 2, IMULT = 1).
    Diffuse {
        /// The sun's zenith angle, degrees.
        sun_zenith_deg: f64,
        /// Zenith angle of the line of sight, degrees.
        zenith_deg: f64,
        /// Azimuth of the line of sight from the sun's, degrees, 0–180.
        azimuth_deg: f64,
    },
}

type Key = (u8, i64, u8, i64, i64);

pub(crate) fn key(p: &LoadsPath) -> Key {
    #[allow(clippy::cast_possible_truncation)]
    let q = |x: f64| (x * 1000.0).round() as i64;
    match *p {
        // The sky's emission first, then each sun: its beam, then its sky.
        LoadsPath::Longwave { zenith_deg } => (0, 0, 0, q(zenith_deg), 0),
        LoadsPath::Direct { sun_zenith_deg } => (1, q(sun_zenith_deg), 0, 0, 0),
        LoadsPath::Diffuse {
            sun_zenith_deg,
            zenith_deg,
            azimuth_deg,
        } => (1, q(sun_zenith_deg), 1, q(zenith_deg), q(azimuth_deg)),
    }
}

/// The plan's unique paths in a fixed order (the longwave lines of sight by zenith angle;
/// then per sun zenith angle, increasing, its direct beam and its diffuse lines of sight by
/// zenith angle and azimuth): run `i` of a build is path `i`. Lines of sight that round to
/// the same node are run once (their weights add in [`assemble`]).
#[must_use]
pub fn paths(plan: &LoadsPlan) -> Vec<LoadsPath> {
    let mut map: BTreeMap<Key, LoadsPath> = BTreeMap::new();
    let mut add = |p: LoadsPath| {
        map.entry(key(&p)).or_insert(p);
    };
    for &(zenith_deg, _) in &plan.longwave {
        add(LoadsPath::Longwave { zenith_deg });
    }
    for sun in &plan.sun {
        add(LoadsPath::Direct {
            sun_zenith_deg: sun.zenith_deg,
        });
        for &(zenith_deg, azimuth_deg, _) in &sun.diffuse {
            add(LoadsPath::Diffuse {
                sun_zenith_deg: sun.zenith_deg,
                zenith_deg,
                azimuth_deg,
            });
        }
    }
    map.into_values().collect()
}

/// The LOWTRAN7 card deck of one path: the plan's model (a radiosonde as the user model,
/// MODEL = 7), its aerosol on card 2 (IHAZE 0 without one) and its ground albedo (SALB);
/// ITYPE 3 from H1 = 0 (the ground) up. Longwave: IEMSCT = 1, IMULT = 1, ANGLE = the
/// zenith angle, the thermal range. Direct: IEMSCT = 3, card 3's alternate form (H1 = 0,
/// ANGLE = the sun's zenith angle, IDAY, ISOURC = 0), the solar range. Diffuse: IEMSCT =
/// 2, IMULT = 1, ANGLE = the line of sight's zenith angle, cards 3A1 `IPARM 2, IPH 2, IDAY,
/// ISOURC 0` (the geometry as angles; LOWTRAN's Mie phase functions of its aerosol models;
/// the sun) and 3A2 `PARM1` = the line of sight's azimuth from the sun's, `PARM2` = the
/// sun's zenith angle, the solar range.
///
/// # Errors
/// A radiosonde LOWTRAN7 cannot hold ([`radiosonde_profile`]).
pub fn deck(plan: &LoadsPlan, path: &LoadsPath) -> Result<CardDeck, AtmosphereError> {
    let up = |zenith_deg: f64| Card3::Path {
        h1_km: 0.0,
        h2_km: 0.0,
        angle_deg: round3(zenith_deg),
        range_km: 0.0,
        beta_deg: 0.0,
        ro_km: 0.0,
        len: 0,
    };
    let (iemsct, card3, range) = match *path {
        LoadsPath::Longwave { zenith_deg } => (1, up(zenith_deg), plan.thermal_wavenumber_per_cm),
        LoadsPath::Direct { sun_zenith_deg } => (
            3,
            Card3::DirectSolar {
                h1_km: 0.0,
                h2_km: 0.0,
                angle_deg: round3(sun_zenith_deg),
                iday: i64::from(plan.day_of_year),
                ro_km: 0.0,
                isourc: 0,
                anglem_deg: 0.0,
            },
            plan.solar_wavenumber_per_cm,
        ),
        LoadsPath::Diffuse { zenith_deg, .. } => (2, up(zenith_deg), plan.solar_wavenumber_per_cm),
    };
    let mut cards = match &plan.model {
        PlanModel::Standard(m) => standard_cards(i64::from(*m), 3, card3, range),
        PlanModel::Radiosonde(levels) => {
            let mut c = standard_cards(7, 3, card3, range);
            c.profile = Some(radiosonde_profile(levels)?);
            c
        }
    };
    cards.card1.mdef = i64::from(matches!(plan.model, PlanModel::Radiosonde(_)));
    cards.card1.iemsct = iemsct;
    // LOWTRAN7 turns multiple scattering off for IEMSCT 3 itself, saying so: not asked.
    cards.card1.imult = i64::from(iemsct != 3);
    cards.card1.salb = plan.ground_albedo;
    if let LoadsPath::Diffuse {
        sun_zenith_deg,
        azimuth_deg,
        ..
    } = *path
    {
        cards.geometry.scattering = Some(sun_scattering(
            plan.day_of_year,
            azimuth_deg,
            sun_zenith_deg,
        ));
    }
    set_aerosol(&mut cards, plan.aerosol.as_ref());
    Ok(CardDeck {
        steps: vec![Step::Full(Box::new(cards))],
    })
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // decks hold the values the plan gives them, copied
mod tests {
    use super::*;
    use irsig_formats::radtran::tape5;
    use irsig_model::AerosolModel;

    #[test]
    fn a_plan_has_one_beam_and_one_sky_per_sun_after_the_longwave() {
        let mut p = make_loads_plan(
            "day",
            PlanModel::Standard(6),
            172,
            &[30.00004, 0.0, 60.0, 30.0],
        )
        .unwrap();
        add_aerosol(
            &mut p,
            PlanAerosol {
                model: AerosolModel::Rural,
                visibility_m: 23_000.4,
                wind_speed_m_s: None,
            },
        )
        .unwrap();
        set_ground_albedo(&mut p, 0.204).unwrap();
        p.validate().unwrap();
        assert_eq!(p.ground_albedo, 0.2);
        let zeniths: Vec<f64> = p.sun.iter().map(|s| s.zenith_deg).collect();
        assert_eq!(zeniths, [0.0, 30.0, 60.0]);
        let all = paths(&p);
        let runs = LONGWAVE_NODES + p.sun.iter().map(|s| 1 + s.diffuse.len()).sum::<usize>();
        assert_eq!(all.len(), runs);
        assert!(matches!(all[0], LoadsPath::Longwave { .. }));
        assert_eq!(
            all[LONGWAVE_NODES],
            LoadsPath::Direct {
                sun_zenith_deg: 0.0
            }
        );
        // Each deck reads back as written, with the cards the path asks for.
        let calc = |path: &LoadsPath| {
            let text = tape5::write(&deck(&p, path).unwrap()).unwrap();
            let back = tape5::parse("d", &text).unwrap();
            assert_eq!(tape5::write(&back).unwrap(), text);
            back.calculations().remove(0)
        };
        let lw = calc(&all[0]);
        assert_eq!((lw.card1.itype, lw.card1.iemsct, lw.card1.imult), (3, 1, 1));
        assert_eq!(lw.card1.salb, 0.2);
        assert_eq!((lw.card2.ihaze, lw.card2.vis_km), (1, 23.0));
        assert_eq!(
            [lw.card4.v1_per_cm, lw.card4.v2_per_cm, lw.card4.dv_per_cm],
            THERMAL_WAVENUMBER_PER_CM
        );
        let beam = calc(&all[LONGWAVE_NODES]);
        assert_eq!(
            (beam.card1.itype, beam.card1.iemsct, beam.card1.imult),
            (3, 3, 0)
        );
        assert!(matches!(
            beam.card3,
            Card3::DirectSolar { h1_km, angle_deg, iday: 172, isourc: 0, .. }
                if h1_km == 0.0 && angle_deg == 0.0
        ));
        let LoadsPath::Diffuse {
            zenith_deg,
            azimuth_deg,
            ..
        } = all[LONGWAVE_NODES + 20]
        else {
            panic!("{:?}", all[LONGWAVE_NODES + 20])
        };
        let d = deck(&p, &all[LONGWAVE_NODES + 20]).unwrap();
        let Step::Full(cards) = &d.steps[0] else {
            panic!("a full deck")
        };
        assert_eq!((cards.card1.iemsct, cards.card1.imult), (2, 1));
        let sc = cards.geometry.scattering.as_ref().unwrap();
        assert_eq!(sc.card3a1, [2, 2, 172, 0]);
        assert_eq!(sc.card3a2[..2], [azimuth_deg, 30.0]);
        assert!(matches!(
            cards.geometry.card3,
            Card3::Path { angle_deg, h1_km, .. } if angle_deg == zenith_deg && h1_km == 0.0
        ));
        assert_eq!(
            [cards.card4.v1_per_cm, cards.card4.v2_per_cm],
            SOLAR_WAVENUMBER_PER_CM[..2]
        );
    }

    #[test]
    fn a_sun_at_or_below_the_horizon_no_sun_or_no_day_is_refused() {
        let m = || PlanModel::Standard(6);
        for (zeniths, day, says) in [
            (&[][..], 172, "at least one"),
            (&[90.0][..], 172, "below 90"),
            (&[89.9996][..], 172, "below 90"),
            (&[30.0, 95.0][..], 172, "95"),
            (&[-1.0][..], 172, "-1"),
            (&[f64::NAN][..], 172, "NaN"),
            (&[30.0][..], 0, "1 to 366"),
            (&[30.0][..], 367, "1 to 366"),
        ] {
            let e = make_loads_plan("d", m(), day, zeniths).unwrap_err();
            assert!(e.to_string().contains(says), "{zeniths:?} {day}: {e}");
        }
        let mut p = make_loads_plan("d", m(), 1, &[89.999]).unwrap();
        assert!(set_ground_albedo(&mut p, 1.2).is_err());
        assert!(set_ground_albedo(&mut p, f64::NAN).is_err());
        assert!(make_loads_plan("d", PlanModel::Standard(0), 1, &[10.0]).is_err());
    }
}
