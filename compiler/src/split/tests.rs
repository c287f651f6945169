//! The split is checked by running it: host, vertex and fragment stages in turn on the
//! interpreter must give what the whole shader gives, and values must cross where expected.

use super::{StageKind, Stages, split, split_folding_host};
use crate::backend::binding::Binding;
use crate::backend::cpu::{CpuProgram, Evaluator};
use crate::ir::Stmt;
use crate::opt::Prepared;
use crate::syntax::preprocess::MemoryLoader;

fn shader(src: &str) -> Prepared {
    let checked = crate::check_source("split.sl", src, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    Prepared::new(checked.program.shaders[0].clone())
}

/// Inputs of one evaluation: uniform values and per-point columns.
struct Case<'a> {
    uniforms: &'a [(&'a str, &'a [f64])],
    points: usize,
    columns: &'a [(&'a str, &'a [f64])],
    output: &'a str,
}

fn run_whole(shader: &Prepared, case: &Case) -> Vec<f64> {
    let program = CpuProgram::compile(shader, &Binding::default()).unwrap();
    let mut eval = Evaluator::<f64>::new(&program);
    for (name, v) in case.uniforms {
        eval.set(name, v).unwrap();
    }
    let columns: Vec<(&str, &[f64])> =
        case.columns.iter().filter(|(n, _)| program.slot(n).is_some()).copied().collect();
    eval.eval_points(case.points, &columns, &[case.output]).unwrap().remove(0)
}

/// Runs the stages in order; each "fragment" is at a vertex, so varyings need no interpolation.
fn run_split(stages: &Stages, case: &Case) -> Vec<f64> {
    let compile = |kind| CpuProgram::compile(stages.stage(kind), &Binding::default()).unwrap();
    let (host, vertex, fragment) =
        (compile(StageKind::Host), compile(StageKind::Vertex), compile(StageKind::Fragment));
    let names = |from: StageKind| -> Vec<&str> {
        stages.transfers.iter().filter(|t| t.from == from).map(|t| t.name.as_str()).collect()
    };

    let mut h = Evaluator::<f64>::new(&host);
    let has = |p: &CpuProgram, name: &str| p.slot(name).is_some();
    for (name, v) in case.uniforms {
        if has(&host, name) {
            h.set(name, v).unwrap();
        }
    }
    let host_names = names(StageKind::Host);
    let host_values = h.eval_points(1, &[], &host_names).unwrap();

    let mut v = Evaluator::<f64>::new(&vertex);
    let mut f = Evaluator::<f64>::new(&fragment);
    for (name, value) in case.uniforms {
        if has(&vertex, name) {
            v.set(name, value).unwrap();
        }
        if has(&fragment, name) {
            f.set(name, value).unwrap();
        }
    }
    for (name, value) in host_names.iter().zip(&host_values) {
        if has(&vertex, name) {
            v.set(name, value).unwrap();
        }
        if has(&fragment, name) {
            f.set(name, value).unwrap();
        }
    }
    let pick = |p: &CpuProgram| -> Vec<(&str, &[f64])> {
        case.columns.iter().filter(|(n, _)| has(p, n)).copied().collect()
    };
    let vertex_names = names(StageKind::Vertex);
    let varyings = v.eval_points(case.points, &pick(&vertex), &vertex_names).unwrap();
    let mut columns = pick(&fragment);
    columns.extend(vertex_names.iter().zip(&varyings).map(|(n, c)| (*n, c.as_slice())));
    f.eval_points(case.points, &columns, &[case.output]).unwrap().remove(0)
}

fn transfers(stages: &Stages, from: StageKind) -> Vec<String> {
    stages.transfers.iter().filter(|t| t.from == from).map(|t| t.name.to_string()).collect()
}

fn stores(block: &[Stmt]) -> usize {
    block
        .iter()
        .map(|s| match s {
            Stmt::Store { .. } => 1,
            Stmt::If { then, otherwise, .. } => stores(then) + stores(otherwise),
            Stmt::Loop { body, step, .. } => stores(body) + stores(step),
            Stmt::Inline { body, .. } | Stmt::Illuminance { body, .. } => stores(body),
            _ => 0,
        })
        .sum()
}

#[test]
fn stanford_rates_become_stages() {
    let src = "surface shader float4 s1(primitive group float k, vertex float3 c) {
        primitive group float k2 = k * k + 1;
        vertex float3 v = c * k2;
        fragment float3 f = v * v + {k2, 0, 0};
        return {f[0], f[1], f[2], 1};
    }";
    let sh = shader(src);
    let stages = split(&sh).unwrap();
    // The host computes k*k + 1 once; `v * v + {k2, 0, 0}` has vertex rate (Stanford's rule: the
    // maximum of its operands), so it is computed per vertex and interpolated into `f`.
    assert_eq!(transfers(&stages, StageKind::Host).len(), 2, "{:?}", stages.transfers);
    assert_eq!(transfers(&stages, StageKind::Vertex), vec!["f_v"]);
    assert!(stages.transfers.iter().any(|t| t.from == StageKind::Host && t.to_vertex));
    let c = [0.5, -1.0, 2.0, 3.0, 0.25, -0.75];
    let case = Case { uniforms: &[("k", &[1.5])], points: 2, columns: &[("c", &c)], output: "result" };
    let whole = run_whole(&sh, &case);
    assert_eq!(run_split(&stages, &case), whole);
    let k2 = 1.5f64 * 1.5 + 1.0;
    assert_eq!(whole[0], (0.5 * k2) * (0.5 * k2) + k2);

    // Folded, the host hands nothing up; the vertex stage computes k2 itself, with the same result.
    let folded = split_folding_host(&sh).unwrap();
    assert!(transfers(&folded, StageKind::Host).is_empty(), "{:?}", folded.transfers);
    assert_eq!(stores(&folded.host.body), 0);
    assert_eq!(transfers(&folded, StageKind::Vertex), vec!["f_v"]);
    assert_eq!(run_split(&folded, &case), whole);
}

