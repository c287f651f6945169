//! Go to definition: a variable's declaration, a function's definitions (in the document, in a
//! file it includes, or in the standard library's sources), and the file an `#include` reads.

use lsp_types::{GotoDefinitionResponse, Location, Position, Uri};
use patina_compiler::source::Span;

use super::analysis::Analysis;
use super::symbols::Referent;
use super::{functions, position, scope};

/// Where the name at `at` is defined; `uri_of` names the compiler's files as URIs.
pub fn definition(
    analysis: &Analysis,
    at: Position,
    uri_of: &dyn Fn(&str) -> Option<Uri>,
) -> Option<GotoDefinitionResponse> {
    let offset = analysis.offset(at)?;
    let sources = &analysis.checked.sources;
    let location = |span: Span| -> Option<Location> {
        let file = sources.file(span.file);
        Some(Location { uri: uri_of(&file.name)?, range: position::range(file, span.range()) })
    };
    let spans: Vec<Span> = match analysis.symbols.at(analysis.checked.root, offset).map(|o| &o.referent) {
        Some(Referent::Variable(declaration)) => vec![*declaration],
        Some(Referent::Function(name)) => {
            functions::named(&analysis.checked.module, name).iter().map(|f| f.name.span).collect()
        }
        // A built-in written in the language: the implementation this call runs.
        Some(Referent::Builtin(_, Some(implementation))) => vec![*implementation],
        // Other built-ins and predefined variables are the compiler's, in no file.
        Some(Referent::Global(_) | Referent::Builtin(_, None)) => Vec::new(),
        // A name the IR does not know (in a function no shader calls): its declaration by the
        // blocks around it. Else, on an `#include` line: the file it read (its first inclusion
        // from here).
        None => {
            let module = &analysis.checked.module;
            let declared = analysis
                .word_at(offset)
                .and_then(|(word, _)| scope::declaration(module, analysis.checked.root, offset, word));
            let included = || {
                sources
                    .files()
                    .find(|(_, f)| {
                        f.included_from.is_some_and(|s| analysis.is_root(s.file) && s.contains_offset(offset))
                    })
                    .map(|(id, _)| Span::new(id, 0..0))
            };
            declared.map(|d| d.name.span).or_else(included).into_iter().collect()
        }
    };
    let locations: Vec<Location> = spans.into_iter().filter_map(location).collect();
    match locations.len() {
        0 => None,
        1 => locations.into_iter().next().map(GotoDefinitionResponse::Scalar),
        _ => Some(GotoDefinitionResponse::Array(locations)),
    }
}
