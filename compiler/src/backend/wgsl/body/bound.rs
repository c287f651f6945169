//! The iteration bound of GPU loops: a shader must not hang the device, and a GPU cannot report
//! an error, so every loop whose trip count is not known at compile time counts its iterations
//! and is left after [`MAX_LOOP_ITERATIONS`] of them (docs/limits.md).

use crate::backend::MAX_LOOP_ITERATIONS;
use crate::ir::stores::Stores;
use crate::ir::types::Base;
use crate::ir::{BinaryOp, Block, ExprId, ExprKind, Literal, Place, Shader, Stmt};

/// The number of iterations of a counting loop known at compile time: `before` (the statement
/// before the loop) stores a literal into a scalar `int` or `float` counter, the condition compares
/// the counter with a literal, the step adds a literal to it (or subtracts one), and nothing else
/// in the shader stores into it (`stores` are the shader's stores per local). The count is found by
/// running the counter in the interpreter's arithmetic (f32 or i32), up to [`MAX_LOOP_ITERATIONS`].
pub(crate) fn constant_trip_count(
    shader: &Shader,
    stores: &[Stores],
    before: Option<&Stmt>,
    cond: Option<ExprId>,
    step: &Block,
) -> Option<u64> {
    let Some(Stmt::Store { place: Place::Local(counter), value: init, .. }) = before else { return None };
    let local = shader.local(*counter);
    if local.ty.array.is_some() || !matches!(local.ty.base, Base::Int | Base::Float) {
        return None;
    }
    if stores[counter.0 as usize].count != 2 {
        return None;
    }
    let [Stmt::Store { place: Place::Local(stepped), value: next, .. }] = step.as_slice() else {
        return None;
    };
    if stepped != counter {
        return None;
    }
    let ExprKind::Binary(step_op @ (BinaryOp::Add | BinaryOp::Sub), a, delta) = shader.expr(*next).kind
    else {
        return None;
    };
    if !is_local(shader, a, *counter) {
        return None;
    }
    let ExprKind::Binary(compare, a, limit) = shader.expr(cond?).kind else { return None };
    if !is_local(shader, a, *counter) {
        return None;
    }
    let (start, delta, limit) = (literal(shader, *init)?, literal(shader, delta)?, literal(shader, limit)?);
    let holds = |x: f64| match compare {
        BinaryOp::Lt => x < limit,
        BinaryOp::Le => x <= limit,
        BinaryOp::Gt => x > limit,
        BinaryOp::Ge => x >= limit,
        BinaryOp::Ne => x != limit,
        _ => true,
    };
    if !matches!(compare, BinaryOp::Lt | BinaryOp::Le | BinaryOp::Gt | BinaryOp::Ge | BinaryOp::Ne) {
        return None;
    }
    let delta = if step_op == BinaryOp::Sub { -delta } else { delta };
    let int = local.ty.base == Base::Int;
    // The counter as the interpreter holds it: i32 arithmetic wraps, f32 arithmetic rounds.
    let advance = |x: f64| {
        if int { (x as i32).wrapping_add(delta as i32) as f64 } else { (x as f32 + delta as f32) as f64 }
    };
    let mut x = if int { start as i32 as f64 } else { start as f32 as f64 };
    let mut count = 0;
    while holds(x) {
        count += 1;
        if count > MAX_LOOP_ITERATIONS {
            return None;
        }
        x = advance(x);
    }
    Some(count)
}

fn is_local(shader: &Shader, e: ExprId, local: crate::ir::LocalId) -> bool {
    matches!(shader.expr(e).kind, ExprKind::Local(l) if l == local)
}

/// The value of a numeric literal, or of a literal converted to the counter's type.
fn literal(shader: &Shader, e: ExprId) -> Option<f64> {
    match &shader.expr(e).kind {
        ExprKind::Literal(Literal::Float(x)) => Some(*x),
        ExprKind::Literal(Literal::Int(x)) => Some(*x as f64),
        ExprKind::Convert(inner) if shader.expr(e).ty.array.is_none() => match shader.expr(*inner).kind {
            ExprKind::Literal(Literal::Int(x)) => Some(x as f64),
            ExprKind::Literal(Literal::Float(x)) => Some(x),
            _ => None,
        },
        _ => None,
    }
}
