//! The CPU reference for your own tests, in the spirit of OSL's `testshade`: evaluate a shader at
//! named points and read its outputs, and render a small scene on both backends to compare the
//! GPU with the reference under the gallery's thresholds.
//!
//! ```
//! let out = patina::testing::shade("surface ramp() { Ci = color(s, t, 0.5); }")
//!     .at(&[("s", &[0.25]), ("t", &[0.75])])
//!     .eval::<f32>()?;
//! assert_eq!(out.get("Ci"), Some(&[0.25, 0.75, 0.5][..]));
//! # Ok::<(), patina::testing::TestError>(())
//! ```
//!
//! A point gives per-point inputs by name: predefined variables (`P`, `N`, `I`, `s`, `t`, ...),
//! varying parameters, derivative seeds (`dx(P)`, `dy(s)`) and per-light values (`L[0]`);
//! [`Shade::set`] gives one value for every point (uniform parameters, spaces as `space:NAME`).
//! What is not given takes its default: parameters their declared one, `Cs` and `Os` white,
//! spaces the identity, every other predefined variable zero (so give `Ng` to a shader that calls
//! `faceforward(N, I)`, which turns `N` against it).
//! Lights are given as the surface sees them, by [`Shade::light`] (`L` towards the light and
//! `Cl`) and [`Shade::ambient`], as `patina eval --light` does; to run real light shaders, render a
//! scene ([`sphere_scene`], [`compare_backends`]). Every name is checked against the shader: a
//! name it does not declare is [`TestError::UnknownInput`], a value of the wrong size
//! [`TestError::WrongWidth`]. A name the shader declares but never reads is accepted and has no
//! effect.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use patina_compiler::backend::binding::{Binding, LightBinding};
use patina_compiler::backend::cpu::scalar::Real;
use patina_compiler::backend::cpu::{CpuProgram, EvalError, Evaluator, SlotKind};
use patina_compiler::ir::Shader;
use patina_compiler::ir::types::Type;
use patina_compiler::syntax::ast::ShaderKind;
use patina_runtime::gpu::Gpu;
use patina_runtime::image::{Comparison, Image, ImageError, Thresholds, compare};
use patina_runtime::render::program::LoadedShader;
use patina_runtime::render::{self, Backend, RenderError};
use patina_runtime::scene::{Scene, SceneError, toml_string};

use crate::facade::components;
use crate::{CompileError, Compiler, Diagnostics, Value};

/// Starts an evaluation of the shader in `source` (shown in diagnostics as `test.sl`; includes
/// are found in the [`include_dir`](Shade::include_dir)s).
pub fn shade(source: &str) -> Shade {
    Shade::new(Input::Text(source.to_string()))
}

/// Starts an evaluation of the shader in the file at `path` (its includes are found beside it,
/// then in the [`include_dir`](Shade::include_dir)s).
pub fn shade_file(path: impl AsRef<Path>) -> Shade {
    Shade::new(Input::File(path.as_ref().to_path_buf()))
}

#[derive(Clone, Debug)]
enum Input {
    Text(String),
    File(PathBuf),
}

/// A light as the surface sees it.
#[derive(Clone, Debug)]
struct LightValue {
    /// `None` for an ambient light.
    l: Option<Value>,
    cl: Value,
}

/// An evaluation being set up: the shader, the values for every point, the points and the
/// lights; run it with [`Shade::eval`].
#[derive(Clone, Debug)]
#[must_use = "nothing is evaluated until `eval`"]
pub struct Shade {
    input: Input,
    compiler: Compiler,
    shader: Option<String>,
    set: Vec<(String, Value)>,
    points: Vec<Vec<(String, Vec<f64>)>>,
    lights: Vec<LightValue>,
    budget: Option<u64>,
}

impl Shade {
    fn new(input: Input) -> Shade {
        Shade {
            input,
            compiler: Compiler::new(),
            shader: None,
            set: Vec::new(),
            points: Vec::new(),
            lights: Vec::new(),
            budget: None,
        }
    }

    /// Picks the shader called `name`, of any kind (the default is the first surface shader, or
    /// the first shader when there is none).
    pub fn shader(mut self, name: &str) -> Shade {
        self.compiler = self.compiler.shader(name);
        self.shader = Some(name.into());
        self
    }

