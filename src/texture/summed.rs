//! Summed-area tables (Crow, 1984): the integral of an image over any axis-aligned box in a
//! fixed number of reads, whatever the box's size. The footprint filter ([`super::footprint`])
//! integrates the texture over a pixel's footprint with them.
//!
//! A table holds, at every texel corner (i, j), the sum of the texels left of column i and
//! below row j (rows counted from the bottom, as v runs): the antiderivative of the
//! nearest-texel image at the corners. The bilinear image is the nearest-texel image blurred by
//! a one-texel box, so its antiderivative at any real (x, y) is the table blurred by that box,
//! a quadratic B-spline over 3 x 3 corners; a box's integral is four of those (36 reads).
//! Outside the image each wrap mode extends the sums exactly ([`axis_terms`]).
//!
//! **One table per mip level**, from the finest within [`MAX_TABLE_TEXELS`] down to 1 x 1 (a
//! third more than the finest alone), so the footprint filter reads the level at which its
//! boxes span a few texels: the corners a box reads stay close together (in the cache), and
//! its sums small.
//!
//! **Exact sums in few bytes.** Texels are summed in fixed point, as integers in wrapping
//! (modular) arithmetic. A box's integral is a signed combination of corner sums whose
//! weights cancel, so it is computed from differences of corners ([`combine`]): each
//! difference is the sum of a rectangle inside the box's hull, exact modulo 2^32 (or 2^64)
//! however large the corners themselves have grown, hence exact while the hull's own sum fits.
//! The footprint filter keeps a box's hull under [`MAX_HULL_TEXELS`] texels (reading a coarser
//! level if it must). Images whose texels all lie in [-1, 1] (every 8-bit image, alpha, 16-bit
//! PNGs) are summed in `i32` at 2^-16 of the texel unit: 12 bytes a corner. Others (HDR and EXR
//! files) are summed in `i64` with as many fractional bits as their largest texel leaves, at
//! least [`MIN_WIDE_BITS`]: 24 bytes a corner. An image with a texel beyond [`MAX_WIDE_TEXEL`]
//! gets no table ([`TablePlan::Refused`]): its texels cannot be summed to 2^-20 in 64 bits, and
//! the footprint filter reads it with EWA instead. (The `f64` sums this replaced cancelled: one
//! texel of 1e16 turned a flat 0.5 elsewhere to garbage.)
//!
//! Written by hand because it is the filter itself: no crate sums a texture under this crate's
//! wrap modes and texel layout.

use super::{ImageData, MipPyramid, Texels, Wrap, mip::half};
use crate::math::{Rgb, floor_fast_f64};

/// The most texels the finest table sums: 4 M (a 2048 x 2048 image). A larger image's tables
/// start at its finest mip level within that ([`SummedArea::first_level`]).
pub const MAX_TABLE_TEXELS: u64 = 1 << 22;

/// The largest area (texels of the level read) of the hull of a box's corner reads, (width +
/// 3) x (height + 3), whose sums stay exact: below 2^15, so that a sum of texels within [-1, 1]
/// at 2^-16 fits an `i32`.
pub const MAX_HULL_TEXELS: f64 = 32_767.0;

/// Fractional bits of an `i32` table: its texels are multiples of 2^-16.
const NARROW_BITS: i32 = 16;

/// The fewest fractional bits an `i64` table may have (texels to within 2^-21, about 5e-7).
pub const MIN_WIDE_BITS: i32 = 20;

/// An `i64` table's texels times 2^bits stay within 2^47, so a hull's sum (under 2^15 texels)
/// stays within 2^62.
const WIDE_RANGE_BITS: i32 = 47;

/// The largest texel an `i64` table sums to [`MIN_WIDE_BITS`] bits: 2^27, about 1.3e8.
pub const MAX_WIDE_TEXEL: f64 = (1u64 << (WIDE_RANGE_BITS - MIN_WIDE_BITS)) as f64;

/// How an image's tables store their sums, decided from its texels before any is built (the
/// scene's budget reserves their bytes from it).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TablePlan {
    /// `i32` sums at 2^-16 of the texel unit: every texel lies in [-1, 1].
    Narrow,
    /// `i64` sums at 2^-`bits`.
    Wide {
        /// Fractional bits, at least [`MIN_WIDE_BITS`].
        bits: i32,
    },
    /// No table; why (a texel too large to sum exactly).
    Refused(String),
}

