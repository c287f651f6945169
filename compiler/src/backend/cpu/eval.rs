//! The library API of the interpreter: compile a shader for a binding, set its parameters and
//! uniform inputs, evaluate it at any number of points, read the outputs.
//!
//! ```
//! use patina_compiler::backend::binding::Binding;
//! use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
//! use patina_compiler::opt::Prepared;
//! use patina_compiler::syntax::preprocess::MemoryLoader;
//!
//! let checked = patina_compiler::check_source(
//!     "ramp.sl",
//!     "surface ramp(float k = 2) { Ci = color(s * k, t, 0); }",
//!     &MemoryLoader::default(),
//! );
//! let prepared = Prepared::new(checked.program.shaders[0].clone());
//! let program = CpuProgram::compile(&prepared, &Binding::default()).unwrap();
//! let mut eval = Evaluator::<f32>::new(&program);
//! eval.set("k", &[3.0]).unwrap();
//! let out = eval.eval_points(2, &[("s", &[0.5, 1.0]), ("t", &[0.25, 0.75])], &["Ci"]).unwrap();
//! assert_eq!(out[0], vec![1.5, 0.25, 0.0, 3.0, 0.75, 0.0]);
//! ```

use super::code::Node;
use super::exec::{LANES, Machine, Stop, Texture};
use super::lower::{self, Lowered, SlotKind};
use super::scalar::Real;
use crate::backend::MAX_LOOP_ITERATIONS;
use crate::backend::binding::Binding;
use crate::diag::{Code, Diagnostic};
use crate::ir::types::Type;
use crate::opt::Prepared;
use crate::source::Span;

/// A shader compiled for the interpreter at one binding (valid for both precisions).
#[derive(Clone, Debug)]
pub struct CpuProgram {
    lowered: Lowered,
}

/// Identifies a named input or output of a [`CpuProgram`].
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct SlotId(usize);

/// What went wrong in an evaluation.
#[derive(Clone, Debug, PartialEq)]
pub enum EvalError {
    /// No input or output has this name.
    UnknownName(String),
    /// A value or column of the wrong length.
    WrongSize {
        /// The input.
        name: String,
        /// The length needed.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// A column given for an input that has one value per batch (use [`Evaluator::set`]).
    Uniform(String),
    /// A loop ran past the iteration budget.
    IterationBudget {
        /// The loop.
        span: Span,
        /// The budget.
        budget: u64,
    },
}

impl EvalError {
    /// The error as a diagnostic (with the loop's position for a budget overrun).
    pub fn to_diagnostic(&self) -> Diagnostic {
        match self {
            EvalError::UnknownName(name) => Diagnostic::error(
                Code::UnknownInput,
                format!("the shader has no input or output `{name}`"),
                Span::default(),
                "",
            ),
            EvalError::WrongSize { name, expected, found } => Diagnostic::error(
                Code::UnknownInput,
                format!("`{name}` needs {expected} values, found {found}"),
                Span::default(),
                "",
            ),
            EvalError::Uniform(name) => Diagnostic::error(
                Code::UnknownInput,
                format!("`{name}` has one value for all points; set it instead of giving a column"),
                Span::default(),
                "",
            ),
            EvalError::IterationBudget { span, budget } => Diagnostic::error(
                Code::IterationBudget,
                format!("this loop ran more than {budget} iterations and was stopped"),
                *span,
                "did not finish",
            )
            .with_help("check the loop's condition; the budget is an option of the evaluation"),
        }
    }
}

impl std::fmt::Display for EvalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.to_diagnostic().message)
    }
}

impl std::error::Error for EvalError {}

/// A named slot, as the caller sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct SlotInfo {
    /// Its name (`Ci`, `Kd`, `dx(P)`, `L[0]`, `space:world`).
    pub name: String,
    /// Its type.
    pub ty: Type,
    /// The number of values one point has (components, times elements for arrays; 32 for a
    /// space: the matrix and its inverse, though `set` takes only the 16 of the matrix).
    pub width: usize,
    /// Whether it is one value per batch (a uniform parameter or input) rather than per point.
    pub uniform: bool,
    /// What it is.
    pub kind: SlotKind,
}

