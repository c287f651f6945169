//! `patina::testing`: the CPU reference from a user's own tests (values at points, typed errors)
//! and the GPU against it on a small scene.

use patina::testing::{self, TestError};

fn example(path: &str) -> String {
    format!("{}/examples/{path}", env!("CARGO_MANIFEST_DIR"))
}

/// Written as a user would test their own shader: a ramp gives its texture coordinates back.
#[test]
fn a_users_ramp_shader_gives_its_coordinates_back() -> Result<(), TestError> {
    let out = testing::shade("surface ramp(float b = 0.5) { Ci = color(s, t, b); }")
        .at(&[("s", &[0.0]), ("t", &[1.0])])
        .at(&[("s", &[0.25]), ("t", &[0.75])])
        .at(&[("s", &[1.0]), ("t", &[0.125])])
        .eval::<f32>()?;
    assert_eq!(out.len(), 3);
    assert_eq!(out.get("Ci"), Some(&[0.0, 1.0, 0.5][..]));
    assert_eq!(out.point(1).unwrap().triple("Ci"), Some([0.25, 0.75, 0.5]));
    assert_eq!(out.point(2).unwrap().triple("Ci"), Some([1.0, 0.125, 0.5]));
    assert_eq!(out.column("Ci").unwrap().len(), 9);
    assert!(out.point(3).is_none());
    Ok(())
}

#[test]
fn with_no_point_the_shader_runs_once_at_its_defaults() {
    let out = testing::shade("surface c(color k = color(0.1, 0.2, 0.3)) { Ci = k; Oi = 0.5; }")
        .eval::<f64>()
        .unwrap();
    assert_eq!(out.len(), 1);
    assert_eq!(out.point(0).unwrap().triple("Ci"), Some([0.1, 0.2, 0.3]));
    assert_eq!(out.point(0).unwrap().triple("Oi"), Some([0.5, 0.5, 0.5]));
    let set = testing::shade("surface c(color k = 0) { Ci = k; }").set("k", [0.5, 0.25, 1.0]).eval::<f32>();
    assert_eq!(set.unwrap().get("Ci"), Some(&[0.5, 0.25, 1.0][..]));
}

/// plastic.sl lit by one light and an ambient light, without its specular term: Ci = Cs * (Ka *
/// Ca + Kd * Cl * cos θ), with θ the angle between the normal and the light.
#[test]
fn plastic_under_a_light_gives_the_analytic_diffuse_value() {
    let (cs, cl, ca) = ([0.9, 0.35, 0.2], [1.0, 0.5, 0.25], [0.1, 0.1, 0.2]);
    let (ka, kd) = (0.8, 0.7);
    let theta: f64 = 0.3;
    let normal = [0.0, theta.sin(), theta.cos()];
    let out = testing::shade_file(example("shaders/plastic.sl"))
        .set("Ka", ka)
        .set("Kd", kd)
        .set("Ks", 0.0)
        .set("Cs", cs)
        // The light 3 units along +z: diffuse normalizes L.
        .light([0.0, 0.0, 3.0], cl)
        .ambient(ca)
        // faceforward(N, I) turns N against Ng, which is zero unless given.
        .set("Ng", [0.0, 0.0, 1.0])
        .at(&[("N", &normal), ("I", &[0.0, 0.0, -1.0])])
        .at(&[("N", &[0.0, 0.0, 1.0]), ("I", &[0.0, 0.0, -1.0])])
        .eval::<f64>()
        .unwrap();
    for (p, cos) in [(0, theta.cos()), (1, 1.0)] {
        let ci = out.point(p).unwrap().triple("Ci").unwrap();
        for c in 0..3 {
            let expected = cs[c] * (ka * ca[c] + kd * cl[c] * cos);
            assert!((ci[c] - expected).abs() < 1e-12, "point {p} channel {c}: {ci:?}, expected {expected}");
        }
    }
    assert_eq!(out.get("Oi"), Some(&[1.0, 1.0, 1.0][..]));
}

