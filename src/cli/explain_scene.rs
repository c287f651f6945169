//! `patina explain SCENE.toml`: what binding kept and left out of each shader of a scene, and why
//! (DESIGN.md §4): per object, the stages' sizes compiled for this scene against every parameter
//! left dynamic, the uniforms, varyings and textures that remain, and each removal's reason.

use std::fmt::Write as _;
use std::process::ExitCode;

use patina_compiler::bind::Decision;
use patina_compiler::source::{SourceMap, Span};
use patina_runtime::render::{self, Options, Prepared, SurfaceProgram};
use patina_runtime::scene::{Scene, ShaderRef};

pub fn run(path: &std::path::Path) -> Result<ExitCode, String> {
    let scene = Scene::load(path).map_err(|e| e.to_string())?;
    let bound = render::prepare_with(&scene, Options { specialize: true, ..Options::default() })
        .map_err(|e| e.to_string())?;
    let dynamic = render::prepare_with(&scene, Options { specialize: false, ..Options::default() })
        .map_err(|e| e.to_string())?;
    print!("{}", report(&scene, &bound, &dynamic));
    Ok(ExitCode::SUCCESS)
}

/// The whole report, object by object.
fn report(scene: &Scene, bound: &Prepared, dynamic: &Prepared) -> String {
    let mut out = String::new();
    let lights = bound.lights.len();
    let _ = writeln!(
        out,
        "{}: {} object(s), {lights} light(s) bound (each light's shader is compiled into every surface; \
         illuminance and the light sums are unrolled over exactly these)",
        scene.file.display(),
        bound.objects.len()
    );
    for (k, light) in bound.lights.iter().enumerate() {
        let decisions = &light.loaded.decisions;
        if !decisions.is_empty() {
            let _ = writeln!(out, "\nlight {k} ({})", light.loaded.shader.name);
            decisions_text(&mut out, decisions, &light.loaded.sources, &scene.lights[k].shader);
        }
    }
    for (i, ((b, d), object)) in bound.objects.iter().zip(&dynamic.objects).zip(&scene.objects).enumerate() {
        let _ = writeln!(out, "\nobject {i}: surface `{}`", b.surface.loaded.shader.name);
        decisions_text(&mut out, &b.surface.loaded.decisions, &b.surface.loaded.sources, &object.surface);
        if let (Some(d), Some(set)) = (&b.surface.displacement, &object.displacement) {
            let _ = writeln!(out, "  displacement `{}`:", d.loaded.shader.name);
            decisions_text(&mut out, &d.loaded.decisions, &d.loaded.sources, set);
        }
        if let (Some(a), Some(set)) = (&b.surface.atmosphere, &object.atmosphere) {
            let _ = writeln!(out, "  atmosphere `{}`:", a.loaded.shader.name);
            decisions_text(&mut out, &a.loaded.decisions, &a.loaded.sources, set);
        }
        sizes(&mut out, &b.surface, &d.surface);
        interface(&mut out, &b.surface, &d.surface);
    }
    if let (Some(imager), Some(set)) = (&bound.imager, &scene.imager) {
        let _ = writeln!(out, "\nimager `{}`", imager.loaded.shader.name);
        decisions_text(&mut out, &imager.loaded.decisions, &imager.loaded.sources, set);
    }
    out
}

/// Where a span is, as `file:line`.
fn place(sources: &SourceMap, span: Span) -> String {
    let file = sources.file(span.file);
    let (line, _) = file.line_column(span.start as usize);
    format!("{}:{line}", file.name)
}

