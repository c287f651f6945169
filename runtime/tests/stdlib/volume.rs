//! The standard library's volume and hypertexture module (`compiler/stdlib/volume.sl`) on the interpreter
//! (f32 and f64) and on the GPU (the WGSL backend's compute kernel, lavapipe), against references
//! written here from the sources' definitions (Perlin & Hoffert's soft sphere and booleans, the
//! printed Wyvill polynomial, the standard Henyey-Greenstein formula, `-expm1(-x)` for the step
//! opacity), closed forms and numerical integrals.
//!
//! What is measured (run with `--nocapture` to see the numbers):
//! - soft shapes against the paper's squared form (r0^2 - rx^2) / (r0^2 - r1^2), within a few ulp
//!   scaled by the slope of the profile r0^2 / (r0^2 - r1^2) (`SHAPE_ULPS`);
//! - booleans against a + b - ab, ab, a - ab, 1 - a, results never outside [0, 1];
//! - the step opacity against `-expm1(-x)` over 1e-30..50 (relative, `OPACITY_REL`), N equal steps
//!   against one step of N times the depth and against the closed form, saturation at depth 1e4;
//! - normals: exact for linear densities, radial on the soft sphere (central differences of a
//!   quadratic are exact), the fallbacks at zero gradients;
//! - Henyey-Greenstein against the formula and its integral over the sphere (= 1) for
//!   g from -1 to 1; Wyvill's cubic against the printed polynomial, its values and C1 at R;
//! - the noise-based densities as compositions of the soft-sphere reference with the noise values;
//! - the stability sweep: every function over the extreme inputs, finite and in range on the
//!   interpreter (f32, f64) and the GPU; the GPU against the f32 interpreter within `GPU_TOL`.

use crate::support;

use crate::support::Rng;

/// Rounds to f32 (every test input is f32-representable, so that the f32 and f64 runs and the
/// references see the same arguments).
fn f(x: f64) -> f64 {
    f64::from(x as f32)
}

/// Machine epsilon of the two interpreter precisions, indexed as `[f64, f32]`.
const EPS: [f64; 2] = [f64::EPSILON, f32::EPSILON as f64];

/// A test shader: `varying` inputs and `output varying` outputs given as (type, name), and a body.
fn shader(inputs: &[(&str, &str)], outputs: &[(&str, &str)], body: &str) -> support::Program {
    let mut params: Vec<String> = inputs.iter().map(|(ty, n)| format!("varying {ty} {n} = 0")).collect();
    params.extend(outputs.iter().map(|(ty, n)| format!("output varying {ty} {n} = 0")));
    let src = format!("#include <volume.sl>\nsurface t({}) {{\n{body}\n}}\n", params.join("; "));
    support::program(&src)
}

/// Named input columns.
#[derive(Default)]
struct Inputs {
    cols: Vec<(&'static str, Vec<f64>)>,
}

impl Inputs {
    fn add(&mut self, name: &'static str, col: Vec<f64>) -> &mut Self {
        self.cols.push((name, col));
        self
    }
    fn columns(&self) -> Vec<(&str, &[f64])> {
        self.cols.iter().map(|(n, c)| (*n, c.as_slice())).collect()
    }
}

/// Runs on the interpreter in f64 and f32: `[f64 outputs, f32 outputs]`.
fn cpu_both(program: &support::Program, n: usize, inputs: &Inputs, outputs: &[&str]) -> [Vec<Vec<f64>>; 2] {
    let cols = inputs.columns();
    [program.cpu::<f64>(n, &cols, outputs), program.cpu::<f32>(n, &cols, outputs)]
}

fn flat3(points: &[[f64; 3]]) -> Vec<f64> {
    points.iter().flatten().copied().collect()
}

/// References written from the sources.
mod reference {
    /// Perlin & Hoffert's soft sphere profile on the squared radius (PH L69), with radii r1, r0.
    pub fn profile_sq(rx2: f64, r1: f64, r0: f64) -> f64 {
        if rx2 <= r1 * r1 {
            1.0
        } else if rx2 >= r0 * r0 {
            0.0
        } else {
            (r0 * r0 - rx2) / (r0 * r0 - r1 * r1)
        }
    }

    /// The inner and outer radii of a shape of radius r and softness s (inner clamped to 0).
    pub fn radii(r: f64, s: f64) -> (f64, f64) {
        let (r, s) = (r.max(0.0), s.max(0.0));
        ((r - s / 2.0).max(0.0), r + s / 2.0)
    }

    /// The profile's slope factor 1 + r0^2 / (r0^2 - r1^2): rounding errors of the radius are
    /// magnified by it.
    pub fn slope(r1: f64, r0: f64) -> f64 {
        if r0 > r1 { 1.0 + r0 * r0 / (r0 * r0 - r1 * r1) } else { 1.0 }
    }

    pub fn soft_sphere(p: [f64; 3], c: [f64; 3], r: f64, s: f64) -> f64 {
        let (r1, r0) = radii(r, s);
        profile_sq((0..3).map(|i| (p[i] - c[i]).powi(2)).sum(), r1, r0)
    }

    pub fn soft_box(p: [f64; 3], c: [f64; 3], h: [f64; 3], s: f64) -> f64 {
        (0..3)
            .map(|i| {
                let (r1, r0) = radii(h[i], s);
                profile_sq((p[i] - c[i]).powi(2), r1, r0)
            })
            .product()
    }

    pub fn soft_torus(p: [f64; 3], c: [f64; 3], major: f64, r: f64, s: f64) -> f64 {
        let ring = (p[0] - c[0]).hypot(p[1] - c[1]) - major.max(0.0);
        let (r1, r0) = radii(r, s);
        profile_sq(ring * ring + (p[2] - c[2]).powi(2), r1, r0)
    }

    /// The standard Henyey-Greenstein phase function.
    pub fn hg(c: f64, g: f64) -> f64 {
        (1.0 - g * g) / (4.0 * std::f64::consts::PI * (1.0 + g * g - 2.0 * g * c).powf(1.5))
    }

    /// Wyvill's cubic as printed (TM L6780), 0 beyond R.
    pub fn wyvill(r: f64, big_r: f64) -> f64 {
        if big_r <= 0.0 || r.abs() >= big_r {
            return 0.0;
        }
        let a = r * r / (big_r * big_r);
        -4.0 / 9.0 * a * a * a + 17.0 / 9.0 * a * a - 22.0 / 9.0 * a + 1.0
    }

