//! Shared by the gallery tests (`runtime/tests/gallery*.rs`): a scene of `examples/scenes/` at a test
//! size with parameter overrides, rendered on both backends and compared with the image thresholds.

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::CpuProgram;
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::image::{Comparison, Image, Thresholds, compare};
use patina_runtime::render::{self, Backend, Lowering};
use patina_runtime::scene::{ParamValue, Scene};

/// Loads `examples/scenes/NAME.toml`, resized to `width × height` with supersampling off (a test
/// image is small; the scene file keeps its gallery settings).
pub fn scene(name: &str, width: u32, height: u32) -> Scene {
    let path = format!("{}/../examples/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let mut scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    scene.output.width = width;
    scene.output.height = height;
    scene.output.supersample = 1;
    scene
}

/// Sets surface parameter `name` to `value` on the objects numbered in `objects` (file order); the
/// render reports a parameter their shader does not declare.
pub fn set(scene: &mut Scene, objects: &[usize], name: &str, value: f64) {
    for &i in objects {
        scene.objects[i].surface.params.insert(name.to_string(), ParamValue::Number(value));
    }
}

/// Both backends' images of one scene and how they compare.
pub struct Renders {
    /// The CPU reference's image.
    pub cpu: Image,
    /// The GPU's image.
    pub gpu: Image,
    /// GPU against CPU.
    pub comparison: Comparison,
}

/// Renders `scene` on the CPU reference and on the GPU, asserts that neither image has a NaN or
/// infinity and that they agree within `t`; `None` when `PATINA_GPU=off` (then nothing is
/// checked: the GPU is the point). Fails loudly when no adapter can be opened. The GPU draws the
/// scene in both lowerings, and each must meet `t`; the returned image is the exact lowering's.
pub fn both(label: &str, scene: &Scene, t: Thresholds) -> Option<Renders> {
    let device = patina_runtime::gpu::for_tests()?;
    let prepared = render::prepare(scene).unwrap_or_else(|e| panic!("{label}: {e}"));
    let cpu = render::render(&prepared, Backend::Cpu, None).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert_finite(&format!("{label} (CPU)"), &cpu);
    let gpu =
        render::render(&prepared, Backend::Gpu, Some(device)).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert_finite(&format!("{label} (GPU)"), &gpu);
    let comparison = compare(&cpu, &gpu, &t).unwrap();
    assert!(comparison.passes(&t), "{label}: GPU and CPU images differ: {comparison:?}");
    let options = render::Options { lowering: Lowering::Fast, ..render::Options::default() };
    let fast = render::prepare_with(scene, options).unwrap_or_else(|e| panic!("{label} (fast): {e}"));
    let fast =
        render::render(&fast, Backend::Gpu, Some(device)).unwrap_or_else(|e| panic!("{label} (fast): {e}"));
    assert_finite(&format!("{label} (GPU, fast lowering)"), &fast);
    let fast_comparison = compare(&cpu, &fast, &t).unwrap();
    assert!(
        fast_comparison.passes(&t),
        "{label}: the GPU's fast lowering and the CPU differ: {fast_comparison:?}"
    );
    Some(Renders { cpu, gpu, comparison })
}

/// Renders `scene` on the CPU reference only (for checks against closed forms that do not need
/// the GPU, and for sweeps too slow to repeat on both backends).
pub fn cpu(label: &str, scene: &Scene) -> Image {
    let prepared = render::prepare(scene).unwrap_or_else(|e| panic!("{label}: {e}"));
    let image = render::render(&prepared, Backend::Cpu, None).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert_finite(label, &image);
    image
}

/// Asserts that every channel of every pixel is finite.
pub fn assert_finite(label: &str, image: &Image) {
    if let Some((i, p)) = image.pixels.iter().enumerate().find(|(_, p)| p.iter().any(|c| !c.is_finite())) {
        panic!("{label}: pixel ({}, {}) is {p:?}", i as u32 % image.width, i as u32 / image.width);
    }
}

/// The fraction of pixels that differ from `background` by more than 1e-3 in some channel.
pub fn covered(image: &Image, background: [f32; 4]) -> f64 {
    let n =
        image.pixels.iter().filter(|p| p.iter().zip(background).any(|(a, b)| (a - b).abs() > 1e-3)).count();
    n as f64 / image.pixels.len() as f64
}

/// The pixel at column `x`, row `y` (row 0 at the top).
pub fn at(image: &Image, x: u32, y: u32) -> [f32; 4] {
    image.pixels[(y * image.width + x) as usize]
}

/// The source of `examples/shaders/NAME.sl`.
pub fn shader_source(name: &str) -> String {
    let path = format!("{}/../examples/shaders/{name}.sl", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// Checks `source` (which must have no diagnostics) and compiles its shader named `name` for the
/// interpreter: a probe shader that follows a scene's shader in the same source and calls its
/// functions (`super::program` takes the first shader).
pub fn program_named(source: &str, name: &str) -> super::Program {
    let checked = patina_compiler::check_source("gallery_probe.sl", source, &MemoryLoader::default());
    assert!(checked.diagnostics.is_empty(), "{:#?}", checked.diagnostics);
    let shader = Prepared::new(
        checked.program.shaders.into_iter().find(|s| s.name == name).expect("the probe shader"),
    );
    let cpu = CpuProgram::compile(&shader, &Binding::default())
        .unwrap_or_else(|d| panic!("{}: {}", d.code, d.message));
    super::Program { shader, cpu }
}
