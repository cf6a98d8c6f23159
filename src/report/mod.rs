//! Speed against error: render a scene in several antialiasing modes (texture filter x pixel
//! sampler x samples per pixel), time each render, and measure its error against a
//! high-spp reference.
//!
//! [`run_scene`] is the library entry point (the GUI plots its rows live; `texplore report`
//! writes them as CSV, Markdown tables and plots through [`write_outputs`]).

pub mod metrics;
// The files a report writes and their charts: the command line's (plotters has no font
// registry on wasm32, and a page has no folder to write them to).
#[cfg(not(target_arch = "wasm32"))]
pub mod output;
#[cfg(not(target_arch = "wasm32"))]
pub mod plot;
pub mod reference;
pub mod table;

pub use metrics::{EncodedImage, METRIC_DEFINITIONS, Metrics, compare};
#[cfg(not(target_arch = "wasm32"))]
pub use output::write_outputs;
#[cfg(not(target_arch = "wasm32"))]
pub use reference::{CacheKey, CachedReference, REFERENCE_VERSION, cache_key, default_cache_dir};
pub use table::{RMSE_TARGETS, pareto_front, time_to_reach};

use crate::names::Named as _;
use crate::render::{Film, render_pass, render_scheduled_pass};
use crate::sampler::PixelSampler;
use crate::scene::{AssetCache, Overrides, SceneDesc, apply_overrides, build_scene};
use crate::texture::Filter;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;
use strum::VariantArray;
use web_time::Instant;

/// Why a report stopped.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// The scene could not be built (bad preset, missing asset).
    #[error(transparent)]
    Scene(#[from] crate::Error),
    /// A cache or output file could not be read or written.
    #[error("{}: {io}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the OS said.
        io: std::io::Error,
    },
    /// A `--modes` list or a setting could not be used.
    #[error("{0}")]
    Invalid(String),
    /// The cancel flag was raised.
    #[error("cancelled")]
    Cancelled,
}

impl ReportError {
    /// An [`ReportError::Io`] for `path`.
    #[must_use]
    pub fn io(path: &Path, io: std::io::Error) -> Self {
        Self::Io {
            path: path.to_path_buf(),
            io,
        }
    }
}

/// One antialiasing mode: how texels are filtered and where samples go in a pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Mode {
    /// Texture filter of every image texture.
    pub filter: Filter,
    /// Pixel sampler.
    pub sampler: PixelSampler,
    /// Adaptive sampling after the first `spp` samples (up to [`ADAPTIVE_FACTOR`] x `spp`, at
    /// least [`ADAPTIVE_MIN_MAX_SPP`], at the default threshold); written `+adaptive`.
    pub adaptive: bool,
}

/// An adaptive mode may spend up to this many times its `spp` on the pixels that need it.
pub const ADAPTIVE_FACTOR: u32 = 4;
/// ... and at least this many samples per pixel.
pub const ADAPTIVE_MIN_MAX_SPP: u32 = 16;

impl Mode {
    /// `filter/sampler`, as `--modes` takes it.
    #[must_use]
    pub fn name(self) -> String {
        let adaptive = if self.adaptive { "+adaptive" } else { "" };
        format!("{}/{}{adaptive}", self.filter.name(), self.sampler.name())
    }

    /// The settings that render a scene in this mode at `spp` samples per pixel: every image
    /// texture's filter and the pixel sampler replaced, adaptive sampling (up to
    /// [`ADAPTIVE_FACTOR`] x `spp`) only in an adaptive mode, whatever the preset says.
    #[must_use]
    pub fn overrides(self, spp: u32) -> Overrides {
        Overrides {
            spp: Some(spp),
            filter: Some(self.filter),
            sampler: Some(self.sampler),
            adaptive: self.adaptive.then(|| crate::scene::AdaptiveDesc {
                max_spp: (spp * ADAPTIVE_FACTOR).max(ADAPTIVE_MIN_MAX_SPP),
                threshold: crate::scene::DEFAULT_ADAPTIVE_THRESHOLD,
            }),
            no_adaptive: !self.adaptive,
            ..Overrides::default()
        }
    }

    /// `desc` rendered in this mode at `spp` samples per pixel (see [`Mode::overrides`]).
    #[must_use]
    pub fn apply(self, desc: &SceneDesc, spp: u32) -> SceneDesc {
        let mut d = desc.clone();
        apply_overrides(&mut d, self.overrides(spp));
        d
    }

