//! All-or-nothing output: every file a run writes is staged beside its destination and only
//! renamed into place, all together, when the run has succeeded.
//!
//! - A staged file is complete on disk and holds no descriptor, so a run may stage one frame
//!   after another (a fly-by of hundreds of views) with memory and descriptors bounded by one
//!   frame.
//! - [`Staged::commit`] checks every destination before the first rename, renames them in
//!   turn, and when a later rename fails it undoes the earlier ones: a replaced file is put
//!   back from the copy it was moved to, a new one is removed.
//! - The same destination named twice is refused, as is a destination that is a directory.
//! - A destination that is a symbolic link to a file keeps its link: the file it points to is
//!   replaced.
//! - A destination that exists and is neither a file nor a directory (a device such as
//!   `/dev/null`, a named pipe, a socket) cannot be replaced by a rename without destroying
//!   it, and its writes cannot be undone: its bytes are kept in memory and written to it in
//!   place at commit, before the first rename, so that a failed write leaves every file as
//!   it was. It may be named more than once.
//! - Staged files are named `.irsig-*.tmp`; an interrupted run (SIGINT, SIGTERM) removes
//!   them ([`remove_staged_files_and_exit`], called from [`crate::run`]'s signal handler),
//!   and a commit under way is finished before they are. A staged file is created and
//!   registered under one lock, and the handler keeps that lock until the process has
//!   exited, so no thread can stage a file the handler does not see: an interrupt at any
//!   moment, during the renames too, leaves no staged file.
//! - Directories go the same way: a scratch directory ([`ScratchDir`], a LOWTRAN7 run's)
//!   and a directory written whole ([`write_dir_atomic`], a plan) are registered when they
//!   are made, so an interrupt removes them with everything in them.

use std::collections::HashSet;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

use miette::{IntoDiagnostic, WrapErr};
use tempfile::TempPath;

/// The staged files of this process that are not yet renamed into place. Held locked for the
/// whole of a commit, so an interrupt waits until the renames are done (or undone).
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn pending() -> MutexGuard<'static, Vec<PathBuf>> {
    PENDING.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Removes every staged file this process still holds (an interrupted run). Returns how many
/// were removed. Files staged after it returns are not removed: an interrupt handler calls
/// [`remove_staged_files_and_exit`] instead.
pub fn remove_staged_files() -> usize {
    remove_all(&mut pending())
}

fn remove_all(list: &mut Vec<PathBuf>) -> usize {
    list.drain(..).filter(|p| remove_any(p)).count()
}

/// Whether `path` is on the list an interrupt removes.
#[cfg(test)]
pub(crate) fn is_pending(path: &Path) -> bool {
    pending().iter().any(|p| p == path)
}

/// Removes `path` as an interrupt would, if it is on the list.
#[cfg(test)]
pub(crate) fn remove_pending(path: &Path) -> bool {
    let list = pending();
    list.iter().any(|p| p == path) && remove_any(path)
}

/// Removes the file or the directory (with everything in it) at `path`. A directory a
/// child process is still writing into may gain an entry while it is emptied: tried again.
fn remove_any(path: &Path) -> bool {
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.is_dir()) {
        (0..4).any(|_| std::fs::remove_dir_all(path).is_ok())
    } else {
        std::fs::remove_file(path).is_ok()
    }
}

/// Removes every staged file and ends the process with `code`, holding the list of staged
/// files locked until the end: a commit under way finishes first (its renames are not cut
/// in half), and no other thread can stage a new file between the removal and the exit.
pub fn remove_staged_files_and_exit(code: i32) -> ! {
    let mut list = pending();
    remove_all(&mut list);
    std::process::exit(code)
}

/// A staged file's place in [`PENDING`], from its creation (before a byte is written) until
/// it is renamed into place or removed.
struct Registration(PathBuf);

