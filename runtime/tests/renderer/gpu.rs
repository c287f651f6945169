//! GPU tests: the compute harness and offscreen rendering, checked value by value.
//!
//! They need an adapter (lavapipe is enough) and panic when none is found, unless `PATINA_GPU=off`.

use patina_runtime::gpu::{
    self, Address, Attribute, Blend, Draw, Filter, Gpu, GpuError, Target, TargetFormat, TextureData,
    TextureDimension,
};
use patina_runtime::image::Image;

fn module(wgsl: &str) -> naga::Module {
    naga::front::wgsl::parse_str(wgsl).unwrap_or_else(|e| panic!("{}", e.emit_to_string(wgsl)))
}

fn f32s(bytes: &[u8]) -> Vec<f32> {
    bytes.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
}

fn bytes(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

#[test]
fn adapter_opens() {
    let Some(gpu) = gpu::for_tests() else { return };
    let description = gpu.adapter_description();
    eprintln!("adapter: {description}");
    assert!(!description.is_empty());
}

const SQUARE_PLUS_ONE: &str = "
@group(0) @binding(1) var<storage, read> xs: array<f32>;
@group(0) @binding(2) var<storage, read_write> out: array<f32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&xs) { return; }
    out[i] = xs[i] * xs[i] + 1.0;
}";

#[test]
fn compute_square_plus_one_is_exact() {
    let Some(gpu) = gpu::for_tests() else { return };
    let xs: Vec<f32> = (0..1000).map(|i| (i as f32 - 500.0) * 0.173).collect();
    let out = gpu.compute(&module(SQUARE_PLUS_ONE), "main", &[], &[&bytes(&xs)], 4 * xs.len(), 16).unwrap();
    let got = f32s(&out);
    assert_eq!(got.len(), xs.len());
    for (x, y) in xs.iter().zip(&got) {
        assert_eq!(y.to_bits(), (x * x + 1.0).to_bits(), "x = {x}");
    }
}

#[test]
fn compute_with_uniforms_and_two_inputs() {
    let Some(gpu) = gpu::for_tests() else { return };
    let m = module(
        "
        struct Params { scale: f32, offset: f32, count: u32 }
        @group(0) @binding(0) var<uniform> params: Params;
        @group(0) @binding(1) var<storage, read> a: array<f32>;
        @group(0) @binding(2) var<storage, read> b: array<u32>;
        @group(0) @binding(3) var<storage, read_write> out: array<vec2<f32>>;
        @compute @workgroup_size(8)
        fn run(@builtin(global_invocation_id) gid: vec3<u32>) {
            let i = gid.x;
            if i >= params.count { return; }
            out[i] = vec2(a[i] * params.scale + params.offset, f32(b[i] * 3u));
        }",
    );
    let uniforms: Vec<u8> = [3.0f32.to_le_bytes(), 0.5f32.to_le_bytes(), 5u32.to_le_bytes()].concat();
    let a = [1.0f32, 2.0, -4.0, 0.25, 10.0];
    let b: Vec<u8> = [7u32, 0, 1, 100, 9].iter().flat_map(|v| v.to_le_bytes()).collect();
    // One vec2 more than the shader writes: it must stay zero.
    let out = gpu.compute(&m, "run", &uniforms, &[&bytes(&a), &b], 6 * 8, 1).unwrap();
    assert_eq!(f32s(&out), [3.5, 21.0, 6.5, 0.0, -11.5, 3.0, 1.25, 300.0, 30.5, 27.0, 0.0, 0.0]);
}

#[test]
fn compute_errors_are_reported_not_panics() {
    let Some(gpu) = gpu::for_tests() else { return };
    let m = module(SQUARE_PLUS_ONE);
    let input = bytes(&[1.0, 2.0]);
    let missing_entry = gpu.compute(&m, "nope", &[], &[&input], 8, 1);
    assert!(matches!(missing_entry, Err(GpuError::Wgpu(_))), "{missing_entry:?}");
    // Without inputs the output moves to binding 1, where the shader reads `xs`: the layout does not
    // match the shader.
    let wrong_layout = gpu.compute(&m, "main", &[], &[], 8, 1);
    match wrong_layout {
        Err(GpuError::Wgpu(message)) => eprintln!("{message}"),
        other => panic!("expected a wgpu error, got {other:?}"),
    }
    let too_many = gpu.compute(&m, "main", &[], &[&input], 8, u32::MAX);
    assert!(
        matches!(too_many, Err(GpuError::Limit { name: "max_compute_workgroups_per_dimension", .. })),
        "{too_many:?}"
    );
    // The device is still usable after the errors.
    assert_eq!(f32s(&gpu.compute(&m, "main", &[], &[&input], 8, 1).unwrap()), [2.0, 5.0]);
}

