//! The chain rule for the built-in functions of mathematics, shaping and components (the geometric
//! ones are in `geometry.rs`). Each rule names the arguments it differentiates in [`operands`],
//! which the analysis follows; a built-in missing there has derivative 0 (the list is in the
//! module documentation of `opt::derivs`).

use std::f64::consts::PI;

use super::analysis::dtype;
use super::rules::Diff;
use crate::ir::types::{Base, Type};
use crate::ir::{Axis, BinaryOp, ExprId};
use crate::sema::builtins::Builtin;

/// The arguments whose derivatives the rule of `b` uses (none for the built-ins whose derivative
/// is taken as 0).
pub(super) fn operands(b: &Builtin, args: &[ExprId]) -> Vec<ExprId> {
    match b.name {
        "radians" | "degrees" | "sin" | "cos" | "tan" | "asin" | "acos" | "atan" | "pow" | "exp" | "sqrt"
        | "inversesqrt" | "log" | "mod" | "abs" | "min" | "max" | "clamp" | "mix" | "smoothstep"
        | "length" | "normalize" | "distance" | "reflect" | "refract" | "depth" | "rgb" | "clamp01"
        | "integrate" | "dot" | "cross" | "transpose" | "affine" | "invert" => args.to_vec(),
        "xcomp" | "ycomp" | "zcomp" | "comp" | "faceforward" => vec![args[0]],
        "transform" | "vtransform" | "ntransform" => {
            vec![*args.last().expect("an argument")]
        }
        "select" => args[1..].to_vec(),
        "spline" => args[knots(b)..].to_vec(),
        _ => Vec::new(),
    }
}

/// Whether a call's derivative is not 0 though it has no arguments (`xyz_screen`).
pub(super) fn is_source(b: &Builtin) -> bool {
    b.name == "xyz_screen"
}

/// The inputs that the derivative of a built-in's output arguments depends on: the value
/// `setxcomp`, `setycomp`, `setzcomp` and `setcomp` write (their last argument). Other outputs
/// (`lightsource`'s and `surface`'s, values of another shader) get derivative 0.
pub(super) fn output_inputs(b: &Builtin, args: &[ExprId]) -> Vec<ExprId> {
    if is_component_setter(b) { vec![*args.last().expect("a value")] } else { Vec::new() }
}

/// Whether `b` writes one component of its output argument with its last argument.
pub(super) fn is_component_setter(b: &Builtin) -> bool {
    matches!(b.name, "setxcomp" | "setycomp" | "setzcomp" | "setcomp")
}

/// Where the knots of a `spline` overload start: after the optional basis name and the parameter.
fn knots(b: &Builtin) -> usize {
    if b.params[0].ty == Type::STRING { 2 } else { 1 }
}

