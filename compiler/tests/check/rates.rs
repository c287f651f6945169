//! Rates, conversions and overload resolution, asserted on the typed IR.
//!
//! The first part is in the style of OSL's `*-reg` suites: for each built-in under test it builds a
//! Stanford-style shader for every combination of argument rates (constant, primitive group, vertex,
//! fragment), stores the call's result in a variable without a rate, and checks the rate inferred
//! for that variable against the rule the built-in follows. The rest checks promotion, control
//! dependence, RenderMan placement, implicit conversions and overload choice on the IR itself.
//!
//! Tests marked `#[ignore = "bug: ..."]` assert the behaviour the compiler should have and does not
//! have yet; run them with `cargo test -p patina-compiler --test rates -- --ignored`.

use patina_compiler::check_source;
use patina_compiler::diag::Code;
use patina_compiler::ir::types::{Base, Frequency, Rate, Type};
use patina_compiler::ir::{Expr, ExprKind, Literal, Local, LocalKind, Place, Shader, Stmt};
use patina_compiler::syntax::preprocess::MemoryLoader;

// ---------------------------------------------------------------------------------------------
// Helpers

/// Checks `src`, which must have no diagnostic at all, and returns its only shader.
fn shader(src: &str) -> Shader {
    let checked = check_source("rates.sl", src, &MemoryLoader::default());
    let messages: Vec<String> =
        checked.diagnostics.iter().map(|d| format!("{}: {}", d.code, d.message)).collect();
    assert!(messages.is_empty(), "unexpected diagnostics {messages:?} in\n{src}");
    assert_eq!(checked.program.shaders.len(), 1, "expected one shader in\n{src}");
    checked.program.shaders.into_iter().next().expect("one shader")
}

/// The codes `src` produces, and how many shaders came through.
fn codes(src: &str) -> (Vec<Code>, usize) {
    let checked = check_source("rates.sl", src, &MemoryLoader::default());
    (checked.diagnostics.iter().map(|d| d.code).collect(), checked.program.shaders.len())
}

/// The variable or parameter `name` of `shader` (the first one, if an inlined function declares it
/// again).
fn local<'s>(shader: &'s Shader, name: &str) -> &'s Local {
    shader
        .locals
        .iter()
        .find(|l| l.name == name && l.kind != LocalKind::Temp)
        .unwrap_or_else(|| panic!("no local `{name}` in {:?}", names(shader)))
}

fn names(shader: &Shader) -> Vec<&str> {
    shader.locals.iter().map(|l| l.name.as_str()).collect()
}

/// Whether `shader` has a local named `name`.
fn has_local(shader: &Shader, name: &str) -> bool {
    shader.locals.iter().any(|l| l.name == name)
}

/// The rate of the variable `name`.
fn rate_of(shader: &Shader, name: &str) -> Rate {
    local(shader, name).rate
}

/// Every value stored into the local `name`, in program order (inlined bodies and branches
/// included).
fn stores_into<'s>(shader: &'s Shader, name: &str) -> Vec<&'s Expr> {
    fn walk<'s>(shader: &'s Shader, block: &'s [Stmt], name: &str, out: &mut Vec<&'s Expr>) {
        for stmt in block {
            match stmt {
                Stmt::Store { place: Place::Local(l), value, .. } if shader.local(*l).name == name => {
                    out.push(shader.expr(*value));
                }
                Stmt::If { then, otherwise, .. } => {
                    walk(shader, then, name, out);
                    walk(shader, otherwise, name, out);
                }
                Stmt::Loop { body, step, .. } => {
                    walk(shader, body, name, out);
                    walk(shader, step, name, out);
                }
                Stmt::Inline { body, .. } | Stmt::Illuminance { body, .. } | Stmt::Emit { body, .. } => {
                    walk(shader, body, name, out)
                }
                _ => {}
            }
        }
    }
    let mut out = Vec::new();
    walk(shader, &shader.body, name, &mut out);
    out
}

/// The one value stored into `name`.
fn stored_into<'s>(shader: &'s Shader, name: &str) -> &'s Expr {
    let stores = stores_into(shader, name);
    assert_eq!(stores.len(), 1, "expected one store into `{name}`");
    stores[0]
}

/// Every call of a built-in in `shader`: its signature and its arguments.
fn builtin_calls(shader: &Shader) -> Vec<(&str, &[patina_compiler::ir::ExprId], &Expr)> {
    shader
        .exprs
        .iter()
        .filter_map(|e| match &e.kind {
            ExprKind::Builtin(b, args) => Some((b.signature.as_str(), args.as_slice(), e)),
            _ => None,
        })
        .collect()
}

/// The one call of the built-in `name` in `shader`.
fn the_call<'s>(shader: &'s Shader, name: &str) -> (&'s str, &'s [patina_compiler::ir::ExprId], &'s Expr) {
    let calls: Vec<_> = builtin_calls(shader)
        .into_iter()
        .filter(|(sig, ..)| sig.split_whitespace().nth(1).is_some_and(|s| s.starts_with(&format!("{name}("))))
        .collect();
    assert_eq!(
        calls.len(),
        1,
        "expected one call of `{name}`, found {:?}",
        calls.iter().map(|c| c.0).collect::<Vec<_>>()
    );
    calls[0]
}

/// The result of the one inlined call of the library built-in `name` (written in the language,
/// `compiler/stdlib/builtins.sl`): the temporary `__NAME_TYPE result` its implementation returns into.
fn the_library_call<'s>(shader: &'s Shader, name: &str) -> &'s Local {
    let prefix = format!("__{name}_");
    let results: Vec<&Local> =
        shader.locals.iter().filter(|l| l.name.starts_with(&prefix) && l.name.ends_with(" result")).collect();
    assert_eq!(results.len(), 1, "expected one call of `{name}`, found {:?}", results);
    assert!(builtin_calls(shader).iter().all(|c| !c.0.contains(&format!(" {name}("))));
    results[0]
}

/// A source file made of `lines`.
fn lines(lines: &[&str]) -> String {
    let mut text = lines.join("\n");
    text.push('\n');
    text
}

