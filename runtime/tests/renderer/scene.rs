//! Scene files: the fixtures under tests/scenes, and one test per class of error with the exact
//! line, column and field of its message.

use glam::{Mat4, Vec3};
use patina_runtime::render::RenderError;
use patina_runtime::scene::{
    Assignment, KnobKind, MeshSource, ParamValue, Reference, Scene, SceneErrorKind, Setting, TransformStep,
};
use std::f32::consts::FRAC_PI_6;
use std::path::{Path, PathBuf};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes").join(name)
}

const CAMERA: &str = "[camera]\nfrom = [0, 0, -5]\nto = [0, 0, 0]\n";
const OBJECT: &str = "[[object]]\nmesh = \"cube\"\nshader = \"a.sl\"\n";

/// The one-line message for a bad scene text.
fn error(text: &str) -> String {
    Scene::parse(text, "scenes/bad.toml", "scenes").unwrap_err().to_string()
}

#[test]
fn the_full_example_reads_every_field() {
    let scene = Scene::load(fixture("spheres.toml")).unwrap();
    let dir = fixture("");
    assert_eq!((scene.output.width, scene.output.height, scene.output.supersample), (320, 240, 2));
    assert_eq!(scene.output.background, [0.1, 0.1, 0.15, 1.0], "RGB gets an opaque alpha");
    let camera = scene.camera();
    assert_eq!((camera.from, camera.to, camera.up), (Vec3::new(0.0, 1.0, -5.0), Vec3::ZERO, Vec3::Y));
    assert_eq!((camera.fov_y_degrees, camera.near, camera.far), (40.0, 0.1, 100.0));

    assert_eq!(scene.lights.len(), 2);
    let point = &scene.lights[1];
    assert_eq!(point.shader.path, dir.join("../../../shaders/lights.sl"));
    assert_eq!(point.shader.name.as_deref(), Some("pointlight"));
    assert_eq!(point.shader.params["intensity"], ParamValue::Number(20.0));
    assert_eq!(point.shader.params["from"], ParamValue::Numbers(vec![2.0, 3.0, -4.0]));
    assert_eq!(point.line, 23);

    let [plastic, wood, floor] = &scene.objects[..] else { panic!("three objects") };
    assert_eq!((plastic.mesh.clone(), plastic.detail, plastic.line), (MeshSource::Sphere, 48, 28));
    assert_eq!(plastic.surface.params["specularcolor"], ParamValue::Numbers(vec![1.0; 3]));
    assert_eq!(plastic.color, [1.0, 0.5, 0.2]);
    assert_eq!(plastic.opacity, [1.0; 3], "the default Os");
    assert_eq!(wood.detail, patina_runtime::scene::DEFAULT_DETAIL);
    assert_eq!(wood.color, [1.0; 3], "the default Cs");
    assert_eq!(wood.surface.name, None);
    assert_eq!(wood.surface.params["texturename"], ParamValue::String("wood.png".into()));
    assert_eq!(wood.surface.params["twosided"], ParamValue::Bool(true));
    assert_eq!(wood.surface.params["ringscale"].as_number(), Some(10.0), "integers are numbers");
    let bumpy = wood.displacement.as_ref().unwrap();
    assert_eq!(bumpy.path, dir.join("../../../shaders/bumpy.sl"));
    assert_eq!(bumpy.params["Km"], ParamValue::Number(0.05));
    assert_eq!(floor.transform.len(), 3);
    assert_eq!(floor.transform[1], TransformStep::Rotate { angle: 90.0, axis: [1.0, 0.0, 0.0] });

    let [rings, antialias] = &scene.knobs[..] else { panic!("two knobs: {:?}", scene.knobs) };
    assert_eq!((rings.name.as_str(), rings.kind), ("ringscale", KnobKind::Samples));
    let ring = |value: f64| Assignment::Param { name: "ringscale".into(), object: Some(1), value };
    let labels: Vec<&str> = rings.settings.iter().map(|s| s.label.as_str()).collect();
    assert_eq!(labels, ["2", "4", "8", "16"]);
    assert_eq!(rings.settings[3].assignments, [ring(16.0)]);
    assert_eq!(
        rings.reference,
        Reference::Setting(Setting { label: "64".into(), assignments: vec![ring(64.0)] })
    );
    // A one-parameter knob takes any value; a knob of settings only its own labels.
    assert_eq!(rings.setting("5").unwrap().assignments, [ring(5.0)]);
    assert_eq!(rings.setting("lots"), None);
    assert_eq!(antialias.settings[1].assignments[0], Assignment::Supersample(2));
    assert_eq!(antialias.setting("5"), None);
    assert_eq!(
        antialias.reference,
        Reference::Scene { path: dir.join("teapot.toml"), label: "exact".into() }
    );
    // Without `object`, a setting reaches the objects whose `params` set the parameter.
    let supersampled = scene.with_setting(&antialias.settings[1]);
    assert_eq!(supersampled.output.supersample, 2);
    assert_eq!(supersampled.objects[1].surface.params["ringscale"], ParamValue::Number(10.0));
    assert!(!supersampled.objects[0].surface.params.contains_key("ringscale"));
    let fine = scene.with_setting(rings.setting("32").as_ref().unwrap());
    assert_eq!(fine.objects[1].surface.params["ringscale"], ParamValue::Number(32.0));
}

