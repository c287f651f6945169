//! The interpreter's colour, spline, Fresnel, matrix, geometry and string built-ins, compiled from
//! source and evaluated in f64 and f32, against values worked out independently here: closed forms,
//! or straightforward reimplementations written from the definitions (Foley and van Dam's colour
//! algorithms, the spline bases' blending functions, the Fresnel equations in their angle form).

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator};
use patina_compiler::diag::Code;

use crate::support::try_compile;

/// Compiles the only shader of `source`, panicking with the diagnostic on failure.
fn compile(source: &str) -> CpuProgram {
    crate::support::compile(source, &Binding::default())
}

/// Evaluates `outputs` at points given by columns, after setting `uniforms`, in f64 and in f32.
fn run_both(
    source: &str,
    count: usize,
    uniforms: &[(&str, &[f64])],
    inputs: &[(&str, &[f64])],
    outputs: &[&str],
) -> [Vec<Vec<f64>>; 2] {
    let program = compile(source);
    let mut wide = Evaluator::<f64>::new(&program);
    let mut narrow = Evaluator::<f32>::new(&program);
    for (name, values) in uniforms {
        wide.set(name, values).unwrap();
        narrow.set(name, values).unwrap();
    }
    [wide.eval_points(count, inputs, outputs).unwrap(), narrow.eval_points(count, inputs, outputs).unwrap()]
}

/// The tolerance of each precision (f64 first), relative to the magnitude of the expected value
/// (at least 1).
const TOLERANCE: [f64; 2] = [1e-11, 2e-5];

/// Checks `got` against `want` at both precisions.
fn check(results: &[Vec<Vec<f64>>; 2], output: usize, want: &[f64], what: &str) {
    for (precision, result) in results.iter().enumerate() {
        let got = &result[output];
        assert_eq!(got.len(), want.len(), "{what}: length");
        for (i, (g, w)) in got.iter().zip(want).enumerate() {
            let tol = TOLERANCE[precision] * w.abs().max(1.0);
            assert!(
                (g - w).abs() <= tol,
                "{what} ({}): component {i}: got {g}, want {w}\n got  {got:?}\n want {want:?}",
                ["f64", "f32"][precision]
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Colour spaces: references written from Foley and van Dam (2nd ed., section 13.3), hue in turns.
// ---------------------------------------------------------------------------------------------

fn hsv_to_rgb([h, s, v]: [f64; 3]) -> [f64; 3] {
    if s == 0.0 {
        return [v; 3];
    }
    let h = (h - h.floor()) * 6.0;
    let i = h.floor();
    let f = h - i;
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    match i as i32 {
        0 => [v, t, p],
        1 => [q, v, p],
        2 => [p, v, t],
        3 => [p, q, v],
        4 => [t, p, v],
        _ => [v, p, q],
    }
}

/// Hue in turns (0 for greys) and the extremes.
fn hue([r, g, b]: [f64; 3]) -> (f64, f64, f64) {
    let max = r.max(g).max(b);
    let min = r.min(g).min(b);
    if max == min {
        return (0.0, max, min);
    }
    let d = max - min;
    let sextant = if r == max {
        (g - b) / d
    } else if g == max {
        2.0 + (b - r) / d
    } else {
        4.0 + (r - g) / d
    };
    let degrees = sextant * 60.0;
    let degrees = if degrees < 0.0 { degrees + 360.0 } else { degrees };
    (degrees / 360.0, max, min)
}

fn rgb_to_hsv(c: [f64; 3]) -> [f64; 3] {
    let (h, max, min) = hue(c);
    let s = if max != 0.0 { (max - min) / max } else { 0.0 };
    [h, s, max]
}

fn hsl_to_rgb([h, s, l]: [f64; 3]) -> [f64; 3] {
    if s == 0.0 {
        return [l; 3];
    }
    let m2 = if l <= 0.5 { l * (1.0 + s) } else { l + s - l * s };
    let m1 = 2.0 * l - m2;
    let value = |hue: f64| {
        let hue = hue - hue.floor();
        if hue < 1.0 / 6.0 {
            m1 + (m2 - m1) * hue * 6.0
        } else if hue < 0.5 {
            m2
        } else if hue < 2.0 / 3.0 {
            m1 + (m2 - m1) * (2.0 / 3.0 - hue) * 6.0
        } else {
            m1
        }
    };
    [value(h + 1.0 / 3.0), value(h), value(h - 1.0 / 3.0)]
}

fn rgb_to_hsl(c: [f64; 3]) -> [f64; 3] {
    let (h, max, min) = hue(c);
    let l = (max + min) / 2.0;
    let s = if max == min {
        0.0
    } else if l <= 0.5 {
        (max - min) / (max + min)
    } else {
        (max - min) / (2.0 - max - min)
    };
    [h, s, l]
}

/// IEC 61966-2-1's RGB to XYZ matrix, to the four decimals it publishes.
const SRGB_TO_XYZ: [[f64; 3]; 3] =
    [[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]];

fn times(m: &[[f64; 3]; 3], c: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| m[i][0] * c[0] + m[i][1] * c[1] + m[i][2] * c[2])
}

/// Colours to convert: primaries, secondaries, greys, black, white and some in between.
const RGBS: [[f64; 3]; 10] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 1.0, 0.0],
    [0.3, 0.3, 0.3],
    [0.0, 0.0, 0.0],
    [1.0, 1.0, 1.0],
    [0.2, 0.5, 0.9],
    [0.9, 0.1, 0.4],
    [0.25, 0.75, 0.5],
];

fn flat(colours: &[[f64; 3]]) -> Vec<f64> {
    colours.iter().flatten().copied().collect()
}

#[test]
fn hsv_known_values() {
    // The cast form, and ctransform from hsv.
    let src = r#"surface t() {
        Ci = color "hsv" (comp(Cs, 0), comp(Cs, 1), comp(Cs, 2));
        Oi = ctransform("hsv", "rgb", Cs);
    }"#;
    let hsv = [
        [0.0, 1.0, 1.0],
        [1.0 / 3.0, 1.0, 1.0],
        [2.0 / 3.0, 1.0, 1.0],
        [1.0 / 6.0, 1.0, 1.0],
        [0.5, 0.5, 0.8],
        [0.95, 0.3, 0.6],
        [1.25, 1.0, 1.0],
        [-0.25, 0.7, 0.4],
        [0.4, 0.0, 0.7],
    ];
    let out = run_both(src, hsv.len(), &[], &[("Cs", &flat(&hsv))], &["Ci", "Oi"]);
    let want = flat(&hsv.map(hsv_to_rgb));
    assert_eq!(&want[..9], &[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], "red, green, blue");
    check(&out, 0, &want, "color \"hsv\" (...)");
    check(&out, 1, &want, "ctransform(\"hsv\", \"rgb\", c)");
}

