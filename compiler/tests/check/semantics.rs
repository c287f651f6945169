//! Snapshot tests of the semantic diagnostics: names and types (`E05xx`) and rates (`E06xx`).
//!
//! Each test checks one small shader, written for the test in RenderMan or Stanford style, with one
//! mistake; it asserts the exact list of codes produced (so that the mistake gives its diagnostic
//! and no cascade of others) and snapshots the diagnostics as a user sees them. After a deliberate
//! change, update the snapshots with
//! `INSTA_UPDATE=always cargo test -p patina-compiler --test semantics` and review every changed
//! `.snap` file.
//!
//! Tests marked `#[ignore = "bug: ..."]` assert the behaviour the compiler should have and does not
//! have yet; run them with `cargo test -p patina-compiler --test semantics -- --ignored`.

use patina_compiler::check_source;
use patina_compiler::diag::{Code, render_text};
use patina_compiler::syntax::preprocess::MemoryLoader;

/// Checks `src` as `shader.sl`; returns the codes found, in order, and the diagnostics rendered as
/// text.
fn run(src: &str) -> (Vec<&'static str>, String) {
    let checked = check_source("shader.sl", src, &MemoryLoader::default());
    let codes = checked.diagnostics.iter().map(|d| d.code.as_str()).collect();
    let list: Vec<_> = checked.diagnostics.iter().cloned().collect();
    (codes, render_text(&checked.sources, &list))
}

/// A source file made of `lines`.
fn lines(lines: &[&str]) -> String {
    let mut text = lines.join("\n");
    text.push('\n');
    text
}

#[test]
fn every_semantic_code_is_covered() {
    // The codes asserted by the tests of this file (the `assert_eq!(codes, [...])` lines).
    let this_file = include_str!("semantics.rs");
    let mut asserted = std::collections::BTreeSet::new();
    for line in this_file.lines().filter(|l| l.trim_start().starts_with("assert_eq!(codes, [")) {
        for part in line.split('"').skip(1).step_by(2) {
            asserted.insert(part.to_string());
        }
    }
    let missing: Vec<&str> = Code::ALL
        .iter()
        .map(|c| c.as_str())
        .filter(|c| c.starts_with("E05") || c.starts_with("E06"))
        .filter(|c| !asserted.contains(*c))
        .collect();
    assert!(missing.is_empty(), "no test produces {missing:?}");
}

// ---------------------------------------------------------------------------------------------
// Names (E0501, E0502)

#[test]
fn unknown_name_with_suggestion() {
    let (codes, text) = run(&lines(&[
        "surface matte(float Kd = 1)",
        "{",
        "    float diffuseness = Kd;",
        "    Ci = Cs * difuseness;",
        "}",
    ]));
    assert_eq!(codes, ["E0501"]);
    insta::assert_snapshot!("unknown_name_with_suggestion", text);
}

#[test]
fn unknown_name_suggests_a_parameter_stanford() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 tint(primitive group float4 basecolor)",
        "{",
        "    return basecolour * 0.5;",
        "}",
    ]));
    assert_eq!(codes, ["E0501"]);
    insta::assert_snapshot!("unknown_name_suggests_a_parameter_stanford", text);
}

#[test]
fn unknown_name_suggests_a_predefined_variable() {
    // `Ci` and `Cs` are both one edit away; the tie goes to the first in alphabetical order.
    let (codes, text) = run(&lines(&["surface matte()", "{", "    Ci = Cd;", "}"]));
    assert_eq!(codes, ["E0501"]);
    insta::assert_snapshot!("unknown_name_suggests_a_predefined_variable", text);
}

#[test]
fn extern_of_an_undeclared_name() {
    let (codes, text) = run(&lines(&[
        "float scaled(float x)",
        "{",
        "    extern float Kdd;",
        "    return x;",
        "}",
        "surface matte(float Kd = 1)",
        "{",
        "    Ci = Cs * scaled(Kd);",
        "}",
    ]));
    assert_eq!(codes, ["E0501"]);
    insta::assert_snapshot!("extern_of_an_undeclared_name", text);
}

#[test]
fn unknown_function_with_suggestion() {
    let (codes, text) =
        run(&lines(&["surface matte(float Kd = 1)", "{", "    Ci = Cs * Kd * smoothstp(0, 1, s);", "}"]));
    assert_eq!(codes, ["E0502"]);
    insta::assert_snapshot!("unknown_function_with_suggestion", text);
}

#[test]
fn unknown_function_stanford() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 lit(vertex float4 uv)",
        "{",
        "    float3 n = normalise(N);",
        "    return {n, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0502"]);
    insta::assert_snapshot!("unknown_function_stanford", text);
}

// ---------------------------------------------------------------------------------------------
// Overloads (E0503, E0504)

#[test]
fn no_matching_overload_lists_candidates() {
    let (codes, text) = run(&lines(&[
        "surface matte(float Kd = 1)",
        "{",
        "    Ci = Cs * Kd * smoothstep(0, 1, \"s\");",
        "}",
    ]));
    assert_eq!(codes, ["E0503"]);
    insta::assert_snapshot!("no_matching_overload_lists_candidates", text);
}

