//! Slicing the body per stage: which statements each stage keeps, which values it takes from a
//! lower stage, and the stage shaders built from that.
//!
//! The stages are sliced from the last to the first: the fragment stage's needs decide what the
//! vertex stage and the host export, and the vertex stage's needs add to the host's. Each slice is
//! a fixpoint over the variables the stage must compute itself (a store is kept when its
//! variable is needed; the values a kept store reads make more variables needed).

use rustc_hash::{FxHashMap, FxHashSet};
use smol_str::SmolStr;

use super::placement::{Placement, root};
use super::{StageKind, Stages, Transfer, Var};
use crate::diag::{Code, Diagnostic};
use crate::ir::types::{Base, Frequency};
use crate::ir::{Block, ExprId, ExprKind, Local, LocalId, LocalKind, Place, Shader, Stmt};
use crate::opt::Prepared;

/// A value one stage asked a lower stage for.
struct Request {
    from: StageKind,
    to_vertex: bool,
    to_fragment: bool,
    hint: SmolStr,
}

pub(super) fn split(shader: &Shader, fold_host: bool) -> Result<Stages, Diagnostic> {
    let placement = Placement::new(shader);
    let mut requests: Vec<(ExprId, Request)> = Vec::new();
    let mut index: FxHashMap<ExprId, usize> = FxHashMap::default();
    let mut needed: FxHashMap<StageKind, FxHashSet<Var>> = FxHashMap::default();

    for stage in [StageKind::Fragment, StageKind::Vertex, StageKind::Host] {
        let exports: FxHashMap<ExprId, LocalId> =
            requests.iter().filter(|(_, r)| r.from == stage).map(|(e, _)| (*e, LocalId(u32::MAX))).collect();
        let roots = match stage {
            StageKind::Fragment => outputs(shader),
            StageKind::Vertex => FxHashSet::default(),
            // What the parameters' defaults read (`ir::defaults`).
            StageKind::Host => shader.default_reads().into_iter().map(Var::Local).collect(),
        };
        let slicer = Slicer::analyse(shader, &placement, stage, roots, &exports, fold_host)?;
        for (e, hint) in slicer.imports {
            let from = placement.of(e);
            let i = *index.entry(e).or_insert_with(|| {
                requests.push((e, Request { from, to_vertex: false, to_fragment: false, hint }));
                requests.len() - 1
            });
            match stage {
                StageKind::Vertex => requests[i].1.to_vertex = true,
                StageKind::Fragment => requests[i].1.to_fragment = true,
                StageKind::Host => unreachable!("the host imports nothing: no stage is below it"),
            }
        }
        needed.insert(stage, slicer.needed);
    }

    // One parameter local per transfer, appended after the shader's own locals.
    let mut names: FxHashSet<SmolStr> = shader.locals.iter().map(|l| l.name.clone()).collect();
    let mut transfers = Vec::new();
    for (k, (e, r)) in requests.iter().enumerate() {
        let expr = shader.expr(*e);
        let name = unique(&mut names, &r.hint, r.from);
        transfers.push(Transfer {
            local: LocalId((shader.locals.len() + k) as u32),
            name,
            ty: expr.ty,
            from: r.from,
            to_vertex: r.to_vertex,
            to_fragment: r.to_fragment,
            span: expr.span,
        });
    }

    let build = |stage: StageKind| -> Result<Shader, Diagnostic> {
        let exports: FxHashMap<ExprId, LocalId> = requests
            .iter()
            .zip(&transfers)
            .filter(|((_, r), _)| r.from == stage)
            .map(|((e, _), t)| (*e, t.local))
            .collect();
        let mut s = Slicer::new(shader, &placement, stage, needed[&stage].clone(), &exports, fold_host);
        let body = s.block(&shader.body, false);
        if let Some(d) = s.error {
            return Err(d);
        }
        let mut out = shader.clone();
        out.body = body;
        for ((e, _), t) in requests.iter().zip(&transfers) {
            let consumer = match stage {
                StageKind::Host => false,
                StageKind::Vertex => t.to_vertex,
                StageKind::Fragment => t.to_fragment,
            };
            let producer = t.from == stage;
            let expr = shader.expr(*e);
            out.locals.push(Local {
                name: t.name.clone(),
                ty: t.ty,
                rate: expr.rate,
                declared: false,
                kind: if producer || consumer {
                    LocalKind::Param { default: None, output: producer }
                } else {
                    LocalKind::Temp
                },
                span: t.span,
                function: None,
            });
            if producer || consumer {
                out.params.push(t.local);
            }
            if consumer {
                out.exprs[e.0 as usize].kind = ExprKind::Local(t.local);
            }
        }
        Ok(out)
    };
    Ok(Stages {
        host: Prepared::assume_prepared(build(StageKind::Host)?),
        vertex: Prepared::assume_prepared(build(StageKind::Vertex)?),
        fragment: Prepared::assume_prepared(build(StageKind::Fragment)?),
        transfers,
    })
}

