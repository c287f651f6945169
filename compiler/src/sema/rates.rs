//! Rates: inference for undeclared variables, promotion by the maximum rule, control dependence,
//! the required rates of derivatives and light sums, `perlight` and `integrate`, and the checks of
//! declared rates — each violation reported with where the value is used and where its rate came
//! from.
//!
//! Inference is a fixpoint: an undeclared variable's rate is the join of everything stored in it
//! (and of the conditions and loops the stores are under); expression rates follow from their
//! operands. The lattice is finite and the joins monotone, so it terminates.

use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::ir::builtin::RateRule;
use crate::ir::types::{Frequency, Rate};
use crate::ir::{Block, ExprId, ExprKind, LocalId, LocalKind, Place, Shader, Stmt};
use crate::source::Span;

/// Why a value has its rate: the place to point at.
#[derive(Copy, Clone, Debug, PartialEq)]
struct Origin {
    span: Span,
    why: Why,
}

#[derive(Copy, Clone, Debug, PartialEq)]
enum Why {
    /// A literal or other constant.
    Constant,
    /// A predefined variable, parameter or declared variable with this rate.
    Declared,
    /// A screen-space derivative (fragment only).
    Derivative,
    /// A function that is always per fragment.
    Fragment,
    /// A sum over lights.
    Lights,
    /// A value stored into an undeclared variable.
    Stored,
}

struct Analysis<'s> {
    shader: &'s mut Shader,
    origins: Vec<Origin>,
    local_origins: Vec<Origin>,
    changed: bool,
    /// The expressions before this one have their rates computed in this round.
    cursor: usize,
    /// Index expressions that made a store depend on their rate (so messages can say "index").
    index_origins: rustc_hash::FxHashSet<Span>,
    /// Stores to check once rates are final: (place root, value, control rate, control origin, store span).
    checks: Vec<(Target, ExprId, Rate, Option<Span>, Span)>,
    /// The inlined calls being walked, innermost last: the function, and the control rate (with
    /// its origin) of the conditions inside its body so far. A declared variable of an inlined
    /// function is checked against these only: it exists only while the body runs, so a
    /// condition around the call cannot make it differ between the points that see it.
    inlined: Vec<(smol_str::SmolStr, Rate, Option<Span>)>,
    /// The constructs around the statement being walked, outermost first: what each one's own
    /// conditions add to the control rate (with the condition that raised it most).
    frames: Vec<(Rate, Option<Span>)>,
    /// For each local, how many constructs were around its declaration, once the walk has met
    /// the store that initialises it there (`None`: not met, or declared without a value).
    declared_at: Vec<Option<usize>>,
}

#[derive(Copy, Clone)]
enum Target {
    Local(LocalId),
    Global(&'static crate::ir::global::Global),
}

fn root(place: &Place) -> Target {
    match place {
        Place::Local(l) => Target::Local(*l),
        Place::Global(g) => Target::Global(g),
        Place::Index(inner, _) => root(inner),
    }
}

/// Infers the rates of `shader`'s values and checks every declared rate.
pub fn infer(shader: &mut Shader, diags: &mut Diagnostics) {
    let constant = Origin { span: shader.span, why: Why::Constant };
    let local_origins = shader
        .locals
        .iter()
        .map(|l| Origin { span: l.span, why: if l.declared { Why::Declared } else { Why::Constant } })
        .collect();
    let mut a = Analysis {
        inlined: Vec::new(),
        frames: Vec::new(),
        declared_at: vec![None; shader.locals.len()],
        origins: vec![constant; shader.exprs.len()],
        local_origins,
        shader,
        changed: true,
        cursor: 0,
        index_origins: Default::default(),
        checks: Vec::new(),
    };
    // Each round that changes anything raises some local's rate, and a rate rises at most four
    // times (three frequency steps and `perlight`), so the loop ends. Expression rates are
    // recomputed in arena order as the walk reaches the statements that read them (`advance`), so
    // a store sees the rates the stores before it in program order gave their variables: only what
    // flows against program order (a value carried round a loop) takes another round. (Recomputing
    // them all at the start of each round moved rates one variable per round, and a cap of 64
    // rounds left longer chains with rates too low.) A statement may read an expression the cursor
    // has not reached (a nested loop's condition, for an early exit): it then has its rate from
    // the end of the round before, or from this first pass.
    a.exprs();
    while a.changed {
        a.changed = false;
        a.checks.clear();
        a.cursor = 0;
        let body = std::mem::take(&mut a.shader.body);
        a.block(&body, Rate::CONSTANT, None, false);
        a.shader.body = body;
        a.advance(usize::MAX);
    }
    a.exprs();
    a.report(diags);
}

impl Analysis<'_> {
    /// Recomputes every expression's rate from its operands (operands come first in the arena).
    fn exprs(&mut self) {
        for i in 0..self.shader.exprs.len() {
            let (rate, origin) = self.rate_of(i);
            self.shader.exprs[i].rate = rate;
            self.origins[i] = origin;
        }
    }