impl TablePlan {
    /// The plan for `image`'s tables: from its largest texel (8-bit sRGB images are always
    /// [`TablePlan::Narrow`]).
    #[must_use]
    pub fn for_image(image: &ImageData) -> Self {
        let Texels::Linear(v) = image.texels() else {
            return Self::Narrow;
        };
        let mut m = 0.0f32;
        for t in v {
            m = m.max(t[0].abs()).max(t[1].abs()).max(t[2].abs());
        }
        if !m.is_finite() || v.iter().flatten().any(|c| c.is_nan()) {
            return Self::Refused("it has texels that are not finite numbers".into());
        }
        if m <= 1.0 {
            return Self::Narrow;
        }
        let bits = (f64::from(WIDE_RANGE_BITS) - f64::from(m).log2()).floor() as i32;
        if bits < MIN_WIDE_BITS {
            return Self::Refused(format!(
                "its largest texel, {m:.3e}, is beyond the {MAX_WIDE_TEXEL:.3e} its summed-area \
                 table sums exactly"
            ));
        }
        Self::Wide { bits: bits.min(40) }
    }

    /// Bytes one corner of a table takes under this plan (0: no table).
    #[must_use]
    pub const fn bytes_per_corner(&self) -> u64 {
        match self {
            Self::Narrow => 12,
            Self::Wide { .. } => 24,
            Self::Refused(_) => 0,
        }
    }

    /// Bytes the tables of a `width` x `height` image take under this plan: every level from
    /// the finest within [`MAX_TABLE_TEXELS`] down to 1 x 1, (w + 1) x (h + 1) corners each (and
    /// a third of a corner of padding).
    #[must_use]
    pub fn table_bytes(&self, width: u32, height: u32) -> u64 {
        let (mut w, mut h) = (width, height);
        let mut thirds = 0u64;
        loop {
            if u64::from(w) * u64::from(h) <= MAX_TABLE_TEXELS {
                thirds += 3 * (u64::from(w) + 1) * (u64::from(h) + 1) + 1;
            }
            if w == 1 && h == 1 {
                break;
            }
            (w, h) = (half(w), half(h));
        }
        thirds * self.bytes_per_corner() / 3
    }
}

/// A fixed-point sum: `i32` or `i64`, added, subtracted and scaled in wrapping arithmetic.
pub(crate) trait FixedSum: Copy + Default + Send + Sync + std::fmt::Debug + 'static {
    /// `v` x `scale`, rounded.
    fn quantize(v: f32, scale: f64) -> Self;
    /// `self + o`, wrapping.
    fn add(self, o: Self) -> Self;
    /// `self - o`, wrapping.
    fn sub(self, o: Self) -> Self;
    /// `self` x `c`, wrapping (modulo 2^bits, like the sums themselves).
    fn times(self, c: i64) -> Self;
    /// As `f32` (the nearest).
    fn to_f32(self) -> f32;
}

impl FixedSum for i32 {
    #[inline(always)]
    fn quantize(v: f32, scale: f64) -> Self {
        // Rounded half away from zero (a cast truncates: no libm call).
        let x = f64::from(v) * scale;
        (x + 0.5f64.copysign(x)) as Self
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.wrapping_add(o)
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.wrapping_sub(o)
    }
    #[inline(always)]
    fn times(self, c: i64) -> Self {
        // c modulo 2^32: the product is right modulo 2^32.
        self.wrapping_mul(c as Self)
    }
    #[inline(always)]
    fn to_f32(self) -> f32 {
        self as f32
    }
}

impl FixedSum for i64 {
    #[inline(always)]
    fn quantize(v: f32, scale: f64) -> Self {
        // Rounded half away from zero (a cast truncates: no libm call).
        let x = f64::from(v) * scale;
        (x + 0.5f64.copysign(x)) as Self
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.wrapping_add(o)
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.wrapping_sub(o)
    }
    #[inline(always)]
    fn times(self, c: i64) -> Self {
        self.wrapping_mul(c)
    }
    #[inline(always)]
    fn to_f32(self) -> f32 {
        self as f32
    }
}

