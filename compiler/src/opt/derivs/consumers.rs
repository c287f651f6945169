//! The derivative built-ins, rewritten in place as arithmetic on screen derivatives.
//!
//! With dX(x), dY(x) the derivatives along the raster axes and du_X, dv_X, du_Y, dv_Y those of the
//! surface parameters, the chain rule dX(x) = Du(x) du_X + Dv(x) dv_X (and the same along y) is a
//! 2x2 system whose determinant is det = du_X dv_Y - du_Y dv_X; solving it gives `Du` and `Dv`.

use super::rules::{Diff, pick};
use crate::ir::builtin::BuiltinId;
use crate::ir::types::{Base, Frequency, Type};
use crate::ir::{Axis, BinaryOp, ExprId, ExprKind, LocalId};

/// The shadows of `u` and `v`, when the shader has them.
#[derive(Copy, Clone)]
pub(super) struct SurfaceParams {
    /// d/dx and d/dy of `u`.
    pub u: [LocalId; 2],
    /// d/dx and d/dy of `v`.
    pub v: [LocalId; 2],
}

impl Diff<'_> {
    /// Overwrites the consumer `c` with its replacement; its type is kept.
    pub(super) fn replace(&mut self, c: ExprId, uv: Option<SurfaceParams>) {
        let expr = self.b.shader.expr(c).clone();
        let ExprKind::Builtin(b, args) = &expr.kind else { unreachable!("a consumer is a call") };
        self.b.span = expr.span;
        let ty = expr.ty;
        // A consumer of a constant or per-draw value is exactly 0.
        let uniform = |s: &Self, x: ExprId| s.b.rate(x).frequency < Frequency::Vertex;
        let replacement = match b.id {
            BuiltinId::FilterStep if uniform(self, args[1]) => self.b.call(BuiltinId::Step, args.clone()),
            BuiltinId::FilterStep => self.filterstep(args[0], args[1]),
            BuiltinId::Deriv if uniform(self, args[0]) || uniform(self, args[1]) => self.b.zero(ty),
            BuiltinId::Deriv => self.deriv(args[0], args[1], ty, uv),
            _ if uniform(self, args[0]) => self.b.zero(ty),
            BuiltinId::Du | BuiltinId::Dv => {
                let which = if b.id == BuiltinId::Du { 0 } else { 1 };
                match self.surface(args[0], uv, which) {
                    Some(value) => value,
                    None => self.b.zero(ty),
                }
            }
            BuiltinId::FilterWidth => self.filterwidth(args[0]),
            BuiltinId::Area => match self.screen(args[0]) {
                Some((dx, dy)) => {
                    let n = self.b.binary(BinaryOp::Cross, dx, dy);
                    self.b.call(BuiltinId::Length, vec![n])
                }
                None => self.b.zero(ty),
            },
            BuiltinId::CalculateNormal => self.calculatenormal(args[0], ty, uv),
            other => unreachable!("`{other}` is not a consumer"),
        };
        self.become_(c, replacement);
    }

    /// Gives `c` the kind of `r` (built for it, of its type).
    fn become_(&mut self, c: ExprId, r: ExprId) {
        let exprs = &mut self.b.shader.exprs;
        assert_eq!(exprs[c.0 as usize].ty, exprs[r.0 as usize].ty, "a replacement keeps the type");
        let kind = exprs[r.0 as usize].kind.clone();
        exprs[c.0 as usize].kind = kind;
        // The root was built last for this purpose and nothing refers to it.
        if r.0 as usize + 1 == exprs.len() {
            exprs.pop();
        }
    }

    /// dX(x) and dY(x), zeros in place of a missing one; `None` when both are 0.
    fn screen(&mut self, x: ExprId) -> Option<(ExprId, ExprId)> {
        let (dx, dy) = (self.d(x, Axis::X), self.d(x, Axis::Y));
        if dx.is_none() && dy.is_none() {
            return None;
        }
        Some((self.or_zero(dx, x), self.or_zero(dy, x)))
    }

    /// The derivative of `u` or `v` (`[u, v]`'s index `which`) along `axis`.
    fn param(&mut self, uv: SurfaceParams, which: usize, axis: Axis) -> ExprId {
        let shadows = if which == 0 { uv.u } else { uv.v };
        self.b.local(pick(shadows, axis))
    }

    /// The determinant of the screen-to-surface-parameter Jacobian.
    fn det(&mut self, uv: SurfaceParams) -> ExprId {
        let (ux, vy) = (self.param(uv, 0, Axis::X), self.param(uv, 1, Axis::Y));
        let (uy, vx) = (self.param(uv, 0, Axis::Y), self.param(uv, 1, Axis::X));
        let (a, b) = (self.b.binary(BinaryOp::Mul, ux, vy), self.b.binary(BinaryOp::Mul, uy, vx));
        self.b.binary(BinaryOp::Sub, a, b)
    }

    /// `det != 0`.
    fn regular(&mut self, det: ExprId) -> ExprId {
        let zero = self.b.float(0.0);
        self.b.binary(BinaryOp::Ne, det, zero)
    }

    /// `Du(x)` (`which` = 0) or `Dv(x)` (1), 0 where the determinant is; `None` when it is 0
    /// everywhere.
    fn surface(&mut self, x: ExprId, uv: Option<SurfaceParams>, which: usize) -> Option<ExprId> {
        let uv = uv?;
        let (dx, dy) = (self.d(x, Axis::X), self.d(x, Axis::Y));
        if dx.is_none() && dy.is_none() {
            return None;
        }
        // Du = (dX dv_Y - dY dv_X) / det, Dv = (du_X dY - du_Y dX) / det.
        let other = 1 - which;
        let t1 = dx.map(|dx| {
            let k = self.param(uv, other, Axis::Y);
            self.b.binary(BinaryOp::Mul, dx, k)
        });
        let t2 = dy.map(|dy| {
            let k = self.param(uv, other, Axis::X);
            self.b.binary(BinaryOp::Mul, dy, k)
        });
        let num = if which == 0 { self.sub(t1, t2) } else { self.sub(t2, t1) };
        let num = num.expect("one of the terms is there");
        let det = self.det(uv);
        let q = self.b.binary(BinaryOp::Div, num, det);
        let regular = self.regular(det);
        let zero = self.b.zero(self.ty(q));
        Some(self.b.select(regular, q, zero))
    }

    /// `Deriv(num, den) = Du(num)/Du(den) + Dv(num)/Dv(den)`, each term 0 where its denominator
    /// is.
    fn deriv(&mut self, num: ExprId, den: ExprId, ty: Type, uv: Option<SurfaceParams>) -> ExprId {
        let mut sum = None;
        for which in 0..2 {
            let (Some(n), Some(d)) = (self.surface(num, uv, which), self.surface(den, uv, which)) else {
                continue;
            };
            let q = self.b.binary(BinaryOp::Div, n, d);
            let zero = self.b.float(0.0);
            let nonzero = self.b.binary(BinaryOp::Ne, d, zero);
            let zero = self.b.zero(self.ty(q));
            let term = self.b.select(nonzero, q, zero);
            sum = self.add(sum, Some(term));
        }
        match sum {
            Some(sum) => self.b.convert(sum, ty),
            None => self.b.zero(ty),
        }
    }

    /// `filterwidth(x) = |dX(x)| + |dY(x)|`.
    fn filterwidth(&mut self, x: ExprId) -> ExprId {
        let mut sum = None;
        for axis in [Axis::X, Axis::Y] {
            if let Some(d) = self.d(x, axis) {
                let t = self.b.call(BuiltinId::Abs, vec![d]);
                sum = self.add(sum, Some(t));
            }
        }
        sum.unwrap_or_else(|| self.b.float(0.0))
    }

    /// `filterstep(edge, x)`: the step box-filtered over [x - w/2, x + w/2], w = filterwidth(x),
    /// which is `clamp((x - edge)/w + 1/2, 0, 1)`; the plain step where w = 0.
    fn filterstep(&mut self, edge: ExprId, x: ExprId) -> ExprId {
        let w = self.filterwidth(x);
        let step = self.b.call(BuiltinId::Step, vec![edge, x]);
        if matches!(self.b.shader.expr(w).kind, ExprKind::Literal(_)) {
            return step;
        }
        let offset = self.b.binary(BinaryOp::Sub, x, edge);
        let ratio = self.b.binary(BinaryOp::Div, offset, w);
        let half = self.b.float(0.5);
        let centred = self.b.binary(BinaryOp::Add, ratio, half);
        let (zero, one) = (self.b.float(0.0), self.b.float(1.0));
        let filtered = self.b.call(BuiltinId::Clamp, vec![centred, zero, one]);
        let zero = self.b.float(0.0);
        let wide = self.b.binary(BinaryOp::Gt, w, zero);
        self.b.select(wide, filtered, step)
    }

    /// `calculatenormal(p) = Du(p) ^ Dv(p)`, which is `(dX(p) ^ dY(p)) / det`; where det = 0
    /// (or there are no surface parameters) the screen-space normal `dX(p) ^ dY(p)`.
    fn calculatenormal(&mut self, p: ExprId, ty: Type, uv: Option<SurfaceParams>) -> ExprId {
        let Some((dx, dy)) = self.screen(p) else { return self.b.zero(ty) };
        let n = self.b.binary(BinaryOp::Cross, dx, dy);
        let n = match uv {
            Some(uv) => {
                let det = self.det(uv);
                let scaled = self.b.binary(BinaryOp::Div, n, det);
                let regular = self.regular(det);
                self.b.select(regular, scaled, n)
            }
            None => n,
        };
        debug_assert_eq!(ty.base, Base::Normal);
        self.b.convert(n, ty)
    }
}
