//! Runs one shader on both backends over the same inputs and compares the named outputs.
//!
//! The interpreter evaluates the shader in batches: every uniform input (a `uniform` parameter, a
//! light's values) is set once per batch, every varying input is a column of per-point values.
//! The GPU runs the same differentiated shader as a compute kernel over all batches' points at
//! once, each point's record carrying its batch's uniform values. Float outputs are compared with
//! the interpreter's f32 run; integer outputs with its f64 run, whose integer registers are the
//! same but whose inputs and outputs pass through f64 without rounding (an f32 run rounds integers
//! above 2^24 on the way in and out).

use patina_compiler::backend::binding::{Binding, LightBinding};
use patina_compiler::backend::cpu::{CpuProgram, Evaluator, SlotKind};
use patina_compiler::backend::wgsl::{KERNEL_WORKGROUP, Lowering, compile_kernel_lowered};
use patina_compiler::ir::types::{Base, Type};
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::gpu::Gpu;

/// How a GPU output must relate to the interpreter's.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Tol {
    /// The same bits (any NaN matches any NaN).
    Exact,
    /// The same bits, except that +0 and -0 match (results of `min` and `max` of zeros, whose
    /// sign WGSL does not fix).
    ZeroSign,
    /// `|gpu - cpu| <= abs + rel * |cpu|`.
    Near { abs: f64, rel: f64 },
    /// At most this many units in the last place apart.
    Ulp(u32),
    /// An integer or boolean result: the same 32 bits, compared with the interpreter's f64 run.
    Int,
}

impl Tol {
    /// An absolute bound.
    pub const fn abs(abs: f64) -> Tol {
        Tol::Near { abs, rel: 0.0 }
    }

    /// A relative bound (with an absolute floor for results near zero).
    pub const fn rel(rel: f64, abs: f64) -> Tol {
        Tol::Near { abs, rel }
    }

    pub(crate) fn accepts(self, gpu: f32, cpu: f32) -> bool {
        if gpu.to_bits() == cpu.to_bits() || (gpu.is_nan() && cpu.is_nan()) {
            return true;
        }
        match self {
            Tol::Exact | Tol::Int => false,
            Tol::ZeroSign => gpu == 0.0 && cpu == 0.0,
            _ if !gpu.is_finite() || !cpu.is_finite() => false,
            Tol::Near { abs, rel } => {
                (f64::from(gpu) - f64::from(cpu)).abs() <= abs + rel * f64::from(cpu.abs())
            }
            Tol::Ulp(n) => ulps(gpu, cpu) <= u64::from(n),
        }
    }
}

/// The distance in units in the last place between two finite floats.
pub(crate) fn ulps(a: f32, b: f32) -> u64 {
    let key = |x: f32| {
        let i = x.to_bits() as i32;
        // Map the bits to a line on which adjacent floats are adjacent integers.
        if i < 0 { i64::from(i32::MIN) - i64::from(i) } else { i64::from(i) }
    };
    (key(a) - key(b)).unsigned_abs()
}

/// One input the values generator is asked for.
pub struct Input<'a> {
    /// The slot's name (`Kd`, `P`, `dx(s)`, `L[0]`).
    pub name: &'a str,
    /// Its type.
    pub ty: Type,
    /// Whether it has one value per batch.
    pub uniform: bool,
    /// The batch.
    pub batch: usize,
    /// The point within the batch (0 for uniform inputs).
    pub point: usize,
}

/// A shader to run on both backends.
pub struct Spec {
    /// Its source (the first shader in it is run).
    pub src: String,
    /// The bound lights (their `L[k]`, `Cl[k]` are inputs).
    pub lights: Vec<LightBinding>,
    /// Batches (each with its own uniform values).
    pub batches: usize,
    /// Points per batch.
    pub points: usize,
    /// The outputs to compare, with their tolerances.
    pub outputs: Vec<(String, Tol)>,
    /// The prefix of the inputs to print with a mismatch of an output (e.g. `o3m1_0` -> `c3a`:
    /// the inputs of the case that failed; an empty prefix prints every input).
    pub related: fn(&str) -> String,
    /// How the kernel writes the built-ins (the tolerances are the caller's to fit).
    pub lowering: Lowering,
}

