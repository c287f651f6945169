use super::*;
use crate::ir::{ExprKind, Stmt};
use crate::syntax::preprocess::MemoryLoader;

fn shader(src: &str) -> Shader {
    let checked = crate::check_source("bind.sl", src, &MemoryLoader::default());
    let messages: Vec<String> =
        checked.diagnostics.iter().map(|d| format!("{}: {}", d.code, d.message)).collect();
    assert!(messages.is_empty(), "{messages:?}");
    checked.program.shaders.into_iter().next().unwrap()
}

/// Specializes for a caller that reads every output parameter.
fn specialize_all(shader: &Shader, fixed: &[Fixed]) -> Bound {
    specialize(shader, fixed, &[], Consumed::All)
}

fn fixed(pairs: &[(&str, &[f64])]) -> Vec<Fixed> {
    pairs.iter().map(|(n, v)| Fixed { name: n.to_string(), value: v.to_vec() }).collect()
}

/// The built-ins the body still calls (statements and every expression they reach).
fn calls(shader: &Shader) -> Vec<String> {
    fn walk(shader: &Shader, block: &[Stmt], out: &mut Vec<String>) {
        let mut roots = Vec::new();
        for s in block {
            match s {
                Stmt::Store { value, .. } => roots.push(*value),
                Stmt::Eval(e) => roots.push(*e),
                Stmt::If { cond, .. } => roots.push(*cond),
                _ => {}
            }
            s.for_each_block(|b| walk(shader, b, out));
        }
        while let Some(e) = roots.pop() {
            if let ExprKind::Builtin(b, _) = &shader.expr(e).kind {
                out.push(b.name().to_string());
            }
            shader.expr(e).kind.for_each_operand(|o| roots.push(o));
        }
    }
    let mut out = Vec::new();
    walk(shader, &shader.body, &mut out);
    out.sort();
    out.dedup();
    out
}

const FLAGS: &str =
    "surface flags(float use_tex = 0; string map = \"checker\"; float wobble = 0; float Kd = 0.8) {
    color c = Cs;
    if (use_tex > 0.5) { c *= color texture(map, s, t); }
    float w = wobble > 0.5 ? noise(P * 4) : 1;
    Ci = c * Kd * w;
}";

#[test]
fn a_fixed_flag_decides_its_branch_either_way() {
    let original = shader(FLAGS);
    assert!(calls(&original).contains(&"texture".to_string()));
    let off = specialize_all(&original, &fixed(&[("use_tex", &[0.0]), ("wobble", &[0.0])]));
    let left = calls(&off.shader);
    assert!(!left.contains(&"texture".to_string()) && !left.iter().any(|c| c.contains("noise")), "{left:?}");
    let branches: Vec<_> = off
        .decisions
        .iter()
        .filter_map(|d| {
            if let Decision::Branch { taken, because, .. } = d {
                Some((*taken, because.clone()))
            } else {
                None
            }
        })
        .collect();
    assert_eq!(branches, [(false, vec!["wobble".to_string()]), (false, vec!["use_tex".to_string()])]);
    let on = specialize_all(&original, &fixed(&[("use_tex", &[1.0])]));
    assert!(calls(&on.shader).contains(&"texture".to_string()));
    // The noise's `?:` is still dynamic: wobble was not fixed.
    assert!(
        calls(&on.shader).iter().any(|c| c.contains("noise"))
            || calls(&original).iter().all(|c| !c.contains("noise"))
    );
}

#[test]
fn values_are_substituted_not_computed() {
    // Kd becomes the literal; `c * Kd * w` is left for the backends to compute as before.
    let original = shader(FLAGS);
    let bound = specialize_all(&original, &fixed(&[("Kd", &[0.5])]));
    assert!(bound.decisions.contains(&Decision::Folded { name: "Kd".into(), value: vec![0.5] }));
    let kd = bound.shader.params.iter().copied().find(|p| bound.shader.local(*p).name == "Kd").unwrap();
    assert!(!bound.shader.exprs.iter().any(|e| matches!(e.kind, ExprKind::Local(l) if l == kd)));
    assert!(bound.shader.exprs.iter().any(|e| e.kind == ExprKind::Literal(crate::ir::Literal::Float(0.5))));
    // Nothing to decide: no branch reads Kd.
    assert!(!bound.decisions.iter().any(|d| matches!(d, Decision::Branch { .. })));
}

#[test]
fn names_it_cannot_fold_stay_dynamic() {
    let original = shader("surface w(float k = 1; output varying float o = 0) { o = k; Ci = k; }");
    let bound = specialize_all(&original, &fixed(&[("o", &[2.0]), ("nope", &[1.0]), ("k", &[1.0, 2.0])]));
    assert!(bound.decisions.is_empty(), "{:?}", bound.decisions);
}

