//! Gallery scene `shadowed_teapot`: a spot light with a shadow map (a depth pass from the light,
//! read by `shadow()` with percentage-closer taps) over a floor and the teapot. Both backends
//! render it within the scene's thresholds, and the shadow is where the geometry puts it: floor
//! pixels whose segment to the light crosses the teapot's triangles (found here by ray casting
//! against the mesh, with a margin) equal the render with the spot light off, and floor pixels
//! whose segment is clear equal the render without a shadow map.
//!
//! Run with `--nocapture` to see the counts.

use crate::support;

use glam::{Mat4, Vec3, Vec4};
use patina_runtime::image::{Image, Thresholds, compare};
use patina_runtime::render::shadow;
use patina_runtime::scene::{ParamValue, Scene};
use support::gallery::{at, both, cpu, scene};

const W: u32 = 100;
const H: u32 = 75;

/// The teapot's world-space triangles and their bounding box.
struct Blocker {
    triangles: Vec<[Vec3; 3]>,
    min: Vec3,
    max: Vec3,
}

impl Blocker {
    fn of(s: &Scene, object: usize) -> Blocker {
        let mesh = s.objects[object].build_mesh().unwrap();
        let m = s.object_transform(object);
        let p: Vec<Vec3> = mesh.positions.iter().map(|p| m.transform_point3(Vec3::from(*p))).collect();
        let triangles: Vec<[Vec3; 3]> =
            mesh.indices.chunks(3).map(|t| [p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]]).collect();
        let (min, max) =
            p.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), q| (a.min(*q), b.max(*q)));
        Blocker { triangles, min, max }
    }

    /// Whether the segment from `a` to `b` crosses a triangle farther than `margin` from both ends.
    fn blocks(&self, a: Vec3, b: Vec3, margin: f32) -> bool {
        let d = b - a;
        let length = d.length();
        // The slab test against the box first.
        let (mut t0, mut t1) = (0.0f32, 1.0f32);
        for k in 0..3 {
            if d[k].abs() < 1e-12 {
                if a[k] < self.min[k] || a[k] > self.max[k] {
                    return false;
                }
                continue;
            }
            let (u, v) = ((self.min[k] - a[k]) / d[k], (self.max[k] - a[k]) / d[k]);
            t0 = t0.max(u.min(v));
            t1 = t1.min(u.max(v));
        }
        if t0 > t1 {
            return false;
        }
        self.triangles.iter().any(|[p0, p1, p2]| {
            // Möller–Trumbore.
            let (e1, e2) = (*p1 - *p0, *p2 - *p0);
            let h = d.cross(e2);
            let det = e1.dot(h);
            if det.abs() < 1e-12 {
                return false;
            }
            let f = 1.0 / det;
            let s = a - *p0;
            let u = f * s.dot(h);
            let q = s.cross(e1);
            let v = f * d.dot(q);
            let t = f * e2.dot(q);
            (0.0..=1.0).contains(&u)
                && v >= 0.0
                && u + v <= 1.0
                && t * length > margin
                && (1.0 - t) * length > margin
        })
    }
}

/// The world point of the floor (y = 0) seen through pixel (x, y)'s centre, if the ray meets it.
fn floor_point(s: &Scene, x: u32, y: u32) -> Option<Vec3> {
    let camera = s.camera();
    let clip_to_world: Mat4 = camera.world_to_clip(s.aspect()).inverse();
    let ndc =
        Vec4::new((x as f32 + 0.5) / W as f32 * 2.0 - 1.0, 1.0 - (y as f32 + 0.5) / H as f32 * 2.0, 0.5, 1.0);
    let far = clip_to_world * ndc;
    let direction = (far.truncate() / far.w - camera.from).normalize();
    let t = -camera.from.y / direction.y;
    (t > 0.0).then(|| camera.from + direction * t)
}

fn luminance(p: [f32; 4]) -> f32 {
    (p[0] + p[1] + p[2]) / 3.0
}

