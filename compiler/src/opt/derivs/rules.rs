//! The chain rule for each kind of expression. `Diff::d(e, axis)` builds the derivative of `e` along
//! one screen axis, as an expression to be evaluated where `e` is: variables' derivatives are read
//! from their shadow locals, which the rewritten statements keep in step with the variables.
//!
//! `None` stands for a derivative that is exactly 0; no arithmetic is generated for it. Built-in
//! functions have their rules in `calls.rs` and `geometry.rs`.

use rustc_hash::{FxHashMap, FxHashSet};

use super::analysis::{dtype, varies};
use crate::ir::types::{Base, Type};
use crate::ir::{Axis, BinaryOp, ExprId, ExprKind, LocalId, UnaryOp};
use crate::opt::build::Builder;

/// The derivative builder: shadows of the variables, memoised derivatives, and the arena.
pub(super) struct Diff<'s> {
    /// Appends the derivative expressions.
    pub b: Builder<'s>,
    /// The shadows (d/dx, d/dy) of each local with derivatives.
    pub locals: FxHashMap<LocalId, [LocalId; 2]>,
    /// The shadows of each predefined variable with derivatives, by name.
    pub globals: FxHashMap<&'static str, [LocalId; 2]>,
    /// Expressions whose derivative is 0 by definition: the derivative consumers (there are no
    /// second derivatives), whose kinds are overwritten by their replacements.
    pub consumers: FxHashSet<ExprId>,
    /// Per expression of the shader as given: whether its derivative can be non-zero (expressions
    /// built later are judged by their operands).
    pub active: Vec<bool>,
    memo: FxHashMap<(ExprId, Axis), Option<ExprId>>,
    /// Values a rule computes from the primal operands, built once for both axes: keyed by the
    /// expression differentiated and a number the rule chooses.
    shared: FxHashMap<(ExprId, u8), ExprId>,
}

/// The shadow of a variable along `axis`.
pub(super) fn pick(shadows: [LocalId; 2], axis: Axis) -> LocalId {
    match axis {
        Axis::X => shadows[0],
        Axis::Y => shadows[1],
    }
}

