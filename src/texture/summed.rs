//! Summed-area tables (Crow, 1984): the integral of an image over any axis-aligned box in four
//! lookups, whatever the box's size. The footprint filter ([`super::footprint`]) integrates
//! the texture over a pixel's footprint with them.
//!
//! The table holds, at every texel corner (i, j), the sum of the texels left of column i and
//! below row j (rows counted from the bottom, as v runs): the antiderivative of the
//! nearest-texel image at the corners. The bilinear image is the nearest-texel image blurred by
//! a one-texel box, so its antiderivative at any real (x, y) is the table blurred by that box,
//! a quadratic B-spline over 3 x 3 corners; a box's integral is four of those. Outside the
//! image each wrap mode extends the sums exactly (see [`SummedArea::box_sum`]).
//!
//! The sums are `f64`: the sum of a million texels in `f32` keeps only 1/16 of a texel's unit,
//! and a 3 x 3 box's mean would be off by a hundredth; in `f64` the difference of two such sums
//! is exact to 1e-9. Written by hand because it is the filter itself: no crate sums a texture
//! under this crate's wrap modes and texel layout.

use super::{ImageData, MipPyramid, Wrap};
use crate::math::{Rgb, floor_fast_f64};

/// The most texels one table sums: 4 M (a 2048 x 2048 image, about 100 MB of sums). A larger
/// image's table sums its finest mip level within that ([`SummedArea::for_pyramid`]).
pub const MAX_TABLE_TEXELS: u64 = 1 << 22;

/// A summed-area table of one level of an image (see the module documentation).
#[derive(Clone, Debug)]
pub struct SummedArea {
    /// The mip level summed (0 unless the image has more than [`MAX_TABLE_TEXELS`] texels).
    level: usize,
    width: u32,
    height: u32,
    /// `sums[j * (width + 1) + i]`: the texels left of column `i` and below row `j`, summed.
    sums: Vec<[f64; 3]>,
}

impl SummedArea {
    /// The table of `image` (which is level `level` of its pyramid), or why there is none (the
    /// memory for it could not be had).
    ///
    /// # Errors
    /// When the sums' memory cannot be allocated.
    pub fn build(image: &ImageData, level: usize) -> Result<Self, String> {
        let (w, h) = (image.width() as usize, image.height() as usize);
        let stride = w + 1;
        let n = stride * (h + 1);
        let mut sums = Vec::new();
        sums.try_reserve_exact(n).map_err(|_| {
            format!(
                "out of memory for the summed-area table of {} ({} MB)",
                image.name,
                (n * 24) >> 20
            )
        })?;
        sums.resize(n, [0.0; 3]);
        for j in 0..h {
            let mut row = [0.0f64; 3];
            for i in 0..w {
                let t = image.texel(i as u32, j as u32).to_array();
                let below = sums[j * stride + i + 1];
                for k in 0..3 {
                    row[k] += f64::from(t[k]);
                }
                sums[(j + 1) * stride + i + 1] =
                    [below[0] + row[0], below[1] + row[1], below[2] + row[2]];
            }
        }
        Ok(Self {
            level,
            width: image.width(),
            height: image.height(),
            sums,
        })
    }

    /// The table for a pyramid's image: of its base, or of its finest level within
    /// [`MAX_TABLE_TEXELS`].
    ///
    /// # Errors
    /// When the sums' memory cannot be allocated.
    pub fn for_pyramid(mip: &MipPyramid) -> Result<Self, String> {
        let level = (0..mip.len())
            .find(|&l| {
                let i = mip.level(l);
                u64::from(i.width()) * u64::from(i.height()) <= MAX_TABLE_TEXELS
            })
            .unwrap_or(mip.len() - 1);
        Self::build(mip.level(level), level)
    }

    /// The mip level this table sums.
    #[must_use]
    pub const fn level(&self) -> usize {
        self.level
    }

    /// Width of the summed level, in texels.
    #[must_use]
    pub const fn width(&self) -> u32 {
        self.width
    }

    /// Height of the summed level, in texels.
    #[must_use]
    pub const fn height(&self) -> u32 {
        self.height
    }

    /// Bytes the sums take.
    #[must_use]
    pub fn bytes(&self) -> usize {
        self.sums.len() * std::mem::size_of::<[f64; 3]>()
    }

    /// The table at corner (`i`, `j`) of the image extended by the wraps: at most four reads.
    #[inline]
    fn corner_wrapped(&self, i: i64, j: i64, wu: Wrap, wv: Wrap) -> [f64; 3] {
        let stride = self.width as usize + 1;
        let tx = axis_terms(wu, i as f64, f64::from(self.width));
        let ty = axis_terms(wv, j as f64, f64::from(self.height));
        let mut out = [0.0; 3];
        for &(cy, ry) in &ty {
            for &(cx, rx) in &tx {
                let c = cx * cy;
                if c != 0.0 {
                    // Every term's point is a corner of the table (integral, in range).
                    let p = self.sums[ry as usize * stride + rx as usize];
                    for ch in 0..3 {
                        out[ch] += c * p[ch];
                    }
                }
            }
        }
        out
    }