fn light_param(s: &mut Scene, name: &str, value: ParamValue) {
    s.lights[0].shader.params.insert(name.to_string(), value);
}

#[test]
fn shadowed_teapot_shadow_is_where_the_teapot_blocks_the_light() {
    let s = scene("shadowed_teapot", W, H);
    let teapot = Blocker::of(&s, 1);
    let camera = s.camera().from;
    // The floor pixels the teapot does not hide, where the shadow falls.
    let on_floor = |x: u32, y: u32| {
        floor_point(&s, x, y)
            .filter(|q| q.x.abs() < 4.5 && q.z.abs() < 4.5 && !teapot.blocks(camera, *q, 0.0))
    };
    let image: Image = match both("shadowed_teapot", &s, s.thresholds()) {
        Some(r) => {
            println!("shadowed_teapot: GPU vs CPU {:?}", r.comparison);
            // On the floor the backends agree within the default thresholds: the teapot's
            // exception (its faceforwarded seams) does not cover the shadow.
            let floor =
                |image: &Image| Image {
                    width: W,
                    height: H,
                    pixels: (0..W * H)
                        .map(|i| {
                            if on_floor(i % W, i / W).is_some() { image.pixels[i as usize] } else { [0.0; 4] }
                        })
                        .collect(),
                };
            let t = Thresholds::default();
            let c = compare(&floor(&r.cpu), &floor(&r.gpu), &t).unwrap();
            println!("shadowed_teapot: floor GPU vs CPU {c:?}");
            assert!(c.passes(&t), "the floor differs: {c:?}");
            r.cpu
        }
        None => cpu("shadowed_teapot", &s),
    };
    let mut unshadowed = s.clone();
    light_param(&mut unshadowed, "shadowname", ParamValue::String(String::new()));
    let unshadowed = cpu("shadowed_teapot without the map", &unshadowed);
    let mut dark = s.clone();
    light_param(&mut dark, "intensity", ParamValue::Number(0.0));
    let dark = cpu("shadowed_teapot with the spot off", &dark);

    let from = match &s.lights[0].shader.params["from"] {
        ParamValue::Numbers(v) => Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32),
        other => panic!("from: {other:?}"),
    };
    let margin = 0.08;
    let offsets = [Vec3::ZERO, Vec3::X * margin, -Vec3::X * margin, Vec3::Z * margin, -Vec3::Z * margin];
    let (mut blocked, mut clear) = (0, 0);
    for y in 0..H {
        for x in 0..W {
            // On the floor (side 10), and seen: the camera's ray to it misses the teapot.
            let Some(q) = on_floor(x, y) else { continue };
            let hits = offsets.iter().filter(|o| teapot.blocks(q + **o, from, 0.2)).count();
            let (shaded, lit, off) = (at(&image, x, y), at(&unshadowed, x, y), at(&dark, x, y));
            if hits == offsets.len() {
                blocked += 1;
                // Fully shadowed: only the ambient light, exactly the render with the spot off.
                for c in 0..3 {
                    assert!(
                        (shaded[c] - off[c]).abs() < 1e-5,
                        "({x}, {y}) at {q}: {shaded:?}, spot off {off:?}"
                    );
                }
                // And the spot would have lit it.
                assert!(luminance(lit) > luminance(off) + 0.05, "({x}, {y}): {lit:?} vs {off:?}");
            } else if hits == 0 && !offsets.iter().any(|o| teapot.blocks(q + *o * 2.0, from, 0.0)) {
                clear += 1;
                for c in 0..3 {
                    assert!(
                        (shaded[c] - lit[c]).abs() < 1e-5,
                        "({x}, {y}) at {q}: {shaded:?}, no map {lit:?}"
                    );
                }
            }
        }
    }
    println!("shadowed_teapot: {blocked} pixels in full shadow, {clear} clear of it");
    assert!(blocked > 60, "{blocked} blocked pixels");
    assert!(clear > 1000, "{clear} clear pixels");

    // The lookup's options reach it: one tap gives a hard edge, and a wide blur a wider
    // penumbra (pixels strictly between fully shadowed and fully lit).
    let penumbra = |image: &Image| {
        (0..W * H)
            .filter(|i| on_floor(i % W, i / W).is_some())
            .filter(|i| {
                let (p, lo, hi) =
                    (image.pixels[*i as usize], dark.pixels[*i as usize], unshadowed.pixels[*i as usize]);
                (0..3).all(|c| p[c] > lo[c] + 1e-3 && p[c] < hi[c] - 1e-3)
            })
            .count()
    };
    let with = |name: &str, value: f64| {
        let mut v = s.clone();
        light_param(&mut v, name, ParamValue::Number(value));
        cpu(&format!("shadowed_teapot with {name} {value}"), &v)
    };
    // Fully lit floor pixels: a blur wider than the bias allows would darken the floor itself
    // (no slope-scaled bias), which this scene's blur must not.
    let lit = |image: &Image| {
        (0..W * H)
            .filter(|i| on_floor(i % W, i / W).is_some())
            .filter(|i| {
                (0..3)
                    .all(|c| (image.pixels[*i as usize][c] - unshadowed.pixels[*i as usize][c]).abs() < 1e-5)
            })
            .count()
    };
    let blurred = with("blur", 0.012);
    let (soft, hard, wide) = (penumbra(&image), penumbra(&with("samples", 1.0)), penumbra(&blurred));
    let (sharp_lit, blurred_lit) = (lit(&image), lit(&blurred));
    println!(
        "shadowed_teapot: penumbra pixels {soft} (16 taps), {hard} (1 tap), {wide} (blur 0.012); fully lit {sharp_lit} and {blurred_lit}"
    );
    assert_eq!(hard, 0, "one tap is all or nothing");
    assert!(soft > 10, "16 taps: {soft}");
    assert!(wide > 2 * soft, "blur 0.012: {wide}, blur 0.004: {soft}");
    assert!(sharp_lit >= clear && blurred_lit >= clear - clear / 10, "{sharp_lit} {blurred_lit} {clear}");
}

