//! A complete headless wgpu program with a Patina shader: its own device, mesh and camera, the
//! plastic shader under a point light, one frame written to a PNG. It draws what
//! `patina render examples/headless.toml` draws (tests/library/headless.rs checks that).
//!
//! `cargo run --example headless -- out.png`

use std::f32::consts::{PI, TAU};

use patina::{Camera, Compiler, Light, View, gpu};
use wgpu::util::DeviceExt;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "headless.png".into());
    let (width, height) = (320, 240);
    // The shader, bound to a point light, and its uniform block for our camera.
    let point = Light::file("examples/shaders/lights.sl").named("pointlight");
    let compiled = Compiler::new().light(point).compile_file("examples/shaders/plastic.sl")?;
    let mut block = compiled.uniforms();
    block.set("Kd", 0.7)?.set("Ks", 0.5)?.set("roughness", 0.08)?;
    block.set_light(0, "intensity", 12.0)?.set_light(0, "from", [-2.5, 3.0, -3.0])?;
    let (from, to, up) = ([0.0, 0.0, -4.0].into(), glam::Vec3::ZERO, glam::Vec3::Y);
    let camera = Camera { from, to, up, fov_y_degrees: 40.0, near: 0.1, far: 100.0 };
    block.set_view(View { camera, width, height, color: [0.9, 0.35, 0.2], ..View::default() });

    // Our own device, and our own mesh: a unit sphere (its normals are its points), 64 × 32 quads.
    let adapter = pollster::block_on(wgpu::Instance::default().request_adapter(&Default::default()))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&Default::default()))?;
    let (nu, nv) = (64, 32);
    let points: Vec<[f32; 3]> = (0..=nv * (nu + 1))
        .map(|k| {
            let (u, v) = ((k % (nu + 1)) as f32 / nu as f32, (k / (nu + 1)) as f32 / nv as f32);
            let (ct, st) = if u >= 1.0 { (1.0, 0.0) } else { ((TAU * u).cos(), (TAU * u).sin()) };
            let phi = PI * (v - 0.5);
            let (cp, sp) = if v == 0.0 || v == 1.0 { (0.0, 2.0 * v - 1.0) } else { (phi.cos(), phi.sin()) };
            [cp * ct, cp * st, sp]
        })
        .collect();
    let quads = (0..nv).flat_map(|j| (0..nu).map(move |i| j * (nu + 1) + i));
    let indices: Vec<u32> = quads.flat_map(|a| [a, a + 1, a + nu + 2, a, a + nu + 2, a + nu + 1]).collect();
    let mesh = gpu::MeshData { positions: &points, normals: &points, ..Default::default() };

    // Buffers, pipeline and bind group from the interface; one frame into an RGBA8 target.
    let init = |contents: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: None, contents, usage })
    };
    let vertices = gpu::vertex_buffers(&device, &compiled.interface, &mesh)?;
    let index_buffer = init(bytemuck::cast_slice(&indices), wgpu::BufferUsages::INDEX);
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let pipeline = gpu::render_pipeline(&device, &compiled, &gpu::PipelineOptions::new(format));
    let uniforms = init(&block.bytes()?, wgpu::BufferUsages::UNIFORM);
    let group = pipeline.uniform_bind_group(&device, &uniforms);
    let target = gpu::Offscreen::new(&device, width, height, format);
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = target.begin_pass(&mut encoder, wgpu::Color { r: 0.05, g: 0.05, b: 0.08, a: 1.0 });
        pipeline.draw(&mut pass, [group.as_ref(), None], &vertices, &index_buffer, indices.len() as u32);
    }
    queue.submit([encoder.finish()]);
    let pixels = target.read(&device, &queue)?;
    image::save_buffer(&out, &pixels, width, height, image::ExtendedColorType::Rgba8)?;
    println!("wrote {out}");
    Ok(())
}
