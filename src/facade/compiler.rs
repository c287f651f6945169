//! [`Compiler`]: a shader file (or text) with its lights, bound to the values you fix, compiled
//! to WGSL, a naga module and its [`Interface`]; and the errors that can stop it.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use patina_compiler::Checked;
use patina_compiler::backend::binding::{Binding, BoundLight};
use patina_compiler::backend::cpu::CpuProgram;
use patina_compiler::backend::object::{Beside, CompiledObject, HostPart, compile_object};
use patina_compiler::backend::wgsl::Lowering;
use patina_compiler::bind::{Consumed, Fixed};
use patina_compiler::diag::{Diagnostic, Severity};
use patina_compiler::opt::Prepared;
use patina_compiler::source::SourceMap;
use patina_compiler::syntax::ast::ShaderKind;
use patina_compiler::syntax::preprocess::FsLoader;
use patina_runtime::render::program::{DisplacementProgram, LightProgram, LoadedShader, SurfaceProgram};

use super::Value;
use crate::Interface;

/// Compiles surface shaders to WGSL: a builder of the options, then [`Compiler::compile_file`] or
/// [`Compiler::compile_source`] for each shader.
///
/// ```
/// let compiled = patina::Compiler::new()
///     .light(patina::Light::stdlib("shaders.sl", "pointlight"))
///     .fix("roughness", 0.2)
///     .compile_source("matte.sl", "surface matte(float Kd = 1; float roughness = 0.1) {
///         Ci = Cs * Kd * diffuse(faceforward(normalize(N), I));
///     }")?;
/// assert!(compiled.wgsl.contains("fn fs_main"));
/// assert_eq!(compiled.interface.param("roughness").unwrap().fixed, Some(vec![0.2]));
/// # Ok::<(), patina::CompileError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Compiler {
    include_dirs: Vec<PathBuf>,
    shader: Option<String>,
    lights: Vec<Light>,
    displacement: Option<Light>,
    atmosphere: Option<Light>,
    fixed: Vec<(String, Value)>,
    fold_host: bool,
    lowering: Lowering,
}

impl Default for Compiler {
    fn default() -> Compiler {
        Compiler {
            include_dirs: Vec::new(),
            shader: None,
            lights: Vec::new(),
            displacement: None,
            atmosphere: None,
            fixed: Vec::new(),
            fold_host: false,
            lowering: Lowering::Fast,
        }
    }
}

/// A light (or displacement or atmosphere) shader to bind: where its source is, which shader of it, and the
/// values it is compiled with.
#[derive(Clone, Debug)]
pub struct Light {
    source: Source,
    name: Option<String>,
    fixed: Vec<(String, Value)>,
}

#[derive(Clone, Debug)]
enum Source {
    File(PathBuf),
    Stdlib(String),
    Text { name: String, text: String },
}

impl Light {
    /// The first light shader of a file (or, for a displacement, its first displacement shader).
    pub fn file(path: impl Into<PathBuf>) -> Light {
        Light { source: Source::File(path.into()), name: None, fixed: Vec::new() }
    }

    /// A shader of a standard-library module (`shaders.sl` has RenderMan's `pointlight`,
    /// `distantlight`, `spotlight`, `ambientlight`, ...).
    pub fn stdlib(module: &str, shader: &str) -> Light {
        Light { source: Source::Stdlib(module.into()), name: Some(shader.into()), fixed: Vec::new() }
    }

    /// A shader of source text, shown in diagnostics as `name`.
    pub fn source(name: &str, text: &str) -> Light {
        Light { source: Source::Text { name: name.into(), text: text.into() }, name: None, fixed: Vec::new() }
    }

    /// Picks the shader called `shader` from the source.
    pub fn named(mut self, shader: &str) -> Light {
        self.name = Some(shader.into());
        self
    }

    /// Compiles the light with parameter `name` set to `value` (not for points, vectors, normals
    /// and matrices: set those per draw with `Uniforms::set_light`).
    pub fn with(mut self, name: &str, value: impl Into<Value>) -> Light {
        self.fixed.push((name.into(), value.into()));
        self
    }
}

impl Compiler {
    /// A compiler with no include directories, no lights and nothing fixed.
    pub fn new() -> Compiler {
        Compiler::default()
    }

