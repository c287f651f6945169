//! Branches decided by folded values, and the code nobody reads once they are gone.

use rustc_hash::FxHashSet;

use super::Decision;
use super::fold::{Reads, Scalar, constant_in};
use crate::ir::stores::Stores;
use crate::ir::{Block, ExprId, ExprKind, LocalId, LocalKind, Place, Shader, Stmt};

/// Decides every `if`, loop condition and `?:` whose condition is now constant: because of a
/// fixed parameter (reported as a decision), or because an inlined function was called with
/// literal arguments (`hart_colormap(f, w, 1, ...)` testing its mode; not reported: it holds for
/// every binding). Returns the decisions and whether anything was decided at all.
pub(super) fn decide(shader: &mut Shader, reads: &Reads) -> (Vec<Decision>, bool) {
    let mut decisions = Vec::new();
    let mut changed = false;
    // `?:` first: a decided one becomes the side it takes (the expression keeps its id).
    for i in 0..shader.exprs.len() {
        if let ExprKind::Select(c, a, b) = shader.exprs[i].kind
            && let Some((taken, because)) = decided(shader, c, reads, &[], &|_| None)
        {
            let chosen = if taken { a } else { b };
            let kind = shader.expr(chosen).kind.clone();
            shader.exprs[i].kind = kind;
            changed = true;
            if !because.is_empty() {
                decisions.push(Decision::Branch { condition: shader.expr(c).span, taken, because });
            }
        }
    }
    let stores = crate::ir::stores::stores(shader);
    let body = std::mem::take(&mut shader.body);
    let mut pruner = Pruner { shader, reads, stores: &stores, decisions: &mut decisions, changed };
    let mut dominating = Vec::new();
    let body = pruner.block(body, &mut dominating);
    let changed = pruner.changed;
    shader.body = body;
    (decisions, changed)
}

/// A local's value known at a point: every path there stored it, and no other store exists.
/// `because` names the fixed parameters the value was computed from.
#[derive(Clone, Debug)]
struct Known {
    local: LocalId,
    value: Scalar,
    because: Vec<String>,
}

struct Pruner<'a> {
    shader: &'a Shader,
    reads: &'a Reads,
    /// The stores into each local, counted before any decision (a local stored once stays so).
    stores: &'a [Stores],
    decisions: &'a mut Vec<Decision>,
    /// Whether anything was decided or left out.
    changed: bool,
}

impl Pruner<'_> {
    /// The block with its decided statements replaced by the side they take. `dominating` holds
    /// the values of locals stored once, by a store that every statement from here on follows
    /// (an inlined function's parameters, called with a fixed parameter or a literal): a
    /// condition reading them inside the function is decided like one reading the parameter.
    /// Statements after a `return`, `break` or `continue` that always runs are gone (a decided
    /// `if` often leaves one).
    fn block(&mut self, stmts: Block, dominating: &mut Vec<Known>) -> Block {
        let shader = self.shader;
        let mut out = Vec::with_capacity(stmts.len());
        // The constant values just stored into whole locals, in straight-line code: what a `for`
        // loop's counter holds when its condition is first tested.
        let mut known: Vec<(LocalId, Scalar)> = Vec::new();
        for stmt in stmts {
            if leaves(&out) {
                self.changed = true;
                break;
            }
            if let Stmt::Store { place: Place::Local(l), value, .. } = &stmt {
                let dominated = |l: LocalId| dominating.iter().find(|k| k.local == l).map(|k| k.value);
                known.retain(|(k, _)| k != l);
                if let Some(v) = constant_in(shader, *value, &dominated) {
                    known.push((*l, v));
                    if self.stores[l.0 as usize].count == 1 {
                        let because = fixed_reads(shader, *value, self.reads, dominating);
                        dominating.push(Known { local: *l, value: v, because });
                    }
                }
                out.push(stmt);
                continue;
            }
            // A loop whose first test fails, given the counter's value stored just before it.
            let never_runs = match &stmt {
                Stmt::Loop { cond: Some(cond), .. } => {
                    let first = |l: LocalId| {
                        known
                            .iter()
                            .find(|(k, _)| *k == l)
                            .map(|(_, v)| *v)
                            .or_else(|| dominating.iter().find(|k| k.local == l).map(|k| k.value))
                    };
                    decided(shader, *cond, self.reads, dominating, &first)
                        .filter(|(runs, _)| !runs)
                        .map(|(_, because)| because)
                }
                _ => None,
            };
            known.clear();
            let dominated = |l: LocalId| dominating.iter().find(|k| k.local == l).map(|k| k.value);
            match stmt {
                Stmt::If { cond, then, otherwise } => {
                    match decided(shader, cond, self.reads, dominating, &dominated) {
                        Some((taken, because)) => {
                            self.changed = true;
                            if !because.is_empty() {
                                self.decisions.push(Decision::Branch {
                                    condition: shader.expr(cond).span,
                                    taken,
                                    because,
                                });
                            }
                            let kept = if taken { then } else { otherwise };
                            // The side taken runs wherever the `if` stood: what it stores once
                            // is known after it too.
                            out.extend(self.block(kept, dominating));
                        }
                        _ => out.push(Stmt::If {
                            cond,
                            then: self.nested(then, dominating),
                            otherwise: self.nested(otherwise, dominating),
                        }),
                    }
                }
                Stmt::Loop { cond: Some(cond), .. } if never_runs.is_some() => {
                    let because = never_runs.unwrap_or_default();
                    self.changed = true;
                    if !because.is_empty() {
                        self.decisions.push(Decision::Loop { condition: shader.expr(cond).span, because });
                    }
                }
                Stmt::Loop { cond, body, step, span } => out.push(Stmt::Loop {
                    cond,
                    body: self.nested(body, dominating),
                    step: self.nested(step, dominating),
                    span,
                }),
                Stmt::Inline { function, body, span } => {
                    // An inlined body runs where the call stands; its `return` leaves only it.
                    let body = self.nested(body, dominating);
                    out.push(Stmt::Inline { function, body, span })
                }
                Stmt::Illuminance { args, body } => {
                    out.push(Stmt::Illuminance { args, body: self.nested(body, dominating) })
                }
                Stmt::Emit { solar, args, body } => {
                    out.push(Stmt::Emit { solar, args, body: self.nested(body, dominating) })
                }
                other => out.push(other),
            }
        }
        out
    }

    /// A block that may not run, or may run again: what it learns stays inside it.
    fn nested(&mut self, stmts: Block, dominating: &[Known]) -> Block {
        let mut inner = dominating.to_vec();
        self.block(stmts, &mut inner)
    }
}

