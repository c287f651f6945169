//! The interface of a compiled GPU program, as data: everything a user's wgpu code (or the
//! runtime) must bind and fill to draw with the module. `patina compile` writes it as JSON
//! (`docs/interface.md` is the schema, [`INTERFACE_VERSION`] its version).
//!
//! Conventions, which every field below follows:
//! - Group 0, binding 0 is the uniform block (a `var<uniform>` of the struct named
//!   [`Interface::uniform_struct`]), visible to both stages. Group 1, binding `k` is texture `k`
//!   (`texture_2d<f32>` or `texture_3d<f32>`, read with `textureLoad`: no sampler, and the texture
//!   need not be filterable). Nothing else is bound.
//! - Matrices are 16 (or 9) floats in the layout of `glam::Mat4::to_cols_array`: read by the
//!   language as a matrix written row by row whose rows are those columns, which is RenderMan's
//!   row-vector convention (`p' = p · M`). A 3x3 matrix occupies three 16-byte columns.
//! - Points, vectors and normals are in "current" space, which is camera space: the eye at the
//!   origin looking down +z, x to the right, y up (left-handed, as RenderMan's camera space).
//! - The fragment entry point writes one `vec4f` at `@location(0)` with premultiplied alpha
//!   (RenderMan's `Ci` is already multiplied by `Oi`): blend it with premultiplied "over".

use serde::{Deserialize, Serialize};

/// The version of the interface's JSON form; it changes whenever a field changes meaning.
pub const INTERFACE_VERSION: u32 = 3;

/// Where the value of a uniform field comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
#[non_exhaustive]
pub enum UniformSource {
    /// A parameter of the surface shader (its value, or its default, as the host computes it).
    Param {
        /// The parameter.
        name: String,
    },
    /// A value the host program computes: read the host stage's output of this name.
    Host {
        /// The output parameter of the host stage.
        name: String,
    },
    /// A predefined variable of uniform rate (`E`, `time`, `Cs`, `__modelview`, ...).
    Global {
        /// Its name.
        name: String,
    },
    /// The matrix from "current" space to a named space (`inverse`: back to current).
    Space {
        /// The space (`world`, `object`, `shader`, `screen`, ...).
        name: String,
        /// Whether this is the matrix back to current space.
        inverse: bool,
        /// The bound light whose space this is (`None`: the surface's).
        light: Option<usize>,
    },
    /// A parameter of a bound light shader.
    LightParam {
        /// The light's position in the binding.
        light: usize,
        /// The parameter.
        name: String,
    },
    /// The position of a bound Stanford-style light, in camera ("current") space: the host's
    /// light position (OpenGL's), from which the fragment stage computes the light's `L` and
    /// `Sdist` at each surface point.
    LightPosition {
        /// The light's position in the binding.
        light: usize,
    },
    /// A parameter of the bound displacement shader.
    DisplacementParam {
        /// The parameter.
        name: String,
    },
    /// A parameter of the bound atmosphere (volume) shader.
    AtmosphereParam {
        /// The parameter.
        name: String,
    },
    /// A matrix the vertex stage's geometry needs (column-vector convention, `v' = M v`).
    Geometry {
        /// Which.
        matrix: GeometryMatrix,
    },
    /// A constant table of the program (a noise's permutation or gradients): always `values`,
    /// element by element. It lives in the block because a driver compiles indexed reads of a
    /// buffer far faster than of a module variable (docs/performance.md);
    /// [`Interface::blank_block`] writes every one.
    Table {
        /// The elements.
        values: Vec<f64>,
    },
}

/// The matrices the vertex stage uses to place geometry.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum GeometryMatrix {
    /// Object space to camera ("current") space.
    ObjectToCamera,
    /// Normals from object to camera space (inverse transpose of the above).
    NormalToCamera,
    /// Camera space to wgpu clip space.
    CameraToClip,
}

/// One member of the uniform block.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct UniformField {
    /// The member's name in the WGSL text (as naga's writer spells it).
    pub name: String,
    /// Where its value comes from.
    pub source: UniformSource,
    /// The language type (`float`, `color`, `matrix`, `float[4]`, ...).
    pub ty: String,
    /// Byte offset in the block.
    pub offset: u32,
    /// How the values are laid out from the offset.
    pub layout: FieldLayout,
}

/// The scalar type a field's components are stored as.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum ScalarKind {
    /// 32-bit float.
    F32,
    /// 32-bit signed integer.
    I32,
    /// 32-bit unsigned integer (booleans: 0 or 1).
    U32,
}

