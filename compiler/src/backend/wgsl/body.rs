//! A stage's body (or a light shader's) to naga: statements and expressions.
//!
//! Every language variable is a private (per-invocation) module variable, so inlined function
//! bodies can become naga functions of their own (their `return` is then naga's `return`), and
//! the entry points fill inputs and read outputs around one call of the body. Expressions are
//! translated per statement (a statement's subexpressions are shared; the next statement reads
//! variables afresh), as the interpreter does.

use naga::{
    BinaryOperator, Expression, Handle, Literal as NLit, MathFunction, RelationalFunction, ScalarKind, Span,
    Statement, UnaryOperator,
};
use rustc_hash::FxHashMap;
use smol_str::SmolStr;

use super::func::FnBuilder;
use super::module::{ModuleBuilder, sanitize, vector_size};
use crate::backend::cpu::LightBinding;
use crate::diag::{Code, Diagnostic};
use crate::ir::types::{Base, Type};
use crate::ir::{BinaryOp, ExprId, ExprKind, Literal, LocalId, Place, Shader, Stmt, UnaryOp};
use crate::source::Span as SrcSpan;

/// Translates one program's statements into naga functions of a module.
pub(crate) struct Translator<'a> {
    pub mb: &'a mut ModuleBuilder,
    pub shader: &'a Shader,
    /// Prepended to every variable name (`l0_` for the first light).
    pub prefix: String,
    /// The bound lights (for `illuminance` and the light sums).
    pub lights: &'a [LightBinding],
    /// Values of string parameters.
    pub strings: &'a [(String, String)],
    pub fb: FnBuilder,
    /// The light the code being translated runs for (in an unrolled light loop).
    pub light: Option<usize>,
    /// The bound light whose shader this is (`None` for the surface), for its spaces.
    pub owner: Option<usize>,
    memo: FxHashMap<(ExprId, Option<usize>), Handle<Expression>>,
    /// The `random()` call sites numbered so far (in the interpreter's order).
    pub random_sites: u32,
    names: FxHashMap<LocalId, String>,
    functions: u32,
}

/// A value with its language type, for the helpers that dispatch on types.
pub(crate) type Value = Handle<Expression>;

impl<'a> Translator<'a> {
    pub fn new(
        mb: &'a mut ModuleBuilder,
        shader: &'a Shader,
        prefix: &str,
        lights: &'a [LightBinding],
        strings: &'a [(String, String)],
        function: &str,
    ) -> Self {
        let names = variable_names(shader, prefix);
        Translator {
            mb,
            shader,
            prefix: prefix.to_string(),
            lights,
            strings,
            fb: FnBuilder::new(function),
            light: None,
            owner: None,
            memo: FxHashMap::default(),
            random_sites: 0,
            names,
            functions: 0,
        }
    }

    pub fn error(&self, span: SrcSpan, message: impl Into<String>) -> Diagnostic {
        Diagnostic::error(Code::Internal, message, span, "here")
            .with_help("the WGSL backend cannot translate this yet; the CPU interpreter can run it")
    }

    // ---------------------------------------------------------------------------------------------
    // Variables.

    /// The private variable holding local `l` (per light for per-light locals).
    pub fn local_var(&mut self, l: LocalId) -> Handle<naga::GlobalVariable> {
        let local = self.shader.local(l);
        let mut name = self.names[&l].clone();
        if local.rate.perlight {
            name = format!("{name}_L{}", self.light.unwrap_or(0));
        }
        self.mb.private(&name, local.ty)
    }

    /// The private variable holding predefined variable `name` (per light for per-light ones).
    pub fn global_var(&mut self, name: &str, ty: Type, perlight: bool) -> Handle<naga::GlobalVariable> {
        let mut full = format!("{}{}", self.prefix, sanitize(name));
        if perlight {
            full = format!("{full}_L{}", self.light.unwrap_or(0));
        }
        self.mb.private(&full, ty)
    }

    /// A pointer expression to a private variable.
    pub fn pointer(&mut self, g: Handle<naga::GlobalVariable>) -> Value {
        self.fb.add(Expression::GlobalVariable(g))
    }

