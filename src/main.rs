//! The `patina` command line.

mod cli;
mod lsp;

use std::process::ExitCode;

use clap::Parser;

// The front end allocates a tree node per expression; mimalloc makes that about a fifth faster
// than the system allocator (see compiler/benches/parse.rs).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(code) => code,
        Err(message) => {
            // A shader's rendered diagnostics name their own severity.
            if message.starts_with("error[") {
                eprintln!("{message}");
            } else {
                eprintln!("error: {message}");
            }
            ExitCode::from(2)
        }
    }
}
