//! Derivatives by forward-mode AD (`opt::derivs`, run by the interpreter) against central finite
//! differences of the same shader, both evaluated in f64.
//!
//! Each case computes `x` from the surface parameters and writes `Du(x)`, `Dv(x)` and the derived
//! filter quantities. The inputs `s`, `t` (and `u`, `v`, which carry the same values) get screen
//! derivatives of a sheared, scaled pixel footprint, so `Du`/`Dv` exercise the full 2x2 solve
//! from screen derivatives back to parameter derivatives. The finite differences step `u`, `v`
//! directly.
//!
//! Tolerance: |AD - FD| <= 1e-7 (1 + |FD|). With h = 1e-5 in f64 the central difference's own
//! error is about h^2 |x'''| / 6 + eps |x| / h, below 1e-9 for these expressions; an error in a
//! chain rule is of the order of the derivative itself.

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_compiler::syntax::preprocess::MemoryLoader;

/// The screen derivatives of (u, v): a footprint that is neither axis-aligned nor unit.
const SEEDS: [(&str, f64); 8] = [
    ("dx(u)", 0.8),
    ("dy(u)", 0.3),
    ("dx(v)", -0.2),
    ("dy(v)", 1.1),
    ("dx(s)", 0.8),
    ("dy(s)", 0.3),
    ("dx(t)", -0.2),
    ("dy(t)", 1.1),
];

const POINTS: [(f64, f64); 5] = [(0.31, 0.47), (0.63, 0.22), (0.12, 0.81), (0.77, 0.58), (0.45, 0.95)];
const H: f64 = 1e-5;

/// Compiles `body` (which sets `float x`) into a shader reporting x and its derivatives.
fn program(body: &str) -> CpuProgram {
    let source = format!(
        "surface t() {{\n  float x;\n  {body}\n  Ci = color(x, Du(x), Dv(x));\n  Oi = color(filterwidth(x), Deriv(x, u), filterstep(0.5, x));\n}}\n"
    );
    crate::support::compile(&source, &Binding::default())
}

/// Checks AD against finite differences at every point, for the shader computing `x` by `body`.
fn check(body: &str) {
    let program = program(body);
    let mut eval = Evaluator::<f64>::new(&program);
    for (name, value) in SEEDS {
        // A shader that never reads `s` has no seed for it; that is fine.
        let _ = eval.set(name, &[value]);
    }
    // For each point: the point itself, then u +- h, then v +- h.
    let mut us = Vec::new();
    let mut vs = Vec::new();
    for &(u, v) in &POINTS {
        for (du, dv) in [(0.0, 0.0), (H, 0.0), (-H, 0.0), (0.0, H), (0.0, -H)] {
            us.push(u + du);
            vs.push(v + dv);
        }
    }
    let n = us.len();
    let inputs: Vec<(&str, &[f64])> = ["u", "s", "v", "t"]
        .into_iter()
        .filter(|name| program.slot(name).is_some())
        .map(|name| (name, if name == "u" || name == "s" { &us[..] } else { &vs[..] }))
        .collect();
    let out = eval.eval_points(n, &inputs, &["Ci", "Oi"]).unwrap();
    let (ci, oi) = (&out[0], &out[1]);
    for (i, point) in POINTS.iter().enumerate() {
        let at = |k: usize, c: usize| ci[(i * 5 + k) * 3 + c];
        let fd_u = (at(1, 0) - at(2, 0)) / (2.0 * H);
        let fd_v = (at(3, 0) - at(4, 0)) / (2.0 * H);
        let close = |ad: f64, fd: f64| (ad - fd).abs() <= 1e-7 * (1.0 + fd.abs());
        let (du, dv) = (at(0, 1), at(0, 2));
        assert!(close(du, fd_u), "{body}\nat {point:?}: Du = {du}, finite difference {fd_u}");
        assert!(close(dv, fd_v), "{body}\nat {point:?}: Dv = {dv}, finite difference {fd_v}");
        // The screen derivatives follow from the parameter ones and the footprint.
        let dx = fd_u * 0.8 + fd_v * -0.2;
        let dy = fd_u * 0.3 + fd_v * 1.1;
        let o = |c: usize| oi[(i * 5) * 3 + c];
        let width = dx.abs() + dy.abs();
        assert!(close(o(0), width), "{body}\nat {point:?}: filterwidth {} vs {width}", o(0));
        // Deriv(x, u) = Du(x)/Du(u) + Dv(x)/Dv(u), and Dv(u) = 0: the second term is dropped.
        assert!(close(o(1), fd_u), "{body}\nat {point:?}: Deriv(x, u) = {} vs {fd_u}", o(1));
        let x = at(0, 0);
        let box_step =
            if width > 0.0 { ((x - 0.5) / width + 0.5).clamp(0.0, 1.0) } else { f64::from(x >= 0.5) };
        assert!((o(2) - box_step).abs() <= 1e-7, "{body}\nat {point:?}: filterstep {} vs {box_step}", o(2));
    }
}

#[test]
fn polynomials() {
    check("x = u * u * v - 3 * u + v * v * v + 0.25;");
    check("x = (u - v) * (u + 2 * v) / (1 + u * u);");
}

