//! Functions written in the language (the document's, its includes', the standard library's):
//! their definitions, signatures and documentation, as hover and completion show them.

use patina_compiler::source::{SourceMap, comment_above};
use patina_compiler::syntax::ast::{FunctionDef, Item, Module};

/// The top-level functions named `name` (every overload), in source order.
pub fn named<'a>(module: &'a Module, name: &str) -> Vec<&'a FunctionDef> {
    all(module).filter(|f| f.name.name == name).collect()
}

/// Every top-level function of the module, its includes' and the standard library's included.
pub fn all(module: &Module) -> impl Iterator<Item = &FunctionDef> {
    module.items.iter().filter_map(|item| if let Item::Function(f) = item { Some(&**f) } else { None })
}

/// The function's signature as written, on one line: `float fbm(point p; float H, lacunarity,
/// octaves)`.
pub fn signature(sources: &SourceMap, f: &FunctionDef) -> String {
    let text = &*sources.file(f.span.file).text;
    let head = text.get(f.span.start as usize..f.span.end as usize).unwrap_or("");
    let after_name = (f.name.span.end.saturating_sub(f.span.start)) as usize;
    // The parameter list ends at the parenthesis that closes the first one after the name.
    let mut depth = 0usize;
    let mut end = None;
    for (at, c) in head.char_indices().skip_while(|(at, _)| *at < after_name) {
        match c {
            '(' => depth += 1,
            ')' if depth == 1 => {
                end = Some(at + 1);
                break;
            }
            ')' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    match end {
        // A definition made by a macro has no text of its own to show.
        Some(end) if !f.span.expn.is_macro() => head[..end].split_whitespace().collect::<Vec<_>>().join(" "),
        _ => format!("{}(...)", f.name.name),
    }
}

/// The comment block directly above the definition: its documentation.
pub fn documentation(sources: &SourceMap, f: &FunctionDef) -> String {
    let text = &*sources.file(f.span.file).text;
    comment_above(text, f.span.start as usize).join("\n")
}

#[cfg(test)]
mod tests {
    use patina_compiler::check_source;
    use patina_compiler::syntax::preprocess::MemoryLoader;

    use super::*;

    #[test]
    fn the_stdlib_signature_and_documentation_are_read_from_its_source() {
        let checked = check_source("t.sl", "#include <fractal.sl>\n", &MemoryLoader::default());
        let fbm = named(&checked.module, "fbm");
        assert_eq!(fbm.len(), 1);
        assert_eq!(signature(&checked.sources, fbm[0]), "float fbm(point p; float H, lacunarity, octaves)");
        assert!(documentation(&checked.sources, fbm[0]).starts_with("Musgrave's fBm"));
    }
}
