//! Program-to-program transformations on the typed IR that every backend shares.
//!
//! `derivs` turns the derivative built-ins (`Du`, `Dv`, `Deriv`, `area`, `filterwidth`,
//! `filterstep`, `calculatenormal`) into plain arithmetic on derivative values computed by
//! forward-mode automatic differentiation, seeded from the screen-space derivatives of the inputs.
//! `textures` turns texture lookups into one filter written as arithmetic on texel fetches, so
//! that every backend filters the same way; `shadow` does the same for shadow-map lookups
//! (percentage-closer filtering over depth texels, the map carrying its own matrix); `splines`
//! turns `spline` calls into arithmetic on their knots. `lights`, unlike the others, runs for one
//! binding, in each backend: the light constructs over the bound lights.

pub mod build;
pub mod derivs;
pub mod lights;
pub mod shadow;
pub mod splines;
pub mod textures;

use crate::ir::Shader;

/// A shader through the passes every backend shares (the footprints of environment lookups,
/// derivatives, texture and shadow-map lookups, splines): the one form the backends take. It is made only
/// by [`Prepared::new`], or by a split, whose stages are slices of a prepared shader; so a backend
/// can be handed neither a shader those passes have not seen nor one they have seen twice.
#[derive(Clone, Debug, PartialEq)]
pub struct Prepared(Shader);

impl Prepared {
    /// Runs a checked (and possibly bound) shader through the shared passes, its `string`
    /// parameters at their defaults.
    ///
    /// Each pass checks its own result in debug builds (`verify`); the whole is checked once
    /// more for what the backends rely on, all the passes' guarantees at once.
    pub fn new(shader: Shader) -> Prepared {
        Prepared::with_strings(shader, &[])
    }

    /// [`Prepared::new`] for a shader whose `string` parameters have the values `strings` (by
    /// name; the others their defaults): the values the backends are given in `Binding::strings`.
    /// A string decides which code a call becomes (a spline's basis).
    pub fn with_strings(mut shader: Shader, strings: &[(String, String)]) -> Prepared {
        textures::footprints(&mut shader);
        derivs::differentiate(&mut shader);
        textures::expand(&mut shader);
        shadow::expand(&mut shader);
        splines::expand(&mut shader, strings);
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