#[test]
fn transformations_concatenate_like_renderman() {
    let scene = Scene::load(fixture("spheres.toml")).unwrap();
    // translate [-1.2, 0, 0], then rotate 90° about x: the rotation acts on the object first.
    let m = scene.object_transform(0);
    assert!(m.transform_point3(Vec3::ZERO).abs_diff_eq(Vec3::new(-1.2, 0.0, 0.0), 1e-6));
    assert!(m.transform_point3(Vec3::Z).abs_diff_eq(Vec3::new(-1.2, -1.0, 0.0), 1e-6), "+z turns to -y");
    // The floor: scaled by 5, turned to face +y, lowered to y = -1.
    let floor = scene.object_transform(2);
    assert!(floor.transform_point3(Vec3::new(1.0, 0.0, 0.0)).abs_diff_eq(Vec3::new(5.0, -1.0, 0.0), 1e-5));
    assert!(
        floor.transform_vector3(Vec3::NEG_Z).normalize().abs_diff_eq(Vec3::Y, 1e-6),
        "the plane faces up"
    );
    assert_eq!(scene.object_transform(99), Mat4::IDENTITY);
}

#[test]
fn every_mesh_kind_builds() {
    for kind in
        [MeshSource::Sphere, MeshSource::Torus, MeshSource::Plane, MeshSource::Cube, MeshSource::Teapot]
    {
        let mesh = kind.build(16).unwrap();
        mesh.validate().unwrap();
        assert!(mesh.triangle_count() > 0, "{kind:?}");
    }
    let scene = Scene::load(fixture("obj.toml")).unwrap();
    let object = &scene.objects[0];
    assert_eq!(object.mesh, MeshSource::Obj(fixture("models/quad.obj")));
    assert_eq!(object.build_mesh().unwrap().triangle_count(), 2);
}

#[test]
fn defaults_fill_a_minimal_scene() {
    let scene = Scene::load(fixture("teapot.toml")).unwrap();
    assert_eq!((scene.output.width, scene.output.height), (256, 256));
    assert_eq!(scene.output.background, [0.0, 0.0, 0.0, 1.0]);
    assert_eq!(scene.output.supersample, 1);
    assert_eq!((scene.camera.fov_y_degrees, scene.camera.near, scene.camera.far), (40.0, 0.1, 100.0));
    assert!(scene.lights.is_empty() && scene.knobs.is_empty());
    assert_eq!(scene.objects[0].surface.path, fixture("shaders/checker.sl"));
    assert_eq!(scene.objects[0].mesh, MeshSource::Teapot);
}

#[test]
fn paths_resolve_against_the_given_directory() {
    let text = format!(
        "{CAMERA}[[light]]\nshader = \"l.sl\"\n\
         [[object]]\nmesh = {{ obj = \"m/x.obj\" }}\nshader = \"/abs/s.sl\"\n"
    );
    let scene = Scene::parse(&text, "inline", "some/dir").unwrap();
    assert_eq!(scene.lights[0].shader.path, Path::new("some/dir/l.sl"));
    assert_eq!(scene.objects[0].mesh, MeshSource::Obj("some/dir/m/x.obj".into()));
    assert_eq!(scene.objects[0].surface.path, Path::new("/abs/s.sl"));
}

