//! `compiler/stdlib/color.sl` (colour tables with Hart's filtering) and the built-in colour spaces
//! (`ctransform`, colour casts) on the interpreter in f64 and f32 against independent ports written
//! here, and on the GPU against the interpreter. Run with `--nocapture` to see the measured numbers.
//!
//! - colortable: the entry floor(N modclamp(x)) (Hart's eq. 2 with errata E8), exactly;
//! - filteredcolortable: the exact box integral of the unfiltered table (summed over the entries
//!   the box covers, in f64) and a midpoint-rule integral; w = 0 gives the unfiltered entry
//!   exactly, a huge w the table's mean (wrap) or the mean of the first and last entries (clamp);
//! - mipcolortable (Hart's colour-table MIP map, errata E10): a port of the level build and the
//!   lookup (f64 within 1e-12, f32 within 5e-7), exact level means for dyadic data, w <= 1 entry
//!   exactly colortable, a huge w the mean, continuity across level boundaries, and its distance
//!   from the exact box filter for a smooth table; GPU within 5e-6 (measured 6e-8);
//! - ctransform to and from hsv, hsl, xyz and YIQ against the textbook algorithms (Smith's
//!   hexcone with its sextant table, the XYZ matrix derived here from the Rec. 709 primaries by
//!   Cramer's rule, Foley and van Dam's YIQ matrix);
//! - the extreme-input sweep finite on both backends in both precisions, and the GPU equal to
//!   the interpreter: bit-identical for colortable and the colour spaces, within 1e-6 for
//!   filteredcolortable (measured 1.8e-7: lavapipe may reassociate its weighted sum).

use crate::support;

use patina_compiler::backend::cpu::scalar::Real;

/// A float as a shader literal that keeps its exact value in both precisions.
fn lit(x: f64) -> String {
    let s = format!("{:?}", f64::from(x as f32));
    if s.contains('.') || s.contains('e') { s } else { format!("{s}.0") }
}

/// A random table of `n` colours with f32-exact components in [0, 1].
fn table(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut rng = support::Rng(seed);
    (0..n).map(|_| [0, 1, 2].map(|_| f64::from(rng.unit() as f32))).collect()
}

/// The shader: Ci the filtered lookup (summed-area table built per call), Oi the unfiltered one;
/// with `sat`, the filtered lookup from a summed-area table built once by the macro.
fn table_shader(t: &[[f64; 3]], sat: bool) -> support::Program {
    let n = t.len();
    let items = t
        .iter()
        .map(|c| format!("color({}, {}, {})", lit(c[0]), lit(c[1]), lit(c[2])))
        .collect::<Vec<_>>()
        .join(", ");
    let filtered = if sat {
        format!(
            "color sat[{n}];\nPATINA_COLORTABLE_SAT(tab, sat, {n});\nCi = filteredcolortable(tab, sat, x, w, wrap);"
        )
    } else {
        "Ci = filteredcolortable(tab, x, w, wrap);".to_string()
    };
    support::program(&format!(
        "#include <color.sl>\nsurface t(varying float x = 0, w = 0, wrap = 0) {{\n\
         constant color tab[{n}] = {{{items}}};\n{filtered}\nOi = colortable(tab, x, wrap);\n}}\n"
    ))
}

/// The entry at x in the evaluator's precision (the formula of Hart's eq. 2 with cells).
fn entry<F: Real>(n: usize, x: f64, wrap: bool) -> usize {
    if std::any::type_name::<F>() == "f32" {
        let (x, n) = (x as f32, n as f32);
        let u = if wrap { n * (x - x.floor()) } else { n * x.clamp(0.0, 1.0) };
        u.floor().min(n - 1.0) as usize
    } else {
        let n = n as f64;
        let u = if wrap { n * (x - x.floor()) } else { n * x.clamp(0.0, 1.0) };
        u.floor().min(n - 1.0) as usize
    }
}

/// The table's value on the index line (one unit per entry): periodic or clamped.
fn extended(t: &[[f64; 3]], k: f64, wrap: bool) -> [f64; 3] {
    let n = t.len() as f64;
    let k = if wrap { k.rem_euclid(n) } else { k.clamp(0.0, n - 1.0) };
    t[k as usize]
}

/// The exact mean of the table over [N x - N w / 2, N x + N w / 2], entry by entry, in f64.
fn box_mean(t: &[[f64; 3]], x: f64, w: f64, wrap: bool) -> [f64; 3] {
    let n = t.len() as f64;
    let (a, b) = (n * x - n * w / 2.0, n * x + n * w / 2.0);
    let mut sum = [0.0; 3];
    let mut k = a.floor();
    while k <= b.floor() {
        let overlap = b.min(k + 1.0) - a.max(k);
        let c = extended(t, k, wrap);
        for i in 0..3 {
            sum[i] += overlap * c[i];
        }
        k += 1.0;
    }
    sum.map(|s| s / (b - a))
}

