//! Wavefront OBJ through `tobj`, with a pass of our own over the text for what `tobj`
//! does not keep: the line and column of a bad number, non-finite coordinates, `usemtl`
//! names that no MTL defines, which material and which line each triangle came from.
//!
//! The two passes run at the same time (`rayon::join`: on two threads when rayon has two,
//! one after the other otherwise), our pass ahead: `tobj` is handed only lines our pass has
//! already accepted ([`Checked`]), as when the two ran one after the other, so `tobj` never
//! sees input our checks reject (tobj 4.0 can panic on some of it in a build with overflow
//! checks). Our pass is about three times faster, so `tobj` seldom waits. The outcome does
//! not depend on timing: an error of our pass always wins, because it names a line and
//! column, and once our pass has failed `tobj`'s input ends.

use std::collections::HashMap;
use std::io::{BufRead, Read};
use std::path::Path;
use std::sync::{Condvar, Mutex, PoisonError};

use super::{Location, MaterialUse, Mesh, Origin, Triangle};
use crate::ParseError;

/// What our own pass learns.
struct Scan {
    materials: Vec<MaterialUse>,
    /// Runs of triangles with one material: from `first_triangle` on, until the next run,
    /// triangles have `material` (an index into `materials`, `None` before any `usemtl`).
    material_runs: Vec<MaterialRun>,
    origins: Vec<Origin>,
    warnings: Vec<String>,
    triangles: usize,
    texcoords: TexCoords,
    /// The image each MTL material's `map_Kd` names, by material name, relative to the
    /// OBJ's folder.
    images: HashMap<String, String>,
}

/// The texture coordinates the scan collects: the `vt` values, and per triangle those of
/// its corners where its face gives every corner a `vt` index (a face that gives some
/// corners none has no coordinates: tobj would invent them from a neighbour).
#[derive(Debug, Default)]
struct TexCoords {
    values: Vec<[f64; 2]>,
    /// Per triangle, from the first triangle on once any has some; empty while none has.
    triangles: Vec<Option<[[f64; 2]; 3]>>,
    /// The face being read: each corner's index into `values`, if it names one.
    face: Vec<Option<usize>>,
}

impl TexCoords {
    /// Records the `vt` index `i` (from 1, or negative from the end) of the face's corner
    /// being read, already checked to exist when negative.
    fn corner(&mut self, i: i64) {
        let index = if i > 0 {
            usize::try_from(i - 1).ok()
        } else {
            usize::try_from(i.unsigned_abs())
                .ok()
                .and_then(|back| self.values.len().checked_sub(back))
        };
        if let Some(last) = self.face.last_mut() {
            *last = index;
        }
    }

    /// Ends a face of `n ≥ 3` corners whose first triangle is `first`: its fan of
    /// triangles `(0, k, k + 1)`, as tobj triangulates, each with its corners' coordinates
    /// where the face gives them all.
    fn end_face(&mut self, first: usize) {
        let corners: Option<Vec<[f64; 2]>> = self
            .face
            .iter()
            .map(|i| i.and_then(|i| self.values.get(i).copied()))
            .collect();
        let n = self.face.len();
        match corners {
            Some(c) => {
                if self.triangles.is_empty() {
                    self.triangles.resize(first, None);
                }
                self.triangles
                    .extend((1..n - 1).map(|k| Some([c[0], c[k], c[k + 1]])));
            }
            None if !self.triangles.is_empty() => {
                self.triangles.extend((1..n - 1).map(|_| None));
            }
            None => {}
        }
        self.face.clear();
    }
}

