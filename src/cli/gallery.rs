//! `patina gallery`: a set of scenes rendered on the GPU and by the CPU reference, compared, with
//! each picture written as a PNG and, optionally, a Markdown page showing them with their timings.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use patina_runtime::gpu::Gpu;
use patina_runtime::image::{Comparison, Image, Thresholds, compare};
use patina_runtime::render::{self, Backend, Progress};
use patina_runtime::scene::Scene;

use super::GalleryArgs;
use super::progress::{RenderBar, steps, with_bars};
use super::render::open_gpu;

/// What one scene gave.
struct Entry {
    /// The scene file as named on the command line.
    path: PathBuf,
    /// The file stem: the picture's and the section's name.
    name: String,
    /// The scene's leading comment lines, as prose.
    caption: String,
    /// The measurements, or why the scene failed.
    result: Result<Measured, String>,
}

/// One render's picture and wall-clock time, or why it failed.
type Rendered = Result<(Image, Duration), String>;

/// Runs a render (the second argument) with a progress bar labelled by the first.
type WithBar<'a> = dyn Fn(&'static str, &dyn Fn(&dyn Progress) -> Rendered) -> Rendered + 'a;

/// One scene's renders.
struct Measured {
    width: u32,
    height: u32,
    compile: Duration,
    gpu: Option<Duration>,
    cpu: Duration,
    /// GPU against CPU, when there is a GPU.
    comparison: Option<Comparison>,
    /// The scene's thresholds for that comparison.
    thresholds: Thresholds,
    /// Why they are not OSL's, when they are not.
    reason: Option<String>,
}

pub fn run(args: GalleryArgs) -> Result<ExitCode, String> {
    std::fs::create_dir_all(&args.images)
        .map_err(|e| format!("{}: cannot create the directory: {e}", args.images.display()))?;
    let gpu = open_gpu();
    let renders_per_scene = if gpu.is_some() { 2 } else { 1 };
    let entries: Vec<Entry> = with_bars(|bars| {
        let sweep = steps(bars, (args.scenes.len() * renders_per_scene) as u64);
        args.scenes
            .iter()
            .map(|path| {
                let name = path.file_stem().map_or("scene".into(), |s| s.to_string_lossy().into_owned());
                let caption = caption(path);
                let result = measure(path, &name, &args, gpu.as_ref(), &|backend, render| {
                    sweep.set_message(format!("{name} ({backend})"));
                    let result = render(&RenderBar::new(bars, backend));
                    sweep.inc(1);
                    result
                });
                Entry { path: path.clone(), name, caption, result }
            })
            .collect()
    });
    let mut failed = false;
    for e in &entries {
        match &e.result {
            Ok(m) => {
                let agreement = match &m.comparison {
                    Some(c) if c.passes(&m.thresholds) => format!("agree (max {:.2e})", c.max_error),
                    Some(c) => {
                        failed = true;
                        format!(
                            "DIFFER (max {:.2e}, {} of {} pixels fail, {} with NaN or infinity)",
                            c.max_error, c.failing_pixels, c.pixels, c.nan_pixels
                        )
                    }
                    None => "CPU only".into(),
                };
                eprintln!(
                    "{}: compile {:.0} ms, GPU {}, CPU {:.0} ms: {agreement}",
                    e.name,
                    ms(m.compile),
                    m.gpu.map_or("-".into(), |d| format!("{:.0} ms", ms(d))),
                    ms(m.cpu)
                );
            }
            Err(message) => {
                failed = true;
                eprintln!("{}: {message}", e.name);
            }
        }
    }
    if let Some(markdown) = &args.markdown {
        let device = gpu.as_ref().map_or("no GPU".into(), Gpu::adapter_description);
        let page = page(&entries, &args, markdown, &device);
        std::fs::write(markdown, page).map_err(|e| format!("{}: cannot write: {e}", markdown.display()))?;
        eprintln!("wrote {}", markdown.display());
    }
    Ok(if failed { ExitCode::FAILURE } else { ExitCode::SUCCESS })
}

/// Renders one scene on both backends (the GPU's when there is one), writes its picture and
/// measures it. Each render runs inside `shown(backend, render)`, which gives it a progress bar.
fn measure(
    path: &Path,
    name: &str,
    args: &GalleryArgs,
    gpu: Option<&Gpu>,
    shown: &WithBar<'_>,
) -> Result<Measured, String> {
    let scene = Scene::load(path).map_err(|e| e.to_string())?;
    let started = Instant::now();
    let options = render::Options { lowering: args.lowering.into(), ..render::Options::default() };
    let prepared = render::prepare_with(&scene, options).map_err(|e| e.to_string())?;
    let compile = started.elapsed();
    let timed = |backend: Backend, label: &'static str| -> Rendered {
        shown(label, &|progress| {
            let started = Instant::now();
            let image = render::render_with_progress(&prepared, backend, gpu, progress);
            Ok((image.map_err(|e| e.to_string())?, started.elapsed()))
        })
    };
    let gpu_render = match gpu {
        Some(_) => Some(timed(Backend::Gpu, "GPU")?),
        None => None,
    };
    let (cpu_image, cpu) = timed(Backend::Cpu, "CPU")?;
    let comparison = match &gpu_render {
        Some((image, _)) => Some(compare(&cpu_image, image, &scene.thresholds()).map_err(|e| e.to_string())?),
        None => None,
    };
    let shown = gpu_render.as_ref().map_or(&cpu_image, |(image, _)| image);
    let png = args.images.join(format!("{name}.png"));
    shown.write_png(&png).map_err(|e| e.to_string())?;
    Ok(Measured {
        width: shown.width,
        height: shown.height,
        compile,
        gpu: gpu_render.map(|(_, d)| d),
        cpu,
        comparison,
        thresholds: scene.thresholds(),
        reason: scene.compare.as_ref().map(|c| c.reason.clone()),
    })
}

