//! Shared by the standard-library tests: one shader source run by the interpreter (f32 and f64)
//! and by the GPU (the WGSL backend's compute kernel), with the same named inputs and outputs, and
//! deterministic sample points.
//!
//! Use it from a test file with `mod support;`. Each test file uses only part of it.
#![allow(dead_code)]

pub mod gallery;

use patina_compiler::backend::cpu::scalar::Real;
use patina_compiler::backend::cpu::{Binding, CpuProgram, Evaluator, LightBinding};
use patina_compiler::ir::Shader;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::gpu::Gpu;

/// A checked shader, ready for both backends.
pub struct Program {
    /// The shader as the semantic stage produced it.
    pub shader: Shader,
    /// The interpreter's code for it.
    pub cpu: CpuProgram,
}

/// Checks `source` (which must have no diagnostics) and compiles its first shader for the
/// interpreter. Standard-library modules are found by `#include <name.sl>`.
pub fn program(source: &str) -> Program {
    let checked = patina_compiler::check_source("stdlib_test.sl", source, &MemoryLoader::default());
    assert!(checked.diagnostics.is_empty(), "{:#?}\nin\n{source}", checked.diagnostics);
    let shader = checked.program.shaders.into_iter().next().expect("the source defines a shader");
    let cpu = CpuProgram::compile(&shader, &Binding::default())
        .unwrap_or_else(|d| panic!("{}: {}", d.code, d.message));
    Program { shader, cpu }
}

/// The named inputs of `count` points: each column holds `count * components` values.
pub type Columns<'a> = [(&'a str, &'a [f64])];

impl Program {
    /// Runs the interpreter in precision `F` (f32 or f64) at `count` points and returns each
    /// named output as one column (`count * components` values).
    pub fn cpu<F: Real>(&self, count: usize, inputs: &Columns, outputs: &[&str]) -> Vec<Vec<f64>> {
        Evaluator::<F>::new(&self.cpu).eval_points(count, inputs, outputs).expect("evaluation")
    }

    /// Runs the shader on the GPU as a compute kernel, one invocation per point, with the same
    /// inputs (rounded to f32) and outputs as [`Program::cpu`]. Every input named must be a float
    /// type (the kernel reads words as f32 bits).
    pub fn gpu(&self, gpu: &Gpu, count: usize, inputs: &Columns, outputs: &[&str]) -> Vec<Vec<f64>> {
        gpu_kernel(gpu, &self.shader, &[], count, inputs, outputs)
    }
}

/// Runs `shader` on the GPU as a compute kernel with `lights` bound (their values are inputs
/// `L[k]`, `Cl[k]`, as for the interpreter), one invocation per point; as [`Program::gpu`].
pub fn gpu_kernel(
    gpu: &Gpu,
    shader: &Shader,
    lights: &[LightBinding],
    count: usize,
    inputs: &Columns,
    outputs: &[&str],
) -> Vec<Vec<f64>> {
    patina_runtime::kernel::run_kernel(gpu, shader, lights, count, inputs, outputs)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Perlin's permutation of 0..255, as published in his ImprovedNoise.java (2002): the table the
/// tests' independent ports of improved noise use.
pub const PERLIN_PERMUTATION: [i32; 256] = [
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69, 142, 8, 99,
    37, 240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32,
    57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175, 74, 165, 71, 134, 139, 48, 27,
    166, 77, 146, 158, 231, 83, 111, 229, 122, 60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244,
    102, 143, 54, 65, 25, 63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169, 200, 196, 135, 130,
    116, 188, 159, 86, 164, 100, 109, 198, 173, 186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147,
    118, 126, 255, 82, 85, 212, 207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119,
    248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110,
    79, 113, 224, 232, 178, 185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179,
    162, 241, 81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204, 176,
    115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78,
    66, 215, 61, 156, 180,
];

/// The lattice hash of `compiler/stdlib/lattice.sl`, ported from its definition (PCG's output permutation,
/// nested over the coordinates): for the tests of the lattice and cellular noises.
pub mod lattice_hash {
    /// PCG's output permutation of one 32-bit state.
    pub fn pcg(v: u32) -> u32 {
        let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
        let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
        (word >> 22) ^ word
    }

    /// The lattice coordinate of an integer-valued float: the integer modulo 2^32, as i32.
    pub fn cell(c: f64) -> i32 {
        if c.abs() < 2_147_483_648.0 { c as i32 } else { c.rem_euclid(4_294_967_296.0) as u64 as u32 as i32 }
    }

    /// The hash of lattice coordinates and a seed.
    pub fn hash(coords: &[i32], seed: i32) -> u32 {
        coords.iter().rev().fold(pcg(seed as u32), |h, &c| pcg((c as u32).wrapping_add(h)))
    }

    /// A hash's top 24 bits as a float in [0, 1).
    pub fn unit(h: u32) -> f64 {
        f64::from(h >> 8) / 16_777_216.0
    }
}

/// splitmix64: deterministic pseudo-random numbers for sample points.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// A point with each coordinate uniform in [lo, hi).
    pub fn point(&mut self, lo: f64, hi: f64) -> [f64; 3] {
        [self.range(lo, hi), self.range(lo, hi), self.range(lo, hi)]
    }
}

/// The extreme values of the stability sweep (issue 7): zero, tiny and denormal magnitudes, and
/// large ones up to 1e30, with both signs.
pub fn extremes() -> Vec<f64> {
    let denormal = f64::from(f32::from_bits(1)); // the smallest f32 denormal, representable in both
    let mut v = vec![0.0, 1e-30, denormal, 1e4, 1e6, 1e7, 1e30, 0.5, 1.0];
    v.extend(v.clone().into_iter().map(|x| -x));
    v
}

/// The largest absolute difference between two columns, and where.
pub fn worst(a: &[f64], b: &[f64]) -> (f64, usize) {
    a.iter().zip(b).enumerate().fold((0.0, 0), |(w, at), (i, (x, y))| {
        let d = (x - y).abs();
        if d > w { (d, i) } else { (w, at) }
    })
}

/// Asserts every value is finite, naming the output and the point.
pub fn assert_finite(name: &str, column: &[f64], components: usize) {
    for (i, x) in column.iter().enumerate() {
        assert!(x.is_finite(), "{name} is {x} at point {} (component {})", i / components, i % components);
    }
}