    /// Adds a directory that `#include` searches.
    pub fn include_dir(mut self, dir: impl Into<PathBuf>) -> Shade {
        self.compiler = self.compiler.include_dir(dir);
        self
    }

    /// Sets `name` for every point: a parameter, a predefined variable, a seed, or a space
    /// (`space:NAME`, the 16 numbers of the matrix from "current" to it, row by row). A point that
    /// gives the same name overrides it.
    pub fn set(mut self, name: &str, value: impl Into<Value>) -> Shade {
        self.set.push((name.into(), value.into()));
        self
    }

    /// Compiles parameter `name` in as `value`, as [`Compiler::fix`] does for the GPU (what it
    /// decides is left out of the program); the values should be those of [`Shade::set`].
    pub fn fix(mut self, name: &str, value: impl Into<Value>) -> Shade {
        self.compiler = self.compiler.fix(name, value);
        self
    }

    /// Adds a point with its inputs, e.g. `.at(&[("s", &[0.5]), ("N", &[0.0, 0.0, 1.0])])`;
    /// inputs it does not give keep the values of [`Shade::set`] or their defaults. With no
    /// point, the shader is evaluated once, at the defaults.
    pub fn at(mut self, inputs: &[(&str, &[f64])]) -> Shade {
        self.points.push(inputs.iter().map(|(n, v)| (n.to_string(), v.to_vec())).collect());
        self
    }

