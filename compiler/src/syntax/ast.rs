//! The abstract syntax tree: both surface styles in one set of types, every node with its span.
//!
//! Items and large statements are boxed: the parser moves its partial results on every step, so
//! small nodes keep it fast (see the parse benchmark).
//!
//! The tree records what was written, not what it means: `uniform` and `primitive group` stay
//! distinct, a cast is not yet a conversion, and `^` is not yet cross product or xor. The semantic
//! stage decides those.

use smol_str::SmolStr;

use crate::source::Span;

/// A name with its place in the source.
#[derive(Clone, Debug, PartialEq)]
pub struct Ident {
    /// The name.
    pub name: SmolStr,
    /// Where it was written.
    pub span: Span,
}

/// One preprocessed source file (with everything it includes).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Module {
    /// The definitions, in source order.
    pub items: Vec<Item>,
}

/// A top-level definition.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// A shader: `surface plastic(...) {...}` or `surface shader float4 f(...) {...}`.
    Shader(Box<ShaderDef>),
    /// A function.
    Function(Box<FunctionDef>),
    /// A global variable declaration (`constant float k = 2;`).
    Variable(Box<VarDecl>),
    /// A definition that did not parse; its error has been reported.
    Error(Span),
}

/// What a shader computes.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum ShaderKind {
    /// Surface colour and opacity.
    Surface,
    /// Light arriving at a surface point.
    Light,
    /// Moved positions and normals.
    Displacement,
    /// Light passing through a volume.
    Volume,
    /// Pixel colours after rendering.
    Imager,
}

impl ShaderKind {
    /// The keyword.
    pub fn keyword(self) -> &'static str {
        match self {
            ShaderKind::Surface => "surface",
            ShaderKind::Light => "light",
            ShaderKind::Displacement => "displacement",
            ShaderKind::Volume => "volume",
            ShaderKind::Imager => "imager",
        }
    }
}

/// Which of the two surface styles a shader was written in.
#[derive(Clone, Debug, PartialEq)]
pub enum ShaderStyle {
    /// `surface name(params) {...}`: results go to `Ci`, `Oi`, `Cl`, `P`, `N`.
    RenderMan,
    /// `surface shader float4 name(params) {...}`: the result is returned.
    Stanford {
        /// The declared result type.
        return_type: TypeSpec,
    },
}

/// A shader definition.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaderDef {
    /// Surface, light, ...
    pub kind: ShaderKind,
    /// The style it was written in.
    pub style: ShaderStyle,
    /// Its name.
    pub name: Ident,
    /// Its parameters, with defaults in RenderMan style.
    pub params: Vec<Param>,
    /// Its body.
    pub body: Block,
    /// The whole definition.
    pub span: Span,
}

/// A function definition.
#[derive(Clone, Debug, PartialEq)]
pub struct FunctionDef {
    /// Stanford's `surface float3 f(...)`: the kind of shader whose built-ins the function may use.
    pub context: Option<(ShaderKind, Span)>,
    /// The result type (`void` for none).
    pub return_type: TypeSpec,
    /// Its name.
    pub name: Ident,
    /// Its parameters.
    pub params: Vec<Param>,
    /// Its body.
    pub body: Block,
    /// The whole definition.
    pub span: Span,
}

/// A type name as written.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum TypeName {
    /// `float`.
    Float,
    /// `color` (RenderMan): three floats, an RGB colour.
    Color,
    /// `point` (RenderMan): three floats, a position, translated by transforms.
    Point,
    /// `vector` (RenderMan): three floats, a direction.
    Vector,
    /// `normal` (RenderMan): three floats, transformed by the inverse transpose.
    Normal,
    /// `matrix` (RenderMan): the 4×4 matrix, the same type as `matrix4`.
    Matrix,
    /// `string`: a compile-time string (texture and space names).
    String,
    /// `void`: the result type of a function that returns nothing.
    Void,
    /// `float3` (Stanford): a plain 3-vector.
    Float3,
    /// `float4` (Stanford): four floats, colours and homogeneous points.
    Float4,
    /// `matrix3` (Stanford): a 3×3 matrix.
    Matrix3,
    /// `matrix4` (Stanford): a 4×4 matrix.
    Matrix4,
    /// `bool`.
    Bool,
    /// `texref` (Stanford): a texture bound by the scene.
    Texref,
    /// `clampf` (Stanford): a float kept in [0, 1].
    Clampf,
    /// `int`: a 32-bit signed integer that wraps.
    Int,
    /// `uint`: a 32-bit unsigned integer that wraps.
    Uint,
}

