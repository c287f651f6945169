//! Generated WGSL against hand-written WGSL (issue 21), on the wgpu device: the same shading,
//! full screen, rendered in one run. Patina's side is the renderer's own program for a scene whose
//! plane fills the view (vertex and fragment stages, uniforms, everything `patina render` draws);
//! the hand-written side is WGSL written as a graphics programmer would (built-ins, the table in
//! a module variable, no copies), drawn as a full-screen quad. Each time is the median wall time of a render
//! of `SIZE` × `SIZE` pixels (drawing and reading the image back) less that of the same render
//! with a trivial shader on the same side, which leaves the shading; the table gives
//! generated / hand-written.
//!
//! So far fBm (6 octaves of Perlin's improved noise, the standard library's `fbm`) and plastic
//! under four point lights (examples/shaders/plastic.sl and lights.sl's pointlight; by hand, the
//! lights' positions and colours in a uniform buffer as the renderer has them); Hart's wood and a
//! hypertexture march are still to be written by hand.

use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};

#[path = "support/timing.rs"]
mod timing;
use patina_runtime::gpu::{Attribute, Blend, Draw, Gpu, Target, TargetFormat};
use patina_runtime::render::{self, Backend, Prepared};
use patina_runtime::scene::Scene;
use timing::median;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Pixels along each side of the image.
const SIZE: u32 = 1024;

/// The Patina surfaces: the trivial baseline and the shaders measured, each over the plane's
/// (s, t) as the hand-written ones use their (u, v).
const SURFACES: &str = "#include <fractal.sl>
surface baseline() { Ci = color(s, t, 0); }
surface fbm_bench() {
    float v = fbm(point(s * 16, t * 16, 0.5), 1, 2, 6);
    Ci = color(v, v, v);
}
";

/// The hand-written module's shading, after the permutation table: fBm of improved noise, as
/// Perlin's reference (ImprovedNoise.java) and a six-octave loop with halving amplitudes.
const HANDWRITTEN: &str = r#"
struct Varyings {
    @builtin(position) position: vec4f,
    @location(0) uv: vec2f,
};

@vertex
fn vs_main(@location(0) position: vec3f) -> Varyings {
    var out: Varyings;
    out.position = vec4f(position.xy, 0.5, 1.0);
    out.uv = vec2f(position.x * 0.5 + 0.5, 0.5 - position.y * 0.5);
    return out;
}

fn perm(i: i32) -> i32 {
    return PERM[i & 255];
}

