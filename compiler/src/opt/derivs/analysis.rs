//! Which values need derivatives: a backward analysis from the arguments of the derivative
//! consumers to the inputs, through expressions and through the variables they read.
//!
//! Only the locals and globals it marks get shadow variables and derivative stores, so a value that
//! feeds only conditions, indices or integer arithmetic costs nothing.
//!
//! A forward pass first finds the *active* values, those that can have a non-zero derivative: the
//! inputs, and whatever is computed from them by differentiable operations, through the variables
//! they are stored in. It matters for RenderMan, where variables are varying unless declared
//! otherwise: a varying loop counter holds only constants, and needs no shadows.

use rustc_hash::{FxHashMap, FxHashSet};

use super::calls;
use crate::ir::builtin::Builtin;
use crate::ir::builtin::BuiltinId;
use crate::ir::global::Global;
use crate::ir::types::{Frequency, Rate, Type};
use crate::ir::{Block, ExprId, ExprKind, LocalId, LocalKind, Place, Shader, Stmt};
use crate::sema::globals;

/// What the analysis found.
#[derive(Debug, Default)]
pub(super) struct Needs {
    /// The consumers to replace, in arena order.
    pub consumers: Vec<ExprId>,
    /// The locals (parameters included) whose derivatives are needed, in id order.
    pub locals: Vec<LocalId>,
    /// The predefined variables whose derivatives are needed, in the order found.
    pub globals: Vec<&'static Global>,
    /// Per expression of the shader as given: whether it can have a non-zero derivative.
    pub active: Vec<bool>,
}

/// The type of an input's derivative: [`Type::derivative`].
pub(super) fn dtype(ty: Type) -> Option<Type> {
    ty.derivative()
}

/// Whether a value of type `ty` and rate `rate` can have a non-zero derivative: it must be made of
/// floats and vary within a primitive (constant and per-draw values have derivative 0).
pub(super) fn varies(ty: Type, rate: Rate) -> bool {
    dtype(ty).is_some() && rate.frequency >= Frequency::Vertex
}

/// Whether a predefined variable is an input with a derivative. Per-light values are not (their
/// derivative is taken as 0), nor are `du`, `dv` (already screen derivatives).
pub(super) fn global_varies(g: &Global) -> bool {
    varies(Type::of(g.ty), Rate { frequency: g.frequency, perlight: false })
        && !g.perlight
        && !matches!(g.name, "du" | "dv")
}

/// Whether a call is a derivative consumer this pass replaces. The texture family is left for the
/// texture filtering work; the 3-argument `filterstep` gives its filter region explicitly.
pub(super) fn is_consumer(b: &Builtin) -> bool {
    calls::rule(b) == calls::Rule::Consumer
}

/// Whether the consumer's replacement uses the derivatives of `u` and `v`.
fn uses_uv(b: &Builtin) -> bool {
    matches!(b.id, BuiltinId::Du | BuiltinId::Dv | BuiltinId::Deriv | BuiltinId::CalculateNormal)
}

/// The arguments whose derivatives a consumer's replacement uses.
pub(super) fn consumer_operands(b: &Builtin, args: &[ExprId]) -> Vec<ExprId> {
    match b.id {
        BuiltinId::FilterStep => vec![args[1]],
        BuiltinId::Deriv => args.to_vec(),
        _ => vec![args[0]],
    }
}

/// The place a built-in's output argument denotes (a local, a global, or an element of one).
pub(super) fn place_of(shader: &Shader, e: ExprId) -> Option<Place> {
    match &shader.expr(e).kind {
        ExprKind::Local(l) => Some(Place::Local(*l)),
        ExprKind::Global(g) => Some(Place::Global(g)),
        ExprKind::Index(base, i) => Some(Place::Index(Box::new(place_of(shader, *base)?), *i)),
        _ => None,
    }
}

/// The variable a place is part of.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub(super) enum Root {
    /// A local or parameter.
    Local(LocalId),
    /// A predefined variable, by name (a shader sees one variable of each name).
    Global(&'static str),
}

/// The variable `place` writes part or all of.
pub(super) fn root(place: &Place) -> Root {
    match place {
        Place::Local(l) => Root::Local(*l),
        Place::Global(g) => Root::Global(g.name),
        Place::Index(inner, _) => root(inner),
    }
}

/// Finds the consumers and everything their arguments' derivatives depend on.
pub(super) fn analyse(shader: &Shader) -> Needs {
    let mut a = Analysis {
        shader,
        stored: FxHashMap::default(),
        active: Vec::new(),
        seen: vec![false; shader.exprs.len()],
        locals: FxHashSet::default(),
        globals: Vec::new(),
        work: Vec::new(),
    };
    a.collect(&shader.body);
    a.activity();
    let mut consumers = Vec::new();
    let mut uv = false;
    for (i, e) in shader.exprs.iter().enumerate() {
        let ExprKind::Builtin(b, args) = &e.kind else { continue };
        if !is_consumer(b) {
            continue;
        }
        consumers.push(ExprId(i as u32));
        for arg in consumer_operands(b, args) {
            uv |= uses_uv(b) && a.active[arg.0 as usize];
            a.work.push(arg);
        }
    }
    if uv {
        for name in ["u", "v"] {
            if let Some(g) = globals::lookup(name, shader.kind, shader.stanford) {
                a.global(g);
            }
        }
    }
    while let Some(e) = a.work.pop() {
        a.mark(e);
    }
    let mut locals: Vec<LocalId> = a.locals.into_iter().collect();
    locals.sort_unstable();
    Needs { consumers, locals, globals: a.globals, active: a.active }
}

