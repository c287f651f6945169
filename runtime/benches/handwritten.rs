//! Generated WGSL against hand-written WGSL (issue 21), on the wgpu device: the same shading,
//! full screen, rendered in one run. Patina's side is the renderer's own program for a scene whose
//! plane fills the view (vertex and fragment stages, uniforms, everything `patina render` draws);
//! the hand-written side is WGSL written as a graphics programmer would (built-ins, the table in
//! a module variable, no copies), drawn as a full-screen quad. Each time is the median wall time
//! of a render (drawing and reading the image back) less that of the same render with a trivial
//! shader on the same side and at the same size, which leaves the shading; the table gives
//! generated / hand-written. The renders of a shader (each side's and each side's trivial one)
//! take turns over 31 rounds, so that the load of the shared machine falls on all alike; and that
//! is done on [`DEVICES`] devices in turn, each compiling its own pipelines, since lavapipe's code
//! for one WGSL runs at speeds up to ~15% apart from one compile to the next. The table gives the
//! median ratio over the devices and each device's.
//!
//! The shaders: fBm (6 octaves of Perlin's improved noise, the standard library's `fbm`), plastic
//! under four point lights (examples/shaders/plastic.sl and lights.sl's pointlight; by hand, the
//! lights' positions and colours in a uniform buffer as the renderer has them), Hart's wood with
//! APST's filter (examples/shaders/hart_solid.sl's solid_wood, aa 1) and Perlin & Hoffert's noisy
//! sphere marched as examples/shaders/hypertexture.sl does. The hand-written WGSL is in
//! support/handwritten/. The two lit surfaces, plastic and wood, are shaded by hand as a mesh's
//! surface shader must be: at the position and normal its vertex stage interpolates, the normal
//! faced towards the eye by the geometric one (RenderMan's `faceforward(normalize(N), I)`), not at
//! the plane's known constant normal, which would measure the scene rather than the shading.
//! `HANDWRITTEN_ONLY=<entry>` (`fbm_bench`, `plastic4`, `wood`, `hypertexture`) measures one. Before anything is timed, both sides' images of each shader are read back
//! and compared: a port that computes a different picture would measure different work.

use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};

use patina_runtime::gpu::{Attribute, Blend, Draw, Gpu, Target, TargetFormat};
use patina_runtime::image::{Image, Thresholds, compare};
use patina_runtime::render::{self, Backend, Lowering, Prepared};
use patina_runtime::scene::Scene;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Pixels along each side of the image, unless a shader's cost calls for fewer.
const SIZE: u32 = 1024;

/// The devices each shader is timed on, each with its own pipelines (`PATINA_BENCH_DEVICES`
/// overrides it).
const DEVICES: usize = 5;

/// The plane's scale in the scenes: the `plane` mesh is 2 wide, and at distance 2 with a 90° field
/// of view the view is 4 wide, so the plane reaches past the view's edges and every pixel is
/// shaded. The hand-written side maps its quad to the part of (s, t) the view shows.
const PLANE_SCALE: f32 = 4.2;
const PLANE_WIDTH: f32 = 2.0;
const VIEW_WIDTH: f32 = 4.0;

/// The Patina surfaces of the bench file: the trivial baseline and fBm, each over the plane's
/// (s, t).
const SURFACES: &str = "#include <fractal.sl>
surface baseline() { Ci = color(s, t, 0); }
surface fbm_bench() {
    float v = fbm(point(s * 16, t * 16, 0.5), 1, 2, 6);
    Ci = color(v, v, v);
}
";

/// The four point lights of the plastic scene, in world space (the camera's space is the world
/// moved 2 along z), and their intensity.
const LIGHTS: [[f32; 3]; 4] = [[-1.5, 1.5, -1.0], [1.5, 1.5, -1.0], [-1.5, -1.5, -1.0], [1.5, -1.5, -1.0]];
const INTENSITY: f32 = 2.0;

