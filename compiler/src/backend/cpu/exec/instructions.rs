//! What each instruction does to the registers. The per-lane arithmetic is `scalar`'s, so the f32
//! and f64 modes and every operand shape share one definition of each operation.

use super::kernels::{File, Lanes, View, map1, map2, map3};
use super::{LANES, Machine, Mask};
use crate::backend::cpu::code::{
    Binary, Compare, Convert, Inst, IntBinary, IntUnary, PrintArg, Reg, Ternary, Unary,
};
use crate::backend::cpu::scalar::{self as s, Real};

/// Expands `$body` once per comparison, with `$f` the comparison's function: matching `op` inside
/// the lane loop instead would jump through a table at every lane.
macro_rules! compare_with {
    ($op:expr, |$f:ident| $body:expr) => {
        match $op {
            Compare::Eq => {
                let $f = PartialEq::eq;
                $body
            }
            Compare::Ne => {
                let $f = PartialEq::ne;
                $body
            }
            Compare::Lt => {
                let $f = PartialOrd::lt;
                $body
            }
            Compare::Le => {
                let $f = PartialOrd::le;
                $body
            }
            Compare::Gt => {
                let $f = PartialOrd::gt;
                $body
            }
            Compare::Ge => {
                let $f = PartialOrd::ge;
                $body
            }
        }
    };
}

