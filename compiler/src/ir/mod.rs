//! The typed IR: what the semantic stage produces and every later stage consumes.
//!
//! A [`Shader`] is one body: its parameters, locals and expressions live in arenas indexed by
//! [`LocalId`] and [`ExprId`], and its statements form a tree of [`Block`]s. User functions are
//! already inlined (each call is an [`Stmt::Inline`] block), so every expression has one type, one
//! rate and one span. Expressions are pure; every effect is a statement.

pub mod builtin;
pub mod defaults;
pub mod global;
pub mod stores;
pub mod strings;
pub mod types;

use smol_str::SmolStr;

use crate::source::Span;
use crate::syntax::ast::ShaderKind;
use builtin::{Builtin, RateRule};
use global::Global;
use types::{Frequency, Rate, Type};

/// Index of a local variable (parameters included) in [`Shader::locals`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct LocalId(pub u32);

/// Index of an expression in [`Shader::exprs`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ExprId(pub u32);

/// What a local variable is.
#[derive(Clone, Debug, PartialEq)]
pub enum LocalKind {
    /// A shader parameter, with its default value (evaluated on the host).
    Param {
        /// The default.
        default: Option<ExprId>,
        /// Whether the shader writes it (`output`).
        output: bool,
    },
    /// A variable declared in the body (or a parameter of an inlined function).
    Var,
    /// A temporary the compiler made (results of inlined calls, `x++`).
    Temp,
}

/// A variable.
#[derive(Clone, Debug, PartialEq)]
pub struct Local {
    /// Its name (for temporaries, a description).
    pub name: SmolStr,
    /// Its type.
    pub ty: Type,
    /// Its rate: declared, or inferred from what is stored in it.
    pub rate: Rate,
    /// Whether the rate was declared (a contract) or inferred.
    pub declared: bool,
    /// What it is.
    pub kind: LocalKind,
    /// Where it was declared.
    pub span: Span,
    /// The inlined function it belongs to (its parameters and variables), if any.
    pub function: Option<SmolStr>,
}

/// A literal value.
#[derive(Clone, Debug, PartialEq)]
pub enum Literal {
    /// A float.
    Float(f64),
    /// An `int`.
    Int(i32),
    /// A `uint`.
    Uint(u32),
    /// A `bool`.
    Bool(bool),
    /// A string.
    String(SmolStr),
}

/// Unary operations, resolved for their operand type.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum UnaryOp {
    /// Arithmetic negation.
    Neg,
    /// Logical not (bool).
    Not,
    /// Bitwise complement (int, uint).
    BitNot,
}

/// Binary operations, resolved for their operand types.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum BinaryOp {
    /// `+`, componentwise.
    Add,
    /// `-`, componentwise.
    Sub,
    /// `*`: componentwise, or matrix product when either side is a matrix.
    Mul,
    /// `/`, componentwise.
    Div,
    /// `%` on integers.
    Rem,
    /// `.`: dot product.
    Dot,
    /// `^` on vectors: cross product.
    Cross,
    /// `^` on integers: exclusive or.
    BitXor,
    /// `&` on integers.
    BitAnd,
    /// `|` on integers.
    BitOr,
    /// `<<` on integers.
    Shl,
    /// `>>` on integers.
    Shr,
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
    /// `&&` (both sides are evaluated; they have no effects).
    And,
    /// `||`.
    Or,
}

/// A shader input whose screen-space derivatives are supplied from outside the program: on the GPU
/// `dpdx`/`dpdy` taken at the top of the fragment stage, on the CPU the rasterizer's (or the
/// caller's) gradients. Derivatives of everything else follow from these by the chain rule
/// (`opt::derivs`).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Input {
    /// A predefined variable (`P`, `s`, `u`, ...).
    Global(&'static Global),
    /// A parameter (a `varying` or `vertex` one: interpolated per fragment).
    Param(LocalId),
}

/// A screen axis.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Axis {
    /// Along the raster x axis (one pixel to the right).
    X,
    /// Along the raster y axis (one pixel down).
    Y,
}