#[test]
fn no_matching_overload_many_candidates() {
    // Sixteen overloads: the first eight are listed, then a count of the rest.
    let (codes, text) =
        run(&lines(&["surface marble()", "{", "    float x = noise(\"a\");", "    Ci = x;", "}"]));
    assert_eq!(codes, ["E0503"]);
    insta::assert_snapshot!("no_matching_overload_many_candidates", text);
}

#[test]
fn no_matching_overload_user_function_stanford() {
    let (codes, text) = run(&lines(&[
        "float4 darken(float4 c, float k)",
        "{",
        "    return c * k;",
        "}",
        "surface shader float4 dim(primitive group float4 base)",
        "{",
        "    return darken(base, base);",
        "}",
    ]));
    assert_eq!(codes, ["E0503"]);
    insta::assert_snapshot!("no_matching_overload_user_function_stanford", text);
}

#[test]
fn ambiguous_call() {
    let (codes, text) = run(&lines(&[
        "float weigh(float x, color c) { return x; }",
        "float weigh(color c, float x) { return x; }",
        "surface matte()",
        "{",
        "    Ci = weigh(1, 1);",
        "}",
    ]));
    assert_eq!(codes, ["E0504"]);
    insta::assert_snapshot!("ambiguous_call", text);
}

// ---------------------------------------------------------------------------------------------
// Types and operators (E0505, E0506)

#[test]
fn type_mismatch_color_for_point() {
    let (codes, text) = run(&lines(&["surface matte()", "{", "    point p = Cs;", "    Ci = Cs;", "}"]));
    assert_eq!(codes, ["E0505"]);
    insta::assert_snapshot!("type_mismatch_color_for_point", text);
}

#[test]
fn type_mismatch_float4_for_float3_stanford() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 tint(primitive group float4 basecolor)",
        "{",
        "    float3 c = basecolor;",
        "    return {c, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0505"]);
    insta::assert_snapshot!("type_mismatch_float4_for_float3_stanford", text);
}

#[test]
fn type_mismatch_in_return_stanford() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 tint(primitive group float4 basecolor)",
        "{",
        "    return \"red\";",
        "}",
    ]));
    assert_eq!(codes, ["E0505"]);
    insta::assert_snapshot!("type_mismatch_in_return_stanford", text);
}

#[test]
fn void_variable() {
    let (codes, text) = run(&lines(&["surface matte()", "{", "    void x;", "    Ci = Cs;", "}"]));
    assert_eq!(codes, ["E0505"]);
    insta::assert_snapshot!("void_variable", text);
}

#[test]
fn remainder_of_floats() {
    let (codes, text) =
        run(&lines(&["surface stripes()", "{", "    float x = s % 2.0;", "    Ci = x;", "}"]));
    assert_eq!(codes, ["E0506"]);
    insta::assert_snapshot!("remainder_of_floats", text);
}

#[test]
fn xor_of_int_and_uint() {
    let (codes, text) = run(&lines(&[
        "surface hashed()",
        "{",
        "    int a = 3;",
        "    uint b = 5u;",
        "    int c = a ^ b;",
        "    Ci = float (c);",
        "}",
    ]));
    assert_eq!(codes, ["E0506"]);
    insta::assert_snapshot!("xor_of_int_and_uint", text);
}

#[test]
fn cross_of_colors() {
    let (codes, text) = run(&lines(&["surface matte()", "{", "    color c = Cs ^ Os;", "    Ci = c;", "}"]));
    assert_eq!(codes, ["E0506"]);
    insta::assert_snapshot!("cross_of_colors", text);
}

#[test]
fn negation_of_a_string() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    string name = \"a\";",
        "    float x = -name;",
        "    Ci = x;",
        "}",
    ]));
    assert_eq!(codes, ["E0506"]);
    insta::assert_snapshot!("negation_of_a_string", text);
}

// ---------------------------------------------------------------------------------------------
// Assignment (E0507, E0508)

#[test]
fn read_only_global() {
    let (codes, text) = run(&lines(&["surface matte()", "{", "    I = 0;", "    Ci = Cs;", "}"]));
    assert_eq!(codes, ["E0507"]);
    insta::assert_snapshot!("read_only_global", text);
}

#[test]
fn assignment_to_a_call() {
    let (codes, text) = run(&lines(&["surface matte()", "{", "    sin(s) = 1;", "    Ci = Cs;", "}"]));
    assert_eq!(codes, ["E0507"]);
    insta::assert_snapshot!("assignment_to_a_call", text);
}

#[test]
fn read_only_predefined_stanford() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 bend(vertex float4 uv)",
        "{",
        "    N = {0, 0, 1};",
        "    return uv;",
        "}",
    ]));
    assert_eq!(codes, ["E0507"]);
    insta::assert_snapshot!("read_only_predefined_stanford", text);
}

#[test]
fn redefinition_of_a_local() {
    let (codes, text) =
        run(&lines(&["surface matte()", "{", "    float x = 1;", "    float x = 2;", "    Ci = x;", "}"]));
    assert_eq!(codes, ["E0508"]);
    insta::assert_snapshot!("redefinition_of_a_local", text);
}

