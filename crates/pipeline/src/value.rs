//! A RON value tree that remembers where every value and key came from.
//!
//! The `ron` crate is the authority on syntax (the file is first checked with it, so its
//! error messages and positions are the ones users see for a syntax error). This tree exists
//! only so that semantic errors found later (a cycle, a missing input, an unknown parameter)
//! can point at the line and column of the value that caused them; `ron::Value` keeps no
//! positions and forgets the difference between a list and a tuple.

/// A value and the byte range of its text in the source.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Node {
    pub kind: Kind,
    /// Byte offset of the first character.
    pub start: usize,
    /// Byte offset one past the last character.
    pub end: usize,
}

/// A struct field name or map key, with its position.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Key {
    pub name: String,
    pub start: usize,
    pub end: usize,
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Kind {
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
pub(crate) struct SyntaxError {
    pub offset: usize,
    pub message: String,
}

/// Parses one RON document into a located tree.
pub(crate) fn parse(source: &str) -> Result<Node, SyntaxError> {
    let mut p = Parser {
        src: source,
        pos: 0,
    };
    p.skip_trivia()?;
    // `#![enable(...)]` extension attributes at the top.
    while p.rest().starts_with("#!") {
        match p.rest().find(']') {
            Some(i) => p.pos += i + 1,
            None => return Err(p.error("unterminated `#![...]` attribute")),
        }
        p.skip_trivia()?;
    }
    let node = p.value()?;
    p.skip_trivia()?;
    if p.pos < source.len() {
        return Err(p.error("expected the end of the file after the top-level value"));
    }
    Ok(node)
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
            Some('r') if self.rest().starts_with("r\"") || self.rest().starts_with("r#") => {
                Kind::Str(self.raw_string()?)
            }
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
        if self.rest().starts_with("r#") {
            self.pos += 2;
        }
        let rest = self.rest();
        let len = rest
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(rest.len());
        let name = rest[..len].to_owned();
        self.pos += len;
        name
    }

    fn number(&mut self) -> Kind {
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
        Kind::Number(self.src[start..self.pos].to_owned())
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_point_at_the_text_of_each_value() {
        let src =
            "Pipeline(\n  stages: [ (tool: \"cat\", params: {\"n\": 3, \"x\": (1, 2.5e-3)}) ],\n)";
        let root = parse(src).unwrap();
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
        let root = parse(src).unwrap();
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
        assert!(parse("[1] [2]").is_err());
        assert!(parse("[1, ").is_err());
    }
}
