//! The canonical irsig files: every `irsig_model` type as RON, and the raw scene also as a
//! compact binary form.
//!
//! Reading parses and then validates: a syntax error carries the RON error's line and
//! column; a value that breaks a model rule (an emissivity of 1.3) is reported with its
//! path into the data (`materials[1].emissivity[1]`) and, where the path can be followed in
//! the text, the line and column of that value.
//!
//! | type | RON | binary |
//! | --- | --- | --- |
//! | [`Object`] | yes (small objects, hand-made tests, diffs) | yes ([`binary_object`], what `irsig-import` writes into a pipe) |
//! | [`Scene`] | yes | no |
//! | [`RawScene`] | yes (small scenes, hand-made tests, diffs) | yes ([`binary`], the default for `irsig-flatten`) |
//! | [`MaterialLibrary`], [`Atmosphere`], [`View`], [`RegionSet`], [`Decision`], [`Uncertainties`] | yes | no |
//! | [`LoadsPlan`], [`BroadbandLoads`] | yes | no |
//!
//! The format pages are `formats/canonical/*.md` in the repository.

pub mod binary;
pub mod binary_history;
pub mod binary_object;
pub mod binary_spectral;
mod layout;

use irsig_model::decision::Decision;
use irsig_model::loads::{BroadbandLoads, LoadsPlan};
use irsig_model::provenance::Provenance;
use irsig_model::uncertainty::Uncertainties;
use irsig_model::{
    Atmosphere, AtmospherePlan, MaterialLibrary, ModelError, Object, RawScene, RegionSet, Scene,
    SpectralAtmosphere, View,
};
use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::ParseError;

/// A canonical irsig type: what it is called in messages, how deep its RON is pretty-printed
/// and how it is validated.
pub trait Canonical: Serialize + DeserializeOwned {
    /// What the file holds, for messages ("object", "material library").
    const WHAT: &'static str;
    /// Nesting depth up to which the RON writer breaks lines; deeper values stay on one
    /// line, so a vertex or a facet is one line of the file.
    const PRETTY_DEPTH: usize;
    /// The model's own checks.
    ///
    /// # Errors
    /// The first rule broken, with its path into the data.
    fn check(&self) -> Result<(), ModelError>;
}

macro_rules! canonical {
    ($ty:ty, $what:literal, $depth:literal) => {
        impl Canonical for $ty {
            const WHAT: &'static str = $what;
            const PRETTY_DEPTH: usize = $depth;
            fn check(&self) -> Result<(), ModelError> {
                self.validate()
            }
        }
    };
}

canonical!(Object, "object", 2);
canonical!(Scene, "scene", 4);
canonical!(RawScene, "raw scene", 2);
canonical!(MaterialLibrary, "material library", 3);
canonical!(Atmosphere, "atmosphere", 3);
canonical!(View, "view", 2);
canonical!(RegionSet, "regions file", 3);
canonical!(SpectralAtmosphere, "spectral atmosphere", 2);
canonical!(AtmospherePlan, "atmosphere plan", 2);
canonical!(LoadsPlan, "loads plan", 4);
canonical!(BroadbandLoads, "broadband loads table", 2);
canonical!(Decision, "decision", 3);
canonical!(Uncertainties, "uncertainties file", 3);
canonical!(Provenance, "provenance", 3);

/// The first line of an image's comments that hold its provenance, which follows as
/// canonical RON (formats/images.md): an image of another program has other comments.
const PROVENANCE_HEADER: &str = "irsig provenance (canonical RON)\n";

/// `provenance` as the text of an image's comments.
///
/// # Errors
/// Only if RON serialisation fails, which it does not for finite numbers.
pub fn provenance_comments(provenance: &Provenance) -> Result<String, ron::Error> {
    Ok(format!("{PROVENANCE_HEADER}{}", to_ron(provenance)?))
}

/// The provenance an image's comments hold (`file` names the image in messages): `None`
/// for comments that are not irsig's provenance.
///
/// # Errors
/// irsig's header followed by RON that is not a valid provenance.
pub fn provenance_of(file: &str, comments: &str) -> Option<Result<Provenance, ParseError>> {
    let ron = comments.strip_prefix(PROVENANCE_HEADER)?;
    Some(from_ron(&format!("{file} (its provenance)"), ron))
}