#[test]
fn transcendental_chains() {
    check("x = sin(exp(u) * v);");
    check("x = pow(u + 2, v + 1.5);");
    check("x = log(u + 3) * sqrt(u * u + v * v + 1) + atan(u, v + 1);");
    check("x = cos(u * 7) * tan(v) + asin(u * 0.9) - acos(v * 0.5) + inversesqrt(u + 1);");
    check("x = exp(sin(u * v * 10)) / (2 + cos(pow(v + 1, u)));");
}

#[test]
fn shaping_functions() {
    check("x = smoothstep(0.2, 0.8, u * v + u * 0.5);");
    check("x = mix(u * u, sin(v), u * v);");
    check("x = clamp(u * 3 - 1, 0.1, 0.9) + abs(v - 0.5) + max(u, v * v) - min(u * 2, 0.7);");
    check("x = mod(u * 5, 0.7) + v;");
}

#[test]
fn vectors() {
    check("vector n = normalize(vector(u, v * u, 1)); x = xcomp(n) + 2 * ycomp(n) - zcomp(n);");
    check("vector a = vector(u, v, u * v); vector b = vector(v, 1, u); x = length(a ^ b) + a . b;");
    check("point p = point(u, v, 0); point q = point(v, u * u, 1); x = distance(p, q);");
    check("color c = color(u, v, 1) * color(v, u, u); x = comp(c, 0) + comp(c, 1) * comp(c, 2);");
}

#[test]
fn geometry_written_in_the_language() {
    // Library code (compiler/stdlib/builtins.sl), differentiated through its body: every argument
    // of the rotations (angle and axis too) and fresnel's outputs.
    check("x = ptlined(point(0, 0, 0), point(1, v, 0.5), point(u, 1, v));");
    check(
        "point q = rotate(point(u, 1, 2), v * 3, point(0, u, 0), point(1, 1, v + 1));
         x = xcomp(q) + 2 * ycomp(q) - zcomp(q);",
    );
    check(
        "matrix m = rotate(translate(scale(matrix 1, point(1 + u, 2, v + 1)), vector(v, u, 1)), u * 2,
                           vector(1, v, u));
         x = determinant(m) + comp(m, 0, 1) + comp(m, 2, 0) * comp(m, 3, 1);",
    );
    check(
        "float kr, kt; vector r, tr;
         fresnel(vector(u - 0.5, v - 0.5, -1), normal(0, 0.2, 1), 0.7, kr, kt, r, tr);
         x = kr + 2 * kt + xcomp(r) * ycomp(tr);",
    );
}

#[test]
fn control_flow() {
    // A loop accumulating terms, with a varying trip count.
    check("float i; x = 0; for (i = 1; i < 3 + 4 * u; i += 1) { x += sin(i * u) / i; }");
    // A branch that differs between points, and a conditional expression.
    check("if (u > 0.5) { x = u * u * v; } else { x = v * 3 + u; } x = x + (v > 0.5 ? v * v : u);");
    // A user function, inlined.
    check("float f(float a; float b) { return a * sin(b) + b; } x = f(u, v) * f(v, u);");
}

#[test]
fn derivatives_of_uniform_values_are_exactly_zero() {
    let program = program("uniform float k = 3; x = k * k;");
    let mut eval = Evaluator::<f64>::new(&program);
    let out = eval.eval_points(1, &[], &["Ci", "Oi"]).unwrap();
    assert_eq!(out[0], vec![9.0, 0.0, 0.0]);
    assert_eq!(out[1][0], 0.0, "filterwidth of a uniform value");
    assert_eq!(out[1][2], 1.0, "filterstep of a uniform value is a plain step");
}

/// `area` and `calculatenormal` from the screen derivatives of `P`: for a plane P = (u, v, 0)
/// mapped by the footprint, dP/dx = (0.8, -0.2, 0) and dP/dy = (0.3, 1.1, 0).
#[test]
fn area_and_calculatenormal_of_a_plane() {
    let source = "surface t() { Ci = color(area(P), 0, 0); Oi = color(calculatenormal(P)); }";
    let checked = patina_compiler::check_source("t.sl", source, &MemoryLoader::default());
    let program = CpuProgram::compile(
        &patina_compiler::opt::Prepared::new(checked.program.shaders[0].clone()),
        &Binding::default(),
    )
    .unwrap();
    let mut eval = Evaluator::<f64>::new(&program);
    eval.set("dx(P)", &[0.8, -0.2, 0.0]).unwrap();
    eval.set("dy(P)", &[0.3, 1.1, 0.0]).unwrap();
    for (name, value) in &SEEDS[..4] {
        eval.set(name, &[*value]).unwrap();
    }
    let out = eval.eval_points(1, &[], &["Ci", "Oi"]).unwrap();
    let cross_z = 0.8 * 1.1 - (-0.2 * 0.3);
    assert!((out[0][0] - cross_z).abs() < 1e-12, "area {}", out[0][0]);
    // Du(P) x Dv(P) for P = (u, v, 0) is (0, 0, 1).
    let n = &out[1];
    assert!(n[0].abs() < 1e-12 && n[1].abs() < 1e-12 && (n[2] - 1.0).abs() < 1e-12, "{n:?}");
}
