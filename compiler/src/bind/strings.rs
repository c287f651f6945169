//! String variables read where their value is known become that value: strings are compile-time
//! values, and the GPU backend resolves a string only through literals and parameters. A string
//! variable stored in straight-line code of the shader's body or of an inlined call in it (not in a
//! branch, a loop or a light construct) is known until the next statement that may store it; its
//! reads in between, nested ones included, are replaced by the stored value (`uniform string f =
//! concat(a, ".tex"); ... texture(f, s, t)` reads `concat(a, ".tex")`, and a function's string
//! parameter, such as a space name passed on, reads the caller's string).

use rustc_hash::{FxHashMap, FxHashSet};

use crate::ir::types::Base;
use crate::ir::{Block, ExprId, ExprKind, LocalId, Place, Shader, Stmt};

/// Replaces the reads of string variables whose value is known there (module documentation).
pub(super) fn propagate(shader: &mut Shader) {
    let outputs = super::fold::output_args(shader);
    let body = std::mem::take(&mut shader.body);
    let mut known = FxHashMap::default();
    walk(shader, &body, &mut known, &outputs, true);
    shader.body = body;
}

fn walk(
    shader: &mut Shader,
    block: &Block,
    known: &mut FxHashMap<LocalId, ExprId>,
    outputs: &FxHashSet<ExprId>,
    straight: bool,
) {
    for stmt in block {
        let whole_store = matches!(stmt, Stmt::Store { place: Place::Local(_), .. });
        if !(straight && whole_store) {
            // A loop may read a value stored later in it: forget whatever the statement stores.
            let mut stored = Vec::new();
            stored_in(shader, std::slice::from_ref(stmt), &mut stored);
            for l in stored {
                known.remove(&l);
            }
        }
        match stmt {
            Stmt::Store { place, value, .. } => {
                substitute_place(shader, place, known, outputs);
                substitute(shader, *value, known, outputs);
                if let Place::Local(l) = place {
                    let ty = shader.local(*l).ty;
                    if straight && ty.base == Base::String && !ty.is_array() {
                        known.insert(*l, *value);
                    } else {
                        known.remove(l);
                    }
                }
            }
            Stmt::Eval(e) => substitute(shader, *e, known, outputs),
            Stmt::If { cond, .. } => substitute(shader, *cond, known, outputs),
            Stmt::Loop { cond: Some(cond), .. } => substitute(shader, *cond, known, outputs),
            Stmt::Illuminance { args, .. } | Stmt::Emit { args, .. } => {
                for &a in args {
                    substitute(shader, a, known, outputs);
                }
            }
            _ => {}
        }
        match stmt {
            // An inlined call runs its body once, in order: straight-line code as much as the
            // code around it. A `Return` may leave it early, so what it stores is not known
            // after it.
            Stmt::Inline { body, .. } => {
                walk(shader, body, known, outputs, straight);
                if returns(body) {
                    let mut stored = Vec::new();
                    stored_in(shader, body, &mut stored);
                    for l in stored {
                        known.remove(&l);
                    }
                }
            }
            _ => stmt.for_each_block(|b| walk(shader, b, known, outputs, false)),
        }
    }
}

/// Whether `block` can leave an inlined call early (a `Return` of its own, not of a call
/// nested in it).
fn returns(block: &[Stmt]) -> bool {
    block.iter().any(|s| match s {
        Stmt::Return => true,
        Stmt::Inline { .. } => false,
        other => {
            let mut found = false;
            other.for_each_block(|b| found |= returns(b));
            found
        }
    })
}

/// The locals `block` stores into anywhere: whole, through an index, or as a built-in's output.
fn stored_in(shader: &Shader, block: &[Stmt], out: &mut Vec<LocalId>) {
    for stmt in block {
        match stmt {
            Stmt::Store { place, .. } => out.extend(place.root_local()),
            Stmt::Eval(id) => {
                if let ExprKind::Builtin(b, args) = &shader.expr(*id).kind {
                    for (k, a) in args.iter().enumerate() {
                        if b.param_type(k).is_some_and(|p| p.output)
                            && let ExprKind::Local(l) = shader.expr(*a).kind
                        {
                            out.push(l);
                        }
                    }
                }
            }
            _ => {}
        }
        stmt.for_each_block(|b| stored_in(shader, b, out));
    }
}

fn substitute_place(
    shader: &mut Shader,
    place: &Place,
    known: &FxHashMap<LocalId, ExprId>,
    outputs: &FxHashSet<ExprId>,
) {
    if let Place::Index(inner, index) = place {
        substitute(shader, *index, known, outputs);
        substitute_place(shader, inner, known, outputs);
    }
}

/// Replaces the reads of known string variables in the expression tree at `root`.
fn substitute(
    shader: &mut Shader,
    root: ExprId,
    known: &FxHashMap<LocalId, ExprId>,
    outputs: &FxHashSet<ExprId>,
) {
    if known.is_empty() {
        return;
    }
    let mut stack = vec![root];
    let mut seen = FxHashSet::default();
    while let Some(id) = stack.pop() {
        if !seen.insert(id) {
            continue;
        }
        if let ExprKind::Local(l) = shader.expr(id).kind {
            if let Some(&value) = known.get(&l)
                && !outputs.contains(&id)
            {
                let kind = shader.expr(value).kind.clone();
                shader.exprs[id.0 as usize].kind = kind;
            }
            continue;
        }
        shader.expr(id).kind.for_each_operand(|a| stack.push(a));
    }
}
