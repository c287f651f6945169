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
    // One row per parameter or variable: name, type, rate, stage, in columns as wide as needed.
    let mut rows: Vec<(bool, [String; 4])> = Vec::new();
    for &p in &shader.params {
        let l = shader.local(p);
        let output = matches!(l.kind, LocalKind::Param { output: true, .. });
        let stage = format!("{}{}", stage(l.rate, shader.stanford), if output { ", output" } else { "" });
        rows.push((true, [l.name.to_string(), l.ty.to_string(), l.rate.to_string(), stage]));
    }
    for l in shader.locals.iter().filter(|l| l.kind == LocalKind::Var) {
        let how = if l.declared { "declared" } else { "inferred" };
        let name = match &l.function {
            Some(f) => format!("{} (in {f})", l.name),
            None => l.name.to_string(),
        };
        let rate = format!("{} ({how})", l.rate);
        rows.push((false, [name, l.ty.to_string(), rate, stage(l.rate, shader.stanford).to_string()]));
    }
    let width = |i: usize| rows.iter().map(|r| r.1[i].len()).max().unwrap_or(0);
    let (w0, w1, w2) = (width(0), width(1), width(2));
    for (heading, params) in [("parameters", true), ("variables", false)] {
        let _ = writeln!(out, "  {heading}:");
        let mut any = false;
        for (_, [name, ty, rate, stage]) in rows.iter().filter(|r| r.0 == params) {
            let _ = writeln!(out, "    {name:<w0$}  {ty:<w1$}  {rate:<w2$}  {stage}");
            any = true;
        }
        if !any {
            let _ = writeln!(out, "    (none)");
        }
    }
    let mut per_stage = std::collections::BTreeMap::new();
    for e in &shader.exprs {
        *per_stage.entry(stage(e.rate, shader.stanford)).or_insert(0usize) += 1;
    }
    let summary: Vec<String> = per_stage.iter().map(|(s, n)| format!("{n} in {s}")).collect();
    let _ =
        writeln!(out, "  computations: {} ({} statements)", summary.join(", "), count_stores(&shader.body));
}
