//! The CPU reference rasterizer: draws triangle lists into a [`Framebuffer`] with the conventions of
//! the GPU path (wgpu on Vulkan), so that the two images can be compared pixel by pixel, and hands
//! the visible fragments to a shading callback in batches (the interpreter runs a batch of lanes at once).
//!
//! Conventions, all those of wgpu's defaults:
//!
//! - **Clip space** x, y in [-w, w] with y up; depth z/w in [0, 1]. The viewport is the whole
//!   framebuffer: `x_fb = (x/w + 1) * width/2`, `y_fb = (1 - y/w) * height/2`, so row 0 is the top.
//! - **Samples** are pixel centres, `(i + 0.5, j + 0.5)` for pixel `(i, j)`. Supersampling n×n is
//!   drawing into an `(n*width, n*height)` framebuffer and [`Framebuffer::downsample`]: the samples of
//!   pixel `(i, j)` are then the regular grid `(i + (a + 0.5)/n, j + (b + 0.5)/n)`, `a, b < n`, and
//!   derivatives are per sample step (as on a GPU rendering the larger image).
//! - **Coverage**: vertices snap to 1/256 pixel ([`SUBPIXEL_BITS`], what Mesa's llvmpipe/lavapipe and
//!   current desktop GPUs use) and edge functions are evaluated exactly in integers. A sample exactly
//!   on an edge belongs to the triangle only if the edge is a top edge (exactly horizontal, the
//!   triangle below it) or a left edge (the triangle to its right): the D3D/Vulkan top-left rule in
//!   framebuffer coordinates. Two triangles sharing an edge therefore cover each sample once.
//! - **Clipping** is done in homogeneous clip space against the near plane `z >= 0`, the far plane
//!   `z <= w` and a guard band on x and y (wide enough that only huge triangles are clipped there);
//!   triangles crossing the near plane keep their visible part. No face culling.
//! - **Interpolation** is perspective-correct, evaluated from the *original* triangle's vertices (so
//!   clipping changes coverage, never values): `a = Σ λᵢ aᵢ/wᵢ / Σ λᵢ/wᵢ`, λ the screen-space
//!   barycentrics. Components marked flat take the value of the provoking vertex, the first vertex of
//!   the triangle (`indices[3t]`), as Vulkan does.
//! - **Derivatives** are analytic: `ddx` is the derivative with respect to the framebuffer x
//!   coordinate (one pixel to the right), `ddy` with respect to the framebuffer y coordinate, which
//!   grows downwards (one row down), matching WGSL's `dpdx`/`dpdy`. A value that grows towards the top
//!   of the image has a negative `ddy`. Flat components have zero derivatives.
//! - **Depth** is z/w interpolated linearly in screen space, clamped to [0, 1], tested with `Less`
//!   against the depth buffer (cleared to 1.0) before shading (early depth test) and written when
//!   [`DrawOptions::depth_write`] is set.
//! - **Facing**: a triangle is front facing when it is counter-clockwise in clip space (y up), that is
//!   clockwise in framebuffer coordinates (wgpu's default `FrontFace::Ccw`).
//! - **Order**: the result is exactly that of drawing the triangles one at a time, in order, each
//!   fragment depth-tested and blended in turn. A batch never holds two fragments of one pixel: a
//!   fragment that passes the depth test at a pixel already waiting in the batch flushes the batch.
//!
//! Bad input never panics: a triangle with a non-finite position is skipped, as are triangles of zero
//! area and those entirely outside the view volume (counted in [`DrawStats`]); indices past the last
//! vertex and mismatched varyings are errors before anything is drawn. The rasterizer produces no NaN
//! or infinity from finite input.

mod batch;
mod clip;
mod coverage;
mod framebuffer;
mod interpolate;

pub use batch::Fragments;
pub use coverage::SUBPIXEL_BITS;
pub use framebuffer::{Blend, Framebuffer};

use batch::{Batcher, Record};
use clip::Clip;
use coverage::Coverage;
use interpolate::Interpolant;

/// The largest framebuffer width or height the rasterizer accepts (keeps its fixed-point edge
/// functions inside 64 bits, with the guard band).
pub const MAX_DIMENSION: u32 = 1 << 16;

/// Per-vertex values to interpolate (a shader's varyings), with the same vertex numbering as the
/// clip-space positions.
#[derive(Copy, Clone, Debug)]
pub struct Varyings<'a> {
    /// Values per vertex.
    pub components: usize,
    /// Vertex-major values: component `c` of vertex `i` at `data[i * components + c]`.
    pub data: &'a [f32],
    /// Which components are flat (taken from the provoking vertex); one per component, or empty
    /// when none is.
    pub flat: &'a [bool],
}

