//! The footprint filter: the texture integrated over the pixel's footprint, so that one sample
//! per pixel gives what the box pixel filter gives with infinitely many.
//!
//! A pixel (or, at n samples per pixel, a sample's share of it) sees the parallelogram
//! `uv + s duv/dx + t duv/dy`, s and t in [-1/2, 1/2], of texture space (the ray differentials,
//! linearised at the hit). Under the box pixel filter the exact pixel value is the mean of the
//! bilinearly reconstructed texture over that parallelogram. This filter takes it by
//! texture-space supersampling: an `na` x `nb` grid of bilinear taps at the centres of equal
//! cells of the parallelogram (the midpoint rule), [`TAPS_PER_TEXEL`] taps per texel along each
//! edge; no extra rays are traced. Footprints longer than [`MAX_TAPS`] taps read the coarsest
//! mip level that still gets [`MAX_TAPS`] taps along the longer edge (its texels average 2^L x
//! 2^L of the image: a blur of at most 1 / [`MAX_TAPS`] of the footprint's length).
//!
//! Unlike trilinear and EWA, which weigh the texels under an isotropic box or a Gaussian a bit
//! wider than the pixel, the mean is over the footprint itself: no blur beyond the pixel's, so
//! it converges to the supersampled image rather than to a blurred one. It is exact for the box
//! pixel filter when the sample is at its cell's centre (the `regular` sampler); a jittered
//! sample moves the footprint with it, adding the jitter's own blur.

use super::{ImageData, MipPyramid, Wrap};
use crate::math::{Rgb, Vec2};

/// Taps per texel along each edge of the footprint (at the level read): the midpoint rule on the
/// bilinear reconstruction, which is smooth between texel centres.
pub const TAPS_PER_TEXEL: f32 = 2.0;

/// The most taps along an edge; longer footprints read a coarser mip level.
pub const MAX_TAPS: u32 = 32;

