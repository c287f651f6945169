//! The Utah teapot, tessellated from its bicubic Bézier patches with analytic derivatives.

use super::teapot_data::{PATCHES, VERTICES};
use super::{MAX_DETAIL, Mesh, SurfacePoint};
use glam::DVec3;

/// The most cells along each parameter of one patch: 32 patches of 129 × 129 vertices is about as
/// large as the other shapes get at [`MAX_DETAIL`].
pub const TEAPOT_MAX_SUBDIVISIONS: u32 = MAX_DETAIL / 8;

/// How far from a degenerate point the normal is taken instead, in patch parameters.
const NUDGE: f64 = 1e-4;

impl Mesh {
    /// The Utah teapot: each of Newell's 32 patches as a grid of `subdivisions × subdivisions`
    /// cells (clamped to `1..=TEAPOT_MAX_SUBDIVISIONS`).
    ///
    /// The data's own frame is kept, as in RenderMan's teapot: z up, the base on z = 0, the lid's
    /// knob at z = 3.15, the spout towards +x (about 6.4 long, 4 deep). Each patch keeps its own
    /// `(u, v)` in `[0, 1]`, like a RenderMan patch primitive, so vertices along patch seams are
    /// repeated. Normals are `dP/du × dP/dv`; where that vanishes (the poles of the lid's knob and
    /// of the bottom, where a whole row of control points coincides) the normal is taken a little
    /// way inside the patch, which converges to the surface's limit normal.
    pub fn teapot(subdivisions: u32) -> Mesh {
        let n = subdivisions.clamp(1, TEAPOT_MAX_SUBDIVISIONS);
        let mut mesh = Mesh::default();
        for patch in &PATCHES {
            let control = control_points(patch);
            mesh.append_grid(n, n, |u, v| evaluate(&control, f64::from(u), f64::from(v)));
        }
        mesh
    }
}

/// A patch's control points as `[row][column]`.
fn control_points(patch: &[u16; 16]) -> [[DVec3; 4]; 4] {
    std::array::from_fn(|row| {
        std::array::from_fn(|col| DVec3::from(VERTICES[usize::from(patch[row * 4 + col])].map(f64::from)))
    })
}

/// The cubic Bernstein polynomials at `t`, exact at 0 and 1.
fn bernstein(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t]
}

/// Their derivatives.
fn bernstein_derivative(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [-3.0 * s * s, 3.0 * s * s - 6.0 * t * s, 6.0 * t * s - 3.0 * t * t, 3.0 * t * t]
}

/// The cubic Bézier curve over `points` at `t` (or its derivative).
fn curve(points: &[DVec3; 4], t: f64, derivative: bool) -> DVec3 {
    // A row of equal points (a pole) evaluates to that point exactly, so pole vertices coincide
    // bitwise and their zero-area triangles are dropped by the grid builder.
    if points.iter().all(|p| *p == points[0]) {
        return if derivative { DVec3::ZERO } else { points[0] };
    }
    let weights = if derivative { bernstein_derivative(t) } else { bernstein(t) };
    points.iter().zip(weights).map(|(p, w)| w * *p).sum()
}

/// The position and both partial derivatives at `(u, v)`.
fn partials(control: &[[DVec3; 4]; 4], u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
    let rows: [DVec3; 4] = std::array::from_fn(|i| curve(&control[i], u, false));
    let row_tangents: [DVec3; 4] = std::array::from_fn(|i| curve(&control[i], u, true));
    (curve(&rows, v, false), curve(&row_tangents, v, false), curve(&rows, v, true))
}

fn unit_normal(dpdu: DVec3, dpdv: DVec3) -> Option<DVec3> {
    let n = dpdu.cross(dpdv);
    let scale = dpdu.length_squared() + dpdv.length_squared();
    (n.length() > 1e-9 * scale).then(|| n.normalize())
}

fn evaluate(control: &[[DVec3; 4]; 4], u: f64, v: f64) -> SurfacePoint {
    let (p, dpdu, dpdv) = partials(control, u, v);
    let inward = |t: f64| if t < 0.5 { t + NUDGE } else { t - NUDGE };
    let n = unit_normal(dpdu, dpdv)
        .or_else(|| {
            [(u, inward(v)), (inward(u), v), (inward(u), inward(v))].into_iter().find_map(|(a, b)| {
                let (_, du, dv) = partials(control, a, b);
                unit_normal(du, dv)
            })
        })
        .unwrap_or(DVec3::Z);
    SurfacePoint { p: p.as_vec3(), n: n.as_vec3(), dpdu: dpdu.as_vec3(), dpdv: dpdv.as_vec3() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn poles_have_the_limit_normal() {
        let mesh = Mesh::teapot(4);
        for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
            if *p == [0.0, 0.0, 3.15] {
                assert!(Vec3::from(*n).dot(Vec3::Z) > 0.999, "{n:?}");
            }
            if *p == [0.0, 0.0, 0.0] {
                assert!(Vec3::from(*n).dot(Vec3::NEG_Z) > 0.999, "{n:?}");
            }
        }
    }

    #[test]
    fn patch_corners_interpolate_the_control_points() {
        for patch in &PATCHES {
            let control = control_points(patch);
            for (u, v, row, col) in [(0.0, 0.0, 0, 0), (1.0, 0.0, 0, 3), (0.0, 1.0, 3, 0), (1.0, 1.0, 3, 3)] {
                assert_eq!(partials(&control, u, v).0, control[row][col]);
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let patch = &PATCHES[5];
        let control = control_points(patch);
        let (u, v, h) = (0.3, 0.6, 1e-6);
        let (_, dpdu, dpdv) = partials(&control, u, v);
        let fd_u = (partials(&control, u + h, v).0 - partials(&control, u - h, v).0) / (2.0 * h);
        let fd_v = (partials(&control, u, v + h).0 - partials(&control, u, v - h).0) / (2.0 * h);
        assert!((dpdu - fd_u).length() < 1e-6 && (dpdv - fd_v).length() < 1e-6);
    }
}
