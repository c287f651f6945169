//! Building expressions after the semantic stage: transformations (`opt::derivs`) append new
//! expressions to a shader's arena with the type, rate and span the semantic stage would have given
//! them.
//!
//! The builder keeps the IR's conventions: operands of arithmetic have one type (a scalar meeting a
//! vector is converted explicitly, as the semantic stage's `Convert` nodes do), built-in calls use
//! the overload whose parameters match exactly, and each rate is the join of the operands' rates
//! refined by the built-in's `RateRule` (`Shader::rate_of`).

use smol_str::SmolStr;

use crate::ir::builtin::BuiltinId;
use crate::ir::types::{Base, Rate, Type};
use crate::ir::{BinaryOp, Expr, ExprId, ExprKind, Literal, LocalId, Shader, UnaryOp};
use crate::sema::builtins;
use crate::source::Span;

/// Appends expressions to a shader, each with the span currently set.
pub struct Builder<'s> {
    /// The shader being extended.
    pub shader: &'s mut Shader,
    /// The span given to new expressions.
    pub span: Span,
}

impl<'s> Builder<'s> {
    /// A builder giving new expressions the span `span`.
    pub fn new(shader: &'s mut Shader, span: Span) -> Builder<'s> {
        Builder { shader, span }
    }

    /// The type of `e`.
    pub fn ty(&self, e: ExprId) -> Type {
        self.shader.expr(e).ty
    }

    /// The rate of `e`.
    pub fn rate(&self, e: ExprId) -> Rate {
        self.shader.expr(e).rate
    }

    /// Appends an expression of type `ty`; its rate follows from `kind`.
    pub fn push(&mut self, kind: ExprKind, ty: Type) -> ExprId {
        let rate = self.rate_of(&kind);
        let id = ExprId(self.shader.exprs.len() as u32);
        self.shader.exprs.push(Expr { kind, ty, rate, span: self.span });
        id
    }

    /// The rate an expression of this kind has, by the rules of `sema::rates`.
    pub fn rate_of(&self, kind: &ExprKind) -> Rate {
        self.shader.rate_of(kind)
    }

    /// A float literal.
    pub fn float(&mut self, v: f64) -> ExprId {
        self.push(ExprKind::Literal(Literal::Float(v)), Type::FLOAT)
    }

    /// An `int` literal.
    pub fn int(&mut self, v: i32) -> ExprId {
        self.push(ExprKind::Literal(Literal::Int(v)), Type::INT)
    }

    /// The value `v` as a `ty`: a literal for scalars, the scalar converted for vectors (every
    /// component `v`) and matrices (`v` times the identity), and an array of such for arrays.
    pub fn splat(&mut self, v: f64, ty: Type) -> ExprId {
        if let Some(n) = ty.array {
            assert!(n > 0, "no value of the unsized array type `{ty}`");
            let element = self.splat(v, Type::of(ty.base));
            return self.push(ExprKind::Construct(vec![element; n as usize]), ty);
        }
        match ty.base {
            Base::Float | Base::Clampf => self.push(ExprKind::Literal(Literal::Float(v)), ty),
            Base::Int => self.int(v as i32),
            _ => {
                let scalar = self.float(v);
                self.push(ExprKind::Convert(scalar), ty)
            }
        }
    }

    /// Zero of type `ty` (see [`Builder::splat`]).
    pub fn zero(&mut self, ty: Type) -> ExprId {
        self.splat(0.0, ty)
    }

    /// The value of local `l`.
    pub fn local(&mut self, l: LocalId) -> ExprId {
        let ty = self.shader.local(l).ty;
        self.push(ExprKind::Local(l), ty)
    }

    /// `e` converted to `ty` (`e` itself when it has that type).
    pub fn convert(&mut self, e: ExprId, ty: Type) -> ExprId {
        if self.ty(e) == ty { e } else { self.push(ExprKind::Convert(e), ty) }
    }

    /// `-e`.
    pub fn neg(&mut self, e: ExprId) -> ExprId {
        let ty = self.ty(e);
        self.push(ExprKind::Unary(UnaryOp::Neg, e), ty)
    }

    /// `a op b`, converting the operands to one type first where they differ: a scalar to the
    /// other operand's type, `clampf` and integers to `float`, and a point to the other triple's
    /// type (`vector - point` is a vector). Matrix products keep their operands.
    pub fn binary(&mut self, op: BinaryOp, a: ExprId, b: ExprId) -> ExprId {
        use BinaryOp as B;
        let (ta, tb) = (self.ty(a), self.ty(b));
        match op {
            B::Eq | B::Ne | B::Lt | B::Le | B::Gt | B::Ge => {
                let (a, b) = self.unify(a, b);
                self.push(ExprKind::Binary(op, a, b), Type::BOOL)
            }
            B::And | B::Or => self.push(ExprKind::Binary(op, a, b), Type::BOOL),
            B::Dot => {
                let (a, b) = self.unify(a, b);
                self.push(ExprKind::Binary(op, a, b), Type::FLOAT)
            }
            B::Cross => {
                let both_float3 = ta.base == Base::Float3 && tb.base == Base::Float3;
                let ty = Type::of(if both_float3 { Base::Float3 } else { Base::Vector });
                let (a, b) = (self.convert(a, ty), self.convert(b, ty));
                self.push(ExprKind::Binary(op, a, b), ty)
            }
            B::Mul if matrix_product(ta, tb).is_some() => {
                let ty = matrix_product(ta, tb).expect("checked");
                self.push(ExprKind::Binary(op, a, b), ty)
            }
            _ => {
                let (a, b) = self.unify(a, b);
                let ty = self.ty(a);
                let ty = if op == B::Sub && ty.base == Base::Point { Type::of(Base::Vector) } else { ty };
                self.push(ExprKind::Binary(op, a, b), ty)
            }
        }
    }

    /// Both operands converted to one type (see [`Builder::binary`]).
    fn unify(&mut self, a: ExprId, b: ExprId) -> (ExprId, ExprId) {
        let (ta, tb) = (self.ty(a), self.ty(b));
        if ta == tb {
            return (a, b);
        }
        let scalar = |t: Type| t.array.is_none() && t.base.components() == 1;
        let ty = match (scalar(ta), scalar(tb)) {
            (true, true) => Type::FLOAT,
            (true, false) => tb,
            (false, true) => ta,
            (false, false) if ta.base == Base::Point => tb,
            (false, false) => ta,
        };
        (self.convert(a, ty), self.convert(b, ty))
    }

    /// `cond ? a : b`, with `b` converted to `a`'s type.
    pub fn select(&mut self, cond: ExprId, a: ExprId, b: ExprId) -> ExprId {
        let ty = self.ty(a);
        let b = self.convert(b, ty);
        self.push(ExprKind::Select(cond, a, b), ty)
    }

    /// Element `i` of an array, vector or matrix (a matrix's row).
    pub fn index(&mut self, base: ExprId, i: u32) -> ExprId {
        let i = self.int(i as i32);
        self.index_by(base, i)
    }

    /// Element `index` of an array, vector or matrix.
    pub fn index_by(&mut self, base: ExprId, index: ExprId) -> ExprId {
        let ty = self.ty(base).element();
        self.push(ExprKind::Index(base, index), ty)
    }

    /// A value of type `ty` built from `parts`.
    pub fn construct(&mut self, parts: Vec<ExprId>, ty: Type) -> ExprId {
        self.push(ExprKind::Construct(parts), ty)
    }

    /// `value`, given in `space`, converted to "current"; of `value`'s type.
    pub fn from_space(&mut self, space: SmolStr, value: ExprId) -> ExprId {
        let ty = self.ty(value);
        self.push(ExprKind::FromSpace { space, value }, ty)
    }

    /// A call of the built-in `id` whose parameters are exactly the argument types.
    ///
    /// # Panics
    /// When there is no such overload: the caller built arguments of the wrong types.
    pub fn call(&mut self, id: BuiltinId, args: Vec<ExprId>) -> ExprId {
        let types: Vec<Type> = args.iter().map(|&a| self.ty(a)).collect();
        let Some(b) = builtins::find(id, &types) else {
            let list: Vec<String> = types.iter().map(Type::to_string).collect();
            panic!("no built-in `{id}({})`", list.join(", "));
        };
        self.push(ExprKind::Builtin(b, args), b.ret)
    }
}

/// The type of a matrix product `a * b`, or `None` when it is not one.
fn matrix_product(a: Type, b: Type) -> Option<Type> {
    if a.is_array() || b.is_array() {
        return None;
    }
    match (a.base, b.base) {
        (Base::Matrix4, Base::Float4) => Some(b),
        (Base::Matrix3, x) if x.is_triple() => Some(b),
        (Base::Matrix4, Base::Matrix4) | (Base::Matrix3, Base::Matrix3) => Some(a),
        _ => None,
    }
}
