//! The footprint filter: the texture integrated over the pixel's footprint, so that one sample
//! per pixel gives what the box pixel filter gives with infinitely many.
//!
//! A pixel (or, at n samples per pixel, a sample's share of it) sees the parallelogram
//! `uv + s duv/dx + t duv/dy`, s and t in [-1/2, 1/2], of texture space (the ray differentials,
//! linearised at the hit). Under the box pixel filter the exact pixel value is the mean of the
//! bilinearly reconstructed texture over that parallelogram.
//!
//! **With a summed-area table** (the texture's [`MipPyramid::summed_area`], the usual way): the
//! parallelogram is replaced by the axis-aligned box with the same variance along u and along
//! v (widths `sqrt(a_u^2 + b_u^2)` and `sqrt(a_v^2 + b_v^2)` texels for edges a and b), and the
//! bilinear texture's mean over that box is exact from the table ([`SummedArea::box_mean`]):
//! a fixed cost, whatever the footprint's size. A box has no shear, so a sheared footprint
//! (edges leaning more than [`MAX_SKEW`] texels off the axes) is cut into cells along its
//! edges, each cell replaced by its own box. Magnified footprints (under
//! [`MIN_HALF_WIDTH`] texels both ways) read the bilinear lookup.
//!
//! **By texture-space supersampling** (images whose table would not fit, footprints too small
//! for the table of a coarser level): an `na` x `nb` grid of bilinear taps at the centres of equal
//! cells of the parallelogram (the midpoint rule), [`TAPS_PER_TEXEL`] taps per texel along each
//! edge. Footprints longer than [`MAX_TAPS`] taps read the coarsest mip level that still gets
//! [`MAX_TAPS`] taps along the longer edge (its texels average 2^L x 2^L of the image: a blur of
//! at most 1 / [`MAX_TAPS`] of the footprint's length).
//!
//! Unlike trilinear and EWA, which weigh the texels under an isotropic box or a Gaussian a bit
//! wider than the pixel, the mean is over the footprint itself: no blur beyond the pixel's, so
//! it converges to the supersampled image rather than to a blurred one. It is exact for the box
//! pixel filter when the sample is at its cell's centre (the `regular` sampler); a jittered
//! sample moves the footprint with it, adding the jitter's own blur.

use super::{ImageData, MipPyramid, SummedArea, Wrap};
use crate::math::{Rgb, Vec2};

/// Taps per texel along each edge of the footprint (at the level read): the midpoint rule on the
/// bilinear reconstruction, which is smooth between texel centres.
pub const TAPS_PER_TEXEL: f32 = 2.0;

/// The most taps along an edge; longer footprints read a coarser mip level.
pub const MAX_TAPS: u32 = 32;

/// How far (texels) a cell's edge may lean off the u or v axis before the summed-area path
/// cuts the footprint into more cells: a box's kernel differs from a sheared cell's by about
/// this much at its corners, under the bilinear reconstruction's own one-texel blur.
pub const MAX_SKEW: f64 = 0.5;

/// The most cells the summed-area path cuts a footprint into (four antiderivatives of nine
/// reads each); a footprint more sheared than that is cut into cells sheared a little more.
pub const MAX_CELLS: u32 = 16;

/// The narrowest half-width (texels) of a box the summed-area path reads: a box's mean is a
/// difference of sums over the whole image divided by its area, so it must not be too thin.
/// Footprints narrower on both axes are magnified and read bilinearly.
pub const MIN_HALF_WIDTH: f64 = 0.01;

/// How many level texels a footprint must span on both axes to be read from a table of a mip
/// level above the base (the level's texels blur by their own width, which must stay small
/// beside the footprint's).
const MIN_LEVEL_SPAN: f64 = 4.0;

/// The mean of the bilinear texture over the footprint parallelogram centred at `uv` with edges
/// `duvdx` and `duvdy` (see the module documentation): from the summed-area table when the
/// pyramid has one, else by supersampling. Without a mip pyramid, footprints longer than
/// [`MAX_TAPS`] taps are sampled by [`MAX_TAPS`] taps at full resolution.
#[must_use]
#[inline(always)]
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
    if !(duvdx.is_finite() && duvdy.is_finite() && uv.is_finite()) {
        return image.bilinear(uv, wu, wv);
    }
    if let Some(t) = mip.and_then(MipPyramid::summed_area)
        && let Some(c) = summed(t, uv, duvdx, duvdy, wu, wv)
    {
        return c;
    }
    supersampled(mip, image, uv, duvdx, duvdy, wu, wv)
}

