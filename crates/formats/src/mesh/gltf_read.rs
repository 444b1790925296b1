//! glTF 2.0 and GLB through the `gltf` crate (JSON, GLB container and validation), with
//! buffers loaded and accessors read here, every range checked before it is touched.

use std::path::{Component, Path, PathBuf};

use base64::Engine as _;
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;

use super::{Location, MaterialUse, Mesh, Origin, Triangle};
use crate::ParseError;

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

/// Reads a glTF (JSON) or GLB file. `base_dir` is where external buffers are looked for
/// (`None` for standard input, where only GLB and `data:` buffers work).
///
/// # Errors
/// Malformed JSON (at its line and column for `.gltf` text), a malformed GLB container, a
/// glTF that fails validation, a buffer URI that is not local and relative, a missing or
/// short buffer, an accessor that runs past its buffer, non-finite positions, an index past
/// the vertices, or no triangles at all.
pub fn read_gltf(file: &str, bytes: &[u8], base_dir: Option<&Path>) -> Result<Mesh, ParseError> {
    let bin_err = |msg: String| ParseError::in_binary(file, 0, msg);
    // gltf 1.4 subtracts the 12-byte header from the declared length unchecked (an
    // arithmetic overflow panic when it is smaller); check it first.
    if let Some(declared) = bytes
        .strip_prefix(b"glTF")
        .and_then(|rest| rest.get(4..8))
        .and_then(|b| <[u8; 4]>::try_from(b).ok())
        .map(u32::from_le_bytes)
        && declared < 12
    {
        return Err(ParseError::in_binary(
            file,
            8,
            format!(
                "malformed GLB header: declared length {declared} bytes, expected at least the \
                 12-byte header"
            ),
        ));
    }
    let doc = parse_and_validate(bytes).map_err(|e| match e {
        gltf::Error::Deserialize(j) => {
            let msg = format!("malformed glTF JSON: {j}");
            match std::str::from_utf8(bytes) {
                Ok(text) if !bytes.starts_with(b"glTF") => {
                    let (line, col) = (j.line(), j.column());
                    let offset = text
                        .split_inclusive('\n')
                        .take(line.saturating_sub(1))
                        .map(str::len)
                        .sum::<usize>()
                        + col.saturating_sub(1);
                    ParseError::at_offset(file, text, offset, msg)
                }
                _ => bin_err(format!("{msg} (in the GLB's JSON chunk)")),
            }
        }
        gltf::Error::Binary(b) => bin_err(format!("malformed GLB container: {b}")),
        gltf::Error::Validation(v) => {
            let first: Vec<String> = v
                .iter()
                .take(3)
                .map(|(path, err)| format!("{}: {err}", path.as_str()))
                .collect();
            bin_err(format!(
                "invalid glTF ({} problems): {}",
                v.len(),
                first.join("; ")
            ))
        }
        other => bin_err(format!("cannot read glTF: {other}")),
    })?;

    let mut buffers: Vec<Vec<u8>> = Vec::new();
    for buffer in doc.buffers() {
        let i = buffer.index();
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => doc.blob.clone().ok_or_else(|| {
                bin_err(format!(
                    "buffer {i} refers to the GLB BIN chunk, but there is none"
                ))
            })?,
            gltf::buffer::Source::Uri(uri) => load_uri(file, uri, base_dir, i)?,
        };
        if data.len() < buffer.length() {
            return Err(bin_err(format!(
                "buffer {i} declares {} bytes but holds {}",
                buffer.length(),
                data.len()
            )));
        }
        buffers.push(data);
    }

    let mut reader = Walk {
        file,
        buffers: &buffers,
        mesh: Mesh {
            file: file.to_owned(),
            ..Mesh::default()
        },
        material_index: std::collections::HashMap::new(),
    };
    let roots: Vec<gltf::Node<'_>> = match doc.default_scene().or_else(|| doc.scenes().next()) {
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
    };
    for node in roots {
        reader.node(&node, &IDENTITY, 0)?;
    }
    if reader.mesh.triangles.is_empty() {
        return Err(bin_err(
            "expected at least one triangle primitive in the scene, found none (empty mesh)".into(),
        ));
    }
    Ok(reader.mesh)
}

