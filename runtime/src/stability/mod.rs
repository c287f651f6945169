//! The extreme-input sweep (`patina stability`): every function of the standard library or of a
//! user's file, and each surface shader, run over extreme arguments on the interpreter in f64 and
//! f32 and on the GPU kernel, counting non-finite results at finite inputs and measuring how far
//! the backends disagree. See docs/stability.md.
//!
//! The error of a value `x` against a reference `r` is `|x - r| / max(1, |r|)`: absolute for
//! results within [-1, 1] (colours, densities, noise), relative beyond (coordinates, lengths),
//! so one number is meaningful across functions whose results differ by thirty orders of
//! magnitude. Points where either value is not finite are counted, not measured.

pub mod args;
pub mod preconditions;
pub mod subjects;
pub mod table;

use patina_compiler::backend::cpu::scalar::Real;
use patina_compiler::backend::cpu::{EvalError, Evaluator};
use patina_compiler::syntax::preprocess::SourceLoader;

use crate::gpu::Gpu;
use crate::kernel::{Resources, run_prepared};
use args::{Points, points};
use patina_compiler::backend::cpu::Texture;
use patina_compiler::backend::wgsl::Lowering;
pub use subjects::{Subject, subjects};

/// How the sweep runs.
#[derive(Copy, Clone, Debug)]
pub struct Options {
    /// Random combinations of extremes per subject, after the systematic ones.
    pub random: usize,
    /// The seed of the random combinations.
    pub seed: u64,
    /// The most iterations any loop of the interpreter may run (a loop the arguments make
    /// endless is reported, and then not run on the GPU); by default the interpreter's own,
    /// which is also lavapipe's loop limit.
    pub budget: u64,
}

impl Default for Options {
    fn default() -> Self {
        Options { random: 64, seed: 0x5EED, budget: patina_compiler::backend::MAX_LOOP_ITERATIONS }
    }
}

/// The backends, as the report names them.
pub const BACKENDS: [&str; 3] = ["f64", "f32", "gpu"];

/// A finite input that produced a non-finite output (or an endless loop).
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// `f64`, `f32` or `gpu`.
    pub backend: &'static str,
    /// The input, as `name=value` pairs.
    pub input: String,
    /// What came out: `result = NaN`, or why the evaluation stopped.
    pub output: String,
}

/// What the sweep measured of one subject.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Measures {
    /// Points with a non-finite output, per backend of [`BACKENDS`] (`None`: not run).
    pub nonfinite: [Option<usize>; 3],
    /// The largest error (see the module comment) of the f32 interpreter against f64.
    pub f32_vs_f64: f64,
    /// The largest error of the GPU against the f32 interpreter (`None`: not run).
    pub gpu_vs_f32: Option<f64>,
    /// The largest error of the GPU in the fast lowering (`Lowering::Fast`, what users' modules
    /// compute by default) against the f64 interpreter (`None`: not run).
    pub fast_vs_f64: Option<f64>,
    /// The first failure of each backend that had one.
    pub failures: Vec<Failure>,
    /// Why the GPU did not run, when it was asked to and could not.
    pub gpu_error: Option<String>,
}

/// One row of the report.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The file of the subject.
    pub file: String,
    /// The subject, e.g. `soft_sphere(point, point, float, float)`.
    pub label: String,
    /// Points swept.
    pub points: usize,
    /// The measures, or why the subject was not swept.
    pub outcome: Result<Measures, String>,
}

impl Row {
    /// Whether a finite input produced a non-finite output (or an endless loop) here.
    pub fn failed(&self) -> bool {
        self.outcome.as_ref().is_ok_and(|m| !m.failures.is_empty())
    }
}

