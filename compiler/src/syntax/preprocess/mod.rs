//! The preprocessor: `#define`, `#undef`, `#include`, conditional compilation, `#error`, `#pragma once`.
//!
//! RenderMan shaders are written for cpp, so Patina runs one — on tokens, not text, so that every
//! token it passes on keeps a span in the file (or macro body) it was written in. Each inclusion of a
//! file is a new [`FileId`] whose `included_from` is the directive, and each macro expansion is an
//! [`ExpnId`](crate::source::ExpnId); diagnostics follow both back to the user's own lines.

mod condition;
mod expand;
mod loader;

pub use expand::Macro;
pub use loader::{FsLoader, LoadError, Loaded, MemoryLoader, SourceLoader, latin1_warning, read_source_file};

use std::ops::Range;

use rustc_hash::{FxHashMap, FxHashSet};
use smol_str::SmolStr;

use crate::diag::{Code, Diagnostic, Diagnostics, Severity};
use crate::source::{FileId, SourceMap, Span};
use crate::syntax::lexer::{Token, lex, unescape};
use crate::syntax::token::TokenKind;
use expand::Expander;

/// Includes nested deeper than this are an error (a file that includes itself gets here fast).
pub const MAX_INCLUDE_DEPTH: usize = 64;

/// A source file larger than this (in bytes) is refused: the root file or an included one.
/// Spans are 32-bit offsets, and no shader comes near this.
pub const MAX_FILE_SIZE: usize = 16 << 20;

/// The text of a root file and everything it includes (each inclusion counted) may not add up to
/// more than this many bytes.
pub const MAX_TOTAL_SOURCE: usize = 64 << 20;

/// One `#if` ... `#endif` in progress.
struct Conditional {
    /// The `#if`, `#ifdef` or `#ifndef` directive.
    opened: Span,
    /// The `#else`, once seen.
    else_seen: Option<Span>,
    /// Whether the enclosing text is being compiled.
    parent_active: bool,
    /// Whether the current branch is being compiled.
    taking: bool,
    /// Whether some branch has been compiled already.
    taken: bool,
}

/// Runs the preprocessor over `root` and everything it includes; returns the tokens the parser
/// reads (no line breaks, no directives).
pub fn preprocess(
    sources: &mut SourceMap,
    root: FileId,
    loader: &dyn SourceLoader,
    diags: &mut Diagnostics,
) -> Vec<Token> {
    let mut pp = Preprocessor {
        sources,
        loader,
        diags,
        macros: FxHashMap::default(),
        initials: [false; 256],
        once: FxHashSet::default(),
        out: Vec::new(),
        produced: 0,
        exhausted: false,
        total: 0,
        too_deep: false,
    };
    let at = Span::new(root, 0..0);
    if pp.too_large(&pp.sources.file(root).name.clone(), pp.sources.file(root).text.len(), at) {
        return Vec::new();
    }
    pp.run_file(root, 0);
    pp.out
}

struct Preprocessor<'a> {
    sources: &'a mut SourceMap,
    loader: &'a dyn SourceLoader,
    diags: &'a mut Diagnostics,
    macros: FxHashMap<SmolStr, Macro>,
    /// First bytes of the names ever `#define`d (see `Expander::initials`).
    initials: [bool; 256],
    once: FxHashSet<String>,
    out: Vec<Token>,
    produced: usize,
    exhausted: bool,
    /// Bytes of source read so far, the root file's and every inclusion's.
    total: usize,
    /// Whether an include went past [`MAX_INCLUDE_DEPTH`]: a file that includes itself twice
    /// would otherwise be read 2^64 times, with an error at every leaf.
    too_deep: bool,
}

fn active(conds: &[Conditional]) -> bool {
    conds.last().is_none_or(|c| c.parent_active && c.taking)
}