/// How a field's components are stored.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FieldLayout {
    /// Components per element (1, 3, 4, 9 or 16).
    pub components: u32,
    /// Elements (1 for non-arrays).
    pub elements: u32,
    /// Bytes from one element to the next.
    pub element_stride: u32,
    /// For 3x3 matrices, bytes between columns (16); otherwise 0.
    pub column_stride: u32,
    /// The scalar type.
    pub scalar: ScalarKind,
}

impl FieldLayout {
    /// The bytes this field spans from its offset.
    pub fn size(&self) -> u32 {
        let last = if self.column_stride > 0 {
            (self.components / 3 - 1) * self.column_stride + 12
        } else {
            self.components * 4
        };
        (self.elements.max(1) - 1) * self.element_stride + last
    }
}

impl UniformField {
    /// Writes `values` (the language's component order: element by element, matrices as
    /// `to_cols_array`) into `block` at this field's place. Missing trailing values leave their
    /// bytes as they were; extra values are ignored. Integer fields take values or their unsigned
    /// bit patterns (the interpreter's outputs): both wrap to the same 32 bits.
    pub fn write(&self, block: &mut [u8], values: &[f64]) {
        let l = &self.layout;
        let per = l.components as usize;
        for e in 0..l.elements as usize {
            for c in 0..per {
                let Some(x) = values.get(e * per + c) else { continue };
                // A 3x3 matrix is three 16-byte columns, each holding one row of the language's.
                let within = if l.column_stride > 0 {
                    (c / 3) as u32 * l.column_stride + (c % 3) as u32 * 4
                } else {
                    c as u32 * 4
                };
                let at = (self.offset + e as u32 * l.element_stride + within) as usize;
                let word: [u8; 4] = match l.scalar {
                    ScalarKind::I32 | ScalarKind::U32 => (*x as i64 as u32).to_le_bytes(),
                    ScalarKind::F32 => (*x as f32).to_le_bytes(),
                };
                if let Some(slot) = block.get_mut(at..at + 4) {
                    slot.copy_from_slice(&word);
                }
            }
        }
    }

    /// Reads this field back from `block`, in the order [`UniformField::write`] takes.
    pub fn read(&self, block: &[u8]) -> Vec<f64> {
        let l = &self.layout;
        let mut out = Vec::with_capacity((l.components * l.elements) as usize);
        for e in 0..l.elements {
            for c in 0..l.components {
                let within =
                    if l.column_stride > 0 { (c / 3) * l.column_stride + (c % 3) * 4 } else { c * 4 };
                let at = (self.offset + e * l.element_stride + within) as usize;
                let word = block.get(at..at + 4).map_or([0; 4], |w| [w[0], w[1], w[2], w[3]]);
                out.push(match l.scalar {
                    ScalarKind::F32 => f64::from(f32::from_le_bytes(word)),
                    ScalarKind::I32 => f64::from(i32::from_le_bytes(word)),
                    ScalarKind::U32 => f64::from(u32::from_le_bytes(word)),
                });
            }
        }
        out
    }
}

/// What a vertex attribute carries.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
#[non_exhaustive]
pub enum AttributeSource {
    /// A property of the mesh, in object space.
    Mesh {
        /// Which.
        what: MeshAttribute,
    },
    /// A vertex-rate parameter of the shader.
    Param {
        /// The parameter.
        name: String,
    },
}

/// The mesh properties a vertex stage may read; each has a fixed location when it is read.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum MeshAttribute {
    /// The position (`vec3f`, location 0; always read).
    Position,
    /// The normal (`vec3f`, location 1).
    Normal,
    /// The surface parameters u, v (`vec2f`, location 2).
    Uv,
    /// The derivative of the position in u (`vec3f`, location 3).
    DpDu,
    /// The derivative of the position in v (`vec3f`, location 4).
    DpDv,
}

impl MeshAttribute {
    /// Every mesh attribute, in location order.
    pub const ALL: [MeshAttribute; 5] = [
        MeshAttribute::Position,
        MeshAttribute::Normal,
        MeshAttribute::Uv,
        MeshAttribute::DpDu,
        MeshAttribute::DpDv,
    ];

    /// Its `@location` (vertex-rate parameters follow from [`MeshAttribute::ALL`]'s length).
    pub fn location(self) -> u32 {
        MeshAttribute::ALL.iter().position(|a| *a == self).unwrap_or(0) as u32
    }

    /// Floats per vertex.
    pub fn components(self) -> u32 {
        if self == MeshAttribute::Uv { 2 } else { 3 }
    }

