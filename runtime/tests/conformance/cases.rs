//! The conformance cases, shared by the compute harness (`conformance.rs`) and the render path
//! (`render.rs`): the tolerance table, the argument domains, and each group of
//! call cases as a function returning its list.
//!
//! Each binary uses a different part of this module.
#![allow(dead_code)]

use super::harness::{self, Input, Tol};
use patina_compiler::backend::binding::LightBinding;

/// The tolerance table: one entry per family of functions, each with the bound it rests on.
///
/// "WGSL" cites the accuracy rules of the WGSL specification (section "Floating Point
/// Accuracy"); "lavapipe" cites the measurements in shared/notes/naga-wgpu-facts.md section 8
/// (262 144 samples per range against a correctly rounded f64 reference). The interpreter
/// computes transcendentals with Rust's f32 `std`, itself within 1-2 ulp of the correctly
/// rounded result, which the bounds below include. Everything not listed here is exact: the
/// interpreter defines each remaining built-in as a fixed sequence of `+ - * /`, `sqrt`, `floor`,
/// `min`/`max`, comparisons and selections, and the WGSL backend writes out the same sequence,
/// which lavapipe evaluates bit for bit (`+ - * /` and `sqrt` are correctly rounded there and no
/// multiply-add is fused). WGSL itself promises less: division and `sqrt` may be 2.5 ulp off, and
/// an implementation may reassociate operations whose exact results are equal (see
/// [`REASSOCIATED`]); another device may need ulp bounds where these say exact.
pub mod tol {
    use super::Tol;

    /// `+ - * /`, `sqrt`, `floor`, `ceil`, `round`, `fract`, `abs`, `sign`, `mix`, `step`,
    /// conversions, comparisons, selections and every built-in made of them: WGSL is exact for
    /// all but division and `sqrt` (2.5 ulp and inherited from `inverseSqrt`), which lavapipe
    /// rounds correctly (measured: 0 ulp).
    pub const EXACT: Tol = Tol::Exact;
    /// `min`, `max`, `clamp` and what is made of them: exact, but WGSL does not say which zero
    /// `min(0, -0)` returns (lavapipe returns the other one than Rust).
    pub const MIN_MAX: Tol = Tol::ZeroSign;
    /// Integer results: exact (WGSL's integer operations are exact and wrap).
    pub const INT: Tol = Tol::Int;
    /// `sin`, `cos` on [-pi, pi]: WGSL allows an absolute error of 2^-11 there (and nothing
    /// outside it); lavapipe measured 6e-8.
    pub const SIN_COS: Tol = Tol::abs(1.0 / 2048.0);
    /// `tan` on [-1.2, 1.2]: WGSL inherits it from `sin(x) / cos(x)`: (1 + |tan x|) 2^-11 / |cos x|
    /// <= 4.8e-3 there; lavapipe measured 3 ulp.
    pub const TAN: Tol = Tol::abs(5e-3);
    /// `asin`, `acos` on [-1, 1]: inherited from `atan2`, 4096 ulp of a result up to pi
    /// (4096 * 2.4e-7 = 9.8e-4); lavapipe measured 3.9e-4 (asin) and 1.6e-4 (acos).
    pub const ASIN_ACOS: Tol = Tol::abs(1e-3);
    /// `atan`, `atan2`: WGSL allows 4096 ulp (plus 2 for the reference); lavapipe measured 346.
    pub const ATAN: Tol = Tol::Ulp(4098);
    /// `exp` on [-10, 10]: WGSL allows 3 + 2|x| ulp (23 there, plus 2 for the reference);
    /// lavapipe measured 10.
    pub const EXP: Tol = Tol::Ulp(25);
    /// `log` on [1e-3, 1e3]: WGSL allows 2^-21 absolute on [0.5, 2] and 3 ulp elsewhere (5 with
    /// the reference's 2); lavapipe measured 1.2e-7 absolute near 1.
    pub const LOG: Tol = Tol::rel(5.0 / 8_388_608.0, 1.0 / 2_097_152.0);
    /// `log(x, base)` = `log(x) / log(base)` with base in [2, 10]: the numerator's bound above
    /// divided by log(2), plus 3 ulp of the denominator relative.
    pub const LOG_BASE: Tol = Tol::rel(2e-6, 4e-6);
    /// `pow(x, y)`, x in [0.5, 4], y in [-4, 4]: inherited from `exp2(y * log2(x))`: log2's
    /// 3 ulp (|log2 x| <= 2) times |y| <= 4 is 2.9e-6 in the exponent, 2e-6 relative after exp2,
    /// plus exp2's 3 + 2 * 8 ulp (2.3e-6): about 4.3e-6 relative; lavapipe measured 9 ulp.
    pub const POW: Tol = Tol::rel(1e-5, 0.0);
    /// The light sums with `pow` in them (`specular`, `phong`, `specularbrdf`), exponents up to
    /// 20: exp2's (3 + 2|z|) ulp and log2's 3 ulp times |z| <= 126 (below that the result
    /// underflows) give at most 6e-5 relative for each term; the terms are non-negative, so the
    /// sum keeps that relative bound.
    pub const POW_SUM: Tol = Tol::rel(1e-4, 1e-7);
    /// Rotation matrices (`rotate`): each entry takes `sin` and `cos` (2^-11 each) about three
    /// times, 3 * 2^-11 per entry; a rotated point sums three entries times components of
    /// |q - p0| <= 2 (points in [-1, 1]^3): 18 * 2^-11.
    pub const ROTATE_POINT: Tol = Tol::abs(18.0 / 2048.0);
    /// `rotate(m, angle, axis)`: a row of m (entries in [-2, 2]) times the rotation's columns:
    /// 3 * 2 * 3 * 2^-11.
    pub const ROTATE_MATRIX: Tol = Tol::abs(18.0 / 2048.0);
    /// Sums of products with a common factor across statements (`integrate` of per-light
    /// values all scaled by one uniform `k`): WGSL lets an implementation reassociate and fuse
    /// operations whose exact results are equal, and lavapipe's compiler turns `a*k + b*k` into
    /// `(a + b)*k` (found by this suite: the bits differ by one rounding). One extra rounding of
    /// a sum of at most 8 in magnitude: 2 ulp of 8 absolute, or 2^-22 relative.
    pub const REASSOCIATED: Tol = Tol::rel(1.0 / 4_194_304.0, 2e-6);
}