#[test]
fn shadow_map_holds_the_nearest_depth_and_its_matrix() {
    let s = scene("shadowed_teapot", W, H);
    let map = &s.shadow_maps[0];
    let world_to_camera = s.camera().world_to_camera();
    let texture = shadow::make(&s, map, world_to_camera).unwrap();
    let n = map.resolution;
    assert_eq!(texture.size, [n, n + 1, 1]);
    let light = shadow::light_view(&s, map).unwrap();
    let from = shadow::light_camera(&s, map).unwrap().from;
    // The matrix row: camera-space points land where the light camera projects them; then the
    // bias.
    let m = shadow::matrix(&light, world_to_camera);
    for r in 0..4 {
        assert_eq!(texture.texels[(n * n) as usize + r], m.row(r).to_array());
    }
    assert_eq!(texture.texels[(n * n) as usize + 4], [map.bias, 0.0, 0.0, 0.0]);
    // The teapot's top is the nearest surface through its texel, and the floor far from the
    // teapot is the nearest through its own.
    let teapot = Blocker::of(&s, 1);
    let top =
        Vec3::new(0.5 * (teapot.min.x + teapot.max.x), teapot.max.y, 0.5 * (teapot.min.z + teapot.max.z));
    let floor = Vec3::new(1.5, 0.0, -0.5);
    for (p, what) in [(top, "teapot top"), (floor, "floor")] {
        let ([x, y], depth) = shadow::project(&light, n, p).expect("inside the map");
        let stored = texture.texels[(y * n + x) as usize][0];
        assert!((stored - depth).abs() < 0.05, "{what}: stored {stored}, depth {depth}");
    }
    // Where the teapot blocks the floor, the map holds the teapot's depth, well in front.
    let inside = Vec3::new(top.x, 0.45 * teapot.max.y, top.z);
    let hit = from + (inside - from) * (from.y / (from.y - inside.y));
    let ([x, y], floor_depth) = shadow::project(&light, n, hit).unwrap();
    let stored = texture.texels[(y * n + x) as usize][0];
    assert!(stored < floor_depth - 0.5, "stored {stored}, floor {floor_depth}");
}

