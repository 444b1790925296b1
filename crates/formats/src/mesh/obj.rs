//! Wavefront OBJ through `tobj`, with a first pass of our own over the text for what
//! `tobj` does not keep: the line and column of a bad number, non-finite coordinates,
//! `usemtl` names that no MTL defines, and which line each triangle came from.

use std::collections::HashMap;
use std::io::Read as _;
use std::path::Path;

use super::{Location, MaterialUse, Mesh, Origin, Triangle};
use crate::ParseError;

/// What the first pass learns.
struct Scan {
    materials: Vec<MaterialUse>,
    origins: Vec<Origin>,
    warnings: Vec<String>,
    triangles: usize,
}

/// Reads an OBJ file's text. `base_dir` is where `mtllib` files are looked for (`None`
/// for standard input: MTL files are then not read).
///
/// # Errors
/// Non-UTF-8 text, a malformed or non-finite number, a face that refers to a vertex that
/// does not exist, a malformed MTL file, an `mtllib` path that is not a local relative
/// file, or no triangles at all; at the offending line and column.
pub fn read_obj(file: &str, bytes: &[u8], base_dir: Option<&Path>) -> Result<Mesh, ParseError> {
    let text = crate::canonical::utf8(file, bytes)?;
    let scan = scan(file, text, base_dir)?;
    if scan.triangles == 0 {
        return Err(ParseError::at_offset(
            file,
            text,
            text.len(),
            "expected at least one face with three or more vertices, found none (empty mesh)",
        ));
    }
    let mut mat_map = HashMap::new();
    let tobj_materials: Vec<tobj::Material> = scan
        .materials
        .iter()
        .enumerate()
        .map(|(i, m)| {
            mat_map.insert(m.name.clone(), i);
            tobj::Material {
                name: m.name.clone(),
                ..tobj::Material::default()
            }
        })
        .collect();
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    // A first `mtllib` line of our own makes tobj's material loader hand it every `usemtl`
    // name found by the scan, whether or not an MTL file defines it: in the thermal band
    // the name is all that matters, and tobj forgets names it has no material for.
    let first = std::cell::Cell::new(true);
    let mut reader = std::io::Cursor::new(b"mtllib irsig-usemtl-names\n".as_slice())
        .chain(std::io::Cursor::new(text.as_bytes()));
    let mut reader = std::io::BufReader::new(&mut reader);
    let loader = |_: &Path| -> tobj::MTLLoadResult {
        if first.replace(false) {
            Ok((tobj_materials.clone(), mat_map.clone()))
        } else {
            Ok((Vec::new(), HashMap::new()))
        }
    };
    let (models, _) = tobj::load_obj_buf(&mut reader, &options, loader)
        .map_err(|e| ParseError::at_offset(file, text, 0, format!("malformed OBJ: {e}")))?;
    let mut positions = Vec::new();
    let mut triangles = Vec::with_capacity(scan.triangles);
    for model in models {
        let mesh = model.mesh;
        let base = u32::try_from(positions.len()).map_err(|_| {
            ParseError::at_offset(file, text, 0, "more than 2^32 vertices in one OBJ")
        })?;
        positions.extend(mesh.positions.chunks_exact(3).map(|c| [c[0], c[1], c[2]]));
        let material = mesh.material_id.and_then(|m| u32::try_from(m).ok());
        triangles.extend(mesh.indices.chunks_exact(3).map(|c| Triangle {
            vertices: [base + c[0], base + c[1], base + c[2]],
            material,
            temperature_k: None,
        }));
    }
    if triangles.len() != scan.triangles {
        // The scan and tobj disagree on what the faces are: never silently mislabel lines.
        return Err(ParseError::at_offset(
            file,
            text,
            0,
            format!(
                "malformed OBJ: expected {} triangles from the faces, tobj made {}",
                scan.triangles,
                triangles.len()
            ),
        ));
    }
    Ok(Mesh {
        file: file.to_owned(),
        positions,
        triangles,
        materials: scan.materials,
        warnings: scan.warnings,
        origins: scan.origins,
        parts: Vec::new(),
    })
}

