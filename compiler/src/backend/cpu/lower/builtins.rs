//! Built-in functions: the interpreter's instructions for `backend::ops`' one-operation built-ins
//! and for `backend::arith`'s componentwise sequences (which those instructions run on numbers),
//! `arith`'s vector sequences on registers, `random`, components, messages between shaders
//! (`lightsource`, `surface`), texel fetches, and the geometric family (in `geometry`).

use super::expr::pick;
use super::{Lower, Val};
use crate::backend::arith;
use crate::backend::cpu::code::{Binary, Compare, IntBinary, IntUnary, PrintArg, Reg, Ternary, Unary};
use crate::backend::ops::{CoreOp, core_op, not_core};
use crate::backend::{POINT_INDEX, UNIFORM_RANDOM_POINT};
use crate::diag::{Code as DiagCode, Diagnostic};
use crate::ir::builtin::Builtin;
use crate::ir::builtin::BuiltinId as B;
use crate::ir::types::{Base, Type};
use crate::ir::{ExprId, ExprKind};

/// The name of the input that gives `lightsource(name, ...)` light `k`'s parameter `name` at
/// each point: the caller reads it from the light's program after running it.
pub fn lightsource_input(name: &str, k: usize) -> String {
    format!("lightsource({name})[{k}]")
}

/// The name of the input that gives `surface(name, ...)` the bound surface's parameter `name` at
/// each point (the caller gives it per object).
pub fn surface_input(name: &str) -> String {
    format!("surface({name})")
}

/// The name of the uniform input that says whether the bound surface has a parameter `name` of
/// the type `surface(name, v)` asks for: 1 or 0.
pub fn surface_flag_input(name: &str) -> String {
    format!("surface?({name})")
}

/// The error for a call the interpreter cannot run.
fn no_implementation(b: &Builtin, span: crate::source::Span) -> Diagnostic {
    Diagnostic::error(
        DiagCode::NotExecutable,
        format!("the interpreter has no implementation of `{}`", b.signature),
        span,
        "this call",
    )
}