/// Parses RON text into `T` without validating it.
///
/// # Errors
/// A syntax or shape error at the RON error's line and column.
pub fn from_ron_unchecked<T: Canonical>(file: &str, text: &str) -> Result<T, ParseError> {
    from_ron_as(file, text, T::WHAT)
}

/// Parses RON text into any serde type, for RON files that are not a model type (slant
/// tables, a tool's own state); `what` names the file's content in messages.
///
/// # Errors
/// A syntax or shape error at the RON error's line and column.
pub fn from_ron_as<T: DeserializeOwned>(
    file: &str,
    text: &str,
    what: &str,
) -> Result<T, ParseError> {
    ron::from_str::<T>(text).map_err(|e| {
        let offset = crate::offset_of(text, e.span.start.line, e.span.start.col);
        let message = match e.code {
            // ron says "Expected option"; the user wrote a plain value where the model has
            // an optional one.
            ron::Error::ExpectedOption => {
                let rest = text.get(offset..).unwrap_or("");
                let value = rest
                    .split([',', ')', ']', '\n'])
                    .next()
                    .unwrap_or("")
                    .trim();
                if value.is_empty() || value.starts_with("Some") || value == "None" {
                    "expected an optional value: write `Some(value)`, or `None`".to_owned()
                } else {
                    format!(
                        "expected an optional value: write `Some({value})` for `{value}` (or \
                         `None` for none)"
                    )
                }
            }
            ref code => ron_message(code),
        };
        ParseError::at_offset(
            file,
            text,
            offset,
            format!("malformed {what} (RON): {message}"),
        )
    })
}

/// What a RON error says, in the user's terms: ron's own text where it speaks of the file,
/// and what is wrong with the file where ron speaks of its API (its recursion limit).
#[must_use]
pub fn ron_message(code: &ron::Error) -> String {
    match code {
        ron::Error::ExceededRecursionLimit => "values are nested too deeply (more than 128 \
            levels of brackets); no irsig file nests more than a few"
            .to_owned(),
        other => other.to_string(),
    }
}

/// Any serde value as pretty-printed RON, for RON that is not a model type (a table of
/// numbers a tool prints, a tool's own state).
///
/// # Errors
/// Only if serde fails, which it does not for finite numbers.
pub fn to_ron_pretty<T: Serialize>(value: &T) -> Result<String, ron::Error> {
    ron::ser::to_string_pretty(value, ron::ser::PrettyConfig::default())
}

/// Parses and validates RON text.
///
/// # Errors
/// A syntax error (at the RON error's line and column) or the first broken model rule (at
/// the value's line and column where the path can be followed in the text, else at the
/// start of the file), always naming `file`.
pub fn from_ron<T: Canonical>(file: &str, text: &str) -> Result<T, ParseError> {
    let value: T = from_ron_unchecked(file, text)?;
    value
        .check()
        .map_err(|e| validation_error::<T>(file, text, &e))?;
    Ok(value)
}

/// Parses and validates RON bytes, rejecting text that is not UTF-8 with the offset of the
/// first bad byte.
///
/// # Errors
/// As [`from_ron`], plus non-UTF-8 input.
pub fn from_ron_bytes<T: Canonical>(file: &str, bytes: &[u8]) -> Result<T, ParseError> {
    from_ron(file, utf8(file, bytes)?)
}

/// The text of `bytes`, or an error at the first byte that is not UTF-8.
///
/// # Errors
/// Non-UTF-8 input.
pub fn utf8<'a>(file: &str, bytes: &'a [u8]) -> Result<&'a str, ParseError> {
    std::str::from_utf8(bytes).map_err(|e| {
        let good = &bytes[..e.valid_up_to()];
        // Safe: the prefix up to valid_up_to is UTF-8 by definition.
        let text = std::str::from_utf8(good).unwrap_or("");
        ParseError::at_offset(
            file,
            text,
            text.len(),
            format!(
                "expected UTF-8 text, found a byte that is not (byte offset {})",
                e.valid_up_to()
            ),
        )
    })
}

