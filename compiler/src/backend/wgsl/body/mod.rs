//! A stage's body (or a light shader's) to naga: statements and expressions.
//!
//! A language variable is a private (per-invocation) module variable, so inlined function bodies
//! can become naga functions of their own (their `return` is then naga's `return`), and the entry
//! points fill inputs and read outputs around one call of the body; a variable stored once before
//! all its reads is the stored value instead (`super::values`). Expressions are
//! translated per statement (a statement's subexpressions are shared; the next statement reads
//! variables afresh), as the interpreter does.

use naga::{
    BinaryOperator, Expression, Handle, Literal as NLit, MathFunction, ScalarKind, Span, Statement,
    UnaryOperator,
};
use rustc_hash::{FxHashMap, FxHashSet};
use smol_str::SmolStr;

mod bound;
mod expr;
mod operators;

/// The most lights one shader may be bound to: light loops and light sums are unrolled over the
/// bound lights, and each bound light adds its shader and its parameters to the module.
pub const MAX_LIGHTS: usize = 64;

/// Refuses more than [`MAX_LIGHTS`] lights bound to `surface` (`lights` are their shaders).
pub(crate) fn check_light_count(surface: &Shader, lights: &[&Shader]) -> Result<(), Diagnostic> {
    let Some(first_over) = lights.get(MAX_LIGHTS) else { return Ok(()) };
    Err(Diagnostic::error(
        Code::LightLimit,
        format!("{} lights are bound to `{}`, over the limit of {MAX_LIGHTS}", lights.len(), surface.name),
        surface.span,
        "this shader's light loops would be unrolled over every light",
    )
    // A note, not a label: the lights are usually compiled from other files than the surface.
    .with_note(format!("light {} (`{}`) is the first over the limit", MAX_LIGHTS + 1, first_over.name))
    .with_help("merge lights into fewer light shaders (a light shader may sum several sources)"))
}

use super::func::FnBuilder;
use super::module::{ModuleBuilder, sanitize};
use crate::backend::MAX_LOOP_ITERATIONS;
use crate::backend::binding::LightBinding;
use crate::diag::{Code, Diagnostic};
use crate::ir::types::{Base, Type};
use crate::ir::{ExprId, ExprKind, LocalId, Place, Shader, Stmt};
use crate::source::Span as SrcSpan;

/// Translates one program's statements into naga functions of a module.
pub(crate) struct Translator<'a> {
    pub mb: &'a mut ModuleBuilder,
    pub shader: &'a Shader,
    /// Prepended to every variable name (`l0_` for the first light).
    pub prefix: String,
    /// The bound lights (for `illuminance` and the light sums).
    pub lights: &'a [LightBinding],
    /// Their shaders, where their functions are in the same module (a surface's body: what
    /// `lightsource` reads); empty otherwise.
    pub light_shaders: Vec<&'a Shader>,
    /// The surface's fragment stage, in a light's or an atmosphere's function of the same
    /// module (what `surface` reads); `None` otherwise.
    pub surface: Option<&'a Shader>,
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
    /// The constant tables among the locals, which live in the uniform block or in initialized
    /// module variables (`super::tables`).
    tables: FxHashMap<LocalId, super::tables::Table>,
    /// The stores into each local (for loops' trip counts and the values).
    stores: Vec<crate::ir::stores::Stores>,
    /// The locals that are values, not variables (`super::values`).
    values: FxHashSet<LocalId>,
    /// The value of each of them stored so far in the function being built.
    value_of: FxHashMap<LocalId, Value>,
    /// The local whose value the function being built returns (`super::values::call_result`).
    returning: Option<LocalId>,
}

/// A value with its language type, for the helpers that dispatch on types.
pub(crate) type Value = Handle<Expression>;

