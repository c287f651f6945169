//! Calls that light loops repeat with the same per-light arguments, computed once per light.
//! RenderMan's `diffuse` and `specular` are two light sums that each normalize `L`, and plastic
//! calls both: left as written, every fragment normalizes each light's `L` twice, and the drivers
//! measured do not merge the two (docs/performance.md).
//!
//! A call (an inlined body inside a light loop) is *self-contained* when its value follows from
//! the visited light and the fragment alone: it runs no loop, light construct or effect (an
//! `Eval`, a built-in's output argument, a store into a predefined variable); every local it
//! reads it has stored itself first, on every path; the predefined variables it reads are ones
//! the shader never stores (`L`, `Cl`, and `P` where nothing moves it); the locals it stores are
//! stored nowhere else; and exactly one of them is read after it (its result). Two such calls are
//! the same when their bodies are the same statements over the same expressions, up to the names
//! of their own locals.
//!
//! Two or more of the same call are computed once: a light loop over every light any of them
//! visits runs the first of them and keeps its result in a per-light variable, just before the
//! top-level statement that holds that first call; each call becomes a store of the variable into
//! its result. The operations are the call's own, in its order, so each value has the same bits
//! as before on every backend, and running it for a light that a call would have skipped (under a
//! condition or a category) computes a value nothing reads.
//!
//! Calls are found inside the light loops made of `illuminance`. A Stanford shader's per-light
//! statements get a light loop each, inside the calls they make (`perlight float a = f(L)` is
//! `f`'s body with a loop around each of its statements), so its calls are not found here.

use rustc_hash::{FxHashMap, FxHashSet};

use crate::ir::types::Rate;
use crate::ir::{Block, ExprId, ExprKind, Local, LocalId, LocalKind, Place, Shader, Stmt};
use crate::opt::build::Builder;

/// Computes once per light the calls that the light loops of `shader` repeat (module
/// documentation).
pub fn share_calls(shader: &mut Shader) {
    let facts = Facts::of(shader);
    let mut calls = Vec::new();
    let mut ordinal = 0;
    for (top, stmt) in shader.body.iter().enumerate() {
        facts.find(shader, stmt, top, None, &mut ordinal, &mut calls);
    }
    let mut groups: Vec<Vec<&Call>> = Vec::new();
    for call in &calls {
        match groups.iter_mut().find(|g| Same::new(shader).stmt(&g[0].stmt, &call.stmt)) {
            Some(group) => group.push(call),
            None => groups.push(vec![call]),
        }
    }
    let mut hoisted: Vec<(usize, Stmt)> = Vec::new();
    let mut replaced: FxHashMap<u32, Stmt> = FxHashMap::default();
    for group in groups.iter().filter(|g| g.len() > 1) {
        let first = group[0];
        let mut lights: Vec<u32> = group.iter().flat_map(|c| c.lights.iter().copied()).collect();
        lights.sort_unstable();
        lights.dedup();
        let result = shader.local(first.result);
        let rate = group.iter().fold(result.rate, |r, c| r.join(shader.local(c.result).rate));
        let function = match &first.stmt {
            Stmt::Inline { function, .. } => function.clone(),
            _ => unreachable!("a call is an inlined body"),
        };
        let shared = LocalId(shader.locals.len() as u32);
        shader.locals.push(Local {
            name: format!("{function} per light").into(),
            ty: result.ty,
            rate: Rate { perlight: true, ..rate },
            declared: false,
            kind: LocalKind::Temp,
            span: first.span,
            function: None,
        });
        let ty = shader.local(shared).ty;
        let mut b = Builder::new(shader, first.span);
        let first_result = b.push(ExprKind::Local(first.result), ty);
        let keep = Stmt::Store { place: Place::Local(shared), value: first_result, span: first.span };
        hoisted.push((first.top, Stmt::Lights { lights, body: vec![first.stmt.clone(), keep] }));
        for call in group {
            let value = b.push(ExprKind::Local(shared), ty);
            replaced.insert(
                call.ordinal,
                Stmt::Store { place: Place::Local(call.result), value, span: call.span },
            );
        }
    }
    if hoisted.is_empty() {
        return;
    }
    let mut ordinal = 0;
    replace(&mut shader.body, &mut ordinal, &replaced);
    let body = std::mem::take(&mut shader.body);
    for (top, stmt) in body.into_iter().enumerate() {
        shader.body.extend(hoisted.iter().filter(|(t, _)| *t == top).map(|(_, s)| s.clone()));
        shader.body.push(stmt);
    }
}

/// A self-contained call inside a light loop.
struct Call {
    /// Its place among the body's inlined calls, in pre-order.
    ordinal: u32,
    /// The top-level statement of the body that holds it.
    top: usize,
    /// The lights its loop visits.
    lights: Vec<u32>,
    /// The local it leaves its value in.
    result: LocalId,
    /// The call (a [`Stmt::Inline`]).
    stmt: Stmt,
    /// Where it was called.
    span: crate::source::Span,
}

