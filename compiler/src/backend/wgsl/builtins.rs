//! Built-in functions in naga IR, with the interpreter's definitions (`backend/cpu/lower`).
//!
//! Where WGSL has the function and is exact (`floor`, `min`, `mix`, ...) its own is used (the
//! one-operation built-ins are `backend::ops`' table, beside the interpreter's instruction); where
//! Patina fixes an order of operations that WGSL leaves open (`dot`, `length`, matrix products,
//! `smoothstep`, `inversesqrt`, ...) the sequence is `backend::arith`'s, built here as naga
//! expressions, the one the interpreter runs, so that both backends give the same bits; the fast
//! lowering uses WGSL's own functions instead. Transcendentals (`sin`, `exp`, `pow`, ...) are
//! WGSL's, within its accuracy rules; `pow` of a negative base is the one definition WGSL lacks
//! that only this backend has to add. Spaces and `transform` live in `geometry`, components and
//! matrices in `matrices`, `concat` and `match` in `strings`; colour spaces, `faceforward`,
//! `reflect`, `refract`, `distance`, `fresnel`, `ptlined`, `rotate`, `translate`, `scale` and
//! `determinant` are the library's (`compiler/stdlib/builtins.sl`), and `spline` is arithmetic on
//! its knots by then (`opt::splines`).

use crate::backend::arith::{self, Arith};
use crate::backend::ops::{CoreOp, core_op, not_core};
use naga::{BinaryOperator as Op, Expression, MathFunction as M, ScalarKind};

use super::body::{Translator, Value};
use crate::diag::{Code, Diagnostic};
use crate::ir::builtin::Builtin;
use crate::ir::builtin::BuiltinId as B;
use crate::ir::types::{Base, Type};
use crate::ir::{ExprId, ExprKind, Literal};

