//! Gallery scenes of surface patterns (no ray marching): `noise_panel` (seed-digest §12 S1, a
//! z-slice of every noise of the standard library), `brick_filtering` (Peachey's brick wall,
//! aliased beside box-filtered), `star` (Peachey's five-pointed star) and `planet` (Musgrave's
//! multifractal terrain on a sphere). Each scene is rendered small on both backends and compared
//! with the default thresholds; each has its own checks on the CPU reference's image.
//!
//! Run with `--nocapture` to see the measured statistics.

use crate::support;

use patina_runtime::image::{Image, Thresholds, compare};
use support::gallery::{at, both, covered, cpu, scene, set};

/// Renders `scene` on both backends (compared with the default thresholds) and returns the CPU
/// reference's image; without a GPU (`PATINA_GPU=off`) only the CPU image.
fn reference(label: &str, scene: &patina_runtime::scene::Scene) -> Image {
    let start = std::time::Instant::now();
    let image = match both(label, scene, Thresholds::default()) {
        Some(r) => {
            println!("{label}: GPU vs CPU {:?}", r.comparison);
            r.cpu
        }
        None => cpu(label, scene),
    };
    println!("{label}: rendered in {:.1} s", start.elapsed().as_secs_f64());
    image
}

/// Renders a scene of one object over `background` on both backends, compares the whole image
/// with `silhouette` thresholds and the object's interior (pixels whose 3 x 3 neighbourhood is
/// covered in both images) with the default ones, and returns the CPU reference's image. The
/// looser whole-image thresholds are for the silhouette: a pixel centre within rounding of a
/// silhouette may be covered by one rasterizer and not the other, and there the GPU's screen
/// derivatives (differences across a 2 x 2 quad, helper invocations off the surface) are not the
/// CPU's analytic ones.
fn reference_interior(
    label: &str,
    scene: &patina_runtime::scene::Scene,
    background: [f32; 4],
    silhouette: Thresholds,
) -> Image {
    let start = std::time::Instant::now();
    let Some(r) = both(label, scene, silhouette) else { return cpu(label, scene) };
    println!("{label}: GPU vs CPU {:?} ({:.1} s)", r.comparison, start.elapsed().as_secs_f64());
    let is_covered = |image: &Image, x: u32, y: u32| {
        at(image, x, y).iter().zip(background).any(|(a, b)| (a - b).abs() > 1e-3)
    };
    let (w, h) = (r.cpu.width, r.cpu.height);
    let interior = |x: u32, y: u32| {
        x > 0
            && y > 0
            && x + 1 < w
            && y + 1 < h
            && (x - 1..=x + 1)
                .all(|i| (y - 1..=y + 1).all(|j| is_covered(&r.cpu, i, j) && is_covered(&r.gpu, i, j)))
    };
    let mask = |image: &Image| Image {
        width: w,
        height: h,
        pixels: (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| if interior(x, y) { at(image, x, y) } else { background })
            .collect(),
    };
    let t = Thresholds::default();
    let c = compare(&mask(&r.cpu), &mask(&r.gpu), &t).unwrap();
    println!("{label}: interior GPU vs CPU {c:?}");
    assert!(c.passes(&t), "{label}: interior pixels differ: {c:?}");
    r.cpu
}

/// Mean and standard deviation.
fn mean_sd(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let m = xs.iter().sum::<f64>() / n;
    let v = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / n;
    (m, v.sqrt())
}

