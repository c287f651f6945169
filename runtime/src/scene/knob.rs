//! Quality knobs: the dimensions along which a scene trades error for run time, as `patina bench`
//! sweeps them. A knob is a list of settings, each a few assignments to shader parameters (of
//! objects, or of lights with `light.NAME`), to `output.supersample` or to
//! `shadow.resolution`, and a reference that the settings are measured against.

use super::error::{Field, Locator, SceneError, field};
use super::schema::{RawKnob, RawReference, RawSetting};
use super::{Light, Object, ParamValue, Scene};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// The key of a setting that assigns the supersampling factor instead of a shader parameter.
pub const SUPERSAMPLE_KEY: &str = "output.supersample";

/// The key of a setting that assigns the resolution of every shadow map (`[[shadow]]`).
pub const SHADOW_RESOLUTION_KEY: &str = "shadow.resolution";

/// The prefix of a setting's key that assigns a light-shader parameter (`light.samples`) of every
/// light whose `params` set it.
pub const LIGHT_PREFIX: &str = "light.";

/// What a knob varies (the categories of issue 10; the plot and the tables name them).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum KnobKind {
    /// Ray-march steps per ray.
    Steps,
    /// Ray-march step length.
    StepSize,
    /// Octaves of a fractal sum.
    Octaves,
    /// Samples per pixel (inside a shader, or `output.supersample`).
    Samples,
    /// Antialiasing: none, analytic (derivative-driven filtering) or supersampled.
    Antialias,
    /// Entries of a colour or shadow table.
    TableSize,
    /// Fixed or jittered phase of the ray-march steps.
    StepPhase,
    /// Early ray termination on or off (or its opacity threshold).
    EarlyTermination,
    /// How shadows are found: shadow rays or a shadow table.
    Shadow,
    /// Which noise function.
    Noise,
}

impl KnobKind {
    /// The name as written in scene files.
    pub fn name(self) -> &'static str {
        match self {
            KnobKind::Steps => "steps",
            KnobKind::StepSize => "step_size",
            KnobKind::Octaves => "octaves",
            KnobKind::Samples => "samples",
            KnobKind::Antialias => "antialias",
            KnobKind::TableSize => "table_size",
            KnobKind::StepPhase => "step_phase",
            KnobKind::EarlyTermination => "early_termination",
            KnobKind::Shadow => "shadow",
            KnobKind::Noise => "noise",
        }
    }
}

/// A quality knob of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Knob {
    /// The name `patina bench --knob NAME=...` uses (the parameter's name by default).
    pub name: String,
    /// What it varies.
    pub kind: KnobKind,
    /// The settings measured by default, cheapest first as the scene lists them.
    pub settings: Vec<Setting>,
    /// What the settings are measured against.
    pub reference: Reference,
    /// For a one-parameter knob, its parameter and object: any value of it can be asked for.
    pub param: Option<(String, Option<usize>)>,
}

/// One setting of a knob.
#[derive(Clone, Debug, PartialEq)]
pub struct Setting {
    /// How tables and plots name it (`16` for a one-parameter knob, or the scene's label).
    pub label: String,
    /// What it assigns.
    pub assignments: Vec<Assignment>,
}

/// One value a setting assigns.
#[derive(Clone, Debug, PartialEq)]
pub enum Assignment {
    /// A surface-shader parameter of one object, or of every object whose `params` set it.
    Param {
        /// The parameter.
        name: String,
        /// The object; `None` for every object whose `params` set the parameter.
        object: Option<usize>,
        /// The value.
        value: f64,
    },
    /// `output.supersample`.
    Supersample(u32),
    /// `shadow.resolution`: every shadow map's resolution.
    ShadowResolution(u32),
    /// `light.NAME`: a light-shader parameter of every light whose `params` set it.
    LightParam {
        /// The parameter.
        name: String,
        /// The value.
        value: f64,
    },
}

/// What a knob's settings are measured against.
#[derive(Clone, Debug, PartialEq)]
pub enum Reference {
    /// The same scene at a (fine) setting.
    Setting(Setting),
    /// Another scene whose image is the exact answer (a closed form, an exact box filter), read
    /// when the knob is measured.
    Scene {
        /// The scene file, resolved against this scene's directory.
        path: PathBuf,
        /// How tables name it.
        label: String,
    },
}

