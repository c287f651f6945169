//! Patina's compiler: shading-language source to diagnostics and, stage by stage, to WGSL and the
//! CPU interpreter. See ARCHITECTURE.md at the repository root for the pipeline.

#![warn(missing_docs)]

pub mod backend;
pub mod bind;
pub mod diag;
pub mod ir;
pub mod opt;
pub mod sema;
pub mod source;
pub mod split;
pub mod stdlib;
pub mod syntax;
pub mod verify;

use std::path::{Path, PathBuf};

use diag::Diagnostics;
use source::{FileId, SourceMap};
use syntax::ast::ShaderKind;
use syntax::preprocess::{FsLoader, SourceLoader, read_source_file};

/// The result of checking one file: its sources (with everything it included), the tree, and every
/// diagnostic found.
#[derive(Debug)]
pub struct Checked {
    /// All source text involved, for rendering diagnostics.
    pub sources: SourceMap,
    /// The root file.
    pub root: FileId,
    /// The parsed module (partial when there were errors).
    pub module: syntax::ast::Module,
    /// The checked shaders (empty when the source did not parse; shaders with errors are left out).
    pub program: ir::Program,
    /// The shaders with semantic errors, lowered as far as they went (the statements and
    /// expressions with errors left out) and with their rates inferred: for tools that show
    /// types and rates while the user fixes the errors (`patina lsp`). Never for later stages.
    pub incomplete: Vec<ir::Shader>,
    /// Errors and warnings, in the order they were found.
    pub diagnostics: Diagnostics,
}

impl Checked {
    /// Whether any diagnostic is an error.
    pub fn has_errors(&self) -> bool {
        self.diagnostics.has_errors()
    }

    /// Every diagnostic rendered as a terminal shows it (codespan's text, no colour); empty when
    /// there are none.
    pub fn diagnostics_text(&self) -> String {
        diag::render_text(&self.sources, &self.diagnostics.clone().into_vec())
    }

    /// The first checked shader of `kind` (any kind when `None`) named `name` (any name when
    /// `None`).
    pub fn find_shader(&self, kind: Option<ShaderKind>, name: Option<&str>) -> Option<&ir::Shader> {
        self.program
            .shaders
            .iter()
            .filter(|s| kind.is_none_or(|k| s.kind == k))
            .find(|s| name.is_none_or(|n| s.name == n))
    }
}

/// A source file that could not be read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadError {
    /// The file, as it was named.
    pub path: PathBuf,
    /// Why: "no such file", "is a directory", "not a text file ...", or the system's message.
    pub reason: String,
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "cannot read `{}`: {}", self.path.display(), self.reason)
    }
}

impl std::error::Error for ReadError {}

/// Reads and checks the shader file at `path` (a path `<stdlib>/name.sl` names a standard-library
/// module), shown in diagnostics by its path, with the `-I` directories `include_dirs`, in the
/// search order of docs/language.md (`#include "x"` beside the including file first, `#include
/// <x>` only in `include_dirs` and the standard library). Every command, the renderer and the
/// facade read a shader file through this, so a file checks alike everywhere.
pub fn check_file(path: &Path, include_dirs: &[PathBuf]) -> Result<Checked, ReadError> {
    let shown = path.display().to_string();
    let module = shown.strip_prefix(stdlib::PREFIX).and_then(|m| m.strip_prefix('/'));
    let text = match module.and_then(stdlib::source) {
        Some(text) => text.to_string(),
        None => match read_source_file(path) {
            Ok(Some(text)) => text,
            Ok(None) => return Err(ReadError { path: path.to_path_buf(), reason: "no such file".into() }),
            Err(reason) => return Err(ReadError { path: path.to_path_buf(), reason }),
        },
    };
    Ok(check_source(&shown, &text, &FsLoader { include_dirs: include_dirs.to_vec() }))
}

