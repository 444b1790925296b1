//! The promises every tool keeps on hostile or careless use, end to end: a closed pipe is
//! success, an interrupt leaves no staged file, several outputs appear all together or not
//! at all, and an error far along a long line is reported without a panic.

use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};

use irsig_tests::{bin, bin_path};
use predicates::prelude::*;

/// An OBJ of `n` triangles in a strip, several megabytes of scene when written out.
fn big_obj(path: &Path, n: usize) {
    let mut s = String::new();
    for i in 0..n + 2 {
        s.push_str(&format!("v {i} {} 0\n", i % 2));
    }
    for i in 1..=n {
        s.push_str(&format!("f {i} {} {}\n", i + 1, i + 2));
    }
    std::fs::write(path, s).unwrap();
}

#[test]
fn a_reader_that_stops_early_is_success() {
    // `irsig-import big.obj | head -c 100` used to exit 1 "Broken pipe", failing any
    // pipeline run under `set -o pipefail`.
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("big.obj");
    big_obj(&obj, 60_000);
    let mut child = Command::new(bin_path("irsig-import"))
        .current_dir(irsig_tests::repo_root())
        .args([
            "--materials",
            "formats/canonical/samples/materials.ron",
            "--default-material",
            "concrete",
        ])
        .arg(&obj)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 100];
    child.stdout.take().unwrap().read_exact(&mut first).unwrap();
    // The read end is closed here, long before the scene is all written.
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "{:?}: {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn an_error_at_column_72032_is_reported_not_a_panic() {
    // A machine-written one-line scene with a typo far along: the diagnostic renderer used
    // to panic past column 65,535 (exit 101).
    let dir = tempfile::tempdir().unwrap();
    let mut line = String::from("(objects: [");
    while line.len() < 72_000 {
        line.push_str("                    ");
    }
    line.push_str("Objekt(file: \"a.obj\")])");
    let scene = dir.path().join("long.ron");
    std::fs::write(&scene, &line).unwrap();
    let out = bin("irsig-flatten")
        .arg(&scene)
        .args(["--materials", "formats/canonical/samples/materials.ron"])
        .arg("-o")
        .arg(dir.path().join("out.raw"))
        .assert()
        .code(1)
        .get_output()
        .clone();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("long.ron:1:"), "{err}");
    assert!(err.len() < 4_000, "the line is cut: {} bytes", err.len());
    assert!(!dir.path().join("out.raw").exists());
}

