//! Rendering a scene: its shaders compiled for both backends ([`prepare`]), then drawn on the GPU
//! or by the CPU reference ([`render`]). Both draw the same triangles with the same inputs, so
//! their images can be compared pixel by pixel.

mod cache;
mod cpu;
pub mod frame;
mod gpu;
pub mod imager;
pub mod program;
mod progress;
pub mod shadow;
pub(crate) mod textures;

use std::sync::Arc;

use glam::Mat4;
pub use patina_compiler::backend::wgsl::Lowering;
use patina_compiler::diag::Diagnostic;
use patina_compiler::source::SourceMap;
use patina_compiler::syntax::ast::ShaderKind;

use crate::gpu::Gpu;
use crate::image::Image;
use crate::mesh::Mesh;
use crate::scene::Scene;
pub use cache::Cache;
pub use frame::Frame;
pub use program::LoadedShader;
pub use program::{LightProgram, SurfaceProgram};
pub use progress::{Progress, Silent, Unit};

/// Why a scene could not be rendered, as one line (or a shader's diagnostics).
#[derive(Clone, Debug, PartialEq)]
pub enum RenderError {
    /// A missing file, an unknown shader or parameter.
    Input(String),
    /// A shader's errors when checked, with their codes and places; shown whole, as a terminal
    /// shows diagnostics.
    Shader(ShaderDiagnostics),
    /// Why a backend could not compile a shader that checked (a limit, a feature the GPU lacks,
    /// an internal error), with its code and place; shown as one line, `CODE: message`.
    Refused(ShaderDiagnostics),
    /// The program could not run (the interpreter's errors, a value the host could not compute,
    /// an input the stages disagree on).
    Run(String),
    /// The GPU failed.
    Gpu(String),
}

impl std::fmt::Display for RenderError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RenderError::Input(m) | RenderError::Run(m) => f.write_str(m.trim_end()),
            RenderError::Shader(d) => write!(f, "{d}"),
            RenderError::Refused(d) => {
                let lines: Vec<String> =
                    d.diagnostics.iter().map(|d| format!("{}: {}", d.code, d.message)).collect();
                f.write_str(&lines.join("; "))
            }
            RenderError::Gpu(m) => write!(f, "GPU: {}", m.trim_end()),
        }
    }
}

impl std::error::Error for RenderError {}

/// A shader's diagnostics with the sources they point into: kept whole (codes, spans, labels,
/// help) for tools, and shown by `Display` as a terminal shows them (codespan's text).
#[derive(Clone, Debug)]
pub struct ShaderDiagnostics {
    /// The sources the spans point into.
    pub sources: Arc<SourceMap>,
    /// The diagnostics, in the order they were found.
    pub diagnostics: Vec<Diagnostic>,
}

impl PartialEq for ShaderDiagnostics {
    fn eq(&self, other: &ShaderDiagnostics) -> bool {
        self.diagnostics == other.diagnostics
    }
}

impl std::fmt::Display for ShaderDiagnostics {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(patina_compiler::diag::render_text(&self.sources, &self.diagnostics).trim_end())
    }
}

/// Which renderer draws.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Backend {
    /// wgpu.
    Gpu,
    /// The CPU reference.
    Cpu,
}

/// One object, compiled.
pub struct Object {
    /// Its surface program.
    pub surface: SurfaceProgram,
    /// Its mesh, in object space.
    pub mesh: Mesh,
    /// Its transformations.
    pub frame: Frame,
    /// The textures its program reads, by name.
    pub textures: Vec<(String, patina_compiler::backend::cpu::Texture)>,
}

impl Object {
    /// A surface parameter's value (the scene's, or the default the host computed).
    pub fn param(&self, name: &str) -> Option<Vec<f64>> {
        self.surface.uniforms.iter().find(|(n, _)| n == name).map(|(_, v)| v.clone())
    }

    /// A vertex-rate parameter's value at vertex `i`, `components` wide: the scene's value, or for
    /// a parameter named `uv` or `st` that the scene leaves unset, the mesh's surface parameters
    /// as (u, v, 0, 1); otherwise its default.
    pub fn vertex_param(&self, name: &str, i: usize, components: usize) -> Vec<f64> {
        let set_by_scene = self.surface.loaded.params.iter().any(|(n, _)| n == name);
        let value = match (name, set_by_scene, self.mesh.uvs.get(i)) {
            ("uv" | "st", false, Some(uv)) => vec![f64::from(uv[0]), f64::from(uv[1]), 0.0, 1.0],
            _ => self.param(name).unwrap_or_default(),
        };
        (0..components).map(|c| value.get(c).copied().unwrap_or(0.0)).collect()
    }
}

/// A scene compiled for rendering at one image size.
pub struct Prepared {
    /// The bound lights.
    pub lights: Vec<LightProgram>,
    /// The objects.
    pub objects: Vec<Object>,
    /// The clear colour (premultiplied).
    pub background: [f32; 4],
    /// Render size before downsampling.
    pub width: u32,
    /// See `width`.
    pub height: u32,
    /// Samples per pixel along each axis.
    pub supersample: u32,
    /// The imager run over the finished image, if the scene has one (then `background` is
    /// transparent black, so that alpha is the coverage, and the imager keeps the scene's).
    pub imager: Option<imager::ImagerProgram>,
}

