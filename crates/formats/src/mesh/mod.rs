//! Modern mesh files: Wavefront OBJ (+ MTL) through `tobj`, and glTF 2.0 / GLB through
//! `gltf`. Both read into a [`Mesh`]: triangles with vertex positions in the file's own
//! length unit, each with the material *name* the file gives (mapping names to ids is the
//! importer's job, against a material library).
//!
//! - **OBJ**: polygons are triangulated by `tobj` as fans from their first vertex (exact for
//!   convex polygons, which is what exporters write; a non-convex polygon should be
//!   triangulated by the exporter). A face's material is the last `usemtl` before it.
//!   `mtllib` files are parsed when present (a malformed MTL is an error) but only the
//!   names matter in the thermal band, and the image a material's `map_Kd` names
//!   ([`MaterialUse::image`]); a missing MTL is a warning. Points and lines are skipped.
//!   Positions are read as `f64`; a face whose every corner has a `vt` index gives its
//!   triangles texture coordinates ([`Triangle::uv`]).
//! - **glTF/GLB**: the default scene (or every root node when there is none) is walked
//!   through its node hierarchy, each node's matrix or TRS applied; a transform with a
//!   negative determinant (a mirror) reverses the winding so that fronts stay fronts.
//!   Every primitive of every mesh is read; triangle lists, strips and fans are
//!   triangulated, points and lines are skipped with a warning. Indices may be u8, u16 or
//!   u32, or absent (non-indexed). A buffer is the GLB `BIN` chunk, an embedded
//!   `data:…;base64,` URI, or a **relative local file** beside the glTF that does not
//!   climb out of its directory (`..`); any other URI (`http://`, `file:///`, an absolute
//!   path) is an error, and irsig never reaches the network; so is a symbolic link that
//!   leads out of the model's directory. `asset.version` must be 2.x, a GLB's stated
//!   length the file's, a buffer's `byteLength` its data's (a GLB `BIN` chunk may add up
//!   to 3 bytes of padding), every buffer view inside its buffer, a triangle list's index
//!   count a multiple of 3. Every accessor is bounds-checked against its buffer before it
//!   is read; sparse accessors are refused. Errors name the JSON path of what is wrong
//!   (`meshes[0].primitives[1].indices`), at its line and column in a `.gltf` and its
//!   byte offset in a GLB. Positions stay in the file's axes (+Y up):
//!   [`Mesh::y_up_to_z_up`] turns them into irsig's.
//! - **Legacy facet files** ([`crate::legacy::object`]) become meshes too
//!   ([`read_legacy_object`]): three vertices of their own per facet, the material index
//!   kept as a number ([`MaterialUse::id`]), the optional facet temperature kept. A
//!   4-vertex facet (irsig extension) is split here, along its shorter diagonal, into two
//!   triangles that share its four vertices and its material, temperature and line: from
//!   the mesh on, the pipeline sees triangles only.

mod gltf_read;
mod json_path;
mod obj;

use crate::ParseError;
use crate::legacy::object::ObjectFile;

use std::fmt;

pub use gltf_read::read_gltf;
pub use obj::read_obj;

/// One triangle of a [`Mesh`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triangle {
    /// Indices into [`Mesh::positions`], counter-clockwise seen from the front.
    pub vertices: [u32; 3],
    /// Index into [`Mesh::materials`], or `None` when the file gives the facet no material.
    pub material: Option<u32>,
    /// Kinetic temperature in kelvin, where the file gives one.
    pub temperature_k: Option<f64>,
    /// Texture coordinates `(u, v)` of the three corners, in the order of `vertices`, where
    /// the file gives them (OBJ `vt`, glTF `TEXCOORD_0`), in irsig's convention: `v` runs
    /// up from the image's bottom row (OBJ's own; glTF's, which runs down from the top, is
    /// turned: `v = 1 − v_gltf`).
    pub uv: Option<[[f64; 2]; 3]>,
}

/// A material name as a mesh file uses it, and where it is first used.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialUse {
    /// The name (`usemtl` name, glTF material name, or `material N` for an unnamed glTF
    /// material).
    pub name: String,
    /// For formats that number materials instead of naming them (the legacy facet file's
    /// material index), the number: it is the material's id in the library.
    pub id: Option<u16>,
    /// Where it is first used.
    pub first_use: Location,
    /// The image the file names for the material's surface (an MTL's `map_Kd`, a glTF
    /// material's `baseColorTexture` image `uri`), as a path relative to the model's
    /// folder with `/` between its parts, checked as every reference is (relative, never
    /// absolute or above that folder). Not read: a material's image map may name it.
    pub image: Option<String>,
    /// The image a glTF material's base colour texture carries inside the file (a GLB's
    /// buffer view, a `data:` URI) instead of naming one beside it: it has no path until
    /// it is written out (`irsig-import --images DIR`).
    pub embedded_image: Option<EmbeddedImage>,
}

