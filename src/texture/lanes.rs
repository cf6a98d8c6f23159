//! Texture lookups written once over pulp's `Simd`, as the render kernel reads them: the
//! bilinear filter's arithmetic in lanes around its per-lane wrap and texel loads
//! ([`ImageData::bilinear`] is its width-1 instance), trilinear filtering as bilinear lanes at
//! each lane's two mip levels ([`MipPyramid::trilinear`] is its width-1 instance), and a
//! texture's value at lanes of texture coordinates already mapped
//! ([`Texture::eval_tex_coord_lanes`], what bump and normal maps read).

use super::{
    Filter, ImageData, ImageTexture, Lookup, MipPyramid, TILE, Texels, Texture, Wrap, mark,
    tiled_index,
};

use crate::mapping::TexCoord;
use crate::math::lanes::{C3, F, MAX_LANES, from_array, mask_from_array, to_array};
use crate::math::{Rgb, Vec2, Vec3A, floor_fast};
use pulp::Simd;

/// Per-lane colour buffers.
type Buf = [[f32; MAX_LANES]; 3];

#[inline(always)]
fn put(b: &mut Buf, i: usize, c: Rgb) {
    (b[0][i], b[1][i], b[2][i]) = (c.0, c.1, c.2);
}

/// `a wa + b wb` per lane.
#[inline(always)]
fn lerp<S: Simd>(s: S, a: &[f32; MAX_LANES], b: &[f32; MAX_LANES], wa: F<S>, wb: F<S>) -> F<S> {
    s.add_f32s(
        s.mul_f32s(from_array::<S>(a), wa),
        s.mul_f32s(from_array::<S>(b), wb),
    )
}

impl ImageData {
    /// The four texels of each lane in `inside` (lanes `0..n`) whose lower-left texel (rows
    /// from the bottom) is stored at `at[i]`, into `t` (lower-left, lower-right, upper-left,
    /// upper-right): the same texels as `ImageData::texel` at the four corners, the other
    /// three addressed from the first by the tile layout, the storage's format chosen once for
    /// all lanes.
    #[inline(always)]
    fn quads(
        &self,
        n: usize,
        inside: &[bool; MAX_LANES],
        at: &[usize; MAX_LANES],
        t: [&mut Buf; 4],
    ) {
        if let Some((v, table)) = self.texels().bytes() {
            self.gather_quads(n, inside, at, t, |k| {
                let [r, g, b, _] = v[k];
                Rgb(table[r as usize], table[g as usize], table[b as usize])
            });
        } else if let Texels::Linear(v) = self.texels() {
            self.gather_quads(n, inside, at, t, |k| Rgb::from_array(v[k]));
        }
    }

    /// [`ImageData::quads`] with the texel at storage index `k` read by `load`.
    #[inline(always)]
    fn gather_quads(
        &self,
        n: usize,
        inside: &[bool; MAX_LANES],
        at: &[usize; MAX_LANES],
        t: [&mut Buf; 4],
        load: impl Fn(usize) -> Rgb,
    ) {
        // One texel right: the next in the tile's row, or the first of the next tile's row.
        // One row up (the file's row above): the tile's row above, or the tile above's last.
        let (tile, row) = ((TILE * TILE) as usize, TILE as usize);
        let up_tile = self.tiles_x() as usize * tile - row * (row - 1);
        let [t00, t10, t01, t11] = t;
        for i in 0..n {
            if !inside[i] {
                continue;
            }
            let k = at[i];
            let right = if k % row == row - 1 {
                tile - (row - 1)
            } else {
                1
            };
            let above = k - if k % tile < row { up_tile } else { row };
            put(t00, i, load(k));
            put(t10, i, load(k + right));
            put(t01, i, load(above));
            put(t11, i, load(above + right));
        }
    }

