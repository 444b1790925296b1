//! LOWTRAN7 card decks (`TAPE5`): the program's input, one 80-column card a line, read
//! with Fortran formats (LOWTRAN7 user's guide, AFGL-TR-88-0177, §3; the formats below are
//! the program's own `FORMAT` statements). Spec page: `formats/radtran/tape5.md`. A deck
//! is ASCII: LOWTRAN counts columns in bytes.
//!
//! A deck is a list of calculations. The first gives every card; each ends with card 5,
//! `IRPT`, which says what the next one changes: 1 every card, 3 the geometry (card 3)
//! only, 4 the spectral range (card 4) only; 0 (or 2, or above 4) ends the deck, and
//! LOWTRAN reads nothing after it.
//!
//! | card | when | format | fields |
//! | --- | --- | --- | --- |
//! | 1 | always | `13I5,F8.3,F7.2` | MODEL ITYPE IEMSCT IMULT M1–M6 MDEF IM NOPRT TBOUND SALB |
//! | 2 | always | `6I5,5F10.3` | IHAZE ISEASN IVULCN ICSTL ICLD IVSA VIS WSS WHH RAINRT GNDALT |
//! | 2A | ICLD 18–20 | `3F10.3,I10` | CTHIK CALT CEXT ISEED |
//! | 2B | IVSA = 1 | `3F10.3` | ZCVSA ZTVSA ZINVSA |
//! | 2C | MODEL 0 or 7, IM = 1 | `3I5,18A4` | ML IRD1 IRD2 TITLE |
//! | 2C1 | ML times | `F10.3,5E10.3,15A1` | ZMDL P T WMOL(1–3) JCHAR |
//! | 2C2 | IRD1 = 1 | `8E10.3` (two lines) | WMOL(4–12) |
//! | 2C3 | IRD2 = 1 | `10X,3F10.3,5I5` | AHAZE EQLWCZ RRATZ IHA1 ICLD1 IVUL1 ISEA1 ICHR |
//! | 3 | always | `6F10.3,I5` | H1 H2 ANGLE RANGE BETA RO LEN |
//! | 3 (alt.) | IEMSCT = 3 | `3F10.3,I5,5X,F10.3,I5,F10.3` | H1 H2 ANGLE IDAY RO ISOURC ANGLEM |
//! | 3A1 | IEMSCT = 2 | `4I5` | IPARM IPH IDAY ISOURC |
//! | 3A2 | IEMSCT = 2 | `8F10.3` | PARM1–4 TIME PSIPO ANGLEM G |
//! | 3B1, 3B2 | IPH = 1 | `I5`; `5E10.3` a line | NANGLS; ANGF F(1–4) |
//! | 4 | always | `3F10.3` | V1 V2 DV (cm⁻¹) |
//! | 5 | always | `I5` | IRPT |
//!
//! Fields are read as LOWTRAN's Fortran reads them: by column, blanks ignored, an all-blank
//! field (or one past the end of a short line) is 0, and a real without a decimal point has
//! an implied one (`F10.3` reads `1234` as 1.234). So an abbreviated deck whose card 2 is
//! just `    0` is a whole deck. The user-defined aerosol of card 2D (IHAZE = 7 or ICLD =
//! 11) and the vertical-structure profile with user levels (IVSA = 1 with MODEL 0 or 7)
//! are not read: such a deck is refused, naming the card.
//!
//! The writer puts every field in its columns with the fewest characters that read back
//! to the same number (`F10.3` as `%10.3f` where that is exact), so
//! `parse(write(deck)) == deck`; a number that does not fit its field is an error.

use super::{Edit, Source, TextLine, read_card, text_lines};
use crate::ParseError;
use crate::legacy::{Position, WriteError, WriteErrorKind};

mod write;
pub use write::write;

