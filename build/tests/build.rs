//! `Shaders::build_to` on real shaders: the files it writes, the cargo lines it prints, its
//! errors, and the generated structs' layouts against the interfaces.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use patina_build::{Light, Shader, Shaders};

/// A fresh directory under the system's temporary directory.
fn temp_dir(name: &str) -> PathBuf {
    static COUNT: AtomicUsize = AtomicUsize::new(0);
    let n = COUNT.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("patina-build-{}-{name}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/shaders")
}

#[test]
fn included_files_are_named_for_cargo() {
    let dir = temp_dir("include");
    let helper = dir.join("helper.sl");
    std::fs::write(&helper, "float half_of(float x) { return x * 0.5; }\n").unwrap();
    let shader = dir.join("main.sl");
    std::fs::write(&shader, "#include \"helper.sl\"\nsurface main(float k = 1) { Ci = Cs * half_of(k); }\n")
        .unwrap();
    let mut cargo = Vec::new();
    let built =
        Shaders::new().out_dir(dir.join("out")).shader(Shader::new(&shader)).build_to(&mut cargo).unwrap();
    let cargo = String::from_utf8(cargo).unwrap();
    let rerun: Vec<PathBuf> = cargo
        .lines()
        .filter_map(|l| l.strip_prefix("cargo:rerun-if-changed="))
        .map(|p| std::fs::canonicalize(p).unwrap())
        .collect();
    for file in [&shader, &helper] {
        let file = std::fs::canonicalize(file).unwrap();
        assert!(rerun.contains(&file), "{} not in:\n{cargo}", file.display());
    }
    assert_eq!(built.shaders[0].module, "main");
    let rust = std::fs::read_to_string(&built.rust).unwrap();
    assert!(rust.contains("pub mod main {"), "{rust}");
    let wgsl = std::fs::read_to_string(&built.shaders[0].wgsl).unwrap();
    naga::front::wgsl::parse_str(&wgsl).unwrap();
    let json = std::fs::read_to_string(&built.shaders[0].json).unwrap();
    let interface: patina_build::Interface = serde_json::from_str(&json).unwrap();
    assert_eq!(interface, built.shaders[0].compiled.interface);
}

#[test]
fn errors_fail_the_build_with_the_diagnostics() {
    let dir = temp_dir("error");
    let shader = dir.join("broken.sl");
    std::fs::write(&shader, "surface broken() { Ci = undefined_thing; }\n").unwrap();
    let mut cargo = Vec::new();
    let err = Shaders::new()
        .out_dir(dir.join("out"))
        .shader(Shader::new(&shader))
        .build_to(&mut cargo)
        .unwrap_err();
    let text = format!("{err:?}"); // what `build().unwrap()` prints
    assert!(text.starts_with("patina-build: cannot compile"), "{text}");
    assert!(text.contains("undefined_thing") && text.contains("error"), "{text}");
    assert!(text.contains("broken.sl"), "{text}");
    // The broken file is still watched, so fixing it reruns the build script.
    assert!(String::from_utf8(cargo).unwrap().contains("rerun-if-changed="));
    assert!(!dir.join("out").join(patina_build::RUST_FILE).exists());
}

#[test]
fn no_out_dir_and_duplicate_modules_are_errors() {
    let plastic = examples().join("plastic.sl");
    // Tests run without OUT_DIR.
    if std::env::var_os("OUT_DIR").is_none() {
        let err = Shaders::new().shader(Shader::new(&plastic)).build_to(&mut Vec::new()).unwrap_err();
        assert!(matches!(err, patina_build::Error::NoOutDir), "{err}");
    }
    let err = Shaders::new()
        .out_dir(temp_dir("dup"))
        .shader(Shader::new(&plastic))
        .shader(Shader::new(&plastic))
        .build_to(&mut Vec::new())
        .unwrap_err();
    assert!(matches!(err, patina_build::Error::DuplicateModule(ref m) if m == "plastic"), "{err}");
}

/// The members of `pub struct Uniforms` in the generated module `module`, as (name, type).
fn struct_members<'a>(rust: &'a str, module: &str) -> Vec<(&'a str, &'a str)> {
    let start = rust.find(&format!("pub mod {module} {{")).unwrap();
    let body = &rust[start..];
    let body = &body[body.find("pub struct Uniforms {").unwrap()..];
    let body = &body[..body.find("\n    }").unwrap()];
    body.lines()
        .filter_map(|l| l.trim().strip_prefix("pub "))
        .filter_map(|l| l.strip_suffix(','))
        .filter_map(|l| l.split_once(": "))
        .collect()
}

