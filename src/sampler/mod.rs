//! Pixel sample patterns, the book's set: regular, random, jittered, n-rooks, multi-jittered and
//! Hammersley. Each sample is computed on its own from (seed, pixel, index, count), in O(1), with
//! no stored sets: the same point on every run and every thread count, and no allocation.

mod pixel_filter;

pub use pixel_filter::{GAUSSIAN_RADIUS, GAUSSIAN_SIGMA, PixelFilter};

use crate::math::{SampleRng, Vec2, hash3, hash3_lanes, pcg_lanes, unit_f32};
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
                let (jx, jy) = if self == Self::Regular {
                    (0.5, 0.5)
                } else {
                    (rng.next_f32(), rng.next_f32())
                };
                let cell = Rows::new(count).cell(index);
                cell.point(jx, jy)
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

impl PixelSampler {
    /// [`PixelSampler::sample`] for `N` pixels at once (`pixels`, one sample `index` of `count`),
    /// lane-wise where the point is one hash and two draws: random, and jittered or regular at
    /// one sample per pixel (every interactive pass and `texplore bench`). The same u32
    /// arithmetic as the scalar sampler in lane loops ([`hash3_lanes`], [`pcg_lanes`]), so each
    /// lane is bit for bit the scalar point; `None` for the other samplers and counts, which
    /// the caller samples per lane.
    #[must_use]
    #[inline(always)]
    pub fn sample_lanes<const N: usize>(
        self,
        seed: u32,
        pixels: &[u32; N],
        index: u32,
        count: u32,
    ) -> Option<([f32; N], [f32; N])> {
        let count = count.max(1);
        let index = if index < count { index } else { index % count };
        let cap = 1.0 - f32::EPSILON / 2.0;
        match self {
            Self::Regular if count == 1 => Some(([0.5; N], [0.5; N])),
            Self::Random | Self::Jittered if self == Self::Random || count == 1 => {
                let mut h = hash3_lanes(seed, pixels, index);
                pcg_lanes(&mut h);
                let x = h.map(|b| unit_f32(b).min(cap));
                pcg_lanes(&mut h);
                let y = h.map(|b| unit_f32(b).min(cap));
                Some((x, y))
            }
            _ => None,
        }
    }
}

impl PixelSampler {
    /// The size (pixels along x and y) of the part of the pixel that sample `index` of `count`
    /// stands for: its cell for the stratified layouts (regular, jittered, multi-jittered),
    /// which tile the pixel; a square of area 1 / `count` for the others. Texture footprints
    /// take this size, so a footprint filter over all of a pixel's samples covers the pixel
    /// once.
    #[must_use]
    #[inline]
    pub fn cell_size(self, index: u32, count: u32) -> Vec2 {
        let count = count.max(1);
        let index = if index < count { index } else { index % count };
        match self {
            Self::Regular | Self::Jittered => Rows::new(count).cell(index).size(),
            Self::MultiJittered => {
                let m = count.isqrt().max(1);
                if count.is_multiple_of(m) {
                    Vec2::new(1.0 / m as f32, 1.0 / (count / m) as f32)
                } else {
                    Rows::new(count).cell(index).size()
                }
            }
            _ => Vec2::splat(1.0 / (count as f32).sqrt()),
        }
    }
}

/// The pixel cut into exactly `count` cells of equal area: `rows` = round(sqrt(count)) rows,
/// row `j` holding `floor((j + 1) count / rows) - floor(j count / rows)` cells (count / rows,
/// rounded down or up) side by side across the full width, and as tall as its share of the
/// count (cells / count). Every cell has area 1 / count, so one point per cell covers the whole
/// pixel evenly for any count; when `rows` divides `count` it is the plain cols x rows grid.
///
/// (A ceil(sqrt n)-column grid filled row by row leaves its last cells empty when n does not
/// fill it, 8, 15, 27, 32, 60 ...: part of every pixel was never sampled.)
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rows {
    /// The number of cells.
    pub count: u32,
    /// The number of rows.
    pub rows: u32,
}

