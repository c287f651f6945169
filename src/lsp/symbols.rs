//! What each name in a checked document refers to, read off the compiler's own results.
//!
//! Nothing here resolves a name: the semantic stage already did, and its typed IR says which
//! local each expression reads, which predefined variable, which function was inlined at a call
//! and which built-in was called. This index only records where those names were written, so
//! that hover, go-to-definition and the semantic tokens agree with `patina check` by construction.

use rustc_hash::FxHashMap;
use smol_str::SmolStr;

use patina_compiler::ir::global::Global;
use patina_compiler::ir::{ExprId, ExprKind, LocalId, LocalKind, Place, Shader, Stmt};
use patina_compiler::sema::builtins::builtins;
use patina_compiler::source::{FileId, SourceMap, Span};
use patina_compiler::stdlib;
use patina_compiler::syntax::ast::{Item, Module};

/// What a name refers to.
#[derive(Clone, Debug, PartialEq)]
pub enum Referent {
    /// A variable or parameter, identified by the span of the name in its declaration.
    Variable(Span),
    /// A predefined variable (`P`, `Ci`, ...).
    Global(&'static Global),
    /// A function written in the language (the file's, an included file's or the standard
    /// library's), by name: all its overloads.
    Function(SmolStr),
    /// A built-in function, and for one written in the language (`noise`, ...) where the
    /// implementation this call was inlined from is (`compiler/stdlib/builtins.sl`).
    Builtin(&'static str, Option<Span>),
}

/// One place a name is written.
#[derive(Clone, Debug, PartialEq)]
pub struct Occurrence {
    /// The name as written.
    pub span: Span,
    /// What it refers to.
    pub referent: Referent,
    /// Whether this is the name's declaration.
    pub declaration: bool,
}

/// One copy of a variable in the IR: a file-level variable is in every shader, and a function's
/// variables are in every inlined call of it, each copy with its own rate.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Instance {
    /// The shader, as numbered by [`super::analysis::Analysis::shader`].
    pub shader: usize,
    /// The local in that shader.
    pub local: LocalId,
}

/// Every name of a compilation, by file and position.
#[derive(Default)]
pub struct Symbols {
    /// Sorted by file and start, without duplicates (several shaders see the same text).
    occurrences: Vec<Occurrence>,
    /// The copies of each variable, by its declaration.
    variables: FxHashMap<Span, Vec<Instance>>,
}

impl Symbols {
    /// Indexes `shaders` (the program's, then those with errors) and `module`'s definitions.
    pub fn build(sources: &SourceMap, module: &Module, shaders: &[&Shader]) -> Symbols {
        let mut index = Symbols::default();
        for (s, shader) in shaders.iter().enumerate() {
            for (i, local) in shader.locals.iter().enumerate() {
                if local.kind == LocalKind::Temp {
                    continue;
                }
                let local_id = LocalId(i as u32);
                index.variables.entry(local.span).or_default().push(Instance { shader: s, local: local_id });
                index.push(local.span, Referent::Variable(local.span), true);
            }
            for expr in &shader.exprs {
                match &expr.kind {
                    ExprKind::Local(id) if shader.local(*id).kind != LocalKind::Temp => {
                        index.push(expr.span, Referent::Variable(shader.local(*id).span), false);
                    }
                    ExprKind::Global(g) => index.push(expr.span, Referent::Global(g), false),
                    ExprKind::Builtin(b, _) => index.call(sources, expr.span, b.name(), None),
                    _ => {}
                }
            }
            index.statements(sources, shader, &shader.body);
        }
        for item in &module.items {
            if let Item::Function(f) = item {
                index.push(f.name.span, Referent::Function(f.name.name.clone()), true);
            }
        }
        index.occurrences.sort_by_key(|o| (o.span.file, o.span.start, o.span.end));
        index.occurrences.dedup();
        index
    }

