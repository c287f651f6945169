//! The device's limits, checked before resources are created: wgpu would report a target, buffer
//! or texture over a limit as a validation error naming none of the caller's objects (or, outside
//! an error scope, abort), so each check here says what was being made, the size asked and the
//! limit, by the name wgpu's `Limits` gives it.

use super::render::{Blend, Draw, Target, TargetFormat};
use super::{GpuError, TextureDimension};

/// `Err(GpuError::Limit)` when `asked` is over `limit`.
fn within(what: impl FnOnce() -> String, asked: u64, limit: u64, name: &'static str) -> Result<(), GpuError> {
    if asked > limit {
        return Err(GpuError::Limit { what: what(), asked, limit, name });
    }
    Ok(())
}

/// The render target: each side, and the buffer it is read back through.
pub(super) fn check_target(
    target: &Target,
    limits: &wgpu::Limits,
    bytes_per_pixel: u32,
) -> Result<(), GpuError> {
    if target.width == 0 || target.height == 0 {
        return Err(GpuError::InvalidInput(format!(
            "an empty render target ({}x{})",
            target.width, target.height
        )));
    }
    let max = u64::from(limits.max_texture_dimension_2d);
    let side = || format!("the render target of {}x{} pixels", target.width, target.height);
    within(side, u64::from(target.width.max(target.height)), max, "max_texture_dimension_2d")?;
    let row = (u64::from(target.width) * u64::from(bytes_per_pixel))
        .next_multiple_of(u64::from(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT));
    let bytes = row * u64::from(target.height);
    let what =
        || format!("the readback buffer of the {}x{} render target, in bytes", target.width, target.height);
    within(what, bytes, limits.max_buffer_size, "max_buffer_size")
}

/// One draw's uniform block, vertex buffers, textures and blending.
pub(super) fn check_draw(
    draw: &Draw,
    format: TargetFormat,
    limits: &wgpu::Limits,
    features: wgpu::Features,
) -> Result<(), GpuError> {
    let uniform = (draw.uniforms.len() as u64).next_multiple_of(16);
    let what = || "the uniform block of the shader's parameters, in bytes".to_string();
    within(what, uniform, limits.max_uniform_buffer_binding_size, "max_uniform_buffer_binding_size")?;
    let what = || "the vertex attributes (one buffer each)".to_string();
    within(what, draw.attributes.len() as u64, u64::from(limits.max_vertex_buffers), "max_vertex_buffers")?;
    if let Some(a) = draw.attributes.iter().max_by_key(|a| a.location) {
        let what = || "the vertex attribute locations (the highest plus one)".to_string();
        let asked = u64::from(a.location) + 1;
        within(what, asked, u64::from(limits.max_vertex_attributes), "max_vertex_attributes")?;
    }
    for a in draw.attributes {
        let what = || format!("the vertex buffer of attribute {}, in bytes", a.location);
        within(what, 4 * a.data.len() as u64, limits.max_buffer_size, "max_buffer_size")?;
    }
    let what = || "the index buffer, in bytes".to_string();
    within(what, 4 * draw.indices.len() as u64, limits.max_buffer_size, "max_buffer_size")?;
    let count = draw.textures.len() as u64;
    let what = || "the textures the shader reads".to_string();
    within(
        what,
        count,
        u64::from(limits.max_sampled_textures_per_shader_stage),
        "max_sampled_textures_per_shader_stage",
    )?;
    if draw.samplers {
        let what = || "the samplers of the textures the shader reads".to_string();
        within(
            what,
            count,
            u64::from(limits.max_samplers_per_shader_stage),
            "max_samplers_per_shader_stage",
        )?;
    }
    for (k, t) in draw.textures.iter().enumerate() {
        let (max, name) = match t.dimension {
            TextureDimension::D1 => (limits.max_texture_dimension_1d, "max_texture_dimension_1d"),
            TextureDimension::D2 => (limits.max_texture_dimension_2d, "max_texture_dimension_2d"),
            TextureDimension::D3 => (limits.max_texture_dimension_3d, "max_texture_dimension_3d"),
        };
        let [w, h, d] = t.size;
        let what = || format!("texture {k} of {w}x{h}x{d} texels ({:?})", t.dimension);
        within(what, u64::from(w.max(h).max(d)), u64::from(max), name)?;
    }
    if draw.blend != Blend::Replace
        && format == TargetFormat::Rgba32Float
        && !features.contains(wgpu::Features::FLOAT32_BLENDABLE)
    {
        return Err(GpuError::Unsupported(
            "blending into an Rgba32Float target needs the FLOAT32_BLENDABLE feature, which this device lacks"
                .to_string(),
        ));
    }
    Ok(())
}