const fn at(frequency: Frequency) -> Rate {
    Rate::at(frequency)
}

// ---------------------------------------------------------------------------------------------
// Built-in result rates for every combination of argument rates

/// The four rates an argument is given in.
const FREQUENCIES: [Frequency; 4] =
    [Frequency::Constant, Frequency::PrimitiveGroup, Frequency::Vertex, Frequency::Fragment];

/// How a built-in's result rate follows from its arguments' (what the test expects).
#[derive(Copy, Clone, Debug)]
enum Rule {
    /// The highest argument rate.
    Max,
    /// A derivative: fragment when an argument varies per vertex or fragment, else the highest
    /// argument rate (the derivative is exactly 0).
    Derivative,
    /// `integrate`: the argument's frequency, no longer per light.
    Integrate,
}

impl Rule {
    fn expected(self, args: &[Frequency]) -> Rate {
        let max = args.iter().copied().max().unwrap_or(Frequency::Constant);
        match self {
            Rule::Max | Rule::Integrate => at(max),
            Rule::Derivative if max >= Frequency::Vertex => Rate::FRAGMENT,
            Rule::Derivative => at(max),
        }
    }
}

/// The argument kinds a built-in takes, each given by a variable of the probe shader.
#[derive(Copy, Clone, Debug)]
enum Arg {
    Float,
    Float3,
    Bool,
    /// A `perlight float` (for `integrate`).
    PerlightFloat,
    /// The texture: only a primitive-group parameter can hold one.
    Texref,
}

impl Arg {
    /// The rates this kind of argument is tried at.
    fn frequencies(self) -> &'static [Frequency] {
        match self {
            Arg::Texref => &[Frequency::PrimitiveGroup],
            _ => &FREQUENCIES,
        }
    }

    /// The name of the probe shader's variable of this kind at `frequency`.
    fn operand(self, frequency: Frequency) -> String {
        let prefix = match frequency {
            Frequency::Constant => "c",
            Frequency::PrimitiveGroup => "g",
            Frequency::Vertex => "v",
            Frequency::Fragment => "f",
        };
        let ty = match self {
            Arg::Float => "float",
            Arg::Float3 => "float3",
            Arg::Bool => "bool",
            Arg::PerlightFloat => "lit",
            Arg::Texref => "texref",
        };
        format!("{prefix}_{ty}")
    }
}

/// A Stanford shader with a variable of every kind at every rate, storing `call` in `r`, a variable
/// of type `result` without a rate.
fn probe(result: &str, call: &str) -> String {
    let returned = match result {
        "float" => "{r, r, r, 1}",
        "float3" => "{r, 1}",
        "float4" => "r",
        other => panic!("no return for `{other}`"),
    };
    lines(&[
        "surface shader float4 probe(primitive group float g_float, vertex float v_float,",
        "                            primitive group float3 g_float3, vertex float3 v_float3,",
        "                            primitive group bool g_bool, vertex bool v_bool,",
        "                            primitive group texref g_texref)",
        "{",
        "    constant float c_float = 0.25;",
        "    constant float3 c_float3 = {0.25, 0.5, 0.75};",
        "    constant bool c_bool = true;",
        "    fragment float f_float = v_float;",
        "    fragment float3 f_float3 = v_float3;",
        "    fragment bool f_bool = v_bool;",
        "    perlight float c_lit = c_float;",
        "    perlight float g_lit = g_float;",
        "    perlight float v_lit = v_float;",
        "    perlight float f_lit = f_float;",
        &format!("    {result} r = {call};"),
        &format!("    return {returned};"),
        "}",
    ])
}

/// Every combination of rates for `args`.
fn combinations(args: &[Arg]) -> Vec<Vec<Frequency>> {
    let mut all = vec![Vec::new()];
    for arg in args {
        all = all
            .into_iter()
            .flat_map(|prefix| {
                arg.frequencies().iter().map(move |f| {
                    let mut next = prefix.clone();
                    next.push(*f);
                    next
                })
            })
            .collect();
    }
    all
}

/// Calls `name` with `args` at every combination of rates, storing into a `result` variable, and
/// checks the inferred rate against `rule`. Returns how many combinations were checked.
fn sweep(name: &str, args: &[Arg], result: &str, rule: Rule) -> usize {
    let mut failures = Vec::new();
    let combos = combinations(args);
    for rates in &combos {
        let operands: Vec<String> = args.iter().zip(rates).map(|(a, f)| a.operand(*f)).collect();
        let call = format!("{name}({})", operands.join(", "));
        let src = probe(result, &call);
        let shader = shader(&src);
        let r = local(&shader, "r");
        assert!(!r.declared, "`r` has no rate qualifier");
        let expected = rule.expected(rates);
        if r.rate != expected {
            failures.push(format!("{call}: expected {expected}, inferred {}", r.rate));
        }
        // The call itself carries the rate too (for a built-in written in the language, the
        // result of its inlined implementation).
        let call_rate = if patina_compiler::stdlib::is_library_builtin(name) {
            the_library_call(&shader, name).rate
        } else {
            the_call(&shader, name).2.rate
        };
        if call_rate != expected {
            failures.push(format!("{call}: the call expression is {call_rate}, expected {expected}"));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} combinations wrong:\n{}",
        failures.len(),
        combos.len(),
        failures.join("\n")
    );
    combos.len()
}

#[test]
fn sin_takes_its_argument_rate() {
    assert_eq!(sweep("sin", &[Arg::Float], "float", Rule::Max), 4);
    assert_eq!(sweep("sin", &[Arg::Float3], "float3", Rule::Max), 4);
}

#[test]
fn pow_takes_the_highest_rate() {
    assert_eq!(sweep("pow", &[Arg::Float, Arg::Float], "float", Rule::Max), 16);
    assert_eq!(sweep("pow", &[Arg::Float3, Arg::Float3], "float3", Rule::Max), 16);
}

