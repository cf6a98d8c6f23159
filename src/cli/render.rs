//! `texplore render`.

use crate::render::render_blocking;
use crate::sampler::PixelSampler;
use crate::scene::{
    AssetCache, Overrides, apply_overrides, build_scene, read_preset_or_png, save_render_png,
};
use crate::texture::Filter;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// `texplore render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// The preset (.ron), or a PNG saved by texplore with its preset inside.
    pub preset: PathBuf,
    /// Output PNG.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Image width (overrides the preset).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height (overrides the preset).
    #[arg(long)]
    pub height: Option<u32>,
    /// Samples per pixel (overrides the preset).
    #[arg(long)]
    pub spp: Option<u32>,
    /// Random seed (overrides the preset).
    #[arg(long)]
    pub seed: Option<u32>,
    /// Texture filter for every image texture (overrides the preset): nearest, bilinear, ...
    #[arg(long)]
    pub filter: Option<Filter>,
    /// Pixel sampler (overrides the preset): regular, random, jittered, n-rooks, ...
    #[arg(long)]
    pub sampler: Option<PixelSampler>,
    /// Worker threads (default: one per core).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Don't draw the progress bar.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Renders the preset and writes the PNG.
///
/// # Errors
/// The preset, its assets or the output cannot be read or written.
pub fn run(a: &RenderArgs) -> Result<()> {
    let mut desc = read_preset_or_png(&a.preset)?;
    apply_overrides(
        &mut desc,
        Overrides {
            width: a.width,
            height: a.height,
            spp: a.spp,
            seed: a.seed,
            filter: a.filter,
            sampler: a.sampler,
        },
    );
    let mut cache = AssetCache::new();
    let scene = build_scene(&desc, &a.preset, &mut cache)?;
    let s = scene.settings;
    let bar = if a.quiet {
        indicatif::ProgressBar::hidden()
    } else {
        let bar = indicatif::ProgressBar::new(u64::from(s.spp));
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{spinner} {msg} [{bar:30}] {pos}/{len} spp, {elapsed} elapsed, {eta} left",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar.set_message(format!("{}x{}", s.width, s.height));
        bar
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.threads)
        .build()
        .context("cannot start worker threads")?;
    let t0 = Instant::now();
    let film = pool.install(|| render_blocking(&scene, |n| bar.set_position(u64::from(n))));
    let dt = t0.elapsed();
    bar.finish_and_clear();
    let preset_dir = a.preset.parent().unwrap_or(Path::new("."));
    save_render_png(
        &a.output,
        &film.to_display(s.exposure_scale),
        &desc,
        preset_dir,
    )?;
    if !a.quiet {
        let rays = f64::from(s.width) * f64::from(s.height) * f64::from(s.spp);
        eprintln!(
            "wrote {} ({}x{}, {} spp) in {:.2} s: {:.1} M rays/s on {} threads",
            a.output.display(),
            s.width,
            s.height,
            s.spp,
            dt.as_secs_f64(),
            rays / dt.as_secs_f64() / 1e6,
            pool.current_num_threads()
        );
    }
    Ok(())
}