#[test]
fn redefinition_of_a_parameter_stanford() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 tint(primitive group float4 c, vertex float4 c)",
        "{",
        "    return c;",
        "}",
    ]));
    assert_eq!(codes, ["E0508"]);
    insta::assert_snapshot!("redefinition_of_a_parameter_stanford", text);
}

#[test]
fn duplicate_function() {
    let (codes, text) = run(&lines(&[
        "float half(float x) { return x / 2; }",
        "float half(float y) { return y * 0.5; }",
        "surface matte()",
        "{",
        "    Ci = half(s);",
        "}",
    ]));
    assert_eq!(codes, ["E0508"]);
    insta::assert_snapshot!("duplicate_function", text);
}

// ---------------------------------------------------------------------------------------------
// Returns and recursion (E0509, E0510)

#[test]
fn missing_return_in_stanford_shader() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 half_lit(vertex float4 uv)",
        "{",
        "    if (uv[0] > 0.5)",
        "        return uv;",
        "}",
    ]));
    assert_eq!(codes, ["E0509"]);
    insta::assert_snapshot!("missing_return_in_stanford_shader", text);
}

#[test]
fn missing_return_in_function() {
    let (codes, text) = run(&lines(&[
        "float ramp(float x)",
        "{",
        "    if (x > 0)",
        "        return x;",
        "}",
        "surface matte()",
        "{",
        "    Ci = ramp(s);",
        "}",
    ]));
    assert_eq!(codes, ["E0509"]);
    insta::assert_snapshot!("missing_return_in_function", text);
}

#[test]
fn return_without_value_in_stanford_shader() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 early(vertex float4 uv)",
        "{",
        "    if (uv[0] > 0.5)",
        "        return;",
        "    return uv;",
        "}",
    ]));
    assert_eq!(codes, ["E0509"]);
    insta::assert_snapshot!("return_without_value_in_stanford_shader", text);
}

#[test]
fn return_value_in_renderman_shader() {
    let (codes, text) = run(&lines(&["surface matte()", "{", "    Ci = Cs;", "    return Ci;", "}"]));
    assert_eq!(codes, ["E0509"]);
    insta::assert_snapshot!("return_value_in_renderman_shader", text);
}

#[test]
fn recursion() {
    let (codes, text) = run(&lines(&[
        "float fact(float n)",
        "{",
        "    if (n <= 1)",
        "        return 1;",
        "    return n * fact(n - 1);",
        "}",
        "surface matte()",
        "{",
        "    Ci = fact(4);",
        "}",
    ]));
    assert_eq!(codes, ["E0510"]);
    insta::assert_snapshot!("recursion", text);
}

#[test]
fn inlining_too_deep() {
    // Generated code: a chain of 70 functions, each calling the next (the limit is 64; the
    // diagnostic's span and the size limit are tested in tests/limits.rs).
    let mut src = String::from("float f70(float x) { return x; }\n");
    for i in (0..70).rev() {
        src.push_str(&format!("float f{i}(float x) {{ return f{}(x) + 1; }}\n", i + 1));
    }
    src.push_str("surface matte() { Ci = f0(1); }\n");
    let (codes, text) = run(&src);
    assert_eq!(codes, ["E0521"]);
    assert!(text.contains("calls nested more than 64 deep"), "{text}");
}

#[test]
fn overloads_may_call_each_other() {
    // Recursion is a definition calling itself, not a name: a library writes one overload in
    // terms of another.
    let (codes, text) = run(&lines(&[
        "float warp(float x) { return x * x; }",
        "float warp(point p) { return warp(xcomp(p)) + warp(ycomp(p)); }",
        "surface s() { Ci = warp(P); }",
    ]));
    assert!(codes.is_empty(), "{text}");
}

#[test]
fn functions_no_shader_calls_see_the_files_variables() {
    // A library function reading a table declared at file level is checked with the table in
    // scope, as it would be inlined.
    let (codes, text) = run(&lines(&[
        "constant float table[4] = {0.5, 1.5, 2.5, 3.5};",
        "float lookup(int i) { return table[i & 3]; }",
        "float broken(int i) { return missing[i]; }",
    ]));
    assert_eq!(codes, ["E0501"], "{text}");
    assert!(text.contains("missing") && !text.contains("`table`"), "{text}");
}

// ---------------------------------------------------------------------------------------------
// Shader kinds and light loops (E0511, E0512, E0513)

#[test]
fn ambient_in_a_light_shader() {
    let (codes, text) =
        run(&lines(&["light glow(float intensity = 1)", "{", "    Cl = intensity * ambient();", "}"]));
    assert_eq!(codes, ["E0511"]);
    insta::assert_snapshot!("ambient_in_a_light_shader", text);
}

#[test]
fn surface_output_in_a_light_shader() {
    let (codes, text) = run(&lines(&["light glow()", "{", "    Ci = 1;", "}"]));
    assert_eq!(codes, ["E0511"]);
    insta::assert_snapshot!("surface_output_in_a_light_shader", text);
}

