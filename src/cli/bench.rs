//! `texplore bench`: full-pass and preview timings per thread count.

use crate::render::{Film, PREVIEW_BLOCKS, render_pass, render_preview};
use crate::scene::{AssetCache, Overrides, apply_overrides, build_scene, read_preset_or_png};
use anyhow::Result;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// `texplore bench`.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// The preset.
    pub preset: PathBuf,
    /// Image width.
    #[arg(long, default_value_t = 800)]
    pub width: u32,
    /// Image height.
    #[arg(long, default_value_t = 800)]
    pub height: u32,
    /// Thread counts to measure.
    #[arg(long, value_delimiter = ',', default_values_t = [1, 2])]
    pub threads: Vec<usize>,
    /// Timed passes per thread count (after one warm-up); the median is reported.
    #[arg(long, default_value_t = 9)]
    pub repeat: usize,
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

pub fn run(a: &BenchArgs) -> Result<()> {
    let mut desc = read_preset_or_png(&a.preset)?;
    apply_overrides(
        &mut desc,
        Overrides {
            width: Some(a.width),
            height: Some(a.height),
            spp: Some(1),
            ..Overrides::default()
        },
    );
    let scene = build_scene(&desc, &a.preset, &mut AssetCache::new())?;
    let rays = f64::from(a.width) * f64::from(a.height);
    println!(
        "{} at {}x{}, 1 spp, median of {} passes after a warm-up",
        a.preset.display(),
        a.width,
        a.height,
        a.repeat.max(1)
    );
    let mut base = None;
    for &threads in &a.threads {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()?;
        let never = || false;
        let (passes, previews) = pool.install(|| {
            let mut film = Film::new(a.width, a.height);
            let _ = render_pass(&scene, &mut film, 0, &never);
            let mut passes = Vec::new();
            let mut previews = Vec::new();
            for i in 0..a.repeat.max(1) {
                let t0 = Instant::now();
                let _ = render_pass(&scene, &mut film, i as u32, &never);
                passes.push(t0.elapsed());
                let t0 = Instant::now();
                let _ = render_preview(&scene, PREVIEW_BLOCKS[0], &never);
                previews.push(t0.elapsed());
            }
            (passes, previews)
        });
        let (pass, preview) = (median(passes), median(previews));
        let rate = rays / pass.as_secs_f64();
        let speedup = base.map_or(1.0, |b: f64| rate / b);
        base.get_or_insert(rate);
        println!(
            "threads {threads}: pass {:.2} ms, {:.1} M primary rays/s (x{speedup:.2}), first preview ({block}x{block} blocks) {:.2} ms",
            pass.as_secs_f64() * 1e3,
            rate / 1e6,
            preview.as_secs_f64() * 1e3,
            block = PREVIEW_BLOCKS[0],
        );
    }
    Ok(())
}
