//! The parameter defaults a GPU program's interface lists (docs/interface.md, `params`): the
//! values the host would compute, computed by the interpreter, which is the host. The WGSL backend
//! takes them as a function ([`wgsl::ParamDefaults`](super::wgsl::ParamDefaults)) so that it does
//! not depend on the interpreter; this is the function every caller passes.

use super::binding::Binding;
use super::cpu::{CpuProgram, Evaluator, SlotKind};
use crate::opt::Prepared;

/// The defaults of the parameters of `host` (a whole shader, or a host stage) that do not depend
/// on the view, by name: the program is run twice in f64, once with every space the identity and
/// every uniform predefined variable zero, once with other values for them, and a default is kept
/// when both runs agree (a default read from a space or a predefined variable, such as `point
/// "shader" (0, 0, 0)`, is left to the host). `strings` are its string parameters' values. Empty
/// when the program cannot run on its own.
pub fn constant_defaults(host: &Prepared, strings: &[(String, String)]) -> Vec<(String, Vec<f64>)> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::preprocess::MemoryLoader;

    #[test]
    fn defaults_that_call_functions_reach_the_interface() {
        // The calls in a default are statements ahead of the body; the host stage keeps them for
        // the default, though nothing in the body reads their results.
        let src = "float twice(float x) { return 2 * x; }
            surface t(float a = radians(30); float b = twice(distance(point(0, 0, 0), point(3, 4, 0)));
                      float c = 1 + b) { Ci = color(a, b, c); }";
        let checked = crate::check_source("t.sl", src, &MemoryLoader::default());
        assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
        let shader = Prepared::new(checked.program.shaders[0].clone());
        let stages = crate::split::split(&shader).unwrap_or_else(|d| panic!("{}", d.message));
        let defaults = constant_defaults(&stages.host, &[]);
        for (name, want) in [("a", std::f64::consts::PI / 6.0), ("b", 10.0), ("c", 11.0)] {
            let value = defaults.iter().find(|(n, _)| n == name).map(|(_, v)| v[0]);
            assert!(value.is_some_and(|v| (v - want).abs() < 1e-15), "{name}: {value:?}, not {want}");
        }
    }
}
