//! The pipeline file as written: stages and sweeps with the position of every value, before
//! templates are expanded and files are looked at.

use std::collections::BTreeMap;

use crate::error::{ErrorKind, PipelineError};
use irsig_formats::ron_tree::{Key, Kind, Node};

/// A value with the byte range of its text in the pipeline file.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Spanned<T> {
    pub value: T,
    pub start: usize,
    pub end: usize,
}

impl<T> Spanned<T> {
    fn new(value: T, node: &Node) -> Self {
        Self {
            value,
            start: node.start,
            end: node.end,
        }
    }
}

/// The pipeline file and its name, for located errors.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Source<'a> {
    pub file: &'a str,
    pub text: &'a str,
}

impl Source<'_> {
    pub fn error(
        &self,
        kind: ErrorKind,
        start: usize,
        end: usize,
        message: impl Into<String>,
    ) -> PipelineError {
        PipelineError::at(
            kind,
            self.file,
            self.text,
            start,
            end.saturating_sub(start),
            message,
        )
    }

    fn structure(&self, node: &Node, message: impl Into<String>) -> PipelineError {
        self.error(ErrorKind::Structure, node.start, node.end, message)
    }

    /// 1-based line of a byte offset, for messages that mention another place in the file.
    pub fn line(&self, offset: usize) -> usize {
        irsig_formats::line_column(self.text, offset).0
    }
}

#[derive(Debug, Clone)]
pub(crate) struct PipelineSpec {
    pub stages: Vec<StageSpec>,
    pub sweeps: BTreeMap<String, SweepSpec>,
    /// The pipeline's `sun`, read and checked; given to the stages when they are planned,
    /// as the tools spell it.
    pub sun: Option<crate::sun::PipelineSun>,
}

/// A flag and the file it names: `"o": "out.ron"`.
pub(crate) type FlagFile = (Spanned<String>, Spanned<String>);

#[derive(Debug, Clone)]
pub(crate) struct StageSpec {
    pub name: Option<Spanned<String>>,
    /// The tool, possibly followed by subcommand words: `"atmos convert"`.
    pub tool: Spanned<String>,
    /// Positional input files, in order.
    pub args: Vec<Spanned<String>>,
    /// Input files given by flag: `{"materials": "m.ron"}` -> `--materials m.ron`.
    pub inputs: Vec<FlagFile>,
    /// Files the tool reads that its command line does not name (the objects a scene file
    /// lists): inputs for ordering, up-to-date checks and Makefile prerequisites, never
    /// words of the command.
    pub reads: Vec<Spanned<String>>,
    /// Output files given by flag: `{"o": "out.exr"}` -> `-o out.exr`.
    pub outputs: Vec<FlagFile>,
    pub params: Vec<(Spanned<String>, Param)>,
    pub sweep: Option<Spanned<String>>,
    pub gather: Option<Spanned<String>>,
    /// What a Slurm task of this stage asks for (`irsig-run --emit-slurm`).
    pub slurm: Option<crate::slurm::Resources>,
    pub start: usize,
    pub end: usize,
}

/// One parameter value, and how it becomes command-line words.
#[derive(Debug, Clone)]
pub(crate) enum Param {
    /// `true` gives the bare flag, `false` leaves it out.
    Switch(bool),
    /// A string or number: `--key value`.
    One(Spanned<String>),
    /// A list `[a, b]`: the flag repeated, `--key a --key b`.
    Repeated(Vec<Spanned<String>>),
    /// A tuple `(a, b)`: one flag with several values, `--key a b`.
    Several(Vec<Spanned<String>>),
}

#[derive(Debug, Clone)]
pub(crate) struct SweepSpec {
    /// The variables of each frame, in frame order; `frame` and `frames` not included.
    pub frames: Vec<BTreeMap<String, String>>,
    /// A `Times` sweep's moments and where its times are written.
    pub times: Option<crate::times::TimesSpec>,
}

