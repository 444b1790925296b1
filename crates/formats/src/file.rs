//! The one way a file is read whole, for inputs named on the command line (through
//! `irsig_cli::read_input`) and for files a format opens itself (an OBJ's `mtllib`, a glTF's
//! buffers, an execute file's viewing files).
//!
//! - Only a regular file, or a pipe (`<(…)`, a named FIFO), is read: a directory, a device
//!   such as `/dev/zero` or a socket is refused before a byte is read.
//! - At most [`MAX_INPUT_BYTES`] are read: a longer file is refused from its length, a pipe
//!   that goes on longer is refused once it passes the limit.
//! - Every regular file read is recorded ([`files_read`]), by its identity ([`FileId`]), so
//!   that the one writer (`irsig_cli::Staged`) refuses to replace any file the process has
//!   read, whoever named it: the command line, or a file the input names (an `mtllib`, an
//!   `.ems`, a viewing file).

use std::io::{self, Read};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};

pub use irsig_model::limits::MAX_INPUT_BYTES;

/// The whole content of the file at `path`.
///
/// # Errors
/// The file is missing or unreadable, is not a regular file or a pipe, or is longer than
/// [`MAX_INPUT_BYTES`]. The message does not repeat the path; callers name it.
pub fn read_file(path: &Path) -> io::Result<Vec<u8>> {
    let file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    if let Some(id) = FileId::of_opened(path, &meta).filter(|_| meta.is_file()) {
        record_read(path, id);
    }
    let kind = meta.file_type();
    #[cfg(unix)]
    let is_pipe = {
        use std::os::unix::fs::FileTypeExt as _;
        kind.is_fifo()
    };
    #[cfg(not(unix))]
    let is_pipe = false;
    if !kind.is_file() && !is_pipe {
        let what = if kind.is_dir() {
            "a directory"
        } else {
            "a device or other special file"
        };
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("it is {what}, not a regular file"),
        ));
    }
    if meta.len() > MAX_INPUT_BYTES {
        return Err(too_long(meta.len()));
    }
    read_bounded(file)
}

/// Everything `reader` gives (standard input, a pipe), refused once it passes
/// [`MAX_INPUT_BYTES`].
///
/// # Errors
/// A read error, or more than [`MAX_INPUT_BYTES`].
pub fn read_bounded(reader: impl Read) -> io::Result<Vec<u8>> {
    read_at_most(reader, MAX_INPUT_BYTES)
}

/// What makes two names one file: the device and inode on Unix (so a symbolic or hard
/// link, `./a` and `d/../a` are one), the canonical path elsewhere.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FileId {
    #[cfg(unix)]
    dev_ino: (u64, u64),
    #[cfg(not(unix))]
    canonical: PathBuf,
}

impl FileId {
    /// The file `path` names now (following symbolic links), or `None` when there is none.
    #[must_use]
    pub fn of(path: &Path) -> Option<Self> {
        let meta = std::fs::metadata(path).ok()?;
        Self::of_opened(path, &meta)
    }

    /// The file `path` was opened as, from its metadata.
    fn of_opened(path: &Path, meta: &std::fs::Metadata) -> Option<Self> {
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt as _;
            let _ = path;
            Some(Self {
                dev_ino: (meta.dev(), meta.ino()),
            })
        }
        #[cfg(not(unix))]
        {
            let _ = meta;
            Some(Self {
                canonical: std::fs::canonicalize(path).ok()?,
            })
        }
    }

    /// The regular file an open `file` is (standard input redirected from a file), or
    /// `None` for a pipe, a terminal or a device. Unix only: `None` elsewhere.
    #[must_use]
    pub fn of_regular_file(file: &std::fs::File) -> Option<Self> {
        #[cfg(unix)]
        {
            let meta = file.metadata().ok().filter(std::fs::Metadata::is_file)?;
            Self::of_opened(Path::new(""), &meta)
        }
        #[cfg(not(unix))]
        {
            let _ = file;
            None
        }
    }
}

/// The regular files this process has read, each with the name it was read by.
static READ: Mutex<Vec<(PathBuf, FileId)>> = Mutex::new(Vec::new());

/// Records a regular file read, `path` the name it was read by (standard input redirected
/// from a file, `tool - < a.exr`, is recorded by its reader), so that no output replaces it.
pub fn record_read(path: &Path, id: FileId) {
    let mut read = READ.lock().unwrap_or_else(PoisonError::into_inner);
    if !read.iter().any(|(p, i)| *i == id && p == path) {
        read.push((path.to_path_buf(), id));
    }
}

/// Every regular file this process has read through [`read_file`] (or recorded with
/// [`record_read`]), with the name it was read by: the inputs no output may replace.
#[must_use]
pub fn files_read() -> Vec<(PathBuf, FileId)> {
    READ.lock().unwrap_or_else(PoisonError::into_inner).clone()
}

fn read_at_most(reader: impl Read, limit: u64) -> io::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    reader.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_long(bytes.len() as u64));
    }
    Ok(bytes)
}

fn too_long(len: u64) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!(
            "{len} bytes or more is longer than the {MAX_INPUT_BYTES} bytes (4 GiB) an input may have"
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn a_device_is_refused_before_it_is_read() {
        // /dev/zero never ends: reading it used to grow without limit.
        let e = read_file(Path::new("/dev/zero")).unwrap_err();
        assert!(e.to_string().contains("not a regular file"), "{e}");
    }

    #[test]
    fn a_directory_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_file(dir.path()).unwrap_err();
        assert!(e.to_string().contains("a directory"), "{e}");
    }

    #[test]
    fn an_endless_stream_stops_at_the_limit() {
        let e = read_at_most(io::repeat(0), 1000).unwrap_err();
        assert!(e.to_string().contains("4 GiB"), "{e}");
        assert_eq!(read_at_most(&[7u8; 1000][..], 1000).unwrap().len(), 1000);
    }

    #[test]
    fn a_regular_file_is_read_whole() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("f");
        std::fs::write(&p, b"abc").unwrap();
        assert_eq!(read_file(&p).unwrap(), b"abc");
    }
}
