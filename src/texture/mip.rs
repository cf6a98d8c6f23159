//! The mip pyramid and the filters that read it: trilinear (isotropic) and EWA (anisotropic,
//! Heckbert's elliptical weighted average with a Gaussian, as in pbrt).
//!
//! Levels are averaged in linear colour. 8-bit sRGB images are decoded to linear, averaged and
//! re-encoded to 8-bit sRGB (4 bytes per texel, like the base level: the pyramid adds a third
//! to the image's memory); linear images keep linear `f32` levels (12 bytes per texel).
//! Non-power-of-two sides are reduced by a polyphase box filter: an even side halves with a
//! 2-tap box, an odd side `n` becomes `(n - 1) / 2` with 3 taps weighted
//! `((m - i) / n, m / n, (i + 1) / n)` for output texel `i` (with `m = (n - 1) / 2`), which is
//! the exact box filter of width `n / m` texels: no row or column is dropped and no image
//! content shifts. A side of 1 stays 1. Lookups wrap each level with the texture's wrap modes,
//! so periodic mappings filter across their seam at every level.

use super::{ImageData, TILE, Texels, Wrap, tiled_index};
use crate::math::{Rgb, Vec2, linear_to_srgb8};
use std::sync::{Arc, LazyLock, OnceLock};

/// The default largest ratio of the footprint's major to minor axis that EWA honours; longer
/// footprints are widened (blurrier, but the work per lookup stays bounded).
pub const DEFAULT_MAX_ANISOTROPY: f32 = 8.0;

/// The largest `max_anisotropy` accepted: EWA's work per lookup grows with it.
pub const MAX_ANISOTROPY_LIMIT: f32 = 64.0;

/// A pyramid of successively halved images; level 0 is the texture itself (shared, not copied).
#[derive(Clone, Debug)]
pub struct MipPyramid {
    levels: Vec<Arc<ImageData>>,
    /// How the summed-area tables store their sums (from the largest texel), decided on first
    /// use ([`MipPyramid::table_plan`]).
    plan: OnceLock<super::TablePlan>,
    /// The summed-area tables the footprint filter reads, built on first use
    /// ([`MipPyramid::summed_area`]); why there are none (the plan refused the image, or their
    /// memory could not be had).
    table: OnceLock<Result<super::SummedArea, String>>,
}

impl MipPyramid {
    /// Builds every level down to 1 x 1 from `base`.
    #[must_use]
    pub fn build(base: Arc<ImageData>) -> Self {
        let mut levels = vec![base];
        loop {
            let last = &levels[levels.len() - 1];
            if last.width() == 1 && last.height() == 1 {
                break;
            }
            let next = downsample(last);
            levels.push(Arc::new(next));
        }
        Self {
            levels,
            plan: OnceLock::new(),
            table: OnceLock::new(),
        }
    }

    /// The summed-area tables of the image's levels (from its finest within
    /// [`super::MAX_TABLE_TEXELS`]) once [`MipPyramid::build_summed_area`] has built them;
    /// `None` before, when the plan refuses the image, or when their memory could not be had
    /// (the footprint filter then reads EWA). A lookup never builds them: the scene's budget
    /// decides whether they are built ([`crate::scene::AssetCache`]).
    #[must_use]
    #[inline(always)]
    pub fn summed_area(&self) -> Option<&super::SummedArea> {
        self.table.get().and_then(|t| t.as_ref().ok())
    }

    /// Builds the summed-area tables (once; later calls return the first outcome).
    ///
    /// # Errors
    /// Why there are none: the plan refuses the image (a texel too large to sum exactly), or
    /// their memory could not be had.
    pub fn build_summed_area(&self) -> Result<&super::SummedArea, &str> {
        self.table
            .get_or_init(|| super::SummedArea::for_pyramid(self, self.table_plan()))
            .as_ref()
            .map_err(String::as_str)
    }

    /// How the summed-area tables store their sums, from the image's largest texel (decided on
    /// the first call, without building them).
    #[must_use]
    pub fn table_plan(&self) -> &super::TablePlan {
        self.plan
            .get_or_init(|| super::TablePlan::for_image(self.level(0)))
    }