pub(crate) fn pipeline(src: Source<'_>, root: &Node) -> Result<PipelineSpec, PipelineError> {
    let fields = fields_of(src, root, "Pipeline", &["stages", "sweeps", "sun"])?;
    let mut sweeps = BTreeMap::new();
    if let Some(node) = fields.get("sweeps") {
        let Kind::Map(entries) = &node.kind else {
            return Err(src.structure(
                node,
                format!(
                    "expected `sweeps` to be a map {{\"name\": Frames([...]), FlyBy(...), Tiles(...) or Times(...)}}, found {}",
                    node.kind.describe()
                ),
            ));
        };
        for (key, value) in entries {
            let name = string(src, key, "a sweep name")?;
            if sweeps.contains_key(&name.value) {
                return Err(src.structure(key, format!("sweep `{}` is defined twice", name.value)));
            }
            sweeps.insert(name.value, sweep(src, value)?);
        }
    }
    let Some(stages_node) = fields.get("stages") else {
        return Err(src.structure(root, "the pipeline has no `stages: [...]` field"));
    };
    let Kind::List(items) = &stages_node.kind else {
        return Err(src.structure(
            stages_node,
            format!(
                "expected `stages` to be a list `[Stage(...), ...]`, found {}",
                stages_node.kind.describe()
            ),
        ));
    };
    if items.is_empty() {
        return Err(src.structure(
            stages_node,
            "the pipeline has no stages: `stages: []` would run nothing and succeed",
        ));
    }
    let stages = items
        .iter()
        .map(|n| stage(src, n))
        .collect::<Result<Vec<_>, _>>()?;
    let sun = fields
        .get("sun")
        .map(|node| crate::sun::read(src, node))
        .transpose()?;
    Ok(PipelineSpec {
        stages,
        sweeps,
        sun,
    })
}

const STAGE_FIELDS: &[&str] = &[
    "name", "tool", "args", "inputs", "reads", "outputs", "params", "sweep", "gather", "slurm",
];

fn stage(src: Source<'_>, node: &Node) -> Result<StageSpec, PipelineError> {
    let f = fields_of(src, node, "Stage", STAGE_FIELDS)?;
    let Some(tool_node) = f.get("tool") else {
        return Err(src.structure(node, "this stage has no `tool: \"...\"` field"));
    };
    let tool = string(src, tool_node, "the tool's name, such as \"trace\"")?;
    if tool.value.split_whitespace().next().is_none() {
        return Err(src.structure(tool_node, "the tool's name is empty"));
    }
    let name = f
        .get("name")
        .map(|n| string(src, n, "a stage name"))
        .transpose()?;
    let args = file_list(src, f.get("args").copied(), "args")?;
    let reads = file_list(src, f.get("reads").copied(), "reads")?;
    let inputs = f
        .get("inputs")
        .map(|n| path_map(src, n, "inputs"))
        .transpose()?
        .unwrap_or_default();
    let outputs = f
        .get("outputs")
        .map(|n| path_map(src, n, "outputs"))
        .transpose()?
        .unwrap_or_default();
    let params = f
        .get("params")
        .map(|n| params(src, n))
        .transpose()?
        .unwrap_or_default();
    let sweep = f
        .get("sweep")
        .map(|n| string(src, n, "the name of a sweep"))
        .transpose()?;
    let gather = f
        .get("gather")
        .map(|n| string(src, n, "the name of a sweep"))
        .transpose()?;
    let slurm = f
        .get("slurm")
        .map(|n| crate::slurm::resources(src, n))
        .transpose()?;
    if let (Some(_), Some(g)) = (&sweep, &gather) {
        return Err(src.error(
            ErrorKind::Structure,
            g.start,
            g.end,
            "a stage either runs once per frame (`sweep`) or once over all frames (`gather`), not both",
        ));
    }
    Ok(StageSpec {
        name,
        tool,
        args,
        inputs,
        reads,
        outputs,
        params,
        sweep,
        gather,
        slurm,
        start: node.start,
        end: node.end,
    })
}

/// A list of file paths: the `args` or `reads` field (absent: none).
fn file_list(
    src: Source<'_>,
    node: Option<&Node>,
    field: &str,
) -> Result<Vec<Spanned<String>>, PipelineError> {
    let Some(n) = node else {
        return Ok(Vec::new());
    };
    match &n.kind {
        Kind::List(items) => items
            .iter()
            .map(|i| string(src, i, "a file path"))
            .collect(),
        other => Err(src.structure(
            n,
            format!(
                "expected `{field}` to be a list of input file paths, found {}",
                other.describe()
            ),
        )),
    }
}