#[test]
fn a_bad_fixture_names_its_file_line_and_field() {
    let path = fixture("bad_fov.toml");
    let e = Scene::load(&path).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("{}:6:7: camera.fov: expected a number, found a string", path.display())
    );
    assert_eq!(
        (e.kind, e.position, e.field.as_deref()),
        (SceneErrorKind::Schema, Some((6, 7)), Some("camera.fov"))
    );
}

#[test]
fn a_missing_file_says_so() {
    let e = Scene::load("scenes/x.toml").unwrap_err();
    assert_eq!(e.to_string(), "cannot read scenes/x.toml: No such file or directory");
    assert_eq!(e.kind, SceneErrorKind::Read);
}

#[test]
fn syntax_errors() {
    assert_eq!(
        error("[camera]\nfrom = [0, 0, -5]\nfov = = 40\n"),
        "scenes/bad.toml:3:7: camera.fov: invalid TOML: extra `=`, expected nothing"
    );
    assert_eq!(
        error("[camera]\nfrom = [0, 0, -5]\nfrom = [1, 2, 3]\n"),
        "scenes/bad.toml:3:1: camera.from: invalid TOML: duplicate key"
    );
}

#[test]
fn wrong_types() {
    assert_eq!(
        error("[camera]\nfrom = [0, 0, -5]\nto = [0, 0, 0]\nfov = \"wide\"\n"),
        "scenes/bad.toml:4:7: camera.fov: expected a number, found a string"
    );
    assert_eq!(
        error("[camera]\nfrom = [0, 0]\nto = [0, 0, 0]\n"),
        "scenes/bad.toml:2:8: camera.from: expected an array of 3 numbers, found 2 elements"
    );
    assert_eq!(
        error(&format!("[output]\nwidth = 2.5\n{CAMERA}")),
        "scenes/bad.toml:2:9: output.width: expected an integer, found the number 2.5"
    );
    assert_eq!(error("camera = 3\n"), "scenes/bad.toml:1:10: camera: expected a table, found the integer 3");
    assert_eq!(
        error(&format!("{CAMERA}{OBJECT}transform = {{ scale = [1, 1, 1] }}\n")),
        "scenes/bad.toml:7:13: object[0].transform: expected an array, found a table"
    );
}

#[test]
fn unknown_fields_list_the_allowed_ones() {
    assert_eq!(
        error(&format!("{CAMERA}fovy = 3\n")),
        "scenes/bad.toml:4:1: camera.fovy: unknown field `fovy`; allowed fields: from, to, up, fov, near, far"
    );
    // The list goes on with the tables added since (atmosphere, imager, ...).
    let e = error(&format!("[camra]\nfov = 3\n{CAMERA}"));
    assert!(
        e.starts_with(
            "scenes/bad.toml:1:2: camra: unknown field `camra`; allowed fields: output, camera, light, \
             object, knob, shadow, compare"
        ),
        "{e}"
    );
    assert_eq!(
        error(&format!("{CAMERA}{OBJECT}{OBJECT}colour = [1, 1, 1]\n")),
        "scenes/bad.toml:10:1: object[1].colour: unknown field `colour`; allowed fields: mesh, detail, \
         shader, \
         name, params, animate, displacement, atmosphere, color, opacity, transform"
    );
    assert_eq!(
        error(&format!("{CAMERA}{OBJECT}transform = [{{ rotate = {{ angle = 1, axes = [1, 2, 3] }} }}]\n")),
        "scenes/bad.toml:7:38: object[0].transform[0].rotate.axes: unknown field `axes`; allowed fields: \
         angle, axis"
    );
}

#[test]
fn missing_fields() {
    assert_eq!(error("[camera]\nto = [0, 0, 0]\n"), "scenes/bad.toml:1:1: camera: missing field `from`");
    assert_eq!(error("[output]\nwidth = 3\n"), "scenes/bad.toml: the scene has no [camera] table");
    assert_eq!(
        error(&format!("{CAMERA}[[object]]\nmesh = \"cube\"\n")),
        "scenes/bad.toml:4:1: object[0]: missing field `shader`"
    );
    assert_eq!(
        error(&format!("{CAMERA}{OBJECT}transform = [{{ rotate = {{ angle = 1 }} }}]\n")),
        "scenes/bad.toml:7:25: object[0].transform[0].rotate: missing field `axis`"
    );
}

