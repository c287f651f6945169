//! wgpu helpers for a [`Compiled`] program on your own device: its bind group layouts, its
//! vertex buffer layouts and a render pipeline. You keep the device, queue, meshes and passes.
//!
//! The layouts follow the [`Interface`]: group 0 binding 0 is the uniform buffer (when the
//! block is not empty), group 1 binding `k` is texture `k` (no samplers); vertex buffer `i`
//! holds attribute `i` of `interface.attributes`, tightly packed `f32` components.

use std::borrow::Cow;

use crate::{Compiled, Interface};

/// What [`render_pipeline`] makes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PipelineOptions {
    /// The colour target's format.
    pub color_format: wgpu::TextureFormat,
    /// The depth target's format, if the pass has one (depth test `Less`, writes on).
    pub depth_format: Option<wgpu::TextureFormat>,
    /// How fragments combine with the target; the shader's output is premultiplied, so the
    /// default is premultiplied "over".
    pub blend: Option<wgpu::BlendState>,
}

impl PipelineOptions {
    /// A colour target of `format` with a `Depth32Float` depth target, blended premultiplied.
    pub fn new(format: wgpu::TextureFormat) -> PipelineOptions {
        PipelineOptions {
            color_format: format,
            depth_format: Some(wgpu::TextureFormat::Depth32Float),
            blend: Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
        }
    }
}

/// A program's render pipeline with the bind group layouts its bind groups must be made with.
#[derive(Clone, Debug)]
pub struct Pipeline {
    /// The pipeline.
    pub pipeline: wgpu::RenderPipeline,
    /// Group 0's layout (the uniform buffer), if the program has uniforms.
    pub uniforms: Option<wgpu::BindGroupLayout>,
    /// Group 1's layout (the textures), if the program reads textures.
    pub textures: Option<wgpu::BindGroupLayout>,
}

impl Pipeline {
    /// A bind group for group 0 holding `buffer` (at least `interface.uniform_size` bytes, with
    /// `UNIFORM` usage); `None` when the program has no uniforms.
    pub fn uniform_bind_group(
        &self,
        device: &wgpu::Device,
        buffer: &wgpu::Buffer,
    ) -> Option<wgpu::BindGroup> {
        let layout = self.uniforms.as_ref()?;
        Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("patina uniforms"),
            layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() }],
        }))
    }

    /// A bind group for group 1 holding `views`, one per `interface.textures` in order; `None`
    /// when the program reads no textures.
    pub fn texture_bind_group(
        &self,
        device: &wgpu::Device,
        views: &[&wgpu::TextureView],
    ) -> Option<wgpu::BindGroup> {
        let layout = self.textures.as_ref()?;
        let entries: Vec<_> = views
            .iter()
            .enumerate()
            .map(|(k, view)| wgpu::BindGroupEntry {
                binding: k as u32,
                resource: wgpu::BindingResource::TextureView(view),
            })
            .collect();
        Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("patina textures"),
            layout,
            entries: &entries,
        }))
    }
}

/// Group 0's layout entries: the uniform buffer, visible to both stages (empty when the
/// program's block is empty).
pub fn uniform_layout_entries(interface: &Interface) -> Vec<wgpu::BindGroupLayoutEntry> {
    if interface.uniforms.is_empty() {
        return Vec::new();
    }
    vec![wgpu::BindGroupLayoutEntry {
        binding: 0,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: wgpu::BufferSize::new(u64::from(interface.uniform_size)),
        },
        count: None,
    }]
}

/// Group 1's layout entries: each texture at its binding, unfilterable float (the program
/// fetches texels itself), visible to both stages.
pub fn texture_layout_entries(interface: &Interface) -> Vec<wgpu::BindGroupLayoutEntry> {
    interface
        .textures
        .iter()
        .map(|t| wgpu::BindGroupLayoutEntry {
            binding: t.binding,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: if t.dimensions == 3 {
                    wgpu::TextureViewDimension::D3
                } else {
                    wgpu::TextureViewDimension::D2
                },
                multisampled: false,
            },
            count: None,
        })
        .collect()
}

/// The vertex attributes of a program, one buffer each: hand [`VertexLayouts::buffers`] to the
/// pipeline and bind buffer `i` at slot `i`.
#[derive(Clone, Debug)]
pub struct VertexLayouts {
    attributes: Vec<wgpu::VertexAttribute>,
}