    /// Perlin's bias and gain (PH L98, L106).
    pub fn bias(b: f64, t: f64) -> f64 {
        let (b, t) = (b.clamp(0.0, 1.0), t.clamp(0.0, 1.0));
        if t <= 0.0 {
            0.0
        } else if t >= 1.0 {
            1.0
        } else if b <= 0.0 {
            0.0
        } else if b >= 1.0 {
            1.0
        } else {
            t.powf(b.ln() / 0.5f64.ln())
        }
    }
    pub fn gain(g: f64, t: f64) -> f64 {
        if t < 0.5 { bias(1.0 - g, 2.0 * t) / 2.0 } else { 1.0 - bias(1.0 - g, 2.0 - 2.0 * t) / 2.0 }
    }
}

/// Shape errors allowed, in units of epsilon times the profile's slope factor.
const SHAPE_ULPS: f64 = 8.0;

/// A random unit vector.
fn direction(rng: &mut Rng) -> [f64; 3] {
    loop {
        let v = rng.point(-1.0, 1.0);
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if l > 0.1 && l <= 1.0 {
            return v.map(|x| x / l);
        }
    }
}

#[test]
fn soft_shapes_match_the_papers_profile() {
    let program = shader(
        &[("point", "p"), ("point", "c"), ("float", "r"), ("float", "s"), ("float", "R"), ("vector", "h")],
        &[("float", "sphere"), ("float", "box"), ("float", "torus"), ("float", "at_r")],
        "sphere = soft_sphere(p, c, r, s); box = soft_box(p, c, h, s); torus = soft_torus(p, c, R, r, s);\n\
         at_r = soft_sphere(c + vector(r, 0, 0), c, r, s);",
    );
    let mut rng = Rng(7);
    let (mut p, mut c, mut r, mut s, mut big_r, mut h) = (vec![], vec![], vec![], vec![], vec![], vec![]);
    for i in 0..3000 {
        let centre = rng.point(-2.0, 2.0).map(f);
        let radius = f(rng.range(0.1, 2.0));
        // Softness from 1e-4 to the whole radius and beyond, and the hard sphere.
        let soft = if i % 10 == 0 { 0.0 } else { f(10f64.powf(rng.range(-4.0, 0.5))) };
        let ring = f(rng.range(0.3, 2.0));
        let half = rng.point(0.1, 1.5).map(f);
        // Points near the sphere's soft shell, near a face of the box, near the torus, or anywhere.
        let point = match i % 4 {
            0 => {
                let d = direction(&mut rng);
                let at = radius + soft * rng.range(-0.7, 0.7);
                [0, 1, 2].map(|k| f(centre[k] + d[k] * at))
            }
            1 => {
                let mut q = [0, 1, 2].map(|k| centre[k] + half[k] * rng.range(-1.2, 1.2));
                let axis = (rng.unit() * 3.0) as usize;
                q[axis] = centre[axis]
                    + (half[axis] + soft * rng.range(-0.7, 0.7)) * if rng.unit() < 0.5 { -1.0 } else { 1.0 };
                q.map(f)
            }
            2 => {
                let phi = rng.range(0.0, std::f64::consts::TAU);
                let d = direction(&mut rng);
                let tube = (radius + soft * rng.range(-0.7, 0.7)).max(0.0);
                [ring * phi.cos() + tube * d[0], ring * phi.sin() + tube * d[1], tube * d[2]]
                    .map(|x| x * 0.5)
                    .iter()
                    .zip(&centre)
                    .map(|(x, o)| f(x * 2.0 + o))
                    .collect::<Vec<_>>()
                    .try_into()
                    .unwrap()
            }
            _ => rng.point(-4.0, 4.0).map(f),
        };
        p.push(point);
        c.push(centre);
        r.push(radius);
        s.push(soft);
        big_r.push(ring);
        h.push(half);
    }
    let n = p.len();
    let mut inputs = Inputs::default();
    inputs
        .add("p", flat3(&p))
        .add("c", flat3(&c))
        .add("r", r.clone())
        .add("s", s.clone())
        .add("R", big_r.clone())
        .add("h", flat3(&h));
    let outputs = ["sphere", "box", "torus", "at_r"];
    for (run, precision) in cpu_both(&program, n, &inputs, &outputs).iter().zip(["f64", "f32"]) {
        let eps = EPS[usize::from(precision == "f32")];
        let mut worst = [0.0f64; 3];
        let mut soft_points = 0;
        for i in 0..n {
            let (r1, r0) = reference::radii(r[i], s[i]);
            let expected = [
                reference::soft_sphere(p[i], c[i], r[i], s[i]),
                reference::soft_box(p[i], c[i], h[i], s[i]),
                reference::soft_torus(p[i], c[i], big_r[i], r[i], s[i]),
            ];
            let box_slope: f64 = (0..3)
                .map(|k| {
                    let (a, b) = reference::radii(h[i][k], s[i]);
                    reference::slope(a, b) * (1.0 + (p[i][k] - c[i][k]).abs() / b.max(1e-30)).min(4.0)
                })
                .sum();
            let torus_scale = 1.0 + (big_r[i] + r0) * (big_r[i] + r0) / (r0 * r0 - r1 * r1).max(1e-300);
            let scales = [reference::slope(r1, r0), box_slope, torus_scale];
            for k in 0..3 {
                let got = run[k][i];
                assert!((0.0..=1.0).contains(&got), "{} {precision} = {got} at point {i}", outputs[k]);
                if s[i] == 0.0 {
                    // The hard shapes: a point within rounding of the boundary may fall either way.
                    continue;
                }
                soft_points += usize::from(got > 0.0 && got < 1.0);
                let err = (got - expected[k]).abs() / (eps * scales[k]);
                worst[k] = worst[k].max(err);
                assert!(
                    err <= SHAPE_ULPS,
                    "{} {precision} at point {i}: {got} against {} ({err} eps)",
                    outputs[k],
                    expected[k]
                );
            }
            // On the radius itself: (r0^2 - r^2) / (r0^2 - r1^2) = 1/2 + s/(8r) while r >= s/2.
            if s[i] > 0.0 && s[i] <= r[i] {
                let closed = 0.5 + s[i] / (8.0 * r[i]);
                let err = (run[3][i] - closed).abs();
                assert!(
                    err <= 16.0 * eps * reference::slope(r1, r0),
                    "at_r {precision}: {} vs {closed}",
                    run[3][i]
                );
            }
        }
        println!(
            "shapes {precision}: worst error in eps x slope (sphere, box, torus) {worst:?}; {soft_points} values in the soft region"
        );
    }
}

#[test]
fn booleans_are_the_papers_algebra() {
    let program = shader(
        &[("float", "a"), ("float", "b")],
        &[("float", "u"), ("float", "i"), ("float", "d"), ("float", "na"), ("float", "dd")],
        "u = soft_union(a, b); i = soft_intersection(a, b); d = soft_difference(a, b);\n\
         na = soft_complement(a); dd = soft_intersection(a, soft_complement(b));",
    );
    let mut rng = Rng(11);
    let mut a = vec![];
    let mut b = vec![];
    for k in 0..2000 {
        let (x, y) = match k % 4 {
            0 => (rng.unit(), rng.unit()),
            1 => (1.0 - 1e-7 * rng.unit(), rng.unit()),
            2 => (rng.range(-2.0, 3.0), rng.range(-2.0, 3.0)),
            _ => ([0.0, 1.0, 0.5][k % 3], [1.0, 0.0, 1e-30][(k / 3) % 3]),
        };
        a.push(f(x));
        b.push(f(y));
    }
    let n = a.len();
    let mut inputs = Inputs::default();
    inputs.add("a", a.clone()).add("b", b.clone());
    let names = ["u", "i", "d", "na", "dd"];
    for (run, precision) in cpu_both(&program, n, &inputs, &names).iter().zip(["f64", "f32"]) {
        let eps = EPS[usize::from(precision == "f32")];
        let mut worst = 0.0f64;
        for k in 0..n {
            let (x, y) = (a[k].clamp(0.0, 1.0), b[k].clamp(0.0, 1.0));
            // The paper's forms (PH L77-80).
            let expected = [x + y - x * y, x * y, x - x * y, 1.0 - x, x * (1.0 - y)];
            for (j, e) in expected.iter().enumerate() {
                let got = run[j][k];
                assert!((0.0..=1.0).contains(&got), "{} {precision} ({x}, {y}) = {got}", names[j]);
                let err = (got - e).abs();
                worst = worst.max(err / eps);
                assert!(err <= 4.0 * eps, "{} {precision} ({x}, {y}): {got} against {e}", names[j]);
            }
            // Difference is intersection with the complement, exactly.
            assert_eq!(run[2][k], run[4][k]);
        }
        println!("booleans {precision}: worst error {worst} eps");
    }
}

#[test]
fn step_opacity_is_one_minus_exp_without_cancellation() {
    let program = shader(&[("float", "x")], &[("float", "alpha")], "alpha = volume_opacity(x);");
    let mut x: Vec<f64> = (0..4000).map(|i| f(10f64.powf(-30.0 + 31.75 * f64::from(i) / 4000.0))).collect();
    x.extend([0.0, -1.0, -1e30, 1e-45, 1.0 / 64.0, 40.0, 39.999, 1e4, 1e30, 3e38].map(f));
    let n = x.len();
    let mut inputs = Inputs::default();
    inputs.add("x", x.clone());
    for (run, precision) in cpu_both(&program, n, &inputs, &["alpha"]).iter().zip(["f64", "f32"]) {
        let eps = EPS[usize::from(precision == "f32")];
        let mut worst = 0.0f64;
        for (k, &xk) in x.iter().enumerate() {
            let got = run[0][k];
            assert!((0.0..=1.0).contains(&got), "volume_opacity {precision}({xk}) = {got}");
            let expected = -(-xk.max(0.0)).exp_m1();
            if xk <= 0.0 {
                assert_eq!(got, 0.0, "volume_opacity {precision}({xk})");
                continue;
            }
            if xk >= 40.0 {
                assert_eq!(got, 1.0, "volume_opacity {precision}({xk})");
                continue;
            }
            let rel = (got - expected).abs() / expected;
            worst = worst.max(rel / eps);
            assert!(
                rel <= OPACITY_REL * eps,
                "volume_opacity {precision}({xk}) = {got}, expected {expected}"
            );
        }
        println!("volume_opacity {precision}: worst relative error {worst} eps over depths 1e-30..56");
    }
}

/// The step opacity's relative error, in units of epsilon.
const OPACITY_REL: f64 = 4.0;

/// The compositing shader: n steps of (d, c, h) from the state (C0, A0), and one step of n h.
fn composite_program() -> support::Program {
    shader(
        &[("float", "n"), ("float", "d"), ("float", "h"), ("float", "A0"), ("color", "c"), ("color", "C0")],
        &[("color", "C"), ("float", "A"), ("color", "C1"), ("float", "A1")],
        "float4 acc = {C0, A0};\n\
         float i = 0;\n\
         while (i < n) { acc = volume_composite(acc, d, c, h); i += 1; }\n\
         C = rgb(acc); A = acc[3];\n\
         float4 one = volume_composite({C0, A0}, d, c, n * h);\n\
         C1 = rgb(one); A1 = one[3];",
    )
}

#[test]
fn n_equal_steps_composite_to_one_step_of_n_times_the_depth() {
    let program = composite_program();
    let mut rng = Rng(5);
    let (mut n, mut d, mut h, mut a0, mut c, mut c0) = (vec![], vec![], vec![], vec![], vec![], vec![]);
    for k in 0..240 {
        n.push([1.0, 2.0, 7.0, 64.0, 200.0, 500.0][k % 6]);
        d.push(f(10f64.powf(rng.range(-3.0, 2.0))));
        h.push(f(10f64.powf(rng.range(-4.0, -1.0))));
        a0.push(if k % 3 == 0 { 0.0 } else { f(rng.unit()) });
        c.push(rng.point(0.0, 2.0).map(f));
        c0.push(rng.point(0.0, 1.0).map(f));
    }
    let count = n.len();
    let mut inputs = Inputs::default();
    inputs
        .add("n", n.clone())
        .add("d", d.clone())
        .add("h", h.clone())
        .add("A0", a0.clone())
        .add("c", flat3(&c))
        .add("C0", flat3(&c0));
    for (run, precision) in
        cpu_both(&program, count, &inputs, &["C", "A", "C1", "A1"]).iter().zip(["f64", "f32"])
    {
        let eps = EPS[usize::from(precision == "f32")];
        let (mut worst_steps, mut worst_closed) = (0.0f64, 0.0f64);
        for k in 0..count {
            let (an, a1) = (run[1][k], run[3][k]);
            assert!(an <= 1.0 && a1 <= 1.0 && an >= a0[k] && a1 >= a0[k], "{precision}: {an} {a1}");
            // The closed form: transmittance multiplies by exp(-n d h); colour grows by c times the
            // opacity added.
            let depth = n[k] * d[k] * h[k];
            let added = (1.0 - a0[k]) * -(-depth).exp_m1();
            // Rounding: a few eps per step in the opacity recurrence, for the opacity and each colour.
            let bound = (n[k] + 8.0) * 4.0 * eps;
            let steps = (an - a1).abs();
            let closed = (a1 - (a0[k] + added)).abs();
            worst_steps = worst_steps.max(steps / ((n[k] + 8.0) * eps));
            worst_closed = worst_closed.max(closed / eps);
            assert!(steps <= bound, "{precision} n={} d={} h={}: {an} vs {a1}", n[k], d[k], h[k]);
            assert!(closed <= 16.0 * eps, "{precision}: one step {a1} vs closed form {}", a0[k] + added);
            for j in 0..3 {
                let (cn, c1) = (run[0][3 * k + j], run[2][3 * k + j]);
                let expected = c0[k][j] + c[k][j] * added;
                assert!((cn - c1).abs() <= 2.0 * bound * (1.0 + c[k][j]), "{precision} colour {cn} vs {c1}");
                assert!(
                    (c1 - expected).abs() <= 32.0 * eps * (1.0 + c[k][j]),
                    "{precision} colour {c1} vs {expected}"
                );
            }
        }
        println!(
            "compositing {precision}: N steps vs one step worst {worst_steps} eps per step; one step vs closed form {worst_closed} eps"
        );
    }
}

#[test]
fn opacity_saturates_at_one_for_any_optical_depth() {
    let program = composite_program();
    // Depth 1e4 per step (and up to 1e30 * 1e30), from every starting opacity; steps of depth 0.
    let mut rng = Rng(9);
    let (mut n, mut d, mut h, mut a0, mut c, mut c0) = (vec![], vec![], vec![], vec![], vec![], vec![]);
    for k in 0..400 {
        n.push([1.0, 3.0, 50.0][k % 3]);
        let (dk, hk) =
            [(1e4, 1.0), (1.0, 1e4), (1e30, 1e30), (1e4, 1e-3), (0.0, 1e30), (1e30, 0.0), (-1e30, 1.0)]
                [k % 7];
        d.push(f(dk));
        h.push(f(hk));
        a0.push(f([0.0, 1.0, rng.unit(), 1.0 - 1e-7, 1e-30][k % 5]));
        c.push([rng.range(0.0, 1e4), 1.0, 0.0].map(f));
        c0.push([0.0, 0.5, 1.0].map(f));
    }
    let count = n.len();
    let mut inputs = Inputs::default();
    inputs
        .add("n", n.clone())
        .add("d", d.clone())
        .add("h", h.clone())
        .add("A0", a0.clone())
        .add("c", flat3(&c))
        .add("C0", flat3(&c0));
    for (run, precision) in
        cpu_both(&program, count, &inputs, &["C", "A", "C1", "A1"]).iter().zip(["f64", "f32"])
    {
        for k in 0..count {
            for col in run {
                support::assert_finite(precision, col, 1);
            }
            let opaque = d[k] > 0.0 && h[k] > 0.0 && d[k] * h[k] >= 40.0;
            for a in [run[1][k], run[3][k]] {
                assert!(
                    a <= 1.0 && a >= a0[k],
                    "{precision}: opacity {a} from {} (d {}, h {})",
                    a0[k],
                    d[k],
                    h[k]
                );
                if opaque {
                    assert_eq!(a, 1.0, "{precision}: an opaque step leaves opacity {a} (from {})", a0[k]);
                } else if d[k] <= 0.0 || h[k] <= 0.0 {
                    assert_eq!(a, a0[k], "{precision}: an empty step changed the opacity");
                }
            }
        }
    }
}

#[test]
fn gradient_normals_are_unit_outward_and_guarded() {
    let program = shader(
        &[("vector", "g"), ("vector", "fb")],
        &[("vector", "central"), ("vector", "onesided"), ("vector", "direct")],
        "central = volume_density_normal(g[0], -g[0], g[1], -g[1], g[2], -g[2], fb);\n\
         onesided = volume_density_normal(0, -g[0], -g[1], -g[2], fb);\n\
         direct = volume_gradient_normal(g, fb);",
    );
    let mut rng = Rng(13);
    let (mut g, mut fb) = (vec![], vec![]);
    for k in 0..1500 {
        let scale = match k % 5 {
            0 => 0.0,
            1 => 1e-45,
            _ => 10f64.powf(rng.range(-44.0, 30.0)),
        };
        let dir = direction(&mut rng);
        let mut v = dir.map(|x| f(x * scale));
        if k % 7 == 3 {
            v[(k / 7) % 3] = 0.0;
        }
        g.push(v);
        fb.push(if k % 2 == 0 { [0.0; 3] } else { rng.point(-1e-30, 1e-30).map(f) });
    }
    let n = g.len();
    let mut inputs = Inputs::default();
    inputs.add("g", flat3(&g)).add("fb", flat3(&fb));
    let names = ["central", "onesided", "direct"];
    for (run, precision) in cpu_both(&program, n, &inputs, &names).iter().zip(["f64", "f32"]) {
        let eps = EPS[usize::from(precision == "f32")];
        let mut fallbacks = 0;
        for k in 0..n {
            // The expected normal: -g / |g|, else the fallback normalized, else +z.
            let unit = |v: [f64; 3]| {
                let m = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                if m == 0.0 {
                    return None;
                }
                let u = v.map(|x| x / m);
                let l = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
                Some(u.map(|x| x / l))
            };
            let expected = match unit(g[k].map(|x| -x)) {
                Some(u) => u,
                None => {
                    fallbacks += 1;
                    unit(fb[k]).unwrap_or([0.0, 0.0, 1.0])
                }
            };
            for (j, name) in names.iter().enumerate() {
                let got = [0, 1, 2].map(|i| run[j][3 * k + i]);
                for i in 0..3 {
                    assert!(
                        (got[i] - expected[i]).abs() <= 4.0 * eps,
                        "{name} {precision} of g {:?} fallback {:?}: {got:?}, expected {expected:?}",
                        g[k],
                        fb[k]
                    );
                }
            }
        }
        println!("normals {precision}: {n} gradients from 0 and 1e-45 to 1e30, {fallbacks} fallbacks");
    }
}

#[test]
fn the_soft_spheres_normal_is_radial() {
    // Central differences of a quadratic are exact, and the soft profile is quadratic in p.
    let program = shader(
        &[("point", "p"), ("point", "c"), ("float", "r"), ("float", "s"), ("float", "h")],
        &[("vector", "nn")],
        "nn = volume_density_normal(\n\
           soft_sphere(p + vector(h, 0, 0), c, r, s), soft_sphere(p - vector(h, 0, 0), c, r, s),\n\
           soft_sphere(p + vector(0, h, 0), c, r, s), soft_sphere(p - vector(0, h, 0), c, r, s),\n\
           soft_sphere(p + vector(0, 0, h), c, r, s), soft_sphere(p - vector(0, 0, h), c, r, s),\n\
           vector(0, 0, 1));",
    );
    let mut rng = Rng(17);
    let (mut p, mut c, mut r, mut s, mut h) = (vec![], vec![], vec![], vec![], vec![]);
    for _ in 0..1000 {
        let centre = rng.point(-1.0, 1.0).map(f);
        let radius = rng.range(0.5, 1.5);
        let soft = rng.range(0.1, 0.8);
        let step = f(soft / 32.0);
        // Well inside the soft region: the stencil stays in it.
        let at = radius + soft * rng.range(-0.35, 0.35);
        let d = direction(&mut rng);
        p.push([0, 1, 2].map(|k| f(centre[k] + d[k] * at)));
        c.push(centre);
        r.push(f(radius));
        s.push(f(soft));
        h.push(step);
    }
    let n = p.len();
    let mut inputs = Inputs::default();
    inputs
        .add("p", flat3(&p))
        .add("c", flat3(&c))
        .add("r", r.clone())
        .add("s", s.clone())
        .add("h", h.clone());
    for (run, precision) in cpu_both(&program, n, &inputs, &["nn"]).iter().zip(["f64", "f32"]) {
        let eps = EPS[usize::from(precision == "f32")];
        let mut worst = 0.0f64;
        for k in 0..n {
            let x = [0, 1, 2].map(|i| p[k][i] - c[k][i]);
            let l = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
            let err = (0..3).map(|i| (run[0][3 * k + i] - x[i] / l).abs()).fold(0.0, f64::max);
            worst = worst.max(err / eps);
            // Rounding of each density (eps) over differences of 2h |grad| (about 2h / s).
            assert!(err <= 64.0 * eps * s[k] / h[k], "{precision} normal at {:?}: error {err}", p[k]);
        }
        println!("soft sphere normal {precision}: worst component error {worst} eps (h = s/32)");
    }
}

#[test]
fn henyey_greenstein_matches_the_formula_and_integrates_to_one() {
    let program = shader(
        &[("float", "cs"), ("float", "g"), ("float", "g2"), ("float", "w")],
        &[("float", "hg"), ("float", "hg2")],
        "hg = henyey_greenstein(cs, g); hg2 = henyey_greenstein2(cs, g, g2, w);",
    );
    // Pointwise, at f32 arguments (where the f64 formula's base 1 + g^2 - 2 g c is exact).
    let mut rng = Rng(19);
    let (mut cs, mut g) = (vec![], vec![]);
    for k in 0..3000 {
        let gk = match k % 4 {
            0 => rng.range(-0.999, 0.999),
            1 => 1.0 - 10f64.powf(rng.range(-7.0, -1.0)),
            2 => -1.0 + 10f64.powf(rng.range(-7.0, -1.0)),
            _ => rng.range(-0.5, 0.5),
        };
        let ck = match k % 3 {
            0 => rng.range(-1.0, 1.0),
            1 => 1.0 - 10f64.powf(rng.range(-7.0, 0.0)),
            _ => -1.0 + 10f64.powf(rng.range(-7.0, 0.0)),
        };
        g.push(f(gk));
        cs.push(f(ck));
    }
    let n = g.len();
    let mut inputs = Inputs::default();
    inputs.add("cs", cs.clone()).add("g", g.clone()).add("g2", vec![0.0; n]).add("w", vec![1.0; n]);
    for (run, precision) in cpu_both(&program, n, &inputs, &["hg", "hg2"]).iter().zip(["f64", "f32"]) {
        let eps = EPS[usize::from(precision == "f32")];
        let mut worst = 0.0f64;
        for k in 0..n {
            let expected = reference::hg(cs[k], g[k]);
            let rel = (run[0][k] - expected).abs() / expected;
            worst = worst.max(rel / eps);
            assert!(
                rel <= 8.0 * eps,
                "HG {precision}({}, {}) = {}, expected {expected}",
                cs[k],
                g[k],
                run[0][k]
            );
            assert_eq!(run[0][k], run[1][k], "the two-lobe sum with w = 1 is the lobe");
        }
        println!("Henyey-Greenstein {precision}: worst relative error {worst} eps (g up to 1 - 1e-7)");
    }

    // The integral over the sphere, 2 pi int_{-1}^{1} p(c) dc, in f64: Simpson's rule in
    // s = ln(1 -+ c) on each half, so the peaks of width (1 - |g|)^2 are resolved, plus the tails.
    let gs = [-1.0, -0.999999, -0.9, -0.5, 0.0, 0.3, 0.7, 0.9, 0.99, 0.999999, 1.0];
    let intervals = 4000;
    let (lo, hi) = (1e-20f64.ln(), 0.0f64);
    let (mut cs, mut g, mut g2, mut w) = (vec![], vec![], vec![], vec![]);
    for &gk in &gs {
        for half in [1.0, -1.0] {
            for i in 0..=intervals {
                let x = (lo + (hi - lo) * f64::from(i) / f64::from(intervals)).exp();
                cs.push(half * (1.0 - x));
                g.push(gk);
                g2.push(-0.5 * gk);
                w.push(0.7);
            }
            // The tail point: c = +-1.
            cs.push(half);
            g.push(gk);
            g2.push(-0.5 * gk);
            w.push(0.7);
        }
    }
    let n = cs.len();
    let mut inputs = Inputs::default();
    inputs.add("cs", cs).add("g", g).add("g2", g2).add("w", w);
    let out = program.cpu::<f64>(n, &inputs.columns(), &["hg", "hg2"]);
    let per_half = intervals as usize + 2;
    for (j, &gk) in gs.iter().enumerate() {
        for (lobe, column) in out.iter().enumerate() {
            let mut total = 0.0;
            for half in 0..2 {
                let base = (2 * j + half) * per_half;
                let step = (hi - lo) / f64::from(intervals);
                let mut sum = 0.0;
                for i in 0..=intervals as usize {
                    let x = (lo + step * i as f64).exp();
                    let weight = if i == 0 || i == intervals as usize {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    sum += weight * column[base + i] * x;
                }
                total += sum * step / 3.0 + column[base + intervals as usize + 1] * lo.exp();
            }
            let integral = 2.0 * std::f64::consts::PI * total;
            println!("HG lobe {lobe} g = {gk}: integral over the sphere {integral}");
            // The nodes c = +-(1 - x) round to f64, which misplaces them by up to 1.1e-16 near
            // c = +-1. That is negligible against the peak's width (1 - |g|)^2 except for
            // |g| = 0.999999 (width 1e-12: an error of about 1e-6) and |g| = 1 (clamped to
            // 1 - 2^-24: width 3.6e-15, 32 ulps; about 2e-4).
            let tol = if gk.abs() == 1.0 {
                1e-3
            } else if gk.abs() > 0.99 {
                1e-5
            } else {
                1e-7
            };
            assert!((integral - 1.0).abs() <= tol, "g = {gk}: the phase function integrates to {integral}");
        }
    }
}

#[test]
fn wyvills_cubic_is_the_printed_polynomial_cut_at_r() {
    let program = shader(
        &[("float", "r"), ("float", "R"), ("point", "p"), ("point", "c")],
        &[("float", "w"), ("float", "wb")],
        "w = wyvill_cubic(r, R); wb = wyvill_blend(p, c, R);",
    );
    let mut rng = Rng(23);
    let (mut r, mut big_r, mut p, mut c) = (vec![], vec![], vec![], vec![]);
    for k in 0..3000 {
        let rk = f(rng.range(0.01, 10.0));
        let x = match k % 3 {
            0 => rng.range(-1.6, 1.6),
            1 => 1.0 - 10f64.powf(rng.range(-7.0, -1.0)),
            _ => rng.range(0.0, 0.01),
        } * rk;
        r.push(f(x));
        big_r.push(rk);
        let centre = rng.point(-3.0, 3.0).map(f);
        let d = direction(&mut rng);
        p.push([0, 1, 2].map(|i| f(centre[i] + d[i] * x)));
        c.push(centre);
    }
    // Exact points: 0, R/2, R, beyond, R <= 0.
    for (x, rk) in
        [(0.0, 1.0), (0.5, 1.0), (1.0, 1.0), (1.2, 1.0), (1.4, 1.0), (3.0, 2.0), (0.0, 0.0), (1.0, -1.0)]
    {
        r.push(x);
        big_r.push(rk);
        p.push([x, 0.0, 0.0]);
        c.push([0.0; 3]);
    }
    let n = r.len();
    let mut inputs = Inputs::default();
    inputs.add("r", r.clone()).add("R", big_r.clone()).add("p", flat3(&p)).add("c", flat3(&c));
    for (run, precision) in cpu_both(&program, n, &inputs, &["w", "wb"]).iter().zip(["f64", "f32"]) {
        let eps = EPS[usize::from(precision == "f32")];
        let mut worst = 0.0f64;
        for k in 0..n {
            let expected = reference::wyvill(r[k], big_r[k]);
            let got = run[0][k];
            assert!((0.0..=1.0).contains(&got), "wyvill {precision}({}, {}) = {got}", r[k], big_r[k]);
            // Absolute: the printed polynomial cancels near R (its own error is a few eps there).
            let err = (got - expected).abs();
            worst = worst.max(err / eps);
            assert!(
                err <= 8.0 * eps,
                "wyvill {precision}({}, {}) = {got}, expected {expected}",
                r[k],
                big_r[k]
            );
            let q = (0..3).map(|i| (p[k][i] - c[k][i]).powi(2)).sum::<f64>().sqrt();
            let expected = reference::wyvill(q, big_r[k]);
            assert!(
                (run[1][k] - expected).abs() <= 16.0 * eps,
                "wyvill_blend {precision}: {} vs {expected}",
                run[1][k]
            );
        }
        let tail = &run[0][n - 8..];
        assert_eq!(
            tail,
            [1.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            "{precision}: F(0), F(R/2), F(R), beyond R, R <= 0"
        );
        println!("wyvill {precision}: worst absolute error {worst} eps");
    }
    // C1 at R: the slope (F(R) - F(R - e)) / e vanishes like e (F = (1 - a)^2 (9 - 4a) / 9).
    let e: Vec<f64> = (1..=6).map(|k| 10f64.powi(-k)).collect();
    let mut inputs = Inputs::default();
    inputs
        .add("r", e.iter().map(|e| 1.0 - e).collect())
        .add("R", vec![1.0; e.len()])
        .add("p", vec![0.0; 3 * e.len()])
        .add("c", vec![0.0; 3 * e.len()]);
    let out = program.cpu::<f64>(e.len(), &inputs.columns(), &["w"]);
    for (k, e) in e.iter().enumerate() {
        let slope = out[0][k] / e;
        assert!(slope <= 3.0 * e, "slope {slope} at R - {e}");
    }
}

#[test]
fn modulated_densities_are_the_papers_compositions() {
    // Each modulated sphere is the soft sphere at the point scaled about the centre by 1 + a n,
    // with n the noise sum the shader also outputs (the noise itself is tested by its own module).
    let program = shader(
        &[
            ("point", "p"),
            ("point", "c"),
            ("float", "r"),
            ("float", "s"),
            ("float", "fq"),
            ("float", "a"),
            ("float", "oct"),
        ],
        &[
            ("float", "noisy"),
            ("float", "fractal"),
            ("float", "fire"),
            ("float", "boom"),
            ("float", "n1"),
            ("float", "n2"),
            ("float", "n3"),
            ("float", "fur"),
            ("float", "nfur"),
            ("float", "shaped"),
            ("point", "proj"),
            ("float", "halpha"),
        ],
        "noisy = noisy_sphere(p, c, r, s, fq, a); fractal = fractal_sphere(p, c, r, s, fq, a, oct);\n\
         fire = fireball(p, c, r, s, fq, a, oct); boom = explosion(p, c, r, fq, a, oct);\n\
         n1 = snoise3(fq * (p - c)); n2 = fbm(fq * (p - c), 1, 2, oct); n3 = turbulence(fq * (p - c), oct);\n\
         proj = volume_project_sphere(p, c, r);\n\
         fur = hypertexture_fur(s, proj, fq, 0.3, 0.9); nfur = noise3(fq * proj);\n\
         shaped = density_bias_gain(a, 0.3, 0.9); halpha = hypertexture_alpha(s, a, fq);",
    );
    let mut rng = Rng(29);
    let (mut p, mut c, mut r, mut s, mut fq, mut a, mut oct) =
        (vec![], vec![], vec![], vec![], vec![], vec![], vec![]);
    for _ in 0..1500 {
        let centre = rng.point(-2.0, 2.0).map(f);
        let radius = rng.range(0.3, 1.5);
        let d = direction(&mut rng);
        let at = radius * rng.range(0.5, 1.5);
        p.push([0, 1, 2].map(|k| f(centre[k] + d[k] * at)));
        c.push(centre);
        r.push(f(radius));
        s.push(f(rng.range(0.05, 0.9)));
        fq.push(f(rng.range(0.5, 8.0)));
        a.push(f(rng.range(0.0, 1.0)));
        oct.push(f(rng.range(0.0, 6.0)));
    }
    let n = p.len();
    let mut inputs = Inputs::default();
    inputs
        .add("p", flat3(&p))
        .add("c", flat3(&c))
        .add("r", r.clone())
        .add("s", s.clone())
        .add("fq", fq.clone())
        .add("a", a.clone())
        .add("oct", oct.clone());
    let names =
        ["noisy", "fractal", "fire", "boom", "n1", "n2", "n3", "fur", "nfur", "shaped", "proj", "halpha"];
    for (run, precision) in cpu_both(&program, n, &inputs, &names).iter().zip(["f64", "f32"]) {
        let eps = EPS[usize::from(precision == "f32")];
        let mut worst = [0.0f64; 7];
        for k in 0..n {
            let x = [0, 1, 2].map(|i| p[k][i] - c[k][i]);
            let (r1, r0) = reference::radii(r[k], s[k]);
            let scaled = |m: f64| {
                let q = x.map(|v| v * m);
                reference::profile_sq(q.iter().map(|v| v * v).sum(), r1, r0)
            };
            let len = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
            // The slope of the profile against the scale factor: |x|^2 2 m / (r0^2 - r1^2).
            let slope = 1.0 + 4.0 * len * len * (1.0 + a[k]) / (r0 * r0 - r1 * r1);
            let expected = [
                scaled(1.0 + a[k] * run[4][k]),
                scaled(1.0 + a[k] * run[5][k]),
                scaled(1.0 + a[k] * run[6][k]),
                reference::profile_sq(len * len, 0.0, r[k]) * (0.5 + a[k] * run[6][k]).clamp(0.0, 1.0),
                reference::gain(0.9, reference::bias(0.3, run[8][k])) * s[k],
                reference::gain(0.9, reference::bias(0.3, a[k])),
                // The book's correction 1 - (1 - alpha)^(scale step) (TM L8497).
                1.0 - (1.0 - s[k]).powf(fq[k] * a[k]),
            ];
            // Tolerances: the shapes to the profile's slope; bias and gain use pow and log
            // (a few hundred eps in f32 through the exponent ln b / ln 0.5); the alpha correction
            // uses log.
            let tols =
                [16.0 * slope, 16.0 * slope, 16.0 * slope, 16.0 * slope / r[k].powi(2), 512.0, 512.0, 64.0];
            for j in 0..7 {
                let got = run[if j < 4 {
                    j
                } else if j == 4 {
                    7
                } else if j == 5 {
                    9
                } else {
                    11
                }][k];
                assert!((0.0..=1.0).contains(&got), "{} {precision} = {got}", names[j]);
                let err = (got - expected[j]).abs() / eps;
                worst[j] = worst[j].max(err / tols[j]);
                assert!(
                    err <= tols[j],
                    "{} {precision} at point {k}: {got} against {}",
                    names[j],
                    expected[j]
                );
            }
            // The projection onto the sphere: at distance r from the centre, along p - c.
            let q = [0, 1, 2].map(|i| run[10][3 * k + i] - c[k][i]);
            let ql = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
            assert!(
                (ql - r[k]).abs() <= 8.0 * eps * (1.0 + r[k]),
                "{precision}: projection at distance {ql}, not {}",
                r[k]
            );
            for i in 0..3 {
                assert!(
                    (q[i] / ql - x[i] / len).abs() <= 8.0 * eps / (len / r[k]).min(1.0),
                    "{precision}: projection direction"
                );
            }
        }
        println!("modulated densities {precision}: worst error as a fraction of its tolerance {worst:?}");
    }
}

#[test]
fn the_ray_sphere_interval_is_the_quadratics_roots() {
    let program = shader(
        &[("point", "o"), ("vector", "d"), ("point", "c"), ("float", "r")],
        &[("vector", "hit")],
        "hit = volume_ray_sphere(o, d, c, r);",
    );
    let mut rng = Rng(31);
    let (mut o, mut d, mut c, mut r) = (vec![], vec![], vec![], vec![]);
    for k in 0..2000 {
        let centre = rng.point(-3.0, 3.0).map(f);
        let radius = f(rng.range(0.1, 2.0));
        let dir = direction(&mut rng);
        let length = 10f64.powf(rng.range(-3.0, 3.0));
        o.push(if k % 3 == 0 {
            [0, 1, 2].map(|i| f(centre[i] + 0.5 * radius * dir[(i + 1) % 3]))
        } else {
            rng.point(-6.0, 6.0).map(f)
        });
        d.push(dir.map(|x| f(x * length)));
        c.push(centre);
        r.push(radius);
    }
    let n = o.len();
    let mut inputs = Inputs::default();
    inputs.add("o", flat3(&o)).add("d", flat3(&d)).add("c", flat3(&c)).add("r", r.clone());
    for (run, precision) in cpu_both(&program, n, &inputs, &["hit"]).iter().zip(["f64", "f32"]) {
        let eps = EPS[usize::from(precision == "f32")];
        let (mut hits, mut worst) = (0, 0.0f64);
        for k in 0..n {
            // |o + t d - c|^2 = r^2: a t^2 + 2 b t + q = 0.
            let oc = [0, 1, 2].map(|i| o[k][i] - c[k][i]);
            let a: f64 = d[k].iter().map(|x| x * x).sum();
            let b: f64 = (0..3).map(|i| d[k][i] * oc[i]).sum();
            let q: f64 = oc.iter().map(|x| x * x).sum::<f64>() - r[k] * r[k];
            let disc = b * b - a * q;
            let got = [0, 1, 2].map(|i| run[0][3 * k + i]);
            // Near tangency the two answers may differ: skip a thin band.
            if disc.abs() <= 1e-4 * a * r[k] * r[k] {
                continue;
            }
            if disc < 0.0 {
                assert_eq!(got, [0.0; 3], "{precision}: a miss");
                continue;
            }
            hits += 1;
            assert_eq!(got[2], 1.0, "{precision}: a hit reported as a miss");
            let h = disc.sqrt();
            let (t0, t1) = ((-b - h) / a, (-b + h) / a);
            // Errors in parameter units: eps times the distances involved over |d|.
            let scale = 16.0 * eps * (1.0 + oc.iter().map(|x| x.abs()).sum::<f64>() + r[k]) / a.sqrt()
                * (1.0 + r[k] * r[k] * a / disc).sqrt();
            let err = (got[0] - t0).abs().max((got[1] - t1).abs());
            worst = worst.max(err / scale);
            assert!(err <= scale, "{precision}: ({}, {}) against ({t0}, {t1})", got[0], got[1]);
        }
        println!("ray-sphere {precision}: {hits} hits; worst error as a fraction of its tolerance {worst}");
    }
}

/// Every function of the module, for the stability sweep: (output, type, expression, range).
/// Inputs: points p, c; vector v; floats x, y, z, w, o (o is an octave count or a sixth density).
const SWEEP: &[(&str, &str, &str, Range)] = &[
    ("length", "float", "volume_length(v)", Range::NonNegative),
    ("unit", "vector", "volume_normalize(v)", Range::UnitOrZero),
    ("profile", "float", "soft_profile(x, y, z)", Range::Unit),
    ("sphere", "float", "soft_sphere(p, c, x, y)", Range::Unit),
    ("box", "float", "soft_box(p, c, v, x)", Range::Unit),
    ("torus", "float", "soft_torus(p, c, x, y, z)", Range::Unit),
    ("uni", "float", "soft_union(x, y)", Range::Unit),
    ("inter", "float", "soft_intersection(x, y)", Range::Unit),
    ("diff", "float", "soft_difference(x, y)", Range::Unit),
    ("compl", "float", "soft_complement(x)", Range::Unit),
    ("noisy", "float", "noisy_sphere(p, c, x, y, z, w)", Range::Unit),
    ("fractal", "float", "fractal_sphere(p, c, x, y, z, w, o)", Range::Unit),
    ("fire", "float", "fireball(p, c, x, y, z, w, o)", Range::Unit),
    ("boom", "float", "explosion(p, c, x, z, w, o)", Range::Unit),
    ("shaped", "float", "density_bias_gain(x, y, z)", Range::Unit),
    ("fur", "float", "hypertexture_fur(x, p, z, y, w)", Range::Unit),
    ("proj", "point", "volume_project_sphere(p, c, x)", Range::Finite),
    ("opacity", "float", "volume_opacity(x * y)", Range::Unit),
    ("acc_c", "color", "rgb(volume_composite({v, w}, x, color(c), y))", Range::Finite),
    ("acc_a", "float", "volume_composite({v, w}, x, color(c), y)[3]", Range::Unit),
    ("halpha", "float", "hypertexture_alpha(x, y, z)", Range::Unit),
    ("gnormal", "vector", "volume_gradient_normal(v, vector(p))", Range::UnitVector),
    ("dnormal6", "vector", "volume_density_normal(x, y, z, w, o, x, vector(c))", Range::UnitVector),
    ("dnormal4", "vector", "volume_density_normal(x, y, z, w, v)", Range::UnitVector),
    ("hg", "float", "henyey_greenstein(x, y)", Range::NonNegative),
    ("hg2", "float", "henyey_greenstein2(x, y, z, w)", Range::NonNegative),
    ("wyvill", "float", "wyvill_cubic(x, y)", Range::Unit),
    ("blend", "float", "wyvill_blend(p, c, x)", Range::Unit),
    ("ray", "vector", "volume_ray_sphere(p, v, c, x)", Range::Finite),
];

#[derive(Clone, Copy, Debug, PartialEq)]
enum Range {
    Finite,
    NonNegative,
    Unit,
    UnitVector,
    UnitOrZero,
}

/// The GPU's tolerance against the f32 interpreter, per output (absolute). Everything is plain
/// arithmetic, sqrt, floor and integer hashing (bit-identical on lavapipe) except: bias and gain
/// (pow and log: `shaped`, `fur`; measured 1.8e-7 and 9.8e-5 on the ordinary inputs, where gain's
/// slope, unbounded as g -> 1, magnifies the pow error), fbm's spectral weights (pow: `fractal`;
/// measured 0, lacunarity 2 and H 1 give exact powers of 2) and the alpha correction (log:
/// `halpha`; measured 1.2e-7). `fractal`, `shaped` and `fur` are compared on the ordinary inputs
/// only: at extreme parameters a pow rounding can move a value across a step (pattern.sl's gain at
/// g <= 0 jumps at 0 and 1, so a denormal that the GPU's pow flushes to 0, or a bias of 1 - 1 ulp,
/// changes it by 1/2; a huge amplitude moves the point across an arbitrarily thin soft shell).
fn gpu_tol(name: &str) -> f64 {
    match name {
        "shaped" | "fur" => 2e-4,
        "halpha" => 1e-5,
        "fractal" => 1e-4,
        _ => 0.0,
    }
}

fn sweep_program() -> support::Program {
    let outputs: Vec<(&str, &str)> = SWEEP.iter().map(|(n, ty, _, _)| (*ty, *n)).collect();
    let body: String = SWEEP.iter().map(|(n, _, e, _)| format!("{n} = {e};\n")).collect();
    shader(
        &[
            ("point", "p"),
            ("point", "c"),
            ("vector", "v"),
            ("float", "x"),
            ("float", "y"),
            ("float", "z"),
            ("float", "w"),
            ("float", "o"),
        ],
        &outputs,
        &body,
    )
}

/// Sweep inputs: `count` points whose every argument is, with probability `extreme`, one of the
/// extreme values (support::extremes and the parameter extremes), else an ordinary value.
fn sweep_inputs(count: usize, extreme: f64, seed: u64) -> Inputs {
    let mut rng = Rng(seed);
    let mut extremes = support::extremes();
    extremes.extend([30.0, 2.0, 0.999999, -0.999999, 1.0 - 1e-7, 40.0, 1e38, -1e38]);
    let pick = |rng: &mut Rng, lo: f64, hi: f64| {
        if rng.unit() < extreme {
            extremes[(rng.unit() * extremes.len() as f64) as usize]
        } else {
            f(rng.range(lo, hi))
        }
    };
    let mut cols: Vec<Vec<f64>> = vec![vec![]; 8];
    for _ in 0..count {
        for _ in 0..3 {
            cols[0].push(pick(&mut rng, -2.0, 2.0));
            cols[1].push(pick(&mut rng, -1.0, 1.0));
            cols[2].push(pick(&mut rng, -1.0, 1.0));
        }
        cols[3].push(pick(&mut rng, 0.0, 1.5));
        cols[4].push(pick(&mut rng, 0.0, 1.0));
        cols[5].push(pick(&mut rng, 0.0, 4.0));
        cols[6].push(pick(&mut rng, 0.0, 1.0));
        cols[7].push(pick(&mut rng, 0.0, 8.0));
    }
    let mut inputs = Inputs::default();
    for (name, col) in ["p", "c", "v", "x", "y", "z", "w", "o"].into_iter().zip(cols) {
        inputs.add(name, col);
    }
    inputs
}

/// Checks every output's range at every point.
fn check_ranges(label: &str, run: &[Vec<f64>], count: usize) {
    for ((name, _, expr, range), col) in SWEEP.iter().zip(run) {
        let width = col.len() / count;
        support::assert_finite(&format!("{label} {name} = {expr}"), col, width);
        for (i, v) in col.chunks_exact(width).enumerate() {
            let ok = match range {
                Range::Finite => true,
                Range::NonNegative => v[0] >= 0.0,
                Range::Unit => (0.0..=1.0).contains(&v[0]),
                Range::UnitVector | Range::UnitOrZero => {
                    let l = (v.iter().map(|x| x * x).sum::<f64>()).sqrt();
                    (l - 1.0).abs() <= 1e-6 || (*range == Range::UnitOrZero && l == 0.0)
                }
            };
            assert!(ok, "{label}: {name} = {expr} is {v:?} at point {i}, outside {range:?}");
        }
    }
}

#[test]
fn every_function_is_finite_and_in_range_over_the_extremes() {
    let program = sweep_program();
    let names: Vec<&str> = SWEEP.iter().map(|(n, ..)| *n).collect();
    let sets = [("ordinary", sweep_inputs(500, 0.0, 37)), ("extreme", sweep_inputs(800, 0.5, 41))];
    let gpu = patina_runtime::gpu::for_tests();
    for (set, inputs) in &sets {
        let count = inputs.cols[3].1.len();
        let start = std::time::Instant::now();
        let [f64_run, f32_run] = cpu_both(&program, count, inputs, &names);
        println!("{set}: interpreter {:?}", start.elapsed());
        check_ranges(&format!("{set} f64"), &f64_run, count);
        check_ranges(&format!("{set} f32"), &f32_run, count);
        let Some(gpu) = &gpu else { continue };
        let start = std::time::Instant::now();
        let gpu_run = program.gpu(gpu, count, &inputs.columns(), &names);
        println!("{set}: GPU {:?}", start.elapsed());
        check_ranges(&format!("{set} GPU"), &gpu_run, count);
        let mut report = Vec::new();
        for ((name, ..), (g, c)) in SWEEP.iter().zip(gpu_run.iter().zip(&f32_run)) {
            let (worst, at) = support::worst(g, c);
            let differing = g.iter().zip(c).filter(|(a, b)| a != b).count();
            if worst > 0.0 {
                report.push(format!("{name} {worst:.2e} ({differing} values)"));
            }
            if *set == "extreme" && matches!(*name, "fractal" | "shaped" | "fur") {
                continue;
            }
            assert!(
                worst <= gpu_tol(name),
                "{set}: GPU {name} differs from the interpreter by {worst} at value {at}: {} vs {}",
                g[at],
                c[at]
            );
        }
        println!(
            "{set} inputs, {count} points: GPU vs f32 interpreter, the outputs that differ: {}",
            report.join(", ")
        );
    }
}
