//! The lexer: one file's text to tokens with spans, and lexical diagnostics.

use logos::Logos;

use super::token::{NumberClass, TokenKind, classify_number};
use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::source::{FileId, Span};

/// A token with its place in the source.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Token {
    /// What it is.
    pub kind: TokenKind,
    /// Where its text is: in its file, or in a macro body when a macro produced it.
    pub span: Span,
    /// Whether it is the first token on its line (directives start with such a `#`).
    pub line_start: bool,
    /// Whether white space precedes it (tells `#define F(x)` from `#define F (x)`).
    pub space_before: bool,
}

/// Splits one file into tokens (the first token of each line marked `line_start`); malformed tokens are reported and left out,
/// except malformed numbers, which stay in (as integers) so that the parser does not trip over them.
pub fn lex(file: FileId, text: &str, diags: &mut Diagnostics) -> Vec<Token> {
    let mut tokens = Vec::with_capacity(text.len() / 4);
    let mut lexer = TokenKind::lexer(text);
    let mut line_start = true;
    let mut prev_end = 0;
    while let Some(result) = lexer.next() {
        let range = lexer.span();
        let span = Span::new(file, range.clone());
        let space_before = range.start > prev_end;
        prev_end = range.end;
        let kind = match result {
            // Line breaks are not tokens: `line_start` on the next token records them.
            Ok(TokenKind::Newline) => {
                line_start = true;
                continue;
            }
            Ok(TokenKind::Number) => match classify_number(lexer.slice()) {
                NumberClass::Int => TokenKind::IntLit,
                NumberClass::Float => TokenKind::FloatLit,
                NumberClass::Malformed(why) => {
                    diags.push(Diagnostic::error(
                        Code::MalformedNumber,
                        format!("malformed number `{}`", lexer.slice()),
                        span,
                        why,
                    ));
                    TokenKind::IntLit
                }
            },
            Ok(TokenKind::StringLit) => {
                check_escapes(lexer.slice(), span, diags);
                TokenKind::StringLit
            }
            Ok(TokenKind::UnterminatedComment) => {
                let opener = Span { end: span.start + 2, ..span };
                diags.push(
                    Diagnostic::error(
                        Code::UnterminatedComment,
                        "unterminated block comment",
                        opener,
                        "comment starts here",
                    )
                    .with_help("close the comment with `*/`"),
                );
                continue;
            }
            Ok(TokenKind::UnterminatedString) => {
                diags.push(
                    Diagnostic::error(
                        Code::UnterminatedString,
                        "unterminated string literal",
                        span,
                        "the string is not closed before the end of the line",
                    )
                    .with_help("add the closing `\"`"),
                );
                continue;
            }
            Ok(kind) => kind,
            Err(()) => {
                let c = lexer.slice().chars().next().unwrap_or('?');
                let mut d = Diagnostic::error(
                    Code::UnknownCharacter,
                    format!("unexpected character `{}`", c.escape_debug()),
                    span,
                    "no token starts with this character",
                );
                if !c.is_ascii() {
                    d = d.with_note("names and operators are ASCII; other characters may appear only in comments and strings");
                }
                diags.push(d);
                continue;
            }
        };
        tokens.push(Token { kind, span, line_start, space_before });
        line_start = false;
    }
    tokens
}

/// Reports escapes a string literal may not contain. The escapes are C's simple ones.
fn check_escapes(text: &str, span: Span, diags: &mut Diagnostics) {
    let mut chars = text.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        if c != '\\' {
            continue;
        }
        let Some((_, e)) = chars.next() else { break };
        if !matches!(e, 'n' | 't' | 'r' | '\\' | '"' | '\'' | '0' | 'a' | 'b' | 'f' | 'v') {
            let start = span.start + i as u32;
            let at = Span { start, end: start + 1 + e.len_utf8() as u32, ..span };
            diags.push(
                Diagnostic::error(
                    Code::InvalidEscape,
                    format!("unknown escape `\\{}`", e.escape_debug()),
                    at,
                    "",
                )
                .with_help("the escapes are \\n \\t \\r \\\\ \\\" \\' \\0 \\a \\b \\f \\v"),
            );
        }
    }
}

/// The value of a string literal's text (quotes included), with escapes replaced.
pub fn unescape(text: &str) -> String {
    let inner = text.strip_prefix('"').and_then(|t| t.strip_suffix('"')).unwrap_or(text);
    let mut out = String::with_capacity(inner.len());
    let mut chars = inner.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('n') => out.push('\n'),
            Some('t') => out.push('\t'),
            Some('r') => out.push('\r'),
            Some('0') => out.push('\0'),
            Some('a') => out.push('\x07'),
            Some('b') => out.push('\x08'),
            Some('f') => out.push('\x0c'),
            Some('v') => out.push('\x0b'),
            Some(other) => out.push(other),
            None => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::SourceMap;

    fn kinds(text: &str) -> (Vec<TokenKind>, Diagnostics) {
        let mut sources = SourceMap::new();
        let file = sources.add_file("t.sl", text, None);
        let mut diags = Diagnostics::default();
        let tokens = lex(file, text, &mut diags);
        (tokens.into_iter().map(|t| t.kind).filter(|k| *k != TokenKind::Newline).collect(), diags)
    }

    #[test]
    fn lexes_both_styles() {
        use TokenKind::*;
        let (k, d) = kinds("surface shader float4 f(primitive group texref t) { return {1, .5e2}; }");
        assert!(d.is_empty());
        assert_eq!(
            k,
            [
                Surface,
                Shader,
                Float4,
                Ident,
                LParen,
                PrimitiveGroup,
                Texref,
                Ident,
                RParen,
                LBrace,
                Return,
                LBrace,
                IntLit,
                Comma,
                FloatLit,
                RBrace,
                Semi,
                RBrace
            ]
        );
        let (k, _) = kinds("Ci = Os * (N . I) ^ dPdu; x <<= 2; // comment\n /* block\n */ y");
        assert_eq!(
            k,
            [
                Ident, Eq, Ident, Star, LParen, Ident, Dot, Ident, RParen, Caret, Ident, Semi, Ident, ShlEq,
                IntLit, Semi, Ident
            ]
        );
    }

    #[test]
    fn reports_lexical_errors() {
        let (_, d) = kinds("a @ b");
        assert_eq!(d.iter().map(|d| d.code).collect::<Vec<_>>(), [Code::UnknownCharacter]);
        let (_, d) = kinds("x = \"open\ny");
        assert_eq!(d.iter().map(|d| d.code).collect::<Vec<_>>(), [Code::UnterminatedString]);
        let (_, d) = kinds("a /* never closed");
        assert_eq!(d.iter().map(|d| d.code).collect::<Vec<_>>(), [Code::UnterminatedComment]);
        let (k, d) = kinds("x = 1e+;");
        assert_eq!(d.iter().map(|d| d.code).collect::<Vec<_>>(), [Code::MalformedNumber]);
        assert_eq!(k.len(), 4, "the malformed number stays a token");
    }

    #[test]
    fn line_starts_are_marked() {
        let mut sources = SourceMap::new();
        let text = "#define A 1\n  # if A\nx /* a\n b */ # y";
        let file = sources.add_file("t.sl", text, None);
        let tokens = lex(file, text, &mut Diagnostics::default());
        let hashes: Vec<bool> =
            tokens.iter().filter(|t| t.kind == TokenKind::Hash).map(|t| t.line_start).collect();
        assert_eq!(hashes, [true, true, false]);
    }

    #[test]
    fn unescapes_strings() {
        assert_eq!(unescape(r#""a\tb\"c""#), "a\tb\"c");
    }
}
