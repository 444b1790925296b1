//! The per-facet temperature history `irsig-therm` writes: times × facets of `f32`
//! kelvins, after a RON header with the times and what made them. A day at 5-minute steps
//! of a million facets is 288 M values (1.1 GB), far too many for RON. Spec page:
//! `formats/canonical/temperature-history.md`.
//!
//! Layout (little-endian, no padding):
//!
//! | offset | size | field |
//! | --- | --- | --- |
//! | 0 | 8 | magic `IRSIGTHM` |
//! | 8 | 4 | `u32` version, 1 |
//! | 12 | 4 | `u32` byte length `H` of the header |
//! | 16 | `H` | header: the history as canonical RON (UTF-8) with `temperature_k` empty |
//! | 16 + `H` | 4 · times · facets | the temperatures, `f32` K, time after time, each time's facets in the raw scene's order |
//!
//! The table's length follows from the header's times and facets; it is checked against
//! the bytes left (exactly) before anything is allocated, and the result is validated.

use irsig_model::history::TemperatureHistory;

use crate::ParseError;

/// The first eight bytes of a temperature history.
pub const MAGIC: &[u8; 8] = b"IRSIGTHM";
/// The layout version this code reads and writes.
pub const VERSION: u32 = 1;

/// True when `bytes` start with [`MAGIC`].
#[must_use]
pub fn is_binary(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// Encodes a history (validated by the caller).
///
/// # Errors
/// A header longer than 4 GiB, or one serde cannot write (never for a validated history).
pub fn encode(history: &TemperatureHistory) -> Result<Vec<u8>, std::io::Error> {
    let mut bare = history.clone();
    bare.temperature_k = Vec::new();
    let ron = ron::ser::to_string(&bare).map_err(std::io::Error::other)?;
    let mut out = Vec::with_capacity(16 + ron.len() + 4 * history.temperature_k.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    let h = u32::try_from(ron.len())
        .map_err(|_| std::io::Error::other("a history header of more than 4 GiB"))?;
    out.extend_from_slice(&h.to_le_bytes());
    out.extend_from_slice(ron.as_bytes());
    for t in &history.temperature_k {
        out.extend_from_slice(&t.to_le_bytes());
    }
    Ok(out)
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

/// Decodes and validates a temperature history.
///
/// # Errors
/// A [`ParseError`] at the byte offset: a wrong magic or version, a header that is not
/// UTF-8 RON of a history or holds temperatures, a table whose length is not the header's
/// times × facets, or a broken model rule (a NaN temperature, times that do not increase).
pub fn decode(file: &str, bytes: &[u8]) -> Result<TemperatureHistory, ParseError> {
    if !is_binary(bytes) {
        return Err(ParseError::in_binary(
            file,
            0,
            "expected the magic `IRSIGTHM` of a temperature history",
        ));
    }
    let version = u32_at(file, bytes, 8, "the version")?;
    if version != VERSION {
        return Err(ParseError::in_binary(
            file,
            8,
            format!("expected version {VERSION}, found {version}"),
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
    let mut history: TemperatureHistory = ron::from_str(text).map_err(|e| {
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
    if !history.temperature_k.is_empty() {
        return Err(ParseError::in_binary(
            file,
            16,
            "the header holds temperatures: they follow it in binary, never in it",
        ));
    }
    let at = 16 + h;
    let left = (bytes.len() - at) as u64;
    let values = history.values();
    if values.checked_mul(4) != Some(left) {
        return Err(ParseError::in_binary(
            file,
            at,
            format!(
                "expected {} times × {} facets = {values} temperatures ({} bytes), found \
                 {left} bytes",
                history.time_s.len(),
                history.facets,
                values.saturating_mul(4)
            ),
        ));
    }
    history.temperature_k = bytes[at..]
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    history.validate().map_err(|e| {
        let offset = e
            .path
            .strip_prefix("temperature_k[")
            .and_then(|r| r.strip_suffix(']'))
            .and_then(|i| i.parse::<usize>().ok())
            .map_or(16, |i| at + 4 * i);
        ParseError::in_binary(file, offset, format!("temperature history: {e}"))
    })?;
    Ok(history)
}

#[cfg(test)]
mod tests {
    use irsig_model::history::ThermalProvenance;

    use super::*;

    fn sample() -> TemperatureHistory {
        TemperatureHistory {
            time_s: vec![1.7e9, 1.7e9 + 300.0],
            facets: 3,
            temperature_k: vec![290.0, 291.5, 300.25, 289.0, 292.0, 301.0],
            provenance: ThermalProvenance {
                irsig_version: "0.1.0".into(),
                inputs: vec![],
                site: (43.08, -77.67, 170.0),
                start_s: 1.7e9 - 86_400.0,
                step_s: 300.0,
                radiation: "weather".into(),
                models: vec![("time step".into(), "300 s".into())],
            },
        }
    }

    #[test]
    fn a_history_reads_back_bit_for_bit() {
        let h = sample();
        let bytes = encode(&h).unwrap();
        // The table is the last 24 bytes, f32 little-endian: 290.0 is 0x43910000.
        assert_eq!(
            &bytes[bytes.len() - 24..bytes.len() - 20],
            &[0, 0, 0x91, 0x43]
        );
        assert_eq!(decode("h", &bytes).unwrap(), h);
    }

    #[test]
    fn a_table_of_the_wrong_size_is_refused_before_anything_is_allocated() {
        let bytes = encode(&sample()).unwrap();
        let e = decode("h", &bytes[..bytes.len() - 4]).unwrap_err();
        assert!(e.to_string().contains("2 times × 3 facets"), "{e}");
        // A header that claims four billion facets over a file of a few hundred bytes.
        let text = String::from_utf8_lossy(&bytes[16..bytes.len() - 24])
            .replace("facets:3", "facets:4000000000");
        let mut forged = Vec::new();
        forged.extend_from_slice(MAGIC);
        forged.extend_from_slice(&VERSION.to_le_bytes());
        forged.extend_from_slice(&(text.len() as u32).to_le_bytes());
        forged.extend_from_slice(text.as_bytes());
        forged.extend_from_slice(&bytes[bytes.len() - 24..]);
        let e = decode("h", &forged).unwrap_err();
        assert!(e.to_string().contains("4000000000 facets"), "{e}");
    }

    #[test]
    fn a_nan_temperature_is_refused_at_its_byte() {
        let mut bytes = encode(&sample()).unwrap();
        let n = bytes.len();
        bytes[n - 8..n - 4].copy_from_slice(&f32::NAN.to_le_bytes());
        let e = decode("h", &bytes).unwrap_err();
        let text = e.to_string();
        assert!(text.contains("temperature_k[4]"), "{text}");
    }
}
