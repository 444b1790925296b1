//! `irsig-import`: a mesh file in, a canonical irsig object (RON or binary) out.
//!
//! Reads the 1990 Intergraph-derived facet file (`.fac`, `irsig_formats::legacy::object`),
//! Wavefront OBJ (+ MTL) and glTF 2.0 / GLB (`irsig_formats::mesh`), converts
//! lengths to metres (`--legacy-unit`, then `--scale`), maps every facet's material name to an id
//! through a material library, and writes an [`irsig_model::Object`]. A facet whose
//! material the library does not know is an error that names the material and where it is
//! first used, unless `--default-material` names the material to use instead. A facet
//! file numbers its materials instead of naming them: its material index is the library's
//! material id (a library converted from the 1990 material index file keeps its numbers).
//! Facet temperatures in a facet file (an irsig extension) are kept. glTF is +Y up (glTF
//! 2.0 §3.4) and irsig +Z up: glTF positions are turned to +Z up unless `--keep-axes`.
//! The image a material's texture names is reported for a material map to name; one a
//! glTF carries inside its file is written out with `--images DIR` ([`images`]).
//!
//! The object is written in one of its two forms (`formats/canonical/object.md`): the
//! compact binary form when the output goes to another program (standard output is a
//! pipe) or to a file whose name ends in `.bin`, and RON otherwise (a terminal, a file a
//! shell redirection made, any other file name), because RON is what a person opens and a
//! million-triangle RON object costs seconds to write and read again. `--binary` and
//! `--ron` override the choice. Every object reader accepts both.
//!
//! ```text
//! irsig-import car.obj --materials materials.ron -o car.ron
//! irsig-import hand.glb --materials materials.ron --default-material skin | irsig-flatten scene.ron --object hand.ron=-
//! ```

// A closed stderr must not panic the tool: notes go through `irsig_cli::note!`.
#![warn(clippy::print_stderr)]

use std::path::Path;

use clap::{Parser, ValueEnum};
use irsig_cli::args::inputs::Materials;
use irsig_cli::args::outputs::{Name, Output, Ron};
use irsig_cli::args::{LegacyUnitArgs, ThreadsArgs};
use irsig_formats::mesh::{self, Mesh};
use irsig_model::{Facet, LengthUnit, MaterialId, MaterialLibrary, Object};
use miette::miette;

mod images;

/// The mesh formats `irsig-import` reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// The 1990 Intergraph-derived facet (object) file: material indices are library ids.
    Intergraph,
    /// Wavefront OBJ, with MTL files beside it.
    Obj,
    /// glTF 2.0, JSON (`.gltf`) or binary (`.glb`): the content tells which.
    Gltf,
    /// Binary glTF; the same reader as `gltf`.
    Glb,
}

