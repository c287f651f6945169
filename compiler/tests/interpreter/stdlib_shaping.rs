//! The standard library's shaping and antialiased pattern functions (`compiler/stdlib/pattern.sl`) on the
//! interpreter, in f32 and f64.
//!
//! What is measured (run with `--nocapture` to see the numbers):
//! - the shaping functions (pulse, boxstep, gammacorrect, bias, gain, schlickbias, schlickgain,
//!   pulsetrain) against their formulas evaluated in f64 in this file, at the same (f32-rounded)
//!   arguments: within 1e-10 in f64 and 1e-5 in f32 (pow and log in f32; see `SHAPING_TOL`);
//! - the box-filtered functions against a 10,000-point midpoint rule of the unfiltered formula
//!   over [x - w/2, x + w/2]: the rule misjudges at most one sample per discontinuity, so the
//!   tolerance is (discontinuities in the box + 1) / N, plus the rounding of the arguments in the
//!   interpreter's precision magnified by 1/w (`filtered_functions_match_numerical_box_integrals`);
//! - the extremes (w = 0, tiny and 1e6; x = ±1e6, ±1e30; b, g = 0 and 1) give finite values,
//!   w = 0 gives the unfiltered function exactly, and w = 1e6 gives the mean.

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::scalar::Real;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_test_support::Rng;

/// Midpoint-rule samples per box.
const N: usize = 10_000;

/// Shaping functions against their formulas: absolute tolerance (relative above 1) per precision.
/// In f64 the largest error (2.9e-11) is the reference's: Schlick's published form of bias,
/// x / ((1/b - 2)(1 - x) + 1), cancels to x / (x + rounding) as b -> 1 and x -> 0, where the
/// library's b x / ((1 - b)(1 - x) + b x) does not.
const SHAPING_TOL: [f64; 2] = [1e-10, 1e-5];

/// The interpreter running `expr` of the four float inputs s, t, u, v, into Ci's first component.
/// (Oi reads all four, so that each is an input whether or not `expr` uses it.)
fn program(expr: &str) -> CpuProgram {
    let src = format!(
        "#include <pattern.sl>\nsurface t() {{ Ci = color({expr}, 0, 0); Oi = color(s + v, t, u); }}\n"
    );
    crate::support::compile(&src, &Binding::default())
}

fn eval<F: Real>(expr: &str, args: &[[f64; 4]]) -> Vec<f64> {
    let program = program(expr);
    let mut e = Evaluator::<F>::new(&program);
    let cols: Vec<Vec<f64>> = (0..4).map(|k| args.iter().map(|a| a[k]).collect()).collect();
    let inputs: Vec<(&str, &[f64])> =
        ["s", "t", "u", "v"].iter().zip(&cols).map(|(n, c)| (*n, c.as_slice())).collect();
    let out = e.eval_points(args.len(), &inputs, &["Ci"]).expect("evaluation");
    out[0].chunks_exact(3).map(|c| c[0]).collect()
}

