//! Writing a deck: every card in LOWTRAN7's own fixed-column format, each real in a field
//! a Fortran read gives back exactly.

use super::*;

/// Formats `value` in a field of `width` columns so that a Fortran read with `decimals`
/// implied decimals gives back exactly `value`; `None` if it cannot.
fn real_field(value: f64, width: usize, decimals: usize) -> Option<String> {
    if !value.is_finite() {
        return None;
    }
    let value = if value == 0.0 { 0.0 } else { value }; // no "-0.000"
    let exact = |s: &str| {
        s.len() <= width
            && super::super::read_real(s, u32::try_from(decimals).unwrap_or(0))
                .is_some_and(|v| v.total_cmp(&value).is_eq())
    };
    let fixed = format!("{value:width$.decimals$}");
    if exact(&fixed) {
        return Some(fixed);
    }
    let mut short = format!("{value}");
    if !short.contains(['.', 'e', 'E']) {
        short.push('.');
    }
    if exact(&short) {
        return Some(format!("{short:>width$}"));
    }
    // `.666666666`: the leading zero costs a column.
    let bare = short.replacen("0.", ".", 1);
    if short.trim_start_matches('-').starts_with("0.") && exact(&bare) {
        return Some(format!("{bare:>width$}"));
    }
    let sci = format!("{value:e}");
    let sci = if sci.contains('.') {
        sci
    } else {
        sci.replacen('e', ".e", 1)
    };
    if exact(&sci) {
        return Some(format!("{sci:>width$}"));
    }
    // Last: the significant digits alone, the decimal point implied and an exponent if
    // needed (how `9999999999` or `66666666+6` read in F10.3).
    let (mantissa, exp10) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp10: i64 = exp10.parse().unwrap_or(0);
    let sign = if value < 0.0 { "-" } else { "" };
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    let digits = digits.trim_end_matches('0');
    let digits = if digits.is_empty() { "0" } else { digits };
    let len = i64::try_from(digits.len()).unwrap_or(0);
    let e = exp10 - (len - 1) + i64::try_from(decimals).unwrap_or(0);
    let candidates = [
        format!(
            "{sign}{digits}{}",
            "0".repeat(usize::try_from(e).unwrap_or(0))
        ),
        format!("{sign}{digits}{e:+}"),
        format!("{sign}{digits}E{e}"),
    ];
    candidates
        .into_iter()
        .find(|c| exact(c))
        .map(|c| format!("{c:>width$}"))
}

struct Writer {
    out: String,
    card: String,
}

impl Writer {
    fn line(&mut self, card: &str, fields: &[(Edit, &str, f64)]) -> Result<(), WriteError> {
        self.card = card.to_owned();
        let mut s = String::new();
        for &(edit, name, v) in fields {
            let text = match edit {
                Edit::I(w) => {
                    let t = format!("{:w$}", int(v));
                    (t.len() <= w && v.fract() == 0.0).then_some(t)
                }
                Edit::F(w, d) => real_field(v, w, d as usize),
            };
            let Some(text) = text else {
                return Err(WriteError::new(
                    format!("card {card}"),
                    if v.is_finite() {
                        WriteErrorKind::OutOfRange(format!(
                            "{name} = {v} does not fit its {} field",
                            edit.name()
                        ))
                    } else {
                        WriteErrorKind::NotFinite
                    },
                ));
            };
            s.push_str(&text);
        }
        self.out.push_str(s.trim_end());
        self.out.push('\n');
        Ok(())
    }

    fn text(&mut self, text: &str, width: usize, what: &str) -> Result<String, WriteError> {
        if text.len() > width || !text.is_ascii() || text.contains(['\n', '\r']) {
            return Err(WriteError::new(
                format!("card {}", self.card),
                WriteErrorKind::OutOfRange(format!(
                    "{what} `{text}` must be ASCII on one line, at most {width} characters"
                )),
            ));
        }
        Ok(format!("{text:<width$}"))
    }
}

