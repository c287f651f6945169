//! The built-ins both backends compute as one operation per component, in one table that pairs
//! the interpreter's instruction with WGSL's math function, so that the two definitions sit side
//! by side and a new one cannot be given to one backend only. Both are exact or within WGSL's
//! accuracy rules for the function (docs/numerics.md); the conformance suite checks each pair.
//!
//! Everything else a backend computes differently on purpose: a fixed order of operations where
//! WGSL leaves one open (`dot`, `length`, matrix products, `smoothstep`), a defined result where
//! WGSL's is not (`pow` of a negative base, `mod`, `sign`), and what depends on how each backend
//! stores values (spaces, textures, messages between shaders).

use naga::MathFunction as M;

use crate::backend::cpu::code::{Binary, Unary};
use crate::diag::{Code, Diagnostic};
use crate::ir::builtin::BuiltinId as B;
use crate::source::Span;

/// One operation per component, on each backend.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum CoreOp {
    /// `f(x)`.
    Unary {
        /// The interpreter's instruction.
        cpu: Unary,
        /// WGSL's function.
        wgsl: M,
    },
    /// `f(x, y)`.
    Binary {
        /// The interpreter's instruction.
        cpu: Binary,
        /// WGSL's function.
        wgsl: M,
    },
}

/// The core operation a call of the built-in `id` on `arguments` float arguments is, if any.
pub(crate) fn core_op(id: B, arguments: usize) -> Option<CoreOp> {
    let unary = |cpu, wgsl| Some(CoreOp::Unary { cpu, wgsl });
    match (id, arguments) {
        (B::Sin, 1) => unary(Unary::Sin, M::Sin),
        (B::Cos, 1) => unary(Unary::Cos, M::Cos),
        (B::Tan, 1) => unary(Unary::Tan, M::Tan),
        (B::Asin, 1) => unary(Unary::Asin, M::Asin),
        (B::Acos, 1) => unary(Unary::Acos, M::Acos),
        (B::Atan, 1) => unary(Unary::Atan, M::Atan),
        (B::Atan, 2) => Some(CoreOp::Binary { cpu: Binary::Atan2, wgsl: M::Atan2 }),
        (B::Exp, 1) => unary(Unary::Exp, M::Exp),
        (B::Sqrt, 1) => unary(Unary::Sqrt, M::Sqrt),
        (B::Log, 1) => unary(Unary::Log, M::Log),
        (B::Abs, 1) => unary(Unary::Abs, M::Abs),
        (B::Floor, 1) => unary(Unary::Floor, M::Floor),
        (B::Ceil, 1) => unary(Unary::Ceil, M::Ceil),
        (B::Round, 1) => unary(Unary::Round, M::Round),
        _ => None,
    }
}

/// The internal error of a backend that dispatched a call of `id` to this table without an entry.
pub(crate) fn not_core(id: B, span: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Internal,
        format!("`{id}` with these arguments is not a core operation"),
        span,
        "this call",
    )
    .with_note("backend::ops::core_op lists the core operations")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::types::Type;

    #[test]
    fn every_core_op_is_an_overload_on_floats() {
        // A table entry for an arity the built-in does not have would never be used.
        for &id in B::ALL {
            for n in 1..=2 {
                if core_op(id, n).is_some() {
                    let floats = vec![Type::FLOAT; n];
                    assert!(crate::sema::builtins::find(id, &floats).is_some(), "`{id}` on {n} floats");
                }
            }
        }
    }
}
