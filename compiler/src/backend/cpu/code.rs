//! The interpreter's instruction form: the typed IR scalarized into operations on registers.
//!
//! Every value is split into scalar components, each held in a register of one of two files: floats
//! (`f32` or `f64`, the interpreter's mode) and integers (`int`, `uint` and `bool` as 32-bit words;
//! `bool` is 0 or 1). A register is either *varying* (one lane per shading point of a batch) or
//! *uniform* (one value for the whole batch): values of rate constant or primitive group are stored
//! once. An instruction whose operands are all uniform computes once; otherwise it computes every
//! lane, whatever the execution mask, because its result is a temporary and garbage in inactive lanes
//! is never stored. Only [`Inst::Move`] and [`Inst::Scatter`], the stores into variables, honour the
//! mask. Control flow stays structured ([`Node`]), the shape the mask discipline needs.
//!
//! Code is precision-independent: the same [`Code`] runs in f32 and in f64.

use crate::source::Span;

/// A register: an index into the float or the integer file (which one is implied by the
/// instruction), and whether it is uniform.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct Reg {
    /// Index in the uniform or varying part of its file.
    pub index: u32,
    /// Whether it holds one value for the whole batch.
    pub uniform: bool,
}

impl Reg {
    /// A varying register.
    pub const fn varying(index: u32) -> Reg {
        Reg { index, uniform: false }
    }

    /// A uniform register.
    pub const fn uniform(index: u32) -> Reg {
        Reg { index, uniform: true }
    }
}

/// Float operations of one operand.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Unary {
    /// `-x`.
    Neg,
    /// `|x|`.
    Abs,
    /// Round toward negative infinity.
    Floor,
    /// Round toward positive infinity.
    Ceil,
    /// Round toward zero.
    Trunc,
    /// Round to nearest, ties to even.
    Round,
    /// `x - floor(x)`.
    Fract,
    /// -1, 0 or 1.
    Sign,
    /// Square root.
    Sqrt,
    /// `1 / sqrt(x)`.
    InverseSqrt,
    /// Sine.
    Sin,
    /// Cosine.
    Cos,
    /// Tangent.
    Tan,
    /// Arcsine.
    Asin,
    /// Arccosine.
    Acos,
    /// Arctangent.
    Atan,
    /// `e^x`.
    Exp,
    /// Natural logarithm.
    Log,
}

/// Float operations of two operands.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Binary {
    /// `a + b`.
    Add,
    /// `a - b`.
    Sub,
    /// `a * b`.
    Mul,
    /// `a / b`.
    Div,
    /// The smaller (the non-NaN one).
    Min,
    /// The larger (the non-NaN one).
    Max,
    /// `a^b`.
    Pow,
    /// `atan2(a, b)`.
    Atan2,
    /// RenderMan `mod`: `a - b * floor(a / b)`.
    Mod,
    /// `step(a, b)`: `b >= a ? 1 : 0`.
    Step,
}

/// Float operations of three operands.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Ternary {
    /// `mix(a, b, t)`.
    Mix,
    /// `clamp(x, lo, hi)`.
    Clamp,
    /// `smoothstep(lo, hi, x)`.
    Smoothstep,
}

/// Comparisons, for floats and integers.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Compare {
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
}

/// Integer operations of one operand.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum IntUnary {
    /// Wrapping `-x`.
    Neg,
    /// Bitwise complement.
    Not,
    /// Logical not of a bool (0 or 1).
    LogicalNot,
    /// `|x|` of an `int` (wrapping: `abs(MIN) = MIN`).
    Abs,
}

/// Integer operations of two operands. Signed and unsigned forms differ where the result does.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum IntBinary {
    /// Wrapping `+`.
    Add,
    /// Wrapping `-`.
    Sub,
    /// Wrapping `*`.
    Mul,
    /// `int` division (`x / 0 = x`).
    DivI,
    /// `uint` division.
    DivU,
    /// `int` remainder (`x % 0 = 0`).
    RemI,
    /// `uint` remainder.
    RemU,
    /// `&` (also logical and of bools).
    And,
    /// `|` (also logical or of bools).
    Or,
    /// `^`.
    Xor,
    /// `<<`, amount modulo 32.
    Shl,
    /// Arithmetic `>>`.
    ShrI,
    /// Logical `>>`.
    ShrU,
    /// Signed minimum.
    MinI,
    /// Unsigned minimum.
    MinU,
    /// Signed maximum.
    MaxI,
    /// Unsigned maximum.
    MaxU,
}

/// Conversions between the files.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Convert {
    /// Float to `int`, saturating, NaN to 0.
    FloatToInt,
    /// Float to `uint`, saturating, NaN to 0.
    FloatToUint,
    /// `int` to float.
    IntToFloat,
    /// `uint` (and bool) to float.
    UintToFloat,
    /// Float to bool: `x != 0`.
    FloatToBool,
}