fn fade(t: vec3f) -> vec3f {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

fn grad(hash: i32, x: f32, y: f32, z: f32) -> f32 {
    let h = hash & 15;
    let u = select(y, x, h < 8);
    let v = select(select(z, x, h == 12 || h == 14), y, h < 4);
    return select(-u, u, (h & 1) == 0) + select(-v, v, (h & 2) == 0);
}

fn improved_noise(p: vec3f) -> f32 {
    let cell = floor(p);
    let f = p - cell;
    let i = vec3i(cell) & vec3i(255);
    let u = fade(f);
    let a = perm(i.x) + i.y;
    let aa = perm(a) + i.z;
    let ab = perm(a + 1) + i.z;
    let b = perm(i.x + 1) + i.y;
    let ba = perm(b) + i.z;
    let bb = perm(b + 1) + i.z;
    return mix(
        mix(mix(grad(perm(aa), f.x, f.y, f.z), grad(perm(ba), f.x - 1.0, f.y, f.z), u.x),
            mix(grad(perm(ab), f.x, f.y - 1.0, f.z), grad(perm(bb), f.x - 1.0, f.y - 1.0, f.z), u.x), u.y),
        mix(mix(grad(perm(aa + 1), f.x, f.y, f.z - 1.0), grad(perm(ba + 1), f.x - 1.0, f.y, f.z - 1.0), u.x),
            mix(grad(perm(ab + 1), f.x, f.y - 1.0, f.z - 1.0), grad(perm(bb + 1), f.x - 1.0, f.y - 1.0, f.z - 1.0), u.x), u.y),
        u.z);
}

// Plastic (RenderMan's: ambient, diffuse and specular sums) under four point lights whose
// camera-space positions and colours (intensity / distance^2 follows) come from the uniforms.
struct Lights {
    position: array<vec4f, 4>,
    colour: array<vec4f, 4>,
};
@group(0) @binding(0) var<uniform> lights: Lights;

@fragment
fn plastic4(in: Varyings) -> @location(0) vec4f {
    // The plane in the camera's space: z = 2, 4 wide.
    let p = vec3f(in.uv.x * 4.0 - 2.0, 2.0 - in.uv.y * 4.0, 2.0);
    let n = faceForward(vec3f(0.0, 0.0, -1.0), p, vec3f(0.0, 0.0, -1.0));
    let v = -normalize(p);
    let cs = vec3f(1.0);
    var diffuse = vec3f(0.0);
    var specular = vec3f(0.0);
    for (var k = 0; k < 4; k++) {
        let l = lights.position[k].xyz - p;
        let cl = lights.colour[k].xyz / dot(l, l);
        let ln = normalize(l);
        diffuse += cl * max(0.0, dot(ln, n));
        specular += cl * pow(max(0.0, dot(n, normalize(ln + v))), 1.0 / 0.1);
    }
    return vec4f(cs * (0.5 * diffuse) + 0.5 * specular, 1.0);
}

@fragment
fn baseline(in: Varyings) -> @location(0) vec4f {
    return vec4f(in.uv, 0.0, 1.0);
}

@fragment
fn fbm_bench(in: Varyings) -> @location(0) vec4f {
    var p = vec3f(in.uv * 16.0, 0.5);
    var sum = 0.0;
    var amplitude = 1.0;
    for (var octave = 0; octave < 6; octave++) {
        sum += amplitude * 0.9649 * improved_noise(p);
        p *= 2.0;
        amplitude *= 0.5;
    }
    return vec4f(vec3f(sum), 1.0);
}
"#;

/// The hand-written module: the standard library's permutation table (the same numbers the
/// generated code reads) as a module variable, then the shading.
fn handwritten_module() -> naga::Module {
    let noise = patina_compiler::stdlib::source("noise.sl").expect("the stdlib has noise.sl");
    let start = noise.find("#define PATINA_PERLIN_PERMUTATION {").expect("the permutation table");
    let body = &noise[start..];
    let table = &body[body.find('{').unwrap() + 1..body.find('}').unwrap()];
    let numbers: Vec<&str> = table.split([',', '\\', ' ', '\n']).filter(|s| !s.trim().is_empty()).collect();
    assert_eq!(numbers.len(), 256, "the permutation table has 256 entries");
    // A `var<private>`, not a `const`: a `const` array indexed at run time is materialized at
    // every access by naga's SPIR-V (measured: a 512 x 512 render took 15 s on lavapipe).
    let text = format!(
        "var<private> PERM: array<i32, 256> = array<i32, 256>({});\n{HANDWRITTEN}",
        numbers.join(", ")
    );
    naga::front::wgsl::parse_str(&text).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&text)))
}

/// The four point lights of the plastic scene, in world space (the camera's space is the world
/// moved 2 along z), and their intensity.
const LIGHTS: [[f32; 3]; 4] = [[-1.5, 1.5, -1.0], [1.5, 1.5, -1.0], [-1.5, -1.5, -1.0], [1.5, -1.5, -1.0]];
const INTENSITY: f32 = 2.0;

