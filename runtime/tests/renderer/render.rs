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
        render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap_or_else(|e| panic!("{name}: {e}"));
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

#[test]
fn the_cpu_renderer_gives_the_same_bits_on_one_thread_and_on_many() {
    // The steam cup: five objects drawn over each other, three lights, the steam's cube blended
    // over the cup with both of its faces at many pixels, and `random()` jittering the march, so
    // the order of blending and the point index both show if threads change them.
    let s = scene("steam_cup", 48, 48);
    let prepared = render::prepare(&s).unwrap();
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let progress = Counted::default();
        let image = pool.install(|| render::render_with_progress(&prepared, Backend::Cpu, None, &progress));
        let total = progress.starts.lock().unwrap()[0].0;
        assert_eq!(progress.done.load(std::sync::atomic::Ordering::Relaxed), total, "{threads} threads");
        image.unwrap()
    };
    let one = on(1);
    let background = s.output.background;
    assert!(covered(&one, background) > 0.2, "the scene should cover the frame");
    for threads in [2, 5] {
        let many = on(threads);
        let differ =
            one.pixels.iter().zip(&many.pixels).filter(|(a, b)| a.map(f32::to_bits) != b.map(f32::to_bits));
        assert_eq!(differ.count(), 0, "{threads} threads against one");
    }
}
/// A scene from text whose object uses the shader `source`, written as NAME.sl beside it in a
/// scratch directory.
fn written_scene(name: &str, source: &str, scene: &str) -> Scene {
    let dir = std::env::temp_dir().join(format!("patina-render-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join(format!("{name}.sl")), source).unwrap();
    Scene::parse(scene, dir.join(format!("{name}.toml")), &dir).unwrap_or_else(|e| panic!("{e}"))
}

/// The CPU reference's picture of `scene`, checked finite, and the GPU's compared with it within
/// `t` (no NaN) when there is a GPU.
fn cpu_checked_against_gpu(
    label: &str,
    scene: &Scene,
    gpu: Option<&patina_runtime::gpu::Gpu>,
    t: Thresholds,
) -> Image {
    let prepared = render::prepare(scene).unwrap_or_else(|e| panic!("{label}: {e}"));
    let cpu = render::render(&prepared, Backend::Cpu, None).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert!(cpu.pixels.iter().flatten().all(|x| x.is_finite()), "{label}: not finite");
    if let Some(gpu) = gpu {
        let image =
            render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap_or_else(|e| panic!("{label}: {e}"));
        let c = compare(&cpu, &image, &t).unwrap();
        assert!(c.passes(&t) && c.nan_pixels == 0, "{label}: GPU and CPU images differ: {c:?}");
    }
    cpu
}

#[test]
fn stanford_matrices_and_object_space_inputs_agree_with_the_geometry() {
    // `__modelview * Pobj` is the eye-space P, `__invmodelview3 * __objnormal` lies along N, and
    // `__invmodelview * P` gives Pobj back: each difference, scaled up, must vanish on both
    // backends, and Pobj itself (blue) must follow the object's height.
    let shader = "surface shader float4 matrices() {\n\
           float4 q = __modelview * Pobj;\n\
           float3 n = normalize(__invmodelview3 * __objnormal);\n\
           float4 back = __invmodelview * P;\n\
           float3 m = __modelview3 * {Pobj[0], Pobj[1], Pobj[2]};\n\
           float3 shift = {__modelview[0][3], __modelview[1][3], __modelview[2][3]};\n\
           float e = length({q[0] - P[0], q[1] - P[1], q[2] - P[2]}) + length({back[0] - Pobj[0], back[1] - Pobj[1], back[2] - Pobj[2]});\n\
           float f = length(m + shift - {P[0], P[1], P[2]});\n\
           return {0.5 + 100 * e, 0.5 + 100 * (1 - dot(n, N)) + 100 * f, 0.5 + 0.5 * Pobj[1], 1};\n\
         }\n";
    let text = "[output]\nwidth = 40\nheight = 40\n\
                [camera]\nfrom = [1.0, 1.5, -4.0]\nto = [0.0, 0.0, 0.0]\nfov = 40\n\
                [[object]]\nmesh = \"sphere\"\ndetail = 24\nshader = \"matrices.sl\"\n\
                transform = [{ translate = [0.3, 0.1, 0.2] }, { rotate = { angle = 35, axis = [1.0, 0.0, 1.0] } }, \
                { scale = [1.1, 0.9, 1.0] }]\n";
    let s = written_scene("matrices", shader, text);
    let prepared = render::prepare(&s).unwrap_or_else(|e| panic!("{e}"));
    let mut images = vec![render::render(&prepared, Backend::Cpu, None).unwrap()];
    if let Some(gpu) = patina_runtime::gpu::for_tests() {
        images.push(render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap());
    }
    for (backend, image) in ["CPU", "GPU"].iter().zip(&images) {
        let mut heights = Vec::new();
        for (i, p) in image.pixels.iter().enumerate() {
            if (p[0] - 0.0).abs() < 1e-6 && p[3] == 1.0 && p[1] == 0.0 {
                continue; // background
            }
            assert!((p[0] - 0.5).abs() < 2e-3 && (p[1] - 0.5).abs() < 2e-3, "{backend}: pixel {i}: {p:?}");
            heights.push((i as u32 / image.width, p[2]));
        }
        assert!(heights.len() > 300, "the sphere covers {} pixels", heights.len());
        // Object y runs from -1 to 1: blue spans most of [0, 1].
        let lo = heights.iter().map(|h| h.1).fold(1.0f32, f32::min);
        let hi = heights.iter().map(|h| h.1).fold(0.0f32, f32::max);
        assert!(lo < 0.2 && hi > 0.8, "{backend}: Pobj's height runs {lo} to {hi}");
    }
    if images.len() == 2 {
        let t = Thresholds::default();
        let c = compare(&images[0], &images[1], &t).unwrap();
        assert!(c.passes(&t), "{c:?}");
    }
}

#[test]
fn library_noise_under_a_varying_condition_renders_alike() {
    // vnoise's loop counters are `constant` inside the function, which a varying `if` around the
    // call does not change; and a function's `uint s` must not share the private variable of the
    // predefined `s` on the GPU (it did: the module failed validation).
    let shader = "#include <lattice.sl>\n\
                  uint triple(uint v) { return v * 3u; }\n\
                  float hashed(float x) { uint s = 5u; uint a = triple(uint(x) + s); return float(a & 255u) / 255; }\n\
                  surface gated() {\n\
                    float v = 0;\n\
                    if (s > 0.5) v = vnoise(P * 4);\n\
                    Ci = color(v, hashed(40 * t), 0.5 * s);\n\
                    Oi = 1;\n\
                  }\n";
    let text = "[output]\nwidth = 32\nheight = 32\n\
                [camera]\nfrom = [0.0, 0.0, -2.0]\nto = [0.0, 0.0, 0.0]\nfov = 53.13\n\
                [[object]]\nmesh = \"plane\"\nshader = \"gated.sl\"\n";
    let s = written_scene("gated", shader, text);
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let prepared = render::prepare(&s).unwrap_or_else(|e| panic!("{e}"));
    let cpu = render::render(&prepared, Backend::Cpu, None).unwrap();
    let gpu = render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap_or_else(|e| panic!("{e}"));
    let t = Thresholds::default();
    let c = compare(&cpu, &gpu, &t).unwrap();
    assert!(c.passes(&t), "{c:?}");
    // Where s < 0.5 (the left half) the noise is not taken; on the right it varies.
    let red = |x: u32, y: u32| cpu.pixels[(y * cpu.width + x) as usize][0];
    assert!((0..32).all(|y| (0..14).all(|x| red(x, y) == 0.0)));
    let right: Vec<f32> =
        (0..32).flat_map(|y| (18..32).map(move |x| (x, y))).map(|(x, y)| red(x, y)).collect();
    let spread =
        right.iter().copied().fold(f32::MIN, f32::max) - right.iter().copied().fold(f32::MAX, f32::min);
    assert!(spread > 0.2, "the noise varies on the right: spread {spread}");
}

#[test]
fn pipelines_are_kept_per_device_and_reused_with_fresh_uniforms() {
    // Rendering again makes no new pipeline and draws the same picture; another value of a
    // parameter still reaches the shader (a kept pipeline gets the draw's own uniforms, or a
    // specialized module gets a pipeline of its own), and the GPU still agrees with the CPU.
    // A device of its own: the shared one keeps the pipelines of every test in the process.
    let Some(gpu) = &patina_runtime::gpu::own_for_tests() else { return };
    let mut s = scene("soft_sphere", 24, 24);
    let prepared = render::prepare(&s).unwrap();
    let first = render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap();
    let kept = gpu.kept_pipelines();
    assert_eq!(kept, 1, "one object, one pipeline");
    let again = render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap();
    assert_eq!(gpu.kept_pipelines(), kept);
    assert_eq!(first.pixels, again.pixels);

    s.objects[0].surface.params.insert("kappa".into(), patina_runtime::scene::ParamValue::Number(12.0));
    let denser = render::prepare(&s).unwrap();
    let gpu_image = render::render(&denser, Backend::Gpu, Some(gpu)).unwrap();
    let cpu_image = render::render(&denser, Backend::Cpu, None).unwrap();
    assert_ne!(gpu_image.pixels, first.pixels, "kappa 12 must draw a denser sphere");
    let t = Thresholds::default();
    let c = compare(&cpu_image, &gpu_image, &t).unwrap();
    assert!(c.passes(&t), "{c:?}");
}

/// Issue 23: `constant` variables declared, then stored again (in a loop too), inside a varying
/// branch (no longer E0605) draw the same on both backends: 7 on the right half, 0 on the left.
#[test]
fn constants_living_inside_a_varying_branch_render_alike() {
    let shader = "surface branch() {\n\
                    float v = 0;\n\
                    if (s > 0.5) {\n\
                      constant float k = 2;\n\
                      k = k * 3;\n\
                      constant float j = 0;\n\
                      for (j = 0; j < 2; j += 1) k += j;\n\
                      v = k / 7;\n\
                    }\n\
                    Ci = v;\n\
                    Oi = 1;\n\
                  }\n";
    let text = "[output]\nwidth = 32\nheight = 32\n\
                [camera]\nfrom = [0.0, 0.0, -2.0]\nto = [0.0, 0.0, 0.0]\nfov = 53.13\n\
                [[object]]\nmesh = \"plane\"\nshader = \"branch.sl\"\n";
    let s = written_scene("branch", shader, text);
    let gpu = patina_runtime::gpu::for_tests();
    let cpu = cpu_checked_against_gpu("branch", &s, gpu, Thresholds::default());
    let red = |x: u32, y: u32| cpu.pixels[(y * cpu.width + x) as usize][0];
    assert!((0..32).all(|y| (0..14).all(|x| red(x, y) == 0.0)));
    assert!((0..32).all(|y| (18..32).all(|x| red(x, y) == 1.0)));
}

/// Issue 23: objects whose shaders compiled to the same module share one pipeline within a render
/// (each object made its own before, and only the next render reused one), and both still draw.
#[test]
fn objects_sharing_a_module_share_one_pipeline_in_a_render() {
    // A device of its own: the shared one counts the pipelines of every test in the process.
    let Some(gpu) = patina_runtime::gpu::own_for_tests() else { return };
    let s = written_scene(
        "shared",
        "surface shared(color tint = 1) { Ci = tint; Oi = 1; }\n",
        "[output]\nwidth = 32\nheight = 16\nbackground = [0, 0, 0, 1]\n\
         [camera]\nfrom = [0, 0, -6]\nto = [0, 0, 0]\n\
         [[object]]\nmesh = \"sphere\"\nshader = \"shared.sl\"\n\
         transform = [{ translate = [-1.5, 0, 0] }]\n\
         [[object]]\nmesh = \"sphere\"\nshader = \"shared.sl\"\n\
         transform = [{ translate = [1.5, 0, 0] }]\n",
    );
    let prepared = render::prepare(&s).unwrap();
    let image = render::render(&prepared, Backend::Gpu, Some(&gpu)).unwrap();
    assert_eq!((gpu.pipelines_made(), gpu.kept_pipelines()), (1, 1), "two objects, one module, one pipeline");
    // Both spheres are drawn: white left and right of the centre, the background between.
    let at = |x: u32| image.pixels[(8 * image.width + x) as usize];
    assert_eq!((at(8), at(16), at(24)), ([1.0; 4], [0.0, 0.0, 0.0, 1.0], [1.0; 4]));
    render::render(&prepared, Backend::Gpu, Some(&gpu)).unwrap();
    assert_eq!(gpu.pipelines_made(), 1, "the next render reuses it");
}

/// Two lights and a surface that reads them through message passing (`lightsource`, light
/// categories, a light's output parameter), bound together by the renderer.
const MESSAGES: &str = r#"
light keylight(float intensity = 1; point from = point(0, 3, -3); float __nondiffuse = 0;
               string __category = "key"; output varying float tint = 0) {
    illuminate(from) {
        Cl = intensity * color(1, 1, 1) / (L . L);
        tint = 0.25 + 0.5 * step(0, ycomp(Ps));
    }
}

light rimlight(float intensity = 1; point from = point(0, -3, -3)) {
    illuminate(from) {
        Cl = intensity * color(1, 1, 1) / (L . L);
    }
}

surface messages(float usetint = 0; float only = 0) {
    color c = 0;
    normal Nf = normalize(N);
    if (only == 1) {
        illuminance("key", P, Nf, PI / 2) {
            c += Cl * max(0, normalize(L) . Nf);
        }
    } else if (only == 2) {
        illuminance("-key", P, Nf, PI / 2) {
            c += Cl * max(0, normalize(L) . Nf);
        }
    } else {
        illuminance(P, Nf, PI / 2) {
            float nd = 0;
            float t = 1;
            // The rim light has no `__nondiffuse`: 0, and nd keeps its value.
            lightsource("__nondiffuse", nd);
            // A colour `intensity` exists in neither light: nothing is written.
            color wrong = 1;
            float typed = lightsource("intensity", wrong);
            if (usetint == 1) {
                lightsource("tint", t);
            }
            c += Cl * (1 - nd) * t * max(0, normalize(L) . Nf) * wrong * (1 - typed);
        }
    }
    Ci = c;
}
"#;

#[test]
fn surfaces_read_their_lights_by_message_passing_on_both_backends() {
    let scene = |surface: &str, key: &str| {
        format!(
            "[output]\nwidth = 40\nheight = 40\n[camera]\nfrom = [0, 0, -5]\nto = [0, 0, 0]\nfov = 40\n\
             [[light]]\nshader = \"messages.sl\"\nname = \"keylight\"\nparams = {{ intensity = 20.0{key} }}\n\
             [[light]]\nshader = \"messages.sl\"\nname = \"rimlight\"\nparams = {{ intensity = 20.0 }}\n\
             [[object]]\nmesh = \"sphere\"\ndetail = 32\nshader = \"messages.sl\"\nname = \"messages\"\n\
             params = {{ {surface} }}\n"
        )
    };
    let gpu = patina_runtime::gpu::for_tests();
    let render = |label: &str, surface: &str, key: &str| -> Image {
        let s = written_scene("messages", MESSAGES, &scene(surface, key));
        cpu_checked_against_gpu(label, &s, gpu, Thresholds::default())
    };
    let key = render("the key light's category", "only = 1", "");
    let rim = render("not the key light's category", "only = 2", "");
    let both = render("both lights", "usetint = 0", "");
    let lit = |image: &Image| image.pixels.iter().filter(|p| p[0] > 0.01).count();
    assert!(
        lit(&key) > 50 && lit(&rim) > 50 && key.pixels != rim.pixels,
        "the categories select different lights"
    );
    for ((k, r), b) in key.pixels.iter().zip(&rim.pixels).zip(&both.pixels) {
        assert!((k[0] + r[0] - b[0]).abs() < 1e-5, "both lights are the sum of the categories");
    }
    // `__nondiffuse = 1` on the key light: the loop leaves it out, as if only the rim lit.
    let nondiffuse = render("__nondiffuse", "usetint = 0", ", __nondiffuse = 1.0");
    assert_eq!(nondiffuse.pixels, rim.pixels);
    // The key light's output parameter, computed per point: 0.75 above the camera's axis, 0.25 below.
    let tinted = render("the key light's output", "usetint = 1", "");
    let mut seen = [false; 2];
    for ((k, r), t) in key.pixels.iter().zip(&rim.pixels).zip(&tinted.pixels) {
        if k[0] > 0.01 && k[0] < 0.99 && t[0] < 0.99 {
            let tint = (t[0] - r[0]) / k[0];
            let near = |x: f32| (tint - x).abs() < 2e-3;
            assert!(near(0.25) || near(0.75), "tint {tint}");
            seen[usize::from(near(0.75))] = true;
        }
    }
    assert_eq!(seen, [true, true], "both sides of the sphere are lit by the key");
}

/// Issue 24: a string parameter passed on to a function as a space name ("a string used as a
/// value" on both backends before): the function's parameter reads the caller's string, as if
/// the name were written in the call.
#[test]
fn a_string_parameter_passed_on_as_a_space_name_renders_on_both_backends() {
    let source = "float along(string space; point p) {
            point q = transform(space, p);
            return xcomp(q) * 0.2 + 0.5;
        }
        surface passed(string myspace = \"world\") { Ci = along(myspace, P); }
        surface written() { Ci = along(\"world\", P); }";
    let scene = |name: &str| {
        format!(
            "[output]\nwidth = 24\nheight = 24\n[camera]\nfrom = [0, 0, -5]\nto = [0, 0, 0]\nfov = 40\n\
             [[object]]\nmesh = \"sphere\"\ndetail = 16\nshader = \"spaces.sl\"\nname = \"{name}\"\n"
        )
    };
    let gpu = patina_runtime::gpu::for_tests();
    let render = |name: &str| -> Image {
        let s = written_scene("spaces", source, &scene(name));
        cpu_checked_against_gpu(name, &s, gpu, Thresholds::default())
    };
    let (passed, written) = (render("passed"), render("written"));
    assert_eq!(passed.pixels, written.pixels);
    // World x varies across the sphere: the space was applied, not dropped.
    let covered: Vec<f32> = passed.pixels.iter().filter(|p| p[3] > 0.0 && p[0] > 0.0).map(|p| p[0]).collect();
    let (lo, hi) = covered.iter().fold((f32::MAX, f32::MIN), |(a, b), x| (a.min(*x), b.max(*x)));
    assert!(covered.len() > 50 && hi - lo > 0.2, "{} pixels, {lo} to {hi}", covered.len());
}

/// A light and an atmosphere that read the surface they are bound with (`surface("name", v)`).
const SURFACE_MESSAGES: &str = r#"
light reader(float intensity = 1; point from = point(0, 3, -3)) {
    illuminate(from) {
        float kd = 1;
        color tint = 1;
        surface("Kd", kd);
        // `plain` has a float `tint`: not the colour asked for, so tint stays 1.
        float has = surface("tint", tint);
        Cl = intensity * kd * tint / (L . L) * (has + 1) * 0.5;
    }
}

volume glowing(float amount = 1) {
    float glow = 0;
    surface("glow", glow);
    Ci += amount * glow * color(0, 0.5, 0);
}

surface lit(float Kd = 0.5; color tint = color(1, 0.5, 0.25); output varying float glow = 0) {
    normal Nf = normalize(N);
    color c = 0;
    illuminance(P, Nf, PI / 2) { c += Cl * max(0, normalize(L) . Nf); }
    glow = s;
    Ci = c;
}

surface plain(float Kd = 0.5; float tint = 1) {
    normal Nf = normalize(N);
    color c = 0;
    illuminance(P, Nf, PI / 2) { c += Cl * max(0, normalize(L) . Nf); }
    Ci = c * tint;
}
"#;

#[test]
fn lights_and_atmospheres_read_their_surface_by_message_passing_on_both_backends() {
    let scene = |surface: &str, params: &str, atmosphere: bool| {
        let atmosphere = if atmosphere {
            "atmosphere = { shader = \"surface_messages.sl\", name = \"glowing\" }\n"
        } else {
            ""
        };
        format!(
            "[output]\nwidth = 40\nheight = 40\n[camera]\nfrom = [0, 0, -5]\nto = [0, 0, 0]\nfov = 40\n\
             [[light]]\nshader = \"surface_messages.sl\"\nname = \"reader\"\nparams = {{ intensity = 20.0 }}\n\
             [[object]]\nmesh = \"sphere\"\ndetail = 32\nshader = \"surface_messages.sl\"\nname = \"{surface}\"\n\
             params = {{ {params} }}\n{atmosphere}"
        )
    };
    let gpu = patina_runtime::gpu::for_tests();
    let render = |label: &str, surface: &str, params: &str, atmosphere: bool| -> Image {
        let s = written_scene("surface_messages", SURFACE_MESSAGES, &scene(surface, params, atmosphere));
        cpu_checked_against_gpu(label, &s, gpu, Thresholds::default())
    };
    let half = render("Kd 0.5", "lit", "Kd = 0.5", false);
    let full = render("Kd 1", "lit", "Kd = 1.0", false);
    let plain = render("a float tint", "plain", "Kd = 1.0", false);
    let lit: Vec<usize> = (0..half.pixels.len()).filter(|&i| full.pixels[i][0] > 0.02).collect();
    assert!(lit.len() > 100, "{} lit pixels", lit.len());
    for &i in &lit {
        let (h, f, p) = (half.pixels[i], full.pixels[i], plain.pixels[i]);
        // The light scales by the surface's Kd, a power of two apart: exactly.
        assert_eq!(f[0], 2.0 * h[0], "pixel {i}");
        // `lit`'s colour tint reaches the light; `plain`'s float one does not (has = 0: half).
        assert!(
            (f[1] - 0.5 * f[0]).abs() <= 1e-6 * f[0] && (f[2] - 0.25 * f[0]).abs() <= 1e-6 * f[0],
            "{f:?}"
        );
        assert!(p[0] == p[1] && p[1] == p[2] && (p[0] - 0.5 * f[0]).abs() <= 1e-6 * f[0], "{p:?} {f:?}");
    }
    // The atmosphere reads the surface's output `glow` (s) as the body left it: green rises by
    // s / 2 where the sphere is, and the other channels stay.
    let glowing = render("an atmosphere reading glow", "lit", "Kd = 1.0", true);
    let mut rises = Vec::new();
    for (g, f) in glowing.pixels.iter().zip(&full.pixels) {
        if f[3] > 0.0 {
            assert_eq!((g[0], g[2]), (f[0], f[2]));
            rises.push(g[1] - f[1]);
        }
    }
    let (lo, hi) = rises.iter().fold((f32::MAX, f32::MIN), |(a, b), x| (a.min(*x), b.max(*x)));
    assert!(lo >= -1e-6 && hi > 0.3 && hi <= 0.5 + 1e-6, "green rises from {lo} to {hi}");
    // Over `plain`, which has no `glow`, the atmosphere adds nothing.
    let over_plain = render("an atmosphere over plain", "plain", "Kd = 1.0", true);
    assert_eq!(over_plain.pixels, plain.pixels);
}

/// The falloff light of W. R. Mark's chapter (`examples/shaders/aniso.sl`: a Stanford-style light
/// shader returns only its colour) and a Stanford surface summing its lights with `integrate`.
const FALLOFF: &str = r#"
light shader float4
falloff_light(float4 lightcolor, float constant_term, float linear_term)
{
    return lightcolor * (1.0 / (linear_term * Sdist + constant_term));
}

surface shader float4
lit(primitive group float4 base)
{
    perlight float4 c = Cl * max(dot(N, L), 0);
    float4 r = base * integrate(c);
    r[3] = 1;
    return r;
}
"#;

/// Issue 23: a Stanford-style light shader could not be bound (the WGSL backend refused it, and
/// the renderer compiles the module for either backend). Placed by the scene's `position`, the
/// falloff light lights a Stanford surface (`L` normalized, `Cl` its float4) and RenderMan's matte
/// (`L` towards the light, `Cl` its rgb) alike on both backends: at the sphere's point nearest
/// the light, where N.L = 1, each is the surface colour times the light's colour / (linear Sdist
/// + constant); facing away it is black; and beside a RenderMan point light the two add up.
#[test]
fn stanford_lights_light_both_styles_of_surface_on_both_backends() {
    const SIZE: u32 = 48;
    let position = glam::Vec3::new(2.0, 2.0, -2.5);
    let falloff = "[[light]]\nshader = \"falloff.sl\"\nname = \"falloff_light\"\n\
                   params = { lightcolor = [1.0, 0.9, 0.8, 1.0], constant_term = 1.0, linear_term = 0.5 }\n\
                   position = [2.0, 2.0, -2.5]\n";
    let point = "[[light]]\nshader = \"<shaders.sl>\"\nname = \"pointlight\"\n\
                 params = { intensity = 6.0, from = [-2.0, 1.0, -3.0] }\n";
    let surfaces = [
        (
            "a Stanford surface",
            "shader = \"falloff.sl\"\nname = \"lit\"\nparams = { base = [0.8, 0.5, 0.3, 1.0] }\n",
        ),
        (
            "RenderMan's matte",
            "shader = \"<shaders.sl>\"\nname = \"matte\"\nparams = { Ka = 0.0 }\ncolor = [0.8, 0.5, 0.3]\n",
        ),
    ];
    let scene = |lights: &str, surface: &str| {
        let text = format!(
            "[output]\nwidth = {SIZE}\nheight = {SIZE}\n\
             [camera]\nfrom = [0.0, 0.0, -3.0]\nto = [0.0, 0.0, 0.0]\nfov = 45\n\
             {lights}[[object]]\nmesh = \"sphere\"\n{surface}"
        );
        written_scene("falloff", FALLOFF, &text)
    };
    // The pixels of two points of the unit sphere facing the camera: the one nearest the light
    // (where N and L are the same direction) and one facing away from it.
    let camera = scene(falloff, surfaces[0].1).camera();
    let raster = camera.camera_to_raster(SIZE, SIZE) * camera.world_to_camera();
    let pixel = |p: glam::Vec3| {
        let r = raster.project_point3(p);
        (r.y as u32 * SIZE + r.x as u32) as usize
    };
    let nearest = position.normalize();
    let (toward, away) = (pixel(nearest), pixel(glam::Vec3::new(-0.5, -0.5, -0.7).normalize()));
    let sdist = position.length() - 1.0;
    let f = 1.0 / (0.5 * sdist + 1.0);
    let expected = [0.8 * f, 0.5 * 0.9 * f, 0.3 * 0.8 * f];
    let gpu = patina_runtime::gpu::for_tests();
    for (style, surface) in surfaces {
        let render = |lights: &str, label: &str| {
            let label = format!("{style} under {label}");
            cpu_checked_against_gpu(&label, &scene(lights, surface), gpu, Thresholds::default())
        };
        let stanford = render(falloff, "the falloff light");
        let got = stanford.pixels[toward];
        for c in 0..3 {
            // The pixel's centre is a little off the nearest point, on a tessellated sphere.
            assert!((got[c] - expected[c]).abs() < 0.01 * expected[c], "{style}: {got:?}, not {expected:?}");
        }
        assert_eq!(stanford.pixels[away][..3], [0.0; 3], "{style}: lit from behind");
        let renderman = render(point, "a point light");
        let both = render(&format!("{falloff}{point}"), "both lights");
        for ((s, r), b) in stanford.pixels.iter().zip(&renderman.pixels).zip(&both.pixels) {
            for c in 0..3 {
                assert!((s[c] + r[c] - b[c]).abs() < 1e-5, "{style}: {s:?} + {r:?} is not {b:?}");
            }
        }
        assert!(renderman.pixels[away][0] > 0.05, "{style}: the point light lights the far side");
    }
}

/// Issue 24: `PI` read by a displacement or a light shader bound to a surface that does not read
/// it was 0 on the GPU (its variable was set only for the surface), so a `threads.sl`-like
/// displacement left a plain sphere there. The constant predefined variables are values in every
/// function of the module now.
#[test]
fn pi_in_a_displacement_and_a_light_is_pi_on_both_backends() {
    let source = "displacement threads(float Km = .1, frequency = 5.0, dampzone = 0.05) {
            float magnitude = sin(PI * 2 * (t * frequency + s)) * Km;
            if (t > (1 - dampzone)) magnitude *= (1.0 - t) / dampzone;
            else if (t < dampzone) magnitude *= t / dampzone;
            P += normalize(N) * magnitude;
            N = calculatenormal(P);
        }
        light round(float intensity = 1; point from = point(-2, 3, -4)) {
            illuminate(from, normalize(point(0, 0, 0) - from), PI / 4) {
                Cl = intensity * color(1, 1, 1) / (L . L) * (PI / PI);
            }
        }
        surface matte() {
            normal Nf = normalize(N);
            color c = 0;
            illuminance(P, Nf, 1.5707963) { c += Cl * max(0, normalize(L) . Nf); }
            Ci = c;
        }";
    let scene = |displaced: bool| {
        let displacement =
            if displaced { "displacement = { shader = \"threads.sl\", name = \"threads\" }\n" } else { "" };
        format!(
            "[output]\nwidth = 48\nheight = 48\n[camera]\nfrom = [0, 0, -5]\nto = [0, 0, 0]\nfov = 40\n\
             [[light]]\nshader = \"threads.sl\"\nname = \"round\"\nparams = {{ intensity = 25.0 }}\n\
             [[object]]\nmesh = \"sphere\"\ndetail = 48\nshader = \"threads.sl\"\nname = \"matte\"\n{displacement}"
        )
    };
    let gpu = patina_runtime::gpu::for_tests();
    let render = |displaced: bool| -> Image {
        let s = written_scene("threads", source, &scene(displaced));
        // Normals from screen derivatives: the displacement scene's allowance.
        let t = Thresholds { hard_fail: 0.05, ..Thresholds::default() };
        cpu_checked_against_gpu(if displaced { "threads" } else { "plain" }, &s, gpu, t)
    };
    let (plain, threaded) = (render(false), render(true));
    let lit = plain.pixels.iter().filter(|p| p[0] > 0.05).count();
    let changed =
        plain.pixels.iter().zip(&threaded.pixels).filter(|(a, b)| (a[0] - b[0]).abs() > 0.05).count();
    assert!(lit > 200 && changed > lit / 4, "{lit} lit pixels, {changed} changed by the threads");
}

/// Issue 24 asked that the CPU rasterizer break ties as the GPU does, so that silhouettes agree
/// exactly. Measured here: with both at 8 sub-pixel bits and the top-left rule, the coverage
/// (alpha over a transparent background) of every pixel is the same on both backends, at one
/// sample per pixel and at 3×3; the colour differences left at silhouettes are shading, not
/// coverage. This keeps it so.
#[test]
fn coverage_is_identical_on_both_backends() {
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    for name in ["plastic", "shiny", "ripples", "shadowed_teapot", "textured", "bricks"] {
        for n in [1, 3] {
            let mut s = scene(name, 120, 90);
            s.output.supersample = n;
            s.output.background = [0.0, 0.0, 0.0, 0.0];
            let prepared = render::prepare(&s).unwrap_or_else(|e| panic!("{name}: {e}"));
            let cpu = render::render(&prepared, Backend::Cpu, None).unwrap();
            let image = render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap();
            let covered = cpu.pixels.iter().filter(|p| p[3] > 0.0).count();
            let differ: Vec<usize> =
                (0..cpu.pixels.len()).filter(|&i| cpu.pixels[i][3] != image.pixels[i][3]).collect();
            assert!(covered > 500, "{name}: {covered} covered pixels");
            assert!(differ.is_empty(), "{name} at {n}x{n}: coverage differs at pixels {differ:?}");
        }
    }
}
