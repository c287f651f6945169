//! Comparing a render with a reference image, in the manner of OpenImageIO's `idiff` as the OSL
//! test suite uses it.

use super::{Image, ImageError};

/// Tolerances for `compare`; the default is the OSL test suite's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thresholds {
    /// A pixel fails when any channel differs by more than this (default 0.004, about one 8-bit step).
    pub fail: f32,
    /// The comparison fails when any channel of any pixel differs by more than this (default 0.01).
    pub hard_fail: f32,
    /// The comparison fails when more than this fraction of pixels fail (default 0.02, i.e. 2%).
    pub max_failing_fraction: f32,
}

impl Default for Thresholds {
    fn default() -> Self {
        Thresholds { fail: 0.004, hard_fail: 0.01, max_failing_fraction: 0.02 }
    }
}

/// What `compare` measured. Errors are absolute per-channel differences over all four channels;
/// pixels with a NaN or infinity are counted in `nan_pixels` and left out of the other figures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Comparison {
    /// The largest channel difference.
    pub max_error: f32,
    /// The mean channel difference over the finite pixels' channels (0 when there are none).
    pub mean_error: f32,
    /// The root mean square of the channel differences over the same channels.
    pub rms_error: f32,
    /// Pixels with some channel differing by more than `fail`.
    pub failing_pixels: usize,
    /// Pixels with some channel differing by more than `hard_fail`.
    pub hard_failing_pixels: usize,
    /// Pixels compared.
    pub pixels: usize,
    /// Pixels with a NaN or infinity in either image (in any channel).
    pub nan_pixels: usize,
}

impl Comparison {
    /// Whether the images match: no pixel has a NaN or infinity, no channel differs by more than
    /// `hard_fail`, and failing pixels are at most `max_failing_fraction` of all pixels.
    ///
    /// Like idiff, the hard limit is on the single worst channel, and the count of failing pixels is
    /// judged as a fraction. Unlike idiff, a non-finite value anywhere fails the comparison, because
    /// a NaN that happens to sit in both images still means something went wrong.
    pub fn passes(&self, t: &Thresholds) -> bool {
        // Rounded to f32 so that a fraction written as a literal (0.02) admits exactly 2 in 100.
        let fraction =
            if self.pixels == 0 { 0.0 } else { (self.failing_pixels as f64 / self.pixels as f64) as f32 };
        self.nan_pixels == 0 && self.hard_failing_pixels == 0 && fraction <= t.max_failing_fraction
    }
}

/// Measures how `a` differs from `b` under thresholds `t`; the images must have the same size.
pub fn compare(a: &Image, b: &Image, t: &Thresholds) -> Result<Comparison, ImageError> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(ImageError::SizeMismatch { a: (a.width, a.height), b: (b.width, b.height) });
    }
    a.check()?;
    b.check()?;
    let mut c = Comparison {
        max_error: 0.0,
        mean_error: 0.0,
        rms_error: 0.0,
        failing_pixels: 0,
        hard_failing_pixels: 0,
        pixels: a.pixels.len(),
        nan_pixels: 0,
    };
    let (mut sum, mut squares) = (0.0f64, 0.0f64);
    let mut channels = 0usize;
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        if !p.iter().chain(q).all(|v| v.is_finite()) {
            c.nan_pixels += 1;
            continue;
        }
        let worst = (0..4).map(|i| (p[i] - q[i]).abs()).fold(0.0f32, f32::max);
        // In f64, so that the differences of nearly equal references do not round away.
        let d: [f64; 4] = std::array::from_fn(|i| f64::from(p[i]) - f64::from(q[i]));
        sum += d.iter().map(|x| x.abs()).sum::<f64>();
        squares += d.iter().map(|x| x * x).sum::<f64>();
        channels += 4;
        c.max_error = c.max_error.max(worst);
        c.failing_pixels += usize::from(worst > t.fail);
        c.hard_failing_pixels += usize::from(worst > t.hard_fail);
    }
    if channels > 0 {
        c.mean_error = (sum / channels as f64) as f32;
        c.rms_error = (squares / channels as f64).sqrt() as f32;
    }
    Ok(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(values: &[f32]) -> Image {
        Image {
            width: values.len() as u32,
            height: 1,
            pixels: values.iter().map(|&v| [v, 0.0, 0.0, 1.0]).collect(),
        }
    }

    #[test]
    fn identical_images_pass() {
        let a = image(&[0.1, 0.2, 0.3]);
        let c = compare(&a, &a, &Thresholds::default()).unwrap();
        assert_eq!((c.max_error, c.mean_error, c.failing_pixels, c.nan_pixels), (0.0, 0.0, 0, 0));
        assert!(c.passes(&Thresholds::default()));
    }

    #[test]
    fn few_small_failures_pass_and_many_do_not() {
        let t = Thresholds::default();
        let reference = image(&[0.5; 100]);
        let mut values = [0.5f32; 100];
        values[0] = 0.5 + 0.008; // fails, but is under the hard limit
        values[1] = 0.5 + 0.008;
        let c = compare(&image(&values), &reference, &t).unwrap();
        assert_eq!((c.failing_pixels, c.hard_failing_pixels), (2, 0));
        assert!(c.passes(&t), "2 of 100 is exactly the 2% allowed");
        values[2] = 0.5 + 0.008;
        assert!(!compare(&image(&values), &reference, &t).unwrap().passes(&t));
    }

    #[test]
    fn one_hard_failure_or_nan_fails() {
        let t = Thresholds::default();
        let reference = image(&[0.5; 100]);
        let mut values = [0.5f32; 100];
        values[7] = 0.52;
        let c = compare(&image(&values), &reference, &t).unwrap();
        assert_eq!(c.hard_failing_pixels, 1);
        assert!((c.max_error - 0.02).abs() < 1e-6);
        assert!((c.mean_error - 0.02 / 400.0).abs() < 1e-8);
        // One channel of 400 off by 0.02 (in f32: 0.52 - 0.5 = 0.0200001).
        let rms = (f64::from(0.52f32 - 0.5).powi(2) / 400.0).sqrt();
        assert!((f64::from(c.rms_error) - rms).abs() < 1e-9, "{} vs {rms}", c.rms_error);
        assert!(!c.passes(&t));
        values[7] = f32::NAN;
        let c = compare(&image(&values), &reference, &t).unwrap();
        assert_eq!((c.nan_pixels, c.max_error), (1, 0.0));
        assert!(!c.passes(&t));
    }

    #[test]
    fn size_mismatch_is_an_error() {
        let e = compare(&image(&[0.0; 2]), &image(&[0.0; 3]), &Thresholds::default());
        assert_eq!(e, Err(ImageError::SizeMismatch { a: (2, 1), b: (3, 1) }));
    }
}
