//! What one object's draw needs on both backends: its matrices, the per-vertex geometry the
//! vertex stage starts from, and the uniform block's values.
//!
//! The vertex geometry follows the WGSL backend's entry point (`compiler/src/backend/wgsl/entry.rs`)
//! formula for formula, so that the CPU reference sees the inputs the GPU sees.

use glam::{Mat3, Mat4, Vec3};
use patina_compiler::backend::wgsl::interface::{GeometryMatrix, Interface, UniformSource};

use super::RenderError;
use super::program::{LightProgram, SurfaceProgram, apply};
use crate::mesh::Mesh;

/// The transformations of one object in one frame.
#[derive(Clone, Debug)]
pub struct Frame {
    /// Object to camera ("current") space.
    pub object_to_camera: Mat4,
    /// Normals from object to camera space.
    pub normal_to_camera: Mat4,
    /// Camera to wgpu clip space.
    pub camera_to_clip: Mat4,
    /// The surface's named spaces.
    pub spaces: Vec<(String, Mat4)>,
    /// The lights' named spaces.
    pub light_spaces: Vec<(String, Mat4)>,
    /// `Cs`, `Os`.
    pub color: [f32; 3],
    /// See `color`.
    pub opacity: [f32; 3],
    /// The camera's near and far clipping distances (what `depth` normalizes by).
    pub clip: [f32; 2],
}

/// The predefined variables of one vertex, in camera space (RenderMan style).
#[derive(Clone, Copy, Debug)]
pub struct VertexGeometry {
    /// The mesh's position and normal, in object space (Stanford's `Pobj`, `__position`, `__normal`).
    pub p_obj: Vec3,
    /// See `p_obj`.
    pub n_obj: Vec3,
    pub p: Vec3,
    pub n: Vec3,
    pub u: f32,
    pub v: f32,
    pub dpdu: Vec3,
    pub dpdv: Vec3,
}

impl Frame {
    /// The geometry of every vertex of `mesh`.
    pub fn geometry(&self, mesh: &Mesh) -> Vec<VertexGeometry> {
        (0..mesh.positions.len())
            .map(|i| VertexGeometry {
                p_obj: Vec3::from(mesh.positions[i]),
                n_obj: Vec3::from(mesh.normals[i]),
                p: apply(self.object_to_camera, Vec3::from(mesh.positions[i]), 1.0),
                n: apply(self.normal_to_camera, Vec3::from(mesh.normals[i]), 0.0),
                u: mesh.uvs[i][0],
                v: mesh.uvs[i][1],
                dpdu: apply(self.object_to_camera, Vec3::from(mesh.dpdu[i]), 0.0),
                dpdv: apply(self.object_to_camera, Vec3::from(mesh.dpdv[i]), 0.0),
            })
            .collect()
    }
}

impl VertexGeometry {
    /// The value of a predefined variable at this vertex, in the language's component order.
    pub fn global(&self, name: &str, stanford: bool) -> Option<Vec<f32>> {
        let v3 = |v: Vec3| vec![v.x, v.y, v.z];
        if stanford {
            let n = self.n / self.n.length();
            let t = self.dpdu / self.dpdu.length();
            return Some(match name {
                "P" => vec![self.p.x, self.p.y, self.p.z, 1.0],
                "N" => v3(n),
                "T" => v3(t),
                "B" => v3(n.cross(t)),
                "E" => v3(-self.p / self.p.length()),
                "Pobj" | "__position" => vec![self.p_obj.x, self.p_obj.y, self.p_obj.z, 1.0],
                "__normal" | "__objnormal" => v3(self.n_obj),
                _ => return None,
            });
        }
        Some(match name {
            "P" | "I" => v3(self.p),
            "N" | "Ng" => v3(self.n),
            "u" | "s" => vec![self.u],
            "v" | "t" => vec![self.v],
            "dPdu" => v3(self.dpdu),
            "dPdv" => v3(self.dpdv),
            "E" | "dPdtime" => vec![0.0; 3],
            _ => return None,
        })
    }
}