    /// A non-adaptive mode.
    #[must_use]
    pub const fn new(filter: Filter, sampler: PixelSampler) -> Self {
        Self {
            filter,
            sampler,
            adaptive: false,
        }
    }

    /// Every filter with every sampler.
    #[must_use]
    pub fn all() -> Vec<Self> {
        Filter::VARIANTS
            .iter()
            .flat_map(|&filter| {
                PixelSampler::VARIANTS
                    .iter()
                    .map(move |&sampler| Self::new(filter, sampler))
            })
            .collect()
    }

    /// Every filter with the jittered sampler, then the bilinear filter with every other
    /// sampler: each option once, at a cost linear in the number of options.
    #[must_use]
    pub fn default_set() -> Vec<Self> {
        let mut v: Vec<Self> = Filter::VARIANTS
            .iter()
            .map(|&filter| Self::new(filter, PixelSampler::Jittered))
            .collect();
        for &sampler in PixelSampler::VARIANTS {
            let m = Self::new(Filter::Bilinear, sampler);
            if !v.contains(&m) {
                v.push(m);
            }
        }
        // The footprint filter at the pixel centre, where it integrates the pixel's own
        // footprint (with jittered samples the footprint moves with the sample).
        v.push(Self::new(Filter::Footprint, PixelSampler::Regular));
        // Adaptive sampling with the filters that need the fewest samples inside textures.
        for filter in [Filter::Footprint, Filter::Ewa, Filter::Bilinear] {
            v.push(Self {
                adaptive: true,
                ..Self::new(filter, PixelSampler::Regular)
            });
        }
        v
    }

    /// Parses `all`, `default`, or a comma-separated list of `filter/sampler` (either part may
    /// be `*` for every value), each optionally followed by `+adaptive`.
    ///
    /// # Errors
    /// An unknown filter or sampler (the message lists the valid names) or an empty list.
    pub fn parse_list(s: &str) -> Result<Vec<Self>, ReportError> {
        let s = s.trim();
        match s {
            "all" => return Ok(Self::all()),
            "default" => return Ok(Self::default_set()),
            _ => {}
        }
        let mut out: Vec<Self> = Vec::new();
        for item in s.split(',').map(str::trim).filter(|i| !i.is_empty()) {
            let (item, adaptive) = match item.strip_suffix("+adaptive") {
                Some(rest) => (rest, true),
                None => (item, false),
            };
            let (f, smp) = item.split_once('/').ok_or_else(|| {
                ReportError::Invalid(format!(
                    "mode '{item}' is not filter/sampler (for example bilinear/jittered)"
                ))
            })?;
            let filters: Vec<Filter> = if f == "*" {
                Filter::VARIANTS.to_vec()
            } else {
                vec![Filter::from_name(f).map_err(ReportError::Invalid)?]
            };
            let samplers: Vec<PixelSampler> = if smp == "*" {
                PixelSampler::VARIANTS.to_vec()
            } else {
                vec![PixelSampler::from_name(smp).map_err(ReportError::Invalid)?]
            };
            for &filter in &filters {
                for &sampler in &samplers {
                    let m = Self {
                        filter,
                        sampler,
                        adaptive,
                    };
                    if !out.contains(&m) {
                        out.push(m);
                    }
                }
            }
        }
        if out.is_empty() {
            return Err(ReportError::Invalid("no modes given".into()));
        }
        Ok(out)
    }
}

/// How the reference is rendered.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceSettings {
    /// Samples per pixel.
    pub spp: u32,
    /// Texture filter.
    pub filter: Filter,
    /// Pixel sampler.
    pub sampler: PixelSampler,
    /// Where references are cached (`None`: not cached). The command line's: a page has no
    /// cache folder.
    #[cfg(not(target_arch = "wasm32"))]
    pub cache_dir: Option<PathBuf>,
    /// An image made outside texplore (linear OpenEXR or Radiance HDR, the render's size) to
    /// judge against instead of rendering a reference: `report --reference FILE.exr`. The
    /// settings above are then unused.
    pub file: Option<PathBuf>,
}

/// The reference's seed is the scene's plus this, so its samples are independent of the
/// renders it judges.
pub const REFERENCE_SEED_OFFSET: u32 = 0x9e37_79b9;

impl Default for ReferenceSettings {
    fn default() -> Self {
        Self {
            spp: 4096,
            filter: Filter::Bilinear,
            sampler: PixelSampler::Jittered,
            #[cfg(not(target_arch = "wasm32"))]
            cache_dir: None,
            file: None,
        }
    }
}

