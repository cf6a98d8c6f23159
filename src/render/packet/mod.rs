//! The packet path: coherent primary rays traced [`LANES`] at a time, struct-of-arrays, for
//! scenes made of what it supports; everything else takes the scalar path unchanged.
//!
//! A packet is up to [`LANES`] consecutive pixels of one row with the same sample index. Their
//! sample positions come from [`sample_position_and_cell`], as on the scalar path; the camera
//! rays, the transform into each object's space, the generic shapes' intersections, the nearest
//! hit, the world-space normal facing the viewer, the mapping, the (u, v) transform and the
//! shading (ambient, Lambert and Phong terms per light, glow) are computed lane-wise by the
//! kernels in [`super::lanes`], operation for operation as the scalar code computes them. Per
//! lane, the texel lookup (the existing `Texture::eval_tex_coord`: wrap, nearest or bilinear
//! index, the compact storage's decode) and each shadow ray (`Scene::occluded_except`, with the
//! same self-shadow rule as `Scene::shade_at_depth`) run the scalar code.
//!
//! Eligibility ([`PacketPlan::new`]) is decided once per pass from the scene: pinhole or
//! orthographic camera, the shaded view, no footprint filter (so no ray differentials), no clip
//! map, and only spheres, planes, rectangles and disks. Within an eligible scene a lane whose hit
//! needs what the packet path lacks (a mirror, a textured coefficient, a bump or normal map) is
//! traced again by the scalar path ([`super::radiance_keyed_cell`]), exactly as before.
//!
//! Runtime dispatch: the pass runs inside [`pulp::Arch::dispatch`], which calls it through a
//! function compiled for the best instruction set the CPU has (AVX-512, AVX2 + FMA, else the
//! SSE2 baseline; NEON on aarch64). Everything on the packet's hot path is `#[inline(always)]`,
//! so it is compiled for that level.

// Lane loops index several arrays by the lane (`for i in 0..LANES`), the form the vectoriser
// reads best; `&` and `|` between lane conditions keep them branch-free (selects, not jumps).
#![allow(clippy::needless_range_loop, clippy::needless_bitwise_bool)]

use super::lanes::{self, F, Flat, LANES, M, V3, splat};
use crate::camera::Projection;
use crate::geometry::Shape;
use crate::mapping::{Mapping, TexCoord, UvAffine};
use crate::material::{Colour, Material, Scalar, ShadePoint};
use crate::math::srgb8_table;
use crate::math::{Affine3A, INV_PI, Mat3A, Ray, Rgb, Vec2, Vec3A, max_abs};
use crate::scene::{SHADOW_OFFSET_RELATIVE, Scene, natural_mapping};
use crate::texture::{Filter, ImageData, Lookup, Texels, Texture, View, Wrap, tiled_index};
use std::fmt;
use std::sync::OnceLock;

/// Which path primary rays take.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SimdMode {
    /// The packet path where the scene is eligible, the scalar path elsewhere.
    #[default]
    Auto,
    /// The scalar path for every scene (for comparison and tests).
    Scalar,
}

impl SimdMode {
    /// The process-wide default: [`SimdMode::Scalar`] when the environment variable
    /// `TEXPLORE_SIMD` is `off` (or `0`, `false`, `scalar`), else [`SimdMode::Auto`]. Read once.
    #[must_use]
    pub fn from_env() -> Self {
        static MODE: OnceLock<SimdMode> = OnceLock::new();
        *MODE.get_or_init(|| match std::env::var("TEXPLORE_SIMD") {
            Ok(v) if matches!(v.trim(), "off" | "0" | "false" | "scalar") => Self::Scalar,
            _ => Self::Auto,
        })
    }
}

/// The instruction set [`pulp::Arch::dispatch`] picks on this CPU, for `texplore bench`.
#[must_use]
pub fn simd_level() -> &'static str {
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    {
        match pulp::Arch::new() {
            pulp::Arch::V4(_) => "AVX-512 (x86-64-v4)",
            pulp::Arch::V3(_) => "AVX2 + FMA (x86-64-v3)",
            _ => "SSE2 (x86-64 baseline)",
        }
    }
    #[cfg(target_arch = "aarch64")]
    {
        "NEON (aarch64)"
    }
    #[cfg(not(any(target_arch = "x86", target_arch = "x86_64", target_arch = "aarch64")))]
    {
        "scalar (no SIMD dispatch on this architecture)"
    }
}

