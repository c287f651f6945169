//! The render times behind docs/error-vs-time.md, under criterion's statistics: the soft sphere
//! (ray-march steps) and the zone plate (antialiasing: point, analytic, in-shader k×k) at each
//! setting of their knobs, on the GPU (when there is an adapter) and the CPU reference, 64×64.
//! `patina bench` measures the same renders with their errors; this bench gives their times a
//! confidence interval.
//!
//! Run with `cargo bench -p patina-runtime --bench sweep`.

use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use patina_runtime::gpu::Gpu;
use patina_runtime::render::{self, Backend};
use patina_runtime::scene::Scene;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// `examples/scenes/NAME.toml` at 64×64.
fn scene(name: &str) -> Scene {
    let path = format!("{}/../examples/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let mut scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    (scene.output.width, scene.output.height) = (64, 64);
    scene
}

fn bench(c: &mut Criterion) {
    let gpu = Gpu::new().ok();
    let mut backends = vec![Backend::Cpu];
    if gpu.is_some() {
        backends.insert(0, Backend::Gpu);
    }
    for (name, knob, labels) in [
        ("soft_sphere", "steps", &["8", "32", "128"][..]),
        ("zone_plate", "antialias", &["point", "analytic", "4x4"][..]),
    ] {
        let base = scene(name);
        let knob = base.knob(knob).expect("the scene's knob");
        let mut group = c.benchmark_group(format!("{name} {}", knob.name));
        group.sample_size(10).measurement_time(Duration::from_secs(4));
        for label in labels {
            let setting = knob.setting(label).expect("a listed setting");
            let prepared = render::prepare(&base.with_setting(&setting)).unwrap_or_else(|e| panic!("{e}"));
            for &backend in &backends {
                let id = format!("{label} {}", if backend == Backend::Gpu { "gpu" } else { "cpu" });
                group.bench_function(id, |b| {
                    b.iter(|| render::render(&prepared, backend, gpu.as_ref()).expect("the render"))
                });
            }
        }
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
