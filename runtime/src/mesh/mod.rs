//! Triangle meshes carrying what a shader's geometric inputs need: `P`, `N`, `u`, `v`, `s`, `t`,
//! `dPdu` and `dPdv`, all in object space.
//!
//! Conventions, shared by every constructor and by [`Mesh::validate`]:
//!
//! - **Winding.** For each triangle `(a, b, c)` the cross product `(b - a) × (c - a)` points the
//!   same way as the vertex normals, i.e. out of the surface. This is "counter-clockwise seen from
//!   outside" when coordinates are read right-handed. RenderMan reads world and camera space
//!   left-handed (see [`crate::camera`]); there the same triangles appear *clockwise* on screen
//!   when they face the eye, so a pipeline that culls must declare clockwise front faces.
//! - **Parameters.** `uvs` holds the surface parameters `(u, v)` in `[0, 1]`, which are also the
//!   default texture coordinates `(s, t)`. Where a shape has an analytic parameterization,
//!   `dpdu × dpdv` points along the normal, as in RenderMan, so `calculatenormal(P)` agrees with `N`.
//! - **Bad sizes do not panic.** Tessellation counts are clamped into a documented range
//!   ([`MAX_DETAIL`] at most, per shape minimums below it); a negative length is taken by its
//!   magnitude and a non-finite one becomes zero (a degenerate but valid mesh).

mod obj;
mod shapes;
mod teapot;
mod teapot_data;

pub use teapot::TEAPOT_MAX_SUBDIVISIONS;

use glam::{Mat3, Mat4, Vec3};
use patina_compiler::backend::wgsl::interface::MeshAttribute;
use std::fmt;
use std::path::PathBuf;

/// The largest tessellation count accepted along one parameter; larger requests are clamped, which
/// bounds a mesh at about a million vertices however a scene's `detail` is set.
pub const MAX_DETAIL: u32 = 1024;

/// A triangle mesh with everything a shader's geometric inputs need, in object space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Unit shading normals.
    pub normals: Vec<[f32; 3]>,
    /// Surface parameters `(u, v)` in `[0, 1]`; also the default texture coordinates `(s, t)`.
    pub uvs: Vec<[f32; 2]>,
    /// ∂P/∂u, not normalized; analytic where the shape has a parameterization.
    pub dpdu: Vec<[f32; 3]>,
    /// ∂P/∂v, not normalized.
    pub dpdv: Vec<[f32; 3]>,
    /// Triangle list, wound as described in the module documentation.
    pub indices: Vec<u32>,
}

/// Why a mesh could not be loaded or is not well formed.
#[derive(Clone, Debug, PartialEq)]
pub enum MeshError {
    /// The file could not be read or parsed; `message` says why.
    Load {
        /// The mesh file.
        path: PathBuf,
        /// Why it could not be read or parsed.
        message: String,
    },
    /// The mesh breaks an invariant of [`Mesh`] (array lengths, index range, finite values).
    Invalid(String),
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::Load { path, message } => write!(f, "cannot load {}: {message}", path.display()),
            MeshError::Invalid(message) => write!(f, "invalid mesh: {message}"),
        }
    }
}

impl std::error::Error for MeshError {}

/// One evaluated point of a parametric surface, before it is stored as f32.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SurfacePoint {
    pub p: Vec3,
    pub n: Vec3,
    pub dpdu: Vec3,
    pub dpdv: Vec3,
}

impl Mesh {
    /// A mesh property as the vertex stage reads it: vertex-major f32 components.
    pub fn attribute(&self, what: MeshAttribute) -> Vec<f32> {
        match what {
            MeshAttribute::Normal => self.normals.iter().flatten().copied().collect(),
            MeshAttribute::Uv => self.uvs.iter().flatten().copied().collect(),
            MeshAttribute::DpDu => self.dpdu.iter().flatten().copied().collect(),
            MeshAttribute::DpDv => self.dpdv.iter().flatten().copied().collect(),
            _ => self.positions.iter().flatten().copied().collect(),
        }
    }

    /// The number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// The number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Checks the invariants every consumer relies on: all per-vertex arrays have the same length,
    /// the index list is whole triangles within range, and no value is NaN or infinite.
    pub fn validate(&self) -> Result<(), MeshError> {
        let n = self.positions.len();
        let lengths = [
            ("normals", self.normals.len()),
            ("uvs", self.uvs.len()),
            ("dpdu", self.dpdu.len()),
            ("dpdv", self.dpdv.len()),
        ];
        for (name, len) in lengths {
            if len != n {
                return Err(MeshError::Invalid(format!("{name} has {len} entries for {n} positions")));
            }
        }
        if !self.indices.len().is_multiple_of(3) {
            return Err(MeshError::Invalid(format!(
                "{} indices is not a whole number of triangles",
                self.indices.len()
            )));
        }
        if let Some((i, &index)) = self.indices.iter().enumerate().find(|&(_, &x)| x as usize >= n) {
            return Err(MeshError::Invalid(format!("index {i} is {index}, past the {n} vertices")));
        }
        let arrays3 = [
            ("positions", &self.positions),
            ("normals", &self.normals),
            ("dpdu", &self.dpdu),
            ("dpdv", &self.dpdv),
        ];
        for (name, array) in arrays3 {
            if let Some(i) = array.iter().position(|v| v.iter().any(|x| !x.is_finite())) {
                return Err(MeshError::Invalid(format!("{name}[{i}] is not finite: {:?}", array[i])));
            }
        }
        if let Some(i) = self.uvs.iter().position(|v| v.iter().any(|x| !x.is_finite())) {
            return Err(MeshError::Invalid(format!("uvs[{i}] is not finite: {:?}", self.uvs[i])));
        }
        Ok(())
    }

