//! `patina stability`: the extreme-input sweep of the standard library or of a user's files, as a
//! table; exit 1 when a finite input produced a non-finite output.

use std::process::ExitCode;

use patina_compiler::syntax::preprocess::{FsLoader, MemoryLoader, SourceLoader};
use patina_runtime::stability::{self, Options, Row, Subject, table};

use super::progress::{steps, with_bars};
use super::render::open_gpu_or;
use super::{BackendChoice, StabilityArgs};

pub fn run(args: StabilityArgs) -> Result<ExitCode, String> {
    let (subjects, loader) = gather(&args)?;
    let subjects: Vec<Subject> = subjects
        .into_iter()
        .filter(|s| args.function.is_empty() || args.function.iter().any(|f| name_of(&s.label) == f))
        .collect();
    if subjects.is_empty() {
        return Err("nothing to sweep: no function or surface shader matches".into());
    }
    let gpu = match args.backend {
        BackendChoice::Cpu => None,
        BackendChoice::Gpu => open_gpu_or("sweeping the interpreter only"),
    };
    let options = Options { random: args.random, ..Options::default() };
    let rows: Vec<Row> = with_bars(|bars| {
        let bar = steps(bars, subjects.len() as u64);
        bar.set_prefix("sweeping");
        let rows = subjects
            .iter()
            .map(|s| {
                bar.set_message(s.label.clone());
                let row = stability::sweep(s, loader.as_ref(), &options, gpu.as_ref());
                bar.inc(1);
                row
            })
            .collect();
        bar.finish_and_clear();
        rows
    });
    print!("{}", table::plain(&rows));
    if let Some(path) = &args.markdown {
        std::fs::write(path, table::markdown(&rows))
            .map_err(|e| format!("cannot write `{}`: {e}", path.display()))?;
    }
    if let Some(path) = &args.csv {
        std::fs::write(path, table::csv(&rows))
            .map_err(|e| format!("cannot write `{}`: {e}", path.display()))?;
    }
    let failed: Vec<&Row> = rows.iter().filter(|r| r.failed()).collect();
    for row in &failed {
        for f in row.outcome.as_ref().map(|m| m.failures.as_slice()).unwrap_or_default() {
            eprintln!(
                "unstable: {} ({}) on {}: {} gives {}",
                row.label, row.file, f.backend, f.input, f.output
            );
        }
    }
    let not_swept = rows.iter().filter(|r| r.outcome.is_err()).count();
    let gpu_errors: Vec<&Row> =
        rows.iter().filter(|r| r.outcome.as_ref().is_ok_and(|m| m.gpu_error.is_some())).collect();
    for row in &gpu_errors {
        if let Ok(m) = &row.outcome {
            eprintln!("GPU error: {}: {}", row.label, m.gpu_error.as_deref().unwrap_or_default());
        }
    }
    let points: usize = rows.iter().map(|r| r.points).sum();
    eprintln!(
        "{} subjects, {points} points on {}: {} unstable, {} not swept, {} GPU errors",
        rows.len(),
        gpu.as_ref().map_or("the interpreter (f64, f32)".to_string(), |g| format!(
            "the interpreter (f64, f32) and {}",
            g.adapter_description()
        )),
        failed.len(),
        not_swept,
        gpu_errors.len()
    );
    Ok(if failed.is_empty() { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

/// A subject's name without its parameter list (`soft_sphere`, or `plastic` for `surface
/// plastic`).
fn name_of(label: &str) -> &str {
    let name = label.strip_prefix("surface ").unwrap_or(label);
    name.split('(').next().unwrap_or(name)
}

/// The subjects to sweep and the loader that resolves their includes.
fn gather(args: &StabilityArgs) -> Result<(Vec<Subject>, Box<dyn SourceLoader>), String> {
    if args.stdlib {
        let modules: Vec<&(&str, &str)> = patina_compiler::stdlib::MODULES
            .iter()
            .filter(|(name, _)| {
                args.module.is_empty() || args.module.iter().any(|m| m == name || format!("{m}.sl") == *name)
            })
            .collect();
        if modules.is_empty() {
            let known: Vec<&str> = patina_compiler::stdlib::MODULES.iter().map(|(n, _)| *n).collect();
            return Err(format!(
                "no standard-library module {}; the modules are {}",
                args.module.join(", "),
                known.join(", ")
            ));
        }
        let loader = MemoryLoader::default();
        let mut all = Vec::new();
        for (name, source) in modules {
            all.extend(stability::subjects(name, source, &loader, true)?);
        }
        return Ok((all, Box::new(loader)));
    }
    if args.files.is_empty() {
        return Err("give a FILE or --stdlib".into());
    }
    let loader = FsLoader { include_dirs: args.include.clone() };
    let mut all = Vec::new();
    for path in &args.files {
        let name = path.to_string_lossy().into_owned();
        let checked = patina_compiler::check_file(path, &args.include).map_err(|e| e.to_string())?;
        if checked.has_errors() {
            eprint!("{}", checked.diagnostics_text());
            return Err(format!("`{name}` does not check; nothing swept"));
        }
        let text = checked.sources.file(checked.root).text.to_string();
        all.extend(stability::subjects(&name, &text, &loader, false)?);
    }
    Ok((all, Box::new(loader)))
}
