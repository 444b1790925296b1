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
const OWNERS: [(&str, &[&str]); 8] = [
    // file syntax: only irsig-formats knows it
    ("ron", &["irsig-formats"]),
    ("gltf", &["irsig-formats"]),
    ("tobj", &["irsig-formats"]),
    ("nom", &["irsig-formats"]),
    ("jsonc-parser", &["irsig-formats"]),
    // EXR files: only irsig-raster reads and writes them
    ("exr", &["irsig-raster"]),
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
/// makes, its default values and whether it takes a value.
fn flags(tool: &str, command: &clap::Command, out: &mut BTreeMap<String, Vec<(String, String)>>) {
    for arg in command.get_arguments() {
        let Some(long) = arg.get_long() else {
            continue;
        };
        let defaults: Vec<String> = arg
            .get_default_values()
            .iter()
            .map(|v| v.to_string_lossy().into_owned())
            .collect();
        let kind = format!(
            "type {:?}, default {defaults:?}, takes a value: {}",
            arg.get_value_parser().type_id(),
            arg.get_action().takes_values()
        );
        let at = format!("{tool} {}", command.get_name());
        out.entry(long.to_owned()).or_default().push((at, kind));
    }
    for sub in command.get_subcommands() {
        flags(tool, sub, out);
    }
}

#[test]
fn a_flag_of_one_name_has_one_type_and_one_default_in_every_tool() {
    use clap::CommandFactory;
    let tools = [
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
    ];
    let mut all = BTreeMap::new();
    for (tool, command) in &tools {
        flags(tool, command, &mut all);
    }
    // The reading is live: the band is in many tools.
    assert!(
        all.get("band").is_some_and(|v| v.len() >= 7),
        "{:?}",
        all.get("band")
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
        "a flag is spelt, typed and defaulted alike in every tool",
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
