//! `Uniforms` packs every parameter of every example scene into the bytes the renderer writes:
//! each scene's objects are compiled through the facade with nothing fixed, every value the scene
//! gives is set by name (`set`, `set_light`, `set_displacement`), and the block must equal, byte
//! for byte, what `patina render` binds for the same scene compiled dynamic.

use std::path::Path;

use patina::runtime::render::{self, Options, frame::program_uniform_bytes};
use patina::runtime::scene::{ParamValue, Scene, ShaderRef};
use patina::{Compiler, Light, Uniforms, Value, View};

/// A scene's value as the facade takes it.
fn value(v: &ParamValue) -> Value {
    match v {
        ParamValue::Number(x) => Value::from(*x),
        ParamValue::Numbers(v) => Value::from(v.clone()),
        ParamValue::String(s) => Value::from(s.as_str()),
        ParamValue::Bool(b) => Value::from(*b),
    }
}

/// The facade's light (or displacement) for a scene's shader, with its strings compiled in.
fn bound(shader: &ShaderRef) -> Light {
    let shown = shader.path.display().to_string();
    let mut light = match shown.strip_prefix(patina::compiler::stdlib::PREFIX) {
        Some(module) => {
            Light::stdlib(module.trim_start_matches('/'), shader.name.as_deref().unwrap_or_default())
        }
        None => Light::file(&shader.path),
    };
    if let Some(name) = &shader.name {
        light = light.named(name);
    }
    for (name, v) in &shader.params {
        if let ParamValue::String(_) = v {
            light = light.with(name, value(v));
        }
    }
    light
}

/// Sets every numeric value of `shader` through `set`.
fn set_all(shader: &ShaderRef, mut set: impl FnMut(&str, Value) -> Result<(), patina::UniformError>) {
    for (name, v) in &shader.params {
        if !matches!(v, ParamValue::String(_)) {
            set(name, value(v)).unwrap_or_else(|e| panic!("{}: `{name}`: {e}", shader.path.display()));
        }
    }
}

fn check_scene(path: &Path) -> usize {
    let scene = Scene::load(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    // The facade compiles in the fast lowering by default: the renderer compiles the same module.
    let options = Options { specialize: false, lowering: patina::Lowering::Fast };
    let prepared =
        render::prepare_with(&scene, options).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut compared = 0;
    for (i, (object, drawn)) in scene.objects.iter().zip(&prepared.objects).enumerate() {
        let mut compiler = Compiler::new();
        for light in &scene.lights {
            compiler = compiler.light(bound(&light.shader));
        }
        if let Some(d) = &object.displacement {
            compiler = compiler.displacement(bound(d));
        }
        let surface = &object.surface;
        for (name, v) in &surface.params {
            if let ParamValue::String(_) = v {
                compiler = compiler.fix(name, value(v));
            }
        }
        if let Some(name) = &surface.name {
            compiler = compiler.shader(name);
        }
        let shown = surface.path.display().to_string();
        let compiled = match shown.strip_prefix(patina::compiler::stdlib::PREFIX) {
            Some(module) => {
                let text =
                    patina::compiler::stdlib::source(module.trim_start_matches('/')).expect("stdlib module");
                compiler.compile_source(&shown, text)
            }
            None => compiler.compile_file(&surface.path),
        }
        .unwrap_or_else(|e| panic!("{}: object {i}: {e}", path.display()));
        assert_eq!(compiled.interface, drawn.surface.gpu.interface, "{}: object {i}", path.display());

        let mut block: Uniforms = compiled.uniforms();
        set_all(surface, |n, v| block.set(n, v).map(|_| ()));
        for (k, light) in scene.lights.iter().enumerate() {
            set_all(&light.shader, |n, v| block.set_light(k, n, v).map(|_| ()));
            if let Some(p) = light.position {
                block.set_light_position(k, p.to_array()).expect("a bound light");
            }
        }
        if let Some(d) = &object.displacement {
            set_all(d, |n, v| block.set_displacement(n, v).map(|_| ()));
        }
        let n = scene.output.supersample.max(1);
        block.set_view(View {
            camera: scene.camera(),
            object_to_world: scene.object_transform(i),
            width: scene.output.width * n,
            height: scene.output.height * n,
            color: object.color,
            opacity: object.opacity,
        });
        let bytes = block.bytes().unwrap_or_else(|e| panic!("{}: object {i}: {e}", path.display()));
        let expected =
            program_uniform_bytes(&drawn.surface, &prepared.lights, &drawn.frame).expect("renderer's bytes");
        for field in &compiled.interface.uniforms {
            assert_eq!(
                field.read(&bytes),
                field.read(&expected),
                "{}: object {i}: uniform `{}` ({:?})",
                path.display(),
                field.name,
                field.source
            );
        }
        assert_eq!(bytes, expected, "{}: object {i}: padding", path.display());
        compared += 1;
    }
    compared
}

#[test]
fn uniforms_match_the_renderer_for_every_example_scene() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scenes: Vec<_> = std::fs::read_dir(root.join("examples/scenes"))
        .expect("examples/scenes")
        .chain(std::fs::read_dir(root.join("examples/scenes/bench")).expect("examples/scenes/bench"))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    scenes.push(root.join("examples/headless.toml"));
    scenes.sort();
    let objects: usize = scenes.iter().map(|s| check_scene(s)).sum();
    assert!(scenes.len() > 20 && objects >= scenes.len(), "{} scenes, {objects} objects", scenes.len());
}

