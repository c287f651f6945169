//! The analytic shapes: RenderMan's quadrics (sphere, torus), a square and a cube.
//!
//! The quadrics follow RenderMan's parameterizations (RI spec, "Quadrics"): both are built around
//! the z axis, `u` runs around it from +x towards +y, and `dpdu × dpdv` points outwards.

use super::{Mesh, SurfacePoint, clamp_count, length};
use glam::Vec3;
use std::f32::consts::{PI, TAU};

/// `(cos, sin)` of the angle `2π t`, exact at the seam `t = 1` so that both ends of a closed
/// parameter land on the same position.
fn turn(t: f32) -> (f32, f32) {
    if t >= 1.0 { (1.0, 0.0) } else { ((TAU * t).cos(), (TAU * t).sin()) }
}

impl Mesh {
    /// A sphere of `radius` about the origin, with poles on the z axis.
    ///
    /// As RenderMan's `Sphere`: `u` is the longitude θ / 2π (from +x towards +y) and `v` runs from
    /// the south pole (z = −radius, v = 0) to the north pole (v = 1). `slices` (around) is clamped
    /// to at least 3 and `stacks` (pole to pole) to at least 2. At the poles `dpdu` is zero, as it
    /// is analytically; the normal there is still exact.
    pub fn sphere(radius: f32, slices: u32, stacks: u32) -> Mesh {
        let r = length(radius);
        Mesh::grid(clamp_count(slices, 3), clamp_count(stacks, 2), |u, v| {
            let (cos_t, sin_t) = turn(u);
            // Exact at the poles so that their triangles are recognized as degenerate.
            let (cos_p, sin_p) = match v {
                0.0 => (0.0, -1.0),
                1.0 => (0.0, 1.0),
                _ => {
                    let phi = PI * (v - 0.5);
                    (phi.cos(), phi.sin())
                }
            };
            let n = Vec3::new(cos_p * cos_t, cos_p * sin_t, sin_p);
            SurfacePoint {
                p: r * n,
                n,
                dpdu: TAU * r * cos_p * Vec3::new(-sin_t, cos_t, 0.0),
                dpdv: PI * r * Vec3::new(-sin_p * cos_t, -sin_p * sin_t, cos_p),
            }
        })
    }

    /// A torus about the z axis: a tube of radius `minor` swept along a circle of radius `major`.
    ///
    /// As RenderMan's `Torus`: `u` goes around the z axis, `v` around the tube, starting on the
    /// outer equator and rising towards +z first. `slices` (around z) and `rings` (around the tube)
    /// are clamped to at least 3. When `minor > major` the tube passes through the axis; normals
    /// stay the analytic ones.
    pub fn torus(major: f32, minor: f32, slices: u32, rings: u32) -> Mesh {
        let (big, small) = (length(major), length(minor));
        Mesh::grid(clamp_count(slices, 3), clamp_count(rings, 3), |u, v| {
            let (cos_t, sin_t) = turn(u);
            let (cos_p, sin_p) = turn(v);
            let n = Vec3::new(cos_p * cos_t, cos_p * sin_t, sin_p);
            let ring = big + small * cos_p;
            SurfacePoint {
                p: Vec3::new(ring * cos_t, ring * sin_t, small * sin_p),
                n,
                dpdu: TAU * ring * Vec3::new(-sin_t, cos_t, 0.0),
                dpdv: TAU * small * Vec3::new(-sin_p * cos_t, -sin_p * sin_t, cos_p),
            }
        })
    }

    /// A square of side `size` in the plane z = 0, centred on the origin, split into
    /// `subdivisions × subdivisions` cells (clamped to at least 1).
    ///
    /// It is oriented like a RenderMan bilinear patch facing the default camera, which looks down
    /// +z: the normal is −z, `u` runs along +x and `v` along −y. Seen through a camera placed at
    /// −z, `(s, t) = (0, 0)` is the top-left corner, so an image texture appears upright.
    pub fn plane(size: f32, subdivisions: u32) -> Mesh {
        let side = length(size);
        let n = clamp_count(subdivisions, 1);
        Mesh::grid(n, n, |u, v| SurfacePoint {
            p: Vec3::new(side * (u - 0.5), side * (0.5 - v), 0.0),
            n: Vec3::NEG_Z,
            dpdu: Vec3::new(side, 0.0, 0.0),
            dpdv: Vec3::new(0.0, -side, 0.0),
        })
    }

    /// An axis-aligned cube of edge `size` centred on the origin: six faces of two triangles each,
    /// with flat normals and each face's own `(u, v)` square.
    ///
    /// Each face is parameterized so that `dpdu × dpdv` is its outward normal and `v` points down
    /// (−y) on the four side faces, so a texture looks upright on each side seen from outside with
    /// +y up; on the top `v` points towards −z and on the bottom towards +z.
    pub fn cube(size: f32) -> Mesh {
        let side = length(size);
        // (outward normal, u axis, v axis) with u × v = normal.
        const FACES: [(Vec3, Vec3, Vec3); 6] = [
            (Vec3::NEG_Z, Vec3::X, Vec3::NEG_Y),
            (Vec3::Z, Vec3::NEG_X, Vec3::NEG_Y),
            (Vec3::X, Vec3::Z, Vec3::NEG_Y),
            (Vec3::NEG_X, Vec3::NEG_Z, Vec3::NEG_Y),
            (Vec3::Y, Vec3::X, Vec3::NEG_Z),
            (Vec3::NEG_Y, Vec3::X, Vec3::Z),
        ];
        let mut mesh = Mesh::default();
        for (n, du, dv) in FACES {
            mesh.append_grid(1, 1, |u, v| SurfacePoint {
                p: side * (0.5 * n + (u - 0.5) * du + (v - 0.5) * dv),
                n,
                dpdu: side * du,
                dpdv: side * dv,
            });
        }
        mesh
    }
}