/// Card 1: the model atmosphere, the kind of path and what to compute.
#[derive(Debug, Clone, PartialEq)]
pub struct Card1 {
    /// Model atmosphere: 1 tropical, 2 mid-latitude summer, 3 mid-latitude winter, 4
    /// sub-arctic summer, 5 sub-arctic winter, 6 US Standard 1976, 7 user-defined (cards
    /// 2C), 0 horizontal path with user meteorological data.
    pub model: i64,
    /// Path type: 1 horizontal, 2 slant between two altitudes, 3 slant to space.
    pub itype: i64,
    /// 0 transmittance, 1 thermal radiance, 2 thermal + solar/lunar scattered radiance,
    /// 3 directly transmitted solar irradiance.
    pub iemsct: i64,
    /// 1 multiple scattering, 0 none.
    pub imult: i64,
    /// M1–M6: temperature/pressure, H2O, O3, CH4, N2O, CO profiles (0 = MODEL's).
    pub m: [i64; 6],
    /// MDEF: default profiles of the other gases.
    pub mdef: i64,
    /// 1 to read user profile cards (2C) for MODEL 0 or 7.
    pub im: i64,
    /// Printing of TAPE6: 0 full, 1 less, -1 more.
    pub noprt: i64,
    /// Boundary (ground) temperature, K; 0 for none.
    pub tbound_k: f64,
    /// Surface albedo, 0–1.
    pub salb: f64,
}

/// Card 2: aerosols, clouds and rain.
#[derive(Debug, Clone, PartialEq)]
pub struct Card2 {
    /// Boundary-layer aerosol model, 0 none.
    pub ihaze: i64,
    /// Season of the aerosol profile.
    pub iseasn: i64,
    /// Stratospheric aerosol profile and type.
    pub ivulcn: i64,
    /// Air-mass character of the Navy maritime model.
    pub icstl: i64,
    /// Cloud or rain model, 0 none.
    pub icld: i64,
    /// 1 to use the Army vertical-structure algorithm (card 2B).
    pub ivsa: i64,
    /// Surface meteorological range, km (0: the aerosol model's default).
    pub vis_km: f64,
    /// Current wind speed, m/s.
    pub wss_m_s: f64,
    /// 24-hour average wind speed, m/s.
    pub whh_m_s: f64,
    /// Rain rate, mm/h.
    pub rainrt_mm_h: f64,
    /// Altitude of the surface above sea level, km.
    pub gndalt_km: f64,
}

/// Card 2A: cirrus cloud (ICLD 18–20).
#[derive(Debug, Clone, PartialEq)]
pub struct Card2A {
    /// Cirrus thickness, km.
    pub cthik_km: f64,
    /// Cirrus base altitude, km.
    pub calt_km: f64,
    /// Cirrus extinction, km⁻¹.
    pub cext_per_km: f64,
    /// Random-number seed.
    pub iseed: i64,
}

/// Card 2B: the Army vertical-structure algorithm (IVSA = 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Card2B {
    /// Cloud ceiling height, km.
    pub zcvsa_km: f64,
    /// Cloud thickness, km.
    pub ztvsa_km: f64,
    /// Inversion layer height, km.
    pub zinvsa_km: f64,
}

/// One level of a user-defined atmosphere (card 2C1 and, when asked for, 2C2 and 2C3).
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileLevel {
    /// Altitude, km.
    pub zmdl_km: f64,
    /// Pressure in the unit `jchar[0]` says (blank or `A`: mb).
    pub p: f64,
    /// Temperature in the unit `jchar[1]` says (blank or `A`: K, `B`: °C).
    pub t: f64,
    /// WMOL(1–3): H2O, CO2, O3 in the units `jchar[2..5]` say.
    pub wmol: [f64; 3],
    /// JCHAR: 14 unit or default-model characters, `P T H2O CO2 O3 N2O CO CH4 O2 NO SO2
    /// NO2 NH3 HNO3` (blank: the first unit of each, a digit 1–6: that model's profile).
    pub jchar: String,
    /// Card 2C2 (IRD1 = 1): WMOL(4–12).
    pub wmol_more: Option<[f64; 9]>,
    /// Card 2C3 (IRD2 = 1): AHAZE EQLWCZ RRATZ and IHA1 ICLD1 IVUL1 ISEA1 ICHR.
    pub aerosol: Option<([f64; 3], [i64; 5])>,
    /// Where card 2C1 is.
    pub position: Position,
}