/// How a scene's shaders are compiled.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Options {
    /// Bind each shader to the parameter values the scene sets and does not animate, leaving out
    /// what they make dead (the default); `false` keeps every parameter in the uniform block.
    pub specialize: bool,
    /// How the GPU module writes the built-ins: [`Lowering::Exact`] (the default here, since the
    /// renderer is what the CPU reference is compared against) reproduces the interpreter's bits,
    /// [`Lowering::Fast`] uses WGSL's own built-ins.
    pub lowering: Lowering,
}

impl Default for Options {
    fn default() -> Self {
        Options { specialize: true, lowering: Lowering::Exact }
    }
}

/// Compiles every shader of `scene`, bound to the values it fixes, and computes its parameters.
pub fn prepare(scene: &Scene) -> Result<Prepared, RenderError> {
    prepare_with(scene, Options::default())
}

/// As [`prepare`], compiled as `options` say.
pub fn prepare_with(scene: &Scene, options: Options) -> Result<Prepared, RenderError> {
    prepare_cached(scene, options, &mut Cache::new())
}

/// As [`prepare_with`], taking compiled programs from `cache` where their binding is the same and
/// keeping the ones it compiles there: preparing the scene again with new values of animated
/// parameters, from another camera (or with the same shader on several objects) compiles nothing.
pub fn prepare_cached(scene: &Scene, options: Options, cache: &mut Cache) -> Result<Prepared, RenderError> {
    let specialize = options.specialize;
    let camera = scene.camera();
    let n = scene.output.supersample.max(1);
    let (width, height) = (scene.output.width * n, scene.output.height * n);
    let world_to_camera = camera.world_to_camera();
    let camera_to_clip = camera.camera_to_clip(scene.aspect());
    let world_spaces = program::spaces(world_to_camera, Mat4::IDENTITY, &camera, width, height);
    let light_spaces = program::light_spaces(&world_spaces);
    let mut lights = Vec::new();
    let mut light_keys = Vec::new();
    for (i, light) in scene.lights.iter().enumerate() {
        let key = cache::light_key(&light.shader, specialize);
        let mut program = match cache.light(&key) {
            Some(cached) => program::rebind_light(cached, &light.shader, world_to_camera, &light_spaces)?,
            None => {
                let loaded = program::load(&light.shader, ShaderKind::Light, world_to_camera, specialize)?;
                let p = program::light_program(loaded, &light_spaces)?;
                cache.keep_light(key.clone(), &p);
                p
            }
        };
        program.position = light_position(scene, i, &program.loaded.shader, world_to_camera)?;
        lights.push(program);
        light_keys.push(key);
    }
    let mut objects = Vec::new();
    // Shadow maps by name, drawn when an object first reads them (render/shadow.rs).
    let mut shadow_maps: std::collections::HashMap<String, patina_compiler::backend::cpu::Texture> =
        std::collections::HashMap::new();
    // Texture files are named relative to the scene's folder.
    let base = scene.file.parent().unwrap_or(std::path::Path::new("."));
    for (i, o) in scene.objects.iter().enumerate() {
        let object_to_world = scene.object_transform(i);
        let spaces = program::spaces(world_to_camera, object_to_world, &camera, width, height);
        let object_to_camera = world_to_camera * object_to_world;
        let frame = Frame {
            object_to_camera,
            normal_to_camera: object_to_camera.inverse().transpose(),
            camera_to_clip,
            spaces,
            light_spaces: light_spaces.clone(),
            color: o.color,
            opacity: o.opacity,
            clip: {
                let (near, far) = camera.clip_range();
                [near, far]
            },
        };
        let key = cache::surface_key(&o.surface, o.displacement.as_ref(), &light_keys, options);
        let key = cache::with_atmosphere(key, o.atmosphere.as_ref());
        let surface = match cache.surface(&key) {
            Some(cached) => program::rebind_shaded(
                cached,
                &o.surface,
                o.displacement.as_ref(),
                o.atmosphere.as_ref(),
                world_to_camera,
                &frame,
            )?,
            None => {
                let atmosphere = match &o.atmosphere {
                    Some(a) => Some(program::load(a, ShaderKind::Volume, world_to_camera, specialize)?),
                    None => None,
                };
                // What the atmosphere reads of the surface is kept by the surface's binding.
                let read = atmosphere.as_ref().map(|a| program::surface_reads(&a.shader)).unwrap_or_default();
                let loaded = program::load_reading(
                    &o.surface,
                    ShaderKind::Surface,
                    world_to_camera,
                    specialize,
                    &read,
                )?;
                let displacement = match &o.displacement {
                    Some(d) => Some(program::load(d, ShaderKind::Displacement, world_to_camera, specialize)?),
                    None => None,
                };
                let surface = program::shaded_program(
                    loaded,
                    displacement,
                    atmosphere,
                    &lights,
                    &frame,
                    options.lowering,
                )?;
                cache.keep_surface(key, &surface);
                surface
            }
        };
        let mesh = o
            .build_mesh()
            .map_err(|e| RenderError::Input(format!("{}: object {i}: {e}", scene.file.display())))?;
        let textures = surface
            .gpu
            .interface
            .textures
            .iter()
            .map(|t| {
                let texture = match scene.shadow_maps.iter().find(|m| m.name == t.name) {
                    Some(map) => match shadow_maps.get(&t.name) {
                        Some(made) => made.clone(),
                        None => {
                            let made = shadow::make(scene, map, world_to_camera)?;
                            shadow_maps.insert(t.name.clone(), made.clone());
                            made
                        }
                    },
                    None => textures::load(&t.name, base)?,
                };
                Ok((t.name.clone(), texture))
            })
            .collect::<Result<_, RenderError>>()?;
        objects.push(Object { surface, mesh, frame, textures });
    }
    let [r, g, b, a] = scene.output.background;
    let mut background = [r * a, g * a, b * a, a];
    let imager = match &scene.imager {
        Some(shader) => {
            let loaded = program::load(shader, ShaderKind::Imager, world_to_camera, specialize)?;
            let (w, h) = (scene.output.width, scene.output.height);
            let spaces = program::spaces(world_to_camera, Mat4::IDENTITY, &camera, w, h);
            let program = imager::imager_program(loaded, background, spaces, base)?;
            background = [0.0; 4];
            Some(program)
        }
        None => None,
    };
    Ok(Prepared { lights, objects, background, width, height, supersample: n, imager })
}

