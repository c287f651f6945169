//! Gallery scenes `hypertexture` and `furry_torus` (seed-digest §12 S3 and S5): Perlin & Hoffert's
//! hypertexture gallery (noisy, high-frequency, high-amplitude, fractal and dripping spheres, the
//! eroded cube) and their tribble (curly fur on a soft torus). Both backends render each scene;
//! the density functions of the shaders are also run pointwise on the interpreter (f32 and f64)
//! through probe shaders appended to the scene's source, and checked against the paper's rules:
//! densities in [0, 1], the octave clamp 2^i f >= 1/step (PH L308), finite unit normals where the
//! gradient vanishes and where 1 + a noise < 0, the fur 0 outside the outer tube, no curl at the
//! roots (gain_0.8(0) = 0), straight hairs as long as the soft region.
//!
//! Run with `--nocapture` to see the image comparisons.

use crate::support;

use patina_runtime::image::Thresholds;
use support::Rng;
use support::gallery::{at, both, covered, program_named, scene, set, shader_source};

// ---------------------------------------------------------------------------------------------
// Shared helpers

/// The scene shader's source followed by `probe` (a surface shader named `probe` calling the
/// scene's functions), checked and compiled for the interpreter.
fn probe(scene_shader: &str, probe: &str) -> support::Program {
    program_named(&format!("{}\n{probe}\n", shader_source(scene_shader)), "probe")
}

/// Runs `program` on the interpreter in f64 and in f32: `[f64 outputs, f32 outputs]`.
fn cpu_both(
    program: &support::Program,
    n: usize,
    inputs: &[(&str, &[f64])],
    outputs: &[&str],
) -> [Vec<Vec<f64>>; 2] {
    [program.cpu::<f64>(n, inputs, outputs), program.cpu::<f32>(n, inputs, outputs)]
}

/// Rounds to f32 (inputs are f32-representable so that both precisions see the same points).
fn f(x: f64) -> f64 {
    f64::from(x as f32)
}

/// The background colour the shaders composite over (their `background` parameter's default).
const SHADER_BACKGROUND: [f32; 4] = [0.06, 0.07, 0.1, 1.0];

/// Asserts that `pixel` is the shaders' background (a ray that misses the bounding sphere adds
/// nothing: Ci = background exactly, up to the image's storage).
fn assert_background(label: &str, pixel: [f32; 4]) {
    for (c, b) in pixel.iter().zip(SHADER_BACKGROUND) {
        assert!((c - b).abs() < 1e-6, "{label}: {pixel:?} is not the background {SHADER_BACKGROUND:?}");
    }
}

/// Asserts that `pixel` differs from the shaders' background (an object is there).
fn assert_not_background(label: &str, pixel: [f32; 4]) {
    let d = pixel.iter().zip(SHADER_BACKGROUND).map(|(c, b)| (c - b).abs()).fold(0.0, f32::max);
    assert!(d > 0.02, "{label}: {pixel:?} is (nearly) the background");
}

// ---------------------------------------------------------------------------------------------
// The hypertexture gallery (seed-digest §12 S3)

/// The tile layout of examples/scenes/hypertexture.toml: variant k is object k, at column k % 3
/// and row k / 3.
const VARIANTS: usize = 6;

#[test]
fn hypertexture_gallery_agrees_on_both_backends() {
    // 72 x 48: each tile 24 x 24 pixels; 16 steps across each bounding sphere (the debug
    // interpreter takes about 6 s for this, lavapipe 3 s, mostly compiling six pipelines).
    let mut s = scene("hypertexture", 72, 48);
    set(&mut s, &[0, 1, 2, 3, 4, 5], "steps", 16.0);
    // The stiff case of the high-amplitude sphere (digest H10): amplitude 2, so 1 + a noise < 0
    // where the noise is below -1/2 (the gallery shows 0.75). `both` asserts no NaN on either side.
    set(&mut s, &[2], "high_amplitude", STIFF_AMPLITUDE);
    let Some(r) = both("hypertexture", &s, Thresholds::default()) else { return };
    println!("hypertexture 72x48, 16 steps: {:?}", r.comparison);
    // Each tile shows its object at its centre and the shader's background in its corners (the
    // corner rays miss the bounding sphere); the gap between tiles is the scene's background.
    let (tw, th) = (72.0 / 3.0, 48.0 / 2.0);
    for k in 0..VARIANTS {
        let (cx, cy) = ((k % 3) as f64 * tw + tw / 2.0, (k / 3) as f64 * th + th / 2.0);
        for image in [&r.cpu, &r.gpu] {
            assert_not_background(&format!("variant {k} centre"), at(image, cx as u32, cy as u32));
            assert_background(
                &format!("variant {k} corner"),
                at(image, (cx - 9.0) as u32, (cy - 9.0) as u32),
            );
        }
    }
    let lit = covered(&r.cpu, SHADER_BACKGROUND);
    assert!(lit > 0.2 && lit < 0.8, "objects cover {lit} of the image");
}