impl Translator<'_> {
    /// A call of a built-in: every built-in has its case here (the match on its id is
    /// exhaustive), those that never reach the backend an internal error.
    pub(super) fn builtin(
        &mut self,
        b: &'static Builtin,
        args: &[ExprId],
        id: ExprId,
    ) -> Result<Value, Diagnostic> {
        let e = self.shader.expr(id);
        let (ret, span) = (e.ty, e.span);
        let types: Vec<Type> = args.iter().map(|a| self.shader.expr(*a).ty).collect();
        if let Some(fetch) = super::textures::Fetch::of(b.id) {
            // The texture argument is a binding, not a value: only the coordinates are computed.
            let coords: Vec<Value> = args[1..].iter().map(|a| self.expr(*a)).collect::<Result<_, _>>()?;
            return self.texel_builtin(fetch, args, &coords);
        }
        // Strings are compile-time values: string arguments are read by `fold_string` where they
        // are used, and a zero stands in for them here.
        let vals: Vec<Value> = args
            .iter()
            .zip(&types)
            .map(|(a, t)| if t.base == Base::String { Ok(self.float(0.0)) } else { self.expr(*a) })
            .collect::<Result<_, _>>()?;
        let v = |i: usize| vals[i];
        let is_int = matches!(ret.base, Base::Int | Base::Uint);
        // Arguments widened to the result's width (a scalar edge with a vector value, ...).
        let n = ret.base.components();
        let wide = |this: &mut Self, i: usize| {
            if types[i].base.components() == 1 && n > 1 && !is_int { this.splat(vals[i], n) } else { vals[i] }
        };
        // The value of a built-in without one (`setcomp`, `printf`, ...): never read.
        let void = |this: &mut Self| this.float(0.0);
        Ok(match b.id {
            B::Pow => {
                let y = wide(self, 1);
                if self.never_negative(args[0], 0) {
                    // The negative-base case cannot arise: WGSL's pow is the interpreter's here.
                    self.math2(M::Pow, v(0), y)
                } else {
                    self.pow(v(0), y, n)
                }
            }
            // 1 / sqrt(x), as the interpreter (WGSL's inverseSqrt may differ by 2 ulp).
            B::InverseSqrt if self.fast() => self.math1(M::InverseSqrt, v(0)),
            B::InverseSqrt => self.inverse_sqrt(v(0)),
            B::Log if args.len() == 2 => {
                let (x, base) = (self.math1(M::Log, v(0)), self.math1(M::Log, v(1)));
                self.binary(Op::Divide, x, base)
            }
            B::Mod => {
                // a - b * floor(a / b), as the interpreter (WGSL's `%` truncates instead).
                let b = wide(self, 1);
                self.modulo(v(0), b)
            }
            B::Abs if ret.base == Base::Uint => v(0),
            B::Sign if self.fast() => self.math1(M::Sign, v(0)),
            B::Sign => self.sign(v(0)),
            // WGSL's `abs` is exact for signed integers too.
            B::Sin
            | B::Cos
            | B::Tan
            | B::Asin
            | B::Acos
            | B::Atan
            | B::Exp
            | B::Sqrt
            | B::Log
            | B::Abs
            | B::Floor
            | B::Ceil
            | B::Round => match core_op(b.id, args.len()) {
                Some(CoreOp::Unary { wgsl, .. }) => self.math1(wgsl, v(0)),
                Some(CoreOp::Binary { wgsl, .. }) => self.math2(wgsl, v(0), v(1)),
                None => return Err(not_core(b.id, span)),
            },
            B::Min | B::Max => {
                let fun = if b.id == B::Min { M::Min } else { M::Max };
                let mut acc = wide(self, 0);
                for i in 1..vals.len() {
                    let x = wide(self, i);
                    acc = self.math2(fun, acc, x);
                }
                acc
            }
            B::Clamp => {
                let (lo, hi) = (wide(self, 1), wide(self, 2));
                // min(max(x, lo), hi), as the interpreter (WGSL's clamp leaves lo > hi open).
                self.clamp(v(0), lo, hi)
            }
            B::Clamp01 => {
                let (zero, one) = (self.float(0.0), self.float(1.0));
                let (zero, one) = (self.splat(zero, n), self.splat(one, n));
                self.clamp(v(0), zero, one)
            }
            B::Mix => {
                // a * (1 - t) + b * t, WGSL's formula.
                let t = wide(self, 2);
                self.math3(M::Mix, v(0), v(1), t)
            }
            B::Step => {
                let edge = wide(self, 0);
                self.step(edge, v(1))
            }
            B::SmoothStep => self.smoothstep(v(0), v(1), v(2)),
            B::FilterStep if args.len() == 3 => arith::filterstep(self, v(0), v(1), v(2)),
            B::Select => match types[1].base {
                Base::Matrix3 if !types[1].is_array() => self.select_matrix(v(0), v(1), v(2), 3),
                Base::Matrix4 if !types[1].is_array() => self.select_matrix(v(0), v(1), v(2), 4),
                _ => self.select(v(0), v(1), v(2)),
            },
            B::Random | B::UniformRandom => {
                // The interpreter's hash of the point index (a fixed one for a uniform value) and
                // the call site (one site per component, numbered in the same order), in u32
                // arithmetic.
                let point = if b.id == B::Random {
                    let var = self.mb.private(crate::backend::POINT_INDEX, Type::of(Base::Uint));
                    let p = self.pointer(var);
                    self.load(p)
                } else {
                    self.fb.add(Expression::Literal(naga::Literal::U32(crate::backend::UNIFORM_RANDOM_POINT)))
                };
                let parts: Vec<Value> = (0..ret.base.components())
                    .map(|_| {
                        self.random_sites += 1;
                        arith::random(self, point, self.random_sites)
                    })
                    .collect();
                if parts.len() == 1 {
                    parts[0]
                } else {
                    let ty = self.mb.ty(ret, false);
                    self.fb.add(Expression::Compose { ty, components: parts })
                }
            }
            // A GPU has no console: `printf` is left out (sema warns at the call).
            B::Printf => void(self),
            B::XComp | B::YComp | B::ZComp => {
                let i = [B::XComp, B::YComp, B::ZComp].iter().position(|c| *c == b.id).unwrap_or(0) as u32;
                self.at(v(0), i)
            }
            B::SetXComp | B::SetYComp | B::SetZComp => {
                let i = [B::SetXComp, B::SetYComp, B::SetZComp].iter().position(|c| *c == b.id).unwrap_or(0);
                let mut parts = self.parts(v(0), 3);
                parts[i] = v(1);
                let new = self.vector(&parts);
                self.write_output(args[0], new);
                void(self)
            }
            B::Comp if types[0].base == Base::Matrix4 => self.matrix_component(v(0), v(1), v(2)),
            B::Comp => {
                // The index converted to an integer and clamped into range, as the interpreter.
                let i = self.float_to_int(v(1));
                let i = self.clamp_int(i, 0, 2);
                let i = self.fb.add(Expression::As { expr: i, kind: ScalarKind::Uint, convert: Some(4) });
                self.fb.add(Expression::Access { base: v(0), index: i })
            }
            B::SetComp if types[0].base == Base::Matrix4 => {
                let new = self.matrix_with(v(0), v(1), v(2), v(3));
                self.write_output(args[0], new);
                void(self)
            }
            B::SetComp => {
                // Out-of-range indices change nothing (the interpreter compares each component's
                // index with the converted one).
                let i = self.float_to_int(v(1));
                let old = self.parts(v(0), 3);
                let parts: Vec<Value> = (0..3)
                    .map(|k| {
                        let kk = self.int(k);
                        let here = self.binary(Op::Equal, i, kk);
                        self.select(here, v(2), old[k as usize])
                    })
                    .collect();
                let new = self.vector(&parts);
                self.write_output(args[0], new);
                void(self)
            }
            B::Length => self.length(v(0)),
            B::Normalize => self.normalize(v(0)),
            B::Dot if self.fast() && types[0].base.components() > 1 => self.math2(M::Dot, v(0), v(1)),
            B::Dot => {
                let k = types[0].base.components();
                let (a, b) = (self.parts(v(0), k), self.parts(v(1), k));
                arith::dot(self, &a, &b)
            }
            B::Cross if self.fast() => self.math2(M::Cross, v(0), v(1)),
            B::Cross => {
                let (a, b) = (self.parts(v(0), 3), self.parts(v(1), 3));
                let c = arith::cross(self, &a, &b);
                self.vector(&c)
            }
            B::Rgb => self.xyz(v(0)),
            B::LightSource => self.lightsource(args, span)?,
            B::Surface => self.surface_message(args, span)?,
            B::Transform | B::VTransform | B::NTransform => self.transform(b.id, args, &vals, ret, span)?,
            B::Transpose => self.math1(M::Transpose, v(0)),
            B::Affine => {
                let m = self.entries(v(0), 4);
                let e: Vec<Value> = (0..9).map(|k| m[(k / 3) * 4 + k % 3]).collect();
                self.matrix(&e, 3)
            }
            B::Invert => {
                let k = if types[0].base == Base::Matrix3 { 3 } else { 4 };
                let m = self.entries(v(0), k);
                let inv = arith::invert(self, &m, k as usize);
                self.matrix(&inv, k)
            }
            B::Depth => self.depth(v(0)),
            B::ColourSpace => {
                let Some(name) = self.fold_string(args[0]) else {
                    return Err(Diagnostic::error(
                        Code::NotExecutable,
                        "colour space names must be known when the shader is compiled",
                        span,
                        "this call",
                    ));
                };
                crate::stdlib::check_colour_space(&name, span)?;
                void(self)
            }
            // Left by `opt::splines` only when it cannot be run.
            B::Spline => return Err(crate::opt::splines::refusal(self.shader, id, self.strings)),
            B::Match => self.pattern_match(args, span)?,
            B::Concat => {
                return Err(self.error(
                    span,
                    "a string used as a value (`concat` is folded only where a name is expected)",
                ));
            }
            B::XyzScreen => {
                // The fragment's window position: the fragment entry point (or a kernel's input
                // of this name) fills this variable, as the interpreter's input of the same name.
                let var = self.mb.private(super::entry::SCREEN_POSITION, ret);
                let p = self.pointer(var);
                self.load(p)
            }
            B::Du | B::Dv | B::Deriv | B::FilterWidth | B::FilterStep | B::Area | B::CalculateNormal => {
                return Err(super::internal(
                    span,
                    format!(
                        "internal error: `{}` reached the WGSL backend without being differentiated",
                        b.id
                    ),
                ));
            }
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
            | B::Degrees => {
                return Err(super::internal(
                    span,
                    format!(
                        "`{}` reached the WGSL backend as a built-in; the semantic stage inlines its \
                         implementation from compiler/stdlib/builtins.sl",
                        b.id
                    ),
                ));
            }
            B::Texture | B::Texture3d | B::Environment | B::Shadow => {
                return Err(super::internal(
                    span,
                    format!(
                        "internal error: `{}` reached the WGSL backend without being expanded (opt::Prepared::new)",
                        b.id
                    ),
                ));
            }
            // A string the semantic stage computes (`format` of literals): no call of it remains.
            B::Format => {
                return Err(
                    self.error(span, format!("the built-in `{}` is not available on the GPU yet", b.id))
                );
            }
            B::Ambient | B::Integrate => {
                return Err(super::internal(
                    span,
                    format!("internal error: `{}` reached the WGSL backend (opt::lights::unroll)", b.id),
                ));
            }
            B::Texel2d | B::Texel3d | B::Texsize2d | B::Texsize3d => unreachable!("fetched above"),
        })
    }

    /// `sqrt(v . v)` of a three-component vector, summed as the interpreter does.
    pub(super) fn length(&mut self, v: Value) -> Value {
        if self.fast() {
            return self.math1(M::Length, v);
        }
        let p = self.parts(v, 3);
        arith::length(self, &p)
    }

    /// `v / length(v)` of a three-component vector (a zero vector gives NaN, as in WGSL).
    pub(super) fn normalize(&mut self, v: Value) -> Value {
        if self.fast() {
            return self.math1(M::Normalize, v);
        }
        let p = self.parts(v, 3);
        let len = arith::length(self, &p);
        let len = self.splat(len, 3);
        self.div(v, len)
    }

    /// Whether the value of `id` is never below zero (it may be NaN or -0, which `pow`'s
    /// negative-base case does not take either): a non-negative literal, `abs`, `sqrt`, `exp`, a
    /// `max` with such an operand, a `min` or `clamp` of such bounds, or a local written once,
    /// by its declaration, with such a value (`float b = min(max(x, 0), 1)`).
    fn never_negative(&self, id: ExprId, depth: u32) -> bool {
        // Deep enough for the guards written in the library; a longer chain is just not proved.
        if depth > 8 {
            return false;
        }
        let sure = |e: &ExprId| self.never_negative(*e, depth + 1);
        match &self.shader.expr(id).kind {
            ExprKind::Literal(Literal::Float(x)) => *x >= 0.0,
            ExprKind::Literal(Literal::Int(x)) => *x >= 0,
            ExprKind::Literal(Literal::Uint(_)) => true,
            ExprKind::Convert(a) => sure(a),
            ExprKind::Local(l) => self.only_initialiser(*l).is_some_and(|value| sure(&value)),
            ExprKind::Builtin(b, args) => match b.id {
                B::Abs | B::Sqrt | B::Exp => true,
                B::Max => args.iter().any(sure),
                B::Min => args.iter().all(sure),
                B::Clamp => args.len() == 3 && args[1..].iter().all(sure),
                _ => false,
            },
            _ => false,
        }
    }

    /// `pow(x, y)` with the interpreter's (C's `powf`) result for a negative base and an integral
    /// exponent, ±|x|^y by the exponent's parity, where WGSL leaves `pow` of a negative base
    /// undefined (NaN on Vulkan drivers); other cases are WGSL's `pow`. One `pow` of the base
    /// chosen for the case, since a `select` evaluates both of its operands. `n` is the width.
    fn pow(&mut self, x: Value, y: Value, n: u32) -> Value {
        let (zero, half) = (self.float(0.0), self.float(0.5));
        let (zero, half) = (self.splat(zero, n), self.splat(half, n));
        let negative = self.binary(Op::Less, x, zero);
        let whole = self.math1(M::Trunc, y);
        let integral = self.binary(Op::Equal, y, whole);
        let take = self.binary(Op::And, negative, integral);
        let ax = self.math1(M::Abs, x);
        let base = self.select(take, ax, x);
        let power = self.math2(M::Pow, base, y);
        let halved = self.binary(Op::Multiply, y, half);
        let halved_whole = self.math1(M::Trunc, halved);
        let odd = self.binary(Op::NotEqual, halved, halved_whole);
        let flip = self.binary(Op::And, take, odd);
        let flipped = self.neg(power);
        self.select(flip, flipped, power)
    }

    /// `lightsource(name, v)` inside `illuminance`, visiting light `self.light`: as the
    /// interpreter decides it from the binding (`backend/cpu/lower/builtins.rs`), 1 with the
    /// light's parameter written to `v`, or 0. The light's function runs earlier in the same
    /// fragment entry point: a parameter it writes is read from its variable, any other from
    /// the uniform block, where the light's parameters live.
    fn lightsource(&mut self, args: &[ExprId], span: crate::source::Span) -> Result<Value, Diagnostic> {
        let ty = self.shader.expr(args[1]).ty;
        let found = match (self.fold_string(args[0]), self.light) {
            (Some(name), Some(k)) if self.lights[k].params.iter().any(|(n, t)| *n == name && *t == ty) => {
                Some((name, k))
            }
            _ => None,
        };
        let Some((name, k)) = found else { return Ok(self.float(0.0)) };
        let Some(light) = self.light_shaders.get(k).copied() else {
            return Err(self.error(span, "`lightsource` needs the light's shader in the same module"));
        };
        let Some(&param) = light.params.iter().find(|p| light.local(**p).name == name) else {
            return Err(self.error(span, format!("the light has no parameter `{name}`")));
        };
        let prefix = format!("l{k}_");
        let value = if crate::ir::stores::stores(light)[param.0 as usize].count > 0 {
            let names = super::body::variable_names(light, &prefix);
            let var = self.mb.private(&names[&param], ty);
            let p = self.pointer(var);
            self.load(p)
        } else {
            let source = super::interface::UniformSource::LightParam { light: k, name: name.to_string() };
            super::entry::uniform_input(self, &format!("{prefix}{name}"), ty, source)
        };
        self.write_output(args[1], value);
        Ok(self.float(1.0))
    }

    /// `surface(name, v)` in a light's or an atmosphere's function: the surface's parameter
    /// `name` when it has one of `v`'s type (1), else 0 and `v` unchanged, as the interpreter has
    /// it with the runtime's inputs (`backend/cpu/lower/builtins.rs`). The surface's variable
    /// where its fragment stage reads the parameter (set at the top of the entry point, before
    /// the lights; after the body for an atmosphere), else its uniform.
    fn surface_message(&mut self, args: &[ExprId], span: crate::source::Span) -> Result<Value, Diagnostic> {
        let ty = self.shader.expr(args[1]).ty;
        let Some(name) = self.fold_string(args[0]) else { return Ok(self.float(0.0)) };
        let Some(surface) = self.surface else {
            return Err(self.error(span, "`surface` needs the surface's shader in the same module"));
        };
        let param = surface.params.iter().copied().find(|p| {
            let local = surface.local(*p);
            local.name == name && local.ty == ty
        });
        let Some(param) = param else { return Ok(self.float(0.0)) };
        let value = if super::uses::Uses::of(surface, &surface.body).locals.contains(&param) {
            let names = super::body::variable_names(surface, "");
            let var = self.mb.private(&names[&param], ty);
            let p = self.pointer(var);
            self.load(p)
        } else {
            let source = super::interface::UniformSource::Param { name: name.to_string() };
            super::entry::uniform_input(self, &name, ty, source)
        };
        self.write_output(args[1], value);
        Ok(self.float(1.0))
    }
}

