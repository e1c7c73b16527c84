//! The files a command writes: checked before any work starts, and
//! written whole.
//!
//! A command names what it reads and writes in an [`Outputs`] plan and
//! calls [`Outputs::check`] first: an output that is one of the inputs, two
//! outputs that are one file, a folder that is missing or cannot be written
//! are refused before a second of simulation is spent. [`write_whole`]
//! writes through a uniquely named file beside the target and renames it
//! over, so an interrupted write never leaves half a file and never
//! touches a file nobody named.

use std::io::Write;
use std::path::{Path, PathBuf};

/// An output that cannot be written as asked.
#[derive(Debug, thiserror::Error)]
#[error("{flag} {path}: {message}")]
pub struct OutputError {
    /// The option naming the output (`--trace`, `--out`).
    pub flag: String,
    /// The path given.
    pub path: String,
    /// What is wrong.
    pub message: String,
}

/// What a command reads and writes.
#[derive(Debug, Default)]
pub struct Outputs {
    inputs: Vec<PathBuf>,
    files: Vec<(String, PathBuf)>,
    folders: Vec<(String, PathBuf)>,
    /// Files whose extension must say what they hold: flag, path, what
    /// they hold, the extensions that say so.
    kinds: Vec<(String, PathBuf, &'static str, &'static [&'static str])>,
}

impl Outputs {
    /// An empty plan.
    pub fn new() -> Outputs {
        Outputs::default()
    }

    /// A file the command reads (never to be written over).
    pub fn input(mut self, path: &Path) -> Outputs {
        self.inputs.push(path.to_path_buf());
        self
    }

    /// A file the command writes, named by option `flag` (`-` is standard
    /// output and is not checked).
    pub fn file(mut self, flag: &str, path: &Path) -> Outputs {
        if path != Path::new("-") {
            self.files.push((flag.to_string(), path.to_path_buf()));
        }
        self
    }

    /// A file the command writes holding `what` (`CSV`, `a PNG picture`):
    /// as [`Outputs::file`], and its extension, if it has one, must be
    /// one of `extensions` (a file named `results.png` holding CSV would
    /// mislead every program that opens it).
    pub fn file_as(
        mut self,
        flag: &str,
        path: &Path,
        what: &'static str,
        extensions: &'static [&'static str],
    ) -> Outputs {
        if path != Path::new("-") {
            self.kinds
                .push((flag.to_string(), path.to_path_buf(), what, extensions));
        }
        self.file(flag, path)
    }

    /// A folder the command writes into (created by [`Outputs::check`]).
    pub fn folder(mut self, flag: &str, path: &Path) -> Outputs {
        self.folders.push((flag.to_string(), path.to_path_buf()));
        self
    }

    /// Refuse the plan if an output is an input, two outputs are one file,
    /// an output file is a folder, or a folder is missing or read-only.
    /// Creates the output folders (nothing else).
    pub fn check(&self) -> Result<(), OutputError> {
        let err = |flag: &str, path: &Path, message: String| OutputError {
            flag: flag.to_string(),
            path: path.display().to_string(),
            message,
        };
        for (flag, dir) in &self.folders {
            if dir.exists() && !dir.is_dir() {
                return Err(err(flag, dir, "exists and is not a folder".into()));
            }
            std::fs::create_dir_all(dir)
                .map_err(|e| err(flag, dir, format!("cannot create the folder: {e}")))?;
            writable(dir).map_err(|e| err(flag, dir, format!("cannot write in it: {e}")))?;
        }
        let inputs: Vec<PathBuf> = self.inputs.iter().filter_map(|p| identity(p)).collect();
        let mut seen: Vec<(&str, PathBuf)> = Vec::new();
        for (flag, file) in &self.files {
            if file.is_dir() {
                return Err(err(flag, file, "is a folder; name a file".into()));
            }
            let dir = folder_of(file);
            if !dir.is_dir() {
                return Err(err(
                    flag,
                    file,
                    format!("the folder {} does not exist", dir.display()),
                ));
            }
            writable(dir).map_err(|e| {
                err(
                    flag,
                    file,
                    format!("cannot write in {}: {e}", dir.display()),
                )
            })?;
            let Some(id) = identity(file) else { continue };
            if let Some(k) = inputs.iter().position(|i| *i == id) {
                return Err(err(
                    flag,
                    file,
                    format!(
                        "is {}, which this command reads; name another file",
                        self.inputs[k].display()
                    ),
                ));
            }
            if let Some((other, _)) = seen.iter().find(|(_, p)| *p == id) {
                return Err(err(
                    flag,
                    file,
                    format!("is also the file of {other}; name two files"),
                ));
            }
            seen.push((flag, id));
        }
        for (flag, file, what, extensions) in &self.kinds {
            let Some(ext) = file.extension().map(|e| e.to_string_lossy().to_lowercase()) else {
                continue;
            };
            if !extensions.contains(&ext.as_str()) {
                let want: Vec<String> = extensions.iter().map(|e| format!(".{e}")).collect();
                return Err(err(
                    flag,
                    file,
                    format!(
                        "is named .{ext} but holds {what}; name it {}",
                        want.join(" or ")
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// The folder a file is in (`.` for a bare name).
fn folder_of(file: &Path) -> &Path {
    match file.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// A path's identity: canonical, whether or not the file exists yet.
fn identity(p: &Path) -> Option<PathBuf> {
    if let Ok(c) = p.canonicalize() {
        return Some(c);
    }
    let dir = folder_of(p).canonicalize().ok()?;
    Some(dir.join(p.file_name()?))
}

/// Whether a file can be made in `dir` (a probe, removed at once).
fn writable(dir: &Path) -> std::io::Result<()> {
    tempfile::Builder::new()
        .prefix(".shisen-probe-")
        .tempfile_in(dir)
        .map(drop)
}

/// Write `bytes` to `path` whole or not at all: into a new, uniquely named
/// file beside it, renamed over `path` once complete (no other file is
/// touched, and an interruption leaves the old `path` as it was).
pub fn write_whole(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::os::unix::fs::PermissionsExt;
    // The file keeps its mode when replaced; a new one is readable by all
    // (a temporary file would be the owner's only).
    let mode = std::fs::metadata(path).map_or(0o644, |m| m.permissions().mode() & 0o7777);
    let mut tmp = tempfile::Builder::new()
        .prefix(".shisen-")
        .suffix(".tmp")
        .permissions(std::fs::Permissions::from_mode(mode))
        .tempfile_in(folder_of(path))?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_data()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_over_inputs_each_other_or_missing_folders_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("x.ron");
        std::fs::write(&scene, "()").unwrap();
        let check = |o: Outputs| o.check().map_err(|e| e.to_string());
        let e = check(Outputs::new().input(&scene).file("--trace", &scene)).unwrap_err();
        assert!(e.contains("which this command reads"), "{e}");
        // The same file by another spelling.
        let other = dir.path().join(".").join("x.ron");
        assert!(check(Outputs::new().input(&scene).file("--trace", &other)).is_err());
        let a = dir.path().join("a.csv");
        let e = check(Outputs::new().file("--trace", &a).file("--plot", &a)).unwrap_err();
        assert!(e.contains("also the file of --trace"), "{e}");
        let e = check(Outputs::new().file("--out", &dir.path().join("no/a.png"))).unwrap_err();
        assert!(e.contains("does not exist"), "{e}");
        let e = check(Outputs::new().file("--out", dir.path())).unwrap_err();
        assert!(e.contains("folder"), "{e}");
        let e = check(Outputs::new().file_as("--out", &dir.path().join("r.png"), "CSV", &["csv"]))
            .unwrap_err();
        assert!(e.contains("holds CSV; name it .csv"), "{e}");
        assert!(
            check(Outputs::new().file_as("--out", &dir.path().join("r.CSV"), "CSV", &["csv"]))
                .is_ok()
        );
        assert!(
            check(Outputs::new().file_as("--out", &dir.path().join("results"), "CSV", &["csv"]))
                .is_ok()
        );
        let e = check(Outputs::new().file("--out", dir.path())).unwrap_err();
        assert!(e.contains("is a folder"), "{e}");
        assert!(
            check(
                Outputs::new()
                    .input(&scene)
                    .file("--trace", &a)
                    .file("-", Path::new("-"))
            )
            .is_ok()
        );
        let made = dir.path().join("made/deeper");
        assert!(check(Outputs::new().folder("--out", &made)).is_ok());
        assert!(made.is_dir());
    }

    #[test]
    fn a_whole_write_leaves_no_other_file() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("r.csv");
        // A file the old code used as its temporary is left alone.
        std::fs::write(dir.path().join("r.csv.tmp"), "mine").unwrap();
        write_whole(&p, b"one").unwrap();
        write_whole(&p, b"two").unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "two");
        assert_eq!(
            std::fs::read_to_string(dir.path().join("r.csv.tmp")).unwrap(),
            "mine"
        );
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
    }
}
