//! `texplore render`.

use crate::names::value_parser;
use crate::output::check_output;
use crate::render::render_blocking;
use crate::sampler::{PixelFilter, PixelSampler};
use crate::scene::{
    AdaptiveDesc, AssetCache, DEFAULT_ADAPTIVE_THRESHOLD, Overrides, apply_overrides, asset_paths,
    build_scene, read_preset_or_png, save_render_png_checked,
};
use crate::texture::{Filter, View};
use anyhow::Result;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What `render -o` accepts: a PNG (display-encoded, with its preset in a text chunk), or the
/// linear float image as OpenEXR or Radiance HDR (for measuring outside texplore).
pub const RENDER_EXTS: &[&str] = &["png", "exr", "hdr"];

/// `texplore render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// The preset (.ron), or a PNG saved by texplore with its preset inside.
    pub preset: PathBuf,
    /// Output: a PNG (display-encoded, with the preset inside), or `.exr` / `.hdr` for the
    /// linear radiance as floats (before exposure; what `report --reference` reads). Other
    /// extensions are refused. Never an input of the render; a symbolic link is followed.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Image width (overrides the preset).
    #[arg(long, value_parser = super::parse_resolution)]
    pub width: Option<u32>,
    /// Image height (overrides the preset).
    #[arg(long, value_parser = super::parse_resolution)]
    pub height: Option<u32>,
    /// Samples per pixel (overrides the preset).
    #[arg(long, value_parser = super::parse_spp)]
    pub spp: Option<u32>,
    /// Random seed (overrides the preset).
    #[arg(long)]
    pub seed: Option<u32>,
    /// Texture filter for every image and checker texture (overrides the preset).
    #[arg(long, value_parser = value_parser::<Filter>())]
    pub filter: Option<Filter>,
    /// Largest anisotropy the EWA filter follows, 1 to 64 (overrides the preset; default 8).
    #[arg(long = "max-aniso", value_name = "RATIO", allow_hyphen_values = true, value_parser = super::parse_max_aniso)]
    pub max_aniso: Option<f32>,
    /// Pixel sampler (overrides the preset).
    #[arg(long, value_parser = value_parser::<PixelSampler>())]
    pub sampler: Option<PixelSampler>,
    /// Pixel reconstruction filter (overrides the preset).
    #[arg(long = "pixel-filter", value_name = "FILTER", value_parser = value_parser::<PixelFilter>())]
    pub pixel_filter: Option<PixelFilter>,
    /// Adaptive sampling: after --spp samples everywhere, up to MAX_SPP where the estimated
    /// error exceeds THRESHOLD (display units, default 0.01). E.g. `--spp 1 --adaptive 16`.
    #[arg(long, value_name = "MAX_SPP[,THRESHOLD]", allow_hyphen_values = true, value_parser = parse_adaptive)]
    pub adaptive: Option<AdaptiveDesc>,
    /// Turn off the preset's adaptive sampling.
    #[arg(long, conflicts_with = "adaptive")]
    pub no_adaptive: bool,
    /// What to render: the shaded image or a debug view.
    #[arg(long, value_parser = value_parser::<View>())]
    pub view: Option<View>,
    /// Worker threads (default: one per core).
    #[arg(long, default_value_t = 0, value_parser = super::parse_threads)]
    pub threads: usize,
    /// Don't draw the progress bar.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Renders the preset and writes the PNG (or the linear EXR / HDR).
///
/// # Errors
/// The preset, its assets or the output cannot be read or written.
pub fn run(a: &RenderArgs, simd: crate::scene::SimdMode) -> Result<()> {
    let mut desc = read_preset_or_png(&a.preset)?;
    // A bad -o fails now, not after the render.
    let preset_dir = a.preset.parent().unwrap_or(Path::new("."));
    let assets = asset_paths(&desc, preset_dir);
    let inputs: Vec<&Path> = std::iter::once(a.preset.as_path())
        .chain(assets.iter().map(PathBuf::as_path))
        .collect();
    check_output(&a.output, RENDER_EXTS, &inputs)?;
    apply_overrides(
        &mut desc,
        Overrides {
            width: a.width,
            height: a.height,
            spp: a.spp,
            seed: a.seed,
            filter: a.filter,
            sampler: a.sampler,
            max_anisotropy: a.max_aniso,
            pixel_filter: a.pixel_filter,
            adaptive: a.adaptive,
            no_adaptive: a.no_adaptive,
            view: a.view,
        },
    );
    let mut cache = AssetCache::new();
    let mut scene = build_scene(&desc, &a.preset, &mut cache)?;
    // Textures whose footprint filter reads EWA (no summed-area tables): say why.
    for n in cache.notices() {
        eprintln!("warning: {}: {n}", a.preset.display());
    }
    scene.settings.simd = simd;
    let s = scene.settings;
    let bar = if a.quiet {
        indicatif::ProgressBar::hidden()
    } else {
        let bar = indicatif::ProgressBar::new(u64::from(s.max_spp()));
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{spinner} {msg} [{bar:30}] {pos}/{len} spp, {elapsed} elapsed, {eta} left",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar.set_message(format!("{}x{}", s.width, s.height));
        bar
    };
    let pool = crate::render::thread_pool(a.threads)?;
    let t0 = Instant::now();
    let film = pool.install(|| render_blocking(&scene, |n| bar.set_position(u64::from(n))));
    let dt = t0.elapsed();
    bar.finish_and_clear();
    if crate::output::LINEAR_EXTS.contains(&crate::output::extension(&a.output).as_str()) {
        let rgb: Vec<f32> = film.to_linear().iter().flat_map(|c| c.to_array()).collect();
        crate::output::write_linear_image(&a.output, &inputs, s.width, s.height, &rgb)?;
    } else {
        save_render_png_checked(
            &a.output,
            &[&a.preset],
            &film.to_display(s.exposure_scale),
            &desc,
            preset_dir,
        )?;
    }
    if !a.quiet {
        let rays = film.total_samples();
        let pixels = f64::from(s.width) * f64::from(s.height);
        eprintln!(
            "wrote {} ({}x{}, {:.2} spp on average) in {:.2} s: {:.1} M rays/s on {} threads",
            a.output.display(),
            s.width,
            s.height,
            rays / pixels,
            dt.as_secs_f64(),
            rays / dt.as_secs_f64() / 1e6,
            pool.current_num_threads()
        );
    }
    // A student's formula that is NaN or infinite somewhere, in any field: say where.
    for n in crate::scene::non_finite_fields(&scene, &desc) {
        eprintln!("warning: {}", n.warning(&desc));
    }
    Ok(())
}

/// `MAX_SPP` or `MAX_SPP,THRESHOLD`.
fn parse_adaptive(s: &str) -> std::result::Result<AdaptiveDesc, String> {
    let (spp, threshold) = match s.split_once(',') {
        Some((a, b)) => (a, Some(b)),
        None => (s, None),
    };
    let max_spp = super::parse_spp(spp).map_err(|e| format!("MAX_SPP: {e}"))?;
    let threshold = match threshold {
        Some(t) => {
            let v = super::parse_finite(t).map_err(|e| format!("THRESHOLD: {e}"))?;
            if !(v > 0.0 && v <= 1.0) {
                return Err(format!("THRESHOLD: {v} is out of range (0, 1]"));
            }
            v as f32
        }
        None => DEFAULT_ADAPTIVE_THRESHOLD,
    };
    Ok(AdaptiveDesc { max_spp, threshold })
}
