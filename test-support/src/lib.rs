//! What the test suites of the compiler, the runtime and the command share, written once: a
//! deterministic generator for sample points ([`Rng`]), Perlin's reference improved noise ported
//! independently of the standard library ([`perlin`]), and the extreme values and error measures
//! of the stability sweep ([`extremes`], [`worst`], [`assert_finite`]).
//!
//! A dev-dependency only: nothing here is part of Patina's API, and it depends on no Patina crate,
//! so every crate's tests can use it without a cycle.

pub mod perlin;

/// splitmix64: deterministic pseudo-random numbers for sample points, the same sequence on every
/// machine, so that a failing point can be found again from its seed.
#[derive(Clone, Debug)]
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1), with 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// A point with each coordinate uniform in [lo, hi).
    pub fn point(&mut self, lo: f64, hi: f64) -> [f64; 3] {
        [self.range(lo, hi), self.range(lo, hi), self.range(lo, hi)]
    }

    /// [`Rng::range`] rounded to f32, for inputs given to the GPU and the f32 interpreter alike.
    pub fn range_f32(&mut self, lo: f64, hi: f64) -> f32 {
        self.range(lo, hi) as f32
    }

    /// [`Rng::point`] rounded to f32.
    pub fn point_f32(&mut self, lo: f64, hi: f64) -> [f32; 3] {
        self.point(lo, hi).map(|x| x as f32)
    }
}

/// The extreme values of the stability sweep (issue 7): zero, tiny and denormal magnitudes, and
/// large ones up to 1e30, with both signs.
pub fn extremes() -> Vec<f64> {
    let denormal = f64::from(f32::from_bits(1)); // the smallest f32 denormal, representable in both
    let mut v = vec![0.0, 1e-30, denormal, 1e4, 1e6, 1e7, 1e30, 0.5, 1.0];
    v.extend(v.clone().into_iter().map(|x| -x));
    v
}

/// The largest absolute difference between two columns, and where.
pub fn worst(a: &[f64], b: &[f64]) -> (f64, usize) {
    a.iter().zip(b).enumerate().fold((0.0, 0), |(w, at), (i, (x, y))| {
        let d = (x - y).abs();
        if d > w { (d, i) } else { (w, at) }
    })
}

/// Asserts every value is finite, naming the output and the point.
///
/// # Panics
/// At the first value that is NaN or infinite.
pub fn assert_finite(name: &str, column: &[f64], components: usize) {
    for (i, x) in column.iter().enumerate() {
        assert!(x.is_finite(), "{name} is {x} at point {} (component {})", i / components, i % components);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_generator_is_splitmix64() {
        // The first output of splitmix64 seeded with 0 (Vigna's reference implementation).
        assert_eq!(Rng(0).next(), 0xe220_a839_7b1d_cdaf);
        let mut rng = Rng(7);
        assert!((0..1000).map(|_| rng.unit()).all(|u| (0.0..1.0).contains(&u)));
    }

    #[test]
    fn worst_finds_the_largest_difference() {
        assert_eq!(worst(&[0.0, 1.0, 2.0], &[0.0, 1.5, 1.9]), (0.5, 1));
    }
}
