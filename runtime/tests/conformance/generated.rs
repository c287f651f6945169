//! Random well-typed programs (issue 11): a generator of surface shaders (`generated/generator.rs`,
//! RenderMan and Stanford style: parameters of both rates with defaults, locals of every type,
//! arrays, arithmetic, comparisons, logic, `?:`, casts and constructors, component access, the
//! built-ins, `if`/`for`/`while`/`break`/`continue`, user functions with `output` parameters and
//! early returns, `illuminance` and `perlight` values summed by `integrate` with one to three
//! lights, and calls into `noise.sl`, `fractal.sl` and `pattern.sl`), each run through the whole
//! compiler:
//!
//! 1. `check_source` reports nothing (a program is well typed by construction; a diagnostic is a
//!    bug of the generator or of the compiler);
//! 2. the render path's module (surface split into stages, the generated lights bound), built by
//!    `wgsl::compile`, which validates it with naga's validator;
//! 3. the interpreter (f32 and f64) and the compute kernel on the GPU, at [`BATCHES`] ×
//!    [`POINTS`] points, compared as below.
//!
//! **The comparison.** Inputs are f32 values (parameters and predefined variables uniform in
//! [-2, 2], colours and light colours in [0, 1]), the same for the three runs. For each output
//! component, with `c32`, `c64` the interpreter's f32 and f64 results and `g` the GPU's:
//! - *ill-conditioned points are skipped*: where `c64` is not finite, |c64| > 1e5, or
//!   |c32 − c64| > 1e-3 (1 + |c64|), f32 rounding alone changes the result macroscopically (an
//!   overflow, a cancellation, a value near a discontinuity), so two correct f32 implementations
//!   need not agree there. A point where both runs are NaN or infinite is therefore never counted
//!   as agreement; a non-finite GPU value where the interpreter's is finite is a disagreement.
//! - elsewhere `|g − c32| ≤ 2^-14 (1 + |c32|) + 64·|c32 − c64|`. The last term scales the bound
//!   with how much f32 rounding moves this output at this point (its conditioning, measured by
//!   the f64 run): a GPU that rounds one operation differently by an ulp or a few moves the
//!   result by about as much, times what the operations after it amplify. The first term covers
//!   the transcendentals (`sin cos exp` on [-8, 8]), light sums, `integrate`, the noises and
//!   fractals (lavapipe's errors: a few ulp to 9 ulp before amplification, docs/numerics.md), and
//!   lavapipe's value-changing optimizations of exact arithmetic: it reassociates constants
//!   (`(x - 3) + c` computed as `x + (c - 3)`, 1 ulp apart, as docs/numerics.md lists), and a
//!   loop `x += c; x *= mod(x, 1)` run twice came out 240 ulp from the interpreter while f32
//!   and f64 agreed to 1e-7, a difference that went away when the intermediate values were
//!   also written out. So outputs the generator calls *exact* (computed only with operations
//!   docs/numerics.md lists as bit-exact) get the same bound; the summary prints their largest
//!   error separately.
//!   Discontinuous operations take exact operands only (see `generator.rs`), so no tolerance has to
//!   absorb a branch or a `floor` that went the other way.
//!
//! **Case counts.** `cargo test -p patina-runtime --test conformance generated::` runs [`DEFAULT_CASES`]
//! programs; `PATINA_GENERATED_CASES=10000` (with `--release`) is the extended mode. The proptest
//! seed is fixed ([`DEFAULT_SEED`], or `PATINA_GENERATED_SEED`), so a run is reproducible; a
//! failure is shrunk and printed with the program's source. The test needs a GPU adapter (lavapipe
//! is enough) and panics without one, unless `PATINA_GPU=off`.

#[path = "generated/generator.rs"]
mod generator;

use crate::harness;

use std::cell::RefCell;

use crate::support::Rng;
use patina_compiler::backend::POINT_INDEX;
use patina_compiler::backend::binding::{Binding, BoundLight, LightBinding};
use patina_compiler::backend::cpu::{CpuProgram, Evaluator, SlotKind};
use patina_compiler::backend::object::{Beside, HostPart, compile_object};
use patina_compiler::backend::wgsl::{KERNEL_WORKGROUP, Lowering, compile_kernel};
use patina_compiler::ir::types::Base;
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::ast::ShaderKind;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::gpu::{self, Gpu};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseError, TestRunner};