#[cfg(test)]
mod tests {
    use crate::backend::wgsl::compile;
    use crate::syntax::preprocess::MemoryLoader;

    /// The shader's module through the render path (split stages), or the first error.
    fn module(src: &str) -> Result<String, String> {
        let checked = crate::check_source("t.sl", src, &MemoryLoader::default());
        assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
        let shader = crate::opt::Prepared::new(checked.program.shaders[0].clone());
        let stages = crate::split::split(&shader).map_err(|d| d.message)?;
        let program = compile(&stages, &[], &[], &crate::backend::defaults::constant_defaults)
            .map_err(|d| d.message)?;
        let wgsl = program.wgsl().map_err(|d| d.message)?;
        naga::front::wgsl::parse_str(&wgsl).map_err(|e| e.emit_to_string(&wgsl))?;
        Ok(wgsl)
    }

    #[test]
    fn named_spaces_depth_and_colour_spaces_validate_and_reparse() {
        // What the conformance kernels cannot bind (uniform matrices of named spaces, the
        // clipping range of `depth`) still has to make a valid module.
        let wgsl = module(
            "surface t(string sp = \"world\") {
                point p = transform(\"object\", P);
                vector v = vtransform(\"world\", \"shader\", I);
                normal n = ntransform(sp, matrix(2), N);
                point q = point \"world\" (1, 2, 3) + transform(\"screen\", \"camera\", P);
                matrix m = matrix \"object\" 1;
                color c = ctransform(\"hsv\", \"xyY\", Cs) + color \"hsl\" (s, t, 0.5);
                float d = depth(p) + comp(m, 1, 2) + determinant(invert(m));
                Ci = c * d + color(xcomp(v), ycomp(n), zcomp(q));
            }",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert!(wgsl.contains("space_object") && wgsl.contains("clip"), "{wgsl}");
    }

    #[test]
    fn the_remaining_built_ins_validate_and_reparse() {
        module(
            "surface t(float knots[5] = {0, 1, 2, 3, 4}) {
                point a = P;
                setxcomp(a, s);
                color c = Cs;
                setcomp(c, t * 3, 0.5);
                matrix m = rotate(translate(scale(matrix(1), point(1, 2, 3)), vector(1, 0, 0)), s, vector(0, 0, 1));
                setcomp(m, 1, 2, t);
                float kr, kt;
                vector r, tr;
                fresnel(I, N, 1.5, kr, kt, r, tr);
                fresnel(I, N, 0.7, kr, kt);
                float f = spline(\"bezier\", s, 1, 2, 3, 4, 5, 6, 7) + spline(t, knots)
                    + ptlined(P, a, point(0, 0, 0)) + match(\"^a\", concat(\"a\", \"b\")) + kr + kt;
                point pr = rotate(P, t, point(0, 0, 0), point(0, 1, 0));
                vector sum = refract(I, N, 1.2) + tr + r + (transform(m, pr) - point(0, 0, 0));
                Ci = spline(\"linear\", s, c, Cs, c, Cs) * f + color(xcomp(sum), ycomp(sum), zcomp(sum))
                    + color(comp(c, 1), comp(m, 0, 3), sign(s));
            }",
        )
        .unwrap_or_else(|e| panic!("{e}"));
    }
}