struct MaterialRun {
    first_triangle: usize,
    material: Option<u32>,
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
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    // tobj starts a new model, with vertices of its own, wherever the material changes;
    // it must know every `usemtl` name from the start to do so (it forgets names no MTL
    // defines). A quick search for `usemtl` lines gives them before either pass runs, and
    // a first `mtllib` line of our own makes tobj's material loader hand them over.
    let names = usemtl_names(text);
    let tobj_materials: Vec<tobj::Material> = names
        .iter()
        .map(|&name| tobj::Material {
            name: name.to_owned(),
            ..tobj::Material::default()
        })
        .collect();
    let mat_map: HashMap<String, usize> = names
        .iter()
        .enumerate()
        .map(|(i, &name)| (name.to_owned(), i))
        .collect();
    let checked = Checked::default();
    let (options, checked) = (&options, &checked);
    let (scan, parsed) = rayon::join(
        || {
            // Whatever happens to the scan, even a panic, tobj stops waiting for it.
            let mut outcome = FailUnlessCleared(Some(checked));
            let scan = scan(file, text, base_dir, checked);
            if scan.is_ok() {
                checked.publish(text.len());
                outcome.0 = None;
            }
            scan
        },
        move || {
            let first_mtllib = std::cell::Cell::new(true);
            let loader = |_: &Path| -> tobj::MTLLoadResult {
                if first_mtllib.replace(false) {
                    Ok((tobj_materials.clone(), mat_map.clone()))
                } else {
                    Ok((Vec::new(), HashMap::new()))
                }
            };
            let mut reader = CheckedText::new(b"mtllib irsig-usemtl-names\n", text, checked);
            tobj::load_obj_buf(&mut reader, options, loader)
        },
    );
    let scan = scan?;
    if scan.triangles == 0 {
        return Err(ParseError::at_offset(
            file,
            text,
            text.len(),
            "expected at least one face with three or more vertices, found none (empty mesh)",
        ));
    }
    let (models, _) =
        parsed.map_err(|e| ParseError::at_offset(file, text, 0, format!("malformed OBJ: {e}")))?;
    let total_positions: usize = models.iter().map(|m| m.mesh.positions.len() / 3).sum();
    let mut positions = Vec::with_capacity(total_positions);
    let mut triangles = Vec::with_capacity(scan.triangles);
    for model in models {
        let mesh = model.mesh;
        let base = u32::try_from(positions.len()).map_err(|_| {
            ParseError::at_offset(file, text, 0, "more than 2^32 vertices in one OBJ")
        })?;
        positions.extend(mesh.positions.chunks_exact(3).map(|c| [c[0], c[1], c[2]]));
        triangles.extend(mesh.indices.chunks_exact(3).map(|c| Triangle {
            vertices: [base + c[0], base + c[1], base + c[2]],
            material: None,
            temperature_k: None,
            uv: None,
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
    // tobj keeps the faces in file order (its models follow one another in the file), so
    // the scan's runs label them; the materials are the scan's, which names them by line.
    let mut runs = scan.material_runs.iter().peekable();
    let mut material = None;
    for (i, t) in triangles.iter_mut().enumerate() {
        while let Some(run) = runs.next_if(|r| r.first_triangle <= i) {
            material = run.material;
        }
        t.material = material;
        t.uv = scan.texcoords.triangles.get(i).copied().flatten();
    }
    let mut materials = scan.materials;
    for m in &mut materials {
        m.image = scan.images.get(&m.name).cloned();
    }
    Ok(Mesh {
        file: file.to_owned(),
        positions,
        triangles,
        materials,
        warnings: scan.warnings,
        origins: scan.origins,
        parts: Vec::new(),
    })
}

/// The names of the `usemtl` lines in the order of their first use, found as [`scan`]
/// finds them: `usemtl` as the first word of a line, the rest of the line trimmed.
fn usemtl_names(text: &str) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    let mut seen = std::collections::HashSet::new();
    // Lines already looked at end before `done`, so that no byte is searched twice however
    // many times a line holds `usemtl`.
    let mut done = 0;
    for (at, _) in text.match_indices("usemtl") {
        if at < done {
            continue;
        }
        let line_start = text[done..at].rfind('\n').map_or(done, |i| done + i + 1);
        let line_end = text[at..].find('\n').map_or(text.len(), |i| at + i);
        done = line_end;
        let line = text[line_start..line_end].trim_end_matches(['\n', '\r']);
        if line.split_whitespace().next() != Some("usemtl")
            || !text[line_start..at].trim_start().is_empty()
        {
            continue;
        }
        let name = line.trim_start()["usemtl".len()..].trim();
        if !name.is_empty() && seen.insert(name) {
            names.push(name);
        }
    }
    names
}

/// How far our scan has checked the text: the byte offset of the end of its last accepted
/// line, or that it has failed. The scan publishes every [`Checked::STEP`] bytes.
#[derive(Debug, Default)]
struct Checked {
    state: Mutex<CheckedState>,
    changed: Condvar,
}

#[derive(Debug, Clone, Copy, Default)]
enum CheckedState {
    UpTo(usize),
    #[default]
    Nothing,
    Failed,
}

impl Checked {
    /// Bytes of text between two publications: small against the text, large against a line.
    const STEP: usize = 256 * 1024;

    fn set(&self, state: CheckedState) {
        *self.state.lock().unwrap_or_else(PoisonError::into_inner) = state;
        self.changed.notify_all();
    }

    fn publish(&self, up_to: usize) {
        self.set(CheckedState::UpTo(up_to));
    }

    /// Waits until more than `offset` bytes are checked; `None` once the scan has failed.
    fn beyond(&self, offset: usize) -> Option<usize> {
        let mut state = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        loop {
            match *state {
                CheckedState::Failed => return None,
                CheckedState::UpTo(n) if n > offset => return Some(n),
                _ => {
                    state = self
                        .changed
                        .wait(state)
                        .unwrap_or_else(PoisonError::into_inner);
                }
            }
        }
    }
}

/// Marks the scan failed when dropped, unless cleared (set to `None`) first.
struct FailUnlessCleared<'a>(Option<&'a Checked>);

impl Drop for FailUnlessCleared<'_> {
    fn drop(&mut self) {
        if let Some(checked) = self.0 {
            checked.set(CheckedState::Failed);
        }
    }
}

/// The OBJ text as tobj reads it: `prefix`, then the text as far as the scan has accepted
/// it. A read past that waits for the scan, and fails once the scan has failed.
struct CheckedText<'a> {
    prefix: &'a [u8],
    text: &'a [u8],
    /// How far tobj has read, and how far it may read without asking again.
    at: usize,
    allowed: usize,
    checked: &'a Checked,
}

