//! Colour spaces: `color "space" (a, b, c)` casts and `ctransform`, with the interpreter's
//! definitions (`backend/cpu/lower/colour.rs`) operation for operation: RenderMan's `"rgb"`,
//! `"hsv"`, `"hsl"`, `"xyz"`/`"XYZ"` (Rec. 709 primaries, D65 white, linear), `"xyY"` and `"YIQ"`.
//!
//! The constant matrices are derived here exactly as the interpreter derives them (in f64, then
//! rounded to f32 where they enter the shader), so both backends multiply by the same bits.

use naga::{BinaryOperator as Op, MathFunction as M};

use super::body::{Translator, Value};
use crate::diag::{Code, Diagnostic};
use crate::source::Span;

/// The Rec. 709 primaries and the D65 white point as CIE xy chromaticities (ITU-R BT.709-6).
const PRIMARIES: [[f64; 2]; 3] = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]];
const WHITE: [f64; 2] = [0.3127, 0.3290];

/// RGB to YIQ, rows Y, I, Q (Foley and van Dam, 2nd ed., eq. 13.36).
const RGB_TO_YIQ: [[f64; 3]; 3] = [[0.299, 0.587, 0.114], [0.596, -0.275, -0.321], [0.212, -0.523, 0.311]];

/// Whether `space` names a colour space (the interpreter's list).
pub(super) fn known_colour_space(space: &str) -> bool {
    matches!(space, "rgb" | "hsv" | "hsl" | "xyz" | "XYZ" | "xyY" | "YIQ")
}

/// Linear RGB to CIE XYZ, derived from the chromaticities (the interpreter's derivation).
fn rgb_to_xyz_matrix() -> [[f64; 3]; 3] {
    let xyz = |[x, y]: [f64; 2]| [x / y, 1.0, (1.0 - x - y) / y];
    let p: Vec<[f64; 3]> = PRIMARIES.iter().map(|c| xyz(*c)).collect();
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

/// The inverse of a 3x3 matrix (adjugate over determinant), in f64.
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
            *x = c(j, i) / det;
        }
    }
    out
}