impl<'a> Translator<'a> {
    /// A translator for `shader` whose variables are named after `prefix`, building `function`.
    pub fn new(
        mb: &'a mut ModuleBuilder,
        shader: &'a Shader,
        prefix: &str,
        lights: &'a [LightBinding],
        strings: &'a [(String, String)],
        function: &str,
    ) -> Self {
        let names = variable_names(shader, prefix);
        let tables = super::tables::find(shader);
        let stores = crate::ir::stores::stores(shader);
        let values = super::values::find(shader, &stores, &tables);
        Translator {
            mb,
            shader,
            prefix: prefix.to_string(),
            lights,
            light_shaders: Vec::new(),
            surface: None,
            strings,
            fb: FnBuilder::new(function),
            light: None,
            owner: None,
            memo: FxHashMap::default(),
            random_sites: 0,
            names,
            functions: 0,
            tables,
            stores,
            values,
            value_of: FxHashMap::default(),
            returning: None,
        }
    }

    /// Whether built-ins are written as WGSL's own (`super::lowering`).
    pub fn fast(&self) -> bool {
        self.mb.lowering == super::Lowering::Fast
    }

    /// A diagnostic for something this backend cannot translate (the interpreter may run it).
    pub fn error(&self, span: SrcSpan, message: impl Into<String>) -> Diagnostic {
        Diagnostic::error(Code::Internal, message, span, "here")
            .with_help("the WGSL backend cannot translate this yet; the CPU interpreter can run it")
    }

    // ---------------------------------------------------------------------------------------------
    // Variables.

    /// The private variable holding local `l` (per light for per-light locals).
    pub fn local_var(&mut self, l: LocalId) -> Handle<naga::GlobalVariable> {
        debug_assert!(!self.values.contains(&l), "local {l:?} is a value, not a variable");
        let local = self.shader.local(l);
        let mut name = self.names[&l].clone();
        if let Some(table) = self.tables.get(&l) {
            // Reached only for a table read whole, which stays a module variable.
            return self.mb.table(&name, local.ty, &table.contents);
        }
        if local.rate.perlight {
            name = format!("{name}_L{}", self.light.unwrap_or(0));
        }
        self.mb.private(&name, local.ty)
    }

    /// The uniform block's member holding the table `base` reads, when it is a table placed there.
    pub(crate) fn uniform_table(&mut self, base: ExprId) -> Option<u32> {
        let ExprKind::Local(l) = self.shader.expr(base).kind else { return None };
        let table = self.tables.get(&l)?;
        let ty = self.shader.local(l).ty;
        self.mb.table_member(&self.names[&l], ty, table)
    }

    /// The private variable holding predefined variable `name` (per light for per-light ones).
    pub fn global_var(&mut self, name: &str, ty: Type, perlight: bool) -> Handle<naga::GlobalVariable> {
        let mut full = format!("{}{}", self.prefix, sanitize(name));
        if perlight {
            full = format!("{full}_L{}", self.light.unwrap_or(0));
        }
        self.mb.private(&full, ty)
    }

    /// The value stored into local `l`, which is a value (`super::values`).
    pub(crate) fn value(&self, l: LocalId, span: SrcSpan) -> Result<Value, Diagnostic> {
        self.value_of.get(&l).copied().ok_or_else(|| {
            crate::backend::wgsl::internal(
                span,
                format!("internal error: `{}` read before its store", self.names[&l]),
            )
        })
    }

    /// Names an expression after the local it is the value of, so the WGSL reads `let x = ...`.
    fn name_value(&mut self, v: Value, l: LocalId) {
        let e = &self.fb.f.expressions[v];
        if !e.needs_pre_emit() && !self.fb.f.named_expressions.contains_key(&v) {
            self.fb.f.named_expressions.insert(v, self.names[&l].clone());
        }
    }

    /// A pointer expression to a private variable.
    pub fn pointer(&mut self, g: Handle<naga::GlobalVariable>) -> Value {
        self.fb.add(Expression::GlobalVariable(g))
    }

    /// The value a pointer points at.
    pub fn load(&mut self, pointer: Value) -> Value {
        self.fb.add(Expression::Load { pointer })
    }

    /// Stores a value through a pointer.
    pub fn store(&mut self, pointer: Value, value: Value) {
        self.fb.push(Statement::Store { pointer, value });
    }

    // ---------------------------------------------------------------------------------------------
    // Statements.

    /// Translates a block of statements into the open naga block.
    pub fn block(&mut self, block: &[Stmt]) -> Result<(), Diagnostic> {
        for (i, s) in block.iter().enumerate() {
            self.statement(s, i.checked_sub(1).map(|j| &block[j]))?;
        }
        Ok(())
    }

