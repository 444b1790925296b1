//! What the two binary forms, the raw scene ([`super::binary`], `IRSIGRAW`) and the object
//! ([`super::binary_object`], `IRSIGOBJ`), share: the opening 16 bytes (an 8-byte magic, a
//! `u32` version and `u32` flags, 0 in every bit the form gives no meaning), `u32` counts, the check of the file
//! length against the header's counts before anything is allocated, positions as `f64`
//! x y z, and records written a chunk at a time. All little-endian, no padding.

use crate::ParseError;

/// Bytes per position: `f64` x y z in metres.
pub(super) const POSITION_LEN: usize = 24;

/// Where the record a validation path names starts, for a body of positions from
/// `positions_at` and facets of `facet_len` bytes from `facets_at`: `positions_m[i]…` and
/// `facets[i]…` at their record, `facets…` at the first; `None` for any other path.
pub(super) fn record_offset(
    path: &str,
    positions_at: usize,
    facets_at: usize,
    facet_len: usize,
) -> Option<usize> {
    let index = |prefix: &str| {
        path.strip_prefix(prefix)
            .and_then(|rest| rest.split(']').next())
            .and_then(|i| i.parse::<usize>().ok())
    };
    if let Some(i) = index("positions_m[") {
        Some(positions_at + POSITION_LEN * i)
    } else if let Some(i) = index("facets[") {
        Some(facets_at + facet_len * i)
    } else {
        path.starts_with("facets").then_some(facets_at)
    }
}

/// One binary form: how its header opens and how messages name it.
#[derive(Debug)]
pub(super) struct Form {
    /// The first eight bytes.
    pub magic: &'static [u8; 8],
    /// The layout version this code reads and writes (bytes 8–11).
    pub version: u32,
    /// The fixed header's length, magic included.
    pub header_len: usize,
    /// What the file holds, for messages ("raw scene", "object").
    pub noun: &'static str,
    /// The bits of the flags word (bytes 12–15) the form gives a meaning; every other
    /// bit is reserved and must be 0, so that a later version can use it.
    pub flag_bits: u32,
}

impl Form {
    /// A buffer for the header (of `capacity` bytes with what follows it), holding the
    /// magic, the version and the flags (only [`Self::flag_bits`] of them kept).
    pub fn start_header(&self, capacity: usize, flags: u32) -> Vec<u8> {
        let mut header = Vec::with_capacity(capacity);
        header.extend_from_slice(self.magic);
        header.extend_from_slice(&self.version.to_le_bytes());
        header.extend_from_slice(&(flags & self.flag_bits).to_le_bytes());
        header
    }

    /// `n` as the `u32` the header stores.
    ///
    /// # Errors
    /// More than `u32::MAX` of `what`, which the layout cannot hold.
    pub fn count(&self, n: usize, what: &str) -> std::io::Result<u32> {
        u32::try_from(n).map_err(|_| {
            std::io::Error::other(format!(
                "the {} has too many {what} for the binary form",
                self.noun
            ))
        })
    }

    /// The checks every file of this form opens with: its magic, a whole fixed-size
    /// header, its version and reserved flag bits that are 0.
    ///
    /// # Errors
    /// The first of these that fails, at its byte offset.
    pub fn check_header(&self, file: &str, bytes: &[u8]) -> Result<(), ParseError> {
        let err = |offset: usize, msg: String| ParseError::in_binary(file, offset, msg);
        if !bytes.starts_with(self.magic) {
            return Err(err(
                0,
                format!(
                    "expected a binary {} starting with `{}`",
                    self.noun,
                    String::from_utf8_lossy(self.magic)
                ),
            ));
        }
        if bytes.len() < self.header_len {
            return Err(err(
                bytes.len(),
                format!(
                    "truncated header: expected {} bytes, found {}",
                    self.header_len,
                    bytes.len()
                ),
            ));
        }
        let found = u32_at(bytes, 8);
        if found != self.version {
            return Err(err(
                8,
                format!(
                    "expected binary {} version {}, found {found}",
                    self.noun, self.version
                ),
            ));
        }
        let flags = u32_at(bytes, 12);
        if flags & !self.flag_bits != 0 {
            let which = if self.flag_bits == 0 {
                "header flags 0 (reserved)".to_owned()
            } else {
                format!(
                    "header flags outside {:#x} to be 0 (reserved)",
                    self.flag_bits
                )
            };
            return Err(err(12, format!("expected {which}, found {flags:#x}")));
        }
        Ok(())
    }

