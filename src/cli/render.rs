//! `patina render`: a scene to a PNG, on the GPU or by the CPU reference.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use patina_runtime::gpu::{self, Gpu};
use patina_runtime::render::{self, Backend};
use patina_runtime::scene::Scene;

use super::{BackendChoice, RenderArgs};

pub fn run(args: RenderArgs) -> Result<ExitCode, String> {
    let scene = Scene::load(&args.scene).map_err(|e| e.to_string())?;
    let started = Instant::now();
    let prepared = render::prepare(&scene).map_err(|e| e.to_string())?;
    let compiled = started.elapsed();
    let (backend, gpu) = match args.backend {
        BackendChoice::Cpu => (Backend::Cpu, None),
        BackendChoice::Gpu if !gpu::adapter_required() => {
            eprintln!("note: {}=off: rendering on the CPU", gpu::GPU_ENV);
            (Backend::Cpu, None)
        }
        BackendChoice::Gpu => match Gpu::new() {
            Ok(gpu) => (Backend::Gpu, Some(gpu)),
            Err(e) => {
                eprintln!("note: no GPU ({e}); rendering on the CPU");
                (Backend::Cpu, None)
            }
        },
    };
    let started = Instant::now();
    let image = render::render(&prepared, backend, gpu.as_ref()).map_err(|e| e.to_string())?;
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
