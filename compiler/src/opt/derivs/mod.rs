//! Screen-space derivatives by forward-mode automatic differentiation, as an IR-to-IR rewrite.
//!
//! The derivative built-ins (`Du`, `Dv`, `Deriv`, `filterwidth`, the 2-argument `filterstep`,
//! `area`, `calculatenormal`) become arithmetic on the derivatives of their arguments along the
//! raster x and y axes. Those are computed by the chain rule from the inputs' derivatives, which
//! the backend supplies as [`ExprKind::Seed`](crate::ir::ExprKind::Seed) values (the GPU takes
//! `dpdx`/`dpdy` of the interpolated inputs, the CPU gets them from its caller). The texture
//! lookups keep their implicit derivatives for now.
//!
//! The steps:
//! 1. `analysis`: which values can have a derivative at all (forward), and which of them the
//!    consumers' arguments depend on (backward, through the variables they are stored in). Only
//!    float-based values of vertex or fragment rate computed from inputs have one; the rest have
//!    derivative exactly 0 and cost nothing.
//! 2. `rewrite`: each variable needed gets two shadow locals, `dx(name)` and `dy(name)`; inputs
//!    (predefined variables, varying parameters) are seeded at the start of the body, and every
//!    store of the variable is preceded by stores of the derivatives of the value stored (zeros
//!    when it has none).
//! 3. `rules`, `calls`, `geometry`: the derivative of each expression, built once per axis.
//! 4. `consumers`: each consumer's expression is overwritten in place with its formula.
//!
//! Every built-in has its rule in `calls::rule`, an exhaustive match on its id: a chain rule, a
//! consumer, a component setter, derivative 0 by definition, or library code.
//! Derivative 0 by definition: per-light values (`L`, `Cl`, `Ol`, Stanford's `H`: a light's
//! values are taken as constant across the pixel), `du` and `dv`, `random()`, the lighting
//! functions, texture lookups, the outputs of `lightsource` and `surface` (another shader's
//! values), and the result of any derivative built-in (there are no second derivatives).
//! Built-ins written in the language (`compiler/stdlib/builtins.sl`: noise, colour spaces,
//! `fresnel`, `ptlined`, `rotate`, `translate`, `scale`, `determinant`) are differentiated through
//! their code. Left out: the change of `spline`'s parameter (knots only), and of the matrix of
//! `transform`, `vtransform` and `ntransform`.
//! Points moved through a projective space ("screen", "raster", "NDC") are differentiated as
//! vectors, without the perspective divide's term. Control flow is differentiated along the path
//! taken: a value that jumps between branches has the derivative of the branch the pixel took.
//!
//! After this pass, replaced consumers refer to expressions appended after them: operands no longer
//! always precede their users in the arena (the graph is still acyclic).

mod analysis;
mod calls;
mod consumers;
mod geometry;
mod rewrite;
mod rules;
#[cfg(test)]
mod tests;

use crate::ir::Shader;
use crate::opt::build::Builder;
use consumers::SurfaceParams;
use rules::Diff;

/// Replaces the derivative built-ins of `shader` (all but the texture lookups) by arithmetic on
/// derivatives computed by the chain rule, adding the shadow locals, seeds and derivative stores
/// that needs. Existing expression ids stay valid: consumers are overwritten in place, new
/// expressions and locals are appended. A shader without consumers is left as it is.
pub(crate) fn differentiate(shader: &mut Shader) {
    // Also what makes the pass idempotent: its output has no consumers, and its arena order is no
    // longer what the analysis walks.
    let has_consumers = shader
        .exprs
        .iter()
        .any(|e| matches!(&e.kind, crate::ir::ExprKind::Builtin(b, _) if analysis::is_consumer(b)));
    if !has_consumers {
        return;
    }
    let mut needs = analysis::analyse(shader);
    if needs.consumers.is_empty() {
        return;
    }
    let (locals, globals) = rewrite::add_shadows(shader, &needs);
    let body = std::mem::take(&mut shader.body);
    let span = shader.span;
    let mut diff = Diff::new(Builder::new(shader, span));
    diff.locals = locals;
    diff.globals = globals;
    diff.consumers = needs.consumers.iter().copied().collect();
    diff.active = std::mem::take(&mut needs.active);
    let mut new_body = diff.seeds(&needs);
    new_body.extend(diff.block(body));
    let uv = match (diff.globals.get("u"), diff.globals.get("v")) {
        (Some(&u), Some(&v)) => Some(SurfaceParams { u, v }),
        _ => None,
    };
    for &c in &needs.consumers {
        diff.replace(c, uv);
    }
    diff.b.shader.body = new_body;
    crate::verify::assert_valid(diff.b.shader, crate::verify::Pass::Derivatives);
}
