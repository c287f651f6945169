//! A draw's render pipeline, bind groups and buffers, built from what the draw holds, and the
//! pipelines kept per device (`Pipelines`) so that drawing the same shader again makes none.

use super::render::{Blend, DEPTH_FORMAT, Draw};
use super::texture::{self, Uploaded};
use super::{Gpu, GpuError};
use std::borrow::Cow;
use std::collections::HashMap;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A draw's GPU objects, made before the render pass borrows them.
pub(super) struct Prepared {
    pub pipeline: wgpu::RenderPipeline,
    pub groups: Vec<(u32, wgpu::BindGroup)>,
    pub vertex_buffers: Vec<wgpu::Buffer>,
    pub index_buffer: wgpu::Buffer,
    pub index_count: u32,
}

/// A kept pipeline and the bind group layouts it was made with (its bind groups, made per draw,
/// must use these very layouts).
#[derive(Clone)]
pub(super) struct Kept {
    pipeline: wgpu::RenderPipeline,
    uniforms: Option<wgpu::BindGroupLayout>,
    textures: Option<wgpu::BindGroupLayout>,
}

/// The pipelines a device has made for fingerprinted draws, by `pipeline_key`, and how many render
/// pipelines it has made in all.
#[derive(Default)]
pub(super) struct Pipelines {
    kept: Mutex<HashMap<u64, Kept>>,
    made: AtomicUsize,
}

/// More than this many kept pipelines and the next one starts the store afresh: a long session
/// of edited shaders must not keep every version alive.
const MAX_KEPT: usize = 256;

impl Pipelines {
    fn get(&self, key: u64) -> Option<Kept> {
        self.kept.lock().ok()?.get(&key).cloned()
    }

    /// Keeps `kept` under `key`.
    pub(super) fn keep(&self, key: u64, kept: Kept) {
        if let Ok(mut map) = self.kept.lock() {
            if map.len() >= MAX_KEPT {
                map.clear();
            }
            map.insert(key, kept);
        }
    }

    /// How many pipelines are kept.
    pub(super) fn len(&self) -> usize {
        self.kept.lock().map_or(0, |m| m.len())
    }

    /// How many render pipelines the device has made.
    pub(super) fn made(&self) -> usize {
        self.made.load(Ordering::Relaxed)
    }
}

/// Everything a draw's pipeline and layouts depend on, hashed; `None` when the draw has no
/// fingerprint.
fn pipeline_key(draw: &Draw, format: wgpu::TextureFormat) -> Option<u64> {
    let mut h = DefaultHasher::new();
    draw.fingerprint?.hash(&mut h);
    (draw.vertex_entry, draw.fragment_entry, format, matches!(draw.blend, Blend::Replace), draw.samplers)
        .hash(&mut h);
    draw.attributes.iter().for_each(|a| (a.location, a.components).hash(&mut h));
    draw.uniforms.is_empty().hash(&mut h);
    draw.textures.iter().for_each(|t| texture::view_dimension(t.dimension).hash(&mut h));
    Some(h.finish())
}

impl Gpu {
    /// Pipeline, bind groups and buffers for one draw; the pipeline is a kept one when the draw
    /// has a fingerprint that was drawn before, or one made earlier in this render (`fresh`,
    /// where a pipeline this draw makes is added: objects sharing a module share it).
    pub(super) fn prepare(
        &self,
        draw: &Draw,
        format: wgpu::TextureFormat,
        fresh: &mut HashMap<u64, Kept>,
    ) -> Result<Prepared, GpuError> {
        let key = pipeline_key(draw, format);
        let found = key.and_then(|k| self.pipelines.get(k).or_else(|| fresh.get(&k).cloned()));
        let kept = match found {
            Some(kept) => kept,
            None => {
                let kept = self.make_pipeline(draw, format);
                if let Some(k) = key {
                    fresh.insert(k, kept.clone());
                }
                kept
            }
        };
        let mut groups = Vec::new();
        if let Some(layout) = &kept.uniforms {
            let buffer = self.buffer_with(draw.uniforms, 16, wgpu::BufferUsages::UNIFORM);
            let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("patina uniforms"),
                layout,
                entries: &[wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() }],
            });
            groups.push((0, group));
        }
        if let Some(layout) = &kept.textures {
            let uploaded =
                draw.textures.iter().map(|t| self.upload_texture(t)).collect::<Result<Vec<_>, _>>()?;
            let entries: Vec<_> = uploaded
                .iter()
                .enumerate()
                .flat_map(|(k, Uploaded { view, sampler })| {
                    let texture = wgpu::BindingResource::TextureView(view);
                    let sampler = wgpu::BindingResource::Sampler(sampler);
                    let (binding, sampler) =
                        if draw.samplers { (2 * k as u32, Some(sampler)) } else { (k as u32, None) };
                    std::iter::once(wgpu::BindGroupEntry { binding, resource: texture }).chain(
                        sampler.map(|resource| wgpu::BindGroupEntry { binding: binding + 1, resource }),
                    )
                })
                .collect();
            let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("patina textures"),
                layout,
                entries: &entries,
            });
            groups.push((1, group));
        }
        let vertex_buffers = draw
            .attributes
            .iter()
            .map(|a| self.buffer_with(bytemuck::cast_slice(&a.data), 4, wgpu::BufferUsages::VERTEX))
            .collect();
        let index_buffer = self.buffer_with(bytemuck::cast_slice(draw.indices), 4, wgpu::BufferUsages::INDEX);
        Ok(Prepared {
            pipeline: kept.pipeline,
            groups,
            vertex_buffers,
            index_buffer,
            index_count: draw.indices.len() as u32,
        })
    }

    /// The bind group layouts and the render pipeline of a draw.
    fn make_pipeline(&self, draw: &Draw, format: wgpu::TextureFormat) -> Kept {
        let both = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
        let uniforms = (!draw.uniforms.is_empty()).then(|| {
            self.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
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
            })
        });
        let textures = (!draw.textures.is_empty()).then(|| {
            let mut entries = Vec::new();
            for (k, t) in draw.textures.iter().enumerate() {
                let texture = |filterable| wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable },
                    view_dimension: texture::view_dimension(t.dimension),
                    multisampled: false,
                };
                let mut add = |binding, ty| {
                    entries.push(wgpu::BindGroupLayoutEntry { binding, visibility: both, ty, count: None });
                };
                if draw.samplers {
                    add(2 * k as u32, texture(true));
                    add(2 * k as u32 + 1, wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering));
                } else {
                    // Patina's modules fetch with `textureLoad`: no sampler, no filtering needed.
                    add(k as u32, texture(false));
                }
            }
            self.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("patina textures"),
                entries: &entries,
            })
        });
        let layouts = [uniforms.as_ref(), textures.as_ref()];
        let used = if textures.is_some() { 2 } else { usize::from(uniforms.is_some()) };
        let layout = self.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &layouts[..used],
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
        self.pipelines.made.fetch_add(1, Ordering::Relaxed);
        Kept { pipeline, uniforms, textures }
    }
}
