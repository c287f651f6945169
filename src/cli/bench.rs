//! `patina bench`: error against run time. A scene's quality knobs swept: each setting rendered
//! on the GPU and the CPU reference, timed, measured against the knob's reference, and written as
//! a CSV file, a Markdown table and a plot (SVG and PNG) with the Pareto front marked.

use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;
use std::time::Duration;

use patina_runtime::render::{Backend, Progress};
use patina_runtime::scene::{Knob, Scene, Setting};
use patina_runtime::sweep::{self, Observer, Plan, Sweep, backend_name};

use super::progress::{RenderBar, steps, with_bars};
use super::render::open_gpu;
use super::{BenchArgs, Renderers};

pub fn run(args: BenchArgs) -> Result<ExitCode, String> {
    let scene = Scene::load(&args.scene).map_err(|e| e.to_string())?;
    let chosen = choose(&scene, &args.knob)?;
    let size = args.size.as_deref().map(parse_size).transpose()?;
    let gpu = match args.backend {
        Renderers::Cpu => None,
        Renderers::Both | Renderers::Gpu => open_gpu(),
    };
    let backends = match (args.backend, &gpu) {
        (Renderers::Cpu, _) | (Renderers::Both, None) => vec![Backend::Cpu],
        (Renderers::Gpu, None) => return Err("no GPU to time (`--backend gpu`)".into()),
        (Renderers::Gpu, Some(_)) => vec![Backend::Gpu],
        (Renderers::Both, Some(_)) => vec![Backend::Gpu, Backend::Cpu],
    };
    let device = gpu.as_ref().map_or_else(|| "no GPU".to_string(), |g| g.adapter_description());
    std::fs::create_dir_all(&args.output)
        .map_err(|e| format!("{}: cannot create the directory: {e}", args.output.display()))?;
    let name = args.scene.file_stem().map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    for (knob, settings) in &chosen {
        let plan =
            Plan { settings: settings.clone(), backends: backends.clone(), runs: args.runs as usize, size };
        // A warm-up and the timed runs per setting and renderer, and the reference.
        let renders = (settings.len() * backends.len() * (args.runs as usize + 1) + 1) as u64;
        let measured = with_bars(|bars| {
            let bar = steps(bars, renders);
            let observer = Bars { bars, bar: &bar };
            sweep::run(&scene, knob, &plan, gpu.as_ref(), &observer)
        })
        .map_err(|e| e.to_string())?;
        let stem = args.output.join(format!("{name}_{}", knob.name));
        let table = markdown(&measured, &args, &device);
        write(&stem.with_extension("csv"), &csv(&measured))?;
        write(&stem.with_extension("md"), &table)?;
        super::plot::write(&measured, &stem)?;
        println!("{table}");
        eprintln!("wrote {}.{{csv,md,svg,png}}", stem.display());
    }
    Ok(ExitCode::SUCCESS)
}

/// The knobs to sweep with their settings: those named by `--knob NAME[=V,..]`, or every knob of
/// the scene at its listed settings.
fn choose(scene: &Scene, wanted: &[String]) -> Result<Vec<(Knob, Vec<Setting>)>, String> {
    if scene.knobs.is_empty() {
        return Err(format!("{}: the scene declares no `[[knob]]` to sweep", scene.file.display()));
    }
    if wanted.is_empty() {
        return Ok(scene.knobs.iter().map(|k| (k.clone(), k.settings.clone())).collect());
    }
    wanted
        .iter()
        .map(|arg| {
            let (name, values) = match arg.split_once('=') {
                Some((n, v)) => (n.trim(), Some(v)),
                None => (arg.trim(), None),
            };
            let knob = scene.knob(name).ok_or_else(|| {
                let names: Vec<&str> = scene.knobs.iter().map(|k| k.name.as_str()).collect();
                format!("`--knob {arg}`: the scene has no knob `{name}` (it has: {})", names.join(", "))
            })?;
            let settings = match values {
                None => knob.settings.clone(),
                Some(list) => (list.split(','))
                    .map(|label| {
                        knob.setting(label.trim()).ok_or_else(|| {
                            let labels: Vec<&str> = knob.settings.iter().map(|s| s.label.as_str()).collect();
                            let any = if knob.param.is_some() { "a number, or one of" } else { "one of" };
                            format!(
                                "`--knob {arg}`: `{}` is not a setting of `{name}` ({any}: {})",
                                label.trim(),
                                labels.join(", ")
                            )
                        })
                    })
                    .collect::<Result<Vec<_>, _>>()?,
            };
            Ok((knob.clone(), settings))
        })
        .collect()
}

