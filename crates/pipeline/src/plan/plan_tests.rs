use super::*;
use crate::TimeFlags;

fn tools() -> Tools {
    Tools::new(|t| Some(PathBuf::from(format!("/opt/irsig-{t}"))))
}

fn plan(text: &str, tools: &Tools) -> Result<Plan, PipelineError> {
    // No inputs below exist on disk, so every input is produced by a stage or absent.
    Pipeline::parse("p.ron", text, Path::new("/nonexistent"))?.plan(tools)
}

#[test]
fn reads_are_inputs_that_order_the_steps_but_are_not_words_of_the_command() {
    let text = r#"(stages: [
            (tool: "flatten", args: ["scene.ron"], reads: ["car.ron"], outputs: {"o": "w.raw"}),
            (tool: "import", outputs: {"o": "car.ron"}),
            (tool: "gen", outputs: {"o": "scene.ron"}),
        ])"#;
    let p = plan(text, &tools()).unwrap();
    let flatten = p.steps.iter().find(|s| s.tool == "flatten").unwrap();
    assert_eq!(flatten.argv, ["irsig-flatten", "scene.ron", "-o", "w.raw"]);
    let read: Vec<_> = flatten.inputs.iter().map(|f| f.path.clone()).collect();
    assert_eq!(read, [PathBuf::from("scene.ron"), PathBuf::from("car.ron")]);
    assert_eq!(flatten.deps.len(), 2, "flatten waits for import and gen");
    assert_eq!(p.steps.last().unwrap().tool, "flatten");
}

#[test]
fn parameters_become_the_words_a_user_would_type() {
    let text = r#"(stages: [(
            tool: "atmos convert",
            inputs: {"materials": "m.ron"},
            params: {"band": "8-14", "size": (512, 384), "mtf": ["a", "b"], "quiet": true,
                     "loud": false, "scale": 1e-3, "--raw": "x"},
            outputs: {"o": "out.ron", "truth": "t.exr"},
        ), (tool: "gen", outputs: {"o": "m.ron"})])"#;
    let p = plan(text, &tools()).unwrap();
    assert_eq!(p.steps[0].argv, ["irsig-gen", "-o", "m.ron"]);
    assert_eq!(
        p.steps[1].argv,
        [
            "irsig-atmos",
            "convert",
            "--materials",
            "m.ron",
            "--band",
            "8-14",
            "--size",
            "512",
            "384",
            "--mtf",
            "a",
            "--mtf",
            "b",
            "--quiet",
            "--scale",
            "1e-3",
            "--raw",
            "x",
            "-o",
            "out.ron",
            "--truth",
            "t.exr"
        ]
    );
    assert_eq!(p.steps[1].deps, [0]);
}

fn reject_size(argv: &[String]) -> Result<(), String> {
    match argv.iter().position(|w| w == "--size") {
        Some(i) if argv.get(i + 1).is_some_and(|v| v.parse::<u32>().is_err()) => Err(format!(
            "error: invalid value '{}' for '--size <N>': not a number\n\nUsage: x",
            argv[i + 1]
        )),
        Some(_) | None if argv.iter().any(|w| w == "--bogus") => {
            Err("error: unexpected argument '--bogus' found\n\n  tip: ...".to_owned())
        }
        _ => Ok(()),
    }
}

#[test]
fn validator_complaints_point_at_the_flag_or_the_value() {
    let mut t = tools();
    t.register("gen", Box::new(reject_size));
    let text = "(stages: [\n (tool: \"gen\", params: {\"size\": \"big\"}),\n])";
    let e = plan(text, &t).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::BadParameter);
    // `"big"` starts at line 2, column 33.
    assert_eq!(e.line_column(), Some((2, 33)));
    assert!(e.to_string().contains("invalid value 'big'"), "{e}");

    let text = "(stages: [\n (tool: \"gen\", params: {\"bogus\": true}),\n])";
    let e = plan(text, &t).unwrap_err();
    // `"bogus"` starts at line 2, column 25 (after ` (tool: "gen", params: {`).
    assert_eq!(e.line_column(), Some((2, 25)));
    // An unregistered tool is not checked here.
    assert!(plan(text, &tools()).is_ok());
}