    /// Checks that the file is exactly as long as the header's counts say (`expected`,
    /// computed in `u64` so that no count can overflow it), so that nothing larger than
    /// the file is ever allocated. `declares` says what the header claims, for the message.
    ///
    /// # Errors
    /// A file longer or shorter than `expected`.
    pub fn check_length(
        &self,
        file: &str,
        bytes: &[u8],
        expected: u64,
        declares: impl FnOnce() -> String,
    ) -> Result<(), ParseError> {
        if expected == bytes.len() as u64 {
            return Ok(());
        }
        Err(ParseError::in_binary(
            file,
            bytes.len().min(self.header_len),
            format!(
                "the header declares {}, which take {expected} bytes, but the file has {}",
                declares(),
                bytes.len()
            ),
        ))
    }
}

/// Writes positions as `f64` x y z records.
pub(super) fn write_positions(
    w: &mut dyn std::io::Write,
    positions: &[[f64; 3]],
) -> std::io::Result<()> {
    write_records(w, positions, POSITION_LEN, |p, out| {
        for c in p {
            out.extend_from_slice(&c.to_le_bytes());
        }
    })
}

/// Reads the positions of `bytes`, whose length the header check has proved a multiple of
/// [`POSITION_LEN`].
pub(super) fn read_positions(bytes: &[u8]) -> Vec<[f64; 3]> {
    bytes
        .chunks_exact(POSITION_LEN)
        .map(|c| [f64_at(c, 0), f64_at(c, 8), f64_at(c, 16)])
        .collect()
}

/// Bytes per facet of the texture-coordinate section: `f64` u v at each of three corners.
pub(super) const UV_LEN: usize = 48;

/// The header flag that says a texture-coordinate section follows the facets: one
/// [`UV_LEN`] record per facet. Written only when some facet has coordinates, so that a
/// scene or object without them keeps the bytes it had before the section existed.
pub(super) const HAS_UV_SECTION: u32 = 1;

/// The header flags for `uvs`: [`HAS_UV_SECTION`] when any facet has coordinates.
pub(super) fn uv_flags<'a>(mut uvs: impl Iterator<Item = Option<&'a [[f64; 2]; 3]>>) -> u32 {
    if uvs.any(|uv| uv.is_some()) {
        HAS_UV_SECTION
    } else {
        0
    }
}

/// Writes the texture-coordinate section when `flags` has [`HAS_UV_SECTION`]: per facet
/// its coordinates, or zeros for a facet without.
pub(super) fn write_uvs<T>(
    w: &mut dyn std::io::Write,
    flags: u32,
    facets: &[T],
    uv: impl Fn(&T) -> Option<&[[f64; 2]; 3]>,
) -> std::io::Result<()> {
    if flags & HAS_UV_SECTION == 0 {
        return Ok(());
    }
    write_records(w, facets, UV_LEN, |f, out| {
        let corners = uv(f).copied().unwrap_or([[0.0; 2]; 3]);
        for x in corners.as_flattened() {
            out.extend_from_slice(&x.to_le_bytes());
        }
    })
}

/// The coordinates of facet `i`, from its record in the texture-coordinate section of
/// `bytes` that starts at `section_at` (`None`: the file has no such section, and no
/// facet has coordinates): `Some` when the facet's flag says it has them, else `None`,
/// and then the record must be zeros (so that decoding and encoding are inverse). The
/// section's length is the caller's to have checked.
///
/// # Errors
/// A facet without coordinates whose record is not zeros, at the record's offset.
pub(super) fn read_uv(
    file: &str,
    bytes: &[u8],
    section_at: Option<usize>,
    has_uv: bool,
    i: usize,
) -> Result<Option<[[f64; 2]; 3]>, ParseError> {
    let Some(section_at) = section_at else {
        return Ok(None);
    };
    let at = section_at + UV_LEN * i;
    let c = &bytes[at..at + UV_LEN];
    if has_uv {
        let x = |k: usize| f64_at(c, 8 * k);
        return Ok(Some([[x(0), x(1)], [x(2), x(3)], [x(4), x(5)]]));
    }
    if c.iter().any(|&b| b != 0) {
        return Err(ParseError::in_binary(
            file,
            at,
            format!(
                "facet {i}: expected a texture-coordinate record of zeros, as its flags say it \
                 has none"
            ),
        ));
    }
    Ok(None)
}

/// Bytes encoded per `write_all` by [`write_records`]: large enough that the writer's
/// buffer is bypassed and the system calls are few, small enough to stay in cache.
const CHUNK_LEN: usize = 256 * 1024;

