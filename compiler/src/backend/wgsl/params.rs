//! The surface shader's parameters for the interface: name, type and, where the default is a
//! constant, its value, computed by the interpreter as the host would compute it.

use super::interface::Parameter;
use crate::backend::cpu::{Binding, CpuProgram, Evaluator};
use crate::ir::types::Frequency;
use crate::ir::{LocalKind, Shader};
use crate::split::Stages;

/// The parameters of the shader the stages were split from (transfers left out).
pub(super) fn parameters(stages: &Stages, strings: &[(String, String)]) -> Vec<Parameter> {
    let shader = &stages.host;
    let declared: Vec<_> =
        shader.params.iter().copied().filter(|p| !stages.transfers.iter().any(|t| t.local == *p)).collect();
    let constant = |p| match shader.local(p).kind {
        LocalKind::Param { default: Some(e), .. } => shader.expr(e).rate.frequency == Frequency::Constant,
        _ => false,
    };
    let defaults = constant_defaults(shader, strings);
    declared
        .into_iter()
        .map(|p| {
            let local = shader.local(p);
            let name = local.name.to_string();
            let default = if constant(p) {
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

/// Every parameter's value with nothing set, from one run of the host program in f64; empty when
/// the host program cannot run on its own (its defaults are then left to the host at draw time).
fn constant_defaults(host: &Shader, strings: &[(String, String)]) -> Vec<(String, Vec<f64>)> {
    let binding = Binding { lights: Vec::new(), strings: strings.to_vec() };
    let Ok(program) = CpuProgram::compile(host, &binding) else { return Vec::new() };
    let names: Vec<String> = program
        .slots()
        .filter(|(_, s)| matches!(s.kind, crate::backend::cpu::SlotKind::Param { .. }))
        .map(|(_, s)| s.name)
        .collect();
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let mut eval = Evaluator::<f64>::new(&program);
    match eval.eval_points(1, &[], &refs) {
        Ok(values) => names.into_iter().zip(values).collect(),
        Err(_) => Vec::new(),
    }
}