/// Programs in a normal run (`cargo test`).
const DEFAULT_CASES: u32 = 100;
/// The proptest seed unless `PATINA_GENERATED_SEED` sets one.
const DEFAULT_SEED: u64 = 0x5eed_0011;
/// Batches of uniform values per program.
const BATCHES: usize = 3;
/// Points per batch.
const POINTS: usize = 16;

/// What one program's comparison saw.
#[derive(Default, Debug)]
struct Totals {
    programs: usize,
    compared: usize,
    skipped: usize,
    /// The largest |g − c32| over its bound.
    worst: f64,
    /// The same over the exact outputs' components only.
    worst_exact: f64,
    /// How many programs use each of [`FEATURES`].
    features: [usize; FEATURES.len()],
}

/// Source fragments whose frequency the summary reports (what the programs cover).
const FEATURES: [&str; 14] = [
    "surface shader",
    "illuminance",
    "integrate(",
    "perlight",
    "output float",
    "if (",
    "for (",
    "while (",
    "break;",
    "continue;",
    ") return",
    "] = {",
    "#include",
    "noise(",
];

/// The bound on |g − c32| (see the module documentation).
fn bound(c32: f64, c64: f64) -> f64 {
    2f64.powi(-14) * (1.0 + c32.abs()) + 64.0 * (c32 - c64).abs()
}

/// Whether f32 rounding alone moves the result too far for a comparison to mean anything.
fn ill_conditioned(c32: f64, c64: f64) -> bool {
    let moved = (c32 - c64).abs();
    !c64.is_finite() || c64.abs() > 1e5 || moved.is_nan() || moved > 1e-3 * (1.0 + c64.abs())
}

