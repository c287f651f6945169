//! A scene's shaders compiled once for rendering: the surface of each object split into its
//! stages and built for both backends, the bound lights, and the values of every parameter (as
//! the host program computes them: the scene's value or the default).

use std::sync::Arc;

use patina_compiler::bind::{Consumed, Decision, Fixed};
use patina_compiler::diag::Diagnostic;
use patina_compiler::source::SourceMap;

use glam::{Mat4, Vec3, Vec4};
use patina_compiler::backend::binding::{Binding, BoundLight, LightBinding};
use patina_compiler::backend::cpu::{CpuProgram, Evaluator, SlotKind};
use patina_compiler::backend::object::{Beside, CompiledObject, HostPart, compile_object};
use patina_compiler::backend::wgsl::{GpuProgram, Lowering};
use patina_compiler::ir::builtin::BuiltinId;
use patina_compiler::ir::types::{Base, Type};
use patina_compiler::ir::{ExprKind, Literal, Shader};
use patina_compiler::opt::Prepared;
use patina_compiler::split::Stages;
use patina_compiler::syntax::ast::ShaderKind;

use super::frame::{Frame, global_value};
use super::{RenderError, ShaderDiagnostics};
use crate::scene::{ParamValue, ShaderRef};

/// A checked shader and the source it came from (kept for rendering diagnostics).
#[derive(Clone)]
pub struct LoadedShader {
    /// The shader, bound and prepared.
    pub shader: Prepared,
    /// Its string parameters' values from the scene.
    pub strings: Vec<(String, String)>,
    /// Its numeric parameters from the scene, in "current" (camera) space.
    pub params: Vec<(String, Vec<f64>)>,
    /// What binding folded, decided and removed (empty when compiled dynamic).
    pub decisions: Vec<Decision>,
    /// The sources it was read from, for naming the places in `decisions`.
    pub sources: Arc<SourceMap>,
}

impl LoadedShader {
    /// The shader as the WGSL backend binds it beside a surface (a light or a displacement).
    pub fn bound(&self) -> BoundLight<'_> {
        BoundLight { shader: &self.shader, strings: self.strings.clone(), categories: Vec::new() }
    }

    /// A backend's refusal of this shader, as the render error that keeps its code and place.
    pub fn error(&self, diagnostic: Diagnostic) -> RenderError {
        RenderError::Refused(ShaderDiagnostics {
            sources: Arc::clone(&self.sources),
            diagnostics: vec![diagnostic],
        })
    }
}

/// The values a scene gives a shader's parameters: strings (texture and space names) and numbers,
/// the latter in "current" (camera) space.
#[allow(clippy::type_complexity)]
pub fn scene_params(
    shader_ir: &Shader,
    shader: &ShaderRef,
    world_to_camera: Mat4,
) -> Result<(Vec<(String, String)>, Vec<(String, Vec<f64>)>), RenderError> {
    let mut strings = Vec::new();
    let mut params = Vec::new();
    for (name, value) in &shader.params {
        let Some(local) =
            shader_ir.params.iter().map(|p| shader_ir.local(*p)).find(|l| l.name == name.as_str())
        else {
            return Err(RenderError::Input(format!(
                "{}: shader `{}` has no parameter `{name}`",
                shader.path.display(),
                shader_ir.name
            )));
        };
        match value {
            ParamValue::String(s) => strings.push((name.clone(), s.clone())),
            ParamValue::Bool(b) => params.push((name.clone(), vec![f64::from(u8::from(*b))])),
            other => {
                let numbers = other.as_numbers().unwrap_or(&[]).to_vec();
                params.push((name.clone(), to_current(local.ty, numbers, world_to_camera)));
            }
        }
    }
    Ok((strings, params))
}

/// A compiled surface given new values of its animated parameters (`shader` is the scene's
/// entry, whose other values the program was compiled for; `displacement` its displacement's), a
/// new camera and a new frame: the parameters are taken into the new camera space and the host
/// part runs again; nothing is compiled.
pub fn rebind_surface(
    cached: &SurfaceProgram,
    shader: &ShaderRef,
    displacement: Option<&ShaderRef>,
    world_to_camera: Mat4,
    frame: &Frame,
) -> Result<SurfaceProgram, RenderError> {
    rebind_shaded(cached, shader, displacement, None, world_to_camera, frame)
}