/// Card 2C and its levels: a user-defined atmosphere.
#[derive(Debug, Clone, PartialEq)]
pub struct UserProfile {
    /// IRD1: 1 to read card 2C2 at each level.
    pub ird1: i64,
    /// IRD2: 1 to read card 2C3 at each level.
    pub ird2: i64,
    /// The title (LOWTRAN keeps its first 20 characters).
    pub title: String,
    /// The levels, `ML` of them.
    pub levels: Vec<ProfileLevel>,
}

/// Card 3: the path.
#[derive(Debug, Clone, PartialEq)]
pub enum Card3 {
    /// Card 3 for IEMSCT 0–2.
    Path {
        /// Observer (or first) altitude, km.
        h1_km: f64,
        /// Final altitude, km (ITYPE 2), or 0.
        h2_km: f64,
        /// Zenith angle at H1, degrees (180 looks straight down).
        angle_deg: f64,
        /// Path length, km (ITYPE 1, or case 2C).
        range_km: f64,
        /// Earth-centre angle between H1 and H2, degrees (case 2B).
        beta_deg: f64,
        /// Earth radius, km (0: the model's).
        ro_km: f64,
        /// 1 for the long path through the tangent height.
        len: i64,
    },
    /// The alternate card 3 for IEMSCT = 3 (direct solar irradiance).
    DirectSolar {
        /// Observer altitude, km.
        h1_km: f64,
        /// Final altitude, km.
        h2_km: f64,
        /// Zenith angle at H1, degrees.
        angle_deg: f64,
        /// Day of the year.
        iday: i64,
        /// Earth radius, km.
        ro_km: f64,
        /// 0 sun, 1 moon (LOWTRAN7 prints `LUNAR SOURCE ONLY` for 1).
        isourc: i64,
        /// Moon phase angle, degrees.
        anglem_deg: f64,
    },
}

/// Cards 3A1, 3A2 and, for IPH = 1, 3B1/3B2: solar or lunar scattering (IEMSCT = 2).
#[derive(Debug, Clone, PartialEq)]
pub struct Scattering {
    /// IPARM IPH IDAY ISOURC.
    pub card3a1: [i64; 4],
    /// PARM1–4 TIME PSIPO ANGLEM G.
    pub card3a2: [f64; 8],
    /// IPH = 1: rows ANGF F(1–4) of the user phase function.
    pub phase_function: Vec<[f64; 5]>,
}

/// One geometry: card 3 and, for IEMSCT = 2, the scattering cards.
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// Card 3.
    pub card3: Card3,
    /// Cards 3A1–3B2 (IEMSCT = 2 only).
    pub scattering: Option<Scattering>,
    /// Where card 3 is.
    pub position: Position,
}

/// Card 4: the spectral range and step, cm⁻¹.
#[derive(Debug, Clone, PartialEq)]
pub struct Card4 {
    /// Initial wavenumber, cm⁻¹.
    pub v1_per_cm: f64,
    /// Final wavenumber, cm⁻¹.
    pub v2_per_cm: f64,
    /// Step, cm⁻¹ (5 at least: LOWTRAN's band model has 20 cm⁻¹ resolution sampled every 5).
    pub dv_per_cm: f64,
    /// Where it is.
    pub position: Position,
}

/// Every card of one calculation (the first of a deck, and every one after `IRPT = 1`).
#[derive(Debug, Clone, PartialEq)]
pub struct Cards {
    /// Card 1.
    pub card1: Card1,
    /// Card 2.
    pub card2: Card2,
    /// Card 2A (ICLD 18–20).
    pub card2a: Option<Card2A>,
    /// Card 2B (IVSA = 1).
    pub card2b: Option<Card2B>,
    /// Cards 2C–2C3 (MODEL 0 or 7 with IM = 1).
    pub profile: Option<UserProfile>,
    /// Card 3 (and 3A–3B).
    pub geometry: Geometry,
    /// Card 4.
    pub card4: Card4,
    /// Where card 1 is.
    pub position: Position,
}

