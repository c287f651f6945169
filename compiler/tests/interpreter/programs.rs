//! The CPU interpreter end to end: shaders compiled from source, evaluated at points, checked
//! against values worked out by hand (or by an independent f64 computation in the test).

use patina_compiler::backend::binding::{Binding, LightBinding};
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_compiler::syntax::preprocess::MemoryLoader;

/// Compiles the only shader of `source`, panicking with the rendered diagnostics on failure.
fn compile(source: &str, binding: &Binding) -> CpuProgram {
    crate::support::compile(source, binding)
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

#[test]
fn illuminance_runs_once_per_light_inside_its_cone() {
    // Two lights: one overhead, one at grazing angle; the cone of 45 degrees around N keeps only
    // the first. An ambient light is never visited by illuminance.
    let src = "surface t() {
        color sum = 0;
        float count = 0;
        illuminance(P, N, PI / 4) { sum += Cl * (normalize(L) . N); count += 1; }
        Ci = sum; Oi = count;
    }";
    let binding = Binding {
        lights: vec![
            LightBinding::default(),
            LightBinding::default(),
            LightBinding { ambient: true, ..LightBinding::default() },
        ],
        strings: vec![],
    };
    let program = compile(src, &binding);
    let mut eval = Evaluator::<f64>::new(&program);
    eval.set("L[0]", &[0.0, 0.0, 2.0]).unwrap();
    eval.set("Cl[0]", &[1.0, 0.5, 0.25]).unwrap();
    eval.set("L[1]", &[1.0, 0.0, 0.1]).unwrap();
    eval.set("Cl[1]", &[7.0, 7.0, 7.0]).unwrap();
    let out = eval.eval_points(2, &[("N", &[0.0, 0.0, 1.0, 1.0, 0.0, 0.0])], &["Ci", "Oi"]).unwrap();
    assert_eq!(&out[0][..3], &[1.0, 0.5, 0.25], "only the overhead light, for N = +z");
    assert_eq!(out[1][0], 1.0);
    let grazing = 7.0 * (1.0 / (1.0f64 + 0.01).sqrt());
    assert!((out[0][3] - grazing).abs() < 1e-12, "only the second light for N = +x: {}", out[0][3]);
    assert_eq!(out[1][3], 1.0);
}

#[test]
fn light_sums_follow_the_ri_definitions() {
    let src = "surface t() { Ci = ambient() + diffuse(N); Oi = specular(N, vector(0, 0, 1), 0.25); }";
    let binding = Binding {
        lights: vec![LightBinding::default(), LightBinding { ambient: true, ..LightBinding::default() }],
        strings: vec![],
    };
    let program = compile(src, &binding);
    let mut eval = Evaluator::<f64>::new(&program);
    eval.set("L[0]", &[0.0, 3.0, 4.0]).unwrap();
    eval.set("Cl[0]", &[1.0, 1.0, 1.0]).unwrap();
    eval.set("Cl[1]", &[0.1, 0.2, 0.3]).unwrap();
    let out = eval.eval_points(1, &[("N", &[0.0, 0.0, 1.0])], &["Ci", "Oi"]).unwrap();
    // diffuse: Cl * normalize(L) . N = 0.8; ambient adds Cl of the ambient light.
    for (c, a) in [0.1, 0.2, 0.3].iter().enumerate() {
        assert!((out[0][c] - (a + 0.8)).abs() < 1e-12);
    }
    // specular: H = normalize((0, 0.6, 0.8) + (0, 0, 1)), (N . H)^(1/0.25).
    let h: [f64; 3] = [0.0, 0.6, 1.8];
    let nh = h[2] / (h[1] * h[1] + h[2] * h[2]).sqrt();
    assert!((out[1][0] - nh.powf(4.0)).abs() < 1e-12, "{} vs {}", out[1][0], nh.powf(4.0));
}

