//! A run's outputs read as one path's spectra, in SI: a LOWTRAN7 TAPE7 or a MODTRAN
//! tape7, checked against what the plan's path needs from it (a thermal path's radiance,
//! the sun's irradiance, a sunlit path's scattered sunlight). Running the code and reading
//! the file are the tool's business; this module owns what the text means.

use irsig_formats::ParseError;
use irsig_formats::radtran::{lowtran_tape7, modtran_tape7};

use super::{Path, PathSpectra};

/// What a run must give its path of the plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunKind {
    /// Transmittance and thermal path radiance (IEMSCT = 1).
    Thermal,
    /// The sun's path: transmittance and the extraterrestrial irradiance (IEMSCT = 3).
    Solar,
    /// Thermal radiance and the sunlight scattered into the path once (IEMSCT = 2,
    /// IMULT = 0).
    Scattered,
    /// The sunlight the sky scatters toward the ground, multiple scattering included
    /// (IEMSCT = 2, IMULT = 1): a loads plan's diffuse lines of sight.
    Diffuse,
}

impl RunKind {
    /// What a spectral atmosphere plan's `path` takes from its run.
    #[must_use]
    pub fn of(path: &Path) -> Self {
        match path {
            Path::Sun { .. } => Self::Solar,
            Path::DownSunlit { .. }
            | Path::UpSunlit { .. }
            | Path::SlabSunlit { .. }
            | Path::Phase { .. } => Self::Scattered,
            Path::Down { .. } | Path::Up { .. } | Path::Slab { .. } => Self::Thermal,
        }
    }
}

/// A run's spectra, and what reading them noticed that the user should hear (each note
/// starts with the file's name).
#[derive(Debug, Clone)]
pub struct RunSpectra {
    pub spectra: PathSpectra,
    pub notes: Vec<String>,
}

/// The spectra of a run's tape7 `text` (named `file` in errors): MODTRAN's when the text
/// starts with a column header's letters, LOWTRAN7's otherwise.
///
/// # Errors
/// The text is not a tape7 of either program, or its run is not of the `kind` the path
/// needs: a [`ParseError`] at the field or header that says so.
pub fn run_spectra(file: &str, text: &str, kind: RunKind) -> Result<RunSpectra, ParseError> {
    let modtran = text
        .trim_start()
        .starts_with(|c: char| c.is_ascii_alphabetic());
    if modtran {
        modtran_spectra(file, text, kind)
    } else {
        Ok(RunSpectra {
            spectra: lowtran_spectra(file, text, kind)?,
            notes: Vec::new(),
        })
    }
}

/// The spectra of LOWTRAN7's TAPE7 `text`, converted to SI (W cm⁻² → W m⁻²) here.
///
/// # Errors
/// Not a TAPE7, no run or no table in it, or a run of another kind than `kind`.
pub fn lowtran_spectra(file: &str, text: &str, kind: RunKind) -> Result<PathSpectra, ParseError> {
    let t7 = lowtran_tape7::parse(file, text)?;
    let end = text.trim_end().len().saturating_sub(1);
    let run = t7.runs.first().ok_or_else(|| {
        ParseError::at_offset(
            file,
            text,
            end,
            "expected a LOWTRAN7 run in this TAPE7, found none by the end of the file",
        )
    })?;
    let table = run.table.as_ref().ok_or_else(|| {
        ParseError::at_line_column(
            file,
            text,
            run.position.line,
            run.position.column,
            "expected the run's spectral table, found none: LOWTRAN7 made no table for this \
             run (see its TAPE6)",
        )
    })?;
    if kind == RunKind::Solar {
        let etoa = table.extraterrestrial_irradiance().ok_or_else(|| {
            ParseError::at_line_column(
                file,
                text,
                run.position.line,
                run.position.column,
                "expected a direct solar irradiance run (IEMSCT = 3): this path of the plan is \
                 the sun's",
            )
        })?;
        return Ok(PathSpectra {
            wavenumber_per_cm: table.wavenumber_per_cm().to_vec(),
            transmission: table.transmission().to_vec(),
            radiance_w_m2_sr_per_cm: Vec::new(),
            // W cm-2 per cm-1 -> W m-2 per cm-1.
            extraterrestrial_w_m2_per_cm: etoa.iter().map(|e| e * 1e4).collect(),
            scattered_w_m2_sr_per_cm: Vec::new(),
        });
    }
    let scattered = if matches!(kind, RunKind::Scattered | RunKind::Diffuse) {
        let l = table.scattered_radiance().ok_or_else(|| {
            ParseError::at_line_column(
                file,
                text,
                run.position.line,
                run.position.column,
                "expected a solar scattering run (IEMSCT = 2): this path of the plan is a \
                 sunlit one",
            )
        })?;
        // W cm-2 sr-1 per cm-1 -> W m-2 sr-1 per cm-1.
        l.iter().map(|x| x * 1e4).collect()
    } else {
        Vec::new()
    };
    let radiance = table.thermal_radiance().ok_or_else(|| {
        ParseError::at_line_column(
            file,
            text,
            run.position.line,
            run.position.column,
            "expected a thermal radiance run (IEMSCT = 1 or 2): the build needs path radiance",
        )
    })?;
    Ok(PathSpectra {
        wavenumber_per_cm: table.wavenumber_per_cm().to_vec(),
        transmission: table.transmission().to_vec(),
        // W cm-2 sr-1 per cm-1 -> W m-2 sr-1 per cm-1.
        radiance_w_m2_sr_per_cm: radiance.iter().map(|l| l * 1e4).collect(),
        extraterrestrial_w_m2_per_cm: Vec::new(),
        scattered_w_m2_sr_per_cm: scattered,
    })
}

