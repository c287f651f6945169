//! The emitter: allocates registers and appends instructions, choosing a uniform destination
//! exactly when every operand is uniform. Everything above it (expressions, built-ins) composes
//! these scalar operations.

use crate::backend::arith::Arith;
use crate::backend::cpu::code::{
    Binary, Compare, Convert, Files, Inst, IntBinary, IntUnary, Node, Reg, Ternary, Unary,
};

/// Temporaries are numbered from this bit until the program is complete, then moved above the
/// variables (see [`Emitter::finish`]); the mark keeps the two numberings apart meanwhile.
const TEMP: u32 = 1 << 31;

/// A value in registers: its scalar components in order (vector components; matrix elements row by
/// row; array elements one after another).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Val {
    /// Components in the float file.
    Float(Vec<Reg>),
    /// Components in the integer file (`int`, `uint`, `bool`).
    Int(Vec<Reg>),
    /// A string, known when the program is compiled.
    Str(smol_str::SmolStr),
    /// No value (`void` calls).
    Void,
}

impl Val {
    /// The float components (empty for other values).
    pub fn floats(&self) -> &[Reg] {
        match self {
            Val::Float(r) => r,
            _ => &[],
        }
    }

    /// The integer components (empty for other values).
    pub fn ints(&self) -> &[Reg] {
        match self {
            Val::Int(r) => r,
            _ => &[],
        }
    }
}

/// Register counters and the instruction list being built.
#[derive(Default)]
pub(crate) struct Emitter {
    /// Registers that live for the whole program: variables, inputs, constants.
    fixed: Files,
    /// The temporaries of the current statement.
    temps: Files,
    /// The most temporaries any statement needed.
    peak: Files,
    /// Constants already in registers, by bit pattern.
    float_constants: rustc_hash::FxHashMap<u64, Reg>,
    int_constants: rustc_hash::FxHashMap<u32, Reg>,
    /// The constants' values, by register.
    pub float_values: Vec<(u32, f64)>,
    pub int_values: Vec<(u32, u32)>,
    /// Where instructions go.
    pub out: Vec<Node>,
}

impl Emitter {
    /// A register that lives for the whole program.
    pub fn fixed(&mut self, float: bool, uniform: bool) -> Reg {
        let counter = counter(&mut self.fixed, float, uniform);
        *counter += 1;
        Reg { index: *counter - 1, uniform }
    }

    /// `n` consecutive fixed registers (arrays must be contiguous for indexing).
    pub fn fixed_block(&mut self, float: bool, uniform: bool, n: u32) -> Vec<Reg> {
        (0..n).map(|_| self.fixed(float, uniform)).collect()
    }

    /// A temporary of the current statement.
    pub fn temp(&mut self, float: bool, uniform: bool) -> Reg {
        let used = counter(&mut self.temps, float, uniform);
        *used += 1;
        let n = *used;
        let peak = counter(&mut self.peak, float, uniform);
        *peak = (*peak).max(n);
        Reg { index: TEMP | (n - 1), uniform }
    }

    /// Starts a statement: its temporaries may reuse the previous statement's.
    pub fn next_statement(&mut self) {
        self.temps = Files::default();
    }

    /// A uniform register holding the float `x`.
    pub fn float(&mut self, x: f64) -> Reg {
        if let Some(r) = self.float_constants.get(&x.to_bits()) {
            return *r;
        }
        let r = self.fixed(true, true);
        self.float_constants.insert(x.to_bits(), r);
        self.float_values.push((r.index, x));
        r
    }

    /// A uniform register holding the integer word `x`.
    pub fn int(&mut self, x: u32) -> Reg {
        if let Some(r) = self.int_constants.get(&x) {
            return *r;
        }
        let r = self.fixed(false, true);
        self.int_constants.insert(x, r);
        self.int_values.push((r.index, x));
        r
    }

    fn push(&mut self, inst: Inst) {
        self.out.push(Node::Inst(inst));
    }

    /// Float `op(a)`.
    pub fn unary(&mut self, op: Unary, a: Reg) -> Reg {
        let dst = self.temp(true, a.uniform);
        self.push(Inst::Unary { op, dst, a });
        dst
    }

    /// Float `op(a, b)`.
    pub fn binary(&mut self, op: Binary, a: Reg, b: Reg) -> Reg {
        let dst = self.temp(true, a.uniform && b.uniform);
        self.push(Inst::Binary { op, dst, a, b });
        dst
    }

