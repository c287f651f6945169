//! Hot reload: the library's `Watcher` over edits, errors, includes, editors' save-by-rename and
//! deleted files, and `patina watch` re-rendering a scene. Every wait has a timeout, so a missed
//! event fails the test with a message instead of hanging it.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use patina::{Compiler, Update, Watcher};

use crate::support::scratch_dir;

/// How long any one expected event may take to arrive.
const TIMEOUT: Duration = Duration::from_secs(10);

/// What an update said, owned (an `Update` borrows the watcher).
#[derive(Debug)]
enum Seen {
    /// The shader compiled; its parameters with their defaults.
    Compiled(Vec<(String, Option<Vec<f64>>)>),
    /// It did not; the rendered error.
    Failed(String),
}

/// Waits for updates until one satisfies `wanted` (a save may be reported as more than one
/// burst, so earlier updates are skipped), failing after [`TIMEOUT`] with `what`.
fn until(watcher: &mut Watcher, what: &str, wanted: impl Fn(&Seen) -> bool) -> Seen {
    let deadline = Instant::now() + TIMEOUT;
    let mut seen = Vec::new();
    while let Some(left) = deadline.checked_duration_since(Instant::now()) {
        let update = watcher.wait(left).expect("watching goes on");
        let update = match update {
            Some(Update::Compiled(c)) => Seen::Compiled(
                c.interface.params.iter().map(|p| (p.name.clone(), p.default.clone())).collect(),
            ),
            Some(Update::Failed(e)) => Seen::Failed(e.to_string()),
            Some(other) => panic!("an update this test does not know: {other:?}"),
            None => continue,
        };
        if wanted(&update) {
            return update;
        }
        seen.push(update);
    }
    panic!("no update {what} within {TIMEOUT:?}; saw {seen:?}");
}

fn has_param(seen: &Seen, name: &str) -> bool {
    matches!(seen, Seen::Compiled(params) if params.iter().any(|(n, _)| n == name))
}

fn default_of(seen: &Seen, name: &str) -> Option<Vec<f64>> {
    match seen {
        Seen::Compiled(params) => params.iter().find(|(n, _)| n == name).and_then(|(_, d)| d.clone()),
        Seen::Failed(_) => None,
    }
}

fn failed_with(seen: &Seen, text: &str) -> bool {
    matches!(seen, Seen::Failed(e) if e.contains(text))
}

/// Writes `text` to `path`, after a pause that keeps this write apart from the one before (its
/// own burst of events, its own modification time).
fn edit(path: &Path, text: &str) {
    std::thread::sleep(Duration::from_millis(50));
    std::fs::write(path, text).expect("write the file");
}

/// Saves as many editors do: writes a new file beside `path`, then renames it over `path`.
fn save_by_rename(path: &Path, text: &str) {
    std::thread::sleep(Duration::from_millis(50));
    let partial = path.with_extension("sl.new");
    std::fs::write(&partial, text).expect("write the new file");
    std::fs::rename(&partial, path).expect("rename it over the old one");
}

const MATTE: &str = "surface s(float Kd = 0.5) { Ci = Cs * Kd * (1 - t); }\n";
const BROKEN: &str = "surface s(float Kd = 0.5) {\n  Ci = Cs * Kd\n  Oi = Os;\n}\n";
const SHINY: &str = "surface s(float Kd = 0.5; float Ks = 0.3) { Ci = Cs * (Kd + Ks) * (1 - t); }\n";

#[test]
fn an_error_is_reported_and_the_last_good_program_kept_then_the_fix() {
    let dir = scratch_dir("watch", "error_then_fix");
    let shader = dir.join("s.sl");
    std::fs::write(&shader, MATTE).unwrap();
    let mut watcher = Watcher::new(Compiler::new(), &shader).expect("watch");
    assert!(watcher.current().is_ok(), "{:?}", watcher.current().err().map(ToString::to_string));
    assert!(
        watcher.files().any(|f| f == shader),
        "the shader is watched: {:?}",
        watcher.files().collect::<Vec<_>>()
    );

    edit(&shader, BROKEN);
    let failed = until(&mut watcher, "with the diagnostic", |s| matches!(s, Seen::Failed(_)));
    assert!(failed_with(&failed, "error[E0303]: expected `;`"), "{failed:?}");
    assert!(failed_with(&failed, "s.sl:2:15"), "the diagnostic points at the line: {failed:?}");
    let error = watcher.current().expect_err("the current result is the failure");
    assert!(matches!(error, patina::CompileError::Diagnostics(d) if d.has_errors()));
    let kept = watcher.last_good().expect("the previous program stays available");
    assert!(kept.interface.param("Kd").is_some() && kept.interface.param("Ks").is_none());

    edit(&shader, SHINY);
    let fixed = until(&mut watcher, "with the new program", |s| has_param(s, "Ks"));
    assert!(has_param(&fixed, "Kd"));
    let current = watcher.current().expect("the fix compiles");
    assert!(current.interface.param("Ks").is_some());
}

