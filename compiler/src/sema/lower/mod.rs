//! Lowering: the AST of one shader, with every function it calls inlined, to a typed IR body.
//!
//! Types are decided here; rates are decided afterwards by `sema::rates`, which needs the whole
//! body. Errors poison the expression they occur in (`None`), so one mistake gives one diagnostic.

mod call;
mod expr;
mod stmt;

use rustc_hash::{FxHashMap, FxHashSet};
use smol_str::SmolStr;

use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::ir::types::{Base, Frequency, Rate, Type};
use crate::ir::{Block, Expr, ExprId, ExprKind, Literal, Local, LocalId, LocalKind, Shader, Stmt};
use crate::source::Span;
use crate::syntax::ast::{self, ShaderKind, ShaderStyle};

use super::convert;

/// The functions a module defines, by name.
pub type FunctionTable<'a> = FxHashMap<SmolStr, Vec<&'a ast::FunctionDef>>;

/// The functions calls can reach: the file's own, and the standard library's implementations of
/// library built-ins (`compiler/stdlib/builtins.sl`), which only built-in calls and library code reach.
#[derive(Default)]
pub struct Functions<'a> {
    /// The file's top-level functions (and those of the files it includes).
    pub user: FunctionTable<'a>,
    /// The library built-ins' implementations and the library functions they call.
    pub library: FunctionTable<'a>,
    /// The files of the standard library (`<stdlib>/...`): their functions' variables are
    /// inferred in both styles.
    pub stdlib_files: FxHashSet<crate::source::FileId>,
}

/// What the statements being lowered are inside of.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum LightLoop {
    /// Not inside a light loop.
    None,
    /// Inside `illuminance` (surface shaders).
    Illuminance,
}

/// A function being inlined.
struct Frame {
    name: SmolStr,
    /// The definition's name, which identifies the function among its overloads.
    definition: Span,
    /// Where the callee's result goes, for non-void functions.
    result: Option<LocalId>,
    ret: Type,
    /// The scope depth where the callee's scopes start (it cannot see the caller's locals).
    scope_base: usize,
    /// For a function defined in a body, the scope depth of its definition: it sees the scopes
    /// below that (the body's variables), as nested functions do.
    outer: Option<usize>,
    call_span: Span,
    /// A library built-in's implementation (or a function it calls): its calls resolve in the
    /// library, never among the user's functions.
    library: bool,
    /// A standard-library function (or a library built-in's): its variables without a rate are
    /// inferred in both styles, so that it is as uniform as its arguments, like a built-in.
    inferred: bool,
    /// Called inside `?:`, `&&` or `||`: the first local of the call; the callee may assign only
    /// locals from there on (its own).
    guarded_from: Option<usize>,
}

/// What lowering keeps across the shaders and functions of one module.
#[derive(Default)]
pub(super) struct Shared {
    /// Diagnostics already reported: a function's body is lowered at every call.
    reported: FxHashSet<(Code, Span, String)>,
    /// The functions inlined somewhere (the others are checked on their own).
    pub(super) inlined: FxHashSet<Span>,
    /// Whether a library built-in was called while no library was loaded: the caller loads it
    /// and checks again.
    pub(super) wants_library: bool,
}

/// The state of lowering one shader.
pub(super) struct Lowerer<'a> {
    diags: &'a mut Diagnostics,
    shared: &'a mut Shared,
    /// Whether an error was found in this shader (reported here or before).
    failed: bool,
    /// Checking a function on its own, not inlined into a shader.
    standalone: bool,
    functions: &'a Functions<'a>,
    kind: ShaderKind,
    stanford: bool,
    locals: Vec<Local>,
    exprs: Vec<Expr>,
    /// Name scopes, innermost last; scope 0 holds module-level variables.
    scopes: Vec<FxHashMap<SmolStr, LocalId>>,
    /// Functions defined in the bodies being lowered, with the scope depth of their definition.
    local_functions: Vec<(usize, std::rc::Rc<ast::FunctionDef>)>,
    frames: Vec<Frame>,
    loops: u32,
    light_loop: LightLoop,
    /// Inside an operand of `?:`, `&&` or `||`, where effects are not allowed.
    no_effects: u32,
    result_local: Option<LocalId>,
    result_type: Type,
    /// Whether the shader's size limit (`call::MAX_SHADER_EXPRESSIONS`) has been reported.
    inline_limit_reported: bool,
    /// How deep the statement being lowered is nested, inlined calls included.
    nesting: usize,
    /// Whether `call::MAX_INLINED_NESTING` has been reported.
    nesting_reported: bool,
    /// Whether the expression being lowered is stored in a variable declared uniform: `random()`
    /// there is one value per draw (`__uniform_random`), as in RSL.
    uniform_random: bool,
    /// The string parameters of library functions that read their argument itself (a literal or
    /// a variable) rather than a copy: the backends know a string only through literals and
    /// shader parameters, so a space name passed to a library built-in must stay one of those
    /// (and a literal one decides the library's `if`s here).
    string_aliases: FxHashMap<LocalId, ExprId>,
}

