//! The rules `ARCHITECTURE.md` states about how the workspace fits together ("Architecture
//! invariants"), checked against `cargo metadata`, the sources and the tools' own clap
//! definitions rather than trusted to review.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use irsig_tests::repo_root;
use serde_json::Value;

/// One workspace package as `cargo metadata --no-deps` describes it.
#[derive(Debug)]
struct Package {
    name: String,
    /// The package directory relative to the repository root (`crates/formats`, `tools/trace`).
    dir: PathBuf,
    /// Binary targets: name and the features they require.
    bins: Vec<(String, Vec<String>)>,
    /// The features the package turns on by default.
    default_features: Vec<String>,
    /// The packages it depends on to build (normal and build dependencies; not the
    /// dev-dependencies its tests use).
    dependencies: Vec<String>,
}

impl Package {
    fn is_tool(&self) -> bool {
        self.dir.starts_with("tools")
    }
}

fn strings(v: &Value) -> Vec<String> {
    v.as_array()
        .map(|a| {
            a.iter()
                .filter_map(Value::as_str)
                .map(str::to_owned)
                .collect()
        })
        .unwrap_or_default()
}

/// The workspace's packages, read once per test from `cargo metadata`.
fn workspace() -> Vec<Package> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let out = Command::new(cargo)
        .args([
            "metadata",
            "--format-version",
            "1",
            "--no-deps",
            "--offline",
        ])
        .current_dir(repo_root())
        .output()
        .expect("run cargo metadata");
    assert!(
        out.status.success(),
        "cargo metadata failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let meta: Value = serde_json::from_slice(&out.stdout).expect("cargo metadata JSON");
    let root = Path::new(meta["workspace_root"].as_str().expect("workspace_root"));
    meta["packages"]
        .as_array()
        .expect("packages")
        .iter()
        .map(|p| {
            let manifest = Path::new(p["manifest_path"].as_str().expect("manifest_path"));
            let dir = manifest
                .parent()
                .and_then(|d| d.strip_prefix(root).ok())
                .expect("package inside the workspace")
                .to_path_buf();
            let bins = p["targets"]
                .as_array()
                .expect("targets")
                .iter()
                .filter(|t| strings(&t["kind"]).iter().any(|k| k == "bin"))
                .map(|t| {
                    (
                        t["name"].as_str().expect("name").to_owned(),
                        strings(&t["required-features"]),
                    )
                })
                .collect();
            Package {
                name: p["name"].as_str().expect("name").to_owned(),
                dir,
                bins,
                default_features: strings(&p["features"]["default"]),
                dependencies: p["dependencies"]
                    .as_array()
                    .expect("dependencies")
                    .iter()
                    .filter(|d| d["kind"].as_str() != Some("dev"))
                    .map(|d| d["name"].as_str().expect("name").to_owned())
                    .collect(),
            }
        })
        .collect()
}

/// Fails with every broken rule at once, one per line.
fn assert_none(broken: &[String], rule: &str) {
    assert!(broken.is_empty(), "{rule}:\n  {}", broken.join("\n  "));
}

#[test]
fn the_workspace_is_what_the_code_map_says() {
    let packages = workspace();
    let by_dir: BTreeMap<String, &str> = packages
        .iter()
        .map(|p| (p.dir.display().to_string(), p.name.as_str()))
        .collect();
    // A sanity check on the reading itself, so that the rules below cannot pass vacuously.
    assert_eq!(by_dir.get("crates/formats"), Some(&"irsig-formats"));
    assert_eq!(by_dir.get("tools/trace"), Some(&"irsig-trace"));
    assert!(packages.len() > 10, "{by_dir:?}");
}

#[test]
fn release_binaries_are_the_tools_alone() {
    // `cargo build --release --bins` builds every binary that needs no feature, and what it
    // builds lands on a user's PATH: only `tools/*` may have such binaries. A test-only
    // program sits behind a feature that is off by default.
    let broken: Vec<String> = workspace()
        .iter()
        .filter(|p| !p.is_tool())
        .flat_map(|p| {
            p.bins.iter().filter_map(move |(bin, required)| {
                let behind_a_feature = !required.is_empty()
                    && required.iter().all(|f| !p.default_features.contains(f));
                (!behind_a_feature).then(|| {
                    format!(
                        "`{bin}` of {} ({}) is built by `cargo build --release --bins`",
                        p.name,
                        p.dir.display()
                    )
                })
            })
        })
        .collect();
    assert_none(
        &broken,
        "binaries outside tools/* must require a non-default feature",
    );
}

