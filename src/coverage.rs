//! The mapping made visible, computed without a window: which texels the pixels read (the
//! *visible region*), which pixels read chosen texels (the *reverse lookup*), and where the
//! lines of constant u and v run over the image (*iso-lines*).
//!
//! Everything starts from one cheap pass, [`UvField::compute`]: one ray through each pixel's
//! centre, as [`Scene::inspect`](crate::scene::Scene) casts it, keeping the object hit, its
//! (u, v) and the footprint's d(u, v)/dx, d(u, v)/dy. The pass runs on the render pool
//! ([`crate::render::thread_pool`]) and stops within a row when cancelled, so the window can
//! start one per scene edit. The texels a pixel reads come from the renderer's own lookups
//! ([`texels_read`]): the nearest filter's texel, bilinear's 4 taps, bicubic's 16, and for the
//! footprint filters (trilinear, EWA) the texels of level 0 under the pixel's footprint.

use crate::geometry::Shape;
use crate::mapping::formula::compare::{self, Agreement, Mistake};
use crate::mapping::{AnyMapping, Mapping, TexCoord};
use crate::math::{Vec2, Vec3A};
use crate::render::{Cancelled, PoolError, thread_pool};
use crate::scene::Scene;
use crate::texture::{Compare, Filter, ImageTexture, Texture};
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};

/// Iso-line spacing by default: lines at u, v = k / 8.
pub const DEFAULT_ISO_DIVISIONS: u32 = 8;

/// Above this many texels, a footprint is rasterised in square blocks of texels (each block
/// marked whole), so one pixel at a pole (whose footprint may cover the whole texture) costs at
/// most about this many steps.
pub const MAX_FOOTPRINT_STEPS: u32 = 4096;

/// What the renderer's primary ray found at one pixel centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelUv {
    /// The object hit (an index into `Scene::objects`).
    pub object: usize,
    /// For meshes, the triangle hit in the mesh's own (BVH) order.
    pub prim: u32,
    /// (u, v) before the wrap modes, with their screen-space derivatives (always computed,
    /// whatever the filter, as the inspector does).
    pub tex: TexCoord,
}

/// One ray through each pixel centre of the scene's film: the object hit and its texture
/// coordinates, for objects whose texture has a mapping.
#[derive(Clone, Debug)]
pub struct UvField {
    /// Film width in pixels.
    pub width: u32,
    /// Film height in pixels.
    pub height: u32,
    /// Row by row from the top; `None` where the ray hits nothing or an untextured object.
    pub pixels: Vec<Option<PixelUv>>,
    /// Each object's mapping in effect (after `uv` falls back to the shape's natural one) for
    /// the pixels that hit it; `None` for constant colours.
    pub mappings: Vec<Option<AnyMapping>>,
}

/// The texture an object's material reads (its diffuse or emitted colour).
#[must_use]
pub fn object_texture(scene: &Scene, object: usize) -> Option<&Texture> {
    let obj = scene.objects.get(object)?;
    Some(scene.materials.get(obj.material)?.texture())
}

/// The image texture an object's material reads, if it reads one.
#[must_use]
pub fn object_image(scene: &Scene, object: usize) -> Option<&ImageTexture> {
    match object_texture(scene, object)? {
        Texture::Image(t) => Some(t),
        _ => None,
    }
}

/// The objects whose texture reads an image, in scene order.
#[must_use]
pub fn textured_objects(scene: &Scene) -> Vec<usize> {
    (0..scene.objects.len())
        .filter(|&i| object_image(scene, i).is_some())
        .collect()
}