/// The values an argument takes: each component uniformly in [lo, hi] (rounded to f32), a
/// quarter of them replaced by one of the specials.
#[derive(Clone, Copy, Debug)]
pub struct Dom {
    pub lo: f64,
    pub hi: f64,
    pub specials: &'static [f64],
    pub integer: bool,
}

pub const fn range(lo: f64, hi: f64) -> Dom {
    Dom { lo, hi, specials: &[], integer: false }
}

pub const fn with(lo: f64, hi: f64, specials: &'static [f64]) -> Dom {
    Dom { lo, hi, specials, integer: false }
}

pub const fn ints(lo: f64, hi: f64, specials: &'static [f64]) -> Dom {
    Dom { lo, hi, specials, integer: true }
}

/// The floats where exact functions are most often wrong: signed zeros, halves, denormals, the
/// largest values, infinities and NaN. (Compute shaders keep denormals on lavapipe.)
pub const SPECIALS: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    -0.5,
    1.5,
    2.5,
    -2.5,
    1e-40,
    -1e-40,
    1.175_494_4e-38,
    3.402_823_5e38,
    -3.402_823_5e38,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
];
/// The same without NaN, for functions whose result on NaN WGSL leaves open and lavapipe
/// computes differently (`!=` is false for NaN on it; `i32(NaN)` is i32::MIN, not 0).
pub const FINITE_SPECIALS: &[f64] =
    &[0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 2.5, -2.5, 1e-40, -1e-40, 3.0e9, -3.0e9];
/// Index-like values: in range, out of range, fractional.
pub const INDICES: &[f64] = &[-1.0, 0.0, 1.0, 2.0, 3.0, 4.0, 0.5, 1.99, -0.5];
/// 32-bit integer edges.
pub const INT_SPECIALS: &[f64] = &[0.0, 1.0, -1.0, 2.0, 31.0, 32.0, 33.0, -2_147_483_648.0, 2_147_483_647.0];
pub const UINT_SPECIALS: &[f64] = &[0.0, 1.0, 2.0, 31.0, 32.0, 33.0, 2_147_483_648.0, 4_294_967_295.0];

/// Angles on which WGSL bounds `sin` and `cos`.
pub const ANGLE: Dom = range(-std::f64::consts::PI, std::f64::consts::PI);
/// A general float range with the specials.
pub const ANY: Dom = with(-8.0, 8.0, SPECIALS);
/// A general finite range.
pub const R4: Dom = range(-4.0, 4.0);
pub const R2: Dom = range(-2.0, 2.0);
pub const R1: Dom = range(-1.0, 1.0);
pub const UNIT: Dom = range(0.0, 1.0);

/// One function call: `body` with `$k` for argument k and `$o` for the output (`$o0`, `$o1`,
/// ... for several).
#[derive(Clone)]
pub struct Case {
    pub body: &'static str,
    pub args: Vec<(&'static str, Dom)>,
    pub outs: Vec<(&'static str, Tol)>,
}

pub fn case(body: &'static str, args: &[(&'static str, Dom)], outs: &[(&'static str, Tol)]) -> Case {
    Case { body, args: args.to_vec(), outs: outs.to_vec() }
}

/// A one-output case.
pub fn c1(body: &'static str, args: &[(&'static str, Dom)], out: &'static str, tol: Tol) -> Case {
    case(body, args, &[(out, tol)])
}

/// The rate mixes of `n` arguments (bit k set: argument k varying): all of them up to four
/// arguments; beyond, all-uniform, all-varying and each argument alone of the other rate.
pub fn mixes(n: usize) -> Vec<u32> {
    if n <= 4 {
        return (0..1u32 << n).collect();
    }
    let all = (1u32 << n) - 1;
    let mut m = vec![0, all];
    for k in 0..n {
        m.push(1 << k);
        m.push(all & !(1 << k));
    }
    m
}

/// A parameter declaration's type and default: `float`, `float k[5]`, `uint ... = 0u`, ...
pub fn declare(ty: &str, name: &str) -> String {
    match ty.split_once('[') {
        Some((base, n)) => {
            let n: usize = n.trim_end_matches(']').parse().expect("array size");
            format!("{base} {name}[{n}] = {{{}}}", vec![zero(base); n].join(", "))
        }
        None => format!("{ty} {name} = {}", zero(ty)),
    }
}

