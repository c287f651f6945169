//! `patina explain`: what the compiler decided about each shader of a file (or, for a scene,
//! `explain_scene.rs`).

use std::process::ExitCode;

use patina_compiler::diag;
use patina_compiler::sema::explain::explain;
use patina_compiler::syntax::preprocess::{FsLoader, read_source_file};

use super::ExplainArgs;

pub fn run(args: ExplainArgs) -> Result<ExitCode, String> {
    if args.file.extension().is_some_and(|e| e == "toml") {
        return super::explain_scene::run(&args.file);
    }
    let name = args.file.to_string_lossy().into_owned();
    let text = match read_source_file(&args.file) {
        Ok(Some(text)) => text,
        Ok(None) => return Err(format!("cannot read `{name}`: no such file")),
        Err(reason) => return Err(format!("cannot read `{name}`: {reason}")),
    };
    let loader = FsLoader { include_dirs: args.include };
    let checked = patina_compiler::check_source(&name, &text, &loader);
    let list = checked.diagnostics.clone().into_vec();
    if !list.is_empty() {
        eprint!("{}", diag::render_text(&checked.sources, &list));
    }
    print!("{}", explain(&checked.program));
    Ok(if checked.has_errors() { ExitCode::FAILURE } else { ExitCode::SUCCESS })
}