impl VertexLayouts {
    /// The layouts of `interface.attributes`.
    pub fn new(interface: &Interface) -> VertexLayouts {
        let attributes = interface
            .attributes
            .iter()
            .map(|a| wgpu::VertexAttribute {
                format: match a.components {
                    1 => wgpu::VertexFormat::Float32,
                    2 => wgpu::VertexFormat::Float32x2,
                    3 => wgpu::VertexFormat::Float32x3,
                    _ => wgpu::VertexFormat::Float32x4,
                },
                offset: 0,
                shader_location: a.location,
            })
            .collect();
        VertexLayouts { attributes }
    }

    /// One `VertexBufferLayout` per attribute, in the interface's order (as
    /// `VertexState::buffers` takes them).
    pub fn buffers(&self) -> Vec<Option<wgpu::VertexBufferLayout<'_>>> {
        self.attributes
            .iter()
            .map(|a| {
                Some(wgpu::VertexBufferLayout {
                    array_stride: a.format.size(),
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: std::slice::from_ref(a),
                })
            })
            .collect()
    }
}

/// The program's render pipeline on `device`: its module, layouts and entry points, triangle
/// lists without culling, for the formats of `options`.
pub fn render_pipeline(device: &wgpu::Device, compiled: &Compiled, options: &PipelineOptions) -> Pipeline {
    let interface = &compiled.interface;
    let layout = |label, entries: Vec<wgpu::BindGroupLayoutEntry>| {
        (!entries.is_empty()).then(|| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries: &entries,
            })
        })
    };
    let uniforms = layout("patina uniforms", uniform_layout_entries(interface));
    let textures = layout("patina textures", texture_layout_entries(interface));
    // A program with textures but no uniforms leaves group 0 empty: textures stay at group 1.
    let groups = [uniforms.as_ref(), textures.as_ref()];
    let used = if textures.is_some() { 2 } else { usize::from(uniforms.is_some()) };
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("patina"),
        bind_group_layouts: &groups[..used],
        immediate_size: 0,
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(interface.shader.as_str()),
        source: wgpu::ShaderSource::Naga(Cow::Owned(compiled.module.clone())),
    });
    let vertex = VertexLayouts::new(interface);
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(interface.shader.as_str()),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some(&interface.vertex_entry),
            compilation_options: Default::default(),
            buffers: &vertex.buffers(),
        },
        primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
        depth_stencil: options.depth_format.map(|format| wgpu::DepthStencilState {
            format,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some(&interface.fragment_entry),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: options.color_format,
                blend: options.blend,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    });
    Pipeline { pipeline, uniforms, textures }
}

/// A mesh as the vertex stage reads it, vertex-major: each slice holds one entry per vertex
/// (leave out what the shader does not read: [`Interface::attributes`] says what it reads).
#[derive(Clone, Copy, Debug, Default)]
pub struct MeshData<'a> {
    /// Positions in object space.
    pub positions: &'a [[f32; 3]],
    /// Normals in object space.
    pub normals: &'a [[f32; 3]],
    /// Surface parameters (u, v).
    pub uvs: &'a [[f32; 2]],
    /// Derivatives of the position in u.
    pub dpdu: &'a [[f32; 3]],
    /// Derivatives of the position in v.
    pub dpdv: &'a [[f32; 3]],
    /// Vertex-rate parameters by name, `components` floats per vertex each.
    pub params: &'a [(&'a str, &'a [f32])],
}

/// Why [`vertex_buffers`] could not fill an attribute.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MissingAttribute(pub String);

impl std::fmt::Display for MissingAttribute {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "the shader reads the vertex attribute `{}`, which the mesh does not have", self.0)
    }
}

impl std::error::Error for MissingAttribute {}

/// One vertex buffer per attribute of `interface`, filled from `mesh`, in the order
/// [`VertexLayouts::buffers`] lays them out: bind buffer `i` at slot `i`.
pub fn vertex_buffers(
    device: &wgpu::Device,
    interface: &Interface,
    mesh: &MeshData,
) -> Result<Vec<wgpu::Buffer>, MissingAttribute> {
    use crate::interface::{AttributeSource, MeshAttribute};
    use wgpu::util::DeviceExt as _;
    interface
        .attributes
        .iter()
        .map(|a| {
            let floats: &[f32] = match &a.source {
                AttributeSource::Mesh { what: MeshAttribute::Position } => mesh.positions.as_flattened(),
                AttributeSource::Mesh { what: MeshAttribute::Normal } => mesh.normals.as_flattened(),
                AttributeSource::Mesh { what: MeshAttribute::Uv } => mesh.uvs.as_flattened(),
                AttributeSource::Mesh { what: MeshAttribute::DpDu } => mesh.dpdu.as_flattened(),
                AttributeSource::Mesh { what: MeshAttribute::DpDv } => mesh.dpdv.as_flattened(),
                AttributeSource::Param { name } => {
                    mesh.params.iter().find(|(n, _)| n == name).map_or(&[][..], |(_, v)| *v)
                }
                _ => &[],
            };
            if floats.is_empty() || floats.len() < mesh.positions.len() * a.components as usize {
                return Err(MissingAttribute(a.name.clone()));
            }
            Ok(device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(a.name.as_str()),
                contents: bytemuck::cast_slice(floats),
                usage: wgpu::BufferUsages::VERTEX,
            }))
        })
        .collect()
}

