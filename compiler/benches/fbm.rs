//! The interpreter against native code: a 6-octave fBm of improved gradient noise over 1M points,
//! evaluated by the interpreter from `fbm.sl` and by the same algorithm in Rust (`native_fbm.rs`),
//! in the same run. Also reports the heap: the evaluation must not allocate per point.
//!
//! `cargo bench -p patina-compiler --bench fbm`

#[path = "native_fbm.rs"]
mod native;

use std::alloc::{GlobalAlloc, Layout};
use std::hint::black_box;
use std::sync::atomic::{AtomicUsize, Ordering};

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_compiler::syntax::preprocess::MemoryLoader;

/// mimalloc (what the `patina` binary uses), counting allocations and the peak of live bytes.
struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);
static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        let live = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
        PEAK.fetch_max(live, Ordering::Relaxed);
        // SAFETY: forwarded unchanged to the inner allocator.
        unsafe { mimalloc::MiMalloc.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        // SAFETY: `ptr` came from `alloc` above with this layout.
        unsafe { mimalloc::MiMalloc.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

const POINTS: usize = 1_000_000;

fn program() -> CpuProgram {
    let checked = patina_compiler::check_source("fbm.sl", include_str!("fbm.sl"), &MemoryLoader::default());
    assert!(!checked.has_errors(), "fbm.sl does not check");
    CpuProgram::compile(
        &patina_compiler::opt::Prepared::new(checked.program.shaders[0].clone()),
        &Binding::default(),
    )
    .expect("fbm.sl compiles")
}

fn fbm(c: &mut Criterion) {
    let program = program();
    let points = native::points(POINTS);
    let perm = native::permutation();
    let mut out = vec![0.0f32; POINTS * 3];
    let mut native_out = vec![0.0f32; POINTS];

    let mut eval = Evaluator::<f32>::new(&program);
    let p = program.slot("P").expect("P");
    let ci = program.slot("Ci").expect("Ci");

    // One run outside the timing: heap use, allocations during evaluation, agreement with native.
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    PEAK.store(LIVE.load(Ordering::Relaxed), Ordering::Relaxed);
    eval.eval(POINTS, &[(p, &points)], &mut [(ci, &mut out)]).expect("evaluates");
    let allocations = ALLOCATIONS.load(Ordering::Relaxed) - before;
    let peak = PEAK.load(Ordering::Relaxed);
    for (i, o) in native_out.iter_mut().enumerate() {
        *o = native::fbm(&perm, [points[3 * i], points[3 * i + 1], points[3 * i + 2]], 6);
    }
    let mismatches = (0..POINTS).filter(|i| out[3 * i].to_bits() != native_out[*i].to_bits()).count();
    eprintln!(
        "fbm over {POINTS} points: {allocations} allocations during evaluation; peak heap {:.1} MiB \
         (inputs and outputs included); {mismatches} results differ from native in any bit",
        peak as f64 / (1 << 20) as f64
    );

    let mut group = c.benchmark_group("interpreter");
    group.throughput(Throughput::Elements(POINTS as u64));
    group.sample_size(10);
    group.bench_function("fbm 6 octaves, 1M points, interpreter f32", |b| {
        b.iter(|| eval.eval(POINTS, &[(p, &points)], &mut [(ci, &mut out)]).expect("evaluates"))
    });
    group.bench_function("fbm 6 octaves, 1M points, native f32", |b| {
        b.iter(|| {
            for (i, o) in native_out.iter_mut().enumerate() {
                let q = [points[3 * i], points[3 * i + 1], points[3 * i + 2]];
                *o = native::fbm(&perm, black_box(q), black_box(6));
            }
        })
    });
    let mut eval64 = Evaluator::<f64>::new(&program);
    let points64: Vec<f64> = points.iter().map(|x| f64::from(*x)).collect();
    let mut out64 = vec![0.0f64; POINTS * 3];
    group.bench_function("fbm 6 octaves, 1M points, interpreter f64", |b| {
        b.iter(|| eval64.eval(POINTS, &[(p, &points64)], &mut [(ci, &mut out64)]).expect("evaluates"))
    });
    group.finish();
}

criterion_group!(benches, fbm);
criterion_main!(benches);