impl Knob {
    /// The setting of a one-parameter knob at `value` (any value, not only the listed ones), or
    /// the listed setting labelled `label`.
    pub fn setting(&self, label: &str) -> Option<Setting> {
        if let Some(s) = self.settings.iter().find(|s| s.label == label) {
            return Some(s.clone());
        }
        if let Reference::Setting(s) = &self.reference
            && s.label == label
        {
            return Some(s.clone());
        }
        let (name, object) = self.param.as_ref()?;
        let value: f64 = label.trim().parse().ok().filter(|v: &f64| v.is_finite())?;
        Some(Setting {
            label: label.trim().to_string(),
            assignments: vec![Assignment::Param { name: name.clone(), object: *object, value }],
        })
    }
}

impl Scene {
    /// The knob called `name`.
    pub fn knob(&self, name: &str) -> Option<&Knob> {
        self.knobs.iter().find(|k| k.name == name)
    }

    /// This scene with `setting`'s values assigned.
    pub fn with_setting(&self, setting: &Setting) -> Scene {
        let mut scene = self.clone();
        for a in &setting.assignments {
            match a {
                Assignment::Supersample(n) => scene.output.supersample = *n,
                Assignment::ShadowResolution(n) => {
                    for m in &mut scene.shadow_maps {
                        m.resolution = *n;
                    }
                }
                Assignment::LightParam { name, value } => {
                    for l in &mut scene.lights {
                        if l.shader.params.contains_key(name) {
                            l.shader.params.insert(name.clone(), ParamValue::Number(*value));
                        }
                    }
                }
                Assignment::Param { name, object, value } => {
                    for (i, o) in scene.objects.iter_mut().enumerate() {
                        let chosen = match object {
                            Some(k) => i == *k,
                            None => o.surface.params.contains_key(name),
                        };
                        if chosen {
                            o.surface.params.insert(name.clone(), ParamValue::Number(*value));
                        }
                    }
                }
            }
        }
        scene
    }
}

/// Checks a `[[knob]]` table.
pub(super) fn knob(
    raw: &RawKnob,
    at: &Field,
    objects: &[Object],
    lights: &[Light],
    shadow_maps: usize,
    loc: &Locator,
    base: &Path,
) -> Result<Knob, SceneError> {
    let object = match raw.object {
        None => None,
        Some(i) if usize::try_from(i).is_ok_and(|i| i < objects.len()) => Some(i as usize),
        Some(i) => {
            let n = objects.len();
            let message = format!("there is no object {i} (the scene has {n}, numbered from 0)");
            return Err(loc.invalid(&at.key("object"), message));
        }
    };
    let check = Check { objects, lights, shadow_maps, object, loc };
    let param = match &raw.param {
        Some(p) if p.trim().is_empty() => {
            return Err(loc.invalid(&at.key("param"), "the parameter name is empty"));
        }
        Some(p) => Some(p.trim().to_string()),
        None => None,
    };
    let name = match (&raw.name, &param) {
        (Some(n), _) if n.trim().is_empty() => {
            return Err(loc.invalid(&at.key("name"), "the knob's name is empty"));
        }
        (Some(n), _) => n.trim().to_string(),
        (None, Some(p)) => p.clone(),
        (None, None) => return Err(loc.invalid(at, "a knob with `settings` needs a `name`")),
    };
    let settings = match (&param, &raw.values, &raw.settings) {
        (Some(p), Some(values), None) => values
            .iter()
            .map(|v| check.value_setting(p, *v, &at.key("values")))
            .collect::<Result<Vec<_>, _>>()?,
        (None, None, Some(list)) => (list.iter().enumerate())
            .map(|(i, s)| check.setting(s, &at.key("settings").index(i)))
            .collect::<Result<Vec<_>, _>>()?,
        _ => return Err(loc.invalid(at, "give either `param` with its `values`, or `settings`")),
    };
    if settings.is_empty() {
        let which = if raw.values.is_some() { "values" } else { "settings" };
        return Err(loc.invalid(&at.key(which), "at least one setting is needed"));
    }
    let reference_at = at.key("reference");
    let reference = match (&raw.reference, &param) {
        (RawReference::Value(v), Some(p)) => Reference::Setting(check.value_setting(p, *v, &reference_at)?),
        (RawReference::Value(_), None) => {
            return Err(loc.invalid(&reference_at, "a knob with `settings` names its reference as a setting"));
        }
        (RawReference::Setting(s), _) => Reference::Setting(check.setting(s, &reference_at)?),
        (RawReference::Scene(s), _) => {
            if s.scene.trim().is_empty() {
                return Err(loc.invalid(&reference_at.key("scene"), "the file name is empty"));
            }
            let label = s.label.clone().unwrap_or_else(|| "exact".to_string());
            Reference::Scene { path: base.join(&s.scene), label }
        }
    };
    Ok(Knob { name, kind: raw.kind, settings, reference, param: param.map(|p| (p, object)) })
}

