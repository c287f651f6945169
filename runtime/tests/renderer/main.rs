//! The runtime's renderer and its parts: scenes, meshes, the CPU rasterizer, the GPU device and
//! its limits, binding, stages, atmosphere, environment maps and the corpus, on both backends. One
//! test binary, so one GPU device serves every module. GPU tests need an adapter (lavapipe in CI)
//! unless `PATINA_GPU=off`.
//!
//! Run one module with `cargo test -p patina-runtime --test renderer bind::`.

mod atmosphere;
mod bind;
mod corpus;
mod environment;
mod from_device;
mod gpu;
mod limits;
mod mesh;
mod raster;
mod render;
mod scene;
mod stages;
