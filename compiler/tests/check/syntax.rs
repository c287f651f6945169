//! The front end on well-formed input: every construct of both styles parses to the tree it should,
//! the preprocessor expands and includes as cpp would, and spans lead back to the right text.

use patina_compiler::check_source;
use patina_compiler::diag::Diagnostics;
use patina_compiler::source::SourceMap;
use patina_compiler::syntax::ast::*;
use patina_compiler::syntax::parse_file;
use patina_compiler::syntax::preprocess::{FsLoader, MemoryLoader};

/// Runs the front end alone (no semantics: these snippets use undeclared names on purpose).
fn parse(src: &str) -> (Module, Diagnostics, SourceMap) {
    let mut sources = SourceMap::new();
    let root = sources.add_file("t.sl", src, None);
    let mut diags = Diagnostics::default();
    let module = parse_file(&mut sources, root, &MemoryLoader::default(), &mut diags);
    (module, diags, sources)
}

/// A compact rendering of an expression tree, so tests can state structure in one line.
fn sexpr(e: &Expr) -> String {
    let list = |head: &str, items: &[&Expr]| {
        let mut s = format!("({head}");
        for item in items {
            s.push(' ');
            s.push_str(&sexpr(item));
        }
        s + ")"
    };
    match &e.kind {
        ExprKind::Int { value, unsigned } => format!("{value}{}", if *unsigned { "u" } else { "" }),
        ExprKind::Float(v) => format!("{v:?}"),
        ExprKind::String(s) => format!("{s:?}"),
        ExprKind::Bool(b) => b.to_string(),
        ExprKind::Name(n) => n.name.to_string(),
        ExprKind::Unary { op, operand } => {
            let op = match op {
                UnaryOp::Neg => "neg",
                UnaryOp::Plus => "pos",
                UnaryOp::Not => "!",
                UnaryOp::BitNot => "~",
            };
            list(op, &[operand])
        }
        ExprKind::Binary { op, lhs, rhs } => list(op.symbol(), &[lhs, rhs]),
        ExprKind::Assign { op, target, value } => {
            list(&format!("{}=", op.map_or("", BinaryOp::symbol)), &[target, value])
        }
        ExprKind::Step { op, prefix, target } => {
            let op = match op {
                StepOp::Increment => "++",
                StepOp::Decrement => "--",
            };
            list(&if *prefix { format!("{op}pre") } else { format!("{op}post") }, &[target])
        }
        ExprKind::Conditional { cond, then, otherwise } => list("?", &[cond, then, otherwise]),
        ExprKind::Call { callee, args } => {
            list(&format!("call {}", callee.name), &args.iter().collect::<Vec<_>>())
        }
        ExprKind::Cast { ty, space, operand } => match space {
            Some((space, _)) => list(&format!("cast {} {space:?}", ty.name.keyword()), &[operand]),
            None => list(&format!("cast {}", ty.name.keyword()), &[operand]),
        },
        ExprKind::Tuple(items) => list("tuple", &items.iter().collect::<Vec<_>>()),
        ExprKind::Braced(items) => list("braced", &items.iter().collect::<Vec<_>>()),
        ExprKind::Index { base, index } => list("index", &[base, index]),
        ExprKind::Error => "<error>".into(),
    }
}

/// Parses `x = <expr>;` inside a surface shader and renders the right-hand side.
fn parse_expr(expr: &str) -> String {
    let src = format!("surface s() {{ x = {expr}; }}");
    let (module, diags, _) = parse(&src);
    assert!(diags.is_empty(), "{expr}: {diags:?}");
    let Item::Shader(shader) = &module.items[0] else { panic!("not a shader") };
    let StmtKind::Expr(e) = &shader.body.stmts[0].kind else { panic!("not an expression statement") };
    let ExprKind::Assign { value, .. } = &e.kind else { panic!("not an assignment") };
    sexpr(value)
}

fn parse_ok(src: &str) -> Module {
    let (module, diags, sources) = parse(src);
    let rendered = patina_compiler::diag::render_text(&sources, &diags.clone().into_vec());
    assert!(diags.is_empty(), "unexpected diagnostics:\n{rendered}");
    module
}

#[test]
fn precedence_follows_renderman_for_dot_and_cross() {
    assert_eq!(parse_expr("a + b ^ c . d * e"), "(+ a (^ b (* (. c d) e)))");
    assert_eq!(parse_expr("a * b ^ c"), "(^ (* a b) c)");
    assert_eq!(parse_expr("-a . b"), "(. (neg a) b)");
    assert_eq!(parse_expr("N . I > 0"), "(> (. N I) 0)");
}