#[test]
fn no_library_depends_on_a_tool() {
    let packages = workspace();
    let tools: Vec<&str> = packages
        .iter()
        .filter(|p| p.is_tool())
        .map(|p| p.name.as_str())
        .collect();
    assert!(tools.contains(&"irsig-trace"), "{tools:?}");
    let broken: Vec<String> = packages
        .iter()
        .filter(|p| p.dir.starts_with("crates"))
        .flat_map(|p| {
            p.dependencies
                .iter()
                .filter(|d| tools.contains(&d.as_str()))
                .map(move |d| format!("{} ({}) depends on the tool {d}", p.name, p.dir.display()))
        })
        .collect();
    assert_none(&broken, "crates/* must not depend on tools/*");
}

/// Crates only one workspace package may depend on (outside tests), and which.
const OWNERS: [(&str, &[&str]); 9] = [
    // file syntax: only irsig-formats knows it
    ("ron", &["irsig-formats"]),
    ("gltf", &["irsig-formats"]),
    ("tobj", &["irsig-formats"]),
    ("nom", &["irsig-formats"]),
    ("jsonc-parser", &["irsig-formats"]),
    // EXR files: only irsig-raster reads and writes them
    ("exr", &["irsig-raster"]),
    // PNG's own encoder (indexed colour), beneath image: irsig-raster's too
    ("png", &["irsig-raster"]),
    // terminals: progress bars only through irsig-cli
    ("indicatif", &["irsig-cli"]),
    // command lines: the tools, the flags they share in irsig-cli, and the test-only
    // program of irsig-tests (behind a feature: `release_binaries_are_the_tools_alone`)
    ("clap", &["irsig-cli", "irsig-tests", "TOOLS"]),
];

#[test]
fn file_syntax_terminals_and_command_lines_each_have_their_owners() {
    let packages = workspace();
    let formats = packages
        .iter()
        .find(|p| p.name == "irsig-formats")
        .expect("irsig-formats");
    // The reading is live: the owner really depends on what it owns.
    assert!(formats.dependencies.iter().any(|d| d == "ron"));
    let mut broken = Vec::new();
    for (krate, owners) in OWNERS {
        for p in &packages {
            let allowed =
                owners.contains(&p.name.as_str()) || (owners.contains(&"TOOLS") && p.is_tool());
            if !allowed && p.dependencies.iter().any(|d| d == krate) {
                broken.push(format!(
                    "{} ({}) depends on {krate}, which belongs to {}",
                    p.name,
                    p.dir.display(),
                    owners.join(", ").replace("TOOLS", "tools/*")
                ));
            }
        }
    }
    assert_none(&broken, "each crate above has its owners");
}

#[test]
fn no_tool_depends_on_another_tool() {
    let packages = workspace();
    let tools: Vec<&str> = packages
        .iter()
        .filter(|p| p.is_tool())
        .map(|p| p.name.as_str())
        .collect();
    assert!(tools.len() >= 10, "{tools:?}");
    let broken: Vec<String> = packages
        .iter()
        .filter(|p| p.is_tool())
        .flat_map(|p| {
            p.dependencies
                .iter()
                .filter(|d| tools.contains(&d.as_str()))
                .map(move |d| format!("{} depends on the tool {d}", p.name))
        })
        .collect();
    assert_none(
        &broken,
        "a tool shares code through crates/*, never through another tool",
    );
}

/// Every `.rs` file under `dir` (relative to the repository root), with its text.
fn sources(dir: &str) -> Vec<(PathBuf, String)> {
    walkdir::WalkDir::new(repo_root().join(dir))
        .into_iter()
        .filter_map(Result::ok)
        .filter(|e| e.path().extension().is_some_and(|x| x == "rs"))
        .map(|e| {
            let text = std::fs::read_to_string(e.path()).unwrap();
            (e.path().to_path_buf(), text)
        })
        .collect()
}

