//! The standard library's cellular module (`compiler/stdlib/cellular.sl`): RenderMan's cellnoise and
//! Worley's cellular basis F1-F4, on the interpreter (f32 and f64) and on the GPU, against an
//! independent Rust port written here from the definitions (module `port`: a cube's population
//! from Worley's table, its points from his LCG, T&M L4093-4380, found by sorting every point of
//! the 27 (or 125) cubes around p, not by his pruned search).
//!
//! Run with `--nocapture` to see the measured numbers (they are quoted in docs/stdlib/cellular.md).

use crate::support;

use crate::support::{Rng, assert_finite, extremes, worst};

mod port {
    pub use super::support::lattice_hash::{cell, hash, unit};

    pub fn cellnoise(coords: &[f64], seed: i32) -> f64 {
        let c: Vec<i32> = coords.iter().map(|x| cell(x.floor())).collect();
        unit(hash(&c, seed))
    }

    /// Worley's table (L4122-4133, with the entry the seed text lost restored).
    pub const POISSON: [u32; 256] = [
        4, 3, 1, 1, 1, 2, 4, 2, 2, 2, 5, 1, 0, 2, 1, 2, 2, 0, 4, 3, 2, 1, 2, 1, 3, 2, 2, 4, 2, 2, 5, 1, 2, 3,
        2, 2, 2, 2, 2, 3, 2, 4, 2, 5, 3, 2, 2, 2, 5, 3, 3, 5, 2, 1, 3, 3, 4, 4, 2, 3, 0, 4, 2, 2, 2, 1, 3, 2,
        2, 2, 3, 3, 3, 1, 2, 0, 2, 1, 1, 2, 2, 2, 2, 5, 3, 2, 3, 2, 3, 2, 2, 1, 0, 2, 1, 1, 2, 1, 2, 2, 1, 3,
        4, 2, 2, 2, 5, 4, 2, 4, 2, 2, 5, 4, 3, 2, 2, 5, 4, 3, 3, 3, 5, 2, 2, 2, 2, 2, 3, 1, 1, 4, 2, 1, 3, 3,
        4, 3, 2, 4, 3, 3, 3, 4, 5, 1, 4, 2, 4, 3, 1, 2, 3, 5, 3, 2, 1, 3, 1, 3, 3, 3, 2, 3, 1, 5, 5, 4, 2, 2,
        4, 1, 3, 4, 1, 5, 3, 3, 5, 3, 4, 3, 2, 2, 1, 1, 1, 1, 1, 2, 4, 5, 4, 5, 4, 2, 1, 5, 1, 1, 2, 3, 3, 3,
        2, 5, 2, 3, 3, 2, 0, 2, 1, 1, 4, 2, 1, 3, 2, 1, 2, 2, 3, 2, 5, 5, 3, 4, 5, 5, 2, 4, 4, 5, 3, 2, 2, 2,
        1, 4, 2, 3, 3, 4, 2, 5, 4, 2, 4, 2, 2, 2, 4, 5, 3, 2,
    ];

    /// DENSITY_ADJUSTMENT as the stdlib rounds it (26093 / 65536; Worley's 0.398150).
    pub const DA: f64 = 26093.0 / 65536.0;

    fn lcg(s: u32) -> u32 {
        s.wrapping_mul(1_402_024_253).wrapping_add(586_950_981)
    }

    fn open_unit(s: u32) -> f64 {
        (f64::from(s >> 9) + 0.5) / 8_388_608.0
    }

    /// A feature point: its offset from p (scaled units), its distance and its id.
    #[derive(Clone, Copy)]
    pub struct Feature {
        pub delta: [f64; 3],
        pub d: f64,
        pub id: u32,
    }

