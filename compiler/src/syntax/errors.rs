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
use crate::source::{ExpnId, SourceMap, Span};

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

/// Words that are names wherever a name is expected: RenderMan's type words, and the keywords the
/// grammar takes as names after reporting them. When a name is expected, "a name" covers them.
const NAME_WORDS: &[&str] = &[
    "color",
    "point",
    "vector",
    "normal",
    "matrix",
    "string",
    "surface",
    "light",
    "displacement",
    "volume",
    "imager",
    "shader",
    "uniform",
    "varying",
    "output",
    "extern",
    "constant",
    "vertex",
    "fragment",
    "perlight",
    "illuminance",
    "illuminate",
    "solar",
    "gather",
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
    let name = has("identifier");
    let expression = name && has("integer literal") && has("(");
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
            || (name && NAME_WORDS.contains(n));
        if covered {
            continue;
        }
        // Token classes are said in words, everything else as it is written.
        let part = match *n {
            "identifier" => "a name".to_string(),
            "integer literal" | "float literal" => "a number".to_string(),
            "string literal" => "a string".to_string(),
            _ => format!("`{n}`"),
        };
        if !parts.contains(&part) {
            parts.push(part);
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
        return else_without_if(at, tokens);
    }
    if let Some(d) = stray_brace(at, tokens, sources) {
        return d;
    }
    if tok.kind.is_keyword() && expects("identifier") && !expects(text) {
        return keyword_as_name(tok, text);
    }
    // `float uniform x`: the grammar took the qualifier for a misused name; the fault is its place.
    if let Some(q) = prev.filter(|p| is_qualifier(p.kind))
        && at >= 2
        && TYPES.contains(&tokens[at - 2].kind.spelling().unwrap_or(""))
        && tok.kind == TokenKind::Ident
    {
        let (qualifier, ty) = (sources.text(q.span), sources.text(tokens[at - 2].span));
        return Diagnostic::error(
            Code::UnexpectedToken,
            format!("qualifier `{qualifier}` after the type"),
            q.span,
            format!("`{qualifier}` must come before `{ty}`"),
        )
        .with_help(format!("write `{qualifier} {ty} {text}`"));
    }
    // Where the `;` goes: after the previous token, or after the use of the macro that produced it
    // when the next token is not from that macro too.
    let before = prev.map(|p| Token { span: outside_expansion(sources, p.span, tok.span), ..p });
    if expects(";")
        && let Some(p) = before
        && (tok.kind == TokenKind::RBrace || starts_later_line(sources, p, tok))
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

/// `span` lifted out of each macro expansion that `other` is not also inside.
fn outside_expansion(sources: &SourceMap, mut span: Span, other: Span) -> Span {
    let mut shared = vec![ExpnId::ROOT];
    let mut at = other;
    while let Some(e) = sources.expansion(at.expn) {
        shared.push(at.expn);
        at = e.call_site;
    }
    while !shared.contains(&span.expn) {
        span = sources.call_site(span);
    }
    span
}

/// `else` where no `if` can take it. The `;` before it gets a label when it is the culprit: a
/// statement of its own right after a complete `if` (`if (c) { ... }; else`).
pub fn else_without_if(at: usize, tokens: &[Token]) -> Diagnostic {
    let mut d = Diagnostic::error(
        Code::ElseWithoutIf,
        "`else` without a matching `if`",
        tokens[at].span,
        "no `if` to attach to",
    );
    if let Some(semi) = at.checked_sub(1).filter(|&i| tokens[i].kind == TokenKind::Semi)
        && let Some(last) = semi.checked_sub(1)
        && matches!(tokens[last].kind, TokenKind::RBrace | TokenKind::Semi)
        && let Some(start) = statement_start(tokens, last)
        && tokens[start].kind == TokenKind::If
    {
        let help = if tokens[last].kind == TokenKind::RBrace {
            "an `if` whose body is a block takes no `;` before `else`"
        } else {
            "the `if` statement already ends with the `;` before this one; remove this one"
        };
        d = d.with_label(tokens[semi].span, "this `;` ends the statement before the `else`").with_help(help);
    }
    d
}

/// Where the statement whose last token is `tokens[last]` starts; `None` when it already has an
/// `else` of its own (so that no `;` could be what keeps an `else` from it). Brackets are balanced:
/// the parser runs only then.
fn statement_start(tokens: &[Token], last: usize) -> Option<usize> {
    let mut i = last;
    loop {
        if matches!(tokens[i].kind, TokenKind::RParen | TokenKind::RBracket | TokenKind::RBrace) {
            i = opener(tokens, i)?;
        }
        if i == 0 || matches!(tokens[i - 1].kind, TokenKind::LBrace | TokenKind::RBrace | TokenKind::Semi) {
            return Some(i);
        }
        i -= 1;
        if tokens[i].kind == TokenKind::Else {
            return None;
        }
    }
}

/// The index of the bracket that the closer at `close` closes.
fn opener(tokens: &[Token], close: usize) -> Option<usize> {
    let mut depth = 0usize;
    for i in (0..=close).rev() {
        match tokens[i].kind {
            TokenKind::RParen | TokenKind::RBracket | TokenKind::RBrace => depth += 1,
            TokenKind::LParen | TokenKind::LBracket | TokenKind::LBrace => {
                depth -= 1;
                if depth == 0 {
                    return Some(i);
                }
            }
            _ => {}
        }
    }
    None
}

/// A keyword where a name belongs.
pub fn keyword_as_name(tok: Token, text: &str) -> Diagnostic {
    Diagnostic::error(
        Code::ReservedWord,
        format!("expected a name, found keyword `{text}`"),
        tok.span,
        "keywords cannot be used as names",
    )
    .with_help(format!("rename it, e.g. `{text}_`"))
}

fn is_qualifier(kind: TokenKind) -> bool {
    use TokenKind::*;
    matches!(kind, Uniform | Varying | Output | Extern | Constant | Vertex | Fragment | Perlight)
}

/// Whether `later` is on a later line than `earlier`, both lifted out of macro expansions to the
/// text the user wrote (a token from another file counts as a new line).
fn starts_later_line(sources: &SourceMap, earlier: Token, later: Token) -> bool {
    let (a, b) = (sources.call_site(earlier.span), sources.call_site(later.span));
    a.file != b.file || {
        let file = sources.file(a.file);
        file.line_index(a.start as usize) < file.line_index(b.start as usize)
    }
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