/// The probe of the gallery's densities: the density of each variant at x (the high-amplitude
/// sphere with amplitude `amp`), the signed noise of the noisy spheres at 4x (the high-amplitude
/// sphere scales x by 1 + amp times it), the octaves of the fractal ones at the scene's step for
/// `steps`, the clamp rule at (fh, fstep), and the shading samples and normal with a fallback.
const HT_PROBE: &str = r#"
surface probe(varying point x = 0; varying float variant = 0; varying float steps = 64;
              varying vector fallback = 0; varying float fh = 0; varying float fstep = 0;
              varying float amp = 0.75;
              output varying float density = 0; output varying float n4 = 0;
              output varying float octaves = 0; output varying float rule = 0;
              output varying float d0 = 0; output varying normal nrm = 0)
{
    float h = 2 * HT_BOUND / clamp(floor(steps), 1, 4096);
    octaves = ht_octaves(ht_frequency(variant), h);
    density = ht_density(x, variant, octaves, amp);
    n4 = snoise3(4 * x);
    rule = ht_octaves(fh, fstep);
    float4 ds = ht_samples(x, variant, octaves, amp, 0.01);
    d0 = ds[0];
    nrm = ht_normal(ds, fallback);
}
"#;

/// Gallery points: `per` random points in the cube [lo, hi)^3 for each variant (four times as
/// many for the high-amplitude sphere, half of them at amplitude 2, the stiff case, the others
/// at the gallery's 0.75), each variant's points followed by its special points (the centre,
/// points on the axes at the bound), with random steps among 8, 16, 64, 512 and random fallback
/// normals.
struct HtPoints {
    x: Vec<f64>,
    variant: Vec<f64>,
    steps: Vec<f64>,
    fallback: Vec<f64>,
    amp: Vec<f64>,
    n: usize,
}

/// The amplitude of the stiff high-amplitude sphere.
const STIFF_AMPLITUDE: f64 = 2.0;

fn ht_points(per: usize, lo: f64, hi: f64, seed: u64) -> HtPoints {
    let mut rng = Rng(seed);
    let mut p = HtPoints { x: vec![], variant: vec![], steps: vec![], fallback: vec![], amp: vec![], n: 0 };
    let steps = [8.0, 16.0, 64.0, 512.0];
    for v in 0..VARIANTS {
        let count = if v == 2 { 4 * per } else { per };
        let mut pts: Vec<[f64; 3]> = (0..count).map(|_| rng.point(lo, hi)).collect();
        pts.extend([[0.0, 0.0, 0.0], [1.2, 0.0, 0.0], [0.0, -1.2, 0.0], [0.0, 0.0, 1.2]]);
        for (i, q) in pts.iter().enumerate() {
            p.x.extend(q.map(f));
            p.variant.push(v as f64);
            p.steps.push(steps[i % steps.len()]);
            let g = rng.point(-1.0, 1.0);
            p.fallback.extend(g.map(f));
            p.amp.push(if v == 2 && i % 2 == 1 { STIFF_AMPLITUDE } else { 0.75 });
            p.n += 1;
        }
    }
    p
}