fn load_uri(
    file: &str,
    uri: &str,
    base_dir: Option<&Path>,
    index: usize,
) -> Result<Vec<u8>, ParseError> {
    let err = |msg: String| ParseError::in_binary(file, 0, format!("buffer {index}: {msg}"));
    if let Some(rest) = uri.strip_prefix("data:") {
        // Embedded data travels inside the file: allowed, it is not a network access.
        let (_, payload) = rest
            .split_once(";base64,")
            .ok_or_else(|| err("a `data:` URI must be base64 (`data:...;base64,...`)".into()))?;
        return base64::engine::general_purpose::STANDARD
            .decode(payload)
            .map_err(|e| err(format!("malformed base64 in its `data:` URI: {e}")));
    }
    let path = local_relative_path(uri).map_err(err)?;
    let dir = base_dir.ok_or_else(|| {
        err(format!(
            "external file `{uri}` cannot be found for a glTF read from standard input; give the file's path instead"
        ))
    })?;
    let full = dir.join(path);
    crate::file::read_file(&full).map_err(|e| err(format!("cannot read `{}`: {e}", full.display())))
}

struct Walk<'a> {
    file: &'a str,
    buffers: &'a [Vec<u8>],
    mesh: Mesh,
    material_index: std::collections::HashMap<Option<usize>, Option<u32>>,
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
    fn err(&self, part: &str, msg: String) -> ParseError {
        ParseError::in_binary(self.file, 0, format!("{part}: {msg}"))
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
                self.primitive(&primitive, &world, part)?;
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
        let what = format!("accessor {}", accessor.index());
        if accessor.sparse().is_some() {
            return Err(self.err(part, format!("{what} is sparse, which irsig does not read")));
        }
        let view = accessor
            .view()
            .ok_or_else(|| self.err(part, format!("{what} has no buffer view")))?;
        let buffer = self
            .buffers
            .get(view.buffer().index())
            .ok_or_else(|| self.err(part, format!("{what}: its buffer does not exist")))?;
        let view_end = view
            .offset()
            .checked_add(view.length())
            .filter(|&e| e <= buffer.len())
            .ok_or_else(|| {
                self.err(
                    part,
                    format!("{what}: buffer view {} runs past its buffer", view.index()),
                )
            })?;
        let view_bytes = &buffer[view.offset()..view_end];
        let stride = view.stride().unwrap_or(element_len);
        if stride < element_len {
            return Err(self.err(
                part,
                format!(
                    "{what}: byte stride {stride} is shorter than an element ({element_len} bytes)"
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
                part,
                format!(
                    "{what}: {count} elements from byte {} run past buffer view {} ({} bytes)",
                    accessor.offset(),
                    view.index(),
                    view_bytes.len()
                ),
            )),
        }
    }

    fn material(&mut self, primitive: &gltf::Primitive<'_>, part: &str) -> Option<u32> {
        let m = primitive.material();
        let key = m.index();
        if let Some(&id) = self.material_index.get(&key) {
            return id;
        }
        let id = key.map(|i| {
            let name = m
                .name()
                .map_or_else(|| format!("material {i}"), str::to_owned);
            let id = u32::try_from(self.mesh.materials.len()).unwrap_or(u32::MAX);
            self.mesh.materials.push(MaterialUse {
                name,
                id: None,
                first_use: Location {
                    file: self.file.to_owned(),
                    line: None,
                    part: Some(part.to_owned()),
                },
            });
            id
        });
        self.material_index.insert(key, id);
        id
    }

    fn primitive(
        &mut self,
        primitive: &gltf::Primitive<'_>,
        world: &Matrix,
        part: String,
    ) -> Result<(), ParseError> {
        let mode = primitive.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            self.mesh.warnings.push(format!(
                "{}: skipped {part}: mode {mode:?} has no triangles",
                self.file
            ));
            return Ok(());
        }
        let positions = primitive
            .get(&gltf::Semantic::Positions)
            .ok_or_else(|| self.err(&part, "expected a POSITION attribute, found none".into()))?;
        if positions.data_type() != DataType::F32 || positions.dimensions() != Dimensions::Vec3 {
            return Err(self.err(
                &part,
                format!(
                    "expected POSITION as float VEC3, found {:?} {:?}",
                    positions.data_type(),
                    positions.dimensions()
                ),
            ));
        }
        let (data, stride) = self.accessor_data(&positions, 12, &part)?;
        let base = self.mesh.positions.len();
        let vertex_count = positions.count();
        let f32_at = |b: &[u8], at: usize| -> f32 {
            let mut a = [0; 4];
            a.copy_from_slice(&b[at..at + 4]);
            f32::from_le_bytes(a)
        };
        let mut new_positions = Vec::with_capacity(vertex_count);
        for k in 0..vertex_count {
            let p = [
                f64::from(f32_at(data, k * stride)),
                f64::from(f32_at(data, k * stride + 4)),
                f64::from(f32_at(data, k * stride + 8)),
            ];
            let mut w = [0.0; 3];
            for (r, v) in w.iter_mut().enumerate() {
                *v = world[0][r] * p[0] + world[1][r] * p[1] + world[2][r] * p[2] + world[3][r];
            }
            if !w.iter().all(|v| v.is_finite()) {
                return Err(self.err(&part, format!("vertex {k} is not finite: {p:?}")));
            }
            new_positions.push(w);
        }

        let indices: Vec<u32> = match primitive.indices() {
            None => (0..u32::try_from(vertex_count).unwrap_or(u32::MAX)).collect(),
            Some(acc) => {
                let size = match (acc.data_type(), acc.dimensions()) {
                    (DataType::U8, Dimensions::Scalar) => 1,
                    (DataType::U16, Dimensions::Scalar) => 2,
                    (DataType::U32, Dimensions::Scalar) => 4,
                    (t, d) => {
                        return Err(self.err(
                            &part,
                            format!("expected u8, u16 or u32 SCALAR indices, found {t:?} {d:?}"),
                        ));
                    }
                };
                let (data, stride) = self.accessor_data(&acc, size, &part)?;
                (0..acc.count())
                    .map(|k| {
                        let at = k * stride;
                        match size {
                            1 => u32::from(data[at]),
                            2 => u32::from(u16::from_le_bytes([data[at], data[at + 1]])),
                            _ => u32::from_le_bytes([
                                data[at],
                                data[at + 1],
                                data[at + 2],
                                data[at + 3],
                            ]),
                        }
                    })
                    .collect()
            }
        };
        if let Some((k, &i)) = indices
            .iter()
            .enumerate()
            .find(|&(_, &i)| i as usize >= vertex_count)
        {
            return Err(self.err(
                &part,
                format!("index {k} is {i}, past the {vertex_count} vertices"),
            ));
        }
        let mut corners: Vec<[u32; 3]> = match mode {
            Mode::Triangles => indices
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2]])
                .collect(),
            // glTF 2.0 §3.7.2.1: strip triangle k is (k, k+1, k+2), every other one
            // reversed to keep the winding; fan triangle k is (0, k+1, k+2).
            Mode::TriangleStrip => indices
                .windows(3)
                .enumerate()
                .map(|(k, w)| {
                    if k % 2 == 0 {
                        [w[0], w[1], w[2]]
                    } else {
                        [w[1], w[0], w[2]]
                    }
                })
                .collect(),
            _ => match indices.split_first() {
                Some((&hub, rest)) => rest.windows(2).map(|w| [hub, w[0], w[1]]).collect(),
                None => Vec::new(),
            },
        };
        if determinant3(world) < 0.0 {
            // A mirroring transform turns counter-clockwise into clockwise.
            for c in &mut corners {
                c.swap(1, 2);
            }
        }
        let offset =
            u32::try_from(base).map_err(|_| self.err(&part, "more than 2^32 vertices".into()))?;
        let material = self.material(primitive, &part);
        let first_triangle = u32::try_from(self.mesh.triangles.len())
            .map_err(|_| self.err(&part, "more than 2^32 triangles".into()))?;
        self.mesh.parts.push(part);
        self.mesh.origins.push(Origin {
            first_triangle,
            line: 0,
            part: u32::try_from(self.mesh.parts.len() - 1).ok(),
        });
        self.mesh.positions.extend(new_positions);
        self.mesh
            .triangles
            .extend(corners.into_iter().map(|c| Triangle {
                vertices: c.map(|v| v + offset),
                material,
                temperature_k: None,
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
