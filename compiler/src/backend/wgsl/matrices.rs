//! Matrices and components, and [`Arith`] on naga expressions.
//!
//! WGSL leaves the order of a matrix product's or a `dot`'s sums to the implementation, so the
//! built-ins that need one take their operands apart into components and build the fixed sequence
//! of `backend::arith` on them, the one the interpreter runs: with IEEE `+ - * /` the results are
//! then the same bits. [`Arith`] is implemented here on whole values, so the componentwise
//! sequences (`clamp`, `mod`, ...) apply to vectors too, operands of equal width.
//!
//! Matrix convention: the module stores each language matrix transposed (a language row is a
//! WGSL column), so `m[i]` is language row `i` and `m[i][j]` is the language's element (i, j).
//! [`Translator::entries`] lists a matrix row by row as the interpreter's registers do, and
//! [`Translator::matrix`] builds one back from that list.

use naga::{BinaryOperator as Op, Expression, MathFunction as M, ScalarKind};

use crate::backend::arith::{Arith, Words};

use super::body::{Translator, Value};
use crate::ir::types::{Base, Type};

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
    // Integers.

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
                self.select(here, x, old[k as usize])
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
                self.select(cond, x, y)
            })
            .collect();
        let base = if n == 3 { Base::Matrix3 } else { Base::Matrix4 };
        let ty = self.mb.ty(Type::of(base), false);
        self.fb.add(Expression::Compose { ty, components: rows })
    }
}

impl Arith for Translator<'_> {
    type V = Value;
    type B = Value;
    fn constant(&mut self, x: f64) -> Value {
        self.float(x)
    }
    fn add(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Add, a, b)
    }
    fn sub(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Subtract, a, b)
    }
    fn mul(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Multiply, a, b)
    }
    fn div(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Divide, a, b)
    }
    fn neg(&mut self, a: Value) -> Value {
        self.fb.add(Expression::Unary { op: naga::UnaryOperator::Negate, expr: a })
    }
    fn sqrt(&mut self, a: Value) -> Value {
        self.math1(M::Sqrt, a)
    }
    fn floor(&mut self, a: Value) -> Value {
        self.math1(M::Floor, a)
    }
    fn min(&mut self, a: Value, b: Value) -> Value {
        self.math2(M::Min, a, b)
    }
    fn max(&mut self, a: Value, b: Value) -> Value {
        self.math2(M::Max, a, b)
    }
    fn less(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Less, a, b)
    }
    fn greater(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Greater, a, b)
    }
    fn greater_equal(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::GreaterEqual, a, b)
    }
    /// From the bits of an f32 scalar: comparisons with NaN are not reliable on every device.
    fn is_nan(&mut self, a: Value) -> Value {
        let bits = self.fb.add(Expression::As { expr: a, kind: ScalarKind::Uint, convert: None });
        let magnitude = self.fb.add(Expression::Literal(naga::Literal::U32(0x7fff_ffff)));
        let magnitude = self.binary(Op::And, bits, magnitude);
        let infinity = self.fb.add(Expression::Literal(naga::Literal::U32(0x7f80_0000)));
        self.binary(Op::Greater, magnitude, infinity)
    }
    fn select(&mut self, c: Value, a: Value, b: Value) -> Value {
        self.fb.add(Expression::Select { condition: c, accept: a, reject: b })
    }
}

impl Words for Translator<'_> {
    type W = Value;
    type F = Value;
    fn word(&mut self, x: u32) -> Value {
        self.fb.add(Expression::Literal(naga::Literal::U32(x)))
    }
    fn wrapping_mul(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Multiply, a, b)
    }
    fn wrapping_add(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::Add, a, b)
    }
    fn shift_right(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::ShiftRight, a, b)
    }
    fn xor(&mut self, a: Value, b: Value) -> Value {
        self.binary(Op::ExclusiveOr, a, b)
    }
    fn unit(&mut self, w: Value) -> Value {
        let f = self.fb.add(Expression::As { expr: w, kind: ScalarKind::Float, convert: Some(4) });
        let scale = self.float(1.0 / 16_777_216.0);
        self.binary(Op::Multiply, f, scale)
    }
}
