//! stdlib/lighting.sl and stdlib/shaders.sl on the interpreter (f32 and f64) and on the GPU (the
//! WGSL backend's compute kernel), with lights bound: the language versions of RenderMan's light
//! sums against the built-ins, every function against an independent Rust port of its formula
//! (RI 3.2 §15.6; Kajiya & Kay eqs. 14 and 16; Heidrich & Seidel's form of Banks' model), the
//! closed-form values of the hair model, the extreme-input sweep, the standard light and surface
//! shaders, and a scene that uses them rendered by both renderers.

mod support;

use patina_compiler::backend::cpu::scalar::Real;
use patina_compiler::backend::cpu::{Binding, CpuProgram, Evaluator, LightBinding};
use patina_compiler::backend::wgsl::{KERNEL_WORKGROUP, compile_kernel};
use patina_compiler::ir::Shader;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::gpu::Gpu;
use support::{Rng, assert_finite, extremes, worst};

/// A checked shader with its lights, ready for both backends.
struct Lit {
    shader: Shader,
    cpu: CpuProgram,
    lights: Vec<LightBinding>,
}

/// `n` illuminating lights, then `ambient` ambient ones (inputs `L[k]`, `Cl[k]` in that order).
fn lights(n: usize, ambient: usize) -> Vec<LightBinding> {
    let mut v = vec![LightBinding::default(); n];
    v.extend((0..ambient).map(|_| LightBinding { ambient: true, categories: vec![] }));
    v
}

/// Checks `source` and compiles its shader called `name` with `lights` bound.
fn lit(source: &str, name: &str, lights: Vec<LightBinding>) -> Lit {
    let checked = patina_compiler::check_source("stdlib_lighting.sl", source, &MemoryLoader::default());
    assert!(checked.diagnostics.is_empty(), "{:#?}\nin\n{source}", checked.diagnostics);
    let shader = checked.program.shaders.into_iter().find(|s| s.name == name).expect("the shader exists");
    let binding = Binding { lights: lights.clone(), strings: vec![] };
    let cpu = CpuProgram::compile(&shader, &binding).unwrap_or_else(|d| panic!("{}: {}", d.code, d.message));
    Lit { shader, cpu, lights }
}

impl Lit {
    fn cpu<F: Real>(&self, count: usize, inputs: &support::Columns, outputs: &[&str]) -> Vec<Vec<f64>> {
        Evaluator::<F>::new(&self.cpu).eval_points(count, inputs, outputs).expect("evaluation")
    }

    /// As `support::Program::gpu`, with this shader's lights bound.
    fn gpu(&self, gpu: &Gpu, count: usize, inputs: &support::Columns, outputs: &[&str]) -> Vec<Vec<f64>> {
        let mut diff = self.shader.clone();
        patina_compiler::opt::derivs::differentiate(&mut diff);
        let names: Vec<&str> = inputs.iter().map(|(n, _)| *n).collect();
        let kernel = compile_kernel(&diff, &self.lights, &[], &names, outputs)
            .unwrap_or_else(|d| panic!("the WGSL backend: {}: {}", d.code, d.message));
        let stride = kernel.input_stride as usize;
        let mut words = vec![0u32; count * stride];
        for (value, (name, column)) in kernel.inputs.iter().zip(inputs) {
            let w = value.words as usize;
            assert_eq!(column.len(), count * w, "input `{name}`");
            for i in 0..count {
                for c in 0..w {
                    words[i * stride + value.offset as usize + c] = (column[i * w + c] as f32).to_bits();
                }
            }
        }
        let input: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
        let out_stride = kernel.output_stride as usize;
        let groups = (count as u32).div_ceil(KERNEL_WORKGROUP).max(1);
        let bytes = gpu
            .compute(&kernel.module, "main", &[], &[&input], count * out_stride * 4, groups)
            .expect("the kernel runs");
        let out: Vec<f32> =
            bytes.chunks_exact(4).map(|c| f32::from_bits(u32::from_le_bytes([c[0], c[1], c[2], c[3]]))).collect();
        kernel
            .outputs
            .iter()
            .map(|value| {
                let w = value.words as usize;
                let mut column = Vec::with_capacity(count * w);
                for i in 0..count {
                    for c in 0..w {
                        column.push(f64::from(out[i * out_stride + value.offset as usize + c]));
                    }
                }
                column
            })
            .collect()
    }
}

