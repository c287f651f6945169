//! Snapshot tests of the syntax-level diagnostics: lexical (`E01xx`), preprocessor (`E02xx`),
//! syntax (`E03xx`) and unsupported RenderMan features (`E04xx`).
//!
//! Each test checks one small shader with one mistake, asserts the exact list of codes it produces
//! (so that the mistake gives its diagnostic and no cascade of others) and snapshots the diagnostics
//! as a user sees them. After a deliberate change, update the snapshots with
//! `INSTA_UPDATE=always cargo test -p patina-compiler --test diagnostics` and review every changed
//! `.snap` file.

use patina_compiler::check_source;
use patina_compiler::diag::render_text;
use patina_compiler::syntax::preprocess::{LoadError, Loaded, MemoryLoader, SourceLoader};

/// Checks `src` as `shader.sl`, resolving includes with `loader`; returns the codes found, in order,
/// and the diagnostics rendered as text.
fn run_with(src: &str, loader: &dyn SourceLoader) -> (Vec<&'static str>, String) {
    let checked = check_source("shader.sl", src, loader);
    let codes = checked.diagnostics.iter().map(|d| d.code.as_str()).collect();
    let list: Vec<_> = checked.diagnostics.iter().cloned().collect();
    (codes, render_text(&checked.sources, &list))
}

/// Checks `src` with nothing to include but the standard library.
fn run(src: &str) -> (Vec<&'static str>, String) {
    run_with(src, &MemoryLoader::default())
}

/// A source file made of `lines`.
fn lines(lines: &[&str]) -> String {
    let mut text = lines.join("\n");
    text.push('\n');
    text
}

// ---------------------------------------------------------------------------------------------
// Lexical errors (E01xx)

#[test]
fn unknown_character() {
    // A template placeholder left in the source.
    let (codes, text) = run(&lines(&["surface matte(float Kd = 1)", "{", "    Ci = $Kd * Cs;", "}"]));
    assert_eq!(codes, ["E0101"]);
    insta::assert_snapshot!("unknown_character", text);
}

#[test]
fn unknown_non_ascii_character() {
    // A non-breaking space pasted from a web page.
    let (codes, text) = run(&lines(&["surface matte(float\u{a0}Kd = 1)", "{", "    Ci = Kd * Cs;", "}"]));
    assert_eq!(codes, ["E0101"]);
    insta::assert_snapshot!("unknown_non_ascii_character", text);
}

#[test]
fn unterminated_comment() {
    let (codes, text) = run(&lines(&[
        "surface matte(float Kd = 1)",
        "{",
        "    Ci = Kd * Cs;",
        "}",
        "/* TODO: add a rim light term",
    ]));
    assert_eq!(codes, ["E0102"]);
    insta::assert_snapshot!("unterminated_comment", text);
}

#[test]
fn unterminated_string() {
    let (codes, text) = run(&lines(&[
        "surface paper()",
        "{",
        "    string texname = \"paper.tx;",
        "    Ci = Cs * texture(texname);",
        "}",
    ]));
    assert_eq!(codes, ["E0103"]);
    insta::assert_snapshot!("unterminated_string", text);
}

#[test]
fn invalid_escape() {
    // A Windows path: `\w` is no escape.
    let (codes, text) = run(&lines(&[
        "surface wood(string texname = \"maps\\wood.tx\")",
        "{",
        "    Ci = Cs * texture(texname);",
        "}",
    ]));
    assert_eq!(codes, ["E0104"]);
    insta::assert_snapshot!("invalid_escape", text);
}

#[test]
fn malformed_number() {
    let (codes, text) =
        run(&lines(&["surface glossy(float roughness = 0.1.5)", "{", "    Ci = Cs * roughness;", "}"]));
    assert_eq!(codes, ["E0105"]);
    insta::assert_snapshot!("malformed_number", text);
}

#[test]
fn malformed_exponent() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 fade(vertex float4 uv)",
        "{",
        "    float k = 2.5e-;",
        "    return uv * k;",
        "}",
    ]));
    assert_eq!(codes, ["E0105"]);
    insta::assert_snapshot!("malformed_exponent", text);
}

#[test]
fn integer_too_large() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 noisy(uint seed = 4294967296)",
        "{",
        "    return float4(1, 1, 1, seed);",
        "}",
    ]));
    assert_eq!(codes, ["E0106"]);
    insta::assert_snapshot!("integer_too_large", text);
}

#[test]
fn float_too_large() {
    let (codes, text) =
        run(&lines(&["surface bright(float intensity = 1e39)", "{", "    Ci = Cs * intensity;", "}"]));
    assert_eq!(codes, ["E0107"]);
    insta::assert_snapshot!("float_too_large", text);
}

#[test]
fn float_just_above_max() {
    // Rounds to infinity in f32 (the largest finite f32 is 3.40282347e38).
    let (codes, text) = run(&lines(&[
        "surface bright(float intensity = 3.4028236e38)",
        "{",
        "    Ci = Cs * intensity;",
        "}",
    ]));
    assert_eq!(codes, ["E0107"]);
    insta::assert_snapshot!("float_just_above_max", text);
}

