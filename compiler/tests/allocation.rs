//! Evaluating points allocates nothing per point: the benchmark's fBm shader over 20,000 points
//! (157 batches) makes no heap allocation at all once the evaluator exists, and neither does a
//! shader with divergent loops, `break` and inlined functions that `return`.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_compiler::syntax::preprocess::MemoryLoader;

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` came from `alloc` above with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations_during_eval(source: &str, inputs: &[(&str, usize)], n: usize) -> usize {
    let checked = patina_compiler::check_source("t.sl", source, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    let program = CpuProgram::compile(
        &patina_compiler::opt::Prepared::new(checked.program.shaders[0].clone()),
        &Binding::default(),
    )
    .unwrap();
    let mut eval = Evaluator::<f32>::new(&program);
    let columns: Vec<(patina_compiler::backend::cpu::SlotId, Vec<f32>)> = inputs
        .iter()
        .map(|(name, width)| {
            let id = program.slot(name).unwrap();
            (id, (0..n * width).map(|k| (k as f32 * 0.618).sin() * 40.0).collect())
        })
        .collect();
    let ci = program.slot("Ci").unwrap();
    let mut out = vec![0.0f32; n * 3];
    let inputs: Vec<_> = columns.iter().map(|(id, c)| (*id, c.as_slice())).collect();
    // The single test in this binary, so no other thread allocates meanwhile.
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    eval.eval(n, &inputs, &mut [(ci, &mut out)]).unwrap();
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    assert!(out.iter().any(|x| *x != 0.0), "the shader computed something");
    after - before
}

#[test]
fn evaluation_does_not_allocate() {
    let fbm = include_str!("../benches/fbm.sl");
    assert_eq!(allocations_during_eval(fbm, &[("P", 3)], 20_000), 0, "fbm");
    let control = "float f(float x) { if (x > 3) return x; return -x; }
        surface t() {
            float acc = 0, i;
            for (i = 0; i < 20; i += 1) { if (acc > s) break; acc += f(i + s); }
            Ci = acc;
        }";
    assert_eq!(allocations_during_eval(control, &[("s", 1)], 20_000), 0, "control flow");
}
