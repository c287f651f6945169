//! The orbit camera: the scene's camera turned about its `to` point (drag) and moved along its
//! line of sight (scroll), the scene's own camera being the start.

use glam::Vec3;
use patina::Camera;

/// Radians turned per pixel dragged.
const RADIANS_PER_PIXEL: f32 = 0.01;

/// How much nearer one line (notch) of scrolling brings the camera.
const ZOOM_PER_LINE: f32 = 0.9;

/// The camera never comes nearer than this fraction of its start distance, nor goes further than
/// its multiple, so that zooming cannot reach the `to` point or lose the scene.
const ZOOM_RANGE: (f32, f32) = (0.05, 20.0);

/// The orbit never quite reaches the poles of `up`, where the view's frame would flip.
const MAX_ELEVATION: f32 = 89.0 * std::f32::consts::PI / 180.0;

/// An orbit about the start camera's `to` point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    start: Camera,
    /// Radians about `up`; positive moves the camera to its left, turning the scene right.
    yaw: f32,
    /// Radians up from the start elevation.
    pitch: f32,
    /// The distance to `to` as a multiple of the start's.
    zoom: f32,
}

impl Orbit {
    /// An orbit starting at `camera`.
    pub fn new(camera: Camera) -> Orbit {
        Orbit { start: camera, yaw: 0.0, pitch: 0.0, zoom: 1.0 }
    }

    /// The start camera, a new one from the scene replacing the old: the orbit and zoom made so
    /// far are kept, so that an edit to the scene does not throw the view back.
    pub fn restart(&mut self, camera: Camera) {
        self.start = camera;
    }

    /// Back to the start camera.
    pub fn reset(&mut self) {
        *self = Orbit::new(self.start);
    }

    /// Turns by a drag of `dx`, `dy` pixels (right and down positive): dragging right turns the
    /// scene right, dragging down tips its top towards the viewer.
    pub fn drag(&mut self, dx: f64, dy: f64) {
        self.yaw += dx as f32 * RADIANS_PER_PIXEL;
        // Clamped where the elevation stops, so that dragging back turns back at once.
        let start = self.start_elevation();
        self.pitch =
            (self.pitch + dy as f32 * RADIANS_PER_PIXEL).clamp(-MAX_ELEVATION - start, MAX_ELEVATION - start);
    }

    /// The start camera's elevation above the plane across `up`, in radians.
    fn start_elevation(&self) -> f32 {
        let back = (self.start.from - self.start.to).try_normalize().unwrap_or(Vec3::Z);
        back.dot(self.up()).clamp(-1.0, 1.0).asin()
    }

    /// The start camera's `up`, of unit length.
    fn up(&self) -> Vec3 {
        self.start.up.try_normalize().unwrap_or(Vec3::Y)
    }

    /// Moves nearer by `lines` notches of a scroll wheel (negative: further).
    pub fn scroll(&mut self, lines: f32) {
        self.zoom = (self.zoom * ZOOM_PER_LINE.powf(lines)).clamp(ZOOM_RANGE.0, ZOOM_RANGE.1);
    }

    /// The camera now: the start's `from` turned about `to` by the orbit's yaw (about `up`) and
    /// pitch (towards `up`), at the zoomed distance; everything else as the start's.
    pub fn camera(&self) -> Camera {
        let start = self.start;
        if (self.yaw, self.pitch, self.zoom) == (0.0, 0.0, 1.0) {
            // Exactly the scene's camera, so that the first picture is `patina render`'s.
            return start;
        }
        let offset = start.from - start.to;
        let distance = offset.length();
        let Some(back) = offset.try_normalize() else { return start };
        let up = self.up();
        // A frame about `up`: `ahead` is the start direction's part across `up`.
        let ahead = (back - up * back.dot(up)).try_normalize().unwrap_or_else(|| up.any_orthonormal_vector());
        let side = up.cross(ahead);
        let elevation = (self.start_elevation() + self.pitch).clamp(-MAX_ELEVATION, MAX_ELEVATION);
        let (sin_yaw, cos_yaw) = self.yaw.sin_cos();
        let direction = (ahead * cos_yaw + side * sin_yaw) * elevation.cos() + up * elevation.sin();
        Camera { from: start.to + direction * distance * self.zoom, ..start }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene_camera() -> Camera {
        Camera {
            from: Vec3::new(0.0, 0.0, -4.0),
            to: Vec3::ZERO,
            up: Vec3::Y,
            fov_y_degrees: 40.0,
            near: 0.1,
            far: 100.0,
        }
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-4
    }

    #[test]
    fn the_start_is_the_scene_camera() {
        assert_eq!(Orbit::new(scene_camera()).camera(), scene_camera());
    }

    #[test]
    fn dragging_keeps_the_distance_and_the_point_looked_at() {
        let mut orbit = Orbit::new(scene_camera());
        orbit.drag(40.0, -25.0);
        let camera = orbit.camera();
        assert_eq!(camera.to, Vec3::ZERO);
        assert!((camera.from.length() - 4.0).abs() < 1e-4, "{camera:?}");
        assert_ne!(camera.from, scene_camera().from);
    }

    #[test]
    fn a_quarter_turn_about_up() {
        let mut orbit = Orbit::new(scene_camera());
        orbit.drag(-std::f64::consts::FRAC_PI_2 / f64::from(RADIANS_PER_PIXEL), 0.0);
        // Dragging left turns the scene left: the camera, from -z, goes to its right, +x (the
        // camera's right, `up` × forward, is +x there).
        assert!(close(orbit.camera().from, Vec3::new(4.0, 0.0, 0.0)), "{:?}", orbit.camera());
    }

    #[test]
    fn pitch_stops_short_of_the_pole() {
        let mut orbit = Orbit::new(scene_camera());
        orbit.drag(0.0, 1e6);
        let from = orbit.camera().from;
        assert!(from.y < 4.0 && from.y > 3.9, "{from:?}");
    }

    #[test]
    fn dragging_back_from_the_pole_turns_back_at_once() {
        let mut orbit = Orbit::new(scene_camera());
        orbit.drag(0.0, 1e6);
        let top = orbit.camera().from;
        orbit.drag(0.0, -10.0);
        assert!(orbit.camera().from.y < top.y - 0.01, "{:?}", orbit.camera());
    }

    #[test]
    fn zoom_is_bounded_and_reset_returns() {
        let mut orbit = Orbit::new(scene_camera());
        orbit.scroll(1000.0);
        assert!(close(orbit.camera().from, Vec3::new(0.0, 0.0, -4.0 * ZOOM_RANGE.0)));
        orbit.scroll(-1e4);
        assert!(close(orbit.camera().from, Vec3::new(0.0, 0.0, -4.0 * ZOOM_RANGE.1)));
        orbit.reset();
        assert_eq!(orbit.camera(), scene_camera());
    }
}
