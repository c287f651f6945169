//! The standard library's shaping and antialiased pattern functions (`compiler/stdlib/pattern.sl`) on the
//! GPU: the shaders compiled as compute kernels by the WGSL backend, against the interpreter's f32
//! mode, over random arguments and the extremes (w = 0, tiny, 1e6; x = ±1e6; b, g = 0 and 1).
//!
//! Tolerances (run with `--nocapture` to see the measured differences):
//! - everything built from `+ - * /`, comparisons, `floor`, `clamp`, `min`, `max` and `abs`
//!   (pulse, boxstep, schlickbias, schlickgain, pulsetrain and the five filtered functions) must be
//!   bit-identical: lavapipe rounds these correctly (docs/numerics.md), as the interpreter does;
//! - gammacorrect, bias and gain use `pow` and `log`, which WGSL computes as exp2(y log2 x) with
//!   loose accuracy (shared/notes/naga-wgpu-facts.md §8: up to 89 ulp for pow, 1.2e-7 absolute
//!   for log near 1). On [0, 1] the error of x^y is at most |x^y ln x| times the error of y plus the
//!   error of pow itself; the exponent ln(b)/ln(0.5) carries log's absolute error divided by ln 2,
//!   and max |x^y ln x| = 1/(e y) is large only for y -> 0 (b -> 1), where x^y is close to 1.
//!   `POW_TOL` = 2e-5, absolute below 1 and relative above (gammacorrect of x > 1; measured: see
//!   the output).

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_compiler::backend::wgsl::{KERNEL_WORKGROUP, compile_kernel};
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::gpu;
use patina_test_support::Rng;

/// Tolerance for the functions that use pow and log: absolute below 1, relative above.
const POW_TOL: f32 = 2e-5;

/// (function as an expression of s, t, u, v; whether it uses pow/log).
const FUNCTIONS: [(&str, bool); 12] = [
    ("pulse(s, t, u)", false),
    ("boxstep(s, t, u)", false),
    ("gammacorrect(s, u)", true),
    ("bias(s, u)", true),
    ("gain(s, u)", true),
    ("schlickbias(s, u)", false),
    ("schlickgain(s, u)", false),
    ("pulsetrain(s, t, u)", false),
    ("filteredstep(s, u, v)", false),
    ("filteredpulse(s, t, u, v)", false),
    ("filteredpulsetrain(s, t, u, v)", false),
    ("filteredabs(u, v)", false),
];

/// (s, t, u, v): s a parameter in [0, 1] (b, g, gamma, an edge), t > s (a pulse's end, a period),
/// u the value x, v the filter width.
fn points() -> Vec<[f32; 4]> {
    let mut rng = Rng(41);
    let mut points = Vec::new();
    for _ in 0..3000 {
        let s = rng.range_f32(0.0, 1.0);
        points.push([s, s + rng.range_f32(0.01, 2.0), rng.range_f32(-0.2, 1.2), rng.range_f32(0.0, 3.0)]);
    }
    for _ in 0..1000 {
        points.push([
            rng.range_f32(0.0, 1.0),
            rng.range_f32(0.2, 3.0),
            rng.range_f32(-20.0, 20.0),
            rng.range_f32(0.0, 40.0),
        ]);
    }
    let params = [(0.0, 1.0), (1.0, 2.0), (0.5, 0.5), (0.25, 1.0)];
    let xs = [0.0, 0.25, 0.5, 1.0, -1.0, 1e6, -1e6];
    let ws = [0.0, 1e-30, 1e-6, 1.0, 1e6];
    for &(s, t) in &params {
        for &x in &xs {
            for &w in &ws {
                points.push([s, t, x, w]);
            }
        }
    }
    points
}