    /// Float `op(a, b, c)`.
    pub fn ternary(&mut self, op: Ternary, a: Reg, b: Reg, c: Reg) -> Reg {
        let dst = self.temp(true, a.uniform && b.uniform && c.uniform);
        self.push(Inst::Ternary { op, dst, a, b, c });
        dst
    }

    /// Float comparison, a bool in the integer file.
    pub fn compare(&mut self, op: Compare, a: Reg, b: Reg) -> Reg {
        let dst = self.temp(false, a.uniform && b.uniform);
        self.push(Inst::Compare { op, dst, a, b });
        dst
    }

    /// Integer `op(a)`.
    pub fn int_unary(&mut self, op: IntUnary, a: Reg) -> Reg {
        let dst = self.temp(false, a.uniform);
        self.push(Inst::IntUnary { op, dst, a });
        dst
    }

    /// Integer `op(a, b)`.
    pub fn int_binary(&mut self, op: IntBinary, a: Reg, b: Reg) -> Reg {
        let dst = self.temp(false, a.uniform && b.uniform);
        self.push(Inst::IntBinary { op, dst, a, b });
        dst
    }

    /// Integer comparison.
    pub fn int_compare(&mut self, op: Compare, signed: bool, a: Reg, b: Reg) -> Reg {
        let dst = self.temp(false, a.uniform && b.uniform);
        self.push(Inst::IntCompare { op, signed, dst, a, b });
        dst
    }

    /// A conversion between the files.
    pub fn convert(&mut self, op: Convert, a: Reg) -> Reg {
        let to_float = matches!(op, Convert::IntToFloat | Convert::UintToFloat);
        let dst = self.temp(to_float, a.uniform);
        self.push(Inst::Convert { op, dst, a });
        dst
    }

    /// `cond ? a : b` in either file.
    pub fn select(&mut self, float: bool, cond: Reg, a: Reg, b: Reg) -> Reg {
        let dst = self.temp(float, cond.uniform && a.uniform && b.uniform);
        self.push(Inst::Select { float, dst, cond, a, b });
        dst
    }

    /// A masked store `dst = src`.
    pub fn store(&mut self, float: bool, dst: Reg, src: Reg) {
        if dst != src {
            self.push(Inst::Move { float, dst, src });
        }
    }

    /// A copy into a fresh temporary (of a given uniformity).
    pub fn copy(&mut self, float: bool, src: Reg, uniform: bool) -> Reg {
        let dst = self.temp(float, uniform);
        self.push(Inst::Move { float, dst, src });
        dst
    }

    /// `regs` as consecutive registers of one kind (what an index needs), copied into fresh
    /// temporaries (which are allocated consecutively) when they are not.
    pub fn consecutive(&mut self, float: bool, regs: Vec<Reg>) -> Vec<Reg> {
        let uniform = regs.iter().all(|r| r.uniform);
        let consecutive =
            regs.windows(2).all(|w| w[1].index == w[0].index + 1 && w[1].uniform == w[0].uniform);
        if consecutive {
            return regs;
        }
        regs.iter().map(|r| self.copy(float, *r, uniform)).collect()
    }

    /// An element of a contiguous array of registers, at a run-time index.
    pub fn gather(&mut self, float: bool, base: Reg, len: u32, stride: u32, index: Reg, signed: bool) -> Reg {
        let dst = self.temp(float, base.uniform && index.uniform);
        self.push(Inst::Gather { float, dst, base, len, stride, index, signed });
        dst
    }

    /// A masked store into an array at a run-time index.
    #[allow(clippy::too_many_arguments)]
    pub fn scatter(
        &mut self,
        float: bool,
        base: Reg,
        len: u32,
        stride: u32,
        index: Reg,
        signed: bool,
        src: Reg,
    ) {
        self.push(Inst::Scatter { float, base, len, stride, index, signed, src });
    }

    /// `random()` at call site `site`.
    /// Channel `channel` of a texel; uniform when the coordinates are.
    pub fn texel(&mut self, texture: u32, channel: u8, x: Reg, y: Reg, z: Reg) -> Reg {
        let dst = self.temp(true, x.uniform && y.uniform && z.uniform);
        self.push(Inst::Texel { texture, channel, dst, x, y, z });
        dst
    }

