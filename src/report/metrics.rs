//! Image error metrics on display-encoded images: RMSE, PSNR, relative MSE, SSIM and FLIP.
//!
//! Every metric compares what a user sees: linear radiance is scaled by the scene's exposure,
//! clipped to [0, 1] and sRGB-encoded ([`EncodedImage`]). RMSE, PSNR, relative MSE and SSIM use
//! the float sRGB values; FLIP (LDR-FLIP, NVIDIA's `nv-flip`) takes the 8-bit sRGB bytes.

use crate::math::{DisplayImage, Rgb, linear_to_srgb, quantize8};
use crate::render::Film;

/// The small constant in relative MSE's denominator, (t - r)^2 / (r^2 + [`REL_MSE_EPSILON`]),
/// which keeps black reference pixels from dividing by zero.
pub const REL_MSE_EPSILON: f64 = 1e-2;
/// SSIM's Gaussian window: 11 x 11 taps ...
pub const SSIM_WINDOW: usize = 11;
/// ... with standard deviation 1.5 pixels (Wang et al. 2004).
pub const SSIM_SIGMA: f64 = 1.5;
/// SSIM's C1 = (K1 L)^2 with K1 = 0.01 and the dynamic range L = 1.
pub const SSIM_C1: f64 = 0.01 * 0.01;
/// SSIM's C2 = (K2 L)^2 with K2 = 0.03 and L = 1.
pub const SSIM_C2: f64 = 0.03 * 0.03;

/// How each metric is computed, one line each, for reports.
pub const METRIC_DEFINITIONS: &[(&str, &str)] = &[
    (
        "RMSE",
        "root of the mean over pixels and R, G, B of (test - reference)^2, on sRGB-encoded values in [0, 1] (exposure applied, clipped)",
    ),
    (
        "PSNR",
        "10 log10(1 / MSE) in dB with the MSE above (peak value 1); inf for identical images",
    ),
    (
        "relMSE",
        "mean over pixels and channels of (test - reference)^2 / (reference^2 + 0.01), on the same sRGB values",
    ),
    (
        "SSIM",
        "mean SSIM (Wang et al. 2004) of the luma Y' = 0.2126 R' + 0.7152 G' + 0.0722 B' of the sRGB values: Gaussian window 11 x 11, sigma 1.5 (weights renormalised where the window leaves the image), C1 = 0.01^2, C2 = 0.03^2; 1 = identical",
    ),
    (
        "FLIP",
        "mean of NVIDIA's LDR-FLIP error map (nv-flip crate) between the 8-bit sRGB images at 67 pixels per degree (0.7 m from a 0.7 m wide 4K screen); 0 = identical, 1 = maximal",
    ),
    (
        "RMSE linear",
        "root of the mean over pixels and R, G, B of (test - reference)^2 on the linear radiance itself (no exposure, no clipping, no sRGB curve): the peer renderers' metric, in the texture's units",
    ),
];

/// A display-encoded image: sRGB values as floats in [0, 1] and as bytes, 3 per pixel,
/// row-major from the top-left pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct EncodedImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// sRGB-encoded values in [0, 1], 3 per pixel.
    pub srgb: Vec<f32>,
    /// The same rounded to bytes (what a PNG holds), 3 per pixel.
    pub srgb8: Vec<u8>,
}

impl EncodedImage {
    /// Encodes linear radiance for display: times `exposure_scale`, clipped, sRGB curve.
    ///
    /// # Panics
    /// If `linear` does not hold `width * height` pixels (a programming error).
    #[must_use]
    pub fn from_linear(width: u32, height: u32, linear: &[Rgb], exposure_scale: f32) -> Self {
        assert_eq!(linear.len(), width as usize * height as usize, "image size");
        let srgb = linear
            .iter()
            .flat_map(|c| (*c * exposure_scale).to_array().map(linear_to_srgb))
            .collect();
        // The bytes are the display image's: a PNG of this render holds exactly these.
        let srgb8 = DisplayImage::from_linear(width, height, linear, exposure_scale).rgb();
        Self {
            width,
            height,
            srgb,
            srgb8,
        }
    }