impl<'a> Varyings<'a> {
    /// No varyings: for depth-only draws and tests of coverage.
    pub fn none() -> Self {
        Varyings { components: 0, data: &[], flat: &[] }
    }

    /// Smooth (perspective-correct) varyings only.
    pub fn smooth(components: usize, data: &'a [f32]) -> Self {
        Varyings { components, data, flat: &[] }
    }

    fn is_flat(&self, component: usize) -> bool {
        self.flat.get(component).copied().unwrap_or(false)
    }
}

/// The fixed-function state of a draw (what the GPU pipeline fixes beside the shader).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct DrawOptions {
    /// How a shaded colour combines with the framebuffer.
    pub blend: Blend,
    /// Whether fragments that pass the depth test write their depth.
    pub depth_write: bool,
    /// The most fragments handed to the shading callback at once (0 is taken as 1).
    pub batch: usize,
}

impl Default for DrawOptions {
    /// Opaque drawing with depth writes, in batches of 128.
    fn default() -> Self {
        DrawOptions { blend: Blend::Replace, depth_write: true, batch: 128 }
    }
}

/// What a draw did, for tests and for `patina explain`-style reports.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct DrawStats {
    /// Triangles in the index list (a trailing incomplete triangle is ignored, as on the GPU).
    pub triangles: usize,
    /// Triangles skipped because a vertex position is NaN or infinite.
    pub invalid: usize,
    /// Triangles entirely outside the view volume.
    pub culled: usize,
    /// Triangles (or clipped pieces) skipped for having no area after snapping.
    pub degenerate: usize,
    /// Triangles that needed clipping.
    pub clipped: usize,
    /// Fragments that passed the depth test and were shaded.
    pub fragments: usize,
    /// Fragments that failed the depth test.
    pub occluded: usize,
    /// Calls of the shading callback.
    pub batches: usize,
}

/// Why a draw failed. Input errors are found before anything is drawn; a shading error stops the
/// draw with the framebuffer partly drawn.
#[derive(Clone, Debug, PartialEq)]
pub enum DrawError<E> {
    /// An index refers past the last vertex.
    IndexOutOfRange {
        /// Where in the index list.
        position: usize,
        /// The index.
        index: u32,
        /// How many vertices there are.
        vertices: usize,
    },
    /// The varyings do not have `components` values per vertex, or the flat mask has the wrong length.
    Varyings {
        /// Values expected (`vertices * components`), or mask entries expected.
        expected: usize,
        /// Values or mask entries given.
        found: usize,
    },
    /// The framebuffer's colour or depth buffer does not have `width * height` entries, or it is
    /// larger than [`MAX_DIMENSION`].
    Framebuffer {
        /// Width.
        width: u32,
        /// Height.
        height: u32,
    },
    /// The shading callback failed.
    Shade(E),
}

impl<E: std::fmt::Display> std::fmt::Display for DrawError<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DrawError::IndexOutOfRange { position, index, vertices } => {
                write!(f, "index {index} at position {position} is past the last of {vertices} vertices")
            }
            DrawError::Varyings { expected, found } => {
                write!(f, "varyings: expected {expected} values, found {found}")
            }
            DrawError::Framebuffer { width, height } => {
                write!(f, "framebuffer {width}x{height} has wrong buffer sizes or is too large")
            }
            DrawError::Shade(e) => write!(f, "shading failed: {e}"),
        }
    }
}

impl<E: std::error::Error + 'static> std::error::Error for DrawError<E> {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            DrawError::Shade(e) => Some(e),
            _ => None,
        }
    }
}

/// Rasterizes a triangle list (`indices` in threes into `clip`, the clip-space positions, and into
/// the varyings) into `fb`. `shade` receives batches of at most `options.batch` visible fragments
/// (after the early depth test) and writes one premultiplied RGBA colour per fragment into its second
/// argument (as long as the batch); the rasterizer then blends them into the framebuffer.
pub fn draw<E>(
    fb: &mut Framebuffer,
    clip: &[[f32; 4]],
    indices: &[u32],
    varyings: &Varyings,
    options: &DrawOptions,
    mut shade: impl FnMut(&Fragments, &mut [[f32; 4]]) -> Result<(), E>,
) -> Result<DrawStats, DrawError<E>> {
    let mut colours = Vec::with_capacity(options.batch.max(1));
    rasterize(fb, clip, indices, varyings, options, |fb, fragments| {
        colours.clear();
        colours.resize(fragments.count, [0.0; 4]);
        shade(fragments, &mut colours)?;
        fb.blend(&fragments.pixels, &colours, options.blend);
        Ok(())
    })
}