// ---------------------------------------------------------------------------------------------
// The independent reference: the formulas in f64, written from their sources.

type V3 = [f64; 3];

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(a: V3) -> V3 {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: V3, k: f64) -> V3 {
    [a[0] * k, a[1] * k, a[2] * k]
}

fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn at(column: &[f64], i: usize) -> V3 {
    [column[3 * i], column[3 * i + 1], column[3 * i + 2]]
}

/// RI 3.2 §15.6: diffuse's weight for one light, max(0, normalize(L) . N).
fn ri_diffuse(n: V3, l: V3) -> f64 {
    dot(unit(l), n).max(0.0)
}

/// specularbrdf: (max(0, N . normalize(normalize(L) + V)))^(1/roughness).
fn ri_specularbrdf(l: V3, n: V3, v: V3, roughness: f64) -> f64 {
    dot(n, unit(add(unit(l), v))).max(0.0).powf(1.0 / roughness)
}

/// specular's weight: specularbrdf where the light is on N's side (the cone of PI/2 about N).
fn ri_specular(n: V3, v: V3, l: V3, roughness: f64) -> f64 {
    if dot(unit(l), n) >= 0.0 { ri_specularbrdf(l, n, v, roughness) } else { 0.0 }
}

/// phong's weight: (max(0, R . normalize(L)))^size, R the mirror of -V about N.
fn ri_phong(n: V3, v: V3, l: V3, size: f64) -> f64 {
    let (nn, vn) = (unit(n), unit(v));
    let i = scale(vn, -1.0);
    let r = add(i, scale(nn, -2.0 * dot(nn, i)));
    if dot(unit(l), n) >= 0.0 { dot(r, unit(l)).max(0.0).powf(size) } else { 0.0 }
}

/// Kajiya & Kay eq. 14: sin(t, l).
fn kk_diffuse(t: V3, l: V3) -> f64 {
    let c = dot(unit(t), unit(l));
    (1.0 - c * c).max(0.0).sqrt()
}

/// Kajiya & Kay eq. 16 (printed, `mirror` false) and its mirror form: the base, before the power.
fn kk_base(t: V3, l: V3, e: V3, mirror: bool) -> f64 {
    let (t, l, e) = (unit(t), unit(l), unit(e));
    let (tl, te) = (dot(t, l), dot(t, e));
    let (sl, se) = ((1.0 - tl * tl).max(0.0).sqrt(), (1.0 - te * te).max(0.0).sqrt());
    if mirror { sl * se - tl * te } else { tl * te + sl * se }
}

fn kk_specular(t: V3, l: V3, e: V3, p: f64, mirror: bool) -> f64 {
    kk_base(t, l, e, mirror).clamp(0.0, 1.0).powf(p)
}

/// A random unit vector.
fn random_unit(rng: &mut Rng) -> V3 {
    loop {
        let p = rng.point(-1.0, 1.0);
        let d = dot(p, p);
        if d > 0.01 && d <= 1.0 {
            return unit(p);
        }
    }
}

/// |a - b| <= rel * max(1, |b|) for every value; returns the largest relative difference.
fn close(what: &str, got: &[f64], want: &[f64], rel: f64) -> f64 {
    assert_eq!(got.len(), want.len());
    let mut w: f64 = 0.0;
    for (i, (g, x)) in got.iter().zip(want).enumerate() {
        let d = (g - x).abs() / x.abs().max(1.0);
        assert!(d <= rel, "{what}: {g} vs {x} at value {i} (relative {d:e} > {rel:e})");
        w = w.max(d);
    }
    w
}

// ---------------------------------------------------------------------------------------------
// RenderMan's light sums.

