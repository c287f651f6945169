//! `patina explain`: what the semantic stage decided, as text: each shader's parameters and
//! variables with their types and rates, and the stage each computation runs in.

use std::fmt::Write;

use crate::ir::types::{Frequency, Rate};
use crate::ir::{LocalKind, Program, Shader, Stmt};

/// The stage a value of this rate is computed in, under the shader's style's placement rule:
/// Stanford code runs at the lowest rate its operands allow; RenderMan `varying` work runs per
/// fragment.
pub fn stage(rate: Rate, stanford: bool) -> &'static str {
    match rate.frequency {
        Frequency::Constant => "compile time",
        Frequency::PrimitiveGroup => "host (once per draw)",
        Frequency::Vertex if stanford => "vertex stage",
        Frequency::Vertex | Frequency::Fragment => "fragment stage",
    }
}

fn count_stores(block: &[Stmt]) -> usize {
    block
        .iter()
        .map(|s| match s {
            Stmt::Store { .. } | Stmt::Eval(_) => 1,
            Stmt::If { then, otherwise, .. } => count_stores(then) + count_stores(otherwise),
            Stmt::Loop { body, step, .. } => count_stores(body) + count_stores(step),
            Stmt::Inline { body, .. } | Stmt::Illuminance { body, .. } | Stmt::Emit { body, .. } => {
                count_stores(body)
            }
            _ => 0,
        })
        .sum()
}

/// A report of every shader in `program`.
pub fn explain(program: &Program) -> String {
    let mut out = String::new();
    for shader in &program.shaders {
        shader_report(shader, &mut out);
    }
    out
}

fn shader_report(shader: &Shader, out: &mut String) {
    let style = if shader.stanford { "Stanford" } else { "RenderMan" };
    let _ = writeln!(out, "{} shader `{}` ({style} style)", shader.kind.keyword(), shader.name);
    if shader.stanford {
        let _ = writeln!(out, "  returns {}", shader.result);
    }
    let _ = writeln!(out, "  parameters:");
    if shader.params.is_empty() {
        let _ = writeln!(out, "    (none)");
    }
    for &p in &shader.params {
        let l = shader.local(p);
        let output = matches!(l.kind, LocalKind::Param { output: true, .. });
        let _ = writeln!(
            out,
            "    {:<16} {:<10} {:<24} {}{}",
            l.name,
            l.ty.to_string(),
            l.rate.to_string(),
            stage(l.rate, shader.stanford),
            if output { ", output" } else { "" }
        );
    }
    let _ = writeln!(out, "  variables:");
    let vars: Vec<_> = shader.locals.iter().filter(|l| l.kind == LocalKind::Var).collect();
    if vars.is_empty() {
        let _ = writeln!(out, "    (none)");
    }
    for l in vars {
        let how = if l.declared { "declared" } else { "inferred" };
        let _ = writeln!(
            out,
            "    {:<16} {:<10} {:<24} {}",
            l.name,
            l.ty.to_string(),
            format!("{} ({how})", l.rate),
            stage(l.rate, shader.stanford)
        );
    }
    let mut per_stage = std::collections::BTreeMap::new();
    for e in &shader.exprs {
        *per_stage.entry(stage(e.rate, shader.stanford)).or_insert(0usize) += 1;
    }
    let summary: Vec<String> = per_stage.iter().map(|(s, n)| format!("{n} in {s}")).collect();
    let _ =
        writeln!(out, "  computations: {} ({} statements)", summary.join(", "), count_stores(&shader.body));
}