/// Whether a block ends in a jump that always runs: a `return`, `break` or `continue` at its top
/// level (nothing after it in the block can run).
fn leaves(block: &[Stmt]) -> bool {
    matches!(block.last(), Some(Stmt::Return | Stmt::Break(_) | Stmt::Continue(_)))
}

/// Condition `cond`'s value and the fixed parameters that decide it (directly or through the
/// `dominating` locals; none for a condition of literals), when it is constant with the locals
/// `known` gives.
fn decided(
    shader: &Shader,
    cond: ExprId,
    reads: &Reads,
    dominating: &[Known],
    known: &dyn Fn(LocalId) -> Option<Scalar>,
) -> Option<(bool, Vec<String>)> {
    let Some(Scalar::Bool(value)) = constant_in(shader, cond, known) else { return None };
    Some((value, fixed_reads(shader, cond, reads, dominating)))
}

/// The fixed parameters expression `id` reads, sorted, each once: directly, or through a local
/// whose known value was computed from them.
fn fixed_reads(shader: &Shader, id: ExprId, reads: &Reads, dominating: &[Known]) -> Vec<String> {
    let mut names = Vec::new();
    let mut stack = vec![id];
    while let Some(e) = stack.pop() {
        if let Some(name) = reads.get(&e) {
            names.push(name.clone());
        }
        if let ExprKind::Local(l) = shader.expr(e).kind
            && let Some(k) = dominating.iter().find(|k| k.local == l)
        {
            names.extend(k.because.iter().cloned());
        }
        shader.expr(e).kind.for_each_operand(|o| stack.push(o));
    }
    names.sort();
    names.dedup();
    names
}

/// Removes the stores into variables that nothing reads (after the decisions above, the
/// variables only the removed branches read). The result and predefined variables are always
/// read; so are the parameters, whose values the host reports, except the `unconsumed` outputs.
pub(super) fn dead_stores(shader: &mut Shader, unconsumed: &[String]) -> Vec<Decision> {
    let live = live_locals(shader, unconsumed);
    let mut removed: FxHashSet<LocalId> = FxHashSet::default();
    let body = std::mem::take(&mut shader.body);
    shader.body = sweep(body, &live, &mut removed);
    let mut ids: Vec<LocalId> = removed.into_iter().collect();
    ids.sort_by_key(|l| l.0);
    // The compiler's own temporaries (a discarded `x++`'s old value) go unreported.
    ids.into_iter()
        .filter(|l| matches!(shader.local(*l).kind, LocalKind::Var))
        .filter(|l| !unconsumed.iter().any(|u| u == shader.local(*l).name.as_str()))
        .map(|l| Decision::DeadVariable {
            name: shader.local(l).name.to_string(),
            declared: shader.local(l).span,
        })
        .collect()
}

