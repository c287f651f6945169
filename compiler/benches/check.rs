//! Checking each example shader end to end (preprocess, parse, types, rates), as `patina check`
//! does, with the standard-library modules it includes. Target: under 1 ms for the largest.

use criterion::{Criterion, criterion_group, criterion_main};

// The allocator the `patina` binary uses, so the numbers are the command line's.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;
use patina_compiler::check_source;
use patina_compiler::syntax::preprocess::FsLoader;

fn bench_examples(c: &mut Criterion) {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders");
    let mut files: Vec<(String, String)> = std::fs::read_dir(dir)
        .expect("examples/shaders")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "sl"))
        .map(|p| {
            (p.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read_to_string(&p).unwrap())
        })
        .collect();
    files.sort();
    let loader = FsLoader::default();
    let mut group = c.benchmark_group("check example");
    for (name, text) in &files {
        let checked = check_source(name, text, &loader);
        assert!(!checked.has_errors(), "{name} must check cleanly");
        group.bench_function(name.as_str(), |b| b.iter(|| check_source(name, text, &loader)));
    }
    group.finish();
}

criterion_group!(benches, bench_examples);
criterion_main!(benches);
