//! Strings: known when the shader is compiled, so `concat` and `match` are folded here and
//! never reach the GPU. `match` uses the matcher the interpreter uses too (`backend::pattern`),
//! so the two backends cannot disagree on a pattern.

use crate::ir::builtin::BuiltinId;
use smol_str::SmolStr;

use super::body::{Translator, Value};
use crate::backend::pattern;
use crate::diag::{Code, Diagnostic};
use crate::ir::{ExprId, ExprKind};
use crate::source::Span;

impl Translator<'_> {
    /// The string a string-typed expression denotes: a literal, a string parameter (bound or its
    /// default), or a `concat` of such.
    pub(super) fn fold_string(&self, id: ExprId) -> Option<SmolStr> {
        if let ExprKind::Builtin(b, args) = &self.shader.expr(id).kind
            && b.id == BuiltinId::Concat
        {
            let mut s = String::new();
            for a in args {
                s.push_str(&self.fold_string(*a)?);
            }
            return Some(s.into());
        }
        self.string_value(id)
    }

    /// `match(pattern, subject)`: 1 or 0, decided now.
    pub(super) fn pattern_match(&mut self, args: &[ExprId], span: Span) -> Result<Value, Diagnostic> {
        let (Some(pattern), Some(subject)) = (self.fold_string(args[0]), self.fold_string(args[1])) else {
            return Err(Diagnostic::error(
                Code::NotExecutable,
                "`match` needs strings known when the shader is compiled",
                span,
                "this call",
            ));
        };
        match pattern::search(&pattern, &subject) {
            Ok(found) => Ok(self.float(if found { 1.0 } else { 0.0 })),
            Err(why) => Err(Diagnostic::error(
                Code::NotExecutable,
                format!("the pattern \"{pattern}\" cannot be matched"),
                span,
                "this pattern",
            )
            .with_note(why)),
        }
    }
}