impl Pipeline {
    /// Records one indexed draw of this pipeline into `pass`: the bind groups (`None` for a
    /// group the program does not use), the vertex buffers of [`vertex_buffers`] and 32-bit
    /// indices.
    pub fn draw(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        groups: [Option<&wgpu::BindGroup>; 2],
        vertex_buffers: &[wgpu::Buffer],
        indices: &wgpu::Buffer,
        index_count: u32,
    ) {
        pass.set_pipeline(&self.pipeline);
        for (index, group) in groups.into_iter().enumerate() {
            if let Some(group) = group {
                pass.set_bind_group(index as u32, group, &[]);
            }
        }
        for (slot, buffer) in vertex_buffers.iter().enumerate() {
            pass.set_vertex_buffer(slot as u32, buffer.slice(..));
        }
        pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..index_count, 0, 0..1);
    }
}

/// An offscreen colour target with a `Depth32Float` depth buffer, for headless programs and
/// tests: begin a pass that clears both, then read the colour back.
#[derive(Debug)]
pub struct Offscreen {
    /// The colour texture (`RENDER_ATTACHMENT | COPY_SRC`).
    pub colour: wgpu::Texture,
    /// The depth texture.
    pub depth: wgpu::Texture,
    colour_view: wgpu::TextureView,
    depth_view: wgpu::TextureView,
}

/// Why [`Offscreen::read`] failed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadError(pub String);

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "reading the target back failed: {}", self.0)
    }
}

impl std::error::Error for ReadError {}

impl Offscreen {
    /// A `width × height` target of `format` (a format with a fixed texel size, such as
    /// `Rgba8Unorm` or `Rgba32Float`).
    pub fn new(device: &wgpu::Device, width: u32, height: u32, format: wgpu::TextureFormat) -> Offscreen {
        let texture = |format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some("patina offscreen"),
                size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
        let colour = texture(format, usage);
        let depth = texture(wgpu::TextureFormat::Depth32Float, wgpu::TextureUsages::RENDER_ATTACHMENT);
        let (colour_view, depth_view) =
            (colour.create_view(&Default::default()), depth.create_view(&Default::default()));
        Offscreen { colour, depth, colour_view, depth_view }
    }

    /// A render pass into the target that clears the colour to `clear` and the depth to 1.
    pub fn begin_pass<'e>(
        &self,
        encoder: &'e mut wgpu::CommandEncoder,
        clear: wgpu::Color,
    ) -> wgpu::RenderPass<'e> {
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("patina offscreen"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &self.colour_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(clear), store: wgpu::StoreOp::Store },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        })
    }

    /// The colour target's texels, row after row from the top, without row padding (waits for
    /// the queue).
    pub fn read(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Vec<u8>, ReadError> {
        let size = self.colour.size();
        let texel = self
            .colour
            .format()
            .block_copy_size(None)
            .ok_or_else(|| ReadError("format has no fixed texel size".into()))?;
        let row = size.width * texel;
        let padded = row.next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("patina readback"),
            size: u64::from(padded) * u64::from(size.height),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        let layout =
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(padded), rows_per_image: None };
        encoder.copy_texture_to_buffer(
            self.colour.as_image_copy(),
            wgpu::TexelCopyBufferInfo { buffer: &buffer, layout },
            size,
        );
        queue.submit([encoder.finish()]);
        let (tx, rx) = std::sync::mpsc::channel();
        buffer.map_async(wgpu::MapMode::Read, .., move |r| {
            let _ = tx.send(r);
        });
        device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| ReadError(e.to_string()))?;
        rx.recv().map_err(|e| ReadError(e.to_string()))?.map_err(|e| ReadError(e.to_string()))?;
        let mapped = buffer.get_mapped_range(..).map_err(|e| ReadError(e.to_string()))?;
        let texels = mapped.chunks(padded as usize).flat_map(|line| &line[..row as usize]).copied().collect();
        Ok(texels)
    }
}
