//! The one way a compressed block is inflated: into a buffer of the size the file's header
//! gives, never the size the stream would grow to.
//!
//! A deflate stream can stand for up to 1032 times its length (RFC 1951: a 258-byte match
//! in at most 2 bits), so a few megabytes can claim gigabytes. Before a byte is inflated
//! the size is checked three ways: it was computed from the header's dimensions (the
//! caller's business, [`zlib_exact`]'s `want`), it is no more than the stream's bytes can
//! hold, and what the whole file would decode to is within
//! [`irsig_model::limits::MEMORY_BUDGET_BYTES`] ([`check_budget`]). The buffer is then
//! reserved fallibly, so a machine with less memory than the budget refuses instead of
//! aborting, and the stream is inflated into it and must fill it exactly.

use irsig_model::limits::MEMORY_BUDGET_BYTES;

use crate::ParseError;

/// The most bytes one byte of a deflate stream can inflate to (RFC 1951).
pub const MAX_DEFLATE_EXPANSION: u64 = 1032;

/// Refuses a file whose tables would decode to more than the memory budget, before any is
/// read: `bytes` is what the header's dimensions say they hold once decoded, `what` says
/// what they are.
///
/// # Errors
/// `bytes` above [`MEMORY_BUDGET_BYTES`], at `at` of `file`.
pub fn check_budget(
    file: &str,
    at: usize,
    bytes: Option<u64>,
    what: &str,
) -> Result<(), ParseError> {
    match bytes {
        Some(b) if b <= MEMORY_BUDGET_BYTES => Ok(()),
        _ => Err(ParseError::in_binary(
            file,
            at,
            format!(
                "{what} would decode to {} bytes, more than the {MEMORY_BUDGET_BYTES} bytes \
                 (16 GiB) of the memory budget",
                bytes.map_or_else(|| "more than 2^64".to_owned(), |b| b.to_string())
            ),
        )),
    }
}

/// A buffer of `len` elements reserved without aborting when memory is short.
///
/// # Errors
/// The allocation fails, at `at` of `file`.
pub fn reserve<T>(file: &str, at: usize, len: usize, what: &str) -> Result<Vec<T>, ParseError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| {
        ParseError::in_binary(
            file,
            at,
            format!(
                "{what} needs {} bytes, which this machine cannot give now",
                len.saturating_mul(std::mem::size_of::<T>())
            ),
        )
    })?;
    Ok(v)
}

/// Inflates the zlib stream `z` (at byte `at` of `file`, `what` for messages) into exactly
/// `want` bytes, `want` computed from the header's dimensions.
///
/// # Errors
/// `want` more than `z` can hold, a buffer that cannot be had, a broken stream or one that
/// does not fill `want` exactly.
pub fn zlib_exact(
    file: &str,
    z: &[u8],
    at: usize,
    want: usize,
    what: &str,
) -> Result<Vec<u8>, ParseError> {
    if want as u64 > (z.len() as u64).saturating_mul(MAX_DEFLATE_EXPANSION) {
        return Err(ParseError::in_binary(
            file,
            at,
            format!(
                "{what} of {want} bytes cannot come from {} compressed bytes (at most \
                 {MAX_DEFLATE_EXPANSION} bytes per byte): the file is damaged",
                z.len()
            ),
        ));
    }
    let mut out: Vec<u8> = reserve(file, at, want, what)?;
    out.resize(want, 0);
    let broken = |status: String| {
        ParseError::in_binary(
            file,
            at,
            format!("expected a zlib stream of {want} bytes ({what}), found {status}"),
        )
    };
    let got = miniz_oxide::inflate::decompress_slice_iter_to_slice(
        &mut out,
        std::iter::once(z),
        true,
        false,
    )
    .map_err(|e| match e {
        miniz_oxide::inflate::TINFLStatus::HasMoreOutput => broken("a longer one".to_owned()),
        other => broken(format!("a broken one ({other:?})")),
    })?;
    if got != want {
        return Err(broken(format!("one of {got} bytes")));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stream_inflates_to_exactly_what_the_header_says() {
        let raw: Vec<u8> = (0..10_000u32).map(|i| (i % 7) as u8).collect();
        let z = miniz_oxide::deflate::compress_to_vec_zlib(&raw, 9);
        assert_eq!(zlib_exact("f", &z, 0, raw.len(), "a table").unwrap(), raw);
        let short = zlib_exact("f", &z, 0, raw.len() - 1, "a table").unwrap_err();
        assert!(short.message.contains("a longer one"), "{}", short.message);
        let long = zlib_exact("f", &z, 0, raw.len() + 1, "a table").unwrap_err();
        assert!(
            long.message.contains("one of 10000 bytes"),
            "{}",
            long.message
        );
    }

    #[test]
    fn a_claim_beyond_the_streams_reach_or_the_budget_is_refused_unallocated() {
        // 4 GiB from a kilobyte: more than deflate can expand to.
        let e = zlib_exact("f", &[0u8; 1000], 7, 1 << 32, "a table").unwrap_err();
        assert!(e.message.contains("cannot come from"), "{}", e.message);
        assert!(check_budget("f", 0, Some(MEMORY_BUDGET_BYTES), "x").is_ok());
        let e = check_budget("f", 0, Some(MEMORY_BUDGET_BYTES + 1), "x").unwrap_err();
        assert!(e.message.contains("memory budget"), "{}", e.message);
        assert!(check_budget("f", 0, None, "x").is_err());
    }
}
