//! Texture lookups as arithmetic on texel fetches, so that the interpreter and the GPU filter the
//! same way, operation for operation (the GPU's own samplers compute their weights in
//! implementation-defined fixed point, which a reference could not reproduce).
//!
//! The filter: bilinear (trilinear in 3D) on level 0, coordinates wrapping (`repeat`). Texel
//! centres are at (i + ½) / size; texel row 0 is t = 0 (the image's top row, RenderMan's
//! convention). A lookup of `texture("name", s, t)` becomes
//!
//! ```text
//! x = s * w - 0.5;  x0 = floor(x);  fx = x - x0;  i0 = wrap(int(x0));  i1 = wrap(i0 + 1)   (and y)
//! c = mix(mix(T[i0, j0], T[i1, j0], fx), mix(T[i0, j1], T[i1, j1], fx), fy)
//! ```
//!
//! with `wrap(i) = ((i % w) + w) % w` and `T` the internal built-ins `__texel2d` / `__texel3d`,
//! `w` from `__texsize2d` / `__texsize3d`. The result is the first channel for a `float` lookup, RGB for a `color`,
//! RGBA for Stanford's `float4`. RenderMan's one-argument form reads `s` and `t`; the
//! four-corner form uses the corners' mean. Stanford's float4 coordinate is homogeneous (divided
//! by w); its float3 one is (s, t, r), of which a 2D lookup reads (s, t).
//!
//! `environment(name, D)` (and the four-direction form, which looks up the directions' mean) is
//! the same bilinear filter over a 2D texture that holds either a lat-long map or a cube map, told
//! apart at run time by the texture's shape (`runtime/src/render/textures.rs` makes both):
//!
//! - a **cube map** is an atlas three faces wide and two tall (width × 2 = height × 3, or
//!   width × 4 = (height + 2) × 3 with its chain below it): faces
//!   +X, −X, +Y in the top row, −Y, +Z, −Z in the bottom one, each F × F texels (F = width / 3).
//!   The face is D's major axis (ties go to x, then y), chosen branch-free, and the face
//!   coordinates are OpenGL's: (u, v) = ((sc / |ma| + 1) / 2, (tc / |ma| + 1) / 2) with (sc, tc)
//!   = (−z, −y) on +X, (z, −y) on −X, (x, z) on +Y, (x, −z) on −Y, (x, −y) on +Z, (−x, −y) on −Z,
//!   v = 0 the face image's top row. Texel coordinates clamp to the face (no filtering across
//!   face edges);
//! - anything else is a **lat-long map**, +Y up: s = ½ + atan(x, −z) / 2π (so −Z is the map's
//!   centre column, +X three quarters across, +Z the seam), t = atan(√(x² + z²), y) / π (t = 0,
//!   the image's top row, straight up). The filter wraps in s and clamps in t. A zero D reads
//!   (½, ½).
//!
//! D need not be normalized. A lat-long map may carry its mip chain (the runtime's `sky:N` and
//! `env:FILE` do): a texture w texels wide and w − 1 tall holds level 0 (w × w/2, w a power of
//! two) in its top rows and each further level, half as wide and tall, below the previous one,
//! down to 2 × 1. Such a map is filtered trilinearly: the footprint f (radians) is the lookup's
//! `"__footprint"` (added by `footprints` before `opt::derivs`: √area(D), from D's screen
//! derivatives) over |D|, times `"width"` when given; in level-0 texels it is
//! f · w / 2π + blur · w (`"blur"`, a fraction of the map's width, when given), and the level is
//! log2 of that (at least 1 texel), clamped to the last level. A cube atlas may carry its chain
//! too (`skycube:N`, `cube:` with faces a power of two wide): 3F wide and 4F − 2 tall, each
//! level (faces half as wide) below the previous one, down to faces of one texel; its footprint
//! is counted in the texels around its equator, 4F, as a lat-long map's in its width. Maps
//! without a chain are read at level 0, where `"blur"` and `"width"` do nothing.
//!
//! Other optional `"name", value` pairs after a lookup's positional arguments are skipped here.
//!
//! Runs after `opt::derivs` (texture lookups carry no derivatives through it) and before the
//! split; rewrites each lookup in place, appending the expressions it needs, all at the lookup's
//! rate.

