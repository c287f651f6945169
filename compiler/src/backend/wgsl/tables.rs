//! Constant tables: a `constant` array variable whose only store is its declaration with literal
//! elements (a permutation or gradient table) becomes one private module variable with that
//! initializer, shared by every inlined copy with the same contents, instead of a composite store
//! at each call. The stdlib's noises declare their tables inside the functions, so a shader with
//! many noise calls would otherwise build the same 256-entry array for every call.
//!
//! Integer and boolean tables, and float tables of at least [`SHARED_FLOAT_TABLE`] elements. With
//! a short float table whose values the driver can see, lavapipe's LLVM folds the arithmetic on
//! them differently from the interpreter (1 ulp in a spline over constant knots, found by
//! runtime/tests/stdlib_shaping_gpu.rs), and the backends promise the same bits; integer
//! operations are exact whatever is folded. A long float table is a gradient table read at a
//! hashed index (Perlin's 1985 noise: 768 floats), which nothing can fold, and composing it at
//! every call is what the driver cannot afford: one `perlin_noise3` took lavapipe 3.2 s to
//! compile that way (runtime/benches/pipelines.rs, docs/performance.md).

use naga::{Expression, Handle, Literal as NLit, Span};
use rustc_hash::FxHashMap;

use super::module::ModuleBuilder;
use crate::ir::types::{Base, Frequency, Type};
use crate::ir::{ExprId, ExprKind, Literal, LocalId, Shader, UnaryOp};

/// A table's element values, as naga literals (their bits identify the table).
pub(crate) type Contents = Vec<NLit>;

/// The fewest elements of a float table that is shared (see the module's comment).
pub(crate) const SHARED_FLOAT_TABLE: u32 = 64;

/// The locals of `shader` that are constant tables, with their contents.
pub(crate) fn find(shader: &Shader) -> FxHashMap<LocalId, Contents> {
    crate::ir::stores::stores(shader)
        .iter()
        .zip(&shader.locals)
        .enumerate()
        .filter_map(|(i, (stores, local))| {
            let table = local.declared
                && local.rate.frequency == Frequency::Constant
                && !local.rate.perlight
                && local.ty.array.is_some_and(|n| local.ty.base != Base::Float || n >= SHARED_FLOAT_TABLE)
                && matches!(local.ty.base, Base::Int | Base::Uint | Base::Bool | Base::Float);
            let value = stores.only_initialiser(local.span).filter(|_| table)?;
            let ExprKind::Construct(parts) = &shader.expr(value).kind else { return None };
            let contents: Option<Contents> =
                parts.iter().map(|&p| literal(shader, p, local.ty.base)).collect();
            contents.filter(|c| c.len() as u32 == local.ty.array.unwrap_or(0)).map(|c| (LocalId(i as u32), c))
        })
        .collect()
}

/// A literal element of type `base`, converted as the interpreter converts it.
fn literal(shader: &Shader, id: ExprId, base: Base) -> Option<NLit> {
    Some(match (base, value(shader, id)?) {
        (Base::Float, Literal::Float(x)) => NLit::F32(x as f32),
        (Base::Int, Literal::Int(i)) => NLit::I32(i),
        (Base::Uint, Literal::Uint(u)) => NLit::U32(u),
        (Base::Bool, Literal::Bool(b)) => NLit::Bool(b),
        _ => return None,
    })
}

/// The value of a literal, possibly negated or converted (`-0.25`, `{1, 2}` in a float table).
/// Int to float is exact in f64 and then rounds once to f32, as the interpreter's conversion.
fn value(shader: &Shader, id: ExprId) -> Option<Literal> {
    let e = shader.expr(id);
    match &e.kind {
        ExprKind::Literal(l) => Some(l.clone()),
        ExprKind::Unary(UnaryOp::Neg, a) => match value(shader, *a)? {
            Literal::Float(x) => Some(Literal::Float(-x)),
            Literal::Int(i) => Some(Literal::Int(i.wrapping_neg())),
            _ => None,
        },
        ExprKind::Convert(a) => match (e.ty.base, value(shader, *a)?) {
            (Base::Float, Literal::Float(x)) => Some(Literal::Float(x)),
            (Base::Float, Literal::Int(i)) => Some(Literal::Float(f64::from(i))),
            (Base::Float, Literal::Uint(u)) => Some(Literal::Float(f64::from(u))),
            (Base::Int, Literal::Int(i)) => Some(Literal::Int(i)),
            (Base::Uint, Literal::Uint(u)) => Some(Literal::Uint(u)),
            (Base::Uint, Literal::Int(i)) if i >= 0 => Some(Literal::Uint(i as u32)),
            _ => None,
        },
        _ => None,
    }
}

impl ModuleBuilder {
    /// The private variable initialized with `contents` (of type `ty`), made on first use and
    /// shared by every table with the same contents.
    pub(crate) fn table(
        &mut self,
        name: &str,
        ty: Type,
        contents: &Contents,
    ) -> Handle<naga::GlobalVariable> {
        let key = (ty, contents.iter().map(bits).collect::<Vec<u64>>());
        if let Some(h) = self.tables.get(&key) {
            return *h;
        }
        let array = self.ty(ty, false);
        let elements: Vec<Handle<Expression>> = contents
            .iter()
            .map(|l| self.module.global_expressions.append(Expression::Literal(*l), Span::UNDEFINED))
            .collect();
        let init = self
            .module
            .global_expressions
            .append(Expression::Compose { ty: array, components: elements }, Span::UNDEFINED);
        let h = self.module.global_variables.append(
            naga::GlobalVariable {
                name: Some(name.to_string()),
                space: naga::AddressSpace::Private,
                binding: None,
                ty: array,
                init: Some(init),
                memory_decorations: naga::MemoryDecorations::empty(),
            },
            Span::UNDEFINED,
        );
        self.tables.insert(key, h);
        h
    }
}

fn bits(l: &NLit) -> u64 {
    match *l {
        NLit::F32(x) => u64::from(x.to_bits()),
        NLit::I32(i) => u64::from(i as u32) | 1 << 32,
        NLit::U32(u) => u64::from(u) | 2 << 32,
        NLit::Bool(b) => u64::from(b) | 3 << 32,
        _ => u64::MAX,
    }
}
