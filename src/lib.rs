//! Patina: a compiler for a procedural shading language in the RenderMan / Stanford RTSL
//! tradition, to WGSL for your wgpu program and to a CPU reference for your tests.
//!
//! Three uses, each a few lines:
//!
//! **Compile a shader to WGSL** with the lights it is bound to and the values you fix; the
//! [`Interface`] says what to bind and fill (uniform layout, attributes, textures, output):
//!
//! ```
//! use patina::{Compiler, Light};
//!
//! let compiled = Compiler::new()
//!     .light(Light::stdlib("shaders.sl", "pointlight"))
//!     .compile_source("plastic.sl", "surface plastic(float Ka = 1, Kd = 0.5, Ks = 0.5, roughness = 0.1) {
//!         normal Nf = faceforward(normalize(N), I);
//!         Ci = Cs * (Ka * ambient() + Kd * diffuse(Nf)) + Ks * specular(Nf, -normalize(I), roughness);
//!     }")?;
//! println!("{}", compiled.wgsl); // vs_main and fs_main; or use compiled.module (naga IR) directly
//! # Ok::<(), patina::CompileError>(())
//! ```
//!
//! **Fill its uniform block** by parameter name; the host part of the shader (what it computes
//! once per draw) runs on the CPU inside [`Uniforms::bytes`]:
//!
//! ```
//! # let compiled = patina::Compiler::new().compile_source("m.sl",
//! #     "surface m(float Kd = 0.5; color tint = 1) { Ci = tint * Kd * (1 - t); }")?;
//! let mut block = compiled.uniforms();
//! block.set("Kd", 0.8)?.set("tint", [1.0, 0.9, 0.8])?;
//! block.set_view(patina::View { width: 640, height: 480, ..Default::default() });
//! let bytes = block.bytes()?; // write it to the buffer at @group(0) @binding(0)
//! assert_eq!(bytes.len(), compiled.interface.uniform_size as usize);
//! assert!(block.set("Kd", [1.0, 2.0]).is_err()); // a float takes one number
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! **Make the render pipeline** for your own device with [`gpu`] (the `wgpu` feature, on by
//! default): bind group layouts, vertex buffer layouts and a `wgpu::RenderPipeline` for your
//! colour and depth formats. `examples/headless.rs` draws a frame with its own device and mesh.
//!
//! The command-line tool (`patina render`, `compile`, `check`, ...) is built from the same crates;
//! the stages of the compiler are in [`compiler`] and the renderer in [`runtime`] (their APIs are
//! internal and may change between versions; the items at this crate's root are the stable ones).

#![warn(missing_docs)]

mod facade;
#[cfg(feature = "wgpu")]
pub mod gpu;
pub mod testing;

pub use facade::{
    CompileError, Compiled, Compiler, Diagnostics, FileWatcher, Light, UniformError, Uniforms, Update, Value,
    View, WatchError, Watcher,
};
pub use patina_compiler::backend::wgsl::Lowering;
pub use patina_compiler::backend::wgsl::interface::{self, Interface};
pub use patina_runtime::camera::Camera;

/// The compiler's stages (internal: may change between versions).
pub use patina_compiler as compiler;
/// The renderer, scenes and the CPU reference rasterizer (internal: may change between versions).
pub use patina_runtime as runtime;

/// The README's Rust snippets, compiled as doctests so they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
