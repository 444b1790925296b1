//! The commands the documents give a user, as they give them: every fenced block of the
//! README, of `pipelines/*/README.md` and of `docs/*.md`, found by its document and its
//! first line, and run as written by `sh` with the test build's tools first on `PATH`.
//!
//! A test that runs a recipe takes its text from the document, never a copy of it, so a
//! recipe cannot change without the test running the new one.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::{bin_path, repo_root, squeeze};

/// One fenced block of a document.
#[derive(Debug, Clone)]
pub struct Block {
    /// The document, relative to the repository root (`pipelines/daylight/README.md`).
    pub doc: String,
    /// The fence's language (`sh`, `python`, `text`).
    pub lang: String,
    /// The line of the opening fence, 1-based.
    pub line: usize,
    /// The block's text, its lines each ending in a newline.
    pub text: String,
}

impl Block {
    /// The block's first line, as written (trailing spaces dropped): how a test names it.
    #[must_use]
    pub fn first_line(&self) -> &str {
        self.text.lines().next().unwrap_or("").trim_end()
    }

    /// The commands of the block: its lines joined where a line ends in `\`, comments and
    /// blank lines dropped, whitespace runs as one space.
    #[must_use]
    pub fn commands(&self) -> Vec<String> {
        let mut commands = Vec::new();
        let mut current = String::new();
        for line in self.text.lines() {
            let code = strip_comment(line);
            let (code, continued) = match code.trim_end().strip_suffix('\\') {
                Some(head) => (head, true),
                None => (code, false),
            };
            current.push(' ');
            current.push_str(code);
            if !continued {
                let squeezed = squeeze(&current);
                if !squeezed.is_empty() {
                    commands.push(squeezed);
                }
                current.clear();
            }
        }
        commands
    }
}

/// A line without its shell comment: from a `#` at the start of a word, outside quotes.
fn strip_comment(line: &str) -> &str {
    let mut quote: Option<char> = None;
    let mut previous = ' ';
    for (i, c) in line.char_indices() {
        match quote {
            Some(q) if c == q => quote = None,
            Some(_) => {}
            None if c == '\'' || c == '"' => quote = Some(c),
            None if c == '#' && previous.is_whitespace() => return &line[..i],
            None => {}
        }
        previous = c;
    }
    line
}

/// The documents whose recipes are run: the README, each pipeline's README and the pages
/// of `docs/`, relative to the repository root, sorted.
///
/// # Panics
/// When a folder cannot be read.
#[must_use]
pub fn documents() -> Vec<String> {
    let root = repo_root();
    let mut docs = vec!["README.md".to_owned()];
    let in_folder = |folder: &str, nested: bool| -> Vec<String> {
        let mut found = Vec::new();
        for entry in std::fs::read_dir(root.join(folder)).expect("a documents folder") {
            let path = entry.expect("a folder entry").path();
            let candidate = if nested {
                path.join("README.md")
            } else {
                path.clone()
            };
            if candidate.is_file() && candidate.extension().is_some_and(|e| e == "md") {
                let relative = candidate.strip_prefix(&root).expect("under the root");
                found.push(relative.to_string_lossy().into_owned());
            }
        }
        found
    };
    let mut rest = in_folder("pipelines", true);
    rest.extend(in_folder("docs", false));
    rest.sort();
    docs.extend(rest);
    docs
}

/// Every fenced block of `doc` (relative to the repository root).
///
/// # Panics
/// When the document cannot be read or a fence is not closed.
#[must_use]
pub fn blocks_of(doc: &str) -> Vec<Block> {
    let text =
        std::fs::read_to_string(repo_root().join(doc)).unwrap_or_else(|e| panic!("{doc}: {e}"));
    let mut blocks = Vec::new();
    let mut open: Option<(String, usize, String)> = None;
    for (i, line) in text.lines().enumerate() {
        let fence = line.trim_start().strip_prefix("```");
        match (&mut open, fence) {
            (None, Some(lang)) => open = Some((lang.trim().to_owned(), i + 1, String::new())),
            (Some(_), Some(_)) => {
                let (lang, line, text) = open.take().expect("an open block");
                blocks.push(Block {
                    doc: doc.to_owned(),
                    lang,
                    line,
                    text,
                });
            }
            (Some((_, _, body)), None) => {
                body.push_str(line);
                body.push('\n');
            }
            (None, None) => {}
        }
    }
    assert!(open.is_none(), "{doc}: a fence is not closed");
    blocks
}

