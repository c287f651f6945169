//! Every operation of the language through the whole interpreter (source, lowering, batch
//! machine), on the specials grid for the exactly-defined ones. Expected values are computed here
//! from WGSL's definitions with Rust's own f32 and integer arithmetic, bit for bit; the
//! transcendental functions are compared with f64 results within a stated tolerance.

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_compiler::syntax::preprocess::MemoryLoader;

/// The issue's specials grid.
const GRID: [f32; 19] = [
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

/// A surface shader computing `r` from varying `a`, `b`, `c` (and `int`s `i`, `j`).
fn program(expr: &str, ty: &str) -> CpuProgram {
    let zero = if ty == "uint" { "0u" } else { "0" };
    let source = format!(
        "surface t(varying float a = 0; varying float b = 0; varying float c = 0;
                   varying int i = 0; varying int j = 0; varying uint m = 0u; varying uint n = 0u;
                   output varying {ty} r = {zero}) {{ r = {expr}; }}"
    );
    crate::support::compile(&source, &Binding::default())
}

/// `r` at every combination of grid values for `a`, `b`, `c` (as many as `arity`), in f32.
fn float_op(expr: &str, arity: usize) -> Vec<(Vec<f32>, f32)> {
    let program = program(expr, "float");
    let mut eval = Evaluator::<f32>::new(&program);
    let mut columns: Vec<Vec<f64>> = vec![Vec::new(); arity];
    let total = GRID.len().pow(arity as u32);
    for k in 0..total {
        let mut rest = k;
        for column in columns.iter_mut() {
            column.push(f64::from(GRID[rest % GRID.len()]));
            rest /= GRID.len();
        }
    }
    let names = ["a", "b", "c"];
    let inputs: Vec<(&str, &[f64])> = columns.iter().enumerate().map(|(i, c)| (names[i], &c[..])).collect();
    let out = eval.eval_points(total, &inputs, &["r"]).unwrap();
    (0..total).map(|k| (columns.iter().map(|c| c[k] as f32).collect(), out[0][k] as f32)).collect()
}

/// Bit equality, with every NaN equal to every NaN.
fn same(x: f32, y: f32) -> bool {
    (x.is_nan() && y.is_nan()) || x.to_bits() == y.to_bits()
}

fn check_exact(expr: &str, arity: usize, expected: impl Fn(&[f32]) -> f32) {
    for (args, got) in float_op(expr, arity) {
        let want = expected(&args);
        assert!(same(got, want), "{expr} at {args:?}: got {got:e}, WGSL gives {want:e}");
    }
}

#[test]
fn arithmetic_is_ieee_f32_on_the_grid() {
    check_exact("a + b", 2, |x| x[0] + x[1]);
    check_exact("a - b", 2, |x| x[0] - x[1]);
    check_exact("a * b", 2, |x| x[0] * x[1]);
    check_exact("a / b", 2, |x| x[0] / x[1]);
    check_exact("-a", 1, |x| -x[0]);
    // No fused multiply-add: two roundings.
    check_exact("a * b + c", 3, |x| x[0] * x[1] + x[2]);
}

#[test]
fn rounding_and_shaping_on_the_grid() {
    check_exact("floor(a)", 1, |x| x[0].floor());
    check_exact("ceil(a)", 1, |x| x[0].ceil());
    check_exact("round(a)", 1, |x| x[0].round_ties_even());
    check_exact("abs(a)", 1, |x| x[0].abs());
    check_exact("sign(a)", 1, |x| {
        if x[0] > 0.0 {
            1.0
        } else if x[0] < 0.0 {
            -1.0
        } else if x[0].is_nan() {
            0.0
        } else {
            x[0]
        }
    });
    check_exact("sqrt(a)", 1, |x| x[0].sqrt());
    check_exact("inversesqrt(a)", 1, |x| 1.0 / x[0].sqrt());
    check_exact("mod(a, b)", 2, |x| x[0] - x[1] * (x[0] / x[1]).floor());
    check_exact("step(a, b)", 2, |x| if x[1] >= x[0] { 1.0 } else { 0.0 });
    check_exact("mix(a, b, c)", 3, |x| x[0] * (1.0 - x[2]) + x[1] * x[2]);
    check_exact("clamp(a, b, c)", 3, |x| x[0].max(x[1]).min(x[2]));
    check_exact("smoothstep(a, b, c)", 3, |x| {
        // max-then-min, not `clamp`: WGSL's clamp sends NaN to the low bound, Rust's keeps it.
        #[allow(clippy::manual_clamp)]
        let t = ((x[2] - x[0]) / (x[1] - x[0])).max(0.0).min(1.0);
        t * t * (3.0 - 2.0 * t)
    });
}

