//! A draw's render pipeline, bind groups and buffers, built from what the draw holds.

use super::render::{Blend, DEPTH_FORMAT, Draw};
use super::texture::{self, Uploaded};
use super::{Gpu, GpuError};
use std::borrow::Cow;

/// A draw's GPU objects, made before the render pass borrows them.
pub(super) struct Prepared {
    pub pipeline: wgpu::RenderPipeline,
    pub groups: Vec<(u32, wgpu::BindGroup)>,
    pub vertex_buffers: Vec<wgpu::Buffer>,
    pub index_buffer: wgpu::Buffer,
    pub index_count: u32,
}

impl Gpu {
    /// Pipeline, bind groups and buffers for one draw.
    pub(super) fn prepare(&self, draw: &Draw, format: wgpu::TextureFormat) -> Result<Prepared, GpuError> {
        let both = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
        let mut layouts = [None, None];
        let mut groups = Vec::new();
        if !draw.uniforms.is_empty() {
            let buffer = self.buffer_with(draw.uniforms, 16, wgpu::BufferUsages::UNIFORM);
            let layout = self.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("patina uniforms"),
                entries: &[wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: both,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                }],
            });
            let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("patina uniforms"),
                layout: &layout,
                entries: &[wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() }],
            });
            groups.push((0, group));
            layouts[0] = Some(layout);
        }
        if !draw.textures.is_empty() {
            let uploaded =
                draw.textures.iter().map(|t| self.upload_texture(t)).collect::<Result<Vec<_>, _>>()?;
            let mut entries = Vec::new();
            for (k, t) in draw.textures.iter().enumerate() {
                let texture = wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: texture::view_dimension(t.dimension),
                    multisampled: false,
                };
                let sampler = wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering);
                for (binding, ty) in [(2 * k as u32, texture), (2 * k as u32 + 1, sampler)] {
                    entries.push(wgpu::BindGroupLayoutEntry { binding, visibility: both, ty, count: None });
                }
            }
            let layout = self.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("patina textures"),
                entries: &entries,
            });
            let entries: Vec<_> = uploaded
                .iter()
                .enumerate()
                .flat_map(|(k, Uploaded { view, sampler })| {
                    [
                        wgpu::BindGroupEntry {
                            binding: 2 * k as u32,
                            resource: wgpu::BindingResource::TextureView(view),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2 * k as u32 + 1,
                            resource: wgpu::BindingResource::Sampler(sampler),
                        },
                    ]
                })
                .collect();
            let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("patina textures"),
                layout: &layout,
                entries: &entries,
            });
            groups.push((1, group));
            layouts[1] = Some(layout);
        }
        let used = if layouts[1].is_some() { 2 } else { usize::from(layouts[0].is_some()) };
        let layout_refs: Vec<_> = layouts[..used].iter().map(Option::as_ref).collect();
        let layout = self.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &layout_refs,
            immediate_size: 0,
        });
        let module = self.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("patina draw"),
            source: wgpu::ShaderSource::Naga(Cow::Owned(draw.module.clone())),
        });
        let vertex_attributes: Vec<_> = draw
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
        let vertex_layouts: Vec<_> = draw
            .attributes
            .iter()
            .zip(&vertex_attributes)
            .map(|(a, attribute)| {
                Some(wgpu::VertexBufferLayout {
                    array_stride: 4 * u64::from(a.components),
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: std::slice::from_ref(attribute),
                })
            })
            .collect();
        let blend = match draw.blend {
            Blend::Replace => None,
            Blend::PremultipliedOver => Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
        };
        let pipeline = self.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("patina draw"),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(draw.vertex_entry),
                compilation_options: Default::default(),
                buffers: &vertex_layouts,
            },
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleList,
                front_face: wgpu::FrontFace::Ccw,
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(draw.fragment_entry),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let vertex_buffers = draw
            .attributes
            .iter()
            .map(|a| self.buffer_with(bytemuck::cast_slice(&a.data), 4, wgpu::BufferUsages::VERTEX))
            .collect();
        let index_buffer = self.buffer_with(bytemuck::cast_slice(draw.indices), 4, wgpu::BufferUsages::INDEX);
        Ok(Prepared {
            pipeline,
            groups,
            vertex_buffers,
            index_buffer,
            index_count: draw.indices.len() as u32,
        })
    }
}