impl UvField {
    /// One ray through each pixel centre of `scene`'s film, on the shared render pool, rows in
    /// parallel. `cancel` is read once per row.
    ///
    /// # Errors
    /// [`FieldError::Cancelled`] when `cancel` was set before the pass finished;
    /// [`FieldError::Pool`] when no worker pool could be had.
    pub fn compute(scene: &Scene, cancel: &AtomicBool) -> Result<Self, FieldError> {
        let (w, h) = (scene.settings.width, scene.settings.height);
        let mappings: Vec<Option<AnyMapping>> = (0..scene.objects.len())
            .map(|i| object_texture(scene, i).and_then(Texture::mapping).cloned())
            .collect();
        let pool = thread_pool(0).map_err(FieldError::Pool)?;
        let mut pixels = vec![None; w as usize * h as usize];
        pool.install(|| {
            pixels
                .par_chunks_mut(w.max(1) as usize)
                .enumerate()
                .try_for_each(|(y, row)| {
                    if cancel.load(Ordering::Relaxed) {
                        return Err(Cancelled);
                    }
                    for (x, px) in row.iter_mut().enumerate() {
                        *px = pixel_uv(scene, &mappings, x as u32, y as u32);
                    }
                    Ok(())
                })
        })
        .map_err(|Cancelled| FieldError::Cancelled)?;
        let effective = mappings
            .iter()
            .zip(&scene.objects)
            .map(|(m, obj)| {
                m.as_ref().map(|m| match (m.builtin(), &obj.shape) {
                    (Some(Mapping::Uv), Shape::Mesh(mesh)) if mesh.mesh.has_uv() => m.clone(),
                    (Some(Mapping::Uv), shape) => crate::scene::natural_mapping(shape).into(),
                    _ => m.clone(),
                })
            })
            .collect();
        Ok(Self {
            width: w,
            height: h,
            pixels,
            mappings: effective,
        })
    }

    /// The sample at pixel (x, y) (from the top-left corner), if the ray hit a textured object.
    #[must_use]
    pub fn at(&self, x: u32, y: u32) -> Option<&PixelUv> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.pixels[(y * self.width + x) as usize].as_ref()
    }
}

/// Why no [`UvField`] came back.
#[derive(Debug, thiserror::Error)]
pub enum FieldError {
    /// A newer request cancelled this pass.
    #[error("cancelled")]
    Cancelled,
    /// No worker pool.
    #[error(transparent)]
    Pool(PoolError),
}

/// The ray through the centre of pixel (x, y), as [`Scene::inspect`] casts it: the object hit
/// and its texture coordinates with the footprint's derivatives.
fn pixel_uv(scene: &Scene, mappings: &[Option<AnyMapping>], x: u32, y: u32) -> Option<PixelUv> {
    let pixel = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
    let (ray, diff) = scene.camera.ray(pixel, 1.0)?;
    let hit = scene.hit(&ray)?;
    let mapping = mappings.get(hit.object)?.as_ref()?;
    let obj = &scene.objects[hit.object];
    let d = if obj.identity {
        diff
    } else {
        diff.transformed(&obj.object_from_world)
    };
    let (dpdx, dpdy) = d.footprint_on_plane(hit.local.p, hit.local.n);
    let ctx = scene.texture_context_at(&hit, dpdx, dpdy);
    Some(PixelUv {
        object: hit.object,
        prim: hit.local.prim,
        tex: ctx.tex_coord(mapping),
    })
}

/// The most pixel centres [`visible_agreement`] looks through (a grid over the film).
pub const MAX_VISIBLE_POINTS: usize = 40_000;

/// The points of `object` that the film's pixel centres see, through a grid of at most
/// `max_points` of them (every k-th pixel of every k-th row): each the local hit point and the
/// shape's own (u, v) there (what a formula's `mesh_u`, `mesh_v` read), as
/// [`crate::mapping::formula::compare`] takes points.
///
/// # Errors
/// As [`UvField::compute`].
pub fn visible_points(
    scene: &Scene,
    object: usize,
    max_points: usize,
    cancel: &AtomicBool,
) -> Result<Vec<(DVec3, DVec2)>, FieldError> {
    let (w, h) = (scene.settings.width, scene.settings.height);
    let pixels = f64::from(w) * f64::from(h);
    let step = (pixels / max_points.max(1) as f64).sqrt().ceil().max(1.0) as u32;
    let pool = thread_pool(0).map_err(FieldError::Pool)?;
    let rows: Vec<u32> = (0..h).step_by(step as usize).collect();
    let found = pool
        .install(|| {
            rows.par_iter()
                .map(|&y| {
                    if cancel.load(Ordering::Relaxed) {
                        return Err(Cancelled);
                    }
                    let mut row = Vec::new();
                    for x in (0..w).step_by(step as usize) {
                        let pixel = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                        let Some((ray, _)) = scene.camera.ray(pixel, 1.0) else {
                            continue;
                        };
                        let Some(hit) = scene.hit(&ray).filter(|hit| hit.object == object) else {
                            continue;
                        };
                        let ctx = scene.texture_context_at(&hit, Vec3A::ZERO, Vec3A::ZERO);
                        let own = Mapping::Uv.map_with_differentials(
                            ctx.p,
                            Vec3A::ZERO,
                            Vec3A::ZERO,
                            ctx.shape_uv,
                            ctx.natural,
                        );
                        row.push((ctx.p.as_dvec3(), own.uv.as_dvec2()));
                    }
                    Ok(row)
                })
                .collect::<Result<Vec<_>, Cancelled>>()
        })
        .map_err(|Cancelled| FieldError::Cancelled)?;
    Ok(found.into_iter().flatten().collect())
}

