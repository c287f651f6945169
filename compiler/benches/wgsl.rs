//! Compile time of each example surface shader, from source text to WGSL text (check,
//! derivatives, split, naga module, validation, WGSL writer), against the time naga's own WGSL
//! front end takes to parse and validate the WGSL we emit, measured in the same run. Target: a
//! ratio of at most 2. The shaders are bound to every light of `examples/shaders/lights.sl`.
//!
//! Criterion reports each measurement; the summary table at the end gives the medians and ratios.

use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use patina_compiler::backend::binding::BoundLight;
use patina_compiler::backend::defaults::constant_defaults;
use patina_compiler::backend::wgsl;
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::ast::ShaderKind;
use patina_compiler::syntax::preprocess::FsLoader;

// The allocator the `patina` binary uses, so the numbers are the command line's.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn examples() -> Vec<(String, String)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders");
    let mut files: Vec<(String, String)> = std::fs::read_dir(dir)
        .expect("examples/shaders")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "sl"))
        .map(|p| (p.display().to_string(), std::fs::read_to_string(&p).unwrap()))
        .collect();
    files.sort();
    files
}

fn lights() -> Vec<Prepared> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders/lights.sl");
    let text = std::fs::read_to_string(path).unwrap();
    let checked = patina_compiler::check_source(path, &text, &FsLoader::default());
    checked.program.shaders.into_iter().map(patina_compiler::opt::Prepared::new).collect()
}

/// Source text to WGSL text, for every surface shader of a file; `None` when one of them cannot
/// be compiled for the GPU yet.
fn compile(name: &str, text: &str, lights: &[Prepared]) -> Option<Vec<String>> {
    let checked = patina_compiler::check_source(name, text, &FsLoader::default());
    let bound: Vec<BoundLight> = lights
        .iter()
        .map(|s| BoundLight { shader: s, strings: Vec::new(), categories: Vec::new() })
        .collect();
    let mut out = Vec::new();
    for shader in checked.program.shaders.iter().filter(|s| s.kind == ShaderKind::Surface) {
        let shader = patina_compiler::opt::Prepared::new(shader.clone());
        let stages = patina_compiler::split::split(&shader).ok()?;
        let program = wgsl::compile(&stages, &bound, &[], &constant_defaults).ok()?;
        out.push(program.wgsl().ok()?);
    }
    Some(out)
}

fn naga_front_end(wgsl: &[String]) {
    for text in wgsl {
        let module = naga::front::wgsl::parse_str(text).expect("our WGSL re-parses");
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::empty())
            .validate(&module)
            .expect("and validates");
    }
}

fn median(mut f: impl FnMut(), runs: usize) -> Duration {
    let mut times: Vec<Duration> = (0..runs)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed()
        })
        .collect();
    times.sort();
    times[runs / 2]
}

fn bench(c: &mut Criterion) {
    let lights = lights();
    let mut rows = Vec::new();
    let mut group = c.benchmark_group("wgsl");
    for (path, text) in examples() {
        let name = path.rsplit('/').next().unwrap_or(&path).to_string();
        let Some(wgsl) = compile(&path, &text, &lights) else { continue };
        if wgsl.is_empty() {
            continue;
        }
        group.bench_function(format!("patina {name}"), |b| b.iter(|| compile(&path, &text, &lights)));
        group.bench_function(format!("naga front end {name}"), |b| b.iter(|| naga_front_end(&wgsl)));
        let ours = median(|| drop(compile(&path, &text, &lights)), 200);
        let naga = median(|| naga_front_end(&wgsl), 200);
        rows.push((name, ours, naga));
    }
    group.finish();
    println!("\n| shader | patina: source to WGSL | naga: parse + validate that WGSL | ratio |");
    println!("|---|---|---|---|");
    for (name, ours, naga) in &rows {
        let ratio = ours.as_secs_f64() / naga.as_secs_f64();
        println!(
            "| {name} | {:.1} µs | {:.1} µs | {ratio:.2} |",
            ours.as_secs_f64() * 1e6,
            naga.as_secs_f64() * 1e6
        );
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