    /// Bytes the summed-area tables take once built, or would take under
    /// [`MipPyramid::table_plan`] (0 when it refuses them): what a scene's budget reserves.
    #[must_use]
    pub fn table_bytes(&self) -> u64 {
        match self.table.get() {
            Some(Ok(t)) => t.bytes() as u64,
            Some(Err(_)) => 0,
            None => {
                let base = self.level(0);
                self.table_plan().table_bytes(base.width(), base.height())
            }
        }
    }

    /// Why the image has no summed-area tables, once their build was tried (or the plan
    /// refused them).
    #[must_use]
    pub fn summed_area_refusal(&self) -> Option<&str> {
        if let Some(super::TablePlan::Refused(why)) = self.plan.get() {
            return Some(why);
        }
        self.table
            .get()
            .and_then(|t| t.as_ref().err())
            .map(String::as_str)
    }

    /// Whether the summed-area tables have been built.
    #[must_use]
    pub fn has_summed_area(&self) -> bool {
        self.table.get().is_some_and(Result::is_ok)
    }

    /// Bytes the levels above the base take (the base belongs to the texture), without the
    /// tables.
    #[must_use]
    pub fn level_bytes(&self) -> u64 {
        self.levels[1..]
            .iter()
            .map(|l| l.storage_bytes() as u64)
            .sum()
    }

    /// Number of levels (1 for a 1 x 1 image).
    #[must_use]
    pub fn len(&self) -> usize {
        self.levels.len()
    }

    /// Always false: a pyramid has at least its base level.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.levels.is_empty()
    }

    /// Level `i` (0 = full resolution), clamped to the coarsest.
    #[must_use]
    pub fn level(&self, i: usize) -> &ImageData {
        &self.levels[i.min(self.levels.len() - 1)]
    }

    /// Bytes taken by the levels above the base (the base belongs to the texture) and by the
    /// summed-area tables once built.
    #[must_use]
    pub fn extra_bytes(&self) -> u64 {
        let table = match self.table.get() {
            Some(Ok(t)) => t.bytes() as u64,
            _ => 0,
        };
        self.level_bytes() + table
    }

    /// Bytes the levels above the base of `image` will take once built (each stored in whole
    /// tiles, as [`MipPyramid::level_bytes`] counts them): what a scene's budget checks before
    /// building a pyramid.
    #[must_use]
    pub fn planned_bytes(image: &ImageData) -> u64 {
        let tile = u64::from(super::TILE);
        let (mut w, mut h) = (image.width(), image.height());
        let mut bytes = 0;
        while w > 1 || h > 1 {
            (w, h) = (half(w), half(h));
            bytes += u64::from(w).div_ceil(tile) * u64::from(h).div_ceil(tile) * tile * tile;
        }
        bytes * image.bytes_per_texel() as u64
    }

    /// The continuous level whose texels are `texels` base texels wide (0 when magnified).
    #[must_use]
    #[inline]
    pub fn level_for_width(&self, texels: f32) -> f32 {
        let max = (self.levels.len() - 1) as f32;
        if texels.is_finite() && texels > 1.0 {
            texels.log2().min(max)
        } else if texels.is_finite() {
            0.0
        } else {
            max
        }
    }

    /// Trilinear filtering: bilinear at the two levels around the footprint's size, blended.
    /// The size is the longer of the two screen-space derivatives, in base texels.
    #[must_use]
    #[inline]
    pub fn trilinear(&self, uv: Vec2, duvdx: Vec2, duvdy: Vec2, wu: Wrap, wv: Wrap) -> Rgb {
        // The width-1 instance of the lanes (`texture/lanes.rs`).
        let mut tc = [crate::mapping::TexCoord::default(); crate::math::lanes::MAX_LANES];
        tc[0] = crate::mapping::TexCoord { uv, duvdx, duvdy };
        let mut on = [false; crate::math::lanes::MAX_LANES];
        on[0] = true;
        let [r, g, b] = self.trilinear_lanes(pulp::Scalar, &tc, wu, wv, &on);
        Rgb(r, g, b)
    }

    /// Elliptically weighted average (Heckbert 1989, pbrt's Gaussian form): the pixel's
    /// footprint is the ellipse with conjugate semi-axes `duvdx` and `duvdy` (scaled by
    /// [`EWA_FOOTPRINT_SCALE`]); the ellipse is
    /// widened so the major / minor ratio is at most `max_anisotropy`, a level is chosen where
    /// the minor axis spans a few texels, and the texels inside are averaged with Gaussian
    /// weights (blended between two levels).
    #[must_use]
    pub fn ewa(
        &self,
        uv: Vec2,
        duvdx: Vec2,
        duvdy: Vec2,
        max_anisotropy: f32,
        wu: Wrap,
        wv: Wrap,
    ) -> Rgb {
        let uv = Wrap::reduce_uv(wu, wv, uv);
        let base = self.level(0);
        let size = Vec2::new(base.width() as f32, base.height() as f32);
        // Work in base texels so non-square images get round texels.
        let k = EWA_FOOTPRINT_SCALE;
        let (mut major, mut minor) = (duvdx * size * k, duvdy * size * k);
        if !(major.is_finite() && minor.is_finite()) {
            return base.bilinear(uv, wu, wv);
        }
        if major.length_squared() < minor.length_squared() {
            std::mem::swap(&mut major, &mut minor);
        }
        let major_len = major.length();
        let mut minor_len = minor.length();
        if major_len == 0.0 {
            return base.bilinear(uv, wu, wv);
        }
        // Clamp the eccentricity: widen the minor axis (perpendicular to the major one when the
        // footprint is degenerate, so it keeps its area).
        let aniso = max_anisotropy.clamp(1.0, MAX_ANISOTROPY_LIMIT);
        if minor_len * aniso < major_len {
            let want = major_len / aniso;
            minor = if minor_len > 0.0 {
                minor * (want / minor_len)
            } else {
                Vec2::new(-major.y, major.x) * (want / major_len)
            };
            minor_len = want;
        }
        let lod = self.level_for_width(minor_len);
        let l0 = lod.floor();
        let t = lod - l0;
        let l0 = l0 as usize;
        let a = ewa_level(self.level(l0), size, uv, major, minor, wu, wv);
        if t <= 0.0 || l0 + 1 >= self.levels.len() {
            return a;
        }
        let b = ewa_level(self.level(l0 + 1), size, uv, major, minor, wu, wv);
        a * (1.0 - t) + b * t
    }
}