    /// Every feature point of the (2r+1)^3 cubes around p, nearest first (in p's units).
    pub fn features(p: [f64; 3], manhattan: bool, r: i32) -> Vec<Feature> {
        let q = p.map(|x| x * DA);
        let c = q.map(f64::floor);
        let g = [q[0] - c[0], q[1] - c[1], q[2] - c[2]];
        let mut all = Vec::new();
        for i in -r..=r {
            for j in -r..=r {
                for k in -r..=r {
                    let o = [i, j, k];
                    let mut s = hash(&[c[0] as i32 + i, c[1] as i32 + j, c[2] as i32 + k], 0);
                    let count = POISSON[(s >> 24) as usize];
                    s = lcg(s);
                    for _ in 0..count {
                        let id = s;
                        let mut delta = [0.0; 3];
                        for a in 0..3 {
                            s = lcg(s);
                            delta[a] = f64::from(o[a]) + open_unit(s) - g[a];
                        }
                        s = lcg(s);
                        let d = if manhattan {
                            delta.iter().map(|x| x.abs()).sum::<f64>()
                        } else {
                            delta.iter().map(|x| x * x).sum::<f64>().sqrt()
                        };
                        all.push(Feature { delta: delta.map(|x| x / DA), d: d / DA, id });
                    }
                }
            }
        }
        all.sort_by(|a, b| a.d.total_cmp(&b.d));
        all
    }
}

fn columns(points: &[[f64; 3]]) -> [Vec<f64>; 3] {
    [0, 1, 2].map(|c| points.iter().map(|p| p[c]).collect())
}

fn to_f32(p: [f64; 3]) -> [f64; 3] {
    p.map(|x| f64::from(x as f32))
}

// -------------------------------------------------------------------------------------------
// cellnoise

const CELLNOISE_SHADER: &str = "#include <cellular.sl>\n\
    surface t(varying float x = 0, y = 0, z = 0, w = 0, s = 0) {\n\
        int seed = int(s);\n\
        Ci = color(cellnoise1(x, seed), cellnoise2(x, y, seed), cellnoise3(point(x, y, z), seed));\n\
        Oi = color(cellnoise4(point(x, y, z), w, seed), 0, 0);\n\
    }\n";

fn cellnoise_expected(p: &[f64; 5]) -> [f64; 4] {
    let s = p[4] as i32;
    [
        port::cellnoise(&p[..1], s),
        port::cellnoise(&p[..2], s),
        port::cellnoise(&p[..3], s),
        port::cellnoise(&p[..4], s),
    ]
}

fn cellnoise_rows(out: &[Vec<f64>]) -> Vec<[f64; 4]> {
    (0..out[0].len() / 3)
        .map(|i| [out[0][3 * i], out[0][3 * i + 1], out[0][3 * i + 2], out[1][3 * i]])
        .collect()
}

fn cellnoise_inputs() -> Vec<[f64; 5]> {
    let mut rng = Rng(5);
    let e = extremes();
    let mut v = Vec::new();
    for i in 0..3000 {
        let mut c = || -> f64 {
            match i % 3 {
                0 => rng.range(-10.0, 10.0),
                1 => rng.range(-3e9, 3e9),
                _ => e[(rng.next() % e.len() as u64) as usize],
            }
        };
        let p = [c(), c(), c(), c(), f64::from(i % 7 - 3)];
        v.push(p.map(|x| f64::from(x as f32)));
    }
    v
}

#[test]
fn cellnoise_matches_the_definition_on_both_backends_bit_for_bit() {
    let program = support::program(CELLNOISE_SHADER);
    let inputs = cellnoise_inputs();
    let cols: [Vec<f64>; 5] = [0, 1, 2, 3, 4].map(|c| inputs.iter().map(|p| p[c]).collect());
    let named = [
        ("x", &cols[0][..]),
        ("y", &cols[1][..]),
        ("z", &cols[2][..]),
        ("w", &cols[3][..]),
        ("s", &cols[4][..]),
    ];
    let expected: Vec<[f64; 4]> = inputs.iter().map(cellnoise_expected).collect();
    let r64 = cellnoise_rows(&program.cpu::<f64>(inputs.len(), &named, &["Ci", "Oi"]));
    let r32 = cellnoise_rows(&program.cpu::<f32>(inputs.len(), &named, &["Ci", "Oi"]));
    for (i, e) in expected.iter().enumerate() {
        assert_eq!(&r64[i], e, "f64 cellnoise at {:?}", inputs[i]);
        assert_eq!(&r32[i], e, "f32 cellnoise at {:?}", inputs[i]);
        assert!(e.iter().all(|v| (0.0..1.0).contains(v)));
    }
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let g = cellnoise_rows(&program.gpu(gpu, inputs.len(), &named, &["Ci", "Oi"]));
    for (i, e) in expected.iter().enumerate() {
        assert_eq!(&g[i], e, "GPU cellnoise at {:?}", inputs[i]);
    }
    println!("cellnoise1-4: {} inputs identical to the definition on f64, f32 and the GPU", inputs.len());
}

