//! The gradient-noise family of `compiler/stdlib/noise.sl` (improved noise over 1D, 2D and 4D with the
//! RenderMan conventions, periodic noise, Perlin's original noise, vector noise, the analytic
//! gradient, flow noise) on the interpreter (f32 and f64) and on the GPU, against an independent
//! Rust port written here from the definitions (module `port`: Perlin's ImprovedNoise.java
//! extended as docs/stdlib/noise.md describes, his 1985 listing T&M L8307-8425, and the
//! gradient-table procedure regenerated from its description).
//!
//! Run with `--nocapture` to see the measured numbers (quoted in docs/stdlib/noise.md).

use crate::support;

use crate::support::{Rng, assert_finite, extremes, worst};

/// The definitions, in f64, written from the sources and the documented decisions.
mod port {
    pub const PERM: [i32; 256] = patina_test_support::perlin::PERMUTATION;
    pub const SCALE3: f64 = 0.9649;
    pub const SCALE1: f64 = 0.25;
    pub const SCALE4: f64 = 0.74;
    pub const TAU: f64 = std::f64::consts::TAU;

    pub fn p(i: i32) -> i32 {
        PERM[(i & 255) as usize]
    }
    pub fn fade(t: f64) -> f64 {
        t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
    }
    pub fn dfade(t: f64) -> f64 {
        30.0 * t * t * (t * (t - 2.0) + 1.0)
    }
    pub fn lerp(t: f64, a: f64, b: f64) -> f64 {
        a + t * (b - a)
    }
    fn sign(bit: bool, x: f64) -> f64 {
        if bit { -x } else { x }
    }
    /// Perlin's 12 gradients (ImprovedNoise.grad).
    pub fn grad3(hash: i32, x: f64, y: f64, z: f64) -> f64 {
        let h = hash & 15;
        let u = if h < 8 { x } else { y };
        let v = if h < 4 {
            y
        } else if h == 12 || h == 14 {
            x
        } else {
            z
        };
        sign(h & 1 != 0, u) + sign(h & 2 != 0, v)
    }
    /// Gustavson's 1D gradients 1..8 with a sign.
    pub fn grad1(hash: i32, x: f64) -> f64 {
        let g = f64::from(1 + (hash & 7));
        sign(hash & 8 != 0, g * x)
    }
    /// The 32 edges of the 4-cube.
    pub fn grad4(hash: i32, x: f64, y: f64, z: f64, w: f64) -> f64 {
        let h = hash & 31;
        let u = if h < 24 { x } else { y };
        let v = if h < 16 { y } else { z };
        let t = if h < 8 { z } else { w };
        sign(h & 1 != 0, u) + sign(h & 2 != 0, v) + sign(h & 4 != 0, t)
    }
    /// A cell (integer-valued) modulo 256.
    pub fn cell(c: f64) -> i32 {
        ((c - 256.0 * (c / 256.0).floor()) as i32) & 255
    }
    pub fn period(p: f64) -> f64 {
        if p.is_nan() { 1.0 } else { p.round_ties_even().clamp(1.0, 16_777_216.0) }
    }
    /// A cell modulo a period, exactly (Euclidean remainder) where |c| < 2^31.
    pub fn pcell(c: f64, p: f64) -> i32 {
        if c.abs() < 2_147_483_520.0 {
            (c as i64).rem_euclid(p as i64) as i32
        } else {
            let mut q = c - p * (c / p).floor();
            q = if q < 0.0 {
                q + p
            } else if q >= p {
                q - p
            } else {
                q
            };
            q.clamp(0.0, p - 1.0) as i32
        }
    }
    pub fn pnext(c: i32, p: f64) -> i32 {
        if c + 1 == p as i32 { 0 } else { c + 1 }
    }

    /// The corners and fractions of one coordinate: (c0, c1, fraction), plain or periodic.
    pub fn split(x: f64, per: Option<f64>) -> (i32, i32, f64) {
        let c = x.floor();
        match per {
            None => (cell(c), cell(c) + 1, x - c),
            Some(p) => {
                let p = period(p);
                let c0 = pcell(c, p);
                (c0, pnext(c0, p), x - c)
            }
        }
    }

    /// ImprovedNoise.noise with the cell's corners given.
    pub fn lattice3(c: [(i32, i32); 3], x: f64, y: f64, z: f64) -> f64 {
        let [(x0, x1), (y0, y1), (z0, z1)] = c;
        let (u, v, w) = (fade(x), fade(y), fade(z));
        let h = |i: i32, j: i32, k: i32| p(p(p(i) + j) + k);
        lerp(
            w,
            lerp(
                v,
                lerp(u, grad3(h(x0, y0, z0), x, y, z), grad3(h(x1, y0, z0), x - 1.0, y, z)),
                lerp(u, grad3(h(x0, y1, z0), x, y - 1.0, z), grad3(h(x1, y1, z0), x - 1.0, y - 1.0, z)),
            ),
            lerp(
                v,
                lerp(u, grad3(h(x0, y0, z1), x, y, z - 1.0), grad3(h(x1, y0, z1), x - 1.0, y, z - 1.0)),
                lerp(
                    u,
                    grad3(h(x0, y1, z1), x, y - 1.0, z - 1.0),
                    grad3(h(x1, y1, z1), x - 1.0, y - 1.0, z - 1.0),
                ),
            ),
        )
    }

    /// Perlin's ImprovedNoise.noise, written as published (the reference of the 2D slice).
    pub fn improved(x: f64, y: f64, z: f64) -> f64 {
        let (a, b, c) = (split(x, None), split(y, None), split(z, None));
        lattice3([(a.0, a.1), (b.0, b.1), (c.0, c.1)], a.2, b.2, c.2)
    }

    pub fn noise1(x: f64, per: Option<f64>) -> f64 {
        let (x0, x1, f) = split(x, per);
        let raw = lerp(fade(f), grad1(p(p(p(x0))), f), grad1(p(p(p(x1))), f - 1.0));
        (SCALE1 * raw).clamp(-1.0, 1.0)
    }

