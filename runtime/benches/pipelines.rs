//! Code size and driver time per example scene (issue 21): for each scene of examples/scenes, the
//! size of its objects' GPU modules (naga expressions, WGSL bytes) and the time the driver takes to
//! create their render pipelines, with Mesa's shader cache disabled, so that every run pays the
//! whole compile as a user's first render after an edit does.
//!
//! Pipeline creation is the first render on a fresh device less a second render of the same
//! scene on it (which finds its pipelines kept), both at 4 × 4 pixels so that shading costs
//! nothing. Each scene is measured in both lowerings (exact, then fast). The table goes to stdout
//! as Markdown; docs/performance.md keeps the last one.
//!
//! Run with `cargo bench -p patina-runtime --bench pipelines` (optionally followed by scene names,
//! `-- noise_panel hypertexture`, to measure only those).

use std::path::Path;
use std::time::Instant;

use patina_runtime::gpu::Gpu;
use patina_runtime::render::{self, Backend, Lowering, Prepared};
use patina_runtime::scene::Scene;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// One scene's measurements.
struct Row {
    name: String,
    modules: usize,
    expressions: usize,
    wgsl_bytes: usize,
    pipeline_ms: f64,
}

/// Every expression of a module: its entry points', its functions' and its global ones.
fn expressions(module: &naga::Module) -> usize {
    module.entry_points.iter().map(|e| e.function.expressions.len()).sum::<usize>()
        + module.functions.iter().map(|(_, f)| f.expressions.len()).sum::<usize>()
        + module.global_expressions.len()
}

fn measure(path: &Path, lowering: Lowering) -> Result<Row, String> {
    let scene = Scene::load(path).map_err(|e| e.to_string())?;
    let options = render::Options { lowering, ..render::Options::default() };
    let mut prepared: Prepared = render::prepare_with(&scene, options).map_err(|e| e.to_string())?;
    prepared.width = 4;
    prepared.height = 4;
    prepared.supersample = 1;
    let (mut expression_count, mut wgsl_bytes) = (0, 0);
    for object in &prepared.objects {
        expression_count += expressions(&object.surface.gpu.module);
        wgsl_bytes += object.surface.gpu.wgsl().map_err(|e| e.message.clone())?.len();
    }
    let gpu = Gpu::new().map_err(|e| e.to_string())?;
    let time = |gpu: &Gpu| -> Result<f64, String> {
        let start = Instant::now();
        render::render(&prepared, Backend::Gpu, Some(gpu)).map_err(|e| e.to_string())?;
        Ok(start.elapsed().as_secs_f64() * 1e3)
    };
    let first = time(&gpu)?;
    let again = time(&gpu)?;
    Ok(Row {
        name: path.file_stem().unwrap_or_default().to_string_lossy().into_owned(),
        modules: prepared.objects.len(),
        expressions: expression_count,
        wgsl_bytes,
        pipeline_ms: first - again,
    })
}

fn main() {
    // Before any device exists: Mesa reads it when the device is made.
    // SAFETY: no other thread runs yet.
    unsafe { std::env::set_var("MESA_SHADER_CACHE_DISABLE", "true") };
    let only: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/scenes");
    let mut scenes: Vec<_> = std::fs::read_dir(&dir)
        .expect("examples/scenes")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| only.is_empty() || only.iter().any(|o| p.file_stem().is_some_and(|s| s == o.as_str())))
        .collect();
    scenes.sort();
    match Gpu::new() {
        Ok(gpu) => println!("\nOn {}, Mesa's shader cache disabled:\n", gpu.adapter_description()),
        Err(_) => {
            println!("no GPU adapter: nothing to measure");
            return;
        }
    }
    println!(
        "| scene | modules | naga expressions (exact / fast) | WGSL bytes (exact / fast) | pipeline creation ms (exact / fast) |"
    );
    println!("|---|---|---|---|---|");
    for path in &scenes {
        match (measure(path, Lowering::Exact), measure(path, Lowering::Fast)) {
            (Ok(e), Ok(f)) => println!(
                "| {} | {} | {} / {} | {} / {} | {:.0} / {:.0} |",
                e.name,
                e.modules,
                e.expressions,
                f.expressions,
                e.wgsl_bytes,
                f.wgsl_bytes,
                e.pipeline_ms,
                f.pipeline_ms
            ),
            (Err(e), _) | (_, Err(e)) => println!("| {} | error: {e} | | | |", path.display()),
        }
    }
}