#[test]
fn an_included_file_is_watched() {
    let dir = scratch_dir("watch", "include");
    let shader = dir.join("s.sl");
    let include = dir.join("defaults.sl");
    std::fs::write(&include, "#define KD 0.5\n").unwrap();
    std::fs::write(&shader, "#include \"defaults.sl\"\nsurface s(float Kd = KD) { Ci = Cs * Kd; }\n")
        .unwrap();
    let mut watcher = Watcher::new(Compiler::new(), &shader).expect("watch");
    let first = watcher.current().expect("it compiles");
    assert_eq!(first.interface.param("Kd").and_then(|p| p.default.clone()), Some(vec![0.5]));
    assert!(watcher.files().any(|f| f == include), "{:?}", watcher.files().collect::<Vec<_>>());

    edit(&include, "#define KD 0.25\n");
    let seen = until(&mut watcher, "after editing the include", |s| default_of(s, "Kd") == Some(vec![0.25]));
    assert!(matches!(seen, Seen::Compiled(_)));

    edit(&include, "#define KD 0.25 +\n");
    until(&mut watcher, "for an error in the include", |s| matches!(s, Seen::Failed(_)));
    assert_eq!(
        watcher.last_good().and_then(|c| c.interface.param("Kd")).and_then(|p| p.default.clone()),
        Some(vec![0.25]),
        "the last good program is the one before the error"
    );
    edit(&include, "#define KD 0.75\n");
    until(&mut watcher, "after fixing the include", |s| default_of(s, "Kd") == Some(vec![0.75]));
}

#[test]
fn a_new_include_that_fails_is_watched_until_fixed() {
    // The failing compile lists no files, so the fix in a file it has just begun to include must
    // be seen through the directory.
    let dir = scratch_dir("watch", "new_include");
    let shader = dir.join("s.sl");
    let extra = dir.join("extra.sl");
    std::fs::write(&shader, MATTE).unwrap();
    let mut watcher = Watcher::new(Compiler::new(), &shader).expect("watch");
    std::fs::write(&extra, "#define GAIN 0.5 +\n").unwrap();
    edit(&shader, "#include \"extra.sl\"\nsurface s(float Kd = GAIN) { Ci = Cs * Kd; }\n");
    until(&mut watcher, "for the new include's error", |s| matches!(s, Seen::Failed(_)));
    edit(&extra, "#define GAIN 0.5\n");
    let seen = until(&mut watcher, "after fixing the new include", |s| matches!(s, Seen::Compiled(_)));
    assert_eq!(default_of(&seen, "Kd"), Some(vec![0.5]));
}

#[test]
fn saving_by_rename_is_seen_every_time() {
    // A watch on the file itself would end with the first rename; the directory's goes on.
    let dir = scratch_dir("watch", "rename");
    let shader = dir.join("s.sl");
    std::fs::write(&shader, MATTE).unwrap();
    let mut watcher = Watcher::new(Compiler::new(), &shader).expect("watch");
    save_by_rename(&shader, SHINY);
    until(&mut watcher, "after the first save by rename", |s| has_param(s, "Ks"));
    save_by_rename(&shader, MATTE);
    until(&mut watcher, "after the second save by rename", |s| {
        matches!(s, Seen::Compiled(_)) && !has_param(s, "Ks")
    });
    save_by_rename(&shader, BROKEN);
    until(&mut watcher, "after a broken save by rename", |s| failed_with(s, "E0303"));
}

#[test]
fn a_deleted_shader_is_an_error_and_its_return_a_program() {
    let dir = scratch_dir("watch", "delete");
    let shader = dir.join("s.sl");
    std::fs::write(&shader, MATTE).unwrap();
    let mut watcher = Watcher::new(Compiler::new(), &shader).expect("watch");
    std::thread::sleep(Duration::from_millis(50));
    std::fs::remove_file(&shader).unwrap();
    let gone = until(&mut watcher, "after deleting the shader", |s| matches!(s, Seen::Failed(_)));
    assert!(failed_with(&gone, "no such file"), "{gone:?}");
    assert!(watcher.last_good().is_some(), "the previous program stays available");
    edit(&shader, SHINY);
    until(&mut watcher, "after writing the shader again", |s| has_param(s, "Ks"));
}

#[test]
fn a_shader_that_never_compiled_is_watched_until_it_does() {
    let dir = scratch_dir("watch", "initially_broken");
    let shader = dir.join("s.sl");
    std::fs::write(&shader, BROKEN).unwrap();
    let mut watcher = Watcher::new(Compiler::new(), &shader).expect("a broken shader is no reason to stop");
    assert!(watcher.current().is_err() && watcher.last_good().is_none());
    edit(&shader, MATTE);
    until(&mut watcher, "after fixing the shader", |s| matches!(s, Seen::Compiled(_)));
    assert!(watcher.current().is_ok());
}