/// Command line of `irsig-import`.
#[derive(Debug, Parser)]
#[command(
    name = "irsig-import",
    version,
    about = "Mesh file (Intergraph facet file, OBJ + MTL, glTF/GLB) -> canonical irsig object (RON, or binary into a pipe)",
    after_help = "Examples:\n  irsig-import vehicle.fac --materials materials.ron -o vehicle.ron\n  irsig-import car.obj --materials materials.ron -o car.ron\n  irsig-import tree.glb --materials materials.ron --default-material leaf --legacy-unit cm\n  cat car.obj | irsig-import - --mesh-format obj --materials materials.ron > car.ron\n\n\
Facet materials come from OBJ `usemtl` names and glTF material names (`material N` when\n\
unnamed), mapped to ids through --materials; a facet file's material indices are ids. Lengths are converted to metres: a facet\n\
file's from --legacy-unit (km, the 1990 data's, unless given), an OBJ's or glTF's from metres\n\
or from --legacy-unit when given; --scale multiplies on top.\n\n\
glTF is +Y up, irsig +Z up: glTF positions are turned (x, y, z) -> (x, -z, y), a rotation\n\
that keeps every front a front; --keep-axes keeps the file's axes.\n\n\
Output form: binary (IRSIGOBJ) into a pipe or to a file ending in .bin, RON otherwise\n\
(terminal, redirection to a file, other names); --binary or --ron to choose. Readers\n\
(irsig-flatten) take either form.",
    group(clap::ArgGroup::new("materials_required").args(["materials"]).required(true)),
    mut_arg("materials", |a| a.help(
        "The material library (canonical RON) that maps material names to ids"
    )),
    mut_arg("legacy_unit", |a| a.alias("unit").help(
        "Length unit of the mesh's coordinates: of a 1990 facet file km unless given (the \
         thesis's files); of an OBJ or glTF metres unless given (m, km, cm, mm, ft or in)"
    )),
    mut_arg("name", |a| a.help("The object's name (default: the file name without its extension)")),
    mut_arg("ron", |a| a.conflicts_with("binary").help(
        "Write RON (the default to a terminal, a redirected file or any non-`.bin` file)"
    )),
    mut_arg("output", |a| a.help("Output file (default: standard output)")),
)]
pub struct Cli {
    /// The mesh file, or `-` for standard input (then --mesh-format is required).
    pub input: String,
    /// The format; by default from the file extension (.fac, .obj, .gltf, .glb).
    #[arg(long, value_enum)]
    pub mesh_format: Option<Format>,
    /// `--materials FILE`.
    #[command(flatten)]
    pub materials: Materials,
    /// The material for facets whose material the library does not know or that have
    /// none. Without it those facets are an error.
    #[arg(long, value_name = "NAME")]
    pub default_material: Option<String>,
    /// `--legacy-unit`: of a facet file (km unless given), and of an OBJ or glTF when given.
    #[command(flatten)]
    pub unit: LegacyUnitArgs,
    /// An extra factor applied after the unit conversion.
    #[arg(long, default_value_t = 1.0)]
    pub scale: f64,
    /// `--name`: the object's.
    #[command(flatten)]
    pub name: Name,
    /// Write the binary object (the default into a pipe or to a `.bin` file).
    #[arg(long)]
    pub binary: bool,
    /// `--ron`.
    #[command(flatten)]
    pub ron: Ron,
    /// `-o PATH`.
    #[command(flatten)]
    pub output: Output,
    /// Keep a glTF's own axes. glTF is +Y up and irsig +Z up, so by default positions are
    /// turned by 90° about +X, (x, y, z) -> (x, -z, y): a rotation, so fronts stay fronts
    /// and what was up in the model is up in the scene. glTF and GLB only.
    #[arg(long)]
    pub keep_axes: bool,
    /// Refuse a mesh with zero-area triangles. By default they are dropped (no ray can hit
    /// them) with a warning that says how many and where the first few are.
    #[arg(long)]
    pub strict: bool,
    /// Write each image a glTF material's base colour carries inside the file (a GLB's
    /// buffer view, a `data:` URI) into DIR, made if absent, as `image-I-NAME` (its index
    /// and name) for a material map to name. Without it such an image is only reported.
    #[arg(long, value_name = "DIR")]
    pub images: Option<std::path::PathBuf>,
    /// `--threads N`: an OBJ's two passes run on two threads when there are two.
    #[command(flatten)]
    pub threads: ThreadsArgs,
}

/// Whether `irsig-import` writes the binary object: `--binary`/`--ron` when given, else
/// binary for a `.bin` output file, and for standard output when `stdout_is_pipe`.
#[must_use]
pub fn writes_binary(cli: &Cli, stdout_is_pipe: bool) -> bool {
    if cli.binary || cli.ron.on {
        return cli.binary;
    }
    match cli.output.path.as_deref() {
        Some(path) if path.as_os_str() != "-" => path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("bin")),
        _ => stdout_is_pipe,
    }
}

/// Runs `irsig-import`.
///
/// # Errors
/// Bad usage (exit 2), or an unreadable, malformed or inconsistent input (exit 1).
pub fn run(cli: Cli) -> miette::Result<()> {
    cli.threads.install(|| import(&cli))
}