/// `WxH` as two sizes.
pub(super) fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("`--size {text}`: expected WIDTHxHEIGHT, e.g. 64x64");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h): (u32, u32) = (w.trim().parse().map_err(|_| bad())?, h.trim().parse().map_err(|_| bad())?);
    if !(1..=16384).contains(&w) || !(1..=16384).contains(&h) {
        return Err(format!("`--size {text}`: each side must be in 1..=16384"));
    }
    Ok((w, h))
}

/// Progress: a bar over the sweep's renders and one per render.
struct Bars<'a> {
    bars: &'a indicatif::MultiProgress,
    bar: &'a indicatif::ProgressBar,
}

impl Observer for Bars<'_> {
    fn render(&self, what: &str) -> Box<dyn Progress + '_> {
        self.bar.set_message(what.to_string());
        self.bar.inc(1);
        Box::new(RenderBar::new(self.bars, "frame"))
    }
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("{}: cannot write: {e}", path.display()))
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// One line per setting and renderer; times in milliseconds.
fn csv(s: &Sweep) -> String {
    let mut out = String::from(
        "scene,knob,kind,setting,backend,width,height,runs,median_ms,min_ms,max_ms,compile_ms,rms_error,max_error,non_finite_pixels,pareto,reference\n",
    );
    let scene = s.scene.display().to_string();
    for r in &s.rows {
        let (lo, hi) = (
            r.times.iter().min().copied().unwrap_or_default(),
            r.times.iter().max().copied().unwrap_or_default(),
        );
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{:.4},{:.4},{:.4},{:.2},{:.6e},{:.6e},{},{},{}",
            field(&scene),
            field(&s.knob),
            s.kind.name(),
            field(&r.setting),
            backend_name(r.backend),
            s.width,
            s.height,
            r.times.len(),
            ms(r.median),
            ms(lo),
            ms(hi),
            ms(r.compile),
            r.rms_error,
            r.max_error,
            r.non_finite,
            r.pareto,
            field(&s.reference)
        );
    }
    out
}

/// A CSV field, quoted when it needs to be.
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// The sweep as a Markdown section: what was measured, how, and the table.
fn markdown(s: &Sweep, args: &BenchArgs, device: &str) -> String {
    let mut out = String::new();
    let command = command_line(args);
    let _ = writeln!(
        out,
        "`{}`, knob `{}` ({}), {}x{}, against the reference `{}` (CPU, {:.1} ms). Median of {} warm \
         runs on {device} (GPU) and the CPU reference. Regenerate: `{command}`\n",
        s.scene.display(),
        s.knob,
        s.kind.name(),
        s.width,
        s.height,
        s.reference,
        ms(s.reference_time),
        s.runs
    );
    for backend in [Backend::Gpu, Backend::Cpu] {
        if let Some(order) = s.convergence_order(backend) {
            let _ = writeln!(
                out,
                "Measured order of convergence ({}): **{order:.2}** (least-squares slope of log RMS error \
                 against log {}).\n",
                backend_name(backend),
                if s.kind == patina_runtime::scene::KnobKind::StepSize { "step size" } else { "setting" }
            );
        }
    }
    let _ = writeln!(out, "| setting | renderer | median ms | min–max ms | RMS error | max error | Pareto |");
    let _ = writeln!(out, "|---|---|---:|---:|---:|---:|:---:|");
    for r in &s.rows {
        let (lo, hi) = (
            r.times.iter().min().copied().unwrap_or_default(),
            r.times.iter().max().copied().unwrap_or_default(),
        );
        let nan =
            if r.non_finite > 0 { format!(" ({} non-finite pixels)", r.non_finite) } else { String::new() };
        let _ = writeln!(
            out,
            "| {} | {} | {:.2} | {:.2}–{:.2} | {:.3e}{nan} | {:.3e} | {} |",
            r.setting,
            backend_name(r.backend),
            ms(r.median),
            ms(lo),
            ms(hi),
            r.rms_error,
            r.max_error,
            if r.pareto { "★" } else { "" }
        );
    }
    out
}

/// The command that regenerates this output.
fn command_line(args: &BenchArgs) -> String {
    let mut words: Vec<String> = vec!["patina bench".into(), display(&args.scene)];
    words.extend(args.knob.iter().map(|k| format!("--knob {k}")));
    if let Some(size) = &args.size {
        words.push(format!("--size {size}"));
    }
    words.push(format!("--runs {}", args.runs));
    words.push(format!("-o {}", display(&args.output)));
    words.join(" ")
}

fn display(path: &Path) -> String {
    path.display().to_string()
}