impl ReferenceSettings {
    /// `scene` as the reference renders it: its filter and sampler at its spp, non-adaptive,
    /// with the seed moved by [`REFERENCE_SEED_OFFSET`]; `width` and `height` override the
    /// preset's size.
    #[must_use]
    pub fn desc(&self, scene: &SceneDesc, width: Option<u32>, height: Option<u32>) -> SceneDesc {
        let mut d = scene.clone();
        apply_overrides(
            &mut d,
            Overrides {
                width,
                height,
                seed: Some(scene.render.seed.wrapping_add(REFERENCE_SEED_OFFSET)),
                ..Mode::new(self.filter, self.sampler).overrides(self.spp)
            },
        );
        d
    }

    /// One line for reports.
    #[must_use]
    pub fn describe(&self) -> String {
        if let Some(file) = &self.file {
            return format!(
                "the linear image {} (made outside texplore, compared as it is)",
                file.display()
            );
        }
        format!(
            "{} spp, {} texture filter, {} sampler, box pixel filter (equal-weight mean of the samples), seed = scene seed + {REFERENCE_SEED_OFFSET:#x}",
            self.spp,
            self.filter.name(),
            self.sampler.name()
        )
    }
}

/// What to measure.
#[derive(Clone, Debug, PartialEq)]
pub struct ReportConfig {
    /// The modes to compare.
    pub modes: Vec<Mode>,
    /// Samples per pixel of each render.
    pub spp: Vec<u32>,
    /// Timed runs per render after one warm-up run (the median is reported).
    pub repeat: usize,
    /// Fewer timed runs once a render's warm-up takes longer than this over `repeat`: at least
    /// one, as many as fit (long renders vary little). The count is recorded in each row.
    pub time_budget: Duration,
    /// Width override.
    pub width: Option<u32>,
    /// Height override.
    pub height: Option<u32>,
    /// The reference.
    pub reference: ReferenceSettings,
    /// Keep FLIP error maps for heat maps at this spp (`None`: keep none).
    pub heatmap_spp: Option<u32>,
    /// How wide the render kernel runs in every render (the reference's too).
    pub simd: crate::scene::SimdMode,
}

impl Default for ReportConfig {
    fn default() -> Self {
        Self {
            modes: Mode::default_set(),
            spp: (0..=8).map(|i| 1 << i).collect(),
            repeat: 5,
            time_budget: Duration::from_secs(2),
            width: None,
            height: None,
            reference: ReferenceSettings::default(),
            heatmap_spp: None,
            simd: crate::scene::SimdMode::Auto,
        }
    }
}

/// One measured render.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The scene's name.
    pub scene: String,
    /// The mode.
    pub mode: Mode,
    /// Samples per pixel.
    pub spp: u32,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Rayon worker threads the render ran on.
    pub threads: usize,
    /// Timed runs (after the warm-up).
    pub runs: usize,
    /// Camera samples the render took (more than width x height x spp with adaptive sampling).
    pub samples: f64,
    /// Median time of the timed runs.
    pub time: Duration,
    /// Fastest timed run.
    pub time_min: Duration,
    /// Errors against the reference.
    pub metrics: Metrics,
}

impl Row {
    /// Camera samples per second at the median time.
    #[must_use]
    pub fn samples_per_second(&self) -> f64 {
        self.samples / self.time.as_secs_f64().max(1e-12)
    }
}

/// A FLIP error map of one render, for a heat map.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorMap {
    /// The mode.
    pub mode: Mode,
    /// Samples per pixel.
    pub spp: u32,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Per-pixel FLIP error in [0, 1], row-major from the top-left.
    pub error: Vec<f32>,
}

/// Everything measured for one scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneReport {
    /// The scene's name.
    pub scene: String,
    /// One row per (mode, spp), in the order rendered.
    pub rows: Vec<Row>,
    /// The reference's settings.
    pub reference: ReferenceSettings,
    /// Whether the reference came from the cache (false: rendered now).
    pub reference_cached: bool,
    /// The reference's EXR, when cached on disk.
    pub reference_file: Option<PathBuf>,
    /// Why a cached reference for this key was not used and the reference was rendered again
    /// ("FILE: checksum mismatch ..."); `None` when the cache held none or it was used.
    pub reference_problem: Option<String>,
    /// Why the reference rendered now could not be kept in the cache (the report goes on
    /// without it); `None` when it was stored, came from the cache, or caching is off.
    pub reference_not_stored: Option<String>,
    /// Time spent rendering the reference (zero when it came from the cache).
    pub reference_time: Duration,
    /// Error maps kept for heat maps.
    pub error_maps: Vec<ErrorMap>,
}

