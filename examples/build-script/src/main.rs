//! Prints what the generated bindings say about each shader, and fills a block.

use patina_build_example::shaders::{banded, plastic, plastic_folded};

fn main() {
    for (module, size, fields, host) in [
        ("plastic", plastic::UNIFORM_SIZE, plastic::FIELDS, plastic::NEEDS_HOST),
        ("plastic_folded", plastic_folded::UNIFORM_SIZE, plastic_folded::FIELDS, plastic_folded::NEEDS_HOST),
        ("banded", banded::UNIFORM_SIZE, banded::FIELDS, banded::NEEDS_HOST),
    ] {
        println!("{module}: {size}-byte uniform block, {} fields, needs host: {host}", fields.len());
    }
    // A program without Patina fills the folded block itself.
    let mut block: plastic_folded::Uniforms = bytemuck::Zeroable::zeroed();
    block.Kd = 0.7;
    block.l0_from = [-2.5, 3.0, -3.0];
    println!(
        "{} bytes for @group({}) @binding({})",
        block.as_bytes().len(),
        plastic_folded::UNIFORM_GROUP,
        plastic_folded::UNIFORM_BINDING
    );
    println!("vertex inputs: {:?}", plastic::ATTRIBUTES);
}