/// Lowers one shader, and says whether it had errors (they have been reported): the parts with
/// errors are then left out of its body.
pub(super) fn lower_shader(
    shader: &ast::ShaderDef,
    globals: &[&ast::VarDecl],
    functions: &Functions<'_>,
    shared: &mut Shared,
    diags: &mut Diagnostics,
) -> (Shader, bool) {
    let (stanford, result_type) = match &shader.style {
        ShaderStyle::RenderMan => (false, Type::VOID),
        ShaderStyle::Stanford { return_type } => (true, Type::of(Base::from_ast(return_type.name))),
    };
    let mut l = Lowerer::new(diags, shared, functions, shader.kind, stanford, result_type);
    let mut body = Vec::new();
    for decl in globals {
        l.declaration(decl, &mut body);
    }
    l.scopes.push(FxHashMap::default());
    let params = l.params(&shader.params, &mut body);
    if stanford {
        let result = l.new_local(
            "result".into(),
            result_type,
            Rate::CONSTANT,
            false,
            LocalKind::Temp,
            shader.name.span,
        );
        l.result_local = Some(result);
    }
    l.block(&shader.body.stmts, &mut body);
    if stanford && !stmt::always_returns(&shader.body.stmts) {
        l.error(
            Diagnostic::error(
                Code::InvalidReturn,
                format!("shader `{}` must return a `{}`", shader.name.name, result_type),
                Span { start: shader.body.span.end.saturating_sub(1), ..shader.body.span },
                "the body can end here without `return`",
            )
            .with_label(shader.name.span, format!("declared to return `{result_type}`")),
        );
    }
    let failed = l.failed;
    let lowered = Shader {
        name: shader.name.name.clone(),
        kind: shader.kind,
        stanford,
        result: result_type,
        result_local: l.result_local,
        params,
        locals: l.locals,
        exprs: l.exprs,
        body,
        span: shader.span,
    };
    (lowered, failed)
}

/// Checks a function's body on its own, for functions no shader calls (their errors would
/// otherwise go unreported). It sees the file's variables, as it would inlined into a shader
/// (errors in their declarations are reported once, however many times they are declared).
pub(super) fn check_function(
    f: &ast::FunctionDef,
    stanford: bool,
    globals: &[&ast::VarDecl],
    functions: &Functions<'_>,
    shared: &mut Shared,
    diags: &mut Diagnostics,
) {
    // Only Stanford style prefixes functions with a shader kind.
    let stanford = stanford || f.context.is_some();
    let kind = f.context.map_or(ShaderKind::Surface, |c| c.0);
    let mut l = Lowerer::new(diags, shared, functions, kind, stanford, Type::VOID);
    let mut body = Vec::new();
    for decl in globals {
        l.declaration(decl, &mut body);
    }
    let args: Vec<Option<ExprId>> = f
        .params
        .iter()
        .map(|p| {
            let ty = stmt::declared_type(p.ty, p.array.as_ref());
            // An output parameter needs a variable to write to.
            let value = if p.qualifiers.output.is_some() {
                let (rate, declared) = (Rate::CONSTANT, false);
                let local = l.new_local(p.name.name.clone(), ty, rate, declared, LocalKind::Temp, p.span);
                ExprKind::Local(local)
            } else {
                ExprKind::Literal(Literal::Float(0.0))
            };
            Some(l.push_expr(value, ty, p.span))
        })
        .collect();
    l.standalone = true;
    l.inline_body(f, &args, f.span, None, false, &mut body);
}

impl<'a> Lowerer<'a> {
    fn new(
        diags: &'a mut Diagnostics,
        shared: &'a mut Shared,
        functions: &'a Functions<'a>,
        kind: ShaderKind,
        stanford: bool,
        result_type: Type,
    ) -> Lowerer<'a> {
        Lowerer {
            diags,
            shared,
            failed: false,
            standalone: false,
            functions,
            kind,
            stanford,
            locals: Vec::new(),
            exprs: Vec::new(),
            scopes: vec![FxHashMap::default()],
            local_functions: Vec::new(),
            frames: Vec::new(),
            loops: 0,
            light_loop: LightLoop::None,
            no_effects: 0,
            result_local: None,
            result_type,
            inline_limit_reported: false,
            nesting: 0,
            nesting_reported: false,
            uniform_random: false,
            string_aliases: FxHashMap::default(),
        }
    }
}