/// The wood's solid-texture scale: rings magnified at the centre and one or two pixels apart at
/// the corners, so that many pixels' filter boxes hold a ring's edge.
const WOOD_SCALE: f32 = 24.0;
/// Where the wood's distant light comes from (hart_wood.toml's), towards the origin.
const WOOD_LIGHT: [f32; 3] = [-1.0, 2.0, -2.0];
/// Where the hypertexture's distant light comes from (hypertexture.toml's), towards the origin.
const HT_LIGHT: [f32; 3] = [-1.0, 1.4, -1.6];

/// The hand-written module: the standard library's permutation table and noise scale (the same
/// numbers the generated code reads) and the scenes' constants, then the shading.
fn handwritten_module() -> naga::Module {
    let noise = patina_compiler::stdlib::source("noise.sl").expect("the stdlib has noise.sl");
    let start = noise.find("#define PATINA_PERLIN_PERMUTATION {").expect("the permutation table");
    let body = &noise[start..];
    let table = &body[body.find('{').unwrap() + 1..body.find('}').unwrap()];
    let numbers: Vec<&str> = table.split([',', '\\', ' ', '\n']).filter(|s| !s.trim().is_empty()).collect();
    assert_eq!(numbers.len(), 256, "the permutation table has 256 entries");
    let scale = noise
        .lines()
        .find_map(|line| line.strip_prefix("#define PATINA_SNOISE_SCALE "))
        .expect("noise.sl defines PATINA_SNOISE_SCALE")
        .trim();
    // Directions to the lights, as the light shaders' L are, normalized as diffuse() does.
    let towards = |[x, y, z]: [f32; 3]| {
        let n = (x * x + y * y + z * z).sqrt();
        format!("vec3f({:?}, {:?}, {:?})", x / n, y / n, z / n)
    };
    // PERM is a `var<private>`, not a `const`: a `const` array indexed at run time is
    // materialized at every access by naga's SPIR-V (measured: a 512 x 512 render took 15 s on
    // lavapipe).
    let text = format!(
        "var<private> PERM: array<i32, 256> = array<i32, 256>({});\n\
         const SNOISE_SCALE: f32 = {scale};\n\
         const PLANE_SPAN: f32 = {:?};\n\
         const WOOD_SCALE: f32 = {WOOD_SCALE:?};\n\
         const WOOD_LIGHT = {};\n\
         const HT_LIGHT = {};\n\
         {}{}{}{}",
        numbers.join(", "),
        VIEW_WIDTH / (PLANE_WIDTH * PLANE_SCALE),
        towards(WOOD_LIGHT),
        towards(HT_LIGHT),
        include_str!("support/handwritten/noise.wgsl"),
        include_str!("support/handwritten/plastic.wgsl"),
        include_str!("support/handwritten/wood.wgsl"),
        include_str!("support/handwritten/hypertexture.wgsl"),
    );
    naga::front::wgsl::parse_str(&text).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&text)))
}

/// A scene's `[[light]]` of examples/shaders/lights.sl: `name` with `params`.
fn light(name: &str, params: &str) -> String {
    let examples = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders");
    format!("[[light]]\nshader = \"{examples}/lights.sl\"\nname = \"{name}\"\nparams = {{ {params} }}\n")
}

/// A distant light from `from` towards the origin, of intensity 1.
fn distant_light([x, y, z]: [f32; 3]) -> String {
    light("distantlight", &format!("intensity = 1.0, from = [{x:?}, {y:?}, {z:?}], to = [0.0, 0.0, 0.0]"))
}

/// The renderer's program for `surface` of `file` (the bench file or one of examples/shaders)
/// with `params`, on a plane that fills a `size` × `size` view, under `lights`.
fn patina_scene(
    size: u32,
    file: &str,
    surface: &str,
    params: &str,
    lights: &str,
    lowering: Lowering,
) -> Prepared {
    let dir = std::env::temp_dir().join(format!("patina-handwritten-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bench.sl"), SURFACES).unwrap();
    let examples = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders");
    let file = if file == "bench.sl" { file.to_string() } else { format!("{examples}/{file}") };
    let text = format!(
        "[output]\nwidth = {size}\nheight = {size}\n[camera]\nfrom = [0, 0, -2]\nto = [0, 0, 0]\nfov = 90\n\
         {lights}[[object]]\nmesh = \"plane\"\ndetail = 1\nshader = \"{file}\"\nname = \"{surface}\"\n\
         params = {{ {params} }}\ntransform = [{{ scale = [{PLANE_SCALE:?}, {PLANE_SCALE:?}, 1.0] }}]\n"
    );
    let scene = Scene::parse(&text, dir.join("bench.toml"), &dir).unwrap_or_else(|e| panic!("{e}"));
    let options = render::Options { lowering, ..render::Options::default() };
    render::prepare_with(&scene, options).unwrap_or_else(|e| panic!("{surface}: {e}"))
}