/// One calculation of a deck, as the card before it (`IRPT`) asked for it.
#[derive(Debug, Clone, PartialEq)]
pub enum Step {
    /// Every card (the first calculation, or after `IRPT = 1`).
    Full(Box<Cards>),
    /// A new geometry only (after `IRPT = 3`).
    Geometry(Geometry),
    /// A new spectral range only (after `IRPT = 4`).
    Spectral(Card4),
}

/// A LOWTRAN7 card deck.
#[derive(Debug, Clone, PartialEq)]
pub struct CardDeck {
    /// The calculations in order; the first is always [`Step::Full`].
    pub steps: Vec<Step>,
}

/// One calculation with every card resolved (what LOWTRAN runs).
#[derive(Debug, Clone, PartialEq)]
pub struct Calculation {
    /// Card 1.
    pub card1: Card1,
    /// Card 2.
    pub card2: Card2,
    /// Cards 2C–2C3, if any.
    pub profile: Option<UserProfile>,
    /// Card 3.
    pub card3: Card3,
    /// Where this calculation's card 3 is.
    pub card3_position: Position,
    /// Card 4.
    pub card4: Card4,
}

impl Card3 {
    /// H1, km.
    #[must_use]
    pub fn h1_km(&self) -> f64 {
        match self {
            Card3::Path { h1_km, .. } | Card3::DirectSolar { h1_km, .. } => *h1_km,
        }
    }
}

impl CardDeck {
    /// Every calculation with the cards it inherits filled in.
    #[must_use]
    pub fn calculations(&self) -> Vec<Calculation> {
        let mut out: Vec<Calculation> = Vec::with_capacity(self.steps.len());
        for step in &self.steps {
            match step {
                Step::Full(c) => out.push(Calculation {
                    card1: c.card1.clone(),
                    card2: c.card2.clone(),
                    profile: c.profile.clone(),
                    card3: c.geometry.card3.clone(),
                    card3_position: c.geometry.position,
                    card4: c.card4.clone(),
                }),
                Step::Geometry(g) => {
                    if let Some(mut c) = out.last().cloned() {
                        c.card3 = g.card3.clone();
                        c.card3_position = g.position;
                        out.push(c);
                    }
                }
                Step::Spectral(c4) => {
                    if let Some(mut c) = out.last().cloned() {
                        c.card4 = c4.clone();
                        out.push(c);
                    }
                }
            }
        }
        out
    }
}