fn run<F: Real>(p: &support::Program, pts: &[[f64; 3]]) -> Vec<Vec<f64>> {
    let cols: Vec<Vec<f64>> = (0..3).map(|k| pts.iter().map(|q| q[k]).collect()).collect();
    let inputs = [("x", &cols[0][..]), ("w", &cols[1][..]), ("wrap", &cols[2][..])];
    p.cpu::<F>(pts.len(), &inputs, &["Ci", "Oi"])
}

fn run_gpu(gpu: &patina_runtime::gpu::Gpu, p: &support::Program, pts: &[[f64; 3]]) -> Vec<Vec<f64>> {
    let cols: Vec<Vec<f64>> = (0..3).map(|k| pts.iter().map(|q| q[k]).collect()).collect();
    let inputs = [("x", &cols[0][..]), ("w", &cols[1][..]), ("wrap", &cols[2][..])];
    p.gpu(gpu, pts.len(), &inputs, &["Ci", "Oi"])
}

/// (x, w, wrap) for the reference comparisons: x across and beyond the table, widths from a
/// fraction of an entry to several tables.
fn table_points(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut rng = support::Rng(seed);
    let mut pts = Vec::new();
    for i in 0..1200 {
        let w = match i % 4 {
            0 => rng.range(0.01, 1.0) / n as f64,
            1 => rng.range(1.0, 8.0) / n as f64,
            2 => rng.range(0.05, 1.0),
            _ => rng.range(1.0, 6.0),
        };
        let x = if i % 5 == 0 { rng.range(-3.0, 4.0) } else { rng.range(-0.3, 1.3) };
        pts.push([x, w, (i % 2) as f64]);
    }
    pts
}

#[test]
fn colour_tables_match_the_box_integral_of_the_table() {
    for (n, seed) in [(2usize, 1u64), (5, 2), (8, 3), (256, 4)] {
        let t = table(n, seed);
        let program = table_shader(&t, false);
        let with_sat = table_shader(&t, true);
        let pts = table_points(n, seed + 10);
        for (k, prec) in ["f64", "f32"].into_iter().enumerate() {
            let (out, out_sat) = if k == 0 {
                (run::<f64>(&program, &pts), run::<f64>(&with_sat, &pts))
            } else {
                (run::<f32>(&program, &pts), run::<f32>(&with_sat, &pts))
            };
            assert_eq!(out[0], out_sat[0], "N = {n} ({prec}): the summed-area table made once differs");
            let eps = if k == 0 { f64::EPSILON } else { f64::from(f32::EPSILON) };
            let mut worst = (0.0f64, 0.0f64, [0.0; 3]);
            for (i, p) in pts.iter().enumerate() {
                let q = if k == 1 { p.map(|v| f64::from(v as f32)) } else { *p };
                let wrap = q[2] != 0.0;
                // Unfiltered: exactly the entry.
                let e = if k == 0 { entry::<f64>(n, q[0], wrap) } else { entry::<f32>(n, q[0], wrap) };
                assert_eq!(&out[1][3 * i..3 * i + 3], &t[e][..], "colortable N = {n} at {q:?} ({prec})");
                // Filtered: the box integral. The arguments' rounding in the precision (N x and
                // N w / 2 to an ulp of N (|x| + w + 2)) is magnified by the box length N w, and the
                // summed-area differences carry a few ulps of the table's total.
                let want = box_mean(&t, q[0], q[1], wrap);
                let nf = n as f64;
                let tol = 8.0 * eps * nf * (q[0].abs() + q[1] + 2.0) / (nf * q[1]) + 4.0 * eps * nf;
                for c in 0..3 {
                    let err = (out[0][3 * i + c] - want[c]).abs();
                    assert!(
                        err <= tol,
                        "filteredcolortable N = {n} at {q:?} ({prec}): {} vs {} (tol {tol:e})",
                        out[0][3 * i + c],
                        want[c]
                    );
                    if err / tol > worst.1 {
                        worst = (err, err / tol, q);
                    }
                }
            }
            println!(
                "filteredcolortable N = {n:3} {prec}: largest error {:.3e} ({:.0}% of its tolerance) at {:?}",
                worst.0,
                100.0 * worst.1,
                worst.2
            );
        }
    }
}

