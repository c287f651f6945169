//! The scene's small value types and how they are read: shader parameter values, transformation
//! steps and mesh choices.

use super::MeshSource;
use glam::{Mat4, Vec3};
use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use std::fmt;

/// A shader parameter's value as written in a scene; the shader's declaration decides its type
/// (an array of 3 numbers may be a color, a point or a `float[3]`).
#[derive(Clone, Debug, PartialEq)]
pub enum ParamValue {
    /// A single number (integers are read as numbers too).
    Number(f64),
    /// An array of numbers.
    Numbers(Vec<f64>),
    /// A string (texture names, spaces, ...).
    String(String),
    /// A boolean.
    Bool(bool),
}

impl ParamValue {
    /// The number, if this is one.
    pub fn as_number(&self) -> Option<f64> {
        match self {
            ParamValue::Number(x) => Some(*x),
            _ => None,
        }
    }

    /// The numbers of an array, or the one number as a slice of one.
    pub fn as_numbers(&self) -> Option<&[f64]> {
        match self {
            ParamValue::Number(x) => Some(std::slice::from_ref(x)),
            ParamValue::Numbers(xs) => Some(xs),
            _ => None,
        }
    }

    /// The string, if this is one.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            ParamValue::String(s) => Some(s),
            _ => None,
        }
    }
}

impl<'de> Deserialize<'de> for ParamValue {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ParamVisitor)
    }
}

struct ParamVisitor;

impl<'de> Visitor<'de> for ParamVisitor {
    type Value = ParamValue;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number, an array of numbers, a string or a boolean")
    }

    fn visit_bool<E: de::Error>(self, v: bool) -> Result<ParamValue, E> {
        Ok(ParamValue::Bool(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<ParamValue, E> {
        Ok(ParamValue::Number(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<ParamValue, E> {
        Ok(ParamValue::Number(v as f64))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<ParamValue, E> {
        Ok(ParamValue::Number(v))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<ParamValue, E> {
        Ok(ParamValue::String(v.to_string()))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<ParamValue, A::Error> {
        let mut numbers = Vec::new();
        while let Some(x) = seq.next_element::<f64>()? {
            numbers.push(x);
        }
        Ok(ParamValue::Numbers(numbers))
    }
}

/// One step of an object's transformation. Angles are in degrees.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "lowercase", deny_unknown_fields)]
pub enum TransformStep {
    /// `{ translate = [x, y, z] }`
    Translate([f32; 3]),
    /// `{ rotate = { angle = 30, axis = [0, 1, 0] } }`: RenderMan's `Rotate`, the usual rotation
    /// matrix about the axis (90° about +z takes +x to +y).
    Rotate {
        /// Degrees.
        angle: f32,
        /// The axis; its length does not matter, but it must not be zero.
        axis: [f32; 3],
    },
    /// `{ scale = [x, y, z] }`
    Scale([f32; 3]),
}

impl TransformStep {
    /// The step as a matrix (column vectors). A zero rotation axis gives the identity.
    pub fn matrix(&self) -> Mat4 {
        match self {
            TransformStep::Translate(t) => Mat4::from_translation(Vec3::from(*t)),
            TransformStep::Rotate { angle, axis } => match Vec3::from(*axis).try_normalize() {
                Some(axis) => Mat4::from_axis_angle(axis, angle.to_radians()),
                None => Mat4::IDENTITY,
            },
            TransformStep::Scale(s) => Mat4::from_scale(Vec3::from(*s)),
        }
    }
}

/// The built-in mesh kinds, by their names in a scene.
const MESH_KINDS: [&str; 5] = ["sphere", "torus", "plane", "cube", "teapot"];

/// `mesh = "sphere"` or `mesh = { obj = "model.obj" }`, before paths are resolved.
#[derive(Clone, Debug)]
pub(crate) enum RawMesh {
    /// Never [`MeshSource::Obj`].
    Builtin(MeshSource),
    Obj(String),
}

impl<'de> Deserialize<'de> for RawMesh {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(MeshVisitor)
    }
}

struct MeshVisitor;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjFile {
    obj: String,
}

impl<'de> Visitor<'de> for MeshVisitor {
    type Value = RawMesh;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "a mesh kind ({}) or a table {{ obj = \"file.obj\" }}", MESH_KINDS.join(", "))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<RawMesh, E> {
        Ok(RawMesh::Builtin(match v {
            "sphere" => MeshSource::Sphere,
            "torus" => MeshSource::Torus,
            "plane" => MeshSource::Plane,
            "cube" => MeshSource::Cube,
            "teapot" => MeshSource::Teapot,
            _ => {
                let kinds = MESH_KINDS.join(", ");
                return Err(E::custom(format!(
                    "unknown mesh kind `{v}`; expected one of {kinds}, or {{ obj = \"file.obj\" }}"
                )));
            }
        }))
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<RawMesh, A::Error> {
        let file = ObjFile::deserialize(de::value::MapAccessDeserializer::new(map))?;
        Ok(RawMesh::Obj(file.obj))
    }
}
