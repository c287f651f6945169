//! Inputs the fuzz targets (fuzz/, CONTRIBUTING.md) found crashing, hanging or running out of
//! memory, minimised, each with the diagnostic or result it must give now.

use std::sync::mpsc;
use std::thread;
use std::time::Duration;

use patina_compiler::diag::{Code, Diagnostic};
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_compiler::{Checked, check_source};

/// Checks `src` on a thread and waits at most `limit` for it: the regressions here were hangs.
fn check_within(src: &'static str, loader: MemoryLoader, limit: Duration) -> Checked {
    let (send, receive) = mpsc::channel();
    thread::spawn(move || {
        let _ = send.send(check_source("fuzz.sl", src, &loader));
    });
    receive.recv_timeout(limit).unwrap_or_else(|_| panic!("checking took longer than {limit:?}"))
}

/// `parse` target, timeout-5647eb2f (and the same input as an out-of-memory): a header that
/// includes itself twice is a binary tree of inclusions 64 deep. It was read 2^64 times with an
/// E0204 at every leaf (the CLI printed millions of errors and reached 1.5 GB in two minutes); now
/// the first include past the depth limit is the only error, and the includes after it are skipped.
#[test]
fn a_file_including_itself_twice_gives_one_depth_error_quickly() {
    const HEADER: &str = "#include \"inc.h\"\n#include \"inc.h\"\n";
    let loader = MemoryLoader::default().with_file("inc.h", HEADER);
    let checked = check_within(HEADER, loader, Duration::from_secs(30));
    let errors: Vec<&Diagnostic> = checked.diagnostics.iter().filter(|d| d.is_error()).collect();
    let messages: Vec<&str> = errors.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(messages, ["`#include` nested more than 64 deep"]);
    assert_eq!(errors[0].code, Code::IncludeDepth);
    // At the first line of the 64th inclusion of inc.h (the 65th file: the root, then 64 copies).
    let span = errors[0].primary_span();
    assert_eq!(checked.sources.file(span.file).name, "inc.h");
    assert_eq!((span.start, checked.sources.text(span)), (0, "#include \"inc.h\""));
    assert_eq!(checked.sources.files().count(), 65);
}