#[test]
fn meshes_and_transformations() {
    assert_eq!(
        error(&format!("{CAMERA}[[object]]\nmesh = \"sphear\"\nshader = \"a.sl\"\n")),
        "scenes/bad.toml:5:8: object[0].mesh: unknown mesh kind `sphear`; expected one of sphere, torus, \
         plane, \
         cube, teapot, or { obj = \"file.obj\" }"
    );
    assert_eq!(
        error(&format!("{CAMERA}[[object]]\nmesh = {{ file = \"a.obj\" }}\nshader = \"a.sl\"\n")),
        "scenes/bad.toml:5:10: object[0].mesh.file: unknown field `file`; allowed fields: obj"
    );
    assert_eq!(
        error(&format!("{CAMERA}[[object]]\nmesh = {{ obj = \" \" }}\nshader = \"a.sl\"\n")),
        "scenes/bad.toml:5:16: object[0].mesh.obj: the OBJ file path is empty"
    );
    assert_eq!(
        error(&format!(
            "{CAMERA}{OBJECT}transform = [{{ scale = [1, 1, 1] }}, {{ translat = [1, 2, 3] }}]\n"
        )),
        "scenes/bad.toml:7:39: object[0].transform[1].translat: unknown transformation `translat`; expected \
         translate, rotate, scale"
    );
    assert_eq!(
        error(&format!("{CAMERA}{OBJECT}transform = [{{ scale = [1, 1, 1], translate = [1, 2, 3] }}]\n")),
        "scenes/bad.toml:7:14: object[0].transform[0]: expected a table with exactly one key, e.g. \
         { translate = [0, 1, 0] }"
    );
    assert_eq!(
        error(&format!("{CAMERA}{OBJECT}transform = [{{ rotate = {{ angle = 30, axis = [0, 0, 0] }} }}]\n")),
        "scenes/bad.toml:7:46: object[0].transform[0].rotate.axis: the rotation axis must not be zero"
    );
    assert_eq!(
        error(&format!("{CAMERA}{OBJECT}detail = 0\n")),
        "scenes/bad.toml:7:10: object[0].detail: must be between 1 and 1024, found 0"
    );
}

#[test]
fn parameter_values() {
    assert_eq!(
        error(&format!("{CAMERA}{OBJECT}params = {{ Kd = {{ x = 1 }} }}\n")),
        "scenes/bad.toml:7:17: object[0].params.Kd: expected a number, an array of numbers, a string or a \
         boolean, found a table"
    );
    assert_eq!(
        error(&format!("{CAMERA}{OBJECT}params = {{ from = [1, \"a\", 3] }}\n")),
        "scenes/bad.toml:7:23: object[0].params.from[1]: expected a number, found a string"
    );
}

#[test]
fn output_ranges() {
    assert_eq!(
        error(&format!("[output]\nwidth = 0\n{CAMERA}")),
        "scenes/bad.toml:2:9: output.width: must be between 1 and 16384, found 0"
    );
    assert_eq!(
        error(&format!("[output]\nheight = 16385\n{CAMERA}")),
        "scenes/bad.toml:2:10: output.height: must be between 1 and 16384, found 16385"
    );
    assert_eq!(
        error(&format!("[output]\nwidth = -5\n{CAMERA}")),
        "scenes/bad.toml:2:9: output.width: must be between 1 and 16384, found -5"
    );
    assert_eq!(
        error(&format!("[output]\nsupersample = 0\n{CAMERA}")),
        "scenes/bad.toml:2:15: output.supersample: must be between 1 and 16, found 0"
    );
    assert_eq!(
        error(&format!("[output]\nbackground = [1, 1]\n{CAMERA}")),
        "scenes/bad.toml:2:14: output.background: expected 3 or 4 numbers (RGB or RGBA), found 2"
    );
}