/// How the formula mapping of `object`'s texture compares with a built-in mapping over the
/// visible surface.
#[derive(Clone, Debug, PartialEq)]
pub struct VisibleAgreement {
    /// The share of the visible points where they agree, and the largest differences.
    pub agreement: Agreement,
    /// The common mistakes found ([`compare::mistakes`]), none for a correct formula.
    pub mistakes: Vec<Mistake>,
    /// The tolerance used, in (u, v).
    pub tolerance: DVec2,
}

/// The formula mapping of `object`'s texture against `compare.with` over the surface the film
/// sees ([`visible_points`], at most [`MAX_VISIBLE_POINTS`]), within `compare.tolerance`
/// texels of the texture's image: the agreement and the mistakes, by the same code as
/// `texplore map --compare`. `Ok(None)` when the object's texture has no formula mapping.
///
/// # Errors
/// As [`UvField::compute`].
pub fn visible_agreement(
    scene: &Scene,
    object: usize,
    compare: Compare,
    cancel: &AtomicBool,
) -> Result<Option<VisibleAgreement>, FieldError> {
    let Some(texture) = object_texture(scene, object) else {
        return Ok(None);
    };
    let Some(AnyMapping::Formula(formula)) = texture.mapping() else {
        return Ok(None);
    };
    let points = visible_points(scene, object, MAX_VISIBLE_POINTS, cancel)?;
    let tolerance = texture.texel_size() * f64::from(compare.tolerance);
    Ok(Some(VisibleAgreement {
        agreement: compare::agreement(formula, compare.with, &points, tolerance),
        mistakes: compare::mistakes(formula, compare.with, &points, tolerance),
        tolerance,
    }))
}

/// A set of texels of one image (level 0), column by row counted from the bottom (as v is).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TexelMask {
    /// Image width in texels.
    pub width: u32,
    /// Image height in texels.
    pub height: u32,
    bits: Vec<bool>,
}

impl TexelMask {
    /// No texel of a `width` x `height` image.
    #[must_use]
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            bits: vec![false; width as usize * height as usize],
        }
    }

    /// Adds texel (`column`, `row_from_bottom`); ignored outside the image.
    pub fn insert(&mut self, column: u32, row_from_bottom: u32) {
        if column < self.width && row_from_bottom < self.height {
            self.bits[(row_from_bottom * self.width + column) as usize] = true;
        }
    }

    /// Whether texel (`column`, `row_from_bottom`) is in the set.
    #[must_use]
    pub fn contains(&self, column: u32, row_from_bottom: u32) -> bool {
        column < self.width
            && row_from_bottom < self.height
            && self.bits[(row_from_bottom * self.width + column) as usize]
    }

    /// How many texels are in the set.
    #[must_use]
    pub fn count(&self) -> usize {
        self.bits.iter().filter(|&&b| b).count()
    }

    /// Whether the set is empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        !self.bits.contains(&true)
    }

    /// Adds every texel of `other` (of the same size).
    fn union_with(&mut self, other: &Self) {
        for (a, b) in self.bits.iter_mut().zip(&other.bits) {
            *a |= *b;
        }
    }
}

