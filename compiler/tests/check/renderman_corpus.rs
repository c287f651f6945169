//! Constructs that real RenderMan shaders use (the kind of code in Aqsis's shader set), each written
//! here in a few lines of our own: contextual Stanford keywords, the optional parameter lists of the
//! texture calls, `printf` and `format`, uniform `random()`, `option()`, `bake()` and Latin-1 files.

use patina_compiler::backend::defaults::constant_defaults;
use patina_compiler::check_source;
use patina_compiler::diag::{Severity, render_text};
use patina_compiler::syntax::preprocess::MemoryLoader;

/// Checks `src`; returns the error codes, the warning messages and the rendered diagnostics.
fn run(src: &str) -> (Vec<&'static str>, Vec<String>, String) {
    let checked = check_source("shader.sl", src, &MemoryLoader::default());
    let list: Vec<_> = checked.diagnostics.iter().cloned().collect();
    let errors = list.iter().filter(|d| d.severity == Severity::Error).map(|d| d.code.as_str()).collect();
    let warnings =
        list.iter().filter(|d| d.severity == Severity::Warning).map(|d| d.message.clone()).collect();
    (errors, warnings, render_text(&checked.sources, &list))
}

#[test]
fn stanford_keywords_are_names_in_renderman_files() {
    let src = "surface constant(float int = 1; float vertex = 2) {\n    float light = int + vertex;\n    float fragment = light;\n    Ci = Cs * fragment;\n}\n";
    let (errors, _, text) = run(src);
    assert!(errors.is_empty(), "{text}");
    let checked = check_source("shader.sl", src, &MemoryLoader::default());
    assert_eq!(checked.program.shaders[0].name, "constant");
}

#[test]
fn stanford_keywords_stay_keywords_in_stanford_files() {
    let (errors, _, text) = run("surface shader float4 s(float int = 1) { return float4(1, 1, 1, 1); }\n");
    assert_eq!(errors.first(), Some(&"E0306"), "{text}");
}

#[test]
fn texture_options_are_checked_and_kept_after_the_positional_arguments() {
    let src = "light spot(string map = \"m.shad\") {\n    illuminate(point(0, 0, 0)) {\n        Cl = shadow(map, Ps, \"samples\", 4, \"blur\", 0.01, \"bias\", 0.1);\n    }\n}\n";
    let checked = check_source("shader.sl", src, &MemoryLoader::default());
    let text = render_text(&checked.sources, &checked.diagnostics.iter().cloned().collect::<Vec<_>>());
    assert!(!checked.has_errors(), "{text}");
    assert!(checked.diagnostics.iter().next().is_none(), "every option is honoured: {text}");
    let shader = &checked.program.shaders[0];
    let call = shader
        .exprs
        .iter()
        .find_map(|e| match &e.kind {
            patina_compiler::ir::ExprKind::Builtin(b, args)
                if b.id == patina_compiler::ir::builtin::BuiltinId::Shadow =>
            {
                Some((b, args.clone()))
            }
            _ => None,
        })
        .expect("a shadow call");
    assert_eq!(call.0.params.len(), 2);
    assert_eq!(call.1.len(), 8);
    let names: Vec<String> = call.1[2..]
        .iter()
        .step_by(2)
        .map(|&a| match &shader.expr(a).kind {
            patina_compiler::ir::ExprKind::Literal(patina_compiler::ir::Literal::String(s)) => s.to_string(),
            other => format!("{other:?}"),
        })
        .collect();
    assert_eq!(names, ["samples", "blur", "bias"]);
    assert_eq!(shader.expr(call.1[3]).ty, patina_compiler::ir::types::Type::FLOAT);
}

#[test]
fn texture_options_not_honoured_or_unknown_are_warnings_and_wrong_types_errors() {
    let src = "surface s(string map = \"a.tx\") {\n    Ci = color texture(map, s, t, \"blur\", 0.1, \"filter\", \"gaussian\", \"wobble\", 2);\n}\n";
    let (errors, warnings, text) = run(src);
    assert!(errors.is_empty(), "{text}");
    assert_eq!(warnings.len(), 2, "{text}");
    assert!(warnings[0].contains("no option `wobble`"), "{text}");
    assert!(warnings[1].contains("ignores the options `blur`, `filter`"), "{text}");
    assert!(text.contains("the options of `texture` are `blur`, `width`"), "{text}");
    let (errors, _, text) =
        run("surface s() {\n    Ci = environment(\"e.env\", I, \"blur\", \"wide\");\n}\n");
    assert_eq!(errors, ["E0505"], "{text}");
    let (errors, _, text) = run("surface s() {\n    Ci = environment(\"e.env\", I, \"blur\");\n}\n");
    assert_eq!(errors, ["E0522"], "{text}");
}