#[test]
fn a_normalization_shared_by_diffuse_and_specular_gives_the_bits_of_each_alone() {
    // Both sums normalize each light's L: in one shader that is computed once per light
    // (opt::lights), alone in each sum it is not. The f32 results must not change by a bit,
    // for L at ordinary lengths, tiny and huge ones (lighting_normalize's rescaled branch), and 0.
    let binding = Binding { lights: vec![LightBinding::default(); 3], strings: vec![] };
    let both = "surface t() { Ci = diffuse(N); Oi = specular(N, vector(0, 0.6, 0.8), 0.1); }";
    let diffuse = "surface t() { Ci = diffuse(N); }";
    let specular = "surface t() { Oi = specular(N, vector(0, 0.6, 0.8), 0.1); }";
    let scales = [1.0, 3e-21, 7e19, 0.0, 0.37];
    let count = 64;
    let mut columns: Vec<(String, Vec<f64>)> = Vec::new();
    for k in 0..3 {
        let l: Vec<f64> = (0..count * 3)
            .map(|i| {
                let v = ((i * 7 + k * 13) % 11) as f64 - 5.0;
                v * scales[(i / 3 + k) % scales.len()]
            })
            .collect();
        let cl: Vec<f64> = (0..count * 3).map(|i| 0.25 + ((i + k) % 5) as f64 * 0.5).collect();
        columns.push((format!("L[{k}]"), l));
        columns.push((format!("Cl[{k}]"), cl));
    }
    let n: Vec<f64> = (0..count)
        .flat_map(|i| {
            let a = i as f64 * 0.37;
            [a.sin() * 0.6, 0.48, a.cos() * 0.64]
        })
        .collect();
    columns.push(("N".into(), n));
    let inputs: Vec<(&str, &[f64])> = columns.iter().map(|(name, c)| (name.as_str(), c.as_slice())).collect();
    let run = |src: &str, outputs: &[&str]| {
        let program = compile(src, &binding);
        Evaluator::<f32>::new(&program).eval_points(count, &inputs, outputs).unwrap()
    };
    let shared = run(both, &["Ci", "Oi"]);
    let alone = [run(diffuse, &["Ci"]).remove(0), run(specular, &["Oi"]).remove(0)];
    for (which, (a, b)) in ["diffuse", "specular"].iter().zip(shared.iter().zip(&alone)) {
        let differ = a.iter().zip(b).filter(|(x, y)| x.to_bits() != y.to_bits()).count();
        assert_eq!(differ, 0, "{which}: {differ} of {} values differ", a.len());
        assert!(a.iter().any(|x| *x != 0.0), "{which} lit something");
    }
}

#[test]
fn stanford_perlight_values_are_integrated_over_the_lights() {
    let src = "surface shader float4 t(vertex float4 uv) {
        perlight float3 contribution = rgb(Cl) * max(dot(L, {0, 0, 1}), 0);
        return {integrate(contribution), uv[0]};
    }";
    let checked = patina_compiler::check_source("t.sl", src, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    let binding = Binding { lights: vec![LightBinding::default(); 3], strings: vec![] };
    let program = CpuProgram::compile(
        &patina_compiler::opt::Prepared::new(checked.program.shaders[0].clone()),
        &binding,
    )
    .unwrap();
    let slots: Vec<String> = program.slots().map(|(_, s)| s.name).collect();
    let mut eval = Evaluator::<f64>::new(&program);
    for k in 0..3 {
        let l = ["L", "Cl"].map(|n| format!("{n}[{k}]"));
        assert!(slots.contains(&l[0]) && slots.contains(&l[1]), "{slots:?}");
        eval.set(&l[0], &[0.0, 0.0, k as f64 - 1.0]).unwrap();
        eval.set(&l[1], &[1.0, 2.0, 3.0, 1.0]).unwrap();
    }
    let out = eval.eval_points(1, &[("uv", &[0.5, 0.0, 0.0, 1.0])], &["result"]).unwrap();
    // Light 0 points down (clamped to 0), light 1 is perpendicular (0), light 2 points up (1).
    assert_eq!(out[0], vec![1.0, 2.0, 3.0, 0.5]);
}

