//! Execution masks: which lanes of a batch a statement runs for.

use super::LANES;
use super::kernels::Lanes;

/// A set of lanes, with its size kept so that "none" and "all" are cheap to test.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Mask {
    lanes: [bool; LANES],
    count: usize,
}

impl Mask {
    /// No lane.
    pub fn none() -> Mask {
        Mask { lanes: [false; LANES], count: 0 }
    }

    /// The first `n` lanes (a batch that is not full).
    pub fn first(n: usize) -> Mask {
        let n = n.min(LANES);
        let mut lanes = [false; LANES];
        lanes[..n].fill(true);
        Mask { lanes, count: n }
    }

    /// Whether any lane is in the set.
    pub fn any(&self) -> bool {
        self.count > 0
    }

    /// Whether every lane is in the set.
    pub fn all(&self) -> bool {
        self.count == LANES
    }

    /// Whether `lane` is in the set.
    #[inline(always)]
    pub fn has(&self, lane: usize) -> bool {
        self.lanes[lane]
    }

    /// The lanes of `self` where `cond` is non-zero, and those where it is zero.
    pub fn split(&self, cond: Lanes<'_, u32>) -> (Mask, Mask) {
        match cond {
            Lanes::Uniform(c) if c != 0 => (self.clone(), Mask::none()),
            Lanes::Uniform(_) => (Mask::none(), self.clone()),
            Lanes::Varying(c) => {
                let mut yes = Mask::none();
                let mut no = Mask::none();
                for (((yes, no), active), c) in
                    yes.lanes.iter_mut().zip(&mut no.lanes).zip(&self.lanes).zip(c)
                {
                    *yes = *active && *c != 0;
                    *no = *active && *c == 0;
                }
                yes.recount();
                no.recount();
                (yes, no)
            }
        }
    }

    /// Adds the lanes of `other`.
    pub fn add(&mut self, other: &Mask) {
        for (a, b) in self.lanes.iter_mut().zip(&other.lanes) {
            *a |= *b;
        }
        self.recount();
    }

    /// Removes the lanes of `other`.
    pub fn remove(&mut self, other: &Mask) {
        if !other.any() {
            return;
        }
        for (a, b) in self.lanes.iter_mut().zip(&other.lanes) {
            *a &= !*b;
        }
        self.recount();
    }

    fn recount(&mut self) {
        self.count = self.lanes.iter().filter(|l| **l).count();
    }
}