#[test]
fn l_outside_illuminance() {
    let (codes, text) = run(&lines(&["surface lambert()", "{", "    Ci = Cs * (L . N);", "}"]));
    assert_eq!(codes, ["E0512"]);
    insta::assert_snapshot!("l_outside_illuminance", text);
}

#[test]
fn cl_outside_illuminance() {
    let (codes, text) = run(&lines(&[
        "surface lambert()",
        "{",
        "    illuminance(P, N, PI / 2) {",
        "        Ci += Cs;",
        "    }",
        "    Ci *= Cl;",
        "}",
    ]));
    assert_eq!(codes, ["E0512"]);
    insta::assert_snapshot!("cl_outside_illuminance", text);
}

#[test]
fn illuminate_in_a_surface_shader() {
    let (codes, text) = run(&lines(&["surface glowing()", "{", "    illuminate(P) { Ci = 1; }", "}"]));
    assert_eq!(codes, ["E0513"]);
    insta::assert_snapshot!("illuminate_in_a_surface_shader", text);
}

#[test]
fn illuminance_in_a_stanford_shader() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 lit(vertex float4 uv)",
        "{",
        "    illuminance(P) { }",
        "    return uv;",
        "}",
    ]));
    assert_eq!(codes, ["E0513"]);
    insta::assert_snapshot!("illuminance_in_a_stanford_shader", text);
}

#[test]
fn break_outside_a_loop() {
    let (codes, text) = run(&lines(&["surface matte()", "{", "    break;", "    Ci = Cs;", "}"]));
    assert_eq!(codes, ["E0513"]);
    insta::assert_snapshot!("break_outside_a_loop", text);
}

#[test]
fn break_two_in_one_loop() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    float i;",
        "    for (i = 0; i < 4; i += 1) {",
        "        if (i > 2)",
        "            break 2;",
        "    }",
        "    Ci = Cs;",
        "}",
    ]));
    assert_eq!(codes, ["E0513"]);
    insta::assert_snapshot!("break_two_in_one_loop", text);
}

#[test]
fn continue_in_a_function_outside_its_loop() {
    // The caller's loop does not count: the function's body is its own.
    let (codes, text) = run(&lines(&[
        "float skip(float x)",
        "{",
        "    if (x > 0)",
        "        continue;",
        "    return x;",
        "}",
        "surface matte()",
        "{",
        "    float i;",
        "    for (i = 0; i < 4; i += 1)",
        "        Ci += skip(i);",
        "}",
    ]));
    assert_eq!(codes, ["E0513"]);
    insta::assert_snapshot!("continue_in_a_function_outside_its_loop", text);
}

// ---------------------------------------------------------------------------------------------
// Tuples, constructors and indexing (E0514, E0515, E0516)

#[test]
fn untyped_tuple() {
    let (codes, text) = run(&lines(&["surface matte()", "{", "    Ci = Cs * length((1, 2, 3));", "}"]));
    assert_eq!(codes, ["E0514"]);
    insta::assert_snapshot!("untyped_tuple", text);
}

#[test]
fn constructor_with_two_components() {
    let (codes, text) = run(&lines(&["surface matte()", "{", "    Ci = color (1, 0);", "}"]));
    assert_eq!(codes, ["E0515"]);
    insta::assert_snapshot!("constructor_with_two_components", text);
}

#[test]
fn braced_two_component_vector() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 uvview(vertex float4 uv)",
        "{",
        "    float3 v = {uv[0], uv[1]};",
        "    return {v, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0515"]);
    insta::assert_snapshot!("braced_two_component_vector", text);
}

#[test]
fn array_initialiser_of_the_wrong_length() {
    let (codes, text) =
        run(&lines(&["surface matte()", "{", "    float weights[3] = {1, 2};", "    Ci = weights[0];", "}"]));
    assert_eq!(codes, ["E0515"]);
    insta::assert_snapshot!("array_initialiser_of_the_wrong_length", text);
}

#[test]
fn index_of_the_wrong_type() {
    let (codes, text) =
        run(&lines(&["surface matte()", "{", "    float a[3] = {1, 2, 3};", "    Ci = a[\"one\"];", "}"]));
    assert_eq!(codes, ["E0516"]);
    insta::assert_snapshot!("index_of_the_wrong_type", text);
}

#[test]
fn constant_index_out_of_range() {
    let (codes, text) =
        run(&lines(&["surface matte()", "{", "    float a[3] = {1, 2, 3};", "    Ci = a[3];", "}"]));
    assert_eq!(codes, ["E0516"]);
    insta::assert_snapshot!("constant_index_out_of_range", text);
}

#[test]
fn index_of_a_scalar() {
    let (codes, text) = run(&lines(&["surface matte()", "{", "    float x = 2;", "    Ci = x[0];", "}"]));
    assert_eq!(codes, ["E0516"]);
    insta::assert_snapshot!("index_of_a_scalar", text);
}

// ---------------------------------------------------------------------------------------------
// Casts and spaces (E0517, E0518)