fn f(edits: &[(Edit, &'static str)], values: &[f64]) -> Vec<(Edit, &'static str, f64)> {
    edits
        .iter()
        .zip(values)
        .map(|(&(e, n), &v)| (e, n, v))
        .collect()
}

#[allow(clippy::cast_precision_loss)]
fn fi(v: i64) -> f64 {
    v as f64
}

fn write_geometry(w: &mut Writer, g: &Geometry) -> Result<(), WriteError> {
    match g.card3 {
        Card3::Path {
            h1_km,
            h2_km,
            angle_deg,
            range_km,
            beta_deg,
            ro_km,
            len,
        } => w.line(
            "3",
            &f(
                &CARD3,
                &[h1_km, h2_km, angle_deg, range_km, beta_deg, ro_km, fi(len)],
            ),
        )?,
        Card3::DirectSolar {
            h1_km,
            h2_km,
            angle_deg,
            iday,
            ro_km,
            isourc,
            anglem_deg,
        } => w.line(
            "3",
            &f(
                &CARD3_SOLAR,
                &[
                    h1_km,
                    h2_km,
                    angle_deg,
                    fi(iday),
                    0.0,
                    ro_km,
                    fi(isourc),
                    anglem_deg,
                ],
            ),
        )?,
    }
    if let Some(s) = &g.scattering {
        w.line("3A1", &f(&CARD3A1, &s.card3a1.map(fi)))?;
        w.line("3A2", &f(&CARD3A2, &s.card3a2))?;
        if s.card3a1[1] == 1 {
            w.line(
                "3B1",
                &f(
                    &CARD3B1,
                    &[fi(i64::try_from(s.phase_function.len()).unwrap_or(i64::MAX))],
                ),
            )?;
            for row in &s.phase_function {
                w.line("3B2", &f(&CARD3B2, row))?;
            }
        }
    }
    Ok(())
}

fn write_card4(w: &mut Writer, c: &Card4) -> Result<(), WriteError> {
    w.line("4", &f(&CARD4, &[c.v1_per_cm, c.v2_per_cm, c.dv_per_cm]))
}

fn write_full(w: &mut Writer, c: &Cards) -> Result<(), WriteError> {
    let c1 = &c.card1;
    let mut v1: Vec<f64> = [c1.model, c1.itype, c1.iemsct, c1.imult]
        .into_iter()
        .chain(c1.m)
        .chain([c1.mdef, c1.im, c1.noprt])
        .map(fi)
        .collect();
    v1.extend([c1.tbound_k, c1.salb]);
    w.line("1", &f(&CARD1, &v1))?;
    let c2 = &c.card2;
    let v2 = [
        fi(c2.ihaze),
        fi(c2.iseasn),
        fi(c2.ivulcn),
        fi(c2.icstl),
        fi(c2.icld),
        fi(c2.ivsa),
        c2.vis_km,
        c2.wss_m_s,
        c2.whh_m_s,
        c2.rainrt_mm_h,
        c2.gndalt_km,
    ];
    w.line("2", &f(&CARD2, &v2))?;
    if let Some(a) = &c.card2a {
        w.line(
            "2A",
            &f(
                &CARD2A,
                &[a.cthik_km, a.calt_km, a.cext_per_km, fi(a.iseed)],
            ),
        )?;
    }
    if let Some(b) = &c.card2b {
        w.line("2B", &f(&CARD2B, &[b.zcvsa_km, b.ztvsa_km, b.zinvsa_km]))?;
    }
    if let Some(p) = &c.profile {
        let ml = i64::try_from(p.levels.len()).unwrap_or(i64::MAX);
        w.card = "2C".to_owned();
        let title = w.text(&p.title, 72, "the title")?;
        let before = w.out.len();
        w.line("2C", &f(&CARD2C, &[fi(ml), fi(p.ird1), fi(p.ird2)]))?;
        // The title follows the three I5 fields: rewrite the line with it.
        w.out.truncate(before);
        let head = format!("{:5}{:5}{:5}", ml, p.ird1, p.ird2);
        w.out.push_str(format!("{head}{title}").trim_end());
        w.out.push('\n');
        for level in &p.levels {
            let before = w.out.len();
            w.line(
                "2C1",
                &f(
                    &CARD2C1,
                    &[
                        level.zmdl_km,
                        level.p,
                        level.t,
                        level.wmol[0],
                        level.wmol[1],
                        level.wmol[2],
                    ],
                ),
            )?;
            let jchar = w.text(&level.jchar, 14, "JCHAR")?;
            if !jchar.trim().is_empty() {
                w.out.truncate(before);
                let mut s = String::new();
                for (i, v) in [
                    level.zmdl_km,
                    level.p,
                    level.t,
                    level.wmol[0],
                    level.wmol[1],
                    level.wmol[2],
                ]
                .into_iter()
                .enumerate()
                {
                    s.push_str(&real_field(v, 10, 3).unwrap_or_else(|| {
                        // Checked by `line` above.
                        let _ = i;
                        String::new()
                    }));
                }
                s.push_str(&jchar);
                w.out.push_str(s.trim_end());
                w.out.push('\n');
            }
            if p.ird1 == 1 {
                let m = level.wmol_more.unwrap_or([0.0; 9]);
                w.line("2C2", &f(&[E10; 8], &m[..8]))?;
                w.line("2C2", &f(&[E10; 1], &m[8..]))?;
            }
            if p.ird2 == 1 {
                let (r, i) = level.aerosol.unwrap_or(([0.0; 3], [0; 5]));
                let mut edits: Vec<(Edit, &str)> = vec![(Edit::I(10), "10X")];
                edits.extend_from_slice(&CARD2C3_REALS);
                edits.extend_from_slice(&CARD2C3_INTS);
                let mut vals = vec![0.0, r[0], r[1], r[2]];
                vals.extend(i.map(fi));
                let before = w.out.len();
                w.line("2C3", &f(&edits, &vals))?;
                // The 10X columns are blank, not a zero.
                let line = w.out[before..].to_owned();
                w.out.truncate(before);
                w.out.push_str("          ");
                w.out.push_str(line.get(10..).unwrap_or("\n"));
            }
        }
    }
    write_geometry(w, &c.geometry)?;
    write_card4(w, &c.card4)
}

/// Writes a card deck that LOWTRAN7 (and [`parse`]) reads back to the same deck.
///
/// # Errors
/// A [`WriteError`] for an empty deck, a first step that is not [`Step::Full`], a number
/// that does not fit its field exactly, or a title or JCHAR that is not ASCII or too long.
pub fn write(deck: &CardDeck) -> Result<String, WriteError> {
    let mut w = Writer {
        out: String::new(),
        card: String::new(),
    };
    if !matches!(deck.steps.first(), Some(Step::Full(_))) {
        return Err(WriteError::new(
            "card 1",
            if deck.steps.is_empty() {
                WriteErrorKind::Empty
            } else {
                WriteErrorKind::OutOfRange("the first calculation must give every card".into())
            },
        ));
    }
    for (i, step) in deck.steps.iter().enumerate() {
        match step {
            Step::Full(c) => write_full(&mut w, c)?,
            Step::Geometry(g) => write_geometry(&mut w, g)?,
            Step::Spectral(c) => write_card4(&mut w, c)?,
        }
        let irpt = match deck.steps.get(i + 1) {
            None => 0,
            Some(Step::Full(_)) => 1,
            Some(Step::Geometry(_)) => 3,
            Some(Step::Spectral(_)) => 4,
        };
        w.line("5", &f(&CARD5, &[fi(irpt)]))?;
    }
    Ok(w.out)
}