#[test]
fn f32_and_f64_agree_on_plastic_with_its_highlight() {
    let mut points = Vec::new();
    for i in 0..40 {
        let a = f64::from(i) * 0.035;
        points.push(vec![("N", vec![a.sin() * 0.6, a.sin() * 0.8, a.cos()]), ("I", vec![0.1, -0.2, -1.0])]);
    }
    let shade = testing::shade_file(example("shaders/plastic.sl"))
        .light([1.0, 2.0, 4.0], [1.0, 0.9, 0.8])
        .light([-1.0, 0.5, 2.0], [0.3, 0.3, 0.5])
        .ambient([0.05, 0.05, 0.05])
        .set("Ng", [0.0, 0.0, 1.0])
        .points(points);
    let single = shade.eval::<f32>().unwrap();
    let double = shade.eval::<f64>().unwrap();
    let (a, b) = (single.column("Ci").unwrap(), double.column("Ci").unwrap());
    assert_eq!(a.len(), 120);
    let worst = a.iter().zip(b).map(|(x, y)| (x - y).abs() / y.abs().max(1.0)).fold(0.0, f64::max);
    assert!(worst < 2e-6, "f32 and f64 differ by {worst}");
    // The highlight is there: some point is brighter than the diffuse term alone could make it.
    assert!(b.iter().any(|x| *x > 0.6), "{double}");
}

#[test]
fn names_the_shader_does_not_declare_are_typed_errors() {
    let plastic = || testing::shade_file(example("shaders/plastic.sl"));
    match plastic().at(&[("Q", &[1.0, 2.0, 3.0])]).eval::<f32>() {
        Err(TestError::UnknownInput { shader, name }) => {
            assert_eq!((shader.as_str(), name.as_str()), ("plastic", "Q"))
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        plastic().set("Kdd", 0.5).eval::<f32>(),
        Err(TestError::UnknownInput { name, .. }) if name == "Kdd"
    ));
    // One light bound: there is no second.
    let err =
        plastic().light([0.0, 0.0, 1.0], [1.0, 1.0, 1.0]).at(&[("L[1]", &[0.0, 0.0, 1.0])]).eval::<f32>();
    assert!(matches!(err, Err(TestError::UnknownInput { name, .. }) if name == "L[1]"));
    let err = plastic().at(&[("N", &[0.0, 1.0])]).eval::<f32>().unwrap_err();
    assert!(
        matches!(err, TestError::WrongWidth { ref name, expected: 3, given: 2 } if name == "N"),
        "{err:?}"
    );
    assert_eq!(err.to_string(), "`N` takes 3 number(s); 2 given");
    let err = plastic().light([0.0, 1.0], [1.0, 1.0, 1.0]).eval::<f32>().unwrap_err();
    assert!(
        matches!(err, TestError::WrongWidth { ref name, expected: 3, given: 2 } if name == "L[0]"),
        "{err:?}"
    );
    assert!(matches!(plastic().set("Kd", "x").eval::<f32>(), Err(TestError::StringValue { .. })));
}

#[test]
fn declared_names_the_shader_never_reads_are_accepted() {
    // plastic reads neither P nor s; giving them changes nothing.
    let base = testing::shade_file(example("shaders/plastic.sl")).at(&[("N", &[0.0, 0.0, 1.0])]);
    let plain = base.clone().eval::<f32>().unwrap();
    let more = testing::shade_file(example("shaders/plastic.sl"))
        .at(&[("N", &[0.0, 0.0, 1.0]), ("P", &[1.0, 2.0, 3.0]), ("s", &[0.5])])
        .eval::<f32>()
        .unwrap();
    assert_eq!(plain.get("Ci"), more.get("Ci"));
    assert_eq!(more.get("P"), None);
}

#[test]
fn uniform_parameters_may_differ_from_point_to_point() {
    let out = testing::shade("surface k(uniform float Kd = 1) { Ci = Kd * s; }")
        .at(&[("s", &[1.0]), ("Kd", &[0.25])])
        .at(&[("s", &[2.0]), ("Kd", &[0.25])])
        .at(&[("s", &[2.0]), ("Kd", &[0.5])])
        .at(&[("s", &[2.0])])
        .eval::<f32>()
        .unwrap();
    let ci: Vec<f64> = out.points().map(|p| p.triple("Ci").unwrap()[0]).collect();
    assert_eq!(ci, [0.25, 0.5, 1.0, 2.0]);
}

