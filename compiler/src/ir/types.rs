//! Types and rates: what every value in the IR carries.

use std::fmt;

/// The base types: scalars, RenderMan's three-component types and Stanford's vectors and matrices.
/// `color`, `point`, `vector`, `normal` and `float3` share a shape (three floats) and differ in
/// meaning (how `transform` treats them, which mixes are allowed).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Base {
    /// No value (functions that return nothing).
    Void,
    /// `bool`: comparisons, `select`, conditions.
    Bool,
    /// `int`: 32-bit two's complement, wrapping.
    Int,
    /// `uint`: 32-bit unsigned, wrapping.
    Uint,
    /// `float`: IEEE f32.
    Float,
    /// Stanford `clampf`: a float kept in [0, 1].
    Clampf,
    /// RenderMan `color`.
    Color,
    /// RenderMan `point`: a position (translated by `transform`).
    Point,
    /// RenderMan `vector`: a direction (not translated).
    Vector,
    /// RenderMan `normal`: transformed by the inverse transpose.
    Normal,
    /// Stanford `float3`.
    Float3,
    /// Stanford `float4`.
    Float4,
    /// Stanford `matrix3`.
    Matrix3,
    /// RenderMan `matrix` and Stanford `matrix4`: 4x4.
    Matrix4,
    /// A string (texture names, space names); constant only.
    String,
    /// A texture bound by the scene.
    Texref,
}

impl Base {
    /// The number of float components (1 for scalars, 0 for non-numeric types).
    pub fn components(self) -> u32 {
        match self {
            Base::Bool | Base::Int | Base::Uint | Base::Float | Base::Clampf => 1,
            Base::Color | Base::Point | Base::Vector | Base::Normal | Base::Float3 => 3,
            Base::Float4 => 4,
            Base::Matrix3 => 9,
            Base::Matrix4 => 16,
            Base::Void | Base::String | Base::Texref => 0,
        }
    }

    /// Whether this is one of the three-float types.
    pub fn is_triple(self) -> bool {
        matches!(self, Base::Color | Base::Point | Base::Vector | Base::Normal | Base::Float3)
    }

    /// Whether this is one of RenderMan's geometric types.
    pub fn is_geometric(self) -> bool {
        matches!(self, Base::Point | Base::Vector | Base::Normal)
    }

    /// Whether arithmetic applies (componentwise).
    pub fn is_numeric(self) -> bool {
        !matches!(self, Base::Void | Base::Bool | Base::String | Base::Texref)
    }

    /// Whether this is `int` or `uint`.
    pub fn is_integer(self) -> bool {
        matches!(self, Base::Int | Base::Uint)
    }

    /// Whether this is a float scalar (`float` or `clampf`).
    pub fn is_float_scalar(self) -> bool {
        matches!(self, Base::Float | Base::Clampf)
    }

    /// The name as written in source.
    pub fn name(self) -> &'static str {
        match self {
            Base::Void => "void",
            Base::Bool => "bool",
            Base::Int => "int",
            Base::Uint => "uint",
            Base::Float => "float",
            Base::Clampf => "clampf",
            Base::Color => "color",
            Base::Point => "point",
            Base::Vector => "vector",
            Base::Normal => "normal",
            Base::Float3 => "float3",
            Base::Float4 => "float4",
            Base::Matrix3 => "matrix3",
            Base::Matrix4 => "matrix",
            Base::String => "string",
            Base::Texref => "texref",
        }
    }

    /// The base type a source type name denotes.
    pub fn from_ast(name: crate::syntax::ast::TypeName) -> Base {
        use crate::syntax::ast::TypeName as T;
        match name {
            T::Float => Base::Float,
            T::Color => Base::Color,
            T::Point => Base::Point,
            T::Vector => Base::Vector,
            T::Normal => Base::Normal,
            T::Matrix | T::Matrix4 => Base::Matrix4,
            T::String => Base::String,
            T::Void => Base::Void,
            T::Float3 => Base::Float3,
            T::Float4 => Base::Float4,
            T::Matrix3 => Base::Matrix3,
            T::Bool => Base::Bool,
            T::Texref => Base::Texref,
            T::Clampf => Base::Clampf,
            T::Int => Base::Int,
            T::Uint => Base::Uint,
        }
    }
}

/// A type: a base type, or a fixed-size array of one.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct Type {
    /// The element type.
    pub base: Base,
    /// `Some(n)` for an array of `n`; `Some(0)` for an array parameter of any length.
    pub array: Option<u32>,
}

impl Type {
    /// A non-array type.
    pub const fn of(base: Base) -> Type {
        Type { base, array: None }
    }

