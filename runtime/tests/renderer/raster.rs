//! The CPU reference rasterizer against closed-form expectations: coverage and the fill rule,
//! perspective-correct values and their derivatives, depth order, clipping, and bad input.

use patina_runtime::raster::{
    Blend, DrawError, DrawOptions, DrawStats, Fragments, Framebuffer, Varyings, draw,
};

/// Clip coordinates (w = 1, z = 0.5) of a framebuffer position in pixels.
fn at_pixel(x: f64, y: f64, fb: &Framebuffer) -> [f32; 4] {
    let (w, h) = (f64::from(fb.width), f64::from(fb.height));
    [(2.0 * x / w - 1.0) as f32, (1.0 - 2.0 * y / h) as f32, 0.5, 1.0]
}

/// Draws and returns the stats and every batch the shader saw; colours come from `colour`.
fn run(
    fb: &mut Framebuffer,
    clip: &[[f32; 4]],
    indices: &[u32],
    varyings: &Varyings,
    options: &DrawOptions,
    colour: impl Fn(&Fragments, usize) -> [f32; 4],
) -> (DrawStats, Vec<Fragments>) {
    let mut seen = Vec::new();
    let stats = draw(fb, clip, indices, varyings, options, |f: &Fragments, out: &mut [[f32; 4]]| {
        assert_eq!(out.len(), f.count);
        for (k, o) in out.iter_mut().enumerate() {
            *o = colour(f, k);
        }
        seen.push(f.clone());
        Ok::<(), String>(())
    })
    .unwrap();
    (stats, seen)
}

/// How many fragments each pixel received.
fn counts(fb: &Framebuffer, batches: &[Fragments]) -> Vec<u32> {
    let mut n = vec![0; fb.color.len()];
    for (x, y) in batches.iter().flat_map(|b| &b.pixels) {
        n[*y as usize * fb.width as usize + *x as usize] += 1;
    }
    n
}

const HALF: [f32; 4] = [0.5; 4];

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn a_triangle_covers_exactly_the_centres_inside_it() {
    let mut fb = Framebuffer::new(16, 16, [0.0; 4]);
    let p = [(1.35, 0.8), (14.2, 3.35), (4.65, 12.85)];
    let clip = p.map(|(x, y)| at_pixel(x, y, &fb));
    let (stats, batches) =
        run(&mut fb, &clip, &[0, 1, 2], &Varyings::none(), &DrawOptions::default(), |_, _| HALF);
    let n = counts(&fb, &batches);
    let mut inside = 0;
    for j in 0..16 {
        for i in 0..16 {
            let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
            // Edge functions of the exact triangle, scaled to distances in pixels.
            let dist = [0, 1, 2].map(|k| {
                let ((ax, ay), (bx, by)) = (p[k], p[(k + 1) % 3]);
                ((bx - ax) * (y - ay) - (by - ay) * (x - ax)) / (bx - ax).hypot(by - ay)
            });
            assert!(dist.iter().all(|d| d.abs() > 0.01), "a centre too close to call");
            let expected = u32::from(dist.iter().all(|&d| d < 0.0) || dist.iter().all(|&d| d > 0.0));
            assert_eq!(n[j * 16 + i], expected, "pixel ({i}, {j})");
            inside += expected;
        }
    }
    assert_eq!(stats.fragments, inside as usize);
    assert!(inside > 50);
}

#[test]
fn two_triangles_sharing_a_diagonal_through_centres_blend_each_pixel_once() {
    for batch in [1, 5, 128] {
        let mut fb = Framebuffer::new(8, 8, [0.0; 4]);
        // The diagonal (1, 1)-(7, 7) passes through the centres (1.5, 1.5) ... (6.5, 6.5).
        let clip = [(1.0, 1.0), (7.0, 1.0), (7.0, 7.0), (1.0, 7.0)].map(|(x, y)| at_pixel(x, y, &fb));
        let options = DrawOptions { blend: Blend::PremultipliedOver, depth_write: false, batch };
        run(&mut fb, &clip, &[0, 1, 2, 0, 2, 3], &Varyings::none(), &options, |_, _| HALF);
        for y in 0..8 {
            for x in 0..8 {
                let inside = (1..7).contains(&x) && (1..7).contains(&y);
                let expected = if inside { HALF } else { [0.0; 4] };
                assert_eq!(fb.pixel(x, y), Some(expected), "pixel ({x}, {y}), batch {batch}");
            }
        }
    }
}