#[test]
fn mix_takes_the_highest_rate() {
    assert_eq!(sweep("mix", &[Arg::Float3, Arg::Float3, Arg::Float], "float3", Rule::Max), 64);
    assert_eq!(sweep("mix", &[Arg::Float, Arg::Float, Arg::Float], "float", Rule::Max), 64);
}

#[test]
fn clamp_takes_the_highest_rate() {
    assert_eq!(sweep("clamp", &[Arg::Float, Arg::Float, Arg::Float], "float", Rule::Max), 64);
    // The scalar-bounds form `clamp(float3, float, float)`.
    assert_eq!(sweep("clamp", &[Arg::Float3, Arg::Float, Arg::Float], "float3", Rule::Max), 64);
}

#[test]
fn smoothstep_takes_the_highest_rate() {
    assert_eq!(sweep("smoothstep", &[Arg::Float, Arg::Float, Arg::Float], "float", Rule::Max), 64);
}

#[test]
fn length_normalize_and_dot_take_the_highest_rate() {
    assert_eq!(sweep("length", &[Arg::Float3], "float", Rule::Max), 4);
    assert_eq!(sweep("normalize", &[Arg::Float3], "float3", Rule::Max), 4);
    assert_eq!(sweep("dot", &[Arg::Float3, Arg::Float3], "float", Rule::Max), 16);
    assert_eq!(sweep("cross", &[Arg::Float3, Arg::Float3], "float3", Rule::Max), 16);
}

#[test]
fn noise_takes_the_highest_rate() {
    assert_eq!(sweep("noise", &[Arg::Float], "float", Rule::Max), 4);
    assert_eq!(sweep("noise", &[Arg::Float, Arg::Float], "float", Rule::Max), 16);
    // `noise(point)` through the implicit float3 -> point conversion.
    assert_eq!(sweep("noise", &[Arg::Float3], "float", Rule::Max), 4);
    assert_eq!(sweep("noise", &[Arg::Float3, Arg::Float], "float", Rule::Max), 16);
}

#[test]
fn select_takes_the_highest_rate_of_condition_and_values() {
    assert_eq!(sweep("select", &[Arg::Bool, Arg::Float, Arg::Float], "float", Rule::Max), 64);
    assert_eq!(sweep("select", &[Arg::Bool, Arg::Float3, Arg::Float3], "float3", Rule::Max), 64);
}

#[test]
fn texture_filters_with_derivatives() {
    // The texture is a primitive-group parameter; its coordinate takes every rate. A lookup at a
    // varying coordinate filters over screen derivatives, so it is per fragment.
    assert_eq!(sweep("texture", &[Arg::Texref, Arg::Float3], "float4", Rule::Derivative), 4);
}

#[test]
fn derivatives_are_per_fragment_or_exactly_zero() {
    assert_eq!(sweep("Du", &[Arg::Float], "float", Rule::Derivative), 4);
    assert_eq!(sweep("Dv", &[Arg::Float], "float", Rule::Derivative), 4);
    assert_eq!(sweep("Du", &[Arg::Float3], "float3", Rule::Derivative), 4);
    assert_eq!(sweep("filterwidth", &[Arg::Float], "float", Rule::Derivative), 4);
    assert_eq!(sweep("filterstep", &[Arg::Float, Arg::Float], "float", Rule::Derivative), 16);
}

#[test]
fn integrate_removes_perlight() {
    assert_eq!(sweep("integrate", &[Arg::PerlightFloat], "float", Rule::Integrate), 4);
    // The per-light variables themselves are perlight.
    let s = shader(&probe("float", "integrate(c_lit)"));
    assert_eq!(rate_of(&s, "c_lit"), Rate { frequency: Frequency::Constant, perlight: true });
    assert_eq!(rate_of(&s, "v_lit"), Rate { frequency: Frequency::Vertex, perlight: true });
    // A value computed from the per-light predefined variables, summed.
    let s = shader(&lines(&[
        "surface shader float4 lambert(vertex float4 uv)",
        "{",
        "    float d = dot(N, L);",
        "    float4 lit = integrate(Cl * d);",
        "    return lit;",
        "}",
    ]));
    assert_eq!(rate_of(&s, "d"), Rate { frequency: Frequency::Vertex, perlight: true });
    assert_eq!(rate_of(&s, "lit"), Rate::VERTEX);
}

#[test]
fn functions_with_fixed_rates() {
    // Light sums and `random` are per fragment whatever their arguments.
    let s = shader(&lines(&[
        "surface matte(float Kd = 1)",
        "{",
        "    uniform normal n = normal (0, 0, 1);",
        "    color d = diffuse(n);",
        "    float r = random();",
        "    Ci = d * r * Kd;",
        "}",
    ]));
    assert_eq!(the_library_call(&s, "diffuse").rate, Rate::FRAGMENT, "{:?}", the_library_call(&s, "diffuse"));
    assert_eq!(the_call(&s, "random").2.rate, Rate::FRAGMENT);
    let s = shader(&lines(&[
        "surface shader float4 screen(primitive group float k)",
        "{",
        "    float4 p = xyz_screen();",
        "    return p * k;",
        "}",
    ]));
    assert_eq!(rate_of(&s, "p"), Rate::FRAGMENT);
}

// ---------------------------------------------------------------------------------------------
// Promotion

/// A Stanford shader with one variable of each rate, and `body` after them.
fn stanford(body: &[&str]) -> String {
    let mut all = vec![
        "surface shader float4 promo(primitive group float g, vertex float v)",
        "{",
        "    constant float c = 2;",
        "    fragment float f = v;",
    ];
    all.extend(body);
    all.push("    return {0, 0, 0, 1};");
    all.push("}");
    lines(&all)
}

#[test]
fn uniform_times_vertex_is_vertex() {
    let s = shader(&stanford(&["    float x = g * v;"]));
    let value = stored_into(&s, "x");
    assert!(matches!(value.kind, ExprKind::Binary(..)));
    assert_eq!(value.rate, Rate::VERTEX);
    assert_eq!(rate_of(&s, "x"), Rate::VERTEX);
    assert!(!local(&s, "x").declared);
}

