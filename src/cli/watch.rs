//! `patina watch`: renders a scene as `patina render` does, then again whenever the scene, a
//! shader it uses (or a file that shader includes), a mesh or a texture changes on disk, printing
//! each outcome as one block. A render that fails leaves the last good image where it was.

use std::collections::BTreeSet;
use std::io::{IsTerminal, Write as _};
use std::num::NonZeroU32;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use patina::FileWatcher;
use patina_runtime::gpu::Gpu;
use patina_runtime::render::{self, Backend, Cache, Prepared, RenderError};
use patina_runtime::scene::{MeshSource, Scene};

use super::progress::{RenderBar, with_bars};
use super::render::open_gpu;
use super::{BackendChoice, LoweringChoice};

/// Arguments of `patina watch`.
#[derive(clap::Args, Debug)]
pub struct WatchArgs {
    /// The scene file (TOML).
    scene: PathBuf,
    /// The PNG to write (replaced only by a render that succeeds).
    #[arg(short, long, value_name = "PNG", default_value = "out.png")]
    output: PathBuf,
    /// The renderer.
    #[arg(long, value_enum, default_value_t = BackendChoice::Gpu)]
    backend: BackendChoice,
    /// Compile every parameter dynamic (as uniforms) instead of binding the scene's values.
    #[arg(long)]
    dynamic: bool,
    /// How the GPU module writes the built-ins: `fast` (WGSL's own) or `exact` (the CPU
    /// reference's bits).
    #[arg(long, value_enum, default_value_t = LoweringChoice::Fast)]
    lowering: LoweringChoice,
    /// Stop after N renders, failed ones included (for scripts and tests); without it, watch until
    /// interrupted.
    #[arg(long, value_name = "N")]
    max_renders: Option<NonZeroU32>,
    /// A directory to search for the shaders' `#include` files (after each shader's own folder
    /// and the scene's `include` list; repeat for more).
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
}

/// How long one wait for changes lasts before it is simply begun again: no limit is intended,
/// this only keeps the clock arithmetic finite.
const WAIT: Duration = Duration::from_secs(3600);

/// The cache is emptied when it holds more programs than this (or than twice the scene's), so
/// that a long session of edits, each leaving its old programs behind, does not grow without end.
const CACHE_PROGRAMS: usize = 32;

pub fn run(args: WatchArgs) -> Result<ExitCode, String> {
    let mut watcher = FileWatcher::new().map_err(|e| e.to_string())?;
    // Watch the scene before the first render, so that an edit made during it is not missed.
    watcher.set([args.scene.clone()], []).map_err(|e| e.to_string())?;
    let gpu = match args.backend {
        BackendChoice::Cpu => None,
        BackendChoice::Gpu => open_gpu(),
    };
    let mut session = Session {
        args,
        backend: if gpu.is_some() { Backend::Gpu } else { Backend::Cpu },
        gpu,
        cache: Cache::new(),
        inputs: Inputs::default(),
        last_failure: None,
        wrote: false,
    };
    let mut renders = 0u32;
    let mut changed = Vec::new();
    loop {
        let reported = session.render_and_report(&changed);
        renders += u32::from(reported);
        let (files, dirs) = session.to_watch();
        watcher.set(files, dirs).map_err(|e| e.to_string())?;
        if session.args.max_renders.is_some_and(|max| renders >= max.get()) {
            return Ok(ExitCode::SUCCESS);
        }
        if reported {
            eprintln!("waiting for changes (Ctrl-C to stop)");
        }
        changed = loop {
            if let Some(changed) = watcher.wait(WAIT).map_err(|e| e.to_string())? {
                break changed;
            }
        };
        session.invalidate(&changed);
    }
}

/// What stays from one render to the next.
struct Session {
    args: WatchArgs,
    backend: Backend,
    gpu: Option<Gpu>,
    cache: Cache,
    /// The files the latest render (or, when it failed early, the one before) read.
    inputs: Inputs,
    /// The latest failure's message, while the scene fails.
    last_failure: Option<String>,
    /// Whether a render has written the image.
    wrote: bool,
}

/// The files a render read, as the scene and the compiler name them.
#[derive(Default)]
struct Inputs {
    scene: Option<PathBuf>,
    /// The shader files the scene names.
    shaders: Vec<PathBuf>,
    /// The files those shaders include.
    includes: Vec<PathBuf>,
    /// OBJ meshes and textures.
    data: Vec<PathBuf>,
}

impl Session {
    /// Renders the scene and prints the outcome as one block; whether it was news (a failure
    /// with the same message as the one before is not: editors' backup and swap files in a
    /// watched directory would repeat it at every keystroke).
    fn render_and_report(&mut self, changed: &[PathBuf]) -> bool {
        let started = Instant::now();
        let outcome = self.render();
        let message = match &outcome {
            Ok(_) => None,
            Err(message) if self.last_failure.as_ref() == Some(message) => return false,
            Err(message) => Some(message.clone()),
        };
        let mut block = String::new();
        if !changed.is_empty() {
            let names: Vec<String> = changed.iter().map(|p| p.display().to_string()).collect();
            block.push_str(&format!("changed: {}\n", names.join(", ")));
        }
        match outcome {
            Ok(summary) => block.push_str(&summary),
            Err(message) => {
                block.push_str(&message);
                block.push('\n');
                if self.wrote {
                    block.push_str(&format!(
                        "note: kept the last good image, {}\n",
                        self.args.output.display()
                    ));
                }
            }
        }
        block.push_str(&format!("({:.1} ms in all)\n", started.elapsed().as_secs_f64() * 1e3));
        let mut err = std::io::stderr().lock();
        if err.is_terminal() {
            // In place: each outcome replaces the one before on the screen.
            let _ = write!(err, "\x1b[2J\x1b[H");
        }
        let _ = write!(err, "{block}");
        self.last_failure = message;
        true
    }