#[test]
fn polling_without_changes_returns_at_once() {
    let dir = scratch_dir("watch", "poll");
    let shader = dir.join("s.sl");
    std::fs::write(&shader, MATTE).unwrap();
    let mut watcher = Watcher::new(Compiler::new(), &shader).expect("watch");
    let started = Instant::now();
    for _ in 0..10 {
        assert!(watcher.poll().expect("watching goes on").is_none());
    }
    assert!(started.elapsed() < Duration::from_secs(1), "poll blocked for {:?}", started.elapsed());
    assert!(watcher.wait(Duration::from_millis(200)).expect("watching goes on").is_none());
}

/// A scene of one small sphere with the shader `s.sl` beside it, rendered on the CPU.
fn scene(dir: &Path, shader: &str) -> PathBuf {
    std::fs::write(dir.join("s.sl"), shader).unwrap();
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        "[output]\nwidth = 24\nheight = 16\n\n[camera]\nfrom = [0.0, 0.0, -4.0]\nto = [0.0, 0.0, 0.0]\n\
         up = [0.0, 1.0, 0.0]\nfov = 40\n\n[[object]]\nmesh = \"sphere\"\ndetail = 8\nshader = \"s.sl\"\n",
    )
    .unwrap();
    scene
}

/// `patina watch` on `scene` until it stops by itself after `max_renders`; `edits` run in turn,
/// each once the command says it is waiting for changes. Its stderr.
fn watch(scene: &Path, output: &Path, max_renders: u32, edits: &[&dyn Fn()]) -> String {
    let mut child = Command::new(env!("CARGO_BIN_EXE_patina"))
        .args(["watch", &scene.display().to_string(), "-o", &output.display().to_string()])
        .args(["--backend", "cpu", "--max-renders", &max_renders.to_string()])
        .env("NODEVICE_SELECT", "1")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the patina binary runs");
    let stderr = child.stderr.take().expect("stderr is piped");
    let (lines, received) = mpsc::channel();
    let reader = std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            if lines.send(line).is_err() {
                break;
            }
        }
    });
    let mut log = Vec::new();
    let next_line = |log: &mut Vec<String>, what: &str| -> Option<String> {
        match received.recv_timeout(TIMEOUT) {
            Ok(line) => {
                log.push(line.clone());
                Some(line)
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => None,
            Err(mpsc::RecvTimeoutError::Timeout) => {
                panic!("`patina watch` printed nothing for {TIMEOUT:?} {what}; so far:\n{}", log.join("\n"))
            }
        }
    };
    for edit in edits {
        loop {
            match next_line(&mut log, "while waiting for it to wait") {
                Some(line) if line.contains("waiting for changes") => break,
                Some(_) => {}
                None => panic!("`patina watch` stopped before an edit:\n{}", log.join("\n")),
            }
        }
        edit();
    }
    while next_line(&mut log, "while waiting for it to finish").is_some() {}
    let deadline = Instant::now() + TIMEOUT;
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait for patina") {
            break status;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("`patina watch` did not stop after {max_renders} renders:\n{}", log.join("\n"));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    reader.join().expect("the reader thread ends");
    let log = log.join("\n");
    assert!(status.success(), "`patina watch` failed ({status}):\n{log}");
    log
}

#[test]
fn cli_renders_again_when_the_shader_changes() {
    let dir = scratch_dir("watch", "cli_edit");
    let scene = scene(&dir, MATTE);
    let output = dir.join("out.png");
    let shader = dir.join("s.sl");
    let first = std::cell::RefCell::new(Vec::new());
    let log = watch(
        &scene,
        &output,
        2,
        &[&|| {
            *first.borrow_mut() = std::fs::read(&output).expect("the first render wrote the image");
            edit(&shader, "surface s() { Ci = color(1, 0, 0); }\n");
        }],
    );
    assert_eq!(log.matches("wrote ").count(), 2, "two renders:\n{log}");
    assert!(log.contains("changed: "), "says what changed:\n{log}");
    let second = std::fs::read(&output).expect("the second render wrote the image");
    assert_ne!(*first.borrow(), second, "the new shader drew a different image:\n{log}");
}

#[test]
fn cli_prints_the_diagnostic_and_keeps_the_last_image() {
    let dir = scratch_dir("watch", "cli_error");
    let scene = scene(&dir, MATTE);
    let output = dir.join("out.png");
    let shader = dir.join("s.sl");
    let first = std::cell::RefCell::new(Vec::new());
    let log = watch(
        &scene,
        &output,
        2,
        &[&|| {
            *first.borrow_mut() = std::fs::read(&output).expect("the first render wrote the image");
            edit(&shader, BROKEN);
        }],
    );
    assert_eq!(log.matches("wrote ").count(), 1, "one image:\n{log}");
    assert!(log.contains("error[E0303]: expected `;`"), "the diagnostic:\n{log}");
    assert!(log.contains("kept the last good image"), "{log}");
    assert_eq!(*first.borrow(), std::fs::read(&output).expect("the image is still there"), "{log}");
}