#[test]
fn the_box_filter_is_the_numerical_integral_of_the_unfiltered_lookup() {
    // The midpoint rule over x of the unfiltered lookup (the Rust port of eq. 2), 20,000 samples:
    // each entry edge in the box misjudges at most one sample.
    const S: usize = 20_000;
    let t = table(7, 31);
    let program = table_shader(&t, false);
    let mut rng = support::Rng(37);
    let pts: Vec<[f64; 3]> =
        (0..60).map(|i| [rng.range(-1.0, 2.0), rng.range(0.01, 3.0), (i % 2) as f64]).collect();
    let out = run::<f64>(&program, &pts);
    for (i, p) in pts.iter().enumerate() {
        let wrap = p[2] != 0.0;
        let mut sum = [0.0; 3];
        for j in 0..S {
            let x = p[0] - p[1] / 2.0 + (j as f64 + 0.5) * p[1] / S as f64;
            let c = t[entry::<f64>(7, x, wrap)];
            for k in 0..3 {
                sum[k] += c[k];
            }
        }
        let edges = 7.0 * p[1] + 2.0;
        for k in 0..3 {
            let mean = sum[k] / S as f64;
            assert!(
                (out[0][3 * i + k] - mean).abs() <= edges / S as f64,
                "at {p:?}: {} vs midpoint {mean}",
                out[0][3 * i + k]
            );
        }
    }
}

#[test]
fn colour_table_limits_extremes_and_the_gpu() {
    let t = table(6, 41);
    let mean: Vec<f64> = (0..3).map(|c| t.iter().map(|e| e[c]).sum::<f64>() / 6.0).collect();
    let ends: Vec<f64> = (0..3).map(|c| (t[0][c] + t[5][c]) / 2.0).collect();
    let program = table_shader(&t, false);
    // Limits: w = 0 is the unfiltered lookup bit for bit; w = 1e30 the mean (wrap) or the mean of
    // the end entries (clamp: the box covers far more of the extension than of the table).
    let xs = [-1.5, -0.01, 0.0, 0.3, 0.5, 0.99, 1.0, 7.25];
    let mut pts: Vec<[f64; 3]> = Vec::new();
    for &x in &xs {
        for wrap in [0.0, 1.0] {
            pts.push([x, 0.0, wrap]);
            pts.push([x, 1e30, wrap]);
        }
    }
    for (prec, out) in [("f64", run::<f64>(&program, &pts)), ("f32", run::<f32>(&program, &pts))] {
        for (i, p) in pts.iter().enumerate() {
            let got = &out[0][3 * i..3 * i + 3];
            if p[1] == 0.0 {
                assert_eq!(got, &out[1][3 * i..3 * i + 3], "w = 0 at {p:?} ({prec})");
            } else {
                let want = if p[2] != 0.0 { &mean } else { &ends };
                for c in 0..3 {
                    assert!(
                        (got[c] - want[c]).abs() < 1e-6,
                        "w = 1e30 at {p:?} ({prec}): {got:?} vs {want:?}"
                    );
                }
            }
        }
    }
    // A box exactly covering the table (clamp, x = 1/2, w = 1) is its mean.
    let out = run::<f64>(&program, &[[0.5, 1.0, 0.0]]);
    for c in 0..3 {
        assert!((out[0][c] - mean[c]).abs() < 1e-14);
    }

    // The sweep: x and w over the extremes (and negative widths), both modes.
    let ex = support::extremes();
    let mut sweep = Vec::new();
    for &x in &ex {
        for &w in &ex {
            for wrap in [0.0, 1.0] {
                sweep.push([x, w, wrap]);
            }
        }
    }
    let cpu32 = run::<f32>(&program, &sweep);
    let cpu64 = run::<f64>(&program, &sweep);
    for (name, out) in [("f32", &cpu32), ("f64", &cpu64)] {
        support::assert_finite(&format!("filteredcolortable ({name})"), &out[0], 3);
        support::assert_finite(&format!("colortable ({name})"), &out[1], 3);
        // Every result is a mean of entries: inside the table's range.
        for v in &out[0] {
            assert!((-1e-6..=1.0 + 1e-6).contains(v), "{name}: {v} outside the table's range");
        }
    }
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let mut all = sweep.clone();
    all.extend(table_points(6, 43));
    let cpu = run::<f32>(&program, &all);
    let got = run_gpu(gpu, &program, &all);
    for k in 0..2 {
        support::assert_finite("colour table (GPU)", &got[k], 3);
        let (d, at) = support::worst(&got[k], &cpu[k]);
        println!(
            "colour table, output {k}: GPU vs interpreter largest difference {d:e} over {} points",
            all.len()
        );
        // The unfiltered lookup is exact; the filtered one is a short weighted sum, which
        // lavapipe may reassociate (WGSL allows it; docs/numerics.md): within FILTER_GPU_TOL.
        let tol = if k == 0 { FILTER_GPU_TOL } else { 0.0 };
        assert!(d <= tol, "the GPU differs by {d:e} at {:?}", all[at / 3]);
    }
}

/// GPU vs interpreter for filteredcolortable, absolute, for entries in [0, 1] (measured 1.8e-7).
const FILTER_GPU_TOL: f64 = 1e-6;

// ---------------------------------------------------------------------------------------------
// The colour-table MIP map (Hart's section 3.3.1 with errata E10), against a port written here.

