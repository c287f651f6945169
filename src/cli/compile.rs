//! `patina compile`: a surface shader (with the lights it is bound to) to WGSL and a JSON
//! description of its interface.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use patina_compiler::backend::wgsl::{self, BoundLight};
use patina_compiler::bind::{Consumed, Fixed};
use patina_compiler::ir::Shader;
use patina_compiler::syntax::ast::ShaderKind;
use patina_compiler::syntax::preprocess::{FsLoader, read_source_file};

use super::CompileArgs;

/// Reads and checks a file; diagnostics are printed and make it fail.
fn load(path: &Path, include: &[PathBuf]) -> Result<Vec<Shader>, String> {
    let name = path.display().to_string();
    let text = match read_source_file(path) {
        Ok(Some(t)) => t,
        Ok(None) => return Err(format!("cannot read `{name}`: no such file")),
        Err(reason) => return Err(format!("cannot read `{name}`: {reason}")),
    };
    let checked = patina_compiler::check_source(&name, &text, &FsLoader { include_dirs: include.to_vec() });
    if checked.has_errors() {
        let list: Vec<_> = checked.diagnostics.iter().cloned().collect();
        eprint!("{}", patina_compiler::diag::render_text(&checked.sources, &list));
        return Err(format!("`{name}` has errors"));
    }
    Ok(checked.program.shaders)
}

fn pick(shaders: &[Shader], kind: ShaderKind, name: Option<&str>, file: &Path) -> Result<Shader, String> {
    shaders.iter().find(|s| s.kind == kind && name.is_none_or(|n| s.name == n)).cloned().ok_or_else(|| {
        match name {
            Some(n) => format!("`{}` has no shader `{n}` of that kind", file.display()),
            None => format!("`{}` has no surface shader", file.display()),
        }
    })
}

/// `NAME=V` or `NAME=V,V,V`: a parameter's value to compile in.
fn parse_fixed(spec: &str) -> Result<Fixed, String> {
    let bad = || format!("`--fix {spec}`: expected NAME=V or NAME=V,V,V with numbers");
    let (name, values) = spec.split_once('=').ok_or_else(bad)?;
    let value = values
        .split(',')
        .map(|v| v.trim().parse::<f64>().map_err(|_| bad()))
        .collect::<Result<Vec<_>, _>>()?;
    if name.trim().is_empty() {
        return Err(bad());
    }
    Ok(Fixed { name: name.trim().to_string(), value })
}

pub fn run(args: CompileArgs) -> Result<ExitCode, String> {
    let shaders = load(&args.file, &args.include)?;
    let mut surface = pick(&shaders, ShaderKind::Surface, args.shader.as_deref(), &args.file)?;
    let mut lights = Vec::new();
    for spec in &args.light {
        // `NAME` (a light of FILE), `PATH` (its first light) or `PATH:NAME`.
        let (path, name) = match spec.rsplit_once(':') {
            Some((p, n)) => (PathBuf::from(p), Some(n.to_string())),
            None if Path::new(spec).is_file() => (PathBuf::from(spec), None),
            None => (args.file.clone(), Some(spec.clone())),
        };
        let file_shaders = if path == args.file { shaders.clone() } else { load(&path, &args.include)? };
        let mut light = pick(&file_shaders, ShaderKind::Light, name.as_deref(), &path)?;
        patina_compiler::opt::prepare(&mut light);
        lights.push(light);
    }
    if !args.fix.is_empty() {
        let fixed = args.fix.iter().map(|f| parse_fixed(f)).collect::<Result<Vec<_>, _>>()?;
        for f in &fixed {
            if !surface.params.iter().any(|p| surface.local(*p).name == f.name.as_str()) {
                return Err(format!("`{}` has no parameter `{}` to fix", surface.name, f.name));
            }
        }
        // Your program reads the output parameters it wants from the interface: keep them all.
        let bound = patina_compiler::bind::specialize(&surface, &fixed, Consumed::All);
        surface = bound.shader;
    }
    patina_compiler::opt::prepare(&mut surface);
    let stages = patina_compiler::split::split(&surface).map_err(|d| d.message)?;
    let bound: Vec<BoundLight> = lights
        .iter()
        .map(|s| BoundLight { shader: s, strings: Vec::new(), categories: Vec::new() })
        .collect();
    let program = wgsl::compile(&stages, &bound, &[]).map_err(|d| d.message)?;
    let text = program.wgsl().map_err(|d| d.message)?;
    let json = serde_json::to_string_pretty(&program.interface).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(&args.output)
        .map_err(|e| format!("cannot create `{}`: {e}", args.output.display()))?;
    let wgsl_path = args.output.join(format!("{}.wgsl", surface.name));
    let json_path = args.output.join(format!("{}.json", surface.name));
    std::fs::write(&wgsl_path, text).map_err(|e| format!("cannot write `{}`: {e}", wgsl_path.display()))?;
    std::fs::write(&json_path, json).map_err(|e| format!("cannot write `{}`: {e}", json_path.display()))?;
    eprintln!("wrote {} and {}", wgsl_path.display(), json_path.display());
    Ok(ExitCode::SUCCESS)
}