impl CpuProgram {
    /// Compiles a prepared shader (a whole one, or a stage of its split) for a binding.
    pub fn compile(shader: &Prepared, binding: &Binding) -> Result<CpuProgram, Diagnostic> {
        let lowered = lower::lower(shader, binding)?;
        Ok(CpuProgram { lowered })
    }

    /// The named inputs and outputs (variables of the body are not listed).
    pub fn slots(&self) -> impl Iterator<Item = (SlotId, SlotInfo)> + '_ {
        self.lowered.slots.iter().enumerate().filter(|(_, s)| s.kind != SlotKind::Variable).map(|(i, s)| {
            let info = SlotInfo {
                name: s.name.clone(),
                ty: s.ty,
                width: s.regs.len(),
                uniform: s.regs.iter().all(|r| r.uniform),
                kind: s.kind.clone(),
            };
            (SlotId(i), info)
        })
    }

    /// The slot called `name`.
    pub fn slot(&self, name: &str) -> Option<SlotId> {
        self.slots().find(|(_, s)| s.name == name).map(|(id, _)| id)
    }

    /// The textures the program reads, by the names [`Evaluator::set_texture`] takes.
    pub fn textures(&self) -> &[String] {
        &self.lowered.code.textures
    }

    /// The number of instructions (static count).
    pub fn instruction_count(&self) -> usize {
        self.lowered.code.instruction_count()
    }
}

/// Runs a [`CpuProgram`] in precision `F` (`f32`, or `f64` for ground truth).
pub struct Evaluator<'p, F> {
    program: &'p CpuProgram,
    machine: Machine<F>,
    /// Per slot: the value set with [`Evaluator::set`] (used for every point without a column).
    set: Vec<Option<Set<F>>>,
    /// Per slot: whether a column is given in the current call (scratch, kept to avoid
    /// allocating per call).
    given: Vec<bool>,
}

/// A value given with [`Evaluator::set`], kept in its register file's form: integers as their
/// 32 bits (an f32 could not hold them beyond 2^24).
#[derive(Clone, Debug)]
enum Set<F> {
    Floats(Vec<F>),
    Ints(Vec<u32>),
}

impl<'p, F: Real> Evaluator<'p, F> {
    /// An evaluator with every input at its default: parameters at their declared defaults,
    /// `Cs` and `Os` white, named spaces the identity, everything else zero.
    pub fn new(program: &'p CpuProgram) -> Self {
        let code = &program.lowered.code;
        let mut machine = Machine::new(code.files, MAX_LOOP_ITERATIONS);
        machine.textures = vec![Texture::default(); code.textures.len()];
        for &(r, x) in &code.float_constants {
            machine.floats.uniform[r as usize] = F::from_f64(x);
        }
        for &(r, x) in &code.int_constants {
            machine.ints.uniform[r as usize] = x;
        }
        let n = program.lowered.slots.len();
        let mut e = Evaluator { program, machine, set: vec![None; n], given: vec![false; n] };
        for (i, slot) in program.lowered.slots.iter().enumerate() {
            let default = match (&slot.kind, slot.name.as_str()) {
                (SlotKind::Global, "Cs" | "Os") => Some(Set::Floats(vec![F::ONE; 3])),
                (SlotKind::Space, _) => Some(Set::Floats(identity_pair())),
                _ => None,
            };
            e.set[i] = default;
        }
        e
    }

    /// Binds a texture the program reads (see [`CpuProgram::textures`]); an unbound one reads as
    /// one black, transparent texel.
    pub fn set_texture(&mut self, name: &str, texture: Texture) -> Result<(), EvalError> {
        let i = self
            .program
            .textures()
            .iter()
            .position(|t| t == name)
            .ok_or_else(|| EvalError::UnknownName(name.to_string()))?;
        self.machine.textures[i] = texture;
        Ok(())
    }

    /// Changes the iteration budget of each loop, by default [`MAX_LOOP_ITERATIONS`] (the GPU's
    /// cap, so that a loop the GPU cuts short is an error here); past it the interpreter runs loops
    /// the GPU cuts short.
    pub fn set_budget(&mut self, budget: u64) {
        self.machine.budget = budget;
    }