#[test]
fn vertex_times_fragment_is_fragment() {
    let s = shader(&stanford(&["    float x = v * f;"]));
    assert_eq!(stored_into(&s, "x").rate, Rate::FRAGMENT);
    assert_eq!(rate_of(&s, "x"), Rate::FRAGMENT);
}

#[test]
fn constant_times_uniform_is_uniform() {
    let s = shader(&stanford(&["    float x = c * g;"]));
    assert_eq!(rate_of(&s, "x"), Rate::UNIFORM);
}

#[test]
fn constants_fold_to_constant_rate() {
    let s = shader(&stanford(&["    float x = 2 * 3 + c;", "    float y = sin(x) * (1 + 0.5);"]));
    assert_eq!(rate_of(&s, "x"), Rate::CONSTANT);
    assert_eq!(rate_of(&s, "y"), Rate::CONSTANT);
    assert!(
        s.exprs.iter().filter(|e| matches!(e.kind, ExprKind::Binary(..))).all(|e| e.rate == Rate::CONSTANT)
    );
}

#[test]
fn inferred_variables_chain() {
    // The rate flows through inferred variables, and a variable is the join of all its stores.
    let s = shader(&stanford(&[
        "    float a = g;",
        "    float b = a * 2;",
        "    b = v;",
        "    float c2 = b + 1;",
    ]));
    assert_eq!(rate_of(&s, "a"), Rate::UNIFORM);
    assert_eq!(rate_of(&s, "b"), Rate::VERTEX);
    assert_eq!(rate_of(&s, "c2"), Rate::VERTEX);
}

#[test]
fn declared_rates_stay_as_declared() {
    // A value of a lower rate fits in a variable of a higher one; the variable keeps its rate.
    let s = shader(&stanford(&["    fragment float x = c;", "    vertex float y = g;"]));
    assert_eq!(rate_of(&s, "x"), Rate::FRAGMENT);
    assert!(local(&s, "x").declared);
    assert_eq!(rate_of(&s, "y"), Rate::VERTEX);
}

#[test]
fn every_expression_is_at_least_as_high_as_its_operands() {
    let s = shader(&stanford(&["    float x = (g + c) * v - f / 2;", "    float y = x > 0.5 ? g : c;"]));
    for e in &s.exprs {
        let operands: Vec<_> = match &e.kind {
            ExprKind::Unary(_, a) | ExprKind::Convert(a) => vec![*a],
            ExprKind::Binary(_, a, b) | ExprKind::Index(a, b) => vec![*a, *b],
            ExprKind::Select(c, a, b) => vec![*c, *a, *b],
            ExprKind::Construct(parts) | ExprKind::Builtin(_, parts) => parts.clone(),
            _ => vec![],
        };
        for o in operands {
            assert!(s.expr(o).rate.fits_in(e.rate), "{:?} is below its operand {:?}", e, s.expr(o));
        }
    }
    assert_eq!(rate_of(&s, "x"), Rate::FRAGMENT);
    assert_eq!(rate_of(&s, "y"), Rate::FRAGMENT);
}

// ---------------------------------------------------------------------------------------------
// Control dependence

#[test]
fn a_store_under_a_fragment_condition_is_fragment() {
    let s = shader(&stanford(&["    float x = 0;", "    if (f > 0.5)", "        x = 1;"]));
    assert_eq!(rate_of(&s, "x"), Rate::FRAGMENT);
    // The stored values themselves are constants: only the condition raises the rate.
    assert!(stores_into(&s, "x").iter().all(|e| e.rate == Rate::CONSTANT));
}

#[test]
fn a_store_in_an_else_branch_is_control_dependent() {
    let s = shader(&stanford(&[
        "    float x = 0;",
        "    if (v > 0.5)",
        "        x = x;",
        "    else",
        "        x = 2;",
    ]));
    assert_eq!(rate_of(&s, "x"), Rate::VERTEX);
}

#[test]
fn a_store_under_a_uniform_condition_stays_uniform() {
    let s = shader(&stanford(&["    float x = 0;", "    if (g > 0.5)", "        x = 1;"]));
    assert_eq!(rate_of(&s, "x"), Rate::UNIFORM);
}

#[test]
fn nested_conditions_take_the_highest_rate() {
    let s = shader(&stanford(&[
        "    float x = 0;",
        "    if (g > 0.5) {",
        "        if (v > 0.5)",
        "            x = 1;",
        "    }",
    ]));
    assert_eq!(rate_of(&s, "x"), Rate::VERTEX);
}

#[test]
fn a_store_in_a_loop_with_a_vertex_condition_is_vertex() {
    let s = shader(&stanford(&[
        "    float n = 0;",
        "    float i;",
        "    for (i = 0; i < v; i += 1)",
        "        n += 1;",
    ]));
    assert_eq!(rate_of(&s, "n"), Rate::VERTEX);
    assert_eq!(rate_of(&s, "i"), Rate::VERTEX);
}

#[test]
fn a_loop_with_a_uniform_condition_keeps_uniform_rates() {
    let s = shader(&stanford(&[
        "    float n = 0;",
        "    float i;",
        "    for (i = 0; i < g; i += 1)",
        "        n += 1;",
    ]));
    assert_eq!(rate_of(&s, "n"), Rate::UNIFORM);
    assert_eq!(rate_of(&s, "i"), Rate::UNIFORM);
}

#[test]
fn a_break_under_a_fragment_condition_makes_the_loop_fragment() {
    let s = shader(&stanford(&[
        "    float n = 0;",
        "    while (n < 10) {",
        "        if (f > 0.5)",
        "            break;",
        "        n += 1;",
        "    }",
    ]));
    assert_eq!(rate_of(&s, "n"), Rate::FRAGMENT);
}

#[test]
fn a_continue_under_a_vertex_condition_makes_the_loop_vertex() {
    let s = shader(&stanford(&[
        "    float n = 0;",
        "    float i;",
        "    for (i = 0; i < 4; i += 1) {",
        "        if (v > 0.5)",
        "            continue;",
        "        n += 1;",
        "    }",
    ]));
    assert_eq!(rate_of(&s, "n"), Rate::VERTEX);
}