    /// A texture's size along an axis (uniform).
    pub fn tex_size(&mut self, texture: u32, axis: u8) -> Reg {
        let dst = self.temp(false, true);
        self.push(Inst::TexSize { texture, axis, dst });
        dst
    }

    /// `printf` of `format` with `args`.
    pub fn printf(&mut self, format: String, args: Vec<crate::backend::cpu::code::PrintArg>) {
        self.push(Inst::Printf { format, args });
    }

    pub fn random(&mut self, site: u32, point: Reg) -> Reg {
        let dst = self.temp(true, false);
        self.push(Inst::Random { dst, site, point });
        dst
    }

    /// The register sizes, with temporaries placed after the fixed registers, and `nodes` renumbered
    /// to match.
    pub fn finish(&self, nodes: &mut [Node]) -> Files {
        let f = self.fixed;
        relocate(nodes, &f);
        Files {
            uniform_floats: f.uniform_floats + self.peak.uniform_floats,
            varying_floats: f.varying_floats + self.peak.varying_floats,
            uniform_ints: f.uniform_ints + self.peak.uniform_ints,
            varying_ints: f.varying_ints + self.peak.varying_ints,
        }
    }
}

fn counter(files: &mut Files, float: bool, uniform: bool) -> &mut u32 {
    match (float, uniform) {
        (true, true) => &mut files.uniform_floats,
        (true, false) => &mut files.varying_floats,
        (false, true) => &mut files.uniform_ints,
        (false, false) => &mut files.varying_ints,
    }
}

fn counter_value(files: &Files, float: bool, uniform: bool) -> u32 {
    match (float, uniform) {
        (true, true) => files.uniform_floats,
        (true, false) => files.varying_floats,
        (false, true) => files.uniform_ints,
        (false, false) => files.varying_ints,
    }
}

/// Moves temporaries above the fixed registers of their file.
fn relocate(nodes: &mut [Node], fixed: &Files) {
    for node in nodes {
        match node {
            Node::Inst(inst) => relocate_inst(inst, fixed),
            Node::If { cond, then, otherwise } => {
                fix(cond, false, fixed);
                relocate(then, fixed);
                relocate(otherwise, fixed);
            }
            Node::Loop { test, cond, body, step, .. } => {
                relocate(test, fixed);
                if let Some(c) = cond {
                    fix(c, false, fixed);
                }
                relocate(body, fixed);
                relocate(step, fixed);
            }
            Node::Function(body) => relocate(body, fixed),
            Node::Break(_) | Node::Continue(_) | Node::Return => {}
        }
    }
}

fn fix(r: &mut Reg, float: bool, fixed: &Files) {
    if r.index & TEMP != 0 {
        let base = counter_value(fixed, float, r.uniform);
        r.index = (r.index & !TEMP) + base;
    }
}

fn relocate_inst(inst: &mut Inst, f: &Files) {
    match inst {
        Inst::Unary { dst, a, .. } => {
            fix(dst, true, f);
            fix(a, true, f);
        }
        Inst::Binary { dst, a, b, .. } => {
            for r in [dst, a, b] {
                fix(r, true, f);
            }
        }
        Inst::Ternary { dst, a, b, c, .. } => {
            for r in [dst, a, b, c] {
                fix(r, true, f);
            }
        }
        Inst::Compare { dst, a, b, .. } => {
            fix(dst, false, f);
            fix(a, true, f);
            fix(b, true, f);
        }
        Inst::IntUnary { dst, a, .. } => {
            fix(dst, false, f);
            fix(a, false, f);
        }
        Inst::IntBinary { dst, a, b, .. } | Inst::IntCompare { dst, a, b, .. } => {
            for r in [dst, a, b] {
                fix(r, false, f);
            }
        }
        Inst::Convert { op, dst, a } => {
            let to_float = matches!(op, Convert::IntToFloat | Convert::UintToFloat);
            fix(dst, to_float, f);
            fix(a, !to_float, f);
        }
        Inst::Select { float, dst, cond, a, b } => {
            let float = *float;
            fix(cond, false, f);
            for r in [dst, a, b] {
                fix(r, float, f);
            }
        }
        Inst::Move { float, dst, src } => {
            let float = *float;
            fix(dst, float, f);
            fix(src, float, f);
        }
        Inst::Gather { float, dst, base, index, .. } => {
            let float = *float;
            fix(dst, float, f);
            fix(base, float, f);
            fix(index, false, f);
        }
        Inst::Scatter { float, base, index, src, .. } => {
            let float = *float;
            fix(base, float, f);
            fix(src, float, f);
            fix(index, false, f);
        }
        Inst::Random { dst, point, .. } => {
            fix(dst, true, f);
            fix(point, false, f);
        }
        Inst::Texel { dst, x, y, z, .. } => {
            fix(dst, true, f);
            for r in [x, y, z] {
                fix(r, false, f);
            }
        }
        Inst::TexSize { dst, .. } => fix(dst, false, f),
        Inst::Printf { args, .. } => {
            for arg in args {
                match arg {
                    crate::backend::cpu::code::PrintArg::Text(_) => {}
                    crate::backend::cpu::code::PrintArg::Floats(regs) => {
                        regs.iter_mut().for_each(|r| fix(r, true, f))
                    }
                    crate::backend::cpu::code::PrintArg::Ints(regs, _) => {
                        regs.iter_mut().for_each(|r| fix(r, false, f))
                    }
                }
            }
        }
    }
}