/// One cell of [`Rows`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cell {
    /// Its row.
    pub row: u32,
    /// Its column within the row.
    pub col: u32,
    /// How many cells the row has.
    pub cols: u32,
    /// How many cells the rows above it hold together (its row's top edge is at `before / count`).
    pub before: u32,
    /// The total number of cells.
    pub count: u32,
    /// The number of rows.
    pub rows: u32,
    /// Whether every row has the same number of cells (`rows` divides `count`).
    pub equal_rows: bool,
}

impl Rows {
    /// The layout of `count` cells (at least 1).
    #[must_use]
    #[inline]
    pub fn new(count: u32) -> Self {
        let count = count.max(1);
        // round(sqrt(count)) in integers: without SSE4.1 (the x86-64 baseline) f32::round is
        // a libm call, 1 % of a 16-spp render. n is never (r + 1/2)^2, so no ties.
        let r = count.isqrt();
        let rows = if count - r * r > r { r + 1 } else { r };
        Self { count, rows }
    }

    /// The cells above row `j` (row `j` starts at this index).
    #[must_use]
    #[inline]
    pub fn start(self, j: u32) -> u32 {
        (u64::from(j) * u64::from(self.count) / u64::from(self.rows)) as u32
    }

    /// Cell `index` (below `count`), rows filled left to right, top to bottom.
    #[must_use]
    #[inline]
    pub fn cell(self, index: u32) -> Cell {
        // Equal rows (every square count and most others): the plain grid, one division for the
        // row as before the rows were introduced (the per-sample cost of the common case).
        let cols = self.count / self.rows;
        if cols * self.rows == self.count {
            let row = index / cols;
            let before = row * cols;
            return Cell {
                row,
                col: index - before,
                cols,
                before,
                count: self.count,
                rows: self.rows,
                equal_rows: true,
            };
        }
        let (n, r) = (u64::from(self.count), u64::from(self.rows));
        // The row j with start(j) <= index < start(j + 1).
        let row = (((u64::from(index) + 1) * r - 1) / n) as u32;
        let before = self.start(row);
        let cols = self.start(row + 1) - before;
        Cell {
            row,
            col: index - before,
            cols,
            before,
            count: self.count,
            rows: self.rows,
            equal_rows: false,
        }
    }
}

impl Cell {
    /// The cell's width and height (pixels): 1 / cols by cols / count.
    #[must_use]
    #[inline]
    pub fn size(self) -> Vec2 {
        if self.equal_rows {
            Vec2::new(1.0 / self.cols as f32, 1.0 / self.rows as f32)
        } else {
            Vec2::new(1.0 / self.cols as f32, self.cols as f32 / self.count as f32)
        }
    }

