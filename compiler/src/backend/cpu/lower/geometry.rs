//! Coordinate systems and matrices.
//!
//! Matrices are stored row by row as written in the source. `transform` and the named spaces use
//! RenderMan's convention, points as row vectors: `p' = (p, 1) * M`, the translation in the last
//! row. A named space arrives from the caller as two matrices, "current to space" and its inverse
//! (see `Slot`), so the interpreter never inverts a per-draw matrix per point.
//!
//! The matrix builders `translate`, `rotate` and `scale`, `determinant`, `ptlined`, the point
//! `rotate` and `fresnel` are the library's (`compiler/stdlib/builtins.sl`, where the builders'
//! postconcatenation is described). `invert` stays here, with the Laplace expansion (`minor`) that
//! the library's `determinant` repeats operation for operation.
//!
//! This module also refuses the `spline` calls `opt::splines` left, dispatches `pattern`'s `match`, checks
//! the colour space names `ctransform` reads from the binding (its conversions are the library's),
//! and holds `depth`.

use super::{Lower, Val};
use crate::backend::CLIP_INPUT;
use crate::backend::cpu::code::{Binary, Compare, Reg};
use crate::diag::{Code as DiagCode, Diagnostic};
use crate::ir::ExprId;
use crate::ir::builtin::Builtin;
use crate::ir::builtin::BuiltinId as B;
use crate::ir::types::{Base, Type};

/// How `transform` treats a three-component value.
#[derive(Copy, Clone, PartialEq, Eq)]
pub(crate) enum Rule {
    /// Translated and divided by w.
    Point,
    /// Not translated.
    Vector,
    /// By the inverse transpose.
    Normal,
}

impl Rule {
    fn of(base: Base) -> Rule {
        match base {
            Base::Point => Rule::Point,
            Base::Normal => Rule::Normal,
            _ => Rule::Vector,
        }
    }
}

