//! Every example a tool's `--help` shows is a command line that tool accepts: each is
//! checked by the tool's own parser and its own rules for its flags, the check `irsig-run`
//! asks of a pipeline's stage (`irsig_cli::CHECK_ARGS`), so an example that names a flag
//! that no longer exists (`irsig-material fresnel --temperature`) or a value the tool
//! refuses fails here. The files an example names are not read: the check stops before
//! any file is opened.

use std::process::Command;

use irsig_tests::{bin_path, repo_root};

/// The flag that asks a tool only to check its command line (`irsig_cli::CHECK_ARGS`).
const CHECK_ARGS: &str = "--irsig-check-args";

/// Every tool of the workspace: one binary per folder of `tools/`, `irsig-NAME`.
fn tools() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(repo_root().join("tools"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "irsig")
        .map(|n| format!("irsig-{n}"))
        .collect();
    names.sort();
    names
}

/// The command lines of the `Examples:` section of a help text: lines indented by two
/// spaces that start a command (`irsig-…`, or `cat FILE | irsig-…`), with the lines a
/// trailing `\` continues; the indented prose under an example is not a command.
fn example_lines(help: &str) -> Vec<String> {
    let Some(start) = help.find("Examples:") else {
        return Vec::new();
    };
    let mut commands = Vec::new();
    let mut lines = help[start..].lines().skip(1);
    while let Some(line) = lines.next() {
        if line.trim().is_empty() && !commands.is_empty() {
            break;
        }
        let body = line.strip_prefix("  ").unwrap_or_default();
        if body.starts_with(' ') || !(body.starts_with("irsig") || body.starts_with("cat ")) {
            continue;
        }
        let mut command = body.trim_end().to_owned();
        while let Some(head) = command.strip_suffix('\\') {
            let next = lines.next().unwrap_or_default();
            command = format!("{} {}", head.trim_end(), next.trim());
        }
        commands.push(command);
    }
    commands
}

/// The irsig commands of a shell line: its pipeline's and `&&` list's parts that run an
/// irsig tool, each cut at its first redirection.
fn irsig_commands(line: &str) -> Vec<Vec<String>> {
    line.split("&&")
        .flat_map(|part| part.split('|'))
        .map(|command| {
            command
                .split_whitespace()
                .take_while(|w| !w.starts_with('>') && !w.starts_with('<'))
                .map(str::to_owned)
                .collect::<Vec<_>>()
        })
        .filter(|words| words.first().is_some_and(|w| w.starts_with("irsig-")))
        .collect()
}

/// The tool's verdict on `words` (its name first): `None` when it accepts them.
fn check(words: &[String]) -> Option<String> {
    let out = Command::new(bin_path(&words[0]))
        .arg(CHECK_ARGS)
        .args(&words[1..])
        .current_dir(repo_root())
        .output()
        .unwrap();
    (!out.status.success()).then(|| {
        format!(
            "`{}` exits {:?}: {}",
            words.join(" "),
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).trim()
        )
    })
}

#[test]
fn every_help_example_is_accepted_by_its_tools_own_parser() {
    let mut failures = Vec::new();
    let mut checked = Vec::new();
    for tool in tools() {
        let help = Command::new(bin_path(&tool))
            .arg("--help")
            .output()
            .unwrap();
        assert!(help.status.success(), "{tool} --help failed");
        for line in example_lines(&String::from_utf8_lossy(&help.stdout)) {
            for words in irsig_commands(&line) {
                checked.push(words[0].clone());
                failures.extend(check(&words));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // The tools whose help shows examples, each checked at least once (a parser of the
    // help that found nothing would pass the loop above).
    for tool in [
        "irsig-atmos",
        "irsig-flatten",
        "irsig-import",
        "irsig-material",
        "irsig-merge",
        "irsig-report",
        "irsig-run",
        "irsig-stats",
        "irsig-therm",
        "irsig-trace",
    ] {
        assert!(
            checked.iter().any(|t| t == tool),
            "no example of {tool} found"
        );
    }
}

#[test]
fn an_example_with_a_flag_that_does_not_exist_would_fail() {
    // The help example that named `--temperature` after it became `--planck-temperature`.
    let words: Vec<String> = "irsig-material fresnel --nk-table water.nk --band 8-14 \
                              --temperature 300 -o water.ems"
        .split_whitespace()
        .map(str::to_owned)
        .collect();
    let message = check(&words).expect("an unknown flag is refused");
    assert!(message.contains("--temperature"), "{message}");
    // A flag's own rule, not clap's: the sun below the horizon.
    let words: Vec<String> = "irsig-trace --scene s.raw --materials m.ron --view v.ron \
                              --sun-zenith-deg 95 --sun-azimuth-deg 0 -o out/f"
        .split_whitespace()
        .map(str::to_owned)
        .collect();
    let message = check(&words).expect("a sun below the horizon is refused");
    assert!(message.contains("--sun-zenith-deg"), "{message}");
}

#[test]
fn the_examples_parser_joins_continued_lines_and_skips_prose() {
    let help = "Usage: x\n\nExamples:\n  irsig-a --b 1 \\\n      --c 2\n      prose \
                irsig-not a command\n  cat f | irsig-d - > g\n\nMore text\n  irsig-e\n";
    let lines = example_lines(help);
    assert_eq!(lines, ["irsig-a --b 1 --c 2", "cat f | irsig-d - > g"]);
    assert_eq!(irsig_commands(&lines[1]), [["irsig-d", "-"]]);
}
