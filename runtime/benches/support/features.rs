//! The scene of the binding benchmark (runtime/benches/binding.rs), which runtime/tests/renderer/bind.rs
//! also renders: `features.sl`, a shader with five feature flags, on a sphere under `lights`
//! point lights, with every flag fixed (only the specular lobe on).

use patina_runtime::scene::Scene;

/// The shader: a texture, a noise-perturbed colour, an fBm bump of the normal, a specular lobe per
/// light and a rim term, each behind its own flag.
pub const SHADER: &str = include_str!("features.sl");

/// The scene at 96×96 with `lights` point lights around the camera's side.
pub fn scene(lights: usize) -> Scene {
    let dir = std::env::temp_dir().join(format!("patina-features-{}-{lights}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("features.sl"), SHADER).unwrap();
    let mut text = String::from(
        "[output]\nwidth = 96\nheight = 96\n[camera]\nfrom = [0.0, 0.5, -3.5]\nto = [0.0, 0.0, 0.0]\n",
    );
    for k in 0..lights {
        let a = k as f32 * 0.8;
        text += &format!(
            "[[light]]\nshader = \"<shaders.sl>\"\nname = \"pointlight\"\n\
             params = {{ intensity = 3.0, from = [{:.2}, 2.0, {:.2}] }}\n",
            3.0 * a.cos(),
            -3.0 * a.sin().abs() - 1.0
        );
    }
    text += "[[object]]\nmesh = \"sphere\"\nshader = \"features.sl\"\n\
             params = { use_tex = 0, detail = 0, bump = 0, specular = 1, rim = 0, Kd = 0.7, Ks = 0.4, roughness = 0.2 }\n";
    Scene::parse(&text, dir.join("features.toml"), &dir).unwrap()
}