/// What the whole shader stores and reads.
struct Facts {
    /// The predefined variables stored anywhere, by name.
    stored_globals: FxHashSet<&'static str>,
    /// How many statements (and built-in outputs) store into each local.
    stores: Vec<u32>,
    /// How many times each local is read, over every statement.
    reads: Vec<u32>,
}

impl Facts {
    fn of(shader: &Shader) -> Facts {
        let mut reads = vec![0; shader.locals.len()];
        count_reads(shader, &shader.body, &mut reads);
        let mut stored = FxHashSet::default();
        stored_globals(&shader.body, &mut stored);
        let stores = crate::ir::stores::stores(shader).iter().map(|s| s.count).collect();
        Facts { stored_globals: stored, stores, reads }
    }

    /// Adds the self-contained calls inside light loops within `stmt` (itself one when it is) to
    /// `out`, numbering every inlined call met in pre-order; `lights` are those of the light loop
    /// around `stmt`, if any.
    fn find(
        &self,
        shader: &Shader,
        stmt: &Stmt,
        top: usize,
        lights: Option<&Vec<u32>>,
        ordinal: &mut u32,
        out: &mut Vec<Call>,
    ) {
        if let Stmt::Inline { body, span, .. } = stmt {
            let this = *ordinal;
            *ordinal += 1;
            if let Some(lights) = lights
                && let Some(result) = self.self_contained(shader, body)
            {
                *ordinal += inlined_calls(body);
                let (lights, stmt, span) = (lights.clone(), stmt.clone(), *span);
                out.push(Call { ordinal: this, top, lights, result, stmt, span });
                return;
            }
        }
        let lights = match stmt {
            Stmt::Lights { lights, .. } => Some(lights),
            _ => lights,
        };
        stmt.for_each_block(|b| {
            for s in b {
                self.find(shader, s, top, lights, ordinal, out);
            }
        });
    }

    /// The result of an inlined call with body `body` when the call is self-contained.
    fn self_contained(&self, shader: &Shader, body: &Block) -> Option<LocalId> {
        let mut inside = Inside::new(shader, &self.stored_globals);
        inside.block(body)?;
        let mut exits = Vec::new();
        Assigned { shader }.block(body, &mut FxHashSet::default(), &mut exits)?;
        let mut result = None;
        for (&l, &stores) in &inside.stores {
            let local = shader.local(l);
            if stores != self.stores[l.0 as usize]
                || matches!(local.kind, LocalKind::Param { .. })
                || Some(l) == shader.result_local
            {
                return None;
            }
            if self.reads[l.0 as usize] > inside.reads.get(&l).copied().unwrap_or(0) {
                if result.is_some() {
                    return None;
                }
                result = Some(l);
            }
        }
        result
    }
}

/// The number of inlined calls within `block`, at any depth.
fn inlined_calls(block: &Block) -> u32 {
    block
        .iter()
        .map(|s| {
            let mut n = u32::from(matches!(s, Stmt::Inline { .. }));
            s.for_each_block(|b| n += inlined_calls(b));
            n
        })
        .sum()
}

/// Replaces the inlined calls numbered in `replaced` (numbered in pre-order, as [`Facts::find`]
/// does) within `block`.
fn replace(block: &mut Block, ordinal: &mut u32, replaced: &FxHashMap<u32, Stmt>) {
    for stmt in block.iter_mut() {
        if let Stmt::Inline { body, .. } = stmt {
            let this = *ordinal;
            *ordinal += 1;
            if let Some(new) = replaced.get(&this) {
                *ordinal += inlined_calls(body);
                *stmt = new.clone();
                continue;
            }
        }
        stmt.for_each_block_mut(|b| replace(b, ordinal, replaced));
    }
}

/// Adds each read of a local in `block` (a store into part of a local reads it too) to `reads`.
fn count_reads(shader: &Shader, block: &Block, reads: &mut [u32]) {
    fn expr(shader: &Shader, id: ExprId, reads: &mut [u32]) {
        let kind = &shader.expr(id).kind;
        if let ExprKind::Local(l) = kind {
            reads[l.0 as usize] += 1;
        }
        kind.for_each_operand(|a| expr(shader, a, reads));
    }
    for stmt in block {
        stmt.for_each_root(|e| expr(shader, e, reads));
        if let Stmt::Store { place: place @ Place::Index(..), .. } = stmt
            && let Some(l) = place.root_local()
        {
            reads[l.0 as usize] += 1;
        }
        stmt.for_each_block(|b| count_reads(shader, b, reads));
    }
}

