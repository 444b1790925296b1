//! glTF 2.0 and GLB through the `gltf` crate (JSON, GLB container and validation), with
//! buffers loaded and accessors read here, every range checked before it is touched.

use std::path::{Component, Path, PathBuf};

use base64::Engine as _;
use gltf::mesh::Mode;

use super::{EmbeddedImage, Location, MaterialUse, Mesh, Origin, Triangle, json_path};
use crate::ParseError;

mod geometry;
mod texcoord;

type Matrix = [[f64; 4]; 4]; // column-major, m[column][row], as glTF stores it

const IDENTITY: Matrix = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// Deeper node hierarchies are refused: a cycle (invalid glTF) would otherwise recurse
/// forever.
const MAX_DEPTH: usize = 256;

/// Checks that a URI or `mtllib` names a local file relative to the model's directory, and
/// returns it as a path. `%XX` escapes are decoded.
///
/// # Errors
/// A scheme (`http:`, `file:`), an absolute path, or a `..` that climbs out of the model's
/// directory, in words.
pub(crate) fn local_relative_path(uri: &str) -> Result<PathBuf, String> {
    let has_scheme = uri.split_once(':').is_some_and(|(s, _)| {
        !s.is_empty()
            && s.chars()
                .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
    });
    if has_scheme || uri.starts_with("//") {
        return Err(format!(
            "`{uri}` is not a local relative file; irsig never fetches from the network or from absolute URIs"
        ));
    }
    let decoded = percent_decode(uri).ok_or_else(|| format!("`{uri}` has a malformed %-escape"))?;
    let path = PathBuf::from(decoded);
    for c in path.components() {
        match c {
            Component::Normal(_) | Component::CurDir => {}
            Component::ParentDir => {
                return Err(format!(
                    "`{uri}` climbs out of the model's directory with `..`, which irsig refuses"
                ));
            }
            Component::RootDir | Component::Prefix(_) => {
                return Err(format!(
                    "`{uri}` is an absolute path; expected a relative one"
                ));
            }
        }
    }
    Ok(path)
}

fn percent_decode(s: &str) -> Option<String> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = std::str::from_utf8(b.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// Where a GLB's JSON chunk starts: after the 12-byte header and the chunk's 8-byte header.
const GLB_JSON_START: usize = 20;

/// The glTF's JSON as it lies in the file, to point errors at the text of a JSON path: a
/// `.gltf` error at its line and column, a GLB error at its byte offset.
struct Source<'a> {
    file: &'a str,
    /// The JSON text: the whole `.gltf`, or a GLB's JSON chunk (`None` when it is not
    /// UTF-8 or the GLB is too short to hold it).
    json: Option<&'a str>,
    glb: bool,
}

impl<'a> Source<'a> {
    fn new(file: &'a str, bytes: &'a [u8]) -> Self {
        let glb = bytes.starts_with(b"glTF");
        let json = if glb {
            bytes
                .get(12..16)
                .and_then(|b| <[u8; 4]>::try_from(b).ok())
                .map(|b| u32::from_le_bytes(b) as usize)
                .and_then(|n| bytes.get(GLB_JSON_START..GLB_JSON_START.checked_add(n)?))
        } else {
            Some(bytes)
        };
        Self {
            file,
            json: json.and_then(|b| std::str::from_utf8(b).ok()),
            glb,
        }
    }

    /// The byte offset and length in the file of `path`'s text (of the deepest part of it
    /// present), with `tree` the parsed JSON when the caller has it.
    fn span(&self, path: &str, tree: Option<&json_path::Tree<'_>>) -> Option<(usize, usize)> {
        let (start, end) = match tree {
            Some(t) => t.locate(path),
            None => json_path::Tree::parse(self.json?)?.locate(path),
        };
        let shift = if self.glb { GLB_JSON_START } else { 0 };
        Some((start + shift, end - start))
    }

    /// An error at `path`, said as `path: message`.
    fn error(&self, path: &str, message: impl std::fmt::Display) -> ParseError {
        let message = format!("{path}: {message}");
        match (self.json, self.span(path, None)) {
            (Some(text), Some((at, len))) if !self.glb => {
                ParseError::at_span(self.file, text, at, len, message)
            }
            (_, Some((at, _))) => ParseError::in_binary(self.file, at, message),
            _ => ParseError::in_binary(self.file, 0, message),
        }
    }