/// What the fragment stage must produce: the predefined variables the body writes, output
/// parameters, and a Stanford shader's result.
fn outputs(shader: &Shader) -> FxHashSet<Var> {
    let mut roots = FxHashSet::default();
    written_globals(&shader.body, &mut roots);
    for &p in &shader.params {
        if let LocalKind::Param { output: true, .. } = shader.local(p).kind {
            roots.insert(Var::Local(p));
        }
    }
    if let Some(r) = shader.result_local {
        roots.insert(Var::Local(r));
    }
    roots
}

fn written_globals(block: &Block, out: &mut FxHashSet<Var>) {
    for stmt in block {
        match stmt {
            Stmt::Store { place, .. } => {
                if let Var::Global(g) = root(place) {
                    out.insert(Var::Global(g));
                }
            }
            Stmt::If { then, otherwise, .. } => {
                written_globals(then, out);
                written_globals(otherwise, out);
            }
            Stmt::Loop { body, step, .. } => {
                written_globals(body, out);
                written_globals(step, out);
            }
            Stmt::Inline { body, .. }
            | Stmt::Illuminance { body, .. }
            | Stmt::Emit { body, .. }
            | Stmt::Lights { body, .. } => written_globals(body, out),
            Stmt::Eval(_) | Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => {}
        }
    }
}

/// A name for a transfer: the hint as an identifier, not used by any local or earlier transfer.
fn unique(names: &mut FxHashSet<SmolStr>, hint: &str, from: StageKind) -> SmolStr {
    let mut base: String =
        hint.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '_' }).collect();
    if base.is_empty() || base.starts_with(|c: char| c.is_ascii_digit()) {
        base.insert(0, '_');
    }
    let base = format!("{base}_{}", &from.name()[..1]);
    let mut name = SmolStr::new(&base);
    let mut n = 1;
    while names.contains(&name) {
        name = SmolStr::new(format!("{base}{n}"));
        n += 1;
    }
    names.insert(name.clone());
    name
}

/// The slice of one stage.
struct Slicer<'a> {
    shader: &'a Shader,
    placement: &'a Placement,
    stage: StageKind,
    /// The variables this stage computes itself.
    needed: FxHashSet<Var>,
    /// Values this stage takes from a lower one, with a name hint, in the order found.
    imports: Vec<(ExprId, SmolStr)>,
    imported: FxHashSet<ExprId>,
    /// Values later stages take from this one, with the parameter that carries each.
    exports: &'a FxHashMap<ExprId, LocalId>,
    exported: FxHashSet<ExprId>,
    /// The name of the variable the current statement stores, for name hints.
    target: Option<SmolStr>,
    /// Whether the host hands nothing up (every stage recomputes what it would have).
    fold_host: bool,
    grew: bool,
    error: Option<Diagnostic>,
}

impl<'a> Slicer<'a> {
    fn new(
        shader: &'a Shader,
        placement: &'a Placement,
        stage: StageKind,
        needed: FxHashSet<Var>,
        exports: &'a FxHashMap<ExprId, LocalId>,
        fold_host: bool,
    ) -> Self {
        Slicer {
            shader,
            placement,
            stage,
            needed,
            imports: Vec::new(),
            imported: FxHashSet::default(),
            exports,
            exported: FxHashSet::default(),
            target: None,
            fold_host,
            grew: false,
            error: None,
        }
    }

    /// Slices until the set of needed variables stops growing.
    fn analyse(
        shader: &'a Shader,
        placement: &'a Placement,
        stage: StageKind,
        roots: FxHashSet<Var>,
        exports: &'a FxHashMap<ExprId, LocalId>,
        fold_host: bool,
    ) -> Result<Self, Diagnostic> {
        let mut s = Slicer::new(shader, placement, stage, roots, exports, fold_host);
        loop {
            s.grew = false;
            s.exported.clear();
            s.block(&shader.body, false);
            if let Some(d) = s.error.take() {
                return Err(d);
            }
            if !s.grew {
                return Ok(s);
            }
        }
    }

    fn need(&mut self, var: Var) {
        if self.placement.written.contains_key(&var) && self.needed.insert(var) {
            self.grew = true;
        }
    }

    fn kept(&self, place: &Place) -> bool {
        self.needed.contains(&root(place))
    }

