//! The command line: `texplore` with no subcommand opens the window; the subcommands run the
//! same scenes headless.

use crate::mapping::{Mapping, explain_lookup, explain_mapping};
use crate::math::Vec3A;
use crate::probe::{ProbeFormat, make_probe};
use crate::render::{Film, PREVIEW_BLOCKS, render_blocking, render_pass, render_preview};
use crate::scene::{
    AssetCache, Overrides, SceneDesc, apply_overrides, build_scene, load_preset, to_ron,
};
use crate::snapshot::{
    MAX_BAD_FRACTION, MAX_MEAN_DIFF, Outcome, PIXEL_TOLERANCE, check_preset, list_presets,
};
use crate::texture::{Lookup, save_png};
use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand, ValueEnum};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The PNG text-chunk keyword under which renders and screenshots carry their preset.
pub const PRESET_CHUNK: &str = "texplore-preset";

/// texplore: an interactive texture-mapping explorer on a progressive CPU ray tracer.
///
/// Without a subcommand it opens the window on the Earth.
#[derive(Debug, Parser)]
#[command(version, about, long_about = None, args_conflicts_with_subcommands = true)]
pub struct Cli {
    /// What to do (none: open the window).
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Preset or screenshot to open in the window (default: the Earth).
    #[arg(value_name = "FILE")]
    pub open: Option<PathBuf>,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a preset to a PNG (the preset is embedded in the PNG's text chunk).
    Render(RenderArgs),
    /// Compare every preset's render with its golden image in screenshots/ (or rewrite them).
    Snapshot(SnapshotArgs),
    /// Print (u, v), column and row of a local hit point under a mapping: the lecture's formulas.
    Map(MapArgs),
    /// Turn an equirectangular panorama into a light-probe image.
    Probe(ProbeArgs),
    /// Time full 1-spp passes and the first preview of a preset with 1, 2, ... threads.
    Bench(BenchArgs),
}

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
    /// Worker threads (default: one per core).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Don't draw the progress bar.
    #[arg(long, short)]
    pub quiet: bool,
}

/// `texplore snapshot`.
#[derive(Debug, clap::Args)]
pub struct SnapshotArgs {
    /// check: compare with the goldens; update: rewrite them.
    pub action: SnapshotAction,
    /// Only these presets (file stems, e.g. `earth`).
    pub names: Vec<String>,
    /// Where the presets are.
    #[arg(long, default_value = "presets")]
    pub presets: PathBuf,
    /// Where the golden images are.
    #[arg(long, default_value = "screenshots")]
    pub screenshots: PathBuf,
}

/// What `snapshot` does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SnapshotAction {
    /// Compare renders with the goldens; exit non-zero on a mismatch.
    Check,
    /// Rewrite the goldens.
    Update,
}

/// `texplore map`.
#[derive(Debug, clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct MapArgs {
    /// rectangular, cylindrical, spherical, light-probe, panoramic or mirror-ball.
    pub mapping: Mapping,
    /// Local hit point x.
    pub x: f32,
    /// Local hit point y.
    pub y: f32,
    /// Local hit point z.
    pub z: f32,
    /// Texture resolution for the column and row (hres vres).
    #[arg(long, num_args = 2, value_names = ["W", "H"], default_values_t = [2048, 1024])]
    pub res: Vec<u32>,
    /// Texel lookup: lecture = (int)((hres - 1) u); centred = min(floor(u hres), hres - 1).
    #[arg(long, value_enum, default_value_t = LookupArg::Centred)]
    pub lookup: LookupArg,
    /// Print one JSON object: u, v, column, row (row counted from the bottom, as v).
    #[arg(long)]
    pub json: bool,
}

/// Texel lookups on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum LookupArg {
    /// The lecture's (int)((hres - 1) u).
    Lecture,
    /// Texel-centred min(floor(u hres), hres - 1).
    Centred,
}

impl From<LookupArg> for Lookup {
    fn from(l: LookupArg) -> Self {
        match l {
            LookupArg::Lecture => Self::Lecture,
            LookupArg::Centred => Self::Centred,
        }
    }
}

/// `texplore probe`.
#[derive(Debug, clap::Args)]
pub struct ProbeArgs {
    /// Equirectangular panorama (HDR or LDR; left edge longitude -180, top row the zenith).
    pub panorama: PathBuf,
    /// Output probe image (.hdr or .exr keep HDR values; .png and .jpg clip).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Width and height of the probe in pixels.
    #[arg(long, default_value_t = 512)]
    pub size: u32,
    /// Probe layout.
    #[arg(long, value_enum, default_value_t = ProbeFormat::Angular)]
    pub format: ProbeFormat,
}

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

/// Runs a subcommand.
///
/// # Errors
/// Anything the subcommand reports, with context naming the file.
pub fn run(command: Command) -> Result<()> {
    match command {
        Command::Render(a) => render(&a),
        Command::Snapshot(a) => snapshot(&a),
        Command::Map(a) => map(&a),
        Command::Probe(a) => {
            make_probe(&a.panorama, &a.output, a.size, a.format)?;
            eprintln!(
                "wrote {} ({size}x{size}, {:?})",
                a.output.display(),
                a.format,
                size = a.size
            );
            Ok(())
        }
        Command::Bench(a) => bench(&a),
    }
}

/// Reads a preset from a `.ron` file or from the text chunk of a PNG texplore saved.
///
/// # Errors
/// The file cannot be read or holds no valid preset.
pub fn read_preset_or_png(path: &Path) -> crate::Result<SceneDesc> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
    {
        let text = read_png_preset(path)?;
        crate::scene::parse_preset(&text, path)
    } else {
        load_preset(path)
    }
}

