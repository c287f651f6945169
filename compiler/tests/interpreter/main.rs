//! The interpreter end to end, one test binary: shaders compiled from source and evaluated at
//! points against values worked out independently (by hand, closed forms, f64 reimplementations
//! written from the definitions, finite differences for derivatives), and the standard library's
//! noises, fractals and shaping functions against their reference ports.

mod builtins;
mod derivatives;
mod operations;
mod programs;
mod shadow;
mod stdlib_fractal;
mod stdlib_noise;
mod stdlib_shaping;
mod support;
mod textures;
