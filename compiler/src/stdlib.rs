//! The standard library's sources, embedded at build time so that `#include <name.sl>` works without
//! any installed files.

/// The directory name standard-library files are shown under in diagnostics.
pub const PREFIX: &str = "<stdlib>";

/// Every module: its file name and its source.
pub const MODULES: &[(&str, &str)] = &[
    ("pattern.sl", include_str!("../../stdlib/pattern.sl")),
    ("noise.sl", include_str!("../../stdlib/noise.sl")),
    ("fractal.sl", include_str!("../../stdlib/fractal.sl")),
    ("lattice.sl", include_str!("../../stdlib/lattice.sl")),
    ("cellular.sl", include_str!("../../stdlib/cellular.sl")),
    ("color.sl", include_str!("../../stdlib/color.sl")),
    ("volume.sl", include_str!("../../stdlib/volume.sl")),
    ("lighting.sl", include_str!("../../stdlib/lighting.sl")),
    ("solid.sl", include_str!("../../stdlib/solid.sl")),
    ("shaders.sl", include_str!("../../stdlib/shaders.sl")),
];

/// The source of the standard-library module `name` (e.g. `"pattern.sl"`).
pub fn source(name: &str) -> Option<&'static str> {
    MODULES.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
}