/// The expressions.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// A literal.
    Literal(Literal),
    /// The value of a local.
    Local(LocalId),
    /// The value of a predefined variable.
    Global(&'static Global),
    /// A unary operation.
    Unary(UnaryOp, ExprId),
    /// A binary operation.
    Binary(BinaryOp, ExprId, ExprId),
    /// The operand converted to this expression's type (float to color by duplication, int to
    /// float, point to vector, ...).
    Convert(ExprId),
    /// A value of this expression's type built from components (vectors, matrices, arrays).
    Construct(Vec<ExprId>),
    /// A point, vector, normal, colour or matrix given in a named space, converted to "current".
    FromSpace {
        /// The space it was written in (`"shader"`, `"hsv"`, ...).
        space: SmolStr,
        /// The value in that space.
        value: ExprId,
    },
    /// An element of an array or a component of a vector or matrix row.
    Index(ExprId, ExprId),
    /// `cond ? a : b` (both sides are evaluated; they have no effects).
    Select(ExprId, ExprId, ExprId),
    /// A built-in function; `output` arguments are locals written by the call.
    Builtin(&'static Builtin, Vec<ExprId>),
    /// The derivative of an input along a screen axis, as supplied from outside (made by
    /// `opt::derivs`, never by the semantic stage). Its type is the input's, with `point` read as
    /// `vector`.
    Seed(Input, Axis),
    /// The sum of `value` evaluated for each of the bound lights `lights` in turn (zero for
    /// none): `ambient()` and Stanford's `integrate` over the lights they sum, made by
    /// `opt::lights`, never by the semantic stage. Inside it, the per-light variables (`L`, `Cl`,
    /// `Ol`, per-light locals) are the visited light's.
    LightSum {
        /// The bound lights, by index in the binding.
        lights: Vec<u32>,
        /// The per-light value.
        value: ExprId,
    },
}

impl ExprKind {
    /// Calls `f` with each operand, in order (a built-in's `output` arguments included).
    pub fn for_each_operand(&self, mut f: impl FnMut(ExprId)) {
        match self {
            ExprKind::Literal(_) | ExprKind::Local(_) | ExprKind::Global(_) | ExprKind::Seed(..) => {}
            ExprKind::Unary(_, a)
            | ExprKind::Convert(a)
            | ExprKind::FromSpace { value: a, .. }
            | ExprKind::LightSum { value: a, .. } => f(*a),
            ExprKind::Binary(_, a, b) | ExprKind::Index(a, b) => {
                f(*a);
                f(*b);
            }
            ExprKind::Select(c, a, b) => {
                f(*c);
                f(*a);
                f(*b);
            }
            ExprKind::Construct(parts) | ExprKind::Builtin(_, parts) => parts.iter().copied().for_each(f),
        }
    }
}

/// An expression with its type, rate and span.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What it computes.
    pub kind: ExprKind,
    /// Its type.
    pub ty: Type,
    /// How often it is computed.
    pub rate: Rate,
    /// Where it was written (for an inlined function, inside the function).
    pub span: Span,
}

/// Where a store writes.
#[derive(Clone, Debug, PartialEq)]
pub enum Place {
    /// A local (or a parameter).
    Local(LocalId),
    /// A writable predefined variable (`Ci`, `P`, ...).
    Global(&'static Global),
    /// One element or component of a place.
    Index(Box<Place>, ExprId),
}

impl Place {
    /// The local this place is (a part of), if it is not a predefined variable.
    pub fn root_local(&self) -> Option<LocalId> {
        match self {
            Place::Local(l) => Some(*l),
            Place::Global(_) => None,
            Place::Index(inner, _) => inner.root_local(),
        }
    }

    /// The predefined variable this place is (a part of), if it is one.
    pub fn root_global(&self) -> Option<&'static Global> {
        match self {
            Place::Local(_) => None,
            Place::Global(g) => Some(g),
            Place::Index(inner, _) => inner.root_global(),
        }
    }
}

/// A sequence of statements.
pub type Block = Vec<Stmt>;

