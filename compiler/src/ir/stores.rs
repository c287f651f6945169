//! Which statements store into each local: for the analyses that treat a variable written once,
//! by its declaration, as a value (constant tables in `sema::rates`, `backend::wgsl` and the
//! interpreter's uniform tables).

use super::{Block, ExprId, ExprKind, Place, Shader, Stmt};
use crate::source::Span;

/// What a shader's body stores into one local.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stores {
    /// The statements that store into it: whole, through an index, or as a built-in's output.
    pub count: u32,
    /// The last store of the whole variable: its value and the store's span.
    pub whole: Option<(ExprId, Span)>,
}

impl Stores {
    /// The value of the only store, when that store is the variable's declaration (its span
    /// covers the declared name `declared`).
    pub fn only_initialiser(&self, declared: Span) -> Option<ExprId> {
        let (value, span) = self.whole.filter(|_| self.count == 1)?;
        is_declaration(span, declared).then_some(value)
    }
}

/// Whether a store at `store` is the initialiser of the variable declared at `declared` (the
/// declarator's span covers the declared name; no other store's does).
pub fn is_declaration(store: Span, declared: Span) -> bool {
    store.file == declared.file && store.start <= declared.start && declared.end <= store.end
}

/// The stores into each local of `shader`, by local index.
pub fn stores(shader: &Shader) -> Vec<Stores> {
    let mut out = vec![Stores::default(); shader.locals.len()];
    walk(&shader.body, &mut out);
    // A built-in's output arguments are written wherever the call stands: in a statement of its
    // own or inside an expression (`float has = surface("tint", tint)`).
    for e in &shader.exprs {
        if let ExprKind::Builtin(b, args) = &e.kind {
            for (p, a) in b.params.iter().zip(args) {
                if let (true, ExprKind::Local(l)) = (p.output, &shader.expr(*a).kind) {
                    out[l.0 as usize].count += 1;
                }
            }
        }
    }
    out
}

fn walk(block: &Block, out: &mut [Stores]) {
    for stmt in block {
        if let Stmt::Store { place, value, span } = stmt
            && let Some(l) = place.root_local()
        {
            let entry = &mut out[l.0 as usize];
            entry.count += 1;
            if matches!(place, Place::Local(_)) {
                entry.whole = Some((*value, *span));
            }
        }
        stmt.for_each_block(|b| walk(b, out));
    }
}