#[test]
fn rgb_to_hsv_and_hsl() {
    let src = r#"surface t() { Ci = ctransform("hsv", Cs); Oi = ctransform("rgb", "hsl", Cs); }"#;
    let out = run_both(src, RGBS.len(), &[], &[("Cs", &flat(&RGBS))], &["Ci", "Oi"]);
    check(&out, 0, &flat(&RGBS.map(rgb_to_hsv)), "rgb to hsv");
    check(&out, 1, &flat(&RGBS.map(rgb_to_hsl)), "rgb to hsl");
}

#[test]
fn hsl_known_values() {
    let src = r#"surface t() { Ci = color "hsl" (comp(Cs, 0), comp(Cs, 1), comp(Cs, 2)); }"#;
    let hsl = [
        [0.0, 1.0, 0.5],
        [1.0 / 3.0, 1.0, 0.5],
        [0.6, 0.4, 0.3],
        [0.1, 0.8, 0.75],
        [0.9, 0.0, 0.2],
        [0.5, 1.0, 1.0],
        [0.25, 0.5, 0.0],
    ];
    let out = run_both(src, hsl.len(), &[], &[("Cs", &flat(&hsl))], &["Ci"]);
    let want = flat(&hsl.map(hsl_to_rgb));
    assert_eq!(&want[..6], &[1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    check(&out, 0, &want, "color \"hsl\" (...)");
}

#[test]
fn xyz_and_xyy_use_the_srgb_primaries_and_d65() {
    let src = r#"surface t() { Ci = ctransform("XYZ", Cs); Oi = ctransform("rgb", "xyY", Cs); }"#;
    let colours = &RGBS[..];
    let [wide, narrow] = run_both(src, colours.len(), &[], &[("Cs", &flat(colours))], &["Ci", "Oi"]);
    for result in [&wide, &narrow] {
        for (p, c) in colours.iter().enumerate() {
            let xyz = times(&SRGB_TO_XYZ, *c);
            for k in 0..3 {
                // The published matrix has four decimals.
                assert!(
                    (result[0][p * 3 + k] - xyz[k]).abs() < 3e-4,
                    "XYZ of {c:?}: {:?}",
                    &result[0][p * 3..p * 3 + 3]
                );
            }
            let sum: f64 = xyz.iter().sum();
            let xyy = if sum == 0.0 { [0.3127, 0.3290, 0.0] } else { [xyz[0] / sum, xyz[1] / sum, xyz[1]] };
            for k in 0..3 {
                assert!(
                    (result[1][p * 3 + k] - xyy[k]).abs() < 3e-4,
                    "xyY of {c:?}: {:?}",
                    &result[1][p * 3..p * 3 + 3]
                );
            }
        }
    }
    // White is D65 at Y = 1 (its chromaticity exactly, to the precision of the evaluation).
    let white = &wide[1][6 * 3..7 * 3];
    assert!(
        (white[0] - 0.3127).abs() < 1e-12
            && (white[1] - 0.3290).abs() < 1e-12
            && (white[2] - 1.0).abs() < 1e-12
    );
    // The primaries' chromaticities are Rec. 709's.
    for (p, xy) in [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]].iter().enumerate() {
        let got = &wide[1][p * 3..p * 3 + 2];
        assert!((got[0] - xy[0]).abs() < 1e-12 && (got[1] - xy[1]).abs() < 1e-12, "primary {p}: {got:?}");
    }
}

#[test]
fn xyy_without_luminance_is_black() {
    // y = 0 leaves X and Z undefined (0 / 0); with Y = 0 the colour is black whatever x, y say.
    let src = r#"surface t() { Ci = color "xyY" (comp(Cs, 0), comp(Cs, 1), comp(Cs, 2)); }"#;
    let out = run_both(src, 2, &[], &[("Cs", &[0.3, 0.0, 0.0, 0.3127, 0.3290, 0.0])], &["Ci"]);
    check(&out, 0, &[0.0; 6], "xyY with Y = 0");
}

#[test]
fn yiq_is_ntsc() {
    let src = r#"surface t() { Ci = ctransform("YIQ", Cs); Oi = color "YIQ" (1, 0, 0); }"#;
    let out = run_both(src, 2, &[], &[("Cs", &[1.0, 0.0, 0.0, 0.2, 0.5, 0.9])], &["Ci", "Oi"]);
    let yiq = |[r, g, b]: [f64; 3]| {
        [
            0.299 * r + 0.587 * g + 0.114 * b,
            0.596 * r - 0.275 * g - 0.321 * b,
            0.212 * r - 0.523 * g + 0.311 * b,
        ]
    };
    check(&out, 0, &flat(&[yiq([1.0, 0.0, 0.0]), yiq([0.2, 0.5, 0.9])]), "rgb to YIQ");
    // Luminance 1 without chrominance is white.
    check(&out, 1, &[1.0; 6], "YIQ (1, 0, 0)");
}

#[test]
fn every_colour_space_round_trips() {
    for space in ["rgb", "hsv", "hsl", "xyz", "XYZ", "xyY", "YIQ"] {
        let src = format!(
            r#"surface t() {{
                color c = ctransform("{space}", Cs);
                Ci = ctransform("{space}", "rgb", c);
                Oi = color "{space}" (comp(c, 0), comp(c, 1), comp(c, 2));
            }}"#
        );
        let out = run_both(&src, RGBS.len(), &[], &[("Cs", &flat(&RGBS))], &["Ci", "Oi"]);
        check(&out, 0, &flat(&RGBS), &format!("{space} round trip by ctransform"));
        check(&out, 1, &flat(&RGBS), &format!("{space} round trip by cast"));
    }
}