    /// Translates one statement (once per light for Stanford per-light statements); `before` is
    /// the statement before it in its block (a loop's counter may be set there).
    pub(crate) fn statement(&mut self, stmt: &Stmt, before: Option<&Stmt>) -> Result<(), Diagnostic> {
        self.memo.clear();
        match stmt {
            // A constant table's declaration: the module variable's initializer holds it.
            Stmt::Store { place: Place::Local(l), .. } if self.tables.contains_key(l) => {}
            Stmt::Store { place: Place::Local(l), value, .. } if self.values.contains(l) => {
                let v = self.expr(*value)?;
                self.name_value(v, *l);
                self.value_of.insert(*l, v);
            }
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
                let counted =
                    bound::constant_trip_count(self.shader, &self.stores, before, *cond, step).is_none();
                let counter = counted.then(|| self.iteration_counter());
                self.fb.open();
                if let Some(c) = cond {
                    self.memo.clear();
                    let c = self.condition(*c)?;
                    let not = self.fb.add(Expression::Unary { op: UnaryOperator::LogicalNot, expr: c });
                    self.break_if(not);
                }
                if let Some(counter) = counter {
                    self.count_iteration(counter);
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
            Stmt::Return => {
                let value = match self.returning {
                    Some(r) => Some(self.value(r, self.shader.span)?),
                    None => None,
                };
                self.fb.push(Statement::Return { value });
            }
            Stmt::Inline { function, body, .. } => self.inline(function, body)?,
            Stmt::Lights { lights, body } => {
                for &k in lights {
                    let outer = self.light.replace(k as usize);
                    let r = self.block(body);
                    self.light = outer;
                    r?;
                }
            }
            Stmt::Illuminance { .. } | Stmt::Emit { .. } => {
                return Err(crate::backend::wgsl::internal(
                    self.shader.span,
                    "internal error: a light construct reached the WGSL backend (opt::lights::unroll)".into(),
                ));
            }
        }
        Ok(())
    }

    /// `if condition { break; }`.
    fn break_if(&mut self, condition: Value) {
        self.fb.open();
        self.fb.push(Statement::Break);
        let accept = self.fb.close();
        self.fb.push(Statement::If { condition, accept, reject: naga::Block::new() });
    }

    /// A fresh `u32` variable of the current function, set to zero here (before the loop it
    /// counts, so that each execution of the loop counts from zero).
    fn iteration_counter(&mut self) -> Handle<naga::LocalVariable> {
        let ty = self.mb.ty(Type::of(Base::Uint), false);
        let name = format!("loop_iterations_{}", self.fb.f.local_variables.len());
        let counter = self
            .fb
            .f
            .local_variables
            .append(naga::LocalVariable { name: Some(name), ty, init: None }, Span::UNDEFINED);
        let pointer = self.fb.add(Expression::LocalVariable(counter));
        let zero = self.fb.add(Expression::Literal(NLit::U32(0)));
        self.store(pointer, zero);
        counter
    }

    /// At the top of a loop's body: leaves the loop once it has run [`MAX_LOOP_ITERATIONS`]
    /// times, and counts this iteration.
    fn count_iteration(&mut self, counter: Handle<naga::LocalVariable>) {
        let pointer = self.fb.add(Expression::LocalVariable(counter));
        let count = self.load(pointer);
        let cap = u32::try_from(MAX_LOOP_ITERATIONS).expect("the cap fits in u32");
        let cap = self.fb.add(Expression::Literal(NLit::U32(cap)));
        let spent =
            self.fb.add(Expression::Binary { op: BinaryOperator::GreaterEqual, left: count, right: cap });
        self.break_if(spent);
        let one = self.fb.add(Expression::Literal(NLit::U32(1)));
        let next = self.fb.add(Expression::Binary { op: BinaryOperator::Add, left: count, right: one });
        self.store(pointer, next);
    }

    /// An inlined call becomes a naga function of its own, so that its `return` is naga's. Its
    /// parameters' values are the function's arguments, computed here, and the value it stores
    /// last, when that is a value, is its result (`super::values`).
    pub(crate) fn inline(&mut self, function: &SmolStr, body: &[Stmt]) -> Result<(), Diagnostic> {
        self.functions += 1;
        let name = format!("{}{}_{}", self.prefix, sanitize(function), self.functions);
        let n = super::values::arguments(self.shader, body);
        let mut parameters = Vec::with_capacity(n);
        let mut arguments = Vec::with_capacity(n);
        for stmt in &body[..n] {
            let Stmt::Store { place: Place::Local(l), value, .. } = stmt else { unreachable!("an argument") };
            arguments.push(self.expr(*value)?);
            parameters.push(*l);
        }
        let result_local = super::values::call_result(body, &self.values);
        let outer = std::mem::replace(&mut self.fb, FnBuilder::new(&name));
        let memo = std::mem::take(&mut self.memo);
        let values = std::mem::take(&mut self.value_of);
        let returning = std::mem::replace(&mut self.returning, result_local);
        let result = self.callee(&parameters, body, n);
        let end_value = result_local.and_then(|r| self.value_of.get(&r).copied());
        let inner = std::mem::replace(&mut self.fb, outer);
        self.memo = memo;
        self.value_of = values;
        self.returning = returning;
        result?;
        let mut f = inner.finish();
        if let Some(r) = result_local {
            if !matches!(body.last(), Some(Stmt::Return)) {
                f.body.push(Statement::Return { value: end_value }, Span::UNDEFINED);
            }
            let ty = self.mb.ty(self.shader.local(r).ty, false);
            f.result = Some(naga::FunctionResult { ty, binding: None });
        }
        let handle = self.mb.module.functions.append(f, Span::UNDEFINED);
        let call_result = result_local.map(|r| {
            let h = self.fb.add_unemitted(Expression::CallResult(handle));
            self.value_of.insert(r, h);
            h
        });
        self.fb.push(Statement::Call { function: handle, arguments, result: call_result });
        Ok(())
    }

    /// The body of an inlined call, in its own function: its parameters from the arguments, then
    /// the statements after their stores.
    fn callee(&mut self, parameters: &[LocalId], body: &[Stmt], n: usize) -> Result<(), Diagnostic> {
        for (i, &l) in parameters.iter().enumerate() {
            let ty = self.mb.ty(self.shader.local(l).ty, false);
            let name = self.names[&l].clone();
            self.fb.f.arguments.push(naga::FunctionArgument { name: Some(name), ty, binding: None });
            let argument = self.fb.add(Expression::FunctionArgument(i as u32));
            if self.values.contains(&l) {
                self.value_of.insert(l, argument);
            } else {
                let g = self.local_var(l);
                let p = self.pointer(g);
                self.store(p, argument);
            }
        }
        for i in n..body.len() {
            self.statement(&body[i], i.checked_sub(1).map(|j| &body[j]))?;
        }
        Ok(())
    }

    /// The value of local `l` when its declaration is its only store.
    pub(crate) fn only_initialiser(&self, l: LocalId) -> Option<ExprId> {
        self.stores.get(l.0 as usize)?.only_initialiser(self.shader.local(l).span)
    }

    /// A pointer to the place a store writes (indices clamped into range).
    pub(crate) fn place(&mut self, place: &Place) -> Result<Value, Diagnostic> {
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
                let ty = self.shader.place_type(inner);
                let base = self.place(inner)?;
                let i = self.index(*index, ty)?;
                Ok(self.fb.add(Expression::Access { base, index: i }))
            }
        }
    }

    /// An index into a value of type `ty`, as a `u32` clamped to the valid range (constant
    /// indices in range are used as they are).
    pub(crate) fn index(&mut self, index: ExprId, ty: Type) -> Result<Value, Diagnostic> {
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
            // A variable named like a predefined one (a function's `uint s`) would share the
            // private variable that holds the predefined value.
            let taken = count[l.name.as_str()] > 1 || crate::sema::globals::is_predefined(&l.name);
            let name = if taken { format!("{base}_{i}") } else { base };
            (LocalId(i as u32), format!("{prefix}{name}"))
        })
        .collect()
}