const SUMS: &str = "#include <lighting.sl>
surface sums(varying normal n = 0; varying vector v = 0; varying vector l = 0;
             varying float r = 0.1; varying float sz = 10;
             output varying color d0 = 0, d1 = 0, s0 = 0, s1 = 0, p0 = 0, p1 = 0, b0 = 0, b1 = 0)
{
    d0 = diffuse(n); d1 = rm_diffuse(n);
    s0 = specular(n, v, r); s1 = rm_specular(n, v, r);
    p0 = phong(n, v, sz); p1 = rm_phong(n, v, sz);
    b0 = specularbrdf(l, n, v, r); b1 = rm_specularbrdf(l, n, v, r);
    Ci = 0; Oi = 1;
}";

const SUM_OUTPUTS: [&str; 8] = ["d0", "d1", "s0", "s1", "p0", "p1", "b0", "b1"];

/// Inputs for the sums: unit n and v, two illuminating lights (L of length 0.2 to 5, some behind
/// the surface) and one ambient light, roughness in [0.02, 1], Phong size in [1, 60].
fn sum_inputs(count: usize, seed: u64) -> Vec<(&'static str, Vec<f64>)> {
    let mut rng = Rng(seed);
    let mut cols: Vec<(&'static str, Vec<f64>)> = ["n", "v", "l", "r", "sz", "L[0]", "Cl[0]", "L[2]", "Cl[2]"]
        .iter()
        .map(|n| (*n, Vec::new()))
        .collect();
    for _ in 0..count {
        let n = random_unit(&mut rng);
        // V mostly on N's side, as a viewer's is.
        let mut v = random_unit(&mut rng);
        if dot(v, n) < 0.0 && rng.unit() < 0.8 {
            v = scale(v, -1.0);
        }
        let l = scale(random_unit(&mut rng), rng.range(0.2, 5.0));
        let l0 = scale(random_unit(&mut rng), rng.range(0.2, 5.0));
        let l2 = scale(random_unit(&mut rng), rng.range(0.2, 5.0));
        let values: [&[f64]; 9] = [
            &n,
            &v,
            &l,
            &[rng.range(0.02, 1.0)],
            &[rng.range(1.0, 60.0)],
            &l0,
            &[rng.range(0.0, 2.0), rng.range(0.0, 2.0), rng.range(0.0, 2.0)],
            &l2,
            &[rng.range(0.0, 2.0), rng.range(0.0, 2.0), rng.range(0.0, 2.0)],
        ];
        for (c, x) in cols.iter_mut().zip(values) {
            c.1.extend_from_slice(x);
        }
    }
    cols
}

fn columns<'a>(cols: &'a [(&'static str, Vec<f64>)]) -> Vec<(&'a str, &'a [f64])> {
    cols.iter().map(|(n, c)| (*n, c.as_slice())).collect()
}

/// Bit-for-bit equality of two columns (the built-in and the language version).
fn same_bits(what: &str, a: &[f64], b: &[f64]) {
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(x.to_bits() == y.to_bits() || (*x == 0.0 && *y == 0.0), "{what}: {x} vs {y} at value {i}");
    }
}

#[test]
fn rm_light_sums_are_the_builtins_bit_for_bit() {
    let program = lit(SUMS, "sums", sum_lights());
    let count = 2000;
    let cols = sum_inputs(count, 7);
    let inputs = columns(&cols);
    for (precision, out) in
        [("f32", program.cpu::<f32>(count, &inputs, &SUM_OUTPUTS)), ("f64", program.cpu::<f64>(count, &inputs, &SUM_OUTPUTS))]
    {
        for k in 0..4 {
            same_bits(&format!("{precision} {}", SUM_OUTPUTS[2 * k + 1]), &out[2 * k + 1], &out[2 * k]);
        }
    }
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let g = program.gpu(&gpu, count, &inputs, &SUM_OUTPUTS);
    for k in 0..4 {
        same_bits(&format!("gpu {}", SUM_OUTPUTS[2 * k + 1]), &g[2 * k + 1], &g[2 * k]);
    }
}

/// The lights of the sums: illuminating, ambient, illuminating.
fn sum_lights() -> Vec<LightBinding> {
    vec![LightBinding::default(), LightBinding { ambient: true, categories: vec![] }, LightBinding::default()]
}