#[test]
fn variables_only_a_removed_branch_read_lose_their_stores() {
    let original = shader(
        "surface d(float fancy = 0) {
            float expensive = noise(P * 8);
            float cheap = 0.5;
            Ci = fancy > 0 ? expensive : cheap;
        }",
    );
    let bound = specialize_all(&original, &fixed(&[("fancy", &[0.0])]));
    assert!(calls(&bound.shader).iter().all(|c| !c.contains("noise")), "{:?}", calls(&bound.shader));
    assert!(
        bound
            .decisions
            .iter()
            .any(|d| matches!(d, Decision::DeadVariable { name, .. } if name == "expensive")),
        "{:?}",
        bound.decisions
    );
    let kept = specialize_all(&original, &fixed(&[("fancy", &[1.0])]));
    assert!(
        calls(&kept.shader).iter().any(|c| c.contains("noise"))
            || calls(&original).iter().all(|c| !c.contains("noise"))
    );
}

#[test]
fn a_loop_whose_condition_is_false_is_gone() {
    let original = shader(
        "surface l(float extra = 0) {
            float sum = 0;
            float i;
            for (i = 0; i < extra; i += 1) { sum += noise(P * i); }
            Ci = sum;
        }",
    );
    let bound = specialize_all(&original, &fixed(&[("extra", &[0.0])]));
    assert!(
        bound
            .decisions
            .iter()
            .any(|d| matches!(d, Decision::Loop { because, .. } if because == &["extra".to_string()]))
    );
    assert!(calls(&bound.shader).iter().all(|c| !c.contains("noise")));
}

#[test]
fn outputs_nobody_consumes_take_their_code_with_them() {
    let original = shader(
        "surface aov(output varying float depth_cue = 0; output varying color albedo = 0) {
            float cue = noise(P * 3);
            depth_cue = cue;
            albedo = Cs;
            Ci = Cs;
        }",
    );
    let all = specialize(&original, &[], &[], Consumed::All);
    assert!(
        calls(&all.shader).iter().any(|c| c.contains("noise"))
            || calls(&original).iter().all(|c| !c.contains("noise"))
    );
    let renderer = specialize(&original, &[], &[], Consumed::Only(&["albedo"]));
    assert!(calls(&renderer.shader).iter().all(|c| !c.contains("noise")), "{:?}", calls(&renderer.shader));
    assert!(renderer.decisions.contains(&Decision::UnconsumedOutput { name: "depth_cue".into() }));
    assert!(
        renderer.decisions.iter().any(|d| matches!(d, Decision::DeadVariable { name, .. } if name == "cue"))
    );
    assert!(
        !renderer
            .decisions
            .iter()
            .any(|d| matches!(d, Decision::UnconsumedOutput { name } if name == "albedo"))
    );
}

const GUARDED: &str = "imager g(string texturename = \"\"; color background = 1) {
    if (texturename != \"\") { Ci += (1 - alpha) * color texture(texturename, s, t); }
    else { Ci += (1 - alpha) * background; }
}";

/// The branches binding decided, with the parameters that decided them.
fn branches(bound: &Bound) -> Vec<(bool, Vec<String>)> {
    let decided = bound.decisions.iter().filter_map(|d| match d {
        Decision::Branch { taken, because, .. } => Some((*taken, because.clone())),
        _ => None,
    });
    decided.collect()
}

#[test]
fn a_string_parameter_decides_its_comparison_from_the_scene_or_its_default() {
    let original = shader(GUARDED);
    assert!(calls(&original).contains(&"texture".to_string()));
    // Unset: the default "" is the value, and the lookup is dead.
    let unset = specialize(&original, &[], &[], Consumed::All);
    assert!(!calls(&unset.shader).contains(&"texture".to_string()), "{:?}", calls(&unset.shader));
    assert_eq!(branches(&unset), [(false, vec!["texturename".to_string()])]);
    // Set by the scene: the lookup is all that is left.
    let set = specialize(&original, &[], &[("texturename".into(), "sky.png".into())], Consumed::All);
    assert!(calls(&set.shader).contains(&"texture".to_string()));
    assert_eq!(branches(&set), [(true, vec!["texturename".to_string()])]);
}