/// As [`rebind_surface`], with the atmosphere's scene entry (`atmosphere`).
pub fn rebind_shaded(
    cached: &SurfaceProgram,
    shader: &ShaderRef,
    displacement: Option<&ShaderRef>,
    atmosphere: Option<&ShaderRef>,
    world_to_camera: Mat4,
    frame: &Frame,
) -> Result<SurfaceProgram, RenderError> {
    let mut surface = cached.clone();
    let (_, params) = scene_params(&surface.loaded.shader, shader, world_to_camera)?;
    surface.loaded.params = params;
    let host_outputs = surface.stages.host_outputs();
    surface.uniforms =
        evaluate_params(&surface.host, &surface.loaded.params, &frame.spaces, Some(frame), &host_outputs)?;
    if let (Some(d), Some(shader)) = (&mut surface.displacement, displacement) {
        d.loaded.params = scene_params(&d.loaded.shader, shader, world_to_camera)?.1;
        d.values = evaluate_params(&d.cpu, &d.loaded.params, &frame.spaces, Some(frame), &[])?;
    }
    if let (Some(a), Some(shader)) = (&mut surface.atmosphere, atmosphere) {
        a.loaded.params = scene_params(&a.loaded.shader, shader, world_to_camera)?.1;
        a.values = evaluate_params(&a.cpu, &a.loaded.params, &frame.spaces, Some(frame), &[])?;
    }
    Ok(surface)
}

/// A compiled light seen from a new camera (`shader` is the scene's entry it was compiled for):
/// its parameter values are computed again in the new camera space, nothing is compiled.
pub fn rebind_light(
    cached: &LightProgram,
    shader: &ShaderRef,
    world_to_camera: Mat4,
    spaces: &[(String, Mat4)],
) -> Result<LightProgram, RenderError> {
    let mut light = cached.clone();
    let (_, params) = scene_params(&light.loaded.shader, shader, world_to_camera)?;
    light.loaded.params = params;
    light.values = evaluate_params(&light.cpu, &light.loaded.params, spaces, None, &[])?;
    Ok(light)
}

/// Reads, checks and differentiates the shader a scene refers to; with `specialize`, first binds
/// it to the parameter values the scene sets and does not animate (`patina_compiler::bind`), and
/// to the defaults written with literals of those it does not set
/// ([`Shader::literal_default`](patina_compiler::ir::Shader::literal_default)), except values
/// that depend on the camera ([`camera_dependent`]): they stay in the uniform block, so that the
/// program serves every camera.
pub fn load(
    shader: &ShaderRef,
    kind: ShaderKind,
    world_to_camera: Mat4,
    specialize: bool,
) -> Result<LoadedShader, RenderError> {
    load_reading(shader, kind, world_to_camera, specialize, &[])
}

