//! The standard library's fractal sums (`compiler/stdlib/fractal.sl`) on the interpreter, against an
//! independent Rust port of the same formulas (module `fractal`, below) on top of a port of
//! Perlin's reference improved noise (`patina_test_support::perlin::noise_wide`).
//!
//! What is measured (run with `--nocapture` to see the numbers):
//! - f64 mode: every function within 1e-12 of the port (`F64_TOL`);
//! - f32 mode: within `F32_TOL` (1e-5) of the port evaluated in f64 at the f32-rounded inputs;
//! - fBm statistics over 20 000 points: mean near 0, variance within a band around
//!   var(snoise3) * sum of the squared spectral weights;
//! - continuity in the fractional octave count (fbm, turbulence, hybrid) and in the filter width;
//! - extremes (octaves 0 and 30, H 0 and 2, lacunarity 1 and 8, coordinates up to ±1e30 and
//!   denormals, width 0 and 1e30): finite in both precisions;
//! - the multiplicative functions and distorted noise (multifractal, hetero_terrain, distnoise,
//!   distfbm): the same checks against their ports (relative for the multifractal), the
//!   extremes (offsets 0, ±1e4, ±1e30, distortions 0 and ±1e30), the multifractal's mean
//!   converging to 0 with the octaves, the terrain smoother at sea level, continuity in octaves.

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::scalar::Real;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_test_support::Rng;
/// Perlin's ImprovedNoise.java with the stdlib's one departure (the cell reduced modulo 256 in
/// float, so that fBm's finer octaves beyond 2^31 keep the period).
use patina_test_support::perlin::noise_wide;

/// The formulas of `compiler/stdlib/fractal.sl`, ported from their definitions (Musgrave, Perlin) in f64,
/// operation for operation in the stdlib's order.
mod fractal {
    /// How the precision rounds the scaled points p lacunarity^i: f64 itself, or to f32.
    pub type Round = fn(f64) -> f64;

    const SNOISE_SCALE: f64 = 0.9649;
    const MAX_OCTAVES: f64 = 30.0;

    pub fn snoise3(p: [f64; 3]) -> f64 {
        SNOISE_SCALE * super::noise_wide(p[0], p[1], p[2])
    }

    fn scale(p: [f64; 3], s: f64) -> [f64; 3] {
        p.map(|x| x * s)
    }

    /// The next octave's point: p lacunarity rounded by the precision, each coordinate clamped
    /// to +-1e30 (PATINA_FRACTAL_MAX_COORD, itself rounded to the precision).
    fn next(round: Round, p: [f64; 3], lac: f64) -> [f64; 3] {
        let bound = round(1e30);
        p.map(|x| round(x * lac).clamp(-bound, bound))
    }

    pub fn fbm(round: Round, p: [f64; 3], h: f64, lacunarity: f64, octaves: f64) -> f64 {
        let h = h.max(0.0);
        let lac = lacunarity.clamp(1.0, 8.0);
        let oct = octaves.clamp(0.0, MAX_OCTAVES);
        let n = oct.floor();
        let mut value = 0.0;
        let mut pp = p;
        let mut i = 0.0;
        while i < n {
            value += snoise3(pp) * lac.powf(-h * i);
            pp = next(round, pp, lac);
            i += 1.0;
        }
        value + (oct - n) * snoise3(pp) * lac.powf(-h * n)
    }

    pub fn turbulence(p: [f64; 3], octaves: f64) -> f64 {
        let oct = octaves.clamp(0.0, MAX_OCTAVES);
        let n = oct.floor();
        let (mut value, mut f) = (0.0, 1.0);
        let mut i = 0.0;
        while i < n {
            value += snoise3(scale(p, f).map(|x| x.clamp(-1e30, 1e30))).abs() / f;
            f *= 2.0;
            i += 1.0;
        }
        value + (oct - n) * snoise3(scale(p, f).map(|x| x.clamp(-1e30, 1e30))).abs() / f
    }

    pub fn ridged(
        round: Round,
        p: [f64; 3],
        h: f64,
        lacunarity: f64,
        octaves: f64,
        offset: f64,
        gain: f64,
    ) -> f64 {
        let h = h.max(0.0);
        let lac = lacunarity.clamp(1.0, 8.0);
        let n = octaves.clamp(0.0, MAX_OCTAVES).floor();
        let o = offset.clamp(-1e4, 1e4);
        let (mut result, mut weight) = (0.0, 1.0);
        let mut pp = p;
        let mut i = 0.0;
        while i < n {
            let s = o - snoise3(pp).abs();
            let signal = s * s * weight;
            result += signal * lac.powf(-h * i);
            weight = (signal * gain).clamp(0.0, 1.0);
            pp = next(round, pp, lac);
            i += 1.0;
        }
        result
    }

