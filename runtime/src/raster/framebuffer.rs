//! The render target of the CPU rasterizer: RGBA f32 colour and f32 depth, row 0 at the top.

/// How a shaded colour combines with the colour already in the framebuffer.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Blend {
    /// The shaded colour replaces what was there.
    #[default]
    Replace,
    /// Premultiplied-alpha "over": `src + dst * (1 - src.a)`, for colour and alpha alike (wgpu's
    /// `BlendState::PREMULTIPLIED_ALPHA_BLENDING`).
    PremultipliedOver,
}

impl Blend {
    /// The framebuffer's new value when `src` is drawn over `dst`.
    pub fn apply(self, src: [f32; 4], dst: [f32; 4]) -> [f32; 4] {
        match self {
            Blend::Replace => src,
            Blend::PremultipliedOver => {
                let k = 1.0 - src[3];
                std::array::from_fn(|c| src[c] + dst[c] * k)
            }
        }
    }
}

/// A colour and depth buffer, row-major with row 0 at the top: pixel `(x, y)` at `y * width + x`.
#[derive(Clone, Debug, PartialEq)]
pub struct Framebuffer {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// RGBA per pixel (premultiplied when blending with [`Blend::PremultipliedOver`]).
    pub color: Vec<[f32; 4]>,
    /// Depth per pixel, in [0, 1]; 1.0 is the far plane.
    pub depth: Vec<f32>,
}

impl Framebuffer {
    /// A framebuffer cleared to `clear` with depth 1.0, as the GPU path clears its targets.
    pub fn new(width: u32, height: u32, clear: [f32; 4]) -> Self {
        let n = width as usize * height as usize;
        Framebuffer { width, height, color: vec![clear; n], depth: vec![1.0; n] }
    }

    /// The colour of pixel `(x, y)`, if it is inside.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[f32; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.color.get(y as usize * self.width as usize + x as usize).copied()
    }

    /// Blends one shaded colour per pixel of `pixels` into the colour buffer, in order (so a
    /// pixel listed twice gets the later colour over the earlier). Pixels outside are skipped.
    pub fn blend(&mut self, pixels: &[(u32, u32)], colours: &[[f32; 4]], blend: Blend) {
        for (&(x, y), &src) in pixels.iter().zip(colours) {
            if x < self.width && y < self.height {
                let dst = &mut self.color[y as usize * self.width as usize + x as usize];
                *dst = blend.apply(src, *dst);
            }
        }
    }

    /// Resolves an n×n supersampled image: each output pixel is the mean of an n×n block (a box
    /// filter over the regular grid of sample positions); depth is the block's nearest. A partial
    /// block at the right or bottom edge is dropped; `n` of 0 is taken as 1.
    pub fn downsample(&self, n: u32) -> Framebuffer {
        let n = n.max(1);
        let (w, h) = (self.width / n, self.height / n);
        let mut out = Framebuffer::new(w, h, [0.0; 4]);
        let scale = 1.0 / (n * n) as f32;
        for y in 0..h {
            for x in 0..w {
                let mut sum = [0.0f32; 4];
                let mut near = 1.0f32;
                for j in 0..n {
                    let row = (y * n + j) as usize * self.width as usize;
                    for i in 0..n {
                        let k = row + (x * n + i) as usize;
                        let (c, d) = (self.color.get(k), self.depth.get(k));
                        for (s, v) in sum.iter_mut().zip(c.unwrap_or(&[0.0; 4])) {
                            *s += v;
                        }
                        near = near.min(d.copied().unwrap_or(1.0));
                    }
                }
                let k = y as usize * w as usize + x as usize;
                out.color[k] = sum.map(|s| s * scale);
                out.depth[k] = near;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn premultiplied_over_blends_colour_and_alpha() {
        let out = Blend::PremultipliedOver.apply([0.25, 0.0, 0.5, 0.5], [1.0, 1.0, 0.0, 1.0]);
        assert_eq!(out, [0.75, 0.5, 0.5, 1.0]);
        assert_eq!(Blend::Replace.apply([0.1, 0.2, 0.3, 0.4], [1.0; 4]), [0.1, 0.2, 0.3, 0.4]);
    }

    #[test]
    fn downsample_averages_blocks() {
        let mut fb = Framebuffer::new(4, 2, [0.0; 4]);
        fb.color[1] = [4.0, 0.0, 0.0, 4.0];
        fb.color[6] = [0.0, 2.0, 0.0, 0.0];
        fb.depth[5] = 0.25;
        let small = fb.downsample(2);
        assert_eq!((small.width, small.height), (2, 1));
        assert_eq!(small.color, vec![[1.0, 0.0, 0.0, 1.0], [0.0, 0.5, 0.0, 0.0]]);
        assert_eq!(small.depth, vec![0.25, 1.0]);
        assert_eq!(small.pixel(1, 0), Some([0.0, 0.5, 0.0, 0.0]));
        assert_eq!(small.pixel(2, 0), None);
    }
}