/// Sweeps one subject: compiled from `loader`'s view of its file, on both interpreters and, with
/// `gpu`, on the GPU kernel.
pub fn sweep(subject: &Subject, loader: &dyn SourceLoader, options: &Options, gpu: Option<&Gpu>) -> Row {
    let mut row = Row {
        file: subject.file.clone(),
        label: subject.label.clone(),
        points: 0,
        outcome: Err(String::new()),
    };
    let build = match &subject.build {
        Ok(build) => build,
        Err(why) => {
            row.outcome = Err(format!("not swept: {why}"));
            return row;
        }
    };
    let compiled = match build.compile(&subject.file, loader) {
        Ok(c) => c,
        Err(why) => {
            row.outcome = Err(why);
            return row;
        }
    };
    // Inputs the program does not read (predefined variables a shader ignores) have no slot.
    let subject = &Subject {
        args: subject.args.iter().filter(|a| compiled.cpu.slot(&a.slot).is_some()).cloned().collect(),
        ..subject.clone()
    };
    // The textures it looks up, loaded as the renderer loads them (a generated one by its name, a
    // file beside the subject's), so that the interpreter and the kernel read the same texels.
    let base = std::path::Path::new(&subject.file).parent().unwrap_or(std::path::Path::new(""));
    let textures = match compiled
        .cpu
        .textures()
        .iter()
        .map(|name| crate::render::textures::load(name, base).map(|t| (name.clone(), t)))
        .collect::<Result<Vec<_>, _>>()
    {
        Ok(textures) => textures,
        Err(e) => {
            row.outcome = Err(format!("not swept: {e}"));
            return row;
        }
    };
    let pts = points(&subject.args, options.random, options.seed);
    row.points = pts.count;
    let outputs: Vec<&str> = subject.outputs.iter().map(String::as_str).collect();
    let mut m = Measures::default();
    let f64_run = interpret::<f64>(&compiled, subject, &textures, &pts, &outputs, options.budget);
    let f32_run = interpret::<f32>(&compiled, subject, &textures, &pts, &outputs, options.budget);
    let mut endless = false;
    for (k, run) in [&f64_run, &f32_run].into_iter().enumerate() {
        match run {
            Ok(columns) => {
                m.nonfinite[k] = Some(count_nonfinite(subject, &pts, columns, BACKENDS[k], &mut m.failures))
            }
            Err((point, why)) => {
                endless = true;
                m.nonfinite[k] = Some(1);
                m.failures.push(Failure {
                    backend: BACKENDS[k],
                    input: describe(subject, &pts, *point),
                    output: why.clone(),
                });
            }
        }
    }
    if let (Ok(a), Ok(b)) = (&f32_run, &f64_run) {
        m.f32_vs_f64 = worst(a, b);
    }
    if let (Some(gpu), false) = (gpu, endless) {
        let inputs: Vec<(&str, &[f64])> =
            subject.args.iter().zip(&pts.columns).map(|(a, c)| (a.slot.as_str(), c.as_slice())).collect();
        let shader = &compiled.shader;
        let run = |lowering| {
            let resources = Resources { textures: &textures, lowering, ..Resources::default() };
            run_prepared(gpu, shader, &resources, pts.count, &inputs, &outputs)
        };
        match run(Lowering::Exact) {
            Ok(columns) => {
                m.nonfinite[2] = Some(count_nonfinite(subject, &pts, &columns, BACKENDS[2], &mut m.failures));
                if let Ok(f32_columns) = &f32_run {
                    m.gpu_vs_f32 = Some(worst(&columns, f32_columns));
                }
            }
            Err(e) => m.gpu_error = Some(e.to_string()),
        }
        if m.gpu_error.is_none() {
            match run(Lowering::Fast) {
                Ok(columns) => {
                    if let Ok(f64_columns) = &f64_run {
                        m.fast_vs_f64 = Some(worst(&columns, f64_columns));
                    }
                }
                Err(e) => m.gpu_error = Some(format!("fast lowering: {e}")),
            }
        }
    }
    row.outcome = Ok(m);
    row
}

