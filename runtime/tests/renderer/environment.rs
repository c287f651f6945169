//! Environment maps on both backends: a lookup along the direction of a texel's centre reads that
//! texel of the generated maps (`sky:N` lat-long, `skycube:N` cube atlas), whose values this test
//! computes itself from the formula documented in runtime/src/render/textures.rs; the float
//! overload reads the first channel and the four-direction form the directions' mean. The GPU
//! half needs an adapter (lavapipe in CI) unless `PATINA_GPU=off`.

use std::f64::consts::{PI, TAU};

use patina_runtime::gpu::Gpu;
use patina_runtime::image::Image;
use patina_runtime::render::{self, Backend};
use patina_runtime::scene::Scene;

/// The probe: a surface whose colour is the lookup along the uniform (dx, dy, dz), in the
/// colour, float and four-direction forms.
const PROBE: &str = "surface probe(string map = \"sky:16\"; float dx = 0; float dy = 1; float dz = 0;
    float form = 0; float spread = 0.001)
{
    vector D = vector(dx, dy, dz);
    vector a = spread * vector(0.3, -0.2, 0.1);
    vector b = spread * vector(-0.1, 0.25, 0.2);
    color c = color environment(map, D);
    if (form == 1)
        c = color(float environment(map, D));
    else if (form == 2)
        c = color environment(map, D + a, D - a, D + b, D - b);
    else if (form == 3)
        c = color environment(map, D, \"blur\", spread);
    Ci = c;
    Oi = 1;
}
";

/// The sky of `sky:N` along `d`, as documented, in f64.
fn sky(d: [f64; 3]) -> [f64; 3] {
    let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let d = d.map(|c| c / l);
    if d[1] >= 0.0 {
        if (d[0] + d[1] - d[2]) / 3f64.sqrt() >= 6f64.to_radians().cos() {
            return [4.0, 3.6, 3.0];
        }
        let (h, z) = ([0.85, 0.9, 1.0], [0.15, 0.35, 0.8]);
        [0, 1, 2].map(|k| h[k] + (z[k] - h[k]) * d[1])
    } else {
        let s = d[0].atan2(-d[2]) / TAU + 0.5;
        let t = d[0].hypot(d[2]).atan2(d[1]) / PI;
        if ((16.0 * s).floor() as i64 + (8.0 * t).floor() as i64) % 2 == 0 {
            [0.45, 0.4, 0.32]
        } else {
            [0.12, 0.1, 0.08]
        }
    }
}

/// The direction of the centre of texel (x, y) of a 2n × n lat-long map.
fn latlong_centre(x: u32, y: u32, n: u32) -> [f64; 3] {
    let phi = TAU * ((f64::from(x) + 0.5) / f64::from(2 * n) - 0.5);
    let theta = PI * (f64::from(y) + 0.5) / f64::from(n);
    [theta.sin() * phi.sin(), theta.cos(), -theta.sin() * phi.cos()]
}

/// The direction of the centre of texel (i, j) of face `face` (+X, -X, +Y, -Y, +Z, -Z) of an
/// n × n cube map, in OpenGL's face axes.
fn cube_centre(face: u32, i: u32, j: u32, n: u32) -> [f64; 3] {
    let (sc, tc) =
        (2.0 * (f64::from(i) + 0.5) / f64::from(n) - 1.0, 2.0 * (f64::from(j) + 0.5) / f64::from(n) - 1.0);
    match face {
        0 => [1.0, -tc, -sc],
        1 => [-1.0, -tc, sc],
        2 => [sc, 1.0, tc],
        3 => [sc, -1.0, -tc],
        4 => [sc, -tc, 1.0],
        _ => [-sc, -tc, -1.0],
    }
}

/// A scene of one sphere filling the middle of an 8 × 8 image, shaded by the probe.
fn probe_scene(map: &str, d: [f64; 3], form: u32) -> Scene {
    probe_scene_spread(map, d, form, 0.001)
}

/// [`probe_scene`] with the four-direction form's directions `spread` apart.
fn probe_scene_spread(map: &str, d: [f64; 3], form: u32, spread: f64) -> Scene {
    // A directory per scene: the tests run in parallel.
    static NEXT: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
    let k = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("patina-environment-{}-{k}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("probe.sl"), PROBE).unwrap();
    let text = format!(
        "[output]\nwidth = 8\nheight = 8\nbackground = [0.0, 0.0, 0.0, 1.0]\n\
         [camera]\nfrom = [0.0, 0.0, -4.0]\nto = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nfov = 20\n\
         [[object]]\nmesh = \"sphere\"\ndetail = 16\nshader = \"probe.sl\"\n\
         params = {{ map = \"{map}\", dx = {:?}, dy = {:?}, dz = {:?}, form = {form}, spread = {spread:?} }}\n",
        d[0], d[1], d[2]
    );
    Scene::parse(&text, dir.join("probe.toml"), &dir).unwrap_or_else(|e| panic!("{e}"))
}

/// The centre pixel of the probe's image on `backend`.
fn probe(map: &str, d: [f64; 3], form: u32, backend: Backend, gpu: Option<&Gpu>) -> [f32; 4] {
    let prepared = render::prepare(&probe_scene(map, d, form)).unwrap_or_else(|e| panic!("{e}"));
    let image: Image = render::render(&prepared, backend, gpu).unwrap_or_else(|e| panic!("{e}"));
    image.pixels[(4 * image.width + 4) as usize]
}

/// One lookup to check: label, map, direction, form (0 colour, 1 float, 2 four directions) and
/// the expected RGB.
type Case<'a> = (String, &'a str, [f64; 3], u32, [f64; 3]);

/// The lookups along `cases` on the CPU and, when there is one, the GPU; returns the largest
/// error seen on each.
fn check(cases: &[Case]) -> (f64, f64) {
    let gpu = patina_runtime::gpu::for_tests();
    let mut worst = (0.0f64, 0.0f64);
    for (label, map, d, form, expected) in cases {
        let mut backends = vec![(Backend::Cpu, None)];
        if let Some(g) = gpu {
            backends.push((Backend::Gpu, Some(g)));
        }
        for (backend, g) in backends {
            let got = probe(map, *d, *form, backend, g);
            let error = (0..3).map(|k| (f64::from(got[k]) - expected[k]).abs()).fold(0.0, f64::max);
            assert!(error < 2e-3, "{label} on {backend:?}: {got:?}, expected {expected:?}");
            let w = if backend == Backend::Cpu { &mut worst.0 } else { &mut worst.1 };
            *w = w.max(error);
        }
    }
    worst
}

#[test]
fn a_lookup_along_a_texel_centre_reads_that_texel_of_a_lat_long_map() {
    let n = 16;
    // Sky near the zenith, sky near the horizon, ground checks of both colours, a column beside
    // the seam (s wraps there) and the sun (above 1: nothing is clamped).
    let texels = [(5, 1), (27, 6), (20, 12), (21, 12), (0, 10), (31, 14), (10, 15)];
    let mut cases: Vec<_> = texels
        .iter()
        .map(|&(x, y)| {
            (
                format!("sky:16 texel ({x}, {y})"),
                "sky:16",
                latlong_centre(x, y, n),
                0,
                sky(latlong_centre(x, y, n)),
            )
        })
        .collect();
    // Texel (80, 19) of sky:64 is in the sun (runtime/src/render/textures.rs).
    cases.push(("sky:64 sun".into(), "sky:64", latlong_centre(80, 19, 64), 0, [4.0, 3.6, 3.0]));
    // Float form: the first channel; four directions 0.001 apart: their mean, D (at level 0: a
    // footprint of 0.005 texels); a direction's length does not matter.
    let d = latlong_centre(20, 12, n);
    let red = sky(d)[0];
    cases.push(("float form".into(), "sky:16", d, 1, [red; 3]));
    cases.push(("four directions".into(), "sky:16", d, 2, sky(d)));
    cases.push(("unnormalized".into(), "sky:16", d.map(|c| c * 7.5), 0, sky(d)));
    for (label, _, _, _, e) in &cases {
        println!("{label}: expected {e:?}");
    }
    let (cpu, gpu) = check(&cases);
    println!("lat-long: worst error CPU {cpu:.2e}, GPU {gpu:.2e}");
}

#[test]
fn a_lookup_along_a_texel_centre_reads_that_texel_of_each_cube_face() {
    let n = 16;
    let texels = [(0, 3, 10), (1, 12, 2), (2, 5, 9), (3, 14, 0), (4, 7, 13), (5, 1, 6)];
    let cases: Vec<_> = texels
        .iter()
        .map(|&(f, i, j)| {
            let d = cube_centre(f, i, j, n);
            (format!("skycube:16 face {f} texel ({i}, {j})"), "skycube:16", d, 0, sky(d))
        })
        .collect();
    let (cpu, gpu) = check(&cases);
    println!("cube: worst error CPU {cpu:.2e}, GPU {gpu:.2e}");
}

#[test]
fn a_zero_direction_reads_the_lat_long_centre_and_bad_names_are_one_error() {
    // D = 0 reads (s, t) = (1/2, 1/2): between the four texels about the map's centre, where the
    // sky meets the ground at -Z, on both backends alike.
    let cpu = probe("sky:16", [0.0; 3], 0, Backend::Cpu, None);
    let centre = |x: u32, y: u32| sky(latlong_centre(x, y, 16));
    let mean: Vec<f64> = (0..3)
        .map(|k| (centre(15, 7)[k] + centre(16, 7)[k] + centre(15, 8)[k] + centre(16, 8)[k]) / 4.0)
        .collect();
    for k in 0..3 {
        assert!((f64::from(cpu[k]) - mean[k]).abs() < 1e-3, "{cpu:?} vs {mean:?}");
    }
    if let Some(g) = patina_runtime::gpu::for_tests() {
        let gpu = probe("sky:16", [0.0; 3], 0, Backend::Gpu, Some(g));
        assert!((0..3).all(|k| (gpu[k] - cpu[k]).abs() < 1e-4), "{gpu:?} vs {cpu:?}");
    }
    for bad in ["cube:a.png", "sky:0", "missing.hdr"] {
        let message = match render::prepare(&probe_scene(bad, [0.0, 1.0, 0.0], 0)) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("{bad} loaded"),
        };
        assert!(message.contains(bad) && !message.contains('\n'), "{bad}: {message}");
    }
}