    pub fn hybrid(round: Round, p: [f64; 3], h: f64, lacunarity: f64, octaves: f64, offset: f64) -> f64 {
        let h = h.max(0.0);
        let lac = lacunarity.clamp(1.0, 8.0);
        let oct = octaves.clamp(0.0, MAX_OCTAVES);
        let n = oct.floor();
        let o = offset.clamp(-1e4, 1e4);
        let (mut result, mut weight) = (0.0, 1.0f64);
        let mut pp = p;
        let mut i = 0.0;
        while i < n {
            weight = weight.clamp(-1e30, 1.0);
            let signal = (snoise3(pp) + o) * lac.powf(-h * i);
            result += weight * signal;
            weight *= signal;
            pp = next(round, pp, lac);
            i += 1.0;
        }
        weight = weight.clamp(-1e30, 1.0);
        let signal = (snoise3(pp) + o) * lac.powf(-h * n);
        result + (oct - n) * weight * signal
    }

    pub fn fbm_filtered(round: Round, p: [f64; 3], h: f64, lacunarity: f64, octaves: f64, width: f64) -> f64 {
        let lac = lacunarity.clamp(1.0, 8.0);
        let w = width.abs().max(1e-30);
        fbm(round, p, h, lac, octaves.min(-w.ln() / lac.ln().max(1e-6)))
    }

    pub fn turbulence_filtered(p: [f64; 3], octaves: f64, width: f64) -> f64 {
        let w = width.abs().max(1e-30);
        turbulence(p, octaves.min(-w.ln() / 2f64.ln().max(1e-6)))
    }
    /// Musgrave's multiplicative multifractal with the stdlib's guards; also returns the product
    /// of max(1, |factor|) over the octaves (a bound on every partial product, for tolerances).
    pub fn multifractal(
        round: Round,
        p: [f64; 3],
        h: f64,
        lacunarity: f64,
        octaves: f64,
        offset: f64,
    ) -> (f64, f64) {
        let h = h.max(0.0);
        let lac = lacunarity.clamp(1.0, 8.0);
        let n = octaves.clamp(0.0, MAX_OCTAVES).floor();
        let o = offset.clamp(-1e4, 1e4);
        let (mut value, mut bound) = (1.0f64, 1.0f64);
        let mut pp = p;
        let mut i = 0.0;
        while i < n {
            let factor = (snoise3(pp) + o) * lac.powf(-h * i);
            value = (value * factor).clamp(-1e30, 1e30);
            bound = (bound * factor.abs().max(1.0)).min(1e30);
            pp = next(round, pp, lac);
            i += 1.0;
        }
        (value, bound)
    }

    /// Musgrave's Hetero_Terrain with the stdlib's decisions (altitude weight clamped to
    /// [-1, 1], first octave weighted by clamp(octaves, 0, 1)).
    pub fn hetero(round: Round, p: [f64; 3], h: f64, lacunarity: f64, octaves: f64, offset: f64) -> f64 {
        let h = h.max(0.0);
        let lac = lacunarity.clamp(1.0, 8.0);
        let oct = octaves.clamp(0.0, MAX_OCTAVES);
        let o = offset.clamp(-1e4, 1e4);
        let mut value = oct.clamp(0.0, 1.0) * (o + snoise3(p));
        let mut pp = next(round, p, lac);
        let mut i = 1.0;
        while i < oct {
            let increment = (snoise3(pp) + o) * lac.powf(-h * i) * value.clamp(-1.0, 1.0);
            value += (oct - i).clamp(0.0, 1.0) * increment;
            pp = next(round, pp, lac);
            i += 1.0;
        }
        value
    }

    /// Musgrave's VecNoise: the noise at q, q + 3.33 and q + 7.77 (each coordinate displaced).
    fn vecnoise(round: Round, q: [f64; 3]) -> [f64; 3] {
        let shift = |d: f64| q.map(|x| round(x + round(d)));
        [snoise3(q), snoise3(shift(3.33)), snoise3(shift(7.77))]
    }

    /// DistNoise: snoise3(p + distortion * VecNoise(p + 0.5)).
    pub fn distnoise(round: Round, p: [f64; 3], distortion: f64) -> f64 {
        let d = distortion.clamp(-1e30, 1e30);
        let v = vecnoise(round, p.map(|x| round(x + 0.5)));
        snoise3([0, 1, 2].map(|k| round(p[k] + round(d * v[k]))))
    }

