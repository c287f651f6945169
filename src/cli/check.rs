//! `patina check`: parse and check files, print diagnostics, fail on errors.

use std::io::{IsTerminal, Write};
use std::process::ExitCode;

use codespan_reporting::term::{self, termcolor};
use patina_compiler::diag::{self, Diagnostic};

use super::{CheckArgs, ColorChoice, OutputFormat};

pub fn run(args: CheckArgs) -> Result<ExitCode, String> {
    let color = match args.color {
        ColorChoice::Always => termcolor::ColorChoice::Always,
        ColorChoice::Never => termcolor::ColorChoice::Never,
        ColorChoice::Auto if std::io::stderr().is_terminal() => termcolor::ColorChoice::Auto,
        ColorChoice::Auto => termcolor::ColorChoice::Never,
    };
    let mut stderr = termcolor::StandardStream::stderr(color);
    let mut stdout = std::io::stdout().lock();
    let (mut errors, mut warnings, mut unreadable) = (0usize, 0usize, 0usize);
    for path in &args.files {
        let checked = match patina_compiler::check_file(path, &args.include) {
            Ok(checked) => checked,
            Err(e) => {
                eprintln!("error: {e}");
                unreadable += 1;
                continue;
            }
        };
        let list: Vec<Diagnostic> = checked.diagnostics.iter().cloned().collect();
        errors += list.iter().filter(|d| d.is_error()).count();
        warnings += list.iter().filter(|d| !d.is_error()).count();
        match args.format {
            OutputFormat::Json => {
                let _ = stdout.write_all(diag::render_json(&checked.sources, &list).as_bytes());
            }
            OutputFormat::Human => {
                let config = term::Config::default();
                for d in &list {
                    let cs = diag::to_codespan(&checked.sources, d);
                    let _ = term::emit_to_write_style(&mut stderr, &config, &checked.sources, &cs);
                }
            }
        }
    }
    if args.format == OutputFormat::Human && (errors > 0 || warnings > 0) {
        let files = args.files.len();
        eprintln!(
            "{}: {errors} error{}, {warnings} warning{} in {files} file{}",
            if errors > 0 { "failed" } else { "ok" },
            if errors == 1 { "" } else { "s" },
            if warnings == 1 { "" } else { "s" },
            if files == 1 { "" } else { "s" },
        );
    }
    Ok(if errors > 0 || unreadable > 0 { ExitCode::FAILURE } else { ExitCode::SUCCESS })
}
