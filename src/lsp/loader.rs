//! The `#include` loader of the editor: the command line's search, reading open buffers before
//! the disk.

use std::path::Path;

use patina_compiler::syntax::preprocess::{FsLoader, LoadError, Loaded, SourceLoader, read_source_file};

use super::documents::Documents;

/// Finds includes exactly as `patina check` does ([`FsLoader::load_with`]: the includer's
/// directory, the include directories, the standard library), except that a file the editor has
/// open is read from its buffer, saved or not.
pub struct EditorLoader<'a> {
    /// The command line's loader, with the include directories.
    pub fs: &'a FsLoader,
    /// The open documents.
    pub documents: &'a Documents,
}

impl SourceLoader for EditorLoader<'_> {
    fn load(&self, target: &str, quoted: bool, includer: &str) -> Result<Loaded, LoadError> {
        self.fs.load_with(target, quoted, includer, &mut |path| match self.documents.text_at(path) {
            Some(text) => Ok(Some(text.to_string())),
            None => read_source_file(path),
        })
    }

    fn read_as_latin1(&self, name: &str) -> bool {
        // An editor's buffer is always UTF-8, whatever the file on disk holds.
        self.documents.text_at(Path::new(name)).is_none() && self.fs.read_as_latin1(name)
    }
}
