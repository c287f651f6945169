//! A scene kept prepared across edits, for the commands that re-render on change (`patina watch`,
//! `patina view`): loading it, knowing which files a render read (so that they are watched),
//! forgetting compiled programs an edit made stale, and printing each outcome as one block.

use std::collections::BTreeSet;
use std::io::{IsTerminal, Write as _};
use std::path::{Path, PathBuf};
use std::time::Instant;

use patina_runtime::render::{self, Cache, Prepared, RenderError};
use patina_runtime::scene::{MeshSource, Scene};

/// The cache is emptied when it holds more programs than this (or than twice the scene's), so
/// that a long session of edits, each leaving its old programs behind, does not grow without end.
const CACHE_PROGRAMS: usize = 32;

/// A scene file, loaded and prepared again after each change, with the compiled programs and the
/// list of files the latest render read.
pub struct LiveScene {
    path: PathBuf,
    include: Vec<PathBuf>,
    options: render::Options,
    cache: Cache,
    /// The files the latest render (or, when it failed early, the one before) read.
    inputs: Inputs,
}

/// The files a render read, as the scene and the compiler name them.
#[derive(Default)]
struct Inputs {
    /// The shader files the scene names.
    shaders: Vec<PathBuf>,
    /// The files those shaders include.
    includes: Vec<PathBuf>,
    /// OBJ meshes and textures.
    data: Vec<PathBuf>,
}

impl LiveScene {
    /// The scene at `path`, its shaders searching `include` for their `#include` files (after
    /// their own folders and the scene's list), compiled as `options` say.
    pub fn new(path: PathBuf, include: Vec<PathBuf>, options: render::Options) -> LiveScene {
        LiveScene { path, include, options, cache: Cache::new(), inputs: Inputs::default() }
    }

    /// Reads the scene file as it is now, noting the shader files it names.
    pub fn load(&mut self) -> Result<Scene, String> {
        let mut scene = Scene::load(&self.path).map_err(|e| format!("error: {e}"))?;
        scene.add_include_dirs(&self.include);
        self.inputs.shaders = shader_files(&scene);
        Ok(scene)
    }

    /// Compiles `scene` (a scene [`load`](LiveScene::load) gave, perhaps with another camera or
    /// size), taking unchanged programs from the cache; the prepared scene and how many programs
    /// were compiled anew, or the diagnostics as printed.
    pub fn prepare(&mut self, scene: &Scene) -> Result<(Prepared, usize), String> {
        let compiled_before = self.cache.misses;
        let prepared = render::prepare_cached(scene, self.options, &mut self.cache).map_err(failure)?;
        self.inputs.includes = includes(&prepared);
        self.inputs.data = data_files(scene, &prepared);
        Ok((prepared, self.cache.misses - compiled_before))
    }

    /// The files to watch, and the directories to watch every file of: while the scene fails
    /// (`failing`), the fix may be in a file no render has read yet (an include just added), so
    /// every file beside the ones known counts.
    pub fn to_watch(&self, failing: bool) -> (Vec<PathBuf>, Vec<PathBuf>) {
        let inputs = &self.inputs;
        let files: Vec<PathBuf> = std::iter::once(&self.path)
            .chain(&inputs.shaders)
            .chain(&inputs.includes)
            .chain(&inputs.data)
            .cloned()
            .collect();
        let dirs = match failing {
            true => files.iter().map(|f| directory(f).to_path_buf()).collect(),
            false => Vec::new(),
        };
        (files, dirs)
    }

    /// Forgets compiled programs that `changed` may have made stale. A program's cache key holds
    /// its shader file's text and the scene's values, so edits to the scene, a shader file, a
    /// mesh or a texture need nothing (an unchanged shader is not compiled again); but it does not
    /// hold the files a shader includes, so a change to any other file (an include, or a file we
    /// cannot name for sure, such as a deleted one) empties it.
    pub fn invalidate(&mut self, changed: &[PathBuf]) {
        let canonical = |paths: &[PathBuf]| -> BTreeSet<PathBuf> {
            paths.iter().filter_map(|p| std::fs::canonicalize(p).ok()).collect()
        };
        let includes = canonical(&self.inputs.includes);
        // Meshes and textures are read anew by every prepare, and no program depends on them.
        let mut keyed = canonical(&self.inputs.shaders);
        keyed.extend(canonical(std::slice::from_ref(&self.path)));
        keyed.extend(canonical(&self.inputs.data));
        let safe = changed
            .iter()
            .all(|p| std::fs::canonicalize(p).is_ok_and(|p| keyed.contains(&p) && !includes.contains(&p)));
        let programs = 2 * self.inputs.shaders.len();
        if !safe || self.cache.misses > CACHE_PROGRAMS.max(programs) {
            self.cache = Cache::new();
        }
    }
}