    /// DistfBm: fbm's sum over distnoise.
    pub fn distfbm(round: Round, p: [f64; 3], h: f64, lacunarity: f64, octaves: f64, distortion: f64) -> f64 {
        let h = h.max(0.0);
        let lac = lacunarity.clamp(1.0, 8.0);
        let oct = octaves.clamp(0.0, MAX_OCTAVES);
        let mut value = 0.0;
        let mut pp = p;
        let mut i = 0.0;
        while i < oct {
            value += (oct - i).clamp(0.0, 1.0) * distnoise(round, pp, distortion) * lac.powf(-h * i);
            pp = next(round, pp, lac);
            i += 1.0;
        }
        value
    }
}

const SHADER: &str = "#include <fractal.sl>\n\
    surface t(varying float H = 0.5, lac = 2, oct = 4, width = 0.01, offset = 1, gain = 2) {\n\
        Ci = color(fbm(P, H, lac, oct), turbulence(P, oct), fbm_filtered(P, H, lac, oct, width));\n\
        Oi = color(ridged_multifractal(P, H, lac, oct, offset, gain),\n\
                   hybrid_multifractal(P, H, lac, oct, offset), turbulence_filtered(P, oct, width));\n\
    }\n";

const NAMES: [&str; 6] = [
    "fbm",
    "turbulence",
    "fbm_filtered",
    "ridged_multifractal",
    "hybrid_multifractal",
    "turbulence_filtered",
];

/// One evaluation's inputs.
#[derive(Clone, Copy, Debug)]
struct Args {
    p: [f64; 3],
    h: f64,
    lac: f64,
    oct: f64,
    width: f64,
    offset: f64,
    gain: f64,
}

impl Args {
    fn new(p: [f64; 3], h: f64, lac: f64, oct: f64, width: f64) -> Args {
        Args { p, h, lac, oct, width, offset: 1.0, gain: 2.0 }
    }

    /// The inputs as the f32 mode sees them.
    fn to_f32(self) -> Args {
        let r = |x: f64| f64::from(x as f32);
        Args {
            p: self.p.map(r),
            h: r(self.h),
            lac: r(self.lac),
            oct: r(self.oct),
            width: r(self.width),
            offset: r(self.offset),
            gain: r(self.gain),
        }
    }

    /// The five functions by the port.
    fn reference(&self, round: fractal::Round) -> [f64; 6] {
        // The multifractals' offsets differ (ridged 1, hybrid 0.7 by Musgrave's suggestions) but
        // one shader parameter feeds both; the tests use `offset` for both.
        [
            fractal::fbm(round, self.p, self.h, self.lac, self.oct),
            fractal::turbulence(self.p, self.oct),
            fractal::fbm_filtered(round, self.p, self.h, self.lac, self.oct, self.width),
            fractal::ridged(round, self.p, self.h, self.lac, self.oct, self.offset, self.gain),
            fractal::hybrid(round, self.p, self.h, self.lac, self.oct, self.offset),
            fractal::turbulence_filtered(self.p, self.oct, self.width),
        ]
    }
}

fn program() -> CpuProgram {
    crate::support::compile(SHADER, &Binding::default())
}

/// The five functions at each argument set, evaluated in precision `F`. The parameters are
/// varying, so every point has its own.
fn eval<F: Real>(program: &CpuProgram, args: &[Args]) -> Vec<[f64; 6]> {
    let mut e = Evaluator::<F>::new(program);
    let p: Vec<f64> = args.iter().flat_map(|a| a.p).collect();
    let col = |f: fn(&Args) -> f64| -> Vec<f64> { args.iter().map(f).collect() };
    let (h, lac, oct) = (col(|a| a.h), col(|a| a.lac), col(|a| a.oct));
    let (width, offset, gain) = (col(|a| a.width), col(|a| a.offset), col(|a| a.gain));
    let inputs: [(&str, &[f64]); 7] = [
        ("P", &p),
        ("H", &h),
        ("lac", &lac),
        ("oct", &oct),
        ("width", &width),
        ("offset", &offset),
        ("gain", &gain),
    ];
    let out = e.eval_points(args.len(), &inputs, &["Ci", "Oi"]).expect("evaluation");
    (0..args.len())
        .map(|i| {
            let (c, o) = (&out[0][3 * i..3 * i + 3], &out[1][3 * i..3 * i + 3]);
            [c[0], c[1], c[2], o[0], o[1], o[2]]
        })
        .collect()
}

