//! Structural tests of the derivative pass: what is replaced, which variables get shadows and
//! seeds, where the derivative stores go, and that every expression built is well typed. (The
//! numeric checks, AD against finite differences, run on the interpreter.)

use super::analysis::dtype;
use super::differentiate;
use crate::ir::builtin::RateRule;
use crate::ir::types::{Base, Type};
use crate::ir::{Axis, BinaryOp, Block, ExprId, ExprKind, Input, Literal, Place, Shader, Stmt, UnaryOp};
use crate::sema::builtins;
use crate::syntax::preprocess::MemoryLoader;

/// The shaders of `src`, checked without errors.
fn check(src: &str) -> Vec<Shader> {
    let checked = crate::check_source("test.sl", src, &MemoryLoader::default());
    let errors: Vec<String> =
        checked.diagnostics.iter().filter(|d| d.is_error()).map(|d| d.message.clone()).collect();
    assert!(errors.is_empty(), "{errors:?} in\n{src}");
    checked.program.shaders
}

/// The first shader of `src`, differentiated and checked for well-formedness.
fn run(src: &str) -> Shader {
    let mut shader = check(src).remove(0);
    let before = shader.clone();
    differentiate(&mut shader);
    well_typed(&shader, &before);
    shader
}

/// The derivative consumers still in the shader, by name.
fn consumers(shader: &Shader) -> Vec<&'static str> {
    let mut used = std::collections::HashSet::new();
    reachable(shader, &shader.body, &mut used);
    let mut names: Vec<&'static str> = used
        .iter()
        .filter_map(|&e| match &shader.expr(e).kind {
            ExprKind::Builtin(b, _) if b.rate == RateRule::Derivative => Some(b.name()),
            _ => None,
        })
        .collect();
    names.sort_unstable();
    names
}

/// Every expression the statements of `block` use, transitively.
fn reachable(shader: &Shader, block: &Block, out: &mut std::collections::HashSet<ExprId>) {
    fn expr(shader: &Shader, e: ExprId, out: &mut std::collections::HashSet<ExprId>) {
        if !out.insert(e) {
            return;
        }
        for o in operands(&shader.expr(e).kind) {
            expr(shader, o, out);
        }
    }
    fn place(shader: &Shader, p: &Place, out: &mut std::collections::HashSet<ExprId>) {
        if let Place::Index(inner, i) = p {
            expr(shader, *i, out);
            place(shader, inner, out);
        }
    }
    for stmt in block {
        match stmt {
            Stmt::Eval(e) => expr(shader, *e, out),
            Stmt::Store { place: p, value, .. } => {
                expr(shader, *value, out);
                place(shader, p, out);
            }
            Stmt::If { cond, then, otherwise } => {
                expr(shader, *cond, out);
                reachable(shader, then, out);
                reachable(shader, otherwise, out);
            }
            Stmt::Loop { cond, body, step, .. } => {
                if let Some(c) = cond {
                    expr(shader, *c, out);
                }
                reachable(shader, body, out);
                reachable(shader, step, out);
            }
            Stmt::Inline { body, .. } | Stmt::Lights { body, .. } => reachable(shader, body, out),
            Stmt::Illuminance { args, body } | Stmt::Emit { args, body, .. } => {
                for a in args {
                    expr(shader, *a, out);
                }
                reachable(shader, body, out);
            }
            Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => {}
        }
    }
}

fn operands(kind: &ExprKind) -> Vec<ExprId> {
    match kind {
        ExprKind::Literal(_) | ExprKind::Local(_) | ExprKind::Global(_) | ExprKind::Seed(..) => vec![],
        ExprKind::Unary(_, a)
        | ExprKind::Convert(a)
        | ExprKind::FromSpace { value: a, .. }
        | ExprKind::LightSum { value: a, .. } => vec![*a],
        ExprKind::Binary(_, a, b) | ExprKind::Index(a, b) => vec![*a, *b],
        ExprKind::Select(c, a, b) => vec![*c, *a, *b],
        ExprKind::Construct(parts) | ExprKind::Builtin(_, parts) => parts.clone(),
    }
}

