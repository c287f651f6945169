//! Constant tables: a `constant` array variable whose only store is its declaration with literal
//! elements (a permutation or gradient table) becomes one private module variable with that
//! initializer, shared by every inlined copy with the same contents, instead of a composite store
//! at each call. The stdlib's noises declare their tables inside the functions, so a shader with
//! many noise calls would otherwise build the same 256-entry array for every call.
//!
//! Integer and boolean tables, and float tables of at least [`SHARED_FLOAT_TABLE`] elements. With
//! a short float table whose values the driver can see, lavapipe's LLVM folds the arithmetic on
//! them differently from the interpreter (1 ulp in a spline over constant knots, found by
//! runtime/tests/stdlib/shaping_gpu.rs), and the backends promise the same bits; integer
//! operations are exact whatever is folded. A long float table is a gradient table read at a
//! hashed index (Perlin's 1985 noise: 768 floats), which nothing can fold, and composing it at
//! every call is what the driver cannot afford: one `perlin_noise3` took lavapipe 3.2 s to
//! compile that way (runtime/benches/pipelines.rs, docs/performance.md).
//!
//! A table that is only ever indexed (never read whole) and whose elements are numbers lives in
//! the uniform block instead, while the block's tables fit [`TABLE_BUDGET`]: lavapipe compiles an
//! indexed read of a module variable's array at a cost that grows with the array (about 5 ms per
//! read of a 256-entry table), and one of a buffer at about a quarter of that, whatever its
//! length. `noise_panel`'s 306 permutation reads took its pipeline creation from 2.5 s to 1.4 s
//! that way. The host writes the values ([`UniformSource::Table`],
//! `Interface::blank_block`).

use naga::{Expression, Handle, Literal as NLit, Span};
use rustc_hash::{FxHashMap, FxHashSet};

use super::interface::UniformSource;
use super::module::ModuleBuilder;
use crate::ir::types::{Base, Frequency, Type};
use crate::ir::{ExprId, ExprKind, Literal, LocalId, Shader, UnaryOp};

/// A table's element values, as naga literals (their bits identify the table).
pub(crate) type Contents = Vec<NLit>;

/// A constant table: its contents, and whether it may live in the uniform block.
pub(crate) struct Table {
    pub contents: Contents,
    /// Whether every read indexes it and its elements are numbers (the block holds no booleans).
    pub indexed_only: bool,
}

/// The fewest elements of a float table that is shared (see the module's comment).
pub(crate) const SHARED_FLOAT_TABLE: u32 = 64;

/// The most bytes of the uniform block that tables take (each element is padded to 16 bytes, as
/// the block's arrays are): half of the 64 KiB every WebGPU device binds, leaving the rest to
/// parameters. `noise_panel`'s tables take 9 KiB.
pub(crate) const TABLE_BUDGET: u32 = 32 * 1024;

/// The locals of `shader` that are constant tables, with their contents.
pub(crate) fn find(shader: &Shader) -> FxHashMap<LocalId, Table> {
    let whole = read_whole(shader);
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
            let l = LocalId(i as u32);
            let indexed_only = local.ty.base != Base::Bool && !whole.contains(&l);
            contents
                .filter(|c| c.len() as u32 == local.ty.array.unwrap_or(0))
                .map(|contents| (l, Table { contents, indexed_only }))
        })
        .collect()
}

/// The locals some expression of `shader` reads whole: as a value, not as the array an index
/// reads from.
fn read_whole(shader: &Shader) -> FxHashSet<LocalId> {
    let mut indexed = FxHashSet::default();
    for e in &shader.exprs {
        if let ExprKind::Index(base, _) = e.kind {
            indexed.insert(base);
        }
    }
    shader
        .exprs
        .iter()
        .enumerate()
        .filter_map(|(i, e)| match e.kind {
            ExprKind::Local(l) if !indexed.contains(&ExprId(i as u32)) => Some(l),
            _ => None,
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
    /// The uniform block's member holding `table` (of type `ty`), when it may live there and
    /// fits the budget; otherwise it is [`ModuleBuilder::table`]'s variable.
    pub(crate) fn table_member(&mut self, name: &str, ty: Type, table: &Table) -> Option<u32> {
        if !table.indexed_only {
            return None;
        }
        let values: Vec<f64> = table.contents.iter().map(value_of).collect();
        let bytes = 16 * table.contents.len() as u32;
        self.uniform_table(name, ty, UniformSource::Table { values }, bytes)
    }

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

/// A table element as the interface writes it.
fn value_of(l: &NLit) -> f64 {
    match *l {
        NLit::F32(x) => f64::from(x),
        NLit::I32(i) => f64::from(i),
        NLit::U32(u) => f64::from(u),
        NLit::Bool(b) => f64::from(u8::from(b)),
        _ => 0.0,
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
