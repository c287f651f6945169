//! `patina compile`: a surface shader (with the lights it is bound to) to WGSL and a JSON
//! description of its interface, through the library's `Compiler`; a light, displacement or
//! volume shader on its own is compiled bound to a surface (`--surface`, default `plastic`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use patina::{CompileError, Compiler, Light, Value};
use patina_compiler::syntax::ast::ShaderKind;

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

/// The kind and name of the shader of `file` that `patina compile` compiles: the one named, or
/// the first surface shader, or (in a file without one) the first shader. `None` when the file
/// does not check (compiling it reports why) or has no such shader.
fn target(file: &Path, name: Option<&str>, include: &[PathBuf]) -> Option<(ShaderKind, String)> {
    let checked = patina_compiler::check_file(file, include).ok()?;
    if checked.has_errors() {
        return None;
    }
    let found = checked.find_shader(Some(ShaderKind::Surface), name).or(checked.find_shader(None, name))?;
    Some((found.kind, found.name.to_string()))
}

/// An imager shader: compiled as the compute kernel the renderer runs over the finished image
/// (one invocation per pixel), written as NAME.wgsl with NAME.json giving its buffers' layout.
fn imager(args: &CompileArgs, name: &str) -> Result<ExitCode, String> {
    use patina_compiler::backend::binding::Binding;
    use patina_compiler::backend::cpu::CpuProgram;
    use patina_compiler::backend::wgsl::{KERNEL_WORKGROUP, compile_kernel};
    let shown = args.file.display().to_string();
    let checked = patina_compiler::check_file(&args.file, &args.include).map_err(|e| e.to_string())?;
    let Some(found) = checked.find_shader(None, Some(name)) else {
        return Err(format!("`{shown}` has errors"));
    };
    let mut numbers = Vec::new();
    let mut strings = Vec::new();
    for spec in &args.fix {
        match parse_fixed(spec)? {
            (n, Value::String(s)) => strings.push((n, s)),
            (n, Value::Numbers(v)) => numbers.push(patina_compiler::bind::Fixed { name: n, value: v }),
            (n, _) => return Err(format!("`--fix {n}`: not a number or a string")),
        }
    }
    for fixed in numbers.iter().map(|f| &f.name).chain(strings.iter().map(|(n, _)| n)) {
        if !found.params.iter().any(|p| found.local(*p).name == fixed.as_str()) {
            return Err(format!("shader `{name}` has no parameter `{fixed}`"));
        }
    }
    let bound =
        patina_compiler::bind::specialize(found, &numbers, &strings, patina_compiler::bind::Consumed::All);
    let shader = patina_compiler::opt::Prepared::with_strings(bound.shader, &strings);
    let binding = Binding { lights: Vec::new(), strings: strings.clone() };
    let cpu = CpuProgram::compile(&shader, &binding).map_err(|d| d.message)?;
    // What the renderer hands an imager, and the parameters the program reads.
    let mut inputs: Vec<String> = ["P", "s", "t", "Ci", "Oi", "alpha"]
        .iter()
        .filter(|n| cpu.slot(n).is_some())
        .map(|n| n.to_string())
        .collect();
    for p in &shader.params {
        let local = shader.local(*p);
        if cpu.slot(&local.name).is_some() && !inputs.contains(&local.name.to_string()) {
            inputs.push(local.name.to_string());
        }
    }
    let outputs: Vec<&str> = ["Ci", "alpha"].into_iter().filter(|n| cpu.slot(n).is_some()).collect();
    let refs: Vec<&str> = inputs.iter().map(String::as_str).collect();
    let kernel = compile_kernel(&shader, &[], &strings, &refs, &outputs).map_err(|d| d.message)?;
    let wgsl =
        naga::back::wgsl::write_string(&kernel.module, &kernel.info, naga::back::wgsl::WriterFlags::empty())
            .map_err(|e| format!("internal error: writing WGSL failed: {e}"))?;
    let values = |list: &[patina_compiler::backend::wgsl::KernelValue]| -> Vec<serde_json::Value> {
        list.iter()
            .map(|v| serde_json::json!({"name": v.name, "ty": v.ty.to_string(), "offset": v.offset, "words": v.words}))
            .collect()
    };
    let json = serde_json::json!({
        "version": 1,
        "kind": "imager",
        "shader": name,
        "entry": "main",
        "workgroup_size": KERNEL_WORKGROUP,
        "input": {"group": 0, "binding": 1, "stride": kernel.input_stride, "values": values(&kernel.inputs)},
        "output": {"group": 0, "binding": 2, "stride": kernel.output_stride, "values": values(&kernel.outputs)},
        // The named spaces' matrices and the constant tables (a noise's permutation), laid out
        // as a surface's uniform block is (docs/interface.md); no block when `size` is 0.
        "uniforms": {"group": 0, "binding": 0, "size": kernel.uniform_size, "fields": kernel.uniforms},
    });
    let json = serde_json::to_string_pretty(&json).map_err(|e| e.to_string())?;
    write_outputs(&args.output, name, &wgsl, &json)
}