    /// The short name used in WGSL argument names (`P`, `N`, `uv`, `dPdu`, `dPdv`).
    pub fn name(self) -> &'static str {
        match self {
            MeshAttribute::Position => "P",
            MeshAttribute::Normal => "N",
            MeshAttribute::Uv => "uv",
            MeshAttribute::DpDu => "dPdu",
            MeshAttribute::DpDv => "dPdv",
        }
    }
}

/// A per-vertex input of the vertex stage (`f32` components, one vertex buffer each in the
/// runtime, but any layout with these locations and formats works).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Attribute {
    /// The entry point argument's name in the WGSL text (unique).
    pub name: String,
    /// What it carries.
    pub source: AttributeSource,
    /// Its `@location`.
    pub location: u32,
    /// Floats per vertex (`f32`, `vec2f`, `vec3f` or `vec4f`).
    pub components: u32,
}

/// A value interpolated from the vertex to the fragment stage.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Varying {
    /// Its name in the WGSL output struct.
    pub name: String,
    /// Its `@location`.
    pub location: u32,
    /// Components (1 to 4).
    pub components: u32,
    /// Whether it is not interpolated (integers and booleans).
    pub flat: bool,
    /// Predefined variables the fragment stage also fills from it, being equal on entry (`I`
    /// carried by `in_P`, `s` and `t` by `in_u` and `in_v`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub also: Vec<String>,
}

/// A texture the program reads: group 1, `binding`, fetched with `textureLoad` (no sampler).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct TextureSlot {
    /// The texture's name: a string parameter's value or a `texref` parameter's binding (the
    /// interpreter's `Evaluator::set_texture` takes the same name).
    pub name: String,
    /// 2 or 3.
    pub dimensions: u32,
    /// Its `@binding` in group 1.
    pub binding: u32,
}

/// What the fragment stage's `@location(0)` holds.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum Output {
    /// RGB from `Ci`, alpha the mean of `Oi` (premultiplied: `Ci` already includes `Oi`).
    CiOi,
    /// RGB from `Ci`, alpha 1 (the shader never writes `Oi`).
    Ci,
    /// A Stanford shader's float4 result, as it is.
    Result,
}

/// A parameter of the surface shader, as a user sets it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Parameter {
    /// Its name in the source.
    pub name: String,
    /// The language type (`float`, `color`, `point`, `string`, `float[4]`, ...).
    pub ty: String,
    /// Its default, when it does not depend on the view (`None` when it reads a space or a
    /// predefined variable, as `point "shader" (0, 0, 0)` does: the host computes it per draw).
    /// A default written in terms of other parameters is given for their defaults.
    pub default: Option<Vec<f64>>,
    /// The value binding compiled in (`--fix`), if any; such a parameter has no uniform.
    pub fixed: Option<Vec<f64>>,
    /// Whether the shader writes it (an output parameter).
    pub output: bool,
}

/// A light or displacement shader bound into the program, with its parameters
/// ([`UniformSource::LightParam`] and [`UniformSource::DisplacementParam`] read them).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LightInterface {
    /// The shader's name.
    pub shader: String,
    /// Its parameters.
    pub params: Vec<Parameter>,
}

/// Everything outside the module that a compiled program needs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Interface {
    /// [`INTERFACE_VERSION`] when written.
    pub version: u32,
    /// The shader's name.
    pub shader: String,
    /// The name of the vertex entry point.
    pub vertex_entry: String,
    /// The name of the fragment entry point.
    pub fragment_entry: String,
    /// The WGSL name of the uniform block's struct (group 0, binding 0).
    pub uniform_struct: String,
    /// The uniform block's members, in order.
    pub uniforms: Vec<UniformField>,
    /// The uniform block's size in bytes (a multiple of 16).
    pub uniform_size: u32,
    /// The surface shader's parameters.
    pub params: Vec<Parameter>,
    /// The bound lights, numbered as [`UniformSource::LightParam`] numbers them.
    pub lights: Vec<LightInterface>,
    /// The bound displacement shader, if any.
    pub displacement: Option<LightInterface>,
    /// The bound atmosphere (volume) shader, run after the surface on its `Ci` and `Oi`, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub atmosphere: Option<LightInterface>,
    /// Whether the uniform block holds values only the host stage computes
    /// ([`UniformSource::Host`]): then the block must be filled by running the host part (the
    /// facade's `Uniforms` does); a program compiled with the host folded in has none.
    pub needs_host: bool,
    /// The vertex attributes the vertex stage reads, by location.
    pub attributes: Vec<Attribute>,
    /// The varyings.
    pub varyings: Vec<Varying>,
    /// The textures, in binding order.
    pub textures: Vec<TextureSlot>,
    /// What the fragment stage writes.
    pub output: Output,
}

