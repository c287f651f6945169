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
use crate::backend::arith::{self, Rule};
use crate::backend::cpu::code::{Binary, Compare, Reg};
use crate::diag::{Code as DiagCode, Diagnostic};
use crate::ir::ExprId;
use crate::ir::builtin::Builtin;
use crate::ir::builtin::BuiltinId as B;
use crate::ir::types::{Base, Type};

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
                        arith::apply(&mut self.emit, &value, rule, &to_m, &from_m)
                    }
                    (Val::Str(from), 3) if arg_ty(1).base == Base::String => {
                        let to = match &vals[1] {
                            Val::Str(s) => s.clone(),
                            _ => "current".into(),
                        };
                        let (to_from, from_from) = self.space_matrices(from);
                        let current = arith::apply(&mut self.emit, &value, rule, &from_from, &to_from);
                        let (to_m, from_m) = self.space_matrices(&to);
                        arith::apply(&mut self.emit, &current, rule, &to_m, &from_m)
                    }
                    (Val::Str(from), 3) => {
                        let (to_from, from_from) = self.space_matrices(from);
                        let current = arith::apply(&mut self.emit, &value, rule, &from_from, &to_from);
                        let m = vals[1].floats().to_vec();
                        let inv = arith::invert(&mut self.emit, &m, 4);
                        arith::apply(&mut self.emit, &current, rule, &m, &inv)
                    }
                    _ => {
                        let m = vals[0].floats().to_vec();
                        let inv = if rule == Rule::Normal {
                            arith::invert(&mut self.emit, &m, 4)
                        } else {
                            m.clone()
                        };
                        arith::apply(&mut self.emit, &value, rule, &m, &inv)
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
            B::Invert => {
                let n = if arg_ty(0).base == Base::Matrix3 { 3 } else { 4 };
                Val::Float(arith::invert(&mut self.emit, vals[0].floats(), n))
            }
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
            return Val::Float(arith::product(&mut self.emit, &value, &from_m, 4));
        }
        Val::Float(arith::apply(&mut self.emit, &value, Rule::of(ty.base), &from_m, &to_m))
    }
}
