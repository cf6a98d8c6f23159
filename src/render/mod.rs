//! The progressive renderer: a film of running sums, passes over row tiles on rayon, a coarse
//! preview first, and a job any viewer can poll and cancel.

mod adaptive;
mod film;
mod job;
mod pool;
mod rows;
// The page's renderer; natively only its tests (they compare it with the threaded one).
#[cfg(any(target_arch = "wasm32", test))]
mod slices;
mod task;

pub use crate::scene::SimdMode;
pub use adaptive::{CONTRAST_FACTOR, adaptive_mask, display_luminance};
pub use film::{DisplayImage, Film, encode_srgb8};
pub use job::{Generation, Progress, RenderJob, RenderOptions};
pub use rows::{kernel_width, simd_level};

/// Pixels whose sample positions are made together, lane-wise where the sampler allows.
pub const LANES: usize = rows::CHUNK;
pub use pool::{MAX_THREADS, PoolError, thread_pool};
pub use task::Task;

#[cfg(target_arch = "wasm32")]
pub use slices::{
    Port as WorkerPort, Worker, add_worker, describe as describe_scene, run_slices, worker_errors,
    worker_lost, worker_memory, worker_message,
};

use crate::math::{Ray, RayDifferential, Rgb, Vec2, hash3};
use crate::sampler::{PixelFilter, permute};
use crate::scene::{RenderSettings, Scene};
use rayon::prelude::*;

/// Rows per tile: a tile is the unit of parallel work and of cancellation. 8 rows of an 800-pixel
/// image keep a tile's texels and film in cache and give rayon enough tiles to balance.
pub const TILE_ROWS: usize = 8;

/// The block sizes of the preview passes, coarse to fine: one ray per block.
pub const PREVIEW_BLOCKS: [u32; 3] = [8, 4, 2];

/// Why a pass stopped early.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cancelled;

/// Texture footprints never shrink below this fraction of a pixel, however many samples a pixel
/// takes (pbrt-v4's clamp): tiny footprints only cost texture cache misses.
pub const MIN_FOOTPRINT_SCALE: f32 = 0.125;

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
    render_pass_masked(scene, film, sample, None, cancelled)
}

/// The film position (pixels) of sample `k` of pixel (x, y): the sampler's point warped by the
/// pixel filter. Samples below `spp` form the sampler's set of `spp`; adaptive samples past it
/// come from a second set of `max_spp - spp` taken in a per-pixel shuffled order, so a pixel that
/// stops early still has an unbiased share of it. Depends only on (seed, pixel, k).
#[must_use]
#[inline]
pub fn sample_position(s: &RenderSettings, x: u32, y: u32, k: u32) -> Vec2 {
    sample_position_impl::<false>(s, x, y, k).0
}

/// [`sample_position`] and the size (pixels along x and y) of the part of the pixel the sample
/// stands for ([`crate::sampler::PixelSampler::cell_size`] in its set): the texture footprint
/// of the sample, so that the footprints of a stratified set tile the pixel for any count.
#[must_use]
#[inline]
pub fn sample_position_and_cell(s: &RenderSettings, x: u32, y: u32, k: u32) -> (Vec2, Vec2) {
    sample_position_impl::<true>(s, x, y, k)
}

/// [`sample_position_and_cell`], with the cell only when `CELL` (zero otherwise).
#[inline(always)]
fn sample_position_impl<const CELL: bool>(
    s: &RenderSettings,
    x: u32,
    y: u32,
    k: u32,
) -> (Vec2, Vec2) {
    let pixel = y * s.width + x;
    let cell_of = |j: u32, n: u32| {
        if CELL {
            s.sampler.cell_size(j, n)
        } else {
            Vec2::ZERO
        }
    };
    let (offset, cell) = if k < s.spp {
        (s.sampler.sample(s.seed, pixel, k, s.spp), cell_of(k, s.spp))
    } else {
        let (j, n) = second_set_index(s, pixel, k);
        (
            s.sampler.sample(s.seed ^ ADAPTIVE_STREAM, pixel, j, n),
            cell_of(j, n),
        )
    };
    let corner = Vec2::new(x as f32, y as f32);
    let pos = match s.pixel_filter {
        // Kept as the corner plus the offset, bit for bit the box sampling of earlier versions.
        PixelFilter::Box => corner + offset,
        f => corner + Vec2::splat(0.5) + f.warp(offset),
    };
    (pos, cell)
}

