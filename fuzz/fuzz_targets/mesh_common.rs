//! What the mesh and canonical fuzz targets check beyond "no panic": an error points inside
//! the input, and a mesh that reads is consistent (indices in range, finite positions,
//! material references that exist, at least one triangle).

use irsig_formats::ParseError;
use irsig_formats::mesh::Mesh;

/// An error about `file` (whose text is `data`, when it is text) lies inside it.
pub fn check_error(e: &ParseError, file: &str, data: &[u8]) {
    assert!(e.line >= 1 && e.column >= 1, "{e}");
    if e.file == file {
        if let Ok(text) = std::str::from_utf8(data) {
            let lines = text.split('\n').count();
            assert!(e.line <= lines, "line {} of {lines}: {e}", e.line);
        }
    }
}

/// A mesh a reader returned is one the importer can use without further checks on shape.
pub fn check_mesh(mesh: &Mesh) {
    assert!(!mesh.triangles.is_empty(), "a mesh without triangles was accepted");
    for p in &mesh.positions {
        assert!(p.iter().all(|c| c.is_finite()), "non-finite position {p:?}");
    }
    for t in &mesh.triangles {
        for v in t.vertices {
            assert!((v as usize) < mesh.positions.len(), "vertex {v} out of range");
        }
        if let Some(m) = t.material {
            assert!((m as usize) < mesh.materials.len(), "material {m} out of range");
        }
    }
    for i in 0..mesh.triangles.len() {
        let _ = mesh.triangle_location(i);
    }
}
