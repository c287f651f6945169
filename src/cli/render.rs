//! `patina render`: a scene to a PNG, on the GPU or by the CPU reference.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use patina_runtime::gpu::{self, Gpu};
use patina_runtime::render::{self, Backend};
use patina_runtime::scene::Scene;

use super::progress::{RenderBar, with_bars};
use super::{BackendChoice, RenderArgs};

pub fn run(args: RenderArgs) -> Result<ExitCode, String> {
    let mut scene = Scene::load(&args.scene).map_err(|e| e.to_string())?;
    scene.add_include_dirs(&args.include);
    let started = Instant::now();
    let options = render::Options { specialize: !args.dynamic, lowering: args.lowering.into() };
    let prepared = render::prepare_with(&scene, options).map_err(|e| e.to_string())?;
    let compiled = started.elapsed();
    let (backend, gpu) = match args.backend {
        BackendChoice::Cpu => (Backend::Cpu, None),
        BackendChoice::Gpu => match open_gpu() {
            Some(gpu) => (Backend::Gpu, Some(gpu)),
            None => (Backend::Cpu, None),
        },
    };
    let started = Instant::now();
    let image = with_bars(|bars| {
        let bar = RenderBar::new(bars, "rendering");
        render::render_with_progress(&prepared, backend, gpu.as_ref(), &bar)
    })
    .map_err(|e| e.to_string())?;
    let drawn = started.elapsed();
    image.write_png(&args.output).map_err(|e| e.to_string())?;
    let device = match &gpu {
        Some(g) => g.adapter_description(),
        None => "CPU reference".to_string(),
    };
    eprintln!(
        "wrote {} ({}x{}) on {device}: compile {:.1} ms, render {:.1} ms",
        Path::new(&args.output).display(),
        image.width,
        image.height,
        compiled.as_secs_f64() * 1e3,
        drawn.as_secs_f64() * 1e3
    );
    Ok(ExitCode::SUCCESS)
}

/// The GPU, or `None` (saying why on stderr) when there is none or `PATINA_GPU=off`: the caller
/// falls back to the CPU reference.
pub fn open_gpu() -> Option<Gpu> {
    open_gpu_or("rendering on the CPU")
}

/// The GPU, or `None` after one `note:` line saying why and what happens instead (`fallback`,
/// e.g. "rendering on the CPU") when there is none or `PATINA_GPU=off`.
pub fn open_gpu_or(fallback: &str) -> Option<Gpu> {
    if !gpu::adapter_required() {
        eprintln!("note: {}=off: {fallback}", gpu::GPU_ENV);
        return None;
    }
    match Gpu::new() {
        Ok(gpu) => Some(gpu),
        Err(e) => {
            eprintln!("note: no GPU ({e}); {fallback}");
            None
        }
    }
}