struct Analysis<'s> {
    shader: &'s Shader,
    /// The values stored into each variable (for a built-in's output, the inputs its derivative
    /// depends on).
    stored: FxHashMap<Root, Vec<ExprId>>,
    active: Vec<bool>,
    seen: Vec<bool>,
    locals: FxHashSet<LocalId>,
    globals: Vec<&'static Global>,
    work: Vec<ExprId>,
}

impl Analysis<'_> {
    /// Records what every store and output argument writes.
    fn collect(&mut self, block: &Block) {
        for stmt in block {
            match stmt {
                Stmt::Store { place, value, .. } => self.stored.entry(root(place)).or_default().push(*value),
                Stmt::Eval(id) => {
                    let ExprKind::Builtin(b, args) = &self.shader.expr(*id).kind else { continue };
                    for (i, &arg) in args.iter().enumerate() {
                        if b.param_type(i).is_some_and(|p| p.output)
                            && let Some(place) = place_of(self.shader, arg)
                        {
                            let inputs = calls::output_inputs(b, args);
                            self.stored.entry(root(&place)).or_default().extend(inputs);
                        }
                    }
                }
                Stmt::If { then, otherwise, .. } => {
                    self.collect(then);
                    self.collect(otherwise);
                }
                Stmt::Loop { body, step, .. } => {
                    self.collect(body);
                    self.collect(step);
                }
                Stmt::Inline { body, .. }
                | Stmt::Illuminance { body, .. }
                | Stmt::Emit { body, .. }
                | Stmt::Lights { body, .. } => {
                    self.collect(body);
                }
                Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => {}
            }
        }
    }

    /// Finds the active expressions: a fixpoint over the locals, each pass over the arena in
    /// order (operands come before their users).
    fn activity(&mut self) {
        let shader = self.shader;
        let mut locals: Vec<bool> = shader
            .locals
            .iter()
            .map(|l| matches!(l.kind, LocalKind::Param { .. }) && varies(l.ty, l.rate))
            .collect();
        loop {
            self.active = Vec::with_capacity(shader.exprs.len());
            for e in &shader.exprs {
                let on = |id: &ExprId| self.active[id.0 as usize];
                let active = varies(e.ty, e.rate)
                    && match &e.kind {
                        ExprKind::Literal(_) => false,
                        ExprKind::Seed(..) => true,
                        ExprKind::Local(l) => locals[l.0 as usize],
                        ExprKind::Global(g) => global_varies(g),
                        ExprKind::Unary(_, a) | ExprKind::Convert(a) | ExprKind::Index(a, _) => on(a),
                        ExprKind::Binary(_, a, b) | ExprKind::Select(_, a, b) => on(a) || on(b),
                        ExprKind::Construct(parts) => parts.iter().any(on),
                        ExprKind::FromSpace { value, .. } | ExprKind::LightSum { value, .. } => on(value),
                        ExprKind::Builtin(b, args) => {
                            !is_consumer(b)
                                && (calls::is_source(b) || calls::operands(b, args).iter().any(on))
                        }
                    };
                self.active.push(active);
            }
            let mut changed = false;
            for (root, values) in &self.stored {
                if let Root::Local(l) = *root
                    && !locals[l.0 as usize]
                    && varies(shader.local(l).ty, shader.local(l).rate)
                    && values.iter().any(|v| self.active[v.0 as usize])
                {
                    locals[l.0 as usize] = true;
                    changed = true;
                }
            }
            if !changed {
                return;
            }
        }
    }

    fn mark(&mut self, e: ExprId) {
        let i = e.0 as usize;
        if std::mem::replace(&mut self.seen[i], true) || !self.active[i] {
            return;
        }
        let expr = self.shader.expr(e);
        match &expr.kind {
            ExprKind::Literal(_) | ExprKind::Seed(..) => {}
            ExprKind::Local(l) => self.local(*l),
            ExprKind::Global(g) => self.global(g),
            ExprKind::Unary(_, a) | ExprKind::Convert(a) | ExprKind::Index(a, _) => self.work.push(*a),
            ExprKind::Binary(_, a, b) | ExprKind::Select(_, a, b) => self.work.extend([*a, *b]),
            ExprKind::Construct(parts) => self.work.extend(parts),
            ExprKind::FromSpace { value, .. } | ExprKind::LightSum { value, .. } => self.work.push(*value),
            ExprKind::Builtin(b, args) => {
                if !is_consumer(b) {
                    self.work.extend(calls::operands(b, args));
                }
            }
        }
    }

    fn local(&mut self, l: LocalId) {
        if self.locals.insert(l) {
            self.work.extend(self.stored.get(&Root::Local(l)).into_iter().flatten());
        }
    }

    fn global(&mut self, g: &'static Global) {
        if global_varies(g) && !self.globals.iter().any(|h| h.name == g.name) {
            self.globals.push(g);
            self.work.extend(self.stored.get(&Root::Global(g.name)).into_iter().flatten());
        }
    }
}