#[test]
fn a_tools_own_rule_points_at_the_value_of_the_flag_it_names() {
    // `sun-zenith-deg: "95"` in a trace stage passed the dry run: the tool's own rules
    // (irsig_cli::CheckArgs) now refuse it, naming the flag first.
    let mut t = tools();
    t.register(
        "trace",
        Box::new(
            |argv: &[String]| match argv.iter().position(|w| w == "--sun-zenith-deg") {
                Some(i) if argv[i + 1] == "95" => Err(
                    "error: --sun-zenith-deg: the sun is 95.0000 deg from the zenith".to_owned(),
                ),
                _ => Ok(()),
            },
        ),
    );
    let text = "(stages: [\n (tool: \"trace\", params: {\"sun-zenith-deg\": \"95\"}),\n])";
    let e = plan(text, &t).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::BadParameter);
    // `"95"` starts at line 2, column 45.
    assert_eq!(e.line_column(), Some((2, 45)));
    assert!(e.to_string().contains("95.0000 deg"), "{e}");
}

#[test]
fn templates_need_a_sweep_and_known_variables() {
    let e = plan(
        r#"(stages: [(tool: "a", outputs: {"o": "{frame}.txt"})])"#,
        &tools(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("has no `sweep`"), "{e}");
    let e = plan(
            r#"(sweeps: {"s": Frames([{"v": 1}])}, stages: [(tool: "a", sweep: "t", outputs: {"o": "x"})])"#,
            &tools(),
        )
        .unwrap_err();
    assert!(e.to_string().contains("no sweep named `t`"), "{e}");
    let p = plan(
            r#"(sweeps: {"s": Frames([{"v": 7}, {"v": 8}])}, stages: [(tool: "a", sweep: "s", outputs: {"o": "{{{v:03}}}-{frame}"})])"#,
            &tools(),
        )
        .unwrap();
    assert_eq!(p.steps[1].argv, ["irsig-a", "-o", "{008}-2"]);
    assert_eq!(p.steps[1].name, "a#1[2]");
}

#[test]
fn a_tiles_sweep_is_one_frame_per_tile_and_a_gather_merges_them() {
    let text = r#"(sweeps: {"t": Tiles(columns: 3, rows: 2)}, stages: [
            (name: "trace", tool: "a", sweep: "t", params: {"tile": "{tile}"},
             outputs: {"o": "t{frame:02}-{tile_column}-{tile_row}"}),
            (name: "merge", tool: "m", gather: "t", args: ["t{frame:02}-{tile_column}-{tile_row}"],
             outputs: {"o": "frame"}),
        ])"#;
    let p = plan(text, &tools()).unwrap();
    assert_eq!(p.steps.len(), 7);
    // Tile 5 of 3 x 2: second row, second column.
    let five = p.steps.iter().find(|s| s.name == "trace[5]").unwrap();
    assert_eq!(five.argv, ["irsig-a", "--tile", "5/3x2", "-o", "t05-2-2"]);
    let merge = p.steps.last().unwrap();
    assert_eq!(
        merge.argv,
        [
            "irsig-m", "t01-1-1", "t02-2-1", "t03-3-1", "t04-1-2", "t05-2-2", "t06-3-2", "-o",
            "frame"
        ]
    );
    assert_eq!(merge.deps.len(), 6);
    for (bad, says) in [
        ("Tiles(columns: 0, rows: 2)", "from 1 to 100000"),
        ("Tiles(columns: 2)", "needs `rows: N`"),
        (
            "Tiles(columns: 1000, rows: 1000)",
            "more than one sweep may hold",
        ),
        (
            "Tiles(columns: 2, rows: 2, depth: 3)",
            "unknown field `depth`",
        ),
    ] {
        let text = format!(
            r#"(sweeps: {{"t": {bad}}}, stages: [(tool: "a", sweep: "t", outputs: {{"o": "x{{frame}}"}})])"#
        );
        let e = plan(&text, &tools()).unwrap_err();
        assert!(e.to_string().contains(says), "{bad}: {e}");
    }
}

const DAY: &str = r#"Times(start: "2001-08-07T12:00", end: "2001-08-07T14:00", step: "PT1H", zone: "America/Denver")"#;