#[test]
fn hypertexture_densities_are_in_the_unit_interval_and_finite() {
    let program = probe("hypertexture", HT_PROBE);
    let p = ht_points(700, -1.25, 1.25, 0x4854_0001);
    let zeros = vec![0.0; p.n];
    let inputs: Vec<(&str, &[f64])> = vec![
        ("x", &p.x),
        ("variant", &p.variant),
        ("steps", &p.steps),
        ("fallback", &p.fallback),
        ("fh", &zeros),
        ("fstep", &zeros),
        ("amp", &p.amp),
    ];
    let [r64, r32] = cpu_both(&program, p.n, &inputs, &["density", "n4", "octaves"]);
    for (label, r) in [("f64", &r64), ("f32", &r32)] {
        let (density, n4) = (&r[0], &r[1]);
        let mut counts = [[0usize; 3]; VARIANTS]; // zero, soft, one
        let mut mirrored = 0;
        for i in 0..p.n {
            let v = p.variant[i] as usize;
            let d = density[i];
            assert!(
                d.is_finite() && (0.0..=1.0).contains(&d),
                "{label}: variant {v} density {d} at point {i}"
            );
            counts[v][if d == 0.0 {
                0
            } else if d < 1.0 {
                1
            } else {
                2
            }] += 1;
            // The high-amplitude sphere where 1 + 0.75 noise < 0 (the point mirrored through the
            // centre, digest H10): finite and in range too (checked above); count them.
            if v == 2 && 1.0 + p.amp[i] * n4[i] < 0.0 {
                mirrored += 1;
            }
        }
        println!("{label}: per variant (zero, soft, one) counts {counts:?}; {mirrored} mirrored points");
        // Every density has an empty outside, a soft region and a solid core among the samples.
        for (v, c) in counts.iter().enumerate() {
            assert!(c.iter().all(|&k| k >= 5), "{label}: variant {v} counts {c:?}");
        }
        assert!(mirrored >= 5, "{label}: only {mirrored} points with 1 + a noise < 0");
    }
    // The two precisions agree on the density except where a sample sits on a steep edge.
    let far = r64[0].iter().zip(&r32[0]).filter(|(a, b)| (*a - *b).abs() > 1e-3).count();
    assert!(far * 100 < p.n, "{far} of {} densities differ by more than 1e-3 between f64 and f32", p.n);
}

/// The octave count Perlin & Hoffert's clamp gives (PH L308: stop at 2^i f >= 1/step), from the
/// rule in exact arithmetic: the number of i >= 0 with 2^i f step < 1, at least 1 and at most 16.
fn clamp_rule(frequency: f64, step: f64) -> f64 {
    let mut n = 0;
    while n < 16 && 2f64.powi(n) * frequency * step < 1.0 {
        n += 1;
    }
    f64::from(n.max(1))
}

#[test]
fn fractal_octaves_follow_the_frequency_clamp() {
    let program = probe("hypertexture", HT_PROBE);
    let mut rng = Rng(0x4854_0002);
    // Random frequencies and steps, the exact ties 2^k f step = 1 (the octave at the tie is
    // dropped), and the scene's own steps for each variant (the fractal sphere has f = 4, the
    // eroded cube f = 3; h = 2.4 / steps).
    let mut fh = vec![];
    let mut fstep = vec![];
    for _ in 0..400 {
        fh.push(f(rng.range(0.5, 16.0)));
        fstep.push(f(2f64.powf(rng.range(-16.0, 1.0))));
    }
    for (freq, step) in [(4.0, 1.0 / 32.0), (4.0, 1.0 / 4.0), (3.0, 1.0 / 96.0), (1.0, 1.0), (8.0, 1.0 / 8.0)]
    {
        fh.push(freq);
        fstep.push(step);
    }
    let scene_steps = [4.0, 8.0, 16.0, 24.0, 32.0, 64.0, 96.0, 128.0, 256.0, 512.0, 4096.0];
    let n = fh.len().max(scene_steps.len() * 2);
    while fh.len() < n {
        fh.push(1.0);
        fstep.push(1.0);
    }
    let mut x = vec![];
    let mut variant = vec![];
    let mut steps = vec![];
    for i in 0..n {
        x.extend([0.3, -0.2, 0.1]);
        variant.push(if i % 2 == 0 { 3.0 } else { 5.0 });
        steps.push(scene_steps[(i / 2) % scene_steps.len()]);
    }
    let fallback = vec![0.0; 3 * n];
    let amp = vec![0.75; n];
    let inputs: Vec<(&str, &[f64])> = vec![
        ("x", &x),
        ("variant", &variant),
        ("steps", &steps),
        ("fallback", &fallback),
        ("fh", &fh),
        ("fstep", &fstep),
        ("amp", &amp),
    ];
    let [r64, r32] = cpu_both(&program, n, &inputs, &["octaves", "rule"]);
    for (label, r) in [("f64", &r64), ("f32", &r32)] {
        for i in 0..n {
            assert_eq!(r[1][i], clamp_rule(fh[i], fstep[i]), "{label}: f = {}, step = {}", fh[i], fstep[i]);
            // The scene's step is 2.4 / steps rounded to f32 (never near a tie: 2^k f 2.4 / steps
            // = 1 would need steps = 9.6 2^k or 7.2 2^k, never an integer).
            let freq = if variant[i] > 4.5 { 3.0 } else { 4.0 };
            let h = f64::from(2.4f32 / steps[i] as f32);
            assert_eq!(r[0][i], clamp_rule(freq, h), "{label}: variant {} at {} steps", variant[i], steps[i]);
        }
    }
    // The ties: 4 x 1/32 = 1/8, so octaves 0, 1, 2 (1/8, 1/4, 1/2) are kept and 3 (1) is not.
    assert_eq!(clamp_rule(4.0, 1.0 / 32.0), 3.0);
    // The gallery's 64 steps keep 3 octaves of the fractal sphere, 512 steps keep 6.
    assert_eq!(clamp_rule(4.0, f64::from(2.4f32 / 64.0)), 3.0);
    assert_eq!(clamp_rule(4.0, f64::from(2.4f32 / 512.0)), 6.0);
}