impl Default for Interface {
    fn default() -> Self {
        Interface {
            version: INTERFACE_VERSION,
            shader: String::new(),
            vertex_entry: "vs_main".into(),
            fragment_entry: "fs_main".into(),
            uniform_struct: "Uniforms".into(),
            uniforms: Vec::new(),
            uniform_size: 0,
            params: Vec::new(),
            lights: Vec::new(),
            displacement: None,
            atmosphere: None,
            needs_host: false,
            attributes: Vec::new(),
            varyings: Vec::new(),
            textures: Vec::new(),
            output: Output::Ci,
        }
    }
}

impl Interface {
    /// A uniform block of [`Interface::uniform_size`] bytes holding the constant tables
    /// ([`UniformSource::Table`]) and zeros elsewhere: the start of every block a host fills.
    pub fn blank_block(&self) -> Vec<u8> {
        let mut block = vec![0u8; self.uniform_size as usize];
        for field in &self.uniforms {
            if let UniformSource::Table { values } = &field.source {
                field.write(&mut block, values);
            }
        }
        block
    }

    /// The uniform field whose value is `source`.
    pub fn uniform(&self, source: &UniformSource) -> Option<&UniformField> {
        self.uniforms.iter().find(|f| f.source == *source)
    }

    /// The attribute of a mesh property, if the vertex stage reads it.
    pub fn mesh_attribute(&self, what: MeshAttribute) -> Option<&Attribute> {
        self.attributes.iter().find(|a| a.source == AttributeSource::Mesh { what })
    }

    /// The parameter `name`.
    pub fn param(&self, name: &str) -> Option<&Parameter> {
        self.params.iter().find(|p| p.name == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field(ty: &str, components: u32, elements: u32, stride: u32, column: u32) -> UniformField {
        UniformField {
            name: "f".into(),
            source: UniformSource::Param { name: "f".into() },
            ty: ty.into(),
            offset: 16,
            layout: FieldLayout {
                components,
                elements,
                element_stride: stride,
                column_stride: column,
                scalar: ScalarKind::F32,
            },
        }
    }

    #[test]
    fn a_3x3_matrix_is_three_padded_columns() {
        let f = field("matrix3", 9, 1, 48, 16);
        let mut block = vec![0xffu8; 64];
        let values: Vec<f64> = (1..=9).map(f64::from).collect();
        f.write(&mut block, &values);
        let word = |at: usize| f32::from_le_bytes(block[at..at + 4].try_into().unwrap());
        assert_eq!([word(16), word(20), word(24)], [1.0, 2.0, 3.0]);
        assert_eq!([word(32), word(36), word(40)], [4.0, 5.0, 6.0]);
        assert_eq!([word(48), word(52), word(56)], [7.0, 8.0, 9.0]);
        // The padding word of each column is left alone.
        assert_eq!(block[28..32], [0xff; 4]);
        assert_eq!(f.read(&block), values);
        assert_eq!(f.layout.size(), 44);
    }

    #[test]
    fn array_elements_are_16_bytes_apart_and_integers_wrap() {
        let mut f = field("int[3]", 1, 3, 16, 0);
        f.layout.scalar = ScalarKind::I32;
        let mut block = vec![0u8; 80];
        f.write(&mut block, &[-1.0, 4_294_967_295.0, 7.0]);
        assert_eq!(block[16..20], (-1i32).to_le_bytes());
        assert_eq!(block[32..36], (-1i32).to_le_bytes());
        assert_eq!(block[48..52], 7i32.to_le_bytes());
        assert_eq!(f.read(&block), vec![-1.0, -1.0, 7.0]);
        assert_eq!(f.layout.size(), 36);
    }

    #[test]
    fn the_json_form_round_trips() {
        let interface = Interface {
            shader: "s".into(),
            uniforms: vec![field("color", 3, 1, 16, 0)],
            attributes: vec![Attribute {
                name: "a_P".into(),
                source: AttributeSource::Mesh { what: MeshAttribute::Position },
                location: 0,
                components: 3,
            }],
            ..Interface::default()
        };
        let text = serde_json::to_string(&interface).unwrap();
        assert!(text.contains(r#""kind":"mesh","what":"position""#), "{text}");
        let back: Interface = serde_json::from_str(&text).unwrap();
        assert_eq!(back, interface);
    }
}