#[test]
fn no_library_prints() {
    // Libraries return what they have to say (errors, warnings, tables); the tools print.
    // Each library denies clippy's print lints at its root, so `cargo clippy` (CI) refuses a
    // print anywhere in it; irsig-cli, the terminal's one owner, allows them where it prints
    // a tool's error.
    let packages = workspace();
    let libraries: Vec<&Package> = packages
        .iter()
        .filter(|p| p.dir.starts_with("crates"))
        .collect();
    assert!(libraries.len() >= 12, "{}", libraries.len());
    let broken: Vec<String> = libraries
        .iter()
        .filter_map(|p| {
            let root = repo_root().join(&p.dir).join("src/lib.rs");
            let text = std::fs::read_to_string(&root).unwrap_or_default();
            (!text.contains("#![deny(clippy::print_stdout, clippy::print_stderr)]"))
                .then(|| format!("{} does not deny printing", root.display()))
        })
        .collect();
    assert_none(
        &broken,
        "every crates/*/src/lib.rs opens with #![deny(clippy::print_stdout, clippy::print_stderr)]",
    );
}

#[test]
fn binary_layouts_are_read_only_by_irsig_formats() {
    // The magics of irsig's binary forms, and bytes decoded as numbers: file syntax, which
    // only irsig-formats knows (tests may build damaged files to check its errors).
    let mut broken = Vec::new();
    for dir in ["crates", "tools"] {
        for (path, text) in sources(dir) {
            if path.starts_with(repo_root().join("crates/formats")) {
                continue;
            }
            for (i, line) in text.lines().enumerate() {
                let code = line.split("//").next().unwrap_or("");
                if code.contains("b\"IRSIG") || code.contains("from_le_bytes") {
                    broken.push(format!("{}:{}: {}", path.display(), i + 1, line.trim()));
                }
            }
        }
    }
    assert_none(&broken, "binary layouts are decoded in irsig-formats alone");
}

/// Every flag of `command` and of its subcommands, by long name: the type its value parser
/// makes, its default values, whether it takes a value, its value names, how many values
/// one use of it takes and whether it is required on its own (a tool that needs one of
/// several flags says so with a group or `required_unless_present`, which is its own
/// business).
fn flags(tool: &str, command: &clap::Command, out: &mut BTreeMap<String, Vec<(String, String)>>) {
    let mut command = command.clone();
    // Built, so that every argument's number of values is settled as clap parses it.
    command.build();
    collect_flags(tool, &command, out);
}

fn collect_flags(
    tool: &str,
    command: &clap::Command,
    out: &mut BTreeMap<String, Vec<(String, String)>>,
) {
    for arg in command.get_arguments() {
        let Some(long) = arg.get_long() else {
            continue;
        };
        let defaults: Vec<String> = arg
            .get_default_values()
            .iter()
            .map(|v| v.to_string_lossy().into_owned())
            .collect();
        let value_names: Vec<String> = arg
            .get_value_names()
            .unwrap_or_default()
            .iter()
            .map(ToString::to_string)
            .collect();
        let kind = format!(
            "type {:?}, default {defaults:?}, takes a value: {}, value names {value_names:?}, \
             values per use {:?}, required: {}",
            arg.get_value_parser().type_id(),
            arg.get_action().takes_values(),
            arg.get_num_args(),
            arg.is_required_set()
        );
        let at = format!("{tool} {}", command.get_name());
        out.entry(long.to_owned()).or_default().push((at, kind));
    }
    for sub in command.get_subcommands() {
        collect_flags(tool, sub, out);
    }
}