#[test]
fn top_left_rule_on_edges_through_centres() {
    let mut fb = Framebuffer::new(8, 8, [0.0; 4]);
    // Left edge x = 1.5 and top edge y = 2.5 keep their centres; right x = 5.5 and bottom y = 6.5
    // do not. The diagonal's centres go to one triangle or the other.
    let clip = [(1.5, 2.5), (5.5, 2.5), (5.5, 6.5), (1.5, 6.5)].map(|(x, y)| at_pixel(x, y, &fb));
    let (_, batches) =
        run(&mut fb, &clip, &[0, 1, 2, 2, 3, 0], &Varyings::none(), &DrawOptions::default(), |_, _| HALF);
    let n = counts(&fb, &batches);
    for y in 0..8 {
        for x in 0..8 {
            let expected = u32::from((1..5).contains(&x) && (2..6).contains(&y));
            assert_eq!(n[y * 8 + x], expected, "pixel ({x}, {y})");
        }
    }
}

/// A jittered grid of quads over the whole viewport, with a different w at every vertex.
fn jittered_grid(cells: usize, rng: &mut Rng) -> (Vec<[f32; 4]>, Vec<u32>) {
    let side = cells + 1;
    let mut clip = Vec::new();
    for j in 0..side {
        for i in 0..side {
            let jitter = |k: usize, r: f64| if k == 0 || k == cells { 0.0 } else { (r - 0.5) * 0.5 };
            let x = -1.0 + 2.0 * (i as f64 + jitter(i, rng.next())) / cells as f64;
            let y = -1.0 + 2.0 * (j as f64 + jitter(j, rng.next())) / cells as f64;
            let w = 0.5 + 1.5 * rng.next();
            clip.push([(x * w) as f32, (y * w) as f32, (0.5 * w) as f32, w as f32]);
        }
    }
    let mut indices = Vec::new();
    for j in 0..cells {
        for i in 0..cells {
            let v = |a: usize, b: usize| ((j + b) * side + i + a) as u32;
            if rng.next() < 0.5 {
                indices.extend([v(0, 0), v(1, 0), v(1, 1), v(0, 0), v(1, 1), v(0, 1)]);
            } else {
                indices.extend([v(0, 0), v(1, 0), v(0, 1), v(1, 0), v(1, 1), v(0, 1)]);
            }
        }
    }
    (clip, indices)
}

#[test]
fn a_jittered_mesh_covers_every_pixel_exactly_once() {
    let mut rng = Rng(7);
    let (clip, indices) = jittered_grid(23, &mut rng);
    let mut fb = Framebuffer::new(97, 64, [0.0; 4]);
    let (stats, batches) =
        run(&mut fb, &clip, &indices, &Varyings::none(), &DrawOptions::default(), |_, _| HALF);
    assert!(counts(&fb, &batches).iter().all(|&n| n == 1));
    assert_eq!(stats.fragments, 97 * 64);
    assert_eq!((stats.triangles, stats.culled, stats.clipped, stats.degenerate), (23 * 23 * 2, 0, 0, 0));
}

#[test]
fn ten_thousand_triangles_at_512_square() {
    let mut rng = Rng(11);
    let (clip, indices) = jittered_grid(71, &mut rng);
    let colours: Vec<f32> = (0..clip.len() * 4).map(|_| rng.next() as f32).collect();
    let varyings = Varyings::smooth(4, &colours);
    let mut fb = Framebuffer::new(512, 512, [0.0; 4]);
    let start = std::time::Instant::now();
    let colour = |f: &Fragments, k: usize| std::array::from_fn(|c| f.values_of(c)[k]);
    let (stats, _) = run(&mut fb, &clip, &indices, &varyings, &DrawOptions::default(), colour);
    eprintln!("{} triangles, {} fragments: {:?}", stats.triangles, stats.fragments, start.elapsed());
    assert_eq!(stats.triangles, 71 * 71 * 2);
    assert_eq!(stats.fragments, 512 * 512);
    assert!(fb.color.iter().flatten().all(|c| (0.0..=1.0).contains(c)));
}

