//! The chain rule for the geometric built-ins: lengths and directions, the closest-point and
//! rotation functions, coordinate transforms and matrices.

use std::f64::consts::PI;

use super::rules::Diff;
use crate::ir::types::{Base, Type};
use crate::ir::{Axis, BinaryOp, ExprId};
use crate::sema::builtins::Builtin;

impl Diff<'_> {
    /// The derivative of the call `e` of the geometric built-in `b` with arguments `a`; `None` for
    /// the built-ins whose derivative is 0.
    pub(super) fn geometric(
        &mut self,
        e: ExprId,
        b: &'static Builtin,
        a: &[ExprId],
        axis: Axis,
    ) -> Option<ExprId> {
        match (b.name, a.len()) {
            ("transform" | "vtransform" | "ntransform", _) => {
                // Linear in the value: the same transform of the derivative (a point's as a vector).
                let (last, leading) = a.split_last().expect("an argument");
                let dx = self.d(*last, axis)?;
                let mut args = leading.to_vec();
                args.push(dx);
                Some(self.b.call(b.name, args))
            }
            ("length", _) => {
                // d|x| = (x . dx) / |x|.
                let dx = self.d(a[0], axis)?;
                let x = self.prim(a[0]);
                let dot = self.op(BinaryOp::Dot, x, dx);
                let q = self.div(dot, e);
                let nonzero = self.shared(e, 0, |s| s.positive(e));
                Some(self.guard(nonzero, q))
            }
            ("normalize", _) => {
                // n = x/|x|: dn = (dx - n (n . dx)) / |x|.
                let dx = self.d(a[0], axis)?;
                let len = self.shared(e, 0, |s| s.b.call("length", vec![a[0]]));
                let along = self.op(BinaryOp::Dot, e, dx);
                let radial = self.mul(e, along);
                let num = self.op(BinaryOp::Sub, dx, radial);
                let q = self.div(num, len);
                let nonzero = self.shared(e, 1, |s| s.positive(len));
                Some(self.guard(nonzero, q))
            }
            ("distance", _) => {
                let (dp, dq) = (self.d(a[0], axis), self.d(a[1], axis));
                let dd = self.sub(dp, dq)?;
                let diff = self.shared(e, 0, |s| {
                    let (p, q) = (s.prim(a[0]), s.prim(a[1]));
                    s.op(BinaryOp::Sub, p, q)
                });
                let dot = self.op(BinaryOp::Dot, diff, dd);
                let q = self.div(dot, e);
                let nonzero = self.shared(e, 1, |s| s.positive(e));
                Some(self.guard(nonzero, q))
            }
            ("ptlined", _) => self.ptlined(e, a, axis),
            ("rotate", 4) => self.rotate_point(e, a, axis),
            ("faceforward", _) => {
                // The result is N or -N: the derivative of N with the sign that was chosen.
                let dn = self.d(a[0], axis)?;
                let kept = self.shared(e, 0, |s| {
                    let (dot, zero) = (s.op(BinaryOp::Dot, e, a[0]), s.lit(0.0));
                    s.op(BinaryOp::Ge, dot, zero)
                });
                let flipped = self.b.neg(dn);
                Some(self.b.select(kept, dn, flipped))
            }
            ("reflect" | "refract", _) => {
                let expanded = self.shared(e, 0, |s| s.expand_reflect_refract(a));
                self.d(expanded, axis)
            }
            ("depth", _) => {
                // depth is affine in the point: depth(p + dp) - depth(p) = depth(dp) - depth(0).
                let dp = self.d(a[0], axis)?;
                let point = Type::of(Base::Point);
                let at_origin = self.shared(e, 0, |s| {
                    let origin = s.b.zero(point);
                    s.b.call("depth", vec![origin])
                });
                let moved = self.b.convert(dp, point);
                let moved = self.b.call("depth", vec![moved]);
                Some(self.op(BinaryOp::Sub, moved, at_origin))
            }
            ("invert", _) => {
                // d A⁻¹ = -A⁻¹ dA A⁻¹.
                let da = self.d(a[0], axis)?;
                let left = self.mul(e, da);
                let product = self.mul(left, e);
                Some(self.b.neg(product))
            }
            ("determinant", _) => {
                // Jacobi's formula: d det A = det A · trace(A⁻¹ dA); 0 where A is singular.
                let da = self.d(a[0], axis)?;
                let inverse = self.shared(e, 0, |s| s.b.call("invert", vec![a[0]]));
                let product = self.mul(inverse, da);
                let mut trace = None;
                for i in 0..4 {
                    let row = self.b.index(product, i);
                    let entry = self.b.index(row, i);
                    trace = self.add(trace, Some(entry));
                }
                let value = self.mul(e, trace.expect("four terms"));
                let regular = self.shared(e, 1, |s| {
                    let zero = s.lit(0.0);
                    s.op(BinaryOp::Ne, e, zero)
                });
                Some(self.guard(regular, value))
            }
            ("translate" | "scale", _) => self.translate_scale(b.name, a, axis),
            ("rotate", _) => {
                // Linear in the matrix; the angle's and axis's terms are left out.
                let dm = self.d(a[0], axis)?;
                Some(self.b.call("rotate", vec![dm, a[1], a[2]]))
            }
            _ => None,
        }
    }

    /// ptlined(p0, p1, q) = |q - c| with c the closest point of the segment, c = p0 + t (p1 - p0).
    /// Where t is inside (0, 1), q - c is perpendicular to the segment, so t's own change drops
    /// out; where it is clamped it does not change.
    fn ptlined(&mut self, e: ExprId, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        let (d0, d1, dq) = (self.d(a[0], axis), self.d(a[1], axis), self.d(a[2], axis));
        let t = self.shared(e, 0, |s| {
            let (p0, p1, q) = (s.prim(a[0]), s.prim(a[1]), s.prim(a[2]));
            let dir = s.op(BinaryOp::Sub, p1, p0);
            let len2 = s.op(BinaryOp::Dot, dir, dir);
            let rel = s.op(BinaryOp::Sub, q, p0);
            let along = s.op(BinaryOp::Dot, rel, dir);
            let ratio = s.div(along, len2);
            let (zero, one) = (s.lit(0.0), s.lit(1.0));
            let clamped = s.b.call("clamp", vec![ratio, zero, one]);
            let long = s.positive(len2);
            s.guard(long, clamped)
        });
        let offset = self.shared(e, 1, |s| {
            let (p0, p1, q) = (s.prim(a[0]), s.prim(a[1]), s.prim(a[2]));
            let dir = s.op(BinaryOp::Sub, p1, p0);
            let along = s.mul(t, dir);
            let closest = s.op(BinaryOp::Add, p0, along);
            s.op(BinaryOp::Sub, q, closest)
        });
        let moved = self.sub(dq, d0);
        let slide = self.sub(d1, d0).map(|d| self.mul(t, d));
        let relative = self.sub(moved, slide)?;
        let dot = self.op(BinaryOp::Dot, offset, relative);
        let q = self.div(dot, e);
        let nonzero = self.shared(e, 2, |s| s.positive(e));
        Some(self.guard(nonzero, q))
    }

    /// rotate(q, angle, p0, p1) = p0 + R (q - p0), R the rotation about the axis p1 - p0, of
    /// direction k. Written with the built-in itself, so that it holds whichever way the rotation
    /// turns: with v = q - p0 and v∥ = k (k.v),
    /// - q and p0 move the point rotated: R (dq - dp0) + dp0 (R about the origin);
    /// - the angle: d/dθ R v = R_{θ+π/2} v - v∥;
    /// - the axis's direction (dk = the part of d(p1 - p0) across k, over |p1 - p0|): with
    ///   S(w) = R w - k (k.w) - cos θ (w - k (k.w)) = ± sin θ (k ^ w), the rotation's own sine
    ///   part, dR v = (1 - cos θ) (dk (k.v) + k (dk.v)) - (k.v) S(dk) - k (dk . S(v)).
    fn rotate_point(&mut self, e: ExprId, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        let (q, angle, p0, p1) = (a[0], a[1], a[2], a[3]);
        let (dq, dangle) = (self.d(q, axis), self.d(angle, axis));
        let (dp0, dp1) = (self.d(p0, axis), self.d(p1, axis));
        let vector = Type::of(Base::Vector);
        let k = self.shared(e, 0, |s| {
            let dir = s.op(BinaryOp::Sub, p1, p0);
            s.b.call("normalize", vec![dir])
        });
        let v = self.shared(e, 1, |s| s.op(BinaryOp::Sub, q, p0));
        let kv = self.shared(e, 2, |s| s.op(BinaryOp::Dot, k, v));
        let moved = self.sub(dq, dp0).map(|w| self.rotated(e, a, w));
        let turning = dangle.map(|da| {
            let rate = self.shared(e, 3, |s| {
                let quarter = s.lit(PI / 2.0);
                let ahead = s.op(BinaryOp::Add, angle, quarter);
                let turned = s.b.call("rotate", vec![q, ahead, p0, p1]);
                let from_p0 = s.op(BinaryOp::Sub, turned, p0);
                let parallel = s.mul(k, kv);
                s.op(BinaryOp::Sub, from_p0, parallel)
            });
            self.mul(rate, da)
        });
        let tilt = self.sub(dp1, dp0).map(|du| {
            let len = self.shared(e, 4, |s| {
                let dir = s.op(BinaryOp::Sub, p1, p0);
                s.b.call("length", vec![dir])
            });
            let (k_du, one) = (self.op(BinaryOp::Dot, k, du), self.lit(1.0));
            let along = self.mul(k, k_du);
            let across = self.op(BinaryOp::Sub, du, along);
            let dk = self.div(across, len);
            let cos = self.shared(e, 5, |s| s.b.call("cos", vec![angle]));
            let one_minus_cos = self.op(BinaryOp::Sub, one, cos);
            let (dk_kv, dk_v) = (self.mul(dk, kv), self.op(BinaryOp::Dot, dk, v));
            let k_dk_v = self.mul(k, dk_v);
            let sum = self.op(BinaryOp::Add, dk_kv, k_dk_v);
            let bend = self.mul(one_minus_cos, sum);
            let s_dk = self.sine_part(e, a, dk, k, cos);
            let s_v = self.shared(e, 6, |s| s.sine_part(e, a, v, k, cos));
            let t1 = self.mul(kv, s_dk);
            let dk_sv = self.op(BinaryOp::Dot, dk, s_v);
            let t2 = self.mul(k, dk_sv);
            let rest = self.op(BinaryOp::Sub, bend, t1);
            self.op(BinaryOp::Sub, rest, t2)
        });
        let sum = self.add(moved, dp0);
        let sum = self.add(sum, turning);
        let total = self.add(sum, tilt)?;
        Some(self.b.convert(total, vector))
    }

    /// The vector `w` rotated as `rotate(e)` rotates, about the origin.
    fn rotated(&mut self, e: ExprId, a: &[ExprId], w: ExprId) -> ExprId {
        let point = Type::of(Base::Point);
        let axis_point = self.shared(e, 7, |s| {
            let dir = s.op(BinaryOp::Sub, a[3], a[2]);
            s.b.convert(dir, point)
        });
        let origin = self.shared(e, 8, |s| s.b.zero(point));
        let w = self.b.convert(w, point);
        let turned = self.b.call("rotate", vec![w, a[1], origin, axis_point]);
        self.b.convert(turned, Type::of(Base::Vector))
    }

    /// S(w) = R w - k (k.w) - cos θ (w - k (k.w)): the sine part of the rotation of `e`.
    fn sine_part(&mut self, e: ExprId, a: &[ExprId], w: ExprId, k: ExprId, cos: ExprId) -> ExprId {
        let turned = self.rotated(e, a, w);
        let kw = self.op(BinaryOp::Dot, k, w);
        let parallel = self.mul(k, kw);
        let across = self.op(BinaryOp::Sub, w, parallel);
        let cos_across = self.mul(cos, across);
        let rest = self.op(BinaryOp::Sub, turned, parallel);
        self.op(BinaryOp::Sub, rest, cos_across)
    }

    /// reflect(I, N) = I - 2 (I.N) N and refract(I, N, eta) as RenderMan defines them, written out
    /// so that the general rules differentiate them.
    fn expand_reflect_refract(&mut self, a: &[ExprId]) -> ExprId {
        let vector = Type::of(Base::Vector);
        let (i, n) = (a[0], self.b.convert(a[1], vector));
        let cos = self.op(BinaryOp::Dot, i, n);
        if a.len() == 2 {
            let two = self.lit(2.0);
            let k = self.mul(two, cos);
            let back = self.mul(k, n);
            return self.op(BinaryOp::Sub, i, back);
        }
        let eta = a[2];
        let one = self.lit(1.0);
        let cos2 = self.mul(cos, cos);
        let sin2 = self.op(BinaryOp::Sub, one, cos2);
        let eta2 = self.mul(eta, eta);
        let s2 = self.mul(eta2, sin2);
        let k = self.op(BinaryOp::Sub, one, s2);
        let bent = self.mul(eta, i);
        let root = self.b.call("sqrt", vec![k]);
        let eta_cos = self.mul(eta, cos);
        let normal_part = self.op(BinaryOp::Add, eta_cos, root);
        let along = self.mul(normal_part, n);
        let refracted = self.op(BinaryOp::Sub, bent, along);
        let zero = self.lit(0.0);
        let total = self.op(BinaryOp::Lt, k, zero);
        let none = self.b.zero(vector);
        self.b.select(total, none, refracted)
    }

    /// translate(M, v) = M T(v) and scale(M, s) = M S(s): linear in M; for the vector,
    /// M (T(v + dv) - T(v)) = translate(M, dv) - M and M (S(s + ds) - S(s)) = scale(M, ds) -
    /// scale(M, 0).
    fn translate_scale(&mut self, name: &str, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        let (m, v) = (a[0], a[1]);
        let (dm, dv) = (self.d(m, axis), self.d(v, axis));
        let t1 = dm.map(|dm| self.b.call(name, vec![dm, v]));
        let t2 = dv.map(|dv| {
            let param = self.ty(v);
            let dv = self.b.convert(dv, param);
            let moved = self.b.call(name, vec![m, dv]);
            let base = if name == "translate" {
                m
            } else {
                let zero = self.b.zero(param);
                self.b.call(name, vec![m, zero])
            };
            self.op(BinaryOp::Sub, moved, base)
        });
        self.add(t1, t2)
    }
}