fn f64_exact(x: f64) -> f64 {
    x
}

fn to_f32(x: f64) -> f64 {
    f64::from(x as f32)
}

/// Random argument sets of ordinary use: points within ±50, H in [0, 1.5], lacunarity 2 or in
/// [1.5, 3], octaves in [0, 10], widths from 1e-4 to 1, offsets and gains around Musgrave's.
fn ordinary_args() -> Vec<Args> {
    let mut rng = Rng(11);
    (0..3000)
        .map(|i| {
            let lac = if i % 2 == 0 { 2.0 } else { rng.range(1.5, 3.0) };
            let mut a = Args::new(
                rng.point(-50.0, 50.0),
                rng.range(0.0, 1.5),
                lac,
                rng.range(0.0, 10.0),
                10f64.powf(rng.range(-4.0, 0.0)),
            );
            a.offset = rng.range(0.5, 1.2);
            a.gain = rng.range(1.0, 3.0);
            a
        })
        .collect()
}

/// The extremes: every combination of the listed points, octaves, H, lacunarities and widths.
fn extreme_args() -> Vec<Args> {
    let mut args = Vec::new();
    let points = [
        [0.0, 0.0, 0.0],
        [0.3, -0.7, 0.55],
        [1e4, -1e4, 1e4 + 0.37],
        [-1e4, 1e4, -1e4],
        [1e6, -1e6, 1e6 + 0.5],
        [-1e6, 1e6 + 0.25, -1e6],
        [1e30, -1e30, 1e-30],
        [1e7, -1e7 + 0.5, f64::from(f32::from_bits(1))],
    ];
    for p in points {
        for oct in [0.0, 0.5, 1.0, 7.3, 30.0] {
            for h in [0.0, 2.0] {
                for lac in [1.0, 2.0, 8.0] {
                    for width in [0.0, 1e-3, 1.0, 1e30] {
                        args.push(Args::new(p, h, lac, oct, width));
                    }
                }
            }
        }
        // the multifractals' offsets and gains at their extremes
        for (offset, gain) in [(0.0, 0.0), (1e4, 1e30), (-1e4, 1.0), (1e30, 2.0), (-1e30, -1e30)] {
            for (h, lac) in [(0.0, 1.0), (2.0, 8.0), (0.0, 8.0)] {
                let mut a = Args::new(p, h, lac, 30.0, 1e-3);
                a.offset = offset;
                a.gain = gain;
                args.push(a);
            }
        }
    }
    args
}

/// The f64 mode's tolerance against the port: the stdlib and the port do the same operations in
/// the same order, and the interpreter's f64 `pow` and `log` are Rust's, so in practice the
/// results agree to the last bit or so.
const F64_TOL: f64 = 1e-12;

/// The f32 mode's tolerances against the port in f64 at the f32-rounded inputs, with the scaled
/// points p lacunarity^i rounded to f32 as the f32 mode rounds them (exact for lacunarity 2;
/// otherwise the rounding of the coordinate, not the arithmetic, would dominate: |p| 3^9 at
/// |p| = 50 is 1e6, where an f32 step is 0.06 of a cell). What remains is the noise's own error
/// (2e-6 per octave, stdlib_noise.rs), the f32 `pow` and the sums' rounding. Measured largest
/// errors are printed: 2.7e-6 (ridged and hybrid multifractals), 1.2e-6 (fBm) over 3000 sets.
const F32_TOL: f64 = 1e-5;

#[test]
fn f64_mode_matches_the_port() {
    let program = program();
    let mut args = ordinary_args();
    args.extend(extreme_args());
    let out = eval::<f64>(&program, &args);
    let mut worst = [0.0f64; 6];
    for (a, o) in args.iter().zip(&out) {
        let r = a.reference(f64_exact);
        for f in 0..6 {
            let err = (o[f] - r[f]).abs();
            worst[f] = worst[f].max(err);
            assert!(err <= F64_TOL, "{}({a:?}) = {}, port {}", NAMES[f], o[f], r[f]);
        }
    }
    println!("f64 mode, {} argument sets, largest error per function {worst:?}", args.len());
}