/// The tools' clap definitions, by the name `irsig-<name>` is run as.
fn tool_commands() -> Vec<(&'static str, clap::Command)> {
    use clap::CommandFactory;
    vec![
        ("import", irsig_import::Cli::command()),
        ("flatten", irsig_flatten::Cli::command()),
        ("atmos", irsig_atmos::Cli::command()),
        ("material", irsig_material::Cli::command()),
        ("therm", irsig_therm::Cli::command()),
        ("trace", irsig_trace::Cli::command()),
        ("merge", irsig_merge::Cli::command()),
        ("sensor", irsig_sensor::Cli::command()),
        ("stats", irsig_stats::Cli::command()),
        ("report", irsig_report::Cli::command()),
        ("run", irsig_run::Cli::command()),
    ]
}

#[test]
fn a_flag_of_one_name_is_spelt_typed_and_defaulted_alike_in_every_tool() {
    let mut all = BTreeMap::new();
    for (tool, command) in &tool_commands() {
        flags(tool, command, &mut all);
    }
    // The reading is live: the band is in many tools, and value names are read.
    assert!(
        all.get("band").is_some_and(|v| v.len() >= 7),
        "{:?}",
        all.get("band")
    );
    assert!(
        all.get("scene")
            .is_some_and(|v| v.iter().all(|(_, k)| k.contains("value names [\"FILE\"]"))),
        "{:?}",
        all.get("scene")
    );
    let mut broken = Vec::new();
    for (flag, uses) in &all {
        let first = &uses[0].1;
        if uses.iter().any(|(_, kind)| kind != first) {
            let each: Vec<String> = uses.iter().map(|(at, k)| format!("{at}: {k}")).collect();
            broken.push(format!("--{flag}:\n    {}", each.join("\n    ")));
        }
    }
    assert_none(
        &broken,
        "a flag is spelt, typed, defaulted, named, counted and required alike in every tool",
    );
}

/// The text between the bracket at `open` (a `(` or `[`) and its match, and the index just
/// past the match; string literals are skipped whole.
fn balanced(text: &str, open: usize) -> Option<(&str, usize)> {
    let bytes = text.as_bytes();
    let (mut depth, mut i, mut in_string) = (0usize, open, false);
    while i < bytes.len() {
        match bytes[i] {
            b'\\' if in_string => i += 1,
            b'"' => in_string = !in_string,
            b'(' | b'[' if !in_string => depth += 1,
            b')' | b']' if !in_string => {
                depth -= 1;
                if depth == 0 {
                    return Some((&text[open + 1..i], i + 1));
                }
            }
            _ => {}
        }
        i += 1;
    }
    None
}

/// `text` without its string literals' contents (`"..."` becomes `""`).
fn without_strings(text: &str) -> String {
    let mut out = String::new();
    let mut in_string = false;
    let mut escaped = false;
    for c in text.chars() {
        match (in_string, escaped, c) {
            (true, false, '\\') => escaped = true,
            (true, true, _) => escaped = false,
            (_, false, '"') => {
                in_string = !in_string;
                out.push('"');
            }
            (false, _, c) => out.push(c),
            (true, false, _) => {}
        }
    }
    out
}

/// The long flags a source file defines through clap's derive: every `#[arg(...)]` that
/// has `long`, named by `long = "..."` or by its field in kebab case.
fn defined_flags(text: &str) -> Vec<String> {
    let mut flags = Vec::new();
    let mut from = 0;
    while let Some(at) = text[from..].find("#[arg(") {
        let open = from + at + "#[arg".len();
        let Some((inside, mut next)) = balanced(text, open) else {
            break;
        };
        from = next;
        // The field: past the attribute's `]`, other attributes and doc comments.
        next += 1;
        let field = loop {
            let rest = text[next..].trim_start();
            next = text.len() - rest.len();
            if rest.starts_with("///") || rest.starts_with("//") {
                next += rest.find('\n').unwrap_or(rest.len());
            } else if rest.starts_with("#[") {
                match balanced(text, next + 1) {
                    Some((_, end)) => next = end + 1,
                    None => break None,
                }
            } else {
                let head: String = rest
                    .trim_start_matches("pub ")
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                break Some(head);
            }
        };
        let code = without_strings(inside);
        let words: Vec<&str> = code
            .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == '='))
            .filter(|w| !w.is_empty())
            .collect();
        let named = inside
            .split("long = \"")
            .nth(1)
            .and_then(|rest| rest.split('"').next());
        match (named, words.contains(&"long"), field) {
            (Some(name), _, _) => flags.push(name.to_owned()),
            (None, true, Some(field)) => flags.push(field.replace('_', "-")),
            _ => {}
        }
    }
    flags
}