    /// Adds points, one per item, each as [`Shade::at`] takes it.
    pub fn points<'a, I, P>(mut self, points: I) -> Shade
    where
        I: IntoIterator<Item = P>,
        P: IntoIterator<Item = (&'a str, Vec<f64>)>,
    {
        for point in points {
            self.points.push(point.into_iter().map(|(n, v)| (n.to_string(), v)).collect());
        }
        self
    }

    /// Binds a light as the surface sees it: `l`, the vector from the surface towards the light
    /// (its length is the distance), and its colour `cl`. Lights are numbered in the order they are
    /// added (`L[0]`, `Cl[0]`, ...; a point can give its own `L[k]`).
    pub fn light(mut self, l: impl Into<Value>, cl: impl Into<Value>) -> Shade {
        self.lights.push(LightValue { l: Some(l.into()), cl: cl.into() });
        self
    }

    /// Binds an ambient light of colour `cl` (summed by `ambient()`, skipped by `illuminance`).
    pub fn ambient(mut self, cl: impl Into<Value>) -> Shade {
        self.lights.push(LightValue { l: None, cl: cl.into() });
        self
    }

    /// Changes the most iterations any loop may run (the GPU's cap by default); a loop that
    /// runs longer stops the evaluation with [`TestError::IterationBudget`].
    pub fn budget(mut self, iterations: u64) -> Shade {
        self.budget = Some(iterations);
        self
    }

    /// Evaluates the shader at every point in precision `F`: `f32`, as the GPU computes, or
    /// `f64`, the ground truth.
    pub fn eval<F: Precision>(&self) -> Result<Shaded, TestError> {
        let (loaded, warnings) = self.load()?;
        let shader = &loaded.shader;
        let binding = Binding {
            lights: self
                .lights
                .iter()
                .map(|l| LightBinding { ambient: l.l.is_none(), ..LightBinding::default() })
                .collect(),
            strings: loaded.strings.clone(),
        };
        let program = CpuProgram::compile(shader, &binding)
            .map_err(|d| TestError::Diagnostics(Diagnostics::new(Arc::clone(&loaded.sources), vec![d])))?;
        let check = Check { shader, program: &program, lights: self.lights.len() };

        // Values for every point: the lights', then those set.
        let mut uniform: Vec<(String, Vec<f64>)> = Vec::new();
        for (k, light) in self.lights.iter().enumerate() {
            if let Some(l) = &light.l {
                uniform.push((format!("L[{k}]"), check.numbers(&format!("L[{k}]"), l)?));
            }
            uniform.push((format!("Cl[{k}]"), check.numbers(&format!("Cl[{k}]"), &light.cl)?));
        }
        for (name, value) in &self.set {
            uniform.push((name.clone(), check.numbers(name, value)?));
        }
        for point in &self.points {
            for (name, value) in point {
                check.width(name, value.len())?;
            }
        }

        let outputs: Vec<(String, usize)> = program
            .slots()
            .filter(|(_, s)| !matches!(s.kind, SlotKind::Variable | SlotKind::Space))
            .map(|(_, s)| (s.name, s.width))
            .collect();
        let output_names: Vec<&str> = outputs.iter().map(|(n, _)| n.as_str()).collect();
        let mut columns: Vec<Vec<f64>> = vec![Vec::new(); outputs.len()];

        // Points are evaluated in runs that give the same names and the same uniform values
        // (one value per batch): usually all of them at once.
        let default_point = vec![Vec::new()];
        let points = if self.points.is_empty() { &default_point } else { &self.points };
        let key = |point: &Vec<(String, Vec<f64>)>| -> Vec<(String, Option<Vec<f64>>)> {
            point
                .iter()
                .filter(|(n, _)| program.slot(n).is_some())
                .map(|(n, v)| (n.clone(), check.is_uniform(n).then(|| v.clone())))
                .collect()
        };
        let mut start = 0;
        while start < points.len() {
            let run_key = key(&points[start]);
            let mut end = start + 1;
            while end < points.len() && key(&points[end]) == run_key {
                end += 1;
            }
            let mut eval = Evaluator::<F>::new(&program);
            if let Some(b) = self.budget {
                eval.set_budget(b);
            }
            for (name, value) in &uniform {
                if program.slot(name).is_some() {
                    eval.set(name, value).map_err(|e| eval_error(e, &loaded))?;
                }
            }
            let mut inputs: Vec<(&str, Vec<f64>)> = Vec::new();
            for (name, value) in &run_key {
                match value {
                    Some(v) => eval.set(name, v).map_err(|e| eval_error(e, &loaded))?,
                    None => {
                        let column = points[start..end]
                            .iter()
                            .flat_map(|p| p.iter().rev().find(|(n, _)| n == name).map(|(_, v)| v))
                            .flatten()
                            .copied()
                            .collect();
                        inputs.push((name.as_str(), column));
                    }
                }
            }
            let inputs: Vec<(&str, &[f64])> = inputs.iter().map(|(n, c)| (*n, c.as_slice())).collect();
            let values =
                eval.eval_points(end - start, &inputs, &output_names).map_err(|e| eval_error(e, &loaded))?;
            for (column, v) in columns.iter_mut().zip(values) {
                column.extend(v);
            }
            start = end;
        }
        Ok(Shaded {
            shader: shader.name.to_string(),
            count: points.len(),
            names: outputs.iter().map(|(n, _)| n.clone()).collect(),
            widths: outputs.iter().map(|(_, w)| *w).collect(),
            columns,
            warnings,
        })
    }

    /// Checks, binds and differentiates the shader through [`Compiler`]'s loading.
    fn load(&self) -> Result<(LoadedShader, Diagnostics), TestError> {
        let checked = match &self.input {
            Input::Text(text) => self.compiler.check_text("test.sl", text),
            Input::File(path) => self.compiler.check_file(path)?,
        };
        const KINDS: [ShaderKind; 5] = [
            ShaderKind::Surface,
            ShaderKind::Light,
            ShaderKind::Displacement,
            ShaderKind::Volume,
            ShaderKind::Imager,
        ];
        for kind in KINDS {
            match self.compiler.load_shader(&checked, kind) {
                Ok(loaded) => return Ok(loaded),
                Err(CompileError::NoShader { .. }) => continue,
                Err(e) => return Err(e.into()),
            }
        }
        let file = checked.sources.file(checked.root).name.clone();
        Err(TestError::NoShader { file, name: self.shader.clone() })
    }
}

/// The precisions the CPU reference evaluates in: `f32` (as the GPU computes) and `f64` (the
/// ground truth).
pub trait Precision: Real + private::Sealed {}

impl Precision for f32 {}
impl Precision for f64 {}

mod private {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// The names and widths the shader declares, for checking what a test gives.
struct Check<'a> {
    shader: &'a Shader,
    program: &'a CpuProgram,
    lights: usize,
}

impl Check<'_> {
    /// The numbers of a value for `name`, checked.
    fn numbers(&self, name: &str, value: &Value) -> Result<Vec<f64>, TestError> {
        match value {
            Value::Numbers(v) => {
                self.width(name, v.len())?;
                Ok(v.clone())
            }
            _ => Err(TestError::StringValue { name: name.into() }),
        }
    }

