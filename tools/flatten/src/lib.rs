//! `irsig-flatten`: a scene and its objects in, a world-space raw scene out.
//!
//! The scene is canonical RON ([`irsig_model::Scene`]) or the 1990 scene file (object name
//! and nine values, optional temperature; `irsig_formats::legacy::scene`), told apart by
//! the extension (`.ron` is RON) or `--scene-format`. A legacy scene's translations are in
//! its length unit, `--legacy-unit` (km unless given, the 1990 data's). An object file that
//! starts with the
//! binary object's magic `IRSIGOBJ` or whose name ends in `.bin` is a binary canonical
//! object, one ending in `.ron` a RON canonical object (standard input is either, told by
//! the magic); any other is a legacy facet file read in `--legacy-unit`, whose material
//! indices are material ids. Each placement's object file is
//! read relative to the scene file's directory (the working directory when the scene comes
//! from standard input); `--object NAME=PATH` replaces the file a placement names by
//! another path or by `-` (standard input), which lets `irsig-import` feed it through a
//! pipe. The transform order, temperatures and overrides are those of
//! [`irsig_scene::flatten`].
//!
//! The raw scene is written in the compact binary form by default (fast at millions of
//! triangles, see `formats/canonical/raw-scene.md`), or as RON with `--ron`.
//!
//! ```text
//! irsig-flatten scene.ron -o scene.raw
//! irsig-import car.obj --materials m.ron | irsig-flatten scene.ron --object car.ron=- -o scene.raw
//! ```
//!
//! In that pipe `irsig-import` writes the binary object, which is what makes a
//! million-triangle import and flatten take about a second instead of six.

// A closed stderr must not panic the tool: notes go through `irsig_cli::note!`.
#![warn(clippy::print_stderr)]

use std::collections::HashMap;
use std::io::IsTerminal as _;
use std::path::{Path, PathBuf};

use clap::{Parser, ValueEnum};
use irsig_cli::args::LegacyUnitArgs;
use irsig_cli::args::inputs::Materials;
use irsig_cli::args::outputs::{Output, Ron};
use irsig_model::{Facet, LengthUnit, MaterialId, MaterialLibrary, Object, Placement, Scene};
use miette::miette;

/// The scene file forms.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SceneFormat {
    /// Canonical RON.
    Ron,
    /// The 1990 scene file: object name, nine values, optional temperature.
    Legacy,
}

/// Command line of `irsig-flatten`.
#[derive(Debug, Parser)]
#[command(
    name = "irsig-flatten",
    version,
    about = "Scene + objects -> world-space raw scene (binary by default, or RON)",
    after_help = "Examples:\n  irsig-flatten scene.ron -o scene.raw\n  irsig-flatten scene.ron --ron > scene.raw.ron\n  irsig-import car.obj --materials m.ron | irsig-flatten scene.ron --object car.ron=- -o scene.raw\n\n\
Each vertex p of a placed object goes to T + R(S p): scale, then the rotation\n\
R = Rz Ry Rx (about world x first, then y, then z, degrees), then the translation.\n\
A mirroring scale reverses the winding. A facet keeps its own temperature, else takes\n\
the placement's temperature_k; overrides then apply in order.",
    mut_arg("legacy_unit", |a| a.alias("unit")),
    mut_arg("materials", |a| a.help(
        "Check that every facet's material id is in this material library"
    )),
    mut_arg("ron", |a| a.help("Write RON instead of the binary raw scene")),
    mut_arg("output", |a| a.help("Output file (default: standard output)")),
)]
pub struct Cli {
    /// The scene file (canonical RON), or `-` for standard input.
    pub scene: String,
    /// Read the object a placement names from PATH instead (`-` for standard input).
    /// NAME is the `object` path exactly as the scene writes it. The object may be RON or
    /// binary (`IRSIGOBJ`, what `irsig-import` writes into a pipe). Repeatable.
    #[arg(long = "object", value_name = "NAME=PATH")]
    pub objects: Vec<String>,
    /// The scene's form; by default `.ron` files (and stdin) are RON, others legacy.
    #[arg(long, value_enum)]
    pub scene_format: Option<SceneFormat>,
    /// `--legacy-unit`: of a legacy scene's translations and legacy facet files.
    #[command(flatten)]
    pub unit: LegacyUnitArgs,
    /// `--materials FILE`: checked against.
    #[command(flatten)]
    pub materials: Materials,
    /// `--ron`.
    #[command(flatten)]
    pub ron: Ron,
    /// `-o PATH`.
    #[command(flatten)]
    pub output: Output,
}

