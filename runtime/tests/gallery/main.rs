//! The gallery (docs/gallery.md): every scene of `examples/scenes/` that reproduces a seed
//! document, rendered small on both backends against the image thresholds, with each scene's own
//! checks (closed forms, ranges, identities) in the module of its group. Needs a GPU adapter
//! (lavapipe in CI) unless `PATINA_GPU=off`.
//!
//! Run one group with `cargo test -p patina-runtime --test gallery soft_sphere -- --nocapture`
//! to see the measured errors.

#[path = "../support/mod.rs"]
mod support;

mod environment;
mod fur;
mod gases;
mod hypertexture;
mod patterns;
mod shadows;
mod soft_sphere;
mod solid;
mod stanford;

/// The gallery's scenes, in docs/gallery.md's order (the order of the seeds' topics).
const SCENES: &[&str] = &[
    "noise_panel",
    "soft_sphere",
    "hypertexture",
    "fireball",
    "furry_torus",
    "kajiya_kay_fur",
    "hart_torus",
    "hart_torus_supersampled",
    "hart_teapot",
    "zone_plate",
    "steam_cup",
    "cumulus",
    "banks_aniso",
    "flame",
    "volume_texture",
    "brick_filtering",
    "star",
    "planet",
    "shinymetal",
    "shadowed_teapot",
];

/// The other example scenes: the renderer's own examples, tested in `runtime/tests/renderer/render.rs`.
const EXAMPLES: &[&str] = &["bricks", "plastic", "ripples", "shiny", "textured"];

/// Every test source that renders scenes, to find the scenes each one names.
const TEST_SOURCES: &[&str] = &[
    include_str!("environment.rs"),
    include_str!("fur.rs"),
    include_str!("gases.rs"),
    include_str!("hypertexture.rs"),
    include_str!("patterns.rs"),
    include_str!("shadows.rs"),
    include_str!("soft_sphere.rs"),
    include_str!("solid.rs"),
    include_str!("stanford.rs"),
    include_str!("../renderer/render.rs"),
];

#[test]
fn every_scene_is_in_the_gallery_and_rendered_by_a_test() {
    let dir = format!("{}/../examples/scenes", env!("CARGO_MANIFEST_DIR"));
    let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
        .expect("examples/scenes")
        .filter_map(|e| e.ok()?.file_name().into_string().ok()?.strip_suffix(".toml").map(String::from))
        .collect();
    on_disk.sort();
    let mut listed: Vec<String> = SCENES.iter().chain(EXAMPLES).map(|s| s.to_string()).collect();
    listed.sort();
    assert_eq!(on_disk, listed, "examples/scenes/ and the lists here must name the same scenes");
    let page = std::fs::read_to_string(format!("{}/../docs/gallery.md", env!("CARGO_MANIFEST_DIR")))
        .expect("docs/gallery.md");
    for name in SCENES {
        assert!(page.contains(&format!("\n## {name}\n")), "docs/gallery.md has no section for {name}");
        assert!(
            page.contains(&format!("](gallery/{name}.png)")),
            "docs/gallery.md shows no picture of {name}"
        );
        let png = format!("{}/../docs/gallery/{name}.png", env!("CARGO_MANIFEST_DIR"));
        assert!(std::path::Path::new(&png).exists(), "{png} is missing");
    }
    for name in SCENES.iter().chain(EXAMPLES) {
        let quoted = format!("\"{name}\"");
        assert!(TEST_SOURCES.iter().any(|s| s.contains(&quoted)), "no test renders {name}");
    }
}