#[test]
fn a_string_the_shader_writes_is_not_decided() {
    let original = shader(
        "surface w(string map = \"\"; float k = 0) {
            if (k > 0.5) { map = \"other.png\"; }
            if (map != \"\") { Ci = color texture(map, s, t); } else { Ci = Cs; }
        }",
    );
    let bound = specialize(&original, &[], &[], Consumed::All);
    assert!(calls(&bound.shader).contains(&"texture".to_string()));
    assert!(branches(&bound).is_empty(), "{:?}", bound.decisions);
}

/// A library-style function choosing its pattern by a parameter, called twice deep with a
/// shader parameter; its early returns leave the rest of its body behind them.
const VARIANTS: &str = "
float pick(point p; float variant)
{
    if (variant < 0.5)
        return sin(p[0]);
    if (variant < 1.5)
        return exp(p[1]);
    return 0.5;
}

float sample(point p; float variant, k)
{
    float d = pick(p, variant);
    return k * d;
}

surface v(float variant = 0; float k = 1) {
    Ci = sample(P, variant, k);
}";

#[test]
fn a_fixed_parameter_decides_branches_inside_the_functions_it_is_passed_to() {
    let original = shader(VARIANTS);
    let all = calls(&original);
    assert_eq!(all, ["exp", "sin"]);
    let first = specialize_all(&original, &fixed(&[("variant", &[0.0])]));
    // The first `if` is taken; its `return` leaves the rest of `pick` unreachable, so the second
    // test is never decided: it is gone with the code after the return.
    assert_eq!(branches(&first), [(true, vec!["variant".to_string()])]);
    assert_eq!(calls(&first.shader), ["sin"]);
    let second = specialize_all(&original, &fixed(&[("variant", &[1.0])]));
    assert_eq!(
        branches(&second),
        [(false, vec!["variant".to_string()]), (true, vec!["variant".to_string()])]
    );
    assert_eq!(calls(&second.shader), ["exp"]);
    let last = specialize_all(&original, &fixed(&[("variant", &[7.0])]));
    assert!(calls(&last.shader).is_empty(), "{:?}", calls(&last.shader));
    // `k` decides nothing: fixing it alone leaves every branch.
    let k = specialize_all(&original, &fixed(&[("k", &[2.0])]));
    assert!(branches(&k).is_empty(), "{:?}", k.decisions);
    assert_eq!(calls(&k.shader), all);
}

#[test]
fn a_variable_stored_in_one_branch_is_not_known_after_it() {
    // `m` is stored once, but only when `flag` holds: after the `if` its value is not known, so
    // the test of `m` stays.
    let original = shader(
        "surface b(float flag = 0; float variant = 0) {
            float m;
            if (flag > 0.5) { m = variant; }
            if (m < 1) { Ci = sin(s); } else { Ci = Cs; }
        }",
    );
    let bound = specialize_all(&original, &fixed(&[("variant", &[0.0])]));
    assert!(branches(&bound).is_empty(), "{:?}", bound.decisions);
    assert_eq!(calls(&bound.shader), ["sin"]);
}

#[test]
fn a_literal_argument_decides_the_branches_it_reaches_without_a_report() {
    // Nothing is fixed, yet `pick` is called with the literal 1: the test of its variant holds
    // for every binding, so the branch goes and no decision names a parameter.
    let src = VARIANTS.replace("Ci = sample(P, variant, k);", "Ci = sample(P, 1, k) + variant;");
    let original = shader(&src);
    assert_eq!(calls(&original), ["exp", "sin"]);
    let bound = specialize_all(&original, &[]);
    assert_eq!(calls(&bound.shader), ["exp"]);
    assert!(bound.decisions.iter().all(|d| !matches!(d, Decision::Branch { .. })), "{:?}", bound.decisions);
}

#[test]
fn a_fixed_matrix_becomes_a_matrix_of_float_literals() {
    // Sixteen floats, as the semantic stage builds `matrix (...)`: each part a `float` literal
    // (they were made of the row type, `float4` literals of one component each).
    let original = shader("surface m(matrix M = 1) {\n    Ci = color (comp(M, 0, 1));\n}\n");
    let values: Vec<f64> = (0..16).map(f64::from).collect();
    let bound = specialize_all(&original, &fixed(&[("M", &values)]));
    crate::verify::verify(&bound.shader, crate::verify::Pass::Bind("test")).expect("valid IR");
    let parts = bound
        .shader
        .exprs
        .iter()
        .find_map(|e| match &e.kind {
            ExprKind::Construct(parts)
                if e.ty == crate::ir::types::Type::of(crate::ir::types::Base::Matrix4) =>
            {
                Some(parts.clone())
            }
            _ => None,
        })
        .expect("the folded matrix");
    assert_eq!(parts.len(), 16);
    assert!(parts.iter().all(|p| bound.shader.expr(*p).ty == crate::ir::types::Type::FLOAT));
}