impl<'s> Diff<'s> {
    /// A derivative builder over `b`'s shader.
    pub fn new(b: Builder<'s>) -> Diff<'s> {
        Diff {
            b,
            locals: FxHashMap::default(),
            globals: FxHashMap::default(),
            consumers: FxHashSet::default(),
            active: Vec::new(),
            memo: FxHashMap::default(),
            shared: FxHashMap::default(),
        }
    }

    /// The type of `e`.
    pub fn ty(&self, e: ExprId) -> Type {
        self.b.ty(e)
    }

    /// The value `build` makes, made once for the rule of `e` (slot `slot`) and reused for the
    /// other axis.
    pub fn shared(&mut self, e: ExprId, slot: u8, build: impl FnOnce(&mut Self) -> ExprId) -> ExprId {
        if let Some(&known) = self.shared.get(&(e, slot)) {
            return known;
        }
        let made = build(self);
        self.shared.insert((e, slot), made);
        made
    }

    /// The derivative of `e` along `axis`; `None` when it is 0.
    pub fn d(&mut self, e: ExprId, axis: Axis) -> Option<ExprId> {
        if let Some(&known) = self.memo.get(&(e, axis)) {
            return known;
        }
        // Expression trees are as deep as the source's operator chains.
        let found = stacker::maybe_grow(64 * 1024, 1024 * 1024, || self.d_here(e, axis));
        self.memo.insert((e, axis), found);
        found
    }

    fn d_here(&mut self, e: ExprId, axis: Axis) -> Option<ExprId> {
        let expr = self.b.shader.expr(e);
        let inactive = self.active.get(e.0 as usize).is_some_and(|a| !a);
        if inactive || !varies(expr.ty, expr.rate) || self.consumers.contains(&e) {
            return None;
        }
        let (kind, ty, span) = (expr.kind.clone(), expr.ty, expr.span);
        // New expressions point at the source of what they differentiate.
        let outer = std::mem::replace(&mut self.b.span, span);
        let found = match kind {
            ExprKind::Literal(_) | ExprKind::Seed(..) => None,
            ExprKind::Local(l) => self.locals.get(&l).map(|&s| self.b.local(pick(s, axis))),
            ExprKind::Global(g) => self.globals.get(g.name).map(|&s| self.b.local(pick(s, axis))),
            ExprKind::Unary(UnaryOp::Neg, a) => self.d(a, axis).map(|da| self.b.neg(da)),
            ExprKind::Unary(..) => None,
            ExprKind::Binary(op, a, b) => self.binary(e, op, a, b, axis),
            ExprKind::Convert(a) => self.convert(a, ty, axis),
            ExprKind::Construct(parts) => {
                let ds: Vec<Option<ExprId>> = parts.iter().map(|&p| self.d(p, axis)).collect();
                if ds.iter().all(Option::is_none) {
                    None
                } else {
                    let parts = parts.iter().zip(ds).map(|(&p, d)| self.or_zero(d, p)).collect();
                    let dty = dtype(ty).expect("varies");
                    Some(self.b.construct(parts, dty))
                }
            }
            // Colours never come here: their spaces are converted by library code.
            ExprKind::FromSpace { space, value } => {
                let dv = self.d(value, axis)?;
                Some(self.b.from_space(space, dv))
            }
            ExprKind::Index(base, index) => self.d(base, axis).map(|db| self.b.index_by(db, index)),
            ExprKind::Select(c, a, b) => {
                let (da, db) = (self.d(a, axis), self.d(b, axis));
                if da.is_none() && db.is_none() {
                    None
                } else {
                    let (da, db) = (self.or_zero(da, a), self.or_zero(db, b));
                    Some(self.b.select(c, da, db))
                }
            }
            ExprKind::Builtin(b, args) => self.call(e, b, &args, axis),
            // Made after this pass, by `opt::lights`.
            ExprKind::LightSum { .. } => None,
        };
        self.b.span = outer;
        found
    }

    /// Binary operators: sums, products (componentwise or matrix, in the operands' order), and
    /// quotients; comparisons and integer operations have no derivative.
    fn binary(&mut self, e: ExprId, op: BinaryOp, a: ExprId, b: ExprId, axis: Axis) -> Option<ExprId> {
        match op {
            BinaryOp::Add => {
                let (da, db) = (self.d(a, axis), self.d(b, axis));
                self.add(da, db)
            }
            BinaryOp::Sub => {
                let (da, db) = (self.d(a, axis), self.d(b, axis));
                self.sub(da, db)
            }
            BinaryOp::Mul | BinaryOp::Dot | BinaryOp::Cross => {
                let (da, db) = (self.d(a, axis), self.d(b, axis));
                let left = da.map(|da| {
                    let b = self.prim(b);
                    self.b.binary(op, da, b)
                });
                let right = db.map(|db| {
                    let a = self.prim(a);
                    self.b.binary(op, a, db)
                });
                self.add(left, right)
            }
            BinaryOp::Div => {
                // d(a/b) = (da - (a/b) db) / b, reusing the quotient itself. For a matrix divisor,
                // a / B = a B⁻¹ and the same formula holds with `*` the matrix product.
                let (da, db) = (self.d(a, axis), self.d(b, axis));
                let q_db = db.map(|db| {
                    let q = self.prim(e);
                    self.b.binary(BinaryOp::Mul, q, db)
                });
                let num = self.sub(da, q_db)?;
                let b = self.prim(b);
                Some(self.b.binary(BinaryOp::Div, num, b))
            }
            _ => None,
        }
    }

    /// Conversions are linear, except to `clampf`, which clamps: its derivative is 0 outside
    /// (0, 1).
    fn convert(&mut self, a: ExprId, to: Type, axis: Axis) -> Option<ExprId> {
        let da = self.d(a, axis)?;
        let dty = dtype(to).expect("varies");
        if to.base == Base::Clampf && !to.is_array() {
            let inside = self.inside_unit(a);
            let zero = self.b.float(0.0);
            let da = self.b.convert(da, dty);
            return Some(self.b.select(inside, da, zero));
        }
        Some(self.b.convert(da, dty))
    }

    /// A float literal.
    pub fn lit(&mut self, v: f64) -> ExprId {
        self.b.float(v)
    }

    /// `a op b` (see [`Builder::binary`] for the conversions).
    pub fn op(&mut self, op: BinaryOp, a: ExprId, b: ExprId) -> ExprId {
        self.b.binary(op, a, b)
    }

    /// `a * b`.
    pub fn mul(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.b.binary(BinaryOp::Mul, a, b)
    }

    /// `a / b`.
    pub fn div(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.b.binary(BinaryOp::Div, a, b)
    }

    /// `cond ? value : 0`.
    pub fn guard(&mut self, cond: ExprId, value: ExprId) -> ExprId {
        let zero = self.b.zero(self.ty(value));
        self.b.select(cond, value, zero)
    }

    /// `x > 0`, for guarding a division by `x`.
    pub fn positive(&mut self, x: ExprId) -> ExprId {
        let zero = self.lit(0.0);
        self.op(BinaryOp::Gt, x, zero)
    }

    /// `0 < x && x < 1` for a scalar `x`.
    pub fn inside_unit(&mut self, x: ExprId) -> ExprId {
        let zero = self.b.float(0.0);
        let one = self.b.float(1.0);
        let above = self.b.binary(BinaryOp::Lt, zero, x);
        let below = self.b.binary(BinaryOp::Lt, x, one);
        self.b.binary(BinaryOp::And, above, below)
    }

    /// `e` read as its derivative's type (a point as a vector, a `clampf` as a float), to combine
    /// with derivatives.
    pub fn prim(&mut self, e: ExprId) -> ExprId {
        let ty = self.ty(e);
        match dtype(ty) {
            Some(dty) if dty != ty => self.b.convert(e, dty),
            _ => e,
        }
    }

    /// `d`, or a zero of the type of `like`'s derivative.
    pub fn or_zero(&mut self, d: Option<ExprId>, like: ExprId) -> ExprId {
        match d {
            Some(d) => d,
            None => {
                let ty = dtype(self.ty(like)).expect("a value with a derivative type");
                self.b.zero(ty)
            }
        }
    }

    /// The sum of two derivatives.
    pub fn add(&mut self, a: Option<ExprId>, b: Option<ExprId>) -> Option<ExprId> {
        match (a, b) {
            (Some(a), Some(b)) => Some(self.b.binary(BinaryOp::Add, a, b)),
            (a, b) => a.or(b),
        }
    }

    /// The difference of two derivatives.
    pub fn sub(&mut self, a: Option<ExprId>, b: Option<ExprId>) -> Option<ExprId> {
        match (a, b) {
            (Some(a), Some(b)) => Some(self.b.binary(BinaryOp::Sub, a, b)),
            (Some(a), None) => Some(a),
            (None, Some(b)) => Some(self.b.neg(b)),
            (None, None) => None,
        }
    }

    /// Component `i` of `e`, or `e` itself when it is a scalar (or `i` is `None`): lets one rule
    /// serve scalars and vectors, and scalar bounds of vector functions.
    pub fn component(&mut self, e: ExprId, i: Option<u32>) -> ExprId {
        match i {
            Some(i) if self.ty(e).base.components() > 1 => self.b.index(e, i),
            _ => e,
        }
    }

    /// A value of type `ty` computed component by component by `f` (called with `None` for a
    /// scalar type).
    pub fn componentwise(&mut self, ty: Type, mut f: impl FnMut(&mut Self, Option<u32>) -> ExprId) -> ExprId {
        let n = ty.base.components();
        if n == 1 {
            return f(self, None);
        }
        let parts = (0..n).map(|i| f(self, Some(i))).collect();
        self.b.construct(parts, ty)
    }
}
