//! Fixed parameters become literals, and conditions over literals are evaluated.

use rustc_hash::FxHashMap;

use super::{Decision, Fixed};
use crate::ir::types::{Base, Rate};
use crate::ir::{BinaryOp, Expr, ExprId, ExprKind, Literal, LocalKind, Shader, UnaryOp};

/// The expressions that read a fixed parameter, with its name (for the reasons of decisions).
pub(super) type Reads = FxHashMap<ExprId, String>;

/// Replaces every read of a fixed parameter by its value: a literal, or a construction of
/// literals for a vector, colour or matrix. Returns what was folded and where.
pub(super) fn substitute(shader: &mut Shader, fixed: &[Fixed]) -> (Vec<Decision>, Reads) {
    let stores = crate::ir::stores::stores(shader);
    let places = output_args(shader);
    let mut decisions = Vec::new();
    let mut reads = Reads::default();
    for f in fixed {
        let Some(&p) = shader.params.iter().find(|p| shader.local(**p).name == f.name.as_str()) else {
            continue;
        };
        let local = shader.local(p);
        let writable = matches!(local.kind, LocalKind::Param { output: true, .. });
        let ty = local.ty;
        // Only values the scene can give as numbers; a parameter the shader writes is a variable.
        let foldable = !writable
            && stores[p.0 as usize].count == 0
            && ty.array.is_none()
            && !matches!(ty.base, Base::String | Base::Texref | Base::Void)
            && f.value.len() == ty.base.components() as usize;
        if !foldable {
            continue;
        }
        let users: Vec<usize> = (0..shader.exprs.len())
            .filter(|&i| {
                matches!(shader.exprs[i].kind, ExprKind::Local(l) if l == p)
                    && !places.contains(&ExprId(i as u32))
            })
            .collect();
        for i in users {
            let span = shader.exprs[i].span;
            let kind = if f.value.len() == 1 {
                ExprKind::Literal(literal(ty.base, f.value[0]))
            } else {
                let element = ty.element();
                let parts = f
                    .value
                    .iter()
                    .map(|&v| {
                        let id = ExprId(shader.exprs.len() as u32);
                        let kind = ExprKind::Literal(literal(element.base, v));
                        shader.exprs.push(Expr { kind, ty: element, rate: Rate::CONSTANT, span });
                        id
                    })
                    .collect();
                ExprKind::Construct(parts)
            };
            let e = &mut shader.exprs[i];
            e.kind = kind;
            e.rate = Rate::CONSTANT;
            reads.insert(ExprId(i as u32), f.name.clone());
        }
        decisions.push(Decision::Folded { name: f.name.clone(), value: f.value.clone() });
    }
    (decisions, reads)
}

/// Decides every comparison of two strings whose values are known: literals, and string
/// parameters the shader never writes, whose value is the scene's (`strings`) or else a literal
/// default. Strings are compile-time values on both backends, so such a comparison is one; the
/// comparisons become literals, recorded in `reads` with the parameters they read, so that the
/// branches they guard (`if (texturename != "")`) are decided like those of fixed numbers.
pub(super) fn compare_strings(shader: &mut Shader, strings: &[(String, String)], reads: &mut Reads) {
    let stores = crate::ir::stores::stores(shader);
    // A known string and the parameter it was read from, if any.
    let value = |shader: &Shader, id: ExprId| -> Option<(String, Option<String>)> {
        match &shader.expr(id).kind {
            ExprKind::Literal(Literal::String(s)) => Some((s.to_string(), None)),
            ExprKind::Local(l) => {
                let local = shader.local(*l);
                let LocalKind::Param { output: false, default } = local.kind else { return None };
                if stores[l.0 as usize].count != 0 || local.ty.is_array() {
                    return None;
                }
                let name = local.name.to_string();
                if let Some((_, s)) = strings.iter().find(|(n, _)| *n == name) {
                    return Some((s.clone(), Some(name)));
                }
                match default.map(|d| &shader.expr(d).kind) {
                    Some(ExprKind::Literal(Literal::String(s))) => Some((s.to_string(), Some(name))),
                    _ => None,
                }
            }
            _ => None,
        }
    };
    for i in 0..shader.exprs.len() {
        let ExprKind::Binary(op @ (BinaryOp::Eq | BinaryOp::Ne), a, b) = shader.exprs[i].kind else {
            continue;
        };
        if shader.expr(a).ty.base != Base::String {
            continue;
        }
        let (Some((x, p)), Some((y, q))) = (value(shader, a), value(shader, b)) else { continue };
        let names: Vec<String> = p.into_iter().chain(q).collect();
        let Some(name) = names.first() else { continue };
        let e = &mut shader.exprs[i];
        e.kind = ExprKind::Literal(Literal::Bool((x == y) == (op == BinaryOp::Eq)));
        e.rate = Rate::CONSTANT;
        reads.insert(ExprId(i as u32), name.clone());
    }
}

/// The expressions that are `output` arguments of built-ins: places written, not reads.
pub(super) fn output_args(shader: &Shader) -> rustc_hash::FxHashSet<ExprId> {
    let mut places = rustc_hash::FxHashSet::default();
    for e in &shader.exprs {
        if let ExprKind::Builtin(b, args) = &e.kind {
            let outputs = args.iter().enumerate().filter(|(k, _)| b.param_type(*k).is_some_and(|p| p.output));
            places.extend(outputs.map(|(_, a)| *a));
        }
    }
    places
}

