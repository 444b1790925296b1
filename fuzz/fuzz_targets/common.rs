//! What every legacy fuzz target checks: decoding and parsing never panic; an error
//! points inside the input; a parsed file writes back and the writing parses again.

use irsig_formats::ParseError;

/// Runs `parse` on `data`; on success, `write` must succeed and its output must parse.
pub fn check<T, W: std::fmt::Debug>(
    data: &[u8],
    parse: impl Fn(&str, &str) -> Result<T, ParseError>,
    write: impl Fn(&T) -> Result<String, W>,
) {
    let text = match irsig_formats::legacy::decode("fuzz", data) {
        Ok(text) => text,
        Err(e) => {
            assert!(e.line >= 1 && e.column >= 1);
            return;
        }
    };
    match parse("fuzz", text) {
        Ok(parsed) => {
            let written = write(&parsed).expect("a parsed file must write back");
            if let Err(e) = parse("rewritten", &written) {
                panic!("writer output does not parse: {e}\n{written}");
            }
        }
        Err(e) => {
            let lines = text.split('\n').count();
            assert!(e.line >= 1 && e.line <= lines, "line {} of {lines}", e.line);
            assert!(e.column >= 1);
        }
    }
}
