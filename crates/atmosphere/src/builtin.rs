//! The built-in atmospheres: LOWTRAN7's six standard models as 8–14 µm band tables and
//! 7.41–14.08 µm spectra in canonical form, shipped inside the binary so scenes can name
//! them, and decoded by `irsig-formats` (this crate knows no file syntax).

use irsig_model::{Atmosphere, SpectralAtmosphere};

use crate::error::{AtmosphereError, AtmosphereErrorKind};

/// Names of the built-in atmospheres: LOWTRAN7's models 6, 3, 1, 2, 4 and 5.
pub const BUILTIN_NAMES: [&str; 6] = [
    "us-std-1976",
    "midlat-winter",
    "tropical",
    "midlat-summer",
    "subarctic-summer",
    "subarctic-winter",
];

/// The canonical RON text of a built-in atmosphere.
#[must_use]
pub fn builtin_ron(name: &str) -> Option<&'static str> {
    match name {
        "us-std-1976" => Some(include_str!("../data/us-std-1976.ron")),
        "midlat-winter" => Some(include_str!("../data/midlat-winter.ron")),
        "tropical" => Some(include_str!("../data/tropical.ron")),
        "midlat-summer" => Some(include_str!("../data/midlat-summer.ron")),
        "subarctic-summer" => Some(include_str!("../data/subarctic-summer.ron")),
        "subarctic-winter" => Some(include_str!("../data/subarctic-winter.ron")),
        _ => None,
    }
}

/// A built-in atmosphere by name ([`BUILTIN_NAMES`]: `us-std-1976`, `midlat-winter`,
/// `tropical`, `midlat-summer`, `subarctic-summer`, `subarctic-winter`): LOWTRAN7 models
/// 6, 3, 1, 2, 4 and 5, no aerosol, 8–14 µm, with slant tables for the `table` model whose
/// rows were placed by error (`slant.interpolation_residual` says how far between them
/// the interpolation was found from LOWTRAN7). See `crates/atmosphere/data/README.md` for
/// provenance and caveats.
///
/// # Errors
/// An unknown name.
pub fn builtin(name: &str) -> Result<Atmosphere, AtmosphereError> {
    let text =
        builtin_ron(name).ok_or_else(|| AtmosphereErrorKind::UnknownBuiltin(name.to_owned()))?;
    irsig_formats::canonical::from_ron::<Atmosphere>(&format!("builtin:{name}"), text).map_err(
        |e| {
            AtmosphereErrorKind::CorruptBuiltin {
                name: name.to_owned(),
                message: e.to_string(),
            }
            .into()
        },
    )
}

/// The bytes of a built-in spectral atmosphere (binary spectral atmosphere,
/// `formats/canonical/spectral-atmosphere.md`).
#[must_use]
pub fn builtin_spectral_bytes(name: &str) -> Option<&'static [u8]> {
    match name {
        "us-std-1976" => Some(include_bytes!("../data/us-std-1976.spectral.bin")),
        "midlat-winter" => Some(include_bytes!("../data/midlat-winter.spectral.bin")),
        "tropical" => Some(include_bytes!("../data/tropical.spectral.bin")),
        "midlat-summer" => Some(include_bytes!("../data/midlat-summer.spectral.bin")),
        "subarctic-summer" => Some(include_bytes!("../data/subarctic-summer.spectral.bin")),
        "subarctic-winter" => Some(include_bytes!("../data/subarctic-winter.spectral.bin")),
        _ => None,
    }
}

/// A built-in atmosphere in spectral form (LOWTRAN7's 710–1350 cm⁻¹ every 5 cm⁻¹, at the
/// paths and nodes of [`builtin`]): [`crate::collapse`] over flat 8–14 µm gives
/// [`builtin`]'s tables back (`tests/spectral.rs`), and over any other band or response
/// the band atmosphere for that sensor.
///
/// # Errors
/// An unknown name.
pub fn builtin_spectral(name: &str) -> Result<SpectralAtmosphere, AtmosphereError> {
    let bytes = builtin_spectral_bytes(name)
        .ok_or_else(|| AtmosphereErrorKind::UnknownBuiltin(name.to_owned()))?;
    irsig_formats::canonical::binary_spectral::decode(name, bytes).map_err(|e| {
        AtmosphereErrorKind::CorruptBuiltin {
            name: name.to_owned(),
            message: e.to_string(),
        }
        .into()
    })
}
