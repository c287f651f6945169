//! Shadow-map lookups as arithmetic on texel fetches, like `opt::textures`, so that the
//! interpreter and the GPU compute the same fraction, operation for operation.
//!
//! A shadow map is a 2D texture of `w × (h + 1)` texels. Rows 0 to h − 1 hold depths (channel 0):
//! the light-space depth of the nearest surface seen through each texel, as RenderMan's shadow
//! files do. Like a RenderMan shadow file the map carries its own camera: the first four texels
//! of the last row, h, are the rows of the 4×4 matrix `M` that takes a point of the shader's
//! current space (camera space) to `(x, y, depth, w)`, where `(x/w, y/w)` is in [−1, 1]² over the
//! map (y up, so row 0 is y/w = 1) and `depth` is in the units of the stored depths; the fifth
//! texel's first channel is the map's own bias, used when the lookup gives none (RenderMan's
//! `Option "shadow" "bias"`, here per map). The renderer writes the maps
//! (runtime/src/render/shadow.rs); no uniform carries the light's matrices.
//!
//! `shadow(name, P, "samples", n, "blur", b, "bias", x, "width", f)` becomes
//!
//! ```text
//! (cx, cy, d, cw) = (M0·P, M1·P, M2·P, M3·P)        (P as (x, y, z, 1), Mi = __texel2d(name, i, h))
//! s = 0.5 + 0.5 cx / cw,  t = 0.5 − 0.5 cy / cw       (cw ≤ 0: behind the light, never shadowed)
//! r = b + f / w                                        (blur, plus f texels of footprint)
//! shadow = Σ_k [inside(s_k, t_k) and d > depth(s_k, t_k) + x] / n,  (s_k, t_k) = (s, t) + r o_k
//! ```
//!
//! with `depth(s, t)` the nearest texel (no filtering of depths, which would be meaningless) and
//! the taps `o_k` a fixed Vogel spiral in the disc of radius ½ (`tap`), the same on every backend
//! because they are literals. Taps outside the map are lit. The result is the fraction of taps in
//! shadow: 1 is fully shadowed (RI 3.2 §15.7.3).
//!
//! The options: `"samples"` (default 16, at most 256) must be a constant once binding has folded
//! the parameters, else the default is used; `"blur"` (default 0, a fraction of the map),
//! `"bias"` (default the map's, in depth units) and `"width"` (default 1, a multiple of one texel) may be
//! any float expressions. Unknown options are ignored. The four-point form reads the points'
//! mean. The footprint is a fixed number of texels, not the lookup's screen-space footprint.
//!
//! Runs after `opt::derivs` and before the split, rewriting each lookup in place at its rate.

use super::textures::{constant, option};
use crate::ir::builtin::BuiltinId;
use crate::ir::types::Type;
use crate::ir::{BinaryOp, ExprId, ExprKind, Shader};
use crate::opt::build::Builder;

/// Taps when a lookup names no `"samples"` (or names a value that is not a constant).
pub const DEFAULT_SAMPLES: u32 = 16;

/// The most taps one lookup may take.
pub const MAX_SAMPLES: u32 = 256;

/// The options of one lookup, as expressions (or the defaults).
struct Options {
    samples: u32,
    blur: Option<ExprId>,
    bias: Option<ExprId>,
    width: Option<ExprId>,
}

