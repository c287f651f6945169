//! Offscreen rendering: draws of indexed triangles into a colour target with a depth buffer, read
//! back into an `Image`.
//!
//! Conventions are wgpu's: clip space has x right, y up and z in [0, 1] after the divide by w;
//! NDC (-1, 1) is the top-left corner of the image, whose row 0 is the top row. Triangles are not
//! culled. The depth buffer (Depth32Float) is cleared to 1.0 and a fragment is kept when its depth
//! is less than what is stored.

use super::pipeline::Prepared;
use super::{Gpu, GpuError, TextureData, limits};
use crate::image::Image;

/// The colour format of a render target; both read back as f32 RGBA.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TargetFormat {
    /// Full float output, for exact comparisons.
    Rgba32Float,
    /// 8-bit unorm (no sRGB encoding), read back as `byte / 255`.
    Rgba8,
}

/// The image a render produces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Target {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Colour format of the attachment.
    pub format: TargetFormat,
    /// RGBA the colour target is cleared to before the first draw.
    pub clear: [f32; 4],
}

/// One vertex attribute: `components` f32s per vertex, read by the vertex shader at `@location(location)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Attribute {
    /// The shader location (`@location(n)` on a vertex entry point input).
    pub location: u32,
    /// 1 to 4: the attribute is `f32`, `vec2f`, `vec3f` or `vec4f`.
    pub components: u32,
    /// Vertex-major values: vertex 0's components, then vertex 1's, ...
    pub data: Vec<f32>,
}

/// How a draw's fragments combine with the colour already in the target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Blend {
    /// The fragment's colour replaces the target's.
    Replace,
    /// Premultiplied "over": `src + dst * (1 - src.a)`, for colour and alpha alike.
    PremultipliedOver,
}

/// One draw call: a shader module, its resources, and a triangle list.
///
/// Bindings: `@group(0) @binding(0)` is the uniform buffer (when `uniforms` is not empty), visible to
/// both stages; in `@group(1)`, texture `k` is at binding `k` (Patina's modules, which fetch with
/// `textureLoad`), or at `2k` with its filtering sampler at `2k + 1` when `samplers` is set.
#[derive(Debug, Clone, Copy)]
pub struct Draw<'a> {
    /// A module with (at least) the vertex and fragment entry points named below.
    pub module: &'a naga::Module,
    /// The module's fingerprint (`GpuProgram::fingerprint`), when the draw's pipeline may be kept:
    /// the pipeline is then made once per device for each fingerprint, entry points, attribute
    /// layout, texture shapes, blend and target format, and later draws reuse it (pipeline
    /// creation is most of a small render's time). `None`: made afresh for this draw.
    pub fingerprint: Option<u64>,
    /// Name of the vertex entry point.
    pub vertex_entry: &'a str,
    /// Name of the fragment entry point; it writes `@location(0) vec4f`.
    pub fragment_entry: &'a str,
    /// Bytes of the uniform block, laid out by WGSL's uniform rules (padded here to 16 bytes).
    pub uniforms: &'a [u8],
    /// Textures of group 1, in binding order.
    pub textures: &'a [TextureData],
    /// Whether each texture has a sampler bound beside it (see the type's documentation).
    pub samplers: bool,
    /// Vertex attributes, each in its own vertex buffer; all must have the same vertex count.
    pub attributes: &'a [Attribute],
    /// Triangle list indices into the attributes' vertices.
    pub indices: &'a [u32],
    /// How the fragments combine with the target.
    pub blend: Blend,
}

pub(super) const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

impl Gpu {
    /// Renders `draws` in order into a fresh target and reads it back (row 0 = top).
    pub fn render(&self, target: &Target, draws: &[Draw]) -> Result<Image, GpuError> {
        let (bytes_per_pixel, format) = match target.format {
            TargetFormat::Rgba32Float => (16, wgpu::TextureFormat::Rgba32Float),
            TargetFormat::Rgba8 => (4, wgpu::TextureFormat::Rgba8Unorm),
        };
        let limits = self.device.limits();
        limits::check_target(target, &limits, bytes_per_pixel)?;
        for (i, draw) in draws.iter().enumerate() {
            check_draw(draw).map_err(|e| GpuError::InvalidInput(format!("draw {i}: {e}")))?;
            limits::check_draw(draw, target.format, &limits, self.device.features())
                .map_err(|e| in_draw(i, e))?;
            for t in draw.textures {
                t.check()?;
            }
        }
        let row = target.width * bytes_per_pixel;
        let padded_row = row.next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        // Each draw's pipeline in a scope of its own, so that a shader the device refuses (too
        // large, an unsupported feature) is reported with the draw it belongs to. A pipeline made
        // here serves the later draws of the same module too: its scope was clean.
        let mut fresh = std::collections::HashMap::new();
        let prepared = draws
            .iter()
            .enumerate()
            .map(|(i, d)| match self.scoped(|| self.prepare(d, format, &mut fresh)) {
                Ok(Ok(p)) => Ok(p),
                Ok(Err(e)) | Err(e) => Err(in_draw(i, e)),
            })
            .collect::<Result<Vec<_>, _>>()?;
        // Accepted by the device (the scopes above are clean; a pipeline made inside a failed
        // one is invalid): these pipelines may be reused by later renders.
        for (key, kept) in fresh {
            self.pipelines.keep(key, kept);
        }
        let readback = self.scoped(|| self.encode_render(target, &prepared, format, padded_row))??;
        let bytes = self.read_buffer(&readback)?;
        let mut pixels = Vec::with_capacity(target.width as usize * target.height as usize);
        for line in bytes.chunks_exact(padded_row as usize).take(target.height as usize) {
            let line = &line[..row as usize];
            match target.format {
                TargetFormat::Rgba32Float => pixels.extend(line.chunks_exact(16).map(|p| {
                    std::array::from_fn(|c| {
                        f32::from_le_bytes([p[4 * c], p[4 * c + 1], p[4 * c + 2], p[4 * c + 3]])
                    })
                })),
                TargetFormat::Rgba8 => pixels
                    .extend(line.chunks_exact(4).map(|p| std::array::from_fn(|c| f32::from(p[c]) / 255.0))),
            }
        }
        if pixels.len() != target.width as usize * target.height as usize {
            return Err(GpuError::Readback(format!(
                "{} bytes read back for a {}x{} target",
                bytes.len(),
                target.width,
                target.height
            )));
        }
        Ok(Image { width: target.width, height: target.height, pixels })
    }