/// The `q`-quantile (0..=1) of `xs`.
fn quantile(xs: &[f64], q: f64) -> f64 {
    let mut v = xs.to_vec();
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

// ---------------------------------------------------------------------------------------------
// noise_panel (seed-digest §12 S1)

/// The panel's layout and each tile's grey mapping `offset + gain * value`, as in
/// examples/shaders/noise_panel.sl (tile index 6 row + column).
const COLUMNS: u32 = 6;
const ROWS: u32 = 5;
const TILES: [(&str, f64, f64); 30] = [
    ("snoise3", 0.5, 0.5),
    ("noise3", 0.0, 1.0),
    ("snoise2", 0.5, 0.5),
    ("psnoise3", 0.5, 0.5),
    ("flownoise3", 0.5, 0.5),
    ("snoise4", 0.5, 0.6),
    ("vnoise", 0.5, 0.4),
    ("vnoise_linear", 0.5, 0.5),
    ("gnoise", 0.5, 0.85),
    ("vgnoise", 0.5, 0.7),
    ("vcnoise", 0.5, 0.38),
    ("scnoise", 0.5, 0.7),
    ("cellnoise3", 0.0, 1.0),
    ("worley_f1", 0.0, 0.5),
    ("worley_f2_f1", 0.0, 1.0),
    ("worley_manhattan_f1", 0.0, 0.33),
    ("distnoise", 0.5, 0.5),
    ("distfbm", 0.5, 0.45),
    ("fbm", 0.5, 0.45),
    ("fbm_filtered", 0.5, 0.45),
    ("turbulence", 0.0, 1.2),
    ("ridged_multifractal", 0.0, 0.5),
    ("hybrid_multifractal", 0.0, 0.3),
    ("hetero_terrain", 0.3, 0.3),
    ("perlin_noise3", 0.5, 0.6),
    ("snoise1", 0.5, 0.5),
    ("noise2", 0.0, 1.0),
    ("pnoise3", 0.0, 1.0),
    ("vsnoise3 x", 0.5, 0.5),
    ("dsnoise3 x", 0.5, 0.25),
];

/// One tile's pixels: (x, y, grey) for every pixel of the tile that is not gutter.
struct Tile {
    pixels: Vec<(u32, u32, f64)>,
}

impl Tile {
    fn greys(&self) -> Vec<f64> {
        self.pixels.iter().map(|p| p.2).collect()
    }

    /// The values the shader mapped to grey, read back through the tile's mapping.
    fn values(&self, k: usize) -> Vec<f64> {
        let (_, offset, gain) = TILES[k];
        self.pixels.iter().map(|p| (p.2 - offset) / gain).collect()
    }

    fn grey_at(&self, x: u32, y: u32) -> Option<f64> {
        self.pixels.iter().find(|p| p.0 == x && p.1 == y).map(|p| p.2)
    }

    /// The mean square difference between horizontally adjacent pixels of the tile.
    fn roughness(&self) -> f64 {
        let pairs: Vec<f64> = self
            .pixels
            .iter()
            .filter_map(|&(x, y, g)| self.grey_at(x + 1, y).map(|h| (h - g) * (h - g)))
            .collect();
        pairs.iter().sum::<f64>() / pairs.len() as f64
    }
}

/// Splits the panel's image into its tiles by pixel centre ((s, t) = ((x + 0.5) / W, (y + 0.5) /
/// H): the plane fills the image). Gutter pixels are blue, tile pixels grey (R = G = B); a grey
/// pixel in a gutter position, or a tile without pixels, fails.
fn tiles(image: &Image) -> Vec<Tile> {
    let mut tiles: Vec<Tile> = (0..COLUMNS * ROWS).map(|_| Tile { pixels: Vec::new() }).collect();
    for y in 0..image.height {
        for x in 0..image.width {
            let p = at(image, x, y);
            let cs = (x as f64 + 0.5) / image.width as f64 * COLUMNS as f64;
            let ct = (y as f64 + 0.5) / image.height as f64 * ROWS as f64;
            let (col, row) = (cs.floor(), ct.floor());
            let (u, v) = (cs - col, ct - row);
            let edge = u.min(1.0 - u).min(v).min(1.0 - v);
            let grey = p[0] == p[1] && p[1] == p[2];
            // The shader's gutter is 0.05 of a tile: a pixel centre well inside is a tile pixel,
            // one well inside the gutter is blue (the margin covers the centres' rounding).
            if edge > 0.051 {
                assert!(grey, "pixel ({x}, {y}) inside a tile is not grey: {p:?}");
                tiles[(row as u32 * COLUMNS + col as u32) as usize].pixels.push((x, y, p[0] as f64));
            } else if edge < 0.049 {
                assert!(!grey, "pixel ({x}, {y}) in the gutter is grey: {p:?}");
            }
        }
    }
    for (k, tile) in tiles.iter().enumerate() {
        assert!(tile.pixels.len() >= 100, "tile {k} ({}) has {} pixels", TILES[k].0, tile.pixels.len());
    }
    tiles
}

#[test]
fn noise_panel() {
    // 72 x 60 keeps the panel's 6:5 (tiles of 12 x 12 pixels, about 100 inside the gutter); 6
    // cells per tile side (2 pixels per cell), so that a tile holds 36 cells; 2 octaves. (The
    // interpreter evaluates five of the lattice and cellular noises at every pixel, see the
    // shader, which makes this scene slow in the debug profile.)
    let mut s = scene("noise_panel", 72, 60);
    set(&mut s, &[0], "octaves", 2.0);
    set(&mut s, &[0], "frequency", 6.0);
    let image = reference("noise_panel", &s);
    let tiles = tiles(&image);

    // Every tile is finite (checked by `reference`), uses a visible grey range (not constant,
    // neither black nor white), and lies within [0, 1] but for a few outliers.
    for (k, tile) in tiles.iter().enumerate() {
        let g = tile.greys();
        let (lo, hi) = (quantile(&g, 0.02), quantile(&g, 0.98));
        let (mean, sd) = mean_sd(&g);
        println!("tile {k:2} {:20} grey 2%..98% [{lo:.3}, {hi:.3}] mean {mean:.3} sd {sd:.3}", TILES[k].0);
        assert!(hi - lo > 0.2, "tile {k} ({}): grey range [{lo}, {hi}] too narrow", TILES[k].0);
        assert!(lo > -0.02 && hi < 1.02, "tile {k} ({}): grey range [{lo}, {hi}] outside [0, 1]", TILES[k].0);
        assert!((0.15..0.85).contains(&mean), "tile {k} ({}): mean grey {mean}", TILES[k].0);
    }

    // Signed gradient noises (0 at every lattice point, the gradients symmetric): the mean is
    // near 0. One tile holds 36 cells: taking cells as independent samples, the standard error
    // of a tile's mean is sd / 6, and of the mean of the eight tiles' standardized means
    // 1 / sqrt(8 * 36) = 0.059; the pooled mean must be within 3.4 of those, 0.2, and each tile's
    // within one sd (a tile's cells are not quite independent: the largest measured is 0.47 sd).
    // The value noises have non-zero lattice values and are left out.
    let mut pooled = 0.0;
    let signed = [0, 2, 3, 4, 5, 8, 24, 28];
    for k in signed {
        let (mean, sd) = mean_sd(&tiles[k].values(k));
        println!("{:12} mean {mean:+.4} sd {sd:.4} ({:+.3} sd)", TILES[k].0, mean / sd);
        assert!(mean.abs() < sd, "{}: mean {mean} with sd {sd}", TILES[k].0);
        pooled += mean / sd / signed.len() as f64;
    }
    println!("signed gradient noises: pooled standardized mean {pooled:+.4}");
    assert!(pooled.abs() < 0.2, "signed gradient noises: pooled standardized mean {pooled}");
    // Tiles 0 and 1 sample the same points: noise3 = (1 + snoise3) / 2 pixel for pixel, in [0, 1].
    let tile_width = image.width / COLUMNS;
    let mut largest = 0.0f64;
    for &(x, y, g) in &tiles[1].pixels {
        let signed = tiles[0].grey_at(x - tile_width, y).map(|h| (h - 0.5) / 0.5).expect("same layout");
        assert!((0.0..=1.0).contains(&g), "noise3 {g} outside [0, 1]");
        largest = largest.max((g - (1.0 + signed) / 2.0).abs());
    }
    println!("noise3 - (1 + snoise3) / 2: largest {largest:.2e}");
    // The two tiles' points agree up to the rounding of 6 s - column (about 1e-6 of a tile,
    // times 6 cells and the noise's slope).
    assert!(largest < 1e-4, "noise3 is not (1 + snoise3) / 2: {largest}");
    // cellnoise: in [0, 1).
    assert!(tiles[12].values(12).iter().all(|v| (0.0..1.0).contains(v)), "cellnoise outside [0, 1)");
    // Worley: F1 >= 0 and F2 - F1 >= 0; tiles 13 and 15 sample the same points, and the
    // Manhattan distance to the nearest point is at least the Euclidean one.
    assert!(tiles[13].values(13).iter().all(|&v| v >= 0.0), "F1 < 0");
    assert!(tiles[14].values(14).iter().all(|&v| v >= 0.0), "F2 - F1 < 0");
    let mut closest = f64::INFINITY;
    for &(x, y, g) in &tiles[13].pixels {
        let manhattan = tiles[15].grey_at(x + 2 * tile_width, y).expect("same layout") / TILES[15].2;
        closest = closest.min(manhattan - g / TILES[13].2);
    }
    println!("Manhattan F1 - Euclidean F1: smallest {closest:.4}");
    assert!(closest >= -1e-4, "Manhattan F1 below Euclidean F1 by {closest}");
    // Turbulence is a sum of |noise|: never negative.
    assert!(tiles[20].values(20).iter().all(|&v| v >= 0.0), "turbulence < 0");
    // Periodic noise of period 2 cells: a shift by 2 cells is 2 / 6 of a tile, 4 pixels; the
    // value repeats up to the rounding of the coordinates.
    let periodic = &tiles[3];
    let mut largest = 0.0f64;
    let mut pairs = 0;
    for &(x, y, g) in &periodic.pixels {
        for (dx, dy) in [(4, 0), (0, 4)] {
            if let Some(h) = periodic.grey_at(x + dx, y + dy) {
                largest = largest.max((h - g).abs());
                pairs += 1;
            }
        }
    }
    println!("psnoise3 period 2: largest difference over {pairs} pairs a period apart {largest:.2e}");
    assert!(pairs > 100 && largest < 1e-4, "psnoise3 is not periodic: {largest} over {pairs} pairs");
    // The filtered fBm drops the octaves finer than a pixel (here 0.5 cells per pixel: it keeps
    // one octave of the two), so it is smoother from pixel to pixel than the plain fBm.
    let (rough, smooth) = (tiles[18].roughness(), tiles[19].roughness());
    println!("fbm adjacent-pixel mean square difference {rough:.5}, fbm_filtered {smooth:.5}");
    assert!(smooth < 0.7 * rough, "fbm_filtered {smooth} not smoother than fbm {rough}");
}

// ---------------------------------------------------------------------------------------------
// brick_filtering (Peachey's brick, T&M ch. 2)

/// The luminance-like mean of a pixel's colour channels.
fn grey(p: [f32; 4]) -> f64 {
    (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0
}

/// The far band of one strip: the pixels of columns `columns` covered by the strip (not the
/// background) in the rows from the horizon (the strip's top row) down to `depth` of the strip's
/// rows. Returns (pixels, mean square difference of horizontally adjacent covered pixels).
fn far_band(
    image: &Image,
    columns: std::ops::Range<u32>,
    depth: f64,
    background: [f32; 4],
) -> (Vec<[f32; 4]>, f64) {
    let is_strip = |x: u32, y: u32| at(image, x, y).iter().zip(background).any(|(a, b)| (a - b).abs() > 1e-3);
    let rows: Vec<u32> = (0..image.height).filter(|&y| columns.clone().any(|x| is_strip(x, y))).collect();
    let (top, bottom) = (rows[0], *rows.last().unwrap());
    let last = top + ((bottom - top) as f64 * depth) as u32;
    let mut pixels = Vec::new();
    let mut diffs = Vec::new();
    for y in top..=last {
        for x in columns.clone() {
            if !is_strip(x, y) {
                continue;
            }
            pixels.push(at(image, x, y));
            if x + 1 < columns.end && is_strip(x + 1, y) {
                let d = grey(at(image, x + 1, y)) - grey(at(image, x, y));
                diffs.push(d * d);
            }
        }
    }
    let roughness = diffs.iter().sum::<f64>() / diffs.len() as f64;
    (pixels, roughness)
}

#[test]
fn brick_filtering() {
    let background = [0.55, 0.7, 0.9, 1.0];
    let s = scene("brick_filtering", 96, 72);
    // The box filter's width comes from screen derivatives: analytic on the CPU, differences
    // across the 2x2 pixel quad on the GPU, which on this steeply receding strip differ by a few
    // percent (near the horizon s and t change non-linearly from pixel to pixel); where a mortar
    // edge falls inside the filter the filtered values then differ (measured: at most 0.0146,
    // 486 pixels above 0.004, all on the filtered strip: 14% of it, 7% of the image). The
    // filtered strip is compared with that allowance (hard 0.02, 16%), the whole image with 8%,
    // and the point-sampled strip with the default thresholds (measured: 1.2e-7).
    let loose = Thresholds { fail: 0.004, hard_fail: 0.02, max_failing_fraction: 0.08 };
    let strip = Thresholds { max_failing_fraction: 0.16, ..loose };
    let image = match both("brick_filtering", &s, loose) {
        Some(r) => {
            println!("brick_filtering: GPU vs CPU {:?}", r.comparison);
            let half = |image: &Image, right: bool| {
                let w = image.width / 2;
                let pixels = (0..image.height)
                    .flat_map(|y| (0..w).map(move |x| (x + if right { w } else { 0 }, y)))
                    .map(|(x, y)| at(image, x, y))
                    .collect();
                Image { width: w, height: image.height, pixels }
            };
            for (right, t) in [(false, Thresholds::default()), (true, strip)] {
                let c = compare(&half(&r.cpu, right), &half(&r.gpu, right), &t).unwrap();
                println!("  {} strip: {c:?}", if right { "filtered" } else { "point-sampled" });
                assert!(c.passes(&t), "brick_filtering, right half {right}: {c:?}");
            }
            r.cpu
        }
        None => cpu("brick_filtering", &s),
    };
    let half = image.width / 2;
    // The far half of each strip (in rows, from the horizon down), where a pixel spans several
    // bricks.
    let (aliased, rough_aliased) = far_band(&image, 0..half, 0.5, background);
    let (filtered, rough_filtered) = far_band(&image, half..image.width, 0.5, background);
    let var = |px: &[[f32; 4]]| mean_sd(&px.iter().map(|&p| grey(p)).collect::<Vec<_>>()).1.powi(2);
    let (var_aliased, var_filtered) = (var(&aliased), var(&filtered));
    println!(
        "far band: aliased {} px, variance {var_aliased:.5}, adjacent mean square {rough_aliased:.5}; \
         filtered {} px, variance {var_filtered:.5}, adjacent mean square {rough_filtered:.5}",
        aliased.len(),
        filtered.len()
    );
    assert!(aliased.len() > 200 && filtered.len() > 200);
    // Measured ratios: 0.056 (adjacent differences) and 0.030 (variance).
    assert!(rough_filtered < 0.25 * rough_aliased, "filtered {rough_filtered} vs aliased {rough_aliased}");
    assert!(var_filtered < 0.25 * var_aliased, "filtered {var_filtered} vs aliased {var_aliased}");

    // Far away the box filter returns the mean of the pattern: the brick's area fraction
    // f = bw bh / ((bw + m)(bh + m)) of brick colour, the rest mortar, times the lighting of the
    // flat floor (ambient 0.3 + 0.9 N.L, with N = +y and L towards (1, 3, -2)). Measured within
    // 5e-4; the band's ends cut bricks, so 0.003 is allowed. (The point-sampled strip is off by
    // 0.022 in green and blue: aliasing also biases the mean.)
    let (bw, bh, m) = (0.25, 0.08, 0.02);
    let f = bw * bh / ((bw + m) * (bh + m));
    let light = 0.3 + 0.9 * 3.0 / 14f64.sqrt();
    let (brick, mortar) = ([0.5, 0.15, 0.14], [0.5, 0.5, 0.5]);
    for c in 0..3 {
        let expected = light * (mortar[c] + f * (brick[c] - mortar[c]));
        let mean = filtered.iter().map(|p| p[c] as f64).sum::<f64>() / filtered.len() as f64;
        let mean_aliased = aliased.iter().map(|p| p[c] as f64).sum::<f64>() / aliased.len() as f64;
        println!(
            "channel {c}: far-band mean filtered {mean:.4}, aliased {mean_aliased:.4}, area mean {expected:.4}"
        );
        assert!(
            (mean - expected).abs() < 0.003,
            "channel {c}: filtered far mean {mean}, expected {expected}"
        );
    }

    // The knob: 4 x 4 point samples per pixel on the aliased strip (CPU only) cut its far-band
    // variation towards the filtered strip's.
    let mut s4 = scene("brick_filtering", 96, 72);
    set(&mut s4, &[0], "samples", 4.0);
    let image4 = cpu("brick_filtering samples 4", &s4);
    let (_, rough4) = far_band(&image4, 0..half, 0.5, background);
    println!("aliased strip with 4 x 4 samples: adjacent mean square {rough4:.5}");
    assert!(rough4 < 0.5 * rough_aliased, "samples 4: {rough4} vs 1: {rough_aliased}");
}

// ---------------------------------------------------------------------------------------------
// star (Peachey, T&M ch. 2)

#[test]
fn star_ball() {
    let s = scene("star", 96, 96);
    // Measured: 4 silhouette pixels differ by up to 0.395 (one backend covers the pixel centre,
    // the other not, or the GPU's quad derivative there spans the background), none inside.
    let silhouette = Thresholds { hard_fail: 0.4, ..Thresholds::default() };
    let image = reference_interior("star", &s, [0.08, 0.08, 0.12, 1.0], silhouette);
    // The star faces the camera: at the centre the colour is starcolor (1, 0.5161, 0) times the
    // lighting, the ball's side blue (Cs).
    let centre = at(&image, 48, 48);
    println!("star: centre {centre:?}, ball coverage {:.3}", covered(&image, [0.08, 0.08, 0.12, 1.0]));
    assert!((centre[1] / centre[0] - 0.5161).abs() < 1e-4 && centre[2] == 0.0, "centre {centre:?}");
    let side = at(&image, 20, 48);
    assert!(side[2] > side[0], "ball side {side:?}");
}

/// The flat test render of the star: its shader on a plane filling the image (s, t in [0, 1]),
/// lit by the ambient light alone at intensity 1, Cs black, so that the red channel is the
/// coverage (starcolor's red is 1).
fn flat_star(size: u32, rmax: f64, rmin: f64, samples: f64) -> Image {
    let mut s = scene("star", size, size);
    s.camera.from = glam::Vec3::new(0.0, 0.0, -2.0);
    s.camera.to = glam::Vec3::ZERO;
    s.camera.fov_y_degrees = 2.0 * 0.5f32.atan().to_degrees();
    let o = &mut s.objects[0];
    o.mesh = patina_runtime::scene::MeshSource::Plane;
    o.transform.clear();
    o.color = [0.0; 3];
    s.lights.retain(|l| l.shader.name.as_deref() == Some("ambientlight"));
    s.lights[0].shader.params.insert("intensity".into(), patina_runtime::scene::ParamValue::Number(1.0));
    set(&mut s, &[0], "Kd", 0.0);
    set(&mut s, &[0], "saspect", 1.0);
    set(&mut s, &[0], "rmax", rmax);
    set(&mut s, &[0], "rmin", rmin);
    set(&mut s, &[0], "samples", samples);
    cpu("star (flat)", &s)
}

#[test]
fn star_area() {
    // A regular pentagram: inner radius rmax cos(2 pi / 5) / cos(pi / 5). Its area is that of
    // 2n triangles (centre, tip, inner vertex): n rmax rmin sin(pi / n).
    let n = 5.0;
    let pi = std::f64::consts::PI;
    let rmax = 0.45;
    let rmin = rmax * (2.0 * pi / n).cos() / (pi / n).cos();
    let area = n * rmax * rmin * (pi / n).sin();
    // The box-filtered straight edge integrates exactly (its ramp is odd about the edge), and a
    // ramp one pixel wide sums over the pixel grid to its integral along a straight edge; what is
    // left are the vertices, where the bands of width w (one pixel) about two edges cross: a
    // rhombus of area w^2 / sin(angle) at each, the ramp there wrong by less than 1. The
    // pentagram's tips have angle 36 degrees, its inner vertices' edges cross at 108: the
    // coverage is within n (1 / sin 36 + 1 / sin 108) w^2 = 13.8 w^2 of the area, and with
    // k x k sub-pixels (each filtered over w / k) within 13.8 (w / k)^2.
    let size = 96;
    let w = 1.0 / size as f64;
    let bound = n * (1.0 / (pi / n).sin() + 1.0 / (3.0 * pi / n).sin()) * w * w;
    for samples in [1.0, 2.0] {
        let image = flat_star(size, rmax, rmin, samples);
        let coverage = image.pixels.iter().map(|p| p[0] as f64).sum::<f64>() / image.pixels.len() as f64;
        let limit = bound / (samples * samples);
        println!(
            "star coverage with {samples} x {samples} sub-pixels: {coverage:.6}, area {area:.6}, \
             error {:.2e} (bound {limit:.2e})",
            coverage - area
        );
        assert!((coverage - area).abs() < limit, "coverage {coverage} vs area {area} (samples {samples})");
    }
}

// ---------------------------------------------------------------------------------------------
// planet (Musgrave's multifractal terrain)

/// What a planet pixel shows, told by its chromaticity (the lights are white, so without the
/// specular term a pixel is its surface colour times a scalar).
#[derive(Clone, Copy, PartialEq, Debug)]
enum Ground {
    Space,
    Ocean,
    Ice,
    Land,
}

fn ground(p: [f32; 4]) -> Ground {
    let (r, g, b) = (p[0] as f64, p[1] as f64, p[2] as f64);
    let (lo, hi) = (r.min(g).min(b), r.max(g).max(b));
    if hi < 1e-3 || (p[0] - 0.0).abs() < 1e-3 && (p[1] - 0.0).abs() < 1e-3 && (p[2] - 0.02).abs() < 1e-3 {
        Ground::Space
    } else if lo > 0.85 * hi {
        Ground::Ice
    } else if b > 1.4 * r.max(g) {
        Ground::Ocean
    } else {
        Ground::Land
    }
}

/// Whiteness: the smallest channel over the largest (1 for grey and white, whatever the light).
fn whiteness(p: [f32; 4]) -> f64 {
    let (r, g, b) = (p[0] as f64, p[1] as f64, p[2] as f64);
    r.min(g).min(b) / r.max(g).max(b).max(1e-6)
}

/// The planet's classes over the image, and the number of land/ocean changes between
/// horizontally adjacent pixels (a measure of coastline length).
fn classify(image: &Image) -> (Vec<Ground>, usize) {
    let classes: Vec<Ground> = image.pixels.iter().map(|&p| ground(p)).collect();
    let w = image.width as usize;
    let coast = (0..classes.len())
        .filter(|&i| i % w + 1 < w)
        .filter(|&i| {
            let (a, b) = (classes[i], classes[i + 1]);
            (a == Ground::Land && b == Ground::Ocean) || (a == Ground::Ocean && b == Ground::Land)
        })
        .count();
    (classes, coast)
}

#[test]
fn planet() {
    let background = [0.0, 0.0, 0.02, 1.0];
    let mut s = scene("planet", 96, 96);
    set(&mut s, &[0], "octaves", 4.0);
    // Measured: 2 silhouette pixels differ, by up to 0.25; inside the disc at most 1e-5.
    let silhouette = Thresholds { hard_fail: 0.3, ..Thresholds::default() };
    reference_interior("planet", &s, background, silhouette);

    // The checks on the ground colours use the CPU image without the ocean's highlight.
    set(&mut s, &[0], "Ks", 0.0);
    let image = cpu("planet (matte)", &s);
    let (classes, coast) = classify(&image);
    let count = |g: Ground| classes.iter().filter(|&&c| c == g).count() as f64;
    let disc = classes.len() as f64 - count(Ground::Space);
    let (land, ocean, ice) =
        (count(Ground::Land) / disc, count(Ground::Ocean) / disc, count(Ground::Ice) / disc);
    println!(
        "planet: disc {disc} px; land {land:.3}, ocean {ocean:.3}, ice and snow {ice:.3}; coast {coast}"
    );
    assert!((0.15..0.6).contains(&land), "land fraction {land}");
    assert!(ocean > 0.25, "ocean fraction {ocean}");

    // Polar cap: the north pole leans towards the camera at the top of the disc. The rows of
    // the disc's top fifth are whiter than the rows about its middle (the equator's latitudes).
    let rows: Vec<u32> = (0..image.height)
        .filter(|&y| (0..image.width).any(|x| classes[(y * image.width + x) as usize] != Ground::Space))
        .collect();
    let (top, bottom) = (rows[0] as f64, *rows.last().unwrap() as f64);
    let band = |from: f64, to: f64| {
        let mut sum = 0.0;
        let mut n = 0.0;
        for y in 0..image.height {
            let f = (y as f64 - top) / (bottom - top);
            if f < from || f > to {
                continue;
            }
            for x in 0..image.width {
                let p = at(&image, x, y);
                if ground(p) != Ground::Space {
                    sum += whiteness(p);
                    n += 1.0;
                }
            }
        }
        sum / n
    };
    let (cap, equator) = (band(0.0, 0.2), band(0.45, 0.55));
    println!("planet: whiteness of the top fifth {cap:.3}, of the middle tenth {equator:.3}");
    assert!(cap > equator + 0.2, "polar cap {cap} not whiter than the equator {equator}");

    // The knob: more octaves make a longer (rougher) coastline.
    set(&mut s, &[0], "octaves", 2.0);
    let (_, coast2) = classify(&cpu("planet (2 octaves)", &s));
    println!("planet: coastline crossings with 2 octaves {coast2}, with 4 {coast}");
    // Measured: 119 crossings with 2 octaves, 286 with 4.
    assert!(coast as f64 > 1.5 * coast2 as f64, "coast {coast} (4 octaves) vs {coast2} (2)");
}
