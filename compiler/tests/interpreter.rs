//! The CPU interpreter end to end: shaders compiled from source, evaluated at points, checked
//! against values worked out by hand (or by an independent f64 computation in the test).

use patina_compiler::backend::cpu::{Binding, CpuProgram, Evaluator, LightBinding};
use patina_compiler::syntax::preprocess::MemoryLoader;

/// Compiles the only shader of `source`, panicking with the rendered diagnostics on failure.
fn compile(source: &str, binding: &Binding) -> CpuProgram {
    let checked = patina_compiler::check_source("test.sl", source, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    CpuProgram::compile(&checked.program.shaders[0], binding)
        .unwrap_or_else(|d| panic!("{}: {}", d.code, d.message))
}

/// Evaluates `outputs` of a surface shader at points given by columns.
fn run(source: &str, count: usize, inputs: &[(&str, &[f64])], outputs: &[&str]) -> Vec<Vec<f64>> {
    let program = compile(source, &Binding::default());
    let mut eval = Evaluator::<f64>::new(&program);
    eval.eval_points(count, inputs, outputs).unwrap()
}

#[test]
fn arithmetic_on_inputs() {
    let out = run(
        "surface t(float k = 2) { Ci = color(s * k, t + 1, s - t); }",
        2,
        &[("s", &[0.5, 1.0]), ("t", &[0.25, 0.75])],
        &["Ci"],
    );
    assert_eq!(out[0], vec![1.0, 1.25, 0.25, 2.0, 1.75, 0.25]);
}

#[test]
fn divergent_if_and_loops() {
    let src = "surface t() {
        float acc = 0;
        float i;
        for (i = 0; i < s; i += 1) {
            if (i == 2) continue;
            if (i > 5) break;
            acc += i;
        }
        Ci = acc;
    }";
    let s: Vec<f64> = (0..300).map(|i| (i % 10) as f64).collect();
    let out = run(src, 300, &[("s", &s)], &["Ci"]);
    for (p, s) in s.iter().enumerate() {
        let mut acc = 0.0;
        let mut i = 0.0;
        while i < *s {
            if i == 2.0 {
                i += 1.0;
                continue;
            }
            if i > 5.0 {
                break;
            }
            acc += i;
            i += 1.0;
        }
        assert_eq!(out[0][p * 3], acc, "s = {s}");
    }
}
