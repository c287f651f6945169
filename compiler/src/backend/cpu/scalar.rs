//! The per-lane semantics of the CPU interpreter: WGSL's definitions wherever WGSL defines a result
//! exactly, so that the interpreter and the GPU agree bit for bit on them. Floats are generic over
//! [`Real`] (`f32` is the interpreter's normal mode, `f64` its ground-truth mode); integers are
//! `i32`/`u32`. docs/numerics.md lists every choice made here and why. The fixed sequences (`clamp`,
//! `smoothstep`, `sign`, ...) are `backend::arith`'s, run here on numbers (`Numbers`).

use crate::backend::arith::{self, Arith, Words};

/// The float types the interpreter evaluates in.
pub trait Real:
    Copy
    + PartialOrd
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Div<Output = Self>
    + std::ops::Neg<Output = Self>
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 3.
    const THREE: Self;
    /// Rounds toward negative infinity.
    fn floor(self) -> Self;
    /// Rounds toward positive infinity.
    fn ceil(self) -> Self;
    /// Rounds toward zero.
    fn trunc(self) -> Self;
    /// Rounds to the nearest integer, ties to even.
    fn round_even(self) -> Self;
    /// The correctly rounded square root.
    fn sqrt(self) -> Self;
    /// Absolute value (clears the sign bit, also of NaN and -0).
    fn abs(self) -> Self;
    /// Whether this is a NaN.
    fn is_nan(self) -> bool;
    /// The smaller operand; the other one when one is NaN.
    fn min(self, other: Self) -> Self;
    /// The larger operand; the other one when one is NaN.
    fn max(self, other: Self) -> Self;
    /// Sine (radians).
    fn sin(self) -> Self;
    /// Cosine.
    fn cos(self) -> Self;
    /// Tangent.
    fn tan(self) -> Self;
    /// Arcsine.
    fn asin(self) -> Self;
    /// Arccosine.
    fn acos(self) -> Self;
    /// Arctangent.
    fn atan(self) -> Self;
    /// Four-quadrant arctangent of `self / x`.
    fn atan2(self, x: Self) -> Self;
    /// `e^self`.
    fn exp(self) -> Self;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// `self^y`.
    fn powf(self, y: Self) -> Self;
    /// The nearest value to an `i32`.
    fn from_i32(x: i32) -> Self;
    /// The nearest value to a `u32`.
    fn from_u32(x: u32) -> Self;
    /// The value as an f64 (exact for both types).
    fn to_f64(self) -> f64;
    /// The nearest value to an f64.
    fn from_f64(x: f64) -> Self;
}

/// `floor` through an integer conversion, which compiles to a few vector instructions on x86-64
/// without SSE4.1, where `f32::floor` is a library call per lane. Bit-identical to `floor`: values
/// of magnitude 2^mantissa-bits and more (and infinities, NaN) are already integers and are returned
/// as they are, and the sign is copied back so that `floor(-0.0)` is `-0.0`.
macro_rules! floor_by_conversion {
    ($t:ty, $int:ty, $x:expr) => {{
        let x: $t = $x;
        const INTEGRAL: $t = (1u64 << (<$t>::MANTISSA_DIGITS - 1)) as $t;
        if x.abs() < INTEGRAL {
            let t = x as $int as $t;
            let t = if t > x { t - 1.0 } else { t };
            t.copysign(x)
        } else {
            x
        }
    }};
}

