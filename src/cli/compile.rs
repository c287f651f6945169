//! `patina compile`: a surface shader (with the lights it is bound to) to WGSL and a JSON
//! description of its interface, through the library's `Compiler`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use patina::{CompileError, Compiler, Light, Value};

use super::CompileArgs;

/// `NAME=V`, `NAME=V,V,V` (numbers) or `NAME="TEXT"` (a string): a parameter's value to
/// compile in.
fn parse_fixed(spec: &str) -> Result<(String, Value), String> {
    let bad = || format!("`--fix {spec}`: expected NAME=V or NAME=V,V,V with numbers, or NAME=\"TEXT\"");
    let (name, values) = spec.split_once('=').ok_or_else(bad)?;
    if name.trim().is_empty() {
        return Err(bad());
    }
    let value = match values.strip_prefix('"').and_then(|v| v.strip_suffix('"')) {
        Some(text) => Value::String(text.to_string()),
        None => Value::Numbers(
            values
                .split(',')
                .map(|v| v.trim().parse::<f64>().map_err(|_| bad()))
                .collect::<Result<_, _>>()?,
        ),
    };
    Ok((name.trim().to_string(), value))
}

/// A `--light` argument: `NAME` (a light of FILE), `PATH` (its first light) or `PATH:NAME`.
fn light(spec: &str, file: &Path) -> Light {
    match spec.rsplit_once(':') {
        Some((path, name)) => Light::file(path).named(name),
        None if Path::new(spec).is_file() => Light::file(spec),
        None => Light::file(file).named(spec),
    }
}

pub fn run(args: CompileArgs) -> Result<ExitCode, String> {
    let mut compiler = Compiler::new().fold_host(args.fold_host);
    for dir in &args.include {
        compiler = compiler.include_dir(dir);
    }
    if let Some(name) = &args.shader {
        compiler = compiler.shader(name);
    }
    for spec in &args.light {
        compiler = compiler.light(light(spec, &args.file));
    }
    for spec in &args.fix {
        let (name, value) = parse_fixed(spec)?;
        compiler = compiler.fix(&name, value);
    }
    let compiled = compiler.compile_file(&args.file).map_err(|e| match e {
        CompileError::Diagnostics(d) => {
            eprintln!("{d}");
            format!("`{}` has errors", args.file.display())
        }
        // A limit or a missing feature of a valid program: its headline, as one line.
        CompileError::Program(d) => {
            d.iter().next().map_or_else(|| d.to_string(), |first| first.message.clone())
        }
        e => e.to_string(),
    })?;
    if !compiled.warnings.is_empty() {
        eprintln!("{}", compiled.warnings);
    }
    let json = serde_json::to_string_pretty(&compiled.interface).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(&args.output)
        .map_err(|e| format!("cannot create `{}`: {e}", args.output.display()))?;
    let write = |path: PathBuf, text: &str| {
        std::fs::write(&path, text).map_err(|e| format!("cannot write `{}`: {e}", path.display()))
    };
    let wgsl_path = args.output.join(format!("{}.wgsl", compiled.name()));
    let json_path = args.output.join(format!("{}.json", compiled.name()));
    write(wgsl_path.clone(), &compiled.wgsl)?;
    write(json_path.clone(), &json)?;
    eprintln!("wrote {} and {}", wgsl_path.display(), json_path.display());
    Ok(ExitCode::SUCCESS)
}