/// The table of one mip level.
#[derive(Clone, Debug)]
pub(crate) struct Level<T> {
    width: u32,
    height: u32,
    /// `sums[3 k..3 k + 3]` for corner k = `j * (width + 1) + i`: the texels left of column
    /// `i` and below row `j`, summed (wrapping), red, green and blue; one element of padding at
    /// the end, so that every corner reads as four lanes ([`Level::at`]).
    sums: Vec<T>,
}

/// The tables of every level from `first` down, in one fixed-point type.
#[derive(Clone, Debug)]
pub(crate) struct Table<T> {
    /// The mip level `levels[0]` sums.
    first: usize,
    /// The texel unit's value of one integer step: 2^-bits.
    quantum: f32,
    levels: Vec<Level<T>>,
}

/// A corner's sums as four lanes (red, green, blue, and a fourth that is ignored): one vector.
type Lanes<T> = [T; 4];

/// The 6 x 6 corners a box reads: rows `ky0..ky0 + 3` then `ky1..ky1 + 3`, each the columns
/// `kx0..kx0 + 3` then `kx1..kx1 + 3`.
type Corners<T> = [[Lanes<T>; 6]; 6];

/// Lane-wise `a - b`, wrapping.
#[inline(always)]
fn sub4<T: FixedSum>(a: Lanes<T>, b: Lanes<T>) -> Lanes<T> {
    [
        a[0].sub(b[0]),
        a[1].sub(b[1]),
        a[2].sub(b[2]),
        a[3].sub(b[3]),
    ]
}

impl<T: FixedSum> Level<T> {
    /// The table of `image` at 2^`bits` to the texel unit.
    fn build(image: &ImageData, bits: i32) -> Result<Self, String> {
        let (w, h) = (image.width() as usize, image.height() as usize);
        let stride = w + 1;
        let n = 3 * stride * (h + 1) + 1;
        let mut sums = Vec::new();
        sums.try_reserve_exact(n).map_err(|_| {
            format!(
                "out of memory for the summed-area table of {} ({} MB)",
                image.name,
                (n * std::mem::size_of::<T>()) >> 20
            )
        })?;
        sums.resize(n, T::default());
        let scale = f64::from(bits).exp2();
        for j in 0..h {
            let mut row = [T::default(); 3];
            for i in 0..w {
                let t = image.texel(i as u32, j as u32).to_array();
                let (below, here) = (3 * (j * stride + i + 1), 3 * ((j + 1) * stride + i + 1));
                for k in 0..3 {
                    row[k] = row[k].add(T::quantize(t[k], scale));
                    sums[here + k] = sums[below + k].add(row[k]);
                }
            }
        }
        Ok(Self {
            width: image.width(),
            height: image.height(),
            sums,
        })
    }

    /// The three corners from corner `k` along a row, as lanes (one slice, one bounds check).
    #[inline(always)]
    fn three(&self, k: usize) -> [Lanes<T>; 3] {
        let s: &[T; 10] = self.sums[3 * k..3 * k + 10]
            .try_into()
            .unwrap_or_else(|_| unreachable!("ten elements"));
        [
            [s[0], s[1], s[2], s[3]],
            [s[3], s[4], s[5], s[6]],
            [s[6], s[7], s[8], s[9]],
        ]
    }

