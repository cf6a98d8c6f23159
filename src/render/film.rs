//! The film: per-pixel running sums of linear radiance and sample weight, and the conversion to
//! display bytes.

use crate::math::Rgb;
pub use crate::math::{DisplayImage, encode_srgb8};

/// Running sums per pixel: `[r, g, b, weight]`, linear radiance; and, for adaptive sampling,
/// the sum and the sum of squares of each sample's display-encoded luminance.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    pixels: Vec<[f32; 4]>,
    stats: Vec<[f32; 2]>,
    keys: Vec<u32>,
}

impl Film {
    /// A black film with no samples.
    #[must_use]
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            pixels: vec![[0.0; 4]; n],
            stats: vec![[0.0; 2]; n],
            keys: vec![0; n],
        }
    }

    /// Per pixel, the sum and the sum of squares of the samples' display luminance (filled by
    /// adaptive renders only).
    #[must_use]
    pub fn stats(&self) -> &[[f32; 2]] {
        &self.stats
    }

    /// Per pixel, the edge key of its first sample (see `Scene::trace_keyed`; filled by
    /// adaptive renders only).
    #[must_use]
    pub fn keys(&self) -> &[u32] {
        &self.keys
    }

    /// The sums, the luminance statistics and the edge keys, mutably (for render passes).
    pub fn buffers_mut(&mut self) -> (&mut [[f32; 4]], &mut [[f32; 2]], &mut [u32]) {
        (&mut self.pixels, &mut self.stats, &mut self.keys)
    }

    /// Total samples taken (the sum of every pixel's weight).
    #[must_use]
    pub fn total_samples(&self) -> f64 {
        self.pixels.iter().map(|p| f64::from(p[3])).sum()
    }

    /// Width in pixels.
    #[must_use]
    pub const fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[must_use]
    pub const fn height(&self) -> u32 {
        self.height
    }

    /// The sums, row-major from the top-left pixel.
    #[must_use]
    pub fn pixels(&self) -> &[[f32; 4]] {
        &self.pixels
    }

    /// The sums, mutably (for render passes).
    pub fn pixels_mut(&mut self) -> &mut [[f32; 4]] {
        &mut self.pixels
    }

    /// The mean radiance of each pixel (black where no sample landed yet).
    #[must_use]
    pub fn to_linear(&self) -> Vec<Rgb> {
        self.pixels.iter().map(|p| mean(*p)).collect()
    }

    /// Whether every pixel's sum is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.pixels.iter().all(|p| p.iter().all(|v| v.is_finite()))
    }

    /// Display-encoded RGBA8 (sRGB), scaled by `exposure_scale` and clipped.
    #[must_use]
    pub fn to_display(&self, exposure_scale: f32) -> DisplayImage {
        DisplayImage::encode(
            self.width,
            self.height,
            self.pixels.iter().map(|p| mean(*p)),
            exposure_scale,
        )
    }
}

#[inline]
fn mean(p: [f32; 4]) -> Rgb {
    if p[3] > 0.0 {
        Rgb(p[0], p[1], p[2]) / p[3]
    } else {
        Rgb::BLACK
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_is_the_mean_encoded_and_black_where_no_sample_landed() {
        let mut f = Film::new(3, 1);
        f.pixels_mut()[0] = [0.5, 2.0, 0.1, 2.0];
        f.pixels_mut()[1] = [f32::NAN, -1.0, 8.0, 1.0];
        let d = f.to_display(2.0);
        assert_eq!((d.width, d.height), (3, 1));
        let e = |v: f32| encode_srgb8(v);
        assert_eq!(
            d.rgba,
            vec![e(0.5), 255, e(0.1), 255, 0, 0, 255, 255, 0, 0, 0, 255]
        );
    }

    #[test]
    fn film_averages_its_samples() {
        let mut f = Film::new(2, 1);
        f.pixels_mut()[0] = [1.0, 2.0, 3.0, 2.0];
        assert_eq!(f.to_linear(), vec![Rgb(0.5, 1.0, 1.5), Rgb::BLACK]);
    }
}
