//! CPU-vs-GPU conformance: every built-in operation and function runs on the interpreter (the
//! reference) and, as a compute kernel built by the WGSL backend, on the GPU, over the same
//! inputs; the results must agree exactly where WGSL is exact and within a documented tolerance
//! (the table in [`tol`]) where it is not.
//!
//! Each case is a function call with typed arguments. Every mix of argument rates is generated
//! (an argument is either a `uniform` parameter, set once per batch of the interpreter, or a
//! `varying` one, a column per point), because the interpreter computes uniform operands in
//! uniform registers once per batch and varying ones per lane, and both paths must agree with
//! the GPU. Many cases go into one shader so a test compiles one kernel. Predefined varying
//! variables (`s`, `t`, `P`, `N`, `I`, `Cs`) are covered by their own test. The case lists and
//! the tolerance table live in `conformance/cases.rs`, shared with `conformance/render.rs`, which
//! runs the same cases through the real vertex -> fragment path.
//!
//! The tests need a GPU adapter (lavapipe is enough) and panic without one, unless
//! `PATINA_GPU=off`.

use crate::cases::{Case, Dom, R2, UNIT, declare, mixes, sample, tol};
use crate::harness::{Input, Spec, Tol};
use crate::{cases, harness};
use patina_compiler::backend::binding::LightBinding;
use patina_compiler::backend::wgsl::Lowering;
use patina_runtime::gpu::{self, Gpu};

// -------------------------------------------------------------------------------------------------
// The compute harness's shaders and values.

/// The shader for a group of cases: parameters `c{i}a{k}u` (uniform) and `c{i}a{k}v` (varying)
/// for argument k of case i, outputs `o{i}m{mix}_{j}`.
fn shader(cases: &[Case]) -> (String, Vec<(String, Tol)>) {
    let mut params = Vec::new();
    let mut body = String::new();
    let mut outputs = Vec::new();
    for (i, c) in cases.iter().enumerate() {
        for (k, (ty, _)) in c.args.iter().enumerate() {
            params.push(format!("uniform {}", declare(ty, &format!("c{i}a{k}u"))));
            params.push(format!("varying {}", declare(ty, &format!("c{i}a{k}v"))));
        }
        for m in mixes(c.args.len()) {
            let mut line = c.body.to_string();
            for (j, (ty, tol)) in c.outs.iter().enumerate() {
                let name = format!("o{i}m{m}_{j}");
                params.push(format!("output varying {}", declare(ty, &name)));
                let tol = if matches!(*ty, "int" | "uint" | "bool") { Tol::Int } else { *tol };
                outputs.push((name.clone(), tol));
                line = if c.outs.len() == 1 {
                    line.replace("$o", &name)
                } else {
                    line.replace(&format!("$o{j}"), &name)
                };
            }
            for k in (0..c.args.len()).rev() {
                let rate = if m & (1 << k) != 0 { 'v' } else { 'u' };
                line = line.replace(&format!("${k}"), &format!("c{i}a{k}{rate}"));
            }
            body.push_str("    ");
            body.push_str(&line);
            body.push('\n');
        }
    }
    let src = format!("surface conformance(\n    {}\n) {{\n{body}}}\n", params.join(";\n    "));
    (src, outputs)
}

/// `o12m3_0` -> `c12a`: the parameters of the case an output belongs to.
fn related(output: &str) -> String {
    case_index(output).map_or_else(String::new, |i| format!("c{i}a"))
}

/// `o12m3_0` -> 12: the case an output belongs to.
fn case_index(output: &str) -> Option<usize> {
    let digits: String = output.strip_prefix('o')?.chars().take_while(|c| c.is_ascii_digit()).collect();
    digits.parse().ok()
}

/// The domain of a case parameter `c{i}a{k}{u,v}`.
fn case_domain(cases: &[Case], name: &str) -> Option<Dom> {
    let rest = name.strip_prefix('c')?;
    let (i, rest) = rest.split_once('a')?;
    let k = rest.trim_end_matches(['u', 'v']);
    let case = cases.get(i.parse::<usize>().ok()?)?;
    Some(case.args.get(k.parse::<usize>().ok()?)?.1)
}

/// Values for inputs that are not case parameters: predefined variables, seeds, light values.
fn default_domain(name: &str) -> Dom {
    match name {
        "Cs" | "Os" => UNIT,
        n if n.starts_with("Cl[") => UNIT,
        _ => R2,
    }
}

/// Batches and points per batch: 16 batches of uniform values, 64 points each (1024 GPU
/// invocations per kernel).
const BATCHES: usize = 16;
const POINTS: usize = 64;

/// Runs a group of cases on both backends.
fn run_cases(cases: &[Case], lights: &[LightBinding]) {
    run_lowered(cases, lights, Lowering::Exact);
}