/// As [`load`], for a shader whose output parameters `read` are read by another shader bound
/// with it (an atmosphere's `surface("name", v)`): binding keeps the code that computes them.
/// A light keeps all of its output parameters, which surfaces read with `lightsource`.
pub fn load_reading(
    shader: &ShaderRef,
    kind: ShaderKind,
    world_to_camera: Mat4,
    specialize: bool,
    read: &[String],
) -> Result<LoadedShader, RenderError> {
    let path = shader.path.as_path();
    let shown = path.display().to_string();
    let checked = patina_compiler::check_file(path, &shader.include_dirs)
        .map_err(|e| RenderError::Input(format!("cannot read {shown}: {}", e.reason)))?;
    if checked.has_errors() {
        let diagnostics = checked.diagnostics.clone().into_vec();
        return Err(RenderError::Shader(ShaderDiagnostics {
            sources: Arc::new(checked.sources),
            diagnostics,
        }));
    }
    let Some(found) = checked.find_shader(Some(kind), shader.name.as_deref()) else {
        let what = match &shader.name {
            Some(n) => format!("no {} shader `{n}`", kind.keyword()),
            None => format!("no {} shader", kind.keyword()),
        };
        return Err(RenderError::Input(format!("{shown}: {what}")));
    };
    let shader_ir = found;
    for name in &shader.animate {
        if !shader_ir.params.iter().any(|p| shader_ir.local(*p).name == name.as_str()) {
            return Err(RenderError::Input(format!(
                "{shown}: shader `{}` has no parameter `{name}` to animate",
                shader_ir.name
            )));
        }
    }
    let (strings, params) = scene_params(shader_ir, shader, world_to_camera)?;
    let (shader_ir, decisions) = if specialize {
        let ty = |name: &str| {
            shader_ir.params.iter().map(|p| shader_ir.local(*p)).find(|l| l.name == name).map(|l| l.ty)
        };
        // A parameter the scene leaves at a default written with literals is as fixed as one it
        // sets: the host would put that same value in the uniform block on every draw.
        let defaults = shader_ir
            .params
            .iter()
            .filter(|&&p| !shader.params.contains_key(shader_ir.local(p).name.as_str()))
            .filter_map(|&p| Some((shader_ir.local(p).name.to_string(), shader_ir.literal_default(p)?)));
        let fixed: Vec<Fixed> = params
            .iter()
            .cloned()
            .chain(defaults)
            .filter(|(name, _)| !shader.animate.contains(name))
            .filter(|(name, _)| !ty(name).is_some_and(camera_dependent))
            .map(|(name, value)| Fixed { name, value })
            .collect();
        // The renderer reads back Ci, Oi or the result, never an output parameter; but a
        // surface may read a light's output parameters with `lightsource`, and an atmosphere a
        // surface's with `surface`.
        let read: Vec<&str> = read.iter().map(String::as_str).collect();
        let consumed = if kind == ShaderKind::Light { Consumed::All } else { Consumed::Only(&read) };
        let bound = patina_compiler::bind::specialize(shader_ir, &fixed, &strings, consumed);
        (bound.shader, bound.decisions)
    } else {
        (shader_ir.clone(), Vec::new())
    };
    Ok(LoadedShader {
        shader: Prepared::with_strings(shader_ir, &strings),
        strings,
        params,
        decisions,
        sources: Arc::new(checked.sources.clone()),
    })
}

/// The names a shader reads from the surface it is bound with: the literal first arguments of
/// its `surface("name", v)` calls.
pub fn surface_reads(shader: &Shader) -> Vec<String> {
    let mut names: Vec<String> = shader
        .exprs
        .iter()
        .filter_map(|e| match &e.kind {
            ExprKind::Builtin(b, args) if b.id == BuiltinId::Surface => {
                match &shader.expr(*args.first()?).kind {
                    ExprKind::Literal(Literal::String(s)) => Some(s.to_string()),
                    _ => None,
                }
            }
            _ => None,
        })
        .collect();
    names.sort();
    names.dedup();
    names
}

/// Whether a parameter's scene value is transformed into camera space ([`to_current`]), so that
/// its value in the shader depends on the camera: a point, vector or normal (not an array of
/// them; a matrix is taken as it is).
pub fn camera_dependent(ty: Type) -> bool {
    !ty.is_array() && matches!(ty.base, Base::Point | Base::Vector | Base::Normal)
}

/// Scene values of geometric types are in world space; shaders see them in camera space.
pub fn to_current(ty: Type, v: Vec<f64>, world_to_camera: Mat4) -> Vec<f64> {
    if !camera_dependent(ty) || v.len() != 3 {
        return v;
    }
    let x = Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32);
    let r = match ty.base {
        Base::Point => world_to_camera.transform_point3(x),
        Base::Vector => world_to_camera.transform_vector3(x),
        Base::Normal => world_to_camera.inverse().transpose().transform_vector3(x),
        _ => return v,
    };
    vec![f64::from(r.x), f64::from(r.y), f64::from(r.z)]
}

/// A light bound to the scene, ready for both backends.
#[derive(Clone)]
pub struct LightProgram {
    /// The light shader.
    pub loaded: LoadedShader,
    /// The interpreter's program for it.
    pub cpu: CpuProgram,
    /// Its parameter values after defaults, by name.
    pub values: Vec<(String, Vec<f64>)>,
    /// Where a Stanford-style light is, in camera space (the scene's `position`, which
    /// [`super::prepare`] sets); `None` for a RenderMan-style light, which its parameters place.
    pub position: Option<Vec3>,
}

/// A displacement shader bound to an object, ready for the CPU (the GPU module includes it).
#[derive(Clone)]
pub struct DisplacementProgram {
    /// The displacement shader.
    pub loaded: LoadedShader,
    /// The interpreter's program for it.
    pub cpu: CpuProgram,
    /// Its parameter values after defaults, by name.
    pub values: Vec<(String, Vec<f64>)>,
}

