//! The identities of the built-in functions: one [`BuiltinId`] per name of the signature table
//! (`sema/builtins/table.rs`, which gives each its overloads). Every stage after the semantic one
//! dispatches on the id, never on the name, and a stage that must decide something for every
//! built-in (the derivative rule of `opt::derivs`, what each backend emits) matches on it
//! exhaustively, so that a new built-in does not compile until each of them has its case.

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

#[cfg(test)]
mod tests {
    use super::BuiltinId;
    use crate::sema::builtins::builtins;

    #[test]
    fn every_table_name_has_an_id_and_back() {
        let table = builtins();
        for name in table.names() {
            let id = BuiltinId::from_name(name).unwrap_or_else(|| panic!("`{name}` has no BuiltinId"));
            assert_eq!(id.name(), name);
            assert!(table.overloads(name).iter().all(|b| b.id == id), "`{name}`'s overloads carry its id");
        }
        for &id in BuiltinId::ALL {
            assert!(!table.overloads(id.name()).is_empty(), "`{id}` is in no line of the table");
            assert_eq!(BuiltinId::from_name(id.name()), Some(id));
        }
        assert_eq!(table.names().count(), BuiltinId::ALL.len());
        assert_eq!(BuiltinId::from_name("trace"), None);
    }
}