    /// The line and column of `path`, as [`Source::error`] gives them.
    fn line_column(&self, path: &str, tree: Option<&json_path::Tree<'_>>) -> (usize, usize) {
        match (self.json, self.span(path, tree)) {
            (Some(text), Some((at, _))) if !self.glb => crate::error::line_column(text, at),
            (_, Some((at, _))) => (1, at + 1),
            _ => (1, 1),
        }
    }

    /// A JSON syntax or type error, at the line and column `serde_json` gives.
    fn syntax_error(&self, bytes: &[u8], j: &gltf::json::Error) -> ParseError {
        let msg = format!("malformed glTF JSON: {j}");
        // serde_json counts columns in bytes.
        let offset_in = |text: &[u8]| {
            text.split_inclusive(|&b| b == b'\n')
                .take(j.line().saturating_sub(1))
                .map(<[u8]>::len)
                .sum::<usize>()
                + j.column().saturating_sub(1)
        };
        match (self.glb, self.json) {
            (false, Some(text)) => {
                ParseError::at_offset(self.file, text, offset_in(text.as_bytes()), msg)
            }
            (true, _) => {
                let chunk = bytes.get(GLB_JSON_START..).unwrap_or_default();
                ParseError::in_binary(
                    self.file,
                    GLB_JSON_START + offset_in(chunk).min(chunk.len()),
                    format!("{msg} (in the GLB's JSON chunk)"),
                )
            }
            (false, None) => {
                let (text, valid) = match std::str::from_utf8(bytes) {
                    Ok(t) => (t, t.len()),
                    Err(e) => (
                        std::str::from_utf8(&bytes[..e.valid_up_to()]).unwrap_or_default(),
                        e.valid_up_to(),
                    ),
                };
                ParseError::at_offset(
                    self.file,
                    text,
                    valid,
                    "expected UTF-8 JSON text, found a byte that is not",
                )
            }
        }
    }
}

/// Reads a glTF (JSON) or GLB file. `base_dir` is where external buffers are looked for
/// (`None` for standard input, where only GLB and `data:` buffers work). Positions are in
/// the file's axes (+Y up): [`Mesh::y_up_to_z_up`] turns them into irsig's.
///
/// Errors name the JSON path of what is wrong (`meshes[0].primitives[1].indices`), at
/// its line and column in a `.gltf`, at its byte offset in a GLB (line 1, column offset
/// + 1), and keep `serde_json`'s line and column for a syntax error.
///
/// # Errors
/// Malformed JSON, a malformed GLB container or one whose stated length is not the file's,
/// a glTF that fails validation or is not version 2, a buffer URI that is not local and
/// relative (or a symbolic link that leads out of the model's directory), a buffer whose
/// bytes are not its `byteLength`, a buffer view or accessor that runs past its buffer,
/// non-finite positions, an index past the vertices, a triangle list whose index count
/// is not a multiple of 3, or no triangles at all.
pub fn read_gltf(file: &str, bytes: &[u8], base_dir: Option<&Path>) -> Result<Mesh, ParseError> {
    let source = Source::new(file, bytes);
    if bytes.starts_with(b"glTF") {
        check_glb_container(file, bytes)?;
    }
    let doc = read_document(&source, file, bytes)?;
    check_version(&source, &doc.as_json().asset)?;
    let buffers = load_buffers(&source, &doc, base_dir)?;
    check_views(&source, &doc)?;

    let mut reader = Walk {
        source: &source,
        base_dir,
        buffers: &buffers,
        mesh: Mesh {
            file: file.to_owned(),
            ..Mesh::default()
        },
        material_index: std::collections::HashMap::new(),
        embedded: std::collections::HashMap::new(),
        primitive_paths: Vec::new(),
    };
    for node in root_nodes(&doc) {
        reader.node(&node, &IDENTITY, 0)?;
    }
    if reader.mesh.triangles.is_empty() {
        return Err(source.error(
            "meshes",
            "expected at least one triangle primitive in the scene, found none (empty mesh)",
        ));
    }
    let Walk {
        mut mesh,
        primitive_paths,
        ..
    } = reader;
    place_parts(&source, &mut mesh, &primitive_paths);
    Ok(mesh)
}