/// The shader: Ci the MIP-mapped lookup (levels built per point by the macro), Oi colortable.
fn mip_shader(t: &[[f64; 3]]) -> support::Program {
    let n = t.len();
    let items = t
        .iter()
        .map(|c| format!("color({}, {}, {})", lit(c[0]), lit(c[1]), lit(c[2])))
        .collect::<Vec<_>>()
        .join(", ");
    support::program(&format!(
        "#include <color.sl>\nsurface t(varying float x = 0, w = 0, wrap = 0) {{\n\
         constant color tab[{n}] = {{{items}}};\ncolor mip[{}];\nPATINA_COLORTABLE_MIP(tab, mip, {n});\n\
         Ci = mipcolortable(mip, {n}, x, w, wrap);\nOi = colortable(tab, x, wrap);\n}}\n",
        2 * n - 1
    ))
}

/// The MIP levels from Hart's description (L239-240): level 0 the table, each further level the
/// pairwise means of the one before, down to one entry.
fn mip_levels(t: &[[f64; 3]]) -> Vec<Vec<[f64; 3]>> {
    let mut levels = vec![t.to_vec()];
    while levels.last().unwrap().len() > 1 {
        let up = levels.last().unwrap();
        let next =
            (0..up.len() / 2).map(|j| [0, 1, 2].map(|c| (up[2 * j][c] + up[2 * j + 1][c]) / 2.0)).collect();
        levels.push(next);
    }
    levels
}

/// The lookup (L242-243 with E10): i = clamp(floor(log2 m), 0, log2 N) for the width m = N w in
/// entries, entry floor(N/2^i modclamp(x)) of level i, linearly blended with level i + 1 by the
/// fractional part of log2 m; m <= 1 the level-0 entry. The entry is taken in the evaluator's
/// precision (as `entry`); the blend in f64.
fn mip_lookup<F: Real>(levels: &[Vec<[f64; 3]>], x: f64, w: f64, wrap: bool) -> [f64; 3] {
    let n = levels[0].len();
    let top = levels.len() - 1;
    let m = n as f64 * w;
    if m <= 1.0 {
        return levels[0][entry::<F>(n, x, wrap)];
    }
    let l = m.log2();
    let i = (l.floor() as usize).min(top);
    let at = |k: usize| levels[k][entry::<F>(n >> k, x, wrap)];
    if i == top {
        return at(top);
    }
    let t = l - i as f64;
    let (lo, hi) = (at(i), at(i + 1));
    [0, 1, 2].map(|c| (1.0 - t) * lo[c] + t * hi[c])
}

/// (x, w, wrap) for the MIP comparisons: widths from a fraction of an entry to beyond the table,
/// log-uniform, and exactly at the level boundaries 2^k entries.
fn mip_points(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut rng = support::Rng(seed);
    let top = (n as f64).log2();
    (0..1200)
        .map(|i| {
            let m = if i % 6 == 0 {
                2f64.powi(rng.range(0.0, top + 1.0).floor() as i32)
            } else {
                2f64.powf(rng.range(-2.0, top + 1.5))
            };
            let x = if i % 5 == 0 { rng.range(-3.0, 4.0) } else { rng.range(-0.3, 1.3) };
            [x, m / n as f64, (i % 2) as f64]
        })
        .collect()
}

/// The f32 interpreter against the port: the level choice and entries are exact (the width is
/// halved exactly), so the error is the blend weight's (log2 of a number in [1, 2) in f32) and
/// the blend's rounding, times the difference of two entries, at most 1 (measured 8.4e-8).
const MIP_F32_TOL: f64 = 5e-7;

/// GPU vs the f32 interpreter for mipcolortable: the blend weight uses log(m, 2), for which
/// docs/numerics.md allows 4e-6 absolute on a GPU, times an entry difference of at most 1
/// (measured on lavapipe 6.0e-8).
const MIP_GPU_TOL: f64 = 5e-6;

#[test]
fn mip_colour_tables_match_the_port() {
    for (n, seed) in [(2usize, 61u64), (8, 62), (64, 63), (256, 64)] {
        let t = table(n, seed);
        let levels = mip_levels(&t);
        let program = mip_shader(&t);
        let pts = mip_points(n, seed + 10);
        for (k, prec) in ["f64", "f32"].into_iter().enumerate() {
            let out = if k == 0 { run::<f64>(&program, &pts) } else { run::<f32>(&program, &pts) };
            let tol = if k == 0 { 1e-12 } else { MIP_F32_TOL };
            let mut worst = (0.0f64, [0.0; 3]);
            for (i, p) in pts.iter().enumerate() {
                let q = if k == 1 { p.map(|v| f64::from(v as f32)) } else { *p };
                let wrap = q[2] != 0.0;
                let want = if k == 0 {
                    mip_lookup::<f64>(&levels, q[0], q[1], wrap)
                } else {
                    mip_lookup::<f32>(&levels, q[0], q[1], wrap)
                };
                for c in 0..3 {
                    let err = (out[0][3 * i + c] - want[c]).abs();
                    assert!(
                        err <= tol,
                        "mipcolortable N = {n} at {q:?} ({prec}): {} vs {}",
                        out[0][3 * i + c],
                        want[c]
                    );
                    if err > worst.0 {
                        worst = (err, q);
                    }
                }
            }
            println!(
                "mipcolortable N = {n:3} {prec}: largest error vs the port {:.3e} at {:?}",
                worst.0, worst.1
            );
        }
    }
}