#[test]
fn camera_checks() {
    assert_eq!(
        error(&format!("{CAMERA}fov = 180\n")),
        "scenes/bad.toml:4:7: camera.fov: must be between 0 and 180 degrees (exclusive), found 180"
    );
    assert_eq!(
        error(&format!("{CAMERA}fov = -10\n")),
        "scenes/bad.toml:4:7: camera.fov: must be between 0 and 180 degrees (exclusive), found -10"
    );
    assert_eq!(
        error(&format!("{CAMERA}near = 0\n")),
        "scenes/bad.toml:4:8: camera.near: must be greater than 0, found 0"
    );
    assert_eq!(
        error(&format!("{CAMERA}near = 1\nfar = 0.5\n")),
        "scenes/bad.toml:5:7: camera.far: must be greater than camera.near (1), found 0.5"
    );
    assert_eq!(
        error(&format!("{CAMERA}near = 200\n")),
        "scenes/bad.toml:4:8: camera.near: must be less than camera.far (100 by default), found 200"
    );
    assert_eq!(
        error("[camera]\nfrom = [1, 2, 3]\nto = [1, 2, 3]\n"),
        "scenes/bad.toml:3:6: camera.to: must differ from camera.from (the camera would look nowhere)"
    );
    assert_eq!(
        error(&format!("{CAMERA}up = [0, 0, 2]\n")),
        "scenes/bad.toml:4:6: camera.up: must not be zero or parallel to the viewing direction"
    );
    assert_eq!(
        error("[camera]\nfrom = [0, nan, -5]\nto = [0, 0, 0]\n"),
        "scenes/bad.toml:2:8: camera.from: values must be finite numbers"
    );
}

#[test]
fn shader_paths_and_names() {
    assert_eq!(
        error(&format!("{CAMERA}[[light]]\nshader = \"l.sl\"\n[[light]]\nshader = \"\"\n")),
        "scenes/bad.toml:7:10: light[1].shader: the shader path is empty"
    );
    assert_eq!(
        error(&format!("{CAMERA}[[object]]\nmesh = \"cube\"\nshader = \"  \"\n")),
        "scenes/bad.toml:6:10: object[0].shader: the shader path is empty"
    );
    assert_eq!(
        error(&format!("{CAMERA}{OBJECT}displacement = {{ shader = \"\" }}\n")),
        "scenes/bad.toml:7:27: object[0].displacement.shader: the shader path is empty"
    );
    assert_eq!(
        error(&format!("{CAMERA}[[light]]\nshader = \"l.sl\"\nname = \"\"\n")),
        "scenes/bad.toml:6:8: light[0].name: the shader name is empty (leave `name` out instead)"
    );
}

#[test]
fn knob_checks() {
    let knob = |body: &str| error(&format!("{CAMERA}{OBJECT}params = {{ steps = 4 }}\n[[knob]]\n{body}"));
    assert_eq!(
        knob("kind = \"steps\"\nparam = \"steps\"\nvalues = []\nreference = 3\n"),
        "scenes/bad.toml:11:10: knob[0].values: at least one setting is needed"
    );
    assert_eq!(
        knob("kind = \"steps\"\nparam = \"steps\"\nobject = 1\nvalues = [1]\nreference = 3\n"),
        "scenes/bad.toml:11:10: knob[0].object: there is no object 1 (the scene has 1, numbered from 0)"
    );
    assert_eq!(
        knob("kind = \"steps\"\nparam = \"steps\"\nvalues = [1]\n"),
        "scenes/bad.toml:8:1: knob[0]: missing field `reference`"
    );
    assert_eq!(
        knob("kind = \"stepz\"\nparam = \"steps\"\nvalues = [1]\nreference = 3\n"),
        "scenes/bad.toml:9:8: knob[0].kind: unknown kind `stepz`; expected steps, step_size, octaves, samples, \
         antialias, table_size, step_phase, early_termination, shadow, noise"
    );
    assert_eq!(
        knob("kind = \"steps\"\nparam = \"stride\"\nvalues = [1]\nreference = 3\n"),
        "scenes/bad.toml:11:10: knob[0].values: no object's `params` set `stride` (set it on the objects the \
         knob varies, or give `object`)"
    );
    assert_eq!(
        knob(
            "kind = \"samples\"\nname = \"aa\"\nsettings = [{ label = \"x\", set = { \"output.supersample\" = 40 } }]\nreference = 1\n"
        ),
        "scenes/bad.toml:11:59: knob[0].settings[0].set.output.supersample: output.supersample is a whole \
         number in 1..=16"
    );
    assert_eq!(
        knob(
            "kind = \"samples\"\nname = \"aa\"\nsettings = [{ label = \"x\", set = { steps = 2 } }]\nreference = 1\n"
        ),
        "scenes/bad.toml:12:13: knob[0].reference: a knob with `settings` names its reference as a setting"
    );
    assert_eq!(
        knob(
            "kind = \"steps\"\nparam = \"steps\"\nsettings = [{ label = \"x\", set = { steps = 2 } }]\nreference = 1\n"
        ),
        "scenes/bad.toml:8:1: knob[0]: give either `param` with its `values`, or `settings`"
    );
}