#[test]
fn a_return_under_a_vertex_condition_makes_the_result_vertex() {
    let s = shader(&lines(&[
        "float step_at(float x, float edge)",
        "{",
        "    if (x < edge)",
        "        return 0;",
        "    return 1;",
        "}",
        "surface shader float4 stepped(vertex float v, primitive group float g)",
        "{",
        "    float a = step_at(g, 0.5);",
        "    float b = step_at(v, 0.5);",
        "    return {a, b, 0, 1};",
        "}",
    ]));
    assert_eq!(rate_of(&s, "a"), Rate::UNIFORM);
    assert_eq!(rate_of(&s, "b"), Rate::VERTEX);
}

#[test]
fn a_break_two_under_a_vertex_condition_makes_the_outer_loop_vertex() {
    let s = shader(&stanford(&[
        "    float n = 0;",
        "    float i = 0;",
        "    float j = 0;",
        "    while (i < 4) {",
        "        i += 1;",
        "        while (j < 4) {",
        "            j += 1;",
        "            if (v > 0.5)",
        "                break 2;",
        "        }",
        "        n += 1;",
        "    }",
    ]));
    assert_eq!(rate_of(&s, "j"), Rate::VERTEX);
    assert_eq!(rate_of(&s, "n"), Rate::VERTEX);
    assert_eq!(rate_of(&s, "i"), Rate::VERTEX);
}

#[test]
fn a_break_two_under_a_varying_condition_is_checked_in_renderman() {
    let (found, _) = codes(&lines(&[
        "surface rings()",
        "{",
        "    uniform float i, j;",
        "    uniform float x = 0;",
        "    for (i = 0; i < 3; i += 1) {",
        "        for (j = 0; j < 3; j += 1) {",
        "            if (s > 0.5) break 2;",
        "        }",
        "        x += 1;",
        "    }",
        "    Ci = x;",
        "}",
    ]));
    // `j = 0`, `j += 1`, `i += 1` and `x += 1` all run a varying number of times.
    assert_eq!(found, [Code::ControlDependence; 4]);
}

// ---------------------------------------------------------------------------------------------
// RenderMan placement

#[test]
fn renderman_placement() {
    let s = shader(&lines(&[
        "surface placed(float a = 1; varying float b = 0; output varying float c = 0;",
        "               output float d = 0; uniform float e = 2)",
        "{",
        "    float x = 1;",
        "    varying float y = 2;",
        "    uniform float z = 3;",
        "    c = x + y + b;",
        "    d = z * a * e;",
        "    Ci = c;",
        "}",
    ]));
    assert!(!s.stanford);
    let param = |name: &str| {
        let l = local(&s, name);
        assert!(s.params.iter().any(|p| s.local(*p).name == name), "`{name}` is a parameter");
        assert!(l.declared, "`{name}` has a declared rate");
        (l.rate, matches!(l.kind, LocalKind::Param { output: true, .. }))
    };
    assert_eq!(param("a"), (Rate::UNIFORM, false));
    assert_eq!(param("b"), (Rate::VERTEX, false));
    assert_eq!(param("c"), (Rate::FRAGMENT, true));
    assert_eq!(param("d"), (Rate::UNIFORM, true));
    assert_eq!(param("e"), (Rate::UNIFORM, false));
    for (name, rate) in [("x", Rate::FRAGMENT), ("y", Rate::FRAGMENT), ("z", Rate::UNIFORM)] {
        let l = local(&s, name);
        assert_eq!((l.rate, l.declared, &l.kind), (rate, true, &LocalKind::Var), "`{name}`");
    }
}

#[test]
fn renderman_locals_are_fragment_even_when_constant() {
    // A RenderMan variable is varying by declaration, whatever is stored in it.
    let s = shader(&lines(&["surface flat()", "{", "    float k = 1;", "    Ci = k;", "}"]));
    assert_eq!(rate_of(&s, "k"), Rate::FRAGMENT);
    assert_eq!(stored_into(&s, "k").rate, Rate::CONSTANT);
}

#[test]
fn stanford_placement() {
    let s = shader(&lines(&[
        "surface shader float4 placed(float4 a, vertex float4 b, primitive group float4 c)",
        "{",
        "    float4 x = a;",
        "    fragment float4 y = b;",
        "    return x + y + c;",
        "}",
    ]));
    assert!(s.stanford);
    assert_eq!((rate_of(&s, "a"), local(&s, "a").declared), (Rate::UNIFORM, true));
    assert_eq!(rate_of(&s, "b"), Rate::VERTEX);
    assert_eq!(rate_of(&s, "c"), Rate::UNIFORM);
    assert_eq!((rate_of(&s, "x"), local(&s, "x").declared), (Rate::UNIFORM, false));
    assert_eq!((rate_of(&s, "y"), local(&s, "y").declared), (Rate::FRAGMENT, true));
}

#[test]
fn predefined_variable_rates() {
    let s = shader(&lines(&[
        "surface probe()",
        "{",
        "    float a = s;",
        "    float b = du;",
        "    point e = E;",
        "    Ci = a + b + e[0];",
        "}",
    ]));
    let global_rate = |name: &str| {
        s.exprs
            .iter()
            .find_map(|e| match e.kind {
                ExprKind::Global(g) if g.name == name => Some(e.rate),
                _ => None,
            })
            .unwrap_or_else(|| panic!("no use of `{name}`"))
    };
    assert_eq!(global_rate("s"), Rate::VERTEX);
    assert_eq!(global_rate("du"), Rate::FRAGMENT);
    assert_eq!(global_rate("E"), Rate::UNIFORM);
    assert_eq!(global_rate("Ci"), Rate::FRAGMENT);
}

// ---------------------------------------------------------------------------------------------
// Implicit conversions

/// The operand of a `Convert` node.
fn converted<'s>(shader: &'s Shader, e: &'s Expr) -> &'s Expr {
    match e.kind {
        ExprKind::Convert(inner) => shader.expr(inner),
        _ => panic!("expected a conversion, found {:?}", e.kind),
    }
}

