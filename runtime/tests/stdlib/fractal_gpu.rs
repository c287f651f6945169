//! The standard library's fractal sums (`compiler/stdlib/fractal.sl`) on the GPU: the shader of
//! `compiler/tests/interpreter/stdlib_fractal.rs` compiled as a compute kernel by the WGSL backend, against
//! the interpreter's f32 mode, with every parameter varying per point: ordinary argument sets
//! and the extremes (octaves 0 and 30, H 0 and 2, lacunarity 1 and 8, coordinates ±1e4, ±1e6,
//! ±1e7, ±1e30 and denormals, width 0 and 1e30, offsets 0, ±1e4 and ±1e30).
//!
//! The noise is bit-exact between the two (runtime/tests/stdlib/noise_gpu.rs); what differs is
//! `pow` (lavapipe computes exp2(b log2 a) in f32, up to 89 ulp: shared/notes/naga-wgpu-facts.md
//! §8) in the spectral weights, and `log` in fbm_filtered's octave count. A weight off by a few
//! 1e-6 relative moves a sum of octaves (each at most 1) by a few 1e-6; the octave count's error
//! moves the fractional octave's weight. `GPU_TOL` is the bound, the measured largest difference
//! is printed. Finite everywhere on both.
//!
//! Needs a GPU adapter (lavapipe is enough); panics without one unless `PATINA_GPU=off`.

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_compiler::backend::wgsl::{KERNEL_WORKGROUP, compile_kernel};
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::gpu;

use crate::support;
use patina_test_support::Rng;

const SHADER: &str = "#include <fractal.sl>\n\
    surface t(varying float H = 0.5, lac = 2, oct = 4, width = 0.01, offset = 1, gain = 2) {\n\
        Ci = color(fbm(P, H, lac, oct), turbulence(P, oct), fbm_filtered(P, H, lac, oct, width));\n\
        Oi = color(ridged_multifractal(P, H, lac, oct, offset, gain),\n\
                   hybrid_multifractal(P, H, lac, oct, offset), turbulence_filtered(P, oct, width));\n\
    }\n";

const NAMES: [&str; 6] = [
    "fbm",
    "turbulence",
    "fbm_filtered",
    "ridged_multifractal",
    "hybrid_multifractal",
    "turbulence_filtered",
];

/// The inputs in the kernel's order: P (3), H, lac, oct, width, offset, gain.
const INPUTS: [&str; 7] = ["P", "H", "lac", "oct", "width", "offset", "gain"];

/// The GPU's tolerance against the interpreter's f32 mode (absolute; the values are at most a
/// few units). Measured on lavapipe: 2.4e-7 (fBm, fbm_filtered), 0 (turbulence, which has no
/// pow), 1.4e-6 (the multifractals); 79% of the values bit-identical.
const GPU_TOL: f32 = 1e-5;

/// Argument sets, 9 words each: P, H, lac, oct, width, offset, gain.
fn args() -> Vec<[f32; 9]> {
    let mut rng = Rng(41);
    let mut args = Vec::new();
    for i in 0..2000 {
        let lac = if i % 2 == 0 { 2.0 } else { rng.range_f32(1.5, 3.0) };
        args.push([
            rng.range_f32(-50.0, 50.0),
            rng.range_f32(-50.0, 50.0),
            rng.range_f32(-50.0, 50.0),
            rng.range_f32(0.0, 1.5),
            lac,
            rng.range_f32(0.0, 10.0),
            10f64.powf(f64::from(rng.range_f32(-4.0, 0.0))) as f32,
            rng.range_f32(0.5, 1.2),
            rng.range_f32(1.0, 3.0),
        ]);
    }
    let points = [
        [0.0, 0.0, 0.0],
        [0.3, -0.7, 0.55],
        [1e4, -1e4, 1e4 + 0.37],
        [-1e4, 1e4, -1e4],
        [1e6, -1e6, 1e6 + 0.5],
        [-1e6, 1e6 + 0.25, -1e6],
        [1e30, -1e30, 1e-30],
        [1e7, -1e7 + 0.5, f32::from_bits(1)],
    ];
    for p in points {
        for oct in [0.0, 0.5, 1.0, 7.3, 30.0] {
            for h in [0.0, 2.0] {
                for lac in [1.0, 2.0, 8.0] {
                    for width in [0.0, 1e-3, 1.0, 1e30] {
                        args.push([p[0], p[1], p[2], h, lac, oct, width, 1.0, 2.0]);
                    }
                }
            }
        }
        // the multifractals' offsets and gains at their extremes
        for (offset, gain) in [(0.0, 0.0), (1e4, 1e30), (-1e4, 1.0), (1e30, 2.0), (-1e30, -1e30)] {
            for (h, lac) in [(0.0, 1.0), (2.0, 8.0), (0.0, 8.0)] {
                args.push([p[0], p[1], p[2], h, lac, 30.0, 1e-3, offset, gain]);
            }
        }
    }
    args
}