/// The glTF document of `bytes`, parsed and validated, its errors at their place.
fn read_document(source: &Source<'_>, file: &str, bytes: &[u8]) -> Result<gltf::Gltf, ParseError> {
    parse_and_validate(bytes).map_err(|e| match e {
        gltf::Error::Deserialize(j) => source.syntax_error(bytes, &j),
        gltf::Error::Binary(b) => {
            ParseError::in_binary(file, 0, format!("malformed GLB container: {b}"))
        }
        gltf::Error::Validation(v) => {
            let (path, first) = v.first().map_or_else(
                || (String::new(), String::new()),
                |(p, err)| (p.as_str().to_owned(), err.to_string()),
            );
            let more = match v.len() {
                0 | 1 => String::new(),
                n => format!(" (and {} more problems)", n - 1),
            };
            source.error(&path, format!("invalid glTF: {first}{more}"))
        }
        other => ParseError::in_binary(file, 0, format!("cannot read glTF: {other}")),
    })
}

/// Checks that the asset is glTF 2.x and needs no more than 2.0.
fn check_version(source: &Source<'_>, asset: &gltf::json::Asset) -> Result<(), ParseError> {
    if !is_version_2(&asset.version) {
        return Err(source.error(
            "asset.version",
            format!(
                "expected glTF version \"2.x\", found \"{}\" (glTF 1.0 is a different format)",
                asset.version
            ),
        ));
    }
    if let Some(min) = asset.min_version.as_deref().filter(|&m| m != "2.0") {
        return Err(source.error(
            "asset.minVersion",
            format!("the file needs glTF \"{min}\"; irsig reads \"2.0\""),
        ));
    }
    Ok(())
}

/// Every buffer's bytes (the GLB's BIN chunk, a `data:` URI or a file next to the model),
/// each checked to be its `byteLength`.
fn load_buffers(
    source: &Source<'_>,
    doc: &gltf::Gltf,
    base_dir: Option<&Path>,
) -> Result<Vec<Vec<u8>>, ParseError> {
    let mut buffers: Vec<Vec<u8>> = Vec::new();
    for buffer in doc.buffers() {
        let i = buffer.index();
        let declared = buffer.length();
        let (mut data, slack) = match buffer.source() {
            gltf::buffer::Source::Bin => (
                doc.blob.clone().ok_or_else(|| {
                    source.error(
                        &format!("buffers[{i}]"),
                        "refers to the GLB BIN chunk, but there is none",
                    )
                })?,
                // The BIN chunk is padded to four bytes (glTF 2.0 §4.4.3.3).
                3,
            ),
            gltf::buffer::Source::Uri(uri) => (load_uri(source, uri, base_dir, i)?, 0),
        };
        if data.len() < declared || data.len() > declared.saturating_add(slack) {
            return Err(source.error(
                &format!("buffers[{i}].byteLength"),
                format!(
                    "the buffer declares {declared} bytes, but its data has {}",
                    data.len()
                ),
            ));
        }
        data.truncate(declared);
        buffers.push(data);
    }
    Ok(buffers)
}

/// Checks that every buffer view lies within its buffer.
fn check_views(source: &Source<'_>, doc: &gltf::Gltf) -> Result<(), ParseError> {
    for view in doc.views() {
        let buffer = view.buffer();
        if view
            .offset()
            .checked_add(view.length())
            .is_none_or(|end| end > buffer.length())
        {
            return Err(source.error(
                &format!("bufferViews[{}].byteLength", view.index()),
                format!(
                    "{} bytes from byte {} run past the {} bytes of buffers[{}]",
                    view.length(),
                    view.offset(),
                    buffer.length(),
                    buffer.index()
                ),
            ));
        }
    }
    Ok(())
}

/// The nodes the mesh is read from: the default scene's (else the first scene's), or,
/// without a scene, every node that is no other's child.
fn root_nodes(doc: &gltf::Gltf) -> Vec<gltf::Node<'_>> {
    match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => {
            let mut is_child = vec![false; doc.nodes().len()];
            for n in doc.nodes() {
                for c in n.children() {
                    if let Some(flag) = is_child.get_mut(c.index()) {
                        *flag = true;
                    }
                }
            }
            doc.nodes()
                .filter(|n| !is_child.get(n.index()).copied().unwrap_or(false))
                .collect()
        }
    }
}