impl TypeName {
    /// The keyword.
    pub fn keyword(self) -> &'static str {
        use TypeName::*;
        match self {
            Float => "float",
            Color => "color",
            Point => "point",
            Vector => "vector",
            Normal => "normal",
            Matrix => "matrix",
            String => "string",
            Void => "void",
            Float3 => "float3",
            Float4 => "float4",
            Matrix3 => "matrix3",
            Matrix4 => "matrix4",
            Bool => "bool",
            Texref => "texref",
            Clampf => "clampf",
            Int => "int",
            Uint => "uint",
        }
    }
}

/// A type with its span.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct TypeSpec {
    /// Which type.
    pub name: TypeName,
    /// Where it was written.
    pub span: Span,
}

/// A storage class (RenderMan) or computation rate (Stanford), as written.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum RateQualifier {
    /// RenderMan `uniform`: one value per primitive group.
    Uniform,
    /// RenderMan `varying`: one value per shading point.
    Varying,
    /// Stanford `constant`: known at compile time.
    Constant,
    /// Stanford `primitive group`.
    PrimitiveGroup,
    /// Stanford `vertex`.
    Vertex,
    /// Stanford `fragment`.
    Fragment,
}

impl RateQualifier {
    /// The keyword(s).
    pub fn keyword(self) -> &'static str {
        match self {
            RateQualifier::Uniform => "uniform",
            RateQualifier::Varying => "varying",
            RateQualifier::Constant => "constant",
            RateQualifier::PrimitiveGroup => "primitive group",
            RateQualifier::Vertex => "vertex",
            RateQualifier::Fragment => "fragment",
        }
    }
}

/// The qualifiers in front of a declaration.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct Qualifiers {
    /// The storage class or rate, if one was written.
    pub rate: Option<(RateQualifier, Span)>,
    /// `perlight`: one instance per bound light.
    pub perlight: Option<Span>,
    /// `output`: a parameter the shader writes.
    pub output: Option<Span>,
    /// `extern`: a variable of an enclosing scope.
    pub extern_: Option<Span>,
}

/// The size of an array declaration.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ArraySize {
    /// The element count; `None` for `[]` (an array parameter of any length).
    pub len: Option<u32>,
    /// The brackets and what is between them.
    pub span: Span,
}

/// A shader or function parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// Its qualifiers (shared with the parameters declared beside it).
    pub qualifiers: Qualifiers,
    /// Its type.
    pub ty: TypeSpec,
    /// Its name.
    pub name: Ident,
    /// Its array size, for an array.
    pub array: Option<ArraySize>,
    /// Its default value (shader parameters).
    pub default: Option<Expr>,
    /// The parameter's declarator (name, size and default).
    pub span: Span,
}

/// A variable declaration: qualifiers, a type, and one or more declarators.
#[derive(Clone, Debug, PartialEq)]
pub struct VarDecl {
    /// The qualifiers.
    pub qualifiers: Qualifiers,
    /// The type.
    pub ty: TypeSpec,
    /// The variables declared.
    pub declarators: Vec<Declarator>,
    /// The whole declaration.
    pub span: Span,
}

/// One variable of a declaration.
#[derive(Clone, Debug, PartialEq)]
pub struct Declarator {
    /// Its name.
    pub name: Ident,
    /// Its array size, for an array.
    pub array: Option<ArraySize>,
    /// Its initial value.
    pub init: Option<Expr>,
    /// Name, size and initialiser.
    pub span: Span,
}

/// `{ statements }`.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// The statements.
    pub stmts: Vec<Stmt>,
    /// The braces and everything between.
    pub span: Span,
}

/// A statement with its span.
#[derive(Clone, Debug, PartialEq)]
pub struct Stmt {
    /// What it is.
    pub kind: StmtKind,
    /// Where it is.
    pub span: Span,
}