/// The EWA ellipse's axes as a fraction of the pixel's differentials. pbrt's Gaussian reaches
/// zero one full pixel offset from the centre (a standard deviation of about half a pixel),
/// blurrier than the box pixel it stands for (0.29 pixel); at 0.7 the 1-spp EWA render of the
/// receding checker plane is closest to the box-filtered reference (RMSE 0.024 at 1.0, 0.0148
/// at 0.7, 0.0227 at 0.6; `examples/aa_measure.rs`) and the Earth's drops from 0.0072 to 0.0052.
pub const EWA_FOOTPRINT_SCALE: f32 = 0.7;

/// Entries of the Gaussian weight table, indexed by the squared elliptical radius.
const WEIGHT_TABLE_SIZE: usize = 128;
/// The Gaussian's falloff: `exp(-ALPHA r^2) - exp(-ALPHA)`, zero on the ellipse's rim.
const EWA_ALPHA: f32 = 2.0;

static EWA_WEIGHTS: LazyLock<[f32; WEIGHT_TABLE_SIZE]> = LazyLock::new(|| {
    let mut t = [0.0; WEIGHT_TABLE_SIZE];
    for (i, w) in t.iter_mut().enumerate() {
        let r2 = i as f32 / (WEIGHT_TABLE_SIZE - 1) as f32;
        *w = (-EWA_ALPHA * r2).exp() - (-EWA_ALPHA).exp();
    }
    t
});

/// The most texels one EWA lookup may visit along a side of its bounding box; the anisotropy
/// clamp keeps real footprints far below it, this only guards against absurd input.
const EWA_MAX_SPAN: f32 = 1024.0;