#[test]
fn float_max_is_accepted() {
    // The largest finite f32, as `f32::MAX` prints it: it does not round to infinity.
    let (codes, text) = run(&lines(&[
        "surface bright(float intensity = 3.4028235e38)",
        "{",
        "    Ci = Cs * intensity;",
        "}",
    ]));
    assert_eq!(codes, [] as [&str; 0], "{text}");
}

#[test]
fn skipped_group_is_not_lexed() {
    // Text in a group the conditionals skip may be anything, as in C: notes, half-written code.
    let (codes, text) = run(&with_matte(&[
        "#if 0",
        "It's unfinished: @todo port the 1.2.3 \"hair model, cost 2.5e- per sample",
        "#define HAIR_WIDTH 0.0.1",
        "#else",
        "#define HAIR_WIDTH 0.01",
        "#endif",
    ]));
    assert_eq!(codes, [] as [&str; 0], "{text}");
}

#[test]
fn unterminated_comment_after_if_0() {
    // The comment starts in compiled text (the directive's line), so it is reported; it hides the
    // `#endif`, which the second error says.
    let (codes, text) =
        run(&with_matte(&["#if 0 /* disabled until the new BRDF lands", "#define NEW_BRDF", "#endif"]));
    assert_eq!(codes, ["E0102", "E0207"]);
    insta::assert_snapshot!("unterminated_comment_after_if_0", text);
}

#[test]
fn unterminated_comment_in_skipped_group() {
    // C reports an unterminated comment even in skipped text: comments are removed before
    // directives are read, so this one hides the `#endif` and everything after it.
    let (codes, text) = run(&with_matte(&["#if 0", "/* old version", "#define OLD", "#endif"]));
    assert_eq!(codes, ["E0102", "E0207"]);
    insta::assert_snapshot!("unterminated_comment_in_skipped_group", text);
}

// ---------------------------------------------------------------------------------------------
// Preprocessor errors (E02xx)

/// A shader with no mistakes, to follow the directives under test.
const MATTE: [&str; 4] = ["surface matte(float Kd = 1)", "{", "    Ci = Kd * Cs;", "}"];

/// `directives`, then [`MATTE`].
fn with_matte(directives: &[&str]) -> String {
    let mut all = directives.to_vec();
    all.extend(MATTE);
    lines(&all)
}

#[test]
fn unknown_directive() {
    let (codes, text) = run(&with_matte(&["#inclde \"noise.h\""]));
    assert_eq!(codes, ["E0201"]);
    insta::assert_snapshot!("unknown_directive", text);
}

#[test]
fn include_not_found() {
    let (codes, text) = run(&with_matte(&["#include \"shading_utils.h\""]));
    assert_eq!(codes, ["E0202"]);
    insta::assert_snapshot!("include_not_found", text);
}

#[test]
fn malformed_include() {
    let (codes, text) = run(&with_matte(&["#include shading_utils.h"]));
    assert_eq!(codes, ["E0203"]);
    insta::assert_snapshot!("malformed_include", text);
}

#[test]
fn include_depth() {
    // A header without an include guard that includes itself.
    let loader =
        MemoryLoader::default().with_file("loop.h", lines(&["#include \"loop.h\"", "float gamma = 2.2;"]));
    let (codes, text) = run_with(&with_matte(&["#include \"loop.h\""]), &loader);
    assert_eq!(codes, ["E0204"]);
    insta::assert_snapshot!("include_depth", text);
}

/// A loader whose every file exists but cannot be used, as a file that is not UTF-8.
struct Unreadable;

impl SourceLoader for Unreadable {
    fn load(&self, target: &str, _quoted: bool, _includer: &str) -> Result<Loaded, LoadError> {
        Err(LoadError::Unreadable {
            name: target.to_string(),
            reason: "not valid UTF-8 (invalid byte at offset 17)".to_string(),
        })
    }
}

#[test]
fn include_unreadable() {
    let (codes, text) = run_with(&with_matte(&["#include \"latin1.h\""]), &Unreadable);
    assert_eq!(codes, ["E0205"]);
    insta::assert_snapshot!("include_unreadable", text);
}

#[test]
fn endif_without_if() {
    let mut src = MATTE.to_vec();
    src.push("#endif");
    let (codes, text) = run(&lines(&src));
    assert_eq!(codes, ["E0206"]);
    insta::assert_snapshot!("endif_without_if", text);
}

#[test]
fn else_without_if_directive() {
    let (codes, text) = run(&with_matte(&["#define Ks 0.5", "#else"]));
    assert_eq!(codes, ["E0206"]);
    insta::assert_snapshot!("else_without_if_directive", text);
}

