//! Shadow maps: a depth pass from a light, drawn once by the CPU rasterizer (`crate::raster`) and
//! handed as the same texture to both backends, so that the interpreter and the GPU compare
//! against identical depths.
//!
//! The map of a `[[shadow]]` table is seen by a pinhole camera at the light's `from` looking at
//! its `to` (world space, from the light's `params`; the table's own `to` instead, for the faces
//! of a point light's cube), with the table's `fov` or else twice the light's `coneangle`
//! (radians, default 30°) plus 10°, square, `near` and `far` from the table. Every object's mesh is drawn undisplaced (a displacement shader does not move the
//! shadows it casts) with its transform; each texel holds the light-camera-space z of the nearest
//! surface through its centre, or 10³⁰ where there is none. The texture is `resolution` ×
//! (`resolution` + 1) texels: the last row's first four texels are the rows of the matrix from
//! the shader's current space (the scene camera's space) to the map's (x, y, depth, w), and the
//! fifth holds the table's `bias`: the layout compiler/src/opt/shadow.rs documents and reads. Spot and other local lights only: a point
//! light would need six maps and a distant light an orthographic one.

use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};
use patina_compiler::backend::cpu::Texture;

use super::RenderError;
use crate::camera::Camera;
use crate::raster::{self, DrawOptions, Framebuffer, Varyings};
use crate::scene::{ParamValue, Scene, ShadowMap};

/// The depth stored where the light sees no surface.
pub const EMPTY_DEPTH: f32 = 1e30;

/// The camera the map of `map` is drawn from.
pub fn light_camera(scene: &Scene, map: &ShadowMap) -> Result<Camera, RenderError> {
    let light = scene.lights.get(map.light).ok_or_else(|| {
        RenderError::Input(format!("shadow map `{}`: there is no light {}", map.name, map.light))
    })?;
    let point = |name: &str| match light.shader.params.get(name) {
        Some(ParamValue::Numbers(v)) if v.len() == 3 && v.iter().all(|x| x.is_finite()) => {
            Ok(Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32))
        }
        _ => Err(RenderError::Input(format!(
            "shadow map `{}`: light {} must set `{name}` (three numbers)",
            map.name, map.light
        ))),
    };
    let from = point("from")?;
    let to = match map.to {
        Some(to) => Vec3::from(to),
        None => point("to")?,
    };
    if (to - from).length() <= 0.0 {
        return Err(RenderError::Input(format!(
            "shadow map `{}`: it looks from light {}'s `from` at the same point",
            map.name, map.light
        )));
    }
    let fov = map.fov.unwrap_or_else(|| {
        let cone = match light.shader.params.get("coneangle") {
            Some(ParamValue::Number(a)) if a.is_finite() => *a as f32,
            _ => 30f32.to_radians(),
        };
        (2.0 * cone.to_degrees() + 10.0).clamp(1.0, 170.0)
    });
    let up = if (to - from).normalize().cross(Vec3::Y).length() < 1e-3 { Vec3::Z } else { Vec3::Y };
    Ok(Camera { from, to, up, fov_y_degrees: fov, near: map.near, far: map.far })
}

/// How a map sees the world: world to the light's camera space, and that to clip space (wgpu's:
/// x, y in [−w, w], depth z/w in [0, 1]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightView {
    /// World space to the light's camera space (looking down +z, left-handed).
    pub view: Mat4,
    /// The light's camera space to clip space: perspective, or orthographic (w = 1).
    pub projection: Mat4,
}

/// One object's mesh in world space: its positions and triangles.
type WorldMesh = (Vec<Vec3>, Vec<u32>);

/// The meshes of `scene` in world space.
fn world_meshes(scene: &Scene) -> Result<Vec<WorldMesh>, RenderError> {
    (scene.objects.iter().enumerate())
        .map(|(i, o)| {
            let mesh = o
                .build_mesh()
                .map_err(|e| RenderError::Input(format!("{}: object {i}: {e}", scene.file.display())))?;
            let m = scene.object_transform(i);
            Ok((mesh.positions.iter().map(|p| m.transform_point3(Vec3::from(*p))).collect(), mesh.indices))
        })
        .collect()
}

/// The view of `map`: [`light_camera`]'s, in perspective, or for an orthographic map a square
/// window just wider than every mesh (5% margin) and a depth range just deeper.
pub fn light_view(scene: &Scene, map: &ShadowMap) -> Result<LightView, RenderError> {
    let meshes = if map.orthographic { world_meshes(scene)? } else { Vec::new() };
    view_of(scene, map, &meshes)
}