/// Runs a group of cases on both backends, the GPU's kernel written in `lowering`; in the fast
/// lowering every output is held to [`fast_tolerance`] instead of its own.
fn run_lowered(cases: &[Case], lights: &[LightBinding], lowering: Lowering) {
    let Some(gpu) = gpu::for_tests() else { return };
    let (src, mut outputs) = shader(cases);
    if lowering == Lowering::Fast {
        for (name, tol) in &mut outputs {
            let projective = case_index(name).is_some_and(|i| {
                let c = &cases[i];
                c.outs.iter().any(|(ty, _)| *ty == "point") && c.args.iter().any(|(ty, _)| *ty == "matrix")
            });
            *tol = if projective { FAST_PROJECTIVE } else { fast_tolerance(*tol) };
        }
    }
    let spec =
        Spec { src, lights: lights.to_vec(), batches: BATCHES, points: POINTS, outputs, related, lowering };
    let values = |input: &Input| {
        let dom = match case_domain(cases, input.name) {
            Some(dom) => {
                // The rate mixes are only tested if the interpreter gives the parameters the
                // rates they are declared with: one register per batch, or one per point.
                let declared_uniform = input.name.ends_with('u');
                assert_eq!(input.uniform, declared_uniform, "the interpreter's rate of `{}`", input.name);
                dom
            }
            None => default_domain(input.name),
        };
        sample(dom, input)
    };
    harness::run(gpu, &spec, &values);
}

/// Runs a hand-written shader whose outputs are named in `outputs`.
fn run_shader(gpu: &Gpu, src: &str, lights: &[LightBinding], outputs: &[(&str, Tol)]) {
    let spec = Spec {
        src: src.to_string(),
        lights: lights.to_vec(),
        batches: 4,
        points: POINTS,
        outputs: outputs.iter().map(|(n, t)| (n.to_string(), *t)).collect(),
        related: |_| String::new(),
        lowering: Lowering::Exact,
    };
    harness::run(gpu, &spec, &|input| sample(default_domain(input.name), input));
}

/// What the fast lowering may differ by: its built-ins (`dot`, `length`, `normalize`,
/// `reflect`, matrix products, `inverseSqrt`, `sign`) round as the driver's instructions do (a
/// multiply-add may be fused, a reciprocal square root approximated), so a result may move by a
/// few ulp of its largest term. The cases' arguments are at most 4 in magnitude (or, for
/// `length`, anything, where the relative bound holds), so `FAST_ABS` bounds the cancellation
/// in a sum of products; integer and boolean results must still be the same bits.
fn fast_tolerance(exact: Tol) -> Tol {
    match exact {
        Tol::Int => Tol::Int,
        Tol::Near { abs, rel } => Tol::Near { abs: abs.max(FAST_ABS), rel: rel.max(FAST_REL) },
        _ => Tol::Near { abs: FAST_ABS, rel: FAST_REL },
    }
}

/// A point transformed by a matrix argument in the fast lowering: the point is divided by its
/// transformed w, which a random matrix can bring near 0, so the products' rounding is magnified
/// by 1/|w| (the sample reaches |w| of about 1e-3, where x / w is 6e3); the f32 interpreter's
/// own error against f64 is magnified alike there. Measured on lavapipe over the suite's
/// sample: 2765 ulp, a relative error of 3.3e-4.
const FAST_PROJECTIVE: Tol = Tol::Near { abs: FAST_ABS, rel: 5e-4 };

/// See [`fast_tolerance`].
const FAST_ABS: f64 = 2e-5;
/// See [`fast_tolerance`].
const FAST_REL: f64 = 2e-6;

// -------------------------------------------------------------------------------------------------
// Tests.

/// The built-ins the fast lowering writes differently, and everything built on them, in the fast
/// lowering: within [`fast_tolerance`] of the interpreter.
#[test]
fn fast_lowering_geometry_and_exact_math() {
    run_lowered(&cases::exact_math(), &[], Lowering::Fast);
    run_lowered(&cases::geometric_functions(), &[], Lowering::Fast);
    run_lowered(&cases::stanford_vector_functions_and_select(), &[], Lowering::Fast);
}

/// As [`fast_lowering_geometry_and_exact_math`]: spaces, matrices and the light sums.
#[test]
fn fast_lowering_transformations_and_light_sums() {
    run_lowered(&cases::transformations_and_matrices(), &[], Lowering::Fast);
    run_lowered(&cases::light_sums(), &cases::light_sum_lights(), Lowering::Fast);
}

#[test]
fn trigonometry_and_exponentials() {
    run_cases(&cases::trigonometry_and_exponentials(), &[]);
}

#[test]
fn exact_math() {
    run_cases(&cases::exact_math(), &[]);
}

#[test]
fn integer_functions_and_operators() {
    run_cases(&cases::integer_functions_and_operators(), &[]);
}

