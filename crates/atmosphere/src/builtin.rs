//! The built-in atmospheres: LOWTRAN7's six standard models as 8–14 µm band tables,
//! 7.41–14.08 µm spectra and, for night, 2.99–5.00 µm spectra in canonical form, shipped
//! inside the binary so scenes can name them, and decoded by `irsig-formats` (this crate
//! knows no file syntax).

use irsig_model::{Atmosphere, SpectralAtmosphere};

use crate::error::{AtmosphereError, AtmosphereErrorKind};

/// LOWTRAN7's six standard models by name and number (its card 1 MODEL), in the order of
/// [`BUILTIN_NAMES`]: every built-in is one of them, and `irsig-atmos plan` names them so.
pub const STANDARD_MODELS: [(&str, u8); 6] = [
    ("us-std-1976", 6),
    ("midlat-winter", 3),
    ("tropical", 1),
    ("midlat-summer", 2),
    ("subarctic-summer", 4),
    ("subarctic-winter", 5),
];

/// Names of the built-in atmospheres: LOWTRAN7's models 6, 3, 1, 2, 4 and 5
/// ([`STANDARD_MODELS`]).
pub const BUILTIN_NAMES: [&str; 6] = {
    let mut names = [""; 6];
    let mut i = 0;
    while i < names.len() {
        names[i] = STANDARD_MODELS[i].0;
        i += 1;
    }
    names
};

/// The top of every built-in's profile and sky rows, metres above the ground: the highest
/// observer their data hold. Above it a path would take the air above 10 km as absent
/// (from 30 km: +3 K at nadir and a sky 29 K too warm against LOWTRAN7), so a camera
/// there is refused, with the way to build an atmosphere for it.
pub const BUILTIN_TOP_M: f64 = 10_000.0;

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

/// The bytes of a built-in's 3–5 µm night spectra (binary spectral atmosphere, version 2:
/// quantised to 16 bits and deflated, `formats/canonical/spectral-atmosphere.md`).
#[must_use]
pub fn builtin_spectral_mwir_bytes(name: &str) -> Option<&'static [u8]> {
    match name {
        "us-std-1976" => Some(include_bytes!("../data/us-std-1976.mwir.bin")),
        "midlat-winter" => Some(include_bytes!("../data/midlat-winter.mwir.bin")),
        "tropical" => Some(include_bytes!("../data/tropical.mwir.bin")),
        "midlat-summer" => Some(include_bytes!("../data/midlat-summer.mwir.bin")),
        "subarctic-summer" => Some(include_bytes!("../data/subarctic-summer.mwir.bin")),
        "subarctic-winter" => Some(include_bytes!("../data/subarctic-winter.mwir.bin")),
        _ => None,
    }
}

/// The spectral ranges the built-ins hold, µm, as their grids span them: 710–1350 cm⁻¹
/// (8–14 µm responses) and 2000–3340 cm⁻¹ (3–5 µm responses, night only).
pub const BUILTIN_SPECTRAL_RANGES_UM: [[f64; 2]; 2] =
    [[1e4 / 1350.0, 1e4 / 710.0], [1e4 / 3340.0, 1e4 / 2000.0]];

/// The bytes of the built-in `name`'s spectra that cover `[lo, hi]` µm: its 7.41–14.08 µm
/// spectra ([`builtin_spectral_bytes`]) or its 2.99–5.00 µm night spectra
/// ([`builtin_spectral_mwir_bytes`]); `None` for an unknown name or a band inside neither
/// ([`BUILTIN_SPECTRAL_RANGES_UM`]).
#[must_use]
pub fn builtin_spectral_bytes_over(name: &str, [lo, hi]: [f64; 2]) -> Option<&'static [u8]> {
    let inside = |[min, max]: [f64; 2]| {
        let slack = 1e-9 * max;
        lo >= min - slack && hi <= max + slack
    };
    if inside(BUILTIN_SPECTRAL_RANGES_UM[0]) {
        builtin_spectral_bytes(name)
    } else if inside(BUILTIN_SPECTRAL_RANGES_UM[1]) {
        builtin_spectral_mwir_bytes(name)
    } else {
        None
    }
}

/// The built-in `name`'s spectra that cover `[lo, hi]` µm (see
/// [`builtin_spectral_bytes_over`]), decoded; `None` when neither range covers the band.
///
/// # Errors
/// An unknown name.
pub fn builtin_spectral_over(
    name: &str,
    range_um: [f64; 2],
) -> Result<Option<SpectralAtmosphere>, AtmosphereError> {
    if !BUILTIN_NAMES.contains(&name) {
        return Err(AtmosphereErrorKind::UnknownBuiltin(name.to_owned()).into());
    }
    builtin_spectral_bytes_over(name, range_um)
        .map(|bytes| decode_builtin(name, bytes))
        .transpose()
}

/// A built-in's 3–5 µm night spectra (LOWTRAN7's 2000–3340 cm⁻¹ every 5 cm⁻¹, IEMSCT = 1,
/// at the paths and nodes of [`builtin_spectral`], its rows): collapsed over a band or
/// response inside 3–5 µm, the band atmosphere for that sensor at night. No `solar` table:
/// by day the sun's geometry is part of the atmosphere, which `irsig-atmos build` makes.
///
/// # Errors
/// An unknown name.
pub fn builtin_spectral_mwir(name: &str) -> Result<SpectralAtmosphere, AtmosphereError> {
    let bytes = builtin_spectral_mwir_bytes(name)
        .ok_or_else(|| AtmosphereErrorKind::UnknownBuiltin(name.to_owned()))?;
    decode_builtin(name, bytes)
}

fn decode_builtin(name: &str, bytes: &[u8]) -> Result<SpectralAtmosphere, AtmosphereError> {
    irsig_formats::canonical::binary_spectral::decode(name, bytes).map_err(|e| {
        AtmosphereErrorKind::CorruptBuiltin {
            name: name.to_owned(),
            message: e.to_string(),
        }
        .into()
    })
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
    decode_builtin(name, bytes)
}
