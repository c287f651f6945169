//! The fixed sequences of scalar operations both backends compute, written once.
//!
//! Where WGSL leaves an order of operations open (`dot`, `length`, matrix products and inverses)
//! or defines a result by a formula a driver may compute its own way (`smoothstep`, `clamp` with
//! crossed bounds, `sign` of NaN, RenderMan's `mod`), Patina fixes one sequence, and the backends
//! agree bit for bit only if each performs exactly that sequence. The sequences live here, generic
//! over [`Arith`], which each backend implements on what it builds: the interpreter on numbers
//! inside its instructions (`cpu::scalar::Numbers`) and on registers while it lowers
//! (`cpu::lower`), the WGSL backend on naga expressions (`wgsl::matrices`).
//!
//! The componentwise sequences are [`Arith`]'s provided methods. The interpreter keeps each of them
//! as one instruction, for speed, by overriding the method with that instruction; the instruction
//! executes the provided method on numbers, so the definition is still the one written here.

/// The scalar operations the sequences are written in.
pub(crate) trait Arith {
    /// A float value: a number, a register, an expression.
    type V: Copy;
    /// A truth value.
    type B: Copy;

    /// The float `x`.
    fn constant(&mut self, x: f64) -> Self::V;
    /// `a + b`.
    fn add(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `a - b`.
    fn sub(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `a * b`.
    fn mul(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `a / b`.
    fn div(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `-a`.
    fn neg(&mut self, a: Self::V) -> Self::V;
    /// The correctly rounded square root.
    fn sqrt(&mut self, a: Self::V) -> Self::V;
    /// Rounds toward negative infinity.
    fn floor(&mut self, a: Self::V) -> Self::V;
    /// The smaller operand; the other one when one is NaN (WGSL's `min` on the devices we test).
    fn min(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// The larger operand; the other one when one is NaN.
    fn max(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `a < b`.
    fn less(&mut self, a: Self::V, b: Self::V) -> Self::B;
    /// `a > b`.
    fn greater(&mut self, a: Self::V, b: Self::V) -> Self::B;
    /// `a >= b`.
    fn greater_equal(&mut self, a: Self::V, b: Self::V) -> Self::B;
    /// Whether `a` is a NaN.
    fn is_nan(&mut self, a: Self::V) -> Self::B;
    /// `c ? a : b`, both operands computed.
    fn select(&mut self, c: Self::B, a: Self::V, b: Self::V) -> Self::V;

    /// `clamp(x, lo, hi)`: `min(max(x, lo), hi)`, WGSL's formula, which also answers crossed
    /// bounds (`hi` wins) and NaN (`lo`), where WGSL's `clamp` leaves them open.
    fn clamp(&mut self, x: Self::V, lo: Self::V, hi: Self::V) -> Self::V {
        let above = self.max(x, lo);
        self.min(above, hi)
    }

    /// `step(edge, x)`: 1 when `x >= edge`, else 0 (so 0 for a NaN `x`, which WGSL's `step`
    /// answers 1 on some devices).
    fn step(&mut self, edge: Self::V, x: Self::V) -> Self::V {
        let (zero, one) = (self.constant(0.0), self.constant(1.0));
        let above = self.greater_equal(x, edge);
        self.select(above, one, zero)
    }

    /// `smoothstep(lo, hi, x)`: `t * t * (3 - 2 * t)` with `t = clamp((x - lo) / (hi - lo), 0, 1)`,
    /// WGSL's formula in this order.
    fn smoothstep(&mut self, lo: Self::V, hi: Self::V, x: Self::V) -> Self::V {
        let (num, den) = (self.sub(x, lo), self.sub(hi, lo));
        let t = self.div(num, den);
        let (zero, one, two, three) =
            (self.constant(0.0), self.constant(1.0), self.constant(2.0), self.constant(3.0));
        let t = self.clamp(t, zero, one);
        let tt = self.mul(t, t);
        let twice = self.mul(two, t);
        let rest = self.sub(three, twice);
        self.mul(tt, rest)
    }

    /// RenderMan's `mod(a, b)`: `a - b * floor(a / b)`, whose result has the sign of `b` (WGSL's
    /// `%` truncates instead).
    fn modulo(&mut self, a: Self::V, b: Self::V) -> Self::V {
        let q = self.div(a, b);
        let whole = self.floor(q);
        let p = self.mul(b, whole);
        self.sub(a, p)
    }

    /// WGSL's `sign`: 1, -1, 0 for NaN, and a zero itself (keeping its sign).
    fn sign(&mut self, x: Self::V) -> Self::V {
        let (zero, one, minus_one) = (self.constant(0.0), self.constant(1.0), self.constant(-1.0));
        let nan = self.is_nan(x);
        let r = self.select(nan, zero, x);
        let below = self.less(x, zero);
        let r = self.select(below, minus_one, r);
        let above = self.greater(x, zero);
        self.select(above, one, r)
    }

    /// `inversesqrt(x)`: `1 / sqrt(x)` (WGSL's `inverseSqrt` may differ by 2 ulp).
    fn inverse_sqrt(&mut self, x: Self::V) -> Self::V {
        let one = self.constant(1.0);
        let root = self.sqrt(x);
        self.div(one, root)
    }
}

/// `a0 b0 + a1 b1 + ...`, summed left to right.
pub(crate) fn dot<A: Arith>(s: &mut A, a: &[A::V], b: &[A::V]) -> A::V {
    let mut sum = s.mul(a[0], b[0]);
    for (x, y) in a.iter().zip(b).skip(1) {
        let p = s.mul(*x, *y);
        sum = s.add(sum, p);
    }
    sum
}

/// `sqrt(v . v)`.
pub(crate) fn length<A: Arith>(s: &mut A, v: &[A::V]) -> A::V {
    let d = dot(s, v, v);
    s.sqrt(d)
}

/// `v / length(v)` (a zero vector gives NaN, as in WGSL; the library guards where it matters).
pub(crate) fn normalize<A: Arith>(s: &mut A, v: &[A::V]) -> Vec<A::V> {
    let len = length(s, v);
    v.iter().map(|x| s.div(*x, len)).collect()
}

/// `a ^ b` of three-component vectors.
pub(crate) fn cross<A: Arith>(s: &mut A, a: &[A::V], b: &[A::V]) -> [A::V; 3] {
    let mut term = |i: usize, j: usize| {
        let p = s.mul(a[i], b[j]);
        let q = s.mul(a[j], b[i]);
        s.sub(p, q)
    };
    [term(1, 2), term(2, 0), term(0, 1)]
}

/// The product `a * b` of two `n` x `n` matrices, entries row by row: each entry the [`dot`] of a
/// row of `a` and a column of `b`.
pub(crate) fn product<A: Arith>(s: &mut A, a: &[A::V], b: &[A::V], n: usize) -> Vec<A::V> {
    let mut out = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let row: Vec<A::V> = (0..n).map(|k| a[i * n + k]).collect();
            let column: Vec<A::V> = (0..n).map(|k| b[k * n + j]).collect();
            out.push(dot(s, &row, &column));
        }
    }
    out
}

/// The inverse of an `n` x `n` matrix (entries row by row): the adjugate over the determinant,
/// each cofactor by Laplace expansion ([`minor`]). A singular matrix gives infinities or NaN, as
/// dividing by zero does. The library's `determinant` (compiler/stdlib/builtins.sl) repeats the
/// expansion operation for operation.
pub(crate) fn invert<A: Arith>(s: &mut A, m: &[A::V], n: usize) -> Vec<A::V> {
    let all: Vec<usize> = (0..n).collect();
    let det = minor(s, m, n, &all, &all);
    let mut out = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            // inverse[i][j] = cofactor[j][i] / det.
            let rows: Vec<usize> = all.iter().copied().filter(|r| *r != j).collect();
            let columns: Vec<usize> = all.iter().copied().filter(|c| *c != i).collect();
            let minor = minor(s, m, n, &rows, &columns);
            let cofactor = if (i + j) % 2 == 0 { minor } else { s.neg(minor) };
            out.push(s.div(cofactor, det));
        }
    }
    out
}

/// The determinant of the submatrix of `m` (`n` x `n`, row by row) on the rows and columns given,
/// by Laplace expansion along its first row, terms summed left to right.
pub(crate) fn minor<A: Arith>(s: &mut A, m: &[A::V], n: usize, rows: &[usize], columns: &[usize]) -> A::V {
    let at = |r: usize, c: usize| m[r * n + c];
    match rows.len() {
        0 => s.constant(1.0),
        1 => at(rows[0], columns[0]),
        2 => {
            let a = s.mul(at(rows[0], columns[0]), at(rows[1], columns[1]));
            let b = s.mul(at(rows[0], columns[1]), at(rows[1], columns[0]));
            s.sub(a, b)
        }
        _ => {
            let mut sum: Option<A::V> = None;
            for (k, &c) in columns.iter().enumerate() {
                let rest: Vec<usize> = columns.iter().copied().filter(|x| *x != c).collect();
                let sub = minor(s, m, n, &rows[1..], &rest);
                let term = s.mul(at(rows[0], c), sub);
                sum = Some(match sum {
                    None => term,
                    Some(total) if k % 2 == 0 => s.add(total, term),
                    Some(total) => s.sub(total, term),
                });
            }
            sum.unwrap_or_else(|| s.constant(1.0))
        }
    }
}

/// The three-argument `filterstep(edge, x0, x1)`: the fraction of `[x0, x1]` at or above `edge`,
/// a plain [`Arith::step`] at `x0` when the interval is empty.
pub(crate) fn filterstep<A: Arith>(s: &mut A, edge: A::V, x0: A::V, x1: A::V) -> A::V {
    let width = s.sub(x1, x0);
    let above = s.sub(x1, edge);
    let t = s.div(above, width);
    let (zero, one) = (s.constant(0.0), s.constant(1.0));
    let t = s.clamp(t, zero, one);
    let step = s.step(edge, x0);
    let wide = s.greater(width, zero);
    s.select(wide, t, step)
}

/// How `transform` treats a three-component value.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Rule {
    /// Translated and divided by w.
    Point,
    /// Not translated.
    Vector,
    /// By the inverse transpose.
    Normal,
}

impl Rule {
    /// The rule of a value of type `base`.
    pub(crate) fn of(base: crate::ir::types::Base) -> Rule {
        use crate::ir::types::Base;
        match base {
            Base::Point => Rule::Point,
            Base::Normal => Rule::Normal,
            _ => Rule::Vector,
        }
    }
}

/// `v` (three components) transformed by the 4 x 4 matrix `m` (entries row by row) under `rule`,
/// in RenderMan's row-vector convention, `(v, 1) m` for a point, then divided by w; `inv` is `m`'s
/// inverse, which only normals use (`n' = n inverse(m)^T`). Sums left to right, the translation
/// last.
pub(crate) fn apply<A: Arith>(s: &mut A, v: &[A::V], rule: Rule, m: &[A::V], inv: &[A::V]) -> Vec<A::V> {
    let column = |s: &mut A, j: usize, entry: &dyn Fn(usize, usize) -> A::V, w: Option<A::V>| {
        let mut sum = s.mul(v[0], entry(0, j));
        for (i, x) in v.iter().enumerate().skip(1).take(2) {
            let p = s.mul(*x, entry(i, j));
            sum = s.add(sum, p);
        }
        match w {
            Some(t) => s.add(sum, t),
            None => sum,
        }
    };
    match rule {
        Rule::Point => {
            let h: Vec<A::V> = (0..4).map(|j| column(s, j, &|i, j| m[i * 4 + j], Some(m[12 + j]))).collect();
            (0..3).map(|j| s.div(h[j], h[3])).collect()
        }
        Rule::Vector => (0..3).map(|j| column(s, j, &|i, j| m[i * 4 + j], None)).collect(),
        // Element (i, j) of the inverse's transpose is inv[j][i].
        Rule::Normal => (0..3).map(|j| column(s, j, &|i, j| inv[j * 4 + i], None)).collect(),
    }
}

/// The `u32` operations `random()`'s hash is written in, wrapping as WGSL's are.
pub(crate) trait Words {
    /// A `u32`.
    type W: Copy;
    /// A float value.
    type F;
    /// The word `x`.
    fn word(&mut self, x: u32) -> Self::W;
    /// `a * b`, wrapping.
    fn wrapping_mul(&mut self, a: Self::W, b: Self::W) -> Self::W;
    /// `a + b`, wrapping.
    fn wrapping_add(&mut self, a: Self::W, b: Self::W) -> Self::W;
    /// `a >> b` (`b` below 32).
    fn shift_right(&mut self, a: Self::W, b: Self::W) -> Self::W;
    /// `a ^ b`.
    fn xor(&mut self, a: Self::W, b: Self::W) -> Self::W;
    /// A word below 2^24 as a float, times 2^-24 (exact in f32).
    fn unit(&mut self, w: Self::W) -> Self::F;
}

/// `random()`: a float in [0, 1) from a hash of the point's index and the call site, PCG's output
/// permutation applied twice, `pcg(pcg(point) ^ site * 0x9e3779b9)`, its top 24 bits over 2^24, so
/// a program gives the same values on every run and every backend.
pub(crate) fn random<S: Words>(s: &mut S, point: S::W, site: u32) -> S::F {
    let inner = pcg(s, point);
    let salt = s.word(site.wrapping_mul(0x9e37_79b9));
    let mixed = s.xor(inner, salt);
    let h = pcg(s, mixed);
    let eight = s.word(8);
    let top = s.shift_right(h, eight);
    s.unit(top)
}

/// PCG's output permutation (RXS-M-XS) of one step of its LCG from `x`.
fn pcg<S: Words>(s: &mut S, x: S::W) -> S::W {
    let (multiplier, increment) = (s.word(747_796_405), s.word(2_891_336_453));
    let state = s.wrapping_mul(x, multiplier);
    let state = s.wrapping_add(state, increment);
    let (k28, k4) = (s.word(28), s.word(4));
    let top = s.shift_right(state, k28);
    let shift = s.wrapping_add(top, k4);
    let shifted = s.shift_right(state, shift);
    let word = s.xor(shifted, state);
    let m = s.word(277_803_737);
    let word = s.wrapping_mul(word, m);
    let k22 = s.word(22);
    let high = s.shift_right(word, k22);
    s.xor(high, word)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::cpu::scalar::Numbers;

    #[test]
    fn random_is_pcg_applied_twice() {
        // The hash in closed form, as docs/numerics.md states it.
        fn pcg(x: u32) -> u32 {
            let state = x.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
            let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
            (word >> 22) ^ word
        }
        for (point, site) in [(0u32, 1u32), (1, 1), (12_345, 7), (u32::MAX, 3), (65_536 * 480 + 17, 200)] {
            let expected = f64::from(pcg(pcg(point) ^ site.wrapping_mul(0x9e37_79b9)) >> 8) / 16_777_216.0;
            let got: f64 = random(&mut Numbers::<f64>::default(), point, site);
            assert_eq!(got, expected, "point {point}, site {site}");
            let single: f32 = random(&mut Numbers::<f32>::default(), point, site);
            assert_eq!(f64::from(single), expected, "exact in f32 too");
            assert!((0.0..1.0).contains(&got));
        }
    }

    #[test]
    fn invert_product_and_transform_on_numbers() {
        let s = &mut Numbers::<f64>::default();
        // A rotation about z by 90 degrees, scaled by 2, translated by (1, 2, 3), row-vector form.
        let m = [0.0, 2.0, 0.0, 0.0, -2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 1.0, 2.0, 3.0, 1.0];
        let inv = invert(s, &m, 4);
        let identity = product(s, &m, &inv, 4);
        for (k, x) in identity.iter().enumerate() {
            let want = if k % 5 == 0 { 1.0 } else { 0.0 };
            assert!((x - want).abs() < 1e-15, "entry {k}: {x}");
        }
        // (1, 0, 0) -> (0, 2, 0) + (1, 2, 3).
        assert_eq!(apply(s, &[1.0, 0.0, 0.0], Rule::Point, &m, &inv), vec![1.0, 4.0, 3.0]);
        assert_eq!(apply(s, &[1.0, 0.0, 0.0], Rule::Vector, &m, &inv), vec![0.0, 2.0, 0.0]);
        // A normal goes by the inverse transpose: rotated, scaled by 1/2.
        assert_eq!(apply(s, &[1.0, 0.0, 0.0], Rule::Normal, &m, &inv), vec![0.0, 0.5, 0.0]);
        assert_eq!(minor(s, &m, 4, &[0, 1, 2, 3], &[0, 1, 2, 3]), 8.0, "det = 2^3");
        assert_eq!(cross(s, &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]);
        assert_eq!(dot(s, &[1.0, 2.0, 3.0], &[4.0, 5.0, 6.0]), 32.0);
        assert_eq!(normalize(s, &[3.0, 0.0, 4.0]), vec![0.6, 0.0, 0.8]);
    }

    #[test]
    fn filterstep_is_the_covered_fraction() {
        let s = &mut Numbers::<f64>::default();
        assert_eq!(filterstep(s, 0.5, 0.0, 1.0), 0.5);
        assert_eq!(filterstep(s, 0.25, 0.0, 1.0), 0.75);
        assert_eq!(filterstep(s, 2.0, 0.0, 1.0), 0.0);
        assert_eq!(filterstep(s, -1.0, 0.0, 1.0), 1.0);
        // An empty interval is a plain step at x0.
        assert_eq!(filterstep(s, 0.5, 0.5, 0.5), 1.0);
        assert_eq!(filterstep(s, 0.6, 0.5, 0.5), 0.0);
    }
}