#[test]
fn unterminated_conditional() {
    let (codes, text) = run(&lines(&[
        "#ifdef USE_BUMP",
        "displacement bumpy(float Km = 0.1)",
        "{",
        "    P += Km * N;",
        "    N = calculatenormal(P);",
        "}",
    ]));
    assert_eq!(codes, ["E0207"]);
    insta::assert_snapshot!("unterminated_conditional", text);
}

#[test]
fn elif_after_else() {
    let (codes, text) = run(&with_matte(&[
        "#define HIGH_QUALITY",
        "#ifdef HIGH_QUALITY",
        "#define SAMPLES 16",
        "#else",
        "#define SAMPLES 4",
        "#elif MEDIUM_QUALITY",
        "#define SAMPLES 8",
        "#endif",
    ]));
    assert_eq!(codes, ["E0208"]);
    insta::assert_snapshot!("elif_after_else", text);
}

#[test]
fn elif_after_active_else() {
    // The `#else` branch is the one compiled; what follows the misplaced `#elif` is skipped with it
    // (compiled, its `#define` would redefine SAMPLES).
    let (codes, text) = run(&with_matte(&[
        "#ifdef HIGH_QUALITY",
        "#define SAMPLES 16",
        "#else",
        "#define SAMPLES 4",
        "#elif MEDIUM_QUALITY",
        "#define SAMPLES 8",
        "#endif",
    ]));
    assert_eq!(codes, ["E0208"]);
    insta::assert_snapshot!("elif_after_active_else", text);
}

#[test]
fn condition_missing_operand() {
    let (codes, text) = run(&with_matte(&["#if QUALITY >", "#define SAMPLES 16", "#endif"]));
    assert_eq!(codes, ["E0209"]);
    insta::assert_snapshot!("condition_missing_operand", text);
}

#[test]
fn condition_empty() {
    let (codes, text) = run(&with_matte(&["#if", "#define SAMPLES 16", "#endif"]));
    assert_eq!(codes, ["E0209"]);
    insta::assert_snapshot!("condition_empty", text);
}

#[test]
fn condition_float() {
    let (codes, text) = run(&with_matte(&["#if VERSION >= 3.5", "#define HAS_LAYERS", "#endif"]));
    assert_eq!(codes, ["E0209"]);
    insta::assert_snapshot!("condition_float", text);
}

#[test]
fn condition_division_by_zero() {
    let (codes, text) =
        run(&with_matte(&["#define QUALITY 0", "#if 16 / QUALITY > 2", "#define FAST", "#endif"]));
    assert_eq!(codes, ["E0209"]);
    insta::assert_snapshot!("condition_division_by_zero", text);
}

#[test]
fn condition_defined_without_name() {
    let (codes, text) = run(&with_matte(&["#if defined", "#define FAST", "#endif"]));
    assert_eq!(codes, ["E0209"]);
    insta::assert_snapshot!("condition_defined_without_name", text);
}

#[test]
fn define_without_name() {
    let (codes, text) = run(&with_matte(&["#define"]));
    assert_eq!(codes, ["E0210"]);
    insta::assert_snapshot!("define_without_name", text);
}

#[test]
fn undef_of_a_number() {
    let (codes, text) = run(&with_matte(&["#undef 42"]));
    assert_eq!(codes, ["E0210"]);
    insta::assert_snapshot!("undef_of_a_number", text);
}

#[test]
fn malformed_macro_params() {
    let (codes, text) = run(&with_matte(&["#define LERP(a b, t) ((a) + ((b) - (a)) * (t))"]));
    assert_eq!(codes, ["E0211"]);
    insta::assert_snapshot!("malformed_macro_params", text);
}

#[test]
fn unclosed_macro_params() {
    let (codes, text) = run(&with_matte(&["#define LERP(a, b"]));
    assert_eq!(codes, ["E0211"]);
    insta::assert_snapshot!("unclosed_macro_params", text);
}

#[test]
fn macro_arity_in_expression() {
    // The call stays in the expression as a name, so the rest of the statement parses.
    let (codes, text) = run(&lines(&[
        "#define LERP(a, b, t) ((a) + ((b) - (a)) * (t))",
        "surface plastic(float Kd = 1)",
        "{",
        "    Ci = LERP(Cs, 1) * Kd;",
        "}",
    ]));
    assert_eq!(codes, ["E0212"]);
    insta::assert_snapshot!("macro_arity_in_expression", text);
}

#[test]
fn duplicate_macro_param() {
    let (codes, text) = run(&with_matte(&["#define LERP(a, a, t) ((a) + ((b) - (a)) * (t))"]));
    assert_eq!(codes, ["E0211"]);
    insta::assert_snapshot!("duplicate_macro_param", text);
}

#[test]
fn macro_arity() {
    let (codes, text) = run(&lines(&[
        "#define ACCUMULATE(c, w) Ci += (c) * (w)",
        "surface plastic(float Kd = 1)",
        "{",
        "    Ci = 0;",
        "    ACCUMULATE(Cs);",
        "}",
    ]));
    assert_eq!(codes, ["E0212"]);
    insta::assert_snapshot!("macro_arity", text);
}

