//! The shipped pipelines' outputs, byte for byte: the quickstart, the thesis fly-by, the
//! thesis experiment and the quickstart traced in tiles and merged, run in full with
//! `irsig-run` on a copy of `pipelines/`, must hash to `tests/data/golden/outputs.sha256`.
//!
//! The manifest was recorded before the frame's library code moved out of `irsig-trace`
//! and `irsig-merge` (into `irsig-render`): it holds a refactor to the bytes the tools
//! wrote before it. A change meant to alter an output re-records it with
//! `sh scripts/golden/record.sh` and says in its commit why the bytes changed. The run
//! report (`report.html`) is left out: it names irsig's version.

use std::collections::BTreeMap;
use std::path::Path;

use irsig_tests::{bin, repo_root};
use sha2::{Digest, Sha256};

/// The pipeline files, run in this order (each writes its own folder).
const PIPELINES: [&str; 4] = [
    "quickstart.ron",
    "thesis-flyby.ron",
    "thesis-experiment.ron",
    "quickstart-tiles.ron",
];

/// `pipelines/` without what earlier runs left in it (`build/`, `out/`, run states).
fn copy_pipelines(to: &Path) {
    let from = repo_root().join("pipelines");
    let generated = |p: &Path| {
        p.components().any(|c| {
            let c = c.as_os_str();
            c == "build" || c == "out" || c == ".irsig-run"
        })
    };
    for entry in walkdir::WalkDir::new(&from) {
        let entry = entry.unwrap();
        let rel = entry.path().strip_prefix(&from).unwrap();
        if generated(rel) || rel.as_os_str() == "Makefile" {
            continue;
        }
        let dest = to.join("pipelines").join(rel);
        if entry.file_type().is_dir() {
            std::fs::create_dir_all(&dest).unwrap();
        } else if entry.file_type().is_file() {
            std::fs::copy(entry.path(), &dest).unwrap();
        }
    }
}

fn manifest() -> BTreeMap<String, String> {
    let text =
        std::fs::read_to_string(repo_root().join("tests/data/golden/outputs.sha256")).unwrap();
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let (hash, path) = l.split_once("  ").expect("`HASH  PATH` lines");
            (path.to_owned(), hash.to_owned())
        })
        .collect()
}

#[test]
fn the_shipped_pipelines_write_their_recorded_bytes() {
    let dir = tempfile::tempdir().unwrap();
    copy_pipelines(dir.path());
    for pipeline in PIPELINES {
        let out = bin("irsig-run")
            .current_dir(dir.path())
            .args(["--quiet", "--jobs", "2"])
            .arg(Path::new("pipelines").join(pipeline))
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "irsig-run {pipeline} failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let want = manifest();
    assert!(want.len() > 100, "the manifest lists {} files", want.len());
    let mut differ = Vec::new();
    for (path, hash) in &want {
        let bytes = std::fs::read(dir.path().join(path))
            .unwrap_or_else(|e| panic!("{path} was not written: {e}"));
        let got: String = Sha256::digest(&bytes)
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect();
        if &got != hash {
            differ.push(path.as_str());
        }
    }
    assert!(
        differ.is_empty(),
        "{} of {} outputs differ from tests/data/golden/outputs.sha256, among them: {}",
        differ.len(),
        want.len(),
        differ[..differ.len().min(12)].join(", ")
    );
}