/// An error about the value at a model `path` (`regions[2].pixels`) of canonical RON `text`,
/// at that value's line and column where the path can be followed (else the start of the
/// file): for checks a tool makes after reading, such as a region that selects no pixel
/// of a particular image.
#[must_use]
pub fn error_at_path(file: &str, text: &str, path: &str, message: impl Into<String>) -> ParseError {
    let (start, end) = crate::ron_tree::locate(text, path);
    ParseError::at_span(file, text, start, (end - start).max(1), message)
}

fn validation_error<T: Canonical>(file: &str, text: &str, e: &ModelError) -> ParseError {
    error_at_path(
        file,
        text,
        &e.path,
        format!("invalid {}: `{}`: {}", T::WHAT, e.path, e.kind),
    )
}

/// Writes `value` as RON, pretty-printed to the type's depth, with a trailing newline.
///
/// # Errors
/// Only if serde fails, which the model types never do for finite numbers.
pub fn to_ron<T: Canonical>(value: &T) -> Result<String, ron::Error> {
    to_ron_at_depth(value, T::PRETTY_DEPTH)
}

/// Any serde value as RON in the canonical layout: lines broken down to nesting `depth`
/// (deeper values stay on one line), two-space indents, a trailing newline. For RON a tool
/// writes that is not a model type (a table of results).
///
/// # Errors
/// Only if serde fails, which it does not for finite numbers.
pub fn to_ron_at_depth<T: Serialize>(value: &T, depth: usize) -> Result<String, ron::Error> {
    let config = ron::ser::PrettyConfig::new()
        .depth_limit(depth)
        .indentor("  ")
        .separate_tuple_members(false);
    let mut text = ron::ser::to_string_pretty(value, config)?;
    text.push('\n');
    Ok(text)
}

/// Writes `value` as RON to `w`.
///
/// # Errors
/// An I/O error from `w`, or a serialisation error as an I/O error.
pub fn write_ron<T: Canonical>(value: &T, w: &mut dyn std::io::Write) -> std::io::Result<()> {
    let text = to_ron(value).map_err(std::io::Error::other)?;
    w.write_all(text.as_bytes())
}

/// Reads a raw scene in either form: binary when the bytes start with
/// [`binary::MAGIC`], RON otherwise. Validates it.
///
/// # Errors
/// As [`binary::decode`] or [`from_ron_bytes`].
pub fn read_raw_scene(file: &str, bytes: &[u8]) -> Result<RawScene, ParseError> {
    if binary::is_binary(bytes) {
        let scene = binary::decode(file, bytes)?;
        scene.validate().map_err(|e| {
            ParseError::in_binary(
                file,
                binary::offset_of_path(&scene, &e.path),
                format!("invalid raw scene: `{}`: {}", e.path, e.kind),
            )
        })?;
        Ok(scene)
    } else {
        from_ron_bytes(file, bytes)
    }
}

/// Reads a spectral atmosphere in either form: binary when the bytes start with
/// [`binary_spectral::MAGIC`], RON otherwise. Validates it.
///
/// # Errors
/// As [`binary_spectral::decode`] or [`from_ron_bytes`].
pub fn read_spectral_atmosphere(
    file: &str,
    bytes: &[u8],
) -> Result<SpectralAtmosphere, ParseError> {
    if binary_spectral::is_binary(bytes) {
        binary_spectral::decode(file, bytes)
    } else {
        from_ron_bytes(file, bytes)
    }
}

/// An error at a model path (`grid.points`) of a spectral atmosphere in either form: in
/// the RON, or in the binary form's RON header, at its byte offset.
#[must_use]
pub fn spectral_atmosphere_error_at_path(
    file: &str,
    bytes: &[u8],
    path: &str,
    message: impl Into<String>,
) -> ParseError {
    if binary_spectral::is_binary(bytes) {
        let (offset, header) = binary_spectral::header(bytes).unwrap_or((16, ""));
        let (start, _) = crate::ron_tree::locate(header, path);
        ParseError::in_binary(file, offset + start, message)
    } else {
        error_at_path(file, &String::from_utf8_lossy(bytes), path, message)
    }
}

