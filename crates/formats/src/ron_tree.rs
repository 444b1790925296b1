//! RON with positions: a value tree that remembers where every value and key came from
//! ([`parse`]), and the byte range of the value at a model path such as
//! `materials[1].emissivity[1]` ([`locate`]), over one grammar.
//!
//! The `ron` crate is the authority on syntax: [`parse`] checks the text with it first, so
//! a syntax error reads, with its line and column, as it would for any RON file. The tree
//! exists so that errors found later (a pipeline's cycle or unknown parameter, a model
//! rule broken by an emissivity of 1.3) can point at the line and column of the value at
//! fault; `ron::Value` keeps no positions and forgets the difference between a list and a
//! tuple.
//!
//! ```
//! use irsig_formats::ron_tree::{self, Kind};
//! let text = "(materials: [\n  (id: 1, emissivity: [(0.0, 0.9)]),\n  (id: 2, emissivity: [(0.0, 1.3)]),\n])";
//! let root = ron_tree::parse("lib.ron", text, "material library").unwrap();
//! assert!(matches!(root.kind, Kind::Struct(None, _)));
//! let (start, end) = ron_tree::locate(text, "materials[1].emissivity[0]");
//! assert_eq!(&text[start..end], "(0.0, 1.3)");
//! assert_eq!(irsig_formats::line_column(text, start), (3, 24));
//! ```

use crate::ParseError;

/// A value and the byte range of its text in the source.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    /// What the value is.
    pub kind: Kind,
    /// Byte offset of the first character.
    pub start: usize,
    /// Byte offset one past the last character.
    pub end: usize,
}

/// A struct field name or map key, with its position.
#[derive(Debug, Clone, PartialEq)]
pub struct Key {
    /// The name as written.
    pub name: String,
    /// Byte offset of the first character.
    pub start: usize,
    /// Byte offset one past the last character.
    pub end: usize,
}

/// The kinds of RON value.
#[derive(Debug, Clone, PartialEq)]
pub enum Kind {
    Bool(bool),
    /// A number, as written (so that `1e-3` is passed on as `1e-3`).
    Number(String),
    /// A string or character literal, unescaped.
    Str(String),
    /// A bare identifier: a unit enum variant, `None`, or a unit struct.
    Ident(String),
    /// `[a, b]`
    List(Vec<Node>),
    /// `(a, b)` or `Name(a, b)`, including `Some(x)`.
    Tuple(Option<String>, Vec<Node>),
    /// `(field: a)` or `Name(field: a)`.
    Struct(Option<String>, Vec<(Key, Node)>),
    /// `{key: value}`
    Map(Vec<(Node, Node)>),
}

impl Kind {
    /// What this value is, for "expected X, found Y" messages.
    #[must_use]
    pub fn describe(&self) -> &'static str {
        match self {
            Kind::Bool(_) => "a boolean",
            Kind::Number(_) => "a number",
            Kind::Str(_) => "a string",
            Kind::Ident(_) => "an identifier",
            Kind::List(_) => "a list `[...]`",
            Kind::Tuple(..) => "a tuple `(...)`",
            Kind::Struct(..) => "a struct `Name(field: ...)`",
            Kind::Map(_) => "a map `{...}`",
        }
    }
}

/// A syntax error of this parser: byte offset and message. Only reached for text that `ron`
/// accepted but this subset does not (byte strings, for example).
#[derive(Debug, Clone, PartialEq)]
struct SyntaxError {
    offset: usize,
    message: String,
}

/// Whether `text` is a struct with a field `name` at its top level: false for anything
/// else, text that is not RON included (its reader reports that).
#[must_use]
pub fn has_top_level_field(text: &str, name: &str) -> bool {
    parse("", text, "document").is_ok_and(|root| {
        matches!(&root.kind, Kind::Struct(_, fields) if fields.iter().any(|(k, _)| k.name == name))
    })
}

