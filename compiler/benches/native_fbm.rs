//! Perlin's improved noise (2002) and its fBm, written natively in scalar f32: the baseline the
//! interpreter benchmark compares against, and the reference the interpreter must match bit for
//! bit. It is the algorithm of `fbm.sl`, operation for operation (same `mix` formula, same
//! association), and reads its permutation table from that file so the two cannot drift.

/// The permutation table of `fbm.sl`.
pub fn permutation() -> [i32; 256] {
    let source = include_str!("fbm.sl");
    let start = source.find("int perm[256] = {").expect("fbm.sl declares perm") + "int perm[256] = {".len();
    let end = start + source[start..].find('}').expect("the table ends");
    let mut table = [0; 256];
    let mut n = 0;
    for (slot, word) in table.iter_mut().zip(source[start..end].split(',')) {
        *slot = word.trim().parse().expect("an integer");
        n += 1;
    }
    assert_eq!(n, 256, "the table has 256 entries");
    table
}

fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

fn grad(hash: i32, x: f32, y: f32, z: f32) -> f32 {
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

/// WGSL's `mix`.
fn mix(a: f32, b: f32, t: f32) -> f32 {
    a * (1.0 - t) + b * t
}

/// Improved noise at `p`.
pub fn improved_noise(perm: &[i32; 256], p: [f32; 3]) -> f32 {
    let (fx, fy, fz) = (p[0].floor(), p[1].floor(), p[2].floor());
    let cell = |f: f32| (f as i32) & 255;
    let (xi, yi, zi) = (cell(fx), cell(fy), cell(fz));
    let (x, y, z) = (p[0] - fx, p[1] - fy, p[2] - fz);
    let (u, v, w) = (fade(x), fade(y), fade(z));
    let at = |i: i32| perm[(i & 255) as usize];
    let a = at(xi) + yi;
    let aa = at(a) + zi;
    let ab = at(a + 1) + zi;
    let b = at(xi + 1) + yi;
    let ba = at(b) + zi;
    let bb = at(b + 1) + zi;
    mix(
        mix(
            mix(grad(at(aa), x, y, z), grad(at(ba), x - 1.0, y, z), u),
            mix(grad(at(ab), x, y - 1.0, z), grad(at(bb), x - 1.0, y - 1.0, z), u),
            v,
        ),
        mix(
            mix(grad(at(aa + 1), x, y, z - 1.0), grad(at(ba + 1), x - 1.0, y, z - 1.0), u),
            mix(grad(at(ab + 1), x, y - 1.0, z - 1.0), grad(at(bb + 1), x - 1.0, y - 1.0, z - 1.0), u),
            v,
        ),
        w,
    )
}

/// fBm: `octaves` octaves of improved noise, each at twice the frequency and half the amplitude.
pub fn fbm(perm: &[i32; 256], p: [f32; 3], octaves: u32) -> f32 {
    let mut sum = 0.0;
    let mut amplitude = 1.0;
    let mut q = p;
    for _ in 0..octaves {
        sum += amplitude * improved_noise(perm, q);
        q = [q[0] * 2.0, q[1] * 2.0, q[2] * 2.0];
        amplitude *= 0.5;
    }
    sum
}

/// `n` points spread over [-50, 50]^3 by a fixed integer hash (no dependency on a RNG crate).
pub fn points(n: usize) -> Vec<f32> {
    let mut out = Vec::with_capacity(n * 3);
    let mut state: u32 = 0x2545_f491;
    for _ in 0..n * 3 {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        out.push((state >> 8) as f32 / (1u32 << 24) as f32 * 100.0 - 50.0);
    }
    out
}
