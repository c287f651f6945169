//! The front end: text to tokens (`lexer`), tokens to tokens (`preprocess`), tokens to a tree
//! (`parser` over `grammar.lalrpop`), and the checks that need only the tree (`unsupported`).

pub mod ast;
mod delimiters;
mod errors;
pub mod lexer;
pub mod parser;
pub mod preprocess;
pub mod token;
mod unsupported;

use crate::diag::Diagnostics;
use crate::source::{FileId, SourceMap};
use preprocess::SourceLoader;

/// Preprocesses and parses the file `root`, reporting every independent lexical, preprocessor and
/// syntax error, and every use of an unsupported RenderMan feature.
pub fn parse_file(
    sources: &mut SourceMap,
    root: FileId,
    loader: &dyn SourceLoader,
    diags: &mut Diagnostics,
) -> ast::Module {
    let tokens = preprocess::preprocess(sources, root, loader, diags);
    let module = parser::parse(&tokens, sources, diags);
    unsupported::check(&module, diags);
    module
}