/// Sample `k` (at least `spp`) of pixel number `pixel` as sample `j` of the second set of `n`,
/// shuffled per pixel.
#[inline]
fn second_set_index(s: &RenderSettings, pixel: u32, k: u32) -> (u32, u32) {
    let n = s.max_spp().saturating_sub(s.spp).max(1);
    let j = permute((k - s.spp) % n, n, hash3(s.seed, pixel, ADAPTIVE_STREAM));
    (j, n)
}

/// The cell of sample `k` (as [`sample_position_and_cell`] gives it) when it is the same for
/// every pixel: in the first set, and in a second set of one sample; `None` when the second
/// set is shuffled per pixel.
#[must_use]
#[inline]
pub fn uniform_cell(s: &RenderSettings, k: u32) -> Option<Vec2> {
    if k < s.spp {
        Some(s.sampler.cell_size(k, s.spp))
    } else if s.max_spp().saturating_sub(s.spp) <= 1 {
        Some(s.sampler.cell_size(0, 1))
    } else {
        None
    }
}

/// The cell of sample `k` of pixel (x, y), as [`sample_position_and_cell`] gives it, without the
/// position.
#[must_use]
#[inline]
pub fn sample_cell(s: &RenderSettings, x: u32, y: u32, k: u32) -> Vec2 {
    if k < s.spp {
        return s.sampler.cell_size(k, s.spp);
    }
    let (j, n) = second_set_index(s, y * s.width + x, k);
    s.sampler.cell_size(j, n)
}

/// Seeds the second sample set of adaptive passes apart from the first.
const ADAPTIVE_STREAM: u32 = 0xada9_7e55;

