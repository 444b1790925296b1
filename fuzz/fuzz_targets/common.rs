//! What every legacy fuzz target checks: decoding and parsing never panic; an error
//! points inside the input; a parsed file writes back, the writing parses again, and it
//! gives back the same values: written once more, it is the same text (as the canonical
//! targets check).

use irsig_formats::ParseError;

/// Runs `parse` on `data`; on success, `write` must succeed, its output must parse, and
/// writing that again must give the same text.
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
            let again = match parse("rewritten", &written) {
                Ok(again) => again,
                Err(e) => panic!("writer output does not parse: {e}\n{written}"),
            };
            let rewritten = write(&again).expect("a parsed file must write back");
            assert_eq!(
                rewritten, written,
                "the written file does not give back the same values"
            );
        }
        Err(e) => {
            let lines = text.split('\n').count();
            assert!(e.line >= 1 && e.line <= lines, "line {} of {lines}", e.line);
            assert!(e.column >= 1);
        }
    }
}
