//! The two ways the backend writes the built-ins.
//!
//! The interpreter fixes an order of operations that WGSL leaves to the driver (`dot` summed left
//! to right, `normalize` as a division by `sqrt` of that sum, matrix products sum by sum, `sign`
//! with NaN read from the bits). The exact lowering spells those out, so that the GPU reproduces
//! the CPU reference bit for bit where WGSL is exact: it is what the conformance suite, the
//! gallery and `patina stability` compare. The fast lowering writes WGSL's own built-ins
//! (`dot`, `length`, `normalize`, `reflect`, `inverseSqrt`, matrix-vector products, ...), which a
//! driver maps to its instructions (fused multiply-adds, reciprocal square roots), as a graphics
//! programmer would write them. Both keep the language's defined results that WGSL leaves
//! undefined (`pow` of a negative base, `mod`, clamped indices, `random`), so the two differ only
//! in rounding: docs/numerics.md gives the fast lowering's measured bounds per family of built-ins,
//! docs/stability.md its error against f64 per standard library function.

/// How the WGSL backend writes built-ins whose WGSL form rounds differently from the interpreter.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum Lowering {
    /// The interpreter's operations, in its order: bit-exact against the CPU reference where WGSL
    /// is exact (the conformance suite's mode).
    #[default]
    Exact,
    /// WGSL's built-ins: what a hand-written shader does, within a few ulp of the exact lowering.
    Fast,
}

impl Lowering {
    /// The lowering named `name` (`exact` or `fast`).
    pub fn from_name(name: &str) -> Option<Lowering> {
        match name {
            "exact" => Some(Lowering::Exact),
            "fast" => Some(Lowering::Fast),
            _ => None,
        }
    }

    /// Its name, as [`Lowering::from_name`] reads it.
    pub fn name(self) -> &'static str {
        match self {
            Lowering::Exact => "exact",
            Lowering::Fast => "fast",
        }
    }
}

impl std::fmt::Display for Lowering {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