#[test]
fn light_shaders_emit_inside_their_cone() {
    let src = "light spot(float intensity = 2; point from = point(0, 0, 0); vector axis = vector(0, 0, 1)) {
        illuminate(from, axis, radians(30)) { Cl = intensity / (L . L); }
    }";
    let program = compile(src, &Binding::default());
    let mut eval = Evaluator::<f64>::new(&program);
    // Surface points: on the axis at distance 2, and well outside the cone.
    let out = eval.eval_points(2, &[("Ps", &[0.0, 0.0, 2.0, 5.0, 0.0, 1.0])], &["Cl", "L"]).unwrap();
    assert_eq!(&out[0][..3], &[0.5, 0.5, 0.5]);
    assert_eq!(&out[0][3..], &[0.0, 0.0, 0.0], "outside the cone the light is black");
    assert_eq!(&out[1][..3], &[0.0, 0.0, 2.0], "L points from the light to the surface point");
}

#[test]
fn nested_loops_with_break_continue_and_return_match_a_rust_reference() {
    let src = "float f(float n) {
            float i, j, acc = 0;
            for (i = 0; i < n; i += 1) {
                for (j = 0; j < 4; j += 1) {
                    if (j == i) continue;
                    if (i + j > 6) break 2;
                    acc += i * 10 + j;
                    if (acc > 200) return -acc;
                }
            }
            return acc;
        }
        surface t() { Ci = f(s); }";
    let reference = |n: f64| -> f64 {
        let mut acc = 0.0;
        let mut i = 0.0;
        'outer: while i < n {
            let mut j = 0.0;
            while j < 4.0 {
                if j == i {
                    j += 1.0;
                    continue;
                }
                if i + j > 6.0 {
                    break 'outer;
                }
                acc += i * 10.0 + j;
                if acc > 200.0 {
                    return -acc;
                }
                j += 1.0;
            }
            i += 1.0;
        }
        acc
    };
    let s: Vec<f64> = (0..257).map(|k| (k % 9) as f64 * 0.75).collect();
    let out = run(src, s.len(), &[("s", &s)], &["Ci"]);
    for (p, n) in s.iter().enumerate() {
        assert_eq!(out[0][p * 3], reference(*n), "n = {n}");
    }
}

#[test]
fn random_is_deterministic_uniform_and_differs_per_point() {
    let out = run("surface t() { Ci = color(random(), random(), 0); }", 4000, &[], &["Ci"]);
    let xs: Vec<f64> = out[0].chunks(3).map(|c| c[0]).collect();
    let ys: Vec<f64> = out[0].chunks(3).map(|c| c[1]).collect();
    assert!(xs.iter().chain(&ys).all(|x| (0.0..1.0).contains(x)));
    let mean = xs.iter().sum::<f64>() / xs.len() as f64;
    assert!((mean - 0.5).abs() < 0.02, "mean {mean}");
    assert!(xs.iter().zip(&ys).filter(|(x, y)| x == y).count() < 5, "two call sites differ");
    let again = run("surface t() { Ci = color(random(), random(), 0); }", 4000, &[], &["Ci"]);
    assert_eq!(out, again);
}

#[test]
fn random_stored_in_a_uniform_variable_is_one_value_per_draw() {
    // RSL: `random()` where a uniform value is wanted is uniform (debug.sl, randgrid.sl).
    let src = "surface t() {\n    uniform color c = color(random(), random(), random());\n    uniform float f;\n    f = random();\n    Ci = c + color(f, 0, random());\n}";
    let out = run(src, 300, &[], &["Ci"]);
    let first = out[0][..3].to_vec();
    assert!(first.iter().all(|x| (0.0..2.0).contains(x)));
    assert_ne!(first[0], first[1], "each call site has its own value");
    assert!(out[0].chunks(3).all(|c| c[0] == first[0] && c[1] == first[1]), "uniform across points");
    let zs: Vec<f64> = out[0].chunks(3).map(|c| c[2]).collect();
    assert!(zs.iter().filter(|z| **z == zs[0]).count() < 5, "the varying call still varies");
}