/// A perspective camera looking down -z, with depth mapped to [0, 1] (near to far).
struct Camera {
    focal: f64,
    near: f64,
    far: f64,
    width: u32,
    height: u32,
}

impl Camera {
    fn project(&self, p: [f64; 3]) -> [f32; 4] {
        let aspect = f64::from(self.width) / f64::from(self.height);
        let a = self.far / (self.near - self.far);
        let b = self.near * self.far / (self.near - self.far);
        [self.focal / aspect * p[0], self.focal * p[1], a * p[2] + b, -p[2]].map(|c| c as f32)
    }

    /// The direction (with z = -1) of the ray through a framebuffer position.
    fn ray(&self, x: f64, y: f64) -> [f64; 3] {
        let aspect = f64::from(self.width) / f64::from(self.height);
        let u = 2.0 * x / f64::from(self.width) - 1.0;
        let v = 1.0 - 2.0 * y / f64::from(self.height);
        [u * aspect / self.focal, v / self.focal, -1.0]
    }
}

/// World x and z where the ray through `(x, y)` meets the floor y = -1 (None above the horizon).
fn floor_hit(cam: &Camera, x: f64, y: f64) -> Option<[f64; 2]> {
    let d = cam.ray(x, y);
    (d[1] < 0.0).then(|| {
        let t = -1.0 / d[1];
        [t * d[0], t * d[2]]
    })
}

#[test]
fn a_receding_floor_is_interpolated_perspective_correctly_with_exact_derivatives() {
    let cam = Camera { focal: 1.2, near: 0.5, far: 100.0, width: 64, height: 48 };
    let corners = [[-2.0, -1.0, -1.5], [2.0, -1.0, -1.5], [2.0, -1.0, -30.0], [-2.0, -1.0, -30.0]];
    let clip = corners.map(|p| cam.project(p));
    // Varyings: world x, world z, and a flat id.
    let data: Vec<f32> =
        corners.iter().enumerate().flat_map(|(i, p)| [p[0] as f32, p[2] as f32, i as f32]).collect();
    let varyings = Varyings { components: 3, data: &data, flat: &[false, false, true] };
    let mut fb = Framebuffer::new(cam.width, cam.height, [0.0; 4]);
    let (stats, batches) =
        run(&mut fb, &clip, &[0, 1, 2, 2, 3, 0], &varyings, &DrawOptions::default(), |_, _| HALF);
    assert!(stats.fragments > 300, "{stats:?}");
    let h = 1e-3;
    for f in &batches {
        for k in 0..f.count {
            let (i, j) = f.pixels[k];
            let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
            let hit = floor_hit(&cam, x, y).unwrap();
            let dx = floor_hit(&cam, x + h, y).unwrap().map2(floor_hit(&cam, x - h, y).unwrap());
            let dy = floor_hit(&cam, x, y + h).unwrap().map2(floor_hit(&cam, x, y - h).unwrap());
            for c in 0..2 {
                let got = f64::from(f.values_of(c)[k]);
                assert!(
                    (got - hit[c]).abs() <= 1e-5 * hit[c].abs().max(1.0),
                    "({i}, {j}) c{c}: {got} vs {}",
                    hit[c]
                );
                let (fx, fy) = (dx[c] / (2.0 * h), dy[c] / (2.0 * h));
                let tol = 1e-3 * (fx.abs() + fy.abs()) + 1e-6;
                assert!((f64::from(f.ddx_of(c)[k]) - fx).abs() <= tol, "ddx ({i}, {j}) c{c}");
                assert!((f64::from(f.ddy_of(c)[k]) - fy).abs() <= tol, "ddy ({i}, {j}) c{c}");
            }
            // Farther rows are higher up the image: z grows (towards 0) going down.
            assert!(f.ddy_of(1)[k] > 0.0);
            // The flat id is the first vertex of the triangle, with no derivative.
            let tri_first = if f.values_of(2)[k] == 0.0 { 0.0 } else { 2.0 };
            assert_eq!((f.values_of(2)[k], f.ddx_of(2)[k], f.ddy_of(2)[k]), (tri_first, 0.0, 0.0));
            let depth = cam.project([hit[0], -1.0, hit[1]]);
            assert!((f.depth[k] - depth[2] / depth[3]).abs() < 1e-5);
        }
    }
}