    pub fn noise2(x: f64, y: f64, per: Option<[f64; 2]>) -> f64 {
        let (x0, x1, fx) = split(x, per.map(|p| p[0]));
        let (y0, y1, fy) = split(y, per.map(|p| p[1]));
        let (u, v) = (fade(fx), fade(fy));
        let h = |i: i32, j: i32| p(p(p(i) + j));
        let raw = lerp(
            v,
            lerp(u, grad3(h(x0, y0), fx, fy, 0.0), grad3(h(x1, y0), fx - 1.0, fy, 0.0)),
            lerp(u, grad3(h(x0, y1), fx, fy - 1.0, 0.0), grad3(h(x1, y1), fx - 1.0, fy - 1.0, 0.0)),
        );
        raw.clamp(-1.0, 1.0)
    }

    pub fn noise3(q: [f64; 3], per: Option<[f64; 3]>) -> f64 {
        let s: Vec<(i32, i32, f64)> = (0..3).map(|i| split(q[i], per.map(|p| p[i]))).collect();
        SCALE3 * lattice3([(s[0].0, s[0].1), (s[1].0, s[1].1), (s[2].0, s[2].1)], s[0].2, s[1].2, s[2].2)
    }

    pub fn raw4(q: [f64; 4], per: Option<[f64; 4]>) -> f64 {
        let s: Vec<(i32, i32, f64)> = (0..4).map(|i| split(q[i], per.map(|p| p[i]))).collect();
        let f: Vec<f64> = s.iter().map(|c| c.2).collect();
        let fd: Vec<f64> = f.iter().map(|&t| fade(t)).collect();
        let corner = |axis: usize, bit: i32| if bit == 0 { s[axis].0 } else { s[axis].1 };
        let g = |i: i32, j: i32, k: i32, l: i32| {
            let h = p(p(p(p(corner(0, i)) + corner(1, j)) + corner(2, k)) + corner(3, l));
            grad4(h, f[0] - f64::from(i), f[1] - f64::from(j), f[2] - f64::from(k), f[3] - f64::from(l))
        };
        let cube = |l: i32| {
            let square = |k: i32| {
                lerp(
                    fd[1],
                    lerp(fd[0], g(0, 0, k, l), g(1, 0, k, l)),
                    lerp(fd[0], g(0, 1, k, l), g(1, 1, k, l)),
                )
            };
            lerp(fd[2], square(0), square(1))
        };
        lerp(fd[3], cube(0), cube(1))
    }

    pub fn noise4(q: [f64; 4], per: Option<[f64; 4]>) -> f64 {
        (SCALE4 * raw4(q, per)).clamp(-1.0, 1.0)
    }

    /// lowbias32 (Wellons): the documented generator of the gradient table.
    pub fn lowbias32(mut x: u32) -> u32 {
        x ^= x >> 16;
        x = x.wrapping_mul(0x7feb_352d);
        x ^= x >> 15;
        x = x.wrapping_mul(0x846c_a68b);
        x ^= x >> 16;
        x
    }

    /// Perlin's init() (T&M L8400-8409) with lowbias32 of a counter as random().
    pub fn gradient_table() -> Vec<[f64; 3]> {
        let mut n = 0u32;
        let mut table = Vec::new();
        while table.len() < 256 {
            let mut v = [0.0; 3];
            for c in &mut v {
                *c = f64::from((lowbias32(n) % 512) as i32 - 256) / 256.0;
                n += 1;
            }
            let s = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            if s > 1.0 || s == 0.0 {
                continue;
            }
            let r = s.sqrt();
            table.push(v.map(|c| c / r));
        }
        table
    }

    /// Perlin's 1985 noise3 (T&M L8307-8391) with floor instead of +10000 and his 2002 table.
    pub fn original(g: &[[f64; 3]], q: [f64; 3]) -> f64 {
        let c = q.map(f64::floor);
        let (rx0, ry0, rz0) = (q[0] - c[0], q[1] - c[1], q[2] - c[2]);
        let (rx1, ry1, rz1) = (rx0 - 1.0, ry0 - 1.0, rz0 - 1.0);
        let (bx0, by0, bz0) = (cell(c[0]), cell(c[1]), cell(c[2]));
        let (bx1, by1, bz1) = (bx0 + 1, by0 + 1, bz0 + 1);
        let (i, j) = (p(bx0), p(bx1));
        let (b00, b10, b01, b11) = (p(i + by0), p(j + by0), p(i + by1), p(j + by1));
        let s = |t: f64| t * t * (3.0 - 2.0 * t);
        let (sx, sy, sz) = (s(rx0), s(ry0), s(rz0));
        let at = |b: i32, rx: f64, ry: f64, rz: f64| {
            let v = g[(b & 255) as usize];
            rx * v[0] + ry * v[1] + rz * v[2]
        };
        let a = lerp(sx, at(b00 + bz0, rx0, ry0, rz0), at(b10 + bz0, rx1, ry0, rz0));
        let b = lerp(sx, at(b01 + bz0, rx0, ry1, rz0), at(b11 + bz0, rx1, ry1, rz0));
        let cc = lerp(sy, a, b);
        let a = lerp(sx, at(b00 + bz1, rx0, ry0, rz1), at(b10 + bz1, rx1, ry0, rz1));
        let b = lerp(sx, at(b01 + bz1, rx0, ry1, rz1), at(b11 + bz1, rx1, ry1, rz1));
        let d = lerp(sy, a, b);
        1.5 * lerp(sz, cc, d)
    }

    /// Musgrave's VecNoise with the offsets 3.33 and 7.77 added after the split.
    pub fn vnoise(q: [f64; 3]) -> [f64; 3] {
        let c = q.map(f64::floor);
        let f = [q[0] - c[0], q[1] - c[1], q[2] - c[2]];
        let at = |oi: i32, of: f64| {
            let mut corners = [(0, 0); 3];
            let mut g = [0.0; 3];
            for a in 0..3 {
                let t = f[a] + of;
                let carry = i32::from(t >= 1.0);
                g[a] = if t >= 1.0 { t - 1.0 } else { t };
                let x = cell(c[a]) + oi + carry;
                corners[a] = (x, x + 1);
            }
            SCALE3 * lattice3(corners, g[0], g[1], g[2])
        };
        [noise3(q, None), at(3, 0.33), at(7, 0.77)]
    }