    pub fn load(&mut self, pointer: Value) -> Value {
        self.fb.add(Expression::Load { pointer })
    }

    pub fn store(&mut self, pointer: Value, value: Value) {
        self.fb.push(Statement::Store { pointer, value });
    }

    // ---------------------------------------------------------------------------------------------
    // Statements.

    pub fn block(&mut self, block: &[Stmt]) -> Result<(), Diagnostic> {
        for s in block {
            self.statement(s)?;
        }
        Ok(())
    }

    fn statement(&mut self, stmt: &Stmt) -> Result<(), Diagnostic> {
        if self.light.is_none() && self.statement_is_perlight(stmt) {
            for k in 0..self.lights.len() {
                self.light = Some(k);
                let r = self.statement(stmt);
                self.light = None;
                r?;
            }
            return Ok(());
        }
        self.memo.clear();
        match stmt {
            Stmt::Store { place, value, .. } => {
                let v = self.expr(*value)?;
                let p = self.place(place)?;
                self.store(p, v);
            }
            Stmt::Eval(id) => {
                self.expr(*id)?;
            }
            Stmt::If { cond, then, otherwise } => {
                let c = self.condition(*cond)?;
                self.fb.open();
                self.block(then)?;
                let accept = self.fb.close();
                self.fb.open();
                self.block(otherwise)?;
                let reject = self.fb.close();
                self.fb.push(Statement::If { condition: c, accept, reject });
            }
            Stmt::Loop { cond, body, step, .. } => {
                self.fb.open();
                if let Some(c) = cond {
                    self.memo.clear();
                    let c = self.condition(*c)?;
                    let not = self.fb.add(Expression::Unary { op: UnaryOperator::LogicalNot, expr: c });
                    self.fb.open();
                    self.fb.push(Statement::Break);
                    let accept = self.fb.close();
                    self.fb.push(Statement::If { condition: not, accept, reject: naga::Block::new() });
                }
                self.block(body)?;
                let body = self.fb.close();
                self.fb.open();
                self.block(step)?;
                let continuing = self.fb.close();
                self.fb.push(Statement::Loop { body, continuing, break_if: None });
            }
            Stmt::Break(1) => self.fb.push(Statement::Break),
            Stmt::Continue(1) => self.fb.push(Statement::Continue),
            Stmt::Break(_) | Stmt::Continue(_) => {
                return Err(self.error(self.shader.span, "`break` or `continue` out of more than one loop"));
            }
            Stmt::Return => self.fb.push(Statement::Return { value: None }),
            Stmt::Inline { function, body, .. } => self.inline(function, body)?,
            Stmt::Illuminance { args, body } => self.illuminance(args, body)?,
            Stmt::Emit { solar, args, body } => self.emission(*solar, args, body)?,
        }
        Ok(())
    }

    /// An inlined call becomes a naga function of its own, so that its `return` is naga's.
    fn inline(&mut self, function: &SmolStr, body: &[Stmt]) -> Result<(), Diagnostic> {
        self.functions += 1;
        let name = format!("{}{}_{}", self.prefix, sanitize(function), self.functions);
        let outer = std::mem::replace(&mut self.fb, FnBuilder::new(&name));
        let memo = std::mem::take(&mut self.memo);
        let result = self.block(body);
        let inner = std::mem::replace(&mut self.fb, outer);
        self.memo = memo;
        result?;
        let handle = self.mb.module.functions.append(inner.finish(), Span::UNDEFINED);
        self.fb.push(Statement::Call { function: handle, arguments: Vec::new(), result: None });
        Ok(())
    }

