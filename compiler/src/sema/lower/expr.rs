//! Lowering expressions: names, operators, assignments, constructors, casts and indexing.

use super::{LightLoop, Lowerer};
use crate::diag::{Code, Diagnostic};
use crate::ir::global::{Access, Global, Scope};
use crate::ir::types::{Base, Rate, Type};
use crate::ir::{BinaryOp, Block, ExprId, ExprKind, Literal, LocalKind, Place, UnaryOp};
use crate::sema::convert;
use crate::sema::globals;
use crate::syntax::ast;

/// The coordinate systems point-like values can be given in.
pub const SPACES: &[&str] =
    &["current", "object", "shader", "world", "camera", "screen", "raster", "NDC", "eye"];
/// The colour spaces colours can be given in.
pub const COLOR_SPACES: &[&str] = crate::stdlib::COLOUR_SPACES;

/// Edit distance counting a swap of neighbours as one edit (optimal string alignment), for "did
/// you mean" suggestions.
fn distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            d[i][j] = (d[i - 1][j] + 1).min(d[i][j - 1] + 1).min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d[i][j] = d[i][j].min(d[i - 2][j - 2] + 1);
            }
        }
    }
    d[a.len()][b.len()]
}

/// The closest of `candidates` to `name`, if it is close enough to be a likely typo.
pub(super) fn suggest<'c>(name: &str, candidates: impl Iterator<Item = &'c str>) -> Option<&'c str> {
    candidates
        .filter(|c| *c != name)
        .map(|c| (distance(name, c), c))
        .filter(|(d, c)| *d <= (name.len().max(c.len()) / 3).max(1))
        .min()
        .map(|(_, c)| c)
}

