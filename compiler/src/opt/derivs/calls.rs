//! The chain rule for the built-in functions of mathematics, shaping and components (the geometric
//! ones are in `geometry.rs`). [`rule`] gives every built-in its rule, exhaustively (a new
//! built-in does not compile until it has one); the arguments a chain rule differentiates are
//! its [`operands`], which the analysis follows, and [`Diff::call`] builds the derivative. The
//! list of the built-ins with derivative 0 is in the module documentation of `opt::derivs`.

use super::analysis::dtype;
use super::rules::Diff;
use crate::ir::builtin::Builtin;
use crate::ir::builtin::BuiltinId as B;
use crate::ir::types::{Base, Type};
use crate::ir::{Axis, BinaryOp, ExprId};

/// How the derivative pass treats a call of a built-in.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum Rule {
    /// The chain rule of [`Diff::call`], through the arguments [`Through`] names.
    Chain(Through),
    /// A derivative though it has no arguments: `xyz_screen`, the window position.
    Source,
    /// Writes one component of its output argument with its last argument (`setxcomp`, ...,
    /// `setcomp`): the same setter writes the derivative of that argument into the output's
    /// shadows (`rewrite.rs`); the call itself has no value.
    SetsComponent,
    /// A derivative built-in, replaced by its formula (`consumers.rs`).
    Consumer,
    /// Derivative 0 by definition: piecewise constant (`floor`, `step`, ...), random, another
    /// shader's or a light's values, texture lookups, strings and calls without a value. Their
    /// output arguments get derivative 0 as well.
    Zero,
    /// Written in the language (`compiler/stdlib/builtins.sl`): the semantic stage inlines its
    /// implementation, which is differentiated through its code, so no call of it reaches this
    /// pass (one that did would get derivative 0).
    Library,
}

/// The arguments a [`Rule::Chain`] differentiates.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum Through {
    /// Every argument.
    All,
    /// The first (the value of `xcomp`, `comp`).
    First,
    /// The last (the value a transform moves; its space or matrix is taken as constant).
    Last,
    /// All but the first (`select`'s two choices).
    AfterFirst,
    /// `spline`'s knots (not its parameter).
    Knots,
}

/// The rule of `b`: one per built-in, and the only place that decides it.
pub(super) fn rule(b: &Builtin) -> Rule {
    use Through::{AfterFirst, All, First, Knots, Last};
    match b.id {
        B::Sin
        | B::Asin
        | B::Cos
        | B::Acos
        | B::Tan
        | B::Atan
        | B::Pow
        | B::Exp
        | B::Sqrt
        | B::InverseSqrt
        | B::Log
        | B::Mod
        | B::Abs
        | B::Min
        | B::Max
        | B::Clamp
        | B::Mix
        | B::SmoothStep
        | B::Length
        | B::Normalize
        | B::Depth
        | B::Rgb
        | B::Clamp01
        | B::Integrate
        | B::Dot
        | B::Cross
        | B::Transpose
        | B::Affine
        | B::Invert => Rule::Chain(All),
        B::XComp | B::YComp | B::ZComp | B::Comp => Rule::Chain(First),
        B::Transform | B::VTransform | B::NTransform => Rule::Chain(Last),
        B::Select => Rule::Chain(AfterFirst),
        B::Spline => Rule::Chain(Knots),
        B::XyzScreen => Rule::Source,
        B::SetXComp | B::SetYComp | B::SetZComp | B::SetComp => Rule::SetsComponent,
        B::Du | B::Dv | B::Deriv | B::FilterWidth | B::Area | B::CalculateNormal => Rule::Consumer,
        // The 3-argument form gives its filter region explicitly: a step, piecewise constant.
        B::FilterStep if b.params.len() == 2 => Rule::Consumer,
        // Piecewise constant.
        B::FilterStep | B::Sign | B::Floor | B::Ceil | B::Round | B::Step => Rule::Zero,
        // Random per point, or one per draw.
        B::Random | B::UniformRandom => Rule::Zero,
        // Texture lookups (they keep their implicit derivatives) and the texel fetches and sizes
        // they are expanded into.
        B::Texture
        | B::Texture3d
        | B::Environment
        | B::Shadow
        | B::Texel2d
        | B::Texel3d
        | B::Texsize2d
        | B::Texsize3d => Rule::Zero,
        // Lights' and other shaders' values (`lightsource` and `surface` write their outputs).
        B::Ambient | B::LightSource | B::Surface => Rule::Zero,
        // Strings, and calls without a value.
        B::Printf | B::Format | B::Concat | B::Match | B::ColourSpace => Rule::Zero,
        B::Noise
        | B::Snoise
        | B::Pnoise
        | B::Cellnoise
        | B::Diffuse
        | B::Specular
        | B::Phong
        | B::SpecularBrdf
        | B::CTransform
        | B::Ptlined
        | B::Rotate
        | B::Translate
        | B::Scale
        | B::Determinant
        | B::Fresnel
        | B::Reflect
        | B::Refract
        | B::Distance
        | B::FaceForward
        | B::Radians
        | B::Degrees => Rule::Library,
    }
}

