//! Finding and running LOWTRAN7, the standalone program `scripts/atmosphere/install-lowtran.sh`
//! builds: a card deck `TAPE5` in the working directory in, `out/TAPE6` and `out/TAPE7`
//! out (which must exist before it starts).

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The environment variable naming the LOWTRAN7 executable.
pub const ENV: &str = "IRSIG_LOWTRAN";
/// The executable's name on `PATH`.
pub const NAME: &str = "lowtran7";

fn is_file(p: &Path) -> bool {
    p.is_file()
}

/// The LOWTRAN7 executable: `$IRSIG_LOWTRAN` if set (it must then exist), else `lowtran7`
/// on `PATH`.
///
/// # Errors
/// A message saying what was looked for and how to install it.
pub fn find() -> Result<PathBuf, String> {
    if let Some(p) = std::env::var_os(ENV).filter(|p| !p.is_empty()) {
        let p = PathBuf::from(p);
        return if is_file(&p) {
            Ok(p)
        } else {
            Err(format!(
                "{ENV} is set to `{}`, which is not a file: run `sh scripts/atmosphere/install-lowtran.sh` (it prints where LOWTRAN7 went)",
                p.display()
            ))
        };
    }
    std::env::var_os("PATH")
        .and_then(|path| {
            std::env::split_paths(&path)
                .map(|d| d.join(NAME))
                .find(|p| is_file(p))
        })
        .ok_or_else(|| {
            format!(
                "LOWTRAN7 not found: neither {ENV} is set nor `{NAME}` on PATH; build it with `sh scripts/atmosphere/install-lowtran.sh` and set {ENV} to the path it prints"
            )
        })
}

/// What one LOWTRAN7 run wrote.
#[derive(Debug, Clone)]
pub struct Output {
    /// `TAPE6`, the printed output.
    pub tape6: String,
    /// `TAPE7`, the spectral table.
    pub tape7: String,
}

/// Runs LOWTRAN7 `exe` on the card deck `deck` in a scratch directory.
///
/// # Errors
/// The program could not start, or it stopped with an error (its own message, from
/// standard error and standard output).
pub fn run(exe: &Path, deck: &str) -> Result<Output, String> {
    // Through the staged writer's registry: an interrupt removes it, as it does a staged file.
    let dir = irsig_cli::ScratchDir::new("irsig-lowtran-")
        .map_err(|e| format!("cannot make a scratch directory: {e}"))?;
    let io = |e: std::io::Error| format!("cannot prepare LOWTRAN7's files: {e}");
    std::fs::write(dir.path().join("TAPE5"), deck).map_err(io)?;
    std::fs::create_dir(dir.path().join("out")).map_err(io)?;
    for t in ["TAPE6", "TAPE7", "TAPE8"] {
        std::fs::write(dir.path().join("out").join(t), "").map_err(io)?;
    }
    let out = Command::new(exe)
        .current_dir(dir.path())
        .stdin(Stdio::null())
        .output()
        .map_err(|e| format!("cannot run LOWTRAN7 `{}`: {e}", exe.display()))?;
    // LOWTRAN's own outputs, read as every file is (bounded, a regular file).
    let read = |t: &str| {
        irsig_formats::file::read_file(&dir.path().join("out").join(t))
            .ok()
            .and_then(|b| String::from_utf8(b).ok())
            .unwrap_or_default()
    };
    if !out.status.success() {
        let said = [
            String::from_utf8_lossy(&out.stderr).trim().to_owned(),
            String::from_utf8_lossy(&out.stdout).trim().to_owned(),
        ]
        .into_iter()
        .filter(|s| !s.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
        return Err(format!("LOWTRAN7 stopped ({}): {said}", out.status));
    }
    Ok(Output {
        tape6: read("TAPE6"),
        tape7: read("TAPE7"),
    })
}
