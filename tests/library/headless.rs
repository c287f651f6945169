//! `examples/headless.rs`, a user's own wgpu program drawing through the facade, draws what the
//! renderer draws for the same scene (`examples/headless.toml`), within the gallery's thresholds.

use std::path::PathBuf;
use std::process::Command;

use patina::runtime::image::{Image, Thresholds, compare};
use patina::runtime::{gpu, render, scene::Scene};

/// The example's binary, which `cargo test` builds beside this test's (`target/<profile>/examples`).
fn example(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("the test's own path");
    let profile = exe.parent().and_then(|deps| deps.parent()).expect("target/<profile>/deps");
    profile.join("examples").join(name)
}

#[test]
fn the_headless_example_draws_what_patina_render_draws() {
    let Some(gpu) = gpu::for_tests() else { return };
    let dir = crate::support::scratch_dir("headless", "example");
    let png = dir.join("headless.png");
    let run = Command::new(example("headless"))
        .arg(&png)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("NODEVICE_SELECT", "1")
        .output()
        .unwrap_or_else(|e| {
            panic!("{e}: the headless example did not run (`cargo test` builds it; alone, run `cargo build --example headless` first)")
        });
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let drawn = Image::read_png(&png).expect("the example's PNG");

    let scene = Scene::load(format!("{}/examples/headless.toml", env!("CARGO_MANIFEST_DIR"))).expect("scene");
    let prepared = render::prepare(&scene).expect("prepare");
    let reference = render::render(&prepared, render::Backend::Gpu, Some(gpu)).expect("render");
    // The renderer's picture as `patina render` writes it: 8 bits a channel.
    let written = dir.join("reference.png");
    reference.write_png(&written).expect("write");
    let reference = Image::read_png(&written).expect("read");
    let c = compare(&drawn, &reference, &Thresholds::default()).expect("same size");
    assert!(c.passes(&Thresholds::default()), "{c:?}");
    // Not a blank picture that matches a blank one: the sphere is lit, the corner is background.
    let centre = drawn.get(150, 100).expect("pixel");
    assert!(centre[0] > 0.2 && centre[0] > centre[2], "{centre:?}");
    let corner = drawn.get(2, 2).expect("pixel");
    assert!((corner[2] - 0.08).abs() < 0.01, "{corner:?}");
}