pub fn zero(ty: &str) -> &'static str {
    match ty {
        "uint" => "0u",
        "bool" => "false",
        _ => "0",
    }
}

/// A deterministic value in [0, 1) for a name and position (splitmix64 of a hash).
pub fn unit(name: &str, batch: usize, point: usize, component: usize, salt: u64) -> f64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325 ^ salt;
    for b in name.bytes() {
        h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
    }
    let mut z = h
        ^ (batch as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15)
        ^ (point as u64).wrapping_mul(0xbf58_476d_1ce4_e5b9)
        ^ (component as u64).wrapping_mul(0x94d0_49bb_1331_11eb);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// The values of one input from its domain.
pub fn sample(dom: Dom, input: &Input) -> Vec<f64> {
    sample_n(dom, input.name, input.batch, input.point, harness::width(input.ty))
}

/// The `n` components of the value named `name` at (`batch`, `point`) from a domain.
pub fn sample_n(dom: Dom, name: &str, batch: usize, point: usize, n: usize) -> Vec<f64> {
    (0..n)
        .map(|c| {
            let r = unit(name, batch, point, c, 1);
            if !dom.specials.is_empty() && r < 0.25 {
                let k = (unit(name, batch, point, c, 2) * dom.specials.len() as f64) as usize;
                return dom.specials[k.min(dom.specials.len() - 1)];
            }
            let x = dom.lo + (dom.hi - dom.lo) * unit(name, batch, point, c, 3);
            if dom.integer { x.round() } else { f64::from(x as f32) }
        })
        .collect()
}

pub const F: &str = "float";

pub fn trigonometry_and_exponentials() -> Vec<Case> {
    let a = ANGLE;
    vec![
        c1("$o = sin($0);", &[(F, a)], F, tol::SIN_COS),
        c1("$o = cos($0);", &[(F, a)], F, tol::SIN_COS),
        c1("$o = sin($0);", &[("color", a)], "color", tol::SIN_COS),
        c1("$o = cos($0);", &[("float3", a)], "float3", tol::SIN_COS),
        c1("$o = sin($0);", &[("float4", a)], "float4", tol::SIN_COS),
        c1("$o = tan($0);", &[(F, range(-1.2, 1.2))], F, tol::TAN),
        c1("$o = asin($0);", &[(F, R1)], F, tol::ASIN_ACOS),
        c1("$o = acos($0);", &[(F, R1)], F, tol::ASIN_ACOS),
        c1("$o = atan($0);", &[(F, range(-10.0, 10.0))], F, tol::ATAN),
        c1("$o = atan($0, $1);", &[(F, R4), (F, R4)], F, tol::ATAN),
        c1("$o = pow($0, $1);", &[(F, range(0.5, 4.0)), (F, R4)], F, tol::POW),
        c1("$o = pow($0, $1);", &[("color", range(0.5, 4.0)), ("color", R4)], "color", tol::POW),
        // A negative base with an integral exponent is ±|x|^y, as C's powf has it (issue 24: WGSL
        // leaves it undefined, NaN on Vulkan).
        c1("$o = pow($0, floor($1));", &[(F, range(-4.0, -0.5)), (F, R4)], F, tol::POW),
        c1("$o = pow($0, floor($1));", &[("color", range(-4.0, -0.5)), ("color", R4)], "color", tol::POW),
        c1("$o = exp($0);", &[(F, range(-10.0, 10.0))], F, tol::EXP),
        c1("$o = exp($0);", &[("float3", range(-10.0, 10.0))], "float3", tol::EXP),
        c1("$o = log($0);", &[(F, range(1e-3, 1e3))], F, tol::LOG),
        c1("$o = log($0);", &[("color", range(1e-3, 1e3))], "color", tol::LOG),
        c1("$o = log($0, $1);", &[(F, range(1e-3, 1e3)), (F, range(2.0, 10.0))], F, tol::LOG_BASE),
    ]
}