    /// Checks that the shader declares `name` and that it takes `given` numbers.
    fn width(&self, name: &str, given: usize) -> Result<(), TestError> {
        let expected = self.expected(name).ok_or_else(|| TestError::UnknownInput {
            shader: self.shader.name.to_string(),
            name: name.into(),
        })?;
        if expected == given {
            Ok(())
        } else {
            Err(TestError::WrongWidth { name: name.into(), expected, given })
        }
    }

    /// How many numbers `name` takes, when the shader declares it (whether or not it reads it).
    fn expected(&self, name: &str) -> Option<usize> {
        if name.starts_with("space:") {
            return Some(16);
        }
        if let Some((_, info)) = self.program.slots().find(|(_, s)| s.name == name) {
            return Some(info.width);
        }
        if let Some(inner) =
            name.strip_prefix("dx(").or_else(|| name.strip_prefix("dy(")).and_then(|n| n.strip_suffix(')'))
        {
            return self.declared(inner, false);
        }
        if let Some((base, index)) = name.strip_suffix(']').and_then(|n| n.split_once('[')) {
            let k: usize = index.parse().ok()?;
            return if k < self.lights { self.declared(base, true) } else { None };
        }
        self.declared(name, false)
    }

    /// The width of a parameter or predefined variable (a per-light one when `perlight`).
    fn declared(&self, name: &str, perlight: bool) -> Option<usize> {
        let s = self.shader;
        if !perlight {
            let param = s.params.iter().map(|p| s.local(*p)).find(|l| l.name == name);
            if let Some(local) = param {
                return Some(components(local.ty));
            }
        }
        let global = patina_compiler::sema::globals::lookup(name, s.kind, s.stanford)?;
        (global.perlight == perlight).then(|| components(Type::of(global.ty)))
    }

    /// Whether the program takes one value of `name` for a whole batch.
    fn is_uniform(&self, name: &str) -> bool {
        self.program.slots().any(|(_, s)| s.name == name && s.uniform)
    }
}

fn eval_error(e: EvalError, loaded: &LoadedShader) -> TestError {
    match e {
        EvalError::UnknownName(name) => {
            TestError::UnknownInput { shader: loaded.shader.name.to_string(), name }
        }
        EvalError::WrongSize { name, expected, found } => {
            TestError::WrongWidth { name, expected, given: found }
        }
        e @ EvalError::IterationBudget { .. } => {
            TestError::IterationBudget(Diagnostics::new(Arc::clone(&loaded.sources), vec![e.to_diagnostic()]))
        }
        e => TestError::Eval(e),
    }
}

/// What a shader computed at each point: its outputs and every predefined variable and
/// parameter it reads or writes, by name.
#[derive(Clone, Debug)]
pub struct Shaded {
    shader: String,
    count: usize,
    names: Vec<String>,
    widths: Vec<usize>,
    /// Per name: `count * width` numbers, point after point.
    columns: Vec<Vec<f64>>,
    warnings: Diagnostics,
}

impl Shaded {
    /// The number of points.
    pub fn len(&self) -> usize {
        self.count
    }

    /// Whether there are no points (never: with no point given, the shader runs once).
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The value of `name` at the first point (the only one, when one was given); `None` when
    /// the shader neither reads nor writes it.
    pub fn get(&self, name: &str) -> Option<&[f64]> {
        self.point(0).and_then(|p| p.get(name))
    }

    /// Point `i` (in the order they were added), if there is one.
    pub fn point(&self, i: usize) -> Option<Point<'_>> {
        (i < self.count).then_some(Point { shaded: self, index: i })
    }

    /// The points in order.
    pub fn points(&self) -> impl Iterator<Item = Point<'_>> {
        (0..self.count).map(|index| Point { shaded: self, index })
    }

    /// The values of `name` at every point, point after point.
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.names.iter().position(|n| n == name).map(|i| self.columns[i].as_slice())
    }

    /// The names that can be read, in the program's order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.names.iter().map(String::as_str)
    }

    /// The shader's warnings (empty when it had none).
    pub fn warnings(&self) -> &Diagnostics {
        &self.warnings
    }
}