fn view_of(
    scene: &Scene,
    map: &ShadowMap,
    meshes: &[(Vec<Vec3>, Vec<u32>)],
) -> Result<LightView, RenderError> {
    let light = light_camera(scene, map)?;
    let view = light.world_to_camera();
    if !map.orthographic {
        return Ok(LightView { view, projection: light.camera_to_clip(1.0) });
    }
    let (mut half, mut near, mut far) = (1e-3f32, f32::MAX, f32::MIN);
    for p in meshes.iter().flat_map(|(p, _)| p) {
        let q = view.transform_point3(*p);
        if q.is_finite() {
            half = half.max(q.x.abs()).max(q.y.abs());
            (near, far) = (near.min(q.z), far.max(q.z));
        }
    }
    if near > far {
        (near, far) = (0.0, 1.0);
    }
    let (half, depth) = (half * 1.05, (far - near).max(1e-3) * 1.1);
    let near = near - 0.05 * depth;
    let projection = Mat4::from_cols(
        Vec4::new(1.0 / half, 0.0, 0.0, 0.0),
        Vec4::new(0.0, 1.0 / half, 0.0, 0.0),
        Vec4::new(0.0, 0.0, 1.0 / depth, 0.0),
        Vec4::new(0.0, 0.0, -near / depth, 1.0),
    );
    Ok(LightView { view, projection })
}

/// Draws the shadow map `map` of `scene` for a shader whose current space is the one
/// `world_to_camera` leads to.
pub fn make(scene: &Scene, map: &ShadowMap, world_to_camera: Mat4) -> Result<Texture, RenderError> {
    let meshes = world_meshes(scene)?;
    let light = view_of(scene, map, &meshes)?;
    let n = map.resolution.max(8);
    let to_clip = light.projection * light.view;
    let mut fb = Framebuffer::new(n, n, [EMPTY_DEPTH; 4]);
    let options = DrawOptions { depth_write: true, ..DrawOptions::default() };
    for (i, (positions, indices)) in meshes.iter().enumerate() {
        let clip: Vec<[f32; 4]> = positions.iter().map(|p| (to_clip * p.extend(1.0)).to_array()).collect();
        let depth: Vec<f32> = positions.iter().map(|p| light.view.transform_point3(*p).z).collect();
        let varyings = Varyings::smooth(1, &depth);
        raster::draw(&mut fb, &clip, indices, &varyings, &options, |fragments, out| {
            for (o, z) in out.iter_mut().zip(fragments.values_of(0)) {
                *o = [*z, *z, *z, 1.0];
            }
            Ok::<(), std::convert::Infallible>(())
        })
        .map_err(|e| RenderError::Input(format!("shadow map `{}`: object {i}: {e:?}", map.name)))?;
    }
    let mut texels: Vec<[f32; 4]> = fb.color;
    let m = matrix(&light, world_to_camera);
    let mut last = vec![[0.0f32; 4]; n as usize];
    for (r, texel) in last.iter_mut().take(4).enumerate() {
        *texel = m.row(r).to_array();
    }
    last[4] = [map.bias, 0.0, 0.0, 0.0];
    texels.extend(last);
    Ok(Texture { size: [n, n + 1, 1], texels: Arc::from(texels) })
}

/// The matrix from the shader's current space to the map's (x, y, depth, w): clip x, y and w of
/// the light's view, and its camera-space z as the depth.
pub fn matrix(light: &LightView, world_to_camera: Mat4) -> Mat4 {
    let camera_to_light = light.view * world_to_camera.inverse();
    let clip = light.projection * camera_to_light;
    Mat4::from_cols(clip.row(0), clip.row(1), camera_to_light.row(2), clip.row(3)).transpose()
}

/// Where the map sees `world` (a world-space point): the texel and the point's depth, `None`
/// when it is behind the light or outside the map.
pub fn project(light: &LightView, resolution: u32, world: Vec3) -> Option<([u32; 2], f32)> {
    let view = light.view.transform_point3(world);
    let clip = light.projection * Vec4::from((view, 1.0));
    if clip.w <= 0.0 {
        return None;
    }
    let (s, t) = (0.5 + 0.5 * clip.x / clip.w, 0.5 - 0.5 * clip.y / clip.w);
    let n = resolution as f32;
    ((0.0..1.0).contains(&s) && (0.0..1.0).contains(&t)).then_some(([(s * n) as u32, (t * n) as u32], view.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matrix_takes_camera_space_to_the_light_view() {
        let eye = Camera {
            from: Vec3::new(0.0, 2.0, -6.0),
            to: Vec3::ZERO,
            up: Vec3::Y,
            fov_y_degrees: 40.0,
            near: 0.1,
            far: 100.0,
        };
        let light = Camera {
            from: Vec3::new(3.0, 6.0, -2.0),
            to: Vec3::ZERO,
            up: Vec3::Y,
            fov_y_degrees: 60.0,
            near: 0.05,
            far: 1000.0,
        };
        let view = LightView { view: light.world_to_camera(), projection: light.camera_to_clip(1.0) };
        let m = matrix(&view, eye.world_to_camera());
        // The light's target is at the map's centre, at depth |to - from|.
        let target = m * eye.world_to_camera().transform_point3(Vec3::ZERO).extend(1.0);
        assert!((target.x / target.w).abs() < 1e-5 && (target.y / target.w).abs() < 1e-5, "{target}");
        assert!((target.z - 7.0).abs() < 1e-4, "{target}");
        assert!((target.w - 7.0).abs() < 1e-4, "{target}");
    }
}
