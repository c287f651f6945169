//! The parser driver: runs the LALRPOP grammar over preprocessed tokens and turns its errors into
//! diagnostics. [`Ctx`] is what the grammar's actions see: spans, literal values, and a place to
//! report problems that do not stop the parse.

use std::cell::RefCell;

use lalrpop_util::ErrorRecovery;
use smol_str::SmolStr;

use super::ast::*;
use super::lexer::{Token, unescape};
use super::token::{NumberClass, TokenKind, classify_number, int_value};
use super::{delimiters, errors};
use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::source::{SourceMap, Span};

/// The most elements an array may have: every shaded point holds its own copy (the interpreter
/// keeps one register per element and lane, 256 lanes to a batch), so a large array exhausts
/// memory long before it is useful. The standard library's largest table has 768.
pub const MAX_ARRAY_LENGTH: usize = 4096;

lalrpop_util::lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused_parens, unused_imports, missing_docs)]
    grammar,
    "/syntax/grammar.rs"
);

/// The grammar's error type: actions never fail (they report through [`Ctx`] instead).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Never {}

/// A syntax error the grammar recovered from.
pub type Recovered = ErrorRecovery<usize, TokenKind, Never>;

/// A qualifier keyword and the index of its token.
pub enum Qualifier {
    /// A storage class or rate.
    Rate(RateQualifier, usize),
    /// `perlight`.
    Perlight(usize),
    /// `output`.
    Output(usize),
    /// `extern`.
    Extern(usize),
}

/// One entry of a parameter list, before the types of continued declarators are filled in.
pub enum ParamItem {
    /// `[qualifiers] type declarator`.
    Typed(Box<(Qualifiers, TypeSpec, Declarator)>),
    /// `declarator`, taking the type of the entry before.
    Continued(Box<Declarator>),
}

/// The parts of `for (init; cond; step)`, each optional.
pub type ForHeader = (Option<Box<Stmt>>, Option<Expr>, Option<Expr>);

/// The header of a statement that takes a body: `while`, `for`, `illuminance`, ...
pub enum LoopHead {
    /// `while (cond)`.
    While(Expr),
    /// `for (init; cond; step)`.
    For(Box<ForHeader>),
    /// `illuminance(args)`.
    Illuminance(Vec<Expr>),
    /// `illuminate(args)`.
    Illuminate(Vec<Expr>),
    /// `solar(args)`.
    Solar(Vec<Expr>),
}

/// What the grammar's actions work with.
pub struct Ctx<'a> {
    tokens: &'a [Token],
    sources: &'a SourceMap,
    reported: RefCell<Vec<Diagnostic>>,
}