impl<F: Real> Machine<F> {
    /// Runs one instruction. Inlined, with everything it calls, into each build of
    /// `Machine::dispatch`, so that the lane loops are compiled for that build's vectors.
    #[inline(always)]
    pub(super) fn inst(&mut self, inst: &Inst, mask: &Mask) {
        match *inst {
            Inst::Unary { op, dst, a } => float_unary(&mut self.floats, op, dst, a),
            Inst::Binary { op, dst, a, b } => float_binary(&mut self.floats, op, dst, a, b),
            Inst::Ternary { op, dst, a, b, c } => {
                let file = &mut self.floats;
                match op {
                    Ternary::Mix => same_file3(file, dst, a, b, c, s::mix),
                    Ternary::Clamp => same_file3(file, dst, a, b, c, s::clamp),
                    Ternary::Smoothstep => same_file3(file, dst, a, b, c, s::smoothstep),
                }
            }
            Inst::Compare { op, dst, a, b } => {
                let (from, to) = (&self.floats, &mut self.ints);
                compare_with!(op, |f| cross2(from, to, dst, a, b, |x: F, y: F| u32::from(f(&x, &y))));
            }
            Inst::IntUnary { op, dst, a } => {
                let file = &mut self.ints;
                match op {
                    IntUnary::Neg => same_file1(file, dst, a, u32::wrapping_neg),
                    IntUnary::Not => same_file1(file, dst, a, |x| !x),
                    IntUnary::LogicalNot => same_file1(file, dst, a, |x| u32::from(x == 0)),
                    IntUnary::Abs => same_file1(file, dst, a, |x| (x as i32).wrapping_abs() as u32),
                }
            }
            Inst::IntBinary { op, dst, a, b } => int_binary(&mut self.ints, op, dst, a, b),
            Inst::IntCompare { op, signed, dst, a, b } => {
                let file = &mut self.ints;
                if signed {
                    compare_with!(op, |f| same_file2(file, dst, a, b, |x, y| u32::from(f(
                        &(x as i32),
                        &(y as i32)
                    ))));
                } else {
                    compare_with!(op, |f| same_file2(file, dst, a, b, |x, y| u32::from(f(&x, &y))));
                }
            }
            Inst::Convert { op, dst, a } => match op {
                Convert::FloatToInt => cross1(&self.floats, &mut self.ints, dst, a, |x| s::to_i32(x) as u32),
                Convert::FloatToUint => cross1(&self.floats, &mut self.ints, dst, a, s::to_u32),
                Convert::FloatToBool => {
                    cross1(&self.floats, &mut self.ints, dst, a, |x| u32::from(x != F::ZERO))
                }
                Convert::IntToFloat => {
                    cross1(&self.ints, &mut self.floats, dst, a, |x| F::from_i32(x as i32))
                }
                Convert::UintToFloat => cross1(&self.ints, &mut self.floats, dst, a, F::from_u32),
            },
            Inst::Select { float: true, dst, cond, a, b } => {
                if dst.uniform {
                    let cond = self.ints.uniform[cond.index as usize];
                    let u = &mut self.floats.uniform;
                    u[dst.index as usize] = u[if cond != 0 { a } else { b }.index as usize];
                } else {
                    let (d, view) = self.floats.split(dst.index);
                    select(d, self.ints.read(cond), view.read(a), view.read(b));
                }
            }
            Inst::Select { float: false, dst, cond, a, b } => {
                let u = &mut self.ints.uniform;
                if dst.uniform {
                    let pick = if u[cond.index as usize] != 0 { a } else { b };
                    u[dst.index as usize] = u[pick.index as usize];
                } else {
                    // The condition is in the destination's file, but never the destination.
                    let (d, view) = self.ints.split(dst.index);
                    select(d, view.read(cond), view.read(a), view.read(b));
                }
            }
            Inst::Move { float: true, dst, src } => store(&mut self.floats, dst, src, mask),
            Inst::Move { float: false, dst, src } => store(&mut self.ints, dst, src, mask),
            Inst::Gather { float, dst, base, len, stride, index, signed } => {
                let at = Clamp { len, stride, signed };
                if dst.uniform {
                    // A uniform destination has a uniform index.
                    let i = self.ints.uniform[index.index as usize];
                    let from = (base.index + at.offset(i)) as usize;
                    if float {
                        self.floats.uniform[dst.index as usize] = self.floats.uniform[from];
                    } else {
                        self.ints.uniform[dst.index as usize] = self.ints.uniform[from];
                    }
                } else if float {
                    let (d, view) = self.floats.split(dst.index);
                    gather(d, &view, base, self.ints.read(index), at);
                } else {
                    // The index is in the destination's file, but never the destination.
                    let (d, view) = self.ints.split(dst.index);
                    gather(d, &view, base, view.read(index), at);
                }
            }
            Inst::Scatter { float, base, len, stride, index, signed, src } => {
                let at = Clamp { len, stride, signed };
                if float {
                    scatter(&mut self.floats, base, self.ints.read(index), src, at, mask);
                } else {
                    let index = lanes_copy(&self.ints, index);
                    scatter(&mut self.ints, base, index.as_lanes(), src, at, mask);
                }
            }
            Inst::Texel { texture, channel, dst, x, y, z } => {
                let fallback = super::Texture::default();
                let t = self.textures.get(texture as usize).unwrap_or(&fallback);
                let ints = &self.ints;
                let fetch = |lane: usize| {
                    let at = |r: Reg| ints.at(r, lane) as i32;
                    F::from_f64(f64::from(t.texel(at(x), at(y), at(z))[channel as usize]))
                };
                if dst.uniform {
                    let v = fetch(0);
                    self.floats.fill(dst, v);
                } else {
                    let values: [F; LANES] = std::array::from_fn(fetch);
                    *self.floats.lanes_mut(dst) = values;
                }
            }
            Inst::Printf { ref format, ref args } => {
                for lane in (0..LANES).filter(|&l| mask.has(l)) {
                    let values: Vec<crate::sema::builtins::PrintValue> = args
                        .iter()
                        .map(|a| match a {
                            PrintArg::Text(s) => crate::sema::builtins::PrintValue::Text(s.clone()),
                            PrintArg::Floats(regs) => crate::sema::builtins::PrintValue::Numbers(
                                regs.iter().map(|r| self.floats.at(*r, lane).to_f64()).collect(),
                            ),
                            PrintArg::Ints(regs, signed) => crate::sema::builtins::PrintValue::Numbers(
                                regs.iter()
                                    .map(|r| {
                                        let x = self.ints.at(*r, lane);
                                        if *signed { f64::from(x as i32) } else { f64::from(x) }
                                    })
                                    .collect(),
                            ),
                        })
                        .collect();
                    print_line(&crate::sema::builtins::printf_format(format, &values));
                }
            }
            Inst::TexSize { texture, axis, dst } => {
                let size = self.textures.get(texture as usize).map_or(1, |t| t.size[axis as usize].max(1));
                self.ints.fill(dst, size);
            }
            Inst::Random { dst, site, point } => {
                let ints = &self.ints;
                let d = &mut self.floats.varying[dst.index as usize];
                for (lane, d) in d.iter_mut().enumerate() {
                    *d = s::random(ints.at(point, lane), site);
                }
            }
        }
    }
}

