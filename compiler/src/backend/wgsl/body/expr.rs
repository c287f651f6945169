//! Expressions to naga: variables, literals, indexing (clamped), conversions' callers, seeds.

use naga::{Expression, Literal as NLit, ScalarKind, UnaryOperator};

use super::{Translator, Value};
use crate::diag::Diagnostic;
use crate::ir::types::{Base, Type};
use crate::ir::{BinaryOp, ExprId, ExprKind, Literal, UnaryOp};
use crate::source::Span as SrcSpan;

/// The longest array whose run-time-indexed reads are written as a chain of selects (a colour
/// ramp's or a spline's few knots); longer ones are read through a pointer.
const SELECTED_ARRAY_MAX: u32 = 4;

impl Translator<'_> {
    /// The value of an expression (computed once per statement and light).
    pub fn expr(&mut self, id: ExprId) -> Result<Value, Diagnostic> {
        if let Some(v) = self.memo.get(&(id, self.light)) {
            return Ok(*v);
        }
        let v = stacker::maybe_grow(64 * 1024, 1024 * 1024, || self.expr_uncached(id))?;
        self.memo.insert((id, self.light), v);
        Ok(v)
    }

    /// An expression's value, computed afresh (see [`Translator::expr`]).
    pub(crate) fn expr_uncached(&mut self, id: ExprId) -> Result<Value, Diagnostic> {
        let e = self.shader.expr(id);
        let (ty, span) = (e.ty, e.span);
        Ok(match &e.kind {
            ExprKind::Literal(l) => self.literal(l, span)?,
            ExprKind::Local(l) => {
                if self.shader.local(*l).ty.base == Base::String {
                    return Err(self.error(span, "a string used as a value"));
                }
                if self.values.contains(l) {
                    return self.value(*l, span);
                }
                let g = self.local_var(*l);
                let p = self.pointer(g);
                self.load(p)
            }
            // The constant predefined variables are values, as in the interpreter, in every
            // function of the module (a light's or displacement's included).
            ExprKind::Global(g) if g.name == "PI" => self.float(std::f64::consts::PI),
            ExprKind::Global(g) if g.name == "ncomps" => self.float(3.0),
            ExprKind::Global(g) => {
                let var = self.global_var(g.name, Type::of(g.ty), g.perlight);
                let p = self.pointer(var);
                self.load(p)
            }
            ExprKind::Unary(op, a) => {
                let v = self.expr(*a)?;
                let op = match (op, self.shader.expr(*a).ty.base) {
                    (UnaryOp::Neg, _) => UnaryOperator::Negate,
                    (UnaryOp::Not, _) => UnaryOperator::LogicalNot,
                    (UnaryOp::BitNot, _) => UnaryOperator::BitwiseNot,
                };
                self.fb.add(Expression::Unary { op, expr: v })
            }
            ExprKind::LightSum { lights, value } => {
                let zero = self.float(0.0);
                let mut sum = self.splat(zero, e.ty.base.components());
                for &k in lights {
                    let outer = self.light.replace(k as usize);
                    let v = self.expr(*value);
                    self.light = outer;
                    sum = self.binary(naga::BinaryOperator::Add, sum, v?);
                }
                sum
            }
            ExprKind::Binary(op, a, b) if self.shader.expr(*a).ty.base == Base::String => {
                // Strings are known at compile time: so is their comparison.
                let (Some(x), Some(y)) = (self.fold_string(*a), self.fold_string(*b)) else {
                    return Err(self.error(span, "a comparison of strings not known at compile time"));
                };
                let equal = x == y;
                let result = if *op == BinaryOp::Eq { equal } else { !equal };
                self.fb.add(Expression::Literal(NLit::Bool(result)))
            }
            ExprKind::Binary(op, a, b) => {
                let (ta, tb) = (self.shader.expr(*a).ty, self.shader.expr(*b).ty);
                let (va, vb) = (self.expr(*a)?, self.expr(*b)?);
                self.binary_op(*op, va, ta, vb, tb, span)?
            }
            ExprKind::Convert(a) => {
                let from = self.shader.expr(*a).ty;
                let v = self.expr(*a)?;
                self.convert(v, from, ty, span)?
            }
            ExprKind::Construct(parts) => {
                let vals: Vec<Value> = parts.iter().map(|p| self.expr(*p)).collect::<Result<_, _>>()?;
                self.construct(&vals, ty)
            }
            ExprKind::FromSpace { space, value } => {
                let v = self.expr(*value)?;
                let from = self.shader.expr(*value).ty;
                self.space_to_current(space, v, from)
            }
            ExprKind::Index(base, index) if let Some(member) = self.uniform_table(*base) => {
                // Element `i` of a table in the uniform block: `u.table[i].x` (its elements are
                // padded to vec4s).
                let bt = self.shader.expr(*base).ty;
                let i = match self.constant_index(*index, bt) {
                    Some(c) => self.fb.add(Expression::Literal(NLit::U32(c))),
                    None => self.index(*index, bt)?,
                };
                let block = self.fb.add(Expression::GlobalVariable(self.mb.uniform_var));
                let array = self.fb.add(Expression::AccessIndex { base: block, index: member });
                let element = self.fb.add(Expression::Access { base: array, index: i });
                let x = self.fb.add(Expression::AccessIndex { base: element, index: 0 });
                self.load(x)
            }
            ExprKind::Index(base, index) => {
                let bt = self.shader.expr(*base).ty;
                if let Some(c) = self.constant_index(*index, bt) {
                    let v = self.expr(*base)?;
                    self.fb.add(Expression::AccessIndex { base: v, index: c })
                } else if bt.is_array()
                    && bt.array.is_some_and(|n| n <= SELECTED_ARRAY_MAX)
                    && !matches!(bt.base, Base::Matrix3 | Base::Matrix4)
                {
                    // A short array's element as a chain of selects over its elements: reads at
                    // constant indices leave the array in registers, where a read at a run-time
                    // index puts it in memory (lavapipe: scratch, a gather per read; GPUs: local
                    // memory). The clamped index picks the same element either way.
                    let n = bt.array.unwrap_or(1);
                    let v = self.expr(*base)?;
                    let i = self.index(*index, bt)?;
                    let mut element = self.fb.add(Expression::AccessIndex { base: v, index: 0 });
                    for j in 1..n {
                        let e = self.fb.add(Expression::AccessIndex { base: v, index: j });
                        let at = self.fb.add(Expression::Literal(NLit::U32(j)));
                        let hit = self.binary(naga::BinaryOperator::Equal, i, at);
                        element =
                            self.fb.add(Expression::Select { condition: hit, accept: e, reject: element });
                    }
                    element
                } else if bt.is_array() {
                    // Arrays are indexed through a pointer (naga indexes array values only by
                    // constants): the variable's own, or a temporary's.
                    let pointer = match &self.shader.expr(*base).kind {
                        ExprKind::Local(l) => {
                            let g = self.local_var(*l);
                            self.pointer(g)
                        }
                        _ => {
                            let v = self.expr(*base)?;
                            let name = format!("{}array_{}", self.prefix, base.0);
                            let g = self.mb.private(&name, bt);
                            let p = self.pointer(g);
                            self.store(p, v);
                            self.pointer(g)
                        }
                    };
                    let i = self.index(*index, bt)?;
                    let element = self.fb.add(Expression::Access { base: pointer, index: i });
                    self.load(element)
                } else {
                    let v = self.expr(*base)?;
                    let i = self.index(*index, bt)?;
                    self.fb.add(Expression::Access { base: v, index: i })
                }
            }
            ExprKind::Select(c, a, b) => {
                let c = self.condition(*c)?;
                let (a, b) = (self.expr(*a)?, self.expr(*b)?);
                if ty.is_array() || matches!(ty.base, Base::Matrix3 | Base::Matrix4) {
                    return Err(self.error(span, "`?:` on arrays or matrices"));
                }
                self.fb.add(Expression::Select { condition: c, accept: a, reject: b })
            }
            ExprKind::Builtin(b, args) => self.builtin(b, args, id)?,
            ExprKind::Seed(input, axis) => {
                let name = crate::backend::wgsl::entry::seed_name(self.shader, *input, *axis);
                let g = self.mb.private(&format!("{}{name}", self.prefix), ty);
                let p = self.pointer(g);
                self.load(p)
            }
        })
    }

    /// A literal index, clamped into range as the interpreter clamps; `None` for computed ones.
    pub(crate) fn constant_index(&self, index: ExprId, ty: Type) -> Option<u32> {
        let len = ty.array.unwrap_or(match ty.base {
            Base::Matrix3 => 3,
            Base::Matrix4 => 4,
            b => b.components(),
        });
        let i = match &self.shader.expr(index).kind {
            ExprKind::Literal(Literal::Int(i)) => i64::from(*i),
            ExprKind::Literal(Literal::Uint(u)) => i64::from(*u),
            _ => return None,
        };
        Some(i.clamp(0, i64::from(len.max(1) - 1)) as u32)
    }

    /// A literal as a naga value.
    pub(crate) fn literal(&mut self, l: &Literal, span: SrcSpan) -> Result<Value, Diagnostic> {
        Ok(match l {
            Literal::Float(x) => self.float(*x),
            Literal::Int(i) => self.fb.add(Expression::Literal(NLit::I32(*i))),
            Literal::Uint(u) => self.fb.add(Expression::Literal(NLit::U32(*u))),
            Literal::Bool(b) => self.fb.add(Expression::Literal(NLit::Bool(*b))),
            Literal::String(_) => return Err(self.error(span, "a string used as a value")),
        })
    }

    /// An `f32` constant; infinities and NaN (which WGSL literals cannot spell) by bit pattern.
    pub fn float(&mut self, x: f64) -> Value {
        let f = x as f32;
        if f.is_finite() {
            self.fb.add(Expression::Literal(NLit::F32(f)))
        } else {
            let bits = self.fb.add(Expression::Literal(NLit::U32(f.to_bits())));
            self.fb.add(Expression::As { expr: bits, kind: ScalarKind::Float, convert: None })
        }
    }
}
