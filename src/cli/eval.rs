//! `patina eval`: run a shader on the CPU interpreter at given points and print a table.

use std::process::ExitCode;

use patina_compiler::backend::binding::{Binding, LightBinding};
use patina_compiler::backend::cpu::{CpuProgram, EvalError, Evaluator, SlotKind};
use patina_compiler::diag;
use patina_compiler::ir::Shader;
use patina_compiler::syntax::ast::ShaderKind;

use super::EvalArgs;

pub fn run(args: EvalArgs) -> Result<ExitCode, String> {
    let name = args.file.to_string_lossy().into_owned();
    let checked = patina_compiler::check_file(&args.file, &args.include).map_err(|e| e.to_string())?;
    eprint!("{}", checked.diagnostics_text());
    if checked.has_errors() {
        return Ok(ExitCode::FAILURE);
    }
    let shader = match &args.shader {
        Some(wanted) => checked
            .find_shader(None, Some(wanted))
            .ok_or_else(|| format!("`{name}` has no shader `{wanted}`"))?,
        None => checked.find_shader(None, None).ok_or_else(|| format!("`{name}` defines no shader"))?,
    };

    let lights: Vec<Vec<(String, Vec<f64>)>> =
        args.light.iter().map(|l| parse_assignments(l)).collect::<Result<_, _>>()?;
    let ambient: Vec<Vec<(String, Vec<f64>)>> =
        args.ambient_light.iter().map(|l| parse_assignments(l)).collect::<Result<_, _>>()?;
    let mut binding = Binding::default();
    for _ in &lights {
        binding.lights.push(LightBinding::default());
    }
    for _ in &ambient {
        binding.lights.push(LightBinding { ambient: true, ..LightBinding::default() });
    }
    for s in &args.string {
        let (k, v) = s.split_once('=').ok_or_else(|| format!("`--string {s}`: expected NAME=VALUE"))?;
        binding.strings.push((k.trim().to_string(), v.to_string()));
    }
    let prepared = patina_compiler::opt::Prepared::with_strings(shader.clone(), &binding.strings);
    let program = match CpuProgram::compile(&prepared, &binding) {
        Ok(p) => p,
        Err(d) => {
            eprint!("{}", diag::render_text(&checked.sources, &[d]));
            return Ok(ExitCode::FAILURE);
        }
    };

    let points: Vec<Vec<(String, Vec<f64>)>> =
        args.at.iter().map(|p| parse_assignments(p)).collect::<Result<_, _>>()?;
    let count = points.len().max(1);
    let mut names: Vec<String> = Vec::new();
    for (name, _) in points.iter().flatten() {
        if !names.contains(name) {
            names.push(name.clone());
        }
    }
    let mut columns: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    for (p, point) in points.iter().enumerate() {
        for (n, column) in names.iter().zip(&mut columns) {
            let value = point.iter().find(|(k, _)| k == n).ok_or_else(|| {
                format!("point {} does not give `{n}` (every `--at` must give the same inputs)", p + 1)
            })?;
            column.extend(&value.1);
        }
    }
    let outputs: Vec<String> =
        if args.output.is_empty() { default_outputs(shader, &program) } else { args.output.clone() };

    let mut uniform: Vec<(String, Vec<f64>)> =
        args.set.iter().map(|s| parse_assignments(s)).collect::<Result<Vec<_>, _>>()?.concat();
    for (k, light) in lights.iter().chain(&ambient).enumerate() {
        for (name, value) in light {
            uniform.push((format!("{name}[{k}]"), value.clone()));
        }
    }
    // Names the shader never reads are dropped with a warning: binding leaves them out, and a
    // table of inputs that mention them is still meaningful.
    let unused = |name: &str| program.slot(name).is_none();
    for name in names.iter().chain(uniform.iter().map(|(n, _)| n)) {
        if unused(name) && !name.starts_with("L[") && !name.starts_with("Cl[") {
            eprintln!("warning: `{name}` is not an input of shader `{}`; ignored", shader.name);
        }
    }
    uniform.retain(|(name, _)| !unused(name));
    let inputs: Vec<(&str, &[f64])> = names
        .iter()
        .map(|n| n.as_str())
        .zip(columns.iter().map(|c| &c[..]))
        .filter(|(name, _)| !unused(name))
        .collect();
    let output_names: Vec<&str> = outputs.iter().map(|s| s.as_str()).collect();
    let result = if args.f64 {
        evaluate::<f64>(&program, &uniform, args.budget, count, &inputs, &output_names)
    } else {
        evaluate::<f32>(&program, &uniform, args.budget, count, &inputs, &output_names)
    };
    let values = match result {
        Ok(v) => v,
        Err(e @ EvalError::IterationBudget { .. }) => {
            eprint!("{}", diag::render_text(&checked.sources, &[e.to_diagnostic()]));
            return Ok(ExitCode::FAILURE);
        }
        Err(e) => return Err(e.to_string()),
    };
    print!("{}", table(count, &inputs, &output_names, &values, args.f64));
    Ok(ExitCode::SUCCESS)
}

