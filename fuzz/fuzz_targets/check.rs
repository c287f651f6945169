//! The whole check pipeline on arbitrary text, then, for a program without errors, every shader
//! through both backends the way the CLI and the renderer drive them: the interpreter's
//! `CpuProgram::compile` for each, and for each surface shader the split and the WGSL module
//! (validated by naga) with the file's lights and displacement bound. A backend may reject a
//! program with a diagnostic; an internal error (E0799) on a program that checked clean is a bug,
//! and so is a panic. The one E0799 that is not a bug is the WGSL translator's "cannot translate
//! this yet" (a construct only the interpreter runs, such as `break 2`): it is a known limit.
//! The IR is verified (`verify`) after the semantic stage, `opt::Prepared::new` and the split: the
//! passes do so themselves in debug builds, and this target does it again so that an optimized
//! fuzzing build (`cargo fuzz run -O`) checks it too.
#![no_main]

use libfuzzer_sys::fuzz_target;
use patina_compiler::backend::binding::{Binding, BoundLight, LightBinding};
use patina_compiler::backend::cpu::CpuProgram;
use patina_compiler::backend::defaults::constant_defaults;
use patina_compiler::backend::wgsl;
use patina_compiler::diag::{Code, Diagnostic};
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::ast::ShaderKind;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_compiler::verify::{Pass, VerifyError, verify, verify_stages};

/// The help line of the WGSL translator's known limits (`Translator::error`).
const NOT_YET: &str = "the WGSL backend cannot translate this yet";

fn not_internal(stage: &str, d: &Diagnostic) {
    let known_limit = d.help.as_deref().is_some_and(|h| h.starts_with(NOT_YET));
    assert!(d.code != Code::Internal || known_limit, "{stage}: {}", d.message);
}

/// A verification failure is a compiler bug, as a panic is.
fn verified(result: Result<(), VerifyError>) {
    if let Err(e) = result {
        panic!("{e}");
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let checked = patina_compiler::check_source("fuzz.sl", text, &MemoryLoader::default());
    let list: Vec<_> = checked.diagnostics.iter().cloned().collect();
    let _ = patina_compiler::diag::render_text(&checked.sources, &list);
    if checked.has_errors() {
        return;
    }
    let prepared: Vec<Prepared> = checked
        .program
        .shaders
        .iter()
        .map(|s| {
            verified(verify(s, Pass::Rates));
            let s = Prepared::new(s.clone());
            verified(verify(&s, Pass::Prepare));
            s
        })
        .collect();
    let lights: Vec<&Prepared> =
        prepared.iter().filter(|s| s.kind == ShaderKind::Light && !s.stanford).collect();
    let light_bindings: Vec<LightBinding> = lights.iter().map(|l| LightBinding::of(l, &[])).collect();
    let bound: Vec<BoundLight> = lights
        .iter()
        .map(|s| BoundLight { shader: s, strings: Vec::new(), categories: Vec::new() })
        .collect();
    let displacement = prepared.iter().find(|s| s.kind == ShaderKind::Displacement).map(|s| BoundLight {
        shader: s,
        strings: Vec::new(),
        categories: Vec::new(),
    });
    for shader in &prepared {
        let lights = if shader.kind == ShaderKind::Surface { light_bindings.clone() } else { Vec::new() };
        let binding = Binding { lights, strings: Vec::new() };
        if let Err(d) = CpuProgram::compile(shader, &binding) {
            not_internal("interpreter", &d);
        }
        if shader.kind != ShaderKind::Surface {
            continue;
        }
        let stages = match patina_compiler::split::split(shader) {
            Ok(stages) => {
                verified(verify_stages(&stages));
                stages
            }
            Err(d) => {
                not_internal("split", &d);
                continue;
            }
        };
        for part in [&stages.host, &stages.vertex, &stages.fragment] {
            if let Err(d) = CpuProgram::compile(part, &binding) {
                not_internal("interpreter (stage)", &d);
            }
        }
        match wgsl::compile_object(&stages, displacement.as_ref(), &bound, &[], &constant_defaults) {
            Ok(program) => {
                if let Err(d) = program.wgsl() {
                    not_internal("WGSL writer", &d);
                }
            }
            Err(d) => not_internal("WGSL backend", &d),
        }
    }
});