    /// Sets an input for every point: a parameter (then its default is not computed), a
    /// predefined variable, a light's `L`/`Cl`, a seed, or a space (`space:NAME`, 16 values of
    /// the matrix from "current" to it, row by row).
    pub fn set(&mut self, name: &str, values: &[f64]) -> Result<(), EvalError> {
        let id = self.program.slot(name).ok_or_else(|| EvalError::UnknownName(name.to_string()))?;
        let slot = &self.program.lowered.slots[id.0];
        let values = if slot.kind == SlotKind::Space {
            check_size(name, 16, values.len())?;
            let inverse = invert4(values);
            Set::Floats(values.iter().chain(&inverse).map(|x| F::from_f64(*x)).collect())
        } else if slot.float {
            check_size(name, slot.regs.len(), values.len())?;
            Set::Floats(values.iter().map(|x| F::from_f64(*x)).collect())
        } else {
            // Integers as given, or as their unsigned bit pattern (what outputs give back).
            check_size(name, slot.regs.len(), values.len())?;
            Set::Ints(values.iter().map(|x| *x as i64 as u32).collect())
        };
        self.set[id.0] = Some(values);
        Ok(())
    }

    /// Evaluates `count` points. Each input column holds `count * width` values, point after
    /// point; each output buffer receives the same layout. Inputs not given keep the values of
    /// [`Evaluator::set`] or their defaults. Allocates nothing.
    pub fn eval(
        &mut self,
        count: usize,
        inputs: &[(SlotId, &[F])],
        outputs: &mut [(SlotId, &mut [F])],
    ) -> Result<(), EvalError> {
        let slots = &self.program.lowered.slots;
        for (id, column) in inputs {
            let slot = &slots[id.0];
            if slot.regs.iter().any(|r| r.uniform) {
                return Err(EvalError::Uniform(slot.name.clone()));
            }
            check_size(&slot.name, count * slot.regs.len(), column.len())?;
        }
        for (id, buffer) in outputs.iter() {
            let slot = &slots[id.0];
            check_size(&slot.name, count * slot.regs.len(), buffer.len())?;
        }
        let mut start = 0;
        while start < count {
            let n = (count - start).min(LANES);
            self.load(start, n, inputs);
            let body: &[Node] = &self.program.lowered.code.body;
            self.machine.run(body, n).map_err(|Stop::IterationBudget { span, budget }| {
                EvalError::IterationBudget { span, budget }
            })?;
            for (id, buffer) in outputs.iter_mut() {
                self.store(id.0, start, n, buffer);
            }
            start += n;
        }
        Ok(())
    }

    /// Fills every slot for the batch of points `start..start + n`.
    fn load(&mut self, start: usize, n: usize, inputs: &[(SlotId, &[F])]) {
        let lowered = &self.program.lowered;
        self.given.fill(false);
        for (id, _) in inputs {
            self.given[id.0] = true;
        }
        for (i, slot) in lowered.slots.iter().enumerate() {
            if self.given[i] {
                let column = inputs.iter().find(|(id, _)| id.0 == i).map(|(_, c)| *c).unwrap_or(&[]);
                let width = slot.regs.len();
                for (c, r) in slot.regs.iter().enumerate() {
                    if slot.float {
                        let lanes = self.machine.floats.lanes_mut(*r);
                        for lane in 0..n {
                            lanes[lane] = column[(start + lane) * width + c];
                        }
                    } else {
                        let lanes = self.machine.ints.lanes_mut(*r);
                        for lane in 0..n {
                            lanes[lane] = column[(start + lane) * width + c].to_f64() as i64 as u32;
                        }
                    }
                }
                continue;
            }
            if slot.name == crate::backend::POINT_INDEX && self.set[i].is_none() && !slot.float {
                // Each point's index in this evaluation, unless the caller gives others.
                let lanes = self.machine.ints.lanes_mut(slot.regs[0]);
                for (lane, x) in lanes.iter_mut().enumerate() {
                    *x = (start + lane) as u32;
                }
                continue;
            }
            for (c, r) in slot.regs.iter().enumerate() {
                match &self.set[i] {
                    Some(Set::Floats(v)) if slot.float => self.machine.floats.fill(*r, v[c]),
                    Some(Set::Ints(v)) if !slot.float => self.machine.ints.fill(*r, v[c]),
                    _ if slot.float => self.machine.floats.fill(*r, F::ZERO),
                    _ => self.machine.ints.fill(*r, 0),
                }
            }
        }
        // Parameters neither set nor given take their defaults, computed in slot order.
        for (slot, code) in &lowered.defaults {
            if self.set[*slot].is_none() && !self.given[*slot] {
                // Defaults are constant or per-draw expressions: no loops, no budget to exceed.
                let _ = self.machine.run(code, n);
            }
        }
    }

