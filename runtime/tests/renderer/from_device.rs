//! A device the caller opened with wgpu, wrapped with `Gpu::from_device`: Patina draws with it as
//! with its own (`Gpu::new`), and wgpu errors the caller's own work raises outside any error scope
//! come back as errors, not panics. Needs a GPU adapter (lavapipe is enough) and panics when none is
//! found, unless `PATINA_GPU=off`.

use patina_runtime::gpu::{self, Gpu, GpuError};
use patina_runtime::image::{Thresholds, compare};
use patina_runtime::render::{self, Backend};
use patina_runtime::scene::Scene;

/// Opens an adapter and a device as a user's program would: with wgpu alone, its own label and
/// features, none of Patina's code. `None` when `PATINA_GPU=off`.
fn users_device() -> Option<(wgpu::Adapter, wgpu::Device, wgpu::Queue)> {
    if !gpu::adapter_required() {
        return None;
    }
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all());
    let instance = wgpu::Instance::new(desc);
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default()))
        .unwrap_or_else(|e| panic!("\n\n*** GPU tests need an adapter and none could be opened ***\n{e}\n"));
    let wanted = wgpu::Features::FLOAT32_FILTERABLE | wgpu::Features::FLOAT32_BLENDABLE;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("the user's device"),
        required_features: adapter.features() & wanted,
        required_limits: wgpu::Limits::default(),
        ..Default::default()
    }))
    .expect("the adapter opens a device");
    Some((adapter, device, queue))
}

/// A small plastic sphere under a distant light (a uniform block, a light loop, varyings).
fn scene() -> Scene {
    let text = "[output]\nwidth = 24\nheight = 20\n[camera]\nfrom = [0.0, 0.0, -3.5]\nto = [0.0, 0.0, 0.0]\n\
                [[light]]\nshader = \"<shaders.sl>\"\nname = \"distantlight\"\n\
                params = { intensity = 1.0, from = [-1.0, 1.0, -1.0], to = [0.0, 0.0, 0.0] }\n\
                [[object]]\nmesh = \"sphere\"\ndetail = 16\nshader = \"<shaders.sl>\"\nname = \"plastic\"\n\
                params = { Kd = 0.7, Ks = 0.4, roughness = 0.2 }\n";
    let dir = std::env::temp_dir();
    Scene::parse(text, dir.join("from_device.toml"), &dir).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_users_device_draws_what_patinas_own_draws() {
    let Some((adapter, device, queue)) = users_device() else { return };
    let gpu = Gpu::from_device(adapter, device.clone(), queue);
    assert!(gpu.device() == &device, "the Gpu draws with the device it was given");
    assert_eq!(gpu.limits(), wgpu::Limits::default(), "the user's limits, not the adapter's best");
    eprintln!("adapter: {}", gpu.adapter_description());

    let prepared = render::prepare(&scene()).unwrap_or_else(|e| panic!("{e}"));
    let image = render::render(&prepared, Backend::Gpu, Some(&gpu)).unwrap_or_else(|e| panic!("{e}"));
    let cpu = render::render(&prepared, Backend::Cpu, None).unwrap();
    let t = Thresholds::default();
    let c = compare(&cpu, &image, &t).unwrap();
    assert!(c.passes(&t), "the user's device and the CPU reference differ: {c:?}");
    // Lit: the sphere covers part of the frame, brighter than the background.
    let lit = image.pixels.iter().filter(|p| p[0] > 0.2).count();
    assert!((50..400).contains(&lit), "{lit} of {} pixels lit", image.pixels.len());

    // The same driver through `Gpu::new` draws the same picture, bit for bit.
    let own = Gpu::new().unwrap();
    let theirs = render::render(&prepared, Backend::Gpu, Some(&own)).unwrap();
    assert_eq!(image.pixels, theirs.pixels, "{} vs {}", gpu.adapter_description(), own.adapter_description());
}

const DOUBLE: &str = "
@group(0) @binding(1) var<storage, read> xs: array<f32>;
@group(0) @binding(2) var<storage, read_write> out: array<f32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x < arrayLength(&xs) { out[gid.x] = 2.0 * xs[gid.x]; }
}";

#[test]
fn the_users_uncaptured_errors_come_back_from_the_next_call() {
    let Some((adapter, device, queue)) = users_device() else { return };
    let gpu = Gpu::from_device(adapter, device, queue);
    let module = naga::front::wgsl::parse_str(DOUBLE).unwrap();
    let input: Vec<u8> = [1.5f32, -3.0].iter().flat_map(|v| v.to_le_bytes()).collect();
    let run = || gpu.compute(&module, "main", &[], &[&input], 8, 1);
    assert_eq!(run().unwrap(), [3.0f32, -6.0].iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>());

    // The caller's own mistake, outside any error scope: wgpu's default handler would panic.
    let _buffer = gpu.device().create_buffer(&wgpu::BufferDescriptor {
        label: Some("mapped both ways"),
        size: 16,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::MAP_WRITE,
        mapped_at_creation: false,
    });
    match run() {
        Err(GpuError::Wgpu(why)) => assert!(why.contains("mapped both ways"), "{why}"),
        other => panic!("the uncaptured error was not reported: {other:?}"),
    }
    // Reported once; the device still works.
    assert_eq!(run().unwrap().len(), 8);
}

#[test]
fn new_asks_for_every_compiled_in_native_backend() {
    let backends = Gpu::default_backends();
    assert!(backends.contains(wgpu::Backends::VULKAN));
    assert!(!backends.contains(wgpu::Backends::NOOP) && !backends.contains(wgpu::Backends::BROWSER_WEBGPU));
    assert_eq!(backends.contains(wgpu::Backends::GL), cfg!(feature = "gl"));
    assert_eq!(
        backends.contains(wgpu::Backends::METAL),
        cfg!(all(feature = "metal", target_vendor = "apple"))
    );
    assert_eq!(backends.contains(wgpu::Backends::DX12), cfg!(all(feature = "dx12", windows)));
    // Only Vulkan is built by default, and lavapipe (or a real driver) is found through it.
    if cfg!(not(any(feature = "gl", feature = "metal", feature = "dx12")))
        && std::env::var_os("WGPU_BACKEND").is_none()
        && let Some(gpu) = gpu::for_tests()
    {
        assert_eq!(gpu.adapter().get_info().backend, wgpu::Backend::Vulkan, "{}", gpu.adapter_description());
    }
}
