//! The compiler's resource limits (docs/limits.md): each one refused with its diagnostic, at the
//! construct that crosses it; input just under a limit still compiles. No test asserts a wall
//! time (the project keeps timings in benchmarks): input built to take minutes or forever past a
//! limit shows the limit holds by finishing at all.

use patina_compiler::backend::MAX_LOOP_ITERATIONS;
use patina_compiler::backend::binding::BoundLight;
use patina_compiler::backend::defaults::constant_defaults;
use patina_compiler::backend::wgsl::{self, MAX_LIGHTS, compile_kernel};
use patina_compiler::diag::Diagnostic;
use patina_compiler::syntax::preprocess::{MAX_FILE_SIZE, MAX_TOTAL_SOURCE, MemoryLoader};
use patina_compiler::{Checked, check_source};

fn check(src: &str) -> Checked {
    check_source("shader.sl", src, &MemoryLoader::default())
}

/// The only error of `checked`, which must have exactly one.
fn only_error(checked: &Checked) -> &Diagnostic {
    let errors: Vec<&Diagnostic> = checked.diagnostics.iter().filter(|d| d.is_error()).collect();
    assert_eq!(
        errors.len(),
        1,
        "expected one error, got {:?}",
        errors.iter().map(|d| &d.message).collect::<Vec<_>>()
    );
    errors[0]
}

/// The source text under the diagnostic's primary span, and the span's start.
fn at(checked: &Checked, d: &Diagnostic) -> (String, usize) {
    let span = d.primary_span();
    (checked.sources.text(span).to_string(), span.start as usize)
}

/// The byte offset of the `n`th (from 0) occurrence of `needle` in `text`.
fn nth(text: &str, needle: &str, n: usize) -> usize {
    text.match_indices(needle).nth(n).map(|(i, _)| i).expect("occurs often enough")
}

/// `depth` statements nested in one another: `ifs_per_block` `if`s without braces, then a block.
fn nested_statements(ifs_per_block: usize, blocks: usize) -> String {
    let mut s = String::from("surface t() {\n    float x = 0;\n");
    for _ in 0..blocks {
        s.push_str(&"if (x < 1) ".repeat(ifs_per_block));
        s.push_str("{\n x = x + 1;\n");
    }
    s.push_str(&"}\n".repeat(blocks));
    s.push_str("    Ci = x;\n}\n");
    s
}

#[test]
fn statements_nested_without_braces_stop_at_the_limit() {
    // 300 `if`s with no braces: under the operator limit (600 operators), over the depth limit.
    let src = format!(
        "surface t() {{\n    float x = 0;\n    {}x = 1;\n    Ci = x;\n}}\n",
        "if (x < 1) ".repeat(300)
    );
    let checked = check(&src);
    let d = only_error(&checked);
    assert_eq!(d.code.as_str(), "E0315");
    assert_eq!(d.message, "statements nested more than 256 deep");
    // The shader's `{` is the first level, so the 256th `if` (index 255) is the 257th level.
    assert_eq!(at(&checked, d), ("if".to_string(), nth(&src, "if", 255)));
    assert!(d.help.as_deref().is_some_and(|h| h.contains("&&")));
}

#[test]
fn statements_nested_through_blocks_stop_at_the_limit() {
    // Four `if`s per block, 250 blocks: 1250 levels, each statement well under the operator
    // limit. This compiled for minutes before the limit.
    let src = nested_statements(4, 250);
    let checked = check(&src);
    let d = only_error(&checked);
    assert_eq!(d.code.as_str(), "E0315");
    assert_eq!(d.message, "statements nested more than 256 deep");
    // Levels: the shader's `{`, then five per block (four `if`s and a `{`): the 256th level after
    // the shader's brace is the first `if` of block 52 (index 51 of blocks, if 204 overall).
    assert_eq!(at(&checked, d), ("if".to_string(), nth(&src, "if", 204)));
}

#[test]
fn statements_under_the_depth_limit_compile() {
    // 50 blocks of four `if`s (251 levels with the shader's brace), and `for` loops whose header
    // `;`s end nothing.
    let checked = check(&nested_statements(4, 50));
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    let mut src = String::from("surface t() {\n    float i, x = 0;\n");
    for _ in 0..100 {
        src.push_str("for (i = 0; i < 2; i += 1) {\n");
    }
    src.push_str("x += 1;\n");
    src.push_str(&"}\n".repeat(100));
    src.push_str("Ci = x;\n}\n");
    let checked = check(&src);
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
}

