//! The split of long `else if` chains (issue 23: placement walked a chain once per link, 17.5 s
//! for 1,000 branches): one chain of 1,000 branches, and ten of 1,000 (10,000 branches; a block
//! holds at most 1,024, docs/limits.md). Linear now: the second takes about ten times the first.

use criterion::{Criterion, criterion_group, criterion_main};
use patina_compiler::syntax::preprocess::MemoryLoader;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// A surface with `chains` chains of `branches` branches each, on a fragment-rate condition.
fn chains(chains: usize, branches: usize) -> patina_compiler::opt::Prepared {
    let mut src = String::from("surface chain() {\n    float v = 0;\n");
    for c in 0..chains {
        // Each chain in a block of its own: a block holds at most 1,024 `else`s.
        src.push_str(&format!("    {{\n    if (s < 0) v += {c};\n"));
        for i in 1..branches {
            src.push_str(&format!("    else if (s < {i}.0 / {branches}.0) v += {i};\n"));
        }
        src.push_str("    }\n");
    }
    src.push_str("    Ci = v;\n}\n");
    let checked = patina_compiler::check_source("chain.sl", &src, &MemoryLoader::default());
    assert!(!checked.has_errors(), "the chains check");
    patina_compiler::opt::Prepared::new(checked.program.shaders.into_iter().next().expect("one shader"))
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("split else-if chains");
    group.sample_size(10);
    for (label, n) in [("1,000 branches", 1), ("10,000 branches in 10 chains", 10)] {
        let shader = chains(n, 1000);
        group
            .bench_function(label, |b| b.iter(|| patina_compiler::split::split(&shader).expect("it splits")));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