impl<'a> CheckedText<'a> {
    fn new(prefix: &'a [u8], text: &'a str, checked: &'a Checked) -> Self {
        Self {
            prefix,
            text: text.as_bytes(),
            at: 0,
            allowed: 0,
            checked,
        }
    }
}

impl Read for CheckedText<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let mut part = self.fill_buf()?;
        let n = part.read(buf)?;
        self.consume(n);
        Ok(n)
    }
}

impl BufRead for CheckedText<'_> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        if !self.prefix.is_empty() {
            return Ok(self.prefix);
        }
        if self.at >= self.allowed && self.at < self.text.len() {
            self.allowed = self
                .checked
                .beyond(self.at)
                .ok_or_else(|| std::io::Error::other("the scan of the OBJ failed first"))?
                .min(self.text.len());
        }
        Ok(self.text.get(self.at..self.allowed).unwrap_or_default())
    }

    fn consume(&mut self, amount: usize) {
        if self.prefix.is_empty() {
            self.at = (self.at + amount).min(self.allowed);
        } else {
            self.prefix = self.prefix.get(amount..).unwrap_or_default();
        }
    }
}

/// One line of an OBJ: its index (from 0), its first byte's offset in the file, and its
/// text without the line's end.
#[derive(Clone, Copy)]
struct Line<'t> {
    index: usize,
    start: usize,
    text: &'t str,
}

impl Line<'_> {
    /// The file offset of `token`, a slice of this line.
    fn at(&self, token: &str) -> usize {
        self.start + (token.as_ptr() as usize - self.text.as_ptr() as usize)
    }

    /// The column (from 1) of the line's first word, past any indentation.
    fn indent_column(&self) -> usize {
        self.text.len() - self.text.trim_start().len() + 1
    }
}

