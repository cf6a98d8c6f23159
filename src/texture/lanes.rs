//! Texture lookups written once over pulp's `Simd`, as the render kernel reads them: the
//! bilinear filter's arithmetic in lanes around its per-lane wrap and texel loads.
//! [`ImageData::bilinear`] is its width-1 instance.

use super::{ImageData, Lookup, Wrap};

use crate::math::lanes::{C3, F, MAX_LANES, from_array, to_array};
use crate::math::{Rgb, Vec2, floor_fast};
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
                // All four texels inside the image (nearly every lookup): no wrapping.
                let (c, r) = (xi as u32, yi as u32);
                put(&mut t00, i, self.texel(c, r));
                put(&mut t10, i, self.texel(c + 1, r));
                put(&mut t01, i, self.texel(c, r + 1));
                put(&mut t11, i, self.texel(c + 1, r + 1));
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
}