/// The floor points of `image` in full shadow of the teapot and those clear of it, as ray casts
/// towards the light (`light(q)`, the point a floor point `q` is lit from) decide: the first must
/// equal the render with the light off (`dark`) and the second the one without shadow maps
/// (`unshadowed`), which is asserted here.
fn blocked_and_clear(
    s: &Scene,
    [image, unshadowed, dark]: [&Image; 3],
    light: impl Fn(Vec3) -> Vec3,
) -> (Vec<Vec3>, Vec<Vec3>) {
    let teapot = Blocker::of(s, 1);
    let camera = s.camera().from;
    let offsets = [Vec3::ZERO, Vec3::X * 0.08, -Vec3::X * 0.08, Vec3::Z * 0.08, -Vec3::Z * 0.08];
    let (mut blocked, mut clear) = (Vec::new(), Vec::new());
    for y in 0..H {
        for x in 0..W {
            let Some(q) = floor_point(s, x, y) else { continue };
            if q.x.abs() > 4.5 || q.z.abs() > 4.5 || teapot.blocks(camera, q, 0.0) {
                continue;
            }
            let hits = offsets.iter().filter(|o| teapot.blocks(q + **o, light(q + **o), 0.2)).count();
            let (shaded, lit, off) = (at(image, x, y), at(unshadowed, x, y), at(dark, x, y));
            if hits == offsets.len() {
                blocked.push(q);
                assert!(
                    (0..3).all(|c| (shaded[c] - off[c]).abs() < 1e-5),
                    "({x}, {y}): {shaded:?} vs {off:?}"
                );
            } else if hits == 0
                && !offsets.iter().any(|o| teapot.blocks(q + *o * 2.0, light(q + *o * 2.0), 0.0))
            {
                clear.push(q);
                assert!(
                    (0..3).all(|c| (shaded[c] - lit[c]).abs() < 1e-5),
                    "({x}, {y}): {shaded:?} vs {lit:?}"
                );
            }
        }
    }
    (blocked, clear)
}

#[test]
fn orthographic_map_shadows_a_distant_light_along_parallel_rays() {
    let mut s = scene("shadowed_teapot", W, H);
    // The spot light becomes a distant one along the same direction, with an orthographic map.
    let spot = s.lights[0].shader.clone();
    s.lights[0].shader.path = spot.path.with_file_name("shadowdistant.sl");
    s.lights[0].shader.name = Some("shadowdistant".into());
    s.lights[0]
        .shader
        .params
        .retain(|k, _| ["from", "to", "shadowname", "samples", "blur"].contains(&k.as_str()));
    s.lights[0].shader.params.insert("intensity".into(), ParamValue::Number(0.9));
    s.shadow_maps[0].orthographic = true;
    s.shadow_maps[0].bias = 0.03;
    let image = match both("shadowed_teapot, distant", &s, s.thresholds()) {
        Some(r) => r.cpu,
        None => cpu("shadowed_teapot, distant", &s),
    };
    let mut dark = s.clone();
    dark.lights[0].shader.params.insert("intensity".into(), ParamValue::Number(0.0));
    let dark = cpu("shadowed_teapot, distant off", &dark);
    let mut unshadowed = s.clone();
    unshadowed.lights[0].shader.params.insert("shadowname".into(), ParamValue::String(String::new()));
    let unshadowed = cpu("shadowed_teapot, distant without the map", &unshadowed);
    let point = |name: &str| match &spot.params[name] {
        ParamValue::Numbers(v) => Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32),
        other => panic!("{name}: {other:?}"),
    };
    // Towards the light: every ray is parallel to from - to.
    let towards = (point("from") - point("to")).normalize() * 50.0;
    let (blocked, clear) = blocked_and_clear(&s, [&image, &unshadowed, &dark], |q| q + towards);
    let (blocked, clear) = (blocked.len(), clear.len());
    println!("shadowed_teapot, distant: {blocked} pixels in full shadow, {clear} clear of it");
    assert!(blocked > 40 && clear > 1000, "{blocked} blocked, {clear} clear");
}

