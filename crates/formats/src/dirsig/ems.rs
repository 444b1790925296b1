//! DIRSIG classic `.ems`: spectral emissivity curves with an angular falloff.
//!
//! ```text
//! 43                 the number of curves
//! 1.000000           91 angular factors, 0° to 90° every 1° (ε(θ) / ε(0°))
//! 0.991828
//! ...
//! 0                  a curve by index (0, 1, …): rows `wavenumber_cm-1 emissivity`,
//! 39850 1.000000     wavenumbers strictly decreasing
//! ...
//! CURVE_BEGIN        or a curve by keyword: rows `wavelength_um emissivity`,
//! 0.35 0.98          wavelengths strictly increasing, to `CURVE_END`, the next
//! ...                `CURVE_BEGIN` or the end of the file
//! ```
//!
//! Both forms occur in DIRSIG's material sets; each curve is given back in µm,
//! increasing. Emissivities and angular factors are 0 to 1; a curve has at least two rows.

use crate::ParseError;
use crate::legacy::Position;
use crate::legacy::lex::{Line, Lines, position};

/// The number of angular factors: 0° to 90° every 1°.
pub const ANGLES: usize = 91;

/// One spectral curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Wavelengths, µm, strictly increasing.
    pub wavelength_um: Vec<f64>,
    /// Emissivity at each wavelength, 0 to 1.
    pub emissivity: Vec<f64>,
    /// Where the curve starts (its index or `CURVE_BEGIN` line).
    pub position: Position,
}

/// A parsed DIRSIG `.ems`.
#[derive(Debug, Clone, PartialEq)]
pub struct DirsigEms {
    /// ε(θ) / ε(0°) at 0°, 1°, … 90°.
    pub angular_factor: Vec<f64>,
    /// The curves, in file order.
    pub curves: Vec<Curve>,
}

