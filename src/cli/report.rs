//! `texplore report`: speed against error for presets, written as CSV, Markdown and plots.

use crate::names::value_parser;
use crate::output::check_output;
use crate::report::{
    Mode, ProgressUpdate, ReferenceSettings, ReportConfig, Stage, default_cache_dir, run_scene,
    write_outputs,
};
use crate::sampler::PixelSampler;
use crate::scene::read_preset_or_png;
use crate::texture::Filter;
use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Duration;

/// `texplore report`.
#[derive(Debug, clap::Args)]
pub struct ReportArgs {
    /// Presets (.ron or PNGs saved by texplore); default: presets/earth.ron and
    /// presets/checker.ron.
    pub presets: Vec<PathBuf>,
    /// Output directory (report.csv, report.md, and a folder of plots per preset).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Modes: `default` (every filter with jittered, bilinear with every sampler), `all`
    /// (every filter x every sampler), or a list like `nearest/jittered,bilinear/*`.
    #[arg(long, default_value = "default")]
    pub modes: String,
    /// Samples per pixel of the measured renders.
    #[arg(long, value_delimiter = ',', default_values_t = [1, 2, 4, 8, 16, 32, 64, 128, 256], value_parser = super::parse_spp)]
    pub spp: Vec<u32>,
    /// Timed runs per render after a warm-up; the median is reported.
    #[arg(long, default_value_t = 5, value_parser = super::parse_repeat)]
    pub repeat: usize,
    /// Seconds the timed runs of one render may take before fewer are made (at least one).
    #[arg(long, default_value_t = 2.0, allow_hyphen_values = true, value_parser = super::parse_time_budget)]
    pub time_budget: f64,
    /// Image width (overrides the presets).
    #[arg(long, value_parser = super::parse_resolution)]
    pub width: Option<u32>,
    /// Image height (overrides the presets).
    #[arg(long, value_parser = super::parse_resolution)]
    pub height: Option<u32>,
    /// Samples per pixel of the reference.
    #[arg(long, default_value_t = 4096, value_parser = super::parse_spp)]
    pub reference_spp: u32,
    /// Texture filter of the reference.
    #[arg(long, default_value = "bilinear", value_parser = value_parser::<Filter>())]
    pub reference_filter: Filter,
    /// Pixel sampler of the reference.
    #[arg(long, default_value = "jittered", value_parser = value_parser::<PixelSampler>())]
    pub reference_sampler: PixelSampler,
    /// Judge against this image instead of rendering a reference: a linear OpenEXR or
    /// Radiance HDR made outside texplore (e.g. Mitsuba's), of the render's size; one preset
    /// only. The display metrics encode it like a render; `rmse_linear` compares it as it is.
    #[arg(long, value_name = "FILE.exr", conflicts_with_all = ["reference_spp", "reference_filter", "reference_sampler"])]
    pub reference: Option<PathBuf>,
    /// Where references are cached (default: the user's cache directory,
    /// ~/.cache/texplore/references, else OUTPUT/.refs).
    #[arg(long)]
    pub cache: Option<PathBuf>,
    /// Render the reference again and do not store it.
    #[arg(long)]
    pub no_cache: bool,
    /// Samples per pixel of the renders whose error heat maps are written (default: the
    /// smallest of --spp).
    #[arg(long, value_parser = super::parse_spp)]
    pub heatmap_spp: Option<u32>,
    /// Worker threads (default: one per core).
    #[arg(long, default_value_t = 0, value_parser = super::parse_threads)]
    pub threads: usize,
    /// Don't draw the progress bar.
    #[arg(long, short)]
    pub quiet: bool,
}

/// What the report's header says about the machine: cores, CPU model and load average.
fn machine() -> String {
    let cores = std::thread::available_parallelism().map_or(0, std::num::NonZero::get);
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .map_or_else(String::new, |l| format!("; load average at start {l}"));
    format!("{cores} logical cores, {cpu}{load}")
}

/// Refuses, before any work, an output folder that is a file, and a `report.csv` or
/// `report.md` in it that the writer would refuse (a FIFO, a directory, a read-only file, one of
/// the presets).
fn check_output_dir(dir: &Path, presets: &[PathBuf]) -> Result<()> {
    match std::fs::metadata(dir) {
        Ok(m) if !m.is_dir() => bail!(
            "cannot write {}: it is a file, not a folder (-o names the report's folder)",
            dir.display()
        ),
        Ok(_) => {
            let inputs: Vec<&Path> = presets.iter().map(PathBuf::as_path).collect();
            for name in ["report.csv", "report.md"] {
                check_output(&dir.join(name), &[], &inputs)?;
            }
        }
        // A missing folder is created when the files are written.
        Err(_) => {}
    }
    Ok(())
}