/// The value of a uniform field's source, in the language's component order (matrices as
/// `to_cols_array`).
pub fn uniform_value(
    source: &UniformSource,
    surface: &SurfaceProgram,
    lights: &[LightProgram],
    frame: &Frame,
) -> Result<Vec<f64>, RenderError> {
    let f64s = |v: &[f32]| v.iter().map(|x| f64::from(*x)).collect::<Vec<f64>>();
    let matrix = |m: Mat4| f64s(&m.to_cols_array());
    let find = |list: &[(String, Vec<f64>)], name: &str| {
        list.iter().find(|(n, _)| n == name).map(|(_, v)| v.clone())
    };
    let missing =
        |what: String| RenderError::Compile(format!("internal error: no value for the uniform {what}"));
    Ok(match source {
        UniformSource::Param { name } | UniformSource::Host { name } => {
            find(&surface.uniforms, name).ok_or_else(|| missing(format!("`{name}`")))?
        }
        UniformSource::Global { name } => {
            global_value(frame, name).ok_or_else(|| missing(format!("predefined variable `{name}`")))?
        }
        UniformSource::Space { name, inverse, light } => {
            let spaces = if light.is_some() { &frame.light_spaces } else { &frame.spaces };
            let m = spaces.iter().find(|(n, _)| n == name).map_or(Mat4::IDENTITY, |(_, m)| *m);
            matrix(if *inverse { m.inverse() } else { m })
        }
        UniformSource::LightParam { light, name } => {
            lights
                .get(*light)
                .and_then(|l| find(&l.values, name))
                .ok_or_else(|| missing(format!("light {light} `{name}`")))?
        }
        UniformSource::DisplacementParam { name } => surface
            .displacement
            .as_ref()
            .and_then(|d| find(&d.values, name))
            .ok_or_else(|| missing(format!("displacement `{name}`")))?,
        UniformSource::Geometry { matrix: which } => matrix(match which {
            GeometryMatrix::ObjectToCamera => frame.object_to_camera,
            GeometryMatrix::NormalToCamera => frame.normal_to_camera,
            GeometryMatrix::CameraToClip => frame.camera_to_clip,
        }),
    })
}

/// The value of the uniform predefined variable `name` for `frame`'s object, in the language's
/// component order; `None` for a predefined variable that is not uniform (`P`, `N`, ...).
pub fn global_value(frame: &Frame, name: &str) -> Option<Vec<f64>> {
    let f64s = |v: &[f32]| v.iter().map(|x| f64::from(*x)).collect::<Vec<f64>>();
    // Stanford multiplies column vectors (`M * v`) and the language lists a matrix row by row,
    // which for glam's column-major matrices is the transpose's column order.
    let rows = |m: Mat4| f64s(&m.transpose().to_cols_array());
    let rows3 = |m: Mat3| f64s(&m.transpose().to_cols_array());
    let modelview = frame.object_to_camera;
    Some(match name {
        "Cs" => f64s(&frame.color),
        "Os" => f64s(&frame.opacity),
        "Ca" | "__ambient" => vec![0.0; 4],
        "time" | "dtime" => vec![0.0],
        "E" => vec![0.0; 3],
        "clip" => f64s(&frame.clip),
        "__modelview" => rows(modelview),
        "__invmodelview" => rows(modelview.inverse()),
        "__modelview3" => rows3(Mat3::from_mat4(modelview)),
        "__invmodelview3" => rows3(Mat3::from_mat4(modelview).inverse().transpose()),
        "__projection" => rows(frame.camera_to_clip),
        _ => return None,
    })
}

/// The uniform block's bytes, laid out as the interface says.
pub fn uniform_bytes(
    interface: &Interface,
    surface: &SurfaceProgram,
    lights: &[LightProgram],
    frame: &Frame,
) -> Result<Vec<u8>, RenderError> {
    let mut bytes = vec![0u8; interface.uniform_size as usize];
    for field in &interface.uniforms {
        let values = uniform_value(&field.source, surface, lights, frame)?;
        let l = &field.layout;
        let per = l.components as usize;
        for e in 0..l.elements as usize {
            for c in 0..per {
                let Some(x) = values.get(e * per + c) else { continue };
                // A 3x3 matrix is three 16-byte columns, each holding one row of the language's.
                let within = if l.column_stride > 0 {
                    (c / 3) as u32 * l.column_stride + (c % 3) as u32 * 4
                } else {
                    c as u32 * 4
                };
                let at = (field.offset + e as u32 * l.element_stride + within) as usize;
                // Integers arrive as values or as their unsigned bit patterns (the interpreter's
                // outputs): both wrap to the same 32 bits.
                let word: [u8; 4] = match l.scalar {
                    "i32" | "u32" => (*x as i64 as u32).to_le_bytes(),
                    _ => (*x as f32).to_le_bytes(),
                };
                if let Some(slot) = bytes.get_mut(at..at + 4) {
                    slot.copy_from_slice(&word);
                }
            }
        }
    }
    Ok(bytes)
}
