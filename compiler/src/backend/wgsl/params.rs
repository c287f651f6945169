//! The parameters of the surface and its bound shaders for the interface: name, type and, where
//! the default does not depend on the view, its value as the host would compute it (given by the
//! caller's [`ParamDefaults`]).

use super::interface::Parameter;
use crate::ir::{LocalId, LocalKind};
use crate::opt::Prepared;
use crate::split::Stages;

/// Computes the defaults of a shader's parameters that do not depend on the view, by name, for
/// the interface: given the shader (a whole shader, or a host stage) and its string parameters'
/// values. The host computes them, and the host is the interpreter, which this backend does not
/// import: callers pass `backend::defaults::constant_defaults`.
pub type ParamDefaults = dyn Fn(&Prepared, &[(String, String)]) -> Vec<(String, Vec<f64>)>;

/// The parameters of the shader the stages were split from (transfers left out).
pub(super) fn surface_parameters(
    stages: &Stages,
    strings: &[(String, String)],
    defaults: &ParamDefaults,
) -> Vec<Parameter> {
    let transfers: Vec<_> = stages.transfers.iter().map(|t| t.local).collect();
    parameters(&stages.host, &transfers, strings, defaults)
}

/// The parameters of `shader` (a whole shader, or a host stage), but for those in `skip`.
pub(super) fn parameters(
    shader: &Prepared,
    skip: &[LocalId],
    strings: &[(String, String)],
    defaults: &ParamDefaults,
) -> Vec<Parameter> {
    let declared: Vec<_> = shader.params.iter().copied().filter(|p| !skip.contains(p)).collect();
    let has_default = |p| matches!(shader.local(p).kind, LocalKind::Param { default: Some(_), .. });
    let defaults = defaults(shader, strings);
    declared
        .into_iter()
        .map(|p| {
            let local = shader.local(p);
            let name = local.name.to_string();
            let default = if has_default(p) {
                defaults.iter().find(|(n, _)| *n == name).map(|(_, v)| v.clone())
            } else {
                None
            };
            Parameter {
                ty: local.ty.to_string(),
                default,
                fixed: None,
                output: matches!(local.kind, LocalKind::Param { output: true, .. }),
                name,
            }
        })
        .collect()
}
