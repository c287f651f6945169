//! Calls: overload resolution over user functions and built-ins, and inlining of user functions.
//!
//! Candidates are ranked by the summed cost of their argument conversions. A tie is broken by the
//! type the context expects (RenderMan's `color noise(P)` chooses by result type), then in favour
//! of a `float` result (RenderMan's default for `noise`).

use super::Lowerer;
use super::expr::suggest;
use super::stmt::declared_type;
use crate::diag::{Code, Diagnostic};
use crate::ir::builtin::BuiltinId;
use crate::ir::builtin::{Builtin, Context};
use crate::ir::types::{Base, Type};
use crate::ir::{Block, ExprId, ExprKind};
use crate::sema::builtins;
use crate::sema::convert;
use crate::source::Span;
use crate::syntax::ast;

/// Calls nested deeper than this (a function calling a function calling ...) are refused: every
/// call is inlined, and later stages take time that grows faster than linearly with the depth.
pub const MAX_INLINE_DEPTH: usize = 64;

/// A shader whose body, with every call inlined, has more expressions than this is refused. The
/// largest example shader (`noise_panel`) has about 30 000; a function calling another twice,
/// thirty levels deep, would have 2^30 copies of the innermost one and stops here instead.
pub const MAX_SHADER_EXPRESSIONS: usize = 500_000;

/// Statements nested deeper than this in a shader with its calls inlined are refused: each source
/// function keeps under the syntax's nesting limit, but a call inside nested statements nests the
/// callee's statements deeper still, and later stages take time that grows faster than linearly
/// with the depth. An `else if` chain does not count (its length has its own limit).
pub const MAX_INLINED_NESTING: usize = 512;

/// A function that could be called: a user function or a built-in overload.
#[derive(Copy, Clone)]
enum Candidate<'a> {
    User(&'a ast::FunctionDef),
    Builtin(&'static Builtin),
}

impl Candidate<'_> {
    fn ret(&self) -> Type {
        match self {
            Candidate::User(f) => declared_type(f.return_type, None),
            Candidate::Builtin(b) => b.ret,
        }
    }

    fn accepts_count(&self, n: usize) -> bool {
        match self {
            Candidate::User(f) => f.params.len() == n,
            Candidate::Builtin(b) => b.accepts_count(n),
        }
    }

    /// The type of parameter `i` and whether it is an output.
    fn param(&self, i: usize) -> Option<(Type, bool)> {
        match self {
            Candidate::User(f) => f
                .params
                .get(i)
                .map(|p| (declared_type(p.ty, p.array.as_ref()), p.qualifiers.output.is_some())),
            Candidate::Builtin(b) => b.param_type(i).map(|p| (p.ty, p.output)),
        }
    }

    fn signature(&self) -> String {
        match self {
            Candidate::User(f) => {
                let params: Vec<String> = f
                    .params
                    .iter()
                    .map(|p| format!("{} {}", declared_type(p.ty, p.array.as_ref()), p.name.name))
                    .collect();
                format!("{} {}({})", declared_type(f.return_type, None), f.name.name, params.join(", "))
            }
            Candidate::Builtin(b) => b.signature.clone(),
        }
    }

    /// The total cost of passing arguments of types `args`, or `None` if they do not fit.
    fn cost(&self, args: &[Type]) -> Option<u32> {
        if !self.accepts_count(args.len()) {
            return None;
        }
        let mut total = 0;
        for (i, arg) in args.iter().enumerate() {
            let (param, output) = self.param(i)?;
            total += if output {
                (*arg == param || (param.array == Some(0) && arg.base == param.base)).then_some(0)?
            } else {
                convert::implicit_cost(*arg, param)?
            };
        }
        Some(total)
    }
}

