//! `spline([basis,] x, k0, k1, k2, k3, ...)` and `spline([basis,] x, T[])` as arithmetic on the
//! knots, so that the interpreter and the GPU evaluate the same operations.
//!
//! RenderMan's definition (RI spec 3.2, section 15.1; Peachey's reference code in *Texturing &
//! Modeling*, "Splines and Mappings"): `x` is clamped to [0, 1] and spread evenly over the segments
//! of the curve; each segment is a cubic in a local parameter t in [0, 1] over four consecutive
//! knots, weighted by the basis matrix. The bases are those of `RiBasis` with their steps
//! (the offset between the first knots of consecutive segments): Catmull-Rom (the default) and
//! B-spline step 1, Hermite step 2 (knots are value, tangent, value, tangent, ...), Bezier step 3.
//! With n knots there are `(n - 4) / step + 1` segments (knots past the last whole segment are
//! ignored). `"linear"` interpolates straight between consecutive knots; like the cubic bases it
//! leaves out the first and the last knot, so all bases start at the same knot.
//!
//! A call becomes
//!
//! ```text
//! x' = clamp(x, 0, 1)
//! one segment:  t = x',  the knots themselves
//! n segments:   s = min(floor(x' n), n - 1),  t = x' n - s,  knot j = knots[int(s) step + j]
//! spline = w0(t) k0 + w1(t) k1 + w2(t) k2 + w3(t) k3
//! ```
//!
//! with each weight w_j column j of the basis as a cubic in t by Horner's rule, its leading zero
//! coefficients left out and a zero constant term not added (a knot the basis never weighs, the
//! linear basis's outer two, is left out of the sum). The knots of several segments are gathered
//! from one array: the array argument itself, or the listed knots composed into one.
//!
//! Runs after `opt::derivs`, whose rule for `spline` is a spline of the knots' derivatives, so
//! that those are expanded too. A call whose basis is not known when the shader is compiled, is
//! not a basis, or has fewer than four knots is left as it is: the backends refuse it with
//! [`refusal`]'s diagnostic.

use smol_str::SmolStr;

use crate::diag::{Code, Diagnostic};
use crate::ir::builtin::BuiltinId;
use crate::ir::types::Type;
use crate::ir::{BinaryOp, ExprId, ExprKind, Shader};
use crate::opt::build::Builder;

/// A spline basis: the matrix `B` such that a segment is `[t^3 t^2 t 1] B [k0 k1 k2 k3]^T`, and the
/// step between segments.
struct Basis {
    /// Rows are the coefficients of t^3, t^2, t and 1; column j weighs knot j.
    matrix: [[f64; 4]; 4],
    /// Knots between the starts of consecutive segments.
    step: u32,
}

/// The basis called `name` (the matrices of `RiBasis`, RI spec 3.2 section 5.2.2).
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
        // (1 - t) k1 + t k2.
        "linear" => ([[0.0; 4], [0.0; 4], [0.0, -1.0, 1.0, 0.0], [0.0, 1.0, 0.0, 0.0]], 1),
        _ => return None,
    };
    Some(Basis { matrix, step })
}

/// What a call of `spline` is: its basis (or why it has none) and its arguments.
struct Call {
    /// The basis's name, when it is known; `None` for a string known only at run time.
    name: Option<SmolStr>,
    /// `x`.
    x: ExprId,
    /// The knot arguments: values, or arrays of them.
    knots: Vec<ExprId>,
}

impl Call {
    /// The call `id`, if it is a call of `spline`.
    fn of(shader: &Shader, id: ExprId, strings: &[(String, String)]) -> Option<Call> {
        let ExprKind::Builtin(b, args) = &shader.expr(id).kind else { return None };
        if b.id != BuiltinId::Spline || args.len() < 2 {
            return None;
        }
        let named = shader.expr(args[0]).ty.base == crate::ir::types::Base::String;
        let name = if named { shader.string_value(args[0], strings) } else { Some("catmull-rom".into()) };
        let first = usize::from(named);
        Some(Call { name, x: args[first], knots: args[first + 1..].to_vec() })
    }

    /// How many knots the call lists (an array argument counts its elements).
    fn count(&self, shader: &Shader) -> u32 {
        self.knots.iter().map(|k| shader.expr(*k).ty.array.unwrap_or(1)).sum()
    }
}

