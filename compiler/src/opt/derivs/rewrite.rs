//! The statements: shadow locals for the variables with derivatives, their seeds at the start of
//! the body, and a store of each derivative before every store of the variable.

use rustc_hash::FxHashMap;

use super::analysis::{Needs, Root, dtype, place_of, root};
use super::calls::is_component_setter;
use super::rules::{Diff, pick};
use crate::ir::types::{Frequency, Rate, Type};
use crate::ir::{Axis, Block, ExprId, ExprKind, Input, Local, LocalId, LocalKind, Place, Shader, Stmt};
use crate::source::Span;

const AXES: [Axis; 2] = [Axis::X, Axis::Y];

/// The shadows (d/dx, d/dy) of the locals and of the predefined variables (by name) that need
/// derivatives, added to `shader.locals`.
pub(super) type Shadows = (FxHashMap<LocalId, [LocalId; 2]>, FxHashMap<&'static str, [LocalId; 2]>);

/// Adds two shadow locals for each variable in `needs`.
pub(super) fn add_shadows(shader: &mut Shader, needs: &Needs) -> Shadows {
    let mut locals = FxHashMap::default();
    for &l in &needs.locals {
        let model = shader.locals[l.0 as usize].clone();
        locals.insert(l, add_pair(shader, model));
    }
    let mut globals = FxHashMap::default();
    for g in &needs.globals {
        let model = Local {
            name: g.name.into(),
            ty: Type::of(g.ty),
            rate: Rate::FRAGMENT,
            declared: false,
            kind: LocalKind::Temp,
            span: shader.span,
            function: None,
        };
        globals.insert(g.name, add_pair(shader, model));
    }
    (locals, globals)
}

/// Two shadows of the variable described by `model`, at fragment rate (per light if it is).
fn add_pair(shader: &mut Shader, model: Local) -> [LocalId; 2] {
    let ty = dtype(model.ty).expect("a variable with derivatives");
    ["dx", "dy"].map(|axis| {
        let id = LocalId(shader.locals.len() as u32);
        shader.locals.push(Local {
            name: format!("{axis}({})", model.name).into(),
            ty,
            rate: Rate { frequency: Frequency::Fragment, perlight: model.rate.perlight },
            declared: false,
            kind: LocalKind::Temp,
            span: model.span,
            function: model.function.clone(),
        });
        id
    })
}

impl Diff<'_> {
    /// The stores that start the body: each input's shadows from its seeds.
    pub(super) fn seeds(&mut self, needs: &Needs) -> Block {
        let mut out = Vec::new();
        let mut seed = |d: &mut Self, input: Input, ty: Type, shadows: [LocalId; 2], span: Span| {
            d.b.span = span;
            let ty = dtype(ty).expect("an input with derivatives");
            for axis in AXES {
                let value = d.b.push(ExprKind::Seed(input, axis), ty);
                out.push(Stmt::Store { place: Place::Local(pick(shadows, axis)), value, span });
            }
        };
        let span = self.b.shader.span;
        for &g in &needs.globals {
            let shadows = self.globals[g.name];
            seed(self, Input::Global(g), Type::of(g.ty), shadows, span);
        }
        for &l in &needs.locals {
            let local = self.b.shader.local(l);
            if matches!(local.kind, LocalKind::Param { .. }) {
                let (ty, span, shadows) = (local.ty, local.span, self.locals[&l]);
                seed(self, Input::Param(l), ty, shadows, span);
            }
        }
        out
    }

    /// `block` with derivative stores added, recursively.
    pub(super) fn block(&mut self, block: Block) -> Block {
        let mut out = Vec::with_capacity(block.len());
        for stmt in block {
            match stmt {
                Stmt::Store { place, value, span } => {
                    self.store_derivatives(&place, value, span, &mut out);
                    out.push(Stmt::Store { place, value, span });
                }
                Stmt::Eval(id) => {
                    self.output_derivatives(id, &mut out);
                    out.push(Stmt::Eval(id));
                }
                Stmt::If { cond, then, otherwise } => {
                    let (then, otherwise) = (self.block(then), self.block(otherwise));
                    out.push(Stmt::If { cond, then, otherwise });
                }
                Stmt::Loop { cond, body, step, span } => {
                    let (body, step) = (self.block(body), self.block(step));
                    out.push(Stmt::Loop { cond, body, step, span });
                }
                Stmt::Inline { function, body, span } => {
                    let body = self.block(body);
                    out.push(Stmt::Inline { function, body, span });
                }
                Stmt::Illuminance { args, body } => {
                    let body = self.block(body);
                    out.push(Stmt::Illuminance { args, body });
                }
                Stmt::Emit { solar, args, body } => {
                    let body = self.block(body);
                    out.push(Stmt::Emit { solar, args, body });
                }
                Stmt::Lights { lights, body } => {
                    let body = self.block(body);
                    out.push(Stmt::Lights { lights, body });
                }
                Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => out.push(stmt),
            }
        }
        out
    }

    /// The shadows of the variable `place` is part of, if it has them.
    fn shadows_of(&self, place: &Place) -> Option<[LocalId; 2]> {
        match root(place) {
            Root::Local(l) => self.locals.get(&l).copied(),
            Root::Global(name) => self.globals.get(name).copied(),
        }
    }

    /// The same part of the variable's shadow along `axis`.
    fn shadow_place(&self, place: &Place, shadows: [LocalId; 2], axis: Axis) -> Place {
        match place {
            Place::Local(_) | Place::Global(_) => Place::Local(pick(shadows, axis)),
            Place::Index(inner, i) => Place::Index(Box::new(self.shadow_place(inner, shadows, axis)), *i),
        }
    }

    /// Before `place = value`: the derivatives of `value` into the shadows (read before the
    /// variable changes, so `x = x * x` differentiates the old `x`); zeros when they are 0, since
    /// the shadow must not keep an older derivative.
    fn store_derivatives(&mut self, place: &Place, value: ExprId, span: Span, out: &mut Block) {
        let Some(shadows) = self.shadows_of(place) else { return };
        for axis in AXES {
            self.b.span = self.b.shader.expr(value).span;
            let d = self.d(value, axis);
            let d = self.or_zero(d, value);
            out.push(Stmt::Store { place: self.shadow_place(place, shadows, axis), value: d, span });
        }
    }

    /// Before a built-in writes output arguments with derivatives: the same component setter on
    /// the shadows, or zeros for other outputs (`lightsource`'s and `surface`'s).
    fn output_derivatives(&mut self, call: ExprId, out: &mut Block) {
        let expr = self.b.shader.expr(call).clone();
        let ExprKind::Builtin(b, args) = &expr.kind else { return };
        for (i, &arg) in args.iter().enumerate() {
            if !b.param_type(i).is_some_and(|p| p.output) {
                continue;
            }
            let Some(place) = place_of(self.b.shader, arg) else { continue };
            let Some(shadows) = self.shadows_of(&place) else { continue };
            for axis in AXES {
                self.b.span = expr.span;
                if is_component_setter(b) {
                    let value = *args.last().expect("a value");
                    let d = self.d(value, axis);
                    let mut shadow_args = args.clone();
                    shadow_args[i] = self.shadow_expr(arg, shadows, axis);
                    *shadow_args.last_mut().expect("a value") = self.or_zero(d, value);
                    let shadow_call = self.b.call(b.id, shadow_args);
                    out.push(Stmt::Eval(shadow_call));
                } else {
                    let zero = self.or_zero(None, arg);
                    let place = self.shadow_place(&place, shadows, axis);
                    out.push(Stmt::Store { place, value: zero, span: expr.span });
                }
            }
        }
    }

    /// The expression for the shadow of the output argument `arg` (a variable or an element).
    fn shadow_expr(&mut self, arg: ExprId, shadows: [LocalId; 2], axis: Axis) -> ExprId {
        match self.b.shader.expr(arg).kind {
            ExprKind::Index(base, i) => {
                let base = self.shadow_expr(base, shadows, axis);
                self.b.index_by(base, i)
            }
            _ => self.b.local(pick(shadows, axis)),
        }
    }
}