/// The sequences of `backend::arith` as instructions. Those the interpreter has one instruction for
/// (`clamp`, `step`, `smoothstep`, `mod`, `sign`, `inversesqrt`) are that instruction, which runs
/// the same sequence on numbers (`scalar::Numbers`).
impl Arith for Emitter {
    type V = Reg;
    type B = Reg;
    fn constant(&mut self, x: f64) -> Reg {
        self.float(x)
    }
    fn add(&mut self, a: Reg, b: Reg) -> Reg {
        self.binary(Binary::Add, a, b)
    }
    fn sub(&mut self, a: Reg, b: Reg) -> Reg {
        self.binary(Binary::Sub, a, b)
    }
    fn mul(&mut self, a: Reg, b: Reg) -> Reg {
        self.binary(Binary::Mul, a, b)
    }
    fn div(&mut self, a: Reg, b: Reg) -> Reg {
        self.binary(Binary::Div, a, b)
    }
    fn neg(&mut self, a: Reg) -> Reg {
        self.unary(Unary::Neg, a)
    }
    fn sqrt(&mut self, a: Reg) -> Reg {
        self.unary(Unary::Sqrt, a)
    }
    fn floor(&mut self, a: Reg) -> Reg {
        self.unary(Unary::Floor, a)
    }
    fn min(&mut self, a: Reg, b: Reg) -> Reg {
        self.binary(Binary::Min, a, b)
    }
    fn max(&mut self, a: Reg, b: Reg) -> Reg {
        self.binary(Binary::Max, a, b)
    }
    fn less(&mut self, a: Reg, b: Reg) -> Reg {
        self.compare(Compare::Lt, a, b)
    }
    fn greater(&mut self, a: Reg, b: Reg) -> Reg {
        self.compare(Compare::Gt, a, b)
    }
    fn greater_equal(&mut self, a: Reg, b: Reg) -> Reg {
        self.compare(Compare::Ge, a, b)
    }
    fn is_nan(&mut self, a: Reg) -> Reg {
        self.compare(Compare::Ne, a, a)
    }
    fn select(&mut self, c: Reg, a: Reg, b: Reg) -> Reg {
        Emitter::select(self, true, c, a, b)
    }
    fn clamp(&mut self, x: Reg, lo: Reg, hi: Reg) -> Reg {
        self.ternary(Ternary::Clamp, x, lo, hi)
    }
    fn step(&mut self, edge: Reg, x: Reg) -> Reg {
        self.binary(Binary::Step, edge, x)
    }
    fn smoothstep(&mut self, lo: Reg, hi: Reg, x: Reg) -> Reg {
        self.ternary(Ternary::Smoothstep, lo, hi, x)
    }
    fn modulo(&mut self, a: Reg, b: Reg) -> Reg {
        self.binary(Binary::Mod, a, b)
    }
    fn sign(&mut self, x: Reg) -> Reg {
        self.unary(Unary::Sign, x)
    }
    fn inverse_sqrt(&mut self, x: Reg) -> Reg {
        self.unary(Unary::InverseSqrt, x)
    }
}