/// The interpreter's outputs in precision `F`, or the point where it stopped and why. Inputs that
/// are one value per batch (a shader's uniform parameters) make it run point by point.
fn interpret<F: Real>(
    compiled: &subjects::Compiled,
    subject: &Subject,
    textures: &[(String, Texture)],
    pts: &Points,
    outputs: &[&str],
    budget: u64,
) -> Result<Vec<Vec<f64>>, (usize, String)> {
    let mut eval = Evaluator::<F>::new(&compiled.cpu);
    eval.set_budget(budget);
    for (name, texture) in textures {
        eval.set_texture(name, texture.clone()).map_err(|e| (0, format!("texture `{name}`: {e}")))?;
    }
    let uniform: Vec<bool> = subject
        .args
        .iter()
        .map(|a| compiled.cpu.slots().find(|(_, s)| s.name == a.slot).is_some_and(|(_, s)| s.uniform))
        .collect();
    let stopped = |point: usize, e: EvalError| (point, format!("the interpreter stopped: {e}"));
    if !uniform.contains(&true) {
        let inputs: Vec<(&str, &[f64])> =
            subject.args.iter().zip(&pts.columns).map(|(a, c)| (a.slot.as_str(), c.as_slice())).collect();
        if let Ok(columns) = eval.eval_points(pts.count, &inputs, outputs) {
            return Ok(columns);
        }
        // A batch stops as a whole; point by point (below) finds the point that stopped it.
    }
    let mut columns: Vec<Vec<f64>> = vec![Vec::new(); outputs.len()];
    for i in 0..pts.count {
        let mut varying: Vec<(&str, &[f64])> = Vec::new();
        for (k, arg) in subject.args.iter().enumerate() {
            let value = pts.value(k, i, arg.kind.components());
            if uniform[k] {
                eval.set(&arg.slot, value).map_err(|e| stopped(i, e))?;
            } else {
                varying.push((arg.slot.as_str(), value));
            }
        }
        let out = eval.eval_points(1, &varying, outputs).map_err(|e| stopped(i, e))?;
        for (column, values) in columns.iter_mut().zip(out) {
            column.extend(values);
        }
    }
    Ok(columns)
}

/// The points where any output is not finite; the first is recorded as a failure.
fn count_nonfinite(
    subject: &Subject,
    pts: &Points,
    columns: &[Vec<f64>],
    backend: &'static str,
    failures: &mut Vec<Failure>,
) -> usize {
    let mut count = 0;
    for i in 0..pts.count {
        let bad: Vec<String> = subject
            .outputs
            .iter()
            .zip(columns)
            .filter_map(|(name, column)| {
                let w = column.len() / pts.count.max(1);
                let v = &column[i * w..(i + 1) * w];
                v.iter().any(|x| !x.is_finite()).then(|| format!("{name} = {}", value_text(v)))
            })
            .collect();
        if bad.is_empty() {
            continue;
        }
        if count == 0 {
            failures.push(Failure { backend, input: describe(subject, pts, i), output: bad.join(", ") });
        }
        count += 1;
    }
    count
}

/// The largest error of `a` against the reference `b` over the points where both are finite.
fn worst(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .filter(|(x, r)| x.is_finite() && r.is_finite())
        .map(|(x, r)| (x - r).abs() / r.abs().max(1.0))
        .fold(0.0, f64::max)
}

/// Point `i`'s input as `name=value` pairs.
fn describe(subject: &Subject, pts: &Points, i: usize) -> String {
    subject
        .args
        .iter()
        .enumerate()
        .map(|(k, a)| format!("{}={}", a.label, value_text(pts.value(k, i, a.kind.components()))))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A value as it reads best: a number (every value crossing is an f32, printed as the shortest
/// text that reads back to it), or its components in parentheses.
fn value_text(v: &[f64]) -> String {
    let number = |x: f64| {
        let x = x as f32;
        if x != 0.0 && x.is_finite() && !(1e-3..1e5).contains(&x.abs()) {
            format!("{x:e}")
        } else {
            format!("{x}")
        }
    };
    match v {
        [x] => number(*x),
        _ => format!("({})", v.iter().map(|x| number(*x)).collect::<Vec<_>>().join(",")),
    }
}