    /// The gradient of snoise3, by the product rule on ImprovedNoise's blend.
    pub fn gradient(q: [f64; 3]) -> [f64; 3] {
        let c = q.map(f64::floor);
        let f = [q[0] - c[0], q[1] - c[1], q[2] - c[2]];
        let x = [cell(c[0]), cell(c[1]), cell(c[2])];
        let h = |i: i32, j: i32, k: i32| p(p(p(x[0] + i) + x[1] + j) + x[2] + k);
        let mut value = [[[0.0; 2]; 2]; 2];
        let mut grads = [[[[0.0; 3]; 2]; 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                for k in 0..2 {
                    let d = [f[0] - i as f64, f[1] - j as f64, f[2] - k as f64];
                    let hh = h(i as i32, j as i32, k as i32);
                    value[i][j][k] = grad3(hh, d[0], d[1], d[2]);
                    grads[i][j][k] =
                        [grad3(hh, 1.0, 0.0, 0.0), grad3(hh, 0.0, 1.0, 0.0), grad3(hh, 0.0, 0.0, 1.0)];
                }
            }
        }
        let w = f.map(fade);
        let dw = f.map(dfade);
        let mut out = [0.0; 3];
        for (axis, o) in out.iter_mut().enumerate() {
            // Sum over corners of d(weight)/d(axis) * value + weight * gradient component.
            let mut total = 0.0;
            for i in 0..2 {
                for j in 0..2 {
                    for k in 0..2 {
                        let bits = [i, j, k];
                        let mut weight = 1.0;
                        let mut dweight = 1.0;
                        for a in 0..3 {
                            let wa = if bits[a] == 1 { w[a] } else { 1.0 - w[a] };
                            weight *= wa;
                            dweight *= if a == axis { if bits[a] == 1 { dw[a] } else { -dw[a] } } else { wa };
                        }
                        total += dweight * value[i][j][k] + weight * grads[i][j][k][axis];
                    }
                }
            }
            *o = SCALE3 * total;
        }
        out
    }

    /// Flow noise: each gradient turned by `angle` in the plane of its two non-zero axes.
    pub fn flow_grad(hash: i32, x: f64, y: f64, z: f64, c: f64, s: f64) -> f64 {
        let h = hash & 15;
        let u = if h < 8 { x } else { y };
        let v = if h < 4 {
            y
        } else if h == 12 || h == 14 {
            x
        } else {
            z
        };
        let gd = sign(h & 1 != 0, u) + sign(h & 2 != 0, v);
        let pd = sign(h & 1 != 0, v) - sign(h & 2 != 0, u);
        c * gd + sign(hash & 16 != 0, s) * pd
    }

    pub fn flow(q: [f64; 3], angle: f64) -> f64 {
        let a = (angle - TAU * (angle * 0.15915494309189535).floor()).clamp(0.0, TAU);
        let (c, s) = (a.cos(), a.sin());
        let cc = q.map(f64::floor);
        let (x, y, z) = (q[0] - cc[0], q[1] - cc[1], q[2] - cc[2]);
        let xi = [cell(cc[0]), cell(cc[1]), cell(cc[2])];
        let h = |i: i32, j: i32, k: i32| p(p(p(xi[0] + i) + xi[1] + j) + xi[2] + k);
        let g = |i: i32, j: i32, k: i32| {
            flow_grad(h(i, j, k), x - f64::from(i), y - f64::from(j), z - f64::from(k), c, s)
        };
        let (u, v, w) = (fade(x), fade(y), fade(z));
        let raw = lerp(
            w,
            lerp(v, lerp(u, g(0, 0, 0), g(1, 0, 0)), lerp(u, g(0, 1, 0), g(1, 1, 0))),
            lerp(v, lerp(u, g(0, 0, 1), g(1, 0, 1)), lerp(u, g(0, 1, 1), g(1, 1, 1))),
        );
        (SCALE3 * raw).clamp(-1.0, 1.0)
    }
}

/// One evaluation point: position, the fourth coordinate, the flow angle and four periods.
#[derive(Clone, Copy, Debug)]
struct In {
    p: [f64; 3],
    w: f64,
    a: f64,
    per: [f64; 4],
}

impl In {
    fn at(p: [f64; 3]) -> In {
        In { p, w: 0.0, a: 0.0, per: [1.0; 4] }
    }
    fn to_f32(self) -> In {
        let r = |x: f64| f64::from(x as f32);
        In { p: self.p.map(r), w: r(self.w), a: r(self.a), per: self.per.map(r) }
    }
}

const PARAMS: &str = "varying float w = 0, a = 0, px = 1, py = 1, pz = 1, pw = 1";

/// A shader computing up to six float expressions (into Ci, then Oi) after `prelude`, with
/// x, y, z the components of P and `per` the point of the first three periods.
fn shader(prelude: &str, exprs: &[&str]) -> support::Program {
    let mut e: Vec<&str> = exprs.to_vec();
    assert!(e.len() <= 6);
    e.resize(6, "0");
    support::program(&format!(
        "#include <noise.sl>\nsurface t({PARAMS}) {{\n\
         float x = xcomp(P), y = ycomp(P), z = zcomp(P);\n\
         point per = point(px, py, pz);\n{prelude}\n\
         Ci = color({}, {}, {});\nOi = color({}, {}, {});\n}}\n",
        e[0], e[1], e[2], e[3], e[4], e[5]
    ))
}