const GRADIENT: &str = "
struct U { scale: f32, offset: f32 }
@group(0) @binding(0) var<uniform> u: U;
struct V { @builtin(position) pos: vec4f, @location(0) t: f32 }
@vertex fn vs(@location(0) p: vec2f, @location(1) t: f32) -> V { return V(vec4f(p, 0.5, 1.0), t); }
@fragment fn fs(v: V) -> @location(0) vec4f { return vec4f(v.t * u.scale, v.pos.x, v.pos.y, u.offset); }
";

/// A quad over the whole target: corners bottom-left, bottom-right, top-right, top-left.
const QUAD: [f32; 8] = [-1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0];
const QUAD_INDICES: [u32; 6] = [0, 1, 2, 0, 2, 3];

fn float_target(width: u32, height: u32, clear: [f32; 4]) -> Target {
    Target { width, height, format: TargetFormat::Rgba32Float, clear }
}

fn attribute(location: u32, components: u32, data: &[f32]) -> Attribute {
    Attribute { location, components, data: data.to_vec() }
}

#[test]
fn render_gradient_from_uniform_and_attribute() {
    let Some(gpu) = gpu::for_tests() else { return };
    let m = module(GRADIENT);
    let uniforms = bytes(&[2.0, 0.25]); // 8 bytes: padded to 16 by the runtime
    let attributes = [attribute(0, 2, &QUAD), attribute(1, 1, &[0.0, 1.0, 1.0, 0.0])];
    let draw = Draw {
        module: &m,
        fingerprint: None,
        vertex_entry: "vs",
        fragment_entry: "fs",
        uniforms: &uniforms,
        textures: &[],
        samplers: false,
        attributes: &attributes,
        indices: &QUAD_INDICES,
        blend: Blend::Replace,
    };
    let image = gpu.render(&float_target(8, 4, [0.0; 4]), &[draw]).unwrap();
    assert_eq!((image.width, image.height, image.pixels.len()), (8, 4, 32));
    for (x, y) in [(0, 0), (3, 1), (7, 3), (5, 2)] {
        let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
        assert_eq!(image.get(x, y), Some([cx / 8.0 * 2.0, cx, cy, 0.25]), "pixel ({x}, {y})");
    }
}

const COLOURED: &str = "
struct V { @builtin(position) pos: vec4f, @location(0) c: vec4f }
@vertex fn vs(@location(0) p: vec3f, @location(1) c: vec4f) -> V { return V(vec4f(p, 1.0), c); }
@fragment fn fs(v: V) -> @location(0) vec4f { return v.c; }
";

/// A one-colour draw of `positions` (x, y, z per vertex) as a triangle fan.
fn flat_draw<'a>(
    m: &'a naga::Module,
    attributes: &'a [Attribute],
    indices: &'a [u32],
    blend: Blend,
) -> Draw<'a> {
    Draw {
        module: m,
        fingerprint: None,
        vertex_entry: "vs",
        fragment_entry: "fs",
        uniforms: &[],
        textures: &[],
        samplers: false,
        attributes,
        indices,
        blend,
    }
}

fn flat(positions: &[f32], colour: [f32; 4]) -> [Attribute; 2] {
    let n = positions.len() / 3;
    [attribute(0, 3, positions), attribute(1, 4, &colour.repeat(n))]
}

#[test]
fn nearer_triangle_wins_in_either_order() {
    let Some(gpu) = gpu::for_tests() else { return };
    let m = module(COLOURED);
    let (red, green) = ([1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]);
    // The far triangle covers the whole target; the near quad only its left half.
    let far = flat(&[-1.0, -1.0, 0.75, 3.0, -1.0, 0.75, -1.0, 3.0, 0.75], green);
    let near = flat(&[-1.0, -1.0, 0.25, 0.0, -1.0, 0.25, 0.0, 1.0, 0.25, -1.0, 1.0, 0.25], red);
    let far_draw = flat_draw(&m, &far, &[0, 1, 2], Blend::Replace);
    let near_draw = flat_draw(&m, &near, &QUAD_INDICES, Blend::Replace);
    for draws in [[far_draw, near_draw], [near_draw, far_draw]] {
        let image = gpu.render(&float_target(8, 8, [0.0; 4]), &draws).unwrap();
        for y in [0, 3, 7] {
            assert_eq!(image.get(0, y), Some(red));
            assert_eq!(image.get(3, y), Some(red));
            assert_eq!(image.get(4, y), Some(green));
            assert_eq!(image.get(7, y), Some(green));
        }
    }
}

