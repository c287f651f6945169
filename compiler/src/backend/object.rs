//! An object's surface compiled for both backends at once: split into its stages, the GPU module
//! of the stages with what is bound beside them, and the interpreter's program for each stage.
//! A renderer needs all of it for every object; building it in one place keeps the CPU reference
//! and the GPU on the same stages and the same light bindings, and keeps the stage split inside
//! the compiler.

use super::binding::{Binding, BoundLight};
use super::cpu::CpuProgram;
use super::defaults::constant_defaults;
use super::wgsl::{self, GpuProgram, Lowering};
use crate::diag::Diagnostic;
use crate::opt::Prepared;
use crate::split::{self, Stages};

/// What a surface is compiled with besides itself.
#[derive(Clone, Debug, Default)]
pub struct Beside<'a> {
    /// The lights, in order: the GPU module unrolls its light loops over them, and the
    /// interpreter's stages are bound to them.
    pub lights: &'a [BoundLight<'a>],
    /// The displacement shader run before the surface at each fragment (bump mapping), if any.
    pub displacement: Option<BoundLight<'a>>,
    /// The atmosphere (volume) shader run after the surface at each fragment, if any.
    pub atmosphere: Option<BoundLight<'a>>,
}

/// Where the values computed once per draw are computed.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum HostPart {
    /// By the interpreter, into the uniform block (the renderer's way: least work per vertex and
    /// fragment).
    #[default]
    Interpreted,
    /// In the GPU stages themselves: the uniform block holds only parameters, predefined
    /// variables, spaces and geometry, which a program without the interpreter can fill
    /// ([`split::split_folding_host`]).
    Folded,
}

/// A surface compiled for both backends.
#[derive(Clone, Debug)]
pub struct CompiledObject {
    /// The surface's stages.
    pub stages: Stages,
    /// The GPU module of the stages and what is bound beside them, with its interface.
    pub gpu: GpuProgram,
    /// The interpreter's program for the host stage (run once per draw for the uniforms).
    pub host: CpuProgram,
    /// The interpreter's program for the vertex stage.
    pub vertex: CpuProgram,
    /// The interpreter's program for the fragment stage.
    pub fragment: CpuProgram,
}

/// Splits `surface` and compiles its stages for both backends: the GPU module in `lowering`, and
/// the interpreter's stages bound to the same lights and to the surface's string parameters'
/// values `strings`.
pub fn compile_object(
    surface: &Prepared,
    strings: &[(String, String)],
    beside: &Beside,
    lowering: Lowering,
    host: HostPart,
) -> Result<CompiledObject, Diagnostic> {
    let stages = match host {
        HostPart::Interpreted => split::split(surface)?,
        HostPart::Folded => split::split_folding_host(surface)?,
    };
    let gpu = wgsl::compile_shaded(
        &stages,
        beside.displacement.as_ref(),
        beside.atmosphere.as_ref(),
        beside.lights,
        strings,
        lowering,
        &constant_defaults,
    )?;
    let binding = Binding {
        lights: beside.lights.iter().map(BoundLight::binding).collect(),
        strings: strings.to_vec(),
    };
    let host = CpuProgram::compile(&stages.host, &binding)?;
    let vertex = CpuProgram::compile(&stages.vertex, &binding)?;
    let fragment = CpuProgram::compile(&stages.fragment, &binding)?;
    Ok(CompiledObject { stages, gpu, host, vertex, fragment })
}
