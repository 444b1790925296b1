//! The compact binary spectral atmosphere: what `irsig-atmos build` writes and the
//! built-ins are embedded as. A spectral atmosphere holds tens of thousands of numbers
//! (the built-ins ~80 000 each); as RON they would be ~1 MB and take tens of milliseconds
//! to parse, as single-precision binary they are ~320 kB and load in well under a
//! millisecond. Spec page: `formats/canonical/spectral-atmosphere.md`.
//!
//! Layout (little-endian, no padding):
//!
//! | offset | size | field |
//! | --- | --- | --- |
//! | 0 | 8 | magic `IRSIGSPA` |
//! | 8 | 4 | `u32` version, 1 or 2 |
//! | 12 | 4 | `u32` byte length `H` of the header |
//! | 16 | `H` | header: the atmosphere as canonical RON (UTF-8) with every table of spectra empty |
//! | 16 + `H` | … | the tables of spectra, each a `u32` count `N` and `N` `f32` values (version 1), or (version 2) a `u32` count `N`, a `u32` byte length `Z` and `Z` bytes of a zlib stream of the table quantised to 16 bits per value ([`encode_quantised`]) |
//!
//! The tables follow in this order, each only when the header has the field:
//! `level_transmission`, `level_path_radiance_w_m2_sr_per_unit`,
//! `transmission_correction.transmission`, `sky_radiance_w_m2_sr_per_unit`,
//! `sky_hemispheric_w_m2_sr_per_unit`, `slant.transmission`,
//! `slant.path_radiance_w_m2_sr_per_unit`, `slant.sky_radiance_w_m2_sr_per_unit`,
//! `solar.extraterrestrial_w_m2_per_unit`, `solar.transmission`, and when
//! `solar.relative_azimuth_deg` is not empty `solar.path_scattered_w_m2_sr_per_unit`,
//! `solar.sky_scattered_w_m2_sr_per_unit`, then each of `solar.further_suns`'
//! `transmission` (and, when `solar.relative_azimuth_deg` is not empty, its
//! `path_scattered_w_m2_sr_per_unit` and `sky_scattered_w_m2_sr_per_unit`), then
//! `solar.phase.scattered_w_m2_sr_per_unit_per_m` when `solar.phase` is there, then for each
//! of `slabs`, its `down` and its
//! `up` table when present, `transmission`, `path_radiance_w_m2_sr_per_unit` and, when
//! `solar.relative_azimuth_deg` is not empty, `scattered_w_m2_sr_per_unit`. (A file
//! without slabs is what it was before them. A file without a `solar` table is what
//! version 1 always was: its bytes do not change; nor does one whose sun has no
//! scattered-sunlight tables, nor one with a single sun.)
//! Each count is checked against the bytes left before anything is allocated; the file
//! must end after the last table; the result is validated.

use irsig_model::SpectralAtmosphere;

use crate::ParseError;

/// The first eight bytes of a binary spectral atmosphere.
pub const MAGIC: &[u8; 8] = b"IRSIGSPA";
/// The layout version [`encode`] writes: every value an `f32`.
pub const VERSION: u32 = 1;
/// The layout version [`encode_quantised`] writes: each table quantised to 16 bits per
/// value against its spectra's maxima, and deflated (zlib). Both are read.
pub const VERSION_QUANTISED: u32 = 2;

