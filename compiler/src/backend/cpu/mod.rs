//! The CPU interpreter: the reference backend the GPU is measured against.
//!
//! `lower` scalarizes a shader's IR into [`code`]: instructions over uniform and varying registers
//! with structured control flow. `exec` runs that code over batches of points with execution masks,
//! in f32 or f64 ([`scalar::Real`]); `scalar` defines every per-lane operation. `eval` is the
//! library API: compile a shader for a binding, set parameters, evaluate it at points.

pub mod code;
pub mod eval;
pub mod exec;
mod lower;
pub mod scalar;

pub use eval::{CpuProgram, EvalError, Evaluator, SlotId, SlotInfo};
pub use exec::Texture;
pub use lower::{SlotKind, lightsource_input, surface_flag_input, surface_input};