#[test]
fn ctransform_between_two_spaces_goes_through_rgb() {
    let src = r#"surface t() { Ci = ctransform("hsv", "hsl", Cs); Oi = ctransform("hsv", "hsv", Cs); }"#;
    let hsv = [[0.1, 0.5, 0.8], [0.7, 1.0, 0.4], [0.3, 0.0, 0.5]];
    let out = run_both(src, hsv.len(), &[], &[("Cs", &flat(&hsv))], &["Ci", "Oi"]);
    check(&out, 0, &flat(&hsv.map(|c| rgb_to_hsl(hsv_to_rgb(c)))), "hsv to hsl");
    check(&out, 1, &flat(&hsv), "hsv to hsv");
}

#[test]
fn an_unknown_colour_space_from_the_binding_is_an_error() {
    let src = r#"surface t(string space) { Ci = ctransform(space, Cs); }"#;
    let bound = |name: &str| Binding { strings: vec![("space".into(), name.into())], ..Binding::default() };
    let err = try_compile(src, &bound("cmyk")).expect_err("cmyk is not a colour space");
    assert_eq!(err.code, Code::UnknownSpace, "{}", err.message);
    assert!(try_compile(src, &bound("hsv")).is_ok());
}

// ---------------------------------------------------------------------------------------------
// Splines: segment choice as RenderMan defines it, blending functions in closed form.
// ---------------------------------------------------------------------------------------------

