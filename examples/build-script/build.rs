//! Compiles the shaders at build time: `OUT_DIR/patina_shaders.rs` then has a module per shader.

use patina_build::{Light, Shader, Shaders};

fn main() -> Result<(), patina_build::Error> {
    let pointlight = Light::file("../shaders/lights.sl").named("pointlight");
    Shaders::new()
        // plastic with a point light; its host part runs on the CPU (patina::Uniforms fills it).
        .shader(Shader::new("../shaders/plastic.sl").light(pointlight.clone()))
        // The same with the host part folded in: every field is one a program can fill itself.
        .shader(
            Shader::new("../shaders/plastic.sl").module("plastic_folded").light(pointlight).fold_host(true),
        )
        // A shader of this crate that `#include`s another file: editing either rebuilds.
        .shader(Shader::new("shaders/banded.sl"))
        .build()?;
    Ok(())
}