fn path_map(src: Source<'_>, node: &Node, field: &str) -> Result<Vec<FlagFile>, PipelineError> {
    let Kind::Map(entries) = &node.kind else {
        return Err(src.structure(
            node,
            format!(
                "expected `{field}` to be a map from flag to file, such as {{\"o\": \"out.ron\"}}, found {}",
                node.kind.describe()
            ),
        ));
    };
    entries
        .iter()
        .map(|(k, v)| Ok((flag_name(src, k)?, string(src, v, "a file path")?)))
        .collect()
}

fn params(src: Source<'_>, node: &Node) -> Result<Vec<(Spanned<String>, Param)>, PipelineError> {
    let Kind::Map(entries) = &node.kind else {
        return Err(src.structure(
            node,
            format!(
                "expected `params` to be a map from flag to value, such as {{\"band\": \"8-14\"}}, found {}",
                node.kind.describe()
            ),
        ));
    };
    entries
        .iter()
        .map(|(k, v)| {
            let key = flag_name(src, k)?;
            let value = match &v.kind {
                Kind::Bool(b) => Param::Switch(*b),
                Kind::List(items) => Param::Repeated(
                    items
                        .iter()
                        .map(|i| scalar(src, i))
                        .collect::<Result<_, _>>()?,
                ),
                Kind::Tuple(None, items) => Param::Several(
                    items
                        .iter()
                        .map(|i| scalar(src, i))
                        .collect::<Result<_, _>>()?,
                ),
                _ => Param::One(scalar(src, v)?),
            };
            Ok((key, value))
        })
        .collect()
}

fn flag_name(src: Source<'_>, node: &Node) -> Result<Spanned<String>, PipelineError> {
    let name = string(src, node, "a flag name in quotes, such as \"band\"")?;
    let bare = name.value.trim_start_matches('-');
    if bare.is_empty() || bare.contains(char::is_whitespace) {
        return Err(src.structure(
            node,
            format!(
                "expected a flag name such as \"band\" (for --band) or \"o\" (for -o), found {:?}",
                name.value
            ),
        ));
    }
    Ok(name)
}

/// A string or number parameter value, as one command-line word.
pub(crate) fn scalar(src: Source<'_>, node: &Node) -> Result<Spanned<String>, PipelineError> {
    match &node.kind {
        Kind::Str(s) => {
            refuse_control(src, node, s)?;
            Ok(Spanned::new(s.clone(), node))
        }
        Kind::Number(n) => Ok(Spanned::new(n.replace('_', ""), node)),
        other => Err(src.structure(
            node,
            format!("expected a string or a number, found {}", other.describe()),
        )),
    }
}

fn string(src: Source<'_>, node: &Node, what: &str) -> Result<Spanned<String>, PipelineError> {
    match &node.kind {
        Kind::Str(s) => {
            refuse_control(src, node, s)?;
            Ok(Spanned::new(s.clone(), node))
        }
        other => Err(src.structure(
            node,
            format!("expected {what} in quotes, found {}", other.describe()),
        )),
    }
}

/// Every string of a pipeline file becomes words of a command line, lines of a Makefile or
/// of a Slurm script: one holding a control character (newline, carriage return, NUL, tab,
/// any of U+0000-U+001F and U+007F-U+009F) is refused here, at the character, written
/// as it is or as an escape (`\n`, `\u{0}`).
fn refuse_control(src: Source<'_>, node: &Node, value: &str) -> Result<(), PipelineError> {
    let Some(bad) = value.chars().find(|c| c.is_control()) else {
        return Ok(());
    };
    let (at, len) = control_in_literal(src.text.get(node.start..node.end).unwrap_or(""))
        .map_or((node.start, node.end - node.start), |(i, n)| {
            (node.start + i, n)
        });
    Err(src.error(
        ErrorKind::ControlCharacter,
        at,
        at + len,
        format!(
            "this string holds the control character {}: a pipeline's names, paths and \
             parameters become words of shell, make and Slurm scripts, where a control \
             character could end a line and start a command",
            describe_control(bad)
        ),
    ))
}

/// The name of a control character for a message: `U+000A (newline)`.
fn describe_control(c: char) -> String {
    let name = match c {
        '\n' => " (newline)",
        '\r' => " (carriage return)",
        '\t' => " (tab)",
        '\0' => " (NUL)",
        _ => "",
    };
    format!("U+{:04X}{name}", u32::from(c))
}

