//! Coordinate systems and matrices.
//!
//! Matrices are stored row by row as written in the source. `transform` and the named spaces use
//! RenderMan's convention, points as row vectors: `p' = (p, 1) * M`, the translation in the last
//! row. A named space arrives from the caller as two matrices, "current to space" and its inverse
//! (see `Slot`), so the interpreter never inverts a per-draw matrix per point.
//!
//! The matrix builders `translate`, `rotate` and `scale` *postconcatenate* (RI spec 3.2, section
//! 15.4): in the row-vector convention the result is `m * T`, so `transform(translate(m, t), p)`
//! is `transform(m, p) + t`: the new transformation applies after `m`. (`RiTranslate` and the
//! other RI calls concatenate the other way, `T * CTM`, applying the new transformation first;
//! the shading-language functions are specified as postconcatenating, and Aqsis's `mtranslate`
//! computes `m * T` in the same convention.)
//!
//! This module also dispatches the built-ins of `curves` (`spline`) and `pattern` (`match`), checks
//! the colour space names `ctransform` reads from the binding (its conversions are the library's,
//! `compiler/stdlib/builtins.sl`), and holds `fresnel`, `ptlined`, the point `rotate` and `depth`.

use super::{Lower, Val};
use crate::backend::CLIP_INPUT;
use crate::backend::cpu::code::{Binary, Compare, Reg, Ternary, Unary};
use crate::diag::{Code as DiagCode, Diagnostic};
use crate::ir::ExprId;
use crate::ir::types::{Base, Type};
use crate::sema::builtins::Builtin;
use crate::source::Span;

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
    /// The built-ins of this module; `None` for names it does not know.
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
        Ok(Some(match b.name {
            "transform" | "vtransform" | "ntransform" => {
                let rule = match b.name {
                    "vtransform" => Rule::Vector,
                    "ntransform" => Rule::Normal,
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
            "transpose" => {
                let n = if arg_ty(0).base == Base::Matrix3 { 3 } else { 4 };
                let m = vals[0].floats();
                Val::Float((0..n * n).map(|k| m[(k % n) * n + k / n]).collect())
            }
            "affine" => {
                let m = vals[0].floats();
                Val::Float((0..9).map(|k| m[(k / 3) * 4 + k % 3]).collect())
            }
            "invert" => Val::Float(self.invert(vals[0].floats(), arg_ty(0).base)),
            "determinant" => {
                let m = vals[0].floats().to_vec();
                let rows: Vec<usize> = (0..4).collect();
                Val::Float(vec![self.minor(&m, 4, &rows, &rows)])
            }
            "translate" | "scale" => {
                let (m, v) = (vals[0].floats(), vals[1].floats());
                let op = if b.name == "translate" { Binary::Add } else { Binary::Mul };
                let out = (0..16)
                    .map(|k| {
                        let (i, j) = (k / 4, k % 4);
                        match (j, op) {
                            (3, _) => m[k],
                            // (m T)[i][j] = m[i][j] + m[i][3] t[j].
                            (_, Binary::Add) => {
                                let shift = self.emit.binary(Binary::Mul, m[i * 4 + 3], v[j]);
                                self.emit.binary(Binary::Add, m[k], shift)
                            }
                            // (m S)[i][j] = m[i][j] s[j].
                            _ => self.emit.binary(Binary::Mul, m[k], v[j]),
                        }
                    })
                    .collect();
                Val::Float(out)
            }
            "rotate" if ret.base == Base::Matrix4 => {
                let m = vals[0].floats();
                let r = self.rotation(vals[1].floats()[0], vals[2].floats());
                let out = (0..16)
                    .map(|k| {
                        let (i, j) = (k / 4, k % 4);
                        if j == 3 {
                            return m[k];
                        }
                        let row = [m[i * 4], m[i * 4 + 1], m[i * 4 + 2]];
                        self.dot(&row, &[r[j], r[3 + j], r[6 + j]])
                    })
                    .collect();
                Val::Float(out)
            }
            "rotate" => {
                // The point about the axis through p0 and p1: (q - p0) R + p0.
                let (q, p0, p1) = (vals[0].floats(), vals[2].floats(), vals[3].floats());
                let axis = self.zip(Binary::Sub, p1, p0);
                let r = self.rotation(vals[1].floats()[0], &axis);
                let v = self.zip(Binary::Sub, q, p0);
                let out = (0..3)
                    .map(|j| {
                        let turned = self.dot(&v, &[r[j], r[3 + j], r[6 + j]]);
                        self.emit.binary(Binary::Add, turned, p0[j])
                    })
                    .collect();
                Val::Float(out)
            }
            "ptlined" => Val::Float(vec![self.ptlined(vals[0].floats(), vals[1].floats(), vals[2].floats())]),
            "depth" => Val::Float(vec![self.depth(vals[0].floats()[2])]),
            "fresnel" => {
                self.fresnel(vals, args, span)?;
                Val::Void
            }
            "__colour_space" => {
                let Val::Str(name) = &vals[0] else { return Ok(None) };
                crate::stdlib::check_colour_space(name, span)?;
                Val::Void
            }
            "spline" => self.spline(vals, ret.base.components(), span)?,
            "match" => {
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

    /// The 3x3 rotation by `angle` radians about `axis` (normalized here), row by row, for row
    /// vectors: `v R = v cos + (k x v) sin + k (k . v)(1 - cos)` (Rodrigues), the matrix of
    /// `RiRotate`. About +z it turns +x towards +y.
    fn rotation(&mut self, angle: Reg, axis: &[Reg]) -> [Reg; 9] {
        let k = self.normalize(axis);
        let (c, s) = (self.emit.unary(Unary::Cos, angle), self.emit.unary(Unary::Sin, angle));
        let one = self.emit.float(1.0);
        let t = self.emit.binary(Binary::Sub, one, c);
        let mut r = [c; 9];
        for i in 0..3 {
            for j in 0..3 {
                // t k_i k_j, plus cos on the diagonal, plus or minus sin k_m off it.
                let ki = self.emit.binary(Binary::Mul, t, k[i]);
                let outer = self.emit.binary(Binary::Mul, ki, k[j]);
                r[i * 3 + j] = if i == j {
                    self.emit.binary(Binary::Add, outer, c)
                } else {
                    let m = 3 - i - j;
                    let sk = self.emit.binary(Binary::Mul, s, k[m]);
                    // (i, j) = (0, 1), (1, 2), (2, 0) add s k_m; the transposed places subtract.
                    if (i + 1) % 3 == j {
                        self.emit.binary(Binary::Add, outer, sk)
                    } else {
                        self.emit.binary(Binary::Sub, outer, sk)
                    }
                };
            }
        }
        r
    }

    /// The distance from `q` to the segment from `a` to `b`: to the nearest point `a + t (b - a)`
    /// with t clamped to [0, 1] (a point segment, whose t is 0/0 = NaN, clamps to `a`).
    fn ptlined(&mut self, a: &[Reg], b: &[Reg], q: &[Reg]) -> Reg {
        let d = self.zip(Binary::Sub, b, a);
        let w = self.zip(Binary::Sub, q, a);
        let along = self.dot(&w, &d);
        let dd = self.dot(&d, &d);
        let t = self.emit.binary(Binary::Div, along, dd);
        let (zero, one) = (self.emit.float(0.0), self.emit.float(1.0));
        let t = self.emit.ternary(Ternary::Clamp, t, zero, one);
        let td = self.zip(Binary::Mul, &d, &[t]);
        let off = self.zip(Binary::Sub, &w, &td);
        self.length(&off)
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

    /// `fresnel(I, N, eta, Kr, Kt [, R, T])`: the Fresnel reflectance of a dielectric for
    /// unpolarized light, `Kr = (rs^2 + rp^2) / 2`, with `eta` the ratio of the index on the side
    /// of I to the index of the side entered (as for `refract`), and `Kt = 1 - Kr`; under total
    /// internal reflection Kr = 1 and Kt = 0. The angle comes from I and N normalized (its cosine
    /// taken as positive, whichever way N faces). `R` and `T` are `reflect(I, N)` and
    /// `refract(I, N, eta)`.
    fn fresnel(&mut self, vals: &[Val], args: &[ExprId], span: Span) -> Result<(), Diagnostic> {
        let (i, n, eta) = (vals[0].floats(), vals[1].floats(), vals[2].floats()[0]);
        let (zero, one, half) = (self.emit.float(0.0), self.emit.float(1.0), self.emit.float(0.5));
        let ni = self.normalize(i);
        let nn = self.normalize(n);
        let cos_i = self.dot(&ni, &nn);
        let cos_i = self.emit.unary(Unary::Abs, cos_i);
        // Snell: sin_t^2 = eta^2 (1 - cos_i^2).
        let c2 = self.emit.binary(Binary::Mul, cos_i, cos_i);
        let sin_i2 = self.emit.binary(Binary::Sub, one, c2);
        let eta2 = self.emit.binary(Binary::Mul, eta, eta);
        let sin_t2 = self.emit.binary(Binary::Mul, eta2, sin_i2);
        let total = self.emit.compare(Compare::Gt, sin_t2, one);
        let cos_t2 = self.emit.binary(Binary::Sub, one, sin_t2);
        let cos_t2 = self.emit.binary(Binary::Max, cos_t2, zero);
        let cos_t = self.emit.unary(Unary::Sqrt, cos_t2);
        // rs = (eta cos_i - cos_t) / (eta cos_i + cos_t), rp = (cos_i - eta cos_t) / (cos_i + eta cos_t).
        let ratio = |this: &mut Self, a: Reg, b: Reg| {
            let num = this.emit.binary(Binary::Sub, a, b);
            let den = this.emit.binary(Binary::Add, a, b);
            let r = this.emit.binary(Binary::Div, num, den);
            this.emit.binary(Binary::Mul, r, r)
        };
        let eci = self.emit.binary(Binary::Mul, eta, cos_i);
        let rs2 = ratio(self, eci, cos_t);
        let ect = self.emit.binary(Binary::Mul, eta, cos_t);
        let rp2 = ratio(self, cos_i, ect);
        let sum = self.emit.binary(Binary::Add, rs2, rp2);
        let kr = self.emit.binary(Binary::Mul, sum, half);
        let kr = self.emit.select(true, total, one, kr);
        let kt = self.emit.binary(Binary::Sub, one, kr);
        self.write_output(args[3], &Val::Float(vec![kr]), span)?;
        self.write_output(args[4], &Val::Float(vec![kt]), span)?;
        if args.len() == 7 {
            let r = self.reflect(i, n);
            let t = self.refract(i, n, eta);
            self.write_output(args[5], &Val::Float(r), span)?;
            self.write_output(args[6], &Val::Float(t), span)?;
        }
        Ok(())
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
