//! A path's LOWTRAN7 card deck: the standard model's cards, a radiosonde's profile as
//! LOWTRAN7's user model, and the geometry, sun and aerosol of each kind of path.

use super::*;

pub(crate) fn standard_cards(model: i64, itype: i64, card3: Card3, v: [f64; 3]) -> Cards {
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

/// The LOWTRAN7 card deck of one path: thermal radiance (IEMSCT = 1), the plan's aerosol
/// (none without one: IHAZE 0), no multiple scattering, the plan's spectral range; case 2A (ITYPE 2, H1, H2, ANGLE =
/// 180 − nadir) down, case 3A (ITYPE 3, H1, ANGLE = zenith) up. The sun's paths are
/// direct solar irradiance runs (IEMSCT = 3, ITYPE 3; card 3's alternate form: H1, ANGLE =
/// the sun's geometric zenith angle, IDAY, ISOURC = 0, the sun). LOWTRAN7 takes that
/// ANGLE as the apparent zenith at H1: the deck is the first guess, and the build runs
/// the beam again at the apparent angle whose refracted ray leaves toward the sun
/// ([`crate::refraction::apparent_zenith`]). The sunlit paths' PARM2 is the sun's
/// geometric angle as it is: LOWTRAN7 bends each scattering point's path to the sun
/// itself.
///
/// # Errors
/// As [`radiosonde_profile`].
pub fn deck(plan: &AtmospherePlan, path: &Path) -> Result<CardDeck, AtmosphereError> {
    let (itype, iemsct, card3) = match *path {
        Path::Down {
            altitude_m,
            nadir_deg,
        }
        | Path::DownSunlit {
            altitude_m,
            nadir_deg,
            ..
        } => (
            2,
            1,
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
        }
        | Path::UpSunlit {
            altitude_m,
            zenith_deg,
            ..
        } => (
            3,
            1,
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
        Path::Slab {
            observer_m,
            target_m,
            zenith_deg,
        }
        | Path::SlabSunlit {
            observer_m,
            target_m,
            zenith_deg,
            ..
        } => (
            2,
            1,
            Card3::Path {
                h1_km: round3(observer_m / 1000.0),
                h2_km: round3(target_m / 1000.0),
                angle_deg: round3(zenith_deg),
                range_km: 0.0,
                beta_deg: 0.0,
                ro_km: 0.0,
                len: 0,
            },
        ),
        Path::Phase {
            altitude_m,
            scattering_deg,
        } => {
            let s = super::phase::slab(altitude_m, scattering_deg, plan.path_end_m);
            (
                2,
                1,
                Card3::Path {
                    h1_km: round3(s.observer_m / 1000.0),
                    h2_km: round3(s.target_m / 1000.0),
                    angle_deg: round3(s.zenith_deg),
                    range_km: 0.0,
                    beta_deg: 0.0,
                    ro_km: 0.0,
                    len: 0,
                },
            )
        }
        Path::Sun {
            altitude_m,
            zenith_deg,
            day_of_year,
        } => (
            3,
            3,
            Card3::DirectSolar {
                h1_km: round3(altitude_m / 1000.0),
                h2_km: 0.0,
                angle_deg: round3(zenith_deg),
                iday: i64::from(day_of_year),
                ro_km: 0.0,
                isourc: 0,
                anglem_deg: 0.0,
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
    cards.card1.iemsct = iemsct;
    let lit = match *path {
        Path::DownSunlit {
            azimuth_deg,
            sun_zenith_deg,
            ..
        }
        | Path::UpSunlit {
            azimuth_deg,
            sun_zenith_deg,
            ..
        } => Some((azimuth_deg, Some(sun_zenith_deg))),
        // A slab table holds the plan's one sun's scattered sunlight.
        Path::SlabSunlit { azimuth_deg, .. } => Some((azimuth_deg, None)),
        // The phase function's runs have a sun of their own.
        Path::Phase {
            altitude_m,
            scattering_deg,
        } => Some((
            super::phase::slab(altitude_m, scattering_deg, plan.path_end_m).azimuth_deg,
            Some(super::phase::SUN_ZENITH_DEG),
        )),
        _ => None,
    };
    if let (Some((azimuth_deg, sun_zenith_deg)), Some(sun)) = (lit, &plan.sun) {
        // IEMSCT 2, single scattering; card 3A1: IPARM 2 (the geometry given as angles),
        // IPH 2 (LOWTRAN's Mie phase functions of its aerosol models), IDAY, ISOURC 0
        // (the sun); card 3A2: PARM1 the azimuth of the sun from the line of sight,
        // PARM2 the sun's geometric zenith angle (LOWTRAN7's SSGEO bends the path from
        // each scattering point to the sun by its own BENDING: PARM2 is not apparent).
        cards.card1.iemsct = 2;
        cards.geometry.scattering = Some(sun_scattering(
            sun.day_of_year,
            azimuth_deg,
            sun_zenith_deg.unwrap_or(sun.zenith_deg),
        ));
    }
    set_aerosol(&mut cards, plan.aerosol.as_ref());
    Ok(CardDeck {
        steps: vec![Step::Full(Box::new(cards))],
    })
}

/// LOWTRAN7's single-scattering cards for a sun `zenith_deg` from the zenith and
/// `azimuth_deg` from the line of sight's vertical plane, on `day_of_year`: card 3A1
/// IPARM 2, IPH 2 (Mie phase functions), IDAY; card 3A2 PARM1 the azimuth, PARM2 the
/// zenith angle, each to the 0.001 deg a deck holds.
pub(crate) fn sun_scattering(day_of_year: u16, azimuth_deg: f64, zenith_deg: f64) -> Scattering {
    Scattering {
        card3a1: [2, 2, i64::from(day_of_year), 0],
        card3a2: [
            round3(azimuth_deg),
            round3(zenith_deg),
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        phase_function: Vec::new(),
    }
}

/// A plan's boundary-layer aerosol on card 2 (IHAZE, VIS, WSS); none leaves the cards as
/// they are.
pub(crate) fn set_aerosol(cards: &mut Cards, aerosol: Option<&PlanAerosol>) {
    if let Some(a) = aerosol {
        cards.card2.ihaze = a.model.ihaze();
        cards.card2.vis_km = round3(a.visibility_m / 1000.0);
        cards.card2.wss_m_s = a.wind_speed_m_s.unwrap_or(0.0);
    }
}
