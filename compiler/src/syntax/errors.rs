//! Turning the grammar's errors into diagnostics a person can act on.
//!
//! LALRPOP reports "unexpected token, expected one of ..." with the grammar's terminal names. The
//! common causes — a missing `;`, a keyword used as a name, a stray `else`, C syntax the language does
//! not have, a vector constructor closed too early — get their own codes and messages; everything
//! else gets a summarised expected list ("an expression" rather than thirty tokens).

use lalrpop_util::ParseError;

use super::lexer::Token;
use super::parser::Never;
use super::token::TokenKind;
use crate::diag::{Code, Diagnostic};
use crate::source::SourceMap;

/// Terminals that can start an expression, as the grammar names them.
const EXPRESSION_STARTS: &[&str] = &[
    "identifier",
    "integer literal",
    "float literal",
    "string literal",
    "true",
    "false",
    "(",
    "{",
    "-",
    "+",
    "!",
    "~",
    "++",
    "--",
];

/// Terminals that continue an expression.
const OPERATORS: &[&str] = &[
    "+", "-", "*", "/", "%", "^", ".", "&", "|", "&&", "||", "<", ">", "<=", ">=", "==", "!=", "<<", ">>",
    "?", "[", "=", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "<<=", ">>=", "++", "--",
];

/// Words that begin a type.
const TYPES: &[&str] = &[
    "float", "color", "point", "vector", "normal", "matrix", "string", "void", "float3", "float4", "matrix3",
    "matrix4", "bool", "texref", "clampf", "int", "uint",
];

/// The diagnostic for one grammar error.
pub fn to_diagnostic(
    e: &ParseError<usize, TokenKind, Never>,
    tokens: &[Token],
    sources: &SourceMap,
) -> Diagnostic {
    match e {
        ParseError::UnrecognizedToken { token: (at, _, _), expected } => {
            unexpected(*at, expected, tokens, sources)
        }
        ParseError::ExtraToken { token: (at, _, _) } => unexpected(*at, &[], tokens, sources),
        ParseError::InvalidToken { location } => unexpected(*location, &[], tokens, sources),
        ParseError::UnrecognizedEof { expected, .. } => {
            let last = tokens.last().map(|t| t.span).unwrap_or_default();
            Diagnostic::error(
                Code::UnexpectedEof,
                format!("unexpected end of file, expected {}", summarise(expected)),
                last,
                "the file ends after this",
            )
        }
        ParseError::User { error } => match *error {},
    }
}

fn describe(t: Token, sources: &SourceMap) -> String {
    let text = sources.text(t.span);
    match t.kind {
        TokenKind::Ident => format!("`{text}`"),
        TokenKind::IntLit | TokenKind::FloatLit => format!("number `{text}`"),
        TokenKind::StringLit => format!("string {text}"),
        TokenKind::Reserved => format!("reserved word `{text}`"),
        k if k.is_keyword() => format!("keyword `{text}`"),
        _ => format!("`{text}`"),
    }
}

fn unquote(name: &str) -> &str {
    name.strip_prefix('"').and_then(|n| n.strip_suffix('"')).unwrap_or(name)
}

/// "an expression", "`;` or `,`", "a type": the expected set, said briefly.
fn summarise(expected: &[String]) -> String {
    let names: Vec<&str> = expected.iter().map(|e| unquote(e)).collect();
    let has = |n: &str| names.contains(&n);
    let mut parts: Vec<String> = Vec::new();
    let expression = has("identifier") && has("integer literal") && has("(");
    let operator = has("*") && has("+");
    let type_name = has("float") && has("color") && has("float4");
    if expression {
        parts.push("an expression".into());
    }
    for n in &names {
        let covered = (expression && EXPRESSION_STARTS.contains(n))
            || (operator && OPERATORS.contains(n))
            || (type_name && TYPES.contains(n))
            || (expression && TYPES.contains(n))
            || (expression && matches!(*n, "surface" | "light" | "displacement" | "volume" | "imager"));
        if !covered {
            parts.push(if n.contains(' ') && !n.starts_with("primitive") {
                (*n).to_string()
            } else {
                format!("`{n}`")
            });
        }
    }
    if type_name && !expression {
        parts.push("a type".into());
    }
    if operator {
        parts.push("an operator".into());
    }
    if parts.len() > 6 {
        parts.truncate(6);
        parts.push("...".into());
    }
    match parts.len() {
        0 => "something else".into(),
        1 => parts.remove(0),
        _ => {
            let last = parts.pop().unwrap_or_default();
            format!("{} or {}", parts.join(", "), last)
        }
    }
}