/// The statements.
#[derive(Clone, Debug, PartialEq)]
pub enum StmtKind {
    /// `{ ... }`.
    Block(Block),
    /// A variable declaration.
    Decl(Box<VarDecl>),
    /// A function defined inside a shader or function (RenderMan allows these).
    Function(Box<FunctionDef>),
    /// An expression evaluated for its effect (an assignment or a call).
    Expr(Expr),
    /// `;`.
    Empty,
    /// `if (cond) then else otherwise`.
    If {
        /// The condition, in parentheses.
        cond: Expr,
        /// The statement run when the condition holds.
        then: Box<Stmt>,
        /// The statement after `else`; `None` without an `else`.
        otherwise: Option<Box<Stmt>>,
    },
    /// `while (cond) body`.
    While {
        /// The condition, tested before each iteration.
        cond: Expr,
        /// The loop body.
        body: Box<Stmt>,
    },
    /// `for (init; cond; step) body`.
    For {
        /// The first clause: a [`StmtKind::Decl`] or a [`StmtKind::Expr`]; `None` when empty.
        init: Option<Box<Stmt>>,
        /// The condition tested before each iteration; `None` when empty (loop until `break`).
        cond: Option<Box<Expr>>,
        /// The expression evaluated after each iteration; `None` when empty.
        step: Option<Box<Expr>>,
        /// The loop body.
        body: Box<Stmt>,
    },
    /// `break;` or `break n;` (leave n enclosing loops).
    Break {
        /// The `n` of `break n`, at least 1 (a smaller one is reported and read as 1); `None` for
        /// a plain `break`.
        levels: Option<u32>,
    },
    /// `continue;` or `continue n;`.
    Continue {
        /// The `n` of `continue n`, at least 1 (a smaller one is reported and read as 1); `None`
        /// for a plain `continue`.
        levels: Option<u32>,
    },
    /// `return;` or `return value;`.
    Return(Option<Expr>),
    /// `illuminance([category,] P [, axis, angle]) body`: a loop over the lights reaching P.
    Illuminance {
        /// The arguments as written, any number; the semantic stage checks the form.
        args: Vec<Expr>,
        /// The statement run for each light.
        body: Box<Stmt>,
    },
    /// `illuminate(from [, axis, angle]) body`: a local light's emission.
    Illuminate {
        /// The arguments as written, any number; the semantic stage checks the form.
        args: Vec<Expr>,
        /// The statement that computes `Cl` for the point being lit.
        body: Box<Stmt>,
    },
    /// `solar([axis, angle]) body`: a distant light's emission.
    Solar {
        /// The arguments as written, any number; the semantic stage checks the form.
        args: Vec<Expr>,
        /// The statement that computes `Cl` for the point being lit.
        body: Box<Stmt>,
    },
    /// `gather(...) body else otherwise`: ray tracing, parsed only to be rejected clearly.
    Gather {
        /// The arguments as written.
        args: Vec<Expr>,
        /// The statement for rays that hit.
        body: Box<Stmt>,
        /// The statement after `else`, for rays that miss; `None` without an `else`.
        otherwise: Option<Box<Stmt>>,
    },
    /// A statement that did not parse; its error has been reported.
    Error,
}

/// An expression with its span.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where it is.
    pub span: Span,
}

/// Unary operators.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum UnaryOp {
    /// `-x`.
    Neg,
    /// `+x`.
    Plus,
    /// `!x`.
    Not,
    /// `~x` (integers).
    BitNot,
}

/// Binary operators. `Caret` is cross product on vectors and xor on integers.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum BinaryOp {
    /// `||`: logical or.
    Or,
    /// `&&`: logical and.
    And,
    /// `|`: bitwise or of integers.
    BitOr,
    /// `&`: bitwise and of integers.
    BitAnd,
    /// `==`.
    Eq,
    /// `!=`.
    Ne,
    /// `<`.
    Lt,
    /// `<=`.
    Le,
    /// `>`.
    Gt,
    /// `>=`.
    Ge,
    /// `<<`: shift left (integers).
    Shl,
    /// `>>`: shift right (integers).
    Shr,
    /// `+`.
    Add,
    /// `-`.
    Sub,
    /// `^`: cross product of vectors, exclusive or of integers.
    Caret,
    /// `*`.
    Mul,
    /// `/`.
    Div,
    /// `%`: the remainder of integers.
    Rem,
    /// `.`: dot product.
    Dot,
}