macro_rules! real {
    ($t:ty, $int:ty) => {
        impl Real for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const TWO: Self = 2.0;
            const THREE: Self = 3.0;
            fn floor(self) -> Self {
                floor_by_conversion!($t, $int, self)
            }
            fn ceil(self) -> Self {
                <$t>::ceil(self)
            }
            fn trunc(self) -> Self {
                <$t>::trunc(self)
            }
            fn round_even(self) -> Self {
                <$t>::round_ties_even(self)
            }
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            fn is_nan(self) -> bool {
                <$t>::is_nan(self)
            }
            fn min(self, other: Self) -> Self {
                <$t>::min(self, other)
            }
            fn max(self, other: Self) -> Self {
                <$t>::max(self, other)
            }
            fn sin(self) -> Self {
                <$t>::sin(self)
            }
            fn cos(self) -> Self {
                <$t>::cos(self)
            }
            fn tan(self) -> Self {
                <$t>::tan(self)
            }
            fn asin(self) -> Self {
                <$t>::asin(self)
            }
            fn acos(self) -> Self {
                <$t>::acos(self)
            }
            fn atan(self) -> Self {
                <$t>::atan(self)
            }
            fn atan2(self, x: Self) -> Self {
                <$t>::atan2(self, x)
            }
            fn exp(self) -> Self {
                <$t>::exp(self)
            }
            fn ln(self) -> Self {
                <$t>::ln(self)
            }
            fn powf(self, y: Self) -> Self {
                <$t>::powf(self, y)
            }
            fn from_i32(x: i32) -> Self {
                x as $t
            }
            fn from_u32(x: u32) -> Self {
                x as $t
            }
            fn to_f64(self) -> f64 {
                self as f64
            }
            fn from_f64(x: f64) -> Self {
                x as $t
            }
        }
    };
}

real!(f32, i32);
real!(f64, i64);

/// WGSL `fract`: `x - floor(x)` (so `fract(-0.25) = 0.75`, and the result can round to 1).
pub fn fract<R: Real>(x: R) -> R {
    x - x.floor()
}

/// WGSL's float `%`: `a - b * trunc(a / b)`, computed in the float type (not C's exact `fmod`).
pub fn rem<R: Real>(a: R, b: R) -> R {
    a - b * (a / b).trunc()
}

/// RenderMan's `mod`: `a - b * floor(a / b)`, whose result has the sign of `b`.
pub fn modulo<R: Real>(a: R, b: R) -> R {
    Numbers::default().modulo(a, b)
}

/// WGSL `mix`: `a * (1 - t) + b * t`, two roundings and no fused multiply-add.
pub fn mix<R: Real>(a: R, b: R, t: R) -> R {
    a * (R::ONE - t) + b * t
}

/// WGSL `clamp`: `min(max(x, lo), hi)`.
pub fn clamp<R: Real>(x: R, lo: R, hi: R) -> R {
    Numbers::default().clamp(x, lo, hi)
}

/// WGSL `step(edge, x)`: 1 when `x >= edge`, else 0 (RenderMan's `step(min, x)` has the same order).
pub fn step<R: Real>(edge: R, x: R) -> R {
    Numbers::default().step(edge, x)
}

/// WGSL `smoothstep(lo, hi, x)`: `t * t * (3 - 2 * t)` with `t = clamp((x - lo) / (hi - lo), 0, 1)`.
pub fn smoothstep<R: Real>(lo: R, hi: R, x: R) -> R {
    Numbers::default().smoothstep(lo, hi, x)
}

/// WGSL `sign`: -1, 0 or 1 (0 keeps its sign; NaN gives 0).
pub fn sign<R: Real>(x: R) -> R {
    Numbers::default().sign(x)
}

/// WGSL `inverseSqrt`: `1 / sqrt(x)`.
pub fn inverse_sqrt<R: Real>(x: R) -> R {
    Numbers::default().inverse_sqrt(x)
}

/// [`Arith`] on numbers of one float type: the sequences of `backend::arith` run on values, as the
/// interpreter's instructions for them do (the WGSL backend builds the same sequences).
pub(crate) struct Numbers<R>(std::marker::PhantomData<R>);

impl<R> Default for Numbers<R> {
    fn default() -> Self {
        Numbers(std::marker::PhantomData)
    }
}

