//! The compact binary object: what `irsig-import` writes into a pipe (or to a `.bin` file)
//! and what every object reader accepts beside RON, because the RON object of a million
//! triangles is 73 MB and takes seconds to write and read (see `BENCHMARKS.md`, section
//! "import and flatten"); this form is 36 MB and takes tens of milliseconds. [`write`]
//! streams it in chunks, so it is never held encoded in memory whole.
//!
//! Layout (all little-endian, no padding, documented in `formats/canonical/object.md`):
//!
//! | offset | size | field |
//! | --- | --- | --- |
//! | 0 | 8 | magic `IRSIGOBJ` |
//! | 8 | 4 | `u32` version, 1 |
//! | 12 | 4 | `u32` flags: bit 0 a texture-coordinate section, bits 1–31 reserved 0 |
//! | 16 | 4 | `u32` byte length `N` of the name |
//! | 20 | 4 | `u32` byte length `S` of the source |
//! | 24 | 4 | `u32` position count `P` |
//! | 28 | 4 | `u32` facet count `F` |
//! | 32 | `N` | name, UTF-8 |
//! | 32 + `N` | `S` | source, UTF-8 |
//! | … | 24 `P` | positions, `f64` x y z in metres |
//! | … | 24 `F` | facets: `u32` v0 v1 v2, `u16` material, `u16` facet flags, `f64` temperature K |
//! | … | 48 `F` | only when flag bit 0 is set: per facet `f64` u v at each corner (zeros for a facet without) |
//!
//! Facet flags: bit 0 set means the facet has a temperature of its own (`Some(T)`); clear
//! means it has none, and the temperature field is written as 0 and ignored. Bit 1 set
//! means the facet has texture coordinates in the section after the facets; clear means
//! its record there is zeros. The other bits are reserved and must be 0. Header flag bit 0
//! is set only when some facet has coordinates, so an object without them keeps the bytes
//! it had before the section existed.
//!
//! The reader checks that the file length equals what the header's counts imply before it
//! allocates anything, so a corrupt count cannot make it allocate more than the file holds.
//!
//! ```
//! use irsig_formats::canonical::binary_object;
//! use irsig_model::{Facet, MaterialId, Object};
//!
//! let object = Object {
//!     name: "tri".into(),
//!     source: String::new(),
//!     positions_m: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
//!     facets: vec![Facet { vertices: [0, 1, 2], material: MaterialId(1), temperature_k: None, uv: None }],
//! };
//! let bytes = binary_object::encode(&object).unwrap();
//! assert_eq!(bytes.len(), 32 + 3 + 3 * 24 + 24);
//! assert_eq!(binary_object::decode("tri.bin", &bytes).unwrap(), object);
//! ```

use irsig_model::{Facet, MaterialId, Object};

use super::layout::{self, Form, UV_LEN, f64_at, u32_at};
use crate::ParseError;

/// The first eight bytes of a binary object.
pub const MAGIC: &[u8; 8] = b"IRSIGOBJ";
/// The layout version this code reads and writes.
pub const VERSION: u32 = 1;
/// Header size in bytes.
pub const HEADER_LEN: usize = 32;
/// Bytes per position.
pub const POSITION_LEN: usize = layout::POSITION_LEN;
/// Bytes per facet.
pub const FACET_LEN: usize = 24;
/// Facet flag: the facet carries its own temperature.
pub const HAS_TEMPERATURE: u16 = 1;
/// Facet flag: the facet has texture coordinates in the section after the facets.
pub const HAS_UV: u16 = 2;

const FORM: Form = Form {
    magic: MAGIC,
    version: VERSION,
    header_len: HEADER_LEN,
    noun: "object",
    flag_bits: layout::HAS_UV_SECTION,
};