/// The input columns of a set of points.
fn columns(ins: &[In]) -> Vec<(&'static str, Vec<f64>)> {
    let mut cols: Vec<(&'static str, Vec<f64>)> =
        ["P", "w", "a", "px", "py", "pz", "pw"].iter().map(|n| (*n, Vec::new())).collect();
    for i in ins {
        cols[0].1.extend(i.p);
        cols[1].1.push(i.w);
        cols[2].1.push(i.a);
        for k in 0..4 {
            cols[3 + k].1.push(i.per[k]);
        }
    }
    cols
}

#[derive(Clone, Copy)]
enum Backend<'a> {
    F32,
    F64,
    Gpu(&'a patina_runtime::gpu::Gpu),
}

/// The six results at each point.
fn run(program: &support::Program, backend: Backend, ins: &[In]) -> Vec<[f64; 6]> {
    let cols = columns(ins);
    let refs: Vec<(&str, &[f64])> = cols.iter().map(|(n, c)| (*n, c.as_slice())).collect();
    let out = match backend {
        Backend::F32 => program.cpu::<f32>(ins.len(), &refs, &["Ci", "Oi"]),
        Backend::F64 => program.cpu::<f64>(ins.len(), &refs, &["Ci", "Oi"]),
        Backend::Gpu(gpu) => program.gpu(gpu, ins.len(), &refs, &["Ci", "Oi"]),
    };
    (0..ins.len())
        .map(|i| {
            let (c, o) = (&out[0][3 * i..3 * i + 3], &out[1][3 * i..3 * i + 3]);
            [c[0], c[1], c[2], o[0], o[1], o[2]]
        })
        .collect()
}

/// The signed functions of the family, as (name, expression, port).
type PortFn = fn(&In) -> f64;

fn family() -> Vec<(&'static str, &'static str, PortFn)> {
    vec![
        ("snoise1", "snoise1(x)", |i| port::noise1(i.p[0], None)),
        ("snoise2", "snoise2(x, y)", |i| port::noise2(i.p[0], i.p[1], None)),
        ("snoise3", "snoise3(P)", |i| port::noise3(i.p, None)),
        ("snoise4", "snoise4(P, w)", |i| port::noise4([i.p[0], i.p[1], i.p[2], i.w], None)),
        ("psnoise1", "psnoise1(x, px)", |i| port::noise1(i.p[0], Some(i.per[0]))),
        ("psnoise2", "psnoise2(x, y, px, py)", |i| port::noise2(i.p[0], i.p[1], Some([i.per[0], i.per[1]]))),
        ("psnoise3", "psnoise3(P, per)", |i| port::noise3(i.p, Some([i.per[0], i.per[1], i.per[2]]))),
        ("psnoise4", "psnoise4(P, w, per, pw)", |i| port::noise4([i.p[0], i.p[1], i.p[2], i.w], Some(i.per))),
        ("perlin_noise3", "perlin_noise3(P)", |i| port::original(&port::gradient_table(), i.p)),
        ("vsnoise3.x", "xcomp(vsnoise3(P))", |i| port::vnoise(i.p)[0]),
        ("vsnoise3.y", "ycomp(vsnoise3(P))", |i| port::vnoise(i.p)[1]),
        ("vsnoise3.z", "zcomp(vsnoise3(P))", |i| port::vnoise(i.p)[2]),
        ("dsnoise3.x", "xcomp(dsnoise3(P))", |i| port::gradient(i.p)[0]),
        ("dsnoise3.y", "ycomp(dsnoise3(P))", |i| port::gradient(i.p)[1]),
        ("dsnoise3.z", "zcomp(dsnoise3(P))", |i| port::gradient(i.p)[2]),
        ("flownoise3", "flownoise3(P, a)", |i| port::flow(i.p, i.a)),
    ]
}

/// The unsigned forms, as (name, expression, the signed expression they are 0.5 + 0.5 * of).
const UNSIGNED: [(&str, &str, &str); 8] = [
    ("noise1", "noise1(x)", "snoise1(x)"),
    ("noise2", "noise2(x, y)", "snoise2(x, y)"),
    ("noise3", "noise3(P)", "snoise3(P)"),
    ("noise4", "noise4(P, w)", "snoise4(P, w)"),
    ("pnoise1", "pnoise1(x, px)", "psnoise1(x, px)"),
    ("pnoise2", "pnoise2(x, y, px, py)", "psnoise2(x, y, px, py)"),
    ("pnoise3", "pnoise3(P, per)", "psnoise3(P, per)"),
    ("pnoise4", "pnoise4(P, w, per, pw)", "psnoise4(P, w, per, pw)"),
];

/// A backend running the family's shader at argument sets.
type Runner<'a> = &'a dyn Fn(&support::Program, &[In]) -> Vec<[f64; 6]>;

/// Runs the whole family at `ins` on one backend: one column of values per family member.
fn run_family(backend: Runner, ins: &[In]) -> Vec<Vec<f64>> {
    let fam = family();
    let mut columns = Vec::new();
    for chunk in fam.chunks(6) {
        let exprs: Vec<&str> = chunk.iter().map(|f| f.1).collect();
        let out = backend(&shader("", &exprs), ins);
        for k in 0..chunk.len() {
            columns.push(out.iter().map(|o| o[k]).collect());
        }
    }
    columns
}

fn periods(rng: &mut Rng) -> [f64; 4] {
    let choices = [1.0, 2.0, 3.0, 5.0, 7.0, 10.0, 255.0, 256.0, 257.0, 1000.0];
    [0; 4].map(|_| choices[(rng.next() % choices.len() as u64) as usize])
}

/// Random points of ordinary size, with random periods, w and angles.
fn ordinary(seed: u64, n: usize) -> Vec<In> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|i| {
            let span = if i % 2 == 0 { 4.0 } else { 600.0 };
            In {
                p: rng.point(-span, span),
                w: rng.range(-span, span),
                a: rng.range(-10.0, 10.0),
                per: periods(&mut rng),
            }
        })
        .collect()
}

#[test]
fn gradient_table_is_the_documented_procedure() {
    let source = include_str!("../../../compiler/stdlib/noise.sl");
    let start = source.find("perlin_g[768] = {").expect("the table") + "perlin_g[768] = {".len();
    let end = start + source[start..].find("};").expect("its end");
    let values: Vec<f64> = source[start..end]
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().expect("a number"))
        .collect();
    let table = port::gradient_table();
    assert_eq!(values.len(), 768);
    for (i, g) in table.iter().enumerate() {
        for c in 0..3 {
            assert_eq!(values[3 * i + c].to_bits(), g[c].to_bits(), "entry {i}");
        }
        let len = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-15, "entry {i} has length {len}");
    }
    // The directions cover the sphere: the mean is near 0, each axis' mean square near 1/3.
    let mean: Vec<f64> = (0..3).map(|c| table.iter().map(|g| g[c]).sum::<f64>() / 256.0).collect();
    let sq: Vec<f64> = (0..3).map(|c| table.iter().map(|g| g[c] * g[c]).sum::<f64>() / 256.0).collect();
    println!("gradient table: mean {mean:.4?}, mean squares {sq:.4?}");
    assert!(mean.iter().all(|m| m.abs() < 0.12) && sq.iter().all(|s| (s - 1.0 / 3.0).abs() < 0.06));
}