#[test]
fn a_root_file_over_the_size_limit_is_refused_before_lexing() {
    let mut src = String::from("surface t() { Ci = 1; }\n");
    src.push_str(&" ".repeat(MAX_FILE_SIZE));
    let checked = check(&src);
    let d = only_error(&checked);
    assert_eq!(d.code.as_str(), "E0220");
    assert_eq!(
        d.message,
        format!("`shader.sl` is {} bytes, over the limit of 16777216 bytes per source file", src.len())
    );
    assert_eq!(at(&checked, d), (String::new(), 0));
}

#[test]
fn an_included_file_over_the_size_limit_is_refused_at_its_include() {
    let big = "\n".repeat(MAX_FILE_SIZE + 1);
    let loader = MemoryLoader::default().with_file("big.sl", big);
    let src = "#include \"small.sl\"\n#include \"big.sl\"\nsurface t() { Ci = 1; }\n";
    let loader = loader.with_file("small.sl", "float half = 0.5;\n");
    let checked = check_source("shader.sl", src, &loader);
    let d = only_error(&checked);
    assert_eq!(d.code.as_str(), "E0220");
    assert!(d.message.starts_with("`big.sl` is 16777217 bytes"), "{}", d.message);
    assert_eq!(at(&checked, d), ("#include \"big.sl\"".to_string(), nth(src, "#include", 1)));
}

#[test]
fn includes_adding_up_past_the_total_limit_are_refused_at_the_include_that_crosses_it() {
    // Each file (15 MiB) is under the per-file limit; the fifth brings the total past 64 MiB, and
    // the sixth is skipped without a second report.
    let part = "\n".repeat(15 << 20);
    let mut loader = MemoryLoader::default();
    let mut src = String::new();
    for i in 0..6 {
        loader = loader.with_file(format!("part{i}.sl"), part.clone());
        src.push_str(&format!("#include \"part{i}.sl\"\n"));
    }
    src.push_str("surface t() { Ci = 1; }\n");
    let checked = check_source("shader.sl", &src, &loader);
    let d = only_error(&checked);
    assert_eq!(d.code.as_str(), "E0220");
    let total = src.len() + 5 * part.len();
    assert!(total > MAX_TOTAL_SOURCE && src.len() + 4 * part.len() <= MAX_TOTAL_SOURCE);
    assert!(part.len() < MAX_FILE_SIZE);
    assert_eq!(
        d.message,
        format!(
            "the source with its includes reaches {total} bytes at `part4.sl`, over the limit of 67108864 bytes"
        )
    );
    assert_eq!(at(&checked, d), ("#include \"part4.sl\"".to_string(), nth(&src, "#include", 4)));
}

/// Functions `f0` ... `f{n}`, each calling the next once, and a shader calling `f0`.
fn call_chain(n: usize) -> String {
    let mut s = format!("float f{n}(float x) {{ return x + 1; }}\n");
    for i in (0..n).rev() {
        s.push_str(&format!("float f{i}(float x) {{ return f{}(x) * 2; }}\n", i + 1));
    }
    s.push_str("surface t() { Ci = f0(s); }\n");
    s
}

#[test]
fn a_long_chain_of_calls_stops_at_the_inlining_depth() {
    // 300 functions: past the refused call, the rest are checked on their own and report nothing.
    let src = call_chain(300);
    let checked = check(&src);
    let d = only_error(&checked);
    assert_eq!(d.code.as_str(), "E0521");
    assert_eq!(d.message, "calls nested more than 64 deep");
    // The call of `f0` is depth 1, so the call of `f64` (in `f63`) would be depth 65.
    let call = src.find("f64(x)").expect("f63 calls f64");
    assert_eq!(at(&checked, d), ("f64(x)".to_string(), call));
    assert!(
        d.labels.iter().any(|l| checked.sources.text(l.span) == "f0(s)" && l.message.contains("outermost"))
    );
    // 64 calls deep is allowed.
    assert!(!check(&call_chain(63)).has_errors());
}

