//! `Scene::parse` on arbitrary text: a scene or a `SceneError`, never a panic. For a scene that
//! parses, the cheap accessors and the built-in meshes (at a small detail: the size limit itself
//! is the scene checker's `MAX_DETAIL`), without the disk or a GPU.
#![no_main]

use libfuzzer_sys::fuzz_target;
use patina_runtime::scene::{MeshSource, Scene};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let scene = match Scene::parse(text, "fuzz.toml", "/nonexistent-fuzz-dir") {
        Ok(scene) => scene,
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    };
    let _ = scene.camera();
    let _ = scene.thresholds();
    let _ = scene.aspect();
    for (i, object) in scene.objects.iter().enumerate() {
        let _ = scene.object_transform(i);
        if !matches!(object.mesh, MeshSource::Obj(_)) {
            let _ = object.mesh.build(object.detail.min(16));
        }
    }
});