/// Parses one RON document into a located tree. `what` names the document in messages
/// ("pipeline", "material library").
///
/// # Errors
/// Text that is not RON, at `ron`'s line and column and with its message.
pub fn parse(file: &str, text: &str, what: &str) -> Result<Node, ParseError> {
    if let Err(e) = ron::Options::default().from_str::<serde::de::IgnoredAny>(text) {
        let offset = crate::offset_of(text, e.span.start.line, e.span.start.col);
        return Err(ParseError::at_offset(
            file,
            text,
            offset,
            format!(
                "malformed {what} (RON): {}",
                crate::canonical::ron_message(&e.code)
            ),
        ));
    }
    parse_tree(text).map_err(|e| {
        ParseError::at_offset(
            file,
            text,
            e.offset,
            format!("malformed {what} (RON): {}", e.message),
        )
    })
}

fn parse_tree(source: &str) -> Result<Node, SyntaxError> {
    let mut p = Parser {
        src: source,
        pos: 0,
    };
    p.skip_header()?;
    let node = p.value()?;
    p.skip_trivia()?;
    if p.pos < source.len() {
        return Err(p.error("expected the end of the file after the top-level value"));
    }
    Ok(node)
}

/// A step of a model path: a struct field or map key, or a list or tuple index.
enum Segment<'a> {
    Field(&'a str),
    Index(usize),
}

/// `a.b[2][0].c` as segments; malformed indices are left out.
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

/// The byte range `(start, end)` in RON `text` of the value at a model `path` (as
/// `irsig_model::ModelError::path` gives it: `materials[1].emissivity[1]`).
///
/// The path is followed as far as the text allows: a segment that cannot be followed (a
/// field of a tuple, an index past the end) stops it at the deepest value reached, the
/// whole document when even the first segment fails. `Some(x)` is looked through. Values
/// before the one sought are skipped without building a tree, so locating a value in a
/// large file costs one pass and no allocation per value.
#[must_use]
pub fn locate(text: &str, path: &str) -> (usize, usize) {
    let mut p = Parser { src: text, pos: 0 };
    if p.skip_header().is_err() {
        return (0, 0);
    }
    let mut start = p.pos;
    for segment in segments(path) {
        p.pos = start;
        match p.child(&segment) {
            Ok(Some(at)) => start = at,
            Ok(None) | Err(_) => break,
        }
    }
    p.pos = start;
    let end = match p.skip_value() {
        Ok(()) => p.pos,
        Err(_) => text.len(),
    };
    (start.min(text.len()), end.max(start).min(text.len()))
}

struct Parser<'a> {
    src: &'a str,
    pos: usize,
}

