//! Backends: what runs the typed IR. `cpu` is the interpreter, the reference the GPU is measured
//! against; `wgsl` builds naga modules for the GPU from the split stages. Neither imports the
//! other: what they must agree on lives here, beside them: the [`binding`] of a shader to its
//! lights and strings, the `ops` both compute as one operation per component (each paired with
//! its instruction on either side), the `arith` sequences both compute where WGSL leaves the order
//! of operations open (`dot`, matrix inverses, `smoothstep`, ...), the `match` built-in's
//! `pattern` matcher, the names of the inputs both read ([`POINT_INDEX`], [`CLIP_INPUT`]), the
//! fixed point of a uniform `random()` ([`UNIFORM_RANDOM_POINT`]) and the loop cap
//! ([`MAX_LOOP_ITERATIONS`]). Two pieces join them:
//! [`defaults`], the interpreter computing the parameter defaults a GPU program's interface
//! lists, and [`object`], a surface split and compiled for both at once (what a renderer needs).

pub(crate) mod arith;
pub mod binding;
pub mod cpu;
pub mod defaults;
pub mod object;
pub(crate) mod ops;
pub(crate) mod pattern;
pub mod wgsl;

/// The input `random()` hashes with its call site: by default each point's index in the
/// evaluation; a renderer gives the pixel (x + 65536 y), as the GPU computes it. The interpreter
/// reads it as a named input, the WGSL backend keeps it in a private variable of this name.
pub const POINT_INDEX: &str = "point_index";

/// The point index `random()` hashes where a uniform value is wanted (`__uniform_random`): one
/// fixed index, so every point of a draw gets the same value (both backends).
pub const UNIFORM_RANDOM_POINT: u32 = 0xffff_ffff;

/// The input `depth` reads: the near and far clipping distances, `(near, far)`, two uniform floats
/// in "camera" (for `depth`, also "current") space units. It is the interpreter's input slot and
/// the GPU's uniform of this name, which the renderer fills alike for both.
pub const CLIP_INPUT: &str = "clip";

/// The most times one execution of a loop runs its body (docs/limits.md): a property of the
/// language as Patina runs it, not of one backend. On the GPU, which cannot report an error and
/// must not hang, a loop is left as if its condition had failed at the next iteration past it; it
/// is the interpreter's default iteration budget, so a loop cut short on the GPU is error E0702
/// there (which can report it) and every loop that ends by itself runs alike on both. 65535 is
/// also where lavapipe (llvmpipe's `LP_MAX_TGSI_LOOP_ITERATIONS`) stops a loop by itself, so on it
/// the two caps agree.
pub const MAX_LOOP_ITERATIONS: u64 = 65_535;
