//! Wavefront OBJ files, through tobj, completed with whatever the file leaves out.

use super::{Mesh, MeshError};
use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::path::Path;

impl Mesh {
    /// Loads every object of an OBJ file into one mesh (polygons triangulated, materials ignored).
    ///
    /// What the file leaves out is derived: normals are smooth, area-weighted averages over the
    /// faces around each position (shared across texture seams); missing texture coordinates are
    /// zero. The file's `vt` has t = 0 at the bottom of the image, RenderMan's at the top, so
    /// `t = 1 − vt`. `dpdu` and `dpdv` solve each triangle's uv gradients and are averaged per
    /// vertex; a vertex with no usable gradient (no uvs, or degenerate ones) gets a tangent frame
    /// perpendicular to its normal, with `dpdu × dpdv = N`. A file without faces is an error.
    pub fn load_obj(path: impl AsRef<Path>) -> Result<Mesh, MeshError> {
        let path = path.as_ref();
        let load_error = |message: String| MeshError::Load { path: path.to_path_buf(), message };
        let bytes = std::fs::read(path).map_err(|e| load_error(crate::scene::io_message(&e)))?;
        let options = tobj::LoadOptions {
            single_index: true,
            triangulate: true,
            ignore_points: true,
            ignore_lines: true,
        };
        let no_materials = |_: &Path| Err(tobj::LoadError::OpenFileFailed);
        let (models, _) = tobj::load_obj_buf(&mut bytes.as_slice(), &options, no_materials)
            .map_err(|e| load_error(e.to_string()))?;
        let mut mesh = Mesh::default();
        for model in &models {
            let count = model.mesh.positions.len() / 3;
            if let Some(&i) = model.mesh.indices.iter().find(|&&i| i as usize >= count) {
                return Err(load_error(format!("object `{}` refers to vertex {i} of {count}", model.name)));
            }
            append_model(&mut mesh, &model.mesh);
        }
        if mesh.indices.is_empty() {
            return Err(load_error("the file has no faces".into()));
        }
        mesh.validate().map_err(|e| load_error(e.to_string()))?;
        Ok(mesh)
    }
}

fn append_model(mesh: &mut Mesh, model: &tobj::Mesh) {
    let base = mesh.positions.len();
    let count = model.positions.len() / 3;
    mesh.positions.extend(model.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
    mesh.indices.extend(model.indices.iter().map(|&i| i + base as u32));
    let triangles: Vec<[usize; 3]> =
        model.indices.chunks_exact(3).map(|t| [0, 1, 2].map(|k| t[k] as usize + base)).collect();
    if model.normals.len() == model.positions.len() {
        mesh.normals.extend(model.normals.chunks_exact(3).map(|n| [n[0], n[1], n[2]]));
    } else {
        mesh.normals.extend(smooth_normals(&mesh.positions, base, &triangles));
    }
    if model.texcoords.len() == 2 * count {
        mesh.uvs.extend(model.texcoords.chunks_exact(2).map(|t| [t[0], 1.0 - t[1]]));
    } else {
        mesh.uvs.extend(std::iter::repeat_n([0.0; 2], count));
    }
    for n in &mut mesh.normals[base..] {
        *n = Vec3::from(*n).try_normalize().unwrap_or(Vec3::Z).to_array();
    }
    let (dpdu, dpdv) = tangents(mesh, base, &triangles);
    mesh.dpdu.extend(dpdu);
    mesh.dpdv.extend(dpdv);
}

/// Area-weighted vertex normals for the vertices from `base` on, summed by position so that
/// vertices split by a texture seam get the same normal.
fn smooth_normals(positions: &[[f32; 3]], base: usize, triangles: &[[usize; 3]]) -> Vec<[f32; 3]> {
    let key = |p: [f32; 3]| p.map(f32::to_bits);
    let mut sums: HashMap<[u32; 3], Vec3> = HashMap::new();
    for t in triangles {
        let [a, b, c] = t.map(|i| Vec3::from(positions[i]));
        // The cross product's length is twice the area: the weighting comes for free.
        let face = (b - a).cross(c - a);
        for &i in t {
            *sums.entry(key(positions[i])).or_default() += face;
        }
    }
    positions[base..].iter().map(|p| sums.get(&key(*p)).copied().unwrap_or(Vec3::ZERO).to_array()).collect()
}

/// Per-vertex ∂P/∂u and ∂P/∂v for the vertices from `base` on (whose normals and uvs are set).
fn tangents(mesh: &Mesh, base: usize, triangles: &[[usize; 3]]) -> (Vec<[f32; 3]>, Vec<[f32; 3]>) {
    let count = mesh.positions.len() - base;
    let mut sums = vec![(Vec3::ZERO, Vec3::ZERO, 0u32); count];
    for t in triangles {
        let [p0, p1, p2] = t.map(|i| Vec3::from(mesh.positions[i]));
        let [t0, t1, t2] = t.map(|i| Vec2::from(mesh.uvs[i]));
        let (e1, e2, d1, d2) = (p1 - p0, p2 - p0, t1 - t0, t2 - t0);
        let det = d1.x * d2.y - d2.x * d1.y;
        if det.abs() <= f32::EPSILON * d1.length_squared().max(d2.length_squared()) {
            continue;
        }
        // Solve [e1 e2] = [dPdu dPdv] [d1 d2] for the two derivative columns.
        let dpdu = (e1 * d2.y - e2 * d1.y) / det;
        let dpdv = (e2 * d1.x - e1 * d2.x) / det;
        if !(dpdu.is_finite() && dpdv.is_finite()) {
            continue;
        }
        for &i in t {
            let s = &mut sums[i - base];
            *s = (s.0 + dpdu, s.1 + dpdv, s.2 + 1);
        }
    }
    sums.iter()
        .zip(&mesh.normals[base..])
        .map(|(&(dpdu, dpdv, k), n)| {
            let n = Vec3::from(*n);
            let (dpdu, dpdv) = (dpdu / k.max(1) as f32, dpdv / k.max(1) as f32);
            if k > 0 && dpdu.cross(dpdv).length_squared() > 0.0 {
                (dpdu.to_array(), dpdv.to_array())
            } else {
                let t = n.any_orthonormal_vector();
                (t.to_array(), n.cross(t).to_array())
            }
        })
        .unzip()
}