#[test]
fn cast_of_a_string_to_float() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    string name = \"a\";",
        "    float x = float (name);",
        "    Ci = x;",
        "}",
    ]));
    assert_eq!(codes, ["E0517"]);
    insta::assert_snapshot!("cast_of_a_string_to_float", text);
}

#[test]
fn unknown_coordinate_space_with_suggestion() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    point p = point \"wold\" (0, 0, 0);",
        "    Ci = Cs;",
        "}",
    ]));
    assert_eq!(codes, ["E0518"]);
    insta::assert_snapshot!("unknown_coordinate_space_with_suggestion", text);
}

#[test]
fn unknown_space_with_transposed_letters_suggests() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    point p = point \"wrold\" (0, 0, 0);",
        "    Ci = Cs;",
        "}",
    ]));
    assert_eq!(codes, [Code::UnknownSpace.as_str()]);
    assert!(text.contains("did you mean \"world\"?"), "{text}");
}

#[test]
fn unknown_colour_space_with_suggestion() {
    let (codes, text) =
        run(&lines(&["surface matte()", "{", "    color c = color \"hsb\" (1, 0, 0);", "    Ci = c;", "}"]));
    assert_eq!(codes, ["E0518"]);
    insta::assert_snapshot!("unknown_colour_space_with_suggestion", text);
}

#[test]
fn space_on_a_string() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    string name = string \"world\" \"a\";",
        "    Ci = Cs;",
        "}",
    ]));
    assert_eq!(codes, ["E0518"]);
    insta::assert_snapshot!("space_on_a_string", text);
}

#[test]
fn space_on_a_float() {
    let (codes, text) =
        run(&lines(&["surface matte()", "{", "    float x = float \"world\" (1);", "    Ci = x;", "}"]));
    assert_eq!(codes, [Code::UnknownSpace.as_str()]);
    assert!(text.contains("`float` values have no space"), "{text}");
}

// ---------------------------------------------------------------------------------------------
// Qualifiers and effects (E0519, E0520)

#[test]
fn perlight_in_renderman_style() {
    let (codes, text) =
        run(&lines(&["surface matte()", "{", "    perlight float x = 1;", "    Ci = x;", "}"]));
    assert_eq!(codes, ["E0519"]);
    insta::assert_snapshot!("perlight_in_renderman_style", text);
}

#[test]
fn output_on_a_local() {
    let (codes, text) = run(&lines(&["surface matte()", "{", "    output float x = 1;", "    Ci = x;", "}"]));
    assert_eq!(codes, ["E0519"]);
    insta::assert_snapshot!("output_on_a_local", text);
}

#[test]
fn extern_on_a_parameter() {
    let (codes, text) = run(&lines(&["surface matte(extern float Kd = 1)", "{", "    Ci = Kd;", "}"]));
    assert_eq!(codes, ["E0519"]);
    insta::assert_snapshot!("extern_on_a_parameter", text);
}

#[test]
fn assignment_inside_conditional() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    float x = 0;",
        "    float y = s > 0.5 ? (x = 1) : 0;",
        "    Ci = y;",
        "}",
    ]));
    assert_eq!(codes, ["E0520"]);
    insta::assert_snapshot!("assignment_inside_conditional", text);
}

#[test]
fn assignment_inside_and_stanford() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 count(vertex float4 uv)",
        "{",
        "    float n = 0;",
        "    bool b = uv[0] > 0 && (n += 1) > 0;",
        "    return {n, 0, 0, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0520"]);
    insta::assert_snapshot!("assignment_inside_and_stanford", text);
}

#[test]
fn assignment_in_a_loop_condition() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    float x = 0;",
        "    while ((x = x + 1) < 4) { }",
        "    Ci = x;",
        "}",
    ]));
    assert_eq!(codes, ["E0520"]);
    insta::assert_snapshot!("assignment_in_a_loop_condition", text);
}

// ---------------------------------------------------------------------------------------------
// Declared rates (E0601, E0602)

#[test]
fn fragment_value_in_a_vertex_variable() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 stripes(vertex float4 uv)",
        "{",
        "    fragment float f = uv[1];",
        "    vertex float y = f * 2;",
        "    return {y, 0, 0, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0601"]);
    insta::assert_snapshot!("fragment_value_in_a_vertex_variable", text);
}

#[test]
fn fragment_value_through_an_inferred_variable() {
    // The label points at where the inferred variable got its rate.
    let (codes, text) = run(&lines(&[
        "surface shader float4 stripes(vertex float4 uv)",
        "{",
        "    fragment float f = uv[1];",
        "    float scaled = f * 2;",
        "    vertex float y = scaled + 1;",
        "    return {y, 0, 0, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0601"]);
    insta::assert_snapshot!("fragment_value_through_an_inferred_variable", text);
}

#[test]
fn vertex_parameter_in_a_primitive_group_variable() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 flat(vertex float4 uv)",
        "{",
        "    primitive group float4 c = uv;",
        "    return c;",
        "}",
    ]));
    assert_eq!(codes, ["E0601"]);
    insta::assert_snapshot!("vertex_parameter_in_a_primitive_group_variable", text);
}