/// Rewrites every `shadow` lookup of `shader` into texel fetches and arithmetic.
pub(crate) fn expand(shader: &mut Shader) {
    let lookups: Vec<ExprId> = (0..shader.exprs.len() as u32)
        .map(ExprId)
        .filter(|id| matches!(&shader.expr(*id).kind, ExprKind::Builtin(b, _) if b.id == BuiltinId::Shadow))
        .collect();
    for id in lookups {
        let span = shader.expr(id).span;
        let (args, positional) = match &shader.expr(id).kind {
            ExprKind::Builtin(b, args) => (args.clone(), b.params.len().min(args.len())),
            _ => continue,
        };
        if positional < 2 {
            continue;
        }
        let options = options(shader, &args[positional..]);
        let rate = shader.expr(id).rate;
        let first_new = shader.exprs.len();
        let mut b = Builder::new(shader, span);
        let texture = args[0];
        let p = if positional >= 5 {
            let quarter = b.float(0.25);
            let ab = b.binary(BinaryOp::Add, args[1], args[2]);
            let cd = b.binary(BinaryOp::Add, args[3], args[4]);
            let sum = b.binary(BinaryOp::Add, ab, cd);
            b.binary(BinaryOp::Mul, sum, quarter)
        } else {
            args[1]
        };
        let value = lookup(&mut b, texture, p, &options);
        b.shader.exprs[id.0 as usize].kind = ExprKind::Convert(value);
        for e in &mut b.shader.exprs[first_new..] {
            e.rate = e.rate.join(rate);
        }
    }
    crate::verify::assert_valid(shader, crate::verify::Pass::Shadows);
}

/// The `"name", value` pairs after the positional arguments.
fn options(shader: &Shader, pairs: &[ExprId]) -> Options {
    let samples = option(shader, pairs, "samples")
        .and_then(|n| constant(shader, n))
        .map_or(DEFAULT_SAMPLES, |n| n.round().clamp(1.0, f64::from(MAX_SAMPLES)) as u32);
    Options {
        samples,
        blur: option(shader, pairs, "blur"),
        bias: option(shader, pairs, "bias"),
        width: option(shader, pairs, "width"),
    }
}

/// Tap `k` of `n`: a Vogel (golden-angle) spiral filling the disc of radius ½; the centre for
/// one tap.
pub fn tap(k: u32, n: u32) -> [f64; 2] {
    if n <= 1 {
        return [0.0, 0.0];
    }
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let r = 0.5 * ((f64::from(k) + 0.5) / f64::from(n)).sqrt();
    let a = golden * f64::from(k);
    [r * a.cos(), r * a.sin()]
}