impl Registration {
    /// A new staged file beside `dest`, created and registered under one lock, so that an
    /// interrupt sees every staged file that exists.
    fn create(dest: &Path) -> io::Result<(tempfile::NamedTempFile, Self)> {
        let mut list = pending();
        let tmp = staged_file(dest)?;
        list.push(tmp.path().to_path_buf());
        let registration = Self(tmp.path().to_path_buf());
        Ok((tmp, registration))
    }
}

impl Registration {
    /// A new directory named `.irsig-*.tmp` in `parent` (a staged directory), or with
    /// `prefix` in the system's temporary directory when `parent` is `None` (a scratch
    /// directory), created and registered under one lock.
    fn create_dir(parent: Option<&Path>, prefix: &str) -> io::Result<(tempfile::TempDir, Self)> {
        let mut list = pending();
        let mut builder = tempfile::Builder::new();
        builder.prefix(prefix).suffix(".tmp");
        let dir = match parent {
            Some(p) => builder.tempdir_in(p)?,
            None => builder.tempdir()?,
        };
        list.push(dir.path().to_path_buf());
        let registration = Self(dir.path().to_path_buf());
        Ok((dir, registration))
    }
}

impl Drop for Registration {
    fn drop(&mut self) {
        let mut list = pending();
        if let Some(i) = list.iter().position(|x| *x == self.0) {
            list.swap_remove(i);
        }
    }
}

struct Entry {
    /// `None` once renamed into place. Dropped (the file removed) before `_registration`.
    staged: Option<TempPath>,
    _registration: Registration,
    /// The file the staged copy is renamed onto (a symbolic link's target).
    dest: PathBuf,
    /// The destination as the caller named it, for messages.
    named: PathBuf,
}

/// What a destination is, and so how its output is placed.
enum Destination {
    /// A regular file, or a name not yet in use: staged beside `0` and renamed onto it.
    File(PathBuf),
    /// An existing device, named pipe or socket: written in place at commit.
    Stream,
}

/// Sorts `dest` (which is not `-`) by what it is now, following a symbolic link.
fn destination(dest: &Path) -> io::Result<Destination> {
    let here = match std::fs::symlink_metadata(dest) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Destination::File(dest.into())),
        Err(e) => return Err(e),
        Ok(m) => m,
    };
    if !here.file_type().is_symlink() {
        return Ok(if here.is_file() || here.is_dir() {
            Destination::File(dest.into())
        } else {
            Destination::Stream
        });
    }
    match std::fs::metadata(dest) {
        Ok(target) if target.is_file() => Ok(Destination::File(std::fs::canonicalize(dest)?)),
        Ok(target) if target.is_dir() => Ok(Destination::File(dest.into())),
        Ok(_) => Ok(Destination::Stream),
        // A link to nothing: the link itself is replaced.
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(Destination::File(dest.into())),
        Err(e) => Err(e),
    }
}

impl std::fmt::Debug for Staged {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let dests: Vec<_> = self.entries.iter().map(|e| &e.dest).collect();
        f.debug_struct("Staged")
            .field("files", &dests)
            .field("streams", &self.streams.len())
            .field("stdout", &self.stdout.is_some())
            .finish()
    }
}

/// Outputs staged for an all-or-nothing commit. Dropping it without [`Staged::commit`]
/// removes every staged file and leaves every destination untouched.
#[derive(Default)]
pub struct Staged {
    entries: Vec<Entry>,
    keys: HashSet<PathBuf>,
    /// Devices, named pipes and sockets, and the bytes each gets, in staging order.
    streams: Vec<(PathBuf, Vec<u8>)>,
    stdout: Option<Vec<u8>>,
}

