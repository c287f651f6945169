//! Gallery scene `kajiya_kay_fur` (seed-digest §12 S7, §2 on Kajiya & Kay): a shell of procedural
//! hair over a torus, ray-marched with Kajiya-Kay lighting and self-shadowing.
//!
//! The Kajiya-Kay identities already covered by `stdlib/lighting.rs` (sin(t, l) at t ∥ l and t ⊥ l,
//! the Lambert integral over the half cylinder built from eqs. 10-12, the specular peak scanning
//! the eye in the plane of t and l) are not repeated. Here: the Lambert integral over the whole
//! circumference with the lit half found by the clamp, with K_d = 2 k_d r (eq. 13); the highlight
//! seen from the scene's side (fixed light and eye, the fibre turning: peak where t ⊥ l − e, or
//! t ⊥ l + e for the mirror form); the march's transmittance through a uniform slab against the
//! chord length (seed-digest H5); shadows on against off; both backends on a small render.
//!
//! Run with `--nocapture` to see the measured values.

use crate::support;

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::CpuProgram;
use patina_compiler::opt::Prepared;
use patina_compiler::syntax::preprocess::MemoryLoader;
use patina_runtime::image::{Image, Thresholds};
use patina_test_support::Rng;
use std::f64::consts::PI;
use support::gallery::{assert_finite, at, both, covered, cpu, scene, set, shader_source};

type V3 = [f64; 3];

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn scale(a: V3, k: f64) -> V3 {
    [a[0] * k, a[1] * k, a[2] * k]
}

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn unit(a: V3) -> V3 {
    scale(a, 1.0 / dot(a, a).sqrt())
}

/// A direction uniform on the unit sphere.
fn direction(rng: &mut Rng) -> V3 {
    let z = 2.0 * rng.unit() - 1.0;
    let phi = 2.0 * PI * rng.unit();
    let r = (1.0 - z * z).sqrt();
    [r * phi.cos(), r * phi.sin(), z]
}

/// Flattens vectors into one input column.
fn column(vs: &[V3]) -> Vec<f64> {
    vs.iter().flatten().copied().collect()
}

// ---------------------------------------------------------------------------------------------
// Kajiya-Kay through the standard library (support::program, the interpreter in f64)

const HAIR: &str = "#include <lighting.sl>
surface hair(varying vector tt = 0; varying vector l = 0; varying vector e = 0;
             varying float Kd = 1, p = 1;
             output varying float psi_d = 0, spec = 0, mirror = 0)
{
    psi_d = Kd * kajiya_kay_diffuse(tt, l);
    spec = kajiya_kay_specular(tt, l, e, p);
    mirror = kajiya_kay_specular_mirror(tt, l, e, p);
    Ci = 0; Oi = 1;
}";

