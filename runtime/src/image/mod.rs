//! Float RGBA images: what renders produce, PNG input and output, and the comparison of a render
//! against a reference (`compare`).

mod compare;

pub use compare::{Comparison, Thresholds, compare};

use std::fmt;
use std::path::{Path, PathBuf};

/// A float RGBA image, row-major with the top row first. Values are linear (no gamma).
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` pixels, row 0 (the top) first.
    pub pixels: Vec<[f32; 4]>,
}

/// Why an image operation failed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ImageError {
    /// The two images of a comparison differ in size (width, height).
    SizeMismatch {
        /// The first image's (width, height).
        a: (u32, u32),
        /// The second image's (width, height).
        b: (u32, u32),
    },
    /// `pixels` does not hold `width * height` pixels.
    BadPixelCount {
        /// The image's width.
        width: u32,
        /// The image's height.
        height: u32,
        /// The number of pixels it holds instead of `width * height`.
        pixels: usize,
    },
    /// Reading, decoding, encoding or writing a file failed.
    File {
        /// The file read or written.
        path: PathBuf,
        /// What went wrong, as the I/O or PNG library put it.
        message: String,
    },
}

impl fmt::Display for ImageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ImageError::SizeMismatch { a, b } => {
                write!(f, "images differ in size: {}x{} and {}x{}", a.0, a.1, b.0, b.1)
            }
            ImageError::BadPixelCount { width, height, pixels } => {
                write!(f, "a {width}x{height} image cannot hold {pixels} pixels")
            }
            ImageError::File { path, message } => write!(f, "{}: {message}", path.display()),
        }
    }
}

impl std::error::Error for ImageError {}

impl Image {
    /// A `width` x `height` image filled with `fill`.
    pub fn new(width: u32, height: u32, fill: [f32; 4]) -> Image {
        Image { width, height, pixels: vec![fill; width as usize * height as usize] }
    }

    /// The pixel at column `x`, row `y` (0 = top), or `None` outside the image.
    pub fn get(&self, x: u32, y: u32) -> Option<[f32; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.pixels.get(y as usize * self.width as usize + x as usize).copied()
    }

    /// Sets the pixel at (`x`, `y`); writes outside the image are ignored.
    pub fn set(&mut self, x: u32, y: u32, value: [f32; 4]) {
        if x < self.width && y < self.height {
            let index = y as usize * self.width as usize + x as usize;
            if let Some(p) = self.pixels.get_mut(index) {
                *p = value;
            }
        }
    }

    fn check(&self) -> Result<(), ImageError> {
        if self.pixels.len() as u64 != u64::from(self.width) * u64::from(self.height) {
            return Err(ImageError::BadPixelCount {
                width: self.width,
                height: self.height,
                pixels: self.pixels.len(),
            });
        }
        Ok(())
    }

    /// Writes an 8-bit RGBA PNG of this premultiplied image (renders are premultiplied): PNG
    /// stores straight alpha, so colour is divided by alpha where alpha is above 0; then each
    /// channel is clamped to [0, 1], times 255, rounded; no gamma is applied. NaN writes as 0.
    pub fn write_png(&self, path: impl AsRef<Path>) -> Result<(), ImageError> {
        let path = path.as_ref();
        self.check()?;
        let bytes = self.to_rgba8();
        let file_error = |message: String| ImageError::File { path: path.to_owned(), message };
        let buffer = image::RgbaImage::from_raw(self.width, self.height, bytes)
            .ok_or_else(|| file_error("pixel buffer does not match the size".into()))?;
        buffer.save_with_format(path, image::ImageFormat::Png).map_err(|e| file_error(e.to_string()))
    }

    /// The pixels as 8-bit straight-alpha RGBA, row by row, exactly as [`Image::write_png`]
    /// stores them (so that a picture shown on screen has the PNG's bytes).
    pub fn to_rgba8(&self) -> Vec<u8> {
        let byte = |c: f32| (c.clamp(0.0, 1.0) * 255.0).round() as u8;
        self.pixels
            .iter()
            .flat_map(|&[r, g, b, a]| {
                let straight = if a > 0.0 && a < 1.0 { 1.0 / a } else { 1.0 };
                [byte(r * straight), byte(g * straight), byte(b * straight), byte(a)]
            })
            .collect()
    }

    /// Reads a PNG (any colour type; 8 or 16 bits) as floats in [0, 1]: `value / 255` or
    /// `value / 65535`, without gamma decoding. Images without alpha get alpha 1.
    pub fn read_png(path: impl AsRef<Path>) -> Result<Image, ImageError> {
        let path = path.as_ref();
        let file_error = |message: String| ImageError::File { path: path.to_owned(), message };
        let decoded = image::ImageReader::open(path)
            .map_err(|e| file_error(e.to_string()))?
            .with_guessed_format()
            .map_err(|e| file_error(e.to_string()))?
            .decode()
            .map_err(|e| file_error(e.to_string()))?;
        let (width, height) = (decoded.width(), decoded.height());
        let sixteen_bit = matches!(
            decoded.color(),
            image::ColorType::L16
                | image::ColorType::La16
                | image::ColorType::Rgb16
                | image::ColorType::Rgba16
        );
        let pixels = if sixteen_bit {
            decoded.to_rgba16().pixels().map(|p| p.0.map(|c| f32::from(c) / 65535.0)).collect()
        } else {
            decoded.to_rgba8().pixels().map(|p| p.0.map(|c| f32::from(c) / 255.0)).collect()
        };
        Ok(Image { width, height, pixels })
    }

    /// A picture of where `a` and `b` differ: per colour channel `|a - b| * scale`, alpha 1, and
    /// magenta where either pixel is not finite. Covers the region the two images share, so images
    /// of different sizes still give a picture.
    pub fn diff_image(a: &Image, b: &Image, scale: f32) -> Image {
        let (width, height) = (a.width.min(b.width), a.height.min(b.height));
        let mut out = Image::new(width, height, [0.0, 0.0, 0.0, 1.0]);
        for y in 0..height {
            for x in 0..width {
                let (Some(p), Some(q)) = (a.get(x, y), b.get(x, y)) else { continue };
                let finite = p.iter().chain(&q).all(|c| c.is_finite());
                let value = if finite {
                    [
                        (p[0] - q[0]).abs() * scale,
                        (p[1] - q[1]).abs() * scale,
                        (p[2] - q[2]).abs() * scale,
                        1.0,
                    ]
                } else {
                    [1.0, 0.0, 1.0, 1.0]
                };
                out.set(x, y, value);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_round_trip_quantizes_without_gamma() {
        let mut img = Image::new(3, 2, [0.0, 0.0, 0.0, 1.0]);
        img.set(0, 0, [1.0, 0.2, 0.6, 1.0]);
        img.set(2, 1, [2.0, -1.0, 1.4 / 255.0, 0.0]);
        img.set(1, 0, [f32::NAN, 0.25, 0.0, 1.0]);
        let path = std::env::temp_dir().join(format!("patina-image-test-{}.png", std::process::id()));
        img.write_png(&path).unwrap();
        let back = Image::read_png(&path).unwrap();
        let _ = std::fs::remove_file(&path);
        assert_eq!((back.width, back.height), (3, 2));
        assert_eq!(back.get(0, 0), Some([1.0, 51.0 / 255.0, 153.0 / 255.0, 1.0]));
        assert_eq!(back.get(2, 1), Some([1.0, 0.0, 1.0 / 255.0, 0.0]));
        assert_eq!(back.get(1, 0), Some([0.0, 64.0 / 255.0, 0.0, 1.0]));
        assert_eq!(back.get(3, 0), None);
    }

    #[test]
    fn png_stores_straight_alpha() {
        // Premultiplied half-transparent orange: the PNG holds the orange itself.
        let img = Image::new(1, 1, [0.4, 0.2, 0.0, 0.5]);
        let path = std::env::temp_dir().join(format!("patina-image-alpha-{}.png", std::process::id()));
        img.write_png(&path).unwrap();
        let back = Image::read_png(&path).unwrap();
        let _ = std::fs::remove_file(&path);
        assert_eq!(back.get(0, 0), Some([204.0 / 255.0, 102.0 / 255.0, 0.0, 128.0 / 255.0]));
    }

    #[test]
    fn bad_images_and_paths_are_errors() {
        let bad = Image { width: 2, height: 2, pixels: vec![[0.0; 4]; 3] };
        let path = std::env::temp_dir().join("patina-never-written.png");
        assert!(matches!(bad.write_png(&path), Err(ImageError::BadPixelCount { .. })));
        assert!(matches!(Image::read_png("/nonexistent/x.png"), Err(ImageError::File { .. })));
    }

    #[test]
    fn diff_image_scales_and_marks_non_finite() {
        let a = Image::new(2, 1, [0.5, 0.5, 0.5, 1.0]);
        let mut b = Image::new(3, 1, [0.25, 0.5, 0.75, 0.0]);
        b.set(1, 0, [f32::INFINITY, 0.0, 0.0, 1.0]);
        let d = Image::diff_image(&a, &b, 2.0);
        assert_eq!((d.width, d.height), (2, 1));
        assert_eq!(d.pixels, [[0.5, 0.0, 0.5, 1.0], [1.0, 0.0, 1.0, 1.0]]);
    }
}