/// The renderer's program for `surface` of `file`, on a plane that fills the view, under
/// `lights` of the example point lights.
fn patina_scene(file: &str, surface: &str, lights: &[[f32; 3]]) -> Prepared {
    let dir = std::env::temp_dir().join(format!("patina-handwritten-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bench.sl"), SURFACES).unwrap();
    // The plane (the unit square, s and t across it) scaled past the view's edges: at distance 2
    // with a 90° field of view the view is 4 wide.
    let examples = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders");
    let lights: String = lights
        .iter()
        .map(|[x, y, z]| {
            format!(
                "[[light]]\nshader = \"{examples}/lights.sl\"\nname = \"pointlight\"\n\
                 params = {{ intensity = {INTENSITY:?}, from = [{x:?}, {y:?}, {z:?}] }}\n"
            )
        })
        .collect();
    let file = if file == "bench.sl" { file.to_string() } else { format!("{examples}/{file}") };
    let text = format!(
        "[output]\nwidth = {SIZE}\nheight = {SIZE}\n[camera]\nfrom = [0, 0, -2]\nto = [0, 0, 0]\nfov = 90\n\
         {lights}[[object]]\nmesh = \"plane\"\ndetail = 1\nshader = \"{file}\"\nname = \"{surface}\"\n\
         transform = [{{ scale = [4.2, 4.2, 1.0] }}]\n"
    );
    let scene = Scene::parse(&text, dir.join("bench.toml"), &dir).unwrap_or_else(|e| panic!("{e}"));
    render::prepare(&scene).unwrap_or_else(|e| panic!("{surface}: {e}"))
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
    let target = Target { width: SIZE, height: SIZE, format: TargetFormat::Rgba32Float, clear: [0.0; 4] };
    // The uniforms of `plastic4`: the lights' camera-space positions, then their colours.
    let uniforms: Vec<u8> = LIGHTS
        .iter()
        .map(|[x, y, z]| [*x, *y, z + 2.0, 1.0])
        .chain(LIGHTS.iter().map(|_| [INTENSITY; 4]))
        .flatten()
        .flat_map(f32::to_le_bytes)
        .collect();
    let handwritten = |entry: &str| {
        let draw = Draw {
            module: &module,
            fingerprint: Some(0x4a4e_5752_4954_5445 ^ entry.len() as u64),
            vertex_entry: "vs_main",
            fragment_entry: entry,
            uniforms: if entry == "plastic4" { &uniforms } else { &[] },
            textures: &[],
            samplers: false,
            attributes: &quad,
            indices: &indices,
            blend: Blend::Replace,
        };
        std::hint::black_box(gpu.render(&target, &[draw]).expect("the hand-written module renders"));
    };
    let generated = |prepared: &Prepared| {
        std::hint::black_box(render::render(prepared, Backend::Gpu, Some(&gpu)).expect("the scene renders"));
    };
    // (label, the Patina scene, the hand-written entry point), after the baseline.
    let shaders = [
        ("fBm, 6 octaves of improved noise", patina_scene("bench.sl", "fbm_bench", &[]), "fbm_bench"),
        ("plastic, 4 point lights", patina_scene("plastic.sl", "plastic", &LIGHTS), "plastic4"),
    ];
    let base_scene = patina_scene("bench.sl", "baseline", &[]);
    // Pipeline creation and the driver's compile, once each, outside the measurement.
    handwritten("baseline");
    generated(&base_scene);
    let mut group = c.benchmark_group("handwritten");
    group.sample_size(10);
    for (label, scene, entry) in &shaders {
        handwritten(entry);
        generated(scene);
        group.bench_function(format!("generated {label}"), |b| b.iter(|| generated(scene)));
        group.bench_function(format!("hand-written {label}"), |b| b.iter(|| handwritten(entry)));
    }
    group.finish();
    let runs = 31;
    let generated_base = median(|| generated(&base_scene), runs);
    let hand_base = median(|| handwritten("baseline"), runs);
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    println!(
        "\n{SIZE}x{SIZE} pixels on {}; the shading's time is a render's less the trivial shader's\n",
        gpu.adapter_description()
    );
    println!("| shader | generated ms | hand-written ms | generated / hand-written |");
    println!("|---|---|---|---|");
    for (label, scene, entry) in &shaders {
        let generated_shading = median(|| generated(scene), runs).saturating_sub(generated_base);
        let hand_shading = median(|| handwritten(entry), runs).saturating_sub(hand_base);
        println!(
            "| {label} | {:.2} | {:.2} | {:.2} |",
            ms(generated_shading),
            ms(hand_shading),
            generated_shading.as_secs_f64() / hand_shading.as_secs_f64().max(1e-9)
        );
    }
    println!(
        "\n(renders with the trivial shader: generated {:.2} ms, hand-written {:.2} ms)",
        ms(generated_base),
        ms(hand_base)
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
