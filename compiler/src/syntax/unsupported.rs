//! RenderMan features Patina does not support, named in a diagnostic rather than left to fail later
//! as unknown functions: ray tracing, message passing between shaders, `gather`, renderer queries.

use super::ast::*;
use crate::diag::{Code, Diagnostic, Diagnostics};

/// What a built-in name belongs to, and why Patina leaves it out.
fn classify(name: &str) -> Option<(Code, &'static str, &'static str)> {
    const RAY_TRACING: &str = "a rasterizer has no rays to trace; these need a ray tracer";
    const MESSAGES: &str =
        "shaders are bound and inlined together, so there is no other shader to query at run time";
    Some(match name {
        "trace" | "transmission" | "occlusion" | "indirectdiffuse" | "rayinfo" | "photonmap" | "caustic" => {
            (Code::RayTracing, "ray tracing", RAY_TRACING)
        }
        "surface" | "displacement" | "light" | "volume" | "imager" | "atmosphere" | "lightsource"
        | "incident" | "opposite" | "interior" | "exterior" => {
            (Code::MessagePassing, "message passing between shaders", MESSAGES)
        }
        "attribute" | "option" | "rendererinfo" | "textureinfo" => (
            Code::RendererQuery,
            "renderer queries",
            "a shader's inputs are its parameters and the scene's bound values; pass the value as a parameter",
        ),
        _ => return None,
    })
}

/// Reports every use of an unsupported feature in `module`. A function the module defines itself
/// with such a name, at the top level or locally in a body around the call, is the user's own and is
/// left alone.
pub fn check(module: &Module, diags: &mut Diagnostics) {
    let mut defined = Vec::new();
    for item in &module.items {
        if let Item::Function(f) = item {
            defined.push(f.name.name.as_str());
        }
    }
    let mut walker = Walker { defined, diags };
    for item in &module.items {
        match item {
            Item::Shader(s) => {
                s.params.iter().filter_map(|p| p.default.as_ref()).for_each(|e| walker.expr(e));
                walker.block(&s.body);
            }
            Item::Function(f) => walker.block(&f.body),
            Item::Variable(v) => walker.decl(v),
            Item::Error(_) => {}
        }
    }
}

struct Walker<'a> {
    /// The functions in scope: the top-level ones, then those of each enclosing block.
    defined: Vec<&'a str>,
    diags: &'a mut Diagnostics,
}

impl<'a> Walker<'a> {
    fn block(&mut self, b: &'a Block) {
        let outer = self.defined.len();
        for s in &b.stmts {
            if let StmtKind::Function(f) = &s.kind {
                self.defined.push(f.name.name.as_str());
            }
        }
        b.stmts.iter().for_each(|s| self.stmt(s));
        self.defined.truncate(outer);
    }

    fn decl(&mut self, d: &'a VarDecl) {
        d.declarators.iter().filter_map(|d| d.init.as_ref()).for_each(|e| self.expr(e));
    }

    fn stmt(&mut self, s: &'a Stmt) {
        match &s.kind {
            StmtKind::Block(b) => self.block(b),
            StmtKind::Decl(d) => self.decl(d),
            StmtKind::Function(f) => self.block(&f.body),
            StmtKind::Expr(e) => self.expr(e),
            StmtKind::If { cond, then, otherwise } => {
                self.expr(cond);
                self.stmt(then);
                otherwise.iter().for_each(|o| self.stmt(o));
            }
            StmtKind::While { cond, body } => {
                self.expr(cond);
                self.stmt(body);
            }
            StmtKind::For { init, cond, step, body } => {
                init.iter().for_each(|i| self.stmt(i));
                cond.iter().chain(step).for_each(|e| self.expr(e));
                self.stmt(body);
            }
            StmtKind::Return(e) => e.iter().for_each(|e| self.expr(e)),
            StmtKind::Illuminance { args, body }
            | StmtKind::Illuminate { args, body }
            | StmtKind::Solar { args, body } => {
                args.iter().for_each(|e| self.expr(e));
                self.stmt(body);
            }
            StmtKind::Gather { .. } => {
                let keyword = crate::source::Span { end: s.span.start + "gather".len() as u32, ..s.span };
                self.diags.push(
                    Diagnostic::error(
                        Code::Gather,
                        "`gather` is not supported: it needs ray tracing",
                        keyword,
                        "`gather` shoots rays into the scene",
                    )
                    .with_note("Patina compiles shaders for a rasterizer (WGSL), which has no rays to trace"),
                );
            }
            StmtKind::Break { .. } | StmtKind::Continue { .. } | StmtKind::Empty | StmtKind::Error => {}
        }
    }

    fn expr(&mut self, e: &'a Expr) {
        match &e.kind {
            ExprKind::Call { callee, args } => {
                if !self.defined.contains(&callee.name.as_str())
                    && let Some((code, feature, why)) = classify(&callee.name)
                {
                    self.diags.push(
                        Diagnostic::error(
                            code,
                            format!(
                                "`{}` is not supported: Patina does not implement {feature}",
                                callee.name
                            ),
                            callee.span,
                            "not available in Patina",
                        )
                        .with_note(why),
                    );
                }
                args.iter().for_each(|a| self.expr(a));
            }
            ExprKind::Unary { operand, .. } | ExprKind::Cast { operand, .. } => self.expr(operand),
            ExprKind::Step { target, .. } => self.expr(target),
            ExprKind::Binary { lhs, rhs, .. } => {
                self.expr(lhs);
                self.expr(rhs);
            }
            ExprKind::Assign { target, value, .. } => {
                self.expr(target);
                self.expr(value);
            }
            ExprKind::Conditional { cond, then, otherwise } => {
                self.expr(cond);
                self.expr(then);
                self.expr(otherwise);
            }
            ExprKind::Tuple(items) | ExprKind::Braced(items) => items.iter().for_each(|i| self.expr(i)),
            ExprKind::Index { base, index } => {
                self.expr(base);
                self.expr(index);
            }
            ExprKind::Int { .. }
            | ExprKind::Float(_)
            | ExprKind::String(_)
            | ExprKind::Bool(_)
            | ExprKind::Name(_)
            | ExprKind::Error => {}
        }
    }
}