/// The flags' own rules are clap's and the run's: nothing more is checked before a file
/// is read.
impl irsig_cli::CheckArgs for Cli {}

/// Runs `irsig-flatten`.
///
/// # Errors
/// Bad usage (exit 2), or an unreadable, malformed or inconsistent input (exit 1).
pub fn run(cli: Cli) -> miette::Result<()> {
    let to_stdout = cli
        .output
        .path
        .as_ref()
        .is_none_or(|p| p.as_os_str() == "-");
    if !cli.ron.on && to_stdout && std::io::stdout().is_terminal() {
        return Err(irsig_cli::usage_error(
            "the binary raw scene would go to a terminal; give -o FILE, redirect, or use --ron",
        ));
    }
    let replacements = object_replacements(&cli)?;
    let scene_input = irsig_cli::read_input(&cli.scene)?;
    let (scene_file, scene) = SceneFile::read(&cli, &scene_input)?;
    for name in replacements.keys() {
        if !scene.objects.iter().any(|p| &p.object == name) {
            return Err(irsig_cli::usage_error(format!(
                "--object `{}` matches no placement in {}",
                name.display(),
                scene_input.name
            )));
        }
    }
    let base = scene_input.base_dir();
    // The file each placement's object was read from.
    let sources: Vec<String> = scene
        .objects
        .iter()
        .map(|p| match replacements.get(&p.object) {
            Some(path) => path.clone(),
            None => resolve(&base, &p.object),
        })
        .collect();
    // The scene, the library and every object file the scene names are inputs.
    let inputs = [cli.scene.as_str()]
        .into_iter()
        .map(PathBuf::from)
        .chain(cli.materials.file.iter().map(PathBuf::from))
        .chain(sources.iter().map(PathBuf::from));
    irsig_cli::refuse_output_is_input(inputs, cli.output.path.iter())?;
    let loaded = load_objects(&scene, &sources, &scene_file, cli.unit.unit())?;
    let objects: Vec<&Object> = scene
        .objects
        .iter()
        .filter_map(|p| loaded.get(&p.object))
        .collect();
    let raw = irsig_scene::flatten(&scene, &objects).map_err(|e| {
        // A rule of the scene itself is at its own value; anything else at the placement.
        let path = match (&e.kind, e.placement) {
            (irsig_scene::FlattenErrorKind::Model(m), None) => Some(m.path.clone()),
            _ => None,
        };
        scene_file.at(e.placement, path.as_deref(), e.to_string())
    })?;
    if let Some(path) = &cli.materials.file {
        let terrain_at = |message| scene_file.at(None, Some("terrain.material"), message);
        check_materials(Path::new(path), &raw, terrain_at, |r, message| {
            facet_material_error(&raw, &objects, &sources, &scene_file, r, message)
        })?;
    }
    irsig_cli::write_output(cli.output.path.as_deref(), |w| {
        if cli.ron.on {
            irsig_formats::canonical::write_ron(&raw, w)
        } else {
            irsig_formats::canonical::binary::write(&raw, w)
        }
    })
}

/// The `--object NAME=PATH` flags, by NAME; standard input may feed only one of them and
/// the scene.
fn object_replacements(cli: &Cli) -> miette::Result<HashMap<PathBuf, String>> {
    let mut replacements: HashMap<PathBuf, String> = HashMap::new();
    for spec in &cli.objects {
        let (name, path) = spec.split_once('=').ok_or_else(|| {
            irsig_cli::usage_error(format!("--object expects NAME=PATH, found `{spec}`"))
        })?;
        if replacements
            .insert(PathBuf::from(name), path.to_owned())
            .is_some()
        {
            return Err(irsig_cli::usage_error(format!(
                "--object `{name}` is given twice"
            )));
        }
    }
    let stdin_uses =
        usize::from(cli.scene == "-") + replacements.values().filter(|p| *p == "-").count();
    if stdin_uses > 1 {
        return Err(irsig_cli::usage_error(
            "standard input (`-`) can feed only one of the scene and the objects",
        ));
    }
    Ok(replacements)
}

