//! The pinhole camera and RenderMan's chain of viewing spaces.
//!
//! Matrices follow glam's column-vector convention, `p' = M * p`. RenderMan (and the interpreter's
//! `transform`) write points as row vectors, `p' = p * R` with `R = Mᵀ`; since glam stores
//! matrices by columns, `M.to_cols_array()` is exactly `R` read row by row, ready for a shader's
//! space matrices.
//!
//! The spaces, as RenderMan defines them (RI spec, "Camera model"):
//!
//! - **camera**: the eye at the origin looking down +z, x to the right and y up. This is a
//!   *left-handed* frame, and it is a shader's "current" space: `P`, `N`, `I` and the light
//!   positions arrive in it. World space is read left-handed too, so [`Camera::world_to_camera`]
//!   is a rotation and translation (determinant +1): with `from` at the origin, `to` on +z and
//!   `up` = +y it is the identity. Geometry wound as [`crate::mesh`] describes therefore appears
//!   clockwise on screen where it faces the eye.
//! - **screen**: the perspective projection. x and y are divided by z and scaled so that the
//!   vertical field of view spans y ∈ [−1, 1] and x ∈ [−aspect, aspect] (RenderMan's default screen
//!   window for aspect ≥ 1; Patina's `fov` is always vertical, where RenderMan's applies to the
//!   shorter side). z is the depth below, 0 at `near` and 1 at `far`.
//! - **NDC**: the screen window mapped to [0, 1]², (0, 0) at the top-left, y down.
//! - **raster**: NDC scaled to pixels; pixel (i, j) covers [i, i+1] × [j, j+1], so its centre is
//!   at (i + ½, j + ½). This is also wgpu's framebuffer position (`@builtin(position).xy`).
//!
//! [`Camera::camera_to_clip`] is the matrix for wgpu: clip x and y in [−1, 1] with y up, depth z/w
//! in [0, 1] with `near` at 0 (the same depth as screen space), w = camera-space z.

use glam::{Mat4, Vec3, Vec4};

/// A pinhole camera placed in world space, with its projection settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The eye position.
    pub from: Vec3,
    /// The point looked at; it lands on the centre of the image.
    pub to: Vec3,
    /// Which way is up; only its component perpendicular to the viewing direction matters.
    pub up: Vec3,
    /// The vertical field of view in degrees, in (0, 180).
    pub fov_y_degrees: f32,
    /// The near clipping distance (camera-space z), > 0.
    pub near: f32,
    /// The far clipping distance, > `near`.
    pub far: f32,
}

impl Camera {
    /// The camera's unit right, up and forward vectors in world space: the rows of the rotation
    /// in [`Camera::world_to_camera`].
    ///
    /// A degenerate setup still gives an orthonormal frame rather than NaN (scenes reject these
    /// setups when they are loaded; this is only a guard): `from == to` looks down +z, and an `up`
    /// parallel to the view is replaced by +y, or +z when the view is vertical.
    pub fn basis(&self) -> (Vec3, Vec3, Vec3) {
        let forward = (self.to - self.from).try_normalize().unwrap_or(Vec3::Z);
        let right = [self.up, Vec3::Y, Vec3::Z]
            .into_iter()
            .find_map(|up| up.cross(forward).try_normalize().filter(|r| r.is_finite()))
            .unwrap_or(Vec3::X);
        // right × up = forward with these three: a rotation, not a reflection.
        (right, forward.cross(right), forward)
    }

    /// World to RenderMan camera space (eye at the origin, looking down +z, left-handed).
    pub fn world_to_camera(&self) -> Mat4 {
        let (r, u, f) = self.basis();
        let from = if self.from.is_finite() { self.from } else { Vec3::ZERO };
        Mat4::from_cols(
            Vec4::new(r.x, u.x, f.x, 0.0),
            Vec4::new(r.y, u.y, f.y, 0.0),
            Vec4::new(r.z, u.z, f.z, 0.0),
            Vec4::new(-r.dot(from), -u.dot(from), -f.dot(from), 1.0),
        )
    }

    /// Camera to world space: the inverse of [`Camera::world_to_camera`], computed exactly.
    pub fn camera_to_world(&self) -> Mat4 {
        let (r, u, f) = self.basis();
        let from = if self.from.is_finite() { self.from } else { Vec3::ZERO };
        Mat4::from_cols(r.extend(0.0), u.extend(0.0), f.extend(0.0), from.extend(1.0))
    }