#[test]
fn precedence_follows_c_elsewhere() {
    assert_eq!(
        parse_expr("a || b && c | d & e == f < g << h + i"),
        "(|| a (&& b (| c (& d (== e (< f (<< g (+ h i))))))))"
    );
    assert_eq!(parse_expr("a - b - c"), "(- (- a b) c)");
    assert_eq!(parse_expr("a / b % c"), "(% (/ a b) c)");
    assert_eq!(parse_expr("!a && ~b"), "(&& (! a) (~ b))");
    assert_eq!(parse_expr("a ? b : c ? d : e"), "(? a b (? c d e))");
    assert_eq!(parse_expr("y = z += 2"), "(= y (+= z 2))");
}

#[test]
fn casts_constructors_and_tuples() {
    assert_eq!(parse_expr("color (1, 0, 0)"), "(cast color (tuple 1 0 0))");
    assert_eq!(parse_expr("point \"shader\" (0, 0, 0)"), "(cast point \"shader\" (tuple 0 0 0))");
    assert_eq!(parse_expr("color noise(P) * 2"), "(* (cast color (call noise P)) 2)");
    assert_eq!(parse_expr("float (i) / 2"), "(/ (cast float i) 2)");
    assert_eq!(parse_expr("float -x"), "(cast float (neg x))");
    assert_eq!(
        parse_expr("matrix (1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1)"),
        "(cast matrix (tuple 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1))"
    );
    assert_eq!(parse_expr("{a, b, 0, 1}"), "(braced a b 0 1)");
    assert_eq!(parse_expr("{c * 2, 1}[3]"), "(index (braced (* c 2) 1) 3)");
}

#[test]
fn renderman_type_words_are_names_outside_type_position() {
    assert_eq!(parse_expr("color - point"), "(- color point)");
    assert_eq!(parse_expr("color * vector[0]"), "(* color (index vector 0))");
    let module =
        parse_ok("surface shader float4 f(float4 color) { float3 normal = rgb(color); return {normal, 1}; }");
    let Item::Shader(shader) = &module.items[0] else { panic!() };
    assert_eq!(shader.params[0].name.name, "color");
    assert_eq!(shader.params[0].ty.name, TypeName::Float4);
}

#[test]
fn postfix_calls_indexing_and_steps() {
    assert_eq!(parse_expr("texture(t, uv)[0]"), "(index (call texture t uv) 0)");
    assert_eq!(parse_expr("m[1][2]++"), "(++post (index (index m 1) 2))");
    assert_eq!(parse_expr("--i"), "(--pre i)");
    assert_eq!(parse_expr("f()"), "(call f)");
    assert_eq!(parse_expr("\"name.tx\"[1]"), "(index \"name.tx\" 1)");
}

#[test]
fn literals_have_their_values() {
    assert_eq!(parse_expr("0x1F"), "31");
    assert_eq!(parse_expr("4294967295u"), "4294967295u");
    assert_eq!(parse_expr(".5"), "0.5");
    assert_eq!(parse_expr("1e3"), "1000.0");
    assert_eq!(parse_expr("2.5f"), "2.5");
    assert_eq!(parse_expr("true"), "true");
    assert_eq!(parse_expr("\"a\\tb\""), "\"a\\tb\"");
}

#[test]
fn else_binds_to_the_nearest_if() {
    let module = parse_ok("surface s() { if (a) if (b) x = 1; else x = 2; }");
    let Item::Shader(shader) = &module.items[0] else { panic!() };
    let StmtKind::If { then, otherwise, .. } = &shader.body.stmts[0].kind else { panic!() };
    assert!(otherwise.is_none(), "the outer if has no else");
    assert!(matches!(&then.kind, StmtKind::If { otherwise: Some(_), .. }), "the inner if has it");
}

#[test]
fn renderman_parameter_groups() {
    let module = parse_ok(
        "surface s(float Ka = 1, Kd = .5; uniform color c = 1; output varying float o; float a[3] = {1,2,3};) {}",
    );
    let Item::Shader(shader) = &module.items[0] else { panic!() };
    let summary: Vec<String> = shader
        .params
        .iter()
        .map(|p| {
            let rate = p.qualifiers.rate.map_or("", |r| r.0.keyword());
            let output = if p.qualifiers.output.is_some() { "output " } else { "" };
            let array = p.array.map_or(String::new(), |a| format!("[{}]", a.len.unwrap_or(0)));
            format!("{output}{rate} {} {}{array}={}", p.ty.name.keyword(), p.name.name, p.default.is_some())
        })
        .collect();
    assert_eq!(
        summary,
        [
            " float Ka=true",
            " float Kd=true",
            "uniform color c=true",
            "output varying float o=false",
            " float a[3]=true"
        ]
    );
    assert_eq!(shader.style, ShaderStyle::RenderMan);
}