#[test]
fn mip_levels_limits_and_continuity() {
    // Dyadic entries (multiples of 1/64): every level's mean is exact in both precisions, so at
    // w = 2^k / N (blend weight log2 1 = 0) the lookup is exactly the mean of the aligned block
    // of 2^k entries holding x, and a huge w exactly the table's mean.
    let n = 16;
    let mut rng = support::Rng(71);
    let t: Vec<[f64; 3]> = (0..n).map(|_| [0, 1, 2].map(|_| (rng.unit() * 64.0).floor() / 64.0)).collect();
    let program = mip_shader(&t);
    let mut pts = Vec::new();
    for k in 0..=5 {
        for j in 0..40 {
            let x = rng.range(-0.5, 1.5);
            let w = if k == 5 { [1e30, 1e6, 1.0, 2.0][j % 4] } else { f64::from(1u32 << k) / n as f64 };
            pts.push([x, w, (j % 2) as f64]);
        }
    }
    for (prec, out) in [("f64", run::<f64>(&program, &pts)), ("f32", run::<f32>(&program, &pts))] {
        for (i, p) in pts.iter().enumerate() {
            let m = (n as f64 * p[1]).min(n as f64) as usize;
            let e = entry::<f64>(n, p[0], p[2] != 0.0);
            let block = (e / m) * m;
            let want: Vec<f64> =
                (0..3).map(|c| (block..block + m).map(|j| t[j][c]).sum::<f64>() / m as f64).collect();
            assert_eq!(&out[0][3 * i..3 * i + 3], &want[..], "level mean at {p:?} ({prec})");
        }
    }

    // w <= 1 entry: exactly colortable; a huge w: the mean of a random table.
    let t = table(32, 73);
    let mean: Vec<f64> = (0..3).map(|c| t.iter().map(|e| e[c]).sum::<f64>() / 32.0).collect();
    let program = mip_shader(&t);
    let mut pts = Vec::new();
    for x in [-1.5, -0.01, 0.0, 0.3, 0.5, 0.99, 1.0, 7.25] {
        for wrap in [0.0, 1.0] {
            for w in [0.0, -1.0, -1e30, 1e-30, 0.5 / 32.0, 1.0 / 32.0] {
                pts.push([x, w, wrap]);
            }
            pts.push([x, 1e30, wrap]);
            pts.push([x, 1.0, wrap]);
        }
    }
    for (prec, out) in [("f64", run::<f64>(&program, &pts)), ("f32", run::<f32>(&program, &pts))] {
        for (i, p) in pts.iter().enumerate() {
            let got = &out[0][3 * i..3 * i + 3];
            if p[1] * 32.0 <= 1.0 {
                assert_eq!(got, &out[1][3 * i..3 * i + 3], "w = {} at {p:?} ({prec})", p[1]);
            } else {
                for c in 0..3 {
                    assert!(
                        (got[c] - mean[c]).abs() < 1e-6,
                        "w = {} at {p:?} ({prec}): {got:?} vs {mean:?}",
                        p[1]
                    );
                }
            }
        }
    }

    // Continuity in w across the level boundaries m = 2^k (k = 0 .. 5 for N = 32): the blend
    // weight log2 m goes from 1 on level k - 1 to 0 on level k, the same colour.
    let mut pts = Vec::new();
    let mut rng = support::Rng(79);
    for k in 0..=5 {
        for _ in 0..20 {
            let x = rng.range(-0.2, 1.2);
            let w = f64::from(1u32 << k) / 32.0;
            for wrap in [0.0, 1.0] {
                pts.push([x, w * (1.0 - 1e-9), wrap]);
                pts.push([x, w * (1.0 + 1e-9), wrap]);
            }
        }
    }
    let out = run::<f64>(&program, &pts);
    let mut worst = 0.0f64;
    for i in (0..pts.len()).step_by(2) {
        for c in 0..3 {
            worst = worst.max((out[0][3 * i + c] - out[0][3 * i + 3 + c]).abs());
        }
    }
    println!("mipcolortable: largest jump across a level boundary (w changed by 2e-9 relative) {worst:.3e}");
    assert!(worst < 1e-8, "mipcolortable jumps by {worst:e} at a level boundary");
}

