use super::*;

#[test]
fn failed_write_leaves_no_file_and_keeps_the_old_one() {
    let dir = tempfile::tempdir().unwrap();
    let dest = dir.path().join("out.txt");
    std::fs::write(&dest, b"old").unwrap();
    let err = write_output(Some(&dest), |w| {
        w.write_all(b"partial")?;
        Err(io::Error::other("disk on fire"))
    });
    assert!(err.is_err());
    assert_eq!(std::fs::read(&dest).unwrap(), b"old");
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        leftovers.len(),
        1,
        "temporary file left behind: {leftovers:?}"
    );
}

#[test]
fn successful_write_replaces_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let dest = dir.path().join("out.txt");
    write_output(Some(&dest), |w| w.write_all(b"new")).unwrap();
    assert_eq!(std::fs::read(&dest).unwrap(), b"new");
}

#[test]
fn missing_input_names_the_file() {
    let err = read_input("/no/such/file.obj").unwrap_err();
    assert!(format!("{err:?}").contains("/no/such/file.obj"));
}

#[cfg(unix)]
#[test]
fn a_device_named_as_input_is_refused() {
    let err = read_input("/dev/zero").unwrap_err();
    let text = format!("{err:?}");
    assert!(
        text.contains("/dev/zero") && text.contains("not a regular file"),
        "{text}"
    );
}

#[test]
fn a_closed_stdout_is_success_even_when_wrapped() {
    // `into_diagnostic` hides the io::Error from the chain; the closed pipe must still
    // be recognised, as it is whatever context a tool adds.
    let r = Report::new(ClosedStdout).wrap_err("writing the scene");
    assert!(is_broken_pipe(&r));
    let hidden = Err::<(), _>(io::Error::from(io::ErrorKind::BrokenPipe))
        .into_diagnostic()
        .unwrap_err();
    assert!(!is_broken_pipe(&hidden), "why write_stdout marks it itself");
}

#[test]
fn an_output_that_is_an_input_is_refused_by_any_name() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.exr");
    std::fs::write(&a, b"tile").unwrap();
    let new = dir.path().join("new.exr");
    // Other names of the same file: `d/./a`, a symbolic link, a hard link.
    let dotted = dir.path().join(".").join("a.exr");
    let mut names = vec![a.clone(), dotted];
    #[cfg(unix)]
    {
        let link = dir.path().join("link.exr");
        std::os::unix::fs::symlink("a.exr", &link).unwrap();
        let hard = dir.path().join("hard.exr");
        std::fs::hard_link(&a, &hard).unwrap();
        names.extend([link, hard]);
    }
    for name in &names {
        let err = refuse_output_is_input([&a], [&new, name]).unwrap_err();
        assert!(err.downcast_ref::<UsageError>().is_some(), "{err:?}");
        let text = format!("{err:?}");
        assert!(
            text.contains(&name.display().to_string())
                && text.contains("both an output and an input"),
            "{text}"
        );
        if name != &a {
            assert!(text.contains(&a.display().to_string()), "{text}");
        }
    }
    assert_eq!(std::fs::read(&a).unwrap(), b"tile");
    // `-`, a name not yet made and a device are no input.
    refuse_output_is_input([a.as_path(), Path::new("-")], [Path::new("-"), &new]).unwrap();
    #[cfg(unix)]
    refuse_output_is_input(["/dev/null"], ["/dev/null"]).unwrap();
}

#[test]
fn a_file_an_input_names_is_never_replaced_by_an_output() {
    // `irsig-import d/box.obj -o d/box.mtl` replaced the `.mtl` the OBJ names, exit 0:
    // the command line named only the OBJ. Every file read through the bounded reader
    // is one the writer refuses, whoever named it.
    let dir = tempfile::tempdir().unwrap();
    let named = dir.path().join("named.mtl");
    std::fs::write(&named, b"newmtl a").unwrap();
    irsig_formats::file::read_file(&named).unwrap();
    let through = dir.path().join(".").join("named.mtl");
    let err = write_output(Some(&through), |w| w.write_all(b"object")).unwrap_err();
    assert!(err.downcast_ref::<UsageError>().is_some(), "{err:?}");
    assert!(
        format!("{err:?}").contains("both an output and an input"),
        "{err:?}"
    );
    assert_eq!(std::fs::read(&named).unwrap(), b"newmtl a");
    assert_eq!(names(dir.path()), ["named.mtl"]);
    // Checked before a long run starts, too.
    assert!(check_output(&named).is_err());
    // A file not read is written.
    write_output(Some(&dir.path().join("other")), |w| w.write_all(b"o")).unwrap();
}