#[test]
fn f64_mode_is_bit_identical_to_the_port() {
    let ins = ordinary(3, 1500);
    let out = run_family(&|p, i| run(p, Backend::F64, i), &ins);
    for (k, (name, _, f)) in family().iter().enumerate() {
        let mut differing = 0;
        for (i, x) in ins.iter().enumerate() {
            let r = f(x);
            // Equal as numbers (a signed zero may differ), and to the last bit otherwise.
            // The gradient's port is an independent formula (the product rule summed over the
            // corners), so it agrees to rounding; everything else to the last bit.
            let tol = if name.starts_with("dsnoise3") { 1e-12 } else { 0.0 };
            if (out[k][i] - r).abs() > tol || out[k][i].is_nan() {
                differing += 1;
                if differing < 5 {
                    eprintln!("{name} at {x:?}: {} vs port {r}", out[k][i]);
                }
            }
        }
        assert_eq!(differing, 0, "{name}: {differing} points differ from the port");
    }
    // 2D noise is improved noise on the plane z = 0, and psnoise3 with periods 256 and 512 is
    // snoise3.
    for x in &ins {
        assert_eq!(port::noise2(x.p[0], x.p[1], None), port::improved(x.p[0], x.p[1], 0.0).clamp(-1.0, 1.0));
    }
    let mut same = ins.clone();
    for (i, x) in same.iter_mut().enumerate() {
        x.per = [256.0, 512.0, 256.0 * (1 + i % 3) as f64, 256.0];
    }
    let prog = shader("", &["psnoise3(P, per)", "snoise3(P)", "psnoise4(P, w, per, pw)", "snoise4(P, w)"]);
    for o in run(&prog, Backend::F64, &same) {
        assert_eq!(o[0], o[1]);
        assert_eq!(o[2], o[3]);
    }
}

/// The f32 mode's tolerance against the port at the same (f32) inputs (absolute).
const F32_TOL: f64 = 1e-5;

#[test]
fn f32_mode_is_close_to_the_port() {
    let ins: Vec<In> = ordinary(5, 1500).into_iter().map(In::to_f32).collect();
    let out = run_family(&|p, i| run(p, Backend::F32, i), &ins);
    for (k, (name, _, f)) in family().iter().enumerate() {
        let port: Vec<f64> = ins.iter().map(f).collect();
        let (err, at) = worst(&out[k], &port);
        println!("{name:14} f32 vs port: largest error {err:.2e} at {:?}", ins[at].p);
        assert!(err <= F32_TOL, "{name}: {err:e} at {:?}", ins[at]);
    }
}

#[test]
fn unsigned_forms_are_half_plus_half_the_signed_ones() {
    let ins = ordinary(7, 500);
    for chunk in UNSIGNED.chunks(3) {
        let mut exprs = Vec::new();
        for u in chunk {
            exprs.push(u.1);
            exprs.push(u.2);
        }
        for out in
            [run(&shader("", &exprs), Backend::F64, &ins), run(&shader("", &exprs), Backend::F32, &ins)]
        {
            for (o, x) in out.iter().zip(&ins) {
                for (k, u) in chunk.iter().enumerate() {
                    let (un, si) = (o[2 * k], o[2 * k + 1]);
                    assert!((un - (0.5 + 0.5 * si)).abs() <= 1e-7, "{} at {x:?}: {un} vs {si}", u.0);
                    assert!((0.0..=1.0).contains(&un), "{} at {x:?}: {un}", u.0);
                }
            }
        }
    }
}

#[test]
fn zero_at_lattice_points() {
    let mut rng = Rng(11);
    let mut ins: Vec<In> = (0..600)
        .map(|_| In {
            p: rng.point(-1000.0, 1000.0).map(f64::floor),
            w: rng.range(-1000.0, 1000.0).floor(),
            a: rng.range(-10.0, 10.0),
            per: periods(&mut rng),
        })
        .collect();
    ins.push(In { p: [16777216.0, -33554432.0, 1e30], w: -1e30, a: 1e30, per: [3.0; 4] });
    let names = ["snoise1", "snoise2", "snoise3", "snoise4", "psnoise1", "psnoise2"];
    let a = shader(
        "",
        &[
            "snoise1(x)",
            "snoise2(x, y)",
            "snoise3(P)",
            "snoise4(P, w)",
            "psnoise1(x, px)",
            "psnoise2(x, y, px, py)",
        ],
    );
    let b = shader(
        "vector v = vsnoise3(P);",
        &[
            "psnoise3(P, per)",
            "psnoise4(P, w, per, pw)",
            "perlin_noise3(P)",
            "flownoise3(P, a)",
            "xcomp(v)",
            "0",
        ],
    );
    let names_b = ["psnoise3", "psnoise4", "perlin_noise3", "flownoise3", "vsnoise3.x"];
    for backend in [Backend::F64, Backend::F32] {
        for (prog, names) in [(&a, &names[..]), (&b, &names_b[..])] {
            for (o, x) in run(prog, backend, &ins).iter().zip(&ins) {
                for (k, name) in names.iter().enumerate() {
                    assert_eq!(o[k], 0.0, "{name} at {x:?}");
                }
            }
        }
    }
}

/// Mean, standard deviation, smallest and largest value of a column.
fn stats(v: &[f64]) -> (f64, f64, f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
    let lo = v.iter().copied().fold(f64::MAX, f64::min);
    let hi = v.iter().copied().fold(f64::MIN, f64::max);
    (mean, var.sqrt(), lo, hi)
}