/// The locals whose value something reads, directly or through locals that are read.
fn live_locals(shader: &Shader, unconsumed: &[String]) -> FxHashSet<LocalId> {
    let mut live: FxHashSet<LocalId> = FxHashSet::default();
    for (i, l) in shader.locals.iter().enumerate() {
        let param =
            matches!(l.kind, LocalKind::Param { .. }) && !unconsumed.iter().any(|u| u == l.name.as_str());
        if param || shader.result_local == Some(LocalId(i as u32)) {
            live.insert(LocalId(i as u32));
        }
    }
    // Reads that do not depend on what is stored: conditions, evaluations, stores into
    // predefined variables, indices, defaults. Then, until nothing changes, the values stored
    // into live locals.
    let mut roots: Vec<ExprId> = Vec::new();
    let mut stores: Vec<(LocalId, ExprId, Vec<ExprId>)> = Vec::new();
    collect(&shader.body, &mut roots, &mut stores);
    for l in &shader.locals {
        if let LocalKind::Param { default: Some(d), .. } = l.kind {
            roots.push(d);
        }
    }
    let mut seen: FxHashSet<ExprId> = FxHashSet::default();
    let mut pending = roots;
    loop {
        while let Some(e) = pending.pop() {
            if !seen.insert(e) {
                continue;
            }
            if let ExprKind::Local(l) = shader.expr(e).kind {
                live.insert(l);
            }
            shader.expr(e).kind.for_each_operand(|o| pending.push(o));
        }
        let before = pending.len();
        for (l, value, indices) in &stores {
            if live.contains(l) {
                pending.extend(
                    std::iter::once(*value).chain(indices.iter().copied()).filter(|e| !seen.contains(e)),
                );
            }
        }
        if pending.len() == before {
            return live;
        }
    }
}

/// Every expression read regardless of liveness, and every store into a local (its root, the
/// value and the index expressions of its place).
fn collect(block: &Block, roots: &mut Vec<ExprId>, stores: &mut Vec<(LocalId, ExprId, Vec<ExprId>)>) {
    for stmt in block {
        match stmt {
            Stmt::Store { place, value, .. } => {
                let mut indices = Vec::new();
                let mut at = place;
                while let Place::Index(inner, index) = at {
                    indices.push(*index);
                    at = inner;
                }
                match at {
                    Place::Local(l) => stores.push((*l, *value, indices)),
                    _ => {
                        roots.push(*value);
                        roots.extend(indices);
                    }
                }
            }
            Stmt::Eval(e) => roots.push(*e),
            Stmt::If { cond, .. } => roots.push(*cond),
            Stmt::Loop { cond, .. } => roots.extend(cond.iter().copied()),
            Stmt::Illuminance { args, .. } | Stmt::Emit { args, .. } => roots.extend(args.iter().copied()),
            Stmt::Inline { .. } | Stmt::Lights { .. } | Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => {
            }
        }
        stmt.for_each_block(|b| collect(b, roots, stores));
    }
}

/// The block without stores into dead locals (recording which ones lost stores).
fn sweep(stmts: Block, live: &FxHashSet<LocalId>, removed: &mut FxHashSet<LocalId>) -> Block {
    stmts
        .into_iter()
        .filter_map(|stmt| match stmt {
            Stmt::Store { ref place, .. } => match place.root_local() {
                Some(l) if !live.contains(&l) => {
                    removed.insert(l);
                    None
                }
                _ => Some(stmt),
            },
            Stmt::If { cond, then, otherwise } => Some(Stmt::If {
                cond,
                then: sweep(then, live, removed),
                otherwise: sweep(otherwise, live, removed),
            }),
            Stmt::Loop { cond, body, step, span } => Some(Stmt::Loop {
                cond,
                body: sweep(body, live, removed),
                step: sweep(step, live, removed),
                span,
            }),
            Stmt::Inline { function, body, span } => {
                Some(Stmt::Inline { function, body: sweep(body, live, removed), span })
            }
            Stmt::Illuminance { args, body } => {
                Some(Stmt::Illuminance { args, body: sweep(body, live, removed) })
            }
            Stmt::Emit { solar, args, body } => {
                Some(Stmt::Emit { solar, args, body: sweep(body, live, removed) })
            }
            other => Some(other),
        })
        .collect()
}