/// The block of `doc` whose first line is `first_line`.
///
/// # Panics
/// When no block, or more than one, starts with that line: the recipe was changed or
/// moved, and its test must follow it.
#[must_use]
pub fn block(doc: &str, first_line: &str) -> Block {
    let mut found: Vec<Block> = blocks_of(doc)
        .into_iter()
        .filter(|b| b.first_line() == first_line)
        .collect();
    assert!(
        found.len() == 1,
        "{doc}: {} blocks start with `{first_line}`, expected one",
        found.len()
    );
    found.remove(0)
}

/// The folder of the test build's tools (`irsig-run`, `irsig-trace`, …), built first.
#[must_use]
pub fn tools_dir() -> PathBuf {
    bin_path("irsig-run")
        .parent()
        .expect("the tools' folder")
        .to_path_buf()
}

/// Runs `block` as written: `sh -eu` reading its text, in `dir`, with [`tools_dir`] first
/// on `PATH` and `envs` set. Returns what it printed and how it ended.
///
/// # Panics
/// When `sh` cannot start.
#[must_use]
pub fn run(block: &Block, dir: &Path, envs: &[(&str, &std::ffi::OsStr)]) -> Output {
    let path = std::env::var_os("PATH").unwrap_or_default();
    let mut paths = vec![tools_dir()];
    paths.extend(std::env::split_paths(&path));
    let mut cmd = Command::new("sh");
    cmd.args(["-eu", "-c", &block.text])
        .current_dir(dir)
        .env("PATH", std::env::join_paths(paths).expect("a PATH"));
    for (key, value) in envs {
        cmd.env(key, value);
    }
    cmd.output().expect("sh must start")
}

/// Like [`run`], and panics with the block's place and what it printed unless it succeeds.
///
/// # Panics
/// When the block fails.
pub fn run_ok(block: &Block, dir: &Path, envs: &[(&str, &std::ffi::OsStr)]) -> Output {
    let out = run(block, dir, envs);
    assert!(
        out.status.success(),
        "{}:{}: the recipe failed as written ({}) in {}:\n{}\n--- stdout:\n{}\n--- stderr:\n{}",
        block.doc,
        block.line,
        out.status,
        dir.display(),
        block.text,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// A copy of the folders the recipes read (`pipelines/`, `formats/`, `scripts/`) in a new
/// temporary directory, as a clone's root would hold them: a recipe's outputs land there,
/// never in the repository.
///
/// # Panics
/// When a file cannot be copied.
#[must_use]
pub fn scratch_root() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("a temporary directory");
    for folder in ["pipelines", "formats", "scripts"] {
        copy_tree(&repo_root().join(folder), &dir.path().join(folder));
    }
    dir
}

/// Copies the folder `from` to `to`, leaving out what a run writes into a checkout (`out/`,
/// `build/`, `.irsig-run/` at any depth), which a clone does not have.
///
/// # Panics
/// When a file cannot be copied.
pub fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap_or_else(|e| panic!("{}: {e}", to.display()));
    for entry in std::fs::read_dir(from).unwrap_or_else(|e| panic!("{}: {e}", from.display())) {
        let entry = entry.expect("a folder entry");
        let path = entry.path();
        let target = to.join(entry.file_name());
        if path.is_dir() {
            // Outputs a run in the repository left behind are not part of a clone.
            if !["out", "build", ".irsig-run"].contains(&entry.file_name().to_str().unwrap_or("")) {
                copy_tree(&path, &target);
            }
        } else {
            std::fs::copy(&path, &target).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commands_join_continued_lines_and_drop_comments() {
        let block = Block {
            doc: "d.md".into(),
            lang: "sh".into(),
            line: 1,
            text: "mkdir -p out   # a folder\n\nirsig-run \\\n    a.ron  # run it\necho '#1=325' # quoted\n".into(),
        };
        assert_eq!(
            block.commands(),
            ["mkdir -p out", "irsig-run a.ron", "echo '#1=325'"]
        );
        assert_eq!(block.first_line(), "mkdir -p out   # a folder");
    }
}
