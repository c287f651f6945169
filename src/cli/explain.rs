//! `patina explain`: what the compiler decided about each shader of a file (or, for a scene,
//! `explain_scene.rs`).

use std::process::ExitCode;

use patina_compiler::sema::explain::explain;

use super::ExplainArgs;

pub fn run(args: ExplainArgs) -> Result<ExitCode, String> {
    if args.file.extension().is_some_and(|e| e == "toml") {
        return super::explain_scene::run(&args.file);
    }
    let checked = patina_compiler::check_file(&args.file, &args.include).map_err(|e| e.to_string())?;
    eprint!("{}", checked.diagnostics_text());
    print!("{}", explain(&checked.program));
    Ok(if checked.has_errors() { ExitCode::FAILURE } else { ExitCode::SUCCESS })
}