/// The lists and numbers clap cannot check one by one: a non-empty `--spp`, a
/// `--heatmap-spp` among it, a finite `--time-budget`.
fn check_numbers(a: &ReportArgs) -> Result<()> {
    if a.spp.is_empty() || a.spp.contains(&0) {
        bail!("--spp needs a list of positive numbers, like 1,4,16");
    }
    if let Some(h) = a.heatmap_spp.filter(|h| !a.spp.contains(h)) {
        bail!(
            "--heatmap-spp {h} is not among --spp {}: the heat map shows one of the renders",
            a.spp
                .iter()
                .map(u32::to_string)
                .collect::<Vec<_>>()
                .join(",")
        );
    }
    if !(a.time_budget.is_finite() && a.time_budget >= 0.0) {
        bail!("--time-budget must be a non-negative number of seconds");
    }
    Ok(())
}

/// The reference cache must be a folder, or one that can be made: refused before any render
/// when it (or a folder above it) is a file, or a symbolic link to nothing, where it used to
/// render the reference and then warn "Not a directory" or "File exists".
fn check_cache_dir(dir: &Path) -> Result<()> {
    let refuse = |why: String| {
        anyhow::anyhow!(
            "cannot use the reference cache {}: {why} (--cache names a folder; --no-cache \
             renders the reference without storing it)",
            dir.display()
        )
    };
    for at in dir.ancestors().filter(|p| !p.as_os_str().is_empty()) {
        let Ok(link) = std::fs::symlink_metadata(at) else {
            continue; // not there yet: made when the reference is stored
        };
        let what = if at == dir {
            "it".to_owned()
        } else {
            at.display().to_string()
        };
        return match std::fs::metadata(at) {
            Ok(m) if m.is_dir() => Ok(()),
            Ok(_) => Err(refuse(format!("{what} is not a folder"))),
            Err(_) if link.file_type().is_symlink() => Err(refuse(format!(
                "{what} is a symbolic link to {}, which does not exist",
                std::fs::read_link(at)
                    .map_or_else(|_| "nothing".to_owned(), |t| t.display().to_string())
            ))),
            Err(e) => Err(refuse(format!("{what}: {e}"))),
        };
    }
    Ok(())
}

/// Runs the report.
///
/// # Errors
/// A preset cannot be read or built, or an output cannot be written.
pub fn run(a: &ReportArgs, simd: crate::scene::SimdMode) -> Result<()> {
    let presets = if a.presets.is_empty() {
        let d = vec![
            PathBuf::from("presets/earth.ron"),
            PathBuf::from("presets/checker.ron"),
        ];
        if !d.iter().all(|p| p.exists()) {
            bail!(
                "no preset given and presets/earth.ron is not here: name the presets to report on"
            );
        }
        d
    } else {
        a.presets.clone()
    };
    if let Some(r) = &a.reference
        && presets.len() != 1
    {
        bail!(
            "--reference {} judges one scene: give exactly one preset (not {})",
            r.display(),
            presets.len()
        );
    }
    check_output_dir(&a.output, &presets)?;
    let modes = Mode::parse_list(&a.modes)?;
    check_numbers(a)?;
    let cache_dir = if a.no_cache {
        None
    } else {
        Some(
            a.cache
                .clone()
                .unwrap_or_else(|| default_cache_dir(&a.output.join(".refs"))),
        )
    };
    if let Some(dir) = &cache_dir {
        check_cache_dir(dir)?;
    }
    let config = ReportConfig {
        modes,
        spp: a.spp.clone(),
        repeat: a.repeat.max(1),
        time_budget: Duration::from_secs_f64(a.time_budget),
        width: a.width,
        height: a.height,
        reference: ReferenceSettings {
            spp: a.reference_spp.max(1),
            filter: a.reference_filter,
            sampler: a.reference_sampler,
            cache_dir: cache_dir.clone(),
            file: a.reference.clone(),
        },
        heatmap_spp: Some(
            a.heatmap_spp
                .unwrap_or_else(|| a.spp.iter().copied().min().unwrap_or(1)),
        ),
        simd,
    };
    let pool = crate::render::thread_pool(a.threads)?;
    let threads = pool.current_num_threads();
    let bar = if a.quiet {
        indicatif::ProgressBar::hidden()
    } else {
        let bar = indicatif::ProgressBar::new(1);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{spinner} {msg:40} [{bar:30}] {percent:>3}% {elapsed} elapsed, {eta} left",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar
    };
    let cancel = AtomicBool::new(false);
    let mut reports = Vec::new();
    for (path, name) in presets.iter().zip(scene_names(&presets)) {
        let desc = read_preset_or_png(path)?;
        let mut on_progress = |p: &ProgressUpdate<'_>| {
            bar.set_length(p.total);
            bar.set_position(p.done);
            bar.set_message(match &p.stage {
                Stage::Reference => format!("{name}: reference"),
                Stage::Mode(m, spp) => format!("{name}: {} {spp} spp", m.name()),
            });
        };
        // The bar's ETA is per preset; it restarts for the next one.
        bar.reset();
        let rep = pool
            .install(|| run_scene(&name, &desc, path, &config, &mut on_progress, &cancel))
            .with_context(|| format!("report on {}", path.display()))?;
        reports.push(rep);
    }
    bar.finish_and_clear();
    let args: Vec<String> = std::env::args().collect();
    let header = format!(
        "Command: `{}`\n\nMachine: {}; renders on {threads} rayon threads.\n\nReference cache: {}.\n",
        args.join(" "),
        machine(),
        cache_dir.as_deref().map_or_else(
            || "off (--no-cache)".to_string(),
            |d: &Path| d.display().to_string()
        ),
    );
    let written = write_outputs(&a.output, &reports, &header)?;
    for rep in &reports {
        if let Some(why) = &rep.reference_not_stored {
            eprintln!(
                "warning: {}: the reference was not stored in the cache ({why}); the report \
                 used it all the same",
                rep.scene
            );
        }
    }
    if !a.quiet {
        for rep in &reports {
            eprintln!(
                "{}: {} renders; reference {}",
                rep.scene,
                rep.rows.len(),
                if let Some(file) = rep.reference.file.as_ref() {
                    format!("{} (external)", file.display())
                } else if rep.reference_cached {
                    "from the cache".to_string()
                } else {
                    let again = rep
                        .reference_problem
                        .as_ref()
                        .map_or_else(String::new, |p| {
                            format!(" (the cached one was not used: {p})")
                        });
                    format!(
                        "rendered in {:.1} s{again}",
                        rep.reference_time.as_secs_f64()
                    )
                }
            );
        }
        eprintln!("wrote {} files into {}", written.len(), a.output.display());
    }
    Ok(())
}

