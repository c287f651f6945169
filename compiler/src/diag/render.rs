//! Showing diagnostics: codespan-reporting's layout for people, JSON lines for tools.

use codespan_reporting::diagnostic as cs;
use codespan_reporting::term;

use super::{Diagnostic, Severity};
use crate::source::{FileId, SourceMap, Span};

/// At most this many macro-expansion labels, and as many include labels, are shown per diagnostic.
const MAX_CONTEXT_LABELS: usize = 4;

/// Keeps at most [`MAX_CONTEXT_LABELS`] of a chain of context labels, innermost first: the innermost
/// ones and the outermost, which is where the user's own text starts it. Returns how many were left
/// out.
fn elide(chain: &mut Vec<cs::Label<FileId>>) -> usize {
    let n = chain.len();
    if n <= MAX_CONTEXT_LABELS {
        return 0;
    }
    let outermost = chain.pop().expect("the chain is longer than the limit");
    chain.truncate(MAX_CONTEXT_LABELS - 1);
    chain.push(outermost);
    n - MAX_CONTEXT_LABELS
}

/// The context labels of a span: each macro expansion it came through, then each `#include` that
/// brought its file in; long chains are cut short, with a note saying how much was left out.
fn context_labels(sources: &SourceMap, span: Span) -> (Vec<cs::Label<FileId>>, Vec<String>) {
    let mut expansions = Vec::new();
    let mut at = span;
    while let Some(expansion) = sources.expansion(at.expn) {
        expansions.push(
            cs::Label::secondary(expansion.call_site.file, expansion.call_site.range())
                .with_message(format!("in this expansion of macro `{}`", expansion.name)),
        );
        at = expansion.call_site;
    }
    let mut includes = Vec::new();
    let mut file = at.file;
    while let Some(site) = sources.file(file).included_from {
        includes.push(
            cs::Label::secondary(site.file, site.range())
                .with_message(format!("`{}` included here", sources.file(file).name)),
        );
        file = site.file;
    }
    let mut notes = Vec::new();
    match elide(&mut expansions) {
        0 => {}
        1 => notes.push("... and 1 more expansion".to_string()),
        n => notes.push(format!("... and {n} more expansions")),
    }
    match elide(&mut includes) {
        0 => {}
        1 => notes.push("... and 1 more include".to_string()),
        n => notes.push(format!("... and {n} more includes")),
    }
    expansions.extend(includes);
    (expansions, notes)
}

/// The codespan-reporting form of a diagnostic, with include and expansion sites added.
pub fn to_codespan(sources: &SourceMap, d: &Diagnostic) -> cs::Diagnostic<FileId> {
    let severity = match d.severity {
        Severity::Error => cs::Severity::Error,
        Severity::Warning => cs::Severity::Warning,
    };
    let mut labels = Vec::new();
    for label in &d.labels {
        let style = if label.primary { cs::LabelStyle::Primary } else { cs::LabelStyle::Secondary };
        labels.push(cs::Label::new(style, label.span.file, label.span.range()).with_message(&label.message));
    }
    let (context, elided) = context_labels(sources, d.primary_span());
    labels.extend(context);
    let mut notes: Vec<String> = d.notes.iter().chain(&elided).map(|n| format!("note: {n}")).collect();
    if let Some(help) = &d.help {
        notes.push(format!("help: {help}"));
    }
    cs::Diagnostic::new(severity)
        .with_code(d.code.as_str())
        .with_message(&d.message)
        .with_labels(labels)
        .with_notes(notes)
}

/// Renders diagnostics in the terminal layout, without colour (for files, pipes and snapshots).
pub fn render_text(sources: &SourceMap, diagnostics: &[Diagnostic]) -> String {
    let config = term::Config::default();
    let mut out = String::new();
    for d in diagnostics {
        // Rendering into a String only fails when a span is outside its file; show the bare
        // headline then rather than nothing.
        if term::emit_to_string(&mut out, &config, sources, &to_codespan(sources, d)).is_err() {
            out.push_str(&format!("{}[{}]: {}\n", severity_word(d.severity), d.code, d.message));
        }
    }
    out
}

fn severity_word(severity: Severity) -> &'static str {
    match severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
    }
}

fn location(sources: &SourceMap, span: Span) -> serde_json::Value {
    let file = sources.file(span.file);
    let (line, column) = file.line_column(span.start as usize);
    let (end_line, end_column) = file.line_column(span.end as usize);
    serde_json::json!({
        "file": file.name,
        "byte_start": span.start,
        "byte_end": span.end,
        "line": line,
        "column": column,
        "end_line": end_line,
        "end_column": end_column,
    })
}

/// Renders diagnostics as JSON lines: one object per diagnostic, each with every label's file, line
/// and column (one-based) and byte range.
pub fn render_json(sources: &SourceMap, diagnostics: &[Diagnostic]) -> String {
    let mut out = String::new();
    for d in diagnostics {
        let code = to_codespan(sources, d);
        let labels: Vec<serde_json::Value> = code
            .labels
            .iter()
            .map(|l| {
                let span = Span::new(l.file_id, l.range.clone());
                let mut value = location(sources, span);
                value["message"] = l.message.clone().into();
                value["primary"] = (l.style == cs::LabelStyle::Primary).into();
                value
            })
            .collect();
        let value = serde_json::json!({
            "severity": severity_word(d.severity),
            "code": d.code.as_str(),
            "message": d.message,
            "location": location(sources, d.primary_span()),
            "labels": labels,
            "notes": d.notes.iter().chain(&context_labels(sources, d.primary_span()).1).collect::<Vec<_>>(),
            "help": d.help,
        });
        out.push_str(&value.to_string());
        out.push('\n');
    }
    out
}