#[test]
fn ranges_and_statistics() {
    // The documented extremes, exactly where the searches found them.
    let peaks = [
        In::at([148.5, 155.5, 0.0]),
        In::at([136.5, 64.5, 0.0]),
        In {
            p: [161.42383661115014, 1.5133455432561786, 24.042218265055425],
            w: 183.46349433366063,
            a: 0.0,
            per: [1.0; 4],
        },
    ];
    let prog = shader("", &["snoise1(x)", "snoise2(x, y)", "snoise4(P, w)"]);
    let o = run(&prog, Backend::F64, &peaks);
    assert_eq!(o[0][0], 1.0);
    let o1 = run(&prog, Backend::F64, &[In::at([155.5, 0.0, 0.0])]);
    assert_eq!(o1[0][0], -1.0);
    assert_eq!(o[1][1], 1.0);
    assert!((o[2][2] + 0.74 * 1.3448189081468407).abs() < 1e-12, "{}", o[2][2]);
    // Statistics over random points of the period (the seeds: values cluster near 0, L2714).
    let mut rng = Rng(13);
    let ins: Vec<In> = (0..6000)
        .map(|_| In {
            p: rng.point(0.0, 256.0),
            w: rng.range(0.0, 256.0),
            a: rng.range(0.0, 7.0),
            per: [1.0; 4],
        })
        .collect();
    let out = run_family(&|p, i| run(p, Backend::F64, i), &ins);
    // (name, documented range, expected standard deviation range)
    let expect: [(&str, f64, f64, f64, f64); 9] = [
        ("snoise1", -1.0, 1.0, 0.15, 0.35),
        ("snoise2", -0.8919, 1.0, 0.15, 0.3),
        ("snoise3", -0.99056, 0.99998, 0.15, 0.3),
        ("snoise4", -1.0, 1.0, 0.1, 0.3),
        ("perlin_noise3", -1.299, 1.299, 0.15, 0.35),
        ("vsnoise3.x", -0.99056, 0.99998, 0.15, 0.3),
        ("vsnoise3.y", -0.99056, 0.99998, 0.15, 0.3),
        ("vsnoise3.z", -0.99056, 0.99998, 0.15, 0.3),
        ("flownoise3", -1.0, 1.0, 0.15, 0.3),
    ];
    let fam = family();
    for (name, lo, hi, sd_lo, sd_hi) in expect {
        let k = fam.iter().position(|f| f.0 == name).expect("a member");
        let (mean, sd, min, max) = stats(&out[k]);
        println!("{name:14} mean {mean:+.4} sd {sd:.4} range [{min:.4}, {max:.4}]");
        assert!(min >= lo - 1e-9 && max <= hi + 1e-9, "{name}: [{min}, {max}]");
        assert!(mean.abs() < 5.0 * sd / (ins.len() as f64).sqrt() + 0.01, "{name}: mean {mean}");
        assert!((sd_lo..=sd_hi).contains(&sd), "{name}: sd {sd}");
    }
    // vsnoise3's components are decorrelated.
    let k = fam.iter().position(|f| f.0 == "vsnoise3.x").expect("vsnoise3");
    for (a, b) in [(k, k + 1), (k, k + 2), (k + 1, k + 2)] {
        let (ma, sa, _, _) = stats(&out[a]);
        let (mb, sb, _, _) = stats(&out[b]);
        let cov =
            out[a].iter().zip(&out[b]).map(|(x, y)| (x - ma) * (y - mb)).sum::<f64>() / ins.len() as f64;
        let corr = cov / (sa * sb);
        println!("vsnoise3 components {} and {}: correlation {corr:+.4}", a - k, b - k);
        assert!(corr.abs() < 0.05, "correlation {corr}");
    }
}

/// Each function along one coordinate (the others fixed): (name, expression, which input moves).
fn along_axes() -> Vec<(&'static str, &'static str, usize)> {
    vec![
        ("snoise1", "snoise1(x)", 0),
        ("snoise2 x", "snoise2(x, y)", 0),
        ("snoise2 y", "snoise2(x, y)", 1),
        ("snoise4 z", "snoise4(P, w)", 2),
        ("snoise4 w", "snoise4(P, w)", 3),
        ("psnoise3 x", "psnoise3(P, per)", 0),
        ("psnoise4 w", "psnoise4(P, w, per, pw)", 3),
        ("perlin_noise3 y", "perlin_noise3(P)", 1),
        ("flownoise3 z", "flownoise3(P, a)", 2),
        ("vsnoise3.z x", "zcomp(vsnoise3(P))", 0),
        ("dsnoise3.x x", "xcomp(dsnoise3(P))", 0),
        ("psnoise1", "psnoise1(x, px)", 0),
    ]
}

#[test]
fn first_derivative_is_continuous_across_cell_faces() {
    // One-sided slopes on both sides of a face (an integer coordinate; for the periodic noises
    // also the period's wrap), for two steps: a kink would leave a jump of order 1 whatever the
    // step; for a C1 function the jump is about h |f''| and shrinks with h.
    let mut rng = Rng(17);
    let mut faces = Vec::new();
    for i in 0..120 {
        let mut x = In {
            p: rng.point(-50.0, 50.0),
            w: rng.range(-50.0, 50.0),
            a: rng.range(0.0, 6.0),
            per: periods(&mut rng),
        };
        let face = |v: f64, per: f64| if i % 3 == 0 { per * (v / per).round() } else { v.floor() };
        for k in 0..3 {
            x.p[k] = face(x.p[k], x.per[k]);
        }
        x.w = face(x.w, x.per[3]);
        faces.push(x);
    }
    for (name, expr, axis) in along_axes() {
        let prog = shader("", &[expr]);
        let mut jumps = Vec::new();
        for h in [1e-4, 1e-6] {
            let mut ins = Vec::new();
            for f in &faces {
                for step in [-1.0, 0.0, 1.0] {
                    let mut q = *f;
                    if axis < 3 {
                        q.p[axis] += step * h
                    } else {
                        q.w += step * h
                    }
                    ins.push(q);
                }
            }
            let out = run(&prog, Backend::F64, &ins);
            let mut worst = 0.0f64;
            for i in 0..faces.len() {
                let (l, c, r) = (out[3 * i][0], out[3 * i + 1][0], out[3 * i + 2][0]);
                worst = worst.max(((c - l) / h - (r - c) / h).abs());
            }
            jumps.push(worst);
        }
        println!(
            "{name:16} largest slope jump across faces: {:.2e} (h 1e-4), {:.2e} (h 1e-6)",
            jumps[0], jumps[1]
        );
        assert!(jumps[1] < 1e-3 && jumps[1] < jumps[0] * 0.1 + 1e-7, "{name}: {jumps:?}");
    }
}