    /// The integral (in integer steps) of the bilinear image over the box [x0, x1] x [y0, y1]
    /// (texel units of this level, texel centres at half-integers; x0 <= x1, y0 <= y1, all
    /// finite, the hull (x1 - x0 + 3) (y1 - y0 + 3) within [`MAX_HULL_TEXELS`]), extended beyond
    /// the image by the wraps as the bilinear lookup extends it: repeat tiles it, mirror tiles
    /// it mirrored, clamp extends the edge texels and black is 0 outside.
    ///
    /// Along each axis the antiderivative at a point reads the corners k, k + 1 and k + 2,
    /// weighed by a quadratic B-spline ([`Spline`]); the box's integral is the antiderivative
    /// at its four corners, added and subtracted: 36 reads.
    #[inline(always)]
    fn box_sum(&self, x0: f64, x1: f64, y0: f64, y1: f64, wu: Wrap, wv: Wrap) -> [f32; 3] {
        let (sx0, sx1, sy0, sy1) = (
            Spline::at(x0),
            Spline::at(x1),
            Spline::at(y0),
            Spline::at(y1),
        );
        let wx = [
            -sx0.w[0], -sx0.w[1], -sx0.w[2], sx1.w[0], sx1.w[1], sx1.w[2],
        ];
        let wy = [
            -sy0.w[0], -sy0.w[1], -sy0.w[2], sy1.w[0], sy1.w[1], sy1.w[2],
        ];
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        let mut e = [[[T::default(); 4]; 6]; 6];
        if sx0.k >= 0 && sy0.k >= 0 && sx1.k + 2 <= w && sy1.k + 2 <= h {
            // Inside the image (nearly every box): the rows straight from the table.
            let stride = self.width as usize + 1;
            let (c0, c1) = (sx0.k as usize, sx1.k as usize);
            let rows = [sy0.k, sy0.k + 1, sy0.k + 2, sy1.k, sy1.k + 1, sy1.k + 2];
            for (er, &r) in e.iter_mut().zip(&rows) {
                let base = r as usize * stride;
                let (a, b) = (self.three(base + c0), self.three(base + c1));
                *er = [a[0], a[1], a[2], b[0], b[1], b[2]];
            }
        } else {
            self.corners_wrapped(&mut e, [sx0.k, sx1.k], [sy0.k, sy1.k], wu, wv);
        }
        combine(&e, &wy, &wx)
    }

    /// The two corners from corner `k` along a row, as lanes.
    #[inline(always)]
    fn two(&self, k: usize) -> [Lanes<T>; 2] {
        let s: &[T; 7] = self.sums[3 * k..3 * k + 7]
            .try_into()
            .unwrap_or_else(|_| unreachable!("seven elements"));
        [[s[0], s[1], s[2], s[3]], [s[3], s[4], s[5], s[6]]]
    }

    /// The integral (in integer steps) of the nearest-texel image over the box [x0, x1] x
    /// [y0, y1] (texel units of this level; x0 <= x1, y0 <= y1, all finite, the hull (x1 - x0 +
    /// 2) (y1 - y0 + 2) within [`MAX_HULL_TEXELS`]), extended beyond the image by the wraps.
    ///
    /// The nearest image's antiderivative is the table interpolated bilinearly between its
    /// corners: 2 x 2 reads at each of the box's four corners, 16 in all.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // the channels of lanes and sums, side by side
    fn nearest_box_sum(&self, x0: f64, x1: f64, y0: f64, y1: f64, wu: Wrap, wv: Wrap) -> [f32; 3] {
        let lin = |x: f64| {
            let k = floor_fast_f64(x);
            (k as i64, (x - k) as f32)
        };
        let ((kx0, tx0), (kx1, tx1), (ky0, ty0), (ky1, ty1)) = (lin(x0), lin(x1), lin(y0), lin(y1));
        let wx = [tx0 - 1.0, -tx0, 1.0 - tx1, tx1];
        let wy = [ty0 - 1.0, -ty0, 1.0 - ty1, ty1];
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        let mut e = [[[T::default(); 4]; 4]; 4];
        if kx0 >= 0 && ky0 >= 0 && kx1 < w && ky1 < h {
            let stride = self.width as usize + 1;
            let (c0, c1) = (kx0 as usize, kx1 as usize);
            for (er, r) in e.iter_mut().zip([ky0, ky0 + 1, ky1, ky1 + 1]) {
                let base = r as usize * stride;
                let (a, b) = (self.two(base + c0), self.two(base + c1));
                *er = [a[0], a[1], b[0], b[1]];
            }
        } else {
            let stride = self.width as usize + 1;
            // (Loops, not `<[T; N]>::map`, whose body is out of line: see `lanes::map3`.)
            let (xs, ys) = ([kx0, kx0 + 1, kx1, kx1 + 1], [ky0, ky0 + 1, ky1, ky1 + 1]);
            let (mut tx, mut ty) = ([[(0, 0); 2]; 4], [[(0, 0); 2]; 4]);
            for k in 0..4 {
                tx[k] = axis_terms(wu, xs[k], w);
                ty[k] = axis_terms(wv, ys[k], h);
            }
            for (er, ty) in e.iter_mut().zip(&ty) {
                for (ec, tx) in er.iter_mut().zip(&tx) {
                    let mut acc = [T::default(); 4];
                    for &(cy, ry) in ty {
                        for &(cx, rx) in tx {
                            let c = cx.wrapping_mul(cy);
                            if c != 0 {
                                let k = 3 * (ry as usize * stride + rx as usize);
                                for ch in 0..3 {
                                    acc[ch] = acc[ch].add(self.sums[k + ch].times(c));
                                }
                            }
                        }
                    }
                    *ec = acc;
                }
            }
        }
        // As in `combine`, relative to the first row and column (whose weights' sums vanish).
        let mut out = [0.0f32; 4];
        for r in 1..4 {
            let side = sub4(e[r][0], e[0][0]);
            let mut acc = [0.0f32; 4];
            for c in 1..4 {
                let q = sub4(sub4(e[r][c], e[0][c]), side);
                for k in 0..4 {
                    acc[k] += wx[c] * q[k].to_f32();
                }
            }
            for k in 0..4 {
                out[k] += wy[r] * acc[k];
            }
        }
        [out[0], out[1], out[2]]
    }