impl Translator<'_> {
    /// A colour given in a named colour space, converted to linear RGB (unknown names are left
    /// unchanged: the semantic stage rejects them in casts, and `ctransform` checks first).
    pub(super) fn colour_to_rgb(&mut self, space: &str, v: Value, _span: Span) -> Result<Value, Diagnostic> {
        if space == "rgb" || !known_colour_space(space) {
            return Ok(v);
        }
        let c = self.parts(v, 3);
        let out = self.colour_parts_to_rgb(space, &c);
        Ok(self.vector(&out))
    }

    /// `ctransform([from,] to, c)`: from `from` (RGB when absent) through RGB to `to`.
    pub(super) fn ctransform(
        &mut self,
        from: &str,
        to: &str,
        v: Value,
        span: Span,
    ) -> Result<Value, Diagnostic> {
        for name in [from, to] {
            if !known_colour_space(name) {
                return Err(Diagnostic::error(
                    Code::UnknownSpace,
                    format!("unknown colour space \"{name}\""),
                    span,
                    "in this conversion",
                )
                .with_note("the colour spaces are rgb, hsv, hsl, xyz, XYZ, xyY, YIQ"));
            }
        }
        fn alias(s: &str) -> &str {
            if s == "XYZ" { "xyz" } else { s }
        }
        if alias(from) == alias(to) {
            // The same space: no conversion (as the interpreter, which adds no rounding).
            return Ok(v);
        }
        let c = self.parts(v, 3);
        let rgb = self.colour_parts_to_rgb(from, &c);
        let out = self.rgb_to_colour_parts(to, &rgb);
        Ok(self.vector(&out))
    }

    fn colour_parts_to_rgb(&mut self, space: &str, c: &[Value]) -> Vec<Value> {
        match space {
            "hsv" => {
                let chroma = self.mul(c[2], c[1]);
                self.rgb_of_hue(c[0], c[2], chroma)
            }
            "hsl" => {
                let (l, s) = (c[2], c[1]);
                let (one, two, half) = (self.float(1.0), self.float(2.0), self.float(0.5));
                let l2 = self.mul(two, l);
                let l2 = self.sub(l2, one);
                let l2 = self.math1(M::Abs, l2);
                let spread = self.sub(one, l2);
                let chroma = self.mul(spread, s);
                let half_chroma = self.mul(chroma, half);
                let top = self.add(l, half_chroma);
                self.rgb_of_hue(c[0], top, chroma)
            }
            "xyz" | "XYZ" => self.linear3(&invert3(&rgb_to_xyz_matrix()), c),
            "xyY" => {
                let xyz = self.xyy_to_xyz(c);
                self.linear3(&invert3(&rgb_to_xyz_matrix()), &xyz)
            }
            "YIQ" => self.linear3(&invert3(&RGB_TO_YIQ), c),
            _ => c.to_vec(),
        }
    }

    fn rgb_to_colour_parts(&mut self, space: &str, c: &[Value]) -> Vec<Value> {
        match space {
            "hsv" => {
                let (hue, top, _, chroma) = self.hue_of(c);
                let zero = self.float(0.0);
                let ratio = self.div(chroma, top);
                let lit = self.binary(Op::NotEqual, top, zero);
                let s = self.pick(lit, ratio, zero);
                vec![hue, s, top]
            }
            "hsl" => {
                let (hue, top, bottom, chroma) = self.hue_of(c);
                let (zero, one, half) = (self.float(0.0), self.float(1.0), self.float(0.5));
                let sum = self.add(top, bottom);
                let l = self.mul(sum, half);
                let l2 = self.sub(sum, one);
                let l2 = self.math1(M::Abs, l2);
                let spread = self.sub(one, l2);
                let ratio = self.div(chroma, spread);
                let defined = self.binary(Op::NotEqual, spread, zero);
                let s = self.pick(defined, ratio, zero);
                vec![hue, s, l]
            }
            "xyz" | "XYZ" => self.linear3(&rgb_to_xyz_matrix(), c),
            "xyY" => {
                let xyz = self.linear3(&rgb_to_xyz_matrix(), c);
                let sum = self.add(xyz[0], xyz[1]);
                let sum = self.add(sum, xyz[2]);
                let zero = self.float(0.0);
                let some = self.binary(Op::NotEqual, sum, zero);
                let x = self.div(xyz[0], sum);
                let y = self.div(xyz[1], sum);
                let (wx, wy) = (self.float(WHITE[0]), self.float(WHITE[1]));
                let x = self.pick(some, x, wx);
                let y = self.pick(some, y, wy);
                vec![x, y, xyz[1]]
            }
            "YIQ" => self.linear3(&RGB_TO_YIQ, c),
            _ => c.to_vec(),
        }
    }

    /// RGB from a hue (in turns), the largest channel and the chroma: channel n (offsets 5, 3, 1)
    /// is `top - chroma * clamp(min(k, 4 - k), 0, 1)` with `k = (6 h + n) mod 6`.
    fn rgb_of_hue(&mut self, hue: Value, top: Value, chroma: Value) -> Vec<Value> {
        let (zero, one, four, six) = (self.float(0.0), self.float(1.0), self.float(4.0), self.float(6.0));
        let h6 = self.mul(hue, six);
        [5.0, 3.0, 1.0]
            .iter()
            .map(|&n| {
                let n = self.float(n);
                let k = self.add(h6, n);
                let k = self.modulo(k, six);
                let rest = self.sub(four, k);
                let w = self.math2(M::Min, k, rest);
                let w = self.clamp_to(w, zero, one);
                let drop = self.mul(chroma, w);
                self.sub(top, drop)
            })
            .collect()
    }

    /// The hue (in turns, 0 for greys), the largest and smallest channel and the chroma.
    fn hue_of(&mut self, c: &[Value]) -> (Value, Value, Value, Value) {
        let (r, g, b) = (c[0], c[1], c[2]);
        let top = self.math2(M::Max, r, g);
        let top = self.math2(M::Max, top, b);
        let bottom = self.math2(M::Min, r, g);
        let bottom = self.math2(M::Min, bottom, b);
        let chroma = self.sub(top, bottom);
        let (zero, two, four, six) = (self.float(0.0), self.float(2.0), self.float(4.0), self.float(6.0));
        let mut part = |p: Value, q: Value, offset: Value| {
            let d = self.sub(p, q);
            let d = self.div(d, chroma);
            self.add(d, offset)
        };
        let near_r = part(g, b, zero);
        let near_g = part(b, r, two);
        let near_b = part(r, g, four);
        let is_r = self.binary(Op::Equal, top, r);
        let is_g = self.binary(Op::Equal, top, g);
        let h = self.pick(is_g, near_g, near_b);
        let h = self.pick(is_r, near_r, h);
        let h = self.modulo(h, six);
        let h = self.div(h, six);
        let coloured = self.binary(Op::Greater, chroma, zero);
        let hue = self.pick(coloured, h, zero);
        (hue, top, bottom, chroma)
    }

    /// `(x, y, Y)` to `(X, Y, Z)`; 0 where y is 0.
    fn xyy_to_xyz(&mut self, c: &[Value]) -> Vec<Value> {
        let (x, y, lum) = (c[0], c[1], c[2]);
        let (zero, one) = (self.float(0.0), self.float(1.0));
        let scale = self.div(lum, y);
        let big_x = self.mul(x, scale);
        let z = self.sub(one, x);
        let z = self.sub(z, y);
        let big_z = self.mul(z, scale);
        let defined = self.binary(Op::NotEqual, y, zero);
        let big_x = self.pick(defined, big_x, zero);
        let big_z = self.pick(defined, big_z, zero);
        vec![big_x, lum, big_z]
    }

    /// `m * c` for a constant 3x3 matrix: each row's products summed left to right.
    fn linear3(&mut self, m: &[[f64; 3]; 3], c: &[Value]) -> Vec<Value> {
        m.iter()
            .map(|row| {
                let terms: Vec<Value> = row
                    .iter()
                    .zip(c)
                    .map(|(k, x)| {
                        let k = self.float(*k);
                        self.mul(k, *x)
                    })
                    .collect();
                let sum = self.add(terms[0], terms[1]);
                self.add(sum, terms[2])
            })
            .collect()
    }
}
