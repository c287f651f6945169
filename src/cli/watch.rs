//! `patina watch`: renders a scene as `patina render` does, then again whenever the scene, a
//! shader it uses (or a file that shader includes), a mesh or a texture changes on disk, printing
//! each outcome as one block. A render that fails leaves the last good image where it was.

use std::num::NonZeroU32;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use patina::FileWatcher;
use patina_runtime::gpu::Gpu;
use patina_runtime::render::{self, Backend};

use super::live::{LiveScene, Reporter, directory, failure};
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

pub fn run(args: WatchArgs) -> Result<ExitCode, String> {
    let mut watcher = FileWatcher::new().map_err(|e| e.to_string())?;
    // Watch the scene before the first render, so that an edit made during it is not missed.
    watcher.set([args.scene.clone()], []).map_err(|e| e.to_string())?;
    let gpu = match args.backend {
        BackendChoice::Cpu => None,
        BackendChoice::Gpu => open_gpu(),
    };
    let options = render::Options { specialize: !args.dynamic, lowering: args.lowering.into() };
    let mut session = Session {
        live: LiveScene::new(args.scene.clone(), args.include.clone(), options),
        args,
        backend: if gpu.is_some() { Backend::Gpu } else { Backend::Cpu },
        gpu,
        reporter: Reporter::default(),
        wrote: false,
    };
    let mut renders = 0u32;
    let mut changed = Vec::new();
    loop {
        let reported = session.render_and_report(&changed);
        renders += u32::from(reported);
        let (files, dirs) = session.live.to_watch(session.reporter.failing());
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
        session.live.invalidate(&changed);
    }
}

/// What stays from one render to the next.
struct Session {
    args: WatchArgs,
    live: LiveScene,
    backend: Backend,
    gpu: Option<Gpu>,
    reporter: Reporter,
    /// Whether a render has written the image.
    wrote: bool,
}

impl Session {
    /// Renders the scene and prints the outcome as one block; whether it was news (see
    /// [`Reporter::report`]).
    fn render_and_report(&mut self, changed: &[PathBuf]) -> bool {
        let started = Instant::now();
        let outcome = self.render();
        let kept = self.wrote.then(|| format!("kept the last good image, {}", self.args.output.display()));
        self.reporter.report(changed, outcome, kept.as_deref(), started)
    }

    /// Loads, prepares and renders the scene and writes the image; a summary line, or why not
    /// (rendered diagnostics for a shader's errors).
    fn render(&mut self) -> Result<String, String> {
        let scene = self.live.load()?;
        let started = Instant::now();
        let (prepared, compiled) = self.live.prepare(&scene)?;
        let compile = started.elapsed();
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