#[test]
fn an_emitted_file_is_no_file_of_the_pipeline() {
    // `irsig-run --emit-makefile p/t.exr p/p.ron` replaced the stage input `t.exr` with
    // the Makefile, and `--emit-slurm p` a stage input named `submit.sh`; a stage's
    // output not made yet is refused too (make would write it over the Makefile).
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("t.exr");
    std::fs::write(&input, b"tile").unwrap();
    let files = vec![
        (
            input.clone(),
            "an input of the pipeline's step `a`".to_owned(),
        ),
        (
            dir.path().join("sub").join("..").join("later.exr"),
            "an output of the pipeline's step `b`".to_owned(),
        ),
    ];
    let err = refuse_output_is_named(&files, [dir.path().join("./t.exr")]).unwrap_err();
    assert!(err.downcast_ref::<UsageError>().is_some(), "{err:?}");
    assert!(format!("{err:?}").contains("step `a`"), "{err:?}");
    let err = refuse_output_is_named(&files, [dir.path().join("later.exr")]).unwrap_err();
    assert!(format!("{err:?}").contains("step `b`"), "{err:?}");
    refuse_output_is_named(&files, [dir.path().join("Makefile"), PathBuf::from("-")]).unwrap();
    assert_eq!(std::fs::read(&input).unwrap(), b"tile");
}

#[test]
fn scratch_and_staged_directories_are_removed_by_an_interrupt() {
    // An interrupted `irsig-atmos build` left its LOWTRAN7 scratch folders (TAPE5,
    // `out/`) in $TMPDIR, and `plan` its directory staged beside the plan: neither went
    // through the staged writer, whose list an interrupt empties. (The list is not
    // emptied here: other tests stage files at the same time.)
    let scratch = ScratchDir::new("irsig-test-scratch-").unwrap();
    std::fs::create_dir(scratch.path().join("out")).unwrap();
    std::fs::write(scratch.path().join("out").join("TAPE6"), b"x").unwrap();
    let path = scratch.path().to_path_buf();
    assert!(staged::is_pending(&path));
    assert!(staged::remove_pending(&path));
    assert!(!path.exists(), "{} is left", path.display());
    drop(scratch);
    assert!(!staged::is_pending(&path));
    // Dropped without an interrupt, it goes too.
    let scratch = ScratchDir::new("irsig-test-scratch-").unwrap();
    let path = scratch.path().to_path_buf();
    drop(scratch);
    assert!(!path.exists() && !staged::is_pending(&path));
}

#[test]
fn a_directory_is_written_whole_or_not_at_all() {
    let dir = tempfile::tempdir().unwrap();
    let plan = dir.path().join("plan");
    let files = vec![
        (PathBuf::from("plan.ron"), b"()".to_vec()),
        (PathBuf::from("runs/0000.tape5"), b"deck".to_vec()),
    ];
    write_dir_atomic(&plan, &files).unwrap();
    assert_eq!(names(dir.path()), ["plan"]);
    assert_eq!(
        std::fs::read(plan.join("runs/0000.tape5")).unwrap(),
        b"deck"
    );
    // Not over a directory that holds something, nor outside it.
    assert!(write_dir_atomic(&plan, &files).is_err());
    let out = vec![(PathBuf::from("../x"), b"x".to_vec())];
    assert!(write_dir_atomic(&dir.path().join("other"), &out).is_err());
    assert_eq!(names(dir.path()), ["plan"]);
}

