//! Shared by the standard-library tests: one shader source run by the interpreter (f32 and f64)
//! and by the GPU (the WGSL backend's compute kernel), with the same named inputs and outputs, and
//! deterministic sample points.
//!
//! Use it from a test file with `mod support;`. Each test file uses only part of it.
#![allow(dead_code)]

pub mod gallery;

use patina_compiler::backend::binding::{Binding, LightBinding};
use patina_compiler::backend::cpu::scalar::Real;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::gpu::Gpu;
// Each test binary uses only part of these.
#[allow(unused_imports)]
pub use patina_test_support::{Rng, assert_finite, extremes, worst};

/// A checked shader, ready for both backends.
pub struct Program {
    /// The shader, prepared for both backends.
    pub shader: Prepared,
    /// The interpreter's code for it.
    pub cpu: CpuProgram,
}

/// Checks `source` (which must have no diagnostics) and compiles its first shader for the
/// interpreter. Standard-library modules are found by `#include <name.sl>`.
pub fn program(source: &str) -> Program {
    let checked = patina_compiler::check_source("stdlib_test.sl", source, &MemoryLoader::default());
    assert!(checked.diagnostics.is_empty(), "{:#?}\nin\n{source}", checked.diagnostics);
    let shader =
        Prepared::new(checked.program.shaders.into_iter().next().expect("the source defines a shader"));
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
    shader: &Prepared,
    lights: &[LightBinding],
    count: usize,
    inputs: &Columns,
    outputs: &[&str],
) -> Vec<Vec<f64>> {
    patina_runtime::kernel::run_kernel(gpu, shader, lights, count, inputs, outputs)
        .unwrap_or_else(|e| panic!("{e}"))
}

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