impl<R: Real> Arith for Numbers<R> {
    type V = R;
    type B = bool;
    #[inline(always)]
    fn constant(&mut self, x: f64) -> R {
        R::from_f64(x)
    }
    #[inline(always)]
    fn add(&mut self, a: R, b: R) -> R {
        a + b
    }
    #[inline(always)]
    fn sub(&mut self, a: R, b: R) -> R {
        a - b
    }
    #[inline(always)]
    fn mul(&mut self, a: R, b: R) -> R {
        a * b
    }
    #[inline(always)]
    fn div(&mut self, a: R, b: R) -> R {
        a / b
    }
    #[inline(always)]
    fn neg(&mut self, a: R) -> R {
        -a
    }
    #[inline(always)]
    fn sqrt(&mut self, a: R) -> R {
        a.sqrt()
    }
    #[inline(always)]
    fn floor(&mut self, a: R) -> R {
        a.floor()
    }
    #[inline(always)]
    fn min(&mut self, a: R, b: R) -> R {
        a.min(b)
    }
    #[inline(always)]
    fn max(&mut self, a: R, b: R) -> R {
        a.max(b)
    }
    #[inline(always)]
    fn less(&mut self, a: R, b: R) -> bool {
        a < b
    }
    #[inline(always)]
    fn greater(&mut self, a: R, b: R) -> bool {
        a > b
    }
    #[inline(always)]
    fn greater_equal(&mut self, a: R, b: R) -> bool {
        a >= b
    }
    #[inline(always)]
    fn is_nan(&mut self, a: R) -> bool {
        a.is_nan()
    }
    #[inline(always)]
    fn select(&mut self, c: bool, a: R, b: R) -> R {
        if c { a } else { b }
    }
}

/// `random()`'s value at point `point` for call site `site` (`backend::arith::random`).
pub fn random<R: Real>(point: u32, site: u32) -> R {
    arith::random(&mut Numbers::<R>::default(), point, site)
}

impl<R: Real> Words for Numbers<R> {
    type W = u32;
    type F = R;
    #[inline(always)]
    fn word(&mut self, x: u32) -> u32 {
        x
    }
    #[inline(always)]
    fn wrapping_mul(&mut self, a: u32, b: u32) -> u32 {
        a.wrapping_mul(b)
    }
    #[inline(always)]
    fn wrapping_add(&mut self, a: u32, b: u32) -> u32 {
        a.wrapping_add(b)
    }
    #[inline(always)]
    fn shift_right(&mut self, a: u32, b: u32) -> u32 {
        a.wrapping_shr(b)
    }
    #[inline(always)]
    fn xor(&mut self, a: u32, b: u32) -> u32 {
        a ^ b
    }
    #[inline(always)]
    fn unit(&mut self, w: u32) -> R {
        R::from_u32(w) / R::from_f64(16_777_216.0)
    }
}

/// The largest f32 below 2^31, the upper end of WGSL's float-to-`i32` clamp.
pub const I32_CLAMP_MAX: f32 = 2_147_483_520.0;
/// The largest f32 below 2^32, the upper end of WGSL's float-to-`u32` clamp.
pub const U32_CLAMP_MAX: f32 = 4_294_967_040.0;

/// WGSL float-to-`i32`: truncate toward zero after clamping to the f32 values that fit,
/// `[-2^31, 2147483520]`; NaN gives 0.
pub fn to_i32<R: Real>(x: R) -> i32 {
    // Rust's `as` truncates, saturates below at -2^31 and maps NaN to 0: only the upper clamp
    // differs from WGSL. (No `trunc` call: this runs once per lane in hashing code.)
    let y = x.to_f64();
    if y > f64::from(I32_CLAMP_MAX) { I32_CLAMP_MAX as i32 } else { y as i32 }
}

/// WGSL float-to-`u32`: truncate toward zero after clamping to `[0, 4294967040]`; NaN gives 0.
pub fn to_u32<R: Real>(x: R) -> u32 {
    let y = x.to_f64();
    if y > f64::from(U32_CLAMP_MAX) { U32_CLAMP_MAX as u32 } else { y as u32 }
}

/// WGSL `i32` division: wrapping; `x / 0 = x`, `MIN / -1 = MIN`.
pub fn div_i32(a: i32, b: i32) -> i32 {
    if b == 0 { a } else { a.wrapping_div(b) }
}

/// WGSL `i32` remainder: `x % 0 = 0`, `MIN % -1 = 0`; otherwise truncating (sign of `a`).
pub fn rem_i32(a: i32, b: i32) -> i32 {
    if b == 0 { 0 } else { a.wrapping_rem(b) }
}

/// WGSL `u32` division: `x / 0 = x`.
pub fn div_u32(a: u32, b: u32) -> u32 {
    a.checked_div(b).unwrap_or(a)
}

