//! Atmosphere (volume) shaders after the surface and imager shaders over the finished image, on
//! both backends, against their formulas at pixels. Needs a GPU adapter (lavapipe in CI) unless
//! PATINA_GPU=off (then only the CPU reference is checked).

use patina_runtime::image::{Image, Thresholds, compare};
use patina_runtime::render::{self, Backend};
use patina_runtime::scene::Scene;

fn scene(name: &str) -> Scene {
    let path = format!("{}/tests/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    Scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// The CPU reference's image, and the GPU's compared with it (OSL's thresholds) when there is one.
fn render_both(label: &str, scene: &Scene) -> Image {
    let prepared = render::prepare(scene).unwrap_or_else(|e| panic!("{label}: {e}"));
    let cpu = render::render(&prepared, Backend::Cpu, None).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert!(cpu.pixels.iter().flatten().all(|x| x.is_finite()), "{label}: not finite");
    if let Some(gpu) = patina_runtime::gpu::for_tests() {
        let image =
            render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap_or_else(|e| panic!("{label}: {e}"));
        let t = Thresholds::default();
        let c = compare(&cpu, &image, &t).unwrap();
        assert!(c.passes(&t), "{label}: GPU and CPU images differ: {c:?}");
    }
    cpu
}

fn at(image: &Image, x: u32, y: u32) -> [f32; 4] {
    image.pixels[(y * image.width + x) as usize]
}

#[test]
fn fog_mixes_towards_its_colour_by_distance() {
    let fogged = scene("fog");
    let mut clear = fogged.clone();
    for o in &mut clear.objects {
        o.atmosphere = None;
    }
    let with = render_both("fog", &fogged);
    let without = render_both("fog without the atmosphere", &clear);
    // The centre pixel looks straight at the sphere's nearest point, 4 units from the eye (the
    // tessellation puts it a little further): d = 1 - exp(-4 / falloff).
    let d = 1.0 - (-4.0f32 / 4.0).exp();
    let (c, f) = (at(&without, 16, 16), at(&with, 16, 16));
    for (k, fog) in [0.5f32, 0.6, 0.7].into_iter().enumerate() {
        let expected = c[k] + (fog - c[k]) * d;
        assert!((f[k] - expected).abs() < 0.01, "channel {k}: {} against {expected}", f[k]);
    }
    assert!((f[3] - 1.0).abs() < 1e-6, "alpha {}", f[3]);
    // A corner pixel sees no surface: the background, untouched.
    assert_eq!(at(&with, 0, 0), at(&without, 0, 0));
    assert!((at(&with, 0, 0)[2] - 0.08).abs() < 1e-6);
}

#[test]
fn an_object_can_have_its_own_atmosphere() {
    let mut s = scene("fog");
    let own = s.objects[0].atmosphere.clone().map(|mut a| {
        a.name = Some("depthcue".into());
        a.params.clear();
        a.params.insert("mindistance".into(), patina_runtime::scene::ParamValue::Number(3.0));
        a.params.insert("maxdistance".into(), patina_runtime::scene::ParamValue::Number(6.0));
        a
    });
    s.objects[0].atmosphere = own;
    let with = render_both("depthcue", &s);
    let mut clear = s.clone();
    clear.objects[0].atmosphere = None;
    let without = render_both("depthcue without", &clear);
    // Depth 4 between 3 and 6: a third of the way to black.
    let (c, f) = (at(&without, 16, 16), at(&with, 16, 16));
    for k in 0..3 {
        let expected = c[k] * (1.0 - 1.0 / 3.0);
        assert!((f[k] - expected).abs() < 0.01, "channel {k}: {} against {expected}", f[k]);
    }
}

#[test]
fn the_background_imager_fills_uncovered_pixels() {
    let s = scene("imager");
    let image = render_both("background imager", &s);
    // A corner sees no surface: alpha 0 before the imager, so exactly the background colour.
    assert_eq!(at(&image, 0, 0), [0.2, 0.3, 0.4, 1.0]);
    // The centre is covered: the imager adds nothing, and the surface's colour is the one drawn
    // without an imager.
    let mut plain = s.clone();
    plain.imager = None;
    let without = render_both("no imager", &plain);
    assert_eq!(at(&without, 16, 16)[3], 1.0);
    assert_eq!(at(&image, 16, 16), at(&without, 16, 16));
    // Without an imager the uncovered pixels are the scene's background (opaque black).
    assert_eq!(at(&without, 0, 0), [0.0, 0.0, 0.0, 1.0]);
}

#[test]
fn exposure_and_vignette_follow_their_formulas() {
    let mut s = scene("imager");
    let plain = {
        let mut p = s.clone();
        p.imager = None;
        render_both("plain", &p)
    };
    let imager = s.imager.as_mut().unwrap();
    imager.name = Some("exposure".into());
    imager.params.clear();
    imager.params.insert("gain".into(), patina_runtime::scene::ParamValue::Number(2.0));
    imager.params.insert("gamma".into(), patina_runtime::scene::ParamValue::Number(2.2));
    let exposed = render_both("exposure", &s);
    let (c, e) = (at(&plain, 16, 16), at(&exposed, 16, 16));
    for k in 0..3 {
        let expected = (2.0 * c[k]).powf(1.0 / 2.2);
        assert!((e[k] - expected).abs() < 1e-4, "channel {k}: {} against {expected}", e[k]);
    }
    let imager = s.imager.as_mut().unwrap();
    imager.name = Some("vignette".into());
    imager.params.clear();
    let vignetted = render_both("vignette", &s);
    // Pixel (16, 10), on the sphere: s = 16.5 / 33 = 0.5, t = 10.5 / 33; r = 2 |t - 0.5| / sqrt(2).
    let (x, y) = (16, 10);
    let t = (y as f32 + 0.5) / 33.0;
    let r = 2.0 * (t - 0.5).abs() / 2f32.sqrt();
    let (c, v) = (at(&plain, x, y), at(&vignetted, x, y));
    assert_eq!(c[3], 1.0, "the pixel is covered");
    for k in 0..3 {
        let expected = c[k] * (1.0 - 0.5 * r * r);
        assert!((v[k] - expected).abs() < 1e-4, "channel {k}: {} against {expected}", v[k]);
    }
}

/// The corpus' imagers and volumes (Aqsis' shaders, read where they are: GPL, not copied), each
/// with its defaults on the test scenes; both backends must agree and the image must change.
#[test]
fn the_corpus_imagers_and_volumes_render_on_both_backends() {
    let corpus = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/corpus/aqsis");
    if !corpus.is_dir() {
        eprintln!("no corpus at {}: skipped", corpus.display());
        return;
    }
    let plain = {
        let mut s = scene("imager");
        s.imager = None;
        render_both("plain", &s)
    };
    for kind in ["imager", "volume"] {
        let mut files: Vec<_> = std::fs::read_dir(corpus.join(kind))
            .unwrap()
            .filter_map(|e| Some(e.ok()?.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "sl"))
            .collect();
        files.sort();
        for file in files {
            let label = file.file_name().unwrap().to_string_lossy().to_string();
            let mut s = scene("imager");
            let mut shader = s.imager.clone().unwrap();
            shader.path = file.clone();
            shader.name = None;
            shader.params.clear();
            if kind == "imager" {
                s.imager = Some(shader);
            } else {
                s.imager = None;
                s.objects[0].atmosphere = Some(shader);
            }
            let image = render_both(&label, &s);
            assert_ne!(image.pixels, plain.pixels, "{label} changed nothing");
        }
    }
}

/// Aqsis's `bluescreen` with a texture behind the image: the lookup its default decides away
/// (`texturename = ""`) runs once the scene names a texture, on both backends (the GPU's imager
/// kernel binds the textures it fetches).
#[test]
fn an_imager_reads_its_texture_on_both_backends() {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/corpus/aqsis/imager/bluescreen.sl");
    assert!(file.is_file(), "{}: the corpus is missing (it lives in ../shared)", file.display());
    let mut s = scene("imager");
    let imager = s.imager.as_mut().unwrap();
    imager.path = file;
    imager.name = None;
    imager.params.clear();
    let blue = render_both("bluescreen", &s);
    assert_eq!(at(&blue, 0, 0), [0.0, 0.0, 1.0, 1.0], "the default background is blue");
    let imager = s.imager.as_mut().unwrap();
    imager.params.insert("texturename".into(), patina_runtime::scene::ParamValue::String("checker:2".into()));
    let textured = render_both("bluescreen over a checker", &s);
    // An uncovered pixel shows the grey checker (white and black texels filtered together), not blue.
    let [r, g, b, a] = at(&textured, 0, 0);
    assert!(r == g && g == b && r > 0.0 && a == 1.0, "{:?}", [r, g, b, a]);
    // Covered pixels keep the surface: the imager adds (1 - alpha) of the texture.
    assert_eq!(at(&textured, 16, 16), at(&blue, 16, 16));
}

#[test]
fn bad_atmospheres_and_imagers_are_one_line_errors() {
    let dir = format!("{}/tests/scenes", env!("CARGO_MANIFEST_DIR"));
    let head = "[camera]\nfrom = [0, 0, -5]\nto = [0, 0, 0]\n\n[[object]]\nmesh = \"sphere\"\n\
                shader = \"../../../examples/shaders/plastic.sl\"\n";
    let parse = |tail: &str| Scene::parse(&format!("{head}{tail}"), format!("{dir}/bad.toml"), &dir);
    // The schema: a misspelt field, an empty path.
    let e = parse("atmosphere = { shader = \"fog.sl\", param = {} }\n").unwrap_err().to_string();
    assert!(e.contains("param") && !e.contains('\n'), "{e}");
    let e = parse("\n[imager]\nshader = \"\"\n").unwrap_err().to_string();
    assert!(e.contains("imager") && !e.contains('\n'), "{e}");
    // A file without a shader of the kind: rendering says which.
    let s = parse("atmosphere = { shader = \"../../../examples/shaders/plastic.sl\" }\n").unwrap();
    let e = render::prepare(&s).err().expect("not a volume shader").to_string();
    assert!(e.contains("no volume shader") && !e.contains('\n'), "{e}");
    let s = parse("\n[imager]\nshader = \"../../../examples/shaders/fog.sl\"\n").unwrap();
    let e = render::prepare(&s).err().expect("not an imager").to_string();
    assert!(e.contains("no imager shader") && !e.contains('\n'), "{e}");
    // An unknown parameter.
    let s = parse("\n[imager]\nshader = \"../../../examples/shaders/imagers.sl\"\nparams = { nope = 1 }\n")
        .unwrap();
    let e = render::prepare(&s).err().expect("unknown parameter").to_string();
    assert!(e.contains("no parameter `nope`") && !e.contains('\n'), "{e}");
}
