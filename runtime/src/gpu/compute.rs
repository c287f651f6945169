//! The compute harness: runs one entry point over caller buffers and returns the output buffer, so
//! compiled shader functions can be checked value by value against the CPU interpreter.

use super::texture::{self, TextureData, Uploaded};
use super::{Gpu, GpuError};
use std::borrow::Cow;

impl Gpu {
    /// Dispatches `workgroups` x 1 x 1 workgroups of `entry` and returns the first `output_len` bytes
    /// of the output buffer (which starts zeroed).
    ///
    /// Bindings, all in `@group(0)`: `@binding(0)` is a uniform buffer holding `uniforms` (only when
    /// it is not empty); `@binding(1)` to `@binding(n)` are the `inputs`, as `var<storage, read>`;
    /// `@binding(n + 1)` is the output, `var<storage, read_write>`. Buffers are zero-padded to a
    /// multiple of 4 bytes (16 for the uniform block), so `arrayLength` sees the padded length.
    pub fn compute(
        &self,
        module: &naga::Module,
        entry: &str,
        uniforms: &[u8],
        inputs: &[&[u8]],
        output_len: usize,
        workgroups: u32,
    ) -> Result<Vec<u8>, GpuError> {
        self.compute_textured(module, entry, uniforms, inputs, &[], output_len, workgroups)
    }

    /// As [`Gpu::compute`], with `textures` bound in `@group(1)`, texture k at `@binding(k)` and
    /// no samplers (the entry fetches texels with `textureLoad`, as Patina's kernels do).
    #[allow(clippy::too_many_arguments)]
    pub fn compute_textured(
        &self,
        module: &naga::Module,
        entry: &str,
        uniforms: &[u8],
        inputs: &[&[u8]],
        textures: &[TextureData],
        output_len: usize,
        workgroups: u32,
    ) -> Result<Vec<u8>, GpuError> {
        super::limits::check_compute(&self.device.limits(), uniforms.len(), inputs, output_len, workgroups)?;
        let uploaded = textures.iter().map(|t| self.upload_texture(t)).collect::<Result<Vec<_>, _>>()?;
        let readback = self.scoped(|| {
            self.encode_compute(
                module,
                entry,
                uniforms,
                inputs,
                (textures, &uploaded),
                output_len,
                workgroups,
            )
        })?;
        let mut bytes = self.read_buffer(&readback)?;
        bytes.truncate(output_len);
        Ok(bytes)
    }

    #[allow(clippy::too_many_arguments)]
    fn encode_compute(
        &self,
        module: &naga::Module,
        entry: &str,
        uniforms: &[u8],
        inputs: &[&[u8]],
        (textures, uploaded): (&[TextureData], &[Uploaded]),
        output_len: usize,
        workgroups: u32,
    ) -> wgpu::Buffer {
        let storage = |read_only| wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        };
        let mut types = Vec::new();
        let mut buffers = Vec::new();
        if !uniforms.is_empty() {
            let ty = wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            };
            types.push((0, ty));
            buffers.push((0, self.buffer_with(uniforms, 16, wgpu::BufferUsages::UNIFORM)));
        }
        for (i, input) in inputs.iter().enumerate() {
            let binding = i as u32 + 1;
            types.push((binding, storage(true)));
            buffers.push((binding, self.buffer_with(input, 4, wgpu::BufferUsages::STORAGE)));
        }
        let out_binding = inputs.len() as u32 + 1;
        let output = self.buffer_with(
            &vec![0; output_len],
            4,
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        );
        types.push((out_binding, storage(false)));
        let entries: Vec<_> = types
            .into_iter()
            .map(|(binding, ty)| wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty,
                count: None,
            })
            .collect();
        let layout = self.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("patina compute"),
            entries: &entries,
        });
        let mut group_entries: Vec<_> = buffers
            .iter()
            .map(|(binding, buffer)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: buffer.as_entire_binding(),
            })
            .collect();
        group_entries
            .push(wgpu::BindGroupEntry { binding: out_binding, resource: output.as_entire_binding() });
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("patina compute"),
            layout: &layout,
            entries: &group_entries,
        });
        let texture_layout = (!textures.is_empty()).then(|| {
            let entries: Vec<_> = textures
                .iter()
                .enumerate()
                .map(|(k, t)| wgpu::BindGroupLayoutEntry {
                    binding: k as u32,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: texture::view_dimension(t.dimension),
                        multisampled: false,
                    },
                    count: None,
                })
                .collect();
            self.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("patina compute textures"),
                entries: &entries,
            })
        });
        let texture_group = texture_layout.as_ref().map(|layout| {
            let entries: Vec<_> = uploaded
                .iter()
                .enumerate()
                .map(|(k, u)| wgpu::BindGroupEntry {
                    binding: k as u32,
                    resource: wgpu::BindingResource::TextureView(&u.view),
                })
                .collect();
            self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("patina compute textures"),
                layout,
                entries: &entries,
            })
        });
        let layouts = [Some(&layout), texture_layout.as_ref()];
        let pipeline_layout = self.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &layouts[..if texture_layout.is_some() { 2 } else { 1 }],
            immediate_size: 0,
        });
        let shader = self.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("patina compute"),
            source: wgpu::ShaderSource::Naga(Cow::Owned(module.clone())),
        });
        let pipeline = self.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("patina compute"),
            layout: Some(&pipeline_layout),
            module: &shader,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        });
        let readback = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("patina readback"),
            size: output.size(),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &group, &[]);
            if let Some(textures) = &texture_group {
                pass.set_bind_group(1, textures, &[]);
            }
            pass.dispatch_workgroups(workgroups, 1, 1);
        }
        encoder.copy_buffer_to_buffer(&output, 0, &readback, 0, output.size());
        self.queue.submit([encoder.finish()]);
        readback
    }
}
