//! The VS Code extension in `editors/vscode/`.
//!
//! - Its grammar's word lists are the compiler's: every keyword of the lexer
//!   (`compiler/src/syntax/token.rs`) in the group docs/language.md puts it in, every built-in
//!   function, predefined variable and standard-library function. A word added to the language
//!   without the grammar fails here, with the list to paste.
//! - The package builds: `npm ci`, `npm test` (the grammar's assertion files `test/*.test.sl`
//!   under vscode-tmgrammar-test, and the client's tests) and `npx vsce package` into a temporary
//!   folder, which must produce a non-empty .vsix (a zip). Skipped only when `npm` is not on PATH;
//!   it needs the npm registry. Nothing is written into the source tree but `node_modules/`.

use std::collections::{BTreeMap, BTreeSet};
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Instant;

use patina::compiler::sema::builtins::builtins;
use patina::compiler::sema::globals::GLOBALS;
use patina::compiler::syntax::ast::Item;
use patina::compiler::syntax::preprocess::MemoryLoader;

/// The workspace root (this test belongs to the root package).
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The extension's folder.
fn package() -> PathBuf {
    root().join("editors/vscode")
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn grammar() -> serde_json::Value {
    let path = package().join("syntaxes/patina.tmLanguage.json");
    serde_json::from_str(&read(&path)).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The names listed in the `match` of the grammar's repository entry `entry` (or of its
/// patterns): the identifiers of each `(?:a|b|c)` alternation.
fn listed(grammar: &serde_json::Value, entry: &str) -> BTreeSet<String> {
    let rule = &grammar["repository"][entry];
    assert!(rule.is_object(), "the grammar has no repository entry `{entry}`");
    let mut matches: Vec<&str> = rule["match"].as_str().into_iter().collect();
    if let Some(patterns) = rule["patterns"].as_array() {
        matches.extend(patterns.iter().filter_map(|p| p["match"].as_str()));
    }
    let mut names = BTreeSet::new();
    for regex in matches {
        for group in regex.split("(?:").skip(1) {
            let alternation = group.split(')').next().unwrap_or_default();
            let is_name = |w: &&str| {
                w.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
                    && w.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            };
            names.extend(alternation.split('|').filter(is_name).map(str::to_owned));
        }
    }
    names
}

fn union(grammar: &serde_json::Value, entries: &[&str]) -> BTreeSet<String> {
    entries.iter().flat_map(|e| listed(grammar, e)).collect()
}

/// `names` as the grammar writes them: an alternation in case-insensitive order.
fn alternation(names: &BTreeSet<String>) -> String {
    let mut names: Vec<&str> = names.iter().map(String::as_str).collect();
    names.sort_by_key(|n| (n.to_ascii_lowercase(), n.to_string()));
    names.join("|")
}

#[track_caller]
fn assert_lists(what: &str, entry: &str, grammar: &BTreeSet<String>, expected: &BTreeSet<String>) {
    let missing: Vec<_> = expected.difference(grammar).collect();
    let extra: Vec<_> = grammar.difference(expected).collect();
    assert!(
        missing.is_empty() && extra.is_empty(),
        "the grammar's {what} (repository `{entry}` of editors/vscode/syntaxes/patina.tmLanguage.json) \
         differ from the compiler's: missing {missing:?}, not in the compiler {extra:?}; the list is\n{}",
        alternation(expected)
    );
}

/// The keywords of the lexer: every alphabetic `#[token("...")]` of `syntax/token.rs`.
fn lexer_keywords() -> BTreeSet<String> {
    let text = read(&root().join("compiler/src/syntax/token.rs"));
    let mut words = BTreeSet::new();
    for token in text.split("#[token(\"").skip(1) {
        let word = token.split('"').next().unwrap_or_default();
        if word.starts_with(|c: char| c.is_ascii_alphabetic()) {
            words.insert(word.to_owned());
        }
    }
    assert!(words.len() > 50, "only {} keywords found: token.rs's form changed", words.len());
    assert!(
        text.contains(r#"#[regex(r"primitive[ \t\r\n]+group")]"#),
        "`primitive group` is no longer one token"
    );
    words
}

/// The rows of docs/language.md's keyword table: group name and its words.
fn documented_keywords() -> Vec<(String, BTreeSet<String>)> {
    let text = read(&root().join("docs/language.md"));
    let table = text.split("| group | keywords |").nth(1).expect("docs/language.md's keyword table");
    table
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|row| {
            let cells: Vec<&str> = row.split('|').map(str::trim).collect();
            let words = cells[2].split('`').skip(1).step_by(2).map(str::to_owned).collect();
            (cells[1].to_owned(), words)
        })
        .collect()
}

#[test]
fn grammar_keywords_are_the_lexers_in_the_documented_groups() {
    let grammar = grammar();
    let lexer = lexer_keywords();
    let documented = documented_keywords();
    let group = |names: &[&str]| -> BTreeSet<String> {
        let found: Vec<_> = documented.iter().filter(|(g, _)| names.contains(&g.as_str())).collect();
        assert_eq!(found.len(), names.len(), "docs/language.md's keyword table lacks a row of {names:?}");
        found.iter().flat_map(|(_, words)| words.iter().cloned()).collect()
    };

    assert_lists(
        "shader kinds",
        "shader-kinds",
        &listed(&grammar, "shader-kinds"),
        &group(&["shader kinds"]),
    );
    // `primitive group` is one token, highlighted by a pattern of its own.
    let mut qualifiers = group(&["qualifiers"]);
    assert!(qualifiers.remove("primitive group"), "`primitive group` is not a documented qualifier");
    let rates = &grammar["repository"]["rate-qualifiers"]["patterns"];
    assert!(
        rates.as_array().into_iter().flatten().any(|p| p["match"] == r"\bprimitive(?:\s+group)?\b"),
        "the grammar does not highlight `primitive group`"
    );
    let non_rates = listed(&grammar, "other-qualifiers");
    assert_eq!(non_rates, ["extern", "output"].map(String::from).into(), "qualifiers that are not rates");
    assert_lists(
        "qualifiers",
        "rate-qualifiers, other-qualifiers",
        &union(&grammar, &["rate-qualifiers", "other-qualifiers"]),
        &qualifiers,
    );
    assert_lists("types", "types", &listed(&grammar, "types"), &group(&["types", "contextual types"]));
    assert_lists(
        "statement keywords",
        "control, light-loops",
        &union(&grammar, &["control", "light-loops"]),
        &group(&["statements"]),
    );
    assert_lists("literals", "booleans", &listed(&grammar, "booleans"), &group(&["literals"]));

    // Whatever else the lexer reserves is C's words (E0312).
    let documented_words: BTreeSet<String> = documented
        .iter()
        .flat_map(|(_, words)| words.iter().flat_map(|w| w.split(' ')).map(str::to_owned))
        .collect();
    let reserved: BTreeSet<String> = lexer.difference(&documented_words).cloned().collect();
    assert!(reserved.contains("switch") && reserved.contains("struct"), "reserved words: {reserved:?}");
    assert_lists("reserved words", "reserved", &listed(&grammar, "reserved"), &reserved);

    // And every keyword of the lexer is in some group of the grammar.
    let keyword_entries = [
        "shader-kinds",
        "rate-qualifiers",
        "other-qualifiers",
        "types",
        "control",
        "light-loops",
        "booleans",
        "reserved",
    ];
    let mut highlighted = union(&grammar, &keyword_entries);
    highlighted.insert("primitive".into());
    assert_lists("keywords", "keywords", &highlighted, &lexer);
}

#[test]
fn grammar_names_are_the_compilers_builtins_variables_and_stdlib() {
    let grammar = grammar();
    let keywords = lexer_keywords();

    // `__` names are the compiler's own; `surface(...)` is highlighted as the keyword. `option`
    // and `bake` are answered in sema/lower/call.rs, outside the table.
    let mut expected: BTreeSet<String> = builtins()
        .names()
        .filter(|n| !n.starts_with("__") && !keywords.contains(*n))
        .map(str::to_owned)
        .collect();
    expected.extend(["option", "bake"].map(String::from));
    let builtin_names = listed(&grammar, "builtin-functions");
    assert_lists("built-in functions", "builtin-functions", &builtin_names, &expected);

    let variables: BTreeSet<String> = GLOBALS.iter().map(|g| g.name.to_owned()).collect();
    assert_lists(
        "predefined variables",
        "predefined-variables",
        &listed(&grammar, "predefined-variables"),
        &variables,
    );

    // The functions each standard-library module defines (with what it includes), less the
    // library's private `_patina_` helpers and its shaders.
    let mut stdlib = BTreeSet::new();
    for (name, source) in patina::compiler::stdlib::MODULES {
        let checked = patina::compiler::check_source(name, source, &MemoryLoader::default());
        assert!(!checked.diagnostics.has_errors(), "the standard library's {name} does not check");
        for item in &checked.module.items {
            if let Item::Function(f) = item
                && !f.name.name.starts_with('_')
                && !builtin_names.contains(f.name.name.as_str())
            {
                stdlib.insert(f.name.name.to_string());
            }
        }
    }
    assert!(stdlib.len() > 100, "only {} standard-library functions found", stdlib.len());
    assert_lists(
        "standard-library functions",
        "stdlib-functions",
        &listed(&grammar, "stdlib-functions"),
        &stdlib,
    );
}

/// The program `name` on PATH (`name.cmd` or `name.exe` too, on Windows).
fn on_path(name: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    let names: Vec<String> = if cfg!(windows) {
        vec![format!("{name}.cmd"), format!("{name}.exe"), name.to_owned()]
    } else {
        vec![name.to_owned()]
    };
    std::env::split_paths(&path).flat_map(|dir| names.iter().map(move |n| dir.join(n))).find(|p| p.is_file())
}

/// Runs `program args` in the extension's folder, failing with its output unless it succeeds.
fn run(program: &Path, args: &[&str]) -> Output {
    let started = Instant::now();
    let out = Command::new(program)
        .current_dir(package())
        .args(args)
        .env("npm_config_audit", "false")
        .env("npm_config_fund", "false")
        .env("npm_config_update_notifier", "false")
        .output()
        .unwrap_or_else(|e| panic!("{} could not be started: {e}", program.display()));
    let command = format!("{} {}", program.file_name().unwrap_or_default().to_string_lossy(), args.join(" "));
    assert!(
        out.status.success(),
        "`{command}` in editors/vscode failed ({}):\n--- stdout\n{}\n--- stderr\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    println!("editor_package: `{command}` took {:.1} s", started.elapsed().as_secs_f64());
    out
}

/// Every file under `dir` (relative path and contents), leaving out `node_modules`.
fn files(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut found = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(at) = stack.pop() {
        for entry in std::fs::read_dir(&at).unwrap_or_else(|e| panic!("{}: {e}", at.display())) {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                if path.file_name().is_some_and(|n| n != "node_modules") {
                    stack.push(path);
                }
            } else {
                let contents = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                found.insert(path.strip_prefix(dir).expect("under the folder").to_path_buf(), contents);
            }
        }
    }
    found
}

#[test]
fn editor_package_installs_tests_and_packages() {
    // What npm writes into the source tree stays out of git.
    let ignored = read(&package().join(".gitignore"));
    for pattern in ["node_modules/", "*.vsix"] {
        assert!(ignored.lines().any(|l| l.trim() == pattern), "editors/vscode/.gitignore lacks `{pattern}`");
    }
    let lock = read(&package().join("package-lock.json"));
    assert!(lock.contains("\"lockfileVersion\""), "editors/vscode/package-lock.json is not a lockfile");

    let Some(npm) = on_path("npm") else {
        // Straight to stderr, past the test harness's capture, so that the skip shows in every run.
        let _ = writeln!(
            std::io::stderr(),
            "editor_package: SKIPPED: `npm` is not on PATH, so the VS Code extension (editors/vscode) was not built or tested"
        );
        return;
    };
    let npx = npm
        .parent()
        .map(|dir| dir.join(npm.file_name().unwrap_or_default().to_string_lossy().replace("npm", "npx")));
    let npx = npx.filter(|p| p.is_file()).or_else(|| on_path("npx")).expect("npm is on PATH but npx is not");

    let before = files(&package());
    let started = Instant::now();
    // Install scripts are not needed to test or package (they fetch vsce's signing tool and the
    // optional keytar for publishing).
    run(&npm, &["ci", "--ignore-scripts"]);
    let tests = run(&npm, &["test"]);
    let report = String::from_utf8_lossy(&tests.stdout);
    for file in ["test/stanford.test.sl", "test/renderman.test.sl"] {
        assert!(report.contains(file), "`npm test` did not run the grammar test {file}:\n{report}");
    }

    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("editor_package");
    let _ = std::fs::remove_dir_all(&out_dir);
    std::fs::create_dir_all(&out_dir).expect("the output folder");
    let vsix = out_dir.join("patina-sl.vsix");
    run(&npx, &["--no", "--", "vsce", "package", "--out", vsix.to_str().expect("a UTF-8 path")]);
    let bytes = std::fs::read(&vsix).unwrap_or_else(|e| panic!("vsce wrote no {}: {e}", vsix.display()));
    assert!(bytes.len() > 1000, "{} has only {} bytes", vsix.display(), bytes.len());
    assert_eq!(&bytes[..2], b"PK", "{} is not a zip file", vsix.display());
    // The package holds the grammar and the client (its listing names them in clear).
    let text = String::from_utf8_lossy(&bytes);
    for member in
        ["extension/syntaxes/patina.tmLanguage.json", "extension/src/extension.js", "extension/package.json"]
    {
        assert!(text.contains(member), "{} lacks {member}", vsix.display());
    }
    assert!(bytes.len() < 2_000_000, "{} is {} bytes: check .vscodeignore", vsix.display(), bytes.len());

    let after = files(&package());
    let changed: Vec<_> =
        before.keys().chain(after.keys()).filter(|p| before.get(*p) != after.get(*p)).collect();
    assert!(
        changed.is_empty(),
        "building the extension changed editors/vscode outside node_modules: {changed:?}"
    );
    println!(
        "editor_package: npm ci, npm test and vsce package took {:.1} s; {} is {} bytes",
        started.elapsed().as_secs_f64(),
        vsix.display(),
        bytes.len()
    );
}