impl Staged {
    /// Nothing staged yet.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Stages `bytes` for `dest` (`-` is standard output, written after every file is in
    /// place).
    ///
    /// # Errors
    /// The destination is a directory, is named twice, or its temporary cannot be written.
    pub fn stage(&mut self, dest: &Path, bytes: &[u8]) -> miette::Result<()> {
        if dest.as_os_str() == "-" {
            if self.stdout.is_some() {
                return Err(crate::usage_error(
                    "only one output can go to standard output (`-`)",
                ));
            }
            self.stdout = Some(bytes.to_vec());
            return Ok(());
        }
        self.stage_with(dest, |w| w.write_all(bytes))
    }

    /// Stages what `write` writes for `dest`, a file (not `-`).
    ///
    /// # Errors
    /// As [`Staged::stage`], or any error from `write`.
    pub fn stage_with(
        &mut self,
        dest: &Path,
        write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
    ) -> miette::Result<()> {
        let ctx = || format!("cannot write output file `{}`", dest.display());
        check_destination(dest).wrap_err_with(ctx)?;
        refuse_replacing_an_input(dest)?;
        let file = match destination(dest).into_diagnostic().wrap_err_with(ctx)? {
            Destination::File(file) => file,
            Destination::Stream => {
                let mut bytes = Vec::new();
                write(&mut bytes).into_diagnostic().wrap_err_with(ctx)?;
                self.streams.push((dest.to_path_buf(), bytes));
                return Ok(());
            }
        };
        let (mut tmp, registration) = Registration::create(&file)
            .into_diagnostic()
            .wrap_err_with(ctx)?;
        {
            let mut w = io::BufWriter::new(tmp.as_file_mut());
            write(&mut w)
                .and_then(|()| w.flush())
                .into_diagnostic()
                .wrap_err_with(ctx)?;
        }
        tmp.as_file()
            .sync_all()
            .into_diagnostic()
            .wrap_err_with(ctx)?;
        // The key is the destination in its real directory, so `d/a` and `./d/../d/a` are
        // one output. The directory exists: the temporary was just made in it.
        let key = std::fs::canonicalize(parent_dir(&file))
            .map(|d| d.join(file.file_name().unwrap_or_default()))
            .unwrap_or_else(|_| file.clone());
        if !self.keys.insert(key) {
            return Err(crate::usage_error(format!(
                "`{}` is named as more than one output",
                dest.display()
            )));
        }
        self.entries.push(Entry {
            staged: Some(tmp.into_temp_path()),
            _registration: registration,
            dest: file,
            named: dest.to_path_buf(),
        });
        Ok(())
    }

    /// Writes the devices and named pipes among the destinations, renames every staged file
    /// into place, then writes standard output.
    ///
    /// # Errors
    /// A destination that became a directory, a device or pipe that cannot be written (every
    /// file is then as it was), or a rename that fails (every file is then as it was before
    /// the commit).
    pub fn commit(mut self) -> miette::Result<()> {
        for e in &self.entries {
            check_destination(&e.dest)
                .wrap_err_with(|| format!("cannot write output file `{}`", e.named.display()))?;
        }
        // Before the lock an interrupt takes: opening a named pipe waits for its reader.
        for (dest, bytes) in &self.streams {
            std::fs::OpenOptions::new()
                .write(true)
                .open(dest)
                .and_then(|mut f| f.write_all(bytes))
                .into_diagnostic()
                .wrap_err_with(|| format!("cannot write output `{}`", dest.display()))?;
        }
        {
            let mut list = pending();
            let mut done: Vec<(PathBuf, Option<TempPath>)> = Vec::new();
            for e in &mut self.entries {
                match place(&mut e.staged, &e.dest, &mut list) {
                    Ok(backup) => done.push((e.dest.clone(), backup)),
                    Err(err) => {
                        for (dest, backup) in done.into_iter().rev() {
                            undo(&dest, backup);
                        }
                        return Err(err).into_diagnostic().wrap_err_with(|| {
                            format!("cannot write output file `{}`", e.named.display())
                        });
                    }
                }
            }
            // Success: the replaced files' copies (`done`'s backups) are removed on drop.
        }
        match self.stdout.take() {
            Some(bytes) => crate::write_stdout(|w| w.write_all(&bytes)),
            None => Ok(()),
        }
    }
}

