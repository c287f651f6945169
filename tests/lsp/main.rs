//! `patina lsp` as an editor sees it: the real binary, spoken to over stdio in framed JSON-RPC
//! (`lsp/client.rs`), answering with the compiler's own diagnostics, types and rates.

mod client;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use client::{Client, position_of, uri};
use serde_json::{Value, json};

/// A fresh directory for one test's files, removed when the test ends.
struct Workspace(PathBuf);

impl std::ops::Deref for Workspace {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Workspace {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn workspace(test: &str) -> Workspace {
    let dir = std::env::temp_dir().join(format!("patina-lsp-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    Workspace(dir)
}

/// A uniform variable assigned a varying value (E0602), and variables whose rates are inferred.
const RATES: &str = "surface t(float Kd = 0.5)
{
    uniform float u = 1;
    float v = s * 2;
    u = v;
    Ci = color(v, Kd, u);
}
";

#[test]
fn a_rate_error_comes_with_its_code_and_its_second_label() {
    let dir = workspace("diagnostic");
    let mut client = Client::start(&dir);
    let doc = uri(&dir.join("rates.sl"));
    client.open(&doc, RATES);
    let diagnostics = client.diagnostics(&doc, 1);
    assert_eq!(diagnostics.len(), 1, "{diagnostics:#?}");
    let d = &diagnostics[0];
    assert_eq!(d["code"], "E0602");
    assert_eq!(d["severity"], 1);
    // The primary label: the value `v` in `u = v;`.
    let (line, character) = position_of(RATES, "u = v", 4);
    assert_eq!(d["range"]["start"], json!({ "line": line, "character": character }));
    let related = d["relatedInformation"].as_array().expect("related information");
    let declared =
        related.iter().find(|r| r["message"] == "`u` is declared uniform here").expect("the second label");
    assert_eq!(declared["location"]["uri"], doc.as_str());
    let (line, character) = position_of(RATES, "u = 1", 0);
    assert_eq!(declared["location"]["range"]["start"], json!({ "line": line, "character": character }));
    assert!(client.shutdown().success());
}

#[test]
fn hover_shows_the_rate_and_stage_of_a_variable_and_an_expression() {
    let dir = workspace("hover");
    let mut client = Client::start(&dir);
    let doc = uri(&dir.join("rates.sl"));
    client.open(&doc, RATES);
    let text = |answer: Value| answer["result"]["contents"]["value"].as_str().unwrap_or_default().to_string();
    let (line, character) = position_of(RATES, "color(v", 6);
    let v = text(client.at("textDocument/hover", &doc, line, character));
    assert!(v.contains("float v") && v.contains("rate: **fragment**") && v.contains("fragment stage"), "{v}");
    let (line, character) = position_of(RATES, "Kd, u)", 5);
    let u = text(client.at("textDocument/hover", &doc, line, character));
    assert!(u.contains("uniform") || u.contains("primitive group"), "{u}");
    assert!(u.contains("host (once per draw)"), "{u}");
    // An expression that is not a name: `s * 2`.
    let (line, character) = position_of(RATES, "* 2", 0);
    let product = text(client.at("textDocument/hover", &doc, line, character));
    assert!(product.contains("float") && product.contains("rate:"), "{product}");
    // While a statement is typed (no `;` yet, so the text does not parse), the last text that
    // checked answers, its positions carried across the edit.
    let typing = RATES.replace("    u = v;\n", "    float w = v *;\n");
    client.change(&doc, 2, &typing);
    let syntax = client.diagnostics(&doc, 2);
    assert!(syntax[0]["code"].as_str().is_some_and(|c| c.starts_with("E03")), "{syntax:#?}");
    let (line, character) = position_of(&typing, "color(v", 6);
    let v = text(client.at("textDocument/hover", &doc, line, character));
    assert!(v.contains("float v") && v.contains("rate: **fragment**"), "{v}");
    let answer =
        client.request("textDocument/semanticTokens/full", json!({ "textDocument": { "uri": doc } }));
    let tokens = decode(&answer["result"]["data"]);
    assert!(tokens.iter().any(|t| (t.0, t.1) == (line, character)), "{tokens:?}");
    // A shader with a type error still has its rates (the compiler keeps what it could lower).
    let typo = RATES.replace("u = v;", "u = nothing;");
    client.change(&doc, 3, &typo);
    assert_eq!(client.diagnostics(&doc, 3)[0]["code"], "E0501");
    let (line, character) = position_of(&typo, "color(v", 6);
    let v = text(client.at("textDocument/hover", &doc, line, character));
    assert!(v.contains("float v") && v.contains("rate: **fragment**"), "{v}");
    assert!(client.shutdown().success());
}

/// The standard library's `fractal.sl`, as the compiler embeds it.
fn fractal() -> (PathBuf, String) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("compiler/stdlib/fractal.sl");
    let text = std::fs::read_to_string(&path).expect("the stdlib source");
    (path, text)
}

const FBM: &str = "#include <fractal.sl>
surface cloudy(float freq = 4)
{
    float v = fbm(P * freq, 0.5, 2, 6);
    Ci = color(v, v, v);
}
";

#[test]
fn definition_of_a_stdlib_function_lands_in_its_source_file() {
    let dir = workspace("definition");
    let mut client = Client::start(&dir);
    let doc = uri(&dir.join("cloudy.sl"));
    client.open(&doc, FBM);
    let (line, character) = position_of(FBM, "fbm(", 1);
    let answer = client.at("textDocument/definition", &doc, line, character);
    let location = &answer["result"];
    let (path, text) = fractal();
    assert_eq!(location["uri"], uri(&path), "{answer}");
    let (line, character) = position_of(&text, "float fbm(", 6);
    assert_eq!(location["range"]["start"], json!({ "line": line, "character": character }));
    // And a variable's definition: its declaration.
    let (line, character) = position_of(FBM, "color(v", 6);
    let answer = client.at("textDocument/definition", &doc, line, character);
    let (line, character) = position_of(FBM, "v = fbm", 0);
    assert_eq!(answer["result"]["range"]["start"], json!({ "line": line, "character": character }));
    // A built-in written in the language: the implementation it was inlined from.
    let noisy = uri(&dir.join("noisy.sl"));
    let text = "surface noisy() { Ci = noise(P * 4); }\n";
    client.open(&noisy, text);
    let answer = client.at("textDocument/definition", &noisy, 0, text.find("noise").unwrap_or_default());
    let library = Path::new(env!("CARGO_MANIFEST_DIR")).join("compiler/stdlib/builtins.sl");
    assert_eq!(answer["result"]["uri"], uri(&library), "{answer}");
    let source = std::fs::read_to_string(&library).expect("the library built-ins' source");
    let (line, _) = position_of(&source, "PATINA_NOISE(noise,", 0);
    assert_eq!(answer["result"]["range"]["start"]["line"], line, "{answer}");
    // In a function no shader calls (no IR), a name still leads to its declaration and type.
    let helper = uri(&dir.join("helper.sl"));
    let text = "float unused(float a) { return a * 2; }\nsurface s() { Ci = 1; }\n";
    client.open(&helper, text);
    let (line, character) = position_of(text, "a * 2", 0);
    let hover = client.at("textDocument/hover", &helper, line, character);
    assert!(hover["result"]["contents"]["value"].as_str().unwrap_or_default().contains("float a"), "{hover}");
    let answer = client.at("textDocument/definition", &helper, line, character);
    let (line, character) = position_of(text, "a)", 0);
    assert_eq!(answer["result"]["range"]["start"], json!({ "line": line, "character": character }));
    // Hover over the call shows the library's documentation.
    let (line, character) = position_of(FBM, "fbm(", 0);
    let hover = client.at("textDocument/hover", &doc, line, character);
    let hover = hover["result"]["contents"]["value"].as_str().unwrap_or_default();
    assert!(hover.contains("float fbm(point p; float H, lacunarity, octaves)"), "{hover}");
    assert!(hover.contains("Musgrave's fBm"), "{hover}");
    assert!(client.shutdown().success());
}

#[test]
fn completion_inlay_hints_and_semantic_tokens_carry_signatures_and_rates() {
    let dir = workspace("completion");
    let mut client = Client::start(&dir);
    let doc = uri(&dir.join("cloudy.sl"));
    client.open(&doc, FBM);
    // Completion inside the shader's body.
    let (line, character) = position_of(FBM, "Ci =", 0);
    let answer = client.at("textDocument/completion", &doc, line, character);
    let items = answer["result"].as_array().expect("a list of items");
    let detail = |label: &str| {
        let item =
            items.iter().find(|i| i["label"] == label).unwrap_or_else(|| panic!("`{label}` is offered"));
        item["detail"].as_str().unwrap_or_default().to_string()
    };
    assert_eq!(detail("fbm"), "float fbm(point p; float H, lacunarity, octaves)");
    assert!(detail("freq").starts_with("float"), "{}", detail("freq"));
    assert!(detail("v").contains("fragment"), "{}", detail("v"));
    assert!(detail("smoothstep").contains("smoothstep("), "{}", detail("smoothstep"));
    assert!(detail("P").contains("point"), "{}", detail("P"));
    // An inlay hint after `v`, whose rate is not written.
    let range = json!({ "start": { "line": 0, "character": 0 }, "end": { "line": 99, "character": 0 } });
    let answer =
        client.request("textDocument/inlayHint", json!({ "textDocument": { "uri": doc }, "range": range }));
    let hints = answer["result"].as_array().expect("hints");
    let (line, character) = position_of(FBM, "v = fbm", 1);
    let at_v = hints.iter().find(|h| h["position"] == json!({ "line": line, "character": character }));
    assert_eq!(at_v.expect("a hint after `v`")["label"], ": fragment", "{hints:#?}");
    // Semantic tokens: `v`'s declaration has the fragment modifier.
    let legend = client.capabilities["semanticTokensProvider"]["legend"].clone();
    let bit = |name: &str| {
        let modifiers = legend["tokenModifiers"].as_array().expect("modifiers");
        1u64 << modifiers.iter().position(|m| m == name).unwrap_or_else(|| panic!("modifier `{name}`"))
    };
    let answer =
        client.request("textDocument/semanticTokens/full", json!({ "textDocument": { "uri": doc } }));
    let tokens = decode(&answer["result"]["data"]);
    assert!(!tokens.is_empty());
    let (line, character) = position_of(FBM, "v = fbm", 0);
    let v = tokens.iter().find(|t| (t.0, t.1) == (line, character)).expect("a token for `v`");
    assert_eq!(v.2, 1);
    assert_ne!(v.3 & bit("fragment"), 0, "{v:?}");
    assert_ne!(v.3 & bit("declaration"), 0, "{v:?}");
    // `freq`, a RenderMan parameter: uniform (primitive group).
    let (line, character) = position_of(FBM, "freq,", 0);
    let freq = tokens.iter().find(|t| (t.0, t.1) == (line, character)).expect("a token for `freq`");
    assert_ne!(freq.3 & bit("primitiveGroup"), 0, "{freq:?}");
    assert!(client.shutdown().success());
}

/// Semantic tokens as (line, column, length, modifiers).
fn decode(data: &Value) -> Vec<(usize, usize, u64, u64)> {
    let numbers: Vec<u64> = data.as_array().expect("token data").iter().filter_map(Value::as_u64).collect();
    let (mut line, mut column) = (0, 0);
    numbers
        .chunks(5)
        .map(|t| {
            if t[0] > 0 {
                column = 0;
            }
            line += t[0] as usize;
            column += t[1] as usize;
            (line, column, t[2], t[4])
        })
        .collect()
}

#[test]
fn an_include_is_read_from_the_editors_unsaved_buffer() {
    let dir = workspace("include");
    std::fs::write(dir.join("helpers.h"), "float helper(float x) { return x; }\n").expect("write");
    let watching = json!({ "workspace": { "didChangeWatchedFiles": { "dynamicRegistration": true } } });
    let mut client = Client::start_with(&dir, watching);
    // The server asks to hear of shader files changed on disk.
    let register = client.wait_for(|m| m["method"] == "client/registerCapability");
    assert_eq!(register["params"]["registrations"][0]["method"], "workspace/didChangeWatchedFiles");
    let main_text =
        "#include \"helpers.h\"\n#include \"unsaved.h\"\nsurface t() { Ci = helper2(s) + more(t); }\n";
    let main = uri(&dir.join("main.sl"));
    client.open(&main, main_text);
    // On disk, `helpers.h` has no `helper2`, and `unsaved.h` does not exist.
    let codes = |d: &[Value]| {
        d.iter().map(|d| d["code"].as_str().unwrap_or_default().to_string()).collect::<Vec<_>>()
    };
    let before = client.diagnostics(&main, 1);
    assert_eq!(codes(&before), ["E0202"], "{before:#?}");
    // The editor opens both headers with text of its own, never saved.
    let helpers = uri(&dir.join("helpers.h"));
    client.open(&helpers, "float helper2(float x) { return x; }\n");
    client.open(&uri(&dir.join("unsaved.h")), "float more(float x) { return 2 * x; }\n");
    let after = loop {
        let d = client.diagnostics(&main, 1);
        if d.is_empty() || !codes(&d).contains(&"E0202".to_string()) {
            break d;
        }
    };
    assert!(after.is_empty(), "{after:#?}");
    // An error inside the header is shown on the `#include` line, and where it is.
    client.change(&helpers, 2, "float helper2(float x) { return y; }\n");
    let broken = client.diagnostics(&main, 1);
    assert_eq!(broken.len(), 1, "{broken:#?}");
    assert_eq!(broken[0]["range"]["start"]["line"], 0);
    let related = broken[0]["relatedInformation"].as_array().expect("where the error is");
    assert!(related.iter().any(|r| r["location"]["uri"] == helpers.as_str()), "{related:#?}");
    // Closed, the header is read from the disk again, where `helper2` is missing...
    client.notify("textDocument/didClose", json!({ "textDocument": { "uri": helpers } }));
    let closed = client.diagnostics(&main, 1);
    assert_eq!(closed.len(), 1, "{closed:#?}");
    // ... until it is written there, which the client reports.
    std::fs::write(dir.join("helpers.h"), "float helper2(float x) { return x; }\n").expect("write");
    client.notify("workspace/didChangeWatchedFiles", json!({ "changes": [{ "uri": helpers, "type": 2 }] }));
    assert!(client.diagnostics(&main, 1).is_empty());
    assert!(client.shutdown().success());
}

#[test]
fn malformed_input_gets_errors_and_the_session_goes_on() {
    let dir = workspace("malformed");
    let mut client = Client::start(&dir);
    let doc = uri(&dir.join("rates.sl"));
    client.open(&doc, RATES);
    // Not JSON: a parse error, with a null id.
    client.send_raw(b"{ this is not json");
    let answer = client.wait_for(|m| m.get("id") == Some(&Value::Null));
    assert_eq!(answer["error"]["code"], -32700);
    // Not UTF-8 at all.
    client.send_raw(&[0xff, 0xfe, 0x00, 0x80]);
    let answer = client.wait_for(|m| m.get("id") == Some(&Value::Null));
    assert_eq!(answer["error"]["code"], -32700);
    // A second `initialize`.
    let answer = client.request("initialize", json!({ "capabilities": {} }));
    assert_eq!(answer["error"]["code"], -32600);
    // A method nobody knows.
    let answer = client.request("textDocument/frobnicate", json!({}));
    assert_eq!(answer["error"]["code"], -32601);
    // Parameters of the wrong shape.
    let answer = client.request("textDocument/hover", json!({ "textDocument": 5 }));
    assert_eq!(answer["error"]["code"], -32602);
    // Positions past the end of a line, of the document, and at the largest numbers.
    for (line, character) in [(2, 900), (900, 0), (u32::MAX as usize, u32::MAX as usize)] {
        let answer = client.at("textDocument/hover", &doc, line, character);
        assert!(answer.get("error").is_none(), "{answer}");
        let answer = client.at("textDocument/definition", &doc, line, character);
        assert!(answer.get("error").is_none(), "{answer}");
        let answer = client.at("textDocument/completion", &doc, line, character);
        assert!(answer.get("error").is_none(), "{answer}");
    }
    // A document that is not open, and URIs that are no file path (not UTF-8, not `file:`).
    let answer = client.at("textDocument/hover", "file:///nowhere/x.sl", 0, 0);
    assert_eq!(answer["result"], Value::Null);
    for odd in ["file:///tmp/%FF%FE.sl", "untitled:Untitled-1"] {
        client.open(odd, RATES);
        let diagnostics = client.diagnostics(odd, 1);
        assert_eq!(diagnostics.len(), 1, "{diagnostics:#?}");
    }
    // The session still answers.
    let (line, character) = position_of(RATES, "color(v", 6);
    let answer = client.at("textDocument/hover", &doc, line, character);
    assert!(
        answer["result"]["contents"]["value"].as_str().unwrap_or_default().contains("fragment"),
        "{answer}"
    );
    assert!(client.shutdown().success());
}

/// A source of `lines` lines: many shaders and helper functions in both styles, without errors.
fn generate(lines: usize) -> String {
    let mut text = String::new();
    let mut n = 0;
    while text.lines().count() < lines {
        text.push_str(&format!(
            "// Helper {n}.
float helper{n}(float x, y; uniform float k)
{{
    float sum = 0, weight = 1;
    for (float i = 0; i < 4; i += 1) {{
        sum += weight * sin(x * 0.25 + i) * cos(y - i);
        weight *= 0.5;
    }}
    return min(sum, k);
}}

surface shade{n}(float Kd = 0.5; color tint = color (1, 0.9, 0.8); float freq = 4)
{{
    normal Nf = faceforward(normalize(N), I);
    float v = helper{n}(s * freq, t * freq, 2);
    color Ct = mix(Cs, tint, smoothstep(0, 1, v));
    Ci = Ct * Kd * diffuse(Nf);
}}

surface shader float4 rt{n}(vertex float4 uv, primitive group float4 tint)
{{
    vertex float4 scaled = {{uv[0] * 2, uv[1], 0, 1}};
    return tint * scaled;
}}

"
        ));
        n += 1;
    }
    text
}

fn median(mut times: Vec<Duration>) -> Duration {
    times.sort();
    times[times.len() / 2]
}

#[test]
fn a_one_character_edit_of_a_5000_line_file_is_checked_quickly() {
    let dir = workspace("latency");
    let mut client = Client::start(&dir);
    let doc = uri(&dir.join("big.sl"));
    let mut text = generate(5000);
    let lines = text.lines().count();
    client.open(&doc, &text);
    assert_eq!(client.diagnostics(&doc, 1), Vec::<Value>::new());
    // Each edit changes one digit of the first helper's constant; every version checks clean.
    let at = text.find("0.25").expect("a constant") + 3;
    let mut edits = Vec::new();
    for version in 2..12 {
        let digit = char::from(b'0' + (version % 10) as u8);
        text.replace_range(at..at + 1, &digit.to_string());
        let started = Instant::now();
        client.change(&doc, version, &text);
        let diagnostics = client.diagnostics(&doc, version);
        edits.push(started.elapsed());
        assert!(diagnostics.is_empty(), "{diagnostics:#?}");
    }
    let (line, character) = position_of(&text, "float v = helper", 6);
    let mut timed = |method: &str, params: Value| {
        let runs: Vec<Duration> = (0..5)
            .map(|_| {
                let started = Instant::now();
                let answer = client.request(method, params.clone());
                assert!(answer.get("error").is_none(), "{answer}");
                started.elapsed()
            })
            .collect();
        median(runs)
    };
    let position =
        json!({ "textDocument": { "uri": doc }, "position": { "line": line, "character": character } });
    let hover = timed("textDocument/hover", position.clone());
    let definition = timed("textDocument/definition", position.clone());
    let completion = timed("textDocument/completion", position);
    let tokens = timed("textDocument/semanticTokens/full", json!({ "textDocument": { "uri": doc } }));
    let edit = median(edits);
    let build = if cfg!(debug_assertions) { "debug" } else { "release" };
    eprintln!(
        "patina lsp on {lines} lines ({build} build), medians: edit -> diagnostics {edit:.0?}, hover {hover:.1?}, \
         definition {definition:.1?}, completion {completion:.1?}, semantic tokens {tokens:.1?}"
    );
    // A generous bound: the numbers themselves are in docs/performance.md.
    assert!(edit < Duration::from_secs(if cfg!(debug_assertions) { 2 } else { 1 }), "{edit:?}");
    assert!(client.shutdown().success());
}