#[test]
fn float_and_vector_operators() {
    run_cases(&cases::float_and_vector_operators(), &[]);
}

#[test]
fn geometric_functions() {
    run_cases(&cases::geometric_functions(), &[]);
}

#[test]
fn transformations_and_matrices() {
    run_cases(&cases::transformations_and_matrices(), &[]);
}

/// RenderMan's `a / M` (`a * inverse(M)`), with the interpreter's inverse and product on both.
#[test]
fn matrix_division() {
    run_cases(&cases::matrix_division(), &[]);
}

#[test]
fn colour_spaces() {
    run_cases(&cases::colour_spaces(), &[]);
}

#[test]
fn noise_float() {
    run_cases(&cases::noise(cases::NoiseGroup::Float), &[]);
}

#[test]
fn noise_colour() {
    run_cases(&cases::noise(cases::NoiseGroup::Colour), &[]);
}

#[test]
fn noise_cell() {
    run_cases(&cases::noise(cases::NoiseGroup::Cell), &[]);
}

#[test]
fn noise_periodic() {
    run_cases(&cases::noise(cases::NoiseGroup::Periodic), &[]);
}

#[test]
fn splines() {
    run_cases(&cases::splines(), &[]);
}

#[test]
fn array_reads() {
    run_cases(&cases::array_reads(), &[]);
}

#[test]
fn light_sums() {
    run_cases(&cases::light_sums(), &cases::light_sum_lights());
}

#[test]
fn derivatives() {
    run_cases(&cases::derivatives(), &[]);
}

#[test]
fn stanford_vector_functions_and_select() {
    run_cases(&cases::stanford_vector_functions_and_select(), &[]);
}

#[test]
fn strings_are_folded() {
    run_cases(&cases::strings_are_folded(), &[]);
}

#[test]
fn predefined_varying_inputs() {
    // The varying globals as arguments, alone and mixed with a uniform parameter.
    let Some(gpu) = gpu::for_tests() else { return };
    let src = "
        surface globals(uniform float k = 0.5;
            output varying float a = 0; output varying float b = 0; output varying color c = 0;
            output varying vector d = 0; output varying float e = 0; output varying point f = 0) {
            a = s * t + u - v * k;
            b = length(P) + distance(P, point(k, 0, 1)) + mod(s, k + 1.5);
            c = Cs * mix(s, t, k) + color(clamp(u, 0, k), max(v, s), floor(t * 7));
            d = normalize(N) + faceforward(N, I) + reflect(I, normalize(N)) * k;
            e = smoothstep(0, k, s) + step(t, k) + xcomp(P) * ycomp(I);
            f = P + transform(\"current\", P) * k + spline(s, P, I, P, I);
        }";
    let outputs = [
        ("a", tol::EXACT),
        ("b", tol::EXACT),
        ("c", tol::MIN_MAX),
        ("d", tol::EXACT),
        ("e", tol::MIN_MAX),
        ("f", tol::MIN_MAX),
    ];
    run_shader(gpu, src, &[], &outputs);
}

#[test]
fn random_hashes_the_point_index_on_both() {
    // `random()` is a hash of the point's index (the kernel's invocation index, the interpreter's
    // point in the evaluation) and the call site, numbered per component in the same order.
    let Some(gpu) = gpu::for_tests() else { return };
    let src = "surface r(output varying float o = 0; output varying color c = 0) {
            o = random();
            c = random() * 0.5 + color random();
        }";
    run_shader(gpu, src, &[], &[("o", tol::EXACT), ("c", tol::EXACT)]);
}

#[test]
fn stanford_shader_with_lights() {
    // A Stanford-style surface: per-light values summed by `integrate`, vertex and
    // primitive-group parameters, float3/float4 arithmetic, `select` and `clamp01`.
    let Some(gpu) = gpu::for_tests() else { return };
    let src = "
        surface shader float4 stanford(vertex float4 uv, primitive group float k) {
            perlight float3 c = rgb(Cl) * max(dot(L, {0, 0, 1}), 0) * k;
            float3 x = {uv[0], uv[1], k};
            float4 q = {uv[2], k, uv[0], 1};
            float3 y = select(uv[3] > k, cross(x, rgb(q)), normalize(x));
            return {integrate(c) + clamp01(x) + y, dot(q, q) + length(x)};
        }";
    let lights = vec![LightBinding::default(), LightBinding::default()];
    run_shader(gpu, src, &lights, &[("result", tol::REASSOCIATED)]);
}

