//! RenderMan features Patina does not support, named in a diagnostic rather than reported as
//! unknown functions: ray tracing, message passing between shaders, `gather`, renderer queries.
//!
//! This is part of name resolution: a call reaches it only when neither the file nor the built-ins
//! define the name, so a user's own function called `trace` is simply called.

use crate::diag::{Code, Diagnostic};
use crate::source::Span;
use crate::syntax::ast::Ident;

/// The diagnostic for a call of an unsupported RenderMan built-in, if `callee` names one.
pub fn call(callee: &Ident) -> Option<Diagnostic> {
    const RAY_TRACING: &str = "a rasterizer has no rays to trace; these need a ray tracer";
    const MESSAGES: &str = "shaders are bound together, so binding answers the queries it can (`lightsource` inside \
         `illuminance`, `surface` in lights and atmospheres, a light's `__category`); there is no other \
         shader to query at run time";
    let (code, feature, why) = match callee.name.as_str() {
        "trace" | "transmission" | "occlusion" | "indirectdiffuse" | "rayinfo" | "photonmap" | "caustic" => {
            (Code::RayTracing, "ray tracing", RAY_TRACING)
        }
        "displacement" | "light" | "volume" | "imager" | "atmosphere" | "incident" | "opposite"
        | "interior" | "exterior" => {
            (Code::MessagePassing, "message passing beyond `lightsource` and `surface`", MESSAGES)
        }
        "attribute" | "rendererinfo" | "textureinfo" => (
            Code::RendererQuery,
            "renderer queries",
            "a shader's inputs are its parameters and the scene's bound values; pass the value as a parameter",
        ),
        _ => return None,
    };
    Some(
        Diagnostic::error(
            code,
            format!("`{}` is not supported: Patina does not implement {feature}", callee.name),
            callee.span,
            "not available in Patina",
        )
        .with_note(why),
    )
}

/// The diagnostic for a `gather` statement starting at `span`.
pub fn gather(span: Span) -> Diagnostic {
    let keyword = Span { end: span.start + "gather".len() as u32, ..span };
    Diagnostic::error(
        Code::Gather,
        "`gather` is not supported: it needs ray tracing",
        keyword,
        "`gather` shoots rays into the scene",
    )
    .with_note("Patina compiles shaders for a rasterizer (WGSL), which has no rays to trace")
}