trait Diff {
    fn map2(self, other: Self) -> Self;
}

impl Diff for [f64; 2] {
    fn map2(self, other: Self) -> Self {
        [self[0] - other[0], self[1] - other[1]]
    }
}

#[test]
fn derivatives_match_finite_differences_of_the_quotient_formula() {
    let mut fb = Framebuffer::new(40, 30, [0.0; 4]);
    let clip = [[-0.9f32, -0.8, 0.1, 1.0], [2.2, -0.4, 1.0, 2.5], [0.3, 3.3, 2.0, 4.0]];
    let data = [1.0f32, -3.0, 0.25, 5.0, 2.0, 0.5, -2.0, 7.0, 0.75];
    let varyings = Varyings::smooth(3, &data);
    let (_, batches) = run(&mut fb, &clip, &[0, 1, 2], &varyings, &DrawOptions::default(), |_, _| HALF);
    // Screen positions from the clip coordinates, then (Σ λ a / w) / (Σ λ / w), in f64.
    let s = clip.map(|v| {
        let (x, y, w) = (f64::from(v[0]), f64::from(v[1]), f64::from(v[3]));
        ((x / w + 1.0) * 20.0, (1.0 - y / w) * 15.0, w)
    });
    let interp = |x: f64, y: f64, c: usize| {
        let area = |a: (f64, f64, f64), b: (f64, f64, f64), px: f64, py: f64| {
            (b.0 - a.0) * (py - a.1) - (b.1 - a.1) * (px - a.0)
        };
        let lambda = [area(s[1], s[2], x, y), area(s[2], s[0], x, y), area(s[0], s[1], x, y)];
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..3 {
            num += lambda[i] * f64::from(data[i * 3 + c]) / s[i].2;
            den += lambda[i] / s[i].2;
        }
        num / den
    };
    let h = 1e-3;
    let mut checked = 0;
    for f in &batches {
        for k in 0..f.count {
            let (x, y) = (f64::from(f.pixels[k].0) + 0.5, f64::from(f.pixels[k].1) + 0.5);
            for c in 0..3 {
                let v = interp(x, y, c);
                assert!((f64::from(f.values_of(c)[k]) - v).abs() <= 1e-5 * v.abs().max(1.0));
                let fx = (interp(x + h, y, c) - interp(x - h, y, c)) / (2.0 * h);
                let fy = (interp(x, y + h, c) - interp(x, y - h, c)) / (2.0 * h);
                let (gx, gy) = (f64::from(f.ddx_of(c)[k]), f64::from(f.ddy_of(c)[k]));
                assert!((gx - fx).abs() <= 1e-3 * fx.abs().max(1e-3), "ddx {gx} vs {fx}");
                assert!((gy - fy).abs() <= 1e-3 * fy.abs().max(1e-3), "ddy {gy} vs {fy}");
                checked += 1;
            }
        }
    }
    assert!(checked > 500);
}

/// Flat-coloured triangles at distinct constant depths, overlapping.
fn overlapping(rng: &mut Rng, n: usize) -> (Vec<[f32; 4]>, Vec<f32>) {
    let mut clip = Vec::new();
    let mut colours = Vec::new();
    for t in 0..n {
        let z = (t as f32 + 0.5) / n as f32;
        let z = if t % 2 == 0 { z } else { 1.0 - z };
        for _ in 0..3 {
            let w = (0.5 + rng.next()) as f32;
            clip.push([(rng.next() * 2.4 - 1.2) as f32 * w, (rng.next() * 2.4 - 1.2) as f32 * w, z * w, w]);
            colours.extend([t as f32 / n as f32, rng.next() as f32, 0.5, 0.75]);
        }
    }
    (clip, colours)
}