impl BinaryOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        use BinaryOp::*;
        match self {
            Or => "||",
            And => "&&",
            BitOr => "|",
            BitAnd => "&",
            Eq => "==",
            Ne => "!=",
            Lt => "<",
            Le => "<=",
            Gt => ">",
            Ge => ">=",
            Shl => "<<",
            Shr => ">>",
            Add => "+",
            Sub => "-",
            Caret => "^",
            Mul => "*",
            Div => "/",
            Rem => "%",
            Dot => ".",
        }
    }
}

/// `++` or `--`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum StepOp {
    /// `++`.
    Increment,
    /// `--`.
    Decrement,
}

/// The expressions.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// An integer literal; `unsigned` when written with a `u` suffix.
    Int {
        /// The value, up to `u32::MAX`; 0 for a malformed or too large literal, which has been
        /// reported. Whether it is an `int` or a `uint` is for the semantic stage.
        value: u32,
        /// Whether the literal has a `u` or `U` suffix.
        unsigned: bool,
    },
    /// A float literal, as the f64 nearest to what was written.
    Float(f64),
    /// A string literal, escapes replaced.
    String(String),
    /// `true` or `false`.
    Bool(bool),
    /// A variable or constant.
    Name(Ident),
    /// A unary operation.
    Unary {
        /// The operator.
        op: UnaryOp,
        /// What it applies to.
        operand: Box<Expr>,
    },
    /// A binary operation.
    Binary {
        /// The operator.
        op: BinaryOp,
        /// The left operand.
        lhs: Box<Expr>,
        /// The right operand.
        rhs: Box<Expr>,
    },
    /// `target = value`, or `target op= value` when `op` is given.
    Assign {
        /// The operator of a compound assignment (`Add` for `+=`); `None` for `=`.
        op: Option<BinaryOp>,
        /// What is assigned to: any expression, checked by the semantic stage.
        target: Box<Expr>,
        /// The right-hand side.
        value: Box<Expr>,
    },
    /// `++x`, `x++`, `--x`, `x--`.
    Step {
        /// Increment or decrement.
        op: StepOp,
        /// `true` for `++x` and `--x`, `false` for `x++` and `x--`.
        prefix: bool,
        /// What is stepped: any expression, checked by the semantic stage.
        target: Box<Expr>,
    },
    /// `cond ? then : otherwise`.
    Conditional {
        /// The condition, before `?`.
        cond: Box<Expr>,
        /// The value when it holds, between `?` and `:`.
        then: Box<Expr>,
        /// The value when it does not, after `:`.
        otherwise: Box<Expr>,
    },
    /// A call of a function or built-in; message passing (`surface("Kd", x)`) is a call too.
    Call {
        /// The name called (a shader kind's keyword for message passing), with the span of the
        /// name only.
        callee: Ident,
        /// The arguments in order; empty for `f()`.
        args: Vec<Expr>,
    },
    /// `type [space] operand`: a conversion, a constructor (`color (1, 0, 0)`) or an overload choice
    /// (`color noise(P)`), with an optional coordinate or colour space (`point "shader" (0, 0, 0)`).
    Cast {
        /// The type word.
        ty: TypeSpec,
        /// The space's string literal, escapes replaced, with the literal's span; `None` when no
        /// space was written.
        space: Option<(String, Span)>,
        /// The value converted, or the components of the value constructed.
        operand: Box<Expr>,
    },
    /// RenderMan's `(a, b, c)` or sixteen-tuple.
    Tuple(Vec<Expr>),
    /// Stanford's `{a, b, c}`, also array initialisers.
    Braced(Vec<Expr>),
    /// `base[index]`.
    Index {
        /// The indexed expression (any postfix expression, also a string literal in RenderMan's
        /// channel syntax `"map"[1]`).
        base: Box<Expr>,
        /// The index, between the brackets.
        index: Box<Expr>,
    },
    /// An expression that did not parse; its error has been reported.
    Error,
}