use crate::ir::builtin::BuiltinId;
use crate::ir::types::{Base, Type};
use crate::ir::{BinaryOp, ExprId, ExprKind, Literal, Shader};
use crate::opt::build::Builder;
use crate::sema::globals;

/// Rewrites every `texture`, `texture3d` and `environment` lookup of `shader` into texel fetches
/// and arithmetic.
pub(crate) fn expand(shader: &mut Shader) {
    let lookups: Vec<ExprId> = (0..shader.exprs.len() as u32)
        .map(ExprId)
        .filter(|id| {
            matches!(&shader.expr(*id).kind, ExprKind::Builtin(b, _)
                if matches!(b.id, BuiltinId::Texture | BuiltinId::Texture3d | BuiltinId::Environment))
        })
        .collect();
    for id in lookups {
        let span = shader.expr(id).span;
        let (args, options, lookup) = match &shader.expr(id).kind {
            // The positional arguments; optional "name", value pairs may follow them.
            ExprKind::Builtin(b, args) => {
                let n = b.params.len().min(args.len());
                (args[..n].to_vec(), args[n..].to_vec(), b.id)
            }
            _ => continue,
        };
        let three_d = lookup == BuiltinId::Texture3d;
        let ret = shader.expr(id).ty;
        let rate = shader.expr(id).rate;
        let first_new = shader.exprs.len();
        let mut b = Builder::new(shader, span);
        let (texture, channel) = channel_selection(b.shader, args[0]);
        let rgba = if lookup == BuiltinId::Environment {
            let Some(direction) = environment_direction(&mut b, &args) else { continue };
            let footprint = Footprint {
                width: option(b.shader, &options, FOOTPRINT),
                scale: option(b.shader, &options, "width"),
                blur: option(b.shader, &options, "blur"),
            };
            environment(&mut b, texture, direction, footprint)
        } else {
            let Some(coords) = coordinates(&mut b, &args, three_d) else { continue };
            if three_d { filter3(&mut b, texture, &coords) } else { filter2(&mut b, texture, &coords) }
        };
        let value = match ret.base {
            Base::Float => b.index(rgba, channel.min(3)),
            Base::Color => {
                let parts = (0..3).map(|c| b.index(rgba, (channel + c).min(3))).collect();
                b.construct(parts, Type::of(Base::Color))
            }
            _ => rgba,
        };
        // The lookup's expression becomes a copy of the filtered value.
        b.shader.exprs[id.0 as usize].kind = ExprKind::Convert(value);
        // The filter runs at the lookup's rate (per fragment: a lookup is a derivative consumer),
        // never at its coordinates' rate: interpolating a filtered value, or a texel coordinate,
        // between vertices would be a different filter.
        for e in &mut b.shader.exprs[first_new..] {
            e.rate = e.rate.join(rate);
        }
    }
    crate::verify::assert_valid(shader, crate::verify::Pass::Textures);
}

/// RenderMan's channel selection, `texture("name"[k], ...)`: the texture's name and the first
/// channel the lookup reads (a float lookup reads channel k, a colour one k to k + 2, clamped
/// to the four channels a texel has). `k` is a constant in every shader seen; any other index
/// reads from channel 0.
fn channel_selection(shader: &Shader, name: ExprId) -> (ExprId, u32) {
    let ExprKind::Index(texture, k) = &shader.expr(name).kind else { return (name, 0) };
    let channel = constant(shader, *k).filter(|k| *k >= 0.0).map(|k| k.trunc() as u32);
    (*texture, channel.unwrap_or(0))
}

/// The name of the option pair [`footprints`] appends to each `environment` lookup: its value is
/// the lookup's footprint, the width of the region its direction sweeps across a pixel.
const FOOTPRINT: &str = "__footprint";