    /// The near and far distances as the matrices use them: `near` > 0 (else 0.01) and
    /// `far` > `near` (else `near` × 1000).
    pub fn clip_range(&self) -> (f32, f32) {
        let near = if self.near.is_finite() && self.near > 0.0 { self.near } else { 0.01 };
        let far = if self.far.is_finite() && self.far > near { self.far } else { near * 1000.0 };
        (near, far)
    }

    /// `1 / tan(fov / 2)`, the focal length for a screen window of half-height 1; the field of
    /// view is clamped into [0.001°, 179.9°] (NaN becomes 90°).
    fn focal(&self) -> f32 {
        let fov = if self.fov_y_degrees.is_nan() { 90.0 } else { self.fov_y_degrees.clamp(1e-3, 179.9) };
        1.0 / (0.5 * fov.to_radians()).tan()
    }

    /// Camera space to wgpu clip space for an image of `aspect` = width / height (a non-positive
    /// or non-finite aspect counts as 1): x, y in [−1, 1] with y up, depth z/w in [0, 1].
    pub fn camera_to_clip(&self, aspect: f32) -> Mat4 {
        let aspect = sane_aspect(aspect);
        self.projection(self.focal() / aspect)
    }

    /// World space straight to clip space.
    pub fn world_to_clip(&self, aspect: f32) -> Mat4 {
        self.camera_to_clip(aspect) * self.world_to_camera()
    }

    /// Camera to RenderMan screen space (projective: divide by w). z is the [0, 1] depth; the
    /// image covers the screen window [−aspect, aspect] × [−1, 1], which is why the matrix itself
    /// does not depend on the aspect ratio.
    pub fn camera_to_screen(&self) -> Mat4 {
        self.projection(self.focal())
    }

    /// Screen space to NDC: the screen window onto [0, 1]², top-left first, y down; z unchanged.
    pub fn screen_to_ndc(aspect: f32) -> Mat4 {
        let aspect = sane_aspect(aspect);
        Mat4::from_cols(
            Vec4::new(0.5 / aspect, 0.0, 0.0, 0.0),
            Vec4::new(0.0, -0.5, 0.0, 0.0),
            Vec4::Z,
            Vec4::new(0.5, 0.5, 0.0, 1.0),
        )
    }

    /// Camera to RenderMan NDC space (projective).
    pub fn camera_to_ndc(&self, aspect: f32) -> Mat4 {
        Camera::screen_to_ndc(aspect) * self.camera_to_screen()
    }

    /// Camera to raster space for a `width × height` image (projective): pixel units, origin at
    /// the top-left corner, y down. A zero size counts as 1.
    pub fn camera_to_raster(&self, width: u32, height: u32) -> Mat4 {
        let (w, h) = (width.max(1) as f32, height.max(1) as f32);
        Mat4::from_scale(Vec3::new(w, h, 1.0)) * self.camera_to_ndc(w / h)
    }

    /// The perspective matrix with the given x focal length and the vertical one from `fov`.
    fn projection(&self, focal_x: f32) -> Mat4 {
        let (near, far) = self.clip_range();
        let depth = far / (far - near);
        Mat4::from_cols(
            Vec4::new(focal_x, 0.0, 0.0, 0.0),
            Vec4::new(0.0, self.focal(), 0.0, 0.0),
            Vec4::new(0.0, 0.0, depth, 1.0),
            Vec4::new(0.0, 0.0, -near * depth, 0.0),
        )
    }
}