/// Level `k` of `sky:16`'s chain at texel (x, y): the mean of the 2^k × 2^k level-0 texels it
/// covers.
fn level_texel(k: u32, x: u32, y: u32) -> [f64; 3] {
    let n = 1 << k;
    let mut sum = [0.0; 3];
    for j in 0..n {
        for i in 0..n {
            let t = sky(latlong_centre(x * n + i, y * n + j, 16)).map(|c| f64::from(c as f32));
            (0..3).for_each(|c| sum[c] += t[c]);
        }
    }
    sum.map(|c| c / f64::from(n * n))
}

/// The bilinear lookup at (s, t) of level `k` of `sky:16` (32 × 16 at level 0), wrapping in s
/// and clamping in t.
fn level_bilinear(k: u32, s: f64, t: f64) -> [f64; 3] {
    let (w, h) = (32 >> k, 16 >> k);
    let (x, y) = (s * f64::from(w) - 0.5, t * f64::from(h) - 0.5);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let col = |i: f64| (i as i64).rem_euclid(i64::from(w)) as u32;
    let row = |j: f64| (j as i64).clamp(0, i64::from(h) - 1) as u32;
    let texel = |i: f64, j: f64| level_texel(k, col(i), row(j));
    let (a, b, c, d) = (texel(x0, y0), texel(x0 + 1.0, y0), texel(x0, y0 + 1.0), texel(x0 + 1.0, y0 + 1.0));
    [0, 1, 2].map(|q| {
        let top = a[q] + (b[q] - a[q]) * fx;
        let bottom = c[q] + (d[q] - c[q]) * fx;
        top + (bottom - top) * fy
    })
}