/// EWA over one level. `base_size` converts the base-texel axes to this level's texels.
fn ewa_level(
    img: &ImageData,
    base_size: Vec2,
    uv: Vec2,
    major: Vec2,
    minor: Vec2,
    wu: Wrap,
    wv: Wrap,
) -> Rgb {
    let (w, h) = (img.width(), img.height());
    let scale = Vec2::new(w as f32, h as f32) / base_size;
    let (d0, d1) = (major * scale, minor * scale);
    let s = uv.x * w as f32 - 0.5;
    let t = uv.y * h as f32 - 0.5;
    // Implicit ellipse A s^2 + B s t + C t^2 = F through the axes' tips, with one texel added to
    // each axis so a magnified lookup still covers a texel (the reconstruction filter).
    let mut a = d0.y * d0.y + d1.y * d1.y + 1.0;
    let mut b = -2.0 * (d0.x * d0.y + d1.x * d1.y);
    let mut c = d0.x * d0.x + d1.x * d1.x + 1.0;
    let f = a * c - b * b * 0.25;
    if !(f.is_finite() && f > 0.0) {
        return img.bilinear(uv, wu, wv);
    }
    let inv_f = 1.0 / f;
    a *= inv_f;
    b *= inv_f;
    c *= inv_f;
    let det = -b * b + 4.0 * a * c;
    let inv_det = 1.0 / det;
    let u_sqrt = (det * c).sqrt();
    let v_sqrt = (a * det).sqrt();
    let du = (2.0 * inv_det * u_sqrt).min(EWA_MAX_SPAN);
    let dv = (2.0 * inv_det * v_sqrt).min(EWA_MAX_SPAN);
    if !(du.is_finite() && dv.is_finite() && s.is_finite() && t.is_finite()) {
        return img.bilinear(uv, wu, wv);
    }
    let (s0, s1) = ((s - du).ceil() as i64, (s + du).floor() as i64);
    let (t0, t1) = ((t - dv).ceil() as i64, (t + dv).floor() as i64);
    let [r, g, b, wsum] = pulp::Arch::new().dispatch(EwaRows {
        img,
        a,
        b,
        c,
        s,
        t,
        columns: (s0, s1),
        rows: (t0, t1),
        wu,
        wv,
    });
    if wsum > 0.0 {
        Rgb(r, g, b) / wsum
    } else {
        img.bilinear(uv, wu, wv)
    }
}

/// The texels of one EWA level inside the ellipse `a ss^2 + b ss tt + c tt^2 < 1` (centred on
/// texel coordinates (`s`, `t`), within the bounding box `columns` x `rows`), each weighed by
/// the Gaussian: the weighted sum of their colours and the sum of the weights, `[r, g, b, w]`.
///
/// Entered through pulp's dispatch so the loop is compiled for the machine's instruction set
/// (rounding and conversions in single instructions, not library calls), with the texel format
/// chosen once per lookup rather than at every texel. The sums run texel by texel in the same
/// order as a plain loop, so the result is the same bits on every instruction set.
struct EwaRows<'a> {
    img: &'a ImageData,
    a: f32,
    b: f32,
    c: f32,
    s: f32,
    t: f32,
    columns: (i64, i64),
    rows: (i64, i64),
    wu: Wrap,
    wv: Wrap,
}

impl pulp::WithSimd for EwaRows<'_> {
    type Output = [f32; 4];

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> [f32; 4] {
        match self.img.texels() {
            Texels::Linear(px) => self.sum(|i| px[i]),
            texels => {
                let Some((px, table)) = texels.bytes() else {
                    return [0.0; 4];
                };
                self.sum(|i| {
                    let [r, g, b, _] = px[i];
                    [table[r as usize], table[g as usize], table[b as usize]]
                })
            }
        }
    }
}

