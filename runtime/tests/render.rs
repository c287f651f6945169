//! Example scenes rendered on the GPU and by the CPU reference, compared with OSL's image
//! thresholds on rgba32float images. Needs a GPU adapter (lavapipe in CI) unless PATINA_GPU=off.

use patina_runtime::image::{Image, Thresholds, compare};
use patina_runtime::render::{self, Backend};
use patina_runtime::scene::Scene;

fn scene(name: &str, width: u32, height: u32) -> Scene {
    let path = format!("{}/../examples/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let mut scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    scene.output.width = width;
    scene.output.height = height;
    scene
}

/// Renders a scene on both backends and checks OSL's default thresholds; returns both images.
fn both(name: &str, width: u32, height: u32) -> Option<(Image, Image)> {
    both_within(name, width, height, Thresholds::default())
}

/// As [`both`], with the scene's own thresholds.
fn both_within(name: &str, width: u32, height: u32, t: Thresholds) -> Option<(Image, Image)> {
    let gpu = patina_runtime::gpu::for_tests()?;
    let s = scene(name, width, height);
    let prepared = render::prepare(&s).unwrap_or_else(|e| panic!("{name}: {e}"));
    let cpu_image = render::render(&prepared, Backend::Cpu, None).unwrap_or_else(|e| panic!("{name}: {e}"));
    let gpu_image =
        render::render(&prepared, Backend::Gpu, Some(&gpu)).unwrap_or_else(|e| panic!("{name}: {e}"));
    let c = compare(&cpu_image, &gpu_image, &t).unwrap();
    assert!(c.passes(&t), "{name}: GPU and CPU images differ: {c:?}");
    Some((cpu_image, gpu_image))
}

/// The fraction of pixels that differ from the background.
fn covered(image: &Image, background: [f32; 4]) -> f64 {
    let n =
        image.pixels.iter().filter(|p| p.iter().zip(background).any(|(a, b)| (a - b).abs() > 1e-3)).count();
    n as f64 / image.pixels.len() as f64
}

#[test]
fn plastic_sphere_agrees() {
    let Some((cpu, _)) = both("plastic", 96, 72) else { return };
    // A unit sphere 4 units away with a 40° field of view covers about a quarter of the frame.
    let f = covered(&cpu, [0.05, 0.05, 0.08, 1.0]);
    assert!((0.15..0.35).contains(&f), "coverage {f}");
    // Lit from the upper left (the point light): brighter there than lower right.
    let at = |x: u32, y: u32| cpu.pixels[(y * cpu.width + x) as usize][0];
    assert!(at(40, 28) > at(56, 44), "{} vs {}", at(40, 28), at(56, 44));
}

#[test]
fn brick_wall_agrees() {
    // The box filter's width comes from screen derivatives: analytic on the CPU, differences
    // across the 2x2 pixel quad on the GPU. Where the mortar's edge falls inside a pixel the two
    // widths give filtered values a little apart, so a few pixels may differ by up to 0.05.
    let t = Thresholds { hard_fail: 0.05, ..Thresholds::default() };
    both_within("bricks", 96, 72, t);
}

#[test]
fn shiny_torus_agrees() {
    both("shiny", 96, 72);
}

#[test]
fn stanford_flame_agrees() {
    both("flame", 48, 72);
}

#[test]
fn textures_agree() {
    // Texel fetches and the shared bilinear/trilinear filter: identical arithmetic on both. A
    // sample within rounding of a silhouette may be covered by one rasterizer and not the other
    // (seen: one pixel of 6912), so single pixels may differ by a lot; the failing fraction stays
    // OSL's.
    let t = Thresholds { hard_fail: 0.25, ..Thresholds::default() };
    let Some((cpu, _)) = both_within("textured", 96, 72, t) else { return };
    let f = covered(&cpu, [0.1, 0.1, 0.12, 1.0]);
    assert!(f > 0.2, "coverage {f}");
}

#[test]
fn displacement_agrees() {
    // ripples.sl moves P along N and recomputes N with calculatenormal (derivatives of the
    // displaced P): bump mapping at each fragment, on both backends. Its normals come from
    // screen derivatives, so the brick scene's allowance applies.
    let t = Thresholds { hard_fail: 0.05, ..Thresholds::default() };
    both_within("ripples", 96, 72, t);
}

/// Counts what a render reports.
#[derive(Default)]
struct Counted {
    starts: std::sync::Mutex<Vec<(u64, render::Unit)>>,
    done: std::sync::atomic::AtomicU64,
}

impl render::Progress for Counted {
    fn start(&self, total: u64, unit: render::Unit) {
        self.starts.lock().unwrap().push((total, unit));
    }
    fn advance(&self, done: u64) {
        self.done.fetch_add(done, std::sync::atomic::Ordering::Relaxed);
    }
}

#[test]
fn the_cpu_renderer_reports_exactly_the_fragments_it_shades() {
    // The total comes from a dry run of the rasterizer before shading; the batches shaded must add
    // up to it exactly, and every covered pixel was shaded at least once.
    let s = scene("textured", 64, 48);
    let prepared = render::prepare(&s).unwrap();
    let progress = Counted::default();
    let image = render::render_with_progress(&prepared, Backend::Cpu, None, &progress).unwrap();
    let starts = progress.starts.lock().unwrap().clone();
    assert_eq!(starts.len(), 1, "{starts:?}");
    let (total, unit) = starts[0];
    assert_eq!(unit, render::Unit::Fragments);
    assert_eq!(progress.done.load(std::sync::atomic::Ordering::Relaxed), total);
    let covered_pixels = (covered(&image, [0.1, 0.1, 0.12, 1.0]) * f64::from(64 * 48)).round() as u64;
    assert!(total >= covered_pixels && covered_pixels > 0, "{total} fragments, {covered_pixels} covered");
}
