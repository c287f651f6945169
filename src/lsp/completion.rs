//! Completion: the names in scope at the cursor (parameters and variables, with their types and
//! rates), the functions of the file and its includes (the standard library's with their
//! signatures), the built-in functions and the predefined variables.

use std::collections::HashSet;

use lsp_types::{CompletionItem, CompletionItemKind, CompletionResponse, Documentation, Position};
use patina_compiler::ir::types::Base;
use patina_compiler::sema::builtins::builtins;
use patina_compiler::sema::globals::{GLOBALS, lookup};
use patina_compiler::syntax::ast::{Item, ShaderStyle};

use super::analysis::{Analysis, distinct_rates, rates_label};
use super::{functions, scope};

/// Everything that can be written at `at`; clients filter by what was typed.
pub fn complete(analysis: &Analysis, at: Position) -> Option<CompletionResponse> {
    let offset = analysis.offset(at)?;
    let checked = &analysis.checked;
    let mut items = Vec::new();
    let mut seen = HashSet::new();
    let mut add = |item: CompletionItem| {
        if seen.insert(item.label.clone()) {
            items.push(item);
        }
    };
    // Innermost first: a local hides a file-level variable of the same name.
    for declared in scope::visible(&checked.module, checked.root, offset).into_iter().rev() {
        let rates = distinct_rates(analysis.variable(declared.name.span).iter().map(|(s, l)| (*s, l.rate)));
        let ty = Base::from_ast(declared.ty.name).name();
        let detail =
            if rates.is_empty() { ty.to_string() } else { format!("{ty} ({})", rates_label(&rates)) };
        let kind = if declared.parameter { CompletionItemKind::FIELD } else { CompletionItemKind::VARIABLE };
        add(item(&declared.name.name, kind, detail, None));
    }
    for f in functions::all(&checked.module) {
        let doc = functions::documentation(&checked.sources, f);
        let signature = functions::signature(&checked.sources, f);
        add(item(&f.name.name, CompletionItemKind::FUNCTION, signature, Some(doc)));
    }
    // The predefined variables of the shader around the cursor, or of every kind outside one.
    let shader = checked.module.items.iter().find_map(|i| match i {
        Item::Shader(s) if s.span.file == checked.root && s.span.contains_offset(offset) => Some(s),
        _ => None,
    });
    for g in GLOBALS {
        let visible = match shader {
            Some(s) => lookup(g.name, s.kind, !matches!(s.style, ShaderStyle::RenderMan)) == Some(g),
            None => true,
        };
        if visible {
            add(item(
                g.name,
                CompletionItemKind::CONSTANT,
                format!("{} {}", g.ty.name(), g.name),
                Some(g.doc.into()),
            ));
        }
    }
    let mut names: Vec<&str> = builtins().names().filter(|n| !n.starts_with("__")).collect();
    names.sort_unstable();
    for name in names {
        let overloads = builtins().overloads(name);
        let Some(first) = overloads.first() else { continue };
        let mut detail = first.signature.clone();
        if overloads.len() > 1 {
            detail.push_str(&format!(" (+{} overloads)", overloads.len() - 1));
        }
        add(item(name, CompletionItemKind::FUNCTION, detail, None));
    }
    Some(CompletionResponse::Array(items))
}

fn item(label: &str, kind: CompletionItemKind, detail: String, doc: Option<String>) -> CompletionItem {
    CompletionItem {
        label: label.to_string(),
        kind: Some(kind),
        detail: Some(detail),
        documentation: doc.filter(|d| !d.is_empty()).map(Documentation::String),
        ..CompletionItem::default()
    }
}