#[test]
fn usage_errors_are_recognised() {
    let r = usage_error("--from must be below --to");
    assert!(r.downcast_ref::<UsageError>().is_some());
}

#[cfg(unix)]
#[test]
fn outputs_get_the_permissions_file_create_would_give() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let reference = dir.path().join("reference");
    File::create(&reference).unwrap();
    let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
    let one = dir.path().join("one");
    write_output(Some(&one), |w| w.write_all(b"x")).unwrap();
    let many = dir.path().join("many");
    write_files_atomic(&[(many.clone(), b"y".to_vec())]).unwrap();
    assert_eq!(mode(&one), mode(&reference));
    assert_eq!(mode(&many), mode(&reference));
}

#[test]
fn several_files_appear_together() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a");
    let b = dir.path().join("b");
    write_files_atomic(&[(a.clone(), b"1".to_vec()), (b.clone(), b"2".to_vec())]).unwrap();
    assert_eq!(std::fs::read(a).unwrap(), b"1");
    assert_eq!(std::fs::read(b).unwrap(), b"2");
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn a_directory_among_the_outputs_leaves_no_file() {
    // `--radiance-exr d/r.exr --truth-exr d/adir` used to leave `r.exr`.
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("adir")).unwrap();
    let err = write_files_atomic(&[
        (dir.path().join("r.exr"), b"1".to_vec()),
        (dir.path().join("adir"), b"2".to_vec()),
    ])
    .unwrap_err();
    assert!(format!("{err:?}").contains("is a directory"), "{err:?}");
    assert_eq!(names(dir.path()), ["adir"]);
}

#[cfg(unix)]
#[test]
fn a_device_named_as_output_is_written_not_replaced() {
    // Run as root, `-o /dev/null` used to rename a staged file onto /dev/null, leaving a
    // regular file in its place for every later process.
    use std::os::unix::fs::FileTypeExt;
    let is_device =
        |p: &str| std::fs::symlink_metadata(p).is_ok_and(|m| m.file_type().is_char_device());
    assert!(is_device("/dev/null"), "/dev/null is not a device here");
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a");
    write_files_atomic(&[
        (a.clone(), b"1".to_vec()),
        ("/dev/null".into(), b"x".to_vec()),
        ("/dev/null".into(), b"y".to_vec()),
    ])
    .unwrap();
    write_output(Some(Path::new("/dev/null")), |w| w.write_all(b"z")).unwrap();
    assert!(is_device("/dev/null"), "/dev/null was replaced");
    assert_eq!(std::fs::read(&a).unwrap(), b"1");
    assert_eq!(names(dir.path()), ["a"]);
}

#[cfg(unix)]
#[test]
fn a_device_that_cannot_be_written_leaves_every_file_as_it_was() {
    // /dev/full refuses every write (ENOSPC): the files staged with it are not placed.
    let dir = tempfile::tempdir().unwrap();
    let (old, new) = (dir.path().join("old"), dir.path().join("new"));
    std::fs::write(&old, b"before").unwrap();
    let err = write_files_atomic(&[
        (old.clone(), b"after".to_vec()),
        (new, b"n".to_vec()),
        ("/dev/full".into(), b"x".to_vec()),
    ])
    .unwrap_err();
    assert!(format!("{err:?}").contains("/dev/full"), "{err:?}");
    assert_eq!(std::fs::read(&old).unwrap(), b"before");
    assert_eq!(names(dir.path()), ["old"]);
}