/// Sets where each primitive's triangles (`primitive_paths`, one per part) and each
/// material's first use are, for the importer's messages.
fn place_parts(source: &Source<'_>, mesh: &mut Mesh, primitive_paths: &[String]) {
    // The JSON is parsed again once for all of them.
    let tree = source.json.and_then(json_path::Tree::parse);
    let places: Vec<(usize, usize)> = primitive_paths
        .iter()
        .map(|p| source.line_column(p, tree.as_ref()))
        .collect();
    for origin in &mut mesh.origins {
        if let Some(&(line, column)) = origin.part.and_then(|p| places.get(p as usize)) {
            origin.line = u32::try_from(line).unwrap_or(u32::MAX);
            origin.column = u32::try_from(column).unwrap_or(u32::MAX);
        }
    }
    for m in &mut mesh.materials {
        if let Some(&(line, column)) = mesh
            .parts
            .iter()
            .position(|p| Some(p) == m.first_use.part.as_ref())
            .and_then(|p| places.get(p))
        {
            m.first_use.line = Some(line);
            m.first_use.column = Some(column);
        }
    }
}

/// A GLB's header and chunk headers (glTF 2.0 §4.4), each checked at its byte offset
/// before gltf reads them: gltf 1.4 subtracts the 12-byte header from the stated length
/// unchecked (an overflow panic when it is smaller), reads a file longer than stated as if
/// it ended there, and reports container errors with no offset.
fn check_glb_container(file: &str, bytes: &[u8]) -> Result<(), ParseError> {
    let at = |offset: usize, msg: String| ParseError::in_binary(file, offset, msg);
    let u32_at = |offset: usize| {
        bytes
            .get(offset..offset.checked_add(4)?)
            .and_then(|b| <[u8; 4]>::try_from(b).ok())
            .map(|b| u32::from_le_bytes(b) as usize)
    };
    let len = bytes.len();
    let (Some(version), Some(declared)) = (u32_at(4), u32_at(8)) else {
        return Err(at(
            len,
            format!("expected the 12-byte GLB header, found the end of the file after {len} bytes"),
        ));
    };
    if declared < 12 {
        return Err(at(
            8,
            format!(
                "malformed GLB header: declared length {declared} bytes, expected at least the \
                 12-byte header"
            ),
        ));
    }
    if version != 2 {
        return Err(at(
            4,
            format!("expected GLB container version 2, found {version}"),
        ));
    }
    if declared != len {
        return Err(at(
            8,
            format!("the GLB header states a length of {declared} bytes, but the file has {len}"),
        ));
    }
    let Some(json_len) = u32_at(12).filter(|_| len >= GLB_JSON_START) else {
        return Err(at(
            12,
            "expected the JSON chunk's 8-byte header after the GLB header, found the end of the \
             file"
                .into(),
        ));
    };
    if &bytes[16..20] != b"JSON" {
        return Err(at(
            16,
            format!(
                "expected the first chunk to be of type `JSON`, found {:?}",
                String::from_utf8_lossy(&bytes[16..20])
            ),
        ));
    }
    let json_end = GLB_JSON_START.saturating_add(json_len);
    if json_end > len {
        return Err(at(
            12,
            format!(
                "the JSON chunk states {json_len} bytes, but {} follow its header",
                len - GLB_JSON_START
            ),
        ));
    }
    if json_end < len {
        let Some(bin_len) = u32_at(json_end).filter(|_| len - json_end >= 8) else {
            return Err(at(
                json_end,
                format!(
                    "expected an 8-byte chunk header after the JSON chunk, found {} bytes",
                    len - json_end
                ),
            ));
        };
        let ty = &bytes[json_end + 4..json_end + 8];
        if ty != b"BIN\0" {
            return Err(at(
                json_end + 4,
                format!(
                    "expected the second chunk to be of type `BIN`, found {:?}",
                    String::from_utf8_lossy(ty)
                ),
            ));
        }
        if bin_len > len - json_end - 8 {
            return Err(at(
                json_end,
                format!(
                    "the BIN chunk states {bin_len} bytes, but {} follow its header",
                    len - json_end - 8
                ),
            ));
        }
    }
    Ok(())
}

/// Whether a glTF `asset.version` is 2.x (`major.minor`, both digits).
fn is_version_2(version: &str) -> bool {
    version
        .strip_prefix("2.")
        .is_some_and(|minor| !minor.is_empty() && minor.bytes().all(|b| b.is_ascii_digit()))
}

