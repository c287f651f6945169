//! Which samples a triangle covers: vertices snapped to a fixed-point grid, exact integer edge
//! functions, the top-left rule for samples on an edge, and one span per row.

/// Bits of sub-pixel precision: vertex positions are rounded to 1/256 pixel before coverage is
/// decided, as on the GPU (Vulkan's `subPixelPrecisionBits` is 8 on llvmpipe and most desktop GPUs).
pub const SUBPIXEL_BITS: u32 = 8;
const ONE: i64 = 1 << SUBPIXEL_BITS;
const HALF: i64 = ONE / 2;
/// Snapped coordinates must stay below this for edge functions to fit in i64 (the guard band keeps
/// them below 2^28; anything larger is refused, not wrapped).
const LIMIT: f32 = (1u64 << 29) as f32;

/// A framebuffer position in units of 1/256 pixel, y down.
pub(super) type ScreenPoint = [i64; 2];

/// Projects a clip-space vertex to the framebuffer and snaps it, in f32 as the GPU's viewport
/// transform does. `None` unless `w > 0` and the result is in range.
pub(super) fn snap(v: [f32; 4], width: u32, height: u32) -> Option<ScreenPoint> {
    let [x, y, _, w] = v;
    if w.is_nan() || w <= 0.0 {
        return None;
    }
    let (hw, hh) = (width as f32 * 0.5, height as f32 * 0.5);
    let fx = ((x / w) * hw + hw) * ONE as f32;
    let fy = (hh - (y / w) * hh) * ONE as f32;
    if !(fx.abs() < LIMIT && fy.abs() < LIMIT) {
        return None;
    }
    Some([fx.round_ties_even() as i64, fy.round_ties_even() as i64])
}

/// One edge function, scaled so that it is positive inside: `a (x - x0) + b (y - y0)`.
#[derive(Copy, Clone, Debug)]
struct Edge {
    origin: ScreenPoint,
    a: i64,
    b: i64,
    /// 0 where a sample on the edge is covered (top and left edges), 1 where it is not.
    bias: i64,
}

impl Edge {
    fn eval(&self, x: i64, y: i64) -> i64 {
        self.a * (x - self.origin[0]) + self.b * (y - self.origin[1])
    }
}

/// A snapped triangle with non-zero area, ready to enumerate its samples.
#[derive(Clone, Debug)]
pub(super) struct Coverage {
    verts: [ScreenPoint; 3],
    edges: [Edge; 3],
    front_facing: bool,
}

impl Coverage {
    /// `None` for a triangle with zero area on the sub-pixel grid (it covers nothing).
    pub(super) fn new(verts: [ScreenPoint; 3]) -> Option<Self> {
        let [[x0, y0], [x1, y1], [x2, y2]] = verts;
        let area2 = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
        if area2 == 0 {
            return None;
        }
        let s = area2.signum();
        let edges = [0, 1, 2].map(|k| {
            let (from, to) = (verts[(k + 1) % 3], verts[(k + 2) % 3]);
            let a = -s * (to[1] - from[1]);
            let b = s * (to[0] - from[0]);
            // Left: the inside is to the right (a > 0). Top: horizontal, inside below (y grows down).
            let top_left = a > 0 || (a == 0 && b > 0);
            Edge { origin: from, a, b, bias: if top_left { 0 } else { 1 } }
        });
        // y grows downwards, so a negative area is clockwise on screen: counter-clockwise in NDC.
        Some(Coverage { verts, edges, front_facing: area2 < 0 })
    }

    /// Whether the triangle is front facing (counter-clockwise in clip space, y up).
    pub(super) fn front_facing(&self) -> bool {
        self.front_facing
    }

    fn covers(&self, x: i64, y: i64) -> bool {
        self.edges.iter().all(|e| e.eval(x, y) >= e.bias)
    }

    /// Calls `visit(i, j)` for every pixel `(i, j)` of a `width × height` framebuffer whose centre
    /// the triangle covers, row by row; stops at the first error.
    pub(super) fn for_each_sample<E>(
        &self,
        width: u32,
        height: u32,
        mut visit: impl FnMut(u32, u32) -> Result<(), E>,
    ) -> Result<(), E> {
        let xs = self.verts.map(|v| v[0]);
        let ys = self.verts.map(|v| v[1]);
        let (lo_x, hi_x) = sample_range(min3(xs), max3(xs), width);
        let (lo_y, hi_y) = sample_range(min3(ys), max3(ys), height);
        for j in lo_y..=hi_y {
            let y = j * ONE + HALF;
            let Some((lo, hi)) = self.span(lo_x, hi_x, y) else { continue };
            for i in lo..=hi {
                debug_assert!(self.covers(i * ONE + HALF, y));
                // The ranges are clamped to the framebuffer, so both fit in u32.
                visit(i as u32, j as u32)?;
            }
        }
        Ok(())
    }