impl Ctx<'_> {
    /// The span from token `l` up to (not including) token `r`.
    pub fn span(&self, l: usize, r: usize) -> Span {
        match (self.tokens.get(l), r.checked_sub(1).and_then(|last| self.tokens.get(last))) {
            (Some(first), Some(last)) if r > l => self.sources.join(first.span, last.span),
            (Some(first), _) => Span { end: first.span.start, ..first.span },
            (None, _) => self.tokens.last().map(|t| t.span.end_point()).unwrap_or_default(),
        }
    }

    fn text(&self, i: usize) -> &str {
        self.sources.text(self.tokens[i].span)
    }

    /// Reports a problem found by an action.
    pub fn report(&self, d: Diagnostic) {
        self.reported.borrow_mut().push(d);
    }

    /// Reports a syntax error the grammar recovered from. Like the problems actions find, it is
    /// reported when the parse gets there, so diagnostics come in the order of the text.
    pub fn recover(&self, e: Recovered) {
        self.report(errors::to_diagnostic(&e.error, self.tokens, self.sources));
    }

    /// The identifier at token `i`.
    pub fn ident(&self, i: usize) -> Ident {
        let text = self.text(i);
        // Names are short: store them inline, skipping `new`'s checks for whitespace runs.
        let name = if text.len() <= 23 { SmolStr::new_inline(text) } else { SmolStr::new(text) };
        Ident { name, span: self.tokens[i].span }
    }

    /// An expression node from token `l` to `r`.
    pub fn expr(&self, l: usize, r: usize, kind: ExprKind) -> Expr {
        Expr { kind, span: self.span(l, r) }
    }

    /// Builds the tree of `first op operand op operand ...` by precedence climbing. Each operand
    /// comes with its token range, so every node spans exactly its tokens (parentheses included).
    /// All binary operators associate to the left.
    pub fn climb(&self, first: (Expr, usize, usize), rest: Vec<(BinaryOp, usize, Expr, usize)>) -> Expr {
        fn precedence(op: BinaryOp) -> u8 {
            use BinaryOp::*;
            match op {
                Or => 1,
                And => 2,
                BitOr => 3,
                BitAnd => 4,
                Eq | Ne => 5,
                Lt | Le | Gt | Ge => 6,
                Shl | Shr => 7,
                Add | Sub => 8,
                // RenderMan: `^` (cross) between `+` and `*`, `.` (dot) tightest.
                Caret => 9,
                Mul | Div | Rem => 10,
                Dot => 11,
            }
        }
        let mut operands: Vec<(Expr, usize, usize)> = Vec::with_capacity(rest.len() + 1);
        let mut operators: Vec<BinaryOp> = Vec::with_capacity(rest.len());
        let reduce = |operands: &mut Vec<(Expr, usize, usize)>, op: BinaryOp| {
            let (rhs, _, r) = operands.pop().expect("an operand for each operator");
            let (lhs, l, _) = operands.pop().expect("an operand for each operator");
            operands.push((self.binary(l, r, op, lhs, rhs), l, r));
        };
        operands.push(first);
        for (op, l, operand, r) in rest {
            while operators.last().is_some_and(|&top| precedence(top) >= precedence(op)) {
                let top = operators.pop().expect("checked");
                reduce(&mut operands, top);
            }
            operators.push(op);
            operands.push((operand, l, r));
        }
        while let Some(op) = operators.pop() {
            reduce(&mut operands, op);
        }
        operands.pop().expect("the whole expression").0
    }

    /// A binary operation.
    pub fn binary(&self, l: usize, r: usize, op: BinaryOp, lhs: Expr, rhs: Expr) -> Expr {
        self.expr(l, r, ExprKind::Binary { op, lhs: Box::new(lhs), rhs: Box::new(rhs) })
    }

    /// A statement node from token `l` to `r`.
    pub fn stmt(&self, l: usize, r: usize, kind: StmtKind) -> Stmt {
        Stmt { kind, span: self.span(l, r) }
    }

    /// A boxed statement node from token `l` to `r`.
    pub fn boxed(&self, l: usize, r: usize, kind: StmtKind) -> Box<Stmt> {
        Box::new(self.stmt(l, r, kind))
    }

    /// The statements of a block, out of the boxes the grammar keeps them in (a statement after a
    /// stray `else` comes second in its pair).
    pub fn unbox(&self, stmts: Vec<(Box<Stmt>, Option<Box<Stmt>>)>) -> Vec<Stmt> {
        stmts
            .into_iter()
            .flat_map(|(s, after_else)| std::iter::once(*s).chain(after_else.map(|s| *s)))
            .collect()
    }

    /// Reports the `else` at token `i`, which follows a statement that is not an `if`.
    pub fn stray_else(&self, i: usize) {
        self.report(errors::else_without_if(i, self.tokens));
    }

    /// Checks the qualifiers written before a function's result type: RenderMan allows one
    /// storage class (`uniform float f()`), which has no effect since rates are inferred; any
    /// other qualifier is an error.
    pub fn result_qualifiers(&self, list: Vec<Qualifier>) {
        for item in &list {
            let (i, word) = match item {
                Qualifier::Rate(RateQualifier::Uniform | RateQualifier::Varying, _) => continue,
                Qualifier::Rate(rate, i) => (*i, rate.keyword()),
                Qualifier::Perlight(i) => (*i, "perlight"),
                Qualifier::Output(i) => (*i, "output"),
                Qualifier::Extern(i) => (*i, "extern"),
            };
            self.report(
                Diagnostic::error(
                    Code::InvalidQualifier,
                    format!("`{word}` cannot qualify a function's result"),
                    self.span(i, i + 1),
                    "not allowed here",
                )
                .with_help("a function's result may be declared `uniform` or `varying`, or nothing"),
            );
        }
        // Conflicts (`uniform varying float f()`) are reported as for declarations.
        let _ = self.qualifiers(list);
    }

    /// The keyword at token `i`, used as a name: reported, and taken as the name.
    pub fn keyword_as_name(&self, i: usize) -> Ident {
        self.report(errors::keyword_as_name(self.tokens[i], self.text(i)));
        self.ident(i)
    }

    /// A statement made of a loop header and its body.
    pub fn looped(&self, l: usize, r: usize, head: LoopHead, body: Stmt) -> Stmt {
        let body = Box::new(body);
        let kind = match head {
            LoopHead::While(cond) => StmtKind::While { cond, body },
            LoopHead::For(header) => {
                let (init, cond, step) = *header;
                StmtKind::For { init, cond: cond.map(Box::new), step: step.map(Box::new), body }
            }
            LoopHead::Illuminance(args) => StmtKind::Illuminance { args, body },
            LoopHead::Illuminate(args) => StmtKind::Illuminate { args, body },
            LoopHead::Solar(args) => StmtKind::Solar { args, body },
        };
        self.stmt(l, r, kind)
    }

    /// The integer literal at token `i`. Malformed literals were reported by the lexer and read as 0.
    pub fn int(&self, i: usize) -> ExprKind {
        let text = self.text(i);
        if classify_number(text) != NumberClass::Int {
            return ExprKind::Int { value: 0, unsigned: false };
        }
        let unsigned = text.ends_with(['u', 'U']);
        let value = int_value(text).and_then(|v| u32::try_from(v).ok());
        match value {
            Some(value) => ExprKind::Int { value, unsigned },
            None => {
                self.report(
                    Diagnostic::error(
                        Code::IntegerTooLarge,
                        format!("integer literal `{text}` does not fit in 32 bits"),
                        self.tokens[i].span,
                        "the largest is 4294967295 (0xffffffff)",
                    )
                    .with_help("write it as a float literal if a float is meant, e.g. `1e10`"),
                );
                ExprKind::Int { value: 0, unsigned }
            }
        }
    }

    /// The float literal at token `i`.
    pub fn float(&self, i: usize) -> ExprKind {
        let text = self.text(i);
        let digits = text.strip_suffix(['f', 'F']).unwrap_or(text);
        let value: f64 = digits.parse().unwrap_or(0.0);
        // Parsed straight to f32, so that the rounding is f32's own (not f64's, then f32's).
        if digits.parse::<f32>().is_ok_and(f32::is_infinite) {
            self.report(
                Diagnostic::error(
                    Code::FloatTooLarge,
                    format!("float literal `{text}` is too large for f32"),
                    self.tokens[i].span,
                    "it would round to infinity",
                )
                .with_note("the largest finite f32 is about 3.4028235e38"),
            );
        }
        ExprKind::Float(value)
    }

    /// The value of the string literal at token `i`, with its span.
    pub fn string_value(&self, i: usize) -> (String, Span) {
        (unescape(self.text(i)), self.tokens[i].span)
    }

    /// The level of `break n` / `continue n`.
    pub fn loop_level(&self, i: usize) -> u32 {
        match self.int(i) {
            ExprKind::Int { value, .. } if value > 0 => value,
            _ => {
                self.report(Diagnostic::error(
                    Code::InvalidLoopLevel,
                    "the loop level of `break` or `continue` must be at least 1",
                    self.tokens[i].span,
                    "counts the enclosing loops to leave; 1 is the innermost",
                ));
                1
            }
        }
    }

    /// A braced constructor `{...}`; an empty one is reported.
    pub fn braced(&self, l: usize, r: usize, items: Vec<Expr>) -> Expr {
        let e = self.expr(l, r, ExprKind::Braced(items));
        if let ExprKind::Braced(items) = &e.kind
            && items.is_empty()
        {
            self.report(
                Diagnostic::error(
                    Code::EmptyConstructor,
                    "empty vector constructor",
                    e.span,
                    "no components",
                )
                .with_help("write the components, e.g. `{0, 0, 0, 1}`"),
            );
        }
        e
    }

    /// The size in `name[size]`, which must be a positive integer literal (after macro expansion)
    /// of at most [`MAX_ARRAY_LENGTH`].
    pub fn array_size(&self, e: Expr, span: Span) -> ArraySize {
        match e.kind {
            ExprKind::Int { value, .. } if value as usize > MAX_ARRAY_LENGTH => {
                self.report(
                    Diagnostic::error(
                        Code::ResourceLimit,
                        format!("an array of {value} elements, over the limit of {MAX_ARRAY_LENGTH}"),
                        e.span,
                        "array size over the limit",
                    )
                    .with_help(
                        "every shaded point holds its own copy of an array: store large tables in a texture",
                    ),
                );
                ArraySize { len: None, span }
            }
            ExprKind::Int { value, .. } if value > 0 => ArraySize { len: Some(value), span },
            _ => {
                self.report(
                    Diagnostic::error(
                        Code::InvalidArraySize,
                        "array size must be a positive integer literal",
                        e.span,
                        "not a positive integer literal",
                    )
                    .with_help("use a number or a `#define`d constant, e.g. `float table[16]`"),
                );
                ArraySize { len: None, span }
            }
        }
    }

    /// Folds a qualifier list, reporting contradictions and repeats.
    pub fn qualifiers(&self, list: Vec<Qualifier>) -> Qualifiers {
        let mut q = Qualifiers::default();
        for item in list {
            let (slot, span, what): (&mut Option<Span>, Span, String) = match item {
                Qualifier::Rate(rate, i) => {
                    let span = self.span(i, i + 1);
                    if let Some((previous, previous_span)) = q.rate {
                        let message = if previous == rate {
                            format!("`{}` is written twice", rate.keyword())
                        } else {
                            format!(
                                "conflicting qualifiers `{}` and `{}`",
                                previous.keyword(),
                                rate.keyword()
                            )
                        };
                        self.report(
                            Diagnostic::error(Code::ConflictingQualifiers, message, span, "")
                                .with_label(previous_span, "the first qualifier")
                                .with_help("a declaration has at most one storage class or rate"),
                        );
                    } else {
                        q.rate = Some((rate, span));
                    }
                    continue;
                }
                Qualifier::Perlight(i) => (&mut q.perlight, self.span(i, i + 1), "perlight".into()),
                Qualifier::Output(i) => (&mut q.output, self.span(i, i + 1), "output".into()),
                Qualifier::Extern(i) => (&mut q.extern_, self.span(i, i + 1), "extern".into()),
            };
            match slot {
                Some(previous) => self.report(
                    Diagnostic::error(
                        Code::ConflictingQualifiers,
                        format!("`{what}` is written twice"),
                        span,
                        "",
                    )
                    .with_label(*previous, "first written here"),
                ),
                None => *slot = Some(span),
            }
        }
        q
    }

    /// Resolves a parameter list: each continued declarator takes the type of the one before it,
    /// but only across `,` (after `;` a new group must name its type).
    pub fn params(&self, items: Vec<(Option<bool>, ParamItem)>) -> Vec<Param> {
        let mut params: Vec<Param> = Vec::with_capacity(items.len());
        let mut head: Option<(Qualifiers, TypeSpec)> = None;
        for (separator, item) in items {
            let after_semicolon = separator == Some(true);
            let (qualifiers, ty, d) = match item {
                ParamItem::Typed(typed) => {
                    let (q, t, d) = *typed;
                    head = Some((q, t));
                    (q, t, d)
                }
                ParamItem::Continued(d) => match head {
                    Some((q, t)) if !after_semicolon => (q, t, *d),
                    _ => {
                        self.report(
                            Diagnostic::error(
                                Code::UnexpectedToken,
                                format!("parameter `{}` has no type", d.name.name),
                                d.name.span,
                                "expected a type before this name",
                            )
                            .with_help(format!("write its type, e.g. `float {}`", d.name.name)),
                        );
                        head = None;
                        continue;
                    }
                },
            };
            params.push(Param {
                qualifiers,
                ty,
                name: d.name,
                array: d.array,
                default: d.init,
                span: d.span,
            });
        }
        params
    }
}