/// Compiles and runs one program; `Err` says what went wrong.
fn run(gpu: &Gpu, program: &generator::Program, totals: &mut Totals) -> Result<(), String> {
    let checked = patina_compiler::check_source("generated.sl", &program.source, &MemoryLoader::default());
    if !checked.diagnostics.is_empty() {
        let list: Vec<_> = checked.diagnostics.iter().cloned().collect();
        return Err(format!(
            "the front end reports:\n{}",
            patina_compiler::diag::render_text(&checked.sources, &list)
        ));
    }
    let shaders = checked.program.shaders;
    let surface =
        Prepared::new(shaders.iter().find(|s| s.kind == ShaderKind::Surface).ok_or("no surface")?.clone());
    let lights: Vec<Prepared> =
        shaders.into_iter().filter(|s| s.kind == ShaderKind::Light).map(Prepared::new).collect();
    if lights.len() != program.lights {
        return Err(format!("{} lights in the source, {} bound", lights.len(), program.lights));
    }
    render_module(&surface, &lights)?;

    let binding = Binding { lights: vec![LightBinding::default(); program.lights], strings: vec![] };
    let cpu =
        CpuProgram::compile(&surface, &binding).map_err(|d| format!("the interpreter: {}", d.message))?;
    let outputs: Vec<&str> = program.outputs.iter().map(|(n, _)| n.as_str()).collect();
    let inputs: Vec<(String, Base, usize, bool)> = cpu
        .slots()
        .map(|(_, s)| s)
        .filter(|s| !outputs.contains(&s.name.as_str()))
        .filter(|s| !matches!(s.kind, SlotKind::Space | SlotKind::Result | SlotKind::Param { output: true }))
        .map(|s| (s.name, s.ty.base, s.width, s.uniform))
        .collect();

    // values[input][batch * POINTS + point]: one value per point (uniform ones repeated).
    let mut rng = Rng(program.source.len() as u64 ^ 0x9e37_79b9);
    let mut values: Vec<Vec<Vec<f64>>> = Vec::new();
    for (name, base, width, uniform) in &inputs {
        let param = program.params.iter().find(|p| p.name == *name);
        let mut column = Vec::with_capacity(BATCHES * POINTS);
        for batch in 0..BATCHES {
            let mut value = Vec::new();
            for point in 0..POINTS {
                if point == 0 || !uniform {
                    value = match param {
                        Some(p) if p.defaulted => p.default.clone(),
                        _ if name == POINT_INDEX => vec![(batch * POINTS + point) as f64],
                        _ => {
                            let (lo, hi) = if ["Cs", "Os"].contains(&name.as_str()) || name.starts_with("Cl[")
                            {
                                (0.0, 1.0)
                            } else {
                                (-2.0, 2.0)
                            };
                            (0..*width).map(|_| f64::from(rng.range(lo, hi) as f32)).collect()
                        }
                    };
                    if matches!(base, Base::Bool | Base::Int | Base::Uint) && name != POINT_INDEX {
                        return Err(format!(
                            "input `{name}` of type {base:?}: the generator makes float inputs only"
                        ));
                    }
                }
                column.push(value.clone());
            }
        }
        values.push(column);
    }

    // The interpreter, batch by batch, in f32 and f64.
    let mut c32: Vec<Vec<f64>> = vec![Vec::new(); outputs.len()];
    let mut c64: Vec<Vec<f64>> = vec![Vec::new(); outputs.len()];
    let mut e32 = Evaluator::<f32>::new(&cpu);
    let mut e64 = Evaluator::<f64>::new(&cpu);
    for batch in 0..BATCHES {
        let mut columns: Vec<(&str, Vec<f64>)> = Vec::new();
        for (i, (name, _, _, uniform)) in inputs.iter().enumerate() {
            if program.params.iter().any(|p| p.name == *name && p.defaulted) {
                continue;
            }
            if *uniform {
                let v = &values[i][batch * POINTS];
                e32.set(name, v).map_err(|e| format!("setting `{name}`: {e}"))?;
                e64.set(name, v).map_err(|e| format!("setting `{name}`: {e}"))?;
            } else {
                columns
                    .push((name, (0..POINTS).flat_map(|p| values[i][batch * POINTS + p].clone()).collect()));
            }
        }
        let cols: Vec<(&str, &[f64])> = columns.iter().map(|(n, c)| (*n, c.as_slice())).collect();
        let out = e32.eval_points(POINTS, &cols, &outputs).map_err(|e| format!("interpreter f32: {e}"))?;
        c32.iter_mut().zip(out).for_each(|(all, o)| all.extend(o));
        let out = e64.eval_points(POINTS, &cols, &outputs).map_err(|e| format!("interpreter f64: {e}"))?;
        c64.iter_mut().zip(out).for_each(|(all, o)| all.extend(o));
    }

    let g = gpu_run(gpu, &surface, program.lights, &inputs, &values, &outputs)?;

    let mut failures = Vec::new();
    for (k, (name, exact_components)) in program.outputs.iter().enumerate() {
        let width = exact_components.len();
        #[allow(clippy::needless_range_loop)] // `p` indexes the point in several tables
        for p in 0..BATCHES * POINTS {
            for (c, &exact) in exact_components.iter().enumerate() {
                let i = p * width + c;
                let (a, b, gv) = (c32[k][i], c64[k][i], g[k][i]);
                if ill_conditioned(a, b) {
                    totals.skipped += 1;
                    continue;
                }
                totals.compared += 1;
                let tol = bound(a, b);
                let err = (gv - a).abs();
                if err <= tol {
                    totals.worst = totals.worst.max(err / tol);
                    if exact {
                        totals.worst_exact = totals.worst_exact.max(err / tol);
                    }
                }
                if (err.is_nan() || err > tol) && failures.len() < 4 {
                    let shown: Vec<String> = inputs
                        .iter()
                        .enumerate()
                        .map(|(j, (n, ..))| format!("{n} = {:?}", values[j][p]))
                        .collect();
                    failures.push(format!(
                        "`{name}`[{c}] at batch {} point {}: gpu {gv:e}, interpreter f32 {a:e}, f64 {b:e} \
                         (bound {tol:e}, {})\n    inputs: {}",
                        p / POINTS,
                        p % POINTS,
                        if exact { "exact" } else { "inexact" },
                        shown.join(", ")
                    ));
                }
            }
        }
    }
    totals.programs += 1;
    if totals.programs.is_multiple_of(1000) {
        // Progress of a long (extended) run.
        eprintln!("{} programs so far: {totals:?}", totals.programs);
    }
    for (count, feature) in totals.features.iter_mut().zip(FEATURES) {
        *count += usize::from(program.source.contains(feature));
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(format!("the GPU and the interpreter disagree:\n{}", failures.join("\n")))
    }
}

/// The render path: the surface split into stages and compiled with its lights into the vertex and
/// fragment module (which the WGSL backend validates with naga's validator).
fn render_module(surface: &Prepared, lights: &[Prepared]) -> Result<(), String> {
    let bound: Vec<BoundLight> = lights
        .iter()
        .map(|l| BoundLight { shader: l, strings: Vec::new(), categories: Vec::new() })
        .collect();
    let beside = Beside { lights: &bound, ..Beside::default() };
    compile_object(surface, &[], &beside, Lowering::Exact, HostPart::Interpreted)
        .map_err(|d| format!("the render path: {}", d.message))?;
    Ok(())
}