    /// Adds a directory that `#include` searches (after the including file's own directory).
    pub fn include_dir(mut self, dir: impl Into<PathBuf>) -> Compiler {
        self.include_dirs.push(dir.into());
        self
    }

    /// Picks the surface shader called `name` (the default is the file's first surface shader).
    pub fn shader(mut self, name: &str) -> Compiler {
        self.shader = Some(name.into());
        self
    }

    /// Binds a light; lights are numbered in the order they are added.
    pub fn light(mut self, light: Light) -> Compiler {
        self.lights.push(light);
        self
    }

    /// Binds a displacement shader, run before the surface at each fragment (bump mapping).
    pub fn displacement(mut self, shader: Light) -> Compiler {
        self.displacement = Some(shader);
        self
    }

    /// Binds an atmosphere (volume) shader, run after the surface at each fragment on its `Ci`
    /// and `Oi` (fog, depth cueing); its parameters take the values given with [`Light::with`].
    pub fn atmosphere(mut self, shader: Light) -> Compiler {
        self.atmosphere = Some(shader);
        self
    }

    /// Compiles parameter `name` in as `value`: what it decides is left out, and it has no
    /// uniform (string parameters, such as texture names, are always compiled in; give them here).
    /// Points, vectors, normals and matrices cannot be fixed (their camera-space value depends on
    /// the view): set them per draw with [`Uniforms::set`](crate::Uniforms::set).
    pub fn fix(mut self, name: &str, value: impl Into<Value>) -> Compiler {
        self.fixed.push((name.into(), value.into()));
        self
    }

    /// With `true`, the host part is folded into the WGSL: the uniform block then holds only
    /// parameters, predefined variables, spaces and geometry matrices, which a program without
    /// Patina can fill ([`Interface::needs_host`] is false); the GPU recomputes per vertex or
    /// fragment what the host would have computed once per draw. The default (`false`) keeps the
    /// host part, which [`Uniforms`](crate::Uniforms) runs on the CPU.
    pub fn fold_host(mut self, fold: bool) -> Compiler {
        self.fold_host = fold;
        self
    }

    /// How the WGSL writes the built-ins. The default, [`Lowering::Fast`], uses WGSL's own
    /// (`dot`, `normalize`, `inverseSqrt`, matrix products), as hand-written WGSL does;
    /// [`Lowering::Exact`] spells them out in the CPU reference's order of operations, so that
    /// the GPU reproduces [`testing`](crate::testing)'s results bit for bit where WGSL is exact.
    pub fn lowering(mut self, lowering: Lowering) -> Compiler {
        self.lowering = lowering;
        self
    }

    /// Reads and compiles the surface shader of `path`.
    pub fn compile_file(&self, path: impl AsRef<Path>) -> Result<Compiled, CompileError> {
        self.compile(&self.check_file(path.as_ref())?)
    }

    /// Compiles the surface shader of `text`, shown in diagnostics as `name`; includes are found
    /// in the include directories.
    pub fn compile_source(&self, name: &str, text: &str) -> Result<Compiled, CompileError> {
        self.compile(&self.check_text(name, text))
    }

    /// Reads and checks `path` as every command does ([`patina_compiler::check_file`]: beside
    /// the file, then in the include directories).
    pub(crate) fn check_file(&self, path: &Path) -> Result<Checked, CompileError> {
        patina_compiler::check_file(path, &self.include_dirs)
            .map_err(|e| CompileError::Io { path: e.path, message: e.reason })
    }

    /// Checks `text`, shown in diagnostics as `name`, with the include directories.
    pub(crate) fn check_text(&self, name: &str, text: &str) -> Checked {
        patina_compiler::check_source(name, text, &FsLoader { include_dirs: self.include_dirs.clone() })
    }