/// Rewrites every call of `spline` whose basis is known into arithmetic (module documentation).
pub(crate) fn expand(shader: &mut Shader, strings: &[(String, String)]) {
    let calls: Vec<(ExprId, Call)> = (0..shader.exprs.len() as u32)
        .map(ExprId)
        .filter_map(|id| Call::of(shader, id, strings).map(|c| (id, c)))
        .collect();
    for (id, call) in calls {
        let Some(basis) = call.name.as_deref().and_then(basis) else { continue };
        let count = call.count(shader);
        if count < 4 {
            continue;
        }
        let (span, rate, ty) = {
            let e = shader.expr(id);
            (e.span, e.rate, e.ty)
        };
        let first_new = shader.exprs.len();
        let mut b = Builder::new(shader, span);
        let value = segment_value(&mut b, &call, &basis, count, ty);
        b.shader.exprs[id.0 as usize].kind = ExprKind::Convert(value);
        for e in &mut b.shader.exprs[first_new..] {
            e.rate = e.rate.join(rate);
        }
    }
    crate::verify::assert_valid(shader, crate::verify::Pass::Splines);
}

/// The spline's value at `x` (module documentation); `ty` is the knots' type.
fn segment_value(b: &mut Builder, call: &Call, basis: &Basis, count: u32, ty: Type) -> ExprId {
    let segments = (count - 4) / basis.step + 1;
    let (zero, one) = (b.float(0.0), b.float(1.0));
    let x = b.call(BuiltinId::Clamp, vec![call.x, zero, one]);
    let (t, knots) = if segments == 1 {
        (x, (0..4).map(|j| knot(b, &call.knots, j)).collect::<Vec<_>>())
    } else {
        let n = b.float(f64::from(segments));
        let scaled = b.binary(BinaryOp::Mul, x, n);
        let floor = b.call(BuiltinId::Floor, vec![scaled]);
        let last = b.float(f64::from(segments - 1));
        let segment = b.call(BuiltinId::Min, vec![floor, last]);
        let t = b.binary(BinaryOp::Sub, scaled, segment);
        let index = b.convert(segment, Type::INT);
        let step = b.int(basis.step as i32);
        let start = b.binary(BinaryOp::Mul, index, step);
        let all = match call.knots.as_slice() {
            [array] if b.ty(*array).is_array() => *array,
            _ => {
                let parts = (0..count).map(|j| knot(b, &call.knots, j)).collect();
                b.construct(parts, Type { array: Some(count), ..ty })
            }
        };
        let knots = (0..4)
            .map(|j| {
                let i = if j == 0 {
                    start
                } else {
                    let j = b.int(j);
                    b.binary(BinaryOp::Add, start, j)
                };
                b.index_by(all, i)
            })
            .collect();
        (t, knots)
    };
    let mut sum: Option<ExprId> = None;
    for (j, k) in knots.into_iter().enumerate() {
        let Some(w) = weight(b, basis, j, t) else { continue };
        let term = b.binary(BinaryOp::Mul, w, k);
        sum = Some(match sum {
            None => term,
            Some(s) => b.binary(BinaryOp::Add, s, term),
        });
    }
    sum.unwrap_or_else(|| b.zero(ty))
}

/// Knot `j` of the call's knot arguments, counting an array's elements one by one.
fn knot(b: &mut Builder, knots: &[ExprId], mut j: u32) -> ExprId {
    for &k in knots {
        match b.ty(k).array {
            Some(n) if j < n => return b.index(k, j),
            Some(n) => j -= n,
            None if j == 0 => return k,
            None => j -= 1,
        }
    }
    unreachable!("the call has at least as many knots as asked for")
}

/// Knot `j`'s weight at `t`: column `j` of the basis as a cubic in `t` by Horner's rule; `None`
/// for a knot the basis never weighs.
fn weight(b: &mut Builder, basis: &Basis, j: usize, t: ExprId) -> Option<ExprId> {
    let mut acc: Option<ExprId> = None;
    for row in basis.matrix {
        let k = row[j];
        acc = match acc {
            None if k == 0.0 => None,
            None => Some(b.float(k)),
            Some(a) => {
                let a = b.binary(BinaryOp::Mul, a, t);
                if k == 0.0 {
                    Some(a)
                } else {
                    let k = b.float(k);
                    Some(b.binary(BinaryOp::Add, a, k))
                }
            }
        };
    }
    acc
}

