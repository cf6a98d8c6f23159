//! Pixel sample patterns, the book's set: regular, random, jittered, n-rooks, multi-jittered and
//! Hammersley. Each sample is computed on its own from (seed, pixel, index, count), in O(1), with
//! no stored sets: the same point on every run and every thread count, and no allocation.

mod pixel_filter;

pub use pixel_filter::{GAUSSIAN_RADIUS, GAUSSIAN_SIGMA, PixelFilter};

use crate::math::{SampleRng, Vec2, hash3};
use serde::{Deserialize, Serialize};

/// Where in a pixel its samples go.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[derive(Serialize, Deserialize)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum PixelSampler {
    /// A grid of cell centres (aliases like one sample, just finer).
    #[strum(
        message = "Samples on a regular grid of cell centres: cheap, but aliases like a finer single sample."
    )]
    Regular,
    /// Independent uniform points.
    #[strum(message = "Independent uniform random points: unbiased but clumpy.")]
    Random,
    /// One random point per grid cell (stratified).
    #[default]
    #[strum(message = "One random point in each cell of a grid: stratified in 2D.")]
    Jittered,
    /// One point per row and per column of an N x N grid (Shirley's n-rooks).
    #[strum(message = "One point in every row and every column: stratified in x and in y.")]
    NRooks,
    /// Kensler's correlated multi-jittered: jittered and n-rooks at once.
    #[strum(
        message = "Kensler's correlated multi-jittered: stratified in 2D and in x and y at once."
    )]
    MultiJittered,
    /// The Hammersley set (x = i / N, y = radical inverse of i), scrambled per pixel.
    #[strum(message = "The Hammersley low-discrepancy set, scrambled per pixel.")]
    Hammersley,
}

impl crate::names::Named for PixelSampler {
    const WHAT: &'static str = "sampler";
}

impl PixelSampler {
    /// Sample `index` of `count` in pixel `pixel`, as an offset in [0, 1)^2 from the pixel's
    /// top-left corner.
    #[must_use]
    #[inline]
    pub fn sample(self, seed: u32, pixel: u32, index: u32, count: u32) -> Vec2 {
        let count = count.max(1);
        // Indices are below `count` but for callers that wrap around; skip the division then.
        let index = if index < count { index } else { index % count };
        // The per-pixel pattern (a permutation or shift shared by the pixel's samples) is hashed
        // only by the samplers that use it: three hash rounds saved per jittered sample.
        let pattern = || hash3(seed, pixel, 0x5a3d_c0de);
        let mut rng = SampleRng::new(seed, pixel, index);
        let p = match self {
            // One sample per pixel (every interactive pass): the cell is the pixel, no divisions.
            Self::Regular if count == 1 => Vec2::splat(0.5),
            Self::Jittered if count == 1 => Vec2::new(rng.next_f32(), rng.next_f32()),
            Self::Regular | Self::Jittered => {
                let (cols, rows) = grid(count);
                let (i, j) = (index % cols, index / cols);
                let (jx, jy) = if self == Self::Regular {
                    (0.5, 0.5)
                } else {
                    (rng.next_f32(), rng.next_f32())
                };
                Vec2::new((i as f32 + jx) / cols as f32, (j as f32 + jy) / rows as f32)
            }
            Self::Random => Vec2::new(rng.next_f32(), rng.next_f32()),
            Self::NRooks => {
                let n = count as f32;
                let row = permute(index, count, pattern());
                Vec2::new(
                    (index as f32 + rng.next_f32()) / n,
                    (row as f32 + rng.next_f32()) / n,
                )
            }
            Self::MultiJittered => cmj(index, count, pattern()),
            Self::Hammersley => {
                let n = count as f32;
                let pattern = pattern();
                let shift = (pattern >> 8) as f32 * (1.0 / 16_777_216.0);
                let x = (index as f32 + 0.5) / n + shift;
                let y = radical_inverse_2(index) ^ hash3(pattern, 1, 2);
                Vec2::new(x - x.floor(), (y >> 8) as f32 * (1.0 / 16_777_216.0))
            }
        };
        p.min(Vec2::splat(1.0 - f32::EPSILON / 2.0))
    }
}