#[test]
fn primitive_group_value_in_a_constant() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 tint(primitive group float k)",
        "{",
        "    constant float c = k * 2;",
        "    return {c, c, c, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0601"]);
    insta::assert_snapshot!("primitive_group_value_in_a_constant", text);
}

#[test]
fn varying_global_in_a_uniform_variable() {
    let (codes, text) =
        run(&lines(&["surface matte()", "{", "    uniform float u = s;", "    Ci = Cs * u;", "}"]));
    assert_eq!(codes, ["E0602"]);
    assert!(text.contains("cannot assign a varying value to the uniform variable `u`"), "{text}");
    insta::assert_snapshot!("varying_global_in_a_uniform_variable", text);
}

#[test]
fn varying_local_in_a_uniform_variable() {
    // RenderMan variables are varying unless declared uniform.
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    float x = 1;",
        "    uniform float y = x;",
        "    Ci = y;",
        "}",
    ]));
    assert_eq!(codes, ["E0602"]);
    insta::assert_snapshot!("varying_local_in_a_uniform_variable", text);
}

#[test]
fn varying_parameter_in_a_uniform_variable() {
    let (codes, text) = run(&lines(&[
        "surface paint(varying float mask = 0)",
        "{",
        "    uniform float m;",
        "    m = mask * 0.5;",
        "    Ci = m;",
        "}",
    ]));
    assert_eq!(codes, ["E0602"]);
    insta::assert_snapshot!("varying_parameter_in_a_uniform_variable", text);
}

// ---------------------------------------------------------------------------------------------
// Per-light values (E0603)

#[test]
fn perlight_value_returned_without_integrate() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 lambert(vertex float4 uv)",
        "{",
        "    float4 c = Cl * dot(N, L);",
        "    return c;",
        "}",
    ]));
    assert_eq!(codes, ["E0603"]);
    insta::assert_snapshot!("perlight_value_returned_without_integrate", text);
}

#[test]
fn perlight_value_in_a_fragment_variable() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 lambert(vertex float4 uv)",
        "{",
        "    fragment float d = dot(N, L);",
        "    return {d, d, d, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0603"]);
    insta::assert_snapshot!("perlight_value_in_a_fragment_variable", text);
}

#[test]
fn perlight_variable_returned() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 lambert(vertex float4 uv)",
        "{",
        "    perlight float3 l = L;",
        "    float3 sum = l;",
        "    return {sum, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0603"]);
    insta::assert_snapshot!("perlight_variable_returned", text);
}

// ---------------------------------------------------------------------------------------------
// Derivatives (E0604)

#[test]
fn derivative_in_a_vertex_variable() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 edges(vertex float4 uv)",
        "{",
        "    vertex float d = Du(uv[0]);",
        "    return {d, 0, 0, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0604"]);
    insta::assert_snapshot!("derivative_in_a_vertex_variable", text);
}

#[test]
fn derivative_through_an_inferred_variable() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 edges(vertex float4 uv)",
        "{",
        "    float d = Du(uv[0]);",
        "    vertex float e = d * 2;",
        "    return {e, 0, 0, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0604"]);
    insta::assert_snapshot!("derivative_through_an_inferred_variable", text);
}

#[test]
fn filterwidth_in_a_uniform_variable() {
    let (codes, text) =
        run(&lines(&["surface aa()", "{", "    uniform float w = filterwidth(s);", "    Ci = w;", "}"]));
    assert_eq!(codes, ["E0604"]);
    insta::assert_snapshot!("filterwidth_in_a_uniform_variable", text);
}

// ---------------------------------------------------------------------------------------------
// Control dependence (E0605)

#[test]
fn uniform_assigned_under_varying_if() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    uniform float x = 0;",
        "    if (s > 0.5)",
        "        x = 1;",
        "    Ci = Cs * x;",
        "}",
    ]));
    assert_eq!(codes, ["E0605"]);
    insta::assert_snapshot!("uniform_assigned_under_varying_if", text);
}

#[test]
fn uniform_assigned_under_varying_else() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    uniform float x;",
        "    if (s > 0.5)",
        "        Ci = Cs;",
        "    else",
        "        x = 1;",
        "    Ci = Cs * x;",
        "}",
    ]));
    assert_eq!(codes, ["E0605"]);
    insta::assert_snapshot!("uniform_assigned_under_varying_else", text);
}

#[test]
fn uniform_assigned_in_a_varying_loop() {
    let (codes, text) = run(&lines(&[
        "surface rings()",
        "{",
        "    uniform float x = 0;",
        "    while (x < s * 10)",
        "        x += 1;",
        "    Ci = Cs * x;",
        "}",
    ]));
    assert_eq!(codes, ["E0605"]);
    insta::assert_snapshot!("uniform_assigned_in_a_varying_loop", text);
}

#[test]
fn uniform_assigned_after_varying_break() {
    let (codes, text) = run(&lines(&[
        "surface rings()",
        "{",
        "    uniform float x = 0;",
        "    while (x < 10) {",
        "        if (t > 0.5)",
        "            break;",
        "        x += 1;",
        "    }",
        "    Ci = Cs * x;",
        "}",
    ]));
    assert_eq!(codes, ["E0605"]);
    insta::assert_snapshot!("uniform_assigned_after_varying_break", text);
}