    /// The names written in statements: the targets of assignments (a store keeps no expression
    /// for its target) and the functions of inlined calls.
    fn statements(&mut self, sources: &SourceMap, shader: &Shader, block: &[Stmt]) {
        for stmt in block {
            match stmt {
                Stmt::Store { place, span, .. } => {
                    let mut root = place;
                    while let Place::Index(inner, _) = root {
                        root = inner;
                    }
                    let (name, referent) = match root {
                        Place::Local(id) if shader.local(*id).kind != LocalKind::Temp => {
                            let local = shader.local(*id);
                            (local.name.as_str(), Referent::Variable(local.span))
                        }
                        Place::Global(g) => (g.name, Referent::Global(g)),
                        _ => continue,
                    };
                    // An assignment's span starts with its target. A parameter's store spans the
                    // argument, which may be a variable of the same name: that is the caller's.
                    if span.end - span.start > name.len() as u32 && ident_at(sources, *span) == name {
                        let at = Span { end: span.start + name.len() as u32, ..*span };
                        self.push(at, referent, false);
                    }
                }
                Stmt::Inline { function, span, body } => {
                    let called = ident_at(sources, *span);
                    if called == function.as_str() {
                        let at = Span { end: span.start + called.len() as u32, ..*span };
                        self.push(at, Referent::Function(function.clone()), false);
                    } else if let Some(b) = builtins().overloads(called).first() {
                        // A built-in written in the language, inlined as its implementation.
                        self.call(sources, *span, b.name(), implementation(sources, shader, body));
                    }
                }
                _ => {}
            }
            stmt.for_each_block(|inner| self.statements(sources, shader, inner));
        }
    }

    /// A call of the built-in `name` at `span`, if the span starts with the name as written
    /// (not with the type of `color noise(P)`, say).
    fn call(&mut self, sources: &SourceMap, span: Span, name: &'static str, implementation: Option<Span>) {
        if ident_at(sources, span) == name {
            let at = Span { end: span.start + name.len() as u32, ..span };
            self.push(at, Referent::Builtin(name, implementation), false);
        }
    }

    fn push(&mut self, span: Span, referent: Referent, declaration: bool) {
        self.occurrences.push(Occurrence { span, referent, declaration });
    }

    /// The name written at byte `offset` of `file` (either end of the name included).
    pub fn at(&self, file: FileId, offset: u32) -> Option<&Occurrence> {
        self.in_file(file)
            .filter(|o| o.span.contains_offset(offset))
            .min_by_key(|o| o.span.end - o.span.start)
    }

    /// The names written in `file`, in order.
    pub fn in_file(&self, file: FileId) -> impl Iterator<Item = &Occurrence> {
        let from = self.occurrences.partition_point(|o| o.span.file < file);
        self.occurrences[from..].iter().take_while(move |o| o.span.file == file)
    }

    /// The copies of the variable declared at `declaration`.
    pub fn instances(&self, declaration: Span) -> &[Instance] {
        self.variables.get(&declaration).map_or(&[], Vec::as_slice)
    }

    /// Every variable declared in `file`, by its declaration.
    pub fn variables_in(&self, file: FileId) -> impl Iterator<Item = (&Span, &[Instance])> {
        self.variables.iter().filter(move |(s, _)| s.file == file).map(|(s, i)| (s, i.as_slice()))
    }
}

/// Where the standard-library code inlined as `body` was written: its first value computed in a
/// library file (the parameters' stores before it compute the caller's arguments), lifted out of
/// the macros that generate the implementations to the line that instantiates them.
fn implementation(sources: &SourceMap, shader: &Shader, body: &[Stmt]) -> Option<Span> {
    let in_library = |e: ExprId| {
        let mut span = shader.expr(e).span;
        while span.expn.is_macro() {
            span = sources.call_site(span);
        }
        sources.file(span.file).name.starts_with(stdlib::PREFIX).then_some(span)
    };
    body.iter().find_map(|stmt| match stmt {
        Stmt::Store { value, .. } | Stmt::Eval(value) => in_library(*value),
        _ => {
            let mut found = None;
            stmt.for_each_block(|inner| found = found.or_else(|| implementation(sources, shader, inner)));
            found
        }
    })
}

/// The identifier `span` starts with.
fn ident_at(sources: &SourceMap, span: Span) -> &str {
    let text = &*sources.file(span.file).text;
    let rest = text.get(span.start as usize..).unwrap_or("");
    let end = rest.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(rest.len());
    &rest[..end]
}