    /// The 6 x 6 corners of a box that reaches outside the image (see [`Corners`]), each the
    /// table of the image extended by the wraps: at most four reads, combined in wrapping
    /// arithmetic (the extended sums are integer combinations of the table's).
    #[inline(never)]
    #[allow(clippy::needless_range_loop)] // the channels of lanes and sums, side by side
    fn corners_wrapped(&self, e: &mut Corners<T>, kx: [i64; 2], ky: [i64; 2], wu: Wrap, wv: Wrap) {
        let stride = self.width as usize + 1;
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        let at = |k: [i64; 2], i: usize| k[i / 3] + (i % 3) as i64;
        // (A loop, not `std::array::from_fn`, whose body is out of line: see `lanes::map3`.)
        let (mut tx, mut ty) = ([[(0, 0); 2]; 6], [[(0, 0); 2]; 6]);
        for i in 0..6 {
            tx[i] = axis_terms(wu, at(kx, i), w);
            ty[i] = axis_terms(wv, at(ky, i), h);
        }
        for (er, ty) in e.iter_mut().zip(&ty) {
            for (ec, tx) in er.iter_mut().zip(&tx) {
                let mut acc = [T::default(); 4];
                for &(cy, ry) in ty {
                    for &(cx, rx) in tx {
                        let c = cx.wrapping_mul(cy);
                        if c != 0 {
                            // Every term's point is a corner of the table (in range).
                            let k = 3 * (ry as usize * stride + rx as usize);
                            for ch in 0..3 {
                                acc[ch] = acc[ch].add(self.sums[k + ch].times(c));
                            }
                        }
                    }
                }
                *ec = acc;
            }
        }
    }
}

/// The box's integral from its 6 x 6 corners `e` with the row weights `wy` and column weights
/// `wx` (each the negated B-spline at the box's low edge, then the B-spline at its high edge):
/// the sum over rows and columns of `wy wx e`.
///
/// Each weight set sums to zero, so the corners may be replaced by their differences from the
/// reference row and column (index 1 of each): `q = e[r][c] - e[1][c] - e[r][1] + e[1][1]` is
/// the sum over the rectangle between corner (1, 1) and corner (r, c), small, and exact in
/// wrapping arithmetic however large the corners are. Only the q are converted to floating
/// point (q is 0 in the reference row and column, which are skipped). Four lanes at a time.
#[inline(always)]
fn combine<T: FixedSum>(e: &Corners<T>, wy: &[f32; 6], wx: &[f32; 6]) -> [f32; 3] {
    let reference = &e[1];
    let mut out = [0.0f32; 4];
    for (r, (er, wr)) in e.iter().zip(wy).enumerate() {
        if r == 1 {
            continue;
        }
        let side = sub4(er[1], reference[1]);
        let mut acc = [0.0f32; 4];
        for (c, wc) in wx.iter().enumerate() {
            if c == 1 {
                continue;
            }
            let q = sub4(sub4(er[c], reference[c]), side);
            for k in 0..4 {
                acc[k] += wc * q[k].to_f32();
            }
        }
        for k in 0..4 {
            out[k] += wr * acc[k];
        }
    }
    [out[0], out[1], out[2]]
}

