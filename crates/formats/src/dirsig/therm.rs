//! A DIRSIG `TEMP_SOLVER_NAME = Therm` block, converted to irsig's thermal record
//! ([`irsig_model::thermal::ThermalProperties`]).
//!
//! DIRSIG's THERM (written by DCS Corporation for the USAF AIRSIM program, ported to C++ in
//! DIRSIG4) is a 1-D slab of uniform properties and a given thickness, its surface heated
//! and cooled by radiation and convection (DIRSIG, "Temperature Solvers", the THERM
//! section). Its inputs and their units are those of DIRSIG's "Material Database File"
//! page (Table 34-2, "Tags values and descriptions"):
//!
//! | key | DIRSIG unit | irsig | conversion |
//! | --- | --- | --- | --- |
//! | `SPECIFIC_HEAT` | cal g⁻¹ °C⁻¹ (see below) | the layer's `specific_heat_j_kg_k` | × 4186.8 |
//! | `MASS_DENSITY` | g cm⁻³ | `density_kg_m3` | × 1000 |
//! | `THERMAL_CONDUCTIVITY` | W m⁻¹ K⁻¹ | `conductivity_w_m_k` | × 1 |
//! | `THICKNESS` | cm | `thickness_m` | × 0.01 |
//! | `SOLAR_ABSORPTION` (older files: `VISIBLE_EMISSIVITY`, "mean solar absorptivity") | fraction | `solar_absorptance` | × 1 |
//! | `THERMAL_EMISSIVITY` | fraction | `thermal_emissivity` | × 1 |
//! | `EXPOSED_AREA` | fraction | — (see below) | — |
//! | `SPECULARITY` | fraction | not read (the specular fraction comes from `EMISSIVITY_PROP`) | — |
//!
//! The page gives the specific heat's unit as "[L/C]", then "[L/cm/C] where [L] is a Langley
//! unit" (1 cal cm⁻²): neither is a specific heat. Its other units are cgs (g cm⁻³, cm) and
//! DIRSIG's own databases give water 1 (with a density of 1): the calorie per gram and
//! degree, 4186.8 J kg⁻¹ K⁻¹ (the International Table calorie, 4.1868 J).
//!
//! The conductivity is taken in W m⁻¹ K⁻¹, as the page's table says, although the same
//! databases give water 5.13, which is water's 0.597 W m⁻¹ K⁻¹ in cal cm⁻¹ h⁻¹ °C⁻¹ (the
//! "Langley per hour" unit the page's note converts) and 8.6 times it in W m⁻¹ K⁻¹; a
//! library converted from such a database should be checked (`formats/dirsig.md`).
//!
//! What irsig cannot represent is refused at its value, saying why:
//! - `THICKNESS = 0`, and no `THICKNESS`: DIRSIG gives them a meaning of its own (its
//!   databases use 0 throughout) that its documentation irsig could read does not state;
//!   irsig's wall needs a thickness.
//! - a negative `EXPOSED_AREA`: likewise (DIRSIG's own databases hold −0.4 and −0.5).
//! - `EXPOSED_AREA` 0–1, "the amount of exposure the facet has to the ambient air" (an
//!   asphalt lot exposed on top only, a fence on both sides), has no counterpart in irsig's
//!   record, which says instead what lies behind the wall. The caller must give that back
//!   boundary; the value is kept in the record's `source`.
//! - a key irsig does not know, which could change the slab's physics.
//!
//! The slab is dry (`wet_fraction` 0) and of irsig's default roughness: THERM has neither.

// ParseError is the crate's shared error; its size is decided there, not here.
#![allow(clippy::result_large_err)]

use irsig_model::thermal::{BackBoundary, Roughness, ThermalLayer, ThermalProperties};
use nom::Input;

use super::mat::{Entry, Located};
use crate::ParseError;
use crate::legacy::lex::{Lines, Span};

/// The International Table calorie, J.
const CALORIE_J: f64 = 4.1868;

/// The keys of a THERM block irsig reads, and what each is for messages.
const KEYS: [(&str, &str); 9] = [
    ("SPECIFIC_HEAT", "a specific heat, cal g⁻¹ °C⁻¹"),
    ("MASS_DENSITY", "a density, g cm⁻³"),
    ("THERMAL_CONDUCTIVITY", "a thermal conductivity, W m⁻¹ K⁻¹"),
    ("THICKNESS", "a thickness, cm"),
    ("SOLAR_ABSORPTION", "a solar absorptance, 0 to 1"),
    ("VISIBLE_EMISSIVITY", "a solar absorptance, 0 to 1"),
    ("THERMAL_EMISSIVITY", "a thermal emissivity, 0 to 1"),
    ("EXPOSED_AREA", "an exposed area, a fraction"),
    ("SPECULARITY", "a specularity, 0 to 1"),
];