impl Lowerer<'_> {
    /// Lowers an expression; `expected` is the type the context wants (for tuples and for the
    /// return-type choice of overloads). Effects are appended to `out`.
    pub(super) fn expr(&mut self, e: &ast::Expr, expected: Option<Type>, out: &mut Block) -> Option<ExprId> {
        // Expressions nest as deep as the source's operator chains (up to the front end's limits);
        // grow the stack instead of overflowing it, whatever thread the compiler runs on.
        stacker::maybe_grow(64 * 1024, 1024 * 1024, || self.expr_here(e, expected, out))
    }

    fn expr_here(&mut self, e: &ast::Expr, expected: Option<Type>, out: &mut Block) -> Option<ExprId> {
        use ast::ExprKind as E;
        let span = e.span;
        match &e.kind {
            E::Int { value, unsigned } => {
                let lit = if *unsigned || *value > i32::MAX as u32 {
                    (Literal::Uint(*value), Base::Uint)
                } else {
                    (Literal::Int(*value as i32), Base::Int)
                };
                Some(self.push_expr(ExprKind::Literal(lit.0), Type::of(lit.1), span))
            }
            E::Float(v) => Some(self.push_expr(ExprKind::Literal(Literal::Float(*v)), Type::FLOAT, span)),
            E::String(s) => {
                Some(self.push_expr(ExprKind::Literal(Literal::String(s.into())), Type::STRING, span))
            }
            E::Bool(b) => Some(self.push_expr(ExprKind::Literal(Literal::Bool(*b)), Type::BOOL, span)),
            E::Name(name) => self.name(name),
            E::Unary { op, operand } => {
                let value = self.expr(operand, expected, out)?;
                self.unary(*op, value, span)
            }
            E::Binary { op: ast::BinaryOp::Sub, lhs, rhs } if self.negated_cast(lhs).is_some() => {
                // RenderMan's `point -1e10`: a cast of a negated operand, which the grammar reads
                // as a subtraction from the type word (in Stanford code the word may be a name).
                let ty = self.negated_cast(lhs)?;
                let negated = ast::ExprKind::Unary { op: ast::UnaryOp::Neg, operand: rhs.clone() };
                let operand =
                    ast::Expr { kind: negated, span: crate::source::Span { start: lhs.span.end, ..span } };
                let cast = ast::Expr { kind: E::Cast { ty, space: None, operand: Box::new(operand) }, span };
                self.expr(&cast, expected, out)
            }
            E::Binary { op, lhs, rhs } => {
                let logical = matches!(op, ast::BinaryOp::And | ast::BinaryOp::Or);
                // Arithmetic passes the wanted type on, so `point p = r * (x, y, z)` types the tuple.
                let arithmetic = matches!(
                    op,
                    ast::BinaryOp::Add | ast::BinaryOp::Sub | ast::BinaryOp::Mul | ast::BinaryOp::Div
                );
                let hint = expected.filter(|t| arithmetic && t.array.is_none() && t.base.components() > 1);
                self.no_effects += u32::from(logical);
                let a = self.expr(lhs, hint, out);
                let b = self.expr(rhs, hint, out);
                self.no_effects -= u32::from(logical);
                self.binary(*op, a?, b?, span)
            }
            E::Assign { op, target, value } => self.assign(*op, target, value, span, out),
            E::Step { op, prefix, target } => {
                let one = ast::Expr { kind: ast::ExprKind::Int { value: 1, unsigned: false }, span };
                let binop = match op {
                    ast::StepOp::Increment => ast::BinaryOp::Add,
                    ast::StepOp::Decrement => ast::BinaryOp::Sub,
                };
                if *prefix {
                    return self.assign(Some(binop), target, &one, span, out);
                }
                let old = self.expr(target, None, out)?;
                let ty = self.ty(old);
                let temp =
                    self.new_local("old value".into(), ty, Rate::CONSTANT, false, LocalKind::Temp, span);
                self.store(Place::Local(temp), old, span, out);
                self.assign(Some(binop), target, &one, span, out)?;
                Some(self.push_expr(ExprKind::Local(temp), ty, span))
            }
            E::Conditional { cond, then, otherwise } => {
                self.no_effects += 1;
                let c = self.expr(cond, Some(Type::BOOL), out).and_then(|c| self.condition(c));
                let a = self.expr(then, expected, out);
                let b = self.expr(otherwise, expected, out);
                self.no_effects -= 1;
                let (c, a, b) = (c?, a?, b?);
                let (ta, tb) = (self.ty(a), self.ty(b));
                let Some(ty) = convert::common_type(ta, tb) else {
                    self.error(
                        Diagnostic::error(
                            Code::TypeMismatch,
                            format!("the two results of `?:` have different types, `{ta}` and `{tb}`"),
                            self.span_of(b),
                            format!("this is `{tb}`"),
                        )
                        .with_label(self.span_of(a), format!("this is `{ta}`")),
                    );
                    return None;
                };
                let (a, b) = self.coerce_both(a, b, ty, "the result")?;
                Some(self.push_expr(ExprKind::Select(c, a, b), ty, span))
            }
            E::Call { callee, args } => self.call(callee, args, expected, span, out),
            E::Cast { ty, space, operand } => self.cast(*ty, space.as_ref(), operand, span, out),
            E::Tuple(items) => match expected {
                Some(t) if t.array.is_none() && (t.base.is_triple() || t.base == Base::Matrix4) => {
                    self.construct(t, items, span, out)
                }
                _ => {
                    self.error(
                        Diagnostic::error(
                            Code::UntypedTuple,
                            format!("the type of this {}-tuple is not known here", items.len()),
                            span,
                            "a tuple needs a type from its context",
                        )
                        .with_help("name the type: `point (x, y, z)`, `color (r, g, b)`, `matrix (...)`"),
                    );
                    None
                }
            },
            E::Braced(items) => self.braced(items, expected, span, out),
            E::Index { base, index } => {
                let b = self.expr(base, None, out);
                let i = self.expr(index, None, out);
                self.index(b?, i?, span)
            }
            E::Error => None,
        }
    }

    /// A name in an expression: a local, a module variable, or a predefined variable.
    /// The type `lhs` names when it is a RenderMan type word used as a value in RenderMan code
    /// and nothing of that name is declared: the left side of `point -1e10`.
    fn negated_cast(&self, lhs: &ast::Expr) -> Option<ast::TypeSpec> {
        let ast::ExprKind::Name(ident) = &lhs.kind else { return None };
        let name = match ident.name.as_str() {
            "color" => ast::TypeName::Color,
            "point" => ast::TypeName::Point,
            "vector" => ast::TypeName::Vector,
            "normal" => ast::TypeName::Normal,
            "matrix" => ast::TypeName::Matrix,
            _ => return None,
        };
        let declared = self.lookup_local(&ident.name).is_some()
            || crate::sema::globals::lookup(&ident.name, self.kind, self.stanford).is_some();
        (!self.stanford && !declared).then_some(ast::TypeSpec { name, span: ident.span })
    }

    fn name(&mut self, name: &ast::Ident) -> Option<ExprId> {
        if let Some(id) = self.lookup_local(&name.name) {
            let ty = self.locals[id.0 as usize].ty;
            if let Some(&arg) = self.string_aliases.get(&id) {
                let kind = self.expr_ref(arg).kind.clone();
                return Some(self.push_expr(kind, ty, name.span));
            }
            return Some(self.push_expr(ExprKind::Local(id), ty, name.span));
        }
        let global = self.global(name)?;
        Some(self.push_expr(ExprKind::Global(global), Type::of(global.ty), name.span))
    }

    /// The predefined variable `name`, checking that it exists here.
    fn global(&mut self, name: &ast::Ident) -> Option<&'static Global> {
        let Some(g) = globals::lookup(&name.name, self.kind, self.stanford) else {
            let other_kind = globals::GLOBALS.iter().find(|g| g.name == name.name);
            let mut d = match other_kind {
                Some(g) => Diagnostic::error(
                    Code::WrongShaderKind,
                    format!(
                        "`{}` is not available in {} {} shader",
                        name.name,
                        article(self.kind),
                        self.kind.keyword()
                    ),
                    name.span,
                    format!("`{}` ({}) exists in other shaders", name.name, g.doc),
                ),
                None => Diagnostic::error(
                    Code::UnknownName,
                    format!("cannot find `{}` in this scope", name.name),
                    name.span,
                    "not declared",
                ),
            };
            if other_kind.is_none() {
                let locals = self.scopes.iter().flat_map(|s| s.keys()).map(|k| k.as_str());
                let predefined = globals::GLOBALS
                    .iter()
                    .filter(|g| globals::lookup(g.name, self.kind, self.stanford).is_some())
                    .map(|g| g.name);
                if let Some(close) =
                    suggest(&name.name, locals.chain(predefined).collect::<Vec<_>>().into_iter())
                {
                    d = d.with_help(format!("a name with a similar spelling exists: `{close}`"));
                }
            }
            self.error(d);
            return None;
        };
        let inside = match g.scope {
            Scope::Anywhere => true,
            Scope::PerLight => self.stanford || self.light_loop == LightLoop::Illuminance,
        };
        if !inside {
            let construct = "illuminance";
            self.error(
                Diagnostic::error(
                    Code::OutsideLightLoop,
                    format!("`{}` exists only inside `{construct}`", g.name),
                    name.span,
                    format!("{} differs for each light", g.doc),
                )
                .with_help(format!("move this into an `{construct}` block")),
            );
            return None;
        }
        Some(g)
    }

    fn unary(&mut self, op: ast::UnaryOp, value: ExprId, span: crate::source::Span) -> Option<ExprId> {
        let ty = self.ty(value);
        let (ir_op, ok) = match op {
            ast::UnaryOp::Plus => return Some(value),
            ast::UnaryOp::Neg => (UnaryOp::Neg, ty.array.is_none() && ty.base.is_numeric()),
            ast::UnaryOp::Not => {
                let value = self.condition(value)?;
                return Some(self.push_expr(ExprKind::Unary(UnaryOp::Not, value), Type::BOOL, span));
            }
            ast::UnaryOp::BitNot => (UnaryOp::BitNot, ty.array.is_none() && ty.base.is_integer()),
        };
        if !ok {
            let symbol = if ir_op == UnaryOp::Neg { "-" } else { "~" };
            self.error(Diagnostic::error(
                Code::InvalidOperands,
                format!("`{symbol}` does not apply to `{ty}`"),
                self.span_of(value),
                format!("this is `{ty}`"),
            ));
            return None;
        }
        Some(self.push_expr(ExprKind::Unary(ir_op, value), ty, span))
    }

    fn invalid_operands(
        &mut self,
        op: ast::BinaryOp,
        a: ExprId,
        b: ExprId,
        help: Option<&str>,
    ) -> Option<ExprId> {
        let (ta, tb) = (self.ty(a), self.ty(b));
        let mut d = Diagnostic::error(
            Code::InvalidOperands,
            format!("`{}` does not apply to `{ta}` and `{tb}`", op.symbol()),
            self.span_of(b),
            format!("this is `{tb}`"),
        )
        .with_label(self.span_of(a), format!("this is `{ta}`"));
        if let Some(help) = help {
            d = d.with_help(help);
        }
        self.error(d);
        None
    }

    pub(super) fn binary(
        &mut self,
        op: ast::BinaryOp,
        a: ExprId,
        b: ExprId,
        span: crate::source::Span,
    ) -> Option<ExprId> {
        use ast::BinaryOp as B;
        let (ta, tb) = (self.ty(a), self.ty(b));
        if ta.is_array() || tb.is_array() {
            return self.invalid_operands(op, a, b, Some("arrays have no operators; work on their elements"));
        }
        let (xa, xb) = (ta.base, tb.base);
        match op {
            B::And | B::Or => {
                let a = self.condition(a)?;
                let b = self.condition(b)?;
                let op = if op == B::And { BinaryOp::And } else { BinaryOp::Or };
                Some(self.push_expr(ExprKind::Binary(op, a, b), Type::BOOL, span))
            }
            B::Eq | B::Ne => {
                let Some(common) = convert::common_type(ta, tb).filter(|t| t.base != Base::Texref) else {
                    return self.invalid_operands(op, a, b, None);
                };
                let (a, b) = self.coerce_both(a, b, common, "the comparison")?;
                let op = if op == B::Eq { BinaryOp::Eq } else { BinaryOp::Ne };
                Some(self.push_expr(ExprKind::Binary(op, a, b), Type::BOOL, span))
            }
            B::Lt | B::Le | B::Gt | B::Ge => {
                let scalar = |t: Base| matches!(t, Base::Float | Base::Clampf | Base::Int | Base::Uint);
                let common = convert::common_type(ta, tb).filter(|t| scalar(t.base));
                let Some(common) = common else {
                    return self.invalid_operands(
                        op,
                        a,
                        b,
                        Some("ordering compares numbers; compare lengths or components"),
                    );
                };
                let (a, b) = self.coerce_both(a, b, common, "the comparison")?;
                let op = match op {
                    B::Lt => BinaryOp::Lt,
                    B::Le => BinaryOp::Le,
                    B::Gt => BinaryOp::Gt,
                    _ => BinaryOp::Ge,
                };
                Some(self.push_expr(ExprKind::Binary(op, a, b), Type::BOOL, span))
            }
            B::BitAnd | B::BitOr | B::Shl | B::Shr | B::Rem => {
                if !(xa.is_integer() && xa == xb) {
                    let help = match op {
                        B::Rem => Some("for floats use `mod(a, b)`"),
                        _ if xa.is_integer() && xb.is_integer() => {
                            Some("convert one side: `int (x)` or `uint (x)`")
                        }
                        _ => Some("bit operations take `int` or `uint`"),
                    };
                    return self.invalid_operands(op, a, b, help);
                }
                let op = match op {
                    B::BitAnd => BinaryOp::BitAnd,
                    B::BitOr => BinaryOp::BitOr,
                    B::Shl => BinaryOp::Shl,
                    B::Shr => BinaryOp::Shr,
                    _ => BinaryOp::Rem,
                };
                Some(self.push_expr(ExprKind::Binary(op, a, b), ta, span))
            }
            B::Caret if xa.is_integer() || xb.is_integer() => {
                if xa != xb {
                    return self.invalid_operands(
                        op,
                        a,
                        b,
                        Some("`^` is exclusive or on two integers of one type"),
                    );
                }
                Some(self.push_expr(ExprKind::Binary(BinaryOp::BitXor, a, b), ta, span))
            }
            B::Caret => {
                let vectorish = |t: Base| t.is_geometric() || t == Base::Float3;
                if !(vectorish(xa) && vectorish(xb)) {
                    return self.invalid_operands(op, a, b, Some("`^` is the cross product of two vectors"));
                }
                let ty = if xa == Base::Float3 && xb == Base::Float3 {
                    Type::of(Base::Float3)
                } else {
                    Type::of(Base::Vector)
                };
                let (a, b) = self.coerce_both(a, b, ty, "the operand")?;
                Some(self.push_expr(ExprKind::Binary(BinaryOp::Cross, a, b), ty, span))
            }
            B::Dot => {
                let dottable = |t: Base| t.is_triple() || t == Base::Float4;
                let common =
                    convert::common_type(ta, tb).filter(|t| dottable(t.base) && dottable(xa) && dottable(xb));
                let Some(common) = common else {
                    return self.invalid_operands(
                        op,
                        a,
                        b,
                        Some("`.` is the dot product of two vectors or colours"),
                    );
                };
                let (a, b) = self.coerce_both(a, b, common, "the operand")?;
                Some(self.push_expr(ExprKind::Binary(BinaryOp::Dot, a, b), Type::FLOAT, span))
            }
            B::Add | B::Sub | B::Mul | B::Div => self.arithmetic(op, a, b, span),
        }
    }

    fn arithmetic(
        &mut self,
        op: ast::BinaryOp,
        a: ExprId,
        b: ExprId,
        span: crate::source::Span,
    ) -> Option<ExprId> {
        use ast::BinaryOp as B;
        let (ta, tb) = (self.ty(a), self.ty(b));
        let (xa, xb) = (ta.base, tb.base);
        let ir_op = match op {
            B::Add => BinaryOp::Add,
            B::Sub => BinaryOp::Sub,
            B::Mul => BinaryOp::Mul,
            _ => BinaryOp::Div,
        };
        if !xa.is_numeric() || !xb.is_numeric() {
            return self.invalid_operands(op, a, b, None);
        }
        // Matrix products: matrix * matrix, and Stanford's matrix * column vector.
        if op == B::Mul {
            let product = match (xa, xb) {
                (Base::Matrix4, Base::Float4) => Some(Base::Float4),
                (Base::Matrix3, b) if b.is_triple() => Some(b),
                (Base::Matrix4, Base::Matrix4) | (Base::Matrix3, Base::Matrix3) => Some(xa),
                _ => None,
            };
            if let Some(result) = product {
                return Some(self.push_expr(ExprKind::Binary(BinaryOp::Mul, a, b), Type::of(result), span));
            }
        }
        if xa.is_integer() && xb.is_integer() && xa != xb {
            return self.invalid_operands(op, a, b, Some("`int` and `uint` do not mix; convert one side"));
        }
        let Some(common) = convert::common_type(ta, tb) else {
            let help = if (xa == Base::Color && xb.is_geometric()) || (xb == Base::Color && xa.is_geometric())
            {
                Some("colours and points do not mix; convert explicitly with `color (p)` or `point (c)`")
            } else if xa == Base::Float4 || xb == Base::Float4 {
                Some(
                    "`float4` mixes only with `float4` and scalars; `rgb(x)` gives the first three components",
                )
            } else {
                None
            };
            return self.invalid_operands(op, a, b, help);
        };
        let (a, b) = self.coerce_both(a, b, common, "the operand")?;
        // RenderMan: point - point is a vector.
        let result = if op == B::Sub && xa == Base::Point && xb == Base::Point {
            Type::of(Base::Vector)
        } else {
            common
        };
        Some(self.push_expr(ExprKind::Binary(ir_op, a, b), result, span))
    }

    /// Both operands converted to `to`.
    fn coerce_both(&mut self, a: ExprId, b: ExprId, to: Type, what: &str) -> Option<(ExprId, ExprId)> {
        let a = self.coerce(a, to, what);
        let b = self.coerce(b, to, what);
        Some((a?, b?))
    }

    /// The place an lvalue expression denotes, or `None` (reported) if it is not assignable.
    pub(super) fn place_of(&mut self, id: ExprId) -> Option<Place> {
        let span = self.span_of(id);
        match self.expr_ref(id).kind.clone() {
            ExprKind::Local(local) => Some(Place::Local(local)),
            ExprKind::Global(g) if g.access == Access::ReadWrite => Some(Place::Global(g)),
            ExprKind::Global(g) => {
                self.error(Diagnostic::error(
                    Code::NotAssignable,
                    format!(
                        "`{}` is read-only in {} {} shader",
                        g.name,
                        article(self.kind),
                        self.kind.keyword()
                    ),
                    span,
                    "cannot be assigned",
                ));
                None
            }
            ExprKind::Index(base, index) => Some(Place::Index(Box::new(self.place_of(base)?), index)),
            _ => {
                self.error(
                    Diagnostic::error(
                        Code::NotAssignable,
                        "cannot assign to this expression",
                        span,
                        "not a variable",
                    )
                    .with_help("assign to a variable, an array element or a component"),
                );
                None
            }
        }
    }

    fn assign(
        &mut self,
        op: Option<ast::BinaryOp>,
        target: &ast::Expr,
        value: &ast::Expr,
        span: crate::source::Span,
        out: &mut Block,
    ) -> Option<ExprId> {
        if self.no_effects > 0 {
            self.error(
                Diagnostic::error(
                    Code::EffectInCondition,
                    "assignment inside `?:`, `&&` or `||`",
                    span,
                    "only one side of the operator is evaluated in C, but every side here",
                )
                .with_help("assign in a statement before the expression"),
            );
            return None;
        }
        let t = self.expr(target, None, out)?;
        let place = self.place_of(t)?;
        if let Some(first) = self.frames.iter().find_map(|f| f.guarded_from) {
            let own = match place.root_local() {
                Some(l) => l.0 as usize >= first,
                None => false,
            };
            if !own {
                self.error(
                    Diagnostic::error(
                        Code::EffectInCondition,
                        "assignment to a variable outside this function, in a call inside `?:`, `&&` or `||`",
                        span,
                        "every side of the operator is evaluated, so this would always run",
                    )
                    .with_help("call the function in a statement before the expression"),
                );
                return None;
            }
        }
        let ty = self.ty(t);
        let uniform = place.root_local().is_some_and(|l| {
            let local = &self.locals[l.0 as usize];
            local.declared && local.rate.frequency == crate::ir::types::Frequency::PrimitiveGroup
        });
        let outer = std::mem::replace(&mut self.uniform_random, uniform);
        let v = self.expr(value, Some(ty), out);
        self.uniform_random = outer;
        let v = v?;
        let v = match op {
            Some(op) => self.binary(op, t, v, span)?,
            None => v,
        };
        let v = self.coerce(v, ty, "the variable")?;
        self.store(place, v, span, out);
        Some(self.push_expr(self.expr_ref(t).kind.clone(), ty, span))
    }

    /// A Stanford braced constructor, or an array initialiser when an array is expected.
    fn braced(
        &mut self,
        items: &[ast::Expr],
        expected: Option<Type>,
        span: crate::source::Span,
        out: &mut Block,
    ) -> Option<ExprId> {
        if let Some(t) = expected.filter(|t| t.is_array()) {
            let elem = Type::of(t.base);
            let mut parts = Vec::with_capacity(items.len());
            for item in items {
                let v = self.expr(item, Some(elem), out)?;
                parts.push(self.coerce(v, elem, "an element")?);
            }
            if t.array != Some(0) && t.array != Some(items.len() as u32) {
                self.error(Diagnostic::error(
                    Code::InvalidConstructor,
                    format!("`{t}` needs {} elements, found {}", t.array.unwrap_or(0), items.len()),
                    span,
                    "wrong number of elements",
                ));
                return None;
            }
            let ty = Type { base: t.base, array: Some(items.len() as u32) };
            return Some(self.push_expr(ExprKind::Construct(parts), ty, span));
        }
        let mut parts = Vec::with_capacity(items.len());
        let mut count = 0;
        for item in items {
            let v = self.expr(item, None, out)?;
            let ty = self.ty(v);
            let n = if ty.array.is_none() && ty.base.is_numeric() && ty.base.components() <= 4 {
                ty.base.components()
            } else {
                0
            };
            if n == 0 {
                self.error(Diagnostic::error(
                    Code::InvalidConstructor,
                    format!("a `{ty}` cannot be a component of a vector"),
                    self.span_of(v),
                    "not a number or vector",
                ));
                return None;
            }
            let v = if ty.base.components() == 1 { self.coerce(v, Type::FLOAT, "a component")? } else { v };
            count += n;
            parts.push(v);
        }
        let base = match count {
            1 => Base::Float,
            3 => Base::Float3,
            4 => Base::Float4,
            _ => {
                self.error(
                    Diagnostic::error(
                        Code::InvalidConstructor,
                        format!("a vector constructor needs 1, 3 or 4 components, found {count}"),
                        span,
                        format!("{count} components"),
                    )
                    .with_help(
                        "`float3` has 3 components and `float4` has 4; there is no 2-component vector",
                    ),
                );
                return None;
            }
        };
        Some(self.push_expr(ExprKind::Construct(parts), Type::of(base), span))
    }

    /// `type (a, b, c)`: each component converted to float.
    fn construct(
        &mut self,
        ty: Type,
        items: &[ast::Expr],
        span: crate::source::Span,
        out: &mut Block,
    ) -> Option<ExprId> {
        let need = ty.base.components() as usize;
        if items.len() != need && !(ty.base == Base::Matrix4 && items.len() == 1) {
            self.error(Diagnostic::error(
                Code::InvalidConstructor,
                format!("`{ty}` has {need} components, found {}", items.len()),
                span,
                "wrong number of components",
            ));
            return None;
        }
        let mut parts = Vec::with_capacity(items.len());
        for item in items {
            let v = self.expr(item, Some(Type::FLOAT), out)?;
            parts.push(self.coerce(v, Type::FLOAT, "a component")?);
        }
        Some(self.push_expr(ExprKind::Construct(parts), ty, span))
    }

    fn cast(
        &mut self,
        ty: ast::TypeSpec,
        space: Option<&(String, crate::source::Span)>,
        operand: &ast::Expr,
        span: crate::source::Span,
        out: &mut Block,
    ) -> Option<ExprId> {
        let to = Type::of(Base::from_ast(ty.name));
        let value = match &operand.kind {
            ast::ExprKind::Tuple(items) if to.base.is_triple() || to.base == Base::Matrix4 => {
                self.construct(to, items, span, out)?
            }
            _ => self.expr(operand, Some(to), out)?,
        };
        let from = self.ty(value);
        let value = if from == to {
            value
        } else if convert::explicit_ok(from, to) {
            self.push_expr(ExprKind::Convert(value), to, span)
        } else {
            self.error(Diagnostic::error(
                Code::InvalidCast,
                format!("cannot convert `{from}` to `{to}`"),
                span,
                format!("`{from}` has no conversion to `{to}`"),
            ));
            return None;
        };
        let Some((name, space_span)) = space else { return Some(value) };
        if !(to.base.is_triple() || to.base == Base::Matrix4) || to.base == Base::Float3 {
            self.error(Diagnostic::error(
                Code::UnknownSpace,
                format!("`{to}` values have no space"),
                *space_span,
                "spaces apply to colours, points, vectors, normals and matrices",
            ));
            return None;
        }
        if !self.known_space(name, *space_span, to.base == Base::Color) {
            return None;
        }
        let from_space = ExprKind::FromSpace { space: name.into(), value };
        if to.base == Base::Color {
            // Colour spaces are converted by the library (`compiler/stdlib/builtins.sl`).
            if name == "rgb" {
                return Some(value);
            }
            let space =
                self.push_expr(ExprKind::Literal(Literal::String(name.into())), Type::STRING, *space_span);
            return self.library_call("_patina_to_rgb", vec![space, value], from_space, to, span, out);
        }
        Some(self.push_expr(from_space, to, span))
    }

    /// Checks a space name, reporting an unknown one with the list and a likely correction.
    pub(super) fn known_space(&mut self, name: &str, span: crate::source::Span, colour: bool) -> bool {
        let known: &[&str] = if colour { COLOR_SPACES } else { SPACES };
        if known.contains(&name) {
            return true;
        }
        let mut d = Diagnostic::error(
            Code::UnknownSpace,
            format!("unknown {} space \"{name}\"", if colour { "colour" } else { "coordinate" }),
            span,
            "not a known space",
        )
        .with_note(format!("the spaces are {}", known.join(", ")));
        if let Some(close) = suggest(name, known.iter().copied()) {
            d = d.with_help(format!("did you mean \"{close}\"?"));
        }
        self.error(d);
        false
    }

    fn index(&mut self, base: ExprId, index: ExprId, span: crate::source::Span) -> Option<ExprId> {
        let bt = self.ty(base);
        let element = match (bt.array, bt.base) {
            (Some(_), b) => Some(Type::of(b)),
            (None, b) if b.is_triple() || b == Base::Float4 => Some(Type::FLOAT),
            (None, Base::Matrix4) => Some(Type::of(Base::Float4)),
            (None, Base::Matrix3) => Some(Type::of(Base::Float3)),
            // RenderMan's channel selection: `texture("name"[1], s, t)`.
            (None, Base::String) => Some(Type::STRING),
            _ => None,
        };
        let Some(element) = element else {
            self.error(Diagnostic::error(
                Code::InvalidIndex,
                format!("`{bt}` cannot be indexed"),
                self.span_of(base),
                "has no elements",
            ));
            return None;
        };
        let it = self.ty(index);
        let index = match it.base {
            Base::Int | Base::Uint if it.array.is_none() => index,
            // RenderMan indexes with floats; they are truncated.
            Base::Float if it.array.is_none() => {
                self.push_expr(ExprKind::Convert(index), Type::INT, self.span_of(index))
            }
            _ => {
                self.error(Diagnostic::error(
                    Code::InvalidIndex,
                    format!("an index must be an integer, found `{it}`"),
                    self.span_of(index),
                    "not an integer",
                ));
                return None;
            }
        };
        // A constant index (a literal, possibly negated) is checked against the array's length.
        let constant = match &self.expr_ref(index).kind {
            ExprKind::Literal(Literal::Int(i)) => Some(i64::from(*i)),
            ExprKind::Literal(Literal::Uint(i)) => Some(i64::from(*i)),
            ExprKind::Unary(UnaryOp::Neg, inner) => match self.expr_ref(*inner).kind {
                ExprKind::Literal(Literal::Int(i)) => Some(-i64::from(i)),
                ExprKind::Literal(Literal::Uint(i)) => Some(-i64::from(i)),
                _ => None,
            },
            _ => None,
        };
        if let (Some(len), Some(i)) = (bt.array.filter(|n| *n > 0), constant)
            && (i < 0 || i >= i64::from(len))
        {
            self.error(Diagnostic::error(
                Code::InvalidIndex,
                format!("index {i} is out of range for `{bt}`"),
                self.span_of(index),
                format!("valid indices are 0 to {}", len - 1),
            ));
            return None;
        }
        Some(self.push_expr(ExprKind::Index(base, index), element, span))
    }
}

/// "a" or "an" before a shader kind.
pub(super) fn article(kind: ast::ShaderKind) -> &'static str {
    match kind {
        ast::ShaderKind::Imager => "an",
        _ => "a",
    }
}
