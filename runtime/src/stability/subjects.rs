//! What the sweep runs: the functions and surface shaders of a source file, found in its syntax
//! tree, each turned into a checked program with named varying inputs and outputs.
//!
//! A function is called from a wrapper surface shader appended to its file, one input per
//! parameter (`a0`, `a1`, .., array elements `a2_0`, `a2_1`, ..) and its result as the output
//! `result` (an `output` parameter's final value as `out1`, ..). A surface shader runs as it is,
//! with its parameters and `P`, `N`, `I`, `s`, `t` as inputs (`Cs` and `Os` white, not swept)
//! and `Ci`, `Oi` as outputs.

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::CpuProgram;
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::ast::{FunctionDef, Item, Param, ShaderDef, ShaderKind, ShaderStyle, TypeName};
use patina_compiler::syntax::preprocess::SourceLoader;

use super::args::{Arg, Kind};
use super::preconditions::{self, Precondition};

/// The name of the wrapper shader the sweep appends to a file.
pub const WRAPPER: &str = "patina_stability_wrapper";

/// The length given to an unsized array parameter (`color clut[]`) unless its precondition says
/// otherwise.
pub const DEFAULT_ARRAY_LEN: usize = 4;

/// One thing to sweep, before it is compiled.
#[derive(Clone, Debug)]
pub struct Subject {
    /// The file it is defined in (`volume.sl`, or the user's path).
    pub file: String,
    /// Its name and parameter types, e.g. `soft_sphere(point, point, float, float)`.
    pub label: String,
    /// Its inputs.
    pub args: Vec<Arg>,
    /// The outputs to compare.
    pub outputs: Vec<String>,
    /// How to build it, or why it is not swept.
    pub build: Result<Build, String>,
}

/// The source and shader that run a subject.
#[derive(Clone, Debug)]
pub struct Build {
    /// The whole source to check (the file, and the wrapper for a function).
    pub source: String,
    /// The shader to run.
    pub shader: String,
}

/// A subject compiled for both backends.
pub struct Compiled {
    /// The shader, prepared (for the GPU kernel).
    pub shader: Prepared,
    /// The interpreter's code.
    pub cpu: CpuProgram,
}

/// The subjects of the file `name` with text `text`: every function it defines itself (not those
/// it includes), and every surface shader. With `public_only`, functions named `_patina_..` (the
/// standard library's private helpers, whose preconditions their callers establish) are left
/// out, and of functions made by a macro for several array sizes only the first size is kept.
pub fn subjects(
    name: &str,
    text: &str,
    loader: &dyn SourceLoader,
    public_only: bool,
) -> Result<Vec<Subject>, String> {
    let checked = patina_compiler::check_source(name, text, loader);
    if checked.has_errors() {
        let first = checked.diagnostics.iter().find(|d| d.is_error()).map(|d| d.message.clone());
        return Err(format!("{name} does not check: {}", first.unwrap_or_default()));
    }
    let source_text = |span: patina_compiler::source::Span| checked.sources.file(span.file).text.clone();
    let mut out: Vec<Subject> = Vec::new();
    let mut families: Vec<String> = Vec::new();
    for item in &checked.module.items {
        match item {
            Item::Function(f) if f.span.file == checked.root || from_root_macro(&checked, f) => {
                if public_only && f.name.name.starts_with("_patina_") {
                    continue;
                }
                let family = format!("{}({})", f.name.name, kinds_of(&f.params));
                if public_only && f.span.expn.is_macro() {
                    if families.contains(&family) {
                        continue;
                    }
                    families.push(family);
                }
                let pre = preconditions::before(&source_text(f.span), f.span.start as usize);
                out.push(function(name, text, f, &pre));
            }
            Item::Shader(s) if s.span.file == checked.root && s.kind == ShaderKind::Surface => {
                let pre = preconditions::before(&source_text(s.span), s.span.start as usize);
                out.push(shader(name, text, s, &pre));
            }
            _ => {}
        }
    }
    Ok(out)
}

/// Whether a function made by a macro expansion was expanded in the root file (the colour-table
/// sizes of `color.sl`, written in its macro definition, are expanded by lines of color.sl).
fn from_root_macro(checked: &patina_compiler::Checked, f: &FunctionDef) -> bool {
    f.span.expn.is_macro() && checked.sources.call_site(f.span).file == checked.root
}

/// The parameter types of a function, as `float, point[]`.
fn kinds_of(params: &[Param]) -> String {
    params
        .iter()
        .map(|p| format!("{}{}", p.ty.name.keyword(), if p.array.is_some() { "[]" } else { "" }))
        .collect::<Vec<_>>()
        .join(", ")
}

/// An error naming the precondition clauses that do not parse.
fn check_preconditions(pre: &[Precondition]) -> Result<(), String> {
    let bad = preconditions::invalid(pre);
    if bad.is_empty() {
        Ok(())
    } else {
        Err(format!("a `sweep:` precondition does not parse: {}", bad.join("; ")))
    }
}