#[test]
fn depth_testing_makes_draw_order_irrelevant_for_opaque_triangles() {
    let mut rng = Rng(3);
    let (clip, colours) = overlapping(&mut rng, 24);
    let varyings = Varyings { components: 4, data: &colours, flat: &[true; 4] };
    let forward: Vec<u32> = (0..clip.len() as u32).collect();
    let backward: Vec<u32> = forward.chunks(3).rev().flatten().copied().collect();
    let colour = |f: &Fragments, k: usize| std::array::from_fn(|c| f.values_of(c)[k]);
    let image = |indices: &[u32], batch: usize| {
        let mut fb = Framebuffer::new(48, 40, [0.0; 4]);
        let options = DrawOptions { batch, ..DrawOptions::default() };
        let (stats, _) = run(&mut fb, &clip, indices, &varyings, &options, colour);
        (fb, stats)
    };
    let (a, sa) = image(&forward, 128);
    let (b, sb) = image(&backward, 128);
    assert_eq!(a, b);
    assert!(sa.occluded > 100 && sb.occluded > 100, "{sa:?} {sb:?}");
    assert_eq!(image(&forward, 1).0, a);
    assert_eq!(image(&backward, 7).0, a);
}

#[test]
fn blending_order_is_kept_whatever_the_batch_size() {
    let mut rng = Rng(5);
    let (clip, colours) = overlapping(&mut rng, 30);
    let varyings = Varyings { components: 4, data: &colours, flat: &[true; 4] };
    let indices: Vec<u32> = (0..clip.len() as u32).collect();
    let premultiplied = |f: &Fragments, k: usize| {
        let a = f.values_of(3)[k] * 0.6;
        [f.values_of(0)[k] * a, f.values_of(1)[k] * a, f.values_of(2)[k] * a, a]
    };
    // One fragment at a time is the definition; every batch size must give the same bits.
    let image = |batch: usize, depth_write: bool| {
        let mut fb = Framebuffer::new(32, 32, [0.1, 0.2, 0.3, 1.0]);
        let options = DrawOptions { blend: Blend::PremultipliedOver, depth_write, batch };
        let (_, batches) = run(&mut fb, &clip, &indices, &varyings, &options, premultiplied);
        for b in &batches {
            assert!(b.count <= batch);
            let mut pixels = b.pixels.clone();
            pixels.sort();
            pixels.dedup();
            assert_eq!(pixels.len(), b.count, "a pixel twice in one batch");
        }
        fb
    };
    for depth_write in [false, true] {
        let reference = image(1, depth_write);
        for batch in [2, 9, 128, 1000] {
            assert_eq!(image(batch, depth_write), reference, "batch {batch}");
        }
    }
}

/// Ray-triangle intersection (Möller–Trumbore) in view space: (t, barycentrics of b and c).
fn ray_hit(d: [f64; 3], tri: [[f64; 3]; 3]) -> Option<(f64, f64, f64)> {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (e1, e2) = (sub(tri[1], tri[0]), sub(tri[2], tri[0]));
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-12 {
        return None;
    }
    let s = sub([0.0; 3], tri[0]);
    let u = dot(s, p) / det;
    let q = cross(s, e1);
    let v = dot(d, q) / det;
    Some((dot(e2, q) / det, u, v))
}