/// Compiles and runs `spec` on both backends and panics with a report of every output outside
/// its tolerance. Returns the number of values compared.
pub fn run(gpu: &Gpu, spec: &Spec, values: &dyn Fn(&Input) -> Vec<f64>) -> usize {
    let checked = patina_compiler::check_source("conformance.sl", &spec.src, &MemoryLoader::default());
    if checked.has_errors() {
        let msgs: Vec<String> = checked.diagnostics.iter().map(|d| d.message.clone()).collect();
        panic!("the test shader does not check:\n{}\n{}", msgs.join("\n"), numbered(&spec.src));
    }
    let shader = &Prepared::new(checked.program.shaders[0].clone());
    let binding = Binding { lights: spec.lights.clone(), strings: vec![] };
    let program = CpuProgram::compile(shader, &binding)
        .unwrap_or_else(|d| panic!("the interpreter rejects the test shader: {}", d.message));

    // Inputs: every slot the caller can fill, except the outputs.
    let outputs: Vec<&str> = spec.outputs.iter().map(|(n, _)| n.as_str()).collect();
    let inputs: Vec<(String, Type, bool)> = program
        .slots()
        .map(|(_, s)| s)
        .filter(|s| !outputs.contains(&s.name.as_str()))
        .filter(|s| !matches!(s.kind, SlotKind::Space | SlotKind::Result | SlotKind::Param { output: true }))
        .map(|s| (s.name, s.ty, s.uniform))
        .collect();
    let (batches, points) = (spec.batches, spec.points);
    // values[input][batch][point] (uniform inputs: one point).
    let table: Vec<Vec<Vec<Vec<f64>>>> = inputs
        .iter()
        .map(|(name, ty, uniform)| {
            (0..batches)
                .map(|batch| {
                    let n = if *uniform { 1 } else { points };
                    (0..n)
                        .map(|point| {
                            // What `random()` hashes: give both backends the same point indices.
                            if name == patina_compiler::backend::POINT_INDEX {
                                return vec![(batch * points + point) as f64];
                            }
                            let v = values(&Input { name, ty: *ty, uniform: *uniform, batch, point });
                            assert_eq!(v.len(), width(*ty), "values for `{name}`");
                            v
                        })
                        .collect()
                })
                .collect()
        })
        .collect();
    let value_at = |i: usize, batch: usize, point: usize| -> &[f64] {
        let per = &table[i][batch];
        &per[if inputs[i].2 { 0 } else { point }]
    };

    // The interpreter, batch by batch, in f32 (and f64 for integer outputs).
    let wants_int = spec.outputs.iter().any(|(_, t)| *t == Tol::Int);
    let mut cpu32: Vec<Vec<f64>> = vec![Vec::new(); outputs.len()];
    let mut cpu64: Vec<Vec<f64>> = vec![Vec::new(); outputs.len()];
    let mut e32 = Evaluator::<f32>::new(&program);
    let mut e64 = Evaluator::<f64>::new(&program);
    for batch in 0..batches {
        let mut columns: Vec<(&str, Vec<f64>)> = Vec::new();
        for (i, (name, _, uniform)) in inputs.iter().enumerate() {
            if *uniform {
                let v = value_at(i, batch, 0);
                e32.set(name, v).unwrap_or_else(|e| panic!("setting `{name}`: {e}"));
                e64.set(name, v).unwrap_or_else(|e| panic!("setting `{name}`: {e}"));
            } else {
                columns.push((name, (0..points).flat_map(|p| value_at(i, batch, p).to_vec()).collect()));
            }
        }
        let cols: Vec<(&str, &[f64])> = columns.iter().map(|(n, c)| (*n, c.as_slice())).collect();
        let out = e32.eval_points(points, &cols, &outputs).unwrap_or_else(|e| panic!("interpreter: {e}"));
        for (k, o) in out.into_iter().enumerate() {
            cpu32[k].extend(o);
        }
        if wants_int {
            let out = e64.eval_points(points, &cols, &outputs).unwrap_or_else(|e| panic!("interpreter: {e}"));
            for (k, o) in out.into_iter().enumerate() {
                cpu64[k].extend(o);
            }
        }
    }

    // The GPU: one kernel over every batch's points.
    let names: Vec<&str> = inputs.iter().map(|(n, _, _)| n.as_str()).collect();
    let kernel = compile_kernel_lowered(shader, &spec.lights, &[], &names, &outputs, spec.lowering)
        .unwrap_or_else(|d| panic!("the WGSL backend rejects the test shader: {}", d.message));
    let total = batches * points;
    let mut record = Vec::with_capacity(total * kernel.input_stride as usize * 4);
    for batch in 0..batches {
        for point in 0..points {
            let mut words = vec![0u32; kernel.input_stride as usize];
            for kv in &kernel.inputs {
                let i = names.iter().position(|n| *n == kv.name).expect("the kernel's inputs are ours");
                for (w, x) in value_at(i, batch, point).iter().enumerate() {
                    words[(kv.offset as usize) + w] = bits(*x, kv.ty.base);
                }
            }
            record.extend(words.iter().flat_map(|w| w.to_le_bytes()));
        }
    }
    let out_len = total * kernel.output_stride as usize * 4;
    let groups = (total as u32).div_ceil(KERNEL_WORKGROUP);
    let bytes = gpu
        .compute(&kernel.module, "main", &[], &[&record], out_len, groups)
        .unwrap_or_else(|e| panic!("the GPU could not run the kernel: {e}"));
    let words: Vec<u32> =
        bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();

    // Compare (and, with PATINA_CONFORMANCE_REPORT set, print each output's largest difference).
    let report = std::env::var_os("PATINA_CONFORMANCE_REPORT").is_some();
    let mut failures = Vec::new();
    let mut compared = 0;
    for (k, (name, tol)) in spec.outputs.iter().enumerate() {
        let kv = kernel.outputs.iter().find(|o| o.name == *name).expect("every output is laid out");
        let w = kv.words as usize;
        let mut bad = 0;
        let mut first = None;
        let (mut max_abs, mut max_ulp) = (0.0f64, 0u64);
        for p in 0..total {
            for c in 0..w {
                let word = words[p * kernel.output_stride as usize + kv.offset as usize + c];
                compared += 1;
                let ok = match (tol, kv.ty.base) {
                    (Tol::Int, _) => f64::from(word) == cpu64[k][p * w + c],
                    (_, Base::Bool | Base::Int | Base::Uint) => f64::from(word) == cpu32[k][p * w + c],
                    _ => {
                        let (g, r) = (f32::from_bits(word), cpu32[k][p * w + c] as f32);
                        if g.is_finite() && r.is_finite() {
                            max_abs = max_abs.max((f64::from(g) - f64::from(r)).abs());
                            max_ulp = max_ulp.max(ulps(g, r));
                        }
                        tol.accepts(g, r)
                    }
                };
                if !ok {
                    bad += 1;
                    if first.is_none() {
                        let cpu = if *tol == Tol::Int { cpu64[k][p * w + c] } else { cpu32[k][p * w + c] };
                        first = Some((p, c, word, cpu));
                    }
                }
            }
        }
        if report && !matches!(tol, Tol::Int) {
            eprintln!("{name:>12} {tol:?}: max |gpu - cpu| {max_abs:e}, max {max_ulp} ulp");
        }
        if let Some((p, c, word, cpu)) = first {
            let (batch, point) = (p / points, p % points);
            let prefix = (spec.related)(name);
            let shown: Vec<String> = inputs
                .iter()
                .enumerate()
                .filter(|(_, (n, _, _))| n.starts_with(&prefix))
                .map(|(i, (n, _, _))| format!("{n} = {:?}", value_at(i, batch, point)))
                .collect();
            let gpu_f = f32::from_bits(word);
            failures.push(format!(
                "`{name}` ({tol:?}): {bad} of {} values differ; first at batch {batch} point {point} \
                 component {c}: gpu {gpu_f:e} (bits {word:#010x}), interpreter {cpu:e} (bits {:#010x}){}\n    inputs: {}",
                total * w,
                (cpu as f32).to_bits(),
                if kv.ty.base.components() == 1 && !matches!(kv.ty.base, Base::Float) {
                    format!(" [integer word {word}]")
                } else {
                    String::new()
                },
                shown.join(", ")
            ));
        }
    }
    if report {
        eprintln!("{} outputs, {compared} values compared", spec.outputs.len());
    }
    assert!(
        failures.is_empty(),
        "\n{} of {} outputs disagree:\n{}\n\nshader:\n{}",
        failures.len(),
        spec.outputs.len(),
        failures.join("\n"),
        numbered(&spec.src)
    );
    compared
}

/// The words (components) of a value of type `ty`.
pub fn width(ty: Type) -> usize {
    (ty.base.components() * ty.array.unwrap_or(1).max(1)) as usize
}

/// A value as the kernel's input word: floats as f32 bits, integers as their 32 bits, booleans
/// as 0 or 1.
pub fn bits(x: f64, base: Base) -> u32 {
    match base {
        Base::Int => (x as i64) as i32 as u32,
        Base::Uint => x as u32,
        Base::Bool => u32::from(x != 0.0),
        _ => (x as f32).to_bits(),
    }
}

fn numbered(src: &str) -> String {
    src.lines().enumerate().map(|(i, l)| format!("{:4} | {l}\n", i + 1)).collect()
}
