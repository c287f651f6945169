//! Which conversions are implicit, which need a cast, and what each costs in overload resolution.
//!
//! The rules (docs/language.md, "Conversions", states them for users):
//! - `int` and `uint` widen to `float` (cost 1); `int` and `uint` never mix implicitly.
//! - `float` and `clampf` convert both ways (cost 1; to `clampf` clamps).
//! - A scalar (`float`, `int`, `uint`) widens to any vector, colour or matrix by duplication
//!   (cost 2; to a matrix it gives the scaled identity, as in RenderMan).
//! - `point`, `vector` and `normal` convert among themselves, and `float3` to and from any of the
//!   three-float types including `color` (cost 1): Stanford's `float3` is RenderMan's shape.
//! - `color` and the geometric types do not mix implicitly; a cast converts them.
//! - Nothing converts implicitly to or from `bool`, `string`, `texref`, `float4` or an array,
//!   except an array to an array parameter of any length.

use crate::ir::types::{Base, Type};

/// The cost of converting `from` to `to` implicitly, or `None` when it needs a cast (or cannot be
/// done at all).
pub fn implicit_cost(from: Type, to: Type) -> Option<u32> {
    if from == to {
        return Some(0);
    }
    match (from.array, to.array) {
        (Some(n), Some(0)) if n > 0 && from.base == to.base => return Some(0),
        (None, None) => {}
        _ => return None,
    }
    use Base::*;
    let (f, t) = (from.base, to.base);
    match (f, t) {
        (Int | Uint, Float | Clampf) => Some(1),
        (Float, Clampf) | (Clampf, Float) => Some(1),
        (
            Float | Clampf | Int | Uint,
            Color | Point | Vector | Normal | Float3 | Float4 | Matrix3 | Matrix4,
        ) => Some(2),
        (Point | Vector | Normal, Point | Vector | Normal) => Some(1),
        (Float3, Color | Point | Vector | Normal) | (Color | Point | Vector | Normal, Float3) => Some(1),
        _ => None,
    }
}

/// Whether `from` can be cast to `to` explicitly (`color (p)`, `float (i)`, `int (x)`).
pub fn explicit_ok(from: Type, to: Type) -> bool {
    if implicit_cost(from, to).is_some() {
        return true;
    }
    if from.array.is_some() || to.array.is_some() {
        return false;
    }
    let (f, t) = (from.base, to.base);
    let scalar = |b: Base| matches!(b, Base::Float | Base::Clampf | Base::Int | Base::Uint | Base::Bool);
    (scalar(f) && scalar(t)) || (f.is_triple() && t.is_triple())
}

/// The common type two operands of an arithmetic operator are brought to, if any.
pub fn common_type(a: Type, b: Type) -> Option<Type> {
    if a == b {
        return Some(a);
    }
    if a.array.is_some() || b.array.is_some() {
        return None;
    }
    use Base::*;
    // Prefer the wider operand: converting the other to it must be implicit.
    let rank = |t: Base| match t {
        Bool | Void | String | Texref => 0,
        Int | Uint => 1,
        Clampf => 2,
        Float => 3,
        Float3 => 4,
        Color | Point | Vector | Normal => 5,
        Float4 => 6,
        Matrix3 => 7,
        Matrix4 => 8,
    };
    let (wide, narrow) = if rank(a.base) >= rank(b.base) { (a, b) } else { (b, a) };
    // Points, vectors and normals mixed: the result is a vector unless a point is involved.
    if wide.base.is_geometric() && narrow.base.is_geometric() {
        return Some(Type::of(if a.base == Point || b.base == Point { Point } else { Vector }));
    }
    implicit_cost(narrow, wide).map(|_| wide)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(b: Base) -> Type {
        Type::of(b)
    }

    #[test]
    fn implicit_conversions() {
        assert_eq!(implicit_cost(t(Base::Int), t(Base::Float)), Some(1));
        assert_eq!(implicit_cost(t(Base::Float), t(Base::Color)), Some(2));
        assert_eq!(implicit_cost(t(Base::Point), t(Base::Vector)), Some(1));
        assert_eq!(implicit_cost(t(Base::Float3), t(Base::Color)), Some(1));
        assert_eq!(implicit_cost(t(Base::Color), t(Base::Point)), None);
        assert_eq!(implicit_cost(t(Base::Int), t(Base::Uint)), None);
        assert_eq!(implicit_cost(t(Base::Float4), t(Base::Float3)), None);
        assert_eq!(implicit_cost(t(Base::Bool), t(Base::Float)), None);
        let arr = |n| Type { base: Base::Float, array: Some(n) };
        assert_eq!(implicit_cost(arr(3), arr(0)), Some(0));
        assert_eq!(implicit_cost(arr(3), arr(4)), None);
    }

    #[test]
    fn explicit_casts() {
        assert!(explicit_ok(t(Base::Color), t(Base::Point)));
        assert!(explicit_ok(t(Base::Float), t(Base::Int)));
        assert!(!explicit_ok(t(Base::String), t(Base::Float)));
        assert!(!explicit_ok(t(Base::Float4), t(Base::Float3)));
    }

    #[test]
    fn common_types() {
        assert_eq!(common_type(t(Base::Float), t(Base::Color)), Some(t(Base::Color)));
        assert_eq!(common_type(t(Base::Point), t(Base::Vector)), Some(t(Base::Point)));
        assert_eq!(common_type(t(Base::Normal), t(Base::Vector)), Some(t(Base::Vector)));
        assert_eq!(common_type(t(Base::Int), t(Base::Float)), Some(t(Base::Float)));
        assert_eq!(common_type(t(Base::Color), t(Base::Point)), None);
        assert_eq!(common_type(t(Base::Float3), t(Base::Color)), Some(t(Base::Color)));
        assert_eq!(common_type(t(Base::Int), t(Base::Uint)), None);
    }
}