/// An atmosphere file in any canonical form: a band atmosphere (RON), or a spectral one
/// (binary or RON).
#[derive(Debug, Clone, PartialEq)]
#[allow(clippy::large_enum_variant)] // one per file read
pub enum AnyAtmosphere {
    /// Band tables.
    Band(Atmosphere),
    /// Spectra.
    Spectral(SpectralAtmosphere),
}

/// Reads an atmosphere file of either kind: binary spectral by its magic; in RON, a
/// spectral atmosphere by its top-level `grid` field (a band atmosphere has none), else a
/// band one.
///
/// # Errors
/// As [`read_spectral_atmosphere`] or [`from_ron_bytes`]: the band atmosphere's errors for
/// a RON file without a `grid`.
pub fn read_any_atmosphere(file: &str, bytes: &[u8]) -> Result<AnyAtmosphere, ParseError> {
    if binary_spectral::is_binary(bytes) {
        return binary_spectral::decode(file, bytes).map(AnyAtmosphere::Spectral);
    }
    let text = utf8(file, bytes)?;
    if crate::ron_tree::has_top_level_field(text, "grid") {
        from_ron(file, text).map(AnyAtmosphere::Spectral)
    } else {
        from_ron(file, text).map(AnyAtmosphere::Band)
    }
}

/// A plan file of either kind.
#[derive(Debug, Clone, PartialEq)]
#[allow(clippy::large_enum_variant)] // one per file read
pub enum AnyPlan {
    /// The paths of a spectral atmosphere for a scene.
    Atmosphere(AtmospherePlan),
    /// The paths of a day's broadband loads.
    Loads(LoadsPlan),
}

/// Reads a plan file of either kind (RON): a loads plan by its top-level `longwave` field
/// (an atmosphere plan has none), else an atmosphere plan.
///
/// # Errors
/// As [`from_ron_bytes`], with the errors of the kind the file is taken for.
pub fn read_any_plan(file: &str, bytes: &[u8]) -> Result<AnyPlan, ParseError> {
    let text = utf8(file, bytes)?;
    if crate::ron_tree::has_top_level_field(text, "longwave") {
        from_ron(file, text).map(AnyPlan::Loads)
    } else {
        from_ron(file, text).map(AnyPlan::Atmosphere)
    }
}

/// Reads an object in either form: binary when the bytes start with
/// [`binary_object::MAGIC`] or `file` ends in `.bin` (so that a damaged binary file is
/// reported as one), RON otherwise. Validates it; a rule broken in a binary object is
/// reported at the byte offset of the record it concerns.
///
/// # Errors
/// As [`binary_object::decode`] or [`from_ron_bytes`], or the first broken model rule.
pub fn read_object(file: &str, bytes: &[u8]) -> Result<Object, ParseError> {
    if binary_object::is_binary(bytes) || file.ends_with(".bin") {
        let object = binary_object::decode(file, bytes)?;
        object.validate().map_err(|e| {
            ParseError::in_binary(
                file,
                binary_object::offset_of_path(&object, &e.path),
                format!("invalid object: `{}`: {}", e.path, e.kind),
            )
        })?;
        Ok(object)
    } else {
        from_ron_bytes(file, bytes)
    }
}

/// An error about the value at a model `path` (`facets[3].material`) of an object read
/// from `bytes` by [`read_object`]: at the value's line and column in RON, at the record's
/// byte offset in the binary form. For checks a tool makes after reading, such as a
/// material id the library does not define.
#[must_use]
pub fn object_error_at_path(
    file: &str,
    bytes: &[u8],
    object: &Object,
    path: &str,
    message: impl Into<String>,
) -> ParseError {
    if binary_object::is_binary(bytes) || file.ends_with(".bin") {
        ParseError::in_binary(file, binary_object::offset_of_path(object, path), message)
    } else {
        error_at_path(file, &String::from_utf8_lossy(bytes), path, message)
    }
}