#[test]
fn hypertexture_normals_are_unit_and_fall_back_where_the_gradient_vanishes() {
    let program = probe("hypertexture", HT_PROBE);
    // Random points over the whole bound (many in the soft regions) and points deep inside the
    // cores (|x| < 0.2, where every density is 1 at all four samples: the gradient is exactly 0)
    // and outside (|x| in the corners of the bound, density 0).
    let mut p = ht_points(500, -1.25, 1.25, 0x4854_0003);
    let mut inside = vec![false; p.n];
    let mut rng = Rng(0x4854_0004);
    for v in 0..VARIANTS {
        for _ in 0..60 {
            let q = rng.point(-0.11, 0.11);
            p.x.extend(q.map(f));
            p.variant.push(v as f64);
            p.steps.push(64.0);
            p.fallback.extend(rng.point(-1.0, 1.0).map(f));
            p.amp.push(0.75);
            inside.push(true);
            p.n += 1;
        }
    }
    let zeros = vec![0.0; p.n];
    let inputs: Vec<(&str, &[f64])> = vec![
        ("x", &p.x),
        ("variant", &p.variant),
        ("steps", &p.steps),
        ("fallback", &p.fallback),
        ("fh", &zeros),
        ("fstep", &zeros),
        ("amp", &p.amp),
    ];
    let [r64, r32] = cpu_both(&program, p.n, &inputs, &["d0", "nrm"]);
    for (label, r, eps) in [("f64", &r64, f64::EPSILON), ("f32", &r32, f64::from(f32::EPSILON))] {
        let (d0, nrm) = (&r[0], &r[1]);
        let mut fell_back = 0;
        for i in 0..p.n {
            let nv = &nrm[3 * i..3 * i + 3];
            assert!(nv.iter().all(|c| c.is_finite()), "{label}: normal {nv:?} at point {i}");
            let len = nv.iter().map(|c| c * c).sum::<f64>().sqrt();
            assert!((len - 1.0).abs() < 8.0 * eps, "{label}: |normal| = {len} at point {i}");
            let g = &p.fallback[3 * i..3 * i + 3];
            let gl = g.iter().map(|c| c * c).sum::<f64>().sqrt();
            let is_fallback = (0..3).all(|k| (nv[k] - g[k] / gl).abs() < 8.0 * eps);
            if inside[i] {
                assert_eq!(
                    d0[i], 1.0,
                    "{label}: variant {} core point {i} has density {}",
                    p.variant[i], d0[i]
                );
                assert!(is_fallback, "{label}: core point {i}: normal {nv:?}, fallback {g:?}");
            }
            if d0[i] == 0.0 {
                assert!(is_fallback, "{label}: empty point {i}: normal {nv:?}, fallback {g:?}");
            }
            if is_fallback {
                fell_back += 1;
            }
        }
        // The soft samples have gradient normals of their own.
        let soft = d0.iter().filter(|&&d| d > 0.0 && d < 1.0).count();
        assert!(soft > 100 && fell_back < p.n - 100, "{label}: {soft} soft samples, {fell_back} fallbacks");
    }
}