pub fn exact_math() -> Vec<Case> {
    let e = tol::EXACT;
    let mm = tol::MIN_MAX;
    vec![
        c1("$o = sqrt($0);", &[(F, with(0.0, 100.0, SPECIALS))], F, e),
        c1("$o = sqrt($0);", &[("float4", with(0.0, 100.0, SPECIALS))], "float4", e),
        c1("$o = inversesqrt($0);", &[(F, with(0.0, 100.0, SPECIALS))], F, e),
        c1("$o = radians($0);", &[(F, ANY)], F, e),
        c1("$o = degrees($0);", &[(F, ANY)], F, e),
        c1("$o = mod($0, $1);", &[(F, ANY), (F, with(-4.0, 4.0, SPECIALS))], F, e),
        c1("$o = abs($0);", &[(F, ANY)], F, e),
        c1("$o = abs($0);", &[("vector", ANY)], "vector", e),
        c1("$o = sign($0);", &[(F, ANY)], F, e),
        c1("$o = floor($0);", &[(F, ANY)], F, e),
        c1("$o = ceil($0);", &[("color", ANY)], "color", e),
        c1("$o = round($0);", &[(F, ANY)], F, e),
        c1("$o = min($0, $1);", &[(F, ANY), (F, ANY)], F, mm),
        c1("$o = max($0, $1, $2);", &[(F, ANY), (F, ANY), (F, ANY)], F, mm),
        c1("$o = min($0, $1, $2);", &[("point", ANY), ("point", ANY), ("point", ANY)], "point", mm),
        c1("$o = max($0, $1);", &[("float4", ANY), ("float4", ANY)], "float4", mm),
        c1("$o = clamp($0, $1, $2);", &[(F, ANY), (F, R2), (F, R2)], F, mm),
        c1("$o = clamp($0, $1, $2);", &[("color", ANY), ("color", R2), ("color", R2)], "color", mm),
        c1("$o = clamp($0, $1, $2);", &[("vector", ANY), (F, R2), (F, R2)], "vector", mm),
        c1("$o = clamp01($0);", &[(F, ANY)], F, mm),
        c1("$o = clamp01($0);", &[("float3", ANY)], "float3", mm),
        c1("$o = mix($0, $1, $2);", &[(F, R4), (F, R4), (F, with(-0.5, 1.5, SPECIALS))], F, e),
        c1("$o = mix($0, $1, $2);", &[("color", R4), ("color", R4), (F, range(-0.5, 1.5))], "color", e),
        c1("$o = mix($0, $1, $2);", &[("float4", R4), ("float4", R4), (F, R1)], "float4", e),
        c1("$o = step($0, $1);", &[(F, ANY), (F, ANY)], F, e),
        c1("$o = smoothstep($0, $1, $2);", &[(F, R1), (F, R2), (F, with(-2.0, 2.0, SPECIALS))], F, mm),
        c1("$o = filterstep($0, $1, $2);", &[(F, R1), (F, R2), (F, R2)], F, mm),
    ]
}

pub fn integer_functions_and_operators() -> Vec<Case> {
    let i = ("int", ints(-1000.0, 1000.0, INT_SPECIALS));
    let u = ("uint", ints(0.0, 1000.0, UINT_SPECIALS));
    let small_i = ("int", ints(-100.0, 100.0, &[0.0, 1.0, -1.0]));
    let e = tol::EXACT;
    vec![
        c1("$o = abs($0);", &[i], "int", tol::INT),
        c1("$o = abs($0);", &[u], "uint", tol::INT),
        c1("$o = min($0, $1);", &[i, i], "int", tol::INT),
        c1("$o = max($0, $1, $2);", &[i, i, i], "int", tol::INT),
        c1("$o = min($0, $1, $2);", &[u, u, u], "uint", tol::INT),
        c1("$o = max($0, $1);", &[u, u], "uint", tol::INT),
        c1("$o = clamp($0, $1, $2);", &[i, i, i], "int", tol::INT),
        c1("$o = clamp($0, $1, $2);", &[u, u, u], "uint", tol::INT),
        c1("$o = $0 + $1 * $0 - $1;", &[i, i], "int", tol::INT),
        c1("$o = $0 / $1;", &[i, i], "int", tol::INT),
        c1("$o = $0 % $1;", &[i, i], "int", tol::INT),
        c1("$o = $0 / $1 + $0 % $1;", &[u, u], "uint", tol::INT),
        c1("$o = $0 * $1 - $1;", &[u, u], "uint", tol::INT),
        c1("$o = ($0 & $1) | ($0 ^ ~$1);", &[i, i], "int", tol::INT),
        c1("$o = ($0 << $1) + ($0 >> $1);", &[i, i], "int", tol::INT),
        c1("$o = ($0 << $1) ^ ($0 >> $1);", &[u, u], "uint", tol::INT),
        c1("$o = -$0;", &[i], "int", tol::INT),
        c1("$o = ($0 < $1) ? $0 : $1;", &[i, i], "int", tol::INT),
        c1("$o = $0 <= $1;", &[u, u], "bool", tol::INT),
        c1("$o = $0 == $1 || $0 > $1 && !($1 != $0);", &[i, i], "bool", tol::INT),
        c1("$o = uint($0) + uint($1 >= $0);", &[i, i], "uint", tol::INT),
        c1("$o = int($0);", &[u], "int", tol::INT),
        c1("$o = int($0);", &[(F, with(-5e9, 5e9, FINITE_SPECIALS))], "int", tol::INT),
        c1("$o = uint($0);", &[(F, with(-5e9, 5e9, FINITE_SPECIALS))], "uint", tol::INT),
        // Integers (kept below 2^24 so the interpreter's f32 run holds them) to floats.
        c1("$o = float($0) + float($0 * 4096);", &[small_i], F, e),
        c1("$o = float($0);", &[("uint", ints(0.0, 16_000_000.0, &[0.0, 1.0]))], F, e),
    ]
}