#[test]
fn unterminated_macro_call() {
    let (codes, text) = run(&lines(&[
        "#define WEIGHT(name) uniform float name##_weight = 1;",
        "WEIGHT(diffuse)",
        "WEIGHT(specular",
    ]));
    assert_eq!(codes, ["E0213"]);
    insta::assert_snapshot!("unterminated_macro_call", text);
}

#[test]
fn macro_redefined() {
    let (codes, text) = run(&lines(&[
        "#define KD 0.8",
        "#define KD 0.5",
        "surface matte(float Kd = KD)",
        "{",
        "    Ci = Kd * Cs;",
        "}",
    ]));
    assert_eq!(codes, ["E0214"]);
    insta::assert_snapshot!("macro_redefined", text);
}

#[test]
fn paste_at_edge() {
    let (codes, text) = run(&with_matte(&["#define CHANNEL(c) Cs_ ## c ##"]));
    assert_eq!(codes, ["E0215"]);
    insta::assert_snapshot!("paste_at_edge", text);
}

#[test]
fn paste_not_one_token() {
    let (codes, text) = run(&lines(&[
        "#define APPLY(x, op) x ## op",
        "surface plastic(float Kd = 1)",
        "{",
        "    Ci = APPLY(Kd, *) Cs;",
        "}",
    ]));
    assert_eq!(codes, ["E0215"]);
    insta::assert_snapshot!("paste_not_one_token", text);
}

#[test]
fn stringize_without_param() {
    let (codes, text) = run(&with_matte(&["#define LABEL(p) #q"]));
    assert_eq!(codes, ["E0216"]);
    insta::assert_snapshot!("stringize_without_param", text);
}

#[test]
fn error_directive() {
    let (codes, text) = run(&with_matte(&[
        "#ifndef SHADING_MODEL",
        "#error SHADING_MODEL must be defined, e.g. -DSHADING_MODEL=1",
        "#endif",
    ]));
    assert_eq!(codes, ["E0217"]);
    insta::assert_snapshot!("error_directive", text);
}

#[test]
fn error_directive_without_message() {
    let (codes, text) = run(&with_matte(&["#ifndef SHADING_MODEL", "#error", "#endif"]));
    assert_eq!(codes, ["E0217"]);
    insta::assert_snapshot!("error_directive_without_message", text);
}

#[test]
fn warning_directive() {
    let (codes, text) = run(&with_matte(&["#warning the matte shader ignores opacity"]));
    assert_eq!(codes, ["E0217"]);
    insta::assert_snapshot!("warning_directive", text);
}

#[test]
fn expansion_too_deep() {
    // A chain of macros each naming the next, longer than the nesting limit. The use stands as its
    // name and the rest of the shader, closing brace included, is read as written.
    let mut src: Vec<String> = vec!["#define LEVEL0 Kd".into()];
    src.extend((1..=205).map(|i| format!("#define LEVEL{i} LEVEL{}", i - 1)));
    src.extend(
        ["surface plastic(float Kd = 1)", "{", "    Ci = Cs * LEVEL205;", "    Oi = Os;", "}"]
            .map(String::from),
    );
    let src: Vec<&str> = src.iter().map(String::as_str).collect();
    let (codes, text) = run(&lines(&src));
    assert_eq!(codes, ["E0218"]);
    insta::assert_snapshot!("expansion_too_deep", text);
}

#[test]
fn extra_tokens_after_endif() {
    let (codes, text) = run(&with_matte(&["#ifdef USE_BUMP", "#define BUMP 1", "#endif USE_BUMP"]));
    assert_eq!(codes, ["E0219"]);
    insta::assert_snapshot!("extra_tokens_after_endif", text);
}

#[test]
fn extra_tokens_after_undef() {
    let (codes, text) = run(&with_matte(&["#define FAST 1", "#undef FAST SLOW"]));
    assert_eq!(codes, ["E0219"]);
    insta::assert_snapshot!("extra_tokens_after_undef", text);
}

// ---------------------------------------------------------------------------------------------
// Syntax errors (E03xx)

#[test]
fn unexpected_token() {
    let (codes, text) = run(&lines(&["surface plastic(float Kd = 1)", "{", "    Ci = Kd * * Cs;", "}"]));
    assert_eq!(codes, ["E0301"]);
    insta::assert_snapshot!("unexpected_token", text);
}

#[test]
fn parameter_without_type() {
    // After `;` a RenderMan parameter group must name its type again.
    let (codes, text) =
        run(&lines(&["surface plastic(float Kd = 1; Ks = 0.5)", "{", "    Ci = (Kd + Ks) * Cs;", "}"]));
    assert_eq!(codes, ["E0301"]);
    insta::assert_snapshot!("parameter_without_type", text);
}

#[test]
fn unexpected_end_of_file() {
    let mut src = MATTE.to_vec();
    src.push("float gamma =");
    let (codes, text) = run(&lines(&src));
    assert_eq!(codes, ["E0302"]);
    insta::assert_snapshot!("unexpected_end_of_file", text);
}

