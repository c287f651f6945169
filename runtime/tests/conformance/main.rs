//! CPU-vs-GPU conformance: every built-in as a compute kernel ([`kernels`]), through the real
//! vertex-to-fragment path ([`render`]), and random well-typed programs ([`generated`]), all
//! against the interpreter. One test binary, so one GPU device serves all three. Needs a GPU
//! adapter (lavapipe in CI) unless `PATINA_GPU=off`.
//!
//! Run one part with `cargo test -p patina-runtime --test conformance generated::`.

#[path = "../support/mod.rs"]
mod support;

mod cases;
mod harness;

mod generated;
mod kernels;
mod render;