#[test]
fn shaping_on_the_gpu_agrees_with_the_interpreter() {
    let Some(gpu) = gpu::for_tests() else { return };
    let points = points();
    let n = points.len();
    let column = |k: usize| -> Vec<f64> { points.iter().map(|p| f64::from(p[k])).collect() };
    let columns: Vec<Vec<f64>> = (0..4).map(column).collect();
    let input: Vec<u8> = points.iter().flatten().flat_map(|x| x.to_bits().to_le_bytes()).collect();

    // Six functions per shader: three into Ci, three into Oi.
    for chunk in FUNCTIONS.chunks(6) {
        let e: Vec<&str> = chunk.iter().map(|f| f.0).collect();
        let src = format!(
            "#include <pattern.sl>\nsurface t() {{ float keep = 0 * (s + t + u + v);\n\
             Ci = color({}, {}, {}) + keep; Oi = color({}, {}, {}); }}\n",
            e[0], e[1], e[2], e[3], e[4], e[5]
        );
        let checked = patina_compiler::check_source("shaping_gpu.sl", &src, &MemoryLoader::default());
        assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
        let shader = &Prepared::new(checked.program.shaders[0].clone());

        let program = CpuProgram::compile(shader, &Binding::default()).expect("the interpreter compiles");
        let inputs: Vec<(&str, &[f64])> =
            ["s", "t", "u", "v"].iter().zip(&columns).map(|(n, c)| (*n, c.as_slice())).collect();
        let cpu = Evaluator::<f32>::new(&program).eval_points(n, &inputs, &["Ci", "Oi"]).expect("evaluation");

        let kernel = compile_kernel(shader, &[], &[], &["s", "t", "u", "v"], &["Ci", "Oi"])
            .expect("the WGSL backend compiles pattern.sl");
        assert_eq!((kernel.input_stride, kernel.output_stride), (4, 6));
        let groups = (n as u32).div_ceil(KERNEL_WORKGROUP);
        let bytes =
            gpu.compute(&kernel.module, "main", &[], &[&input], n * 6 * 4, groups).expect("the kernel runs");
        let gpu_out: Vec<f32> = bytes
            .chunks_exact(4)
            .map(|c| f32::from_bits(u32::from_le_bytes([c[0], c[1], c[2], c[3]])))
            .collect();

        for (j, &(name, uses_pow)) in chunk.iter().enumerate() {
            let (cpu_col, slot) = if j < 3 { (&cpu[0], j) } else { (&cpu[1], j - 3) };
            let mut worst = (0.0f32, [0.0f32; 4]);
            let mut identical = 0;
            for (i, p) in points.iter().enumerate() {
                let r = cpu_col[3 * i + slot] as f32;
                let g = gpu_out[6 * i + j];
                // gammacorrect(gamma, x) for x > 1 may overflow; elsewhere everything is finite.
                if !(name.starts_with("gammacorrect") && p[2] > 1.0) {
                    assert!(r.is_finite() && g.is_finite(), "{name} at {p:?}: gpu {g}, interpreter {r}");
                }
                if g.to_bits() == r.to_bits() {
                    identical += 1;
                    continue;
                }
                let err = (g - r).abs() / r.abs().max(1.0);
                if uses_pow {
                    if !r.is_finite() {
                        continue;
                    }
                    assert!(err <= POW_TOL, "{name} at {p:?}: gpu {g:e}, interpreter {r:e}");
                    if err > worst.0 {
                        worst = (err, *p);
                    }
                } else {
                    panic!(
                        "{name} at {p:?}: gpu {g:e} ({:#010x}), interpreter {r:e} ({:#010x})",
                        g.to_bits(),
                        r.to_bits()
                    );
                }
            }
            println!(
                "{name:32} {identical} of {n} bit-identical, largest difference {:.3e} at {:?}",
                worst.0, worst.1
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Splines, sinusoid sums and bricks (pattern.sl, and the built-in `spline`), on the interpreter in
// f64 and f32 against independent ports written here, and on the GPU against the interpreter.
// Measured numbers are printed with `--nocapture`.

use crate::support;

/// Peachey's C `spline` (T&M L1410-1440) in f64, with the span clamp corrected to nknots - 4
/// (catalogue §1.3: as printed, x = 1 reads one knot past the end): Horner on the coefficients
/// c3..c0 of the Catmull-Rom basis matrix.
fn peachey_spline(x: f64, knots: &[f64]) -> f64 {
    const CR: [[f64; 4]; 4] =
        [[-0.5, 1.5, -1.5, 0.5], [1.0, -2.5, 2.0, -0.5], [-0.5, 0.0, 0.5, 0.0], [0.0, 1.0, 0.0, 0.0]];
    let nspans = knots.len() - 3;
    let x = x.clamp(0.0, 1.0) * nspans as f64;
    let span = (x as usize).min(knots.len() - 4);
    let x = x - span as f64;
    let k = &knots[span..span + 4];
    let c: Vec<f64> = CR.iter().map(|row| row.iter().zip(k).map(|(a, b)| a * b).sum()).collect();
    ((c[0] * x + c[1]) * x + c[2]) * x + c[3]
}

/// A float as a shader literal that keeps its exact value (the shortest repr of an f32 value).
fn lit(x: f64) -> String {
    let s = format!("{:?}", f64::from(x as f32));
    if s.contains('.') || s.contains('e') { s } else { format!("{s}.0") }
}

/// Spline parameters: the seeds' ends (0 gives knot 2, 1 gives knot N-1), outside [0, 1]
/// (clamped), the knots' own parameters k / nspans, the extremes, and random points.
fn spline_params(spans: usize) -> Vec<f64> {
    let mut xs = support::extremes();
    xs.extend([-2.0, 2.0, 0.25, 0.75]);
    xs.extend((0..=spans).map(|k| k as f64 / spans as f64));
    let mut rng = Rng(3);
    xs.extend((0..200).map(|_| rng.unit()));
    xs
}

#[test]
fn spline_matches_peachey_for_float_and_colour_knots() {
    let mut rng = Rng(5);
    for n in [4usize, 5, 7, 10, 16, 33] {
        let knots: Vec<f64> = (0..n).map(|_| f64::from(rng.range(-2.0, 2.0) as f32)).collect();
        let listed = knots.iter().map(|&k| lit(k)).collect::<Vec<_>>().join(", ");
        // Colour knots: three float splines (L1446-1458), the knots' components shifted copies.
        let ck: Vec<[f64; 3]> = (0..n).map(|i| [knots[i], knots[(i + 1) % n], knots[(i + 2) % n]]).collect();
        let colours = ck
            .iter()
            .map(|c| format!("color({}, {}, {})", lit(c[0]), lit(c[1]), lit(c[2])))
            .collect::<Vec<_>>()
            .join(", ");
        let src = format!(
            "surface t(varying float x = 0) {{\n\
             constant float k[{n}] = {{{listed}}};\n\
             constant color c[{n}] = {{{colours}}};\n\
             Ci = color(spline(x, {listed}), spline(x, k), 0);\n\
             Oi = spline(x, c) + 0 * color spline(x, {colours});\n}}\n"
        );
        let program = support::program(&src);
        let xs = spline_params(n - 3);
        let count = xs.len();
        let inputs = [("x", &xs[..])];
        let ends = [knots[1], knots[n - 2]];
        for (prec, out) in [
            ("f64", program.cpu::<f64>(count, &inputs, &["Ci", "Oi"])),
            ("f32", program.cpu::<f32>(count, &inputs, &["Ci", "Oi"])),
        ] {
            // f32: x * (n - 3) rounds to half an ulp of the span count, times the slope.
            let tol = if prec == "f64" { 1e-12 } else { 4e-7 * (n - 3) as f64 };
            let mut worst = 0.0f64;
            for (i, &x) in xs.iter().enumerate() {
                let x = if prec == "f32" { f64::from(x as f32) } else { x };
                let want = peachey_spline(x, &knots);
                for got in [out[0][3 * i], out[0][3 * i + 1]] {
                    worst = worst.max((got - want).abs());
                }
                for c in 0..3 {
                    let kc: Vec<f64> = ck.iter().map(|k| k[c]).collect();
                    worst = worst.max((out[1][3 * i + c] - peachey_spline(x, &kc)).abs());
                }
                // The seeds' conventions: knot 2 at x <= 0, knot N-1 at x >= 1, exactly.
                if x <= 0.0 {
                    assert_eq!(out[0][3 * i], ends[0], "{n} knots at x = {x} ({prec})");
                }
                if x >= 1.0 {
                    assert_eq!(out[0][3 * i], ends[1], "{n} knots at x = {x} ({prec})");
                }
            }
            println!("spline, {n:2} knots, {prec}: largest difference from Peachey's code {worst:.3e}");
            assert!(worst <= tol, "spline with {n} knots ({prec}): {worst:e}");
        }
        if let Some(gpu) = patina_runtime::gpu::for_tests() {
            let cpu = program.cpu::<f32>(count, &inputs, &["Ci", "Oi"]);
            let got = program.gpu(gpu, count, &inputs, &["Ci", "Oi"]);
            for k in 0..2 {
                let (d, at) = support::worst(&got[k], &cpu[k]);
                assert!(d == 0.0, "spline with {n} knots: the GPU differs by {d:e} at x = {}", xs[at / 3]);
            }
        }
    }
}

/// The sinusoid sum's definition, in f64 with Rust's own sin on the unreduced argument.
fn sinesum_reference(x: f64, w: f64, minfreq: f64, maxfreq: f64) -> f64 {
    if minfreq <= 0.0 {
        return 0.0;
    }
    let mut f = minfreq.max(1e-30);
    let mut value = 0.0;
    for _ in 0..30 {
        if f < maxfreq {
            let fade = (2.0 - 4.0 * f * w.max(0.0)).clamp(0.0, 1.0);
            value += fade * (2.0 * std::f64::consts::PI * f * x).sin() / f;
        }
        f *= 2.0;
    }
    value
}

const SINESUM: &str = "#include <pattern.sl>\n\
    surface t(varying float x = 0, w = 0, lo = 1, hi = 64) {\n\
    Ci = color(sinesum(x, w, lo, hi), 0, 0); Oi = 0; }\n";

#[test]
fn sinesum_matches_its_definition_and_fades_terms_above_nyquist() {
    let program = support::program(SINESUM);
    let mut rng = Rng(9);
    let mut pts: Vec<[f64; 4]> = Vec::new();
    for i in 0..1500 {
        let lo = [1.0, 0.5, 3.0, 0.1][i % 4];
        let hi = [64.0, 1000.0, 8.0, 3.0][(i / 4) % 4];
        let w = match i % 3 {
            0 => 0.0,
            1 => 10f64.powf(rng.range(-4.0, 0.0)),
            _ => rng.range(0.0, 0.05),
        };
        pts.push([rng.range(-20.0, 20.0), w, lo, hi]);
    }
    let cols: Vec<Vec<f64>> = (0..4).map(|k| pts.iter().map(|p| p[k]).collect()).collect();
    let inputs = [("x", &cols[0][..]), ("w", &cols[1][..]), ("lo", &cols[2][..]), ("hi", &cols[3][..])];
    for (prec, out) in [
        ("f64", program.cpu::<f64>(pts.len(), &inputs, &["Ci"])),
        ("f32", program.cpu::<f32>(pts.len(), &inputs, &["Ci"])),
    ] {
        let mut worst = (0.0f64, [0.0; 4]);
        for (i, p) in pts.iter().enumerate() {
            let q = if prec == "f32" { p.map(|v| f64::from(v as f32)) } else { *p };
            let want = sinesum_reference(q[0], q[1], q[2], q[3]);
            let err = (out[0][3 * i] - want).abs() * q[2];
            if err > worst.0 {
                worst = (err, q);
            }
        }
        // Relative to the size of the sum, which is below 2 / minfreq: f64 within 1e-11 (the
        // reference's own sin(2 pi f x) at f x up to 2e4 is good to ~1e-12), f32 within 2e-6.
        let tol = if prec == "f64" { 1e-11 } else { 2e-6 };
        println!("sinesum {prec}: largest error x minfreq {:.3e} at {:?}", worst.0, worst.1);
        assert!(worst.0 <= tol, "sinesum ({prec}): {:e} at {:?}", worst.0, worst.1);
    }
    // Frequency clamping: w = 0.25 / f0 keeps every term below f0 / 2 whole, fades (f0/2, f0)
    // and drops f0 and above. With minfreq 1: w = 1/64 keeps 1..8 whole, fades 16 by 1/2... and
    // a very wide filter leaves nothing.
    let xs = [0.1, 0.37, 3.3];
    for &x in &xs {
        let cases = [(1.0 / 64.0, 1.0, 1000.0), (1e30, 1.0, 1000.0), (0.0, 1.0, 16.0)];
        for (w, lo, hi) in cases {
            let got = program.cpu::<f64>(
                1,
                &[("x", &[x][..]), ("w", &[w][..]), ("lo", &[lo][..]), ("hi", &[hi][..])],
                &["Ci"],
            )[0][0];
            let tau = 2.0 * std::f64::consts::PI;
            let want = if w >= 1.0 {
                0.0
            } else if w == 0.0 {
                (0..4).map(|k| (tau * f64::from(1 << k) * x).sin() / f64::from(1 << k)).sum()
            } else {
                // fade(f) = clamp(2 - 4 f / 64, 0, 1): 1 up to f = 16, 0 from 32 on.
                (0..5).map(|k| (tau * f64::from(1 << k) * x).sin() / f64::from(1 << k)).sum()
            };
            assert!((got - want).abs() < 1e-12, "sinesum({x}, {w}, {lo}, {hi}) = {got}, want {want}");
        }
    }
}

/// Peachey's brick (L1559-1620) in f64, as printed (with `th` read as `h`).
fn brick_reference(s: f64, t: f64, bw: f64, bh: f64, mortar: f64) -> f64 {
    let (bmw, bmh) = (bw + mortar, bh + mortar);
    let (mwf, mhf) = (mortar * 0.5 / bmw, mortar * 0.5 / bmh);
    let step = |a: f64, x: f64| if x < a { 0.0 } else { 1.0 };
    let mut ss = s / bmw;
    let mut tt = t / bmh;
    if (tt * 0.5).rem_euclid(1.0) > 0.5 {
        ss += 0.5;
    }
    ss -= ss.floor();
    tt -= tt.floor();
    (step(mwf, ss) - step(1.0 - mwf, ss)) * (step(mhf, tt) - step(1.0 - mhf, tt))
}

const BRICK: &str = "#include <pattern.sl>\n\
    surface t(varying float x = 0, y = 0, sw = 0, tw = 0, bw = 0.25, bh = 0.08, m = 0.01) {\n\
    Ci = color(filteredbrick(x, y, sw, tw, bw, bh, m), brick(x, y, bw, bh, m), 0); Oi = 0; }\n";

fn brick_inputs(pts: &[[f64; 7]]) -> Vec<Vec<f64>> {
    (0..7).map(|k| pts.iter().map(|p| p[k]).collect()).collect()
}

fn brick_run<F: patina_compiler::backend::cpu::scalar::Real>(
    program: &support::Program,
    pts: &[[f64; 7]],
) -> Vec<Vec<f64>> {
    let cols = brick_inputs(pts);
    let names = ["x", "y", "sw", "tw", "bw", "bh", "m"];
    let inputs: Vec<(&str, &[f64])> = names.iter().zip(&cols).map(|(n, c)| (*n, c.as_slice())).collect();
    program.cpu::<F>(pts.len(), &inputs, &["Ci"])
}

#[test]
fn filtered_brick_is_the_box_mean_of_peachey_brick() {
    let program = support::program(BRICK);
    let mut rng = Rng(13);
    // (s, t, swidth, twidth, brickwidth, brickheight, mortar): boxes from a fraction of the
    // mortar to several bricks, so that boxes span rows and the row shift matters.
    let mut pts = Vec::new();
    for i in 0..160 {
        let (bw, bh, m) = if i % 2 == 0 { (0.25, 0.08, 0.01) } else { (1.0, 0.5, 0.2) };
        let scale = [0.003, 0.05, 0.4, 2.0][i % 4] * (bw + m);
        pts.push([
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            scale * rng.range(0.2, 1.0),
            scale * rng.range(0.2, 1.0),
            bw,
            bh,
            m,
        ]);
    }
    const M: usize = 240;
    let out64 = brick_run::<f64>(&program, &pts);
    let out32 = brick_run::<f32>(&program, &pts);
    let mut worst = [0.0f64; 2];
    for (i, p) in pts.iter().enumerate() {
        // The midpoint rule on an M x M grid: the indicator's edges in the box misjudge at most
        // one row or column of samples each.
        let mut sum = 0.0;
        for a in 0..M {
            let s = p[0] - p[2] / 2.0 + (a as f64 + 0.5) * p[2] / M as f64;
            for b in 0..M {
                let t = p[1] - p[3] / 2.0 + (b as f64 + 0.5) * p[3] / M as f64;
                sum += brick_reference(s, t, p[4], p[5], p[6]);
            }
        }
        let mean = sum / (M * M) as f64;
        let (bmw, bmh) = (p[4] + p[6], p[5] + p[6]);
        let edges_s = 2.0 * (2.0 * p[2] / bmw + 2.0); // both rows' edges
        let edges_t = 2.0 * (p[3] / bmh + 2.0);
        let tol = (edges_s + edges_t) / M as f64;
        for (k, out) in [&out64, &out32].iter().enumerate() {
            let err = (out[0][3 * i] - mean).abs();
            worst[k] = worst[k].max(err / tol);
            assert!(err <= tol, "filteredbrick at {p:?}: {} vs box mean {mean} (tol {tol:e})", out[0][3 * i]);
        }
    }
    println!(
        "filteredbrick vs a {M}x{M} midpoint rule: worst {:.0}% (f64), {:.0}% (f32) of the rule's tolerance",
        100.0 * worst[0],
        100.0 * worst[1]
    );
}

#[test]
fn brick_limits_and_extremes() {
    let program = support::program(BRICK);
    let mut rng = Rng(17);
    // Unfiltered: Peachey's brick, away from the mortar edges (within rounding either side is
    // right); widths 0 give the same.
    let mut pts = Vec::new();
    for _ in 0..3000 {
        pts.push([rng.range(-10.0, 10.0), rng.range(-10.0, 10.0), 0.0, 0.0, 0.25, 0.08, 0.01]);
    }
    for (prec, out) in [("f64", brick_run::<f64>(&program, &pts)), ("f32", brick_run::<f32>(&program, &pts))]
    {
        let mut checked = 0;
        for (i, p) in pts.iter().enumerate() {
            let p = if prec == "f32" { p.map(|v| f64::from(v as f32)) } else { *p };
            let d = 1e-5;
            let r = brick_reference(p[0], p[1], p[4], p[5], p[6]);
            let around = [(-d, -d), (-d, d), (d, -d), (d, d)];
            if around.iter().any(|(a, b)| brick_reference(p[0] + a, p[1] + b, p[4], p[5], p[6]) != r) {
                continue;
            }
            checked += 1;
            assert_eq!(out[0][3 * i + 1], r, "brick at {p:?} ({prec})");
            assert_eq!(out[0][3 * i], r, "filteredbrick with zero widths at {p:?} ({prec})");
        }
        assert!(checked > 2500);
    }
    // Wide boxes: the brick's area fraction (1 - 2 MWF)(1 - 2 MHF) = (0.25 / 0.26)(0.08 / 0.09).
    let frac = (0.25 / 0.26) * (0.08 / 0.09);
    let wide = [[0.3, 0.7, 1e6, 1e6, 0.25, 0.08, 0.01], [-5.0, 1e4, 1e30, 1e30, 0.25, 0.08, 0.01]];
    for (prec, out) in
        [("f64", brick_run::<f64>(&program, &wide)), ("f32", brick_run::<f32>(&program, &wide))]
    {
        for (i, p) in wide.iter().enumerate() {
            assert!(
                (out[0][3 * i] - frac).abs() < 1e-5,
                "filteredbrick at {p:?} ({prec}): {}",
                out[0][3 * i]
            );
        }
    }
    // The sweep: every coordinate, width and size extreme, finite on both backends.
    let ex = support::extremes();
    let sizes =
        [(0.25, 0.08, 0.01), (0.0, 0.0, 0.0), (1e30, 1e30, 1e30), (-1.0, 0.5, -1.0), (1e-30, 1e-30, 0.5)];
    let mut sweep = Vec::new();
    for (j, &x) in ex.iter().enumerate() {
        for (k, &w) in ex.iter().enumerate() {
            let (bw, bh, m) = sizes[(j + k) % sizes.len()];
            sweep.push([x, ex[(j + 3) % ex.len()], w.abs(), ex[(k + 5) % ex.len()].abs(), bw, bh, m]);
            sweep.push([x, -x, w, w, bw, bh, m]);
        }
    }
    let cpu32 = brick_run::<f32>(&program, &sweep);
    support::assert_finite("brick (f32)", &cpu32[0], 3);
    support::assert_finite("brick (f64)", &brick_run::<f64>(&program, &sweep)[0], 3);
    if let Some(gpu) = patina_runtime::gpu::for_tests() {
        let cols = brick_inputs(&sweep);
        let names = ["x", "y", "sw", "tw", "bw", "bh", "m"];
        let inputs: Vec<(&str, &[f64])> = names.iter().zip(&cols).map(|(n, c)| (*n, c.as_slice())).collect();
        let got = program.gpu(gpu, sweep.len(), &inputs, &["Ci"]);
        support::assert_finite("brick (GPU)", &got[0], 3);
        let (d, at) = support::worst(&got[0], &cpu32[0]);
        println!("brick sweep: GPU vs interpreter largest difference {d:e}");
        assert!(d == 0.0, "brick: the GPU differs by {d:e} at {:?}", sweep[at / 3]);
    }
}

#[test]
fn sinesum_extremes_and_the_gpu() {
    let program = support::program(SINESUM);
    let ex = support::extremes();
    let freqs = [(1.0, 64.0), (0.0, 64.0), (-1.0, 1.0), (1e-30, 1e30), (1e4, 1e7), (1e30, 3e38), (0.5, 0.0)];
    let mut pts = Vec::new();
    for &x in &ex {
        for &w in &ex {
            for &(lo, hi) in &freqs {
                pts.push([x, w, lo, hi]);
            }
        }
    }
    let mut rng = Rng(23);
    for _ in 0..2000 {
        pts.push([
            rng.range(-100.0, 100.0),
            rng.range(0.0, 0.1),
            [1.0, 0.25, 2.0][rng.next() as usize % 3],
            1e4,
        ]);
    }
    let cols: Vec<Vec<f64>> = (0..4).map(|k| pts.iter().map(|p| p[k]).collect()).collect();
    let inputs = [("x", &cols[0][..]), ("w", &cols[1][..]), ("lo", &cols[2][..]), ("hi", &cols[3][..])];
    let cpu32 = program.cpu::<f32>(pts.len(), &inputs, &["Ci"]);
    support::assert_finite("sinesum (f32)", &cpu32[0], 3);
    support::assert_finite("sinesum (f64)", &program.cpu::<f64>(pts.len(), &inputs, &["Ci"])[0], 3);
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let got = program.gpu(gpu, pts.len(), &inputs, &["Ci"]);
    support::assert_finite("sinesum (GPU)", &got[0], 3);
    // sin differs (lavapipe within ~1e-7 absolute on [-pi, pi]; the arguments are identical), so
    // the difference is at most that times sum(1 / f) < 2 / minfreq.
    let mut worst = (0.0f64, [0.0; 4]);
    for (i, p) in pts.iter().enumerate() {
        let d = (got[0][3 * i] - cpu32[0][3 * i]).abs() * (p[2] as f32).max(1e-30) as f64;
        if d > worst.0 {
            worst = (d, *p);
        }
    }
    println!("sinesum GPU vs interpreter: largest difference x minfreq {:.3e} at {:?}", worst.0, worst.1);
    assert!(worst.0 <= SINESUM_GPU_TOL, "sinesum on the GPU: {:e} at {:?}", worst.0, worst.1);
}

/// GPU vs interpreter for sinesum, times minfreq (the sum is below 2 / minfreq).
const SINESUM_GPU_TOL: f64 = 2e-6;
