//! What requests are answered from: the document's current analysis, or, while its text does not
//! parse (the semantic stage does not run on it, as for `patina check`), the last analysis that
//! did, with positions carried across the edit between the two texts.
//!
//! Typing a statement leaves the text without its `;` most of the time; without this, hover,
//! inlay hints and the rate colours would vanish at every keystroke and come back at the next `;`.

use lsp_types::{GotoDefinitionResponse, Hover, InlayHint, Location, Position, Range, SemanticTokens, Uri};

use super::analysis::Analysis;
use super::{definition, hover, inlay_hints, position, semantic_tokens};

/// The analysis to answer from.
pub enum View<'a> {
    /// The current text's, which went through the semantic stage (or there is no other).
    Current(&'a Analysis),
    /// An earlier text's, which did, while the current one has syntax errors.
    Earlier {
        /// The earlier analysis.
        then: &'a Analysis,
        /// The current one (its text, its syntax tree and diagnostics).
        now: &'a Analysis,
        /// The edit between their texts.
        edit: Edit,
    },
}

impl<'a> View<'a> {
    /// Answers from `now`, or from `then` if `now` has no semantic results and `then` has.
    pub fn new(now: &'a Analysis, then: Option<&'a Analysis>) -> View<'a> {
        match then {
            Some(then) if !now.has_semantics() => {
                let edit = Edit::between(&then.root().text, &now.root().text);
                View::Earlier { then, now, edit }
            }
            _ => View::Current(now),
        }
    }

    /// The current analysis (diagnostics and completion always read the current text).
    pub fn now(&self) -> &'a Analysis {
        match self {
            View::Current(now) | View::Earlier { now, .. } => now,
        }
    }

    /// Hover at `at` of the current text.
    pub fn hover(&self, at: Position) -> Option<Hover> {
        match self {
            View::Current(now) => hover::hover(now, at),
            View::Earlier { .. } => {
                let mut found = hover::hover(self.then()?, self.back(at)?)?;
                found.range = found.range.and_then(|r| self.forward_range(r));
                Some(found)
            }
        }
    }

    /// The definition of the name at `at` of the current text (the document is `uri`).
    pub fn definition(
        &self,
        at: Position,
        uri: &Uri,
        uri_of: &dyn Fn(&str) -> Option<Uri>,
    ) -> Option<GotoDefinitionResponse> {
        let View::Earlier { then, .. } = self else { return definition::definition(self.now(), at, uri_of) };
        let found = definition::definition(then, self.back(at)?, uri_of)?;
        // Places in the document itself moved with the edit; those in other files did not.
        let carry = |l: Location| -> Option<Location> {
            if &l.uri != uri {
                return Some(l);
            }
            Some(Location { range: self.forward_range(l.range)?, ..l })
        };
        let locations: Vec<Location> = match found {
            GotoDefinitionResponse::Scalar(l) => vec![l],
            GotoDefinitionResponse::Array(ls) => ls,
            GotoDefinitionResponse::Link(_) => return None,
        };
        let locations: Vec<Location> = locations.into_iter().filter_map(carry).collect();
        (!locations.is_empty()).then_some(GotoDefinitionResponse::Array(locations))
    }

    /// The inlay hints of `range` of the current text.
    pub fn hints(&self, range: Range) -> Vec<InlayHint> {
        let View::Earlier { then, .. } = self else { return inlay_hints::hints(self.now(), range) };
        let whole = Range { start: Position::new(0, 0), end: Position::new(u32::MAX, 0) };
        let inside = |p: Position| {
            (p.line, p.character) >= (range.start.line, range.start.character)
                && (p.line, p.character) <= (range.end.line, range.end.character)
        };
        inlay_hints::hints(then, whole)
            .into_iter()
            .filter_map(|hint| Some(InlayHint { position: self.forward(hint.position)?, ..hint }))
            .filter(|hint| inside(hint.position))
            .collect()
    }

    /// The semantic tokens of the current text.
    pub fn tokens(&self) -> SemanticTokens {
        let View::Earlier { then, now, edit } = self else { return semantic_tokens::tokens(self.now()) };
        let moved = semantic_tokens::classify(then).into_iter().filter_map(|mut token| {
            token.range = edit.forward(token.range.start)?..edit.forward(token.range.end)?;
            Some(token)
        });
        semantic_tokens::encode(now.root(), moved)
    }

    fn then(&self) -> Option<&'a Analysis> {
        match self {
            View::Earlier { then, .. } => Some(then),
            View::Current(_) => None,
        }
    }

    /// A position of the current text in the earlier one.
    fn back(&self, at: Position) -> Option<Position> {
        let View::Earlier { then, now, edit } = self else { return Some(at) };
        let offset = edit.back(position::offset(now.root(), at)?)?;
        Some(position::position(then.root(), offset))
    }

    /// A position of the earlier text in the current one.
    fn forward(&self, at: Position) -> Option<Position> {
        let View::Earlier { then, now, edit } = self else { return Some(at) };
        let offset = edit.forward(position::offset(then.root(), at)?)?;
        Some(position::position(now.root(), offset))
    }

    fn forward_range(&self, range: Range) -> Option<Range> {
        Some(Range { start: self.forward(range.start)?, end: self.forward(range.end)? })
    }
}

