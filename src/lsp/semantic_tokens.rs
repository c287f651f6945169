//! Semantic tokens: every variable, parameter, predefined variable and function name of the
//! document, with a modifier for its rate, so that a theme can colour values by how often they
//! are computed.

use std::collections::HashSet;
use std::ops::Range;

use lsp_types::{
    SemanticToken, SemanticTokenModifier, SemanticTokenType, SemanticTokens, SemanticTokensLegend,
};
use patina_compiler::ir::LocalKind;
use patina_compiler::ir::types::{Frequency, Rate};
use patina_compiler::source::SourceFile;
use patina_compiler::stdlib;

use super::analysis::Analysis;
use super::position;
use super::symbols::Referent;

/// The token types, in the legend's order.
const TYPES: [SemanticTokenType; 3] =
    [SemanticTokenType::VARIABLE, SemanticTokenType::PARAMETER, SemanticTokenType::FUNCTION];
const VARIABLE: u32 = 0;
const PARAMETER: u32 = 1;
const FUNCTION: u32 = 2;

/// The modifiers, in the legend's order (bit i of a token's modifiers is modifier i): one per
/// frequency of the rate lattice, and `perlight`.
const MODIFIERS: [&str; 7] =
    ["declaration", "defaultLibrary", "constant", "primitiveGroup", "vertex", "fragment", "perlight"];
const DECLARATION: u32 = 1 << 0;
const DEFAULT_LIBRARY: u32 = 1 << 1;

/// What the server declares it sends.
pub fn legend() -> SemanticTokensLegend {
    SemanticTokensLegend {
        token_types: TYPES.to_vec(),
        token_modifiers: MODIFIERS.iter().map(|m| SemanticTokenModifier::new(m)).collect(),
    }
}

/// The modifier bits of a rate.
fn rate_bits(rate: Rate) -> u32 {
    let frequency = match rate.frequency {
        Frequency::Constant => 2,
        Frequency::PrimitiveGroup => 3,
        Frequency::Vertex => 4,
        Frequency::Fragment => 5,
    };
    (1 << frequency) | if rate.perlight { 1 << 6 } else { 0 }
}

/// One token: a byte range of the document, its type and its modifier bits.
#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    /// The name's bytes in the document.
    pub range: Range<usize>,
    /// The index of its type in [`TYPES`].
    pub kind: u32,
    /// Its modifier bits (see [`MODIFIERS`]).
    pub modifiers: u32,
}

/// The tokens of the whole document, in order.
pub fn tokens(analysis: &Analysis) -> SemanticTokens {
    encode(analysis.root(), classify(analysis))
}

/// Every name of the document as a token, in order.
pub fn classify(analysis: &Analysis) -> Vec<Token> {
    let sources = &analysis.checked.sources;
    let library: HashSet<&str> = super::functions::all(&analysis.checked.module)
        .filter(|f| sources.file(f.span.file).name.starts_with(stdlib::PREFIX))
        .map(|f| f.name.name.as_str())
        .collect();
    let mut out = Vec::new();
    // Names made by macros have no place of their own in the text.
    for name in analysis.symbols.in_file(analysis.checked.root).filter(|o| !o.span.expn.is_macro()) {
        let declaration = if name.declaration { DECLARATION } else { 0 };
        let (kind, modifiers) = match &name.referent {
            Referent::Variable(decl) => {
                let copies = analysis.variable(*decl);
                let Some((_, first)) = copies.first() else { continue };
                // The highest of the copies' rates: the one that costs.
                let rate = copies.iter().map(|(_, l)| l.rate).reduce(Rate::join).unwrap_or(first.rate);
                let kind = if matches!(first.kind, LocalKind::Param { .. }) { PARAMETER } else { VARIABLE };
                (kind, rate_bits(rate) | declaration)
            }
            Referent::Global(g) => {
                (VARIABLE, rate_bits(Rate { frequency: g.frequency, perlight: g.perlight }) | DEFAULT_LIBRARY)
            }
            Referent::Function(name) => {
                (FUNCTION, declaration | if library.contains(name.as_str()) { DEFAULT_LIBRARY } else { 0 })
            }
            Referent::Builtin(..) => (FUNCTION, DEFAULT_LIBRARY),
        };
        out.push(Token { range: name.span.range(), kind, modifiers });
    }
    out
}

/// The protocol's encoding of `tokens` (in order) in `file`: each relative to the one before.
pub fn encode(file: &SourceFile, tokens: impl IntoIterator<Item = Token>) -> SemanticTokens {
    let mut data = Vec::new();
    let (mut line, mut start, mut end_of_last) = (0u32, 0u32, 0u32);
    for token in tokens {
        let at = position::position(file, token.range.start);
        let end = position::position(file, token.range.end);
        // One token per place: the same name may be indexed twice (a declaration that is also
        // the target of its initialising store).
        let overlaps = at.line == line && at.character < end_of_last && !data.is_empty();
        if end.line != at.line || end.character <= at.character || overlaps {
            continue;
        }
        let delta_line = at.line - line;
        let delta_start = if delta_line == 0 { at.character - start } else { at.character };
        data.push(SemanticToken {
            delta_line,
            delta_start,
            length: end.character - at.character,
            token_type: token.kind,
            token_modifiers_bitset: token.modifiers,
        });
        (line, start, end_of_last) = (at.line, at.character, end.character);
    }
    SemanticTokens { result_id: None, data }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_rate_has_its_modifier() {
        let name = |bits: u32| MODIFIERS[bits.trailing_zeros() as usize];
        assert_eq!(name(rate_bits(Rate::CONSTANT)), "constant");
        assert_eq!(name(rate_bits(Rate::UNIFORM)), "primitiveGroup");
        assert_eq!(name(rate_bits(Rate::VERTEX)), "vertex");
        assert_eq!(name(rate_bits(Rate::FRAGMENT)), "fragment");
        let perlight = Rate { perlight: true, ..Rate::FRAGMENT };
        assert_eq!(rate_bits(perlight), (1 << 5) | (1 << 6));
    }
}