/// The segment and local parameter of `x` for `count` knots and a basis step.
fn segment(x: f64, count: usize, step: usize) -> (usize, f64) {
    let segments = (count - 4) / step + 1;
    let xs = x.clamp(0.0, 1.0) * segments as f64;
    let seg = (xs.floor() as usize).min(segments - 1);
    (seg * step, xs - seg as f64)
}

/// Peachey's Catmull-Rom evaluation (coefficients of the cubic, Horner's rule).
fn catmull_rom(x: f64, k: &[f64]) -> f64 {
    let (first, t) = segment(x, k.len(), 1);
    let k = &k[first..first + 4];
    let c3 = -0.5 * k[0] + 1.5 * k[1] - 1.5 * k[2] + 0.5 * k[3];
    let c2 = k[0] - 2.5 * k[1] + 2.0 * k[2] - 0.5 * k[3];
    let c1 = -0.5 * k[0] + 0.5 * k[2];
    let c0 = k[1];
    ((c3 * t + c2) * t + c1) * t + c0
}

fn bezier(x: f64, k: &[f64]) -> f64 {
    let (first, t) = segment(x, k.len(), 3);
    let s = 1.0 - t;
    s * s * s * k[first]
        + 3.0 * s * s * t * k[first + 1]
        + 3.0 * s * t * t * k[first + 2]
        + t * t * t * k[first + 3]
}

fn bspline(x: f64, k: &[f64]) -> f64 {
    let (first, t) = segment(x, k.len(), 1);
    let s = 1.0 - t;
    let b = [
        s * s * s,
        3.0 * t * t * t - 6.0 * t * t + 4.0,
        -3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0,
        t * t * t,
    ];
    (0..4).map(|j| b[j] / 6.0 * k[first + j]).sum()
}

/// Knots are value, tangent, value, tangent, ...
fn hermite(x: f64, k: &[f64]) -> f64 {
    let (first, t) = segment(x, k.len(), 2);
    let (t2, t3) = (t * t, t * t * t);
    let h = [2.0 * t3 - 3.0 * t2 + 1.0, t3 - 2.0 * t2 + t, -2.0 * t3 + 3.0 * t2, t3 - t2];
    (0..4).map(|j| h[j] * k[first + j]).sum()
}

fn linear(x: f64, k: &[f64]) -> f64 {
    let (first, t) = segment(x, k.len(), 1);
    (1.0 - t) * k[first + 1] + t * k[first + 2]
}

/// A spline evaluated at a parameter over float knots.
type Reference = fn(f64, &[f64]) -> f64;

/// Parameters spanning the segments, both ends, and values outside [0, 1].
const XS: [f64; 14] = [0.0, 0.1, 0.2, 0.25, 1.0 / 3.0, 0.4, 0.5, 0.6, 2.0 / 3.0, 0.8, 0.95, 1.0, -0.5, 1.7];