    /// Recomputes the rates of the expressions from the cursor up to `last` (inclusive), from the
    /// locals' rates as they are now.
    fn advance(&mut self, last: usize) {
        let end = last.saturating_add(1).min(self.shader.exprs.len());
        while self.cursor < end {
            let (rate, origin) = self.rate_of(self.cursor);
            self.shader.exprs[self.cursor].rate = rate;
            self.origins[self.cursor] = origin;
            self.cursor += 1;
        }
    }

    /// Brings the expressions `stmt` reads itself (its value, condition, indices or arguments) up
    /// to date before the walk looks at their rates.
    fn reach(&mut self, stmt: &Stmt) {
        let mut last = None;
        let mut see = |e: ExprId| last = last.max(Some(e.0 as usize));
        match stmt {
            Stmt::Store { place, value, .. } => {
                see(*value);
                let mut at = place;
                while let Place::Index(inner, index) = at {
                    see(*index);
                    at = inner;
                }
            }
            Stmt::Eval(id) | Stmt::If { cond: id, .. } | Stmt::Loop { cond: Some(id), .. } => see(*id),
            Stmt::Illuminance { args, .. } | Stmt::Emit { args, .. } => args.iter().for_each(|a| see(*a)),
            Stmt::Loop { cond: None, .. }
            | Stmt::Break(_)
            | Stmt::Continue(_)
            | Stmt::Return
            | Stmt::Inline { .. }
            | Stmt::Lights { .. } => {}
        }
        if let Some(last) = last {
            self.advance(last);
        }
    }

    fn rate_of(&self, i: usize) -> (Rate, Origin) {
        let e = &self.shader.exprs[i];
        let span = e.span;
        let join_all = |ids: &[ExprId]| -> (Rate, Origin) {
            let mut rate = Rate::CONSTANT;
            let mut origin = Origin { span, why: Why::Constant };
            for &id in ids {
                let r = self.shader.exprs[id.0 as usize].rate;
                if r.frequency > rate.frequency || (r.perlight && !rate.perlight) {
                    origin = self.origins[id.0 as usize];
                }
                rate = rate.join(r);
            }
            (rate, origin)
        };
        match &e.kind {
            ExprKind::Literal(_) => (Rate::CONSTANT, Origin { span, why: Why::Constant }),
            ExprKind::Seed(..) => (Rate::FRAGMENT, Origin { span, why: Why::Derivative }),
            ExprKind::Local(l) => {
                let local = &self.shader.locals[l.0 as usize];
                // A declared variable's rate comes from its declaration: point there.
                let origin = if local.declared {
                    Origin { span: local.span, why: Why::Declared }
                } else {
                    self.local_origins[l.0 as usize]
                };
                (local.rate, origin)
            }
            ExprKind::Global(g) => {
                (Rate { frequency: g.frequency, perlight: g.perlight }, Origin { span, why: Why::Declared })
            }
            ExprKind::Unary(_, a) | ExprKind::Convert(a) => join_all(&[*a]),
            ExprKind::LightSum { value, .. } => {
                let (rate, origin) = join_all(&[*value]);
                (Rate { perlight: false, ..rate }, origin)
            }
            ExprKind::Binary(_, a, b) | ExprKind::Index(a, b) => join_all(&[*a, *b]),
            ExprKind::Select(c, a, b) => join_all(&[*c, *a, *b]),
            ExprKind::Construct(parts) => join_all(parts),
            ExprKind::FromSpace { space, value } => {
                let (rate, origin) = join_all(&[*value]);
                // Leaving "current" needs the space's matrix, known per draw.
                if space != "current" && rate.frequency < Frequency::PrimitiveGroup {
                    (rate.join(Rate::UNIFORM), Origin { span, why: Why::Declared })
                } else {
                    (rate, origin)
                }
            }
            ExprKind::Builtin(b, args) => {
                let (rate, origin) = join_all(args);
                match b.rate {
                    RateRule::Max => (rate, origin),
                    RateRule::Derivative if rate.frequency >= Frequency::Vertex => (
                        Rate { frequency: Frequency::Fragment, perlight: rate.perlight },
                        Origin { span, why: Why::Derivative },
                    ),
                    // The derivative of a constant or per-draw value is exactly 0, at its rate.
                    RateRule::Derivative => (rate, origin),
                    RateRule::Fragment => (rate.join(Rate::FRAGMENT), Origin { span, why: Why::Fragment }),
                    RateRule::Uniform => (rate.join(Rate::UNIFORM), Origin { span, why: Why::Declared }),
                    RateRule::Lights => (rate.join(Rate::FRAGMENT), Origin { span, why: Why::Lights }),
                    RateRule::Integrate => (Rate { perlight: false, ..rate }, origin),
                }
            }
        }
    }