#[test]
fn a_fixed_parameter_gives_what_setting_it_gives() {
    let src = "surface f(float mode = 0) { if (mode > 0.5) Ci = color(s, 0, 0); else Ci = color(0, t, 0); }";
    let point: &[(&str, &[f64])] = &[("s", &[0.75]), ("t", &[0.5])];
    let fixed = testing::shade(src).fix("mode", 1.0).at(point).eval::<f32>().unwrap();
    let set = testing::shade(src).set("mode", 1.0).at(point).eval::<f32>().unwrap();
    assert_eq!(fixed.get("Ci"), Some(&[0.75, 0.0, 0.0][..]));
    assert_eq!(fixed.get("Ci"), set.get("Ci"));
    assert!(matches!(testing::shade(src).fix("nope", 1.0).eval::<f32>(), Err(TestError::Compile(_))));
}

#[test]
fn a_syntax_error_is_diagnostics_with_its_code() {
    let err = testing::shade("surface broken() {\n  Ci = ;\n}\n").eval::<f32>().unwrap_err();
    let TestError::Diagnostics(ref d) = err else { panic!("{err:?}") };
    assert!(d.has_errors());
    let text = err.to_string();
    assert!(text.contains("error[E0") && text.contains("test.sl:2:"), "{text}");
    assert!(std::error::Error::source(&err).is_some());
}

#[test]
fn a_runaway_loop_is_reported_at_the_loop() {
    let err = testing::shade("surface s() {\n  float x = 0;\n  while (x < 1) { x += 0; }\n  Ci = x;\n}\n")
        .budget(100)
        .eval::<f32>()
        .unwrap_err();
    assert!(matches!(err, TestError::IterationBudget(_)), "{err:?}");
    let text = err.to_string();
    assert!(text.contains("error[E0702]") && text.contains("test.sl:3:3"), "{text}");
}

#[test]
fn shaders_are_picked_by_name_of_any_kind() {
    // The standard point light at the origin, seen from 2 units away: intensity / distance².
    let out = testing::shade_file(example("shaders/lights.sl"))
        .shader("pointlight")
        .set("intensity", 4.0)
        .at(&[("Ps", &[0.0, 0.0, 2.0])])
        .eval::<f64>()
        .unwrap();
    assert_eq!(out.get("Cl"), Some(&[1.0, 1.0, 1.0][..]));
    let missing = testing::shade_file(example("shaders/lights.sl")).shader("nolight").eval::<f32>();
    assert!(matches!(missing, Err(TestError::NoShader { name: Some(n), .. }) if n == "nolight"));
    let unreadable = testing::shade_file(example("shaders/no-such-file.sl")).eval::<f32>();
    assert!(matches!(unreadable, Err(TestError::Compile(_))));
}

#[test]
fn sphere_scene_of_plastic_matches_on_both_backends() {
    let scene = testing::sphere_scene(example("shaders/plastic.sl")).unwrap();
    assert_eq!((scene.output.width, scene.output.height), (64, 48));
    let Some(gpu) = patina::runtime::gpu::for_tests() else { return };
    let result = testing::compare_backends(&scene, gpu).unwrap();
    assert!(result.passes, "GPU and CPU differ: {:?}", result.comparison);
    assert_eq!(result.thresholds, patina::runtime::image::Thresholds::default());
    // The sphere is lit: the centre pixel is far brighter than the background.
    let centre = result.cpu.get(32, 24).unwrap();
    assert!(centre[0] > 0.2, "{centre:?}");
    assert_eq!(result.comparison.pixels, 64 * 48);
    let err = testing::compare_backends_file(example("scenes/no-such-scene.toml"), gpu).unwrap_err();
    assert!(matches!(err, TestError::Scene(_)), "{err:?}");
}