/// Whether `entry` has a THERM temperature solver (`TEMP_SOLVER_NAME = Therm`, any case).
#[must_use]
pub fn is_therm(entry: &Entry) -> bool {
    entry
        .temp_solver
        .as_ref()
        .and_then(|s| s.name.as_ref())
        .is_some_and(|n| n.value.eq_ignore_ascii_case("therm"))
}

/// The thermal record of `entry`'s THERM block, with `back` behind its slab; `None` for an
/// entry whose temperature solver is not THERM (`Null`, `DataDriven`, none: its facets'
/// temperatures are given by the scene). `file` and `text` are the `.mat`'s name and text.
///
/// # Errors
/// A [`ParseError`] at the value (or key, or the block) irsig cannot convert faithfully: a
/// key it does not know, a value that is not a number, one given under both of its names, a
/// required key missing (`SPECIFIC_HEAT`, `MASS_DENSITY`, `THERMAL_CONDUCTIVITY`,
/// `THICKNESS`), `THICKNESS = 0`, a negative or above-1 `EXPOSED_AREA`, and a number
/// outside irsig's range for it (a conductivity of 0, an absorptance above 1), named in
/// DIRSIG's unit and in SI.
pub fn thermal(
    file: &str,
    text: &str,
    entry: &Entry,
    back: BackBoundary,
) -> Result<Option<ThermalProperties>, ParseError> {
    if !is_therm(entry) {
        return Ok(None);
    }
    let Some(solver) = &entry.temp_solver else {
        return Ok(None);
    };
    let lines = Lines::new(file, text);
    let at = |l: &Located<String>, message: String| {
        ParseError::at_span(file, text, l.span.0, l.span.1.max(1), message)
    };
    let mut found: [Option<(f64, &Located<String>)>; KEYS.len()] = [None; KEYS.len()];
    for (key, value) in &solver.values {
        let Some(k) = KEYS.iter().position(|(name, _)| *name == key.value) else {
            return Err(at(
                key,
                format!(
                    "irsig does not know the THERM key {}: it reads {}; a key it cannot read \
                     could change the slab's physics",
                    key.value,
                    KEYS.map(|(name, _)| name).join(", ")
                ),
            ));
        };
        let span: Span<'_> = Span::new(text).take_from(value.span.0).take(value.span.1);
        let v = lines.real(span, KEYS[k].1)?;
        found[k] = Some((v, value));
    }
    let get = |name: &str| {
        KEYS.iter()
            .position(|(n, _)| *n == name)
            .and_then(|k| found[k])
    };
    if let (Some(_), Some((_, second))) = (get("SOLAR_ABSORPTION"), get("VISIBLE_EMISSIVITY")) {
        return Err(at(
            second,
            "VISIBLE_EMISSIVITY is the older name of SOLAR_ABSORPTION, and both are given: \
             which one is meant?"
                .into(),
        ));
    }
    if let Some((area, value)) = get("EXPOSED_AREA")
        && !(0.0..=1.0).contains(&area)
    {
        let why = if area < 0.0 {
            "a negative exposed area has a meaning of its own in DIRSIG's THERM, which the \
             documentation irsig could read (the Material Database File page: \"the amount of \
             exposure the facet has to the ambient air\", a fraction) does not give; irsig \
             refuses it rather than guess"
        } else {
            "the exposed area is a fraction of the surface, 0 to 1"
        };
        return Err(at(value, format!("EXPOSED_AREA {area}: {why}")));
    }
    let block = |message: String| {
        let (start, len) = solver
            .block
            .or_else(|| solver.name.as_ref().map(|n| n.span))
            .unwrap_or(entry.id.span);
        ParseError::at_span(file, text, start, len.max(1), message)
    };
    let required = |name: &str| {
        get(name).ok_or_else(|| {
            block(format!(
                "this THERM block has no {name}: irsig needs the slab's thickness, density, \
                 specific heat and conductivity"
            ))
        })
    };
    let (specific_heat, _) = required("SPECIFIC_HEAT")?;
    let (density, _) = required("MASS_DENSITY")?;
    let (conductivity, _) = required("THERMAL_CONDUCTIVITY")?;
    let (thickness_cm, d_at) = required("THICKNESS")?;
    if thickness_cm == 0.0 {
        return Err(at(
            d_at,
            "THICKNESS 0: DIRSIG's THERM gives a zero thickness a meaning of its own, which \
             the documentation irsig could read does not state; irsig's wall needs the \
             slab's thickness in cm"
                .into(),
        ));
    }
    let absorptance = get("SOLAR_ABSORPTION").or_else(|| get("VISIBLE_EMISSIVITY"));
    let emissivity = get("THERMAL_EMISSIVITY");
    let exposed = get("EXPOSED_AREA").map_or_else(
        || "no EXPOSED_AREA".to_owned(),
        |(a, _)| format!("EXPOSED_AREA {a} (not represented: the back boundary replaces it)"),
    );
    let layer = ThermalLayer {
        thickness_m: thickness_cm * 0.01,
        conductivity_w_m_k: conductivity,
        density_kg_m3: density * 1000.0,
        specific_heat_j_kg_k: specific_heat * CALORIE_J * 1000.0,
        source: format!(
            "DIRSIG {file} ID {} TEMP_SOLVER Therm: THICKNESS {thickness_cm} cm, \
             THERMAL_CONDUCTIVITY {conductivity} W/(m K), MASS_DENSITY {density} g/cm3, \
             SPECIFIC_HEAT {specific_heat} cal/(g C)",
            entry.id.value
        ),
    };
    let properties = ThermalProperties {
        layers: vec![layer],
        back,
        solar_absorptance: absorptance.map(|(a, _)| a),
        thermal_emissivity: emissivity.map(|(e, _)| e),
        wet_fraction: 0.0,
        roughness: Roughness::default(),
        source: format!(
            "DIRSIG {file} ID {} TEMP_SOLVER Therm: {}, {}, {exposed}; dry and of medium \
             roughness (irsig's defaults: THERM has neither)",
            entry.id.value,
            absorptance.map_or_else(
                || "no solar absorptance".to_owned(),
                |(a, _)| format!("solar absorptance {a}")
            ),
            emissivity.map_or_else(
                || "no thermal emissivity".to_owned(),
                |(e, _)| format!("thermal emissivity {e}")
            ),
        ),
    };
    properties.validate("thermal").map_err(|e| {
        let field = e.path.rsplit('.').next().unwrap_or_default();
        let key = match field {
            "thickness_m" => "THICKNESS",
            "conductivity_w_m_k" => "THERMAL_CONDUCTIVITY",
            "density_kg_m3" => "MASS_DENSITY",
            "specific_heat_j_kg_k" => "SPECIFIC_HEAT",
            "solar_absorptance" if get("SOLAR_ABSORPTION").is_some() => "SOLAR_ABSORPTION",
            "solar_absorptance" => "VISIBLE_EMISSIVITY",
            "thermal_emissivity" => "THERMAL_EMISSIVITY",
            _ => "",
        };
        match get(key) {
            Some((_, value)) => at(
                value,
                format!("{key} {}: as {field} in SI, {}", value.value, e.kind),
            ),
            None => block(format!("the back boundary given: {e}")),
        }
    })?;
    Ok(Some(properties))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dirsig::mat;
    use irsig_model::thermal::BackAir;

    fn entry_with(block: &str) -> String {
        format!(
            "MATERIAL_ENTRY {{\n    ID = 7\n    NAME = asphalt\n    TEMP_SOLVER_NAME = Therm\n    \
             TEMP_SOLVER {{\n{block}    }}\n}}\n"
        )
    }

    const ASPHALT: &str = "        SPECIFIC_HEAT        = 0.22\n        MASS_DENSITY         = 2.1\n        THERMAL_CONDUCTIVITY = 0.75\n        SOLAR_ABSORPTION     = 0.9\n        THERMAL_EMISSIVITY   = 0.95\n        EXPOSED_AREA         = 0.4\n        THICKNESS            = 10\n";

    fn convert(text: &str) -> Result<Option<ThermalProperties>, ParseError> {
        let entries = mat::parse("m.mat", text)?;
        thermal("m.mat", text, &entries[0], BackBoundary::Adiabatic)
    }

    #[test]
    fn a_therm_block_converts_to_si_by_hand() {
        let t = convert(&entry_with(ASPHALT)).unwrap().unwrap();
        let layer = &t.layers[0];
        // 10 cm; 2.1 g/cm³ = 2100 kg/m³; 0.22 cal/(g °C) × 4186.8 = 921.096 J/(kg K).
        assert!((layer.thickness_m - 0.1).abs() < 1e-15);
        assert!((layer.density_kg_m3 - 2100.0).abs() < 1e-9);
        assert!((layer.specific_heat_j_kg_k - 921.096).abs() < 1e-9);
        assert!((layer.conductivity_w_m_k - 0.75).abs() < 1e-15);
        assert_eq!(t.solar_absorptance, Some(0.9));
        assert_eq!(t.thermal_emissivity, Some(0.95));
        assert_eq!(t.back, BackBoundary::Adiabatic);
        assert!(t.source.contains("EXPOSED_AREA 0.4"), "{}", t.source);
        assert!(layer.source.contains("ID 7"), "{}", layer.source);
        // The back is the caller's.
        let entries = mat::parse("m.mat", &entry_with(ASPHALT)).unwrap();
        let back = BackBoundary::Convective {
            h_w_m2_k: 10.0,
            air: BackAir::Outdoor,
        };
        let t = thermal("m.mat", &entry_with(ASPHALT), &entries[0], back)
            .unwrap()
            .unwrap();
        assert_eq!(t.back, back);
        // The older name of the absorptance, alone, and the solver name in capitals.
        let older = ASPHALT.replace("SOLAR_ABSORPTION  ", "VISIBLE_EMISSIVITY");
        let text = entry_with(&older).replace("= Therm", "= THERM");
        assert_eq!(
            convert(&text).unwrap().unwrap().solar_absorptance,
            Some(0.9)
        );
    }

    #[test]
    fn other_solvers_give_no_thermal_record() {
        let data_driven = "MATERIAL_ENTRY {\n  ID = 1\n  NAME = hot\n  TEMP_SOLVER_NAME = DataDriven\n  TEMP_SOLVER {\n    TEMPERATURE = 1500\n  }\n}\n";
        assert_eq!(convert(data_driven).unwrap(), None);
        let none = "MATERIAL_ENTRY {\n  ID = 1\n  NAME = bare\n}\n";
        assert_eq!(convert(none).unwrap(), None);
    }

    /// `(line, column, message)` of the refusal of a block with `old` replaced by `new`.
    fn refused(old: &str, new: &str) -> (usize, usize, String) {
        let e = convert(&entry_with(&ASPHALT.replace(old, new))).unwrap_err();
        (e.line, e.column, e.message)
    }

    #[test]
    fn what_irsig_cannot_represent_is_refused_at_its_value() {
        // Lines: 5 opens the block, 6-12 its keys; values at column 32.
        let (l, c, m) = refused("= 10\n", "= 0\n");
        assert_eq!((l, c), (12, 32), "{m}");
        assert!(m.contains("THICKNESS 0"), "{m}");
        let (l, c, m) = refused("= 0.4\n", "= -0.4\n");
        assert_eq!((l, c), (11, 32), "{m}");
        assert!(m.contains("negative"), "{m}");
        let (l, c, _) = refused("= 0.4\n", "= 1.5\n");
        assert_eq!((l, c), (11, 32));
        let (l, c, m) = refused("= 0.75\n", "= 0\n");
        assert_eq!((l, c), (8, 32), "{m}");
        assert!(
            m.contains("conductivity_w_m_k") && m.contains("out of range"),
            "{m}"
        );
        let (l, c, m) = refused("= 0.9\n", "= 1.2\n");
        assert_eq!(
            (l, c, m.contains("solar_absorptance")),
            (9, 32, true),
            "{m}"
        );
        let (l, c, m) = refused("= 2.1\n", "= dense\n");
        assert_eq!((l, c, m.contains("number")), (7, 32, true), "{m}");
        // An unknown key, at the key.
        let (l, c, m) = refused("EXPOSED_AREA ", "HEAT_SOURCE  ");
        assert_eq!((l, c), (11, 9), "{m}");
        assert!(m.contains("HEAT_SOURCE"), "{m}");
        // A required key missing, at the block.
        let (l, c, m) = refused("        THICKNESS            = 10\n", "");
        assert_eq!((l, c), (5, 5), "{m}");
        assert!(m.contains("no THICKNESS"), "{m}");
        // Both names of the absorptance.
        let both = format!("{ASPHALT}        VISIBLE_EMISSIVITY   = 0.8\n");
        let e = convert(&entry_with(&both)).unwrap_err();
        assert_eq!((e.line, e.column), (13, 32), "{e}");
    }

    #[test]
    fn dirsigs_own_database_is_refused_where_it_means_something_irsig_cannot_say() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/third-party/dirsig-channel/anadirsig.mat");
        let text = std::fs::read_to_string(path).unwrap();
        let entries = mat::parse("anadirsig.mat", &text).unwrap();
        let at = |i: usize| {
            let e =
                thermal("anadirsig.mat", &text, &entries[i], BackBoundary::Adiabatic).unwrap_err();
            (e.line, e.column)
        };
        assert_eq!(
            thermal("anadirsig.mat", &text, &entries[0], BackBoundary::Adiabatic).unwrap(),
            None,
            "ID 100's solver is Null"
        );
        // Water: EXPOSED_AREA -0.4 (line 37); grass: THICKNESS 0 (line 70); dirt:
        // EXPOSED_AREA -0.5 (line 101). Values at column 32.
        assert_eq!(at(1), (37, 32));
        assert_eq!(at(2), (70, 32));
        assert_eq!(at(3), (101, 32));
    }
}