    /// The covered pixels of one row, solved exactly from each edge's integer inequality
    /// `e + k·a·ONE >= bias` for the step `k` from `lo`.
    fn span(&self, mut lo: i64, mut hi: i64, y: i64) -> Option<(i64, i64)> {
        let x0 = lo * ONE + HALF;
        let first = lo;
        for e in &self.edges {
            let at = e.eval(x0, y);
            let step = e.a * ONE;
            if step > 0 {
                lo = lo.max(first + ceil_div(e.bias - at, step));
            } else if step < 0 {
                hi = hi.min(first + (at - e.bias).div_euclid(-step));
            } else if at < e.bias {
                return None;
            }
        }
        (lo <= hi).then_some((lo, hi))
    }
}

/// The pixels whose centres lie in `[lo, hi]` (fixed point), clamped to `0..size`; empty when
/// `lo > hi`.
fn sample_range(lo: i64, hi: i64, size: u32) -> (i64, i64) {
    (ceil_div(lo - HALF, ONE).max(0), (hi - HALF).div_euclid(ONE).min(i64::from(size) - 1))
}

fn ceil_div(n: i64, d: i64) -> i64 {
    -(-n).div_euclid(d)
}

fn min3(v: [i64; 3]) -> i64 {
    v[0].min(v[1]).min(v[2])
}

fn max3(v: [i64; 3]) -> i64 {
    v[0].max(v[1]).max(v[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn px(x: f64, y: f64) -> ScreenPoint {
        [(x * ONE as f64) as i64, (y * ONE as f64) as i64]
    }

    fn samples(tri: [ScreenPoint; 3], w: u32, h: u32) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        if let Some(c) = Coverage::new(tri) {
            c.for_each_sample(w, h, |i, j| {
                out.push((i, j));
                Ok::<(), ()>(())
            })
            .unwrap();
        }
        out
    }

    #[test]
    fn snapping_follows_the_viewport_transform() {
        // NDC (-1, 1) is the top-left corner, (1, -1) the bottom-right; w divides.
        assert_eq!(snap([-2.0, 2.0, 0.0, 2.0], 8, 4), Some([0, 0]));
        assert_eq!(snap([1.0, -1.0, 0.5, 1.0], 8, 4), Some([8 * ONE, 4 * ONE]));
        assert_eq!(snap([0.0, 0.0, 0.5, 0.0], 8, 4), None);
        assert_eq!(snap([f32::MAX, 0.0, 0.5, 1e-30], 8, 4), None);
    }

    #[test]
    fn rectangle_edges_through_centres_follow_the_top_left_rule() {
        // Left x = 1.5 and top y = 1.5 are kept, right x = 5.5 and bottom y = 5.5 are not; each
        // centre on the shared diagonal (2.5, 2.5), (3.5, 3.5), ... goes to exactly one triangle.
        let (a, b, c, d) = (px(1.5, 1.5), px(5.5, 1.5), px(5.5, 5.5), px(1.5, 5.5));
        let mut all = samples([a, b, c], 8, 8);
        all.extend(samples([a, c, d], 8, 8));
        all.sort();
        let expected: Vec<_> = (1..5).flat_map(|i| (1..5).map(move |j| (i, j))).collect();
        assert_eq!(all, expected);
    }

    #[test]
    fn winding_does_not_change_coverage_but_sets_facing() {
        let (a, b, c) = (px(0.3, 0.2), px(6.1, 1.7), px(2.2, 7.9));
        let mut cw = samples([a, b, c], 8, 8);
        let mut ccw = samples([a, c, b], 8, 8);
        cw.sort();
        ccw.sort();
        assert_eq!(cw, ccw);
        let facing = |t| Coverage::new(t).map(|c| c.front_facing());
        assert_eq!(facing([a, b, c]), Some(false));
        assert_eq!(facing([a, c, b]), Some(true));
        assert_eq!(facing([a, a, b]), None);
    }

    #[test]
    fn spans_agree_with_testing_every_sample() {
        let mut seed = 0x2545_f491_u64;
        let mut next = move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 33) % (24 * ONE as u64)) as i64 - 4 * ONE
        };
        for _ in 0..300 {
            let tri = [[next(), next()], [next(), next()], [next(), next()]];
            let Some(c) = Coverage::new(tri) else { continue };
            let mut brute = Vec::new();
            for j in 0..16 {
                for i in 0..16 {
                    if c.covers(i * ONE + HALF, j * ONE + HALF) {
                        brute.push((i as u32, j as u32));
                    }
                }
            }
            let mut spans = samples(tri, 16, 16);
            spans.sort_by_key(|&(i, j)| (j, i));
            brute.sort_by_key(|&(i, j)| (j, i));
            assert_eq!(spans, brute);
        }
    }
}