/// One shader measured: its label, its size, the renderer's program in each lowering and the
/// hand-written entry.
struct Shader {
    label: &'static str,
    size: u32,
    exact: Prepared,
    fast: Prepared,
    entry: &'static str,
}

/// Compares the two sides' images of `label` and panics unless they agree: no NaN, an RMS
/// channel difference below 1e-3 and at most 0.1% of pixels off by more than 0.01 (filtered ring
/// edges and rounding may move a few pixels; a wrong port moves many). Returns the figures; on a
/// disagreement the two images are written to the temporary directory.
fn check_agreement(label: &str, generated: &Image, handwritten: &Image) -> String {
    let thresholds = Thresholds { fail: 0.01, hard_fail: f32::MAX, max_failing_fraction: 1e-3 };
    let c = compare(generated, handwritten, &thresholds).expect("both sides render the same size");
    let figures = format!(
        "| {label} | {:.1e} | {:.1e} | {} of {} |",
        c.rms_error, c.max_error, c.failing_pixels, c.pixels
    );
    if !(c.passes(&thresholds) && c.rms_error < 1e-3) {
        let dir = std::env::temp_dir();
        let name =
            |side: &str| dir.join(format!("handwritten-{}-{side}.png", label.replace([' ', ',', '\''], "_")));
        generated.write_png(name("generated")).unwrap();
        handwritten.write_png(name("hand-written")).unwrap();
        panic!("the generated and hand-written {label} differ ({c:?}); images in {}", dir.display());
    }
    figures
}