/// The summed-area path (see the module documentation), or `None` for a footprint it does not
/// take: magnified, or too small for a table of a coarser level.
#[inline(always)]
fn summed(t: &SummedArea, uv: Vec2, duvdx: Vec2, duvdy: Vec2, wu: Wrap, wv: Wrap) -> Option<Rgb> {
    let (w, h) = (f64::from(t.width()), f64::from(t.height()));
    let (ax, ay) = (f64::from(duvdx.x) * w, f64::from(duvdx.y) * h);
    let (bx, by) = (f64::from(duvdy.x) * w, f64::from(duvdy.y) * h);
    // Cells along each edge: enough that no cell's edge leans more than MAX_SKEW off an axis.
    let cells = |x: f64, y: f64| (x.abs().min(y.abs()) / MAX_SKEW).ceil().max(1.0);
    let (mut n, mut m) = (cells(ax, ay), cells(bx, by));
    if n * m > f64::from(MAX_CELLS) {
        // Long, thin and diagonal (a sphere's limb, a plane at a grazing angle): at most
        // MAX_CELLS cells in the same proportion, each a little more sheared than MAX_SKEW.
        let k = (f64::from(MAX_CELLS) / (n * m)).sqrt();
        (n, m) = ((n * k).floor().max(1.0), (m * k).floor().max(1.0));
    }
    let (ax, ay, bx, by) = (ax / n, ay / n, bx / m, by / m);
    let hx = 0.5 * (ax * ax + bx * bx).sqrt();
    let hy = 0.5 * (ay * ay + by * by).sqrt();
    if hx.max(hy) < MIN_HALF_WIDTH {
        // Magnified: the mean over so small a box is the bilinear lookup (taken by the caller).
        return None;
    }
    let (hx, hy) = (hx.max(MIN_HALF_WIDTH), hy.max(MIN_HALF_WIDTH));
    if t.level() > 0 && hx.min(hy) * 2.0 < MIN_LEVEL_SPAN {
        return None;
    }
    // How far the cells' boxes reach from the centre along each axis.
    let (sa, sb) = (0.5 * (n - 1.0), 0.5 * (m - 1.0));
    let (rx, ry) = (
        hx + ax.abs() * sa + bx.abs() * sb,
        hy + ay.abs() * sa + by.abs() * sb,
    );
    let (cx, cy) = (f64::from(uv.x) * w, f64::from(uv.y) * h);
    // Under black, a footprint wholly past the half texel that blends the edge into black is
    // black, exactly.
    let beyond = |c: f64, r: f64, n: f64| c - r >= n + 0.5 || c + r <= -0.5;
    if (wu == Wrap::Black && beyond(cx, rx, w)) || (wv == Wrap::Black && beyond(cy, ry, h)) {
        return Some(Rgb::BLACK);
    }
    let (cx, cy) = (clamp_shift(cx, rx, w, wu), clamp_shift(cy, ry, h, wv));
    if n * m == 1.0 {
        return Some(t.box_mean(cx, cy, hx, hy, wu, wv));
    }
    let mut sum = Rgb::BLACK;
    for j in 0..m as u32 {
        let tb = f64::from(j) + 0.5 - 0.5 * m;
        for i in 0..n as u32 {
            let ta = f64::from(i) + 0.5 - 0.5 * n;
            let (x, y) = (cx + ax * ta + bx * tb, cy + ay * ta + by * tb);
            sum += t.box_mean(x, y, hx, hy, wu, wv);
        }
    }
    Some(sum / (n * m) as f32)
}

/// Under clamp, a footprint wholly past the last texel centre (or before the first) reads only
/// the edge texels, which clamp repeats: it is moved to touch that centre, so every such
/// footprint reads the same sums (and gives the same colour, bit for bit). `c` is the centre,
/// `reach` how far the footprint reaches from it, `n` the side (texel units).
#[inline]
fn clamp_shift(c: f64, reach: f64, n: f64, wrap: Wrap) -> f64 {
    if wrap != Wrap::Clamp {
        c
    } else if c - reach > n - 0.5 {
        n - 0.5 + reach
    } else if c + reach < 0.5 {
        0.5 - reach
    } else {
        c
    }
}