/// A set of film pixels, row by row from the top.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PixelMask {
    /// Film width in pixels.
    pub width: u32,
    /// Film height in pixels.
    pub height: u32,
    /// One flag per pixel, row by row from the top.
    pub bits: Vec<bool>,
}

impl PixelMask {
    /// Whether pixel (x, y) is in the set.
    #[must_use]
    pub fn contains(&self, x: u32, y: u32) -> bool {
        x < self.width && y < self.height && self.bits[(y * self.width + x) as usize]
    }

    /// How many pixels are in the set.
    #[must_use]
    pub fn count(&self) -> usize {
        self.bits.iter().filter(|&&b| b).count()
    }
}

/// Calls `f(column, row_from_bottom)` for every texel of level 0 that `texture`'s filter reads
/// at `tex` (with repeats for texels a wrap brings back twice): the nearest filter's texel under
/// its lookup, bilinear's 4 taps, bicubic's 16; trilinear, EWA and footprint read their footprint: the
/// texels whose centres lie in the parallelogram the pixel square maps to (half of d(u, v)/dx
/// and d(u, v)/dy either side of the centre, see [`footprint_texels`]), with bilinear's 4 taps
/// around its centre (what they read when the texture is magnified).
pub fn texels_read(texture: &ImageTexture, tex: &TexCoord, mut f: impl FnMut(u32, u32)) {
    let img = &texture.image;
    let (w, h) = (img.width(), img.height());
    let (wu, wv) = texture.wraps();
    let taps = |x0: i64, y0: i64, n: i64, f: &mut dyn FnMut(u32, u32)| {
        for j in y0..y0 + n {
            for i in x0..x0 + n {
                if let (Some(c), Some(r)) = (wu.index(i, w), wv.index(j, h)) {
                    f(c, r);
                }
            }
        }
    };
    let x = tex.uv.x * w as f32 - 0.5;
    let y = tex.uv.y * h as f32 - 0.5;
    match texture.filter {
        Filter::Nearest => {
            if let Some((c, r)) = img.nearest_index(tex.uv, texture.lookup, wu, wv) {
                f(c, r);
            }
        }
        _ if !(x.is_finite() && y.is_finite()) => {
            if let Some((c, r)) = img.nearest_index(tex.uv, crate::texture::Lookup::Centred, wu, wv)
            {
                f(c, r);
            }
        }
        Filter::Bilinear => taps(x.floor() as i64, y.floor() as i64, 2, &mut f),
        Filter::Bicubic => taps(x.floor() as i64 - 1, y.floor() as i64 - 1, 4, &mut f),
        Filter::Trilinear | Filter::Ewa | Filter::Footprint => {
            if texture.mip.is_none() {
                // Without a pyramid they fall back to bilinear.
                taps(x.floor() as i64, y.floor() as i64, 2, &mut f);
                return;
            }
            taps(x.floor() as i64, y.floor() as i64, 2, &mut f);
            footprint_texels(tex, w, h, &mut |i, j| {
                if let (Some(c), Some(r)) = (wu.index(i, w), wv.index(j, h)) {
                    f(c, r);
                }
            });
        }
    }
}