#[test]
fn cellnoise_is_constant_per_cell_uniform_and_independent_between_seeds() {
    let program = support::program(CELLNOISE_SHADER);
    // Points spread inside 256 cells: each cell's value must not change.
    let mut rng = Rng(9);
    let cells: Vec<[f64; 4]> = (0..256).map(|_| [0; 4].map(|_| rng.range(-1000.0, 1000.0).floor())).collect();
    let mut inputs = Vec::new();
    for c in &cells {
        for _ in 0..4 {
            let p = c.map(|x| x + rng.range(0.0, 0.999));
            inputs.push([p[0], p[1], p[2], p[3], 0.0].map(|x| f64::from(x as f32)));
        }
    }
    let cols: [Vec<f64>; 5] = [0, 1, 2, 3, 4].map(|c| inputs.iter().map(|p| p[c]).collect());
    let named = [
        ("x", &cols[0][..]),
        ("y", &cols[1][..]),
        ("z", &cols[2][..]),
        ("w", &cols[3][..]),
        ("s", &cols[4][..]),
    ];
    let rows = cellnoise_rows(&program.cpu::<f32>(inputs.len(), &named, &["Ci", "Oi"]));
    for group in rows.chunks_exact(4) {
        assert!(group.iter().all(|r| r == &group[0]), "cellnoise changes inside a cell: {group:?}");
    }
    // Uniformity and independence of the streams 0, 1, 2 (what the built-in's vector results use),
    // over 4096 cells of a 16^3 block (port, proved identical above).
    let n = 4096;
    let values: Vec<[f64; 3]> = (0..n)
        .map(|i| {
            let p = [f64::from(i % 16), f64::from((i / 16) % 16), f64::from(i / 256)];
            [0, 1, 2].map(|s| port::cellnoise(&p, s))
        })
        .collect();
    for s in 0..3 {
        let mut bins = [0.0; 16];
        for v in &values {
            bins[(v[s] * 16.0) as usize] += 1.0;
        }
        let e = f64::from(n) / 16.0;
        let chi2: f64 = bins.iter().map(|b| (b - e) * (b - e) / e).sum();
        println!("cellnoise3 seed {s}: chi2(15 dof) = {chi2:.1}");
        assert!(chi2 < 37.7, "seed {s}: chi2 {chi2}");
    }
    for (a, b) in [(0, 1), (0, 2), (1, 2)] {
        let cov = values.iter().map(|v| (v[a] - 0.5) * (v[b] - 0.5)).sum::<f64>() / f64::from(n);
        let corr = cov * 12.0;
        println!("cellnoise3 seeds {a} and {b}: correlation {corr:.4}");
        assert!(corr.abs() < 0.05);
    }
}

// -------------------------------------------------------------------------------------------
// Worley's basis

const WORLEY_SHADER: &str = "#include <cellular.sl>\n\
    surface t(varying float x = 0, y = 0, z = 0, m = 0;\n\
              output varying float f4 = 0, id1 = 0, id2 = 0, id3 = 0;\n\
              output varying color q1 = 0, q2 = 0, q3 = 0) {\n\
        matrix w = worley_basis(point(x, y, z), m);\n\
        Ci = color(w[0][0], w[0][1], w[0][2]);\n\
        f4 = w[0][3];\n\
        q1 = color(w[1][0], w[1][1], w[1][2]); id1 = w[1][3];\n\
        q2 = color(w[2][0], w[2][1], w[2][2]); id2 = w[2][3];\n\
        q3 = color(w[3][0], w[3][1], w[3][2]); id3 = w[3][3];\n\
    }\n";

const OUTPUTS: [&str; 8] = ["Ci", "f4", "id1", "id2", "id3", "q1", "q2", "q3"];

/// One point's results: f1..f4, then the three ids, then the three positions.
#[derive(Debug, Clone, Copy)]
struct Basis {
    f: [f64; 4],
    id: [f64; 3],
    q: [[f64; 3]; 3],
}

fn eval_basis(out: &[Vec<f64>]) -> Vec<Basis> {
    (0..out[1].len())
        .map(|i| Basis {
            f: [out[0][3 * i], out[0][3 * i + 1], out[0][3 * i + 2], out[1][i]],
            id: [out[2][i], out[3][i], out[4][i]],
            q: [5, 6, 7].map(|c| [out[c][3 * i], out[c][3 * i + 1], out[c][3 * i + 2]]),
        })
        .collect()
}

