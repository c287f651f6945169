//! The device's limits and failures as errors with context (docs/limits.md): a render target over
//! the texture limit, a texture over it, an unbounded loop on the GPU, a lost device.

use patina_compiler::backend::MAX_LOOP_ITERATIONS;
use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, EvalError, Evaluator};
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::gpu::{
    Address, Blend, Draw, Filter, GpuError, Target, TargetFormat, TextureData, TextureDimension,
};
use patina_runtime::kernel::run_kernel;
use patina_runtime::render::{self, Backend, RenderError};
use patina_runtime::scene::Scene;

/// A plastic sphere under one light, `width` pixels wide at supersample 16.
fn supersampled_scene(width: u32) -> Scene {
    let shaders = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders");
    let text = format!(
        r#"
[output]
width = {width}
height = 8
supersample = 16

[camera]
from = [0, 0, -5]
to = [0, 0, 0]

[[light]]
shader = "{shaders}/lights.sl"
name = "pointlight"

[[object]]
mesh = "sphere"
shader = "{shaders}/plastic.sl"
"#
    );
    Scene::parse(&text, "wide.toml", ".").unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_supersampled_target_over_the_texture_limit_is_an_error_naming_the_image() {
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let max = gpu.limits().max_texture_dimension_2d;
    let width = max / 16 + 1;
    let prepared = render::prepare(&supersampled_scene(width)).unwrap_or_else(|e| panic!("{e}"));
    let error = render::render(&prepared, Backend::Gpu, Some(gpu)).expect_err("over the limit");
    let RenderError::Gpu(message) = &error else { panic!("{error:?}") };
    let target = width * 16;
    assert_eq!(
        message,
        &format!(
            "rendering the {width}x8 image at supersample 16: the render target of {target}x128 pixels: \
             {target} is over the device's limit of {max} (max_texture_dimension_2d)"
        )
    );
    // One pixel narrower fits, and renders.
    let prepared = render::prepare(&supersampled_scene(max / 16)).unwrap_or_else(|e| panic!("{e}"));
    let image = render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((image.width, image.height), (max / 16, 8));
}

/// A draw of one triangle reading `texture` (the shader is never reached: the checks come first).
fn textured_draw<'a>(module: &'a naga::Module, texture: &'a [TextureData]) -> Draw<'a> {
    Draw {
        module,
        fingerprint: None,
        vertex_entry: "vs",
        fragment_entry: "fs",
        uniforms: &[],
        textures: texture,
        samplers: false,
        attributes: &[],
        indices: &[0, 1, 2],
        blend: Blend::Replace,
    }
}

#[test]
fn a_texture_or_uniform_block_over_the_device_limits_is_refused_before_it_is_created() {
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let limits = gpu.limits();
    let module = naga::Module::default();
    let target = Target { width: 4, height: 4, format: TargetFormat::Rgba32Float, clear: [0.0; 4] };
    let wide = limits.max_texture_dimension_2d + 1;
    let texture = TextureData {
        dimension: TextureDimension::D2,
        size: [wide, 1, 1],
        texels: vec![[0.5; 4]; wide as usize],
        filter: Filter::Linear,
        address: Address::Repeat,
        mipmaps: false,
    };
    let textures = [texture];
    match gpu.render(&target, &[textured_draw(&module, &textures)]) {
        Err(GpuError::Limit { what, asked, limit, name }) => {
            assert_eq!(what, format!("draw 0: texture 0 of {wide}x1x1 texels (D2)"));
            assert_eq!(
                (asked, limit, name),
                (u64::from(wide), u64::from(wide - 1), "max_texture_dimension_2d")
            );
        }
        other => panic!("expected a limit error, got {other:?}"),
    }
    // A uniform block one 16-byte row over the limit (only where the limit is small enough to
    // allocate; lavapipe's is 64 KiB).
    let max = limits.max_uniform_buffer_binding_size;
    if max <= 1 << 26 {
        let uniforms = vec![0u8; max as usize + 16];
        let mut draw = textured_draw(&module, &[]);
        draw.uniforms = &uniforms;
        let error = gpu.render(&target, &[draw]).expect_err("over the limit");
        assert_eq!(
            error.to_string(),
            format!(
                "draw 0: the uniform block of the shader's parameters, in bytes: {} is over the device's limit of {max} (max_uniform_buffer_binding_size)",
                max + 16
            )
        );
    }
}

/// The loop never ends by itself: `x` grows until the iteration cap stops it.
const UNBOUNDED: &str = "surface t(float start = 1) {
    float x = start;
    while (x > 0) {
        x += 1;
    }
    Ci = x;
}
";