#[test]
fn a_triangle_through_the_near_plane_keeps_its_visible_part() {
    let cam = Camera { focal: 1.0, near: 1.0, far: 100.0, width: 64, height: 64 };
    // The apex is behind the eye (w = -1); the near plane z = -1 cuts the triangle along y = 0.
    let tri = [[-3.0, -2.0, -3.0], [3.0, -2.0, -3.0], [0.0, 2.0, 1.0]];
    let clip = tri.map(|p| cam.project(p));
    assert!(clip[2][3] < 0.0);
    let data: Vec<f32> = tri.iter().flatten().map(|&c| c as f32).collect();
    let mut fb = Framebuffer::new(64, 64, [0.0; 4]);
    let (stats, batches) =
        run(&mut fb, &clip, &[0, 1, 2], &Varyings::smooth(3, &data), &DrawOptions::default(), |_, _| HALF);
    assert_eq!(stats.clipped, 1);
    let n = counts(&fb, &batches);
    let (mut covered, mut empty) = (0, 0);
    for j in 0..64u32 {
        for i in 0..64u32 {
            let d = cam.ray(f64::from(i) + 0.5, f64::from(j) + 0.5);
            let (t, u, v) = ray_hit(d, tri).unwrap();
            let z = -t;
            let margins = [u, v, 1.0 - u - v, -cam.near - z];
            if margins.iter().any(|m| m.abs() < 1e-3) {
                continue;
            }
            let expected = u32::from(margins.iter().all(|&m| m > 0.0) && t > 0.0);
            assert_eq!(n[(j * 64 + i) as usize], expected, "pixel ({i}, {j})");
            if expected == 1 { covered += 1 } else { empty += 1 }
        }
    }
    // The cut is the horizontal line through the centre: the lower half only, all of it visible.
    assert!(covered > 600 && empty > 1500, "{covered} {empty}");
    assert!(batches.iter().flat_map(|b| &b.pixels).all(|&(_, y)| y >= 32));
    // Values are those of the unclipped triangle: the world position the ray hits.
    for f in &batches {
        for k in 0..f.count {
            let d = cam.ray(f64::from(f.pixels[k].0) + 0.5, f64::from(f.pixels[k].1) + 0.5);
            let (t, _, _) = ray_hit(d, tri).unwrap();
            for (c, d) in d.iter().enumerate() {
                let expected = t * d;
                assert!((f64::from(f.values_of(c)[k]) - expected).abs() < 1e-4 * expected.abs().max(1.0));
            }
        }
    }
}

#[test]
fn facing_follows_winding_in_clip_space() {
    let mut fb = Framebuffer::new(8, 8, [0.0; 4]);
    // Counter-clockwise with y up: front facing.
    let clip = [[-1.0, -1.0, 0.5, 1.0], [1.0, -1.0, 0.5, 1.0], [-1.0, 1.0, 0.5, 1.0]];
    let facing = |indices: &[u32]| {
        let mut fb = fb.clone();
        let (_, b) = run(&mut fb, &clip, indices, &Varyings::none(), &DrawOptions::default(), |_, _| HALF);
        let all: Vec<bool> = b.iter().flat_map(|b| b.front_facing.clone()).collect();
        assert!(!all.is_empty());
        all
    };
    assert!(facing(&[0, 1, 2]).iter().all(|&f| f));
    assert!(facing(&[0, 2, 1]).iter().all(|&f| !f));
    let stats =
        draw(&mut fb, &clip, &[0, 2, 1], &Varyings::none(), &DrawOptions::default(), |_, _| Ok::<(), ()>(()));
    // Half of the 8×8 square below the diagonal y = x; its centres are on a right edge: not drawn.
    assert_eq!(stats.map(|s| s.fragments), Ok(28));
}