    /// The variables a built-in call writes.
    fn call_outputs(&self, id: ExprId) -> Vec<Var> {
        let ExprKind::Builtin(b, args) = &self.shader.expr(id).kind else { return Vec::new() };
        b.params
            .iter()
            .zip(args)
            .filter_map(|(p, a)| match (p.output, &self.shader.expr(*a).kind) {
                (true, ExprKind::Local(l)) => Some(Var::Local(*l)),
                _ => None,
            })
            .collect()
    }

    fn block(&mut self, block: &Block, in_loop: bool) -> Block {
        let mut out = Vec::new();
        for stmt in block {
            self.statement(stmt, in_loop, &mut out);
        }
        out
    }

    fn statement(&mut self, stmt: &Stmt, in_loop: bool, out: &mut Block) {
        self.emit_exports(stmt, out);
        match stmt {
            Stmt::Store { place, value, .. } => {
                if self.kept(place) {
                    self.target = Some(self.var_name(root(place)));
                    self.visit(*value, in_loop);
                    self.visit_place(place, in_loop);
                    self.target = None;
                    out.push(stmt.clone());
                }
            }
            Stmt::Eval(id) => {
                if self.call_outputs(*id).iter().any(|v| self.needed.contains(v)) {
                    self.visit(*id, in_loop);
                    out.push(stmt.clone());
                }
            }
            Stmt::If { cond, then, otherwise } => {
                if self.placement.of(*cond) <= self.stage {
                    let then = self.block(then, in_loop);
                    let otherwise = self.block(otherwise, in_loop);
                    if !then.is_empty() || !otherwise.is_empty() {
                        self.visit(*cond, in_loop);
                        out.push(Stmt::If { cond: *cond, then, otherwise });
                    }
                } else {
                    // A branch this stage cannot decide holds none of its stores (placement
                    // raised them), only values it exports, which are pure: compute them.
                    self.exports_only(then, out);
                    self.exports_only(otherwise, out);
                }
            }
            Stmt::Loop { cond, body, step, span } => {
                if self.has_effects(body) || self.has_effects(step) {
                    if let Some(c) = cond {
                        self.visit(*c, true);
                    }
                    let body = self.block(body, true);
                    let step = self.block(step, true);
                    out.push(Stmt::Loop { cond: *cond, body, step, span: *span });
                }
            }
            Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => out.push(stmt.clone()),
            Stmt::Inline { function, body, span } => {
                if self.has_effects(body) {
                    let body = self.block(body, in_loop);
                    out.push(Stmt::Inline { function: function.clone(), body, span: *span });
                } else {
                    self.exports_only(body, out);
                }
            }
            Stmt::Illuminance { args, body } => {
                if self.stage == StageKind::Fragment && self.has_effects(body) {
                    for &a in args {
                        self.visit(a, true);
                    }
                    let body = self.block(body, true);
                    out.push(Stmt::Illuminance { args: args.clone(), body });
                }
            }
            Stmt::Lights { lights, body } => {
                if self.stage == StageKind::Fragment && self.has_effects(body) {
                    let body = self.block(body, true);
                    out.push(Stmt::Lights { lights: lights.clone(), body });
                }
            }
            Stmt::Emit { solar, args, body } => {
                if self.stage == StageKind::Fragment {
                    for &a in args {
                        self.visit(a, in_loop);
                    }
                    let body = self.block(body, in_loop);
                    out.push(Stmt::Emit { solar: *solar, args: args.clone(), body });
                }
            }
        }
    }

    /// Whether this stage keeps anything of `block` (stores of needed variables).
    fn has_effects(&self, block: &Block) -> bool {
        block.iter().any(|stmt| match stmt {
            Stmt::Store { place, .. } => self.kept(place),
            Stmt::Eval(id) => self.call_outputs(*id).iter().any(|v| self.needed.contains(v)),
            Stmt::If { then, otherwise, .. } => self.has_effects(then) || self.has_effects(otherwise),
            Stmt::Loop { body, step, .. } => self.has_effects(body) || self.has_effects(step),
            Stmt::Inline { body, .. } => self.has_effects(body),
            Stmt::Illuminance { body, .. } | Stmt::Lights { body, .. } => {
                self.stage == StageKind::Fragment && self.has_effects(body)
            }
            Stmt::Emit { .. } => self.stage == StageKind::Fragment,
            Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => false,
        })
    }

    /// Only the exports of `block`, at their places, without its control flow.
    fn exports_only(&mut self, block: &Block, out: &mut Block) {
        for stmt in block {
            self.emit_exports(stmt, out);
            match stmt {
                Stmt::If { then, otherwise, .. } => {
                    self.exports_only(then, out);
                    self.exports_only(otherwise, out);
                }
                Stmt::Inline { body, .. } => self.exports_only(body, out),
                _ => {}
            }
        }
    }

