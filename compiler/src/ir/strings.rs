//! The value of a string expression when the shader is compiled: strings never reach a GPU, so
//! every string a program computes with must be known by then.

use smol_str::SmolStr;

use super::builtin::BuiltinId;
use super::{ExprId, ExprKind, Literal, LocalKind, Shader};

impl Shader {
    /// The string expression `id` denotes: a literal, a `string` parameter (its value in
    /// `strings`, by name, else its literal default), or a `concat` of such; `None` when it
    /// depends on anything else.
    pub fn string_value(&self, id: ExprId, strings: &[(String, String)]) -> Option<SmolStr> {
        match &self.expr(id).kind {
            ExprKind::Literal(Literal::String(s)) => Some(s.clone()),
            ExprKind::Builtin(b, args) if b.id == BuiltinId::Concat => {
                let mut s = String::new();
                for a in args {
                    s.push_str(&self.string_value(*a, strings)?);
                }
                Some(s.into())
            }
            ExprKind::Local(l) => {
                let local = self.local(*l);
                if let Some((_, v)) = strings.iter().find(|(n, _)| *n == local.name) {
                    return Some(SmolStr::new(v));
                }
                match local.kind {
                    LocalKind::Param { default: Some(d), .. } => self.string_value(d, strings),
                    _ => None,
                }
            }
            _ => None,
        }
    }
}