    fn compile(&self, checked: &Checked) -> Result<Compiled, CompileError> {
        let loaded = self.load(checked, ShaderKind::Surface, self.shader.as_deref(), &self.fixed)?;
        let mut warnings = loaded.warnings;
        let surface = loaded.shader;
        let mut lights = Vec::new();
        for light in &self.lights {
            let l = self.load_bound(light, ShaderKind::Light)?;
            warnings.extend(l.warnings);
            let binding = Binding { lights: Vec::new(), strings: l.shader.strings.clone() };
            let cpu = CpuProgram::compile(&l.shader.shader, &binding).map_err(|d| internal(d, &l.shader))?;
            lights.push(LightProgram { loaded: l.shader, cpu, values: Vec::new(), position: None });
        }
        let displacement = match &self.displacement {
            Some(d) => {
                let d = self.load_bound(d, ShaderKind::Displacement)?;
                warnings.extend(d.warnings);
                let binding = Binding { lights: Vec::new(), strings: d.shader.strings.clone() };
                let cpu =
                    CpuProgram::compile(&d.shader.shader, &binding).map_err(|e| internal(e, &d.shader))?;
                Some(DisplacementProgram { loaded: d.shader, cpu, values: Vec::new() })
            }
            None => None,
        };
        let atmosphere = match &self.atmosphere {
            Some(a) => {
                let a = self.load_bound(a, ShaderKind::Volume)?;
                warnings.extend(a.warnings);
                let binding = Binding { lights: Vec::new(), strings: a.shader.strings.clone() };
                let cpu =
                    CpuProgram::compile(&a.shader.shader, &binding).map_err(|e| internal(e, &a.shader))?;
                Some(DisplacementProgram { loaded: a.shader, cpu, values: Vec::new() })
            }
            None => None,
        };
        let host_part = if self.fold_host { HostPart::Folded } else { HostPart::Interpreted };
        let compiled = {
            let bound: Vec<BoundLight> = lights.iter().map(|l| l.loaded.bound()).collect();
            let beside = Beside {
                lights: &bound,
                displacement: displacement.as_ref().map(|d| d.loaded.bound()),
                atmosphere: atmosphere.as_ref().map(|a| a.loaded.bound()),
            };
            compile_object(&surface.shader, &surface.strings, &beside, self.lowering, host_part)
        };
        let CompiledObject { stages, mut gpu, host, vertex, fragment } =
            compiled.map_err(|d| internal(d, &surface))?;
        for p in &mut gpu.interface.params {
            p.fixed = surface.params.iter().find(|(n, _)| *n == p.name).map(|(_, v)| v.clone());
        }
        let wgsl = gpu.wgsl().map_err(|d| internal(d, &surface))?;
        let program = SurfaceProgram {
            loaded: surface,
            stages,
            gpu,
            host,
            vertex,
            fragment,
            uniforms: Vec::new(),
            displacement,
            atmosphere,
        };
        let mut files = Vec::new();
        let shaders = std::iter::once(&program.loaded)
            .chain(lights.iter().map(|l| &l.loaded))
            .chain(program.displacement.iter().map(|d| &d.loaded))
            .chain(program.atmosphere.iter().map(|a| &a.loaded));
        for shader in shaders {
            for (_, file) in shader.sources.files() {
                let path = PathBuf::from(&file.name);
                // Standard-library modules and macro expansions are not files on disk.
                if path.is_file() && !files.contains(&path) {
                    files.push(path);
                }
            }
        }
        Ok(Compiled {
            files,
            wgsl,
            module: program.gpu.module.clone(),
            interface: program.gpu.interface.clone(),
            warnings,
            program: Arc::new(program),
            lights: Arc::new(lights),
        })
    }

    fn load_bound(&self, light: &Light, kind: ShaderKind) -> Result<Loaded, CompileError> {
        match &light.source {
            Source::File(path) => {
                self.load(&self.check_file(path)?, kind, light.name.as_deref(), &light.fixed)
            }
            Source::Stdlib(module) => {
                let shown = format!("{}/{module}", patina_compiler::stdlib::PREFIX);
                let text = patina_compiler::stdlib::source(module).ok_or_else(|| CompileError::Io {
                    path: PathBuf::from(&shown),
                    message: "no such standard-library module".into(),
                })?;
                self.load(&self.check_text(&shown, text), kind, light.name.as_deref(), &light.fixed)
            }
            Source::Text { name, text } => {
                self.load(&self.check_text(name, text), kind, light.name.as_deref(), &light.fixed)
            }
        }
    }

    /// The bound and prepared shader of `checked` with its warnings, for the CPU reference
    /// ([`crate::testing`]): the [`shader`](Compiler::shader) named, or the first, of `kind`.
    pub(crate) fn load_shader(
        &self,
        checked: &Checked,
        kind: ShaderKind,
    ) -> Result<(LoadedShader, Diagnostics), CompileError> {
        let loaded = self.load(checked, kind, self.shader.as_deref(), &self.fixed)?;
        Ok((loaded.shader, loaded.warnings))
    }