pub fn float_and_vector_operators() -> Vec<Case> {
    let e = tol::EXACT;
    vec![
        c1("$o = $0 + $1;", &[(F, ANY), (F, ANY)], F, e),
        c1("$o = $0 - $1;", &[(F, ANY), (F, ANY)], F, e),
        c1("$o = $0 * $1;", &[(F, ANY), (F, ANY)], F, e),
        c1("$o = $0 / $1;", &[(F, ANY), (F, ANY)], F, e),
        c1("$o = -$0;", &[(F, ANY)], F, e),
        c1(
            "$o = ($0 < $1 ? 1 : 0) + ($0 <= $1 ? 2 : 0) + ($0 > $1 ? 4 : 0) + ($0 >= $1 ? 8 : 0) + ($0 == $1 ? 16 : 0);",
            &[(F, ANY), (F, ANY)],
            F,
            e,
        ),
        // `!=` without NaN: lavapipe's `!=` is ordered (false for NaN), WGSL leaves it open.
        c1(
            "$o = ($0 != $1) ? 1 : 0;",
            &[(F, with(-2.0, 2.0, FINITE_SPECIALS)), (F, with(-2.0, 2.0, FINITE_SPECIALS))],
            F,
            e,
        ),
        c1("$o = ($0 < 0 && $1 > 0 || !($0 < $1)) ? $0 : $1;", &[(F, R2), (F, R2)], F, e),
        c1("$o = $0 + $1 * $2;", &[("color", ANY), ("color", ANY), (F, ANY)], "color", e),
        c1("$o = $0 - $1;", &[("point", ANY), ("point", ANY)], "vector", e),
        c1("$o = $0 / $1 - $1 * $0;", &[("vector", R4), (F, R4)], "vector", e),
        c1("$o = $0 . $1;", &[("vector", R4), ("vector", R4)], F, e),
        c1("$o = $0 ^ $1;", &[("vector", R4), ("vector", R4)], "vector", e),
        c1(
            "$o = ($0 == $1) ? 1 : (($0 != $1) ? 2 : 3);",
            &[("color", ints(0.0, 1.0, &[])), ("color", ints(0.0, 1.0, &[]))],
            F,
            e,
        ),
        c1("$o = $0 * $1 + $2;", &[("float4", ANY), ("float4", ANY), ("float4", ANY)], "float4", e),
        c1("$o = ($0 > 0) ? $1 : $2;", &[(F, R1), ("color", R4), ("color", R4)], "color", e),
        c1("$o = $0 * $1;", &[("matrix", R2), ("matrix", R2)], "matrix", tol::EXACT),
        c1("$o = $0 + $1 - $2;", &[("matrix", R2), (F, R2), ("matrix", R2)], "matrix", e),
        c1("$o = $0 * $1;", &[("matrix3", R2), ("float3", R2)], "float3", e),
        c1("$o = $0 * $1;", &[("matrix", R2), ("float4", R2)], "float4", e),
        c1(
            "{ float a[4] = {$1, $2, 7, 9}; $o = a[int($0)]; }",
            &[(F, with(-2.0, 6.0, INDICES)), (F, R4), (F, R4)],
            F,
            e,
        ),
    ]
}

pub fn geometric_functions() -> Vec<Case> {
    let e = tol::EXACT;
    let v = ("vector", R4);
    let p = ("point", R4);
    let n = ("normal", R1);
    vec![
        c1("$o = xcomp($0) + 2 * ycomp($0) + 4 * zcomp($0);", &[p], F, e),
        c1("$o = $0; setxcomp($o, $1);", &[p, (F, ANY)], "point", e),
        c1("$o = $0; setycomp($o, $1);", &[v, (F, ANY)], "vector", e),
        c1("$o = $0; setzcomp($o, $1);", &[n, (F, ANY)], "normal", e),
        c1("$o = length($0);", &[v], F, e),
        c1("$o = length($0);", &[("vector", ANY)], F, e),
        c1("$o = normalize($0);", &[v], "vector", e),
        c1("$o = normalize($0);", &[p], "vector", e),
        c1("$o = distance($0, $1);", &[p, p], F, e),
        c1("$o = ptlined($0, $1, $2);", &[p, p, p], F, tol::MIN_MAX),
        c1(
            "$o = rotate($0, $1, $2, $3);",
            &[("point", R1), (F, ANGLE), ("point", R1), ("point", R1)],
            "point",
            tol::ROTATE_POINT,
        ),
        c1("$o = faceforward($0, $1);", &[n, v], "normal", e),
        c1("$o = faceforward($0, $1, $2);", &[v, v, v], "vector", e),
        c1("$o = reflect($0, $1);", &[v, n], "vector", e),
        c1("$o = refract($0, $1, $2);", &[("vector", R1), n, (F, range(0.5, 2.0))], "vector", e),
        case("fresnel($0, $1, $2, $o0, $o1);", &[("vector", R1), n, (F, range(0.5, 2.0))], &[(F, e), (F, e)]),
        case(
            "fresnel($0, $1, $2, $o0, $o1, $o2, $o3);",
            &[("vector", R1), n, (F, range(0.5, 2.0))],
            &[(F, e), (F, e), ("vector", e), ("vector", e)],
        ),
    ]
}