/// The arguments whose derivatives the rule of `b` uses (none for the built-ins whose derivative
/// is taken as 0).
pub(super) fn operands(b: &Builtin, args: &[ExprId]) -> Vec<ExprId> {
    match rule(b) {
        Rule::Chain(Through::All) => args.to_vec(),
        Rule::Chain(Through::First) => vec![args[0]],
        Rule::Chain(Through::Last) => vec![*args.last().expect("an argument")],
        Rule::Chain(Through::AfterFirst) => args[1..].to_vec(),
        Rule::Chain(Through::Knots) => args[knots(b)..].to_vec(),
        Rule::Source | Rule::SetsComponent | Rule::Consumer | Rule::Zero | Rule::Library => Vec::new(),
    }
}

/// Whether a call's derivative is not 0 though it has no arguments (`xyz_screen`).
pub(super) fn is_source(b: &Builtin) -> bool {
    rule(b) == Rule::Source
}

/// The inputs that the derivative of a built-in's output arguments depends on: the value
/// `setxcomp`, `setycomp`, `setzcomp` and `setcomp` write (their last argument). Other outputs
/// (`lightsource`'s and `surface`'s, values of another shader) get derivative 0.
pub(super) fn output_inputs(b: &Builtin, args: &[ExprId]) -> Vec<ExprId> {
    if is_component_setter(b) { vec![*args.last().expect("a value")] } else { Vec::new() }
}

/// Whether `b` writes one component of its output argument with its last argument.
pub(super) fn is_component_setter(b: &Builtin) -> bool {
    rule(b) == Rule::SetsComponent
}

/// Where the knots of a `spline` overload start: after the optional basis name and the parameter.
fn knots(b: &Builtin) -> usize {
    if b.params[0].ty == Type::STRING { 2 } else { 1 }
}