/// True when `bytes` start with [`MAGIC`].
#[must_use]
pub fn is_binary(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

fn tables(a: &SpectralAtmosphere) -> Vec<&Vec<f32>> {
    let mut t = vec![
        &a.level_transmission,
        &a.level_path_radiance_w_m2_sr_per_unit,
    ];
    if let Some(c) = &a.transmission_correction {
        t.push(&c.transmission);
    }
    t.push(&a.sky_radiance_w_m2_sr_per_unit);
    if let Some(h) = &a.sky_hemispheric_w_m2_sr_per_unit {
        t.push(h);
    }
    if let Some(s) = &a.slant {
        t.extend([
            &s.transmission,
            &s.path_radiance_w_m2_sr_per_unit,
            &s.sky_radiance_w_m2_sr_per_unit,
        ]);
    }
    if let Some(s) = &a.solar {
        t.extend([&s.extraterrestrial_w_m2_per_unit, &s.transmission]);
        if !s.relative_azimuth_deg.is_empty() {
            t.extend([
                &s.path_scattered_w_m2_sr_per_unit,
                &s.sky_scattered_w_m2_sr_per_unit,
            ]);
        }
        for b in &s.further_suns {
            t.push(&b.transmission);
            if !s.relative_azimuth_deg.is_empty() {
                t.extend([
                    &b.path_scattered_w_m2_sr_per_unit,
                    &b.sky_scattered_w_m2_sr_per_unit,
                ]);
            }
        }
        if let Some(p) = &s.phase {
            t.push(&p.scattered_w_m2_sr_per_unit_per_m);
        }
    }
    let lit = a
        .solar
        .as_ref()
        .is_some_and(|s| !s.relative_azimuth_deg.is_empty());
    for table in a.slabs.iter().flat_map(|s| [&s.down, &s.up]).flatten() {
        t.extend([&table.transmission, &table.path_radiance_w_m2_sr_per_unit]);
        if lit {
            t.push(&table.scattered_w_m2_sr_per_unit);
        }
    }
    t
}

fn tables_mut(a: &mut SpectralAtmosphere) -> Vec<&mut Vec<f32>> {
    // The header holds no values: a slab table's scattered spectra follow when the
    // atmosphere has the sun's azimuths (as `validate` requires them then).
    let lit = a
        .solar
        .as_ref()
        .is_some_and(|s| !s.relative_azimuth_deg.is_empty());
    let mut t = vec![
        &mut a.level_transmission,
        &mut a.level_path_radiance_w_m2_sr_per_unit,
    ];
    if let Some(c) = &mut a.transmission_correction {
        t.push(&mut c.transmission);
    }
    t.push(&mut a.sky_radiance_w_m2_sr_per_unit);
    if let Some(h) = &mut a.sky_hemispheric_w_m2_sr_per_unit {
        t.push(h);
    }
    if let Some(s) = &mut a.slant {
        t.extend([
            &mut s.transmission,
            &mut s.path_radiance_w_m2_sr_per_unit,
            &mut s.sky_radiance_w_m2_sr_per_unit,
        ]);
    }
    if let Some(s) = &mut a.solar {
        let scattered = !s.relative_azimuth_deg.is_empty();
        t.extend([&mut s.extraterrestrial_w_m2_per_unit, &mut s.transmission]);
        if scattered {
            t.extend([
                &mut s.path_scattered_w_m2_sr_per_unit,
                &mut s.sky_scattered_w_m2_sr_per_unit,
            ]);
        }
        for b in &mut s.further_suns {
            t.push(&mut b.transmission);
            if scattered {
                t.extend([
                    &mut b.path_scattered_w_m2_sr_per_unit,
                    &mut b.sky_scattered_w_m2_sr_per_unit,
                ]);
            }
        }
        if let Some(p) = &mut s.phase {
            t.push(&mut p.scattered_w_m2_sr_per_unit_per_m);
        }
    }
    for table in a
        .slabs
        .iter_mut()
        .flat_map(|s| [&mut s.down, &mut s.up])
        .flatten()
    {
        t.extend([
            &mut table.transmission,
            &mut table.path_radiance_w_m2_sr_per_unit,
        ]);
        if lit {
            t.push(&mut table.scattered_w_m2_sr_per_unit);
        }
    }
    t
}

/// How many spectra each table holds, from the header's dimensions alone, in the order of
/// [`tables_mut`], with the table's path: what every count in the file must be, checked
/// before a table is read or inflated. `Err` holds the header path of a dimension that
/// cannot be had (scattered sunlight without slant tables) and why.
fn expected_spectra(a: &SpectralAtmosphere) -> Result<Vec<(String, usize)>, (String, String)> {
    let mut t = vec![
        ("level_transmission".to_owned(), a.levels.len()),
        (
            "level_path_radiance_w_m2_sr_per_unit".to_owned(),
            a.levels.len(),
        ),
    ];
    if let Some(c) = &a.transmission_correction {
        t.push((
            "transmission_correction.transmission".to_owned(),
            c.nadir_deg.len(),
        ));
    }
    t.push((
        "sky_radiance_w_m2_sr_per_unit".to_owned(),
        a.sky_zenith_deg.len(),
    ));
    if a.sky_hemispheric_w_m2_sr_per_unit.is_some() {
        t.push(("sky_hemispheric_w_m2_sr_per_unit".to_owned(), 1));
    }
    let product = |x: usize, y: usize| x.saturating_mul(y);
    if let Some(s) = &a.slant {
        let paths = product(s.altitude_m.len(), s.nadir_deg.len());
        t.extend([
            ("slant.transmission".to_owned(), paths),
            ("slant.path_radiance_w_m2_sr_per_unit".to_owned(), paths),
            (
                "slant.sky_radiance_w_m2_sr_per_unit".to_owned(),
                product(s.sky_altitude_m.len(), s.sky_zenith_deg.len()),
            ),
        ]);
    }
    let azimuths = a.solar.as_ref().map_or(0, |s| s.relative_azimuth_deg.len());
    if let Some(s) = &a.solar {
        t.extend([
            ("solar.extraterrestrial_w_m2_per_unit".to_owned(), 1),
            ("solar.transmission".to_owned(), s.altitude_m.len()),
        ]);
        if azimuths > 0 {
            let Some(sl) = &a.slant else {
                return Err((
                    "solar.relative_azimuth_deg".to_owned(),
                    "scattered-sunlight tables lie on the slant tables' nodes: expected a \
                     `slant` table"
                        .to_owned(),
                ));
            };
            t.extend([
                (
                    "solar.path_scattered_w_m2_sr_per_unit".to_owned(),
                    product(product(sl.altitude_m.len(), sl.nadir_deg.len()), azimuths),
                ),
                (
                    "solar.sky_scattered_w_m2_sr_per_unit".to_owned(),
                    product(
                        product(s.altitude_m.len(), sl.sky_zenith_deg.len()),
                        azimuths,
                    ),
                ),
            ]);
        }
        for i in 0..s.further_suns.len() {
            t.push((
                format!("solar.further_suns[{i}].transmission"),
                s.altitude_m.len(),
            ));
            if let (true, Some(sl)) = (azimuths > 0, &a.slant) {
                t.extend([
                    (
                        format!("solar.further_suns[{i}].path_scattered_w_m2_sr_per_unit"),
                        product(product(sl.altitude_m.len(), sl.nadir_deg.len()), azimuths),
                    ),
                    (
                        format!("solar.further_suns[{i}].sky_scattered_w_m2_sr_per_unit"),
                        product(
                            product(s.altitude_m.len(), sl.sky_zenith_deg.len()),
                            azimuths,
                        ),
                    ),
                ]);
            }
        }
        if let Some(p) = &s.phase {
            t.push((
                "solar.phase.scattered_w_m2_sr_per_unit_per_m".to_owned(),
                product(s.altitude_m.len(), p.scattering_deg.len()),
            ));
        }
    }
    for (i, slab) in a.slabs.iter().enumerate() {
        for (dir, table) in [("down", &slab.down), ("up", &slab.up)] {
            let Some(table) = table else { continue };
            let count = product(table.target_m.len(), table.angle_deg.len());
            let path = |f: &str| format!("slabs[{i}].{dir}.{f}");
            t.push((path("transmission"), count));
            t.push((path("path_radiance_w_m2_sr_per_unit"), count));
            if azimuths > 0 {
                t.push((path("scattered_w_m2_sr_per_unit"), product(count, azimuths)));
            }
        }
    }
    Ok(t)
}

/// Encodes a spectral atmosphere.
///
/// # Errors
/// A table longer than `u32::MAX` values, or a header serde cannot write (never for a
/// validated atmosphere).
pub fn encode(atmosphere: &SpectralAtmosphere) -> Result<Vec<u8>, std::io::Error> {
    let total: usize = tables(atmosphere).iter().map(|t| 4 + 4 * t.len()).sum();
    let mut out = start(atmosphere, VERSION, total)?;
    for t in tables(atmosphere) {
        out.extend_from_slice(&u32::try_from(t.len()).map_err(|_| too_big())?.to_le_bytes());
        for v in t {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    Ok(out)
}

/// The file's start for `version`: the magic, the version, and the atmosphere without its
/// tables as RON with its byte length; room for `tables` bytes more.
fn start(
    atmosphere: &SpectralAtmosphere,
    version: u32,
    tables: usize,
) -> Result<Vec<u8>, std::io::Error> {
    let mut bare = atmosphere.clone();
    for t in tables_mut(&mut bare) {
        t.clear();
    }
    let ron = ron::ser::to_string(&bare).map_err(std::io::Error::other)?;
    let mut out = Vec::with_capacity(16 + ron.len() + tables);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(
        &u32::try_from(ron.len())
            .map_err(|_| too_big())?
            .to_le_bytes(),
    );
    out.extend_from_slice(ron.as_bytes());
    Ok(out)
}

fn too_big() -> std::io::Error {
    std::io::Error::other("a table of spectra holds more than 2^32 values")
}

/// Encodes a spectral atmosphere in version 2 (`formats/canonical/spectral-atmosphere.md`):
/// each spectrum's values as 16-bit fractions `q` of its largest value `s`, `v = q·s/65535`
/// (rounded to nearest: at most `s/131070` off), each table's `q` the difference from the
/// previous spectrum's (mod 2¹⁶), low bytes then high bytes, deflated with its scales. What
/// the built-ins over 3–5 µm are embedded as: a quarter of the `f32` form's bytes, within
/// 0.001 K of it (docs/accuracy.md).
///
/// # Errors
/// As [`encode`]; a table whose length is not a whole number of spectra.
pub fn encode_quantised(atmosphere: &SpectralAtmosphere) -> Result<Vec<u8>, std::io::Error> {
    let n = atmosphere.grid.points.len().max(1);
    let mut out = start(atmosphere, VERSION_QUANTISED, 0)?;
    for t in tables(atmosphere) {
        if t.len() % n != 0 {
            return Err(std::io::Error::other(format!(
                "a table of {} values is not a whole number of spectra of {n} points",
                t.len()
            )));
        }
        let spectra = t.len() / n;
        let mut raw = Vec::with_capacity(4 * spectra + 2 * t.len());
        let mut low = Vec::with_capacity(t.len());
        let mut high = Vec::with_capacity(t.len());
        let mut previous = vec![0_u16; n];
        for spectrum in t.chunks_exact(n) {
            let scale = spectrum.iter().copied().fold(0.0_f32, f32::max);
            raw.extend_from_slice(&scale.to_le_bytes());
            for (v, p) in spectrum.iter().zip(&mut previous) {
                let q = if scale > 0.0 {
                    // In 0..=65535: 0 <= v <= scale.
                    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                    let q = (f64::from(*v) / f64::from(scale) * 65535.0)
                        .round()
                        .clamp(0.0, 65535.0) as u16;
                    q
                } else {
                    0
                };
                let [l, h] = q.wrapping_sub(*p).to_le_bytes();
                low.push(l);
                high.push(h);
                *p = q;
            }
        }
        raw.extend_from_slice(&low);
        raw.extend_from_slice(&high);
        let z = miniz_oxide::deflate::compress_to_vec_zlib(&raw, 9);
        out.extend_from_slice(&u32::try_from(t.len()).map_err(|_| too_big())?.to_le_bytes());
        out.extend_from_slice(&u32::try_from(z.len()).map_err(|_| too_big())?.to_le_bytes());
        out.extend_from_slice(&z);
    }
    Ok(out)
}

/// The values of one version 2 table of `count` values (spectra of `n` points) from its
/// zlib stream `z`, which starts at byte `at` of the file.
fn dequantise(
    file: &str,
    z: &[u8],
    at: usize,
    count: usize,
    n: usize,
) -> Result<Vec<f32>, ParseError> {
    if n == 0 || count % n != 0 {
        return Err(ParseError::in_binary(
            file,
            at,
            format!(
                "expected a whole number of spectra of {n} points, found a table of {count} values"
            ),
        ));
    }
    let spectra = count / n;
    // Within the budget: `count` is the header's, checked by the caller.
    let want = 2 * count + 4 * spectra;
    let raw =
        crate::inflate::zlib_exact(file, z, at + 4, want, &format!("a table of {count} values"))?;
    let (scales, q) = raw.split_at(4 * spectra);
    let (low, high) = q.split_at(count);
    let mut values = crate::inflate::reserve(file, at, count, "a table of spectra")?;
    let mut previous = vec![0_u16; n];
    for (k, scale) in scales.chunks_exact(4).enumerate() {
        let scale = f64::from(f32::from_le_bytes([scale[0], scale[1], scale[2], scale[3]]));
        for (i, p) in previous.iter_mut().enumerate() {
            let j = k * n + i;
            *p = p.wrapping_add(u16::from_le_bytes([low[j], high[j]]));
            #[allow(clippy::cast_possible_truncation)]
            values.push((f64::from(*p) * scale / 65535.0) as f32);
        }
    }
    Ok(values)
}

/// The header's RON text and its byte offset in the file, if `bytes` hold a well-formed
/// header (what [`decode`] reads first).
#[must_use]
pub fn header(bytes: &[u8]) -> Option<(usize, &str)> {
    if !is_binary(bytes) {
        return None;
    }
    let h = u32::from_le_bytes(bytes.get(12..16)?.try_into().ok()?) as usize;
    let text = std::str::from_utf8(bytes.get(16..16usize.checked_add(h)?)?).ok()?;
    Some((16, text))
}

fn u32_at(file: &str, bytes: &[u8], at: usize, what: &str) -> Result<u32, ParseError> {
    bytes
        .get(at..at + 4)
        .and_then(|b| b.try_into().ok())
        .map(u32::from_le_bytes)
        .ok_or_else(|| {
            ParseError::in_binary(
                file,
                at,
                format!("expected {what} (4 bytes), found the end of the file: it is truncated"),
            )
        })
}

/// Reads the tables that follow the header from `at` into `atm`, each count held to the
/// header's dimensions and all of them to the memory budget before a value is read or a
/// byte inflated; returns where the last table ends.
fn read_tables(
    file: &str,
    bytes: &[u8],
    text: &str,
    atm: &mut SpectralAtmosphere,
    version: u32,
    mut at: usize,
) -> Result<usize, ParseError> {
    let points = atm.grid.points.len();
    let shapes = expected_spectra(atm).map_err(|(path, why)| {
        let (start, _) = crate::ron_tree::locate(text, &path);
        ParseError::in_binary(file, 16 + start, why)
    })?;
    let values = shapes.iter().try_fold(0_u64, |sum, (_, spectra)| {
        sum.checked_add((*spectra as u64).checked_mul(points as u64)?)
    });
    crate::inflate::check_budget(
        file,
        16,
        values.and_then(|v| v.checked_mul(4)),
        "the tables the header describes",
    )?;
    for (t, (path, spectra)) in tables_mut(atm).into_iter().zip(&shapes) {
        let n = u32_at(file, bytes, at, "the count of a table of spectra")? as usize;
        // Within the budget just checked, so no product overflows.
        let want = spectra * points;
        if n != want {
            return Err(ParseError::in_binary(
                file,
                at,
                format!(
                    "expected `{path}` to hold {want} values ({spectra} spectra of {points} \
                     points, as the header gives them), found a count of {n}"
                ),
            ));
        }
        if version == VERSION_QUANTISED {
            let z = u32_at(file, bytes, at + 4, "the byte length of a compressed table")? as usize;
            let stream = bytes
                .get(at + 8..(at + 8).saturating_add(z))
                .ok_or_else(|| {
                    ParseError::in_binary(
                        file,
                        at + 4,
                        format!(
                            "a compressed table of {z} bytes, but only {} are left: the file is \
                         truncated",
                            bytes.len().saturating_sub(at + 8)
                        ),
                    )
                })?;
            *t = dequantise(file, stream, at, n, points)?;
            at += 8 + z;
            continue;
        }
        let len = n.checked_mul(4).filter(|&l| l <= bytes.len() - at - 4).ok_or_else(|| {
            ParseError::in_binary(
                file,
                at,
                format!(
                    "a table of {n} values needs {} bytes, but only {} are left: the file is truncated",
                    n.saturating_mul(4),
                    bytes.len() - at - 4
                ),
            )
        })?;
        at += 4;
        *t = bytes[at..at + len]
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        at += len;
    }
    Ok(at)
}

/// Decodes and validates a binary spectral atmosphere.
///
/// # Errors
/// A [`ParseError`] at the byte offset: a wrong magic or version, a header that is not
/// UTF-8 RON of a spectral atmosphere, a count larger than the bytes left, bytes after the
/// last table, or a broken model rule.
pub fn decode(file: &str, bytes: &[u8]) -> Result<SpectralAtmosphere, ParseError> {
    if !is_binary(bytes) {
        return Err(ParseError::in_binary(
            file,
            0,
            "expected the magic `IRSIGSPA` of a binary spectral atmosphere",
        ));
    }
    let version = u32_at(file, bytes, 8, "the version")?;
    if version != VERSION && version != VERSION_QUANTISED {
        return Err(ParseError::in_binary(
            file,
            8,
            format!("expected version {VERSION} or {VERSION_QUANTISED}, found {version}"),
        ));
    }
    let h = u32_at(file, bytes, 12, "the header length")? as usize;
    let header = bytes.get(16..16usize.saturating_add(h)).ok_or_else(|| {
        ParseError::in_binary(
            file,
            12,
            format!(
                "the header length {h} runs past the end of the file ({} bytes)",
                bytes.len()
            ),
        )
    })?;
    let text = std::str::from_utf8(header).map_err(|e| {
        ParseError::in_binary(file, 16 + e.valid_up_to(), "expected a UTF-8 RON header")
    })?;
    let mut atm: SpectralAtmosphere = ron::from_str(text).map_err(|e| {
        let offset = crate::offset_of(text, e.span.start.line, e.span.start.col);
        ParseError::in_binary(
            file,
            16 + offset,
            format!(
                "malformed header (RON): {}",
                crate::canonical::ron_message(&e.code)
            ),
        )
    })?;
    // The header's tables are empty: their values follow it. Values in both places would
    // be silently replaced.
    let c = atm.transmission_correction.as_ref();
    let sl = atm.slant.as_ref();
    let so = atm.solar.as_ref();
    let in_header = [
        ("level_transmission", atm.level_transmission.len()),
        (
            "level_path_radiance_w_m2_sr_per_unit",
            atm.level_path_radiance_w_m2_sr_per_unit.len(),
        ),
        (
            "transmission_correction.transmission",
            c.map_or(0, |c| c.transmission.len()),
        ),
        (
            "sky_radiance_w_m2_sr_per_unit",
            atm.sky_radiance_w_m2_sr_per_unit.len(),
        ),
        (
            "sky_hemispheric_w_m2_sr_per_unit",
            atm.sky_hemispheric_w_m2_sr_per_unit
                .as_ref()
                .map_or(0, Vec::len),
        ),
        ("slant.transmission", sl.map_or(0, |s| s.transmission.len())),
        (
            "slant.path_radiance_w_m2_sr_per_unit",
            sl.map_or(0, |s| s.path_radiance_w_m2_sr_per_unit.len()),
        ),
        (
            "slant.sky_radiance_w_m2_sr_per_unit",
            sl.map_or(0, |s| s.sky_radiance_w_m2_sr_per_unit.len()),
        ),
        (
            "solar.extraterrestrial_w_m2_per_unit",
            so.map_or(0, |s| s.extraterrestrial_w_m2_per_unit.len()),
        ),
        ("solar.transmission", so.map_or(0, |s| s.transmission.len())),
        (
            "solar.path_scattered_w_m2_sr_per_unit",
            so.map_or(0, |s| s.path_scattered_w_m2_sr_per_unit.len()),
        ),
        (
            "solar.sky_scattered_w_m2_sr_per_unit",
            so.map_or(0, |s| s.sky_scattered_w_m2_sr_per_unit.len()),
        ),
        (
            "solar.phase.scattered_w_m2_sr_per_unit_per_m",
            so.and_then(|s| s.phase.as_ref())
                .map_or(0, |p| p.scattered_w_m2_sr_per_unit_per_m.len()),
        ),
    ];
    let slab_values = atm.slabs.iter().enumerate().flat_map(|(i, s)| {
        [("down", &s.down), ("up", &s.up)]
            .into_iter()
            .filter_map(move |(dir, t)| t.as_ref().map(|t| (i, dir, t)))
            .flat_map(|(i, dir, t)| {
                [
                    ("transmission", t.transmission.len()),
                    (
                        "path_radiance_w_m2_sr_per_unit",
                        t.path_radiance_w_m2_sr_per_unit.len(),
                    ),
                    (
                        "scattered_w_m2_sr_per_unit",
                        t.scattered_w_m2_sr_per_unit.len(),
                    ),
                ]
                .map(|(f, n)| (format!("slabs[{i}].{dir}.{f}"), n))
            })
    });
    let in_header: Vec<(String, usize)> = in_header
        .into_iter()
        .map(|(p, n)| (p.to_owned(), n))
        .chain(slab_values)
        .collect();
    if let Some((path, n)) = in_header.into_iter().find(|(_, n)| *n > 0) {
        let path = path.as_str();
        let (start, _) = crate::ron_tree::locate(text, path);
        return Err(ParseError::in_binary(
            file,
            16 + start,
            format!(
                "expected `{path}` empty in the header (the values follow the header), found \
                 {n} values"
            ),
        ));
    }
    let at = read_tables(file, bytes, text, &mut atm, version, 16 + h)?;
    if at != bytes.len() {
        return Err(ParseError::in_binary(
            file,
            at,
            format!(
                "expected the end of the file after the last table, found {} more bytes",
                bytes.len() - at
            ),
        ));
    }
    atm.validate().map_err(|e| {
        ParseError::in_binary(
            file,
            16,
            format!("invalid spectral atmosphere: `{}`: {}", e.path, e.kind),
        )
    })?;
    Ok(atm)
}

#[cfg(test)]
mod tests;