/// Gives every `environment` lookup its footprint, as a trailing `"__footprint", w` option pair:
/// for `environment(name, D)` w = sqrt(area(D)) (the square root of |dD/dx × dD/dy|, screen
/// derivatives); for the four-direction form the largest distance from the first direction to
/// the others. Runs before `opt::derivs`, which rewrites `area` into arithmetic on derivatives
/// (0 for a D that does not vary); `expand` divides w by |D| to make it an angle.
pub(crate) fn footprints(shader: &mut Shader) {
    let lookups: Vec<ExprId> = (0..shader.exprs.len() as u32)
        .map(ExprId)
        .filter(
            |id| matches!(&shader.expr(*id).kind, ExprKind::Builtin(b, _) if b.id == BuiltinId::Environment),
        )
        .collect();
    for id in lookups {
        let span = shader.expr(id).span;
        let ExprKind::Builtin(builtin, args) = shader.expr(id).kind.clone() else { continue };
        let n = builtin.params.len().min(args.len());
        let mut b = Builder::new(shader, span);
        let width = match n {
            2 => {
                let point = b.convert(args[1], Type::of(Base::Point));
                let area = b.call(BuiltinId::Area, vec![point]);
                b.call(BuiltinId::Sqrt, vec![area])
            }
            5 => {
                let distance = |b: &mut Builder, k: usize| {
                    let d = b.binary(BinaryOp::Sub, args[k], args[1]);
                    b.call(BuiltinId::Length, vec![d])
                };
                let (d2, d3, d4) = (distance(&mut b, 2), distance(&mut b, 3), distance(&mut b, 4));
                b.call(BuiltinId::Max, vec![d2, d3, d4])
            }
            _ => continue,
        };
        let name = b.push(ExprKind::Literal(Literal::String(FOOTPRINT.into())), Type::STRING);
        if let ExprKind::Builtin(_, args) = &mut b.shader.exprs[id.0 as usize].kind {
            args.extend([name, width]);
        }
    }
    crate::verify::assert_valid(shader, crate::verify::Pass::Footprints);
}

/// The value of option `name` among a lookup's trailing `"name", value` pairs (a numeric
/// scalar; the last pair naming it wins, as in RenderMan's parameter lists).
pub(crate) fn option(shader: &Shader, pairs: &[ExprId], name: &str) -> Option<ExprId> {
    pairs.chunks_exact(2).rev().find_map(|pair| {
        let ExprKind::Literal(Literal::String(n)) = &shader.expr(pair[0]).kind else { return None };
        let ty = shader.expr(pair[1]).ty;
        let numeric = matches!(ty.base, Base::Float | Base::Int | Base::Uint) && !ty.is_array();
        (n.as_str() == name && numeric).then_some(pair[1])
    })
}

/// The value of a constant numeric expression (a literal, possibly converted).
pub(crate) fn constant(shader: &Shader, e: ExprId) -> Option<f64> {
    match &shader.expr(e).kind {
        ExprKind::Literal(Literal::Float(x)) if x.is_finite() => Some(*x),
        ExprKind::Literal(Literal::Int(i)) => Some(f64::from(*i)),
        ExprKind::Literal(Literal::Uint(u)) => Some(f64::from(*u)),
        ExprKind::Convert(inner) => constant(shader, *inner),
        _ => None,
    }
}

/// What widens an environment lookup's filter: its footprint (from [`footprints`]) and the
/// `"width"` (a factor on it) and `"blur"` (added, a fraction of the map's width) options.
struct Footprint {
    width: Option<ExprId>,
    scale: Option<ExprId>,
    blur: Option<ExprId>,
}

/// The lookup's coordinates as floats: (s, t) or (s, t, r).
fn coordinates(b: &mut Builder, args: &[ExprId], three_d: bool) -> Option<Vec<ExprId>> {
    let shader_kind = b.shader.kind;
    let stanford = b.shader.stanford;
    let global = |b: &mut Builder, name: &str| {
        globals::lookup(name, shader_kind, stanford).map(|g| b.push(ExprKind::Global(g), Type::of(g.ty)))
    };
    match args.len() {
        1 => Some(vec![global(b, "s")?, global(b, "t")?]),
        3 => Some(vec![args[1], args[2]]),
        9 => {
            let quarter = b.float(0.25);
            let mean = |b: &mut Builder, i: usize| {
                let ab = b.binary(BinaryOp::Add, args[i], args[i + 2]);
                let cd = b.binary(BinaryOp::Add, args[i + 4], args[i + 6]);
                let sum = b.binary(BinaryOp::Add, ab, cd);
                b.binary(BinaryOp::Mul, sum, quarter)
            };
            Some(vec![mean(b, 1), mean(b, 2)])
        }
        2 => {
            let c = args[1];
            let n = if three_d { 3 } else { 2 };
            let mut parts: Vec<ExprId> = (0..n).map(|i| b.index(c, i)).collect();
            if b.ty(c).base == Base::Float4 {
                let w = b.index(c, 3);
                parts = parts.into_iter().map(|p| b.binary(BinaryOp::Div, p, w)).collect();
            }
            Some(parts)
        }
        _ => None,
    }
}