/// The statements.
#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    /// Evaluate for the outputs of a built-in.
    Eval(ExprId),
    /// Store a value.
    Store {
        /// Where.
        place: Place,
        /// What.
        value: ExprId,
        /// The assignment in the source.
        span: Span,
    },
    /// Two-way branch.
    If {
        /// The condition (bool).
        cond: ExprId,
        /// Taken when true.
        then: Block,
        /// Taken when false.
        otherwise: Block,
    },
    /// A loop: `while (cond) { body; step }`; `continue` runs `step`.
    Loop {
        /// Tested before each iteration; `None` loops until `break`.
        cond: Option<ExprId>,
        /// The body.
        body: Block,
        /// Run after the body and after `continue` (a `for` loop's third clause).
        step: Block,
        /// The loop in the source, for iteration-budget diagnostics.
        span: Span,
    },
    /// Leave `levels` enclosing loops.
    Break(u32),
    /// Go to the next iteration of the loop `levels` out.
    Continue(u32),
    /// Leave the enclosing inlined function (with its result stored first) or the shader.
    Return,
    /// An inlined call: the body of a user function, left by `Return`.
    Inline {
        /// The function's name.
        function: SmolStr,
        /// The body, with parameters already stored.
        body: Block,
        /// The call in the source.
        span: Span,
    },
    /// `illuminance`: run `body` once per bound light that passes the test in `args`.
    Illuminance {
        /// Category (optional), position, and optional axis and angle.
        args: Vec<ExprId>,
        /// The per-light body.
        body: Block,
    },
    /// `illuminate` (local light) or `solar` (distant light): the light's emission.
    Emit {
        /// Whether this is `solar`.
        solar: bool,
        /// Position or axis, and optional cone.
        args: Vec<ExprId>,
        /// The body that sets `Cl`.
        body: Block,
    },
    /// `body` run once for each of the bound lights `lights`, in order, with the per-light
    /// variables (`L`, `Cl`, `Ol`, per-light locals) and per-light expressions the visited
    /// light's: what `illuminance` and Stanford per-light statements become in `opt::lights`,
    /// never made by the semantic stage.
    Lights {
        /// The bound lights, by index in the binding.
        lights: Vec<u32>,
        /// The per-light body.
        body: Block,
    },
}

impl Stmt {
    /// Calls `f` with each block nested directly in this statement, in order (both sides of an
    /// `if`, a loop's body then its step, the body of an inlined call or a light construct).
    pub fn for_each_block(&self, mut f: impl FnMut(&Block)) {
        match self {
            Stmt::If { then, otherwise, .. } => {
                f(then);
                f(otherwise);
            }
            Stmt::Loop { body, step, .. } => {
                f(body);
                f(step);
            }
            Stmt::Inline { body, .. }
            | Stmt::Illuminance { body, .. }
            | Stmt::Emit { body, .. }
            | Stmt::Lights { body, .. } => f(body),
            Stmt::Eval(_) | Stmt::Store { .. } | Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => {}
        }
    }

    /// Calls `f` with each expression the statement evaluates itself, its nested blocks aside (a
    /// store's value and the indices of its place, a condition, a construct's arguments).
    pub fn for_each_root(&self, mut f: impl FnMut(ExprId)) {
        match self {
            Stmt::Eval(e) => f(*e),
            Stmt::Store { place, value, .. } => {
                f(*value);
                let mut at = place;
                while let Place::Index(inner, index) = at {
                    f(*index);
                    at = inner;
                }
            }
            Stmt::If { cond, .. } => f(*cond),
            Stmt::Loop { cond, .. } => cond.iter().copied().for_each(f),
            Stmt::Illuminance { args, .. } | Stmt::Emit { args, .. } => args.iter().copied().for_each(f),
            Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return | Stmt::Inline { .. } | Stmt::Lights { .. } => {
            }
        }
    }

    /// [`Stmt::for_each_block`] for rewriting: `f` may change each nested block.
    pub fn for_each_block_mut(&mut self, mut f: impl FnMut(&mut Block)) {
        match self {
            Stmt::If { then, otherwise, .. } => {
                f(then);
                f(otherwise);
            }
            Stmt::Loop { body, step, .. } => {
                f(body);
                f(step);
            }
            Stmt::Inline { body, .. }
            | Stmt::Illuminance { body, .. }
            | Stmt::Emit { body, .. }
            | Stmt::Lights { body, .. } => f(body),
            Stmt::Eval(_) | Stmt::Store { .. } | Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => {}
        }
    }
}

/// A checked shader, with every function it calls inlined.
#[derive(Clone, Debug, PartialEq)]
pub struct Shader {
    /// Its name.
    pub name: SmolStr,
    /// Surface, light, ...
    pub kind: ShaderKind,
    /// Whether it is written in Stanford style.
    pub stanford: bool,
    /// Stanford shaders return a value of this type; RenderMan shaders return `void`.
    pub result: Type,
    /// For Stanford shaders, the local holding the returned value.
    pub result_local: Option<LocalId>,
    /// The parameters, in order (they are also in `locals`).
    pub params: Vec<LocalId>,
    /// Every variable.
    pub locals: Vec<Local>,
    /// Every expression.
    pub exprs: Vec<Expr>,
    /// The body.
    pub body: Block,
    /// The definition in the source.
    pub span: Span,
}

impl Shader {
    /// The expression `id`.
    pub fn expr(&self, id: ExprId) -> &Expr {
        &self.exprs[id.0 as usize]
    }

    /// The local `id`.
    pub fn local(&self, id: LocalId) -> &Local {
        &self.locals[id.0 as usize]
    }