impl Preprocessor<'_> {
    fn text(&self, t: Token) -> &str {
        self.sources.text(t.span)
    }

    /// Counts a file of `len` bytes read for `at` (the include directive, or the root file's
    /// start) and reports it if it crosses [`MAX_FILE_SIZE`] or [`MAX_TOTAL_SOURCE`].
    fn too_large(&mut self, name: &str, len: usize, at: Span) -> bool {
        // Past the total, the includes that follow are skipped without a report of their own.
        if self.total > MAX_TOTAL_SOURCE {
            return true;
        }
        self.total += len;
        let (message, help) = if len > MAX_FILE_SIZE {
            (
                format!("`{name}` is {len} bytes, over the limit of {MAX_FILE_SIZE} bytes per source file"),
                "split the file, or generate tables as textures instead of source",
            )
        } else if self.total > MAX_TOTAL_SOURCE {
            (
                format!(
                    "the source with its includes reaches {} bytes at `{name}`, over the limit of {MAX_TOTAL_SOURCE} bytes",
                    self.total
                ),
                "include each file once (`#pragma once`), or include fewer files",
            )
        } else {
            return false;
        };
        let label = if at.start == at.end && at.start == 0 { "in this file" } else { "included here" };
        self.diags.push(Diagnostic::error(Code::SourceTooLarge, message, at, label).with_help(help));
        true
    }

    fn expander(&mut self) -> Expander<'_> {
        Expander {
            macros: &self.macros,
            initials: &self.initials,
            sources: self.sources,
            diags: self.diags,
            produced: &mut self.produced,
            exhausted: &mut self.exhausted,
        }
    }

    fn run_file(&mut self, file: FileId, depth: usize) {
        let text = self.sources.file(file).text.clone();
        // Lexical errors wait until it is known which text the conditionals skip: C accepts any
        // characters there. They still come first among this file's diagnostics.
        let mut lexical = Diagnostics::default();
        let tokens = lex(file, &text, &mut lexical);
        let lexical_at = self.diags.len();
        let mut skipped: Vec<Range<u32>> = Vec::new();
        let mut skip_start: Option<u32> = None;
        let mut conds: Vec<Conditional> = Vec::new();
        // Text between directives is expanded straight from `tokens`; conditionals change what is
        // compiled only at directives.
        let mut run_start = Some(0);
        let mut i = 0;
        while i < tokens.len() {
            let t = tokens[i];
            if !(t.kind == TokenKind::Hash && t.line_start) {
                i += 1;
                continue;
            }
            let end = tokens[i + 1..].iter().position(|t| t.line_start).map_or(tokens.len(), |n| i + 1 + n);
            if let Some(start) = run_start.take() {
                self.flush(&tokens[start..i]);
            }
            let was_active = active(&conds);
            self.directive(t, &tokens[i + 1..end], &mut conds, file, depth);
            match (was_active, active(&conds)) {
                // Skipping starts after the directive's line and ends at the `#` of the directive
                // that resumes compiling.
                (true, false) => skip_start = Some(tokens[end - 1].span.end),
                (false, true) => skipped.extend(skip_start.take().map(|start| start..t.span.start)),
                _ => {}
            }
            if active(&conds) {
                run_start = Some(end);
            }
            i = end;
        }
        if let Some(start) = run_start {
            self.flush(&tokens[start..]);
        }
        skipped.extend(skip_start.map(|start| start..u32::MAX));
        // An unterminated comment is reported wherever it starts: it hides the rest of the file,
        // directives included, and C reports it in skipped text too.
        let comment_start =
            lexical.iter().find(|d| d.code == Code::UnterminatedComment).map(|d| d.primary_span().start);
        let lexical = lexical.into_iter().filter(|d| {
            d.code == Code::UnterminatedComment
                || !skipped.iter().any(|r| r.contains(&d.primary_span().start))
        });
        self.diags.insert(lexical_at, lexical);
        for c in conds.into_iter().rev() {
            let mut d = Diagnostic::error(
                Code::UnterminatedConditional,
                "unterminated conditional",
                c.opened,
                "this is never closed",
            );
            if comment_start.is_some_and(|start| start > c.opened.start) {
                d = d.with_note("the rest of the file is inside the unterminated comment, so an `#endif` there is not seen");
            }
            self.diags.push(d.with_help("add `#endif` before the end of the file"));
        }
    }

    fn flush(&mut self, run: &[Token]) {
        if run.is_empty() {
            return;
        }
        let mut out = std::mem::take(&mut self.out);
        self.expander().expand(run, &[], &mut out);
        self.out = out;
    }

    fn directive(
        &mut self,
        hash: Token,
        line: &[Token],
        conds: &mut Vec<Conditional>,
        file: FileId,
        depth: usize,
    ) {
        let Some(&name_tok) = line.first() else { return }; // `#` alone is the null directive
        let span = self.sources.join(hash.span, line.last().map_or(hash.span, |t| t.span));
        let name = self.text(name_tok).to_string();
        let rest = &line[1..];
        match name.as_str() {
            "if" => {
                let parent_active = active(conds);
                let taking = parent_active && self.condition(name_tok, rest);
                conds.push(Conditional { opened: span, else_seen: None, parent_active, taking, taken: taking });
            }
            "ifdef" | "ifndef" => {
                let parent_active = active(conds);
                let mut taking = false;
                if parent_active {
                    match self.macro_name(name_tok, rest, &name) {
                        Some(macro_name) => {
                            taking = self.macros.contains_key(self.text(macro_name)) == (name == "ifdef");
                            self.no_extra_tokens(&name, &rest[1..]);
                        }
                        None => taking = false,
                    }
                }
                conds.push(Conditional { opened: span, else_seen: None, parent_active, taking, taken: taking });
            }
            "elif" | "else" => {
                let Some(c) = conds.last() else {
                    self.unmatched(&name, span);
                    return;
                };
                if let Some(else_span) = c.else_seen {
                    self.diags.push(
                        Diagnostic::error(
                            Code::ConditionalAfterElse,
                            format!("`#{name}` after `#else`"),
                            span,
                            format!("this `#{name}` can never be reached"),
                        )
                        .with_label(else_span, "the `#else` is here"),
                    );
                    // Whatever follows it up to `#endif` is as unreachable as the directive.
                    conds.last_mut().expect("checked above").taking = false;
                    return;
                }
                let (parent_active, taken) = (c.parent_active, c.taken);
                let taking = if name == "else" {
                    self.no_extra_tokens(&name, rest);
                    parent_active && !taken
                } else {
                    parent_active && !taken && self.condition(name_tok, rest)
                };
                let c = conds.last_mut().expect("checked above");
                c.taking = taking;
                c.taken |= taking;
                if name == "else" {
                    c.else_seen = Some(span);
                }
            }
            "endif" => {
                if conds.pop().is_none() {
                    self.unmatched(&name, span);
                } else {
                    self.no_extra_tokens(&name, rest);
                }
            }
            _ if !active(conds) => {}
            "define" => self.define(name_tok, rest),
            "undef" => {
                if let Some(macro_name) = self.macro_name(name_tok, rest, &name) {
                    let key = self.text(macro_name).to_string();
                    self.macros.remove(key.as_str());
                    self.no_extra_tokens(&name, &rest[1..]);
                }
            }
            "include" => self.include(span, rest, file, depth),
            "pragma" => {
                if rest.first().is_some_and(|t| self.text(*t) == "once") {
                    let name = self.sources.file(file).name.clone();
                    self.once.insert(name);
                }
                // Other pragmas are for other compilers; C ignores unknown pragmas and so do we.
            }
            "error" | "warning" => {
                let message = match (rest.first(), rest.last()) {
                    (Some(first), Some(last)) => {
                        let whole = self.sources.join(first.span, last.span);
                        format!("#{name}: {}", self.sources.text(whole))
                    }
                    _ => format!("`#{name}` directive"),
                };
                let mut d = Diagnostic::error(Code::ErrorDirective, message, span, "");
                if name == "warning" {
                    d.severity = Severity::Warning;
                }
                self.diags.push(d);
            }
            _ => self.diags.push(
                Diagnostic::error(
                    Code::UnknownDirective,
                    format!("unknown directive `#{name}`"),
                    name_tok.span,
                    "not a preprocessor directive",
                )
                .with_help(
                    "the directives are #define #undef #include #if #ifdef #ifndef #elif #else #endif #error #warning #pragma",
                ),
            ),
        }
    }

    fn unmatched(&mut self, name: &str, span: Span) {
        self.diags.push(Diagnostic::error(
            Code::UnmatchedConditional,
            format!("`#{name}` without `#if`"),
            span,
            "no `#if`, `#ifdef` or `#ifndef` is open here",
        ));
    }

    fn no_extra_tokens(&mut self, name: &str, rest: &[Token]) {
        if let (Some(first), Some(last)) = (rest.first(), rest.last()) {
            let span = self.sources.join(first.span, last.span);
            self.diags.push(
                Diagnostic::warning(
                    Code::ExtraTokens,
                    format!("extra tokens after `#{name}`"),
                    span,
                    "these are ignored",
                )
                .with_help("write a comment with `//` or `/* */`"),
            );
        }
    }

    /// The identifier a `#define`, `#undef`, `#ifdef` or `#ifndef` names.
    fn macro_name(&mut self, directive: Token, rest: &[Token], name: &str) -> Option<Token> {
        match rest.first() {
            Some(t) if t.kind == TokenKind::Ident => Some(*t),
            Some(t) => {
                let found = t.kind.describe();
                self.diags.push(Diagnostic::error(
                    Code::MissingMacroName,
                    format!("expected a macro name after `#{name}`, found {found}"),
                    t.span,
                    "macro names are identifiers",
                ));
                None
            }
            None => {
                self.diags.push(Diagnostic::error(
                    Code::MissingMacroName,
                    format!("`#{name}` needs a macro name"),
                    directive.span,
                    "no name follows",
                ));
                None
            }
        }
    }

    /// Evaluates an `#if`/`#elif` operand; an invalid one is reported and counts as false.
    fn condition(&mut self, directive: Token, rest: &[Token]) -> bool {
        let end = rest.last().map_or(directive.span, |t| t.span).end_point();
        let mut resolved = Vec::with_capacity(rest.len());
        let mut i = 0;
        while i < rest.len() {
            let t = rest[i];
            if t.kind == TokenKind::Ident && self.text(t) == "defined" {
                let (operand, consumed) = match (rest.get(i + 1), rest.get(i + 2), rest.get(i + 3)) {
                    (Some(open), Some(name), Some(close))
                        if open.kind == TokenKind::LParen
                            && name.kind == TokenKind::Ident
                            && close.kind == TokenKind::RParen =>
                    {
                        (Some(*name), 4)
                    }
                    (Some(name), _, _) if name.kind == TokenKind::Ident => (Some(*name), 2),
                    _ => (None, 1),
                };
                let Some(operand) = operand else {
                    self.diags.push(Diagnostic::error(
                        Code::InvalidConditionExpr,
                        "`defined` needs a macro name",
                        t.span,
                        "write `defined NAME` or `defined(NAME)`",
                    ));
                    return false;
                };
                let is_defined = self.macros.contains_key(self.text(operand));
                let kind = if is_defined { TokenKind::True } else { TokenKind::False };
                resolved.push(Token { kind, ..t });
                i += consumed;
                continue;
            }
            resolved.push(t);
            i += 1;
        }
        let mut expanded = Vec::new();
        self.expander().expand(&resolved, &[], &mut expanded);
        match condition::evaluate(&expanded, self.sources, end) {
            Ok(value) => value != 0,
            Err(e) => {
                let code = Code::InvalidConditionExpr;
                let label = if rest.is_empty() { "no condition follows" } else { "" };
                let span = if rest.is_empty() { directive.span } else { e.span };
                self.diags.push(
                    Diagnostic::error(
                        code,
                        format!("invalid preprocessor condition: {}", e.message),
                        span,
                        label,
                    )
                    .with_note("conditions are integer constant expressions; undefined names count as 0"),
                );
                false
            }
        }
    }

    fn define(&mut self, directive: Token, rest: &[Token]) {
        let Some(name_tok) = self.macro_name(directive, rest, "define") else { return };
        let name = SmolStr::new(self.text(name_tok));
        let mut body_start = 1;
        let mut params = None;
        if let Some(open) = rest.get(1).filter(|t| t.kind == TokenKind::LParen && !t.space_before) {
            match self.macro_params(*open, &rest[2..]) {
                Some((list, consumed)) => {
                    params = Some(list);
                    body_start = 2 + consumed;
                }
                None => return,
            }
        }
        let body = rest[body_start..].to_vec();
        if let Some(list) = &params
            && !self.check_body(&body, list)
        {
            return;
        }
        if body.first().is_some_and(|t| t.kind == TokenKind::HashHash)
            || body.last().is_some_and(|t| t.kind == TokenKind::HashHash)
        {
            let at = if body[0].kind == TokenKind::HashHash { body[0] } else { body[body.len() - 1] };
            self.diags.push(Diagnostic::error(
                Code::InvalidPaste,
                "`##` cannot begin or end a macro body",
                at.span,
                "nothing to paste on this side",
            ));
            return;
        }
        let new = Macro { name_span: name_tok.span, params, body };
        if let Some(old) = self.macros.get(&name)
            && !self.same_definition(old, &new)
        {
            self.diags.push(
                Diagnostic::warning(
                    Code::MacroRedefined,
                    format!("macro `{name}` redefined"),
                    name_tok.span,
                    "the new definition differs",
                )
                .with_label(old.name_span, "the previous definition"),
            );
        }
        self.initials[usize::from(name.as_bytes()[0])] = true;
        self.macros.insert(name, new);
    }

    /// Parses `a, b, c)` after the `(` of a function-like macro; returns the names and how many
    /// tokens were used.
    fn macro_params(&mut self, open: Token, tokens: &[Token]) -> Option<(Vec<SmolStr>, usize)> {
        let mut params: Vec<SmolStr> = Vec::new();
        let mut spans: Vec<Span> = Vec::new();
        let mut i = 0;
        let malformed = |pp: &mut Self, span: Span, label: &str| {
            let mut d =
                Diagnostic::error(Code::MalformedMacroParams, "malformed macro parameter list", span, label);
            if span != open.span {
                d = d.with_label(open.span, "the parameter list starts here");
            }
            pp.diags.push(d.with_help("write `#define NAME(a, b) ...` with distinct identifiers"));
        };
        if tokens.first().is_some_and(|t| t.kind == TokenKind::RParen) {
            return Some((params, 1));
        }
        loop {
            match tokens.get(i) {
                Some(t) if t.kind == TokenKind::Ident => {
                    let name = SmolStr::new(self.text(*t));
                    if let Some(first) = params.iter().position(|p| *p == name) {
                        self.diags.push(
                            Diagnostic::error(
                                Code::MalformedMacroParams,
                                format!("duplicate macro parameter `{name}`"),
                                t.span,
                                "used again here",
                            )
                            .with_label(spans[first], "first used here"),
                        );
                        return None;
                    }
                    params.push(name);
                    spans.push(t.span);
                }
                Some(t) => {
                    malformed(self, t.span, "expected a parameter name");
                    return None;
                }
                None => {
                    malformed(self, open.span, "this parameter list is never closed");
                    return None;
                }
            }
            i += 1;
            match tokens.get(i) {
                Some(t) if t.kind == TokenKind::Comma => i += 1,
                Some(t) if t.kind == TokenKind::RParen => return Some((params, i + 1)),
                Some(t) => {
                    malformed(self, t.span, "expected `,` or `)`");
                    return None;
                }
                None => {
                    malformed(self, open.span, "this parameter list is never closed");
                    return None;
                }
            }
        }
    }

    /// Checks that every `#` in a function-like macro's body is followed by a parameter.
    fn check_body(&mut self, body: &[Token], params: &[SmolStr]) -> bool {
        for (i, t) in body.iter().enumerate() {
            if t.kind != TokenKind::Hash {
                continue;
            }
            let next = body.get(i + 1);
            if !next.is_some_and(|n| n.kind == TokenKind::Ident && params.iter().any(|p| p == self.text(*n)))
            {
                self.diags.push(Diagnostic::error(
                    Code::InvalidStringize,
                    "`#` must be followed by a macro parameter",
                    t.span,
                    "`#` turns a parameter into a string",
                ));
                return false;
            }
        }
        true
    }

    fn same_definition(&self, a: &Macro, b: &Macro) -> bool {
        a.params == b.params
            && a.body.len() == b.body.len()
            && a.body.iter().zip(&b.body).enumerate().all(|(i, (x, y))| {
                x.kind == y.kind
                    && self.text(*x) == self.text(*y)
                    && (i == 0 || x.space_before == y.space_before)
            })
    }

    fn include(&mut self, span: Span, rest: &[Token], file: FileId, depth: usize) {
        let (target, quoted) = match rest.first() {
            Some(t) if t.kind == TokenKind::StringLit => (unescape(self.text(*t)), true),
            Some(t) if t.kind == TokenKind::Lt => match rest.iter().position(|t| t.kind == TokenKind::Gt) {
                Some(close) if close > 1 => {
                    let inner = Span { start: t.span.end, end: rest[close].span.start, ..t.span };
                    (self.sources.text(inner).trim().to_string(), false)
                }
                _ => (String::new(), false),
            },
            _ => (String::new(), true),
        };
        if target.is_empty() {
            self.diags.push(
                Diagnostic::error(
                    Code::MalformedInclude,
                    "`#include` needs a file name",
                    span,
                    "no file named here",
                )
                .with_help("write `#include \"file.sl\"` or `#include <file.sl>`"),
            );
            return;
        }
        // Past the depth limit once, the includes that follow are skipped without a report.
        if self.too_deep {
            return;
        }
        if depth >= MAX_INCLUDE_DEPTH {
            self.too_deep = true;
            self.diags.push(
                Diagnostic::error(
                    Code::IncludeDepth,
                    format!("`#include` nested more than {MAX_INCLUDE_DEPTH} deep"),
                    span,
                    "included here",
                )
                .with_help("a file probably includes itself; guard it with `#pragma once` or `#ifndef`"),
            );
            return;
        }
        let includer = self.sources.file(file).name.clone();
        match self.loader.load(&target, quoted, &includer) {
            Ok(loaded) => {
                if self.once.contains(&loaded.name) || self.too_large(&loaded.name, loaded.text.len(), span) {
                    return;
                }
                if self.loader.read_as_latin1(&loaded.name) {
                    self.diags.push(loader::latin1_warning(&loaded.name, span));
                }
                let id = self.sources.add_file(loaded.name, loaded.text, Some(span));
                self.run_file(id, depth + 1);
            }
            Err(LoadError::NotFound { searched }) => self.diags.push(
                Diagnostic::error(
                    Code::IncludeNotFound,
                    format!("cannot find `{target}`"),
                    span,
                    "included here",
                )
                .with_note(format!("searched: {}", searched.join(", ")))
                .with_help("add the file's directory with `-I DIR`"),
            ),
            Err(LoadError::Unreadable { name, reason }) => self.diags.push(Diagnostic::error(
                Code::IncludeUnreadable,
                format!("cannot read `{name}`: {reason}"),
                span,
                "included here",
            )),
        }
    }
}