#[test]
fn a_call_tree_of_exponential_size_is_refused_quickly() {
    // `g0` calls `g1` twice, ... thirty levels: 2^30 inlined copies of `g30`.
    let n = 30;
    let mut src = format!("float g{n}(float x) {{ return x + 1; }}\n");
    for i in (0..n).rev() {
        src.push_str(&format!("float g{i}(float x) {{ return g{j}(x) + g{j}(x * 2); }}\n", j = i + 1));
    }
    src.push_str("surface t() { Ci = g0(s); }\n");
    // No wall-clock bound (timings belong in benchmarks): the inliner building the tree would
    // mean 2^30 copies, which never finishes, so finishing with E0521 shows the refusal comes
    // at the limit, not after the growth.
    let checked = check(&src);
    let d = only_error(&checked);
    assert_eq!(d.code.as_str(), "E0521");
    assert_eq!(d.message, "with its calls inlined, the shader grows past 500000 expressions");
    let (text, _) = at(&checked, d);
    assert!(text.starts_with('g') && text.contains("(x"), "the span is a call: {text}");
}

/// A shader with a loop whose trip count depends on data (`while (x > 0) x += 1` runs forever)
/// and a counting loop of four iterations.
pub const UNBOUNDED_LOOP: &str = "surface t(float start = 1) {
    float x = start;
    while (x > 0) {
        x += 1;
    }
    float i, y = 0;
    for (i = 0; i < 4; i += 1) {
        y += i;
    }
    Ci = x + y;
}
";

/// Whether a naga loop body starts its iteration with the iteration cap: `if count >= MAX { break }`.
fn has_iteration_cap(f: &naga::Function, body: &naga::Block) -> bool {
    let cap = u32::try_from(MAX_LOOP_ITERATIONS).unwrap();
    body.iter().any(|s| match s {
        naga::Statement::If { condition, accept, .. } => {
            matches!(
                f.expressions[*condition],
                naga::Expression::Binary { op: naga::BinaryOperator::GreaterEqual, right, .. }
                    if matches!(f.expressions[right], naga::Expression::Literal(naga::Literal::U32(c)) if c == cap)
            ) && matches!(accept.first(), Some(naga::Statement::Break))
        }
        _ => false,
    })
}

/// For every loop of the module: whether it has the iteration cap.
fn loops(module: &naga::Module) -> Vec<bool> {
    fn walk(f: &naga::Function, block: &naga::Block, out: &mut Vec<bool>) {
        for s in block.iter() {
            match s {
                naga::Statement::Loop { body, continuing, .. } => {
                    out.push(has_iteration_cap(f, body));
                    walk(f, body, out);
                    walk(f, continuing, out);
                }
                naga::Statement::If { accept, reject, .. } => {
                    walk(f, accept, out);
                    walk(f, reject, out);
                }
                naga::Statement::Block(b) => walk(f, b, out),
                _ => {}
            }
        }
    }
    let mut out = Vec::new();
    for (_, f) in module.functions.iter() {
        walk(f, &f.body, &mut out);
    }
    for e in &module.entry_points {
        walk(&e.function, &e.function.body, &mut out);
    }
    out
}

#[test]
fn gpu_loops_with_data_dependent_trip_counts_are_capped_and_counting_loops_are_not() {
    let checked = check(UNBOUNDED_LOOP);
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    let shader = patina_compiler::opt::Prepared::new(checked.program.shaders[0].clone());
    let kernel = compile_kernel(&shader, &[], &[], &["start"], &["Ci"]).expect("compiles");
    // The `while` first, then the `for`.
    assert_eq!(loops(&kernel.module), [true, false]);
    // The counter is reset before the loop and advanced at the top of its body; the text shows it.
    let text =
        naga::back::wgsl::write_string(&kernel.module, &kernel.info, naga::back::wgsl::WriterFlags::empty())
            .expect("writes");
    assert!(text.contains("65535u"), "{text}");
}

