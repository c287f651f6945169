//! Backends: what runs the typed IR. `cpu` is the interpreter, the reference the GPU is measured
//! against; `wgsl` builds naga modules for the GPU from the split stages.

pub mod cpu;
pub mod wgsl;
