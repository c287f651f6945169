//! [`Uniforms`]: the bytes of a compiled program's uniform block, from named parameter values and
//! a [`View`], with the host part run on the CPU where the program has one.

use std::fmt;

use glam::{Mat4, Vec3};
use patina_compiler::backend::wgsl::interface::UniformSource;
use patina_runtime::camera::Camera;
use patina_runtime::render::frame::{Frame, HostValues, uniform_bytes};
use patina_runtime::render::program::{evaluate_params, to_current};

use super::{Compiled, Value, components};

/// Where an object is seen from: the camera, the object's placement in the world, the image
/// size (for the `raster` and `NDC` spaces and the aspect ratio), and its `Cs` and `Os`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// The camera, in world space (RenderMan's camera space: +z forward, left-handed).
    pub camera: Camera,
    /// The object's transformation from object to world space.
    pub object_to_world: Mat4,
    /// The image's width in pixels.
    pub width: u32,
    /// The image's height in pixels.
    pub height: u32,
    /// The surface colour `Cs`.
    pub color: [f32; 3],
    /// The surface opacity `Os`.
    pub opacity: [f32; 3],
}

impl Default for View {
    /// A 40° camera at (0, 0, -5) looking at the origin, the object untransformed, a 256 × 256
    /// image, `Cs` and `Os` white (the scene format's defaults).
    fn default() -> View {
        View {
            camera: Camera {
                from: Vec3::new(0.0, 0.0, -5.0),
                to: Vec3::ZERO,
                up: Vec3::Y,
                fov_y_degrees: 40.0,
                near: 0.1,
                far: 100.0,
            },
            object_to_world: Mat4::IDENTITY,
            width: 256,
            height: 256,
            color: [1.0; 3],
            opacity: [1.0; 3],
        }
    }
}

impl View {
    /// The frame the runtime draws this view with.
    pub(crate) fn frame(&self) -> Frame {
        Frame::new(&self.camera, self.object_to_world, self.width, self.height, self.color, self.opacity)
    }
}

/// The uniform block of a [`Compiled`] program: parameter values by name and a [`View`], packed
/// into the exact bytes the WGSL's uniform struct reads.
///
/// Points, vectors and normals are given in world space (as in scene files) and moved to camera
/// space with the view; colours and floats as they are. Unset parameters keep their defaults.
#[derive(Clone, Debug)]
pub struct Uniforms<'c> {
    compiled: &'c Compiled,
    surface: Vec<(String, Vec<f64>)>,
    lights: Vec<Vec<(String, Vec<f64>)>>,
    /// Each light's position in world space, where one is set (Stanford-style lights need one).
    light_positions: Vec<Option<Vec3>>,
    displacement: Vec<(String, Vec<f64>)>,
    view: View,
}

/// Why a value could not be set or the block could not be filled.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum UniformError {
    /// The shader has no parameter of this name.
    Unknown {
        /// The shader.
        shader: String,
        /// The name asked for.
        name: String,
    },
    /// The value has the wrong number of components, or is a string.
    WrongType {
        /// The parameter.
        name: String,
        /// Its type.
        ty: String,
        /// What was given.
        given: String,
    },
    /// The parameter was compiled in (`Compiler::fix`, or a string parameter); it has no uniform.
    CompiledIn {
        /// The parameter.
        name: String,
    },
    /// There is no light of this number.
    NoLight {
        /// The number asked for.
        light: usize,
        /// How many are bound.
        count: usize,
    },
    /// A Stanford-style light's position was not set (`Uniforms::set_light_position`).
    NoPosition {
        /// The light.
        light: usize,
    },
    /// The host part failed (a loop past its budget, ...).
    Host(String),
}

