//! The standard library's lattice module (`compiler/stdlib/lattice.sl`): the PCG lattice hash and Peachey's
//! lattice noises, on the interpreter (f32 and f64) and on the GPU, against an independent Rust
//! port written here from the definitions (module `port`: Jarzynski & Olano's `pcg`, Peachey's
//! formulas, T&M L2246-2658).
//!
//! Run with `--nocapture` to see the measured numbers (they are quoted in docs/stdlib/lattice.md).

use crate::support;

use crate::support::{Rng, assert_finite, extremes, worst};

/// The definitions, in f64, written from the sources (not from lattice.sl).
mod port {
    pub use super::support::lattice_hash::{cell, hash, pcg, unit};

    pub fn signed(h: u32) -> f64 {
        (2.0 * f64::from(h >> 9) + 1.0) / 8_388_608.0 - 1.0
    }

    pub fn lcg(s: u32) -> u32 {
        s.wrapping_mul(1_402_024_253).wrapping_add(586_950_981)
    }

    fn split(p: [f64; 3]) -> ([i32; 3], [f64; 3]) {
        let c = p.map(f64::floor);
        ([cell(c[0]), cell(c[1]), cell(c[2])], [p[0] - c[0], p[1] - c[1], p[2] - c[2]])
    }

    fn value(i: [i32; 3], seed: i32) -> f64 {
        signed(hash(&i, seed))
    }

    /// Catmull-Rom through k on the span k[1]..k[2] (Peachey's basis matrix, L1390-1408).
    pub fn catrom4(t: f64, k: [f64; 4]) -> f64 {
        let m = [[-0.5, 1.5, -1.5, 0.5], [1.0, -2.5, 2.0, -0.5], [-0.5, 0.0, 0.5, 0.0], [0.0, 1.0, 0.0, 0.0]];
        let c: Vec<f64> = m.iter().map(|row| row.iter().zip(&k).map(|(a, b)| a * b).sum()).collect();
        ((c[0] * t + c[1]) * t + c[2]) * t + c[3]
    }

    /// The radial Catmull-Rom filter of a squared distance (L2505-2530, without the table).
    pub fn catrom2(d2: f64) -> f64 {
        let x = d2.sqrt();
        if x < 1.0 {
            1.0 - 2.5 * x * x + 1.5 * x * x * x
        } else if x < 2.0 {
            2.0 - 4.0 * x + 2.5 * x * x - 0.5 * x * x * x
        } else {
            0.0
        }
    }

    pub fn vnoise(p: [f64; 3], seed: i32) -> f64 {
        let (i, f) = split(p);
        let mut zk = [0.0; 4];
        for (k, z) in zk.iter_mut().enumerate() {
            let mut yk = [0.0; 4];
            for (j, y) in yk.iter_mut().enumerate() {
                let xk = [0, 1, 2, 3]
                    .map(|a| value([i[0] + a - 1, i[1] + j as i32 - 1, i[2] + k as i32 - 1], seed));
                *y = catrom4(f[0], xk);
            }
            *z = catrom4(f[1], yk);
        }
        catrom4(f[2], zk)
    }

    fn lerp(t: f64, a: f64, b: f64) -> f64 {
        a + t * (b - a)
    }

    /// Trilinear interpolation of corner values `v(dx, dy, dz)` with weights w.
    fn trilinear(w: [f64; 3], v: impl Fn(i32, i32, i32) -> f64) -> f64 {
        let x = |dy, dz| lerp(w[0], v(0, dy, dz), v(1, dy, dz));
        lerp(w[2], lerp(w[1], x(0, 0), x(1, 0)), lerp(w[1], x(0, 1), x(1, 1)))
    }

    pub fn vnoise_linear(p: [f64; 3], seed: i32) -> f64 {
        let (i, f) = split(p);
        trilinear(f, |a, b, c| value([i[0] + a, i[1] + b, i[2] + c], seed))
    }

