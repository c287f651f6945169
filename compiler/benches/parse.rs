//! Front-end throughput: lexing, preprocessing and parsing a generated 5,000-line source (the
//! semantic stage is measured separately, in `check.rs`).
//!
//! Criterion reports the throughput in "elements" per second, and each element is one source line,
//! so it reads as lines per second (target: over a million in release).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};

// The allocator the `patina` binary uses, so the numbers are the command line's.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;
use patina_compiler::check_source;
use patina_compiler::diag::Diagnostics;
use patina_compiler::source::SourceMap;
use patina_compiler::syntax::{self, preprocess::MemoryLoader};

/// A source of about `lines` lines in the mix a real shader library has: macros, helper functions
/// with loops and branches, shaders of both styles.
pub fn generate(lines: usize) -> String {
    let mut src = String::from("#define SCALE 0.25\n#define SQ(x) ((x) * (x))\n\n");
    let mut n = 0;
    while src.lines().count() < lines {
        src.push_str(&format!(
            "// Helper {n}: a damped sum of sines.
float helper{n}(float x, y; uniform float k)
{{
    float sum = 0, weight = 1;
    for (int i = 0; i < 4; i += 1) {{
        sum += weight * sin(x * SCALE + i) * cos(y - i);
        weight *= 0.5;
    }}
    if (sum > k)
        sum = k + (sum - k) / (1 + SQ(sum - k));
    else
        sum = max(sum, -k);
    return sum;
}}

surface
shade{n}(float Ka = 1, Kd = 0.5; color tint = color (1, 0.9, 0.8); float freq = 4)
{{
    normal Nf = faceforward(normalize(N), I);
    float v = helper{n}(s * freq, t * freq, 2);
    color Ct = mix(Cs, tint, smoothstep(0, 1, v));
    Oi = Os;
    Ci = Os * Ct * (Ka * ambient() + Kd * diffuse(Nf));
}}

surface shader float4
rt{n}(vertex float4 uv, primitive group float4 tint)
{{
    vertex float4 scaled = {{uv[0] * 2, uv[1], 0, 1}};
    fragment float4 c = tint * scaled;
    return c * {{0.5, 0.5, 0.5, 1}};
}}

"
        ));
        n += 1;
    }
    src.lines().take(lines).collect::<Vec<_>>().join("\n") + "\n"
}

fn bench_parse(c: &mut Criterion) {
    let src = generate(5000);
    let lines = src.lines().count() as u64;
    let loader = MemoryLoader::default();
    let checked = check_source("gen.sl", &src, &loader);
    assert!(checked.diagnostics.iter().all(|d| !d.is_error()), "the generated source must be valid");
    let mut group = c.benchmark_group("front end");
    group.throughput(Throughput::Elements(lines));
    // Freeing the tree is not parsing (and a compiler keeps it): leave the drop out of the timing.
    group.bench_function("parse 5000 lines", |b| {
        b.iter_with_large_drop(|| {
            let mut sources = SourceMap::new();
            let root = sources.add_file("gen.sl", src.as_str(), None);
            let mut diags = Diagnostics::default();
            syntax::parse_file(&mut sources, root, &loader, &mut diags)
        })
    });
    group.bench_function("check 5000 lines (with semantics)", |b| {
        b.iter(|| check_source("gen.sl", &src, &loader))
    });
    group.finish();
}

criterion_group!(benches, bench_parse);
criterion_main!(benches);
