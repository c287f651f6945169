//! Binding (DESIGN.md §4) through the whole pipeline: each thing a scene makes unnecessary is
//! absent from the compiled naga module (the global, the argument, the code), and the picture is
//! the one the unspecialized program draws. Needs a GPU adapter unless `PATINA_GPU=off`.

use patina_runtime::image::{Image, Thresholds, compare};
use patina_runtime::render::{self, Backend, Options, Prepared};
use patina_runtime::scene::Scene;

/// A surface shader with two option flags, a texture behind one, a vertex-rate value that only
/// the other's branch reads, and a light loop.
const FLAGS: &str =
    "surface flags(float use_tex = 0; string map = \"checker:4\"; float detail = 0; float Kd = 0.8)
{
    color c = Cs;
    float stripes = 0.5 + 0.5 * sin(40 * u);
    if (use_tex > 0.5) {
        c *= color texture(map, s, t);
    }
    if (detail > 0.5) {
        c *= 0.5 + 0.5 * stripes * noise(P * 6);
    }
    normal Nf = normalize(N);
    color lit = 0;
    illuminance(P, Nf, PI / 2) {
        lit += Cl * max(normalize(L) . Nf, 0);
    }
    Ci = c * Kd * (0.1 + lit);
    Oi = 1;
}
";

const LIGHT: &str = "[[light]]\nshader = \"<shaders.sl>\"\nname = \"distantlight\"\n\
                     params = { intensity = 1.0, from = [-1.0, 1.0, -1.0], to = [0.0, 0.0, 0.0] }\n";