#[test]
fn f32_mode_is_close_to_the_port() {
    let program = program();
    let args = ordinary_args();
    let out = eval::<f32>(&program, &args);
    let mut worst = [[0.0f64; 6]; 2];
    for (a, o) in args.iter().zip(&out) {
        let r = a.to_f32().reference(to_f32);
        let k = if a.lac == 2.0 { 0 } else { 1 };
        for f in 0..6 {
            let err = (o[f] - r[f]).abs();
            worst[k][f] = worst[k][f].max(err);
            assert!(err <= F32_TOL, "{}({a:?}) = {}, port {}", NAMES[f], o[f], r[f]);
        }
    }
    println!("f32 mode, {} argument sets, largest error per function:", args.len());
    println!("  lacunarity 2 {:?}", worst[0]);
    println!("  lacunarity in [1.5, 3] {:?}", worst[1]);
}

#[test]
fn extremes_are_finite_in_both_precisions() {
    let program = program();
    let args = extreme_args();
    let out64 = eval::<f64>(&program, &args);
    let out32 = eval::<f32>(&program, &args);
    for (i, a) in args.iter().enumerate() {
        for f in 0..6 {
            assert!(out64[i][f].is_finite(), "f64 {}({a:?}) = {}", NAMES[f], out64[i][f]);
            assert!(out32[i][f].is_finite(), "f32 {}({a:?}) = {}", NAMES[f], out32[i][f]);
        }
        if a.oct == 0.0 {
            assert_eq!([out64[i][0], out64[i][1], out64[i][3], out64[i][4]], [0.0; 4], "octaves 0: {a:?}");
        }
        if a.width >= 1.0 {
            assert_eq!([out64[i][2], out64[i][5]], [0.0; 2], "width >= 1 keeps no octave: {a:?}");
        }
    }
    println!("{} extreme argument sets finite in f64 and f32", args.len());
}

#[test]
fn fbm_statistics() {
    let program = program();
    let mut rng = Rng(5);
    let (h, lac, oct) = (0.5, 2.0, 6.0);
    let args: Vec<Args> =
        (0..20_000).map(|_| Args::new(rng.point(-200.0, 200.0), h, lac, oct, 0.01)).collect();
    let out = eval::<f64>(&program, &args);
    let n = args.len() as f64;
    let mean = out.iter().map(|o| o[0]).sum::<f64>() / n;
    let var = out.iter().map(|o| (o[0] - mean).powi(2)).sum::<f64>() / n;
    // The basis's variance at the same points, and the sum of the squared weights 2^(-i).
    let s: Vec<f64> = args.iter().map(|a| fractal::snoise3(a.p)).collect();
    let s_mean = s.iter().sum::<f64>() / n;
    let s_var = s.iter().map(|x| (x - s_mean).powi(2)).sum::<f64>() / n;
    let weights: f64 = (0..6).map(|i| f64::powf(lac, -2.0 * h * f64::from(i))).sum();
    let expected = s_var * weights;
    println!("fbm(H 0.5, lacunarity 2, 6 octaves): mean {mean:.5}, variance {var:.5}");
    println!("snoise3 variance {s_var:.5}; octaves independent would give {expected:.5}");
    assert!(mean.abs() < 0.01, "mean {mean}");
    assert!((0.06..0.08).contains(&s_var), "snoise3 variance {s_var}");
    assert!((0.8 * expected..1.2 * expected).contains(&var), "variance {var} against {expected}");
    // Turbulence is non-negative.
    assert!(out.iter().all(|o| o[1] >= 0.0));
}

#[test]
fn fractional_octaves_are_continuous() {
    let program = program();
    let mut rng = Rng(3);
    let eps = 1e-7;
    let mut args = Vec::new();
    for _ in 0..200 {
        let p = rng.point(-20.0, 20.0);
        for n in 0..10 {
            let n = f64::from(n);
            for oct in [n - eps, n, n + eps] {
                let mut a = Args::new(p, 0.7, 2.0, oct.max(0.0), 1e-9);
                a.offset = 0.7;
                args.push(a);
            }
        }
    }
    for precision in ["f64", "f32"] {
        let out =
            if precision == "f64" { eval::<f64>(&program, &args) } else { eval::<f32>(&program, &args) };
        let mut worst = [0.0f64; 6];
        for (t, c) in out.chunks_exact(3).zip(args.chunks_exact(3)) {
            for f in [0, 1, 2, 4] {
                let jump = (t[0][f] - t[1][f]).abs().max((t[2][f] - t[1][f]).abs());
                worst[f] = worst[f].max(jump);
                let tol = if precision == "f64" { 1e-6 } else { 1e-5 };
                assert!(jump <= tol, "{precision} {} jumps by {jump} at {:?}", NAMES[f], c[1]);
            }
        }
        println!("{precision}: largest change for octaves n ± 1e-7, per function {worst:?}");
    }
}