/// The supersampling path: the midpoint rule over the parallelogram (see the module
/// documentation). `uv` is already reduced by the wraps. Public for the benchmark that sets the
/// table against it; the filter calls it only where the table does not serve.
#[must_use]
pub fn supersampled(
    mip: Option<&MipPyramid>,
    image: &ImageData,
    uv: Vec2,
    duvdx: Vec2,
    duvdy: Vec2,
    wu: Wrap,
    wv: Wrap,
) -> Rgb {
    let size = Vec2::new(image.width() as f32, image.height() as f32);
    let (la, lb) = ((duvdx * size).length(), (duvdy * size).length());
    if !(la.is_finite() && lb.is_finite()) {
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
            let want = exact(&img, uv, dx, dy);
            let f = footprint(None, &img, uv, dx, dy, R, R);
            assert!(max_diff(f, want) < 0.02, "{f:?} vs {want:?}");
            // ... where one bilinear tap at the centre is far off.
            let centre = img.bilinear(uv, R, R);
            assert!(max_diff(centre, want) > 0.05, "{centre:?} vs {want:?}");
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
    /// The footprint's exact mean: a 256 x 256 midpoint integration of the bilinear texture.
    fn exact(img: &ImageData, uv: Vec2, dx: Vec2, dy: Vec2) -> Rgb {
        let n = 256;
        let mut sum = Rgb::BLACK;
        for j in 0..n {
            for i in 0..n {
                let s = (i as f32 + 0.5) / n as f32 - 0.5;
                let t = (j as f32 + 0.5) / n as f32 - 0.5;
                sum += img.bilinear(uv + dx * s + dy * t, R, R);
            }
        }
        sum / (n * n) as f32
    }

    fn max_diff(a: Rgb, b: Rgb) -> f32 {
        let (a, b) = (a.to_array(), b.to_array());
        (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f32::max)
    }

    #[test]
    fn the_table_path_follows_sheared_and_rotated_footprints() {
        // Footprints a few texels long, axis-aligned, sheared and rotated by 45 degrees, across
        // the seam: the table's boxes against the exact mean, as close as the tap grid gets.
        let img = busy();
        let mip = MipPyramid::build(img.clone());
        let texel = Vec2::new(1.0 / 48.0, 1.0 / 40.0);
        for (uv, dx, dy) in [
            (
                Vec2::new(0.31, 0.42),
                Vec2::new(5.0, 0.0),
                Vec2::new(0.0, 3.0),
            ),
            (
                Vec2::new(0.31, 0.42),
                Vec2::new(4.0, 1.5),
                Vec2::new(-0.5, 3.0),
            ),
            (
                Vec2::new(0.55, 0.62),
                Vec2::new(3.0, 3.0),
                Vec2::new(-2.0, 2.0),
            ),
            (
                Vec2::new(0.77, 0.15),
                Vec2::new(6.0, -2.5),
                Vec2::new(0.5, 2.0),
            ),
            (
                Vec2::new(0.02, 0.97),
                Vec2::new(2.5, 0.0),
                Vec2::new(0.0, 2.4),
            ),
        ] {
            let (dx, dy) = (dx * texel, dy * texel);
            let want = exact(&img, uv, dx, dy);
            let table = footprint(Some(&mip), &img, uv, dx, dy, R, R);
            let taps = footprint(None, &img, uv, dx, dy, R, R);
            let (e_table, e_taps) = (max_diff(table, want), max_diff(taps, want));
            assert!(
                e_table < 0.03,
                "{uv:?} {dx:?} {dy:?}: {table:?} against {want:?}"
            );
            assert!(
                e_table < e_taps + 0.02,
                "table {e_table} taps {e_taps} at {uv:?}"
            );
        }
    }

    #[test]
    fn magnified_the_table_path_is_the_bilinear_lookup() {
        let img = busy();
        let mip = MipPyramid::build(img.clone());
        for k in 0..200 {
            let uv = Vec2::new((k as f32 * 0.618).fract(), (k as f32 * 0.414).fract());
            let d = Vec2::new(1e-6, 0.0);
            let f = footprint(Some(&mip), &img, uv, d, d.perp(), R, R);
            assert!(max_diff(f, img.bilinear(uv, R, R)) < 1e-5, "{uv:?}");
        }
        assert!(mip.has_summed_area());
    }
}