#[test]
fn bad_input_is_an_error_or_skipped_never_a_panic() {
    let ok = |_: &Fragments, _: &mut [[f32; 4]]| Ok::<(), ()>(());
    let opts = DrawOptions::default();
    let mut fb = Framebuffer::new(8, 8, [0.0; 4]);
    let good = [[-1.0, -1.0, 0.5, 1.0], [1.0, -1.0, 0.5, 1.0], [-1.0, 1.0, 0.5, 1.0]];
    let none = Varyings::none();
    assert_eq!(draw(&mut fb, &[], &[], &none, &opts, ok), Ok(DrawStats::default()));
    assert_eq!(
        draw(&mut fb, &good, &[0, 1, 3], &none, &opts, ok),
        Err(DrawError::IndexOutOfRange { position: 2, index: 3, vertices: 3 })
    );
    assert_eq!(fb, Framebuffer::new(8, 8, [0.0; 4]));
    let short = Varyings::smooth(2, &[1.0; 5]);
    assert_eq!(
        draw(&mut fb, &good, &[0, 1, 2], &short, &opts, ok),
        Err(DrawError::Varyings { expected: 6, found: 5 })
    );
    let mask = Varyings { components: 2, data: &[1.0; 6], flat: &[true] };
    assert!(matches!(draw(&mut fb, &good, &[0, 1, 2], &mask, &opts, ok), Err(DrawError::Varyings { .. })));
    let mut broken = fb.clone();
    broken.depth.pop();
    assert!(matches!(
        draw(&mut broken, &good, &[0, 1, 2], &none, &opts, ok),
        Err(DrawError::Framebuffer { .. })
    ));

    // NaN, infinite, zero-w, behind-the-eye and collinear triangles are skipped; a trailing
    // incomplete triangle is ignored; huge but finite coordinates are clipped without overflow.
    let nan = f32::NAN;
    let clip = [
        good[0],
        good[1],
        [nan, 0.0, 0.5, 1.0],
        good[0],
        good[1],
        [f32::INFINITY, 0.0, 0.5, 1.0],
        [0.0; 4],
        [0.0; 4],
        [0.0; 4],
        [0.0, 0.0, 0.5, -1.0],
        [1.0, 0.0, 0.5, -1.0],
        [0.0, 1.0, 0.5, -1.0],
        [0.0, 0.0, 0.5, 1.0],
        [0.5, 0.5, 0.5, 1.0],
        [1.0, 1.0, 0.5, 1.0],
        [-3e38, -3e38, 0.5, 1.0],
        [3e38, -3e38, 0.5, 1.0],
        [0.0, 3e38, 0.5, 1e-30],
    ];
    let indices: Vec<u32> = (0..clip.len() as u32).chain([0, 1]).collect();
    let data: Vec<f32> = (0..clip.len()).map(|i| i as f32).collect();
    let mut fb = Framebuffer::new(8, 8, [0.0; 4]);
    let (stats, batches) = run(&mut fb, &clip, &indices, &Varyings::smooth(1, &data), &opts, |f, k| {
        [f.values_of(0)[k], f.ddx_of(0)[k], f.ddy_of(0)[k], f.depth[k]]
    });
    assert_eq!((stats.triangles, stats.invalid), (6, 2));
    assert!(stats.culled + stats.degenerate >= 3, "{stats:?}");
    assert!(batches.iter().all(|b| b.pixels.iter().all(|&(x, y)| x < 8 && y < 8)));
    assert!(fb.color.iter().flatten().chain(&fb.depth).all(|c| c.is_finite()));
}

#[test]
fn a_shading_error_stops_the_draw() {
    let mut fb = Framebuffer::new(8, 8, [0.0; 4]);
    let clip = [[-1.0, -1.0, 0.5, 1.0], [1.0, -1.0, 0.5, 1.0], [-1.0, 1.0, 0.5, 1.0]];
    let result =
        draw(&mut fb, &clip, &[0, 1, 2], &Varyings::none(), &DrawOptions::default(), |_, _| Err("no"));
    assert_eq!(result, Err(DrawError::Shade("no")));
}

#[test]
fn geometry_beyond_the_far_plane_or_outside_the_view_is_culled() {
    let mut fb = Framebuffer::new(8, 8, [0.0; 4]);
    let far = [[-1.0, -1.0, 1.5, 1.0], [1.0, -1.0, 1.5, 1.0], [-1.0, 1.0, 1.5, 1.0]];
    let left = [[-3.0, -1.0, 0.5, 1.0], [-2.0, -1.0, 0.5, 1.0], [-3.0, 1.0, 0.5, 1.0]];
    let clip: Vec<_> = far.iter().chain(&left).copied().collect();
    let stats =
        draw(&mut fb, &clip, &[0, 1, 2, 3, 4, 5], &Varyings::none(), &DrawOptions::default(), |_, _| {
            Ok::<(), ()>(())
        });
    // The left one is inside the guard band: drawn, but it covers no pixel.
    assert_eq!(stats.map(|s| (s.culled, s.fragments)), Ok((1, 0)));
}
