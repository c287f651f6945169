//! The front end: text to tokens (`lexer`), tokens to tokens (`preprocess`), tokens to a tree
//! (`parser` over `grammar.lalrpop`).

pub mod ast;
mod delimiters;
mod errors;
pub mod lexer;
pub mod parser;
pub mod preprocess;
pub mod token;

use crate::diag::Diagnostics;
use crate::source::{FileId, SourceMap};
use preprocess::SourceLoader;

/// Preprocesses and parses the file `root`, reporting every independent lexical, preprocessor and
/// syntax error.
pub fn parse_file(
    sources: &mut SourceMap,
    root: FileId,
    loader: &dyn SourceLoader,
    diags: &mut Diagnostics,
) -> ast::Module {
    let tokens = preprocess::preprocess(sources, root, loader, diags);
    parser::parse(&tokens, sources, diags)
}
