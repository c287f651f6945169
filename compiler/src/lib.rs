//! Patina's compiler: shading-language source to diagnostics and, stage by stage, to WGSL and the
//! CPU interpreter. See ARCHITECTURE.md at the repository root for the pipeline.

pub mod backend;
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
    let module = syntax::parse_file(&mut sources, root, loader, &mut diagnostics);
    // Semantics on a tree with syntax errors would only echo them.
    let program = if diagnostics.has_errors() {
        ir::Program::default()
    } else {
        sema::check(&module, &mut diagnostics)
    };
    Checked { sources, root, module, program, diagnostics }
}
