//! Inlay hints: the rate the compiler gave each variable and parameter whose declaration does not
//! write one (`float v` becomes `float v: fragment`), in the requested range.

use std::collections::HashSet;

use lsp_types::{InlayHint, InlayHintKind, InlayHintLabel, Range};

use super::analysis::{Analysis, distinct_rates, rates_label};
use super::{position, scope};

/// The hints of the document between `range`'s ends.
pub fn hints(analysis: &Analysis, range: Range) -> Vec<InlayHint> {
    let root = analysis.root();
    let (Some(from), to) = (analysis.offset(range.start), analysis.offset(range.end)) else {
        return Vec::new();
    };
    let to = to.unwrap_or(root.text.len() as u32);
    // A written rate (`uniform`, `vertex`, ...) needs no hint.
    let written: HashSet<_> = scope::all(&analysis.checked.module)
        .into_iter()
        .filter(|d| d.qualifiers.rate.is_some())
        .map(|d| d.name.span)
        .collect();
    let mut out: Vec<InlayHint> = analysis
        .symbols
        .variables_in(analysis.checked.root)
        .filter(|(span, _)| {
            !span.expn.is_macro() && from <= span.start && span.end <= to && !written.contains(*span)
        })
        .filter_map(|(span, _)| {
            let copies = analysis.variable(*span);
            let rates = distinct_rates(copies.iter().map(|(s, l)| (*s, l.rate)));
            (!rates.is_empty()).then(|| InlayHint {
                position: position::position(root, span.end as usize),
                label: InlayHintLabel::String(format!(": {}", rates_label(&rates))),
                kind: Some(InlayHintKind::TYPE),
                text_edits: None,
                tooltip: None,
                padding_left: None,
                padding_right: None,
                data: None,
            })
        })
        .collect();
    out.sort_by_key(|h| (h.position.line, h.position.character));
    out
}