pub fn transformations_and_matrices() -> Vec<Case> {
    let e = tol::EXACT;
    let m = ("matrix", R2);
    vec![
        c1("$o = transform(\"current\", $0);", &[("point", R4)], "point", e),
        c1("$o = transform(\"camera\", \"current\", $0);", &[("vector", R4)], "vector", e),
        c1("$o = transform($0, $1);", &[m, ("point", R4)], "point", e),
        c1("$o = transform($0, $1);", &[m, ("vector", R4)], "vector", e),
        c1("$o = transform($0, $1);", &[m, ("normal", R4)], "normal", e),
        c1("$o = transform(\"current\", $0, $1);", &[m, ("point", R4)], "point", e),
        c1("$o = vtransform(\"camera\", $0);", &[("vector", R4)], "vector", e),
        c1("$o = vtransform($0, $1);", &[m, ("vector", R4)], "vector", e),
        c1("$o = ntransform(\"current\", \"camera\", $0);", &[("normal", R4)], "normal", e),
        c1("$o = ntransform($0, $1);", &[m, ("normal", R4)], "normal", e),
        c1("$o = ntransform(\"camera\", $0, $1);", &[m, ("normal", R4)], "normal", e),
        c1("$o = point \"current\" ($0, $1, $2);", &[(F, R4), (F, R4), (F, R4)], "point", e),
        c1("$o = vector \"camera\" $0;", &[("vector", R4)], "vector", e),
        c1("$o = normal \"current\" $0;", &[("normal", R4)], "normal", e),
        c1("$o = matrix \"current\" $0;", &[m], "matrix", e),
        c1("$o = comp($0, $1, $2);", &[m, (F, with(0.0, 3.0, INDICES)), (F, with(0.0, 3.0, INDICES))], F, e),
        c1(
            "$o = $0; setcomp($o, $1, $2, $3);",
            &[m, (F, with(0.0, 3.0, INDICES)), (F, with(0.0, 3.0, INDICES)), (F, ANY)],
            "matrix",
            e,
        ),
        c1("$o = determinant($0);", &[m], F, e),
        c1("$o = invert($0);", &[m], "matrix", e),
        c1("$o = invert($0);", &[("matrix3", R2)], "matrix3", e),
        c1("$o = affine($0);", &[m], "matrix3", e),
        c1("$o = transpose($0);", &[m], "matrix", e),
        c1("$o = transpose($0);", &[("matrix3", R2)], "matrix3", e),
        c1("$o = translate($0, $1);", &[m, ("vector", R4)], "matrix", e),
        c1("$o = scale($0, $1);", &[m, ("point", R4)], "matrix", e),
        c1("$o = rotate($0, $1, $2);", &[m, (F, ANGLE), ("vector", R1)], "matrix", tol::ROTATE_MATRIX),
    ]
}

/// RenderMan's `a / M` (`a * inverse(M)`), with the interpreter's inverse and product on both.
pub fn matrix_division() -> Vec<Case> {
    let m = ("matrix", R2);
    vec![c1("$o = $0 / $1;", &[m, m], "matrix", tol::EXACT)]
}

pub fn colour_spaces() -> Vec<Case> {
    let e = tol::MIN_MAX;
    let c = ("color", with(0.0, 1.0, &[0.0, 1.0, 0.5, 0.25]));
    let mut cases = vec![
        c1("$o = comp($0, $1);", &[c, (F, with(0.0, 2.0, INDICES))], F, e),
        c1("$o = $0; setcomp($o, $1, $2);", &[c, (F, with(0.0, 2.0, INDICES)), (F, ANY)], "color", e),
    ];
    // Every colour space from and to RGB (`ctransform(to, c)`, the cast `color "space" c`).
    for to in SPACE_CALLS {
        cases.push(c1(to, &[c], "color", e));
    }
    for from in CAST_CALLS {
        cases.push(c1(from, &[(F, with(-0.25, 1.25, &[0.0, 1.0, 0.5])), (F, UNIT), (F, UNIT)], "color", e));
    }
    // Every pair.
    for pair in PAIR_CALLS {
        cases.push(c1(pair, &[c], "color", e));
    }
    cases
}

