//! The standard library's noise core (`compiler/stdlib/noise.sl`) on the GPU: the same shader compiled as
//! a compute kernel by the WGSL backend, against the interpreter's f32 mode, over a few thousand
//! points (random ones, cell and period edges, lattice points, offsets 2^k up to 2^24, and every
//! combination of the extreme coordinates 0, ±1e-30, ±1e-40 (an f32 denormal), ±1e4, ±1e6, ±1e7,
//! ±1e30).
//!
//! Improved noise uses only `+ - *`, `floor`, comparisons, selections, a float-to-int conversion
//! of a value in [0, 256) and integer `& +` with table lookups. WGSL computes all of them exactly
//! on a device that rounds `+ - *` correctly and fuses no multiply-add (lavapipe: see
//! docs/numerics.md), and the interpreter defines them the same way, so the results must be
//! bit-identical. Compute shaders on lavapipe keep denormals, as the interpreter does.
//!
//! Needs a GPU adapter (lavapipe is enough); panics without one unless `PATINA_GPU=off`.

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_compiler::backend::wgsl::{KERNEL_WORKGROUP, compile_kernel};
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::gpu;
use patina_test_support::Rng;

const SHADER: &str = "#include <noise.sl>\n\
    surface t() { Ci = color(improved_noise(P), snoise3(P), noise3(P)); }\n";

fn points() -> Vec<[f32; 3]> {
    let mut rng = Rng(29);
    let mut points = Vec::new();
    for _ in 0..1000 {
        points.push(rng.point_f32(-2.0, 2.0));
    }
    for _ in 0..2000 {
        points.push(rng.point_f32(-600.0, 600.0));
    }
    for _ in 0..500 {
        // Near the edges of the period (cells 255 and 0), from both sides.
        let mut edge = || (256.0 * rng.range(-3.0, 3.0).round() + rng.range(-1.5, 1.5)) as f32;
        points.push([edge(), edge(), edge()]);
    }
    for _ in 0..200 {
        points.push(rng.point_f32(-1000.0, 1000.0).map(f32::floor));
    }
    for k in 0..=24 {
        let offset = 2f64.powi(k);
        for i in 0..40 {
            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
            points.push([0, 1, 2].map(|_| (sign * (offset + rng.unit())) as f32));
        }
    }
    let extremes = [0.0, 1e-30, -1e-30, 1e-40, -1e-40, 1e4, -1e4, 1e6, -1e6, 1e7, -1e7, 1e30, -1e30];
    for &x in &extremes {
        for &y in &extremes {
            for &z in &extremes {
                points.push([x, y, z]);
            }
        }
    }
    points
}

#[test]
fn improved_noise_on_the_gpu_is_bit_identical_to_the_interpreter() {
    let Some(gpu) = gpu::for_tests() else { return };
    let checked = patina_compiler::check_source("noise_gpu.sl", SHADER, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    let shader = &Prepared::new(checked.program.shaders[0].clone());
    let points = points();
    let n = points.len();

    // The interpreter in f32.
    let program =
        CpuProgram::compile(shader, &Binding::default()).expect("the interpreter compiles noise.sl");
    let column: Vec<f64> = points.iter().flatten().map(|&x| f64::from(x)).collect();
    let cpu = Evaluator::<f32>::new(&program).eval_points(n, &[("P", &column)], &["Ci"]).expect("evaluation");
    let cpu: Vec<f32> = cpu[0].iter().map(|&x| x as f32).collect();

    // The GPU: one invocation per point, P in, Ci out.
    let kernel =
        compile_kernel(shader, &[], &[], &["P"], &["Ci"]).expect("the WGSL backend compiles noise.sl");
    assert_eq!((kernel.input_stride, kernel.output_stride), (3, 3));
    let input: Vec<u8> = points.iter().flatten().flat_map(|x| x.to_bits().to_le_bytes()).collect();
    let groups = (n as u32).div_ceil(KERNEL_WORKGROUP);
    let bytes =
        gpu.compute(&kernel.module, "main", &[], &[&input], n * 3 * 4, groups).expect("the kernel runs");
    let gpu_out: Vec<f32> =
        bytes.chunks_exact(4).map(|c| f32::from_bits(u32::from_le_bytes([c[0], c[1], c[2], c[3]]))).collect();

    let names = ["improved_noise", "snoise3", "noise3"];
    let mut differing = Vec::new();
    for (i, p) in points.iter().enumerate() {
        for c in 0..3 {
            let (g, r) = (gpu_out[3 * i + c], cpu[3 * i + c]);
            assert!(r.is_finite(), "{}({p:?}) = {r} on the interpreter", names[c]);
            if g.to_bits() != r.to_bits() {
                differing.push(format!(
                    "{}({p:?}): gpu {g:e} ({:#010x}), interpreter {r:e} ({:#010x})",
                    names[c],
                    g.to_bits(),
                    r.to_bits()
                ));
            }
        }
    }
    println!("{} of {} values bit-identical", 3 * n - differing.len(), 3 * n);
    assert!(
        differing.is_empty(),
        "{} values differ:\n{}",
        differing.len(),
        differing[..differing.len().min(20)].join("\n")
    );
}