#[test]
fn filtered_fbm_is_continuous_in_width_and_drops_fine_octaves() {
    let program = program();
    let mut rng = Rng(17);
    let mut args = Vec::new();
    for _ in 0..200 {
        let p = rng.point(-20.0, 20.0);
        // Widths at which log2(1 / width) passes a whole number of octaves, and just beside.
        for k in 1..8 {
            let w = 2f64.powi(-k);
            for width in [w * (1.0 - 1e-7), w, w * (1.0 + 1e-7)] {
                args.push(Args::new(p, 0.5, 2.0, 8.0, width));
            }
        }
    }
    let out = eval::<f64>(&program, &args);
    for (t, c) in out.chunks_exact(3).zip(args.chunks_exact(3)) {
        let jump = (t[0][2] - t[1][2]).abs().max((t[2][2] - t[1][2]).abs());
        assert!(jump <= 1e-6, "fbm_filtered jumps by {jump} at {:?}", c[1]);
        // At width 2^-k exactly, the filtered fBm is fBm with k octaves.
        let k = -c[1].width.log2();
        let whole = fractal::fbm(f64_exact, c[1].p, 0.5, 2.0, k);
        assert!(
            (t[1][2] - whole).abs() <= 1e-12,
            "width {}: {} against fbm with {k} octaves {whole}",
            c[1].width,
            t[1][2]
        );
    }
}

// ---- The multiplicative functions and distorted noise (multifractal, hetero_terrain,
// distnoise, distfbm). ----

const SHADER2: &str = "#include <fractal.sl>\n\
    surface t(varying float H = 0.25, lac = 2, oct = 4, offset = 0.8, d = 1) {\n\
        Ci = color(multifractal(P, H, lac, oct, offset), hetero_terrain(P, H, lac, oct, offset),\n\
                   distnoise(P, d));\n\
        Oi = color(distfbm(P, H, lac, oct, d), 0, 0);\n\
    }\n";

const NAMES2: [&str; 4] = ["multifractal", "hetero_terrain", "distnoise", "distfbm"];

/// One evaluation's inputs for SHADER2.
#[derive(Clone, Copy, Debug)]
struct Args2 {
    p: [f64; 3],
    h: f64,
    lac: f64,
    oct: f64,
    offset: f64,
    d: f64,
}

impl Args2 {
    fn to_f32(self) -> Args2 {
        let r = |x: f64| f64::from(x as f32);
        Args2 {
            p: self.p.map(r),
            h: r(self.h),
            lac: r(self.lac),
            oct: r(self.oct),
            offset: r(self.offset),
            d: r(self.d),
        }
    }

    /// The four functions by the port, and the multifractal's bound on its partial products.
    fn reference(&self, round: fractal::Round) -> ([f64; 4], f64) {
        let (m, bound) = fractal::multifractal(round, self.p, self.h, self.lac, self.oct, self.offset);
        (
            [
                m,
                fractal::hetero(round, self.p, self.h, self.lac, self.oct, self.offset),
                fractal::distnoise(round, self.p, self.d),
                fractal::distfbm(round, self.p, self.h, self.lac, self.oct, self.d),
            ],
            bound,
        )
    }
}

fn program2() -> CpuProgram {
    crate::support::compile(SHADER2, &Binding::default())
}

fn eval2<F: Real>(program: &CpuProgram, args: &[Args2]) -> Vec<[f64; 4]> {
    let mut e = Evaluator::<F>::new(program);
    let p: Vec<f64> = args.iter().flat_map(|a| a.p).collect();
    let col = |f: fn(&Args2) -> f64| -> Vec<f64> { args.iter().map(f).collect() };
    let (h, lac, oct, offset, d) =
        (col(|a| a.h), col(|a| a.lac), col(|a| a.oct), col(|a| a.offset), col(|a| a.d));
    let inputs: [(&str, &[f64]); 6] =
        [("P", &p), ("H", &h), ("lac", &lac), ("oct", &oct), ("offset", &offset), ("d", &d)];
    let out = e.eval_points(args.len(), &inputs, &["Ci", "Oi"]).expect("evaluation");
    (0..args.len()).map(|i| [out[0][3 * i], out[0][3 * i + 1], out[0][3 * i + 2], out[1][3 * i]]).collect()
}