/// Why a scene takes the scalar path.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ineligible(pub String);

impl fmt::Display for Ineligible {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

/// Which path a scene's primary rays take under `mode`: `Ok(())` for the packet path, or why
/// not.
///
/// # Errors
/// The reason the scene (or `mode`) sends it to the scalar path.
pub fn packet_eligibility(scene: &Scene, mode: SimdMode) -> Result<(), Ineligible> {
    PacketPlan::new(scene, mode).map(|_| ())
}

/// A generic shape the packet path intersects.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Sphere,
    Flat(Flat),
}

/// How the packet path shades one object's hits (constant coefficients).
#[derive(Clone, Copy, Debug)]
enum Response {
    /// Matte or Phong: ambient `ka`, `kd / pi`, the highlight and the glow.
    Lit {
        ka: f32,
        kd_pi: f32,
        specular: Option<(Rgb, f32)>,
        glow: Rgb,
    },
    /// Emissive: `ls` times the texture.
    Emissive { ls: f32 },
}

/// The texture and response of an object the packet path shades.
#[derive(Clone, Copy, Debug)]
struct Shading<'a> {
    texture: &'a Texture,
    /// The lane-wise nearest lookup, where the texture is an image read that way.
    nearest: Option<Nearest<'a>>,
    /// The mapping after `Uv` falls back to the shape's own (`None` for a constant).
    mapping: Option<Mapping>,
    affine: Option<UvAffine>,
    response: Response,
}

/// An image texture under the nearest filter with repeat or clamp wrapping (the Earth's): its
/// wrap, texel index and tile address computed lane-wise, then one load per lane. Each step is
/// `ImageData::nearest`'s (`Wrap::coord`, `Lookup::index`, `ImageData::texel`), so a lane reads
/// the texel the scalar lookup reads.
#[derive(Clone, Copy, Debug)]
struct Nearest<'a> {
    image: &'a ImageData,
    lookup: Lookup,
    wu: Wrap,
    wv: Wrap,
    scale: f32,
}