#[test]
fn string_parameters_with_defaults_are_compile_time_values() {
    let src = "surface t(string space = \"world\") { Ci = color(transform(space, point(1, 2, 3))); }";
    let program = compile(src, &Binding::default());
    let mut eval = Evaluator::<f64>::new(&program);
    // Current to world: a translation by (10, 0, 0) (row-vector convention, last row).
    let mut m = [0.0; 16];
    for i in 0..4 {
        m[i * 5] = 1.0;
    }
    m[12] = 10.0;
    eval.set("space:world", &m).unwrap();
    let out = eval.eval_points(1, &[], &["Ci"]).unwrap();
    assert_eq!(out[0], vec![11.0, 2.0, 3.0]);
}

#[test]
fn option_format_reads_the_resolution_from_the_raster_space() {
    let src = "surface t() {\n    float r[3];\n    float ok = option(\"Format\", r);\n    Ci = color(r[0], r[1], r[2] * ok);\n}";
    let program = compile(src, &Binding::default());
    let mut eval = Evaluator::<f64>::new(&program);
    // Current to NDC: the identity; current to raster: a 640 × 480 scale.
    let mut ndc = [0.0; 16];
    for i in 0..4 {
        ndc[i * 5] = 1.0;
    }
    let mut raster = ndc;
    raster[0] = 640.0;
    raster[5] = 480.0;
    eval.set("space:NDC", &ndc).unwrap();
    eval.set("space:raster", &raster).unwrap();
    let out = eval.eval_points(1, &[], &["Ci"]).unwrap();
    assert_eq!(out[0], vec![640.0, 480.0, 1.0]);
}

#[test]
fn printf_runs_in_the_interpreter_without_changing_results() {
    let src = "surface t() {\n    if (s > 0.5) printf(\"s=%f i=%d c=%c\\n\", s, 2, color(s, 0, 1));\n    Ci = color(s, 0, 0);\n}";
    let out = run(src, 3, &[("s", &[0.25, 0.75, 1.0])], &["Ci"]);
    assert_eq!(out[0], vec![0.25, 0.0, 0.0, 0.75, 0.0, 0.0, 1.0, 0.0, 0.0]);
}

#[test]
fn light_construct_arguments_are_converted_and_counted() {
    // Integer angles are floats, as for any float argument (this used to reach the lowering as an
    // integer and panic it).
    let solar = compile("light sun() { solar(vector(0, 0, 1), 0) { Cl = 1; } }", &Binding::default());
    let mut eval = Evaluator::<f64>::new(&solar);
    let out = eval.eval_points(1, &[], &["Cl", "L"]).unwrap();
    assert_eq!(out[0], vec![1.0, 1.0, 1.0]);
    assert_eq!(out[1], vec![0.0, 0.0, 1.0]);
    let binding = Binding { lights: vec![LightBinding::default()], strings: vec![] };
    compile("surface s() { illuminance(P, N, 1) { Ci += Cl; } }", &binding);
    // A wrong number of arguments is a diagnostic naming the forms.
    let checked = patina_compiler::check_source(
        "bad.sl",
        "light l() { illuminate(P, vector(0, 0, 1)) { Cl = 1; } }",
        &MemoryLoader::default(),
    );
    let messages: Vec<String> = checked.diagnostics.iter().map(|d| d.message.clone()).collect();
    assert!(messages.iter().any(|m| m.contains("`illuminate(position, axis, angle)`")), "{messages:?}");
}

#[test]
fn nested_integrate_sums_over_every_light() {
    // The inner `integrate` inside a per-light value is the sum over all lights, not the outer
    // light's own term (found by runtime/tests/conformance/generated.rs: the interpreter gave half of this
    // with two lights, the GPU the sum).
    let src = "surface shader float4 t(primitive group float k) {
        perlight float3 a = {1, 2, 3};
        perlight float b = rgb(Cl)[0];
        return {integrate(integrate(a) * b), integrate(b)};
    }";
    let checked = patina_compiler::check_source("t.sl", src, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    let binding = Binding { lights: vec![LightBinding::default(); 2], strings: vec![] };
    let program = CpuProgram::compile(
        &patina_compiler::opt::Prepared::new(checked.program.shaders[0].clone()),
        &binding,
    )
    .unwrap();
    let mut eval = Evaluator::<f64>::new(&program);
    for (k, b) in [0.25, 0.5].iter().enumerate() {
        eval.set(&format!("Cl[{k}]"), &[*b, 0.0, 0.0, 1.0]).unwrap();
    }
    let out = eval.eval_points(1, &[], &["result"]).unwrap();
    // integrate(a) = 2a; sum over j of 2a * b_j = 2a * 0.75.
    assert_eq!(out[0], vec![1.5, 3.0, 4.5, 0.75]);
}