/// Adds the names of the predefined variables `block` stores into to `out`.
fn stored_globals(block: &Block, out: &mut FxHashSet<&'static str>) {
    for stmt in block {
        if let Stmt::Store { place, .. } = stmt
            && let Some(g) = place.root_global()
        {
            out.insert(g.name);
        }
        stmt.for_each_block(|b| stored_globals(b, out));
    }
}

/// What a call's body stores and reads, found while checking that it has no effect.
struct Inside<'a> {
    shader: &'a Shader,
    /// The predefined variables the shader stores into, which a call must not read.
    stored_globals: &'a FxHashSet<&'static str>,
    /// Stores into each local.
    stores: FxHashMap<LocalId, u32>,
    /// Reads of each local.
    reads: FxHashMap<LocalId, u32>,
}

impl<'a> Inside<'a> {
    fn new(shader: &'a Shader, stored_globals: &'a FxHashSet<&'static str>) -> Inside<'a> {
        Inside { shader, stored_globals, stores: FxHashMap::default(), reads: FxHashMap::default() }
    }

    /// `Some` when `block` has no effect beyond storing locals, counting its stores and reads.
    fn block(&mut self, block: &Block) -> Option<()> {
        for stmt in block {
            match stmt {
                Stmt::Store { place, .. } => {
                    let l = place.root_local()?;
                    *self.stores.entry(l).or_default() += 1;
                    if matches!(place, Place::Index(..)) {
                        *self.reads.entry(l).or_default() += 1;
                    }
                }
                Stmt::If { .. } | Stmt::Inline { .. } | Stmt::Return => {}
                Stmt::Eval(_)
                | Stmt::Loop { .. }
                | Stmt::Break(_)
                | Stmt::Continue(_)
                | Stmt::Illuminance { .. }
                | Stmt::Emit { .. }
                | Stmt::Lights { .. } => return None,
            }
            let mut pure = true;
            stmt.for_each_root(|e| pure &= self.expr(e));
            if !pure {
                return None;
            }
            let mut nested = Some(());
            stmt.for_each_block(|b| nested = nested.and_then(|()| self.block(b)));
            nested?;
        }
        Some(())
    }

    /// Whether expression `id` reads only locals and predefined variables nothing stores, and
    /// writes nothing; counts its reads of locals.
    fn expr(&mut self, id: ExprId) -> bool {
        let kind = &self.shader.expr(id).kind;
        let ok = match kind {
            ExprKind::Local(l) => {
                *self.reads.entry(*l).or_default() += 1;
                true
            }
            ExprKind::Global(g) => !self.stored_globals.contains(g.name),
            ExprKind::Builtin(b, _) => b.params.iter().all(|p| !p.output),
            _ => true,
        };
        let mut operands = true;
        kind.for_each_operand(|a| operands &= self.expr(a));
        ok && operands
    }
}

/// The check that a body reads each local only after storing it on every path.
struct Assigned<'a> {
    shader: &'a Shader,
}

impl Assigned<'_> {
    /// Whether `block` reads only locals in `assigned` or stored before the read, `None` if not;
    /// `Some(false)` when every path through it returns. `assigned` becomes the locals stored on
    /// every path that falls through; `exits` gains those stored on each path that returns.
    fn block(
        &self,
        block: &Block,
        assigned: &mut FxHashSet<LocalId>,
        exits: &mut Vec<FxHashSet<LocalId>>,
    ) -> Option<bool> {
        for stmt in block {
            let mut read = true;
            stmt.for_each_root(|e| read &= self.stored(e, assigned));
            if !read {
                return None;
            }
            match stmt {
                Stmt::Store { place, .. } => match place {
                    Place::Local(l) => {
                        assigned.insert(*l);
                    }
                    _ => {
                        if !place.root_local().is_some_and(|l| assigned.contains(&l)) {
                            return None;
                        }
                    }
                },
                Stmt::If { then, otherwise, .. } => {
                    let (mut a, mut b) = (assigned.clone(), assigned.clone());
                    match (self.block(then, &mut a, exits)?, self.block(otherwise, &mut b, exits)?) {
                        (true, true) => *assigned = a.intersection(&b).copied().collect(),
                        (true, false) => *assigned = a,
                        (false, true) => *assigned = b,
                        (false, false) => return Some(false),
                    }
                }
                Stmt::Inline { body, .. } => {
                    let mut returns = Vec::new();
                    let mut a = assigned.clone();
                    if self.block(body, &mut a, &mut returns)? {
                        returns.push(a);
                    }
                    let mut sets = returns.into_iter();
                    let first = sets.next()?;
                    *assigned = sets.fold(first, |acc, s| acc.intersection(&s).copied().collect());
                }
                Stmt::Return => {
                    exits.push(assigned.clone());
                    return Some(false);
                }
                _ => return None,
            }
        }
        Some(true)
    }

    /// Whether expression `id` reads only locals in `assigned`.
    fn stored(&self, id: ExprId, assigned: &FxHashSet<LocalId>) -> bool {
        let mut reads = FxHashSet::default();
        self.shader.add_reads(id, &mut reads);
        reads.is_subset(assigned)
    }
}

