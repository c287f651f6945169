//! Matrices and the scalar arithmetic the composite built-ins are written in.
//!
//! The interpreter scalarizes every value and defines each composite built-in (`transform`,
//! `invert`, `spline`, ...) as a fixed sequence of scalar operations.
//! WGSL leaves the order of a matrix product's or a `dot`'s sums to the implementation, so the
//! built-ins here take their operands apart into components and repeat the interpreter's
//! sequence operation for operation: with IEEE `+ - * /` the results are then the same bits.
//!
//! Matrix convention: the module stores each language matrix transposed (a language row is a
//! WGSL column), so `m[i]` is language row `i` and `m[i][j]` is the language's element (i, j).
//! [`Translator::entries`] lists a matrix row by row as the interpreter's registers do, and
//! [`Translator::matrix`] builds one back from that list.

use naga::{BinaryOperator as Op, Expression, MathFunction as M, ScalarKind};

use super::body::{Translator, Value};
use crate::ir::types::{Base, Type};

/// How `transform` treats a three-component value (the interpreter's `Rule`).
#[derive(Copy, Clone, PartialEq, Eq)]
pub(super) enum Rule {
    /// Translated and divided by w.
    Point,
    /// Not translated.
    Vector,
    /// By the inverse transpose.
    Normal,
}

impl Rule {
    /// The rule of a value of type `base`.
    pub(super) fn of(base: Base) -> Rule {
        match base {
            Base::Point => Rule::Point,
            Base::Normal => Rule::Normal,
            _ => Rule::Vector,
        }
    }
}