#[cfg(unix)]
#[test]
fn a_named_pipe_gets_the_bytes_and_stays_a_pipe() {
    use std::os::unix::fs::FileTypeExt;
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("fifo");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo (coreutils) must run");
    assert!(made.success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    write_output(Some(&fifo), |w| w.write_all(b"through the pipe")).unwrap();
    // Checked before waiting for the reader, which waits for ever on a replaced pipe.
    let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    assert!(kind.is_fifo(), "{kind:?}");
    assert_eq!(reader.join().unwrap(), b"through the pipe");
    assert_eq!(names(dir.path()), ["fifo"]);
}

#[cfg(unix)]
#[test]
fn a_symbolic_link_keeps_its_link_and_its_target_is_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let (real, link) = (dir.path().join("real"), dir.path().join("link"));
    std::fs::write(&real, b"old").unwrap();
    std::os::unix::fs::symlink("real", &link).unwrap();
    write_output(Some(&link), |w| w.write_all(b"new")).unwrap();
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read(&real).unwrap(), b"new");
    assert_eq!(names(dir.path()), ["link", "real"]);
    // The link and its target named together are one output.
    let err = write_files_atomic(&[(link, b"1".to_vec()), (real, b"2".to_vec())]).unwrap_err();
    assert!(err.downcast_ref::<UsageError>().is_some(), "{err:?}");
}

#[test]
fn an_output_is_checked_without_leaving_a_file() {
    let dir = tempfile::tempdir().unwrap();
    check_output(Path::new("-")).unwrap();
    check_output(&dir.path().join("new.exr")).unwrap();
    #[cfg(unix)]
    check_output(Path::new("/dev/null")).unwrap();
    assert!(names(dir.path()).is_empty(), "{:?}", names(dir.path()));
    let err = check_output(dir.path()).unwrap_err();
    assert!(format!("{err:?}").contains("is a directory"), "{err:?}");
    let err = check_output(&dir.path().join("gone").join("f.exr")).unwrap_err();
    assert!(
        format!("{err:?}").contains("is not an existing directory"),
        "{err:?}"
    );
}

#[test]
fn the_same_output_twice_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.exr");
    let again = dir.path().join(".").join("a.exr");
    let err = write_files_atomic(&[(a, b"1".to_vec()), (again, b"2".to_vec())]).unwrap_err();
    assert!(err.downcast_ref::<UsageError>().is_some(), "{err:?}");
    assert!(names(dir.path()).is_empty(), "{:?}", names(dir.path()));
}

#[test]
fn a_failed_rename_undoes_the_earlier_ones() {
    let dir = tempfile::tempdir().unwrap();
    let (d1, d2) = (dir.path().join("d1"), dir.path().join("d2"));
    std::fs::create_dir(&d1).unwrap();
    std::fs::create_dir(&d2).unwrap();
    let old = d1.join("old");
    std::fs::write(&old, b"before").unwrap();
    let mut staged = Staged::new();
    staged.stage(&old, b"after").unwrap();
    staged.stage(&d1.join("new"), b"n").unwrap();
    staged.stage(&d2.join("last"), b"l").unwrap();
    // The last file's staged copy disappears (its folder is swapped for an empty one):
    // its rename fails after the first two have been made.
    std::fs::rename(&d2, dir.path().join("moved")).unwrap();
    std::fs::create_dir(&d2).unwrap();
    assert!(staged.commit().is_err());
    assert_eq!(std::fs::read(&old).unwrap(), b"before");
    assert_eq!(names(&d1), ["old"]);
    assert!(names(&d2).is_empty(), "{:?}", names(&d2));
}

#[test]
fn staged_files_hold_no_descriptor_and_vanish_when_dropped() {
    let dir = tempfile::tempdir().unwrap();
    let mut staged = Staged::new();
    for i in 0..3 {
        staged
            .stage(&dir.path().join(format!("f{i}")), b"x")
            .unwrap();
    }
    let mut held: Vec<_> = std::fs::read_dir("/proc/self/fd").map_or(vec![], |d| {
        d.filter_map(|e| std::fs::read_link(e.ok()?.path()).ok())
            .collect()
    });
    held.retain(|p| p.starts_with(dir.path()));
    assert!(held.is_empty(), "descriptors held: {held:?}");
    assert_eq!(names(dir.path()).len(), 3);
    drop(staged);
    assert!(names(dir.path()).is_empty());
    let mut staged = Staged::new();
    staged.stage(&dir.path().join("g"), b"x").unwrap();
    drop(staged);
    assert!(names(dir.path()).is_empty());
}