/// Rasterizes like [`draw`], depth tests and depth writes included, but leaves the colour buffer
/// to `on_batch`, which receives each batch of visible fragments with the framebuffer. Shading and
/// blending the batches later, in the order they came, gives exactly what [`draw`] gives: no
/// fragment's depth test depends on a colour, and no batch holds two fragments of one pixel.
pub fn rasterize<E>(
    fb: &mut Framebuffer,
    clip: &[[f32; 4]],
    indices: &[u32],
    varyings: &Varyings,
    options: &DrawOptions,
    mut on_batch: impl FnMut(&mut Framebuffer, &Fragments) -> Result<(), E>,
) -> Result<DrawStats, DrawError<E>> {
    validate(fb, clip, indices, varyings)?;
    let triangles = indices.len() / 3;
    let mut stats = DrawStats { triangles, ..DrawStats::default() };
    if fb.width == 0 || fb.height == 0 {
        return Ok(stats);
    }
    let guard = clip::guard_band(fb.width, fb.height);
    let mut batcher = Batcher::new(varyings, fb, options.batch.max(1));
    for t in 0..triangles {
        let tri = [indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]];
        let v = tri.map(|i| clip[i as usize]);
        if v.iter().flatten().any(|c| !c.is_finite()) {
            stats.invalid += 1;
            continue;
        }
        let polygon = match clip::clip_triangle(&v, guard) {
            Clip::Reject => {
                stats.culled += 1;
                continue;
            }
            Clip::Accept => clip::Polygon::from_triangle(&v),
            Clip::Clipped(polygon) => {
                stats.clipped += 1;
                *polygon
            }
        };
        let Some(interp) = Interpolant::new(&v, fb.width, fb.height) else {
            stats.degenerate += 1;
            continue;
        };
        let Some(snapped) = polygon.snap(fb.width, fb.height) else {
            stats.degenerate += 1;
            continue;
        };
        let screen = snapped.points();
        for k in 1..screen.len().saturating_sub(1) {
            let Some(cov) = Coverage::new([screen[0], screen[k], screen[k + 1]]) else {
                stats.degenerate += 1;
                continue;
            };
            let front = cov.front_facing();
            cov.for_each_sample(fb.width, fb.height, |x, y| {
                let pixel = y as usize * fb.width as usize + x as usize;
                let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                let depth = interp.depth(px, py);
                let passes = depth < fb.depth[pixel];
                if !passes {
                    stats.occluded += 1;
                    return Ok(());
                }
                let Some(sample) = interp.sample(px, py) else {
                    return Ok(());
                };
                if options.depth_write {
                    fb.depth[pixel] = depth;
                }
                stats.fragments += 1;
                let record = Record { x, y, depth, front, tri, sample };
                batcher.push(fb, record, &mut on_batch)
            })
            .map_err(DrawError::Shade)?;
        }
    }
    batcher.flush(fb, &mut on_batch).map_err(DrawError::Shade)?;
    stats.batches = batcher.batches();
    Ok(stats)
}

/// Checks everything that would make the draw index out of bounds, so that the loop never can.
fn validate<E>(
    fb: &Framebuffer,
    clip: &[[f32; 4]],
    indices: &[u32],
    varyings: &Varyings,
) -> Result<(), DrawError<E>> {
    let pixels = fb.width as usize * fb.height as usize;
    if fb.width > MAX_DIMENSION
        || fb.height > MAX_DIMENSION
        || fb.color.len() != pixels
        || fb.depth.len() != pixels
    {
        return Err(DrawError::Framebuffer { width: fb.width, height: fb.height });
    }
    let expected = clip.len() * varyings.components;
    if varyings.data.len() != expected {
        return Err(DrawError::Varyings { expected, found: varyings.data.len() });
    }
    if !varyings.flat.is_empty() && varyings.flat.len() != varyings.components {
        return Err(DrawError::Varyings { expected: varyings.components, found: varyings.flat.len() });
    }
    let used = indices.len() / 3 * 3;
    if let Some((position, &index)) =
        indices[..used].iter().enumerate().find(|(_, i)| **i as usize >= clip.len())
    {
        return Err(DrawError::IndexOutOfRange { position, index, vertices: clip.len() });
    }
    Ok(())
}