impl Lowerer<'_> {
    pub(super) fn call(
        &mut self,
        callee: &ast::Ident,
        args: &[ast::Expr],
        expected: Option<Type>,
        span: Span,
        out: &mut Block,
    ) -> Option<ExprId> {
        // Library code calls library functions and built-ins only, whatever the user defines.
        let in_library = self.in_library();
        let functions = if in_library { &self.functions.library } else { &self.functions.user };
        // Functions defined in enclosing bodies come first, then the file's, then the built-ins.
        let locals: Vec<(usize, std::rc::Rc<ast::FunctionDef>)> = if in_library {
            Vec::new()
        } else {
            self.local_functions.iter().filter(|(_, f)| f.name.name == callee.name).cloned().collect()
        };
        let user: Vec<Candidate<'_>> = if locals.is_empty() {
            functions
                .get(&callee.name)
                .map_or(Vec::new(), |fs| fs.iter().map(|f| Candidate::User(f)).collect())
        } else {
            locals.iter().map(|(_, f)| Candidate::User(f)).collect()
        };
        let builtin_call = user.is_empty();
        // A texture lookup's optional `"name", value` arguments start at the first string literal
        // after the file name; the overload is chosen by the arguments before them.
        let builtin_id = if builtin_call { BuiltinId::from_name(&callee.name) } else { None };
        let (args, option_args) = match builtin_id.and_then(builtins::options) {
            Some(_) => {
                let at = args
                    .iter()
                    .skip(1)
                    .position(|a| matches!(a.kind, ast::ExprKind::String(_)))
                    .map_or(args.len(), |i| i + 1);
                args.split_at(at)
            }
            _ => (args, &[][..]),
        };
        if matches!(builtin_id, Some(BuiltinId::Printf | BuiltinId::Format)) {
            return self.printf_call(callee, args, span, out);
        }
        let candidates: Vec<Candidate<'_>> = if builtin_call {
            builtins::builtins().overloads(&callee.name).iter().map(Candidate::Builtin).collect()
        } else {
            user
        };
        if candidates.is_empty() && callee.name == "option" {
            return self.option_call(args, span, out);
        }
        if candidates.is_empty() && callee.name == "bake" {
            return self.bake_call(callee, args, span, out);
        }
        if candidates.is_empty()
            && let Some(d) = crate::sema::unsupported::call(callee)
        {
            self.error(d);
            return None;
        }
        if candidates.is_empty() {
            let known: Vec<String> = functions
                .keys()
                .map(|k| k.to_string())
                .chain(builtins::builtins().names().map(String::from))
                .collect();
            let close = suggest(&callee.name, known.iter().map(String::as_str)).map(str::to_string);
            let mut d = Diagnostic::error(
                Code::UnknownFunction,
                format!("cannot find function `{}`", callee.name),
                callee.span,
                "not a built-in or a function of this file",
            );
            if let Some(close) = close {
                d = d.with_help(format!("a function with a similar name exists: `{close}`"));
            }
            self.error(d);
            return None;
        }
        // Tuples take their type from the parameter when every candidate agrees on it.
        let mut lowered = Vec::with_capacity(args.len());
        for (i, a) in args.iter().enumerate() {
            let hint = match &a.kind {
                ast::ExprKind::Tuple(_) => {
                    let types: Vec<Type> =
                        candidates.iter().filter_map(|c| c.param(i).map(|p| p.0)).collect();
                    types.first().copied().filter(|t| types.iter().all(|x| x == t))
                }
                _ => None,
            };
            lowered.push(self.expr(a, hint, out));
        }
        let lowered: Vec<ExprId> = lowered.into_iter().collect::<Option<_>>()?;
        let types: Vec<Type> = lowered.iter().map(|&a| self.ty(a)).collect();
        let message = matches!(builtin_id, Some(BuiltinId::LightSource | BuiltinId::Surface));
        if message && types.get(1).is_some_and(|t| t.base == Base::String) {
            let help = if builtin_id == Some(BuiltinId::LightSource) {
                "select lights by category with `illuminance(\"category\", ...)`: a light's `__category` parameter names its categories"
            } else {
                "pass the string to this shader as a parameter of its own"
            };
            self.error(
                Diagnostic::error(
                    Code::MessagePassing,
                    format!("`{}` cannot read a string parameter", callee.name),
                    args[1].span,
                    "a string variable",
                )
                .with_note("strings are compile-time values, and this one would differ from shader to shader")
                .with_help(help),
            );
            return None;
        }
        let chosen = self.resolve(callee, &candidates, &types, expected, span)?;
        match chosen {
            Candidate::User(f) => {
                // The same definition, not just the same name: overloads may call each other.
                if self.frames.iter().any(|frame| frame.definition == f.name.span) {
                    self.error(
                        Diagnostic::error(
                            Code::Recursion,
                            format!("function `{}` calls itself", f.name.name),
                            callee.span,
                            "recursive call",
                        )
                        .with_label(f.name.span, "defined here")
                        .with_note("functions are inlined into shaders, so they cannot recurse; use a loop"),
                    );
                    return None;
                }
                let args: Vec<Option<ExprId>> = lowered.into_iter().map(Some).collect();
                let outer = locals.iter().find(|(_, g)| std::ptr::eq(&**g, f)).map(|(depth, _)| *depth);
                self.inline_call(f, &args, span, outer, in_library, out)
            }
            Candidate::Builtin(b) => {
                if matches!(b.id, BuiltinId::LightSource | BuiltinId::Surface)
                    && !matches!(args[0].kind, ast::ExprKind::String(_))
                {
                    self.error(Diagnostic::error(
                        Code::TypeMismatch,
                        format!("`{}` needs the parameter's name as a string literal", b.id),
                        args[0].span,
                        "not a string literal",
                    ));
                    return None;
                }
                match b.context {
                    Context::Surface if self.kind != ast::ShaderKind::Surface => {
                        return self.wrong_kind(callee, "surface");
                    }
                    Context::Light if self.kind != ast::ShaderKind::Light => {
                        return self.wrong_kind(callee, "light");
                    }
                    Context::LightOrVolume
                        if !matches!(self.kind, ast::ShaderKind::Light | ast::ShaderKind::Volume) =>
                    {
                        return self.wrong_kind(callee, "light or volume");
                    }
                    Context::Illuminance if self.light_loop != super::LightLoop::Illuminance => {
                        self.error(
                            Diagnostic::error(
                                Code::OutsideLightLoop,
                                format!("`{}` exists only inside `illuminance`", b.id),
                                callee.span,
                                "it reads a parameter of the light being visited",
                            )
                            .with_help("move this into an `illuminance` block"),
                        );
                        return None;
                    }
                    _ => {}
                }
                let mut converted = Vec::with_capacity(lowered.len());
                for (i, &arg) in lowered.iter().enumerate() {
                    let (param, output) = chosen.param(i).expect("resolution checked the count");
                    if output {
                        self.place_of(arg)?;
                        converted.push(arg);
                    } else if param.array == Some(0) {
                        converted.push(arg);
                    } else {
                        converted.push(self.coerce(arg, param, "the parameter")?);
                    }
                }
                if !option_args.is_empty() {
                    self.lookup_options(callee, b, option_args, &mut converted, out)?;
                }
                // Space names given as literals are checked here; others are known per draw.
                if matches!(
                    b.id,
                    BuiltinId::Transform
                        | BuiltinId::VTransform
                        | BuiltinId::NTransform
                        | BuiltinId::CTransform
                ) {
                    let colour = b.id == BuiltinId::CTransform;
                    let literals: Vec<(smol_str::SmolStr, Span)> = converted
                        .iter()
                        .filter_map(|&a| match &self.expr_ref(a).kind {
                            ExprKind::Literal(crate::ir::Literal::String(name)) => {
                                Some((name.clone(), self.span_of(a)))
                            }
                            _ => None,
                        })
                        .collect();
                    for (name, at) in literals {
                        if !self.known_space(&name, at, colour) {
                            return None;
                        }
                    }
                }
                // `faceforward(N, I)` compares with the geometric normal: make that argument
                // explicit, so that rates, derivatives and the library's code see it (where the
                // shader has no `Ng`, the library's two-argument form compares with N itself).
                let mut b = b;
                if b.id == BuiltinId::FaceForward
                    && converted.len() == 2
                    && let Some(ng) = crate::sema::globals::lookup("Ng", self.kind, self.stanford)
                {
                    let ng_expr = self.push_expr(ExprKind::Global(ng), Type::of(ng.ty), span);
                    let ng_expr = self.coerce(ng_expr, b.ret, "the reference normal")?;
                    let types = [b.ret, Type::of(crate::ir::types::Base::Vector), b.ret];
                    if let Some(three) = crate::sema::builtins::find(BuiltinId::FaceForward, &types) {
                        converted.push(ng_expr);
                        b = three;
                    }
                }
                if crate::stdlib::LIBRARY_BUILTINS.contains(&b.id) {
                    return self.library_builtin(b, converted, span, out);
                }
                // A literal space name was checked where the library built-in was called.
                if b.id == BuiltinId::ColourSpace
                    && matches!(self.expr_ref(converted[0]).kind, ExprKind::Literal(_))
                {
                    return Some(self.push_expr(ExprKind::Construct(Vec::new()), Type::VOID, span));
                }
                if b.id == BuiltinId::Random
                    && self.uniform_random
                    && let Some(u) = builtins::builtins()
                        .overloads(BuiltinId::UniformRandom.name())
                        .iter()
                        .find(|u| u.ret == b.ret)
                {
                    return Some(self.push_expr(ExprKind::Builtin(u, converted), u.ret, span));
                }
                Some(self.push_expr(ExprKind::Builtin(b, converted), b.ret, span))
            }
        }
    }

    /// `float option(string name, output T value)` (RI 3.2 section 15.8): 1 with `value` written
    /// for the options a render answers, 0 (with a warning) for any other name. `"Format"` writes
    /// the image's width, height and pixel aspect ratio (1) to a `float[3]`, read per draw from the
    /// raster space (so a resize recompiles nothing); `"Exposure"` writes gain and gamma, 1 and 1,
    /// to a `float[2]`.
    fn option_call(&mut self, args: &[ast::Expr], span: Span, out: &mut Block) -> Option<ExprId> {
        use crate::ir::{Literal, Place};
        let [name, target] = args else {
            self.error(Diagnostic::error(
                Code::NoMatchingOverload,
                format!("`option` takes 2 arguments, found {}", args.len()),
                span,
                "expected `option(\"name\", variable)`",
            ));
            return None;
        };
        let ast::ExprKind::String(option) = &name.kind else {
            self.error(Diagnostic::error(
                Code::TypeMismatch,
                "`option` needs the option's name as a string literal",
                name.span,
                "not a string literal",
            ));
            return None;
        };
        let float =
            |this: &mut Self, x: f64| this.push_expr(ExprKind::Literal(Literal::Float(x)), Type::FLOAT, span);
        if !matches!(option.as_str(), "Format" | "Exposure") {
            // Checked as a variable, in code of its own: nothing reads or writes it.
            let mut scratch = Block::default();
            let t = self.expr(target, None, &mut scratch)?;
            self.place_of(t)?;
            self.error(
                Diagnostic::warning(
                    Code::RendererQuery,
                    format!("`option` does not know `{option}`: it returns 0 and leaves the variable as it is"),
                    name.span,
                    "unknown option",
                )
                .with_note("the options answered are \"Format\" (float[3]: width, height, pixel aspect) and \"Exposure\" (float[2]: gain, gamma)"),
            );
            return Some(float(self, 0.0));
        }
        let t = self.expr(target, None, out)?;
        let place = self.place_of(t)?;
        let ty = self.ty(t);
        let (values, want): (Vec<ExprId>, &str) = match option.as_str() {
            "Format" => {
                let s = |this: &mut Self, text: &str| {
                    this.push_expr(ExprKind::Literal(Literal::String(text.into())), Type::STRING, span)
                };
                let (ndc, raster) = (s(self, "NDC"), s(self, "raster"));
                let (one, zero) = (float(self, 1.0), float(self, 0.0));
                let point = Type::of(Base::Point);
                let corner = self.push_expr(ExprKind::Construct(vec![one, one, zero]), point, span);
                let transform = builtins::find(BuiltinId::Transform, &[Type::STRING, Type::STRING, point])?;
                let size =
                    self.push_expr(ExprKind::Builtin(transform, vec![ndc, raster, corner]), point, span);
                let mut values = Vec::new();
                for axis in [BuiltinId::XComp, BuiltinId::YComp] {
                    let comp = builtins::find(axis, &[point])?;
                    let c = self.push_expr(ExprKind::Builtin(comp, vec![size]), Type::FLOAT, span);
                    let round = builtins::find(BuiltinId::Round, &[Type::FLOAT])?;
                    values.push(self.push_expr(ExprKind::Builtin(round, vec![c]), Type::FLOAT, span));
                }
                values.push(float(self, 1.0));
                (values, "float[3]")
            }
            // "Exposure": gain and gamma.
            _ => (vec![float(self, 1.0), float(self, 1.0)], "float[2]"),
        };
        if ty.base != Base::Float || ty.array != Some(values.len() as u32) {
            self.error(Diagnostic::error(
                Code::TypeMismatch,
                format!("option `{option}` is a `{want}`, found `{ty}`"),
                target.span,
                format!("expected a `{want}` variable"),
            ));
            return None;
        }
        for (i, value) in values.into_iter().enumerate() {
            let index = self.push_expr(ExprKind::Literal(Literal::Int(i as i32)), Type::of(Base::Int), span);
            self.store(Place::Index(Box::new(place.clone()), index), value, span, out);
        }
        Some(float(self, 1.0))
    }

    /// `void printf(string format, ...)` and `string format(string format, ...)` (RI 3.2 section
    /// 15.9): the values are checked against a literal format's conversions. `printf` prints in the
    /// CPU interpreter and is left out by the GPU backend (warned here); `format` is a string, and
    /// strings are compile-time values, so its values must be literals.
    fn printf_call(
        &mut self,
        callee: &ast::Ident,
        args: &[ast::Expr],
        span: Span,
        out: &mut Block,
    ) -> Option<ExprId> {
        use crate::ir::Literal;
        let name = callee.name.as_str();
        let lowered: Vec<ExprId> = args.iter().map(|a| self.expr(a, None, out)).collect::<Option<_>>()?;
        let Some((&format, values)) = lowered.split_first() else {
            self.error(Diagnostic::error(
                Code::NoMatchingOverload,
                format!("`{name}` needs a format string"),
                span,
                format!("expected `{name}(\"...\", values)`"),
            ));
            return None;
        };
        self.coerce(format, Type::STRING, "the format")?;
        let literal = match &self.expr_ref(format).kind {
            ExprKind::Literal(Literal::String(text)) => Some(text.to_string()),
            _ => None,
        };
        if let Some(text) = &literal {
            let conversions = builtins::printf_conversions(text);
            if conversions.len() != values.len() {
                self.error(
                    Diagnostic::error(
                        Code::NoMatchingOverload,
                        format!(
                            "the format has {} conversion{}, and {} value{} follow it",
                            conversions.len(),
                            if conversions.len() == 1 { "" } else { "s" },
                            values.len(),
                            if values.len() == 1 { "" } else { "s" }
                        ),
                        span,
                        "one value per `%` conversion",
                    )
                    .with_label(self.span_of(format), "the format"),
                );
                return None;
            }
            for (&c, &v) in conversions.iter().zip(values) {
                let ty = self.ty(v);
                let (fits, what) = match c {
                    'f' | 'g' | 'e' | 'd' | 'i' => {
                        (matches!(ty.base, Base::Float | Base::Int | Base::Uint | Base::Bool), "a number")
                    }
                    'p' | 'v' | 'n' => (
                        matches!(ty.base, Base::Point | Base::Vector | Base::Normal),
                        "a point, vector or normal",
                    ),
                    'c' => (ty.base == Base::Color, "a colour"),
                    'm' => (matches!(ty.base, Base::Matrix4 | Base::Matrix3), "a matrix"),
                    's' => (ty.base == Base::String, "a string"),
                    other => {
                        self.error(
                            Diagnostic::error(
                                Code::TypeMismatch,
                                format!("`%{other}` is not a conversion of `{name}`"),
                                self.span_of(format),
                                "in this format",
                            )
                            .with_help("the conversions are %f %g %e %d (numbers), %p %v %n (points), %c (colours), %m (matrices), %s (strings) and %%"),
                        );
                        return None;
                    }
                };
                if !fits || ty.is_array() {
                    self.error(Diagnostic::error(
                        Code::TypeMismatch,
                        format!("`%{c}` prints {what}, found `{ty}`"),
                        self.span_of(v),
                        format!("this is `{ty}`"),
                    ));
                    return None;
                }
            }
        }
        let b = builtins::builtins().overloads(name).first()?;
        if b.id == BuiltinId::Printf {
            self.error(
                Diagnostic::warning(
                    Code::IgnoredFeature,
                    "`printf` prints only when the shader runs in the CPU interpreter",
                    callee.span,
                    "left out of GPU code",
                )
                .with_note("a GPU has no console: the WGSL backend leaves the call out; `patina eval` and CPU renders print it to stderr"),
            );
            return Some(self.push_expr(ExprKind::Builtin(b, lowered), Type::VOID, span));
        }
        // `format`: known now, or not at all.
        let mut printed = Vec::with_capacity(values.len());
        for &v in values {
            let value = match &self.expr_ref(v).kind {
                ExprKind::Literal(Literal::Float(x)) => builtins::PrintValue::Numbers(vec![*x]),
                ExprKind::Literal(Literal::Int(x)) => builtins::PrintValue::Numbers(vec![f64::from(*x)]),
                ExprKind::Literal(Literal::Uint(x)) => builtins::PrintValue::Numbers(vec![f64::from(*x)]),
                ExprKind::Literal(Literal::Bool(x)) => {
                    builtins::PrintValue::Numbers(vec![f64::from(u8::from(*x))])
                }
                ExprKind::Literal(Literal::String(s)) => builtins::PrintValue::Text(s.to_string()),
                _ => {
                    self.error(
                        Diagnostic::error(
                            Code::TypeMismatch,
                            "`format` needs values known when the shader is compiled",
                            self.span_of(v),
                            "not a literal",
                        )
                        .with_note(
                            "strings are compile-time values in Patina, so a formatted string must be too",
                        ),
                    );
                    return None;
                }
            };
            printed.push(value);
        }
        let Some(text) = literal else {
            self.error(Diagnostic::error(
                Code::TypeMismatch,
                "`format` needs a literal format string",
                self.span_of(format),
                "not a literal",
            ));
            return None;
        };
        let result = builtins::printf_format(&text, &printed);
        Some(self.push_expr(ExprKind::Literal(Literal::String(result.into())), Type::STRING, span))
    }

    /// `void bake(string file, float s, float t, T value)` (PRMan): its arguments are checked, and
    /// the call does nothing on either backend, with a warning (bake files are not written).
    fn bake_call(
        &mut self,
        callee: &ast::Ident,
        args: &[ast::Expr],
        span: Span,
        out: &mut Block,
    ) -> Option<ExprId> {
        let lowered: Vec<ExprId> = args.iter().map(|a| self.expr(a, None, out)).collect::<Option<_>>()?;
        let valid = lowered.len() == 4 && {
            let types: Vec<Type> = lowered.iter().map(|&a| self.ty(a)).collect();
            types[0] == Type::STRING
                && convert::implicit_cost(types[1], Type::FLOAT).is_some()
                && convert::implicit_cost(types[2], Type::FLOAT).is_some()
                && !types[3].is_array()
                && matches!(
                    types[3].base,
                    Base::Float | Base::Color | Base::Point | Base::Vector | Base::Normal
                )
        };
        if !valid {
            let types: Vec<String> = lowered.iter().map(|&a| self.ty(a).to_string()).collect();
            self.error(Diagnostic::error(
                Code::NoMatchingOverload,
                format!("no overload of `bake` takes ({})", types.join(", ")),
                span,
                "expected `bake(string file, float s, float t, value)`",
            ));
            return None;
        }
        self.error(
            Diagnostic::warning(
                Code::IgnoredFeature,
                "`bake` does nothing: bake files are not written",
                callee.span,
                "ignored",
            )
            .with_note(
                "Patina renders one image per run and has no bake pass; compute the value where it is used",
            ),
        );
        Some(self.push_expr(ExprKind::Construct(Vec::new()), Type::VOID, span))
    }

    /// Checks the optional `"name", value` arguments of a texture lookup and appends each pair the
    /// function knows to `converted` (a string literal, then the value as a float, or a string for
    /// `"filter"`); warns about names it does not know (left out) and about options no backend
    /// honours (kept, for the passes that will).
    fn lookup_options(
        &mut self,
        callee: &ast::Ident,
        b: &'static Builtin,
        pairs: &[ast::Expr],
        converted: &mut Vec<ExprId>,
        out: &mut Block,
    ) -> Option<()> {
        let known = builtins::options(b.id).unwrap_or(&[]);
        let honoured = builtins::honoured_options(b.id);
        let mut ignored: Vec<String> = Vec::new();
        for pair in pairs.chunks(2) {
            let name_expr = &pair[0];
            let ast::ExprKind::String(name) = &name_expr.kind else {
                self.error(
                    Diagnostic::error(
                        Code::UnknownOption,
                        format!("`{}` expects an option name here", b.name()),
                        name_expr.span,
                        "expected a string literal naming an option",
                    )
                    .with_help("optional arguments come in pairs: `\"blur\", 0.01`"),
                );
                return None;
            };
            let Some(value) = pair.get(1) else {
                self.error(Diagnostic::error(
                    Code::UnknownOption,
                    format!("option `{name}` of `{}` has no value", b.name()),
                    name_expr.span,
                    "expected `, value` after this name",
                ));
                return None;
            };
            let Some(&(_, string_valued)) = known.iter().find(|(n, _)| *n == name.as_str()) else {
                let names: Vec<String> = known.iter().map(|(n, _)| format!("`{n}`")).collect();
                self.error(
                    Diagnostic::warning(
                        Code::UnknownOption,
                        format!("`{}` has no option `{name}`; it is ignored", b.name()),
                        name_expr.span,
                        "unknown option name",
                    )
                    .with_help(format!(
                        "the options of `{}` are {}",
                        b.name(),
                        names.join(", ")
                    )),
                );
                continue;
            };
            let value_id = self.expr(value, None, out)?;
            let want = if string_valued { Type::STRING } else { Type::FLOAT };
            let value_id = self.coerce(value_id, want, &format!("option `{name}`"))?;
            let name_id = self.expr(name_expr, None, out)?;
            converted.push(name_id);
            converted.push(value_id);
            if !honoured.contains(&name.as_str()) && !ignored.contains(&name.to_string()) {
                ignored.push(name.to_string());
            }
        }
        if !ignored.is_empty() {
            let list: Vec<String> = ignored.iter().map(|n| format!("`{n}`")).collect();
            let honoured_list: Vec<String> = honoured.iter().map(|n| format!("`{n}`")).collect();
            let note = if honoured.is_empty() {
                format!("no option of `{}` has an effect yet", b.name())
            } else {
                format!("the options of `{}` with an effect are {}", b.name(), honoured_list.join(", "))
            };
            self.error(
                Diagnostic::warning(
                    Code::IgnoredFeature,
                    format!(
                        "`{}` ignores the option{} {}",
                        b.name(),
                        if list.len() == 1 { "" } else { "s" },
                        list.join(", ")
                    ),
                    callee.span,
                    "no backend implements these options",
                )
                .with_note(note),
            );
        }
        Some(())
    }

    /// Inlines a call of `f` and returns the expression of its result; `None` past the inlining
    /// limits (reported).
    fn inline_call(
        &mut self,
        f: &ast::FunctionDef,
        args: &[Option<ExprId>],
        span: Span,
        outer: Option<usize>,
        library: bool,
        out: &mut Block,
    ) -> Option<ExprId> {
        if !self.within_inline_limits(f, span) {
            return None;
        }
        let result = self.inline_body(f, args, span, outer, library, out);
        Some(match result {
            Some(local) => self.push_expr(ExprKind::Local(local), declared_type(f.return_type, None), span),
            // A void call used as a statement: give the caller something to ignore.
            None => self.push_expr(ExprKind::Construct(Vec::new()), Type::VOID, span),
        })
    }

    /// Enters a nested statement body (or an inlined call's) at `span`: false, reported once per
    /// shader, past [`MAX_INLINED_NESTING`]; the caller leaves with `self.nesting -= 1` when true.
    pub(super) fn enter_nested(&mut self, span: Span) -> bool {
        if self.nesting >= MAX_INLINED_NESTING {
            // Functions checked on their own would report the same chain again.
            if !self.standalone && !std::mem::replace(&mut self.nesting_reported, true) {
                self.error(
                    Diagnostic::error(
                        Code::InlineLimit,
                        format!("statements nested more than {MAX_INLINED_NESTING} deep with calls inlined"),
                        span,
                        "nesting limit reached here",
                    )
                    .with_note("a call is inlined where it is made: a call inside nested statements nests the function's statements deeper still")
                    .with_help("move the call out of the nested statements, or combine the conditions with `&&`"),
                );
            }
            return false;
        }
        self.nesting += 1;
        true
    }

    /// Whether a call of `f` at `span` may be inlined: reports [`MAX_INLINE_DEPTH`] at the call
    /// that crosses it, and [`MAX_SHADER_EXPRESSIONS`] once per shader (every later call is
    /// refused too, so that an exponential call tree stops at the limit).
    fn within_inline_limits(&mut self, f: &ast::FunctionDef, span: Span) -> bool {
        if self.exprs.len() > MAX_SHADER_EXPRESSIONS {
            if !std::mem::replace(&mut self.inline_limit_reported, true) {
                self.error(
                    Diagnostic::error(
                        Code::InlineLimit,
                        format!(
                            "with its calls inlined, the shader grows past {MAX_SHADER_EXPRESSIONS} expressions"
                        ),
                        span,
                        format!("inlining this call of `{}` crosses the limit", f.name.name),
                    )
                    .with_note("every call inlines a copy of the function's body: a function that calls another twice, nested 20 deep, makes a million copies")
                    .with_help("call the function in a loop instead of repeating the call, or compute the value once and reuse it"),
                );
            }
            return false;
        }
        if self.frames.len() >= MAX_INLINE_DEPTH {
            let mut d = Diagnostic::error(
                Code::InlineLimit,
                format!("calls nested more than {MAX_INLINE_DEPTH} deep"),
                span,
                format!("this call of `{}` would be inlined at depth {}", f.name.name, self.frames.len() + 1),
            )
            .with_help("functions are inlined into the shader: shorten the chain of calls, or use a loop");
            if let Some(first) = self.frames.first() {
                d = d.with_label(first.call_span, format!("the outermost call, of `{}`", first.name));
            }
            // The functions past the refused call are checked on their own, each starting a
            // chain as deep again: only a shader's chain is reported, once.
            if !self.standalone {
                self.error(d);
            }
            return false;
        }
        true
    }

    /// A built-in written in the language (`noise`, `cellnoise`, ...): inlines its implementation
    /// from `compiler/stdlib/builtins.sl`, the function `__NAME_RESULT` whose parameters have the
    /// overload's types. Without the library loaded, asks for it (the caller checks again).
    fn library_builtin(
        &mut self,
        b: &'static Builtin,
        args: Vec<ExprId>,
        span: Span,
        out: &mut Block,
    ) -> Option<ExprId> {
        let name = format!("__{}_{}", b.name(), b.ret);
        let placeholder = ExprKind::Builtin(b, args.clone());
        let first = self.locals.len();
        let result = self.library_call(&name, args, placeholder, b.ret, span, out)?;
        // `patina explain` shows the implementation's variables under the built-in's name.
        for local in &mut self.locals[first..] {
            if local.function.as_deref() == Some(name.as_str()) {
                local.function = Some(b.name().into());
            }
        }
        Some(result)
    }

    /// Inlines the function `name` of `compiler/stdlib/builtins.sl` whose parameters have the
    /// types of `args`. Without the library loaded, asks for it and stands `placeholder` (of type
    /// `ret`) in for the call until the semantic stage runs again with it.
    pub(super) fn library_call(
        &mut self,
        name: &str,
        args: Vec<ExprId>,
        placeholder: ExprKind,
        ret: Type,
        span: Span,
        out: &mut Block,
    ) -> Option<ExprId> {
        let types: Vec<Type> = args.iter().map(|&a| self.ty(a)).collect();
        let implementation = self.functions.library.get(name).and_then(|fs| {
            fs.iter().copied().find(|f| {
                f.params.len() == types.len()
                    && f.params.iter().zip(&types).all(|(p, t)| declared_type(p.ty, p.array.as_ref()) == *t)
            })
        });
        let Some(f) = implementation else {
            if self.functions.library.is_empty() {
                self.shared.wants_library = true;
                return Some(self.push_expr(placeholder, ret, span));
            }
            let types = types.iter().map(|t| t.to_string()).collect::<Vec<_>>().join(", ");
            self.error(Diagnostic::error(
                Code::Internal,
                format!("the standard library has no function `{name}({types})`"),
                span,
                "implemented by it",
            ));
            return None;
        };
        let args: Vec<Option<ExprId>> = args.into_iter().map(Some).collect();
        self.inline_call(f, &args, span, None, true, out)
    }

    fn wrong_kind(&mut self, callee: &ast::Ident, needs: &str) -> Option<ExprId> {
        self.error(Diagnostic::error(
            Code::WrongShaderKind,
            format!("`{}` can only be called in {needs} shaders", callee.name),
            callee.span,
            format!("this is {} {} shader", super::expr::article(self.kind), self.kind.keyword()),
        ));
        None
    }

    fn resolve<'c>(
        &mut self,
        callee: &ast::Ident,
        candidates: &[Candidate<'c>],
        args: &[Type],
        expected: Option<Type>,
        span: Span,
    ) -> Option<Candidate<'c>> {
        let scored: Vec<(u32, Candidate<'c>)> =
            candidates.iter().filter_map(|c| c.cost(args).map(|k| (k, *c))).collect();
        let list = |cands: &mut dyn Iterator<Item = &Candidate<'c>>| {
            cands.take(8).map(|c| format!("  {}", c.signature())).collect::<Vec<_>>().join("\n")
        };
        let arg_list = args.iter().map(|t| t.to_string()).collect::<Vec<_>>().join(", ");
        let Some(best) = scored.iter().map(|s| s.0).min() else {
            let count = candidates.len();
            self.error(
                Diagnostic::error(
                    Code::NoMatchingOverload,
                    format!("no overload of `{}` takes ({arg_list})", callee.name),
                    span,
                    format!("called with ({arg_list})"),
                )
                .with_note(format!(
                    "the {} candidate{}:\n{}{}",
                    count,
                    if count == 1 { " is" } else { "s are" },
                    list(&mut candidates.iter()),
                    if count > 8 { format!("\n  ... and {} more", count - 8) } else { String::new() }
                )),
            );
            return None;
        };
        let mut best: Vec<Candidate<'c>> = scored.iter().filter(|s| s.0 == best).map(|s| s.1).collect();
        if best.len() > 1
            && let Some(want) = expected
        {
            let matching: Vec<Candidate<'c>> = best.iter().copied().filter(|c| c.ret() == want).collect();
            if !matching.is_empty() {
                best = matching;
            }
        }
        if best.len() > 1 {
            let floats: Vec<Candidate<'c>> =
                best.iter().copied().filter(|c| c.ret() == Type::FLOAT).collect();
            if floats.len() == 1 {
                best = floats;
            }
        }
        if best.len() > 1 {
            self.error(
                Diagnostic::error(
                    Code::AmbiguousCall,
                    format!("call of `{}` with ({arg_list}) is ambiguous", callee.name),
                    span,
                    "several overloads fit equally well",
                )
                .with_note(format!("the candidates are:\n{}", list(&mut best.iter())))
                .with_help(if best.iter().any(|c| c.ret() != best[0].ret()) {
                    "cast the result to the type you want, as in `color noise(P)`, or convert an argument"
                } else {
                    "convert an argument to the parameter type of the overload you want"
                }),
            );
            return None;
        }
        best.first().copied()
    }
}