/// The scene file as read: its text and form, to point errors at its placements and
/// values.
struct SceneFile<'a> {
    input: &'a irsig_cli::Input,
    format: SceneFormat,
    text: String,
    /// For a legacy scene, where each entry starts.
    entry_positions: Vec<irsig_formats::legacy::Position>,
}

impl<'a> SceneFile<'a> {
    /// Reads the scene of `input`, in the form `--scene-format` gives or its name tells.
    fn read(cli: &Cli, input: &'a irsig_cli::Input) -> miette::Result<(Self, Scene)> {
        let format = cli.scene_format.unwrap_or_else(|| {
            if cli.scene == "-" || cli.scene.ends_with(".ron") {
                SceneFormat::Ron
            } else {
                SceneFormat::Legacy
            }
        });
        match format {
            SceneFormat::Ron => {
                let scene: Scene =
                    irsig_formats::canonical::from_ron_bytes(&input.name, &input.bytes)?;
                let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?.to_owned();
                let file = Self {
                    input,
                    format,
                    text,
                    entry_positions: Vec::new(),
                };
                Ok((file, scene))
            }
            SceneFormat::Legacy => {
                let text = irsig_formats::legacy::decode(&input.name, &input.bytes)?;
                let file = irsig_formats::legacy::scene::parse(&input.name, text)?;
                let text = text.to_owned();
                let metres = cli.unit.unit().metres();
                let entry_positions = file.entries.iter().map(|e| e.position).collect();
                let scene = Scene {
                    objects: file
                        .entries
                        .into_iter()
                        .map(|e| Placement {
                            object: PathBuf::from(e.object),
                            rotation_deg: e.rotation_deg,
                            translation_m: e.translation.map(|t| t * metres),
                            scale: e.scale,
                            temperature_k: e.temperature_k,
                            overrides: Vec::new(),
                        })
                        .collect(),
                    ..Scene::default()
                };
                let file = Self {
                    input,
                    format,
                    text,
                    entry_positions,
                };
                Ok((file, scene))
            }
        }
    }

    /// An error about placement `i` (or the scene value at a model `path`), at its line
    /// and column in the scene file.
    fn at(&self, i: Option<usize>, path: Option<&str>, message: String) -> miette::Report {
        let name = &self.input.name;
        let i = i.or_else(|| path.and_then(|p| index_in(p, "objects")));
        match self.format {
            SceneFormat::Ron => {
                let path = path.map_or_else(
                    || i.map(|i| format!("objects[{i}]")),
                    |p| Some(p.to_owned()),
                );
                match path {
                    Some(p) => miette::Report::new(irsig_formats::canonical::error_at_path(
                        name, &self.text, &p, message,
                    )),
                    None => miette!("{name}: {message}"),
                }
            }
            SceneFormat::Legacy => match i.and_then(|i| self.entry_positions.get(i)) {
                Some(p) => miette::Report::new(irsig_formats::ParseError::at_line_column(
                    name.clone(),
                    &self.text,
                    p.line,
                    p.column,
                    message,
                )),
                None => miette!("{name}: {message}"),
            },
        }
    }
}

/// Reads the object of each placement from its file (`sources`, one per placement; a
/// legacy facet file in `unit`), each distinct object once however many placements use
/// it.
fn load_objects(
    scene: &Scene,
    sources: &[String],
    scene_file: &SceneFile<'_>,
    unit: LengthUnit,
) -> miette::Result<HashMap<PathBuf, Object>> {
    let mut loaded: HashMap<PathBuf, Object> = HashMap::new();
    for (i, placement) in scene.objects.iter().enumerate() {
        if loaded.contains_key(&placement.object) {
            continue;
        }
        let source = sources[i].clone();
        let input = irsig_cli::read_input(&source).map_err(|e| {
            let why: Vec<String> = e.chain().map(ToString::to_string).collect();
            scene_file.at(
                Some(i),
                (scene_file.format == SceneFormat::Ron)
                    .then(|| format!("objects[{i}].object"))
                    .as_deref(),
                format!(
                    "cannot read the object `{}`: {}",
                    placement.object.display(),
                    why.join(": ")
                ),
            )
        })?;
        let object = if source == "-"
            || source.ends_with(".ron")
            || source.ends_with(".bin")
            || irsig_formats::canonical::binary_object::is_binary(&input.bytes)
        {
            irsig_formats::canonical::read_object(&input.name, &input.bytes)?
        } else {
            legacy_object(&input, unit)?
        };
        loaded.insert(placement.object.clone(), object);
    }
    Ok(loaded)
}