impl Diff<'_> {
    /// The derivative of the call `e` of `b` with arguments `a`.
    pub(super) fn call(
        &mut self,
        e: ExprId,
        b: &'static Builtin,
        a: &[ExprId],
        axis: Axis,
    ) -> Option<ExprId> {
        let ty = self.ty(e);
        let dty = dtype(ty).expect("varies");
        match (b.name, a.len()) {
            ("radians" | "degrees", _) => {
                let dx = self.d(a[0], axis)?;
                let k = self.lit(if b.name == "radians" { PI / 180.0 } else { 180.0 / PI });
                Some(self.mul(dx, k))
            }
            ("sin", _) => {
                let dx = self.d(a[0], axis)?;
                let c = self.shared(e, 0, |s| s.b.call("cos", vec![a[0]]));
                Some(self.mul(c, dx))
            }
            ("cos", _) => {
                let dx = self.d(a[0], axis)?;
                let s = self.shared(e, 0, |s| s.b.call("sin", vec![a[0]]));
                let m = self.mul(s, dx);
                Some(self.b.neg(m))
            }
            ("tan", _) => {
                // 1 + tan² = 1 / cos², from the result itself.
                let dx = self.d(a[0], axis)?;
                let k = self.shared(e, 0, |s| {
                    let (one, sq) = (s.lit(1.0), s.mul(e, e));
                    s.op(BinaryOp::Add, one, sq)
                });
                Some(self.mul(dx, k))
            }
            ("asin" | "acos", _) => {
                let dx = self.d(a[0], axis)?;
                let k = self.shared(e, 0, |s| {
                    let (one, sq) = (s.lit(1.0), s.mul(a[0], a[0]));
                    let r = s.op(BinaryOp::Sub, one, sq);
                    s.b.call("inversesqrt", vec![r])
                });
                let m = self.mul(dx, k);
                Some(if b.name == "acos" { self.b.neg(m) } else { m })
            }
            ("atan", 1) => {
                let dx = self.d(a[0], axis)?;
                let k = self.shared(e, 0, |s| {
                    let (one, sq) = (s.lit(1.0), s.mul(a[0], a[0]));
                    s.op(BinaryOp::Add, one, sq)
                });
                Some(self.div(dx, k))
            }
            ("atan", _) => {
                // atan(y, x): (x dy - y dx) / (x² + y²).
                let (y, x) = (a[0], a[1]);
                let (dy, dx) = (self.d(y, axis), self.d(x, axis));
                let t1 = dy.map(|dy| self.mul(x, dy));
                let t2 = dx.map(|dx| self.mul(y, dx));
                let num = self.sub(t1, t2)?;
                let r2 = self.shared(e, 0, |s| {
                    let (xx, yy) = (s.mul(x, x), s.mul(y, y));
                    s.op(BinaryOp::Add, xx, yy)
                });
                Some(self.div(num, r2))
            }
            ("pow", _) => self.pow(e, a[0], a[1], axis),
            ("exp", _) => {
                let dx = self.d(a[0], axis)?;
                Some(self.mul(e, dx))
            }
            ("sqrt", _) => {
                let dx = self.d(a[0], axis)?;
                let twice = self.shared(e, 0, |s| s.op(BinaryOp::Add, e, e));
                Some(self.div(dx, twice))
            }
            ("inversesqrt", _) => {
                // d x^(-1/2) = -x^(-3/2)/2 dx = -y³/2 dx.
                let dx = self.d(a[0], axis)?;
                let k = self.shared(e, 0, |s| {
                    let (yy, half) = (s.mul(e, e), s.lit(-0.5));
                    let yyy = s.mul(yy, e);
                    s.mul(half, yyy)
                });
                Some(self.mul(k, dx))
            }
            ("log", 1) => {
                let dx = self.d(a[0], axis)?;
                Some(self.div(dx, a[0]))
            }
            ("log", _) => {
                // log_b x = ln x / ln b.
                let (x, base) = (a[0], a[1]);
                let (dx, db) = (self.d(x, axis), self.d(base, axis));
                let ln_b = self.shared(e, 0, |s| s.b.call("log", vec![base]));
                let t1 = dx.map(|dx| {
                    let den = self.mul(x, ln_b);
                    self.div(dx, den)
                });
                let t2 = db.map(|db| {
                    let (num, den) = (self.mul(e, db), self.mul(base, ln_b));
                    self.div(num, den)
                });
                self.sub(t1, t2)
            }
            ("mod", _) => {
                // mod(a, b) = a - b floor(a/b).
                let (da, db) = (self.d(a[0], axis), self.d(a[1], axis));
                let t2 = db.map(|db| {
                    let f = self.shared(e, 0, |s| {
                        let q = s.div(a[0], a[1]);
                        s.b.call("floor", vec![q])
                    });
                    self.mul(f, db)
                });
                self.sub(da, t2)
            }
            ("abs", _) => {
                let dx = self.d(a[0], axis)?;
                Some(self.componentwise(dty, |s, i| {
                    let xi = s.component(a[0], i);
                    let sign = s.b.call("sign", vec![xi]);
                    let di = s.component(dx, i);
                    s.mul(sign, di)
                }))
            }
            ("min" | "max", _) => self.min_max(e, b.name == "min", a, axis),
            ("clamp", _) => self.clamp(a[0], a[1], a[2], dty, axis),
            ("mix", _) => {
                let (x, y, t) = (a[0], a[1], a[2]);
                let (dx, dy, dt) = (self.d(x, axis), self.d(y, axis), self.d(t, axis));
                let t1 = dx.map(|dx| {
                    let one_minus = self.shared(e, 0, |s| {
                        let one = s.lit(1.0);
                        s.op(BinaryOp::Sub, one, t)
                    });
                    self.mul(dx, one_minus)
                });
                let t2 = dy.map(|dy| self.mul(dy, t));
                let t3 = dt.map(|dt| {
                    let span = self.shared(e, 1, |s| {
                        let (py, px) = (s.prim(y), s.prim(x));
                        s.op(BinaryOp::Sub, py, px)
                    });
                    self.mul(span, dt)
                });
                let sum = self.add(t1, t2);
                self.add(sum, t3)
            }
            ("smoothstep", _) => self.smoothstep(e, a, axis),
            ("spline", _) => {
                let first = knots(b);
                let ds: Vec<Option<ExprId>> = a[first..].iter().map(|&k| self.d(k, axis)).collect();
                if ds.iter().all(Option::is_none) {
                    return None;
                }
                let mut args = a[..first].to_vec();
                for (&k, d) in a[first..].iter().zip(ds) {
                    args.push(self.or_zero(d, k));
                }
                Some(self.b.call("spline", args))
            }
            ("xcomp" | "ycomp" | "zcomp" | "rgb" | "transpose" | "affine" | "integrate", _) => {
                let dx = self.d(a[0], axis)?;
                Some(self.b.call(b.name, vec![dx]))
            }
            ("comp", _) => {
                let dx = self.d(a[0], axis)?;
                let mut args = a.to_vec();
                args[0] = dx;
                Some(self.b.call("comp", args))
            }
            ("clamp01", _) => {
                let dx = self.d(a[0], axis)?;
                Some(self.componentwise(dty, |s, i| {
                    let (xi, di) = (s.component(a[0], i), s.component(dx, i));
                    let inside = s.inside_unit(xi);
                    s.guard(inside, di)
                }))
            }
            ("select", _) => {
                let (dx, dy) = (self.d(a[1], axis), self.d(a[2], axis));
                if dx.is_none() && dy.is_none() {
                    return None;
                }
                let (dx, dy) = (self.or_zero(dx, a[1]), self.or_zero(dy, a[2]));
                Some(self.b.call("select", vec![a[0], dx, dy]))
            }
            ("dot" | "cross", _) => {
                let (dx, dy) = (self.d(a[0], axis), self.d(a[1], axis));
                let t1 = dx.map(|dx| self.b.call(b.name, vec![dx, a[1]]));
                let t2 = dy.map(|dy| self.b.call(b.name, vec![a[0], dy]));
                self.add(t1, t2)
            }
            ("xyz_screen", _) => {
                // x and y are the pixel coordinates themselves.
                let (x, y) = if axis == Axis::X { (1.0, 0.0) } else { (0.0, 1.0) };
                let parts = vec![self.lit(x), self.lit(y), self.lit(0.0), self.lit(0.0)];
                Some(self.b.construct(parts, Type::of(Base::Float4)))
            }
            _ => self.geometric(e, b, a, axis),
        }
    }

    /// d aᵖ = p a^(p-1) da + aᵖ ln a dp; the second term is 0 where a ≤ 0 (per component).
    fn pow(&mut self, e: ExprId, x: ExprId, p: ExprId, axis: Axis) -> Option<ExprId> {
        let ty = self.ty(e);
        let (dx, dp) = (self.d(x, axis), self.d(p, axis));
        let t1 = dx.map(|dx| {
            let k = self.shared(e, 0, |s| {
                let one = s.lit(1.0);
                let p1 = s.op(BinaryOp::Sub, p, one);
                let power = s.b.call("pow", vec![x, p1]);
                s.mul(p, power)
            });
            self.mul(k, dx)
        });
        let t2 = dp.map(|dp| {
            self.componentwise(ty, |s, i| {
                let (xi, yi, di) = (s.component(x, i), s.component(e, i), s.component(dp, i));
                let ln = s.b.call("log", vec![xi]);
                let k = s.mul(yi, ln);
                let term = s.mul(k, di);
                let positive = s.positive(xi);
                s.guard(positive, term)
            })
        });
        self.add(t1, t2)
    }

    /// min and max, pairwise from the left: the derivative of the operand that wins (the first on
    /// a tie), per component.
    fn min_max(&mut self, e: ExprId, min: bool, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        let name = if min { "min" } else { "max" };
        let mut best = a[0];
        let mut d_best = self.d(a[0], axis);
        for (k, &next) in a.iter().enumerate().skip(1) {
            let d_next = self.d(next, axis);
            if d_best.is_some() || d_next.is_some() {
                let (db, dn) = (self.or_zero(d_best, best), self.or_zero(d_next, next));
                let dty = self.ty(db);
                d_best = Some(self.componentwise(dty, |s, i| {
                    let (bi, ni) = (s.component(best, i), s.component(next, i));
                    let wins = s.op(if min { BinaryOp::Le } else { BinaryOp::Ge }, bi, ni);
                    let (dbi, dni) = (s.component(db, i), s.component(dn, i));
                    s.b.select(wins, dbi, dni)
                }));
            }
            if k + 1 < a.len() {
                best = self.shared(e, k as u8, |s| s.b.call(name, vec![best, next]));
            }
        }
        d_best
    }

    /// clamp(x, lo, hi) = min(max(x, lo), hi): the derivative of the bound that applies, per
    /// component (scalar bounds apply to every component); `hi` wins when the bounds cross.
    fn clamp(&mut self, x: ExprId, lo: ExprId, hi: ExprId, dty: Type, axis: Axis) -> Option<ExprId> {
        let (dx, dlo, dhi) = (self.d(x, axis), self.d(lo, axis), self.d(hi, axis));
        if dx.is_none() && dlo.is_none() && dhi.is_none() {
            return None;
        }
        let (dx, dlo, dhi) = (self.or_zero(dx, x), self.or_zero(dlo, lo), self.or_zero(dhi, hi));
        Some(self.componentwise(dty, |s, i| {
            let (xi, loi, hii) = (s.component(x, i), s.component(lo, i), s.component(hi, i));
            let below = s.op(BinaryOp::Lt, xi, loi);
            let (x_above, lo_above) = (s.op(BinaryOp::Gt, xi, hii), s.op(BinaryOp::Gt, loi, hii));
            let above = s.op(BinaryOp::Or, x_above, lo_above);
            let (dxi, dloi, dhii) = (s.component(dx, i), s.component(dlo, i), s.component(dhi, i));
            let inner = s.b.select(below, dloi, dxi);
            s.b.select(above, dhii, inner)
        }))
    }

    /// smoothstep(e0, e1, x) = s²(3 - 2s) with s = clamp((x - e0)/(e1 - e0), 0, 1): its derivative
    /// is 6s(1 - s) ds, and 0 where e0 = e1 (a step).
    fn smoothstep(&mut self, e: ExprId, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        let (e0, e1, x) = (a[0], a[1], a[2]);
        let ratio = self.shared(e, 0, |s| {
            let (num, den) = (s.op(BinaryOp::Sub, x, e0), s.op(BinaryOp::Sub, e1, e0));
            s.div(num, den)
        });
        let dr = self.d(ratio, axis)?;
        let slope = self.shared(e, 1, |s| {
            let (zero, one, six) = (s.lit(0.0), s.lit(1.0), s.lit(6.0));
            let clamped = s.b.call("clamp", vec![ratio, zero, one]);
            let rest = s.op(BinaryOp::Sub, one, clamped);
            let k = s.mul(six, clamped);
            s.mul(k, rest)
        });
        let value = self.mul(slope, dr);
        let distinct = self.shared(e, 2, |s| s.op(BinaryOp::Ne, e1, e0));
        Some(self.guard(distinct, value))
    }
}