/// The byte offset and length, in a string literal's source text (`"..."`, `r#"..."#` or
/// `'.'`), of its first control character, written as it is or as an escape.
fn control_in_literal(literal: &str) -> Option<(usize, usize)> {
    let raw = literal.starts_with('r');
    let mut chars = literal.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        if c.is_control() {
            return Some((i, c.len_utf8()));
        }
        if raw || c != '\\' {
            continue;
        }
        let &(_, e) = chars.peek()?;
        let rest = &literal[i + 1..];
        let (value, len) = match e {
            'n' => (Some('\n'), 2),
            't' => (Some('\t'), 2),
            'r' => (Some('\r'), 2),
            '0' => (Some('\0'), 2),
            'x' => (
                rest.get(1..3)
                    .and_then(|h| u32::from_str_radix(h, 16).ok())
                    .and_then(char::from_u32),
                4,
            ),
            'u' => match rest.find('}') {
                Some(close) => (
                    rest.get(2..close)
                        .and_then(|h| u32::from_str_radix(&h.replace('_', ""), 16).ok())
                        .and_then(char::from_u32),
                    close + 2,
                ),
                None => (None, 2),
            },
            _ => (None, 2),
        };
        if value.is_some_and(char::is_control) {
            return Some((i, len));
        }
        // Past the escape: `\\` must not start another.
        for _ in 1..len {
            if chars.next().is_none() {
                break;
            }
        }
    }
    None
}

/// The fields of a struct value `Name(field: ...)` or `(field: ...)`, refusing unknown ones.
pub(crate) fn fields_of<'n>(
    src: Source<'_>,
    node: &'n Node,
    type_name: &str,
    allowed: &[&str],
) -> Result<BTreeMap<&'n str, &'n Node>, PipelineError> {
    let fields: &[(Key, Node)] = match &node.kind {
        Kind::Struct(name, fields) if name.as_deref().is_none_or(|n| n == type_name) => fields,
        Kind::Tuple(name, items)
            if items.is_empty() && name.as_deref().is_none_or(|n| n == type_name) =>
        {
            &[]
        }
        other => {
            return Err(src.structure(
                node,
                format!(
                    "expected {type_name}(field: ..., ...), found {}",
                    other.describe()
                ),
            ));
        }
    };
    let mut out = BTreeMap::new();
    for (key, value) in fields {
        if !allowed.contains(&key.name.as_str()) {
            return Err(src
                .error(
                    ErrorKind::Structure,
                    key.start,
                    key.end,
                    format!("unknown field `{}` in {type_name}", key.name),
                )
                .with_help(format!(
                    "{type_name} has the fields: {}",
                    allowed.join(", ")
                )));
        }
        if out.insert(key.name.as_str(), value).is_some() {
            return Err(src.error(
                ErrorKind::Structure,
                key.start,
                key.end,
                format!("field `{}` is given twice", key.name),
            ));
        }
    }
    Ok(out)
}

fn sweep(src: Source<'_>, node: &Node) -> Result<SweepSpec, PipelineError> {
    if matches!(&node.kind, Kind::Struct(Some(name), _) if name == "Times") {
        let (frames, times) = crate::times::read(src, node)?;
        return Ok(SweepSpec {
            frames,
            times: Some(times),
        });
    }
    let frames = match &node.kind {
        Kind::Tuple(Some(name), items) if name == "Frames" && items.len() == 1 => {
            frames_list(src, &items[0])?
        }
        Kind::Struct(Some(name), _) if name == "FlyBy" => fly_by(src, node)?,
        Kind::Struct(Some(name), _) if name == "Tiles" => tiles(src, node)?,
        other => {
            return Err(src.structure(
                node,
                format!(
                    "expected a sweep: Frames([{{\"var\": \"value\", ...}}, ...]), \
                     FlyBy(frames: N, path: [(x, y, z), ...], look_at: (x, y, z)), \
                     Tiles(columns: C, rows: R) or Times(start: \"YYYY-MM-DDTHH:MM\", end: \
                     \"...\", step: \"PT1H\", zone: \"America/Denver\"), found {}",
                    other.describe()
                ),
            ));
        }
    };
    if frames.is_empty() {
        return Err(src.structure(node, "a sweep needs at least one frame"));
    }
    Ok(SweepSpec {
        frames,
        times: None,
    })
}