/// Ordinary use: points within ±50, H in [0, 1.5], lacunarity 2 or in [1.5, 3], octaves in
/// [0, 10], offsets in [0, 1.2] (Musgrave: 0.8 for the multifractal), distortions in [0, 3].
fn ordinary_args2(count: usize, seed: u64) -> Vec<Args2> {
    let mut rng = Rng(seed);
    (0..count)
        .map(|i| Args2 {
            p: rng.point(-50.0, 50.0),
            h: rng.range(0.0, 1.5),
            lac: if i % 2 == 0 { 2.0 } else { rng.range(1.5, 3.0) },
            oct: rng.range(0.0, 10.0),
            offset: rng.range(0.0, 1.2),
            d: rng.range(0.0, 3.0),
        })
        .collect()
}

/// The extremes: points up to ±1e6 (and 1e30), octaves 0 and 30, H 0 and 2, lacunarity 1 and
/// 8, offsets 0, ±1e4, ±1e30, distortions 0, ±1e30.
fn extreme_args2() -> Vec<Args2> {
    let mut args = Vec::new();
    let points = [
        [0.0, 0.0, 0.0],
        [0.3, -0.7, 0.55],
        [1e4, -1e4, 1e4 + 0.37],
        [-1e6, 1e6 + 0.25, -1e6],
        [1e30, -1e30, 1e-30],
    ];
    for p in points {
        for oct in [0.0, 0.5, 30.0] {
            for h in [0.0, 2.0] {
                for lac in [1.0, 8.0] {
                    for (offset, d) in
                        [(0.0, 0.0), (1e4, 1e30), (-1e4, -1e30), (1e30, 1.0), (-1e30, 1e-30), (0.8, -1.0)]
                    {
                        args.push(Args2 { p, h, lac, oct, offset, d });
                    }
                }
            }
        }
    }
    args
}

#[test]
fn multiplicative_and_distorted_f64_match_the_port() {
    let program = program2();
    let mut args = ordinary_args2(2000, 21);
    args.extend(extreme_args2());
    let out = eval2::<f64>(&program, &args);
    let mut worst = [0.0f64; 4];
    for (a, o) in args.iter().zip(&out) {
        let (r, _) = a.reference(f64_exact);
        for f in 0..4 {
            // relative for the multifractal, whose values span many orders of magnitude
            let err = (o[f] - r[f]).abs() / r[f].abs().max(1.0);
            worst[f] = worst[f].max(err);
            assert!(err <= F64_TOL, "{}({a:?}) = {}, port {}", NAMES2[f], o[f], r[f]);
        }
    }
    println!("f64 mode, {} argument sets, largest (relative) error per function {worst:?}", args.len());
}

/// The f32 mode's tolerance F32_TOL, scaled: for the multifractal by the octave count times the
/// bound on its partial products (each factor's error, the noise's 2e-6 and the f32 pow's,
/// multiplies the other factors), for the terrain by 1 + |offset|, for distnoise by
/// 1 + |distortion| (the inner noises' error moves the outer noise's argument by the distortion
/// times it, and the noise's slope is up to about 3) and for distfbm by that times the octave
/// count. Measured largest scaled errors: multifractal 4.4e-7, hetero_terrain 1.3e-6, distnoise
/// 2.9e-6, distfbm 1.0e-6 (printed).
#[test]
fn multiplicative_and_distorted_f32_close_to_the_port() {
    let program = program2();
    let args = ordinary_args2(2000, 22);
    let out = eval2::<f32>(&program, &args);
    let mut worst = [0.0f64; 4];
    for (a, o) in args.iter().zip(&out) {
        let a = a.to_f32();
        let (r, bound) = a.reference(to_f32);
        let scales = [
            bound * a.oct.max(1.0),
            1.0 + a.offset.abs(),
            1.0 + a.d.abs(),
            (1.0 + a.d.abs()) * a.oct.max(1.0),
        ];
        for f in 0..4 {
            let err = (o[f] - r[f]).abs() / scales[f];
            worst[f] = worst[f].max(err);
            assert!(err <= F32_TOL, "{}({a:?}) = {}, port {}", NAMES2[f], o[f], r[f]);
        }
    }
    println!("f32 mode, {} argument sets, largest scaled error per function {worst:?}", args.len());
}