/// What binding decided for one shader; `set` is the scene's entry for it, which tells the values
/// it sets from the defaults it leaves.
fn decisions_text(out: &mut String, decisions: &[Decision], sources: &SourceMap, set: &ShaderRef) {
    if decisions.is_empty() {
        let _ = writeln!(out, "  nothing fixed: every parameter stays in the uniform block");
        return;
    }
    for d in decisions {
        let _ = match d {
            Decision::Folded { name, value } => {
                let v: Vec<String> = value.iter().map(|x| format!("{x}")).collect();
                let default = if set.params.contains_key(name) { "" } else { " (its default)" };
                writeln!(out, "  folded     `{name}` = {}{default}", v.join(", "))
            }
            Decision::Branch { condition, taken, because } => writeln!(
                out,
                "  decided    the condition at {} is always {taken}: the {} side is gone (because of {})",
                place(sources, *condition),
                if *taken { "false" } else { "true" },
                names(because)
            ),
            Decision::Loop { condition, because } => writeln!(
                out,
                "  decided    the loop at {} never runs: it is gone (because of {})",
                place(sources, *condition),
                names(because)
            ),
            Decision::UnconsumedOutput { name } => writeln!(
                out,
                "  removed    output `{name}`: the renderer does not read it (only Ci, Oi or the result)"
            ),
            Decision::DeadVariable { name, declared } => writeln!(
                out,
                "  removed    `{name}` ({}): only removed code read it",
                place(sources, *declared)
            ),
        };
    }
}

fn names(list: &[String]) -> String {
    list.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
}

/// The stages' sizes, bound against dynamic.
fn sizes(out: &mut String, b: &SurfaceProgram, d: &SurfaceProgram) {
    let wgsl = |p: &SurfaceProgram| p.gpu.wgsl().map_or(0, |w| w.len());
    let naga = |p: &SurfaceProgram| {
        let m = &p.gpu.module;
        m.functions.iter().map(|(_, f)| f.expressions.len()).sum::<usize>()
            + m.entry_points.iter().map(|e| e.function.expressions.len()).sum::<usize>()
    };
    let _ = writeln!(out, "  {:<42} {:>10} {:>10}", "", "this scene", "dynamic");
    let rows = [
        (
            "vertex stage (interpreter instructions)",
            b.vertex.instruction_count(),
            d.vertex.instruction_count(),
        ),
        (
            "fragment stage (interpreter instructions)",
            b.fragment.instruction_count(),
            d.fragment.instruction_count(),
        ),
        ("naga expressions", naga(b), naga(d)),
        ("WGSL bytes", wgsl(b), wgsl(d)),
    ];
    for (what, x, y) in rows {
        let _ = writeln!(out, "  {what:<42} {x:>10} {y:>10}");
    }
}

/// What the GPU program reads from outside, and what binding left out of it.
fn interface(out: &mut String, b: &SurfaceProgram, d: &SurfaceProgram) {
    let bi = &b.gpu.interface;
    let di = &d.gpu.interface;
    let list = |out: &mut String, what: &str, kept: Vec<String>, all: Vec<String>, why: &str| {
        let gone: Vec<&String> = all.iter().filter(|n| !kept.contains(n)).collect();
        let _ =
            writeln!(out, "  {what:<10} {}", if kept.is_empty() { "(none)".into() } else { kept.join(", ") });
        if !gone.is_empty() {
            let g: Vec<&str> = gone.iter().map(|s| s.as_str()).collect();
            let _ = writeln!(out, "  {:<10} left out: {} ({why})", "", g.join(", "));
        }
    };
    let uniforms = |i: &patina_compiler::backend::wgsl::interface::Interface| {
        i.uniforms.iter().map(|u| u.name.clone()).collect::<Vec<_>>()
    };
    let varyings = |i: &patina_compiler::backend::wgsl::interface::Interface| {
        i.varyings.iter().map(|v| v.name.clone()).collect::<Vec<_>>()
    };
    let textures = |i: &patina_compiler::backend::wgsl::interface::Interface| {
        i.textures.iter().map(|t| t.name.clone()).collect::<Vec<_>>()
    };
    list(out, "uniforms", uniforms(bi), uniforms(di), "folded, or read only by removed code");
    list(out, "varyings", varyings(bi), varyings(di), "read only by removed code");
    list(out, "textures", textures(bi), textures(di), "sampled only by removed code");
}
