//! Clipping in homogeneous clip space: against the near plane `z >= 0` (which also removes every
//! point with `w <= 0`), the far plane `z <= w`, and a guard band `|x|, |y| <= g w` that keeps
//! snapped screen coordinates small enough for exact 64-bit edge functions.

use super::coverage::{self, ScreenPoint};

/// At most 3 vertices plus one per plane for a convex polygon; the rest is headroom for rounding.
const CAPACITY: usize = 16;

/// Screen coordinates stay within about 2^19 pixels of the origin, whatever the framebuffer size.
const GUARD_PIXELS: f64 = (1u64 << 20) as f64;

/// The guard band half-width in NDC units for a framebuffer (at least the viewport itself).
pub(super) fn guard_band(width: u32, height: u32) -> f64 {
    (GUARD_PIXELS / f64::from(width.max(height).max(1))).max(1.0)
}

/// What clipping left of a triangle.
pub(super) enum Clip {
    /// Wholly inside: draw the triangle as it is.
    Accept,
    /// Wholly outside one plane (or clipped away to nothing).
    Reject,
    /// Partly inside: the visible convex polygon, in the triangle's winding order.
    Clipped(Box<Polygon>),
}

/// A convex polygon in clip space.
pub(super) struct Polygon {
    verts: [[f64; 4]; CAPACITY],
    len: usize,
}

/// A clipped polygon's vertices snapped to the sub-pixel grid.
pub(super) struct Snapped {
    points: [ScreenPoint; CAPACITY],
    len: usize,
}

impl Snapped {
    /// The vertices, in order.
    pub(super) fn points(&self) -> &[ScreenPoint] {
        &self.points[..self.len]
    }
}

impl Polygon {
    /// The triangle itself (f32 to f64 and back is exact, so an accepted triangle snaps as given).
    pub(super) fn from_triangle(v: &[[f32; 4]; 3]) -> Self {
        let mut p = Polygon { verts: [[0.0; 4]; CAPACITY], len: 3 };
        for (dst, src) in p.verts.iter_mut().zip(v) {
            *dst = src.map(f64::from);
        }
        p
    }

    fn vertices(&self) -> &[[f64; 4]] {
        &self.verts[..self.len]
    }

    fn push(&mut self, v: [f64; 4]) -> bool {
        if self.len == CAPACITY {
            return false;
        }
        self.verts[self.len] = v;
        self.len += 1;
        true
    }

    /// Projects and snaps every vertex; `None` if one is not strictly in front of the eye (only a
    /// polygon through the clip-space origin has one, and it has no area on screen).
    pub(super) fn snap(&self, width: u32, height: u32) -> Option<Snapped> {
        let mut out = Snapped { points: [[0; 2]; CAPACITY], len: self.len };
        for (dst, v) in out.points.iter_mut().zip(self.vertices()) {
            *dst = coverage::snap(v.map(|c| c as f32), width, height)?;
        }
        Some(out)
    }
}

/// Signed distances to the six planes; a point is inside where all are >= 0.
fn distances(v: [f64; 4], guard: f64) -> [f64; 6] {
    let [x, y, z, w] = v;
    [z, w - z, x + guard * w, guard * w - x, y + guard * w, guard * w - y]
}

/// Clips a triangle with finite vertices against the near and far planes and the guard band.
pub(super) fn clip_triangle(v: &[[f32; 4]; 3], guard: f64) -> Clip {
    let tri = Polygon::from_triangle(v);
    let d = [0, 1, 2].map(|i| distances(tri.verts[i], guard));
    let outside = |plane: usize| d.iter().filter(|d| d[plane] < 0.0).count();
    if (0..6).any(|plane| outside(plane) == 3) {
        return Clip::Reject;
    }
    let in_front = tri.vertices().iter().all(|p| p[3] > 0.0);
    if in_front && (0..6).all(|plane| outside(plane) == 0) {
        return Clip::Accept;
    }
    let mut poly = tri;
    for plane in 0..6 {
        if poly.vertices().iter().all(|&p| distances(p, guard)[plane] >= 0.0) {
            continue;
        }
        match clip_plane(&poly, plane, guard) {
            Some(next) if next.len >= 3 => poly = next,
            _ => return Clip::Reject,
        }
    }
    Clip::Clipped(Box::new(poly))
}

