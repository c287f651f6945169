//! Operators and conversions with the language's meaning: scalars widened, matrix products in
//! the interpreter's order, comparisons of vectors, shifts masked.

use naga::{BinaryOperator, Expression, Literal as NLit, MathFunction, RelationalFunction, ScalarKind};

use super::{Translator, Value};
use crate::backend::wgsl::module::vector_size;
use crate::diag::Diagnostic;
use crate::ir::BinaryOp;
use crate::ir::types::{Base, Type};
use crate::source::Span as SrcSpan;

impl Translator<'_> {
    /// `left op right`.
    pub fn binary(&mut self, op: BinaryOperator, left: Value, right: Value) -> Value {
        self.fb.add(Expression::Binary { op, left, right })
    }

    /// A math function of one argument.
    pub fn math1(&mut self, fun: MathFunction, arg: Value) -> Value {
        self.fb.add(Expression::Math { fun, arg, arg1: None, arg2: None, arg3: None })
    }

    /// A math function of two arguments.
    pub fn math2(&mut self, fun: MathFunction, arg: Value, arg1: Value) -> Value {
        self.fb.add(Expression::Math { fun, arg, arg1: Some(arg1), arg2: None, arg3: None })
    }

    /// A math function of three arguments.
    pub fn math3(&mut self, fun: MathFunction, arg: Value, arg1: Value, arg2: Value) -> Value {
        self.fb.add(Expression::Math { fun, arg, arg1: Some(arg1), arg2: Some(arg2), arg3: None })
    }

    /// A scalar widened to `n` components (`n == 1`: as it is).
    pub fn splat(&mut self, v: Value, n: u32) -> Value {
        if n <= 1 { v } else { self.fb.add(Expression::Splat { size: vector_size(n), value: v }) }
    }

    /// A language binary operator on values of types `ta` and `tb`.
    pub(crate) fn binary_op(
        &mut self,
        op: BinaryOp,
        a: Value,
        ta: Type,
        b: Value,
        tb: Type,
        span: SrcSpan,
    ) -> Result<Value, Diagnostic> {
        use BinaryOp as B;
        let matrix = |t: Type| !t.is_array() && matches!(t.base, Base::Matrix3 | Base::Matrix4);
        let width = |t: Type| if matrix(t) { 0 } else { t.base.components() };
        if matches!(op, B::Mul) && (matrix(ta) || matrix(tb)) && width(ta) != 1 && width(tb) != 1 {
            return Ok(self.mat_mul(a, ta, b, tb));
        }
        if matches!(op, B::Div) && matrix(tb) {
            // RenderMan: a / M = a * inverse(M), with the interpreter's inverse.
            let n = if tb.base == Base::Matrix3 { 3 } else { 4 };
            let entries = self.entries(b, n);
            let inverse = crate::backend::arith::invert(self, &entries, n as usize);
            let inverse = self.matrix(&inverse, n);
            return Ok(self.mat_mul(a, ta, inverse, tb));
        }
        // A scalar operand applies to every component.
        let (a, b) = match (width(ta), width(tb)) {
            (1, n) if n > 1 => (self.splat(a, n), b),
            (n, 1) if n > 1 => (a, self.splat(b, n)),
            _ => (a, b),
        };
        let (a, b) = if matrix(ta) && width(tb) == 1 && matches!(op, B::Add | B::Sub) {
            // RenderMan: a scalar added to a matrix is the scaled identity.
            let m = self.scalar_to_matrix(b, ta.base);
            (a, m)
        } else {
            (a, b)
        };
        let bop = match op {
            B::Add => BinaryOperator::Add,
            B::Sub => BinaryOperator::Subtract,
            B::Mul => BinaryOperator::Multiply,
            B::Div => BinaryOperator::Divide,
            B::Rem => BinaryOperator::Modulo,
            B::BitXor => BinaryOperator::ExclusiveOr,
            B::BitAnd => BinaryOperator::And,
            B::BitOr => BinaryOperator::InclusiveOr,
            B::Shl => BinaryOperator::ShiftLeft,
            B::Shr => BinaryOperator::ShiftRight,
            B::And => BinaryOperator::LogicalAnd,
            B::Or => BinaryOperator::LogicalOr,
            B::Dot => return Ok(self.math2(MathFunction::Dot, a, b)),
            B::Cross => return Ok(self.math2(MathFunction::Cross, a, b)),
            B::Eq | B::Ne | B::Lt | B::Le | B::Gt | B::Ge => return self.comparison(op, a, ta, b, tb, span),
        };
        let (a, b) = if matches!(op, B::Shl | B::Shr) {
            // WGSL shifts by a `u32`, and only by less than 32: the interpreter masks the same way.
            let b = if tb.base == Base::Int {
                self.fb.add(Expression::As { expr: b, kind: ScalarKind::Uint, convert: Some(4) })
            } else {
                b
            };
            let mask = self.fb.add(Expression::Literal(NLit::U32(31)));
            (a, self.binary(BinaryOperator::And, b, mask))
        } else {
            (a, b)
        };
        if matches!(op, B::Div | B::Rem) && self.is_integer_zero(b) {
            // naga (as WGSL) rejects an integer division or remainder by a constant zero when the
            // module is created, though it defines the value at run time: x / 0 = x, x % 0 = 0,
            // the interpreter's rule. A literal zero divisor gets that value here.
            return Ok(if matches!(op, B::Div) { a } else { self.binary(BinaryOperator::Subtract, a, a) });
        }
        Ok(self.binary(bop, a, b))
    }

    /// Whether `v` is an integer literal zero (or one splatted).
    fn is_integer_zero(&self, v: Value) -> bool {
        match self.fb.f.expressions[v] {
            Expression::Literal(NLit::I32(0) | NLit::U32(0)) => true,
            Expression::Splat { value, .. } => self.is_integer_zero(value),
            _ => false,
        }
    }

    /// A comparison; vectors compare equal when every component does, unequal when any does.
    pub(crate) fn comparison(
        &mut self,
        op: BinaryOp,
        a: Value,
        ta: Type,
        b: Value,
        tb: Type,
        span: SrcSpan,
    ) -> Result<Value, Diagnostic> {
        if ta.is_array() || matches!(ta.base, Base::Matrix3 | Base::Matrix4) {
            return Err(self.error(span, "comparison of arrays or matrices"));
        }
        let n = ta.base.components().max(tb.base.components());
        let a = if ta.base.components() == 1 { self.splat(a, n) } else { a };
        let b = if tb.base.components() == 1 { self.splat(b, n) } else { b };
        let bop = match op {
            BinaryOp::Eq => BinaryOperator::Equal,
            BinaryOp::Ne => BinaryOperator::NotEqual,
            BinaryOp::Lt => BinaryOperator::Less,
            BinaryOp::Le => BinaryOperator::LessEqual,
            BinaryOp::Gt => BinaryOperator::Greater,
            _ => BinaryOperator::GreaterEqual,
        };
        let c = self.binary(bop, a, b);
        if n <= 1 {
            return Ok(c);
        }
        // Vectors are equal when every component is, and unequal when any is.
        let fun = if op == BinaryOp::Ne { RelationalFunction::Any } else { RelationalFunction::All };
        Ok(self.fb.add(Expression::Relational { fun, argument: c }))
    }

    /// Matrix products with the language's meaning. The module stores each matrix transposed
    /// (a language row is a WGSL column), so every product swaps its operands; a
    /// three-component vector with a 4x4 matrix is a point (w = 1, divided by the result's w).
    pub(crate) fn mat_mul(&mut self, a: Value, ta: Type, b: Value, tb: Type) -> Value {
        let is_m = |t: Type| matches!(t.base, Base::Matrix3 | Base::Matrix4);
        let four = ta.base == Base::Matrix4 || tb.base == Base::Matrix4;
        let extend = |this: &mut Self, v: Value, t: Type| -> (Value, bool) {
            if four && t.base.components() == 3 {
                let one = this.float(1.0);
                let ty = this.mb.ty(Type::of(Base::Float4), false);
                (this.fb.add(Expression::Compose { ty, components: vec![v, one] }), true)
            } else {
                (v, false)
            }
        };
        let (product, point) = match (is_m(ta), is_m(tb)) {
            (true, true) => {
                // Entry by entry in the interpreter's order of sums (WGSL leaves it open).
                let n = if four { 4 } else { 3 };
                let (x, y) = (self.entries(a, n), self.entries(b, n));
                let entries = crate::backend::arith::product(self, &x, &y, n as usize);
                (self.matrix(&entries, n), false)
            }
            (true, false) => {
                let (v, point) = extend(self, b, tb);
                (self.binary(BinaryOperator::Multiply, v, a), point)
            }
            _ => {
                let (v, point) = extend(self, a, ta);
                (self.binary(BinaryOperator::Multiply, b, v), point)
            }
        };
        if !point {
            return product;
        }
        let w = self.fb.add(Expression::AccessIndex { base: product, index: 3 });
        let xyz = self.fb.add(Expression::Swizzle {
            size: naga::VectorSize::Tri,
            vector: product,
            pattern: [
                naga::SwizzleComponent::X,
                naga::SwizzleComponent::Y,
                naga::SwizzleComponent::Z,
                naga::SwizzleComponent::X,
            ],
        });
        let w = self.splat(w, 3);
        self.binary(BinaryOperator::Divide, xyz, w)
    }

    /// `x` times the identity.
    pub fn scalar_to_matrix(&mut self, x: Value, base: Base) -> Value {
        let n = if base == Base::Matrix3 { 3 } else { 4 };
        let zero = self.float(0.0);
        let column_ty = self.mb.ty(Type::of(if n == 3 { Base::Float3 } else { Base::Float4 }), false);
        let columns: Vec<Value> = (0..n)
            .map(|c| {
                let components = (0..n).map(|r| if r == c { x } else { zero }).collect();
                self.fb.add(Expression::Compose { ty: column_ty, components })
            })
            .collect();
        let ty = self.mb.ty(Type::of(base), false);
        self.fb.add(Expression::Compose { ty, components: columns })
    }

    /// The implicit and explicit conversions, as the interpreter defines them.
    pub(crate) fn convert(
        &mut self,
        v: Value,
        from: Type,
        to: Type,
        span: SrcSpan,
    ) -> Result<Value, Diagnostic> {
        if from.is_array() || to.is_array() {
            if from.base == to.base {
                return Ok(v);
            }
            return Err(self.error(span, "conversion of arrays of a different type"));
        }
        let (f, t) = (from.base, to.base);
        let to_float = !matches!(t, Base::Bool | Base::Int | Base::Uint);
        if to_float {
            let scalar = if matches!(f, Base::Int | Base::Uint | Base::Bool) {
                self.fb.add(Expression::As { expr: v, kind: ScalarKind::Float, convert: Some(4) })
            } else {
                v
            };
            let from_n = if matches!(f, Base::Int | Base::Uint | Base::Bool) { 1 } else { f.components() };
            return Ok(match (from_n, t) {
                (1, Base::Matrix3 | Base::Matrix4) => self.scalar_to_matrix(scalar, t),
                (1, _) if t.components() > 1 => self.splat(scalar, t.components()),
                (1, Base::Clampf) => {
                    let (zero, one) = (self.float(0.0), self.float(1.0));
                    self.math3(MathFunction::Clamp, scalar, zero, one)
                }
                _ => scalar,
            });
        }
        Ok(match (f, t) {
            (Base::Int | Base::Uint | Base::Bool, Base::Int) => {
                self.fb.add(Expression::As { expr: v, kind: ScalarKind::Sint, convert: Some(4) })
            }
            (Base::Int | Base::Uint | Base::Bool, Base::Uint) => {
                self.fb.add(Expression::As { expr: v, kind: ScalarKind::Uint, convert: Some(4) })
            }
            (Base::Bool, Base::Bool) => v,
            (Base::Int, Base::Bool) => {
                let zero = self.fb.add(Expression::Literal(NLit::I32(0)));
                self.binary(BinaryOperator::NotEqual, v, zero)
            }
            (Base::Uint, Base::Bool) => {
                let zero = self.fb.add(Expression::Literal(NLit::U32(0)));
                self.binary(BinaryOperator::NotEqual, v, zero)
            }
            (_, Base::Int) => {
                self.fb.add(Expression::As { expr: v, kind: ScalarKind::Sint, convert: Some(4) })
            }
            (_, Base::Uint) => {
                self.fb.add(Expression::As { expr: v, kind: ScalarKind::Uint, convert: Some(4) })
            }
            _ => {
                let zero = self.float(0.0);
                self.binary(BinaryOperator::NotEqual, v, zero)
            }
        })
    }

    /// A value of type `ty` from its parts: vectors from scalars, matrices from 9 or 16 floats
    /// (row by row in the language, so each row is a WGSL column), arrays from elements.
    pub(crate) fn construct(&mut self, parts: &[Value], ty: Type) -> Value {
        let naga_ty = self.mb.ty(ty, false);
        if !ty.is_array() && matches!(ty.base, Base::Matrix3 | Base::Matrix4) {
            if parts.len() == 1 {
                return self.scalar_to_matrix(parts[0], ty.base);
            }
            let n = if ty.base == Base::Matrix3 { 3 } else { 4 };
            let column_ty = self.mb.ty(Type::of(if n == 3 { Base::Float3 } else { Base::Float4 }), false);
            let columns = parts
                .chunks(n)
                .map(|row| self.fb.add(Expression::Compose { ty: column_ty, components: row.to_vec() }))
                .collect();
            return self.fb.add(Expression::Compose { ty: naga_ty, components: columns });
        }
        if parts.len() == 1 && !ty.is_array() && ty.base.components() == 1 {
            return parts[0];
        }
        self.fb.add(Expression::Compose { ty: naga_ty, components: parts.to_vec() })
    }
}