#[test]
fn a_gather_stage_repeats_every_templated_value_once_per_frame() {
    // One thermal solve writes every frame's scene; each frame's trace reads its own.
    let text = format!(
        r##"(sweeps: {{"day": {DAY}}}, stages: [
            (name: "therm", tool: "therm", gather: "day", args: ["start.raw"],
             params: {{"at": "{{time}}", "hold": "#1=325", "pair": ("{{clock}}", "x")}},
             outputs: {{"raw": "s-{{time_utc}}.raw"}}),
            (name: "trace", tool: "trace", sweep: "day", inputs: {{"scene": "s-{{time_utc}}.raw"}},
             outputs: {{"o": "f-{{time_utc}}.exr"}}),
            (tool: "gen", outputs: {{"o": "start.raw"}}),
        ])"##
    );
    let p = plan(&text, &tools()).unwrap();
    let therm = p.steps.iter().find(|s| s.name == "therm").unwrap();
    assert_eq!(
        therm.argv,
        [
            "irsig-therm",
            "start.raw",
            "--at",
            "2001-08-07T12:00:00-06:00",
            "--at",
            "2001-08-07T13:00:00-06:00",
            "--at",
            "2001-08-07T14:00:00-06:00",
            "--hold",
            "#1=325",
            "--pair",
            "12:00",
            "x",
            "--pair",
            "13:00",
            "x",
            "--pair",
            "14:00",
            "x",
            "--raw",
            "s-20010807T180000Z.raw",
            "--raw",
            "s-20010807T190000Z.raw",
            "--raw",
            "s-20010807T200000Z.raw",
        ]
    );
    assert_eq!(therm.outputs.len(), 3);
    assert_eq!(therm.label, None);
    // Each trace frame waits for the one solve; its name says its time.
    let trace = p.steps.iter().find(|s| s.name == "trace[2]").unwrap();
    assert_eq!(trace.deps.len(), 1);
    assert_eq!(p.steps[trace.deps[0]].name, "therm");
    assert_eq!(trace.described(), "trace[2] (2001-08-07T13:00:00-06:00)");
    assert_eq!(trace.argv[2], "s-20010807T190000Z.raw");
    // A stage without a sweep still has no frame variables.
    let e = plan(&text.replace(r#"gather: "day", "#, ""), &tools()).unwrap_err();
    assert!(e.to_string().contains("has no `sweep`"), "{e}");
}

/// The sample weather record (Golden, Colorado, 4-7 August 2001, hourly, local standard
/// time UTC-7): its first row is 4 August hour 1 (08:00 UTC), its last 7 August hour 24
/// (8 August 07:00 UTC).
fn weathered(start: &str, end: &str) -> Result<Plan, PipelineError> {
    let mut t = tools();
    t.with_time_flags(TimeFlags {
        weather: "weather",
        weather_year: "weather-year",
    });
    let text = format!(
        "(\n  sweeps: {{\"day\": Times(start: \"{start}\",\n    end: \"{end}\", step: \"PT1H\", \
             zone: \"America/Denver\")}},\n  stages: [(tool: \"therm\", gather: \"day\", \
             inputs: {{\"weather\": \"golden-tmy3-aug.epw\"}}, params: {{\"at\": \"{{time}}\"}})],\n)"
    );
    let samples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../formats/samples");
    Pipeline::parse("p.ron", &text, &samples)?.plan(&t)
}

#[test]
fn frames_outside_the_weather_record_are_refused_at_their_time() {
    // 7 August, 00:00 to 23:00 MDT: 06:00 UTC on the 7th to 05:00 on the 8th, inside.
    assert!(weathered("2001-08-07T00:00", "2001-08-07T23:00").is_ok());
    // Ending at 02:00 MDT on the 8th (08:00 UTC), an hour past the record: at `end`.
    let e = weathered("2001-08-07T20:00", "2001-08-08T02:00").unwrap_err();
    // Line 3: `    end: ` is 9 characters, then the value.
    assert_eq!(e.line_column(), Some((3, 10)), "{e}");
    assert!(e.to_string().contains("outside the weather record"), "{e}");
    assert!(e.to_string().contains("2001-08-08T07:00:00Z"), "{e}");
    // Starting at 01:00 MDT on the 4th (07:00 UTC), an hour before it: at `start`.
    let e = weathered("2001-08-04T01:00", "2001-08-04T05:00").unwrap_err();
    // Line 2: `  sweeps: {"day": Times(start: ` is 31 characters, then the value.
    assert_eq!(e.line_column(), Some((2, 32)), "{e}");
    assert!(e.to_string().contains("2001-08-04T08:00:00Z"), "{e}");
    // 02:00 MDT on the 4th (08:00 UTC) is the record's first row: inside.
    assert!(weathered("2001-08-04T02:00", "2001-08-04T05:00").is_ok());
}

/// Line and column (from 1) of the `n`th (from 0) occurrence of `needle` in `text`.
fn place_of(text: &str, needle: &str, n: usize) -> (usize, usize) {
    let at = text.match_indices(needle).nth(n).unwrap().0;
    irsig_formats::line_column(text, at)
}

#[test]
fn control_characters_are_refused_where_they_are_written() {
    // A newline in a parameter (escaped or raw), a stage name, a path, a flag, a tool's
    // word or a sweep variable would reach a Makefile, a Slurm script or a dry run.
    let cases = [
        (
            r#"(stages: [(tool: "a", params: {"command": "a\nr.html: ; touch X #"})])"#,
            r"\n",
        ),
        (r#"(stages: [(name: "x\ntouch X", tool: "a")])"#, r"\n"),
        (
            r#"(stages: [(tool: "a", outputs: {"o": "o\u{0}"})])"#,
            r"\u{0}",
        ),
        (
            r#"(stages: [(tool: "a", params: {"k": r"tab	here"})])"#,
            "\t",
        ),
        (
            r#"(stages: [(tool: "a", params: {"k": ["ok", "cr\r"]})])"#,
            r"\r",
        ),
        (
            r#"(stages: [(tool: "a", params: {"k\x07": true})])"#,
            r"\x07",
        ),
        (r#"(stages: [(tool: "a b\x7f")])"#, r"\x7f"),
        (
            r#"(stages: [(tool: "a", params: {"k": "\\n is fine", "j": "\u{9b}"})])"#,
            r"\u{9b}",
        ),
        (
            r#"(sweeps: {"s": Frames([{"v": "x\ny"}])}, stages: [(tool: "a", sweep: "s")])"#,
            r"\n",
        ),
    ];
    for (text, bad) in cases {
        let e = plan(text, &tools()).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::ControlCharacter, "{text}: {e}");
        assert_eq!(e.line_column(), Some(place_of(text, bad, 0)), "{text}: {e}");
        assert!(e.to_string().contains("control character U+00"), "{e}");
    }
    // An escaped backslash before an `n` is no newline.
    let p = plan(r#"(stages: [(tool: "a", params: {"k": "\\n"})])"#, &tools()).unwrap();
    assert_eq!(p.steps[0].argv, ["irsig-a", "-k", "\\n"]);
}

#[test]
fn scripts_never_carry_a_word_no_shell_can_read() {
    // `--dry-run` used to print a word holding a NUL raw (shlex refuses it), so that a
    // `$(...)` in it ran. A plan built by hand, past the reader, is refused too.
    // A tool program that exists, to be hashed by the dry run.
    let this = Tools::new(|_| std::env::current_exe().ok());
    let mut p = plan(r#"(stages: [(tool: "a", outputs: {"o": "out"})])"#, &this).unwrap();
    p.steps[0].argv.push("$(touch X)\0".to_owned());
    let e = p.dry_run_script(true).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::ControlCharacter, "{e}");
    let e = p.makefile().unwrap_err();
    assert_eq!(e.kind(), ErrorKind::ControlCharacter, "{e}");
    // For messages the word is shown escaped and quoted: inert.
    assert_eq!(
        p.steps[0].command_line(),
        format!(
            "irsig-a -o out {}",
            crate::shell_quote(r"$(touch X)\0").unwrap()
        )
    );
}

#[test]
fn a_pipeline_of_no_stage_is_refused() {
    // `(stages: [])` ran nothing, rc 0.
    let e = plan("(\n  stages: [],\n)", &tools()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Structure);
    assert_eq!(e.line_column(), Some((2, 11)), "{e}");
    assert!(e.to_string().contains("no stages"), "{e}");
}

#[test]
fn an_unknown_tool_is_located() {
    let t = Tools::new(|_| None);
    let e = plan("(stages: [(tool: \"nope\")])", &t).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::UnknownTool);
    assert_eq!(e.line_column(), Some((1, 18)));
}

proptest::proptest! {
    #[test]
    fn no_text_makes_the_parser_panic(text in "\\PC{0,200}") {
        let _ = Pipeline::parse("p.ron", &text, Path::new("."));
    }

    #[test]
    fn no_mangled_pipeline_makes_the_planner_panic(cut in 0usize..400, insert in "[\\[\\](){}\",:{}a-z0-9 ]{0,5}") {
        let base = r#"(sweeps: {"s": Frames([{"v": 1}])}, stages: [(tool: "a", sweep: "s", args: ["{v}"], params: {"k": (1, 2)}, outputs: {"o": "o{frame}"}), (tool: "b", args: ["o1"], outputs: {"o": "x"})])"#;
        let at = cut.min(base.len());
        let text = format!("{}{insert}{}", &base[..at], &base[at..]);
        if let Ok(p) = Pipeline::parse("p.ron", &text, Path::new("/nonexistent")) {
            let _ = p.plan(&tools());
        }
    }
}