/// An object's surface, ready for both backends.
#[derive(Clone)]
pub struct SurfaceProgram {
    /// The surface shader (differentiated, whole).
    pub loaded: LoadedShader,
    /// Its stages.
    pub stages: Stages,
    /// The GPU module and its interface.
    pub gpu: GpuProgram,
    /// The interpreter's program for the host part (run once per draw for the uniforms).
    pub host: CpuProgram,
    /// The interpreter's programs for the vertex and fragment stages.
    pub vertex: CpuProgram,
    /// See `vertex`.
    pub fragment: CpuProgram,
    /// The host program's results: every parameter's value and every host transfer, by name.
    pub uniforms: Vec<(String, Vec<f64>)>,
    /// The displacement shader run before the surface at each fragment, if any.
    pub displacement: Option<DisplacementProgram>,
    /// The atmosphere (volume) shader run after the surface at each fragment, on its `Ci` and
    /// `Oi`, if any (the same kind of program as a displacement: a shader bound beside the surface).
    pub atmosphere: Option<DisplacementProgram>,
}

/// Compiles a light and computes its parameter values.
pub fn light_program(loaded: LoadedShader, spaces: &[(String, Mat4)]) -> Result<LightProgram, RenderError> {
    let binding = Binding { lights: Vec::new(), strings: loaded.strings.clone() };
    let cpu = CpuProgram::compile(&loaded.shader, &binding).map_err(|d| loaded.error(d))?;
    let values = evaluate_params(&cpu, &loaded.params, spaces, None, &[])?;
    Ok(LightProgram { loaded, cpu, values, position: None })
}

/// The interpreter's bindings for the lights.
pub fn light_bindings(lights: &[LightProgram]) -> Vec<LightBinding> {
    lights.iter().map(|l| LightBinding::of(&l.loaded.shader, &l.loaded.strings)).collect()
}

/// Splits and compiles a surface for both backends and runs its host program.
pub fn surface_program(
    loaded: LoadedShader,
    displacement: Option<LoadedShader>,
    lights: &[LightProgram],
    frame: &Frame,
) -> Result<SurfaceProgram, RenderError> {
    shaded_program(loaded, displacement, None, lights, frame, Lowering::Exact)
}

/// As [`surface_program`], with an atmosphere (volume) shader run after the surface, and the GPU
/// module written in `lowering`.
pub fn shaded_program(
    loaded: LoadedShader,
    displacement: Option<LoadedShader>,
    atmosphere: Option<LoadedShader>,
    lights: &[LightProgram],
    frame: &Frame,
    lowering: Lowering,
) -> Result<SurfaceProgram, RenderError> {
    let spaces = &frame.spaces;
    let beside = |d: Option<LoadedShader>| -> Result<Option<DisplacementProgram>, RenderError> {
        let Some(d) = d else { return Ok(None) };
        let binding = Binding { lights: Vec::new(), strings: d.strings.clone() };
        let cpu = CpuProgram::compile(&d.shader, &binding).map_err(|e| d.error(e))?;
        let values = evaluate_params(&cpu, &d.params, spaces, Some(frame), &[])?;
        Ok(Some(DisplacementProgram { loaded: d, cpu, values }))
    };
    let displacement = beside(displacement)?;
    let atmosphere = beside(atmosphere)?;
    let compiled = {
        let lights: Vec<BoundLight> = lights.iter().map(|l| l.loaded.bound()).collect();
        let beside = Beside {
            lights: &lights,
            displacement: displacement.as_ref().map(|d| d.loaded.bound()),
            atmosphere: atmosphere.as_ref().map(|a| a.loaded.bound()),
        };
        compile_object(&loaded.shader, &loaded.strings, &beside, lowering, HostPart::Interpreted)
    };
    let CompiledObject { stages, gpu, host, vertex, fragment } = compiled.map_err(|d| loaded.error(d))?;
    let uniforms = evaluate_params(&host, &loaded.params, spaces, Some(frame), &stages.host_outputs())?;
    Ok(SurfaceProgram { loaded, stages, gpu, host, vertex, fragment, uniforms, displacement, atmosphere })
}