/// What [`run_scene`] is doing, told to its progress callback.
#[derive(Clone, Debug, PartialEq)]
pub enum Stage {
    /// Rendering the reference (not cached yet).
    Reference,
    /// Rendering and timing a mode.
    Mode(Mode, u32),
}

/// Progress of [`run_scene`]: work is counted in camera samples (pixels x spp), rendered or
/// skipped.
#[derive(Clone, Debug, PartialEq)]
pub struct ProgressUpdate<'a> {
    /// Samples done.
    pub done: u64,
    /// Samples planned in total, fixed for a run (timed runs skipped by the time budget are
    /// counted as done, so `done` ends equal to `total`).
    pub total: u64,
    /// What is being rendered.
    pub stage: Stage,
    /// The row just finished, if any (the GUI appends it to its live plot).
    pub row: Option<&'a Row>,
}

/// Renders `scene` (a preset read from `preset_path`, whose directory resolves asset paths) in
/// every mode at every spp of `config` on the current rayon pool, and measures each against
/// the reference (loaded from the cache or rendered and stored). `progress` is called after
/// every reference pass and every complete render; raising `cancel` stops within one tile.
///
/// # Errors
/// The scene cannot be built, the cache cannot be written, or `cancel` was raised.
pub fn run_scene(
    name: &str,
    scene: &SceneDesc,
    preset_path: &Path,
    config: &ReportConfig,
    progress: &mut dyn FnMut(&ProgressUpdate<'_>),
    cancel: &AtomicBool,
) -> Result<SceneReport, ReportError> {
    validate(config)?;
    let mut assets = AssetCache::new();
    let r = &config.reference;
    let ref_desc = r.desc(scene, config.width, config.height);
    let (width, height) = (ref_desc.render.width, ref_desc.render.height);
    let pixels = u64::from(width) * u64::from(height);
    let spp_sum: u64 = config.spp.iter().map(|s| u64::from(*s)).sum();
    let repeat = config.repeat.max(1) as u64;
    let mut tally = Tally {
        done: 0,
        total: pixels * spp_sum * (1 + repeat) * config.modes.len() as u64,
        progress,
    };

    // The reference: from the cache, or rendered now (and stored).
    #[cfg(not(target_arch = "wasm32"))]
    let key = cache_key(&ref_desc, preset_path);
    // An external reference is never cached.
    #[cfg(not(target_arch = "wasm32"))]
    let cached = r
        .cache_dir
        .as_ref()
        .filter(|_| r.file.is_none())
        .map(|dir| CachedReference::new(dir, &key));
    let t0 = Instant::now();
    #[cfg(not(target_arch = "wasm32"))]
    let (stored, reference_problem) = match cached.as_ref().map(|c| c.load(&key, width, height)) {
        Some(Ok(img)) => (img, None),
        Some(Err(problem)) => (None, Some(problem)),
        None => (None, None),
    };
    #[cfg(target_arch = "wasm32")]
    let (stored, reference_problem) = (None, None);
    #[cfg_attr(target_arch = "wasm32", allow(unused_mut))]
    let mut reference_not_stored = None;
    let (reference_linear, reference_cached) = if let Some(file) = &r.file {
        (reference::load_linear(file, width, height)?, false)
    } else if let Some(img) = stored {
        (img, true)
    } else {
        let mut ref_scene = build_scene(&ref_desc, preset_path, &mut assets)?;
        ref_scene.settings.simd = config.simd;
        let img = render_reference(&ref_scene, r.spp, &mut tally, cancel)?;
        // A cache that cannot keep it (a damaged entry that is a folder, a full disk) costs
        // only the next run's render: the report goes on, and says so.
        #[cfg(not(target_arch = "wasm32"))]
        if let Some(c) = &cached
            && let Err(e) = c.store(&key, width, height, &img)
        {
            reference_not_stored = Some(e.to_string());
        }
        (img, false)
    };
    let reference_time = if reference_cached || r.file.is_some() {
        Duration::ZERO
    } else {
        t0.elapsed()
    };
    let exposure = scene.render.exposure.exp2();
    let target = Target {
        name,
        config,
        reference: EncodedImage::from_linear(width, height, &reference_linear, exposure),
        reference_linear,
        exposure,
        cancel,
    };

    let mut rows = Vec::new();
    let mut error_maps = Vec::new();
    for &mode in &config.modes {
        for &spp in &config.spp {
            let desc = sized(scene, config, mode, spp);
            let mut built = build_scene(&desc, preset_path, &mut assets)?;
            built.settings.simd = config.simd;
            let (row, flip_map) = target.measure(&built, mode, spp, &mut tally)?;
            if let Some(error) = flip_map.filter(|_| config.heatmap_spp == Some(spp)) {
                error_maps.push(ErrorMap {
                    mode,
                    spp,
                    width,
                    height,
                    error,
                });
            }
            rows.push(row);
            tally.tell(Stage::Mode(mode, spp), rows.last());
        }
    }
    Ok(SceneReport {
        scene: name.to_string(),
        rows,
        reference: r.clone(),
        reference_cached,
        #[cfg(not(target_arch = "wasm32"))]
        reference_file: r.file.clone().or_else(|| {
            cached
                .filter(|_| reference_not_stored.is_none())
                .map(|c| c.exr)
        }),
        #[cfg(target_arch = "wasm32")]
        reference_file: r.file.clone(),
        reference_problem,
        reference_not_stored,
        reference_time,
        error_maps,
    })
}

/// Refuses an empty spp list, a zero spp, or no modes.
fn validate(config: &ReportConfig) -> Result<(), ReportError> {
    if config.spp.is_empty() || config.spp.contains(&0) {
        return Err(ReportError::Invalid(
            "the spp list must be non-empty and every value at least 1".into(),
        ));
    }
    if config.modes.is_empty() {
        return Err(ReportError::Invalid("no modes given".into()));
    }
    Ok(())
}

/// `scene` as measured in `mode` at `spp`, at the configured size.
fn sized(scene: &SceneDesc, config: &ReportConfig, mode: Mode, spp: u32) -> SceneDesc {
    let mut d = scene.clone();
    apply_overrides(
        &mut d,
        Overrides {
            width: config.width,
            height: config.height,
            ..mode.overrides(spp)
        },
    );
    d
}

/// Progress counted in camera samples, told to the caller's callback.
struct Tally<'p> {
    done: u64,
    total: u64,
    progress: &'p mut dyn FnMut(&ProgressUpdate<'_>),
}