/// The inputs seeded, as `name/axis`, sorted.
fn seeds(shader: &Shader) -> Vec<String> {
    let mut out: Vec<String> = shader
        .exprs
        .iter()
        .filter_map(|e| match e.kind {
            ExprKind::Seed(input, axis) => {
                let name = match input {
                    Input::Global(g) => g.name.to_string(),
                    Input::Param(l) => shader.local(l).name.to_string(),
                };
                Some(format!("{name}/{}", if axis == Axis::X { "x" } else { "y" }))
            }
            _ => None,
        })
        .collect();
    out.sort();
    out
}

/// The names of the variables that got shadows, sorted.
fn shadowed(shader: &Shader) -> Vec<String> {
    let mut out: Vec<String> = shader
        .locals
        .iter()
        .filter_map(|l| l.name.strip_prefix("dx(").map(|n| n.trim_end_matches(')').to_string()))
        .collect();
    out.sort();
    out
}

/// Every statement, depth first, in order.
fn flatten(block: &Block) -> Vec<&Stmt> {
    let mut out = Vec::new();
    for s in block {
        out.push(s);
        match s {
            Stmt::If { then, otherwise, .. } => {
                out.extend(flatten(then));
                out.extend(flatten(otherwise));
            }
            Stmt::Loop { body, step, .. } => {
                out.extend(flatten(body));
                out.extend(flatten(step));
            }
            Stmt::Inline { body, .. } | Stmt::Illuminance { body, .. } | Stmt::Emit { body, .. } => {
                out.extend(flatten(body));
            }
            _ => {}
        }
    }
    out
}

/// The name of the local a place is rooted at.
fn root_name(shader: &Shader, place: &Place) -> String {
    match place {
        Place::Local(l) => shader.local(*l).name.to_string(),
        Place::Global(g) => g.name.to_string(),
        Place::Index(inner, _) => root_name(shader, inner),
    }
}

/// Asserts that the expressions the pass built or changed (`before` is the shader it was given)
/// are typed as the backends expect, that the expression graph has no cycle, and that the stores
/// into shadows store values of the shadow's type.
fn well_typed(shader: &Shader, before: &Shader) {
    let ty = |e: ExprId| shader.expr(e).ty;
    let scalar = |t: Type| t.array.is_none() && t.base.components() == 1;
    for (i, e) in shader.exprs.iter().enumerate() {
        if before.exprs.get(i).is_some_and(|old| old.kind == e.kind) {
            continue;
        }
        let ok = match &e.kind {
            ExprKind::Literal(Literal::Float(_)) => e.ty.base.is_float_scalar(),
            ExprKind::Literal(Literal::Int(_)) => e.ty == Type::INT,
            ExprKind::Literal(_) => true,
            ExprKind::Local(l) => e.ty == shader.local(*l).ty,
            ExprKind::Global(g) => e.ty == Type::of(g.ty),
            ExprKind::Seed(input, _) => {
                let input_ty = match input {
                    Input::Global(g) => Type::of(g.ty),
                    Input::Param(l) => shader.local(*l).ty,
                };
                Some(e.ty) == dtype(input_ty)
            }
            ExprKind::Unary(UnaryOp::Neg, a) => e.ty == ty(*a),
            ExprKind::Unary(..) => true,
            ExprKind::Binary(op, a, b) => {
                let (ta, tb) = (ty(*a), ty(*b));
                match op {
                    BinaryOp::Add | BinaryOp::Sub | BinaryOp::Div => {
                        ta == tb && (e.ty == ta || (ta.base == Base::Point && e.ty.base == Base::Vector))
                    }
                    BinaryOp::Mul => {
                        let product = matches!(
                            (ta.base, tb.base),
                            (Base::Matrix4, Base::Float4 | Base::Matrix4) | (Base::Matrix3, _)
                        );
                        (ta == tb && e.ty == ta) || (product && (e.ty == tb || e.ty == ta))
                    }
                    BinaryOp::Dot => ta == tb && e.ty == Type::FLOAT,
                    BinaryOp::Cross => ta == tb && e.ty == ta,
                    BinaryOp::Lt | BinaryOp::Le | BinaryOp::Gt | BinaryOp::Ge => {
                        ta == tb && scalar(ta) && e.ty == Type::BOOL
                    }
                    BinaryOp::And | BinaryOp::Or => ta == Type::BOOL && tb == Type::BOOL,
                    _ => ta == tb && e.ty == Type::BOOL,
                }
            }
            ExprKind::Convert(a) => crate::sema::convert::explicit_ok(ty(*a), e.ty),
            ExprKind::Construct(parts) => match e.ty.array {
                Some(n) => parts.len() == n as usize && parts.iter().all(|&p| ty(p) == Type::of(e.ty.base)),
                None => {
                    let n: u32 = parts.iter().map(|&p| ty(p).base.components()).sum();
                    n == e.ty.base.components()
                }
            },
            ExprKind::FromSpace { value, .. } | ExprKind::LightSum { value, .. } => e.ty == ty(*value),
            ExprKind::Index(base, index) => e.ty == ty(*base).element() && ty(*index).base.is_integer(),
            ExprKind::Select(c, a, b) => ty(*c) == Type::BOOL && ty(*a) == e.ty && ty(*b) == e.ty,
            ExprKind::Builtin(b, args) => {
                let types: Vec<Type> = args.iter().map(|&a| ty(a)).collect();
                builtins::find(b.id, &types).is_some_and(|found| std::ptr::eq(found, *b)) && e.ty == b.ret
            }
        };
        assert!(ok, "expression {i} is ill-typed: {:?} of type {}", e.kind, e.ty);
    }
    // No expression reaches itself.
    let mut state = vec![0u8; shader.exprs.len()];
    fn visit(shader: &Shader, e: usize, state: &mut [u8]) {
        match state[e] {
            1 => panic!("expression {e} depends on itself"),
            2 => return,
            _ => {}
        }
        state[e] = 1;
        for o in operands(&shader.exprs[e].kind) {
            visit(shader, o.0 as usize, state);
        }
        state[e] = 2;
    }
    for e in 0..shader.exprs.len() {
        visit(shader, e, &mut state);
    }
    for stmt in flatten(&shader.body) {
        if let Stmt::Store { place, value, .. } = stmt
            && root_name(shader, place).starts_with('d')
            && root_name(shader, place).contains('(')
        {
            assert_eq!(shader.place_type(place), ty(*value), "store into {}", root_name(shader, place));
        }
    }
}

