//! Pixel reconstruction filters, by importance sampling (pbrt-v4's approach): a sample's point in
//! [0, 1)^2 is warped through the filter's inverse CDF to an offset from the pixel centre, and
//! every sample weighs 1. The film stays a running sum per pixel (no splatting into neighbours,
//! so passes stay parallel per tile and deterministic), and the warp is smooth, so stratified
//! patterns stay stratified.

use crate::math::{TAU, Vec2};
use serde::{Deserialize, Serialize};

/// The standard deviation of the Gaussian filter, in pixels.
pub const GAUSSIAN_SIGMA: f32 = 0.5;
/// Where the Gaussian filter is cut off, in pixels from the centre.
pub const GAUSSIAN_RADIUS: f32 = 1.5;

/// How a pixel weighs the points around its centre.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[derive(Serialize, Deserialize)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum PixelFilter {
    /// Every point of the pixel square weighs the same (the lecture's average).
    #[default]
    #[strum(message = "Every point of the pixel square weighs the same (the lecture's average).")]
    Box,
    /// A tent of radius 1 pixel: smoother, less aliasing, slightly softer.
    #[strum(message = "A tent of radius 1 pixel: smoother, less aliasing, slightly softer.")]
    Tent,
    /// A radially symmetric Gaussian, sigma 0.5 pixel, cut off at 1.5 pixels.
    #[strum(message = "A radially symmetric Gaussian, sigma 0.5 pixel, cut off at 1.5 pixels.")]
    Gaussian,
}

impl crate::names::Named for PixelFilter {
    const WHAT: &'static str = "pixel filter";
}

impl PixelFilter {
    /// The offset from the pixel centre, in pixels, of the sample at `p` in [0, 1)^2.
    #[must_use]
    #[inline]
    pub fn warp(self, p: Vec2) -> Vec2 {
        match self {
            Self::Box => p - Vec2::splat(0.5),
            Self::Tent => Vec2::new(tent(p.x), tent(p.y)),
            Self::Gaussian => {
                // Radius from the truncated 2D Gaussian's radial CDF 1 - exp(-r^2 / 2 sigma^2),
                // angle uniform.
                let tail = (-GAUSSIAN_RADIUS * GAUSSIAN_RADIUS
                    / (2.0 * GAUSSIAN_SIGMA * GAUSSIAN_SIGMA))
                    .exp();
                let x = p.x * (1.0 - tail);
                let r = GAUSSIAN_SIGMA * (-2.0 * (1.0 - x).ln()).max(0.0).sqrt();
                let (s, c) = (TAU * p.y).sin_cos();
                Vec2::new(r * c, r * s)
            }
        }
    }
}

/// The inverse CDF of the tent of radius 1 on [-1, 1].
#[inline]
fn tent(u: f32) -> f32 {
    if u < 0.5 {
        -1.0 + (2.0 * u).sqrt()
    } else {
        1.0 - (2.0 * (1.0 - u)).max(0.0).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_is_the_pixel_square_and_tent_and_gaussian_have_their_support() {
        for i in 0..64 {
            for j in 0..64 {
                let p = Vec2::new((i as f32 + 0.5) / 64.0, (j as f32 + 0.5) / 64.0);
                let b = PixelFilter::Box.warp(p);
                assert!(b.abs().max_element() <= 0.5);
                let t = PixelFilter::Tent.warp(p);
                assert!(t.abs().max_element() <= 1.0);
                let g = PixelFilter::Gaussian.warp(p);
                assert!(g.length() <= GAUSSIAN_RADIUS + 1e-5 && g.is_finite());
            }
        }
    }

    #[test]
    fn tent_density_is_triangular() {
        // A uniform grid warped through the tent: the share landing within 0.5 of the centre is
        // the tent's mass there, 3/4 per axis.
        let n = 10_000;
        let inside = (0..n)
            .filter(|i| tent((*i as f32 + 0.5) / n as f32).abs() < 0.5)
            .count();
        assert!((inside as f32 / n as f32 - 0.75).abs() < 1e-3);
        // Gaussian: the share within sigma of the centre is (1 - e^-1/2) / (1 - e^-4.5).
        let m = 200;
        let mut within = 0;
        for i in 0..m {
            for j in 0..m {
                let p = Vec2::new((i as f32 + 0.5) / m as f32, (j as f32 + 0.5) / m as f32);
                within += usize::from(PixelFilter::Gaussian.warp(p).length() < GAUSSIAN_SIGMA);
            }
        }
        let expected = (1.0 - (-0.5f32).exp()) / (1.0 - (-4.5f32).exp());
        assert!((within as f32 / (m * m) as f32 - expected).abs() < 0.01);
    }
}