impl Diff<'_> {
    /// The derivative of the call `e` of `b` with arguments `a`: the chain rule of each built-in
    /// whose [`rule`] is [`Rule::Chain`] or [`Rule::Source`] (here or in `geometry.rs`).
    pub(super) fn call(
        &mut self,
        e: ExprId,
        b: &'static Builtin,
        a: &[ExprId],
        axis: Axis,
    ) -> Option<ExprId> {
        let ty = self.ty(e);
        let dty = dtype(ty).expect("varies");
        match (b.id, a.len()) {
            (B::Sin, _) => {
                let dx = self.d(a[0], axis)?;
                let c = self.shared(e, 0, |s| s.b.call(B::Cos, vec![a[0]]));
                Some(self.mul(c, dx))
            }
            (B::Cos, _) => {
                let dx = self.d(a[0], axis)?;
                let s = self.shared(e, 0, |s| s.b.call(B::Sin, vec![a[0]]));
                let m = self.mul(s, dx);
                Some(self.b.neg(m))
            }
            (B::Tan, _) => {
                // 1 + tan² = 1 / cos², from the result itself.
                let dx = self.d(a[0], axis)?;
                let k = self.shared(e, 0, |s| {
                    let (one, sq) = (s.lit(1.0), s.mul(e, e));
                    s.op(BinaryOp::Add, one, sq)
                });
                Some(self.mul(dx, k))
            }
            (B::Asin | B::Acos, _) => {
                let dx = self.d(a[0], axis)?;
                let k = self.shared(e, 0, |s| {
                    let (one, sq) = (s.lit(1.0), s.mul(a[0], a[0]));
                    let r = s.op(BinaryOp::Sub, one, sq);
                    s.b.call(B::InverseSqrt, vec![r])
                });
                let m = self.mul(dx, k);
                Some(if b.id == B::Acos { self.b.neg(m) } else { m })
            }
            (B::Atan, 1) => {
                let dx = self.d(a[0], axis)?;
                let k = self.shared(e, 0, |s| {
                    let (one, sq) = (s.lit(1.0), s.mul(a[0], a[0]));
                    s.op(BinaryOp::Add, one, sq)
                });
                Some(self.div(dx, k))
            }
            (B::Atan, _) => {
                // atan(y, x): (x dy - y dx) / (x² + y²).
                let (y, x) = (a[0], a[1]);
                let (dy, dx) = (self.d(y, axis), self.d(x, axis));
                let t1 = dy.map(|dy| self.mul(x, dy));
                let t2 = dx.map(|dx| self.mul(y, dx));
                let num = self.sub(t1, t2)?;
                let r2 = self.shared(e, 0, |s| {
                    let (xx, yy) = (s.mul(x, x), s.mul(y, y));
                    s.op(BinaryOp::Add, xx, yy)
                });
                Some(self.div(num, r2))
            }
            (B::Pow, _) => self.pow(e, a[0], a[1], axis),
            (B::Exp, _) => {
                let dx = self.d(a[0], axis)?;
                Some(self.mul(e, dx))
            }
            (B::Sqrt, _) => {
                let dx = self.d(a[0], axis)?;
                let twice = self.shared(e, 0, |s| s.op(BinaryOp::Add, e, e));
                Some(self.div(dx, twice))
            }
            (B::InverseSqrt, _) => {
                // d x^(-1/2) = -x^(-3/2)/2 dx = -y³/2 dx.
                let dx = self.d(a[0], axis)?;
                let k = self.shared(e, 0, |s| {
                    let (yy, half) = (s.mul(e, e), s.lit(-0.5));
                    let yyy = s.mul(yy, e);
                    s.mul(half, yyy)
                });
                Some(self.mul(k, dx))
            }
            (B::Log, 1) => {
                let dx = self.d(a[0], axis)?;
                Some(self.div(dx, a[0]))
            }
            (B::Log, _) => {
                // log_b x = ln x / ln b.
                let (x, base) = (a[0], a[1]);
                let (dx, db) = (self.d(x, axis), self.d(base, axis));
                let ln_b = self.shared(e, 0, |s| s.b.call(B::Log, vec![base]));
                let t1 = dx.map(|dx| {
                    let den = self.mul(x, ln_b);
                    self.div(dx, den)
                });
                let t2 = db.map(|db| {
                    let (num, den) = (self.mul(e, db), self.mul(base, ln_b));
                    self.div(num, den)
                });
                self.sub(t1, t2)
            }
            (B::Mod, _) => {
                // mod(a, b) = a - b floor(a/b).
                let (da, db) = (self.d(a[0], axis), self.d(a[1], axis));
                let t2 = db.map(|db| {
                    let f = self.shared(e, 0, |s| {
                        let q = s.div(a[0], a[1]);
                        s.b.call(B::Floor, vec![q])
                    });
                    self.mul(f, db)
                });
                self.sub(da, t2)
            }
            (B::Abs, _) => {
                let dx = self.d(a[0], axis)?;
                Some(self.componentwise(dty, |s, i| {
                    let xi = s.component(a[0], i);
                    let sign = s.b.call(B::Sign, vec![xi]);
                    let di = s.component(dx, i);
                    s.mul(sign, di)
                }))
            }
            (B::Min | B::Max, _) => self.min_max(e, b.id == B::Min, a, axis),
            (B::Clamp, _) => self.clamp(a[0], a[1], a[2], dty, axis),
            (B::Mix, _) => {
                let (x, y, t) = (a[0], a[1], a[2]);
                let (dx, dy, dt) = (self.d(x, axis), self.d(y, axis), self.d(t, axis));
                let t1 = dx.map(|dx| {
                    let one_minus = self.shared(e, 0, |s| {
                        let one = s.lit(1.0);
                        s.op(BinaryOp::Sub, one, t)
                    });
                    self.mul(dx, one_minus)
                });
                let t2 = dy.map(|dy| self.mul(dy, t));
                let t3 = dt.map(|dt| {
                    let span = self.shared(e, 1, |s| {
                        let (py, px) = (s.prim(y), s.prim(x));
                        s.op(BinaryOp::Sub, py, px)
                    });
                    self.mul(span, dt)
                });
                let sum = self.add(t1, t2);
                self.add(sum, t3)
            }
            (B::SmoothStep, _) => self.smoothstep(e, a, axis),
            (B::Spline, _) => {
                let first = knots(b);
                let ds: Vec<Option<ExprId>> = a[first..].iter().map(|&k| self.d(k, axis)).collect();
                if ds.iter().all(Option::is_none) {
                    return None;
                }
                let mut args = a[..first].to_vec();
                for (&k, d) in a[first..].iter().zip(ds) {
                    args.push(self.or_zero(d, k));
                }
                Some(self.b.call(B::Spline, args))
            }
            (B::XComp | B::YComp | B::ZComp | B::Rgb | B::Transpose | B::Affine | B::Integrate, _) => {
                let dx = self.d(a[0], axis)?;
                Some(self.b.call(b.id, vec![dx]))
            }
            (B::Comp, _) => {
                let dx = self.d(a[0], axis)?;
                let mut args = a.to_vec();
                args[0] = dx;
                Some(self.b.call(B::Comp, args))
            }
            (B::Clamp01, _) => {
                let dx = self.d(a[0], axis)?;
                Some(self.componentwise(dty, |s, i| {
                    let (xi, di) = (s.component(a[0], i), s.component(dx, i));
                    let inside = s.inside_unit(xi);
                    s.guard(inside, di)
                }))
            }
            (B::Select, _) => {
                let (dx, dy) = (self.d(a[1], axis), self.d(a[2], axis));
                if dx.is_none() && dy.is_none() {
                    return None;
                }
                let (dx, dy) = (self.or_zero(dx, a[1]), self.or_zero(dy, a[2]));
                Some(self.b.call(B::Select, vec![a[0], dx, dy]))
            }
            (B::Dot | B::Cross, _) => {
                let (dx, dy) = (self.d(a[0], axis), self.d(a[1], axis));
                let t1 = dx.map(|dx| self.b.call(b.id, vec![dx, a[1]]));
                let t2 = dy.map(|dy| self.b.call(b.id, vec![a[0], dy]));
                self.add(t1, t2)
            }
            (B::XyzScreen, _) => {
                // x and y are the pixel coordinates themselves.
                let (x, y) = if axis == Axis::X { (1.0, 0.0) } else { (0.0, 1.0) };
                let parts = vec![self.lit(x), self.lit(y), self.lit(0.0), self.lit(0.0)];
                Some(self.b.construct(parts, Type::of(Base::Float4)))
            }
            (B::Transform | B::VTransform | B::NTransform, _) => self.d_transform(b, a, axis),
            (B::Length, _) => self.d_length(e, a, axis),
            (B::Normalize, _) => self.d_normalize(e, a, axis),
            (B::Depth, _) => self.d_depth(e, a, axis),
            (B::Invert, _) => self.d_invert(e, a, axis),
            // No chain rule: their rule gives them no operands, so no call of them is active.
            (
                B::SetXComp
                | B::SetYComp
                | B::SetZComp
                | B::SetComp
                | B::Du
                | B::Dv
                | B::Deriv
                | B::FilterWidth
                | B::Area
                | B::CalculateNormal
                | B::FilterStep
                | B::Sign
                | B::Floor
                | B::Ceil
                | B::Round
                | B::Step
                | B::Random
                | B::UniformRandom
                | B::Texture
                | B::Texture3d
                | B::Environment
                | B::Shadow
                | B::Texel2d
                | B::Texel3d
                | B::Texsize2d
                | B::Texsize3d
                | B::Ambient
                | B::LightSource
                | B::Surface
                | B::Printf
                | B::Format
                | B::Concat
                | B::Match
                | B::ColourSpace
                | B::Noise
                | B::Snoise
                | B::Pnoise
                | B::Cellnoise
                | B::Diffuse
                | B::Specular
                | B::Phong
                | B::SpecularBrdf
                | B::CTransform
                | B::Ptlined
                | B::Rotate
                | B::Translate
                | B::Scale
                | B::Determinant
                | B::Fresnel
                | B::Reflect
                | B::Refract
                | B::Distance
                | B::FaceForward
                | B::Radians
                | B::Degrees,
                _,
            ) => None,
        }
    }

    /// d aᵖ = p a^(p-1) da + aᵖ ln a dp; the second term is 0 where a ≤ 0 (per component).
    fn pow(&mut self, e: ExprId, x: ExprId, p: ExprId, axis: Axis) -> Option<ExprId> {
        let ty = self.ty(e);
        let (dx, dp) = (self.d(x, axis), self.d(p, axis));
        let t1 = dx.map(|dx| {
            let k = self.shared(e, 0, |s| {
                let one = s.lit(1.0);
                let p1 = s.op(BinaryOp::Sub, p, one);
                let power = s.b.call(B::Pow, vec![x, p1]);
                s.mul(p, power)
            });
            self.mul(k, dx)
        });
        let t2 = dp.map(|dp| {
            self.componentwise(ty, |s, i| {
                let (xi, yi, di) = (s.component(x, i), s.component(e, i), s.component(dp, i));
                let ln = s.b.call(B::Log, vec![xi]);
                let k = s.mul(yi, ln);
                let term = s.mul(k, di);
                let positive = s.positive(xi);
                s.guard(positive, term)
            })
        });
        self.add(t1, t2)
    }

    /// min and max, pairwise from the left: the derivative of the operand that wins (the first on
    /// a tie), per component.
    fn min_max(&mut self, e: ExprId, min: bool, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        let id = if min { B::Min } else { B::Max };
        let mut best = a[0];
        let mut d_best = self.d(a[0], axis);
        for (k, &next) in a.iter().enumerate().skip(1) {
            let d_next = self.d(next, axis);
            if d_best.is_some() || d_next.is_some() {
                let (db, dn) = (self.or_zero(d_best, best), self.or_zero(d_next, next));
                let dty = self.ty(db);
                d_best = Some(self.componentwise(dty, |s, i| {
                    let (bi, ni) = (s.component(best, i), s.component(next, i));
                    let wins = s.op(if min { BinaryOp::Le } else { BinaryOp::Ge }, bi, ni);
                    let (dbi, dni) = (s.component(db, i), s.component(dn, i));
                    s.b.select(wins, dbi, dni)
                }));
            }
            if k + 1 < a.len() {
                best = self.shared(e, k as u8, |s| s.b.call(id, vec![best, next]));
            }
        }
        d_best
    }

    /// clamp(x, lo, hi) = min(max(x, lo), hi): the derivative of the bound that applies, per
    /// component (scalar bounds apply to every component); `hi` wins when the bounds cross.
    fn clamp(&mut self, x: ExprId, lo: ExprId, hi: ExprId, dty: Type, axis: Axis) -> Option<ExprId> {
        let (dx, dlo, dhi) = (self.d(x, axis), self.d(lo, axis), self.d(hi, axis));
        if dx.is_none() && dlo.is_none() && dhi.is_none() {
            return None;
        }
        let (dx, dlo, dhi) = (self.or_zero(dx, x), self.or_zero(dlo, lo), self.or_zero(dhi, hi));
        Some(self.componentwise(dty, |s, i| {
            let (xi, loi, hii) = (s.component(x, i), s.component(lo, i), s.component(hi, i));
            let below = s.op(BinaryOp::Lt, xi, loi);
            let (x_above, lo_above) = (s.op(BinaryOp::Gt, xi, hii), s.op(BinaryOp::Gt, loi, hii));
            let above = s.op(BinaryOp::Or, x_above, lo_above);
            let (dxi, dloi, dhii) = (s.component(dx, i), s.component(dlo, i), s.component(dhi, i));
            let inner = s.b.select(below, dloi, dxi);
            s.b.select(above, dhii, inner)
        }))
    }

    /// smoothstep(e0, e1, x) = s²(3 - 2s) with s = clamp((x - e0)/(e1 - e0), 0, 1): its derivative
    /// is 6s(1 - s) ds, and 0 where e0 = e1 (a step).
    fn smoothstep(&mut self, e: ExprId, a: &[ExprId], axis: Axis) -> Option<ExprId> {
        let (e0, e1, x) = (a[0], a[1], a[2]);
        let ratio = self.shared(e, 0, |s| {
            let (num, den) = (s.op(BinaryOp::Sub, x, e0), s.op(BinaryOp::Sub, e1, e0));
            s.div(num, den)
        });
        let dr = self.d(ratio, axis)?;
        let slope = self.shared(e, 1, |s| {
            let (zero, one, six) = (s.lit(0.0), s.lit(1.0), s.lit(6.0));
            let clamped = s.b.call(B::Clamp, vec![ratio, zero, one]);
            let rest = s.op(BinaryOp::Sub, one, clamped);
            let k = s.mul(six, clamped);
            s.mul(k, rest)
        });
        let value = self.mul(slope, dr);
        let distinct = self.shared(e, 2, |s| s.op(BinaryOp::Ne, e1, e0));
        Some(self.guard(distinct, value))
    }
}