#[test]
fn mip_colour_tables_approximate_the_box_filter_on_smooth_tables() {
    // A smooth periodic table (a sinusoid per channel, one period over the table): the MIP level
    // averages an aligned block of 2^i entries, the box filter the centred [x - w/2, x + w/2];
    // they differ by about the table's slope times the block length, so at most a fraction of
    // the table's range for wide boxes and little for narrow ones.
    let n = 256;
    let t: Vec<[f64; 3]> = (0..n)
        .map(|j| {
            let a = std::f64::consts::TAU * (j as f64 + 0.5) / n as f64;
            [0, 1, 2].map(|c| f64::from((0.5 + 0.4 * (a + c as f64).sin()) as f32))
        })
        .collect();
    let mip = mip_shader(&t);
    let boxed = table_shader(&t, true);
    let mut rng = support::Rng(83);
    let mut pts = Vec::new();
    // Widths in entries 1/4 .. 8 (narrow) and 8 .. 64 (wide), wrapped.
    for i in 0..800 {
        let m = if i % 2 == 0 { 2f64.powf(rng.range(-2.0, 3.0)) } else { 2f64.powf(rng.range(3.0, 6.0)) };
        pts.push([rng.range(0.0, 1.0), m / n as f64, 1.0]);
    }
    let a = run::<f64>(&mip, &pts);
    let b = run::<f64>(&boxed, &pts);
    let (mut narrow, mut wide) = (0.0f64, 0.0f64);
    for (i, p) in pts.iter().enumerate() {
        for c in 0..3 {
            let d = (a[0][3 * i + c] - b[0][3 * i + c]).abs();
            if p[1] * n as f64 <= 8.0 { narrow = narrow.max(d) } else { wide = wide.max(d) }
        }
    }
    println!(
        "mipcolortable vs filteredcolortable, sinusoid of amplitude 0.4 over N = 256: widths <= 8 entries {narrow:.3e}, 8-64 entries {wide:.3e}"
    );
    assert!(narrow < 0.05 && wide < 0.3, "MIP vs box: {narrow:e}, {wide:e}");
}

#[test]
fn mip_colour_table_extremes_and_the_gpu() {
    let t = table(64, 89);
    let program = mip_shader(&t);
    let ex = support::extremes();
    let mut sweep = Vec::new();
    for &x in &ex {
        for &w in &ex {
            for wrap in [0.0, 1.0] {
                sweep.push([x, w, wrap]);
            }
        }
    }
    let cpu32 = run::<f32>(&program, &sweep);
    let cpu64 = run::<f64>(&program, &sweep);
    for (name, out) in [("f32", &cpu32), ("f64", &cpu64)] {
        support::assert_finite(&format!("mipcolortable ({name})"), &out[0], 3);
        for v in &out[0] {
            assert!((-1e-6..=1.0 + 1e-6).contains(v), "{name}: {v} outside the table's range");
        }
    }
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let mut all = sweep.clone();
    all.extend(mip_points(64, 91));
    let cpu = run::<f32>(&program, &all);
    let got = run_gpu(gpu, &program, &all);
    support::assert_finite("mipcolortable (GPU)", &got[0], 3);
    let (d, at) = support::worst(&got[0], &cpu[0]);
    println!("mipcolortable: GPU vs interpreter largest difference {d:e} over {} points", all.len());
    assert!(d <= MIP_GPU_TOL, "the GPU differs by {d:e} at {:?}", all[at / 3]);
}

// ---------------------------------------------------------------------------------------------
// Colour spaces (the built-in ctransform), against textbook algorithms.

/// RGB to hue (turns), chroma, max, min (Smith 1978).
fn hue(c: [f64; 3]) -> (f64, f64, f64, f64) {
    let (r, g, b) = (c[0], c[1], c[2]);
    let max = r.max(g).max(b);
    let min = r.min(g).min(b);
    let chroma = max - min;
    let h = if chroma <= 0.0 {
        0.0
    } else if max == r {
        ((g - b) / chroma).rem_euclid(6.0)
    } else if max == g {
        (b - r) / chroma + 2.0
    } else {
        (r - g) / chroma + 4.0
    };
    (h / 6.0, chroma, max, min)
}

fn rgb_to_hsv(c: [f64; 3]) -> [f64; 3] {
    let (h, chroma, max, _) = hue(c);
    [h, if max != 0.0 { chroma / max } else { 0.0 }, max]
}

fn rgb_to_hsl(c: [f64; 3]) -> [f64; 3] {
    let (h, chroma, max, min) = hue(c);
    let l = (max + min) / 2.0;
    let d = 1.0 - (2.0 * l - 1.0).abs();
    [h, if d != 0.0 { chroma / d } else { 0.0 }, l]
}