const CARD1: [(Edit, &str); 15] = [
    (Edit::I(5), "MODEL"),
    (Edit::I(5), "ITYPE"),
    (Edit::I(5), "IEMSCT"),
    (Edit::I(5), "IMULT"),
    (Edit::I(5), "M1"),
    (Edit::I(5), "M2"),
    (Edit::I(5), "M3"),
    (Edit::I(5), "M4"),
    (Edit::I(5), "M5"),
    (Edit::I(5), "M6"),
    (Edit::I(5), "MDEF"),
    (Edit::I(5), "IM"),
    (Edit::I(5), "NOPRT"),
    (Edit::F(8, 3), "TBOUND"),
    (Edit::F(7, 2), "SALB"),
];
const CARD2: [(Edit, &str); 11] = [
    (Edit::I(5), "IHAZE"),
    (Edit::I(5), "ISEASN"),
    (Edit::I(5), "IVULCN"),
    (Edit::I(5), "ICSTL"),
    (Edit::I(5), "ICLD"),
    (Edit::I(5), "IVSA"),
    (Edit::F(10, 3), "VIS"),
    (Edit::F(10, 3), "WSS"),
    (Edit::F(10, 3), "WHH"),
    (Edit::F(10, 3), "RAINRT"),
    (Edit::F(10, 3), "GNDALT"),
];
const CARD2A: [(Edit, &str); 4] = [
    (Edit::F(10, 3), "CTHIK"),
    (Edit::F(10, 3), "CALT"),
    (Edit::F(10, 3), "CEXT"),
    (Edit::I(10), "ISEED"),
];
const CARD2B: [(Edit, &str); 3] = [
    (Edit::F(10, 3), "ZCVSA"),
    (Edit::F(10, 3), "ZTVSA"),
    (Edit::F(10, 3), "ZINVSA"),
];
const CARD2C: [(Edit, &str); 3] = [
    (Edit::I(5), "ML"),
    (Edit::I(5), "IRD1"),
    (Edit::I(5), "IRD2"),
];
const CARD2C1: [(Edit, &str); 6] = [
    (Edit::F(10, 3), "ZMDL"),
    (Edit::F(10, 3), "P"),
    (Edit::F(10, 3), "T"),
    (Edit::F(10, 3), "WMOL(1)"),
    (Edit::F(10, 3), "WMOL(2)"),
    (Edit::F(10, 3), "WMOL(3)"),
];
const E10: (Edit, &str) = (Edit::F(10, 3), "WMOL");
const CARD2C3_REALS: [(Edit, &str); 3] = [
    (Edit::F(10, 3), "AHAZE"),
    (Edit::F(10, 3), "EQLWCZ"),
    (Edit::F(10, 3), "RRATZ"),
];
const CARD2C3_INTS: [(Edit, &str); 5] = [
    (Edit::I(5), "IHA1"),
    (Edit::I(5), "ICLD1"),
    (Edit::I(5), "IVUL1"),
    (Edit::I(5), "ISEA1"),
    (Edit::I(5), "ICHR"),
];
const CARD3: [(Edit, &str); 7] = [
    (Edit::F(10, 3), "H1"),
    (Edit::F(10, 3), "H2"),
    (Edit::F(10, 3), "ANGLE"),
    (Edit::F(10, 3), "RANGE"),
    (Edit::F(10, 3), "BETA"),
    (Edit::F(10, 3), "RO"),
    (Edit::I(5), "LEN"),
];
// 3F10.3,I5,5X,F10.3,I5,F10.3: the 5X is read as an ignored field.
const CARD3_SOLAR: [(Edit, &str); 8] = [
    (Edit::F(10, 3), "H1"),
    (Edit::F(10, 3), "H2"),
    (Edit::F(10, 3), "ANGLE"),
    (Edit::I(5), "IDAY"),
    (Edit::I(5), "blank (5X)"),
    (Edit::F(10, 3), "RO"),
    (Edit::I(5), "ISOURC"),
    (Edit::F(10, 3), "ANGLEM"),
];
const CARD3A1: [(Edit, &str); 4] = [
    (Edit::I(5), "IPARM"),
    (Edit::I(5), "IPH"),
    (Edit::I(5), "IDAY"),
    (Edit::I(5), "ISOURC"),
];
const CARD3A2: [(Edit, &str); 8] = [
    (Edit::F(10, 3), "PARM1"),
    (Edit::F(10, 3), "PARM2"),
    (Edit::F(10, 3), "PARM3"),
    (Edit::F(10, 3), "PARM4"),
    (Edit::F(10, 3), "TIME"),
    (Edit::F(10, 3), "PSIPO"),
    (Edit::F(10, 3), "ANGLEM"),
    (Edit::F(10, 3), "G"),
];
const CARD3B1: [(Edit, &str); 1] = [(Edit::I(5), "NANGLS")];
const CARD3B2: [(Edit, &str); 5] = [
    (Edit::F(10, 3), "ANGF"),
    (Edit::F(10, 3), "F(1)"),
    (Edit::F(10, 3), "F(2)"),
    (Edit::F(10, 3), "F(3)"),
    (Edit::F(10, 3), "F(4)"),
];
const CARD4: [(Edit, &str); 3] = [
    (Edit::F(10, 3), "V1"),
    (Edit::F(10, 3), "V2"),
    (Edit::F(10, 3), "DV"),
];
const CARD5: [(Edit, &str); 1] = [(Edit::I(5), "IRPT")];

/// ZM(34) in LOWTRAN's common blocks: a user profile has at most this many levels.
pub const MAX_LEVELS: usize = 34;

struct Reader<'a> {
    src: Source<'a>,
    lines: Vec<TextLine<'a>>,
    next: usize,
}