#[test]
fn vertex_assigned_under_fragment_condition() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 edges(vertex float4 uv)",
        "{",
        "    vertex float x = 0;",
        "    if (Du(uv[0]) > 0)",
        "        x = 1;",
        "    return {x, 0, 0, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0605"]);
    insta::assert_snapshot!("vertex_assigned_under_fragment_condition", text);
}

#[test]
fn primitive_group_assigned_in_a_vertex_loop() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 steps(vertex float4 uv)",
        "{",
        "    primitive group float x = 0;",
        "    while (x < uv[0])",
        "        x += 1;",
        "    return {x, 0, 0, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0605"]);
    insta::assert_snapshot!("primitive_group_assigned_in_a_vertex_loop", text);
}

#[test]
fn vertex_assigned_after_fragment_break() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 steps(vertex float4 uv, primitive group float k)",
        "{",
        "    fragment float f = uv[0];",
        "    vertex float x = k;",
        "    while (x < 10) {",
        "        if (f > 0.5)",
        "            break;",
        "        x += 1;",
        "    }",
        "    return {x, 0, 0, 1};",
        "}",
    ]));
    assert_eq!(codes, ["E0605"]);
    insta::assert_snapshot!("vertex_assigned_after_fragment_break", text);
}

// ---------------------------------------------------------------------------------------------
// integrate (E0606) and parameter defaults (E0607)

#[test]
fn integrate_of_a_value_that_is_not_perlight() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 glow(vertex float4 uv)",
        "{",
        "    float4 c = integrate(Cl) + integrate(uv);",
        "    return c;",
        "}",
    ]));
    assert_eq!(codes, ["E0606"]);
    insta::assert_snapshot!("integrate_of_a_value_that_is_not_perlight", text);
}

#[test]
fn default_uses_a_varying_global() {
    let (codes, text) = run(&lines(&["surface matte(float Kd = s)", "{", "    Ci = Cs * Kd;", "}"]));
    assert_eq!(codes, ["E0607"]);
    insta::assert_snapshot!("default_uses_a_varying_global", text);
}

#[test]
fn default_uses_a_vertex_parameter() {
    let (codes, text) = run(&lines(&[
        "surface shader float4 tint(vertex float4 uv, primitive group float k = uv[0] * 2)",
        "{",
        "    return uv * k;",
        "}",
    ]));
    assert_eq!(codes, ["E0607"]);
    insta::assert_snapshot!("default_uses_a_vertex_parameter", text);
}

// ---------------------------------------------------------------------------------------------
// Known bugs: the behaviour the compiler should have. Each is described in the `ignore` reason.

/// The offset of the first occurrence of `needle` in `src`, plus `skip`.
fn offset(src: &str, needle: &str, skip: usize) -> u32 {
    (src.find(needle).unwrap_or_else(|| panic!("`{needle}` not in the source")) + skip) as u32
}

#[test]
fn rate_origin_label_points_at_the_declaration() {
    let src = lines(&[
        "surface shader float4 stripes(vertex float4 uv)",
        "{",
        "    fragment float f = uv[1];",
        "    vertex float y = f * 2;",
        "    return {y, 0, 0, 1};",
        "}",
    ]);
    let checked = check_source("shader.sl", &src, &MemoryLoader::default());
    let d = checked.diagnostics.iter().next().expect("a diagnostic");
    assert_eq!(d.code, Code::RateTooHigh);
    let declaration = offset(&src, "fragment float f", "fragment float ".len());
    assert!(
        d.labels.iter().any(|l| !l.primary && l.span.start == declaration),
        "no label at the declaration of `f`: {:?}",
        d.labels
    );
}

#[test]
fn renderman_rate_messages_say_uniform_and_varying() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    uniform float x = 0;",
        "    if (s > 0.5)",
        "        x = 1;",
        "    uniform float u = s;",
        "    Ci = Cs * x * u;",
        "}",
    ]));
    assert_eq!(codes, [Code::ControlDependence.as_str(), Code::VaryingToUniform.as_str()]);
    assert!(!text.contains("primitive group"), "{text}");
    assert!(text.contains("`x` is declared uniform but assigned under a varying condition"), "{text}");
}

#[test]
fn rate_errors_have_a_help_line() {
    for src in [
        lines(&["surface matte()", "{", "    uniform float u = s;", "    Ci = u;", "}"]),
        lines(&[
            "surface shader float4 edges(vertex float4 uv)",
            "{",
            "    vertex float d = Du(uv[0]);",
            "    return {d, 0, 0, 1};",
            "}",
        ]),
        lines(&[
            "surface matte()",
            "{",
            "    uniform float x = 0;",
            "    if (s > 0.5)",
            "        x = 1;",
            "    Ci = x;",
            "}",
        ]),
    ] {
        let checked = check_source("shader.sl", &src, &MemoryLoader::default());
        for d in checked.diagnostics.iter() {
            assert!(d.help.is_some(), "{} has no help: {}", d.code, d.message);
        }
    }
}