// ---------------------------------------------------------------------------------------------
// The furry torus (seed-digest §12 S5)

/// The scene's torus (examples/shaders/furry_torus.sl): core radius, inner (root) and outer (tip)
/// tube radii.
const MAJOR: f64 = 0.58;
const R1: f64 = 0.26 - 0.09;
const R0: f64 = 0.26 + 0.09;

#[test]
fn furry_torus_agrees_on_both_backends() {
    // 40 x 40 with 16 steps across the bounding sphere (about 7 s on the debug interpreter).
    let mut s = scene("furry_torus", 40, 40);
    set(&mut s, &[0], "steps", 16.0);
    let Some(r) = both("furry_torus", &s, Thresholds::default()) else { return };
    println!("furry_torus 40x40, 16 steps: {:?}", r.comparison);
    for image in [&r.cpu, &r.gpu] {
        // The corners' rays miss the bounding sphere; the rays at x = -+0.6 (the core circle's
        // radius, 0.58) through the middle row pass through the tube's skin, opaque.
        assert_background("corner", at(image, 1, 1));
        assert_background("corner", at(image, 38, 38));
        assert_not_background("left of the ring", at(image, 8, 20));
        assert_not_background("right of the ring", at(image, 31, 20));
    }
    let lit = covered(&r.cpu, SHADER_BACKGROUND);
    assert!(lit > 0.3 && lit < 0.8, "the torus covers {lit} of the image");
}

/// The probe of the fur: the torus density d, the curled point and the straight and curly fur
/// (without the skin) at q (torus frame), and the skin union.
const FUR_PROBE: &str = r#"
surface probe(varying point q = 0; varying float curliness = 0.09;
              output varying float d = 0; output varying point curled = 0;
              output varying float straight = 0; output varying float curly = 0;
              output varying float full = 0)
{
    d = soft_torus(q, point(0, 0, 0), FUR_MAJOR, FUR_TUBE, FUR_SOFT);
    curled = fur_curl(q, d, curliness, 3);
    straight = fur_density(q, 22, 0, 3);
    curly = fur_density(q, 22, curliness, 3);
    full = tribble_density(q, 22, curliness, 3);
}
"#;

/// The distance of q from the torus's core circle.
fn tube_distance(q: [f64; 3]) -> f64 {
    (q[0].hypot(q[1]) - MAJOR).hypot(q[2])
}

/// A point at tube distance `rho`, around the core at angle `theta`, around the tube at `phi`.
fn torus_point(theta: f64, phi: f64, rho: f64) -> [f64; 3] {
    let ring = MAJOR + rho * phi.cos();
    [ring * theta.cos(), ring * theta.sin(), rho * phi.sin()]
}