    /// The integral of the bilinear image over the box [x0, x1] x [y0, y1] (texel units of the
    /// summed level, texel centres at half-integers; x0 <= x1, y0 <= y1, all finite), extended
    /// beyond the image by the wraps as the bilinear lookup extends it: repeat tiles it, mirror
    /// tiles it mirrored, clamp extends the edge texels and black is 0 outside.
    ///
    /// The bilinear image is the nearest-texel image blurred by a one-texel box, so its
    /// antiderivative at (x, y) is the table (the nearest-texel one, linear between corners)
    /// blurred by that box: along each axis the corners k, k + 1 and k + 2 weighed by a
    /// quadratic B-spline. The box's integral is the antiderivative at its four
    /// corners, added and subtracted: 36 reads, and exact.
    #[must_use]
    #[inline(always)]
    pub fn box_sum(&self, x0: f64, x1: f64, y0: f64, y1: f64, wu: Wrap, wv: Wrap) -> [f64; 3] {
        let (sx0, sx1, sy0, sy1) = (
            Spline::at(x0),
            Spline::at(x1),
            Spline::at(y0),
            Spline::at(y1),
        );
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        let mut out = [0.0; 3];
        if sx0.k >= 0 && sy0.k >= 0 && sx1.k + 2 <= w && sy1.k + 2 <= h {
            // Inside the image (nearly every box): the rows straight from the table.
            let stride = self.width as usize + 1;
            let (c0, c1) = (sx0.k as usize, sx1.k as usize);
            for (sy, sign) in [(sy1, 1.0), (sy0, -1.0)] {
                for (r, wr) in sy.w.iter().enumerate() {
                    let row = &self.sums[(sy.k as usize + r) * stride..];
                    let (a, b) = (&row[c1..c1 + 3], &row[c0..c0 + 3]);
                    let wr = sign * wr;
                    for ch in 0..3 {
                        let right = sx1.w[0] * a[0][ch] + sx1.w[1] * a[1][ch] + sx1.w[2] * a[2][ch];
                        let left = sx0.w[0] * b[0][ch] + sx0.w[1] * b[1][ch] + sx0.w[2] * b[2][ch];
                        out[ch] += wr * (right - left);
                    }
                }
            }
            return out;
        }
        for (sy, sign_y) in [(sy1, 1.0), (sy0, -1.0)] {
            for (r, wr) in sy.w.iter().enumerate() {
                for (sx, sign_x) in [(sx1, 1.0), (sx0, -1.0)] {
                    for (c, wc) in sx.w.iter().enumerate() {
                        let p = self.corner_wrapped(sx.k + c as i64, sy.k + r as i64, wu, wv);
                        let k = sign_x * sign_y * wr * wc;
                        for ch in 0..3 {
                            out[ch] += k * p[ch];
                        }
                    }
                }
            }
        }
        out
    }

    /// The mean of the bilinear image over the box centred at (`cx`, `cy`) with half-widths
    /// `hx`, `hy` (texel units of the summed level, both positive).
    #[must_use]
    #[inline(always)]
    pub fn box_mean(&self, cx: f64, cy: f64, hx: f64, hy: f64, wu: Wrap, wv: Wrap) -> Rgb {
        let s = self.box_sum(cx - hx, cx + hx, cy - hy, cy + hy, wu, wv);
        let k = 0.25 / (hx * hy);
        Rgb((s[0] * k) as f32, (s[1] * k) as f32, (s[2] * k) as f32)
    }
}

/// Where the antiderivative at a coordinate x reads along one axis: the corners `k`, `k + 1`,
/// `k + 2` with weights `w`, for k = floor(x - 1/2) and t = x - 1/2 - k: `(1 - t)^2 / 2`,
/// `1/2 + t - t^2`, `t^2 / 2` (the table, linear between corners, blurred by a one-texel box).
#[derive(Clone, Copy, Debug)]
struct Spline {
    k: i64,
    w: [f64; 3],
}

impl Spline {
    #[inline(always)]
    fn at(x: f64) -> Self {
        let xs = x - 0.5;
        let k = floor_fast_f64(xs);
        let t = xs - k;
        Self {
            k: k as i64,
            w: [0.5 * (1.0 - t) * (1.0 - t), 0.5 + t - t * t, 0.5 * t * t],
        }
    }
}

/// The integral along one axis up to `x` of the image (`n` texels) extended by `wrap`, as
/// coefficients on the integral up to points of [0, n]: E(x) = sum of c F(r) over the terms
/// (c, r). Repeat: q whole periods and the rest; mirror: the same over periods of 2n, the second
/// half read backwards; clamp: the edge texel's column repeated; black: nothing outside.
#[inline]
fn axis_terms(wrap: Wrap, x: f64, n: f64) -> [(f64, f64); 2] {
    if (0.0..=n).contains(&x) {
        return [(1.0, x), (0.0, 0.0)];
    }
    match wrap {
        Wrap::Repeat => {
            let q = (x / n).floor();
            [(q, n), (1.0, (x - q * n).clamp(0.0, n))]
        }
        Wrap::Mirror => {
            let p = 2.0 * n;
            let q = (x / p).floor();
            let s = (x - q * p).clamp(0.0, p);
            if s <= n {
                [(2.0 * q, n), (1.0, s)]
            } else {
                [(2.0 * q + 2.0, n), (-1.0, p - s)]
            }
        }
        Wrap::Clamp if x < 0.0 => [(x, 1.0), (0.0, 0.0)],
        // F(n) + (x - n) times the last column, which is F(n) - F(n - 1).
        Wrap::Clamp => [(1.0 + x - n, n), (n - x, n - 1.0)],
        Wrap::Black => [(1.0, x.clamp(0.0, n)), (0.0, 0.0)],
    }
}

#[cfg(test)]
mod tests;
