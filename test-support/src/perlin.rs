//! Perlin's reference implementation of improved noise (ImprovedNoise.java, 2002), line for line
//! in f64, ported from the Java independently of the standard library's `noise.sl`, so that tests
//! can hold the library against it. `(int)Math.floor(x)` is `floor() as i32`: both saturate at the
//! ends of the `int` range and map NaN to 0.

/// Perlin's permutation of 0..255 (`permutation[]` in ImprovedNoise.java).
pub const PERMUTATION: [i32; 256] = [
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69, 142, 8, 99,
    37, 240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32,
    57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175, 74, 165, 71, 134, 139, 48, 27,
    166, 77, 146, 158, 231, 83, 111, 229, 122, 60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244,
    102, 143, 54, 65, 25, 63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169, 200, 196, 135, 130,
    116, 188, 159, 86, 164, 100, 109, 198, 173, 186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147,
    118, 126, 255, 82, 85, 212, 207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119,
    248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110,
    79, 113, 224, 232, 178, 185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179,
    162, 241, 81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204, 176,
    115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78,
    66, 215, 61, 156, 180,
];

/// `p[]`: the permutation twice over (`p[256 + i] = p[i] = permutation[i]`).
fn p(i: i32) -> i32 {
    PERMUTATION[i as usize % 256]
}

/// ImprovedNoise.noise(x, y, z), exactly as published: the cell is `(int)Math.floor(x) & 255`,
/// which saturates beyond 2^31.
pub fn noise(x: f64, y: f64, z: f64) -> f64 {
    noise_in_cell(x, y, z, |x| (x.floor() as i32) & 255)
}

/// [`noise`] with the standard library's one departure: the cell is reduced modulo 256 in float
/// before the conversion to int, so coordinates beyond 2^31 (the finer octaves of fBm reach
/// 0.3 · 8^29 = 1.3e26) keep the noise's period instead of saturating. Equal to [`noise`] below
/// 2^31 in magnitude.
pub fn noise_wide(x: f64, y: f64, z: f64) -> f64 {
    noise_in_cell(x, y, z, |x| (x.floor() - 256.0 * (x.floor() * 0.00390625).floor()) as i32 & 255)
}

fn noise_in_cell(mut x: f64, mut y: f64, mut z: f64, cell: impl Fn(f64) -> i32) -> f64 {
    let xi = cell(x); // FIND UNIT CUBE THAT
    let yi = cell(y); // CONTAINS POINT.
    let zi = cell(z);
    x -= x.floor(); // FIND RELATIVE X,Y,Z
    y -= y.floor(); // OF POINT IN CUBE.
    z -= z.floor();
    let u = fade(x); // COMPUTE FADE CURVES
    let v = fade(y); // FOR EACH OF X,Y,Z.
    let w = fade(z);
    let a = p(xi) + yi; // HASH COORDINATES OF
    let aa = p(a) + zi; // THE 8 CUBE CORNERS,
    let ab = p(a + 1) + zi;
    let b = p(xi + 1) + yi;
    let ba = p(b) + zi;
    let bb = p(b + 1) + zi;
    lerp(
        w,
        lerp(
            v,
            lerp(u, grad(p(aa), x, y, z), grad(p(ba), x - 1.0, y, z)),
            lerp(u, grad(p(ab), x, y - 1.0, z), grad(p(bb), x - 1.0, y - 1.0, z)),
        ),
        lerp(
            v,
            lerp(u, grad(p(aa + 1), x, y, z - 1.0), grad(p(ba + 1), x - 1.0, y, z - 1.0)),
            lerp(u, grad(p(ab + 1), x, y - 1.0, z - 1.0), grad(p(bb + 1), x - 1.0, y - 1.0, z - 1.0)),
        ),
    )
}

/// The quintic fade curve 6t^5 - 15t^4 + 10t^3, in the reference's order of operations.
pub fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

fn lerp(t: f64, a: f64, b: f64) -> f64 {
    a + t * (b - a)
}

/// The dot product of (x, y, z) with one of the 12 gradient directions chosen by `hash`.
pub fn grad(hash: i32, x: f64, y: f64, z: f64) -> f64 {
    let h = hash & 15; // CONVERT LO 4 BITS OF HASH CODE
    let u = if h < 8 { x } else { y }; // INTO 12 GRADIENT DIRECTIONS.
    let v = if h < 4 {
        y
    } else if h == 12 || h == 14 {
        x
    } else {
        z
    };
    (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
}

#[cfg(test)]
mod tests {
    /// The published value of ImprovedNoise.noise(3.14, 42, 7).
    #[test]
    #[allow(clippy::approx_constant)]
    fn the_published_value() {
        assert_eq!(super::noise(3.14, 42.0, 7.0), 0.13691995878400012);
        assert_eq!(super::noise_wide(3.14, 42.0, 7.0), 0.13691995878400012);
    }
}