#[test]
fn dsnoise3_is_the_gradient_of_snoise3() {
    let mut rng = Rng(19);
    let ins: Vec<In> = (0..400).map(|_| In::at(rng.point(-40.0, 40.0))).collect();
    let prog = shader("vector g = dsnoise3(P);", &["xcomp(g)", "ycomp(g)", "zcomp(g)"]);
    let h = 1e-5;
    let mut worst = 0.0f64;
    for backend in [Backend::F64, Backend::F32] {
        let f64_mode = matches!(backend, Backend::F64);
        let out = run(&prog, backend, &ins);
        for (o, x) in out.iter().zip(&ins) {
            for axis in 0..3 {
                let (mut a, mut b) = (x.p, x.p);
                a[axis] += h;
                b[axis] -= h;
                let slope = (port::noise3(a, None) - port::noise3(b, None)) / (2.0 * h);
                let err = (o[axis] - slope).abs();
                if f64_mode {
                    worst = worst.max(err);
                    assert!(err < 1e-7, "d/d{axis} at {x:?}: {} vs {slope}", o[axis]);
                } else {
                    assert!(err < 1e-4, "f32 d/d{axis} at {x:?}: {} vs {slope}", o[axis]);
                }
            }
        }
    }
    println!("dsnoise3 vs central differences of snoise3 (h = {h:e}): largest difference {worst:.2e}");
}

#[test]
fn flownoise3_turns_snoise3() {
    let mut rng = Rng(23);
    let base: Vec<In> = (0..500).map(|_| In::at(rng.point(-100.0, 100.0))).collect();
    let prog = shader("", &["flownoise3(P, a)", "snoise3(P)"]);
    // Angle 0 (and multiples of 2 pi in f64) is snoise3 exactly.
    for backend in [Backend::F64, Backend::F32] {
        for (o, x) in run(&prog, backend, &base).iter().zip(&base) {
            assert_eq!(o[0], o[1], "at {x:?}");
        }
    }
    // Periodic in the angle: a + 2 pi k against a.
    let mut ins = Vec::new();
    for x in &base {
        let a = rng.range(0.0, std::f64::consts::TAU);
        for k in [0.0, 1.0, -1.0, 5.0, -40.0, 1000.0] {
            ins.push(In { a: a + k * port::TAU, ..*x });
        }
    }
    for (backend, tol) in [(Backend::F64, 1e-9), (Backend::F32, 5e-4)] {
        let out = run(&prog, backend, &ins);
        let mut worst = 0.0f64;
        for i in 0..ins.len() {
            let first = out[i - i % 6][0];
            worst = worst.max((out[i][0] - first).abs());
        }
        println!("flownoise3: largest change under angle + 2 pi k, |k| <= 1000: {worst:.2e}");
        assert!(worst <= tol, "{worst:e}");
    }
    // It moves: a quarter turn changes the values (decorrelates them from snoise3).
    let quarter: Vec<In> = base.iter().map(|x| In { a: std::f64::consts::FRAC_PI_2, ..*x }).collect();
    let out = run(&prog, Backend::F64, &quarter);
    let a: Vec<f64> = out.iter().map(|o| o[0]).collect();
    let b: Vec<f64> = out.iter().map(|o| o[1]).collect();
    let (ma, sa, _, _) = stats(&a);
    let (mb, sb, _, _) = stats(&b);
    let corr = a.iter().zip(&b).map(|(x, y)| (x - ma) * (y - mb)).sum::<f64>() / a.len() as f64 / (sa * sb);
    println!("flownoise3 at a quarter turn vs snoise3: correlation {corr:+.3}");
    assert!(corr.abs() < 0.3, "{corr}");
}

#[test]
fn periodicity_is_exact() {
    // Periods that do and do not divide 256, huge ones, and those below 1 (taken as 1), rounded.
    let periods = [
        1.0, 2.0, 3.0, 7.0, 100.0, 255.0, 256.0, 257.0, 1000.0, 65537.0, 16777216.0, 1e30, 0.0, -5.0, 0.4,
        2.5,
    ];
    let mut rng = Rng(29);
    let mut ins = Vec::new();
    let mut groups = Vec::new();
    for &per in &periods {
        let eff = port::period(per);
        for _ in 0..6 {
            // A point with a fraction of 6 bits, so that shifts by multiples of the period stay
            // exact where they fit in f32's 24 bits.
            let q = |r: &mut Rng| (r.range(-300.0, 300.0) * 64.0).round() / 64.0;
            let base =
                In { p: [q(&mut rng), q(&mut rng), q(&mut rng)], w: q(&mut rng), a: 0.0, per: [per; 4] };
            let start = ins.len();
            for k in [0.0, 1.0, -1.0, 2.0, -3.0, 1000.0] {
                let s = k * eff;
                ins.push(In {
                    p: [base.p[0] + s, base.p[1] - s, base.p[2] + 2.0 * s],
                    w: base.w - s,
                    ..base
                });
            }
            groups.push((per, start));
        }
    }
    let prog = shader(
        "",
        &["psnoise1(x, px)", "psnoise2(x, y, px, py)", "psnoise3(P, per)", "psnoise4(P, w, per, pw)"],
    );
    let exact32 = |x: &In| x.p.iter().chain([&x.w]).all(|v| f64::from(*v as f32) == *v);
    for backend in [Backend::F64, Backend::F32] {
        let f32_mode = matches!(backend, Backend::F32);
        let out = run(&prog, backend, &ins);
        let mut compared = 0;
        for &(per, start) in &groups {
            for i in start..start + 6 {
                if f32_mode && !exact32(&ins[i]) {
                    continue;
                }
                compared += 1;
                assert_eq!(out[i][..4], out[start][..4], "period {per}, at {:?}", ins[i]);
            }
        }
        println!(
            "periodicity: {compared} shifted points equal to their base ({})",
            if f32_mode { "f32" } else { "f64" }
        );
    }
    // A period of 1e30 is the largest, 2^24.
    let a: Vec<In> = ins.iter().take(6).map(|x| In { per: [1e30; 4], ..*x }).collect();
    let b: Vec<In> = a.iter().map(|x| In { per: [16777216.0; 4], ..*x }).collect();
    assert_eq!(run(&prog, Backend::F64, &a), run(&prog, Backend::F64, &b));
}

