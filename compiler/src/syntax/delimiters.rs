//! Bracket balance, checked before parsing: an unclosed `{` or a stray `)` is reported once, with
//! the opener it fails to match, instead of as a cascade of parse errors.

use crate::diag::{Code, Diagnostic};
use crate::syntax::lexer::Token;
use crate::syntax::token::TokenKind;

/// Brackets nested deeper than this are refused: later stages walk the tree recursively.
pub const MAX_NESTING: usize = 256;

fn closer_of(open: TokenKind) -> TokenKind {
    match open {
        TokenKind::LParen => TokenKind::RParen,
        TokenKind::LBracket => TokenKind::RBracket,
        _ => TokenKind::RBrace,
    }
}

fn symbol(kind: TokenKind) -> &'static str {
    kind.spelling().unwrap_or("?")
}

/// Checks that every `(`, `[` and `{` is closed by its partner, in order.
pub fn check(tokens: &[Token]) -> Vec<Diagnostic> {
    let mut diags = Vec::new();
    let mut open: Vec<Token> = Vec::new();
    for &t in tokens {
        match t.kind {
            TokenKind::LParen | TokenKind::LBracket | TokenKind::LBrace => {
                open.push(t);
                if open.len() > MAX_NESTING {
                    diags.push(
                        Diagnostic::error(
                            Code::ResourceLimit,
                            format!("brackets nested more than {MAX_NESTING} deep"),
                            t.span,
                            "nesting limit reached here",
                        )
                        .with_label(open[0].span, "the outermost bracket"),
                    );
                    return diags;
                }
            }
            TokenKind::RParen | TokenKind::RBracket | TokenKind::RBrace => match open.last() {
                Some(&o) if closer_of(o.kind) == t.kind => {
                    open.pop();
                }
                Some(&o) => {
                    let d = Diagnostic::error(
                        Code::UnexpectedCloser,
                        format!("mismatched closing delimiter `{}`", symbol(t.kind)),
                        t.span,
                        format!("expected `{}` first", symbol(closer_of(o.kind))),
                    )
                    .with_label(o.span, format!("this `{}` is not closed", symbol(o.kind)));
                    diags.push(d);
                    // Stop at the first mismatch: later ones are almost always its echo.
                    return diags;
                }
                None => {
                    diags.push(
                        Diagnostic::error(
                            Code::UnexpectedCloser,
                            format!("unexpected closing delimiter `{}`", symbol(t.kind)),
                            t.span,
                            "nothing is open here",
                        )
                        .with_help("remove it, or add the opening delimiter it was meant to close"),
                    );
                    return diags;
                }
            },
            _ => {}
        }
    }
    let end = tokens.last().map(|t| t.span.end_point()).unwrap_or_default();
    if let Some(&o) = open.last() {
        diags.push(
            Diagnostic::error(
                Code::UnclosedDelimiter,
                format!("unclosed delimiter `{}`", symbol(o.kind)),
                o.span,
                "opened here",
            )
            .with_label(end, "the file ends here")
            .with_help(format!("add the matching `{}`", symbol(closer_of(o.kind)))),
        );
    }
    diags
}