impl<'a> Nearest<'a> {
    fn new(texture: &'a Texture) -> Option<Self> {
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
    fn sample(&self, u: &F, v: &F, mine: M) -> [F; 3] {
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

/// The (u, v) of object-space points `p` under `mapping` (spherical, cylindrical or
/// rectangular), then the (u, v) transform `affine` (`UvAffine::apply`: non-finite results
/// become (0, 0)).
#[inline(always)]
fn map_lanes(plan: &PacketPlan, mapping: Mapping, affine: Option<&UvAffine>, p: &V3) -> (F, F) {
    let (mut u, mut v) = match mapping {
        Mapping::Spherical => plan.spherical(p),
        Mapping::Cylindrical => lanes::cylindrical(p),
        _ => lanes::rectangular(p),
    };
    if let Some(a) = affine {
        let (mx, my) = (a.matrix.x_axis, a.matrix.y_axis);
        for i in 0..LANES {
            let nu = (mx.x * u[i] + my.x * v[i]) + a.offset.x;
            let nv = (mx.y * u[i] + my.y * v[i]) + a.offset.y;
            let ok = nu.is_finite() & nv.is_finite();
            u[i] = if ok { nu } else { 0.0 };
            v[i] = if ok { nv } else { 0.0 };
        }
    }
    (u, v)
}

/// One object as the packet path sees it.
#[derive(Clone, Debug)]
struct ObjectPlan<'a> {
    kind: Kind,
    identity: bool,
    object_from_world: Affine3A,
    world_from_object: Affine3A,
    normal_to_world: Mat3A,
    normal_orthonormal: bool,
    /// The object's translation's largest coordinate, for the shadow offset.
    translation_max_abs: f32,
    /// `None`: lanes that hit this object take the scalar path.
    shading: Option<Shading<'a>>,
}

/// What the packet path needs of a scene, built once per pass.
#[derive(Clone, Debug)]
pub(crate) struct PacketPlan<'a> {
    scene: &'a Scene,
    orthographic: bool,
    objects: Vec<ObjectPlan<'a>>,
    /// The explicit 8-wide kernels' token (AVX2 and up); `None`: the lane loops alone.
    #[cfg(target_arch = "x86_64")]
    wide: Option<pulp::x86::V3>,
}

fn constant(s: &Scalar) -> Option<f32> {
    match s {
        Scalar::Const(v) => Some(*v),
        Scalar::Texture(_) => None,
    }
}

fn constant_colour(c: &Colour) -> Option<Rgb> {
    match c {
        Colour::Const(v) => Some(*v),
        Colour::Texture(_) => None,
    }
}

/// The packet path's shading of `material` on `shape`, or `None` where it lacks something.
fn shading<'a>(material: &'a Material, shape: &Shape) -> Option<Shading<'a>> {
    let (texture, response) = match material {
        Material::Matte { ka, kd, cd } => (
            cd,
            Response::Lit {
                ka: constant(ka)?,
                kd_pi: constant(kd)? * INV_PI,
                specular: None,
                glow: Rgb::BLACK,
            },
        ),
        Material::Phong {
            ka,
            kd,
            cd,
            ks,
            cs,
            exp,
            ce,
        } => (
            cd,
            Response::Lit {
                ka: constant(ka)?,
                kd_pi: constant(kd)? * INV_PI,
                specular: Some((constant_colour(cs)? * constant(ks)?, constant(exp)?)),
                glow: constant_colour(ce)?,
            },
        ),
        Material::Emissive { ls, ce } => (ce, Response::Emissive { ls: constant(ls)? }),
        Material::Reflective { .. } => return None,
    };
    if texture.needs_differentials() {
        return None;
    }
    let mapping = texture.mapping().map(|m| match m {
        Mapping::Uv => natural_mapping(shape),
        m => m,
    });
    if !matches!(
        mapping,
        None | Some(Mapping::Spherical | Mapping::Cylindrical | Mapping::Rectangular)
    ) {
        return None;
    }
    Some(Shading {
        texture,
        nearest: Nearest::new(texture),
        mapping,
        affine: texture.uv_affine(),
        response,
    })
}

impl<'a> PacketPlan<'a> {
    /// The plan for `scene`, or why it takes the scalar path.
    pub(crate) fn new(scene: &'a Scene, mode: SimdMode) -> Result<Self, Ineligible> {
        let no = |why: &str| Err(Ineligible(why.to_owned()));
        if mode == SimdMode::Scalar {
            return no("the scalar path was asked for");
        }
        if scene.settings.view != View::Shaded {
            return no("a debug view");
        }
        if scene.needs_differentials {
            return no("a filter that needs ray differentials");
        }
        if scene.has_clips {
            return no("a clip map");
        }
        let orthographic = match scene.camera.projection {
            Projection::Pinhole { .. } => false,
            Projection::Orthographic { .. } => true,
            _ => return no("a fisheye or spherical camera"),
        };
        if scene.objects.len() >= 0xffff {
            return no("more objects than edge keys");
        }
        let mut objects = Vec::with_capacity(scene.objects.len());
        for (i, o) in scene.objects.iter().enumerate() {
            let kind = match o.shape {
                Shape::Sphere => Kind::Sphere,
                Shape::Plane => Kind::Flat(Flat::Plane),
                Shape::Rectangle => Kind::Flat(Flat::Rectangle),
                Shape::Disk => Kind::Flat(Flat::Disk),
                Shape::Cylinder { .. } => return no("a cylinder"),
                Shape::Mesh(_) => return no("a mesh"),
            };
            let perturbed = scene.bumps.get(i).is_some_and(Option::is_some)
                || scene.normal_maps.get(i).is_some_and(Option::is_some);
            let shading = if perturbed {
                None
            } else {
                shading(&scene.materials[o.material], &o.shape)
            };
            objects.push(ObjectPlan {
                kind,
                identity: o.identity,
                object_from_world: o.object_from_world,
                world_from_object: o.world_from_object,
                normal_to_world: o.normal_to_world,
                normal_orthonormal: o.normal_orthonormal,
                translation_max_abs: max_abs(o.world_from_object.translation),
                shading,
            });
        }
        Ok(Self {
            scene,
            orthographic,
            objects,
            #[cfg(target_arch = "x86_64")]
            wide: lanes::wide::token(),
        })
    }

