//! The backend's own checks: modules validate, and their WGSL re-parses with naga's front end.

use crate::backend::binding::BoundLight;
use crate::backend::defaults::constant_defaults;
use crate::backend::wgsl::compile;
use crate::opt::Prepared;
use crate::syntax::preprocess::MemoryLoader;

fn program(src: &str, light_src: Option<&str>) -> super::GpuProgram {
    let checked = crate::check_source("t.sl", src, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    let shader = crate::opt::Prepared::new(checked.program.shaders[0].clone());
    let stages = crate::split::split(&shader).unwrap();
    let lights_checked = light_src.map(|l| crate::check_source("l.sl", l, &MemoryLoader::default()));
    let prepared: Vec<Prepared> =
        lights_checked.iter().flat_map(|c| c.program.shaders.iter().cloned()).map(Prepared::new).collect();
    let lights: Vec<BoundLight> =
        prepared.iter().map(|s| BoundLight { shader: s, strings: vec![], categories: vec![] }).collect();
    match compile(&stages, &lights, &[], &constant_defaults) {
        Ok(p) => p,
        Err(d) => panic!("{}", d.message),
    }
}

#[test]
fn a_constant_surface_validates_and_reparses() {
    let p = program("surface c(color k = 1) { Ci = k * s; Oi = 1; }", None);
    let wgsl = p.wgsl().unwrap();
    naga::front::wgsl::parse_str(&wgsl).unwrap_or_else(|e| panic!("{}\n{wgsl}", e.emit_to_string(&wgsl)));
    assert!(wgsl.contains("fn fs_main"), "{wgsl}");
}

#[test]
fn plastic_with_lights_validates() {
    let plastic = include_str!("../../../../examples/shaders/plastic.sl");
    let lights = include_str!("../../../../examples/shaders/lights.sl");
    let p = program(plastic, Some(lights));
    let wgsl = p.wgsl().unwrap();
    naga::front::wgsl::parse_str(&wgsl).unwrap_or_else(|e| panic!("{}\n{wgsl}", e.emit_to_string(&wgsl)));
}

/// The fragment entry hands a RenderMan light only the surface values it reads (`Ps` always:
/// `illuminate` reads it without naming it), and takes back its `Ol` only for a surface that
/// reads `Ol`: the module holds no copy that nothing reads.
#[test]
fn a_light_gets_only_the_surface_values_it_reads() {
    let point = "light pt(point from = point \"shader\" (0, 0, 0)) { illuminate(from) Cl = 1 / (L . L); }";
    let facing = "light facing(point from = point \"shader\" (0, 0, 0))
        { illuminate(from) { Cl = max(0, normalize(N) . normalize(-L)); Ol = 0.5; } }";
    let matte = "surface matte() { illuminance(P, N, PI / 2) { Ci += Cl * normalize(L) . normalize(N); } }";
    let seen = "surface seen() { illuminance(P, N, PI / 2) { Ci += Cl * Ol; } }";
    let privates = |surface: &str, light: &str| -> Vec<String> {
        let p = program(surface, Some(light));
        let module = &p.module;
        module
            .global_variables
            .iter()
            .filter(|(_, g)| g.space == naga::AddressSpace::Private)
            .filter_map(|(_, g)| g.name.clone())
            .collect()
    };
    let names = privates(matte, point);
    assert!(names.iter().any(|n| n == "l0_Ps"), "{names:?}");
    for unread in ["l0_P", "l0_N", "l0_Ol"] {
        assert!(!names.iter().any(|n| n == unread), "{unread}: {names:?}");
    }
    assert!(!names.iter().any(|n| n.starts_with("Ol")), "{names:?}");
    // A light that reads N gets it; a surface that reads Ol gets the light's.
    let names = privates(seen, facing);
    for read in ["l0_Ps", "l0_N", "l0_Ol"] {
        assert!(names.iter().any(|n| n == read), "{read}: {names:?}");
    }
}

/// Every example shader but the lights (which are compiled where they are bound: here every
/// light of lights.sl is bound to each) builds a module that validates and whose WGSL re-parses.
#[test]
fn every_example_shader_validates_and_reparses() {
    use crate::syntax::ast::ShaderKind;
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders");
    let loader = crate::syntax::preprocess::FsLoader { include_dirs: vec![] };
    let lights_src = std::fs::read_to_string(format!("{dir}/lights.sl")).unwrap();
    let lights_checked = crate::check_source("lights.sl", &lights_src, &loader);
    let prepared: Vec<Prepared> = lights_checked.program.shaders.iter().cloned().map(Prepared::new).collect();
    let lights: Vec<BoundLight> =
        prepared.iter().map(|s| BoundLight { shader: s, strings: vec![], categories: vec![] }).collect();
    let mut failures = Vec::new();
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let checked = crate::check_source(&path.display().to_string(), &text, &loader);
        for s in checked.program.shaders.iter().filter(|s| s.kind != ShaderKind::Light) {
            let s = crate::opt::Prepared::new(s.clone());
            let stages = crate::split::split(&s).unwrap();
            count += 1;
            match compile(&stages, &lights, &[], &constant_defaults) {
                Ok(p) => {
                    let wgsl = p.wgsl().unwrap();
                    if let Err(e) = naga::front::wgsl::parse_str(&wgsl) {
                        failures.push(format!(
                            "{}: {}: reparse: {}",
                            path.display(),
                            s.name,
                            e.emit_to_string(&wgsl)
                        ));
                    }
                }
                Err(d) => failures.push(format!("{}: {}: {}", path.display(), s.name, d.message)),
            }
        }
    }
    assert!(failures.is_empty(), "{} of {count} failed:\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn kernels_validate_and_lay_out_their_records() {
    let checked = crate::check_source(
        "k.sl",
        "surface k(float Kd = 0.5; uniform int n = 2) { Ci = color(Kd * s, Du(s), n); }",
        &MemoryLoader::default(),
    );
    let shader = crate::opt::Prepared::new(checked.program.shaders[0].clone());
    let k = super::compile_kernel(&shader, &[], &[], &["Kd", "n", "s", "dx(s)", "du"], &["Ci"]).unwrap();
    assert_eq!(k.input_stride, 5);
    assert_eq!(k.output_stride, 3);
    assert_eq!(k.inputs[3].offset, 3);
    assert!(super::compile_kernel(&shader, &[], &[], &["nope"], &["Ci"]).is_err());
}

/// A shader whose `pick` reads a constant table at a varying index, called three times.
const TABLE_SHADER: &str = "float pick(float i) { constant int table[4] = {5, -25, 2, -3}; return table[int(i)]; }\n\
                            surface t() { Ci = color(pick(s), pick(t), pick(s + t)); }";

#[test]
fn a_constant_table_is_one_uniform_member_shared_by_its_calls() {
    let p = program(TABLE_SHADER, None);
    let tables: Vec<_> = p
        .interface
        .uniforms
        .iter()
        .filter_map(|f| match &f.source {
            super::interface::UniformSource::Table { values } => Some((f, values.clone())),
            _ => None,
        })
        .collect();
    assert_eq!(tables.len(), 1, "one table for three calls: {:?}", p.interface.uniforms);
    let (field, values) = &tables[0];
    assert_eq!(values, &[5.0, -25.0, 2.0, -3.0]);
    assert_eq!((field.ty.as_str(), field.layout.element_stride), ("int[4]", 16));
    // The host's blank block holds the values, one per 16 bytes.
    let block = p.interface.blank_block();
    let word = |k: u32| {
        let at = (field.offset + 16 * k) as usize;
        i32::from_le_bytes(block[at..at + 4].try_into().unwrap())
    };
    assert_eq!([word(0), word(1), word(2), word(3)], [5, -25, 2, -3]);
    assert!(p.module.global_variables.iter().all(|(_, g)| g.init.is_none()), "no module variable holds it");
    let wgsl = p.wgsl().unwrap();
    assert!(!wgsl.contains("table = array"), "no store of the table:\n{wgsl}");
    naga::front::wgsl::parse_str(&wgsl).unwrap_or_else(|e| panic!("{}\n{wgsl}", e.emit_to_string(&wgsl)));
}

#[test]
fn a_kernels_constant_table_is_one_initialized_variable_shared_by_its_calls() {
    let checked = crate::check_source("k.sl", TABLE_SHADER, &MemoryLoader::default());
    let shader = crate::opt::Prepared::new(checked.program.shaders[0].clone());
    let k = super::compile_kernel(&shader, &[], &[], &["s", "t"], &["Ci"]).unwrap();
    assert_eq!(k.uniform_size, 0, "a kernel binds no uniform block for its tables");
    let module = &k.module;
    let tables: Vec<_> = module.global_variables.iter().filter(|(_, g)| g.init.is_some()).collect();
    assert_eq!(tables.len(), 1, "one table for three calls");
    let (_, g) = tables[0];
    let naga::Expression::Compose { components, .. } = &module.global_expressions[g.init.unwrap()] else {
        panic!("a composite initializer");
    };
    let values: Vec<i32> = components
        .iter()
        .map(|&c| match module.global_expressions[c] {
            naga::Expression::Literal(naga::Literal::I32(x)) => x,
            ref other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(values, [5, -25, 2, -3]);
}

#[test]
fn a_table_read_whole_stays_a_module_variable() {
    let src = "float pick(float i) { constant int table[4] = {5, -25, 2, -3}; int copy[4] = table; \
               copy[0] = int(i); return copy[int(i) + 1]; }\n\
               surface t() { Ci = color(pick(s), pick(t), 0); }";
    let p = program(src, None);
    let sources: Vec<_> = p.interface.uniforms.iter().map(|f| &f.source).collect();
    assert!(
        !sources.iter().any(|s| matches!(s, super::interface::UniformSource::Table { .. })),
        "{sources:?}"
    );
    assert_eq!(p.module.global_variables.iter().filter(|(_, g)| g.init.is_some()).count(), 1);
}

#[test]
fn a_short_arrays_run_time_reads_are_selects() {
    let src = "surface t(float a[3] = {1, 2, 3}; float b[5] = {1, 2, 3, 4, 5}) {\n\
               int i = int(s * 8) - 2; Ci = color(a[i], b[i], 0); }";
    let wgsl = program(src, None).wgsl().unwrap();
    // The index is clamped to the last element in both; only the longer array is then indexed.
    assert!(wgsl.contains("4u)]"), "{wgsl}");
    assert!(wgsl.contains("2u)"), "{wgsl}");
    assert!(!wgsl.contains("2u)]"), "{wgsl}");
}

#[test]
fn i_crosses_in_the_varying_of_p() {
    let plastic = include_str!("../../../../examples/shaders/plastic.sl");
    let lights = include_str!("../../../../examples/shaders/lights.sl");
    let p = program(plastic, Some(lights));
    let varyings = &p.interface.varyings;
    assert!(!varyings.iter().any(|v| v.name == "in_I"), "{varyings:?}");
    let in_p = varyings.iter().find(|v| v.name == "in_P").expect("P crosses");
    assert_eq!(in_p.also, ["I"]);
}

#[test]
fn pow_of_a_base_that_cannot_be_negative_is_wgsls_pow() {
    // A negative base takes the interpreter's rule (the exponent's parity, through `trunc`); a
    // base clamped to [0, 1], directly or through a variable written once, cannot take it.
    let wgsl = |body: &str| program(&format!("surface t(float e = 2) {{ {body} }}"), None).wgsl().unwrap();
    assert!(wgsl("Ci = pow(s - 0.5, e);").contains("trunc("));
    for guarded in ["Ci = pow(max(s - 0.5, 0), e);", "float b = clamp(s, 0, 1); Ci = pow(b, e);"] {
        let text = wgsl(guarded);
        assert!(text.contains("pow(") && !text.contains("trunc("), "{guarded}\n{text}");
    }
}

/// The falloff light of W. R. Mark's chapter: a Stanford light shader returns only its colour.
const FALLOFF: &str =
    "light shader float4 falloff(float4 c, float k) { return c * (1.0 / (k * Sdist + 1.0)); }";

/// A Stanford-style light binds under both styles of surface: the scene's position of it is a
/// uniform of the block, and the module validates and re-parses.
#[test]
fn a_stanford_light_reads_its_position_from_the_uniform_block() {
    use super::interface::UniformSource;
    let surfaces = [
        "surface shader float4 lit() { perlight float4 c = Cl * max(dot(N, L), 0); return integrate(c); }",
        "surface matte() { illuminance(P, N, PI / 2) { Ci += Cl * normalize(L) . normalize(N); } }",
    ];
    for surface in surfaces {
        let p = program(surface, Some(FALLOFF));
        let position = UniformSource::LightPosition { light: 0 };
        assert!(p.interface.uniforms.iter().any(|u| u.source == position), "{:?}", p.interface.uniforms);
        let wgsl = p.wgsl().unwrap();
        naga::front::wgsl::parse_str(&wgsl).unwrap_or_else(|e| panic!("{}\n{wgsl}", e.emit_to_string(&wgsl)));
    }
}

/// A RenderMan-style surface has no `Pobj` (nor `B`, `T`, ...) to give a Stanford light.
#[test]
fn a_stanford_light_reading_pobj_needs_a_stanford_surface() {
    let checked = crate::check_source("t.sl", "surface m() { Ci = 1; }", &MemoryLoader::default());
    let stages = crate::split::split(&Prepared::new(checked.program.shaders[0].clone())).unwrap();
    let light_src = "light shader float4 l(float4 c) { return c * Pobj[0] / Sdist; }";
    let light = crate::check_source("l.sl", light_src, &MemoryLoader::default());
    assert!(!light.has_errors(), "{:?}", light.diagnostics);
    let light = Prepared::new(light.program.shaders[0].clone());
    let bound = [BoundLight { shader: &light, strings: vec![], categories: vec![] }];
    let error = compile(&stages, &bound, &[], &constant_defaults).expect_err("refused");
    assert_eq!(error.code, crate::diag::Code::NotExecutable);
    assert!(error.message.contains("`Pobj`") && error.message.contains("`m`"), "{}", error.message);
}