fn frames_list(
    src: Source<'_>,
    node: &Node,
) -> Result<Vec<BTreeMap<String, String>>, PipelineError> {
    let Kind::List(items) = &node.kind else {
        return Err(src.structure(
            node,
            format!(
                "expected a list of frames, each a map of variables, found {}",
                node.kind.describe()
            ),
        ));
    };
    items
        .iter()
        .map(|item| {
            let Kind::Map(entries) = &item.kind else {
                return Err(src.structure(
                    item,
                    format!(
                        "expected a frame: a map of variables such as {{\"view\": \"v1.ron\"}}, found {}",
                        item.kind.describe()
                    ),
                ));
            };
            let mut vars = BTreeMap::new();
            for (k, v) in entries {
                let key = string(src, k, "a variable name")?;
                if matches!(key.value.as_str(), "frame" | "frames") || !is_variable(&key.value) {
                    return Err(src.structure(
                        k,
                        format!(
                            "`{}` cannot be a variable name: use letters, digits and `_`, \
                             and not `frame` or `frames`, which every sweep sets",
                            key.value
                        ),
                    ));
                }
                vars.insert(key.value, scalar(src, v)?.value);
            }
            Ok(vars)
        })
        .collect()
}

pub(crate) fn is_variable(name: &str) -> bool {
    !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Whether `text` holds a template `{...}` (a `{{` is a literal brace, no template).
pub(crate) fn has_template(text: &str) -> bool {
    let mut rest = text;
    while let Some(i) = rest.find('{') {
        if rest[i + 1..].starts_with('{') {
            rest = &rest[i + 2..];
        } else {
            return true;
        }
    }
    false
}

/// A fly-by: `frames` sensor positions spaced evenly along the polyline `path` (metres, by
/// arc length, first and last frame on the path's ends), all looking at `look_at`.
fn fly_by(src: Source<'_>, node: &Node) -> Result<Vec<BTreeMap<String, String>>, PipelineError> {
    let f = fields_of(src, node, "FlyBy", &["frames", "path", "look_at"])?;
    let Some(count_node) = f.get("frames") else {
        return Err(src.structure(node, "FlyBy needs `frames: N`, the number of frames"));
    };
    let count = match &count_node.kind {
        Kind::Number(n) => n.replace('_', "").parse::<usize>().ok(),
        _ => None,
    }
    .filter(|&n| (1..=100_000).contains(&n))
    .ok_or_else(|| {
        src.structure(
            count_node,
            "expected a whole number of frames from 1 to 100000",
        )
    })?;
    let Some(path_node) = f.get("path") else {
        return Err(src.structure(
            node,
            "FlyBy needs `path: [(x, y, z), ...]`, sensor positions in metres",
        ));
    };
    let Kind::List(points) = &path_node.kind else {
        return Err(src.structure(
            path_node,
            "expected a list of positions `[(x, y, z), ...]` in metres",
        ));
    };
    let path = points
        .iter()
        .map(|p| point(src, p))
        .collect::<Result<Vec<_>, _>>()?;
    if path.is_empty() {
        return Err(src.structure(path_node, "the fly-by path needs at least one position"));
    }
    let look_at = f.get("look_at").map(|n| point(src, n)).transpose()?;
    let positions = sample_polyline(&path, count);
    Ok(positions
        .iter()
        .map(|eye| {
            let mut vars = BTreeMap::new();
            vars.insert("eye_x_m".to_owned(), metres(eye[0]));
            vars.insert("eye_y_m".to_owned(), metres(eye[1]));
            vars.insert("eye_z_m".to_owned(), metres(eye[2]));
            vars.insert("eye".to_owned(), triple(eye));
            if let Some(target) = &look_at {
                vars.insert("look_at".to_owned(), triple(target));
            }
            vars
        })
        .collect())
}

/// The most tiles one `Tiles` sweep may cut a frame into.
const TILES_MAX: u64 = 100_000;

/// A frame cut into `columns × rows` tiles: one "frame" of the sweep per tile, numbered from
/// 1 row by row from the top-left, with the variables `tile` (`I/CxR`, as `irsig-trace
/// --tile` takes it), `tile_column` and `tile_row` (from 1).
fn tiles(src: Source<'_>, node: &Node) -> Result<Vec<BTreeMap<String, String>>, PipelineError> {
    let f = fields_of(src, node, "Tiles", &["columns", "rows"])?;
    let count = |name: &str| -> Result<u64, PipelineError> {
        let Some(n) = f.get(name) else {
            return Err(src.structure(
                node,
                format!(
                    "Tiles needs `{name}: N`, the number of tiles {}",
                    if name == "rows" {
                        "down the frame"
                    } else {
                        "across the frame"
                    }
                ),
            ));
        };
        match &n.kind {
            Kind::Number(t) => t.replace('_', "").parse::<u64>().ok(),
            _ => None,
        }
        .filter(|&v| (1..=TILES_MAX).contains(&v))
        .ok_or_else(|| {
            src.structure(
                n,
                format!("expected `{name}` to be a whole number from 1 to {TILES_MAX}"),
            )
        })
    };
    let (columns, rows) = (count("columns")?, count("rows")?);
    if columns * rows > TILES_MAX {
        return Err(src.structure(
            node,
            format!("{columns} x {rows} tiles are more than one sweep may hold ({TILES_MAX})"),
        ));
    }
    Ok((1..=columns * rows)
        .map(|i| {
            let mut vars = BTreeMap::new();
            vars.insert("tile".to_owned(), format!("{i}/{columns}x{rows}"));
            vars.insert(
                "tile_column".to_owned(),
                ((i - 1) % columns + 1).to_string(),
            );
            vars.insert("tile_row".to_owned(), ((i - 1) / columns + 1).to_string());
            vars
        })
        .collect())
}

fn point(src: Source<'_>, node: &Node) -> Result<[f64; 3], PipelineError> {
    let bad = || {
        src.structure(
            node,
            "expected a position (x, y, z) of three finite numbers, in metres",
        )
    };
    let Kind::Tuple(None, items) = &node.kind else {
        return Err(bad());
    };
    let mut out = [0.0; 3];
    if items.len() != 3 {
        return Err(bad());
    }
    for (slot, item) in out.iter_mut().zip(items) {
        *slot = match &item.kind {
            Kind::Number(n) => n.replace('_', "").parse::<f64>().ok(),
            _ => None,
        }
        .filter(|v| v.is_finite())
        .ok_or_else(|| src.structure(item, "expected a finite number of metres"))?;
    }
    Ok(out)
}

/// `count` points evenly spaced by arc length along the polyline, ends included.
pub(crate) fn sample_polyline(path: &[[f64; 3]], count: usize) -> Vec<[f64; 3]> {
    let seg_len = |a: &[f64; 3], b: &[f64; 3]| {
        ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt()
    };
    let total: f64 = path.windows(2).map(|w| seg_len(&w[0], &w[1])).sum();
    let first = path.first().copied().unwrap_or([0.0; 3]);
    (0..count)
        .map(|i| {
            if count == 1 || total <= 0.0 {
                return first;
            }
            #[allow(clippy::cast_precision_loss)]
            let mut remaining = total * i as f64 / (count - 1) as f64;
            for w in path.windows(2) {
                let len = seg_len(&w[0], &w[1]);
                if remaining <= len && len > 0.0 {
                    let t = remaining / len;
                    return [0, 1, 2].map(|k| irsig_model::interp::lerp(w[0][k], w[1][k], t));
                }
                remaining -= len;
            }
            path.last().copied().unwrap_or(first)
        })
        .collect()
}

/// A length in metres for a command line: micrometre resolution, no trailing zeros, so that
/// the same fly-by always gives the same words.
fn metres(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

fn triple(p: &[f64; 3]) -> String {
    format!("{},{},{}", metres(p[0]), metres(p[1]), metres(p[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polyline_samples_are_even_in_arc_length() {
        // An L-shaped path of 3 m + 1 m: 5 frames at 0, 1, 2, 3, 4 m along it.
        let path = [[0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [3.0, 1.0, 0.0]];
        let p = sample_polyline(&path, 5);
        let expected = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [3.0, 1.0, 0.0],
        ];
        for (got, want) in p.iter().zip(expected) {
            for k in 0..3 {
                assert!((got[k] - want[k]).abs() < 1e-12, "{got:?} vs {want:?}");
            }
        }
        assert_eq!(sample_polyline(&path, 1), vec![[0.0, 0.0, 0.0]]);
    }

    #[test]
    fn metres_are_printed_without_noise() {
        assert_eq!(metres(1000.0), "1000");
        assert_eq!(metres(-2.5), "-2.5");
        assert_eq!(metres(1.0 / 3.0), "0.333333");
        assert_eq!(metres(-0.0000001), "0");
    }
}