impl Parser<'_> {
    fn rest(&self) -> &str {
        self.src.get(self.pos..).unwrap_or("")
    }

    fn peek(&self) -> Option<char> {
        self.rest().chars().next()
    }

    fn error(&self, message: &str) -> SyntaxError {
        SyntaxError {
            offset: self.pos,
            message: message.to_owned(),
        }
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.peek()?;
        self.pos += c.len_utf8();
        Some(c)
    }

    fn eat(&mut self, c: char) -> bool {
        if self.peek() == Some(c) {
            self.pos += c.len_utf8();
            true
        } else {
            false
        }
    }

    fn expect(&mut self, c: char) -> Result<(), SyntaxError> {
        if self.eat(c) {
            Ok(())
        } else {
            Err(self.error(&format!("expected `{c}`")))
        }
    }

    /// Skips whitespace and comments (`//` to the end of the line, nested `/* */`).
    fn skip_trivia(&mut self) -> Result<(), SyntaxError> {
        loop {
            let rest = self.rest();
            if let Some(c) = rest.chars().next().filter(|c| c.is_whitespace()) {
                self.pos += c.len_utf8();
            } else if rest.starts_with("//") {
                self.pos += rest.find('\n').unwrap_or(rest.len());
            } else if rest.starts_with("/*") {
                let mut depth = 0usize;
                loop {
                    let r = self.rest();
                    if r.starts_with("/*") {
                        depth += 1;
                        self.pos += 2;
                    } else if r.starts_with("*/") {
                        depth -= 1;
                        self.pos += 2;
                        if depth == 0 {
                            break;
                        }
                    } else if self.bump().is_none() {
                        return Err(self.error("unterminated block comment"));
                    }
                }
            } else {
                return Ok(());
            }
        }
    }

    fn value(&mut self) -> Result<Node, SyntaxError> {
        self.skip_trivia()?;
        let start = self.pos;
        let kind = match self.peek() {
            None => return Err(self.error("expected a value, found the end of the file")),
            Some('[') => {
                self.pos += 1;
                Kind::List(self.sequence(']')?)
            }
            Some('{') => {
                self.pos += 1;
                self.map()?
            }
            Some('(') => {
                self.pos += 1;
                self.paren_body(None)?
            }
            Some('"') => Kind::Str(self.string()?),
            Some('\'') => Kind::Str(self.char_literal()?),
            Some('r') if self.at_raw_string() => Kind::Str(self.raw_string()?),
            Some(c) if c.is_ascii_digit() || matches!(c, '-' | '+' | '.') => self.number(),
            Some(c) if c.is_alphabetic() || c == '_' => {
                let name = self.identifier();
                match name.as_str() {
                    "true" => Kind::Bool(true),
                    "false" => Kind::Bool(false),
                    "inf" | "NaN" => Kind::Number(name),
                    _ => {
                        let save = self.pos;
                        self.skip_trivia()?;
                        if self.eat('(') {
                            self.paren_body(Some(name))?
                        } else {
                            self.pos = save;
                            Kind::Ident(name)
                        }
                    }
                }
            }
            Some(c) => return Err(self.error(&format!("expected a value, found `{c}`"))),
        };
        Ok(Node {
            kind,
            start,
            end: self.pos,
        })
    }

    fn identifier(&mut self) -> String {
        let (start, end) = self.scan_identifier();
        self.src[start..end].to_owned()
    }

    /// Moves past an identifier (`r#` raw ones too) and returns the byte range of its name.
    /// A raw identifier may hold `.`, `+` and `-` as well (`r#sky-view`), as `ron` reads it.
    fn scan_identifier(&mut self) -> (usize, usize) {
        let raw = self.rest().starts_with("r#");
        if raw {
            self.pos += 2;
        }
        let rest = self.rest();
        let len = rest
            .find(|c: char| {
                !(c.is_alphanumeric() || c == '_' || (raw && matches!(c, '.' | '+' | '-')))
            })
            .unwrap_or(rest.len());
        let start = self.pos;
        self.pos += len;
        (start, self.pos)
    }

    fn number(&mut self) -> Kind {
        let start = self.pos;
        self.scan_number();
        Kind::Number(self.src[start..self.pos].to_owned())
    }

    fn scan_number(&mut self) {
        let start = self.pos;
        let mut prev = ' ';
        while let Some(c) = self.peek() {
            let exponent_sign =
                matches!(c, '+' | '-') && (self.pos == start || matches!(prev, 'e' | 'E'));
            if c.is_alphanumeric() || c == '_' || c == '.' || exponent_sign {
                prev = c;
                self.pos += c.len_utf8();
            } else {
                break;
            }
        }
    }

    /// Elements up to `close`, separated by commas, a trailing comma allowed.
    fn sequence(&mut self, close: char) -> Result<Vec<Node>, SyntaxError> {
        let mut items = Vec::new();
        loop {
            self.skip_trivia()?;
            if self.eat(close) {
                return Ok(items);
            }
            items.push(self.value()?);
            self.skip_trivia()?;
            if !self.eat(',') {
                self.skip_trivia()?;
                self.expect(close)?;
                return Ok(items);
            }
        }
    }

    fn map(&mut self) -> Result<Kind, SyntaxError> {
        let mut entries = Vec::new();
        loop {
            self.skip_trivia()?;
            if self.eat('}') {
                return Ok(Kind::Map(entries));
            }
            let key = self.value()?;
            self.skip_trivia()?;
            self.expect(':')?;
            let value = self.value()?;
            entries.push((key, value));
            self.skip_trivia()?;
            if !self.eat(',') {
                self.skip_trivia()?;
                self.expect('}')?;
                return Ok(Kind::Map(entries));
            }
        }
    }

    /// After `(`: a struct if the first item is `ident:`, else a tuple.
    fn paren_body(&mut self, name: Option<String>) -> Result<Kind, SyntaxError> {
        self.skip_trivia()?;
        let save = self.pos;
        let is_struct = if self.peek().is_some_and(|c| c.is_alphabetic() || c == '_') {
            self.identifier();
            self.skip_trivia()?;
            let colon = self.rest().starts_with(':') && !self.rest().starts_with("::");
            self.pos = save;
            colon
        } else {
            false
        };
        if !is_struct {
            return Ok(Kind::Tuple(name, self.sequence(')')?));
        }
        let mut fields = Vec::new();
        loop {
            self.skip_trivia()?;
            if self.eat(')') {
                return Ok(Kind::Struct(name, fields));
            }
            let start = self.pos;
            let field = self.identifier();
            if field.is_empty() {
                return Err(self.error("expected a field name"));
            }
            let key = Key {
                name: field,
                start,
                end: self.pos,
            };
            self.skip_trivia()?;
            self.expect(':')?;
            let value = self.value()?;
            fields.push((key, value));
            self.skip_trivia()?;
            if !self.eat(',') {
                self.skip_trivia()?;
                self.expect(')')?;
                return Ok(Kind::Struct(name, fields));
            }
        }
    }

    fn string(&mut self) -> Result<String, SyntaxError> {
        self.expect('"')?;
        let mut out = String::new();
        loop {
            match self.bump() {
                None => return Err(self.error("unterminated string")),
                Some('"') => return Ok(out),
                Some('\\') => out.push(self.escape()?),
                Some(c) => out.push(c),
            }
        }
    }

    fn char_literal(&mut self) -> Result<String, SyntaxError> {
        self.expect('\'')?;
        let c = match self.bump() {
            Some('\\') => self.escape()?,
            Some(c) => c,
            None => return Err(self.error("unterminated character")),
        };
        self.expect('\'')?;
        Ok(c.to_string())
    }

    fn escape(&mut self) -> Result<char, SyntaxError> {
        Ok(match self.bump() {
            Some('n') => '\n',
            Some('t') => '\t',
            Some('r') => '\r',
            Some('0') => '\0',
            Some(c @ ('\\' | '"' | '\'')) => c,
            Some('x') => {
                let hex = self.rest().get(..2).unwrap_or("");
                let v = u32::from_str_radix(hex, 16).map_err(|_| self.error("bad `\\x` escape"))?;
                self.pos += 2;
                char::from_u32(v).ok_or_else(|| self.error("bad `\\x` escape"))?
            }
            Some('u') => {
                self.expect('{')?;
                let rest = self.rest();
                let end = rest
                    .find('}')
                    .ok_or_else(|| self.error("bad `\\u` escape"))?;
                let v = u32::from_str_radix(&rest[..end].replace('_', ""), 16)
                    .map_err(|_| self.error("bad `\\u` escape"))?;
                self.pos += end + 1;
                char::from_u32(v).ok_or_else(|| self.error("bad `\\u` escape"))?
            }
            _ => return Err(self.error("unknown escape in string")),
        })
    }

    fn raw_string(&mut self) -> Result<String, SyntaxError> {
        self.expect('r')?;
        let mut hashes = 0;
        while self.eat('#') {
            hashes += 1;
        }
        self.expect('"')?;
        let close = format!("\"{}", "#".repeat(hashes));
        let rest = self.rest();
        let end = rest
            .find(&close)
            .ok_or_else(|| self.error("unterminated raw string"))?;
        let text = rest[..end].to_owned();
        self.pos += end + close.len();
        Ok(text)
    }
}