/// Runs the surface as a compute kernel over every point; one column per output.
fn gpu_run(
    gpu: &Gpu,
    surface: &Prepared,
    lights: usize,
    inputs: &[(String, Base, usize, bool)],
    values: &[Vec<Vec<f64>>],
    outputs: &[&str],
) -> Result<Vec<Vec<f64>>, String> {
    let names: Vec<&str> = inputs.iter().map(|(n, ..)| n.as_str()).collect();
    let kernel = compile_kernel(surface, &vec![LightBinding::default(); lights], &[], &names, outputs)
        .map_err(|d| format!("the kernel: {}", d.message))?;
    let total = BATCHES * POINTS;
    let stride = kernel.input_stride as usize;
    let mut words = vec![0u32; total * stride];
    for kv in &kernel.inputs {
        let i = names.iter().position(|n| *n == kv.name).expect("the kernel's inputs are ours");
        for p in 0..total {
            for (w, x) in values[i][p].iter().enumerate() {
                words[p * stride + kv.offset as usize + w] = harness::bits(*x, kv.ty.base);
            }
        }
    }
    let input: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    let out_stride = kernel.output_stride as usize;
    let groups = (total as u32).div_ceil(KERNEL_WORKGROUP);
    let bytes = gpu
        .compute(&kernel.module, "main", &[], &[&input], total * out_stride * 4, groups)
        .map_err(|e| format!("the GPU could not run the kernel: {e}"))?;
    let out: Vec<f32> =
        bytes.chunks_exact(4).map(|c| f32::from_bits(u32::from_le_bytes([c[0], c[1], c[2], c[3]]))).collect();
    Ok(kernel
        .outputs
        .iter()
        .map(|kv| {
            (0..total)
                .flat_map(|p| (0..kv.words as usize).map(move |c| (p, c)))
                .map(|(p, c)| f64::from(out[p * out_stride + kv.offset as usize + c]))
                .collect()
        })
        .collect())
}

fn env_number(name: &str) -> Option<u64> {
    let text = std::env::var(name).ok()?;
    let t = text.trim();
    let parsed = match t.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16),
        None => t.parse(),
    };
    Some(parsed.unwrap_or_else(|_| panic!("{name}={text}: expected a number")))
}

/// `PATINA_GENERATED_FILE=PATH` runs one program from a file instead (a shrunk failure, edited
/// while looking for the smallest program that still fails), with every output parameter and
/// `Ci` (or a Stanford result) compared as inexact.
#[test]
fn generated_program_from_a_file() {
    let Some(path) = std::env::var_os("PATINA_GENERATED_FILE") else { return };
    let Some(gpu) = gpu::for_tests() else { return };
    let source = std::fs::read_to_string(&path).expect("the program file");
    let program = generator::Program::from_source(source);
    let mut totals = Totals::default();
    let result = run(gpu, &program, &mut totals);
    eprintln!("{totals:?}");
    if let Err(e) = result {
        panic!("{e}");
    }
}

#[test]
fn generated_programs_compile_validate_and_agree() {
    let Some(gpu) = gpu::for_tests() else { return };
    let cases = env_number("PATINA_GENERATED_CASES").map_or(DEFAULT_CASES, |n| n as u32);
    let seed = env_number("PATINA_GENERATED_SEED").unwrap_or(DEFAULT_SEED);
    let config = Config {
        cases,
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(seed),
        max_shrink_iters: 1024,
        max_shrink_time: 120_000,
        ..Config::default()
    };
    let totals = RefCell::new(Totals::default());
    let start = std::time::Instant::now();
    let programs =
        proptest::collection::vec(any::<u8>(), 0..600).prop_map(|bytes| generator::generate(&bytes));
    let result = TestRunner::new(config).run(&programs, |program| {
        if std::env::var_os("PATINA_GENERATED_SHOW").is_some() {
            eprintln!("{program:?}");
        }
        run(gpu, &program, &mut totals.borrow_mut()).map_err(TestCaseError::fail)
    });
    let t = totals.borrow();
    eprintln!(
        "{} programs (seed {seed:#x}) in {:.1} s: {} values compared, {} skipped as ill-conditioned, \
         largest error {:.3} of its bound ({:.3} on exact outputs)",
        t.programs,
        start.elapsed().as_secs_f64(),
        t.compared,
        t.skipped,
        t.worst,
        t.worst_exact
    );
    let used: Vec<String> = FEATURES.iter().zip(t.features).map(|(f, n)| format!("`{f}` {n}")).collect();
    eprintln!("programs using: {}", used.join(", "));
    if let Err(e) = result {
        panic!("{e}");
    }
}
