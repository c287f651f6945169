//! `patina lsp`: the language server, over stdin and stdout (see `src/lsp/`).

use std::process::ExitCode;

use patina_compiler::syntax::preprocess::FsLoader;

use super::LspArgs;

/// Serves one editor session on stdin and stdout, until the editor says `exit`.
pub fn run(args: LspArgs) -> Result<ExitCode, String> {
    let loader = FsLoader { include_dirs: args.include };
    // The reader thread owns stdin; `Stdin` (unlike its lock) can be sent to it.
    let stdin = std::io::BufReader::new(std::io::stdin());
    let stdout = std::io::stdout().lock();
    match crate::lsp::serve(stdin, stdout, loader) {
        Ok(true) => Ok(ExitCode::SUCCESS),
        // `exit` without `shutdown`, or the client went away: the protocol asks for status 1.
        Ok(false) => Ok(ExitCode::FAILURE),
        Err(e) => Err(format!("the editor's connection failed: {e}")),
    }
}
