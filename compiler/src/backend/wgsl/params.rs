//! The parameters of the surface and its bound shaders for the interface: name, type and, where
//! the default does not depend on the view, its value, computed by the interpreter as the host
//! would compute it.

use super::interface::Parameter;
use crate::backend::cpu::{Binding, CpuProgram, Evaluator, SlotKind};
use crate::ir::{LocalId, LocalKind, Shader};
use crate::split::Stages;

/// The parameters of the shader the stages were split from (transfers left out).
pub(super) fn surface_parameters(stages: &Stages, strings: &[(String, String)]) -> Vec<Parameter> {
    let transfers: Vec<_> = stages.transfers.iter().map(|t| t.local).collect();
    parameters(&stages.host, &transfers, strings)
}

/// The parameters of `shader` (a whole shader, or a host stage), but for those in `skip`.
pub(super) fn parameters(shader: &Shader, skip: &[LocalId], strings: &[(String, String)]) -> Vec<Parameter> {
    let declared: Vec<_> = shader.params.iter().copied().filter(|p| !skip.contains(p)).collect();
    let has_default = |p| matches!(shader.local(p).kind, LocalKind::Param { default: Some(_), .. });
    let defaults = constant_defaults(shader, strings);
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

/// The parameters' defaults that do not depend on the view: the host program is run twice in
/// f64, once with every space the identity and every uniform predefined variable zero, once with
/// other values for them, and a default is kept when both runs agree (a default read from a space
/// or a predefined variable, such as `point "shader" (0, 0, 0)`, is left to the host). Empty when
/// the host program cannot run on its own.
fn constant_defaults(host: &Shader, strings: &[(String, String)]) -> Vec<(String, Vec<f64>)> {
    let binding = Binding { lights: Vec::new(), strings: strings.to_vec() };
    let Ok(program) = CpuProgram::compile(host, &binding) else { return Vec::new() };
    let names: Vec<String> = program
        .slots()
        .filter(|(_, s)| matches!(s.kind, SlotKind::Param { .. }))
        .map(|(_, s)| s.name)
        .collect();
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let run = |perturb: bool| -> Option<Vec<Vec<f64>>> {
        let mut eval = Evaluator::<f64>::new(&program);
        if perturb {
            for (_, slot) in program.slots() {
                let width = match slot.kind {
                    // A space takes its matrix (its inverse is derived): a rotation and a shift.
                    SlotKind::Space => {
                        let m = [
                            0.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.5, -2.0, 3.0, 1.0,
                        ];
                        eval.set(&slot.name, &m).ok()?;
                        continue;
                    }
                    SlotKind::Global if slot.uniform => slot.width,
                    _ => continue,
                };
                let values: Vec<f64> = (0..width).map(|k| 0.375 + 0.25 * k as f64).collect();
                eval.set(&slot.name, &values).ok()?;
            }
        }
        eval.eval_points(1, &[], &refs).ok()
    };
    let (Some(plain), Some(perturbed)) = (run(false), run(true)) else { return Vec::new() };
    names
        .into_iter()
        .zip(plain.into_iter().zip(perturbed))
        .filter(|(_, (a, b))| a == b)
        .map(|(name, (a, _))| (name, a))
        .collect()
}