    fn rate(&self, id: ExprId) -> Rate {
        self.shader.exprs[id.0 as usize].rate
    }

    /// Walks statements under a control rate (conditions and loops enclosing them).
    fn block(&mut self, block: &Block, control: Rate, control_origin: Option<Span>, in_light_loop: bool) {
        for stmt in block {
            self.reach(stmt);
            match stmt {
                Stmt::Store { place, value, span } => {
                    self.store(place, *value, control, control_origin, *span, in_light_loop);
                }
                Stmt::Eval(id) => {
                    // Built-ins with output parameters write their locals at the call's rate.
                    if let ExprKind::Builtin(b, args) = &self.shader.exprs[id.0 as usize].kind {
                        let outputs: Vec<ExprId> = args
                            .iter()
                            .enumerate()
                            .filter(|(i, _)| b.param_type(*i).is_some_and(|p| p.output))
                            .map(|(_, a)| *a)
                            .collect();
                        for out in outputs {
                            if let ExprKind::Local(l) = self.shader.exprs[out.0 as usize].kind {
                                self.raise(l, *id, control, control_origin, in_light_loop);
                            }
                        }
                    }
                }
                Stmt::If { cond, then, otherwise } => {
                    let (inner, origin) = self.under(control, control_origin, *cond);
                    let saved = self.inlined.clone();
                    let cond_span = self.shader.exprs[cond.0 as usize].span;
                    self.enter(self.rate(*cond), cond_span);
                    self.push_frame(&[(self.rate(*cond), cond_span)]);
                    self.block(then, inner, origin, in_light_loop);
                    self.block(otherwise, inner, origin, in_light_loop);
                    self.frames.pop();
                    self.inlined = saved;
                }
                Stmt::Loop { cond, body, step, .. } => {
                    let (mut inner, mut origin) = match cond {
                        Some(c) => self.under(control, control_origin, *c),
                        None => (control, control_origin),
                    };
                    let saved = self.inlined.clone();
                    let mut own = Vec::new();
                    if let Some(c) = cond {
                        let span = self.shader.exprs[c.0 as usize].span;
                        self.enter(self.rate(*c), span);
                        own.push((self.rate(*c), span));
                    }
                    // A loop left under a varying condition runs a varying number of times.
                    if let Some((rate, span)) = self.exit_conditions(body, 0) {
                        if rate.frequency > inner.frequency {
                            origin = Some(span);
                        }
                        inner = inner.join(Rate { perlight: false, ..rate });
                        self.enter(rate, span);
                        own.push((rate, span));
                    }
                    self.push_frame(&own);
                    self.block(body, inner, origin, in_light_loop);
                    self.block(step, inner, origin, in_light_loop);
                    self.frames.pop();
                    self.inlined = saved;
                }
                Stmt::Inline { function, body, .. } => {
                    let (mut inner, mut origin) = (control, control_origin);
                    let saved = self.inlined.clone();
                    self.inlined.push((function.clone(), Rate::CONSTANT, None));
                    let exit = self.exit_conditions(body, u32::MAX);
                    if let Some((rate, span)) = exit {
                        if rate.frequency > inner.frequency {
                            origin = Some(span);
                        }
                        inner = inner.join(Rate { perlight: false, ..rate });
                        self.enter(rate, span);
                    }
                    self.push_frame(exit.as_slice());
                    self.block(body, inner, origin, in_light_loop);
                    self.frames.pop();
                    self.inlined = saved;
                }
                Stmt::Illuminance { args, body } | Stmt::Emit { args, body, .. } => {
                    let mut inner = control;
                    let mut origin = control_origin;
                    for a in args {
                        let r = self.rate(*a);
                        if r.frequency > inner.frequency {
                            origin = Some(self.shader.exprs[a.0 as usize].span);
                        }
                        inner = inner.join(Rate { perlight: false, ..r });
                    }
                    let lights = matches!(stmt, Stmt::Illuminance { .. });
                    let saved = self.inlined.clone();
                    let own: Vec<(Rate, Span)> =
                        args.iter().map(|a| (self.rate(*a), self.shader.exprs[a.0 as usize].span)).collect();
                    for (rate, span) in &own {
                        self.enter(*rate, *span);
                    }
                    self.push_frame(&own);
                    self.block(body, inner, origin, in_light_loop || lights);
                    self.frames.pop();
                    self.inlined = saved;
                }
                // Made after this pass (`opt::lights`): a light loop.
                Stmt::Lights { body, .. } => self.block(body, control, control_origin, true),
                Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => {}
            }
        }
    }

