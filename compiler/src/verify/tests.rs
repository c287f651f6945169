//! `verify` over every shader there is (the examples, the standard library, Aqsis's corpus) through
//! every pass, and against hand-broken IR that it must refuse.

use std::path::{Path, PathBuf};

use super::{Pass, verify, verify_stages};
use crate::bind::{self, Consumed, Fixed};
use crate::ir::types::{Base, Rate, Type};
use crate::ir::{BinaryOp, ExprId, ExprKind, LocalKind, Place, Shader, Stmt};
use crate::split;
use crate::syntax::ast::{Item, ShaderKind, TypeName};
use crate::syntax::preprocess::{FsLoader, MemoryLoader};

/// Asserts `verify` accepts `shader` after `pass`.
fn ok(shader: &Shader, pass: Pass, file: &str) {
    if let Err(e) = verify(shader, pass) {
        panic!("{file}: {e}");
    }
}

/// A value for each parameter a scene could fix (numbers of the parameter's width), so that
/// binding folds them and decides the branches they settle.
fn fixed_values(shader: &Shader) -> Vec<Fixed> {
    shader
        .params
        .iter()
        .map(|p| shader.local(*p))
        .filter(|l| l.ty.array.is_none() && l.ty.base.components() > 0)
        .map(|l| Fixed { name: l.name.to_string(), value: vec![0.25; l.ty.base.components() as usize] })
        .collect()
}

/// Every pass after the semantic stage, each result verified: binding (without and with fixed
/// values, reading back no outputs), the steps of `opt::Prepared::new`, and both splits.
fn through_every_pass(original: &Shader, file: &str) {
    ok(original, Pass::Rates, file);
    let mut bound = vec![bind::specialize(original, &[], &[], Consumed::All).shader];
    let fixed = fixed_values(original);
    // Without parameters the second binding would be the first again (the standard library's
    // wrappers, the slowest to run through every pass, have none).
    if !fixed.is_empty() {
        bound.push(bind::specialize(original, &fixed, &[], Consumed::Only(&[])).shader);
    }
    for shader in bound {
        ok(&shader, Pass::Bind("all"), file);
        let mut s = shader;
        crate::opt::textures::footprints(&mut s);
        ok(&s, Pass::Footprints, file);
        crate::opt::derivs::differentiate(&mut s);
        ok(&s, Pass::Derivatives, file);
        crate::opt::textures::expand(&mut s);
        ok(&s, Pass::Textures, file);
        crate::opt::shadow::expand(&mut s);
        ok(&s, Pass::Shadows, file);
        ok(&s, Pass::Prepare, file);
        let s = crate::opt::Prepared::assume_prepared(s);
        for stages in [split::split(&s), split::split_folding_host(&s)] {
            match stages {
                Ok(stages) => {
                    if let Err(e) = verify_stages(&stages) {
                        panic!("{file}: {e}");
                    }
                }
                Err(d) => panic!("{file}: shader `{}` does not split: {}", s.name, d.message),
            }
        }
    }
}

/// Checks `text` and runs each of its shaders through every pass; `Err` when it does not check
/// (the corpus has known gaps).
fn file(name: &str, text: &str) -> Result<usize, String> {
    let checked = crate::check_source(name, text, &FsLoader::default());
    if checked.has_errors() {
        let first = checked.diagnostics.iter().find(|d| d.is_error()).map(|d| d.message.clone());
        return Err(first.unwrap_or_default());
    }
    for shader in &checked.program.shaders {
        through_every_pass(shader, name);
    }
    Ok(checked.program.shaders.len())
}

/// The `.sl` files under `dir`, recursively, sorted.
fn sources(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else { return out };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            out.extend(sources(&path));
        } else if path.extension().is_some_and(|e| e == "sl") {
            out.push(path);
        }
    }
    out.sort();
    out
}

fn repository() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