/// The hexcone's sextant table (Foley and van Dam, Fig. 13.34): RGB from hue, chroma and the
/// amount m added to every channel.
fn from_hue(h: f64, chroma: f64, m: f64) -> [f64; 3] {
    let h6 = h.rem_euclid(1.0) * 6.0;
    let x = chroma * (1.0 - (h6.rem_euclid(2.0) - 1.0).abs());
    let (r, g, b) = match h6 as u32 {
        0 => (chroma, x, 0.0),
        1 => (x, chroma, 0.0),
        2 => (0.0, chroma, x),
        3 => (0.0, x, chroma),
        4 => (x, 0.0, chroma),
        _ => (chroma, 0.0, x),
    };
    [r + m, g + m, b + m]
}

fn hsv_to_rgb(c: [f64; 3]) -> [f64; 3] {
    let chroma = c[2] * c[1];
    from_hue(c[0], chroma, c[2] - chroma)
}

fn hsl_to_rgb(c: [f64; 3]) -> [f64; 3] {
    let chroma = (1.0 - (2.0 * c[2] - 1.0).abs()) * c[1];
    from_hue(c[0], chroma, c[2] - chroma / 2.0)
}

/// RGB (Rec. 709 primaries, D65 white) to XYZ: the primaries' XYZ scaled so that RGB white is
/// the white point at Y = 1, the scales solved by Cramer's rule.
fn xyz_matrix() -> [[f64; 3]; 3] {
    let xyz = |x: f64, y: f64| [x / y, 1.0, (1.0 - x - y) / y];
    let p = [xyz(0.64, 0.33), xyz(0.30, 0.60), xyz(0.15, 0.06)];
    let w = xyz(0.3127, 0.3290);
    let det3 = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    // Columns are the primaries: M = [p0 p1 p2], M s = w.
    let m = [[p[0][0], p[1][0], p[2][0]], [p[0][1], p[1][1], p[2][1]], [p[0][2], p[1][2], p[2][2]]];
    let d = det3(m);
    let s: Vec<f64> = (0..3)
        .map(|j| {
            let mut mj = m;
            for i in 0..3 {
                mj[i][j] = w[i];
            }
            det3(mj) / d
        })
        .collect();
    let mut out = m;
    for row in &mut out {
        for j in 0..3 {
            row[j] *= s[j];
        }
    }
    out
}

const YIQ: [[f64; 3]; 3] = [[0.299, 0.587, 0.114], [0.596, -0.275, -0.321], [0.212, -0.523, 0.311]];

fn apply(m: &[[f64; 3]; 3], c: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| m[i][0] * c[0] + m[i][1] * c[1] + m[i][2] * c[2])
}

/// The colour-space shader: Ci = ctransform(to, c) (from RGB), Oi = ctransform(space, "rgb", c).
fn space_shader(space: &str) -> support::Program {
    support::program(&format!(
        "surface t(varying color c = 0) {{ Ci = ctransform(\"{space}\", c); Oi = ctransform(\"{space}\", \"rgb\", c); }}"
    ))
}

/// Colours to convert: random in [0, 1], greys, black, white, the primaries and secondaries.
fn colours() -> Vec<[f64; 3]> {
    let mut rng = support::Rng(53);
    let mut v: Vec<[f64; 3]> = (0..2000).map(|_| [rng.unit(), rng.unit(), rng.unit()]).collect();
    for g in [0.0, 0.25, 0.5, 1.0] {
        v.push([g, g, g]);
    }
    for k in 1..8u32 {
        v.push([f64::from(k & 1), f64::from((k >> 1) & 1), f64::from((k >> 2) & 1)]);
    }
    v.push([1.0, 1.0, 0.5]);
    v.push([0.5, 1.0, 1.0]);
    v
}