    /// Records and submits the whole render; returns the buffer the colour target was copied into.
    fn encode_render(
        &self,
        target: &Target,
        prepared: &[Prepared],
        format: wgpu::TextureFormat,
        padded_row: u32,
    ) -> Result<wgpu::Buffer, GpuError> {
        let size = wgpu::Extent3d { width: target.width, height: target.height, depth_or_array_layers: 1 };
        let attachment = |format, usage| {
            self.device.create_texture(&wgpu::TextureDescriptor {
                label: None,
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let colour =
            attachment(format, wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC);
        let depth = attachment(DEPTH_FORMAT, wgpu::TextureUsages::RENDER_ATTACHMENT);
        let colour_view = colour.create_view(&Default::default());
        let depth_view = depth.create_view(&Default::default());
        let mut encoder = self.device.create_command_encoder(&Default::default());
        {
            let [r, g, b, a] = target.clear.map(f64::from);
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("patina render"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &colour_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            for p in prepared {
                pass.set_pipeline(&p.pipeline);
                for (index, group) in &p.groups {
                    pass.set_bind_group(*index, group, &[]);
                }
                for (slot, buffer) in p.vertex_buffers.iter().enumerate() {
                    pass.set_vertex_buffer(slot as u32, buffer.slice(..));
                }
                pass.set_index_buffer(p.index_buffer.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..p.index_count, 0, 0..1);
            }
        }
        let readback = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("patina readback"),
            size: u64::from(padded_row) * u64::from(target.height),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        encoder.copy_texture_to_buffer(
            colour.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row),
                    rows_per_image: Some(target.height),
                },
            },
            size,
        );
        self.queue.submit([encoder.finish()]);
        Ok(readback)
    }
}

/// `e` with the draw it happened in (a lost device belongs to no draw).
fn in_draw(i: usize, e: GpuError) -> GpuError {
    match e {
        GpuError::Limit { what, asked, limit, name } => {
            GpuError::Limit { what: format!("draw {i}: {what}"), asked, limit, name }
        }
        GpuError::Wgpu(why) => GpuError::Wgpu(format!("draw {i}: {why}")),
        GpuError::OutOfMemory(why) => GpuError::OutOfMemory(format!("draw {i}: {why}")),
        GpuError::Unsupported(why) => GpuError::Unsupported(format!("draw {i}: {why}")),
        e => e,
    }
}

/// The checks wgpu would not make (or would make only as a hard-to-read validation error).
fn check_draw(draw: &Draw) -> Result<(), String> {
    let mut vertices = None;
    for a in draw.attributes {
        if !(1..=4).contains(&a.components) {
            return Err(format!("attribute {} has {} components (1 to 4 allowed)", a.location, a.components));
        }
        if !a.data.len().is_multiple_of(a.components as usize) {
            return Err(format!("attribute {} has a partial vertex", a.location));
        }
        let count = a.data.len() / a.components as usize;
        if *vertices.get_or_insert(count) != count {
            return Err(format!(
                "attribute {} has {count} vertices, an earlier one has {vertices:?}",
                a.location
            ));
        }
        if draw.attributes.iter().filter(|b| b.location == a.location).count() > 1 {
            return Err(format!("location {} is given twice", a.location));
        }
    }
    if !draw.indices.len().is_multiple_of(3) {
        return Err(format!("{} indices do not make whole triangles", draw.indices.len()));
    }
    if u32::try_from(draw.indices.len()).is_err() {
        return Err("too many indices".into());
    }
    // With no attributes the vertex shader works from the vertex index alone; any index is fine.
    if let Some(n) = vertices
        && let Some(bad) = draw.indices.iter().find(|&&i| i as usize >= n)
    {
        return Err(format!("index {bad} is out of range for {n} vertices"));
    }
    Ok(())
}
