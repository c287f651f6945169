//! `spline([basis,] x, k0, k1, k2, k3, ...)` and `spline([basis,] x, T[])`.
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
//! `x` varies per point, so the segment is chosen at run time: its index becomes an integer and the
//! four knots are gathered from a contiguous copy of all of them.

use super::{Lower, Val};
use crate::backend::cpu::code::{Binary, Convert, IntBinary, Reg, Ternary, Unary};
use crate::diag::{Code as DiagCode, Diagnostic};
use crate::source::Span;

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

/// Where the knots of the segment being evaluated are.
enum Knots {
    /// One segment: the knots' own registers.
    Fixed(Vec<Reg>),
    /// Several: consecutive registers holding all `count` knots, and the indices of the segment's
    /// four knots.
    Gathered { root: Vec<Reg>, indices: Vec<Reg>, count: u32 },
}

impl Lower<'_> {
    /// A call of `spline` with its arguments' values; `components` is the knot type's width.
    pub(super) fn spline(&mut self, vals: &[Val], components: u32, span: Span) -> Result<Val, Diagnostic> {
        let (name, rest) = match &vals[0] {
            Val::Str(s) => (s.as_str(), &vals[1..]),
            _ => ("catmull-rom", vals),
        };
        let Some(basis) = basis(name) else {
            return Err(Diagnostic::error(
                DiagCode::NotExecutable,
                format!("unknown spline basis \"{name}\""),
                span,
                "this call",
            )
            .with_note(
                "the bases are \"catmull-rom\", \"bezier\", \"bspline\", \"hermite\" and \"linear\"",
            ));
        };
        let x = rest[0].floats()[0];
        // The knots, listed or in one array, as one run of registers: knot after knot.
        let regs: Vec<Reg> = rest[1..].iter().flat_map(|v| v.floats().iter().copied()).collect();
        let count = regs.len() as u32 / components.max(1);
        if count < 4 {
            return Err(Diagnostic::error(
                DiagCode::NotExecutable,
                format!("`spline` needs at least four knots, and this one has {count}"),
                span,
                "this call",
            ));
        }
        let segments = (count - 4) / basis.step + 1;
        let (zero, one) = (self.emit.float(0.0), self.emit.float(1.0));
        let x = self.emit.ternary(Ternary::Clamp, x, zero, one);
        // Which segment, and where in it: x = 1 falls in the last segment at t = 1 (the reference
        // code's index would read past the last knot there).
        let (t, knots) = if segments == 1 {
            (x, Knots::Fixed(regs))
        } else {
            let n = self.emit.float(f64::from(segments));
            let scaled = self.emit.binary(Binary::Mul, x, n);
            let last = self.emit.float(f64::from(segments - 1));
            let first = self.emit.unary(Unary::Floor, scaled);
            let segment = self.emit.binary(Binary::Min, first, last);
            let t = self.emit.binary(Binary::Sub, scaled, segment);
            let index = self.emit.convert(Convert::FloatToInt, segment);
            let step = self.emit.int(basis.step);
            let start = self.emit.int_binary(IntBinary::Mul, index, step);
            let indices: Vec<Reg> = (0..4)
                .map(|j| {
                    if j == 0 {
                        return start;
                    }
                    let j = self.emit.int(j);
                    self.emit.int_binary(IntBinary::Add, start, j)
                })
                .collect();
            (t, Knots::Gathered { root: self.emit.consecutive(true, regs), indices, count })
        };
        // Knot j's weight: column j of the basis as a cubic in t (Horner); None for a knot the basis
        // never uses (the linear basis's outer two).
        let weights: Vec<Option<Reg>> = (0..4)
            .map(|j| {
                let mut acc: Option<Reg> = None;
                for row in basis.matrix {
                    let k = row[j];
                    acc = match acc {
                        None if k == 0.0 => None,
                        None => Some(self.emit.float(k)),
                        Some(a) => {
                            let a = self.emit.binary(Binary::Mul, a, t);
                            if k == 0.0 {
                                Some(a)
                            } else {
                                let k = self.emit.float(k);
                                Some(self.emit.binary(Binary::Add, a, k))
                            }
                        }
                    };
                }
                acc
            })
            .collect();
        let out: Vec<Reg> = (0..components)
            .map(|c| {
                let mut sum: Option<Reg> = None;
                for (j, w) in weights.iter().enumerate() {
                    let Some(w) = *w else { continue };
                    let k = self.knot(&knots, j as u32 * components + c, components);
                    let term = self.emit.binary(Binary::Mul, w, k);
                    sum = Some(match sum {
                        None => term,
                        Some(s) => self.emit.binary(Binary::Add, s, term),
                    });
                }
                sum.unwrap_or(zero)
            })
            .collect();
        Ok(Val::Float(out))
    }

    /// Component `at` (knot j of the segment times the width, plus the component) of the current
    /// segment's knots.
    fn knot(&mut self, knots: &Knots, at: u32, components: u32) -> Reg {
        match knots {
            Knots::Fixed(regs) => regs[at as usize],
            Knots::Gathered { root, indices, count } => {
                let (j, c) = ((at / components) as usize, (at % components) as usize);
                self.emit.gather(true, root[c], *count, components, indices[j], true)
            }
        }
    }
}
