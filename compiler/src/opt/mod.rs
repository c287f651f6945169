//! Program-to-program transformations on the typed IR that every backend shares.
//!
//! `derivs` turns the derivative built-ins (`Du`, `Dv`, `Deriv`, `area`, `filterwidth`,
//! `filterstep`, `calculatenormal`) into plain arithmetic on derivative values computed by
//! forward-mode automatic differentiation, seeded from the screen-space derivatives of the inputs.
//! `textures` turns texture lookups into one filter written as arithmetic on texel fetches, so
//! that every backend filters the same way; `shadow` does the same for shadow-map lookups
//! (percentage-closer filtering over depth texels, the map carrying its own matrix).

pub mod build;
pub mod derivs;
pub mod shadow;
pub mod textures;

use crate::ir::Shader;

/// A shader through the passes every backend shares (the footprints of environment lookups,
/// derivatives, texture and shadow-map lookups): the one form the backends take. It is made only
/// by [`Prepared::new`], or by a split, whose stages are slices of a prepared shader; so a backend
/// can be handed neither a shader those passes have not seen nor one they have seen twice.
#[derive(Clone, Debug, PartialEq)]
pub struct Prepared(Shader);

impl Prepared {
    /// Runs a checked (and possibly bound) shader through the shared passes.
    ///
    /// Each pass checks its own result in debug builds (`verify`); the whole is checked once
    /// more for what the backends rely on, all three passes' guarantees at once.
    pub fn new(mut shader: Shader) -> Prepared {
        textures::footprints(&mut shader);
        derivs::differentiate(&mut shader);
        textures::expand(&mut shader);
        shadow::expand(&mut shader);
        crate::verify::assert_valid(&shader, crate::verify::Pass::Prepare);
        Prepared(shader)
    }

    /// A shader known to be prepared already: a stage sliced from a prepared shader, or one a
    /// test ran through the passes one by one.
    pub(crate) fn assume_prepared(shader: Shader) -> Prepared {
        Prepared(shader)
    }

    /// The prepared shader.
    pub fn shader(&self) -> &Shader {
        &self.0
    }
}

impl std::ops::Deref for Prepared {
    type Target = Shader;

    fn deref(&self) -> &Shader {
        &self.0
    }
}

/// Tests break prepared IR by hand to see `verify` refuse it.
#[cfg(test)]
impl std::ops::DerefMut for Prepared {
    fn deref_mut(&mut self) -> &mut Shader {
        &mut self.0
    }
}