    /// Bilinear interpolation between the four nearest texel centres, (i + 0.5) / w, at
    /// (`u`, `v`) per lane for the lanes in `on`: each axis reduced by its wrap, the texel
    /// corner and weights, the four texels loaded per lane (wrapped only at the image's edges;
    /// black outside under `Black`), then `bottom (1 - fy) + top fy` with `top`, `bottom` each
    /// `left (1 - fx) + right fx`, in lanes. Lanes whose texel position is not finite read the
    /// nearest (centred) texel.
    #[must_use]
    #[inline(always)]
    pub fn bilinear_lanes<S: Simd>(
        &self,
        s: S,
        u: F<S>,
        v: F<S>,
        wu: Wrap,
        wv: Wrap,
        on: &[bool; MAX_LANES],
    ) -> C3<S> {
        let n = S::F32_LANES;
        let (ua, va) = (to_array::<S>(u), to_array::<S>(v));
        let (mut ru, mut rv) = ([0.0; MAX_LANES], [0.0; MAX_LANES]);
        for i in 0..n {
            ru[i] = wu.reduce(ua[i]);
            rv[i] = wv.reduce(va[i]);
        }
        let half = s.splat_f32s(0.5);
        let x = s.sub_f32s(
            s.mul_f32s(from_array::<S>(&ru), s.splat_f32s(self.width() as f32)),
            half,
        );
        let y = s.sub_f32s(
            s.mul_f32s(from_array::<S>(&rv), s.splat_f32s(self.height() as f32)),
            half,
        );
        let (xa, ya) = (to_array::<S>(x), to_array::<S>(y));
        let (mut x0, mut y0) = ([0.0; MAX_LANES], [0.0; MAX_LANES]);
        let mut odd = [false; MAX_LANES];
        let (mut t00, mut t10, mut t01, mut t11): (Buf, Buf, Buf, Buf) = Default::default();
        let mut near: Buf = Default::default();
        let (w, h) = (i64::from(self.width()), i64::from(self.height()));
        // The lanes whose four texels are all inside the image (nearly every lookup), and the
        // storage index of each one's lower-left texel, gathered below in one pass.
        let mut inside = [false; MAX_LANES];
        let mut at = [0_usize; MAX_LANES];
        for i in 0..n {
            if !on[i] {
                continue;
            }
            if !(xa[i].is_finite() && ya[i].is_finite()) {
                odd[i] = true;
                let uv = Vec2::new(ru[i], rv[i]);
                put(&mut near, i, self.nearest(uv, Lookup::Centred, wu, wv));
                continue;
            }
            (x0[i], y0[i]) = (floor_fast(xa[i]), floor_fast(ya[i]));
            let (xi, yi) = (x0[i] as i64, y0[i] as i64);
            if xi >= 0 && yi >= 0 && xi + 1 < w && yi + 1 < h {
                inside[i] = true;
                // `ImageData::texel`: rows from the bottom, stored from the top.
                at[i] = tiled_index(self.tiles_x(), xi as u32, (h - 1 - yi) as u32);
            } else {
                // At an edge: each axis's two indices wrapped once.
                let (c0, c1) = (wu.index(xi, self.width()), wu.index(xi + 1, self.width()));
                let (r0, r1) = (wv.index(yi, self.height()), wv.index(yi + 1, self.height()));
                let fetch = |c: Option<u32>, r: Option<u32>| match (c, r) {
                    (Some(c), Some(r)) => self.texel(c, r),
                    _ => Rgb::BLACK,
                };
                put(&mut t00, i, fetch(c0, r0));
                put(&mut t10, i, fetch(c1, r0));
                put(&mut t01, i, fetch(c0, r1));
                put(&mut t11, i, fetch(c1, r1));
            }
        }
        self.quads(n, &inside, &at, [&mut t00, &mut t10, &mut t01, &mut t11]);
        let one = s.splat_f32s(1.0);
        let fx = s.sub_f32s(x, from_array::<S>(&x0));
        let fy = s.sub_f32s(y, from_array::<S>(&y0));
        let (gx, gy) = (s.sub_f32s(one, fx), s.sub_f32s(one, fy));
        let mut out = [s.splat_f32s(0.0); 3];
        for c in 0..3 {
            let top = lerp(s, &t01[c], &t11[c], gx, fx);
            let bottom = lerp(s, &t00[c], &t10[c], gx, fx);
            out[c] = s.add_f32s(s.mul_f32s(bottom, gy), s.mul_f32s(top, fy));
        }
        if odd[..n].contains(&true) {
            let m = crate::math::lanes::mask_from_array(s, &odd);
            for c in 0..3 {
                out[c] = s.select_f32s(m, from_array::<S>(&near[c]), out[c]);
            }
        }
        out
    }
}

