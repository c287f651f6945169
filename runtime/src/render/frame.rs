//! What one object's draw needs on both backends: its matrices, the per-vertex geometry the
//! vertex stage starts from, and the uniform block's values.
//!
//! The vertex geometry follows the WGSL backend's entry point (`compiler/src/backend/wgsl/entry.rs`)
//! formula for formula, so that the CPU reference sees the inputs the GPU sees.

use glam::{Mat3, Mat4, Vec3};
use patina_compiler::backend::CLIP_INPUT;
use patina_compiler::backend::wgsl::interface::{GeometryMatrix, Interface, UniformSource};

use super::RenderError;
use super::program::{LightProgram, SurfaceProgram, apply};
use crate::camera::Camera;
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

impl Frame {
    /// The frame of an object placed by `object_to_world`, seen by `camera` in a `width × height`
    /// image, with `Cs` and `Os` as given.
    pub fn new(
        camera: &Camera,
        object_to_world: Mat4,
        width: u32,
        height: u32,
        color: [f32; 3],
        opacity: [f32; 3],
    ) -> Frame {
        let world_to_camera = camera.world_to_camera();
        let object_to_camera = world_to_camera * object_to_world;
        let spaces = super::program::spaces(world_to_camera, object_to_world, camera, width, height);
        let world_spaces = super::program::spaces(world_to_camera, Mat4::IDENTITY, camera, width, height);
        let (near, far) = camera.clip_range();
        Frame {
            object_to_camera,
            normal_to_camera: object_to_camera.inverse().transpose(),
            camera_to_clip: camera.camera_to_clip(width as f32 / height.max(1) as f32),
            spaces,
            light_spaces: super::program::light_spaces(&world_spaces),
            color,
            opacity,
            clip: [near, far],
        }
    }
}

/// The predefined variables of one vertex, in camera space (RenderMan style).
#[derive(Clone, Copy, Debug)]
pub struct VertexGeometry {
    /// The mesh's position and normal, in object space (Stanford's `Pobj`, `__position`, `__normal`).
    pub p_obj: Vec3,
    /// See `p_obj`.
    pub n_obj: Vec3,
    /// The position in camera space (RenderMan's `P` and `I`; Stanford's `P`, with w = 1).
    pub p: Vec3,
    /// The normal in camera space, by the inverse transpose and not normalized (RenderMan's `N`
    /// and `Ng`; Stanford's `N` is it normalized).
    pub n: Vec3,
    /// The surface parameter u (RenderMan's `u` and `s`).
    pub u: f32,
    /// The surface parameter v (RenderMan's `v` and `t`).
    pub v: f32,
    /// ∂P/∂u in camera space (RenderMan's `dPdu`; Stanford's `T` is it normalized).
    pub dpdu: Vec3,
    /// ∂P/∂v in camera space (RenderMan's `dPdv`).
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

/// What the host computed for one draw, which the uniform block's fields read: every parameter
/// value and host output of the surface, of each bound light and of the displacement shader.
#[derive(Clone, Copy, Debug)]
pub struct HostValues<'a> {
    /// The surface's, by name.
    pub surface: &'a [(String, Vec<f64>)],
    /// Each light's, by name.
    pub lights: &'a [&'a [(String, Vec<f64>)]],
    /// Each light's position in camera space: a Stanford-style light's; `None` for the others.
    pub light_positions: &'a [Option<Vec3>],
    /// The displacement shader's, by name (empty without one).
    pub displacement: &'a [(String, Vec<f64>)],
    /// The atmosphere shader's, by name (empty without one).
    pub atmosphere: &'a [(String, Vec<f64>)],
}

/// The value of a uniform field's source, in the language's component order (matrices as
/// `to_cols_array`).
pub fn uniform_value(
    source: &UniformSource,
    values: &HostValues,
    frame: &Frame,
) -> Result<Vec<f64>, RenderError> {
    let f64s = |v: &[f32]| v.iter().map(|x| f64::from(*x)).collect::<Vec<f64>>();
    let matrix = |m: Mat4| f64s(&m.to_cols_array());
    let find = |list: &[(String, Vec<f64>)], name: &str| {
        list.iter().find(|(n, _)| n == name).map(|(_, v)| v.clone())
    };
    let missing = |what: String| RenderError::Run(format!("internal error: no value for the uniform {what}"));
    Ok(match source {
        UniformSource::Param { name } | UniformSource::Host { name } => {
            find(values.surface, name).ok_or_else(|| missing(format!("`{name}`")))?
        }
        UniformSource::Global { name } => {
            global_value(frame, name).ok_or_else(|| missing(format!("predefined variable `{name}`")))?
        }
        UniformSource::Space { name, inverse, light } => {
            let spaces = if light.is_some() { &frame.light_spaces } else { &frame.spaces };
            let m = spaces.iter().find(|(n, _)| n == name).map_or(Mat4::IDENTITY, |(_, m)| *m);
            matrix(if *inverse { m.inverse() } else { m })
        }
        UniformSource::LightParam { light, name } => values
            .lights
            .get(*light)
            .and_then(|l| find(l, name))
            .ok_or_else(|| missing(format!("light {light} `{name}`")))?,
        UniformSource::LightPosition { light } => values
            .light_positions
            .get(*light)
            .copied()
            .flatten()
            .map(|p| f64s(&p.to_array()))
            .ok_or_else(|| missing(format!("light {light}'s position")))?,
        UniformSource::DisplacementParam { name } => {
            find(values.displacement, name).ok_or_else(|| missing(format!("displacement `{name}`")))?
        }
        UniformSource::AtmosphereParam { name } => {
            find(values.atmosphere, name).ok_or_else(|| missing(format!("atmosphere `{name}`")))?
        }
        UniformSource::Geometry { matrix: which } => matrix(match which {
            GeometryMatrix::ObjectToCamera => frame.object_to_camera,
            GeometryMatrix::NormalToCamera => frame.normal_to_camera,
            GeometryMatrix::CameraToClip => frame.camera_to_clip,
            other => return Err(missing(format!("geometry matrix {other:?}"))),
        }),
        UniformSource::Table { values } => values.clone(),
        other => return Err(missing(format!("{other:?}"))),
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
        CLIP_INPUT => f64s(&frame.clip),
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
    values: &HostValues,
    frame: &Frame,
) -> Result<Vec<u8>, RenderError> {
    let mut bytes = vec![0u8; interface.uniform_size as usize];
    for field in &interface.uniforms {
        field.write(&mut bytes, &uniform_value(&field.source, values, frame)?);
    }
    Ok(bytes)
}

/// The uniform block's bytes for a compiled surface and its lights, from the values their host
/// programs last computed.
pub fn program_uniform_bytes(
    surface: &SurfaceProgram,
    lights: &[LightProgram],
    frame: &Frame,
) -> Result<Vec<u8>, RenderError> {
    let light_values: Vec<&[(String, Vec<f64>)]> = lights.iter().map(|l| l.values.as_slice()).collect();
    let light_positions: Vec<Option<Vec3>> = lights.iter().map(|l| l.position).collect();
    let values = HostValues {
        surface: &surface.uniforms,
        lights: &light_values,
        light_positions: &light_positions,
        displacement: surface.displacement.as_ref().map_or(&[], |d| d.values.as_slice()),
        atmosphere: surface.atmosphere.as_ref().map_or(&[], |a| a.values.as_slice()),
    };
    uniform_bytes(&surface.gpu.interface, &values, frame)
}
