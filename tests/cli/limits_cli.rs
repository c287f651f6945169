//! The command line at the project's limits (docs/limits.md): one error line and a failing exit,
//! never a backtrace.

use std::path::PathBuf;
use std::process::Output;

use crate::support::patina;

/// A directory of this test's own.
fn scratch(test: &str) -> PathBuf {
    crate::support::scratch_dir("limits-cli", test)
}

fn example(name: &str) -> String {
    format!("{}/examples/shaders/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// The one line of stderr, which must be the only one.
fn one_line(out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(!stderr.contains("panicked") && !stderr.contains("backtrace"), "{stderr}");
    stderr.trim_end().to_string()
}

#[test]
fn rendering_a_target_over_the_device_limit_prints_one_error_line() {
    // On the GPU only: without one the CPU would render the 262144 x 128 target.
    if patina_runtime::gpu::for_tests().is_none() {
        return;
    }
    let dir = scratch("render");
    let scene = dir.join("wide.toml");
    let text = format!(
        "[output]\nwidth = 16384\nheight = 8\nsupersample = 16\n\n[camera]\nfrom = [0, 0, -5]\nto = [0, 0, 0]\n\n\
         [[object]]\nmesh = \"sphere\"\nshader = \"{}\"\n",
        example("plastic.sl")
    );
    std::fs::write(&scene, text).expect("write the scene");
    let png = dir.join("out.png");
    let out = patina(&["render", scene.to_str().unwrap(), "-o", png.to_str().unwrap()]);
    assert!(!out.status.success());
    let line = one_line(&out);
    assert!(line.contains("rendering the 16384x8 image at supersample 16"), "{line}");
    assert!(
        line.contains("the render target of 262144x128 pixels: 262144 is over the device's limit of"),
        "{line}"
    );
    assert!(line.ends_with("(max_texture_dimension_2d)"), "{line}");
    assert!(!png.exists());
}

#[test]
fn compiling_with_more_lights_than_the_limit_prints_one_error_line() {
    let dir = scratch("compile");
    let light = format!("{}:pointlight", example("lights.sl"));
    let mut args = vec!["compile".to_string(), example("plastic.sl"), "-o".into(), dir.display().to_string()];
    for _ in 0..65 {
        args.extend(["--light".to_string(), light.clone()]);
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = patina(&args);
    assert!(!out.status.success());
    let line = one_line(&out);
    assert!(line.contains("65 lights are bound to `plastic`, over the limit of 64"), "{line}");
    assert!(!dir.join("plastic.wgsl").exists());
}

#[test]
fn rendering_a_scene_with_more_lights_than_the_limit_prints_one_error_line() {
    // Refused while compiling, before any device is used: on either backend.
    let dir = scratch("lights");
    let scene = dir.join("lights.toml");
    let mut text =
        String::from("[output]\nwidth = 8\nheight = 8\n\n[camera]\nfrom = [0, 0, -5]\nto = [0, 0, 0]\n\n");
    for _ in 0..65 {
        text.push_str(&format!(
            "[[light]]\nshader = \"{}\"\nname = \"pointlight\"\n\n",
            example("lights.sl")
        ));
    }
    text.push_str(&format!("[[object]]\nmesh = \"sphere\"\nshader = \"{}\"\n", example("plastic.sl")));
    std::fs::write(&scene, text).expect("write the scene");
    let png = dir.join("out.png");
    for backend in ["gpu", "cpu"] {
        let out =
            patina(&["render", scene.to_str().unwrap(), "--backend", backend, "-o", png.to_str().unwrap()]);
        assert!(!out.status.success());
        let line = one_line(&out);
        assert!(line.contains("65 lights are bound to `plastic`, over the limit of 64"), "{backend}: {line}");
    }
    assert!(!png.exists());
}
