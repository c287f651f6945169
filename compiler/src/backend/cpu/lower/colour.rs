//! Colour spaces: `color "space" (a, b, c)` casts and `ctransform`.
//!
//! The spaces are RenderMan's (RI spec 3.2, section 11.1 and `ctransform` in 15.3), all converted
//! to and from linear RGB:
//!
//! - `"rgb"`: the identity.
//! - `"hsv"`, `"hsl"`: hue, saturation and value or lightness (Smith 1978; Foley and van Dam,
//!   section 13.3), hue as a fraction of the full circle (0 red, 1/3 green, 2/3 blue; it wraps).
//! - `"xyz"`, `"XYZ"` (the same space): CIE XYZ, for linear RGB with the Rec. 709 / sRGB primaries
//!   and the D65 white (no transfer curve: shading colours are linear).
//! - `"xyY"`: chromaticity x, y and luminance Y of the same XYZ.
//! - `"YIQ"`: NTSC luminance and chrominance (the matrix of Foley and van Dam, eq. 13.36).
//!
//! The piecewise parts (the hue sextants, the special cases of black and grey) are branch-free:
//! both sides of every choice are computed and `select`ed, as the rest of the lowering does.

use super::Lower;
use crate::backend::cpu::code::{Binary, Compare, Reg, Ternary, Unary};

/// The Rec. 709 primaries and the D65 white point as CIE xy chromaticities (ITU-R BT.709-6,
/// IEC 61966-2-1).
const PRIMARIES: [[f64; 2]; 3] = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]];
const WHITE: [f64; 2] = [0.3127, 0.3290];

/// RGB to YIQ, rows Y, I, Q (Foley and van Dam, 2nd ed., eq. 13.36). Its I and Q rows sum to zero,
/// so greys have no chrominance; the inverse is computed from it rather than taken from a table,
/// so that a round trip is exact up to rounding.
const RGB_TO_YIQ: [[f64; 3]; 3] = [[0.299, 0.587, 0.114], [0.596, -0.275, -0.321], [0.212, -0.523, 0.311]];

/// Whether `space` names a colour space the interpreter converts.
pub(crate) fn known_colour_space(space: &str) -> bool {
    matches!(space, "rgb" | "hsv" | "hsl" | "xyz" | "XYZ" | "xyY" | "YIQ")
}

/// The matrix taking linear RGB (Rec. 709 primaries, D65 white) to CIE XYZ, as columns act on
/// `(r, g, b)`: each primary's XYZ at unit luminance, scaled so that RGB white is the D65 white
/// with Y = 1. Derived here from the chromaticities rather than copied from a rounded table.
pub(crate) fn rgb_to_xyz_matrix() -> [[f64; 3]; 3] {
    let xyz = |[x, y]: [f64; 2]| [x / y, 1.0, (1.0 - x - y) / y];
    let p: Vec<[f64; 3]> = PRIMARIES.iter().map(|c| xyz(*c)).collect();
    // Columns are the primaries.
    let m = [[p[0][0], p[1][0], p[2][0]], [p[0][1], p[1][1], p[2][1]], [p[0][2], p[1][2], p[2][2]]];
    let w = xyz(WHITE);
    let inv = invert3(&m);
    let s: Vec<f64> = (0..3).map(|i| (0..3).map(|j| inv[i][j] * w[j]).sum()).collect();
    let mut out = [[0.0; 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = m[i][j] * s[j];
        }
    }
    out
}

/// The inverse of a 3x3 matrix (adjugate over determinant), in f64 at compile time.
fn invert3(m: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let c = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
    };
    let det: f64 = (0..3).map(|j| m[0][j] * c(0, j)).sum();
    let mut out = [[0.0; 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            // The cyclic cofactor already carries its sign; the inverse is its transpose.
            *x = c(j, i) / det;
        }
    }
    out
}