/// Encodes `records` (each `record_len` bytes, by `encode`) into a reused buffer and
/// writes it whenever it is full.
pub(super) fn write_records<T>(
    w: &mut dyn std::io::Write,
    records: &[T],
    record_len: usize,
    encode: impl Fn(&T, &mut Vec<u8>),
) -> std::io::Result<()> {
    let per_chunk = (CHUNK_LEN / record_len).max(1);
    let mut buf = Vec::with_capacity(per_chunk * record_len);
    for chunk in records.chunks(per_chunk) {
        buf.clear();
        for r in chunk {
            encode(r, &mut buf);
        }
        w.write_all(&buf)?;
    }
    Ok(())
}

// Callers pass offsets whose bytes the header and length checks have already proved present.
pub(super) fn u32_at(b: &[u8], at: usize) -> u32 {
    let mut a = [0; 4];
    a.copy_from_slice(&b[at..at + 4]);
    u32::from_le_bytes(a)
}

pub(super) fn f64_at(b: &[u8], at: usize) -> f64 {
    let mut a = [0; 8];
    a.copy_from_slice(&b[at..at + 8]);
    f64::from_le_bytes(a)
}

#[cfg(test)]
mod tests {
    use super::*;

    const FORM: Form = Form {
        magic: b"IRSIGTST",
        version: 3,
        header_len: 20,
        noun: "test",
        flag_bits: 0,
    };

    fn header() -> Vec<u8> {
        let mut h = FORM.start_header(20, 0);
        h.extend_from_slice(&7u32.to_le_bytes());
        h
    }

    #[test]
    fn the_opening_bytes_are_magic_version_and_zero_flags() {
        let h = header();
        assert_eq!(&h[..8], b"IRSIGTST");
        assert_eq!(h[8..12], 3u32.to_le_bytes());
        assert_eq!(h[12..16], [0; 4]);
        assert!(FORM.check_header("t.bin", &h).is_ok());
    }

    #[test]
    fn each_header_check_fails_at_its_offset() {
        let mut wrong_magic = header();
        wrong_magic[0] = b'X';
        let mut wrong_version = header();
        wrong_version[8] = 4;
        let mut flags = header();
        flags[13] = 1;
        for (bytes, column, says) in [
            (
                wrong_magic,
                1,
                "expected a binary test starting with `IRSIGTST`",
            ),
            (
                header()[..19].to_vec(),
                20,
                "truncated header: expected 20 bytes, found 19",
            ),
            (wrong_version, 9, "expected binary test version 3, found 4"),
            (flags, 13, "expected header flags 0 (reserved), found 0x100"),
        ] {
            let e = FORM.check_header("t.bin", &bytes).unwrap_err();
            assert_eq!((e.column, e.message.as_str()), (column, says));
        }
    }

    #[test]
    fn a_form_reads_its_own_flag_bits_and_refuses_the_reserved_ones() {
        let low = Form {
            flag_bits: 0xffff,
            ..FORM
        };
        let mut h = low.start_header(20, 0x0001_0007);
        h.extend_from_slice(&7u32.to_le_bytes());
        assert_eq!(
            h[12..16],
            7u32.to_le_bytes(),
            "bits outside the form's are not written"
        );
        assert!(low.check_header("t.bin", &h).is_ok());
        h[14] = 1;
        let e = low.check_header("t.bin", &h).unwrap_err();
        assert_eq!(
            (e.column, e.message.as_str()),
            (
                13,
                "expected header flags outside 0xffff to be 0 (reserved), found 0x10007"
            )
        );
        assert!(FORM.check_header("t.bin", &h).is_err());
    }

    #[test]
    fn the_length_must_match_the_counts_exactly() {
        let h = header();
        assert!(FORM.check_length("t.bin", &h, 20, String::new).is_ok());
        let e = FORM
            .check_length("t.bin", &h, 21, || "7 things".into())
            .unwrap_err();
        assert_eq!(
            e.message,
            "the header declares 7 things, which take 21 bytes, but the file has 20"
        );
    }

    #[test]
    fn positions_round_trip_and_counts_fit_u32() {
        let p = [[1.5, -2.0, 1e-9], [0.0, f64::MAX, -0.0]];
        let mut out = Vec::new();
        write_positions(&mut out, &p).unwrap();
        assert_eq!(out.len(), 2 * POSITION_LEN);
        assert_eq!(read_positions(&out), p);
        assert_eq!(FORM.count(5, "things").unwrap(), 5);
        if let Ok(too_many) = usize::try_from(u64::from(u32::MAX) + 1) {
            let e = FORM.count(too_many, "things").unwrap_err();
            assert_eq!(
                e.to_string(),
                "the test has too many things for the binary form"
            );
        }
    }
}