    /// The mesh moved by the affine transformation `m` (column vectors: `m * p`).
    ///
    /// Positions are transformed as points, `dpdu` and `dpdv` as vectors and normals by the inverse
    /// transpose (computed as the cofactor matrix, so a singular `m` still gives finite normals; a
    /// normal that collapses to zero keeps its old direction). A mirroring `m` (negative
    /// determinant) also reverses the winding so that front faces stay front faces; `dpdu × dpdv`
    /// then points against the normal, as RenderMan's handedness rule has it.
    pub fn transformed(&self, m: Mat4) -> Mesh {
        let linear = Mat3::from_mat4(m);
        let det = linear.determinant();
        let cofactor = Mat3::from_cols(
            linear.y_axis.cross(linear.z_axis),
            linear.z_axis.cross(linear.x_axis),
            linear.x_axis.cross(linear.y_axis),
        );
        let sign = if det < 0.0 { -1.0 } else { 1.0 };
        let point = |p: &[f32; 3]| m.transform_point3(Vec3::from(*p)).to_array();
        let vector = |v: &[f32; 3]| linear.mul_vec3(Vec3::from(*v)).to_array();
        let normal = |n: &[f32; 3]| {
            let old = Vec3::from(*n);
            (sign * cofactor.mul_vec3(old)).try_normalize().unwrap_or(old).to_array()
        };
        let mut indices = self.indices.clone();
        if det < 0.0 {
            for triangle in indices.chunks_exact_mut(3) {
                triangle.swap(1, 2);
            }
        }
        Mesh {
            positions: self.positions.iter().map(point).collect(),
            normals: self.normals.iter().map(normal).collect(),
            uvs: self.uvs.clone(),
            dpdu: self.dpdu.iter().map(vector).collect(),
            dpdv: self.dpdv.iter().map(vector).collect(),
            indices,
        }
    }

    /// The axis-aligned bounding box `(min, max)` of the positions; `None` for an empty mesh.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let first = Vec3::from(*self.positions.first()?);
        Some(self.positions.iter().fold((first, first), |(lo, hi), p| {
            let p = Vec3::from(*p);
            (lo.min(p), hi.max(p))
        }))
    }

    /// A grid of `(nu + 1) × (nv + 1)` vertices at `u = i / nu`, `v = j / nv`, evaluated by
    /// `surface`, with two triangles per cell wound so that `dpdu × dpdv` is their front.
    /// Triangles with two bitwise-equal corners (at a pole) are left out.
    pub(crate) fn grid(nu: u32, nv: u32, surface: impl Fn(f32, f32) -> SurfacePoint) -> Mesh {
        let mut mesh = Mesh::default();
        mesh.append_grid(nu, nv, surface);
        mesh
    }

    /// Adds a grid as [`Mesh::grid`] makes it to this mesh.
    pub(crate) fn append_grid(&mut self, nu: u32, nv: u32, surface: impl Fn(f32, f32) -> SurfacePoint) {
        let base = self.positions.len() as u32;
        for j in 0..=nv {
            for i in 0..=nu {
                let (u, v) = (i as f32 / nu as f32, j as f32 / nv as f32);
                let s = surface(u, v);
                self.positions.push(s.p.to_array());
                self.normals.push(s.n.to_array());
                self.uvs.push([u, v]);
                self.dpdu.push(s.dpdu.to_array());
                self.dpdv.push(s.dpdv.to_array());
            }
        }
        let row = nu + 1;
        for j in 0..nv {
            for i in 0..nu {
                let a = base + j * row + i;
                let (b, c, d) = (a + 1, a + row + 1, a + row);
                for triangle in [[a, b, c], [a, c, d]] {
                    if !self.has_repeated_corner(triangle) {
                        self.indices.extend_from_slice(&triangle);
                    }
                }
            }
        }
    }

    fn has_repeated_corner(&self, [a, b, c]: [u32; 3]) -> bool {
        let p = |i: u32| self.positions[i as usize];
        p(a) == p(b) || p(b) == p(c) || p(a) == p(c)
    }
}

/// A tessellation count clamped into `min..=MAX_DETAIL`.
pub(crate) fn clamp_count(n: u32, min: u32) -> u32 {
    n.clamp(min, MAX_DETAIL)
}

/// A length made usable: its magnitude, or zero when it is NaN or infinite.
pub(crate) fn length(x: f32) -> f32 {
    if x.is_finite() { x.abs() } else { 0.0 }
}

#[cfg(test)]
mod tests;