impl Lowerer<'_> {
    /// Whether the code being lowered is a library built-in's (`compiler/stdlib/builtins.sl`).
    fn in_library(&self) -> bool {
        self.frames.last().is_some_and(|f| f.library)
    }

    /// The value of a condition made of comparisons of literal strings (with `&&`, `||` and `!`),
    /// if it is one: a space name given as a literal to a library built-in.
    fn decided(&self, id: ExprId) -> Option<bool> {
        use crate::ir::{BinaryOp, UnaryOp};
        match &self.expr_ref(id).kind {
            ExprKind::Literal(Literal::Bool(b)) => Some(*b),
            ExprKind::Binary(op @ (BinaryOp::Eq | BinaryOp::Ne), a, b) => {
                match (&self.expr_ref(*a).kind, &self.expr_ref(*b).kind) {
                    (ExprKind::Literal(Literal::String(x)), ExprKind::Literal(Literal::String(y))) => {
                        Some((x == y) == (*op == BinaryOp::Eq))
                    }
                    _ => None,
                }
            }
            ExprKind::Binary(BinaryOp::And, a, b) => match (self.decided(*a), self.decided(*b)) {
                (Some(false), _) | (_, Some(false)) => Some(false),
                (Some(true), Some(true)) => Some(true),
                _ => None,
            },
            ExprKind::Binary(BinaryOp::Or, a, b) => match (self.decided(*a), self.decided(*b)) {
                (Some(true), _) | (_, Some(true)) => Some(true),
                (Some(false), Some(false)) => Some(false),
                _ => None,
            },
            ExprKind::Unary(UnaryOp::Not, a) => self.decided(*a).map(|b| !b),
            _ => None,
        }
    }

    /// Reports a diagnostic once (an inlined function's body is lowered at every call).
    fn error(&mut self, d: Diagnostic) {
        self.failed |= d.is_error();
        let key = (d.code, d.primary_span(), d.message.clone());
        if self.shared.reported.insert(key) {
            let d = match self.frames.last() {
                Some(frame) if !self.standalone && !d.labels.iter().any(|l| l.span == frame.call_span) => {
                    let call = frame.call_span;
                    let name = frame.name.clone();
                    d.with_label(call, format!("in this call of `{name}`"))
                }
                _ => d,
            };
            self.diags.push(d);
        }
    }

    fn push_expr(&mut self, kind: ExprKind, ty: Type, span: Span) -> ExprId {
        let id = ExprId(self.exprs.len() as u32);
        self.exprs.push(Expr { kind, ty, rate: Rate::CONSTANT, span });
        id
    }

    fn expr_ref(&self, id: ExprId) -> &Expr {
        &self.exprs[id.0 as usize]
    }

    fn ty(&self, id: ExprId) -> Type {
        self.exprs[id.0 as usize].ty
    }

    fn span_of(&self, id: ExprId) -> Span {
        self.exprs[id.0 as usize].span
    }

    fn new_local(
        &mut self,
        name: SmolStr,
        ty: Type,
        rate: Rate,
        declared: bool,
        kind: LocalKind,
        span: Span,
    ) -> LocalId {
        let id = LocalId(self.locals.len() as u32);
        let function = self.frames.last().map(|f| f.name.clone());
        self.locals.push(Local { name, ty, rate, declared, kind, span, function });
        id
    }

    /// Binds `name` in the innermost scope, reporting a redefinition in the same scope.
    fn bind(&mut self, name: &ast::Ident, id: LocalId) {
        let scope = self.scopes.last_mut().expect("a scope is open");
        if let Some(&previous) = scope.get(&name.name) {
            let previous_span = self.locals[previous.0 as usize].span;
            self.error(
                Diagnostic::error(
                    Code::Redefinition,
                    format!("`{}` is declared twice in the same scope", name.name),
                    name.span,
                    "declared again here",
                )
                .with_label(previous_span, "first declared here"),
            );
            return;
        }
        scope.insert(name.name.clone(), id);
    }

    /// The local a name refers to: this function's scopes, then the module's.
    fn lookup_local(&self, name: &str) -> Option<LocalId> {
        let (base, outer) = self.frames.last().map_or((0, None), |f| (f.scope_base, f.outer));
        let own = &self.scopes[base.max(1).min(self.scopes.len())..];
        let enclosing =
            outer.map_or(&self.scopes[..0], |depth| &self.scopes[1..depth.min(self.scopes.len())]);
        own.iter()
            .rev()
            .chain(enclosing.iter().rev())
            .chain(self.scopes[..1].iter())
            .find_map(|s| s.get(name).copied())
    }

    /// Converts `id` to `to` implicitly, reporting a mismatch at `id`'s span; `what` names the
    /// destination for the message.
    fn coerce(&mut self, id: ExprId, to: Type, what: &str) -> Option<ExprId> {
        let from = self.ty(id);
        if from == to {
            return Some(id);
        }
        if convert::implicit_cost(from, to).is_some() {
            return Some(self.convert(id, to));
        }
        let span = self.span_of(id);
        let mut d = Diagnostic::error(
            Code::TypeMismatch,
            format!("expected `{to}`, found `{from}`"),
            span,
            format!("this is `{from}`, {what} is `{to}`"),
        );
        if convert::explicit_ok(from, to) {
            d = d.with_help(format!("convert it explicitly: `{} (...)`", to.base.name()));
        } else if from.base == Base::Float4 && to.base.is_triple() {
            d = d.with_help("take the first three components with `rgb(...)`");
        }
        self.error(d);
        None
    }

    /// A conversion node (or a converted literal, so that `Kd = 1` stores a float).
    fn convert(&mut self, id: ExprId, to: Type) -> ExprId {
        let span = self.span_of(id);
        if let ExprKind::Literal(lit) = &self.expr_ref(id).kind {
            let value = match lit {
                Literal::Int(v) => Some(f64::from(*v)),
                Literal::Uint(v) => Some(f64::from(*v)),
                _ => None,
            };
            if let (Some(v), true) = (value, to.base.is_float_scalar()) {
                return self.push_expr(ExprKind::Literal(Literal::Float(v)), to, span);
            }
        }
        self.push_expr(ExprKind::Convert(id), to, span)
    }

    /// Turns a scalar condition into a `bool` (`x` means `x != 0`).
    fn condition(&mut self, id: ExprId) -> Option<ExprId> {
        let ty = self.ty(id);
        match ty.base {
            Base::Bool if ty.array.is_none() => Some(id),
            Base::Float | Base::Clampf | Base::Int | Base::Uint if ty.array.is_none() => {
                let span = self.span_of(id);
                let zero = match ty.base {
                    Base::Int => Literal::Int(0),
                    Base::Uint => Literal::Uint(0),
                    _ => Literal::Float(0.0),
                };
                let zero = self.push_expr(ExprKind::Literal(zero), ty, span);
                Some(self.push_expr(ExprKind::Binary(crate::ir::BinaryOp::Ne, id, zero), Type::BOOL, span))
            }
            _ => {
                let span = self.span_of(id);
                self.error(Diagnostic::error(
                    Code::TypeMismatch,
                    format!("a condition must be `bool` or a number, found `{ty}`"),
                    span,
                    "not a truth value",
                ));
                None
            }
        }
    }

    /// Emits a store statement.
    fn store(&mut self, place: crate::ir::Place, value: ExprId, span: Span, out: &mut Block) {
        out.push(Stmt::Store { place, value, span });
    }

    /// The rate a declaration's qualifiers give, and whether it is a contract.
    fn declared_rate(&mut self, q: &ast::Qualifiers, is_param: bool) -> (Rate, bool) {
        let perlight = q.perlight.is_some();
        if perlight && !self.stanford && q.perlight.is_some() {
            // RenderMan style has no `perlight` qualifier: per-light values live in illuminance.
            let span = q.perlight.unwrap_or_default();
            self.error(
                Diagnostic::error(
                    Code::InvalidQualifier,
                    "`perlight` belongs to Stanford-style shaders",
                    span,
                    "not available in a RenderMan-style shader",
                )
                .with_help("compute per-light values inside `illuminance (...) { ... }`"),
            );
        }
        let frequency = match q.rate.map(|r| r.0) {
            Some(ast::RateQualifier::Constant) => Some(Frequency::Constant),
            Some(ast::RateQualifier::Uniform | ast::RateQualifier::PrimitiveGroup) => {
                Some(Frequency::PrimitiveGroup)
            }
            Some(ast::RateQualifier::Vertex) => Some(Frequency::Vertex),
            Some(ast::RateQualifier::Fragment) => Some(Frequency::Fragment),
            // RenderMan: varying input parameters are per-vertex primitive variables; varying
            // variables and outputs are computed per shading point, i.e. per fragment.
            Some(ast::RateQualifier::Varying) => {
                Some(if is_param && q.output.is_none() { Frequency::Vertex } else { Frequency::Fragment })
            }
            // Standard-library variables are inferred in both styles, so that a library
            // function (a built-in written in the language too) keeps a built-in's rate: that
            // of its arguments.
            None if self.stanford || self.frames.last().is_some_and(|f| f.inferred) => {
                if is_param {
                    Some(Frequency::PrimitiveGroup)
                } else {
                    None
                }
            }
            // RenderMan defaults: parameters are uniform, variables varying.
            None => Some(if is_param { Frequency::PrimitiveGroup } else { Frequency::Fragment }),
        };
        // `perlight` alone fixes the per-light part; the frequency is still inferred.
        match frequency {
            Some(frequency) => (Rate { frequency, perlight }, true),
            None => (Rate { frequency: Frequency::Constant, perlight }, false),
        }
    }
}
