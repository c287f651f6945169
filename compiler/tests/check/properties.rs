//! Generated input for the lexer, preprocessor and parser: random bytes and random token sequences
//! never panic, and every diagnostic points inside the input it was given.

use patina_compiler::check_source;
use patina_compiler::diag::render_text;
use patina_compiler::syntax::preprocess::MemoryLoader;
use proptest::prelude::*;

/// The vocabulary random token sequences are drawn from: every keyword and operator, names,
/// literals good and bad, directives (with their line breaks), comments and strings.
const VOCABULARY: &[&str] = &[
    "surface",
    "light",
    "displacement",
    "volume",
    "imager",
    "shader",
    "uniform",
    "varying",
    "output",
    "extern",
    "constant",
    "vertex",
    "fragment",
    "perlight",
    "primitive group",
    "primitive",
    "float",
    "color",
    "point",
    "vector",
    "normal",
    "matrix",
    "string",
    "void",
    "float3",
    "float4",
    "matrix3",
    "matrix4",
    "bool",
    "texref",
    "clampf",
    "int",
    "uint",
    "if",
    "else",
    "for",
    "while",
    "break",
    "continue",
    "return",
    "illuminance",
    "illuminate",
    "solar",
    "gather",
    "true",
    "false",
    "struct",
    "switch",
    "do",
    "{",
    "}",
    "(",
    ")",
    "[",
    "]",
    ";",
    ",",
    ".",
    "?",
    ":",
    "+",
    "-",
    "*",
    "/",
    "%",
    "^",
    "&",
    "|",
    "~",
    "!",
    "<",
    ">",
    "<=",
    ">=",
    "==",
    "!=",
    "&&",
    "||",
    "<<",
    ">>",
    "=",
    "+=",
    "-=",
    "*=",
    "/=",
    "%=",
    "&=",
    "|=",
    "^=",
    "<<=",
    ">>=",
    "++",
    "--",
    "#",
    "##",
    "x",
    "Ci",
    "P",
    "N",
    "noise",
    "trace",
    "0",
    "1",
    "0.5",
    ".5e3",
    "0x1Fu",
    "99999999999",
    "1e99",
    "1e",
    "\"s\"",
    "\"unterminated",
    "/* c */",
    "// line\n",
    "/* open",
    "\n",
    "\n#define M(a) a + a\n",
    "\n#define X X\n",
    "\n#if 1\n",
    "\n#if\n",
    "\n#else\n",
    "\n#endif\n",
    "\n#include \"missing.sl\"\n",
    "\n#include \"self.sl\"\n",
    "\n#include <pattern.sl>\n",
    "M(",
    "X",
    "\n#undef M\n",
    "\n#error e\n",
    "@",
    "\\\n",
];

/// Checks `src` and asserts that nothing panicked and every label lies inside its file.
fn check_spans(src: &str) {
    let loader = MemoryLoader::default().with_file("self.sl", "#include \"self.sl\"\nfloat y;\n");
    let checked = check_source("fuzz.sl", src, &loader);
    for d in checked.diagnostics.iter() {
        assert!(!d.labels.is_empty(), "diagnostic without a label: {d:?}");
        for label in &d.labels {
            let file = checked.sources.file(label.span.file);
            let text = &file.text;
            assert!(label.span.start <= label.span.end, "inverted span in {d:?}");
            assert!((label.span.end as usize) <= text.len(), "span past the end of {} in {d:?}", file.name);
            assert!(text.is_char_boundary(label.span.start as usize), "span not on a char boundary: {d:?}");
            assert!(text.is_char_boundary(label.span.end as usize), "span not on a char boundary: {d:?}");
        }
    }
    // Rendering must not fail or panic either.
    let list = checked.diagnostics.clone().into_vec();
    let rendered = render_text(&checked.sources, &list);
    assert_eq!(rendered.is_empty(), list.is_empty());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, .. ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        let text = String::from_utf8_lossy(&bytes);
        check_spans(&text);
    }

    #[test]
    fn random_token_sequences_never_panic(
        tokens in proptest::collection::vec(proptest::sample::select(VOCABULARY), 0..120),
        spaces in proptest::collection::vec(any::<bool>(), 120),
    ) {
        let mut src = String::new();
        for (token, space) in tokens.iter().zip(&spaces) {
            src.push_str(token);
            if *space {
                src.push(' ');
            }
        }
        check_spans(&src);
    }

    /// Mutations of a valid shader: one token removed or duplicated anywhere.
    #[test]
    fn mutated_shaders_never_panic(cut in 0usize..400, len in 0usize..6, dup in any::<bool>()) {
        let valid = include_str!("../../../examples/shaders/bricks.sl");
        let cut = cut.min(valid.len());
        let end = (cut + len).min(valid.len());
        if valid.is_char_boundary(cut) && valid.is_char_boundary(end) {
            let mutated = if dup {
                format!("{}{}{}", &valid[..end], &valid[cut..end], &valid[end..])
            } else {
                format!("{}{}", &valid[..cut], &valid[end..])
            };
            check_spans(&mutated);
        }
    }
}

#[test]
fn deep_nesting_is_refused_not_overflowed() {
    let depth = 100_000;
    let src = format!("surface s() {{ x = {}1{}; }}", "(".repeat(depth), ")".repeat(depth));
    let checked = check_source("deep.sl", &src, &MemoryLoader::default());
    let codes: Vec<&str> = checked.diagnostics.iter().map(|d| d.code.as_str()).collect();
    assert_eq!(codes, ["E0315"]);
}

#[test]
fn long_operator_chains_are_refused_not_overflowed() {
    // A chain of n operators is a tree n deep; these would overflow the stack when walked.
    for src in [
        format!("surface s() {{ float x = 1{}; }}", " + 1".repeat(100_000)),
        format!("surface s() {{ float x = {}1; }}", "- ".repeat(100_000)),
        format!("surface s() {{ float x; {} x = 1; }}", "if (x > 0) ".repeat(100_000)),
        format!("surface s() {{ float x; if (x > 0) x = 1; {} }}", "else if (x > 1) x = 2; ".repeat(100_000)),
    ] {
        let checked = check_source("long.sl", &src, &MemoryLoader::default());
        let codes: Vec<&str> = checked.diagnostics.iter().map(|d| d.code.as_str()).collect();
        assert_eq!(codes, ["E0315"]);
    }
    // A long statement under the limit is fine, and the limit is per statement.
    let fine = format!(
        "surface s() {{ float x = 1{}; {} if (x > 0) x = 0; {} }}",
        " + 1".repeat(1000),
        "x += 1; ".repeat(2000),
        "else if (x > 1) x = 1; ".repeat(500)
    );
    let checked = check_source("fine.sl", &fine, &MemoryLoader::default());
    assert!(checked.diagnostics.is_empty(), "{:?}", checked.diagnostics.iter().next());
}

#[test]
fn macro_bombs_are_stopped() {
    // Each level doubles the expansion: 2^40 tokens if nothing stopped it.
    let mut src = String::from("#define A0 x\n");
    for i in 1..=40 {
        src.push_str(&format!("#define A{i} A{} A{}\n", i - 1, i - 1));
    }
    src.push_str("surface s() { y = A40; }\n");
    let checked = check_source("bomb.sl", &src, &MemoryLoader::default());
    let codes: Vec<&str> = checked.diagnostics.iter().map(|d| d.code.as_str()).collect();
    // Stopped once, with the rest of the shader (its `}` included) read as written.
    assert_eq!(codes, ["E0218"], "{:?}", checked.diagnostics);
}