/// An image stored inside a glTF file, as stored: its encoded bytes (PNG or JPEG), not
/// decoded.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EmbeddedImage {
    /// Its index in the file's `images`.
    pub index: usize,
    /// The name the file gives it, if any: a label, not a path, and never used as one
    /// unchecked.
    pub name: Option<String>,
    /// Its MIME type as the file states it (`image/png` or `image/jpeg`, the two glTF 2.0
    /// allows), `None` where it states none.
    pub mime_type: Option<String>,
    /// The bytes, one copy however many materials use the image.
    pub bytes: std::sync::Arc<[u8]>,
}

/// A place in an input file, for messages: a line, or a described part of a binary file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file name as the user gave it.
    pub file: String,
    /// The 1-based line, for text files (line 1 for a GLB).
    pub line: Option<usize>,
    /// The 1-based column in characters (for a GLB, the byte offset + 1).
    pub column: Option<usize>,
    /// What part of the file, for binary files (`mesh "Body" primitive 0`).
    pub part: Option<String>,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.file)?;
        if let Some(l) = self.line {
            write!(f, ":{l}")?;
            if let Some(c) = self.column {
                write!(f, ":{c}")?;
            }
        }
        if let Some(p) = &self.part {
            write!(f, " ({p})")?;
        }
        Ok(())
    }
}

/// Where a run of triangles came from: triangles from `first_triangle` on, until the next
/// run, came from `line` and `column` (0 when unknown) and `part`; or, when `lines_follow`,
/// triangle `first_triangle + k` from line `line + k` (an OBJ's triangles one per line, as
/// most are written: a million of them make one run, not a million).
#[derive(Debug, Clone, PartialEq)]
struct Origin {
    first_triangle: u32,
    line: u32,
    column: u32,
    part: Option<u32>,
    lines_follow: bool,
}

/// A triangle mesh as read from a file, in the file's length unit.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// The file name as the user gave it.
    pub file: String,
    /// Vertex positions in the file's unit, after any node transforms (glTF).
    pub positions: Vec<[f64; 3]>,
    /// The triangles.
    pub triangles: Vec<Triangle>,
    /// Material names the triangles refer to.
    pub materials: Vec<MaterialUse>,
    /// What was skipped or assumed (points, lines, a missing MTL), for the tool to print.
    pub warnings: Vec<String>,
    origins: Vec<Origin>,
    parts: Vec<String>,
}

/// Reads a legacy (Intergraph-derived) facet file into a [`Mesh`].
///
/// # Errors
/// Non-UTF-8 text or any error of [`crate::legacy::object::parse`].
pub fn read_legacy_object(file: &str, bytes: &[u8]) -> Result<Mesh, ParseError> {
    let text = crate::legacy::decode(file, bytes)?;
    let object = crate::legacy::object::parse(file, text)?;
    from_legacy_object(file, &object)
}

/// Converts a parsed legacy facet file into a [`Mesh`]: each facet keeps its own three
/// vertices, its material index (as [`MaterialUse::id`]) and its temperature. A 4-vertex
/// facet keeps its own four vertices and becomes the two triangles of
/// [`crate::legacy::object::LegacyFacet::triangles`] (split along its shorter diagonal,
/// wound as the facet), both located at the facet's line.
///
/// # Errors
/// More than 2^32 vertices or triangles, or a 4-vertex facet that is not planar and convex
/// (the parser refuses those; an `ObjectFile` built in code is checked again here), at the
/// facet's line.
pub fn from_legacy_object(file: &str, object: &ObjectFile) -> Result<Mesh, ParseError> {
    let too_big = || ParseError::at_offset(file, "", 0, "too many facets for one object");
    let mut mesh = Mesh {
        file: file.to_owned(),
        ..Mesh::default()
    };
    let mut by_index = std::collections::HashMap::new();
    for (i, f) in object.facets.iter().enumerate() {
        if let Err(e) = f.check_quad() {
            let mut error = ParseError::at_offset(
                file,
                "",
                0,
                format!("facet {} (vertex {}): {e}", i + 1, e.vertex),
            );
            error.line = f.position.line;
            error.column = f.position.column;
            return Err(error);
        }
        let material = *by_index.entry(f.material_index).or_insert_with(|| {
            mesh.materials.push(MaterialUse {
                name: format!("material index {}", f.material_index),
                id: Some(f.material_index),
                first_use: Location {
                    file: file.to_owned(),
                    line: Some(f.position.line),
                    column: Some(f.position.column),
                    part: None,
                },
                image: None,
                embedded_image: None,
            });
            u32::try_from(mesh.materials.len() - 1).unwrap_or(u32::MAX)
        });
        let base = u32::try_from(mesh.positions.len()).map_err(|_| too_big())?;
        base.checked_add(3).ok_or_else(too_big)?;
        let first_triangle = u32::try_from(mesh.triangles.len()).map_err(|_| too_big())?;
        mesh.positions.extend(f.corners());
        for corners in f.triangles() {
            mesh.triangles.push(Triangle {
                // `corners` are 0 to 3, and `base + 3` fits (checked above).
                vertices: corners.map(|k| base + u32::try_from(k).unwrap_or(0)),
                material: Some(material),
                temperature_k: f.temperature_k,
                uv: None,
            });
        }
        mesh.origins.push(Origin {
            first_triangle,
            line: u32::try_from(f.position.line).unwrap_or(u32::MAX),
            column: u32::try_from(f.position.column).unwrap_or(u32::MAX),
            part: None,
            lines_follow: false,
        });
    }
    Ok(mesh)
}

