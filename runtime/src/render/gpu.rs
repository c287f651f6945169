//! Drawing a prepared scene with wgpu.

use super::frame::uniform_bytes;
use super::{Prepared, RenderError};
use crate::gpu::{Attribute, Blend, Draw, Gpu, Target, TargetFormat};
use crate::image::Image;

/// Renders every object of a prepared scene on the GPU into an rgba32float image of
/// `width × height` (the caller downsamples supersampled renders).
pub fn render(gpu: &Gpu, prepared: &Prepared, width: u32, height: u32) -> Result<Image, RenderError> {
    let mut owned = Vec::new();
    for object in &prepared.objects {
        let interface = &object.surface.gpu.interface;
        let uniforms = uniform_bytes(interface, &object.surface, &prepared.lights, &object.frame)?;
        let mesh = &object.mesh;
        let mut attributes = Vec::new();
        for a in &interface.attributes {
            // Locations 0 to 4 are the mesh's geometry; the rest are vertex-rate parameters.
            let data: Vec<f32> = match (a.location, a.name.as_str()) {
                (0, _) => mesh.positions.iter().flatten().copied().collect(),
                (1, _) => mesh.normals.iter().flatten().copied().collect(),
                (2, _) => mesh.uvs.iter().flatten().copied().collect(),
                (3, _) => mesh.dpdu.iter().flatten().copied().collect(),
                (4, _) => mesh.dpdv.iter().flatten().copied().collect(),
                (_, param) => (0..mesh.positions.len())
                    .flat_map(|i| object.vertex_param(param, i, a.components as usize))
                    .map(|x| x as f32)
                    .collect(),
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
