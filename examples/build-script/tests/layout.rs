//! The generated structs against the interfaces the compiler wrote: size and every field's
//! offset (read from the embedded JSON, not from the generated constants), and the WGSL parses.

use core::mem::{offset_of, size_of};

use patina_build_example::shaders::{UniformFieldInfo, banded, plastic, plastic_folded};
use serde_json::Value;

/// Checks one shader: `offsets` are `offset_of!` of each struct field, by WGSL member name.
fn check(json: &str, size: usize, offsets: &[(&str, usize)], fields: &[UniformFieldInfo], wgsl: &str) {
    let interface: Value = serde_json::from_str(json).unwrap();
    assert_eq!(size as u64, interface["uniform_size"].as_u64().unwrap());
    let uniforms = interface["uniforms"].as_array().unwrap();
    assert_eq!(uniforms.len(), offsets.len(), "every member has a field");
    assert_eq!(uniforms.len(), fields.len());
    for (u, (name, offset)) in uniforms.iter().zip(offsets) {
        assert_eq!(u["name"].as_str().unwrap(), *name);
        assert_eq!(u["offset"].as_u64().unwrap(), *offset as u64, "offset of `{name}`");
    }
    for (u, f) in uniforms.iter().zip(fields) {
        assert_eq!(u["name"].as_str().unwrap(), f.name);
        assert_eq!(u["offset"].as_u64().unwrap(), f.offset as u64);
        assert_eq!(serde_json::from_str::<Value>(f.source).unwrap(), u["source"]);
    }
    let module = naga::front::wgsl::parse_str(wgsl).unwrap();
    let names: Vec<&str> = module.entry_points.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

macro_rules! offsets {
    ($ty:ty; $($field:ident),* $(,)?) => {
        &[$((stringify!($field), offset_of!($ty, $field))),*]
    };
}

#[test]
fn plastic_struct_matches_its_interface() {
    use plastic::*;
    assert_eq!(size_of::<Uniforms>(), UNIFORM_SIZE);
    // `e_h`: specular's exponent 1 / max(roughness, 1e-30), which the host part computes once.
    let offsets = offsets!(Uniforms; object_to_camera, normal_to_camera, camera_to_clip, Ci_h, Ci_h1_,
        Ci_h2_, e_h, Os, Cs, l0_intensity, l0_lightcolor, l0_from);
    check(INTERFACE_JSON, size_of::<Uniforms>(), offsets, FIELDS, WGSL);
    const { assert!(NEEDS_HOST) };
    assert_eq!((LOCATION_P, LOCATION_N), (0, 1));
    assert_eq!((UNIFORM_GROUP, UNIFORM_BINDING, TEXTURE_GROUP), (0, 0, 1));
    assert_eq!((VERTEX_ENTRY, FRAGMENT_ENTRY), ("vs_main", "fs_main"));
}

#[test]
fn folded_plastic_has_only_fields_a_program_can_fill() {
    use plastic_folded::*;
    assert_eq!(size_of::<Uniforms>(), UNIFORM_SIZE);
    let offsets = offsets!(Uniforms; object_to_camera, normal_to_camera, camera_to_clip, Ka, Kd, Ks,
        roughness, specularcolor, Os, Cs, l0_intensity, l0_lightcolor, l0_from);
    check(INTERFACE_JSON, size_of::<Uniforms>(), offsets, FIELDS, WGSL);
    const { assert!(!NEEDS_HOST) };
    assert!(FIELDS.iter().all(|f| !f.source.contains("\"host\"")));
    // The bytes a program writes land where the WGSL reads them.
    let mut block: Uniforms = bytemuck::Zeroable::zeroed();
    block.Kd = 0.7;
    block.l0_from = [-2.5, 3.0, -3.0];
    let bytes = block.as_bytes();
    assert_eq!(bytes.len(), UNIFORM_SIZE);
    assert_eq!(bytes[offset::Kd..offset::Kd + 4], 0.7f32.to_le_bytes());
    assert_eq!(bytes[offset::l0_from + 8..offset::l0_from + 12], (-3.0f32).to_le_bytes());
}

#[test]
fn banded_struct_matches_its_interface() {
    use banded::*;
    assert_eq!(size_of::<Uniforms>(), UNIFORM_SIZE);
    let offsets = offsets!(Uniforms; object_to_camera, normal_to_camera, camera_to_clip, bright, dark,
        Ci_h, count_h, Os);
    check(INTERFACE_JSON, size_of::<Uniforms>(), offsets, FIELDS, WGSL);
}

#[test]
fn the_build_script_names_the_included_file() {
    // Cargo keeps the build script's output next to OUT_DIR; it must name the included file, so
    // that editing it reruns the build script.
    let out = std::path::Path::new(env!("OUT_DIR")).parent().unwrap().join("output");
    let text = std::fs::read_to_string(&out).unwrap();
    for file in ["shaders/banded.sl", "shaders/bands.sl", "../shaders/plastic.sl", "../shaders/lights.sl"] {
        assert!(
            text.lines().any(|l| l.starts_with("cargo:rerun-if-changed=") && l.ends_with(file)),
            "no rerun-if-changed for {file} in:\n{text}"
        );
    }
}
