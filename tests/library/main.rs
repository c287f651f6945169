//! Patina as a library in a user's program, one test binary: a wgpu program drawing through the
//! facade (`examples/headless.rs`), a program with only the emitted WGSL and interface, the CPU
//! reference of `patina::testing`, and `Uniforms` against the renderer's own packing.

mod headless;
mod standalone;
mod testing;
mod uniforms;

/// Scratch directories, as the command-line tests make them.
#[path = "../cli/support/mod.rs"]
mod support;
