//! Expressions: each becomes the registers of its components.

use super::stmt::Access;
use super::{Lower, Val};
use crate::backend::arith;
use crate::backend::cpu::code::{Binary, Compare, Convert, IntBinary, IntUnary, Reg, Unary};
use crate::diag::Diagnostic;
use crate::ir::types::{Base, Type};
use crate::ir::{BinaryOp, ExprId, ExprKind, Literal, LocalKind, UnaryOp};

impl Lower<'_> {
    /// The value of an expression (computed once per statement and light).
    pub(crate) fn expr(&mut self, id: ExprId) -> Result<Val, Diagnostic> {
        if let Some(v) = self.memo_get(id) {
            return Ok(v);
        }
        let v = stacker::maybe_grow(64 * 1024, 1024 * 1024, || self.expr_uncached(id))?;
        self.memo_put(id, &v);
        Ok(v)
    }

    fn expr_uncached(&mut self, id: ExprId) -> Result<Val, Diagnostic> {
        let e = self.shader.expr(id);
        Ok(match &e.kind {
            ExprKind::Literal(l) => match l {
                Literal::Float(x) => Val::Float(vec![self.emit.float(*x)]),
                Literal::Int(i) => Val::Int(vec![self.emit.int(*i as u32)]),
                Literal::Uint(u) => Val::Int(vec![self.emit.int(*u)]),
                Literal::Bool(b) => Val::Int(vec![self.emit.int(u32::from(*b))]),
                Literal::String(s) => Val::Str(s.clone()),
            },
            ExprKind::Local(l) => {
                let local = self.shader.local(*l);
                if local.ty.base == Base::String {
                    return self.string_local(*l);
                }
                self.local(*l)
            }
            ExprKind::Global(g) => self.global(g),
            ExprKind::Unary(op, a) => {
                let a = self.expr(*a)?;
                self.unary_op(*op, &a)
            }
            ExprKind::Binary(op, a, b) => {
                let (ta, tb) = (self.shader.expr(*a).ty, self.shader.expr(*b).ty);
                let (va, vb) = (self.expr(*a)?, self.expr(*b)?);
                self.binary_op(*op, &va, ta, &vb, tb)
            }
            ExprKind::Convert(a) => {
                let from = self.shader.expr(*a).ty;
                let v = self.expr(*a)?;
                self.convert(&v, from, e.ty)
            }
            ExprKind::Construct(parts) => {
                let vals: Vec<Val> = parts.iter().map(|p| self.expr(*p)).collect::<Result<_, _>>()?;
                self.construct(&vals, e.ty)
            }
            ExprKind::LightSum { lights, value } => {
                let mut sum = vec![self.emit.float(0.0); e.ty.base.components() as usize];
                for &k in lights {
                    let outer = self.light.replace(k as usize);
                    let v = self.expr(*value);
                    self.light = outer;
                    sum = self.zip(Binary::Add, &sum, v?.floats());
                }
                Val::Float(sum)
            }
            ExprKind::FromSpace { space, value } => {
                let v = self.expr(*value)?;
                let ty = self.shader.expr(*value).ty;
                self.space_to_current(space, &v, ty)
            }
            ExprKind::Index(base, index) => {
                let ty = self.shader.expr(*base).ty;
                let v = self.expr(*base)?;
                let access = self.contiguous(v);
                let a = self.index_access(access, ty, *index)?;
                self.read(&a)
            }
            ExprKind::Select(c, a, b) => {
                let c = self.condition(*c)?;
                let (a, b) = (self.expr(*a)?, self.expr(*b)?);
                self.select(c, &a, &b)
            }
            ExprKind::Builtin(b, args) => self.builtin(b, args, id)?,
            ExprKind::Seed(input, axis) => self.seed(*input, *axis, e.ty),
        })
    }

    /// A string variable's value: strings are known when the program is compiled (parameters from
    /// the binding or their defaults).
    fn string_local(&mut self, id: crate::ir::LocalId) -> Result<Val, Diagnostic> {
        if let Some(s) = self.bound_string(id) {
            return Ok(Val::Str(s));
        }
        match self.shader.local(id).kind {
            LocalKind::Param { default: Some(d), .. } => self.expr(d),
            _ => Ok(Val::Str("".into())),
        }
    }

    /// An access to all of a value's registers, copied into consecutive ones if they are not (an
    /// index needs them consecutive and of one kind).
    fn contiguous(&mut self, v: Val) -> Access {
        let float = matches!(v, Val::Float(_));
        let regs = match v {
            Val::Float(r) | Val::Int(r) => r,
            _ => Vec::new(),
        };
        let root = self.emit.consecutive(float, regs);
        Access { width: root.len() as u32, root, float, offset: 0, dynamic: None }
    }

    fn unary_op(&mut self, op: UnaryOp, a: &Val) -> Val {
        match (op, a) {
            (UnaryOp::Neg, Val::Float(r)) => {
                Val::Float(r.iter().map(|x| self.emit.unary(Unary::Neg, *x)).collect())
            }
            (UnaryOp::Neg, Val::Int(r)) => {
                Val::Int(r.iter().map(|x| self.emit.int_unary(IntUnary::Neg, *x)).collect())
            }
            (UnaryOp::BitNot, Val::Int(r)) => {
                Val::Int(r.iter().map(|x| self.emit.int_unary(IntUnary::Not, *x)).collect())
            }
            (UnaryOp::Not, v) => {
                let t = self.truth(v);
                Val::Int(vec![self.emit.int_unary(IntUnary::LogicalNot, t)])
            }
            (_, v) => v.clone(),
        }
    }

    fn binary_op(&mut self, op: BinaryOp, a: &Val, ta: Type, b: &Val, tb: Type) -> Val {
        use BinaryOp as B;
        let signed = ta.base == Base::Int;
        match op {
            B::Add | B::Sub | B::Div if matches!(a, Val::Float(_)) => {
                let op = match op {
                    B::Add => Binary::Add,
                    B::Sub => Binary::Sub,
                    _ => Binary::Div,
                };
                if op == Binary::Div && is_matrix(tb) {
                    // RenderMan: a / M = a * inverse(M).
                    let n = if tb.base == Base::Matrix3 { 3 } else { 4 };
                    let inv = arith::invert(&mut self.emit, b.floats(), n);
                    return self.mat_mul(a.floats(), ta, &inv, tb);
                }
                Val::Float(self.zip(op, a.floats(), b.floats()))
            }
            B::Mul if matches!(a, Val::Float(_)) => {
                if (is_matrix(ta) || is_matrix(tb)) && a.floats().len() > 1 && b.floats().len() > 1 {
                    self.mat_mul(a.floats(), ta, b.floats(), tb)
                } else {
                    Val::Float(self.zip(Binary::Mul, a.floats(), b.floats()))
                }
            }
            B::Add
            | B::Sub
            | B::Mul
            | B::Div
            | B::Rem
            | B::BitAnd
            | B::BitOr
            | B::BitXor
            | B::Shl
            | B::Shr => {
                let op = match op {
                    B::Add => IntBinary::Add,
                    B::Sub => IntBinary::Sub,
                    B::Mul => IntBinary::Mul,
                    B::Div if signed => IntBinary::DivI,
                    B::Div => IntBinary::DivU,
                    B::Rem if signed => IntBinary::RemI,
                    B::Rem => IntBinary::RemU,
                    B::BitAnd => IntBinary::And,
                    B::BitOr => IntBinary::Or,
                    B::BitXor => IntBinary::Xor,
                    B::Shl => IntBinary::Shl,
                    B::Shr if signed => IntBinary::ShrI,
                    _ => IntBinary::ShrU,
                };
                let (a, b) = (a.ints(), b.ints());
                let n = a.len().max(b.len());
                Val::Int((0..n).map(|i| self.emit.int_binary(op, pick(a, i), pick(b, i))).collect())
            }
            B::Dot => Val::Float(vec![arith::dot(&mut self.emit, a.floats(), b.floats())]),
            B::Cross => Val::Float(arith::cross(&mut self.emit, a.floats(), b.floats()).to_vec()),
            B::Eq | B::Ne | B::Lt | B::Le | B::Gt | B::Ge => self.comparison(op, a, b, signed),
            B::And | B::Or => {
                let (x, y) = (self.truth(a), self.truth(b));
                let op = if op == B::And { IntBinary::And } else { IntBinary::Or };
                Val::Int(vec![self.emit.int_binary(op, x, y)])
            }
        }
    }

    fn comparison(&mut self, op: BinaryOp, a: &Val, b: &Val, signed: bool) -> Val {
        let cmp = match op {
            BinaryOp::Eq => Compare::Eq,
            BinaryOp::Ne => Compare::Ne,
            BinaryOp::Lt => Compare::Lt,
            BinaryOp::Le => Compare::Le,
            BinaryOp::Gt => Compare::Gt,
            _ => Compare::Ge,
        };
        let parts: Vec<Reg> = match (a, b) {
            (Val::Str(x), Val::Str(y)) => {
                let equal = x == y;
                return Val::Int(vec![self.emit.int(u32::from(if cmp == Compare::Eq {
                    equal
                } else {
                    !equal
                }))]);
            }
            (Val::Float(x), Val::Float(y)) => {
                let n = x.len().max(y.len());
                (0..n).map(|i| self.emit.compare(cmp, pick(x, i), pick(y, i))).collect()
            }
            (x, y) => {
                let (x, y) = (x.ints(), y.ints());
                let n = x.len().max(y.len());
                (0..n).map(|i| self.emit.int_compare(cmp, signed, pick(x, i), pick(y, i))).collect()
            }
        };
        // Vectors are equal when every component is, and unequal when any is.
        let join = if cmp == Compare::Ne { IntBinary::Or } else { IntBinary::And };
        let first = parts[0];
        Val::Int(vec![parts[1..].iter().fold(first, |acc, r| self.emit.int_binary(join, acc, *r))])
    }

    /// Componentwise `op`, a scalar operand applying to every component.
    pub(crate) fn zip(&mut self, op: Binary, a: &[Reg], b: &[Reg]) -> Vec<Reg> {
        let n = a.len().max(b.len());
        (0..n).map(|i| self.emit.binary(op, pick(a, i), pick(b, i))).collect()
    }

    /// Matrix products: matrix by matrix, matrix by column vector, row vector by matrix. A
    /// three-component vector with a 4x4 matrix is a point (w = 1, divided by the result's w).
    fn mat_mul(&mut self, a: &[Reg], ta: Type, b: &[Reg], tb: Type) -> Val {
        let n = if ta.base == Base::Matrix3 || tb.base == Base::Matrix3 { 3 } else { 4 };
        let vector = |v: &[Reg], this: &mut Self| -> (Vec<Reg>, bool) {
            if v.len() == n - 1 {
                (v.iter().copied().chain([this.emit.float(1.0)]).collect(), true)
            } else {
                (v.to_vec(), false)
            }
        };
        let entry = |this: &mut Self, row: &dyn Fn(usize) -> Reg, col: &dyn Fn(usize) -> Reg| {
            let pairs: Vec<(Reg, Reg)> = (0..n).map(|k| (row(k), col(k))).collect();
            let (x, y): (Vec<Reg>, Vec<Reg>) = pairs.into_iter().unzip();
            arith::dot(&mut this.emit, &x, &y)
        };
        match (is_matrix(ta), is_matrix(tb)) {
            (true, true) => {
                let mut out = Vec::with_capacity(n * n);
                for i in 0..n {
                    for j in 0..n {
                        out.push(entry(self, &|k| a[i * n + k], &|k| b[k * n + j]));
                    }
                }
                Val::Float(out)
            }
            (true, false) => {
                let (v, point) = vector(b, self);
                let out: Vec<Reg> = (0..n).map(|i| entry(self, &|k| a[i * n + k], &|k| v[k])).collect();
                Val::Float(self.dehomogenize(out, point))
            }
            _ => {
                let (v, point) = vector(a, self);
                let out: Vec<Reg> = (0..n).map(|j| entry(self, &|k| v[k], &|k| b[k * n + j])).collect();
                Val::Float(self.dehomogenize(out, point))
            }
        }
    }

    /// Divides by the last component and drops it, for points given without one.
    pub(crate) fn dehomogenize(&mut self, v: Vec<Reg>, point: bool) -> Vec<Reg> {
        if !point {
            return v;
        }
        let w = v[v.len() - 1];
        v[..v.len() - 1].iter().map(|x| self.emit.binary(Binary::Div, *x, w)).collect()
    }

    /// `cond ? a : b`, componentwise.
    pub(crate) fn select(&mut self, cond: Reg, a: &Val, b: &Val) -> Val {
        match (a, b) {
            (Val::Float(x), Val::Float(y)) => {
                Val::Float(x.iter().zip(y).map(|(x, y)| self.emit.select(true, cond, *x, *y)).collect())
            }
            (Val::Int(x), Val::Int(y)) => {
                Val::Int(x.iter().zip(y).map(|(x, y)| self.emit.select(false, cond, *x, *y)).collect())
            }
            (a, _) => a.clone(),
        }
    }

    /// Converts a value of type `from` to type `to` (the implicit and explicit conversions).
    pub(crate) fn convert(&mut self, v: &Val, from: Type, to: Type) -> Val {
        let elements = to.array.unwrap_or(1).max(1) as usize;
        let from_n = super::layout(Type::of(from.base)).map_or(1, |l| l.1) as usize;
        let parts: Vec<Reg> = match v {
            Val::Float(r) | Val::Int(r) => r.clone(),
            other => return other.clone(),
        };
        let mut floats = Vec::new();
        let mut ints = Vec::new();
        for e in 0..elements {
            let element = &parts[(e * from_n).min(parts.len())..((e + 1) * from_n).min(parts.len())];
            let converted = self.convert_element(element, from.base, to.base);
            match converted {
                Val::Float(r) => floats.extend(r),
                Val::Int(r) => ints.extend(r),
                _ => {}
            }
        }
        if super::layout(to).is_some_and(|(float, _)| float) { Val::Float(floats) } else { Val::Int(ints) }
    }

    fn convert_element(&mut self, v: &[Reg], from: Base, to: Base) -> Val {
        let to_float = !matches!(to, Base::Bool | Base::Int | Base::Uint);
        let scalar: Option<Reg> = (v.len() == 1).then(|| v[0]);
        if to_float {
            let float_parts: Vec<Reg> = match from {
                Base::Int => vec![self.emit.convert(Convert::IntToFloat, v[0])],
                Base::Uint | Base::Bool => vec![self.emit.convert(Convert::UintToFloat, v[0])],
                _ => v.to_vec(),
            };
            let n = to.components() as usize;
            let out = match (float_parts.len(), to) {
                (1, Base::Matrix3 | Base::Matrix4) => {
                    let side = if to == Base::Matrix3 { 3 } else { 4 };
                    let zero = self.emit.float(0.0);
                    (0..n).map(|i| if i % (side + 1) == 0 { float_parts[0] } else { zero }).collect()
                }
                (1, _) if n > 1 => vec![float_parts[0]; n],
                (1, Base::Clampf) => {
                    let (zero, one) = (self.emit.float(0.0), self.emit.float(1.0));
                    vec![self.emit.ternary(
                        crate::backend::cpu::code::Ternary::Clamp,
                        float_parts[0],
                        zero,
                        one,
                    )]
                }
                _ => float_parts,
            };
            return Val::Float(out);
        }
        let Some(x) = scalar else { return Val::Int(v.to_vec()) };
        let r = match (from, to) {
            (Base::Int | Base::Uint | Base::Bool, Base::Int | Base::Uint) => x,
            (Base::Int | Base::Uint, Base::Bool) => {
                let zero = self.emit.int(0);
                self.emit.int_compare(Compare::Ne, false, x, zero)
            }
            (Base::Bool, Base::Bool) => x,
            (_, Base::Int) => self.emit.convert(Convert::FloatToInt, x),
            (_, Base::Uint) => self.emit.convert(Convert::FloatToUint, x),
            _ => self.emit.convert(Convert::FloatToBool, x),
        };
        Val::Int(vec![r])
    }

    fn construct(&mut self, parts: &[Val], ty: Type) -> Val {
        if ty.array.is_none() && matches!(ty.base, Base::Matrix4 | Base::Matrix3) && parts.len() == 1 {
            return self.convert(&parts[0], Type::FLOAT, ty);
        }
        let float = super::layout(ty).is_none_or(|(f, _)| f);
        let regs: Vec<Reg> = parts
            .iter()
            .flat_map(|p| match p {
                Val::Float(r) | Val::Int(r) => r.clone(),
                _ => Vec::new(),
            })
            .collect();
        if float { Val::Float(regs) } else { Val::Int(regs) }
    }
}

/// Component `i`, or the only one of a scalar.
pub(super) fn pick(r: &[Reg], i: usize) -> Reg {
    if r.len() == 1 { r[0] } else { r[i] }
}

fn is_matrix(t: Type) -> bool {
    t.array.is_none() && matches!(t.base, Base::Matrix3 | Base::Matrix4)
}