/// Issue 24: forms of third-party RenderMan shaders that did not parse or were misread: a storage
/// class on a function's result (`uniform float f()`), and casts of a negated operand
/// (`point -1e10`, `vector -I`), which read as subtractions from the type word.
#[test]
fn result_storage_classes_and_casts_of_negated_operands() {
    let src = "uniform float twice(float x) { return 2 * x; }
        varying color shade(color c) { return c * 0.5; }
        surface t() {
            point far = point -1e10;
            vector v = vector -I;
            color c = color -1 + 3;
            Ci = shade(c) * twice(xcomp(far) * 1e-10) + color(xcomp(v), ycomp(v), zcomp(v));
        }";
    let out = run(src, 1, &[("I", &[1.0, 2.0, 4.0])], &["Ci"]);
    // c = (-1) + 3 = 2 per channel; shade(c) * twice(-1) = 1 * -2; minus I.
    assert_eq!(out[0], vec![-3.0, -4.0, -6.0]);
    // Only a storage class may qualify a result.
    let checked = patina_compiler::check_source(
        "test.sl",
        "output float f() { return 1; } surface t() { Ci = f(); }",
        &MemoryLoader::default(),
    );
    let codes: Vec<&str> = checked.diagnostics.iter().map(|d| d.code.as_str()).collect();
    assert_eq!(codes, ["E0519"], "{:?}", checked.diagnostics);
}

/// Issue 24: a function defined inside another (RSL since PRMan 3.8) is the outer function's own,
/// defined afresh at each call: calling the outer function twice is neither a redefinition
/// (E0508) nor an ambiguous call (E0504), and the inner function sees the outer's variables.
#[test]
fn nested_functions_are_defined_at_each_call() {
    let src = "float outer(float x) {
            float scale = 3;
            float inner(float y) { return y * scale; }
            return inner(x) + 1;
        }
        float twice(float x) { return outer(x) + outer(x * 2); }
        surface t() { Ci = twice(s) + outer(t); }";
    let out = run(src, 2, &[("s", &[1.0, 0.5]), ("t", &[2.0, 0.0])], &["Ci"]);
    // outer(x) = 3x + 1, so Ci = (3s + 1) + (6s + 1) + (3t + 1).
    let expected = |s: f64, t: f64| 9.0 * s + 3.0 * t + 3.0;
    assert_eq!(out[0], [[expected(1.0, 2.0); 3], [expected(0.5, 0.0); 3]].concat());
}

#[test]
fn parameter_defaults_may_call_functions_and_library_built_ins() {
    // The calls in a default (a user function, a built-in the library implements) are statements
    // the semantic stage puts ahead of the body; the default still has their value.
    let src = "float twice(float x) { return 2 * x; }
        surface t(float a = twice(3); float b = distance(point(0, 0, 0), point(3, 4, 0));
                  float c = 1 + twice(b)) { Ci = color(a, b, c); }";
    let program = compile(src, &Binding::default());
    let mut eval = Evaluator::<f64>::new(&program);
    let out = eval.eval_points(2, &[], &["Ci"]).unwrap();
    assert_eq!(out[0], vec![6.0, 5.0, 11.0, 6.0, 5.0, 11.0]);
    // A value the caller gives replaces its default, and the later defaults read it.
    eval.set("b", &[7.0]).unwrap();
    let out = eval.eval_points(1, &[], &["Ci"]).unwrap();
    assert_eq!(out[0], vec![6.0, 7.0, 15.0]);
}