/// WGSL `u32` remainder: `x % 0 = 0`.
pub fn rem_u32(a: u32, b: u32) -> u32 {
    a.checked_rem(b).unwrap_or(0)
}

/// WGSL shifts take the shift amount modulo 32.
pub fn shl_i32(a: i32, b: u32) -> i32 {
    a.wrapping_shl(b & 31)
}

/// Arithmetic (sign-filling) right shift, amount modulo 32.
pub fn shr_i32(a: i32, b: u32) -> i32 {
    a.wrapping_shr(b & 31)
}

/// Left shift of a `u32`, amount modulo 32.
pub fn shl_u32(a: u32, b: u32) -> u32 {
    a.wrapping_shl(b & 31)
}

/// Logical right shift of a `u32`, amount modulo 32.
pub fn shr_u32(a: u32, b: u32) -> u32 {
    a.wrapping_shr(b & 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The specials grid.
    const GRID: &[f32] = &[
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        -0.5,
        2.5,
        -2.5,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        1e-40,
        -1e-40,
        f32::MAX,
        -f32::MAX,
        1e10,
        -1e10,
        3e9,
        -3e9,
    ];

    fn same(a: f32, b: f32) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    #[test]
    fn rounding_functions_on_the_grid() {
        // (x, floor, ceil, trunc, round-ties-even, fract), written out by hand.
        let expect: &[(f32, f32, f32, f32, f32, f32)] = &[
            (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            (-0.0, -0.0, -0.0, -0.0, -0.0, 0.0),
            (0.5, 0.0, 1.0, 0.0, 0.0, 0.5),
            (-0.5, -1.0, -0.0, -0.0, -0.0, 0.5),
            (2.5, 2.0, 3.0, 2.0, 2.0, 0.5),
            (-2.5, -3.0, -2.0, -2.0, -2.0, 0.5),
            (1e-40, 0.0, 1.0, 0.0, 0.0, 1e-40),
            (-1e-40, -1.0, -0.0, -0.0, -0.0, 1.0),
            (1e10, 1e10, 1e10, 1e10, 1e10, 0.0),
            (f32::INFINITY, f32::INFINITY, f32::INFINITY, f32::INFINITY, f32::INFINITY, f32::NAN),
        ];
        for &(x, fl, ce, tr, ro, fr) in expect {
            assert!(same(Real::floor(x), fl), "floor({x})");
            assert!(same(Real::ceil(x), ce), "ceil({x})");
            assert!(same(Real::trunc(x), tr), "trunc({x})");
            assert!(same(x.round_even(), ro), "round({x})");
            assert!(same(fract(x), fr), "fract({x}) = {}", fract(x));
        }
        // fract(-1e-40) rounds to exactly 1: x - floor(x) = 1 - 1e-40 in f32.
        assert_eq!(fract(-1e-40f32), 1.0);
        for &x in GRID {
            assert!(!(x.is_finite() && fract(x) < 0.0), "fract({x}) is never negative");
        }
    }

    /// `floor` by conversion must equal the library's on every kind of value: a sweep of bit
    /// patterns (all exponents, both signs, NaN payloads) plus the grid, in both precisions.
    #[test]
    fn floor_by_conversion_is_bit_identical_to_std() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for _ in 0..200_000 {
            let bits = next();
            let x = f32::from_bits(bits as u32);
            assert_eq!(Real::floor(x).to_bits(), x.floor().to_bits(), "floor({x:e})");
            let y = f64::from_bits(bits);
            assert_eq!(Real::floor(y).to_bits(), y.floor().to_bits(), "floor({y:e})");
            // Values near integers, where the correction step matters.
            let z = (bits % 2_000_001) as f32 / 1000.0 - 1000.0;
            assert_eq!(Real::floor(z).to_bits(), z.floor().to_bits(), "floor({z})");
        }
        for &x in GRID {
            assert!(same(Real::floor(x), x.floor()), "floor({x})");
        }
    }

    #[test]
    fn float_remainder_is_wgsls_formula() {
        assert_eq!(rem(7.5f32, 2.0), 1.5);
        assert_eq!(rem(-7.5f32, 2.0), -1.5);
        assert!(rem(1.0f32, f32::INFINITY).is_nan(), "x % inf is NaN under the formula (fmod gives x)");
        assert!(same(rem(-0.0f32, 1.0), 0.0), "-0 % 1 is +0 under the formula");
        assert!(rem(1.0f32, 0.0).is_nan());
        // RenderMan mod follows the divisor's sign.
        assert_eq!(modulo(-7.5f32, 2.0), 0.5);
        assert_eq!(modulo(7.5f32, -2.0), -0.5);
    }

    #[test]
    fn mix_clamp_step_smoothstep() {
        assert_eq!(mix(1.0f32, 3.0, 0.25), 1.5);
        assert_eq!(mix(f32::MAX, f32::MAX, 0.5), f32::MAX);
        // Two roundings, no fusion: 0.1*(1-0.7) + 0.3*0.7 in f32.
        let expected = 0.1f32 * (1.0 - 0.7) + 0.3 * 0.7;
        assert_eq!(mix(0.1f32, 0.3, 0.7).to_bits(), expected.to_bits());
        assert_eq!(clamp(5.0f32, 0.0, 1.0), 1.0);
        assert_eq!(clamp(f32::NAN, 0.0, 1.0), 0.0, "NaN clamps to the low end, as on lavapipe");
        assert_eq!(step(0.5f32, 0.5), 1.0);
        assert_eq!(step(0.5f32, 0.4999), 0.0);
        assert_eq!(smoothstep(0.0f32, 1.0, 0.5), 0.5);
        assert_eq!(smoothstep(0.0f32, 1.0, -3.0), 0.0);
        assert_eq!(smoothstep(0.0f32, 1.0, 1e10), 1.0);
        assert_eq!(smoothstep(0.0f32, 2.0, 0.5), 0.15625);
    }

    #[test]
    fn sign_and_inverse_sqrt() {
        assert_eq!(sign(-2.5f32), -1.0);
        assert_eq!(sign(1e-40f32), 1.0);
        assert!(same(sign(-0.0f32), -0.0));
        assert_eq!(sign(f32::NAN), 0.0);
        assert_eq!(inverse_sqrt(4.0f32), 0.5);
        assert_eq!(inverse_sqrt(0.0f32), f32::INFINITY);
        assert!(inverse_sqrt(-1.0f32).is_nan());
    }

    #[test]
    fn float_to_integer_saturates_like_wgsl() {
        assert_eq!(to_i32(3e9f32), 2_147_483_520);
        assert_eq!(to_i32(f32::INFINITY), 2_147_483_520);
        assert_eq!(to_i32(-3e9f32), i32::MIN);
        assert_eq!(to_i32(f32::NAN), 0);
        assert_eq!(to_i32(-2.5f32), -2);
        assert_eq!(to_i32(2.5f32), 2);
        assert_eq!(to_i32(-1e-40f32), 0);
        assert_eq!(to_u32(1e10f32), 4_294_967_040);
        assert_eq!(to_u32(-1.0f32), 0);
        assert_eq!(to_u32(f32::NAN), 0);
        assert_eq!(to_u32(3e9f32), 3_000_000_000);
        // f64 mode clamps to the same bounds.
        assert_eq!(to_i32(3e9f64), 2_147_483_520);
    }

    #[test]
    fn integer_division_and_shifts() {
        assert_eq!(div_i32(7, 0), 7);
        assert_eq!(div_i32(i32::MIN, -1), i32::MIN);
        assert_eq!(div_i32(-7, 2), -3);
        assert_eq!(rem_i32(7, 0), 0);
        assert_eq!(rem_i32(i32::MIN, -1), 0);
        assert_eq!(rem_i32(-7, 2), -1);
        assert_eq!(div_u32(7, 0), 7);
        assert_eq!(rem_u32(7, 0), 0);
        assert_eq!(shl_i32(1, 33), 2, "shift amounts are taken modulo 32");
        assert_eq!(shr_i32(-8, 1), -4, "arithmetic shift");
        assert_eq!(shr_u32(0x8000_0000, 31), 1);
        assert_eq!(shl_u32(0xffff_ffff, 4), 0xffff_fff0);
        assert_eq!(i32::MAX.wrapping_add(1), i32::MIN, "arithmetic wraps");
    }
}