    /// Whether a statement computes a per-light value outside a light loop (Stanford style).
    fn statement_is_perlight(&self, stmt: &Stmt) -> bool {
        let perlight = |id: &ExprId| self.shader.expr(*id).rate.perlight;
        let place_perlight = |mut p: &Place| loop {
            match p {
                Place::Local(l) => return self.shader.local(*l).rate.perlight,
                Place::Global(g) => return g.perlight,
                Place::Index(inner, _) => p = inner,
            }
        };
        match stmt {
            Stmt::Store { place, value, .. } => place_perlight(place) || perlight(value),
            Stmt::Eval(id) => perlight(id),
            Stmt::If { cond, .. } => perlight(cond),
            Stmt::Loop { cond, .. } => cond.as_ref().is_some_and(perlight),
            _ => false,
        }
    }

    /// A pointer to the place a store writes (indices clamped into range).
    fn place(&mut self, place: &Place) -> Result<Value, Diagnostic> {
        match place {
            Place::Local(l) => {
                let g = self.local_var(*l);
                Ok(self.pointer(g))
            }
            Place::Global(g) => {
                let var = self.global_var(g.name, Type::of(g.ty), g.perlight);
                Ok(self.pointer(var))
            }
            Place::Index(inner, index) => {
                let ty = place_type(self.shader, inner);
                let base = self.place(inner)?;
                let i = self.index(*index, ty)?;
                Ok(self.fb.add(Expression::Access { base, index: i }))
            }
        }
    }

    /// An index into a value of type `ty`, as a `u32` clamped to the valid range (constant
    /// indices in range are used as they are).
    fn index(&mut self, index: ExprId, ty: Type) -> Result<Value, Diagnostic> {
        let len = match ty.array {
            Some(n) => n,
            None => match ty.base {
                Base::Matrix3 => 3,
                Base::Matrix4 => 4,
                b => b.components(),
            },
        };
        let signed = self.shader.expr(index).ty.base == Base::Int;
        let i = self.expr(index)?;
        let i = if signed {
            let zero = self.fb.add(Expression::Literal(NLit::I32(0)));
            let m = self.math2(MathFunction::Max, i, zero);
            self.fb.add(Expression::As { expr: m, kind: ScalarKind::Uint, convert: Some(4) })
        } else {
            i
        };
        let last = self.fb.add(Expression::Literal(NLit::U32(len.max(1) - 1)));
        Ok(self.math2(MathFunction::Min, i, last))
    }

    /// A condition as a naga `bool`.
    pub fn condition(&mut self, id: ExprId) -> Result<Value, Diagnostic> {
        self.expr(id)
    }

    // ---------------------------------------------------------------------------------------------
    // Lights.

    /// `illuminance`: the body once per bound non-ambient light of the category, inside its cone.
    fn illuminance(&mut self, args: &[ExprId], body: &[Stmt]) -> Result<(), Diagnostic> {
        let (category, rest) = match args.first().map(|a| self.shader.expr(*a).ty.base) {
            Some(Base::String) => (self.string_value(args[0]), &args[1..]),
            _ => (None, args),
        };
        for k in 0..self.lights.len() {
            let light = &self.lights[k];
            if light.ambient || category.as_ref().is_some_and(|c| !category_matches(c, &light.categories)) {
                continue;
            }
            self.light = Some(k);
            self.memo.clear();
            let cone = match rest {
                [_, axis, angle] => {
                    let l = self.global_value("L")?;
                    let axis = self.expr(*axis)?;
                    let angle = self.expr(*angle)?;
                    Some(self.inside_cone(l, axis, angle))
                }
                _ => None,
            };
            self.fb.open();
            let r = self.block(body);
            let inner = self.fb.close();
            self.light = None;
            r?;
            match cone {
                Some(c) => {
                    self.fb.push(Statement::If { condition: c, accept: inner, reject: naga::Block::new() })
                }
                None => self.fb.push(Statement::Block(inner)),
            }
        }
        Ok(())
    }