#[test]
fn a_folded_host_leaves_renderman_uniforms_to_the_fragment_stage() {
    let src = "surface t9(float Kd = 0.5; color tint = color(1, 0.5, 0.25)) {
        uniform color k = tint * Kd * 2 + color(sqrt(Kd));
        Ci = k * s + color(t);
    }";
    let sh = shader(src);
    let split_stages = split(&sh).unwrap();
    assert!(!transfers(&split_stages, StageKind::Host).is_empty());
    let folded = split_folding_host(&sh).unwrap();
    assert!(folded.transfers.is_empty(), "{:?}", folded.transfers);
    let s = [0.0, 0.5, 1.0];
    let t = [1.0, 0.25, 0.0];
    let case = Case {
        uniforms: &[("Kd", &[0.8]), ("tint", &[0.2, 0.4, 0.6])],
        points: 3,
        columns: &[("s", &s), ("t", &t)],
        output: "Ci",
    };
    let whole = run_whole(&sh, &case);
    assert_eq!(run_split(&folded, &case), whole);
    assert_eq!(run_split(&split_stages, &case), whole);
    assert!((whole[3] - ((0.2 * 0.8 * 2.0 + 0.8f64.sqrt()) * 0.5 + 0.25)).abs() < 1e-12);
}

#[test]
fn loops_recompute_what_they_read_and_hand_over_the_rest() {
    let src = "surface t2(float Kd = 0.5; float octaves = 4) {
        uniform float amp = Kd * 2;
        float sum = 0;
        float f = 1;
        for (uniform float i = 0; i < octaves; i += 1) { sum += amp * sin(s * f); f *= 2; }
        Ci = color(sum, t * amp, 0);
    }";
    let sh = shader(src);
    let stages = split(&sh).unwrap();
    // `amp` crosses from the host (its value for the loop, and its read outside it); the loop
    // runs in the fragment stage with its own counter.
    assert!(!transfers(&stages, StageKind::Host).is_empty());
    assert!(transfers(&stages, StageKind::Vertex).is_empty());
    assert_eq!(stores(&stages.vertex.body), 0);
    let s = [0.1, 0.7, 2.5];
    let t = [0.3, 0.2, 0.9];
    let case = Case {
        uniforms: &[("Kd", &[0.8]), ("octaves", &[3.0])],
        points: 3,
        columns: &[("s", &s), ("t", &t)],
        output: "Ci",
    };
    assert_eq!(run_split(&stages, &case), run_whole(&sh, &case));
}

#[test]
fn conditions_the_lower_stage_cannot_decide_still_get_their_values() {
    // `c * 3` is per vertex but used only where a per-fragment condition holds; the vertex stage
    // computes it unconditionally and the fragment stage decides.
    let src = "surface shader float4 s3(vertex float c, primitive group float k) {
        vertex float w = c * 3;
        fragment float g = w + 1;
        fragment float r = 0;
        if (g > 2) { r = w * k; } else { r = k; }
        return {r, g, 0, 1};
    }";
    let sh = shader(src);
    let stages = split(&sh).unwrap();
    let c = [0.1, 0.5, 0.9];
    let case = Case { uniforms: &[("k", &[2.0])], points: 3, columns: &[("c", &c)], output: "result" };
    let whole = run_whole(&sh, &case);
    assert_eq!(run_split(&stages, &case), whole);
    assert_eq!(whole[0], 2.0, "g = 1.3 takes the else branch");
    assert_eq!(whole[8], 0.9 * 3.0 * 2.0);
}

#[test]
fn derivatives_stay_in_the_fragment_stage() {
    let src = "surface d(float freq = 4) {
        float x = sin(s * freq);
        Ci = color(x, Du(x), filterwidth(t * freq));
    }";
    let sh = shader(src);
    let stages = split(&sh).unwrap();
    let s = [0.1, 0.4];
    let t = [0.2, 0.6];
    let dsx = [0.01, 0.02];
    let case = Case {
        uniforms: &[("freq", &[4.0])],
        points: 2,
        columns: &[("s", &s), ("t", &t), ("dx(s)", &dsx), ("dx(t)", &dsx)],
        output: "Ci",
    };
    assert_eq!(run_split(&stages, &case), run_whole(&sh, &case));
}

#[test]
fn renderman_varying_work_runs_per_fragment() {
    // `k * s` has vertex rate, but RenderMan users expect varying expressions per shading point:
    // only the inputs are interpolated.
    let sh = shader("surface c(color k = 1) { Ci = k * s; Oi = 1; }");
    let stages = split(&sh).unwrap();
    assert!(stages.transfers.is_empty(), "{:?}", stages.transfers);
    assert_eq!(stores(&stages.host.body), 0);
    assert_eq!(stores(&stages.vertex.body), 0);
    assert_eq!(stores(&stages.fragment.body), 2);
}

#[test]
fn every_example_shader_splits() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders");
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let loader = crate::syntax::preprocess::FsLoader { include_dirs: vec![] };
        let checked = crate::check_source(&path.display().to_string(), &text, &loader);
        for s in &checked.program.shaders {
            let s = Prepared::new(s.clone());
            if let Err(d) = split(&s) {
                panic!("{}: {}: {}", path.display(), s.name, d.message);
            }
            count += 1;
        }
    }
    assert!(count >= 7, "only {count} shaders");
}