    /// Picks the shader of `kind` of a checked source, binds it to `fixed` and prepares it.
    fn load(
        &self,
        checked: &Checked,
        kind: ShaderKind,
        shader: Option<&str>,
        fixed: &[(String, Value)],
    ) -> Result<Loaded, CompileError> {
        let name = checked.sources.file(checked.root).name.as_str();
        let sources = Arc::new(checked.sources.clone());
        let all: Vec<Diagnostic> = checked.diagnostics.iter().cloned().collect();
        if checked.has_errors() {
            return Err(CompileError::Diagnostics(Diagnostics::new(sources, all)));
        }
        let warnings = Diagnostics::new(Arc::clone(&sources), all);
        let found = checked
            .program
            .shaders
            .iter()
            .find(|s| s.kind == kind && shader.is_none_or(|n| s.name == n))
            .ok_or_else(|| CompileError::NoShader {
                file: name.into(),
                kind: kind.keyword(),
                name: shader.map(Into::into),
            })?;
        let mut strings = Vec::new();
        let mut numbers = Vec::new();
        for (param, value) in fixed {
            let Some(local) = found.params.iter().map(|p| found.local(*p)).find(|l| l.name == param.as_str())
            else {
                return Err(CompileError::UnknownParam {
                    shader: found.name.to_string(),
                    name: param.clone(),
                });
            };
            match value {
                Value::String(s) => strings.push((param.clone(), s.clone())),
                Value::Numbers(_) if super::depends_on_view(local.ty) => {
                    return Err(CompileError::DependsOnView {
                        name: param.clone(),
                        ty: local.ty.to_string(),
                    });
                }
                Value::Numbers(v) => {
                    let expected = super::components(local.ty);
                    if v.len() != expected {
                        return Err(CompileError::WrongValue {
                            name: param.clone(),
                            ty: local.ty.to_string(),
                            expected,
                            given: v.len(),
                        });
                    }
                    numbers.push((param.clone(), v.clone()));
                }
            }
        }
        let fixed: Vec<Fixed> =
            numbers.iter().map(|(n, v)| Fixed { name: n.clone(), value: v.clone() }).collect();
        // A user's program may read any output parameter: keep them all.
        let bound = patina_compiler::bind::specialize(found, &fixed, &strings, Consumed::All);
        let shader = Prepared::with_strings(bound.shader, &strings);
        let loaded = LoadedShader { shader, strings, params: numbers, decisions: bound.decisions, sources };
        Ok(Loaded { shader: loaded, warnings })
    }
}

/// A checked, bound and differentiated shader with its warnings.
struct Loaded {
    shader: LoadedShader,
    warnings: Diagnostics,
}

/// A diagnostic from a stage after checking (a limit, a feature the GPU lacks, an internal error).
fn internal(d: Diagnostic, shader: &LoadedShader) -> CompileError {
    CompileError::Program(Diagnostics::new(Arc::clone(&shader.sources), vec![d]))
}

/// A compiled surface shader: the WGSL, the naga module it is written from, and the interface
/// that says how to bind and fill it. Cheap to clone.
#[derive(Clone)]
pub struct Compiled {
    /// The module as WGSL text.
    pub wgsl: String,
    /// The validated naga module (for `wgpu::ShaderSource::Naga`, or other naga back ends).
    pub module: naga::Module,
    /// Its bindings, uniform layout, attributes, varyings, parameters and output.
    pub interface: Interface,
    /// Warnings from checking the sources (empty when there were none).
    pub warnings: Diagnostics,
    /// Every file on disk the program was compiled from: the shader's, its lights', and
    /// everything they include (for rebuilding or reloading when one changes).
    pub files: Vec<PathBuf>,
    pub(crate) program: Arc<SurfaceProgram>,
    pub(crate) lights: Arc<Vec<LightProgram>>,
}

impl fmt::Debug for Compiled {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Compiled").field("shader", &self.interface.shader).finish_non_exhaustive()
    }
}

impl Compiled {
    /// The shader's name.
    pub fn name(&self) -> &str {
        &self.interface.shader
    }

