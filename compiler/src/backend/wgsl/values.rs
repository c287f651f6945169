//! Locals that are values: a variable stored once, whose every read comes after that store in
//! the same naga function and in a block the store's block encloses, is the stored expression
//! itself (a WGSL `let`), not a private variable.
//!
//! An inlined call's naga function takes the values its body's leading parameter stores would
//! store as arguments ([`arguments`]), and gives the value its last statement stores as its
//! result ([`call_result`]), so that neither crosses the call in a private variable.
//!
//! Why: every other local lives in a private module variable, and Mesa's NIR passes (lavapipe)
//! cost about the number of variables times the code's size: `noise_panel`'s 4,380 private
//! variables made 70% of its 5-second pipeline creation (runtime/benches/pipelines.rs). The
//! values are the same either way (the store's expression is what a load would read), so the
//! arithmetic, and the bits, do not change.

use rustc_hash::{FxHashMap, FxHashSet};

use crate::ir::stores::Stores;
use crate::ir::types::Base;
use crate::ir::{Block, ExprId, ExprKind, LocalId, LocalKind, Place, Shader, Stmt};

/// How many leading statements of an inlined call's `body` store its parameters: whole stores
/// of locals of number, vector or matrix type whose values read none of the locals stored
/// before them. The call's naga function takes these values as arguments, computed by the caller.
pub(crate) fn arguments(shader: &Shader, body: &[Stmt]) -> usize {
    let mut stored = Vec::new();
    for stmt in body {
        let Stmt::Store { place: Place::Local(l), value, .. } = stmt else { break };
        let local = shader.local(*l);
        let mut reads = FxHashSet::default();
        shader.add_reads(*value, &mut reads);
        if local.function.is_none()
            || local.ty.array.is_some()
            || matches!(local.ty.base, Base::String | Base::Texref)
            || stored.iter().any(|l| reads.contains(l))
        {
            break;
        }
        stored.push(*l);
    }
    stored.len()
}

/// The local an inlined call's `body` gives back: the one of `values` its last statement before
/// any trailing `return` stores, when no `return` comes earlier (an earlier one would leave
/// without it). The call's naga function returns that value.
pub(crate) fn call_result(body: &[Stmt], values: &FxHashSet<LocalId>) -> Option<LocalId> {
    let end = body.iter().rposition(|s| !matches!(s, Stmt::Return))?;
    let Stmt::Store { place: Place::Local(r), .. } = &body[end] else { return None };
    (values.contains(r) && !body[..end].iter().any(returns)).then_some(*r)
}

/// Whether a statement may `return` from the function it is in (not from a call inside it).
fn returns(stmt: &Stmt) -> bool {
    match stmt {
        Stmt::Return => true,
        Stmt::Inline { .. } => false,
        _ => {
            let mut found = false;
            stmt.for_each_block(|b| found = found || b.iter().any(returns));
            found
        }
    }
}

/// Where a statement is: the block it is in (numbered in walk order), its index there, and
/// whether that block is an inlined call's body (a naga function of its own).
#[derive(Clone, Copy, PartialEq, Eq)]
struct Step {
    block: u32,
    index: u32,
    inline: bool,
}

/// The locals of `shader` that can be values (see the module's comment); `tables` are kept as
/// the module variables `tables` makes them.
pub(crate) fn find<T>(
    shader: &Shader,
    stores: &[Stores],
    tables: &FxHashMap<LocalId, T>,
) -> FxHashSet<LocalId> {
    // A built-in's `output` argument is written by the call wherever the call is (`surface()` in
    // a condition, not only in an `Eval` statement, which is all `stores` counts).
    let written_by_calls: FxHashSet<LocalId> = shader
        .exprs
        .iter()
        .filter_map(|e| match &e.kind {
            ExprKind::Builtin(b, args) => Some(b.params.iter().zip(args).filter(|(p, _)| p.output)),
            _ => None,
        })
        .flatten()
        .filter_map(|(_, a)| match shader.expr(*a).kind {
            ExprKind::Local(l) => Some(l),
            _ => None,
        })
        .collect();
    let candidate = |l: LocalId| {
        let local = shader.local(l);
        let s = stores[l.0 as usize];
        matches!(local.kind, LocalKind::Var | LocalKind::Temp)
            && shader.result_local != Some(l)
            && !tables.contains_key(&l)
            && !written_by_calls.contains(&l)
            && !local.rate.perlight
            && local.ty.array.is_none()
            && !matches!(local.ty.base, Base::String | Base::Texref)
            && s.count == 1
            && s.whole.is_some()
    };
    let mut walk = Walk {
        shader,
        serial: 0,
        path: Vec::new(),
        store_at: FxHashMap::default(),
        results: FxHashSet::default(),
        candidates: (0..shader.locals.len() as u32).map(LocalId).filter(|l| candidate(*l)).collect(),
        refused: FxHashSet::default(),
        seen: FxHashSet::default(),
    };
    walk.block(&shader.body, false, 0, Pass::Stores);
    walk.serial = 0;
    walk.block(&shader.body, false, 0, Pass::Reads);
    let Walk { candidates, refused, store_at, .. } = walk;
    candidates.into_iter().filter(|l| store_at.contains_key(l) && !refused.contains(l)).collect()
}

