//! Texture lookups on the interpreter: the shared filter of `opt::textures` (bilinear on level 0,
//! repeat), checked against values computed here by hand.

use std::sync::Arc;

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator, Texture};

fn program(src: &str, binding: &Binding) -> CpuProgram {
    crate::support::compile(src, binding)
}

/// A 2x2 texture: red, green on the top row; blue, white below.
fn quad() -> Texture {
    let texels = vec![[1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0], [1.0, 1.0, 1.0, 1.0]];
    Texture { size: [2, 2, 1], texels: Arc::from(texels) }
}

#[test]
fn bilinear_lookups_hit_texel_centres_blend_between_and_wrap() {
    let p = program("surface t(string map = \"quad\") { Ci = texture(map, s, t); }", &Binding::default());
    assert_eq!(p.textures(), ["quad"]);
    let mut e = Evaluator::<f64>::new(&p);
    e.set_texture("quad", quad()).unwrap();
    // Texel centres at 0.25 and 0.75; halfway between all four; s wraps by whole periods; at the
    // left edge (s = 0) the filter blends the first column with the last (repeat).
    let s = [0.25, 0.75, 0.25, 0.5, 1.25, 0.0];
    let t = [0.25, 0.25, 0.75, 0.5, -0.75, 0.25];
    let out = e.eval_points(6, &[("s", &s), ("t", &t)], &["Ci"]).unwrap().remove(0);
    let at = |k: usize| &out[k * 3..k * 3 + 3];
    assert_eq!(at(0), &[1.0, 0.0, 0.0]);
    assert_eq!(at(1), &[0.0, 1.0, 0.0]);
    assert_eq!(at(2), &[0.0, 0.0, 1.0]);
    assert_eq!(at(3), &[0.5, 0.5, 0.5]);
    assert_eq!(at(4), &[1.0, 0.0, 0.0]);
    assert_eq!(at(5), &[0.5, 0.5, 0.0]);
}

#[test]
fn a_float_lookup_reads_the_first_channel_and_the_one_argument_form_reads_s_and_t() {
    let p = program("surface t() { float r = texture(\"quad\"); Ci = r; }", &Binding::default());
    let mut e = Evaluator::<f32>::new(&p);
    e.set_texture("quad", quad()).unwrap();
    let out = e.eval_points(2, &[("s", &[0.25, 0.5]), ("t", &[0.25, 0.25])], &["Ci"]).unwrap().remove(0);
    assert_eq!(out, vec![1.0, 1.0, 1.0, 0.5, 0.5, 0.5]);
}

#[test]
fn stanford_texrefs_and_3d_textures_are_bound_by_name() {
    let src = "surface shader float4 v(vertex float4 uvw, primitive group texref vol) {
        return texture3d(vol, uvw);
    }";
    let binding = Binding { lights: vec![], strings: vec![("vol".into(), "cube.raw".into())] };
    let p = program(src, &binding);
    assert_eq!(p.textures(), ["cube.raw"]);
    // A 2x1x2 volume: the far slice is brighter.
    let texels = vec![[0.0; 4], [0.2; 4], [0.6; 4], [1.0; 4]];
    let mut e = Evaluator::<f64>::new(&p);
    e.set_texture("cube.raw", Texture { size: [2, 1, 2], texels: Arc::from(texels) }).unwrap();
    // Homogeneous coordinates: (0.5, 0.5, 0.5, 1) is the centre, where all four texels mix
    // equally; (0.25, 0.5, 0.75, 1) is texel (0, 0, 1) exactly; w = 2 halves the coordinates.
    let uvw = [0.5, 0.5, 0.5, 1.0, 0.25, 0.5, 0.75, 1.0, 0.5, 1.0, 1.5, 2.0];
    let out = e.eval_points(3, &[("uvw", &uvw)], &["result"]).unwrap().remove(0);
    // Texels are f32: the expectations use the same values.
    let (a, b) = (f64::from(0.2f32), f64::from(0.6f32));
    assert!((out[0] - (a + b + 1.0) / 4.0).abs() < 1e-15, "{out:?}");
    assert_eq!(out[4], b);
    assert_eq!(out[8], b);
}

#[test]
fn an_unbound_texture_reads_black() {
    let p = program("surface t() { Ci = texture(\"missing\", s, t); }", &Binding::default());
    let mut e = Evaluator::<f32>::new(&p);
    let out = e.eval_points(1, &[("s", &[0.3]), ("t", &[0.7])], &["Ci"]).unwrap().remove(0);
    assert_eq!(out, vec![0.0, 0.0, 0.0]);
    assert!(e.set_texture("other", quad()).is_err());
}

#[test]
fn a_channel_selected_name_reads_from_that_channel_on() {
    // `texture(name[k], ...)` (RenderMan's channel selection; cd.sl's `titlemap[3]`) once
    // panicked in the interpreter's lowering. Texels with distinct channels show which are read.
    let src = "surface t(string map = \"ch\") {
        float a = texture(map[3], s, t);
        color gba = texture(map[1], s, t);
        Ci = color(a, comp(gba, 0), comp(gba, 2));
    }";
    let p = program(src, &Binding::default());
    assert_eq!(p.textures(), ["ch"]);
    let mut e = Evaluator::<f32>::new(&p);
    e.set_texture("ch", Texture { size: [1, 1, 1], texels: Arc::from(vec![[0.1, 0.2, 0.3, 0.4]]) }).unwrap();
    let out = e.eval_points(1, &[("s", &[0.5]), ("t", &[0.5])], &["Ci"]).unwrap().remove(0);
    assert_eq!(out, [0.4f32, 0.2, 0.4].map(f64::from));
}