/// (precision, the arguments as that precision sees them, results) for f64 and f32.
type Run = (&'static str, Vec<[f64; 4]>, Vec<f64>);

fn eval_both(expr: &str, args: &[[f64; 4]]) -> [Run; 2] {
    let args32: Vec<[f64; 4]> = args.iter().map(|a| a.map(|x| f64::from(x as f32))).collect();
    let got32 = eval::<f32>(expr, &args32);
    [("f64", args.to_vec(), eval::<f64>(expr, args)), ("f32", args32, got32)]
}

/// Independent formulas, in f64.
mod reference {
    pub fn step(a: f64, x: f64) -> f64 {
        if x < a { 0.0 } else { 1.0 }
    }
    pub fn pulse(a: f64, b: f64, x: f64) -> f64 {
        step(a, x) - step(b, x)
    }
    pub fn boxstep(a: f64, b: f64, x: f64) -> f64 {
        if a == b { step(a, x) } else { ((x - a) / (b - a)).clamp(0.0, 1.0) }
    }
    pub fn gammacorrect(g: f64, x: f64) -> f64 {
        if x <= 0.0 {
            0.0
        } else if g <= 0.0 {
            step(1.0, x)
        } else {
            x.powf(1.0 / g)
        }
    }
    pub fn bias(b: f64, x: f64) -> f64 {
        let x = x.clamp(0.0, 1.0);
        if x == 0.0 || x == 1.0 {
            return x;
        }
        if b <= 0.0 {
            0.0
        } else if b >= 1.0 {
            1.0
        } else {
            x.powf(b.ln() / 0.5f64.ln())
        }
    }
    pub fn gain(g: f64, x: f64) -> f64 {
        if x < 0.5 { bias(1.0 - g, 2.0 * x) / 2.0 } else { 1.0 - bias(1.0 - g, 2.0 - 2.0 * x) / 2.0 }
    }
    /// Schlick's published form x / ((1/b - 2)(1 - x) + 1), with its corners.
    pub fn schlickbias(b: f64, x: f64) -> f64 {
        let (x, b) = (x.clamp(0.0, 1.0), b.clamp(0.0, 1.0));
        if x == 0.0 || x == 1.0 {
            return x;
        }
        if b == 0.0 {
            return 0.0;
        }
        x / ((1.0 / b - 2.0) * (1.0 - x) + 1.0)
    }
    pub fn schlickgain(g: f64, x: f64) -> f64 {
        if x < 0.5 {
            schlickbias(1.0 - g, 2.0 * x) / 2.0
        } else {
            1.0 - schlickbias(1.0 - g, 2.0 - 2.0 * x) / 2.0
        }
    }
    pub fn pulsetrain(edge: f64, period: f64, x: f64) -> f64 {
        let e = (edge / period).clamp(0.0, 0.5);
        let t = x / period;
        pulse(e, 1.0 - e, t - t.floor())
    }
    /// The mean of f over [x - w/2, x + w/2] by the midpoint rule with N samples.
    pub fn box_mean(f: impl Fn(f64) -> f64, x: f64, w: f64) -> f64 {
        let n = super::N;
        let d = w / n as f64;
        (0..n).map(|i| f(x - w / 2.0 + (i as f64 + 0.5) * d)).sum::<f64>() / n as f64
    }
}

type Shaping = (&'static str, fn(&[f64; 4]) -> f64);

/// Every shaping function as a shader expression of (s, t, u, v) and its reference.
const SHAPING: &[Shaping] = &[
    ("pulse(s, t, u)", |a| reference::pulse(a[0], a[1], a[2])),
    ("boxstep(s, t, u)", |a| reference::boxstep(a[0], a[1], a[2])),
    ("gammacorrect(s, u)", |a| reference::gammacorrect(a[0], a[2])),
    ("bias(s, u)", |a| reference::bias(a[0], a[2])),
    ("gain(s, u)", |a| reference::gain(a[0], a[2])),
    ("schlickbias(s, u)", |a| reference::schlickbias(a[0], a[2])),
    ("schlickgain(s, u)", |a| reference::schlickgain(a[0], a[2])),
    ("pulsetrain(s, t, u)", |a| reference::pulsetrain(a[0], a[1], a[2])),
];

fn shaping_args() -> Vec<[f64; 4]> {
    let mut rng = Rng(7);
    let mut args = Vec::new();
    let grid = [0.0, 1e-6, 0.001, 0.1, 0.25, 0.3, 0.5, 0.7, 0.75, 0.9, 0.999, 1.0];
    for &p in &grid {
        for &x in &grid {
            args.push([p, p + 0.5, x, 0.0]);
        }
    }
    for _ in 0..2000 {
        let p = rng.unit();
        args.push([p, p + rng.range(0.01, 2.0), rng.range(-0.2, 1.2), 0.0]);
    }
    for _ in 0..500 {
        args.push([rng.range(-3.0, 3.0), rng.range(0.1, 3.0), rng.range(-10.0, 10.0), 0.0]);
    }
    args
}

#[test]
fn shaping_functions_match_their_formulas() {
    let args = shaping_args();
    for &(expr, f) in SHAPING {
        for (k, (prec, args, got)) in eval_both(expr, &args).into_iter().enumerate() {
            let eps = if k == 0 { f64::EPSILON } else { f64::from(f32::EPSILON) };
            let mut skipped = 0;
            let mut worst = (0.0f64, [0.0; 4]);
            for (a, g) in args.iter().zip(&got) {
                let r = f(a);
                // x^(1/gamma) beyond the range of f32 (gammacorrect(0.006, 7.5)).
                if r.is_nan() || r.abs() >= 1e30 {
                    continue;
                }
                // Within rounding of a discontinuity (pulse edges), either side is right.
                let d = 8.0 * eps * (a[0].abs() + a[1].abs() + a[2].abs() + 1.0);
                if (f(&[a[0], a[1], a[2] - d, a[3]]) - f(&[a[0], a[1], a[2] + d, a[3]])).abs() > 0.5 {
                    skipped += 1;
                    continue;
                }
                // gammacorrect's arguments here are not restricted to [0, 1]: x^(1/gamma) may be
                // large, so compare relatively above 1.
                let err = (g - r).abs() / r.abs().max(1.0);
                assert!(g.is_finite(), "{expr} at {a:?} = {g} ({prec})");
                if err > worst.0 {
                    worst = (err, *a);
                }
            }
            println!(
                "{expr:22} {prec}: largest error {:.3e} at {:?} ({skipped} points at an edge skipped)",
                worst.0, worst.1
            );
            assert!(worst.0 <= SHAPING_TOL[k], "{expr} ({prec}): error {:e} at {:?}", worst.0, worst.1);
        }
    }
}

#[test]
fn shaping_identities_and_corners() {
    // (expression, arguments, expected), within SHAPING_TOL (the arguments are rounded to f32).
    let cases: &[(&str, [f64; 4], f64)] = &[
        ("bias(s, u)", [0.3, 0.0, 0.5, 0.0], 0.3),
        ("bias(s, u)", [0.5, 0.0, 0.3, 0.0], 0.3),
        ("bias(s, u)", [0.0, 0.0, 0.0, 0.0], 0.0),
        ("bias(s, u)", [0.0, 0.0, 1.0, 0.0], 1.0),
        ("bias(s, u)", [0.0, 0.0, 0.5, 0.0], 0.0),
        ("bias(s, u)", [1.0, 0.0, 0.0, 0.0], 0.0),
        ("bias(s, u)", [1.0, 0.0, 0.5, 0.0], 1.0),
        ("gain(s, u)", [0.0, 0.0, 0.5, 0.0], 0.5),
        ("gain(s, u)", [1.0, 0.0, 0.5, 0.0], 0.5),
        ("gain(s, u)", [0.0, 0.0, 0.25, 0.0], 0.5),
        ("gain(s, u)", [1.0, 0.0, 0.25, 0.0], 0.0),
        ("gain(s, u)", [1.0, 0.0, 1.0, 0.0], 1.0),
        ("schlickbias(s, u)", [0.0, 0.0, 1.0, 0.0], 1.0),
        ("schlickbias(s, u)", [1.0, 0.0, 0.0, 0.0], 0.0),
        ("schlickbias(s, u)", [0.25, 0.0, 0.5, 0.0], 0.25),
        ("schlickgain(s, u)", [0.75, 0.0, 0.25, 0.0], 0.125),
        ("schlickgain(s, u)", [0.0, 0.0, 0.75, 0.0], 0.5),
        ("gammacorrect(s, u)", [0.0, 0.0, 0.5, 0.0], 0.0),
        ("gammacorrect(s, u)", [0.0, 0.0, 1.0, 0.0], 1.0),
        ("boxstep(s, t, u)", [0.5, 0.5, 0.5, 0.0], 1.0),
        // A narrow filter keeps its precision: the Advanced RenderMan form would give 0 here.
        ("filteredpulse(s, t, u, v)", [1e6, 1e6 + 1.0, 1e6 + 0.5, 1e-9], 1.0),
        ("filteredpulsetrain(s, t, u, v)", [0.1, 1.0, 0.5, 1e-9], 1.0),
        ("filteredpulsetrain(s, t, u, v)", [0.1, 1.0, 3.05, 1e-9], 0.0),
        ("filteredabs(u, v)", [0.0, 0.0, -2.0, 1.0], 2.0),
        ("filteredabs(u, v)", [0.0, 0.0, 0.0, 2.0], 0.5),
    ];
    for (expr, a, want) in cases {
        for (k, (prec, _, got)) in eval_both(expr, &[*a]).into_iter().enumerate() {
            assert!((got[0] - want).abs() <= SHAPING_TOL[k], "{expr} at {a:?} ({prec}): {}", got[0]);
        }
    }
}

/// (filtered expression, unfiltered function of the same arguments, discontinuities of the
/// unfiltered function in the box, size of the arguments for the rounding term).
type Filtered = (&'static str, fn(&[f64; 4]) -> f64, fn(&[f64; 4]) -> f64, fn(&[f64; 4]) -> f64);

const FILTERED: &[Filtered] = &[
    ("filteredstep(s, u, v)", |a| reference::step(a[0], a[2]), |_| 1.0, |a| a[0].abs() + a[2].abs()),
    ("aastep(s, u, v)", |a| reference::step(a[0], a[2]), |_| 1.0, |a| a[0].abs() + a[2].abs()),
    (
        "filteredpulse(s, t, u, v)",
        |a| reference::pulse(a[0], a[1], a[2]),
        |_| 2.0,
        |a| a[0].abs() + a[1].abs() + a[2].abs(),
    ),
    (
        "filteredpulsetrain(s, t, u, v)",
        |a| reference::pulsetrain(a[0], a[1], a[2]),
        |a| 2.0 * (a[3] / a[1] + 2.0),
        // Everything is computed in units of the period.
        |a| a[2].abs() + a[1],
    ),
    ("filteredabs(u, v)", |a| a[2].abs(), |_| 0.0, |a| a[2].abs() + a[3]),
];

fn filtered_args(rng: &mut Rng) -> Vec<[f64; 4]> {
    let mut args = Vec::new();
    for i in 0..300 {
        let w = match i % 3 {
            0 => rng.range(0.001, 0.1),
            1 => rng.range(0.1, 2.0),
            _ => rng.range(2.0, 20.0),
        };
        let a = rng.range(-2.0, 2.0);
        let period = rng.range(0.3, 2.0);
        // For the pulse train, (s, t) = (edge, period), the edge up to a little over half the
        // period; otherwise (a, b) with a <= b.
        let edge = rng.range(0.0, 0.55) * period;
        let (s, t) = if i % 2 == 0 { (a, a + rng.range(0.0, 2.0)) } else { (edge, period) };
        args.push([s, t, rng.range(-4.0, 4.0), w]);
    }
    args
}

#[test]
fn filtered_functions_match_numerical_box_integrals() {
    let mut rng = Rng(11);
    let args = filtered_args(&mut rng);
    for &(expr, f, discontinuities, size) in FILTERED {
        for (k, (prec, args, got)) in eval_both(expr, &args).into_iter().enumerate() {
            let eps = if k == 0 { f64::EPSILON } else { f64::from(f32::EPSILON) };
            let mut worst = (0.0f64, 0.0f64, [0.0; 4]);
            for (a, g) in args.iter().zip(&got) {
                if expr.contains("pulsetrain") && a[1] <= 0.0 {
                    continue;
                }
                let mean = reference::box_mean(|x| f(&[a[0], a[1], x, a[3]]), a[2], a[3]);
                let tol = (discontinuities(a) + 1.0) / N as f64 + 8.0 * eps * (size(a) + 1.0) / a[3];
                let err = (g - mean).abs();
                assert!(
                    err <= tol,
                    "{expr} at {a:?} ({prec}): {g}, box integral {mean}, error {err:e} > {tol:e}"
                );
                if err / tol > worst.1 {
                    worst = (err, err / tol, *a);
                }
            }
            println!(
                "{expr:32} {prec}: worst error {:.3e} ({:.0}% of its tolerance) at {:?}",
                worst.0,
                100.0 * worst.1,
                worst.2
            );
        }
    }
}

#[test]
fn extremes_are_finite_and_have_the_right_limits() {
    let xs = [0.0, 0.5, -0.5, 1.0, 1e6, -1e6, 1e30, -1e30];
    let ws = [0.0, 1e-30, 1e-6, 1.0, 1e6];
    let ps = [(0.0, 1.0), (0.25, 0.5), (1.0, 1.0), (0.0, 0.0), (0.1, 1e6)];
    let mut args = Vec::new();
    for &x in &xs {
        for &w in &ws {
            for &(s, t) in &ps {
                args.push([s, t, x, w]);
            }
        }
    }
    let all: Vec<&str> = SHAPING.iter().map(|s| s.0).chain(FILTERED.iter().map(|f| f.0)).collect();
    for expr in all {
        for (prec, args, got) in eval_both(expr, &args) {
            for (a, g) in args.iter().zip(&got) {
                // The pulse train's period must be positive.
                if expr.contains("pulsetrain") && a[1] == 0.0 {
                    continue;
                }
                // gammacorrect(gamma, 1e30) = 1e30^(1/gamma) is outside the range of floats.
                if expr.starts_with("gammacorrect") && a[2] > 1.0 {
                    continue;
                }
                assert!(g.is_finite(), "{expr} at {a:?} = {g} ({prec})");
            }
        }
    }
    // w = 0: exactly the unfiltered function.
    for &(expr, f, _, _) in FILTERED {
        let args: Vec<[f64; 4]> = xs
            .iter()
            .flat_map(|&x| ps.iter().filter(|p| p.1 > 0.0).map(move |&(s, t)| [s, t, x, 0.0]))
            .collect();
        for (prec, args, got) in eval_both(expr, &args) {
            for (a, g) in args.iter().zip(&got) {
                assert_eq!(*g, f(a), "{expr} at {a:?} ({prec})");
            }
        }
    }
    // w = 1e6 around moderate x: the mean of the function over the line.
    let wide: &[(&str, [f64; 4], f64, f64)] = &[
        ("filteredstep(s, u, v)", [0.3, 0.0, 2.0, 1e6], 0.5, 1e-5),
        ("filteredpulse(s, t, u, v)", [0.0, 1.0, 0.5, 1e6], 0.0, 1e-5),
        ("filteredpulsetrain(s, t, u, v)", [0.1, 1.0, 0.5, 1e6], 0.8, 1e-5),
        ("filteredpulsetrain(s, t, u, v)", [0.5, 2.0, -7.0, 1e6], 0.5, 1e-5),
        ("filteredabs(u, v)", [0.0, 0.0, 3.0, 1e6], 2.5e5, 1e-1),
    ];
    for (expr, a, want, tol) in wide {
        for (prec, _, got) in eval_both(expr, &[*a]) {
            assert!((got[0] - want).abs() <= *tol, "{expr} at {a:?} ({prec}): {}, want {want}", got[0]);
        }
    }
}