#[inline(always)]
fn float_unary<F: Real>(file: &mut File<F>, op: Unary, dst: Reg, a: Reg) {
    // One call per arm, so that each operation gets its own (inlined, vectorizable) loop rather
    // than a call through a function pointer per lane.
    match op {
        Unary::Neg => same_file1(file, dst, a, |x: F| -x),
        Unary::Abs => same_file1(file, dst, a, F::abs),
        Unary::Floor => same_file1(file, dst, a, F::floor),
        Unary::Ceil => same_file1(file, dst, a, F::ceil),
        Unary::Trunc => same_file1(file, dst, a, F::trunc),
        Unary::Round => same_file1(file, dst, a, F::round_even),
        Unary::Fract => same_file1(file, dst, a, s::fract),
        Unary::Sign => same_file1(file, dst, a, s::sign),
        Unary::Sqrt => same_file1(file, dst, a, F::sqrt),
        Unary::InverseSqrt => same_file1(file, dst, a, s::inverse_sqrt),
        Unary::Sin => same_file1(file, dst, a, F::sin),
        Unary::Cos => same_file1(file, dst, a, F::cos),
        Unary::Tan => same_file1(file, dst, a, F::tan),
        Unary::Asin => same_file1(file, dst, a, F::asin),
        Unary::Acos => same_file1(file, dst, a, F::acos),
        Unary::Atan => same_file1(file, dst, a, F::atan),
        Unary::Exp => same_file1(file, dst, a, F::exp),
        Unary::Log => same_file1(file, dst, a, F::ln),
    }
}

#[inline(always)]
fn float_binary<F: Real>(file: &mut File<F>, op: Binary, dst: Reg, a: Reg, b: Reg) {
    // The four commonest operations get their own loops so that they vectorize.
    match op {
        Binary::Add => same_file2(file, dst, a, b, |x, y| x + y),
        Binary::Sub => same_file2(file, dst, a, b, |x, y| x - y),
        Binary::Mul => same_file2(file, dst, a, b, |x, y| x * y),
        Binary::Div => same_file2(file, dst, a, b, |x, y| x / y),
        Binary::Min => same_file2(file, dst, a, b, F::min),
        Binary::Max => same_file2(file, dst, a, b, F::max),
        Binary::Pow => same_file2(file, dst, a, b, F::powf),
        Binary::Atan2 => same_file2(file, dst, a, b, F::atan2),
        Binary::Mod => same_file2(file, dst, a, b, s::modulo),
        Binary::Step => same_file2(file, dst, a, b, s::step),
    }
}

#[inline(always)]
fn int_binary(file: &mut File<u32>, op: IntBinary, dst: Reg, a: Reg, b: Reg) {
    let i = |x: u32| x as i32;
    match op {
        IntBinary::Add => same_file2(file, dst, a, b, u32::wrapping_add),
        IntBinary::Sub => same_file2(file, dst, a, b, u32::wrapping_sub),
        IntBinary::Mul => same_file2(file, dst, a, b, u32::wrapping_mul),
        IntBinary::DivI => same_file2(file, dst, a, b, |x, y| s::div_i32(i(x), i(y)) as u32),
        IntBinary::DivU => same_file2(file, dst, a, b, s::div_u32),
        IntBinary::RemI => same_file2(file, dst, a, b, |x, y| s::rem_i32(i(x), i(y)) as u32),
        IntBinary::RemU => same_file2(file, dst, a, b, s::rem_u32),
        IntBinary::And => same_file2(file, dst, a, b, |x, y| x & y),
        IntBinary::Or => same_file2(file, dst, a, b, |x, y| x | y),
        IntBinary::Xor => same_file2(file, dst, a, b, |x, y| x ^ y),
        IntBinary::Shl => same_file2(file, dst, a, b, s::shl_u32),
        IntBinary::ShrI => same_file2(file, dst, a, b, |x, y| s::shr_i32(i(x), y) as u32),
        IntBinary::ShrU => same_file2(file, dst, a, b, s::shr_u32),
        IntBinary::MinI => same_file2(file, dst, a, b, |x, y| i(x).min(i(y)) as u32),
        IntBinary::MinU => same_file2(file, dst, a, b, u32::min),
        IntBinary::MaxI => same_file2(file, dst, a, b, |x, y| i(x).max(i(y)) as u32),
        IntBinary::MaxU => same_file2(file, dst, a, b, u32::max),
    }
}

