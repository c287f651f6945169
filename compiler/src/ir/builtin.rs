//! The identities of the built-in functions: one [`BuiltinId`] per name of the signature table
//! (`sema/builtins/table.rs`, which gives each its overloads). Every stage after the semantic one
//! dispatches on the id, never on the name, and a stage that must decide something for every
//! built-in (the derivative rule of `opt::derivs`, what each backend emits) matches on it
//! exhaustively, so that a new built-in does not compile until each of them has its case.
//!
//! [`Builtin`] is one overload, the record a call in the IR points to
//! (`ExprKind::Builtin(&'static Builtin, args)`): its parameter and result types, its [`RateRule`]
//! and its [`Context`]. The IR owns the record; the semantic stage owns the table of them
//! (`sema::builtins::builtins`, parsed from the signature lines) and the overload resolution.

use super::types::Type;

/// Defines [`BuiltinId`] from `Variant = "name"` pairs, with its name table.
macro_rules! builtin_ids {
    ($($variant:ident = $name:literal,)*) => {
        /// A built-in function, by name: all the overloads of that name share it.
        #[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum BuiltinId {
            $(
                #[doc = concat!("`", $name, "`")]
                $variant,
            )*
        }

        impl BuiltinId {
            /// Every built-in, in the order of the signature table.
            pub const ALL: &'static [BuiltinId] = &[$(BuiltinId::$variant,)*];

            /// The name a shader calls it by.
            pub const fn name(self) -> &'static str {
                match self {
                    $(BuiltinId::$variant => $name,)*
                }
            }

            /// The built-in called `name`, if there is one.
            pub fn from_name(name: &str) -> Option<BuiltinId> {
                match name {
                    $($name => Some(BuiltinId::$variant),)*
                    _ => None,
                }
            }
        }
    };
}

builtin_ids! {
    Radians = "radians",
    Degrees = "degrees",
    Sin = "sin",
    Asin = "asin",
    Cos = "cos",
    Acos = "acos",
    Tan = "tan",
    Atan = "atan",
    Pow = "pow",
    Exp = "exp",
    Sqrt = "sqrt",
    InverseSqrt = "inversesqrt",
    Log = "log",
    Mod = "mod",
    Abs = "abs",
    Sign = "sign",
    Min = "min",
    Max = "max",
    Clamp = "clamp",
    Mix = "mix",
    Floor = "floor",
    Ceil = "ceil",
    Round = "round",
    Step = "step",
    SmoothStep = "smoothstep",
    FilterStep = "filterstep",
    Spline = "spline",
    Du = "Du",
    Dv = "Dv",
    Deriv = "Deriv",
    FilterWidth = "filterwidth",
    Random = "random",
    Printf = "printf",
    Format = "format",
    UniformRandom = "__uniform_random",
    Noise = "noise",
    Snoise = "snoise",
    Pnoise = "pnoise",
    Cellnoise = "cellnoise",
    XComp = "xcomp",
    YComp = "ycomp",
    ZComp = "zcomp",
    SetXComp = "setxcomp",
    SetYComp = "setycomp",
    SetZComp = "setzcomp",
    Length = "length",
    Normalize = "normalize",
    Distance = "distance",
    Ptlined = "ptlined",
    Rotate = "rotate",
    Area = "area",
    FaceForward = "faceforward",
    Reflect = "reflect",
    Refract = "refract",
    Fresnel = "fresnel",
    Transform = "transform",
    VTransform = "vtransform",
    NTransform = "ntransform",
    Depth = "depth",
    CalculateNormal = "calculatenormal",
    Comp = "comp",
    SetComp = "setcomp",
    CTransform = "ctransform",
    ColourSpace = "__colour_space",
    Determinant = "determinant",
    Translate = "translate",
    Scale = "scale",
    Concat = "concat",
    Match = "match",
    Ambient = "ambient",
    Diffuse = "diffuse",
    Specular = "specular",
    Phong = "phong",
    SpecularBrdf = "specularbrdf",
    LightSource = "lightsource",
    Surface = "surface",
    Texture = "texture",
    Environment = "environment",
    Shadow = "shadow",
    Texture3d = "texture3d",
    Texel2d = "__texel2d",
    Texel3d = "__texel3d",
    Texsize2d = "__texsize2d",
    Texsize3d = "__texsize3d",
    Dot = "dot",
    Cross = "cross",
    Rgb = "rgb",
    Clamp01 = "clamp01",
    Select = "select",
    Invert = "invert",
    Affine = "affine",
    Transpose = "transpose",
    Integrate = "integrate",
    XyzScreen = "xyz_screen",
}

impl std::fmt::Display for BuiltinId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// How a built-in's result rate follows from its arguments.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum RateRule {
    /// The highest rate among the arguments (most functions).
    Max,
    /// A screen-space derivative: fragment rate when an argument varies per vertex or fragment;
    /// on constant or primitive-group arguments the derivative is exactly 0 at their rate.
    Derivative,
    /// Always at least fragment rate (`random`, screen position).
    Fragment,
    /// Always at least primitive-group rate: one value per draw (`random()` where a uniform value
    /// is wanted, as `__uniform_random`).
    Uniform,
    /// Sums over the bound lights (`ambient`, `diffuse`, `specular`, ...): fragment rate.
    Lights,
    /// `integrate`: the argument's rate without `perlight`.
    Integrate,
}

/// Where a built-in may be called.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Context {
    /// Anywhere.
    Any,
    /// Only in surface shaders (and functions they call).
    Surface,
    /// Only in light shaders.
    Light,
    /// Only in light and volume (atmosphere) shaders: those bound with a surface.
    LightOrVolume,
    /// Only inside `illuminance`, where one light is visited.
    Illuminance,
}

/// A parameter of a built-in.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct BuiltinParam {
    /// Its type (`array: Some(0)` for an array of any length).
    pub ty: Type,
    /// Whether the built-in writes it.
    pub output: bool,
}

/// One overload of a built-in function.
#[derive(Clone, Debug, PartialEq)]
pub struct Builtin {
    /// Which built-in it is (its name).
    pub id: BuiltinId,
    /// The result type.
    pub ret: Type,
    /// The fixed parameters.
    pub params: Vec<BuiltinParam>,
    /// The type of any further arguments, for variadic functions.
    pub rest: Option<Type>,
    /// How the result's rate is decided.
    pub rate: RateRule,
    /// Where it may be called.
    pub context: Context,
    /// The signature as written in the table, for diagnostics.
    pub signature: String,
}

impl Builtin {
    /// Its name.
    pub fn name(&self) -> &'static str {
        self.id.name()
    }

    /// Whether `n` arguments can be passed.
    pub fn accepts_count(&self, n: usize) -> bool {
        if self.rest.is_some() { n >= self.params.len() } else { n == self.params.len() }
    }

    /// The type expected for argument `i`.
    pub fn param_type(&self, i: usize) -> Option<BuiltinParam> {
        self.params.get(i).copied().or_else(|| self.rest.map(|ty| BuiltinParam { ty, output: false }))
    }
}