/// As [`object_error_at_path`], for a raw scene read by [`read_raw_scene`].
#[must_use]
pub fn raw_scene_error_at_path(
    file: &str,
    bytes: &[u8],
    scene: &RawScene,
    path: &str,
    message: impl Into<String>,
) -> ParseError {
    if binary::is_binary(bytes) {
        ParseError::in_binary(file, binary::offset_of_path(scene, path), message)
    } else {
        error_at_path(file, &String::from_utf8_lossy(bytes), path, message)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::{Material, MaterialId};

    fn library() -> MaterialLibrary {
        MaterialLibrary {
            materials: vec![
                Material {
                    id: MaterialId(1),
                    name: "asphalt".into(),
                    emissivity: vec![(0.0, 0.96), (90.0, 0.0)],
                    specular_fraction: 0.0,
                    source: "test".into(),
                    band_um: None,
                    spectral: None,
                    rms_slope: None,
                    thermal: None,
                    texture: None,
                    maps: None,
                },
                Material {
                    id: MaterialId(2),
                    name: "steel".into(),
                    emissivity: vec![(0.0, 0.3), (60.0, 0.25)],
                    specular_fraction: 1.0,
                    source: "test".into(),
                    band_um: None,
                    spectral: None,
                    rms_slope: None,
                    thermal: None,
                    texture: None,
                    maps: None,
                },
            ],
        }
    }

    #[test]
    fn deep_nesting_is_said_in_the_files_terms() {
        let text = format!("{}{}", "[".repeat(10_000), "]".repeat(10_000));
        let e = from_ron_as::<ron::Value>("deep.ron", &text, "table").unwrap_err();
        assert!(e.message.contains("nested too deeply"), "{e}");
        assert!(!e.message.contains("serde_stacker"), "{e}");
    }

    #[test]
    fn a_plain_value_where_an_option_goes_is_told_how_to_write_it() {
        let text = "(regions: [(name: \"panel\", material: 3)])";
        let e = from_ron::<RegionSet>("r.ron", text).unwrap_err();
        assert!(e.message.contains("write `Some(3)` for `3`"), "{e}");
        // At the value (ron points at the space before it).
        assert_eq!((e.line, e.column), (1, 37), "{e}");
    }

    #[test]
    fn a_library_round_trips() {
        let lib = library();
        let text = to_ron(&lib).unwrap();
        assert_eq!(from_ron::<MaterialLibrary>("lib.ron", &text).unwrap(), lib);
    }

    #[test]
    fn syntax_errors_carry_ron_line_and_column() {
        let text = "(\n  materials: [\n    (id: 1, name: \"a\", emissivity: [(0.0, 0.9)], specular_fraction: 0.0, source: \"x\" oops),\n  ],\n)\n";
        let e = from_ron::<MaterialLibrary>("lib.ron", text).unwrap_err();
        assert_eq!(e.file, "lib.ron");
        assert_eq!(e.line, 3, "{e}");
        assert!(e.column > 80, "{e}");
    }

    #[test]
    fn validation_errors_point_at_the_value() {
        let text = "(\n  materials: [\n    (id: 1, name: \"a\", emissivity: [(0.0, 0.9)], specular_fraction: 0.0, source: \"x\"),\n    (id: 2, name: \"b\", emissivity: [(0.0, 0.9), (45.0, 1.3)], specular_fraction: 0.0, source: \"x\"),\n  ],\n)\n";
        let e = from_ron::<MaterialLibrary>("lib.ron", text).unwrap_err();
        assert!(
            e.message.contains("materials[1].emissivity[1].emissivity"),
            "{e}"
        );
        // The path is followed to the tuple `(45.0, 1.3)` on line 4.
        assert_eq!(e.line, 4, "{e}");
        let col_of_tuple = text.lines().nth(3).unwrap().find("(45.0").unwrap() + 1;
        assert_eq!(e.column, col_of_tuple, "{e}");
        assert!(e.to_string().starts_with("lib.ron:4:"));
    }

    #[test]
    fn non_utf8_is_rejected_with_its_offset() {
        let e = from_ron_bytes::<MaterialLibrary>("lib.ron", b"(materials: [\xff])").unwrap_err();
        assert!(e.message.contains("byte offset 13"), "{e}");
    }
}
