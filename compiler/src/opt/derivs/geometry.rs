//! The chain rule for the geometric built-ins: lengths and directions, reflection, coordinate
//! transforms and matrices. (`ptlined`, `rotate`, `translate`, `scale` and `determinant` are
//! library code, `compiler/stdlib/builtins.sl`, differentiated through it.)

use super::rules::Diff;
use crate::ir::builtin::Builtin;
use crate::ir::builtin::BuiltinId;
use crate::ir::types::{Base, Type};
use crate::ir::{Axis, BinaryOp, ExprId};

impl Diff<'_> {
    /// The derivative of `transform`, `vtransform` or `ntransform` (`b`) with arguments `a`.
    pub(super) fn d_transform(&mut self, b: &'static Builtin, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        // Linear in the value: the same transform of the derivative (a point's as a vector).
        let (last, leading) = a.split_last().expect("an argument");
        let dx = self.d(*last, axis)?;
        let mut args = leading.to_vec();
        args.push(dx);
        Some(self.b.call(b.id, args))
    }

    /// The derivative of `length` (`e` the call, `a` its arguments).
    pub(super) fn d_length(&mut self, e: ExprId, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        // d|x| = (x . dx) / |x|.
        let dx = self.d(a[0], axis)?;
        let x = self.prim(a[0]);
        let dot = self.op(BinaryOp::Dot, x, dx);
        let q = self.div(dot, e);
        let nonzero = self.shared(e, 0, |s| s.positive(e));
        Some(self.guard(nonzero, q))
    }

    /// The derivative of `normalize` (`e` the call, `a` its arguments).
    pub(super) fn d_normalize(&mut self, e: ExprId, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        // n = x/|x|: dn = (dx - n (n . dx)) / |x|.
        let dx = self.d(a[0], axis)?;
        let len = self.shared(e, 0, |s| s.b.call(BuiltinId::Length, vec![a[0]]));
        let along = self.op(BinaryOp::Dot, e, dx);
        let radial = self.mul(e, along);
        let num = self.op(BinaryOp::Sub, dx, radial);
        let q = self.div(num, len);
        let nonzero = self.shared(e, 1, |s| s.positive(len));
        Some(self.guard(nonzero, q))
    }

    /// The derivative of `depth` (`e` the call, `a` its arguments).
    pub(super) fn d_depth(&mut self, e: ExprId, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        // depth is affine in the point: depth(p + dp) - depth(p) = depth(dp) - depth(0).
        let dp = self.d(a[0], axis)?;
        let point = Type::of(Base::Point);
        let at_origin = self.shared(e, 0, |s| {
            let origin = s.b.zero(point);
            s.b.call(BuiltinId::Depth, vec![origin])
        });
        let moved = self.b.convert(dp, point);
        let moved = self.b.call(BuiltinId::Depth, vec![moved]);
        Some(self.op(BinaryOp::Sub, moved, at_origin))
    }

    /// The derivative of `invert` (`e` the call, `a` its arguments).
    pub(super) fn d_invert(&mut self, e: ExprId, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        // d A⁻¹ = -A⁻¹ dA A⁻¹.
        let da = self.d(a[0], axis)?;
        let left = self.mul(e, da);
        let product = self.mul(left, e);
        Some(self.b.neg(product))
    }
}
