//! A whole shader run on the GPU as a compute kernel (the WGSL backend's `compile_kernel`), one
//! invocation per point, with the interpreter's named inputs and outputs: what the conformance and
//! standard-library tests and `patina stability` compare the interpreter against.

use std::fmt;

use patina_compiler::backend::binding::LightBinding;
use patina_compiler::backend::cpu::Texture;
use patina_compiler::backend::wgsl::interface::UniformSource;
use patina_compiler::backend::wgsl::{KERNEL_WORKGROUP, KernelValue, Lowering, compile_kernel_lowered};
use patina_compiler::diag::Diagnostic;
use patina_compiler::ir::types::Base;
use patina_compiler::opt::Prepared;

use crate::gpu::{Gpu, GpuError};

/// Named columns of `count` points: each holds `count * components` values, as for the
/// interpreter's `Evaluator::eval_points`.
pub type Columns<'a> = [(&'a str, &'a [f64])];

/// Why a kernel could not be run.
#[derive(Debug, Clone)]
pub enum KernelError {
    /// The WGSL backend rejected the shader (or a name that is not one of its values).
    Compile(Diagnostic),
    /// An input column does not hold `count * components` values.
    WrongSize {
        /// The input's name.
        name: String,
        /// The values expected.
        expected: usize,
        /// The values given.
        found: usize,
    },
    /// The device failed (no adapter, validation, readback, too many points).
    Gpu(GpuError),
}

impl fmt::Display for KernelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            KernelError::Compile(d) => write!(f, "the WGSL backend: {}: {}", d.code, d.message),
            KernelError::WrongSize { name, expected, found } => {
                write!(f, "input `{name}`: {found} values where {expected} were expected")
            }
            KernelError::Gpu(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for KernelError {}

impl From<GpuError> for KernelError {
    fn from(e: GpuError) -> Self {
        KernelError::Gpu(e)
    }
}

/// Runs `shader` on the GPU with `lights` bound (their values are inputs `L[k]`,
/// `Cl[k]`), one invocation per point, and returns each named output as one column.
///
/// Values cross as the kernel stores them: floats rounded to f32, integers as i32 or u32 (the
/// f64 value truncated and wrapped), booleans as 0 or 1.
pub fn run_kernel(
    gpu: &Gpu,
    shader: &Prepared,
    lights: &[LightBinding],
    count: usize,
    inputs: &Columns,
    outputs: &[&str],
) -> Result<Vec<Vec<f64>>, KernelError> {
    run_kernel_lowered(gpu, shader, lights, Lowering::Exact, count, inputs, outputs)
}

/// As [`run_kernel`], the kernel written in `lowering`.
pub fn run_kernel_lowered(
    gpu: &Gpu,
    shader: &Prepared,
    lights: &[LightBinding],
    lowering: Lowering,
    count: usize,
    inputs: &Columns,
    outputs: &[&str],
) -> Result<Vec<Vec<f64>>, KernelError> {
    run_prepared(gpu, shader, &Resources { lights, lowering, ..Resources::default() }, count, inputs, outputs)
}

/// What a kernel reads besides its per-point columns.
#[derive(Clone, Copy, Default)]
pub struct Resources<'a> {
    /// The lights bound (their values are inputs `L[k]`, `Cl[k]`).
    pub lights: &'a [LightBinding],
    /// The values of the shader's string parameters, by name.
    pub strings: &'a [(String, String)],
    /// The matrices of the named spaces it reads, from "current" space to each (a space not
    /// listed is the identity).
    pub spaces: &'a [(String, glam::Mat4)],
    /// The textures it looks up, by the name the interpreter's `set_texture` takes.
    pub textures: &'a [(String, Texture)],
    /// How the kernel writes the built-ins.
    pub lowering: Lowering,
}

/// As [`run_kernel`], with the string values, spaces and textures of `resources`.
pub fn run_prepared(
    gpu: &Gpu,
    shader: &Prepared,
    resources: &Resources,
    count: usize,
    inputs: &Columns,
    outputs: &[&str],
) -> Result<Vec<Vec<f64>>, KernelError> {
    let names: Vec<&str> = inputs.iter().map(|(n, _)| *n).collect();
    let kernel = compile_kernel_lowered(
        shader,
        resources.lights,
        resources.strings,
        &names,
        outputs,
        resources.lowering,
    )
    .map_err(KernelError::Compile)?;
    let textures = kernel
        .textures
        .iter()
        .map(|slot| match resources.textures.iter().find(|(n, _)| *n == slot.name) {
            Some((_, t)) => Ok(crate::render::textures::gpu_data(t, slot.dimensions)),
            None => Err(GpuError::InvalidInput(format!("no texture `{}` given to the kernel", slot.name))),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let stride = kernel.input_stride as usize;
    let mut words = vec![0u32; count * stride];
    for (value, (name, column)) in kernel.inputs.iter().zip(inputs) {
        let w = value.words as usize;
        if column.len() != count * w {
            return Err(KernelError::WrongSize {
                name: name.to_string(),
                expected: count * w,
                found: column.len(),
            });
        }
        for i in 0..count {
            for c in 0..w {
                words[i * stride + value.offset as usize + c] = encode(value, column[i * w + c]);
            }
        }
    }
    let input: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    let out_stride = kernel.output_stride as usize;
    let groups = u32::try_from(count.div_ceil(KERNEL_WORKGROUP as usize).max(1))
        .map_err(|_| GpuError::InvalidInput(format!("{count} points")))?;
    let mut uniforms = vec![0u8; kernel.uniform_size as usize];
    for field in &kernel.uniforms {
        match &field.source {
            UniformSource::Space { name, inverse, .. } => {
                let m = resources
                    .spaces
                    .iter()
                    .find(|(n, _)| n == name)
                    .map_or(glam::Mat4::IDENTITY, |(_, m)| *m);
                let m = if *inverse { m.inverse() } else { m };
                let values: Vec<f64> = m.to_cols_array().iter().map(|x| f64::from(*x)).collect();
                field.write(&mut uniforms, &values);
            }
            UniformSource::Table { values } => field.write(&mut uniforms, values),
            _ => {}
        }
    }
    let bytes = gpu.compute_textured(
        &kernel.module,
        "main",
        &uniforms,
        &[&input],
        &textures,
        count * out_stride * 4,
        groups,
    )?;
    let out: Vec<u32> = bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    Ok(kernel
        .outputs
        .iter()
        .map(|value| {
            let w = value.words as usize;
            (0..count)
                .flat_map(|i| (0..w).map(move |c| i * out_stride + value.offset as usize + c))
                .map(|at| decode(value, out[at]))
                .collect()
        })
        .collect())
}

/// One input word as the kernel reads it for `value`'s type.
fn encode(value: &KernelValue, x: f64) -> u32 {
    match value.ty.base {
        // `as` saturates (and sends NaN to 0); integers wider than 32 bits wrap as the language's do.
        Base::Int => (x as i64) as i32 as u32,
        Base::Uint => (x as i64) as u32,
        Base::Bool => u32::from(x != 0.0),
        _ => (x as f32).to_bits(),
    }
}

/// One output word as the value of `value`'s type.
fn decode(value: &KernelValue, bits: u32) -> f64 {
    match value.ty.base {
        Base::Int => f64::from(bits as i32),
        Base::Uint | Base::Bool => f64::from(bits),
        _ => f64::from(f32::from_bits(bits)),
    }
}