fn evaluate<F: patina_compiler::backend::cpu::scalar::Real>(
    program: &CpuProgram,
    uniform: &[(String, Vec<f64>)],
    budget: u64,
    count: usize,
    inputs: &[(&str, &[f64])],
    outputs: &[&str],
) -> Result<Vec<Vec<f64>>, EvalError> {
    let mut eval = Evaluator::<F>::new(program);
    eval.set_budget(budget);
    for (name, value) in uniform {
        eval.set(name, value)?;
    }
    eval.eval_points(count, inputs, outputs)
}

/// What a shader of each kind produces.
fn default_outputs(shader: &Shader, program: &CpuProgram) -> Vec<String> {
    let mut names: Vec<String> = match (shader.stanford, shader.kind) {
        (true, _) => vec!["result".into()],
        (false, ShaderKind::Surface) => vec!["Ci".into(), "Oi".into()],
        (false, ShaderKind::Light) => vec!["Cl".into()],
        (false, ShaderKind::Displacement) => vec!["P".into(), "N".into()],
        (false, ShaderKind::Volume) => vec!["Ci".into(), "Oi".into()],
        (false, ShaderKind::Imager) => vec!["Ci".into(), "alpha".into()],
    };
    for (_, slot) in program.slots() {
        if slot.kind == (SlotKind::Param { output: true }) {
            names.push(slot.name);
        }
    }
    names.retain(|n| program.slot(n).is_some());
    names
}

/// `NAME=V[,V...]` assignments separated by spaces or semicolons.
fn parse_assignments(text: &str) -> Result<Vec<(String, Vec<f64>)>, String> {
    text.split([';', ' '])
        .filter(|part| !part.trim().is_empty())
        .map(|part| {
            let (name, values) =
                part.split_once('=').ok_or_else(|| format!("`{part}`: expected NAME=VALUE[,VALUE...]"))?;
            let values = values
                .split(',')
                .map(|v| v.trim().parse::<f64>().map_err(|_| format!("`{part}`: `{v}` is not a number")))
                .collect::<Result<Vec<_>, _>>()?;
            Ok((name.trim().to_string(), values))
        })
        .collect()
}

/// One row per point: the inputs given, then the outputs.
fn table(
    count: usize,
    inputs: &[(&str, &[f64])],
    outputs: &[&str],
    values: &[Vec<f64>],
    f64_mode: bool,
) -> String {
    let show = |v: &[f64]| -> String {
        let parts: Vec<String> =
            v.iter().map(|x| if f64_mode { format!("{x}") } else { format!("{}", *x as f32) }).collect();
        if parts.len() == 1 { parts[0].clone() } else { format!("({})", parts.join(", ")) }
    };
    let mut header: Vec<String> = vec!["point".into()];
    header.extend(inputs.iter().map(|(n, _)| n.to_string()));
    header.extend(outputs.iter().map(|n| n.to_string()));
    let mut rows = vec![header];
    for p in 0..count {
        let mut row = vec![(p + 1).to_string()];
        for (_, column) in inputs {
            let width = column.len() / count;
            row.push(show(&column[p * width..(p + 1) * width]));
        }
        for column in values {
            let width = column.len() / count;
            row.push(show(&column[p * width..(p + 1) * width]));
        }
        rows.push(row);
    }
    let widths: Vec<usize> =
        (0..rows[0].len()).map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0)).collect();
    let mut out = String::new();
    for row in &rows {
        let cells: Vec<String> = row.iter().zip(&widths).map(|(cell, w)| format!("{cell:<w$}")).collect();
        out.push_str(cells.join("  ").trim_end());
        out.push('\n');
    }
    out
}