/// Light `i`'s position in camera space: a Stanford-style light shader computes only its colour,
/// so the scene places it (`position`, required); a RenderMan-style light is placed by its
/// parameters (`from`), so a `position` beside them is refused rather than ignored.
fn light_position(
    scene: &Scene,
    i: usize,
    shader: &patina_compiler::ir::Shader,
    world_to_camera: Mat4,
) -> Result<Option<glam::Vec3>, RenderError> {
    let light = &scene.lights[i];
    let at = format!("{}:{}: light[{i}]", scene.file.display(), light.line);
    let name = &shader.name;
    match (shader.stanford, light.position) {
        (true, Some(p)) => Ok(Some(world_to_camera.transform_point3(p))),
        (false, None) => Ok(None),
        (true, None) => Err(RenderError::Input(format!(
            "{at}: `{name}` is a Stanford-style light shader, which the scene places: add its \
             world-space position, e.g. `position = [0, 2, -3]`"
        ))),
        (false, Some(_)) => Err(RenderError::Input(format!(
            "{at}.position: `{name}` is a RenderMan-style light shader, which takes its position \
             from its parameters (e.g. `from`): remove `position`"
        ))),
    }
}

/// Renders a prepared scene on a backend (the GPU one needs `gpu`), downsampled to the scene's
/// output size.
pub fn render(prepared: &Prepared, backend: Backend, gpu: Option<&Gpu>) -> Result<Image, RenderError> {
    render_with_progress(prepared, backend, gpu, &Silent)
}

/// As [`render`], telling `progress` how far it has got.
pub fn render_with_progress(
    prepared: &Prepared,
    backend: Backend,
    gpu: Option<&Gpu>,
    progress: &dyn Progress,
) -> Result<Image, RenderError> {
    let image = match (backend, gpu) {
        (Backend::Gpu, Some(gpu)) => {
            progress.start(1, Unit::Draws);
            let image = gpu::render(gpu, prepared, prepared.width, prepared.height)?;
            progress.advance(1);
            image
        }
        (Backend::Gpu, None) => return Err(RenderError::Gpu("no GPU adapter".into())),
        (Backend::Cpu, _) => cpu::render(prepared, prepared.width, prepared.height, progress)?,
    };
    let image = downsample(&image, prepared.supersample);
    match (&prepared.imager, backend, gpu) {
        (Some(program), Backend::Gpu, Some(gpu)) => imager::gpu(gpu, program, &image),
        (Some(program), _, _) => imager::cpu(program, &image),
        (None, _, _) => Ok(image),
    }
}

/// The mean of each `n × n` block of samples.
fn downsample(image: &Image, n: u32) -> Image {
    if n <= 1 {
        return image.clone();
    }
    let (w, h) = (image.width / n, image.height / n);
    let mut pixels = vec![[0f32; 4]; (w * h) as usize];
    let scale = 1.0 / (n * n) as f32;
    for y in 0..h {
        for x in 0..w {
            let mut sum = [0f32; 4];
            for j in 0..n {
                for i in 0..n {
                    let p = image.pixels[((y * n + j) * image.width + x * n + i) as usize];
                    for c in 0..4 {
                        sum[c] += p[c];
                    }
                }
            }
            pixels[(y * w + x) as usize] = sum.map(|s| s * scale);
        }
    }
    Image { width: w, height: h, pixels }
}
