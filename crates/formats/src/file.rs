//! The one way a file is read whole, for inputs named on the command line (through
//! `irsig_cli::read_input`) and for files a format opens itself (an OBJ's `mtllib`, a glTF's
//! buffers, an execute file's viewing files).
//!
//! - Only a regular file, or a pipe (`<(…)`, a named FIFO), is read: a directory, a device
//!   such as `/dev/zero` or a socket is refused before a byte is read.
//! - At most [`MAX_INPUT_BYTES`] are read: a longer file is refused from its length, a pipe
//!   that goes on longer is refused once it passes the limit.

use std::io::{self, Read};
use std::path::Path;

pub use irsig_model::limits::MAX_INPUT_BYTES;

/// The whole content of the file at `path`.
///
/// # Errors
/// The file is missing or unreadable, is not a regular file or a pipe, or is longer than
/// [`MAX_INPUT_BYTES`]. The message does not repeat the path; callers name it.
pub fn read_file(path: &Path) -> io::Result<Vec<u8>> {
    let file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
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