#[test]
fn an_unbounded_loop_stops_at_the_cap_on_the_gpu_and_is_e0702_in_the_interpreter() {
    let checked = patina_compiler::check_source("loop.sl", UNBOUNDED, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    let shader = &Prepared::new(checked.program.shaders[0].clone());
    // The interpreter, with its default budget (the cap): the loop's error, with its position.
    let program = CpuProgram::compile(shader, &Binding::default()).expect("compiles");
    let mut eval = Evaluator::<f32>::new(&program);
    match eval.eval_points(1, &[], &["Ci"]) {
        Err(EvalError::IterationBudget { budget, .. }) => assert_eq!(budget, MAX_LOOP_ITERATIONS),
        other => panic!("expected the iteration budget, got {other:?}"),
    }
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    // On the GPU: the body runs MAX_LOOP_ITERATIONS times, from 1 and from 100, then the loop
    // is left; every invocation finishes.
    let start = std::time::Instant::now();
    let out = run_kernel(gpu, shader, &[], 2, &[("start", &[1.0, 100.0])], &["Ci"])
        .unwrap_or_else(|e| panic!("{e}"));
    let cap = MAX_LOOP_ITERATIONS as f64;
    assert_eq!(out[0], [1.0 + cap, 1.0 + cap, 1.0 + cap, 100.0 + cap, 100.0 + cap, 100.0 + cap]);
    eprintln!("two invocations of {MAX_LOOP_ITERATIONS} iterations: {:?}", start.elapsed());
}

#[test]
fn a_lost_device_is_an_error_not_a_panic() {
    // A device of its own: losing it must not disturb the other tests.
    let Some(gpu) = patina_runtime::gpu::own_for_tests() else { return };
    gpu.lose_device_for_tests();
    let target = Target { width: 4, height: 4, format: TargetFormat::Rgba32Float, clear: [0.0; 4] };
    let module = naga::Module::default();
    match gpu.render(&target, &[textured_draw(&module, &[])]) {
        Err(GpuError::DeviceLost(why)) => assert!(why.contains("Destroyed"), "{why}"),
        other => panic!("expected a lost device, got {other:?}"),
    }
    let error = gpu.compute(&module, "main", &[], &[], 4, 1).expect_err("lost");
    assert!(error.to_string().starts_with("the GPU device was lost"), "{error}");
}

#[test]
fn a_pipeline_the_device_refuses_is_an_error_naming_its_draw() {
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let target = Target { width: 4, height: 4, format: TargetFormat::Rgba32Float, clear: [0.0; 4] };
    // A module without the entry points the draws name: wgpu refuses the second draw's pipeline.
    let empty = naga::Module::default();
    let ok = naga::front::wgsl::parse_str(
        "@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f { return vec4f(0.0, 0.0, 0.0, 1.0); }
         @fragment fn fs() -> @location(0) vec4f { return vec4f(1.0); }",
    )
    .expect("parses");
    let draws = [textured_draw(&ok, &[]), textured_draw(&empty, &[])];
    match gpu.render(&target, &draws) {
        Err(GpuError::Wgpu(why)) => assert!(why.starts_with("draw 1: "), "{why}"),
        other => panic!("expected wgpu's error for draw 1, got {other:?}"),
    }
}