/// `dir/rel`, for a reference `rel` that [`local_relative_path`] accepted, once every
/// symbolic link on the way is followed: it must still lie inside `dir`, so that a link in
/// the model's directory that leads out of it is refused as `..` is. A file that does not
/// exist is returned as joined, for the caller's read to report.
///
/// # Errors
/// The reference leads out of `dir`, in words.
pub(crate) fn inside(dir: &Path, rel: &Path, uri: &str) -> Result<PathBuf, String> {
    let full = dir.join(rel);
    let (Ok(real_dir), Ok(real)) = (dir.canonicalize(), full.canonicalize()) else {
        return Ok(full);
    };
    if real.starts_with(&real_dir) {
        Ok(full)
    } else {
        Err(format!(
            "`{uri}` leads out of the model's directory through a symbolic link (to {}), which \
             irsig refuses as it refuses `..`",
            real.display()
        ))
    }
}

/// A `data:` URI's media type and bytes, from what follows `data:`; only base64 is read.
pub(super) fn decode_data_uri(rest: &str) -> Result<(&str, Vec<u8>), String> {
    let (media_type, payload) = rest
        .split_once(";base64,")
        .ok_or_else(|| "a `data:` URI must be base64 (`data:...;base64,...`)".to_owned())?;
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(payload)
        .map_err(|e| format!("malformed base64 in its `data:` URI: {e}"))?;
    Ok((media_type, bytes))
}

fn load_uri(
    source: &Source<'_>,
    uri: &str,
    base_dir: Option<&Path>,
    index: usize,
) -> Result<Vec<u8>, ParseError> {
    let path = format!("buffers[{index}].uri");
    let err = |msg: String| source.error(&path, msg);
    if let Some(rest) = uri.strip_prefix("data:") {
        // Embedded data travels inside the file: allowed, it is not a network access.
        return decode_data_uri(rest).map(|(_, bytes)| bytes).map_err(err);
    }
    let rel = local_relative_path(uri).map_err(err)?;
    let dir = base_dir.ok_or_else(|| {
        err(format!(
            "external file `{uri}` cannot be found for a glTF read from standard input; give the file's path instead"
        ))
    })?;
    let full = inside(dir, &rel, uri).map_err(err)?;
    crate::file::read_file(&full).map_err(|e| err(format!("cannot read `{}`: {e}", full.display())))
}

struct Walk<'a> {
    source: &'a Source<'a>,
    /// Where the model's file is, for the images its materials name (`None`: standard
    /// input).
    base_dir: Option<&'a Path>,
    buffers: &'a [Vec<u8>],
    mesh: Mesh,
    material_index: std::collections::HashMap<Option<usize>, Option<u32>>,
    /// Each image read from inside the file, by image index: read and decoded once, and
    /// materials that share it share one copy of its bytes.
    embedded: std::collections::HashMap<usize, EmbeddedImage>,
    /// The JSON path of each of `mesh.parts`.
    primitive_paths: Vec<String>,
}

fn multiply(a: &Matrix, b: &Matrix) -> Matrix {
    let mut m = [[0.0; 4]; 4];
    for (c, col) in m.iter_mut().enumerate() {
        for (r, v) in col.iter_mut().enumerate() {
            *v = (0..4).map(|k| a[k][r] * b[c][k]).sum();
        }
    }
    m
}

fn determinant3(m: &Matrix) -> f64 {
    let (a, b, c) = (m[0], m[1], m[2]);
    a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1])
        + c[0] * (a[1] * b[2] - a[2] * b[1])
}

fn label(kind: &str, index: usize, name: Option<&str>) -> String {
    match name {
        Some(n) => format!("{kind} {index} \"{n}\""),
        None => format!("{kind} {index}"),
    }
}