#[test]
fn int_converts_to_float() {
    let s = shader(&lines(&[
        "surface shader float4 ints(primitive group float g)",
        "{",
        "    int i = 3;",
        "    float x = i;",
        "    float y = 2;",
        "    return {x, y, g, 1};",
        "}",
    ]));
    let x = stored_into(&s, "x");
    assert_eq!(x.ty, Type::FLOAT);
    assert_eq!(converted(&s, x).ty, Type::INT);
    // An int literal becomes a float literal rather than a conversion.
    let y = stored_into(&s, "y");
    assert_eq!((&y.kind, y.ty), (&ExprKind::Literal(Literal::Float(2.0)), Type::FLOAT));
}

#[test]
fn float_converts_to_color() {
    let s =
        shader(&lines(&["surface grey(float Kd = 0.5)", "{", "    color c = Kd;", "    Ci = Cs * 2;", "}"]));
    let c = stored_into(&s, "c");
    assert_eq!(c.ty, Type::of(Base::Color));
    assert_eq!(converted(&s, c).ty, Type::FLOAT);
    // In arithmetic, the scalar is widened to the colour.
    let product = stored_into_global(&s, "Ci");
    let ExprKind::Binary(_, a, b) = product.kind else { panic!("expected a product") };
    assert_eq!(s.expr(a).ty, Type::of(Base::Color));
    assert_eq!(s.expr(b).ty, Type::of(Base::Color));
    assert_eq!(converted(&s, s.expr(b)).ty, Type::INT);
}

/// The one value stored into the predefined variable `name`.
fn stored_into_global<'s>(shader: &'s Shader, name: &str) -> &'s Expr {
    let values: Vec<&Expr> = shader
        .body
        .iter()
        .filter_map(|stmt| match stmt {
            Stmt::Store { place: Place::Global(g), value, .. } if g.name == name => Some(shader.expr(*value)),
            _ => None,
        })
        .collect();
    assert_eq!(values.len(), 1, "expected one store into `{name}`");
    values[0]
}

#[test]
fn point_converts_to_vector() {
    let s = shader(&lines(&[
        "surface directions()",
        "{",
        "    vector v = P;",
        "    normal n = v;",
        "    Ci = color (v[0], n[1], 0);",
        "}",
    ]));
    let v = stored_into(&s, "v");
    assert_eq!(v.ty, Type::of(Base::Vector));
    let inner = converted(&s, v);
    assert_eq!(inner.ty, Type::of(Base::Point));
    assert!(matches!(inner.kind, ExprKind::Global(g) if g.name == "P"));
    let n = stored_into(&s, "n");
    assert_eq!((n.ty, converted(&s, n).ty), (Type::of(Base::Normal), Type::of(Base::Vector)));
}

#[test]
fn float3_and_color_convert_both_ways() {
    let s = shader(&lines(&[
        "surface shader float4 tinted(vertex float3 v3)",
        "{",
        "    color c = v3;",
        "    float3 back = c;",
        "    return {back, 1};",
        "}",
    ]));
    let c = stored_into(&s, "c");
    assert_eq!((c.ty, converted(&s, c).ty), (Type::of(Base::Color), Type::of(Base::Float3)));
    let back = stored_into(&s, "back");
    assert_eq!((back.ty, converted(&s, back).ty), (Type::of(Base::Float3), Type::of(Base::Color)));
    // A conversion keeps the rate of its operand.
    assert_eq!(c.rate, Rate::VERTEX);
    assert_eq!(rate_of(&s, "back"), Rate::VERTEX);
}

#[test]
fn color_does_not_convert_to_point() {
    let (found, shaders) = codes(&lines(&["surface mixed()", "{", "    point p = Cs;", "    Ci = Cs;", "}"]));
    assert_eq!(found, [Code::TypeMismatch]);
    assert_eq!(shaders, 0, "a shader with errors is left out of the program");
    // An explicit cast converts.
    let s =
        shader(&lines(&["surface mixed()", "{", "    point p = point (Cs);", "    Ci = color (p);", "}"]));
    let p = stored_into(&s, "p");
    assert_eq!((p.ty, converted(&s, p).ty), (Type::of(Base::Point), Type::of(Base::Color)));
}

#[test]
fn int_does_not_convert_to_uint() {
    let (found, _) = codes(&lines(&[
        "surface shader float4 bits(primitive group float g)",
        "{",
        "    int i = 3;",
        "    uint u = i;",
        "    return {g, 0, 0, 1};",
        "}",
    ]));
    assert_eq!(found, [Code::TypeMismatch]);
}

// ---------------------------------------------------------------------------------------------
// Overload resolution

#[test]
fn color_noise_picks_the_color_overload() {
    let s = shader(&lines(&["surface marble()", "{", "    color c = color noise(P);", "    Ci = c;", "}"]));
    let result = the_library_call(&s, "noise");
    assert_eq!((result.name.as_str(), result.ty), ("__noise_color result", Type::of(Base::Color)));
}

#[test]
fn float_noise_picks_the_float_overload() {
    let s = shader(&lines(&["surface marble()", "{", "    float n = noise(P);", "    Ci = n;", "}"]));
    assert_eq!(the_library_call(&s, "noise").name, "__noise_float result");
}

#[test]
fn noise_assigned_to_a_color_picks_the_color_overload() {
    let s = shader(&lines(&["surface marble()", "{", "    Ci = noise(P * 4);", "}"]));
    assert_eq!(the_library_call(&s, "noise").name, "__noise_color result");
}

#[test]
fn noise_without_context_defaults_to_float() {
    // A comparison wants no particular type of its operands.
    let s = shader(&lines(&["surface marble()", "{", "    if (noise(P) > 0.5)", "        Ci = Cs;", "}"]));
    assert_eq!(the_library_call(&s, "noise").name, "__noise_float result");
}