/// True when `bytes` start with [`MAGIC`].
#[must_use]
pub fn is_binary(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// Encodes an object into one buffer; [`write`] streams the same bytes instead.
///
/// # Errors
/// As [`write`], less the I/O errors.
pub fn encode(object: &Object) -> Result<Vec<u8>, std::io::Error> {
    let uv_len = if object.facets.iter().any(|f| f.uv.is_some()) {
        UV_LEN
    } else {
        0
    };
    let mut out = Vec::with_capacity(
        HEADER_LEN
            + object.name.len()
            + object.source.len()
            + POSITION_LEN * object.positions_m.len()
            + (FACET_LEN + uv_len) * object.facets.len(),
    );
    write(object, &mut out)?;
    Ok(out)
}

/// Writes an object in the binary form, a few hundred kilobytes at a time, so that a
/// million-triangle object is never held encoded in memory whole (36 MB) and a reader at
/// the other end of a pipe starts at once.
///
/// # Errors
/// An object with more than `u32::MAX` positions or facets, or a name or source over
/// 4 GiB, which this layout cannot hold (found before anything is written), or an I/O
/// error from `w`.
pub fn write(object: &Object, w: &mut dyn std::io::Write) -> std::io::Result<()> {
    let count = |n: usize, what: &str| FORM.count(n, what);
    let uv_flags = layout::uv_flags(object.facets.iter().map(|f| f.uv.as_ref()));
    let mut header = FORM.start_header(
        HEADER_LEN + object.name.len() + object.source.len(),
        uv_flags,
    );
    header.extend_from_slice(&count(object.name.len(), "name bytes")?.to_le_bytes());
    header.extend_from_slice(&count(object.source.len(), "source bytes")?.to_le_bytes());
    header.extend_from_slice(&count(object.positions_m.len(), "positions")?.to_le_bytes());
    header.extend_from_slice(&count(object.facets.len(), "facets")?.to_le_bytes());
    header.extend_from_slice(object.name.as_bytes());
    header.extend_from_slice(object.source.as_bytes());
    w.write_all(&header)?;
    layout::write_positions(w, &object.positions_m)?;
    layout::write_records(w, &object.facets, FACET_LEN, |f, out| {
        for v in f.vertices {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&f.material.0.to_le_bytes());
        let (mut flags, t) = match f.temperature_k {
            Some(t) => (HAS_TEMPERATURE, t),
            None => (0, 0.0),
        };
        if f.uv.is_some() {
            flags |= HAS_UV;
        }
        out.extend_from_slice(&flags.to_le_bytes());
        out.extend_from_slice(&t.to_le_bytes());
    })?;
    layout::write_uvs(w, uv_flags, &object.facets, |f| f.uv.as_ref())
}

/// Where the record a validation path names (`positions_m[i]…`, `facets[i]…`) starts in
/// the encoding of `object`, so that an error can give its byte offset.
#[must_use]
pub fn offset_of_path(object: &Object, path: &str) -> usize {
    let positions_at = HEADER_LEN + object.name.len() + object.source.len();
    let facets_at = positions_at + POSITION_LEN * object.positions_m.len();
    layout::record_offset(path, positions_at, facets_at, FACET_LEN).unwrap_or(0)
}

/// Decodes a binary object. Does not validate the model rules (see
/// [`super::read_object`], which does).
///
/// # Errors
/// A wrong magic or version, a length that disagrees with the header's counts, a name or
/// source that is not UTF-8, reserved flags that are set; at the byte offset of the
/// problem.
pub fn decode(file: &str, bytes: &[u8]) -> Result<Object, ParseError> {
    let err = |offset: usize, msg: String| ParseError::in_binary(file, offset, msg);
    FORM.check_header(file, bytes)?;
    let name_len = u32_at(bytes, 16) as usize;
    let source_len = u32_at(bytes, 20) as usize;
    let positions = u32_at(bytes, 24) as usize;
    let facets = u32_at(bytes, 28) as usize;
    let has_uv_section = u32_at(bytes, 12) & layout::HAS_UV_SECTION != 0;
    let uv_len = if has_uv_section { UV_LEN } else { 0 };
    // u64 arithmetic: u32 counts times record sizes cannot overflow it.
    let expected = HEADER_LEN as u64
        + name_len as u64
        + source_len as u64
        + POSITION_LEN as u64 * positions as u64
        + (FACET_LEN + uv_len) as u64 * facets as u64;
    FORM.check_length(file, bytes, expected, || {
        let uvs = if has_uv_section {
            " with texture coordinates"
        } else {
            ""
        };
        format!(
            "a {name_len}-byte name, a {source_len}-byte source, {positions} positions and \
             {facets} facets{uvs}"
        )
    })?;
    // From here every count is bounded by the file length.
    let text = |at: usize, len: usize, what: &str| {
        std::str::from_utf8(&bytes[at..at + len])
            .map(str::to_owned)
            .map_err(|e| {
                err(
                    at + e.valid_up_to(),
                    format!("the object's {what} is not UTF-8"),
                )
            })
    };
    let name = text(HEADER_LEN, name_len, "name")?;
    let source = text(HEADER_LEN + name_len, source_len, "source")?;
    let positions_at = HEADER_LEN + name_len + source_len;
    let facets_at = positions_at + POSITION_LEN * positions;
    let positions_m = layout::read_positions(&bytes[positions_at..facets_at]);
    let uvs_at = facets_at + FACET_LEN * facets;
    let allowed = if has_uv_section {
        HAS_TEMPERATURE | HAS_UV
    } else {
        HAS_TEMPERATURE
    };
    let mut out = Vec::with_capacity(facets);
    for (i, c) in bytes[facets_at..uvs_at].chunks_exact(FACET_LEN).enumerate() {
        let flags = u16::from_le_bytes([c[14], c[15]]);
        if flags & !allowed != 0 {
            return Err(err(
                facets_at + FACET_LEN * i + 14,
                format!("facet {i}: expected facet flags within {allowed:#x}, found {flags:#x}"),
            ));
        }
        let uv = layout::read_uv(
            file,
            bytes,
            has_uv_section.then_some(uvs_at),
            flags & HAS_UV != 0,
            i,
        )?;
        out.push(Facet {
            vertices: [u32_at(c, 0), u32_at(c, 4), u32_at(c, 8)],
            material: MaterialId(u16::from_le_bytes([c[12], c[13]])),
            temperature_k: (flags & HAS_TEMPERATURE != 0).then(|| f64_at(c, 16)),
            uv,
        });
    }
    Ok(Object {
        name,
        source,
        positions_m,
        facets: out,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn object() -> Object {
        Object {
            name: "ström".into(),
            source: "test".into(),
            positions_m: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 1e-9]],
            facets: vec![
                Facet {
                    vertices: [0, 1, 2],
                    material: MaterialId(7),
                    temperature_k: Some(300.25),
                    uv: None,
                },
                Facet {
                    vertices: [2, 1, 0],
                    material: MaterialId(65535),
                    temperature_k: None,
                    uv: None,
                },
            ],
        }
    }

    // "ström" is 6 bytes, "test" 4.
    const FACETS_AT: usize = 32 + 6 + 4 + 3 * 24;

    #[test]
    fn round_trips_bit_exactly() {
        let o = object();
        let bytes = encode(&o).unwrap();
        assert_eq!(bytes.len(), FACETS_AT + 2 * 24);
        assert_eq!(decode("o.bin", &bytes).unwrap(), o);
    }

    #[test]
    fn the_layout_is_the_documented_one() {
        let bytes = encode(&object()).unwrap();
        assert_eq!(&bytes[..8], b"IRSIGOBJ");
        assert_eq!(bytes[8..12], 1u32.to_le_bytes());
        assert_eq!(bytes[16..20], 6u32.to_le_bytes());
        assert_eq!(bytes[20..24], 4u32.to_le_bytes());
        assert_eq!(bytes[24..28], 3u32.to_le_bytes());
        assert_eq!(bytes[28..32], 2u32.to_le_bytes());
        assert_eq!(&bytes[32..38], "ström".as_bytes());
        assert_eq!(&bytes[38..42], b"test");
        assert_eq!(bytes[42 + 24..42 + 32], 1.0f64.to_le_bytes());
        let f0 = FACETS_AT;
        assert_eq!(bytes[f0 + 8..f0 + 12], 2u32.to_le_bytes());
        assert_eq!(bytes[f0 + 12..f0 + 14], 7u16.to_le_bytes());
        assert_eq!(bytes[f0 + 14..f0 + 16], 1u16.to_le_bytes());
        assert_eq!(bytes[f0 + 16..f0 + 24], 300.25f64.to_le_bytes());
        let f1 = FACETS_AT + 24;
        assert_eq!(bytes[f1 + 14..f1 + 16], 0u16.to_le_bytes());
        assert_eq!(bytes[f1 + 16..f1 + 24], 0.0f64.to_le_bytes());
    }

    /// Takes at most 7 bytes per call, and fails once `limit` bytes have been taken.
    struct Trickle {
        bytes: Vec<u8>,
        limit: usize,
    }

    impl std::io::Write for Trickle {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            if self.bytes.len() >= self.limit {
                return Err(std::io::Error::other("disk full"));
            }
            let n = buf.len().min(7);
            self.bytes.extend_from_slice(&buf[..n]);
            Ok(n)
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn an_object_of_many_chunks_streams_and_reads_back() {
        // 30,000 facets are 720,000 bytes: several of the writer's 256 KiB chunks.
        let n = 30_000u32;
        let o = Object {
            name: "strip".into(),
            source: String::new(),
            positions_m: (0..n + 2)
                .map(|i| [f64::from(i), f64::from(i % 2), -1.5])
                .collect(),
            facets: (0..n)
                .map(|i| Facet {
                    vertices: [i, i + 1, i + 2],
                    material: MaterialId((i % 7) as u16),
                    temperature_k: (i % 3 == 0).then(|| 250.0 + f64::from(i) / 1024.0),
                    uv: None,
                })
                .collect(),
        };
        let mut w = Trickle {
            bytes: Vec::new(),
            limit: usize::MAX,
        };
        write(&o, &mut w).unwrap();
        assert_eq!(
            w.bytes.len(),
            32 + 5 + 24 * (n as usize + 2) + 24 * n as usize
        );
        assert_eq!(decode("s.bin", &w.bytes).unwrap(), o);
        // A writer that fails part way reports it.
        let mut w = Trickle {
            bytes: Vec::new(),
            limit: 500_000,
        };
        let e = write(&o, &mut w).unwrap_err();
        assert_eq!(e.to_string(), "disk full");
    }

    #[test]
    fn truncation_at_every_length_is_an_error() {
        let bytes = encode(&object()).unwrap();
        for n in 0..bytes.len() {
            let e = decode("o.bin", &bytes[..n]).unwrap_err();
            assert_eq!(e.file, "o.bin");
        }
    }

    #[test]
    fn wrong_magic_and_version_are_errors() {
        let mut bytes = encode(&object()).unwrap();
        bytes[..8].copy_from_slice(b"IRSIGRAW");
        let e = decode("o.bin", &bytes).unwrap_err();
        assert!(e.message.contains("`IRSIGOBJ`"), "{e}");
        let mut bytes = encode(&object()).unwrap();
        bytes[8] = 2;
        let e = decode("o.bin", &bytes).unwrap_err();
        assert!(e.message.contains("version 1, found 2"), "{e}");
        assert_eq!(e.column, 9, "byte offset 8 is column 9");
    }

    #[test]
    fn lying_counts_do_not_allocate_and_say_what_they_claim() {
        for (at, what) in [
            (16, "4294967295-byte name"),
            (20, "4294967295-byte source"),
            (24, "4294967295 positions"),
            (28, "4294967295 facets"),
        ] {
            let mut bytes = encode(&object()).unwrap();
            bytes[at..at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
            let e = decode("o.bin", &bytes).unwrap_err();
            assert!(e.message.contains(what), "{e}");
        }
        // One facet fewer than the bytes hold is as wrong as one more.
        let mut bytes = encode(&object()).unwrap();
        bytes[28..32].copy_from_slice(&1u32.to_le_bytes());
        let e = decode("o.bin", &bytes).unwrap_err();
        assert!(
            e.message.contains("take 138 bytes, but the file has 162"),
            "{e}"
        );
    }

    #[test]
    fn bad_text_and_reserved_bits_are_errors_at_their_offset() {
        let mut bytes = encode(&object()).unwrap();
        bytes[32] = 0xff;
        let e = decode("o.bin", &bytes).unwrap_err();
        assert!(e.message.contains("name is not UTF-8"), "{e}");
        assert_eq!(e.column, 33, "offset 32 is the first invalid byte");
        let mut bytes = encode(&object()).unwrap();
        bytes[12] = 2;
        assert!(decode("o.bin", &bytes).is_err());
        let mut bytes = encode(&object()).unwrap();
        bytes[FACETS_AT + 24 + 14] = 4;
        let e = decode("o.bin", &bytes).unwrap_err();
        assert!(
            e.message.starts_with("facet 1: expected facet flags"),
            "{e}"
        );
        assert_eq!(e.column, FACETS_AT + 24 + 14 + 1);
    }

    #[test]
    fn texture_coordinates_follow_the_facets_only_when_a_facet_has_them() {
        let plain = encode(&object()).unwrap();
        let mut o = object();
        o.facets[0].uv = Some([[0.25, 0.75], [1.0, 0.0], [-3.0, 2.0]]);
        let bytes = encode(&o).unwrap();
        let facets_end = FACETS_AT + 2 * 24;
        assert_eq!(bytes.len(), facets_end + 2 * 48);
        assert_eq!(bytes[12], 1, "header flag bit 0: the section");
        // Facet 0 has a temperature (bit 0) and coordinates (bit 1); facet 1 neither.
        assert_eq!(bytes[FACETS_AT + 14..FACETS_AT + 16], 3u16.to_le_bytes());
        assert_eq!(bytes[FACETS_AT + 24 + 14..FACETS_AT + 24 + 16], [0, 0]);
        let mut masked = bytes[..facets_end].to_vec();
        masked[12] = 0;
        masked[FACETS_AT + 14] = 1;
        assert_eq!(masked, plain, "otherwise the bytes of the object without");
        assert_eq!(
            bytes[facets_end + 8..facets_end + 16],
            0.75f64.to_le_bytes()
        );
        assert_eq!(
            bytes[facets_end + 32..facets_end + 40],
            (-3.0f64).to_le_bytes()
        );
        assert_eq!(bytes[facets_end + 48..], [0; 48]);
        assert_eq!(decode("o.bin", &bytes).unwrap(), o);
        for n in 0..bytes.len() {
            assert!(decode("o.bin", &bytes[..n]).is_err(), "length {n}");
        }
        let mut stray = bytes.clone();
        stray[facets_end + 48 + 47] = 0x80;
        let e = decode("o.bin", &stray).unwrap_err();
        assert_eq!(e.column, facets_end + 48 + 1);
        assert!(
            e.message
                .starts_with("facet 1: expected a texture-coordinate"),
            "{e}"
        );
        // A facet's coordinate flag without the header's section is reserved.
        let mut no_section = plain;
        no_section[FACETS_AT + 24 + 14] = 2;
        let e = decode("o.bin", &no_section).unwrap_err();
        assert!(e.message.contains("within 0x1, found 0x2"), "{e}");
    }

    #[test]
    fn validation_paths_map_to_record_offsets() {
        let o = object();
        assert_eq!(offset_of_path(&o, "positions_m[2]"), 42 + 48);
        assert_eq!(offset_of_path(&o, "facets[1].vertices[2]"), FACETS_AT + 24);
        assert_eq!(offset_of_path(&o, "facets"), FACETS_AT);
        assert_eq!(offset_of_path(&o, "name"), 0);
    }
}
