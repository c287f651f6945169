//! Macro expansion: C's rescanning algorithm over a stack of token frames.
//!
//! A macro's replacement is pushed as a frame and rescanned; while that frame is live the macro is
//! disabled, which is how `#define X X + 1` stops after one step. Arguments are expanded on their own
//! first (except where `#` or `##` use them), as C specifies. Replacement tokens keep the span of
//! their spelling in the `#define`, tagged with a new expansion id whose call site is the macro's use;
//! argument tokens keep their own spans.

use rustc_hash::FxHashMap;
use smol_str::SmolStr;

use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::source::{Expansion, SourceMap, Span};
use crate::syntax::lexer::{Token, lex};
use crate::syntax::token::TokenKind;

/// Expansion stops with an error past this many nested replacements...
const MAX_DEPTH: usize = 200;
/// ...or past this many tokens produced by replacements in one compilation.
const MAX_PRODUCED: usize = 4_000_000;

/// A `#define`d macro.
#[derive(Debug, Clone)]
pub struct Macro {
    /// The macro's name in its `#define`.
    pub name_span: Span,
    /// The parameter names of a function-like macro; `None` for an object-like one.
    pub params: Option<Vec<SmolStr>>,
    /// The replacement list.
    pub body: Vec<Token>,
}

struct Frame {
    tokens: Vec<Token>,
    pos: usize,
    disabled: Option<SmolStr>,
}

/// Expands macros in token runs, reporting misuse.
pub struct Expander<'a> {
    pub(super) macros: &'a FxHashMap<SmolStr, Macro>,
    /// The first bytes of every macro name ever defined: a name starting otherwise is no macro,
    /// which saves hashing almost every identifier.
    pub(super) initials: &'a [bool; 256],
    pub(super) sources: &'a mut SourceMap,
    pub(super) diags: &'a mut Diagnostics,
    pub(super) produced: &'a mut usize,
    /// Set once [`MAX_PRODUCED`] has been reported; from then on nothing is expanded.
    pub(super) exhausted: &'a mut bool,
}

/// What a use of a macro turns into.
enum Replacement {
    /// These tokens, to be rescanned.
    Tokens(Vec<Token>),
    /// The macro's name as a plain identifier: the use was malformed and has been reported, and a
    /// name keeps the surrounding expression well-formed.
    Name,
    /// Nothing: the use ran to the end of the input and has been reported.
    Nothing,
}

fn next(frames: &mut Vec<Frame>) -> Option<Token> {
    loop {
        let top = frames.last_mut()?;
        if let Some(&t) = top.tokens.get(top.pos) {
            top.pos += 1;
            return Some(t);
        }
        frames.pop();
    }
}

fn peek(frames: &[Frame]) -> Option<Token> {
    frames.iter().rev().find_map(|f| f.tokens.get(f.pos).copied())
}

