//! The malformed corpus, end to end and data-driven: every case listed in a
//! `tests/data/malformed/*/cases.tsv` manifest runs through its tool, which must (unless
//! the case expects otherwise, below) exit 1 within a time and memory bound, name the case's file with a line and column (a binary
//! file's byte offset is given as line 1, column offset + 1; an OBJ face is located by its
//! line; a bad sample of an image by its pixel, `pixel (x X, y Y)`; an image's provenance
//! record at its own line and column, `a.exr (its provenance):2:36`), hold the manifest's
//! message
//! fragment, and leave its output folder empty and its own folder as it was (outputs an
//! execute file names lie beside it): no output and no staged temporary file.
//!
//! A manifest line is `file<TAB>tool<TAB>arguments<TAB>fragment[<TAB>expected]`; in the
//! arguments `{in}` is the case's path and `{out}` an empty folder for outputs. Lines
//! starting with `#` are comments. `expected` is the outcome when it is not the one above
//! (`1`): `2`, bad usage (exit 2, the fragment in the message, nothing written: an output
//! that is an input, say); `0`, success within the same time and memory bounds (a small
//! file that asks for a large cost); `stderr-closed`, exit 1 with the reader of stderr
//! closed before the tool starts (no panic, nothing written). In every case the case's own
//! file is left as it was, byte for byte.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use irsig_tests::{bin_path, repo_root};

/// No case may take longer (a parser that loops, or reads without end).
const TIME_LIMIT: Duration = Duration::from_secs(60);
/// Nor map more virtual memory, KiB (`ulimit -v`): a size taken on trust aborts the tool,
/// which then does not exit with 1.
const MEMORY_LIMIT_KIB: u64 = 4 << 20;

fn unwrap_report(stderr: &str) -> String {
    stderr
        .lines()
        .map(|l| l.trim_start().trim_start_matches(['│', '×']).trim())
        .collect::<Vec<_>>()
        .join(" ")
}

/// Whether `text` holds `STEM.EXT:LINE`, where `STEM` is the case's file stem (the error
/// may lie in a file the case names, `short-colour.mtl` of `short-colour.obj`). A column
/// follows the line everywhere except for an OBJ face, which is located by its line. An
/// image's sample is located by its pixel instead: the file's name and `pixel (x X, y Y)`.
fn has_location(text: &str, file: &str) -> bool {
    let name = Path::new(file)
        .file_name()
        .map_or_else(|| file.to_owned(), |s| s.to_string_lossy().into_owned());
    if text.contains(&name) && text.contains("pixel (x ") {
        return true;
    }
    // An image's provenance is a file of its own inside the image: `a.exr (its
    // provenance):2:36`.
    let record = format!("{name} (its provenance):");
    if text
        .match_indices(&record)
        .any(|(i, _)| text[i + record.len()..].starts_with(|c: char| c.is_ascii_digit()))
    {
        return true;
    }
    let stem = Path::new(file)
        .file_stem()
        .map_or_else(|| file.to_owned(), |s| s.to_string_lossy().into_owned());
    let key = format!("{stem}.");
    text.match_indices(&key).any(|(i, _)| {
        let rest = &text[i + key.len()..];
        let ext = rest.bytes().take_while(u8::is_ascii_alphanumeric).count();
        rest[ext..]
            .strip_prefix(':')
            .is_some_and(|r| r.bytes().next().is_some_and(|b| b.is_ascii_digit()))
    })
}

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<std::ffi::OsString> {
    let mut names: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    names.sort();
    names
}

/// A case's expected outcome.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Expected {
    /// Exit 1, located, the fragment, nothing written.
    Located,
    /// Exit 2, the fragment, nothing written.
    Usage,
    /// Exit 0.
    Success,
    /// Exit 1 with stderr closed, nothing written.
    StderrClosed,
}

impl Expected {
    fn parse(text: Option<&str>) -> Self {
        match text {
            None | Some("1") => Self::Located,
            Some("2") => Self::Usage,
            Some("0") => Self::Success,
            Some("stderr-closed") => Self::StderrClosed,
            Some(other) => panic!("unknown expected outcome `{other}`"),
        }
    }
}