    /// `void`.
    pub const VOID: Type = Type::of(Base::Void);
    /// `float`.
    pub const FLOAT: Type = Type::of(Base::Float);
    /// `bool`.
    pub const BOOL: Type = Type::of(Base::Bool);
    /// `int`.
    pub const INT: Type = Type::of(Base::Int);
    /// `string`.
    pub const STRING: Type = Type::of(Base::String);

    /// Whether this is an array.
    pub fn is_array(self) -> bool {
        self.array.is_some()
    }

    /// The type of this type's derivative (`opt::derivs`): a point's is a vector, a `clampf`'s a
    /// `float`; `None` when values of the type have no derivative (integers, bools, strings).
    pub fn derivative(self) -> Option<Type> {
        let base = match self.base {
            Base::Float | Base::Clampf => Base::Float,
            Base::Point => Base::Vector,
            b @ (Base::Color | Base::Vector | Base::Normal | Base::Float3 | Base::Float4) => b,
            b @ (Base::Matrix3 | Base::Matrix4) => b,
            Base::Void | Base::Bool | Base::Int | Base::Uint | Base::String | Base::Texref => return None,
        };
        Some(Type { base, array: self.array })
    }

    /// The type of an element of this type (what indexing it gives): an array's base type, a
    /// matrix's row, a string's character (a string), or a vector's component.
    pub fn element(self) -> Type {
        match (self.array, self.base) {
            (Some(_), b) => Type::of(b),
            (None, Base::Matrix4) => Type::of(Base::Float4),
            (None, Base::Matrix3) => Type::of(Base::Float3),
            (None, Base::String) => Type::STRING,
            (None, _) => Type::FLOAT,
        }
    }
}

impl fmt::Display for Type {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.array {
            None => f.write_str(self.base.name()),
            Some(0) => write!(f, "{}[]", self.base.name()),
            Some(n) => write!(f, "{}[{n}]", self.base.name()),
        }
    }
}

/// How often a value is computed: the lattice `constant < primitive group < vertex < fragment`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Frequency {
    /// Known when the shader is compiled.
    Constant,
    /// Once per draw (RenderMan `uniform`); computed on the host.
    PrimitiveGroup,
    /// Once per vertex.
    Vertex,
    /// Once per fragment (shading point).
    Fragment,
}

impl Frequency {
    /// How the rate is written in source.
    pub fn name(self) -> &'static str {
        match self {
            Frequency::Constant => "constant",
            Frequency::PrimitiveGroup => "primitive group",
            Frequency::Vertex => "vertex",
            Frequency::Fragment => "fragment",
        }
    }
}

/// The rate of a value: a frequency, and whether there is one instance per bound light.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct Rate {
    /// How often it is computed.
    pub frequency: Frequency,
    /// One instance per light (inside `illuminance`, or declared `perlight`).
    pub perlight: bool,
}

impl Rate {
    /// A rate without `perlight`.
    pub const fn at(frequency: Frequency) -> Rate {
        Rate { frequency, perlight: false }
    }

    /// Compile-time constant.
    pub const CONSTANT: Rate = Rate::at(Frequency::Constant);
    /// Once per draw.
    pub const UNIFORM: Rate = Rate::at(Frequency::PrimitiveGroup);
    /// Once per vertex.
    pub const VERTEX: Rate = Rate::at(Frequency::Vertex);
    /// Once per fragment.
    pub const FRAGMENT: Rate = Rate::at(Frequency::Fragment);

    /// The least rate at least as high as both (Stanford's promotion rule).
    pub fn join(self, other: Rate) -> Rate {
        Rate { frequency: self.frequency.max(other.frequency), perlight: self.perlight || other.perlight }
    }

    /// Whether a value of rate `self` may be stored where `other` is declared.
    pub fn fits_in(self, other: Rate) -> bool {
        self.frequency <= other.frequency && (!self.perlight || other.perlight)
    }
}

impl fmt::Display for Rate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.perlight {
            write!(f, "perlight {}", self.frequency.name())
        } else {
            f.write_str(self.frequency.name())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_form_a_lattice() {
        let perlight_vertex = Rate { frequency: Frequency::Vertex, perlight: true };
        assert_eq!(Rate::UNIFORM.join(Rate::VERTEX), Rate::VERTEX);
        assert_eq!(Rate::FRAGMENT.join(Rate::CONSTANT), Rate::FRAGMENT);
        assert_eq!(
            perlight_vertex.join(Rate::FRAGMENT),
            Rate { frequency: Frequency::Fragment, perlight: true }
        );
        assert!(Rate::VERTEX.fits_in(Rate::FRAGMENT));
        assert!(!Rate::FRAGMENT.fits_in(Rate::VERTEX));
        assert!(!perlight_vertex.fits_in(Rate::FRAGMENT));
        assert_eq!(perlight_vertex.to_string(), "perlight vertex");
        assert_eq!(Type { base: Base::Float, array: Some(3) }.to_string(), "float[3]");
    }
}