impl Expander<'_> {
    fn text(&self, t: Token) -> &str {
        self.sources.text(t.span)
    }

    /// Expands `input`, appending the result to `out`. Macros named in `disabled` are not expanded
    /// (they are being expanded further out).
    pub fn expand(&mut self, input: &[Token], disabled: &[SmolStr], out: &mut Vec<Token>) {
        if self.macros.is_empty() || *self.exhausted {
            out.extend_from_slice(input);
            return;
        }
        // Most tokens name no macro: copy them straight through, and start the rescanning machinery
        // at the first one that does.
        let macros = self.macros;
        let first_use = input.iter().position(|t| {
            t.kind == TokenKind::Ident && {
                let name = self.sources.text(t.span);
                self.initials[usize::from(name.as_bytes()[0])] && macros.contains_key(name)
            }
        });
        let Some(first_use) = first_use else {
            out.extend_from_slice(input);
            return;
        };
        out.extend_from_slice(&input[..first_use]);
        let mut frames = vec![Frame { tokens: input[first_use..].to_vec(), pos: 0, disabled: None }];
        // The use of a macro written in `input` being expanded: where its output starts in `out`,
        // and its name.
        let mut call: Option<(usize, Token)> = None;
        while let Some(tok) = next(&mut frames) {
            if tok.kind == TokenKind::Ident
                && let Some((name, mac)) = self.macros.get_key_value(self.text(tok))
            {
                let live =
                    !disabled.contains(name) && !frames.iter().any(|f| f.disabled.as_ref() == Some(name));
                if live
                    && (mac.params.is_none() || peek(&frames).is_some_and(|t| t.kind == TokenKind::LParen))
                {
                    if frames.len() == 1 {
                        call = Some((out.len(), tok));
                    }
                    let too_large = *self.produced > MAX_PRODUCED;
                    if frames.len() > MAX_DEPTH || too_large {
                        // The whole use written in `input` stands as its bare name; the text after
                        // it is kept (expanded as usual unless the token budget is spent).
                        let (start, outer) = call.take().unwrap_or((out.len(), tok));
                        if !*self.exhausted {
                            self.limit_reached(outer, tok);
                        }
                        *self.exhausted |= too_large;
                        out.truncate(start);
                        out.push(outer);
                        frames.truncate(1);
                        if too_large {
                            let rest = frames.pop().map(|f| f.tokens.into_iter().skip(f.pos));
                            out.extend(rest.into_iter().flatten());
                            return;
                        }
                        continue;
                    }
                    let mut outer: Vec<SmolStr> = disabled.to_vec();
                    outer.extend(frames.iter().filter_map(|f| f.disabled.clone()));
                    match self.replace(name, mac, tok, &mut frames, &outer) {
                        Replacement::Tokens(replacement) => {
                            *self.produced += replacement.len();
                            frames.push(Frame { tokens: replacement, pos: 0, disabled: Some(name.clone()) });
                        }
                        Replacement::Name => out.push(tok),
                        Replacement::Nothing => {}
                    }
                    continue;
                }
            }
            out.push(tok);
        }
    }

    /// Reports the expansion limit, reached at `tok` while expanding the use of `outer`.
    fn limit_reached(&mut self, outer: Token, tok: Token) {
        let name = self.text(outer).to_string();
        self.diags.push(
            Diagnostic::error(
                Code::ExpansionLimit,
                format!("macro expansion too deep or too large while expanding `{name}`"),
                tok.span,
                "expansion stopped here",
            )
            .with_note(format!("the limits are {MAX_DEPTH} nested expansions and {MAX_PRODUCED} tokens")),
        );
    }

    /// The replacement of one use of `mac`, whose name token `name_tok` was just read; for a
    /// function-like macro the arguments are read from `frames`.
    fn replace(
        &mut self,
        name: &SmolStr,
        mac: &Macro,
        name_tok: Token,
        frames: &mut Vec<Frame>,
        disabled: &[SmolStr],
    ) -> Replacement {
        let Some(params) = &mac.params else {
            let expn = self.sources.add_expansion(Expansion {
                name: name.clone(),
                definition: mac.name_span,
                call_site: name_tok.span,
            });
            return Replacement::Tokens(
                mac.body.iter().map(|t| Token { span: Span { expn, ..t.span }, ..*t }).collect(),
            );
        };
        let Some((args, close)) = self.read_arguments(name, name_tok, frames) else {
            return Replacement::Nothing;
        };
        let call_site = self.sources.join(name_tok.span, close.span);
        // `F()` passes one empty argument, which is right for a one-parameter macro and means
        // "no arguments" for a zero-parameter one.
        let args = if params.is_empty() && args.len() == 1 && args[0].is_empty() { Vec::new() } else { args };
        if args.len() != params.len() {
            let plural = |n: usize| if n == 1 { "" } else { "s" };
            self.diags.push(
                Diagnostic::error(
                    Code::MacroArity,
                    format!(
                        "macro `{name}` takes {} argument{} but {} {} given",
                        params.len(),
                        plural(params.len()),
                        args.len(),
                        if args.len() == 1 { "was" } else { "were" }
                    ),
                    call_site,
                    format!("{} argument{} here", args.len(), plural(args.len())),
                )
                .with_label(mac.name_span, format!("`{name}` is defined here with ({})", params.join(", "))),
            );
            return Replacement::Name;
        }
        let expn = self.sources.add_expansion(Expansion {
            name: name.clone(),
            definition: mac.name_span,
            call_site,
        });
        Replacement::Tokens(self.substitute(mac, params, &args, disabled, expn))
    }

    /// Reads `( arg, ... )` after a function-like macro's name, splitting at top-level commas.
    fn read_arguments(
        &mut self,
        name: &SmolStr,
        name_tok: Token,
        frames: &mut Vec<Frame>,
    ) -> Option<(Vec<Vec<Token>>, Token)> {
        next(frames); // the `(` that peek saw
        let mut args = vec![Vec::new()];
        let mut depth = 0usize;
        while let Some(t) = next(frames) {
            match t.kind {
                TokenKind::LParen | TokenKind::LBracket | TokenKind::LBrace => depth += 1,
                TokenKind::RParen if depth == 0 => return Some((args, t)),
                TokenKind::RParen | TokenKind::RBracket | TokenKind::RBrace => {
                    depth = depth.saturating_sub(1)
                }
                TokenKind::Comma if depth == 0 => {
                    args.push(Vec::new());
                    continue;
                }
                _ => {}
            }
            args.last_mut().expect("args starts non-empty").push(t);
        }
        self.diags.push(
            Diagnostic::error(
                Code::UnterminatedMacroCall,
                format!("unterminated call of macro `{name}`"),
                name_tok.span,
                "the argument list is never closed",
            )
            .with_help(
                "add the closing `)`; a macro call cannot run past a directive or the end of its file",
            ),
        );
        None
    }

    fn substitute(
        &mut self,
        mac: &Macro,
        params: &[SmolStr],
        args: &[Vec<Token>],
        disabled: &[SmolStr],
        expn: crate::source::ExpnId,
    ) -> Vec<Token> {
        let param_index = |this: &Self, t: Token| {
            (t.kind == TokenKind::Ident).then(|| params.iter().position(|p| p == this.text(t))).flatten()
        };
        let mut expanded: Vec<Option<Vec<Token>>> = vec![None; args.len()];
        let mut out: Vec<Token> = Vec::with_capacity(mac.body.len());
        let body = &mac.body;
        let mut i = 0;
        let mut paste_next = false;
        while i < body.len() {
            let t = body[i];
            let respelled = Token { span: Span { expn, ..t.span }, ..t };
            if t.kind == TokenKind::HashHash {
                paste_next = true;
                i += 1;
                continue;
            }
            let pieces: Vec<Token> = if t.kind == TokenKind::Hash && i + 1 < body.len() {
                // Checked at #define: `#` is always followed by a parameter.
                let index = param_index(self, body[i + 1]).unwrap_or(0);
                i += 1;
                vec![self.stringize(&args[index], respelled.span)]
            } else if let Some(index) = param_index(self, t) {
                let next_is_paste = body.get(i + 1).is_some_and(|n| n.kind == TokenKind::HashHash);
                if paste_next || next_is_paste {
                    args[index].clone()
                } else {
                    if expanded[index].is_none() {
                        let mut result = Vec::new();
                        self.expand(&args[index], disabled, &mut result);
                        expanded[index] = Some(result);
                    }
                    expanded[index].clone().unwrap_or_default()
                }
            } else {
                vec![respelled]
            };
            let mut pieces = pieces.into_iter();
            if paste_next {
                paste_next = false;
                if let Some(first) = pieces.next() {
                    match out.pop() {
                        Some(left) => {
                            let pasted = self.paste(left, first, expn);
                            out.extend(pasted);
                        }
                        None => out.push(first),
                    }
                }
            }
            out.extend(pieces);
            i += 1;
        }
        out
    }

    /// `#arg`: the argument's spelling as a string literal.
    fn stringize(&mut self, arg: &[Token], at: Span) -> Token {
        let mut text = String::from("\"");
        for (n, t) in arg.iter().enumerate() {
            if n > 0 && t.space_before {
                text.push(' ');
            }
            for c in self.text(*t).chars() {
                if c == '"' || c == '\\' {
                    text.push('\\');
                }
                text.push(c);
            }
        }
        text.push('"');
        let span = self.scratch(text, at);
        Token { kind: TokenKind::StringLit, span, line_start: false, space_before: true }
    }

    /// `left ## right`: one token spelled as both together, or both unchanged and an error.
    fn paste(&mut self, left: Token, right: Token, expn: crate::source::ExpnId) -> Vec<Token> {
        let joined = format!("{}{}", self.text(left), self.text(right));
        let span = self.scratch(joined.clone(), Span { expn, ..left.span });
        let mut relex = Diagnostics::default();
        let tokens: Vec<Token> = lex(span.file, &joined, &mut relex)
            .into_iter()
            .filter(|t| t.kind != TokenKind::Newline)
            .collect();
        if let [single] = tokens.as_slice()
            && relex.is_empty()
        {
            return vec![Token {
                span: Span { expn, ..single.span },
                space_before: left.space_before,
                ..*single
            }];
        }
        self.diags.push(Diagnostic::error(
            Code::InvalidPaste,
            format!("pasting `{}` and `{}` does not give a single token", self.text(left), self.text(right)),
            self.sources.call_site(Span { expn, ..left.span }),
            format!("`{joined}` is not one token"),
        ));
        vec![left, right]
    }

    /// Puts text made during expansion into a scratch file, so its tokens have a span like any other.
    fn scratch(&mut self, text: String, origin: Span) -> Span {
        let len = text.len();
        let file = self.sources.add_file("<macro expansion>", text, None);
        Span { file, start: 0, end: len as u32, expn: origin.expn }
    }
}