#[test]
fn ambiguous_call_help_fits_the_function() {
    let (codes, text) = run(&lines(&[
        "float weigh(float x, color c) { return x; }",
        "float weigh(color c, float x) { return x; }",
        "surface matte()",
        "{",
        "    Ci = weigh(1, 1);",
        "}",
    ]));
    assert_eq!(codes, [Code::AmbiguousCall.as_str()]);
    assert!(!text.contains("noise"), "{text}");
}

#[test]
fn function_called_by_two_shaders_reports_once() {
    let (codes, text) = run(&lines(&[
        "float scaled(float x) { return x * gain; }",
        "surface a() { Ci = scaled(1); }",
        "surface b() { Ci = scaled(2); }",
    ]));
    assert_eq!(codes, [Code::UnknownName.as_str()], "{text}");
}

#[test]
fn uncalled_function_is_checked() {
    let (codes, text) =
        run(&lines(&["float unused(float x) { return x * gain; }", "surface matte() { Ci = Cs; }"]));
    assert_eq!(codes, [Code::UnknownName.as_str()], "{text}");
}

#[test]
fn negative_constant_index_out_of_range() {
    let (codes, text) =
        run(&lines(&["surface matte()", "{", "    float a[3] = {1, 2, 3};", "    Ci = a[-1];", "}"]));
    assert_eq!(codes, [Code::InvalidIndex.as_str()], "{text}");
}

#[test]
fn each_uniform_output_of_a_builtin_is_reported() {
    let (codes, text) = run(&lines(&[
        "surface glass()",
        "{",
        "    uniform float kr, kt;",
        "    fresnel(I, N, 1.5, kr, kt);",
        "    Ci = kr + kt;",
        "}",
    ]));
    assert_eq!(codes, [Code::VaryingToUniform.as_str(), Code::VaryingToUniform.as_str()], "{text}");
    assert!(text.contains("`kt`"), "{text}");
}

#[test]
fn transform_with_an_unknown_space() {
    let (codes, text) = run(&lines(&[
        "surface matte()",
        "{",
        "    point p = transform(\"wrold\", P);",
        "    color c = ctransform(\"hsb\", Cs);",
        "    Ci = c;",
        "}",
    ]));
    assert_eq!(codes, ["E0518", "E0518"]);
    insta::assert_snapshot!("transform_with_an_unknown_space", text);
}

#[test]
fn per_light_value_returned_from_a_stanford_shader() {
    let (codes, text) = run(&lines(&["surface shader float4 lit()", "{", "    return Cl;", "}"]));
    assert_eq!(codes, ["E0603"]);
    assert!(text.contains("the shader returns one value"), "{text}");
    insta::assert_snapshot!("per_light_value_returned_from_a_stanford_shader", text);
}

#[test]
fn uniform_array_written_at_a_varying_index() {
    let (codes, text) = run(&lines(&[
        "surface bands()",
        "{",
        "    uniform float hits[4] = {0, 0, 0, 0};",
        "    hits[int(s * 3)] = 1;",
        "    Ci = hits[0];",
        "}",
    ]));
    assert_eq!(codes, ["E0605"]);
    assert!(text.contains("assigned at a varying index"), "{text}");
    insta::assert_snapshot!("uniform_array_written_at_a_varying_index", text);
}

#[test]
fn a_function_no_shader_calls_may_have_output_parameters() {
    // Checked on its own, it gets a variable for each output (library modules are all such
    // functions).
    let (codes, _) =
        run("void fill(output float a; output color c[]) { a = 1; c[0] = a; }\nsurface t() { Ci = 1; }\n");
    assert!(codes.is_empty(), "{codes:?}");
    let (codes, _) = run("void fill(output float a) { a = undefined_name; }\nsurface t() { Ci = 1; }\n");
    assert_eq!(codes, ["E0501"]);
}

#[test]
fn a_function_called_inside_a_conditional_may_assign_its_own_variables() {
    let (codes, _) = run(
        "float f(float x) { float y = x; y = y + 1; return y; }\nsurface t() { Ci = s < 0.5 ? f(s) : 0; }\n",
    );
    assert!(codes.is_empty(), "{codes:?}");
    // But not the caller's state: every operand is evaluated.
    let (codes, _) =
        run("float g(float x) { Ci = 1; return x; }\nsurface t() { Oi = s < 0.5 ? g(s) : 0; }\n");
    assert_eq!(codes, ["E0520"]);
    let (codes, _) = run(
        "float h(output float o) { o = 2; return o; }\nsurface t() { float k = 0; if (s > 0 && h(k) > 1) Ci = k; }\n",
    );
    assert_eq!(codes, ["E0520"]);
}

#[test]
fn texture_option_without_value() {
    let (codes, text) =
        run(&lines(&["surface s()", "{", "    Ci = environment(\"e.env\", I, \"blur\");", "}"]));
    assert_eq!(codes, ["E0522"]);
    assert!(text.contains("option `blur` of `environment` has no value"), "{text}");
}
