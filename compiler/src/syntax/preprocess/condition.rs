//! Evaluation of `#if` and `#elif` operands: C's integer constant expressions over `i64`.
//!
//! `defined` has already been replaced and macros expanded when this runs; any identifier left is
//! 0, as in C.

use crate::source::{SourceMap, Span};
use crate::syntax::lexer::Token;
use crate::syntax::token::{TokenKind, int_value};

/// Why an operand could not be evaluated, and where.
#[derive(Debug)]
pub struct ConditionError {
    /// The offending token (or the directive's end).
    pub span: Span,
    /// What went wrong.
    pub message: String,
}

struct Evaluator<'a> {
    tokens: &'a [Token],
    pos: usize,
    sources: &'a SourceMap,
    end: Span,
}

/// Evaluates a condition; `end` is where a missing operand is reported.
pub fn evaluate(tokens: &[Token], sources: &SourceMap, end: Span) -> Result<i64, ConditionError> {
    let mut e = Evaluator { tokens, pos: 0, sources, end };
    let value = e.conditional()?;
    if let Some(t) = e.peek() {
        return Err(e.error_at(t.span, format!("unexpected `{}` in condition", sources.text(t.span))));
    }
    Ok(value)
}

fn binary_precedence(kind: TokenKind) -> Option<u8> {
    use TokenKind::*;
    Some(match kind {
        OrOr => 1,
        AndAnd => 2,
        Pipe => 3,
        Caret => 4,
        Amp => 5,
        EqEq | Ne => 6,
        Lt | Gt | Le | Ge => 7,
        Shl | Shr => 8,
        Plus | Minus => 9,
        Star | Slash | Percent => 10,
        _ => return None,
    })
}

impl Evaluator<'_> {
    fn peek(&self) -> Option<Token> {
        self.tokens.get(self.pos).copied()
    }

    fn error_at(&self, span: Span, message: String) -> ConditionError {
        ConditionError { span, message }
    }

    fn conditional(&mut self) -> Result<i64, ConditionError> {
        let cond = self.binary(1)?;
        if self.peek().is_some_and(|t| t.kind == TokenKind::Question) {
            self.pos += 1;
            let then = self.conditional()?;
            match self.peek() {
                Some(t) if t.kind == TokenKind::Colon => self.pos += 1,
                Some(t) => return Err(self.error_at(t.span, "expected `:` in conditional expression".into())),
                None => return Err(self.error_at(self.end, "expected `:` in conditional expression".into())),
            }
            let otherwise = self.conditional()?;
            return Ok(if cond != 0 { then } else { otherwise });
        }
        Ok(cond)
    }

    fn binary(&mut self, min: u8) -> Result<i64, ConditionError> {
        let mut lhs = self.unary()?;
        while let Some(op) = self.peek() {
            let Some(prec) = binary_precedence(op.kind) else { break };
            if prec < min {
                break;
            }
            self.pos += 1;
            let rhs = self.binary(prec + 1)?;
            use TokenKind::*;
            lhs = match op.kind {
                OrOr => ((lhs != 0) || (rhs != 0)) as i64,
                AndAnd => ((lhs != 0) && (rhs != 0)) as i64,
                Pipe => lhs | rhs,
                Caret => lhs ^ rhs,
                Amp => lhs & rhs,
                EqEq => (lhs == rhs) as i64,
                Ne => (lhs != rhs) as i64,
                Lt => (lhs < rhs) as i64,
                Gt => (lhs > rhs) as i64,
                Le => (lhs <= rhs) as i64,
                Ge => (lhs >= rhs) as i64,
                Shl => lhs.wrapping_shl(rhs as u32),
                Shr => lhs.wrapping_shr(rhs as u32),
                Plus => lhs.wrapping_add(rhs),
                Minus => lhs.wrapping_sub(rhs),
                Star => lhs.wrapping_mul(rhs),
                Slash | Percent if rhs == 0 => {
                    return Err(self.error_at(op.span, "division by zero in condition".into()));
                }
                Slash => lhs.wrapping_div(rhs),
                Percent => lhs.wrapping_rem(rhs),
                _ => unreachable!("binary_precedence only admits binary operators"),
            };
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> Result<i64, ConditionError> {
        let Some(t) = self.peek() else {
            return Err(self.error_at(self.end, "expected a value in condition".into()));
        };
        self.pos += 1;
        let text = self.sources.text(t.span);
        match t.kind {
            TokenKind::Minus => Ok(self.unary()?.wrapping_neg()),
            TokenKind::Plus => self.unary(),
            TokenKind::Bang => Ok((self.unary()? == 0) as i64),
            TokenKind::Tilde => Ok(!self.unary()?),
            TokenKind::IntLit => int_value(text).ok_or_else(|| {
                self.error_at(t.span, format!("integer `{text}` is too large for a condition"))
            }),
            TokenKind::FloatLit => {
                Err(self.error_at(t.span, format!("`{text}` is a float; conditions take integers only")))
            }
            TokenKind::True => Ok(1),
            TokenKind::False => Ok(0),
            // An identifier that survived macro expansion is 0, as in C; so is a keyword.
            _ if t.kind == TokenKind::Ident || t.kind.is_keyword() => Ok(0),
            TokenKind::LParen => {
                let value = self.conditional()?;
                match self.peek() {
                    Some(close) if close.kind == TokenKind::RParen => {
                        self.pos += 1;
                        Ok(value)
                    }
                    _ => Err(self.error_at(t.span, "this `(` is not closed".into())),
                }
            }
            _ => Err(self.error_at(t.span, format!("unexpected `{text}` in condition"))),
        }
    }
}