/// One Sutherland–Hodgman step. The intersection on an edge is always computed from its inside
/// end towards its outside end, so two triangles sharing the edge get the same point.
fn clip_plane(poly: &Polygon, plane: usize, guard: f64) -> Option<Polygon> {
    let mut out = Polygon { verts: [[0.0; 4]; CAPACITY], len: 0 };
    let verts = poly.vertices();
    for (i, &cur) in verts.iter().enumerate() {
        let next = verts[(i + 1) % verts.len()];
        let (dc, dn) = (distances(cur, guard)[plane], distances(next, guard)[plane]);
        if dc >= 0.0 && !out.push(cur) {
            return None;
        }
        if (dc >= 0.0) != (dn >= 0.0) {
            let (inside, outside, di, doo) =
                if dc >= 0.0 { (cur, next, dc, dn) } else { (next, cur, dn, dc) };
            let t = di / (di - doo);
            let p = std::array::from_fn(|c| inside[c] + t * (outside[c] - inside[c]));
            if !out.push(p) {
                return None;
            }
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clipped(v: [[f32; 4]; 3]) -> Vec<[f64; 4]> {
        match clip_triangle(&v, 1.0) {
            Clip::Clipped(p) => p.vertices().to_vec(),
            Clip::Accept => panic!("accepted"),
            Clip::Reject => panic!("rejected"),
        }
    }

    #[test]
    fn inside_triangle_is_accepted_and_outside_rejected() {
        let inside = [[0.0, 0.0, 0.5, 1.0], [0.5, 0.0, 0.5, 1.0], [0.0, 0.5, 0.5, 1.0]];
        assert!(matches!(clip_triangle(&inside, 1.0), Clip::Accept));
        let behind = [[0.0, 0.0, -0.5, 1.0], [0.5, 0.0, -0.1, 1.0], [0.0, 0.5, -2.0, -1.0]];
        assert!(matches!(clip_triangle(&behind, 1.0), Clip::Reject));
        let right = [[2.0, 0.0, 0.5, 1.0], [3.0, 0.0, 0.5, 1.0], [2.0, 0.5, 0.5, 1.0]];
        assert!(matches!(clip_triangle(&right, 1.0), Clip::Reject));
    }

    #[test]
    fn near_plane_cuts_off_the_vertex_behind() {
        // z goes from 1 at two vertices to -1 at the third: the cut is halfway along two edges.
        let p = clipped([[0.0, 0.0, -1.0, 1.0], [0.5, 0.0, 1.0, 1.0], [0.0, 0.5, 1.0, 1.0]]);
        assert_eq!(p.len(), 4);
        assert!(p.iter().all(|v| v[2] >= 0.0 && v[3] > 0.0));
        assert_eq!(p[0], [0.25, 0.0, 0.0, 1.0]);
        assert_eq!(p[3], [0.0, 0.25, 0.0, 1.0]);
    }

    #[test]
    fn shared_edge_is_cut_at_the_same_point_both_ways() {
        let a = [0.3f32, -0.2, -0.7, 0.9];
        let b = [-0.1f32, 0.4, 0.8, 1.3];
        let c = [0.5f32, 0.5, 0.5, 1.0];
        let d = [-0.5f32, -0.5, 0.5, 1.0];
        let one = clipped([a, b, c]);
        let two = clipped([b, a, d]);
        // Shared: the vertex b and the cut on the edge a-b, bit for bit.
        let shared = one.iter().filter(|v| two.contains(v)).count();
        assert_eq!(shared, 2);
    }
}