    /// A film's mean radiance encoded for display (see [`EncodedImage::from_linear`]).
    #[must_use]
    pub fn from_film(film: &Film, exposure_scale: f32) -> Self {
        Self::from_linear(
            film.width(),
            film.height(),
            &film.to_linear(),
            exposure_scale,
        )
    }

    /// An image from sRGB floats in [0, 1] (3 per pixel); the bytes are rounded from them.
    ///
    /// # Panics
    /// If `srgb` does not hold `3 * width * height` values (a programming error).
    #[must_use]
    pub fn from_srgb(width: u32, height: u32, srgb: Vec<f32>) -> Self {
        assert_eq!(
            srgb.len(),
            width as usize * height as usize * 3,
            "image size"
        );
        let srgb8 = srgb.iter().map(|v| quantize8(*v)).collect();
        Self {
            width,
            height,
            srgb,
            srgb8,
        }
    }

    /// Rec. 709 luma of the encoded values, one per pixel (what SSIM compares).
    #[must_use]
    pub fn luma(&self) -> Vec<f64> {
        self.srgb
            .chunks_exact(3)
            .map(|p| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]))
            .collect()
    }
}

/// Every metric of one image against its reference.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Metrics {
    /// Root mean squared error of the sRGB values.
    pub rmse: f64,
    /// Peak signal-to-noise ratio in dB (infinite for identical images).
    pub psnr: f64,
    /// Relative mean squared error.
    pub rel_mse: f64,
    /// Mean structural similarity of the luma (1 for identical images).
    pub ssim: f64,
    /// Mean LDR-FLIP error (0 for identical images); `None` in a build without the `flip`
    /// feature (the browser's, which cannot compile FLIP's C++).
    pub flip: Option<f64>,
    /// RMSE of the linear radiance (before exposure, not clipped), over every pixel and R, G,
    /// B: the metric of the peer renderers (`report --reference FILE.exr`).
    pub rmse_linear: f64,
}

/// Compares `test` with `reference`; also returns FLIP's per-pixel error map (row-major, values
/// in [0, 1]) for heat maps, `None` without the `flip` feature.
///
/// # Panics
/// If the images differ in size (a programming error: the caller renders both).
#[must_use]
pub fn compare(reference: &EncodedImage, test: &EncodedImage) -> (Metrics, Option<Vec<f32>>) {
    assert_eq!(
        (reference.width, reference.height),
        (test.width, test.height),
        "images differ in size"
    );
    let mse = mse(&reference.srgb, &test.srgb);
    #[cfg(feature = "flip")]
    let flip_map = Some(flip_error_map(reference, test));
    #[cfg(not(feature = "flip"))]
    let flip_map = None;
    let flip = flip_map.as_deref().map(mean_f32);
    let metrics = Metrics {
        rmse: mse.sqrt(),
        psnr: psnr(mse),
        rel_mse: rel_mse(&reference.srgb, &test.srgb),
        ssim: ssim(
            reference.width as usize,
            reference.height as usize,
            &reference.luma(),
            &test.luma(),
        ),
        flip,
        rmse_linear: 0.0,
    };
    (metrics, flip_map)
}

/// RMSE of linear radiance over every pixel and R, G, B (no exposure, no clipping): the
/// metric Mitsuba's benchmark and the peer baseline compute.
///
/// # Panics
/// If the images differ in length (a programming error: the caller checks the sizes).
#[must_use]
pub fn rmse_linear(reference: &[Rgb], test: &[Rgb]) -> f64 {
    assert_eq!(reference.len(), test.len(), "images differ in size");
    let sum: f64 = reference
        .iter()
        .zip(test)
        .map(|(r, t)| {
            r.to_array()
                .iter()
                .zip(t.to_array())
                .map(|(a, b)| {
                    let d = f64::from(b) - f64::from(*a);
                    d * d
                })
                .sum::<f64>()
        })
        .sum();
    (sum / (3 * reference.len().max(1)) as f64).sqrt()
}

/// RMSE of `test` against `reference` (the report's RMSE column), or `None` if the sizes
/// differ.
#[must_use]
pub fn rmse(reference: &EncodedImage, test: &EncodedImage) -> Option<f64> {
    ((reference.width, reference.height) == (test.width, test.height))
        .then(|| mse(&reference.srgb, &test.srgb).sqrt())
}