#[test]
fn fur_is_zero_outside_straight_at_the_roots_and_as_long_as_the_soft_region() {
    let program = probe("furry_torus", FUR_PROBE);
    let mut rng = Rng(0x4854_0005);
    let mut q: Vec<[f64; 3]> = vec![];
    // Random points in the bound, and points by tube distance: cores (rho < R1), the soft region,
    // just outside R0, and the degenerate points (the axis, the core circle, the origin).
    for _ in 0..1500 {
        q.push(rng.point(-1.0, 1.0).map(f));
    }
    for _ in 0..1500 {
        let rho = rng.range(0.0, 0.5);
        q.push(torus_point(rng.range(0.0, 6.3), rng.range(0.0, 6.3), rho).map(f));
    }
    q.extend([
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.5],
        [0.0, 0.0, -0.9],
        [f(MAJOR), 0.0, 0.0],
        [0.0, -f(MAJOR), 0.0],
    ]);
    // Radial lines across the soft region: hairs, 12 samples each from R1 to R0 (exclusive).
    let lines = 40;
    let per_line = 12;
    let first_line = q.len();
    for _ in 0..lines {
        let (theta, phi) = (rng.range(0.0, 6.3), rng.range(0.0, 6.3));
        for j in 0..per_line {
            let rho = R1 + (R0 - R1) * (j as f64 + 0.5) / per_line as f64;
            q.push(torus_point(theta, phi, rho).map(f));
        }
    }
    let n = q.len();
    let flat: Vec<f64> = q.iter().flatten().copied().collect();
    let curliness = vec![0.09; n];
    let inputs: Vec<(&str, &[f64])> = vec![("q", &flat), ("curliness", &curliness)];
    let outputs = ["d", "curled", "straight", "curly", "full"];
    let [r64, r32] = cpu_both(&program, n, &inputs, &outputs);
    for (label, r) in [("f64", &r64), ("f32", &r32)] {
        let (d, curled, straight, curly, full) = (&r[0], &r[1], &r[2], &r[3], &r[4]);
        let (mut roots, mut outside, mut hairy, mut curled_soft, mut changed) = (0, 0, 0, 0, 0);
        for i in 0..n {
            for (name, col) in [("d", d), ("straight", straight), ("curly", curly), ("full", full)] {
                let v = col[i];
                assert!(v.is_finite() && (0.0..=1.0).contains(&v), "{label}: {name} = {v} at {:?}", q[i]);
            }
            let c = &curled[3 * i..3 * i + 3];
            assert!(c.iter().all(|x| x.is_finite()), "{label}: curled {c:?} at {:?}", q[i]);
            let rho = tube_distance(q[i]);
            // The fur is 0 outside the outer tube (with and without curl, and with the skin).
            if rho > R0 * (1.0 + 1e-5) {
                assert_eq!(d[i], 0.0, "{label}: torus density at {:?}", q[i]);
                assert_eq!(curly[i], 0.0, "{label}: fur outside r0 at {:?}", q[i]);
                assert_eq!(full[i], 0.0, "{label}: fur or skin outside r0 at {:?}", q[i]);
                outside += 1;
            }
            // At the roots (D = 1) gain_0.8(1 - D) = gain_0.8(0) = 0: the point is not displaced,
            // exactly, so curly and straight fur agree there.
            if d[i] == 1.0 {
                assert_eq!(c, &q[i][..], "{label}: a root point moved");
                assert_eq!(curly[i], straight[i], "{label}: curl at a root at {:?}", q[i]);
                roots += 1;
            }
            // In the soft region the point is displaced (by at most curliness sqrt(3)).
            if d[i] > 0.0 && d[i] < 0.9 {
                let qi = q[i];
                let moved = (0..3).map(|k| (c[k] - qi[k]).powi(2)).sum::<f64>().sqrt();
                assert!(moved <= 0.09 * 3f64.sqrt() * (1.0 + 1e-5), "{label}: moved {moved}");
                if moved > 1e-3 {
                    curled_soft += 1;
                }
            }
            if curly[i] > 0.0 {
                hairy += 1;
            }
            // The curl reaches the density: curly and straight fur differ in the soft region.
            if (curly[i] - straight[i]).abs() > 0.05 {
                changed += 1;
            }
        }
        println!(
            "{label}: {roots} roots, {outside} outside, {hairy} with fur, {curled_soft} curled, {changed} changed by the curl"
        );
        assert!(
            roots > 100 && outside > 100 && hairy > 100 && curled_soft > 100 && changed > 50,
            "{label}: too few samples"
        );
        // A straight hair (curliness 0) is the noise at one projected point times D: along a
        // radial line f / D is constant from the root to the tip, so every hair is exactly as long
        // as the soft region (PH L266), fading only with D.
        let mut hairs = 0;
        for l in 0..lines {
            let idx: Vec<usize> = (0..per_line).map(|j| first_line + l * per_line + j).collect();
            let ratio0 = straight[idx[0]] / d[idx[0]];
            for &i in &idx {
                let ratio = straight[i] / d[i];
                assert!(d[i] > 0.0 && d[i] < 1.0, "{label}: line point {i} is not in the soft region");
                assert!(
                    (ratio - ratio0).abs() <= 1e-4 * ratio0.max(0.05),
                    "{label}: line {l}: {ratio} vs {ratio0}"
                );
            }
            if ratio0 > 0.1 {
                hairs += 1;
            }
        }
        assert!(hairs >= 3, "{label}: only {hairs} of {lines} radial lines cross a hair");
    }
}