impl<'a> Reader<'a> {
    fn card(&mut self, name: &str) -> Result<TextLine<'a>, ParseError> {
        let Some(line) = self.lines.get(self.next).copied() else {
            return Err(self
                .src
                .eof_error(format!("expected card {name}, found the end of the deck")));
        };
        self.next += 1;
        Ok(line)
    }

    fn read(
        &mut self,
        name: &str,
        edits: &[(Edit, &str)],
    ) -> Result<(Vec<f64>, TextLine<'a>), ParseError> {
        let line = self.card(name)?;
        let values = read_card(self.src, &line, edits).map_err(|e| with_card(e, name))?;
        Ok((values, line))
    }

    fn error_at(&self, line: &TextLine<'_>, col: usize, width: usize, msg: String) -> ParseError {
        self.src.error(line.offset_of_column(col), width, msg)
    }
}

fn with_card(mut e: ParseError, name: &str) -> ParseError {
    e.message = format!("card {name}: {}", e.message);
    e
}

#[allow(clippy::cast_possible_truncation)]
fn int(v: f64) -> i64 {
    v as i64
}

fn check_choice(
    r: &Reader<'_>,
    line: &TextLine<'_>,
    field: usize,
    name: &str,
    value: i64,
    allowed: &[i64],
    what: &str,
) -> Result<(), ParseError> {
    if allowed.contains(&value) {
        return Ok(());
    }
    Err(r.error_at(
        line,
        field * 5,
        5,
        format!("card 1: expected {name} {what}, found {value}"),
    ))
}

fn read_geometry(r: &mut Reader<'_>, iemsct: i64) -> Result<Geometry, ParseError> {
    let (card3, line) = if iemsct == 3 {
        let (v, line) = r.read("3 (IEMSCT = 3)", &CARD3_SOLAR)?;
        (
            Card3::DirectSolar {
                h1_km: v[0],
                h2_km: v[1],
                angle_deg: v[2],
                iday: int(v[3]),
                ro_km: v[5],
                isourc: int(v[6]),
                anglem_deg: v[7],
            },
            line,
        )
    } else {
        let (v, line) = r.read("3", &CARD3)?;
        (
            Card3::Path {
                h1_km: v[0],
                h2_km: v[1],
                angle_deg: v[2],
                range_km: v[3],
                beta_deg: v[4],
                ro_km: v[5],
                len: int(v[6]),
            },
            line,
        )
    };
    let scattering = if iemsct == 2 {
        let (a1, _) = r.read("3A1", &CARD3A1)?;
        let (a2, _) = r.read("3A2", &CARD3A2)?;
        let card3a1 = [int(a1[0]), int(a1[1]), int(a1[2]), int(a1[3])];
        let mut card3a2 = [0.0; 8];
        card3a2.copy_from_slice(&a2);
        let mut phase_function = Vec::new();
        if card3a1[1] == 1 {
            let (n, l) = r.read("3B1", &CARD3B1)?;
            let n = int(n[0]);
            if !(1..=50).contains(&n) {
                return Err(r.error_at(
                    &l,
                    0,
                    5,
                    format!("card 3B1: expected NANGLS 1 to 50 (LOWTRAN's ANGF(50)), found {n}"),
                ));
            }
            for _ in 0..n {
                let (row, _) = r.read("3B2", &CARD3B2)?;
                phase_function.push([row[0], row[1], row[2], row[3], row[4]]);
            }
        }
        Some(Scattering {
            card3a1,
            card3a2,
            phase_function,
        })
    } else {
        None
    };
    Ok(Geometry {
        card3,
        scattering,
        position: line.position(),
    })
}

fn read_card4(r: &mut Reader<'_>) -> Result<Card4, ParseError> {
    let (v, line) = r.read("4", &CARD4)?;
    if v[2].partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(r.error_at(
            &line,
            20,
            10,
            format!("card 4: expected a step DV above 0 cm-1, found {}", v[2]),
        ));
    }
    Ok(Card4 {
        v1_per_cm: v[0],
        v2_per_cm: v[1],
        dv_per_cm: v[2],
        position: line.position(),
    })
}