    /// `illuminate`/`solar` in a light shader: sets `L` (from the light to `Ps`) and runs the body
    /// where the point is inside the cone.
    fn emission(&mut self, solar: bool, args: &[ExprId], body: &[Stmt]) -> Result<(), Diagnostic> {
        self.memo.clear();
        let vals: Vec<Value> = args.iter().map(|a| self.expr(*a)).collect::<Result<_, _>>()?;
        let l_var = self.global_var("L", Type::of(Base::Vector), false);
        let direction = if solar {
            match vals.first() {
                Some(axis) => *axis,
                None => {
                    let p = self.pointer(l_var);
                    self.load(p)
                }
            }
        } else {
            let ps = self.global_value("Ps")?;
            self.binary(BinaryOperator::Subtract, ps, vals[0])
        };
        let p = self.pointer(l_var);
        self.store(p, direction);
        let (axis, angle) = if solar { (vals.first(), vals.get(1)) } else { (vals.get(1), vals.get(2)) };
        let cone = match (axis, angle) {
            (Some(&axis), Some(&angle)) => Some(self.inside_cone(direction, axis, angle)),
            _ => None,
        };
        self.fb.open();
        self.block(body)?;
        let inner = self.fb.close();
        match cone {
            Some(c) => {
                self.fb.push(Statement::If { condition: c, accept: inner, reject: naga::Block::new() })
            }
            None => self.fb.push(Statement::Block(inner)),
        }
        Ok(())
    }

    /// `dot(l, axis) >= cos(angle) * sqrt(dot(l, l) * dot(axis, axis))`, as the interpreter.
    fn inside_cone(&mut self, l: Value, axis: Value, angle: Value) -> Value {
        let dot = self.math2(MathFunction::Dot, l, axis);
        let ll = self.math2(MathFunction::Dot, l, l);
        let aa = self.math2(MathFunction::Dot, axis, axis);
        let lengths = self.binary(BinaryOperator::Multiply, ll, aa);
        let lengths = self.math1(MathFunction::Sqrt, lengths);
        let cos = self.math1(MathFunction::Cos, angle);
        let bound = self.binary(BinaryOperator::Multiply, cos, lengths);
        self.binary(BinaryOperator::GreaterEqual, dot, bound)
    }

    /// The value of a predefined variable of this shader by name.
    pub fn global_value(&mut self, name: &str) -> Result<Value, Diagnostic> {
        match crate::sema::globals::lookup(name, self.shader.kind, self.shader.stanford) {
            Some(g) => {
                let var = self.global_var(g.name, Type::of(g.ty), g.perlight);
                let p = self.pointer(var);
                Ok(self.load(p))
            }
            None => Err(self.error(self.shader.span, format!("this shader has no `{name}`"))),
        }
    }

    // ---------------------------------------------------------------------------------------------
    // Expressions.

    /// The value of an expression (computed once per statement and light).
    pub fn expr(&mut self, id: ExprId) -> Result<Value, Diagnostic> {
        if let Some(v) = self.memo.get(&(id, self.light)) {
            return Ok(*v);
        }
        let v = stacker::maybe_grow(64 * 1024, 1024 * 1024, || self.expr_uncached(id))?;
        self.memo.insert((id, self.light), v);
        Ok(v)
    }