#[test]
fn catmull_rom_passes_through_its_knots() {
    let knots = [3.0, 1.0, 4.0, 1.5, 5.0, 9.0];
    let src = "surface t() {
        Ci = spline(s, 3, 1, 4, 1.5, 5, 9);
        Oi = spline(\"catmull-rom\", s, 3, 1, 4, 1.5, 5, 9);
    }";
    // The segment boundaries (three segments) give knots 1 to 4.
    let at = [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0];
    let out = run_both(src, at.len(), &[], &[("s", &at)], &["Ci", "Oi"]);
    let want: Vec<f64> = knots[1..5].iter().flat_map(|k| [*k; 3]).collect();
    check(&out, 0, &want, "spline at the segment boundaries");
    check(&out, 1, &want, "named catmull-rom");
    let out = run_both(src, XS.len(), &[], &[("s", &XS)], &["Ci"]);
    let want: Vec<f64> = XS.iter().flat_map(|x| [catmull_rom(*x, &knots); 3]).collect();
    check(&out, 0, &want, "catmull-rom between the knots");
}

#[test]
fn the_named_bases() {
    // Seven knots: two Bezier segments, three Hermite ones would need eight (two, and a knot
    // left over), four Catmull-Rom, B-spline and linear ones.
    let knots = [0.5, 2.0, -1.0, 3.0, 0.0, 4.0, 1.0];
    let list = "0.5, 2, -1, 3, 0, 4, 1";
    let cases: [(&str, Reference); 4] =
        [("bezier", bezier), ("bspline", bspline), ("hermite", hermite), ("linear", linear)];
    for (name, reference) in cases {
        let src = format!("surface t() {{ Ci = spline(\"{name}\", s, {list}); }}");
        let out = run_both(&src, XS.len(), &[], &[("s", &XS)], &["Ci"]);
        let want: Vec<f64> = XS.iter().flat_map(|x| [reference(*x, &knots); 3]).collect();
        check(&out, 0, &want, name);
    }
    // Bezier passes through the knots that end its segments.
    assert_eq!([bezier(0.0, &knots), bezier(0.5, &knots), bezier(1.0, &knots)], [0.5, 3.0, 1.0]);
}

#[test]
fn the_linear_basis_draws_straight_lines() {
    // Knots 1 to 4 of six (the first and last are unused): 10, 20, 40, 0 at x = 0, 1/3, 2/3, 1.
    let src = "surface t() { Ci = spline(\"linear\", s, 99, 10, 20, 40, 0, -99); }";
    let xs = [0.0, 1.0 / 6.0, 1.0 / 3.0, 0.5, 2.0 / 3.0, 5.0 / 6.0, 1.0];
    let out = run_both(src, xs.len(), &[], &[("s", &xs)], &["Ci"]);
    let want: Vec<f64> = [10.0, 15.0, 20.0, 30.0, 40.0, 20.0, 0.0].iter().flat_map(|v| [*v; 3]).collect();
    check(&out, 0, &want, "linear spline");
}

#[test]
fn colour_point_and_array_splines() {
    let src = "surface t() {
        color c[5] = {color(0, 1, 2), color(1, 0, 0), color(2, 4, 8), color(3, 3, 3), color(0, 0, 1)};
        Ci = spline(s, c);
        point p = spline(\"bspline\", s, point(0, 0, 1), point(1, 2, 3), point(4, 1, 0), point(2, 2, 2), point(0, 5, 0));
        Oi = color(xcomp(p), ycomp(p), zcomp(p));
    }";
    let colours = [[0.0, 1.0, 2.0], [1.0, 0.0, 0.0], [2.0, 4.0, 8.0], [3.0, 3.0, 3.0], [0.0, 0.0, 1.0]];
    let points = [[0.0, 0.0, 1.0], [1.0, 2.0, 3.0], [4.0, 1.0, 0.0], [2.0, 2.0, 2.0], [0.0, 5.0, 0.0]];
    let out = run_both(src, XS.len(), &[], &[("s", &XS)], &["Ci", "Oi"]);
    let per_component = |f: Reference, knots: &[[f64; 3]]| -> Vec<f64> {
        XS.iter()
            .flat_map(|x| {
                (0..3)
                    .map(move |c| f(*x, &knots.iter().map(|k| k[c]).collect::<Vec<f64>>()))
                    .collect::<Vec<_>>()
            })
            .collect()
    };
    check(&out, 0, &per_component(catmull_rom, &colours), "colour array spline");
    check(&out, 1, &per_component(bspline, &points), "point spline");
}