#[test]
fn pow_with_an_int_literal_exponent() {
    let s =
        shader(&lines(&["surface shiny(float x = 2)", "{", "    float y = pow(x, 2);", "    Ci = y;", "}"]));
    let (sig, args, call) = the_call(&s, "pow");
    assert_eq!(sig, "float pow(float, float)");
    assert_eq!(call.ty, Type::FLOAT);
    let exponent = s.expr(args[1]);
    assert_eq!((&exponent.kind, exponent.ty), (&ExprKind::Literal(Literal::Float(2.0)), Type::FLOAT));
}

#[test]
fn pow_of_a_color_picks_the_color_overload() {
    let s = shader(&lines(&["surface shiny()", "{", "    Ci = pow(Cs, 2);", "}"]));
    let (sig, args, _) = the_call(&s, "pow");
    assert_eq!(sig, "color pow(color, color)");
    assert_eq!(converted(&s, s.expr(args[1])).ty, Type::INT);
}

#[test]
fn user_overloads_are_chosen_by_argument_type() {
    let src = |arg: &str| {
        lines(&[
            "float weight(float x) { return x; }",
            "float weight(color c) { return comp(c, 0); }",
            "surface weighed()",
            "{",
            &format!("    float w = weight({arg});"),
            "    Ci = w;",
            "}",
        ])
    };
    // Each overload's parameter is a local of the shader it is inlined into.
    let s = shader(&src("Cs"));
    assert!(has_local(&s, "c") && !has_local(&s, "x"), "{:?}", names(&s));
    assert_eq!(local(&s, "c").ty, Type::of(Base::Color));
    let s = shader(&src("s"));
    assert!(has_local(&s, "x") && !has_local(&s, "c"), "{:?}", names(&s));
    // An int is closer to float (cost 1) than to color (cost 2).
    let s = shader(&src("1"));
    assert!(has_local(&s, "x") && !has_local(&s, "c"), "{:?}", names(&s));
}

#[test]
fn stanford_user_overloads_are_chosen_by_argument_type() {
    let src = lines(&[
        "float4 shade(float4 c) { return c; }",
        "float4 shade(float3 c3) { return {c3, 1}; }",
        "surface shader float4 both(vertex float4 uv, primitive group float3 k)",
        "{",
        "    return shade(uv) + shade(k);",
        "}",
    ]);
    let s = shader(&src);
    assert_eq!(local(&s, "c").ty, Type::of(Base::Float4));
    assert_eq!(local(&s, "c3").ty, Type::of(Base::Float3));
    // Parameters without a rate take their argument's rate at each call.
    assert_eq!(rate_of(&s, "c"), Rate::VERTEX);
    assert_eq!(rate_of(&s, "c3"), Rate::UNIFORM);
}

#[test]
fn an_exact_match_beats_a_conversion() {
    // `length(float3)` takes the float3 as it is; the point, vector and normal forms need a
    // conversion.
    let s = shader(&lines(&[
        "surface shader float4 len(vertex float3 v3)",
        "{",
        "    float l = length(v3);",
        "    return {l, 0, 0, 1};",
        "}",
    ]));
    let (sig, args, _) = the_call(&s, "length");
    assert_eq!(sig, "float length(float3)");
    assert!(matches!(s.expr(args[0]).kind, ExprKind::Local(_)));
}

#[test]
fn a_store_at_a_varying_index_makes_the_array_varying() {
    // Which element is written depends on the index, as if the store were under a condition on it.
    let s = shader(&lines(&[
        "surface shader float4 pick(vertex float4 uv)",
        "{",
        "    float weights[4] = {0, 0, 0, 0};",
        "    weights[int(uv[0] * 3)] = 1;",
        "    return {weights[0], weights[1], weights[2], weights[3]};",
        "}",
    ]));
    let weights = s.locals.iter().find(|l| l.name == "weights").expect("the array");
    assert_eq!(weights.rate, Rate::VERTEX);
}

#[test]
fn a_constant_table_declared_in_a_varying_loop_stays_constant() {
    // The declaration is its only store, so wherever it is read it holds the table: a function
    // with a `constant` table may be called from a loop bounded by a varying count.
    let s = shader(&lines(&[
        "float lookup(float i) {",
        "    constant float table[3] = { 1, 2, 4 };",
        "    return table[int(i) % 3];",
        "}",
        "surface sum(varying float n = 3)",
        "{",
        "    float total = 0;",
        "    float i;",
        "    for (i = 0; i < n; i += 1) total += lookup(i);",
        "    Ci = total;",
        "}",
    ]));
    assert_eq!(rate_of(&s, "table"), Rate::CONSTANT);
}

#[test]
fn a_constant_variable_stored_under_a_varying_condition_is_still_an_error() {
    // Stored once, but not by its declaration: read after the `if`, it may be either value.
    let (found, _) = codes(&lines(&[
        "surface s()",
        "{",
        "    constant float x;",
        "    if (s > 0.5) x = 1;",
        "    Ci = x;",
        "}",
    ]));
    assert_eq!(found, [Code::ControlDependence]);
    // Declared before a loop of varying count and stored in it: after n passes it holds n.
    let (found, _) = codes(&lines(&[
        "surface s()",
        "{",
        "    float i;",
        "    constant float x = 1;",
        "    for (i = 0; i < s; i += 1) {",
        "        x = x + 1;",
        "        Ci = x;",
        "    }",
        "}",
    ]));
    assert_eq!(found, [Code::ControlDependence]);
    // Declared in the loop and stored again there, it is new on each pass, and every pass stores
    // the same values (issue 23).
    let (found, _) = codes(&lines(&[
        "surface s()",
        "{",
        "    float i;",
        "    for (i = 0; i < s; i += 1) {",
        "        constant float x = 1;",
        "        x = 2;",
        "        Ci = x;",
        "    }",
        "}",
    ]));
    assert_eq!(found, []);
}