fn read_profile(
    r: &mut Reader<'_>,
    line2c: TextLine<'_>,
    v: &[f64],
) -> Result<UserProfile, ParseError> {
    let ml = int(v[0]);
    let (ird1, ird2) = (int(v[1]), int(v[2]));
    if !(1..=MAX_LEVELS as i64).contains(&ml) {
        return Err(r.error_at(
            &line2c,
            0,
            5,
            format!("card 2C: expected ML, the number of levels, 1 to {MAX_LEVELS}, found {ml}"),
        ));
    }
    let title = line2c.field(15, 72).trim_end().to_owned();
    let mut levels = Vec::new();
    let mut last_z = f64::NEG_INFINITY;
    for _ in 0..ml {
        let (l, line) = r.read("2C1", &CARD2C1)?;
        if l[0] <= last_z {
            return Err(r.error_at(
                &line,
                0,
                10,
                format!(
                    "card 2C1: expected altitudes ZMDL to increase, found {} km after {} km",
                    l[0], last_z
                ),
            ));
        }
        last_z = l[0];
        let jchar: String = line.field(60, 14).to_owned();
        let mut wmol_more = None;
        if ird1 == 1 {
            let (a, _) = r.read("2C2", &[E10; 8])?;
            let (b, _) = r.read("2C2 (second line)", &[E10; 1])?;
            let mut w = [0.0; 9];
            w[..8].copy_from_slice(&a);
            w[8] = b[0];
            wmol_more = Some(w);
        }
        let mut aerosol = None;
        if ird2 == 1 {
            let c = r.card("2C3")?;
            // 10X: the first ten columns are skipped.
            let shifted = TextLine {
                text: c
                    .text
                    .get(c.offset_of_column(10) - c.offset..)
                    .unwrap_or(""),
                offset: c.offset_of_column(10),
                number: c.number,
            };
            let mut edits: Vec<(Edit, &str)> = CARD2C3_REALS.to_vec();
            edits.extend_from_slice(&CARD2C3_INTS);
            let v = read_card(r.src, &shifted, &edits).map_err(|e| with_card(e, "2C3"))?;
            aerosol = Some((
                [v[0], v[1], v[2]],
                [int(v[3]), int(v[4]), int(v[5]), int(v[6]), int(v[7])],
            ));
        }
        levels.push(ProfileLevel {
            zmdl_km: l[0],
            p: l[1],
            t: l[2],
            wmol: [l[3], l[4], l[5]],
            jchar: jchar.trim_end().to_owned(),
            wmol_more,
            aerosol,
            position: line.position(),
        });
    }
    Ok(UserProfile {
        ird1,
        ird2,
        title,
        levels,
    })
}