    /// The spherical map per lane, 8 wide where the CPU allows.
    #[inline(always)]
    fn spherical(&self, p: &V3) -> (F, F) {
        #[cfg(target_arch = "x86_64")]
        if let Some(s) = self.wide {
            return lanes::wide::spherical(s, p);
        }
        lanes::spherical(p)
    }

    /// The camera rays through the lanes' film positions (`Camera::primary_ray`).
    #[inline(always)]
    fn camera_rays(&self, px: &F, py: &F) -> (V3, V3) {
        let cam = &self.scene.camera;
        let (w, h) = (cam.width as f32, cam.height as f32);
        let scale = cam.pixel_scale();
        let [u, v, back] = cam.frame;
        let (mut x, mut y) = ([0.0; LANES], [0.0; LANES]);
        for i in 0..LANES {
            x[i] = (px[i] - 0.5 * w) * scale;
            y[i] = (0.5 * h - py[i]) * scale;
        }
        let mut o = V3::splat(cam.eye);
        let mut d = V3::splat(-back);
        if self.orthographic {
            // eye + x u + y v, summed left to right as glam does.
            for i in 0..LANES {
                o.x[i] = (cam.eye.x + x[i] * u.x) + y[i] * v.x;
                o.y[i] = (cam.eye.y + x[i] * u.y) + y[i] * v.y;
                o.z[i] = (cam.eye.z + x[i] * u.z) + y[i] * v.z;
            }
        } else {
            // x u + y v - back.
            for i in 0..LANES {
                d.x[i] = (x[i] * u.x + y[i] * v.x) - back.x;
                d.y[i] = (x[i] * u.y + y[i] * v.y) - back.y;
                d.z[i] = (x[i] * u.z + y[i] * v.z) - back.z;
            }
        }
        (o, d)
    }

