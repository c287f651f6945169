//! Shadow-map lookups on the interpreter: `opt::shadow`'s percentage-closer taps over a small
//! synthetic map whose matrix row is orthographic (x, y, depth, w) = (P.x, P.y, P.z, 1), checked
//! against counts of the taps computed here from the same pattern.

use std::sync::Arc;

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator, Texture};
use patina_compiler::opt::shadow::{DEFAULT_SAMPLES, tap};

fn program(src: &str) -> CpuProgram {
    crate::support::compile(src, &Binding::default())
}

const N: u32 = 8;

/// An 8×8 map: depth 1 in the left half (texel x < 4), nothing (10^30) in the right; the last row
/// holds the identity-like matrix and the map's bias, 0.05.
fn map() -> Texture {
    let mut texels: Vec<[f32; 4]> =
        (0..N * N).map(|i| if i % N < N / 2 { [1.0; 4] } else { [1e30; 4] }).collect();
    let mut last = vec![[0.0f32; 4]; N as usize];
    last[0] = [1.0, 0.0, 0.0, 0.0];
    last[1] = [0.0, 1.0, 0.0, 0.0];
    last[2] = [0.0, 0.0, 1.0, 0.0];
    last[3] = [0.0, 0.0, 0.0, 1.0];
    last[4] = [0.05, 0.0, 0.0, 0.0];
    texels.extend(last);
    Texture { size: [N, N + 1, 1], texels: Arc::from(texels) }
}

/// The lookup at each point (x, y, z) of `points`.
fn shadow(src: &str, points: &[[f64; 3]]) -> Vec<f64> {
    let p = program(src);
    assert_eq!(p.textures(), ["m"]);
    let mut e = Evaluator::<f32>::new(&p);
    e.set_texture("m", map()).unwrap();
    let flat: Vec<f64> = points.iter().flatten().copied().collect();
    let out = e.eval_points(points.len(), &[("P", &flat)], &["Ci"]).unwrap().remove(0);
    out.chunks(3).map(|c| c[0]).collect()
}

#[test]
fn taps_compare_against_depth_plus_the_maps_bias() {
    let src = "surface t() { Ci = shadow(\"m\", P); }";
    // Behind the left half's surface; in front of it by less than the bias; over the empty right
    // half; off the map (lit); on the boundary between the halves (s = 0.5).
    let out = shadow(
        src,
        &[[-0.5, 0.0, 2.0], [-0.5, 0.0, 1.02], [0.5, 0.0, 2.0], [-1.5, 0.0, 2.0], [0.0, 0.0, 2.0]],
    );
    assert_eq!(&out[..4], &[1.0, 0.0, 0.0, 0.0]);
    // On the boundary the taps left of it (offset x < 0, at one texel of spread) are shadowed.
    let n = DEFAULT_SAMPLES;
    let left = (0..n).filter(|k| tap(*k, n)[0] < 0.0).count() as f64;
    assert_eq!(out[4], left / f64::from(n));
    assert!(out[4] > 0.3 && out[4] < 0.7, "{}", out[4]);
}

#[test]
fn options_set_the_taps_the_blur_and_the_bias() {
    // One tap: the centre, which on the boundary reads the right (empty) half.
    let one = shadow(
        "surface t() { Ci = shadow(\"m\", P, \"samples\", 1); }",
        &[[0.0, 0.0, 2.0], [-0.1, 0.0, 2.0]],
    );
    assert_eq!(one, [0.0, 1.0]);
    // A bias of 0 shadows the point just behind the surface.
    let biased = shadow("surface t() { Ci = shadow(\"m\", P, \"bias\", 0); }", &[[-0.5, 0.0, 1.02]]);
    assert_eq!(biased, [1.0]);
    // A blur of half the map, 64 taps: at s = 0.25 (x = -0.5) the taps spread over
    // s in 0.25 ± (0.5 + 1/8) / 2, those at s >= 0.5 lit, those below 0 off the map and lit.
    let n = 64;
    let blurred =
        shadow("surface t() { Ci = shadow(\"m\", P, \"samples\", 64, \"blur\", 0.5); }", &[[-0.5, 0.0, 2.0]]);
    let spread = 0.5f64 + 1.0 / f64::from(N);
    let shadowed = (0..n)
        .filter(|k| {
            let s = 0.25 + spread * tap(*k, n)[0];
            let t = 0.5 + spread * tap(*k, n)[1];
            (0.0..0.5).contains(&s) && (0.0..1.0).contains(&t)
        })
        .count() as f64;
    assert_eq!(blurred, [shadowed / f64::from(n)]);
    assert!(blurred[0] > 0.4 && blurred[0] < 0.95, "{blurred:?}");
}
