//! The `patina` command line as a user meets it: exit codes, one-line errors for bad files, the
//! human and JSON diagnostic formats.

use std::path::PathBuf;
use std::process::{Command, Output};

fn patina(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_patina"))
        .args(args)
        .env("NODEVICE_SELECT", "1")
        .output()
        .expect("the patina binary runs")
}

fn scratch(name: &str, contents: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("patina-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, contents).expect("write scratch file");
    path
}

fn example(name: &str) -> String {
    format!("{}/examples/shaders/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn clean_files_pass_silently() {
    let out = patina(&["check", &example("plastic.sl"), &example("aniso.sl"), &example("bricks.sl")]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.stderr.is_empty() && out.stdout.is_empty());
}

#[test]
fn errors_are_rendered_and_fail_the_run() {
    let bad = scratch("bad.sl", b"surface s() {\n  x = 1\n  y = 2;\n}\n");
    let out = patina(&["check", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.contains("error[E0303]: expected `;`, found `y`"), "{stderr}");
    assert!(stderr.contains("bad.sl:2:8"), "{stderr}");
    assert!(stderr.contains("failed: 1 error, 0 warnings in 1 file"), "{stderr}");
    assert!(!stderr.contains("\x1b["), "no colour when piped");
}

#[test]
fn warnings_alone_do_not_fail() {
    let warn = scratch("warn.sl", b"#define A 1\n#define A 2\nfloat x;\n");
    let out = patina(&["check", warn.to_str().unwrap()]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("warning[E0214]"));
}

#[test]
fn json_format_gives_one_object_per_line() {
    let bad = scratch("json.sl", b"surface s() { x = 1; color y = trace(P, N); }\n");
    let out = patina(&["check", "--format", "json", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<serde_json::Value> =
        stdout.lines().map(|l| serde_json::from_str(l).expect("each line is JSON")).collect();
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[0]["code"], "E0501");
    assert_eq!(lines[0]["location"]["line"], 1);
    assert_eq!(lines[0]["location"]["column"], 15);
    assert_eq!(lines[1]["code"], "E0401");
    assert_eq!(lines[1]["labels"][0]["primary"], true);
}

#[test]
fn missing_unreadable_and_binary_files_get_one_line() {
    let out = patina(&["check", "/definitely/not/here.sl"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("error: cannot read `/definitely/not/here.sl`"), "{stderr}");

    let binary = scratch("binary.sl", &[b's', 0xff, 0xfe, b'\n']);
    let out = patina(&["check", binary.to_str().unwrap()]);
    assert!(!out.status.success());
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("not valid UTF-8 (invalid byte at offset 1)"), "{stderr}");

    let dir = std::env::temp_dir();
    let out = patina(&["check", dir.to_str().unwrap()]);
    assert!(!out.status.success());
    assert_eq!(String::from_utf8(out.stderr).unwrap().lines().count(), 1);
}

#[test]
fn include_directories_are_searched() {
    let lib = scratch("mylib.sl", b"float helper(float x) { return x; }\n");
    let main = scratch("uses_lib.sl", b"#include <mylib.sl>\nsurface s() { Ci = helper(1); }\n");
    let dir = lib.parent().unwrap().to_str().unwrap().to_string();
    let out = patina(&["check", main.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "angle includes do not search the includer's directory");
    let out = patina(&["check", "-I", &dir, main.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn usage_errors_exit_non_zero() {
    let out = patina(&["check"]);
    assert!(!out.status.success());
    let out = patina(&["frobnicate"]);
    assert!(!out.status.success());
}

#[test]
fn explain_prints_types_rates_and_stages() {
    let out = patina(&["explain", &example("aniso.sl")]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    let row = |name: &str| -> Vec<String> {
        let line =
            text.lines().find(|l| l.trim_start().starts_with(&format!("{name} "))).unwrap_or_else(|| {
                panic!("no row for `{name}` in:\n{text}");
            });
        line.split("  ").map(str::trim).filter(|s| !s.is_empty()).map(String::from).collect()
    };
    assert_eq!(row("base_uv"), ["base_uv", "float4", "vertex (declared)", "vertex stage"]);
    assert_eq!(row("lit"), ["lit", "float4", "perlight fragment (inferred)", "fragment stage"]);
    assert_eq!(row("ka"), ["ka", "float4", "constant (declared)", "compile time"]);
    assert_eq!(row("ambient_color"), ["ambient_color", "float4", "primitive group", "host (once per draw)"]);
    assert!(text.contains("surface shader `aniso` (Stanford style)"));
}