#[test]
fn a_counter_stored_in_the_body_or_reused_keeps_the_cap() {
    // The counter changes in the body: the trip count is no longer the header's.
    let inside = "surface t() { float i, y = 0; for (i = 0; i < 4; i += 1) { i -= 1; y += 1; } Ci = y; }";
    // A loop the interpreter's arithmetic never ends (the step is lost to rounding at 2^24).
    let stuck =
        "surface t() { float i, y = 0; for (i = 16777216; i < 16777220; i += 1) { y += 1; } Ci = y; }";
    // Counting down with `>=`: five iterations, no cap.
    let down = "surface t() { float i, y = 0; for (i = 4; i >= 0; i -= 1) { y += 1; } Ci = y; }";
    for (src, capped) in [(inside, [true]), (stuck, [true]), (down, [false])] {
        let checked = check(src);
        assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
        let shader = patina_compiler::opt::Prepared::new(checked.program.shaders[0].clone());
        let kernel = compile_kernel(&shader, &[], &[], &[], &["Ci"]).expect("compiles");
        assert_eq!(loops(&kernel.module), capped, "{src}");
    }
}

#[test]
fn more_lights_than_the_limit_are_refused_and_the_limit_itself_compiles() {
    let surface = check("surface lit() {\n    illuminance(P) { Ci += Cl; }\n}\n");
    let light = check("light one() {\n    illuminate(point(0, 1, 0)) { Cl = 1; }\n}\n");
    let shader = patina_compiler::opt::Prepared::new(surface.program.shaders[0].clone());
    let stages = patina_compiler::split::split(&shader).expect("splits");
    let one = patina_compiler::opt::Prepared::new(light.program.shaders[0].clone());
    let bound = |n: usize| -> Vec<BoundLight> {
        (0..n).map(|_| BoundLight { shader: &one, strings: vec![], categories: vec![] }).collect()
    };
    assert!(wgsl::compile(&stages, &bound(MAX_LIGHTS), &[], &constant_defaults).is_ok());
    let d =
        wgsl::compile(&stages, &bound(MAX_LIGHTS + 1), &[], &constant_defaults).expect_err("over the limit");
    assert_eq!(d.code.as_str(), "E0704");
    assert_eq!(d.message, "65 lights are bound to `lit`, over the limit of 64");
    assert!(surface.sources.text(d.primary_span()).starts_with("surface lit()"));
    assert_eq!(d.notes, ["light 65 (`one`) is the first over the limit"]);
}

#[test]
fn an_array_over_the_length_limit_is_refused_at_its_size() {
    let src = "surface t() {\n    float table[100000000];\n    table[3] = 1;\n    Ci = table[3];\n}\n";
    let checked = check(src);
    let d = only_error(&checked);
    assert_eq!(d.code.as_str(), "E0315");
    assert_eq!(d.message, "an array of 100000000 elements, over the limit of 4096");
    assert_eq!(at(&checked, d), ("100000000".to_string(), src.find("100000000").unwrap()));
    assert!(!check("surface t() { float table[4096]; table[3] = 1; Ci = table[3]; }").has_errors());
}

#[test]
fn statements_nested_through_inlined_calls_stop_at_the_combined_limit() {
    // Twenty functions, each nesting 200 `if`s around its call of the next: every function is
    // under the syntax's depth limit, but inlined they nest 4000 deep (this compiled for minutes).
    let n = 20;
    let mut src = format!("float f{n}(float x) {{ return x; }}\n");
    for i in (0..n).rev() {
        src.push_str(&format!(
            "float f{i}(float x) {{ float y = x;\n{}y = f{}(y);\n return y; }}\n",
            "if (y > 0) ".repeat(200),
            i + 1
        ));
    }
    src.push_str("surface t() { Ci = f0(s); }\n");
    let checked = check(&src);
    let d = only_error(&checked);
    assert_eq!(d.code.as_str(), "E0521");
    assert_eq!(d.message, "statements nested more than 512 deep with calls inlined");
    // Levels: f0's inlined body 1, its `if` bodies 2 to 201, f1's body 202, ..., f2's body 403,
    // the body of f2's `if` number k (from 0) 404 + k: the body of `if` 109, which is `if` 110,
    // would be level 513.
    let f2 = src.find("float f2(").unwrap();
    let (text, start_at) = at(&checked, d);
    assert!(text.starts_with("if (y > 0)"), "{text}");
    assert_eq!(start_at, f2 + src[f2..].find("if").unwrap() + 110 * "if (y > 0) ".len());
    assert!(d.labels.iter().any(|l| l.message == "in this call of `f2`"));
}