enum Backend<'a> {
    F32,
    F64,
    Gpu(&'a patina_runtime::gpu::Gpu),
}

fn worley(program: &support::Program, backend: Backend, points: &[[f64; 3]], manhattan: bool) -> Vec<Basis> {
    let [x, y, z] = columns(points);
    let m = vec![if manhattan { 1.0 } else { 0.0 }; points.len()];
    let inputs = [("x", &x[..]), ("y", &y[..]), ("z", &z[..]), ("m", &m[..])];
    let out = match backend {
        Backend::F32 => program.cpu::<f32>(points.len(), &inputs, &OUTPUTS),
        Backend::F64 => program.cpu::<f64>(points.len(), &inputs, &OUTPUTS),
        Backend::Gpu(gpu) => program.gpu(gpu, points.len(), &inputs, &OUTPUTS),
    };
    eval_basis(&out)
}

fn expected_basis(p: [f64; 3], manhattan: bool) -> Basis {
    let f = port::features(p, manhattan, 1);
    Basis {
        f: [0, 1, 2, 3].map(|n| f[n].d),
        id: [0, 1, 2].map(|n| port::unit(f[n].id)),
        q: [0, 1, 2].map(|n| [0, 1, 2].map(|a| p[a] + f[n].delta[a])),
    }
}

/// The largest difference between two sets of results in the distances, positions and ids.
fn basis_diff(a: &[Basis], b: &[Basis]) -> (f64, f64, f64, usize) {
    let mut w = (0.0f64, 0.0f64, 0.0f64, 0);
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        let df = x.f.iter().zip(&y.f).map(|(u, v)| (u - v).abs()).fold(0.0, f64::max);
        let dq = (0..3)
            .flat_map(|n| (0..3).map(move |c| (n, c)))
            .map(|(n, c)| (x.q[n][c] - y.q[n][c]).abs())
            .fold(0.0, f64::max);
        let di = x.id.iter().zip(&y.id).map(|(u, v)| (u - v).abs()).fold(0.0, f64::max);
        if df > w.0 {
            w.3 = i;
        }
        w = (w.0.max(df), w.1.max(dq), w.2.max(di), w.3);
    }
    w
}

fn random_points(n: usize, seed: u64, lo: f64, hi: f64) -> Vec<[f64; 3]> {
    let mut rng = Rng(seed);
    (0..n).map(|_| rng.point(lo, hi)).collect()
}

#[test]
fn worley_matches_the_port() {
    let program = support::program(WORLEY_SHADER);
    let mut points = random_points(384, 3, -5.0, 5.0);
    points.extend(random_points(256, 4, -1e4, 1e4));
    for manhattan in [false, true] {
        let expected: Vec<Basis> = points.iter().map(|&p| expected_basis(p, manhattan)).collect();
        let (df, dq, di, at) = basis_diff(&worley(&program, Backend::F64, &points, manhattan), &expected);
        println!("worley (manhattan {manhattan}) f64 vs port: F {df:.2e}, positions {dq:.2e}, ids {di:.2e}");
        assert!(df < 1e-9 && dq < 1e-9 && di == 0.0, "f64 differs from the port at {:?}", points[at]);
        let rounded: Vec<[f64; 3]> = points.iter().map(|&p| to_f32(p)).collect();
        let expected: Vec<Basis> = rounded.iter().map(|&p| expected_basis(p, manhattan)).collect();
        let got = worley(&program, Backend::F32, &rounded, manhattan);
        let (df, dq, di, at) = basis_diff(&got, &expected);
        println!("worley (manhattan {manhattan}) f32 vs port: F {df:.2e}, positions {dq:.2e}, ids {di:.2e}");
        assert!(df < 1e-5 && di == 0.0, "f32 differs from the port at {:?}", rounded[at]);
        // Positions are p + delta in f32: within an ulp of |p| (1e-3 at 1e4) plus the delta's error.
        assert!(dq < 2e-3, "f32 positions differ by {dq}");
    }
}