#[test]
fn diffuse_is_lambert_over_the_whole_circumference_with_kd_2_kd_r() {
    let program = support::program(HAIR);
    let mut rng = Rng(11);
    let count = 48;
    let (mut ts, mut ls, mut kds, mut want) = (vec![], vec![], vec![], vec![]);
    for i in 0..count {
        let t = direction(&mut rng);
        // Every eighth light direction is (nearly) along the fibre, where the integral vanishes.
        let l = if i % 8 == 0 { unit(add(t, scale(direction(&mut rng), 1e-3))) } else { direction(&mut rng) };
        let (kd, r) = (0.2 + rng.unit(), 0.01 + 0.2 * rng.unit());
        // The hair's normals n(phi) = u cos(phi) + w sin(phi) around the whole circumference, in a
        // basis of the normal plane that does not depend on l; a surface element r dphi reflects
        // kd max(0, l . n) (Lambert), so the lit half is where the clamp is positive.
        let helper = if t[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
        let u = unit(cross(t, helper));
        let w = cross(t, u);
        let steps = 20_000;
        let h = 2.0 * PI / steps as f64;
        let integral: f64 = (0..steps)
            .map(|k| {
                let phi = (k as f64 + 0.5) * h;
                let n = add(scale(u, phi.cos()), scale(w, phi.sin()));
                kd * dot(l, n).max(0.0) * r * h
            })
            .sum();
        ts.push(t);
        ls.push(l);
        kds.push(2.0 * kd * r); // K_d = 2 k_d r (eq. 13)
        want.push(integral);
    }
    let cols = [("tt", column(&ts)), ("l", column(&ls)), ("Kd", kds.clone())];
    let inputs: Vec<(&str, &[f64])> = cols.iter().map(|(n, c)| (*n, c.as_slice())).collect();
    let out = program.cpu::<f64>(count, &inputs, &["psi_d"]);
    let mut worst = 0.0f64;
    for i in 0..count {
        // The midpoint rule on an integrand with two kinks (the terminator): O(h^2) there.
        let err = (out[0][i] - want[i]).abs() / kds[i];
        worst = worst.max(err);
        assert!(err < 1e-7, "point {i}: stdlib {} vs quadrature {} (K_d {})", out[0][i], want[i], kds[i]);
    }
    eprintln!("Lambert over the circumference vs K_d sin(t, l): worst {worst:e} (relative to K_d)");
}

#[test]
fn the_highlight_is_where_the_fibre_is_perpendicular_to_l_minus_e() {
    // In the scene the light and the eye are fixed and the fibre direction varies. The printed
    // term is 1 exactly where t . l = t . e, i.e. t ⊥ l − e; the mirror term where t ⊥ l + e.
    // Scan t around a great circle through ±(l ∓ e) normalized and a vector w ⊥ it: the peaks must be
    // at the two crossings of the plane ⊥ (l ∓ e).
    let program = support::program(HAIR);
    let mut rng = Rng(5);
    let n = 720; // half-degree steps
    for case in 0..6 {
        let (l, e) = (direction(&mut rng), direction(&mut rng));
        for mirror in [false, true] {
            let m = unit(if mirror { add(l, e) } else { add(l, scale(e, -1.0)) });
            let w = unit(cross(m, direction(&mut rng)));
            let ts: Vec<V3> = (0..n)
                .map(|k| {
                    let b = 2.0 * PI * k as f64 / n as f64;
                    add(scale(w, b.cos()), scale(m, b.sin()))
                })
                .collect();
            let cols = [
                ("tt", column(&ts)),
                ("l", column(&vec![l; n])),
                ("e", column(&vec![e; n])),
                ("p", vec![60.0; n]),
            ];
            let inputs: Vec<(&str, &[f64])> = cols.iter().map(|(n, c)| (*n, c.as_slice())).collect();
            let out = program.cpu::<f64>(n, &inputs, &["spec", "mirror"]);
            let values = &out[usize::from(mirror)];
            let name = if mirror { "mirror" } else { "printed" };
            for k in [0, n / 2] {
                assert!(
                    (values[k] - 1.0).abs() < 1e-12,
                    "case {case} {name}: {} at the crossing {k}",
                    values[k]
                );
            }
            // Away from the crossings the term falls off: below 1 - 1e-6 from one step on, and the
            // largest value more than 10 degrees away is well below the peak.
            for (k, v) in values.iter().enumerate() {
                let from_peak = k.min(n - k).min(k.abs_diff(n / 2));
                if from_peak >= 1 {
                    assert!(*v < 1.0 - 1e-6, "case {case} {name}: {v} at step {k}");
                }
                if from_peak >= 20 {
                    assert!(*v < 0.9, "case {case} {name}: {v} at step {k}, {from_peak} steps from a peak");
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The scene's shader on the interpreter: transmittance of a uniform slab (seed-digest H5)

/// The scene shader compiled with no lights: Oi is the march's opacity alone.
fn fur_program() -> CpuProgram {
    let source = shader_source("kajiya_kay_fur");
    let checked = patina_compiler::check_source("kajiya_kay_fur.sl", &source, &MemoryLoader::default());
    assert!(checked.diagnostics.is_empty(), "{:#?}", checked.diagnostics);
    let shader =
        checked.program.shaders.into_iter().find(|s| s.name == "kajiya_kay_fur").expect("the shader");
    CpuProgram::compile(&Prepared::new(shader), &Binding::default())
        .unwrap_or_else(|d| panic!("{}: {}", d.code, d.message))
}

/// The tube radius of the torus mesh (the outer surface of the fur shell) and the scene's defaults.
const OUTER: f64 = 0.25;
const SHELL: f64 = 0.09;
const TAU: f64 = 120.0;

#[test]
fn a_uniform_slab_has_the_exact_transmittance_for_any_step_count() {
    // Rays from the top of the tube's cross-section in the plane y = 0 (centre (1, 0, 0)), going
    // down at angle a below the horizontal: in that plane the shell is the annulus between radii
    // 0.25 - shell and 0.25, and a ray that misses the core (0.25 cos a > 0.25 - shell) crosses
    // the shell along the chord 2 * 0.25 * sin(a). With a uniform density rho the opacity must be
    // 1 - exp(-tau rho chord) whatever the number of steps (the last segment is not rounded to a
    // step: the interval is the exact chord, split evenly).
    let program = fur_program();
    let angles = [8.0f64, 15.0, 24.0, 33.0, 41.0];
    let mut ps = vec![];
    let mut is = vec![];
    let mut chords = vec![];
    for a in angles {
        let a = a.to_radians();
        assert!(OUTER * a.cos() > OUTER - SHELL + 1e-3, "the ray must miss the core");
        for side in [1.0, -1.0] {
            ps.push([1.0, 0.0, OUTER]);
            is.push([side * a.cos(), 0.0, -a.sin()]);
            chords.push((2.0 * OUTER * a.sin(), a.sin()));
        }
    }
    let n = ps.len();
    let mut worst = 0.0f64;
    for rho in [0.02, 0.1] {
        for steps in [1.0, 3.0, 7.0, 24.0] {
            let mut eval = patina_compiler::backend::cpu::Evaluator::<f64>::new(&program);
            for (name, value) in [("slab", rho), ("steps", steps), ("shadow_steps", 0.0)] {
                eval.set(name, &[value]).unwrap();
            }
            let cols = [("P", column(&ps)), ("I", column(&is))];
            let inputs: Vec<(&str, &[f64])> = cols.iter().map(|(n, c)| (*n, c.as_slice())).collect();
            let out = eval.eval_points(n, &inputs, &["Oi"]).unwrap();
            for (k, (chord, exit_slope)) in chords.iter().enumerate() {
                let want = 1.0 - (-TAU * rho * chord).exp();
                let got = out[0][3 * k];
                // The shader stops its search for the exit where |0.25 - rho| < 1e-6, rho growing
                // at sin(a) per unit length there: the chord is within 1e-6 / sin(a), and the
                // opacity within tau rho (1 - opacity) times that.
                let tol = TAU * rho * (1.0 - want) * 1e-6 / exit_slope + 1e-12;
                let err = (got - want).abs();
                worst = worst.max(err / tol);
                assert!(err < tol, "rho {rho}, {steps} steps, chord {chord}: opacity {got}, want {want}");
            }
        }
    }
    eprintln!("uniform slab: worst opacity error {worst:.3} of the tolerance");
}

// ---------------------------------------------------------------------------------------------
// The rendered scene

/// The scene at `width × height` with `steps` view samples and `shadow_steps` shadow samples.
fn fur_scene(width: u32, height: u32, steps: f64, shadow_steps: f64) -> patina_runtime::scene::Scene {
    let mut s = scene("kajiya_kay_fur", width, height);
    set(&mut s, &[0], "steps", steps);
    set(&mut s, &[0], "shadow_steps", shadow_steps);
    s
}

fn luminance(p: [f32; 4]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

#[test]
fn fur_renders_alike_on_both_backends() {
    let s = fur_scene(80, 60, 6.0, 2.0);
    let background = s.output.background;
    let Some(r) = both("kajiya_kay_fur", &s, Thresholds::default()) else { return };
    eprintln!("kajiya_kay_fur GPU vs CPU: {:?}", r.comparison);
    let c = covered(&r.cpu, background);
    eprintln!("covered: {c:.3}");
    assert!(c > 0.3 && c < 0.8, "the torus covers {c} of the image");
    // The hole in the middle shows the background.
    assert_eq!(at(&r.cpu, 40, 30), background, "the centre of the hole");
}

/// Mean luminance and standard deviation over the pixels `mask` selects.
fn stats(image: &Image, mask: &[bool]) -> (f64, f64) {
    let values: Vec<f64> =
        image.pixels.iter().zip(mask).filter(|(_, m)| **m).map(|(p, _)| luminance(*p)).collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    (mean, var.sqrt())
}

#[test]
fn self_shadowing_darkens_the_fur_measurably() {
    let lit = cpu("shadows off", &fur_scene(56, 42, 6.0, 0.0));
    let shadowed = cpu("shadows on", &fur_scene(56, 42, 6.0, 3.0));
    let background = fur_scene(1, 1, 1.0, 1.0).output.background;
    assert_finite("shadows off", &lit);
    let mask: Vec<bool> =
        lit.pixels.iter().map(|p| p.iter().zip(background).any(|(a, b)| (a - b).abs() > 1e-3)).collect();
    // Shadows only attenuate each sample's light (the opacities do not change): no pixel gets
    // brighter, channel by channel.
    for (k, (a, b)) in lit.pixels.iter().zip(&shadowed.pixels).enumerate() {
        for c in 0..4 {
            assert!(b[c] <= a[c] + 1e-6, "pixel {k} channel {c}: {} with shadows, {} without", b[c], a[c]);
        }
        assert!((a[3] - b[3]).abs() < 1e-6, "pixel {k}: the opacity changed");
    }
    let (m0, s0) = stats(&lit, &mask);
    let (m1, s1) = stats(&shadowed, &mask);
    eprintln!("luminance without shadows {m0:.4} ± {s0:.4}, with {m1:.4} ± {s1:.4}");
    assert!(m1 < 0.8 * m0, "shadows must darken the fur measurably: {m1} vs {m0}");
    assert!(m1 > 0.2 * m0, "but not black it out: {m1} vs {m0}");
}

/// The root-mean-square difference of the colour channels of two images of the same size.
fn rms(a: &Image, b: &Image) -> f64 {
    let sum: f64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| (0..3).map(|c| (p[c] as f64 - q[c] as f64).powi(2)).sum::<f64>())
        .sum();
    (sum / (3 * a.pixels.len()) as f64).sqrt()
}

#[test]
fn the_march_converges_as_steps_grow() {
    // The scene's knob: errors against 48 steps fall as the step count doubles (shadows off, so
    // only the view march varies; 32 x 24 pixels to keep the reference affordable).
    let reference = cpu("48 steps", &fur_scene(32, 24, 48.0, 0.0));
    let errors: Vec<f64> = [4.0, 8.0, 16.0]
        .iter()
        .map(|&n| rms(&cpu(&format!("{n} steps"), &fur_scene(32, 24, n, 0.0)), &reference))
        .collect();
    eprintln!("RMS against 48 steps at 4, 8, 16 steps: {errors:?}");
    assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
    assert!(errors[2] < 0.5 * errors[0], "{errors:?}");
}

/// Renders `scene` on the GPU alone (no comparison: for settings where the images need not
/// agree, only be finite); `None` when `PATINA_GPU=off`.
fn gpu_only(label: &str, scene: &patina_runtime::scene::Scene) -> Option<Image> {
    use patina_runtime::render::{self, Backend};
    let gpu = patina_runtime::gpu::for_tests()?;
    let prepared = render::prepare(scene).unwrap_or_else(|e| panic!("{label}: {e}"));
    let image = render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert_finite(label, &image);
    Some(image)
}

#[test]
fn extreme_settings_stay_finite_and_in_range() {
    // Seed-digest S7 stiff settings (H22): a huge tau (every hair opaque), one step, a razor-sharp
    // highlight, a hair shell 0.001 thick, an extreme comb, a shell filling the tube (the core a
    // circle), the mirror highlight. Finite on both backends, colours >= 0, opacity in [0, 1].
    let cases: [&[(&str, f64)]; 4] = [
        &[("tau", 1e7), ("steps", 1.0), ("p", 1e6)],
        &[("shell", 0.001), ("comb", 1e4), ("shadow_steps", 1.0)],
        &[("shell", 0.25), ("kd", 0.0), ("mirror", 1.0), ("p", 0.0)],
        &[("tau", 0.0), ("slab", 1.0)],
    ];
    for (k, params) in cases.iter().enumerate() {
        let mut s = fur_scene(24, 18, 3.0, 2.0);
        for (name, value) in params.iter() {
            set(&mut s, &[0], name, *value);
        }
        let label = format!("extreme case {k} {params:?}");
        let mut images = vec![cpu(&label, &s)];
        images.extend(gpu_only(&label, &s));
        for image in &images {
            for p in &image.pixels {
                assert!(p[..3].iter().all(|c| *c >= 0.0) && (0.0..=1.0).contains(&p[3]), "{label}: {p:?}");
            }
        }
    }
}
