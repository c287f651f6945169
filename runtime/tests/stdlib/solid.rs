//! Hart's parameterized solid texture (`compiler/stdlib/solid.sl`) on the interpreter (f64 and f32) and on
//! the GPU, against an independent Rust port of APST's formulas (module `hart`, below) on top of
//! a port of Perlin's reference improved noise (module `reference`).
//!
//! What is checked (run with `--nocapture` to see the measured numbers):
//! - f64 mode: the classification f, its analytic gradient, the filter width and the presets
//!   within 1e-12 of the port (relative to the size of the terms); the colour map within 1e-12 of
//!   a port written differently (piece by piece over the knots and periods in the interval);
//! - the colour map's box filter against brute-force numerical integration;
//! - the analytic gradient against central differences of f (f64);
//! - the filter: width 0 is the unfiltered sum, the noise terms drop out one by one as the width
//!   grows and f tends to q + 0.5 sum a_i; the variance of f - q falls with the width;
//! - continuity of the colour map in its index and width (across its internal branch points);
//! - f32 mode: within the measured tolerances of the port evaluated with the f32 roundings of the
//!   noise argument;
//! - the stability sweep: extreme coordinates, matrices, amplitudes, widths and indices give
//!   finite results in f64, f32 and on the GPU;
//! - the GPU (WGSL compute kernel on lavapipe) against the interpreter's f32 mode.

use crate::support;

/// Perlin's ImprovedNoise.java in f64, with the stdlib's reduction of the cell modulo 256 in
/// float (so that the period holds beyond the range of `int`).
mod reference {
    const PERMUTATION: [i32; 256] = patina_test_support::perlin::PERMUTATION;

    fn p(i: i32) -> i32 {
        PERMUTATION[i as usize % 256]
    }

    fn cell(x: f64) -> i32 {
        (x.floor() - 256.0 * (x.floor() * 0.00390625).floor()) as i32 & 255
    }

    pub fn fade(t: f64) -> f64 {
        t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
    }

    pub fn lerp(t: f64, a: f64, b: f64) -> f64 {
        a + t * (b - a)
    }

    pub fn grad(hash: i32, x: f64, y: f64, z: f64) -> f64 {
        let h = hash & 15;
        let u = if h < 8 { x } else { y };
        let v = if h < 4 {
            y
        } else if h == 12 || h == 14 {
            x
        } else {
            z
        };
        (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
    }

    /// The corner hashes h[c] for c = 4 dz + 2 dy + dx, and the fractions.
    fn corners(x: f64, y: f64, z: f64) -> ([i32; 8], [f64; 3]) {
        let (xi, yi, zi) = (cell(x), cell(y), cell(z));
        let a = p(xi) + yi;
        let aa = p(a) + zi;
        let ab = p(a + 1) + zi;
        let b = p(xi + 1) + yi;
        let ba = p(b) + zi;
        let bb = p(b + 1) + zi;
        let h = [p(aa), p(ba), p(ab), p(bb), p(aa + 1), p(ba + 1), p(ab + 1), p(bb + 1)];
        (h, [x - x.floor(), y - y.floor(), z - z.floor()])
    }

    pub fn noise(x: f64, y: f64, z: f64) -> f64 {
        let (h, [x, y, z]) = corners(x, y, z);
        let (u, v, w) = (fade(x), fade(y), fade(z));
        lerp(
            w,
            lerp(v, lerp(u, grad(h[0], x, y, z), grad(h[1], x - 1.0, y, z)), {
                lerp(u, grad(h[2], x, y - 1.0, z), grad(h[3], x - 1.0, y - 1.0, z))
            }),
            lerp(v, lerp(u, grad(h[4], x, y, z - 1.0), grad(h[5], x - 1.0, y, z - 1.0)), {
                lerp(u, grad(h[6], x, y - 1.0, z - 1.0), grad(h[7], x - 1.0, y - 1.0, z - 1.0))
            }),
        )
    }

    /// The analytic gradient, written as the sum over the 8 corners of d/dx of
    /// weight(corner) * dot(gradient, offset): the product rule corner by corner (a different
    /// arrangement from the stdlib's nested interpolation).
    pub fn noise_gradient(x: f64, y: f64, z: f64) -> [f64; 3] {
        let (h, f) = corners(x, y, z);
        let fade_d = |t: f64| 30.0 * t * t * (t - 1.0) * (t - 1.0);
        let mut g = [0.0; 3];
        for (c, &hash) in h.iter().enumerate() {
            let d = [c & 1, (c >> 1) & 1, (c >> 2) & 1].map(|b| b as f64);
            let off = [f[0] - d[0], f[1] - d[1], f[2] - d[2]];
            // weight per axis: fade(f) towards the far corner, 1 - fade(f) towards the near one
            let wt: Vec<f64> =
                (0..3).map(|a| if d[a] == 1.0 { fade(f[a]) } else { 1.0 - fade(f[a]) }).collect();
            let dwt: Vec<f64> =
                (0..3).map(|a| if d[a] == 1.0 { fade_d(f[a]) } else { -fade_d(f[a]) }).collect();
            let dot = grad(hash, off[0], off[1], off[2]);
            let gv = [grad(hash, 1.0, 0.0, 0.0), grad(hash, 0.0, 1.0, 0.0), grad(hash, 0.0, 0.0, 1.0)];
            let weight = wt[0] * wt[1] * wt[2];
            g[0] += dwt[0] * wt[1] * wt[2] * dot + weight * gv[0];
            g[1] += wt[0] * dwt[1] * wt[2] * dot + weight * gv[1];
            g[2] += wt[0] * wt[1] * dwt[2] * dot + weight * gv[2];
        }
        g
    }
}

/// APST's formulas from the paper's definitions (shared/seeds/004 L93-231) with the stdlib's
/// documented guards and conventions, in f64.
#[allow(clippy::needless_range_loop)] // matrix entries read best by their indices
mod hart {
    pub const SNOISE_SCALE: f64 = 0.9649;

    /// One call's parameters. Matrices row by row (`m[4 * row + col]`).
    #[derive(Clone, Copy, Debug)]
    pub struct Params {
        pub q: [f64; 16],
        pub nterms: f64,
        pub amp: f64,
        pub gain: f64,
        pub t: [f64; 16],
        pub lac: f64,
        pub phase: [f64; 3],
        pub fw: f64,
    }

    fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
        let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    }

    fn clamp_point(p: [f64; 3]) -> [f64; 3] {
        p.map(|x| x.clamp(-1e9, 1e9))
    }

    fn entry(m: &[f64; 16], row: usize, col: usize, bound: f64) -> f64 {
        m[4 * row + col].clamp(-bound, bound)
    }

