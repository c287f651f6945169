//! Strings: known when the shader is compiled, so `concat` and `match` are folded here and
//! never reach the GPU. `match` uses the matcher the interpreter uses too (`backend::pattern`),
//! so the two backends cannot disagree on a pattern.

use smol_str::SmolStr;

use super::body::{Translator, Value};
use crate::backend::pattern;
use crate::diag::{Code, Diagnostic};
use crate::ir::ExprId;
use crate::source::Span;

impl Translator<'_> {
    /// The string a string-typed expression denotes (`Shader::string_value`, with the bound
    /// string parameters).
    pub(super) fn fold_string(&self, id: ExprId) -> Option<SmolStr> {
        self.shader.string_value(id, self.strings)
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