#[test]
fn setting_a_value_checks_name_type_and_binding() {
    let source = "surface p(float Kd = 0.5, Ks = 0.5; color tint = 1; point at = 0) {
        Ci = tint * (Kd + Ks) + color(at);
    }";
    // The host computes `tint * (Kd + Ks)` once per draw; folded, the parameters themselves are
    // the uniforms, and no host part is needed.
    let hosted = Compiler::new().fix("Ks", 0.25).compile_source("p.sl", source).expect("compiles");
    assert!(hosted.interface.needs_host);
    let compiled =
        Compiler::new().fix("Ks", 0.25).fold_host(true).compile_source("p.sl", source).expect("compiles");
    assert!(!compiled.interface.needs_host);
    let mut block = compiled.uniforms();
    assert!(matches!(block.set("Kx", 1.0), Err(patina::UniformError::Unknown { .. })));
    assert!(matches!(block.set("tint", 1.0), Err(patina::UniformError::WrongType { .. })));
    assert!(matches!(block.set("Kd", "a"), Err(patina::UniformError::WrongType { .. })));
    assert!(matches!(block.set("Ks", 1.0), Err(patina::UniformError::CompiledIn { .. })));
    block.set("Kd", 0.75).expect("Kd").set("tint", [0.5, 0.25, 1.0]).expect("tint");
    let bytes = block.bytes().expect("bytes");
    let read = |name: &str| {
        let source = patina::interface::UniformSource::Param { name: name.into() };
        block.read(&bytes, &source).unwrap_or_else(|| panic!("no uniform for {name}"))
    };
    assert_eq!(read("Kd"), vec![0.75]);
    assert_eq!(read("tint"), vec![0.5, 0.25, 1.0]);
    // Ks is compiled in: no uniform, and the interface says so.
    assert!(
        compiled.interface.uniform(&patina::interface::UniformSource::Param { name: "Ks".into() }).is_none()
    );
    assert_eq!(compiled.interface.param("Ks").and_then(|p| p.fixed.clone()), Some(vec![0.25]));
    assert_eq!(compiled.interface.param("Kd").and_then(|p| p.default.clone()), Some(vec![0.5]));
    // A point depends on the view and cannot be compiled in.
    let fixed_point = Compiler::new()
        .fix("at", [1.0, 2.0, 3.0])
        .compile_source("p.sl", "surface p(point at = 0) { Ci = color(at); }");
    assert!(matches!(fixed_point, Err(patina::CompileError::DependsOnView { .. })));
}

/// Issue 23: a Stanford-style light is placed by the host; its position is a uniform the block
/// fills in camera space once `set_light_position` gives it (in world space), and not before.
#[test]
fn a_stanford_lights_position_is_set_in_world_space() {
    let light = "light shader float4 falloff(float4 c) { return c * (1.0 / (0.5 * Sdist + 1.0)); }";
    let surface =
        "surface shader float4 lit() { perlight float4 c = Cl * max(dot(N, L), 0); return integrate(c); }";
    let compiled = Compiler::new()
        .light(Light::source("falloff.sl", light))
        .compile_source("lit.sl", surface)
        .expect("compiles");
    let mut block = compiled.uniforms();
    assert!(matches!(block.bytes(), Err(patina::UniformError::NoPosition { light: 0 })));
    assert!(matches!(block.set_light_position(1, [0.0; 3]), Err(patina::UniformError::NoLight { .. })));
    block.set_light_position(0, [1.0, 2.0, -3.0]).expect("light 0");
    let bytes = block.bytes().expect("bytes");
    let source = patina::interface::UniformSource::LightPosition { light: 0 };
    let position = block.read(&bytes, &source).expect("a position uniform");
    // The default view's camera looks from (0, 0, -5) at the origin: camera space is world
    // space moved 5 along +z.
    let expected = [1.0, 2.0, 2.0];
    assert!(position.iter().zip(expected).all(|(p, e)| (p - e).abs() < 1e-6), "{position:?}");
}