fn unexpected(at: usize, expected: &[String], tokens: &[Token], sources: &SourceMap) -> Diagnostic {
    let Some(&tok) = tokens.get(at) else {
        let last = tokens.last().map(|t| t.span).unwrap_or_default();
        return Diagnostic::error(
            Code::UnexpectedEof,
            "unexpected end of file",
            last,
            "the file ends after this",
        );
    };
    let prev = at.checked_sub(1).and_then(|i| tokens.get(i)).copied();
    let found = describe(tok, sources);
    let text = sources.text(tok.span);
    let expects = |name: &str| expected.iter().any(|e| unquote(e) == name);

    if tok.kind == TokenKind::Reserved {
        let help = match text {
            "struct" | "union" => "there are no structures; use separate variables or arrays",
            "switch" | "case" => "use `if` / `else if` chains",
            "do" => "use a `while` or `for` loop",
            "goto" => "use loops with `break` and `continue`",
            "typedef" => "there are no type aliases; `#define` can name a type",
            "const" => "write `constant` (compile-time, Stanford style) or `uniform` (RenderMan style)",
            "enum" => "use `#define`d integer constants",
            _ => "this C feature is not part of the language",
        };
        return Diagnostic::error(
            Code::UnsupportedSyntax,
            format!("`{text}` is not part of the language"),
            tok.span,
            "reserved C keyword",
        )
        .with_help(help);
    }
    if tok.kind == TokenKind::Primitive {
        return Diagnostic::error(
            Code::PrimitiveWithoutGroup,
            "`primitive` must be followed by `group`",
            tok.span,
            "the rate is written `primitive group`",
        );
    }
    if tok.kind == TokenKind::Else {
        let mut d = Diagnostic::error(
            Code::ElseWithoutIf,
            "`else` without a matching `if`",
            tok.span,
            "no `if` to attach to",
        );
        if let Some(p) = prev.filter(|p| p.kind == TokenKind::Semi) {
            d = d
                .with_label(p.span, "this `;` ends the statement before the `else`")
                .with_help("an `if` whose body is a block takes no `;` before `else`");
        }
        return d;
    }
    if let Some(d) = stray_brace(at, tokens, sources) {
        return d;
    }
    if tok.kind.is_keyword() && expects("identifier") && !expects(text) {
        return Diagnostic::error(
            Code::ReservedWord,
            format!("expected a name, found keyword `{text}`"),
            tok.span,
            "keywords cannot be used as names",
        )
        .with_help(format!("rename it, e.g. `{text}_`"));
    }
    if expects(";")
        && let Some(p) = prev
        && (tok.kind == TokenKind::RBrace || line_of(sources, p) < line_of(sources, tok))
    {
        return Diagnostic::error(
            Code::MissingSemicolon,
            format!("expected `;`, found {found}"),
            p.span.end_point(),
            "expected `;` here",
        )
        .with_label(tok.span, format!("unexpected {found}"))
        .with_help("add `;` at the end of the statement");
    }
    let message = if expected.is_empty() {
        format!("unexpected {found}")
    } else {
        format!("expected {}, found {found}", summarise(expected))
    };
    Diagnostic::error(Code::UnexpectedToken, message, tok.span, format!("unexpected {found}"))
}

fn line_of(sources: &SourceMap, t: Token) -> usize {
    let span = sources.call_site(t.span);
    sources.file(span.file).line_index(span.start as usize) + span.file.index() * 1_000_000
}

/// `x = {a, b}, c, d;`: a vector constructor closed before its last components. The parser sees a
/// declarator list continue with a non-name; the fault is the `}`.
fn stray_brace(at: usize, tokens: &[Token], sources: &SourceMap) -> Option<Diagnostic> {
    let tok = tokens[at];
    if at < 2 || tokens[at - 1].kind != TokenKind::Comma || tokens[at - 2].kind != TokenKind::RBrace {
        return None;
    }
    if matches!(tok.kind, TokenKind::Ident | TokenKind::RBrace | TokenKind::Semi) {
        return None;
    }
    let close = tokens[at - 2];
    let mut depth = 0usize;
    let mut open_at = None;
    for i in (0..at - 2).rev() {
        match tokens[i].kind {
            TokenKind::RBrace => depth += 1,
            TokenKind::LBrace if depth == 0 => {
                open_at = Some(i);
                break;
            }
            TokenKind::LBrace => depth -= 1,
            _ => {}
        }
    }
    let open = open_at?;
    if open == 0 || tokens[open - 1].kind != TokenKind::Eq {
        return None;
    }
    let last_component =
        tokens[at..].iter().position(|t| t.kind == TokenKind::Semi).map_or(tok, |n| tokens[at + n - 1]);
    let outside = sources.join(tok.span, last_component.span);
    Some(
        Diagnostic::error(
            Code::StrayBrace,
            "stray `}` closes the vector constructor before its last components",
            close.span,
            "the constructor ends here",
        )
        .with_label(tokens[open].span, "the constructor starts here")
        .with_label(outside, "these components are left outside it")
        .with_help("remove this `}` and close the constructor after its last component"),
    )
}