/// What a MODTRAN tape7's card 1 says, for errors: `IEMSCT = 1`, or that it has none.
fn modtran_mode(t: &modtran_tape7::ModtranTape7) -> String {
    t.iemsct.map_or_else(
        || "no card 1 with an IEMSCT".to_owned(),
        |k| format!("card 1's IEMSCT = {k}"),
    )
}

/// The spectra of a MODTRAN tape7 given for one path, converted to SI (W cm⁻² → W m⁻²)
/// here. A sun's path takes a direct solar irradiance run (IEMSCT = 3: `TRANS`, `SOLAR`);
/// a sunlit path a solar scattering run (IEMSCT = 2), whose `SOL_SCAT` is the scattered
/// sunlight; a thermal path a radiance-mode run. A file of another mode is an error at
/// card 1's IEMSCT (or the column header, without card 1).
fn modtran_spectra(file: &str, text: &str, kind: RunKind) -> Result<RunSpectra, ParseError> {
    let t = modtran_tape7::parse(file, text)?;
    // The wrong IEMSCT is an error at card 1's field; the right one without the columns
    // it needs, at the column header.
    let wrong = |expected: &str, iemsct: i64, columns: &str| {
        let (at, found) = if t.iemsct == Some(iemsct) {
            (
                t.header_position,
                format!("card 1's IEMSCT = {iemsct} without {columns} in the column header"),
            )
        } else {
            (
                t.iemsct_position.unwrap_or(t.header_position),
                modtran_mode(&t),
            )
        };
        ParseError::at_line_column(
            file,
            text,
            at.line,
            at.column,
            format!("expected {expected}, found {found}"),
        )
    };
    let tau = t.transmission();
    if kind == RunKind::Solar {
        // Only a direct solar run: an IEMSCT 2 run's TOA_SUN and TOT_TRANS are of another
        // path than the sun's.
        let etoa = (t.mode == modtran_tape7::Mode::DirectSolar)
            .then(|| t.extraterrestrial_irradiance())
            .flatten();
        let (Some(tau), Some(etoa)) = (tau, etoa) else {
            return Err(wrong(
                "a direct solar irradiance run (IEMSCT = 3, columns TRANS, SOL TR and SOLAR): \
                 this path of the plan is the sun's",
                3,
                "a TRANS column",
            ));
        };
        return Ok(RunSpectra {
            spectra: PathSpectra {
                wavenumber_per_cm: t.wavenumber_per_cm().to_vec(),
                transmission: tau.to_vec(),
                radiance_w_m2_sr_per_cm: Vec::new(),
                // W cm-2 per cm-1 -> W m-2 per cm-1.
                extraterrestrial_w_m2_per_cm: etoa.iter().map(|e| e * 1e4).collect(),
                scattered_w_m2_sr_per_cm: Vec::new(),
            },
            notes: Vec::new(),
        });
    }
    let mut notes = Vec::new();
    let scattered = if matches!(kind, RunKind::Scattered | RunKind::Diffuse) {
        let Some(l) = t.solar_scattered_radiance() else {
            return Err(wrong(
                "a solar scattering run (IEMSCT = 2, column SOL_SCAT): this path of the plan \
                 is a sunlit one",
                2,
                "a SOL_SCAT column",
            ));
        };
        if kind == RunKind::Scattered {
            notes.extend(multiple_scattering(file, &t, l));
        }
        // W cm-2 sr-1 per cm-1 -> W m-2 sr-1 per cm-1.
        l.iter().map(|x| x * 1e4).collect()
    } else {
        Vec::new()
    };
    let Some(tau) = tau else {
        return Err(ParseError::at_line_column(
            file,
            text,
            t.header_position.line,
            t.header_position.column,
            "expected a TOT_TRANS or COMBIN TRANS column in the header, found none",
        ));
    };
    let l = t.path_thermal_radiance().ok_or_else(|| {
        ParseError::at_line_column(
            file,
            text,
            t.header_position.line,
            t.header_position.column,
            "expected the path radiance column (PTH_THRML) of a radiance-mode \
             tape7, found none: run MODTRAN in radiance mode",
        )
    })?;
    Ok(RunSpectra {
        spectra: PathSpectra {
            wavenumber_per_cm: t.wavenumber_per_cm().to_vec(),
            transmission: tau.to_vec(),
            radiance_w_m2_sr_per_cm: l.iter().map(|x| x * 1e4).collect(),
            extraterrestrial_w_m2_per_cm: Vec::new(),
            scattered_w_m2_sr_per_cm: scattered,
        },
        notes,
    })
}