fn scan(file: &str, text: &str, base_dir: Option<&Path>) -> Result<Scan, ParseError> {
    let mut out = Scan {
        materials: Vec::new(),
        origins: Vec::new(),
        warnings: Vec::new(),
        triangles: 0,
    };
    let mut names: HashMap<&str, usize> = HashMap::new();
    let mut vertices = 0usize;
    let mut offset = 0usize;
    let mut skipped_short_faces = 0usize;
    for (line_index, raw) in text.split_inclusive('\n').enumerate() {
        let line_start = offset;
        offset += raw.len();
        let line = raw.trim_end_matches(['\n', '\r']);
        let at = |token: &str| line_start + (token.as_ptr() as usize - line.as_ptr() as usize);
        let err = |token: &str, msg: String| {
            ParseError::at_span(file, text, at(token), token.len().max(1), msg)
        };
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                for axis in ["x", "y", "z"] {
                    let Some(w) = words.next() else {
                        return Err(ParseError::at_offset(
                            file,
                            text,
                            line_start + line.len(),
                            format!(
                                "expected the vertex's {axis} coordinate, found the end of the line"
                            ),
                        ));
                    };
                    let v: f64 = w.parse().map_err(|_| {
                        err(
                            w,
                            format!(
                                "expected a number for the vertex's {axis} coordinate, found `{w}`"
                            ),
                        )
                    })?;
                    if !v.is_finite() {
                        return Err(err(
                            w,
                            format!("expected a finite {axis} coordinate, found `{w}`"),
                        ));
                    }
                }
                vertices += 1;
            }
            Some("f") => {
                let mut n = 0usize;
                for w in words {
                    let index = w.split('/').next().unwrap_or("");
                    let i: i64 = index
                        .parse()
                        .map_err(|_| err(w, format!("expected a vertex index, found `{w}`")))?;
                    let ok = if i > 0 {
                        (i as u64) <= vertices as u64
                    } else {
                        i != 0 && i.unsigned_abs() <= vertices as u64
                    };
                    if !ok {
                        return Err(err(
                            w,
                            format!(
                                "vertex index {i} does not exist: {vertices} vertices are defined before this face (indices count from 1, negative ones from the end)"
                            ),
                        ));
                    }
                    n += 1;
                }
                if n < 3 {
                    skipped_short_faces += 1;
                    continue;
                }
                let first = u32::try_from(out.triangles)
                    .map_err(|_| err(line, "more than 2^32 triangles in one OBJ".into()))?;
                out.origins.push(Origin {
                    first_triangle: first,
                    line: u32::try_from(line_index + 1).unwrap_or(u32::MAX),
                    part: None,
                });
                out.triangles += n - 2;
            }
            Some("usemtl") => {
                let name = line.trim_start()["usemtl".len()..].trim();
                if name.is_empty() {
                    return Err(ParseError::at_offset(
                        file,
                        text,
                        line_start + line.len(),
                        "expected a material name after `usemtl`",
                    ));
                }
                if !names.contains_key(name) {
                    names.insert(name, out.materials.len());
                    out.materials.push(MaterialUse {
                        name: name.to_owned(),
                        id: None,
                        first_use: Location {
                            file: file.to_owned(),
                            line: Some(line_index + 1),
                            part: None,
                        },
                    });
                }
            }
            Some("mtllib") => {
                let name = line.trim_start()["mtllib".len()..].trim();
                check_mtl(file, text, at(name), name, base_dir, &mut out.warnings)?;
            }
            Some("vn" | "vt") => {
                for w in words.take(2) {
                    if w.parse::<f64>().is_err() {
                        return Err(err(w, format!("expected a number, found `{w}`")));
                    }
                }
            }
            _ => {}
        }
    }
    if skipped_short_faces > 0 {
        out.warnings.push(format!(
            "{file}: skipped {skipped_short_faces} faces with fewer than three vertices (points and lines)"
        ));
    }
    Ok(out)
}

/// An `mtllib` must be a local relative file that stays in the OBJ's directory. It is
/// parsed when present, so that a broken MTL is reported; its contents (colours,
/// textures) mean nothing in the thermal band.
fn check_mtl(
    file: &str,
    text: &str,
    offset: usize,
    name: &str,
    base_dir: Option<&Path>,
    warnings: &mut Vec<String>,
) -> Result<(), ParseError> {
    let path = super::gltf_read::local_relative_path(name).map_err(|why| {
        ParseError::at_span(
            file,
            text,
            offset,
            name.len().max(1),
            format!("mtllib `{name}`: {why}"),
        )
    })?;
    let Some(dir) = base_dir else {
        warnings.push(format!(
            "{file}: mtllib `{name}` not read (the OBJ came from standard input); material names come from `usemtl`"
        ));
        return Ok(());
    };
    let full = dir.join(path);
    match std::fs::read(&full) {
        Ok(bytes) => {
            let mtl_name = full.display().to_string();
            let mtl_text = String::from_utf8_lossy(&bytes);
            check_mtl_colours(&mtl_name, &mtl_text)?;
            let mut reader = std::io::BufReader::new(bytes.as_slice());
            tobj::load_mtl_buf(&mut reader).map_err(|e| {
                ParseError::at_offset(&mtl_name, &mtl_text, 0, format!("malformed MTL: {e}"))
            })?;
            Ok(())
        }
        Err(_) => {
            warnings.push(format!(
                "{file}: mtllib `{name}` not found at {}; material names come from `usemtl`",
                full.display()
            ));
            Ok(())
        }
    }
}

