//! The documents agree with the code: every error code is in docs/language.md's table, every
//! built-in in docs/builtins.md, and every path ARCHITECTURE.md names exists. A code, built-in or
//! file added or renamed without its document fails here.

use patina_compiler::diag::Code;
use patina_compiler::sema::builtins::builtins;

/// The text of a file at the repository's root.
fn document(name: &str) -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    std::fs::read_to_string(format!("{path}/{name}")).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn every_error_code_is_in_the_language_reference() {
    let language = document("docs/language.md");
    let missing: Vec<&str> =
        Code::ALL.iter().map(|c| c.as_str()).filter(|c| !language.contains(&format!("| {c} |"))).collect();
    assert!(missing.is_empty(), "codes without a row in docs/language.md: {missing:?}");
}

#[test]
fn every_builtin_is_in_the_builtin_reference() {
    let reference = document("docs/builtins.md");
    // `__` names are the compiler's own (texel reads, uniform random), not the language's. A name
    // is documented by a signature (`float sin(float)`) or, in a row of alike ones, by itself
    // (`acos`).
    let documented = |n: &str| {
        [format!(" {n}("), format!("`{n}("), format!("`{n}`")].iter().any(|f| reference.contains(f))
    };
    let mut missing: Vec<&str> =
        builtins().names().filter(|n| !n.starts_with("__") && !documented(n)).collect();
    missing.sort_unstable();
    assert!(missing.is_empty(), "built-ins without a signature in docs/builtins.md: {missing:?}");
}

#[test]
fn every_path_in_architecture_exists() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let architecture = document("ARCHITECTURE.md");
    // Paths are written from the repository's root or, in a crate's table, from its source folder.
    let bases = ["", "compiler/src/", "runtime/src/", "compiler/", "runtime/"];
    let is_path_char = |c: char| c.is_ascii_alphanumeric() || "_./-".contains(c);
    let mut named = 0;
    let mut missing = Vec::new();
    for quoted in architecture.split('`').skip(1).step_by(2) {
        if !quoted.contains('/') || quoted == "/" || !quoted.chars().all(is_path_char) {
            continue;
        }
        named += 1;
        if !bases.iter().any(|b| std::path::Path::new(&format!("{root}/{b}{quoted}")).exists()) {
            missing.push(quoted);
        }
    }
    assert!(named > 50, "only {named} paths found: the scan no longer reads ARCHITECTURE.md's form");
    assert!(missing.is_empty(), "ARCHITECTURE.md names paths that do not exist: {missing:?}");
}

#[test]
fn the_builtin_reference_counts_the_table() {
    // docs/builtins.md opens with "N overloads under M names" (the language's, not the
    // compiler's own `__` names).
    let table = builtins();
    let names: Vec<&str> = table.names().filter(|n| !n.starts_with("__")).collect();
    let overloads: usize = names.iter().map(|n| table.overloads(n).len()).sum();
    let line = format!("{overloads} overloads under {} names.", names.len());
    assert!(document("docs/builtins.md").contains(&line), "docs/builtins.md should say: {line}");
}