impl Lower<'_> {
    /// A call of a built-in: every built-in has its case here (the match on its id is
    /// exhaustive), those that never reach the interpreter an internal error.
    pub(super) fn builtin(
        &mut self,
        b: &'static Builtin,
        args: &[ExprId],
        id: ExprId,
    ) -> Result<Val, Diagnostic> {
        let span = self.shader.expr(id).span;
        let ret = self.shader.expr(id).ty;
        let vals: Vec<Val> = args.iter().map(|a| self.expr(*a)).collect::<Result<_, _>>()?;
        let f = |i: usize| vals[i].floats();
        let is_int = matches!(ret.base, Base::Int | Base::Uint);
        let signed = ret.base == Base::Int;
        Ok(match b.id {
            B::Pow => Val::Float(self.zip(Binary::Pow, f(0), f(1))),
            B::InverseSqrt => self.each(Unary::InverseSqrt, f(0)),
            B::Log if args.len() == 2 => {
                let (x, base) = (self.emit.unary(Unary::Log, f(0)[0]), self.emit.unary(Unary::Log, f(1)[0]));
                Val::Float(vec![self.emit.binary(Binary::Div, x, base)])
            }
            B::Mod => Val::Float(self.zip(Binary::Mod, f(0), f(1))),
            B::Abs if is_int && signed => {
                Val::Int(vals[0].ints().iter().map(|x| self.emit.int_unary(IntUnary::Abs, *x)).collect())
            }
            B::Abs if is_int => vals[0].clone(),
            B::Sign => self.each(Unary::Sign, f(0)),
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
                Some(CoreOp::Unary { cpu, .. }) => self.each(cpu, f(0)),
                Some(CoreOp::Binary { cpu, .. }) => Val::Float(self.zip(cpu, f(0), f(1))),
                None => return Err(not_core(b.id, span)),
            },
            B::Min | B::Max if is_int => {
                let op = match (b.id == B::Min, signed) {
                    (true, true) => IntBinary::MinI,
                    (true, false) => IntBinary::MinU,
                    (_, true) => IntBinary::MaxI,
                    _ => IntBinary::MaxU,
                };
                let mut acc = vals[0].ints().to_vec();
                for v in &vals[1..] {
                    acc = acc.iter().zip(v.ints()).map(|(a, b)| self.emit.int_binary(op, *a, *b)).collect();
                }
                Val::Int(acc)
            }
            B::Min | B::Max => {
                let op = if b.id == B::Min { Binary::Min } else { Binary::Max };
                let mut acc = f(0).to_vec();
                for v in &vals[1..] {
                    acc = self.zip(op, &acc, v.floats());
                }
                Val::Float(acc)
            }
            B::Clamp if is_int => {
                let (lo_op, hi_op) = if signed {
                    (IntBinary::MaxI, IntBinary::MinI)
                } else {
                    (IntBinary::MaxU, IntBinary::MinU)
                };
                let (x, lo, hi) = (vals[0].ints(), vals[1].ints(), vals[2].ints());
                let r = self.emit.int_binary(lo_op, x[0], lo[0]);
                Val::Int(vec![self.emit.int_binary(hi_op, r, hi[0])])
            }
            B::Clamp => self.each3(Ternary::Clamp, f(0), f(1), f(2)),
            B::Clamp01 => {
                let (zero, one) = (self.emit.float(0.0), self.emit.float(1.0));
                self.each3(Ternary::Clamp, f(0), &[zero], &[one])
            }
            B::Mix => self.each3(Ternary::Mix, f(0), f(1), f(2)),
            B::Step => Val::Float(self.zip(Binary::Step, f(0), f(1))),
            B::SmoothStep => self.each3(Ternary::Smoothstep, f(0), f(1), f(2)),
            B::FilterStep if args.len() == 3 => {
                Val::Float(vec![arith::filterstep(&mut self.emit, f(0)[0], f(1)[0], f(2)[0])])
            }
            B::Select => {
                let c = self.truth(&vals[0]);
                self.select(c, &vals[1], &vals[2])
            }
            B::Random | B::UniformRandom => {
                let n = ret.base.components();
                let regs = if b.id == B::Random {
                    let point = self.named_input(POINT_INDEX, Type::of(Base::Uint), false)[0];
                    (0..n)
                        .map(|_| {
                            self.random_sites += 1;
                            self.emit.random(self.random_sites, point)
                        })
                        .collect()
                } else {
                    // One value per draw: the hash of the fixed point index, known now.
                    (0..n)
                        .map(|_| {
                            self.random_sites += 1;
                            let x = crate::backend::cpu::scalar::random::<f64>(
                                UNIFORM_RANDOM_POINT,
                                self.random_sites,
                            );
                            self.emit.float(x)
                        })
                        .collect()
                };
                Val::Float(regs)
            }
            B::Printf => {
                let format = match &vals[0] {
                    Val::Str(s) => s.to_string(),
                    _ => String::new(),
                };
                let printed = args[1..]
                    .iter()
                    .zip(&vals[1..])
                    .map(|(a, v)| match v {
                        Val::Str(s) => PrintArg::Text(s.to_string()),
                        Val::Int(regs) => {
                            PrintArg::Ints(regs.clone(), self.shader.expr(*a).ty.base == Base::Int)
                        }
                        Val::Float(regs) => PrintArg::Floats(regs.clone()),
                        Val::Void => PrintArg::Text(String::new()),
                    })
                    .collect();
                self.emit.printf(format, printed);
                Val::Void
            }
            B::XComp | B::YComp | B::ZComp => {
                let i = [B::XComp, B::YComp, B::ZComp].iter().position(|n| *n == b.id).unwrap_or(0);
                Val::Float(vec![f(0)[i]])
            }
            B::SetXComp | B::SetYComp | B::SetZComp => {
                let i = [B::SetXComp, B::SetYComp, B::SetZComp].iter().position(|n| *n == b.id).unwrap_or(0);
                let mut v = f(0).to_vec();
                v[i] = f(1)[0];
                self.write_output(args[0], &Val::Float(v), span)?;
                Val::Void
            }
            B::Comp | B::SetComp => self.component(b.id, args, &vals, span)?,
            B::Length => Val::Float(vec![arith::length(&mut self.emit, f(0))]),
            B::Normalize => Val::Float(arith::normalize(&mut self.emit, f(0))),
            B::Dot => Val::Float(vec![arith::dot(&mut self.emit, f(0), f(1))]),
            B::Cross => Val::Float(arith::cross(&mut self.emit, f(0), f(1)).to_vec()),
            B::Rgb => Val::Float(f(0)[..3].to_vec()),
            B::LightSource => self.lightsource(&vals[0], args[1], span)?,
            B::Surface => self.surface_message(&vals[0], &vals[1], args[1], span)?,
            B::Concat => Val::Str(
                vals.iter()
                    .map(|v| match v {
                        Val::Str(s) => s.as_str(),
                        _ => "",
                    })
                    .collect::<String>()
                    .into(),
            ),
            B::XyzScreen => Val::Float(self.named_input("xyz_screen", ret, false)),
            B::Du | B::Dv | B::Deriv | B::FilterWidth | B::FilterStep | B::Area | B::CalculateNormal => {
                return Err(Diagnostic::error(
                    DiagCode::Internal,
                    format!("`{}` reached the interpreter without being differentiated", b.id),
                    span,
                    "this derivative",
                )
                .with_note("opt::derivs::differentiate must run before the interpreter's lowering"));
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
                return Err(Diagnostic::error(
                    DiagCode::Internal,
                    format!("`{}` reached the interpreter as a built-in", b.id),
                    span,
                    "this call",
                )
                .with_note(
                    "the semantic stage inlines its implementation from compiler/stdlib/builtins.sl",
                ));
            }
            B::Texel2d | B::Texel3d => {
                let texture = self.texture_index(args[0])?;
                let ints: Vec<Reg> = vals[1..].iter().map(|v| v.ints()[0]).collect();
                let zero = self.emit.int(0);
                let z = ints.get(2).copied().unwrap_or(zero);
                Val::Float((0..4).map(|c| self.emit.texel(texture, c, ints[0], ints[1], z)).collect())
            }
            B::Texsize2d | B::Texsize3d => {
                let texture = self.texture_index(args[0])?;
                let axis = match &self.shader.expr(args[1]).kind {
                    ExprKind::Literal(crate::ir::Literal::Int(a)) => (*a).clamp(0, 2) as u8,
                    _ => 0,
                };
                Val::Int(vec![self.emit.tex_size(texture, axis)])
            }
            B::Texture | B::Texture3d | B::Environment | B::Shadow => {
                return Err(Diagnostic::error(
                    DiagCode::NotExecutable,
                    format!("`{}` needs a bound texture, and evaluation at points has none", b.id),
                    span,
                    "texture lookup",
                )
                .with_note("textures are bound by the runtime when a scene is rendered"));
            }
            B::Transform
            | B::VTransform
            | B::NTransform
            | B::Transpose
            | B::Affine
            | B::Invert
            | B::Depth
            | B::ColourSpace
            | B::Spline
            | B::Match => match self.geometry(b, &vals, args, id)? {
                Some(v) => v,
                None => return Err(no_implementation(b, span)),
            },
            // A string the semantic stage computes (`format` of literals): no call of it remains.
            B::Format => return Err(no_implementation(b, span)),
            B::Ambient | B::Integrate => {
                return Err(Diagnostic::error(
                    DiagCode::Internal,
                    format!("`{}` reached the interpreter as a built-in", b.id),
                    span,
                    "this call",
                )
                .with_note("opt::lights::unroll makes it a sum over the bound lights"));
            }
        })
    }

    /// `lightsource(name, v)` inside `illuminance`, visiting light `self.light`: when the light
    /// has a parameter `name` of `v`'s type, its value at each point (the caller's input
    /// [`lightsource_input`]) is written to `v` and the call is 1; otherwise it is 0. Which it
    /// is, binding decides.
    fn lightsource(&mut self, name: &Val, out: ExprId, span: crate::source::Span) -> Result<Val, Diagnostic> {
        let ty = self.shader.expr(out).ty;
        let found = match (name, self.light) {
            (Val::Str(name), Some(k)) => self.binding.lights[k]
                .params
                .iter()
                .any(|(n, t)| n == name && *t == ty)
                .then(|| (name.clone(), k)),
            _ => None,
        };
        let Some((name, k)) = found else { return Ok(Val::Float(vec![self.emit.float(0.0)])) };
        let regs = self.named_input(&lightsource_input(&name, k), ty, false);
        self.write_output(out, &Val::Float(regs), span)?;
        Ok(Val::Float(vec![self.emit.float(1.0)]))
    }

    /// `surface(name, v)` in a light or an atmosphere: the bound surface's parameter `name`,
    /// which the caller gives per object, as [`surface_input`] (its value at each point) and
    /// [`surface_flag_input`] (1 when the surface has one of `v`'s type; 0 leaves `v` as it is).
    fn surface_message(
        &mut self,
        name: &Val,
        current: &Val,
        out: ExprId,
        span: crate::source::Span,
    ) -> Result<Val, Diagnostic> {
        let Val::Str(name) = name else { return Ok(Val::Float(vec![self.emit.float(0.0)])) };
        let ty = self.shader.expr(out).ty;
        let flag = self.named_input(&surface_flag_input(name), Type::FLOAT, true)[0];
        let value = self.named_input(&surface_input(name), ty, false);
        let zero = self.emit.float(0.0);
        let has = self.emit.compare(Compare::Ne, flag, zero);
        let chosen: Vec<Reg> =
            value.iter().zip(current.floats()).map(|(v, c)| self.emit.select(true, has, *v, *c)).collect();
        self.write_output(out, &Val::Float(chosen), span)?;
        Ok(Val::Float(vec![flag]))
    }

    /// Stores into the local passed as an `output` argument.
    pub(super) fn write_output(
        &mut self,
        arg: ExprId,
        v: &Val,
        span: crate::source::Span,
    ) -> Result<(), Diagnostic> {
        let place = match self.kind(arg) {
            ExprKind::Local(l) => crate::ir::Place::Local(*l),
            ExprKind::Global(g) => crate::ir::Place::Global(g),
            _ => return Ok(()),
        };
        let access = self.access(&place)?;
        self.store(&access, v, span)
    }

    /// `comp(c, i)`, `comp(m, row, col)`, `setcomp(c, i, x)`, `setcomp(m, row, col, x)`.
    fn component(
        &mut self,
        which: B,
        args: &[ExprId],
        vals: &[Val],
        span: crate::source::Span,
    ) -> Result<Val, Diagnostic> {
        let matrix = self.shader.expr(args[0]).ty.base == Base::Matrix4;
        let index_count = if matrix { 2 } else { 1 };
        let to_int = |this: &mut Self, v: &Val| {
            this.emit.convert(crate::backend::cpu::code::Convert::FloatToInt, v.floats()[0])
        };
        let mut index = to_int(self, &vals[1]);
        let width = if matrix { 16 } else { 3 };
        if matrix {
            let four = self.emit.int(4);
            let zero = self.emit.int(0);
            let three = self.emit.int(3);
            let row = self.emit.int_binary(IntBinary::MaxI, index, zero);
            let row = self.emit.int_binary(IntBinary::MinI, row, three);
            let col = to_int(self, &vals[2]);
            let col = self.emit.int_binary(IntBinary::MaxI, col, zero);
            let col = self.emit.int_binary(IntBinary::MinI, col, three);
            let row = self.emit.int_binary(IntBinary::Mul, row, four);
            index = self.emit.int_binary(IntBinary::Add, row, col);
        }
        let regs = vals[0].floats().to_vec();
        if which == B::Comp {
            let access = self.emit.consecutive(true, regs);
            let d = super::stmt::Dynamic { index, signed: true, len: width, stride: 1 };
            let a = super::stmt::Access { root: access, float: true, offset: 0, width: 1, dynamic: Some(d) };
            return Ok(self.read(&a));
        }
        // setcomp: the new value in the selected component, the old elsewhere.
        let x = vals[1 + index_count].floats()[0];
        let out: Vec<Reg> = (0..width)
            .map(|c| {
                let k = self.emit.int(c);
                let here = self.emit.int_compare(Compare::Eq, true, index, k);
                self.emit.select(true, here, x, regs[c as usize])
            })
            .collect();
        self.write_output(args[0], &Val::Float(out), span)?;
        Ok(Val::Void)
    }

    /// `op` applied to each component.
    pub(crate) fn each(&mut self, op: Unary, a: &[Reg]) -> Val {
        Val::Float(a.iter().map(|x| self.emit.unary(op, *x)).collect())
    }

    /// `op` applied componentwise to three operands (scalars apply to every component).
    pub(crate) fn each3(&mut self, op: Ternary, a: &[Reg], b: &[Reg], c: &[Reg]) -> Val {
        let n = a.len().max(b.len()).max(c.len());
        Val::Float((0..n).map(|i| self.emit.ternary(op, pick(a, i), pick(b, i), pick(c, i))).collect())
    }

    /// The number of the texture a name or `texref` argument denotes (a string's value, or the
    /// value the binding gives a texref parameter, or the parameter's name).
    fn texture_index(&mut self, id: ExprId) -> Result<u32, Diagnostic> {
        let name = match &self.shader.expr(id).kind {
            ExprKind::Local(l) if self.shader.local(*l).ty.base == Base::Texref => self
                .bound_string(*l)
                .map(|s| s.to_string())
                .unwrap_or_else(|| self.shader.local(*l).name.to_string()),
            _ => self.string_of(id)?.map(|s| s.to_string()).unwrap_or_default(),
        };
        let index = match self.textures.iter().position(|t| *t == name) {
            Some(i) => i,
            None => {
                self.textures.push(name);
                self.textures.len() - 1
            }
        };
        Ok(index as u32)
    }
}