/// The fraction of the taps of `options` in shadow for the point `p` (see the module docs).
fn lookup(b: &mut Builder, texture: ExprId, p: ExprId, options: &Options) -> ExprId {
    let float =
        |b: &mut Builder, e: ExprId| if b.ty(e) == Type::FLOAT { e } else { b.convert(e, Type::FLOAT) };
    let (zero_i, one_i) = (b.int(0), b.int(1));
    let width = b.call(BuiltinId::Texsize2d, vec![texture, zero_i]);
    let height = b.call(BuiltinId::Texsize2d, vec![texture, one_i]);
    // The depth rows, and the matrix row below them.
    let rows = b.binary(BinaryOp::Sub, height, one_i);
    let width_f = b.convert(width, Type::FLOAT);
    let rows_f = b.convert(rows, Type::FLOAT);
    let point: Vec<ExprId> = (0..3).map(|i| b.index(p, i)).collect();
    let row = |b: &mut Builder, i: i32| {
        let column = b.int(i);
        let m = b.call(BuiltinId::Texel2d, vec![texture, column, rows]);
        let mut sum = None;
        for c in 0..4 {
            let mc = b.index(m, c);
            let term = if c == 3 { mc } else { b.binary(BinaryOp::Mul, mc, point[c as usize]) };
            sum = Some(match sum {
                None => term,
                Some(total) => b.binary(BinaryOp::Add, total, term),
            });
        }
        sum.expect("four terms")
    };
    let (cx, cy, depth, cw) = (row(b, 0), row(b, 1), row(b, 2), row(b, 3));
    let zero = b.float(0.0);
    let (half, one) = (b.float(0.5), b.float(1.0));
    let front = b.binary(BinaryOp::Gt, cw, zero);
    let safe_w = b.select(front, cw, one);
    let inv_w = b.binary(BinaryOp::Div, one, safe_w);
    let ndc = |b: &mut Builder, c: ExprId, sign: f64| {
        let scaled = b.binary(BinaryOp::Mul, c, inv_w);
        let k = b.float(0.5 * sign);
        let scaled = b.binary(BinaryOp::Mul, scaled, k);
        b.binary(BinaryOp::Add, half, scaled)
    };
    let (s, t) = (ndc(b, cx, 1.0), ndc(b, cy, -1.0));
    // The radius of the taps: blur plus the footprint in texels.
    let texel = b.binary(BinaryOp::Div, one, width_f);
    let footprint = match options.width {
        Some(f) => {
            let f = float(b, f);
            b.binary(BinaryOp::Mul, f, texel)
        }
        None => texel,
    };
    let spread = match options.blur {
        Some(blur) => {
            let blur = float(b, blur);
            b.binary(BinaryOp::Add, blur, footprint)
        }
        None => footprint,
    };
    let bias = match options.bias {
        Some(bias) => float(b, bias),
        None => {
            let column = b.int(4);
            let texel = b.call(BuiltinId::Texel2d, vec![texture, column, rows]);
            b.index(texel, 0)
        }
    };
    let reach = b.binary(BinaryOp::Sub, depth, bias);
    let (lo, hi) = (b.float(-1.0), b.float(2.0));
    let mut sum = None;
    for k in 0..options.samples {
        let [ox, oy] = tap(k, options.samples);
        let coordinate = |b: &mut Builder, c: ExprId, o: f64, size: ExprId, size_f: ExprId| {
            let o = b.float(o);
            let offset = b.binary(BinaryOp::Mul, spread, o);
            let c = b.binary(BinaryOp::Add, c, offset);
            // Clamped so that the conversion to int is exact on every backend.
            let c = b.call(BuiltinId::Clamp, vec![c, lo, hi]);
            let ge = b.binary(BinaryOp::Ge, c, zero);
            let lt = b.binary(BinaryOp::Lt, c, one);
            let inside = b.binary(BinaryOp::And, ge, lt);
            let scaled = b.binary(BinaryOp::Mul, c, size_f);
            let floor = b.call(BuiltinId::Floor, vec![scaled]);
            let i = b.convert(floor, Type::INT);
            (wrap(b, i, size), inside)
        };
        let (x, inside_x) = coordinate(b, s, ox, width, width_f);
        let (y, inside_y) = coordinate(b, t, oy, rows, rows_f);
        let stored = b.call(BuiltinId::Texel2d, vec![texture, x, y]);
        let stored = b.index(stored, 0);
        let behind = b.binary(BinaryOp::Gt, reach, stored);
        let inside = b.binary(BinaryOp::And, inside_x, inside_y);
        let shadowed = b.binary(BinaryOp::And, inside, behind);
        let shadowed = b.binary(BinaryOp::And, shadowed, front);
        let value = b.select(shadowed, one, zero);
        sum = Some(match sum {
            None => value,
            Some(total) => b.binary(BinaryOp::Add, total, value),
        });
    }
    let total = sum.unwrap_or(zero);
    let n = b.float(f64::from(options.samples.max(1)));
    b.binary(BinaryOp::Div, total, n)
}

/// `((i % n) + n) % n`: an index wrapped into [0, n).
fn wrap(b: &mut Builder, i: ExprId, n: ExprId) -> ExprId {
    let r = b.binary(BinaryOp::Rem, i, n);
    let r = b.binary(BinaryOp::Add, r, n);
    b.binary(BinaryOp::Rem, r, n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn taps_fill_the_half_disc_and_one_tap_is_the_centre() {
        assert_eq!(tap(0, 1), [0.0, 0.0]);
        for n in [4, 16, 64] {
            let taps: Vec<[f64; 2]> = (0..n).map(|k| tap(k, n)).collect();
            let mean =
                taps.iter().fold([0.0, 0.0], |m, t| [m[0] + t[0] / f64::from(n), m[1] + t[1] / f64::from(n)]);
            for t in &taps {
                assert!(t[0].hypot(t[1]) <= 0.5 + 1e-12, "{t:?}");
            }
            // Spread evenly: the mean is near the centre.
            assert!(mean[0].hypot(mean[1]) < 0.1, "{n}: {mean:?}");
        }
        // The outermost of 16 taps: radius ½ √(15.5/16).
        let last = tap(15, 16);
        assert!((last[0].hypot(last[1]) - 0.5 * (15.5f64 / 16.0).sqrt()).abs() < 1e-12);
    }
}
