//! Hover: the type, rate and stage of the variable or expression under the cursor, the signature
//! and documentation of a function, the overloads of a built-in.

use std::fmt::Write;

use lsp_types::{Hover, HoverContents, MarkupContent, MarkupKind, Position};
use patina_compiler::ir::LocalKind;
use patina_compiler::ir::global::Styles;
use patina_compiler::ir::types::{Base, Rate};
use patina_compiler::sema::builtins::builtins;
use patina_compiler::sema::explain::stage;
use patina_compiler::source::Span;
use patina_compiler::stdlib;

use super::analysis::{Analysis, distinct_rates};
use super::symbols::Referent;
use super::{functions, position, scope};

/// The fence of code blocks: C's highlighting fits the language's syntax, and every client has it.
const FENCE: &str = "```c";

/// What to show for the position `at` of the document; `None` where there is nothing there.
pub fn hover(analysis: &Analysis, at: Position) -> Option<Hover> {
    let offset = analysis.offset(at)?;
    let root = analysis.checked.root;
    if let Some(name) = analysis.symbols.at(root, offset) {
        let text = match &name.referent {
            Referent::Variable(declaration) => variable(analysis, *declaration),
            Referent::Global(g) => {
                let mut out = format!("{FENCE}\n{} {}\n```\npredefined: {}\n\n", g.ty.name(), g.name, g.doc);
                // The rate the value has here (binding can raise a light's values), in the style
                // of the shader it is read in (which decides the stage).
                let here = analysis.expressions_at(offset);
                let mut rates = distinct_rates(here.iter().map(|(s, e)| (*s, e.rate)));
                if rates.is_empty() {
                    let stanford = matches!(g.styles, Styles::Stanford);
                    rates.push((Rate { frequency: g.frequency, perlight: g.perlight }, stanford));
                }
                rate_lines(&mut out, &rates);
                Some(out)
            }
            Referent::Function(name) => function(analysis, name).map(|f| f + &this_call(analysis, offset)),
            Referent::Builtin(name, _) => Some(builtin(name) + &this_call(analysis, offset)),
        };
        if let Some(text) = text {
            return Some(markdown(text, analysis, name.span));
        }
    }
    if let Some((word, span)) = analysis.word_at(offset)
        && let Some(declared) =
            scope::declaration(&analysis.checked.module, analysis.checked.root, offset, word)
    {
        let ty = Base::from_ast(declared.ty.name).name();
        let what = if declared.parameter { "parameter" } else { "variable" };
        let out = format!(
            "{FENCE}\n{ty} {word}\n```\n{what}; no rate: it is in no checked shader (a function no shader \
             calls is checked on its own, without a caller to give it rates)\n"
        );
        return Some(markdown(out, analysis, span));
    }
    let found = analysis.expressions_at(offset);
    let (_, first) = found.first()?;
    let mut out = format!("{FENCE}\n{}\n```\n", first.ty);
    rate_lines(&mut out, &distinct_rates(found.iter().map(|(s, e)| (*s, e.rate))));
    Some(markdown(out, analysis, first.span))
}

/// What the call whose name is at `offset` returns here: its type and rate.
fn this_call(analysis: &Analysis, offset: u32) -> String {
    let found = analysis.expressions_at(offset);
    let Some((_, call)) = found.first() else { return String::new() };
    let mut out = format!("\n---\nthis call: `{}`  \n", call.ty);
    rate_lines(&mut out, &distinct_rates(found.iter().map(|(s, e)| (*s, e.rate))));
    out
}

fn markdown(value: String, analysis: &Analysis, span: Span) -> Hover {
    let range = (!span.expn.is_macro()).then(|| position::range(analysis.root(), span.range()));
    Hover { contents: HoverContents::Markup(MarkupContent { kind: MarkupKind::Markdown, value }), range }
}

/// A variable or parameter: its declaration, then its rate and stage in every copy.
fn variable(analysis: &Analysis, declaration: Span) -> Option<String> {
    let copies = analysis.variable(declaration);
    let (_, local) = copies.first()?;
    let what = match local.kind {
        LocalKind::Param { output: true, .. } => "output parameter",
        LocalKind::Param { .. } => "parameter",
        _ => "variable",
    };
    let mut out = format!("{FENCE}\n{} {}\n```\n{what}", local.ty, local.name);
    if let Some(function) = &local.function {
        let _ = write!(out, " of `{function}`");
    }
    out.push_str(if local.declared { ", rate declared" } else { ", rate inferred" });
    out.push_str("\n\n");
    rate_lines(&mut out, &distinct_rates(copies.iter().map(|(s, l)| (*s, l.rate))));
    Some(out)
}

/// `rate: fragment, stage: fragment stage`, one line per distinct rate.
fn rate_lines(out: &mut String, rates: &[(Rate, bool)]) {
    for (rate, stanford) in rates {
        let _ = writeln!(out, "rate: **{rate}** · stage: {}  ", stage(*rate, *stanford));
    }
}

/// A function written in the language: each overload's signature and documentation, and where
/// it is defined.
fn function(analysis: &Analysis, name: &str) -> Option<String> {
    let sources = &analysis.checked.sources;
    let overloads = functions::named(&analysis.checked.module, name);
    let mut out = String::new();
    for f in &overloads {
        let file = &sources.file(f.name.span.file).name;
        let _ = write!(out, "{FENCE}\n{}\n```\n", functions::signature(sources, f));
        let doc = functions::documentation(sources, f);
        if !doc.is_empty() {
            let _ = write!(out, "{doc}\n\n");
        }
        let (line, _) = sources.file(f.name.span.file).line_column(f.name.span.start as usize);
        let library = if file.starts_with(stdlib::PREFIX) { " (standard library)" } else { "" };
        let _ = write!(out, "*defined in `{file}`, line {line}*{library}\n\n");
    }
    (!overloads.is_empty()).then_some(out)
}

/// A built-in: its overloads as the built-in table writes them.
fn builtin(name: &str) -> String {
    let overloads = builtins().overloads(name);
    let mut out = format!("{FENCE}\n");
    // A family of a dozen overloads says the same thing a dozen times; a few show the pattern.
    const SHOWN: usize = 8;
    for b in overloads.iter().take(SHOWN) {
        let _ = writeln!(out, "{}", b.signature);
    }
    out.push_str("```\n");
    if overloads.len() > SHOWN {
        let _ = writeln!(out, "… and {} more overloads  ", overloads.len() - SHOWN);
    }
    out.push_str("built-in function");
    if stdlib::is_library_builtin(name) {
        out.push_str(", written in the language (`compiler/stdlib/builtins.sl`)");
    }
    out.push('\n');
    out
}