/// Whether a token is a keyword only in the Stanford style: in a RenderMan-style file it is a name.
fn stanford_only(kind: TokenKind) -> bool {
    use TokenKind as T;
    matches!(
        kind,
        T::Constant
            | T::Vertex
            | T::Fragment
            | T::Perlight
            | T::Primitive
            | T::Int
            | T::Uint
            | T::Bool
            | T::Float3
            | T::Float4
            | T::Matrix3
            | T::Matrix4
            | T::Texref
            | T::Clampf
    )
}

/// Whether a word followed by a name declares it: a type word.
fn declares(kind: TokenKind) -> bool {
    use TokenKind as T;
    matches!(kind, T::Float | T::Color | T::Point | T::Vector | T::Normal | T::Matrix | T::String | T::Void)
        || (stanford_only(kind)
            && !matches!(kind, T::Constant | T::Vertex | T::Fragment | T::Perlight | T::Primitive))
}

/// The tokens of a RenderMan-style file with the words that are keywords only in the Stanford style
/// turned into names (`surface constant()`, `float int = 1`), and the shader kinds used as
/// variables inside a definition (`float light = 1`) too; `None` when nothing changes. A file is
/// RenderMan-style when it defines a shader as `surface name(...)` and none as `surface shader
/// type name(...)`; a file of functions only keeps every keyword (the standard library's are
/// Stanford-style).
fn renderman_words(tokens: &[Token]) -> Option<Vec<Token>> {
    use TokenKind as T;
    let is_kind = |k: TokenKind| matches!(k, T::Surface | T::Light | T::Displacement | T::Volume | T::Imager);
    let mut depth = 0usize;
    let mut renderman = false;
    for (i, t) in tokens.iter().enumerate() {
        let next = tokens.get(i + 1).map(|t| t.kind);
        match t.kind {
            T::LBrace | T::LParen | T::LBracket => depth += 1,
            T::RBrace | T::RParen | T::RBracket => depth = depth.saturating_sub(1),
            T::Shader if i > 0 && is_kind(tokens[i - 1].kind) => return None,
            k if depth == 0 && is_kind(k) => {
                let name = next.is_some_and(|n| n == T::Ident || stanford_only(n));
                let paren = tokens.get(i + 2).is_some_and(|t| t.kind == T::LParen);
                renderman |= name && paren;
            }
            _ => {}
        }
    }
    if !renderman {
        return None;
    }
    let mut out = tokens.to_vec();
    let mut depth = 0usize;
    for (i, token) in out.iter_mut().enumerate() {
        let kind = token.kind;
        let previous = i.checked_sub(1).map(|p| tokens[p].kind);
        let next = tokens.get(i + 1).map(|t| t.kind);
        match kind {
            T::LBrace | T::LParen | T::LBracket => depth += 1,
            T::RBrace | T::RParen | T::RBracket => depth = depth.saturating_sub(1),
            // A qualifier or type word is followed by a name, another keyword or (a cast) `(`; one
            // that is declared (`float int`, `surface constant(`) or followed by anything else
            // (`int + 1`, `vertex;`) is a name.
            k if stanford_only(k) => {
                let declared = previous.is_some_and(|p| declares(p) || is_kind(p));
                let as_keyword = next.is_some_and(|n| n == T::Ident || n == T::LParen || n.is_keyword());
                if declared || !as_keyword {
                    token.kind = T::Ident;
                }
            }
            // `surface("Kd", Kd)` stays message passing; `light float f()` a function's context.
            k if depth > 0 && is_kind(k) && next != Some(T::LParen) => token.kind = T::Ident,
            _ => {}
        }
    }
    Some(out)
}