/// Integer coordinates of the two texels around `coord` along an axis of `size` texels, and the
/// weight of the second.
pub(crate) fn axis(
    b: &mut Builder,
    texture: ExprId,
    which: i32,
    coord: ExprId,
    three_d: bool,
) -> (ExprId, ExprId, ExprId) {
    let a = b.int(which);
    let size = b.call(if three_d { BuiltinId::Texsize3d } else { BuiltinId::Texsize2d }, vec![texture, a]);
    let size_f = b.convert(size, Type::FLOAT);
    let half = b.float(0.5);
    let scaled = b.binary(BinaryOp::Mul, coord, size_f);
    let x = b.binary(BinaryOp::Sub, scaled, half);
    let x0 = b.call(BuiltinId::Floor, vec![x]);
    let fraction = b.binary(BinaryOp::Sub, x, x0);
    let i0 = b.convert(x0, Type::INT);
    let i0 = wrap(b, i0, size);
    let one = b.int(1);
    let next = b.binary(BinaryOp::Add, i0, one);
    let i1 = wrap(b, next, size);
    (i0, i1, fraction)
}

/// `((i % n) + n) % n`: a coordinate wrapped into [0, n).
pub(crate) fn wrap(b: &mut Builder, i: ExprId, n: ExprId) -> ExprId {
    let r = b.binary(BinaryOp::Rem, i, n);
    let r = b.binary(BinaryOp::Add, r, n);
    b.binary(BinaryOp::Rem, r, n)
}

fn mix(b: &mut Builder, x: ExprId, y: ExprId, t: ExprId) -> ExprId {
    b.call(BuiltinId::Mix, vec![x, y, t])
}

/// The bilinear filter of a 2D texture at (s, t) = (`c[0]`, `c[1]`), wrapping on both axes: the
/// RGBA `float4`.
pub(crate) fn filter2(b: &mut Builder, texture: ExprId, c: &[ExprId]) -> ExprId {
    let (x0, x1, fx) = axis(b, texture, 0, c[0], false);
    let (y0, y1, fy) = axis(b, texture, 1, c[1], false);
    bilinear(b, texture, [x0, x1, fx], [y0, y1, fy])
}

/// The texel coordinates (unwrapped, unclamped) of the two texels around `coord` along an axis of
/// `size` texels, and the weight of the second: x = coord * size - ½, i0 = floor(x), i1 = i0 + 1.
pub(crate) fn split(b: &mut Builder, coord: ExprId, size: ExprId) -> (ExprId, ExprId, ExprId) {
    let half = b.float(0.5);
    let scaled = b.binary(BinaryOp::Mul, coord, size);
    let x = b.binary(BinaryOp::Sub, scaled, half);
    let x0 = b.call(BuiltinId::Floor, vec![x]);
    let fraction = b.binary(BinaryOp::Sub, x, x0);
    let i0 = b.convert(x0, Type::INT);
    let one = b.int(1);
    let i1 = b.binary(BinaryOp::Add, i0, one);
    (i0, i1, fraction)
}

/// The bilinear blend of the four texels at integer coordinates `x[0..2]` × `y[0..2]`, with the
/// weights `x[2]`, `y[2]` of the second of each pair.
pub(crate) fn bilinear(b: &mut Builder, texture: ExprId, x: [ExprId; 3], y: [ExprId; 3]) -> ExprId {
    let ([x0, x1, fx], [y0, y1, fy]) = (x, y);
    let mut texel = |x, y| b.call(BuiltinId::Texel2d, vec![texture, x, y]);
    let (c00, c10, c01, c11) = (texel(x0, y0), texel(x1, y0), texel(x0, y1), texel(x1, y1));
    let top = mix(b, c00, c10, fx);
    let bottom = mix(b, c01, c11, fx);
    mix(b, top, bottom, fy)
}