/// Runs a program once with the scene's parameter values (and, for an object's programs, its
/// frame's uniform predefined variables) and reads back every parameter (the scene's value or its
/// default) and the named extra outputs.
pub fn evaluate_params(
    program: &CpuProgram,
    params: &[(String, Vec<f64>)],
    spaces: &[(String, Mat4)],
    frame: Option<&Frame>,
    extra: &[String],
) -> Result<Vec<(String, Vec<f64>)>, RenderError> {
    // In f64, which holds every 32-bit integer exactly (the values are rounded to f32 where
    // they are used as floats).
    let mut eval = Evaluator::<f64>::new(program);
    set_spaces(&mut eval, program, spaces);
    if let Some(frame) = frame {
        set_globals(&mut eval, program, frame);
    }
    for (name, value) in params {
        eval.set(name, value).map_err(|e| RenderError::Input(format!("parameter `{name}`: {e}")))?;
    }
    let mut names: Vec<String> = program
        .slots()
        .filter(|(_, s)| matches!(s.kind, SlotKind::Param { .. }))
        .map(|(_, s)| s.name)
        .collect();
    names.extend(extra.iter().cloned());
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let values = eval.eval_points(1, &[], &refs).map_err(|e| RenderError::Run(e.to_string()))?;
    Ok(names.into_iter().zip(values).collect())
}

/// Fills every uniform predefined variable a program reads (`Cs`, `time`, Stanford's matrices, ...)
/// with its value for `frame`, as the GPU's uniform block holds it.
pub fn set_globals<F: patina_compiler::backend::cpu::scalar::Real>(
    eval: &mut Evaluator<'_, F>,
    program: &CpuProgram,
    frame: &Frame,
) {
    let globals: Vec<String> =
        program.slots().filter(|(_, s)| s.kind == SlotKind::Global).map(|(_, s)| s.name).collect();
    for name in globals {
        if let Some(value) = global_value(frame, &name) {
            // `set` fails only on names the program lacks; a per-point input of that name
            // (RenderMan's `Cs`) is given per point by the caller instead.
            let _ = eval.set(&name, &value);
        }
    }
}

/// Fills every `space:NAME` slot a program has from the scene's spaces.
pub fn set_spaces<F: patina_compiler::backend::cpu::scalar::Real>(
    eval: &mut Evaluator<'_, F>,
    program: &CpuProgram,
    spaces: &[(String, Mat4)],
) {
    let wanted: Vec<String> = program
        .slots()
        .filter(|(_, s)| s.kind == SlotKind::Space)
        .map(|(_, s)| s.name.trim_start_matches("space:").to_string())
        .collect();
    for name in wanted {
        let m = spaces.iter().find(|(n, _)| *n == name).map_or(Mat4::IDENTITY, |(_, m)| *m);
        let values: Vec<f64> = m.to_cols_array().iter().map(|x| f64::from(*x)).collect();
        // A space the scene cannot name keeps the identity; `set` only fails on unknown names.
        let _ = eval.set(&format!("space:{name}"), &values);
    }
}

/// The named spaces of an object, as matrices from "current" (camera) space to each.
pub fn spaces(
    world_to_camera: Mat4,
    object_to_world: Mat4,
    camera: &crate::camera::Camera,
    width: u32,
    height: u32,
) -> Vec<(String, Mat4)> {
    let camera_to_world = world_to_camera.inverse();
    let camera_to_object = object_to_world.inverse() * camera_to_world;
    let aspect = width as f32 / height.max(1) as f32;
    vec![
        ("world".into(), camera_to_world),
        ("object".into(), camera_to_object),
        ("shader".into(), camera_to_object),
        ("camera".into(), Mat4::IDENTITY),
        ("current".into(), Mat4::IDENTITY),
        ("screen".into(), camera.camera_to_screen()),
        ("NDC".into(), camera.camera_to_ndc(aspect)),
        ("raster".into(), camera.camera_to_raster(width, height)),
    ]
}

/// The spaces of a light: its "shader" space is world space (lights have no transformation).
pub fn light_spaces(surface_spaces: &[(String, Mat4)]) -> Vec<(String, Mat4)> {
    let world = surface_spaces.iter().find(|(n, _)| n == "world").map_or(Mat4::IDENTITY, |(_, m)| *m);
    surface_spaces
        .iter()
        .map(|(n, m)| if n == "shader" || n == "object" { (n.clone(), world) } else { (n.clone(), *m) })
        .collect()
}

/// `m * (v, w)`, the first three components.
pub fn apply(m: Mat4, v: Vec3, w: f32) -> Vec3 {
    (m * Vec4::new(v.x, v.y, v.z, w)).truncate()
}
