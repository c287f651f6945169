//! Lane loops: each instruction applies a per-lane function over a batch. The uniform/varying
//! combinations of the operands are matched once per instruction, outside the loop, so each loop is
//! a plain pass over fixed-size arrays that the compiler can vectorize.

use super::LANES;
use crate::backend::cpu::code::Reg;

/// One register file: uniform registers (one value) and varying ones (one value per lane).
#[derive(Clone, Debug)]
pub(crate) struct File<T> {
    pub uniform: Vec<T>,
    pub varying: Vec<[T; LANES]>,
}

/// An operand as the loops see it.
#[derive(Copy, Clone)]
pub(crate) enum Lanes<'a, T> {
    /// One value per lane.
    Varying(&'a [T; LANES]),
    /// One value for all lanes.
    Uniform(T),
}

impl<T: Copy> Lanes<'_, T> {
    #[inline(always)]
    pub fn at(&self, lane: usize) -> T {
        match self {
            Lanes::Varying(v) => v[lane],
            Lanes::Uniform(x) => *x,
        }
    }
}

impl<T: Copy> File<T> {
    pub fn new(uniform: u32, varying: u32, zero: T) -> Self {
        File { uniform: vec![zero; uniform as usize], varying: vec![[zero; LANES]; varying as usize] }
    }

    /// The lanes of a varying register.
    #[inline(always)]
    pub fn lanes_mut(&mut self, r: Reg) -> &mut [T; LANES] {
        &mut self.varying[r.index as usize]
    }

    /// Sets every lane of a register (the one value of a uniform one).
    #[inline(always)]
    pub fn fill(&mut self, r: Reg, x: T) {
        if r.uniform {
            self.uniform[r.index as usize] = x;
        } else {
            self.varying[r.index as usize].fill(x);
        }
    }

    /// The value of a register in `lane`.
    #[inline(always)]
    pub fn at(&self, r: Reg, lane: usize) -> T {
        if r.uniform { self.uniform[r.index as usize] } else { self.varying[r.index as usize][lane] }
    }

    /// A source operand of an instruction whose destination is in another file.
    #[inline(always)]
    pub fn read(&self, r: Reg) -> Lanes<'_, T> {
        if r.uniform {
            Lanes::Uniform(self.uniform[r.index as usize])
        } else {
            Lanes::Varying(&self.varying[r.index as usize])
        }
    }

    /// The varying destination `dst` and a reader for the rest of the file. An instruction never
    /// reads its own destination (the lowering allocates a fresh one), which is what lets the two
    /// borrows coexist.
    #[inline(always)]
    pub fn split(&mut self, dst: u32) -> (&mut [T; LANES], View<'_, T>) {
        let (lo, rest) = self.varying.split_at_mut(dst as usize);
        let (d, hi) = rest.split_first_mut().expect("destination register exists");
        (d, View { uniform: &self.uniform, lo, hi, at: dst })
    }
}

/// The registers of a file other than one varying destination.
pub(crate) struct View<'a, T> {
    uniform: &'a [T],
    lo: &'a [[T; LANES]],
    hi: &'a [[T; LANES]],
    at: u32,
}

impl<'a, T: Copy> View<'a, T> {
    #[inline(always)]
    pub fn read(&self, r: Reg) -> Lanes<'a, T> {
        if r.uniform {
            return Lanes::Uniform(self.uniform[r.index as usize]);
        }
        let i = r.index;
        assert!(i != self.at, "interpreter invariant: an instruction never reads its destination");
        if i < self.at {
            Lanes::Varying(&self.lo[i as usize])
        } else {
            Lanes::Varying(&self.hi[(i - self.at - 1) as usize])
        }
    }

    /// The varying register `index + offset` of an array (never the destination).
    #[inline(always)]
    pub fn varying(&self, index: u32) -> &'a [T; LANES] {
        match self.read(Reg::varying(index)) {
            Lanes::Varying(v) => v,
            Lanes::Uniform(_) => unreachable!(),
        }
    }

    /// The uniform registers `start..start + len` (an array's, all within the file).
    #[inline(always)]
    pub fn uniforms(&self, start: usize, len: usize) -> &'a [T] {
        &self.uniform[start..start + len]
    }

    /// The uniform register `index`.
    #[inline(always)]
    pub fn uniform(&self, index: u32) -> T {
        self.uniform[index as usize]
    }
}

/// `d[l] = f(a[l])`.
#[inline(always)]
pub(crate) fn map1<A: Copy, D>(d: &mut [D; LANES], a: Lanes<'_, A>, f: impl Fn(A) -> D) {
    match a {
        Lanes::Varying(a) => {
            for (d, a) in d.iter_mut().zip(a) {
                *d = f(*a);
            }
        }
        Lanes::Uniform(a) => d.fill_with(|| f(a)),
    }
}

/// `d[l] = f(a[l], b[l])`.
#[inline(always)]
pub(crate) fn map2<A: Copy, B: Copy, D>(
    d: &mut [D; LANES],
    a: Lanes<'_, A>,
    b: Lanes<'_, B>,
    f: impl Fn(A, B) -> D,
) {
    match (a, b) {
        (Lanes::Varying(a), Lanes::Varying(b)) => {
            for ((d, a), b) in d.iter_mut().zip(a).zip(b) {
                *d = f(*a, *b);
            }
        }
        (Lanes::Varying(a), Lanes::Uniform(b)) => {
            for (d, a) in d.iter_mut().zip(a) {
                *d = f(*a, b);
            }
        }
        (Lanes::Uniform(a), Lanes::Varying(b)) => {
            for (d, b) in d.iter_mut().zip(b) {
                *d = f(a, *b);
            }
        }
        (Lanes::Uniform(a), Lanes::Uniform(b)) => d.fill_with(|| f(a, b)),
    }
}

/// `d[l] = f(a[l], b[l], c[l])`.
#[inline(always)]
pub(crate) fn map3<A: Copy, B: Copy, C: Copy, D>(
    d: &mut [D; LANES],
    a: Lanes<'_, A>,
    b: Lanes<'_, B>,
    c: Lanes<'_, C>,
    f: impl Fn(A, B, C) -> D,
) {
    use Lanes::{Uniform as U, Varying as V};
    match (a, b, c) {
        (V(a), V(b), V(c)) => {
            for (((d, a), b), c) in d.iter_mut().zip(a).zip(b).zip(c) {
                *d = f(*a, *b, *c);
            }
        }
        (V(a), U(b), U(c)) => {
            for (d, a) in d.iter_mut().zip(a) {
                *d = f(*a, b, c);
            }
        }
        (U(a), U(b), V(c)) => {
            for (d, c) in d.iter_mut().zip(c) {
                *d = f(a, b, *c);
            }
        }
        (V(a), V(b), U(c)) => {
            for ((d, a), b) in d.iter_mut().zip(a).zip(b) {
                *d = f(*a, *b, c);
            }
        }
        (V(a), U(b), V(c)) => {
            for ((d, a), c) in d.iter_mut().zip(a).zip(c) {
                *d = f(*a, b, *c);
            }
        }
        (U(a), V(b), V(c)) => {
            for ((d, b), c) in d.iter_mut().zip(b).zip(c) {
                *d = f(a, *b, *c);
            }
        }
        (U(a), V(b), U(c)) => {
            for (d, b) in d.iter_mut().zip(b) {
                *d = f(a, *b, c);
            }
        }
        (U(a), U(b), U(c)) => d.fill_with(|| f(a, b, c)),
    }
}
