//! Drawing a prepared scene with wgpu.

use super::frame::program_uniform_bytes;
use super::{Prepared, RenderError};
use crate::gpu::{Attribute, Blend, Draw, Gpu, Target, TargetFormat};
use crate::image::Image;
use patina_compiler::backend::wgsl::interface::AttributeSource;

/// Renders every object of a prepared scene on the GPU into an rgba32float image of
/// `width × height` (the caller downsamples supersampled renders).
pub fn render(gpu: &Gpu, prepared: &Prepared, width: u32, height: u32) -> Result<Image, RenderError> {
    let mut owned = Vec::new();
    for object in &prepared.objects {
        let interface = &object.surface.gpu.interface;
        let uniforms = program_uniform_bytes(&object.surface, &prepared.lights, &object.frame)?;
        let mesh = &object.mesh;
        let mut attributes = Vec::new();
        for a in &interface.attributes {
            let data: Vec<f32> = match &a.source {
                AttributeSource::Mesh { what } => mesh.attribute(*what),
                AttributeSource::Param { name } => (0..mesh.positions.len())
                    .flat_map(|i| object.vertex_param(name, i, a.components as usize))
                    .map(|x| x as f32)
                    .collect(),
                _ => return Err(RenderError::Run(format!("unknown attribute `{}`", a.name))),
            };
            attributes.push(Attribute { location: a.location, components: a.components, data });
        }
        let textures: Vec<_> = object
            .surface
            .gpu
            .interface
            .textures
            .iter()
            .filter_map(|slot| {
                let t = object.textures.iter().find(|(n, _)| *n == slot.name)?;
                Some(super::textures::gpu_data(&t.1, slot.dimensions))
            })
            .collect();
        owned.push((uniforms, attributes, textures));
    }
    let draws: Vec<Draw> = prepared
        .objects
        .iter()
        .zip(&owned)
        .map(|(object, (uniforms, attributes, textures))| Draw {
            module: &object.surface.gpu.module,
            fingerprint: Some(object.surface.gpu.fingerprint),
            vertex_entry: &object.surface.gpu.interface.vertex_entry,
            fragment_entry: &object.surface.gpu.interface.fragment_entry,
            uniforms,
            textures,
            samplers: false,
            attributes,
            indices: &object.mesh.indices,
            blend: Blend::PremultipliedOver,
        })
        .collect();
    let target = Target { width, height, format: TargetFormat::Rgba32Float, clear: prepared.background };
    // The device's limits apply to the supersampled target: say which image asked for it.
    let n = prepared.supersample.max(1);
    let image = match n {
        1 => format!("the {width}x{height} image"),
        n => format!("the {}x{} image at supersample {n}", width / n, height / n),
    };
    gpu.render(&target, &draws).map_err(|e| RenderError::Gpu(format!("rendering {image}: {e}")))
}