/// What checking a knob's settings needs.
struct Check<'a> {
    objects: &'a [Object],
    lights: &'a [Light],
    shadow_maps: usize,
    object: Option<usize>,
    loc: &'a Locator<'a>,
}

impl Check<'_> {
    /// The setting that assigns `value` to `param`.
    fn value_setting(&self, param: &str, value: f64, at: &Field) -> Result<Setting, SceneError> {
        let assignment = self.assignment(param, value, at)?;
        Ok(Setting { label: format!("{value}"), assignments: vec![assignment] })
    }

    fn setting(&self, raw: &RawSetting, at: &Field) -> Result<Setting, SceneError> {
        if raw.label.trim().is_empty() {
            return Err(self.loc.invalid(&at.key("label"), "the label is empty"));
        }
        if raw.set.is_empty() {
            return Err(self.loc.invalid(&at.key("set"), "a setting assigns at least one value"));
        }
        let assignments = (raw.set.iter())
            .map(|(key, value)| self.assignment(key, *value, &at.key("set").key(key)))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Setting { label: raw.label.trim().to_string(), assignments })
    }

    fn assignment(&self, key: &str, value: f64, at: &Field) -> Result<Assignment, SceneError> {
        if !value.is_finite() {
            return Err(self.loc.invalid(at, "settings must be finite numbers"));
        }
        if key == SUPERSAMPLE_KEY {
            return match value {
                v if v.fract() == 0.0 && (1.0..=16.0).contains(&v) => Ok(Assignment::Supersample(v as u32)),
                _ => Err(self.loc.invalid(at, "output.supersample is a whole number in 1..=16")),
            };
        }
        if key == SHADOW_RESOLUTION_KEY {
            let range = f64::from(super::shadow::MIN_RESOLUTION)..=f64::from(super::shadow::MAX_RESOLUTION);
            return match value {
                _ if self.shadow_maps == 0 => Err(self.loc.invalid(at, "the scene has no `[[shadow]]` map")),
                v if v.fract() == 0.0 && range.contains(&v) => Ok(Assignment::ShadowResolution(v as u32)),
                _ => Err(self.loc.invalid(at, "shadow.resolution is a whole number in 8..=4096")),
            };
        }
        if let Some(name) = key.strip_prefix(LIGHT_PREFIX) {
            if !self.lights.iter().any(|l| l.shader.params.contains_key(name)) {
                let message = format!("no light's `params` set `{name}`");
                return Err(self.loc.invalid(at, message));
            }
            return Ok(Assignment::LightParam { name: name.to_string(), value });
        }
        // Without an object, the knob reaches the objects whose `params` set the parameter: the
        // scene file then says which objects it applies to.
        if self.object.is_none() && !self.objects.iter().any(|o| o.surface.params.contains_key(key)) {
            let message = format!(
                "no object's `params` set `{key}` (set it on the objects the knob varies, or give `object`)"
            );
            return Err(self.loc.invalid(at, message));
        }
        Ok(Assignment::Param { name: key.to_string(), object: self.object, value })
    }
}

/// The knobs of a scene, checked: names are unique.
pub(super) fn knobs(
    raw: &[RawKnob],
    objects: &[Object],
    lights: &[Light],
    shadow_maps: usize,
    loc: &Locator,
    base: &Path,
) -> Result<Vec<Knob>, SceneError> {
    let mut knobs: Vec<Knob> = Vec::new();
    for (i, r) in raw.iter().enumerate() {
        let at = field(&["knob"]).index(i);
        let k = knob(r, &at, objects, lights, shadow_maps, loc, base)?;
        if knobs.iter().any(|other| other.name == k.name) {
            return Err(loc.invalid(&at, format!("a second knob named `{}`", k.name)));
        }
        knobs.push(k);
    }
    Ok(knobs)
}