/// A literal of a scalar type from a scene's number.
fn literal(base: Base, v: f64) -> Literal {
    match base {
        Base::Int => Literal::Int(v as i32),
        Base::Uint => Literal::Uint(v as u32),
        Base::Bool => Literal::Bool(v != 0.0),
        _ => Literal::Float(v),
    }
}

/// A scalar known at bind time.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(super) enum Scalar {
    Float(f64),
    Int(i64),
    Bool(bool),
}

impl Scalar {
    fn number(self) -> f64 {
        match self {
            Scalar::Float(x) => x,
            Scalar::Int(i) => i as f64,
            Scalar::Bool(b) => f64::from(u8::from(b)),
        }
    }
}

/// The value of scalar expression `id` when it depends on literals only, evaluated in f64 (as the
/// host evaluates per-draw values) and with wrapping 32-bit integers; `None` otherwise, or where
/// the value would need a built-in (those are left to run as they would).
pub(super) fn constant(shader: &Shader, id: ExprId) -> Option<Scalar> {
    constant_in(shader, id, &|_| None)
}

/// As [`constant`], with the values `known` gives for some locals (those just stored).
pub(super) fn constant_in(
    shader: &Shader,
    id: ExprId,
    known: &dyn Fn(crate::ir::LocalId) -> Option<Scalar>,
) -> Option<Scalar> {
    let constant = |shader: &Shader, id: ExprId| constant_in(shader, id, known);
    let e = shader.expr(id);
    if e.ty.array.is_some() || e.ty.base.components() != 1 {
        return None;
    }
    let int = matches!(e.ty.base, Base::Int | Base::Uint);
    let wrap =
        |x: i64| -> i64 { if e.ty.base == Base::Uint { i64::from(x as u32) } else { i64::from(x as i32) } };
    Some(match &e.kind {
        ExprKind::Literal(Literal::Float(x)) => Scalar::Float(*x),
        ExprKind::Literal(Literal::Int(i)) => Scalar::Int(i64::from(*i)),
        ExprKind::Literal(Literal::Uint(u)) => Scalar::Int(i64::from(*u)),
        ExprKind::Literal(Literal::Bool(b)) => Scalar::Bool(*b),
        ExprKind::Literal(Literal::String(_)) => return None,
        ExprKind::Local(l) => known(*l)?,
        ExprKind::Convert(a) => {
            let v = constant(shader, *a)?;
            match e.ty.base {
                Base::Bool => Scalar::Bool(v.number() != 0.0),
                Base::Int | Base::Uint => Scalar::Int(wrap(v.number() as i64)),
                _ => Scalar::Float(v.number()),
            }
        }
        ExprKind::Unary(op, a) => match (op, constant(shader, *a)?) {
            (UnaryOp::Neg, Scalar::Float(x)) => Scalar::Float(-x),
            (UnaryOp::Neg, Scalar::Int(i)) => Scalar::Int(wrap(-i)),
            (UnaryOp::Not, Scalar::Bool(b)) => Scalar::Bool(!b),
            (UnaryOp::BitNot, Scalar::Int(i)) => Scalar::Int(wrap(!i)),
            _ => return None,
        },
        ExprKind::Binary(op, a, b) => {
            let (x, y) = (constant(shader, *a)?, constant(shader, *b)?);
            binary(*op, x, y, int, wrap)?
        }
        ExprKind::Select(c, a, b) => match constant(shader, *c)? {
            Scalar::Bool(true) => constant(shader, *a)?,
            Scalar::Bool(false) => constant(shader, *b)?,
            _ => return None,
        },
        _ => return None,
    })
}

fn binary(op: BinaryOp, x: Scalar, y: Scalar, int: bool, wrap: impl Fn(i64) -> i64) -> Option<Scalar> {
    use BinaryOp::*;
    if let (Scalar::Bool(p), Scalar::Bool(q)) = (x, y) {
        return Some(Scalar::Bool(match op {
            And => p && q,
            Or => p || q,
            Eq => p == q,
            Ne => p != q,
            _ => return None,
        }));
    }
    let (a, b) = (x.number(), y.number());
    let compare = |r: bool| Some(Scalar::Bool(r));
    match op {
        Eq => compare(a == b),
        Ne => compare(a != b),
        Lt => compare(a < b),
        Le => compare(a <= b),
        Gt => compare(a > b),
        Ge => compare(a >= b),
        // Integer arithmetic only where it cannot trap; float arithmetic in f64 like the host.
        Add | Sub | Mul if int => {
            let (i, j) = (a as i64, b as i64);
            Some(Scalar::Int(wrap(match op {
                Add => i.wrapping_add(j),
                Sub => i.wrapping_sub(j),
                _ => i.wrapping_mul(j),
            })))
        }
        Add => Some(Scalar::Float(a + b)),
        Sub => Some(Scalar::Float(a - b)),
        Mul => Some(Scalar::Float(a * b)),
        Div if !int => Some(Scalar::Float(a / b)),
        _ => None,
    }
}