/// The file a model or a materials file in `dir` names by `reference` (a buffer, an MTL, an
/// image map): a local relative path (`%`-escapes decoded) that stays in `dir`, never an
/// absolute path, a URI with a scheme, a `..` or a symbolic link out of `dir`.
///
/// # Errors
/// Why the reference is refused, naming it.
pub fn resolve_reference(
    dir: &std::path::Path,
    reference: &str,
) -> Result<std::path::PathBuf, String> {
    let rel = gltf_read::local_relative_path(reference)?;
    gltf_read::inside(dir, &rel, reference)
}

/// A relative path, already checked to hold only normal parts, written with `/` between
/// them whatever the platform, as a model's references and irsig's files write paths.
pub(crate) fn slash_path(path: &std::path::Path) -> String {
    path.components()
        .filter_map(|c| match c {
            std::path::Component::Normal(part) => Some(part.to_string_lossy().into_owned()),
            _ => None,
        })
        .collect::<Vec<_>>()
        .join("/")
}

impl Mesh {
    /// Where triangle `index` came from: its face's line (OBJ) or its mesh, primitive and
    /// node (glTF).
    #[must_use]
    pub fn triangle_location(&self, index: usize) -> Location {
        let i = self
            .origins
            .partition_point(|o| o.first_triangle as usize <= index);
        let origin = i.checked_sub(1).and_then(|i| self.origins.get(i));
        Location {
            file: self.file.clone(),
            line: origin
                .map(|o| {
                    let step = if o.lines_follow {
                        index - o.first_triangle as usize
                    } else {
                        0
                    };
                    o.line as usize + step
                })
                .filter(|&l| l > 0),
            column: origin.map(|o| o.column as usize).filter(|&c| c > 0),
            part: origin
                .and_then(|o| o.part)
                .and_then(|p| self.parts.get(p as usize).cloned()),
        }
    }

    /// Where in the input a model error's path points: for `facets[i]...` the origin of
    /// triangle `i` (facet `i` of an object built from this mesh, in order), otherwise the
    /// file. Lets importers report `Object::validate` errors at the input line.
    #[must_use]
    pub fn locate(&self, model_path: &str) -> String {
        model_path
            .strip_prefix("facets[")
            .and_then(|r| r.split(']').next())
            .and_then(|i| i.parse::<usize>().ok())
            .map_or_else(
                || self.file.clone(),
                |i| self.triangle_location(i).to_string(),
            )
    }

    /// Turns positions from glTF's axes (+Y up, +Z toward the viewer; glTF 2.0 §3.4) into
    /// irsig's (+Z up): `(x, y, z)` becomes `(x, -z, y)`, a rotation of 90° about +X. A
    /// rotation keeps handedness, so counter-clockwise fronts stay fronts and no winding
    /// changes; what was up in the file is up in the scene.
    pub fn y_up_to_z_up(&mut self) {
        for p in &mut self.positions {
            *p = [p[0], -p[2], p[1]];
        }
    }

    /// The material name of triangle `index`, if any.
    #[must_use]
    pub fn material_name(&self, index: usize) -> Option<&str> {
        let m = self.triangles.get(index)?.material?;
        self.materials.get(m as usize).map(|m| m.name.as_str())
    }
}