/// The preset embedded in a PNG's text chunk.
///
/// # Errors
/// Not a PNG, or no texplore preset inside.
pub fn read_png_preset(path: &Path) -> crate::Result<String> {
    let file = std::fs::File::open(path).map_err(|e| crate::Error::io(path, e))?;
    let decoder = png::Decoder::new(std::io::BufReader::new(file));
    let reader = decoder.read_info().map_err(|e| crate::Error::Image {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let info = reader.info();
    let found = info
        .utf8_text
        .iter()
        .find(|c| c.keyword == PRESET_CHUNK)
        .and_then(|c| c.get_text().ok())
        .or_else(|| {
            info.uncompressed_latin1_text
                .iter()
                .find(|c| c.keyword == PRESET_CHUNK)
                .map(|c| c.text.clone())
        });
    found.ok_or_else(|| {
        crate::Error::invalid(
            path,
            format!("this PNG has no '{PRESET_CHUNK}' text chunk (it was not saved by texplore)"),
        )
    })
}

fn render(a: &RenderArgs) -> Result<()> {
    let mut desc = read_preset_or_png(&a.preset)?;
    apply_overrides(
        &mut desc,
        Overrides {
            width: a.width,
            height: a.height,
            spp: a.spp,
            seed: a.seed,
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
    write_render(&a.output, &film, s.exposure_scale, &desc)?;
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

/// Writes a film as an sRGB PNG with the preset in a text chunk.
///
/// # Errors
/// The PNG cannot be written.
pub fn write_render(
    path: &Path,
    film: &Film,
    exposure_scale: f32,
    desc: &SceneDesc,
) -> crate::Result<()> {
    let img = film.to_display(exposure_scale);
    save_png(
        path,
        img.width,
        img.height,
        &img.rgb(),
        &[(PRESET_CHUNK, &to_ron(desc))],
    )
}

fn snapshot(a: &SnapshotArgs) -> Result<()> {
    let update = a.action == SnapshotAction::Update;
    let mut presets = list_presets(&a.presets)?;
    if !a.names.is_empty() {
        presets.retain(|p| {
            p.file_stem()
                .is_some_and(|s| a.names.iter().any(|n| s == n.as_str()))
        });
        if presets.is_empty() {
            bail!(
                "no preset named {} in {}",
                a.names.join(", "),
                a.presets.display()
            );
        }
    }
    let mut cache = AssetCache::new();
    let mut failed = 0;
    for p in &presets {
        let name = p.file_stem().unwrap_or_default().to_string_lossy();
        match check_preset(p, &a.screenshots, update, &mut cache)? {
            Outcome::Match(c) => println!(
                "ok       {name} (max diff {}, mean {:.3})",
                c.max_diff, c.mean_diff
            ),
            Outcome::Updated => println!("updated  {name}"),
            Outcome::Missing { new } => {
                failed += 1;
                println!(
                    "missing  {name}: no golden image of this size; the render is in {}",
                    new.display()
                );
            }
            Outcome::Mismatch {
                comparison: c,
                new,
                diff,
            } => {
                failed += 1;
                println!(
                    "MISMATCH {name}: {:.3}% of pixels differ by more than {PIXEL_TOLERANCE}/255 (limit {:.1}%), mean diff {:.3} (limit {MAX_MEAN_DIFF}), max {}; new render {}, diff x8 {}",
                    c.bad_fraction * 100.0,
                    MAX_BAD_FRACTION * 100.0,
                    c.mean_diff,
                    c.max_diff,
                    new.display(),
                    diff.display()
                );
            }
        }
    }
    if failed > 0 {
        bail!(
            "{failed} of {} snapshots do not match (run `texplore snapshot update` if the change is intended)",
            presets.len()
        );
    }
    Ok(())
}

fn map(a: &MapArgs) -> Result<()> {
    let (hres, vres) = (a.res[0], a.res[1]);
    if hres == 0 || vres == 0 {
        bail!("--res must be at least 1 x 1");
    }
    let p = Vec3A::new(a.x, a.y, a.z);
    let lookup = Lookup::from(a.lookup);
    let uv = a.mapping.map_point(p).uv;
    let wrapped = |t: f32| {
        if a.mapping == Mapping::Rectangular {
            t - t.floor()
        } else {
            t.clamp(0.0, 1.0)
        }
    };
    let (u, v) = (wrapped(uv.x), wrapped(uv.y));
    let (column, row) = (lookup.index(u, hres), lookup.index(v, vres));
    if a.json {
        let out = serde_json::json!({
            "mapping": a.mapping.name(),
            "point": [a.x, a.y, a.z],
            "u": uv.x,
            "v": uv.y,
            "column": column,
            "row": row,
            "file_row": vres - 1 - row,
            "lookup": lookup.name(),
            "res": [hres, vres],
        });
        println!("{out}");
        return Ok(());
    }
    println!(
        "{} mapping of the local hit point ({}, {}, {}):",
        a.mapping, a.x, a.y, a.z
    );
    for line in explain_mapping(a.mapping, p) {
        println!("  {line}");
    }
    if (u, v) != (uv.x, uv.y) {
        println!("  wrapped (repeat) into [0, 1]: u = {u:.4}, v = {v:.4}");
    }
    println!(
        "texel in a {hres} x {vres} image ({} lookup):",
        lookup.name()
    );
    for line in explain_lookup(u, v, hres, vres, lookup) {
        println!("  {line}");
    }
    println!(
        "  (row counts from the bottom, as v does; the file's row from the top is {})",
        vres - 1 - row
    );
    Ok(())
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

fn bench(a: &BenchArgs) -> Result<()> {
    let mut desc = read_preset_or_png(&a.preset)?;
    apply_overrides(
        &mut desc,
        Overrides {
            width: Some(a.width),
            height: Some(a.height),
            spp: Some(1),
            seed: None,
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
