//! Finding and reading the files `#include` names.

use std::path::{Path, PathBuf};

use crate::stdlib;

/// Why an include could not be loaded.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LoadError {
    /// No search location has the file; the locations tried, in order.
    NotFound {
        /// Where the loader looked.
        searched: Vec<String>,
    },
    /// The file exists but cannot be used (I/O error, not UTF-8).
    Unreadable {
        /// The file's name as it would be shown.
        name: String,
        /// Why.
        reason: String,
    },
}

/// A file found by an include.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Loaded {
    /// The name diagnostics show, and the identity `#pragma once` keys on.
    pub name: String,
    /// The file's text.
    pub text: String,
}

/// Resolves `#include` operands to source text.
pub trait SourceLoader {
    /// Loads `target` as named by `#include "target"` (`quoted`) or `#include <target>`, from a
    /// file whose name is `includer`.
    fn load(&self, target: &str, quoted: bool, includer: &str) -> Result<Loaded, LoadError>;

    /// Whether the file named `name` (as loaded, or as the root file was named) is not UTF-8 and
    /// so was read as Latin-1 (see [`read_source_file`]); the front end warns about such files.
    fn read_as_latin1(&self, name: &str) -> bool {
        let _ = name;
        false
    }
}

/// The directory part of a file name as the loaders write them.
fn directory_of(name: &str) -> &str {
    name.rfind('/').map_or("", |i| &name[..i])
}

fn join(dir: &str, target: &str) -> String {
    if dir.is_empty() { target.to_string() } else { format!("{dir}/{target}") }
}

/// Looks in the embedded standard library, whose files are named `<stdlib>/NAME`.
fn load_stdlib(target: &str, searched: &mut Vec<String>) -> Option<Loaded> {
    let name = join(stdlib::PREFIX, target);
    searched.push(name.clone());
    stdlib::source(target).map(|text| Loaded { name, text: text.to_string() })
}

/// Reads a file from disk, telling "absent" from "unusable". A file that is not UTF-8 is read as
/// Latin-1 (older shaders carry authors' names and degree signs in it), unless it holds a NUL
/// byte, which no source text has: that is a binary file.
pub fn read_source_file(path: &Path) -> Result<Option<String>, String> {
    match std::fs::read(path) {
        Ok(bytes) => match String::from_utf8(bytes) {
            Ok(text) => Ok(Some(text)),
            Err(e) => {
                let bytes = e.as_bytes();
                match bytes.iter().position(|&b| b == 0) {
                    Some(at) => Err(format!("not a text file (a NUL byte at offset {at})")),
                    None => Ok(Some(bytes.iter().map(|&b| char::from(b)).collect())),
                }
            }
        },
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) if path.is_dir() => Err(format!("is a directory ({e})")),
        Err(e) => Err(e.to_string()),
    }
}

/// The loader of the command line: the includer's directory (for `"..."`), then the `-I`
/// directories in order, then the standard library.
#[derive(Debug, Clone, Default)]
pub struct FsLoader {
    /// The `-I` directories.
    pub include_dirs: Vec<PathBuf>,
}

impl FsLoader {
    /// The search of [`FsLoader::load`] with the reading of each candidate left to `read`, which
    /// answers as [`read_source_file`] does (`Ok(None)`: no such file, go on to the next). An
    /// editor's loader reads its open, unsaved buffers first and the disk after, so that both
    /// find the same file for the same `#include`.
    pub fn load_with(
        &self,
        target: &str,
        quoted: bool,
        includer: &str,
        read: &mut dyn FnMut(&Path) -> Result<Option<String>, String>,
    ) -> Result<Loaded, LoadError> {
        let mut searched = Vec::new();
        let includer_dir = directory_of(includer);
        if quoted
            && includer_dir == stdlib::PREFIX
            && let Some(found) = load_stdlib(target, &mut searched)
        {
            return Ok(found);
        }
        let mut candidates = Vec::new();
        if quoted && includer_dir != stdlib::PREFIX {
            candidates.push(join(includer_dir, target));
        }
        candidates.extend(self.include_dirs.iter().map(|d| d.join(target).to_string_lossy().into_owned()));
        for name in candidates {
            match read(Path::new(&name)) {
                Ok(Some(text)) => return Ok(Loaded { name, text }),
                Ok(None) => searched.push(name),
                Err(reason) => return Err(LoadError::Unreadable { name, reason }),
            }
        }
        load_stdlib(target, &mut searched).ok_or(LoadError::NotFound { searched })
    }
}

impl SourceLoader for FsLoader {
    fn load(&self, target: &str, quoted: bool, includer: &str) -> Result<Loaded, LoadError> {
        self.load_with(target, quoted, includer, &mut read_source_file)
    }

    fn read_as_latin1(&self, name: &str) -> bool {
        std::fs::read(name).is_ok_and(|bytes| std::str::from_utf8(&bytes).is_err() && !bytes.contains(&0))
    }
}

/// The warning for a file read as Latin-1 because it is not UTF-8, at `span` (the file's start,
/// or the `#include` that read it).
pub fn latin1_warning(name: &str, span: crate::source::Span) -> crate::diag::Diagnostic {
    crate::diag::Diagnostic::warning(
        crate::diag::Code::IncludeUnreadable,
        format!("`{name}` is not UTF-8; it was read as Latin-1"),
        span,
        "read as Latin-1",
    )
    .with_help("convert the file to UTF-8 (e.g. `iconv -f latin1 -t utf-8`) to silence this")
}

/// A loader over files held in memory (plus the standard library), for tests and embedders.
#[derive(Debug, Clone, Default)]
pub struct MemoryLoader {
    files: Vec<(String, String)>,
}

impl MemoryLoader {
    /// Adds a file that `#include "name"` finds.
    pub fn with_file(mut self, name: impl Into<String>, text: impl Into<String>) -> MemoryLoader {
        self.files.push((name.into(), text.into()));
        self
    }
}

impl SourceLoader for MemoryLoader {
    fn load(&self, target: &str, _quoted: bool, includer: &str) -> Result<Loaded, LoadError> {
        let mut searched = Vec::new();
        for name in [join(directory_of(includer), target), target.to_string()] {
            if let Some((name, text)) = self.files.iter().find(|(n, _)| *n == name) {
                return Ok(Loaded { name: name.clone(), text: text.clone() });
            }
            if !searched.contains(&name) {
                searched.push(name);
            }
        }
        load_stdlib(target, &mut searched).ok_or(LoadError::NotFound { searched })
    }
}
