//! From the file as written to a [`Scene`]: range and consistency checks, each reported at its
//! field, and paths resolved against the scene's directory.

use super::error::{Field, Locator, SceneError, field};
use super::schema::{RawCamera, RawCompare, RawLight, RawObject, RawOutput, RawScene, RawShader};
use super::value::{RawMesh, TransformStep};
use super::{Compare, DEFAULT_DETAIL, Light, MeshSource, Object, Output, Scene, ShaderRef};
use crate::camera::Camera;
use crate::image::Thresholds;
use crate::mesh::MAX_DETAIL;
use glam::Vec3;
use std::path::{Path, PathBuf};

pub(super) fn build(raw: RawScene, loc: &Locator, file: &Path, base: &Path) -> Result<Scene, SceneError> {
    let output = output(&raw.output, loc)?;
    let camera = camera(&raw.camera, loc)?;
    let lights = (raw.light.iter().enumerate())
        .map(|(i, light)| self::light(light, &field(&["light"]).index(i), loc, base))
        .collect::<Result<Vec<_>, SceneError>>()?;
    let atmosphere =
        raw.atmosphere.as_ref().map(|a| shader(a, &field(&["atmosphere"]), loc, base)).transpose()?;
    let imager = raw.imager.as_ref().map(|a| shader(a, &field(&["imager"]), loc, base)).transpose()?;
    let mut objects = (raw.object.iter().enumerate())
        .map(|(i, object)| self::object(object, &field(&["object"]).index(i), loc, base))
        .collect::<Result<Vec<_>, SceneError>>()?;
    for object in &mut objects {
        if object.atmosphere.is_none() {
            object.atmosphere.clone_from(&atmosphere);
        }
    }
    let shadow_maps = super::shadow::shadow_maps(&raw.shadow, &lights, loc)?;
    let knobs = super::knob::knobs(&raw.knob, &objects, &lights, shadow_maps.len(), loc, base)?;
    let compare = raw.compare.as_ref().map(|c| compare(c, loc)).transpose()?;
    let mut scene = Scene {
        file: file.to_path_buf(),
        output,
        camera,
        lights,
        objects,
        knobs,
        imager,
        shadow_maps,
        compare,
    };
    let include_dirs = include_dirs(&raw.include, loc, base)?;
    for shader in scene.shaders_mut() {
        shader.include_dirs.clone_from(&include_dirs);
    }
    Ok(scene)
}

/// The scene's `include` directories, resolved against its directory.
fn include_dirs(raw: &[String], loc: &Locator, base: &Path) -> Result<Vec<PathBuf>, SceneError> {
    raw.iter()
        .enumerate()
        .map(|(i, dir)| match dir.trim().is_empty() {
            true => Err(loc.invalid(&field(&["include"]).index(i), "the include directory is empty")),
            false => Ok(base.join(dir)),
        })
        .collect()
}

fn line(loc: &Locator, at: &Field) -> usize {
    loc.span_of(at).map_or(0, |s| loc.position(s.start).0)
}

/// `value` as a `u32` in `range`, or an error at `at`.
fn in_range(
    value: i64,
    range: std::ops::RangeInclusive<u32>,
    at: &Field,
    loc: &Locator,
) -> Result<u32, SceneError> {
    match u32::try_from(value) {
        Ok(v) if range.contains(&v) => Ok(v),
        _ => {
            Err(loc
                .invalid(at, format!("must be between {} and {}, found {value}", range.start(), range.end())))
        }
    }
}

fn finite(values: &[f32; 3], at: &Field, loc: &Locator) -> Result<Vec3, SceneError> {
    if values.iter().all(|x| x.is_finite()) {
        Ok(Vec3::from(*values))
    } else {
        Err(loc.invalid(at, "values must be finite numbers"))
    }
}