impl MipPyramid {
    /// Trilinear filtering per lane for the lanes in `on` (`tc`: each lane's coordinates and
    /// screen-space derivatives): each lane's footprint width and continuous level
    /// ([`MipPyramid::level_for_width`]), bilinear lanes at each level the lanes need (one
    /// call per distinct level, masked to its lanes), then `a (1 - t) + b t` in lanes where a
    /// lane's level has a fraction `t > 0`.
    #[must_use]
    #[inline(always)]
    pub fn trilinear_lanes<S: Simd>(
        &self,
        s: S,
        tc: &[TexCoord; MAX_LANES],
        wu: Wrap,
        wv: Wrap,
        on: &[bool; MAX_LANES],
    ) -> C3<S> {
        let base = self.level(0);
        let size = Vec2::new(base.width() as f32, base.height() as f32);
        let (mut u, mut v) = ([0.0; MAX_LANES], [0.0; MAX_LANES]);
        let (mut lower, mut t) = ([0_usize; MAX_LANES], [0.0_f32; MAX_LANES]);
        let mut upper_on = [false; MAX_LANES];
        for i in 0..S::F32_LANES {
            if !on[i] {
                continue;
            }
            (u[i], v[i]) = (tc[i].uv.x, tc[i].uv.y);
            let width = (tc[i].duvdx * size)
                .length()
                .max((tc[i].duvdy * size).length());
            let lod = self.level_for_width(width);
            let l0 = lod.floor();
            t[i] = lod - l0;
            lower[i] = l0 as usize;
            upper_on[i] = t[i] > 0.0;
        }
        let (u, v) = (from_array::<S>(&u), from_array::<S>(&v));
        let a = self.levels_lanes(s, u, v, &lower, wu, wv, on);
        if !upper_on[..S::F32_LANES].contains(&true) {
            return a;
        }
        let mut upper = lower;
        for l in &mut upper {
            *l += 1;
        }
        let b = self.levels_lanes(s, u, v, &upper, wu, wv, &upper_on);
        let t = from_array::<S>(&t);
        let one_minus = s.sub_f32s(s.splat_f32s(1.0), t);
        let blend = mask_from_array(s, &upper_on);
        let mut out = a;
        for k in 0..3 {
            let mixed = s.add_f32s(s.mul_f32s(a[k], one_minus), s.mul_f32s(b[k], t));
            out[k] = s.select_f32s(blend, mixed, a[k]);
        }
        out
    }

    /// Bilinear lanes at level `level[i]` for each lane `i` in `on`: one masked call per
    /// distinct level.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn levels_lanes<S: Simd>(
        &self,
        s: S,
        u: F<S>,
        v: F<S>,
        level: &[usize; MAX_LANES],
        wu: Wrap,
        wv: Wrap,
        on: &[bool; MAX_LANES],
    ) -> C3<S> {
        let mut out = [s.splat_f32s(0.0); 3];
        let mut left = *on;
        while let Some(first) = left[..S::F32_LANES].iter().position(|&x| x) {
            let l = level[first];
            let mut these = [false; MAX_LANES];
            for i in 0..S::F32_LANES {
                these[i] = left[i] && level[i] == l;
            }
            let c = self.level(l).bilinear_lanes(s, u, v, wu, wv, &these);
            let m = mask_from_array(s, &these);
            for k in 0..3 {
                out[k] = s.select_f32s(m, c[k], out[k]);
            }
            for i in 0..S::F32_LANES {
                left[i] &= !these[i];
            }
        }
        out
    }
}

