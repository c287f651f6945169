//! Gallery scenes `steam_cup` and `cumulus` (seed-digest §12 S12 and S14): Ebert's steam slab
//! ray-marched over a teacup and Ebert's cumulus cloud (nine Wyvill spheres plus turbulence) with
//! a shadow march toward the sun. Both backends render each scene at a test size; the shaders'
//! density and march functions are also run pointwise on the interpreter (f64 and f32) and on the
//! GPU kernel, against closed forms: the density's range and support, the opacity law
//! 1 - exp(-tau sum(rho dt)) (TM L5247), the support of the cloud's density (every term carries the
//! implicit field), and Wyvill's cubic at its centre.
//!
//! Run with `--nocapture` to see the measured differences.

use crate::support;

use patina_runtime::image::Thresholds;
use support::Rng;
use support::gallery::{at, both, covered, program_named, scene, set, shader_source};

// ---------------------------------------------------------------------------------------------
// Shared helpers

/// Flattens points into one input column.
fn flat(points: &[[f64; 3]]) -> Vec<f64> {
    points.iter().flatten().copied().collect()
}

/// The point `k` of a column of points.
fn point(column: &[f64], k: usize) -> [f64; 3] {
    [column[3 * k], column[3 * k + 1], column[3 * k + 2]]
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The standard Henyey-Greenstein phase function, written from its formula.
fn henyey_greenstein(cos_theta: f64, g: f64) -> f64 {
    (1.0 - g * g) / (4.0 * std::f64::consts::PI * (1.0 + g * g - 2.0 * g * cos_theta).powf(1.5))
}

// ---------------------------------------------------------------------------------------------
// Steam rising from a teacup (S12)

/// The steam cube's index among the scene's objects (saucer, wall, handle, tea, steam).
const STEAM_OBJECT: usize = 4;

/// The steam shader's density parameters as the scene uses them (its defaults): maxdensity,
/// exponent, gain, frequency, octaves, radius0, radius1.
const MAXDENSITY: f64 = 0.57;
const STEAM_ARGS: &str = "0.57, 6, 1.8, 1.6, 5, 0.55, 1.0";

/// The plume's support in cube coordinates: height fraction in (0, 0.95) and squared axis distance
/// below the radius at that height (radius0 0.55 at the tea, 1.0 at the top). Returns the distance
/// (in the same units) from the support's boundary, positive inside.
fn plume_margin(q: [f64; 3]) -> f64 {
    let h = (q[1] + 1.0) / 2.0;
    let radius = 0.55 + (1.0 - 0.55) * h.clamp(0.0, 1.0);
    let axis = (q[0] * q[0] + q[2] * q[2]).sqrt();
    h.min(0.95 - h).min(radius - axis)
}

#[test]
fn steam_cup_renders_alike_on_both_backends() {
    let mut s = scene("steam_cup", 48, 48);
    set(&mut s, &[STEAM_OBJECT], "steps", 12.0);
    let background = s.output.background;
    let Some(r) = both("steam_cup", &s, Thresholds::default()) else { return };
    println!("steam_cup 48x48, 12 steps: {:?}", r.comparison);
    // The steam: above the cup, the middle third of the image differs from the background.
    let (mut lit, mut n) = (0, 0);
    for y in 6..16 {
        for x in 16..32 {
            let p = at(&r.cpu, x, y);
            n += 1;
            if (0..3).any(|c| (p[c] - background[c]).abs() > 0.02) {
                lit += 1;
            }
        }
    }
    assert!(lit * 3 > n, "only {lit} of {n} pixels above the cup show steam");
    // Outside the cube's and the cup's images (the top corners) the background is untouched.
    for (x, y) in [(0, 0), (47, 0), (2, 3), (45, 3)] {
        let p = at(&r.cpu, x, y);
        assert!(
            (0..4).all(|c| (p[c] - background[c]).abs() <= 1e-6),
            "pixel ({x}, {y}) is {p:?}, not the background"
        );
    }
    println!(
        "steam_cup: {:.1}% of the pixels differ from the background",
        100.0 * covered(&r.cpu, background)
    );
}

#[test]
fn steam_density_is_non_negative_bounded_and_zero_outside_the_plume() {
    let source = format!(
        "{}\nsurface probe_density(varying point q = 0; varying float frame = 0; output varying float d = 0)\n\
         {{ d = steam_density(q, frame, {STEAM_ARGS}); }}\n",
        shader_source("steam")
    );
    let program = program_named(&source, "probe_density");
    let mut rng = Rng(61);
    let (mut q, mut frame) = (vec![], vec![]);
    for k in 0..4000 {
        // Mostly inside the cube, some beyond it; a quarter near the axis, where the plume is.
        let p = if k % 4 == 0 {
            [rng.range(-0.5, 0.5), rng.range(-1.0, 1.0), rng.range(-0.5, 0.5)]
        } else {
            rng.point(-1.3, 1.3)
        };
        q.push(p);
        frame.push([0.0, 17.0, 125.5, 300.0][k % 4]);
    }
    // Boundaries and extremes: the tea (h = 0), h = 0.95, the axis, the radius, far away.
    for p in [
        [0.0, -1.0, 0.0],
        [0.0, 0.9, 0.0],
        [0.0, 0.0, 0.0],
        [0.775, 0.0, 0.0],
        [0.0, -0.999, 0.549],
        [1e30, 0.0, 0.0],
        [0.0, -1e30, 0.0],
        [0.0, 0.0, 1e-30],
    ] {
        q.push(p);
        frame.push(0.0);
    }
    let n = q.len();
    let columns = [("q", flat(&q)), ("frame", frame)];
    let inputs: Vec<(&str, &[f64])> = columns.iter().map(|(n, c)| (*n, c.as_slice())).collect();
    let mut runs = vec![
        ("f64", program.cpu::<f64>(n, &inputs, &["d"]).remove(0)),
        ("f32", program.cpu::<f32>(n, &inputs, &["d"]).remove(0)),
    ];
    if let Some(gpu) = patina_runtime::gpu::for_tests() {
        runs.push(("GPU", program.gpu(gpu, n, &inputs, &["d"]).remove(0)));
    }
    for (name, d) in &runs {
        support::assert_finite(&format!("steam density ({name})"), d, 1);
        let mut positive = 0;
        let mut largest = 0.0f64;
        for k in 0..n {
            assert!(
                (0.0..=MAXDENSITY * (1.0 + 1e-6)).contains(&d[k]),
                "{name}: density {} at {:?} is outside [0, {MAXDENSITY}]",
                d[k],
                q[k]
            );
            let margin = plume_margin(q[k]);
            if margin < -1e-5 {
                assert_eq!(d[k], 0.0, "{name}: density {} outside the plume at {:?}", d[k], q[k]);
            }
            if d[k] > 0.0 {
                positive += 1;
            }
            largest = largest.max(d[k]);
        }
        println!("steam density {name}: {positive} of {n} samples positive, largest {largest:.4}");
        // Not identically zero: the plume holds gas as dense as a third of the maximum.
        assert!(positive * 20 > n, "{name}: only {positive} of {n} samples have gas");
        assert!(largest > MAXDENSITY / 3.0, "{name}: the densest sample is {largest}");
    }
    // The backends agree pointwise (exp, pow and cos are not bit-exact on the GPU).
    let (worst, k) = support::worst(&runs[1].1, &runs[0].1);
    println!("steam density: f32 interpreter vs f64 worst {worst:.2e} at {:?}", q[k]);
    // Measured 5.5e-6 (f32 against f64: pow with exponent 6) and 1.5e-7 (GPU against f32).
    assert!(worst <= 2e-5, "f32 vs f64: {worst} at {:?}", q[k]);
    if let Some((_, gpu)) = runs.get(2) {
        let (worst, k) = support::worst(gpu, &runs[1].1);
        println!("steam density: GPU vs f32 interpreter worst {worst:.2e} at {:?}", q[k]);
        assert!(worst <= 1e-6, "GPU vs f32: {worst} at {:?}", q[k]);
    }
}

/// The parameters of the exit of the ray o + t d from the cube [-1, 1]^3 (slabs): (t0, t1).
fn cube_interval(o: [f64; 3], d: [f64; 3]) -> (f64, f64) {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    for i in 0..3 {
        let (a, b) = ((-1.0 - o[i]) / d[i], (1.0 - o[i]) / d[i]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    (t0, t1)
}

#[test]
fn steam_march_obeys_the_exponential_opacity_law() {
    // steam_march composites front to back, step by step; the law is the closed form of the whole
    // ray: opacity = 1 - exp(-tau sum(rho dl)) (TM L5247), and with a colour constant along the
    // ray the premultiplied colour is that colour times the opacity. The densities are evaluated
    // here separately (steam_density at the same sample points) and summed in f64.
    const STEPS: usize = 16;
    const TAU: f64 = 6.0;
    const G: f64 = 0.35;
    let (sun, ambient, albedo) = ([9.0, 8.6, 8.0], [0.25, 0.27, 0.32], 0.8);
    let source = format!(
        "{}\nsurface probe_march(varying point o = 0; varying vector dir = 0; varying float t0 = 0, t1 = 0, \
         cos_theta = 0; output varying color c = 0; output varying float alpha = 0, depth = 0)\n\
         {{ float dd; float4 acc = steam_march(o, dir, t0, t1, length(dir), {STEPS}, 0.5, 2, {TAU}, \
         color({}, {}, {}), color({}, {}, {}), cos_theta, {G}, {albedo}, 0, {STEAM_ARGS}, dd); \
         c = rgb(acc); alpha = acc[3]; depth = dd; }}\n\
         surface probe_density(varying point q = 0; output varying float d = 0)\n\
         {{ d = steam_density(q, 0, {STEAM_ARGS}); }}\n",
        shader_source("steam"),
        sun[0],
        sun[1],
        sun[2],
        ambient[0],
        ambient[1],
        ambient[2]
    );
    let march = program_named(&source, "probe_march");
    let density = program_named(&source, "probe_density");
    let mut rng = Rng(7);
    let (mut o, mut dir, mut t0, mut t1, mut cos) = (vec![], vec![], vec![], vec![], vec![]);
    while o.len() < 96 {
        // From an eye outside the cube towards a point of the plume's core.
        let eye = [rng.range(-2.0, 2.0), rng.range(-0.5, 2.5), -3.0 - rng.range(0.0, 2.0)];
        let target = [rng.range(-0.4, 0.4), rng.range(-0.9, 0.6), rng.range(-0.4, 0.4)];
        let d = [target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]];
        let (a, b) = cube_interval(eye, d);
        if a < b && a > 0.0 {
            o.push(eye);
            dir.push(d);
            t0.push(a);
            t1.push(b);
            cos.push(rng.range(-1.0, 1.0));
        }
    }
    let rays = o.len();
    // The sample points: step k at t0 + (k + 0.5) h.
    let mut samples = vec![];
    for r in 0..rays {
        let h = (t1[r] - t0[r]) / STEPS as f64;
        for k in 0..STEPS {
            let t = t0[r] + (k as f64 + 0.5) * h;
            samples.push([0, 1, 2].map(|i| o[r][i] + t * dir[r][i]));
        }
    }
    let columns = [
        ("o", flat(&o)),
        ("dir", flat(&dir)),
        ("t0", t0.clone()),
        ("t1", t1.clone()),
        ("cos_theta", cos.clone()),
    ];
    let inputs: Vec<(&str, &[f64])> = columns.iter().map(|(n, c)| (*n, c.as_slice())).collect();
    let q = flat(&samples);
    let q_inputs: [(&str, &[f64]); 1] = [("q", &q)];
    let rho = density.cpu::<f64>(samples.len(), &q_inputs, &["d"]).remove(0);
    let outputs = ["c", "alpha", "depth"];
    let mut runs = vec![
        ("f64", march.cpu::<f64>(rays, &inputs, &outputs), 1e-12),
        ("f32", march.cpu::<f32>(rays, &inputs, &outputs), 2e-5),
    ];
    if let Some(gpu) = patina_runtime::gpu::for_tests() {
        // Measured 8e-6 in f32 on both (the depth is a sum of 16 terms rounded to f32).
        runs.push(("GPU", march.gpu(gpu, rays, &inputs, &outputs), 2e-5));
    }
    let mut dense = 0;
    for (name, out, tol) in &runs {
        let mut worst = [0.0f64; 3];
        for r in 0..rays {
            let len = dist(dir[r], [0.0; 3]);
            let dl = (t1[r] - t0[r]) / STEPS as f64 * len;
            let depth: f64 = rho[r * STEPS..(r + 1) * STEPS].iter().map(|d| TAU * d * dl).sum();
            let alpha = 1.0 - (-depth).exp();
            let phase = henyey_greenstein(cos[r], G);
            let errs = [
                (out[2][r] - depth).abs() / depth.max(1.0),
                (out[1][r] - alpha).abs(),
                (0..3)
                    .map(|i| (out[0][3 * r + i] - albedo * (sun[i] * phase + ambient[i]) * alpha).abs())
                    .fold(0.0, f64::max),
            ];
            for (w, e) in worst.iter_mut().zip(errs) {
                *w = w.max(e);
            }
            assert!(
                errs.iter().all(|e| *e <= *tol),
                "{name}, ray {r}: depth {} vs {depth}, opacity {} vs {alpha}, colour {:?} (errors {errs:?})",
                out[2][r],
                out[1][r],
                &out[0][3 * r..3 * r + 3]
            );
            if *name == "f64" && alpha > 0.5 {
                dense += 1;
            }
        }
        println!(
            "opacity law {name}: worst depth {:.2e}, opacity {:.2e}, colour {:.2e}",
            worst[0], worst[1], worst[2]
        );
    }
    // The rays are not all transparent: the law is tested where it matters.
    assert!(dense * 5 > rays, "only {dense} of {rays} rays reach opacity 0.5");
}

// ---------------------------------------------------------------------------------------------
// A cumulus cloud (S14)

/// The cloud's nine spheres (cloud units), as examples/shaders/cumulus.sl defines them.
const SPHERES: [([f64; 3], f64); 9] = [
    ([0.0, -0.2, 0.0], 1.3),
    ([-1.4, -0.5, 0.1], 1.0),
    ([1.4, -0.45, -0.1], 1.05),
    ([-0.6, 0.8, 0.0], 1.0),
    ([0.7, 0.7, -0.2], 1.05),
    ([0.0, 1.6, 0.1], 0.9),
    ([-2.4, -0.7, 0.0], 0.7),
    ([2.4, -0.75, 0.2], 0.65),
    ([1.3, 1.3, 0.3], 0.7),
];

/// How far inside the union of the spheres' balls `p` is (negative outside): the largest R_i - |p - c_i|.
fn ball_margin(p: [f64; 3], dilate: f64) -> f64 {
    SPHERES.iter().map(|(c, r)| r + dilate - dist(p, *c)).fold(f64::NEG_INFINITY, f64::max)
}

#[test]
fn cumulus_renders_alike_on_both_backends() {
    let mut s = scene("cumulus", 48, 36);
    set(&mut s, &[0], "steps", 12.0);
    set(&mut s, &[0], "shadowsteps", 3.0);
    let background = s.output.background;
    let Some(r) = both("cumulus", &s, Thresholds::default()) else { return };
    println!("cumulus 48x36, 12 steps, 3 shadow steps: {:?}", r.comparison);
    let cloud = covered(&r.cpu, background);
    println!("cumulus: the cloud covers {:.1}% of the image", 100.0 * cloud);
    assert!((0.15..0.8).contains(&cloud), "the cloud covers {cloud} of the image");
    // The centre of the cloud is nearly opaque and brighter than the sky; the corners are sky.
    let c = at(&r.cpu, 24, 18);
    assert!(c[0] > background[0] + 0.2, "the cloud's centre is {c:?}");
    for (x, y) in [(0, 0), (47, 0), (0, 35), (47, 35)] {
        assert_eq!(at(&r.cpu, x, y), background, "corner ({x}, {y})");
    }
}

#[test]
fn cumulus_density_is_zero_outside_the_warped_balls_and_never_nan() {
    // Ebert's cumulus density carries the implicit field mdens in every term, so it is exactly 0
    // wherever the warped point is outside every sphere's ball, and positive wherever it is inside
    // one; with no warp (turbamount 0) the support is the union of the balls itself. pow(., 0.5)
    // is evaluated at 0 wherever the density vanishes: it must give 0, not NaN, on every backend.
    let source = format!(
        "{}\nsurface probe(varying point q = 0; varying float ta = 0; output varying float d = 0; \
         output varying point w = 0)\n\
         {{ point pw; d = cumulus_density(q, 0.3, 0.5, 0.4, ta, 2, 4, pw); w = pw; }}\n",
        shader_source("cumulus")
    );
    let program = program_named(&source, "probe");
    let mut rng = Rng(91);
    let (mut q, mut ta) = (vec![], vec![]);
    for k in 0..3000 {
        let warp = if k % 3 == 0 { 0.0 } else { 0.7 };
        let p = if k % 2 == 0 {
            [rng.range(-5.0, 5.0), rng.range(-3.5, 4.0), rng.range(-3.0, 3.0)]
        } else {
            // Near a sphere's surface, within 0.5 of it either side.
            let (c, r) = SPHERES[k % 9];
            let u = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)];
            let l = dist(u, [0.0; 3]).max(1e-9);
            let s = r + rng.range(-0.5, 0.5);
            [0, 1, 2].map(|i| c[i] + s * u[i] / l)
        };
        q.push(p);
        ta.push(warp);
    }
    // Centres, points exactly on a sphere, far away.
    for (c, r) in SPHERES {
        q.push(c);
        ta.push(0.0);
        q.push([c[0] + r, c[1], c[2]]);
        ta.push(0.0);
    }
    q.push([1e30, -1e30, 0.0]);
    ta.push(0.7);
    let n = q.len();
    let columns = [("q", flat(&q)), ("ta", ta.clone())];
    let inputs: Vec<(&str, &[f64])> = columns.iter().map(|(n, c)| (*n, c.as_slice())).collect();
    let mut runs = vec![
        ("f64", program.cpu::<f64>(n, &inputs, &["d", "w"])),
        ("f32", program.cpu::<f32>(n, &inputs, &["d", "w"])),
    ];
    if let Some(gpu) = patina_runtime::gpu::for_tests() {
        runs.push(("GPU", program.gpu(gpu, n, &inputs, &["d", "w"])));
    }
    for (name, out) in &runs {
        let (d, w) = (&out[0], &out[1]);
        support::assert_finite(&format!("cumulus density ({name})"), d, 1);
        let (mut zero, mut inside, mut moved, mut pow_zero) = (0, 0, 0, 0);
        for k in 0..n {
            assert!(d[k] >= 0.0, "{name}: density {} at {:?}", d[k], q[k]);
            let warped = point(w, k);
            // The point as this run saw it (the f32 runs round the inputs).
            let seen = if *name == "f64" { q[k] } else { q[k].map(|x| f64::from(x as f32)) };
            if ta[k] == 0.0 {
                assert_eq!(warped, seen, "{name}: no warp, yet the point moved");
            }
            // Far from every ball (beyond the largest warp, sqrt(3) 2 turbamount): 0, not warped.
            if ball_margin(q[k], 3f64.sqrt() * 2.0 * ta[k]) < -1e-6 {
                assert_eq!((d[k], warped), (0.0, seen), "{name}: far point {:?}", q[k]);
            }
            let m = ball_margin(warped, 0.0);
            if m < -1e-5 {
                assert_eq!(d[k], 0.0, "{name}: density {} with the warped point {warped:?} outside", d[k]);
                zero += 1;
                if warped != seen {
                    // Past the early exit: the density is pow(0, 0.5).
                    pow_zero += 1;
                }
            } else if m > 1e-3 {
                assert!(d[k] > 0.0, "{name}: density 0 with the warped point {warped:?} inside");
                inside += 1;
            }
            if ta[k] > 0.0 && (ball_margin(q[k], 0.0) > 0.0) != (m > 0.0) {
                moved += 1;
            }
        }
        println!(
            "cumulus {name}: {zero} zero outside ({pow_zero} of them pow(0, 0.5)), {inside} positive inside, \
             {moved} moved across a boundary"
        );
        assert!(pow_zero > 50, "{name}: only {pow_zero} points evaluate pow(0, 0.5)");
        assert!(zero > n / 5 && inside > n / 5, "{name}: {zero} outside, {inside} inside of {n}");
        // The warp matters: some points cross a sphere's boundary.
        assert!(moved > 50, "{name}: only {moved} points warped across a boundary");
    }
    let (worst, k) = support::worst(&runs[1].1[0], &runs[0].1[0]);
    println!("cumulus density: f32 interpreter vs f64 worst {worst:.2e} at {:?}", q[k]);
    // Measured 7.4e-7 (f32 against f64) and 9e-8 (GPU against f32).
    assert!(worst <= 1e-5, "f32 vs f64: {worst} at {:?}", q[k]);
    if let Some((_, gpu)) = runs.get(2) {
        let (worst, k) = support::worst(&gpu[0], &runs[1].1[0]);
        println!("cumulus density: GPU vs f32 interpreter worst {worst:.2e} at {:?}", q[k]);
        assert!(worst <= 1e-6, "GPU vs f32: {worst} at {:?}", q[k]);
    }
}