#[test]
fn min_and_max_on_the_grid() {
    // WGSL allows either zero for min(0, -0); compare those as equal.
    for (expr, f) in [("min(a, b)", f32::min as fn(f32, f32) -> f32), ("max(a, b)", f32::max)] {
        for (args, got) in float_op(expr, 2) {
            let want = f(args[0], args[1]);
            let both_zero = got == 0.0 && want == 0.0;
            assert!(both_zero || same(got, want), "{expr} at {args:?}: {got} vs {want}");
        }
    }
}

#[test]
fn comparisons_and_selection_on_the_grid() {
    check_exact("a < b ? 1 : 0", 2, |x| f32::from(u8::from(x[0] < x[1])));
    check_exact("a <= b ? 1 : 0", 2, |x| f32::from(u8::from(x[0] <= x[1])));
    check_exact("a == b ? 1 : 0", 2, |x| f32::from(u8::from(x[0] == x[1])));
    check_exact("a != b ? 1 : 0", 2, |x| f32::from(u8::from(x[0] != x[1])));
    check_exact("a > b ? a : b", 2, |x| if x[0] > x[1] { x[0] } else { x[1] });
}

#[test]
fn float_to_integer_conversions_saturate() {
    let expected_int = |x: f32| -> f32 {
        let i: i32 = if x.is_nan() {
            0
        } else if x >= 2_147_483_520.0 {
            2_147_483_520
        } else if x <= -2_147_483_648.0 {
            i32::MIN
        } else {
            x.trunc() as i32
        };
        i as f32
    };
    check_exact("float(int(a))", 1, |x| expected_int(x[0]));
    check_exact("float(uint(a))", 1, |x| {
        let u: u32 = if x[0].is_nan() || x[0] <= 0.0 {
            0
        } else if x[0] >= 4_294_967_040.0 {
            4_294_967_040
        } else {
            x[0].trunc() as u32
        };
        u as f32
    });
}

/// Integer operations in the f64 evaluator, where every `int` input is exact.
fn int_op(expr: &str, ty: &str, values: &[i64]) -> Vec<((i64, i64), u32)> {
    let program = program(expr, ty);
    let mut eval = Evaluator::<f64>::new(&program);
    let mut xs = Vec::new();
    let mut ys = Vec::new();
    for &x in values {
        for &y in values {
            xs.push(x as f64);
            ys.push(y as f64);
        }
    }
    let (first, second) = if ty == "int" { ("i", "j") } else { ("m", "n") };
    let out = eval.eval_points(xs.len(), &[(first, &xs), (second, &ys)], &["r"]).unwrap();
    xs.iter().zip(&ys).zip(&out[0]).map(|((x, y), r)| ((*x as i64, *y as i64), *r as u32)).collect()
}

const INTS: [i64; 14] = [0, 1, -1, 2, -2, 7, -7, 31, 32, 33, 12345, -98765, i32::MAX as i64, i32::MIN as i64];
const UINTS: [i64; 10] = [0, 1, 2, 7, 31, 32, 33, 0x8000_0000, 0xffff_fffe, 0xffff_ffff];

#[test]
fn int_arithmetic_wraps_and_divides_like_wgsl() {
    type IntOp = fn(i32, i32) -> i32;
    let cases: [(&str, IntOp); 10] = [
        ("i + j", i32::wrapping_add),
        ("i - j", i32::wrapping_sub),
        ("i * j", i32::wrapping_mul),
        ("i / j", |x, y| if y == 0 { x } else { x.wrapping_div(y) }),
        ("i % j", |x, y| if y == 0 { 0 } else { x.wrapping_rem(y) }),
        ("i & j", |x, y| x & y),
        ("i | j", |x, y| x | y),
        ("i ^ j", |x, y| x ^ y),
        ("i << j", |x, y| x.wrapping_shl(y as u32 & 31)),
        ("i >> j", |x, y| x.wrapping_shr(y as u32 & 31)),
    ];
    for (expr, f) in cases {
        for ((x, y), got) in int_op(expr, "int", &INTS) {
            let want = f(x as i32, y as i32) as u32;
            assert_eq!(got, want, "{expr} at ({x}, {y})");
        }
    }
    for ((x, _), got) in int_op("-i", "int", &INTS) {
        assert_eq!(got, (x as i32).wrapping_neg() as u32, "-{x}");
    }
    for ((x, _), got) in int_op("~i", "int", &INTS) {
        assert_eq!(got, !(x as i32) as u32, "~{x}");
    }
}