#[test]
fn missing_semicolon() {
    let (codes, text) = run(&lines(&[
        "surface plastic(float Kd = 1)",
        "{",
        "    Ci = Kd * Cs",
        "    Oi = Os;",
        "    Ci *= Oi;",
        "}",
    ]));
    assert_eq!(codes, ["E0303"]);
    insta::assert_snapshot!("missing_semicolon", text);
}

#[test]
fn missing_semicolon_before_brace() {
    let (codes, text) =
        run(&lines(&["surface plastic(float Kd = 1)", "{", "    Oi = Os; Ci = Kd * Cs * Oi", "}"]));
    assert_eq!(codes, ["E0303"]);
    insta::assert_snapshot!("missing_semicolon_before_brace", text);
}

#[test]
fn missing_semicolon_stanford() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 tint(vertex float4 uv)",
        "{",
        "    float4 c = uv * 2",
        "    return c;",
        "}",
    ]));
    assert_eq!(codes, ["E0303"]);
    insta::assert_snapshot!("missing_semicolon_stanford", text);
}

#[test]
fn missing_semicolon_after_macro_call() {
    // The `;` belongs after the use of the macro, not at the end of its `#define`.
    let (codes, text) = run(&lines(&[
        "#define SHADE(c) Ci = (c) * Kd",
        "surface plastic(float Kd = 1)",
        "{",
        "    SHADE(Cs)",
        "    Oi = Os;",
        "}",
    ]));
    assert_eq!(codes, ["E0303"]);
    insta::assert_snapshot!("missing_semicolon_after_macro_call", text);
}

#[test]
fn unexpected_end_after_type() {
    let mut src = MATTE.to_vec();
    src.push("float");
    let (codes, text) = run(&lines(&src));
    assert_eq!(codes, ["E0302"]);
    insta::assert_snapshot!("unexpected_end_after_type", text);
}

#[test]
fn unclosed_brace() {
    let (codes, text) = run(&lines(&[
        "surface plastic(float Kd = 1)",
        "{",
        "    Ci = Kd * Cs;",
        "    if (Kd > 0.5) {",
        "        Oi = Os;",
        "}",
    ]));
    assert_eq!(codes, ["E0304"]);
    insta::assert_snapshot!("unclosed_brace", text);
}

#[test]
fn mismatched_closer() {
    let (codes, text) =
        run(&lines(&["surface plastic(float Kd = 1)", "{", "    Ci = Kd * diffuse(normalize(N]);", "}"]));
    assert_eq!(codes, ["E0305"]);
    insta::assert_snapshot!("mismatched_closer", text);
}

#[test]
fn unclosed_paren_before_brace() {
    let (codes, text) =
        run(&lines(&["surface plastic(float Kd = 1)", "{", "    Ci = Kd * diffuse(normalize(N);", "}"]));
    assert_eq!(codes, ["E0305"]);
    insta::assert_snapshot!("unclosed_paren_before_brace", text);
}

#[test]
fn stray_closing_brace() {
    let mut src = MATTE.to_vec();
    src.push("}");
    let (codes, text) = run(&lines(&src));
    assert_eq!(codes, ["E0305"]);
    insta::assert_snapshot!("stray_closing_brace", text);
}

#[test]
fn keyword_as_name() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 fog(float density = 1)",
        "{",
        "    float volume = 0.5;",
        "    return float4(1, 1, 1, density);",
        "}",
    ]));
    assert_eq!(codes, ["E0306"]);
    insta::assert_snapshot!("keyword_as_name", text);
}

#[test]
fn keyword_as_name_each_use() {
    // Each use of the name is reported, not only its declaration.
    let (codes, text) = run(&lines(&[
        "surface shader float4 tint(vertex float4 uv)",
        "{",
        "    float4 fragment = uv * 2;",
        "    return fragment;",
        "}",
    ]));
    assert_eq!(codes, ["E0306", "E0306"]);
    insta::assert_snapshot!("keyword_as_name_each_use", text);
}

#[test]
fn keyword_as_name_then_used() {
    // The declaration is taken with the keyword as its name, so the use is read as a name too:
    // one error at each, not a parse derailed at the use.
    let (codes, text) = run(&lines(&[
        "surface shader float4 plastic(float Kd = 1)",
        "{",
        "    float light = 0.5;",
        "    return float4(1, 1, Kd, light);",
        "}",
    ]));
    assert_eq!(codes, ["E0306", "E0306"]);
    insta::assert_snapshot!("keyword_as_name_then_used", text);
}

#[test]
fn keyword_as_function_name() {
    // A local function named by a keyword is taken as a function, so its body does not derail the
    // shader's; the call, which reads as message passing, is its own and not reported.
    let (codes, text) = run(&lines(&[
        "surface plastic(float Kd = 1)",
        "{",
        "    float surface(float x) { return x * Kd; }",
        "    Ci = Cs * surface(0.5);",
        "}",
    ]));
    assert_eq!(codes, ["E0306"]);
    insta::assert_snapshot!("keyword_as_function_name", text);
}