#[test]
fn colour_spaces_match_the_textbook_conversions() {
    // The derived XYZ matrix is the published sRGB one (IEC 61966-2-1, four decimals).
    let published = [[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]];
    let xm = xyz_matrix();
    for (a, b) in xm.iter().flatten().zip(published.iter().flatten()) {
        assert!((a - b).abs() < 1e-4);
    }
    let rgb = colours();
    // hsv and hsl inputs: hue over several turns and negative (it wraps).
    let mut rng = support::Rng(59);
    let hsx: Vec<[f64; 3]> = (0..2000).map(|_| [rng.range(-2.0, 3.0), rng.unit(), rng.unit()]).collect();
    type To = fn([f64; 3]) -> [f64; 3];
    let spaces: [(&str, To, Option<To>); 4] = [
        ("hsv", rgb_to_hsv, Some(hsv_to_rgb)),
        ("hsl", rgb_to_hsl, Some(hsl_to_rgb)),
        ("xyz", |c| apply(&xyz_matrix(), c), None),
        ("YIQ", |c| apply(&YIQ, c), None),
    ];
    for (space, to, from) in spaces {
        let program = space_shader(space);
        // Inputs to convert from the space: hue-based spaces take hsx; linear ones the space's
        // image of random colours.
        let back_in: Vec<[f64; 3]> =
            if from.is_some() { hsx.clone() } else { rgb.iter().map(|&c| to(c)).collect() };
        for (k, prec) in ["f64", "f32"].into_iter().enumerate() {
            let tol = if k == 0 { 1e-12 } else { 4e-6 };
            for (dir, inputs) in [("to", &rgb), ("from", &back_in)] {
                let col: Vec<f64> = inputs.iter().flatten().copied().collect();
                let ins = [("c", &col[..])];
                let out = if k == 0 {
                    program.cpu::<f64>(inputs.len(), &ins, &["Ci", "Oi"])
                } else {
                    program.cpu::<f32>(inputs.len(), &ins, &["Ci", "Oi"])
                };
                let mut worst = 0.0f64;
                for (i, c) in inputs.iter().enumerate() {
                    let c = if k == 1 { c.map(|v| f64::from(v as f32)) } else { *c };
                    let (got, want) = if dir == "to" {
                        let g = [out[0][3 * i], out[0][3 * i + 1], out[0][3 * i + 2]];
                        (g, to(c))
                    } else {
                        let g = [out[1][3 * i], out[1][3 * i + 1], out[1][3 * i + 2]];
                        match from {
                            Some(f) => (g, f(c)),
                            // Linear spaces: the forward matrix takes the result back to the input.
                            None => (to(g), c),
                        }
                    };
                    for j in 0..3 {
                        let mut d = (got[j] - want[j]).abs();
                        // Hue is a circle: 1 and 0 are the same hue.
                        if dir == "to" && j == 0 && from.is_some() {
                            d = d.min((d - 1.0).abs());
                        }
                        worst = worst.max(d);
                    }
                }
                println!("ctransform {dir:4} {space} {prec}: largest difference {worst:.3e}");
                assert!(worst <= tol, "ctransform {dir} {space} ({prec}): {worst:e}");
            }
        }
        // Round trip in f64.
        let col: Vec<f64> = rgb.iter().flatten().copied().collect();
        let there = program.cpu::<f64>(rgb.len(), &[("c", &col[..])], &["Ci"]);
        let back = program.cpu::<f64>(rgb.len(), &[("c", &there[0][..])], &["Oi"]);
        let (d, _) = support::worst(&back[0], &col);
        assert!(d < 1e-12, "{space} round trip: {d:e}");
    }
}

#[test]
fn colour_spaces_extremes_and_the_gpu() {
    // Hue over every extreme; saturation in [0, 1]; value, lightness and RGB components over the
    // non-negative extremes (a negative RGB colour has no hexcone: its saturation can overflow);
    // the linear spaces over every extreme of both signs.
    let ex = support::extremes();
    let pos: Vec<f64> = ex.iter().copied().filter(|&x| x >= 0.0).collect();
    let mut rgb_in = Vec::new();
    for &a in &pos {
        for &b in &pos {
            for &c in &[0.0, 0.5, 1e30] {
                rgb_in.push([a, b, c]);
            }
        }
    }
    let mut hsx_in = Vec::new();
    for &h in &ex {
        for &s in &[0.0, 0.5, 1.0] {
            for &v in &pos {
                hsx_in.push([h, s, v]);
            }
        }
    }
    let mut lin_in = Vec::new();
    for &a in &ex {
        for &b in &ex {
            lin_in.push([a, b, -a]);
        }
    }
    let gpu = patina_runtime::gpu::for_tests();
    for space in ["hsv", "hsl", "xyz", "YIQ"] {
        let program = space_shader(space);
        let linear = space == "xyz" || space == "YIQ";
        let to_in = if linear { &lin_in } else { &rgb_in };
        let from_in = if linear { &lin_in } else { &hsx_in };
        for (dir, inputs, output) in [("to", to_in, "Ci"), ("from", from_in, "Oi")] {
            let col: Vec<f64> = inputs.iter().flatten().copied().collect();
            let ins = [("c", &col[..])];
            let cpu32 = program.cpu::<f32>(inputs.len(), &ins, &[output]);
            support::assert_finite(&format!("ctransform {dir} {space} (f32)"), &cpu32[0], 3);
            let cpu64 = program.cpu::<f64>(inputs.len(), &ins, &[output]);
            support::assert_finite(&format!("ctransform {dir} {space} (f64)"), &cpu64[0], 3);
            if let Some(gpu) = &gpu {
                let got = program.gpu(gpu, inputs.len(), &ins, &[output]);
                support::assert_finite(&format!("ctransform {dir} {space} (GPU)"), &got[0], 3);
                let (d, at) = support::worst(&got[0], &cpu32[0]);
                println!("ctransform {dir:4} {space}: GPU vs interpreter largest difference {d:e}");
                assert!(d == 0.0, "ctransform {dir} {space}: GPU differs by {d:e} at {:?}", inputs[at / 3]);
            }
        }
    }
}