fn output(raw: &RawOutput, loc: &Locator) -> Result<Output, SceneError> {
    let at = |name| field(&["output", name]);
    let width = in_range(raw.width, 1..=16384, &at("width"), loc)?;
    let height = in_range(raw.height, 1..=16384, &at("height"), loc)?;
    let supersample = in_range(raw.supersample, 1..=16, &at("supersample"), loc)?;
    let background = match raw.background[..] {
        [r, g, b] => [r, g, b, 1.0],
        [r, g, b, a] => [r, g, b, a],
        _ => {
            let n = raw.background.len();
            return Err(
                loc.invalid(&at("background"), format!("expected 3 or 4 numbers (RGB or RGBA), found {n}"))
            );
        }
    };
    if background.iter().any(|x| !x.is_finite()) {
        return Err(loc.invalid(&at("background"), "values must be finite numbers"));
    }
    Ok(Output { width, height, background, supersample })
}

fn camera(raw: &RawCamera, loc: &Locator) -> Result<Camera, SceneError> {
    let at = |name| field(&["camera", name]);
    let from = finite(&raw.from, &at("from"), loc)?;
    let to = finite(&raw.to, &at("to"), loc)?;
    let up = finite(&raw.up, &at("up"), loc)?;
    if !(raw.fov > 0.0 && raw.fov < 180.0) {
        return Err(loc.invalid(
            &at("fov"),
            format!("must be between 0 and 180 degrees (exclusive), found {}", raw.fov),
        ));
    }
    if !(raw.near > 0.0 && raw.near.is_finite()) {
        return Err(loc.invalid(&at("near"), format!("must be greater than 0, found {}", raw.near)));
    }
    if !(raw.far > raw.near && raw.far.is_finite()) {
        // Blame what was written: a large `near` against the default `far` is the near's fault.
        return Err(if loc.is_written(&at("far")) {
            loc.invalid(
                &at("far"),
                format!("must be greater than camera.near ({}), found {}", raw.near, raw.far),
            )
        } else {
            let message =
                format!("must be less than camera.far ({} by default), found {}", raw.far, raw.near);
            loc.invalid(&at("near"), message)
        });
    }
    if from == to {
        return Err(loc.invalid(&at("to"), "must differ from camera.from (the camera would look nowhere)"));
    }
    if up.cross(to - from).length_squared() <= 1e-12 * up.length_squared() * (to - from).length_squared() {
        return Err(loc.invalid(&at("up"), "must not be zero or parallel to the viewing direction"));
    }
    Ok(Camera { from, to, up, fov_y_degrees: raw.fov, near: raw.near, far: raw.far })
}

fn shader(raw: &RawShader, at: &Field, loc: &Locator, base: &Path) -> Result<ShaderRef, SceneError> {
    shader_parts(&raw.shader, &raw.name, &raw.params, &raw.animate, at, loc, base)
}

fn shader_parts(
    path: &str,
    name: &Option<String>,
    params: &std::collections::BTreeMap<String, super::ParamValue>,
    animate: &[String],
    at: &Field,
    loc: &Locator,
    base: &Path,
) -> Result<ShaderRef, SceneError> {
    if path.trim().is_empty() {
        return Err(loc.invalid(&at.key("shader"), "the shader path is empty"));
    }
    if name.as_deref().is_some_and(|n| n.trim().is_empty()) {
        return Err(loc.invalid(&at.key("name"), "the shader name is empty (leave `name` out instead)"));
    }
    // `<shaders.sl>`: a module of the standard library, as `#include <shaders.sl>` names it.
    if let Some(module) = path.strip_prefix('<').and_then(|p| p.strip_suffix('>')) {
        if patina_compiler::stdlib::source(module).is_none() {
            let known: Vec<&str> = patina_compiler::stdlib::MODULES.iter().map(|(n, _)| *n).collect();
            return Err(loc.invalid(
                &at.key("shader"),
                format!("no standard-library module `{module}` (there are {})", known.join(", ")),
            ));
        }
        let path = PathBuf::from(format!("{}/{module}", patina_compiler::stdlib::PREFIX));
        return Ok(ShaderRef {
            path,
            name: name.clone(),
            params: params.clone(),
            animate: animate.to_vec(),
            include_dirs: Vec::new(),
        });
    }
    Ok(ShaderRef {
        path: base.join(path),
        name: name.clone(),
        params: params.clone(),
        animate: animate.to_vec(),
        include_dirs: Vec::new(),
    })
}