#[test]
fn compare_sets_the_scenes_thresholds_with_a_reason() {
    let parse = |body: &str| Scene::parse(&format!("{CAMERA}{OBJECT}[compare]\n{body}"), "s.toml", ".");
    let scene = parse("hard_fail = 0.5\nreason = \"silhouettes\"\n").unwrap();
    let t = scene.thresholds();
    assert_eq!((t.fail, t.hard_fail, t.max_failing_fraction), (0.004, 0.5, 0.02));
    assert_eq!(scene.compare.unwrap().reason, "silhouettes");
    let plain = Scene::parse(&format!("{CAMERA}{OBJECT}"), "s.toml", ".").unwrap();
    assert_eq!(plain.thresholds(), patina_runtime::image::Thresholds::default());
    let compare = |body: &str| error(&format!("{CAMERA}{OBJECT}[compare]\n{body}"));
    assert_eq!(compare("hard_fail = 0.5\n"), "scenes/bad.toml:7:1: compare: missing field `reason`");
    assert_eq!(
        compare("hard_fail = 0.5\nreason = \" \"\n"),
        "scenes/bad.toml:9:10: compare.reason: say why the images may differ this much"
    );
    assert_eq!(
        compare("fail = -1\nreason = \"x\"\n"),
        "scenes/bad.toml:8:8: compare.fail: must be a finite number, at least 0"
    );
    assert_eq!(
        compare("max_failing_fraction = 2\nreason = \"x\"\n"),
        "scenes/bad.toml:8:24: compare.max_failing_fraction: must be a fraction, at most 1"
    );
}

#[test]
fn the_documented_example_is_a_valid_scene() {
    let source = include_str!("../../src/scene/mod.rs");
    let doc: Vec<&str> =
        source.lines().filter_map(|l| l.strip_prefix("//!")).map(|l| l.trim_start_matches(' ')).collect();
    let start = doc.iter().position(|l| *l == "```toml").unwrap() + 1;
    let end = start + doc[start..].iter().position(|l| *l == "```").unwrap();
    let text = doc[start..end].join("\n");
    let scene = Scene::parse(&text, "module documentation", ".").unwrap();
    assert_eq!((scene.lights.len(), scene.objects.len()), (2, 1));
    assert_eq!(scene.lights[0].position, None);
    assert_eq!(scene.lights[1].position, Some(Vec3::new(2.0, 3.0, -4.0)));
    let m = scene.object_transform(0);
    assert!(
        m.transform_point3(Vec3::X)
            .abs_diff_eq(Vec3::new(2.0 * FRAC_PI_6.cos(), 0.0, 1.0 - 2.0 * FRAC_PI_6.sin()), 1e-3)
    );
}

#[test]
fn a_shader_can_be_a_standard_library_module() {
    let text =
        format!("{CAMERA}[[object]]\nmesh = \"sphere\"\nshader = \"<shaders.sl>\"\nname = \"plastic\"\n");
    let scene = Scene::parse(&text, "scenes/lib.toml", "scenes").unwrap();
    assert_eq!(scene.objects[0].surface.path, Path::new("<stdlib>/shaders.sl"));
    let text = format!("{CAMERA}[[object]]\nmesh = \"sphere\"\nshader = \"<shader.sl>\"\n");
    let message = Scene::parse(&text, "scenes/bad.toml", "scenes").unwrap_err().to_string();
    assert!(
        message.starts_with("scenes/bad.toml:6:10: object[0].shader: no standard-library module `shader.sl`"),
        "{message}"
    );
    assert!(message.contains("shaders.sl") && !message.contains('\n'), "{message}");
}