/// A sphere shaded by FLAGS with `params`, under `lights` copies of a distant light.
fn scene(params: &str, lights: usize) -> Scene {
    // A directory per scene: tests run in parallel, and one must not read a file another is
    // rewriting.
    static SCENES: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = SCENES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("patina-bind-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("flags.sl"), FLAGS).unwrap();
    let text = format!(
        "[output]\nwidth = 40\nheight = 40\n[camera]\nfrom = [0.0, 0.0, -3.5]\nto = [0.0, 0.0, 0.0]\n\
         {}[[object]]\nmesh = \"sphere\"\ndetail = 24\nshader = \"flags.sl\"\nparams = {{ {params} }}\n",
        LIGHT.repeat(lights)
    );
    Scene::parse(&text, dir.join("flags.toml"), &dir).unwrap_or_else(|e| panic!("{e}"))
}

fn prepared(scene: &Scene, specialize: bool) -> Prepared {
    render::prepare_with(scene, Options { specialize, ..Options::default() })
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The CPU reference's image and, with a GPU, the GPU's.
fn images(p: &Prepared) -> Vec<Image> {
    let mut out = vec![render::render(p, Backend::Cpu, None).unwrap()];
    if let Some(gpu) = patina_runtime::gpu::for_tests() {
        out.push(render::render(p, Backend::Gpu, Some(gpu)).unwrap_or_else(|e| panic!("{e}")));
    }
    out
}

/// Specialized and dynamic programs draw the same picture on each backend: bit for bit on the
/// CPU (the same arithmetic in the same order); on the GPU within a few ulps, since the driver
/// may fold differently once a value is a constant.
fn assert_same_pictures(scene: &Scene) {
    let (fixed, dynamic) = (images(&prepared(scene, true)), images(&prepared(scene, false)));
    assert_eq!(fixed[0].pixels, dynamic[0].pixels, "CPU: the specialized picture differs");
    if let (Some(a), Some(b)) = (fixed.get(1), dynamic.get(1)) {
        let t = Thresholds { fail: 1e-6, hard_fail: 1e-5, max_failing_fraction: 0.0 };
        let c = compare(a, b, &t).unwrap();
        assert!(c.passes(&t), "GPU: the specialized picture differs: {c:?}");
    }
}

/// The names of the module's global variables bound to a resource group (uniforms, textures).
fn bound_globals(p: &Prepared) -> Vec<(u32, String)> {
    let module = &p.objects[0].surface.gpu.module;
    module
        .global_variables
        .iter()
        .filter_map(|(_, g)| g.binding.as_ref().map(|b| (b.group, g.name.clone().unwrap_or_default())))
        .collect()
}

/// How many expressions the module's functions hold in all: its size, the way naga counts.
fn expressions(p: &Prepared) -> usize {
    let module = &p.objects[0].surface.gpu.module;
    module.functions.iter().map(|(_, f)| f.expressions.len()).sum::<usize>()
        + module.entry_points.iter().map(|e| e.function.expressions.len()).sum::<usize>()
}

#[test]
fn a_texture_behind_a_flag_fixed_off_is_not_bound() {
    let off = scene("use_tex = 0, detail = 0", 1);
    let (fixed, dynamic) = (prepared(&off, true), prepared(&off, false));
    let textures = |p: &Prepared| bound_globals(p).into_iter().filter(|(g, _)| *g == 1).count();
    assert!(textures(&dynamic) > 0, "the dynamic program binds the texture: {:?}", bound_globals(&dynamic));
    assert_eq!(textures(&fixed), 0, "{:?}", bound_globals(&fixed));
    assert!(fixed.objects[0].surface.gpu.interface.textures.is_empty());
    assert!(fixed.objects[0].textures.is_empty(), "no texture is loaded for it either");
    assert_same_pictures(&off);
    // Fixed on, the texture stays.
    let on = scene("use_tex = 1, detail = 0", 1);
    assert!(textures(&prepared(&on, true)) > 0);
    assert_same_pictures(&on);
}

#[test]
fn a_flag_fixed_either_way_keeps_only_its_side() {
    let off = prepared(&scene("detail = 0", 1), true);
    let on = prepared(&scene("detail = 1", 1), true);
    let dynamic = prepared(&scene("detail = 0", 1), false);
    // The noise and the stripes are code only the `detail` branch has.
    assert!(expressions(&off) < expressions(&on), "{} vs {}", expressions(&off), expressions(&on));
    assert!(expressions(&on) <= expressions(&dynamic));
    let wgsl = |p: &Prepared| p.objects[0].surface.gpu.wgsl().unwrap();
    assert!(
        wgsl(&on).contains("sin(") && !wgsl(&off).contains("sin("),
        "the stripes' sine goes with the branch"
    );
    // Neither flag is in the specialized uniform block; the dynamic program reads them per draw.
    let uniforms = |p: &Prepared| {
        p.objects[0].surface.gpu.interface.uniforms.iter().map(|u| u.name.clone()).collect::<Vec<_>>()
    };
    assert!(
        uniforms(&dynamic).len() > uniforms(&off).len(),
        "{:?} vs {:?}",
        uniforms(&dynamic),
        uniforms(&off)
    );
    assert_same_pictures(&scene("detail = 0", 1));
    assert_same_pictures(&scene("detail = 1", 1));
}

#[test]
fn a_value_computed_per_vertex_for_a_removed_branch_is_not_carried() {
    // `stripes` depends on u only: u (or `stripes`, computed by the vertex stage) crosses to the
    // fragment stage, unless the branch that reads it is gone. Values carried, counting the predefined variables a varying also fills (`s` in `in_u`).
    let carried = |p: &Prepared| -> Vec<String> {
        let varyings = &p.objects[0].surface.gpu.interface.varyings;
        varyings.iter().flat_map(|v| std::iter::once(v.name.clone()).chain(v.also.clone())).collect()
    };
    let off = prepared(&scene("detail = 0", 1), true);
    let dynamic = prepared(&scene("detail = 0", 1), false);
    assert!(carried(&off).len() < carried(&dynamic).len(), "{:?} vs {:?}", carried(&off), carried(&dynamic));
}

#[test]
fn lights_are_unrolled_over_exactly_the_bound_ones() {
    for lights in [0, 1, 3] {
        let s = scene("detail = 0", lights);
        let p = prepared(&s, true);
        let module = &p.objects[0].surface.gpu.module;
        let light_functions = module
            .functions
            .iter()
            .filter(|(_, f)| f.name.as_deref().is_some_and(|n| n.starts_with("light")))
            .count();
        assert_eq!(light_functions, lights, "{lights} lights");
        let light_uniforms =
            p.objects[0].surface.gpu.interface.uniforms.iter().filter(|u| u.name.starts_with('l')).count();
        assert_eq!(
            light_uniforms == 0,
            lights == 0,
            "{lights} lights: {:?}",
            p.objects[0].surface.gpu.interface.uniforms
        );
        assert_same_pictures(&s);
    }
}

#[test]
fn animated_parameters_stay_in_the_uniform_block() {
    let base = scene("detail = 1, Kd = 0.6", 1);
    let mut animated = base.clone();
    animated.objects[0].surface.animate = vec!["detail".into()];
    let a = prepared(&animated, true);
    let f = prepared(&base, true);
    assert!(expressions(&a) > expressions(&f), "the branch stays when detail is animated");
    assert_eq!(images(&a)[0].pixels, images(&f)[0].pixels);
}

#[test]
fn parameters_left_at_a_literal_default_are_folded_as_if_set() {
    // FLAGS's flags default to 0 and Kd to 0.8: a scene that sets nothing compiles the program
    // of one that sets those values, so the texture and the detail branch are gone.
    let unset = scene("", 1);
    let set = scene("use_tex = 0, detail = 0, Kd = 0.8", 1);
    let (u, s) = (prepared(&unset, true), prepared(&set, true));
    let wgsl = |p: &Prepared| p.objects[0].surface.gpu.wgsl().unwrap();
    assert_eq!(wgsl(&u), wgsl(&s));
    assert!(u.objects[0].surface.gpu.interface.textures.is_empty());
    let folded: Vec<&str> = u.objects[0]
        .surface
        .loaded
        .decisions
        .iter()
        .filter_map(|d| match d {
            patina_compiler::bind::Decision::Folded { name, .. } => Some(name.as_str()),
            _ => None,
        })
        .collect();
    assert_eq!(folded, ["use_tex", "detail", "Kd"]);
    assert_same_pictures(&unset);
}

#[test]
fn defaults_the_host_computes_and_animated_defaults_stay_in_the_uniform_block() {
    let dir = std::env::temp_dir().join(format!("patina-bind-defaults-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("d.sl"),
        "surface d(float k = sqrt(0.5); float j = 0.25; float h = 0.75)\n\
         { Ci = color(s * k, t * j, u * h); Oi = 1; }\n",
    )
    .unwrap();
    let text = "[output]\nwidth = 16\nheight = 16\n[camera]\nfrom = [0, 0, -3]\nto = [0, 0, 0]\n\
                [[object]]\nmesh = \"sphere\"\nshader = \"d.sl\"\nanimate = [\"h\"]\n";
    let scene = Scene::parse(text, dir.join("d.toml"), &dir).unwrap_or_else(|e| panic!("{e}"));
    let p = prepared(&scene, true);
    let uniforms: Vec<&str> =
        p.objects[0].surface.gpu.interface.uniforms.iter().map(|u| u.name.as_str()).collect();
    assert!(uniforms.contains(&"k"), "sqrt(0.5) is the host's: {uniforms:?}");
    assert!(uniforms.contains(&"h"), "h is animated: {uniforms:?}");
    assert!(!uniforms.contains(&"j"), "j is folded: {uniforms:?}");
    assert_same_pictures(&scene);
}

#[test]
fn the_cache_recompiles_nothing_for_new_animated_values() {
    let mut s = scene("detail = 1, Kd = 0.6", 1);
    s.objects[0].surface.animate = vec!["Kd".into()];
    let mut cache = render::Cache::new();
    let first = render::prepare_cached(&s, Options::default(), &mut cache).unwrap();
    assert_eq!((cache.hits, cache.misses), (0, 2), "the light and the surface are compiled");
    // A new value of the animated Kd: both programs come from the cache, and the picture is the
    // one a fresh compile draws.
    s.objects[0].surface.params.insert("Kd".into(), patina_runtime::scene::ParamValue::Number(0.3));
    let again = render::prepare_cached(&s, Options::default(), &mut cache).unwrap();
    assert_eq!((cache.hits, cache.misses), (2, 2));
    let fresh = prepared(&s, true);
    assert_eq!(images(&again)[0].pixels, images(&fresh)[0].pixels);
    assert_ne!(images(&again)[0].pixels, images(&first)[0].pixels, "Kd changed the picture");
    if let (Some(a), Some(f)) = (images(&again).get(1), images(&fresh).get(1)) {
        assert_eq!(a.pixels, f.pixels, "GPU");
    }
    // A new value of a fixed parameter is a new binding.
    s.objects[0].surface.params.insert("detail".into(), patina_runtime::scene::ParamValue::Number(0.0));
    render::prepare_cached(&s, Options::default(), &mut cache).unwrap();
    assert_eq!((cache.hits, cache.misses), (3, 3), "the light is found, the surface compiled");
}

#[path = "../../benches/support/features.rs"]
mod features;

#[test]
fn the_benchmarks_specialized_program_draws_the_dynamic_picture() {
    // Five flags fixed, eight lights: the specialized program is a fraction of the dynamic one
    // (runtime/benches/binding.rs measures how much) and draws the same picture.
    let s = features::scene(8);
    let fixed = prepared(&s, true);
    let dynamic = prepared(&s, false);
    let bytes = |p: &Prepared| p.objects[0].surface.gpu.wgsl().unwrap().len();
    assert!(bytes(&fixed) * 3 < bytes(&dynamic), "{} vs {} bytes", bytes(&fixed), bytes(&dynamic));
    assert_same_pictures(&s);
}

/// A surface with a point parameter the scene fixes, under a distant light whose `from` and `to`
/// are points too: values the shader sees in camera space.
const SPOT: &str = "surface spot(point centre = point(0, 0, 0); float radius = 0.45; float Kd = 0.8)
{
    normal Nf = normalize(N);
    color lit = 0;
    illuminance(P, Nf, PI / 2) {
        lit += Cl * max(normalize(L) . Nf, 0);
    }
    float inside = 1 - smoothstep(radius - 0.1, radius + 0.1, distance(P, centre));
    Ci = Cs * Kd * (0.1 + lit) * (0.3 + 0.7 * inside);
    Oi = 1;
}
";

/// A sphere shaded by SPOT, its spot at a world-space point on the sphere's front.
fn spot_scene() -> Scene {
    let dir = std::env::temp_dir().join(format!("patina-bind-spot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("spot.sl"), SPOT).unwrap();
    let text = format!(
        "[output]\nwidth = 40\nheight = 40\n[camera]\nfrom = [0.0, 0.0, -3.5]\nto = [0.0, 0.0, 0.0]\n\
         {LIGHT}[[object]]\nmesh = \"sphere\"\ndetail = 24\nshader = \"spot.sl\"\n\
         params = {{ centre = [0.35, 0.3, -0.89], Kd = 0.9 }}\n"
    );
    Scene::parse(&text, dir.join("spot.toml"), &dir).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_cache_serves_a_moving_camera() {
    let mut s = spot_scene();
    let mut cache = render::Cache::new();
    let first = render::prepare_cached(&s, Options::default(), &mut cache).unwrap();
    assert_eq!((cache.hits, cache.misses), (0, 2), "the light and the surface are compiled");
    // Points the scene fixes depend on the camera: they stay parameters, which the host part
    // puts in the camera's space per draw (into the uniform block, here as the value
    // `distance`'s library code stores from `centre`: the pictures below show the spot follows
    // the camera), while `Kd` is compiled in.
    let uniforms = |p: &Prepared| -> Vec<String> {
        p.objects[0].surface.gpu.interface.uniforms.iter().map(|u| u.name.clone()).collect()
    };
    assert!(!uniforms(&first).iter().any(|n| n.contains("Kd")), "Kd is compiled in: {:?}", uniforms(&first));

    s.camera.from = glam::Vec3::new(1.6, 0.9, -3.0);
    let moved = render::prepare_cached(&s, Options::default(), &mut cache).unwrap();
    assert_eq!((cache.hits, cache.misses), (2, 2), "the second camera compiles nothing");
    let fresh = prepared(&s, true);
    let (moved_images, fresh_images) = (images(&moved), images(&fresh));
    assert_eq!(moved_images[0].pixels, fresh_images[0].pixels, "CPU: the cached program's picture differs");
    if let (Some(a), Some(f)) = (moved_images.get(1), fresh_images.get(1)) {
        assert_eq!(a.pixels, f.pixels, "GPU: the cached program's picture differs");
    }
    assert_ne!(moved_images[0].pixels, images(&first)[0].pixels, "the camera moved");
    // The same specialized program draws what the dynamic one does, from either camera.
    assert_same_pictures(&s);
}

/// Issue 23: the cache keys a shader by its own text, and checks the files it includes when it is
/// found: an edited include is compiled again (it used to be served from the cache), an
/// unchanged one is not.
#[test]
fn the_cache_compiles_again_when_an_included_file_changes() {
    let dir = std::env::temp_dir().join(format!("patina-cache-include-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let header = dir.join("tint.h");
    std::fs::write(&header, "color tint() { return color(1, 0, 0); }\n").unwrap();
    std::fs::write(dir.join("s.sl"), "#include \"tint.h\"\nsurface s() { Ci = tint(); }\n").unwrap();
    let text = "[output]\nwidth = 8\nheight = 8\n[camera]\nfrom = [0, 0, -3]\nto = [0, 0, 0]\n\
                [[object]]\nmesh = \"sphere\"\nshader = \"s.sl\"\n";
    let s = Scene::parse(text, dir.join("s.toml"), &dir).unwrap();
    let centre = |p: &Prepared| render::render(p, Backend::Cpu, None).unwrap().pixels[4 * 8 + 4];
    let mut cache = render::Cache::new();
    let red = render::prepare_cached(&s, Options::default(), &mut cache).unwrap();
    assert_eq!(centre(&red), [1.0, 0.0, 0.0, 1.0]);
    let same = render::prepare_cached(&s, Options::default(), &mut cache).unwrap();
    assert_eq!((cache.hits, cache.misses, centre(&same)), (1, 1, [1.0, 0.0, 0.0, 1.0]));
    std::fs::write(&header, "color tint() { return color(0, 0, 1); }\n").unwrap();
    let blue = render::prepare_cached(&s, Options::default(), &mut cache).unwrap();
    assert_eq!((cache.hits, cache.misses), (1, 2), "the edited include is compiled again");
    assert_eq!(centre(&blue), [0.0, 0.0, 1.0, 1.0]);
}