impl ImageTexture {
    /// The filtered colour (before `scale`) at each lane's coordinates `tc` for the lanes in
    /// `on`: [`ImageTexture::sample`] lane-wise, the bilinear and trilinear filters in lanes,
    /// the others per lane.
    #[must_use]
    #[inline(always)]
    pub fn sample_lanes<S: Simd>(
        &self,
        s: S,
        tc: &[TexCoord; MAX_LANES],
        on: &[bool; MAX_LANES],
    ) -> C3<S> {
        let (wu, wv) = self.wraps();
        match (self.filter, &self.mip) {
            (Filter::Trilinear, Some(m)) => m.trilinear_lanes(s, tc, wu, wv, on),
            (Filter::Bilinear, _) | (Filter::Trilinear | Filter::Ewa, None) => {
                let (mut u, mut v) = ([0.0; MAX_LANES], [0.0; MAX_LANES]);
                for i in 0..S::F32_LANES {
                    (u[i], v[i]) = (tc[i].uv.x, tc[i].uv.y);
                }
                self.image
                    .bilinear_lanes(s, from_array::<S>(&u), from_array::<S>(&v), wu, wv, on)
            }
            _ => {
                let mut c: Buf = Default::default();
                for i in 0..S::F32_LANES {
                    if on[i] {
                        put(&mut c, i, self.sample(tc[i]));
                    }
                }
                crate::math::lanes::map3(c, |a| from_array::<S>(&a))
            }
        }
    }
}

impl ImageTexture {
    /// The colour at each lane's coordinates `tc` (after the (u, v) transform) for the lanes in
    /// `on`: [`ImageTexture::sample_lanes`] times the texture's `scale`, the [`mark`] where a
    /// lane's (u, v) is not finite (what `ImageTexture::eval_mapped` gives per lane).
    #[must_use]
    #[inline(always)]
    pub fn eval_lanes<S: Simd>(
        &self,
        s: S,
        tc: &[TexCoord; MAX_LANES],
        on: &[bool; MAX_LANES],
    ) -> C3<S> {
        let mut ok = [false; MAX_LANES];
        for i in 0..S::F32_LANES {
            ok[i] = on[i] && tc[i].uv.is_finite();
        }
        let k = s.splat_f32s(self.scale);
        let mut c = self.sample_lanes(s, tc, &ok);
        for x in &mut c {
            *x = s.mul_f32s(*x, k);
        }
        if ok[..S::F32_LANES] != on[..S::F32_LANES] {
            let m = mask_from_array(s, &ok);
            let x = mark();
            let x = [x.0, x.1, x.2];
            for k in 0..3 {
                c[k] = s.select_f32s(m, c[k], s.splat_f32s(x[k]));
            }
        }
        c
    }
}

