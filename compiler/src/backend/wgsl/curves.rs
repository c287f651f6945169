//! `spline([basis,] x, k0, k1, k2, k3, ...)` and `spline([basis,] x, T[])`, with the
//! interpreter's definition (`backend/cpu/lower/curves.rs`): `x` clamped to [0, 1] and spread
//! over the segments, each a cubic in the local parameter weighted by the basis matrix (Horner
//! per knot, the knots' terms summed in order). With several segments the knots go into a
//! per-invocation array and the segment's four are read by a run-time index.

use naga::{BinaryOperator as Op, Expression, MathFunction as M};

use super::body::{Translator, Value};
use crate::diag::{Code, Diagnostic};
use crate::ir::ExprId;
use crate::ir::types::{Base, Type};
use crate::source::Span;

/// A spline basis: rows are the coefficients of t^3, t^2, t and 1, column j weighs knot j; and
/// the step between the first knots of consecutive segments.
struct Basis {
    matrix: [[f64; 4]; 4],
    step: u32,
}

/// The basis called `name` (the matrices of `RiBasis`, as the interpreter lists them).
fn basis(name: &str) -> Option<Basis> {
    let (matrix, step) = match name {
        "catmull-rom" => {
            ([[-0.5, 1.5, -1.5, 0.5], [1.0, -2.5, 2.0, -0.5], [-0.5, 0.0, 0.5, 0.0], [0.0, 1.0, 0.0, 0.0]], 1)
        }
        "bezier" => {
            ([[-1.0, 3.0, -3.0, 1.0], [3.0, -6.0, 3.0, 0.0], [-3.0, 3.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]], 3)
        }
        "bspline" => {
            let s = 1.0 / 6.0;
            (
                [
                    [-s, 3.0 * s, -3.0 * s, s],
                    [3.0 * s, -6.0 * s, 3.0 * s, 0.0],
                    [-3.0 * s, 0.0, 3.0 * s, 0.0],
                    [s, 4.0 * s, s, 0.0],
                ],
                1,
            )
        }
        "hermite" => {
            ([[2.0, 1.0, -2.0, 1.0], [-3.0, -2.0, 3.0, -1.0], [0.0, 1.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]], 2)
        }
        "linear" => ([[0.0; 4], [0.0; 4], [0.0, -1.0, 1.0, 0.0], [0.0, 1.0, 0.0, 0.0]], 1),
        _ => return None,
    };
    Some(Basis { matrix, step })
}

impl Translator<'_> {
    /// A call of `spline`: `args` and their values (a string basis first, or not); `ret` is the
    /// knots' type.
    pub(super) fn spline(
        &mut self,
        args: &[ExprId],
        vals: &[Value],
        ret: Type,
        span: Span,
    ) -> Result<Value, Diagnostic> {
        let named = self.shader.expr(args[0]).ty.base == Base::String;
        let name = if named {
            match self.fold_string(args[0]) {
                Some(s) => s.to_string(),
                None => {
                    return Err(Diagnostic::error(
                        Code::NotExecutable,
                        "the spline basis must be known when the shader is compiled",
                        span,
                        "this call",
                    ));
                }
            }
        } else {
            "catmull-rom".to_string()
        };
        let Some(basis) = basis(&name) else {
            return Err(Diagnostic::error(
                Code::NotExecutable,
                format!("unknown spline basis \"{name}\""),
                span,
                "this call",
            )
            .with_note(
                "the bases are \"catmull-rom\", \"bezier\", \"bspline\", \"hermite\" and \"linear\"",
            ));
        };
        let first = usize::from(named);
        let x = vals[first];
        // The knots, listed or in one array, as one list.
        let mut knots = Vec::new();
        for (a, v) in args[first + 1..].iter().zip(&vals[first + 1..]) {
            match self.shader.expr(*a).ty.array {
                Some(n) => knots.extend((0..n).map(|k| self.at(*v, k))),
                None => knots.push(*v),
            }
        }
        let count = knots.len() as u32;
        if count < 4 {
            return Err(Diagnostic::error(
                Code::NotExecutable,
                format!("`spline` needs at least four knots, and this one has {count}"),
                span,
                "this call",
            ));
        }
        let segments = (count - 4) / basis.step + 1;
        let (zero, one) = (self.float(0.0), self.float(1.0));
        let x = self.clamp_to(x, zero, one);
        let (t, segment_knots) = if segments == 1 {
            (x, knots[..4].to_vec())
        } else {
            let n = self.float(f64::from(segments));
            let scaled = self.mul(x, n);
            let last = self.float(f64::from(segments - 1));
            let floor = self.math1(M::Floor, scaled);
            let segment = self.math2(M::Min, floor, last);
            let t = self.sub(scaled, segment);
            let index = self.float_to_int(segment);
            let step = self.int(basis.step as i32);
            let start = self.binary(Op::Multiply, index, step);
            // All the knots in a per-invocation array, read at the segment's four indices
            // (clamped into range as every index is).
            let array_ty = Type { base: ret.base, array: Some(count) };
            let ty = self.mb.ty(array_ty, false);
            let all = self.fb.add(Expression::Compose { ty, components: knots });
            // One array per knot shape, shared by every call: each call stores its knots right
            // before reading them.
            let name = format!("{}spline_knots_{}x{count}", self.prefix, ret.base.components());
            let var = self.mb.private(&name, array_ty);
            let p = self.pointer(var);
            self.store(p, all);
            let four: Vec<Value> = (0..4)
                .map(|j| {
                    let i = if j == 0 {
                        start
                    } else {
                        let j = self.int(j);
                        self.binary(Op::Add, start, j)
                    };
                    let i = self.clamp_int(i, 0, count as i32 - 1);
                    let i = self.fb.add(Expression::As {
                        expr: i,
                        kind: naga::ScalarKind::Uint,
                        convert: Some(4),
                    });
                    let base = self.pointer(var);
                    let element = self.fb.add(Expression::Access { base, index: i });
                    self.load(element)
                })
                .collect();
            (t, four)
        };
        // Knot j's weight: column j of the basis as a cubic in t (Horner); None for a knot the
        // basis never uses.
        let weights: Vec<Option<Value>> = (0..4)
            .map(|j| {
                let mut acc: Option<Value> = None;
                for row in basis.matrix {
                    let k = row[j];
                    acc = match acc {
                        None if k == 0.0 => None,
                        None => Some(self.float(k)),
                        Some(a) => {
                            let a = self.mul(a, t);
                            if k == 0.0 {
                                Some(a)
                            } else {
                                let k = self.float(k);
                                Some(self.add(a, k))
                            }
                        }
                    };
                }
                acc
            })
            .collect();
        let n = ret.base.components();
        let mut sum: Option<Value> = None;
        for (j, w) in weights.iter().enumerate() {
            let Some(w) = *w else { continue };
            let w = self.splat(w, n);
            let term = self.mul(w, segment_knots[j]);
            sum = Some(match sum {
                None => term,
                Some(s) => self.add(s, term),
            });
        }
        Ok(match sum {
            Some(s) => s,
            None => self.splat(zero, n),
        })
    }
}