/// Each preset's scene name: its file stem, or where two presets share a stem, the folder
/// and the stem (`a-earth`, `b-earth`), numbered if those still repeat (the same file twice).
/// The name names the scene's rows and its folder of plots, so no two may be equal, and none
/// may be one of the report's own files or hidden (`report.csv.ron` makes the folder
/// `scene-report.csv`).
fn scene_names(presets: &[PathBuf]) -> Vec<String> {
    let stem = |p: &Path| {
        let s = p
            .file_stem()
            .map_or_else(|| "scene".to_string(), |s| s.to_string_lossy().into_owned());
        let lower = s.to_lowercase();
        if lower == "report.csv" || lower == "report.md" || s.starts_with('.') || s.is_empty() {
            format!("scene-{s}")
        } else {
            s
        }
    };
    let stems: Vec<String> = presets.iter().map(|p| stem(p)).collect();
    let named: Vec<String> = presets
        .iter()
        .zip(&stems)
        .map(|(p, s)| {
            if stems.iter().filter(|t| *t == s).count() == 1 {
                return s.clone();
            }
            let folder = std::path::absolute(p).ok().and_then(|a| {
                a.parent()?
                    .file_name()
                    .map(|f| f.to_string_lossy().into_owned())
            });
            folder.map_or_else(|| s.clone(), |f| format!("{f}-{s}"))
        })
        .collect();
    named
        .iter()
        .enumerate()
        .map(|(i, n)| {
            if named.iter().filter(|m| *m == n).count() == 1 {
                n.clone()
            } else {
                let k = named[..=i].iter().filter(|m| *m == n).count();
                format!("{n}-{k}")
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::scene_names;
    use std::path::PathBuf;

    #[test]
    fn presets_sharing_a_stem_get_their_folder_or_a_number() {
        let p = |s: &str| PathBuf::from(s);
        assert_eq!(
            scene_names(&[p("a/earth.ron"), p("b/earth.ron"), p("b/checker.ron")]),
            ["a-earth", "b-earth", "checker"]
        );
        assert_eq!(
            scene_names(&[p("a/earth.ron"), p("a/earth.ron")]),
            ["a-earth-1", "a-earth-2"]
        );
        assert_eq!(
            scene_names(&[p("report.csv.ron"), p("REPORT.md.ron"), p(".refs.ron")]),
            ["scene-report.csv", "scene-REPORT.md", "scene-.refs"]
        );
    }
}
