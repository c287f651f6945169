//! Backends: what runs the typed IR. `cpu` is the interpreter, the reference the GPU is measured
//! against (issue 5; so far its per-lane semantics). The WGSL backend arrives with issue 6.

pub mod cpu;
