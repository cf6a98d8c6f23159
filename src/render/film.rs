//! The film: per-pixel running sums of linear radiance and sample weight, and the conversion to
//! display bytes.

use crate::math::{Rgb, linear_to_srgb};
use std::sync::LazyLock;

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
        let mut rgba = Vec::with_capacity(self.pixels.len() * 4);
        for p in &self.pixels {
            let c = mean(*p) * exposure_scale;
            rgba.extend_from_slice(&[encode_srgb8(c.0), encode_srgb8(c.1), encode_srgb8(c.2), 255]);
        }
        DisplayImage {
            width: self.width,
            height: self.height,
            rgba,
        }
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

/// An 8-bit sRGB RGBA image ready for the screen or a PNG.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DisplayImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// RGBA bytes, row-major from the top-left pixel.
    pub rgba: Vec<u8>,
}

impl DisplayImage {
    /// Linear radiance, scaled and encoded.
    #[must_use]
    pub fn from_linear(width: u32, height: u32, pixels: &[Rgb], exposure_scale: f32) -> Self {
        let mut rgba = Vec::with_capacity(pixels.len() * 4);
        for c in pixels {
            let c = *c * exposure_scale;
            rgba.extend_from_slice(&[encode_srgb8(c.0), encode_srgb8(c.1), encode_srgb8(c.2), 255]);
        }
        Self {
            width,
            height,
            rgba,
        }
    }

    /// The RGB bytes without alpha.
    #[must_use]
    pub fn rgb(&self) -> Vec<u8> {
        self.rgba
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect()
    }
}

const ENCODE_STEPS: usize = 1 << 16;

static ENCODE_TABLE: LazyLock<Vec<u8>> = LazyLock::new(|| {
    (0..ENCODE_STEPS)
        .map(|i| (linear_to_srgb(i as f32 / (ENCODE_STEPS - 1) as f32) * 255.0).round() as u8)
        .collect()
});

/// Linear value to 8-bit sRGB through a 65536-entry table (clips to [0, 1]; NaN to 0).
#[must_use]
#[inline]
pub fn encode_srgb8(v: f32) -> u8 {
    let v = if v > 0.0 { v.min(1.0) } else { 0.0 }; // also maps NaN to 0
    ENCODE_TABLE[(v * (ENCODE_STEPS - 1) as f32 + 0.5) as usize]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_encoding_matches_the_curve_within_one_step() {
        for i in 0..=1000 {
            let v = i as f32 / 1000.0;
            let exact = (linear_to_srgb(v) * 255.0).round() as i32;
            assert!((i32::from(encode_srgb8(v)) - exact).abs() <= 1, "{v}");
        }
        assert_eq!(encode_srgb8(f32::NAN), 0);
        assert_eq!(encode_srgb8(f32::INFINITY), 255);
        assert_eq!(encode_srgb8(-3.0), 0);
    }

    #[test]
    fn film_averages_its_samples() {
        let mut f = Film::new(2, 1);
        f.pixels_mut()[0] = [1.0, 2.0, 3.0, 2.0];
        assert_eq!(f.to_linear(), vec![Rgb(0.5, 1.0, 1.5), Rgb::BLACK]);
    }
}