/// Writes NAME.wgsl and NAME.json into `dir`.
fn write_outputs(dir: &Path, name: &str, wgsl: &str, json: &str) -> Result<ExitCode, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create `{}`: {e}", dir.display()))?;
    let write = |path: PathBuf, text: &str| {
        std::fs::write(&path, text).map_err(|e| format!("cannot write `{}`: {e}", path.display()))
    };
    let wgsl_path = dir.join(format!("{name}.wgsl"));
    let json_path = dir.join(format!("{name}.json"));
    write(wgsl_path.clone(), wgsl)?;
    write(json_path.clone(), json)?;
    eprintln!("wrote {} and {}", wgsl_path.display(), json_path.display());
    Ok(ExitCode::SUCCESS)
}

/// The surface a light, displacement or volume shader compiled on its own is bound to:
/// `--surface PATH[:NAME]`, or the standard library's `plastic`.
fn surface_source(spec: Option<&str>) -> Result<(String, String, Option<String>), String> {
    let Some(spec) = spec else {
        let module = "shaders.sl";
        let text = patina_compiler::stdlib::source(module).ok_or("the standard library has no shaders.sl")?;
        let shown = format!("{}/{module}", patina_compiler::stdlib::PREFIX);
        return Ok((shown, text.to_string(), Some("plastic".into())));
    };
    let (path, name) = match spec.rsplit_once(':') {
        Some((path, name)) if !Path::new(spec).is_file() => (path, Some(name.to_string())),
        _ => (spec, None),
    };
    let text = match patina_compiler::syntax::preprocess::read_source_file(Path::new(path)) {
        Ok(Some(text)) => text,
        Ok(None) => return Err(format!("cannot read `{path}`: no such file")),
        Err(reason) => return Err(format!("cannot read `{path}`: {reason}")),
    };
    Ok((path.to_string(), text, name))
}

pub fn run(args: CompileArgs) -> Result<ExitCode, String> {
    let mut compiler = Compiler::new().fold_host(args.fold_host).lowering(args.lowering.into());
    for dir in &args.include {
        compiler = compiler.include_dir(dir);
    }
    for spec in &args.light {
        compiler = compiler.light(light(spec, &args.file));
    }
    for spec in &args.fix {
        let (name, value) = parse_fixed(spec)?;
        compiler = compiler.fix(&name, value);
    }
    // A light, displacement or volume shader is compiled bound to a surface (RenderMan binds them
    // beside one); the files are named after it.
    let bound = match target(&args.file, args.shader.as_deref(), &args.include) {
        Some((kind @ (ShaderKind::Light | ShaderKind::Displacement | ShaderKind::Volume), name)) => {
            Some((kind, name))
        }
        Some((ShaderKind::Imager, name)) => return imager(&args, &name),
        _ => None,
    };
    let result = match &bound {
        Some((kind, name)) => {
            let shader = Light::file(&args.file).named(name);
            compiler = match kind {
                ShaderKind::Light => compiler.light(shader),
                ShaderKind::Displacement => compiler.displacement(shader),
                _ => compiler.atmosphere(shader),
            };
            let (shown, text, surface) = surface_source(args.surface.as_deref())?;
            if let Some(surface) = &surface {
                compiler = compiler.shader(surface);
            }
            let dir = Path::new(&shown).parent().filter(|_| args.surface.is_some());
            if let Some(dir) = dir {
                compiler = compiler.include_dir(dir);
            }
            compiler.compile_source(&shown, &text)
        }
        None => {
            if let Some(surface) = &args.surface {
                return Err(format!(
                    "`--surface {surface}`: `{}` has a surface shader; --surface binds a light, \
                     displacement or volume shader compiled on its own",
                    args.file.display()
                ));
            }
            if let Some(name) = &args.shader {
                compiler = compiler.shader(name);
            }
            compiler.compile_file(&args.file)
        }
    };
    let compiled = result.map_err(|e| match e {
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
    let name = bound.as_ref().map_or(compiled.name(), |(_, name)| name.as_str());
    write_outputs(&args.output, name, &compiled.wgsl, &json)
}
