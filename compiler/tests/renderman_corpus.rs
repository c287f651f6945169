//! Constructs that real RenderMan shaders use (the kind of code in Aqsis's shader set), each written
//! here in a few lines of our own: contextual Stanford keywords, the optional parameter lists of the
//! texture calls, `printf` and `format`, uniform `random()`, `option()`, `bake()` and Latin-1 files.

use patina_compiler::check_source;
use patina_compiler::diag::{Severity, render_text};
use patina_compiler::syntax::preprocess::MemoryLoader;

/// Checks `src`; returns the error codes, the warning messages and the rendered diagnostics.
fn run(src: &str) -> (Vec<&'static str>, Vec<String>, String) {
    let checked = check_source("shader.sl", src, &MemoryLoader::default());
    let list: Vec<_> = checked.diagnostics.iter().cloned().collect();
    let errors = list.iter().filter(|d| d.severity == Severity::Error).map(|d| d.code.as_str()).collect();
    let warnings =
        list.iter().filter(|d| d.severity == Severity::Warning).map(|d| d.message.clone()).collect();
    (errors, warnings, render_text(&checked.sources, &list))
}

#[test]
fn stanford_keywords_are_names_in_renderman_files() {
    let src = "surface constant(float int = 1; float vertex = 2) {\n    float light = int + vertex;\n    float fragment = light;\n    Ci = Cs * fragment;\n}\n";
    let (errors, _, text) = run(src);
    assert!(errors.is_empty(), "{text}");
    let checked = check_source("shader.sl", src, &MemoryLoader::default());
    assert_eq!(checked.program.shaders[0].name, "constant");
}

#[test]
fn stanford_keywords_stay_keywords_in_stanford_files() {
    let (errors, _, text) = run("surface shader float4 s(float int = 1) { return float4(1, 1, 1, 1); }\n");
    assert_eq!(errors.first(), Some(&"E0306"), "{text}");
}