/// One instruction. Float registers are in the float file, `int`/`uint`/`bool` ones in the integer
/// file; `dst` is uniform exactly when every operand is.
#[derive(Clone, Debug, PartialEq)]
pub enum Inst {
    /// Float `dst = op(a)`.
    Unary {
        /// The operation.
        op: Unary,
        /// The result (float file).
        dst: Reg,
        /// The operand (float file).
        a: Reg,
    },
    /// Float `dst = op(a, b)`.
    Binary {
        /// The operation.
        op: Binary,
        /// The result (float file).
        dst: Reg,
        /// The first operand (float file).
        a: Reg,
        /// The second operand (float file).
        b: Reg,
    },
    /// Float `dst = op(a, b, c)`.
    Ternary {
        /// The operation.
        op: Ternary,
        /// The result (float file).
        dst: Reg,
        /// The first operand (float file): `mix`'s `a`, `clamp`'s `x`, `smoothstep`'s `lo`.
        a: Reg,
        /// The second operand (float file): `mix`'s `b`, `clamp`'s `lo`, `smoothstep`'s `hi`.
        b: Reg,
        /// The third operand (float file): `mix`'s `t`, `clamp`'s `hi`, `smoothstep`'s `x`.
        c: Reg,
    },
    /// Integer-file `dst = a op b` of two floats (1 or 0).
    Compare {
        /// The comparison; any comparison with a NaN is false except `!=`.
        op: Compare,
        /// The result (integer file): 1 where the comparison holds, else 0.
        dst: Reg,
        /// The left operand (float file).
        a: Reg,
        /// The right operand (float file).
        b: Reg,
    },
    /// Integer `dst = op(a)`.
    IntUnary {
        /// The operation.
        op: IntUnary,
        /// The result (integer file).
        dst: Reg,
        /// The operand (integer file).
        a: Reg,
    },
    /// Integer `dst = op(a, b)`.
    IntBinary {
        /// The operation (its signedness chosen by the lowering).
        op: IntBinary,
        /// The result (integer file).
        dst: Reg,
        /// The first operand (integer file).
        a: Reg,
        /// The second operand (integer file): the divisor, or the shift amount.
        b: Reg,
    },
    /// `dst = a op b` of two integers (1 or 0), signed or unsigned.
    IntCompare {
        /// The comparison.
        op: Compare,
        /// Whether the operands are read as `int` (`true`) or as `uint`.
        signed: bool,
        /// The result (integer file): 1 where the comparison holds, else 0.
        dst: Reg,
        /// The left operand (integer file).
        a: Reg,
        /// The right operand (integer file).
        b: Reg,
    },
    /// A conversion between the files (or within the float file, for `FloatToBool`'s source).
    Convert {
        /// The conversion, which names the files of `dst` and `a`.
        op: Convert,
        /// The result: integer file for `FloatTo*`, float file for `*ToFloat`.
        dst: Reg,
        /// The operand: float file for `FloatTo*`, integer file for `*ToFloat`.
        a: Reg,
    },
    /// `dst = cond ? a : b` (`cond` in the integer file), in the float file or the integer file.
    Select {
        /// Whether `dst`, `a` and `b` are in the float file (else the integer file).
        float: bool,
        /// The result; every lane is written, whatever the execution mask.
        dst: Reg,
        /// The condition (integer file): non-zero picks `a`. Never `dst` itself.
        cond: Reg,
        /// The value where `cond` is non-zero.
        a: Reg,
        /// The value where `cond` is zero.
        b: Reg,
    },
    /// A store into a variable: `dst = src` in the lanes of the execution mask.
    Move {
        /// Whether both registers are in the float file (else the integer file).
        float: bool,
        /// The variable's register; a uniform one is only stored under uniform control, from a
        /// uniform `src`, and is written whole.
        dst: Reg,
        /// The value stored.
        src: Reg,
    },
    /// `dst = array[clamp(index, 0, len - 1)]`: registers `base + i * stride` for `i` in `0..len`
    /// hold the elements (of one component); `index` is an `int` (`signed`) or a `uint`.
    Gather {
        /// Whether `dst` and the elements are in the float file (else the integer file).
        float: bool,
        /// The result; uniform exactly when `base` and `index` are.
        dst: Reg,
        /// The register of element 0's component: every element's register is uniform or varying
        /// as this one is.
        base: Reg,
        /// The number of elements.
        len: u32,
        /// The registers from one element to the next (the element's component count, or 1 for
        /// an index already flattened over nested arrays).
        stride: u32,
        /// The element index (integer file), clamped into `0..len`; may vary per lane.
        index: Reg,
        /// Whether `index` is an `int` (a negative one clamps to 0) or a `uint`.
        signed: bool,
    },
    /// `array[clamp(index, 0, len - 1)] = src` in the lanes of the execution mask.
    Scatter {
        /// Whether `src` and the elements are in the float file (else the integer file).
        float: bool,
        /// The register of element 0's component, as in [`Inst::Gather`]. When it is uniform,
        /// `index` and `src` are too and the store is made once, unmasked (uniform variables are
        /// stored under uniform control only).
        base: Reg,
        /// The number of elements.
        len: u32,
        /// The registers from one element to the next, as in [`Inst::Gather`].
        stride: u32,
        /// The element index (integer file), clamped into `0..len`; each lane of the execution mask
        /// stores into the element its own index names.
        index: Reg,
        /// Whether `index` is an `int` (a negative one clamps to 0) or a `uint`.
        signed: bool,
        /// The value stored.
        src: Reg,
    },
    /// `dst` = a uniformly distributed float in [0, 1), a hash of `point` (integer file: the
    /// point's index, unless the caller gives another) and `site`.
    Random {
        /// The result (float file), always varying.
        dst: Reg,
        /// A number distinct for each `random()` call in the program, so calls differ.
        site: u32,
        /// The point's index (integer file), or another value the caller hashes instead.
        point: Reg,
    },
    /// `dst` = channel `channel` of texel (x, y, z) of texture `texture` (coordinates in the
    /// integer file, clamped into range).
    Texel {
        /// The texture: an index into [`Code::textures`]; a texture the machine lacks reads as 0.
        texture: u32,
        /// The channel read, 0 to 3 (red, green, blue, alpha).
        channel: u8,
        /// The result (float file); uniform when the coordinates are.
        dst: Reg,
        /// The column (integer file, read as `int`), clamped into the texture.
        x: Reg,
        /// The row (integer file, read as `int`), clamped into the texture.
        y: Reg,
        /// The layer of a 3D texture (integer file, read as `int`), clamped into the texture.
        z: Reg,
    },
    /// `dst` (integer file, uniform) = the size of texture `texture` along `axis`.
    TexSize {
        /// The texture: an index into [`Code::textures`]; a missing one has size 1.
        texture: u32,
        /// 0 for the width, 1 for the height, 2 for the depth (at least 1 each).
        axis: u8,
        /// The result (integer file), always uniform.
        dst: Reg,
    },
    /// `printf`: in each lane of the execution mask, `format` with the lane's values, one line on
    /// stderr (`exec::print_line` limits how many).
    Printf {
        /// The format string, with its `%` conversions.
        format: String,
        /// The values for the conversions, in order.
        args: Vec<PrintArg>,
    },
}