    /// A uniform block for this program with every parameter at its default, for the default
    /// [`View`](crate::View): set values, then take its [`bytes`](crate::Uniforms::bytes).
    pub fn uniforms(&self) -> crate::Uniforms<'_> {
        crate::Uniforms::new(self)
    }
}

/// Diagnostics with the sources they point into; `Display` renders them as the command line
/// does (codespan-reporting's layout, without colour).
#[derive(Clone, Default)]
pub struct Diagnostics {
    /// Each checked source's diagnostics with its files (a surface and its lights are checked
    /// apart, and their spans point into their own maps).
    groups: Vec<(Arc<SourceMap>, Vec<Diagnostic>)>,
}

impl Diagnostics {
    pub(crate) fn new(sources: Arc<SourceMap>, list: Vec<Diagnostic>) -> Diagnostics {
        Diagnostics { groups: vec![(sources, list)] }
    }

    /// The diagnostics, in the order they were found.
    pub fn iter(&self) -> impl Iterator<Item = &Diagnostic> {
        self.groups.iter().flat_map(|(_, list)| list)
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.iter().next().is_none()
    }

    /// Whether any is an error.
    pub fn has_errors(&self) -> bool {
        self.iter().any(|d| d.severity == Severity::Error)
    }

    fn extend(&mut self, other: Diagnostics) {
        self.groups.extend(other.groups.into_iter().filter(|(_, list)| !list.is_empty()));
    }
}

impl fmt::Debug for Diagnostics {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter().map(|d| (&d.code, &d.message))).finish()
    }
}

impl fmt::Display for Diagnostics {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text: String = self
            .groups
            .iter()
            .map(|(sources, list)| patina_compiler::diag::render_text(sources, list))
            .collect();
        f.write_str(text.trim_end())
    }
}

impl std::error::Error for Diagnostics {}

/// Why a shader could not be compiled.
#[derive(Debug)]
#[non_exhaustive]
pub enum CompileError {
    /// The source has errors (rendered by `Display`).
    Diagnostics(Diagnostics),
    /// The source is valid, but the program cannot be built: a resource limit (the number of
    /// bound lights, ...), a feature the GPU back end lacks, or an internal error.
    Program(Diagnostics),
    /// A file could not be read.
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        message: String,
    },
    /// The source has no shader of the kind (and name) asked for.
    NoShader {
        /// The source's name.
        file: String,
        /// `surface`, `light` or `displacement`.
        kind: &'static str,
        /// The name asked for, if any.
        name: Option<String>,
    },
    /// A value was fixed for a parameter the shader does not have.
    UnknownParam {
        /// The shader.
        shader: String,
        /// The parameter.
        name: String,
    },
    /// A point, vector, normal or matrix was fixed: its value in camera space depends on the
    /// view, so it is set per draw with `Uniforms::set` (or `set_light`) instead.
    DependsOnView {
        /// The parameter.
        name: String,
        /// Its type.
        ty: String,
    },
    /// A fixed value has the wrong number of components for its parameter.
    WrongValue {
        /// The parameter.
        name: String,
        /// Its type.
        ty: String,
        /// Components it takes.
        expected: usize,
        /// Components given.
        given: usize,
    },
}

impl fmt::Display for CompileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CompileError::Diagnostics(d) | CompileError::Program(d) => write!(f, "{d}"),
            CompileError::Io { path, message } => write!(f, "cannot read `{}`: {message}", path.display()),
            CompileError::NoShader { file, kind, name: Some(name) } => {
                write!(f, "`{file}` has no {kind} shader `{name}`")
            }
            CompileError::NoShader { file, kind, name: None } => write!(f, "`{file}` has no {kind} shader"),
            CompileError::UnknownParam { shader, name } => {
                write!(f, "shader `{shader}` has no parameter `{name}`")
            }
            CompileError::DependsOnView { name, ty } => write!(
                f,
                "parameter `{name}` is a {ty}, which depends on the view: set it per draw with `Uniforms::set`"
            ),
            CompileError::WrongValue { name, ty, expected, given } => {
                write!(f, "parameter `{name}` is a {ty} of {expected} number(s); {given} given")
            }
        }
    }
}

impl std::error::Error for CompileError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            CompileError::Diagnostics(d) | CompileError::Program(d) => Some(d),
            _ => None,
        }
    }
}
