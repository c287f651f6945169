//! Coordinate systems: values given in a named space, converted to "current" with the matrices
//! the uniform block carries, by the interpreter's rules (`backend/cpu/lower/geometry.rs`).

use naga::{BinaryOperator as Op, Expression, MathFunction as M, SwizzleComponent as C, VectorSize};

use super::body::{Translator, Value};
use super::interface::UniformSource;
use crate::diag::Diagnostic;
use crate::ir::types::{Base, Type};
use crate::source::Span;

impl Translator<'_> {
    /// The matrix from "current" to `space` (`inverse`: back), from the uniform block.
    pub(super) fn space_matrix(&mut self, space: &str, inverse: bool) -> Value {
        let source = UniformSource::Space { name: space.to_string(), inverse, light: self.owner };
        let name = format!("{}space_{space}{}", self.prefix, if inverse { "_inv" } else { "" });
        self.uniform_value(&name, Type::of(Base::Matrix4), source)
    }

    /// A member of the uniform block, loaded.
    pub(super) fn uniform_value(&mut self, name: &str, ty: Type, source: UniformSource) -> Value {
        let index = self.mb.uniform(name, ty, source);
        let block = self.fb.add(Expression::GlobalVariable(self.mb.uniform_var));
        let member = self.fb.add(Expression::AccessIndex { base: block, index });
        self.load(member)
    }

    /// `v` (of type `ty`) given in `space`, converted to "current".
    pub(super) fn space_to_current(
        &mut self,
        space: &str,
        v: Value,
        ty: Type,
        span: Span,
    ) -> Result<Value, Diagnostic> {
        if ty.base == Base::Color {
            return self.colour_to_rgb(space, v, span);
        }
        if matches!(space, "current" | "camera") {
            return Ok(v);
        }
        let from = self.space_matrix(space, true);
        Ok(match ty.base {
            // Language V * F; the module stores matrices transposed, so the product swaps.
            Base::Matrix4 => self.binary(Op::Multiply, from, v),
            Base::Normal => {
                let to = self.space_matrix(space, false);
                let t = self.math1(M::Transpose, to);
                self.transform_by(t, v, 0.0)
            }
            Base::Vector => self.transform_by(from, v, 0.0),
            _ => {
                let p = self.transform_by_full(from, v);
                let w = self.fb.add(Expression::AccessIndex { base: p, index: 3 });
                let xyz = self.xyz(p);
                let w = self.splat(w, 3);
                self.binary(Op::Divide, xyz, w)
            }
        })
    }

    /// `(m * vec4(v, w)).xyz`.
    pub(super) fn transform_by(&mut self, m: Value, v: Value, w: f64) -> Value {
        let w = self.float(w);
        let ty = self.mb.ty(Type::of(Base::Float4), false);
        let v4 = self.fb.add(Expression::Compose { ty, components: vec![v, w] });
        let r = self.binary(Op::Multiply, m, v4);
        self.xyz(r)
    }

    /// `m * vec4(v, 1)`.
    fn transform_by_full(&mut self, m: Value, v: Value) -> Value {
        let one = self.float(1.0);
        let ty = self.mb.ty(Type::of(Base::Float4), false);
        let v4 = self.fb.add(Expression::Compose { ty, components: vec![v, one] });
        self.binary(Op::Multiply, m, v4)
    }

    /// The first three components of a `vec4`.
    pub(super) fn xyz(&mut self, v: Value) -> Value {
        self.fb.add(Expression::Swizzle {
            size: VectorSize::Tri,
            vector: v,
            pattern: [C::X, C::Y, C::Z, C::X],
        })
    }

    /// A colour given in a named colour space, converted to RGB.
    pub(super) fn colour_to_rgb(&mut self, space: &str, v: Value, span: Span) -> Result<Value, Diagnostic> {
        match space {
            "rgb" => Ok(v),
            _ => Err(self.error(span, format!("colour space `{space}` on the GPU"))),
        }
    }
}
