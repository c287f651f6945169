//! Compile Patina shaders in `build.rs`: the WGSL goes into `OUT_DIR`, and Rust bindings are
//! generated for it, per shader a `#[repr(C)]` [`bytemuck`](https://docs.rs/bytemuck) struct laid
//! out as the uniform block (padding included), constants for the bind groups, bindings,
//! vertex locations and entry points, and the WGSL as a `&'static str`.
//!
//! In `build.rs` (with `patina-build` under `[build-dependencies]`):
//!
//! ```no_run
//! use patina_build::{Light, Shader, Shaders};
//!
//! fn main() -> Result<(), patina_build::Error> {
//!     Shaders::new()
//!         .shader(
//!             Shader::new("shaders/plastic.sl")
//!                 .light(Light::file("shaders/lights.sl").named("pointlight"))
//!                 .fix("roughness", 0.1),
//!         )
//!         .build()?; // a shader with errors fails the build, its diagnostics in the message
//!     Ok(())
//! }
//! ```
//!
//! and in the crate (which depends on `bytemuck` with its `derive` feature):
//!
//! ```ignore
//! mod shaders {
//!     include!(concat!(env!("OUT_DIR"), "/patina_shaders.rs"));
//! }
//! let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
//!     label: Some(shaders::plastic::SHADER),
//!     source: wgpu::ShaderSource::Wgsl(shaders::plastic::WGSL.into()),
//! });
//! let mut block: shaders::plastic::Uniforms = bytemuck::Zeroable::zeroed();
//! block.roughness = 0.2;
//! queue.write_buffer(&buffer, 0, block.as_bytes()); // @group(UNIFORM_GROUP) @binding(UNIFORM_BINDING)
//! ```
//!
//! What [`Shaders::build`] does, for each [`Shader`]:
//! - compiles it with [`patina::Compiler`] (its lights, displacement, fixed values, include
//!   directories and [`fold_host`](Shader::fold_host));
//! - writes `OUT_DIR/<module>.wgsl` and `OUT_DIR/<module>.json` (the interface,
//!   docs/interface.md);
//! - prints `cargo:rerun-if-changed` for every file it was compiled from (the shader, its
//!   lights' files and everything they `#include`), so editing any of them rebuilds the crate,
//!   and `cargo:warning` for each line of the compiler's warnings;
//! - adds `pub mod <module>` to `OUT_DIR/patina_shaders.rs` with `SHADER`, `WGSL`,
//!   `INTERFACE_JSON`, `VERTEX_ENTRY`, `FRAGMENT_ENTRY`, `UNIFORM_GROUP`, `UNIFORM_BINDING`,
//!   `UNIFORM_SIZE`, `TEXTURE_GROUP`, a `TEXTURE_<NAME>_BINDING` per texture, a
//!   `LOCATION_<NAME>` per vertex input (`LOCATION_P`, `LOCATION_N`, `LOCATION_UV`, ...,
//!   `LOCATION_PARAM_<NAME>`), the tables `FIELDS`, `ATTRIBUTES` and `TEXTURES`, the
//!   struct `Uniforms`, `offset::<field>` for each field, and compile-time assertions that the
//!   struct's size and offsets are the block's.
//!
//! Each field's documentation says where its value comes from. When the shader has a host part
//! (`NEEDS_HOST`; some fields are computed once per draw on the CPU), either fill the block at
//! run time with `patina::Uniforms`, whose bytes have this layout, or build with
//! `fold_host(true)`: then every field is a parameter, a predefined variable, a space or a
//! geometry matrix, and the program needs no Patina at run time.
//!
//! `examples/build-script` in Patina's repository is a complete crate that uses it.

#![warn(missing_docs)]

mod codegen;

use std::fmt;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

pub use patina::{CompileError, Compiled, Interface, Light, Value};

/// The name of the generated Rust file in the output directory.
pub const RUST_FILE: &str = "patina_shaders.rs";