#[test]
fn a_wide_footprint_reads_the_mip_chain_trilinearly() {
    // The four-direction form with D ± a, D ± b: the footprint is the largest distance from the
    // first direction to the others, |2a| = 2 spread |(0.3, -0.2, 0.1)|, over |D| = 1; in
    // level-0 texels of sky:16 (32 wide) f · 32 / 2π, and the level its log2.
    let gpu = patina_runtime::gpu::for_tests();
    // On the ground, where the checks make the levels differ.
    let d = latlong_centre(20, 12, 16);
    let s = d[0].atan2(-d[2]) / TAU + 0.5;
    let t = d[0].hypot(d[2]).atan2(d[1]) / PI;
    for spread in [0.5, 1.0, 2.0] {
        let width = [2.0 * 0.3, 2.0 * -0.2, 2.0 * 0.1].map(|c: f64| c * spread);
        let others = [[-0.4, 0.45, 0.1], [-0.2, -0.05, -0.3]].map(|v: [f64; 3]| v.map(|c| c * spread));
        let footprint = [width, others[0], others[1]]
            .iter()
            .map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
            .fold(0.0, f64::max);
        let lod = (footprint * 32.0 / TAU).max(1.0).log2().min(4.0);
        let (l0, f) = (lod.floor() as u32, lod - lod.floor());
        let (near, far) = (level_bilinear(l0, s, t), level_bilinear((l0 + 1).min(4), s, t));
        let expected = [0, 1, 2].map(|q| near[q] + (far[q] - near[q]) * f);
        let scene = probe_scene_spread("sky:16", d, 2, spread);
        let prepared = render::prepare(&scene).unwrap_or_else(|e| panic!("{e}"));
        let mut backends = vec![(Backend::Cpu, None)];
        if let Some(g) = gpu {
            backends.push((Backend::Gpu, Some(g)));
        }
        for (backend, g) in backends {
            let image = render::render(&prepared, backend, g).unwrap_or_else(|e| panic!("{e}"));
            let got = image.pixels[(4 * image.width + 4) as usize];
            let error = (0..3).map(|q| (f64::from(got[q]) - expected[q]).abs()).fold(0.0, f64::max);
            println!(
                "spread {spread}: level {lod:.3} on {backend:?}: {got:?}, expected {expected:?}, error {error:.2e}"
            );
            assert!(error < 1e-3, "spread {spread}, level {lod}, {backend:?}: {got:?} vs {expected:?}");
        }
        // The "blur" option, a fraction of the map's width: 0.25 of 32 texels is level 3.
        if spread == 2.0 {
            let expected = level_bilinear(3, s, t);
            let scene = probe_scene_spread("sky:16", d, 3, 0.25);
            let prepared = render::prepare(&scene).unwrap_or_else(|e| panic!("{e}"));
            let image = render::render(&prepared, Backend::Cpu, None).unwrap_or_else(|e| panic!("{e}"));
            let got = image.pixels[(4 * image.width + 4) as usize];
            println!("blur 0.25: {got:?}, expected {expected:?}");
            assert!(
                (0..3).all(|q| (f64::from(got[q]) - expected[q]).abs() < 1e-4),
                "blur: {got:?} vs {expected:?}"
            );
        }
        // The blurred value is not level 0's.
        let sharp = level_bilinear(0, s, t);
        assert!(
            (0..3).any(|q| (sharp[q] - expected[q]).abs() > 0.01),
            "spread {spread}: {sharp:?} {expected:?}"
        );
    }
}