/// Mean squared difference of two equally long slices.
#[must_use]
pub fn mse(reference: &[f32], test: &[f32]) -> f64 {
    let n = reference.len().max(1) as f64;
    reference
        .iter()
        .zip(test)
        .map(|(r, t)| {
            let d = f64::from(*t) - f64::from(*r);
            d * d
        })
        .sum::<f64>()
        / n
}

/// PSNR in dB for a peak value of 1: `10 log10(1 / mse)`, infinite when `mse` is 0.
#[must_use]
pub fn psnr(mse: f64) -> f64 {
    if mse > 0.0 {
        -10.0 * mse.log10()
    } else {
        f64::INFINITY
    }
}

/// Relative MSE: the mean of `(t - r)^2 / (r^2 + REL_MSE_EPSILON)`.
#[must_use]
pub fn rel_mse(reference: &[f32], test: &[f32]) -> f64 {
    let n = reference.len().max(1) as f64;
    reference
        .iter()
        .zip(test)
        .map(|(r, t)| {
            let (r, t) = (f64::from(*r), f64::from(*t));
            (t - r) * (t - r) / (r * r + REL_MSE_EPSILON)
        })
        .sum::<f64>()
        / n
}

fn mean_f32(v: &[f32]) -> f64 {
    v.iter().map(|x| f64::from(*x)).sum::<f64>() / v.len().max(1) as f64
}

/// The normalised 1D Gaussian of SSIM's window.
fn gaussian_taps() -> [f64; SSIM_WINDOW] {
    let mut k = [0.0; SSIM_WINDOW];
    let half = (SSIM_WINDOW / 2) as f64;
    for (i, w) in k.iter_mut().enumerate() {
        let x = i as f64 - half;
        *w = (-x * x / (2.0 * SSIM_SIGMA * SSIM_SIGMA)).exp();
    }
    let sum: f64 = k.iter().sum();
    k.map(|w| w / sum)
}

/// Separable Gaussian blur; where the window leaves the image the weights inside are
/// renormalised (so a constant image stays constant up to its border).
fn blur(width: usize, height: usize, src: &[f64]) -> Vec<f64> {
    let k = gaussian_taps();
    let half = (SSIM_WINDOW / 2) as isize;
    let pass = |src: &[f64], horizontal: bool| {
        let mut out = vec![0.0; src.len()];
        for y in 0..height {
            for x in 0..width {
                let (mut acc, mut wsum) = (0.0, 0.0);
                for (i, w) in k.iter().enumerate() {
                    let o = i as isize - half;
                    let (sx, sy) = if horizontal {
                        (x as isize + o, y as isize)
                    } else {
                        (x as isize, y as isize + o)
                    };
                    if sx >= 0 && sy >= 0 && (sx as usize) < width && (sy as usize) < height {
                        acc += w * src[sy as usize * width + sx as usize];
                        wsum += w;
                    }
                }
                out[y * width + x] = acc / wsum;
            }
        }
        out
    };
    pass(&pass(src, true), false)
}

/// Mean SSIM of two single-channel images with values in [0, 1] (see
/// [`METRIC_DEFINITIONS`]).
///
/// # Panics
/// If a slice does not hold `width * height` values.
#[must_use]
pub fn ssim(width: usize, height: usize, a: &[f64], b: &[f64]) -> f64 {
    assert!(
        a.len() == width * height && b.len() == a.len(),
        "image size"
    );
    if a.is_empty() {
        return 1.0;
    }
    let prod = |f: &dyn Fn(f64, f64) -> f64| -> Vec<f64> {
        a.iter().zip(b).map(|(x, y)| f(*x, *y)).collect()
    };
    let mu_a = blur(width, height, a);
    let mu_b = blur(width, height, b);
    let aa = blur(width, height, &prod(&|x, _| x * x));
    let bb = blur(width, height, &prod(&|_, y| y * y));
    let ab = blur(width, height, &prod(&|x, y| x * y));
    let mut sum = 0.0;
    for i in 0..a.len() {
        let (ma, mb) = (mu_a[i], mu_b[i]);
        let var_a = (aa[i] - ma * ma).max(0.0);
        let var_b = (bb[i] - mb * mb).max(0.0);
        let cov = ab[i] - ma * mb;
        sum += ((2.0 * ma * mb + SSIM_C1) * (2.0 * cov + SSIM_C2))
            / ((ma * ma + mb * mb + SSIM_C1) * (var_a + var_b + SSIM_C2));
    }
    sum / a.len() as f64
}