/// Reads a DIRSIG `.ems`.
///
/// # Errors
/// A [`ParseError`] at the place: a missing or non-numeric count, fewer than 91 angular
/// factors, a value outside 0–1, a curve whose index is not the next one, a row without
/// exactly two finite numbers, wavenumbers that do not decrease or wavelengths that do not
/// increase, a curve of fewer than two rows, or a count of curves that disagrees with the
/// first line.
pub fn parse(file: &str, text: &str) -> Result<DirsigEms, ParseError> {
    let mut lines = Lines::new(file, text);
    let first = lines.expect_line("the number of curves")?;
    let count = lines.single_unsigned(first, "the number of curves")?;
    if count == 0 || count > 100_000 {
        return Err(lines.error(
            first.span,
            format!("expected 1 to 100000 curves, found {count}"),
        ));
    }
    let mut angular_factor = Vec::with_capacity(ANGLES);
    for k in 0..ANGLES {
        let line = lines.expect_line(&format!("the angular factor at {k} deg"))?;
        let ([v], [span]) = lines.reals::<1>(line, "an angular factor")?;
        if !(0.0..=1.0).contains(&v) {
            return Err(lines.error(
                span,
                format!("expected an angular factor 0 to 1, found {v}"),
            ));
        }
        angular_factor.push(v);
    }
    let mut curves: Vec<Curve> = Vec::new();
    let mut pending = lines.next_line();
    while let Some(head) = pending {
        let keyword = head.span.fragment().trim() == "CURVE_BEGIN";
        if !keyword {
            let index = lines.single_unsigned(head, "a curve index or CURVE_BEGIN")?;
            if index != curves.len() as u64 {
                return Err(lines.error(
                    head.span,
                    format!("expected curve index {}, found {index}", curves.len()),
                ));
            }
        }
        if curves.len() as u64 == count {
            return Err(lines.error(
                head.span,
                format!("the first line says {count} curve(s); this is one more"),
            ));
        }
        let mut rows: Vec<([f64; 2], Line<'_>)> = Vec::new();
        pending = None;
        while let Some(line) = lines.next_line() {
            let body = line.span.fragment().trim();
            if body == "CURVE_END" && keyword {
                // The next curve, if any, starts on the following line.
                pending = lines.next_line();
                break;
            }
            if body == "CURVE_BEGIN" || Lines::tokens(line).count() == 1 {
                pending = Some(line);
                break;
            }
            let (v, spans) = lines.reals::<2>(
                line,
                if keyword {
                    "wavelength in um and emissivity"
                } else {
                    "wavenumber in cm-1 and emissivity"
                },
            )?;
            if v[0] <= 0.0 {
                return Err(lines.error(
                    spans[0],
                    format!("expected a value above 0, found {}", v[0]),
                ));
            }
            if !(0.0..=1.0).contains(&v[1]) {
                return Err(lines.error(
                    spans[1],
                    format!("expected an emissivity 0 to 1, found {}", v[1]),
                ));
            }
            if let Some((prev, _)) = rows.last() {
                let ok = if keyword {
                    v[0] > prev[0]
                } else {
                    v[0] < prev[0]
                };
                if !ok {
                    let what = if keyword {
                        "wavelengths must increase"
                    } else {
                        "wavenumbers must decrease"
                    };
                    return Err(
                        lines.error(spans[0], format!("{what}: {} follows {}", v[0], prev[0]))
                    );
                }
            }
            rows.push((v, line));
        }
        if rows.len() < 2 {
            return Err(lines.error(head.span, "a curve needs at least two rows"));
        }
        // Decreasing wavenumbers are increasing wavelengths.
        let points: Vec<(f64, f64)> = rows
            .iter()
            .map(|(v, _)| {
                if keyword {
                    (v[0], v[1])
                } else {
                    (1e4 / v[0], v[1])
                }
            })
            .collect();
        curves.push(Curve {
            wavelength_um: points.iter().map(|p| p.0).collect(),
            emissivity: points.iter().map(|p| p.1).collect(),
            position: position(head.span),
        });
    }
    if (curves.len() as u64) < count {
        return Err(lines.eof_error(&format!(
            "the first line says {count} curve(s), found {}",
            curves.len()
        )));
    }
    Ok(DirsigEms {
        angular_factor,
        curves,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(count: usize) -> String {
        let mut s = format!("{count}\n");
        for k in 0..ANGLES {
            s.push_str(&format!("{}\n", 1.0 - k as f64 / 90.0));
        }
        s
    }

    #[test]
    fn both_curve_forms_read_in_micrometres() {
        let text = header(2) + "0\n1250 0.9\n1000 0.8\n714.2857 0.7\n1\n2000 0.5\n500 0.6\n";
        let e = parse("a.ems", &text).unwrap();
        assert_eq!(e.angular_factor.len(), 91);
        assert!((e.angular_factor[45] - 0.5).abs() < 1e-12);
        assert_eq!(e.curves.len(), 2);
        let c = &e.curves[0];
        assert!((c.wavelength_um[0] - 8.0).abs() < 1e-12);
        assert!((c.wavelength_um[1] - 10.0).abs() < 1e-12);
        assert!((c.wavelength_um[2] - 1e4 / 714.2857).abs() < 1e-9);
        assert_eq!(c.emissivity, vec![0.9, 0.8, 0.7]);
        let text = header(1) + "CURVE_BEGIN\n8.0\t0.98\n14.0\t0.97\nCURVE_END\n";
        let e = parse("b.ems", &text).unwrap();
        assert_eq!(e.curves[0].wavelength_um, vec![8.0, 14.0]);
        // Two keyword curves, each closed by CURVE_END: both read.
        let text = header(2)
            + "CURVE_BEGIN\n8.0 0.98\n14.0 0.97\nCURVE_END\n\
               CURVE_BEGIN\n8.5 0.96\n13.0 0.95\nCURVE_END\n";
        let e = parse("c.ems", &text).unwrap();
        assert_eq!(e.curves.len(), 2);
        assert_eq!(e.curves[1].wavelength_um, vec![8.5, 13.0]);
        assert_eq!(e.curves[1].emissivity, vec![0.96, 0.95]);
    }

    #[test]
    fn malformed_files_fail_at_their_place() {
        let at = |text: String| parse("x.ems", &text).unwrap_err();
        let e = at(header(1) + "0\n1000 0.9\n1100 0.8\n");
        assert_eq!((e.line, e.column), (95, 1), "{e}");
        assert!(e.message.contains("decrease"), "{e}");
        let e = at(header(2) + "0\n1000 0.9\n900 0.8\n");
        assert!(e.message.contains("2 curve(s), found 1"), "{e}");
        let e = at(header(1) + "0\n1000 1.5\n900 0.8\n");
        assert_eq!((e.line, e.column), (94, 6), "{e}");
        let e = at(header(1) + "3\n1000 0.9\n900 0.8\n");
        assert!(e.message.contains("expected curve index 0"), "{e}");
        let e = at("1\n1.0\n".to_owned());
        assert!(e.message.contains("angular factor at 1 deg"), "{e}");
    }
}