#[test]
fn stanford_items_and_rates() {
    let module = parse_ok(
        "light shader float4 l(float4 c) { return c; }
         surface float3 obj(float3 v) { return v; }
         float twice(float x) { return 2 * x; }
         surface shader float4 s(vertex float4 uv, primitive group texref t) {
             perlight fragment float4 p = Cl;
             constant float k = 2;
             return integrate(p) * k;
         }",
    );
    assert_eq!(module.items.len(), 4);
    let Item::Shader(light) = &module.items[0] else { panic!() };
    assert_eq!(light.kind, ShaderKind::Light);
    assert!(matches!(
        light.style,
        ShaderStyle::Stanford { return_type: TypeSpec { name: TypeName::Float4, .. } }
    ));
    let Item::Function(obj) = &module.items[1] else { panic!() };
    assert_eq!(obj.context.map(|c| c.0), Some(ShaderKind::Surface));
    let Item::Function(twice) = &module.items[2] else { panic!() };
    assert_eq!(twice.context, None);
    let Item::Shader(surface) = &module.items[3] else { panic!() };
    assert_eq!(surface.params[1].qualifiers.rate.map(|r| r.0), Some(RateQualifier::PrimitiveGroup));
    let StmtKind::Decl(p) = &surface.body.stmts[0].kind else { panic!() };
    assert!(p.qualifiers.perlight.is_some());
    assert_eq!(p.qualifiers.rate.map(|r| r.0), Some(RateQualifier::Fragment));
}

#[test]
fn statements_of_every_kind() {
    let module = parse_ok(
        "surface s() {
            float a = 1, b[2];
            float local(float x) { return x; }
            ;
            for (int i = 0; i < 4; i += 1) { if (i == 2) continue; if (i == 3) break 1; }
            for (;;) break;
            while (a < 2) a += 1;
            illuminance(P, N, PI/2) Ci += Cl;
            illuminance(\"diffuse\", P) { Ci += Cl; }
            return;
        }
        light l() { illuminate(P, N, 1) Cl = 1; solar() Cl = 1; solar(N, 0) { Cl = 1; } }",
    );
    let Item::Shader(s) = &module.items[0] else { panic!() };
    let kinds: Vec<&str> = s
        .body
        .stmts
        .iter()
        .map(|st| match &st.kind {
            StmtKind::Decl(_) => "decl",
            StmtKind::Function(_) => "function",
            StmtKind::Empty => "empty",
            StmtKind::For { .. } => "for",
            StmtKind::While { .. } => "while",
            StmtKind::Illuminance { .. } => "illuminance",
            StmtKind::Return(None) => "return",
            _ => "other",
        })
        .collect();
    assert_eq!(
        kinds,
        ["decl", "function", "empty", "for", "for", "while", "illuminance", "illuminance", "return"]
    );
    let Item::Shader(l) = &module.items[1] else { panic!() };
    assert!(matches!(l.body.stmts[0].kind, StmtKind::Illuminate { .. }));
    assert!(matches!(&l.body.stmts[1].kind, StmtKind::Solar { args, .. } if args.is_empty()));
}

#[test]
fn global_declarations() {
    let module = parse_ok("constant float scale = 2; uniform float k;");
    assert!(matches!(&module.items[..], [Item::Variable(_), Item::Variable(_)]));
}

#[test]
fn macros_expand_as_in_cpp() {
    let src = "#define W 0.25\n\
               #define SQ(x) ((x) * (x))\n\
               #define NAME(s) #s\n\
               #define GLUE(a, b) a ## b\n\
               #define SELF SELF + 1\n\
               #define EMPTY()\n\
               surface s() { x = SQ(W + 1); y = NAME(a  \"q\"); z = GLUE(fo, o)(1); w = SELF; EMPTY() }";
    let module = parse_ok(src);
    let Item::Shader(s) = &module.items[0] else { panic!() };
    let rhs: Vec<String> = s
        .body
        .stmts
        .iter()
        .map(|st| match &st.kind {
            StmtKind::Expr(Expr { kind: ExprKind::Assign { value, .. }, .. }) => sexpr(value),
            _ => "other".into(),
        })
        .collect();
    assert_eq!(rhs, ["(* (+ 0.25 1) (+ 0.25 1))", "\"a \\\"q\\\"\"", "(call foo 1)", "(+ SELF 1)"]);
}