#[test]
fn a_functions_constant_counter_answers_only_to_conditions_inside_it() {
    // The counter exists only while the call runs, so the varying `if` around the call cannot
    // make it differ between the points that see it; this is how the stdlib's lattice loops are
    // written (vnoise called under a varying condition).
    let src = lines(&[
        "float tri(float x) { float c = 0; constant float j; for (j = 0; j < 3; j += 1) c += x * j; return c; }",
        "surface t() { float c = 0; if (s > 0.5) { c = tri(s); } Ci = c; }",
    ]);
    let sh = shader(&src);
    assert_eq!(rate_of(&sh, "j").frequency, Frequency::Constant);
    assert!(
        shader(&lines(&[
            "#include <lattice.sl>",
            "surface r() { float v = 0; if (s > 0.5) v = vnoise(P); Ci = v; }"
        ]))
        .params
        .is_empty()
    );
    // A condition inside the function still counts.
    let inside = lines(&[
        "float bad(float x) { constant float j = 0; if (x > 0.5) j = 1; return j; }",
        "surface t() { Ci = bad(s); }",
    ]);
    assert_eq!(codes(&inside).0, vec![Code::ControlDependence]);
    // So does a varying condition around the call for a variable declared outside the function.
    let outside = lines(&["surface t() { constant float j = 0; if (s > 0.5) j = 1; Ci = j; }"]);
    assert_eq!(codes(&outside).0, vec![Code::ControlDependence]);
}

/// Issue 23: a variable with a declared rate whose only store is its initialiser, declared inside
/// a varying branch, is read only in that branch after its declaration: no E0605 (a `uniform`
/// one was reported; a `constant` one already was not). Stored again there under another
/// varying condition, or stored once but not by its declaration, it still is.
#[test]
fn a_uniform_variable_declared_and_initialised_in_a_varying_branch_is_not_control_dependent() {
    for rate in ["uniform", "constant"] {
        let (found, _) = codes(&lines(&[
            "surface s()",
            "{",
            "    float v = 0;",
            "    if (s > 0.5) {",
            &format!("        {rate} float k = 2;"),
            "        v = k * s;",
            "    }",
            "    Ci = v;",
            "}",
        ]));
        assert!(found.is_empty(), "{rate}: {found:?}");
    }
    let (found, _) = codes(&lines(&[
        "surface s()",
        "{",
        "    float v = 0;",
        "    if (s > 0.5) {",
        "        uniform float k = 2;",
        "        if (t > 0.5) k = 3;",
        "        v = k * s;",
        "    }",
        "    Ci = v;",
        "}",
    ]));
    assert!(!found.is_empty() && found.iter().all(|c| *c == Code::ControlDependence), "{found:?}");
    let (found, _) = codes(&lines(&[
        "surface s()",
        "{",
        "    uniform float x;",
        "    if (s > 0.5) x = 1;",
        "    Ci = x;",
        "}",
    ]));
    assert_eq!(found, [Code::ControlDependence]);
}

/// Issue 23: a declared variable whose whole life is inside a varying branch (declared there with
/// an initialiser, then stored again there, by statements or in a loop of constant count) holds
/// one value in every point that reaches each of its reads: it answers only to the conditions
/// between its declaration and a store, not to the branch around it. The interpreter, which
/// keeps such a variable in one uniform register, still computes each point's value.
#[test]
fn a_declared_variable_living_inside_a_varying_branch_answers_only_to_conditions_inside_it() {
    for (rate, frequency) in [("constant", Frequency::Constant), ("uniform", Frequency::PrimitiveGroup)] {
        let src = lines(&[
            "surface s()",
            "{",
            "    float v = -1;",
            "    if (s > 0.5) {",
            &format!("        {rate} float k = 2;"),
            "        k = k * 3;",
            "        k += 1;",
            &format!("        {rate} float i = 0;"),
            "        for (i = 0; i < 3; i += 1)",
            "            k += i;",
            "        v = k * s;",
            "    }",
            "    Ci = v;",
            "}",
        ]);
        let sh = shader(&src);
        assert_eq!(rate_of(&sh, "k").frequency, frequency, "{rate}");
        let program = patina_compiler::backend::cpu::CpuProgram::compile(
            &patina_compiler::opt::Prepared::new(sh.clone()),
            &Default::default(),
        )
        .unwrap_or_else(|d| panic!("{}: {}", d.code, d.message));
        for (s, want) in [(0.25, -1.0), (0.75, 10.0 * 0.75)] {
            let mut eval = patina_compiler::backend::cpu::Evaluator::<f64>::new(&program);
            let out = eval.eval_points(1, &[("s", &[s])], &["Ci"]).unwrap();
            assert_eq!(out[0], vec![want; 3], "{rate} at s = {s}");
        }
    }
}

/// Issue 23: what still depends on a varying condition inside the variable's life is reported: a
/// store under a varying `if` or in a loop of varying count after the declaration, a variable
/// declared outside the branch, and one declared without an initialiser (where its life begins
/// is not known: in a loop it keeps its value from one pass to the next).
#[test]
fn a_declared_variable_stored_under_a_varying_condition_inside_its_life_is_still_an_error() {
    for body in [
        "if (s > 0.5) { constant float k = 2; if (t > 0.5) k = 3; Ci = k; }",
        "if (s > 0.5) { constant float k = 2; float i; for (i = 0; i < t * 4; i += 1) k += 1; Ci = k; }",
        "constant float k = 2; if (s > 0.5) { k = 3; Ci = k; }",
        "if (s > 0.5) { constant float k; k = 3; Ci = k; }",
    ] {
        let (found, _) = codes(&lines(&["surface s()", "{", body, "}"]));
        assert_eq!(found, [Code::ControlDependence], "{body}");
    }
}

#[test]
fn a_long_chain_of_variables_takes_the_rate_of_its_start() {
    // Each variable is inferred from the one before: rates must flow along the whole chain in
    // program order, however long (they once flowed one link per round, for 64 rounds).
    let mut body: Vec<String> = vec!["    float a0 = v;".into()];
    body.extend((1..200).map(|i| format!("    float a{i} = a{} + 1;", i - 1)));
    let body: Vec<&str> = body.iter().map(String::as_str).collect();
    let s = shader(&stanford(&body));
    assert_eq!(rate_of(&s, "a199"), Rate::VERTEX);
    assert_eq!(stored_into(&s, "a199").rate, Rate::VERTEX);
}