/// The shaders to compile and the options they share; [`Shaders::build`] compiles them.
#[derive(Clone, Debug)]
pub struct Shaders {
    shaders: Vec<Shader>,
    include_dirs: Vec<PathBuf>,
    fold_host: bool,
    bytemuck: bool,
    out_dir: Option<PathBuf>,
}

impl Default for Shaders {
    fn default() -> Shaders {
        Shaders::new()
    }
}

/// One shader to compile: a `.sl` file and how to compile it. The generated module is named
/// after the file (`plastic.sl` gives `plastic`) unless [`Shader::module`] names it.
#[derive(Clone, Debug)]
pub struct Shader {
    path: PathBuf,
    module: Option<String>,
    surface: Option<String>,
    lights: Vec<Light>,
    displacement: Option<Light>,
    fixed: Vec<(String, Value)>,
    include_dirs: Vec<PathBuf>,
    fold_host: Option<bool>,
    lowering: patina::Lowering,
}

impl Shader {
    /// The surface shader of `path` (relative to the package's directory in a build script).
    pub fn new(path: impl Into<PathBuf>) -> Shader {
        Shader {
            path: path.into(),
            module: None,
            surface: None,
            lights: Vec::new(),
            displacement: None,
            fixed: Vec::new(),
            include_dirs: Vec::new(),
            fold_host: None,
            lowering: patina::Lowering::Fast,
        }
    }

    /// Names the generated module (and `OUT_DIR/<name>.wgsl`); the default is the file's stem.
    pub fn module(mut self, name: &str) -> Shader {
        self.module = Some(name.into());
        self
    }

    /// Picks the surface shader called `name` (the default is the file's first).
    pub fn surface(mut self, name: &str) -> Shader {
        self.surface = Some(name.into());
        self
    }

    /// Binds a light ([`patina::Light`]); lights are numbered in the order they are added.
    pub fn light(mut self, light: Light) -> Shader {
        self.lights.push(light);
        self
    }

    /// Binds a displacement shader.
    pub fn displacement(mut self, shader: Light) -> Shader {
        self.displacement = Some(shader);
        self
    }

    /// Compiles parameter `name` in as `value` ([`patina::Compiler::fix`]): it then has no field.
    pub fn fix(mut self, name: &str, value: impl Into<Value>) -> Shader {
        self.fixed.push((name.into(), value.into()));
        self
    }

    /// Adds a directory that `#include` searches (after the file's own directory and before
    /// the [`Shaders`]' directories).
    pub fn include_dir(mut self, dir: impl Into<PathBuf>) -> Shader {
        self.include_dirs.push(dir.into());
        self
    }

    /// Folds the host part into the WGSL ([`patina::Compiler::fold_host`]), overriding
    /// [`Shaders::fold_host`] for this shader.
    pub fn fold_host(mut self, fold: bool) -> Shader {
        self.fold_host = Some(fold);
        self
    }

    /// How the WGSL writes the built-ins ([`patina::Compiler::lowering`]; the default is
    /// [`patina::Lowering::Fast`], WGSL's own built-ins).
    pub fn lowering(mut self, lowering: patina::Lowering) -> Shader {
        self.lowering = lowering;
        self
    }

    fn module_name(&self) -> String {
        let name = match &self.module {
            Some(m) => m.clone(),
            None => self.path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
        };
        codegen::ident(&name).trim_start_matches("r#").to_string()
    }

    fn compiler(&self, shared: &Shaders) -> patina::Compiler {
        let mut c = patina::Compiler::new()
            .fold_host(self.fold_host.unwrap_or(shared.fold_host))
            .lowering(self.lowering);
        for dir in self.include_dirs.iter().chain(&shared.include_dirs) {
            c = c.include_dir(dir);
        }
        if let Some(s) = &self.surface {
            c = c.shader(s);
        }
        for l in &self.lights {
            c = c.light(l.clone());
        }
        if let Some(d) = &self.displacement {
            c = c.displacement(d.clone());
        }
        for (name, value) in &self.fixed {
            c = c.fix(name, value.clone());
        }
        c
    }
}