/// The edit between two texts, as one replaced stretch: what they share at the start and the end.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Edit {
    /// The bytes both texts start with.
    prefix: usize,
    /// The bytes both texts end with (not overlapping the prefix in either).
    suffix: usize,
    old_len: usize,
    new_len: usize,
}

impl Edit {
    /// The edit that turns `old` into `new`.
    pub fn between(old: &str, new: &str) -> Edit {
        let (a, b) = (old.as_bytes(), new.as_bytes());
        let mut prefix = a.iter().zip(b).take_while(|(x, y)| x == y).count();
        while !old.is_char_boundary(prefix) {
            prefix -= 1;
        }
        let most = a.len().min(b.len()) - prefix;
        let mut suffix = a.iter().rev().zip(b.iter().rev()).take(most).take_while(|(x, y)| x == y).count();
        while !old.is_char_boundary(a.len() - suffix) || !new.is_char_boundary(b.len() - suffix) {
            suffix -= 1;
        }
        Edit { prefix, suffix, old_len: a.len(), new_len: b.len() }
    }

    /// Where byte `offset` of the old text is in the new one; `None` inside the replaced stretch.
    pub fn forward(&self, offset: usize) -> Option<usize> {
        if offset <= self.prefix {
            Some(offset)
        } else if offset >= self.old_len - self.suffix {
            Some(offset + self.new_len - self.old_len)
        } else {
            None
        }
    }

    /// Where byte `offset` of the new text is in the old one; `None` inside the replacement.
    pub fn back(&self, offset: usize) -> Option<usize> {
        if offset <= self.prefix {
            Some(offset)
        } else if offset >= self.new_len - self.suffix {
            Some(offset + self.old_len - self.new_len)
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Edit;

    #[test]
    fn offsets_move_with_the_edit_and_vanish_inside_it() {
        let edit = Edit::between("float a; b = 1;", "float a; xyz b = 1;");
        assert_eq!(edit.forward(3), Some(3));
        assert_eq!(edit.forward(9), Some(9));
        assert_eq!(edit.forward(10), Some(14)); // the space after `b`, after the insertion
        assert_eq!(edit.back(14), Some(10));
        assert_eq!(edit.back(11), None); // inside `xyz `
        let same = Edit::between("abc", "abc");
        assert_eq!((same.forward(2), same.back(3)), (Some(2), Some(3)));
    }

    #[test]
    fn a_shared_stretch_never_splits_a_character() {
        // `é` and `è` share their first byte.
        let edit = Edit::between("xé", "xè");
        assert_eq!(edit.forward(1), Some(1));
        assert_eq!(edit.forward(3), Some(3));
        assert_eq!(edit.back(2), None);
    }
}