#[test]
fn uint_arithmetic_wraps_and_divides_like_wgsl() {
    type UintOp = fn(u32, u32) -> u32;
    let cases: [(&str, UintOp); 7] = [
        ("m + n", u32::wrapping_add),
        ("m - n", u32::wrapping_sub),
        ("m * n", u32::wrapping_mul),
        ("m / n", |x, y| x.checked_div(y).unwrap_or(x)),
        ("m % n", |x, y| x.checked_rem(y).unwrap_or(0)),
        ("m >> n", |x, y| x.wrapping_shr(y & 31)),
        ("m << n", |x, y| x.wrapping_shl(y & 31)),
    ];
    for (expr, f) in cases {
        for ((x, y), got) in int_op(expr, "uint", &UINTS) {
            assert_eq!(got, f(x as u32, y as u32), "{expr} at ({x}, {y})");
        }
    }
}

#[test]
fn integer_comparisons_and_builtins() {
    for ((x, y), got) in int_op("i < j ? 1 : 0", "int", &INTS) {
        assert_eq!(got, u32::from(x < y), "{x} < {y}");
    }
    for ((x, y), got) in int_op("m < n ? 1u : 0u", "uint", &UINTS) {
        assert_eq!(got, u32::from(x < y), "{x} < {y} unsigned");
    }
    for ((x, y), got) in int_op("min(i, j)", "int", &INTS) {
        assert_eq!(got, x.min(y) as i32 as u32);
    }
    for ((x, y), got) in int_op("max(m, n)", "uint", &UINTS) {
        assert_eq!(got, x.max(y) as u32);
    }
    for ((x, _), got) in int_op("abs(i)", "int", &INTS) {
        assert_eq!(got, (x as i32).wrapping_abs() as u32);
    }
    for ((x, y), got) in int_op("clamp(i, -5, j)", "int", &INTS) {
        assert_eq!(got, (x as i32).max(-5).min(y as i32) as u32);
    }
}

/// Transcendentals in f32 against f64 on the ranges where WGSL specifies them, within a few
/// units in the last place of the f32 result (Rust's libm is faithful to 1-2 ulp).
#[test]
fn transcendentals_against_f64() {
    type F64 = fn(f64) -> f64;
    let cases: [(&str, F64, f64, f64); 9] = [
        ("sin(a)", f64::sin, -std::f64::consts::PI, std::f64::consts::PI),
        ("cos(a)", f64::cos, -std::f64::consts::PI, std::f64::consts::PI),
        ("tan(a)", f64::tan, -1.5, 1.5),
        ("asin(a)", f64::asin, -1.0, 1.0),
        ("acos(a)", f64::acos, -1.0, 1.0),
        ("atan(a)", f64::atan, -100.0, 100.0),
        ("exp(a)", f64::exp, -80.0, 80.0),
        ("log(a)", f64::ln, 1e-30, 1e30),
        ("radians(a)", f64::to_radians, -1000.0, 1000.0),
    ];
    for (expr, f, lo, hi) in cases {
        let program = program(expr, "float");
        let mut eval = Evaluator::<f32>::new(&program);
        let xs: Vec<f64> =
            (0..1001).map(|k| f64::from((lo + (hi - lo) * f64::from(k) / 1000.0) as f32)).collect();
        let out = eval.eval_points(xs.len(), &[("a", &xs)], &["r"]).unwrap();
        for (x, got) in xs.iter().zip(&out[0]) {
            let want = f(*x);
            let ulp = f64::from((want as f32).abs().max(f32::MIN_POSITIVE)) * f64::from(f32::EPSILON);
            assert!((got - want).abs() <= 4.0 * ulp, "{expr} at {x}: {got} vs {want}");
        }
    }
    let program = program("pow(a, b) + atan(a, b)", "float");
    let mut eval = Evaluator::<f32>::new(&program);
    let out = eval.eval_points(1, &[("a", &[2.0]), ("b", &[0.5])], &["r"]).unwrap();
    let want = 2f64.sqrt() + 2f64.atan2(0.5);
    assert!((out[0][0] - want).abs() < 1e-6, "{} vs {want}", out[0][0]);
}