/// Milliseconds, for printing.
fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// The comment lines that open a scene file, joined into one paragraph ("" if it has none).
fn caption(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let lines: Vec<&str> = text
        .lines()
        .take_while(|l| l.trim_start().starts_with('#'))
        .map(|l| l.trim_start().trim_start_matches('#').trim())
        .collect();
    lines.join(" ").trim().to_string()
}

/// `path` relative to directory `base` when it lies under it (both as given), else as given.
fn relative(path: &Path, base: &Path) -> String {
    let shown = path.strip_prefix(base).unwrap_or(path);
    shown.display().to_string()
}

/// The Markdown page: how it was made, a table of every scene, then each scene's picture,
/// caption and command.
fn page(entries: &[Entry], args: &GalleryArgs, markdown: &Path, device: &str) -> String {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let base = markdown.parent().unwrap_or(Path::new(""));
    let scenes: Vec<String> = args.scenes.iter().map(|p| p.display().to_string()).collect();
    let mut out = String::new();
    let _ = writeln!(out, "# Gallery\n");
    let _ = writeln!(
        out,
        "The scenes of the seed documents, each rendered by wgpu on the GPU and by the CPU reference \
         renderer and compared pixel by pixel. This page is generated: to remake it (the pictures \
         too), run\n\n```sh\ncargo run --release -- gallery {} --images {} --markdown {}\n```\n",
        scenes.join(" "),
        args.images.display(),
        markdown.display()
    );
    let _ = writeln!(
        out,
        "Times are the wall-clock time of one render at the size shown, on this page's last run \
         (a machine with {threads} CPU threads): **GPU** is wgpu on {device} (pipeline creation, \
         drawing and reading the image back; on lavapipe, compiling a large shader's pipeline \
         dominates, and Mesa's shader cache makes a second run faster than the first), **CPU** \
         is the CPU reference (the interpreter's vertex and fragment stages and the rasterizer), and \
         **compile** is compiling the scene's shaders for both backends. **max |Δ|** is the largest \
         difference of any channel of any pixel between the two images, **failing** the share of \
         pixels that differ by more than the fail threshold, **NaN** the pixels with a NaN or an \
         infinity in either image (left out of the other figures), and **agree** whether the two meet the \
         scene's thresholds: OSL's (fail 0.004, hard fail 0.01, at most 2% failing) unless the \
         scene's `[compare]` table says otherwise, with its reason under the picture. The tests \
         (`runtime/tests/gallery/`) render each scene smaller and check its own properties too.\n"
    );
    let _ = writeln!(out, "| scene | size | compile | GPU | CPU | max \\|Δ\\| | failing | NaN | agree |");
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|---|");
    for e in entries {
        match &e.result {
            Ok(m) => {
                let (max, failing, nan, agree) = match &m.comparison {
                    Some(c) => (
                        format!("{:.1e}", c.max_error),
                        format!("{:.2}%", 100.0 * c.failing_pixels as f64 / c.pixels.max(1) as f64),
                        c.nan_pixels.to_string(),
                        match (c.passes(&m.thresholds), &m.reason) {
                            (true, None) => "yes",
                            (true, Some(_)) => "yes (own thresholds)",
                            (false, _) => "**no**",
                        },
                    ),
                    None => ("-".into(), "-".into(), "-".into(), "-"),
                };
                let _ = writeln!(
                    out,
                    "| [{name}](#{name}) | {}×{} | {:.0} ms | {} | {:.0} ms | {max} | {failing} | {nan} | {agree} |",
                    m.width,
                    m.height,
                    ms(m.compile),
                    m.gpu.map_or("-".into(), |d| format!("{:.0} ms", ms(d))),
                    ms(m.cpu),
                    name = e.name,
                );
            }
            Err(message) => {
                let _ = writeln!(
                    out,
                    "| {} | failed: {} | | | | | | | |",
                    e.name,
                    message.lines().next().unwrap_or("")
                );
            }
        }
    }
    for e in entries {
        let _ = writeln!(out, "\n## {}\n", e.name);
        if !e.caption.is_empty() {
            let _ = writeln!(out, "{}\n", e.caption);
        }
        if let Ok(m) = &e.result {
            let png = args.images.join(format!("{}.png", e.name));
            let _ = writeln!(out, "![{}]({})\n", e.name, relative(&png, base));
            if let Some(reason) = &m.reason {
                let t = m.thresholds;
                let _ = writeln!(
                    out,
                    "Compared with hard fail {}, fail {} and at most {}% failing: {reason}\n",
                    t.hard_fail,
                    t.fail,
                    100.0 * t.max_failing_fraction
                );
            }
        }
        let _ =
            writeln!(out, "```sh\ncargo run --release -- render {} -o {}.png\n```", e.path.display(), e.name);
    }
    out
}
