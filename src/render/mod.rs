//! The progressive renderer: a film of running sums, passes over row tiles on rayon, a coarse
//! preview first, and a job any viewer can poll and cancel.

mod film;
mod job;

pub use film::{DisplayImage, Film, encode_srgb8};
pub use job::{Generation, Progress, RenderJob, RenderOptions};

use crate::math::{Rgb, Vec2};
use crate::scene::Scene;
use rayon::prelude::*;

/// Rows per tile: a tile is the unit of parallel work and of cancellation. 8 rows of an 800-pixel
/// image keep a tile's texels and film in cache and give rayon enough tiles to balance.
pub const TILE_ROWS: usize = 8;

/// The block sizes of the preview passes, coarse to fine: one ray per block.
pub const PREVIEW_BLOCKS: [u32; 3] = [8, 4, 2];

/// Why a pass stopped early.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cancelled;

/// Renders full-resolution sample `sample` of every pixel into `film` (one sample per pixel),
/// checking `cancelled` before each tile.
///
/// # Errors
/// [`Cancelled`] if `cancelled` returned true; the film then holds a partial pass and should be
/// discarded.
pub fn render_pass(
    scene: &Scene,
    film: &mut Film,
    sample: u32,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Result<(), Cancelled> {
    let s = &scene.settings;
    let width = film.width() as usize;
    let spacing = 1.0 / (s.spp as f32).sqrt();
    let result: Result<(), Cancelled> = film
        .pixels_mut()
        .par_chunks_mut(width * TILE_ROWS)
        .enumerate()
        .try_for_each(|(tile, chunk)| {
            if cancelled() {
                return Err(Cancelled);
            }
            let y0 = tile * TILE_ROWS;
            for (i, px) in chunk.iter_mut().enumerate() {
                let (x, y) = (i % width, y0 + i / width);
                let pixel = (y * width + x) as u32;
                let offset = s.sampler.sample(s.seed, pixel, sample, s.spp);
                let pos = Vec2::new(x as f32, y as f32) + offset;
                let l = radiance(scene, pos, spacing);
                debug_assert!(l.is_finite(), "non-finite radiance at pixel ({x}, {y})");
                px[0] += l.0;
                px[1] += l.1;
                px[2] += l.2;
                px[3] += 1.0;
            }
            Ok(())
        });
    result
}

/// Radiance through film position `pos` (pixels), with ray differentials for samples spaced
/// `spacing` pixels apart when the scene needs them.
#[must_use]
#[inline]
pub fn radiance(scene: &Scene, pos: Vec2, spacing: f32) -> Rgb {
    // Without a footprint filter only the main ray is needed (saves two camera directions).
    if !scene.needs_differentials {
        return scene
            .camera
            .primary_ray(pos)
            .map_or(Rgb::BLACK, |ray| scene.trace(&ray, None));
    }
    match scene.camera.ray(pos, spacing) {
        Some((ray, diff)) => scene.trace(&ray, Some(&diff)),
        None => Rgb::BLACK,
    }
}

/// A preview at one ray per `block` x `block` pixels, drawn as blocks: linear RGB, row-major.
///
/// # Errors
/// [`Cancelled`] if `cancelled` returned true.
pub fn render_preview(
    scene: &Scene,
    block: u32,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Result<Vec<Rgb>, Cancelled> {
    let (w, h) = (
        scene.settings.width as usize,
        scene.settings.height as usize,
    );
    let b = block.max(1) as usize;
    let mut out = vec![Rgb::BLACK; w * h];
    let band = w * b;
    let result: Result<(), Cancelled> =
        out.par_chunks_mut(band)
            .enumerate()
            .try_for_each(|(by, rows)| {
                if cancelled() {
                    return Err(Cancelled);
                }
                let y0 = by * b;
                let rows_here = rows.len() / w;
                for bx in (0..w).step_by(b) {
                    let cx = (bx + b / 2).min(w - 1);
                    let cy = (y0 + b / 2).min(h - 1);
                    let l = radiance(scene, Vec2::new(cx as f32 + 0.5, cy as f32 + 0.5), b as f32);
                    for r in 0..rows_here {
                        for x in bx..(bx + b).min(w) {
                            rows[r * w + x] = l;
                        }
                    }
                }
                Ok(())
            });
    result.map(|()| out)
}

/// Renders `scene` to completion on the current rayon pool: every pass, no preview.
/// `on_pass` is told after each pass (for progress bars).
#[must_use]
pub fn render_blocking(scene: &Scene, mut on_pass: impl FnMut(u32)) -> Film {
    let s = &scene.settings;
    let mut film = Film::new(s.width, s.height);
    for sample in 0..s.spp {
        let never = || false;
        // Cannot be cancelled: `never` is always false.
        let _ = render_pass(scene, &mut film, sample, &never);
        on_pass(sample + 1);
    }
    film
}