fn import(cli: &Cli) -> miette::Result<()> {
    let materials = cli.materials.required()?;
    irsig_cli::refuse_output_is_input(
        [Path::new(&cli.input), Path::new(materials)],
        cli.output.path.iter(),
    )?;
    let format = flags_format(cli)?;
    let gltf = matches!(format, Format::Gltf | Format::Glb);
    let library = read_library(materials)?;
    let default = match &cli.default_material {
        Some(name) => Some(library.by_name(name).map(|m| m.id).ok_or_else(|| {
            irsig_cli::usage_error(format!(
                "--default-material `{name}` is not in {materials}; it has: {}",
                known_names(&library)
            ))
        })?),
        None => None,
    };
    let input = irsig_cli::read_input(&cli.input)?;
    let base_dir = input.path.as_ref().map(|_| input.base_dir());
    let mut mesh = match format {
        Format::Intergraph => mesh::read_legacy_object(&input.name, &input.bytes)?,
        Format::Obj => mesh::read_obj(&input.name, &input.bytes, base_dir.as_deref())?,
        Format::Gltf | Format::Glb => {
            mesh::read_gltf(&input.name, &input.bytes, base_dir.as_deref())?
        }
    };
    if gltf && !cli.keep_axes {
        mesh.y_up_to_z_up();
    }
    let embedded = images::take(&mut mesh);
    for w in &mesh.warnings {
        irsig_cli::note!("warning: {w}");
    }
    let name = cli.name.value.clone().unwrap_or_else(|| {
        std::path::Path::new(&input.name)
            .file_stem()
            .map_or_else(|| "object".to_owned(), |s| s.to_string_lossy().into_owned())
    });
    // The text and the mesh are dropped as soon as the object is built: the peak memory of
    // a million-triangle import is set by what is alive at once.
    drop(input);
    let object = to_object(mesh, &library, cli, default, name, format)?;
    // Before the object: it may go to a pipe whose reader has all it wants and closes it.
    images::write_or_report(&embedded, cli, [cli.input.as_str(), materials])?;
    let binary = writes_binary(cli, irsig_cli::stdout_is_pipe());
    irsig_cli::write_output(cli.output.path.as_deref(), |w| {
        if binary {
            irsig_formats::canonical::binary_object::write(&object, w)
        } else {
            irsig_formats::canonical::write_ron(&object, w)
        }
    })
}

/// The unit of the mesh's coordinates: a 1990 facet file's is the legacy unit (km unless
/// given); an OBJ's or glTF's is metres (glTF 2.0 §3.4; OBJ by custom) unless one is given.
fn mesh_unit(cli: &Cli, format: Format) -> LengthUnit {
    match format {
        Format::Intergraph => cli.unit.unit(),
        Format::Obj | Format::Gltf | Format::Glb => cli.unit.given.unwrap_or(LengthUnit::M),
    }
}

impl irsig_cli::CheckArgs for Cli {
    fn check_args(&self) -> miette::Result<()> {
        flags_format(self).map(drop)
    }
}

/// The mesh format the flags give, and their own rules: a positive finite scale, a format
/// for standard input, `--keep-axes` and `--images` for glTF only.
fn flags_format(cli: &Cli) -> miette::Result<Format> {
    if !(cli.scale.is_finite() && cli.scale > 0.0) {
        return Err(irsig_cli::usage_error(format!(
            "--scale must be a positive finite number, found {}",
            cli.scale
        )));
    }
    let format = match (cli.mesh_format, cli.input.as_str()) {
        (Some(f), _) => f,
        (None, "-") => {
            return Err(irsig_cli::usage_error(
                "reading standard input needs --mesh-format (intergraph, obj, gltf or glb)",
            ));
        }
        (None, path) => format_of(path)?,
    };
    if cli.keep_axes && !matches!(format, Format::Gltf | Format::Glb) {
        return Err(irsig_cli::usage_error(
            "--keep-axes is for glTF and GLB, whose axes are +Y up; other formats state no up \
             axis and are never turned",
        ));
    }
    if cli.images.is_some() && !matches!(format, Format::Gltf | Format::Glb) {
        return Err(irsig_cli::usage_error(
            "--images is for glTF and GLB, which can carry their images inside the file; an \
             OBJ's images are files already, named in the note of each material",
        ));
    }
    Ok(format)
}

