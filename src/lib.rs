//! Patina: a compiler for a procedural shading language in the RenderMan / Stanford RTSL tradition.
//!
//! This crate is the command-line tool and a thin facade over the workspace's libraries:
//! [`compiler`] (source to diagnostics, IR, WGSL and the CPU interpreter) and [`runtime`] (wgpu,
//! scenes, the CPU reference renderer).

pub use patina_compiler as compiler;
pub use patina_runtime as runtime;