fn light(raw: &RawLight, at: &Field, loc: &Locator, base: &Path) -> Result<Light, SceneError> {
    let shader = shader_parts(&raw.shader, &raw.name, &raw.params, &raw.animate, at, loc, base)?;
    let position = raw.position.as_ref().map(|p| finite(p, &at.key("position"), loc)).transpose()?;
    Ok(Light { shader, position, line: line(loc, at) })
}

fn object(raw: &RawObject, at: &Field, loc: &Locator, base: &Path) -> Result<Object, SceneError> {
    let mesh = match &raw.mesh {
        RawMesh::Builtin(kind) => kind.clone(),
        RawMesh::Obj(path) if path.trim().is_empty() => {
            return Err(loc.invalid(&at.key("mesh").key("obj"), "the OBJ file path is empty"));
        }
        RawMesh::Obj(path) => MeshSource::Obj(base.join(path)),
    };
    let detail = match raw.detail {
        Some(d) => in_range(d, 1..=MAX_DETAIL, &at.key("detail"), loc)?,
        None => DEFAULT_DETAIL,
    };
    let surface = shader_parts(&raw.shader, &raw.name, &raw.params, &raw.animate, at, loc, base)?;
    let displacement =
        raw.displacement.as_ref().map(|d| shader(d, &at.key("displacement"), loc, base)).transpose()?;
    let atmosphere =
        raw.atmosphere.as_ref().map(|a| shader(a, &at.key("atmosphere"), loc, base)).transpose()?;
    let colour = |value: Option<[f32; 3]>, name: &str| -> Result<[f32; 3], SceneError> {
        let value = value.unwrap_or([1.0; 3]);
        finite(&value, &at.key(name), loc)?;
        Ok(value)
    };
    for (k, step) in raw.transform.iter().enumerate() {
        transform_step(step, &at.key("transform").index(k), loc)?;
    }
    Ok(Object {
        mesh,
        detail,
        surface,
        displacement,
        atmosphere,
        color: colour(raw.color, "color")?,
        opacity: colour(raw.opacity, "opacity")?,
        transform: raw.transform.clone(),
        line: line(loc, at),
    })
}

fn transform_step(step: &TransformStep, at: &Field, loc: &Locator) -> Result<(), SceneError> {
    match step {
        TransformStep::Translate(t) => finite(t, &at.key("translate"), loc).map(drop),
        TransformStep::Scale(s) => finite(s, &at.key("scale"), loc).map(drop),
        TransformStep::Rotate { angle, axis } => {
            let at = at.key("rotate");
            if !angle.is_finite() {
                return Err(loc.invalid(&at.key("angle"), "must be a finite number"));
            }
            if finite(axis, &at.key("axis"), loc)? == Vec3::ZERO {
                return Err(loc.invalid(&at.key("axis"), "the rotation axis must not be zero"));
            }
            Ok(())
        }
    }
}

fn compare(raw: &RawCompare, loc: &Locator) -> Result<Compare, SceneError> {
    let at = |name| field(&["compare", name]);
    let defaults = Thresholds::default();
    let get = |value: Option<f32>, default: f32, name: &'static str| match value {
        None => Ok(default),
        Some(x) if x.is_finite() && x >= 0.0 => Ok(x),
        Some(_) => Err(loc.invalid(&at(name), "must be a finite number, at least 0")),
    };
    let thresholds = Thresholds {
        fail: get(raw.fail, defaults.fail, "fail")?,
        hard_fail: get(raw.hard_fail, defaults.hard_fail, "hard_fail")?,
        max_failing_fraction: get(
            raw.max_failing_fraction,
            defaults.max_failing_fraction,
            "max_failing_fraction",
        )?,
    };
    if thresholds.max_failing_fraction > 1.0 {
        return Err(loc.invalid(&at("max_failing_fraction"), "must be a fraction, at most 1"));
    }
    if raw.reason.trim().is_empty() {
        return Err(loc.invalid(&at("reason"), "say why the images may differ this much"));
    }
    Ok(Compare { thresholds, reason: raw.reason.trim().to_string() })
}