    /// The point at (`fx`, `fy`) in [0, 1)^2 within the cell, as a pixel offset.
    #[must_use]
    #[inline]
    pub fn point(self, fx: f32, fy: f32) -> Vec2 {
        let x = (self.col as f32 + fx) / self.cols as f32;
        let y = if self.equal_rows {
            // Equal rows: the plain grid, computed as it always was (bit for bit).
            (self.row as f32 + fy) / self.rows as f32
        } else {
            (self.before as f32 + self.cols as f32 * fy) / self.count as f32
        };
        Vec2::new(x, y)
    }
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
///
/// When m = floor(sqrt(count)) does not divide `count`, the m x n grid would have empty cells at
/// the bottom; the points go instead into the equal-area cells of [`Rows`], one per cell, with
/// the same correlated construction: exactly one point in each of `count` horizontal strips
/// (a permutation of the row's cells, shared by the rows of equal length) and, within rows of
/// equal length, one per fine column.
#[inline]
fn cmj(s: u32, count: u32, p: u32) -> Vec2 {
    let m = count.isqrt().max(1);
    if !count.is_multiple_of(m) {
        let cell = Rows::new(count).cell(s);
        let sub_y = permute(cell.col, cell.cols, p.wrapping_mul(0xa511_e9b3));
        let sub_x = permute(cell.row, cell.rows, p.wrapping_mul(0x63d8_3595));
        let jx = randfloat(s, p.wrapping_mul(0xa399_d265));
        let jy = randfloat(s, p.wrapping_mul(0x711a_d6a5));
        return Vec2::new(
            (cell.col as f32 + (sub_x as f32 + jx) / cell.rows as f32) / cell.cols as f32,
            (cell.before as f32 + sub_y as f32 + jy) / count as f32,
        );
    }
    let n = count / m;
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
    fn lane_samples_are_the_scalar_points_bit_for_bit() {
        let pixels = [0, 1, 2, 3, 639, 640, 307_199, u32::MAX];
        let mut lane_wise = Vec::new();
        for &s in PixelSampler::VARIANTS {
            for count in [0, 1, 2, 4, 16] {
                for (seed, index) in [(0, 0), (7, 1), (0xada9_7e55, 3), (u32::MAX, 17)] {
                    let Some((x, y)) = s.sample_lanes(seed, &pixels, index, count) else {
                        continue;
                    };
                    lane_wise.push((s, count));
                    for (i, &p) in pixels.iter().enumerate() {
                        let want = s.sample(seed, p, index, count);
                        assert_eq!(
                            (x[i].to_bits(), y[i].to_bits()),
                            (want.x.to_bits(), want.y.to_bits()),
                            "{s} sample {index} of {count}, pixel {p}, seed {seed}"
                        );
                    }
                }
            }
        }
        // Which ones are lane-wise: random always, jittered and regular at one sample.
        lane_wise.dedup();
        let random = |c| (PixelSampler::Random, c);
        assert_eq!(
            lane_wise,
            [
                (PixelSampler::Regular, 0),
                (PixelSampler::Regular, 1),
                random(0),
                random(1),
                random(2),
                random(4),
                random(16),
                (PixelSampler::Jittered, 0),
                (PixelSampler::Jittered, 1),
            ]
        );
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

    /// The largest distance from any point of the pixel (a 64 x 64 grid of probes, corners
    /// included) to its nearest sample: the biggest hole the samples leave.
    fn covering_radius(pts: &[Vec2]) -> f32 {
        let mut worst = 0.0f32;
        for a in 0..=64 {
            for b in 0..=64 {
                let q = Vec2::new(a as f32 / 64.0, b as f32 / 64.0);
                let d = pts.iter().map(|p| p.distance(q)).fold(f32::MAX, f32::min);
                worst = worst.max(d);
            }
        }
        worst
    }

    #[test]
    fn cell_sizes_tile_the_pixel_and_hold_their_points() {
        for n in 1..=60u32 {
            for s in [
                PixelSampler::Regular,
                PixelSampler::Jittered,
                PixelSampler::MultiJittered,
            ] {
                let area: f32 = (0..n)
                    .map(|i| {
                        let c = s.cell_size(i, n);
                        c.x * c.y
                    })
                    .sum();
                assert!((area - 1.0).abs() < 1e-4, "{s:?} {n}: {area}");
            }
            // A regular point is its cell's centre: the cell around it stays in the pixel.
            for i in 0..n {
                let (p, c) = (
                    PixelSampler::Regular.sample(1, 0, i, n),
                    PixelSampler::Regular.cell_size(i, n),
                );
                let (lo, hi) = (p - c * 0.5, p + c * 0.5);
                assert!(
                    lo.min_element() > -1e-6 && hi.max_element() < 1.0 + 1e-6,
                    "{n} {i}: {p} {c}"
                );
            }
            let r = PixelSampler::Random.cell_size(0, n);
            assert!((r.x * r.y * n as f32 - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn rows_are_the_rounded_square_root() {
        for n in 1..200_000u32 {
            assert_eq!(Rows::new(n).rows, f64::from(n).sqrt().round() as u32, "{n}");
        }
    }

    #[test]
    fn regular_covers_the_pixel_evenly_for_every_count() {
        // n = 1..100: the grid's centroid is the pixel centre (a linear ramp is seen at its
        // mean value) and no hole is wider than a cell of area 1 / n would allow. A
        // ceil(sqrt n)-column grid filled row by row fails both at 3, 8, 15, 27, 32, 60 ...
        for n in 1..=100u32 {
            let pts = points(PixelSampler::Regular, n, 0);
            let mean = pts.iter().fold(Vec2::ZERO, |a, p| a + *p) / n as f32;
            assert!(
                (mean - Vec2::splat(0.5)).abs().max_element() < 1e-5,
                "regular {n}: centroid {mean}"
            );
            let r = covering_radius(&pts);
            assert!(
                r <= 1.0 / (n as f32).sqrt(),
                "regular {n}: a hole of radius {r}"
            );
        }
    }

    #[test]
    fn every_random_sampler_fills_the_pixel_evenly_for_every_count() {
        // n = 1..100: the points of many pixels, binned on an 8 x 8 grid, give every bin its
        // share (1/64) within 12 %: five standard deviations of independent points, which the
        // stratified samplers beat by far. A pattern that never samples part of the pixel leaves
        // a bin (nearly) empty.
        let k = 8usize;
        for &s in PixelSampler::VARIANTS {
            if s == PixelSampler::Regular {
                continue;
            }
            for n in 1..=100u32 {
                let pixels = 128_000 / n;
                let mut bins = vec![0u32; k * k];
                for pixel in 0..pixels {
                    for i in 0..n {
                        let p = s.sample(3, pixel, i, n);
                        bins[(p.y * k as f32) as usize * k + (p.x * k as f32) as usize] += 1;
                    }
                }
                let expect = f64::from(pixels * n) / (k * k) as f64;
                let worst = bins
                    .iter()
                    .map(|&b| (f64::from(b) / expect - 1.0).abs())
                    .fold(0.0, f64::max);
                assert!(worst < 0.12, "{s:?} {n}: a bin off its share by {worst:.3}");
            }
        }
    }

    #[test]
    fn jittered_and_multi_jittered_put_one_point_in_each_equal_area_cell_for_any_count() {
        // Row j of `Rows` is cells_j / n tall with cells_j cells across it: the cells tile the
        // pixel with area 1 / n each, and each holds one point; multi-jittered also puts one
        // point in each of n horizontal strips of height 1 / n.
        for n in 1..=100u32 {
            let layout = Rows::new(n);
            assert_eq!(layout.start(0), 0);
            assert_eq!(layout.start(layout.rows), n);
            for j in 0..layout.rows {
                let cells = layout.start(j + 1) - layout.start(j);
                // Rows of n / rows cells, rounded down or up: near-square cells.
                assert!(
                    cells == n / layout.rows || cells == n / layout.rows + 1,
                    "{n}: row {j}"
                );
            }
            for pixel in 0..10 {
                for s in [PixelSampler::Jittered, PixelSampler::MultiJittered] {
                    let mut seen = vec![false; n as usize];
                    // Multi-jittered keeps Kensler's m x (n / m) grid (m = floor(sqrt n)) when
                    // it is full.
                    let m = (n as f32).sqrt().floor() as u32;
                    let kensler = s == PixelSampler::MultiJittered && n % m == 0;
                    for (i, p) in points(s, n, pixel).into_iter().enumerate() {
                        let cell = if kensler {
                            (p.y * (n / m) as f32) as u32 * m + (p.x * m as f32) as u32
                        } else {
                            // The cell holding p: its row by its band of y, its column by x.
                            let j = (0..layout.rows)
                                .find(|&j| p.y * (n as f32) < layout.start(j + 1) as f32)
                                .unwrap();
                            let cols = layout.start(j + 1) - layout.start(j);
                            layout.start(j) + (p.x * cols as f32) as u32
                        };
                        assert!(
                            !seen[cell as usize],
                            "{s:?} {n}: two points in cell {cell} (sample {i})"
                        );
                        seen[cell as usize] = true;
                    }
                }
                if n % (n as f32).sqrt().floor() as u32 != 0 {
                    let mut strips = vec![0; n as usize];
                    for p in points(PixelSampler::MultiJittered, n, pixel) {
                        strips[(p.y * n as f32) as usize] += 1;
                    }
                    assert!(
                        strips.iter().all(|&c| c == 1),
                        "multi-jittered {n}: {strips:?}"
                    );
                }
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