#[test]
fn wyvills_cubic_is_flat_at_the_centre() {
    // runtime/tests/stdlib/volume.rs tests F(0) = 1, F(R/2) = 1/2, F(R) = 0, F = 0 beyond R and the
    // zero slope at R; this is the remaining identity, F'(0) = 0, with the exact curvature: near 0,
    // F(r) = 1 - (22/9) (r/R)^2 + (17/9) (r/R)^4 - ..., so (1 - F(e)) / (e/R)^2 -> 22/9.
    let program = support::program(
        "#include <volume.sl>\nsurface t(varying float r = 0, R = 0; output varying float w = 0) { w = wyvill_cubic(r, R); }",
    );
    let (mut r, mut big_r) = (vec![], vec![]);
    for big in [1.0, 2.5, 0.3] {
        for k in 1..=5 {
            r.push(big * 10f64.powi(-k));
            big_r.push(big);
        }
    }
    let inputs: [(&str, &[f64]); 2] = [("r", &r), ("R", &big_r)];
    let w = program.cpu::<f64>(r.len(), &inputs, &["w"]).remove(0);
    for k in 0..r.len() {
        let x = r[k] / big_r[k];
        let curvature = (1.0 - w[k]) / (x * x);
        // The next term of the series is (17/9) x^2; rounding of 1 - F is 1e-16 / x^2.
        assert!(
            (curvature - 22.0 / 9.0).abs() <= 2.0 * x * x + 1e-15 / (x * x),
            "F({}, R = {}) = {}: (1 - F) / x^2 = {curvature}",
            r[k],
            big_r[k],
            w[k]
        );
        // So the slope (1 - F(e)) / e vanishes like e.
        assert!((1.0 - w[k]) / r[k] <= 2.5 * r[k] / (big_r[k] * big_r[k]));
    }
}