    /// The quadric [s t r 1] Q [s t r 1]^T, eq. (4).
    pub fn quadric(p: [f64; 3], q: &[f64; 16]) -> f64 {
        let s = clamp_point(p);
        let x = [s[0], s[1], s[2], 1.0];
        let mut sum = 0.0;
        for k in 0..4 {
            let mut row = 0.0;
            for j in 0..4 {
                row += x[j] * entry(q, j, k, 1e18);
            }
            sum += row * x[k];
        }
        sum
    }

    /// d q / d s: sum_j x_j (Q_jk + Q_kj), eq. (11) with erratum E9.
    pub fn quadric_gradient(p: [f64; 3], q: &[f64; 16]) -> [f64; 3] {
        let s = clamp_point(p);
        let x = [s[0], s[1], s[2], 1.0];
        let mut g = [0.0; 3];
        for (k, gk) in g.iter_mut().enumerate() {
            for j in 0..4 {
                *gk += x[j] * entry(q, j, k, 1e18) + entry(q, k, j, 1e18) * x[j];
            }
        }
        g
    }

    /// How the precision rounds: identity (f64) or to f32.
    pub type Round = fn(f64) -> f64;

    /// s T for a row vector s (the translation row included), rounding each operation.
    fn affine(r: Round, s: [f64; 3], t: &[f64; 16]) -> [f64; 3] {
        let mut y = [0.0; 3];
        for (k, yk) in y.iter_mut().enumerate() {
            *yk = entry(t, 3, k, 1e9);
            for (j, sj) in s.iter().enumerate() {
                *yk = r(*yk + r(sj * entry(t, j, k, 1e9)));
            }
        }
        y
    }

    fn stretch(t: &[f64; 16]) -> f64 {
        (0..3).map(|k| (0..3).map(|j| entry(t, j, k, 1e9).abs()).sum::<f64>()).fold(0.0, f64::max)
    }

    fn term_weight(k: f64, fw: f64) -> f64 {
        1.0 - smoothstep(0.4, 1.6, k * fw)
    }

    /// The terms' arguments T_i(s), amplitudes a_i, frequencies and fade weights.
    fn terms(r: Round, p: [f64; 3], prm: &Params) -> Vec<([f64; 3], f64, f64, f64)> {
        let s = clamp_point(p).map(r);
        let nt = prm.nterms.clamp(0.0, 8.0);
        let lac = prm.lac.clamp(1.0, 8.0);
        let fw = prm.fw.abs().min(1e30);
        let ph = prm.phase.map(|x| x.clamp(-1e9, 1e9));
        let sigma = stretch(&prm.t);
        let ts = affine(r, s, &prm.t);
        let (mut a, g, mut k) = (prm.amp.clamp(-1e6, 1e6), prm.gain.clamp(-8.0, 8.0), 1.0);
        let mut out = Vec::new();
        let mut i = 0.0;
        while i < nt {
            let x = [0, 1, 2].map(|c| r(r(k * ts[c]) + ph[c]));
            out.push((x, (nt - i).clamp(0.0, 1.0) * a, k, term_weight(k * sigma, fw)));
            a *= g;
            k = r(k * lac);
            i += 1.0;
        }
        out
    }

    /// f = q + sum_i a_i (0.5 + w_i (noise3 - 0.5)), eq. (1) with the filter's fade.
    pub fn solid(r: Round, p: [f64; 3], prm: &Params) -> f64 {
        let mut f = quadric(p, &prm.q);
        for (x, a, _, w) in terms(r, p, prm) {
            f += a * (0.5 + w * (0.5 * SNOISE_SCALE * super::reference::noise(x[0], x[1], x[2])));
        }
        f
    }

    /// d L: T's linear part applied to the row vector d, d clamped to +-1e9.
    fn linear(d: [f64; 3], t: &[f64; 16]) -> [f64; 3] {
        let d = d.map(|x| x.clamp(-1e9, 1e9));
        [0, 1, 2].map(|k| (0..3).map(|j| d[j] * entry(t, j, k, 1e9)).sum())
    }

    /// f over a footprint (prm.fw isotropic, dx and dy the parallelogram): term i is the midpoint
    /// rule for the mean of the noise over k T_0(s) + phase + k t M, t in [-1/2, 1/2], with
    /// n_i = clamp(2 k |M| + 1/2, 1, 8) (fractional) pieces of length 1/n_i from t = -1/2, the last one
    /// cut at 1/2, each probe weighted by its piece's length; M the longer of dx L and dy L,
    /// faded by the footprint one piece covers, sqrt((sigma fw)^2 + (|minor|^2 + (|M| / n_i)^2) / 2).
    pub fn solid_footprint(p: [f64; 3], prm: &Params, dx: [f64; 3], dy: [f64; 3]) -> f64 {
        let len2 = |v: [f64; 3]| v.iter().map(|c| c * c).sum::<f64>();
        let (x, y) = (linear(dx, &prm.t), linear(dy, &prm.t));
        let (major, minor2) = if len2(x) >= len2(y) { (x, len2(y)) } else { (y, len2(x)) };
        let lmajor = len2(major).sqrt();
        let iso = stretch(&prm.t) * prm.fw.abs();
        let mut f = quadric(p, &prm.q);
        for (arg, a, k, _) in terms(|x| x, p, prm) {
            let n = (2.0 * k * lmajor + 0.5).clamp(1.0, 8.0);
            let piece = lmajor / n;
            let w = term_weight(k, (iso * iso + 0.5 * (minor2 + piece * piece)).sqrt());
            let mut sum = 0.0;
            for j in 0..n.ceil() as usize {
                let start = j as f64 / n - 0.5;
                let end = ((j + 1) as f64 / n - 0.5).min(0.5);
                let t = k * 0.5 * (start + end);
                let noise = super::reference::noise(
                    arg[0] + t * major[0],
                    arg[1] + t * major[1],
                    arg[2] + t * major[2],
                );
                sum += (end - start) * noise;
            }
            f += a * (0.5 + w * 0.5 * SNOISE_SCALE * sum);
        }
        f
    }

    /// A bound on the size of f's terms, for relative tolerances.
    pub fn scale(p: [f64; 3], prm: &Params) -> f64 {
        let s = clamp_point(p);
        let x = [s[0], s[1], s[2], 1.0];
        let mut q = 0.0;
        for j in 0..4 {
            for k in 0..4 {
                q += (x[j] * entry(&prm.q, j, k, 1e18) * x[k]).abs();
            }
        }
        q + terms(|x| x, p, prm).iter().map(|t| t.1.abs()).sum::<f64>()
    }

    /// grad f = grad q + sum_i a_i w_i k_i L (0.5 grad noise), eqs. (10)-(12).
    pub fn solid_gradient(r: Round, p: [f64; 3], prm: &Params) -> [f64; 3] {
        let mut g = quadric_gradient(p, &prm.q);
        for (x, a, k, w) in terms(r, p, prm) {
            let dn = super::reference::noise_gradient(x[0], x[1], x[2]).map(|d| 0.5 * SNOISE_SCALE * d);
            for (j, gj) in g.iter_mut().enumerate() {
                let ldn: f64 = (0..3).map(|c| entry(&prm.t, j, c, 1e9) * dn[c]).sum();
                *gj += a * w * k * ldn;
            }
        }
        g
    }