/// The size of a generated member type: `f32`, `u32`, `i32` or arrays of them.
fn size_of_type(ty: &str) -> usize {
    match ty {
        "f32" | "i32" | "u32" => 4,
        _ => {
            let inner = ty.strip_prefix('[').and_then(|t| t.strip_suffix(']')).unwrap();
            let (element, n) = inner.rsplit_once("; ").unwrap();
            size_of_type(element) * n.parse::<usize>().unwrap()
        }
    }
}

#[test]
fn generated_structs_lay_out_the_example_shaders_blocks() {
    let out = temp_dir("examples");
    let pointlight = || Light::file(examples().join("lights.sl")).named("pointlight");
    let mut shaders = Shaders::new().out_dir(&out);
    let names =
        ["plastic", "bricks", "planet", "textured", "aniso", "volume_texture", "cumulus", "brick_filtering"];
    for name in names {
        let path = examples().join(format!("{name}.sl"));
        shaders = shaders.shader(Shader::new(&path).light(pointlight()));
        shaders = shaders
            .shader(Shader::new(&path).module(&format!("{name}_folded")).light(pointlight()).fold_host(true));
    }
    let built = shaders.build_to(&mut Vec::new()).unwrap();
    let rust = std::fs::read_to_string(&built.rust).unwrap();
    assert_eq!(built.shaders.len(), names.len() * 2);
    for b in &built.shaders {
        let interface = &b.compiled.interface;
        // Every member is 4-byte aligned, so #[repr(C)] puts each right after the one before.
        let members = struct_members(&rust, &b.module);
        let mut at = 0;
        let mut fields = interface.uniforms.iter();
        for (name, ty) in &members {
            if !name.starts_with("_pad") {
                let field = fields.next().unwrap_or_else(|| panic!("{}: extra member {name}", b.module));
                assert_eq!(*name, field.name, "{}", b.module);
                assert_eq!(at, field.offset as usize, "{}: offset of {name}", b.module);
                assert!(size_of_type(ty) >= field.layout.size() as usize, "{}: {name}: {ty}", b.module);
                let n = field.layout.elements;
                let expected = match (field.layout.components, n) {
                    // An array of scalars (a constant table): each element padded to 16 bytes.
                    (1, 2..) => format!("[[f32; 4]; {n}]|[[i32; 4]; {n}]|[[u32; 4]; {n}]"),
                    (1, _) => "f32|i32|u32".into(),
                    (3, _) => "[f32; 3]".into(),
                    (4, _) => "[f32; 4]".into(),
                    (16, _) => "[[f32; 4]; 4]".into(),
                    _ => String::new(),
                };
                assert!(expected.split('|').any(|e| e == *ty), "{}: {name}: {ty} for {field:?}", b.module);
            }
            at += size_of_type(ty);
        }
        assert!(fields.next().is_none(), "{}: a field has no member", b.module);
        assert_eq!(at, interface.uniform_size as usize, "{}: size", b.module);
        let section = &rust[rust.find(&format!("pub mod {} {{", b.module)).unwrap()..];
        assert!(section.contains(&format!("pub const UNIFORM_SIZE: usize = {};", interface.uniform_size)));
        for t in &interface.textures {
            assert!(section.contains(&format!("_BINDING: u32 = {};", t.binding)), "{}", b.module);
        }
        for a in &interface.attributes {
            assert!(
                section.contains(&format!("name: {:?}, location: {}", a.name, a.location)),
                "{}",
                b.module
            );
        }
        if b.module.ends_with("_folded") {
            assert!(!interface.needs_host, "{}", b.module);
        }
    }
    // A constant table's values are a constant of the member's name, padded as the block is:
    // planet's improved noise reads Perlin's permutation in pairs (151 + 256 * 160, 160 + 256 *
    // 137, 137 + 256 * 91, ...: compiler/stdlib/noise.sl's PATINA_PERLIN_PAIRS; WGSL names that
    // end in a digit get a `_`).
    let planet = &rust[rust.find("pub mod planet {").unwrap()..];
    assert!(
        planet.contains(
            "pub const perlin_p2_: [[i32; 4]; 256] = [[41111, 0, 0, 0], [35232, 0, 0, 0], [23433, 0, 0, 0],"
        ),
        "planet's permutation table, in pairs"
    );
    // A host field says how to fill it.
    let plastic = &rust[rust.find("pub mod plastic {").unwrap()..];
    assert!(plastic.contains("computed by the shader's host part (its output `Ci_h`)"));
    assert!(plastic.contains("**Needs the host part**"));
    let textured = &rust[rust.find("pub mod textured {").unwrap()..];
    assert!(textured.contains("pub const TEXTURE_CHECKER_8_BINDING: u32 = 0;"), "{textured}");
    assert!(textured.contains("pub const LOCATION_UV: u32 = 2;"));
}