/// Every member over the extreme values (support::extremes) in every input, with periods,
/// angles and w extreme too.
fn extreme_points() -> Vec<In> {
    let e = extremes();
    let mut rng = Rng(31);
    let mut ins = Vec::new();
    for &x in &e {
        for &y in &e {
            for &z in &e {
                if !rng.next().is_multiple_of(3) {
                    continue;
                }
                let pick = |r: &mut Rng| e[(r.next() % e.len() as u64) as usize];
                ins.push(In {
                    p: [x, y, z],
                    w: pick(&mut rng),
                    a: pick(&mut rng),
                    per: [0; 4].map(|_| pick(&mut rng)),
                });
            }
        }
    }
    ins
}

#[test]
fn extreme_inputs_give_finite_values() {
    let ins = extreme_points();
    for backend in [Backend::F64, Backend::F32] {
        let out = run_family(&|p, i| run(p, backend, i), &ins);
        for (k, (name, _, _)) in family().iter().enumerate() {
            assert_finite(name, &out[k], 1);
            if !name.starts_with("dsnoise3") && *name != "perlin_noise3" {
                assert!(out[k].iter().all(|v| v.abs() <= 1.0), "{name} out of [-1, 1]");
            }
        }
    }
    println!("{} extreme points: finite on the interpreter (f32, f64)", ins.len());
}

/// The functions with no transcendental operation are bit-identical on the GPU; flow noise uses
/// sin and cos (lavapipe's differ by a few ulp), so it gets a tolerance.
const GPU_FLOW_TOL: f64 = 1e-5;

/// vsnoise3's offset components differ by an ulp or two at a few points on lavapipe (measured
/// 2.8e-7, 21 and 51 of 2850 values): the GPU compiler appears to fold (f + 0.33) - 1 into f - 0.67, a
/// reassociation the interpreter does not do.
const GPU_OFFSET_TOL: f64 = 5e-7;

#[test]
fn gpu_agrees_with_the_interpreter() {
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    let mut ins: Vec<In> = ordinary(37, 600).into_iter().map(In::to_f32).collect();
    ins.extend(extreme_points().into_iter().map(In::to_f32));
    for k in 0..=24 {
        let mut rng = Rng(41 + k);
        for _ in 0..12 {
            let o = 2f64.powi(k as i32);
            let x = In {
                p: rng.point(0.0, 1.0).map(|f| o + f),
                w: o + rng.unit(),
                a: 1.0,
                per: periods(&mut rng),
            };
            ins.push(x.to_f32());
        }
    }
    // One small kernel per function (lavapipe compiles a few small kernels much faster than
    // one large one).
    for (name, expr, _) in family() {
        let start = std::time::Instant::now();
        let prog = shader("", &[expr]);
        let cpu: Vec<f64> = run(&prog, Backend::F32, &ins).iter().map(|o| o[0]).collect();
        let dev: Vec<f64> = run(&prog, Backend::Gpu(gpu), &ins).iter().map(|o| o[0]).collect();
        assert_finite(name, &dev, 1);
        let (err, at) = worst(&dev, &cpu);
        let same = dev.iter().zip(&cpu).filter(|(a, b)| a == b).count();
        println!(
            "{name:14} GPU vs f32 interpreter: {same} of {} equal, largest difference {err:.2e} ({:.1} s)",
            ins.len(),
            start.elapsed().as_secs_f64()
        );
        let tol = match name {
            "flownoise3" => GPU_FLOW_TOL,
            n if n.starts_with("vsnoise3") => GPU_OFFSET_TOL,
            _ => 0.0,
        };
        assert!(err <= tol, "{name}: {err:e} at {:?}", ins[at]);
    }
}

#[test]
fn large_coordinate_accuracy() {
    // At offsets 2^k (k = 0..24, both signs), the f32 interpreter against the f64 one at the same
    // f32 coordinates (the computation's own error) and at the exact coordinates (what a shader
    // sees, including the rounding of the coordinate itself).
    let per = 40;
    let mut exact = Vec::new();
    let mut rng = Rng(43);
    for k in 0..=24 {
        let o = 2f64.powi(k);
        for i in 0..per {
            let s = if i % 2 == 0 { 1.0 } else { -1.0 };
            let f = rng.point(0.0, 1.0);
            exact.push(In {
                p: f.map(|v| s * (o + v)),
                w: s * (o + rng.unit()),
                a: 1.0,
                per: [7.0, 100.0, 1000.0, 3.0],
            });
        }
    }
    let rounded: Vec<In> = exact.iter().map(|x| x.to_f32()).collect();
    let f32_out = run_family(&|p, i| run(p, Backend::F32, i), &rounded);
    let f64_same = run_family(&|p, i| run(p, Backend::F64, i), &rounded);
    let f64_exact = run_family(&|p, i| run(p, Backend::F64, i), &exact);
    println!("largest |f32 - f64| at offsets 2^k: own (same f32 coordinates) / total (exact coordinates)");
    let fam = family();
    let mut header = String::from("  k ");
    for (name, _, _) in &fam {
        header.push_str(&format!("{name:>21}"));
    }
    println!("{header}");
    let mut limits = vec![None::<usize>; fam.len()];
    for k in 0..=24usize {
        let mut row = format!("{k:3} ");
        for (m, limit) in limits.iter_mut().enumerate() {
            let r = k * per..(k + 1) * per;
            let own = worst(&f32_out[m][r.clone()], &f64_same[m][r.clone()]).0;
            let total = worst(&f32_out[m][r.clone()], &f64_exact[m][r]).0;
            row.push_str(&format!("  {own:8.1e}/{total:8.1e}"));
            assert!(own <= 1e-3, "{}: own error {own:e} at 2^{k}", fam[m].0);
            if total <= 1e-3 && (k == 0 || *limit == Some(k - 1)) {
                *limit = Some(k);
            }
        }
        println!("{row}");
    }
    for (m, limit) in limits.iter().enumerate() {
        let limit = limit.expect("accurate at 2^0");
        println!("{:14} within 1e-3 of f64 at the exact coordinate up to 2^{limit}", fam[m].0);
        // The coordinate's own rounding (half an ulp of 2^k, 2^(k-24)) times the slope limits this.
        assert!(limit >= 10, "{}: only up to 2^{limit}", fam[m].0);
    }
}