/// One value of a `printf`.
#[derive(Clone, Debug, PartialEq)]
pub enum PrintArg {
    /// A string, known when the program was compiled.
    Text(String),
    /// Components in the float file.
    Floats(Vec<Reg>),
    /// Components in the integer file, read as signed integers or not.
    Ints(Vec<Reg>, bool),
}

/// Structured control flow over instructions.
#[derive(Clone, Debug, PartialEq)]
pub enum Node {
    /// One instruction.
    Inst(Inst),
    /// Run `then` in the lanes where `cond` (integer file) is non-zero, `otherwise` in the rest.
    If {
        /// The condition (integer file); a branch no lane takes is skipped.
        cond: Reg,
        /// Run with the mask narrowed to the lanes where `cond` is non-zero.
        then: Vec<Node>,
        /// Run with the mask narrowed to the rest; empty without an `else`.
        otherwise: Vec<Node>,
    },
    /// Repeat: run `test` and leave the lanes where `cond` is zero, then `body`, then `step`.
    Loop {
        /// Computes the condition (empty with `cond: None`).
        test: Vec<Node>,
        /// The condition register; `None` loops until every lane has left by `break` or `return`.
        cond: Option<Reg>,
        /// The body.
        body: Vec<Node>,
        /// Run after the body and after `continue`.
        step: Vec<Node>,
        /// The loop in the source, for the iteration-budget diagnostic.
        span: Span,
    },
    /// Leave this many enclosing loops (in the current function).
    Break(u32),
    /// Go on with the next iteration of the loop this many levels out.
    Continue(u32),
    /// Leave the current function (or the shader).
    Return,
    /// An inlined function body: the target of `Return`.
    Function(Vec<Node>),
}

/// The sizes of the register files.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct Files {
    /// Uniform float registers.
    pub uniform_floats: u32,
    /// Varying float registers.
    pub varying_floats: u32,
    /// Uniform integer registers.
    pub uniform_ints: u32,
    /// Varying integer registers.
    pub varying_ints: u32,
}

/// A compiled program: constants to load once, and the code to run per batch.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Code {
    /// Register file sizes.
    pub files: Files,
    /// Uniform float registers holding constants, with their values.
    pub float_constants: Vec<(u32, f64)>,
    /// Uniform integer registers holding constants, with their values.
    pub int_constants: Vec<(u32, u32)>,
    /// The body, run once per batch of points.
    pub body: Vec<Node>,
    /// The textures the code reads, by name, in the order `Inst::Texel` numbers them.
    pub textures: Vec<String>,
}

impl Code {
    /// The number of instructions, counted statically (for `patina explain` and tests).
    pub fn instruction_count(&self) -> usize {
        fn count(nodes: &[Node]) -> usize {
            nodes
                .iter()
                .map(|n| match n {
                    Node::Inst(_) => 1,
                    Node::If { then, otherwise, .. } => 1 + count(then) + count(otherwise),
                    Node::Loop { test, body, step, .. } => 1 + count(test) + count(body) + count(step),
                    Node::Function(body) => count(body),
                    Node::Break(_) | Node::Continue(_) | Node::Return => 1,
                })
                .sum()
        }
        count(&self.body)
    }
}