impl Texture {
    /// [`Texture::eval_tex_coord`] at each lane's coordinates `tc` and object-space point `p`
    /// for the lanes in `on`: an image in lanes ([`ImageTexture::sample_lanes`], times its
    /// `scale`; the [`mark`] where a lane's (u, v) is not finite), a constant splat, the other
    /// kinds per lane.
    #[must_use]
    #[inline(always)]
    pub fn eval_tex_coord_lanes<S: Simd>(
        &self,
        s: S,
        tc: &[TexCoord; MAX_LANES],
        p: &[Vec3A; MAX_LANES],
        on: &[bool; MAX_LANES],
    ) -> C3<S> {
        match self {
            Self::Image(t) => t.eval_lanes(s, tc, on),
            Self::Constant(c) => [s.splat_f32s(c.0), s.splat_f32s(c.1), s.splat_f32s(c.2)],
            _ => {
                let mut c: Buf = Default::default();
                for i in 0..S::F32_LANES {
                    if on[i] {
                        put(&mut c, i, self.eval_tex_coord(tc[i], p[i]));
                    }
                }
                crate::math::lanes::map3(c, |a| from_array::<S>(&a))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::lanes::testing::{Walk, WidthCheck, at_every_width, bits};
    use strum::VariantArray;

    /// The bilinear lanes at every width against width 1, under every wrap pair, on hard
    /// coordinates (edges, huge, NaN, infinite) and images of 1x1 to 7x3 texels.
    struct Agree;

    impl WidthCheck for Agree {
        fn check<S: Simd>(&mut self, s: S, name: &'static str) {
            let images = [
                ImageData::from_fn(7, 3, "7x3", |c, r| Rgb(c as f32, r as f32 * 0.5, 0.25)),
                ImageData::from_fn(1, 1, "1x1", |_, _| Rgb(0.5, 0.25, 1.0)),
                ImageData::from_fn(2, 5, "2x5", |c, r| Rgb::grey((c * 5 + r) as f32 / 10.0)),
            ];
            let mut walk = Walk(9);
            let on = [true; MAX_LANES];
            for round in 0..400 {
                let (u, v) = (walk.lanes(), walk.lanes());
                let img = &images[round % images.len()];
                for &wu in Wrap::VARIANTS {
                    for &wv in Wrap::VARIANTS {
                        let c = img
                            .bilinear_lanes(
                                s,
                                from_array::<S>(&u),
                                from_array::<S>(&v),
                                wu,
                                wv,
                                &on,
                            )
                            .map(to_array::<S>);
                        for i in 0..S::F32_LANES {
                            let one = img.bilinear(Vec2::new(u[i], v[i]), wu, wv);
                            assert_eq!(
                                [c[0][i], c[1][i], c[2][i]].map(bits),
                                [one.0, one.1, one.2].map(bits),
                                "{name}: ({}, {}) {wu:?} {wv:?}",
                                u[i],
                                v[i]
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn bilinear_gives_the_same_bits_at_every_width() {
        assert!(at_every_width(&mut Agree) >= 1);
    }

    /// The bilinear lanes at every width against the filter's definition from the four
    /// `ImageData::texel` reads, at every inside position of images whose sides are not
    /// multiples of the tile (so lanes read across tile edges in both directions), in 8-bit
    /// and linear storage.
    struct Corners;

    impl WidthCheck for Corners {
        fn check<S: Simd>(&mut self, s: S, name: &'static str) {
            let (w, h) = (11_u32, 9_u32);
            let colour =
                |c: u32, r: u32| [(c * 23 + r * 7) as u8, (r * 31) as u8, (c * 5) as u8, 255];
            let texels = |f: fn(Vec<[u8; 4]>) -> Texels| {
                f((0..h)
                    .flat_map(|r| (0..w).map(move |c| colour(c, r)))
                    .collect())
            };
            let images = [
                ImageData::new(w, h, texels(Texels::Srgb8), "srgb"),
                ImageData::new(w, h, texels(Texels::Unorm8), "unorm"),
                ImageData::from_fn(w, h, "linear", |c, r| {
                    let [a, b, d, _] = colour(c, r);
                    Rgb(f32::from(a) / 7.0, f32::from(b) / 3.0, f32::from(d))
                }),
            ];
            // Every lower-left texel (c, r) of an inside quad, at a point inside it.
            let corners: Vec<(u32, u32)> = (0..h - 1)
                .flat_map(|r| (0..w - 1).map(move |c| (c, r)))
                .collect();
            for img in &images {
                for chunk in corners.chunks(S::F32_LANES) {
                    let (mut u, mut v) = ([0.0; MAX_LANES], [0.0; MAX_LANES]);
                    let mut on = [false; MAX_LANES];
                    for (i, &(c, r)) in chunk.iter().enumerate() {
                        u[i] = (c as f32 + 0.5 + 0.3) / w as f32;
                        v[i] = (r as f32 + 0.5 + 0.6) / h as f32;
                        on[i] = true;
                    }
                    let (wu, wv) = (Wrap::Repeat, Wrap::Clamp);
                    let got = img
                        .bilinear_lanes(s, from_array::<S>(&u), from_array::<S>(&v), wu, wv, &on)
                        .map(to_array::<S>);
                    for (i, &(c, r)) in chunk.iter().enumerate() {
                        let (x, y) = (u[i] * w as f32 - 0.5, v[i] * h as f32 - 0.5);
                        let (fx, fy) = (x - c as f32, y - r as f32);
                        let (gx, gy) = (1.0 - fx, 1.0 - fy);
                        let t = |c, r| img.texel(c, r).to_array();
                        let (t00, t10, t01, t11) =
                            (t(c, r), t(c + 1, r), t(c, r + 1), t(c + 1, r + 1));
                        for k in 0..3 {
                            let bottom = t00[k] * gx + t10[k] * fx;
                            let top = t01[k] * gx + t11[k] * fx;
                            let want = bottom * gy + top * fy;
                            assert_eq!(
                                bits(got[k][i]),
                                bits(want),
                                "{name} {}: texel ({c}, {r}) channel {k}",
                                img.name
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn bilinear_reads_the_four_texels_across_tile_edges() {
        assert!(at_every_width(&mut Corners) >= 1);
    }

    /// Trilinear lanes at every width against the filter's definition per lane: bilinear at
    /// the two levels around the footprint's width, `a (1 - t) + b t`, on footprints from
    /// magnified to wider than the image (so the lanes of one packet read different levels),
    /// with hard coordinates and derivatives.
    struct Trilinear;

    impl WidthCheck for Trilinear {
        fn check<S: Simd>(&mut self, s: S, name: &'static str) {
            let base = ImageData::from_fn(37, 20, "37x20", |c, r| {
                Rgb(c as f32 / 37.0, (r * c % 7) as f32 / 7.0, 0.25)
            });
            let mip = MipPyramid::build(std::sync::Arc::new(base));
            let mut walk = Walk(3);
            for round in 0..300 {
                let (u, v) = (walk.lanes(), walk.lanes());
                let (dx, dy) = (walk.lanes(), walk.lanes());
                let on: [bool; MAX_LANES] = std::array::from_fn(|i| (i + round) % 5 != 0);
                let tc: [TexCoord; MAX_LANES] = std::array::from_fn(|i| {
                    // Widths from a hundredth of a texel to past the whole image.
                    let k = 10f32.powi((i as i32 + round as i32) % 6 - 4);
                    TexCoord {
                        uv: Vec2::new(u[i], v[i]),
                        duvdx: Vec2::new(dx[i] * k, dy[i] * k * 0.5),
                        duvdy: Vec2::new(dy[i] * k * 0.25, dx[i] * k),
                    }
                });
                let (wu, wv) = (Wrap::VARIANTS[round % 4], Wrap::VARIANTS[(round / 4) % 4]);
                let c = mip.trilinear_lanes(s, &tc, wu, wv, &on).map(to_array::<S>);
                for i in 0..S::F32_LANES {
                    if !on[i] {
                        continue;
                    }
                    let size = Vec2::new(37.0, 20.0);
                    let width = (tc[i].duvdx * size)
                        .length()
                        .max((tc[i].duvdy * size).length());
                    let lod = mip.level_for_width(width);
                    let l0 = lod.floor();
                    let t = lod - l0;
                    let a = mip.level(l0 as usize).bilinear(tc[i].uv, wu, wv);
                    let want = if t <= 0.0 {
                        a
                    } else {
                        let b = mip.level(l0 as usize + 1).bilinear(tc[i].uv, wu, wv);
                        a * (1.0 - t) + b * t
                    };
                    assert_eq!(
                        [c[0][i], c[1][i], c[2][i]].map(bits),
                        [want.0, want.1, want.2].map(bits),
                        "{name}: {:?} {wu:?} {wv:?}",
                        tc[i]
                    );
                }
            }
        }
    }

    #[test]
    fn trilinear_gives_the_filters_bits_at_every_width() {
        assert!(at_every_width(&mut Trilinear) >= 1);
    }
}
