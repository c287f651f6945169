//! The CPU interpreter. So far: `scalar`, the per-lane semantics of every exactly-defined operation,
//! shared by the interpreter's f32 and f64 modes. The batch evaluator (structure-of-arrays registers,
//! execution masks) builds on it.

pub mod scalar;