/// Prints each outcome of a re-render as one block on stderr, replacing the one before on a
/// terminal, and keeps quiet about a failure that repeats the one before.
#[derive(Default)]
pub struct Reporter {
    /// The latest failure's message, while the scene fails.
    last_failure: Option<String>,
}

impl Reporter {
    /// Whether the latest outcome was a failure.
    pub fn failing(&self) -> bool {
        self.last_failure.is_some()
    }

    /// Prints `outcome` (a summary or why it failed, each ending in a newline or not) after the
    /// files that `changed`, and after a failure `kept` (e.g. "kept the last good image, out.png")
    /// as a note; `started` is when the render began. Whether anything was printed: a failure
    /// with the same message as the one before is not news (editors' backup and swap files in a
    /// watched directory would repeat it at every keystroke).
    pub fn report(
        &mut self,
        changed: &[PathBuf],
        outcome: Result<String, String>,
        kept: Option<&str>,
        started: Instant,
    ) -> bool {
        if let Err(message) = &outcome
            && self.last_failure.as_ref() == Some(message)
        {
            return false;
        }
        let mut block = String::new();
        if !changed.is_empty() {
            let names: Vec<String> = changed.iter().map(|p| p.display().to_string()).collect();
            block.push_str(&format!("changed: {}\n", names.join(", ")));
        }
        self.last_failure = match outcome {
            Ok(summary) => {
                block.push_str(summary.trim_end());
                block.push('\n');
                None
            }
            Err(message) => {
                block.push_str(message.trim_end());
                block.push('\n');
                if let Some(kept) = kept {
                    block.push_str(&format!("note: {kept}\n"));
                }
                Some(message)
            }
        };
        block.push_str(&format!("({:.1} ms in all)\n", started.elapsed().as_secs_f64() * 1e3));
        let mut err = std::io::stderr().lock();
        if err.is_terminal() {
            // In place: each outcome replaces the one before on the screen.
            let _ = write!(err, "\x1b[2J\x1b[H");
        }
        let _ = write!(err, "{block}");
        true
    }
}

/// A render error as printed: a shader's diagnostics as they are, anything else as one line.
pub fn failure(e: RenderError) -> String {
    match e {
        RenderError::Shader(diagnostics) => diagnostics.to_string(),
        other => format!("error: {other}"),
    }
}

/// The shader files a scene names, for its lights, objects and imager.
fn shader_files(scene: &Scene) -> Vec<PathBuf> {
    let objects = scene
        .objects
        .iter()
        .flat_map(|o| std::iter::once(&o.surface).chain(&o.displacement).chain(&o.atmosphere));
    scene
        .lights
        .iter()
        .map(|l| &l.shader)
        .chain(objects)
        .chain(&scene.imager)
        .map(|s| s.path.clone())
        .collect()
}

/// Every file on disk the prepared programs include (not the shader files themselves, which the
/// scene names; standard-library modules are not on disk).
fn includes(prepared: &Prepared) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let shaders = prepared.lights.iter().map(|l| &l.loaded).chain(prepared.objects.iter().flat_map(|o| {
        std::iter::once(&o.surface.loaded)
            .chain(o.surface.displacement.as_ref().map(|d| &d.loaded))
            .chain(o.surface.atmosphere.as_ref().map(|a| &a.loaded))
    }));
    let shaders = shaders.chain(prepared.imager.as_ref().map(|i| &i.loaded));
    for shader in shaders {
        for (_, file) in shader.sources.files() {
            let path = PathBuf::from(&file.name);
            if file.included_from.is_some() && path.is_file() && !found.contains(&path) {
                found.push(path);
            }
        }
    }
    found
}

/// The OBJ meshes and texture files the scene reads.
fn data_files(scene: &Scene, prepared: &Prepared) -> Vec<PathBuf> {
    let base = directory(&scene.file);
    let meshes = scene.objects.iter().filter_map(|o| match &o.mesh {
        MeshSource::Obj(path) => Some(path.clone()),
        _ => None,
    });
    let textures =
        prepared.objects.iter().flat_map(|o| &o.surface.gpu.interface.textures).map(|t| base.join(&t.name));
    meshes.chain(textures).filter(|p| p.is_file()).collect()
}

/// The directory a file is in (`.` for a bare file name).
pub fn directory(file: &Path) -> &Path {
    match file.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    }
}