/// The real vertex -> fragment path for the built-ins a kernel cannot run: named coordinate
/// systems come from the uniform block (the kernel binds none), here with composites that read
/// them. A plane rendered by both renderers; they interpolate the same vertex values at the same
/// sample positions, so only f32 rounding (and the f32 inverse of each space the runtime uploads)
/// separates the images.
#[test]
fn render_path_named_spaces_and_composites() {
    use patina_runtime::image::{Thresholds, compare};
    use patina_runtime::render::{self, Backend};
    use patina_runtime::scene::Scene;
    let Some(gpu) = gpu::for_tests() else { return };
    let shader = "surface composite(float k = 0.5) {
        point pw = transform(\"world\", P);
        vector vo = vtransform(\"object\", I);
        normal nw = ntransform(\"world\", \"object\", N);
        point ps = transform(\"shader\", \"current\", point \"object\" (s, t, k));
        color hsv = ctransform(\"hsv\", \"rgb\", color(s, 0.5 + 0.5 * t, k));
        color back = ctransform(\"hsl\", color(s, t, k)) + color \"xyY\" (0.3, 0.3, t);
        float kr, kt;
        fresnel(I, N, 1.3, kr, kt);
        point r = rotate(point(s, t, 0), k, point(0, 0, 0), point(0, 0, 1));
        float sp = spline(\"bspline\", s, 0, 1, 0.25, 0.75, 0.5, 1);
        matrix m = rotate(translate(matrix \"world\" 1, vector(1, 2, 3)), k, vector(0, 1, 0));
        point pm = transform(invert(m), pw);
        Ci = color(0.5 + 0.05 * xcomp(pw) + 0.02 * ycomp(vo), 0.5 + 0.05 * zcomp(nw) * kt, sp) * 0.5
            + (hsv + back) * 0.1 + color(xcomp(r), ycomp(r), kr) * 0.1
            + color(xcomp(ps), ycomp(pm), zcomp(ps)) * 0.01;
        Oi = 1;
    }";
    let dir = std::env::temp_dir().join(format!("patina-conformance-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("s.sl"), shader).unwrap();
    let scene = "[output]\nwidth = 32\nheight = 32\n[camera]\nfrom = [0.0, 0.5, -3.0]\nto = [0.0, 0.0, 0.0]\n\
         up = [0.0, 1.0, 0.0]\nfov = 40\n[[object]]\nmesh = \"plane\"\ndetail = 4\nshader = \"s.sl\"\n\
         params = { k = 0.75 }\n\
         transform = [{ rotate = { angle = 30, axis = [0.0, 1.0, 0.0] } }, { translate = [0.2, 0.1, 0.5] }]\n";
    let scene = Scene::parse(scene, dir.join("s.toml"), &dir).unwrap_or_else(|e| panic!("{e}"));
    let prepared = render::prepare(&scene).unwrap_or_else(|e| panic!("{e}"));
    let cpu = render::render(&prepared, Backend::Cpu, None).unwrap_or_else(|e| panic!("{e}"));
    let gpu = render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap_or_else(|e| panic!("{e}"));
    let t = Thresholds { fail: 1e-4, hard_fail: 1e-3, max_failing_fraction: 0.01 };
    let c = compare(&cpu, &gpu, &t).unwrap();
    assert!(c.passes(&t), "GPU and CPU images differ: {c:?}");
    let covered = cpu.pixels.iter().filter(|p| p[3] > 0.5).count();
    assert!(covered > cpu.pixels.len() / 3, "the plane covers only {covered} pixels");
}

#[test]
fn integer_division_by_a_literal_zero() {
    // naga rejects an integer `/` or `%` whose divisor is a constant zero (found by
    // `generated.rs`: `(1 / 0)` in a shader did not validate); WGSL's values at run time, which
    // the interpreter computes, are x / 0 = x and x % 0 = 0.
    let Some(gpu) = gpu::for_tests() else { return };
    let src =
        "surface z(output varying float a = 0; output varying float b = 0; output varying float c = 0) {
            int i = int(s * 8) - 3;
            uint n = uint(t * 8);
            a = float(i / 0) + float(7 / 0) * 10;
            b = float(i % 0) + float((i + 5) % 0) + float(n % 0u);
            c = float(n / 0u) + float(i / -0);
        }";
    run_shader(gpu, src, &[], &[("a", tol::EXACT), ("b", tol::EXACT), ("c", tol::EXACT)]);
}

#[test]
fn nested_integrate_on_both() {
    // An `integrate` inside a per-light value sums over every light on both backends (found by
    // `generated.rs`: the interpreter used the outer light's term).
    let Some(gpu) = gpu::for_tests() else { return };
    let src = "
        surface shader float4 nested(vertex float4 uv) {
            perlight float3 a = rgb(Cl) * uv[0];
            perlight float b = dot(L, {0, 0, 1});
            return {integrate(integrate(a) * b), uv[1]};
        }";
    let lights = vec![LightBinding::default(), LightBinding::default(), LightBinding::default()];
    run_shader(gpu, src, &lights, &[("result", tol::REASSOCIATED)]);
}