    fn expr_uncached(&mut self, id: ExprId) -> Result<Value, Diagnostic> {
        let e = self.shader.expr(id);
        let (ty, span) = (e.ty, e.span);
        Ok(match &e.kind {
            ExprKind::Literal(l) => self.literal(l, span)?,
            ExprKind::Local(l) => {
                if self.shader.local(*l).ty.base == Base::String {
                    return Err(self.error(span, "a string used as a value"));
                }
                let g = self.local_var(*l);
                let p = self.pointer(g);
                self.load(p)
            }
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
            ExprKind::Binary(op, a, b) if self.shader.expr(*a).ty.base == Base::String => {
                // Strings are known at compile time: so is their comparison.
                let (Some(x), Some(y)) = (self.string_value(*a), self.string_value(*b)) else {
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
                self.space_to_current(space, v, from, span)?
            }
            ExprKind::Index(base, index) => {
                let bt = self.shader.expr(*base).ty;
                if let Some(c) = self.constant_index(*index, bt) {
                    let v = self.expr(*base)?;
                    self.fb.add(Expression::AccessIndex { base: v, index: c })
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
                let name = super::entry::seed_name(self.shader, *input, *axis);
                let g = self.mb.private(&format!("{}{name}", self.prefix), ty);
                let p = self.pointer(g);
                self.load(p)
            }
        })
    }

    fn constant_index(&self, index: ExprId, ty: Type) -> Option<u32> {
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

    fn literal(&mut self, l: &Literal, span: SrcSpan) -> Result<Value, Diagnostic> {
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

    /// The string a string-typed expression denotes (strings are known at compile time).
    pub fn string_value(&self, id: ExprId) -> Option<SmolStr> {
        match &self.shader.expr(id).kind {
            ExprKind::Literal(Literal::String(s)) => Some(s.clone()),
            ExprKind::Local(l) => {
                let local = self.shader.local(*l);
                if let Some((_, v)) = self.strings.iter().find(|(n, _)| *n == local.name) {
                    return Some(SmolStr::new(v));
                }
                match local.kind {
                    crate::ir::LocalKind::Param { default: Some(d), .. } => self.string_value(d),
                    _ => None,
                }
            }
            _ => None,
        }
    }

    // ---------------------------------------------------------------------------------------------
    // Operators.

    pub fn binary(&mut self, op: BinaryOperator, left: Value, right: Value) -> Value {
        self.fb.add(Expression::Binary { op, left, right })
    }

    pub fn math1(&mut self, fun: MathFunction, arg: Value) -> Value {
        self.fb.add(Expression::Math { fun, arg, arg1: None, arg2: None, arg3: None })
    }

    pub fn math2(&mut self, fun: MathFunction, arg: Value, arg1: Value) -> Value {
        self.fb.add(Expression::Math { fun, arg, arg1: Some(arg1), arg2: None, arg3: None })
    }

    pub fn math3(&mut self, fun: MathFunction, arg: Value, arg1: Value, arg2: Value) -> Value {
        self.fb.add(Expression::Math { fun, arg, arg1: Some(arg1), arg2: Some(arg2), arg3: None })
    }

    /// A scalar widened to `n` components (`n == 1`: as it is).
    pub fn splat(&mut self, v: Value, n: u32) -> Value {
        if n <= 1 { v } else { self.fb.add(Expression::Splat { size: vector_size(n), value: v }) }
    }

    fn binary_op(
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
            let inverse = self.invert_entries(&entries, n as usize);
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
        Ok(self.binary(bop, a, b))
    }

    fn comparison(
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
    fn mat_mul(&mut self, a: Value, ta: Type, b: Value, tb: Type) -> Value {
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
                let entries = self.product(&x, &y, n as usize);
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
    fn convert(&mut self, v: Value, from: Type, to: Type, span: SrcSpan) -> Result<Value, Diagnostic> {
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
    fn construct(&mut self, parts: &[Value], ty: Type) -> Value {
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

/// The private variable name of every local of `shader`: its source name, with the local's number
/// when the name is used twice, after `prefix`.
pub(crate) fn variable_names(shader: &Shader, prefix: &str) -> FxHashMap<LocalId, String> {
    let mut count: FxHashMap<&str, u32> = FxHashMap::default();
    for l in &shader.locals {
        *count.entry(l.name.as_str()).or_default() += 1;
    }
    shader
        .locals
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let base = sanitize(&l.name);
            let name = if count[l.name.as_str()] > 1 { format!("{base}_{i}") } else { base };
            (LocalId(i as u32), format!("{prefix}{name}"))
        })
        .collect()
}

/// The type of a place.
fn place_type(shader: &Shader, place: &Place) -> Type {
    match place {
        Place::Local(l) => shader.local(*l).ty,
        Place::Global(g) => Type::of(g.ty),
        Place::Index(inner, _) => crate::backend::cpu::element_type(place_type(shader, inner)),
    }
}

/// Whether a light's categories match an `illuminance` category selector (`"a,b"`: any of
/// them; `"-a"`: not in a), as the interpreter decides.
fn category_matches(selector: &str, categories: &[String]) -> bool {
    crate::backend::cpu::category_matches(selector, categories)
}
