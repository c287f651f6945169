//! Lowering statements, declarations and parameters.

use rustc_hash::FxHashMap;

use super::{Frame, LightLoop, Lowerer};
use crate::diag::{Code, Diagnostic};
use crate::ir::types::{Base, Rate, Type};
use crate::ir::{Block, ExprId, ExprKind, LocalId, LocalKind, Place, Stmt};
use crate::syntax::ast::{self, StmtKind};

/// The type a declaration gives: its base type, made an array by the declarator's size.
pub(super) fn declared_type(ty: ast::TypeSpec, array: Option<&ast::ArraySize>) -> Type {
    Type { base: Base::from_ast(ty.name), array: array.map(|a| a.len.unwrap_or(0)) }
}

/// Whether every path through `stmts` ends in `return` (a conservative syntactic check).
pub(super) fn always_returns(stmts: &[ast::Stmt]) -> bool {
    stmts.iter().any(|s| match &s.kind {
        StmtKind::Return(_) => true,
        StmtKind::Block(b) => always_returns(&b.stmts),
        StmtKind::If { then, otherwise: Some(otherwise), .. } => {
            always_returns(std::slice::from_ref(then)) && always_returns(std::slice::from_ref(otherwise))
        }
        _ => false,
    })
}

impl Lowerer<'_> {
    /// Lowers statements in a new scope, appending to `out`.
    pub(super) fn block(&mut self, stmts: &[ast::Stmt], out: &mut Block) {
        self.scopes.push(FxHashMap::default());
        let functions = self.local_functions.len();
        for s in stmts {
            self.stmt(s, out);
        }
        self.local_functions.truncate(functions);
        self.scopes.pop();
    }

    /// The body of a nested statement, one level deeper (empty past the nesting limit).
    fn sub_block(&mut self, s: &ast::Stmt) -> Block {
        let mut out = Vec::new();
        if self.enter_nested(s.span) {
            self.block(std::slice::from_ref(s), &mut out);
            self.nesting -= 1;
        }
        out
    }

    /// Declares and stores the parameters of a shader; returns their locals.
    pub(super) fn params(&mut self, params: &[ast::Param], out: &mut Block) -> Vec<LocalId> {
        let mut ids = Vec::with_capacity(params.len());
        for p in params {
            let ty = declared_type(p.ty, p.array.as_ref());
            if p.qualifiers.extern_.is_some() {
                self.error(Diagnostic::error(
                    Code::InvalidQualifier,
                    "a parameter cannot be `extern`",
                    p.qualifiers.extern_.unwrap_or_default(),
                    "`extern` names a variable of an enclosing scope",
                ));
            }
            let (rate, declared) = self.declared_rate(&p.qualifiers, true);
            let default = p.default.as_ref().and_then(|d| {
                let value = self.expr(d, Some(ty), out)?;
                self.coerce(value, ty, "the parameter")
            });
            let kind = LocalKind::Param { default, output: p.qualifiers.output.is_some() };
            let id = self.new_local(p.name.name.clone(), ty, rate, declared, kind, p.name.span);
            self.bind(&p.name, id);
            ids.push(id);
        }
        ids
    }

    /// Lowers a variable declaration: a local per declarator, and a store of each initialiser.
    pub(super) fn declaration(&mut self, decl: &ast::VarDecl, out: &mut Block) {
        if let Some(span) = decl.qualifiers.output {
            self.error(
                Diagnostic::error(
                    Code::InvalidQualifier,
                    "only parameters can be `output`",
                    span,
                    "not a parameter",
                )
                .with_help("remove `output`; a variable can always be assigned"),
            );
        }
        for d in &decl.declarators {
            let ty = declared_type(decl.ty, d.array.as_ref());
            if ty.base == Base::Void {
                self.error(Diagnostic::error(
                    Code::TypeMismatch,
                    "a variable cannot be `void`",
                    decl.ty.span,
                    "`void` has no values",
                ));
                continue;
            }
            if decl.qualifiers.extern_.is_some() {
                // `extern float x;` names a variable of the shader; nothing new is declared.
                if self.lookup_local(&d.name.name).is_none()
                    && super::super::globals::lookup(&d.name.name, self.kind, self.stanford).is_none()
                {
                    self.error(Diagnostic::error(
                        Code::UnknownName,
                        format!("`extern` names `{}`, which is not declared", d.name.name),
                        d.name.span,
                        "no such variable",
                    ));
                }
                continue;
            }
            let (rate, declared) = self.declared_rate(&decl.qualifiers, false);
            let uniform = declared && rate.frequency == crate::ir::types::Frequency::PrimitiveGroup;
            let outer = std::mem::replace(&mut self.uniform_random, uniform);
            let init = d.init.as_ref().and_then(|e| {
                let value = self.expr(e, Some(ty), out)?;
                self.coerce(value, ty, "the variable")
            });
            self.uniform_random = outer;
            let id = self.new_local(d.name.name.clone(), ty, rate, declared, LocalKind::Var, d.name.span);
            if let Some(value) = init {
                self.store(Place::Local(id), value, d.span, out);
            }
            self.bind(&d.name, id);
        }
    }

    fn stmt(&mut self, s: &ast::Stmt, out: &mut Block) {
        // Statements nest as deep as the source's `if` and `else if` chains (within the front
        // end's limits): grow the stack rather than overflow it.
        stacker::maybe_grow(64 * 1024, 1024 * 1024, || self.stmt_here(s, out))
    }

    fn stmt_here(&mut self, s: &ast::Stmt, out: &mut Block) {
        match &s.kind {
            StmtKind::Block(b) => self.block(&b.stmts, out),
            StmtKind::Decl(d) => self.declaration(d, out),
            // A function defined in a body is visible in the rest of that body and inlined at
            // its calls there, seeing the body's variables.
            StmtKind::Function(f) => self.define_local_function(f),
            StmtKind::Expr(e) => {
                if let Some(id) = self.expr(e, None, out)
                    && matches!(self.expr_ref(id).kind, crate::ir::ExprKind::Builtin(..))
                {
                    out.push(Stmt::Eval(id));
                }
            }
            StmtKind::Empty | StmtKind::Error => {}
            StmtKind::Gather { .. } => self.error(crate::sema::unsupported::gather(s.span)),
            StmtKind::If { cond, then, otherwise } => {
                let cond = self.expr(cond, Some(Type::BOOL), out).and_then(|c| self.condition(c));
                // In library code a condition on literal strings (a space name) is decided here:
                // only the side it takes is lowered, so nothing of the others reaches a backend.
                if self.in_library()
                    && let Some(taken) = cond.and_then(|c| self.decided(c))
                {
                    let side = if taken { Some(&**then) } else { otherwise.as_deref() };
                    if let Some(side) = side {
                        let block = self.sub_block(side);
                        out.extend(block);
                    }
                    return;
                }
                let then = self.sub_block(then);
                // An `else if` chain is as deep as it is long; its length has its own limit.
                let otherwise = match otherwise.as_deref() {
                    Some(o @ ast::Stmt { kind: StmtKind::If { .. }, .. }) => {
                        let mut out = Vec::new();
                        self.block(std::slice::from_ref(o), &mut out);
                        out
                    }
                    Some(o) => self.sub_block(o),
                    None => Vec::new(),
                };
                if let Some(cond) = cond {
                    out.push(Stmt::If { cond, then, otherwise });
                }
            }
            StmtKind::While { cond, body } => {
                let mut prelude = Vec::new();
                let cond = self.expr(cond, Some(Type::BOOL), &mut prelude).and_then(|c| self.condition(c));
                self.no_effects_in_loop_condition(&prelude, s.span);
                self.loops += 1;
                let body = self.sub_block(body);
                self.loops -= 1;
                if let Some(cond) = cond {
                    out.push(Stmt::Loop { cond: Some(cond), body, step: Vec::new(), span: s.span });
                }
            }
            StmtKind::For { init, cond, step, body } => {
                self.scopes.push(FxHashMap::default());
                if let Some(init) = init {
                    self.stmt(init, out);
                }
                let mut prelude = Vec::new();
                let cond = cond
                    .as_ref()
                    .map(|c| self.expr(c, Some(Type::BOOL), &mut prelude).and_then(|c| self.condition(c)));
                self.no_effects_in_loop_condition(&prelude, s.span);
                let mut step_block = Vec::new();
                if let Some(step) = step {
                    self.expr(step, None, &mut step_block);
                }
                self.loops += 1;
                let body = self.sub_block(body);
                self.loops -= 1;
                self.scopes.pop();
                match cond {
                    Some(None) => {}
                    Some(Some(c)) => {
                        out.push(Stmt::Loop { cond: Some(c), body, step: step_block, span: s.span })
                    }
                    None => out.push(Stmt::Loop { cond: None, body, step: step_block, span: s.span }),
                }
            }
            StmtKind::Break { levels } | StmtKind::Continue { levels } => {
                let levels = levels.unwrap_or(1);
                let word = if matches!(s.kind, StmtKind::Break { .. }) { "break" } else { "continue" };
                if levels > self.loops {
                    let message = if self.loops == 0 {
                        format!("`{word}` outside a loop")
                    } else {
                        format!("`{word} {levels}` leaves more loops than the {} it is in", self.loops)
                    };
                    self.error(Diagnostic::error(
                        Code::MisplacedStatement,
                        message,
                        s.span,
                        "no loop to leave",
                    ));
                } else if word == "break" {
                    out.push(Stmt::Break(levels));
                } else {
                    out.push(Stmt::Continue(levels));
                }
            }
            StmtKind::Return(value) => self.return_stmt(value.as_ref(), s.span, out),
            StmtKind::Illuminance { args, body } => {
                if self.kind != ast::ShaderKind::Surface || self.stanford {
                    let mut d = Diagnostic::error(
                        Code::MisplacedStatement,
                        "`illuminance` belongs in RenderMan-style surface shaders",
                        s.span,
                        if self.stanford {
                            "this is a Stanford-style shader".to_string()
                        } else {
                            format!(
                                "this is {} {} shader",
                                super::expr::article(self.kind),
                                self.kind.keyword()
                            )
                        },
                    );
                    d = if self.stanford {
                        d.with_help("Stanford-style shaders sum per-light values with `integrate(...)`")
                    } else if self.kind == ast::ShaderKind::Light {
                        d.with_help("a light shader emits with `illuminate (...)` or `solar (...)`")
                    } else {
                        d
                    };
                    self.error(d);
                    return;
                }
                let args =
                    self.args(args, out).and_then(|a| self.light_args(a, LightForm::Illuminance, s.span));
                let saved = std::mem::replace(&mut self.light_loop, LightLoop::Illuminance);
                let body = self.sub_block(body);
                self.light_loop = saved;
                if let Some(args) = args {
                    out.push(Stmt::Illuminance { args, body });
                }
            }
            StmtKind::Illuminate { args, body } | StmtKind::Solar { args, body } => {
                let solar = matches!(s.kind, StmtKind::Solar { .. });
                let word = if solar { "solar" } else { "illuminate" };
                if self.kind != ast::ShaderKind::Light {
                    self.error(Diagnostic::error(
                        Code::MisplacedStatement,
                        format!("`{word}` belongs in light shaders"),
                        s.span,
                        "not a light shader",
                    ));
                    return;
                }
                let form = if solar { LightForm::Solar } else { LightForm::Illuminate };
                let args = self.args(args, out).and_then(|a| self.light_args(a, form, s.span));
                let body = self.sub_block(body);
                if let Some(args) = args {
                    out.push(Stmt::Emit { solar, args, body });
                }
            }
        }
    }

    /// A loop condition's effects would be hoisted out of the loop and run once: refuse them.
    fn no_effects_in_loop_condition(&mut self, prelude: &Block, span: crate::source::Span) {
        if !prelude.is_empty() {
            self.error(Diagnostic::error(
                Code::EffectInCondition,
                "a loop condition cannot assign",
                span,
                "the assignment would run once, not on every test",
            ));
        }
    }

    /// Lowers arguments of a statement (`illuminance(...)`), each without an expected type.
    /// The arguments of `illuminance`, `illuminate` or `solar`, converted to the types the
    /// construct takes (RenderMan's: `[string category,] point position [, vector axis, float
    /// angle]`, `point position [, vector axis, float angle]`, `[vector axis, float angle]`).
    fn light_args(
        &mut self,
        args: Vec<ExprId>,
        form: LightForm,
        span: crate::source::Span,
    ) -> Option<Vec<ExprId>> {
        let (point, vector, float) = (Type::of(Base::Point), Type::of(Base::Vector), Type::FLOAT);
        let category =
            form == LightForm::Illuminance && args.first().is_some_and(|a| self.ty(*a).base == Base::String);
        let rest = if category { &args[1..] } else { &args[..] };
        let expected: Option<&[Type]> = match (form, rest.len()) {
            (LightForm::Illuminance | LightForm::Illuminate, 1) => Some(&[point]),
            (LightForm::Illuminance | LightForm::Illuminate, 3) => Some(&[point, vector, float]),
            (LightForm::Solar, 0) => Some(&[]),
            (LightForm::Solar, 2) => Some(&[vector, float]),
            _ => None,
        };
        let Some(expected) = expected else {
            let forms = match form {
                LightForm::Illuminance => {
                    "`illuminance([category,] position)` or `illuminance([category,] position, axis, angle)`"
                }
                LightForm::Illuminate => "`illuminate(position)` or `illuminate(position, axis, angle)`",
                LightForm::Solar => "`solar()` or `solar(axis, angle)`",
            };
            self.error(
                Diagnostic::error(
                    Code::NoMatchingOverload,
                    format!("expected {forms}"),
                    span,
                    "these arguments",
                )
                .with_help("the angle is a cone half-angle in radians around the axis"),
            );
            return None;
        };
        let what = ["the position", "the axis", "the angle"];
        let what = if form == LightForm::Solar { &what[1..] } else { &what[..] };
        let mut out: Vec<ExprId> = if category { vec![args[0]] } else { Vec::new() };
        for ((arg, ty), what) in rest.iter().zip(expected).zip(what) {
            out.push(self.coerce(*arg, *ty, what)?);
        }
        Some(out)
    }

    fn args(&mut self, args: &[ast::Expr], out: &mut Block) -> Option<Vec<ExprId>> {
        let lowered: Vec<Option<ExprId>> = args.iter().map(|a| self.expr(a, None, out)).collect();
        lowered.into_iter().collect()
    }

    fn return_stmt(&mut self, value: Option<&ast::Expr>, span: crate::source::Span, out: &mut Block) {
        let (target, ty, what) = match self.frames.last() {
            Some(frame) => (frame.result, frame.ret, format!("function `{}`", frame.name)),
            None if self.stanford => (self.result_local, self.result_type, "the shader".to_string()),
            None => (None, Type::VOID, "a RenderMan-style shader".to_string()),
        };
        match (value, target) {
            (Some(v), Some(target)) => {
                if let Some(id) = self.expr(v, Some(ty), out).and_then(|id| self.coerce(id, ty, "the result"))
                {
                    self.store(Place::Local(target), id, span, out);
                }
            }
            (Some(v), None) => {
                let help = if self.frames.is_empty() {
                    "RenderMan-style shaders set `Ci` and `Oi` (or `Cl`, `P`, `N`); write `return;` to stop early"
                } else {
                    "declare the function with a result type, e.g. `float f(...)`"
                };
                self.error(
                    Diagnostic::error(
                        Code::InvalidReturn,
                        format!("{what} returns no value"),
                        v.span,
                        "this value has nowhere to go",
                    )
                    .with_help(help),
                );
                return;
            }
            (None, Some(_)) => {
                self.error(Diagnostic::error(
                    Code::InvalidReturn,
                    format!("{what} must return a `{ty}`"),
                    span,
                    "no value returned",
                ));
                return;
            }
            (None, None) => {}
        }
        out.push(Stmt::Return);
    }

    /// Inlines the body of `f` with its parameters bound to `args`; returns the result's local.
    fn define_local_function(&mut self, f: &ast::FunctionDef) {
        let depth = self.scopes.len();
        let signature = |f: &ast::FunctionDef| -> Vec<(ast::TypeName, Option<u32>)> {
            f.params.iter().map(|p| (p.ty.name, p.array.map(|a| a.len.unwrap_or(0)))).collect()
        };
        let previous = self
            .local_functions
            .iter()
            .find(|(d, g)| *d == depth && g.name.name == f.name.name && signature(g) == signature(f))
            .map(|(_, g)| g.name.span);
        if let Some(previous) = previous {
            self.error(
                Diagnostic::error(
                    Code::Redefinition,
                    format!("function `{}` is defined twice with the same parameter types", f.name.name),
                    f.name.span,
                    "defined again here",
                )
                .with_label(previous, "first defined here"),
            );
            return;
        }
        self.local_functions.push((depth, std::rc::Rc::new(f.clone())));
    }

    /// Inlines the body of `f` with its parameters bound to `args`; returns the result's local.
    /// `outer` is the definition depth of a function defined in a body; `library` says that `f`
    /// is a library built-in's implementation or a function one calls.
    pub(super) fn inline_body(
        &mut self,
        f: &ast::FunctionDef,
        args: &[Option<ExprId>],
        call_span: crate::source::Span,
        outer: Option<usize>,
        library: bool,
        out: &mut Block,
    ) -> Option<LocalId> {
        self.shared.inlined.insert(f.span);
        let ret = declared_type(f.return_type, None);
        let result = (ret.base != Base::Void).then(|| {
            self.new_local(
                format!("{} result", f.name.name).into(),
                ret,
                Rate::CONSTANT,
                false,
                LocalKind::Temp,
                call_span,
            )
        });
        let scope_base = self.scopes.len();
        self.scopes.push(FxHashMap::default());
        let mut body = Vec::new();
        let saved_loops = std::mem::replace(&mut self.loops, 0);
        // Inside `?:`, `&&` or `||` every operand is evaluated: the callee may assign its own
        // variables (only those, checked in `assign`), but may not write back to the caller.
        let guarded = (self.no_effects > 0).then_some(self.locals.len());
        let saved_no_effects = std::mem::replace(&mut self.no_effects, 0);
        if guarded.is_some()
            && let Some(p) = f.params.iter().find(|p| p.qualifiers.output.is_some())
        {
            self.error(
                Diagnostic::error(
                    Code::EffectInCondition,
                    format!(
                        "`{}` writes its output parameter `{}` inside `?:`, `&&` or `||`",
                        f.name.name, p.name.name
                    ),
                    call_span,
                    "every side of the operator is evaluated here",
                )
                .with_label(p.name.span, "an output parameter")
                .with_help("call it in a statement before the expression"),
            );
        }
        let mut outputs = Vec::new();
        for (p, arg) in f.params.iter().zip(args) {
            let mut ty = declared_type(p.ty, p.array.as_ref());
            // An open-length array parameter (`float t[]`) has its argument's length at this call.
            if ty.array == Some(0)
                && let Some(arg) = arg
                && let arg_ty = self.ty(*arg)
                && arg_ty.base == ty.base
                && arg_ty.array.is_some()
            {
                ty.array = arg_ty.array;
            }
            let (rate, declared) = self.declared_rate_function_param(&p.qualifiers);
            let id = self.new_local(p.name.name.clone(), ty, rate, declared, LocalKind::Var, p.name.span);
            // Created before the callee's frame is pushed, but the callee's own.
            self.locals[id.0 as usize].function = Some(f.name.name.clone());
            if let Some(arg) = arg {
                let arg_span = self.span_of(*arg);
                // A library function's string parameter is its argument (see `string_aliases`):
                // library code never stores into one.
                if library
                    && ty == Type::STRING
                    && self.ty(*arg) == Type::STRING
                    && p.qualifiers.output.is_none()
                    && matches!(self.expr_ref(*arg).kind, ExprKind::Literal(_) | ExprKind::Local(_))
                {
                    self.string_aliases.insert(id, *arg);
                    self.bind(&p.name, id);
                    continue;
                }
                if let Some(value) = self.coerce(*arg, ty, "the parameter") {
                    self.store(Place::Local(id), value, arg_span, &mut body);
                }
                if p.qualifiers.output.is_some() {
                    outputs.push((id, *arg));
                }
            }
            self.bind(&p.name, id);
        }
        self.frames.push(Frame {
            name: f.name.name.clone(),
            definition: f.name.span,
            result,
            ret,
            scope_base,
            outer,
            call_span,
            library,
            inferred: library || self.functions.stdlib_files.contains(&f.span.file),
            guarded_from: guarded,
        });
        let stmts = &f.body.stmts;
        // Functions defined in the body are the callee's, defined afresh at each call.
        let functions = self.local_functions.len();
        if self.enter_nested(call_span) {
            for s in stmts {
                self.stmt(s, &mut body);
            }
            self.nesting -= 1;
        }
        self.local_functions.truncate(functions);
        self.frames.pop();
        self.loops = saved_loops;
        self.no_effects = saved_no_effects;
        self.scopes.truncate(scope_base);
        if ret.base != Base::Void && !always_returns(stmts) {
            self.error(
                Diagnostic::error(
                    Code::InvalidReturn,
                    format!("function `{}` must return a `{ret}` on every path", f.name.name),
                    crate::source::Span { start: f.body.span.end.saturating_sub(1), ..f.body.span },
                    "the body can end here without `return`",
                )
                .with_label(f.return_type.span, format!("declared to return `{ret}`")),
            );
        }
        out.push(Stmt::Inline { function: f.name.name.clone(), body, span: call_span });
        for (local, arg) in outputs {
            if let Some(place) = self.place_of(arg) {
                let value = self.push_expr(
                    crate::ir::ExprKind::Local(local),
                    self.locals[local.0 as usize].ty,
                    call_span,
                );
                self.store(place, value, call_span, out);
            }
        }
        result
    }

    fn declared_rate_function_param(&mut self, q: &ast::Qualifiers) -> (Rate, bool) {
        // A function parameter without a rate takes the rate of its argument at each call.
        if q.rate.is_none() {
            return (Rate { perlight: q.perlight.is_some(), ..Rate::CONSTANT }, false);
        }
        self.declared_rate(q, false)
    }
}

/// Which light construct's arguments are checked.
#[derive(Copy, Clone, PartialEq, Eq)]
enum LightForm {
    Illuminance,
    Illuminate,
    Solar,
}
