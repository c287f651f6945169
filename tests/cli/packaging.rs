//! The published crates package: `cargo package --workspace --no-verify` succeeds offline (from
//! the local registry cache, as after any build), and what each crate's code embeds at build time
//! (`include_str!`, `include_bytes!`) lies inside that crate's package, so the crates build from
//! crates.io. Nothing is compiled: `--no-verify`, and `--list` only lists.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The workspace root (this test belongs to the root package).
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A target directory of its own, so that packaging neither waits for nor disturbs the build.
fn target_dir() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("packaging")
}

/// `cargo ARGS` in `dir`, offline, allowing uncommitted changes (a working tree under edit).
fn cargo(dir: &Path, args: &[&str]) -> Output {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    Command::new(cargo)
        .current_dir(dir)
        .args(args)
        .args(["--allow-dirty", "--offline", "--target-dir"])
        .arg(target_dir())
        .output()
        .expect("cargo runs")
}

fn assert_success(what: &str, out: &Output) {
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{}{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The files `cargo package` would put in the package of the crate at `dir`.
fn package_files(dir: &Path) -> BTreeSet<String> {
    let out = cargo(dir, &["package", "--list"]);
    assert_success(&format!("cargo package --list in {}", dir.display()), &out);
    String::from_utf8(out.stdout).expect("UTF-8 file list").lines().map(str::to_owned).collect()
}

/// The literal paths given to `include_str!` and `include_bytes!` in `text`.
fn included_paths(text: &str) -> Vec<&str> {
    let mut paths = Vec::new();
    for macro_name in ["include_str!(", "include_bytes!("] {
        for (at, _) in text.match_indices(macro_name) {
            let rest = text[at + macro_name.len()..].trim_start();
            // `include_str!(concat!(env!(..), ..))` and the like name no literal path.
            if let Some(rest) = rest.strip_prefix('"')
                && let Some(end) = rest.find('"')
            {
                paths.push(&rest[..end]);
            }
        }
    }
    paths
}

/// `relative` joined to the directory of the package file `file`, with `..` resolved; `None` when
/// it climbs out of the package.
fn resolve(file: &str, relative: &str) -> Option<String> {
    let mut parts: Vec<&str> = file.split('/').collect();
    parts.pop();
    for part in relative.split('/') {
        match part {
            "" | "." => {}
            ".." => {
                parts.pop()?;
            }
            _ => parts.push(part),
        }
    }
    Some(parts.join("/"))
}

/// Whether a package file is compiled only for tests, benchmarks or examples (which may read the
/// repository around the crate; a packaged crate's users never build them).
fn test_only(file: &str) -> bool {
    let mut dirs = file.split('/').collect::<Vec<_>>();
    let name = dirs.pop().unwrap_or_default();
    name == "tests.rs" || dirs.iter().any(|d| matches!(*d, "tests" | "benches" | "examples"))
}

/// The build-time inclusions of the package at `dir` that are not in its file list.
fn missing_inclusions(dir: &Path, files: &BTreeSet<String>) -> Vec<String> {
    let mut missing = Vec::new();
    for file in files.iter().filter(|f| f.ends_with(".rs") && !test_only(f)) {
        let Ok(text) = std::fs::read_to_string(dir.join(file)) else { continue };
        for path in included_paths(&text) {
            match resolve(file, path) {
                Some(target) if files.contains(&target) => {}
                Some(target) => missing.push(format!("{file}: {path:?} ({target} is not packaged)")),
                None => missing.push(format!("{file}: {path:?} (outside the package)")),
            }
        }
    }
    missing
}

/// The workspace's members: name, version, directory and whether they may be published.
fn members() -> Vec<(String, String, PathBuf, bool)> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let out = Command::new(cargo)
        .current_dir(root())
        .args(["metadata", "--format-version", "1", "--no-deps", "--offline"])
        .output()
        .expect("cargo runs");
    assert_success("cargo metadata", &out);
    let metadata: serde_json::Value = serde_json::from_slice(&out.stdout).expect("cargo metadata's JSON");
    let packages = metadata["packages"].as_array().expect("packages");
    packages
        .iter()
        .map(|p| {
            let manifest = PathBuf::from(p["manifest_path"].as_str().expect("manifest_path"));
            // `publish = false` reads as an empty list of registries.
            let publishable = p["publish"].as_array().is_none_or(|registries| !registries.is_empty());
            (
                p["name"].as_str().expect("name").to_owned(),
                p["version"].as_str().expect("version").to_owned(),
                manifest.parent().expect("the package's directory").to_path_buf(),
                publishable,
            )
        })
        .collect()
}

#[test]
fn every_crate_packages_with_what_it_embeds() {
    let members = members();
    let published: Vec<_> = members.iter().filter(|m| m.3).collect();
    for name in ["patina-compiler", "patina-runtime"] {
        assert!(published.iter().any(|m| m.0 == name), "{name} is not a published member: {members:?}");
    }
    assert!(published.iter().any(|m| m.2 == root()), "the root package is published: {members:?}");

    // What each published crate's code embeds is packaged with it (the compiler's old
    // `include_str!("../../stdlib/..")` reached the workspace's folder, which no package holds).
    for (name, _, dir, _) in &published {
        let files = package_files(dir);
        let missing = missing_inclusions(dir, &files);
        assert!(missing.is_empty(), "{name} embeds files its package lacks: {missing:#?}");
        if name == "patina-compiler" {
            for module in ["noise.sl", "builtins.sl", "shaders.sl"] {
                let file = format!("stdlib/{module}");
                assert!(files.contains(&file), "the compiler's package lacks {file}");
            }
        }
    }

    // The whole workspace, as CI packages it (path dependencies resolved to their versions).
    let packages = target_dir().join("package");
    let _ = std::fs::remove_dir_all(&packages);
    let out = cargo(root(), &["package", "--workspace", "--no-verify"]);
    assert_success("cargo package --workspace --no-verify", &out);
    let crates: BTreeSet<String> = std::fs::read_dir(&packages)
        .expect("cargo package wrote target/package")
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".crate"))
        .collect();
    for (name, version, _, _) in &published {
        assert!(crates.contains(&format!("{name}-{version}.crate")), "no {name} package in {crates:?}");
    }
}

#[test]
fn inclusions_resolve_inside_the_package_or_not_at_all() {
    assert_eq!(resolve("src/stdlib.rs", "../stdlib/noise.sl").as_deref(), Some("stdlib/noise.sl"));
    // The old layout: the compiler's `src/stdlib.rs` reaching the workspace's `stdlib/`.
    assert_eq!(resolve("src/stdlib.rs", "../../stdlib/noise.sl"), None);
    assert_eq!(resolve("src/cli/plot.rs", "../../assets/f.ttf").as_deref(), Some("assets/f.ttf"));
    let text = r#"const A: &str = include_str!("../x.sl"); const B: &[u8] = include_bytes!( "y.bin" );
        const C: &str = include_str!(concat!(env!("OUT_DIR"), "/z"));"#;
    assert_eq!(included_paths(text), ["../x.sl", "y.bin"]);
    assert!(test_only("src/backend/wgsl/tests.rs") && test_only("tests/a.rs") && !test_only("src/lib.rs"));
}