fn read_full(r: &mut Reader<'_>) -> Result<Cards, ParseError> {
    let (c1, line1) = r.read("1", &CARD1)?;
    let card1 = Card1 {
        model: int(c1[0]),
        itype: int(c1[1]),
        iemsct: int(c1[2]),
        imult: int(c1[3]),
        m: [
            int(c1[4]),
            int(c1[5]),
            int(c1[6]),
            int(c1[7]),
            int(c1[8]),
            int(c1[9]),
        ],
        mdef: int(c1[10]),
        im: int(c1[11]),
        noprt: int(c1[12]),
        tbound_k: c1[13],
        salb: c1[14],
    };
    check_choice(
        r,
        &line1,
        0,
        "MODEL",
        card1.model,
        &[0, 1, 2, 3, 4, 5, 6, 7],
        "0 to 7",
    )?;
    check_choice(r, &line1, 1, "ITYPE", card1.itype, &[1, 2, 3], "1, 2 or 3")?;
    check_choice(
        r,
        &line1,
        2,
        "IEMSCT",
        card1.iemsct,
        &[0, 1, 2, 3],
        "0 to 3",
    )?;
    let (c2, line2) = r.read("2", &CARD2)?;
    let card2 = Card2 {
        ihaze: int(c2[0]),
        iseasn: int(c2[1]),
        ivulcn: int(c2[2]),
        icstl: int(c2[3]),
        icld: int(c2[4]),
        ivsa: int(c2[5]),
        vis_km: c2[6],
        wss_m_s: c2[7],
        whh_m_s: c2[8],
        rainrt_mm_h: c2[9],
        gndalt_km: c2[10],
    };
    if card2.ihaze == 7 || card2.icld == 11 {
        let col = if card2.ihaze == 7 { 0 } else { 20 };
        return Err(r.error_at(
            &line2,
            col,
            5,
            "card 2: a user-defined aerosol (IHAZE = 7 or ICLD = 11, card 2D) is not read by irsig"
                .to_owned(),
        ));
    }
    let card2a = if card2.icld >= 18 {
        let (v, _) = r.read("2A", &CARD2A)?;
        Some(Card2A {
            cthik_km: v[0],
            calt_km: v[1],
            cext_per_km: v[2],
            iseed: int(v[3]),
        })
    } else {
        None
    };
    let card2b = if card2.ivsa == 1 {
        let (v, _) = r.read("2B", &CARD2B)?;
        Some(Card2B {
            zcvsa_km: v[0],
            ztvsa_km: v[1],
            zinvsa_km: v[2],
        })
    } else {
        None
    };
    let user = (card1.model == 7 && card1.im == 1) || card1.model == 0;
    let profile = if user {
        if card2.ivsa == 1 {
            return Err(r.error_at(
                &line2,
                25,
                5,
                "card 2: user levels with the vertical-structure algorithm (IVSA = 1 with MODEL 0 or 7) are not read by irsig".to_owned(),
            ));
        }
        let (v, line) = r.read("2C", &CARD2C)?;
        Some(read_profile(r, line, &v)?)
    } else {
        None
    };
    let geometry = read_geometry(r, card1.iemsct)?;
    let card4 = read_card4(r)?;
    Ok(Cards {
        card1,
        card2,
        card2a,
        card2b,
        profile,
        geometry,
        card4,
        position: line1.position(),
    })
}

/// Reads a card deck.
///
/// # Errors
/// A [`ParseError`] at the field: a number a Fortran read would reject, a card missing at
/// the end of the file, MODEL, ITYPE or IEMSCT out of range, a user profile of more than
/// 34 levels or with altitudes that do not increase, a step `DV` not above 0, or a card
/// irsig does not read (2D, or user levels with IVSA = 1).
pub fn parse(file: &str, text: &str) -> Result<CardDeck, ParseError> {
    let src = Source { file, text };
    let mut r = Reader {
        src,
        lines: text_lines(text),
        next: 0,
    };
    if r.lines.iter().all(|l| l.text.trim().is_empty()) {
        return Err(src.error(
            0,
            0,
            "expected card 1 of a LOWTRAN7 deck, found an empty file",
        ));
    }
    // LOWTRAN counts columns in bytes, irsig in characters: the two agree on ASCII only.
    if let Some(at) = text.find(|c: char| !c.is_ascii()) {
        return Err(src.error(
            at,
            1,
            "expected ASCII: a card's columns are bytes, and this character is more than one",
        ));
    }
    // A card is one line of printable characters (tabs aside): a carriage return or other
    // control character inside one would end or garble the record.
    for line in &r.lines {
        if let Some(i) = line.text.find(|c: char| c.is_ascii_control() && c != '\t') {
            return Err(src.error(
                line.offset + i,
                1,
                format!(
                    "expected printable characters on a card, found the control character {:?}",
                    &line.text[i..=i]
                ),
            ));
        }
    }
    let mut steps = Vec::new();
    let mut iemsct = read_full(&mut r).map(|c| {
        let i = c.card1.iemsct;
        steps.push(Step::Full(Box::new(c)));
        i
    })?;
    loop {
        let (v, _) = r.read("5", &CARD5)?;
        match int(v[0]) {
            1 => {
                let c = read_full(&mut r)?;
                iemsct = c.card1.iemsct;
                steps.push(Step::Full(Box::new(c)));
            }
            3 => steps.push(Step::Geometry(read_geometry(&mut r, iemsct)?)),
            4 => steps.push(Step::Spectral(read_card4(&mut r)?)),
            // 0 ends the deck; LOWTRAN stops on 2 and above 4 as well.
            _ => break,
        }
    }
    Ok(CardDeck { steps })
}

#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests;
