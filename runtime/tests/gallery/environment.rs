//! The environment-mapped gallery scene: `shinymetal` (RI 3.2 Appendix A's shinymetal on two
//! spheres, a lat-long and a cube-map sky). Rendered small on both backends and compared with the
//! default thresholds; its own checks on the CPU reference's image: the spheres mirror sky above
//! and ground below, and the cube map and the lat-long map of the same sky give nearly the same
//! sphere.
//!
//! Run with `--nocapture` to see the measured statistics.

use crate::support;

use patina_runtime::image::{Image, Thresholds, compare};
use patina_runtime::scene::ParamValue;
use support::gallery::{at, both, cpu, scene};

/// The mean of channel `c` over the pixels of the disc of radius `r` about (cx, cy).
fn disc_mean(image: &Image, cx: f64, cy: f64, r: f64, c: usize) -> f64 {
    let (mut sum, mut n) = (0.0, 0.0);
    for y in 0..image.height {
        for x in 0..image.width {
            let (dx, dy) = (f64::from(x) + 0.5 - cx, f64::from(y) + 0.5 - cy);
            if dx * dx + dy * dy < r * r {
                sum += f64::from(at(image, x, y)[c]);
                n += 1.0;
            }
        }
    }
    sum / n
}

#[test]
fn shinymetal_mirrors_the_sky_alike_on_both_backends() {
    let s = scene("shinymetal", 128, 72);
    // Each sphere's mip level (sky:64's chain, skycube:32's) comes from the footprint of the
    // reflected direction, from screen derivatives: differences across the 2 x 2 quad on the GPU
    // (helper invocations off the sphere at its silhouette), analytic on the CPU. So the whole
    // image is compared with a looser hard fail (measured at 128 x 72: 21 pixels over 0.004, the
    // largest 0.060, all at the silhouettes) and the interior, pixels whose 3 x 3 neighbourhood is
    // covered in both images, with the default thresholds (measured: 3 pixels over 0.004, the
    // largest 0.0085).
    let silhouette = Thresholds { hard_fail: 0.08, ..Thresholds::default() };
    let image = match both("shinymetal", &s, silhouette) {
        Some(r) => {
            println!("shinymetal: GPU vs CPU {:?}", r.comparison);
            let background = s.output.background;
            let covered = |image: &Image, x: u32, y: u32| {
                at(image, x, y).iter().zip(background).any(|(a, b)| (a - b).abs() > 1e-3)
            };
            let (w, h) = (r.cpu.width, r.cpu.height);
            let interior = |x: u32, y: u32| {
                x > 0
                    && y > 0
                    && x + 1 < w
                    && y + 1 < h
                    && (x - 1..=x + 1)
                        .all(|i| (y - 1..=y + 1).all(|j| covered(&r.cpu, i, j) && covered(&r.gpu, i, j)))
            };
            let mask = |image: &Image| Image {
                width: w,
                height: h,
                pixels: (0..w * h)
                    .map(|i| if interior(i % w, i / w) { image.pixels[i as usize] } else { [0.0; 4] })
                    .collect(),
            };
            let t = Thresholds::default();
            let inside = compare(&mask(&r.cpu), &mask(&r.gpu), &t).unwrap();
            println!("shinymetal interior: GPU vs CPU {inside:?}");
            assert!(inside.passes(&t), "shinymetal interior: {inside:?}");
            r.cpu
        }
        None => cpu("shinymetal", &s),
    };
    // The spheres' centres and radius in the 128 x 72 image (measured from the picture: the
    // spheres of radius 0.85 at x = ±0.95 under a 45° field of view from 4 away).
    let (left, right, cy, r) = (37.0, 91.0, 38.0, 17.0);
    for (label, cx) in [("left (lat-long)", left), ("right (cube)", right)] {
        // Near the top the reflection points up: sky, bluer than red.
        let top = at(&image, cx as u32, (cy - 0.7 * r) as u32);
        assert!(top[2] > top[0] + 0.1, "{label}: top {top:?}");
        // Near the bottom it points down: the ground's dark and light checks, no blue sky.
        let bottom_blue = disc_mean(&image, cx, cy + 0.7 * r, 3.0, 2);
        let top_blue = disc_mean(&image, cx, cy - 0.7 * r, 3.0, 2);
        assert!(bottom_blue < 0.5 * top_blue, "{label}: blue below {bottom_blue}, above {top_blue}");
    }
    // The right sphere with the lat-long map instead of the cube map: nearly the same picture
    // (the two maps hold one sky at different resolutions), while a different sky (a checker
    // board) is far off.
    let with = |name: &str| {
        let mut t = scene("shinymetal", 128, 72);
        t.objects[1].surface.params.insert("texturename".into(), ParamValue::String(name.into()));
        cpu(name, &t)
    };
    let difference = |other: &Image| {
        (0..3)
            .map(|c| (disc_mean(&image, right, cy, r, c) - disc_mean(other, right, cy, r, c)).abs())
            .fold(0.0, f64::max)
    };
    let latlong = difference(&with("sky:64"));
    let checker = difference(&with("checker:8"));
    println!("shinymetal: right sphere's mean, cube vs lat-long {latlong:.4}, vs a checker {checker:.4}");
    assert!(latlong < 0.01 && checker > 0.05, "{latlong} {checker}");
}
