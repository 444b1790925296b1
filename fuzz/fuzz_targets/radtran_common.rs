//! What the radiative-transfer fuzz targets check: decoding and parsing never panic, and
//! an error points inside the input.

use irsig_formats::ParseError;

/// Runs `parse` on `data` as text; returns the parsed value, if any.
pub fn check<T>(data: &[u8], parse: impl Fn(&str, &str) -> Result<T, ParseError>) -> Option<T> {
    let text = match irsig_formats::legacy::decode("fuzz", data) {
        Ok(text) => text,
        Err(e) => {
            assert!(e.line >= 1 && e.column >= 1);
            return None;
        }
    };
    match parse("fuzz", text) {
        Ok(v) => Some(v),
        Err(e) => {
            let lines = text.split('\n').count();
            assert!(e.line >= 1 && e.line <= lines, "line {} of {lines}", e.line);
            assert!(e.column >= 1);
            None
        }
    }
}