impl fmt::Display for UniformError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            UniformError::Unknown { shader, name } => {
                write!(f, "shader `{shader}` has no parameter `{name}`")
            }
            UniformError::WrongType { name, ty, given } => {
                write!(f, "parameter `{name}` is a {ty}; {given} given")
            }
            UniformError::CompiledIn { name } => {
                write!(f, "parameter `{name}` is compiled in; compile without fixing it to set it per draw")
            }
            UniformError::NoLight { light, count } => {
                write!(f, "there is no light {light}: {count} are bound")
            }
            UniformError::NoPosition { light } => write!(
                f,
                "light {light} is a Stanford-style light: set its position with `set_light_position`"
            ),
            UniformError::Host(why) => write!(f, "the host part failed: {why}"),
        }
    }
}

impl std::error::Error for UniformError {}

impl<'c> Uniforms<'c> {
    pub(crate) fn new(compiled: &'c Compiled) -> Uniforms<'c> {
        let program = &compiled.program;
        Uniforms {
            compiled,
            surface: program.loaded.params.clone(),
            lights: compiled.lights.iter().map(|l| l.loaded.params.clone()).collect(),
            light_positions: vec![None; compiled.lights.len()],
            displacement: program.displacement.as_ref().map(|d| d.loaded.params.clone()).unwrap_or_default(),
            view: View::default(),
        }
    }

    /// Sets the surface parameter `name`.
    pub fn set(&mut self, name: &str, value: impl Into<Value>) -> Result<&mut Self, UniformError> {
        let shader = &self.compiled.program.loaded;
        let value = checked(&shader.shader, &shader.params, name, value.into(), &shader.strings)?;
        put(&mut self.surface, name, value);
        Ok(self)
    }

    /// Sets parameter `name` of bound light `light` (numbered as they were added).
    pub fn set_light(
        &mut self,
        light: usize,
        name: &str,
        value: impl Into<Value>,
    ) -> Result<&mut Self, UniformError> {
        let count = self.compiled.lights.len();
        let loaded = &self.compiled.lights.get(light).ok_or(UniformError::NoLight { light, count })?.loaded;
        let value = checked(&loaded.shader, &loaded.params, name, value.into(), &loaded.strings)?;
        put(&mut self.lights[light], name, value);
        Ok(self)
    }

    /// Sets the world-space position of bound light `light`, a Stanford-style light (whose shader
    /// computes only its colour; its `L` and `Sdist` are measured from this point).
    pub fn set_light_position(
        &mut self,
        light: usize,
        position: [f32; 3],
    ) -> Result<&mut Self, UniformError> {
        let count = self.compiled.lights.len();
        let slot = self.light_positions.get_mut(light).ok_or(UniformError::NoLight { light, count })?;
        *slot = Some(Vec3::from(position));
        Ok(self)
    }

    /// Sets parameter `name` of the bound displacement shader.
    pub fn set_displacement(
        &mut self,
        name: &str,
        value: impl Into<Value>,
    ) -> Result<&mut Self, UniformError> {
        let Some(d) = &self.compiled.program.displacement else {
            return Err(UniformError::Unknown {
                shader: "(no displacement shader)".into(),
                name: name.into(),
            });
        };
        let value = checked(&d.loaded.shader, &d.loaded.params, name, value.into(), &d.loaded.strings)?;
        put(&mut self.displacement, name, value);
        Ok(self)
    }

    /// Sets the view: camera, object transformation, image size, `Cs` and `Os`.
    pub fn set_view(&mut self, view: View) -> &mut Self {
        self.view = view;
        self
    }

    /// The view the block is filled for.
    pub fn view(&self) -> &View {
        &self.view
    }

    /// The block's bytes (`interface.uniform_size` of them): the host part runs (in f64, as the
    /// renderer runs it) for the values set and the view.
    pub fn bytes(&self) -> Result<Vec<u8>, UniformError> {
        let frame = self.view.frame();
        let world_to_camera = self.view.camera.world_to_camera();
        let program = &self.compiled.program;
        let host = |e: patina_runtime::render::RenderError| UniformError::Host(e.to_string());
        let current = |shader: &patina_compiler::ir::Shader, values: &[(String, Vec<f64>)]| {
            values
                .iter()
                .map(|(name, v)| {
                    let ty = shader.params.iter().map(|p| shader.local(*p)).find(|l| l.name == name.as_str());
                    let v = ty.map_or(v.clone(), |l| to_current(l.ty, v.clone(), world_to_camera));
                    (name.clone(), v)
                })
                .collect::<Vec<_>>()
        };
        let surface = evaluate_params(
            &program.host,
            &current(&program.loaded.shader, &self.surface),
            &frame.spaces,
            Some(&frame),
            &program.stages.host_outputs(),
        )
        .map_err(host)?;
        let mut lights = Vec::new();
        for (light, values) in self.compiled.lights.iter().zip(&self.lights) {
            let values = current(&light.loaded.shader, values);
            lights.push(evaluate_params(&light.cpu, &values, &frame.light_spaces, None, &[]).map_err(host)?);
        }
        let displacement = match &program.displacement {
            Some(d) => {
                let values = current(&d.loaded.shader, &self.displacement);
                evaluate_params(&d.cpu, &values, &frame.spaces, Some(&frame), &[]).map_err(host)?
            }
            None => Vec::new(),
        };
        // The atmosphere's parameters take the values it was compiled with, or their defaults.
        let atmosphere = match &program.atmosphere {
            Some(a) => {
                evaluate_params(&a.cpu, &a.loaded.params, &frame.spaces, Some(&frame), &[]).map_err(host)?
            }
            None => Vec::new(),
        };
        let light_refs: Vec<&[(String, Vec<f64>)]> = lights.iter().map(Vec::as_slice).collect();
        for field in &self.compiled.interface.uniforms {
            if let UniformSource::LightPosition { light } = field.source
                && self.light_positions.get(light).copied().flatten().is_none()
            {
                return Err(UniformError::NoPosition { light });
            }
        }
        let light_positions: Vec<Option<Vec3>> =
            self.light_positions.iter().map(|p| p.map(|p| world_to_camera.transform_point3(p))).collect();
        let values = HostValues {
            surface: &surface,
            lights: &light_refs,
            light_positions: &light_positions,
            displacement: &displacement,
            atmosphere: &atmosphere,
        };
        uniform_bytes(&self.compiled.interface, &values, &frame).map_err(host)
    }

    /// The value the block holds for the uniform fed by `source`, read back from `bytes`.
    pub fn read(&self, bytes: &[u8], source: &UniformSource) -> Option<Vec<f64>> {
        self.compiled.interface.uniform(source).map(|f| f.read(bytes))
    }
}

/// `value` checked against parameter `name` of `shader`: it exists, is not compiled in, and has
/// the parameter's number of components.
fn checked(
    shader: &patina_compiler::ir::Shader,
    fixed: &[(String, Vec<f64>)],
    name: &str,
    value: Value,
    strings: &[(String, String)],
) -> Result<Vec<f64>, UniformError> {
    let Some(local) = shader.params.iter().map(|p| shader.local(*p)).find(|l| l.name == name) else {
        return Err(UniformError::Unknown { shader: shader.name.to_string(), name: name.into() });
    };
    let compiled_in = |n: &str| fixed.iter().any(|(f, _)| f == n) || strings.iter().any(|(s, _)| s == n);
    if compiled_in(name) || local.ty.base == patina_compiler::ir::types::Base::String {
        return Err(UniformError::CompiledIn { name: name.into() });
    }
    let wrong =
        |given: String| UniformError::WrongType { name: name.into(), ty: local.ty.to_string(), given };
    match value {
        Value::String(s) => Err(wrong(format!("the string {s:?}"))),
        Value::Numbers(v) if v.len() != components(local.ty) => Err(wrong(format!("{} number(s)", v.len()))),
        Value::Numbers(v) => Ok(v),
    }
}

fn put(list: &mut Vec<(String, Vec<f64>)>, name: &str, value: Vec<f64>) {
    match list.iter_mut().find(|(n, _)| n == name) {
        Some(slot) => slot.1 = value,
        None => list.push((name.to_string(), value)),
    }
}