/// The texels (unwrapped indices, column and row from the bottom) whose centres lie in the
/// footprint of `tex` on a `w` x `h` image: the parallelogram the pixel square maps to, centre
/// `uv`, half of d(u, v)/dx and of d(u, v)/dy either side (the pixel spans half a pixel either
/// side of its centre). Neighbouring pixels' parallelograms tile the texture, so the visible
/// region has no holes between them; the ellipse the window draws is inscribed in it. Big
/// footprints are walked in square blocks (see [`MAX_FOOTPRINT_STEPS`]).
pub fn footprint_texels(tex: &TexCoord, w: u32, h: u32, f: &mut dyn FnMut(i64, i64)) {
    let s = Vec2::new(w as f32, h as f32);
    let c = tex.uv * s;
    let (a, b) = (tex.duvdx * s * 0.5, tex.duvdy * s * 0.5);
    let det = a.x * b.y - a.y * b.x;
    if !(det.is_finite() && c.is_finite()) || det.abs() < 1e-12 {
        return;
    }
    // The parallelogram {c + s a + t b : |s|, |t| <= 1}: q in it when both coordinates of
    // M^-1 (q - c) are within [-1, 1], M = [a b].
    let inv = |d: Vec2| Vec2::new(b.y * d.x - b.x * d.y, -a.y * d.x + a.x * d.y) / det;
    let half = a.abs() + b.abs();
    let (lo, hi) = ((c - half).floor(), (c + half).ceil());
    let area = (hi.x - lo.x) * (hi.y - lo.y);
    let step = if area > MAX_FOOTPRINT_STEPS as f32 {
        (area / MAX_FOOTPRINT_STEPS as f32).sqrt().ceil() as i64
    } else {
        1
    };
    let (x0, x1, y0, y1) = (lo.x as i64, hi.x as i64, lo.y as i64, hi.y as i64);
    let mut j = y0;
    while j <= y1 {
        let mut i = x0;
        while i <= x1 {
            // A block is in when its centre is (texel centres at i + 0.5 when step is 1).
            let centre = Vec2::new(i as f32 + step as f32 * 0.5, j as f32 + step as f32 * 0.5);
            if inv(centre - c).abs().max_element() <= 1.0 {
                for jj in j..j + step {
                    for ii in i..i + step {
                        f(ii, jj);
                    }
                }
            }
            i += step;
        }
        j += step;
    }
}

/// The *visible region* of object `object`'s image: every texel of level 0 that some pixel of
/// the field reads through [`texels_read`]. `None` when the object reads no image.
#[must_use]
pub fn visible_region(scene: &Scene, field: &UvField, object: usize) -> Option<TexelMask> {
    let texture = object_image(scene, object)?;
    let (w, h) = (texture.image.width(), texture.image.height());
    let pool = thread_pool(0).ok();
    let run = || {
        field
            .pixels
            .par_chunks(field.width.max(1) as usize)
            // One mask per worker or two, not per row: a mask is as big as the image.
            .with_min_len((field.height as usize / (2 * rayon::current_num_threads())).max(1))
            .fold(
                || TexelMask::new(w, h),
                |mut mask, row| {
                    for p in row.iter().flatten().filter(|p| p.object == object) {
                        texels_read(texture, &p.tex, |c, r| mask.insert(c, r));
                    }
                    mask
                },
            )
            .reduce(
                || TexelMask::new(w, h),
                |mut a, b| {
                    a.union_with(&b);
                    a
                },
            )
    };
    Some(match pool {
        Some(p) => p.install(run),
        None => run(),
    })
}

/// The *reverse lookup*: the pixels of the field whose lookup on object `object`'s image reads
/// a texel of `chosen` (through [`texels_read`], so under the texture's current filter). Empty
/// when the object reads no image.
#[must_use]
pub fn pixels_reading(
    scene: &Scene,
    field: &UvField,
    object: usize,
    chosen: &TexelMask,
) -> PixelMask {
    let mut bits = vec![false; field.pixels.len()];
    if let Some(texture) = object_image(scene, object)
        && texture.image.width() == chosen.width
        && texture.image.height() == chosen.height
        && !chosen.is_empty()
    {
        let run = |bits: &mut [bool]| {
            bits.par_iter_mut()
                .zip(field.pixels.par_iter())
                .for_each(|(bit, p)| {
                    if let Some(p) = p.as_ref().filter(|p| p.object == object) {
                        texels_read(texture, &p.tex, |c, r| *bit |= chosen.contains(c, r));
                    }
                });
        };
        match thread_pool(0) {
            Ok(pool) => pool.install(|| run(&mut bits)),
            Err(_) => run(&mut bits),
        }
    }
    PixelMask {
        width: field.width,
        height: field.height,
        bits,
    }
}

/// Iso-line flags of a pixel: a line of constant u crosses it.
pub const ISO_U: u8 = 1;
/// A line of constant v crosses the pixel.
pub const ISO_V: u8 = 2;
/// The seam of a periodic mapping (u jumps from 1 back to 0) crosses the pixel.
pub const ISO_SEAM: u8 = 4;
/// The pixel holds a pole of the spherical map (v reaches 0 or 1 inside it).
pub const ISO_POLE: u8 = 8;

