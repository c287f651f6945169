//! CPU-vs-GPU conformance: every built-in operation and function runs on the interpreter (the
//! reference) and, as a compute kernel built by the WGSL backend, on the GPU, over the same
//! inputs; the results must agree exactly where WGSL is exact and within a documented tolerance
//! (the table in [`tol`]) where it is not.
//!
//! Each case is a function call with typed arguments. Every mix of argument rates is generated
//! (an argument is either a `uniform` parameter, set once per batch of the interpreter, or a
//! `varying` one, a column per point), because the interpreter computes uniform operands in
//! uniform registers once per batch and varying ones per lane, and both paths must agree with
//! the GPU. Many cases go into one shader so a test compiles one kernel. Predefined varying
//! variables (`s`, `t`, `P`, `N`, `I`, `Cs`) are covered by their own test.
//!
//! The tests need a GPU adapter (lavapipe is enough) and panic without one, unless
//! `PATINA_GPU=off`.

#[path = "conformance/harness.rs"]
mod harness;

use harness::{Input, Spec, Tol};
use patina_compiler::backend::cpu::LightBinding;
use patina_runtime::gpu::{self, Gpu};

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
mod tol {
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

// -------------------------------------------------------------------------------------------------
// Cases.

/// The values an argument takes: each component uniformly in [lo, hi] (rounded to f32), a
/// quarter of them replaced by one of the specials.
#[derive(Clone, Copy, Debug)]
struct Dom {
    lo: f64,
    hi: f64,
    specials: &'static [f64],
    integer: bool,
}

const fn range(lo: f64, hi: f64) -> Dom {
    Dom { lo, hi, specials: &[], integer: false }
}

const fn with(lo: f64, hi: f64, specials: &'static [f64]) -> Dom {
    Dom { lo, hi, specials, integer: false }
}

const fn ints(lo: f64, hi: f64, specials: &'static [f64]) -> Dom {
    Dom { lo, hi, specials, integer: true }
}

/// The floats where exact functions are most often wrong: signed zeros, halves, denormals, the
/// largest values, infinities and NaN. (Compute shaders keep denormals on lavapipe.)
const SPECIALS: &[f64] = &[
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
const FINITE_SPECIALS: &[f64] = &[0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 2.5, -2.5, 1e-40, -1e-40, 3.0e9, -3.0e9];
/// Index-like values: in range, out of range, fractional.
const INDICES: &[f64] = &[-1.0, 0.0, 1.0, 2.0, 3.0, 4.0, 0.5, 1.99, -0.5];
/// 32-bit integer edges.
const INT_SPECIALS: &[f64] = &[0.0, 1.0, -1.0, 2.0, 31.0, 32.0, 33.0, -2_147_483_648.0, 2_147_483_647.0];
const UINT_SPECIALS: &[f64] = &[0.0, 1.0, 2.0, 31.0, 32.0, 33.0, 2_147_483_648.0, 4_294_967_295.0];

/// Angles on which WGSL bounds `sin` and `cos`.
const ANGLE: Dom = range(-std::f64::consts::PI, std::f64::consts::PI);
/// A general float range with the specials.
const ANY: Dom = with(-8.0, 8.0, SPECIALS);
/// A general finite range.
const R4: Dom = range(-4.0, 4.0);
const R2: Dom = range(-2.0, 2.0);
const R1: Dom = range(-1.0, 1.0);
const UNIT: Dom = range(0.0, 1.0);

/// One function call: `body` with `$k` for argument k and `$o` for the output (`$o0`, `$o1`,
/// ... for several).
struct Case {
    body: &'static str,
    args: Vec<(&'static str, Dom)>,
    outs: Vec<(&'static str, Tol)>,
}

fn case(body: &'static str, args: &[(&'static str, Dom)], outs: &[(&'static str, Tol)]) -> Case {
    Case { body, args: args.to_vec(), outs: outs.to_vec() }
}

/// A one-output case.
fn c1(body: &'static str, args: &[(&'static str, Dom)], out: &'static str, tol: Tol) -> Case {
    case(body, args, &[(out, tol)])
}

/// The rate mixes of `n` arguments (bit k set: argument k varying): all of them up to four
/// arguments; beyond, all-uniform, all-varying and each argument alone of the other rate.
fn mixes(n: usize) -> Vec<u32> {
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
fn declare(ty: &str, name: &str) -> String {
    match ty.split_once('[') {
        Some((base, n)) => {
            let n: usize = n.trim_end_matches(']').parse().expect("array size");
            format!("{base} {name}[{n}] = {{{}}}", vec![zero(base); n].join(", "))
        }
        None => format!("{ty} {name} = {}", zero(ty)),
    }
}

fn zero(ty: &str) -> &'static str {
    match ty {
        "uint" => "0u",
        "bool" => "false",
        _ => "0",
    }
}

/// The shader for a group of cases: parameters `c{i}a{k}u` (uniform) and `c{i}a{k}v` (varying)
/// for argument k of case i, outputs `o{i}m{mix}_{j}`.
fn shader(cases: &[Case]) -> (String, Vec<(String, Tol)>) {
    let mut params = Vec::new();
    let mut body = String::new();
    let mut outputs = Vec::new();
    for (i, c) in cases.iter().enumerate() {
        for (k, (ty, _)) in c.args.iter().enumerate() {
            params.push(format!("uniform {}", declare(ty, &format!("c{i}a{k}u"))));
            params.push(format!("varying {}", declare(ty, &format!("c{i}a{k}v"))));
        }
        for m in mixes(c.args.len()) {
            let mut line = c.body.to_string();
            for (j, (ty, tol)) in c.outs.iter().enumerate() {
                let name = format!("o{i}m{m}_{j}");
                params.push(format!("output varying {}", declare(ty, &name)));
                let tol = if matches!(*ty, "int" | "uint" | "bool") { Tol::Int } else { *tol };
                outputs.push((name.clone(), tol));
                line = if c.outs.len() == 1 {
                    line.replace("$o", &name)
                } else {
                    line.replace(&format!("$o{j}"), &name)
                };
            }
            for k in (0..c.args.len()).rev() {
                let rate = if m & (1 << k) != 0 { 'v' } else { 'u' };
                line = line.replace(&format!("${k}"), &format!("c{i}a{k}{rate}"));
            }
            body.push_str("    ");
            body.push_str(&line);
            body.push('\n');
        }
    }
    let src = format!("surface conformance(\n    {}\n) {{\n{body}}}\n", params.join(";\n    "));
    (src, outputs)
}

/// `o12m3_0` -> `c12a`: the parameters of the case an output belongs to.
fn related(output: &str) -> String {
    let digits: String = output.chars().skip(1).take_while(|c| c.is_ascii_digit()).collect();
    if output.starts_with('o') && !digits.is_empty() { format!("c{digits}a") } else { String::new() }
}

/// A deterministic value in [0, 1) for a name and position (splitmix64 of a hash).
fn unit(name: &str, batch: usize, point: usize, component: usize, salt: u64) -> f64 {
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
fn sample(dom: Dom, input: &Input) -> Vec<f64> {
    (0..harness::width(input.ty))
        .map(|c| {
            let r = unit(input.name, input.batch, input.point, c, 1);
            if !dom.specials.is_empty() && r < 0.25 {
                let k =
                    (unit(input.name, input.batch, input.point, c, 2) * dom.specials.len() as f64) as usize;
                return dom.specials[k.min(dom.specials.len() - 1)];
            }
            let x = dom.lo + (dom.hi - dom.lo) * unit(input.name, input.batch, input.point, c, 3);
            if dom.integer { x.round() } else { f64::from(x as f32) }
        })
        .collect()
}

/// The domain of a case parameter `c{i}a{k}{u,v}`.
fn case_domain(cases: &[Case], name: &str) -> Option<Dom> {
    let rest = name.strip_prefix('c')?;
    let (i, rest) = rest.split_once('a')?;
    let k = rest.trim_end_matches(['u', 'v']);
    let case = cases.get(i.parse::<usize>().ok()?)?;
    Some(case.args.get(k.parse::<usize>().ok()?)?.1)
}

/// Values for inputs that are not case parameters: predefined variables, seeds, light values.
fn default_domain(name: &str) -> Dom {
    match name {
        "Cs" | "Os" => UNIT,
        n if n.starts_with("Cl[") => UNIT,
        _ => R2,
    }
}

/// Batches and points per batch: 16 batches of uniform values, 64 points each (1024 GPU
/// invocations per kernel).
const BATCHES: usize = 16;
const POINTS: usize = 64;

/// Runs a group of cases on both backends.
fn run_cases(cases: &[Case], lights: &[LightBinding]) {
    let Some(gpu) = gpu::for_tests() else { return };
    let (src, outputs) = shader(cases);
    let spec = Spec { src, lights: lights.to_vec(), batches: BATCHES, points: POINTS, outputs, related };
    let values = |input: &Input| {
        let dom = match case_domain(cases, input.name) {
            Some(dom) => {
                // The rate mixes are only tested if the interpreter gives the parameters the
                // rates they are declared with: one register per batch, or one per point.
                let declared_uniform = input.name.ends_with('u');
                assert_eq!(input.uniform, declared_uniform, "the interpreter's rate of `{}`", input.name);
                dom
            }
            None => default_domain(input.name),
        };
        sample(dom, input)
    };
    harness::run(&gpu, &spec, &values);
}

/// Runs a hand-written shader whose outputs are named in `outputs`.
fn run_shader(gpu: &Gpu, src: &str, lights: &[LightBinding], outputs: &[(&str, Tol)]) {
    let spec = Spec {
        src: src.to_string(),
        lights: lights.to_vec(),
        batches: 4,
        points: POINTS,
        outputs: outputs.iter().map(|(n, t)| (n.to_string(), *t)).collect(),
        related: |_| String::new(),
    };
    harness::run(gpu, &spec, &|input| sample(default_domain(input.name), input));
}

const F: &str = "float";

// -------------------------------------------------------------------------------------------------
// Tests.

#[test]
fn trigonometry_and_exponentials() {
    let a = ANGLE;
    run_cases(
        &[
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
            c1("$o = exp($0);", &[(F, range(-10.0, 10.0))], F, tol::EXP),
            c1("$o = exp($0);", &[("float3", range(-10.0, 10.0))], "float3", tol::EXP),
            c1("$o = log($0);", &[(F, range(1e-3, 1e3))], F, tol::LOG),
            c1("$o = log($0);", &[("color", range(1e-3, 1e3))], "color", tol::LOG),
            c1("$o = log($0, $1);", &[(F, range(1e-3, 1e3)), (F, range(2.0, 10.0))], F, tol::LOG_BASE),
        ],
        &[],
    );
}

#[test]
fn exact_math() {
    let e = tol::EXACT;
    let mm = tol::MIN_MAX;
    run_cases(
        &[
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
        ],
        &[],
    );
}

#[test]
fn integer_functions_and_operators() {
    let i = ("int", ints(-1000.0, 1000.0, INT_SPECIALS));
    let u = ("uint", ints(0.0, 1000.0, UINT_SPECIALS));
    let small_i = ("int", ints(-100.0, 100.0, &[0.0, 1.0, -1.0]));
    let e = tol::EXACT;
    run_cases(
        &[
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
        ],
        &[],
    );
}

#[test]
fn float_and_vector_operators() {
    let e = tol::EXACT;
    run_cases(
        &[
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
        ],
        &[],
    );
}

#[test]
fn geometric_functions() {
    let e = tol::EXACT;
    let v = ("vector", R4);
    let p = ("point", R4);
    let n = ("normal", R1);
    run_cases(
        &[
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
            case(
                "fresnel($0, $1, $2, $o0, $o1);",
                &[("vector", R1), n, (F, range(0.5, 2.0))],
                &[(F, e), (F, e)],
            ),
            case(
                "fresnel($0, $1, $2, $o0, $o1, $o2, $o3);",
                &[("vector", R1), n, (F, range(0.5, 2.0))],
                &[(F, e), (F, e), ("vector", e), ("vector", e)],
            ),
        ],
        &[],
    );
}

#[test]
fn transformations_and_matrices() {
    let e = tol::EXACT;
    let m = ("matrix", R2);
    run_cases(
        &[
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
            c1(
                "$o = comp($0, $1, $2);",
                &[m, (F, with(0.0, 3.0, INDICES)), (F, with(0.0, 3.0, INDICES))],
                F,
                e,
            ),
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
        ],
        &[],
    );
}

/// RenderMan's `a / M` (`a * inverse(M)`), with the interpreter's inverse and product on both.
#[test]
fn matrix_division() {
    let m = ("matrix", R2);
    run_cases(&[c1("$o = $0 / $1;", &[m, m], "matrix", tol::EXACT)], &[]);
}

#[test]
fn colour_spaces() {
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
    run_cases(&cases, &[]);
}

const SPACE_CALLS: &[&str] = &[
    "$o = ctransform(\"rgb\", $0);",
    "$o = ctransform(\"hsv\", $0);",
    "$o = ctransform(\"hsl\", $0);",
    "$o = ctransform(\"xyz\", $0);",
    "$o = ctransform(\"XYZ\", $0);",
    "$o = ctransform(\"xyY\", $0);",
    "$o = ctransform(\"YIQ\", $0);",
];

const CAST_CALLS: &[&str] = &[
    "$o = color \"rgb\" ($0, $1, $2);",
    "$o = color \"hsv\" ($0, $1, $2);",
    "$o = color \"hsl\" ($0, $1, $2);",
    "$o = color \"xyz\" ($0, $1, $2);",
    "$o = color \"XYZ\" ($0, $1, $2);",
    "$o = color \"xyY\" ($0, $1, $2);",
    "$o = color \"YIQ\" ($0, $1, $2);",
];

/// `ctransform(from, to, c)` for every pair of spaces (the same space is the identity).
const PAIR_CALLS: &[&str] = &[
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

#[test]
fn splines() {
    let e = tol::MIN_MAX;
    let x = (F, with(-0.2, 1.2, &[0.0, 1.0, 0.5, 0.25, 0.75, 1.0 / 3.0]));
    let k = (F, R4);
    let kc = ("color", R4);
    let kp = ("point", R4);
    run_cases(
        &[
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
        ],
        &[],
    );
}

#[test]
fn light_sums() {
    // Two lights that illuminate and one ambient light: `L[k]` and `Cl[k]` are per-point inputs.
    let lights = vec![
        LightBinding { ambient: false, categories: vec![] },
        LightBinding { ambient: true, categories: vec![] },
        LightBinding { ambient: false, categories: vec![] },
    ];
    let n = ("normal", R1);
    let v = ("vector", R1);
    run_cases(
        &[
            c1("$o = ambient();", &[], "color", tol::EXACT),
            c1("$o = diffuse($0);", &[n], "color", tol::MIN_MAX),
            c1("$o = specular($0, $1, $2);", &[n, v, (F, range(0.05, 1.0))], "color", tol::POW_SUM),
            c1("$o = phong($0, $1, $2);", &[n, v, (F, range(1.0, 20.0))], "color", tol::POW_SUM),
            c1(
                "$o = specularbrdf($0, $1, $2, $3);",
                &[v, n, v, (F, range(0.05, 1.0))],
                "color",
                tol::POW_SUM,
            ),
        ],
        &lights,
    );
}

#[test]
fn derivatives() {
    // The derivative built-ins are rewritten into arithmetic on seeds (`dx(s)`, `dy(P)`, ...)
    // before either backend sees them; both run the rewritten program.
    let e = tol::EXACT;
    run_cases(
        &[
            c1("$o = Du($0 * s) + Dv(t * $0);", &[(F, R2)], F, e),
            c1("$o = Deriv($0 * s * s, s);", &[(F, R2)], F, e),
            c1("$o = Du(P * $0);", &[(F, R2)], "vector", e),
            c1("$o = filterwidth(s * $0);", &[(F, R2)], F, e),
            c1("$o = filterstep($0, s * t);", &[(F, R1)], F, tol::MIN_MAX),
            c1("$o = area(P * $0);", &[(F, R2)], F, e),
            c1("$o = calculatenormal(P + $0);", &[("vector", R2)], "normal", e),
        ],
        &[],
    );
}

#[test]
fn stanford_vector_functions_and_select() {
    let e = tol::EXACT;
    let f3 = ("float3", R4);
    let f4 = ("float4", R4);
    let b = (F, R1);
    run_cases(
        &[
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
        ],
        &[],
    );
}

#[test]
fn strings_are_folded() {
    run_cases(
        &[
            c1(
                "$o = match(\"^wo+d$\", concat(\"w\", \"oo\", \"d\")) + 2 * match(\"[0-9]\", \"abc\");",
                &[],
                F,
                tol::EXACT,
            ),
            c1("$o = transform(concat(\"cur\", \"rent\"), $0);", &[("point", R4)], "point", tol::EXACT),
            c1("$o = spline(concat(\"lin\", \"ear\"), $0, 1, 2, 4, 8);", &[(F, UNIT)], F, tol::MIN_MAX),
        ],
        &[],
    );
}

#[test]
fn predefined_varying_inputs() {
    // The varying globals as arguments, alone and mixed with a uniform parameter.
    let Some(gpu) = gpu::for_tests() else { return };
    let src = "
        surface globals(uniform float k = 0.5;
            output varying float a = 0; output varying float b = 0; output varying color c = 0;
            output varying vector d = 0; output varying float e = 0; output varying point f = 0) {
            a = s * t + u - v * k;
            b = length(P) + distance(P, point(k, 0, 1)) + mod(s, k + 1.5);
            c = Cs * mix(s, t, k) + color(clamp(u, 0, k), max(v, s), floor(t * 7));
            d = normalize(N) + faceforward(N, I) + reflect(I, normalize(N)) * k;
            e = smoothstep(0, k, s) + step(t, k) + xcomp(P) * ycomp(I);
            f = P + transform(\"current\", P) * k + spline(s, P, I, P, I);
        }";
    let outputs = [
        ("a", tol::EXACT),
        ("b", tol::EXACT),
        ("c", tol::MIN_MAX),
        ("d", tol::EXACT),
        ("e", tol::MIN_MAX),
        ("f", tol::MIN_MAX),
    ];
    run_shader(&gpu, src, &[], &outputs);
}

#[test]
fn what_neither_backend_runs_is_rejected_by_both() {
    use patina_compiler::backend::cpu::{Binding, CpuProgram};
    use patina_compiler::backend::wgsl::compile_kernel;
    use patina_compiler::syntax::preprocess::MemoryLoader;
    let compile = |body: &str| {
        let src = format!("surface t(output varying float o = 0; output varying color c = 0) {{ {body} }}");
        let checked = patina_compiler::check_source("t.sl", &src, &MemoryLoader::default());
        assert!(!checked.has_errors(), "{body}: {:?}", checked.diagnostics);
        let shader = checked.program.shaders[0].clone();
        let cpu = CpuProgram::compile(&shader, &Binding::default()).map(|_| ());
        let mut diff = shader;
        patina_compiler::opt::prepare(&mut diff);
        let gpu = compile_kernel(&diff, &[], &[], &["s"], &["o"]).map(|_| ());
        (cpu, gpu)
    };
    // Noise: neither backend has it until the standard library writes it in the language.
    for body in ["o = noise(s);", "c = cellnoise(P);", "o = snoise(s, t);", "o = pnoise(s, 4);"] {
        let (cpu, gpu) = compile(body);
        assert!(cpu.is_err() && gpu.is_err(), "{body}: interpreter {cpu:?}, GPU {gpu:?}");
    }
}

#[test]
fn random_hashes_the_point_index_on_both() {
    // `random()` is a hash of the point's index (the kernel's invocation index, the interpreter's
    // point in the evaluation) and the call site, numbered per component in the same order.
    let Some(gpu) = gpu::for_tests() else { return };
    let src = "surface r(output varying float o = 0; output varying color c = 0) {
            o = random();
            c = random() * 0.5 + color random();
        }";
    run_shader(&gpu, src, &[], &[("o", tol::EXACT), ("c", tol::EXACT)]);
}

#[test]
fn stanford_shader_with_lights() {
    // A Stanford-style surface: per-light values summed by `integrate`, vertex and
    // primitive-group parameters, float3/float4 arithmetic, `select` and `clamp01`.
    let Some(gpu) = gpu::for_tests() else { return };
    let src = "
        surface shader float4 stanford(vertex float4 uv, primitive group float k) {
            perlight float3 c = rgb(Cl) * max(dot(L, {0, 0, 1}), 0) * k;
            float3 x = {uv[0], uv[1], k};
            float4 q = {uv[2], k, uv[0], 1};
            float3 y = select(uv[3] > k, cross(x, rgb(q)), normalize(x));
            return {integrate(c) + clamp01(x) + y, dot(q, q) + length(x)};
        }";
    let lights = vec![LightBinding::default(), LightBinding::default()];
    run_shader(&gpu, src, &lights, &[("result", tol::REASSOCIATED)]);
}

/// The real vertex -> fragment path for the built-ins a kernel cannot run: named coordinate
/// systems come from the uniform block (the kernel binds none), here with composites that read
/// them. A plane rendered by both renderers; they interpolate the same vertex values at the same
/// sample positions, so only f32 rounding (and the f32 inverse of each space the runtime uploads)
/// separates the images.
#[test]
fn render_path_named_spaces_and_composites() {
    use patina_runtime::image::{Thresholds, compare};
    use patina_runtime::render::{self, Backend};
    use patina_runtime::scene::Scene;
    let Some(gpu) = gpu::for_tests() else { return };
    let shader = "surface composite(float k = 0.5) {
        point pw = transform(\"world\", P);
        vector vo = vtransform(\"object\", I);
        normal nw = ntransform(\"world\", \"object\", N);
        point ps = transform(\"shader\", \"current\", point \"object\" (s, t, k));
        color hsv = ctransform(\"hsv\", \"rgb\", color(s, 0.5 + 0.5 * t, k));
        color back = ctransform(\"hsl\", color(s, t, k)) + color \"xyY\" (0.3, 0.3, t);
        float kr, kt;
        fresnel(I, N, 1.3, kr, kt);
        point r = rotate(point(s, t, 0), k, point(0, 0, 0), point(0, 0, 1));
        float sp = spline(\"bspline\", s, 0, 1, 0.25, 0.75, 0.5, 1);
        matrix m = rotate(translate(matrix \"world\" 1, vector(1, 2, 3)), k, vector(0, 1, 0));
        point pm = transform(invert(m), pw);
        Ci = color(0.5 + 0.05 * xcomp(pw) + 0.02 * ycomp(vo), 0.5 + 0.05 * zcomp(nw) * kt, sp) * 0.5
            + (hsv + back) * 0.1 + color(xcomp(r), ycomp(r), kr) * 0.1
            + color(xcomp(ps), ycomp(pm), zcomp(ps)) * 0.01;
        Oi = 1;
    }";
    let dir = std::env::temp_dir().join(format!("patina-conformance-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("s.sl"), shader).unwrap();
    let scene = "[output]\nwidth = 32\nheight = 32\n[camera]\nfrom = [0.0, 0.5, -3.0]\nto = [0.0, 0.0, 0.0]\n\
         up = [0.0, 1.0, 0.0]\nfov = 40\n[[object]]\nmesh = \"plane\"\ndetail = 4\nshader = \"s.sl\"\n\
         params = { k = 0.75 }\n\
         transform = [{ rotate = { angle = 30, axis = [0.0, 1.0, 0.0] } }, { translate = [0.2, 0.1, 0.5] }]\n";
    let scene = Scene::parse(scene, dir.join("s.toml"), &dir).unwrap_or_else(|e| panic!("{e}"));
    let prepared = render::prepare(&scene).unwrap_or_else(|e| panic!("{e}"));
    let cpu = render::render(&prepared, Backend::Cpu, None).unwrap_or_else(|e| panic!("{e}"));
    let gpu = render::render(&prepared, Backend::Gpu, Some(&gpu)).unwrap_or_else(|e| panic!("{e}"));
    let t = Thresholds { fail: 1e-4, hard_fail: 1e-3, max_failing_fraction: 0.01 };
    let c = compare(&cpu, &gpu, &t).unwrap();
    assert!(c.passes(&t), "GPU and CPU images differ: {c:?}");
    let covered = cpu.pixels.iter().filter(|p| p[3] > 0.5).count();
    assert!(covered > cpu.pixels.len() / 3, "the plane covers only {covered} pixels");
}