/// Runs one case; returns what is wrong with its outcome, if anything.
fn run_case(
    folder: &Path,
    file: &str,
    tool: &str,
    args: &str,
    fragment: &str,
    expected: Expected,
) -> Option<String> {
    let out = tempfile::tempdir().unwrap();
    let before = listing(folder);
    let case = folder.join(file);
    let case_bytes = std::fs::read(&case).unwrap();
    let args: Vec<String> = args
        .split_whitespace()
        .map(|a| {
            a.replace("{in}", &case.to_string_lossy())
                .replace("{out}", &out.path().to_string_lossy())
        })
        .collect();
    let stderr = if expected == Expected::StderrClosed {
        irsig_tests::closed_pipe()
    } else {
        Stdio::piped()
    };
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {MEMORY_LIMIT_KIB}; exec \"$@\""))
        .arg("sh")
        .arg(bin_path(tool))
        .args(&args)
        .current_dir(repo_root())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(stderr)
        .spawn()
        .unwrap();
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > TIME_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            return Some(format!("took longer than {TIME_LIMIT:?}"));
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let mut stderr = String::new();
    if let Some(mut pipe) = child.stderr.take() {
        std::io::Read::read_to_string(&mut pipe, &mut stderr).unwrap();
    }
    let text = unwrap_report(&stderr);
    let left: Vec<_> = std::fs::read_dir(out.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    let mut wrong = Vec::new();
    let code = match expected {
        Expected::Located | Expected::StderrClosed => 1,
        Expected::Usage => 2,
        Expected::Success => 0,
    };
    if status.code() != Some(code) {
        wrong.push(format!("exit {status}, expected {code}"));
    }
    if expected == Expected::Located && !has_location(&text, file) {
        wrong.push(format!("no `{file}:LINE`"));
    }
    if matches!(expected, Expected::Located | Expected::Usage) && !text.contains(fragment) {
        wrong.push(format!("no `{fragment}`"));
    }
    if expected != Expected::Success && !left.is_empty() {
        wrong.push(format!("left {left:?}"));
    }
    let after = listing(folder);
    if after != before {
        wrong.push(format!("changed its own folder: {before:?} -> {after:?}"));
    }
    if std::fs::read(&case).ok().as_deref() != Some(case_bytes.as_slice()) {
        wrong.push("changed the case's own file".to_owned());
    }
    (!wrong.is_empty()).then(|| format!("{}: {}\n{stderr}", wrong.join("; "), args.join(" ")))
}

#[test]
fn every_malformed_case_fails_cleanly_with_a_location() {
    let root = repo_root().join("tests/data/malformed");
    let mut folders: Vec<_> = std::fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("cases.tsv").is_file())
        .collect();
    folders.sort();
    assert!(!folders.is_empty(), "no manifest under {}", root.display());
    let mut failures = Vec::new();
    let mut count = 0;
    for folder in &folders {
        let manifest = std::fs::read_to_string(folder.join("cases.tsv")).unwrap();
        for line in manifest
            .lines()
            .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        {
            let cols: Vec<&str> = line.split('\t').collect();
            let (file, tool, args, fragment, expected) = match cols[..] {
                [file, tool, args, fragment] => (file, tool, args, fragment, None),
                [file, tool, args, fragment, expected] => {
                    (file, tool, args, fragment, Some(expected))
                }
                _ => panic!("{}: malformed manifest line `{line}`", folder.display()),
            };
            assert!(folder.join(file).is_file(), "{file} is listed but missing");
            count += 1;
            let expected = Expected::parse(expected);
            if let Some(w) = run_case(folder, file, tool, args, fragment, expected) {
                failures.push(format!("{}/{file}: {w}", folder.display()));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {count} cases failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// In a log the message is one line, however long the path before it: `grep` finds it.
/// (On a terminal miette wraps it to the window; stderr here is a pipe.)
#[test]
fn a_long_path_does_not_wrap_the_message() {
    let dir = tempfile::tempdir().unwrap();
    let deep = dir.path().join("a".repeat(120)).join("b".repeat(120));
    std::fs::create_dir_all(&deep).unwrap();
    let case = deep.join("non-utf8.obj");
    std::fs::copy(
        repo_root().join("tests/data/malformed/mesh/non-utf8.obj"),
        &case,
    )
    .unwrap();
    let out = Command::new(bin_path("irsig-import"))
        .arg(&case)
        .args([
            "--materials",
            "formats/canonical/samples/materials.ron",
            "-o",
        ])
        .arg(dir.path().join("object.bin"))
        .current_dir(repo_root())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    let line = format!(
        "{}:4:9: expected UTF-8 text, found a byte that is not",
        case.display()
    );
    assert!(
        stderr.lines().any(|l| l.contains(&line)),
        "no line holding `{line}` in\n{stderr}"
    );
}