impl<T: FixedSum> Table<T> {
    /// The tables of `mip`'s levels from `first` down, at 2^`bits` to the texel unit.
    fn build(mip: &MipPyramid, first: usize, bits: i32) -> Result<Self, String> {
        let levels = (first..mip.len())
            .map(|l| Level::build(mip.level(l), bits))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            first,
            quantum: (-f64::from(bits)).exp2() as f32,
            levels,
        })
    }

    /// The mip level of the finest table.
    pub(crate) const fn first(&self) -> usize {
        self.first
    }

    /// The mip level of the coarsest table (1 x 1).
    pub(crate) fn last(&self) -> usize {
        self.first + self.levels.len() - 1
    }

    /// The size (texels) of mip level `level` (from [`Table::first`] to [`Table::last`]).
    #[inline(always)]
    pub(crate) fn size(&self, level: usize) -> (u32, u32) {
        let l = &self.levels[level - self.first];
        (l.width, l.height)
    }

    /// The integral of mip level `level`'s bilinear image over the box [x0, x1] x [y0, y1]
    /// (see [`Level::box_sum`]), in texel units.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)] // a box's four edges and two wraps, at a level
    pub(crate) fn box_sum(
        &self,
        level: usize,
        x0: f64,
        x1: f64,
        y0: f64,
        y1: f64,
        wu: Wrap,
        wv: Wrap,
    ) -> [f32; 3] {
        let s = self.levels[level - self.first].box_sum(x0, x1, y0, y1, wu, wv);
        crate::math::lanes::map3(s, |c| c * self.quantum)
    }

    /// The integral of mip level `level`'s nearest-texel image over the box [x0, x1] x
    /// [y0, y1] (see [`Level::nearest_box_sum`]), in texel units.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)] // a box's four edges and two wraps, at a level
    pub(crate) fn nearest_box_sum(
        &self,
        level: usize,
        x0: f64,
        x1: f64,
        y0: f64,
        y1: f64,
        wu: Wrap,
        wv: Wrap,
    ) -> [f32; 3] {
        let s = self.levels[level - self.first].nearest_box_sum(x0, x1, y0, y1, wu, wv);
        crate::math::lanes::map3(s, |c| c * self.quantum)
    }

    fn bytes(&self) -> usize {
        self.levels
            .iter()
            .map(|l| l.sums.len() * std::mem::size_of::<T>())
            .sum()
    }
}

/// The tables of an image (see the module documentation), `i32` or `i64`.
#[derive(Clone, Debug)]
pub(crate) enum Tables {
    /// Texels within [-1, 1], at 2^-16.
    Narrow(Table<i32>),
    /// Larger texels, in `i64`.
    Wide(Table<i64>),
}

/// The summed-area tables of an image's mip levels (see the module documentation).
#[derive(Clone, Debug)]
pub struct SummedArea {
    pub(crate) tables: Tables,
}

impl SummedArea {
    /// The tables for a pyramid's image under `plan` (from its finest level within
    /// [`MAX_TABLE_TEXELS`]), or why there are none.
    ///
    /// # Errors
    /// The plan refuses the image, or the sums' memory cannot be allocated.
    pub fn for_pyramid(mip: &MipPyramid, plan: &TablePlan) -> Result<Self, String> {
        let first = (0..mip.len())
            .find(|&l| {
                let i = mip.level(l);
                u64::from(i.width()) * u64::from(i.height()) <= MAX_TABLE_TEXELS
            })
            .unwrap_or(mip.len() - 1);
        let tables = match plan {
            TablePlan::Narrow => Tables::Narrow(Table::build(mip, first, NARROW_BITS)?),
            TablePlan::Wide { bits } => Tables::Wide(Table::build(mip, first, *bits)?),
            TablePlan::Refused(why) => return Err(why.clone()),
        };
        Ok(Self { tables })
    }