/// A RenderMan surface shader with `body`.
fn surface(body: &str) -> String {
    format!("surface test(uniform float k = 2; varying float vp = 0) {{\n{body}\n}}\n")
}

#[test]
fn du_of_an_input_is_replaced_and_seeded() {
    let shader = run(&surface("Ci = Du(s) + Dv(t) + filterwidth(s);"));
    assert!(consumers(&shader).is_empty(), "{:?}", consumers(&shader));
    assert_eq!(seeds(&shader), ["s/x", "s/y", "t/x", "t/y", "u/x", "u/y", "v/x", "v/y"]);
    assert_eq!(shadowed(&shader), ["s", "t", "u", "v"]);
    // The seeds come first.
    for stmt in &shader.body[..8] {
        let Stmt::Store { value, .. } = stmt else { panic!("a seed store first") };
        assert!(matches!(shader.expr(*value).kind, ExprKind::Seed(..)));
    }
}

#[test]
fn only_the_values_feeding_consumers_get_shadows() {
    let shader = run(&surface(
        "float a = s * 3;
         float b = t * 2;
         float c = s + t;
         if (a > 0.5) Ci = c;
         Oi = Du(b);",
    ));
    assert_eq!(shadowed(&shader), ["b", "t", "u", "v"]);
    assert_eq!(seeds(&shader), ["t/x", "t/y", "u/x", "u/y", "v/x", "v/y"]);
}

#[test]
fn uniform_arguments_give_exact_zeros() {
    let mut shader =
        check(&surface("Ci = color (Du(k), filterwidth(k * 3), area(E)); Oi = filterstep(k, 1);")).remove(0);
    let calls: Vec<ExprId> = (0..shader.exprs.len() as u32)
        .map(ExprId)
        .filter(
            |&e| matches!(&shader.expr(e).kind, ExprKind::Builtin(b, _) if b.rate == RateRule::Derivative),
        )
        .collect();
    assert_eq!(calls.len(), 4);
    differentiate(&mut shader);
    for e in calls {
        match &shader.expr(e).kind {
            ExprKind::Literal(Literal::Float(x)) => assert_eq!(*x, 0.0),
            ExprKind::Builtin(b, _) => assert_eq!(b.name(), "step"),
            other => panic!("not a zero: {other:?}"),
        }
    }
    assert!(seeds(&shader).is_empty() && shadowed(&shader).is_empty());
}