/// An error about raw facet `r`'s material, where that material was given: in its object
/// file, unless an override of the placement changed it.
fn facet_material_error(
    raw: &irsig_model::RawScene,
    objects: &[&Object],
    sources: &[String],
    scene_file: &SceneFile<'_>,
    r: usize,
    message: String,
) -> miette::Report {
    let i = raw.facets[r].object as usize;
    let first: usize = objects[..i].iter().map(|o| o.facets.len()).sum();
    let k = r - first;
    let from_object = objects[i].facets.get(k).map(|f| f.material) == Some(raw.facets[r].material);
    let source = &sources[i];
    if from_object && source != "-" {
        if let Ok(input) = irsig_cli::read_input(source) {
            return miette::Report::new(irsig_formats::canonical::object_error_at_path(
                &input.name,
                &input.bytes,
                objects[i],
                &format!("facets[{k}].material"),
                message,
            ));
        }
    }
    scene_file.at(Some(i), None, message)
}

/// A legacy facet file as a canonical object: coordinates from `unit` to metres, material
/// indices as ids, facet temperatures kept. Checked here, so that a bad facet is reported
/// at its line.
fn legacy_object(input: &irsig_cli::Input, unit: LengthUnit) -> miette::Result<Object> {
    let mesh = irsig_formats::mesh::read_legacy_object(&input.name, &input.bytes)?;
    let metres = unit.metres();
    let object = Object {
        name: Path::new(&input.name)
            .file_stem()
            .map_or_else(|| "object".to_owned(), |s| s.to_string_lossy().into_owned()),
        source: format!("legacy facet file {} (unit {unit:?})", input.name),
        positions_m: mesh
            .positions
            .iter()
            .map(|p| p.map(|c| c * metres))
            .collect(),
        facets: mesh
            .triangles
            .iter()
            .map(|t| Facet {
                vertices: t.vertices,
                material: MaterialId(
                    t.material
                        .and_then(|m| mesh.materials.get(m as usize))
                        .and_then(|m| m.id)
                        .unwrap_or(0),
                ),
                temperature_k: t.temperature_k,
                uv: None,
            })
            .collect(),
    };
    object
        .validate()
        .map_err(|e| miette!("{}: {}: {}", mesh.locate(&e.path), e.path, e.kind))?;
    Ok(object)
}

fn resolve(base: &Path, object: &Path) -> String {
    if object.is_absolute() {
        object.to_string_lossy().into_owned()
    } else {
        base.join(object).to_string_lossy().into_owned()
    }
}

fn check_materials(
    path: &Path,
    raw: &irsig_model::RawScene,
    terrain_at: impl Fn(String) -> miette::Report,
    at: impl Fn(usize, String) -> miette::Report,
) -> miette::Result<()> {
    let input = irsig_cli::read_input(path)?;
    let library: MaterialLibrary =
        irsig_formats::canonical::from_ron_bytes(&input.name, &input.bytes)?;
    if let Some(m) = raw.terrain.material
        && library.by_id(m).is_none()
    {
        return Err(terrain_at(format!(
            "the terrain's material is {}, which {} does not define",
            m.0, input.name
        )));
    }
    for (i, f) in raw.facets.iter().enumerate() {
        if library.by_id(f.material).is_none() {
            let object = raw
                .objects
                .get(f.object as usize)
                .map_or("?", String::as_str);
            // Reported where the facet's material was given.
            return Err(at(
                i,
                format!(
                    "object `{object}`: raw facet {i} has material id {}, which {} does not define",
                    f.material.0, input.name
                ),
            ));
        }
    }
    Ok(())
}

/// `i` of a model path `field[i]...`.
fn index_in(path: &str, field: &str) -> Option<usize> {
    let rest = path.strip_prefix(field)?.strip_prefix('[')?;
    rest[..rest.find(']')?].parse().ok()
}