fn bench(c: &mut Criterion) {
    let Ok(gpu) = Gpu::new() else {
        println!("no GPU adapter: nothing to measure");
        return;
    };
    let module = handwritten_module();
    let quad = [Attribute {
        location: 0,
        components: 3,
        data: vec![-1., -1., 0., 1., -1., 0., 1., 1., 0., -1., 1., 0.],
    }];
    let indices = [0, 1, 2, 0, 2, 3];
    // The uniforms of `plastic4`: the lights' camera-space positions, then their colours.
    let uniforms: Vec<u8> = LIGHTS
        .iter()
        .map(|[x, y, z]| [*x, *y, z + 2.0, 1.0])
        .chain(LIGHTS.iter().map(|_| [INTENSITY; 4]))
        .flatten()
        .flat_map(f32::to_le_bytes)
        .collect();
    let handwritten = |gpu: &Gpu, entry: &str, size: u32| {
        let target = Target { width: size, height: size, format: TargetFormat::Rgba32Float, clear: [0.0; 4] };
        let draw = Draw {
            module: &module,
            fingerprint: Some(0x4a4e_5752_4954_5445),
            vertex_entry: if matches!(entry, "plastic4" | "wood") { "vs_surface" } else { "vs_main" },
            fragment_entry: entry,
            uniforms: if entry == "plastic4" { &uniforms } else { &[] },
            textures: &[],
            samplers: false,
            attributes: &quad,
            indices: &indices,
            blend: Blend::Replace,
        };
        std::hint::black_box(gpu.render(&target, &[draw]).expect("the hand-written module renders"))
    };
    let generated = |gpu: &Gpu, prepared: &Prepared| {
        std::hint::black_box(render::render(prepared, Backend::Gpu, Some(gpu)).expect("the scene renders"))
    };
    let point_lights: String = LIGHTS
        .iter()
        .map(|[x, y, z]| {
            light("pointlight", &format!("intensity = {INTENSITY:?}, from = [{x:?}, {y:?}, {z:?}]"))
        })
        .collect();
    let wood_lights = light("ambientlight", "intensity = 1.0") + &distant_light(WOOD_LIGHT);
    // The renderer's program for a scene, in both lowerings.
    let shader = |label, size, (file, surface, params, lights): (&str, &str, &str, &str), entry| Shader {
        label,
        size,
        exact: patina_scene(size, file, surface, params, lights, Lowering::Exact),
        fast: patina_scene(size, file, surface, params, lights, Lowering::Fast),
        entry,
    };
    let wood_params = format!("aa = 1, scale = {WOOD_SCALE:?}");
    let hypertexture_light = distant_light(HT_LIGHT);
    let shaders = [
        shader("fBm, 6 octaves of improved noise", SIZE, ("bench.sl", "fbm_bench", "", ""), "fbm_bench"),
        shader("plastic, 4 point lights", SIZE, ("plastic.sl", "plastic", "", &point_lights), "plastic4"),
        shader(
            "Hart's wood, APST filter",
            SIZE,
            ("hart_solid.sl", "solid_wood", &wood_params, &wood_lights),
            "wood",
        ),
        // Half the size: at 1024 x 1024 one generated render took 2.2 s on the shared 2-core
        // machine, and 31 of each side would dominate the run.
        shader(
            "hypertexture, noisy sphere, 64 steps",
            SIZE / 2,
            ("hypertexture.sl", "hypertexture", "variant = 0, steps = 64", &hypertexture_light),
            "hypertexture",
        ),
    ];
    // `HANDWRITTEN_ONLY=wood` (a hand-written entry's name) measures that shader alone.
    let only = std::env::var("HANDWRITTEN_ONLY").ok();
    let shaders: Vec<Shader> =
        shaders.into_iter().filter(|s| only.as_deref().is_none_or(|entry| s.entry == entry)).collect();
    // The trivial shader at each size measured.
    let mut sizes: Vec<u32> = shaders.iter().map(|s| s.size).collect();
    sizes.sort_unstable();
    sizes.dedup();
    let baselines: Vec<(u32, Prepared)> = sizes
        .iter()
        .map(|&size| (size, patina_scene(size, "bench.sl", "baseline", "", "", Lowering::Exact)))
        .collect();
    // Pipeline creation and the driver's compile, once each, outside the measurement; the images
    // of these first renders are the ones compared.
    for (size, scene) in &baselines {
        handwritten(&gpu, "baseline", *size);
        generated(&gpu, scene);
    }
    let agreement: Vec<String> = shaders
        .iter()
        .flat_map(|s| {
            let hand = handwritten(&gpu, s.entry, s.size);
            [
                check_agreement(&format!("{} (exact)", s.label), &generated(&gpu, &s.exact), &hand),
                check_agreement(&format!("{} (fast)", s.label), &generated(&gpu, &s.fast), &hand),
            ]
        })
        .collect();
    let mut group = c.benchmark_group("handwritten");
    group.sample_size(10);
    for s in &shaders {
        group
            .bench_function(format!("generated (fast) {}", s.label), |b| b.iter(|| generated(&gpu, &s.fast)));
        group.bench_function(format!("hand-written {}", s.label), |b| {
            b.iter(|| handwritten(&gpu, s.entry, s.size))
        });
    }
    group.finish();
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    println!("\nAgreement of the two sides' images (channel differences):\n");
    println!("| shader | RMS | max | pixels off by > 0.01 |");
    println!("|---|---|---|---|");
    agreement.iter().for_each(|line| println!("{line}"));
    println!(
        "\nOn {}; the shading's time is a render's less the trivial shader's at the same size\n",
        gpu.adapter_description()
    );
    println!(
        "| shader | pixels | exact ms | fast ms | hand-written ms | exact / hand-written (median; each device) | fast / hand-written (median; each device) |"
    );
    println!("|---|---|---|---|---|---|---|");
    let devices =
        std::env::var("PATINA_BENCH_DEVICES").ok().and_then(|v| v.parse().ok()).unwrap_or(DEVICES).max(1);
    let mut trivial = Vec::new();
    for s in &shaders {
        let base = &baselines.iter().find(|b| b.0 == s.size).unwrap().1;
        // One set of timings per device: each device compiles its own pipelines, and the same
        // WGSL compiled twice by lavapipe runs up to ~15% apart (code placement), far more than
        // the load's drift within a set. The figures are medians over the devices.
        let sets: Vec<Timings> = (0..devices)
            .map(|_| {
                let gpu = Gpu::new().expect("a second device on the adapter that gave the first");
                let mut renders: [&mut dyn FnMut(); 5] = [
                    &mut || drop(generated(&gpu, base)),
                    &mut || drop(handwritten(&gpu, "baseline", s.size)),
                    &mut || drop(generated(&gpu, &s.exact)),
                    &mut || drop(generated(&gpu, &s.fast)),
                    &mut || drop(handwritten(&gpu, s.entry, s.size)),
                ];
                // Pipeline creation, outside the timings.
                renders.iter_mut().for_each(|render| render());
                let [generated_base, hand_base, exact, fast, hand] = interleaved_medians(renders, 31);
                Timings {
                    generated_base,
                    hand_base,
                    exact: exact.saturating_sub(generated_base),
                    fast: fast.saturating_sub(generated_base),
                    hand: hand.saturating_sub(hand_base),
                }
            })
            .collect();
        let ratios_of = |of: fn(&Timings) -> Duration| -> Vec<f64> {
            sets.iter().map(|t| of(t).as_secs_f64() / t.hand.as_secs_f64().max(1e-9)).collect()
        };
        let exact_ratios = ratios_of(|t| t.exact);
        let fast_ratios = ratios_of(|t| t.fast);
        let time = |of: fn(&Timings) -> Duration| ms(median_of(sets.iter().map(of).collect()));
        println!(
            "| {} | {} × {} | {:.2} | {:.2} | {:.2} | {} | {} |",
            s.label,
            s.size,
            s.size,
            time(|t| t.exact),
            time(|t| t.fast),
            time(|t| t.hand),
            ratios(&exact_ratios),
            ratios(&fast_ratios)
        );
        let (generated_base, hand_base) = (time(|t| t.generated_base), time(|t| t.hand_base));
        trivial
            .push(format!("{}: generated {generated_base:.2} ms, hand-written {hand_base:.2} ms", s.label));
    }
    println!("\n(renders with the trivial shader, measured alongside each: {})", trivial.join("; "));
}