#[test]
fn splines_of_a_uniform_parameter_and_array_parameter() {
    let src = "surface t(float x = 0.3; float k[6] = {1, 2, 0, 5, 3, 7}) { Ci = spline(x, k) + spline(\"linear\", s, k); }";
    let knots = [1.0, 2.0, 0.0, 5.0, 3.0, 7.0];
    let s = [0.0, 0.45, 0.9];
    for x in [0.3, 0.85] {
        let out = run_both(src, s.len(), &[("x", &[x])], &[("s", &s)], &["Ci"]);
        let want: Vec<f64> =
            s.iter().flat_map(|s| [catmull_rom(x, &knots) + linear(*s, &knots); 3]).collect();
        check(&out, 0, &want, &format!("x = {x}"));
    }
}

#[test]
fn spline_errors() {
    let src = "surface t(string b) { Ci = spline(b, s, 0, 1, 2, 3); }";
    let bound = |name: &str| Binding { strings: vec![("b".into(), name.into())], ..Binding::default() };
    assert_eq!(try_compile(src, &bound("cardinal")).err().map(|d| d.code), Some(Code::NotExecutable));
    assert!(try_compile(src, &bound("bezier")).is_ok());
    let short =
        try_compile("surface t() { float k[3] = {0, 1, 2}; Ci = spline(s, k); }", &Binding::default());
    assert_eq!(short.err().map(|d| d.code), Some(Code::NotExecutable));
}

// ---------------------------------------------------------------------------------------------
// fresnel
// ---------------------------------------------------------------------------------------------

/// Kr from the Fresnel equations in their angle form (Hecht): eta = n_incident / n_transmitted.
fn fresnel_kr(cos_i: f64, eta: f64) -> f64 {
    let ti = cos_i.abs().min(1.0).acos();
    let sin_t = eta * ti.sin();
    if sin_t > 1.0 {
        return 1.0;
    }
    if ti == 0.0 {
        return ((eta - 1.0) / (eta + 1.0)).powi(2);
    }
    let tt = sin_t.asin();
    let rs = (ti - tt).sin() / (ti + tt).sin();
    let rp = (ti - tt).tan() / (ti + tt).tan();
    (rs * rs + rp * rp) / 2.0
}

const FRESNEL: &str =
    "surface t(float eta = 1.5; output varying vector r = 0; output varying vector tr = 0) {
    float kr = -1, kt = -1;
    fresnel(I, N, eta, kr, kt, r, tr);
    float kr2, kt2;
    fresnel(I, N, eta, kr2, kt2);
    Ci = color(kr, kt, kr2 + kt2);
}";

#[test]
fn fresnel_at_normal_incidence() {
    for eta in [1.5, 1.0 / 1.33] {
        let out = run_both(
            FRESNEL,
            1,
            &[("eta", &[eta])],
            &[("I", &[0.0, 0.0, -2.0]), ("N", &[0.0, 0.0, 1.0])],
            &["Ci", "r", "tr"],
        );
        let kr = ((eta - 1.0) / (eta + 1.0)).powi(2);
        check(&out, 0, &[kr, 1.0 - kr, 1.0], &format!("Kr, Kt at eta {eta}"));
        check(&out, 1, &[0.0, 0.0, 2.0], "R");
        // Straight through, by the RI spec's refract (which expects unit vectors: I here is not,
        // and Kr above does not depend on its length): eta I - (eta I.N + sqrt(k)) N.
        let i_n = -2.0;
        let k: f64 = 1.0 - eta * eta * (1.0 - i_n * i_n);
        check(&out, 2, &[0.0, 0.0, eta * -2.0 - (eta * i_n + k.sqrt())], "T");
    }
}