#[test]
fn derivative_stores_precede_the_primal_store() {
    let shader = run(&surface("float x = s; x = x * x; Ci = Du(x);"));
    let stmts = flatten(&shader.body);
    let names: Vec<String> = stmts
        .iter()
        .filter_map(|s| match s {
            Stmt::Store { place, .. } => Some(root_name(&shader, place)),
            _ => None,
        })
        .filter(|n| !n.contains("(s)") && !n.contains("(u)") && !n.contains("(v)"))
        .collect();
    assert_eq!(names, ["dx(x)", "dy(x)", "x", "dx(x)", "dy(x)", "x", "Ci"]);
    // d(x*x) reads the old derivative: dx(x) * x + x * dx(x).
    let Some(Stmt::Store { value, .. }) = stmts.iter().copied().find(|s| {
        matches!(s, Stmt::Store { place, value, .. }
            if root_name(&shader, place) == "dx(x)" && matches!(shader.expr(*value).kind, ExprKind::Binary(..)))
    }) else {
        panic!("no derivative store of x * x")
    };
    let ExprKind::Binary(BinaryOp::Add, l, r) = shader.expr(*value).kind else { panic!("a sum") };
    for side in [l, r] {
        let ExprKind::Binary(BinaryOp::Mul, a, b) = shader.expr(side).kind else { panic!("a product") };
        let reads: Vec<String> = [a, b]
            .iter()
            .map(|&e| match shader.expr(e).kind {
                ExprKind::Local(l) => shader.local(l).name.to_string(),
                ref other => format!("{other:?}"),
            })
            .collect();
        assert!(reads.contains(&"dx(x)".to_string()) && reads.contains(&"x".to_string()), "{reads:?}");
    }
}

#[test]
fn zero_derivatives_are_stored_explicitly() {
    // The second store's value is uniform: the shadow must be reset, not left with d(s).
    let shader = run(&surface("float x = s; if (s > 0.5) x = k; Ci = filterwidth(x);"));
    let resets = flatten(&shader.body)
        .into_iter()
        .filter(|s| {
            matches!(s, Stmt::Store { place, value, .. }
                if root_name(&shader, place).starts_with("d") && root_name(&shader, place).ends_with("(x)")
                    && matches!(shader.expr(*value).kind, ExprKind::Literal(Literal::Float(z)) if z == 0.0))
        })
        .count();
    assert_eq!(resets, 2);
}

#[test]
fn stores_in_nested_statements_and_loops_are_followed() {
    let shader = run(&surface(
        "float acc = 0;
         for (float i = 0; i < 3; i += 1) {
             if (i > 1) acc += sin(s * i); else acc += t;
         }
         Ci = Du(acc);",
    ));
    assert_eq!(shadowed(&shader), ["acc", "s", "t", "u", "v"]);
    // `i` is uniform: no shadow, and its loop condition gets nothing.
    let loops = flatten(&shader.body).into_iter().filter(|s| matches!(s, Stmt::Loop { .. })).count();
    assert_eq!(loops, 1);
}

#[test]
fn writes_to_globals_update_their_shadows() {
    let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders/ripples.sl"))
        .expect("the example");
    let shader = run(&src);
    assert!(consumers(&shader).is_empty());
    assert_eq!(seeds(&shader), ["N/x", "N/y", "P/x", "P/y", "s/x", "s/y", "u/x", "u/y", "v/x", "v/y"]);
    let stores: Vec<String> = flatten(&shader.body)
        .into_iter()
        .filter_map(|s| match s {
            Stmt::Store { place, .. } => Some(root_name(&shader, place)),
            _ => None,
        })
        .collect();
    let p = stores.iter().position(|n| n == "P").expect("P is written");
    assert_eq!(&stores[p - 2..p], ["dx(P)", "dy(P)"]);
    // N is read before calculatenormal writes it; the result of a consumer has derivative 0.
    let n = stores.iter().position(|n| n == "N").expect("N is written");
    assert_eq!(&stores[n - 2..n], ["dx(N)", "dy(N)"]);
}

#[test]
fn the_three_argument_filterstep_stays() {
    let shader = run(&surface("Ci = filterstep(0.5, s) + filterstep(0.5, s, t);"));
    assert_eq!(consumers(&shader), ["filterstep"]);
    assert_eq!(seeds(&shader), ["s/x", "s/y"]);
}