fn function(file: &str, text: &str, f: &FunctionDef, pre: &[Precondition]) -> Subject {
    let label = format!("{}({})", f.name.name, kinds_of(&f.params));
    let mut subject =
        Subject { file: file.to_string(), label, args: vec![], outputs: vec![], build: Err(String::new()) };
    subject.build = (|| {
        check_preconditions(pre)?;
        let mut params = Vec::new();
        let mut locals = String::new();
        let mut call = Vec::new();
        let mut copies = String::new();
        for (k, p) in f.params.iter().enumerate() {
            let kind = Kind::of(p.ty.name).ok_or_else(|| format!("a {} parameter", p.ty.name.keyword()))?;
            let constraint = preconditions::for_param(pre, &p.name.name);
            let ty = p.ty.name.keyword();
            match p.array {
                None => {
                    subject.args.push(Arg::new(format!("a{k}"), kind, p.name.name.as_str(), constraint));
                    params.push(format!("varying {ty} a{k} = {}", zero(kind)));
                }
                Some(size) => {
                    let len = size.len.map(|n| n as usize).or(constraint.length).unwrap_or(DEFAULT_ARRAY_LEN);
                    let names: Vec<String> = (0..len).map(|i| format!("a{k}_{i}")).collect();
                    for (i, n) in names.iter().enumerate() {
                        let label = format!("{}[{i}]", p.name.name);
                        subject.args.push(Arg::new(n.clone(), kind, &label, constraint.clone()));
                        params.push(format!("varying {ty} {n} = {}", zero(kind)));
                    }
                    locals.push_str(&format!("    {ty} l{k}[{len}] = {{ {} }};\n", names.join(", ")));
                }
            }
            let arg = if p.array.is_some() { format!("l{k}") } else { format!("a{k}") };
            if p.qualifiers.output.is_some() {
                if p.array.is_some() {
                    return Err("an output array parameter".into());
                }
                locals.push_str(&format!("    {ty} o{k} = a{k};\n"));
                params.push(format!("output varying {ty} out{k} = {}", zero(kind)));
                copies.push_str(&format!("    out{k} = o{k};\n"));
                subject.outputs.push(format!("out{k}"));
                call.push(format!("o{k}"));
            } else {
                call.push(arg);
            }
        }
        let call = format!("{}({})", f.name.name, call.join(", "));
        let body = match f.return_type.name {
            TypeName::Void => format!("{locals}    {call};\n{copies}"),
            ret => {
                let kind = Kind::of(ret).ok_or_else(|| format!("a {} result", ret.keyword()))?;
                params.push(format!("output varying {} result = {}", ret.keyword(), zero(kind)));
                subject.outputs.insert(0, "result".into());
                format!("{locals}    result = {call};\n{copies}")
            }
        };
        if subject.outputs.is_empty() {
            return Err("no result and no output parameter".into());
        }
        let source = format!("{text}\n\nsurface {WRAPPER}({})\n{{\n{body}}}\n", params.join(";\n    "));
        Ok(Build { source, shader: WRAPPER.to_string() })
    })();
    subject
}

/// The literal zero of a kind (a `uint` needs its suffix).
fn zero(kind: Kind) -> &'static str {
    if kind == Kind::Uint { "0u" } else { "0" }
}

fn shader(file: &str, text: &str, s: &ShaderDef, pre: &[Precondition]) -> Subject {
    let label = format!("surface {}", s.name.name);
    let mut subject =
        Subject { file: file.to_string(), label, args: vec![], outputs: vec![], build: Err(String::new()) };
    subject.build = (|| {
        check_preconditions(pre)?;
        for p in &s.params {
            // Outputs are not inputs; strings (texture and space names) keep their defaults.
            if p.qualifiers.output.is_some() || matches!(p.ty.name, TypeName::String | TypeName::Texref) {
                continue;
            }
            let kind = Kind::of(p.ty.name).ok_or_else(|| format!("a {} parameter", p.ty.name.keyword()))?;
            if p.array.is_some() {
                return Err("an array parameter".into());
            }
            let constraint = preconditions::for_param(pre, &p.name.name);
            subject.args.push(Arg::new(p.name.name.to_string(), kind, p.name.name.as_str(), constraint));
        }
        let renderman = s.style == ShaderStyle::RenderMan;
        for (name, kind) in [
            ("P", Kind::Point),
            ("N", Kind::Normal),
            ("I", Kind::Vector),
            ("s", Kind::Float),
            ("t", Kind::Float),
        ] {
            // A Stanford shader reads what it declares; RenderMan's predefined variables are there.
            if renderman {
                subject.args.push(Arg::new(
                    name.to_string(),
                    kind,
                    name,
                    preconditions::for_param(pre, name),
                ));
            }
        }
        // The surface colour and opacity are a renderer's defaults, white and opaque, on every
        // backend (unset, the interpreter and the kernel would start them differently).
        if renderman {
            for name in ["Cs", "Os"] {
                let white = preconditions::Constraint { values: Some(vec![1.0]), ..Default::default() };
                subject.args.push(Arg::new(name.to_string(), Kind::Color, name, white));
            }
        }
        subject.outputs = if renderman { vec!["Ci".into(), "Oi".into()] } else { vec!["result".into()] };
        Ok(Build { source: text.to_string(), shader: s.name.name.to_string() })
    })();
    subject
}

impl Build {
    /// Checks the source and compiles the subject's shader for the interpreter.
    pub fn compile(&self, name: &str, loader: &dyn SourceLoader) -> Result<Compiled, String> {
        let checked = patina_compiler::check_source(name, &self.source, loader);
        if let Some(d) = checked.diagnostics.iter().find(|d| d.is_error()) {
            return Err(format!("the sweep's shader does not check: {}: {}", d.code, d.message));
        }
        let shader = checked
            .program
            .shaders
            .into_iter()
            .find(|s| s.name == self.shader)
            .ok_or_else(|| format!("no shader `{}` after checking", self.shader))?;
        let shader = Prepared::new(shader);
        let cpu = CpuProgram::compile(&shader, &Binding::default())
            .map_err(|d| format!("{}: {}", d.code, d.message))?;
        Ok(Compiled { shader, cpu })
    }
}