fn format_of(path: &str) -> miette::Result<Format> {
    let ext = std::path::Path::new(path)
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("fac") => Ok(Format::Intergraph),
        Some("obj") => Ok(Format::Obj),
        Some("gltf") => Ok(Format::Gltf),
        Some("glb") => Ok(Format::Glb),
        _ => Err(irsig_cli::usage_error(format!(
            "cannot tell the format of `{path}` from its extension; give --mesh-format intergraph, obj, gltf or glb"
        ))),
    }
}

fn read_library(path: &str) -> miette::Result<MaterialLibrary> {
    let input = irsig_cli::read_input(path)?;
    Ok(irsig_formats::canonical::from_ron_bytes(
        &input.name,
        &input.bytes,
    )?)
}

fn known_names(library: &MaterialLibrary) -> String {
    let names: Vec<String> = library
        .materials
        .iter()
        .map(|m| format!("{} (id {})", m.name, m.id.0))
        .collect();
    if names.is_empty() {
        "no materials".into()
    } else {
        names.join(", ")
    }
}

fn to_object(
    mut mesh: Mesh,
    library: &MaterialLibrary,
    cli: &Cli,
    default: Option<MaterialId>,
    name: String,
    format: Format,
) -> miette::Result<Object> {
    let library_name = cli.materials.file.as_deref().unwrap_or_default();
    // Map each material name once.
    let mut ids = Vec::with_capacity(mesh.materials.len());
    for m in &mesh.materials {
        let found = match m.id {
            Some(id) => library.by_id(MaterialId(id)),
            None => library.by_name(&m.name),
        };
        let id = match (found, default) {
            (Some(found), _) => found.id,
            (None, Some(d)) => d,
            (None, None) => {
                return Err(miette!(
                    help = "add the material to the library, or name a default with --default-material NAME",
                    "{}: material `{}` is not in {library_name} (which has: {})",
                    m.first_use,
                    m.name,
                    known_names(library)
                ));
            }
        };
        if let Some(image) = &m.image {
            // What a material map of the library needs to lay the asset's texture on it.
            irsig_cli::note!(
                "{}: material `{}` (id {}) names the image `{image}`, relative to the model's folder",
                m.first_use,
                m.name,
                id.0
            );
        }
        ids.push(id);
    }
    let unit = mesh_unit(cli, format);
    let factor = unit.metres() * cli.scale;
    let mut facets = Vec::with_capacity(mesh.triangles.len());
    for (i, t) in mesh.triangles.iter().enumerate() {
        let material = match t.material.and_then(|m| ids.get(m as usize)) {
            Some(&id) => id,
            None => default.ok_or_else(|| {
                miette!(
                    help = "name a material for such facets with --default-material NAME",
                    "{}: facet {i} has no material",
                    mesh.triangle_location(i)
                )
            })?,
        };
        facets.push(Facet {
            vertices: t.vertices,
            material,
            temperature_k: t.temperature_k,
            uv: t.uv,
        });
    }
    let mut object = Object {
        name,
        source: format!(
            "irsig-import {} {} (unit {}, scale {}{})",
            format!("{format:?}").to_lowercase(),
            mesh.file,
            format!("{unit:?}").to_lowercase(),
            cli.scale,
            match format {
                Format::Gltf | Format::Glb if cli.keep_axes => ", the file's axes kept",
                Format::Gltf | Format::Glb => ", +Y up turned to +Z up",
                _ => "",
            }
        ),
        positions_m: std::mem::take(&mut mesh.positions),
        facets,
    };
    // Scaled in place: a million positions need not be copied.
    for p in &mut object.positions_m {
        *p = p.map(|c| c * factor);
    }
    let dropped = if cli.strict {
        Vec::new()
    } else {
        drop_zero_area(&mut object, &mesh)
    };
    object.validate().map_err(|e| {
        let at = mesh.locate(&mesh_path(&e.path, &dropped));
        miette!("{at}: {}: {}", e.path, e.kind)
    })?;
    Ok(object)
}

