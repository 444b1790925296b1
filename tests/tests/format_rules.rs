//! Every "must" a format page states names what refuses its violation: a row of the table
//! in `formats/README.md` ("The rules the pages state, and what refuses each") holding the
//! rule's words and a case of the malformed corpus or a test. A page that gains a "must"
//! without a row fails here, as does a row whose rule left its page or whose case or test
//! is gone.

use std::path::Path;

use irsig_tests::{repo_root, squeeze};

/// A row of the table: the page (relative to `formats/`), the rule's words as the page
/// has them, and what refuses a violation.
#[derive(Debug)]
struct Row {
    page: String,
    rule: String,
    refused_by: String,
}

const HEADING: &str = "## The rules the pages state, and what refuses each";

/// `text` with every run of white space one space: a rule may be wrapped anywhere.
fn rows(readme: &str) -> Vec<Row> {
    let start = readme.find(HEADING).expect("the rule table's heading");
    let section = &readme[start + HEADING.len()..];
    let section = section.find("\n## ").map_or(section, |end| &section[..end]);
    section
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| page |") && !l.starts_with("| ---"))
        .map(|l| {
            let cells: Vec<&str> = l.trim().trim_matches('|').split(" | ").collect();
            assert_eq!(cells.len(), 3, "a row of three cells: {l}");
            Row {
                page: cells[0].trim().to_owned(),
                rule: cells[1].trim().to_owned(),
                refused_by: cells[2].trim().to_owned(),
            }
        })
        .collect()
}

/// Byte offsets of the word "must" (any case) in `text`.
fn musts(text: &str) -> Vec<usize> {
    let lower = text.to_ascii_lowercase();
    let bytes = lower.as_bytes();
    let word = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    lower
        .match_indices("must")
        .map(|(i, _)| i)
        .filter(|&i| (i == 0 || !word(bytes[i - 1])) && bytes.get(i + 4).is_none_or(|&b| !word(b)))
        .collect()
}

/// The pages: every Markdown file under `formats/` but the index that holds the table.
fn pages(formats: &Path) -> Vec<String> {
    let mut out: Vec<String> = walkdir::WalkDir::new(formats)
        .into_iter()
        .map(|e| e.unwrap())
        .filter(|e| e.path().extension().is_some_and(|x| x == "md"))
        .map(|e| {
            e.path()
                .strip_prefix(formats)
                .unwrap()
                .to_string_lossy()
                .into_owned()
        })
        .filter(|p| p != "README.md")
        .collect();
    out.sort();
    out
}

/// Why `evidence` (`case FOLDER/FILE`, `test PATH::FUNCTION` or `advice: …`) does not
/// stand, if it does not.
fn missing(root: &Path, evidence: &str) -> Option<String> {
    if let Some(case) = evidence.strip_prefix("case ") {
        let (folder, file) = case.split_once('/')?;
        let tsv = std::fs::read_to_string(
            root.join("tests/data/malformed")
                .join(folder)
                .join("cases.tsv"),
        )
        .unwrap_or_default();
        let listed = tsv.lines().any(|l| l.split('\t').next() == Some(file));
        return (!listed)
            .then(|| format!("no case `{file}` in tests/data/malformed/{folder}/cases.tsv"));
    }
    if let Some(test) = evidence.strip_prefix("test ") {
        let Some((path, function)) = test.split_once("::") else {
            return Some(format!("`{test}`: expected PATH::FUNCTION"));
        };
        let text = std::fs::read_to_string(root.join(path)).unwrap_or_default();
        let found = text.contains(&format!("fn {function}("));
        return (!found).then(|| format!("no `fn {function}` in {path}"));
    }
    if evidence
        .strip_prefix("advice: ")
        .is_some_and(|why| !why.trim().is_empty())
    {
        return None;
    }
    Some(format!(
        "`{evidence}`: expected `case FOLDER/FILE`, `test PATH::FUNCTION` or `advice: WHY`"
    ))
}

#[test]
fn every_must_a_format_page_states_names_a_case_or_test_that_refuses_it() {
    let root = repo_root();
    let formats = root.join("formats");
    let readme = std::fs::read_to_string(formats.join("README.md")).unwrap();
    let rows = rows(&readme);
    assert!(rows.len() >= 30, "{} rows", rows.len());
    let mut faults = Vec::new();
    for row in &rows {
        assert!(row.rule.to_ascii_lowercase().contains("must"), "{row:?}");
        for evidence in row.refused_by.split(", ") {
            if let Some(why) = missing(&root, evidence) {
                faults.push(format!("{} ({}): {why}", row.page, row.rule));
            }
        }
    }
    for page in pages(&formats) {
        let text = squeeze(&std::fs::read_to_string(formats.join(&page)).unwrap());
        let mine: Vec<&Row> = rows.iter().filter(|r| r.page == page).collect();
        // Where each of the page's rows stands on it.
        let mut spans = Vec::new();
        for row in &mine {
            let rule = squeeze(&row.rule);
            let at: Vec<usize> = text.match_indices(&rule).map(|(i, _)| i).collect();
            if at.is_empty() {
                faults.push(format!(
                    "{page}: the rule `{}` is not on the page",
                    row.rule
                ));
            }
            spans.extend(at.into_iter().map(|i| i..i + rule.len()));
        }
        for i in musts(&text) {
            if !spans.iter().any(|s| s.contains(&i)) {
                let from = text[..i].char_indices().rev().nth(60).map_or(0, |(j, _)| j);
                let to = text[i..]
                    .char_indices()
                    .nth(60)
                    .map_or(text.len(), |(j, _)| i + j);
                faults.push(format!("{page}: no row for \"…{}…\"", &text[from..to]));
            }
        }
    }
    for row in &rows {
        if !formats.join(&row.page).is_file() {
            faults.push(format!("{}: no such page", row.page));
        }
    }
    assert!(faults.is_empty(), "{}", faults.join("\n"));
}

#[test]
fn the_scan_finds_words_not_parts_of_words() {
    assert_eq!(musts("It must be. Mustard must-have; MUST"), [3, 20, 31]);
    assert_eq!(squeeze(" a\n  b\tc "), "a b c");
}