/// A label on an iso-line: which line, and a pixel on it.
#[derive(Clone, Debug, PartialEq)]
pub struct IsoLabel {
    /// The pixel the label sits at (film pixels from the top-left corner).
    pub pixel: (u32, u32),
    /// `true` for a line of constant u, `false` for v.
    pub is_u: bool,
    /// The line is at k / divisions.
    pub k: u32,
    /// What to write: "u = 3/8".
    pub text: String,
}

/// Lines of constant u and v over the image, every 1 / `divisions`, with the seam and the
/// poles.
#[derive(Clone, Debug)]
pub struct IsoLines {
    /// Film width in pixels.
    pub width: u32,
    /// Film height in pixels.
    pub height: u32,
    /// Lines at k / `divisions`.
    pub divisions: u32,
    /// One set of `ISO_*` flags per pixel, row by row from the top.
    pub flags: Vec<u8>,
    /// One label per line that shows, near the middle of its run of pixels.
    pub labels: Vec<IsoLabel>,
    /// The pixels on the seam, for a drawing that is seen from afar (a line one film pixel wide
    /// is not).
    pub seam: Vec<(u32, u32)>,
    /// Where each pole shows: of the pixels flagged for it, the centre of the one whose v is
    /// nearest the pole's (film pixels from the top-left corner), one per object and pole.
    pub poles: Vec<(f32, f32)>,
}

impl IsoLines {
    /// The flags of pixel (x, y).
    #[must_use]
    pub fn at(&self, x: u32, y: u32) -> u8 {
        if x >= self.width || y >= self.height {
            return 0;
        }
        self.flags[(y * self.width + x) as usize]
    }
}

/// Where lines of constant u and v, at k / `divisions`, cross the image: a pixel is marked when
/// u (or v) at its centre and at its right or lower neighbour's centre, on the same object, lie
/// on either side of some k / `divisions`. Where a periodic mapping's u jumps by more than one
/// half between neighbours, the pixel is on the seam instead. Under the spherical map, a pixel
/// holds a pole when v is within its footprint of 0 or 1.
#[must_use]
pub fn iso_lines(field: &UvField, divisions: u32) -> IsoLines {
    let n = divisions.max(1) as f32;
    let (w, h) = (field.width, field.height);
    let mut flags = vec![0_u8; field.pixels.len()];
    // (is_u, k) -> the pixels on that line.
    let mut runs: BTreeMap<(bool, u32), Vec<(u32, u32)>> = BTreeMap::default();
    let mut seam = Vec::new();
    // (object, north) -> the pixel nearest the pole so far, and its distance to it in v.
    let mut poles: BTreeMap<(usize, bool), (f32, u32, u32)> = BTreeMap::default();
    for y in 0..h {
        for x in 0..w {
            let Some(p) = field.at(x, y) else { continue };
            let mapping = field.mappings.get(p.object).and_then(Option::as_ref);
            // A formula's u may wrap with fract: a jump of more than half is its seam too.
            let periodic = mapping.is_some_and(|m| m.u_is_periodic() || m.builtin().is_none());
            let mut f = 0;
            for (nx, ny) in [(x + 1, y), (x, y + 1)] {
                let Some(q) = field.at(nx, ny).filter(|q| q.object == p.object) else {
                    continue;
                };
                let (a, b) = (p.tex.uv, q.tex.uv);
                if periodic && (a.x - b.x).abs() > 0.5 {
                    f |= ISO_SEAM;
                } else if let Some(k) = crossing(a.x, b.x, n) {
                    f |= ISO_U;
                    runs.entry((true, k)).or_default().push((x, y));
                }
                if let Some(k) = crossing(a.y, b.y, n) {
                    f |= ISO_V;
                    runs.entry((false, k)).or_default().push((x, y));
                }
            }
            if mapping.is_some_and(AnyMapping::v_clamps) {
                // The footprint's reach in v, or (without ray differentials: nearest and
                // bilinear lookups) the step in v to the neighbouring pixels, so a pole between
                // pixel centres still marks the pixel nearest it.
                let step = [
                    (x.wrapping_sub(1), y),
                    (x + 1, y),
                    (x, y.wrapping_sub(1)),
                    (x, y + 1),
                ]
                .into_iter()
                .filter_map(|(nx, ny)| field.at(nx, ny).filter(|q| q.object == p.object))
                .map(|q| (q.tex.uv.y - p.tex.uv.y).abs())
                .fold(0.0_f32, f32::max);
                let dv = (p.tex.duvdx.y.abs().max(p.tex.duvdy.y.abs()) * 0.5).max(step);
                if p.tex.uv.y + dv >= 1.0 || p.tex.uv.y - dv <= 0.0 {
                    f |= ISO_POLE;
                    let north = p.tex.uv.y > 0.5;
                    let off = if north { 1.0 - p.tex.uv.y } else { p.tex.uv.y };
                    let e = poles.entry((p.object, north)).or_insert((off, x, y));
                    if off < e.0 {
                        *e = (off, x, y);
                    }
                }
            }
            if f & ISO_SEAM != 0 {
                seam.push((x, y));
            }
            flags[(y * w + x) as usize] = f;
        }
    }
    let labels = runs
        .into_iter()
        .map(|((is_u, k), pixels)| IsoLabel {
            pixel: pixels[pixels.len() / 2],
            is_u,
            k,
            text: format!(
                "{} = {}",
                if is_u { "u" } else { "v" },
                fraction(k, divisions)
            ),
        })
        .collect();
    IsoLines {
        width: w,
        height: h,
        divisions,
        flags,
        labels,
        seam,
        poles: poles
            .into_values()
            .map(|(_, x, y)| (x as f32 + 0.5, y as f32 + 0.5))
            .collect(),
    }
}