impl EwaRows<'_> {
    /// The sums, reading the texel at a tiled storage index with `texel`.
    #[inline(always)]
    fn sum(&self, texel: impl Fn(usize) -> [f32; 3]) -> [f32; 4] {
        let Self { a, b, c, s, t, .. } = *self;
        let (w, h) = (self.img.width(), self.img.height());
        let tiles_x = self.img.tiles_x() as usize;
        let weights = &*EWA_WEIGHTS;
        let table_scale = (WEIGHT_TABLE_SIZE - 1) as f32;
        // Accumulated in the order a plain loop adds: the same bits whatever the loop's shape.
        let mut acc = [0.0_f32; 4];
        let add = |acc: &mut [f32; 4], c: [f32; 3], wgt: f32| {
            *acc = [
                acc[0] + c[0] * wgt,
                acc[1] + c[1] * wgt,
                acc[2] + c[2] * wgt,
                acc[3] + wgt,
            ];
        };
        for it in self.rows.0..=self.rows.1 {
            let tt = it as f32 - t;
            // Only the span of this row inside the ellipse: A ss^2 + (B tt) ss + (C tt^2 - 1) < 0.
            let (qb, qc) = (b * tt, c * tt * tt - 1.0);
            let disc = qb * qb - 4.0 * a * qc;
            // (NaN fails the comparison too.)
            if disc.is_nan() || disc <= 0.0 {
                continue;
            }
            let root = disc.sqrt();
            let lo = ((s + (-qb - root) / (2.0 * a)).ceil() as i64).max(self.columns.0);
            let hi = ((s + (-qb + root) / (2.0 * a)).floor() as i64).min(self.columns.1);
            let ctt = c * tt * tt;
            let weight = |is: i64| {
                let ss = is as f32 - s;
                let r2 = a * ss * ss + b * ss * tt + ctt;
                (r2 < 1.0 || r2.is_nan())
                    .then(|| weights[((r2 * table_scale) as usize).min(WEIGHT_TABLE_SIZE - 1)])
            };
            let row = self.wv.index(it, h);
            match row {
                // Every column inside the image (the common case): no wrapping, and the
                // storage index of (column, row) from the row's start in its tiles.
                Some(row) if lo >= 0 && hi < i64::from(w) => {
                    let top = (h - 1 - row) as usize;
                    let start = top / TILE as usize * tiles_x * (TILE * TILE) as usize
                        + top % TILE as usize * TILE as usize;
                    for is in lo..=hi {
                        if let Some(wgt) = weight(is) {
                            let col = is as usize;
                            let i = start
                                + col / TILE as usize * (TILE * TILE) as usize
                                + col % TILE as usize;
                            add(&mut acc, texel(i), wgt);
                        }
                    }
                }
                _ => {
                    for is in lo..=hi {
                        let Some(wgt) = weight(is) else { continue };
                        // Outside under `Black`: black texels still count in the average.
                        match (row, self.wu.index(is, w)) {
                            (Some(row), Some(col)) => {
                                let i = tiled_index(self.img.tiles_x(), col, h - 1 - row);
                                add(&mut acc, texel(i), wgt);
                            }
                            _ => acc[3] += wgt,
                        }
                    }
                }
            }
        }
        acc
    }
}

/// The next level: each side halved by the polyphase box filter (see the module docs).
fn downsample(img: &ImageData) -> ImageData {
    let (w, h) = (img.width(), img.height());
    let (nw, nh) = (half(w), half(h));
    // Along x (reading the source's texels in place, row 0 = top: row order does not matter
    // for a box), then along y.
    let mut tmp = vec![Rgb::BLACK; nw as usize * h as usize];
    for row in 0..h {
        let start = row as usize * nw as usize;
        for (i, out) in tmp[start..start + nw as usize].iter_mut().enumerate() {
            *out = taps(w, i as u32, |k| img.texel_top(k, row));
        }
    }
    let mut dst = vec![Rgb::BLACK; nw as usize * nh as usize];
    for col in 0..nw as usize {
        for j in 0..nh as usize {
            dst[j * nw as usize + col] = taps(h, j as u32, |k| tmp[k as usize * nw as usize + col]);
        }
    }
    let name = format!("{} ({nw}x{nh})", img.name);
    let texels = match img.texels() {
        Texels::Srgb8(_) => Texels::Srgb8(
            dst.iter()
                .map(|c| {
                    let e = linear_to_srgb8;
                    [e(c.0), e(c.1), e(c.2), 255]
                })
                .collect(),
        ),
        // Raw 8-bit levels keep their averages unquantised, as linear floats.
        Texels::Unorm8(_) | Texels::Linear(_) => {
            Texels::Linear(dst.iter().map(|c| c.to_array()).collect())
        }
    };
    ImageData::new(nw, nh, texels, name)
}

/// The size of a side after one reduction.
#[must_use]
pub const fn half(n: u32) -> u32 {
    if n <= 1 { 1 } else { n / 2 }
}

/// Output texel `i` of a side of `n` source texels read through `at`.
#[inline]
fn taps(n: u32, i: u32, at: impl Fn(u32) -> Rgb) -> Rgb {
    if n <= 1 {
        return at(0);
    }
    if n.is_multiple_of(2) {
        return (at(2 * i) + at(2 * i + 1)) * 0.5;
    }
    let m = (n - 1) / 2;
    let nf = n as f32;
    at(2 * i) * ((m - i) as f32 / nf)
        + at(2 * i + 1) * (m as f32 / nf)
        + at(2 * i + 2) * ((i + 1) as f32 / nf)
}

#[cfg(test)]
mod tests {
    use super::*;
    use strum::VariantArray;