impl Lower<'_> {
    /// The built-ins of this module (`builtin` sends them here); `None` for the others, and for
    /// a colour space or pattern that is not a string.
    pub(super) fn geometry(
        &mut self,
        b: &'static Builtin,
        vals: &[Val],
        args: &[ExprId],
        id: ExprId,
    ) -> Result<Option<Val>, Diagnostic> {
        let ret = self.shader.expr(id).ty;
        let span = self.shader.expr(id).span;
        let arg_ty = |i: usize| self.shader.expr(args[i]).ty;
        Ok(Some(match b.id {
            B::Transform | B::VTransform | B::NTransform => {
                let rule = match b.id {
                    B::VTransform => Rule::Vector,
                    B::NTransform => Rule::Normal,
                    _ => Rule::of(ret.base),
                };
                let value = vals[vals.len() - 1].floats().to_vec();
                let out = match (&vals[0], vals.len()) {
                    (Val::Str(to), 2) => {
                        let (to_m, from_m) = self.space_matrices(to);
                        self.apply(&value, rule, &to_m, &from_m)
                    }
                    (Val::Str(from), 3) if arg_ty(1).base == Base::String => {
                        let to = match &vals[1] {
                            Val::Str(s) => s.clone(),
                            _ => "current".into(),
                        };
                        let (to_from, from_from) = self.space_matrices(from);
                        let current = self.apply(&value, rule, &from_from, &to_from);
                        let (to_m, from_m) = self.space_matrices(&to);
                        self.apply(&current, rule, &to_m, &from_m)
                    }
                    (Val::Str(from), 3) => {
                        let (to_from, from_from) = self.space_matrices(from);
                        let current = self.apply(&value, rule, &from_from, &to_from);
                        let m = vals[1].floats().to_vec();
                        let inv = self.invert(&m, Base::Matrix4);
                        self.apply(&current, rule, &m, &inv)
                    }
                    _ => {
                        let m = vals[0].floats().to_vec();
                        let inv =
                            if rule == Rule::Normal { self.invert(&m, Base::Matrix4) } else { m.clone() };
                        self.apply(&value, rule, &m, &inv)
                    }
                };
                Val::Float(out)
            }
            B::Transpose => {
                let n = if arg_ty(0).base == Base::Matrix3 { 3 } else { 4 };
                let m = vals[0].floats();
                Val::Float((0..n * n).map(|k| m[(k % n) * n + k / n]).collect())
            }
            B::Affine => {
                let m = vals[0].floats();
                Val::Float((0..9).map(|k| m[(k / 3) * 4 + k % 3]).collect())
            }
            B::Invert => Val::Float(self.invert(vals[0].floats(), arg_ty(0).base)),
            B::Depth => Val::Float(vec![self.depth(vals[0].floats()[2])]),
            B::ColourSpace => {
                let Val::Str(name) = &vals[0] else { return Ok(None) };
                crate::stdlib::check_colour_space(name, span)?;
                Val::Void
            }
            // Left by `opt::splines` only when it cannot be run.
            B::Spline => return Err(crate::opt::splines::refusal(self.shader, id, &self.binding.strings)),
            B::Match => {
                let (Val::Str(pattern), Val::Str(subject)) = (&vals[0], &vals[1]) else { return Ok(None) };
                match crate::backend::pattern::search(pattern, subject) {
                    Ok(found) => Val::Float(vec![self.emit.float(if found { 1.0 } else { 0.0 })]),
                    Err(why) => {
                        return Err(Diagnostic::error(
                            DiagCode::NotExecutable,
                            format!("the interpreter cannot match the pattern \"{pattern}\""),
                            span,
                            "this pattern",
                        )
                        .with_note(why));
                    }
                }
            }
            _ => return Ok(None),
        }))
    }

    /// `depth(p)`: `(z - near) / (far - near)` for z in camera space, which the interpreter takes
    /// to be "current". Near and far come from the [`CLIP_INPUT`] input; an empty range (among them
    /// the evaluator's default of zeros) counts as 1, so that an unset slot gives plain z.
    fn depth(&mut self, z: Reg) -> Reg {
        let clip = self.named_input(CLIP_INPUT, Type { base: Base::Float, array: Some(2) }, true);
        let (near, far) = (clip[0], clip[1]);
        let range = self.emit.binary(Binary::Sub, far, near);
        let (zero, one) = (self.emit.float(0.0), self.emit.float(1.0));
        let empty = self.emit.compare(Compare::Eq, range, zero);
        let range = self.emit.select(true, empty, one, range);
        let from_near = self.emit.binary(Binary::Sub, z, near);
        self.emit.binary(Binary::Div, from_near, range)
    }

    /// The matrices of a named space: (current to it, it to current); identities for "current".
    fn space_matrices(&mut self, name: &str) -> (Vec<Reg>, Vec<Reg>) {
        if matches!(name, "current" | "camera") {
            let identity = self.identity();
            return (identity.clone(), identity);
        }
        self.space(name)
    }

    fn identity(&mut self) -> Vec<Reg> {
        let (zero, one) = (self.emit.float(0.0), self.emit.float(1.0));
        (0..16).map(|i| if i % 5 == 0 { one } else { zero }).collect()
    }

    /// `value` given in `space`, converted to "current".
    pub(super) fn space_to_current(&mut self, space: &str, v: &Val, ty: Type) -> Val {
        let value = v.floats().to_vec();
        let (to_m, from_m) = self.space_matrices(space);
        if ty.base == Base::Matrix4 {
            return Val::Float(self.product(&value, &from_m, 4));
        }
        Val::Float(self.apply(&value, Rule::of(ty.base), &from_m, &to_m))
    }

    /// `v` transformed by `m` (row-vector convention) under `rule`; `inv` is `m`'s inverse, used by
    /// normals.
    pub(crate) fn apply(&mut self, v: &[Reg], rule: Rule, m: &[Reg], inv: &[Reg]) -> Vec<Reg> {
        let row_times = |this: &mut Self, j: usize, mat: &dyn Fn(usize, usize) -> Reg, w: Option<Reg>| {
            let mut sum = this.emit.binary(Binary::Mul, v[0], mat(0, j));
            for (i, x) in v.iter().enumerate().skip(1).take(2) {
                let p = this.emit.binary(Binary::Mul, *x, mat(i, j));
                sum = this.emit.binary(Binary::Add, sum, p);
            }
            match w {
                Some(t) => this.emit.binary(Binary::Add, sum, t),
                None => sum,
            }
        };
        match rule {
            Rule::Point => {
                let out: Vec<Reg> =
                    (0..4).map(|j| row_times(self, j, &|i, j| m[i * 4 + j], Some(m[12 + j]))).collect();
                self.dehomogenize(out, true)
            }
            Rule::Vector => (0..3).map(|j| row_times(self, j, &|i, j| m[i * 4 + j], None)).collect(),
            // n' = n * inverse(M)^T: element (i, j) of the transpose is inv[j][i].
            Rule::Normal => (0..3).map(|j| row_times(self, j, &|i, j| inv[j * 4 + i], None)).collect(),
        }
    }

    /// The matrix product `a * b` of two n x n matrices.
    fn product(&mut self, a: &[Reg], b: &[Reg], n: usize) -> Vec<Reg> {
        let mut out = Vec::with_capacity(n * n);
        for i in 0..n {
            for j in 0..n {
                let row: Vec<Reg> = (0..n).map(|k| a[i * n + k]).collect();
                let col: Vec<Reg> = (0..n).map(|k| b[k * n + j]).collect();
                out.push(self.dot(&row, &col));
            }
        }
        out
    }

    /// The inverse of a 3x3 or 4x4 matrix: the adjugate over the determinant (a singular matrix
    /// gives infinities or NaN, as dividing by zero does).
    pub(crate) fn invert(&mut self, m: &[Reg], base: Base) -> Vec<Reg> {
        let n = if base == Base::Matrix3 { 3 } else { 4 };
        let all: Vec<usize> = (0..n).collect();
        let det = self.minor(m, n, &all, &all);
        let mut out = vec![m[0]; n * n];
        for i in 0..n {
            for j in 0..n {
                // inverse[i][j] = cofactor[j][i] / det.
                let rows: Vec<usize> = all.iter().copied().filter(|r| *r != j).collect();
                let cols: Vec<usize> = all.iter().copied().filter(|c| *c != i).collect();
                let minor = self.minor(m, n, &rows, &cols);
                let signed = if (i + j) % 2 == 0 {
                    minor
                } else {
                    self.emit.unary(crate::backend::cpu::code::Unary::Neg, minor)
                };
                out[i * n + j] = self.emit.binary(Binary::Div, signed, det);
            }
        }
        out
    }

    /// The determinant of the submatrix of the rows and columns given, by Laplace expansion.
    fn minor(&mut self, m: &[Reg], n: usize, rows: &[usize], cols: &[usize]) -> Reg {
        let at = |r: usize, c: usize| m[r * n + c];
        match rows.len() {
            1 => at(rows[0], cols[0]),
            2 => {
                let a = self.emit.binary(Binary::Mul, at(rows[0], cols[0]), at(rows[1], cols[1]));
                let b = self.emit.binary(Binary::Mul, at(rows[0], cols[1]), at(rows[1], cols[0]));
                self.emit.binary(Binary::Sub, a, b)
            }
            _ => {
                let mut sum: Option<Reg> = None;
                for (k, &c) in cols.iter().enumerate() {
                    let rest: Vec<usize> = cols.iter().copied().filter(|x| *x != c).collect();
                    let sub = self.minor(m, n, &rows[1..], &rest);
                    let term = self.emit.binary(Binary::Mul, at(rows[0], c), sub);
                    sum = Some(match sum {
                        None => term,
                        Some(s) if k % 2 == 0 => self.emit.binary(Binary::Add, s, term),
                        Some(s) => self.emit.binary(Binary::Sub, s, term),
                    });
                }
                sum.unwrap_or_else(|| self.emit.float(1.0))
            }
        }
    }
}
