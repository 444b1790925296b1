//! Modern mesh files: Wavefront OBJ (+ MTL) through `tobj`, and glTF 2.0 / GLB through
//! `gltf`. Both read into a [`Mesh`]: triangles with vertex positions in the file's own
//! length unit, each with the material *name* the file gives (mapping names to ids is the
//! importer's job, against a material library).
//!
//! - **OBJ**: polygons are triangulated by `tobj` as fans from their first vertex (exact for
//!   convex polygons, which is what exporters write; a non-convex polygon should be
//!   triangulated by the exporter). A face's material is the last `usemtl` before it.
//!   `mtllib` files are parsed when present (a malformed MTL is an error) but only the
//!   names matter in the thermal band; a missing MTL is a warning. Points and lines are
//!   skipped. Positions are read as `f64`.
//! - **glTF/GLB**: the default scene (or every root node when there is none) is walked
//!   through its node hierarchy, each node's matrix or TRS applied; a transform with a
//!   negative determinant (a mirror) reverses the winding so that fronts stay fronts.
//!   Every primitive of every mesh is read; triangle lists, strips and fans are
//!   triangulated, points and lines are skipped with a warning. Indices may be u8, u16 or
//!   u32, or absent (non-indexed). A buffer is the GLB `BIN` chunk, an embedded
//!   `data:…;base64,` URI, or a **relative local file** beside the glTF that does not
//!   climb out of its directory (`..`); any other URI (`http://`, `file:///`, an absolute
//!   path) is an error, and irsig never reaches the network. Every accessor is bounds-
//!   checked against its buffer before it is read; sparse accessors are refused.

mod gltf_read;
mod obj;

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
}

/// A material name as a mesh file uses it, and where it is first used.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialUse {
    /// The name (`usemtl` name, glTF material name, or `material N` for an unnamed glTF
    /// material).
    pub name: String,
    /// Where it is first used.
    pub first_use: Location,
}

/// A place in an input file, for messages: a line, or a described part of a binary file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file name as the user gave it.
    pub file: String,
    /// The 1-based line, for text files.
    pub line: Option<usize>,
    /// What part of the file, for binary files (`mesh "Body" primitive 0`).
    pub part: Option<String>,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.file)?;
        if let Some(l) = self.line {
            write!(f, ":{l}")?;
        }
        if let Some(p) = &self.part {
            write!(f, " ({p})")?;
        }
        Ok(())
    }
}

/// Where a run of triangles came from: triangles from `first_triangle` on, until the next
/// run, came from `line` or `part`.
#[derive(Debug, Clone, PartialEq)]
struct Origin {
    first_triangle: u32,
    line: u32,
    part: Option<u32>,
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
            line: origin.map(|o| o.line as usize).filter(|&l| l > 0).or(None),
            part: origin
                .and_then(|o| o.part)
                .and_then(|p| self.parts.get(p as usize).cloned()),
        }
    }

    /// The material name of triangle `index`, if any.
    #[must_use]
    pub fn material_name(&self, index: usize) -> Option<&str> {
        let m = self.triangles.get(index)?.material?;
        self.materials.get(m as usize).map(|m| m.name.as_str())
    }
}
