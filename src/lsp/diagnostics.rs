//! The compiler's diagnostics as the protocol's: each where the user's own text is, with the
//! secondary labels, and the real place of an error inside a macro or an included file, as
//! related information.

use lsp_types::{
    Diagnostic, DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString, Uri,
};
use patina_compiler::diag::{Code, Severity};
use patina_compiler::source::{FileId, SourceMap, Span};

use super::analysis::Analysis;
use super::position;

/// The diagnostics of a checked document. `uri_of` names the compiler's files (includes, the
/// standard library) as URIs.
pub fn of(analysis: &Analysis, uri_of: &dyn Fn(&str) -> Option<Uri>) -> Vec<Diagnostic> {
    let sources = &analysis.checked.sources;
    let root = analysis.root();
    let location = |span: Span| -> Option<Location> {
        let file = sources.file(span.file);
        Some(Location { uri: uri_of(&file.name)?, range: position::range(file, span.range()) })
    };
    let mut out = Vec::new();
    if let Some(panic) = &analysis.panic {
        out.push(Diagnostic {
            severity: Some(DiagnosticSeverity::ERROR),
            code: Some(NumberOrString::String(Code::Internal.as_str().to_string())),
            source: Some("patina".to_string()),
            message: format!("internal compiler error (please report it): {panic}"),
            ..Diagnostic::default()
        });
    }
    for d in analysis.checked.diagnostics.iter() {
        let primary = d.primary_span();
        // Where the user wrote what led here: out of macro bodies to their uses, out of included
        // files to the `#include`. A diagnostic of a file nothing includes (the library
        // built-ins' implementation) is shown at the top.
        let shown = lift_into(sources, analysis.checked.root, primary);
        let mut related: Vec<DiagnosticRelatedInformation> = Vec::new();
        if shown != Some(primary)
            && let Some(location) = location(primary)
        {
            let message = d.labels.iter().find(|l| l.primary).map_or("", |l| l.message.as_str());
            let message = if message.is_empty() { d.message.clone() } else { message.to_string() };
            related.push(DiagnosticRelatedInformation { location, message });
        }
        for label in d.labels.iter().filter(|l| !l.primary) {
            if let Some(location) = location(label.span) {
                related.push(DiagnosticRelatedInformation { location, message: label.message.clone() });
            }
        }
        let mut message = d.message.clone();
        for note in &d.notes {
            message.push_str("\nnote: ");
            message.push_str(note);
        }
        if let Some(help) = &d.help {
            message.push_str("\nhelp: ");
            message.push_str(help);
        }
        out.push(Diagnostic {
            range: position::range(root, shown.map_or(0..0, Span::range)),
            severity: Some(match d.severity {
                Severity::Error => DiagnosticSeverity::ERROR,
                Severity::Warning => DiagnosticSeverity::WARNING,
            }),
            code: Some(NumberOrString::String(d.code.as_str().to_string())),
            source: Some("patina".to_string()),
            message,
            related_information: (!related.is_empty()).then_some(related),
            ..Diagnostic::default()
        });
    }
    out
}

/// `span`, or the macro use or `#include` that brought it into `file`; `None` if nothing did.
fn lift_into(sources: &SourceMap, file: FileId, mut span: Span) -> Option<Span> {
    loop {
        if span.expn.is_macro() {
            span = sources.call_site(span);
        } else if span.file == file {
            return Some(span);
        } else {
            span = sources.file(span.file).included_from?;
        }
    }
}