#[cfg(unix)]
#[test]
fn an_interrupt_leaves_no_staged_file() {
    // SIGTERM while an output is being staged: the hidden `.irsig-*.tmp` files went on
    // lying in the output folder. The tool reads its input from a pipe that stays open, so
    // it is certainly interrupted before it could finish.
    let dir = tempfile::tempdir().unwrap();
    let mut child = Command::new(bin_path("irsig-testcat"))
        .arg("-o")
        .arg(dir.path().join("out.txt"))
        .arg("--copy-stdin")
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Wait until the staged file exists, then interrupt.
    let staged = || {
        std::fs::read_dir(dir.path())
            .unwrap()
            .filter_map(Result::ok)
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .count()
    };
    let start = std::time::Instant::now();
    while staged() == 0 {
        assert!(start.elapsed().as_secs() < 60, "nothing was staged");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    // Hold the pipe open through the wait: `Child::wait` closes a stdin it still owns, and
    // the end of its input would let the tool finish normally, racing the signal.
    let stdin = child.stdin.take();
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    drop(stdin);
    assert!(!status.success(), "{status:?}");
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

#[cfg(unix)]
#[test]
fn an_interrupted_atmosphere_build_leaves_no_scratch_folder() {
    // SIGINT or SIGTERM during `irsig-atmos build` left its LOWTRAN7 scratch folders
    // (`irsig-lowtran-*`, with TAPE5 and `out/`) in $TMPDIR, 4 runs of 4. Here LOWTRAN7 is
    // a stand-in that waits, so every signal lands while the runs are under way.
    let dir = tempfile::tempdir().unwrap();
    let plan = irsig_tests::quickstart_plan(dir.path(), "plan", &["--model", "us-std-1976"], &[]);
    let fake = dir.path().join("lowtran7");
    std::fs::write(&fake, "#!/bin/sh\nexec sleep 20\n").unwrap();
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    let mut wrong = Vec::new();
    for signal in ["INT", "TERM"] {
        let tmp = dir.path().join(format!("tmp-{signal}"));
        std::fs::create_dir(&tmp).unwrap();
        let mut child = Command::new(bin_path("irsig-atmos"))
            .arg("build")
            .arg(&plan)
            .arg("-o")
            .arg(dir.path().join("a.spa"))
            .args(["--jobs", "2"])
            .env("IRSIG_LOWTRAN", &fake)
            .env("TMPDIR", &tmp)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let start = std::time::Instant::now();
        while names_in(&tmp).len() < 2 {
            assert!(start.elapsed().as_secs() < 60, "no LOWTRAN7 run started");
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        let killed = Command::new("kill")
            .args([&format!("-{signal}"), &child.id().to_string()])
            .status()
            .unwrap();
        assert!(killed.success());
        let status = child.wait().unwrap();
        let left = names_in(&tmp);
        if status.success() || !left.is_empty() {
            wrong.push(format!("SIG{signal}: {status:?}, left {left:?}"));
        }
    }
    assert!(
        names_in(dir.path())
            .iter()
            .all(|n| !n.starts_with(".irsig-"))
    );
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// Every name in `dir`.
fn names_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[cfg(unix)]
#[test]
fn an_interrupt_at_any_moment_leaves_nothing_staged() {
    // SIGINT during the write phase left a staged file in 2 of 16 runs: the handler removed
    // the staged files, then let go of their list before the process ended, and the tool
    // went on staging new ones in between; and a file was created before it was listed.
    // Signals here land all along a run that stages 2,001 files and renames them into
    // place: afterwards the folder holds every output or none, and no staged file. In
    // memory (/dev/shm) when there is one, where staging is fast enough for a signal to land
    // between two files' creation often: on a disk, syncing each file hides the race.
    const EXTRA: usize = 2000;
    let shm = Path::new("/dev/shm");
    let dir = if shm.is_dir() {
        tempfile::tempdir_in(shm).unwrap()
    } else {
        tempfile::tempdir().unwrap()
    };
    let input = dir.path().join("in.txt");
    std::fs::write(&input, vec![b'x'; 4096]).unwrap();
    let out = dir.path().join("out");
    let run = |signal: Option<(&str, std::time::Duration)>| {
        if out.exists() {
            std::fs::remove_dir_all(&out).unwrap();
        }
        std::fs::create_dir(&out).unwrap();
        let mut child = Command::new(bin_path("irsig-testcat"))
            .arg(&input)
            .arg("-o")
            .arg(out.join("o"))
            .args(["--stage-many", &EXTRA.to_string()])
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        if let Some((name, delay)) = signal {
            std::thread::sleep(delay);
            // The process may have ended already: then `kill` fails, which is fine.
            let _ = Command::new("kill")
                .args([&format!("-{name}"), &child.id().to_string()])
                .stderr(Stdio::null())
                .status();
        }
        let status = child.wait().unwrap();
        (status, names_in(&out))
    };
    let start = std::time::Instant::now();
    let (status, whole) = run(None);
    let duration = start.elapsed();
    assert!(status.success(), "{status:?}");
    assert_eq!(whole.len(), EXTRA + 1, "{whole:?}");
    let mut wrong = Vec::new();
    let points = 40;
    for i in 0..points {
        let delay = duration.mul_f64(1.2 * f64::from(i) / f64::from(points));
        let signal = if i % 2 == 0 { "INT" } else { "TERM" };
        let (status, names) = run(Some((signal, delay)));
        let staged: Vec<_> = names.iter().filter(|n| n.starts_with(".irsig-")).collect();
        let placed = names.len() - staged.len();
        if !staged.is_empty() || (placed != 0 && placed != EXTRA + 1) {
            wrong.push(format!(
                "SIG{signal} after {delay:?}: {status:?}, {placed} placed, {} staged left",
                staged.len()
            ));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[cfg(unix)]
#[test]
fn a_closed_stderr_loses_the_message_not_the_exit_status() {
    // `irsig-flatten bad.ron ... 2>&1 | head -c1` exited 101 ("failed printing to stderr:
    // Broken pipe"): the message was printed with `eprintln!`, which panics on a closed
    // stderr. Here the reader of stderr is closed before the tool starts, so every write
    // to it fails.
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.ron");
    std::fs::write(&bad, "(objects: [Objekt()])").unwrap();
    let closed_stderr = irsig_tests::closed_pipe;
    let root = irsig_tests::repo_root();
    let status = Command::new(bin_path("irsig-flatten"))
        .arg(&bad)
        .args([
            "--materials",
            "formats/canonical/samples/materials.ron",
            "-o",
        ])
        .arg(dir.path().join("out.raw"))
        .current_dir(&root)
        .stdout(Stdio::null())
        .stderr(closed_stderr())
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(1), "an error: {status:?}");
    assert!(!dir.path().join("out.raw").exists());
    // A usage error, and a run that succeeds while it reports its stages on stderr.
    let status = Command::new(bin_path("irsig-sensor"))
        .args(["-", "--dc-png", "x.png"])
        .current_dir(&root)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(closed_stderr())
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(2), "bad usage: {status:?}");
    std::fs::write(dir.path().join("a.txt"), "a").unwrap();
    std::fs::write(
        dir.path().join("p.ron"),
        r#"(stages: [(tool: "testcat", args: ["a.txt"], outputs: {"o": "b.txt"})])"#,
    )
    .unwrap();
    let status = Command::new(bin_path("irsig-run"))
        .arg(dir.path().join("p.ron"))
        .stdout(Stdio::null())
        .stderr(closed_stderr())
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(0), "a run that reports: {status:?}");
    assert_eq!(std::fs::read(dir.path().join("b.txt")).unwrap(), b"a");
}

#[test]
fn no_tool_writes_over_one_of_its_inputs() {
    // `irsig-merge t0*.exr --radiance-exr t01.radiance.exr` replaced an input tile, rc 0;
    // every tool could do the same. Each command below names one of its inputs as an
    // output (by the same name, another spelling or a link): bad usage, exit 2, naming it,
    // and the input as it was.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let root = irsig_tests::repo_root();
    let copy = |from: &str, to: &str| {
        std::fs::copy(root.join(from), d.join(to)).unwrap();
    };
    copy("tests/data/malformed/base/truth.exr", "truth.exr");
    copy("formats/canonical/samples/regions.ron", "regions.ron");
    copy("formats/canonical/samples/materials.ron", "materials.ron");
    copy("formats/canonical/samples/box.obj", "box.obj");
    copy("formats/canonical/samples/box.mtl", "box.mtl");
    copy("formats/canonical/samples/box.ron", "box.ron");
    copy("formats/canonical/samples/scene.ron", "scene.ron");
    copy("tests/data/malformed/base/good.atm", "good.atm");
    copy("tests/data/malformed/base/good.dwr", "good.dwr");
    copy("formats/samples/srf-8-12um.txt", "band.srf");
    copy("formats/samples/water-hale-querry-nk.txt", "water.nk");
    copy(
        "tests/data/third-party/dirsig-channel/anadirsig.mat",
        "a.mat",
    );
    std::fs::create_dir(d.join("emissivity")).unwrap();
    for entry in
        std::fs::read_dir(root.join("tests/data/third-party/dirsig-channel/emissivity")).unwrap()
    {
        let path = entry.unwrap().path();
        std::fs::copy(&path, d.join("emissivity").join(path.file_name().unwrap())).unwrap();
    }
    copy("formats/samples/golden-tmy3-aug.epw", "w.epw");
    std::fs::write(
        d.join("p.ron"),
        r#"(stages: [(tool: "testcat", args: ["box.obj"], outputs: {"o": "x.txt"}),
            (name: "b", tool: "testcat", args: ["submit.sh"], outputs: {"o": "y.txt"})])"#,
    )
    .unwrap();
    std::fs::write(d.join("submit.sh"), "echo a stage's input\n").unwrap();
    // A flattened scene, a view and two radiance tiles of it, for trace and merge.
    let tool = |name: &str, args: &[&str]| {
        let out = Command::new(bin_path(name))
            .args(args)
            .current_dir(d)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    tool(
        "irsig-flatten",
        &[
            "scene.ron",
            "--materials",
            "materials.ron",
            "-o",
            "scene.raw",
        ],
    );
    std::fs::write(
        d.join("view.ron"),
        "LookAt(position_m: (1.5, -14.0, 3.0), target_m: (1.5, 1.0, 0.5), pixels: (8, 4), \
         fov_deg: (40.0, 20.0))",
    )
    .unwrap();
    for (tile, name) in [("1", "t0.exr"), ("2", "t1.exr")] {
        let of = format!("{tile}/1x2");
        tool(
            "irsig-trace",
            &[
                "--scene",
                "scene.raw",
                "--materials",
                "materials.ron",
                "--view",
                "view.ron",
                "--tile",
                &of,
                "--radiance-exr",
                name,
            ],
        );
    }
    #[cfg(unix)]
    std::os::unix::fs::symlink("truth.exr", d.join("alias.exr")).unwrap();
    let ems = std::fs::read_dir(d.join("emissivity"))
        .unwrap()
        .map(|e| format!("emissivity/{}", e.unwrap().file_name().to_string_lossy()))
        .next()
        .unwrap();
    let cases: Vec<(&str, Vec<&str>, &str)> = vec![
        (
            "irsig-sensor",
            vec!["truth.exr", "--mtf", "box:1x1", "-o", "truth.exr"],
            "truth.exr",
        ),
        (
            "irsig-sensor",
            vec![
                "truth.exr",
                "-o",
                "s.exr",
                "--dc-per-kelvin",
                "2",
                "--dc-png",
                "./truth.exr",
            ],
            "truth.exr",
        ),
        (
            "irsig-sensor",
            vec![
                "truth.exr",
                "-o",
                "s.exr",
                "--band",
                "band.srf",
                "--lut",
                "band.srf",
                "--dc-per-kelvin",
                "2",
            ],
            "band.srf",
        ),
        (
            "irsig-stats",
            vec!["truth.exr", "--regions", "regions.ron", "-o", "regions.ron"],
            "regions.ron",
        ),
        (
            "irsig-report",
            vec!["truth.exr", "-o", "truth.exr"],
            "truth.exr",
        ),
        (
            "irsig-import",
            vec![
                "box.obj",
                "--materials",
                "materials.ron",
                "-o",
                "materials.ron",
            ],
            "materials.ron",
        ),
        (
            "irsig-flatten",
            vec!["scene.ron", "--materials", "materials.ron", "-o", "box.ron"],
            "box.ron",
        ),
        (
            "irsig-atmos",
            vec![
                "convert",
                "--altitude-unit",
                "km",
                "--radiance-unit",
                "W/cm2/sr",
                "--name",
                "a",
                "--atm",
                "good.atm",
                "--dwr",
                "good.dwr",
                "-o",
                "good.dwr",
            ],
            "good.dwr",
        ),
        (
            "irsig-atmos",
            vec![
                "rtt", "--from", "200", "--to", "210", "--band", "band.srf", "-o", "band.srf",
            ],
            "band.srf",
        ),
        (
            "irsig-material",
            vec![
                "fresnel",
                "--nk-table",
                "water.nk",
                "--planck-temperature",
                "300",
                "--angles",
                "0:90:30",
                "-o",
                "water.nk",
            ],
            "water.nk",
        ),
        (
            "irsig-material",
            vec!["dirsig", "a.mat", "--default-emissivity", "0.9", "-o", &ems],
            &ems,
        ),
        (
            "irsig-run",
            vec!["--emit-makefile", "p.ron", "p.ron"],
            "p.ron",
        ),
        // The mtl the OBJ names, not the command line.
        (
            "irsig-import",
            vec!["box.obj", "--materials", "materials.ron", "-o", "box.mtl"],
            "box.mtl",
        ),
        // A stage's input, replaced by the Makefile; one named like an emitted script.
        (
            "irsig-run",
            vec!["--emit-makefile", "box.obj", "p.ron"],
            "box.obj",
        ),
        ("irsig-run", vec!["--emit-slurm", ".", "p.ron"], "submit.sh"),
        (
            "irsig-therm",
            vec![
                "scene.raw",
                "--materials",
                "materials.ron",
                "--weather",
                "w.epw",
                "--at",
                "2026-07-15T12:00Z",
                "-o",
                "scene",
            ],
            "scene.raw",
        ),
        (
            "irsig-trace",
            vec![
                "--scene",
                "scene.raw",
                "--materials",
                "materials.ron",
                "--view",
                "view.ron",
                "--radiance-exr",
                "x.exr",
                "--truth-exr",
                "view.ron",
            ],
            "view.ron",
        ),
        (
            "irsig-trace",
            vec![
                "--scene",
                "scene.raw",
                "--materials",
                "materials.ron",
                "--view",
                "view.ron",
                "--map-png",
                "./scene.raw",
            ],
            "scene.raw",
        ),
        (
            "irsig-trace",
            vec![
                "--scene",
                "scene.raw",
                "--materials",
                "materials.ron",
                "--view",
                "view.ron",
                "--tolerance",
                "1",
                "--radiance-exr",
                "x.exr",
                "--decision-out",
                "materials.ron",
            ],
            "materials.ron",
        ),
        (
            "irsig-merge",
            vec!["t0.exr", "t1.exr", "--radiance-exr", "t1.exr"],
            "t1.exr",
        ),
    ];
    #[cfg(unix)]
    let cases = {
        let mut c = cases;
        c.push((
            "irsig-sensor",
            vec!["truth.exr", "--mtf", "box:1x1", "-o", "alias.exr"],
            "alias.exr",
        ));
        c
    };
    let snapshot = || -> Vec<(String, Vec<u8>)> {
        let mut v = Vec::new();
        for sub in ["", "emissivity"] {
            for e in std::fs::read_dir(d.join(sub)).unwrap() {
                let e = e.unwrap();
                if e.file_type().unwrap().is_file() {
                    v.push((
                        format!("{sub}/{}", e.file_name().to_string_lossy()),
                        std::fs::read(e.path()).unwrap(),
                    ));
                }
            }
        }
        v.sort();
        v
    };
    let before = snapshot();
    let mut wrong = Vec::new();
    for (tool, args, named) in &cases {
        let out = Command::new(bin_path(tool))
            .args(args)
            .current_dir(d)
            .stdin(Stdio::null())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        if out.status.code() != Some(2)
            || !(stderr.contains("both an output and an input")
                || stderr.contains("output and also an input"))
            || !stderr.contains(named)
        {
            wrong.push(format!(
                "{tool} {}: {:?}\n{stderr}",
                args.join(" "),
                out.status
            ));
        }
        if snapshot() != before {
            wrong.push(format!("{tool} {}: changed the folder", args.join(" ")));
            break;
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn the_same_output_twice_is_refused_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let raw = dir.path().join("scene.raw");
    bin("irsig-flatten")
        .args([
            "formats/canonical/samples/scene.ron",
            "--materials",
            "formats/canonical/samples/materials.ron",
            "-o",
        ])
        .arg(&raw)
        .assert()
        .success();
    let view = dir.path().join("view.ron");
    std::fs::write(
        &view,
        "LookAt(position_m: (1.5, -14.0, 3.0), target_m: (1.5, 1.0, 0.5), pixels: (8, 6), \
         fov_deg: (64.0, 48.0))",
    )
    .unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let trace = |radiance: &str, truth: &str| {
        let mut cmd = bin("irsig-trace");
        cmd.arg("--scene")
            .arg(&raw)
            .args(["--materials", "formats/canonical/samples/materials.ron"])
            .arg("--view")
            .arg(&view)
            .args(["--atmosphere", "us-std-1976"])
            .arg("--radiance-exr")
            .arg(out.join(radiance))
            .arg("--truth-exr")
            .arg(out.join(truth));
        cmd
    };
    trace("a.exr", "a.exr")
        .assert()
        .code(2)
        .stderr(predicate::str::contains("more than one output"));
    assert!(std::fs::read_dir(&out).unwrap().next().is_none());
    // A directory among the outputs: the radiance EXR is not left behind.
    std::fs::create_dir(out.join("adir")).unwrap();
    trace("r.exr", "adir")
        .assert()
        .code(1)
        .stderr(predicate::str::contains("is a directory"));
    let left: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, ["adir"]);
}