/// Like [`render_pass`], but only for pixels where `mask` is true (all when `None`). When the
/// scene renders adaptively, each sample's display luminance also goes into the film's
/// statistics. Rays run through the render kernel at the width
/// [`RenderSettings::simd`](crate::scene::RenderSettings::simd) picks.
///
/// # Errors
/// [`Cancelled`] if `cancelled` returned true.
pub fn render_pass_masked(
    scene: &Scene,
    film: &mut Film,
    sample: u32,
    mask: Option<&[bool]>,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Result<(), Cancelled> {
    render_pass_with(scene, film, sample, mask, scene.settings.simd, cancelled)
}

/// [`render_pass_masked`] with the path chosen by `mode`: [`SimdMode::Scalar`] forces the
/// kernel one ray a packet, [`SimdMode::Auto`] at the CPU's SIMD width ([`kernel_width`]): the
/// same code, so the same film bit for bit.
///
/// # Errors
/// [`Cancelled`] if `cancelled` returned true.
pub fn render_pass_with(
    scene: &Scene,
    film: &mut Film,
    sample: u32,
    mask: Option<&[bool]>,
    mode: SimdMode,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Result<(), Cancelled> {
    let tiles = 0..tile_count(film.height());
    render_tiles_with(scene, film, sample, mask, mode, tiles, cancelled)
}

/// The tiles of a film `height` rows high ([`TILE_ROWS`] rows each, the last one shorter).
#[must_use]
pub const fn tile_count(height: u32) -> usize {
    (height as usize).div_ceil(TILE_ROWS)
}

/// [`render_pass_with`] over the tiles `tiles` only (tile t holds rows t * [`TILE_ROWS`] ..):
/// a pass cut into slices, which the page renders between frames (it has no threads). Each
/// tile's pixels depend on nothing but the tile, so a pass rendered in slices is the pass
/// rendered at once, bit for bit.
///
/// # Errors
/// [`Cancelled`] if `cancelled` returned true.
pub fn render_tiles_with(
    scene: &Scene,
    film: &mut Film,
    sample: u32,
    mask: Option<&[bool]>,
    mode: SimdMode,
    tiles: std::ops::Range<usize>,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Result<(), Cancelled> {
    let s = &scene.settings;
    let width = film.width() as usize;
    let stats_on = s.adaptive.is_some();
    let rows = width * TILE_ROWS;
    let (sums, stats, keys) = film.buffers_mut();
    let end = (tiles.end * rows).min(sums.len());
    let start = (tiles.start * rows).min(end);
    let result: Result<(), Cancelled> = sums[start..end]
        .par_chunks_mut(rows)
        .zip(stats[start..end].par_chunks_mut(rows))
        .zip(keys[start..end].par_chunks_mut(rows))
        .enumerate()
        .try_for_each(|(i, ((chunk, stat), key))| {
            if cancelled() {
                return Err(Cancelled);
            }
            let y0 = (tiles.start + i) * TILE_ROWS;
            // Row by row: no integer division per pixel to find its coordinates.
            let rows_here = chunk
                .chunks_mut(width)
                .zip(stat.chunks_mut(width))
                .zip(key.chunks_mut(width));
            for (r, ((row_px, row_st), row_k)) in rows_here.enumerate() {
                let y = y0 + r;
                let row_mask = mask.map(|m| &m[y * width..(y + 1) * width]);
                let mut row = Row {
                    px: row_px,
                    st: row_st,
                    keys: row_k,
                    stats_on,
                    exposure: s.exposure_scale,
                };
                rows::render_row(scene, &mut row, y as u32, sample, row_mask, mode);
            }
            Ok(())
        });
    result
}

/// One row of a tile's film: running sums, adaptive statistics and edge keys.
struct Row<'a> {
    px: &'a mut [[f32; 4]],
    st: &'a mut [[f32; 2]],
    keys: &'a mut [u32],
    stats_on: bool,
    exposure: f32,
}

impl Row<'_> {
    /// [`Row::add`] of the radiance (r, g, b).
    #[inline(always)]
    fn add_parts(&mut self, x: usize, r: f32, g: f32, b: f32, edge_key: u32) {
        let px = &mut self.px[x];
        if self.stats_on {
            if px[3] == 0.0 {
                self.keys[x] = edge_key;
            }
            let e = display_luminance(Rgb(r, g, b), self.exposure);
            let st = &mut self.st[x];
            st[0] += e;
            st[1] += e * e;
        }
        px[0] += r;
        px[1] += g;
        px[2] += b;
        px[3] += 1.0;
    }
}

/// [`sample_position`] of sample `k` for the [`LANES`] pixels from (`x0`, `y`) along the row,
/// lane-wise ([`crate::sampler::PixelSampler::sample_lanes`]): the same positions bit for bit,
/// for the box pixel filter where the sampler has a lane-wise form (the first `spp` samples, and
/// those past it when the second set has one sample); `None` otherwise. Lanes past the row's end get positions nobody reads.
#[inline(always)]
fn sample_positions_lanes(
    s: &RenderSettings,
    x0: u32,
    y: u32,
    k: u32,
) -> Option<([f32; LANES], [f32; LANES])> {
    if s.pixel_filter != PixelFilter::Box {
        return None;
    }
    // Past `spp`, the second set's sample `j` of `n`; with a set of one (`n` = 1, as for every
    // pass past the first of a scene without adaptive sampling, `texplore bench`'s) `permute`
    // gives j = 0 whatever its hash. Larger sets take the scalar `permute` per lane.
    let (seed, index, count) = if k < s.spp {
        (s.seed, k, s.spp)
    } else if s.max_spp().saturating_sub(s.spp) <= 1 {
        (s.seed ^ ADAPTIVE_STREAM, 0, 1)
    } else {
        return None;
    };
    let first = y.wrapping_mul(s.width).wrapping_add(x0);
    let mut pixels = [0_u32; LANES];
    for (i, p) in pixels.iter_mut().enumerate() {
        *p = first.wrapping_add(i as u32);
    }
    let (mut px, mut py) = s.sampler.sample_lanes(seed, &pixels, index, count)?;
    let row = y as f32;
    for i in 0..LANES {
        // The corner plus the offset, as `sample_position_impl` adds them.
        px[i] += (x0 + i as u32) as f32;
        py[i] += row;
    }
    Some((px, py))
}

/// Runs pass `pass` of the scene's schedule: passes below `spp` sample every pixel; with
/// adaptive sampling, later passes (up to `max_spp`) sample only the pixels
/// [`adaptive_mask`] selects. Returns how many pixels were sampled: 0 means the render is
/// complete (every pass done, or every pixel converged).
///
/// # Errors
/// [`Cancelled`] if `cancelled` returned true.
pub fn render_scheduled_pass(
    scene: &Scene,
    film: &mut Film,
    pass: u32,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Result<usize, Cancelled> {
    render_scheduled_pass_with(scene, film, pass, scene.settings.simd, cancelled)
}

/// [`render_scheduled_pass`] with the path chosen by `mode` (see [`render_pass_with`]).
///
/// # Errors
/// [`Cancelled`] if `cancelled` returned true.
pub fn render_scheduled_pass_with(
    scene: &Scene,
    film: &mut Film,
    pass: u32,
    mode: SimdMode,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Result<usize, Cancelled> {
    match pass_pixels(scene, film, pass) {
        PassPixels::All => {
            render_pass_with(scene, film, pass, None, mode, cancelled)?;
            Ok(film.pixels().len())
        }
        PassPixels::Masked(mask, n) => {
            render_pass_with(scene, film, pass, Some(&mask), mode, cancelled)?;
            Ok(n)
        }
        PassPixels::None => Ok(0),
    }
}

/// The pixels a scheduled pass samples.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PassPixels {
    /// Every pixel: the first `spp` passes.
    All,
    /// The adaptive mask's pixels (true: sample it), and how many there are (at least one).
    Masked(Vec<bool>, usize),
    /// None: the render is done (past `max_spp`, or every pixel has converged).
    None,
}

/// Which pixels [`render_scheduled_pass`] samples in pass `pass` of `film`: all of them in the
/// first `spp` passes, then (adaptive rendering) those [`adaptive_mask`] picks from the film.
#[must_use]
pub fn pass_pixels(scene: &Scene, film: &Film, pass: u32) -> PassPixels {
    let s = &scene.settings;
    if pass < s.spp {
        return PassPixels::All;
    }
    let Some(a) = s.adaptive.filter(|_| pass < s.max_spp()) else {
        return PassPixels::None;
    };
    let mask = adaptive_mask(film, &a);
    match mask.iter().filter(|m| **m).count() {
        0 => PassPixels::None,
        n => PassPixels::Masked(mask, n),
    }
}

/// Radiance through film position `pos` (pixels), with ray differentials for samples spaced
/// `spacing` pixels apart when the scene needs them: the texture footprint is `spacing` pixels
/// wide (at least [`MIN_FOOTPRINT_SCALE`]).
#[must_use]
#[inline]
pub fn radiance(scene: &Scene, pos: Vec2, spacing: f32) -> Rgb {
    radiance_keyed(scene, pos, spacing).0
}

/// [`radiance`] with the hit's edge key (see [`Scene::trace_keyed`]).
#[must_use]
#[inline]
pub fn radiance_keyed(scene: &Scene, pos: Vec2, spacing: f32) -> (Rgb, u32) {
    radiance_keyed_cell(scene, pos, Vec2::splat(spacing))
}

/// [`radiance_keyed`] for a sample standing for a `cell` (pixels along x and y) of its pixel:
/// the texture footprint is `cell.x` pixels wide and `cell.y` high (each at least
/// [`MIN_FOOTPRINT_SCALE`]); a square cell is exactly [`radiance_keyed`] with that spacing.
#[must_use]
#[inline]
pub fn radiance_keyed_cell(scene: &Scene, pos: Vec2, cell: Vec2) -> (Rgb, u32) {
    // Without a footprint filter only the main ray is needed (saves two camera directions).
    if !scene.needs_differentials() {
        return scene
            .camera
            .primary_ray(pos)
            .map_or((Rgb::BLACK, 0), |ray| scene.trace_keyed(&ray, None));
    }
    match footprint_ray(scene, pos, cell) {
        Some((ray, diff)) => scene.trace_keyed(&ray, Some(&diff)),
        None => (Rgb::BLACK, 0),
    }
}

/// The camera ray through film position `pos` with its ray differentials for a sample standing
/// for a `cell` of its pixel (pixels along x and y, each at least [`MIN_FOOTPRINT_SCALE`]):
/// the neighbours' rays `cell.x` pixels right and `cell.y` pixels down. `None` where the
/// camera has no ray. Every width of the kernel takes its footprints from here.
#[must_use]
#[inline]
pub fn footprint_ray(scene: &Scene, pos: Vec2, cell: Vec2) -> Option<(Ray, RayDifferential)> {
    let r = scene.camera.footprint_rays_lanes(
        pulp::Scalar,
        pos.x,
        pos.y,
        cell.x,
        cell.y,
        MIN_FOOTPRINT_SCALE,
    );
    r.seen.then(|| {
        (
            Ray::new(r.o.vec(), r.d.vec()),
            RayDifferential {
                rx_origin: r.rx_origin.vec(),
                rx_dir: r.rx_dir.vec(),
                ry_origin: r.ry_origin.vec(),
                ry_dir: r.ry_dir.vec(),
            },
        )
    })
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
    let mut out = Vec::new();
    render_preview_into(scene, block, &mut out, cancelled).map(|()| out)
}

/// [`render_preview`] into `out`, reusing its allocation (a benchmark's repeated previews then
/// measure tracing, not the kernel clearing fresh pages).
///
/// # Errors
/// [`Cancelled`] if `cancelled` returned true; `out` then holds a partial preview.
pub fn render_preview_into(
    scene: &Scene,
    block: u32,
    out: &mut Vec<Rgb>,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Result<(), Cancelled> {
    let (w, h) = (
        scene.settings.width as usize,
        scene.settings.height as usize,
    );
    let b = block.max(1) as usize;
    out.clear();
    out.resize(w * h, Rgb::BLACK);
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
    result
}

/// Renders `scene` to completion on the current rayon pool: every pass (adaptive ones too), no
/// preview. `on_pass` is told the number of passes done after each (for progress bars; the
/// most there can be is [`RenderSettings::max_spp`]).
#[must_use]
pub fn render_blocking(scene: &Scene, on_pass: impl FnMut(u32)) -> Film {
    render_blocking_with(scene, scene.settings.simd, on_pass)
}

/// [`render_blocking`] with the path chosen by `mode` (see [`render_pass_with`]).
#[must_use]
pub fn render_blocking_with(scene: &Scene, mode: SimdMode, mut on_pass: impl FnMut(u32)) -> Film {
    let s = &scene.settings;
    let mut film = Film::new(s.width, s.height);
    let never = || false;
    for pass in 0..s.max_spp() {
        // Cannot be cancelled: `never` is always false.
        match render_scheduled_pass_with(scene, &mut film, pass, mode, &never) {
            Ok(0) | Err(Cancelled) => break,
            Ok(_) => on_pass(pass + 1),
        }
    }
    film
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::PixelSampler;
    use crate::scene::{AdaptiveDesc, AssetCache, build_scene, parse_preset};
    use std::path::Path;

    fn scene(adaptive: bool) -> Scene {
        let text = r"(
            version: 1,
            camera: (eye: (0, 0, 4)),
            render: (width: 24, height: 16, spp: 1, background: (0.2, 0.3, 0.4)),
            lights: [Directional(direction: (1, 1, 1))],
            objects: [(shape: Sphere, material: Matte(cd: Checker(mapping: Spherical, filter: Ewa)))],
        )";
        let mut desc = parse_preset(text, Path::new("test.ron")).unwrap();
        if adaptive {
            desc.render.adaptive = Some(AdaptiveDesc {
                max_spp: 9,
                threshold: 0.01,
            });
        }
        build_scene(&desc, Path::new("test.ron"), &mut AssetCache::new()).unwrap()
    }

    #[test]
    fn adaptive_samples_past_spp_form_a_whole_stratified_set() {
        // spp 1, max 17: the 16 extra samples of a pixel are the jittered set of 16 in a
        // shuffled order, one per cell of a 4 x 4 grid.
        let mut s = scene(false).settings;
        s.sampler = PixelSampler::Jittered;
        s.adaptive = Some(AdaptiveDesc {
            max_spp: 17,
            threshold: 0.01,
        });
        let mut seen = [false; 16];
        for k in 1..17 {
            let p = sample_position(&s, 5, 7, k) - Vec2::new(5.0, 7.0);
            let cell = (p.y * 4.0) as usize * 4 + (p.x * 4.0) as usize;
            assert!(!seen[cell], "sample {k} lands in a taken cell");
            seen[cell] = true;
        }
        // The order is shuffled per pixel, not the same for every pixel.
        assert_ne!(
            sample_position(&s, 5, 7, 1) - Vec2::new(5.0, 7.0),
            sample_position(&s, 6, 7, 1) - Vec2::new(6.0, 7.0)
        );
    }

    #[test]
    fn progressive_job_and_blocking_render_give_the_same_adaptive_film() {
        let sc = scene(true);
        let blocking = render_blocking(&sc, |_| {});
        // Some pixels were refined, others were not.
        let counts: Vec<f32> = blocking.pixels().iter().map(|p| p[3]).collect();
        assert!(counts.contains(&1.0) && counts.iter().any(|&c| c > 1.0));
        let job = RenderJob::start(
            std::sync::Arc::new(sc),
            RenderOptions {
                threads: 2,
                preview: true,
            },
            &Generation::new(),
        )
        .expect("a pool of 2 workers");
        let film = job.film_when_done();
        assert!(film.as_deref() == Some(&blocking));
    }

    #[test]
    fn a_dropped_job_stops_without_blocking_and_a_new_one_runs_on_the_same_pool() {
        let mut sc = scene(false);
        sc.settings.spp = 100_000;
        let generation = Generation::new();
        let options = RenderOptions {
            threads: 2,
            preview: false,
        };
        let sc = std::sync::Arc::new(sc);
        let long = RenderJob::start(sc.clone(), options, &generation).expect("a pool");
        while long.progress().spp_done == 0 {
            std::thread::yield_now();
        }
        let t0 = std::time::Instant::now();
        drop(long);
        assert!(t0.elapsed() < std::time::Duration::from_millis(50));
        // The cancelled task frees the pool within a tile: a short job after it finishes.
        let mut short = (*sc).clone();
        short.settings.spp = 2;
        let job = RenderJob::start(std::sync::Arc::new(short), options, &generation).unwrap();
        let p = job.wait();
        assert!(p.finished && !p.cancelled);
        assert_eq!(p.spp_done, 2);
    }

    #[test]
    fn a_job_that_cannot_have_its_threads_is_an_error_not_a_hang() {
        let e = RenderJob::start(
            std::sync::Arc::new(scene(false)),
            RenderOptions {
                threads: MAX_THREADS + 1,
                preview: true,
            },
            &Generation::new(),
        )
        .err()
        .expect("refused");
        assert!(e.to_string().contains("at most 1024"), "{e}");
    }
}