impl fmt::Display for Shaded {
    /// A table: one row per point, one column per name.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "shader `{}`, {} point(s)", self.shader, self.count)?;
        for p in self.points() {
            write!(f, "{}:", p.index)?;
            for name in &self.names {
                let v = p.get(name).unwrap_or(&[]);
                let parts: Vec<String> = v.iter().map(|x| x.to_string()).collect();
                write!(f, " {name}=({})", parts.join(", "))?;
            }
            writeln!(f)?;
        }
        Ok(())
    }
}

/// One point of a [`Shaded`].
#[derive(Copy, Clone, Debug)]
pub struct Point<'a> {
    shaded: &'a Shaded,
    index: usize,
}

impl<'a> Point<'a> {
    /// Its position among the points.
    pub fn index(&self) -> usize {
        self.index
    }

    /// The value of `name` here; `None` when the shader neither reads nor writes it.
    pub fn get(&self, name: &str) -> Option<&'a [f64]> {
        let s = self.shaded;
        let i = s.names.iter().position(|n| n == name)?;
        let w = s.widths[i];
        Some(&s.columns[i][self.index * w..(self.index + 1) * w])
    }

    /// A float's value here (`None` also when `name` is not one number).
    pub fn float(&self, name: &str) -> Option<f64> {
        match self.get(name)? {
            [x] => Some(*x),
            _ => None,
        }
    }

    /// A colour's, point's, vector's or normal's value here (`None` also when `name` is not three
    /// numbers).
    pub fn triple(&self, name: &str) -> Option<[f64; 3]> {
        self.get(name)?.try_into().ok()
    }
}

/// Why an evaluation or a comparison could not be made.
#[derive(Debug)]
#[non_exhaustive]
pub enum TestError {
    /// The source has errors (`Display` renders them as the compiler does, with their codes).
    Diagnostics(Diagnostics),
    /// The shader could not be loaded for another reason (a file that cannot be read, a value
    /// fixed for a parameter the shader does not have, ...).
    Compile(CompileError),
    /// The source has no shader (of that name).
    NoShader {
        /// The source's name.
        file: String,
        /// The name asked for, if any.
        name: Option<String>,
    },
    /// An input the shader does not declare (not a parameter or predefined variable of its
    /// kind, or a light it is not bound to).
    UnknownInput {
        /// The shader.
        shader: String,
        /// The name given.
        name: String,
    },
    /// A value with the wrong number of numbers for its input.
    WrongWidth {
        /// The input.
        name: String,
        /// The numbers it takes.
        expected: usize,
        /// The numbers given.
        given: usize,
    },
    /// A string given where numbers are needed (string parameters are compiled in: use
    /// [`Shade::fix`]).
    StringValue {
        /// The input.
        name: String,
    },
    /// A loop ran past the iteration budget (the diagnostic points at it).
    IterationBudget(Diagnostics),
    /// The interpreter refused the inputs.
    Eval(EvalError),
    /// A scene could not be read or is invalid.
    Scene(SceneError),
    /// A scene could not be rendered.
    Render(RenderError),
    /// The two images could not be compared (different sizes, a bad pixel).
    Image(ImageError),
}

impl From<CompileError> for TestError {
    fn from(e: CompileError) -> TestError {
        match e {
            CompileError::Diagnostics(d) => TestError::Diagnostics(d),
            e => TestError::Compile(e),
        }
    }
}