/// A point light casts shadows through a cube of six maps, each looking along one axis from the
/// light (`[[shadow]]`'s own `to`), read by Aqsis's standard `shadowpoint` (from the corpus in
/// ../shared, not copied), which picks the map by the direction of L in world space.
#[test]
fn a_point_light_casts_shadows_through_a_cube_of_six_maps() {
    let corpus = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/corpus/aqsis/light/shadowpoint.sl");
    assert!(corpus.is_file(), "{}: the corpus is missing (it lives in ../shared)", corpus.display());
    let mut s = scene("shadowed_teapot", W, H);
    let spot = s.lights[0].shader.clone();
    let from = match &spot.params["from"] {
        ParamValue::Numbers(v) => Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32),
        other => panic!("from: {other:?}"),
    };
    s.lights[0].shader.path = corpus;
    s.lights[0].shader.name = Some("shadowpoint".into());
    s.lights[0].shader.params.retain(|k, _| ["from", "samples"].contains(&k.as_str()));
    s.lights[0].shader.params.insert("intensity".into(), ParamValue::Number(45.0));
    let template = s.shadow_maps[0].clone();
    s.shadow_maps.clear();
    let faces = [
        ("px", Vec3::X),
        ("nx", -Vec3::X),
        ("py", Vec3::Y),
        ("ny", -Vec3::Y),
        ("pz", Vec3::Z),
        ("nz", -Vec3::Z),
    ];
    for (face, axis) in faces {
        let name = format!("point.{face}.shad");
        s.lights[0].shader.params.insert(format!("sf{face}"), ParamValue::String(name.clone()));
        let to = from + axis;
        // A little wider than 90 degrees, so the taps of a lookup near a face's edge stay inside.
        s.shadow_maps.push(patina_runtime::scene::ShadowMap {
            name,
            fov: Some(96.0),
            to: Some(to.to_array()),
            ..template.clone()
        });
    }
    let image = match both("shadowed_teapot, point", &s, s.thresholds()) {
        Some(r) => r.cpu,
        None => cpu("shadowed_teapot, point", &s),
    };
    let mut dark = s.clone();
    dark.lights[0].shader.params.insert("intensity".into(), ParamValue::Number(0.0));
    let dark = cpu("shadowed_teapot, point off", &dark);
    let mut unshadowed = s.clone();
    for (face, _) in faces {
        unshadowed.lights[0].shader.params.insert(format!("sf{face}"), ParamValue::String(String::new()));
    }
    let unshadowed = cpu("shadowed_teapot, point without maps", &unshadowed);
    let (blocked, clear) = blocked_and_clear(&s, [&image, &unshadowed, &dark], |_| from);
    // Which face of the cube each clear point's lookup read: the major axis of the direction from
    // the light.
    let faces_lit: std::collections::BTreeSet<usize> = clear
        .iter()
        .map(|q| {
            let l = *q - from;
            if l.x.abs() > l.y.abs() && l.x.abs() > l.z.abs() {
                0
            } else if l.y.abs() > l.z.abs() {
                1
            } else {
                2
            }
        })
        .collect();
    let (blocked, clear) = (blocked.len(), clear.len());
    println!(
        "shadowed_teapot, point: {blocked} pixels in full shadow, {clear} clear of it, faces {faces_lit:?}"
    );
    assert!(blocked > 40 && clear > 1000, "{blocked} blocked, {clear} clear");
    assert!(faces_lit.len() >= 2, "the floor is seen through more than one face: {faces_lit:?}");
}