fn sane_aspect(aspect: f32) -> f32 {
    if aspect.is_finite() && aspect > 0.0 { aspect } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            from: Vec3::new(1.0, 2.0, -5.0),
            to: Vec3::new(0.5, 0.0, 1.0),
            up: Vec3::Y,
            fov_y_degrees: 40.0,
            near: 0.5,
            far: 50.0,
        }
    }

    fn clip_of(c: &Camera, world: Vec3) -> Vec3 {
        c.world_to_clip(1.5).project_point3(world)
    }

    #[test]
    fn the_default_frame_is_the_identity() {
        let c = Camera { from: Vec3::ZERO, to: Vec3::Z, ..camera() };
        assert!(c.world_to_camera().abs_diff_eq(Mat4::IDENTITY, 1e-6));
    }

    #[test]
    fn the_look_at_point_is_the_screen_centre() {
        let c = camera();
        let p = clip_of(&c, c.to);
        assert!(p.x.abs() < 1e-5 && p.y.abs() < 1e-5, "{p}");
        let raster = c.camera_to_raster(300, 200).project_point3(c.world_to_camera().transform_point3(c.to));
        assert!((raster.x - 150.0).abs() < 1e-3 && (raster.y - 100.0).abs() < 1e-3, "{raster}");
    }

    #[test]
    fn camera_space_looks_down_positive_z_with_x_right_and_y_up() {
        let c = camera();
        let (right, up, forward) = c.basis();
        let m = c.world_to_camera();
        let distance = (c.to - c.from).length();
        assert!(m.transform_point3(c.to).abs_diff_eq(Vec3::new(0.0, 0.0, distance), 1e-5));
        assert!(m.transform_vector3(right).abs_diff_eq(Vec3::X, 1e-6));
        assert!(m.transform_vector3(up).abs_diff_eq(Vec3::Y, 1e-6));
        assert!((m.determinant() - 1.0).abs() < 1e-5, "a rotation, not a reflection");
        assert!(clip_of(&c, c.to + right).x > 0.0 && clip_of(&c, c.to + up).y > 0.0);
        assert!(c.camera_to_world().mul_mat4(&m).abs_diff_eq(Mat4::IDENTITY, 1e-5));
        assert!(forward.dot(c.to - c.from) > 0.0);
    }

    #[test]
    fn depth_runs_from_zero_at_near_to_one_at_far() {
        let c = camera();
        let proj = c.camera_to_clip(1.5);
        let depth = |z: f32| proj.project_point3(Vec3::new(0.1, -0.2, z)).z;
        assert!(depth(c.near).abs() < 1e-6);
        assert!((depth(c.far) - 1.0).abs() < 1e-6);
        let mut last = depth(c.near);
        for z in [0.6, 1.0, 3.0, 10.0, 49.0] {
            assert!(depth(z) > last);
            last = depth(z);
        }
        assert_eq!(proj.mul_vec4(Vec4::new(0.0, 0.0, 7.0, 1.0)).w, 7.0, "w is camera-space z");
    }

    #[test]
    fn the_field_of_view_spans_the_vertical() {
        let c = Camera { from: Vec3::ZERO, to: Vec3::Z, fov_y_degrees: 90.0, ..camera() };
        let top = c.camera_to_clip(2.0).project_point3(Vec3::new(0.0, 3.0, 3.0));
        let side = c.camera_to_clip(2.0).project_point3(Vec3::new(6.0, 0.0, 3.0));
        assert!((top.y - 1.0).abs() < 1e-6 && (side.x - 1.0).abs() < 1e-6);
        let screen = c.camera_to_screen().project_point3(Vec3::new(6.0, 3.0, 3.0));
        assert!(screen.abs_diff_eq(Vec3::new(2.0, 1.0, screen.z), 1e-6));
        let ndc = c.camera_to_ndc(2.0).project_point3(Vec3::new(-6.0, 3.0, 3.0));
        assert!(ndc.abs_diff_eq(Vec3::new(0.0, 0.0, ndc.z), 1e-6), "top-left is NDC (0, 0): {ndc}");
    }

    #[test]
    fn degenerate_cameras_give_finite_matrices() {
        let bad = [
            Camera { to: Vec3::new(1.0, 2.0, -5.0), ..camera() },
            Camera { up: Vec3::new(-0.5, -2.0, 6.0), ..camera() },
            Camera { up: Vec3::ZERO, from: Vec3::ZERO, to: Vec3::Y, ..camera() },
            Camera { fov_y_degrees: 0.0, near: -1.0, far: f32::NAN, ..camera() },
            Camera { fov_y_degrees: 180.0, near: 0.0, far: 0.0, ..camera() },
        ];
        for c in bad {
            let m = c.world_to_clip(0.0) * c.camera_to_raster(0, 0);
            assert!(m.is_finite(), "{c:?}");
        }
    }
}