/// Why a backend cannot run the call of `spline` `id` that `expand` left: its basis is not known
/// when the shader is compiled, is no basis, or it has fewer than four knots.
pub fn refusal(shader: &Shader, id: ExprId, strings: &[(String, String)]) -> Diagnostic {
    let span = shader.expr(id).span;
    let Some(call) = Call::of(shader, id, strings) else {
        return Diagnostic::error(
            Code::Internal,
            "a `spline` call with too few arguments",
            span,
            "this call",
        );
    };
    match call.name.as_deref() {
        None => Diagnostic::error(
            Code::NotExecutable,
            "the spline basis must be known when the shader is compiled",
            span,
            "this call",
        ),
        Some(name) if basis(name).is_none() => Diagnostic::error(
            Code::NotExecutable,
            format!("unknown spline basis \"{name}\""),
            span,
            "this call",
        )
        .with_note("the bases are \"catmull-rom\", \"bezier\", \"bspline\", \"hermite\" and \"linear\""),
        Some(_) => Diagnostic::error(
            Code::NotExecutable,
            format!("`spline` needs at least four knots, and this one has {}", call.count(shader)),
            span,
            "this call",
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::opt::Prepared;
    use crate::syntax::preprocess::MemoryLoader;

    /// The shader of `src`, prepared with the string parameters `strings`.
    fn prepared(src: &str, strings: &[(String, String)]) -> Prepared {
        let checked = crate::check_source("test.sl", src, &MemoryLoader::default());
        assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
        Prepared::with_strings(checked.program.shaders[0].clone(), strings)
    }

    fn is_spline(e: &crate::ir::Expr) -> bool {
        matches!(&e.kind, ExprKind::Builtin(b, _) if b.id == BuiltinId::Spline)
    }

    /// The calls of `spline` left in `shader` (an expanded call's expression is a conversion of its
    /// value now).
    fn splines(shader: &Shader) -> usize {
        shader.exprs.iter().filter(|e| is_spline(e)).count()
    }

    #[test]
    fn every_call_with_a_known_basis_becomes_arithmetic() {
        // A listed, a named, an array, a colour and a derivative's spline (of the knots' derivatives).
        let src = "surface t(string b = \"bezier\"; float k[6] = {1, 2, 0, 5, 3, 7}) {
            float f = spline(s, 0, 1, 2, 3, 4) + spline(b, s, 0, 1, 2, 3, 4, 5, 6) + spline(\"linear\", t, k);
            color c = spline(\"bspline\", s, color(0), color(1), Cs, color(2), color(3));
            Ci = c * f + Du(spline(t, s, 2 * s, s * s, 1));
        }";
        let shader = prepared(src, &[]);
        assert_eq!(splines(&shader), 0);
        // Hermite by the bound value instead of the default: still known.
        assert_eq!(splines(&prepared(src, &[("b".into(), "hermite".into())])), 0);
    }

    #[test]
    fn calls_it_cannot_run_are_left_for_the_backends_to_refuse() {
        let src = "surface t(string b) { Ci = spline(b, s, 0, 1, 2, 3); }";
        let unknown = prepared(src, &[]);
        assert_eq!(splines(&unknown), 1);
        assert_eq!(
            refusal_message(&unknown, &[]),
            "the spline basis must be known when the shader is compiled"
        );
        let strings = [("b".to_string(), "cardinal".to_string())];
        let not_a_basis = prepared(src, &strings);
        assert_eq!(refusal_message(&not_a_basis, &strings), "unknown spline basis \"cardinal\"");
        let short = prepared("surface t() { float k[3] = {0, 1, 2}; Ci = spline(s, k); }", &[]);
        assert_eq!(refusal_message(&short, &[]), "`spline` needs at least four knots, and this one has 3");
    }

    /// The refusal (its code checked) of the first call of `spline` left in `shader`.
    fn refusal_message(shader: &Shader, strings: &[(String, String)]) -> String {
        let call = ExprId(shader.exprs.iter().position(is_spline).expect("a spline is left") as u32);
        let refusal = refusal(shader, call, strings);
        assert_eq!(refusal.code, Code::NotExecutable);
        refusal.message
    }
}