/// A compute dispatch: its workgroups and the bytes of each buffer.
pub(super) fn check_compute(
    limits: &wgpu::Limits,
    uniforms: usize,
    inputs: &[&[u8]],
    output_len: usize,
    workgroups: u32,
) -> Result<(), GpuError> {
    let what = || "the workgroups of the dispatch".to_string();
    let max = u64::from(limits.max_compute_workgroups_per_dimension);
    within(what, u64::from(workgroups), max, "max_compute_workgroups_per_dimension")?;
    let what = || "the uniform block, in bytes".to_string();
    let max = limits.max_uniform_buffer_binding_size;
    within(what, (uniforms as u64).next_multiple_of(16), max, "max_uniform_buffer_binding_size")?;
    let storage = limits.max_storage_buffer_binding_size;
    for (i, input) in inputs.iter().enumerate() {
        let what = || format!("input buffer {i}, in bytes");
        within(what, (input.len() as u64).next_multiple_of(4), storage, "max_storage_buffer_binding_size")?;
    }
    let what = || "the output buffer, in bytes".to_string();
    within(what, (output_len as u64).next_multiple_of(4), storage, "max_storage_buffer_binding_size")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn draw<'a>(module: &'a naga::Module, uniforms: &'a [u8], blend: Blend) -> Draw<'a> {
        Draw {
            module,
            fingerprint: None,
            vertex_entry: "vs",
            fragment_entry: "fs",
            uniforms,
            textures: &[],
            samplers: false,
            attributes: &[],
            indices: &[0, 1, 2],
            blend,
        }
    }

    #[test]
    fn the_limits_are_checked_without_a_device() {
        // WebGPU's default limits, which every WebGPU device offers at the least.
        let limits = wgpu::Limits::default();
        let wide = Target { width: 8193, height: 2, format: TargetFormat::Rgba8, clear: [0.0; 4] };
        assert_eq!(
            check_target(&wide, &limits, 4).unwrap_err().to_string(),
            "the render target of 8193x2 pixels: 8193 is over the device's limit of 8192 (max_texture_dimension_2d)"
        );
        let fits = Target { width: 8192, ..wide };
        assert_eq!(check_target(&fits, &limits, 4), Ok(()));
        let module = naga::Module::default();
        let uniforms = vec![0u8; 64 * 1024 + 1];
        let error = check_draw(
            &draw(&module, &uniforms, Blend::Replace),
            TargetFormat::Rgba8,
            &limits,
            wgpu::Features::empty(),
        );
        assert_eq!(
            error,
            Err(GpuError::Limit {
                what: "the uniform block of the shader's parameters, in bytes".into(),
                asked: 64 * 1024 + 16,
                limit: 64 * 1024,
                name: "max_uniform_buffer_binding_size",
            })
        );
    }

    #[test]
    fn blending_into_float_targets_needs_the_feature() {
        let limits = wgpu::Limits::default();
        let module = naga::Module::default();
        let over = draw(&module, &[], Blend::PremultipliedOver);
        let without = check_draw(&over, TargetFormat::Rgba32Float, &limits, wgpu::Features::empty());
        assert!(
            matches!(without, Err(GpuError::Unsupported(ref why)) if why.contains("FLOAT32_BLENDABLE")),
            "{without:?}"
        );
        let with = check_draw(&over, TargetFormat::Rgba32Float, &limits, wgpu::Features::FLOAT32_BLENDABLE);
        assert_eq!(with, Ok(()));
        // Replacing needs no blending, and Rgba8 blends everywhere.
        let replace = draw(&module, &[], Blend::Replace);
        assert_eq!(check_draw(&replace, TargetFormat::Rgba32Float, &limits, wgpu::Features::empty()), Ok(()));
        assert_eq!(check_draw(&over, TargetFormat::Rgba8, &limits, wgpu::Features::empty()), Ok(()));
    }
}