#[derive(Clone, Copy, PartialEq)]
enum Pass {
    /// Records where each candidate's store is.
    Stores,
    /// Refuses the candidates read where their store's value is not in scope.
    Reads,
}

struct Walk<'a> {
    shader: &'a Shader,
    serial: u32,
    path: Vec<Step>,
    store_at: FxHashMap<LocalId, Vec<Step>>,
    /// The calls' results: their store counts as made where the call is.
    results: FxHashSet<LocalId>,
    candidates: FxHashSet<LocalId>,
    refused: FxHashSet<LocalId>,
    /// The expressions already scanned in the current statement.
    seen: FxHashSet<ExprId>,
}

impl Walk<'_> {
    /// Walks `block`; `arguments` leading statements are an inlined call's parameter stores,
    /// whose values the caller computes (their reads were checked at the call).
    fn block(&mut self, block: &Block, inline: bool, arguments: usize, pass: Pass) {
        let serial = self.serial;
        self.serial += 1;
        for (i, stmt) in block.iter().enumerate() {
            self.path.push(Step { block: serial, index: i as u32, inline });
            // A parameter store's place counts (its value is the argument); its reads do not.
            if i >= arguments || pass == Pass::Stores {
                self.statement(stmt, pass);
            }
            self.path.pop();
        }
    }

    fn statement(&mut self, stmt: &Stmt, pass: Pass) {
        self.seen.clear();
        match (stmt, pass) {
            (Stmt::Inline { body, .. }, Pass::Stores) => {
                if let Some(r) = call_result(body, &self.candidates) {
                    self.results.insert(r);
                    self.store_at.insert(r, self.path.clone());
                }
            }
            (Stmt::Store { place: Place::Local(l), .. }, Pass::Stores)
                if self.candidates.contains(l) && !self.results.contains(l) =>
            {
                self.store_at.insert(*l, self.path.clone());
            }
            (_, Pass::Stores) => {}
            (Stmt::Store { place, value, .. }, Pass::Reads) => {
                let mut p = place;
                while let Place::Index(inner, index) = p {
                    self.reads(*index);
                    p = inner;
                }
                self.reads(*value);
            }
            (Stmt::Eval(id), Pass::Reads) => self.reads(*id),
            (Stmt::If { cond, .. }, Pass::Reads) => self.reads(*cond),
            (Stmt::Loop { cond, .. }, Pass::Reads) => {
                if let Some(c) = cond {
                    self.reads(*c);
                }
            }
            (Stmt::Illuminance { args, .. } | Stmt::Emit { args, .. }, Pass::Reads) => {
                for a in args {
                    self.reads(*a);
                }
            }
            (Stmt::Inline { body, .. }, Pass::Reads) => {
                for s in &body[..arguments(self.shader, body)] {
                    if let Stmt::Store { value, .. } = s {
                        self.reads(*value);
                    }
                }
            }
            (Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return | Stmt::Lights { .. }, Pass::Reads) => {}
        }
        match stmt {
            Stmt::Inline { body, .. } => {
                let n = arguments(self.shader, body);
                self.block(body, true, n, pass);
            }
            _ => stmt.for_each_block(|b| self.block(b, false, 0, pass)),
        }
    }

    /// Checks every local `id` reads against the place of its store.
    fn reads(&mut self, id: ExprId) {
        if !self.seen.insert(id) {
            return;
        }
        let e = self.shader.expr(id);
        if let ExprKind::Local(l) = e.kind
            && self.candidates.contains(&l)
            && !self.in_scope(l)
        {
            self.refused.insert(l);
        }
        e.kind.for_each_operand(|a| self.reads(a));
    }

    /// Whether local `l`'s stored value is in scope here: the store is an earlier statement of a
    /// block enclosing this one, with no inlined call's body in between.
    fn in_scope(&self, l: LocalId) -> bool {
        let Some(store) = self.store_at.get(&l) else { return false };
        let k = store.len() - 1;
        self.path.len() > k
            && self.path[..k] == store[..k]
            && self.path[k].block == store[k].block
            && self.path[k].index > store[k].index
            && !self.path[k + 1..].iter().any(|s| s.inline)
    }
}