/// tobj 4.0 panics on a colour line (`Ka`, `Kd`, `Ks`, `Ke`) with fewer than three values
/// instead of returning an error; this finds such a line first and says where it is.
fn check_mtl_colours(mtl_name: &str, text: &str) -> Result<(), ParseError> {
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let mut words = line.split_whitespace();
        if let Some(key) = words.next()
            && matches!(key, "Ka" | "Kd" | "Ks" | "Ke")
            && words.count() < 3
        {
            let at = offset + line.find(key).unwrap_or(0);
            return Err(ParseError::at_span(
                mtl_name,
                text,
                at,
                key.len(),
                format!("malformed MTL: expected three numbers (r g b) after `{key}`"),
            ));
        }
        offset += line.len();
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quad_becomes_two_triangles_with_its_material() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl asphalt\nf 1 2 3 4\n";
        let m = read_obj("q.obj", text.as_bytes(), None).unwrap();
        assert_eq!(m.triangles.len(), 2);
        assert_eq!(m.material_name(0), Some("asphalt"));
        assert_eq!(m.material_name(1), Some("asphalt"));
        assert_eq!(m.triangle_location(1).line, Some(6));
        // Fan from the first vertex, winding kept: (1,2,3) and (1,3,4).
        let p = |i: u32| m.positions[i as usize];
        let t1 = m.triangles[1].vertices.map(p);
        assert_eq!(t1, [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]);
    }

    #[test]
    fn materials_without_an_mtl_keep_their_names_and_groups_their_order() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nusemtl b\nf 1 2 4\nusemtl a\nf 1 3 4\nusemtl b\nf 2 3 4\n";
        let m = read_obj("m.obj", text.as_bytes(), None).unwrap();
        let names: Vec<_> = (0..4).map(|i| m.material_name(i)).collect();
        assert_eq!(names, [None, Some("b"), Some("a"), Some("b")]);
        assert_eq!(m.materials[0].first_use.line, Some(6));
        assert_eq!(m.triangle_location(3).line, Some(11));
    }

    #[test]
    fn bad_numbers_name_line_and_column() {
        let e = read_obj("b.obj", b"v 0 0 0\nv 1 zero 0\n", None).unwrap_err();
        assert_eq!((e.line, e.column), (2, 5), "{e}");
        let e = read_obj("b.obj", b"v 0 0 0\nv 1 0 NaN\n", None).unwrap_err();
        assert_eq!((e.line, e.column), (2, 7), "{e}");
        assert!(e.message.contains("finite"));
        let e = read_obj("b.obj", b"v 0 0 0\nv 1 0 inf\n", None).unwrap_err();
        assert!(e.message.contains("finite"));
        let e = read_obj("b.obj", b"v 0 0\n", None).unwrap_err();
        assert!(e.message.contains("z coordinate"), "{e}");
    }

    #[test]
    fn faces_pointing_past_the_vertices_are_errors() {
        let e = read_obj("b.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", None).unwrap_err();
        assert_eq!((e.line, e.column), (4, 7), "{e}");
        let e = read_obj("b.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", None).unwrap_err();
        assert_eq!(e.line, 4);
        // Negative indices count back from the last vertex.
        let m = read_obj("b.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n", None).unwrap();
        assert_eq!(m.triangles.len(), 1);
    }

    #[test]
    fn an_empty_mesh_is_an_error() {
        let e = read_obj("e.obj", b"# nothing\nv 0 0 0\n", None).unwrap_err();
        assert!(e.message.contains("empty mesh"), "{e}");
        assert!(read_obj("e.obj", b"", None).is_err());
    }

    #[test]
    fn network_mtllib_is_refused() {
        let e = read_obj(
            "n.obj",
            b"mtllib http://example.com/a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            None,
        )
        .unwrap_err();
        assert_eq!(e.line, 1);
        assert!(e.message.contains("mtllib"), "{e}");
    }
}
