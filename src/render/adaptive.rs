//! Adaptive sampling: which pixels take another sample.
//!
//! The decision reads only the film (deterministic sums), so it is the same for any thread
//! count. Errors are measured on the display-encoded luminance (what a viewer sees): a pixel
//! keeps sampling while
//! - it has one sample and either its first hit differs from a 4-neighbour's in object or in
//!   which lights it sees (an object or shadow edge: the film's edge keys), or it differs from
//!   a 4-neighbour by more than [`CONTRAST_FACTOR`] x threshold where the texture was not
//!   filtered over the pixel's footprint (high local contrast that only more samples
//!   antialias; a footprint filter has already averaged it), or
//! - it has two or more and the standard error of its mean exceeds the threshold, or a
//!   4-neighbour's does (the mask is dilated by one pixel so an edge pixel whose first samples
//!   happened to agree is not left behind);
//!
//! and it has fewer than `max_spp` samples. Flat, texture-filtered interiors have no sample
//! variance (the filter already averaged the texels), so they stop after the first pass.

use super::Film;
use crate::math::{Rgb, linear_to_srgb};
use crate::scene::AdaptiveDesc;
use rayon::prelude::*;

/// After one sample, a pixel is refined when it differs from a neighbour by this many
/// thresholds: neighbours of a smooth, filtered texture differ a little; edges differ a lot.
pub const CONTRAST_FACTOR: f32 = 8.0;

/// The edge-key bit saying the texture was filtered over the pixel's footprint.
const PREFILTERED: u32 = 1 << 31;

/// A sample's luminance as a display value in [0, 1] (exposure applied, sRGB-encoded).
#[must_use]
#[inline]
pub fn display_luminance(l: Rgb, exposure_scale: f32) -> f32 {
    let y = l.luminance() * exposure_scale;
    linear_to_srgb(if y > 0.0 { y.min(1.0) } else { 0.0 })
}

/// Which pixels the next adaptive pass samples (row-major).
#[must_use]
pub fn adaptive_mask(film: &Film, a: &AdaptiveDesc) -> Vec<bool> {
    let (w, h) = (film.width() as usize, film.height() as usize);
    let pixels = film.pixels();
    let stats = film.stats();
    let keys = film.keys();
    let threshold = a.threshold;
    let max_spp = a.max_spp as f32;
    // Mean display luminance and, where it has 2+ samples, whether the pixel is noisy.
    let mean: Vec<f32> = stats
        .par_iter()
        .zip(pixels)
        .map(|(s, p)| if p[3] > 0.0 { s[0] / p[3] } else { 0.0 })
        .collect();
    let noisy: Vec<bool> = stats
        .par_iter()
        .zip(pixels)
        .map(|(s, p)| {
            let n = p[3];
            if n < 2.0 {
                return false;
            }
            let var = ((s[1] - s[0] * s[0] / n) / (n - 1.0)).max(0.0);
            (var / n).sqrt() > threshold
        })
        .collect();
    let mut mask = vec![false; w * h];
    mask.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, m) in row.iter_mut().enumerate() {
            let i = y * w + x;
            let n = pixels[i][3];
            if n >= max_spp {
                continue;
            }
            let neighbours = [
                (x > 0).then(|| i - 1),
                (x + 1 < w).then(|| i + 1),
                (y > 0).then(|| i - w),
                (y + 1 < h).then(|| i + w),
            ];
            *m = if n < 2.0 {
                let prefiltered = keys[i] & PREFILTERED != 0;
                neighbours.iter().flatten().any(|&j| {
                    (keys[j] & !PREFILTERED) != (keys[i] & !PREFILTERED)
                        || (!prefiltered && (mean[j] - mean[i]).abs() > CONTRAST_FACTOR * threshold)
                })
            } else {
                noisy[i] || neighbours.iter().flatten().any(|&j| noisy[j])
            };
        }
    });
    mask
}

#[cfg(test)]
mod tests {
    use super::*;

    fn film_with(values: &[&[f32]]) -> Film {
        // One column of pixels per entry, each with the given samples (grey radiance).
        let mut f = Film::new(values.len() as u32, 1);
        let (sums, stats, _) = f.buffers_mut();
        for (i, samples) in values.iter().enumerate() {
            for &v in *samples {
                let e = display_luminance(Rgb::grey(v), 1.0);
                sums[i][0] += v;
                sums[i][1] += v;
                sums[i][2] += v;
                sums[i][3] += 1.0;
                stats[i][0] += e;
                stats[i][1] += e * e;
            }
        }
        f
    }

    #[test]
    fn one_sample_pixels_refine_at_edges_only() {
        let a = AdaptiveDesc {
            max_spp: 16,
            threshold: 0.01,
        };
        let f = film_with(&[&[0.2], &[0.2], &[0.2], &[0.9], &[0.9]]);
        assert_eq!(adaptive_mask(&f, &a), [false, false, true, true, false]);
    }

    #[test]
    fn object_and_shadow_edges_refine_and_prefiltered_contrast_does_not() {
        let a = AdaptiveDesc {
            max_spp: 16,
            threshold: 0.01,
        };
        // Five prefiltered pixels of a high-contrast texture on object 1; the last sees a
        // different object.
        let mut f = film_with(&[&[0.1], &[0.9], &[0.1], &[0.9], &[0.9]]);
        let (_, _, keys) = f.buffers_mut();
        keys.copy_from_slice(&[
            1 | PREFILTERED,
            1 | PREFILTERED,
            1 | PREFILTERED,
            1 | PREFILTERED,
            2,
        ]);
        assert_eq!(adaptive_mask(&f, &a), [false, false, false, true, true]);
        // A shadow edge: same object, one light blocked.
        let mut f = film_with(&[&[0.5], &[0.5], &[0.5]]);
        let (_, _, keys) = f.buffers_mut();
        keys.copy_from_slice(&[1, 1, 1 | 1 << 16]);
        assert_eq!(adaptive_mask(&f, &a), [false, true, true]);
    }

    #[test]
    fn noisy_pixels_and_their_neighbours_refine_until_max_spp() {
        let a = AdaptiveDesc {
            max_spp: 4,
            threshold: 0.01,
        };
        let f = film_with(&[
            &[0.5, 0.5],
            &[0.5, 0.5],
            &[0.0, 1.0],
            &[0.5, 0.5],
            &[0.5, 0.5],
            &[0.0, 1.0, 0.0, 1.0],
        ]);
        // Pixel 2 is noisy, 1 and 3 are its neighbours; pixel 5 is noisy but done; 4 borders
        // it and still refines.
        assert_eq!(
            adaptive_mask(&f, &a),
            [false, true, true, true, true, false]
        );
    }
}