    /// Joins a condition of rate `rate` (at `span`) into every inlined call's control (the
    /// caller restores the frames when it leaves the condition).
    fn enter(&mut self, rate: Rate, span: Span) {
        for (_, control, origin) in &mut self.inlined {
            if rate.frequency > control.frequency {
                *origin = Some(span);
            }
            *control = control.join(Rate { perlight: false, ..rate });
        }
    }

    /// Enters a construct whose own conditions are `conds` (rate and span of each).
    fn push_frame(&mut self, conds: &[(Rate, Span)]) {
        let mut frame = (Rate::CONSTANT, None);
        for (rate, span) in conds {
            if rate.frequency > frame.0.frequency {
                frame.1 = Some(*span);
            }
            frame.0 = frame.0.join(Rate { perlight: false, ..*rate });
        }
        self.frames.push(frame);
    }

    /// The control rate of the constructs entered since `depth` (with the condition that raised it
    /// most): what a store answers to in a variable declared with `depth` constructs around it.
    fn control_since(&self, depth: usize) -> (Rate, Option<Span>) {
        let mut control = (Rate::CONSTANT, None);
        for (rate, span) in self.frames.get(depth..).unwrap_or_default() {
            if rate.frequency > control.0.frequency {
                control.1 = *span;
            }
            control.0 = control.0.join(*rate);
        }
        control
    }

    /// The control rate inside a statement conditioned on `cond`.
    fn under(&self, control: Rate, origin: Option<Span>, cond: ExprId) -> (Rate, Option<Span>) {
        let r = self.rate(cond);
        let origin = if r.frequency > control.frequency {
            Some(self.shader.exprs[cond.0 as usize].span)
        } else {
            origin
        };
        (control.join(Rate { perlight: false, ..r }), origin)
    }