#[test]
fn worley_statistics_mean_f1_is_one_and_the_distances_are_ordered() {
    let program = support::program(WORLEY_SHADER);
    let points = random_points(4096, 7, -2000.0, 2000.0);
    let got = worley(&program, Backend::F32, &points, false);
    let n = got.len() as f64;
    let mut means = [0.0; 4];
    for b in &got {
        assert!(b.f[0] <= b.f[1] && b.f[1] <= b.f[2] && b.f[2] <= b.f[3], "F out of order: {b:?}");
        assert!(b.f[0] >= 0.0);
        for (m, f) in means.iter_mut().zip(&b.f) {
            *m += f / n;
        }
    }
    let var = got.iter().map(|b| (b.f[0] - means[0]).powi(2)).sum::<f64>() / n;
    let max = got.iter().map(|b| b.f[3]).fold(0.0, f64::max);
    println!(
        "worley: means F1 {:.4}, F2 {:.4}, F3 {:.4}, F4 {:.4}; F1 variance {var:.4}; largest F4 {max:.3}",
        means[0], means[1], means[2], means[3]
    );
    // Worley's DENSITY_ADJUSTMENT makes mean F1 = 1 (catalogue: 1.0021 with his linear hash;
    // the standard error over 4096 points is 0.3 / 64 = 0.005).
    assert!((means[0] - 1.0).abs() < 0.02, "mean F1 {}", means[0]);
    // Manhattan distances are at least Euclidean ones, so Manhattan F1 >= Euclidean F1.
    let man = worley(&program, Backend::F32, &points[..512], true);
    assert!(man.iter().zip(&got).all(|(m, e)| m.f[0] >= e.f[0] - 1e-6));
    // Each returned position is at its distance, and the id belongs to it (f64 mode).
    let exact = worley(&program, Backend::F64, &points[..512], false);
    for (b, p) in exact.iter().zip(&points) {
        for k in 0..3 {
            let d = (0..3).map(|a| (b.q[k][a] - p[a]).powi(2)).sum::<f64>().sqrt();
            assert!((d - b.f[k]).abs() < 1e-9, "F{} = {} but the point is at {d}", k + 1, b.f[k]);
        }
    }
}

#[test]
fn the_27_cube_search_finds_the_nearest_points_and_f_is_continuous() {
    // Against the 125-cube search of the port: how often do the 27 cubes miss one of the four
    // nearest points (Worley's density is tuned so that this is rare up to F4)?
    let mut rng = Rng(13);
    let (mut misses, total) = ([0usize; 4], 8000);
    for _ in 0..total {
        let p = rng.point(-1000.0, 1000.0);
        let near = port::features(p, false, 1);
        let far = port::features(p, false, 2);
        for n in 0..4 {
            if near[n].d != far[n].d {
                misses[n] += 1;
            }
        }
    }
    println!("27-cube search vs 125 cubes, {total} points: F1-F4 differ at {misses:?}");
    assert_eq!(misses[0] + misses[1], 0);
    assert!(misses[2] + misses[3] <= 2);
    // Lipschitz continuity: |F_n(p) - F_n(q)| <= |p - q| for every n (exact for the true F_n), on
    // pairs 1e-3 apart, many across the scaled cube faces, evaluated by the stdlib in f32.
    let program = support::program(WORLEY_SHADER);
    let mut a = Vec::new();
    let mut b = Vec::new();
    for i in 0..1024 {
        let mut p = rng.point(-300.0, 300.0);
        if i % 2 == 0 {
            // Right on a face of the scaled lattice in x.
            p[0] = (p[0] * port::DA).round() / port::DA;
        }
        let d = rng.point(-1.0, 1.0);
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-9);
        a.push(p);
        b.push([0, 1, 2].map(|c| p[c] + 1e-3 * d[c] / len));
    }
    let (fa, fb) = (worley(&program, Backend::F32, &a, false), worley(&program, Backend::F32, &b, false));
    let mut worst_ratio = 0.0f64;
    for (x, y) in fa.iter().zip(&fb) {
        for n in 0..4 {
            worst_ratio = worst_ratio.max((x.f[n] - y.f[n]).abs() / 1e-3);
        }
    }
    println!("F1-F4 over steps of 1e-3: largest |dF| / step = {worst_ratio:.4} (Lipschitz bound 1)");
    assert!(worst_ratio < 1.05, "F jumps: ratio {worst_ratio}");
}

