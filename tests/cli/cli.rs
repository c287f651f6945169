//! The `patina` command line as a user meets it: exit codes, one-line errors for bad files, the
//! human and JSON diagnostic formats.

use std::path::PathBuf;
use std::process::Command;

use crate::support::patina;

fn scratch(name: &str, contents: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("patina-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, contents).expect("write scratch file");
    path
}

fn example(name: &str) -> String {
    format!("{}/examples/shaders/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn clean_files_pass_silently() {
    let out = patina(&["check", &example("plastic.sl"), &example("aniso.sl"), &example("bricks.sl")]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.stderr.is_empty() && out.stdout.is_empty());
}

#[test]
fn errors_are_rendered_and_fail_the_run() {
    let bad = scratch("bad.sl", b"surface s() {\n  x = 1\n  y = 2;\n}\n");
    let out = patina(&["check", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.contains("error[E0303]: expected `;`, found `y`"), "{stderr}");
    assert!(stderr.contains("bad.sl:2:8"), "{stderr}");
    assert!(stderr.contains("failed: 1 error, 0 warnings in 1 file"), "{stderr}");
    assert!(!stderr.contains("\x1b["), "no colour when piped");
}

#[test]
fn warnings_alone_do_not_fail() {
    let warn = scratch("warn.sl", b"#define A 1\n#define A 2\nfloat x;\n");
    let out = patina(&["check", warn.to_str().unwrap()]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("warning[E0214]"));
}

#[test]
fn json_format_gives_one_object_per_line() {
    let bad = scratch("json.sl", b"surface s() { x = 1; color y = trace(P, N); }\n");
    let out = patina(&["check", "--format", "json", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<serde_json::Value> =
        stdout.lines().map(|l| serde_json::from_str(l).expect("each line is JSON")).collect();
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[0]["code"], "E0501");
    assert_eq!(lines[0]["location"]["line"], 1);
    assert_eq!(lines[0]["location"]["column"], 15);
    assert_eq!(lines[1]["code"], "E0401");
    assert_eq!(lines[1]["labels"][0]["primary"], true);
}

#[test]
fn missing_unreadable_and_binary_files_get_one_line() {
    let out = patina(&["check", "/definitely/not/here.sl"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("error: cannot read `/definitely/not/here.sl`"), "{stderr}");

    let binary = scratch("binary.sl", &[b's', 0xff, 0x00, b'\n']);
    let out = patina(&["check", binary.to_str().unwrap()]);
    assert!(!out.status.success());
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("not a text file (a NUL byte at offset 2)"), "{stderr}");

    let dir = std::env::temp_dir();
    let out = patina(&["check", dir.to_str().unwrap()]);
    assert!(!out.status.success());
    assert_eq!(String::from_utf8(out.stderr).unwrap().lines().count(), 1);
}

#[test]
fn include_directories_are_searched() {
    let lib = scratch("mylib.sl", b"float helper(float x) { return x; }\n");
    let main = scratch("uses_lib.sl", b"#include <mylib.sl>\nsurface s() { Ci = helper(1); }\n");
    let dir = lib.parent().unwrap().to_str().unwrap().to_string();
    let out = patina(&["check", main.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "angle includes do not search the includer's directory");
    let out = patina(&["check", "-I", &dir, main.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn render_searches_the_command_line_include_directories() {
    let shader = scratch("uses_renderlib.sl", b"#include <renderlib.sl>\nsurface s() { Ci = tint(); }\n");
    // The library is in a folder of its own, which only -I names.
    let lib = shader.with_file_name("renderlib").join("renderlib.sl");
    std::fs::create_dir_all(lib.parent().unwrap()).unwrap();
    std::fs::write(&lib, b"color tint() { return color(1, 0.5, 0.25); }\n").unwrap();
    let scene = scratch(
        "includes.toml",
        format!(
            "[output]\nwidth = 8\nheight = 8\n[camera]\nfrom = [0, 0, -3]\nto = [0, 0, 0]\n\
             [[object]]\nmesh = \"sphere\"\nshader = \"{}\"\n",
            shader.display()
        )
        .as_bytes(),
    );
    let png = scene.with_file_name("includes.png");
    let dir = lib.parent().unwrap().to_str().unwrap().to_string();
    let args = ["render", scene.to_str().unwrap(), "-o", png.to_str().unwrap(), "--backend", "cpu"];
    let out = patina(&args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "an angle include needs a search directory: {stderr}");
    assert!(stderr.starts_with("error[E0202]: cannot find `renderlib.sl`"), "{stderr}");
    let out = patina(&[&args[..], &["-I", &dir]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (_, [r, g, b, _]) = png_pixel(&png, 4, 4);
    assert!(r == 255 && g < r && b < g && b > 0, "the included colour: {:?}", [r, g, b]);
}

#[test]
fn usage_errors_exit_non_zero() {
    let out = patina(&["check"]);
    assert!(!out.status.success());
    let out = patina(&["frobnicate"]);
    assert!(!out.status.success());
}

#[test]
fn explain_prints_types_rates_and_stages() {
    let out = patina(&["explain", &example("aniso.sl")]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    let row = |name: &str| -> Vec<String> {
        let line =
            text.lines().find(|l| l.trim_start().starts_with(&format!("{name} "))).unwrap_or_else(|| {
                panic!("no row for `{name}` in:\n{text}");
            });
        line.split("  ").map(str::trim).filter(|s| !s.is_empty()).map(String::from).collect()
    };
    assert_eq!(row("base_uv"), ["base_uv", "float4", "vertex (declared)", "vertex stage"]);
    assert_eq!(row("lit"), ["lit", "float4", "perlight fragment (inferred)", "fragment stage"]);
    assert_eq!(row("ka"), ["ka", "float4", "constant (declared)", "compile time"]);
    assert_eq!(row("ambient_color"), ["ambient_color", "float4", "primitive group", "host (once per draw)"]);
    assert!(text.contains("surface shader `aniso` (Stanford style)"));
}

#[test]
fn eval_prints_a_table_of_outputs() {
    let out = patina(&[
        "eval",
        &example("plastic.sl"),
        "--light",
        "L=0,0,1 Cl=1,1,1",
        "--at",
        "N=0,0,1 Ng=0,0,1 I=0,0,-1",
        "--at",
        "N=0,0.6,0.8 Ng=0,0,1 I=0,0,-1",
        "--set",
        "Ks=0",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stdout = String::from_utf8(out.stdout).unwrap();
    let rows: Vec<&str> = stdout.lines().collect();
    assert!(rows[0].starts_with("point") && rows[0].contains("Ci") && rows[0].contains("Oi"), "{stdout}");
    // Kd * N.L: 0.5 overhead, 0.5 * 0.8 tilted.
    assert!(rows[1].contains("(0.5, 0.5, 0.5)"), "{stdout}");
    assert!(rows[2].contains("(0.4, 0.4, 0.4)"), "{stdout}");
}

#[test]
fn eval_reports_a_runaway_loop_at_its_position() {
    let file =
        scratch("loop.sl", b"surface s() {\n  float x = 0;\n  while (x < 1) { x += 0; }\n  Ci = x;\n}\n");
    let out = patina(&["eval", file.to_str().unwrap(), "--budget", "100"]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.contains("error[E0702]") && stderr.contains("loop.sl:3:3"), "{stderr}");
    // Issue 23: the help states the default budget, which a run without --budget also stops at.
    let help = String::from_utf8(patina(&["eval", "--help"]).stdout).unwrap();
    let line = help.lines().find(|l| l.contains("--budget")).unwrap_or_default();
    let default = patina_compiler::backend::MAX_LOOP_ITERATIONS;
    assert!(line.contains(&format!("[default: {default}]")), "{line}");
    let out = patina(&["eval", file.to_str().unwrap()]);
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.contains(&format!("{default}")), "{stderr}");
}

#[test]
fn eval_rejects_malformed_points_with_one_line() {
    let out = patina(&["eval", &example("plastic.sl"), "--at", "N=0,zero,1"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("`zero` is not a number"), "{stderr}");
}

fn scene(name: &str) -> String {
    format!("{}/examples/scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// Reads a PNG's size and the RGBA of one pixel.
fn png_pixel(path: &std::path::Path, x: u32, y: u32) -> ((u32, u32), [u8; 4]) {
    let image = patina_runtime::image::Image::read_png(path).expect("a PNG");
    let p = image.pixels[(y * image.width + x) as usize];
    ((image.width, image.height), p.map(|c| (c * 255.0).round() as u8))
}

#[test]
fn render_writes_a_png_on_the_cpu_when_asked() {
    let out_path = scratch("plastic-cpu.png", b"");
    let out =
        patina(&["render", &scene("plastic.toml"), "-o", out_path.to_str().unwrap(), "--backend", "cpu"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("CPU reference"), "{stderr}");
    let (size, centre) = png_pixel(&out_path, 160, 120);
    assert_eq!(size, (320, 240));
    // The sphere covers the centre: lit orange-red plastic, not the dark blue background.
    assert!(centre[0] > 40 && centre[0] > centre[2], "{centre:?}");
}

#[test]
fn render_falls_back_to_the_cpu_when_the_gpu_is_off() {
    let out_path = scratch("plastic-off.png", b"");
    let out = Command::new(env!("CARGO_BIN_EXE_patina"))
        .args(["render", &scene("flame.toml"), "-o", out_path.to_str().unwrap()])
        .env("PATINA_GPU", "off")
        .output()
        .expect("runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stderr).contains("rendering on the CPU"));
}

#[test]
fn malformed_and_missing_scenes_get_one_line() {
    let bad = scratch("bad.toml", b"[camera]\nfov = \"wide\"\n");
    let out = patina(&["render", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("bad.toml:2:7: camera.fov: expected a number"), "{stderr}");

    let out = patina(&["render", "/nonexistent/scene.toml"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.starts_with("error: cannot read /nonexistent/scene.toml"), "{stderr}");
    assert_eq!(stderr.lines().count(), 1);
}

#[test]
fn compile_writes_wgsl_that_reparses_and_an_interface() {
    let dir = std::env::temp_dir().join(format!("patina-compile-{}", std::process::id()));
    let light = format!("{}:pointlight", example("lights.sl"));
    let out = patina(&["compile", &example("plastic.sl"), "--light", &light, "-o", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let wgsl = std::fs::read_to_string(dir.join("plastic.wgsl")).unwrap();
    naga::front::wgsl::parse_str(&wgsl).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&wgsl)));
    assert!(wgsl.contains("fn vs_main") && wgsl.contains("fn fs_main"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("plastic.json")).unwrap()).unwrap();
    let params: Vec<&str> =
        json["params"].as_array().unwrap().iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(params, ["Ka", "Kd", "Ks", "roughness", "specularcolor"]);
    let names: Vec<&str> =
        json["uniforms"].as_array().unwrap().iter().map(|u| u["name"].as_str().unwrap()).collect();
    assert!(names.contains(&"l0_intensity") && names.contains(&"camera_to_clip"), "{names:?}");
    // The attributes are named as in the WGSL and say what they carry; plastic reads P and N only.
    assert_eq!(json["attributes"][0]["name"], "a_P");
    assert_eq!(json["attributes"][0]["source"]["what"], "position");
    assert_eq!(json["attributes"].as_array().unwrap().len(), 2);
    assert!(wgsl.contains("@location(0) a_P: vec3<f32>") && !wgsl.contains("a_uv"), "{wgsl}");
    assert_eq!(json["version"], 3);
    for name in &names {
        assert!(wgsl.contains(&format!("    {name}: ")), "the WGSL has no member {name}");
    }
}

#[test]
fn gallery_renders_compares_and_writes_a_page() {
    let dir = scratch("gallery.md", b"").parent().unwrap().join("gallery");
    let images = dir.join("img");
    let page = dir.join("page.md");
    let broken = scratch(
        "broken.toml",
        b"# Names a shader that is not there.\n[camera]\nfrom = [0, 0, -3]\nto = [0, 0, 0]\n\
          [[object]]\nmesh = \"sphere\"\nshader = \"missing.sl\"\n",
    );
    let out = patina(&[
        "gallery",
        &scene("flame.toml"),
        broken.to_str().unwrap(),
        "--images",
        images.to_str().unwrap(),
        "--markdown",
        page.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    // The broken scene fails the run, after the others were rendered and the page written.
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    let gpu = patina_runtime::gpu::adapter_required();
    let expected = if gpu { "flame: compile" } else { "rendering on the CPU" };
    assert!(stderr.contains(expected), "{stderr}");
    if gpu {
        assert!(stderr.contains("ms: agree (max"), "the GPU and CPU images must agree: {stderr}");
    }
    assert!(stderr.contains("broken: ") && stderr.contains("missing.sl"), "{stderr}");
    let md = std::fs::read_to_string(&page).expect("the page is written");
    assert!(md.contains("| [flame](#flame) | 160×240 |"), "{md}");
    if gpu {
        // No pixel of either picture is NaN or infinite: the NaN column says 0.
        let row = md.lines().find(|l| l.starts_with("| [flame](#flame)")).unwrap_or_default();
        assert!(row.ends_with("| 0 | yes |"), "{row}");
    }
    assert!(md.contains("![flame](img/flame.png)"), "{md}");
    assert!(md.contains("The Stanford-style procedural flame"), "the caption is the scene's comment: {md}");
    assert!(md.contains("| broken | failed: "), "{md}");
    assert!(!md.contains("![broken]"), "{md}");
    let (size, _) = png_pixel(&images.join("flame.png"), 0, 0);
    assert_eq!(size, (160, 240));
}

#[test]
fn explain_of_a_scene_says_what_binding_left_out_and_why() {
    let dir = scratch("flags.sl", b"").parent().unwrap().to_path_buf();
    std::fs::write(
        dir.join("flags.sl"),
        "surface flags(float use_tex = 0; string map = \"checker:4\"; float Kd = 0.8; float gain = 2) {\n\
           color c = Cs;\n\
           if (use_tex > 0.5) { c *= color texture(map, s, t); }\n\
           Ci = c * Kd * gain;\n\
           Oi = 1;\n\
         }\n",
    )
    .unwrap();
    let scene = dir.join("flags.toml");
    std::fs::write(
        &scene,
        "[camera]\nfrom = [0, 0, -3]\nto = [0, 0, 0]\n[[object]]\nmesh = \"sphere\"\nshader = \"flags.sl\"\n\
         params = { use_tex = 0, Kd = 0.5 }\nanimate = [\"Kd\"]\n",
    )
    .unwrap();
    let out = patina(&["explain", scene.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("folded     `use_tex` = 0\n"), "{stdout}");
    assert!(stdout.contains("folded     `gain` = 2 (its default)\n"), "the scene leaves gain: {stdout}");
    assert!(!stdout.contains("`Kd` ="), "Kd is animated, not folded: {stdout}");
    assert!(
        stdout.contains("flags.sl:3 is always false: the true side is gone (because of `use_tex`)"),
        "{stdout}"
    );
    assert!(stdout.contains("left out: checker:4 (sampled only by removed code)"), "{stdout}");
    let bytes: Vec<usize> = stdout
        .lines()
        .find(|l| l.trim_start().starts_with("WGSL bytes"))
        .map(|l| l.split_whitespace().filter_map(|w| w.parse().ok()).collect())
        .unwrap_or_default();
    assert!(bytes.len() == 2 && bytes[0] < bytes[1], "bound WGSL is smaller than dynamic: {stdout}");
}

#[test]
fn compile_with_fixed_parameters_leaves_out_what_they_decide() {
    let shader = scratch(
        "fixable.sl",
        b"surface fixable(float use_tex = 0; string map = \"grid.png\"; float Kd = 0.8) {\n\
            color c = Cs;\n\
            if (use_tex > 0.5) { c *= color texture(map, s, t); }\n\
            Ci = c * Kd;\n\
          }\n",
    );
    let dir = shader.parent().unwrap();
    let (fixed, dynamic) = (dir.join("fixed"), dir.join("dynamic"));
    let out =
        patina(&["compile", shader.to_str().unwrap(), "--fix", "use_tex=0", "-o", fixed.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let out = patina(&["compile", shader.to_str().unwrap(), "-o", dynamic.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let read =
        |d: &std::path::Path, ext: &str| std::fs::read_to_string(d.join(format!("fixable.{ext}"))).unwrap();
    assert!(read(&dynamic, "json").contains("grid.png") && !read(&fixed, "json").contains("grid.png"));
    assert!(read(&fixed, "wgsl").len() < read(&dynamic, "wgsl").len());
    let out = patina(&["compile", shader.to_str().unwrap(), "--fix", "use_tex=on"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("expected NAME=V"), "{stderr}");
    let out = patina(&["compile", shader.to_str().unwrap(), "--fix", "nope=1"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("has no parameter `nope`"));
}

#[test]
fn compile_binds_a_light_displacement_or_volume_shader_to_a_surface_and_an_imager_as_a_kernel() {
    let dir = std::env::temp_dir().join(format!("patina-compile-bound-{}", std::process::id()));
    let out_dir = dir.to_str().unwrap();
    let json = |name: &str| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(dir.join(format!("{name}.json"))).unwrap()).unwrap()
    };
    let wgsl = |name: &str| {
        let text = std::fs::read_to_string(dir.join(format!("{name}.wgsl"))).unwrap();
        naga::front::wgsl::parse_str(&text).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&text)));
        text
    };
    // A light on its own: bound to the standard library's plastic, its parameters in the block.
    let out = patina(&["compile", &example("lights.sl"), "--shader", "spotlight", "-o", out_dir]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let j = json("spotlight");
    assert_eq!(j["shader"], "plastic");
    assert_eq!(j["lights"][0]["shader"], "spotlight");
    let text = wgsl("spotlight");
    assert!(text.contains("l0_coneangle") && text.contains("fn fs_main"), "{text}");
    // Bound to a surface of the user's choosing.
    let surface = format!("{}:plastic", example("plastic.sl"));
    let out = patina(&["compile", &example("lights.sl"), "--surface", &surface, "-o", out_dir]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(json("pointlight")["lights"][0]["shader"], "pointlight");
    // A displacement.
    let out = patina(&["compile", &example("ripples.sl"), "-o", out_dir]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let j = json("ripples");
    assert_eq!(j["displacement"]["shader"], "ripples");
    assert!(j["lights"].as_array().unwrap().is_empty());
    assert!(wgsl("ripples").contains("fn displace"));
    // A volume: the atmosphere after the surface, its opacity the fragment's alpha.
    let out = patina(&["compile", &example("fog.sl"), "-o", out_dir]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let j = json("fog");
    assert_eq!(j["atmosphere"]["shader"], "fog");
    assert_eq!(j["output"], "ci_oi");
    let names: Vec<&str> =
        j["uniforms"].as_array().unwrap().iter().map(|u| u["name"].as_str().unwrap()).collect();
    assert!(names.contains(&"a_falloff") && names.contains(&"a_background"), "{names:?}");
    assert!(wgsl("fog").contains("fn atmosphere"));
    // An imager: the compute kernel the renderer runs per pixel, with its buffers' layout.
    let out = patina(&["compile", &example("imagers.sl"), "--shader", "background", "-o", out_dir]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let j = json("background");
    assert_eq!((j["kind"].as_str(), j["entry"].as_str()), (Some("imager"), Some("main")));
    let inputs: Vec<&str> =
        j["input"]["values"].as_array().unwrap().iter().map(|v| v["name"].as_str().unwrap()).collect();
    assert_eq!(inputs, ["Ci", "Oi", "alpha", "bgcolor"]);
    let outputs: Vec<&str> =
        j["output"]["values"].as_array().unwrap().iter().map(|v| v["name"].as_str().unwrap()).collect();
    assert_eq!(outputs, ["Ci", "alpha"]);
    assert!(wgsl("background").contains("@compute"));
    // --surface with a surface shader, and a surface file that is not there: one line each.
    let out = patina(&["compile", &example("plastic.sl"), "--surface", &surface, "-o", out_dir]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(String::from_utf8_lossy(&out.stderr).lines().count(), 1);
    let out = patina(&["compile", &example("fog.sl"), "--surface", "/nonexistent.sl", "-o", out_dir]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("cannot read `/nonexistent.sl`") && stderr.lines().count() == 1, "{stderr}");
}

#[test]
fn corpus_checks_renders_and_tabulates_a_directory() {
    // A directory of two files: a surface that renders, and one that does not check.
    let dir = std::env::temp_dir().join(format!("patina-cli-corpus-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("surface")).unwrap();
    std::fs::write(
        dir.join("surface/flat.sl"),
        "surface flat(color c = color(0.5, 0.25, 1)) { Ci = c; Oi = 1; }\n",
    )
    .unwrap();
    std::fs::write(dir.join("broken.sl"), "surface broken() { Ci = nosuch; }\n").unwrap();
    let (md, sheet) = (dir.join("corpus.md"), dir.join("corpus.png"));
    let out = patina(&[
        "corpus",
        dir.to_str().unwrap(),
        "--cpu-only",
        "--markdown",
        md.to_str().unwrap(),
        "--sheet",
        sheet.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let page = std::fs::read_to_string(&md).unwrap();
    assert!(page.contains("| `broken.sl` | ? | **E0"), "{page}");
    assert!(page.contains("| `surface/flat.sl` | surface | ok | – (no GPU) | ok |"), "{page}");
    assert!(
        page.contains("**Totals**: 2 files; 1 check; 0 render on the GPU, 1 on the CPU; 0 agree."),
        "{page}"
    );
    // The sheet: two tiles in a row of four, each of two 128 × 96 pictures and a label.
    let image = patina_runtime::image::Image::read_png(&sheet).unwrap();
    assert_eq!((image.width, image.height), (4 * (2 * 128 + 8), 96 + 18 + 8));
    // The flat surface's CPU picture (right half of the second tile) has its colour at the centre.
    let centre = image.get(264 + 4 + 128 + 64, 4 + 48).unwrap();
    assert!((centre[0] - 0.5).abs() < 0.01 && (centre[2] - 1.0).abs() < 0.01, "{centre:?}");

    let out = patina(&["corpus", dir.join("missing").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("missing"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
