//! The semantic stage: names, types, overloads and rates. Lowers the AST to the typed IR.
//!
//! `lower` decides types and inlines user functions into each shader; `rates` then decides every
//! value's rate and checks the declared ones. `explain` prints what was decided.

pub mod builtins;
pub mod convert;
pub mod explain;
pub mod globals;
mod lower;
pub mod rates;
pub mod unsupported;

use rustc_hash::FxHashMap;

use crate::diag::{Code, Diagnostic, Diagnostics};
use crate::ir::Program;
use crate::syntax::ast::{self, Item};
use crate::verify::Pass;
use lower::{FunctionTable, Functions};

/// Collects the module's top-level functions, reporting duplicates. (Functions defined inside
/// bodies are scoped to them; the lowering handles those.)
fn functions<'a>(module: &'a ast::Module, diags: &mut Diagnostics) -> FunctionTable<'a> {
    let all: Vec<&ast::FunctionDef> = module
        .items
        .iter()
        .filter_map(|i| if let Item::Function(f) = i { Some(&**f) } else { None })
        .collect();
    let mut table: FunctionTable<'a> = FxHashMap::default();
    for f in all {
        let signature = |f: &ast::FunctionDef| -> Vec<(ast::TypeName, Option<u32>)> {
            f.params.iter().map(|p| (p.ty.name, p.array.map(|a| a.len.unwrap_or(0)))).collect()
        };
        let overloads = table.entry(f.name.name.clone()).or_default();
        if let Some(previous) = overloads.iter().find(|g| signature(g) == signature(f)) {
            diags.push(
                Diagnostic::error(
                    Code::Redefinition,
                    format!("function `{}` is defined twice with the same parameter types", f.name.name),
                    f.name.span,
                    "defined again here",
                )
                .with_label(previous.name.span, "first defined here"),
            );
            continue;
        }
        overloads.push(f);
    }
    table
}

/// What [`check`] found.
pub struct Checked {
    /// The shaders without errors.
    pub program: Program,
    /// The shaders with errors, lowered as far as they went (see [`crate::Checked::incomplete`]).
    pub incomplete: Vec<crate::ir::Shader>,
    /// Whether the module calls a built-in written in the language (`compiler/stdlib/builtins.sl`) while
    /// `library` was not given: check again with it.
    pub wants_library: bool,
}

/// Checks a parsed module and lowers each of its shaders to the typed IR. Shaders with errors are
/// left out of the program; their diagnostics are in `diags`. `library` is the parsed
/// `compiler/stdlib/builtins.sl`, whose functions implement the library built-ins.
/// `stdlib_files` are the files of the standard library among those the module was read from.
pub fn check(
    module: &ast::Module,
    library: Option<&ast::Module>,
    stdlib_files: rustc_hash::FxHashSet<crate::source::FileId>,
    diags: &mut Diagnostics,
) -> Checked {
    let table = Functions {
        user: functions(module, diags),
        library: library.map(|l| functions(l, diags)).unwrap_or_default(),
        stdlib_files,
    };
    let globals: Vec<&ast::VarDecl> = module
        .items
        .iter()
        .filter_map(|i| if let Item::Variable(v) = i { Some(&**v) } else { None })
        .collect();
    let mut program = Program::default();
    let mut incomplete = Vec::new();
    let mut shared = lower::Shared::default();
    for item in &module.items {
        let Item::Shader(s) = item else { continue };
        match lower::lower_shader(s, &globals, &table, &mut shared, diags) {
            (mut shader, false) => {
                crate::verify::assert_valid(&shader, Pass::Lower);
                let errors = diags.iter().filter(|d| d.is_error()).count();
                rates::infer(&mut shader, diags);
                // A shader with rate errors keeps values its variables' rates do not allow; the
                // caller sees the errors and goes no further.
                if diags.iter().filter(|d| d.is_error()).count() == errors {
                    crate::verify::assert_valid(&shader, Pass::Rates);
                }
                program.shaders.push(shader);
            }
            // Rates are inferred for tools, which show them while the user fixes the errors;
            // what the check says about a body with parts missing would only mislead.
            (mut partial, true) => {
                rates::infer(&mut partial, &mut Diagnostics::default());
                incomplete.push(partial);
            }
        }
    }
    // Functions are checked where they are inlined; the ones no shader calls (all of them, in a
    // library module) are checked on their own so that their errors are reported too. An included
    // standard-library module is not: it checks clean on its own (a test in `stdlib.rs` says so),
    // and its functions are RenderMan-style, which a Stanford-style file would misread.
    let mut unused: Vec<&ast::FunctionDef> = table
        .user
        .values()
        .flatten()
        .copied()
        .filter(|f| !shared.inlined.contains(&f.span) && !table.stdlib_files.contains(&f.span.file))
        .collect();
    unused.sort_by_key(|f| (f.span.file, f.span.start));
    // A function outside any shader is read in the file's style (Stanford if its shaders are).
    let stanford = module
        .items
        .iter()
        .any(|i| matches!(i, Item::Shader(s) if !matches!(s.style, ast::ShaderStyle::RenderMan)))
        && !module
            .items
            .iter()
            .any(|i| matches!(i, Item::Shader(s) if matches!(s.style, ast::ShaderStyle::RenderMan)));
    for f in unused {
        lower::check_function(f, stanford, &globals, &table, &mut shared, diags);
    }
    Checked { program, incomplete, wants_library: shared.wants_library }
}