#[test]
fn qualifier_after_type() {
    let (codes, text) = run(&lines(&[
        "surface plastic(float Kd = 1)",
        "{",
        "    float uniform k = Kd;",
        "    Ci = k * Cs;",
        "}",
    ]));
    assert_eq!(codes, ["E0301"]);
    insta::assert_snapshot!("qualifier_after_type", text);
}

#[test]
fn primitive_without_group() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 tint(primitive float4 base, fragment float4 uv)",
        "{",
        "    return base * uv;",
        "}",
    ]));
    assert_eq!(codes, ["E0307"]);
    insta::assert_snapshot!("primitive_without_group", text);
}

#[test]
fn conflicting_qualifiers() {
    let (codes, text) =
        run(&lines(&["surface plastic(uniform varying float Kd = 1)", "{", "    Ci = Kd * Cs;", "}"]));
    assert_eq!(codes, ["E0308"]);
    insta::assert_snapshot!("conflicting_qualifiers", text);
}

#[test]
fn repeated_qualifier() {
    let (codes, text) = run(&lines(&[
        "surface plastic(float Kd = 1; output output float coverage = 0)",
        "{",
        "    Ci = Kd * Cs;",
        "    coverage = 1;",
        "}",
    ]));
    assert_eq!(codes, ["E0308"]);
    insta::assert_snapshot!("repeated_qualifier", text);
}

#[test]
fn zero_array_size() {
    let (codes, text) =
        run(&lines(&["surface blur(float Kd = 1)", "{", "    float weights[0];", "    Ci = Kd * Cs;", "}"]));
    assert_eq!(codes, ["E0309"]);
    insta::assert_snapshot!("zero_array_size", text);
}

#[test]
fn variable_array_size() {
    let (codes, text) = run(&lines(&[
        "surface blur(float Kd = 1; float taps = 4)",
        "{",
        "    float weights[taps];",
        "    Ci = Kd * Cs;",
        "}",
    ]));
    assert_eq!(codes, ["E0309"]);
    insta::assert_snapshot!("variable_array_size", text);
}

#[test]
fn stray_brace_in_constructor() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 tint(vertex float4 uv)",
        "{",
        "    float4 x = {1, 2}, 0, 1;",
        "    return x * uv;",
        "}",
    ]));
    assert_eq!(codes, ["E0310"]);
    insta::assert_snapshot!("stray_brace_in_constructor", text);
}

#[test]
fn empty_constructor() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 tint(vertex float4 uv)",
        "{",
        "    float4 x = {};",
        "    return x * uv;",
        "}",
    ]));
    assert_eq!(codes, ["E0311"]);
    insta::assert_snapshot!("empty_constructor", text);
}

#[test]
fn reserved_switch() {
    let (codes, text) = run(&lines(&[
        "surface toon(float bands = 3)",
        "{",
        "    switch (bands) {",
        "    case 2: Ci = Cs * 0.5;",
        "    }",
        "}",
    ]));
    assert_eq!(codes, ["E0312"]);
    insta::assert_snapshot!("reserved_switch", text);
}

#[test]
fn reserved_struct() {
    let mut src = vec!["struct Material { float Kd; float Ks; };"];
    src.extend(MATTE);
    let (codes, text) = run(&lines(&src));
    assert_eq!(codes, ["E0312"]);
    insta::assert_snapshot!("reserved_struct", text);
}

#[test]
fn reserved_do() {
    let (codes, text) = run(&lines(&[
        "surface rings(float count = 4)",
        "{",
        "    float i = 0;",
        "    do {",
        "        i += 1;",
        "    } while (i < count);",
        "    Ci = Cs * i;",
        "}",
    ]));
    assert_eq!(codes, ["E0312"]);
    insta::assert_snapshot!("reserved_do", text);
}

#[test]
fn reserved_const() {
    let mut src = vec!["const float PI2 = 6.2831853;"];
    src.extend(MATTE);
    let (codes, text) = run(&lines(&src));
    assert_eq!(codes, ["E0312"]);
    insta::assert_snapshot!("reserved_const", text);
}

#[test]
fn break_zero() {
    let (codes, text) = run(&lines(&[
        "surface steps(float Kd = 1)",
        "{",
        "    float i;",
        "    for (i = 0; i < 4; i += 1) {",
        "        if (i > Kd) break 0;",
        "    }",
        "    Ci = Cs * i;",
        "}",
    ]));
    assert_eq!(codes, ["E0313"]);
    insta::assert_snapshot!("break_zero", text);
}

#[test]
fn else_after_semicolon() {
    let (codes, text) = run(&lines(&[
        "surface plastic(float Kd = 1)",
        "{",
        "    if (Kd > 0.5) {",
        "        Ci = Cs;",
        "    };",
        "    else",
        "        Ci = 0;",
        "}",
    ]));
    assert_eq!(codes, ["E0314"]);
    insta::assert_snapshot!("else_after_semicolon", text);
}