#[test]
fn multiplicative_and_distorted_extremes_are_finite() {
    let program = program2();
    let args = extreme_args2();
    let out64 = eval2::<f64>(&program, &args);
    let out32 = eval2::<f32>(&program, &args);
    for (i, a) in args.iter().enumerate() {
        for f in 0..4 {
            assert!(out64[i][f].is_finite(), "f64 {}({a:?}) = {}", NAMES2[f], out64[i][f]);
            assert!(out32[i][f].is_finite(), "f32 {}({a:?}) = {}", NAMES2[f], out32[i][f]);
        }
        let bound = 31.0 * (a.offset.abs().min(1e4) + 1.0);
        assert!(out64[i][1].abs() <= bound && out32[i][1].abs() <= bound * 1.0001, "terrain bound at {a:?}");
        assert!(
            out64[i][0].abs() <= 1e30 && out32[i][0].abs() <= f64::from(1e30f32),
            "product bound at {a:?}"
        );
        if a.oct == 0.0 {
            assert_eq!([out64[i][0], out64[i][1], out64[i][3]], [1.0, 0.0, 0.0], "octaves 0: {a:?}");
        }
    }
    println!("{} extreme argument sets finite in f64 and f32", args.len());
}

#[test]
fn multiplicative_and_distorted_statistics() {
    let program = program2();
    let mut rng = Rng(23);
    let points: Vec<[f64; 3]> = (0..4000).map(|_| rng.point(-100.0, 100.0)).collect();
    // The multifractal at Musgrave's H 0.25, offset 0.8: its mean converges to 0 with the
    // octaves ("it will either converge to zero or diverge to infinity", L10228).
    let mut means = Vec::new();
    for oct in [2.0, 4.0, 6.0, 8.0, 12.0] {
        let args: Vec<Args2> =
            points.iter().map(|&p| Args2 { p, h: 0.25, lac: 2.0, oct, offset: 0.8, d: 0.0 }).collect();
        let out = eval2::<f64>(&program, &args);
        means.push(out.iter().map(|o| o[0]).sum::<f64>() / out.len() as f64);
        // distortion 0: distnoise is snoise3 itself
        for (a, o) in args.iter().zip(&out) {
            assert_eq!(o[2], fractal::snoise3(a.p), "distnoise(p, 0) at {:?}", a.p);
        }
    }
    println!("multifractal(H 0.25, offset 0.8) mean at 2, 4, 6, 8, 12 octaves: {means:?}");
    for w in means.windows(2) {
        assert!(w[1] < w[0], "the mean decreases with octaves: {means:?}");
    }
    assert!(means[4] < 0.05 * means[0]);
    // The terrain: high areas are rougher than low ones. The detail added by octaves 3..8 is
    // smaller where the 2-octave terrain is near sea level.
    let at = |oct: f64| -> Vec<[f64; 4]> {
        let args: Vec<Args2> =
            points.iter().map(|&p| Args2 { p, h: 0.25, lac: 2.0, oct, offset: 0.3, d: 1.0 }).collect();
        eval2::<f64>(&program, &args)
    };
    let (low, high) = (at(2.0), at(8.0));
    let (mut near, mut far) = ((0.0, 0), (0.0, 0));
    for (l, h) in low.iter().zip(&high) {
        let detail = (h[1] - l[1]).abs();
        if l[1].abs() < 0.1 {
            near = (near.0 + detail, near.1 + 1);
        } else if l[1].abs() > 0.6 {
            far = (far.0 + detail, far.1 + 1);
        }
    }
    let (near, far) = (near.0 / near.1 as f64, far.0 / far.1 as f64);
    println!("hetero_terrain: mean detail of octaves 3-8 near sea level {near:.4}, at altitude {far:.4}");
    assert!(near < 0.5 * far);
    // distnoise and distfbm stay in [-1, 1] and in fbm's range
    for o in &high {
        assert!(o[2].abs() <= 1.0);
    }
}

#[test]
fn terrain_and_distorted_fbm_are_continuous_in_octaves() {
    let program = program2();
    let mut rng = Rng(24);
    let eps = 1e-7;
    let mut args = Vec::new();
    for _ in 0..200 {
        let p = rng.point(-20.0, 20.0);
        for n in 0..10 {
            let n = f64::from(n);
            for oct in [n - eps, n, n + eps] {
                args.push(Args2 { p, h: 0.5, lac: 2.0, oct: oct.max(0.0), offset: 0.7, d: 1.0 });
            }
        }
    }
    let out = eval2::<f64>(&program, &args);
    let mut worst = [0.0f64; 4];
    for (t, c) in out.chunks_exact(3).zip(args.chunks_exact(3)) {
        for f in [1, 3] {
            let jump = (t[0][f] - t[1][f]).abs().max((t[2][f] - t[1][f]).abs());
            worst[f] = worst[f].max(jump);
            assert!(jump <= 1e-6, "{} jumps by {jump} at {:?}", NAMES2[f], c[1]);
        }
    }
    println!("largest change for octaves n ± 1e-7: hetero_terrain {}, distfbm {}", worst[1], worst[3]);
}
