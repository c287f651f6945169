//! The scene file exactly as written: serde's view, before semantic checks and path resolution.
//! Integers that have a valid range are read as `i64` so that the range check, not the type,
//! reports a negative value.

use super::KnobKind;
use super::value::{ParamValue, RawMesh, TransformStep};
use serde::Deserialize;
use std::collections::BTreeMap;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawScene {
    #[serde(default)]
    pub output: RawOutput,
    pub camera: RawCamera,
    #[serde(default)]
    pub light: Vec<RawLight>,
    #[serde(default)]
    pub object: Vec<RawObject>,
    #[serde(default)]
    pub knob: Vec<RawKnob>,
    #[serde(default)]
    pub shadow: Vec<RawShadowMap>,
    pub compare: Option<RawCompare>,
    pub atmosphere: Option<RawShader>,
    pub imager: Option<RawShader>,
    #[serde(default)]
    pub include: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, default)]
pub(crate) struct RawOutput {
    pub width: i64,
    pub height: i64,
    pub background: Vec<f32>,
    pub supersample: i64,
}

impl Default for RawOutput {
    fn default() -> Self {
        RawOutput { width: 256, height: 256, background: vec![0.0, 0.0, 0.0, 1.0], supersample: 1 }
    }
}

fn default_up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}

fn default_fov() -> f32 {
    40.0
}

fn default_near() -> f32 {
    0.1
}

fn default_far() -> f32 {
    100.0
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawCamera {
    pub from: [f32; 3],
    pub to: [f32; 3],
    #[serde(default = "default_up")]
    pub up: [f32; 3],
    #[serde(default = "default_fov")]
    pub fov: f32,
    #[serde(default = "default_near")]
    pub near: f32,
    #[serde(default = "default_far")]
    pub far: f32,
}

/// A light, or an object's displacement: a shader file, which shader in it, and parameters.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawShader {
    pub shader: String,
    pub name: Option<String>,
    #[serde(default)]
    pub params: BTreeMap<String, ParamValue>,
    #[serde(default)]
    pub animate: Vec<String>,
}

/// A `[[light]]`: its shader, and the position of a Stanford-style light (world space). The fields
/// of [`RawShader`] are repeated, not flattened: serde's `flatten` does not combine with
/// `deny_unknown_fields`, which keeps a misspelt key an error.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLight {
    pub shader: String,
    pub name: Option<String>,
    #[serde(default)]
    pub params: BTreeMap<String, ParamValue>,
    #[serde(default)]
    pub animate: Vec<String>,
    pub position: Option<[f32; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawObject {
    pub mesh: RawMesh,
    pub detail: Option<i64>,
    pub shader: String,
    pub name: Option<String>,
    #[serde(default)]
    pub params: BTreeMap<String, ParamValue>,
    #[serde(default)]
    pub animate: Vec<String>,
    pub displacement: Option<RawShader>,
    pub atmosphere: Option<RawShader>,
    pub color: Option<[f32; 3]>,
    pub opacity: Option<[f32; 3]>,
    #[serde(default)]
    pub transform: Vec<TransformStep>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawKnob {
    pub name: Option<String>,
    pub kind: KnobKind,
    pub param: Option<String>,
    pub object: Option<i64>,
    pub values: Option<Vec<f64>>,
    pub settings: Option<Vec<RawSetting>>,
    pub reference: RawReference,
}

/// One named setting of a knob: the parameter values (and `output.supersample`) it assigns.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSetting {
    pub label: String,
    pub set: BTreeMap<String, f64>,
}

/// A knob's reference: one of its parameter's values, a setting, or another scene.
#[derive(Deserialize)]
#[serde(untagged)]
pub(crate) enum RawReference {
    Value(f64),
    Setting(RawSetting),
    Scene(RawReferenceScene),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawReferenceScene {
    pub scene: String,
    pub label: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawCompare {
    pub fail: Option<f32>,
    pub hard_fail: Option<f32>,
    pub max_failing_fraction: Option<f32>,
    pub reason: String,
}

/// A `[[shadow]]` table: a shadow map made by a depth pass from a light.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawShadowMap {
    pub name: String,
    pub light: i64,
    pub resolution: Option<i64>,
    pub fov: Option<f32>,
    pub near: Option<f32>,
    pub far: Option<f32>,
    pub bias: Option<f32>,
    pub projection: Option<String>,
    pub to: Option<[f32; 3]>,
}