    fn mean(img: &ImageData) -> Rgb {
        let mut s = Rgb::BLACK;
        for r in 0..img.height() {
            for c in 0..img.width() {
                s += img.texel_top(c, r);
            }
        }
        s / (img.width() * img.height()) as f32
    }

    #[test]
    fn odd_and_thin_sizes_reduce_to_one_texel_keeping_the_mean() {
        for (w, h) in [
            (1, 1),
            (1, 7),
            (7, 1),
            (3, 5),
            (5, 3),
            (6, 9),
            (2048, 1024),
            (17, 2),
        ] {
            let img = Arc::new(ImageData::from_fn(w, h, "t", |c, r| {
                Rgb(c as f32, r as f32, ((c * 7 + r * 3) % 5) as f32)
            }));
            let m0 = mean(&img);
            let p = MipPyramid::build(img);
            let last = p.level(p.len() - 1);
            assert_eq!((last.width(), last.height()), (1, 1), "{w}x{h}");
            // Every level keeps the image's mean (the box filter conserves energy).
            for l in 0..p.len() {
                let m = mean(p.level(l));
                assert!(
                    (m.0 - m0.0).abs() < 1e-3 * (1.0 + m0.0)
                        && (m.1 - m0.1).abs() < 1e-3 * (1.0 + m0.1)
                        && (m.2 - m0.2).abs() < 1e-3 * (1.0 + m0.2),
                    "{w}x{h} level {l}: {m:?} vs {m0:?}"
                );
            }
            // Level count: one per halving of the longer side.
            let expected = 1 + (w.max(h) as f32).log2().floor() as usize;
            assert_eq!(p.len(), expected, "{w}x{h}");
        }
    }

    #[test]
    fn three_by_five_level_one_is_the_polyphase_box() {
        // A ramp in x: 3 texels 0, 1, 2 -> one texel, the mean 1.
        let img = Arc::new(ImageData::from_fn(3, 5, "r", |c, _| Rgb::grey(c as f32)));
        let p = MipPyramid::build(img);
        let l1 = p.level(1);
        assert_eq!((l1.width(), l1.height()), (1, 2));
        assert!((l1.texel_top(0, 0).0 - 1.0).abs() < 1e-6);
        // 5 -> 2 in y: weights (2/5, 2/5, 1/5) and (1/5, 2/5, 2/5): a y ramp 0..4 gives 0.8, 3.2.
        let img = Arc::new(ImageData::from_fn(1, 5, "r", |_, r| Rgb::grey(r as f32)));
        let p = MipPyramid::build(img);
        let l1 = p.level(1);
        assert_eq!((l1.width(), l1.height()), (1, 2));
        assert!((l1.texel_top(0, 0).0 - 0.8).abs() < 1e-5);
        assert!((l1.texel_top(0, 1).0 - 3.2).abs() < 1e-5);
    }

    #[test]
    fn srgb_levels_average_in_linear_colour() {
        // Black and white columns: the linear mean 0.5 is sRGB byte 188, not 128.
        let texels = (0..4)
            .map(|i| {
                if i % 2 == 0 {
                    [0, 0, 0, 255]
                } else {
                    [255, 255, 255, 255]
                }
            })
            .collect();
        let img = Arc::new(ImageData::new(2, 2, Texels::Srgb8(texels), "bw"));
        let p = MipPyramid::build(img);
        assert_eq!(p.level(1).bytes_per_texel(), 4);
        let c = p.level(1).texel_top(0, 0);
        assert!((c.0 - 0.5).abs() < 0.01, "{c:?}");
        let Texels::Srgb8(v) = p.level(1).texels() else {
            panic!("level 1 should stay 8-bit sRGB")
        };
        assert_eq!(v[0][0], 188);
    }