#[test]
fn conditionals_select_text() {
    let src = "#define LEVEL 2\n\
               #if LEVEL > 3\nA\n#elif defined(LEVEL) && LEVEL % 2 == 0\nfloat chosen;\n#else\nB\n#endif\n\
               #ifdef MISSING\nC\n#endif\n\
               #ifndef MISSING\nfloat also;\n#endif\n\
               #undef LEVEL\n#if LEVEL\nD\n#endif\n\
               #if 0\n#bogus directives are skipped\n#endif\n";
    let module = parse_ok(src);
    let names: Vec<String> = module
        .items
        .iter()
        .map(|i| match i {
            Item::Variable(v) => v.declarators[0].name.name.to_string(),
            _ => "other".into(),
        })
        .collect();
    assert_eq!(names, ["chosen", "also"]);
}

#[test]
fn includes_are_found_and_guarded() {
    let loader = MemoryLoader::default()
        .with_file(
            "lib/noise.sl",
            "#pragma once\n#include \"helpers.sl\"\nfloat n(float x) { return h(x); }\n",
        )
        .with_file(
            "lib/helpers.sl",
            "#ifndef HELPERS\n#define HELPERS\nfloat h(float x) { return x; }\n#endif\n",
        );
    let src = "#include \"lib/noise.sl\"\n#include \"lib/noise.sl\"\n#include \"lib/helpers.sl\"\n#include <pattern.sl>\n";
    let checked = check_source("main.sl", src, &loader);
    assert!(checked.diagnostics.is_empty(), "{:?}", checked.diagnostics);
    let names: Vec<String> = checked
        .module
        .items
        .iter()
        .map(|i| match i {
            Item::Function(f) => f.name.name.to_string(),
            _ => "other".into(),
        })
        .collect();
    // Each guarded file contributes its functions once: the two helpers, then the stdlib module.
    assert_eq!(names[..2], ["h", "n"]);
    assert!(names[2..].iter().all(|n| n != "h" && n != "n"), "{names:?}");
    assert!(names.contains(&"pulse".to_string()) && names.contains(&"filteredpulse".to_string()));
    let unique: std::collections::BTreeSet<_> = names.iter().collect();
    assert_eq!(unique.len(), names.len(), "a guarded file was included twice: {names:?}");
}

#[test]
fn spans_lead_back_through_includes_and_macros() {
    let loader = MemoryLoader::default().with_file("inc.sl", "float f() {\n  return 1 +;\n}\n");
    let checked = check_source("main.sl", "// main\n#include \"inc.sl\"\n", &loader);
    let d = checked.diagnostics.iter().next().expect("an error");
    let span = d.primary_span();
    let file = checked.sources.file(span.file);
    assert_eq!(file.name, "inc.sl");
    assert_eq!(file.line_column(span.start as usize), (2, 13));
    let site = file.included_from.expect("included from main.sl");
    assert_eq!(checked.sources.file(site.file).name, "main.sl");
    assert_eq!(checked.sources.text(site), "#include \"inc.sl\"");

    let checked =
        check_source("m.sl", "#define BAD (1 + )\nsurface s() {\n  x = BAD;\n}\n", &MemoryLoader::default());
    let d = checked.diagnostics.iter().next().expect("an error");
    let span = d.primary_span();
    assert_eq!(checked.sources.text(span), ")", "the error is at the `)` in the macro body");
    let expansion = checked.sources.expansion(span.expn).expect("from a macro");
    assert_eq!(expansion.name, "BAD");
    assert_eq!(checked.sources.text(expansion.call_site), "BAD");
    assert_eq!(
        checked.sources.file(expansion.call_site.file).line_column(expansion.call_site.start as usize),
        (3, 7)
    );
}

#[test]
fn node_spans_cover_their_text() {
    let (module, _, sources) = parse("surface s() { x = a + b * c; }");
    let Item::Shader(s) = &module.items[0] else { panic!() };
    assert_eq!(sources.text(s.body.stmts[0].span), "x = a + b * c;");
    let StmtKind::Expr(e) = &s.body.stmts[0].kind else { panic!() };
    let ExprKind::Assign { value, .. } = &e.kind else { panic!() };
    assert_eq!(sources.text(value.span), "a + b * c");
    assert_eq!(sources.text(s.span), "surface s() { x = a + b * c; }");
}

#[test]
fn every_example_shader_checks_cleanly() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders");
    let mut count = 0;
    for entry in std::fs::read_dir(dir).expect("examples/shaders exists") {
        let path = entry.expect("readable").path();
        if path.extension().is_none_or(|e| e != "sl") {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("UTF-8");
        let name = path.to_string_lossy().into_owned();
        let checked = check_source(&name, &text, &FsLoader::default());
        let list = checked.diagnostics.clone().into_vec();
        assert!(list.is_empty(), "{}", patina_compiler::diag::render_text(&checked.sources, &list));
        assert!(!checked.module.items.is_empty());
        count += 1;
    }
    assert!(count >= 7, "expected the example shaders, found {count}");
}
