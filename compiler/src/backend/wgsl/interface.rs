//! The interface of a compiled GPU program, as data: what the runtime (or a user's own wgpu code)
//! must bind and fill. Written to JSON by `patina compile`.
//!
//! Conventions:
//! - Group 0, binding 0 is the uniform block; group 1 holds textures (binding 2k) and their
//!   samplers (2k + 1).
//! - Matrices are 16 (or 9) floats in the layout of `glam::Mat4::to_cols_array`: read by the
//!   language as a matrix written row by row whose rows are those columns, which is RenderMan's
//!   row-vector convention (`p' = p · M`). A 3x3 matrix occupies three 16-byte columns.
//! - Points, vectors and normals are in "current" space, which is camera space: the eye at the
//!   origin looking down +z, x to the right, y up (left-handed, as RenderMan's camera space).

use serde::Serialize;

/// Where the value of a uniform field comes from.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
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
    /// A parameter of the bound displacement shader.
    DisplacementParam {
        /// The parameter.
        name: String,
    },
    /// A matrix the vertex stage's geometry needs (column-vector convention, `v' = M v`).
    Geometry {
        /// Which.
        matrix: GeometryMatrix,
    },
}

/// The matrices the vertex stage uses to place geometry.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GeometryMatrix {
    /// Object space to camera ("current") space.
    ObjectToCamera,
    /// Normals from object to camera space (inverse transpose of the above).
    NormalToCamera,
    /// Camera space to wgpu clip space.
    CameraToClip,
}

/// One member of the uniform block.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct UniformField {
    /// The member's name in the WGSL struct.
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

/// How a field's components are stored.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct FieldLayout {
    /// Components per element (1, 3, 4, 9 or 16).
    pub components: u32,
    /// Elements (1 for non-arrays).
    pub elements: u32,
    /// Bytes from one element to the next.
    pub element_stride: u32,
    /// For 3x3 matrices, bytes between columns (16); otherwise 0.
    pub column_stride: u32,
    /// The scalar type: `f32`, `i32` or `u32` (booleans are `u32` 0 or 1).
    pub scalar: &'static str,
}

/// A per-vertex input of the vertex stage.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Attribute {
    /// What it carries: `P`, `N`, `uv`, `dPdu`, `dPdv` (object space), or a vertex-rate
    /// parameter of the shader by name.
    pub name: String,
    /// Its `@location`.
    pub location: u32,
    /// Floats per vertex.
    pub components: u32,
}

/// A value interpolated from the vertex to the fragment stage.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Varying {
    /// Its name in the WGSL output struct.
    pub name: String,
    /// Its `@location`.
    pub location: u32,
    /// Components (1 to 4).
    pub components: u32,
    /// Whether it is not interpolated (integers and booleans).
    pub flat: bool,
}

/// A texture the program reads (group 1; its sampler, unused by the fetches, at `binding + 1`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TextureSlot {
    /// The texture's name: a string parameter's value or a `texref` parameter's binding (the
    /// interpreter's `Evaluator::set_texture` takes the same name).
    pub name: String,
    /// 2 or 3.
    pub dimensions: u32,
    /// Its `@binding` in group 1.
    pub binding: u32,
}

/// Everything outside the module that a compiled program needs.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Interface {
    /// The name of the vertex entry point.
    pub vertex_entry: String,
    /// The name of the fragment entry point.
    pub fragment_entry: String,
    /// The uniform block's members, in order.
    pub uniforms: Vec<UniformField>,
    /// The uniform block's size in bytes (a multiple of 16).
    pub uniform_size: u32,
    /// The vertex attributes.
    pub attributes: Vec<Attribute>,
    /// The varyings.
    pub varyings: Vec<Varying>,
    /// The textures, in binding order.
    pub textures: Vec<TextureSlot>,
    /// What the fragment stage writes to `@location(0)`: `Ci, Oi` (RGB from `Ci`, alpha the mean
    /// of `Oi`), `Ci` (alpha 1: the shader never writes `Oi`), or `result` (a Stanford shader's
    /// float4).
    pub output: String,
}
