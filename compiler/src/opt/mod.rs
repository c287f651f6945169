//! Program-to-program transformations on the typed IR that every backend shares.
//!
//! `derivs` turns the derivative built-ins (`Du`, `Dv`, `Deriv`, `area`, `filterwidth`,
//! `filterstep`, `calculatenormal`) into plain arithmetic on derivative values computed by
//! forward-mode automatic differentiation, seeded from the screen-space derivatives of the inputs.
//! `textures` turns texture lookups into one filter written as arithmetic on texel fetches, so
//! that every backend filters the same way; `shadow` does the same for shadow-map lookups
//! (percentage-closer filtering over depth texels, the map carrying its own matrix).

pub mod derivs;
pub mod shadow;
pub mod textures;

/// What every backend runs a checked shader through first: the footprints of environment lookups
/// (`textures::footprints`, derivative consumers), derivatives, then texture lookups,
/// then shadow-map lookups.
///
/// Each pass checks its own result in debug builds (`ir::verify`); the whole is checked once more
/// for what the backends rely on, all three passes' guarantees at once.
pub fn prepare(shader: &mut crate::ir::Shader) {
    textures::footprints(shader);
    derivs::differentiate(shader);
    textures::expand(shader);
    shadow::expand(shader);
    crate::ir::verify::assert_valid(shader, crate::ir::verify::Pass::Prepare);
}