/// The model path `path` of an object whose facets `dropped` (the mesh's triangle indices,
/// ascending) were removed, spelled with the mesh's triangle index, so that an error is
/// located at the triangle's own line: facet `k` of the object is the mesh's `k`-th kept
/// triangle. Paths that name no facet are returned as they are.
fn mesh_path(path: &str, dropped: &[usize]) -> String {
    let Some((index, rest)) = path
        .strip_prefix("facets[")
        .and_then(|r| r.split_once(']'))
        .and_then(|(i, rest)| Some((i.parse::<usize>().ok()?, rest)))
    else {
        return path.to_owned();
    };
    let mut triangle = index;
    for &d in dropped {
        if d > triangle {
            break;
        }
        triangle += 1;
    }
    format!("facets[{triangle}]{rest}")
}

/// Removes the facets whose triangle has no area (what `Object::validate` calls degenerate)
/// and says on stderr how many and where the first few are. Facets with a non-finite
/// coordinate or a vertex index out of range are kept, for `validate` to refuse. Returns
/// the mesh's indices of the triangles dropped, ascending.
fn drop_zero_area(object: &mut Object, mesh: &Mesh) -> Vec<usize> {
    let positions = &object.positions_m;
    let mut dropped = Vec::new();
    let mut i = 0;
    object.facets.retain(|f| {
        let p = f.vertices.map(|v| positions.get(v as usize).copied());
        let zero = match p {
            [Some(a), Some(b), Some(c)] => {
                a.iter().chain(&b).chain(&c).all(|x| x.is_finite())
                    && irsig_model::triangle_is_degenerate(a, b, c)
            }
            _ => false,
        };
        if zero {
            dropped.push(i);
        }
        i += 1;
        !zero
    });
    if dropped.is_empty() {
        return dropped;
    }
    let first: Vec<String> = dropped
        .iter()
        .take(3)
        .map(|&i| mesh.triangle_location(i).to_string())
        .collect();
    irsig_cli::note!(
        "warning: dropped {} zero-area triangle{} of {} (no ray can hit them), the first at {}; \
         --strict refuses them",
        dropped.len(),
        if dropped.len() == 1 { "" } else { "s" },
        dropped.len() + object.facets.len(),
        first.join(", ")
    );
    dropped
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_error_after_a_drop_names_the_meshs_triangle() {
        // Triangles 1 and 2 dropped: the object's facets 0, 1, 2 are the mesh's 0, 3, 4.
        let dropped = [1, 2];
        assert_eq!(
            mesh_path("facets[0].material", &dropped),
            "facets[0].material"
        );
        assert_eq!(mesh_path("facets[1]", &dropped), "facets[3]");
        assert_eq!(
            mesh_path("facets[2].vertices[1]", &dropped),
            "facets[4].vertices[1]"
        );
        assert_eq!(mesh_path("facets[1]", &[0, 1, 5]), "facets[3]");
        assert_eq!(
            mesh_path("positions_m[3][2]", &dropped),
            "positions_m[3][2]"
        );
        assert_eq!(mesh_path("facets[x]", &dropped), "facets[x]");
    }

    #[test]
    fn formats_come_from_extensions() {
        assert_eq!(format_of("a/B.OBJ").unwrap(), Format::Obj);
        assert_eq!(format_of("x.glb").unwrap(), Format::Glb);
        assert!(format_of("x.stl").is_err());
    }

    #[test]
    fn the_output_form_follows_flags_then_file_name_then_pipe() {
        let cli = |args: &[&str]| {
            let mut all = vec!["irsig-import", "car.obj", "--materials", "m.ron"];
            all.extend_from_slice(args);
            Cli::try_parse_from(all).unwrap()
        };
        assert!(writes_binary(&cli(&[]), true));
        assert!(!writes_binary(&cli(&[]), false));
        assert!(writes_binary(&cli(&["-o", "-"]), true));
        assert!(writes_binary(&cli(&["-o", "car.BIN"]), false));
        assert!(!writes_binary(&cli(&["-o", "car.ron"]), true));
        assert!(!writes_binary(&cli(&["-o", "car"]), true));
        assert!(!writes_binary(&cli(&["--ron"]), true));
        assert!(writes_binary(&cli(&["--binary", "-o", "car.ron"]), false));
        assert!(
            Cli::try_parse_from([
                "irsig-import",
                "x.obj",
                "--materials",
                "m.ron",
                "--ron",
                "--binary"
            ])
            .is_err()
        );
    }
}