    /// The unit gradient of a lattice point: uniform on the sphere (Peachey L2350-2380).
    pub fn gradient(h: u32) -> [f64; 3] {
        let h1 = pcg(h);
        let z = 1.0 - 2.0 * unit(h1);
        let r = (1.0 - z * z).max(0.0).sqrt();
        let theta = 2.0 * std::f64::consts::PI * unit(pcg(h1)) - std::f64::consts::PI;
        [r * theta.cos(), r * theta.sin(), z]
    }

    pub fn gnoise(p: [f64; 3], seed: i32) -> f64 {
        let (i, f) = split(p);
        let w = f.map(|t| t * t * (3.0 - 2.0 * t));
        trilinear(w, |a, b, c| {
            let g = gradient(hash(&[i[0] + a, i[1] + b, i[2] + c], seed));
            g[0] * (f[0] - f64::from(a)) + g[1] * (f[1] - f64::from(b)) + g[2] * (f[2] - f64::from(c))
        })
    }

    pub fn vgnoise(p: [f64; 3], w: f64, seed: i32) -> f64 {
        let k = w.clamp(0.0, 1.0);
        (1.0 - k) * gnoise(p, seed + 1) + k * vnoise(p, seed)
    }

    pub fn vcnoise(p: [f64; 3], seed: i32) -> f64 {
        let (i, f) = split(p);
        let mut sum = 0.0;
        for k in -1..=2 {
            for j in -1..=2 {
                for a in -1..=2 {
                    let d = [f64::from(a) - f[0], f64::from(j) - f[1], f64::from(k) - f[2]];
                    sum += value([i[0] + a, i[1] + j, i[2] + k], seed)
                        * catrom2(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                }
            }
        }
        sum
    }

    pub fn scnoise(p: [f64; 3], seed: i32) -> f64 {
        let (i, f) = split(p);
        let mut sum = 0.0;
        for k in -2..=2 {
            for j in -2..=2 {
                for a in -2..=2 {
                    let mut h = hash(&[i[0] + a, i[1] + j, i[2] + k], seed);
                    for _ in 0..3 {
                        let mut draw = || {
                            h = lcg(h);
                            h
                        };
                        let px = f64::from(a) + unit(draw());
                        let py = f64::from(j) + unit(draw());
                        let pz = f64::from(k) + unit(draw());
                        let amp = signed(draw());
                        let d = [f[0] - px, f[1] - py, f[2] - pz];
                        sum += catrom2(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * amp;
                    }
                }
            }
        }
        sum / 3.0
    }
}

/// The noises of lattice.sl: name, the call in the language, the port.
type Port = fn([f64; 3]) -> f64;
const NOISES: &[(&str, &str, Port)] = &[
    ("vnoise", "vnoise(p)", |p| port::vnoise(p, 665)),
    ("vnoise_linear", "vnoise_linear(p)", |p| port::vnoise_linear(p, 665)),
    ("gnoise", "gnoise(p)", |p| port::gnoise(p, 665)),
    ("vgnoise", "vgnoise(p)", |p| port::vgnoise(p, 0.5, 665)),
    ("vcnoise", "vcnoise(p)", |p| port::vcnoise(p, 665)),
    ("scnoise", "scnoise(p)", |p| port::scnoise(p, 665)),
];

/// Whether a noise uses sin/cos (so the GPU is not bit-identical).
fn uses_trig(name: &str) -> bool {
    name == "gnoise" || name == "vgnoise"
}

/// How many of `n` sample points a test uses for a noise: sparse convolution noise sums 375
/// filter terms per point, so it gets a quarter (the interpreter runs debug builds in tests).
fn budget(name: &str, n: usize) -> usize {
    if name == "scnoise" { n / 4 } else { n }
}

fn noise_program(call: &str) -> support::Program {
    support::program(&format!(
        "#include <lattice.sl>\n\
         surface t(varying float x = 0, y = 0, z = 0) {{ point p = point(x, y, z); Ci = {call}; }}\n"
    ))
}

/// Columns x, y, z of the points.
fn columns(points: &[[f64; 3]]) -> [Vec<f64>; 3] {
    [0, 1, 2].map(|c| points.iter().map(|p| p[c]).collect())
}

/// The first component of Ci at every point, in precision F.
fn eval<F: patina_compiler::backend::cpu::scalar::Real>(
    program: &support::Program,
    points: &[[f64; 3]],
) -> Vec<f64> {
    let [x, y, z] = columns(points);
    let out = program.cpu::<F>(points.len(), &[("x", &x), ("y", &y), ("z", &z)], &["Ci"]);
    out[0].chunks_exact(3).map(|c| c[0]).collect()
}

fn eval_gpu(gpu: &patina_runtime::gpu::Gpu, program: &support::Program, points: &[[f64; 3]]) -> Vec<f64> {
    let [x, y, z] = columns(points);
    let out = program.gpu(gpu, points.len(), &[("x", &x), ("y", &y), ("z", &z)], &["Ci"]);
    out[0].chunks_exact(3).map(|c| c[0]).collect()
}

fn to_f32(p: [f64; 3]) -> [f64; 3] {
    p.map(|x| f64::from(x as f32))
}

/// Random points in a few ranges, including negative ones and cells far from the origin.
fn sample_points(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|i| match i % 3 {
            0 => rng.point(-3.0, 3.0),
            1 => rng.point(-300.0, 300.0),
            _ => rng.point(-1e5, 1e5),
        })
        .collect()
}

// -------------------------------------------------------------------------------------------
// The hash

const HASH_SHADER: &str = "#include <lattice.sl>\n\
    surface t(varying float x = 0, y = 0, z = 0, w = 0, s = 0;\n\
              output varying float h4hi = 0, h4lo = 0) {\n\
        int ix = lattice_cell(floor(x)), iy = lattice_cell(floor(y)), iz = lattice_cell(floor(z));\n\
        int iw = lattice_cell(floor(w)), is = int(s);\n\
        uint h1 = lattice_hash1(ix, is), h2 = lattice_hash2(ix, iy, is), h3 = lattice_hash3(ix, iy, iz, is);\n\
        uint h4 = lattice_hash4(ix, iy, iz, iw, is);\n\
        Ci = color(float(h1 >> 16u), float(h1 & 65535u), float(h2 >> 16u));\n\
        Oi = color(float(h2 & 65535u), float(h3 >> 16u), float(h3 & 65535u));\n\
        h4hi = float(h4 >> 16u); h4lo = float(h4 & 65535u);\n\
    }\n";

/// Integer-valued f32 coordinates: small, negative, around +-2^24 and +-2^31, huge.
fn hash_inputs() -> Vec<[f64; 5]> {
    let mut rng = Rng(11);
    let specials = [
        0.0,
        1.0,
        -1.0,
        2.0,
        -2.0,
        255.0,
        256.0,
        -256.0,
        65535.0,
        65536.0,
        16_777_216.0,
        -16_777_216.0,
        2_147_483_520.0,
        -2_147_483_648.0,
        2_147_483_648.0,
        4_294_967_296.0,
        -4_294_967_296.0,
        1e9,
        -1e9,
        1e10,
        1e20,
        -1e30,
        1e30,
    ];
    let mut v = Vec::new();
    for _ in 0..2500 {
        let mut c = || -> f64 {
            match rng.next() % 4 {
                0 => (rng.range(-100.0, 100.0)).floor(),
                1 => f64::from((rng.range(-3e9, 3e9)) as f32).floor(),
                2 => specials[(rng.next() % specials.len() as u64) as usize],
                _ => f64::from(rng.range(-1e12, 1e12) as f32).floor(),
            }
        };
        let p = [c(), c(), c(), c(), (rng.next() % 2000) as f64 - 1000.0];
        // Every input is an f32, so that all three evaluations see the same integers.
        v.push(p.map(|x| f64::from(x as f32)));
    }
    v
}

/// The four hashes of one input row, from the port, as the shader splits them.
fn hash_expected(i: &[f64; 5]) -> [f64; 8] {
    let c = [port::cell(i[0]), port::cell(i[1]), port::cell(i[2]), port::cell(i[3])];
    let s = i[4] as i32;
    let h = [port::hash(&c[..1], s), port::hash(&c[..2], s), port::hash(&c[..3], s), port::hash(&c, s)];
    let split = |h: u32| [f64::from(h >> 16), f64::from(h & 65535)];
    let [a, b, c, d] = h.map(split);
    [a[0], a[1], b[0], b[1], c[0], c[1], d[0], d[1]]
}

fn hash_columns(inputs: &[[f64; 5]]) -> [Vec<f64>; 5] {
    [0, 1, 2, 3, 4].map(|c| inputs.iter().map(|p| p[c]).collect())
}

/// Reassembles the shader's outputs into rows of 8 halves.
fn hash_rows(out: &[Vec<f64>]) -> Vec<[f64; 8]> {
    (0..out[0].len() / 3)
        .map(|i| {
            [
                out[0][3 * i],
                out[0][3 * i + 1],
                out[0][3 * i + 2],
                out[1][3 * i],
                out[1][3 * i + 1],
                out[1][3 * i + 2],
                out[2][i],
                out[3][i],
            ]
        })
        .collect()
}

#[test]
fn hash_matches_the_pcg_definition_on_both_backends_bit_for_bit() {
    let program = support::program(HASH_SHADER);
    let inputs = hash_inputs();
    let [x, y, z, w, s] = hash_columns(&inputs);
    let cols = [("x", &x[..]), ("y", &y[..]), ("z", &z[..]), ("w", &w[..]), ("s", &s[..])];
    let outputs = ["Ci", "Oi", "h4hi", "h4lo"];
    let expected: Vec<[f64; 8]> = inputs.iter().map(hash_expected).collect();
    // Known values of the port itself (computed by hand from the definition with Python).
    assert_eq!(port::pcg(3), (32526 << 16) | 63164);
    assert_eq!(port::pcg(-5i32 as u32), (46190 << 16) | 3564);
    let f64_rows = hash_rows(&program.cpu::<f64>(inputs.len(), &cols, &outputs));
    let f32_rows = hash_rows(&program.cpu::<f32>(inputs.len(), &cols, &outputs));
    for (i, e) in expected.iter().enumerate() {
        assert_eq!(&f64_rows[i], e, "f64 hash of {:?}", inputs[i]);
        assert_eq!(&f32_rows[i], e, "f32 hash of {:?}", inputs[i]);
    }
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let gpu_rows = hash_rows(&program.gpu(gpu, inputs.len(), &cols, &outputs));
    for (i, e) in expected.iter().enumerate() {
        assert_eq!(&gpu_rows[i], e, "GPU hash of {:?}", inputs[i]);
    }
    println!("hash: {} inputs x 4 hashes identical to the port on f64, f32 and the GPU", inputs.len());
}

#[test]
fn hash_values_are_uniform_and_uncorrelated_between_neighbours() {
    // lattice_unit over a 64 x 64 block of consecutive cells and 4 seeds: chi-square over 32 bins,
    // the mean, and the correlation between x-neighbours (computed from the port, which the test
    // above proves bit-identical to the language's hash).
    let mut units = Vec::new();
    let mut pairs = Vec::new();
    for seed in 0..4 {
        for y in -32..32 {
            for x in -32..32 {
                let u = port::unit(port::hash(&[x, y], seed));
                let v = port::unit(port::hash(&[x + 1, y], seed));
                units.push(u);
                pairs.push((u, v));
            }
        }
    }
    let n = units.len() as f64;
    let mut bins = [0.0; 32];
    for &u in &units {
        bins[(u * 32.0) as usize] += 1.0;
    }
    let e = n / 32.0;
    let chi2: f64 = bins.iter().map(|b| (b - e) * (b - e) / e).sum();
    let mean = units.iter().sum::<f64>() / n;
    let cov = pairs.iter().map(|(u, v)| (u - 0.5) * (v - 0.5)).sum::<f64>() / n;
    let corr = cov / (1.0 / 12.0);
    println!("hash: {n} units, chi2(31 dof) = {chi2:.1}, mean {mean:.4}, neighbour correlation {corr:.4}");
    // 31 degrees of freedom: the 99.9% point is 61.1.
    assert!(chi2 < 61.1, "chi2 {chi2}");
    assert!((mean - 0.5).abs() < 0.01);
    assert!(corr.abs() < 0.03);
    // Every hash to float conversion is exact and in range.
    for h in [0u32, 1, 255, 256, 511, 512, u32::MAX, u32::MAX - 255, 0x8000_0000] {
        let (u, s) = (port::unit(h), port::signed(h));
        assert!((0.0..1.0).contains(&u) && s > -1.0 && s < 1.0);
        assert_eq!(f64::from(u as f32), u);
        assert_eq!(f64::from(s as f32), s);
    }
}

// -------------------------------------------------------------------------------------------
// The noises against the port

#[test]
fn noises_match_the_port_in_f64_and_f32() {
    for &(name, call, reference) in NOISES {
        let points = sample_points(budget(name, 384), 3);
        let rounded: Vec<[f64; 3]> = points.iter().map(|&p| to_f32(p)).collect();
        let program = noise_program(call);
        let expected: Vec<f64> = points.iter().map(|&p| reference(p)).collect();
        let (e64, at64) = worst(&eval::<f64>(&program, &points), &expected);
        let expected32: Vec<f64> = rounded.iter().map(|&p| reference(p)).collect();
        let (e32, at32) = worst(&eval::<f32>(&program, &rounded), &expected32);
        println!(
            "{name}: f64 vs port {e64:.2e} (at {:?}), f32 vs port {e32:.2e} (at {:?})",
            points[at64], rounded[at32]
        );
        assert!(e64 < 1e-12, "{name}: f64 differs from the port by {e64} at {:?}", points[at64]);
        assert!(e32 < 2e-5, "{name}: f32 differs from the port by {e32} at {:?}", rounded[at32]);
    }
}

#[test]
fn value_noise_interpolates_its_lattice_values_and_gradient_noise_vanishes_there() {
    let mut rng = Rng(5);
    let lattice: Vec<[f64; 3]> = (0..400).map(|_| rng.point(-1000.0, 1000.0).map(f64::floor)).collect();
    let values: Vec<f64> =
        lattice.iter().map(|p| port::signed(port::hash(&p.map(|c| c as i32), 665))).collect();
    for (name, call) in [("vnoise", "vnoise(p)"), ("vnoise_linear", "vnoise_linear(p)")] {
        let program = noise_program(call);
        for got in [eval::<f64>(&program, &lattice), eval::<f32>(&program, &lattice)] {
            assert_eq!(got, values, "{name} at lattice points");
        }
    }
    let program = noise_program("gnoise(p)");
    assert!(eval::<f32>(&program, &lattice).iter().all(|&v| v == 0.0), "gnoise is 0 at lattice points");
    // The lattice values are uniform in (-1, 1): chi-square over 16 bins of 4096 lattice values
    // read through vnoise itself (f64 mode), mean 0, variance 1/3.
    let grid: Vec<[f64; 3]> = (0..4096)
        .map(|i| [f64::from(i % 16) - 8.0, f64::from((i / 16) % 16), f64::from(i / 256) * 7.0])
        .collect();
    let got = eval::<f64>(&noise_program("vnoise(p)"), &grid);
    let n = got.len() as f64;
    let mut bins = [0.0; 16];
    for v in &got {
        bins[((v + 1.0) * 8.0) as usize] += 1.0;
    }
    let chi2: f64 = bins.iter().map(|b| (b - n / 16.0).powi(2) / (n / 16.0)).sum();
    let mean = got.iter().sum::<f64>() / n;
    let var = got.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    println!(
        "vnoise lattice values: chi2(15 dof) = {chi2:.1}, mean {mean:.4}, variance {var:.4} (uniform: 1/3)"
    );
    assert!(chi2 < 37.7, "chi2 {chi2}"); // 99.9% point of chi2 with 15 dof
    assert!(mean.abs() < 0.03 && (var - 1.0 / 3.0).abs() < 0.02);
}

/// Mean, variance, minimum and maximum of a noise over random points (f64 mode).
fn statistics(name: &str, values: &[f64]) -> (f64, f64, f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    println!("{name}: mean {mean:.4}, variance {var:.4}, range [{lo:.4}, {hi:.4}] over {n} points");
    (mean, var, lo, hi)
}

#[test]
fn noise_statistics() {
    let mut rng = Rng(17);
    let all: Vec<[f64; 3]> = (0..2048).map(|_| rng.point(-500.0, 500.0)).collect();
    // (name, call, |mean| bound, variance range, documented range)
    type Case<'a> = (&'a str, &'a str, f64, (f64, f64), (f64, f64));
    let cases: &[Case] = &[
        ("vnoise", "vnoise(p)", 0.03, (0.10, 0.30), (-1.953, 1.953)),
        ("vnoise_linear", "vnoise_linear(p)", 0.03, (0.03, 0.15), (-1.0, 1.0)),
        ("gnoise", "gnoise(p)", 0.03, (0.02, 0.12), (-1.0, 1.0)),
        ("vgnoise", "vgnoise(p)", 0.03, (0.02, 0.12), (-1.5, 1.5)),
        ("vcnoise", "vcnoise(p)", 0.03, (0.10, 0.50), (-3.0, 3.0)),
        ("scnoise", "scnoise(p)", 0.03, (0.02, 0.30), (-3.0, 3.0)),
    ];
    for &(name, call, mean_bound, (vlo, vhi), (lo, hi)) in cases {
        let values = eval::<f64>(&noise_program(call), &all[..budget(name, all.len())]);
        let (mean, var, min, max) = statistics(name, &values);
        assert!(mean.abs() < mean_bound, "{name} mean {mean}");
        assert!(var > vlo && var < vhi, "{name} variance {var}");
        assert!(min >= lo && max <= hi, "{name} range [{min}, {max}]");
    }
}

#[test]
fn continuity_across_cell_faces() {
    // Across x = integer faces: the value jump (C0) and the jump of the one-sided x-derivative
    // (C1), by differences of step h = 1e-4 on each side, in f64 mode. C1 noises: the derivative
    // jump must be O(h) (bounded by 1e-2); vnoise_linear is C0 only (its derivative jumps).
    let mut rng = Rng(23);
    let faces: Vec<[f64; 3]> = (0..128)
        .map(|_| [rng.range(-50.0, 50.0).round(), rng.range(-50.0, 50.0), rng.range(-50.0, 50.0)])
        .collect();
    let h = 1e-4;
    let offsets = [-2.0 * h, -h, 0.0, h, 2.0 * h];
    for &(name, call, _) in NOISES {
        let program = noise_program(call);
        let points: Vec<[f64; 3]> =
            faces.iter().flat_map(|p| offsets.map(|o| [p[0] + o, p[1], p[2]])).collect();
        let v = eval::<f64>(&program, &points);
        let (mut jump, mut djump) = (0.0f64, 0.0f64);
        for s in v.chunks_exact(5) {
            // Values just left (extrapolated to the face) and at the face.
            let left = 2.0 * s[1] - s[0];
            jump = jump.max((left - s[2]).abs());
            let dl = (s[1] - s[0]) / h;
            let dr = (s[4] - s[3]) / h;
            djump = djump.max((dl - dr).abs());
        }
        println!("{name}: across cell faces, value jump {jump:.2e}, derivative jump {djump:.2e}");
        assert!(jump < 1e-3, "{name} is discontinuous: {jump}");
        if name == "vnoise_linear" {
            assert!(djump > 1e-2, "vnoise_linear's derivative should jump");
        } else {
            assert!(djump < 1e-2, "{name} is not C1: {djump}");
        }
    }
}

// -------------------------------------------------------------------------------------------
// Extremes, the GPU, large coordinates

fn extreme_points() -> Vec<[f64; 3]> {
    let e = extremes();
    let mut v = Vec::new();
    for &x in &e {
        for &y in &e {
            for &z in &e {
                v.push([x, y, z]);
            }
        }
    }
    v
}

/// GPU tolerance per noise (absolute, against the f32 interpreter): 0 where only exact operations
/// are used; gnoise and vgnoise use sin and cos (lavapipe within 6e-8 on [-pi, pi]).
fn gpu_tolerance(name: &str) -> f64 {
    if uses_trig(name) { 2e-6 } else { 0.0 }
}

#[test]
fn extreme_inputs_give_finite_results_and_the_gpu_agrees() {
    // The extreme coordinates: each one on the diagonal and on each axis with the others 0 and
    // 0.5, then combinations of three chosen at random (all 18^3 would make the test slow on the
    // debug interpreter), and normal points.
    let e = extremes();
    let all = extreme_points();
    let gpu = patina_runtime::gpu::for_tests();
    for &(name, call, _) in NOISES {
        let mut rng = Rng(31);
        let mut extreme: Vec<[f64; 3]> = Vec::new();
        for &x in &e {
            extreme.extend([[x, x, x], [x, 0.0, 0.5], [0.5, x, 0.0], [0.0, 0.5, x], [x, -x, x]]);
        }
        extreme.extend((0..budget(name, 1024)).map(|_| all[(rng.next() % all.len() as u64) as usize]));
        let mut normal: Vec<[f64; 3]> = (0..budget(name, 512)).map(|_| rng.point(-100.0, 100.0)).collect();
        normal.extend(sample_points(budget(name, 384), 37));
        let program = noise_program(call);
        for points in [&extreme, &normal] {
            let r32 = eval::<f32>(&program, points);
            let r64 = eval::<f64>(&program, points);
            assert_finite(&format!("{name} (f32)"), &r32, 1);
            assert_finite(&format!("{name} (f64)"), &r64, 1);
            if let Some(gpu) = &gpu {
                let g = eval_gpu(gpu, &program, points);
                assert_finite(&format!("{name} (GPU)"), &g, 1);
                let (d, at) = worst(&g, &r32);
                println!(
                    "{name}: GPU vs f32 interpreter, {} points: largest difference {d:.2e}",
                    points.len()
                );
                assert!(d <= gpu_tolerance(name), "{name}: GPU differs by {d} at {:?}", points[at]);
            }
        }
    }
}

/// The accuracy sweep at offsets 2^k (k = 0..24): for each noise, the largest difference between
/// the f32 and the f64 interpreter (a) at the same f32 coordinates (the algorithm's own error) and
/// (b) at the exact f64 coordinates (adding the rounding of the coordinates to f32).
fn large_coordinate_sweep(name: &str, program: &support::Program) -> Vec<(i32, f64, f64)> {
    const PER_OFFSET: usize = 10;
    let mut rng = Rng(41);
    let mut exact = Vec::new();
    for k in 0..=24 {
        let offset = 2f64.powi(k);
        for i in 0..PER_OFFSET {
            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
            exact.push([0, 1, 2].map(|_| sign * (offset + rng.unit())));
        }
    }
    let rounded: Vec<[f64; 3]> = exact.iter().map(|&p| to_f32(p)).collect();
    // One evaluation of every offset at once per mode (the interpreter runs batches of 128).
    let same32 = eval::<f32>(program, &rounded);
    let same64 = eval::<f64>(program, &rounded);
    let exact32 = eval::<f32>(program, &exact);
    let exact64 = eval::<f64>(program, &exact);
    let rows: Vec<(i32, f64, f64)> = (0..=24)
        .map(|k| {
            let r = k as usize * PER_OFFSET..(k as usize + 1) * PER_OFFSET;
            let (same, _) = worst(&same32[r.clone()], &same64[r.clone()]);
            let (total, _) = worst(&exact32[r.clone()], &exact64[r]);
            (k, same, total)
        })
        .collect();
    println!("{name}: offset 2^k | f32 vs f64, same coordinates | f32 vs f64, exact coordinates");
    for (k, a, b) in &rows {
        println!("  2^{k:<2} | {a:.2e} | {b:.2e}");
    }
    rows
}

/// The last k for which every offset up to 2^k stays within 1e-3.
fn accurate_up_to(rows: &[(i32, f64, f64)], pick: fn(&(i32, f64, f64)) -> f64) -> i32 {
    rows.iter().take_while(|r| pick(r) <= 1e-3).last().map_or(-1, |r| r.0)
}

#[test]
fn large_coordinates_table() {
    // The documented thresholds (docs/stdlib/lattice.md): at the same f32 coordinates every noise
    // stays within 1e-3 of f64 at every offset up to 2^24; at exact coordinates the rounding of
    // the coordinate to f32 (up to 2^(k-24)) times the noise's slope dominates.
    for &(name, call, _) in NOISES {
        let rows = large_coordinate_sweep(name, &noise_program(call));
        let same = accurate_up_to(&rows, |r| r.1);
        let total = accurate_up_to(&rows, |r| r.2);
        println!("{name}: within 1e-3 up to 2^{same} (same coordinates), 2^{total} (exact coordinates)");
        assert_eq!(same, 24, "{name}: the f32 algorithm loses accuracy at large coordinates");
        assert!(total >= 12, "{name}: accurate only up to 2^{total} at exact coordinates");
    }
}

#[test]
fn catmull_rom_filter_matches_its_formula_and_is_bit_identical_on_the_gpu() {
    // 4096 squared distances over [0, 4.2], the filter against the formula (f64 port) and the
    // GPU against the f32 interpreter, bit for bit. (Written with sqrt(d2) * sqrt(d2) for x^2,
    // the GPU differed by an ulp at 47% of the points: lavapipe folds the product into d2.)
    let program = support::program(
        "#include <lattice.sl>\n surface t(varying float x = 0, y = 0, z = 0) { Ci = color(lattice_catrom2(x), 0, 0); }\n",
    );
    let mut rng = Rng(3);
    let points: Vec<[f64; 3]> = (0..4096).map(|_| [rng.range(0.0, 4.2), 0.0, 0.0]).collect();
    let expected: Vec<f64> = points.iter().map(|p| port::catrom2(p[0])).collect();
    let (d64, _) = worst(&eval::<f64>(&program, &points), &expected);
    let r32 = eval::<f32>(&program, &points);
    let (d32, _) = worst(&r32, &expected);
    println!("catrom2: f64 vs formula {d64:.2e}, f32 vs formula {d32:.2e}");
    assert!(d64 < 1e-14 && d32 < 1e-6);
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let (dg, at) = worst(&eval_gpu(gpu, &program, &points), &r32);
    assert_eq!(dg, 0.0, "GPU differs at d2 = {}", points[at][0]);
}
