//! Coordinate systems and the geometric built-ins: values given in a named space, converted to
//! "current" with the matrices the uniform block carries, `transform` and its family, `refract`
//! and `depth`, by the interpreter's rules (`backend/cpu/lower/geometry.rs`), operation for
//! operation (see `matrices`).

use crate::ir::builtin::BuiltinId;
use naga::{BinaryOperator as Op, Expression, SwizzleComponent as C, VectorSize};

use super::body::{Translator, Value};
use super::interface::UniformSource;
use crate::backend::CLIP_INPUT;
use crate::backend::arith::{self, Arith, Rule};
use crate::diag::{Code, Diagnostic};
use crate::ir::types::{Base, Type};
use crate::ir::{ExprId, ExprKind};
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

    /// The entries of a named space's matrices: (current to it, it to current); the identity's
    /// for "current" and "camera", which the interpreter still multiplies by.
    pub(super) fn space_entries(&mut self, space: &str) -> (Vec<Value>, Vec<Value>) {
        if matches!(space, "current" | "camera") {
            let identity = self.identity_entries();
            return (identity.clone(), identity);
        }
        let to = self.space_matrix(space, false);
        let from = self.space_matrix(space, true);
        (self.entries(to, 4), self.entries(from, 4))
    }

    /// `v` (of type `ty`) given in `space`, converted to "current" (colours never come here:
    /// their spaces are converted by library code).
    pub(super) fn space_to_current(&mut self, space: &str, v: Value, ty: Type) -> Value {
        if self.fast() && ty.base != Base::Matrix4 {
            return self.by_space(v, Rule::of(ty.base), space, false);
        }
        let (to_m, from_m) = self.space_entries(space);
        if ty.base == Base::Matrix4 {
            let value = self.entries(v, 4);
            let product = arith::product(self, &value, &from_m, 4);
            return self.matrix(&product, 4);
        }
        let value = self.parts(v, 3);
        let out = arith::apply(self, &value, Rule::of(ty.base), &from_m, &to_m);
        self.vector(&out)
    }

    /// `transform`, `vtransform` and `ntransform` in their four forms: to a space, from one space
    /// to another, by a matrix, and from a space by a matrix.
    pub(super) fn transform(
        &mut self,
        which: BuiltinId,
        args: &[ExprId],
        vals: &[Value],
        ret: Type,
        span: Span,
    ) -> Result<Value, Diagnostic> {
        let rule = match which {
            BuiltinId::VTransform => Rule::Vector,
            BuiltinId::NTransform => Rule::Normal,
            _ => Rule::of(ret.base),
        };
        let is_string = |this: &Self, i: usize| this.shader.expr(args[i]).ty.base == Base::String;
        let last = vals.len() - 1;
        if self.fast() {
            // Spaces by their matrices; a matrix argument too, except for a normal, whose
            // inverse WGSL has no built-in for.
            match args.len() {
                2 if is_string(self, 0) => {
                    let to = self.space_name(args[0], span)?;
                    return Ok(self.by_space(vals[last], rule, &to, true));
                }
                3 if is_string(self, 1) => {
                    let (from, to) = (self.space_name(args[0], span)?, self.space_name(args[1], span)?);
                    let current = self.by_space(vals[last], rule, &from, false);
                    return Ok(self.by_space(current, rule, &to, true));
                }
                3 if rule != Rule::Normal => {
                    let from = self.space_name(args[0], span)?;
                    let current = self.by_space(vals[last], rule, &from, false);
                    return Ok(self.apply_matrix(current, rule, vals[1]));
                }
                2 if rule != Rule::Normal => return Ok(self.apply_matrix(vals[1], rule, vals[0])),
                _ => {}
            }
        }
        let value = self.parts(vals[last], 3);
        let out = match args.len() {
            2 if is_string(self, 0) => {
                let to = self.space_name(args[0], span)?;
                let (to_m, from_m) = self.space_entries(&to);
                arith::apply(self, &value, rule, &to_m, &from_m)
            }
            3 if is_string(self, 1) => {
                let from = self.space_name(args[0], span)?;
                let to = self.space_name(args[1], span)?;
                let (to_from, from_from) = self.space_entries(&from);
                let current = arith::apply(self, &value, rule, &from_from, &to_from);
                let (to_m, from_m) = self.space_entries(&to);
                arith::apply(self, &current, rule, &to_m, &from_m)
            }
            3 => {
                let from = self.space_name(args[0], span)?;
                let (to_from, from_from) = self.space_entries(&from);
                let current = arith::apply(self, &value, rule, &from_from, &to_from);
                let m = self.entries(vals[1], 4);
                let inv = if rule == Rule::Normal { arith::invert(self, &m, 4) } else { m.clone() };
                arith::apply(self, &current, rule, &m, &inv)
            }
            _ => {
                let m = self.entries(vals[0], 4);
                let inv = if rule == Rule::Normal { arith::invert(self, &m, 4) } else { m.clone() };
                arith::apply(self, &value, rule, &m, &inv)
            }
        };
        Ok(self.vector(&out))
    }

    /// The fast lowering's conversion of `v` to the named space (`to`) or from it to "current":
    /// by the one matrix of the uniform block that `rule` needs (a normal goes by the inverse
    /// transpose, so by the other direction's matrix); "current" and "camera" are the identity.
    fn by_space(&mut self, v: Value, rule: Rule, space: &str, to: bool) -> Value {
        if matches!(space, "current" | "camera") {
            return v;
        }
        // `space_matrix(space, false)` is current to the space, `true` the space to current.
        let matrix = self.space_matrix(space, to == (rule == Rule::Normal));
        self.apply_matrix(v, rule, matrix)
    }

    /// The fast lowering's `transform`: `v` by the language matrix `m` under `rule` as WGSL
    /// matrix products, where for a normal `m` is the inverse of the transformation. A language
    /// row is a WGSL column, so the row vector `(v, 1) M` is `m * vec4(v, 1)`, and a normal's
    /// `n inv(M)^T` is `vec4(n, 0) * m`.
    fn apply_matrix(&mut self, v: Value, rule: Rule, m: Value) -> Value {
        let w = self.float(if rule == Rule::Point { 1.0 } else { 0.0 });
        let ty = self.mb.ty(Type::of(Base::Float4), false);
        let v4 = self.fb.add(Expression::Compose { ty, components: vec![v, w] });
        let product = match rule {
            Rule::Normal => self.binary(Op::Multiply, v4, m),
            _ => self.binary(Op::Multiply, m, v4),
        };
        let xyz = self.xyz(product);
        if rule != Rule::Point {
            return xyz;
        }
        let w = self.at(product, 3);
        let w = self.splat(w, 3);
        self.div(xyz, w)
    }

    /// The name of a space, which must be known when the shader is compiled.
    fn space_name(&self, id: ExprId, span: Span) -> Result<String, Diagnostic> {
        self.fold_string(id).map(|s| s.to_string()).ok_or_else(|| {
            Diagnostic::error(
                Code::NotExecutable,
                "the name of a coordinate system must be known when the shader is compiled",
                span,
                "in this call",
            )
            .with_help("pass a string literal or a string parameter")
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

    /// The first three components of a `vec4`.
    pub(super) fn xyz(&mut self, v: Value) -> Value {
        self.fb.add(Expression::Swizzle {
            size: VectorSize::Tri,
            vector: v,
            pattern: [C::X, C::Y, C::Z, C::X],
        })
    }

    /// Stores into the variable passed as an `output` argument (anything else is not stored, as
    /// in the interpreter).
    pub(super) fn write_output(&mut self, arg: ExprId, v: Value) {
        let var = match &self.shader.expr(arg).kind {
            ExprKind::Local(l) => self.local_var(*l),
            ExprKind::Global(g) => self.global_var(g.name, Type::of(g.ty), g.perlight),
            _ => return,
        };
        let p = self.pointer(var);
        self.store(p, v);
    }

    /// `depth(p)`: `(z - near) / (far - near)`, near and far from the [`CLIP_INPUT`] uniform
    /// (an empty range counts as 1, as in the interpreter).
    pub(super) fn depth(&mut self, p: Value) -> Value {
        let ty = Type { base: Base::Float, array: Some(2) };
        let clip = self.uniform_value(CLIP_INPUT, ty, UniformSource::Global { name: CLIP_INPUT.into() });
        // Uniform arrays of floats are padded to `vec4` elements.
        let near = self.at(clip, 0);
        let near = self.at(near, 0);
        let far = self.at(clip, 1);
        let far = self.at(far, 0);
        let z = self.at(p, 2);
        let range = self.sub(far, near);
        let (zero, one) = (self.float(0.0), self.float(1.0));
        let empty = self.binary(Op::Equal, range, zero);
        let range = self.select(empty, one, range);
        let from_near = self.sub(z, near);
        self.div(from_near, range)
    }
}
