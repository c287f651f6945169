//! The lexer, preprocessor and parser on arbitrary text: any input gives a tree and diagnostics,
//! never a panic. Includes resolve only in memory (one file, `inc.h`) and the embedded stdlib.
#![no_main]

use libfuzzer_sys::fuzz_target;
use patina_compiler::diag::Diagnostics;
use patina_compiler::source::SourceMap;
use patina_compiler::syntax::preprocess::MemoryLoader;

fuzz_target!(|data: &[u8]| {
    // The compiler reads text; bytes that are not UTF-8 are rejected before it (read_source_file).
    let Ok(text) = std::str::from_utf8(data) else { return };
    // A file that includes itself exercises the include-depth limit.
    let loader = MemoryLoader::default().with_file("inc.h", text);
    let mut sources = SourceMap::new();
    let root = sources.add_file("fuzz.sl", text, None);
    let mut diags = Diagnostics::default();
    let _module = patina_compiler::syntax::parse_file(&mut sources, root, &loader, &mut diags);
    // Rendering touches every span: one out of its file's bounds would panic here.
    let list: Vec<_> = diags.iter().cloned().collect();
    let _ = patina_compiler::diag::render_text(&sources, &list);
});