/// The direction of an environment lookup: D, or the mean of the four directions.
fn environment_direction(b: &mut Builder, args: &[ExprId]) -> Option<ExprId> {
    match args.len() {
        2 => Some(args[1]),
        5 => {
            let ab = b.binary(BinaryOp::Add, args[1], args[2]);
            let cd = b.binary(BinaryOp::Add, args[3], args[4]);
            let sum = b.binary(BinaryOp::Add, ab, cd);
            let quarter = b.float(0.25);
            Some(b.binary(BinaryOp::Mul, sum, quarter))
        }
        _ => None,
    }
}

/// The environment lookup along `d` (module documentation): a lat-long or a cube-map atlas,
/// chosen by the texture's shape, filtered bilinearly; the RGBA `float4`.
fn environment(b: &mut Builder, texture: ExprId, d: ExprId, footprint: Footprint) -> ExprId {
    let (x, y, z) = (b.index(d, 0), b.index(d, 1), b.index(d, 2));
    let zero_f = b.float(0.0);
    let half = b.float(0.5);
    let one_f = b.float(1.0);
    let (zero, one, two, three) = (b.int(0), b.int(1), b.int(2), b.int(3));
    let w = b.call(BuiltinId::Texsize2d, vec![texture, zero]);
    let h = b.call(BuiltinId::Texsize2d, vec![texture, one]);
    let w2 = b.binary(BinaryOp::Mul, w, two);
    let h3 = b.binary(BinaryOp::Mul, h, three);
    let plain_cube = b.binary(BinaryOp::Eq, w2, h3);
    // A cube atlas with its chain: 3F wide, 4F - 2 tall (4w = 3(h + 2)).
    let four = b.int(4);
    let w4 = b.binary(BinaryOp::Mul, w, four);
    let h_two = b.binary(BinaryOp::Add, h, two);
    let h_two3 = b.binary(BinaryOp::Mul, h_two, three);
    let cube_chain = b.binary(BinaryOp::Eq, w4, h_two3);
    let is_cube = b.binary(BinaryOp::Or, plain_cube, cube_chain);

    // Lat-long coordinates.
    let xx = b.binary(BinaryOp::Mul, x, x);
    let zz = b.binary(BinaryOp::Mul, z, z);
    let r2 = b.binary(BinaryOp::Add, xx, zz);
    let yy = b.binary(BinaryOp::Mul, y, y);
    let len2 = b.binary(BinaryOp::Add, r2, yy);
    let around = b.binary(BinaryOp::Gt, r2, zero_f);
    let nonzero = b.binary(BinaryOp::Gt, len2, zero_f);
    let minus_z = b.neg(z);
    let azimuth = b.call(BuiltinId::Atan, vec![x, minus_z]);
    let inv_two_pi = b.float(1.0 / (2.0 * std::f64::consts::PI));
    let s = b.binary(BinaryOp::Mul, azimuth, inv_two_pi);
    let s = b.binary(BinaryOp::Add, s, half);
    let s = b.select(around, s, half);
    let r = b.call(BuiltinId::Sqrt, vec![r2]);
    let polar = b.call(BuiltinId::Atan, vec![r, y]);
    let inv_pi = b.float(1.0 / std::f64::consts::PI);
    let t = b.binary(BinaryOp::Mul, polar, inv_pi);
    let t = b.select(nonzero, t, half);

    // Cube-map face and face coordinates.
    let (ax, ay, az) =
        (b.call(BuiltinId::Abs, vec![x]), b.call(BuiltinId::Abs, vec![y]), b.call(BuiltinId::Abs, vec![z]));
    let x_ge_y = b.binary(BinaryOp::Ge, ax, ay);
    let x_ge_z = b.binary(BinaryOp::Ge, ax, az);
    let x_major = b.binary(BinaryOp::And, x_ge_y, x_ge_z);
    let y_major = b.binary(BinaryOp::Ge, ay, az);
    let x_pos = b.binary(BinaryOp::Ge, x, zero_f);
    let y_pos = b.binary(BinaryOp::Ge, y, zero_f);
    let z_pos = b.binary(BinaryOp::Ge, z, zero_f);
    let minus_x = b.neg(x);
    let minus_y = b.neg(y);
    let pick = |b: &mut Builder, on_x: ExprId, on_y: ExprId, on_z: ExprId| {
        let yz = b.select(y_major, on_y, on_z);
        b.select(x_major, on_x, yz)
    };
    // Face index: +X 0, -X 1, +Y 2, -Y 3, +Z 4, -Z 5.
    let (f0, f1, f2, f3, f4, f5) = (zero, one, two, three, b.int(4), b.int(5));
    let fx = b.select(x_pos, f0, f1);
    let fy = b.select(y_pos, f2, f3);
    let fz = b.select(z_pos, f4, f5);
    let face = pick(b, fx, fy, fz);
    let scx = b.select(x_pos, minus_z, z);
    let scz = b.select(z_pos, x, minus_x);
    let sc = pick(b, scx, x, scz);
    let tcy = b.select(y_pos, z, minus_z);
    let tc = pick(b, minus_y, tcy, minus_y);
    let major = pick(b, ax, ay, az);
    let tiny = b.float(1e-30);
    let major = b.call(BuiltinId::Max, vec![major, tiny]);
    let to_unit = |b: &mut Builder, c: ExprId| {
        let q = b.binary(BinaryOp::Div, c, major);
        let q = b.binary(BinaryOp::Add, q, one_f);
        b.binary(BinaryOp::Mul, q, half)
    };
    let u = to_unit(b, sc);
    let v = to_unit(b, tc);
    let size = b.binary(BinaryOp::Div, w, three);
    let column = b.binary(BinaryOp::Rem, face, three);
    let row = b.binary(BinaryOp::Div, face, three);

    // The mip level: a map with its chain (a lat-long map w wide and w - 1 tall: level 0, w × w/2,
    // on top, each next level half as wide and tall below the last; a cube atlas 3F wide and
    // 4F - 2 tall, its levels likewise) is read at log2 of the footprint in level-0 texels,
    // trilinearly between the two levels about it; other maps at level 0.
    let w_less_one = b.binary(BinaryOp::Sub, w, one);
    let chain_shape = b.binary(BinaryOp::Eq, h, w_less_one);
    let not_plain_cube = b.binary(BinaryOp::Ne, w2, h3);
    let not_cube_chain = b.binary(BinaryOp::Ne, w4, h_two3);
    let is_latlong = b.binary(BinaryOp::And, not_plain_cube, not_cube_chain);
    let latlong_chain = b.binary(BinaryOp::And, chain_shape, is_latlong);
    let has_chain = b.binary(BinaryOp::Or, latlong_chain, cube_chain);
    let half_w = b.binary(BinaryOp::Div, w, two);
    let level0_h = b.select(latlong_chain, half_w, h);
    // Level 0's rows (a lat-long map) or a face's (a cube): the chain ends at one.
    let rows0 = b.select(is_cube, size, level0_h);
    let h0_f = b.convert(rows0, Type::FLOAT);
    let base = b.float(2.0);
    let top_level = b.call(BuiltinId::Log, vec![h0_f, base]);
    let top_level = b.binary(BinaryOp::Add, top_level, half);
    let top_level = b.call(BuiltinId::Floor, vec![top_level]);
    // The footprint in level-0 texels: an angle (the width over |D|) times the texels per radian
    // around the equator (a lat-long map's width, a cube's four faces), scaled by "width", plus
    // "blur" times those texels.
    let around_cube = b.binary(BinaryOp::Mul, size, four);
    let equator = b.select(is_cube, around_cube, w);
    let equator = b.convert(equator, Type::FLOAT);
    let mut texels = zero_f;
    if let Some(width) = footprint.width {
        let length = b.call(BuiltinId::Sqrt, vec![len2]);
        let length = b.call(BuiltinId::Max, vec![length, tiny]);
        let angle = b.binary(BinaryOp::Div, width, length);
        let per_radian = b.binary(BinaryOp::Mul, equator, inv_two_pi);
        texels = b.binary(BinaryOp::Mul, angle, per_radian);
        if let Some(scale) = footprint.scale {
            let scale = b.convert(scale, Type::FLOAT);
            texels = b.binary(BinaryOp::Mul, texels, scale);
        }
    }
    if let Some(blur) = footprint.blur {
        let blur = b.convert(blur, Type::FLOAT);
        let blur = b.binary(BinaryOp::Mul, blur, equator);
        texels = b.binary(BinaryOp::Add, texels, blur);
    }
    let texels = b.call(BuiltinId::Max, vec![texels, one_f]);
    let lod = b.call(BuiltinId::Log, vec![texels, base]);
    let lod = b.call(BuiltinId::Min, vec![lod, top_level]);
    let lod = b.select(has_chain, lod, zero_f);
    let lod_floor = b.call(BuiltinId::Floor, vec![lod]);
    let between = b.binary(BinaryOp::Sub, lod, lod_floor);
    let top_level = b.convert(top_level, Type::INT);
    let l0 = b.convert(lod_floor, Type::INT);
    let l0 = b.call(BuiltinId::Clamp, vec![l0, zero, top_level]);
    let l1 = b.binary(BinaryOp::Add, l0, one);
    let l1 = b.call(BuiltinId::Min, vec![l1, top_level]);
    let l1 = b.select(has_chain, l1, l0);

    // One filter per level: lat-long (s wraps over the level's width, t clamps to its height, its
    // rows below the levels above it) or the face's square.
    let s = b.select(is_cube, u, s);
    let t = b.select(is_cube, v, t);
    let across0 = b.select(is_cube, size, w);
    let down0 = b.select(is_cube, size, level0_h);
    let level = |b: &mut Builder, l: ExprId| {
        let across = b.binary(BinaryOp::Shr, across0, l);
        let down = b.binary(BinaryOp::Shr, down0, l);
        // Level l's first row: 2 h0 - 2 (h0 >> l), the heights of the levels above it (each
        // level of a cube atlas two faces tall: twice that), then the face's row in it.
        let twice = b.binary(BinaryOp::Mul, down0, two);
        let twice_l = b.binary(BinaryOp::Mul, down, two);
        let first_row = b.binary(BinaryOp::Sub, twice, twice_l);
        let cube_first = b.binary(BinaryOp::Mul, first_row, two);
        let oy = b.binary(BinaryOp::Mul, row, down);
        let cube_row = b.binary(BinaryOp::Add, cube_first, oy);
        let row_offset = b.select(is_cube, cube_row, first_row);
        let ox = b.binary(BinaryOp::Mul, column, across);
        let across_f = b.convert(across, Type::FLOAT);
        let down_f = b.convert(down, Type::FLOAT);
        let (x0, x1, wx) = split(b, s, across_f);
        let (y0, y1, wy) = split(b, t, down_f);
        let last_across = b.binary(BinaryOp::Sub, across, one);
        let last_down = b.binary(BinaryOp::Sub, down, one);
        let column_of = |b: &mut Builder, i: ExprId| {
            let clamped = b.call(BuiltinId::Clamp, vec![i, zero, last_across]);
            let in_face = b.binary(BinaryOp::Add, clamped, ox);
            let wrapped = wrap(b, i, across);
            b.select(is_cube, in_face, wrapped)
        };
        let row_of = |b: &mut Builder, i: ExprId| {
            let clamped = b.call(BuiltinId::Clamp, vec![i, zero, last_down]);
            b.binary(BinaryOp::Add, clamped, row_offset)
        };
        let (x0, x1) = (column_of(b, x0), column_of(b, x1));
        let (y0, y1) = (row_of(b, y0), row_of(b, y1));
        bilinear(b, texture, [x0, x1, wx], [y0, y1, wy])
    };
    let near = level(b, l0);
    let far = level(b, l1);
    mix(b, near, far, between)
}

fn filter3(b: &mut Builder, texture: ExprId, c: &[ExprId]) -> ExprId {
    let (x0, x1, fx) = axis(b, texture, 0, c[0], true);
    let (y0, y1, fy) = axis(b, texture, 1, c[1], true);
    let (z0, z1, fz) = axis(b, texture, 2, c[2], true);
    let plane = |b: &mut Builder, z| {
        let mut texel = |x, y| b.call(BuiltinId::Texel3d, vec![texture, x, y, z]);
        let (c00, c10, c01, c11) = (texel(x0, y0), texel(x1, y0), texel(x0, y1), texel(x1, y1));
        let top = mix(b, c00, c10, fx);
        let bottom = mix(b, c01, c11, fx);
        mix(b, top, bottom, fy)
    };
    let near = plane(b, z0);
    let far = plane(b, z1);
    mix(b, near, far, fz)
}
