//! How the page names files: relative to the report's own directory, so that a name on the
//! page still says where the file is when the page is opened from anywhere else (the
//! working directory the report was made in is not the reader's). A report written to
//! standard output has no directory of its own: its names are relative to the working
//! directory.

use std::path::{Component, Path, PathBuf};

/// Names paths relative to the report's directory.
#[derive(Debug, Clone)]
pub struct Names {
    /// The working directory, absolute.
    cwd: Option<PathBuf>,
    /// The report's directory, absolute, symbolic links resolved where it exists; `None`
    /// for a report written to standard output.
    dir: Option<PathBuf>,
}

impl Names {
    /// Names relative to the directory of `output` (`None` or `-`: the working directory).
    #[must_use]
    pub fn for_output(output: Option<&Path>) -> Self {
        let cwd = std::env::current_dir().ok();
        let dir = match (output, &cwd) {
            (Some(o), Some(cwd)) if o.as_os_str() != "-" => {
                let abs = lexical(&cwd.join(o));
                abs.parent().map(resolved)
            }
            _ => None,
        };
        Self { cwd, dir }
    }

    /// `path` (relative to the working directory, or absolute) as the page shows it.
    #[must_use]
    pub fn show(&self, path: &Path) -> String {
        let (Some(cwd), Some(dir)) = (&self.cwd, &self.dir) else {
            return path.display().to_string();
        };
        let abs = lexical(&cwd.join(path));
        // The file's directory with its links resolved, like the report's, so that both
        // are spelled alike; the file's own name is kept (a link stays the link).
        let abs = match (abs.parent(), abs.file_name()) {
            (Some(parent), Some(name)) => resolved(parent).join(name),
            _ => abs,
        };
        relative(&abs, dir).display().to_string()
    }

    /// A name as a tool was given it: `-` and `<stdin>` stay as they are.
    #[must_use]
    pub fn show_name(&self, name: &str) -> String {
        if name == "-" || name.starts_with('<') {
            name.to_owned()
        } else {
            self.show(Path::new(name))
        }
    }
}

/// The directory with its symbolic links resolved, or lexically normalised when it does
/// not exist (yet).
fn resolved(dir: &Path) -> PathBuf {
    std::fs::canonicalize(dir).unwrap_or_else(|_| lexical(dir))
}

/// `.` dropped and `..` applied to the component before it, without asking the file system.
fn lexical(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    out.push("..");
                }
            }
            other => out.push(other.as_os_str()),
        }
    }
    out
}

/// `path` relative to the directory `base`, both absolute and normalised.
fn relative(path: &Path, base: &Path) -> PathBuf {
    let p: Vec<Component<'_>> = path.components().collect();
    let b: Vec<Component<'_>> = base.components().collect();
    let common = p.iter().zip(&b).take_while(|(x, y)| x == y).count();
    if common == 0 {
        // Nothing shared (another drive): the absolute path is the only name.
        return path.to_path_buf();
    }
    let mut out = PathBuf::new();
    for _ in common..b.len() {
        out.push("..");
    }
    for c in &p[common..] {
        out.push(c.as_os_str());
    }
    if out.as_os_str().is_empty() {
        out.push(".");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_are_named_from_the_reports_directory() {
        let r = |p: &str, b: &str| relative(Path::new(p), Path::new(b)).display().to_string();
        assert_eq!(r("/a/out/q/truth.exr", "/a/out/q"), "truth.exr");
        assert_eq!(
            r("/a/pipelines/q/regions.ron", "/a/out/q"),
            "../../pipelines/q/regions.ron"
        );
        assert_eq!(r("/a/out", "/a/out/q"), "..");
        assert_eq!(
            lexical(Path::new("/a/pipelines/../out/./q")),
            Path::new("/a/out/q")
        );
        let names = Names {
            cwd: Some(PathBuf::from("/nonexistent-irsig/a/pipelines")),
            dir: Some(PathBuf::from("/nonexistent-irsig/a/out/quickstart")),
        };
        assert_eq!(
            names.show(Path::new("../out/quickstart/lut.txt")),
            "lut.txt"
        );
        assert_eq!(
            names.show(Path::new("quickstart/regions.ron")),
            "../../pipelines/quickstart/regions.ron"
        );
        assert_eq!(names.show_name("<stdin>"), "<stdin>");
        let to_stdout = Names {
            cwd: Some(PathBuf::from("/x")),
            dir: None,
        };
        assert_eq!(to_stdout.show(Path::new("../y/z.exr")), "../y/z.exr");
    }
}
