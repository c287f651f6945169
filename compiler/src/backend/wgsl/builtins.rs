//! Built-in functions in naga IR, with the interpreter's definitions (`backend/cpu/lower`) where
//! WGSL's own differ or do not exist.

use naga::{BinaryOperator as Op, Expression, MathFunction as M};

use super::body::{Translator, Value};
use crate::diag::Diagnostic;
use crate::ir::ExprId;
use crate::ir::types::{Base, Type};
use crate::sema::builtins::Builtin;

/// Which RenderMan light sum.
#[derive(Copy, Clone, PartialEq, Eq)]
enum LightTerm {
    Ambient,
    Diffuse,
    Specular,
    Phong,
}

impl Translator<'_> {
    /// A call of a built-in.
    pub(super) fn builtin(
        &mut self,
        b: &'static Builtin,
        args: &[ExprId],
        id: ExprId,
    ) -> Result<Value, Diagnostic> {
        let e = self.shader.expr(id);
        let (ret, span) = (e.ty, e.span);
        let types: Vec<Type> = args.iter().map(|a| self.shader.expr(*a).ty).collect();
        if b.name == "integrate" {
            return self.integrate(args[0], ret);
        }
        let vals: Vec<Value> = args.iter().map(|a| self.expr(*a)).collect::<Result<_, _>>()?;
        let v = |i: usize| vals[i];
        let is_int = matches!(ret.base, Base::Int | Base::Uint);
        // Arguments widened to the result's width (a scalar edge with a vector value, ...).
        let n = ret.base.components();
        let wide = |this: &mut Self, i: usize| {
            if types[i].base.components() == 1 && n > 1 && !is_int { this.splat(vals[i], n) } else { vals[i] }
        };
        Ok(match b.name {
            "radians" => self.scale(v(0), std::f64::consts::PI / 180.0),
            "degrees" => self.scale(v(0), 180.0 / std::f64::consts::PI),
            "sin" => self.math1(M::Sin, v(0)),
            "cos" => self.math1(M::Cos, v(0)),
            "tan" => self.math1(M::Tan, v(0)),
            "asin" => self.math1(M::Asin, v(0)),
            "acos" => self.math1(M::Acos, v(0)),
            "atan" if args.len() == 1 => self.math1(M::Atan, v(0)),
            "atan" => self.math2(M::Atan2, v(0), v(1)),
            "pow" => {
                let y = wide(self, 1);
                self.math2(M::Pow, v(0), y)
            }
            "exp" => self.math1(M::Exp, v(0)),
            "sqrt" => self.math1(M::Sqrt, v(0)),
            "inversesqrt" => self.math1(M::InverseSqrt, v(0)),
            "log" if args.len() == 1 => self.math1(M::Log, v(0)),
            "log" => {
                let (x, base) = (self.math1(M::Log, v(0)), self.math1(M::Log, v(1)));
                self.binary(Op::Divide, x, base)
            }
            "mod" => {
                // a - b * floor(a / b), as the interpreter (WGSL's `%` truncates instead).
                let b = wide(self, 1);
                let q = self.binary(Op::Divide, v(0), b);
                let f = self.math1(M::Floor, q);
                let p = self.binary(Op::Multiply, b, f);
                self.binary(Op::Subtract, v(0), p)
            }
            "abs" if ret.base == Base::Uint => v(0),
            "abs" => self.math1(M::Abs, v(0)),
            "sign" => self.math1(M::Sign, v(0)),
            "floor" => self.math1(M::Floor, v(0)),
            "ceil" => self.math1(M::Ceil, v(0)),
            "round" => self.math1(M::Round, v(0)),
            "min" | "max" => {
                let fun = if b.name == "min" { M::Min } else { M::Max };
                let mut acc = wide(self, 0);
                for i in 1..vals.len() {
                    let x = wide(self, i);
                    acc = self.math2(fun, acc, x);
                }
                acc
            }
            "clamp" => {
                let (lo, hi) = (wide(self, 1), wide(self, 2));
                // min(max(x, lo), hi), as the interpreter (WGSL's clamp leaves lo > hi open).
                let m = self.math2(M::Max, v(0), lo);
                self.math2(M::Min, m, hi)
            }
            "clamp01" => {
                let (zero, one) = (self.float(0.0), self.float(1.0));
                let (zero, one) = (self.splat(zero, n), self.splat(one, n));
                let m = self.math2(M::Max, v(0), zero);
                self.math2(M::Min, m, one)
            }
            "mix" => {
                // a * (1 - t) + b * t, WGSL's formula.
                let t = wide(self, 2);
                self.math3(M::Mix, v(0), v(1), t)
            }
            "step" => {
                let edge = wide(self, 0);
                self.math2(M::Step, edge, v(1))
            }
            "smoothstep" => {
                let (e0, e1) = (wide(self, 0), wide(self, 1));
                self.math3(M::SmoothStep, e0, e1, v(2))
            }
            "filterstep" if args.len() == 3 => self.filterstep_explicit(v(0), v(1), v(2)),
            "select" => self.fb.add(Expression::Select { condition: v(0), accept: v(1), reject: v(2) }),
            "xcomp" | "ycomp" | "zcomp" => {
                let i = ["xcomp", "ycomp", "zcomp"].iter().position(|c| *c == b.name).unwrap_or(0) as u32;
                self.fb.add(Expression::AccessIndex { base: v(0), index: i })
            }
            "length" => self.length(v(0)),
            "distance" => {
                let d = self.binary(Op::Subtract, v(0), v(1));
                self.length(d)
            }
            "normalize" => self.normalize(v(0)),
            "dot" => self.math2(M::Dot, v(0), v(1)),
            "cross" => self.math2(M::Cross, v(0), v(1)),
            "rgb" => self.fb.add(Expression::Swizzle {
                size: naga::VectorSize::Tri,
                vector: v(0),
                pattern: [
                    naga::SwizzleComponent::X,
                    naga::SwizzleComponent::Y,
                    naga::SwizzleComponent::Z,
                    naga::SwizzleComponent::X,
                ],
            }),
            "faceforward" => {
                let nref = match vals.get(2) {
                    Some(r) => *r,
                    None => self.global_value("Ng").unwrap_or(v(0)),
                };
                // WGSL faceForward: n where dot(i, nref) < 0, else -n.
                let d = self.math2(M::Dot, v(1), nref);
                let zero = self.float(0.0);
                let facing = self.binary(Op::Less, d, zero);
                let neg = self.fb.add(Expression::Unary { op: naga::UnaryOperator::Negate, expr: v(0) });
                self.fb.add(Expression::Select { condition: facing, accept: v(0), reject: neg })
            }
            "reflect" => self.reflect(v(0), v(1)),
            "ambient" => self.light_sum(LightTerm::Ambient, &vals)?,
            "diffuse" => self.light_sum(LightTerm::Diffuse, &vals)?,
            "specular" => self.light_sum(LightTerm::Specular, &vals)?,
            "phong" => self.light_sum(LightTerm::Phong, &vals)?,
            "specularbrdf" => {
                let l = self.normalize(v(0));
                let brdf = self.specular_brdf(l, v(1), v(2), v(3));
                self.splat(brdf, 3)
            }
            _ => {
                return Err(
                    self.error(span, format!("the built-in `{}` is not available on the GPU yet", b.name))
                );
            }
        })
    }

    fn scale(&mut self, a: Value, k: f64) -> Value {
        let k = self.float(k);
        self.binary(Op::Multiply, a, k)
    }

    /// `sqrt(v . v)`, as the interpreter.
    pub(super) fn length(&mut self, v: Value) -> Value {
        let d = self.math2(M::Dot, v, v);
        self.math1(M::Sqrt, d)
    }

    /// `v / length(v)`, as the interpreter (a zero vector gives NaN, as in WGSL).
    pub(super) fn normalize(&mut self, v: Value) -> Value {
        let len = self.length(v);
        let len = self.splat(len, 3);
        self.binary(Op::Divide, v, len)
    }

    /// `i - 2 * dot(n, i) * n`.
    pub(super) fn reflect(&mut self, i: Value, n: Value) -> Value {
        let d = self.math2(M::Dot, n, i);
        let two = self.float(2.0);
        let k = self.binary(Op::Multiply, two, d);
        let kn = self.binary(Op::Multiply, n, k);
        self.binary(Op::Subtract, i, kn)
    }

    /// The 3-argument `filterstep(edge, x0, x1)`.
    fn filterstep_explicit(&mut self, edge: Value, x0: Value, x1: Value) -> Value {
        let w = self.binary(Op::Subtract, x1, x0);
        let above = self.binary(Op::Subtract, x1, edge);
        let t = self.binary(Op::Divide, above, w);
        let (zero, one) = (self.float(0.0), self.float(1.0));
        let t = self.math2(M::Max, t, zero);
        let t = self.math2(M::Min, t, one);
        let step = self.math2(M::Step, edge, x0);
        let wide = self.binary(Op::Greater, w, zero);
        self.fb.add(Expression::Select { condition: wide, accept: t, reject: step })
    }

    /// `pow(max(0, N . normalize(L + V)), 1 / roughness)`.
    fn specular_brdf(&mut self, l: Value, n: Value, v: Value, roughness: Value) -> Value {
        let h = self.binary(Op::Add, l, v);
        let h = self.normalize(h);
        let d = self.math2(M::Dot, n, h);
        let (zero, one) = (self.float(0.0), self.float(1.0));
        let d = self.math2(M::Max, zero, d);
        let e = self.binary(Op::Divide, one, roughness);
        self.math2(M::Pow, d, e)
    }

    /// The RenderMan light sums, as the RI specification defines them with `illuminance`.
    fn light_sum(&mut self, term: LightTerm, vals: &[Value]) -> Result<Value, Diagnostic> {
        let zero = self.float(0.0);
        let mut sum = self.splat(zero, 3);
        for k in 0..self.lights.len() {
            if self.lights[k].ambient != (term == LightTerm::Ambient) {
                continue;
            }
            let outer = self.light.replace(k);
            let cl = self.global_value("Cl");
            let l = self.global_value("L");
            self.light = outer;
            let (cl, l) = (cl?, l?);
            let weight = match term {
                LightTerm::Ambient => None,
                LightTerm::Diffuse => {
                    let nl = self.normalize(l);
                    let d = self.math2(M::Dot, nl, vals[0]);
                    Some(self.math2(M::Max, zero, d))
                }
                LightTerm::Specular => {
                    let nl = self.normalize(l);
                    let facing = self.math2(M::Dot, nl, vals[0]);
                    let brdf = self.specular_brdf(nl, vals[0], vals[1], vals[2]);
                    let lit = self.binary(Op::GreaterEqual, facing, zero);
                    Some(self.fb.add(Expression::Select { condition: lit, accept: brdf, reject: zero }))
                }
                LightTerm::Phong => {
                    let n = self.normalize(vals[0]);
                    let v = self.normalize(vals[1]);
                    let minus_v = self.fb.add(Expression::Unary { op: naga::UnaryOperator::Negate, expr: v });
                    let r = self.reflect(minus_v, n);
                    let nl = self.normalize(l);
                    let facing = self.math2(M::Dot, nl, vals[0]);
                    let d = self.math2(M::Dot, r, nl);
                    let d = self.math2(M::Max, zero, d);
                    let p = self.math2(M::Pow, d, vals[2]);
                    let lit = self.binary(Op::GreaterEqual, facing, zero);
                    Some(self.fb.add(Expression::Select { condition: lit, accept: p, reject: zero }))
                }
            };
            let contribution = match weight {
                Some(w) => {
                    let w = self.splat(w, 3);
                    self.binary(Op::Multiply, cl, w)
                }
                None => cl,
            };
            sum = self.binary(Op::Add, sum, contribution);
        }
        Ok(sum)
    }

    /// Stanford's `integrate(x)`: the sum of a per-light value over the bound lights.
    fn integrate(&mut self, arg: ExprId, ret: Type) -> Result<Value, Diagnostic> {
        let zero = self.float(0.0);
        let mut sum = self.splat(zero, ret.base.components());
        for k in 0..self.lights.len() {
            let outer = self.light.replace(k);
            let x = self.expr(arg);
            self.light = outer;
            sum = self.binary(Op::Add, sum, x?);
        }
        Ok(sum)
    }
}