/// MODTRAN's `SOL_SCAT` includes multiple scattering when MODTRAN ran with it; LOWTRAN7's
/// runs of a plan scatter sunlight once (IMULT = 0). Where `SOL_SCAT` exceeds the
/// single-scattered `SING_SCAT`, the path's scattered sunlight is not the same quantity as
/// the other paths', and the note says so.
fn multiple_scattering(
    file: &str,
    t: &modtran_tape7::ModtranTape7,
    total: &[f64],
) -> Option<String> {
    let single = t.single_scattered_radiance()?;
    let excess = total
        .iter()
        .zip(single)
        .filter(|(a, _)| **a > 0.0)
        .map(|(a, b)| (a - b) / a)
        .fold(0.0_f64, f64::max);
    // Both are printed to 5 digits: a difference within their rounding is none.
    (excess > 1e-4).then(|| {
        format!(
            "{file}: MODTRAN's SOL_SCAT includes multiple scattering (up to {:.1} % above \
             SING_SCAT): this sunlit path's scattered sunlight is MODTRAN's single plus \
             multiple scattering, while the paths LOWTRAN7 runs for the plan scatter sunlight \
             once (IMULT = 0)",
            excess * 100.0
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const LOWTRAN_THERMAL: &str =
        include_str!("../../../../formats/radtran/samples/us-std-1976.tape7");
    const MODTRAN_SOLAR: &str =
        include_str!("../../../../formats/radtran/samples/modtran-iemsct3-layout.tape7");

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs()
    }

    #[test]
    fn a_lowtran7_radiance_run_is_read_in_si() {
        // The sample's first row: 710 cm-1, TRANS 0.1245, ATMOS RADIANCE 1.07E-05 W cm-2
        // sr-1 per cm-1, which is 0.107 W m-2 sr-1 per cm-1.
        let r = run_spectra("us.tape7", LOWTRAN_THERMAL, RunKind::Thermal).unwrap();
        assert!(r.notes.is_empty());
        let s = &r.spectra;
        assert!(close(s.wavenumber_per_cm[0], 710.0));
        assert!(close(s.transmission[0], 0.1245));
        assert!(
            close(s.radiance_w_m2_sr_per_cm[0], 0.107),
            "{}",
            s.radiance_w_m2_sr_per_cm[0]
        );
        assert!(s.extraterrestrial_w_m2_per_cm.is_empty());
        assert!(s.scattered_w_m2_sr_per_cm.is_empty());
        assert_eq!(s.wavenumber_per_cm.len(), s.transmission.len());
    }

    #[test]
    fn a_lowtran7_radiance_run_given_for_the_suns_path_is_refused_at_the_run() {
        let e = run_spectra("us.tape7", LOWTRAN_THERMAL, RunKind::Solar).unwrap_err();
        let text = e.to_string();
        assert!(text.contains("IEMSCT = 3"), "{text}");
        let e = run_spectra("us.tape7", LOWTRAN_THERMAL, RunKind::Scattered).unwrap_err();
        assert!(e.to_string().contains("IEMSCT = 2"), "{e}");
    }

    #[test]
    fn a_modtran_direct_solar_run_is_read_in_si() {
        // First row: TRANS 0.8304, SOLAR 1.52E-06 W cm-2 per cm-1 = 0.0152 W m-2 per cm-1.
        let r = run_spectra("m.tape7", MODTRAN_SOLAR, RunKind::Solar).unwrap();
        let s = &r.spectra;
        assert!(close(s.wavenumber_per_cm[0], 2500.0));
        assert!(close(s.transmission[0], 0.8304));
        assert!(close(s.extraterrestrial_w_m2_per_cm[0], 0.0152));
        assert_eq!(s.wavenumber_per_cm.len(), 6);
        assert!(s.radiance_w_m2_sr_per_cm.is_empty());
    }

    #[test]
    fn a_modtran_solar_run_given_for_a_thermal_path_is_refused_at_its_header() {
        let e = run_spectra("m.tape7", MODTRAN_SOLAR, RunKind::Thermal).unwrap_err();
        assert!(e.to_string().contains("PTH_THRML"), "{e}");
    }

    #[test]
    fn an_empty_file_is_refused_not_read_as_no_spectra() {
        assert!(run_spectra("e.tape7", "", RunKind::Thermal).is_err());
        assert!(run_spectra("e.tape7", "   \n", RunKind::Solar).is_err());
    }
}