/// Moving through values without building them: what [`locate`] uses.
impl Parser<'_> {
    /// Skips leading trivia and `#![enable(...)]` extension attributes.
    fn skip_header(&mut self) -> Result<(), SyntaxError> {
        self.skip_trivia()?;
        while self.rest().starts_with("#!") {
            match self.rest().find(']') {
                Some(i) => self.pos += i + 1,
                None => return Err(self.error("unterminated `#![...]` attribute")),
            }
            self.skip_trivia()?;
        }
        Ok(())
    }

    /// `r"..."` or `r#"..."#` (any number of `#`), not a raw identifier `r#name`.
    fn at_raw_string(&self) -> bool {
        self.rest()
            .strip_prefix('r')
            .is_some_and(|r| r.trim_start_matches('#').starts_with('"'))
    }

    fn starts_identifier(&self) -> bool {
        self.peek().is_some_and(|c| c.is_alphabetic() || c == '_')
    }

    /// After `(`: whether the body is a struct's (`field: ...`) rather than a tuple's.
    fn struct_body_follows(&mut self) -> Result<bool, SyntaxError> {
        self.skip_trivia()?;
        if !self.starts_identifier() {
            return Ok(false);
        }
        let save = self.pos;
        self.scan_identifier();
        self.skip_trivia()?;
        let colon = self.rest().starts_with(':') && !self.rest().starts_with("::");
        self.pos = save;
        Ok(colon)
    }

    /// Moves past one value, as [`Parser::value`] reads it, without building it.
    fn skip_value(&mut self) -> Result<(), SyntaxError> {
        self.skip_trivia()?;
        match self.peek() {
            None => Err(self.error("expected a value, found the end of the file")),
            Some('[') => {
                self.pos += 1;
                self.skip_items(']', false)
            }
            Some('{') => {
                self.pos += 1;
                self.skip_items('}', true)
            }
            Some('(') => {
                self.pos += 1;
                self.skip_paren_body()
            }
            Some('"') => self.string().map(drop),
            Some('\'') => self.char_literal().map(drop),
            Some('r') if self.at_raw_string() => self.raw_string().map(drop),
            Some(c) if c.is_ascii_digit() || matches!(c, '-' | '+' | '.') => {
                self.scan_number();
                Ok(())
            }
            Some(c) if c.is_alphabetic() || c == '_' => {
                self.scan_identifier();
                let save = self.pos;
                self.skip_trivia()?;
                if self.eat('(') {
                    self.skip_paren_body()
                } else {
                    self.pos = save;
                    Ok(())
                }
            }
            Some(c) => Err(self.error(&format!("expected a value, found `{c}`"))),
        }
    }

    /// Skips comma-separated items up to `close`; each is `key: value` when `keyed` (a
    /// map), a value otherwise.
    fn skip_items(&mut self, close: char, keyed: bool) -> Result<(), SyntaxError> {
        loop {
            self.skip_trivia()?;
            if self.eat(close) {
                return Ok(());
            }
            if keyed {
                self.skip_value()?;
                self.skip_trivia()?;
                self.expect(':')?;
            }
            self.skip_value()?;
            self.skip_trivia()?;
            if !self.eat(',') {
                self.skip_trivia()?;
                return self.expect(close);
            }
        }
    }

    /// After `(`: skips a struct's fields or a tuple's elements and the closing `)`.
    fn skip_paren_body(&mut self) -> Result<(), SyntaxError> {
        if !self.struct_body_follows()? {
            return self.skip_items(')', false);
        }
        loop {
            self.skip_trivia()?;
            if self.eat(')') {
                return Ok(());
            }
            self.scan_identifier();
            self.skip_trivia()?;
            self.expect(':')?;
            self.skip_value()?;
            self.skip_trivia()?;
            if !self.eat(',') {
                self.skip_trivia()?;
                return self.expect(')');
            }
        }
    }

    /// From the start of a value, the start of its child named by `segment`: a struct
    /// field or string map key, or a list or tuple element. `None` when the value has no
    /// such child. `Some(x)` is looked through to `x`.
    fn child(&mut self, segment: &Segment<'_>) -> Result<Option<usize>, SyntaxError> {
        self.skip_trivia()?;
        let close = if self.starts_identifier() {
            let (start, end) = self.scan_identifier();
            let is_some = &self.src[start..end] == "Some";
            self.skip_trivia()?;
            if !self.eat('(') {
                return Ok(None);
            }
            if is_some {
                return self.child(segment);
            }
            ')'
        } else if self.eat('(') {
            ')'
        } else if self.eat('[') {
            ']'
        } else if self.eat('{') {
            '}'
        } else {
            return Ok(None);
        };
        match (segment, close) {
            (Segment::Field(name), ')') if self.struct_body_follows()? => loop {
                self.skip_trivia()?;
                let (start, end) = self.scan_identifier();
                self.skip_trivia()?;
                self.expect(':')?;
                self.skip_trivia()?;
                if &self.src[start..end] == *name {
                    return Ok(Some(self.pos));
                }
                self.skip_value()?;
                self.skip_trivia()?;
                if !self.eat(',') {
                    return Ok(None);
                }
                self.skip_trivia()?;
                if self.peek() == Some(')') {
                    return Ok(None);
                }
            },
            (Segment::Field(name), '}') => loop {
                self.skip_trivia()?;
                if self.eat('}') {
                    return Ok(None);
                }
                let key = if self.peek() == Some('"') {
                    Some(self.string()?)
                } else {
                    self.skip_value()?;
                    None
                };
                self.skip_trivia()?;
                self.expect(':')?;
                self.skip_trivia()?;
                if key.as_deref() == Some(*name) {
                    return Ok(Some(self.pos));
                }
                self.skip_value()?;
                self.skip_trivia()?;
                if !self.eat(',') {
                    return Ok(None);
                }
            },
            (Segment::Index(k), ')' | ']') if close == ']' || !self.struct_body_follows()? => {
                for _ in 0..*k {
                    self.skip_value()?;
                    self.skip_trivia()?;
                    if !self.eat(',') {
                        return Ok(None);
                    }
                }
                self.skip_trivia()?;
                Ok((!self.rest().starts_with([')', ']'])).then_some(self.pos))
            }
            _ => Ok(None),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_point_at_the_text_of_each_value() {
        let src =
            "Pipeline(\n  stages: [ (tool: \"cat\", params: {\"n\": 3, \"x\": (1, 2.5e-3)}) ],\n)";
        let root = parse_tree(src).unwrap();
        let Kind::Struct(Some(name), fields) = &root.kind else {
            panic!("{root:?}")
        };
        assert_eq!(name, "Pipeline");
        let (key, stages) = &fields[0];
        assert_eq!(&src[key.start..key.end], "stages");
        let Kind::List(items) = &stages.kind else {
            panic!()
        };
        let Kind::Struct(None, stage) = &items[0].kind else {
            panic!()
        };
        assert_eq!(&src[stage[0].1.start..stage[0].1.end], "\"cat\"");
        let Kind::Map(params) = &stage[1].1.kind else {
            panic!()
        };
        assert_eq!(params[0].1.kind, Kind::Number("3".into()));
        let Kind::Tuple(None, t) = &params[1].1.kind else {
            panic!()
        };
        assert_eq!(t[1].kind, Kind::Number("2.5e-3".into()));
    }

    #[test]
    fn comments_escapes_and_raw_strings() {
        let src = "/* a /* nested */ comment */ [\"a\\\"b\\u{e9}\", r#\"x\"y\"#, // end\n 'c', Some(-1), None]";
        let root = parse_tree(src).unwrap();
        let Kind::List(items) = root.kind else {
            panic!()
        };
        assert_eq!(items[0].kind, Kind::Str("a\"b\u{e9}".into()));
        assert_eq!(items[1].kind, Kind::Str("x\"y".into()));
        assert_eq!(items[2].kind, Kind::Str("c".into()));
        let Kind::Tuple(Some(some), inner) = &items[3].kind else {
            panic!()
        };
        assert_eq!(some, "Some");
        assert_eq!(&src[inner[0].start..inner[0].end], "-1");
        assert_eq!(items[4].kind, Kind::Ident("None".into()));
    }

    #[test]
    fn trailing_garbage_is_an_error() {
        assert!(parse_tree("[1] [2]").is_err());
        assert!(parse_tree("[1, ").is_err());
    }

    #[test]
    fn syntax_errors_are_rons_at_its_line_and_column() {
        let e = parse("p.ron", "(\n  a: 1\n  b: 2,\n)", "pipeline").unwrap_err();
        assert_eq!((e.file.as_str(), e.line, e.column), ("p.ron", 3, 3), "{e}");
        assert!(e.message.starts_with("malformed pipeline (RON): "), "{e}");
    }

    fn at<'a>(text: &'a str, path: &str) -> &'a str {
        let (start, end) = locate(text, path);
        &text[start..end]
    }

    #[test]
    fn locate_follows_fields_and_indices() {
        let text = "(a: 1, b: [ (x: \"s,)\"), (x: 7, y: [1, 2, 3]) ])";
        assert_eq!(at(text, "b[1].y[2]"), "3");
        assert_eq!(at(text, "b[1].x"), "7");
        assert_eq!(at(text, "b[0].x"), "\"s,)\"");
        // A segment that cannot be followed stops at the deepest value found.
        assert_eq!(at(text, "b[1].z"), "(x: 7, y: [1, 2, 3])");
        assert_eq!(at(text, "b[7]"), "[ (x: \"s,)\"), (x: 7, y: [1, 2, 3]) ]");
        assert_eq!(locate(text, "q"), (0, text.len()));
    }

    #[test]
    fn locate_skips_comments_names_and_looks_through_some() {
        let text = "// c\n#![enable(implicit_some)]\nScene( /* x */ objects: [ P(t: 1) ], \
                    c: Some((1.0, 2.0, 3.5)), m: {\"k\": [4, 5]}, s: r#\"a\"b\"#, z: ',', w: 9)";
        assert_eq!(at(text, "objects[0].t"), "1");
        assert_eq!(at(text, "c[2]"), "3.5");
        assert_eq!(at(text, "m.k[1]"), "5");
        // A character literal holding a comma is one value, as the tree reads it.
        assert_eq!(at(text, "z"), "','");
        assert_eq!(at(text, "w"), "9");
        // A field of a tuple cannot be followed: the tuple is where it stops.
        assert_eq!(at(text, "c.x"), "Some((1.0, 2.0, 3.5))");
    }

    #[test]
    fn locate_passes_raw_identifiers_that_hold_a_hyphen() {
        // A decision's models are written `r#sky-view`, `r#path-terms`, `r#sub-bands`: the
        // entries after one are reached, not the list that holds them.
        let text = "(choices: [\n  (model: r#sky-view, setting: \"0\"),\n  \
                    (model: r#path-terms, setting: \"exakt\"),\n  \
                    (model: r#sub.bands+x, setting: \"x\"),\n])";
        assert_eq!(at(text, "choices[1].setting"), "\"exakt\"");
        assert_eq!(at(text, "choices[2].setting"), "\"x\"");
        // Line 3, column 34: the setting of the second entry, as an error reports it.
        let (start, _) = locate(text, "choices[1].setting");
        let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
        assert_eq!(text[..start].matches('\n').count() + 1, 3);
        assert_eq!(start - line_start + 1, 34);
        // The tree reads the name whole.
        let root = parse_tree(text).unwrap();
        let Kind::Struct(None, fields) = &root.kind else {
            panic!("{root:?}")
        };
        let Kind::List(items) = &fields[0].1.kind else {
            panic!()
        };
        let Kind::Struct(None, entry) = &items[1].kind else {
            panic!()
        };
        assert_eq!(entry[0].1.kind, Kind::Ident("path-terms".into()));
    }

    /// Every path into the tree of `text`, with the range the tree gives its value.
    fn paths(node: &Node, path: &str, out: &mut Vec<(String, usize, usize)>) {
        out.push((path.to_owned(), node.start, node.end));
        let dot = if path.is_empty() { "" } else { "." };
        match &node.kind {
            Kind::Struct(_, fields) => {
                for (key, value) in fields {
                    paths(value, &format!("{path}{dot}{}", key.name), out);
                }
            }
            Kind::List(items) | Kind::Tuple(None, items) => {
                for (i, item) in items.iter().enumerate() {
                    paths(item, &format!("{path}[{i}]"), out);
                }
            }
            _ => {}
        }
    }

    #[test]
    fn locate_and_the_tree_agree_on_every_value() {
        // One grammar: the locator's range for every path equals the tree's.
        let text = "Pipeline(\n  stages: [\n    (tool: \"a\", args: [\"x\", r\"y\"], n: -1.5e-3),\n    \
                    // a comment, with ) and ]\n    (tool: 'b', params: (1, (2, [3])), flag: true),\n  ],\n  \
                    sweeps: [],\n)";
        let root = parse("p.ron", text, "pipeline").unwrap();
        let mut all = Vec::new();
        paths(&root, "", &mut all);
        assert!(all.len() > 15, "{all:?}");
        for (path, start, end) in all.into_iter().skip(1) {
            assert_eq!(locate(text, &path), (start, end), "{path}");
        }
    }
}