/// The same operation with uniform and varying operands in every combination: the batch machine
/// has a loop per combination.
#[test]
fn uniform_and_varying_operands_agree() {
    let source = "surface t(varying float a = 0; uniform float ua = 0; varying float b = 0;
                            uniform float ub = 0; output varying float r = 0)
                  { r = mix(a, ub, b) + mix(ua, b, ub) + mix(ua, ub, a) + (a - ub) * (ua - b); }";
    let checked = patina_compiler::check_source("t.sl", source, &MemoryLoader::default());
    let program = CpuProgram::compile(
        &patina_compiler::opt::Prepared::new(checked.program.shaders[0].clone()),
        &Binding::default(),
    )
    .unwrap();
    let mut eval = Evaluator::<f32>::new(&program);
    let (ua, ub) = (0.75f32, -1.25f32);
    eval.set("ua", &[f64::from(ua)]).unwrap();
    eval.set("ub", &[f64::from(ub)]).unwrap();
    let xs: Vec<f64> = (0..300).map(|k| f64::from(k as f32 * 0.37 - 50.0)).collect();
    let ys: Vec<f64> = (0..300).map(|k| f64::from((k as f32 * 0.11).sin())).collect();
    let out = eval.eval_points(xs.len(), &[("a", &xs), ("b", &ys)], &["r"]).unwrap();
    let mix = |x: f32, y: f32, t: f32| x * (1.0 - t) + y * t;
    for ((x, y), got) in xs.iter().zip(&ys).zip(&out[0]) {
        let (a, b) = (*x as f32, *y as f32);
        let want = mix(a, ub, b) + mix(ua, b, ub) + mix(ua, ub, a) + (a - ub) * (ua - b);
        assert_eq!(*got as f32, want, "a = {a}, b = {b}");
    }
}

/// Out-of-range array indices clamp to the array (what the WGSL backend will do), never panic;
/// a loop that does not end is stopped with its position.
#[test]
fn runtime_errors_are_defined() {
    let source = "surface t(varying float a = 0; output varying float r = 0) {
        float table[3] = {10, 20, 30};
        table[int(a)] = table[int(a)] + 1;
        r = table[0] + table[1] * 100 + table[2] * 10000;
    }";
    let checked = patina_compiler::check_source("t.sl", source, &MemoryLoader::default());
    let program = CpuProgram::compile(
        &patina_compiler::opt::Prepared::new(checked.program.shaders[0].clone()),
        &Binding::default(),
    )
    .unwrap();
    let mut eval = Evaluator::<f64>::new(&program);
    let out = eval.eval_points(4, &[("a", &[-5.0, 1.0, 2.0, 99.0])], &["r"]).unwrap();
    assert_eq!(
        out[0],
        vec![
            11.0 + 2000.0 + 300000.0,
            10.0 + 2100.0 + 300000.0,
            10.0 + 2000.0 + 310000.0,
            10.0 + 2000.0 + 310000.0
        ]
    );

    let source = "surface t(varying float a = 0) { float x = 0; while (x < 10) { x += a; } Ci = x; }";
    let checked = patina_compiler::check_source("t.sl", source, &MemoryLoader::default());
    let program = CpuProgram::compile(
        &patina_compiler::opt::Prepared::new(checked.program.shaders[0].clone()),
        &Binding::default(),
    )
    .unwrap();
    let mut eval = Evaluator::<f32>::new(&program);
    eval.set_budget(1000);
    // One point makes progress, one never does.
    let err = eval.eval_points(2, &[("a", &[1.0, 0.0])], &["Ci"]).unwrap_err();
    let diagnostic = err.to_diagnostic();
    assert_eq!(diagnostic.code.as_str(), "E0702");
    assert!(diagnostic.message.contains("1000 iterations"), "{}", diagnostic.message);
    let start = diagnostic.labels[0].span.start as usize;
    assert!(source[start..].starts_with("while"), "points at the loop: {}", &source[start..]);
}