#[test]
fn else_after_semicolon_with_block() {
    // The `else` branch is read as a statement of the block, so the shader's `}` still closes it.
    let (codes, text) = run(&lines(&[
        "surface plastic(float Kd = 1)",
        "{",
        "    if (Kd > 0.5) { Ci = Cs; }; else { Ci = 0; }",
        "}",
    ]));
    assert_eq!(codes, ["E0314"]);
    insta::assert_snapshot!("else_after_semicolon_with_block", text);
}

#[test]
fn else_after_empty_statement() {
    let (codes, text) = run(&lines(&[
        "surface plastic(float Kd = 1)",
        "{",
        "    if (Kd > 0.5) Ci = Cs;;",
        "    else Ci = 0;",
        "}",
    ]));
    assert_eq!(codes, ["E0314"]);
    insta::assert_snapshot!("else_after_empty_statement", text);
}

#[test]
fn else_after_statement() {
    // The `;` ends an assignment, not an `if`: the `if` is missing, not a `;` too many.
    let (codes, text) = run(&lines(&[
        "surface plastic(float Kd = 1)",
        "{",
        "    Ci = Cs;",
        "    else {",
        "        Ci = 0;",
        "    }",
        "    Oi = Os;",
        "}",
    ]));
    assert_eq!(codes, ["E0314"]);
    insta::assert_snapshot!("else_after_statement", text);
}

#[test]
fn else_after_two_statements() {
    // Braces left out: the `if` took only the first statement. The `;` is not the fault.
    let (codes, text) = run(&lines(&[
        "surface plastic(float Kd = 1)",
        "{",
        "    if (Kd > 0.5)",
        "        Ci = Cs;",
        "        Oi = Os;",
        "    else",
        "        Ci = 0;",
        "}",
    ]));
    assert_eq!(codes, ["E0314"]);
    insta::assert_snapshot!("else_after_two_statements", text);
}

#[test]
fn independent_errors_in_text_order() {
    // Errors the parser recovers from and problems its actions find come in the order of the text.
    let (codes, text) = run(&lines(&[
        "surface shader float4 fog(float density = 1)",
        "{",
        "    float volume = 1e39;",
        "    float c = density * * 2;",
        "    return float4(3.5e39, 1, 1, 1);",
        "}",
    ]));
    assert_eq!(codes, ["E0306", "E0107", "E0301", "E0107"]);
    insta::assert_snapshot!("independent_errors_in_text_order", text);
}

#[test]
fn brackets_nested_too_deep() {
    // Generated code: more nested blocks than the compiler accepts.
    let depth = 300;
    let mut src = vec!["surface deep(float Kd = 1)", "{"];
    src.extend(std::iter::repeat_n("{", depth));
    src.push("Ci = Kd * Cs;");
    src.extend(std::iter::repeat_n("}", depth + 1));
    let (codes, text) = run(&lines(&src));
    assert_eq!(codes, ["E0315"]);
    insta::assert_snapshot!("brackets_nested_too_deep", text);
}

// ---------------------------------------------------------------------------------------------
// Unsupported RenderMan features (E04xx)

#[test]
fn ray_tracing() {
    let (codes, text) = run(&lines(&[
        "surface mirror(float Kr = 1)",
        "{",
        "    Ci = Kr * trace(P, reflect(I, normalize(N)));",
        "}",
    ]));
    assert_eq!(codes, ["E0401"]);
    insta::assert_snapshot!("ray_tracing", text);
}

#[test]
fn message_passing() {
    let (codes, text) = run(&lines(&[
        "surface bumped(float Kd = 1)",
        "{",
        "    float amplitude = 0;",
        "    displacement(\"Km\", amplitude);",
        "    Ci = Kd * amplitude;",
        "}",
    ]));
    assert_eq!(codes, ["E0402"]);
    insta::assert_snapshot!("message_passing", text);
}

#[test]
fn lightsource_outside_illuminance_or_with_a_computed_name() {
    let (codes, text) = run(&lines(&[
        "surface s(string which = \"__nondiffuse\")",
        "{",
        "    float nd = 0;",
        "    lightsource(\"__nondiffuse\", nd);",
        "    illuminance(P) {",
        "        lightsource(which, nd);",
        "        Ci += Cl * (1 - nd);",
        "    }",
        "}",
    ]));
    assert_eq!(codes, ["E0512", "E0505"], "{text}");
    assert!(text.contains("`lightsource` exists only inside `illuminance`"), "{text}");
    assert!(text.contains("the parameter's name as a string literal"), "{text}");
    // Inside illuminance, with a literal name, it checks.
    let (codes, text) = run(&lines(&[
        "surface s()",
        "{",
        "    illuminance(P) {",
        "        color tint = 1;",
        "        float nd = 0;",
        "        if (lightsource(\"__nondiffuse\", nd) == 1) { Ci += Cl * (1 - nd); }",
        "        lightsource(\"tint\", tint);",
        "    }",
        "}",
    ]));
    assert!(codes.is_empty(), "{text}");
    // A string differs from light to light: the category is read by `illuminance` instead.
    let (codes, text) = run(&lines(&[
        "surface s()",
        "{",
        "    illuminance(P) {",
        "        string c = \"\";",
        "        lightsource(\"__category\", c);",
        "    }",
        "}",
    ]));
    assert_eq!(codes, ["E0402"], "{text}");
    assert!(text.contains("illuminance(\"category\", ...)"), "{text}");
}