/// Checks the source `text`, shown as `name`, resolving includes with `loader`.
pub fn check_source(name: &str, text: &str, loader: &dyn SourceLoader) -> Checked {
    let mut sources = SourceMap::new();
    let root = sources.add_file(name, text, None);
    let mut diagnostics = Diagnostics::default();
    if loader.read_as_latin1(name) {
        let start = crate::source::Span::new(root, 0..0);
        diagnostics.push(syntax::preprocess::latin1_warning(name, start));
    }
    let module = syntax::parse_file(&mut sources, root, loader, &mut diagnostics);
    // Semantics on a tree with syntax errors would only echo them.
    if diagnostics.has_errors() {
        return Checked {
            sources,
            root,
            module,
            program: ir::Program::default(),
            incomplete: Vec::new(),
            diagnostics,
        };
    }
    // The built-ins written in the language are parsed only for files that may call them; a call
    // the scan misses (a name made by token pasting) is caught by the semantic stage, which then
    // asks for the library and is run again.
    let before = diagnostics.clone();
    let mut library = stdlib::mentions_library_builtins(&sources)
        .then(|| stdlib::parse_library_builtins(&mut sources, loader, &mut diagnostics));
    let mut checked = sema::check(&module, library.as_ref(), stdlib::files(&sources), &mut diagnostics);
    if checked.wants_library && library.is_none() {
        diagnostics = before;
        library = Some(stdlib::parse_library_builtins(&mut sources, loader, &mut diagnostics));
        checked = sema::check(&module, library.as_ref(), stdlib::files(&sources), &mut diagnostics);
    }
    Checked { sources, root, module, program: checked.program, incomplete: checked.incomplete, diagnostics }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh directory under the system's temporary one.
    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("patina-check-file-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn check_file_searches_as_the_language_says() {
        let dir = scratch("includes");
        let extra = dir.join("extra");
        std::fs::create_dir_all(&extra).unwrap();
        std::fs::write(dir.join("near.h"), "float near_value() { return 1; }\n").unwrap();
        std::fs::write(extra.join("far.h"), "float far_value() { return 2; }\n").unwrap();
        let shader = dir.join("s.sl");
        let text =
            "#include \"near.h\"\n#include <far.h>\nsurface s() { Ci = near_value() + far_value(); }\n";
        std::fs::write(&shader, text).unwrap();
        let checked = check_file(&shader, std::slice::from_ref(&extra)).expect("it reads");
        assert!(!checked.has_errors(), "{}", checked.diagnostics_text());
        assert_eq!(checked.sources.file(checked.root).name, shader.display().to_string());
        // Without the include directory, `far.h` is not found, and the error says so.
        let checked = check_file(&shader, &[]).expect("it reads");
        assert!(checked.has_errors());
        assert!(checked.diagnostics_text().contains("far.h"), "{}", checked.diagnostics_text());
        // An angle include is not searched beside the file (docs/language.md).
        std::fs::write(&shader, text.replace("\"near.h\"", "<near.h>")).unwrap();
        let checked = check_file(&shader, std::slice::from_ref(&extra)).expect("it reads");
        assert!(checked.has_errors());
        assert!(checked.diagnostics_text().contains("near.h"), "{}", checked.diagnostics_text());
    }

    #[test]
    fn check_file_names_what_it_cannot_read() {
        let dir = scratch("unreadable");
        let missing = dir.join("missing.sl");
        let e = check_file(&missing, &[]).expect_err("no such file");
        assert_eq!(e.to_string(), format!("cannot read `{}`: no such file", missing.display()));
        let e = check_file(&dir, &[]).expect_err("a directory");
        assert!(e.reason.starts_with("is a directory"), "{}", e.reason);
    }

    #[test]
    fn check_file_reads_standard_library_modules_by_their_prefix() {
        let checked = check_file(Path::new("<stdlib>/shaders.sl"), &[]).expect("a library module");
        assert!(!checked.has_errors(), "{}", checked.diagnostics_text());
        let light = checked.find_shader(Some(ShaderKind::Light), Some("pointlight")).expect("pointlight");
        assert_eq!(light.name, "pointlight");
        assert!(checked.find_shader(Some(ShaderKind::Surface), Some("pointlight")).is_none());
        let e = check_file(Path::new("<stdlib>/nothing.sl"), &[]).expect_err("no such module");
        assert_eq!(e.reason, "no such file");
    }
}