    /// Stores of the values later stages take from this one that `stmt` computes (in its own
    /// expressions, not in nested statements), placed before it.
    fn emit_exports(&mut self, stmt: &Stmt, out: &mut Block) {
        if self.exports.is_empty() {
            return;
        }
        let mut roots = Vec::new();
        match stmt {
            Stmt::Store { place, value, .. } => {
                roots.push(*value);
                place_indices(place, &mut roots);
            }
            Stmt::Eval(id) => roots.push(*id),
            Stmt::If { cond, .. } => roots.push(*cond),
            _ => return,
        }
        let mut found = Vec::new();
        for r in roots {
            self.find_exports(r, &mut found);
        }
        for e in found {
            let local = self.exports[&e];
            self.visit(e, false);
            let span = self.shader.expr(e).span;
            out.push(Stmt::Store { place: Place::Local(local), value: e, span });
        }
    }

    fn find_exports(&mut self, id: ExprId, found: &mut Vec<ExprId>) {
        if self.exports.contains_key(&id) && self.exported.insert(id) {
            found.push(id);
        }
        self.shader.expr(id).kind.for_each_operand(|o| self.find_exports(o, found));
    }

    fn visit_place(&mut self, place: &Place, in_loop: bool) {
        let mut indices = Vec::new();
        place_indices(place, &mut indices);
        for i in indices {
            self.visit(i, in_loop);
        }
    }

    /// Records what computing `id` in this stage takes: values from lower stages, and the
    /// variables it reads that this stage must compute.
    fn visit(&mut self, id: ExprId, in_loop: bool) {
        let e = self.shader.expr(id);
        let stage = self.placement.of(id);
        if stage > self.stage {
            if self.error.is_none() {
                self.error = Some(
                    Diagnostic::error(
                        Code::Internal,
                        format!(
                            "internal error: the {} stage needs this value, which only the {} stage can \
                             compute",
                            self.stage.name(),
                            stage.name()
                        ),
                        e.span,
                        "placed here",
                    )
                    .with_help("this is a bug in Patina's stage split; please report it with the shader"),
                );
            }
            return;
        }
        if stage < self.stage && self.transferable(id, in_loop) {
            if self.imported.insert(id) {
                let hint = match &e.kind {
                    ExprKind::Local(l) => self.shader.local(*l).name.clone(),
                    ExprKind::Global(g) => SmolStr::new(g.name),
                    _ => self.target.clone().unwrap_or_else(|| SmolStr::new("value")),
                };
                self.imports.push((id, hint));
            }
            return;
        }
        match &e.kind {
            ExprKind::Local(l) => self.need(Var::Local(*l)),
            ExprKind::Global(g) => self.need(Var::Global(g.name)),
            kind => kind.for_each_operand(|o| self.visit(o, in_loop)),
        }
    }

    /// Whether `id`, computed by a lower stage, can be handed up rather than recomputed: it is
    /// computed once per invocation (not in a loop or per light), it is not an input every stage
    /// reads anyway, and its type can cross (varyings are scalars and vectors). In RenderMan-style
    /// shaders only uniform values cross.
    fn transferable(&self, id: ExprId, in_loop: bool) -> bool {
        let e = self.shader.expr(id);
        if in_loop || e.rate.perlight || e.rate.frequency == Frequency::Constant {
            return false;
        }
        if self.fold_host && self.placement.of(id) == StageKind::Host {
            return false;
        }
        // RenderMan users expect varying expressions per shading point (only the inputs are
        // interpolated); Stanford's rates say per vertex, and mean it.
        if !self.shader.stanford && self.placement.of(id) == StageKind::Vertex {
            return false;
        }
        let leaf = match &e.kind {
            ExprKind::Literal(_) | ExprKind::Seed(..) => true,
            ExprKind::Local(l) => !self.placement.written.contains_key(&Var::Local(*l)),
            ExprKind::Global(g) => !self.placement.written.contains_key(&Var::Global(g.name)),
            ExprKind::Builtin(b, _) => b.params.iter().any(|p| p.output),
            _ => false,
        };
        if leaf {
            return false;
        }
        match e.ty.base {
            Base::Void | Base::String | Base::Texref => false,
            Base::Matrix3 | Base::Matrix4 => self.placement.of(id) == StageKind::Host,
            _ => !e.ty.is_array() || self.placement.of(id) == StageKind::Host,
        }
    }

    fn var_name(&self, var: Var) -> SmolStr {
        match var {
            Var::Local(l) => self.shader.local(l).name.clone(),
            Var::Global(g) => SmolStr::new(g),
        }
    }
}

/// The index expressions of a place, outermost last.
fn place_indices(place: &Place, out: &mut Vec<ExprId>) {
    if let Place::Index(inner, index) = place {
        place_indices(inner, out);
        out.push(*index);
    }
}