#[test]
fn every_example_shader_verifies_after_every_pass() {
    let mut shaders = 0;
    for path in sources(&repository().join("examples/shaders")) {
        let text = std::fs::read_to_string(&path).expect("UTF-8");
        let name = path.to_string_lossy();
        shaders += file(&name, &text).unwrap_or_else(|e| panic!("{name} does not check: {e}"));
    }
    assert!(shaders >= 29, "expected the example shaders, found {shaders}");
}

#[test]
fn the_corpus_verifies_after_every_pass() {
    // Aqsis's shaders live beside the repository (ARCHITECTURE.md, `corpus.rs`); a checkout
    // without them has nothing to run here.
    let dir = repository().join("../shared/corpus");
    let files = sources(&dir);
    if files.is_empty() {
        eprintln!("no corpus at {}: skipped", dir.display());
        return;
    }
    let mut checked = 0;
    for path in &files {
        // Some are Latin-1; what matters here is their code, which is ASCII.
        let text = String::from_utf8_lossy(&std::fs::read(path).expect("readable")).into_owned();
        // A shader with a known gap does not check: there is no IR to verify.
        if file(&path.to_string_lossy(), &text).is_ok() {
            checked += 1;
        }
    }
    assert!(checked * 4 >= files.len() * 3, "only {checked} of {} corpus files check", files.len());
}

/// An expression of type `ty` built from the wrapper's inputs, for an argument.
fn argument(ty: TypeName) -> Option<&'static str> {
    Some(match ty {
        TypeName::Float => "(s + 0.25)",
        TypeName::Int => "int (s * 7)",
        TypeName::Uint => "uint (t * 5)",
        TypeName::Color => "color (s, t, 0.5)",
        TypeName::Point => "P",
        TypeName::Vector => "vector (I)",
        TypeName::Normal => "normalize (N)",
        TypeName::Matrix => "matrix \"shader\" 1",
        TypeName::String => "\"shader\"",
        _ => return None,
    })
}

/// A colour from a value of type `ty` (`None` for strings).
fn to_colour(ty: TypeName, value: &str) -> Option<String> {
    Some(match ty {
        TypeName::Float | TypeName::Int | TypeName::Uint => format!("color (float ({value}))"),
        TypeName::Color => value.to_string(),
        TypeName::Point | TypeName::Vector | TypeName::Normal => format!("color ({value})"),
        TypeName::Matrix => format!("color (comp ({value}, 0, 1))"),
        _ => return None,
    })
}