    /// The highest rate of the conditions under which control leaves a construct early, with the
    /// span of that condition. `block` is the construct's body or part of it, `loops` the loops
    /// between it and the construct: `break n` and `continue n` leave the construct when `n` is
    /// more than that, and `return` always does. (An inlined body passes `u32::MAX`: only `return`
    /// leaves it.)
    fn exit_conditions(&self, block: &Block, loops: u32) -> Option<(Rate, Span)> {
        fn exits(block: &Block, loops: u32) -> bool {
            block.iter().any(|s| match s {
                Stmt::Break(n) | Stmt::Continue(n) => *n > loops,
                Stmt::Return => true,
                Stmt::If { then, otherwise, .. } => exits(then, loops) || exits(otherwise, loops),
                Stmt::Loop { body, .. }
                | Stmt::Illuminance { body, .. }
                | Stmt::Emit { body, .. }
                | Stmt::Lights { body, .. } => exits(body, loops.saturating_add(1)),
                Stmt::Inline { .. } | Stmt::Store { .. } | Stmt::Eval(_) => false,
            })
        }
        fn consider(best: &mut Option<(Rate, Span)>, found: Option<(Rate, Span)>) {
            if let Some((r, span)) = found
                && best.is_none_or(|(b, _)| r.frequency > b.frequency)
            {
                *best = Some((r, span));
            }
        }
        let mut best: Option<(Rate, Span)> = None;
        for s in block {
            match s {
                Stmt::If { cond, then, otherwise } => {
                    if exits(then, loops) || exits(otherwise, loops) {
                        consider(
                            &mut best,
                            Some((self.rate(*cond), self.shader.exprs[cond.0 as usize].span)),
                        );
                    }
                    consider(&mut best, self.exit_conditions(then, loops));
                    consider(&mut best, self.exit_conditions(otherwise, loops));
                }
                Stmt::Loop { cond, body, .. } => {
                    let inner = loops.saturating_add(1);
                    if let Some(c) = cond
                        && exits(body, inner)
                    {
                        consider(&mut best, Some((self.rate(*c), self.shader.exprs[c.0 as usize].span)));
                    }
                    consider(&mut best, self.exit_conditions(body, inner));
                }
                Stmt::Illuminance { body, .. } | Stmt::Emit { body, .. } | Stmt::Lights { body, .. } => {
                    consider(&mut best, self.exit_conditions(body, loops.saturating_add(1)));
                }
                _ => {}
            }
        }
        best
    }

    fn store(
        &mut self,
        place: &Place,
        value: ExprId,
        control: Rate,
        origin: Option<Span>,
        span: Span,
        in_light_loop: bool,
    ) {
        // Which element is written depends on the indices: they act like a condition on the store.
        let (mut control, mut origin) = (control, origin);
        let (mut index_control, mut index_origin) = (Rate::CONSTANT, None);
        let mut at = place;
        while let Place::Index(inner, index) = at {
            let r = self.rate(*index);
            let index_span = self.shader.exprs[index.0 as usize].span;
            if r.frequency > control.frequency {
                self.index_origins.insert(index_span);
                origin = Some(index_span);
            }
            if r.frequency > index_control.frequency {
                index_origin = Some(index_span);
            }
            control = control.join(Rate { perlight: false, ..r });
            index_control = index_control.join(Rate { perlight: false, ..r });
            at = inner;
        }
        let mut value_rate = self.rate(value);
        // Inside `illuminance`, storing into a variable accumulates over the lights: the variable
        // holds one value, not one per light (RenderMan's semantics).
        if in_light_loop && !self.shader.stanford {
            value_rate.perlight = false;
        }
        match root(place) {
            Target::Local(l) => {
                // A declared variable initialised where it is declared begins its life there,
                // each time control reaches the declaration, and is read only in its scope: the
                // conditions around the declaration choose which points see it, not what they
                // see. Its stores answer only to the conditions entered since (and to their own
                // indices): a `constant` counter declared and stepped inside a varying branch.
                let local = &self.shader.locals[l.0 as usize];
                if local.declared
                    && matches!(place, Place::Local(_))
                    && crate::ir::stores::is_declaration(span, local.span)
                {
                    self.declared_at[l.0 as usize] = Some(self.frames.len());
                }
                if local.declared
                    && let Some(depth) = self.declared_at[l.0 as usize]
                {
                    let (scope, scope_origin) = self.control_since(depth);
                    if scope.frequency < control.frequency {
                        control = scope.join(index_control);
                        origin = if index_control.frequency > scope.frequency {
                            index_origin
                        } else {
                            scope_origin
                        };
                    }
                }
                let local = &self.shader.locals[l.0 as usize];
                if !local.declared {
                    let new = local.rate.join(value_rate).join(control);
                    if new != local.rate {
                        let why = if value_rate.frequency >= control.frequency || origin.is_none() {
                            self.origins[value.0 as usize]
                        } else {
                            Origin { span: origin.unwrap_or(span), why: Why::Stored }
                        };
                        self.local_origins[l.0 as usize] =
                            if why.why == Why::Constant { Origin { span, why: Why::Stored } } else { why };
                        self.shader.locals[l.0 as usize].rate = new;
                        self.changed = true;
                    }
                }
                // A declared variable of an inlined function answers only to the conditions
                // inside the innermost call of that function.
                let local = &self.shader.locals[l.0 as usize];
                let (control, origin) = match self
                    .inlined
                    .iter()
                    .rev()
                    .find(|(f, _, _)| local.declared && local.function.as_ref() == Some(f))
                {
                    Some((_, inner, inner_origin)) if inner.frequency < control.frequency => {
                        (inner.join(Rate { perlight: false, ..index_control }), inner_origin.or(index_origin))
                    }
                    _ => (control, origin),
                };
                self.checks.push((Target::Local(l), value, control, origin, span));
            }
            Target::Global(g) => self.checks.push((Target::Global(g), value, control, origin, span)),
        }
    }

