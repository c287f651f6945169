//! What parameter defaults depend on. The semantic stage lowers the calls in a default (user
//! functions, the built-ins the library implements) into statements at the top of the body, ahead
//! of the shader's own, and leaves the default an expression that reads their results from
//! temporaries. Whoever evaluates a default (the interpreter, before the body) runs those
//! statements first, and the split keeps them in the host stage, which computes the defaults.

use rustc_hash::FxHashSet;

use super::{ExprId, LocalId, LocalKind, Shader, Stmt};

impl Shader {
    /// The locals the parameters' default expressions read.
    pub fn default_reads(&self) -> FxHashSet<LocalId> {
        let mut out = FxHashSet::default();
        for &p in &self.params {
            if let LocalKind::Param { default: Some(d), .. } = self.local(p).kind {
                self.add_reads(d, &mut out);
            }
        }
        out
    }

    /// The statements the default `value` needs run before it: the body's top-level statements
    /// that store a local it reads (not a parameter), transitively, in body order. They also stay
    /// in the body, where running them again computes the same temporaries.
    pub fn default_prelude(&self, value: ExprId) -> Vec<Stmt> {
        let mut needed = FxHashSet::default();
        self.add_reads(value, &mut needed);
        let mut taken = vec![false; self.body.len()];
        // A statement feeds an earlier one only through locals it stores: walk backwards.
        for (i, stmt) in self.body.iter().enumerate().rev() {
            let mut stored = FxHashSet::default();
            self.stmt_locals(stmt, &mut stored, &mut FxHashSet::default());
            if stored.iter().any(|l| needed.contains(l) && !self.params.contains(l)) {
                taken[i] = true;
                self.stmt_locals(stmt, &mut FxHashSet::default(), &mut needed);
            }
        }
        self.body.iter().zip(taken).filter(|(_, t)| *t).map(|(s, _)| s.clone()).collect()
    }

    /// Adds the locals `stmt` (with the blocks in it) stores to `stored` and those it reads to
    /// `read`.
    fn stmt_locals(&self, stmt: &Stmt, stored: &mut FxHashSet<LocalId>, read: &mut FxHashSet<LocalId>) {
        if let Stmt::Store { place, .. } = stmt {
            stored.extend(place.root_local());
        }
        stmt.for_each_root(|e| self.add_reads(e, read));
        stmt.for_each_block(|block| block.iter().for_each(|s| self.stmt_locals(s, stored, read)));
    }
}