#[test]
fn premultiplied_over_blends_with_the_clear_colour() {
    let Some(gpu) = gpu::for_tests() else { return };
    let m = module(COLOURED);
    let cover = flat(&[-1.0, -1.0, 0.5, 3.0, -1.0, 0.5, -1.0, 3.0, 0.5], [0.25, 0.5, 0.0, 0.5]);
    let draw = flat_draw(&m, &cover, &[0, 1, 2], Blend::PremultipliedOver);
    let image = gpu.render(&float_target(4, 4, [0.0, 0.0, 0.5, 0.5]), &[draw]).unwrap();
    // src + dst * (1 - 0.5)
    assert!(image.pixels.iter().all(|&p| p == [0.25, 0.5, 0.25, 0.75]), "{:?}", image.pixels[0]);
    let replace = flat_draw(&m, &cover, &[0, 1, 2], Blend::Replace);
    let image = gpu.render(&float_target(4, 4, [0.0, 0.0, 0.5, 0.5]), &[replace]).unwrap();
    assert!(image.pixels.iter().all(|&p| p == [0.25, 0.5, 0.0, 0.5]));
}

#[test]
fn rgba8_target_reads_back_as_unit_floats() {
    let Some(gpu) = gpu::for_tests() else { return };
    let m = module(COLOURED);
    let cover = flat(&[-1.0, -1.0, 0.5, 3.0, -1.0, 0.5, -1.0, 3.0, 0.5], [1.0, 0.2, 0.6, 0.0]);
    let draw = flat_draw(&m, &cover, &[0, 1, 2], Blend::Replace);
    // 70 pixels * 4 bytes = 280: rows are padded to 512 bytes in the readback buffer.
    let target = Target { width: 70, height: 3, format: TargetFormat::Rgba8, clear: [0.0; 4] };
    let image = gpu.render(&target, &[draw]).unwrap();
    assert_eq!(image.pixels.len(), 210);
    assert!(image.pixels.iter().all(|&p| p == [1.0, 51.0 / 255.0, 153.0 / 255.0, 0.0]));
}

const TEXTURED: &str = "
@group(1) @binding(0) var tex: texture_2d<f32>;
@group(1) @binding(1) var smp: sampler;
struct V { @builtin(position) pos: vec4f, @location(0) uv: vec2f }
@vertex fn vs(@location(0) p: vec2f, @location(1) uv: vec2f) -> V { return V(vec4f(p, 0.5, 1.0), uv); }
@fragment fn fs(v: V) -> @location(0) vec4f { return textureSample(tex, smp, v.uv); }
@fragment fn fs_level1(v: V) -> @location(0) vec4f { return textureSampleLevel(tex, smp, v.uv, 1.0); }
";

/// uv (0, 0) at the top-left corner, so pixel (x, y) samples texel (x, y) of a texture of the target's size.
const QUAD_UV: [f32; 8] = [0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0];

fn texel(x: u32, y: u32) -> [f32; 4] {
    [x as f32 / 4.0, y as f32 / 4.0, (x + 4 * y) as f32 / 16.0, 1.0]
}

fn texture_4x4(mipmaps: bool) -> TextureData {
    TextureData {
        dimension: TextureDimension::D2,
        size: [4, 4, 1],
        texels: (0..16).map(|i| texel(i % 4, i / 4)).collect(),
        filter: Filter::Nearest,
        address: Address::ClampToEdge,
        mipmaps,
    }
}

fn render_textured(gpu: &Gpu, texture: TextureData, fragment_entry: &str) -> Image {
    let m = module(TEXTURED);
    let attributes = [attribute(0, 2, &QUAD), attribute(1, 2, &QUAD_UV)];
    let draw = Draw {
        module: &m,
        fingerprint: None,
        vertex_entry: "vs",
        fragment_entry,
        uniforms: &[],
        textures: &[texture],
        samplers: true,
        attributes: &attributes,
        indices: &QUAD_INDICES,
        blend: Blend::Replace,
    };
    gpu.render(&float_target(4, 4, [0.0; 4]), &[draw]).unwrap()
}

#[test]
fn nearest_sampling_returns_the_texels() {
    let Some(gpu) = gpu::for_tests() else { return };
    let image = render_textured(gpu, texture_4x4(false), "fs");
    for y in 0..4 {
        for x in 0..4 {
            assert_eq!(image.get(x, y), Some(texel(x, y)), "pixel ({x}, {y})");
        }
    }
}

#[test]
fn mip_level_one_is_the_box_filtered_texels() {
    let Some(gpu) = gpu::for_tests() else { return };
    let image = render_textured(gpu, texture_4x4(true), "fs_level1");
    for y in 0..4 {
        for x in 0..4 {
            let (bx, by) = (x / 2 * 2, y / 2 * 2);
            let block = [texel(bx, by), texel(bx + 1, by), texel(bx, by + 1), texel(bx + 1, by + 1)];
            let mean: [f32; 4] = std::array::from_fn(|c| block.iter().map(|t| t[c]).sum::<f32>() / 4.0);
            assert_eq!(image.get(x, y), Some(mean), "pixel ({x}, {y})");
        }
    }
}

