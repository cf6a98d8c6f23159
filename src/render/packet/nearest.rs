//! The packet path's texel lookups and mappings: the lane-wise nearest lookup of an image
//! texture, and the (u, v) of a lane's object-space point under the mappings the packet path
//! computes lane-wise ([`LaneMapping`]; a formula mapping runs per lane).

// Lane loops index several arrays by the lane, the form the vectoriser reads best.
#![allow(clippy::needless_range_loop)]

use super::super::lanes::{self, F, LANES, M, V3};
use super::{LaneMapping, PacketPlan};
use crate::mapping::UvAffine;
use crate::math::srgb8_table;
use crate::texture::{Filter, ImageData, Lookup, Texels, Texture, Wrap, tiled_index};

/// An image texture under the nearest filter with repeat or clamp wrapping (the Earth's): its
/// wrap, texel index and tile address computed lane-wise, then one load per lane. Each step is
/// `ImageData::nearest`'s (`Wrap::coord`, `Lookup::index`, `ImageData::texel`), so a lane reads
/// the texel the scalar lookup reads.
#[derive(Clone, Copy, Debug)]
pub(super) struct Nearest<'a> {
    image: &'a ImageData,
    lookup: Lookup,
    wu: Wrap,
    wv: Wrap,
    scale: f32,
}

impl<'a> Nearest<'a> {
    pub(super) fn new(texture: &'a Texture) -> Option<Self> {
        let Texture::Image(t) = texture else {
            return None;
        };
        let (wu, wv) = t.wraps();
        let plain = |w: Wrap| matches!(w, Wrap::Repeat | Wrap::Clamp);
        (t.filter == Filter::Nearest && plain(wu) && plain(wv)).then_some(Self {
            image: &t.image,
            lookup: t.lookup,
            wu,
            wv,
            scale: t.scale,
        })
    }

    /// `Wrap::coord` per lane for repeat or clamp (never `None` for these).
    #[inline(always)]
    fn coord(wrap: Wrap, t: &mut F) {
        let repeat = wrap == Wrap::Repeat;
        for x in t.iter_mut() {
            let v = *x;
            let inside = (0.0..=1.0).contains(&v);
            let f = v - v.floor();
            let wrapped = if repeat {
                if f < 1.0 { f } else { 0.0 }
            } else if v < 0.0 {
                0.0
            } else {
                1.0
            };
            let w = if v.is_nan() { 0.0 } else { wrapped };
            *x = if inside { v } else { w };
        }
    }

    /// `Lookup::index` per lane.
    #[inline(always)]
    fn index(lookup: Lookup, t: &F, n: u32) -> [u32; LANES] {
        let last = n - 1;
        // The lecture's (hres - 1) u or the centred u hres (a product: the order of its
        // operands does not change it).
        let nf = match lookup {
            Lookup::Lecture => last as f32,
            Lookup::Centred => n as f32,
        };
        let mut r = [0; LANES];
        for i in 0..LANES {
            r[i] = ((t[i] * nf) as u32).min(last);
        }
        r
    }

    /// The colours (times the texture's scale) at (u, v) per lane, for the lanes in `mine`.
    #[inline(always)]
    pub(super) fn sample(&self, u: &F, v: &F, mine: M) -> [F; 3] {
        let (mut u, mut v) = (*u, *v);
        Self::coord(self.wu, &mut u);
        Self::coord(self.wv, &mut v);
        let (w, h) = (self.image.width(), self.image.height());
        let col = Self::index(self.lookup, &u, w);
        let row = Self::index(self.lookup, &v, h);
        let tiles_x = self.image.tiles_x();
        let mut at = [0_usize; LANES];
        for i in 0..LANES {
            // `ImageData::texel`: the row from the bottom to the file's row from the top.
            at[i] = tiled_index(tiles_x, col[i], h - 1 - row[i]);
        }
        let mut c = [[0.0; LANES]; 3];
        let s = self.scale;
        match self.image.texels() {
            Texels::Srgb8(px) => {
                let t = srgb8_table();
                for i in 0..LANES {
                    if mine[i] {
                        let [r, g, b, _] = px[at[i]];
                        c[0][i] = t[r as usize] * s;
                        c[1][i] = t[g as usize] * s;
                        c[2][i] = t[b as usize] * s;
                    }
                }
            }
            Texels::Linear(px) => {
                for i in 0..LANES {
                    if mine[i] {
                        let [r, g, b] = px[at[i]];
                        c[0][i] = r * s;
                        c[1][i] = g * s;
                        c[2][i] = b * s;
                    }
                }
            }
        }
        c
    }
}

/// The (u, v) of object-space points `p` under `mapping`, then the (u, v) transform `affine`
/// (`UvAffine::apply`: non-finite results become (0, 0)).
#[inline(always)]
pub(super) fn map_lanes<S: pulp::Simd>(
    s: S,
    mapping: LaneMapping,
    affine: Option<&UvAffine>,
    p: &V3,
    mine: M,
) -> (F, F) {
    let (mut u, mut v) = match mapping {
        LaneMapping::Spherical => PacketPlan::spherical(s, p),
        LaneMapping::Cylindrical => lanes::cylindrical(p),
        LaneMapping::Rectangular => lanes::rectangular(p),
        LaneMapping::Formula(f, natural) => formula_lanes(f, natural, p, mine),
    };
    // A formula's NaN (u, v) stays NaN through the transform: the texel is marked, as on the
    // scalar path (`ImageTexture::tex_coord` skips the transform there).
    let formula = matches!(mapping, LaneMapping::Formula(..));
    if let Some(a) = affine {
        let (mx, my) = (a.matrix.x_axis, a.matrix.y_axis);
        for i in 0..LANES {
            let nu = (mx.x * u[i] + my.x * v[i]) + a.offset.x;
            let nv = (mx.y * u[i] + my.y * v[i]) + a.offset.y;
            let ok = nu.is_finite() & nv.is_finite();
            let marked = formula & (u[i].is_nan() | v[i].is_nan());
            u[i] = if ok {
                nu
            } else if marked {
                f32::NAN
            } else {
                0.0
            };
            v[i] = if ok {
                nv
            } else if marked {
                f32::NAN
            } else {
                0.0
            };
        }
    }
    (u, v)
}

/// A formula mapping per lane: the scalar program (the lanes' mesh_u, mesh_v from the shape's
/// natural mapping, as `AnyMapping::map_with_differentials` reads them); NaN where not finite.
#[inline(always)]
fn formula_lanes(
    f: &crate::mapping::FormulaMapping,
    natural: crate::mapping::Mapping,
    p: &V3,
    mine: M,
) -> (F, F) {
    let (mut u, mut v) = ([0.0; LANES], [0.0; LANES]);
    let mesh = f.reads_mesh();
    for i in 0..LANES {
        if !mine[i] {
            continue; // another object's lane: its point is not this formula's to count
        }
        let q = crate::math::Vec3A::new(p.x[i], p.y[i], p.z[i]);
        let own = if mesh {
            natural.map_uv(q)
        } else {
            crate::math::Vec2::ZERO
        };
        let uv = f.map_uv(q, own);
        (u[i], v[i]) = (uv.x, uv.y);
    }
    (u, v)
}