impl Tally<'_> {
    /// Tells the callback where the run is.
    fn tell(&mut self, stage: Stage, row: Option<&Row>) {
        (self.progress)(&ProgressUpdate {
            done: self.done,
            total: self.total,
            stage,
            row,
        });
    }
}

/// The reference rendered pass by pass (its samples join the planned total), as linear
/// radiance.
fn render_reference(
    scene: &crate::scene::Scene,
    spp: u32,
    tally: &mut Tally<'_>,
    cancel: &AtomicBool,
) -> Result<Vec<crate::math::Rgb>, ReportError> {
    let (width, height) = (scene.settings.width, scene.settings.height);
    let pixels = u64::from(width) * u64::from(height);
    tally.total += pixels * u64::from(spp);
    let mut film = Film::new(width, height);
    for sample in 0..spp {
        pass(scene, &mut film, sample, cancel)?;
        tally.done += pixels;
        tally.tell(Stage::Reference, None);
    }
    Ok(film.to_linear())
}

/// What every render of a run is measured against, and how.
struct Target<'a> {
    /// The scene's name, for the rows.
    name: &'a str,
    config: &'a ReportConfig,
    /// The reference, display-encoded.
    reference: EncodedImage,
    /// The reference's linear radiance.
    reference_linear: Vec<crate::math::Rgb>,
    /// The scene's exposure as a scale.
    exposure: f32,
    cancel: &'a AtomicBool,
}

