//! The standard library (`compiler/stdlib/*.sl`) on the interpreter (f32 and f64) and on the GPU,
//! one module per stdlib module, each against an independent reference written in Rust from the
//! seed documents' definitions. One test binary, so one GPU device serves every module
//! (`patina_runtime::gpu::for_tests`). Needs a GPU adapter (lavapipe in CI) unless `PATINA_GPU=off`.
//!
//! Run one module with `cargo test -p patina-runtime --test stdlib cellular::`.

#[path = "../support/mod.rs"]
mod support;

mod cellular;
mod color;
mod fractal_gpu;
mod harness;
mod lattice;
mod lighting;
mod noise_family;
mod noise_gpu;
mod shaping_gpu;
mod solid;
mod volume;