/// One device's medians: the two trivial renders, and the shading times (each render less its
/// side's trivial one).
struct Timings {
    generated_base: Duration,
    hand_base: Duration,
    exact: Duration,
    fast: Duration,
    hand: Duration,
}

/// The median of `ratios` in bold, then each of them.
fn ratios(ratios: &[f64]) -> String {
    let each: Vec<String> = ratios.iter().map(|r| format!("{r:.2}")).collect();
    format!("**{:.2}**; {}", median_of(ratios.to_vec()), each.join(", "))
}

/// The median of `values` (the upper one of an even count).
fn median_of<T: PartialOrd + Copy>(mut values: Vec<T>) -> T {
    values.sort_by(|a, b| a.partial_cmp(b).expect("no NaN"));
    values[values.len() / 2]
}

/// The median wall time of each of `fs` over `runs` rounds that call each once in turn: a change
/// in the load of the machine (shared, on lavapipe, with whatever else runs) then falls on all of
/// them alike instead of on whichever was being timed.
fn interleaved_medians<const N: usize>(mut fs: [&mut dyn FnMut(); N], runs: usize) -> [Duration; N] {
    let mut times = vec![Vec::with_capacity(runs); N];
    for _ in 0..runs {
        for (f, t) in fs.iter_mut().zip(&mut times) {
            let start = Instant::now();
            f();
            t.push(start.elapsed());
        }
    }
    std::array::from_fn(|i| median_of(std::mem::take(&mut times[i])))
}

criterion_group!(benches, bench);
criterion_main!(benches);