/// The scan's running state: what the lines so far have defined and gathered.
struct Scanner<'t> {
    file: &'t str,
    text: &'t str,
    base_dir: Option<&'t Path>,
    out: Scan,
    names: HashMap<&'t str, u32>,
    vertices: usize,
    texcoords: usize,
    normals: usize,
    skipped_short_faces: usize,
    /// The material of the last `usemtl`, and whether a run with it has been started.
    current_material: Option<u32>,
    run_started: bool,
}

/// Our pass over the text, publishing its progress to `checked` as it goes.
fn scan(
    file: &str,
    text: &str,
    base_dir: Option<&Path>,
    checked: &Checked,
) -> Result<Scan, ParseError> {
    let mut s = Scanner {
        file,
        text,
        base_dir,
        out: Scan {
            materials: Vec::new(),
            material_runs: Vec::new(),
            origins: Vec::new(),
            warnings: Vec::new(),
            triangles: 0,
            texcoords: TexCoords::default(),
            images: HashMap::new(),
        },
        names: HashMap::new(),
        vertices: 0,
        texcoords: 0,
        normals: 0,
        skipped_short_faces: 0,
        current_material: None,
        run_started: false,
    };
    let mut offset = 0usize;
    let mut published = 0usize;
    for (index, raw) in text.split_inclusive('\n').enumerate() {
        let start = offset;
        // Every line before this one is accepted.
        if start - published >= Checked::STEP {
            checked.publish(start);
            published = start;
        }
        offset += raw.len();
        let line = Line {
            index,
            start,
            text: raw.trim_end_matches(['\n', '\r']),
        };
        let mut words = line.text.split_whitespace();
        match words.next() {
            Some("v") => s.vertex(line, words)?,
            Some("f") => s.face(line, words)?,
            Some("usemtl") => s.usemtl(line)?,
            Some("mtllib") => s.mtllib(line)?,
            Some(kind @ ("vn" | "vt")) => s.normal_or_texcoord(line, kind, words)?,
            _ => {}
        }
    }
    if s.skipped_short_faces > 0 {
        s.out.warnings.push(format!(
            "{file}: skipped {} faces with fewer than three vertices (points and lines)",
            s.skipped_short_faces
        ));
    }
    Ok(s.out)
}

impl<'t> Scanner<'t> {
    /// An error at `token`, a slice of `line`.
    fn err(&self, line: Line<'t>, token: &str, msg: String) -> ParseError {
        ParseError::at_span(
            self.file,
            self.text,
            line.at(token),
            token.len().max(1),
            msg,
        )
    }

    /// An error at the end of `line`: what it should have held and does not.
    fn at_end(&self, line: Line<'t>, msg: impl Into<String>) -> ParseError {
        ParseError::at_offset(self.file, self.text, line.start + line.text.len(), msg)
    }

    /// `v x y z`: three finite numbers.
    fn vertex(
        &mut self,
        line: Line<'t>,
        mut words: std::str::SplitWhitespace<'t>,
    ) -> Result<(), ParseError> {
        for axis in ["x", "y", "z"] {
            let Some(w) = words.next() else {
                return Err(self.at_end(
                    line,
                    format!("expected the vertex's {axis} coordinate, found the end of the line"),
                ));
            };
            let v: f64 = w.parse().map_err(|_| {
                self.err(
                    line,
                    w,
                    format!("expected a number for the vertex's {axis} coordinate, found `{w}`"),
                )
            })?;
            if !v.is_finite() {
                return Err(self.err(
                    line,
                    w,
                    format!("expected a finite {axis} coordinate, found `{w}`"),
                ));
            }
        }
        self.vertices += 1;
        Ok(())
    }