    /// The mip level of the finest table (0 unless the image has more than
    /// [`MAX_TABLE_TEXELS`] texels).
    #[must_use]
    pub const fn first_level(&self) -> usize {
        match &self.tables {
            Tables::Narrow(t) => t.first(),
            Tables::Wide(t) => t.first(),
        }
    }

    /// Bytes the sums take.
    #[must_use]
    pub fn bytes(&self) -> usize {
        match &self.tables {
            Tables::Narrow(t) => t.bytes(),
            Tables::Wide(t) => t.bytes(),
        }
    }

    /// The integral of mip level `level`'s bilinear image over the box [x0, x1] x [y0, y1]
    /// (texel units of that level, texel centres at half-integers; x0 <= x1, y0 <= y1, the
    /// hull (x1 - x0 + 3) (y1 - y0 + 3) within [`MAX_HULL_TEXELS`]), extended by the wraps as
    /// the bilinear lookup extends it.
    #[must_use]
    pub fn box_sum(
        &self,
        level: usize,
        x: (f64, f64),
        y: (f64, f64),
        wu: Wrap,
        wv: Wrap,
    ) -> [f32; 3] {
        match &self.tables {
            Tables::Narrow(t) => t.box_sum(level, x.0, x.1, y.0, y.1, wu, wv),
            Tables::Wide(t) => t.box_sum(level, x.0, x.1, y.0, y.1, wu, wv),
        }
    }

    /// The mean of mip level `level`'s bilinear image over the box centred at (`cx`, `cy`)
    /// with half-widths `hx`, `hy` (texel units of that level, both positive).
    #[must_use]
    pub fn box_mean(
        &self,
        level: usize,
        (cx, cy): (f64, f64),
        (hx, hy): (f64, f64),
        wu: Wrap,
        wv: Wrap,
    ) -> Rgb {
        let s = self.box_sum(level, (cx - hx, cx + hx), (cy - hy, cy + hy), wu, wv);
        let k = (0.25 / (hx * hy)) as f32;
        Rgb(s[0] * k, s[1] * k, s[2] * k)
    }
}

/// Where the antiderivative at a coordinate x reads along one axis: the corners `k`, `k + 1`,
/// `k + 2` with weights `w`, for k = floor(x - 1/2) and t = x - 1/2 - k: `(1 - t)^2 / 2`,
/// `1/2 + t - t^2`, `t^2 / 2` (the table, linear between corners, blurred by a one-texel box).
#[derive(Clone, Copy, Debug)]
struct Spline {
    k: i64,
    w: [f32; 3],
}

impl Spline {
    #[inline(always)]
    fn at(x: f64) -> Self {
        let xs = x - 0.5;
        let k = floor_fast_f64(xs);
        let t = (xs - k) as f32;
        Self {
            k: k as i64,
            w: [0.5 * (1.0 - t) * (1.0 - t), 0.5 + t - t * t, 0.5 * t * t],
        }
    }
}

/// The sum along one axis up to corner `x` of the image (`n` texels) extended by `wrap`, as
/// integer coefficients on the sums up to corners of [0, n]: E(x) = sum of c F(r) over the
/// terms (c, r). Repeat: q whole periods and the rest; mirror: the same over periods of 2n, the
/// second half read backwards; clamp: the edge texel's column repeated; black: nothing outside.
#[inline]
fn axis_terms(wrap: Wrap, x: i64, n: i64) -> [(i64, i64); 2] {
    if (0..=n).contains(&x) {
        return [(1, x), (0, 0)];
    }
    match wrap {
        Wrap::Repeat => {
            let q = x.div_euclid(n);
            [(q, n), (1, x - q * n)]
        }
        Wrap::Mirror => {
            let p = 2 * n;
            let q = x.div_euclid(p);
            let s = x - q * p;
            if s <= n {
                [(2 * q, n), (1, s)]
            } else {
                [(2 * q + 2, n), (-1, p - s)]
            }
        }
        Wrap::Clamp if x < 0 => [(x, 1), (0, 0)],
        // F(n) + (x - n) times the last column, which is F(n) - F(n - 1).
        Wrap::Clamp => [(1 + x - n, n), (n - x, n - 1)],
        Wrap::Black => [(1, x.clamp(0, n)), (0, 0)],
    }
}

#[cfg(test)]
mod tests;