#[test]
fn fractal_sums_on_the_gpu_match_the_interpreter() {
    let Some(gpu) = gpu::for_tests() else { return };
    let checked = patina_compiler::check_source("fractal_gpu.sl", SHADER, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    let shader = &Prepared::new(checked.program.shaders[0].clone());
    let args = args();
    let n = args.len();

    // The interpreter in f32.
    let program =
        CpuProgram::compile(shader, &Binding::default()).expect("the interpreter compiles fractal.sl");
    let p: Vec<f64> = args.iter().flat_map(|a| a[..3].iter().map(|&x| f64::from(x))).collect();
    let scalars: Vec<Vec<f64>> = (3..9).map(|k| args.iter().map(|a| f64::from(a[k])).collect()).collect();
    let mut inputs: Vec<(&str, &[f64])> = vec![("P", &p)];
    for (name, column) in INPUTS[1..].iter().zip(&scalars) {
        inputs.push((name, column));
    }
    let cpu = Evaluator::<f32>::new(&program).eval_points(n, &inputs, &["Ci", "Oi"]).expect("evaluation");
    let cpu: Vec<[f32; 6]> = (0..n)
        .map(|i| {
            let (c, o) = (&cpu[0][3 * i..3 * i + 3], &cpu[1][3 * i..3 * i + 3]);
            [c[0], c[1], c[2], o[0], o[1], o[2]].map(|x| x as f32)
        })
        .collect();

    // The GPU: one invocation per argument set.
    let kernel = compile_kernel(shader, &[], &[], &INPUTS, &["Ci", "Oi"])
        .expect("the WGSL backend compiles fractal.sl");
    assert_eq!((kernel.input_stride, kernel.output_stride), (9, 6));
    let input: Vec<u8> = args.iter().flatten().flat_map(|x| x.to_bits().to_le_bytes()).collect();
    let groups = (n as u32).div_ceil(KERNEL_WORKGROUP);
    let bytes =
        gpu.compute(&kernel.module, "main", &[], &[&input], n * 6 * 4, groups).expect("the kernel runs");
    let gpu_out: Vec<f32> =
        bytes.chunks_exact(4).map(|c| f32::from_bits(u32::from_le_bytes([c[0], c[1], c[2], c[3]]))).collect();

    let mut worst = [0.0f32; 6];
    let mut identical = 0;
    for (i, a) in args.iter().enumerate() {
        for f in 0..6 {
            let (g, r) = (gpu_out[6 * i + f], cpu[i][f]);
            assert!(r.is_finite(), "{}({a:?}) = {r} on the interpreter", NAMES[f]);
            assert!(g.is_finite(), "{}({a:?}) = {g} on the GPU", NAMES[f]);
            let err = (g - r).abs();
            worst[f] = worst[f].max(err);
            identical += usize::from(g.to_bits() == r.to_bits());
            assert!(err <= GPU_TOL, "{}({a:?}): gpu {g:e}, interpreter {r:e}", NAMES[f]);
        }
    }
    println!("{n} argument sets; {identical} of {} values bit-identical", 6 * n);
    println!("largest GPU - interpreter difference per function {worst:?}");
}

/// The multiplicative functions and distorted noise (multifractal, hetero_terrain, distnoise,
/// distfbm) with every parameter varying.
const SHADER2: &str = "#include <fractal.sl>\n\
    surface t(varying float H = 0.25, lac = 2, oct = 4, offset = 0.8, d = 1) {\n\
        Ci = color(multifractal(P, H, lac, oct, offset), hetero_terrain(P, H, lac, oct, offset),\n\
                   distnoise(P, d));\n\
        Oi = color(distfbm(P, H, lac, oct, d), 0, 0);\n\
    }\n";

/// The GPU's tolerances for SHADER2 against the interpreter's f32 mode, relative to
/// max(1, |value|). The multifractal and the terrain differ only through pow in the spectral
/// weights (a product of n factors compounds n such errors): measured 4.5e-7 and 4.0e-7.
/// distnoise and distfbm differ more: measured 1.5e-5 and 2.7e-5. In a small kernel the same
/// operations (p + d * v with the three noises) agree to the bit (checked while writing this
/// test), so the difference comes from how lavapipe compiles this larger kernel, presumably a
/// fused multiply-add for p + d * v (one rounding instead of two): one ulp of the displaced
/// argument (4e-6 at |p| = 50) times the noise's slope (up to about 3), and more at the finer
/// octaves' larger coordinates.
const GPU_TOL2: f64 = 1e-5;
const GPU_TOL2_DISTORTED: f64 = 1e-4;

#[test]
fn multiplicative_and_distorted_on_the_gpu_match_the_interpreter() {
    let Some(gpu) = gpu::for_tests() else { return };
    let program = support::program(SHADER2);
    let mut rng = Rng(43);
    let mut rows: Vec<[f64; 8]> = Vec::new();
    for i in 0..1500 {
        let p = rng.point(-50.0, 50.0);
        let lac = if i % 2 == 0 { 2.0 } else { rng.range(1.5, 3.0) };
        rows.push([
            p[0],
            p[1],
            p[2],
            rng.range(0.0, 1.5),
            lac,
            rng.range(0.0, 10.0),
            rng.range(0.0, 1.2),
            rng.range(0.0, 3.0),
        ]);
    }
    let denormal = f64::from(f32::from_bits(1));
    let points = [
        [0.0, 0.0, 0.0],
        [1e4, -1e4, 1e4 + 0.37],
        [-1e6, 1e6 + 0.25, -1e6],
        [1e7, -1e7 + 0.5, denormal],
        [1e30, -1e30, 1e-30],
    ];
    for p in points {
        for oct in [0.0, 0.5, 30.0] {
            for h in [0.0, 2.0] {
                for lac in [1.0, 8.0] {
                    for (offset, d) in
                        [(0.0, 0.0), (1e4, 1e30), (-1e4, -1e30), (1e30, 1.0), (-1e30, 1e-30), (0.8, -1.0)]
                    {
                        rows.push([p[0], p[1], p[2], h, lac, oct, offset, d]);
                    }
                }
            }
        }
    }
    let rows: Vec<[f64; 8]> = rows.iter().map(|r| r.map(|x| f64::from(x as f32))).collect();
    let n = rows.len();
    let p: Vec<f64> = rows.iter().flat_map(|r| r[..3].to_vec()).collect();
    let cols: Vec<Vec<f64>> = (3..8).map(|k| rows.iter().map(|r| r[k]).collect()).collect();
    let names = ["H", "lac", "oct", "offset", "d"];
    let mut inputs: Vec<(&str, &[f64])> = vec![("P", &p)];
    for (name, c) in names.iter().zip(&cols) {
        inputs.push((name, c));
    }
    let cpu = program.cpu::<f32>(n, &inputs, &["Ci", "Oi"]);
    let out = program.gpu(gpu, n, &inputs, &["Ci", "Oi"]);
    let funcs = ["multifractal", "hetero_terrain", "distnoise", "distfbm"];
    let mut worst = [0.0f64; 4];
    let mut identical = 0;
    for (i, r) in rows.iter().enumerate() {
        let c = [cpu[0][3 * i], cpu[0][3 * i + 1], cpu[0][3 * i + 2], cpu[1][3 * i]];
        let g = [out[0][3 * i], out[0][3 * i + 1], out[0][3 * i + 2], out[1][3 * i]];
        for f in 0..4 {
            assert!(
                c[f].is_finite() && g[f].is_finite(),
                "{}({r:?}): interpreter {}, gpu {}",
                funcs[f],
                c[f],
                g[f]
            );
            let err = (c[f] - g[f]).abs() / c[f].abs().max(1.0);
            worst[f] = worst[f].max(err);
            identical += usize::from(c[f] == g[f]);
            let tol = if f < 2 { GPU_TOL2 } else { GPU_TOL2_DISTORTED };
            assert!(err <= tol, "{}({r:?}): interpreter {:e}, gpu {:e}", funcs[f], c[f], g[f]);
        }
    }
    println!("{n} argument sets; {identical} of {} values identical", 4 * n);
    println!("largest relative GPU - interpreter difference {funcs:?}: {worst:?}");
}