#[test]
fn surface_only_in_lights_and_volumes() {
    let (codes, text) = run(&lines(&[
        "surface s(float Kd = 1)",
        "{",
        "    float kd = 0;",
        "    surface(\"Kd\", kd);",
        "    Ci = kd;",
        "}",
    ]));
    assert_eq!(codes, ["E0511"], "{text}");
    assert!(text.contains("`surface` can only be called in light or volume shaders"), "{text}");
    let (codes, text) = run(&lines(&[
        "light l(float intensity = 1)",
        "{",
        "    float kd = 1;",
        "    if (surface(\"Kd\", kd) == 1) { kd *= 2; }",
        "    illuminate(P) { Cl = intensity * kd; }",
        "}",
        "volume v()",
        "{",
        "    color glow = 0;",
        "    surface(\"glow\", glow);",
        "    Ci += glow;",
        "}",
    ]));
    assert!(codes.is_empty(), "{text}");
}

#[test]
fn gather() {
    let (codes, text) = run(&lines(&[
        "surface ao(float samples = 16)",
        "{",
        "    float hits = 0;",
        "    gather(\"illuminance\", P, N, PI / 2, samples) {",
        "        hits += 1;",
        "    }",
        "    Ci = Cs * (1 - hits / samples);",
        "}",
    ]));
    assert_eq!(codes, ["E0403"]);
    insta::assert_snapshot!("gather", text);
}

#[test]
fn renderer_query() {
    let (codes, text) = run(&lines(&[
        "surface sided(float Kd = 1)",
        "{",
        "    float sides = 2;",
        "    attribute(\"Sides\", sides);",
        "    Ci = Kd * Cs * sides;",
        "}",
    ]));
    assert_eq!(codes, ["E0404"]);
    insta::assert_snapshot!("renderer_query", text);
}

#[test]
fn local_function_named_like_a_builtin() {
    // A function defined in the shader's body is the user's own, like a top-level one, but only
    // in the body that defines it.
    let (codes, text) = run(&lines(&[
        "surface own(float Kd = 1)",
        "{",
        "    float attribute(float x) { return x * Kd; }",
        "    Ci = Cs * attribute(0.5);",
        "}",
        "surface other(float Kd = 1)",
        "{",
        "    Ci = Cs * attribute(0.5);",
        "}",
    ]));
    assert_eq!(codes, ["E0404"]);
    insta::assert_snapshot!("local_function_named_like_a_builtin", text);
}

// ---------------------------------------------------------------------------------------------
// Where a diagnostic came from: included files and macro expansions

#[test]
fn error_in_included_file() {
    let loader =
        MemoryLoader::default().with_file("inc.sl", lines(&["float gamma = 2.2", "float gain = 1;"]));
    let mut src = vec!["#include \"inc.sl\""];
    src.extend(MATTE);
    let (codes, text) = run_with(&lines(&src), &loader);
    assert_eq!(codes, ["E0303"]);
    insta::assert_snapshot!("error_in_included_file", text);
}

#[test]
fn error_in_nested_include() {
    let loader = MemoryLoader::default()
        .with_file("lib/color.h", lines(&["#include \"consts.h\"", "color tint = color(1, 0.9, 0.8);"]))
        .with_file("lib/consts.h", lines(&["float EPSILON = 1e-6.;"]));
    let mut src = vec!["#include \"lib/color.h\""];
    src.extend(MATTE);
    let (codes, text) = run_with(&lines(&src), &loader);
    assert_eq!(codes, ["E0105"]);
    insta::assert_snapshot!("error_in_nested_include", text);
}

#[test]
fn error_in_macro_expansion() {
    let (codes, text) = run(&lines(&[
        "#define GAIN(x) ((x) * * 2)",
        "surface plastic(float Kd = 1)",
        "{",
        "    Ci = GAIN(Kd) * Cs;",
        "}",
    ]));
    assert_eq!(codes, ["E0301"]);
    insta::assert_snapshot!("error_in_macro_expansion", text);
}

#[test]
fn error_in_nested_macro_expansion() {
    let (codes, text) = run(&lines(&[
        "#define HUGE 1e39",
        "#define INTENSITY (HUGE * 2)",
        "surface plastic(float Kd = 1)",
        "{",
        "    Ci = Kd * Cs * INTENSITY;",
        "}",
    ]));
    assert_eq!(codes, ["E0107"]);
    insta::assert_snapshot!("error_in_nested_macro_expansion", text);
}