#[test]
fn reading_a_flag_definition_finds_its_long_name() {
    let text = r#"
        /// A doc comment that says long = "nothing".
        #[arg(long, value_name = "N", help = "not long")]
        #[allow(dead_code)]
        pub sun_shadow_rays: Option<u32>,
        #[arg(id = "output", short = 'o', long = "output", conflicts_with_all = ["a", "b"])]
        pub path: Option<PathBuf>,
        #[arg(value_name = "TILE", long_help = "long")]
        pub tiles: Vec<String>,
    "#;
    assert_eq!(defined_flags(text), ["sun-shadow-rays", "output"]);
}

#[test]
fn a_flag_two_tools_share_is_defined_once_in_irsig_cli() {
    // What each tool takes, by the tools' own clap definitions.
    let mut tools_of: BTreeMap<String, std::collections::BTreeSet<&str>> = BTreeMap::new();
    for (tool, command) in &tool_commands() {
        let mut all = BTreeMap::new();
        flags(tool, command, &mut all);
        for flag in all.into_keys() {
            tools_of.entry(flag).or_default().insert(tool);
        }
    }
    let shared: Vec<&String> = tools_of
        .iter()
        .filter(|(flag, tools)| tools.len() >= 2 && !["help", "version"].contains(&flag.as_str()))
        .map(|(flag, _)| flag)
        .collect();
    // Where each flag is defined: in irsig-cli, or in a tool.
    let mut in_cli: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut in_tools: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (dir, into) in [("crates/cli/src", &mut in_cli), ("tools", &mut in_tools)] {
        for (path, text) in sources(dir) {
            let shown = path
                .strip_prefix(repo_root())
                .unwrap_or(&path)
                .display()
                .to_string();
            // A unit test's own command lines are not the tools'.
            let code = text
                .split("#[cfg(test)]\nmod tests")
                .next()
                .unwrap_or(&text);
            for flag in defined_flags(code) {
                into.entry(flag).or_default().push(shown.clone());
            }
        }
    }
    // The reading is live: shared flags are found where they are defined, and a tool's
    // own flag in its tool.
    assert!(shared.len() >= 20, "{shared:?}");
    assert!(in_cli.contains_key("band") && in_cli.contains_key("sun-zenith-deg"));
    assert!(in_tools.contains_key("sun-shadow-rays"), "{in_tools:?}");
    let mut broken = Vec::new();
    for flag in shared {
        if let Some(files) = in_tools.get(flag.as_str()) {
            broken.push(format!(
                "--{flag} (in {:?}) is defined in {}",
                tools_of[flag],
                files.join(", ")
            ));
        }
        match in_cli.get(flag.as_str()).map(Vec::len) {
            Some(1) => {}
            n => broken.push(format!(
                "--{flag} (in {:?}) is defined {} times in irsig-cli",
                tools_of[flag],
                n.unwrap_or(0)
            )),
        }
    }
    assert_none(
        &broken,
        "a flag two tools share is defined once, in irsig-cli",
    );
}

#[test]
fn test_helpers_are_not_compiled_into_the_tools() {
    // A library's test meshes and experiments (`testing` modules, with their unwraps) sit
    // behind `cfg(test)` or a feature that only dev-dependencies turn on.
    let mut seen = 0;
    let mut broken = Vec::new();
    for (path, text) in sources("crates") {
        let lines: Vec<&str> = text.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            if line.trim() == "pub mod testing;" {
                seen += 1;
                let gated = i > 0 && lines[i - 1].trim_start().starts_with("#[cfg(");
                if !gated {
                    broken.push(format!("{}:{}", path.display(), i + 1));
                }
            }
        }
    }
    assert!(
        seen >= 1,
        "no testing module found: the check reads nothing"
    );
    assert_none(&broken, "testing modules are behind cfg(test) or a feature");
}