/// The line k / n crossed going from `a` to `b` (the one nearer `a` when several are), if any.
fn crossing(a: f32, b: f32, n: f32) -> Option<u32> {
    let (ka, kb) = ((a * n).floor(), (b * n).floor());
    if !(ka.is_finite() && kb.is_finite()) || ka == kb {
        return None;
    }
    // Lines are at the larger cell's lower edge: k = max(ka, kb) when adjacent.
    let k = if kb > ka { ka + 1.0 } else { ka };
    Some(k.rem_euclid(n) as u32)
}

/// k / n in lowest terms ("1/2", "3/8", "0", "1").
fn fraction(k: u32, n: u32) -> String {
    if k == 0 {
        return "0".into();
    }
    let (mut a, mut b) = (k, n);
    while b != 0 {
        (a, b) = (b, a % b);
    }
    if k == n {
        "1".into()
    } else {
        format!("{}/{}", k / a, n / a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossings_name_the_line_between_two_values() {
        assert_eq!(crossing(0.10, 0.13, 8.0), Some(1));
        assert_eq!(crossing(0.13, 0.10, 8.0), Some(1));
        assert_eq!(crossing(0.10, 0.11, 8.0), None);
        assert_eq!(crossing(0.99, 1.01, 8.0), Some(0));
        assert_eq!(fraction(4, 8), "1/2");
        assert_eq!(fraction(3, 8), "3/8");
        assert_eq!(fraction(0, 8), "0");
    }

    #[test]
    fn a_footprint_covers_the_texels_inside_its_parallelogram() {
        // 10 texels along u, 2 along v, centred on texel (50, 50)'s centre.
        let tex = TexCoord {
            uv: Vec2::new(50.5, 50.5) / 100.0,
            duvdx: Vec2::new(0.1, 0.0),
            duvdy: Vec2::new(0.0, 0.02),
        };
        let mut seen = Vec::new();
        footprint_texels(&tex, 100, 100, &mut |i, j| seen.push((i, j)));
        assert!(seen.contains(&(50, 50)) && seen.contains(&(45, 50)) && seen.contains(&(55, 50)));
        assert!(!seen.contains(&(57, 50)) && !seen.contains(&(50, 53)));
        // Columns 45 to 55 (centres 45.5 to 55.5), rows 49 to 51.
        assert_eq!(seen.len(), 11 * 3);
    }
}