#[inline(always)]
fn same_file1<T: Copy>(file: &mut File<T>, dst: Reg, a: Reg, f: impl Fn(T) -> T) {
    if dst.uniform {
        file.uniform[dst.index as usize] = f(file.uniform[a.index as usize]);
    } else {
        let (d, view) = file.split(dst.index);
        map1(d, view.read(a), f);
    }
}

#[inline(always)]
fn same_file2<T: Copy>(file: &mut File<T>, dst: Reg, a: Reg, b: Reg, f: impl Fn(T, T) -> T) {
    if dst.uniform {
        let u = &mut file.uniform;
        u[dst.index as usize] = f(u[a.index as usize], u[b.index as usize]);
    } else {
        let (d, view) = file.split(dst.index);
        map2(d, view.read(a), view.read(b), f);
    }
}

#[inline(always)]
fn same_file3<T: Copy>(file: &mut File<T>, dst: Reg, a: Reg, b: Reg, c: Reg, f: impl Fn(T, T, T) -> T) {
    if dst.uniform {
        let u = &mut file.uniform;
        u[dst.index as usize] = f(u[a.index as usize], u[b.index as usize], u[c.index as usize]);
    } else {
        let (d, view) = file.split(dst.index);
        map3(d, view.read(a), view.read(b), view.read(c), f);
    }
}

#[inline(always)]
fn cross1<A: Copy, D: Copy>(from: &File<A>, to: &mut File<D>, dst: Reg, a: Reg, f: impl Fn(A) -> D) {
    if dst.uniform {
        to.uniform[dst.index as usize] = f(from.uniform[a.index as usize]);
    } else {
        map1(&mut to.varying[dst.index as usize], from.read(a), f);
    }
}

#[inline(always)]
fn cross2<A: Copy, D: Copy>(
    from: &File<A>,
    to: &mut File<D>,
    dst: Reg,
    a: Reg,
    b: Reg,
    f: impl Fn(A, A) -> D,
) {
    if dst.uniform {
        to.uniform[dst.index as usize] = f(from.uniform[a.index as usize], from.uniform[b.index as usize]);
    } else {
        map2(&mut to.varying[dst.index as usize], from.read(a), from.read(b), f);
    }
}

/// `d[l] = cond[l] != 0 ? a[l] : b[l]`.
#[inline(always)]
fn select<T: Copy>(d: &mut [T; LANES], cond: Lanes<'_, u32>, a: Lanes<'_, T>, b: Lanes<'_, T>) {
    match cond {
        Lanes::Uniform(c) => map1(d, if c != 0 { a } else { b }, |x| x),
        Lanes::Varying(c) => map3(d, Lanes::Varying(c), a, b, |c, a, b| if c != 0 { a } else { b }),
    }
}

/// A store into a variable: only the lanes of the mask change.
#[inline(always)]
fn store<T: Copy>(file: &mut File<T>, dst: Reg, src: Reg, mask: &Mask) {
    if dst == src {
        return;
    }
    if dst.uniform {
        // The rate rules guarantee uniform variables are stored under uniform control only, and
        // only from uniform values (the lowering checks the latter).
        file.uniform[dst.index as usize] = file.uniform[src.index as usize];
        return;
    }
    let (d, view) = file.split(dst.index);
    let src = view.read(src);
    if mask.all() {
        map1(d, src, |x| x);
    } else {
        for (lane, d) in d.iter_mut().enumerate() {
            if mask.has(lane) {
                *d = src.at(lane);
            }
        }
    }
}

/// Where element `i` of an array lives, with the index clamped into the array.
#[derive(Copy, Clone)]
struct Clamp {
    len: u32,
    stride: u32,
    signed: bool,
}

