//! Bracket balance, checked before parsing: an unclosed `{` or a stray `)` is reported once, with
//! the opener it fails to match, instead of as a cascade of parse errors. The same pass bounds how
//! deep a tree the parser can build: brackets nest at most [`MAX_NESTING`] deep and a statement has
//! at most [`MAX_OPERATORS`] operators, and statements nest at most [`MAX_STATEMENT_DEPTH`] deep,
//! because later stages walk (and drop) the tree recursively.

use crate::diag::{Code, Diagnostic};
use crate::syntax::lexer::Token;
use crate::syntax::token::TokenKind;

/// Brackets nested deeper than this are refused.
pub const MAX_NESTING: usize = 256;

/// A statement with more operators and control keywords than this is refused, and so is a block
/// with more `else` branches: an operator chain, `if if if ...` or an `else if` chain is a tree as
/// deep as it is long.
pub const MAX_OPERATORS: usize = 1024;

/// Statements nested deeper than this are refused: blocks and the bodies of `if`, loops and light
/// constructs, with or without braces. Later stages take time that grows faster than linearly with
/// the depth (about 0.3 s to compile 256 levels in a debug build, ten seconds for 1000).
pub const MAX_STATEMENT_DEPTH: usize = 256;

/// The keywords whose statement contains another statement.
fn nests_statement(kind: TokenKind) -> bool {
    use TokenKind::*;
    matches!(kind, If | While | For | Illuminance | Illuminate | Solar | Gather)
}

/// Tokens that can add a level to the tree: operators, and the keywords of nested statements.
fn adds_depth(kind: TokenKind) -> bool {
    kind.is_operator() || nests_statement(kind)
}

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
    let mut operators = 0usize;
    let mut statement_start: Option<Token> = None;
    // `else` branches counted per brace level (the file level first).
    let mut elses: Vec<usize> = vec![0];
    // Per brace level (the file level first), the statement keywords whose statement is still
    // open there: `if (a) if (b) {` opens three levels. A `;` or `}` at that level ends them.
    let mut statements: Vec<usize> = vec![0];
    let mut statement_depth = 0usize;
    for &t in tokens {
        // A `;` between parentheses (a `for` header) ends no statement.
        let at_statement_level = open.last().is_none_or(|o| o.kind == TokenKind::LBrace);
        if t.kind == TokenKind::Semi {
            operators = 0;
            statement_start = None;
            if at_statement_level {
                let pending = statements.last_mut().expect("the file level is always there");
                statement_depth -= *pending;
                *pending = 0;
            }
            continue;
        }
        if (nests_statement(t.kind) && at_statement_level) || t.kind == TokenKind::LBrace {
            statement_depth += 1;
            if t.kind != TokenKind::LBrace {
                *statements.last_mut().expect("the file level is always there") += 1;
            }
            // Braces alone past the bracket limit get that limit's diagnostic, below.
            let bracket_limit = t.kind == TokenKind::LBrace && open.len() >= MAX_NESTING;
            if statement_depth > MAX_STATEMENT_DEPTH && !bracket_limit {
                let mut d = Diagnostic::error(
                    Code::ResourceLimit,
                    format!("statements nested more than {MAX_STATEMENT_DEPTH} deep"),
                    t.span,
                    "nesting limit reached here",
                );
                if let Some(outer) = open.first() {
                    d = d.with_label(outer.span, "the outermost block");
                }
                diags.push(
                    d.with_help("combine conditions with `&&`, or move the inner statements into a function"),
                );
                return diags;
            }
        }
        statement_start.get_or_insert(t);
        if t.kind == TokenKind::Else {
            let count = elses.last_mut().expect("the file level is always there");
            *count += 1;
            if *count > MAX_OPERATORS {
                diags.push(
                    Diagnostic::error(
                        Code::ResourceLimit,
                        format!("more than {MAX_OPERATORS} `else` branches in one block"),
                        t.span,
                        "branch limit reached here",
                    )
                    .with_help("look the case up in an array, or split the chain into blocks"),
                );
                return diags;
            }
        }
        if adds_depth(t.kind) {
            operators += 1;
            if operators > MAX_OPERATORS {
                diags.push(
                    Diagnostic::error(
                        Code::ResourceLimit,
                        format!("a statement with more than {MAX_OPERATORS} operators or nested statements"),
                        t.span,
                        "operator limit reached here",
                    )
                    .with_label(statement_start.map_or(t.span, |s| s.span), "the statement starts here")
                    .with_help("split the computation into several statements with intermediate variables"),
                );
                return diags;
            }
        }
        match t.kind {
            TokenKind::LParen | TokenKind::LBracket | TokenKind::LBrace => {
                if t.kind == TokenKind::LBrace {
                    elses.push(0);
                    statements.push(0);
                }
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
                    if t.kind == TokenKind::RBrace {
                        elses.pop();
                        // The block, and the statements around it at the enclosing level, end.
                        let inner = statements.pop().expect("pushed with its `{`");
                        let outer = statements.last_mut().expect("the file level is always there");
                        statement_depth -= inner + 1 + *outer;
                        *outer = 0;
                    }
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