    /// An output argument written by a built-in.
    fn raise(&mut self, l: LocalId, call: ExprId, control: Rate, origin: Option<Span>, in_light_loop: bool) {
        let span = self.shader.exprs[call.0 as usize].span;
        self.store(&Place::Local(l), call, control, origin, span, in_light_loop);
    }

    fn report(&mut self, diags: &mut Diagnostics) {
        let stanford = self.shader.stanford;
        // RenderMan users think in uniform and varying; Stanford users in the four rates.
        let word = |rate: Rate| -> String {
            match (stanford, rate.frequency) {
                (true, _) => rate.to_string(),
                (false, Frequency::Constant) => "constant".into(),
                (false, Frequency::PrimitiveGroup) => "uniform".into(),
                (false, Frequency::Vertex | Frequency::Fragment) => "varying".into(),
            }
        };
        // Parameter defaults are evaluated on the host, once per draw.
        for p in self.shader.params.clone() {
            let local = &self.shader.locals[p.0 as usize];
            if let LocalKind::Param { default: Some(d), .. } = local.kind {
                let rate = self.rate(d);
                if rate.frequency > Frequency::PrimitiveGroup {
                    let origin = self.origins[d.0 as usize];
                    let value_span = self.shader.exprs[d.0 as usize].span;
                    let mut diag = Diagnostic::error(
                        Code::DefaultRate,
                        format!(
                            "the default of `{}` must be known once per draw, but it is {}",
                            local.name,
                            word(rate)
                        ),
                        value_span,
                        format!("this is {}", word(rate)),
                    );
                    if origin.span != value_span {
                        diag = diag.with_label(origin.span, format!("{} because of this", word(rate)));
                    }
                    diags.push(diag.with_note("defaults are computed on the host before drawing").with_help(
                        "use constants and other parameters here; compute per-point values in the body",
                    ));
                }
            }
        }
        let mut seen = std::collections::HashSet::new();
        for (target, value, control, control_origin, span) in std::mem::take(&mut self.checks) {
            let (name, declared, decl_span, is_result) = match target {
                Target::Local(l) => {
                    let local = &self.shader.locals[l.0 as usize];
                    let is_result = Some(l) == self.shader.result_local;
                    if !(local.declared || stanford && is_result) {
                        continue;
                    }
                    let declared = if is_result { Rate::FRAGMENT } else { local.rate };
                    (local.name.to_string(), declared, local.span, is_result)
                }
                Target::Global(g) => (
                    g.name.to_string(),
                    Rate { frequency: Frequency::Fragment, perlight: g.perlight },
                    span,
                    false,
                ),
            };
            let mut value_rate = self.rate(value);
            if !stanford && value_rate.perlight && !declared.perlight {
                // RenderMan per-light values exist only inside illuminance, where stores accumulate.
                value_rate.perlight = false;
            }
            let origin = self.origins[value.0 as usize];
            let value_span = self.shader.exprs[value.0 as usize].span;
            if !seen.insert((value_span, span, name.clone())) {
                continue;
            }
            // The origin earns its own label only where it is not the value itself.
            let origin_label = (origin.span != value_span).then_some(origin.span);
            let with_origin = |d: Diagnostic, text: String| match origin_label {
                Some(at) => d.with_label(at, text),
                None => d,
            };
            if value_rate.perlight && !declared.perlight {
                let what = if is_result { "the shader's result".to_string() } else { format!("`{name}`") };
                let d = Diagnostic::error(
                    Code::PerlightEscape,
                    format!("a per-light value cannot be stored in {what}"),
                    value_span,
                    "one value per light",
                );
                let target =
                    if is_result { "the shader returns one value" } else { "declared without `perlight`" };
                diags.push(
                    with_origin(d, "per-light because of this".into())
                        .with_label(decl_span, target)
                        .with_help("sum it over the lights with `integrate(...)`"),
                );
                continue;
            }
            if !value_rate.fits_in(declared) {
                let mut d = if origin.why == Why::Derivative {
                    let d = Diagnostic::error(
                        Code::DerivativeRate,
                        format!(
                            "a screen-space derivative cannot be stored in `{name}`, declared {}",
                            word(declared)
                        ),
                        value_span,
                        "derivatives exist only per fragment",
                    );
                    with_origin(d, "this derivative is per fragment".into()).with_help(format!(
                        "declare `{name}` {} (or leave its rate out); only derivatives of constant or per-draw \
                         values, which are 0, are allowed at lower rates",
                        if stanford { "fragment" } else { "varying" }
                    ))
                } else if !stanford {
                    let d = Diagnostic::error(
                        Code::VaryingToUniform,
                        format!("cannot assign a varying value to the uniform variable `{name}`"),
                        value_span,
                        "this value is varying",
                    );
                    with_origin(d, "varying because of this".into()).with_help(format!(
                        "declare `{name}` varying, or compute it from uniform values only"
                    ))
                } else {
                    let d = Diagnostic::error(
                        Code::RateTooHigh,
                        format!("cannot store a {} value in `{name}`, declared {declared}", word(value_rate)),
                        value_span,
                        format!("this value is {}", word(value_rate)),
                    );
                    with_origin(d, format!("{} because of this", word(value_rate))).with_help(format!(
                        "declare `{name}` {} or leave its rate out to let it be inferred",
                        value_rate.frequency.name()
                    ))
                };
                d = d.with_label(decl_span, format!("`{name}` is declared {} here", word(declared)));
                diags.push(d);
                continue;
            }
            if !control.fits_in(Rate { perlight: true, ..declared }) {
                let condition = control_origin.unwrap_or(span);
                let by_index = self.index_origins.contains(&condition);
                let what = if by_index { "index" } else { "condition" };
                diags.push(
                    Diagnostic::error(
                        Code::ControlDependence,
                        format!(
                            "`{name}` is declared {} but assigned {} a {} {what}",
                            word(declared),
                            if by_index { "at" } else { "under" },
                            word(control)
                        ),
                        span,
                        format!("this assignment depends on a {} {what}", word(control)),
                    )
                    .with_label(condition, format!("this {what} is {}", word(control)))
                    .with_label(decl_span, format!("`{name}` is declared {} here", word(declared)))
                    .with_help(format!(
                        "declare `{name}` {}, or make the {what} {}",
                        if stanford { control.frequency.name() } else { "varying" },
                        word(declared)
                    )),
                );
            }
        }
        // `integrate` of a value that is the same for every light is almost certainly a mistake.
        for e in &self.shader.exprs {
            if let ExprKind::Builtin(b, args) = &e.kind
                && b.rate == RateRule::Integrate
                && let Some(&arg) = args.first()
                && !self.shader.exprs[arg.0 as usize].rate.perlight
            {
                diags.push(
                    Diagnostic::warning(
                        Code::IntegrateNotPerlight,
                        "`integrate` of a value that is the same for every light",
                        self.shader.exprs[arg.0 as usize].span,
                        "not per-light",
                    )
                    .with_help("this multiplies the value by the number of lights; `integrate` is meant for perlight values"),
                );
            }
        }
    }
}
