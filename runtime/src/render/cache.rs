//! Compiled shaders by binding (DESIGN.md §4), so that preparing a scene again — with new values
//! of its animated parameters, from another camera, or the same shader on another object —
//! compiles nothing.
//!
//! A surface's key is everything its compiled program depends on: the shader file (by path and
//! text), which shader of it, the values binding compiles in (the parameters the scene sets and
//! does not animate, its strings), its displacement, its lights (each by file, text, name and
//! parameters) and whether it is specialized. The camera is not part of it: binding compiles in
//! no value that depends on the camera (a point, vector or normal the scene gives in world space
//! is seen by the shader in camera space, so it stays in the uniform block, see
//! `program::camera_dependent`), and a program found here is rebound to the new camera (its host
//! part runs again, `program::rebind_surface` and `program::rebind_light`). Such parameters are
//! still in the key by their world-space value, which the camera does not change. A shader's
//! include directories are in the key; the files it includes are checked when it is found: a
//! program is kept with the text of every file its shaders included (read when it was compiled),
//! and one whose included file has changed since is compiled again.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::PathBuf;

use super::program::{LightProgram, LoadedShader, SurfaceProgram};
use crate::scene::{ParamValue, ShaderRef};

/// The files a program's shaders included, each with a hash of the text they were compiled from.
type Included = Vec<(PathBuf, u64)>;

/// Compiled surfaces and lights, by key; see the module documentation.
#[derive(Default)]
pub struct Cache {
    surfaces: HashMap<String, (SurfaceProgram, Included)>,
    lights: HashMap<String, (LightProgram, Included)>,
    /// How many programs were found compiled.
    pub hits: usize,
    /// How many programs had to be compiled.
    pub misses: usize,
}

impl Cache {
    /// An empty cache.
    pub fn new() -> Cache {
        Cache::default()
    }

    pub(super) fn surface(&mut self, key: &str) -> Option<&SurfaceProgram> {
        found(&self.surfaces, key, &mut self.hits)
    }

    pub(super) fn keep_surface(&mut self, key: String, program: &SurfaceProgram) {
        self.misses += 1;
        let shaders = std::iter::once(&program.loaded)
            .chain(program.displacement.as_ref().map(|d| &d.loaded))
            .chain(program.atmosphere.as_ref().map(|a| &a.loaded));
        self.surfaces.insert(key, (program.clone(), included(shaders)));
    }

    pub(super) fn light(&mut self, key: &str) -> Option<&LightProgram> {
        found(&self.lights, key, &mut self.hits)
    }

    pub(super) fn keep_light(&mut self, key: String, program: &LightProgram) {
        self.misses += 1;
        self.lights.insert(key, (program.clone(), included(std::iter::once(&program.loaded))));
    }
}

/// The program kept under `key` whose included files are as it was compiled from, counting a hit
/// when there is one.
fn found<'a, T>(programs: &'a HashMap<String, (T, Included)>, key: &str, hits: &mut usize) -> Option<&'a T> {
    let program = programs.get(key).filter(|(_, files)| {
        files.iter().all(|(path, was)| {
            // Read as the compiler reads sources (a Latin-1 file included).
            patina_compiler::syntax::preprocess::read_source_file(path)
                .is_ok_and(|text| text.is_some_and(|text| hash(&text) == *was))
        })
    });
    *hits += usize::from(program.is_some());
    program.map(|(p, _)| p)
}

/// The files on disk that `shaders` included, with a hash of the text they were compiled from
/// (the standard library's modules, compiled into the program, never change under it).
fn included<'a>(shaders: impl Iterator<Item = &'a LoadedShader>) -> Included {
    let mut files = Included::new();
    for shader in shaders {
        for (_, file) in shader.sources.files() {
            let path = PathBuf::from(&file.name);
            if file.included_from.is_some() && path.is_file() && !files.iter().any(|(p, _)| *p == path) {
                files.push((path, hash(&file.text)));
            }
        }
    }
    files
}

/// The part of a key that names one shader and the values compiled into it: every parameter the
/// scene sets except `skip`ped (animated) ones.
pub(super) fn shader_key(shader: &ShaderRef, skip: &[String]) -> String {
    let text = std::fs::read_to_string(&shader.path).unwrap_or_default();
    let mut key =
        format!("{}#{}#{}|", shader.path.display(), shader.name.as_deref().unwrap_or(""), hash(&text));
    for dir in &shader.include_dirs {
        let _ = write!(key, "include {};", dir.display());
    }
    for (name, value) in &shader.params {
        // Strings (texture and space names) are compiled in even into a dynamic program.
        if skip.contains(name) && !matches!(value, ParamValue::String(_)) {
            continue;
        }
        let _ = match value {
            ParamValue::Number(x) => write!(key, "{name}={x:?};"),
            ParamValue::Numbers(v) => write!(key, "{name}={v:?};"),
            ParamValue::String(s) => write!(key, "{name}={s:?};"),
            ParamValue::Bool(b) => write!(key, "{name}={b};"),
        };
    }
    key
}

/// The key of a light: the shader with all its values.
pub(super) fn light_key(shader: &ShaderRef, specialize: bool) -> String {
    format!("{}|{specialize}", shader_key(shader, &[]))
}

/// The key of a surface: see the module documentation.
pub(super) fn surface_key(
    surface: &ShaderRef,
    displacement: Option<&ShaderRef>,
    light_keys: &[String],
    options: super::Options,
) -> String {
    let specialize = options.specialize;
    let skip = if specialize { surface.animate.clone() } else { surface.params.keys().cloned().collect() };
    let mut key = shader_key(surface, &skip);
    if let Some(d) = displacement {
        let _ = write!(key, "|displacement {}", shader_key(d, &[]));
    }
    for l in light_keys {
        let _ = write!(key, "|light {l}");
    }
    let _ = write!(key, "|{specialize}|{}", options.lowering);
    key
}

/// `key` (a surface's) with the atmosphere bound after it, if any.
pub(super) fn with_atmosphere(mut key: String, atmosphere: Option<&ShaderRef>) -> String {
    if let Some(a) = atmosphere {
        let _ = write!(key, "|atmosphere {}", shader_key(a, &[]));
    }
    key
}

/// FNV-1a: a short stand-in for a file's text in a key.
fn hash(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}