#[test]
fn per_light_values_and_surface_derivatives_have_none() {
    let shader = run(&surface(
        "color c = 0;
         illuminance (P) { c += Cl * max(0, normalize(L) . N); }
         Ci = filterwidth(comp(c, 0)) + filterwidth(du + random());",
    ));
    assert_eq!(seeds(&shader), ["N/x", "N/y"]);
}

#[test]
fn varying_parameters_are_seeded() {
    let shader = run(&surface("Ci = Deriv(vp * s, t) + calculatenormal(P) . I;"));
    assert_eq!(
        seeds(&shader),
        ["P/x", "P/y", "s/x", "s/y", "t/x", "t/y", "u/x", "u/y", "v/x", "v/y", "vp/x", "vp/y"]
    );
}

#[test]
fn stanford_shaders_have_no_surface_parameters() {
    let shader = run("surface shader float4 st(float4 base) {
             float4 p = P * 2;
             return {filterwidth(p[0]), xcomp(calculatenormal(point (rgb(P)))), 0, 1};
         }");
    assert!(consumers(&shader).is_empty());
    assert_eq!(seeds(&shader), ["P/x", "P/y"]);
}

#[test]
fn component_setters_are_differentiated_on_the_shadows() {
    let shader = run(&surface(
        "point p = P; setxcomp(p, s); float kr = s, kt = 0;
         illuminance (P) { lightsource(\"intensity\", kr); lightsource(\"intensity\", kt); }
         Ci = color (Du(p)) + filterwidth(kr) + kt;",
    ));
    let evals: Vec<String> = flatten(&shader.body)
        .into_iter()
        .filter_map(|s| match s {
            Stmt::Eval(e) => match &shader.expr(*e).kind {
                ExprKind::Builtin(b, args) => Some(format!(
                    "{}({})",
                    b.id,
                    match shader.expr(args[0]).kind {
                        ExprKind::Local(l) => shader.local(l).name.to_string(),
                        ExprKind::Global(g) => g.name.to_string(),
                        _ => "?".into(),
                    }
                )),
                _ => None,
            },
            _ => None,
        })
        .collect();
    assert_eq!(
        evals,
        ["setxcomp(dx(p))", "setxcomp(dy(p))", "setxcomp(p)", "lightsource(?)", "lightsource(?)"]
    );
    // Another shader's values have derivative 0: kr's shadows are reset just before the call.
    let stmts = flatten(&shader.body);
    let call = stmts
        .iter()
        .position(|s| {
            matches!(s, Stmt::Eval(e) if matches!(&shader.expr(*e).kind,
        ExprKind::Builtin(b, _) if b.name() == "lightsource"))
        })
        .expect("the call");
    let resets: Vec<String> = stmts[call - 2..call]
        .iter()
        .map(|s| match s {
            Stmt::Store { place, value, .. } => {
                assert!(matches!(shader.expr(*value).kind, ExprKind::Literal(Literal::Float(z)) if z == 0.0));
                root_name(&shader, place)
            }
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(resets, ["dx(kr)", "dy(kr)"]);
    // kt is written only by a constant and lightsource: it never has a derivative, and gets no
    // shadows.
    assert!(!shadowed(&shader).contains(&"kt".to_string()));
}

#[test]
fn xyz_screen_has_exact_derivatives() {
    let shader = run("surface shader float4 st() { return {filterwidth(xyz_screen()[0] * 2), 0, 0, 1}; }");
    assert!(seeds(&shader).is_empty());
    let unit = shader.exprs.iter().any(|e| {
        matches!(&e.kind, ExprKind::Construct(parts) if parts.len() == 4
            && matches!(shader.expr(parts[0]).kind, ExprKind::Literal(Literal::Float(x)) if x == 1.0))
    });
    assert!(unit);
}

#[test]
fn shaders_without_consumers_are_untouched() {
    let before = check(&surface("Ci = sin(s) * Cs;")).remove(0);
    let mut after = before.clone();
    differentiate(&mut after);
    assert_eq!(before, after);
}

/// An argument of type `ty` that varies per fragment, in RenderMan style.
fn argument(name: &str, ty: Type) -> Option<String> {
    let base = match ty.base {
        Base::Float | Base::Clampf => "(s * 0.5 + 0.25)",
        Base::Point => "P",
        Base::Vector => "I",
        Base::Normal => "N",
        Base::Color => "Cs",
        Base::Float3 => "v3",
        Base::Float4 => "v4",
        Base::Matrix4 => "m4",
        Base::Matrix3 => "m3",
        Base::Bool => "(s > 0.5)",
        Base::Int => "int (s * 8)",
        Base::Uint => "uint (s * 8)",
        Base::String if name == "ctransform" => "\"hsv\"",
        Base::String if name == "spline" => "\"catmull-rom\"",
        Base::String => "\"shader\"",
        Base::Void | Base::Texref => return None,
    };
    Some(match ty.array {
        None => base.to_string(),
        Some(_) => format!("array_{}", ty.base.name()),
    })
}

/// A float that depends on every component of a value of type `ty` named `r`.
fn extract(ty: Type) -> &'static str {
    match ty.base {
        Base::Float | Base::Clampf => "r",
        Base::Float4 => "r[0] + r[3]",
        Base::Matrix4 | Base::Matrix3 => "r[0][0] + r[1][2]",
        _ => "r[0] + r[1] + r[2]",
    }
}

#[test]
fn every_differentiable_built_in_gives_well_typed_derivatives() {
    let table = builtins::builtins();
    let mut names: Vec<&str> = table.names().collect();
    names.sort_unstable();
    let mut count = 0;
    for name in names {
        if matches!(name, "texture" | "texture3d" | "environment" | "shadow") {
            continue;
        }
        for b in table.overloads(name) {
            if dtype(b.ret).is_none() || b.params.iter().any(|p| p.output) {
                continue;
            }
            let mut params: Vec<Type> = b.params.iter().map(|p| p.ty).collect();
            params.extend(b.rest);
            let Some(args) = params.iter().map(|&t| argument(name, t)).collect::<Option<Vec<String>>>()
            else {
                continue;
            };
            let src = format!(
                "surface sweep() {{
                    varying float3 v3 = float3 (s, t, s * t);
                    varying float4 v4 = {{s, t, s * t, 1}};
                    varying matrix m4 = matrix (s, 1, 0, 0, 0, t, 0, 0, 0, 0, 1, 0, s, 0, 0, 1);
                    varying matrix3 m3 = affine(m4);
                    varying float array_float[5] = {{s, t, s, t, 1}};
                    varying color array_color[5] = {{Cs, Cs * s, Cs, Cs * t, Cs}};
                    varying point array_point[5] = {{P, P * s, P, P * t, P}};
                    varying vector array_vector[5] = {{I, I * s, I, I * t, I}};
                    {ret} r = {name}({args});
                    float x = {extract};
                    Ci = color (Du(x), Dv(x), filterwidth(x)) + Deriv(Cs * x, s);
                }}",
                ret = b.ret,
                args = args.join(", "),
                extract = extract(b.ret),
            );
            let shader = run(&src);
            assert!(consumers(&shader).iter().all(|&n| n == "filterstep"), "{}", b.signature);
            count += 1;
        }
    }
    println!("{count} overloads differentiated");
    assert!(count > 250, "{count} overloads differentiated");
}

#[test]
fn per_light_variables_get_per_light_shadows() {
    let shader = run("surface shader float4 st(vertex float4 uv) {
             perlight float lit = uv[0] * max(dot(N, L), 0);
             float w = integrate(filterwidth(lit)) + filterwidth(integrate(lit * uv[1]));
             return {w, 0, 0, 1};
         }");
    assert!(consumers(&shader).is_empty());
    assert_eq!(seeds(&shader), ["N/x", "N/y", "uv/x", "uv/y"]);
    let shadow = shader.locals.iter().find(|l| l.name == "dx(lit)").expect("lit has shadows");
    assert!(shadow.rate.perlight && shadow.rate.frequency == crate::ir::types::Frequency::Fragment);
}

/// `stdlib::LIBRARY_BUILTINS` (what the semantic stage inlines from `builtins.sl`) is not an
/// exhaustive match; the derivative rules are: the two must name the same built-ins.
#[test]
fn the_library_rule_names_exactly_the_library_builtins() {
    use super::calls::{Rule, rule};
    use crate::ir::builtin::BuiltinId;
    let table = builtins::builtins();
    for id in BuiltinId::ALL {
        let overload = &table.overloads(id.name())[0];
        let library = crate::stdlib::LIBRARY_BUILTINS.contains(id);
        assert_eq!(rule(overload) == Rule::Library, library, "{id}");
    }
}
