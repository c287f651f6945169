//! Program-to-program transformations on the typed IR that every backend shares.
//!
//! `derivs` turns the derivative built-ins (`Du`, `Dv`, `Deriv`, `area`, `filterwidth`,
//! `filterstep`, `calculatenormal`) into plain arithmetic on derivative values computed by
//! forward-mode automatic differentiation, seeded from the screen-space derivatives of the inputs.

pub mod derivs;
