//! The standard library's volume and hypertexture module (`stdlib/volume.sl`) on the interpreter
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

mod support;

use support::Rng;

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