#[test]
fn fresnel_at_an_angle_and_total_internal_reflection() {
    // Unit incident directions at 0 to 90 degrees from the normal in the x-z plane, the last one
    // exactly grazing (its cosine 0, not cos(pi / 2) in floating point).
    let angles: Vec<f64> = (0..19).map(|k| (k as f64 * 5.0).to_radians()).collect();
    let dirs: Vec<f64> = angles
        .iter()
        .flat_map(|a| if *a < 1.5 { [a.sin(), 0.0, -a.cos()] } else { [1.0, 0.0, 0.0] })
        .collect();
    let normals: Vec<f64> = angles.iter().flat_map(|_| [0.0, 0.0, 1.0]).collect();
    for eta in [1.0 / 1.5, 1.5] {
        let out = run_both(
            FRESNEL,
            angles.len(),
            &[("eta", &[eta])],
            &[("I", &dirs), ("N", &normals)],
            &["Ci", "r", "tr"],
        );
        let mut kr_kt = Vec::new();
        let mut reflected = Vec::new();
        let mut transmitted = Vec::new();
        for a in &angles {
            let kr = fresnel_kr(a.cos(), eta);
            kr_kt.extend([kr, 1.0 - kr, 1.0]);
            reflected.extend([a.sin(), 0.0, a.cos()]);
            // Snell's law: sin_t = eta sin_i, bent towards -N; nothing under total internal reflection.
            let sin_t = eta * a.sin();
            transmitted.extend(if sin_t > 1.0 {
                [0.0; 3]
            } else {
                [sin_t, 0.0, -(1.0 - sin_t * sin_t).sqrt()]
            });
        }
        check(&out, 0, &kr_kt, &format!("Kr, Kt at eta {eta}"));
        check(&out, 1, &reflected, "R");
        check(&out, 2, &transmitted, "T");
        if eta > 1.0 {
            // Past the critical angle (41.8 degrees) everything is reflected.
            let total = &out[0][0][9 * 3..];
            assert!(total.chunks(3).all(|c| c[0] == 1.0 && c[1] == 0.0), "{total:?}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Matrices and geometry
// ---------------------------------------------------------------------------------------------

#[test]
fn translate_rotate_scale_postconcatenate() {
    let src =
        "surface t(output matrix a = 0; output matrix b = 0; output matrix c = 0; output matrix d = 0) {
        uniform matrix one = 1;
        a = translate(one, vector(1, 2, 3));
        b = scale(a, point(2, 3, 4));
        c = rotate(one, 1.5707963267948966, vector(0, 0, 2));
        d = translate(scale(one, point(2, 2, 2)), vector(1, 0, 0));
        point p = transform(b, point(1, 1, 1));
        point q = transform(d, point(1, 1, 1));
        Ci = color(xcomp(p), ycomp(p), zcomp(p));
        Oi = color(xcomp(q), ycomp(q), zcomp(q));
    }";
    let out = run_both(src, 1, &[], &[], &["a", "b", "c", "d", "Ci", "Oi"]);
    #[rustfmt::skip]
    let translation = [
        1.0, 0.0, 0.0, 0.0,
        0.0, 1.0, 0.0, 0.0,
        0.0, 0.0, 1.0, 0.0,
        1.0, 2.0, 3.0, 1.0,
    ];
    check(&out, 0, &translation, "translate");
    // T S: the translation is scaled too, since the scale applies after it.
    #[rustfmt::skip]
    let then_scale = [
        2.0, 0.0, 0.0, 0.0,
        0.0, 3.0, 0.0, 0.0,
        0.0, 0.0, 4.0, 0.0,
        2.0, 6.0, 12.0, 1.0,
    ];
    check(&out, 1, &then_scale, "scale after translate");
    // A quarter turn about +z takes +x to +y: row 0 is the image of x.
    #[rustfmt::skip]
    let quarter = [
        0.0, 1.0, 0.0, 0.0,
        -1.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 1.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
    ];
    check(&out, 2, &quarter, "rotate");
    // ((1, 1, 1) + (1, 2, 3)) * (2, 3, 4), and (1, 1, 1) * 2 + (1, 0, 0).
    check(&out, 4, &[4.0, 9.0, 16.0], "transform by translate then scale");
    check(&out, 5, &[3.0, 2.0, 2.0], "transform by scale then translate");
}

#[test]
fn rotation_about_the_diagonal_permutes_the_axes() {
    // A third of a turn about (1, 1, 1) takes x to y, y to z, z to x.
    let src = "surface t(output matrix m = 0) {
        m = rotate(matrix 1, 2.0943951023931953, vector(1, 1, 1));
        point q = rotate(point(3, 1, 1), 2.0943951023931953, point(1, 1, 1), point(2, 2, 2));
        Ci = color(xcomp(q), ycomp(q), zcomp(q));
    }";
    let out = run_both(src, 1, &[], &[], &["m", "Ci"]);
    #[rustfmt::skip]
    let cycle = [
        0.0, 1.0, 0.0, 0.0,
        0.0, 0.0, 1.0, 0.0,
        1.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
    ];
    check(&out, 0, &cycle, "rotate(m, 2pi/3, (1, 1, 1))");
    // (3, 1, 1) is (1, 1, 1) + 2x; it goes to (1, 1, 1) + 2y.
    check(&out, 1, &[1.0, 3.0, 1.0], "rotate a point about an axis through (1, 1, 1)");
}

#[test]
fn rotate_points_about_an_axis_through_two_points() {
    // About the vertical line through (1, 1): a quarter turn takes (2, 1, z) to (1, 2, z); the
    // angle varies per point.
    let src = "surface t() { point q = rotate(point(2, 1, 5), s, point(1, 1, 0), point(1, 1, 3)); Ci = color(xcomp(q), ycomp(q), zcomp(q)); }";
    let angles = [0.0, std::f64::consts::FRAC_PI_2, std::f64::consts::PI, 0.3];
    let out = run_both(src, angles.len(), &[], &[("s", &angles)], &["Ci"]);
    let want: Vec<f64> = angles.iter().flat_map(|a| [1.0 + a.cos(), 1.0 + a.sin(), 5.0]).collect();
    check(&out, 0, &want, "rotate(q, angle, p0, p1)");
}

#[test]
fn ptlined_measures_to_the_segment() {
    let src = "surface t() {
        Ci = color(ptlined(point(0, 0, 0), point(4, 0, 0), P),
                   ptlined(point(1, 1, 1), point(1, 1, 1), P),
                   ptlined(point(4, 0, 0), point(0, 0, 0), P));
    }";
    // Beside the middle, beyond either end, on the segment.
    let ps = [[2.0, 3.0, 0.0], [-3.0, 4.0, 0.0], [7.0, 0.0, 4.0], [1.5, 0.0, 0.0]];
    let out = run_both(src, ps.len(), &[], &[("P", &flat(&ps))], &["Ci"]);
    let to_point = |p: [f64; 3]| ((p[0] - 1.0).powi(2) + (p[1] - 1.0).powi(2) + (p[2] - 1.0).powi(2)).sqrt();
    let segment = [3.0, 5.0, 5.0, 0.0];
    let want: Vec<f64> = ps.iter().zip(segment).flat_map(|(p, d)| [d, to_point(*p), d]).collect();
    check(&out, 0, &want, "ptlined");
}

#[test]
fn depth_spans_the_clipping_planes() {
    let src = "surface t() { Ci = depth(P); }";
    let ps = [0.0, 0.0, 1.0, 5.0, 5.0, 6.0, 0.0, 0.0, 11.0];
    let out = run_both(src, 3, &[("clip", &[1.0, 11.0])], &[("P", &ps)], &["Ci"]);
    check(&out, 0, &[0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0], "depth with near 1, far 11");
    // Unset: the range is empty and counts as 1, giving z.
    let out = run_both(src, 3, &[], &[("P", &ps)], &["Ci"]);
    check(&out, 0, &[1.0, 1.0, 1.0, 6.0, 6.0, 6.0, 11.0, 11.0, 11.0], "depth without clipping planes");
}

#[test]
fn match_finds_patterns() {
    let src = r#"surface t(string name) {
        Ci = color(match("brush", name), match("^metal", name), match("^brush", name));
        Oi = color(match("_[a-c]r.*d$", name), match("^[^_]*$", name), match("x*", ""));
    }"#;
    let evaluate = |name: &str| {
        let binding = Binding { strings: vec![("name".into(), name.into())], ..Binding::default() };
        let program = try_compile(src, &binding).unwrap();
        Evaluator::<f64>::new(&program).eval_points(1, &[], &["Ci", "Oi"]).unwrap()
    };
    assert_eq!(evaluate("metal_brushed"), vec![vec![1.0, 1.0, 0.0], vec![1.0, 0.0, 1.0]]);
    assert_eq!(evaluate("wood"), vec![vec![0.0, 0.0, 0.0], vec![0.0, 1.0, 1.0]]);
    let groups = try_compile(r#"surface t() { Ci = match("(a|b)", "a"); }"#, &Binding::default());
    assert_eq!(groups.err().map(|d| d.code), Some(Code::NotExecutable));
}