impl Translator<'_> {
    // ---------------------------------------------------------------------------------------------
    // Components.

    /// Component `i` of a vector, or language row `i` of a matrix.
    pub(super) fn at(&mut self, v: Value, i: u32) -> Value {
        self.fb.add(Expression::AccessIndex { base: v, index: i })
    }

    /// The components of an `n`-component value (a scalar is its own single component).
    pub(super) fn parts(&mut self, v: Value, n: u32) -> Vec<Value> {
        if n <= 1 {
            return vec![v];
        }
        (0..n).map(|i| self.at(v, i)).collect()
    }

    /// The entries of an `n` x `n` matrix, row by row as the language writes them.
    pub(super) fn entries(&mut self, m: Value, n: u32) -> Vec<Value> {
        let mut out = Vec::with_capacity((n * n) as usize);
        for i in 0..n {
            let row = self.at(m, i);
            for j in 0..n {
                out.push(self.at(row, j));
            }
        }
        out
    }

    /// A float vector (or a scalar, for one part) from its components.
    pub(super) fn vector(&mut self, parts: &[Value]) -> Value {
        match parts.len() {
            0 => self.float(0.0),
            1 => parts[0],
            n => {
                let base = if n == 4 { Base::Float4 } else { Base::Float3 };
                let ty = self.mb.ty(Type::of(base), false);
                self.fb.add(Expression::Compose { ty, components: parts.to_vec() })
            }
        }
    }

    /// An `n` x `n` matrix from its entries row by row (each language row a WGSL column).
    pub(super) fn matrix(&mut self, entries: &[Value], n: u32) -> Value {
        let rows: Vec<Value> = entries.chunks(n as usize).map(|row| self.vector(row)).collect();
        let base = if n == 3 { Base::Matrix3 } else { Base::Matrix4 };
        let ty = self.mb.ty(Type::of(base), false);
        self.fb.add(Expression::Compose { ty, components: rows })
    }

    /// The identity's entries as literals (the interpreter multiplies by them, rather than
    /// skipping the product, for "current" and "camera").
    pub(super) fn identity_entries(&mut self) -> Vec<Value> {
        let (zero, one) = (self.float(0.0), self.float(1.0));
        (0..16).map(|i| if i % 5 == 0 { one } else { zero }).collect()
    }

    // ---------------------------------------------------------------------------------------------
    // Scalar arithmetic, in the interpreter's order.

    /// `a + b`.
    pub(super) fn add(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Add, a, b)
    }

    /// `a - b`.
    pub(super) fn sub(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Subtract, a, b)
    }

    /// `a * b`.
    pub(super) fn mul(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Multiply, a, b)
    }

    /// `a / b`.
    pub(super) fn div(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Divide, a, b)
    }

    /// `cond ? a : b`.
    pub(super) fn pick(&mut self, cond: Value, a: Value, b: Value) -> Value {
        self.fb.add(Expression::Select { condition: cond, accept: a, reject: b })
    }

    /// `min(max(x, lo), hi)`, the interpreter's clamp.
    pub(super) fn clamp_to(&mut self, x: Value, lo: Value, hi: Value) -> Value {
        let m = self.math2(M::Max, x, lo);
        self.math2(M::Min, m, hi)
    }

    /// `a - b * floor(a / b)`, the interpreter's `mod`.
    pub(super) fn modulo(&mut self, a: Value, b: Value) -> Value {
        let q = self.div(a, b);
        let f = self.math1(M::Floor, q);
        let p = self.mul(b, f);
        self.sub(a, p)
    }

    /// `a0 b0 + a1 b1 + ...`, summed left to right.
    pub(super) fn dot_parts(&mut self, a: &[Value], b: &[Value]) -> Value {
        let mut sum = self.mul(a[0], b[0]);
        for i in 1..a.len().min(b.len()) {
            let p = self.mul(a[i], b[i]);
            sum = self.add(sum, p);
        }
        sum
    }

    /// `sqrt(v . v)` of components.
    pub(super) fn length_parts(&mut self, v: &[Value]) -> Value {
        let d = self.dot_parts(v, v);
        self.math1(M::Sqrt, d)
    }

    /// A float as an `i32` (WGSL's clamping conversion, which the interpreter's also is).
    pub(super) fn float_to_int(&mut self, x: Value) -> Value {
        self.fb.add(Expression::As { expr: x, kind: ScalarKind::Sint, convert: Some(4) })
    }

    /// An `i32` literal.
    pub(super) fn int(&mut self, i: i32) -> Value {
        self.fb.add(Expression::Literal(naga::Literal::I32(i)))
    }

    /// An `i32` clamped to `[lo, hi]`.
    pub(super) fn clamp_int(&mut self, i: Value, lo: i32, hi: i32) -> Value {
        let (lo, hi) = (self.int(lo), self.int(hi));
        let m = self.math2(M::Max, i, lo);
        self.math2(M::Min, m, hi)
    }

    // ---------------------------------------------------------------------------------------------
    // Transformations.

    /// `v` transformed by the language matrix `m` (entries row by row) under `rule`, in the
    /// row-vector convention; `inv` is `m`'s inverse, which only normals use. The interpreter's
    /// `apply`, sum for sum.
    pub(super) fn apply(&mut self, v: &[Value], rule: Rule, m: &[Value], inv: &[Value]) -> Vec<Value> {
        let row_times = |this: &mut Self, j: usize, mat: &dyn Fn(usize, usize) -> Value, w: Option<Value>| {
            let mut sum = this.mul(v[0], mat(0, j));
            for (i, x) in v.iter().enumerate().skip(1).take(2) {
                let p = this.mul(*x, mat(i, j));
                sum = this.add(sum, p);
            }
            match w {
                Some(t) => this.add(sum, t),
                None => sum,
            }
        };
        match rule {
            Rule::Point => {
                let out: Vec<Value> =
                    (0..4).map(|j| row_times(self, j, &|i, j| m[i * 4 + j], Some(m[12 + j]))).collect();
                (0..3).map(|j| self.div(out[j], out[3])).collect()
            }
            Rule::Vector => (0..3).map(|j| row_times(self, j, &|i, j| m[i * 4 + j], None)).collect(),
            // n' = n * inverse(M)^T: element (i, j) of the transpose is inv[j][i].
            Rule::Normal => (0..3).map(|j| row_times(self, j, &|i, j| inv[j * 4 + i], None)).collect(),
        }
    }

    /// The language product `a * b` of two `n` x `n` matrices (entries row by row).
    pub(super) fn product(&mut self, a: &[Value], b: &[Value], n: usize) -> Vec<Value> {
        let mut out = Vec::with_capacity(n * n);
        for i in 0..n {
            for j in 0..n {
                let row: Vec<Value> = (0..n).map(|k| a[i * n + k]).collect();
                let col: Vec<Value> = (0..n).map(|k| b[k * n + j]).collect();
                out.push(self.dot_parts(&row, &col));
            }
        }
        out
    }

    /// The inverse of an `n` x `n` matrix: the adjugate over the determinant, as the interpreter
    /// computes it (a singular matrix gives infinities or NaN).
    pub(super) fn invert_entries(&mut self, m: &[Value], n: usize) -> Vec<Value> {
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
                    self.fb.add(Expression::Unary { op: naga::UnaryOperator::Negate, expr: minor })
                };
                out[i * n + j] = self.div(signed, det);
            }
        }
        out
    }

    /// The determinant of the submatrix of the rows and columns given, by Laplace expansion along
    /// the first row (the interpreter's `minor`).
    pub(super) fn minor(&mut self, m: &[Value], n: usize, rows: &[usize], cols: &[usize]) -> Value {
        let at = |r: usize, c: usize| m[r * n + c];
        match rows.len() {
            0 => self.float(1.0),
            1 => at(rows[0], cols[0]),
            2 => {
                let a = self.mul(at(rows[0], cols[0]), at(rows[1], cols[1]));
                let b = self.mul(at(rows[0], cols[1]), at(rows[1], cols[0]));
                self.sub(a, b)
            }
            _ => {
                let mut sum: Option<Value> = None;
                for (k, &c) in cols.iter().enumerate() {
                    let rest: Vec<usize> = cols.iter().copied().filter(|x| *x != c).collect();
                    let sub = self.minor(m, n, &rows[1..], &rest);
                    let term = self.mul(at(rows[0], c), sub);
                    sum = Some(match sum {
                        None => term,
                        Some(s) if k % 2 == 0 => self.add(s, term),
                        Some(s) => self.sub(s, term),
                    });
                }
                sum.unwrap_or_else(|| self.float(1.0))
            }
        }
    }

    /// `comp(m, row, col)`: the element, row and column converted to integers and clamped to
    /// [0, 3] (as the interpreter does).
    pub(super) fn matrix_component(&mut self, m: Value, row: Value, col: Value) -> Value {
        let (row, col) = self.row_col(row, col);
        let r = self.fb.add(Expression::Access { base: m, index: row });
        self.fb.add(Expression::Access { base: r, index: col })
    }

    /// `setcomp(m, row, col, x)`: `m` with the element replaced (every entry selected).
    pub(super) fn matrix_with(&mut self, m: Value, row: Value, col: Value, x: Value) -> Value {
        let (row, col) = self.row_col(row, col);
        let four = self.fb.add(Expression::Literal(naga::Literal::U32(4)));
        let r4 = self.binary(Op::Multiply, row, four);
        let index = self.binary(Op::Add, r4, col);
        let old = self.entries(m, 4);
        let out: Vec<Value> = (0..16)
            .map(|k| {
                let kk = self.fb.add(Expression::Literal(naga::Literal::U32(k)));
                let here = self.binary(Op::Equal, index, kk);
                self.pick(here, x, old[k as usize])
            })
            .collect();
        self.matrix(&out, 4)
    }

    /// A row and column index from floats, clamped to [0, 3], as `u32`s.
    fn row_col(&mut self, row: Value, col: Value) -> (Value, Value) {
        let index = |this: &mut Self, x: Value| {
            let i = this.float_to_int(x);
            let i = this.clamp_int(i, 0, 3);
            this.fb.add(Expression::As { expr: i, kind: ScalarKind::Uint, convert: Some(4) })
        };
        (index(self, row), index(self, col))
    }

    /// `cond ? a : b` for matrices (naga selects only scalars and vectors): row by row.
    pub(super) fn select_matrix(&mut self, cond: Value, a: Value, b: Value, n: u32) -> Value {
        let rows: Vec<Value> = (0..n)
            .map(|i| {
                let (x, y) = (self.at(a, i), self.at(b, i));
                self.pick(cond, x, y)
            })
            .collect();
        let base = if n == 3 { Base::Matrix3 } else { Base::Matrix4 };
        let ty = self.mb.ty(Type::of(base), false);
        self.fb.add(Expression::Compose { ty, components: rows })
    }
}
