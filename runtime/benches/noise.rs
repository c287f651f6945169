//! Nanoseconds per evaluation of each noise variant of the standard library, on the interpreter
//! (f32, 128-lane batches) and on the GPU (the WGSL backend's compute kernel on whatever adapter
//! wgpu finds; lavapipe in CI), for the table in docs/stdlib/noise.md.
//!
//! Each variant is a shader `Ci = color(EXPR, 0, 0)` over `POINTS` points P spread over many
//! cells. The GPU's time per evaluation is that of the kernel minus that of the same kernel
//! without the noise (`Ci = P`): what remains is the noise, not the buffer transfers. Criterion
//! reports each measurement; the summary table at the end gives the medians.

use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};

#[path = "support/timing.rs"]
mod timing;
use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_compiler::backend::wgsl::{KERNEL_WORKGROUP, Kernel, compile_kernel};
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::gpu::Gpu;
use timing::median;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Points per measurement.
const POINTS: usize = 1 << 16;

/// (name in the table, module to include, expression of P).
const VARIANTS: &[(&str, &str, &str)] = &[
    ("improved noise 3D (snoise3)", "noise.sl", "snoise3(P)"),
    ("improved noise 1D (snoise1)", "noise.sl", "snoise1(xcomp(P))"),
    ("improved noise 2D (snoise2)", "noise.sl", "snoise2(xcomp(P), ycomp(P))"),
    ("improved noise 4D (snoise4)", "noise.sl", "snoise4(P, zcomp(P) * 0.7)"),
    ("periodic noise 3D (psnoise3)", "noise.sl", "psnoise3(P, point(5, 6, 7))"),
    ("Perlin's original noise (perlin_noise3)", "noise.sl", "perlin_noise3(P)"),
    ("analytic gradient (dsnoise3)", "noise.sl", "xcomp(dsnoise3(P))"),
    ("vector noise (vsnoise3)", "noise.sl", "xcomp(vsnoise3(P))"),
    ("flow noise (flownoise3)", "noise.sl", "flownoise3(P, 0.7)"),
    ("built-in noise(P)", "noise.sl", "noise(P)"),
    ("built-in color noise(P)", "noise.sl", "comp(color noise(P), 0)"),
    ("cellnoise 3D (cellnoise3)", "cellular.sl", "cellnoise3(P, 0)"),
    ("Worley F1 (worley_f1)", "cellular.sl", "worley_f1(P)"),
    ("value noise (vnoise)", "lattice.sl", "vnoise(P)"),
    ("lattice convolution noise (vcnoise)", "lattice.sl", "vcnoise(P)"),
    ("sparse convolution noise (scnoise)", "lattice.sl", "scnoise(P)"),
    ("fBm, 6 octaves (fbm)", "fractal.sl", "fbm(P, 1, 2, 6)"),
    ("turbulence, 6 octaves", "fractal.sl", "turbulence(P, 6)"),
];

/// The shader of a variant, or `None` when the stdlib does not define what it calls (yet).
fn program(module: &str, expr: &str) -> Option<(Prepared, CpuProgram)> {
    let src = format!("#include <{module}>\nsurface bench() {{ Ci = color({expr}, 0, 0); }}\n");
    let checked = patina_compiler::check_source("bench.sl", &src, &MemoryLoader::default());
    if checked.has_errors() {
        return None;
    }
    let shader = Prepared::new(checked.program.shaders.into_iter().next()?);
    let cpu = CpuProgram::compile(&shader, &Binding::default()).ok()?;
    Some((shader, cpu))
}

fn kernel(shader: &Prepared) -> Kernel {
    compile_kernel(shader, &[], &[], &["P"], &["Ci"]).expect("the WGSL backend compiles the variant")
}

/// Sample points over many cells, both signs.
fn points() -> Vec<f64> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    (0..3 * POINTS)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 200.0 - 100.0
        })
        .collect()
}

fn run_gpu(gpu: &Gpu, kernel: &Kernel, input: &[u8]) {
    let groups = (POINTS as u32).div_ceil(KERNEL_WORKGROUP);
    let out =
        gpu.compute(&kernel.module, "main", &[], &[input], POINTS * 3 * 4, groups).expect("kernel runs");
    std::hint::black_box(out);
}

fn bench(c: &mut Criterion) {
    let p = points();
    let input: Vec<u8> = p.iter().flat_map(|x| (*x as f32).to_bits().to_le_bytes()).collect();
    let gpu = Gpu::new().ok();
    let baseline = gpu.as_ref().map(|gpu| {
        let (shader, _) = program("noise.sl", "xcomp(P)").expect("the baseline compiles");
        let k = kernel(&shader);
        run_gpu(gpu, &k, &input);
        median(|| run_gpu(gpu, &k, &input), 15)
    });
    let mut rows = Vec::new();
    let mut group = c.benchmark_group("noise");
    group.sample_size(10);
    for (name, module, expr) in VARIANTS {
        let Some((shader, cpu)) = program(module, expr) else {
            println!("skipped (not in the stdlib): {name}");
            continue;
        };
        let mut eval = Evaluator::<f32>::new(&cpu);
        let interpret = |e: &mut Evaluator<f32>| {
            std::hint::black_box(e.eval_points(POINTS, &[("P", &p)], &["Ci"]).expect("evaluation"));
        };
        group.bench_function(format!("interpreter {name}"), |b| b.iter(|| interpret(&mut eval)));
        let cpu_time = median(|| interpret(&mut eval), 7);
        let gpu_time = gpu.as_ref().map(|gpu| {
            let k = kernel(&shader);
            run_gpu(gpu, &k, &input); // pipeline creation and the driver's compile, once
            group.bench_function(format!("gpu {name}"), |b| b.iter(|| run_gpu(gpu, &k, &input)));
            median(|| run_gpu(gpu, &k, &input), 15)
        });
        rows.push((name, cpu_time, gpu_time));
    }
    group.finish();
    let adapter = gpu.as_ref().map_or("no GPU adapter".to_string(), |g| g.adapter_description());
    println!("\n{POINTS} points; GPU: {adapter} (time of the kernel less that of `Ci = P`)\n");
    println!("| variant | interpreter (f32) ns/eval | GPU ns/eval |");
    println!("|---|---|---|");
    let per = |d: Duration| d.as_secs_f64() * 1e9 / POINTS as f64;
    for (name, cpu, gpu_time) in rows {
        let gpu_cell = match (gpu_time, baseline) {
            (Some(t), Some(b)) => format!("{:.2}", per(t.saturating_sub(b))),
            _ => "-".into(),
        };
        println!("| {name} | {:.1} | {gpu_cell} |", per(cpu));
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