    /// One corner `v[/vt[/vn]]` of a face: its indices checked against what is defined
    /// before the face, its texture coordinate's index kept.
    fn corner(&mut self, line: Line<'t>, w: &'t str) -> Result<(), ParseError> {
        self.out.texcoords.face.push(None);
        let index = w.split('/').next().unwrap_or("");
        let i: i64 = index
            .parse()
            .map_err(|_| self.err(line, w, format!("expected a vertex index, found `{w}`")))?;
        let vertices = self.vertices;
        let ok = if i > 0 {
            (i as u64) <= vertices as u64
        } else {
            i != 0 && i.unsigned_abs() <= vertices as u64
        };
        if !ok {
            return Err(self.err(
                line,
                w,
                format!(
                    "vertex index {i} does not exist: {vertices} vertices are defined before this face (indices count from 1, negative ones from the end)"
                ),
            ));
        }
        // tobj 4.0.5 turns a texture or normal index of 0, or a negative one that reaches
        // before the first, into an index near 2^64 and overflows on it (a panic with
        // overflow checks); positive ones it bounds-checks itself.
        let mut parts = w.split('/').skip(1);
        for (what, defined) in [
            ("texture coordinate", self.texcoords),
            ("normal", self.normals),
        ] {
            let Some(part) = parts.next().filter(|p| !p.is_empty()) else {
                continue;
            };
            let i: i64 = part.parse().map_err(|_| {
                self.err(
                    line,
                    w,
                    format!("expected a {what} index in `{w}`, found `{part}`"),
                )
            })?;
            if i == 0 || (i < 0 && i.unsigned_abs() > defined as u64) {
                return Err(self.err(
                    line,
                    w,
                    format!(
                        "{what} index {i} does not exist: {defined} are defined before this face (indices count from 1, negative ones from the end)"
                    ),
                ));
            }
            if what == "texture coordinate" {
                self.out.texcoords.corner(i);
            }
        }
        Ok(())
    }

    /// `f` and its corners: a fan of `n − 2` triangles, in the current material's run,
    /// located at the face's line and column (a run of one-triangle lines shares one
    /// origin); fewer than three corners (a point or a line) skipped and counted.
    fn face(
        &mut self,
        line: Line<'t>,
        words: std::str::SplitWhitespace<'t>,
    ) -> Result<(), ParseError> {
        let mut n = 0usize;
        for w in words {
            self.corner(line, w)?;
            n += 1;
        }
        let out = &mut self.out;
        if n < 3 {
            out.texcoords.face.clear();
            self.skipped_short_faces += 1;
            return Ok(());
        }
        out.texcoords.end_face(out.triangles);
        let Ok(first) = u32::try_from(out.triangles) else {
            return Err(self.err(
                line,
                line.text,
                "more than 2^32 triangles in one OBJ".into(),
            ));
        };
        if !self.run_started {
            out.material_runs.push(MaterialRun {
                first_triangle: out.triangles,
                material: self.current_material,
            });
            self.run_started = true;
        }
        // The face's column: where its `f` is (past any indentation).
        let column = u32::try_from(line.indent_column()).unwrap_or(u32::MAX);
        let line_no = u32::try_from(line.index + 1).unwrap_or(u32::MAX);
        // A triangle on the line after the last one of a run of triangles, at the same
        // column, continues that run.
        let follows = n == 3
            && out.origins.last().is_some_and(|o| {
                o.lines_follow
                    && o.column == column
                    && u64::from(o.line) + u64::from(first - o.first_triangle) == u64::from(line_no)
            });
        if !follows {
            out.origins.push(Origin {
                first_triangle: first,
                line: line_no,
                column,
                part: None,
                lines_follow: n == 3,
            });
        }
        out.triangles += n - 2;
        Ok(())
    }