/// FLIP's per-pixel error map (LDR-FLIP on the 8-bit sRGB images), row-major.
#[cfg(feature = "flip")]
#[must_use]
pub fn flip_error_map(reference: &EncodedImage, test: &EncodedImage) -> Vec<f32> {
    let r = nv_flip::FlipImageRgb8::with_data(reference.width, reference.height, &reference.srgb8);
    let t = nv_flip::FlipImageRgb8::with_data(test.width, test.height, &test.srgb8);
    nv_flip::flip(r, t, nv_flip::DEFAULT_PIXELS_PER_DEGREE).to_vec()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn constant(w: u32, h: u32, v: f32) -> EncodedImage {
        EncodedImage::from_srgb(w, h, vec![v; (w * h * 3) as usize])
    }

    /// A deterministic textured image (a ramp with a checker), so SSIM sees structure.
    fn pattern(w: u32, h: u32) -> EncodedImage {
        let mut v = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let c = if (x / 4 + y / 4) % 2 == 0 { 0.2 } else { 0.7 };
                let ramp = x as f32 / w as f32 * 0.2;
                v.extend_from_slice(&[c + ramp, c, c * 0.5]);
            }
        }
        EncodedImage::from_srgb(w, h, v)
    }

    #[test]
    fn linear_rmse_is_over_every_channel_of_the_unclipped_radiance() {
        let r = [Rgb(0.0, 0.0, 0.0), Rgb(1.0, 2.0, 3.0)];
        let t = [Rgb(0.1, 0.0, 0.0), Rgb(1.0, 2.0, 3.5)];
        // (0.1^2 + 0.5^2) / 6 values; 3.0 and 3.5 are both above 1 and still differ.
        let want = ((0.01f64 + 0.25) / 6.0).sqrt();
        assert!(
            (rmse_linear(&r, &t) - want).abs() < 1e-7,
            "{}",
            rmse_linear(&r, &t)
        );
        assert_eq!(rmse_linear(&r, &r), 0.0);
    }

    #[test]
    fn identical_images_have_zero_error() {
        let a = pattern(40, 30);
        let (m, map) = compare(&a, &a.clone());
        assert_eq!(m.rmse, 0.0);
        assert_eq!(m.psnr, f64::INFINITY);
        assert_eq!(m.rel_mse, 0.0);
        assert!((m.ssim - 1.0).abs() < 1e-12, "{}", m.ssim);
        assert_eq!(m.flip, Some(0.0));
        assert!(map.unwrap().iter().all(|e| *e == 0.0));
    }

    #[test]
    fn a_constant_offset_gives_the_hand_computed_values() {
        let r = constant(16, 12, 0.5);
        let t = constant(16, 12, 0.6);
        let (m, _) = compare(&r, &t);
        // Every difference is 0.1 (in f32): RMSE 0.1, PSNR 10 log10(1 / 0.01) = 20 dB.
        assert!((m.rmse - 0.1).abs() < 1e-6, "{}", m.rmse);
        assert!((m.psnr - 20.0).abs() < 1e-4, "{}", m.psnr);
        // relMSE = 0.01 / (0.25 + 0.01).
        assert!((m.rel_mse - 0.01 / 0.26).abs() < 1e-6, "{}", m.rel_mse);
        // Flat images: no variance, so SSIM is the luminance term alone:
        // (2 0.5 0.6 + C1) / (0.25 + 0.36 + C1) = 0.6001 / 0.6101.
        assert!((m.ssim - 0.6001 / 0.6101).abs() < 1e-6, "{}", m.ssim);
        let flip = m.flip.unwrap();
        assert!(flip > 0.0 && flip < 1.0, "{flip}");
    }

    #[test]
    fn half_the_pixels_off_by_a_known_amount() {
        // One pixel of two differs by 0.2 in every channel: MSE = 0.04 / 2 = 0.02.
        let r = EncodedImage::from_srgb(2, 1, vec![0.3; 6]);
        let t = EncodedImage::from_srgb(2, 1, vec![0.3, 0.3, 0.3, 0.5, 0.5, 0.5]);
        assert!((mse(&r.srgb, &t.srgb) - 0.02).abs() < 1e-7);
        assert!((psnr(0.02) - 16.989_700_043).abs() < 1e-6);
    }

    #[test]
    fn ssim_drops_with_noise_and_ranks_images() {
        let a = pattern(48, 32);
        let mut slightly = a.srgb.clone();
        let mut very = a.srgb.clone();
        for (i, (s, v)) in slightly.iter_mut().zip(very.iter_mut()).enumerate() {
            let n = if (i * 7919) % 13 < 6 { 1.0 } else { -1.0 };
            *s = (*s + 0.02 * n).clamp(0.0, 1.0);
            *v = (*v + 0.2 * n).clamp(0.0, 1.0);
        }
        let s1 = compare(&a, &EncodedImage::from_srgb(48, 32, slightly)).0;
        let s2 = compare(&a, &EncodedImage::from_srgb(48, 32, very)).0;
        assert!(
            s1.ssim < 1.0 && s2.ssim < s1.ssim,
            "{} {}",
            s1.ssim,
            s2.ssim
        );
        assert!(s2.rmse > s1.rmse && s2.flip.unwrap() > s1.flip.unwrap());
    }

    #[test]
    fn gaussian_window_is_normalised_and_symmetric() {
        let k = gaussian_taps();
        assert!((k.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        assert!((k[0] - k[10]).abs() < 1e-15 && k[5] > k[4]);
        // The centre tap of an 11-tap sigma 1.5 Gaussian, by hand: 1 / sum(exp(-x^2 / 4.5)).
        let s: f64 = (-5..=5).map(|x: i32| (-f64::from(x * x) / 4.5).exp()).sum();
        assert!((k[5] - 1.0 / s).abs() < 1e-12);
    }

    #[test]
    fn encoding_applies_exposure_and_clips() {
        let img = EncodedImage::from_linear(2, 1, &[Rgb(0.5, 2.0, 0.0), Rgb::BLACK], 2.0);
        assert!((img.srgb[0] - 1.0).abs() < 1e-6, "{}", img.srgb[0]);
        assert_eq!(img.srgb8[..3], [255, 255, 0]);
        assert!((img.srgb[3]).abs() < 1e-7);
    }

    /// The window's A/B split measures its sides with `rmse` on films: more samples of a mode
    /// come closer to a high-spp render, a film has none against itself, and films of
    /// different sizes are not compared.
    #[test]
    fn film_rmse_falls_with_samples_and_is_zero_against_itself() {
        use crate::render::render_blocking;
        use crate::report::Mode;
        use crate::sampler::PixelSampler;
        use crate::scene::{AssetCache, build_scene, load_preset};
        use crate::texture::Filter;
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/earth.ron");
        let mut desc = load_preset(&path).expect("earth preset");
        desc.render.width = 64;
        desc.render.height = 48;
        let mut cache = AssetCache::new();
        let mode = Mode::new(Filter::Bilinear, PixelSampler::Jittered);
        let mut render = |spp| {
            let scene = build_scene(&mode.apply(&desc, spp), &path, &mut cache).expect("build");
            EncodedImage::from_film(&render_blocking(&scene, |_| {}), 1.0)
        };
        let (one, sixteen, reference) = (render(1), render(16), render(64));
        let e1 = rmse(&reference, &one).expect("same size");
        let e16 = rmse(&reference, &sixteen).expect("same size");
        assert!(e1 > e16 && e16 > 0.0, "{e1} {e16}");
        assert_eq!(rmse(&reference, &reference), Some(0.0));
        assert_eq!(rmse(&one, &constant(3, 3, 0.5)), None);
        // The same number the report writes for the pair.
        assert_eq!(compare(&reference, &one).0.rmse, e1);
    }
}