    #[test]
    fn trilinear_and_ewa_average_a_fine_checker_to_grey_when_minified() {
        let img = Arc::new(ImageData::from_fn(64, 64, "c", |c, r| {
            Rgb::grey(((c + r) % 2) as f32)
        }));
        let p = MipPyramid::build(img);
        let d = Vec2::new(16.0 / 64.0, 0.0);
        let e = Vec2::new(0.0, 16.0 / 64.0);
        for uv in [
            Vec2::new(0.3, 0.7),
            Vec2::new(0.0, 0.0),
            Vec2::new(0.99, 0.5),
        ] {
            let t = p.trilinear(uv, d, e, Wrap::Repeat, Wrap::Repeat);
            assert!((t.0 - 0.5).abs() < 0.02, "{uv}: {t:?}");
            let x = p.ewa(uv, d, e, 8.0, Wrap::Repeat, Wrap::Repeat);
            assert!((x.0 - 0.5).abs() < 0.02, "{uv}: {x:?}");
        }
        // Magnified, EWA still reconstructs the texel (no blur toward grey at a texel centre
        // beyond the one-texel reconstruction). Column 0, bottom row (file row 63) is white.
        let tiny = Vec2::new(1e-5, 0.0);
        let x = p.ewa(
            Vec2::new(0.5 / 64.0, 0.5 / 64.0),
            tiny,
            tiny.perp(),
            8.0,
            Wrap::Repeat,
            Wrap::Repeat,
        );
        assert!(x.0 > 0.6, "{x:?}");
    }

    #[test]
    fn ewa_is_anisotropic_and_respects_max_anisotropy() {
        // Vertical stripes, one texel wide: a footprint long along v and one texel along u keeps
        // them; a footprint long along u averages them.
        let img = Arc::new(ImageData::from_fn(64, 64, "s", |c, _| {
            Rgb::grey((c % 2) as f32)
        }));
        let p = MipPyramid::build(img);
        let uv = Vec2::new(1.5 / 64.0, 0.5);
        let along_v = p.ewa(
            uv,
            Vec2::new(0.0, 16.0 / 64.0),
            Vec2::new(0.2 / 64.0, 0.0),
            16.0,
            Wrap::Repeat,
            Wrap::Repeat,
        );
        assert!(along_v.0 > 0.6, "{along_v:?}");
        let along_u = p.ewa(
            uv,
            Vec2::new(16.0 / 64.0, 0.0),
            Vec2::new(0.0, 0.2 / 64.0),
            16.0,
            Wrap::Repeat,
            Wrap::Repeat,
        );
        assert!((along_u.0 - 0.5).abs() < 0.05, "{along_u:?}");
        // With max anisotropy 1 the long-along-v footprint becomes a 16-texel disc: grey.
        let iso = p.ewa(
            uv,
            Vec2::new(0.0, 16.0 / 64.0),
            Vec2::new(0.2 / 64.0, 0.0),
            1.0,
            Wrap::Repeat,
            Wrap::Repeat,
        );
        assert!((iso.0 - 0.5).abs() < 0.05, "{iso:?}");
    }

    #[test]
    fn filters_wrap_across_the_u_seam_at_every_level() {
        // Left half black, right half white: at u = 0 with repeat the footprint straddles the
        // seam and sees both halves, at every level.
        let img = Arc::new(ImageData::from_fn(64, 32, "h", |c, _| {
            Rgb::grey(if c < 32 { 0.0 } else { 1.0 })
        }));
        let p = MipPyramid::build(img);
        for width in [1.0_f32, 4.0, 16.0] {
            let d = Vec2::new(width / 64.0, 0.0);
            let e = Vec2::new(0.0, width / 32.0);
            let t = p.trilinear(Vec2::new(0.0, 0.5), d, e, Wrap::Repeat, Wrap::Clamp);
            let x = p.ewa(Vec2::new(0.0, 0.5), d, e, 8.0, Wrap::Repeat, Wrap::Clamp);
            assert!((t.0 - 0.5).abs() < 0.15, "trilinear {width}: {t:?}");
            assert!((x.0 - 0.5).abs() < 0.15, "ewa {width}: {x:?}");
        }
    }

    #[test]
    fn degenerate_footprints_are_finite() {
        let img = Arc::new(ImageData::from_fn(8, 4, "d", |c, r| {
            Rgb::grey((c + r) as f32)
        }));
        let p = MipPyramid::build(img);
        for (d, e) in [
            (Vec2::ZERO, Vec2::ZERO),
            (Vec2::new(1.0, 0.0), Vec2::ZERO),
            (Vec2::new(1.0, 1.0), Vec2::new(1.0, 1.0)),
            (Vec2::splat(f32::NAN), Vec2::ZERO),
            (Vec2::splat(1e30), Vec2::splat(-1e30)),
        ] {
            for &w in Wrap::VARIANTS {
                assert!(p.ewa(Vec2::new(0.2, 0.9), d, e, 8.0, w, w).is_finite());
                assert!(p.trilinear(Vec2::new(0.2, 0.9), d, e, w, w).is_finite());
            }
        }
    }
}
