//! Declarations in the syntax tree: which are visible at a position (for completion, which must
//! work on text the semantic stage has not seen yet) and how each was written (for the inlay
//! hints, which show a rate only where the source does not say it).
//!
//! This reads the tree's block structure; it decides no types or rates, which come from the IR.

use patina_compiler::source::{FileId, Span};
use patina_compiler::syntax::ast::{
    FunctionDef, Ident, Item, Module, Param, Qualifiers, Stmt, StmtKind, TypeSpec, VarDecl,
};

/// A declared variable or parameter, as written.
#[derive(Copy, Clone, Debug)]
pub struct Declared<'a> {
    /// Its name.
    pub name: &'a Ident,
    /// Its type.
    pub ty: &'a TypeSpec,
    /// Its qualifiers (a rate, `output`, ...).
    pub qualifiers: &'a Qualifiers,
    /// Whether it is a shader's or function's parameter.
    pub parameter: bool,
}

/// Every declaration of the module, nested ones included, in source order within each definition.
pub fn all(module: &Module) -> Vec<Declared<'_>> {
    let mut out = Vec::new();
    for item in &module.items {
        match item {
            Item::Variable(v) => variables(v, &mut out),
            Item::Shader(s) => {
                params(&s.params, &mut out);
                s.body.stmts.iter().for_each(|st| every(st, &mut out));
            }
            Item::Function(f) => function(f, &mut out),
            Item::Error(_) => {}
        }
    }
    out
}

/// The declarations visible at byte `offset` of `file`: the file's variables declared before it
/// (and those of the files it includes), then the parameters and the variables of the enclosing
/// shader or function and of its blocks around the position, declared before it.
pub fn visible(module: &Module, file: FileId, offset: u32) -> Vec<Declared<'_>> {
    let inside = |span: Span| span.file == file && span.start < offset && offset <= span.end;
    let mut out = Vec::new();
    for item in &module.items {
        match item {
            Item::Variable(v) if v.span.file != file || v.span.end <= offset => variables(v, &mut out),
            Item::Shader(s) if inside(s.span) => {
                params(&s.params, &mut out);
                s.body.stmts.iter().for_each(|st| before(st, &inside, offset, &mut out));
            }
            Item::Function(f) if inside(f.span) => {
                params(&f.params, &mut out);
                f.body.stmts.iter().for_each(|st| before(st, &inside, offset, &mut out));
            }
            _ => {}
        }
    }
    out
}

/// The declaration the name `name` written at byte `offset` of `file` refers to by the blocks
/// around it (the innermost visible one), or that it is. For names the IR does not know: those
/// in a function no shader calls, which the compiler checks on its own and keeps no IR of.
pub fn declaration<'a>(module: &'a Module, file: FileId, offset: u32, name: &str) -> Option<Declared<'a>> {
    let here = |d: &Declared<'_>| {
        d.name.name == name && d.name.span.file == file && d.name.span.contains_offset(offset)
    };
    all(module)
        .into_iter()
        .find(here)
        .or_else(|| visible(module, file, offset).into_iter().rev().find(|d| d.name.name == name))
}

/// The declarations of `stmt` visible at `offset`: its own if it ends before, those of the blocks
/// around the position.
fn before<'a>(stmt: &'a Stmt, inside: &dyn Fn(Span) -> bool, offset: u32, out: &mut Vec<Declared<'a>>) {
    match &stmt.kind {
        StmtKind::Decl(v) if stmt.span.end <= offset => variables(v, out),
        StmtKind::Block(b) if inside(b.span) => b.stmts.iter().for_each(|s| before(s, inside, offset, out)),
        StmtKind::If { then, otherwise, .. } => {
            before(then, inside, offset, out);
            if let Some(o) = otherwise {
                before(o, inside, offset, out);
            }
        }
        StmtKind::For { init, body, .. } if inside(stmt.span) => {
            if let Some(init) = init {
                before(init, inside, offset, out);
            }
            before(body, inside, offset, out);
        }
        StmtKind::While { body, .. }
        | StmtKind::Illuminance { body, .. }
        | StmtKind::Illuminate { body, .. }
        | StmtKind::Solar { body, .. } => before(body, inside, offset, out),
        StmtKind::Function(f) if inside(f.span) => {
            params(&f.params, out);
            f.body.stmts.iter().for_each(|s| before(s, inside, offset, out));
        }
        _ => {}
    }
}

/// Every declaration inside `stmt`.
fn every<'a>(stmt: &'a Stmt, out: &mut Vec<Declared<'a>>) {
    match &stmt.kind {
        StmtKind::Decl(v) => variables(v, out),
        StmtKind::Block(b) => b.stmts.iter().for_each(|s| every(s, out)),
        StmtKind::Function(f) => function(f, out),
        StmtKind::If { then, otherwise, .. } => {
            every(then, out);
            if let Some(o) = otherwise {
                every(o, out);
            }
        }
        StmtKind::For { init, body, .. } => {
            if let Some(init) = init {
                every(init, out);
            }
            every(body, out);
        }
        StmtKind::While { body, .. }
        | StmtKind::Illuminance { body, .. }
        | StmtKind::Illuminate { body, .. }
        | StmtKind::Solar { body, .. } => every(body, out),
        StmtKind::Gather { body, otherwise, .. } => {
            every(body, out);
            if let Some(o) = otherwise {
                every(o, out);
            }
        }
        _ => {}
    }
}

fn function<'a>(f: &'a FunctionDef, out: &mut Vec<Declared<'a>>) {
    params(&f.params, out);
    f.body.stmts.iter().for_each(|s| every(s, out));
}

fn params<'a>(params: &'a [Param], out: &mut Vec<Declared<'a>>) {
    out.extend(params.iter().map(|p| Declared {
        name: &p.name,
        ty: &p.ty,
        qualifiers: &p.qualifiers,
        parameter: true,
    }));
}

fn variables<'a>(v: &'a VarDecl, out: &mut Vec<Declared<'a>>) {
    out.extend(v.declarators.iter().map(|d| Declared {
        name: &d.name,
        ty: &v.ty,
        qualifiers: &v.qualifiers,
        parameter: false,
    }));
}

#[cfg(test)]
mod tests {
    use patina_compiler::check_source;
    use patina_compiler::syntax::preprocess::MemoryLoader;

    use super::*;

    #[test]
    fn only_the_blocks_around_the_position_are_visible() {
        let text = "float g = 1;\nsurface s(float Kd = 1) {\n    { float gone = 1; }\n    float a = 2;\n    if (a > 1) { float b = a; }\n    float c = 3; // here\n    float after = 4;\n}\n";
        let checked = check_source("t.sl", text, &MemoryLoader::default());
        let at = text.find("// here").unwrap() as u32;
        let names: Vec<&str> =
            visible(&checked.module, checked.root, at).iter().map(|d| d.name.name.as_str()).collect();
        assert_eq!(names, ["g", "Kd", "a", "c"]);
        let all: Vec<&str> = super::all(&checked.module).iter().map(|d| d.name.name.as_str()).collect();
        assert_eq!(all, ["g", "Kd", "gone", "a", "b", "c", "after"]);
    }
}
