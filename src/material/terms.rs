//! The lecture's shading terms per lane, written once over pulp's `Simd`: what a material makes
//! of its (textured) colour and coefficients at a hit ([`Material::terms`]), and one light's
//! reflected radiance ([`Terms::add_light`]). [`Material::shade_point`] and
//! [`ShadePoint::direct`] are their width-1 instances.

use super::{Colour, Material, Scalar};
use crate::math::lanes::{F, M, MAX_LANES, V3, from_array, mask_splat, to_array};
use crate::math::{INV_PI, Rgb};
use pulp::Simd;

pub use crate::math::lanes::C3;

/// A colour in every lane.
#[must_use]
#[inline(always)]
pub fn splat_rgb<S: Simd>(s: S, c: Rgb) -> C3<S> {
    [s.splat_f32s(c.0), s.splat_f32s(c.1), s.splat_f32s(c.2)]
}

/// `a * b` per channel and lane.
#[inline(always)]
fn mul3<S: Simd>(s: S, a: &C3<S>, b: &C3<S>) -> C3<S> {
    [
        s.mul_f32s(a[0], b[0]),
        s.mul_f32s(a[1], b[1]),
        s.mul_f32s(a[2], b[2]),
    ]
}

/// `a * k` per channel and lane.
#[inline(always)]
fn scale3<S: Simd>(s: S, a: &C3<S>, k: F<S>) -> C3<S> {
    [
        s.mul_f32s(a[0], k),
        s.mul_f32s(a[1], k),
        s.mul_f32s(a[2], k),
    ]
}

/// Whether a colour is not black, per lane (`c != Rgb::BLACK`).
#[inline(always)]
fn non_black<S: Simd>(s: S, c: &C3<S>) -> M<S> {
    let z = s.splat_f32s(0.0);
    s.not_m32s(s.and_m32s(
        s.and_m32s(s.equal_f32s(c[0], z), s.equal_f32s(c[1], z)),
        s.equal_f32s(c[2], z),
    ))
}

/// A material's terms at a packet's hits (the lecture's BRDF, evaluated once and then applied
/// per light).
#[derive(Clone, Copy, Debug)]
pub struct Terms<S: Simd> {
    /// Ambient term `ka cd * L_ambient` (or the emitted radiance for emissive surfaces).
    pub base: C3<S>,
    /// `kd cd / pi`, the Lambertian BRDF.
    pub diffuse: C3<S>,
    /// Specular `ks cs` and exponent, if the material has a highlight (Phong, Reflective).
    pub specular: Option<(C3<S>, F<S>)>,
    /// The mirror's `kr cr` (Reflective), and the lanes where it is not black.
    pub mirror: Option<(C3<S>, M<S>)>,
    /// Phong's glow `ce`, and the lanes where it is not black.
    pub glow: Option<(C3<S>, M<S>)>,
    /// Whether lights affect the material (emissive surfaces ignore them).
    pub lit: bool,
}

/// Where a material's coefficients and colours come from, per lane: a constant in every lane,
/// a texture evaluated lane by lane. (A trait, not closures: closures are compiled outside the
/// kernel's instruction set and would call each SIMD operation.)
pub trait ParamLanes<S: Simd> {
    /// A coefficient's value per lane.
    fn scalar(&self, p: &Scalar) -> F<S>;
    /// A colour's value per lane.
    fn colour(&self, p: &Colour) -> C3<S>;
}

/// `c ambient ka` and `c (kd / pi)`: the lecture's matte terms.
#[inline(always)]
fn lambert<S: Simd, P: ParamLanes<S>>(
    s: S,
    cd: &C3<S>,
    amb: &C3<S>,
    ka: &Scalar,
    kd: &Scalar,
    params: &P,
) -> (C3<S>, C3<S>) {
    (
        scale3(s, &mul3(s, cd, amb), params.scalar(ka)),
        scale3(s, cd, s.mul_f32s(params.scalar(kd), s.splat_f32s(INV_PI))),
    )
}

/// `ks cs` and the exponent: a highlight's terms.
#[inline(always)]
fn highlight<S: Simd, P: ParamLanes<S>>(
    s: S,
    ks: &Scalar,
    cs: &Colour,
    exp: &Scalar,
    params: &P,
) -> (C3<S>, F<S>) {
    (
        scale3(s, &params.colour(cs), params.scalar(ks)),
        params.scalar(exp),
    )
}