    fn store(&self, slot: usize, start: usize, n: usize, buffer: &mut [F]) {
        let slot = &self.program.lowered.slots[slot];
        let width = slot.regs.len();
        for (c, r) in slot.regs.iter().enumerate() {
            for lane in 0..n {
                buffer[(start + lane) * width + c] = if slot.float {
                    self.machine.floats.at(*r, lane)
                } else {
                    F::from_f64(f64::from(self.machine.ints.at(*r, lane)))
                };
            }
        }
    }

    /// Evaluates at `count` points given by name, in f64 (converted to and from `F`), and returns
    /// the named outputs. Convenient for tests and the command line; allocates per call.
    pub fn eval_points(
        &mut self,
        count: usize,
        inputs: &[(&str, &[f64])],
        outputs: &[&str],
    ) -> Result<Vec<Vec<f64>>, EvalError> {
        let program = self.program;
        let find = |name: &str| program.slot(name).ok_or_else(|| EvalError::UnknownName(name.to_string()));
        let columns: Vec<(SlotId, Vec<F>)> = inputs
            .iter()
            .map(|(name, values)| Ok((find(name)?, values.iter().map(|x| F::from_f64(*x)).collect())))
            .collect::<Result<_, EvalError>>()?;
        let mut buffers: Vec<(SlotId, Vec<F>)> = outputs
            .iter()
            .map(|name| {
                let id = find(name)?;
                Ok((id, vec![F::ZERO; count * program.lowered.slots[id.0].regs.len()]))
            })
            .collect::<Result<_, EvalError>>()?;
        let inputs: Vec<(SlotId, &[F])> = columns.iter().map(|(id, c)| (*id, c.as_slice())).collect();
        let mut outs: Vec<(SlotId, &mut [F])> =
            buffers.iter_mut().map(|(id, b)| (*id, b.as_mut_slice())).collect();
        self.eval(count, &inputs, &mut outs)?;
        Ok(buffers.into_iter().map(|(_, b)| b.into_iter().map(F::to_f64).collect()).collect())
    }
}

fn check_size(name: &str, expected: usize, found: usize) -> Result<(), EvalError> {
    if expected == found {
        Ok(())
    } else {
        Err(EvalError::WrongSize { name: name.to_string(), expected, found })
    }
}

fn identity_pair<F: Real>() -> Vec<F> {
    (0..32).map(|i| if (i % 16) % 5 == 0 { F::ONE } else { F::ZERO }).collect()
}

/// The inverse of a 4x4 matrix in f64 (Gauss-Jordan with partial pivoting); a singular matrix
/// gives NaN entries.
fn invert4(m: &[f64]) -> Vec<f64> {
    let mut a = [[0.0f64; 8]; 4];
    for i in 0..4 {
        for j in 0..4 {
            a[i][j] = m[i * 4 + j];
        }
        a[i][4 + i] = 1.0;
    }
    for col in 0..4 {
        let pivot = (col..4).max_by(|x, y| a[*x][col].abs().total_cmp(&a[*y][col].abs())).unwrap_or(col);
        a.swap(col, pivot);
        let p = a[col][col];
        if p == 0.0 {
            return vec![f64::NAN; 16];
        }
        for x in a[col].iter_mut() {
            *x /= p;
        }
        for row in 0..4 {
            if row != col {
                let k = a[row][col];
                let pivot_row = a[col];
                for (x, y) in a[row].iter_mut().zip(pivot_row) {
                    *x -= k * y;
                }
            }
        }
    }
    (0..16).map(|k| a[k / 4][4 + k % 4]).collect()
}