/// What [`Shaders::build`] wrote.
#[derive(Debug)]
#[non_exhaustive]
pub struct Built {
    /// The generated Rust file (`OUT_DIR/patina_shaders.rs`).
    pub rust: PathBuf,
    /// Each shader, in the order given.
    pub shaders: Vec<BuiltShader>,
}

/// One compiled shader and the files written for it.
#[derive(Debug)]
#[non_exhaustive]
pub struct BuiltShader {
    /// Its module in the generated Rust file.
    pub module: String,
    /// `OUT_DIR/<module>.wgsl`.
    pub wgsl: PathBuf,
    /// `OUT_DIR/<module>.json`, the interface.
    pub json: PathBuf,
    /// The compiled program (its `files` are what `cargo:rerun-if-changed` named).
    pub compiled: Compiled,
}

/// Why the shaders could not be built. `Debug` prints the same text as `Display` (the
/// diagnostics as the compiler renders them), so `build().unwrap()` and `fn main() -> Result<..>`
/// both fail the build with a readable message.
#[non_exhaustive]
pub enum Error {
    /// No output directory: `OUT_DIR` is unset (not in a build script) and none was given.
    NoOutDir,
    /// A shader has errors, or a file it needs could not be read.
    Compile {
        /// The shader's file.
        path: PathBuf,
        /// What the compiler said.
        error: CompileError,
    },
    /// Two shaders would generate the same module.
    DuplicateModule(String),
    /// The uniform block has a layout the generator cannot express (a bug: please report it).
    Layout {
        /// The shader's file.
        path: PathBuf,
        /// What does not fit.
        message: String,
    },
    /// An output file could not be written.
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        error: io::Error,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NoOutDir => {
                write!(f, "patina-build: OUT_DIR is not set (run it from build.rs, or give Shaders::out_dir)")
            }
            Error::Compile { path, error } => {
                write!(f, "patina-build: cannot compile `{}`:\n{error}", path.display())
            }
            Error::DuplicateModule(m) => write!(f, "patina-build: two shaders generate module `{m}`"),
            Error::Layout { path, message } => {
                write!(f, "patina-build: cannot lay out the uniform block of `{}`: {message}", path.display())
            }
            Error::Io { path, error } => {
                write!(f, "patina-build: cannot write `{}`: {error}", path.display())
            }
        }
    }
}

impl fmt::Debug for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Compile { error, .. } => Some(error),
            Error::Io { error, .. } => Some(error),
            _ => None,
        }
    }
}

impl Shaders {
    /// No shaders yet; the host part kept (`fold_host(false)`), `bytemuck` derives on, and the
    /// output in `OUT_DIR`.
    pub fn new() -> Shaders {
        Shaders {
            shaders: Vec::new(),
            include_dirs: Vec::new(),
            fold_host: false,
            bytemuck: true,
            out_dir: None,
        }
    }

    /// Adds a shader.
    pub fn shader(mut self, shader: Shader) -> Shaders {
        self.shaders.push(shader);
        self
    }

    /// Adds a directory that every shader's `#include` searches.
    pub fn include_dir(mut self, dir: impl Into<PathBuf>) -> Shaders {
        self.include_dirs.push(dir.into());
        self
    }

    /// Folds the host part of every shader into its WGSL (unless the shader says otherwise):
    /// the generated struct then holds only values a program without Patina can fill.
    pub fn fold_host(mut self, fold: bool) -> Shaders {
        self.fold_host = fold;
        self
    }

    /// Whether the structs derive `bytemuck::Pod` and `Zeroable` and have `as_bytes` (the
    /// default; the crate then depends on `bytemuck` with its `derive` feature).
    pub fn bytemuck(mut self, derive: bool) -> Shaders {
        self.bytemuck = derive;
        self
    }