/// The mean, in f64, of the level-0 texels of `skycube:16`'s face `face` in the `n` × `n` block
/// at block (i, j): the texel of the chain's level log2(n) there.
fn cube_block_mean(face: u32, i: u32, j: u32, n: u32) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for b in 0..n {
        for a in 0..n {
            let t = sky(cube_centre(face, i * n + a, j * n + b, 16)).map(|c| f64::from(c as f32));
            (0..3).for_each(|c| sum[c] += t[c]);
        }
    }
    sum.map(|c| c / f64::from(n * n))
}

#[test]
fn a_wide_footprint_reads_a_cube_maps_chain() {
    let gpu = patina_runtime::gpu::for_tests();
    let mut backends = vec![(Backend::Cpu, None)];
    if let Some(g) = gpu {
        backends.push((Backend::Gpu, Some(g)));
    }
    // +X, which the horizon crosses: the centre of level 2's texel (1, 2), a 4 × 4 face there, the
    // ground's checks just below the horizon. "blur" 1/16 of the 4 × 16 texels around the
    // equator is 4 texels: level 2.
    let d = cube_centre(0, 1, 2, 4);
    let level2 = cube_block_mean(0, 1, 2, 4);
    let sharp = sky(cube_centre(0, 4, 8, 16));
    // A footprint wider than the face: the last level, one texel, the face's mean.
    let whole = cube_block_mean(0, 0, 0, 16);
    let differ = |a: [f64; 3], b: [f64; 3]| (0..3).any(|q| (a[q] - b[q]).abs() > 0.01);
    assert!(
        differ(level2, sharp) && differ(level2, whole),
        "{sharp:?} {level2:?} {whole:?}: the levels differ here"
    );
    for (label, form, spread, expected) in
        [("blur 1/16", 3, 1.0 / 16.0, level2), ("a wide footprint", 2, 4.0, whole)]
    {
        let scene = probe_scene_spread("skycube:16", d, form, spread);
        let prepared = render::prepare(&scene).unwrap_or_else(|e| panic!("{e}"));
        for (backend, g) in &backends {
            let image = render::render(&prepared, *backend, *g).unwrap_or_else(|e| panic!("{e}"));
            let got = image.pixels[(4 * image.width + 4) as usize];
            let error = (0..3).map(|q| (f64::from(got[q]) - expected[q]).abs()).fold(0.0, f64::max);
            println!("cube, {label} on {backend:?}: {got:?}, expected {expected:?}, error {error:.2e}");
            assert!(error < 1e-4, "cube, {label} on {backend:?}: {got:?} vs {expected:?}");
        }
    }
}