impl Lower<'_> {
    /// A colour given in `space`, converted to linear RGB. Unknown names are left unchanged: the
    /// semantic stage rejects them in casts (E0518), and `ctransform` checks with
    /// [`known_colour_space`] before calling.
    pub(crate) fn colour_to_rgb(&mut self, space: &str, c: &[Reg]) -> Vec<Reg> {
        match space {
            "hsv" => {
                let (v, s) = (c[2], c[1]);
                let chroma = self.emit.binary(Binary::Mul, v, s);
                self.rgb_of_hue(c[0], v, chroma)
            }
            "hsl" => {
                // Chroma (1 - |2L - 1|) S; the largest channel is L + chroma / 2.
                let (l, s) = (c[2], c[1]);
                let (one, two, half) = (self.emit.float(1.0), self.emit.float(2.0), self.emit.float(0.5));
                let l2 = self.emit.binary(Binary::Mul, two, l);
                let l2 = self.emit.binary(Binary::Sub, l2, one);
                let l2 = self.emit.unary(Unary::Abs, l2);
                let spread = self.emit.binary(Binary::Sub, one, l2);
                let chroma = self.emit.binary(Binary::Mul, spread, s);
                let half_chroma = self.emit.binary(Binary::Mul, chroma, half);
                let top = self.emit.binary(Binary::Add, l, half_chroma);
                self.rgb_of_hue(c[0], top, chroma)
            }
            "xyz" | "XYZ" => {
                let m = invert3(&rgb_to_xyz_matrix());
                self.linear3(&m, c)
            }
            "xyY" => {
                let xyz = self.xyy_to_xyz(c);
                let m = invert3(&rgb_to_xyz_matrix());
                self.linear3(&m, &xyz)
            }
            "YIQ" => self.linear3(&invert3(&RGB_TO_YIQ), c),
            _ => c.to_vec(),
        }
    }

    /// A linear RGB colour converted to `space` (the inverse of [`Lower::colour_to_rgb`]).
    pub(crate) fn rgb_to_colour(&mut self, space: &str, c: &[Reg]) -> Vec<Reg> {
        match space {
            "hsv" => {
                let (hue, top, _, chroma) = self.hue_of(c);
                let zero = self.emit.float(0.0);
                let ratio = self.emit.binary(Binary::Div, chroma, top);
                let lit = self.emit.compare(Compare::Ne, top, zero);
                let s = self.emit.select(true, lit, ratio, zero);
                vec![hue, s, top]
            }
            "hsl" => {
                let (hue, top, bottom, chroma) = self.hue_of(c);
                let (zero, one, half) = (self.emit.float(0.0), self.emit.float(1.0), self.emit.float(0.5));
                let sum = self.emit.binary(Binary::Add, top, bottom);
                let l = self.emit.binary(Binary::Mul, sum, half);
                // S = chroma / (1 - |2L - 1|), 0 where the denominator vanishes (black, white).
                let l2 = self.emit.binary(Binary::Sub, sum, one);
                let l2 = self.emit.unary(Unary::Abs, l2);
                let spread = self.emit.binary(Binary::Sub, one, l2);
                let ratio = self.emit.binary(Binary::Div, chroma, spread);
                let defined = self.emit.compare(Compare::Ne, spread, zero);
                let s = self.emit.select(true, defined, ratio, zero);
                vec![hue, s, l]
            }
            "xyz" | "XYZ" => self.linear3(&rgb_to_xyz_matrix(), c),
            "xyY" => {
                let xyz = self.linear3(&rgb_to_xyz_matrix(), c);
                // x = X / (X + Y + Z), y = Y / (X + Y + Z); black has no chromaticity and gets the
                // white point's, so that converting it back gives black again.
                let sum = self.emit.binary(Binary::Add, xyz[0], xyz[1]);
                let sum = self.emit.binary(Binary::Add, sum, xyz[2]);
                let zero = self.emit.float(0.0);
                let some = self.emit.compare(Compare::Ne, sum, zero);
                let x = self.emit.binary(Binary::Div, xyz[0], sum);
                let y = self.emit.binary(Binary::Div, xyz[1], sum);
                let (wx, wy) = (self.emit.float(WHITE[0]), self.emit.float(WHITE[1]));
                let x = self.emit.select(true, some, x, wx);
                let y = self.emit.select(true, some, y, wy);
                vec![x, y, xyz[1]]
            }
            "YIQ" => self.linear3(&RGB_TO_YIQ, c),
            _ => c.to_vec(),
        }
    }

    /// `ctransform([from,] to, c)`: from `from` (RGB when absent) through RGB to `to`.
    pub(crate) fn ctransform(&mut self, from: &str, to: &str, c: &[Reg]) -> Vec<Reg> {
        let alias = |s: &str| if s == "XYZ" { "xyz".to_string() } else { s.to_string() };
        if alias(from) == alias(to) {
            // The same space: no conversion (a round trip through RGB would only add rounding).
            return c.to_vec();
        }
        let rgb = self.colour_to_rgb(from, c);
        self.rgb_to_colour(to, &rgb)
    }

    /// RGB from a hue (in turns), the largest channel and the chroma (largest minus smallest).
    /// Channel `n` (offsets 5, 3, 1 for red, green, blue) is `top - chroma * w` with
    /// `w = clamp(min(k, 4 - k), 0, 1)` and `k = (6 h + n) mod 6`: the hexcone's six sextants as
    /// one piecewise-linear ramp, without a branch per sextant.
    fn rgb_of_hue(&mut self, hue: Reg, top: Reg, chroma: Reg) -> Vec<Reg> {
        let (zero, one, four, six) =
            (self.emit.float(0.0), self.emit.float(1.0), self.emit.float(4.0), self.emit.float(6.0));
        let h6 = self.emit.binary(Binary::Mul, hue, six);
        [5.0, 3.0, 1.0]
            .iter()
            .map(|&n| {
                let n = self.emit.float(n);
                let k = self.emit.binary(Binary::Add, h6, n);
                let k = self.emit.binary(Binary::Mod, k, six);
                let rest = self.emit.binary(Binary::Sub, four, k);
                let w = self.emit.binary(Binary::Min, k, rest);
                let w = self.emit.ternary(Ternary::Clamp, w, zero, one);
                let drop = self.emit.binary(Binary::Mul, chroma, w);
                self.emit.binary(Binary::Sub, top, drop)
            })
            .collect()
    }

    /// The hue (in turns, in [0, 1); 0 for greys), the largest and smallest channel and the chroma
    /// of an RGB colour.
    fn hue_of(&mut self, c: &[Reg]) -> (Reg, Reg, Reg, Reg) {
        let (r, g, b) = (c[0], c[1], c[2]);
        let top = self.emit.binary(Binary::Max, r, g);
        let top = self.emit.binary(Binary::Max, top, b);
        let bottom = self.emit.binary(Binary::Min, r, g);
        let bottom = self.emit.binary(Binary::Min, bottom, b);
        let chroma = self.emit.binary(Binary::Sub, top, bottom);
        let (zero, two, four, six) =
            (self.emit.float(0.0), self.emit.float(2.0), self.emit.float(4.0), self.emit.float(6.0));
        // The sextant pair of the largest channel: (g - b) / C near red, 2 + (b - r) / C near
        // green, 4 + (r - g) / C near blue; red wins ties, then green.
        let mut part = |p: Reg, q: Reg, offset: Reg| {
            let d = self.emit.binary(Binary::Sub, p, q);
            let d = self.emit.binary(Binary::Div, d, chroma);
            self.emit.binary(Binary::Add, d, offset)
        };
        let near_r = part(g, b, zero);
        let near_g = part(b, r, two);
        let near_b = part(r, g, four);
        let is_r = self.emit.compare(Compare::Eq, top, r);
        let is_g = self.emit.compare(Compare::Eq, top, g);
        let h = self.emit.select(true, is_g, near_g, near_b);
        let h = self.emit.select(true, is_r, near_r, h);
        let h = self.emit.binary(Binary::Mod, h, six);
        let h = self.emit.binary(Binary::Div, h, six);
        // A grey has no hue (the divisions above gave NaN there): 0.
        let coloured = self.emit.compare(Compare::Gt, chroma, zero);
        let hue = self.emit.select(true, coloured, h, zero);
        (hue, top, bottom, chroma)
    }

    /// `(x, y, Y)` to `(X, Y, Z)`: `X = x Y / y`, `Z = (1 - x - y) Y / y`; 0 where y is 0.
    fn xyy_to_xyz(&mut self, c: &[Reg]) -> Vec<Reg> {
        let (x, y, lum) = (c[0], c[1], c[2]);
        let (zero, one) = (self.emit.float(0.0), self.emit.float(1.0));
        let scale = self.emit.binary(Binary::Div, lum, y);
        let big_x = self.emit.binary(Binary::Mul, x, scale);
        let z = self.emit.binary(Binary::Sub, one, x);
        let z = self.emit.binary(Binary::Sub, z, y);
        let big_z = self.emit.binary(Binary::Mul, z, scale);
        let defined = self.emit.compare(Compare::Ne, y, zero);
        let big_x = self.emit.select(true, defined, big_x, zero);
        let big_z = self.emit.select(true, defined, big_z, zero);
        vec![big_x, lum, big_z]
    }

    /// `m * c` for a constant 3x3 matrix and a column of three registers.
    fn linear3(&mut self, m: &[[f64; 3]; 3], c: &[Reg]) -> Vec<Reg> {
        m.iter()
            .map(|row| {
                let terms: Vec<Reg> = row
                    .iter()
                    .zip(c)
                    .map(|(k, x)| {
                        let k = self.emit.float(*k);
                        self.emit.binary(Binary::Mul, k, *x)
                    })
                    .collect();
                let sum = self.emit.binary(Binary::Add, terms[0], terms[1]);
                self.emit.binary(Binary::Add, sum, terms[2])
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::{invert3, rgb_to_xyz_matrix};

    #[test]
    fn the_derived_matrix_is_the_published_one() {
        // IEC 61966-2-1 (sRGB), to the four decimals it publishes.
        let published = [[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]];
        let m = rgb_to_xyz_matrix();
        for (got, want) in m.iter().flatten().zip(published.iter().flatten()) {
            assert!((got - want).abs() < 1e-4, "{got} vs {want}");
        }
    }

    #[test]
    fn invert3_inverts() {
        let m = [[2.0, 1.0, 0.5], [0.0, 3.0, 1.0], [1.0, -1.0, 4.0]];
        let inv = invert3(&m);
        for (i, row) in m.iter().enumerate() {
            for j in 0..3 {
                let p: f64 = row.iter().zip(&inv).map(|(a, inv_row)| a * inv_row[j]).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((p - want).abs() < 1e-12, "({i}, {j}) = {p}");
            }
        }
    }
}