    /// Adds the locals expression `id` reads (through any of its operands) to `out`.
    pub fn add_reads(&self, id: ExprId, out: &mut rustc_hash::FxHashSet<LocalId>) {
        let kind = &self.expr(id).kind;
        if let ExprKind::Local(l) = kind {
            out.insert(*l);
        }
        kind.for_each_operand(|a| self.add_reads(a, out));
    }

    /// The type of what `place` stores into: its variable's, narrowed by each index.
    pub fn place_type(&self, place: &Place) -> Type {
        match place {
            Place::Local(l) => self.local(*l).ty,
            Place::Global(g) => Type::of(g.ty),
            Place::Index(inner, _) => self.place_type(inner).element(),
        }
    }

    /// Whether `place` is a per-light variable or an element of one.
    pub fn place_perlight(&self, mut place: &Place) -> bool {
        loop {
            match place {
                Place::Local(l) => return self.local(*l).rate.perlight,
                Place::Global(g) => return g.perlight,
                Place::Index(inner, _) => place = inner,
            }
        }
    }

    /// Whether a statement computes a per-light value itself (Stanford style): it stores into or
    /// a per-light value, or decides on one (its nested statements aside).
    pub fn computes_perlight(&self, stmt: &Stmt) -> bool {
        let perlight = |id: &ExprId| self.expr(*id).rate.perlight;
        match stmt {
            Stmt::Store { place, value, .. } => self.place_perlight(place) || perlight(value),
            Stmt::Eval(id) => perlight(id),
            Stmt::If { cond, .. } => perlight(cond),
            Stmt::Loop { cond, .. } => cond.as_ref().is_some_and(perlight),
            _ => false,
        }
    }

    /// The rate an expression of this kind has in this shader, from its operands' rates, by the
    /// rules of `sema::rates` (for builders of new expressions, `opt::build`, and for `verify` to
    /// check the rates pass).
    pub fn rate_of(&self, kind: &ExprKind) -> Rate {
        let rate = |id: ExprId| self.expr(id).rate;
        let join = |ids: &[ExprId]| ids.iter().fold(Rate::CONSTANT, |r, &id| r.join(rate(id)));
        match kind {
            ExprKind::Literal(_) => Rate::CONSTANT,
            ExprKind::Seed(..) => Rate::FRAGMENT,
            ExprKind::Local(l) => self.local(*l).rate,
            ExprKind::Global(g) => Rate { frequency: g.frequency, perlight: g.perlight },
            ExprKind::Unary(_, a) | ExprKind::Convert(a) => rate(*a),
            ExprKind::Binary(_, a, b) | ExprKind::Index(a, b) => join(&[*a, *b]),
            ExprKind::Select(c, a, b) => join(&[*c, *a, *b]),
            ExprKind::Construct(parts) => join(parts),
            ExprKind::FromSpace { space, value } if space != "current" => rate(*value).join(Rate::UNIFORM),
            ExprKind::FromSpace { value, .. } => rate(*value),
            ExprKind::LightSum { value, .. } => Rate { perlight: false, ..rate(*value) },
            ExprKind::Builtin(b, args) => {
                let rate = join(args);
                match b.rate {
                    RateRule::Max => rate,
                    RateRule::Derivative if rate.frequency >= Frequency::Vertex => {
                        Rate { frequency: Frequency::Fragment, ..rate }
                    }
                    RateRule::Derivative => rate,
                    RateRule::Fragment | RateRule::Lights => rate.join(Rate::FRAGMENT),
                    RateRule::Uniform => rate.join(Rate::UNIFORM),
                    RateRule::Integrate => Rate { perlight: false, ..rate },
                }
            }
        }
    }
}

/// Whether a light shader is ambient: a RenderMan-style light with no `illuminate` or `solar`
/// (RenderMan's rule). A Stanford-style light is never ambient: it has a position (the scene's),
/// and its `L` points to it.
pub fn is_ambient(light: &Shader) -> bool {
    fn emits(block: &[Stmt]) -> bool {
        block.iter().any(|s| match s {
            Stmt::Emit { .. } => true,
            Stmt::If { then, otherwise, .. } => emits(then) || emits(otherwise),
            Stmt::Loop { body, step, .. } => emits(body) || emits(step),
            Stmt::Inline { body, .. } | Stmt::Illuminance { body, .. } | Stmt::Lights { body, .. } => {
                emits(body)
            }
            _ => false,
        })
    }
    !light.stanford && !emits(&light.body)
}

/// The checked program: every shader of a source file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Program {
    /// The shaders, in source order.
    pub shaders: Vec<Shader>,
}