    /// Traces one packet: film positions `px`, `py` for the `active` lanes. Returns the radiance
    /// (r, g, b per lane), the edge keys, and the lanes the scalar path must trace instead.
    #[allow(clippy::too_many_lines)]
    #[inline(always)]
    pub(crate) fn trace(&self, px: &F, py: &F, active: M) -> ([F; 3], [u32; LANES], M) {
        let scene = self.scene;
        let (o, d) = self.camera_rays(px, py);

        // The nearest hit over the objects, in preset order (`Scene::intersect`).
        let mut t_best = [0.0_f32; LANES];
        for i in 0..LANES {
            t_best[i] = if active[i] { f32::INFINITY } else { 0.0 };
        }
        let mut object = [u32::MAX; LANES];
        let mut lp = V3::splat(Vec3A::ZERO);
        let mut ln = V3::splat(Vec3A::Y);
        for (k, ob) in self.objects.iter().enumerate() {
            let (oo, od) = if ob.identity {
                (o, d)
            } else {
                (
                    o.point(&ob.object_from_world),
                    d.linear(&ob.object_from_world.matrix3),
                )
            };
            #[cfg(target_arch = "x86_64")]
            if let Some(s) = self.wide {
                use lanes::wide;
                let (t, p, n, hit) = match ob.kind {
                    Kind::Sphere => {
                        let (t, hit) = wide::sphere(s, &oo, &od, &t_best);
                        if !wide::any(hit) {
                            continue;
                        }
                        let p = lanes::sphere_point(&oo, &od, &t);
                        (t, p, p, hit)
                    }
                    Kind::Flat(f) => {
                        let (t, p, hit) = lanes::flat(&oo, &od, &t_best, f);
                        (t, p, V3::splat(Vec3A::Y), wide::mask(&hit))
                    }
                };
                t_best = wide::select(s, hit, &t, &t_best);
                object = wide::select_u32(s, hit, &[k as u32; LANES], &object);
                lp = wide::select_v3(s, hit, &p, &lp);
                ln = wide::select_v3(s, hit, &n, &ln);
                continue;
            }
            let (t, p, n, hit) = match ob.kind {
                Kind::Sphere => {
                    let (t, hit) = lanes::sphere(&oo, &od, &t_best);
                    if !hit.contains(&true) {
                        continue;
                    }
                    let p = lanes::sphere_point(&oo, &od, &t);
                    (t, p, p, hit)
                }
                Kind::Flat(f) => {
                    let (t, p, hit) = lanes::flat(&oo, &od, &t_best, f);
                    (t, p, V3::splat(Vec3A::Y), hit)
                }
            };
            for i in 0..LANES {
                let h = hit[i];
                t_best[i] = if h { t[i] } else { t_best[i] };
                object[i] = if h { k as u32 } else { object[i] };
                lp.x[i] = if h { p.x[i] } else { lp.x[i] };
                lp.y[i] = if h { p.y[i] } else { lp.y[i] };
                lp.z[i] = if h { p.z[i] } else { lp.z[i] };
                ln.x[i] = if h { n.x[i] } else { ln.x[i] };
                ln.y[i] = if h { n.y[i] } else { ln.y[i] };
                ln.z[i] = if h { n.z[i] } else { ln.z[i] };
            }
        }

        // Background for misses; the scalar path for lanes whose object it must shade.
        let bg = scene.settings.background;
        let mut rgb = [splat(bg.0), splat(bg.1), splat(bg.2)];
        let mut keys = [0_u32; LANES];
        let mut fallback = [false; LANES];
        let mut shaded = [false; LANES];
        for i in 0..LANES {
            if object[i] != u32::MAX {
                let has = self.objects[object[i] as usize].shading.is_some();
                fallback[i] = !has;
                shaded[i] = has;
            }
        }
        if !shaded.contains(&true) {
            return (rgb, keys, fallback);
        }

        // World-space point and normal per lane (`Scene::resolve`), the (u, v) and the
        // material's terms, object by object for the objects this packet hit.
        let mut p = lp;
        let mut ng = ln;
        let mut base = [[0.0; LANES]; 3];
        let mut diffuse = [[0.0; LANES]; 3];
        let mut spec = [[0.0; LANES]; 3];
        let mut exponent = [0.0; LANES];
        let mut has_spec = [false; LANES];
        let mut glow = [[0.0; LANES]; 3];
        let mut lit_material = [false; LANES];
        let mut trans = [0.0; LANES];
        let mut self_shadowing_sphere = [false; LANES];
        let ambient = scene.ambient;
        for (k, ob) in self.objects.iter().enumerate() {
            let Some(sh) = &ob.shading else { continue };
            let mut mine = [false; LANES];
            for i in 0..LANES {
                mine[i] = shaded[i] && object[i] == k as u32;
            }
            if !mine.contains(&true) {
                continue;
            }
            if !ob.identity {
                let wp = lp.point(&ob.world_from_object);
                let mut wn = ln.linear(&ob.normal_to_world);
                if !ob.normal_orthonormal {
                    wn = wn.normalize_or(Vec3A::Y);
                }
                for i in 0..LANES {
                    if mine[i] {
                        p.set_lane(i, wp.lane(i));
                        ng.set_lane(i, wn.lane(i));
                    }
                }
            }
            // (u, v) of the object-space point, then the (u, v) transform.
            // A function, not a closure: a closure this size stays out of line, compiled for
            // the baseline instead of the dispatched level.
            #[allow(clippy::manual_map)]
            let uv = match sh.mapping {
                Some(m) => Some(map_lanes(self, m, sh.affine.as_ref(), &lp)),
                None => None,
            };
            // The texel lookups first, the scalar filter per lane (a gather); then the
            // material's terms lane-wise.
            let mut tex = [[0.0; LANES]; 3];
            if let (Some(n), Some((u, v))) = (&sh.nearest, &uv) {
                tex = n.sample(u, v, mine);
            }
            for i in 0..LANES {
                if !mine[i] || (sh.nearest.is_some() & uv.is_some()) {
                    continue;
                }
                let c = match &uv {
                    Some((u, v)) => sh.texture.eval_tex_coord(TexCoord {
                        uv: Vec2::new(u[i], v[i]),
                        duvdx: Vec2::ZERO,
                        duvdy: Vec2::ZERO,
                    }),
                    None => sh.texture.eval_tex_coord(TexCoord::default()),
                };
                (tex[0][i], tex[1][i], tex[2][i]) = (c.0, c.1, c.2);
            }
            let amb = [ambient.0, ambient.1, ambient.2];
            match sh.response {
                Response::Lit {
                    ka,
                    kd_pi,
                    specular,
                    glow: g,
                } => {
                    let g = [g.0, g.1, g.2];
                    let (s, e) = specular.map_or(([0.0; 3], 0.0), |(s, e)| ([s.0, s.1, s.2], e));
                    for c in 0..3 {
                        for i in 0..LANES {
                            let m = mine[i];
                            // c ambient ka and c (kd / pi), as `Material::shade_point`.
                            base[c][i] = if m {
                                tex[c][i] * amb[c] * ka
                            } else {
                                base[c][i]
                            };
                            diffuse[c][i] = if m { tex[c][i] * kd_pi } else { diffuse[c][i] };
                            spec[c][i] = if m { s[c] } else { spec[c][i] };
                            glow[c][i] = if m { g[c] } else { glow[c][i] };
                        }
                    }
                    for i in 0..LANES {
                        let m = mine[i];
                        exponent[i] = if m { e } else { exponent[i] };
                        has_spec[i] = if m { specular.is_some() } else { has_spec[i] };
                        lit_material[i] |= m;
                    }
                }
                Response::Emissive { ls } => {
                    for c in 0..3 {
                        for i in 0..LANES {
                            base[c][i] = if mine[i] { tex[c][i] * ls } else { base[c][i] };
                        }
                    }
                }
            }
            for i in 0..LANES {
                let m = mine[i];
                trans[i] = if m { ob.translation_max_abs } else { trans[i] };
                self_shadowing_sphere[i] |= m & (ob.kind == Kind::Sphere);
            }
        }

        // Facing: two-sided surfaces shade the side the ray came from.
        let mut wo = d;
        for i in 0..LANES {
            wo.x[i] = -d.x[i];
            wo.y[i] = -d.y[i];
            wo.z[i] = -d.z[i];
        }
        let wo = wo.normalize_or(Vec3A::Z);
        let facing = ng.dot(&wo);
        let mut front = [true; LANES];
        for i in 0..LANES {
            let back = facing[i] < 0.0;
            front[i] = !back;
            ng.x[i] = if back { -ng.x[i] } else { ng.x[i] };
            ng.y[i] = if back { -ng.y[i] } else { ng.y[i] };
            ng.z[i] = if back { -ng.z[i] } else { ng.z[i] };
        }
        let ns = ng;

        // Direct light (`Scene::shade_at_depth`): the ambient term, then each light that
        // reaches the point past its shadow ray.
        let mut l = base;
        let pmax = p.max_abs();
        let mut offset = [0.0; LANES];
        for i in 0..LANES {
            offset[i] = SHADOW_OFFSET_RELATIVE * (pmax[i] + trans[i]).max(f32::MIN_POSITIVE);
            keys[i] = if shaded[i] {
                (object[i] + 1) & 0xffff
            } else {
                0
            };
        }
        let mut lit = [0.0; LANES];
        let lights_on = lit_material.contains(&true);
        for (li, light) in scene.lights.iter().enumerate().filter(|_| lights_on) {
            let mut wi = V3::splat(Vec3A::ZERO);
            let mut dist = [f32::INFINITY; LANES];
            let (radiance, shadows) = match *light {
                crate::material::Light::Directional {
                    to_light,
                    radiance,
                    shadows,
                } => {
                    wi = V3::splat(to_light);
                    (radiance, shadows)
                }
                crate::material::Light::Point {
                    position,
                    radiance,
                    shadows,
                } => {
                    let mut dv = p;
                    for i in 0..LANES {
                        dv.x[i] = position.x - p.x[i];
                        dv.y[i] = position.y - p.y[i];
                        dv.z[i] = position.z - p.z[i];
                    }
                    let len2 = dv.dot(&dv);
                    for i in 0..LANES {
                        let dl = len2[i].sqrt();
                        dist[i] = dl;
                        let pos = dl > 0.0;
                        wi.x[i] = if pos { dv.x[i] / dl } else { 0.0 };
                        wi.y[i] = if pos { dv.y[i] / dl } else { 1.0 };
                        wi.z[i] = if pos { dv.z[i] / dl } else { 0.0 };
                    }
                    (radiance, shadows)
                }
            };
            let ndotwi = ns.dot(&wi);
            let gdotwi = ng.dot(&wi);
            let mut reach = [false; LANES];
            for i in 0..LANES {
                reach[i] = lit_material[i] && !(ndotwi[i] <= 0.0 || gdotwi[i] <= 0.0);
            }
            if shadows {
                for i in 0..LANES {
                    if !reach[i] {
                        continue;
                    }
                    // A sphere hit from outside cannot shadow itself, nor can a flat shape.
                    let k = object[i] as usize;
                    let skip = if self_shadowing_sphere[i] && !front[i] {
                        usize::MAX
                    } else {
                        k
                    };
                    let origin = p.lane(i) + ng.lane(i) * offset[i];
                    let t_max = if dist[i].is_finite() {
                        dist[i] - offset[i]
                    } else {
                        f32::INFINITY
                    };
                    if scene.occluded_except(&Ray::new(origin, wi.lane(i)), t_max, skip) {
                        keys[i] |= (1 << (16 + li.min(14))) as u32;
                        reach[i] = false;
                    }
                }
            }
            let mut pw = [0.0; LANES];
            if has_spec.contains(&true) {
                for i in 0..LANES {
                    // r = -wi + 2 (n . wi) n; the highlight where r . wo > 0.
                    let two = 2.0 * ndotwi[i];
                    let rx = -wi.x[i] + two * ns.x[i];
                    let ry = -wi.y[i] + two * ns.y[i];
                    let rz = -wi.z[i] + two * ns.z[i];
                    let rdotwo = (rx * wo.x[i] + ry * wo.y[i]) + rz * wo.z[i];
                    if reach[i] && has_spec[i] && rdotwo > 0.0 {
                        pw[i] = rdotwo.powf(exponent[i]);
                    }
                }
            }
            let li_c = [radiance.0, radiance.1, radiance.2];
            #[cfg(target_arch = "x86_64")]
            if let Some(s) = self.wide {
                lanes::wide::add_light(
                    s, &reach, &has_spec, &pw, &diffuse, &spec, li_c, &ndotwi, &mut l, &mut lit,
                );
                continue;
            }
            for c in 0..3 {
                for i in 0..LANES {
                    let f = if has_spec[i] && pw[i] != 0.0 {
                        diffuse[c][i] + spec[c][i] * pw[i]
                    } else {
                        diffuse[c][i]
                    };
                    let add = f * li_c[c] * ndotwi[i];
                    l[c][i] = if reach[i] { l[c][i] + add } else { l[c][i] };
                }
            }
            for i in 0..LANES {
                lit[i] = if reach[i] { lit[i] + ndotwi[i] } else { lit[i] };
            }
        }
        for i in 0..LANES {
            if !shaded[i] {
                continue;
            }
            let g = Rgb(glow[0][i], glow[1][i], glow[2][i]);
            let mut v = Rgb(l[0][i], l[1][i], l[2][i]);
            if g != Rgb::BLACK {
                v += g * ShadePoint::glow_weight(lit[i]);
            }
            if !v.is_finite() {
                v = Rgb::BLACK;
            }
            (rgb[0][i], rgb[1][i], rgb[2][i]) = (v.0, v.1, v.2);
        }
        (rgb, keys, fallback)
    }
}
