//! Finds the text of a value in RON from a model path such as `materials[1].emissivity[1]`,
//! so that a validation error points at the line that holds the bad value.
//!
//! It follows the path as far as the text allows (a path segment that names part of a
//! tuple, say, stops it) and returns the start of the deepest value it reached. Best
//! effort: the file has already parsed, so only well-formed RON reaches it.

enum Segment<'a> {
    Field(&'a str),
    Index(usize),
}

fn segments(path: &str) -> Vec<Segment<'_>> {
    let mut out = Vec::new();
    for part in path.split('.') {
        let (name, mut rest) = part.split_once('[').map_or((part, ""), |(n, r)| (n, r));
        if !name.is_empty() {
            out.push(Segment::Field(name));
        }
        while let Some((index, after)) = rest.split_once(']') {
            if let Ok(i) = index.parse() {
                out.push(Segment::Index(i));
            }
            rest = after.strip_prefix('[').unwrap_or(after);
        }
    }
    out
}

/// The byte offset of the value at `path` in `text` (0 when even the first segment cannot
/// be followed).
pub(super) fn path_offset(text: &str, path: &str) -> usize {
    let b = text.as_bytes();
    let mut pos = skip_ws(b, 0);
    for seg in segments(path) {
        let next = match seg {
            Segment::Field(name) => find_field(b, pos, name),
            Segment::Index(k) => find_element(b, pos, k),
        };
        match next {
            Some(p) => pos = p,
            None => break,
        }
    }
    pos.min(text.len())
}

/// The length of the value starting at `offset`, for the underline.
pub(super) fn value_len(text: &str, offset: usize) -> usize {
    skip_value(text.as_bytes(), offset).saturating_sub(offset)
}

fn skip_ws(b: &[u8], mut p: usize) -> usize {
    loop {
        while p < b.len() && b[p].is_ascii_whitespace() {
            p += 1;
        }
        if b[p..].starts_with(b"//") {
            while p < b.len() && b[p] != b'\n' {
                p += 1;
            }
        } else if b[p..].starts_with(b"/*") {
            p = b[p + 2..]
                .windows(2)
                .position(|w| w == b"*/")
                .map_or(b.len(), |i| p + 2 + i + 2);
        } else if b[p..].starts_with(b"#![") {
            p = b[p..]
                .iter()
                .position(|&c| c == b']')
                .map_or(b.len(), |i| p + i + 1);
        } else {
            return p;
        }
    }
}

fn is_ident(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// Skips one value (number, string, identifier, struct, list, tuple, map, `Some(..)`) and
/// returns the offset just after it.
fn skip_value(b: &[u8], mut p: usize) -> usize {
    let mut depth = 0usize;
    while p < b.len() {
        match b[p] {
            b'"' => {
                p += 1;
                while p < b.len() && b[p] != b'"' {
                    p += if b[p] == b'\\' { 2 } else { 1 };
                }
                p += 1;
            }
            b'(' | b'[' | b'{' => {
                depth += 1;
                p += 1;
            }
            b')' | b']' | b'}' => {
                if depth == 0 {
                    return p;
                }
                depth -= 1;
                p += 1;
                if depth == 0 {
                    return p;
                }
            }
            b',' if depth == 0 => return p,
            _ => p += 1,
        }
    }
    b.len()
}

/// Past an optional struct name to the opening bracket of the value at `p`.
fn open_bracket(b: &[u8], p: usize, brackets: &[u8]) -> Option<usize> {
    let mut q = p;
    while q < b.len() && is_ident(b[q]) {
        q += 1;
    }
    q = skip_ws(b, q);
    (q < b.len() && brackets.contains(&b[q])).then_some(q + 1)
}

fn find_field(b: &[u8], p: usize, name: &str) -> Option<usize> {
    let mut q = open_bracket(b, p, b"(")?;
    loop {
        q = skip_ws(b, q);
        let start = q;
        while q < b.len() && is_ident(b[q]) {
            q += 1;
        }
        let ident = &b[start..q];
        q = skip_ws(b, q);
        if q >= b.len() || b[q] != b':' {
            return None;
        }
        q = skip_ws(b, q + 1);
        if ident == name.as_bytes() {
            return Some(q);
        }
        q = skip_ws(b, skip_value(b, q));
        if q < b.len() && b[q] == b',' {
            q += 1;
        } else {
            return None;
        }
    }
}

fn find_element(b: &[u8], p: usize, k: usize) -> Option<usize> {
    let mut q = skip_ws(b, open_bracket(b, p, b"[(")?);
    for _ in 0..k {
        q = skip_ws(b, skip_value(b, q));
        if q < b.len() && b[q] == b',' {
            q = skip_ws(b, q + 1);
        } else {
            return None;
        }
    }
    (q < b.len() && !matches!(b[q], b')' | b']')).then_some(q)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn follows_fields_and_indices() {
        let text = "(a: 1, b: [ (x: \"s,)\"), (x: 7, y: [1, 2, 3]) ])";
        let p = path_offset(text, "b[1].y[2]");
        assert_eq!(&text[p..=p], "3");
        let p = path_offset(text, "b[1].x");
        assert_eq!(&text[p..=p], "7");
        // A segment that cannot be followed stops at the deepest value found.
        let p = path_offset(text, "b[1].z");
        assert_eq!(&text[p..p + 2], "(x");
        assert_eq!(path_offset(text, "q"), 0);
    }

    #[test]
    fn comments_and_struct_names_are_skipped() {
        let text = "// c\nScene( /* x */ objects: [ P(t: 1) ])";
        let p = path_offset(text, "objects[0].t");
        assert_eq!(&text[p..=p], "1");
    }
}