    /// Loads, prepares and renders the scene and writes the image; a summary line, or why not
    /// (rendered diagnostics for a shader's errors).
    fn render(&mut self) -> Result<String, String> {
        let mut scene = Scene::load(&self.args.scene).map_err(|e| format!("error: {e}"))?;
        scene.add_include_dirs(&self.args.include);
        self.inputs.scene = Some(scene.file.clone());
        self.inputs.shaders = scene
            .lights
            .iter()
            .map(|l| &l.shader)
            .chain(
                scene
                    .objects
                    .iter()
                    .flat_map(|o| std::iter::once(&o.surface).chain(&o.displacement).chain(&o.atmosphere)),
            )
            .chain(&scene.imager)
            .map(|s| s.path.clone())
            .collect();
        let started = Instant::now();
        let options = render::Options { specialize: !self.args.dynamic, lowering: self.args.lowering.into() };
        let compiled_before = self.cache.misses;
        let prepared = render::prepare_cached(&scene, options, &mut self.cache).map_err(failure)?;
        let compile = started.elapsed();
        let compiled = self.cache.misses - compiled_before;
        self.inputs.includes = includes(&prepared);
        self.inputs.data = data_files(&scene, &prepared);
        let started = Instant::now();
        let image = with_bars(|bars| {
            let bar = RenderBar::new(bars, "rendering");
            render::render_with_progress(&prepared, self.backend, self.gpu.as_ref(), &bar)
        })
        .map_err(failure)?;
        let drawn = started.elapsed();
        write_atomically(&image, &self.args.output)?;
        self.wrote = true;
        let device = match &self.gpu {
            Some(g) => g.adapter_description(),
            None => "CPU reference".to_string(),
        };
        let programs = prepared.lights.len() + prepared.objects.len();
        Ok(format!(
            "wrote {} ({}x{}) on {device}: compile {:.1} ms ({compiled} of {programs} programs compiled, the rest \
             unchanged), render {:.1} ms\n",
            self.args.output.display(),
            image.width,
            image.height,
            compile.as_secs_f64() * 1e3,
            drawn.as_secs_f64() * 1e3,
        ))
    }

    /// The files to watch, and the directories to watch every file of: while the scene fails,
    /// the fix may be in a file no render has read yet (an include just added), so every file
    /// beside the ones known counts.
    fn to_watch(&self) -> (Vec<PathBuf>, Vec<PathBuf>) {
        let inputs = &self.inputs;
        let files: Vec<PathBuf> = std::iter::once(&self.args.scene)
            .chain(&inputs.shaders)
            .chain(&inputs.includes)
            .chain(&inputs.data)
            .cloned()
            .collect();
        let dirs = match self.last_failure {
            Some(_) => files.iter().map(|f| directory(f).to_path_buf()).collect(),
            None => Vec::new(),
        };
        (files, dirs)
    }

    /// Forgets compiled programs that `changed` may have made stale. A program's cache key holds
    /// its shader file's text and the scene's values, so edits to the scene, a shader file, a
    /// mesh or a texture need nothing (an unchanged shader is not compiled again); but it does not
    /// hold the files a shader includes, so a change to any other file (an include, or a file we
    /// cannot name for sure, such as a deleted one) empties it.
    fn invalidate(&mut self, changed: &[PathBuf]) {
        let canonical = |paths: &[PathBuf]| -> BTreeSet<PathBuf> {
            paths.iter().filter_map(|p| std::fs::canonicalize(p).ok()).collect()
        };
        let includes = canonical(&self.inputs.includes);
        // Meshes and textures are read anew by every prepare, and no program depends on them.
        let mut keyed = canonical(&self.inputs.shaders);
        keyed.extend(canonical(std::slice::from_ref(&self.args.scene)));
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

/// A render error as printed: a shader's diagnostics as they are, anything else as one line.
fn failure(e: RenderError) -> String {
    match e {
        RenderError::Shader(diagnostics) => diagnostics.trim_end().to_string(),
        other => format!("error: {other}"),
    }
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

/// Writes the image beside `output` and renames it into place, so that a viewer never reads a
/// half-written file and a failed write leaves the last good image.
fn write_atomically(image: &patina_runtime::image::Image, output: &Path) -> Result<(), String> {
    let name = output.file_name().map_or_else(|| "out.png".into(), |n| n.to_string_lossy().into_owned());
    let partial = directory(output).join(format!(".{name}.partial"));
    image.write_png(&partial).map_err(|e| format!("error: {e}"))?;
    std::fs::rename(&partial, output).map_err(|e| {
        let _ = std::fs::remove_file(&partial);
        format!("error: cannot write {}: {e}", output.display())
    })
}

/// The directory a file is in (`.` for a bare file name).
fn directory(file: &Path) -> &Path {
    match file.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    }
}