#[test]
fn extreme_inputs_give_finite_ordered_results_and_the_gpu_agrees() {
    let e = extremes();
    let mut rng = Rng(19);
    let mut points: Vec<[f64; 3]> = Vec::new();
    for &x in &e {
        points.extend([[x, x, x], [x, 0.0, 0.5], [0.5, x, 0.0], [0.0, 0.5, x], [x, -x, x]]);
    }
    for _ in 0..256 {
        points.push([0; 3].map(|_| e[(rng.next() % e.len() as u64) as usize]));
    }
    let normal = random_points(512, 23, -100.0, 100.0);
    let program = support::program(WORLEY_SHADER);
    let gpu = patina_runtime::gpu::for_tests();
    for set in [&points, &normal] {
        for manhattan in [false, true] {
            let r32 = worley(&program, Backend::F32, set, manhattan);
            let r64 = worley(&program, Backend::F64, set, manhattan);
            for (label, r) in [("f32", &r32), ("f64", &r64)] {
                let flat: Vec<f64> = r.iter().flat_map(|b| b.f.iter().chain(&b.id).copied()).collect();
                assert_finite(&format!("worley F and ids ({label})"), &flat, 7);
                for b in r.iter() {
                    assert!(
                        b.f[0] <= b.f[1] && b.f[1] <= b.f[2] && b.f[2] <= b.f[3],
                        "order ({label}): {b:?}"
                    );
                    assert!(b.f[3] < 10.0, "F4 = {} ({label}): a search found too few points", b.f[3]);
                }
            }
            if let Some(gpu) = &gpu {
                let g = worley(&program, Backend::Gpu(gpu), set, manhattan);
                let (df, dq, di, at) = basis_diff(&g, &r32);
                println!(
                    "worley (manhattan {manhattan}) GPU vs f32, {} points: F {df:.2e}, positions {dq:.2e}, ids {di:.2e}",
                    set.len()
                );
                assert!(df <= 1e-6 && di == 0.0, "GPU differs at {:?}", set[at]);
                // Positions are p + delta: equal up to the ulp of the coordinate.
                let rel = g
                    .iter()
                    .zip(&r32)
                    .zip(set.iter())
                    .map(|((x, y), p)| {
                        let scale = p.iter().fold(1.0f64, |m, c| m.max(c.abs()));
                        (0..3)
                            .map(|n| (0..3).map(|c| (x.q[n][c] - y.q[n][c]).abs()).fold(0.0, f64::max))
                            .fold(0.0, f64::max)
                            / scale
                    })
                    .fold(0.0, f64::max);
                assert!(rel <= 1e-6, "GPU positions differ by {rel} relative");
            }
        }
    }
}

#[test]
fn large_coordinates_table() {
    // f32 against f64 at offsets 2^k (k = 0..24): (a) at the same f32 coordinates, the
    // algorithm's own error; (b) at the exact coordinates, adding their rounding to f32.
    let program = support::program(WORLEY_SHADER);
    const PER_OFFSET: usize = 16;
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
    let same32 = worley(&program, Backend::F32, &rounded, false);
    let same64 = worley(&program, Backend::F64, &rounded, false);
    let exact32 = worley(&program, Backend::F32, &exact, false);
    let exact64 = worley(&program, Backend::F64, &exact, false);
    let f = |v: &[Basis]| -> Vec<f64> { v.iter().flat_map(|b| b.f).collect() };
    let (same32, same64, exact32, exact64) = (f(&same32), f(&same64), f(&exact32), f(&exact64));
    println!("worley F1-F4: offset 2^k | f32 vs f64, same coordinates | f32 vs f64, exact coordinates");
    let (mut same_ok, mut exact_ok) = (-1, -1);
    for k in 0..=24usize {
        let r = 4 * k * PER_OFFSET..4 * (k + 1) * PER_OFFSET;
        let (a, _) = worst(&same32[r.clone()], &same64[r.clone()]);
        let (b, _) = worst(&exact32[r.clone()], &exact64[r]);
        println!("  2^{k:<2} | {a:.2e} | {b:.2e}");
        if a <= 1e-3 && same_ok == k as i32 - 1 {
            same_ok = k as i32;
        }
        if b <= 1e-3 && exact_ok == k as i32 - 1 {
            exact_ok = k as i32;
        }
    }
    println!("worley: within 1e-3 up to 2^{same_ok} (same coordinates), 2^{exact_ok} (exact coordinates)");
    assert_eq!(same_ok, 24);
    assert!(exact_ok >= 9, "exact coordinates: only up to 2^{exact_ok}");
    // cellnoise is exact at every offset: the f32 and f64 results agree wherever the coordinate
    // rounds to the same cell (checked bit for bit above); nothing to tabulate.
}
