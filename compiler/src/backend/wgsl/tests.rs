//! The backend's own checks: modules validate, and their WGSL re-parses with naga's front end.

use crate::backend::wgsl::{BoundLight, compile};
use crate::syntax::preprocess::MemoryLoader;

fn program(src: &str, light_src: Option<&str>) -> super::GpuProgram {
    let checked = crate::check_source("t.sl", src, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    let mut shader = checked.program.shaders[0].clone();
    crate::opt::prepare(&mut shader);
    let stages = crate::split::split(&shader).unwrap();
    let lights_checked = light_src.map(|l| crate::check_source("l.sl", l, &MemoryLoader::default()));
    let lights: Vec<BoundLight> = lights_checked
        .iter()
        .flat_map(|c| c.program.shaders.iter())
        .map(|s| BoundLight { shader: s, strings: vec![], categories: vec![] })
        .collect();
    match compile(&stages, &lights, &[]) {
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

/// Every example shader but the lights (which are compiled where they are bound: here every
/// light of lights.sl is bound to each) builds a module that validates and whose WGSL re-parses.
#[test]
fn every_example_shader_validates_and_reparses() {
    use crate::syntax::ast::ShaderKind;
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders");
    let loader = crate::syntax::preprocess::FsLoader { include_dirs: vec![] };
    let lights_src = std::fs::read_to_string(format!("{dir}/lights.sl")).unwrap();
    let lights_checked = crate::check_source("lights.sl", &lights_src, &loader);
    let lights: Vec<BoundLight> = lights_checked
        .program
        .shaders
        .iter()
        .map(|s| BoundLight { shader: s, strings: vec![], categories: vec![] })
        .collect();
    let mut failures = Vec::new();
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let checked = crate::check_source(&path.display().to_string(), &text, &loader);
        for s in checked.program.shaders.iter().filter(|s| s.kind != ShaderKind::Light) {
            let mut s = s.clone();
            crate::opt::prepare(&mut s);
            let stages = crate::split::split(&s).unwrap();
            count += 1;
            match compile(&stages, &lights, &[]) {
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
    let mut shader = checked.program.shaders[0].clone();
    crate::opt::prepare(&mut shader);
    let k = super::compile_kernel(&shader, &[], &[], &["Kd", "n", "s", "dx(s)", "du"], &["Ci"]).unwrap();
    assert_eq!(k.input_stride, 5);
    assert_eq!(k.output_stride, 3);
    assert_eq!(k.inputs[3].offset, 3);
    assert!(super::compile_kernel(&shader, &[], &[], &["nope"], &["Ci"]).is_err());
}

#[test]
fn a_constant_integer_table_is_one_initialized_variable_shared_by_its_calls() {
    let src = "float pick(float i) { constant int table[4] = {5, -25, 2, -3}; return table[int(i)]; }\n\
               surface t() { Ci = color(pick(s), pick(t), pick(s + t)); }";
    let p = program(src, None);
    let module = &p.module;
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
    let wgsl = p.wgsl().unwrap();
    assert!(!wgsl.contains("table = array"), "no store of the table:\n{wgsl}");
    naga::front::wgsl::parse_str(&wgsl).unwrap_or_else(|e| panic!("{}\n{wgsl}", e.emit_to_string(&wgsl)));
}