#[test]
fn the_bench_and_reference_scenes_load_and_their_knobs_resolve() {
    // examples/scenes/bench/ (the receding planes of docs/error-vs-time.md) and
    // examples/scenes/reference/ (the exact references) are not gallery scenes; they must still
    // load, and each bench knob's settings and reference must apply to the scene.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/scenes");
    for dir in ["bench", "reference"] {
        let mut count = 0;
        for entry in std::fs::read_dir(root.join(dir)).unwrap() {
            let path = entry.unwrap().path();
            let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
            count += 1;
            if dir == "bench" {
                assert!(!scene.knobs.is_empty(), "{} declares no knob", path.display());
                for knob in &scene.knobs {
                    for setting in &knob.settings {
                        let _ = scene.with_setting(setting);
                    }
                    // The planes' reference is 16 x 16 supersampling of the point-sampled texture.
                    let Reference::Setting(s) = &knob.reference else {
                        panic!("{}: a setting", path.display())
                    };
                    assert_eq!(scene.with_setting(s).output.supersample, 16, "{}", path.display());
                }
            }
        }
        assert!(count >= 2, "{dir}: {count} scenes");
    }
}

/// Issue 24: a scene's `include` list (relative to the scene) is searched by every shader's
/// `#include` (a quoted one looks beside the including file first); an empty entry is a one-line
/// error.
#[test]
fn a_scenes_include_list_is_searched_by_its_shaders() {
    let dir = std::env::temp_dir().join(format!("patina-scene-include-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("shaders")).unwrap();
    std::fs::create_dir_all(dir.join("lib")).unwrap();
    std::fs::write(dir.join("lib/tint.h"), "color tint() { return color(1, 0.5, 0.25); }\n").unwrap();
    std::fs::write(dir.join("shaders/s.sl"), "#include <tint.h>\nsurface s() { Ci = tint(); }\n").unwrap();
    let text = |include: &str| {
        format!(
            "{include}[output]\nwidth = 8\nheight = 8\n[camera]\nfrom = [0, 0, -3]\nto = [0, 0, 0]\n\
             [[object]]\nmesh = \"sphere\"\nshader = \"shaders/s.sl\"\n"
        )
    };
    let file = dir.join("scene.toml");
    let without = Scene::parse(&text(""), &file, &dir).unwrap();
    let e =
        patina_runtime::render::prepare(&without).err().expect("tint.h is not beside the shader").to_string();
    assert!(e.contains("cannot find `tint.h`"), "{e}");
    let with = Scene::parse(&text("include = [\"lib\"]\n"), &file, &dir).unwrap();
    assert_eq!(with.objects[0].surface.include_dirs, [dir.join("lib")]);
    let prepared = patina_runtime::render::prepare(&with).unwrap_or_else(|e| panic!("{e}"));
    let image =
        patina_runtime::render::render(&prepared, patina_runtime::render::Backend::Cpu, None).unwrap();
    assert_eq!(image.pixels[(4 * 8 + 4) as usize], [1.0, 0.5, 0.25, 1.0]);
    let e = Scene::parse(&text("include = [\" \"]\n"), &file, &dir).unwrap_err().to_string();
    assert!(e.contains("include[0]") && e.contains("empty") && !e.contains('\n'), "{e}");
}

/// Issue 23: `position` places a Stanford-style light, whose shader computes only its colour. A
/// bad value is an error at the field; rendering requires it of a Stanford light and refuses it
/// beside a RenderMan light's own parameters, each in one line naming the light's header.
#[test]
fn a_stanford_light_is_placed_by_its_position() {
    let light = "[[light]]\nshader = \"l.sl\"\n";
    assert_eq!(
        error(&format!("{CAMERA}{light}position = [1, nan, 2]\n")),
        "scenes/bad.toml:6:12: light[0].position: values must be finite numbers"
    );
    assert_eq!(
        error(&format!("{CAMERA}{light}position = [1, 2]\n")),
        "scenes/bad.toml:6:12: light[0].position: expected an array of 3 numbers, found 2 elements"
    );
    let dir = std::env::temp_dir().join(format!("patina-scene-position-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("falloff.sl"),
        "light shader float4 falloff_light(float4 lightcolor) { return lightcolor * (1.0 / Sdist); }\n\
         surface shader float4 lit() { perlight float4 c = Cl * max(dot(N, L), 0); return integrate(c); }\n",
    )
    .unwrap();
    let file = dir.join("scene.toml");
    let prepared = |light: &str| {
        let text = format!(
            "[output]\nwidth = 8\nheight = 8\n{CAMERA}{light}\
             [[object]]\nmesh = \"sphere\"\nshader = \"falloff.sl\"\nname = \"lit\"\n"
        );
        let scene = Scene::parse(&text, &file, &dir).unwrap_or_else(|e| panic!("{e}"));
        patina_runtime::render::prepare(&scene).map(drop).map_err(|e| e.to_string())
    };
    let stanford = "[[light]]\nshader = \"falloff.sl\"\nname = \"falloff_light\"\n";
    assert_eq!(
        prepared(stanford),
        Err(format!(
            "{}:7: light[0]: `falloff_light` is a Stanford-style light shader, which the scene places: \
             add its world-space position, e.g. `position = [0, 2, -3]`",
            file.display()
        ))
    );
    assert_eq!(prepared(&format!("{stanford}position = [0, 2, -3]\n")), Ok(()));
    let renderman = "[[light]]\nshader = \"<shaders.sl>\"\nname = \"pointlight\"\nposition = [0, 2, -3]\n";
    assert_eq!(
        prepared(renderman),
        Err(format!(
            "{}:7: light[0].position: `pointlight` is a RenderMan-style light shader, which takes its \
             position from its parameters (e.g. `from`): remove `position`",
            file.display()
        ))
    );
}

/// Issue 23: a shader's diagnostics reach the caller of `render::prepare` whole, whether the check
/// found them or a backend refused the checked shader: the code, the place in the file, and the
/// text a terminal shows.
#[test]
fn a_shaders_diagnostics_keep_their_codes_and_places_through_the_renderer() {
    let dir = std::env::temp_dir().join(format!("patina-scene-diagnostics-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("scene.toml");
    let prepare = |source: &str, params: &str| {
        std::fs::write(dir.join("s.sl"), source).unwrap();
        let text = format!(
            "[output]\nwidth = 8\nheight = 8\n[camera]\nfrom = [0, 0, -3]\nto = [0, 0, 0]\n\
             [[object]]\nmesh = \"sphere\"\nshader = \"s.sl\"\n{params}"
        );
        let scene = Scene::parse(&text, &file, &dir).unwrap_or_else(|e| panic!("{e}"));
        match patina_runtime::render::prepare(&scene) {
            Err(RenderError::Shader(d)) => (d, true),
            Err(RenderError::Refused(d)) => (d, false),
            Err(other) => panic!("not a shader's diagnostics: {other:?}"),
            Ok(_) => panic!("prepared"),
        }
    };
    // The check's error, shown whole.
    let (d, checked) = prepare("surface s() {\n    Ci = undefined_thing;\n}\n", "");
    assert!(checked);
    assert_eq!(d.diagnostics.len(), 1);
    assert_eq!(d.diagnostics[0].code.as_str(), "E0501");
    assert_eq!(d.sources.text(d.diagnostics[0].primary_span()), "undefined_thing");
    let shown = d.to_string();
    assert!(shown.contains("error[E0501]") && shown.contains("s.sl:2:10"), "{shown}");
    // A backend's refusal of a shader that checks (a spline basis named by the scene): its code
    // and place kept, shown in one line.
    let (d, checked) = prepare(
        "surface s(string basis = \"bezier\") {\n    Ci = spline(basis, s, 0, 1, 2, 3);\n}\n",
        "params = { basis = \"cardinal\" }\n",
    );
    assert!(!checked);
    assert_eq!(d.diagnostics.len(), 1);
    assert_eq!(d.diagnostics[0].code.as_str(), "E0701", "{d}");
    assert!(d.sources.text(d.diagnostics[0].primary_span()).starts_with("spline("), "{d}");
    assert!(d.to_string().contains("s.sl:2:"), "{d}");
    let line = RenderError::Refused(d.clone()).to_string();
    assert!(line.starts_with("E0701: ") && !line.contains('\n'), "{line}");
}