/// The noise built-ins (`noise`, `snoise`, `pnoise`, `cellnoise`), written in the language
/// (compiler/stdlib/builtins.sl over noise.sl and cellular.sl): floor, integer hashing and
/// polynomials, so the two backends agree bit for bit. Every overload, with float results and
/// with colour results (three float evaluations at offset domains or seeds); coordinates across
/// many cells, both signs, on lattice points and far out; periods including the guarded ones
/// (below 1, fractional, beyond 256). In groups small enough for a GPU driver to compile quickly
/// (each call inlines a whole noise).
pub fn noise(group: NoiseGroup) -> Vec<Case> {
    let e = tol::EXACT;
    const COORDINATES: &[f64] = &[0.0, -0.0, 0.5, -0.5, 1.0, 255.5, -256.25, 1e4 + 0.25, -1e6, 3.0e9];
    const PERIODS: &[f64] = &[1.0, 0.0, -3.0, 0.5, 2.5, 7.0, 256.0, 300.0];
    let x = (F, with(-300.0, 300.0, COORDINATES));
    let p = ("point", with(-300.0, 300.0, COORDINATES));
    let q = (F, with(1.0, 9.0, PERIODS));
    let qp = ("point", with(1.0, 9.0, PERIODS));
    let domains = |call: [&'static str; 4], out: &'static str| {
        vec![
            c1(call[0], &[x], out, e),
            c1(call[1], &[x, x], out, e),
            c1(call[2], &[p], out, e),
            c1(call[3], &[p, x], out, e),
        ]
    };
    const NOISE: [&str; 4] =
        ["$o = noise($0);", "$o = noise($0, $1);", "$o = noise($0);", "$o = noise($0, $1);"];
    const SNOISE: [&str; 4] =
        ["$o = snoise($0);", "$o = snoise($0, $1);", "$o = snoise($0);", "$o = snoise($0, $1);"];
    const CELLNOISE: [&str; 4] =
        ["$o = cellnoise($0);", "$o = cellnoise($0, $1);", "$o = cellnoise($0);", "$o = cellnoise($0, $1);"];
    match group {
        NoiseGroup::Float => [domains(NOISE, F), domains(SNOISE, F)].concat(),
        NoiseGroup::Colour => domains(NOISE, "color"),
        NoiseGroup::Cell => [domains(CELLNOISE, F), domains(CELLNOISE, "color")].concat(),
        NoiseGroup::Periodic => vec![
            c1("$o = pnoise($0, $1);", &[x, q], F, e),
            c1("$o = pnoise($0, $1, $2, $3);", &[x, x, q, q], F, e),
            c1("$o = pnoise($0, $1);", &[p, qp], F, e),
            c1("$o = pnoise($0, $1, $2, $3);", &[p, x, qp, q], F, e),
            c1("$o = pnoise($0, $1);", &[x, q], "color", e),
            c1("$o = pnoise($0, $1);", &[p, qp], "color", e),
        ],
    }
}

/// The groups of [`noise`].
#[derive(Clone, Copy, Debug)]
pub enum NoiseGroup {
    /// `noise` and `snoise` over each domain, float results.
    Float,
    /// `noise` over each domain, colour results (`snoise`'s are the same code, scaled).
    Colour,
    /// `cellnoise`, float and colour.
    Cell,
    /// `pnoise` over each domain (float), and colour results over two.
    Periodic,
}

pub fn splines() -> Vec<Case> {
    let e = tol::MIN_MAX;
    let x = (F, with(-0.2, 1.2, &[0.0, 1.0, 0.5, 0.25, 0.75, 1.0 / 3.0]));
    let k = (F, R4);
    let kc = ("color", R4);
    let kp = ("point", R4);
    vec![
        c1("$o = spline($0, $1, $2, $3, $4);", &[x, k, k, k, k], F, e),
        c1("$o = spline($0, $1, $2, $3, $4, $1, $2);", &[x, k, k, k, k], F, e),
        c1("$o = spline(\"catmull-rom\", $0, $1, $2, $3, $4, $2);", &[x, kc, kc, kc, kc], "color", e),
        c1("$o = spline(\"bezier\", $0, $1, $2, $3, $4, $1, $3, $2);", &[x, kp, kp, kp, kp], "point", e),
        c1(
            "$o = spline(\"bspline\", $0, $1, $2, $3, $4, $3);",
            &[x, ("vector", R4), ("vector", R4), ("vector", R4), ("vector", R4)],
            "vector",
            e,
        ),
        c1("$o = spline(\"hermite\", $0, $1, $2, $3, $4, $1, $2);", &[x, k, k, k, k], F, e),
        c1("$o = spline(\"linear\", $0, $1, $2, $3, $4, $1);", &[x, k, k, k, k], F, e),
        c1("$o = spline($0, $1);", &[x, ("float[6]", R4)], F, e),
        c1("$o = spline(\"bezier\", $0, $1);", &[x, ("color[7]", R4)], "color", e),
        c1("$o = spline(\"linear\", $0, $1);", &[x, ("point[5]", R4)], "point", e),
    ]
}

/// Reads of arrays at run-time indices, in range and out of it (clamped to the ends): a short
/// array's read is a chain of selects in the WGSL, a longer one's a read through a pointer.
pub fn array_reads() -> Vec<Case> {
    let e = tol::EXACT;
    let i = ("int", ints(-3.0, 8.0, &[]));
    vec![
        c1("$o = $1[$0];", &[i, ("float[2]", R4)], F, e),
        c1("$o = $1[$0] + $1[$0 + 1];", &[i, ("float[4]", R4)], F, e),
        c1("$o = $1[$0];", &[i, ("color[3]", R4)], "color", e),
        c1("$o = $1[$0];", &[i, ("float[5]", R4)], F, e),
    ]
}

pub fn light_sums() -> Vec<Case> {
    let n = ("normal", R1);
    let v = ("vector", R1);
    vec![
        c1("$o = ambient();", &[], "color", tol::EXACT),
        c1("$o = diffuse($0);", &[n], "color", tol::MIN_MAX),
        c1("$o = specular($0, $1, $2);", &[n, v, (F, range(0.05, 1.0))], "color", tol::POW_SUM),
        c1("$o = phong($0, $1, $2);", &[n, v, (F, range(1.0, 20.0))], "color", tol::POW_SUM),
        c1("$o = specularbrdf($0, $1, $2, $3);", &[v, n, v, (F, range(0.05, 1.0))], "color", tol::POW_SUM),
    ]
}

/// The lights of [`light_sums`]: two that illuminate and one ambient light (in the compute
/// harness their `L[k]` and `Cl[k]` are per-point inputs).
pub fn light_sum_lights() -> Vec<LightBinding> {
    vec![
        LightBinding { ambient: false, ..LightBinding::default() },
        LightBinding { ambient: true, ..LightBinding::default() },
        LightBinding { ambient: false, ..LightBinding::default() },
    ]
}

pub fn derivatives() -> Vec<Case> {
    // The derivative built-ins are rewritten into arithmetic on seeds (`dx(s)`, `dy(P)`, ...)
    // before either backend sees them; both run the rewritten program.
    let e = tol::EXACT;
    vec![
        c1("$o = Du($0 * s) + Dv(t * $0);", &[(F, R2)], F, e),
        c1("$o = Deriv($0 * s * s, s);", &[(F, R2)], F, e),
        c1("$o = Du(P * $0);", &[(F, R2)], "vector", e),
        c1("$o = filterwidth(s * $0);", &[(F, R2)], F, e),
        c1("$o = filterstep($0, s * t);", &[(F, R1)], F, tol::MIN_MAX),
        c1("$o = area(P * $0);", &[(F, R2)], F, e),
        c1("$o = calculatenormal(P + $0);", &[("vector", R2)], "normal", e),
    ]
}

pub fn stanford_vector_functions_and_select() -> Vec<Case> {
    let e = tol::EXACT;
    let f3 = ("float3", R4);
    let f4 = ("float4", R4);
    let b = (F, R1);
    vec![
        c1("$o = dot($0, $1);", &[f3, f3], F, e),
        c1("$o = dot($0, $1);", &[f4, f4], F, e),
        c1("$o = cross($0, $1);", &[f3, f3], "float3", e),
        c1("$o = normalize($0);", &[f3], "float3", e),
        c1("$o = length($0);", &[f3], F, e),
        c1("$o = rgb($0);", &[f4], "float3", e),
        c1("$o = clamp01($0);", &[("float4", ANY)], "float4", tol::MIN_MAX),
        c1("$o = select($0 < $1, $2, $3);", &[b, b, (F, ANY), (F, ANY)], F, e),
        c1("$o = select($0 < $1, $2, $3);", &[b, b, f4, f4], "float4", e),
        c1("$o = select($0 < $1, $2, $3);", &[b, b, ("color", R4), ("color", R4)], "color", e),
        c1(
            "$o = select($0 < $1, $2, $3);",
            &[b, b, ("int", ints(-9.0, 9.0, &[])), ("int", ints(-9.0, 9.0, &[]))],
            "int",
            tol::INT,
        ),
        c1("$o = select($0 < $1, $2, $3);", &[b, b, ("matrix", R4), ("matrix", R4)], "matrix", e),
        c1(
            "$o = select($0 < $1, $2, $3);",
            &[b, b, ("uint", ints(0.0, 4e9, UINT_SPECIALS)), ("uint", ints(0.0, 4e9, UINT_SPECIALS))],
            "uint",
            tol::INT,
        ),
        c1("$o = select($0 < $1, $2, $3);", &[b, b, ("matrix3", R4), ("matrix3", R4)], "matrix3", e),
    ]
}

pub fn strings_are_folded() -> Vec<Case> {
    vec![
        c1(
            "$o = match(\"^wo+d$\", concat(\"w\", \"oo\", \"d\")) + 2 * match(\"[0-9]\", \"abc\");",
            &[],
            F,
            tol::EXACT,
        ),
        c1("$o = transform(concat(\"cur\", \"rent\"), $0);", &[("point", R4)], "point", tol::EXACT),
        c1("$o = spline(concat(\"lin\", \"ear\"), $0, 1, 2, 4, 8);", &[(F, UNIT)], F, tol::MIN_MAX),
    ]
}

pub const SPACE_CALLS: &[&str] = &[
    "$o = ctransform(\"rgb\", $0);",
    "$o = ctransform(\"hsv\", $0);",
    "$o = ctransform(\"hsl\", $0);",
    "$o = ctransform(\"xyz\", $0);",
    "$o = ctransform(\"XYZ\", $0);",
    "$o = ctransform(\"xyY\", $0);",
    "$o = ctransform(\"YIQ\", $0);",
];

pub const CAST_CALLS: &[&str] = &[
    "$o = color \"rgb\" ($0, $1, $2);",
    "$o = color \"hsv\" ($0, $1, $2);",
    "$o = color \"hsl\" ($0, $1, $2);",
    "$o = color \"xyz\" ($0, $1, $2);",
    "$o = color \"XYZ\" ($0, $1, $2);",
    "$o = color \"xyY\" ($0, $1, $2);",
    "$o = color \"YIQ\" ($0, $1, $2);",
];

/// `ctransform(from, to, c)` for every pair of spaces (the same space is the identity).
pub const PAIR_CALLS: &[&str] = &[
    "$o = ctransform(\"hsv\", \"hsl\", $0);",
    "$o = ctransform(\"hsl\", \"hsv\", $0);",
    "$o = ctransform(\"hsv\", \"xyz\", $0);",
    "$o = ctransform(\"xyz\", \"hsv\", $0);",
    "$o = ctransform(\"hsl\", \"xyY\", $0);",
    "$o = ctransform(\"xyY\", \"hsl\", $0);",
    "$o = ctransform(\"YIQ\", \"hsv\", $0);",
    "$o = ctransform(\"hsv\", \"YIQ\", $0);",
    "$o = ctransform(\"xyz\", \"xyY\", $0);",
    "$o = ctransform(\"xyY\", \"YIQ\", $0);",
    "$o = ctransform(\"YIQ\", \"XYZ\", $0);",
    "$o = ctransform(\"XYZ\", \"xyz\", $0);",
    "$o = ctransform(\"hsl\", \"hsl\", $0);",
    "$o = ctransform(\"rgb\", \"hsv\", $0);",
    "$o = ctransform(\"xyY\", \"rgb\", $0);",
];
