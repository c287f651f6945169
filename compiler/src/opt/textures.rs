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
//! Runs after `opt::derivs` (texture lookups carry no derivatives through it) and before the
//! split; rewrites each lookup in place, appending the expressions it needs, all at the lookup's
//! rate.

use crate::ir::build::Builder;
use crate::ir::types::{Base, Type};
use crate::ir::{BinaryOp, ExprId, ExprKind, Shader};
use crate::sema::globals;

/// Rewrites every `texture` and `texture3d` lookup of `shader` into texel fetches and arithmetic.
pub fn expand(shader: &mut Shader) {
    let lookups: Vec<ExprId> = (0..shader.exprs.len() as u32)
        .map(ExprId)
        .filter(|id| matches!(&shader.expr(*id).kind, ExprKind::Builtin(b, _) if matches!(b.name, "texture" | "texture3d")))
        .collect();
    for id in lookups {
        let span = shader.expr(id).span;
        let (args, three_d) = match &shader.expr(id).kind {
            ExprKind::Builtin(b, args) => (args.clone(), b.name == "texture3d"),
            _ => continue,
        };
        let ret = shader.expr(id).ty;
        let rate = shader.expr(id).rate;
        let first_new = shader.exprs.len();
        let mut b = Builder::new(shader, span);
        let Some(coords) = coordinates(&mut b, &args, three_d) else { continue };
        let texture = args[0];
        let rgba =
            if three_d { filter3(&mut b, texture, &coords) } else { filter2(&mut b, texture, &coords) };
        let value = match ret.base {
            Base::Float => b.index(rgba, 0),
            Base::Color => {
                let parts = (0..3).map(|c| b.index(rgba, c)).collect();
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
fn axis(
    b: &mut Builder,
    texture: ExprId,
    which: i32,
    coord: ExprId,
    three_d: bool,
) -> (ExprId, ExprId, ExprId) {
    let a = b.int(which);
    let size = b.call(if three_d { "__texsize3d" } else { "__texsize2d" }, vec![texture, a]);
    let size_f = b.convert(size, Type::FLOAT);
    let half = b.float(0.5);
    let scaled = b.binary(BinaryOp::Mul, coord, size_f);
    let x = b.binary(BinaryOp::Sub, scaled, half);
    let x0 = b.call("floor", vec![x]);
    let fraction = b.binary(BinaryOp::Sub, x, x0);
    let i0 = b.convert(x0, Type::INT);
    let i0 = wrap(b, i0, size);
    let one = b.int(1);
    let next = b.binary(BinaryOp::Add, i0, one);
    let i1 = wrap(b, next, size);
    (i0, i1, fraction)
}

/// `((i % n) + n) % n`: a coordinate wrapped into [0, n).
fn wrap(b: &mut Builder, i: ExprId, n: ExprId) -> ExprId {
    let r = b.binary(BinaryOp::Rem, i, n);
    let r = b.binary(BinaryOp::Add, r, n);
    b.binary(BinaryOp::Rem, r, n)
}

fn mix(b: &mut Builder, x: ExprId, y: ExprId, t: ExprId) -> ExprId {
    b.call("mix", vec![x, y, t])
}

fn filter2(b: &mut Builder, texture: ExprId, c: &[ExprId]) -> ExprId {
    let (x0, x1, fx) = axis(b, texture, 0, c[0], false);
    let (y0, y1, fy) = axis(b, texture, 1, c[1], false);
    let mut texel = |x, y| b.call("__texel2d", vec![texture, x, y]);
    let (c00, c10, c01, c11) = (texel(x0, y0), texel(x1, y0), texel(x0, y1), texel(x1, y1));
    let top = mix(b, c00, c10, fx);
    let bottom = mix(b, c01, c11, fx);
    mix(b, top, bottom, fy)
}

fn filter3(b: &mut Builder, texture: ExprId, c: &[ExprId]) -> ExprId {
    let (x0, x1, fx) = axis(b, texture, 0, c[0], true);
    let (y0, y1, fy) = axis(b, texture, 1, c[1], true);
    let (z0, z1, fz) = axis(b, texture, 2, c[2], true);
    let plane = |b: &mut Builder, z| {
        let mut texel = |x, y| b.call("__texel3d", vec![texture, x, y, z]);
        let (c00, c10, c01, c11) = (texel(x0, y0), texel(x1, y0), texel(x0, y1), texel(x1, y1));
        let top = mix(b, c00, c10, fx);
        let bottom = mix(b, c01, c11, fx);
        mix(b, top, bottom, fy)
    };
    let near = plane(b, z0);
    let far = plane(b, z1);
    mix(b, near, far, fz)
}
