//! Staged files: every file is created as a temporary file beside its target before any
//! computation (so a bad path fails at once), written, flushed, and renamed over the
//! target only when complete. An error or an interruption leaves no partial file and any
//! earlier file of that name intact.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use serde::Serialize;
use tempfile::NamedTempFile;

use super::live;
use crate::error::{Error, Result};

/// The files a command may write at a path it was given: their extensions, and what to
/// say about another one.
#[derive(Debug, Clone, Copy)]
pub struct Allowed<'a> {
    /// What the files are, the start of the error for another extension (e.g. "plots are
    /// PNG images").
    pub what: &'a str,
    /// The extensions allowed, lowercase without the dot (matched case-insensitively).
    pub extensions: &'a [&'a str],
}

/// An I/O error's text without the path it may carry (a temporary file's name is no
/// business of the user's): the system's message, e.g. `Permission denied (os error 13)`.
fn io_text(e: &std::io::Error) -> String {
    match e.raw_os_error() {
        Some(code) => std::io::Error::from_raw_os_error(code).to_string(),
        // tempfile's errors say `… at path "…/.NAME.XXXXXX.part"`.
        None => {
            let text = e.to_string();
            text.split(" at path ")
                .next()
                .unwrap_or_default()
                .to_string()
        }
    }
}

/// Creates the folder `dir` of the output `path` when it is missing, after checking that
/// no part of it is an existing file.
fn create_folder(path: &Path, dir: &Path) -> Result<()> {
    if dir.is_dir() {
        return Ok(());
    }
    if let Some(file) = dir.ancestors().find(|a| a.exists() && !a.is_dir()) {
        return Err(Error::Output {
            path: path.to_path_buf(),
            message: format!("{} is a file, not a folder", file.display()),
        });
    }
    std::fs::create_dir_all(dir).map_err(|e| Error::Output {
        path: path.to_path_buf(),
        message: format!(
            "cannot create the folder {}: {}",
            dir.display(),
            io_text(&e)
        ),
    })
}

/// A file being written: a temporary file beside its target, registered in [`live`]
/// from its creation until it is renamed or dropped, so SIGINT/SIGTERM remove it.
pub struct Staged {
    pub path: PathBuf,
    /// `None` once renamed over the target.
    tmp: Option<NamedTempFile>,
    id: u64,
}

impl Staged {
    /// Creates the temporary file now, so an unwritable target fails before any work.
    pub fn create(path: &Path) -> Result<Self> {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .ok_or_else(|| Error::Output {
                path: path.to_path_buf(),
                message: "not a file name".into(),
            })?;
        if path.is_dir() {
            return Err(Error::Output {
                path: path.to_path_buf(),
                message: "is a folder".into(),
            });
        }
        create_folder(path, dir)?;
        let prefix = format!(".{name}.");
        let mut builder = tempfile::Builder::new();
        builder.prefix(&prefix).suffix(".part");
        // Finished files get ordinary permissions, not the private mode of temporary files.
        #[cfg(unix)]
        builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o644));
        // Created and registered under the lock: a signal cannot fall between the two.
        let mut live = live::lock();
        let tmp = builder.tempfile_in(dir).map_err(|e| Error::Output {
            path: path.to_path_buf(),
            message: format!("cannot write in {}: {}", dir.display(), io_text(&e)),
        })?;
        let id = live::register(&mut live, tmp.path());
        Ok(Self {
            path: path.to_path_buf(),
            tmp: Some(tmp),
            id,
        })
    }

    /// Stages `path` (as [`Staged::create`]) after checking that its extension is one of
    /// `allowed` and that it is none of the files of `not_same_as`, each with what to say
    /// when it is (e.g. an input being read: "is the file being analyzed").
    pub fn create_checked(
        path: &Path,
        allowed: &Allowed,
        not_same_as: &[(&Path, &str)],
    ) -> Result<Self> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        if !ext.is_some_and(|e| allowed.extensions.contains(&e.as_str())) {
            let names: Vec<String> = allowed.extensions.iter().map(|e| format!(".{e}")).collect();
            return Err(Error::Output {
                path: path.to_path_buf(),
                message: format!(
                    "{}: the file name must end in {}",
                    allowed.what,
                    names.join(" or ")
                ),
            });
        }
        for (other, message) in not_same_as {
            let same = match (std::fs::canonicalize(path), std::fs::canonicalize(other)) {
                (Ok(a), Ok(b)) => a == b,
                _ => path == *other,
            };
            if same {
                return Err(Error::Output {
                    path: path.to_path_buf(),
                    message: message.to_string(),
                });
            }
        }
        Self::create(path)
    }

    /// Writes the content through a buffered writer, then renames over the target.
    pub fn write_with(
        mut self,
        f: impl FnOnce(&mut BufWriter<&File>) -> std::io::Result<()>,
    ) -> Result<()> {
        let io = |e| Error::io(&self.path, e);
        let tmp = self.tmp.take().expect("a staged file is written once");
        let written = (|| {
            let mut w = BufWriter::with_capacity(1 << 20, tmp.as_file());
            f(&mut w)?;
            w.flush()
        })();
        if let Err(e) = written {
            // Removed before the registry forgets it.
            drop(tmp);
            return Err(io(e));
        }
        // Renamed under the lock: an interruption leaves the target complete or untouched.
        let persisted = {
            let _live = live::lock();
            tmp.persist(&self.path)
        };
        persisted.map_err(|e| Error::io(&self.path, e.error))?;
        Ok(())
    }
}

impl Staged {
    /// Writes `value` as pretty-printed JSON with a final newline (sidecars, indexes).
    pub fn write_json(self, value: &impl Serialize) -> Result<()> {
        self.write_with(|w| {
            serde_json::to_writer_pretty(&mut *w, value)?;
            w.write_all(b"\n")
        })
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        let mut live = live::lock();
        // An unwritten file is removed (NamedTempFile's drop) while the lock is held.
        drop(self.tmp.take());
        live.remove(&self.id);
    }
}