/// Structural equality of two calls' bodies, up to a one-to-one renaming of their locals.
struct Same<'a> {
    shader: &'a Shader,
    /// The renaming so far, both ways.
    forward: FxHashMap<LocalId, LocalId>,
    backward: FxHashMap<LocalId, LocalId>,
}

impl<'a> Same<'a> {
    fn new(shader: &'a Shader) -> Same<'a> {
        Same { shader, forward: FxHashMap::default(), backward: FxHashMap::default() }
    }

    fn block(&mut self, a: &Block, b: &Block) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(a, b)| self.stmt(a, b))
    }

    fn stmt(&mut self, a: &Stmt, b: &Stmt) -> bool {
        match (a, b) {
            (Stmt::Store { place: pa, value: va, .. }, Stmt::Store { place: pb, value: vb, .. }) => {
                self.place(pa, pb) && self.expr(*va, *vb)
            }
            (
                Stmt::If { cond: ca, then: ta, otherwise: oa },
                Stmt::If { cond: cb, then: tb, otherwise: ob },
            ) => self.expr(*ca, *cb) && self.block(ta, tb) && self.block(oa, ob),
            (Stmt::Inline { function: fa, body: ba, .. }, Stmt::Inline { function: fb, body: bb, .. }) => {
                fa == fb && self.block(ba, bb)
            }
            (Stmt::Return, Stmt::Return) => true,
            _ => false,
        }
    }

    fn place(&mut self, a: &Place, b: &Place) -> bool {
        match (a, b) {
            (Place::Local(a), Place::Local(b)) => self.local(*a, *b),
            (Place::Global(a), Place::Global(b)) => a.name == b.name,
            (Place::Index(pa, ia), Place::Index(pb, ib)) => self.place(pa, pb) && self.expr(*ia, *ib),
            _ => false,
        }
    }

    fn local(&mut self, a: LocalId, b: LocalId) -> bool {
        match (self.forward.get(&a), self.backward.get(&b)) {
            (Some(&fa), Some(&fb)) => fa == b && fb == a,
            (None, None) => {
                let (la, lb) = (self.shader.local(a), self.shader.local(b));
                if la.ty != lb.ty || la.kind != lb.kind {
                    return false;
                }
                self.forward.insert(a, b);
                self.backward.insert(b, a);
                true
            }
            _ => false,
        }
    }

    fn exprs(&mut self, a: &[ExprId], b: &[ExprId]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(a, b)| self.expr(*a, *b))
    }

    fn expr(&mut self, a: ExprId, b: ExprId) -> bool {
        let (ea, eb) = (self.shader.expr(a), self.shader.expr(b));
        if ea.ty != eb.ty {
            return false;
        }
        match (&ea.kind, &eb.kind) {
            (ExprKind::Literal(x), ExprKind::Literal(y)) => x == y,
            (ExprKind::Local(x), ExprKind::Local(y)) => self.local(*x, *y),
            (ExprKind::Global(x), ExprKind::Global(y)) => x.name == y.name,
            (ExprKind::Unary(ox, x), ExprKind::Unary(oy, y)) => ox == oy && self.expr(*x, *y),
            (ExprKind::Binary(ox, x1, x2), ExprKind::Binary(oy, y1, y2)) => {
                ox == oy && self.expr(*x1, *y1) && self.expr(*x2, *y2)
            }
            (ExprKind::Convert(x), ExprKind::Convert(y)) => self.expr(*x, *y),
            (ExprKind::Construct(x), ExprKind::Construct(y)) => self.exprs(x, y),
            (ExprKind::FromSpace { space: sx, value: x }, ExprKind::FromSpace { space: sy, value: y }) => {
                sx == sy && self.expr(*x, *y)
            }
            (ExprKind::Index(x1, x2), ExprKind::Index(y1, y2)) => self.expr(*x1, *y1) && self.expr(*x2, *y2),
            (ExprKind::Select(x1, x2, x3), ExprKind::Select(y1, y2, y3)) => {
                self.expr(*x1, *y1) && self.expr(*x2, *y2) && self.expr(*x3, *y3)
            }
            (ExprKind::Builtin(bx, x), ExprKind::Builtin(by, y)) => {
                std::ptr::eq(*bx, *by) && self.exprs(x, y)
            }
            (ExprKind::Seed(ix, ax), ExprKind::Seed(iy, ay)) => ix == iy && ax == ay,
            (ExprKind::LightSum { lights: lx, value: x }, ExprKind::LightSum { lights: ly, value: y }) => {
                lx == ly && self.expr(*x, *y)
            }
            _ => false,
        }
    }
}