impl Material {
    /// The terms per lane, from the colour texture's value `cd` (or the emissive `ce`'s) and
    /// `params`, which give each coefficient's and colour's value per lane.
    #[must_use]
    #[inline(always)]
    pub fn terms<S: Simd, P: ParamLanes<S>>(
        &self,
        s: S,
        cd: &C3<S>,
        ambient: Rgb,
        params: &P,
    ) -> Terms<S> {
        let amb = splat_rgb(s, ambient);
        let black = splat_rgb(s, Rgb::BLACK);
        match self {
            Self::Matte { ka, kd, .. } => {
                let (base, diffuse) = lambert(s, cd, &amb, ka, kd, params);
                Terms {
                    base,
                    diffuse,
                    specular: None,
                    mirror: None,
                    glow: None,
                    lit: true,
                }
            }
            Self::Phong {
                ka,
                kd,
                ks,
                cs,
                exp,
                ce,
                ..
            } => {
                let (base, diffuse) = lambert(s, cd, &amb, ka, kd, params);
                let g = params.colour(ce);
                Terms {
                    base,
                    diffuse,
                    specular: Some(highlight(s, ks, cs, exp, params)),
                    mirror: None,
                    glow: Some((g, non_black(s, &g))),
                    lit: true,
                }
            }
            Self::Reflective {
                ka,
                kd,
                ks,
                cs,
                exp,
                kr,
                cr,
                ..
            } => {
                let (base, diffuse) = lambert(s, cd, &amb, ka, kd, params);
                let m = scale3(s, &params.colour(cr), params.scalar(kr));
                Terms {
                    base,
                    diffuse,
                    specular: Some(highlight(s, ks, cs, exp, params)),
                    mirror: Some((m, non_black(s, &m))),
                    glow: None,
                    lit: true,
                }
            }
            Self::Emissive { ls, .. } => Terms {
                base: scale3(s, cd, params.scalar(ls)),
                diffuse: black,
                specular: None,
                mirror: None,
                glow: None,
                lit: false,
            },
        }
    }
}

impl<S: Simd> Terms<S> {
    /// Adds one light's reflected radiance to `l` where `reach` (the light arrives above the
    /// surface, unshadowed): `f li (n . wi)` with `f = kd cd / pi`, plus `ks cs (r . wo)^exp`
    /// where the mirrored light direction `r = 2 (n . wi) n - wi` leans toward the viewer
    /// (libm's `powf`, per lane). `ndotwi` is `n . wi`; `lit` sums it where `reach`, for the
    /// glow's weight. `share` scales both where a shadow ray passed clip-mapped surfaces (the
    /// share of light they let through).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn add_light(
        &self,
        s: S,
        reach: M<S>,
        n: &V3<S>,
        wo: &V3<S>,
        wi: &V3<S>,
        li: Rgb,
        ndotwi: F<S>,
        share: Option<F<S>>,
        l: &mut C3<S>,
        lit: &mut F<S>,
    ) {
        let mut f = self.diffuse;
        if let Some((ks, exp)) = &self.specular {
            // r = -wi + (2 (n . wi)) n.
            let two = s.mul_f32s(s.splat_f32s(2.0), ndotwi);
            let r = wi.neg(s).add(s, &n.scale(s, two));
            let rdotwo = r.dot(s, wo);
            let toward = s.and_m32s(reach, s.greater_than_f32s(rdotwo, s.splat_f32s(0.0)));
            if crate::math::lanes::any(s, toward) {
                let (rd, e) = (to_array::<S>(rdotwo), to_array::<S>(*exp));
                let on = crate::math::lanes::mask_to_array(s, toward);
                let mut pw = [0.0; MAX_LANES];
                for i in 0..S::F32_LANES {
                    if on[i] {
                        pw[i] = rd[i].powf(e[i]);
                    }
                }
                let pw = from_array::<S>(&pw);
                for c in 0..3 {
                    let with = s.add_f32s(f[c], s.mul_f32s(ks[c], pw));
                    f[c] = s.select_f32s(toward, with, f[c]);
                }
            }
        }
        let li = splat_rgb(s, li);
        for c in 0..3 {
            let mut add = s.mul_f32s(s.mul_f32s(f[c], li[c]), ndotwi);
            if let Some(tr) = share {
                add = s.mul_f32s(add, tr);
            }
            l[c] = s.select_f32s(reach, s.add_f32s(l[c], add), l[c]);
        }
        let cos = share.map_or(ndotwi, |tr| s.mul_f32s(ndotwi, tr));
        *lit = s.select_f32s(reach, s.add_f32s(*lit, cos), *lit);
    }

    /// The mask of lanes where the material has a mirror that is not black.
    #[must_use]
    #[inline(always)]
    pub fn mirror_lanes(&self, s: S) -> M<S> {
        self.mirror.map_or(mask_splat(s, false), |(_, m)| m)
    }
}
