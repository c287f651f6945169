//! Perspective-correct interpolation over a triangle, its analytic screen-space derivatives, and
//! the depth plane, all from the triangle's clip-space vertices.
//!
//! With `Vᵢ = (xᵢ, yᵢ, wᵢ)` and `M = [V₀ V₁ V₂]`, the screen point `(u, v)` (NDC) sees the point of
//! the triangle's plane with barycentrics `bᵢ = eᵢ / Σ eᵢ`, where `e = M⁻¹ (u, v, 1)`. Each `eᵢ` is
//! linear in screen space (it is `λᵢ / wᵢ`, λ the screen-space barycentrics), `Σ eᵢ = 1/w`, and
//! `z/w = Σ zᵢ eᵢ`. This needs no division by a vertex's w, so it holds for triangles crossing the
//! near plane as well: clipping only decides which samples are drawn.

/// The interpolation planes of one triangle, in framebuffer pixel coordinates (y down).
#[derive(Clone, Debug)]
pub(super) struct Interpolant {
    /// `eᵢ(x, y) = gx[i] x + gy[i] y + c[i]`.
    gx: [f64; 3],
    gy: [f64; 3],
    c: [f64; 3],
    /// `z/w = depth[0] + depth[1] x + depth[2] y`.
    depth: [f64; 3],
}

/// The perspective-correct barycentrics at a sample and their derivatives along x and y.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(super) struct Sample {
    /// Weights of the three vertices (summing to 1).
    pub(super) bary: [f64; 3],
    /// d bary / dx, one pixel to the right.
    pub(super) ddx: [f64; 3],
    /// d bary / dy, one row down.
    pub(super) ddy: [f64; 3],
}

impl Interpolant {
    /// `None` when the triangle's plane passes through the eye (no area on screen) or the planes
    /// are not finite.
    pub(super) fn new(v: &[[f32; 4]; 3], width: u32, height: u32) -> Option<Self> {
        let p = v.map(|p| [f64::from(p[0]), f64::from(p[1]), f64::from(p[3])]);
        let rows = [0, 1, 2].map(|i| cross(p[(i + 1) % 3], p[(i + 2) % 3]));
        let det = dot(p[0], rows[0]);
        if det == 0.0 {
            return None;
        }
        // e in NDC is rows·(u, v, 1)/det; with u = 2x/width - 1 and v = 1 - 2y/height in pixels:
        let (sx, sy) = (2.0 / f64::from(width), 2.0 / f64::from(height));
        let gx = rows.map(|r| r[0] * sx / det);
        let gy = rows.map(|r| -r[1] * sy / det);
        let c = rows.map(|r| (r[2] - r[0] + r[1]) / det);
        let z = v.map(|p| f64::from(p[2]));
        let depth = [dot(z, c), dot(z, gx), dot(z, gy)];
        let all = gx.iter().chain(&gy).chain(&c).chain(&depth);
        all.clone().all(|k| k.is_finite()).then_some(Interpolant { gx, gy, c, depth })
    }

    /// The depth z/w at a point, clamped to the depth range [0, 1].
    pub(super) fn depth(&self, x: f64, y: f64) -> f32 {
        let [d, dx, dy] = self.depth;
        (d + dx * x + dy * y).clamp(0.0, 1.0) as f32
    }

    /// Barycentrics and derivatives at a point; `None` where the point is not in front of the eye
    /// (never inside a clipped triangle, short of rounding) or the values would not be finite.
    pub(super) fn sample(&self, x: f64, y: f64) -> Option<Sample> {
        let e: [f64; 3] = std::array::from_fn(|i| self.gx[i] * x + self.gy[i] * y + self.c[i]);
        let inv_w = e[0] + e[1] + e[2];
        if !(inv_w > 0.0 && inv_w.is_finite()) {
            return None;
        }
        let bary = e.map(|e| e / inv_w);
        // Quotient rule on eᵢ / Σe: (gᵢ - bᵢ Σg) / Σe.
        let (sum_gx, sum_gy) = (self.gx.iter().sum::<f64>(), self.gy.iter().sum::<f64>());
        let ddx = std::array::from_fn(|i| (self.gx[i] - bary[i] * sum_gx) / inv_w);
        let ddy = std::array::from_fn(|i| (self.gy[i] - bary[i] * sum_gy) / inv_w);
        let s = Sample { bary, ddx, ddy };
        s.bary.iter().chain(&s.ddx).chain(&s.ddy).all(|v| v.is_finite()).then_some(s)
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRI: [[f32; 4]; 3] = [[-0.8, -0.6, 0.2, 1.0], [1.5, -0.5, 1.2, 2.0], [0.2, 2.4, 2.9, 3.0]];

    fn to_pixels(v: [f32; 4], w: f64, h: f64) -> (f64, f64) {
        let (x, y, vw) = (f64::from(v[0]), f64::from(v[1]), f64::from(v[3]));
        ((x / vw + 1.0) * w / 2.0, (1.0 - y / vw) * h / 2.0)
    }

    #[test]
    fn vertices_get_their_own_weight_and_depth() {
        let it = Interpolant::new(&TRI, 64, 32).unwrap();
        for (i, v) in TRI.iter().enumerate() {
            let (x, y) = to_pixels(*v, 64.0, 32.0);
            let s = it.sample(x, y).unwrap();
            for (k, b) in s.bary.iter().enumerate() {
                assert!((b - if k == i { 1.0 } else { 0.0 }).abs() < 1e-12, "{i} {k} {b}");
            }
            assert!((f64::from(it.depth(x, y)) - f64::from(v[2] / v[3])).abs() < 1e-7);
        }
    }

    #[test]
    fn derivatives_match_central_differences() {
        let it = Interpolant::new(&TRI, 64, 32).unwrap();
        let h = 1e-4;
        for &(x, y) in &[(30.5, 14.5), (35.25, 9.75), (40.5, 20.5)] {
            let s = it.sample(x, y).unwrap();
            let (xp, xm) = (it.sample(x + h, y).unwrap(), it.sample(x - h, y).unwrap());
            let (yp, ym) = (it.sample(x, y + h).unwrap(), it.sample(x, y - h).unwrap());
            for i in 0..3 {
                let fx = (xp.bary[i] - xm.bary[i]) / (2.0 * h);
                let fy = (yp.bary[i] - ym.bary[i]) / (2.0 * h);
                assert!((s.ddx[i] - fx).abs() <= 1e-6 * (1.0 + fx.abs()), "x {i}: {} {fx}", s.ddx[i]);
                assert!((s.ddy[i] - fy).abs() <= 1e-6 * (1.0 + fy.abs()), "y {i}: {} {fy}", s.ddy[i]);
            }
        }
    }

    #[test]
    fn a_plane_through_the_eye_has_no_interpolant() {
        // Three collinear points: a segment, whose plane contains the eye.
        let flat = [[0.0, 0.0, 0.5, 1.0], [1.0, 0.0, 0.5, 1.0], [2.0, 0.0, 0.5, 1.0]];
        assert!(Interpolant::new(&flat, 8, 8).is_none());
    }
}
