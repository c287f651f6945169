//! Binding against dynamic compilation (DESIGN.md §4), measured in one run: one surface shader with
//! several feature flags under 1 and 8 point lights, compiled for a scene that fixes every flag
//! (specialized) and with every parameter left dynamic. For each: the WGSL's size, naga's
//! validation time of the module, and the time of one render on the GPU (lavapipe without a GPU:
//! pipeline creation, which grows with the shader, drawing 96×96 and reading back). Criterion
//! reports each measurement; the table at the end gives the medians and the ratios (specialized ÷
//! dynamic), which docs/binding.md quotes.
//!
//! Run with `cargo bench -p patina-runtime --bench binding`.

use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use patina_runtime::gpu::Gpu;
use patina_runtime::render::{self, Backend, Options, Prepared};

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[path = "support/features.rs"]
mod features;

use features::scene;

fn validate(p: &Prepared) {
    let module = &p.objects[0].surface.gpu.module;
    let mut v =
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all());
    v.validate(module).expect("the module validates");
}

fn median(mut runs: Vec<Duration>) -> Duration {
    runs.sort();
    runs[runs.len() / 2]
}

fn time(runs: usize, mut f: impl FnMut()) -> Duration {
    median(
        (0..runs)
            .map(|_| {
                let t = Instant::now();
                f();
                t.elapsed()
            })
            .collect(),
    )
}

fn bench(c: &mut Criterion) {
    let gpu = Gpu::new().ok();
    let mut rows = Vec::new();
    for lights in [1, 8] {
        let s = scene(lights);
        let mut measured = Vec::new();
        for specialize in [true, false] {
            let p = render::prepare_with(&s, Options { specialize, ..Options::default() }).unwrap();
            let label = format!("{lights} light(s), {}", if specialize { "specialized" } else { "dynamic" });
            let wgsl = p.objects[0].surface.gpu.wgsl().unwrap().len();
            let mut group = c.benchmark_group("binding");
            group.sample_size(10).measurement_time(Duration::from_secs(3));
            group.bench_function(format!("validate, {label}"), |b| b.iter(|| validate(&p)));
            if let Some(gpu) = &gpu {
                group.bench_function(format!("render 96x96 on the GPU, {label}"), |b| {
                    b.iter(|| render::render(&p, Backend::Gpu, Some(gpu)).unwrap())
                });
            }
            group.finish();
            let validation = time(15, || validate(&p));
            let render_time =
                gpu.as_ref().map(|g| time(5, || drop(render::render(&p, Backend::Gpu, Some(g)).unwrap())));
            measured.push((wgsl, validation, render_time));
        }
        rows.push((lights, measured));
    }
    let adapter = gpu.as_ref().map_or("no GPU".to_string(), Gpu::adapter_description);
    println!("\nbinding: specialized against dynamic (medians; GPU: {adapter})");
    println!("| lights | WGSL bytes | ratio | validation | ratio | GPU render | ratio |");
    println!("|---|---|---|---|---|---|---|");
    for (lights, m) in rows {
        let (s, d) = (&m[0], &m[1]);
        let ms = |x: Duration| x.as_secs_f64() * 1e3;
        let render = match (s.2, d.2) {
            (Some(a), Some(b)) => format!("{:.1} ms vs {:.1} ms | {:.2}", ms(a), ms(b), ms(a) / ms(b)),
            _ => "- | -".into(),
        };
        println!(
            "| {lights} | {} vs {} | {:.2} | {:.3} ms vs {:.3} ms | {:.2} | {render} |",
            s.0,
            d.0,
            s.0 as f64 / d.0 as f64,
            ms(s.1),
            ms(d.1),
            ms(s.1) / ms(d.1),
        );
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