impl Clamp {
    #[inline(always)]
    fn offset(self, raw: u32) -> u32 {
        let last = self.len.saturating_sub(1);
        let i = if self.signed { (raw as i32).clamp(0, last as i32) as u32 } else { raw.min(last) };
        i * self.stride
    }

    /// The offset of the last element.
    #[inline(always)]
    fn last_offset(self) -> u32 {
        self.len.saturating_sub(1) * self.stride
    }
}

/// `d[l] = array[index[l]]`, for a varying destination.
#[inline(always)]
fn gather<T: Copy>(d: &mut [T; LANES], view: &View<'_, T>, base: Reg, index: Lanes<'_, u32>, at: Clamp) {
    match (base.uniform, index) {
        (true, Lanes::Uniform(i)) => d.fill(view.uniform(base.index + at.offset(i))),
        // A table lookup (a permutation, a colour table): the commonest gather in the stdlib.
        (true, Lanes::Varying(index)) => {
            let table = view.uniforms(base.index as usize, at.last_offset() as usize + 1);
            // Clamped offsets are at most the table's last; the `min` says so to the compiler,
            // which then needs no bounds check per lane. One loop per signedness, so that no lane
            // tests it.
            let (top, stride) = (table.len().saturating_sub(1), at.stride as usize);
            let last = at.len.saturating_sub(1);
            let lookup = |i: u32| table[(i as usize * stride).min(top)];
            if at.signed {
                let last = last.min(i32::MAX as u32) as i32;
                map1(d, Lanes::Varying(index), |i| lookup((i as i32).max(0).min(last) as u32));
            } else {
                map1(d, Lanes::Varying(index), |i| lookup(i.min(last)));
            }
        }
        (false, Lanes::Uniform(i)) => *d = *view.varying(base.index + at.offset(i)),
        (false, Lanes::Varying(index)) => {
            for (lane, d) in d.iter_mut().enumerate() {
                *d = view.varying(base.index + at.offset(index[lane]))[lane];
            }
        }
    }
}

#[inline(always)]
fn scatter<T: Copy>(file: &mut File<T>, base: Reg, index: Lanes<'_, u32>, src: Reg, at: Clamp, mask: &Mask) {
    if base.uniform {
        let to = base.index + at.offset(index.at(0));
        file.uniform[to as usize] = file.uniform[src.index as usize];
        return;
    }
    let src = lanes_copy(file, src);
    let src = src.as_lanes();
    for lane in (0..LANES).filter(|l| mask.has(*l)) {
        let to = base.index + at.offset(index.at(lane));
        file.varying[to as usize][lane] = src.at(lane);
    }
}

/// An operand copied out of its file (onto the stack), so that the file can be written while it is
/// read.
enum Copied<T> {
    Varying([T; LANES]),
    Uniform(T),
}

impl<T: Copy> Copied<T> {
    fn as_lanes(&self) -> Lanes<'_, T> {
        match self {
            Copied::Varying(v) => Lanes::Varying(v),
            Copied::Uniform(x) => Lanes::Uniform(*x),
        }
    }
}

#[inline(always)]
fn lanes_copy<T: Copy>(file: &File<T>, r: Reg) -> Copied<T> {
    match file.read(r) {
        Lanes::Varying(v) => Copied::Varying(*v),
        Lanes::Uniform(x) => Copied::Uniform(x),
    }
}

/// The most `printf` lines one process writes; past it, one line says the rest were dropped.
pub const MAX_PRINTED_LINES: u64 = 100;

/// Writes one line of `printf` output to stderr, counting lines per process: after
/// [`MAX_PRINTED_LINES`] lines a single `... further printf output left out` line follows, and
/// nothing more.
fn print_line(line: &str) {
    use std::sync::atomic::{AtomicU64, Ordering};
    static PRINTED: AtomicU64 = AtomicU64::new(0);
    let n = PRINTED.fetch_add(1, Ordering::Relaxed);
    if n < MAX_PRINTED_LINES {
        eprintln!("{line}");
    } else if n == MAX_PRINTED_LINES {
        eprintln!("... further printf output left out (more than {MAX_PRINTED_LINES} lines)");
    }
}