/// The mean of the bilinear texture over the footprint parallelogram centred at `uv` with edges
/// `duvdx` and `duvdy` (see the module documentation). Without a mip pyramid, footprints
/// longer than [`MAX_TAPS`] taps are sampled by [`MAX_TAPS`] taps at full resolution.
#[must_use]
pub fn footprint(
    mip: Option<&MipPyramid>,
    image: &ImageData,
    uv: Vec2,
    duvdx: Vec2,
    duvdy: Vec2,
    wu: Wrap,
    wv: Wrap,
) -> Rgb {
    let uv = Wrap::reduce_uv(wu, wv, uv);
    let size = Vec2::new(image.width() as f32, image.height() as f32);
    let (la, lb) = ((duvdx * size).length(), (duvdy * size).length());
    if !(la.is_finite() && lb.is_finite() && uv.is_finite()) {
        return image.bilinear(uv, wu, wv);
    }
    let longest = la.max(lb) * TAPS_PER_TEXEL;
    // The level whose texels are long enough that MAX_TAPS taps cover the longer edge.
    let (level, scale) = match mip {
        Some(m) if longest > MAX_TAPS as f32 => {
            let l = (longest / MAX_TAPS as f32)
                .log2()
                .ceil()
                .min((m.len() - 1) as f32);
            (m.level(l as usize), (-l).exp2())
        }
        _ => (image, 1.0),
    };
    let taps = |len: f32| ((len * TAPS_PER_TEXEL * scale).ceil() as u32).clamp(1, MAX_TAPS);
    let (na, nb) = (taps(la), taps(lb));
    if na == 1 && nb == 1 {
        return level.bilinear(uv, wu, wv);
    }
    let (sa, sb) = (duvdx / na as f32, duvdy / nb as f32);
    // The centre of cell (0, 0).
    let corner = uv - duvdx * 0.5 - duvdy * 0.5 + (sa + sb) * 0.5;
    let mut sum = Rgb::BLACK;
    for j in 0..nb {
        let row = corner + sb * j as f32;
        for i in 0..na {
            sum += level.bilinear(row + sa * i as f32, wu, wv);
        }
    }
    sum / (na * nb) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    /// Vertical stripes two texels wide (period 4 texels): 1, 1, 0, 0, 1, 1, ...
    fn stripes() -> Arc<ImageData> {
        Arc::new(ImageData::from_fn(64, 8, "stripes", |c, _| {
            Rgb::grey(if (c / 2) % 2 == 0 { 1.0 } else { 0.0 })
        }))
    }

    /// A texture with no period: smooth waves and a hard checker.
    fn busy() -> Arc<ImageData> {
        Arc::new(ImageData::from_fn(48, 40, "busy", |c, r| {
            let (x, y) = (c as f32, r as f32);
            let check = if (c / 3 + r / 5) % 2 == 0 { 0.8 } else { 0.1 };
            Rgb(
                check,
                0.5 + 0.4 * (x * 0.7).sin() * (y * 0.3).cos(),
                x / 48.0,
            )
        }))
    }

    const R: Wrap = Wrap::Repeat;

    #[test]
    fn a_footprint_of_whole_periods_averages_the_stripes_exactly() {
        let img = stripes();
        // 8 texels (two periods) wide, its left edge on a texel centre; bilinear at the centre
        // reads one stripe.
        let (uv, dx, dy) = (
            Vec2::new(14.5 / 64.0, 0.5),
            Vec2::new(8.0 / 64.0, 0.0),
            Vec2::new(0.0, 2.0 / 8.0),
        );
        let f = footprint(None, &img, uv, dx, dy, R, R);
        assert!((f.0 - 0.5).abs() < 1e-6, "{f:?}");
        assert!((img.bilinear(uv, R, R).0 - 0.5).abs() > 0.4);
    }

    #[test]
    fn it_converges_to_the_integral_over_the_parallelogram() {
        // A sheared, rotated footprint a few texels long: the filter against a 256 x 256
        // midpoint integration of the same bilinear texture.
        let img = busy();
        for (uv, dx, dy) in [
            (
                Vec2::new(0.31, 0.42),
                Vec2::new(0.07, 0.02),
                Vec2::new(-0.03, 0.09),
            ),
            (
                Vec2::new(0.77, 0.15),
                Vec2::new(0.12, -0.05),
                Vec2::new(0.01, 0.04),
            ),
            (
                Vec2::new(0.02, 0.97),
                Vec2::new(0.05, 0.0),
                Vec2::new(0.0, 0.06),
            ),
        ] {
            let n = 256;
            let mut sum = Rgb::BLACK;
            for j in 0..n {
                for i in 0..n {
                    let s = (i as f32 + 0.5) / n as f32 - 0.5;
                    let t = (j as f32 + 0.5) / n as f32 - 0.5;
                    sum += img.bilinear(uv + dx * s + dy * t, R, R);
                }
            }
            let exact = sum / (n * n) as f32;
            let f = footprint(None, &img, uv, dx, dy, R, R);
            let centre = img.bilinear(uv, R, R);
            let diff = |a: Rgb, b: Rgb| {
                let (a, b) = (a.to_array(), b.to_array());
                [0, 1, 2].map(|k| (a[k] - b[k]).abs())
            };
            let err = diff(f, exact);
            assert!(err.iter().all(|e| *e < 0.02), "{f:?} vs {exact:?}");
            // ... where one bilinear tap at the centre is far off.
            let off = diff(centre, exact);
            assert!(off.iter().any(|e| *e > 0.05), "{centre:?} vs {exact:?}");
        }
    }

    #[test]
    fn magnified_it_is_bilinear_and_a_huge_footprint_reads_the_mip_pyramid() {
        let img = busy();
        let uv = Vec2::new(0.4, 0.6);
        let tiny = Vec2::new(0.1 / 48.0, 0.0);
        assert_eq!(
            footprint(None, &img, uv, tiny, tiny.perp(), R, R),
            img.bilinear(uv, R, R)
        );
        // The whole stripe texture under one pixel: its mean, 0.5, from a coarse level.
        let s = stripes();
        let mip = MipPyramid::build(s.clone());
        let f = footprint(
            Some(&mip),
            &s,
            uv,
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
            R,
            R,
        );
        assert!((f.0 - 0.5).abs() < 0.02, "{f:?}");
        // Non-finite derivatives fall back to one bilinear tap.
        let nan = Vec2::new(f32::NAN, 0.0);
        assert_eq!(
            footprint(None, &img, uv, nan, nan, R, R),
            img.bilinear(uv, R, R)
        );
    }
}