    /// `usemtl NAME`: the material of the faces that follow, numbered by first use.
    fn usemtl(&mut self, line: Line<'t>) -> Result<(), ParseError> {
        let name = line.text.trim_start()["usemtl".len()..].trim();
        if name.is_empty() {
            return Err(self.at_end(line, "expected a material name after `usemtl`"));
        }
        let index = if let Some(&index) = self.names.get(name) {
            index
        } else {
            let Ok(index) = u32::try_from(self.out.materials.len()) else {
                return Err(self.err(
                    line,
                    name,
                    "more than 2^32 material names in one OBJ".into(),
                ));
            };
            self.names.insert(name, index);
            self.out.materials.push(MaterialUse {
                name: name.to_owned(),
                id: None,
                first_use: Location {
                    file: self.file.to_owned(),
                    line: Some(line.index + 1),
                    column: Some(line.indent_column()),
                    part: None,
                },
                image: None,
                embedded_image: None,
            });
            index
        };
        if self.current_material != Some(index) {
            self.current_material = Some(index);
            self.run_started = false;
        }
        Ok(())
    }

    /// `mtllib NAME`: the library checked, and the image each of its materials names.
    fn mtllib(&mut self, line: Line<'t>) -> Result<(), ParseError> {
        let name = line.text.trim_start()["mtllib".len()..].trim();
        let images = check_mtl(
            self.file,
            self.text,
            line.at(name),
            name,
            self.base_dir,
            &mut self.out.warnings,
        )?;
        for (material, image) in images {
            self.out.images.entry(material).or_insert(image);
        }
        Ok(())
    }

    /// `vn x y z` or `vt u v [w]`: what tobj requires (and otherwise reports at 1:1), a
    /// texture coordinate's u and v kept.
    fn normal_or_texcoord(
        &mut self,
        line: Line<'t>,
        kind: &str,
        words: std::str::SplitWhitespace<'t>,
    ) -> Result<(), ParseError> {
        let (need, what) = if kind == "vt" {
            self.texcoords += 1;
            (2, "a texture coordinate (u v)")
        } else {
            self.normals += 1;
            (3, "a normal (x y z)")
        };
        let mut found = 0;
        let mut uv = [0.0; 2];
        for w in words.take(need) {
            let Ok(x) = w.parse::<f64>() else {
                return Err(self.err(line, w, format!("expected a number, found `{w}`")));
            };
            if kind == "vt" && !x.is_finite() {
                return Err(self.err(line, w, format!("expected a finite number, found `{w}`")));
            }
            if let Some(slot) = uv.get_mut(found) {
                *slot = x;
            }
            found += 1;
        }
        if kind == "vt" {
            self.out.texcoords.values.push(uv);
        }
        if found < need {
            return Err(self.at_end(
                line,
                format!("expected {need} numbers after `{kind}` for {what}, found {found}"),
            ));
        }
        Ok(())
    }
}

/// An `mtllib` must be a local relative file that stays in the OBJ's directory. It is
/// parsed when present, so that a broken MTL is reported; its colours mean nothing in the
/// thermal band, but the image each material's `map_Kd` names is returned (material name,
/// image path relative to the OBJ's folder), checked as the `mtllib` is: relative to the
/// MTL's folder, and never out of the OBJ's.
fn check_mtl(
    file: &str,
    text: &str,
    offset: usize,
    name: &str,
    base_dir: Option<&Path>,
    warnings: &mut Vec<String>,
) -> Result<Vec<(String, String)>, ParseError> {
    let refused = |why| {
        ParseError::at_span(
            file,
            text,
            offset,
            name.len().max(1),
            format!("mtllib `{name}`: {why}"),
        )
    };
    let path = super::gltf_read::local_relative_path(name).map_err(refused)?;
    let Some(dir) = base_dir else {
        warnings.push(format!(
            "{file}: mtllib `{name}` not read (the OBJ came from standard input); material names come from `usemtl`"
        ));
        return Ok(Vec::new());
    };
    let full = super::gltf_read::inside(dir, &path, name).map_err(refused)?;
    match crate::file::read_file(&full) {
        Ok(bytes) => {
            let mtl_name = full.display().to_string();
            let mtl_text = crate::canonical::utf8(&mtl_name, &bytes)?;
            check_mtl_lines(&mtl_name, mtl_text)?;
            let mut reader = std::io::BufReader::new(bytes.as_slice());
            let (materials, _) = tobj::load_mtl_buf(&mut reader).map_err(|e| {
                ParseError::at_offset(&mtl_name, mtl_text, 0, format!("malformed MTL: {e}"))
            })?;
            let mtl_dir = path.parent().unwrap_or(Path::new(""));
            materials
                .into_iter()
                .filter_map(|m| m.diffuse_texture.map(|image| (m.name, image)))
                .map(|(material, image)| {
                    let refused = |why: String| {
                        let at = mtl_text.find(image.as_str()).unwrap_or(0);
                        ParseError::at_span(&mtl_name, mtl_text, at, image.len().max(1), why)
                    };
                    let rel = super::gltf_read::local_relative_path(&image)
                        .map(|p| mtl_dir.join(p))
                        .map_err(|why| refused(format!("map_Kd {why}")))?;
                    super::gltf_read::inside(dir, &rel, &image)
                        .map_err(|why| refused(format!("map_Kd {why}")))?;
                    Ok((material, super::slash_path(&rel)))
                })
                .collect()
        }
        Err(_) => {
            warnings.push(format!(
                "{file}: mtllib `{name}` not found at {}; material names come from `usemtl`",
                full.display()
            ));
            Ok(Vec::new())
        }
    }
}

