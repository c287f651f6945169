//! One document checked: the compiler's front end, run exactly as `patina check` runs it.
//!
//! There is no second checker. The document's text goes through `check_source` with the editor's
//! loader; the diagnostics are the command line's, and hover, definitions, hints and tokens read
//! the typed IR it produced (`symbols.rs`).

use std::path::Path;

use lsp_types::Position;
use patina_compiler::ir::types::Rate;
use patina_compiler::ir::{Expr, Local, Shader};
use patina_compiler::source::{FileId, SourceFile, Span};
use patina_compiler::syntax::preprocess::SourceLoader;
use patina_compiler::{Checked, check_source};

use super::symbols::Symbols;
use super::{position, uri};

/// A document's text as the compiler saw it, and what it found.
pub struct Analysis {
    /// The front end's result: sources (the document is `checked.root`), tree, IR, diagnostics.
    pub checked: Checked,
    /// The names written in the sources and what they refer to.
    pub symbols: Symbols,
    /// What the compiler said if it panicked on this text (a bug: the analysis is then that of an
    /// empty document, and the message is shown as a diagnostic).
    pub panic: Option<String>,
}

impl Analysis {
    /// Checks `text`, named `name`, with `loader` for its includes.
    pub fn run(name: &str, text: &str, loader: &dyn SourceLoader) -> Analysis {
        let run = || {
            let checked = check_source(name, text, loader);
            let shaders: Vec<&Shader> = checked.program.shaders.iter().chain(&checked.incomplete).collect();
            let symbols = Symbols::build(&checked.sources, &checked.module, &shaders);
            (checked, symbols)
        };
        // A compiler bug must not end the editing session: the document is then shown as empty,
        // with the panic as its diagnostic, until the next edit.
        let (checked, symbols, panic) = match std::panic::catch_unwind(std::panic::AssertUnwindSafe(run)) {
            Ok((checked, symbols)) => (checked, symbols, None),
            Err(payload) => {
                let message = payload
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "no message".to_string());
                let checked = check_source(name, "", loader);
                (checked, Symbols::default(), Some(message))
            }
        };
        Analysis { symbols, checked, panic }
    }

    /// Every shader: the checked program's, then (numbered after them) those with errors, lowered
    /// as far as they went.
    pub fn shaders(&self) -> impl Iterator<Item = &Shader> {
        self.checked.program.shaders.iter().chain(&self.checked.incomplete)
    }

    /// Shader `index` of [`Analysis::shaders`].
    pub fn shader(&self, index: usize) -> &Shader {
        let checked = &self.checked.program.shaders;
        checked.get(index).unwrap_or_else(|| &self.checked.incomplete[index - checked.len()])
    }

    /// The document itself.
    pub fn root(&self) -> &SourceFile {
        self.checked.sources.file(self.checked.root)
    }

    /// The byte offset of a protocol position in the document.
    pub fn offset(&self, at: Position) -> Option<u32> {
        position::offset(self.root(), at).map(|o| o as u32)
    }

    /// Whether the document's includes read the file at `path`.
    pub fn reads(&self, path: &Path) -> bool {
        self.checked
            .sources
            .files()
            .any(|(id, f)| id != self.checked.root && uri::normalize(Path::new(&f.name)) == path)
    }

    /// Whether the semantic stage ran on this text: it does not on a text with syntax errors, and
    /// then every shader of the tree is missing from the IR.
    pub fn has_semantics(&self) -> bool {
        use patina_compiler::syntax::ast::Item;
        let has_shaders = self.checked.module.items.iter().any(|i| matches!(i, Item::Shader(_)));
        !has_shaders || self.shaders().next().is_some()
    }

    /// The identifier of the document around byte `offset`, with its span.
    pub fn word_at(&self, offset: u32) -> Option<(&str, Span)> {
        let text = &*self.root().text;
        let offset = (offset as usize).min(text.len());
        let is_word = |c: char| c.is_ascii_alphanumeric() || c == '_';
        let start = text[..offset].rfind(|c: char| !is_word(c)).map_or(0, |i| i + 1);
        let end = text[offset..].find(|c: char| !is_word(c)).map_or(text.len(), |i| offset + i);
        let word = &text[start..end];
        let starts_like_a_name = word.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
        starts_like_a_name.then(|| (word, Span::new(self.checked.root, start..end)))
    }

    /// Whether `file` is the document (not a file it includes).
    pub fn is_root(&self, file: FileId) -> bool {
        file == self.checked.root
    }

    /// The copies of the variable declared at `declaration` (see [`super::symbols::Instance`]),
    /// each with the shader it is in.
    pub fn variable(&self, declaration: Span) -> Vec<(&Shader, &Local)> {
        let instances = self.symbols.instances(declaration);
        instances.iter().map(|i| (self.shader(i.shader), self.shader(i.shader).local(i.local))).collect()
    }

    /// The innermost expressions of the document around byte `offset`: one per copy of that
    /// text in the IR (a function's body is inlined at every call), each with its shader.
    pub fn expressions_at(&self, offset: u32) -> Vec<(&Shader, &Expr)> {
        let around = |e: &&Expr| {
            self.is_root(e.span.file) && !e.span.expn.is_macro() && e.span.contains_offset(offset)
        };
        let all: Vec<(&Shader, &Expr)> =
            self.shaders().flat_map(|s| s.exprs.iter().filter(around).map(move |e| (s, e))).collect();
        let Some(width) = all.iter().map(|(_, e)| e.span.end - e.span.start).min() else { return Vec::new() };
        all.into_iter().filter(|(_, e)| e.span.end - e.span.start == width).collect()
    }
}

/// The distinct rates among copies of one value, lowest first, each with the style of a shader it
/// has that rate in (which decides the stage it runs in).
pub fn distinct_rates<'a>(copies: impl IntoIterator<Item = (&'a Shader, Rate)>) -> Vec<(Rate, bool)> {
    let mut rates: Vec<(Rate, bool)> = copies.into_iter().map(|(s, r)| (r, s.stanford)).collect();
    rates.sort_by_key(|(r, stanford)| (r.frequency, r.perlight, *stanford));
    rates.dedup_by_key(|(r, _)| *r);
    rates
}

/// The rates of `rates` as a label: `fragment`, or `primitive group | fragment` for a function's
/// variable whose calls differ.
pub fn rates_label(rates: &[(Rate, bool)]) -> String {
    rates.iter().map(|(r, _)| r.to_string()).collect::<Vec<_>>().join(" | ")
}
