//! The real vertex → fragment path: shaders whose values cross stages (host values in the uniform
//! block, vertex values as varyings, flat integers, derivative seeds) rendered on the GPU and by
//! the CPU reference must agree closely — both interpolate the same vertex values at the same
//! sample positions, so only f32 rounding separates them.

use patina_runtime::image::{Image, Thresholds, compare};
use patina_runtime::render::{self, Backend};
use patina_runtime::scene::Scene;

/// A plane filling most of a 48x48 image, shaded by `shader` (the file's only surface).
fn render_both(name: &str, shader: &str, params: &str) -> Option<(Image, Image)> {
    let gpu = patina_runtime::gpu::for_tests()?;
    let dir = std::env::temp_dir().join(format!("patina-stages-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("s.sl"), shader).unwrap();
    let scene = format!(
        "[output]\nwidth = 48\nheight = 48\n[camera]\nfrom = [0.0, 0.0, -3.0]\nto = [0.0, 0.0, 0.0]\n\
         up = [0.0, 1.0, 0.0]\nfov = 40\n[[light]]\nshader = \"{lights}\"\nname = \"pointlight\"\n\
         params = {{ intensity = 8.0, from = [1.0, 2.0, -3.0] }}\n[[object]]\nmesh = \"plane\"\ndetail = 4\n\
         shader = \"s.sl\"\nparams = {{ {params} }}\ntransform = [{{ rotate = {{ angle = 30, axis = [0.0, 1.0, 0.0] }} }}]\n",
        lights = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders/lights.sl"),
    );
    let scene = Scene::parse(&scene, dir.join("s.toml"), &dir).unwrap_or_else(|e| panic!("{e}"));
    let prepared = render::prepare(&scene).unwrap_or_else(|e| panic!("{e}"));
    let cpu = render::render(&prepared, Backend::Cpu, None).unwrap();
    let gpu = render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap();
    Some((cpu, gpu))
}

fn assert_close(name: &str, cpu: &Image, gpu: &Image, t: Thresholds) {
    let c = compare(cpu, gpu, &t).unwrap();
    assert!(c.passes(&t), "{name}: {c:?}");
    let covered = cpu.pixels.iter().filter(|p| p[3] > 0.5 && (p[0] > 0.01 || p[1] > 0.01)).count();
    assert!(covered > cpu.pixels.len() / 3, "{name}: the plane covers only {covered} pixels");
}

/// Interpolation and f32 rounding only: no derivatives involved.
const CLOSE: Thresholds = Thresholds { fail: 1e-4, hard_fail: 1e-3, max_failing_fraction: 0.01 };

#[test]
fn stanford_values_cross_as_uniforms_and_varyings() {
    let shader = "surface shader float4 crossing(vertex float4 uv, primitive group float k) {
        primitive group float k2 = k * k + 0.25;
        vertex float a = uv[0] * k2;
        fragment float b = sin(a * 6.0) * 0.5 + 0.5;
        fragment int band = int(floor(uv[1] * 4.0));
        float c = select(band % 2 == 0, b, 1.0 - b);
        return {c, uv[1], k2 * 0.5, 1};
    }";
    let Some((cpu, gpu)) = render_both("crossing", shader, "k = 0.75") else { return };
    assert_close("crossing", &cpu, &gpu, CLOSE);
    // k2 = 0.8125 reaches the blue channel through the uniform block on both.
    let centre = cpu.pixels[(24 * 48 + 24) as usize];
    assert!((centre[2] - 0.40625).abs() < 1e-6, "{centre:?}");
}

#[test]
fn renderman_uniform_work_and_lights_cross_stages() {
    let shader = "surface lit(float Kd = 0.8; float freq = 3) {
        uniform float f2 = freq * 2;
        normal Nf = faceforward(normalize(N), I);
        float stripes = mod(floor(s * f2) + floor(t * f2), 2);
        Ci = Kd * diffuse(Nf) * mix(color(1, 0.5, 0.2), color(0.2, 0.4, 1), stripes);
        Oi = 1;
    }";
    let Some((cpu, gpu)) = render_both("lit", shader, "freq = 2.0") else { return };
    // Stripe edges fall where floor() flips; a sample within rounding of an edge may differ.
    let t = Thresholds { fail: 1e-3, hard_fail: 1.0, max_failing_fraction: 0.02 };
    assert_close("lit", &cpu, &gpu, t);
}

#[test]
fn derivative_seeds_agree_within_quad_differences() {
    // filterwidth: analytic derivatives on the CPU, 2x2-quad differences on the GPU. On a plane
    // under perspective s and t are not linear in screen space, so the two differ by the
    // second-order term only: about a percent of the width (measured: at most 0.014 here, on
    // values around 1.3).
    let shader = "surface fw(float scale = 40) {
        Ci = color(filterwidth(s) * scale, filterwidth(t) * scale, 0.25);
        Oi = 1;
    }";
    let Some((cpu, gpu)) = render_both("fw", shader, "") else { return };
    let t = Thresholds { fail: 0.02, hard_fail: 0.05, max_failing_fraction: 0.02 };
    assert_close("fw", &cpu, &gpu, t);
}

#[test]
fn depth_is_normalized_by_the_cameras_clipping_distances() {
    let shader = "surface d() { Ci = depth(P); Oi = 1; }";
    let Some((cpu, gpu)) = render_both("depth", shader, "") else { return };
    assert_close("depth", &cpu, &gpu, CLOSE);
    // The plane's centre is 3 units away; the scene's clipping range is the default 0.1 to 100.
    let centre = cpu.pixels[(24 * 48 + 24) as usize][0];
    let expected = (3.0 - 0.1) / (100.0 - 0.1);
    assert!((centre - expected).abs() < 2e-3, "{centre} vs {expected}");
}

#[test]
fn window_positions_agree() {
    // xyz_screen(): pixel centres, depth and 1/w, from the GPU's fragment position and from the
    // CPU rasterizer.
    let shader = "surface shader float4 w() {
        float4 p = xyz_screen();
        return {p[0] / 48, p[1] / 48, p[3] + p[2] * 0.01, 1};
    }";
    let Some((cpu, gpu)) = render_both("screen", shader, "") else { return };
    assert_close("screen", &cpu, &gpu, CLOSE);
    // Pixel (24, 24)'s centre is (24.5, 24.5); the plane is about 3 units away there, so 1/w is
    // about 1/3 and the depth about 100 * 2.9 / (99.9 * 3) = 0.968.
    let centre = cpu.pixels[(24 * 48 + 24) as usize];
    assert_eq!([centre[0], centre[1]], [24.5 / 48.0, 24.5 / 48.0]);
    assert!((centre[2] - (1.0 / 3.0 + 0.00968)).abs() < 0.005, "{centre:?}");
}

#[test]
fn random_is_the_same_noise_on_both() {
    // random() hashes the pixel (x + 4096 y) and the call site on both renderers.
    let shader = "surface r() { Ci = color(random(), random(), 0.5); Oi = 1; }";
    let Some((cpu, gpu)) = render_both("random", shader, "") else { return };
    assert_close("random", &cpu, &gpu, CLOSE);
    // And it is noise: neighbouring pixels differ.
    let row = &cpu.pixels[24 * 48..25 * 48];
    assert!(row.windows(2).filter(|w| w[0][0] != w[1][0]).count() > 15);
}