#[test]
fn latin1_files_are_read_with_a_warning() {
    use patina_compiler::syntax::preprocess::{FsLoader, read_source_file};
    let dir = std::env::temp_dir().join(format!("patina-latin1-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let header = dir.join("author.h");
    std::fs::write(&header, b"/* \xa9 Fran\xe7ois */\nfloat half(float x) { return x / 2; }\n").unwrap();
    let root = dir.join("root.sl");
    std::fs::write(&root, b"#include \"author.h\"\n/* 90\xb0 */\nsurface s() { Ci = half(1); }\n").unwrap();
    let text = read_source_file(&root).unwrap().unwrap();
    assert!(text.contains("90\u{b0}"));
    let name = root.to_string_lossy().into_owned();
    let checked = check_source(&name, &text, &FsLoader::default());
    let list: Vec<_> = checked.diagnostics.iter().cloned().collect();
    let rendered = render_text(&checked.sources, &list);
    assert!(!checked.has_errors(), "{rendered}");
    let warnings: Vec<&str> = list.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(warnings.len(), 2, "{rendered}");
    assert!(warnings.iter().all(|w| w.contains("is not UTF-8; it was read as Latin-1")), "{rendered}");
    std::fs::write(dir.join("binary.sl"), b"s\xff\x00").unwrap();
    assert_eq!(
        read_source_file(&dir.join("binary.sl")),
        Err("not a text file (a NUL byte at offset 2)".into())
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn option_answers_format_and_exposure_and_warns_for_other_names() {
    let src = "surface s() {\n    float r[3];\n    float g[2];\n    uniform string pass = \"\";\n    float ok = option(\"Format\", r) + option(\"Exposure\", g);\n    float no = option(\"user:pass\", pass);\n    Ci = color(r[0] / r[1], g[0] * g[1], ok + no);\n}\n";
    let (errors, warnings, text) = run(src);
    assert!(errors.is_empty(), "{text}");
    assert_eq!(warnings.len(), 1, "{text}");
    assert!(warnings[0].contains("`option` does not know `user:pass`"), "{text}");
    let (errors, _, text) = run("surface s() {\n    float r[2];\n    option(\"Format\", r);\n}\n");
    assert_eq!(errors, ["E0505"], "{text}");
    assert!(text.contains("option `Format` is a `float[3]`, found `float[2]`"), "{text}");
    let (errors, _, text) = run("surface s() {\n    float r[3];\n    option(attribute, r);\n}\n");
    assert_eq!(errors, ["E0505"], "{text}");
    let (errors, _, text) =
        run("surface s() {\n    float r[3];\n    attribute(\"identifier:name\", r);\n}\n");
    assert_eq!(errors, ["E0404"], "{text}");
}

#[test]
fn bake_is_accepted_as_a_no_op_with_a_warning() {
    let src = "surface s(string file = \"x.bake\") {\n    color c = color noise(s, t);\n    bake(file, s, t, c);\n    Ci = c;\n}\n";
    let (errors, warnings, text) = run(src);
    assert!(errors.is_empty(), "{text}");
    assert_eq!(warnings, ["`bake` does nothing: bake files are not written"], "{text}");
    let checked = check_source("shader.sl", src, &MemoryLoader::default());
    let shader = &checked.program.shaders[0];
    assert!(
        !shader
            .exprs
            .iter()
            .any(|e| matches!(&e.kind, patina_compiler::ir::ExprKind::Builtin(b, _) if b.name() == "bake"))
    );
    let (errors, _, text) = run("surface s() {\n    bake(1, s, t, Ci);\n}\n");
    assert_eq!(errors, ["E0503"], "{text}");
}

#[test]
fn printf_and_format_are_checked_against_the_format() {
    let src = "surface s() {\n    printf(\"%f %d %p %c %s %%\\n\", s, 3, P, Cs, \"x\");\n    string name = format(\"map%d.%s\", 7, \"tx\");\n    Ci = texture(name, s, t);\n}\n";
    let (errors, warnings, text) = run(src);
    assert!(errors.is_empty(), "{text}");
    assert_eq!(warnings, ["`printf` prints only when the shader runs in the CPU interpreter"], "{text}");
    let checked = check_source("shader.sl", src, &MemoryLoader::default());
    let shader = &checked.program.shaders[0];
    let names: Vec<String> = shader
        .exprs
        .iter()
        .filter_map(|e| match &e.kind {
            patina_compiler::ir::ExprKind::Literal(patina_compiler::ir::Literal::String(s)) => {
                Some(s.to_string())
            }
            _ => None,
        })
        .collect();
    assert!(names.contains(&"map7.tx".to_string()), "{names:?}");
    let (errors, _, text) = run("surface s() {\n    printf(\"%f %f\", s);\n}\n");
    assert_eq!(errors, ["E0503"], "{text}");
    assert!(text.contains("the format has 2 conversions, and 1 value follow"), "{text}");
    let (errors, _, text) = run("surface s() {\n    printf(\"%c\", s);\n}\n");
    assert_eq!(errors, ["E0505"], "{text}");
    assert!(text.contains("`%c` prints a colour, found `float`"), "{text}");
    let (errors, _, text) = run("surface s() {\n    string n = format(\"%f\", s);\n}\n");
    assert_eq!(errors, ["E0505"], "{text}");
    assert!(text.contains("`format` needs values known when the shader is compiled"), "{text}");
}

#[test]
fn printf_formats_as_rsl() {
    use patina_compiler::sema::builtins::{PrintValue, printf_conversions, printf_format};
    assert_eq!(printf_conversions("%f %5.2d %% %p"), ['f', 'd', 'p']);
    let values = [
        PrintValue::Numbers(vec![0.5]),
        PrintValue::Numbers(vec![-3.7]),
        PrintValue::Numbers(vec![1.0, 2.0, 3.0]),
        PrintValue::Text("ok".into()),
    ];
    assert_eq!(printf_format("%f %d [%.1p] %s 100%%", &values), "0.500000 -3 [1.0 2.0 3.0] ok 100%");
}

#[test]
fn the_wgsl_backend_compiles_printf_uniform_random_option_and_bake() {
    use patina_compiler::backend::wgsl;
    let src = "surface s(string bakename = \"b.bake\") {\n    uniform string pass = \"\";\n    option(\"user:pass\", pass);\n    float r[3];\n    float g[2];\n    option(\"Format\", r);\n    option(\"Exposure\", g);\n    uniform color c = color(random(), random(), random());\n    printf(\"%f %c\\n\", s, c);\n    bake(bakename, s, t, c);\n    Ci = c * r[0] / r[1] * g[0] + random();\n}\n";
    let checked = check_source("shader.sl", src, &MemoryLoader::default());
    let list: Vec<_> = checked.diagnostics.iter().cloned().collect();
    assert!(!checked.has_errors(), "{}", render_text(&checked.sources, &list));
    let shader = patina_compiler::opt::Prepared::new(checked.program.shaders[0].clone());
    let stages = patina_compiler::split::split(&shader).expect("splits");
    let compiled = wgsl::compile(&stages, &[], &[], &constant_defaults);
    assert!(compiled.is_ok(), "{:?}", compiled.err());
}

/// The shader of `src`, bound with nothing fixed.
fn bound(src: &str) -> patina_compiler::ir::Shader {
    let checked = check_source("shader.sl", src, &MemoryLoader::default());
    let list: Vec<_> = checked.diagnostics.iter().cloned().collect();
    assert!(!checked.has_errors(), "{}", render_text(&checked.sources, &list));
    let shader = &checked.program.shaders[0];
    patina_compiler::bind::specialize(shader, &[], &[], patina_compiler::bind::Consumed::All).shader
}

#[test]
fn string_variables_stored_in_straight_line_code_are_known_where_read() {
    use patina_compiler::backend::wgsl;
    // expensive.sl's pattern: a file name made by `concat`, read under a branch.
    let src = "surface s(string base = \"a\"; string ext = \".tex\") {\n    uniform string f = \"\";\n    f = concat(base, ext);\n    color c = 0;\n    if (s > 0.5) {\n        c = color texture(f, s, t);\n    } else {\n        c = 1;\n    }\n    Ci = c;\n}\n";
    let shader = patina_compiler::opt::Prepared::new(bound(src));
    let stages = patina_compiler::split::split(&shader).expect("splits");
    let compiled = wgsl::compile(&stages, &[], &[], &constant_defaults);
    assert!(compiled.is_ok(), "{:?}", compiled.err());
    // A read in a loop that stores the variable later is left alone.
    let src = "surface s() {\n    uniform string g = \"x\";\n    uniform float i;\n    for (i = 0; i < 2; i += 1) {\n        Ci += match(\"x\", g);\n        g = \"y\";\n    }\n}\n";
    let shader = bound(src);
    let subject = shader
        .exprs
        .iter()
        .find_map(|e| match &e.kind {
            patina_compiler::ir::ExprKind::Builtin(b, args)
                if b.id == patina_compiler::ir::builtin::BuiltinId::Match =>
            {
                Some(args[1])
            }
            _ => None,
        })
        .expect("a match call");
    assert!(matches!(shader.expr(subject).kind, patina_compiler::ir::ExprKind::Local(_)));
}