/// Moves `staged` onto `dest`, first moving an existing `dest` aside to a backup beside it.
/// Returns the backup (`None` when `dest` did not exist). On error `dest` is as it was.
fn place(
    staged: &mut Option<TempPath>,
    dest: &Path,
    pending: &mut Vec<PathBuf>,
) -> io::Result<Option<TempPath>> {
    let backup = if dest.symlink_metadata().is_ok() {
        let b = tempfile::Builder::new()
            .prefix(".irsig-")
            .suffix(".bak")
            .tempfile_in(parent_dir(dest))?
            .into_temp_path();
        std::fs::rename(dest, &b)?;
        Some(b)
    } else {
        None
    };
    let from = staged.as_deref().map(Path::to_path_buf).unwrap_or_default();
    match std::fs::rename(&from, dest) {
        Ok(()) => {
            // Placed: the temporary no longer exists under its own name.
            pending.retain(|x| *x != from);
            if let Some(tmp) = staged.take() {
                let _ = tmp.keep();
            }
            Ok(backup)
        }
        Err(e) => {
            if let Some(b) = backup {
                let _ = std::fs::rename(&b, dest);
                let _ = b.keep();
            }
            Err(e)
        }
    }
}

/// Puts `dest` back as it was before [`place`]: its backup renamed back, or removed.
fn undo(dest: &Path, backup: Option<TempPath>) {
    match backup {
        Some(b) => {
            if std::fs::rename(&b, dest).is_ok() {
                let _ = b.keep();
            }
        }
        None => {
            let _ = std::fs::remove_file(dest);
        }
    }
}

/// A scratch directory in the system's temporary directory (`$TMPDIR`), for a program this
/// one runs (LOWTRAN7 reads and writes its tapes in one). It and everything in it are
/// removed when it is dropped, and by an interrupt (SIGINT, SIGTERM), as staged files are.
pub struct ScratchDir {
    /// Dropped (the directory removed) before `_registration`.
    dir: tempfile::TempDir,
    _registration: Registration,
}

impl std::fmt::Debug for ScratchDir {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_tuple("ScratchDir").field(&self.dir.path()).finish()
    }
}

impl ScratchDir {
    /// A new, empty scratch directory whose name starts with `prefix`.
    ///
    /// # Errors
    /// The directory cannot be made.
    pub fn new(prefix: &str) -> io::Result<Self> {
        let (dir, registration) = Registration::create_dir(None, prefix)?;
        Ok(Self {
            dir,
            _registration: registration,
        })
    }

    /// Where it is.
    #[must_use]
    pub fn path(&self) -> &Path {
        self.dir.path()
    }
}