    /// Writes into `dir` instead of `OUT_DIR`.
    pub fn out_dir(mut self, dir: impl Into<PathBuf>) -> Shaders {
        self.out_dir = Some(dir.into());
        self
    }

    /// Compiles every shader and writes the WGSL, the interfaces and `patina_shaders.rs`,
    /// printing cargo's `rerun-if-changed` and `warning` lines on standard output. Call it from
    /// `build.rs` and `unwrap()` it (or return it with `?`): an error fails the build with the
    /// diagnostics.
    pub fn build(&self) -> Result<Built, Error> {
        self.build_to(&mut io::stdout().lock())
    }

    /// [`Shaders::build`], printing cargo's lines to `cargo` instead of standard output.
    pub fn build_to(&self, cargo: &mut dyn Write) -> Result<Built, Error> {
        let out_dir = match &self.out_dir {
            Some(d) => d.clone(),
            None => std::env::var_os("OUT_DIR").map(PathBuf::from).ok_or(Error::NoOutDir)?,
        };
        let out_dir = std::path::absolute(&out_dir).unwrap_or(out_dir);
        std::fs::create_dir_all(&out_dir).map_err(|error| Error::Io { path: out_dir.clone(), error })?;
        let options = codegen::Options { bytemuck: self.bytemuck };
        let mut rust = String::from(codegen::PRELUDE);
        let mut built = Vec::new();
        let mut printed = std::collections::HashSet::new();
        let mut line = |text: String| {
            // Standard output going away is no reason to fail the build.
            if printed.insert(text.clone()) {
                let _ = writeln!(cargo, "{text}");
            }
        };
        for shader in &self.shaders {
            let module = shader.module_name();
            if built.iter().any(|b: &BuiltShader| b.module == module) {
                return Err(Error::DuplicateModule(module));
            }
            // Named before compiling, so that a shader with errors is rebuilt once it is fixed.
            line(format!("cargo:rerun-if-changed={}", shader.path.display()));
            let compiled = shader
                .compiler(self)
                .compile_file(&shader.path)
                .map_err(|error| Error::Compile { path: shader.path.clone(), error })?;
            for file in compiled.files.iter().filter(|f| **f != shader.path) {
                line(format!("cargo:rerun-if-changed={}", file.display()));
            }
            if !compiled.warnings.is_empty() {
                for text in compiled.warnings.to_string().lines().filter(|l| !l.trim().is_empty()) {
                    line(format!("cargo:warning={text}"));
                }
            }
            let wgsl = out_dir.join(format!("{module}.wgsl"));
            let json = out_dir.join(format!("{module}.json"));
            let interface = serde_json::to_string_pretty(&compiled.interface)
                .map_err(|e| Error::Io { path: json.clone(), error: io::Error::other(e) })?;
            write_if_changed(&wgsl, &compiled.wgsl)?;
            write_if_changed(&json, &interface)?;
            let code = codegen::module(&module, &shader.path, &compiled.interface, &wgsl, &json, &options)
                .map_err(|message| Error::Layout { path: shader.path.clone(), message })?;
            rust.push('\n');
            rust.push_str(&code);
            built.push(BuiltShader { module, wgsl, json, compiled });
        }
        let path = out_dir.join(RUST_FILE);
        write_if_changed(&path, &rust)?;
        Ok(Built { rust: path, shaders: built })
    }
}

/// Writes `text` to `path` unless it already holds it (so nothing that includes it rebuilds).
fn write_if_changed(path: &Path, text: &str) -> Result<(), Error> {
    if std::fs::read_to_string(path).is_ok_and(|old| old == text) {
        return Ok(());
    }
    std::fs::write(path, text).map_err(|error| Error::Io { path: path.to_path_buf(), error })
}