impl Target<'_> {
    /// One (mode, spp): a warm-up render (the image measured; renders are deterministic),
    /// then the timed runs that fit the budget. Returns the row and FLIP's error map (`None`
    /// without the `flip` feature).
    fn measure(
        &self,
        built: &crate::scene::Scene,
        mode: Mode,
        spp: u32,
        tally: &mut Tally<'_>,
    ) -> Result<(Row, Option<Vec<f32>>), ReportError> {
        let (width, height) = (self.reference.width, self.reference.height);
        let cell = u64::from(width) * u64::from(height) * u64::from(spp);
        let repeat = self.config.repeat.max(1);
        let (film, warm) = render_timed(built, spp, self.cancel)?;
        tally.done += cell;
        tally.tell(Stage::Mode(mode, spp), None);
        let runs = timed_runs(warm, repeat, self.config.time_budget);
        let mut times = Vec::with_capacity(runs);
        for _ in 0..runs {
            times.push(render_timed(built, spp, self.cancel)?.1);
            tally.done += cell;
            tally.tell(Stage::Mode(mode, spp), None);
        }
        // Skipped runs count as done, so the ETA stays honest.
        tally.done += cell * (repeat - runs) as u64;
        times.sort();
        let linear = film.to_linear();
        let test = EncodedImage::from_linear(width, height, &linear, self.exposure);
        let (mut metrics, flip_map) = compare(&self.reference, &test);
        metrics.rmse_linear = metrics::rmse_linear(&self.reference_linear, &linear);
        let row = Row {
            scene: self.name.to_string(),
            mode,
            samples: film.total_samples(),
            spp,
            width,
            height,
            threads: rayon::current_num_threads(),
            runs,
            time: times[times.len() / 2],
            time_min: times[0],
            metrics,
        };
        Ok((row, flip_map))
    }
}

/// How many timed runs fit: `repeat`, or fewer when the warm-up shows they would take longer
/// than `budget` (at least one).
fn timed_runs(warm: Duration, repeat: usize, budget: Duration) -> usize {
    if warm.is_zero() {
        return repeat;
    }
    let fit = (budget.as_secs_f64() / warm.as_secs_f64()).floor() as usize;
    fit.clamp(1, repeat)
}

fn pass(
    scene: &crate::scene::Scene,
    film: &mut Film,
    sample: u32,
    cancel: &AtomicBool,
) -> Result<(), ReportError> {
    let cancelled = || cancel.load(Ordering::Relaxed);
    render_pass(scene, film, sample, &cancelled).map_err(|_| ReportError::Cancelled)
}

/// One complete render (every pass, adaptive ones included) and its wall time.
fn render_timed(
    scene: &crate::scene::Scene,
    spp: u32,
    cancel: &AtomicBool,
) -> Result<(Film, Duration), ReportError> {
    let t0 = Instant::now();
    let mut film = Film::new(scene.settings.width, scene.settings.height);
    if scene.settings.adaptive.is_none() {
        for sample in 0..spp {
            pass(scene, &mut film, sample, cancel)?;
        }
    } else {
        let cancelled = || cancel.load(Ordering::Relaxed);
        for p in 0..scene.settings.max_spp() {
            match render_scheduled_pass(scene, &mut film, p, &cancelled) {
                Ok(0) => break,
                Ok(_) => {}
                Err(_) => return Err(ReportError::Cancelled),
            }
        }
    }
    Ok((film, t0.elapsed()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_parse_from_lists_and_wildcards() {
        let m = Mode::parse_list("nearest/jittered, bilinear/regular").unwrap();
        assert_eq!(
            m,
            vec![
                Mode::new(Filter::Nearest, PixelSampler::Jittered),
                Mode::new(Filter::Bilinear, PixelSampler::Regular)
            ]
        );
        assert_eq!(
            Mode::parse_list("all").unwrap().len(),
            Filter::VARIANTS.len() * PixelSampler::VARIANTS.len()
        );
        assert_eq!(
            Mode::parse_list("*/jittered").unwrap().len(),
            Filter::VARIANTS.len()
        );
        let d = Mode::default_set();
        // Every filter with jittered, bilinear with the other samplers, footprint/regular,
        // three adaptive modes.
        assert_eq!(
            d.len(),
            Filter::VARIANTS.len() + PixelSampler::VARIANTS.len() - 1 + 1 + 3
        );
        assert_eq!(d.iter().filter(|m| m.adaptive).count(), 3);
        let e = Mode::parse_list("bilinear/zigzag").unwrap_err().to_string();
        assert!(e.contains("zigzag") && e.contains("jittered"), "{e}");
        assert!(Mode::parse_list("bilinear").is_err());
        assert!(Mode::parse_list(" , ").is_err());
    }

    #[test]
    fn timed_runs_fit_the_budget() {
        let b = Duration::from_secs(2);
        assert_eq!(timed_runs(Duration::from_millis(10), 5, b), 5);
        assert_eq!(timed_runs(Duration::from_millis(700), 5, b), 2);
        assert_eq!(timed_runs(Duration::from_secs(5), 5, b), 1);
    }
}