/// Writes `files` (paths relative to `dir`, and their bytes) as the directory `dir`, all or
/// nothing: into a staged directory beside it first, renamed into place at the end. `dir`
/// must not exist or be empty. An interrupt removes the staged directory, as it does a
/// staged file.
///
/// # Errors
/// `dir` exists and is not empty, a relative path that leaves `dir`, or any I/O error;
/// `dir` is then as it was.
pub fn write_dir_atomic(dir: &Path, files: &[(PathBuf, Vec<u8>)]) -> miette::Result<()> {
    if dir.exists() {
        let empty = std::fs::read_dir(dir)
            .into_diagnostic()
            .wrap_err_with(|| format!("cannot read `{}`", dir.display()))?
            .next()
            .is_none();
        if !empty {
            return Err(miette::miette!(
                "`{}` exists and is not empty: choose a new directory",
                dir.display()
            ));
        }
    }
    if let Some((rel, _)) = files.iter().find(|(rel, _)| {
        rel.components()
            .any(|c| !matches!(c, std::path::Component::Normal(_)))
    }) {
        return Err(miette::miette!(
            "`{}` is not a plain relative path inside `{}`",
            rel.display(),
            dir.display()
        ));
    }
    let parent = parent_dir(dir);
    std::fs::create_dir_all(&parent)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot create `{}`", parent.display()))?;
    let (tmp, registration) = Registration::create_dir(Some(&parent), ".irsig-")
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot create a directory in `{}`", parent.display()))?;
    for (rel, bytes) in files {
        let p = tmp.path().join(rel);
        if let Some(d) = p.parent() {
            std::fs::create_dir_all(d)
                .into_diagnostic()
                .wrap_err_with(|| format!("cannot create `{}`", d.display()))?;
        }
        std::fs::write(&p, bytes)
            .into_diagnostic()
            .wrap_err_with(|| format!("cannot write `{}`", p.display()))?;
    }
    // Under the lock an interrupt takes: the directory is either still staged (and removed)
    // or in place.
    let mut list = pending();
    if dir.exists() {
        std::fs::remove_dir(dir)
            .into_diagnostic()
            .wrap_err_with(|| format!("cannot replace the empty `{}`", dir.display()))?;
    }
    std::fs::rename(tmp.path(), dir)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot rename the directory into `{}`", dir.display()))?;
    list.retain(|x| x != tmp.path());
    drop(list);
    // Renamed: nothing is left under the staged name to remove.
    let _ = tmp.keep();
    drop(registration);
    Ok(())
}

/// Checks that `dest` can take an output before the work that makes it starts: `-`; a
/// device, named pipe or socket; or a name that is not a directory, in an existing
/// directory where a file can be created (a staged file is made there and removed). A long
/// run (a fly-by, a frame of hours) then fails at once, not when its first output is
/// written.
///
/// # Errors
/// A destination that is a directory, a directory that does not exist, or one where no file
/// can be created, naming them.
pub fn check_output(dest: &Path) -> miette::Result<()> {
    if dest.as_os_str() == "-" {
        return Ok(());
    }
    let ctx = || format!("cannot write output file `{}`", dest.display());
    check_destination(dest).wrap_err_with(ctx)?;
    refuse_replacing_an_input(dest)?;
    let Destination::File(file) = destination(dest).into_diagnostic().wrap_err_with(ctx)? else {
        return Ok(());
    };
    let dir = parent_dir(&file);
    if !dir.is_dir() {
        return Err(miette::miette!(
            "`{}` is not an existing directory",
            dir.display()
        ))
        .wrap_err_with(ctx);
    }
    Registration::create(&file)
        .map(drop)
        .into_diagnostic()
        .wrap_err_with(|| format!("no file can be created in `{}`", dir.display()))
        .wrap_err_with(ctx)
}

/// An output must not be a file this process has read: the one output-over-input check,
/// made for every file staged, whoever named the input (the command line, or a file an
/// input names, such as an OBJ's `mtllib`).
fn refuse_replacing_an_input(dest: &Path) -> miette::Result<()> {
    // Only the files still there under the name they were read by: a scratch file read and
    // removed since is no input any more, and its inode may now be another file's.
    let mut read = irsig_formats::file::files_read();
    read.retain(|(path, id)| irsig_formats::file::FileId::of(path).as_ref() == Some(id));
    crate::refuse_output_among(dest, &read)
}

/// An output destination must not be an existing directory.
fn check_destination(dest: &Path) -> miette::Result<()> {
    if dest.is_dir() {
        return Err(miette::miette!("`{}` is a directory", dest.display()));
    }
    Ok(())
}

fn parent_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// A temporary file beside `path`, to be renamed onto it when complete.
///
/// Created with mode 0o666 less the umask, as `File::create` would make the destination:
/// tempfile's default 0o600 would otherwise survive the rename and leave every output
/// readable by its owner only.
fn staged_file(path: &Path) -> io::Result<tempfile::NamedTempFile> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(".irsig-").suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(parent_dir(path))
}
