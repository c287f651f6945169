//! The standard library's shaping and antialiased pattern functions (`stdlib/pattern.sl`) on the
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

use patina_compiler::backend::cpu::{Binding, CpuProgram, Evaluator};
use patina_compiler::backend::wgsl::{KERNEL_WORKGROUP, compile_kernel};
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::gpu;

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

/// splitmix64: deterministic pseudo-random numbers.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f32 {
        (lo + (hi - lo) * self.unit()) as f32
    }
}

/// (s, t, u, v): s a parameter in [0, 1] (b, g, gamma, an edge), t > s (a pulse's end, a period),
/// u the value x, v the filter width.
fn points() -> Vec<[f32; 4]> {
    let mut rng = Rng(41);
    let mut points = Vec::new();
    for _ in 0..3000 {
        let s = rng.range(0.0, 1.0);
        points.push([s, s + rng.range(0.01, 2.0), rng.range(-0.2, 1.2), rng.range(0.0, 3.0)]);
    }
    for _ in 0..1000 {
        points.push([rng.range(0.0, 1.0), rng.range(0.2, 3.0), rng.range(-20.0, 20.0), rng.range(0.0, 40.0)]);
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
        let shader = &checked.program.shaders[0];

        let program = CpuProgram::compile(shader, &Binding::default()).expect("the interpreter compiles");
        let inputs: Vec<(&str, &[f64])> =
            ["s", "t", "u", "v"].iter().zip(&columns).map(|(n, c)| (*n, c.as_slice())).collect();
        let cpu = Evaluator::<f32>::new(&program).eval_points(n, &inputs, &["Ci", "Oi"]).expect("evaluation");

        let mut diff = shader.clone();
        patina_compiler::opt::derivs::differentiate(&mut diff);
        let kernel = compile_kernel(&diff, &[], &[], &["s", "t", "u", "v"], &["Ci", "Oi"])
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