/// A surface shader calling every function `module` defines, each result (and each output
/// argument) added into `Ci` so that no pass drops the call.
fn wrapper(module: &str, text: &str) -> String {
    let checked = crate::check_source(module, text, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{module} checks on its own");
    let mut body = String::new();
    for item in &checked.module.items {
        let Item::Function(f) = item else { continue };
        let mine = f.span.file == checked.root
            || (f.span.expn.is_macro() && checked.sources.call_site(f.span).file == checked.root);
        if !mine {
            continue;
        }
        let mut block = String::new();
        let mut args = Vec::new();
        let mut outputs = Vec::new();
        let mut callable = true;
        for (k, p) in f.params.iter().enumerate() {
            let Some(value) = argument(p.ty.name) else {
                callable = false;
                break;
            };
            let ty = p.ty.name.keyword();
            match p.array {
                Some(size) => {
                    let n = size.len.unwrap_or(4);
                    let items = vec![value; n as usize].join(", ");
                    block.push_str(&format!("        {ty} a{k}[{n}] = {{ {items} }};\n"));
                }
                None => block.push_str(&format!("        {ty} a{k} = {value};\n")),
            }
            if p.qualifiers.output.is_some() && p.array.is_none() {
                outputs.extend(to_colour(p.ty.name, &format!("a{k}")));
            }
            args.push(format!("a{k}"));
        }
        if !callable {
            continue;
        }
        let call = format!("{}({})", f.name.name, args.join(", "));
        match to_colour(f.return_type.name, &call) {
            Some(c) => block.push_str(&format!("        Ci += {c};\n")),
            None => block.push_str(&format!("        {call};\n")),
        }
        for o in outputs {
            block.push_str(&format!("        Ci += {o};\n"));
        }
        body.push_str(&format!("    {{\n{block}    }}\n"));
    }
    format!("#include <{module}>\n\nsurface verify_wrapper()\n{{\n    Ci = 0;\n{body}}}\n")
}

#[test]
fn the_standard_library_verifies_after_every_pass() {
    for (module, text) in crate::stdlib::MODULES {
        let source = wrapper(module, text);
        let name = format!("wrapper of {module}");
        let shaders = file(&name, &source).unwrap_or_else(|e| panic!("{name} does not check: {e}\n{source}"));
        assert!(shaders >= 1, "{name}");
    }
    // The built-ins written in the language (`compiler/stdlib/builtins.sl`), inlined at their calls.
    let builtins = "surface library_builtins(float Ks = .5; float roughness = .1)\n{\n\
                    float f = noise(s) + noise(s, t) + noise(P) + noise(P, t)\n\
                    + snoise(s) + snoise(P) + pnoise(s, 4) + pnoise(P, point (4, 4, 4))\n\
                    + cellnoise(s) + cellnoise(s, t) + cellnoise(P) + cellnoise(P, t);\n\
                    color c = color noise(P) + color pnoise(P, point 4) + color cellnoise(P);\n\
                    vector v = vector noise(P) + vector snoise(P);\n\
                    normal Nf = faceforward(normalize(N), I);\n\
                    Ci = f * c + color (v) + diffuse(Nf) + Ks * specular(Nf, -normalize(I), roughness)\n\
                    + phong(Nf, -normalize(I), 20) + ambient();\n\
                    }\n";
    file("library_builtins.sl", builtins)
        .unwrap_or_else(|e| panic!("the library built-ins do not check: {e}"));
}

// --- broken IR -------------------------------------------------------------------------------

/// The checked shader of `src` (one shader, no diagnostics).
fn checked(src: &str) -> Shader {
    let checked = crate::check_source("broken.sl", src, &MemoryLoader::default());
    assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
    checked.program.shaders[0].clone()
}

const SIMPLE: &str = "surface simple(float Kd = 0.5) {\n    float x = Kd * s;\n    Ci = color (x);\n}\n";

/// The violations `verify` finds, joined (asserting it finds some).
fn refused(shader: &Shader, pass: Pass) -> String {
    match verify(shader, pass) {
        Ok(()) => panic!("verify accepted broken IR after {pass}"),
        Err(e) => e.to_string(),
    }
}

/// The first binary operation of `shader`.
fn first_binary(shader: &Shader) -> usize {
    shader.exprs.iter().position(|e| matches!(e.kind, ExprKind::Binary(..))).expect("a binary operation")
}

#[test]
fn the_simple_shader_is_valid() {
    let shader = checked(SIMPLE);
    ok(&shader, Pass::Rates, "simple");
}

#[test]
fn an_out_of_range_operand_is_refused() {
    let mut shader = checked(SIMPLE);
    let i = first_binary(&shader);
    if let ExprKind::Binary(_, a, _) = &mut shader.exprs[i].kind {
        *a = ExprId(9999);
    }
    let message = refused(&shader, Pass::Rates);
    assert!(message.contains("e9999, past the"), "{message}");
}

#[test]
fn an_out_of_range_local_is_refused() {
    let mut shader = checked(SIMPLE);
    shader.body.push(Stmt::Store {
        place: Place::Local(crate::ir::LocalId(77)),
        value: ExprId(0),
        span: shader.span,
    });
    let message = refused(&shader, Pass::Rates);
    assert!(message.contains("l77"), "{message}");
}

#[test]
fn an_operand_type_mismatch_is_refused() {
    let mut shader = checked(SIMPLE);
    // `Kd * s` with `s` replaced by a colour: the operands no longer agree.
    let colour = shader.exprs.iter().position(|e| e.ty == Type::of(Base::Color)).expect("a colour") as u32;
    let i = first_binary(&shader);
    let ExprKind::Binary(op, a, _) = shader.exprs[i].kind.clone() else { unreachable!() };
    shader.exprs[i].kind = ExprKind::Binary(op, a, ExprId(colour));
    // Keep the arena in operand order, so that only the types are wrong.
    if colour as usize > i {
        shader.exprs[i].kind = ExprKind::Binary(op, a, a);
        shader.exprs[i].ty = Type::of(Base::Color);
    }
    let message = refused(&shader, Pass::Rates);
    assert!(message.contains("gives `color`") || message.contains("differ"), "{message}");
}

#[test]
fn a_comparison_of_the_wrong_type_is_refused() {
    let mut shader = checked(SIMPLE);
    let i = first_binary(&shader);
    let ExprKind::Binary(_, a, b) = shader.exprs[i].kind.clone() else { unreachable!() };
    // `<` gives a bool, not a float.
    shader.exprs[i].kind = ExprKind::Binary(BinaryOp::Lt, a, b);
    let message = refused(&shader, Pass::Rates);
    assert!(message.contains("Lt"), "{message}");
}

#[test]
fn a_break_outside_a_loop_is_refused() {
    let mut shader = checked(SIMPLE);
    shader.body.push(Stmt::Break(1));
    let message = refused(&shader, Pass::Rates);
    assert!(message.contains("`break 1` inside 0 loops"), "{message}");
}

#[test]
fn a_break_out_of_an_inlined_call_is_refused() {
    // The loop is the caller's; the `break` inside the call cannot leave it.
    let mut shader = checked(
        "float f(float x) { return x * 2; }\n\
         surface s1() { float i; for (i = 0; i < 3; i += 1) { Ci += f(i); } }\n",
    );
    fn add_break(block: &mut [Stmt]) -> bool {
        block.iter_mut().any(|stmt| match stmt {
            Stmt::Inline { body, .. } => {
                body.insert(0, Stmt::Break(1));
                true
            }
            Stmt::Loop { body, .. } | Stmt::If { then: body, .. } => add_break(body),
            _ => false,
        })
    }
    assert!(add_break(&mut shader.body), "an inlined call in the loop");
    let message = refused(&shader, Pass::Rates);
    assert!(message.contains("`break 1` inside 0 loops"), "{message}");
}

#[test]
fn a_cycle_is_refused() {
    let mut shader = checked(SIMPLE);
    let i = first_binary(&shader);
    if let ExprKind::Binary(_, a, _) = &mut shader.exprs[i].kind {
        *a = ExprId(i as u32);
    }
    // Operand order is not required after binding, but acyclicity is.
    let message = refused(&shader, Pass::Bind("test"));
    assert!(message.contains("cycle"), "{message}");
    assert!(!message.contains("does not come before"), "{message}");
    let message = refused(&shader, Pass::Rates);
    assert!(message.contains("does not come before"), "{message}");
}

#[test]
fn a_rate_below_its_operands_is_refused() {
    let mut shader = checked(SIMPLE);
    let i = first_binary(&shader);
    assert!(shader.exprs[i].rate.frequency > Rate::UNIFORM.frequency, "`Kd * s` varies");
    shader.exprs[i].rate = Rate::UNIFORM;
    let message = refused(&shader, Pass::Bind("test"));
    assert!(message.contains("at least"), "{message}");
}

#[test]
fn a_varying_value_in_a_uniform_variable_is_refused() {
    let mut shader = checked(SIMPLE);
    let x = shader.locals.iter().position(|l| l.name == "x").expect("x");
    shader.locals[x].rate = Rate::UNIFORM;
    // The reads of `x` follow its rate; the store into it does not fit.
    for e in &mut shader.exprs {
        if matches!(e.kind, ExprKind::Local(l) if l.0 as usize == x) {
            e.rate = Rate::UNIFORM;
        }
    }
    let message = refused(&shader, Pass::Bind("test"));
    assert!(message.contains("stored into"), "{message}");
}

#[test]
fn a_derivative_left_after_prepare_is_refused() {
    let src = "surface d() {\n    float w = Du(s) + filterwidth(t);\n    Ci = color (w);\n}\n";
    let shader = checked(src);
    ok(&shader, Pass::Rates, "d");
    let message = refused(&shader, Pass::Prepare);
    assert!(message.contains("still calls") && message.contains("Du("), "{message}");
    assert!(message.contains("filterwidth"), "{message}");
    let prepared = crate::opt::Prepared::new(shader.clone());
    ok(&prepared, Pass::Prepare, "d");
}

#[test]
fn a_texture_lookup_left_after_prepare_is_refused() {
    let shader = checked("surface t1(string map = \"a.png\") {\n    Ci = color texture(map, s, t);\n}\n");
    let message = refused(&shader, Pass::Textures);
    assert!(message.contains("texture"), "{message}");
    let prepared = crate::opt::Prepared::new(shader.clone());
    ok(&prepared, Pass::Prepare, "t1");
}

#[test]
fn a_stage_reading_a_later_stage_is_refused() {
    let shader = crate::opt::Prepared::new(checked(SIMPLE));
    let mut stages = split::split(&shader).expect("splits");
    verify_stages(&stages).expect("the split is valid");
    // The host computes `Ci` now, which reads `s`, a per-vertex value.
    stages.host.body = stages.fragment.body.clone();
    let message = match verify_stages(&stages) {
        Ok(()) => panic!("a host stage reading `s` was accepted"),
        Err(e) => e.to_string(),
    };
    assert!(message.contains("the host stage reads"), "{message}");
}

#[test]
fn a_transfer_that_is_not_a_parameter_is_refused() {
    // `Kd * 2` is per draw and crosses from the host to the fragment stage.
    let shader = checked("surface tr(float Kd = 0.5) {\n    float k = Kd * 2;\n    Ci = color (k * s);\n}\n");
    let shader = crate::opt::Prepared::new(shader);
    let mut stages = split::split(&shader).expect("splits");
    verify_stages(&stages).expect("the split is valid");
    let t = stages.transfers.first().expect("a transfer").local;
    stages.fragment.locals[t.0 as usize].kind = LocalKind::Temp;
    stages.fragment.params.retain(|p| *p != t);
    let message = verify_stages(&stages).expect_err("refused").to_string();
    assert!(message.contains("should be an input parameter"), "{message}");
}

#[test]
fn illuminance_outside_a_surface_is_refused() {
    let mut shader = checked("light l1() {\n    Cl = 1;\n}\n");
    shader.body.push(Stmt::Illuminance { args: Vec::new(), body: Vec::new() });
    let message = refused(&shader, Pass::Rates);
    assert!(message.contains("`illuminance` outside a RenderMan-style surface"), "{message}");
}

#[test]
fn a_light_value_outside_illuminance_is_refused() {
    let mut shader =
        checked("surface lit() {\n    color c = 0;\n    illuminance (P) { c += Cl; }\n    Ci = c;\n}\n");
    // Hoist the light loop's body out of it.
    let inside = shader
        .body
        .iter()
        .find_map(|s| match s {
            Stmt::Illuminance { body, .. } => Some(body.clone()),
            _ => None,
        })
        .expect("illuminance");
    shader.body.extend(inside);
    let message = refused(&shader, Pass::Rates);
    assert!(message.contains("read outside `illuminance`"), "{message}");
}

#[test]
#[cfg(debug_assertions)]
#[should_panic(
    expected = "internal compiler error: the IR of shader `simple` is invalid after opt::textures::footprints"
)]
fn a_pass_that_breaks_the_ir_panics_in_debug_builds() {
    let mut shader = checked(SIMPLE);
    shader.body.push(Stmt::Break(1));
    crate::opt::Prepared::new(shader);
}

#[test]
fn a_light_shader_verifies() {
    let shader = checked(
        "light spot(float intensity = 1; point from = point \"shader\" (0, 0, 0)) {\n    \
         illuminate (from, vector (0, 0, 1), 0.5) { Cl = intensity / (L . L); }\n}\n",
    );
    assert_eq!(shader.kind, ShaderKind::Light);
    through_every_pass(&shader, "spot");
}