/// A near-square grid with at least `count` cells: columns x rows.
#[must_use]
pub fn grid(count: u32) -> (u32, u32) {
    let cols = (count as f32).sqrt().ceil().max(1.0) as u32;
    let rows = count.div_ceil(cols);
    (cols, rows)
}

/// Van der Corput's radical inverse in base 2, as 32 fraction bits.
#[inline]
fn radical_inverse_2(i: u32) -> u32 {
    i.reverse_bits()
}

/// A pseudo-random permutation of [0, l) indexed by `i`, chosen by `p` (Kensler 2013).
#[must_use]
#[inline]
pub fn permute(mut i: u32, l: u32, p: u32) -> u32 {
    if l <= 1 {
        return 0;
    }
    let mut w = l - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= p;
        i = i.wrapping_mul(0xe170_893d);
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i = i.wrapping_mul(0x0929_eb3f);
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | p >> 27);
        i = i.wrapping_mul(0x6935_fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dc_b303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860_a3df);
        i &= w;
        i ^= i >> 5;
        if i < l {
            break;
        }
    }
    (i.wrapping_add(p)) % l
}

#[inline]
fn randfloat(mut i: u32, p: u32) -> f32 {
    i ^= p;
    i ^= i >> 17;
    i ^= i >> 10;
    i = i.wrapping_mul(0xb365_34e5);
    i ^= i >> 12;
    i ^= i >> 21;
    i = i.wrapping_mul(0x93fc_4795);
    i ^= 0xdf6e_307f;
    i ^= i >> 17;
    i = i.wrapping_mul(1 | p >> 18);
    (i >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Correlated multi-jittered sample `s` of `count` (Kensler, "Correlated Multi-Jittered
/// Sampling", 2013): an m x n jittered grid whose points also fall one per column and row of the
/// fine grid.
#[inline]
fn cmj(s: u32, count: u32, p: u32) -> Vec2 {
    let m = (count as f32).sqrt().floor().max(1.0) as u32;
    let n = count.div_ceil(m);
    let sx = permute(s % m, m, p.wrapping_mul(0xa511_e9b3));
    let sy = permute(s / m, n, p.wrapping_mul(0x63d8_3595));
    let jx = randfloat(s, p.wrapping_mul(0xa399_d265));
    let jy = randfloat(s, p.wrapping_mul(0x711a_d6a5));
    Vec2::new(
        ((s % m) as f32 + (sy as f32 + jx) / n as f32) / m as f32,
        ((s / m) as f32 + (sx as f32 + jy) / m as f32) / n as f32,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use strum::VariantArray;

    fn points(s: PixelSampler, n: u32, pixel: u32) -> Vec<Vec2> {
        (0..n).map(|i| s.sample(7, pixel, i, n)).collect()
    }

    #[test]
    fn all_points_in_the_unit_square_and_deterministic() {
        for &s in PixelSampler::VARIANTS {
            for n in [1, 2, 3, 5, 16, 17, 64, 100] {
                let a = points(s, n, 3);
                assert_eq!(a, points(s, n, 3));
                assert!(
                    a.iter()
                        .all(|p| (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y)),
                    "{s:?} {n}"
                );
            }
        }
    }

    #[test]
    fn jittered_has_one_point_per_cell() {
        for n in [4, 16, 64] {
            let k = (n as f32).sqrt() as u32;
            let mut seen = vec![false; n as usize];
            for p in points(PixelSampler::Jittered, n, 11) {
                let cell = (p.y * k as f32) as u32 * k + (p.x * k as f32) as u32;
                assert!(!seen[cell as usize]);
                seen[cell as usize] = true;
            }
        }
    }

    #[test]
    fn n_rooks_and_multi_jittered_have_one_point_per_row_and_column() {
        for s in [
            PixelSampler::NRooks,
            PixelSampler::MultiJittered,
            PixelSampler::Hammersley,
        ] {
            // Hammersley is stratified in y (the radical inverse) for powers of two only.
            let counts: &[u32] = if s == PixelSampler::Hammersley {
                &[4, 16, 64, 256]
            } else {
                &[4, 9, 16, 64, 256]
            };
            for &n in counts {
                for pixel in 0..20 {
                    let (mut cols, mut rows) = (vec![0; n as usize], vec![0; n as usize]);
                    for p in points(s, n, pixel) {
                        cols[(p.x * n as f32) as usize] += 1;
                        rows[(p.y * n as f32) as usize] += 1;
                    }
                    assert!(
                        cols.iter().all(|&c| c == 1) && rows.iter().all(|&c| c == 1),
                        "{s:?} {n}"
                    );
                }
            }
        }
    }

    #[test]
    fn multi_jittered_is_also_jittered() {
        let n = 16;
        let mut seen = [false; 16];
        for p in points(PixelSampler::MultiJittered, n, 5) {
            let cell = (p.y * 4.0) as usize * 4 + (p.x * 4.0) as usize;
            assert!(!seen[cell]);
            seen[cell] = true;
        }
    }

    #[test]
    fn jittered_and_multi_jittered_fill_their_grid_for_any_count() {
        // Non-square counts: jittered uses a cols x rows grid with at least `count` cells, one
        // point in each of `count` distinct cells; multi-jittered an m x n grid (m = floor(sqrt)),
        // one point per coarse cell, and at most one per fine column (m n of them) and per fine
        // row.
        for n in [2, 3, 5, 7, 12, 17, 30] {
            for pixel in 0..10 {
                let (cols, rows) = grid(n);
                let mut seen = vec![false; (cols * rows) as usize];
                for p in points(PixelSampler::Jittered, n, pixel) {
                    let cell = (p.y * rows as f32) as u32 * cols + (p.x * cols as f32) as u32;
                    assert!(
                        !seen[cell as usize],
                        "jittered {n}: two points in cell {cell}"
                    );
                    seen[cell as usize] = true;
                }
                let m = (n as f32).sqrt().floor() as u32;
                let k = n.div_ceil(m);
                let fine = (m * k) as usize;
                let (mut coarse, mut fx, mut fy) = (vec![0; fine], vec![0; fine], vec![0; fine]);
                for p in points(PixelSampler::MultiJittered, n, pixel) {
                    coarse[(p.y * k as f32) as usize * m as usize + (p.x * m as f32) as usize] += 1;
                    fx[(p.x * fine as f32) as usize] += 1;
                    fy[(p.y * fine as f32) as usize] += 1;
                }
                assert!(
                    coarse.iter().all(|&c| c <= 1),
                    "multi-jittered {n}: {coarse:?}"
                );
                assert!(fx.iter().chain(&fy).all(|&c| c <= 1), "multi-jittered {n}");
            }
        }
    }

    #[test]
    fn regular_is_the_grid_of_cell_centres_and_hammersley_is_stratified_in_x() {
        let pts = points(PixelSampler::Regular, 4, 9);
        assert_eq!(
            pts,
            [
                Vec2::new(0.25, 0.25),
                Vec2::new(0.75, 0.25),
                Vec2::new(0.25, 0.75),
                Vec2::new(0.75, 0.75)
            ]
        );
        for n in [3, 10, 33] {
            let mut cols = vec![0; n as usize];
            for p in points(PixelSampler::Hammersley, n, 4) {
                cols[(p.x * n as f32) as usize] += 1;
            }
            assert!(cols.iter().all(|&c| c == 1), "hammersley {n}: {cols:?}");
        }
    }

    #[test]
    fn patterns_differ_between_pixels() {
        for s in [
            PixelSampler::Random,
            PixelSampler::Jittered,
            PixelSampler::NRooks,
            PixelSampler::MultiJittered,
            PixelSampler::Hammersley,
        ] {
            assert_ne!(points(s, 16, 1), points(s, 16, 2), "{s:?}");
        }
    }

    #[test]
    fn permute_is_a_permutation() {
        for l in [1, 2, 7, 64, 1000] {
            let mut seen = vec![false; l as usize];
            for i in 0..l {
                let j = permute(i, l, 0xdead_beef) as usize;
                assert!(!seen[j]);
                seen[j] = true;
            }
        }
    }
}