    /// A bound on the size of the gradient's terms.
    pub fn gradient_scale(p: [f64; 3], prm: &Params) -> f64 {
        let s = clamp_point(p);
        let x = [s[0], s[1], s[2], 1.0];
        let mut g = 0.0;
        for j in 0..4 {
            for k in 0..4 {
                g += 2.0 * (x[j] * entry(&prm.q, j, k, 1e18)).abs();
            }
        }
        let sigma: f64 = prm.t[..12].iter().map(|x| x.clamp(-1e9, 1e9).abs()).sum();
        g + terms(|x| x, p, prm).iter().map(|t| 4.0 * t.1.abs() * t.2 * sigma).sum::<f64>()
    }

    pub fn filterwidth(g: [f64; 3], fw: f64) -> f64 {
        let g = g.map(|x| x.clamp(-1e18, 1e18));
        (fw.abs().min(1e30) * (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt()).min(1e30)
    }

    pub const MOD: f64 = 1.0;
    pub const CLAMP: f64 = 0.0;

    /// The ramp through `clut` (knots at j / (n - 1)) at an index in [0, 1].
    fn ramp(clut: &[[f64; 3]], x: f64) -> [f64; 3] {
        let m = (clut.len() - 1) as f64;
        let y = x * m;
        let j = y.floor().clamp(0.0, m - 1.0);
        let t = y - j;
        let (c0, c1) = (clut[j as usize], clut[j as usize + 1]);
        [0, 1, 2].map(|c| c0[c] + t * (c1[c] - c0[c]))
    }

    /// The extended map at any index: frac(x) (modulo) or clamp(x, 0, 1).
    pub fn ramp_ext(clut: &[[f64; 3]], mode: f64, x: f64) -> [f64; 3] {
        if mode == MOD { ramp(clut, x - x.floor()) } else { ramp(clut, x.clamp(0.0, 1.0)) }
    }

    /// The box average of the extended map over [f - w/2, f + w/2], written piece by piece:
    /// the interval is cut at every knot (and period boundary), each piece being linear, so its
    /// integral is its length times the value at its midpoint; whole periods beyond the first
    /// few count as the period's mean (modulo) and the parts outside [0, 1] as the end colours
    /// (clamp).
    pub fn colormap(clut: &[[f64; 3]], mode: f64, f: f64, width: f64) -> [f64; 3] {
        let n = clut.len();
        if n < 2 {
            return clut[0];
        }
        let m = (n - 1) as f64;
        let w = width.abs().min(1e30);
        let h = (0.5 * w).min(1e30 / m);
        if h * m < 5e-7 {
            return ramp_ext(clut, mode, f);
        }
        // In index units: [a, b]; for the modulo mode, shifted so that f is in [0, 1).
        let f0 = if mode == MOD { f - f.floor() } else { f };
        let (a, b) = (f0 - h, f0 + h);
        let mut sum = [0.0; 3];
        let mut add = |len: f64, c: [f64; 3]| {
            for k in 0..3 {
                sum[k] += len * c[k];
            }
        };
        let (mut lo, mut hi) = (a, b);
        if mode == MOD {
            // the map has period 1: whole periods count as the period's mean, and what is left
            // is the integral from a over the remainder
            let len = b - a;
            let periods = len.floor();
            let mean: Vec<f64> = (0..3)
                .map(|c| (0..n - 1).map(|j| 0.5 * (clut[j][c] + clut[j + 1][c])).sum::<f64>() / m)
                .collect();
            add(periods, [mean[0], mean[1], mean[2]]);
            hi = a + (len - periods);
        } else {
            if b <= 0.0 {
                return clut[0];
            }
            if a >= 1.0 {
                return clut[n - 1];
            }
            if a < 0.0 {
                add(-a, clut[0]);
                lo = 0.0;
            }
            if b > 1.0 {
                add(b - 1.0, clut[n - 1]);
                hi = 1.0;
            }
        }
        if hi > lo {
            piecewise(clut, mode, lo, hi, &mut add);
        }
        sum.map(|s| s / (b - a))
    }

    /// Adds the integral over [lo, hi] of the extended map, cut at the knots j / m.
    fn piecewise(clut: &[[f64; 3]], mode: f64, lo: f64, hi: f64, add: &mut impl FnMut(f64, [f64; 3])) {
        let m = (clut.len() - 1) as f64;
        let mut x = lo;
        while x < hi {
            let next = (((x * m).floor() + 1.0) / m).min(hi);
            let next = if next <= x { hi } else { next };
            add(next - x, ramp_ext(clut, mode, 0.5 * (x + next)));
            x = next;
        }
    }
}

/// The parameters the test shader reads, in its order.
const SHADER: &str = "#include <solid.sl>\n\
    surface t(varying matrix Q = 0; varying float nterms = 4, amp = 0.5, gain = 0.5;\n\
              varying matrix T = 1; varying float lac = 2; varying vector phase = 0;\n\
              varying float fw = 0, cf = 0, cw = 0;\n\
              output varying float f = 0, fwo = 0; output varying vector g = 0;\n\
              output varying color cmod = 0, cclamp = 0, wood = 0, marble = 0, clouds = 0, fire = 0)\n\
    {\n\
        f = hart_solid(P, Q, nterms, amp, gain, T, lac, phase, fw);\n\
        g = hart_solid_gradient(P, Q, nterms, amp, gain, T, lac, phase, fw);\n\
        fwo = hart_filterwidth(g, fw);\n\
        constant color clut[4] = {color(0.1, 0.2, 0.3), color(0.9, 0.5, 0.1),\n\
            color(0.4, 1, 0.6), color(0, 0.3, 0.8)};\n\
        cmod = hart_colormap(cf, cw, HART_MOD, clut, 4);\n\
        cclamp = hart_colormap(cf, cw, HART_CLAMP, clut, 4);\n\
        wood = hart_wood(P, fw);\n\
        marble = hart_marble(P, fw);\n\
        clouds = hart_clouds(P, fw);\n\
        fire = hart_fire(P, zcomp(phase), fw);\n\
        Ci = 0;\n\
        Oi = 1;\n\
    }\n";

const CLUT: [[f64; 3]; 4] = [[0.1, 0.2, 0.3], [0.9, 0.5, 0.1], [0.4, 1.0, 0.6], [0.0, 0.3, 0.8]];

const OUTPUTS: [&str; 9] = ["f", "g", "fwo", "cmod", "cclamp", "wood", "marble", "clouds", "fire"];

/// One evaluation's inputs.
#[derive(Clone, Copy, Debug)]
struct Args {
    p: [f64; 3],
    prm: hart::Params,
    cf: f64,
    cw: f64,
}

impl Args {
    fn to_f32(self) -> Args {
        let r = |x: f64| f64::from(x as f32);
        let prm = self.prm;
        Args {
            p: self.p.map(r),
            prm: hart::Params {
                q: prm.q.map(r),
                nterms: r(prm.nterms),
                amp: r(prm.amp),
                gain: r(prm.gain),
                t: prm.t.map(r),
                lac: r(prm.lac),
                phase: prm.phase.map(r),
                fw: r(prm.fw),
            },
            cf: r(self.cf),
            cw: r(self.cw),
        }
    }
}

/// The outputs at one point.
#[derive(Clone, Copy, Debug)]
struct Out {
    f: f64,
    g: [f64; 3],
    fwo: f64,
    cmod: [f64; 3],
    cclamp: [f64; 3],
    presets: [[f64; 3]; 4],
}

/// The presets' parameters, as documented in solid.sl.
fn preset(which: usize, fw: f64, phase: f64) -> (hart::Params, f64, Vec<[f64; 3]>) {
    let diag = |a: f64, b: f64, c: f64| [a, 0., 0., 0., 0., b, 0., 0., 0., 0., c, 0., 0., 0., 0., 1.];
    let mut q_r = [0.0; 16];
    q_r[11] = 0.5;
    q_r[14] = 0.5;
    let mut q_wood = [0.0; 16];
    q_wood[0] = 1.0;
    q_wood[5] = 1.0;
    let fractal = |q: [f64; 16], t: [f64; 16], ph: [f64; 3]| hart::Params {
        q,
        nterms: 4.0,
        amp: 0.5,
        gain: 0.5,
        t,
        lac: 2.0,
        phase: ph,
        fw,
    };
    match which {
        0 => (
            hart::Params {
                q: q_wood,
                nterms: 1.0,
                amp: 1.0,
                gain: 1.0,
                t: diag(4.0, 4.0, 1.0),
                lac: 1.0,
                phase: [0.0; 3],
                fw,
            },
            hart::MOD,
            vec![[0.86, 0.66, 0.42], [0.50, 0.30, 0.14]],
        ),
        1 => (
            fractal(q_r, diag(2.0, 2.0, 2.0), [0.0; 3]),
            hart::MOD,
            vec![
                [0.93, 0.92, 0.89],
                [0.85, 0.84, 0.82],
                [0.62, 0.62, 0.66],
                [0.30, 0.30, 0.36],
                [0.70, 0.70, 0.72],
                [0.93, 0.92, 0.89],
            ],
        ),
        2 => (
            fractal([0.0; 16], diag(2.0, 2.0, 2.0), [0.0; 3]),
            hart::CLAMP,
            vec![[0.25, 0.45, 0.85], [1.0, 1.0, 1.0]],
        ),
        _ => (
            fractal(q_r, diag(2.0, 0.0, 2.0), [0.0, 0.0, phase]),
            hart::CLAMP,
            vec![[0.0, 0.0, 0.0], [0.75, 0.1, 0.0], [1.0, 0.5, 0.0], [1.0, 0.9, 0.3], [1.0, 1.0, 1.0]],
        ),
    }
}

/// Every output by the port.
fn reference(a: &Args, r: hart::Round) -> Out {
    let g = hart::solid_gradient(r, a.p, &a.prm);
    let presets = [0, 1, 2, 3].map(|k| {
        let (prm, mode, clut) = preset(k, a.prm.fw, a.prm.phase[2]);
        let f = hart::solid(r, a.p, &prm);
        let w = hart::filterwidth(hart::solid_gradient(r, a.p, &prm), prm.fw);
        hart::colormap(&clut, mode, f, w)
    });
    Out {
        f: hart::solid(r, a.p, &a.prm),
        g,
        fwo: hart::filterwidth(g, a.prm.fw),
        cmod: hart::colormap(&CLUT, hart::MOD, a.cf, a.cw),
        cclamp: hart::colormap(&CLUT, hart::CLAMP, a.cf, a.cw),
        presets,
    }
}

fn identity(x: f64) -> f64 {
    x
}

fn to_f32(x: f64) -> f64 {
    f64::from(x as f32)
}

/// The inputs as columns, in the shader's order.
fn columns(args: &[Args]) -> Vec<(&'static str, Vec<f64>)> {
    let col = |f: &dyn Fn(&Args) -> Vec<f64>| -> Vec<f64> { args.iter().flat_map(f).collect() };
    vec![
        ("P", col(&|a| a.p.to_vec())),
        ("Q", col(&|a| a.prm.q.to_vec())),
        ("nterms", col(&|a| vec![a.prm.nterms])),
        ("amp", col(&|a| vec![a.prm.amp])),
        ("gain", col(&|a| vec![a.prm.gain])),
        ("T", col(&|a| a.prm.t.to_vec())),
        ("lac", col(&|a| vec![a.prm.lac])),
        ("phase", col(&|a| a.prm.phase.to_vec())),
        ("fw", col(&|a| vec![a.prm.fw])),
        ("cf", col(&|a| vec![a.cf])),
        ("cw", col(&|a| vec![a.cw])),
    ]
}

fn unpack(n: usize, out: &[Vec<f64>]) -> Vec<Out> {
    let v3 = |c: &Vec<f64>, i: usize| [c[3 * i], c[3 * i + 1], c[3 * i + 2]];
    (0..n)
        .map(|i| Out {
            f: out[0][i],
            g: v3(&out[1], i),
            fwo: out[2][i],
            cmod: v3(&out[3], i),
            cclamp: v3(&out[4], i),
            presets: [v3(&out[5], i), v3(&out[6], i), v3(&out[7], i), v3(&out[8], i)],
        })
        .collect()
}

fn eval<F: patina_compiler::backend::cpu::scalar::Real>(
    program: &support::Program,
    args: &[Args],
) -> Vec<Out> {
    let cols = columns(args);
    let inputs: Vec<(&str, &[f64])> = cols.iter().map(|(n, c)| (*n, &c[..])).collect();
    unpack(args.len(), &program.cpu::<F>(args.len(), &inputs, &OUTPUTS))
}

fn eval_gpu(program: &support::Program, gpu: &patina_runtime::gpu::Gpu, args: &[Args]) -> Vec<Out> {
    let cols = columns(args);
    let inputs: Vec<(&str, &[f64])> = cols.iter().map(|(n, c)| (*n, &c[..])).collect();
    unpack(args.len(), &program.gpu(gpu, args.len(), &inputs, &OUTPUTS))
}

/// Random argument sets of ordinary use: points within ±4, symmetric Q with entries in ±1,
/// T with entries in ±2, 0 to 8 terms (fractional counts too), amplitudes within ±1, gains in
/// [0, 1], lacunarities in [1.5, 2.5], phases within ±2, filter widths 0 or 1e-4 to 1, colour
/// indices within ±3 and colour widths 0 or 1e-8 to 10.
fn ordinary_args(count: usize, seed: u64) -> Vec<Args> {
    let mut rng = support::Rng(seed);
    (0..count)
        .map(|i| {
            let mut q = [0.0; 16];
            for r in 0..4 {
                for c in r..4 {
                    q[4 * r + c] = rng.range(-1.0, 1.0);
                    q[4 * c + r] = q[4 * r + c];
                }
            }
            let mut t = [0.0; 16];
            for x in t.iter_mut().take(12) {
                *x = rng.range(-2.0, 2.0);
            }
            for x in t.iter_mut().skip(12).take(3) {
                *x = rng.range(-3.0, 3.0);
            }
            t[15] = 1.0;
            let nterms = if i % 3 == 0 { rng.range(0.0, 8.0) } else { rng.range(0.0, 8.0).floor() };
            let fw = if i % 4 == 0 { 0.0 } else { 10f64.powf(rng.range(-4.0, 0.0)) };
            let cw = if i % 5 == 0 { 0.0 } else { 10f64.powf(rng.range(-8.0, 1.0)) };
            Args {
                p: rng.point(-4.0, 4.0),
                prm: hart::Params {
                    q,
                    nterms,
                    amp: rng.range(-1.0, 1.0),
                    gain: rng.range(0.0, 1.0),
                    t,
                    lac: rng.range(1.5, 2.5),
                    phase: rng.point(-2.0, 2.0),
                    fw,
                },
                cf: rng.range(-3.0, 3.0),
                cw,
            }
        })
        .collect()
}

/// The largest relative error of the port comparisons, per output family.
#[derive(Default, Debug)]
struct Worst {
    f: f64,
    g: f64,
    fwo: f64,
    cmap: f64,
    presets: f64,
}

/// Compares `out` with the port at `args`, with the tolerances `tol` (relative to each value's
/// scale), returning the largest scaled errors.
fn compare(args: &[Args], out: &[Out], r: hart::Round, tol: &Worst, what: &str) -> Worst {
    let mut w = Worst::default();
    for (a, o) in args.iter().zip(out) {
        let e = reference(a, r);
        let fs = 1.0 + hart::scale(a.p, &a.prm);
        let gs = 1.0 + hart::gradient_scale(a.p, &a.prm);
        let err = (o.f - e.f).abs() / fs;
        w.f = w.f.max(err);
        assert!(err <= tol.f, "{what}: f at {a:?} = {}, port {}", o.f, e.f);
        for k in 0..3 {
            let err = (o.g[k] - e.g[k]).abs() / gs;
            w.g = w.g.max(err);
            assert!(err <= tol.g, "{what}: grad at {a:?} = {:?}, port {:?}", o.g, e.g);
        }
        let err = (o.fwo - e.fwo).abs() / (gs * a.prm.fw.abs().max(1e-30));
        let err = if a.prm.fw == 0.0 { (o.fwo - e.fwo).abs() } else { err };
        w.fwo = w.fwo.max(err);
        assert!(err <= tol.fwo, "{what}: filter width at {a:?} = {}, port {}", o.fwo, e.fwo);
        for k in 0..3 {
            let err = (o.cmod[k] - e.cmod[k]).abs().max((o.cclamp[k] - e.cclamp[k]).abs());
            w.cmap = w.cmap.max(err);
            assert!(
                err <= tol.cmap,
                "{what}: colour map at f {} width {}: mod {:?} (port {:?}), clamp {:?} (port {:?})",
                a.cf,
                a.cw,
                o.cmod,
                e.cmod,
                o.cclamp,
                e.cclamp
            );
        }
        for (p, (x, y)) in o.presets.iter().zip(&e.presets).enumerate() {
            for k in 0..3 {
                let err = (x[k] - y[k]).abs();
                w.presets = w.presets.max(err);
                assert!(err <= tol.presets, "{what}: preset {p} at {a:?} = {x:?}, port {y:?}");
            }
        }
    }
    w
}

#[test]
fn f64_mode_matches_the_port() {
    let program = support::program(SHADER);
    let args = ordinary_args(2000, 1);
    let out = eval::<f64>(&program, &args);
    let tol = Worst { f: 1e-12, g: 1e-12, fwo: 1e-12, cmap: 1e-12, presets: 1e-12 };
    let w = compare(&args, &out, identity, &tol, "f64");
    println!("f64 mode, {} argument sets: largest scaled errors {w:?}", args.len());
}

/// The f32 mode's tolerances against the port at the f32 inputs (with the noise argument
/// rounded as the f32 mode rounds it), relative to the size of the terms: the noise's own f32
/// error (2e-6 per term, stdlib_noise.rs) and the sums' rounding; the gradient adds the f32
/// error of the fade derivatives; the colour map's integral form loses a few ulp to
/// cancellation. A preset's colour moves by the colour slope times f's error (wood's index runs
/// to s^2 + t^2 = 32 at |p| = 4). Measured largest errors: f 1.4e-7, gradient 4.6e-8, filter
/// width 4.9e-8, colour map 2.6e-7, presets 7.7e-6 (printed).
const F32_TOL: Worst = Worst { f: 2e-6, g: 2e-6, fwo: 1e-5, cmap: 1e-5, presets: 2e-4 };

#[test]
fn f32_mode_is_close_to_the_port() {
    let program = support::program(SHADER);
    let args = ordinary_args(2000, 2);
    let out = eval::<f32>(&program, &args);
    let args32: Vec<Args> = args.iter().map(|a| a.to_f32()).collect();
    let w = compare(&args32, &out, to_f32, &F32_TOL, "f32");
    println!("f32 mode, {} argument sets: largest scaled errors {w:?}", args.len());
}

#[test]
fn colour_map_is_the_box_average() {
    // Brute force: the midpoint rule over 20 000 cells of the interval, f64 in the port's ramp.
    let program = support::program(SHADER);
    let mut rng = support::Rng(9);
    let mut args = ordinary_args(300, 3);
    for a in &mut args {
        a.cf = rng.range(-2.0, 3.0);
        a.cw = [0.0, 1e-3, 0.05, 0.3, 0.7, 1.3, 4.0][rng.next() as usize % 7] * rng.range(0.5, 1.5);
    }
    let out = eval::<f64>(&program, &args);
    let mut worst = 0.0f64;
    for (a, o) in args.iter().zip(&out) {
        for (mode, got) in [(hart::MOD, o.cmod), (hart::CLAMP, o.cclamp)] {
            let cells = 20_000;
            let mut avg = [0.0; 3];
            if a.cw == 0.0 {
                avg = hart::ramp_ext(&CLUT, mode, a.cf);
            } else {
                for i in 0..cells {
                    let x = a.cf - 0.5 * a.cw + a.cw * (i as f64 + 0.5) / cells as f64;
                    let c = hart::ramp_ext(&CLUT, mode, x);
                    for k in 0..3 {
                        avg[k] += c[k] / cells as f64;
                    }
                }
            }
            for k in 0..3 {
                let err = (got[k] - avg[k]).abs();
                worst = worst.max(err);
                // midpoint rule: exact on linear pieces, O(1/cells) where a jump or knot falls in a cell
                assert!(err <= 2e-4, "mode {mode} f {} width {}: {got:?}, brute force {avg:?}", a.cf, a.cw);
            }
        }
    }
    println!("colour map against brute-force integration: largest difference {worst:e}");
}

#[test]
fn gradient_matches_central_differences() {
    let program = support::program(SHADER);
    let base = ordinary_args(300, 4);
    // The step: 1e-4 of the finest term's feature size (its frequency is at most
    // lacunarity^(nterms - 1) times the sum of |T|'s entries), so that the truncation error
    // (h^2 / 6 times the third derivative) stays far below the tolerance.
    let step = |a: &Args| {
        let sigma: f64 = a.prm.t[..12].iter().map(|x| x.abs()).sum();
        1e-4 / (1.0 + sigma * a.prm.lac.powf(a.prm.nterms.ceil() - 1.0))
    };
    let mut args = Vec::new();
    for a in &base {
        let h = step(a);
        args.push(*a);
        for axis in 0..3 {
            for sign in [-1.0, 1.0] {
                let mut b = *a;
                b.p[axis] += sign * h;
                args.push(b);
            }
        }
    }
    let out = eval::<f64>(&program, &args);
    let mut worst = 0.0f64;
    for (k, chunk) in out.chunks_exact(7).enumerate() {
        let scale = 1.0 + hart::gradient_scale(base[k].p, &base[k].prm);
        let h = step(&base[k]);
        for axis in 0..3 {
            let fd = (chunk[2 + 2 * axis].f - chunk[1 + 2 * axis].f) / (2.0 * h);
            let err = (chunk[0].g[axis] - fd).abs() / scale;
            worst = worst.max(err);
            // central differences: O(h^2) truncation (third derivative) plus O(eps f / h) rounding
            assert!(err <= 1e-6, "axis {axis} at {:?}: analytic {:?}, difference {fd}", base[k], chunk[0].g);
        }
    }
    println!("analytic gradient against central differences: largest scaled error {worst:e}");
}

#[test]
fn filtering_drops_terms_and_tends_to_the_mean() {
    let program = support::program(SHADER);
    let base: Vec<Args> = ordinary_args(400, 5)
        .into_iter()
        .map(|mut a| {
            a.prm.nterms = 6.0;
            a.prm.gain = 0.6;
            a
        })
        .collect();
    let widths = [0.0, 1e-4, 1e-3, 1e-2, 0.03, 0.1, 0.3, 1.0, 10.0, 1e30];
    let mut args = Vec::new();
    for a in &base {
        for w in widths {
            let mut b = *a;
            b.prm.fw = w;
            args.push(b);
        }
    }
    let out = eval::<f64>(&program, &args);
    let mut variance = vec![0.0; widths.len()];
    for (k, chunk) in out.chunks_exact(widths.len()).enumerate() {
        let a = &base[k];
        let q = hart::quadric(a.p, &a.prm.q);
        // the mean: q + 0.5 sum a_i
        let mut mean = q;
        let mut amp = a.prm.amp;
        for _ in 0..6 {
            mean += 0.5 * amp;
            amp *= a.prm.gain;
        }
        let mut unfiltered = *a;
        unfiltered.prm.fw = 0.0;
        let plain = hart::solid(identity, a.p, &unfiltered.prm);
        assert!((chunk[0].f - plain).abs() <= 1e-12 * (1.0 + plain.abs()), "width 0 is the unfiltered sum");
        // the number of terms still (partly) present never grows with the width
        let sigma = (0..3).map(|c| (0..3).map(|j| a.prm.t[4 * j + c].abs()).sum::<f64>()).fold(0.0, f64::max);
        let mut last = usize::MAX;
        for (i, w) in widths.iter().enumerate() {
            let live = (0..6).filter(|&t| a.prm.lac.powi(t) * sigma * w < 1.6).count();
            assert!(live <= last);
            last = live;
            variance[i] += (chunk[i].f - mean).powi(2) / base.len() as f64;
            if live == 0 {
                assert!(
                    (chunk[i].f - mean).abs() <= 1e-12 * (1.0 + mean.abs()),
                    "width {w}: {} not the mean {mean}",
                    chunk[i].f
                );
                assert!(
                    chunk[i]
                        .g
                        .iter()
                        .zip(hart::quadric_gradient(a.p, &a.prm.q))
                        .all(|(x, y)| (x - y).abs() <= 1e-12 * (1.0 + y.abs())),
                    "width {w}: the gradient is the quadric's"
                );
            }
        }
    }
    println!("mean squared distance of f from q + 0.5 sum a_i, per width {widths:?}:\n  {variance:?}");
    for i in 1..widths.len() {
        assert!(variance[i] <= variance[i - 1] * 1.05 + 1e-15, "variance grows at width {}", widths[i]);
    }
    assert!(variance[widths.len() - 1] < 1e-20 && variance[0] > 1e-3);
}

/// A slow zoom changes the footprint continuously, and so must the filtered texture: the noise
/// terms' probe counts are fractional (hart_term_probes), where a whole count was a step that
/// made f jump by ~1e-2 as the count changed (flicker). Marble's four terms at eight points, the
/// footprint (a receding plane's, 6 times longer than wide) scaled by 1.0015 per frame from 0.01
/// to 3 texture units: f's largest change between two frames stays within what its slope allows,
/// on the interpreter in f32 and f64 and on the GPU.
#[test]
fn filtered_value_is_continuous_in_a_zoom() {
    let program = support::program(
        "#include <solid.sl>\n\
         surface t(varying vector dx = 0, dy = 0; output varying float f = 0) {\n\
             f = hart_solid_footprint(P, (0, 0, 0, 0,  0, 0, 0, 0,  0, 0, 0, 0.5,  0, 0, 0.5, 0), 4, 0.5, 0.5,\n\
                                      (2, 0, 0, 0,  0, 2, 0, 0,  0, 0, 2, 0,  0, 0, 0, 1), 2, vector(0), 0, dx, dy);\n\
             Ci = 0; Oi = 1;\n\
         }",
    );
    let frames = (3.0f64 / 0.01).ln() / 1.0015f64.ln();
    let frames = frames.ceil() as usize;
    let points = 8;
    let mut rng = support::Rng(0x2005);
    let mut cols: Vec<Vec<f64>> = vec![Vec::new(); 3];
    for _ in 0..points {
        let p = [rng.range(-3.0, 3.0), rng.range(-3.0, 3.0), rng.range(-3.0, 3.0)];
        for i in 0..frames {
            let z = 0.01 * 1.0015f64.powi(i as i32);
            cols[0].extend(p);
            cols[1].extend([z * 0.6, z * 0.3, z * 0.1]);
            cols[2].extend([-z * 0.05, z * 0.08, z * 0.02]);
        }
    }
    let n = points * frames;
    let inputs: Vec<(&str, &[f64])> =
        ["P", "dx", "dy"].into_iter().zip(cols.iter().map(|c| &c[..])).collect();
    let mut runs = vec![
        ("f64", program.cpu::<f64>(n, &inputs, &["f"]).remove(0)),
        ("f32", program.cpu::<f32>(n, &inputs, &["f"]).remove(0)),
    ];
    if let Some(gpu) = patina_runtime::gpu::for_tests() {
        runs.push(("gpu", program.gpu(gpu, n, &inputs, &["f"]).remove(0)));
    }
    for (what, f) in runs {
        let jump = (0..points)
            .flat_map(|k| (1..frames).map(move |i| k * frames + i))
            .map(|i| (f[i] - f[i - 1]).abs())
            .fold(0.0, f64::max);
        println!("{what}: largest change of f between two frames {jump:.2e}");
        assert!(jump < 1e-3, "{what}: f jumps by {jump:e} between two frames of the zoom");
    }
}

#[test]
fn colour_map_is_continuous() {
    // Across the branch points of hart_colormap: half-widths 5e-7 and 0.5 segment (widths
    // 1e-6 / 3 and 1 / 3 for 4 colours), the knots and the period boundary, in f64 and f32.
    let program = support::program(SHADER);
    let mut args = Vec::new();
    let base = ordinary_args(1, 6)[0];
    let mut rng = support::Rng(7);
    for _ in 0..200 {
        let f = rng.range(-1.5, 2.5);
        for w in [1e-6 / 3.0, 1.0 / 3.0, rng.range(0.0, 3.0)] {
            for (df, dw) in [(0.0, 0.0), (0.0, -1e-9), (0.0, 1e-9), (-1e-9, 0.0), (1e-9, 0.0)] {
                let mut a = base;
                a.cf = f + df;
                a.cw = w + dw;
                args.push(a);
            }
        }
        for knot in [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0] {
            for (df, w) in [(-1e-9, 0.0), (1e-9, 0.0), (-1e-9, 0.1), (1e-9, 0.1)] {
                let mut a = base;
                a.cf = knot + df;
                a.cw = w;
                args.push(a);
            }
        }
    }
    let out = eval::<f64>(&program, &args);
    let mut worst = 0.0f64;
    let mut i = 0;
    for _ in 0..200 {
        for _ in 0..3 {
            let c = &out[i..i + 5];
            for o in &c[1..] {
                for k in 0..3 {
                    let jump = (o.cmod[k] - c[0].cmod[k]).abs().max((o.cclamp[k] - c[0].cclamp[k]).abs());
                    worst = worst.max(jump);
                    assert!(
                        jump <= 1e-6,
                        "colour map jumps by {jump} at f {} width {}",
                        args[i].cf,
                        args[i].cw
                    );
                }
            }
            i += 5;
        }
        for _ in 0..4 {
            // across a knot, width 0: continuous in the clamp mode at every knot, and in the
            // modulo mode at the inner ones (0 and 1 are the period's jump, unfiltered)
            let c = &out[i..i + 4];
            for k in 0..3 {
                let clamp_jump = (c[0].cclamp[k] - c[1].cclamp[k]).abs();
                assert!(clamp_jump <= 1e-6, "clamp map jumps at {}", args[i].cf);
                let filtered =
                    (c[2].cmod[k] - c[3].cmod[k]).abs().max((c[2].cclamp[k] - c[3].cclamp[k]).abs());
                assert!(filtered <= 1e-6, "filtered map jumps at {}", args[i].cf);
            }
            i += 4;
        }
    }
    println!("colour map: largest change for index or width ± 1e-9 at the branch points {worst:e}");
}

/// The sweep: each parameter at the extremes of issue 7, the rest ordinary.
fn extreme_args() -> Vec<Args> {
    let ext = support::extremes();
    let base = ordinary_args(8, 8);
    let mut args = Vec::new();
    for (k, b) in base.iter().enumerate() {
        for &x in &ext {
            let mut a = *b;
            a.p = [x, -x * 0.5, x];
            args.push(a);
            let mut a = *b;
            a.p[k % 3] = x;
            a.prm.q = [x; 16];
            args.push(a);
            let mut a = *b;
            a.prm.t = [x; 16];
            a.prm.phase = [x; 3];
            args.push(a);
            let mut a = *b;
            a.prm.amp = x;
            a.prm.gain = x;
            a.prm.lac = x;
            a.prm.nterms = if k % 2 == 0 { x } else { 30.0 };
            args.push(a);
            let mut a = *b;
            a.prm.fw = x;
            a.cf = x;
            a.cw = ext[(k * 7 + 3) % ext.len()];
            args.push(a);
            let mut a = *b;
            a.cf = b.cf;
            a.cw = x;
            args.push(a);
        }
    }
    args
}

fn assert_all_finite(what: &str, args: &[Args], out: &[Out]) {
    for (a, o) in args.iter().zip(out) {
        let mut values = vec![o.f, o.fwo];
        values.extend(o.g);
        values.extend(o.cmod);
        values.extend(o.cclamp);
        values.extend(o.presets.iter().flatten());
        assert!(values.iter().all(|v| v.is_finite()), "{what}: not finite at {a:?}: {o:?}");
    }
}

#[test]
fn extremes_are_finite_in_both_precisions() {
    let program = support::program(SHADER);
    let args = extreme_args();
    assert_all_finite("f64", &args, &eval::<f64>(&program, &args));
    let cpu = eval::<f32>(&program, &args);
    assert_all_finite("f32", &args, &cpu);
    println!(
        "{} extreme argument sets finite in f64 and f32 (on the GPU: gpu_matches_the_interpreter)",
        args.len()
    );
}

/// The GPU's tolerances against the interpreter's f32 mode, relative to each value's scale.
/// solid.sl uses no transcendental function (the noise is bit-exact on both, smoothstep is
/// written out, sqrt is exact), and in small kernels the two agree to the bit (f, q, the noise,
/// the gradient, the filter width and the colour map at the same inputs); in this large kernel
/// lavapipe's results differ from the interpreter's by a few ulp in the gradient, the filter
/// width and the colour map (measured 6e-8, 2.4e-7, 1.8e-7 scaled), presumably from
/// reassociation or contraction that WGSL allows. A preset's box-filtered modulo map amplifies
/// such a difference where the filter straddles the map's jump (wood: latewood back to
/// earlywood, a jump of 0.36 over a width of a few hundredths): measured 2.1e-5 there.
const GPU_TOL: f64 = 1e-6;
const GPU_TOL_PRESETS: f64 = 1e-4;

#[test]
fn gpu_matches_the_interpreter() {
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let program = support::program(SHADER);
    let mut args = ordinary_args(1500, 10);
    args.extend(extreme_args());
    let args: Vec<Args> = args.iter().map(|a| a.to_f32()).collect();
    let cpu = eval::<f32>(&program, &args);
    // One kernel for both checks: it is large (four presets besides the general function), and
    // lavapipe's compilation of it is most of this test's time.
    let out = eval_gpu(&program, gpu, &args);
    assert_all_finite("gpu", &args, &out);
    let mut worst = [0.0f64; 9];
    let mut identical = 0;
    let mut total = 0;
    for ((a, c), g) in args.iter().zip(&cpu).zip(&out) {
        let fs = 1.0 + hart::scale(a.p, &a.prm).min(1e30);
        let gs = 1.0 + hart::gradient_scale(a.p, &a.prm).min(1e30);
        let mut pairs: Vec<(usize, f64, f64, f64)> =
            vec![(0, c.f, g.f, fs), (2, c.fwo, g.fwo, 1.0 + c.fwo.abs())];
        for k in 0..3 {
            pairs.push((1, c.g[k], g.g[k], gs));
            pairs.push((3, c.cmod[k], g.cmod[k], 1.0));
            pairs.push((4, c.cclamp[k], g.cclamp[k], 1.0));
            for p in 0..4 {
                pairs.push((5 + p, c.presets[p][k], g.presets[p][k], 1.0));
            }
        }
        for (which, x, y, scale) in pairs {
            total += 1;
            identical += usize::from(x == y);
            let err = (x - y).abs() / scale;
            worst[which] = worst[which].max(err);
            let tol = if which >= 5 { GPU_TOL_PRESETS } else { GPU_TOL };
            assert!(err <= tol, "{} at {a:?}: interpreter {x:e}, gpu {y:e}", OUTPUTS[which]);
        }
    }
    println!("{} argument sets: {identical} of {total} values identical", args.len());
    println!("largest scaled GPU - interpreter difference per output {OUTPUTS:?}:\n  {worst:?}");
}

/// The footprint filter: `hart_footprint_width` is APST's ||grad_xy f|| (9) joined with the
/// isotropic width, `hart_term_footprint` carries the footprint through T's linear part, and a
/// preset over a footprint is the colour map of f (each term the mean of its probes along the
/// footprint's major axis) at the width of f's gradient, its terms faded by that footprint;
/// within 1e-12 (widths) and 1e-9 (colours) of the port in f64, at random gradients, footprints
/// (isotropic, anisotropic, both) and points, for marble (T = 2 I) and wood (T = diag(4, 4, 1),
/// where the footprint along r counts a quarter).
#[test]
fn footprint_filter_is_apst_9_and_matches_the_port() {
    let program = support::program(
        "#include <solid.sl>\n\
         surface t(varying vector grad = 0, dx = 0, dy = 0; varying float fw = 0;\n\
                   output varying float width = 0, tf = 0; output varying color marble = 0, wood = 0) {\n\
             width = hart_footprint_width(grad, fw, dx, dy);\n\
             tf = hart_term_footprint((4, 0, 0, 0,  0, 4, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1), fw, dx, dy);\n\
             marble = hart_marble_footprint(P, fw, dx, dy);\n\
             wood = hart_wood_footprint(P, fw, dx, dy);\n\
             Ci = 0; Oi = 1;\n\
         }",
    );
    let mut rng = support::Rng(0x50f7);
    let n = 300;
    let mut cols: Vec<Vec<f64>> = vec![Vec::new(); 5];
    for i in 0..n {
        let v = |rng: &mut support::Rng, s: f64| [0; 3].map(|_| rng.range(-s, s));
        cols[0].extend(v(&mut rng, 4.0));
        cols[1].extend(v(&mut rng, 3.0));
        // a third of the footprints isotropic only, a third anisotropic only, a third both
        let (dx, dy) = if i % 3 == 0 { ([0.0; 3], [0.0; 3]) } else { (v(&mut rng, 0.3), v(&mut rng, 0.3)) };
        cols[2].extend(dx);
        cols[3].extend(dy);
        cols[4].push(if i % 3 == 1 { 0.0 } else { rng.range(0.0, 0.3) });
    }
    let names = ["P", "grad", "dx", "dy", "fw"];
    let inputs: Vec<(&str, &[f64])> = names.iter().zip(&cols).map(|(n, c)| (*n, &c[..])).collect();
    let out = program.cpu::<f64>(n, &inputs, &["width", "tf", "marble", "wood"]);
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    for i in 0..n {
        let at = |c: usize| &cols[c][3 * i..3 * i + 3];
        let (p, g, dx, dy, fw) = (at(0), at(1), at(2), at(3), cols[4][i]);
        let width =
            |g: &[f64]| ((fw * dot(g, g).sqrt()).powi(2) + dot(g, dx).powi(2) + dot(g, dy).powi(2)).sqrt();
        assert!((out[0][i] - width(g)).abs() <= 1e-12 * (1.0 + width(g)), "width at {i}");
        if dot(dx, dx) + dot(dy, dy) == 0.0 {
            let iso = hart::filterwidth([g[0], g[1], g[2]], fw);
            assert!((out[0][i] - iso).abs() <= 1e-12 * (1.0 + iso), "isotropic width at {i}");
        }
        // The term footprint through T = diag(s, s, r): sqrt((sigma fw)^2 + (|dx L|^2 + |dy L|^2) / 2).
        let term = |s: f64, r: f64| {
            let l = |d: &[f64]| (s * d[0]).powi(2) + (s * d[1]).powi(2) + (r * d[2]).powi(2);
            ((s.max(r) * fw).powi(2) + 0.5 * (l(dx) + l(dy))).sqrt()
        };
        assert!(
            (out[1][i] - term(4.0, 1.0)).abs() <= 1e-12 * (1.0 + term(4.0, 1.0)),
            "term footprint at {i}"
        );
        let p = [p[0], p[1], p[2]];
        for (which, sigma, column) in [(1, 2.0, 2), (0, 4.0, 3)] {
            let tf = if which == 1 { term(2.0, 2.0) } else { term(4.0, 1.0) };
            // The port's gradient fades term i by k sigma fw: a width of tf / sigma fades it by k tf.
            let (prm, mode, clut) = preset(which, tf / sigma, 0.0);
            let (at_fw, _, _) = preset(which, fw, 0.0);
            let f = hart::solid_footprint(p, &at_fw, [dx[0], dx[1], dx[2]], [dy[0], dy[1], dy[2]]);
            let grad_f = hart::solid_gradient(identity, p, &prm);
            let expected = hart::colormap(&clut, mode, f, width(&grad_f));
            for k in 0..3 {
                let got = out[column][3 * i + k];
                assert!(
                    (got - expected[k]).abs() <= 1e-9,
                    "preset {which} at {p:?}: {got}, port {}",
                    expected[k]
                );
            }
        }
    }
}