impl Walk<'_> {
    /// An error at JSON `path`, in `part` (the node, mesh and primitive being read).
    fn err(&self, path: &str, part: &str, msg: impl std::fmt::Display) -> ParseError {
        self.source.error(path, format!("{msg} (reading {part})"))
    }

    fn node(
        &mut self,
        node: &gltf::Node<'_>,
        parent: &Matrix,
        depth: usize,
    ) -> Result<(), ParseError> {
        let node_label = label("node", node.index(), node.name());
        if depth > MAX_DEPTH {
            return Err(self.err(
                &format!("nodes[{}].children", node.index()),
                &node_label,
                format!("the node hierarchy is deeper than {MAX_DEPTH} levels (a cycle?)"),
            ));
        }
        let local = node.transform().matrix().map(|c| c.map(f64::from));
        let world = multiply(parent, &local);
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                let part = format!(
                    "{node_label}, {}, primitive {}",
                    label("mesh", mesh.index(), mesh.name()),
                    primitive.index()
                );
                let path = format!("meshes[{}].primitives[{}]", mesh.index(), primitive.index());
                self.primitive(&primitive, &world, part, path)?;
            }
        }
        for child in node.children() {
            self.node(&child, &world, depth + 1)?;
        }
        Ok(())
    }

    /// The bytes of an accessor's view from its first element on, and its stride, after
    /// checking every range against the loaded buffer.
    fn accessor_data(
        &self,
        accessor: &gltf::Accessor<'_>,
        element_len: usize,
        part: &str,
    ) -> Result<(&[u8], usize), ParseError> {
        let at = format!("accessors[{}]", accessor.index());
        if accessor.sparse().is_some() {
            return Err(self.err(
                &format!("{at}.sparse"),
                part,
                "a sparse accessor, which irsig does not read",
            ));
        }
        let view = accessor.view().ok_or_else(|| {
            self.err(
                &at,
                part,
                "expected a `bufferView`, found none (irsig does not read all-zero accessors)",
            )
        })?;
        let view_at = format!("bufferViews[{}]", view.index());
        let buffer = self.buffers.get(view.buffer().index()).ok_or_else(|| {
            self.err(
                &format!("{view_at}.buffer"),
                part,
                "the buffer does not exist",
            )
        })?;
        let view_end = view
            .offset()
            .checked_add(view.length())
            .filter(|&e| e <= buffer.len())
            .ok_or_else(|| self.err(&view_at, part, "the view runs past its buffer"))?;
        let view_bytes = &buffer[view.offset()..view_end];
        let stride = view.stride().unwrap_or(element_len);
        if stride < element_len {
            return Err(self.err(
                &format!("{view_at}.byteStride"),
                part,
                format!(
                    "byte stride {stride} is shorter than an element of {at} ({element_len} bytes)"
                ),
            ));
        }
        let count = accessor.count();
        let end = count
            .checked_sub(1)
            .and_then(|n| n.checked_mul(stride))
            .and_then(|n| n.checked_add(element_len))
            .and_then(|n| n.checked_add(accessor.offset()));
        match end {
            _ if count == 0 => Ok((&[], stride)),
            Some(end) if end <= view_bytes.len() => {
                Ok((&view_bytes[accessor.offset()..end], stride))
            }
            _ => Err(self.err(
                &format!("{at}.count"),
                part,
                format!(
                    "{count} elements from byte {} run past {view_at} ({} bytes)",
                    accessor.offset(),
                    view_bytes.len()
                ),
            )),
        }
    }

    fn material(
        &mut self,
        primitive: &gltf::Primitive<'_>,
        part: &str,
    ) -> Result<Option<u32>, ParseError> {
        let m = primitive.material();
        let key = m.index();
        if let Some(&id) = self.material_index.get(&key) {
            return Ok(id);
        }
        let id = match key {
            None => None,
            Some(i) => {
                let name = m
                    .name()
                    .map_or_else(|| format!("material {i}"), str::to_owned);
                let image = self.base_color_image(&m, self.base_dir)?;
                let embedded_image = self.base_color_embedded(&m)?;
                let id = u32::try_from(self.mesh.materials.len()).unwrap_or(u32::MAX);
                self.mesh.materials.push(MaterialUse {
                    name,
                    id: None,
                    first_use: Location {
                        file: self.source.file.to_owned(),
                        line: None,
                        column: None,
                        part: Some(part.to_owned()),
                    },
                    image,
                    embedded_image,
                });
                Some(id)
            }
        };
        self.material_index.insert(key, id);
        Ok(id)
    }

    /// Reads one primitive of a node's mesh (`world`: the node's transform) into the mesh:
    /// its positions, its triangles, their material and texture coordinates; a primitive
    /// without triangles (points, lines) is skipped with a warning.
    fn primitive(
        &mut self,
        primitive: &gltf::Primitive<'_>,
        world: &Matrix,
        part: String,
        path: String,
    ) -> Result<(), ParseError> {
        let mode = primitive.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            self.mesh.warnings.push(format!(
                "{}: skipped {part}: mode {mode:?} has no triangles",
                self.source.file
            ));
            return Ok(());
        }
        let (pos_at, new_positions) = self.positions(primitive, world, &part, &path)?;
        let base = self.mesh.positions.len();
        let vertex_count = new_positions.len();
        let indices_at = format!("{path}.indices");
        let indices = self.indices(primitive, mode, &pos_at, vertex_count, &indices_at, &part)?;
        let corners = geometry::corners(mode, &indices, world);
        let offset =
            u32::try_from(base).map_err(|_| self.err(&pos_at, &part, "more than 2^32 vertices"))?;
        let material = self.material(primitive, &part)?;
        let texcoords = self.texcoords(primitive, vertex_count, &part)?;
        let first_triangle = u32::try_from(self.mesh.triangles.len())
            .map_err(|_| self.err(&indices_at, &part, "more than 2^32 triangles"))?;
        self.mesh.parts.push(part);
        self.primitive_paths.push(path);
        self.mesh.origins.push(Origin {
            first_triangle,
            line: 0,
            column: 0,
            part: u32::try_from(self.mesh.parts.len() - 1).ok(),
            lines_follow: false,
        });
        self.mesh.positions.extend(new_positions);
        self.mesh.triangles.extend(corners.into_iter().map(|c| {
            Triangle {
                uv: texcoords
                    .as_ref()
                    .map(|t| c.map(|v| t.get(v as usize).copied().unwrap_or_default())),
                vertices: c.map(|v| v + offset),
                material,
                temperature_k: None,
            }
        }));
        Ok(())
    }
}

