//! Execution masks: which lanes of a batch a statement runs for.

use super::LANES;
use super::kernels::Lanes;

/// 64-lane words in a mask.
const WORDS: usize = LANES.div_ceil(64);

/// A set of lanes, one bit each, so that the tests and set operations every statement does under
/// divergent control flow cost a few word operations rather than a pass over the lanes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Mask {
    bits: [u64; WORDS],
}

impl Mask {
    /// No lane.
    pub fn none() -> Mask {
        Mask { bits: [0; WORDS] }
    }

    /// The first `n` lanes (a batch that is not full).
    pub fn first(n: usize) -> Mask {
        let n = n.min(LANES);
        let mut bits = [0; WORDS];
        for (w, word) in bits.iter_mut().enumerate() {
            let lanes = n.saturating_sub(w * 64).min(64);
            *word = if lanes == 64 { u64::MAX } else { (1u64 << lanes) - 1 };
        }
        Mask { bits }
    }

    /// Whether any lane is in the set.
    pub fn any(&self) -> bool {
        self.bits.iter().any(|w| *w != 0)
    }

    /// Whether every lane is in the set.
    pub fn all(&self) -> bool {
        *self == Mask::first(LANES)
    }

    /// Whether `lane` is in the set.
    #[inline(always)]
    pub fn has(&self, lane: usize) -> bool {
        self.bits[lane / 64] >> (lane % 64) & 1 != 0
    }

    /// The lanes of `self` where `cond` is non-zero, and those where it is zero.
    pub fn split(&self, cond: Lanes<'_, u32>) -> (Mask, Mask) {
        match cond {
            Lanes::Uniform(c) if c != 0 => (self.clone(), Mask::none()),
            Lanes::Uniform(_) => (Mask::none(), self.clone()),
            Lanes::Varying(c) => {
                let mut set = [0u64; WORDS];
                for (word, lanes) in set.iter_mut().zip(c.chunks(64)) {
                    *word = lanes.iter().enumerate().fold(0, |w, (i, c)| w | u64::from(*c != 0) << i);
                }
                let yes = std::array::from_fn(|w| self.bits[w] & set[w]);
                let no = std::array::from_fn(|w| self.bits[w] & !set[w]);
                (Mask { bits: yes }, Mask { bits: no })
            }
        }
    }

    /// Adds the lanes of `other`.
    pub fn add(&mut self, other: &Mask) {
        for (a, b) in self.bits.iter_mut().zip(&other.bits) {
            *a |= *b;
        }
    }

    /// Removes the lanes of `other`.
    pub fn remove(&mut self, other: &Mask) {
        for (a, b) in self.bits.iter_mut().zip(&other.bits) {
            *a &= !*b;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lanes(m: &Mask) -> Vec<usize> {
        (0..LANES).filter(|l| m.has(*l)).collect()
    }

    #[test]
    fn first_split_add_and_remove_are_set_operations() {
        assert_eq!(lanes(&Mask::first(0)), Vec::<usize>::new());
        assert_eq!(lanes(&Mask::first(70)), (0..70).collect::<Vec<_>>());
        assert!(Mask::first(LANES).all() && !Mask::first(LANES - 1).all());
        assert!(!Mask::none().any() && Mask::first(1).any());
        let cond: [u32; LANES] = std::array::from_fn(|l| (l % 3 == 0) as u32 * 7);
        let (yes, no) = Mask::first(100).split(Lanes::Varying(&cond));
        assert_eq!(lanes(&yes), (0..100).filter(|l| l % 3 == 0).collect::<Vec<_>>());
        assert_eq!(lanes(&no), (0..100).filter(|l| l % 3 != 0).collect::<Vec<_>>());
        let mut m = yes.clone();
        m.add(&no);
        assert_eq!(m, Mask::first(100));
        m.remove(&yes);
        assert_eq!(m, no);
        assert_eq!(Mask::first(5).split(Lanes::Uniform(1)), (Mask::first(5), Mask::none()));
        assert_eq!(Mask::first(5).split(Lanes::Uniform(0)), (Mask::none(), Mask::first(5)));
    }
}