impl fmt::Display for TestError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TestError::Diagnostics(d) | TestError::IterationBudget(d) => write!(f, "{d}"),
            TestError::Compile(e) => write!(f, "{e}"),
            TestError::NoShader { file, name: Some(name) } => write!(f, "`{file}` has no shader `{name}`"),
            TestError::NoShader { file, name: None } => write!(f, "`{file}` defines no shader"),
            TestError::UnknownInput { shader, name } => {
                write!(f, "shader `{shader}` has no input `{name}`")
            }
            TestError::WrongWidth { name, expected, given } => {
                write!(f, "`{name}` takes {expected} number(s); {given} given")
            }
            TestError::StringValue { name } => {
                write!(f, "`{name}` takes numbers; a string parameter is compiled in with `fix`")
            }
            TestError::Eval(e) => write!(f, "{e}"),
            TestError::Scene(e) => write!(f, "{e}"),
            TestError::Render(e) => write!(f, "{e}"),
            TestError::Image(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for TestError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            TestError::Diagnostics(d) | TestError::IterationBudget(d) => Some(d),
            TestError::Compile(e) => Some(e),
            TestError::Eval(e) => Some(e),
            TestError::Scene(e) => Some(e),
            TestError::Render(e) => Some(e),
            TestError::Image(e) => Some(e),
            _ => None,
        }
    }
}

/// A scene rendered on both backends, and how the GPU's image compares with the CPU
/// reference's.
#[derive(Clone, Debug)]
pub struct BackendComparison {
    /// The GPU's image.
    pub gpu: Image,
    /// The CPU reference's image.
    pub cpu: Image,
    /// GPU against CPU.
    pub comparison: Comparison,
    /// The thresholds judged by: the scene's own, or OSL's (the gallery's default).
    pub thresholds: Thresholds,
    /// Whether the GPU matches the reference within them.
    pub passes: bool,
}

/// Renders `scene` on the CPU reference and on `gpu` and compares the images with the scene's
/// thresholds (OSL's unless its `[compare]` says otherwise), as the gallery does. In a test,
/// take the device from [`patina::runtime::gpu::for_tests`](crate::runtime::gpu::for_tests).
///
/// ```no_run
/// let gpu = patina::runtime::gpu::Gpu::new()?;
/// let scene = patina::testing::sphere_scene("shaders/plastic.sl")?;
/// let result = patina::testing::compare_backends(&scene, &gpu)?;
/// assert!(result.passes, "{:?}", result.comparison);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn compare_backends(scene: &Scene, gpu: &Gpu) -> Result<BackendComparison, TestError> {
    let prepared = render::prepare(scene).map_err(TestError::Render)?;
    let cpu = render::render(&prepared, Backend::Cpu, None).map_err(TestError::Render)?;
    let gpu = render::render(&prepared, Backend::Gpu, Some(gpu)).map_err(TestError::Render)?;
    let thresholds = scene.thresholds();
    let comparison = compare(&gpu, &cpu, &thresholds).map_err(TestError::Image)?;
    let passes = comparison.passes(&thresholds);
    Ok(BackendComparison { gpu, cpu, comparison, thresholds, passes })
}

/// As [`compare_backends`], for the scene file at `path`.
pub fn compare_backends_file(path: impl AsRef<Path>, gpu: &Gpu) -> Result<BackendComparison, TestError> {
    let scene = Scene::load(path).map_err(TestError::Scene)?;
    compare_backends(&scene, gpu)
}

/// A small scene for a surface shader: a unit sphere with the shader (its parameters at their
/// defaults), seen from 4 units away under a white point light above and to the left of the
/// camera and a dim ambient light, 64 × 48 pixels. Change it before rendering (e.g. set
/// `scene.objects[0].surface.params`).
pub fn sphere_scene(shader: impl AsRef<Path>) -> Result<Scene, TestError> {
    let shader = shader.as_ref();
    let text = format!(
        r#"[output]
width = 64
height = 48
background = [0.05, 0.05, 0.08, 1.0]

[camera]
from = [0.0, 0.0, -4.0]
to = [0.0, 0.0, 0.0]
fov = 40

[[light]]
shader = "<shaders.sl>"
name = "pointlight"
params = {{ intensity = 12.0, from = [-2.5, 3.0, -3.0] }}

[[light]]
shader = "<shaders.sl>"
name = "ambientlight"
params = {{ intensity = 0.08 }}

[[object]]
mesh = "sphere"
detail = 32
shader = {}
color = [0.9, 0.35, 0.2]
"#,
        toml_string(&shader.display().to_string())
    );
    // A relative path is relative to the current directory, as for `shade_file`.
    Scene::parse(&text, "sphere_scene.toml", ".").map_err(TestError::Scene)
}