/// Parses preprocessed tokens into a module, reporting every independent syntax error.
pub fn parse(tokens: &[Token], sources: &SourceMap, diags: &mut Diagnostics) -> Module {
    // Unbalanced brackets derail any LR parser into a cascade of errors; report them alone.
    let delimiter_errors = delimiters::check(tokens);
    if !delimiter_errors.is_empty() {
        diags.extend(delimiter_errors);
        return Module::default();
    }
    let renderman_words = renderman_words(tokens);
    let tokens: &[Token] = renderman_words.as_deref().unwrap_or(tokens);
    let ctx = Ctx { tokens, sources, reported: RefCell::default() };
    let input = tokens.iter().enumerate().map(|(i, t)| Ok::<_, Never>((i, t.kind, i + 1)));
    let result = grammar::ModuleParser::new().parse(&ctx, input);
    let module = match result {
        Ok(module) => module,
        Err(e) => {
            ctx.report(errors::to_diagnostic(&e, tokens, sources));
            Module::default()
        }
    };
    // Actions run in reduction order, not text order (an inlined rule's action runs when its
    // parent reduces); report in the order of the tokens the diagnostics point at.
    let mut reported = ctx.reported.take();
    reported.sort_by_cached_key(|d| {
        let at = sources.call_site(d.primary_span());
        tokens.iter().position(|t| {
            let t = sources.call_site(t.span);
            t.file == at.file && t.end > at.start
        })
    });
    diags.extend(reported);
    module
}
