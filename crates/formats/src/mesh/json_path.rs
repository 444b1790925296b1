//! Where a JSON path lies in a glTF's JSON text, so that an error found in the parsed
//! document (an index count, a buffer length, gltf's own validation) points at the text
//! that holds the value: `meshes[0].primitives[1].indices`, as gltf's validation spells
//! paths (`.field`, `[index]`, `["key"]`, and a trailing ` = "value"` that is ignored).
//!
//! The text is parsed again for this, with `jsonc-parser`, which keeps each value's byte
//! range; it is only done for JSON that `serde_json` has already accepted, so both read
//! the same tree.

use jsonc_parser::ast::Value;
use jsonc_parser::common::Ranged as _;

/// One step of a path.
#[derive(Debug, PartialEq, Eq)]
enum Step<'a> {
    Field(&'a str),
    Index(usize),
}

fn steps(path: &str) -> Vec<Step<'_>> {
    let path = path.split_once(" = ").map_or(path, |(p, _)| p);
    let mut out = Vec::new();
    let mut rest = path;
    while !rest.is_empty() {
        if let Some(r) = rest.strip_prefix("[\"") {
            let end = r.find("\"]").unwrap_or(r.len());
            out.push(Step::Field(&r[..end]));
            rest = r.get(end + 2..).unwrap_or("");
        } else if let Some(r) = rest.strip_prefix('[') {
            let end = r.find(']').unwrap_or(r.len());
            match r[..end].parse() {
                Ok(i) => out.push(Step::Index(i)),
                Err(_) => break,
            }
            rest = r.get(end + 1..).unwrap_or("");
        } else {
            let r = rest.strip_prefix('.').unwrap_or(rest);
            let end = r.find(['.', '[']).unwrap_or(r.len());
            out.push(Step::Field(&r[..end]));
            rest = &r[end..];
        }
    }
    out
}

/// A JSON text parsed with the byte range of every value.
pub(crate) struct Tree<'a>(Value<'a>);

impl<'a> Tree<'a> {
    /// `None` when `text` is not JSON.
    pub(crate) fn parse(text: &'a str) -> Option<Self> {
        jsonc_parser::parse_to_ast(text, &Default::default(), &Default::default())
            .ok()?
            .value
            .map(Self)
    }

    /// The byte range of the deepest part of `path` that the JSON holds: for a field,
    /// from its name to the end of its value; for an array element, the element. A path
    /// none of which is present gives the whole document.
    pub(crate) fn locate(&self, path: &str) -> (usize, usize) {
        let mut value = &self.0;
        let mut range = value.range();
        for step in steps(path) {
            let next = match (step, value) {
                (Step::Field(name), Value::Object(o)) => o.get(name).map(|p| (p.range(), &p.value)),
                (Step::Index(i), Value::Array(a)) => a.elements.get(i).map(|e| (e.range(), e)),
                _ => None,
            };
            let Some((r, v)) = next else { break };
            range = r;
            value = v;
        }
        (range.start, range.end)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_split_as_gltf_spells_them() {
        assert_eq!(
            steps("meshes[0].primitives[12].attributes[\"POSITION\"]"),
            [
                Step::Field("meshes"),
                Step::Index(0),
                Step::Field("primitives"),
                Step::Index(12),
                Step::Field("attributes"),
                Step::Field("POSITION"),
            ]
        );
        assert_eq!(
            steps("asset.version = \"1.0\""),
            [Step::Field("asset"), Step::Field("version")]
        );
        assert!(steps("").is_empty());
    }

    #[test]
    fn the_deepest_present_part_is_found() {
        let text = "{\"meshes\": [{\"primitives\": [{}, {\"indices\": 3}]}]}";
        let tree = Tree::parse(text).unwrap();
        let at = |path: &str| {
            let (s, e) = tree.locate(path);
            &text[s..e]
        };
        assert_eq!(at("meshes[0].primitives[1].indices"), "\"indices\": 3");
        assert_eq!(at("meshes[0].primitives[1]"), "{\"indices\": 3}");
        // Past what is there: the deepest part that is.
        assert_eq!(at("meshes[0].primitives[0].material"), "{}");
        assert_eq!(
            at("meshes[0].primitives[7]"),
            "\"primitives\": [{}, {\"indices\": 3}]"
        );
        assert_eq!(at("accessors[0]"), text);
        assert!(Tree::parse("{").is_none());
    }
}