/// `gltf::Gltf::from_slice`, except that a primitive's `POSITION` accessor index is checked
/// before gltf's own validation runs: gltf-json 1.4.1 indexes the accessor list with it
/// unchecked (mesh.rs `primitive_validate_hook`) and panics when it is out of range (found
/// by the `gltf` fuzz target). The index is reported the way gltf reports every other bad
/// index.
fn parse_and_validate(bytes: &[u8]) -> Result<gltf::Gltf, gltf::Error> {
    use gltf::json::{Path, mesh::Semantic, validation::Checked, validation::Error};
    let gltf::Gltf { document, blob } = gltf::Gltf::from_slice_without_validation(bytes)?;
    let json = document.into_json();
    let accessors = json.accessors.len();
    let mut bad = Vec::new();
    for (i, mesh) in json.meshes.iter().enumerate() {
        for (j, primitive) in mesh.primitives.iter().enumerate() {
            if let Some(index) = primitive
                .attributes
                .get(&Checked::Valid(Semantic::Positions))
                && index.value() >= accessors
            {
                bad.push((
                    Path::new()
                        .field("meshes")
                        .index(i)
                        .field("primitives")
                        .index(j)
                        .field("attributes")
                        .key("POSITION"),
                    Error::IndexOutOfBounds,
                ));
            }
        }
    }
    if !bad.is_empty() {
        return Err(gltf::Error::Validation(bad));
    }
    Ok(gltf::Gltf {
        document: gltf::Document::from_json(json)?,
        blob,
    })
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // small integers, exact in f64
mod tests {
    use super::*;

    #[test]
    fn uris_must_be_local_and_relative() {
        assert!(local_relative_path("mesh.bin").is_ok());
        assert_eq!(
            local_relative_path("a%20b.bin").unwrap(),
            PathBuf::from("a b.bin")
        );
        for bad in [
            "http://x/y.bin",
            "https://x",
            "file:///etc/passwd",
            "/etc/passwd",
            "../up.bin",
            "a/../../b",
            "//host/x",
        ] {
            assert!(local_relative_path(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn matrices_multiply_column_major() {
        let t = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [5.0, 0.0, 0.0, 1.0],
        ];
        let s = [
            [2.0, 0.0, 0.0, 0.0],
            [0.0, 2.0, 0.0, 0.0],
            [0.0, 0.0, 2.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        // T·S applies S first: the translation stays 5, the diagonal 2.
        let m = multiply(&t, &s);
        assert_eq!(m[3][0], 5.0);
        assert_eq!(m[0][0], 2.0);
        let m = multiply(&s, &t);
        assert_eq!(m[3][0], 10.0);
        assert_eq!(determinant3(&s), 8.0);
    }
}
