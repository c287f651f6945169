//! Showing a rendered picture in the window: the picture is uploaded as a texture with the bytes
//! `patina render` writes to its PNG, and a fullscreen triangle copies it, pixel for pixel, to the
//! swapchain image.

use std::sync::Arc;

use patina_runtime::gpu::Gpu;
use patina_runtime::image::Image;
use winit::event_loop::ActiveEventLoop;
use winit::window::Window;

/// The blit: one triangle covering the viewport, each fragment fetching its own texel (clamped,
/// so that while a resized window waits for its new picture it shows the old one's corner).
const BLIT: &str = r"
@group(0) @binding(0) var picture: texture_2d<f32>;

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
    let uv = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs(@builtin(position) position: vec4f) -> @location(0) vec4f {
    let last = textureDimensions(picture) - 1u;
    let texel = textureLoad(picture, min(vec2u(position.xy), last), 0);
    // The window is opaque: show the colour as the PNG stores it, without its alpha.
    return vec4f(texel.rgb, 1.0);
}
";

/// The window's swapchain and what copies a picture to it.
pub struct Presenter {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    device: wgpu::Device,
    queue: wgpu::Queue,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    /// The picture's texture format: sRGB exactly when the swapchain's is, so that the sRGB
    /// decode on sampling and the encode on writing cancel and the screen gets the PNG's bytes.
    picture_format: wgpu::TextureFormat,
    /// The picture shown, once there is one.
    picture: Option<wgpu::BindGroup>,
}

impl Presenter {
    /// A presenter for `window`, and the device it draws with, which renders the scene too
    /// (opened as `Gpu::new` opens one, on an adapter that can draw to the window).
    pub fn open(event_loop: &ActiveEventLoop, window: Arc<Window>) -> Result<(Presenter, Gpu), String> {
        let mut desc =
            wgpu::InstanceDescriptor::new_with_display_handle(Box::new(event_loop.owned_display_handle()));
        desc.backends = wgpu::Backends::from_env().unwrap_or_else(Gpu::default_backends);
        desc.flags = wgpu::InstanceFlags::default().with_env();
        let instance = wgpu::Instance::new(desc);
        let surface = instance
            .create_surface(Arc::clone(&window))
            .map_err(|e| format!("cannot draw to the window: {e}"))?;
        let options =
            wgpu::RequestAdapterOptions { compatible_surface: Some(&surface), ..Default::default() };
        // The window is drawn by the GPU even when the picture is the CPU's: without an adapter
        // there is nothing to show it with.
        let adapter = pollster::block_on(instance.request_adapter(&options)).map_err(|e| {
            format!(
                "no GPU adapter can draw the window ({e}); install a Vulkan driver (on Debian/Ubuntu: \
                 apt-get install mesa-vulkan-drivers libvulkan1), or use `patina watch`, which renders \
                 to a PNG without one"
            )
        })?;
        let gpu = Gpu::from_adapter(adapter).map_err(|e| e.to_string())?;
        let presenter =
            Presenter::new(window, surface, gpu.adapter(), gpu.device().clone(), gpu.queue().clone())?;
        Ok((presenter, gpu))
    }

    /// A presenter for `window` through `surface`, made on `adapter`'s `device`.
    fn new(
        window: Arc<Window>,
        surface: wgpu::Surface<'static>,
        adapter: &wgpu::Adapter,
        device: wgpu::Device,
        queue: wgpu::Queue,
    ) -> Result<Presenter, String> {
        let caps = surface.get_capabilities(adapter);
        // Prefer a format that stores what is written as it is: the picture's bytes are already
        // the PNG's, with no gamma to apply.
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| matches!(f, wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm))
            .or_else(|| caps.formats.first().copied())
            .ok_or("the window's surface offers no format this GPU can draw to")?;
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            color_space: wgpu::SurfaceColorSpace::Auto,
            width: size.width.max(1),
            height: size.height.max(1),
            desired_maximum_frame_latency: 2,
            // Fifo is the one mode every surface has.
            present_mode: wgpu::PresentMode::Fifo,
            alpha_mode: caps.alpha_modes.first().copied().unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: vec![],
        };
        surface.configure(&device, &config);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("patina view blit"),
            source: wgpu::ShaderSource::Wgsl(BLIT.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("patina view picture"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("patina view blit"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("patina view blit"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let picture_format = if format.is_srgb() {
            wgpu::TextureFormat::Rgba8UnormSrgb
        } else {
            wgpu::TextureFormat::Rgba8Unorm
        };
        Ok(Presenter {
            window,
            surface,
            config,
            device,
            queue,
            pipeline,
            layout,
            picture_format,
            picture: None,
        })
    }

    /// The window's size in pixels now (at least 1 by 1).
    pub fn size(&self) -> (u32, u32) {
        let size = self.window.inner_size();
        (size.width.max(1), size.height.max(1))
    }

    /// Resizes the swapchain to the window (a minimized window, 0 pixels wide, keeps the old);
    /// whether its size changed.
    pub fn resize(&mut self) -> bool {
        let size = self.window.inner_size();
        let changed = (size.width, size.height) != (self.config.width, self.config.height);
        if changed && size.width > 0 && size.height > 0 {
            self.config.width = size.width;
            self.config.height = size.height;
            self.surface.configure(&self.device, &self.config);
            return true;
        }
        false
    }

    /// Makes `image` the picture shown from the next [`present`](Presenter::present) on.
    pub fn show(&mut self, image: &Image) {
        let size = wgpu::Extent3d {
            width: image.width.max(1),
            height: image.height.max(1),
            depth_or_array_layers: 1,
        };
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("patina view picture"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: self.picture_format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let mut bytes = image.to_rgba8();
        bytes.resize(4 * size.width as usize * size.height as usize, 0);
        self.queue.write_texture(
            texture.as_image_copy(),
            &bytes,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * size.width),
                rows_per_image: None,
            },
            size,
        );
        let view = texture.create_view(&Default::default());
        self.picture = Some(self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("patina view picture"),
            layout: &self.layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&view),
            }],
        }));
    }

    /// Draws the picture (black before there is one) to the window; whether a frame was
    /// presented (not when the surface had no image to give, e.g. while the window is hidden).
    pub fn present(&mut self) -> bool {
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => {
                frame
            }
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                // The window changed under the swapchain: make it anew, and draw next time.
                self.surface.configure(&self.device, &self.config);
                self.window.request_redraw();
                return false;
            }
            wgpu::CurrentSurfaceTexture::Timeout => {
                self.window.request_redraw();
                return false;
            }
            _ => return false,
        };
        let view = frame.texture.create_view(&Default::default());
        let mut encoder = self.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("patina view blit"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            if let Some(picture) = &self.picture {
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(0, picture, &[]);
                pass.draw(0..3, 0..1);
            }
        }
        self.queue.submit([encoder.finish()]);
        self.window.pre_present_notify();
        self.queue.present(frame);
        true
    }
}