#[test]
fn volume_texture_samples_the_right_slice() {
    let Some(gpu) = gpu::for_tests() else { return };
    let m = module(
        "
        @group(1) @binding(0) var tex: texture_3d<f32>;
        @group(1) @binding(1) var smp: sampler;
        struct V { @builtin(position) pos: vec4f, @location(0) uvw: vec3f }
        @vertex fn vs(@location(0) p: vec2f, @location(1) uvw: vec3f) -> V { return V(vec4f(p, 0.5, 1.0), uvw); }
        @fragment fn fs(v: V) -> @location(0) vec4f { return textureSample(tex, smp, v.uvw); }",
    );
    let texels: Vec<[f32; 4]> =
        (0..8).map(|i| [(i % 2) as f32, (i / 2 % 2) as f32, (i / 4) as f32, 1.0]).collect();
    let texture = TextureData {
        dimension: TextureDimension::D3,
        size: [2, 2, 2],
        texels,
        filter: Filter::Nearest,
        address: Address::Repeat,
        mipmaps: false,
    };
    let uvw = [0.0, 1.0, 0.75, 1.0, 1.0, 0.75, 1.0, 0.0, 0.75, 0.0, 0.0, 0.75];
    let attributes = [attribute(0, 2, &QUAD), attribute(1, 3, &uvw)];
    let draw = Draw {
        module: &m,
        fingerprint: None,
        vertex_entry: "vs",
        fragment_entry: "fs",
        uniforms: &[],
        textures: std::slice::from_ref(&texture),
        samplers: true,
        attributes: &attributes,
        indices: &QUAD_INDICES,
        blend: Blend::Replace,
    };
    let image = gpu.render(&float_target(2, 2, [0.0; 4]), &[draw]).unwrap();
    assert_eq!(
        image.pixels,
        [[0.0, 0.0, 1.0, 1.0], [1.0, 0.0, 1.0, 1.0], [0.0, 1.0, 1.0, 1.0], [1.0, 1.0, 1.0, 1.0]]
    );
}

#[test]
fn bad_draws_are_errors_and_the_device_survives() {
    let Some(gpu) = gpu::for_tests() else { return };
    let m = module(COLOURED);
    let cover = flat(&[-1.0, -1.0, 0.5, 3.0, -1.0, 0.5, -1.0, 3.0, 0.5], [1.0; 4]);
    let target = float_target(2, 2, [0.0; 4]);
    let out_of_range = gpu.render(&target, &[flat_draw(&m, &cover, &[0, 1, 3], Blend::Replace)]);
    assert!(matches!(out_of_range, Err(GpuError::InvalidInput(_))), "{out_of_range:?}");
    let partial = gpu.render(&target, &[flat_draw(&m, &cover, &[0, 1], Blend::Replace)]);
    assert!(matches!(partial, Err(GpuError::InvalidInput(_))), "{partial:?}");
    let empty = gpu.render(&float_target(0, 2, [0.0; 4]), &[]);
    assert!(matches!(empty, Err(GpuError::InvalidInput(_))), "{empty:?}");
    let mut wrong_entry = flat_draw(&m, &cover, &[0, 1, 2], Blend::Replace);
    wrong_entry.fragment_entry = "missing";
    assert!(matches!(gpu.render(&target, &[wrong_entry]), Err(GpuError::Wgpu(_))));
    // The shader reads a texture that the draw does not provide.
    let textured = module(TEXTURED);
    let uv = [attribute(0, 2, &QUAD), attribute(1, 2, &QUAD_UV)];
    let mut no_texture = flat_draw(&textured, &uv, &QUAD_INDICES, Blend::Replace);
    no_texture.vertex_entry = "vs";
    match gpu.render(&target, &[no_texture]) {
        Err(e @ GpuError::Wgpu(_)) => eprintln!("{e}"),
        other => panic!("expected a wgpu error, got {other:?}"),
    }
    let mut short = texture_4x4(false);
    short.texels.pop();
    no_texture.textures = std::slice::from_ref(&short);
    let result = gpu.render(&target, &[no_texture]);
    assert!(matches!(result, Err(GpuError::InvalidInput(_))), "{result:?}");
    let image = gpu.render(&target, &[flat_draw(&m, &cover, &[0, 1, 2], Blend::Replace)]).unwrap();
    assert_eq!(image.pixels, [[1.0; 4]; 4]);
}
