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

use diag::Diagnostics;
use source::{FileId, SourceMap};
use syntax::preprocess::SourceLoader;

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