/// Checks every MTL line tobj parses, as tobj reads it, and says where the first bad one
/// is (at the value, or at the key when a value is missing): tobj reports only "material parse error" with no line (and tobj 4.0 panics on a
/// colour line with fewer than three values). Colours and textures mean nothing in the
/// thermal band, but a file that breaks its own syntax is refused, not half-read.
fn check_mtl_lines(mtl_name: &str, text: &str) -> Result<(), ParseError> {
    let mut offset = 0;
    for raw in text.split_inclusive('\n') {
        let line_start = offset;
        offset += raw.len();
        let line = raw.trim_end_matches(['\n', '\r']);
        let at = |token: &str| line_start + (token.as_ptr() as usize - line.as_ptr() as usize);
        let err = |token: &str, msg: String| {
            ParseError::at_span(mtl_name, text, at(token), token.len().max(1), msg)
        };
        let mut words = line.split_whitespace();
        let Some(key) = words.next() else { continue };
        let numbers = match key {
            "Ka" | "Kd" | "Ks" | "Ke" => 3,
            "Ns" | "Ni" | "d" => 1,
            "newmtl" | "map_Ka" | "map_Kd" | "map_Ks" | "map_Bump" | "map_bump" | "map_Ns"
            | "map_ns" | "map_NS" | "bump" | "map_d" => {
                if line.trim_start()[key.len()..].trim().is_empty() {
                    let what = if key == "newmtl" {
                        "a material name"
                    } else {
                        "a texture file name"
                    };
                    return Err(err(key, format!("expected {what} after `{key}`")));
                }
                continue;
            }
            "illum" => {
                let Some(w) = words.next() else {
                    return Err(err(
                        key,
                        "expected an illumination model (0 to 255) after `illum`".into(),
                    ));
                };
                if w.parse::<u8>().is_err() {
                    return Err(err(
                        w,
                        format!("expected an illumination model (0 to 255), found `{w}`"),
                    ));
                }
                continue;
            }
            _ => continue,
        };
        for k in 0..numbers {
            let Some(w) = words.next() else {
                let what = if numbers == 3 {
                    "three numbers (r g b)"
                } else {
                    "a number"
                };
                return Err(err(
                    key,
                    format!("malformed MTL: expected {what} after `{key}`, found {k}"),
                ));
            };
            match w.parse::<f64>() {
                Ok(v) if v.is_finite() => {}
                Ok(_) => {
                    return Err(err(
                        w,
                        format!("expected a finite number after `{key}`, found `{w}`"),
                    ));
                }
                Err(_) => {
                    return Err(err(
                        w,
                        format!("expected a number after `{key}`, found `{w}`"),
                    ));
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
